// Copyright (c) 2026 SpringMotion developers.
#include "Raw_mesh.h"

#include <algorithm>
#include <numeric>
#include <sstream>
#include <utility>

namespace spring_motion {
namespace io_internal {

namespace {

std::string format_double(double value)
{
  std::ostringstream out;
  out.precision(17);
  out << value;
  return out.str();
}

[[noreturn]] void fail_unsupported(const Unsupported_elements& u, const Error_reporter& reader,
                                   const char* expected)
{
  reader.fail_at(u.first_line, "unsupported elements (" + u.first_kind + ", " + std::to_string(u.count)
                                   + " in all): expected " + expected);
}

template <int D>
void copy_names(Indexed_mesh<D>& mesh, Raw_mesh& raw)
{
  mesh.label_names = raw.comment_names;
  // Boundary facets' names last, so that they win when a number is used in
  // both dimensions: boundary conditions are chosen by boundary label.
  for(const auto& [tag, name] : raw.names[D])
    mesh.label_names[tag] = name;
  for(const auto& [tag, name] : raw.names[D - 1])
    mesh.label_names[tag] = name;
}

void fill_vertex_ids(Mesh_file& result, Raw_mesh& raw, std::size_t n)
{
  if(raw.point_ids.size() == n)
    result.vertex_ids = std::move(raw.point_ids);
  else {
    result.vertex_ids.resize(n);
    std::iota(result.vertex_ids.begin(), result.vertex_ids.end(), std::int64_t(1));
  }
}

// A facet whose vertices no element uses cannot lie on the mesh's boundary:
// it belongs to a separate part of lower dimension (a surface mesh next to a
// volume mesh, a line mesh next to a triangle mesh).
template <int D>
void check_facets_use_element_vertices(const Indexed_mesh<D>& mesh, const Mesh_file& file,
                                       const Error_reporter& reader, const char* facet, const char* element)
{
  std::vector<char> used(mesh.points.size(), 0);
  for(const auto& e : mesh.elements)
    for(std::uint32_t v : e)
      used[v] = 1;
  for(std::size_t f = 0; f < mesh.boundary_facets.size(); ++f)
    for(std::uint32_t v : mesh.boundary_facets[f])
      if(!used[v])
        reader.fail_at(file.boundary_facet_lines[f],
                       std::string("mixed dimensions: this ") + facet + " uses vertex "
                         + std::to_string(file.vertex_ids[v]) + ", which no " + element + " uses; expected every "
                         + facet + " to lie on the boundary of the " + element + " mesh (a " + std::to_string(D)
                         + "D mesh only)");
}

// A binary file has no lines: its positions go to the offsets, and the lines
// are 0 ("no line"), which callers that only know lines print as the file.
void move_offsets(Mesh_file& result, bool byte_offsets)
{
  if(!byte_offsets)
    return;
  result.element_offsets = std::move(result.element_lines);
  result.boundary_facet_offsets = std::move(result.boundary_facet_lines);
  result.element_lines.assign(result.element_offsets.size(), 0);
  result.boundary_facet_lines.assign(result.boundary_facet_offsets.size(), 0);
}

} // namespace

std::string entry_suffix(const std::string& section, std::size_t entry_index)
{
  return " (" + section + " entry " + std::to_string(entry_index + 1) + ")";
}

template <std::size_t N>
void check_distinct_vertices(const std::array<std::uint32_t, N>& simplex, const Error_reporter& reader,
                             const std::string& section, std::size_t entry_index)
{
  for(std::size_t i = 0; i < N; ++i)
    for(std::size_t j = i + 1; j < N; ++j)
      if(simplex[i] == simplex[j])
        reader.fail("an element uses the same vertex twice: expected " + std::to_string(N)
                    + " distinct vertices" + entry_suffix(section, entry_index));
}

template <std::size_t N>
std::size_t remove_duplicate_simplices(std::vector<std::array<std::uint32_t, N>>& simplices,
                                       std::vector<int>& labels, std::vector<std::size_t>& lines)
{
  using Key = std::array<std::uint32_t, N>;
  std::vector<std::pair<Key, std::size_t>> keys(simplices.size());
  for(std::size_t i = 0; i < simplices.size(); ++i) {
    keys[i].first = simplices[i];
    std::sort(keys[i].first.begin(), keys[i].first.end());
    keys[i].second = i;
  }
  // Sorting (key, position) puts the first copy of each vertex set first.
  std::sort(keys.begin(), keys.end());
  std::vector<char> keep(simplices.size(), 1);
  std::size_t removed = 0;
  for(std::size_t i = 1; i < keys.size(); ++i)
    if(keys[i].first == keys[i - 1].first) {
      keep[keys[i].second] = 0;
      ++removed;
    }
  if(removed == 0)
    return 0;
  std::size_t out = 0;
  for(std::size_t i = 0; i < simplices.size(); ++i)
    if(keep[i]) {
      simplices[out] = simplices[i];
      labels[out] = labels[i];
      lines[out] = lines[i];
      ++out;
    }
  simplices.resize(out);
  labels.resize(out);
  lines.resize(out);
  return removed;
}

template std::size_t remove_duplicate_simplices<2>(std::vector<std::array<std::uint32_t, 2>>&, std::vector<int>&,
                                                      std::vector<std::size_t>&);
template std::size_t remove_duplicate_simplices<3>(std::vector<std::array<std::uint32_t, 3>>&, std::vector<int>&,
                                                      std::vector<std::size_t>&);
template std::size_t remove_duplicate_simplices<4>(std::vector<std::array<std::uint32_t, 4>>&, std::vector<int>&,
                                                      std::vector<std::size_t>&);
template void check_distinct_vertices<2>(const std::array<std::uint32_t, 2>&, const Error_reporter&,
                                         const std::string&, std::size_t);
template void check_distinct_vertices<3>(const std::array<std::uint32_t, 3>&, const Error_reporter&,
                                         const std::string&, std::size_t);
template void check_distinct_vertices<4>(const std::array<std::uint32_t, 4>&, const Error_reporter&,
                                         const std::string&, std::size_t);

Mesh_file finish_mesh(Raw_mesh&& raw, const Error_reporter& reader)
{
  Mesh_file result;
  if(!raw.tetrahedra.empty()) {
    if(raw.unsupported[3].count != 0)
      fail_unsupported(raw.unsupported[3], reader, "linear tetrahedra only");
    Indexed_mesh<3>& mesh = result.mesh_3;
    result.dimension = 3;
    mesh.points = std::move(raw.points);
    mesh.elements = std::move(raw.tetrahedra);
    mesh.element_labels = std::move(raw.tetrahedron_labels);
    mesh.boundary_facets = std::move(raw.triangles);
    mesh.boundary_labels = std::move(raw.triangle_labels);
    copy_names(mesh, raw);
    result.element_lines = std::move(raw.tetrahedron_lines);
    result.boundary_facet_lines = std::move(raw.triangle_lines);
    fill_vertex_ids(result, raw, mesh.points.size());
    check_facets_use_element_vertices(mesh, result, reader, "triangle", "tetrahedron");
    move_offsets(result, raw.byte_offsets);
    return result;
  }

  if(!raw.triangles.empty()) {
    if(raw.unsupported[3].count != 0)
      fail_unsupported(raw.unsupported[3], reader, "linear tetrahedra only in a 3D mesh");
    if(raw.unsupported[2].count != 0)
      fail_unsupported(raw.unsupported[2], reader, "linear triangles only in a 2D mesh");
    if(raw.first_nonzero_z_line != 0)
      reader.fail_at(raw.first_nonzero_z_line,
                     "vertex " + std::to_string(raw.first_nonzero_z_vertex + 1) + " has z = "
                       + format_double(raw.first_nonzero_z)
                       + " in a mesh of triangles without tetrahedra: surface meshes in 3D are "
                         "not supported, expected z = 0 everywhere for a 2D mesh");
    Indexed_mesh<2>& mesh = result.mesh_2;
    result.dimension = 2;
    mesh.points.resize(raw.points.size());
    for(std::size_t i = 0; i < raw.points.size(); ++i)
      mesh.points[i] = {raw.points[i][0], raw.points[i][1]};
    raw.points = {};
    mesh.elements = std::move(raw.triangles);
    mesh.element_labels = std::move(raw.triangle_labels);
    mesh.boundary_facets = std::move(raw.edges);
    mesh.boundary_labels = std::move(raw.edge_labels);
    copy_names(mesh, raw);
    result.element_lines = std::move(raw.triangle_lines);
    result.boundary_facet_lines = std::move(raw.edge_lines);
    fill_vertex_ids(result, raw, mesh.points.size());
    check_facets_use_element_vertices(mesh, result, reader, "edge", "triangle");
    move_offsets(result, raw.byte_offsets);
    return result;
  }

  for(int d : {3, 2})
    if(raw.unsupported[static_cast<std::size_t>(d)].count != 0)
      fail_unsupported(raw.unsupported[static_cast<std::size_t>(d)], reader,
                       "triangles (2D) or tetrahedra (3D)");
  std::string message = "no triangles or tetrahedra: expected a 2D triangle mesh or a 3D tetrahedral mesh";
  if(!raw.skipped_sections.empty()) {
    message += "; skipped unknown sections:";
    for(const std::string& name : raw.skipped_sections)
      message += " " + Token_reader::quote(name);
  }
  reader.fail(message);
}

} // namespace io_internal
} // namespace spring_motion
