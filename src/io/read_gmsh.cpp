// Copyright (c) 2026 SpringMotion developers.
#include <spring_motion/io/read_mesh.h>

#include "Gmsh_common.h"
#include "Raw_mesh.h"
#include "Token_reader.h"

#include <array>
#include <cstdint>
#include <limits>
#include <map>
#include <string>
#include <string_view>
#include <unordered_map>
#include <utility>
#include <vector>

namespace spring_motion {

namespace {

using io_internal::Element_type;
using io_internal::Node_numbering;
using io_internal::Progress_scope;
using io_internal::describe_type;
using io_internal::find_element_type;
using io_internal::line_type;
using io_internal::tetrahedron_type;
using io_internal::triangle_type;
using io_internal::Raw_mesh;
using io_internal::Section_progress;
using io_internal::Token_reader;

constexpr std::size_t max_count = std::numeric_limits<std::uint32_t>::max();

class Gmsh_reader
{
public:
  Gmsh_reader(std::istream& in, const std::string& name) : in_(in), reader_(in, name) {}

  Mesh_file read();

private:
  // True for a binary file, whose rest the binary reader reads.
  bool read_format();
  void read_physical_names();
  void read_entities();
  void read_nodes_2();
  void read_nodes_4();
  void read_elements_2();
  void read_elements_4();
  void skip_section(const std::string& section);
  void expect_end(const std::string& section, const std::string& after);

  void add_node(std::int64_t tag, double x, double y, double z, std::size_t line);
  int to_label(std::int64_t physical, const char* what);
  // Reads the node tags of one element of a known type and stores it.
  void read_element(std::int64_t type, int label, std::size_t entry_index);

