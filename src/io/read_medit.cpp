// Copyright (c) 2026 SpringMotion developers.
#include <spring_motion/io/read_mesh.h>

#include "Raw_mesh.h"
#include "Token_reader.h"

#include <array>
#include <cstdint>
#include <limits>
#include <string>
#include <string_view>
#include <vector>

namespace spring_motion {

namespace {

using io_internal::Progress_scope;
using io_internal::Raw_mesh;
using io_internal::Section_progress;
using io_internal::Token_reader;
using io_internal::equal_ignoring_case;

constexpr std::size_t max_count = std::numeric_limits<std::uint32_t>::max();

// Sections we do not use but whose entry length is known, so that they are
// skipped by their count and a wrong count is still caught.
struct Known_section
{
  const char* keyword;
  int numbers_per_entry;   // when 0: one per coordinate (the dimension)
  int element_dimension;   // elements we cannot hold: their dimension; else -1
};

constexpr Known_section known_sections[] = {
  {"Corners", 1, -1},
  {"Ridges", 1, -1},
  {"RequiredVertices", 1, -1},
  {"RequiredEdges", 1, -1},
  {"RequiredTriangles", 1, -1},
  {"RequiredQuadrilaterals", 1, -1},
  {"RequiredTetrahedra", 1, -1},
  {"Normals", 0, -1},
  {"Tangents", 0, -1},
  {"NormalAtVertices", 2, -1},
  {"NormalAtTriangleVertices", 3, -1},
  {"NormalAtQuadrilateralVertices", 3, -1},
  {"TangentAtVertices", 2, -1},
  {"TangentAtEdgeVertices", 3, -1},
  {"EdgesP2", 4, 1},
  {"Quadrilaterals", 5, 2},
  {"TrianglesP2", 7, 2},
  {"QuadrilateralsQ2", 10, 2},
  {"Hexahedra", 9, 3},
  {"Prisms", 7, 3},
  {"Pyramids", 6, 3},
  {"TetrahedraP2", 11, 3},
  {"HexahedraQ2", 28, 3},
};

bool is_keyword(std::string_view token)
{
  const char c = token.front();
  return (c >= 'A' && c <= 'Z') || (c >= 'a' && c <= 'z');
}

int read_reference(Token_reader& reader, const char* what)
{
  const std::int64_t value = reader.expect_integer(what);
  if(value < std::numeric_limits<int>::min() || value > std::numeric_limits<int>::max())
    reader.fail(std::string("expected ") + what + " that fits in an int, found " + std::to_string(value));
  return static_cast<int>(value);
}

void read_vertices(Token_reader& reader, int dimension, Raw_mesh& raw)
{
  const std::size_t count = reader.expect_count("the number of vertices", max_count);
  Section_progress progress{"Vertices", "vertices", count, 0};
  Progress_scope scope(reader, progress);
  // Each vertex takes at least dimension + 1 numbers of two bytes ("0 ").
  raw.points.reserve(reader.reserve_limit(count, 2 * static_cast<std::size_t>(dimension + 1)));
  for(std::size_t i = 0; i < count; ++i) {
    const double x = reader.expect_double("a vertex coordinate");
    const std::size_t line = reader.line();
    const double y = reader.expect_double("a vertex coordinate");
    const double z = (dimension == 3) ? reader.expect_double("a vertex coordinate") : 0.0;
    read_reference(reader, "a vertex reference");
    raw.add_point(x, y, z, line);
    ++progress.read;
  }
}

template <std::size_t N>
void read_simplices(Token_reader& reader, const char* section, const char* entries,
                    std::size_t number_of_vertices, std::vector<std::array<std::uint32_t, N>>& simplices,
                    std::vector<int>& labels, std::vector<std::size_t>& lines)
{
  const std::size_t count = reader.expect_count((std::string("the number of ") + entries).c_str(), max_count);
  Section_progress progress{section, entries, count, 0};
  Progress_scope scope(reader, progress);
  const std::size_t limit = reader.reserve_limit(count, 2 * (N + 1));
  simplices.reserve(simplices.size() + limit);
  labels.reserve(labels.size() + limit);
  lines.reserve(lines.size() + limit);
  for(std::size_t i = 0; i < count; ++i) {
    std::array<std::uint32_t, N> simplex;
    std::size_t line = 0;
    for(std::size_t k = 0; k < N; ++k) {
      const std::int64_t index = reader.expect_integer("a vertex index");
      if(k == 0)
        line = reader.line();
      if(index < 1 || static_cast<std::uint64_t>(index) > number_of_vertices)
        reader.fail("vertex index " + std::to_string(index) + " out of range: expected 1 to "
                    + std::to_string(number_of_vertices) + io_internal::entry_suffix(section, i));
      simplex[k] = static_cast<std::uint32_t>(index - 1);
    }
    const int label = read_reference(reader, "an element reference");
    io_internal::check_distinct_vertices(simplex, reader, section, i);
    simplices.push_back(simplex);
    labels.push_back(label);
    lines.push_back(line);
    ++progress.read;
  }
}

void skip_known_section(Token_reader& reader, const Known_section& known, const std::string& keyword,
                        int dimension, std::size_t keyword_line, Raw_mesh& raw)
{
  const std::size_t count = reader.expect_count("the number of entries", max_count);
  const std::size_t per_entry = known.numbers_per_entry == 0 ? static_cast<std::size_t>(dimension)
                                                             : static_cast<std::size_t>(known.numbers_per_entry);
  Section_progress progress{keyword, "entries", count, 0};
  Progress_scope scope(reader, progress);
  for(std::size_t i = 0; i < count; ++i) {
    for(std::size_t k = 0; k < per_entry; ++k)
      reader.expect_double("a number");
    ++progress.read;
  }
  if(known.element_dimension >= 0 && count > 0)
    raw.add_unsupported(known.element_dimension, keyword, keyword_line, count);
}

} // namespace

Mesh_file read_medit(std::istream& in, const std::string& name_for_errors)
{
  Token_reader reader(in, name_for_errors);
  reader.set_comment_character('#');
  Raw_mesh raw;
  // "# label N: NAME", as write_medit() writes the label names
  reader.set_comment_handler([&raw](std::string_view comment, std::size_t) {
    int label = 0;
    std::string name;
    if(io_internal::parse_label_comment(comment, label, name))
      raw.comment_names[label] = std::move(name);
  });
  int dimension = 0;
  bool have_vertices = false;
  std::string previous_section;

  const auto require_vertices = [&](const std::string& keyword) {
    if(!have_vertices)
      reader.fail("section " + keyword + " before Vertices: expected the Vertices section first");
  };

  std::string_view token;
  while(reader.next(token)) {
    if(!is_keyword(token)) {
      std::string message = "expected a section keyword, found " + Token_reader::quote(token);
      if(!previous_section.empty())
        message += " after section " + previous_section + " (is its count right?)";
      reader.fail(message);
    }
    const std::string keyword(token);
    const std::size_t keyword_line = reader.line();
    if(equal_ignoring_case(keyword, "End"))
      break;

    if(equal_ignoring_case(keyword, "MeshVersionFormatted")) {
      const std::int64_t version = reader.expect_integer("a format version after MeshVersionFormatted");
      if(version < 1 || version > 4)
        reader.fail("expected MeshVersionFormatted 1 to 4, found " + std::to_string(version));
    } else if(equal_ignoring_case(keyword, "MeshVersionUnformatted")) {
      reader.fail("binary Medit meshes are not supported: expected an ASCII file (MeshVersionFormatted)");
    } else if(equal_ignoring_case(keyword, "Dimension")) {
      if(dimension != 0)
        reader.fail("a second Dimension section: expected one");
      const std::int64_t value = reader.expect_integer("the dimension after Dimension");
      if(value != 2 && value != 3)
        reader.fail("expected Dimension 2 or 3, found " + std::to_string(value));
      dimension = static_cast<int>(value);
    } else if(equal_ignoring_case(keyword, "Vertices")) {
      if(dimension == 0)
        reader.fail("section Vertices before Dimension: expected 'Dimension 2' or 'Dimension 3' first");
      if(have_vertices)
        reader.fail("a second Vertices section: expected one");
      read_vertices(reader, dimension, raw);
      have_vertices = true;
    } else if(equal_ignoring_case(keyword, "Triangles")) {
      require_vertices(keyword);
      read_simplices(reader, "Triangles", "triangles", raw.points.size(), raw.triangles, raw.triangle_labels,
                     raw.triangle_lines);
    } else if(equal_ignoring_case(keyword, "Tetrahedra")) {
      require_vertices(keyword);
      if(dimension == 2)
        reader.fail("Tetrahedra in a Dimension 2 file: mixed 2D and 3D elements, expected Triangles only");
      read_simplices(reader, "Tetrahedra", "tetrahedra", raw.points.size(), raw.tetrahedra,
                     raw.tetrahedron_labels, raw.tetrahedron_lines);
    } else if(equal_ignoring_case(keyword, "Edges")) {
      require_vertices(keyword);
      read_simplices(reader, "Edges", "edges", raw.points.size(), raw.edges, raw.edge_labels, raw.edge_lines);
    } else {
      const Known_section* known = nullptr;
      for(const Known_section& k : known_sections)
        if(equal_ignoring_case(keyword, k.keyword))
          known = &k;
      if(known != nullptr) {
        if(known->numbers_per_entry == 0 && dimension == 0)
          reader.fail("section " + keyword + " before Dimension: expected 'Dimension 2' or 'Dimension 3' first");
        skip_known_section(reader, *known, keyword, dimension, keyword_line, raw);
      } else {
        // Unknown layout: Medit data are all numbers, so the next word is the
        // next section.
        raw.skipped_sections.push_back(keyword);
        double ignored;
        while(reader.next(token))
          if(!io_internal::parse_double(token, ignored)) {
            reader.put_back();
            break;
          }
      }
    }
    previous_section = keyword;
  }

  if(dimension == 0)
    reader.fail("no Dimension section: expected a Medit mesh starting with "
                "'MeshVersionFormatted' and 'Dimension'");
  if(!have_vertices)
    reader.fail("no Vertices section: expected a Medit mesh with Vertices");
  return io_internal::finish_mesh(std::move(raw), reader);
}

} // namespace spring_motion
