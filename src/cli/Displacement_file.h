// Copyright (c) 2026 SpringMotion developers.
// Private to the spring-motion executable: `--displacement FILE`.
#ifndef SPRING_MOTION_SRC_CLI_DISPLACEMENT_FILE_H
#define SPRING_MOTION_SRC_CLI_DISPLACEMENT_FILE_H

#include <array>
#include <cstddef>
#include <cstdint>
#include <map>
#include <string>
#include <vector>

namespace spring_motion {
namespace cli {

/// A displacement file: one line per prescribed vertex, "ID DX DY" (2D) or
/// "ID DX DY DZ" (3D), where ID is the vertex's number in the mesh file
/// (Medit: 1-based index; Gmsh: node tag). Blank lines and text after '#'
/// are ignored.
template <int D>
struct Displacement_file
{
  std::string path;
  std::vector<std::size_t> vertices;                 ///< 0-based mesh vertices, in file order
  std::vector<std::array<double, D>> displacements;  ///< one per vertex
  std::vector<std::size_t> lines;                    ///< the line of each
};

/// Reads the file; `vertex_ids` are the mesh file's vertex numbers (see
/// `Mesh_file::vertex_ids`). Throws Input_error (file:line, what was
/// expected) on a missing file, a malformed line, a non-finite number, an id
/// the mesh does not have, an id given twice, and an empty file.
template <int D>
Displacement_file<D> read_displacement_file(const std::string& path, const std::vector<std::int64_t>& vertex_ids);

/// The motion of `--displacement`: each prescribed vertex goes to
/// p0 + t * displacement, looked up by its initial point.
template <int D>
struct Displacement_motion
{
  std::map<std::array<double, D>, std::array<double, D>> by_point;

  std::array<double, D> operator()(const std::array<double, D>& p0, double t) const;
};

} // namespace cli
} // namespace spring_motion

#endif