  std::istream& in_;
  Token_reader reader_;
  Raw_mesh raw_;
  Node_numbering nodes_;
  int version_ = 0; // 2 or 4
  bool have_nodes_ = false;
  bool have_elements_ = false;
  // Format 4.1: the first physical group of each (dimension, entity tag).
  std::map<std::pair<int, std::int64_t>, int> entity_labels_;
};

Mesh_file read_gmsh_impl(std::istream& in, const std::string& name)
{
  Gmsh_reader reader(in, name);
  return reader.read();
}

bool Gmsh_reader::read_format()
{
  std::string_view token;
  if(!reader_.next(token))
    reader_.fail("empty file: expected a Gmsh mesh starting with $MeshFormat");
  if(token != "$MeshFormat")
    reader_.fail("expected $MeshFormat at the start of a Gmsh file, found " + Token_reader::quote(token));
  const std::string version(reader_.expect_token("the format version"));
  if(version == "2" || version == "2.0" || version == "2.1" || version == "2.2")
    version_ = 2;
  else if(version == "4.1")
    version_ = 4;
  else
    reader_.fail("unsupported Gmsh format version " + Token_reader::quote(version)
                 + ": expected 2.2 or 4.1 (gmsh -format msh22 or msh41)");
  const std::int64_t file_type = reader_.expect_integer("the file type (0 for ASCII, 1 for binary)");
  if(file_type != 0 && file_type != 1)
    reader_.fail("expected the file type 0 (ASCII) or 1 (binary), found " + std::to_string(file_type));
  const std::int64_t data_size = reader_.expect_integer("the data size");
  if(file_type == 0) {
    expect_end("$MeshFormat", "the format line");
    return false;
  }
  // Binary data start right after this line, with doubles and (4.1) size_t
  // of 8 bytes: what every gmsh writes on 64-bit machines.
  if(data_size != 8)
    reader_.fail("binary Gmsh file with data size " + std::to_string(data_size) + ": expected 8");
  for(char c : reader_.rest_of_line())
    if(c != ' ' && c != '\t' && c != '\r')
      reader_.fail("expected the end of the format line before the binary data");
  return true;
}

void Gmsh_reader::expect_end(const std::string& section, const std::string& after)
{
  const std::string end = "$End" + section.substr(1);
  const std::string_view token = reader_.expect_token(end.c_str());
  if(token != end)
    reader_.fail("expected " + end + " after " + after + ", found " + Token_reader::quote(token)
                 + " (is the count in " + section + " right?)");
}

void Gmsh_reader::skip_section(const std::string& section)
{
  const std::string end = "$End" + section.substr(1);
  const std::size_t start_line = reader_.line();
  std::string_view token;
  while(reader_.next(token))
    if(token == end)
      return;
  reader_.fail("unexpected end of file in section " + section + " (started at line "
               + std::to_string(start_line) + "): expected " + end);
}

int Gmsh_reader::to_label(std::int64_t physical, const char* what)
{
  if(physical < std::numeric_limits<int>::min() || physical > std::numeric_limits<int>::max())
    reader_.fail(std::string("expected ") + what + " that fits in an int, found " + std::to_string(physical));
  return static_cast<int>(physical);
}

void Gmsh_reader::read_physical_names()
{
  const std::size_t count = reader_.expect_count("the number of physical names", max_count);
  Section_progress progress{"$PhysicalNames", "names", count, 0};
  {
    Progress_scope scope(reader_, progress);
    for(std::size_t i = 0; i < count; ++i) {
      const std::int64_t dimension = reader_.expect_integer("a physical dimension");
      if(dimension < 0 || dimension > 3)
        reader_.fail("expected a physical dimension 0 to 3, found " + std::to_string(dimension));
      const int tag = to_label(reader_.expect_integer("a physical tag"), "a physical tag");
      std::string_view rest = reader_.rest_of_line();
      while(!rest.empty() && (rest.front() == ' ' || rest.front() == '\t'))
        rest.remove_prefix(1);
      while(!rest.empty() && (rest.back() == ' ' || rest.back() == '\t' || rest.back() == '\r'))
        rest.remove_suffix(1);
      if(rest.size() < 2 || rest.front() != '"' || rest.back() != '"')
        reader_.fail("expected a quoted physical name, found " + Token_reader::quote(rest)
                     + io_internal::entry_suffix("$PhysicalNames", i));
      raw_.names[static_cast<std::size_t>(dimension)][tag] = std::string(rest.substr(1, rest.size() - 2));
      ++progress.read;
    }
  }
  expect_end("$PhysicalNames", std::to_string(count) + " names");
}

void Gmsh_reader::read_entities()
{
  std::array<std::size_t, 4> counts;
  for(std::size_t d = 0; d < 4; ++d)
    counts[d] = reader_.expect_count("the number of entities", max_count);
  static const char* const plurals[] = {"points", "curves", "surfaces", "volumes"};
  for(int d = 0; d < 4; ++d) {
    Section_progress progress{"$Entities", plurals[d], counts[static_cast<std::size_t>(d)], 0};
    Progress_scope scope(reader_, progress);
    for(std::size_t i = 0; i < progress.expected; ++i) {
      const std::int64_t tag = reader_.expect_integer("an entity tag");
      // A point has its coordinates, the others their bounding box.
      for(int k = 0; k < (d == 0 ? 3 : 6); ++k)
        reader_.expect_double("an entity coordinate");
      const std::size_t physical_count = reader_.expect_count("the number of physical tags", max_count);
      for(std::size_t k = 0; k < physical_count; ++k) {
        const int physical = to_label(reader_.expect_integer("a physical tag"), "a physical tag");
        if(k == 0)
          entity_labels_[{d, tag}] = physical;
      }
      if(d > 0) {
        const std::size_t bounding_count = reader_.expect_count("the number of bounding entities", max_count);
        for(std::size_t k = 0; k < bounding_count; ++k)
          reader_.expect_integer("a bounding entity tag");
      }
      ++progress.read;
    }
  }
  expect_end("$Entities", "the entities");
}

void Gmsh_reader::add_node(std::int64_t tag, double x, double y, double z, std::size_t line)
{
  if(tag < 1)
    reader_.fail_at(line, "expected a positive node tag, found " + std::to_string(tag));
  if(!nodes_.add(tag))
    reader_.fail_at(line, "node tag " + std::to_string(tag) + " is used twice: expected distinct tags");
  raw_.add_point(x, y, z, line);
  raw_.point_ids.push_back(tag);
}

void Gmsh_reader::read_nodes_2()
{
  const std::size_t count = reader_.expect_count("the number of nodes", max_count);
  Section_progress progress{"$Nodes", "nodes", count, 0};
  {
    Progress_scope scope(reader_, progress);
    raw_.points.reserve(reader_.reserve_limit(count, 8));
    for(std::size_t i = 0; i < count; ++i) {
      const std::int64_t tag = reader_.expect_integer("a node number");
      const std::size_t line = reader_.line();
      const double x = reader_.expect_double("a node coordinate");
      const double y = reader_.expect_double("a node coordinate");
      const double z = reader_.expect_double("a node coordinate");
      add_node(tag, x, y, z, line);
      ++progress.read;
    }
  }
  expect_end("$Nodes", std::to_string(count) + " nodes");
}

void Gmsh_reader::read_nodes_4()
{
  const std::size_t block_count = reader_.expect_count("the number of entity blocks", max_count);
  const std::size_t count = reader_.expect_count("the number of nodes", max_count);
  reader_.expect_integer("the minimum node tag");
  reader_.expect_integer("the maximum node tag");
  Section_progress progress{"$Nodes", "nodes", count, 0};
  {
    Progress_scope scope(reader_, progress);
    raw_.points.reserve(reader_.reserve_limit(count, 8));
    std::vector<std::int64_t> tags;
    for(std::size_t b = 0; b < block_count; ++b) {
      const std::int64_t entity_dimension = reader_.expect_integer("an entity dimension");
      if(entity_dimension < 0 || entity_dimension > 3)
        reader_.fail("expected an entity dimension 0 to 3, found " + std::to_string(entity_dimension));
      reader_.expect_integer("an entity tag");
      const std::int64_t parametric = reader_.expect_integer("the parametric flag (0 or 1)");
      if(parametric != 0 && parametric != 1)
        reader_.fail("expected the parametric flag 0 or 1, found " + std::to_string(parametric));
      const std::size_t block_size = reader_.expect_count("the number of nodes in the block", max_count);
      if(block_size > count - progress.read)
        reader_.fail("an entity block of " + std::to_string(block_size) + " nodes after "
                     + std::to_string(progress.read) + ": more than the " + std::to_string(count)
                     + " nodes announced in the $Nodes header");
      tags.clear();
      tags.reserve(reader_.reserve_limit(block_size, 2));
      for(std::size_t i = 0; i < block_size; ++i)
        tags.push_back(reader_.expect_integer("a node tag"));
      const std::size_t extra = parametric ? static_cast<std::size_t>(entity_dimension) : 0;
      for(std::size_t i = 0; i < block_size; ++i) {
        const double x = reader_.expect_double("a node coordinate");
        const std::size_t line = reader_.line();
        const double y = reader_.expect_double("a node coordinate");
        const double z = reader_.expect_double("a node coordinate");
        for(std::size_t k = 0; k < extra; ++k)
          reader_.expect_double("a parametric coordinate");
        add_node(tags[i], x, y, z, line);
        ++progress.read;
      }
    }
    if(progress.read != count)
      reader_.fail("the $Nodes header announces " + std::to_string(count) + " nodes, its "
                   + std::to_string(block_count) + " entity blocks hold " + std::to_string(progress.read));
  }
  expect_end("$Nodes", std::to_string(count) + " nodes");
}

void Gmsh_reader::read_element(std::int64_t type, int label, std::size_t entry_index)
{
  const Element_type& t = *find_element_type(type);
  std::array<std::uint32_t, 4> vertices{};
  const std::size_t line = reader_.line();
  for(int k = 0; k < t.nodes; ++k) {
    const std::int64_t tag = reader_.expect_integer("a node tag");
    std::uint32_t index = 0;
    if(!nodes_.find(tag, index))
      reader_.fail("node " + std::to_string(tag) + " is not in $Nodes: expected a node tag of the file"
                   + io_internal::entry_suffix("$Elements", entry_index));
    if(k < 4)
      vertices[static_cast<std::size_t>(k)] = index;
  }
  switch(type) {
  case line_type: {
    const std::array<std::uint32_t, 2> edge{vertices[0], vertices[1]};
    io_internal::check_distinct_vertices(edge, reader_, "$Elements", entry_index);
    raw_.edges.push_back(edge);
    raw_.edge_labels.push_back(label);
    raw_.edge_lines.push_back(line);
    break;
  }
  case triangle_type: {
    const std::array<std::uint32_t, 3> triangle{vertices[0], vertices[1], vertices[2]};
    io_internal::check_distinct_vertices(triangle, reader_, "$Elements", entry_index);
    raw_.triangles.push_back(triangle);
    raw_.triangle_labels.push_back(label);
    raw_.triangle_lines.push_back(line);
    break;
  }
  case tetrahedron_type:
    io_internal::check_distinct_vertices(vertices, reader_, "$Elements", entry_index);
    raw_.tetrahedra.push_back(vertices);
    raw_.tetrahedron_labels.push_back(label);
    raw_.tetrahedron_lines.push_back(line);
    break;
  default:
    // Points carry nothing the mesh needs; other kinds are only an error if
    // they turn out to be of the mesh's dimension (see finish_mesh).
    if(t.dimension > 0)
      raw_.add_unsupported(t.dimension, describe_type(type), line);
    break;
  }
}

void Gmsh_reader::read_elements_2()
{
  const std::size_t count = reader_.expect_count("the number of elements", max_count);
  Section_progress progress{"$Elements", "elements", count, 0};
  {
    Progress_scope scope(reader_, progress);
    for(std::size_t i = 0; i < count; ++i) {
      reader_.expect_integer("an element number");
      const std::int64_t type = reader_.expect_integer("an element type");
      const std::size_t tag_count = reader_.expect_count("the number of element tags", max_count);
      std::int64_t physical = 0;
      for(std::size_t k = 0; k < tag_count; ++k) {
        const std::int64_t tag = reader_.expect_integer("an element tag");
        if(k == 0)
          physical = tag;
      }
      const int label = to_label(physical, "a physical tag");
      if(find_element_type(type) != nullptr)
        read_element(type, label, i);
      else
        reader_.skip_rest_of_line(); // one element per line: the only way past an unknown type
      ++progress.read;
    }
  }
  expect_end("$Elements", std::to_string(count) + " elements");
  // An element in several physical groups is written once per group.
  io_internal::remove_duplicate_simplices(raw_.tetrahedra, raw_.tetrahedron_labels, raw_.tetrahedron_lines);
  io_internal::remove_duplicate_simplices(raw_.triangles, raw_.triangle_labels, raw_.triangle_lines);
  io_internal::remove_duplicate_simplices(raw_.edges, raw_.edge_labels, raw_.edge_lines);
}

void Gmsh_reader::read_elements_4()
{
  const std::size_t block_count = reader_.expect_count("the number of entity blocks", max_count);
  const std::size_t count = reader_.expect_count("the number of elements", max_count);
  reader_.expect_integer("the minimum element tag");
  reader_.expect_integer("the maximum element tag");
  Section_progress progress{"$Elements", "elements", count, 0};
  {
    Progress_scope scope(reader_, progress);
    for(std::size_t b = 0; b < block_count; ++b) {
      const std::int64_t entity_dimension = reader_.expect_integer("an entity dimension");
      if(entity_dimension < 0 || entity_dimension > 3)
        reader_.fail("expected an entity dimension 0 to 3, found " + std::to_string(entity_dimension));
      const std::int64_t entity_tag = reader_.expect_integer("an entity tag");
      const std::int64_t type = reader_.expect_integer("an element type");
      const std::size_t block_size = reader_.expect_count("the number of elements in the block", max_count);
      if(block_size > count - progress.read)
        reader_.fail("an entity block of " + std::to_string(block_size) + " elements after "
                     + std::to_string(progress.read) + ": more than the " + std::to_string(count)
                     + " elements announced in the $Elements header");
      const auto it = entity_labels_.find({static_cast<int>(entity_dimension), entity_tag});
      const int label = it != entity_labels_.end() ? it->second : 0;
      const bool known = find_element_type(type) != nullptr;
      for(std::size_t i = 0; i < block_size; ++i) {
        reader_.expect_integer("an element tag");
        if(known)
          read_element(type, label, progress.read);
        else {
          // The block's dimension says whether the mesh needed these.
          if(i == 0 && entity_dimension > 0)
            raw_.add_unsupported(static_cast<int>(entity_dimension), describe_type(type), reader_.line(),
                                 block_size);
          reader_.skip_rest_of_line(); // one element per line: the only way past an unknown type
        }
        ++progress.read;
      }
    }
    if(progress.read != count)
      reader_.fail("the $Elements header announces " + std::to_string(count) + " elements, its "
                   + std::to_string(block_count) + " entity blocks hold " + std::to_string(progress.read));
  }
  expect_end("$Elements", std::to_string(count) + " elements");
}

Mesh_file Gmsh_reader::read()
{
  if(read_format())
    return io_internal::read_gmsh_binary(in_, reader_.file_name(), reader_.bytes_consumed(), version_);
  std::string_view token;
  while(reader_.next(token)) {
    if(token.front() != '$' || token.size() < 2)
      reader_.fail("expected a section such as $Nodes or $Elements, found " + Token_reader::quote(token));
    const std::string section(token);
    if(section == "$MeshFormat")
      reader_.fail("a second $MeshFormat section: expected one");
    else if(section == "$PhysicalNames")
      read_physical_names();
    else if(section == "$Entities" && version_ == 4)
      read_entities();
    else if(section == "$Nodes") {
      if(have_nodes_)
        reader_.fail("a second $Nodes section: expected one");
      if(version_ == 2)
        read_nodes_2();
      else
        read_nodes_4();
      have_nodes_ = true;
    } else if(section == "$Elements") {
      if(!have_nodes_)
        reader_.fail("section $Elements before $Nodes: expected $Nodes first");
      if(have_elements_)
        reader_.fail("a second $Elements section: expected one");
      if(version_ == 2)
        read_elements_2();
      else
        read_elements_4();
      have_elements_ = true;
    } else if(section.compare(0, 4, "$End") == 0)
      reader_.fail("unexpected " + Token_reader::quote(section) + ": expected a section start");
    else
      skip_section(section);
  }
  if(!have_nodes_)
    reader_.fail("no $Nodes section: expected a Gmsh mesh with $Nodes and $Elements");
  if(!have_elements_)
    reader_.fail("no $Elements section: expected a Gmsh mesh with $Nodes and $Elements");
  return io_internal::finish_mesh(std::move(raw_), reader_);
}

} // namespace

Mesh_file read_gmsh(std::istream& in, const std::string& name_for_errors)
{
  return read_gmsh_impl(in, name_for_errors);
}

} // namespace spring_motion
