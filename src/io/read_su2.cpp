// Copyright (c) 2026 SpringMotion developers.
// SU2 native meshes (.su2), single zone: the layout of the SU2 documentation,
// "Mesh File" (NDIME=, NELEM=, NPOIN=, NMARK= with MARKER_TAG= and
// MARKER_ELEMS=), element types by their VTK numbers.
#include <spring_motion/io/read_mesh.h>

#include "Raw_mesh.h"
#include "Token_reader.h"

#include <array>
#include <cstdint>
#include <limits>
#include <map>
#include <set>
#include <string>
#include <string_view>
#include <vector>

namespace spring_motion {

namespace {

using io_internal::Progress_scope;
using io_internal::Raw_mesh;
using io_internal::Section_progress;
using io_internal::Token_reader;

constexpr std::size_t max_count = std::numeric_limits<std::uint32_t>::max();

// VTK cell types, as SU2 numbers its elements.
constexpr std::int64_t su2_line = 3, su2_triangle = 5, su2_tetrahedron = 10;

std::string describe_su2_type(std::int64_t type)
{
  switch(type) {
  case 1: return "vertex (SU2 type 1)";
  case 3: return "line (SU2 type 3)";
  case 5: return "triangle (SU2 type 5)";
  case 9: return "quadrilateral (SU2 type 9)";
  case 10: return "tetrahedron (SU2 type 10)";
  case 12: return "hexahedron (SU2 type 12)";
  case 13: return "prism (SU2 type 13)";
  case 14: return "pyramid (SU2 type 14)";
  default: return "unknown element type " + std::to_string(type);
  }
}

struct Marker
{
  std::string tag;
  std::size_t line = 0;
  std::size_t first_facet = 0; // in raw.edges or raw.triangles
  std::size_t facet_count = 0;
};

class Su2_reader
{
public:
  Su2_reader(std::istream& in, const std::string& name) : reader_(in, name)
  {
    reader_.set_comment_character('%');
    // "% label N: NAME", as write_su2() keeps label numbers and names.
    reader_.set_comment_handler([this](std::string_view comment, std::size_t) {
      int label = 0;
      std::string label_name;
      if(io_internal::parse_label_comment(comment, label, label_name))
        comment_labels_[label] = std::move(label_name);
    });
  }

  Mesh_file read();

private:
  // A keyword token "NAME=" or "NAME=VALUE": the name, and the value as the
  // rest of the token or the next token.
  bool next_keyword(std::string& keyword, std::size_t& line);
  std::string_view keyword_value(const std::string& keyword);
  std::size_t keyword_count(const std::string& keyword);
  // An optional trailing number on the entry's line (SU2's index column).
  void skip_optional_index(std::size_t line);

  void read_elements();
  void read_points();
  void read_markers();
  std::uint32_t read_vertex(const std::string& section, std::size_t entry);

