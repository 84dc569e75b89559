// Copyright (c) 2026 SpringMotion developers.
#ifndef SPRING_MOTION_IO_WRITE_MESH_H
#define SPRING_MOTION_IO_WRITE_MESH_H

#include <spring_motion/Error.h>
#include <spring_motion/Indexed_mesh.h>
#include <spring_motion/Input_error.h>
#include <spring_motion/io/read_mesh.h>

#include <functional>
#include <iosfwd>
#include <string>
#include <vector>

namespace spring_motion {

/// A named field to write with a mesh: `values` holds `components` numbers
/// per vertex (point data) or per element (cell data), interleaved:
/// e.g. {"displacement", 3, {dx0, dy0, dz0, dx1, ...}}, {"skewness", 1, {...}}.
struct Data_array
{
  std::string name;
  int components = 1;
  std::vector<double> values;
};

// Every writer checks the mesh first (vertex indices in range, one label per
// element and per boundary facet, or none at all, meaning 0) and the data
// arrays (non-empty name, 1 to 9 components, the right number of values),
// and throws spring_motion::Error otherwise (programming errors), before
// anything is written.
//
// The writers taking a path write a temporary file in the target's directory
// and rename it over the target when complete, so that a failed or
// interrupted run never leaves a partial file behind. Problems with the path
// (missing directory, no permission, disk full) throw `Input_error` naming it.
//
// The writers taking a stream leave the stream's state for the caller to check.

/// Medit ASCII: `Vertices`, then `Triangles` + `Edges` (2D) or `Tetrahedra` +
/// `Triangles` (3D) with the labels as references, and `label_names` as
/// comments (`# label N: NAME`, which `read_medit()` reads back; other Medit
/// readers ignore them). Coordinates are written in the shortest form that
/// reads back to the same double, so `read_medit()` returns the same mesh bit
/// for bit.
template <int D>
void write_medit(const Indexed_mesh<D>& mesh, std::ostream& out);
template <int D>
void write_medit(const Indexed_mesh<D>& mesh, const std::string& path);

/// Gmsh MSH 4.1 ASCII, as `gmsh -format msh41` writes it and Gmsh 4.x reads
/// it: one entity per label and dimension (tagged 1, 2, ... in label order),
/// in the physical group of that label (label 0: an entity without physical
/// group), `$PhysicalNames` for the named labels in use; all nodes in one
/// block (tags 1 to n, in the order of `points`); the boundary facets (lines
/// or triangles), then the elements (triangles or tetrahedra), one block per
/// run of equal labels so that their order is kept. Coordinates are written
/// in the shortest form that reads back to the same double: `read_gmsh()`
/// returns the same mesh bit for bit, with `label_names` restricted to the
/// labels in use. `Gmsh_encoding::binary` writes the same as `gmsh -bin`
/// does (format 4.1, file type 1: the numbers in binary, in this machine's
/// byte order, marked by the integer 1; `$PhysicalNames` as text).
enum class Gmsh_encoding { ascii, binary };
template <int D>
void write_gmsh(const Indexed_mesh<D>& mesh, std::ostream& out, Gmsh_encoding encoding = Gmsh_encoding::ascii);
template <int D>
void write_gmsh(const Indexed_mesh<D>& mesh, const std::string& path,
                Gmsh_encoding encoding = Gmsh_encoding::ascii);

/// SU2 native mesh (single zone): `NDIME=`, `NELEM=` (VTK types 5 or 10,
/// 0-based indices, index column), `NPOIN=` (index column), `NMARK=` with one
/// marker per boundary label in label order. A marker's `MARKER_TAG=` is the
/// label's name when it is one word that is not a number, the label number
/// otherwise; every name is also written as a comment `% label N: NAME`,
/// from which `read_su2()` gets the label numbers back (SU2 ignores
/// comments). Element labels have no place in SU2 and are not written.
/// Coordinates round-trip bit for bit, as for `write_medit()`.
template <int D>
void write_su2(const Indexed_mesh<D>& mesh, std::ostream& out);
template <int D>
void write_su2(const Indexed_mesh<D>& mesh, const std::string& path);

/// VTK XML UnstructuredGrid, ASCII (ParaView, VisIt): the elements as
/// VTK_TRIANGLE (5) or VTK_TETRA (10) cells, points always with 3
/// components (z = 0 in 2D), and the given point and cell data as Float64
/// arrays. Boundary facets are not written. Non-finite values are written as
/// "nan", "inf", "-inf" (VTK 9.1 reads them, though "-inf" as +inf).
template <int D>
void write_vtu(const Indexed_mesh<D>& mesh, std::ostream& out,
               const std::vector<Data_array>& point_data = {},
               const std::vector<Data_array>& cell_data = {});
template <int D>
void write_vtu(const Indexed_mesh<D>& mesh, const std::string& path,
               const std::vector<Data_array>& point_data = {},
               const std::vector<Data_array>& cell_data = {});

/// Writes by extension (case-insensitive): `.vtu` (with the data arrays),
/// `.mesh` (Medit), `.msh` (always Gmsh 4.1 ASCII, whatever the input's
/// format) or `.su2` (SU2); the data arrays are written to `.vtu` only, the
/// other formats have no place for them.
/// \throws Input_error for any other extension, naming the expected ones.
template <int D>
void write_mesh(const std::string& path, const Indexed_mesh<D>& mesh,
                const std::vector<Data_array>& point_data = {},
                const std::vector<Data_array>& cell_data = {});
/// The mesh of `file` that matches its `dimension`.
void write_mesh(const std::string& path, const Mesh_file& file,
                const std::vector<Data_array>& point_data = {},
                const std::vector<Data_array>& cell_data = {});

/// Calls `write` on a temporary file beside `path`, then renames it over
/// `path`: the file the writers above use, for any other output (a JSON
/// report). A failure (an exception from `write`, a failed write) removes the
/// temporary file and leaves `path` as it was.
/// \throws Input_error naming `path` when the file cannot be written.
void write_file_atomically(const std::string& path, const std::function<void(std::ostream&)>& write);

/// One time step of a ParaView collection: `file` is the .vtu as the .pvd
/// refers to it (ParaView resolves relative names from the .pvd's directory).
struct Pvd_entry
{
  double time = 0;
  std::string file;
};

/// Writes a ParaView collection (.pvd) listing the files with their times.
void write_pvd(const std::string& path, const std::vector<Pvd_entry>& entries);

/// Builds a .pvd while a run writes its time steps: each `add()` rewrites the
/// whole collection, so that the .pvd on disk is valid whenever the run stops.
class Pvd_writer
{
public:
  explicit Pvd_writer(std::string path);

  /// Adds a step. `vtu_path` is given as the program wrote it (relative to
  /// the working directory, or absolute); it is stored relative to the .pvd's
  /// directory when both are in the same place, so the pair can be moved.
  void add(double time, const std::string& vtu_path);

  const std::string& path() const { return path_; }
  const std::vector<Pvd_entry>& entries() const { return entries_; }

private:
  std::string path_;
  std::vector<Pvd_entry> entries_;
};

} // namespace spring_motion

#endif
