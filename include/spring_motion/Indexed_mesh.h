// Copyright (c) 2026 SpringMotion developers.
#ifndef SPRING_MOTION_INDEXED_MESH_H
#define SPRING_MOTION_INDEXED_MESH_H

#include <array>
#include <cstddef>
#include <cstdint>
#include <map>
#include <string>
#include <vector>

namespace spring_motion {

/// A plain simplex mesh held in flat arrays: what the file readers produce and
/// the command-line tool deforms. `D` is 2 (triangles) or 3 (tetrahedra).
///
/// Boundary facets (edges in 2D, triangles in 3D) carry integer labels: the
/// element references of a Medit file or the physical groups of a Gmsh file.
/// Facets need not cover the whole boundary; a boundary facet without a label
/// is found from the elements themselves by `Spring_network`.
template <int D>
struct Indexed_mesh
{
  static_assert(D == 2 || D == 3, "Indexed_mesh: dimension must be 2 or 3");
  static constexpr int dimension = D;
  using Point = std::array<double, D>;
  using Element = std::array<std::uint32_t, D + 1>;
  using Facet = std::array<std::uint32_t, D>;

  std::vector<Point> points;
  std::vector<Element> elements;
  std::vector<int> element_labels;        // one per element (0 when the file has none)
  std::vector<Facet> boundary_facets;
  std::vector<int> boundary_labels;       // one per boundary facet
  std::map<int, std::string> label_names; // Gmsh physical names, when given

  std::size_t number_of_vertices() const { return points.size(); }
  std::size_t number_of_elements() const { return elements.size(); }
};

using Indexed_mesh_2 = Indexed_mesh<2>;
using Indexed_mesh_3 = Indexed_mesh<3>;

} // namespace spring_motion

#endif