  Token_reader reader_;
  Raw_mesh raw_;
  int dimension_ = 0;
  std::string_view pending_value_;
  std::string pending_storage_;
  bool have_elements_ = false, have_points_ = false, have_markers_ = false;
  std::map<int, std::string> comment_labels_;
  std::vector<Marker> markers_;
  // Vertex indices are checked once NPOIN is known (NELEM usually comes first).
  std::vector<std::pair<std::int64_t, std::size_t>> indices_to_check_;
};

bool Su2_reader::next_keyword(std::string& keyword, std::size_t& line)
{
  std::string_view token;
  if(!reader_.next(token))
    return false;
  line = reader_.line();
  const std::size_t equal = token.find('=');
  if(equal == std::string_view::npos || equal == 0)
    reader_.fail("expected a keyword such as NDIME=, NELEM=, NPOIN= or NMARK=, found " + Token_reader::quote(token));
  keyword = std::string(token.substr(0, equal));
  pending_storage_ = std::string(token.substr(equal + 1));
  pending_value_ = pending_storage_;
  return true;
}

std::string_view Su2_reader::keyword_value(const std::string& keyword)
{
  if(!pending_value_.empty()) {
    const std::string_view value = pending_value_;
    pending_value_ = {};
    return value;
  }
  return reader_.expect_token(("a value after " + keyword + "=").c_str());
}

std::size_t Su2_reader::keyword_count(const std::string& keyword)
{
  const std::string_view token = keyword_value(keyword);
  std::int64_t value = 0;
  if(!io_internal::parse_integer(token, value))
    reader_.fail("expected a count after " + keyword + "=, found " + Token_reader::quote(token));
  if(value < 0)
    reader_.fail("expected a count after " + keyword + "=, found " + Token_reader::quote(token)
                 + ": a count cannot be negative");
  if(static_cast<std::uint64_t>(value) > max_count)
    reader_.fail("expected a count after " + keyword + "=, found " + Token_reader::quote(token)
                 + ": more than the supported " + std::to_string(max_count));
  return static_cast<std::size_t>(value);
}

void Su2_reader::skip_optional_index(std::size_t line)
{
  std::string_view token;
  if(!reader_.next(token))
    return;
  if(reader_.line() != line) {
    reader_.put_back();
    return;
  }
  std::int64_t ignored = 0;
  if(!io_internal::parse_integer(token, ignored))
    reader_.fail("expected the end of the line or an index, found " + Token_reader::quote(token));
}

std::uint32_t Su2_reader::read_vertex(const std::string& section, std::size_t entry)
{
  const std::int64_t index = reader_.expect_integer("a vertex index");
  if(index < 0 || index > static_cast<std::int64_t>(max_count) - 1)
    reader_.fail("vertex index " + std::to_string(index) + " out of range: expected 0 or more (SU2 counts from 0)"
                 + io_internal::entry_suffix(section, entry));
  if(have_points_) {
    if(static_cast<std::size_t>(index) >= raw_.points.size())
      reader_.fail("vertex index " + std::to_string(index) + " out of range: expected 0 to "
                   + std::to_string(raw_.points.size()) + " - 1" + io_internal::entry_suffix(section, entry));
  } else
    indices_to_check_.push_back({index, reader_.line()});
  return static_cast<std::uint32_t>(index);
}

void Su2_reader::read_elements()
{
  const std::size_t count = keyword_count("NELEM");
  Section_progress progress{"NELEM", "elements", count, 0};
  Progress_scope scope(reader_, progress);
  const std::int64_t expected_type = dimension_ == 2 ? su2_triangle : su2_tetrahedron;
  for(std::size_t i = 0; i < count; ++i) {
    const std::int64_t type = reader_.expect_integer("an element type");
    const std::size_t line = reader_.line();
    if(type != expected_type)
      reader_.fail(describe_su2_type(type) + " in NELEM: expected " + describe_su2_type(expected_type)
                   + " only in an NDIME= " + std::to_string(dimension_) + " mesh"
                   + io_internal::entry_suffix("NELEM", i));
    if(dimension_ == 2) {
      std::array<std::uint32_t, 3> t;
      for(auto& v : t)
        v = read_vertex("NELEM", i);
      io_internal::check_distinct_vertices(t, reader_, "NELEM", i);
      raw_.triangles.push_back(t);
      raw_.triangle_labels.push_back(0);
      raw_.triangle_lines.push_back(line);
    } else {
      std::array<std::uint32_t, 4> t;
      for(auto& v : t)
        v = read_vertex("NELEM", i);
      io_internal::check_distinct_vertices(t, reader_, "NELEM", i);
      raw_.tetrahedra.push_back(t);
      raw_.tetrahedron_labels.push_back(0);
      raw_.tetrahedron_lines.push_back(line);
    }
    skip_optional_index(line);
    ++progress.read;
  }
}

void Su2_reader::read_points()
{
  // "NPOIN= 9" or, from parallel tools, "NPOIN= 9 8" (points, domain points).
  const std::size_t count = keyword_count("NPOIN");
  skip_optional_index(reader_.line());
  Section_progress progress{"NPOIN", "points", count, 0};
  Progress_scope scope(reader_, progress);
  raw_.points.reserve(reader_.reserve_limit(count, 2 * static_cast<std::size_t>(dimension_)));
  raw_.point_ids.reserve(reader_.reserve_limit(count, 2 * static_cast<std::size_t>(dimension_)));
  for(std::size_t i = 0; i < count; ++i) {
    const double x = reader_.expect_double("a point coordinate");
    const std::size_t line = reader_.line();
    const double y = reader_.expect_double("a point coordinate");
    const double z = dimension_ == 3 ? reader_.expect_double("a point coordinate") : 0.0;
    skip_optional_index(line);
    raw_.add_point(x, y, z, line);
    raw_.point_ids.push_back(static_cast<std::int64_t>(i));
    ++progress.read;
  }
  have_points_ = true;
  for(const auto& [index, line] : indices_to_check_)
    if(static_cast<std::size_t>(index) >= count)
      reader_.fail_at(line, "vertex index " + std::to_string(index) + " out of range: expected 0 to "
                              + std::to_string(count) + " - 1 (NPOIN= " + std::to_string(count) + ")");
  indices_to_check_.clear();
}

void Su2_reader::read_markers()
{
  const std::size_t count = keyword_count("NMARK");
  for(std::size_t m = 0; m < count; ++m) {
    std::string keyword;
    std::size_t line = 0;
    if(!next_keyword(keyword, line))
      reader_.fail("unexpected end of file: expected MARKER_TAG= of marker " + std::to_string(m + 1) + " of "
                   + std::to_string(count));
    if(keyword != "MARKER_TAG")
      reader_.fail("expected MARKER_TAG= of marker " + std::to_string(m + 1) + " of " + std::to_string(count)
                   + ", found " + Token_reader::quote(keyword + "="));
    Marker marker;
    marker.line = line;
    // The tag is the rest of the line (SU2 tags have no blanks; keep any).
    std::string tag(pending_value_);
    pending_value_ = {};
    std::string_view rest = reader_.rest_of_line();
    const std::size_t cut = rest.find('%');
    if(cut != std::string_view::npos)
      rest = rest.substr(0, cut);
    tag += std::string(rest);
    while(!tag.empty() && (tag.front() == ' ' || tag.front() == '\t'))
      tag.erase(tag.begin());
    while(!tag.empty() && (tag.back() == ' ' || tag.back() == '\t' || tag.back() == '\r'))
      tag.pop_back();
    if(tag.empty())
      reader_.fail("expected a marker name after MARKER_TAG=");
    marker.tag = tag;
    if(!next_keyword(keyword, line) || keyword != "MARKER_ELEMS")
      reader_.fail("expected MARKER_ELEMS= after MARKER_TAG= " + Token_reader::quote(tag));
    const std::size_t elements = keyword_count("MARKER_ELEMS");
    const std::string section = "MARKER_ELEMS of " + tag;
    Section_progress progress{section, "elements", elements, 0};
    Progress_scope scope(reader_, progress);
    const std::int64_t expected_type = dimension_ == 2 ? su2_line : su2_triangle;
    marker.first_facet = dimension_ == 2 ? raw_.edges.size() : raw_.triangles.size();
    marker.facet_count = elements;
    for(std::size_t i = 0; i < elements; ++i) {
      const std::int64_t type = reader_.expect_integer("an element type");
      const std::size_t entry_line = reader_.line();
      if(type != expected_type)
        reader_.fail(describe_su2_type(type) + " in a marker: expected " + describe_su2_type(expected_type)
                     + " only in an NDIME= " + std::to_string(dimension_) + " mesh"
                     + io_internal::entry_suffix(section, i));
      const int provisional = static_cast<int>(markers_.size());
      if(dimension_ == 2) {
        std::array<std::uint32_t, 2> e;
        for(auto& v : e)
          v = read_vertex(section, i);
        io_internal::check_distinct_vertices(e, reader_, section, i);
        raw_.edges.push_back(e);
        raw_.edge_labels.push_back(provisional);
        raw_.edge_lines.push_back(entry_line);
      } else {
        std::array<std::uint32_t, 3> t;
        for(auto& v : t)
          v = read_vertex(section, i);
        io_internal::check_distinct_vertices(t, reader_, section, i);
        raw_.triangles.push_back(t);
        raw_.triangle_labels.push_back(provisional);
        raw_.triangle_lines.push_back(entry_line);
      }
      skip_optional_index(entry_line);
      ++progress.read;
    }
    markers_.push_back(marker);
  }
}

Mesh_file Su2_reader::read()
{
  std::string keyword;
  std::size_t line = 0;
  std::vector<std::string> skipped;
  while(next_keyword(keyword, line)) {
    if(keyword == "NDIME") {
      if(dimension_ != 0)
        reader_.fail("a second NDIME=: expected one");
      const std::string_view value = keyword_value(keyword);
      if(value != "2" && value != "3")
        reader_.fail("expected NDIME= 2 or 3, found " + Token_reader::quote(value));
      dimension_ = value == "2" ? 2 : 3;
    } else if(keyword == "NELEM" || keyword == "NPOIN" || keyword == "NMARK") {
      if(dimension_ == 0)
        reader_.fail(keyword + "= before NDIME=: expected NDIME= 2 or 3 first");
      bool& seen = keyword == "NELEM" ? have_elements_ : keyword == "NPOIN" ? have_points_ : have_markers_;
      if(seen)
        reader_.fail("a second " + keyword + "=: expected one (multi-zone files are not supported)");
      if(keyword == "NELEM") {
        read_elements();
        have_elements_ = true;
      } else if(keyword == "NPOIN")
        read_points();
      else {
        read_markers();
        have_markers_ = true;
      }
    } else if(keyword == "NZONE" || keyword == "IZONE") {
      const std::string_view value = keyword_value(keyword);
      if(value != "1")
        reader_.fail(keyword + "= " + std::string(value) + ": multi-zone SU2 files are not supported, expected one zone");
    } else {
      // Sections of other layout (FFD boxes...): their data are numbers, so
      // the next token with '=' is the next keyword.
      skipped.push_back(keyword);
      pending_value_ = {};
      std::string_view token;
      while(reader_.next(token))
        if(token.find('=') != std::string_view::npos && token.front() >= 'A' && token.front() <= 'Z') {
          reader_.put_back();
          break;
        }
    }
  }
  if(dimension_ == 0)
    reader_.fail("no NDIME=: expected an SU2 mesh starting with NDIME= 2 or 3");
  if(!have_points_)
    reader_.fail("no NPOIN=: expected an SU2 mesh with NELEM= and NPOIN=");
  if(!have_elements_)
    reader_.fail("no NELEM=: expected an SU2 mesh with NELEM= and NPOIN=");

  // Marker labels: the number of a "% label N: NAME" comment naming the tag;
  // else the tag itself if it is a number; else the smallest positive number
  // not used otherwise, in file order.
  std::map<std::string, int> label_of;
  std::set<int> used;
  for(const auto& [label, name] : comment_labels_) {
    used.insert(label);
    label_of.emplace(name, label);
  }
  for(const Marker& marker : markers_) {
    std::int64_t number = 0;
    if(label_of.count(marker.tag) == 0 && io_internal::parse_integer(marker.tag, number)
       && number >= std::numeric_limits<int>::min() && number <= std::numeric_limits<int>::max()) {
      label_of[marker.tag] = static_cast<int>(number);
      used.insert(static_cast<int>(number));
    }
  }
  int next_free = 1;
  std::vector<int> marker_labels;
  for(const Marker& marker : markers_) {
    auto it = label_of.find(marker.tag);
    if(it == label_of.end()) {
      while(used.count(next_free) != 0)
        ++next_free;
      it = label_of.emplace(marker.tag, next_free).first;
      used.insert(next_free);
      raw_.comment_names[next_free] = marker.tag;
    } else if(comment_labels_.count(it->second) != 0)
      raw_.comment_names[it->second] = comment_labels_[it->second];
    marker_labels.push_back(it->second);
  }
  // Names of labels no marker uses (element labels, say) are kept too.
  for(const auto& [label, name] : comment_labels_)
    raw_.comment_names.emplace(label, name);
  for(int& label : dimension_ == 2 ? raw_.edge_labels : raw_.triangle_labels)
    label = marker_labels[static_cast<std::size_t>(label)];
  return io_internal::finish_mesh(std::move(raw_), reader_);
}

} // namespace

Mesh_file read_su2(std::istream& in, const std::string& name_for_errors)
{
  Su2_reader reader(in, name_for_errors);
  return reader.read();
}

} // namespace spring_motion
