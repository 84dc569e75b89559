// Copyright (c) 2026 SpringMotion developers.
// Private to src/io: what the Medit and Gmsh readers collect before the
// dimension of the mesh is known, and the one place that decides it.
#ifndef SPRING_MOTION_SRC_IO_RAW_MESH_H
#define SPRING_MOTION_SRC_IO_RAW_MESH_H

#include "Token_reader.h"

#include <spring_motion/io/read_mesh.h>

#include <array>
#include <cstddef>
#include <cstdint>
#include <map>
#include <string>
#include <vector>

namespace spring_motion {
namespace io_internal {

/// Elements the mesh cannot hold (quadrilaterals, prisms, higher order...):
/// only an error when they are of the mesh's own dimension.
struct Unsupported_elements
{
  std::size_t count = 0;
  std::size_t first_line = 0;
  std::string first_kind; // "quadrangle (Gmsh type 3)", "Hexahedra"
};

struct Raw_mesh
{
  /// The `*_lines` below, and the other positions, are byte offsets (binary
  /// files) rather than 1-based lines.
  bool byte_offsets = false;
  std::vector<std::array<double, 3>> points;
  std::vector<std::int64_t> point_ids; // the file's vertex numbers (Gmsh node tags); empty: 1, 2, ...
  std::vector<std::array<std::uint32_t, 4>> tetrahedra;
  std::vector<int> tetrahedron_labels;
  std::vector<std::size_t> tetrahedron_lines;
  std::vector<std::array<std::uint32_t, 3>> triangles;
  std::vector<int> triangle_labels;
  std::vector<std::size_t> triangle_lines;
  std::vector<std::array<std::uint32_t, 2>> edges;
  std::vector<int> edge_labels;
  std::vector<std::size_t> edge_lines;

  // The first vertex off the z = 0 plane: a 2D mesh has none.
  std::size_t first_nonzero_z_line = 0; // 0: every z is 0
  std::size_t first_nonzero_z_vertex = 0;
  double first_nonzero_z = 0;

  std::array<Unsupported_elements, 4> unsupported; // by element dimension
  std::array<std::map<int, std::string>, 4> names; // Gmsh physical names by dimension
  std::map<int, std::string> comment_names;        // Medit "# label N: NAME" comments
  std::vector<std::string> skipped_sections;       // Medit sections of unknown layout

  void add_point(double x, double y, double z, std::size_t line)
  {
    if(z != 0 && first_nonzero_z_line == 0) {
      first_nonzero_z_line = line;
      first_nonzero_z_vertex = points.size();
      first_nonzero_z = z;
    }
    points.push_back({x, y, z});
  }

  void add_unsupported(int dimension, const std::string& kind, std::size_t line, std::size_t count = 1)
  {
    Unsupported_elements& u = unsupported[static_cast<std::size_t>(dimension)];
    if(u.count == 0) {
      u.first_line = line;
      u.first_kind = kind;
    }
    u.count += count;
  }
};

/// Decides the dimension (tetrahedra: 3D; else triangles: 2D; else an error)
/// and moves the data into the matching `Indexed_mesh`. `reader` names the
/// file in errors; its current position is used when no better one is known.
Mesh_file finish_mesh(Raw_mesh&& raw, const Error_reporter& reader);

/// Removes the later copies of elements with the same vertex set (and their
/// labels and lines), keeping the first; returns how many were removed.
template <std::size_t N>
std::size_t remove_duplicate_simplices(std::vector<std::array<std::uint32_t, N>>& simplices,
                                       std::vector<int>& labels, std::vector<std::size_t>& lines);

/// The message suffix naming an entry of a section: " (Triangles entry 3)".
std::string entry_suffix(const std::string& section, std::size_t entry_index);

/// Checks that the N vertex indices of a simplex are distinct.
template <std::size_t N>
void check_distinct_vertices(const std::array<std::uint32_t, N>& simplex, const Error_reporter& reader,
                             const std::string& section, std::size_t entry_index);

} // namespace io_internal
} // namespace spring_motion

#endif
