// Copyright (c) 2026 SpringMotion developers.
#ifndef SPRING_MOTION_IO_READ_MESH_H
#define SPRING_MOTION_IO_READ_MESH_H

#include <spring_motion/Indexed_mesh.h>
#include <spring_motion/Input_error.h>

#include <cstddef>
#include <cstdint>
#include <iosfwd>
#include <string>
#include <vector>

namespace spring_motion {

/// What a mesh file holds: a 2D or a 3D mesh, decided by the file's content.
/// Only the member matching `dimension` is filled; the other one is empty.
struct Mesh_file
{
  int dimension = 0;   // 2 or 3
  Indexed_mesh<2> mesh_2;
  Indexed_mesh<3> mesh_3;

  // Where things came from, for messages that point into the file.
  /// The number the file gives each vertex: Medit's 1-based index, Gmsh's
  /// node tag (one per vertex, in the order of `points`).
  std::vector<std::int64_t> vertex_ids;
  /// The 1-based line on which each element, and each boundary facet, is
  /// written (one per entry of `elements` and of `boundary_facets`); 0 for
  /// every entry of a binary file, which has no lines.
  std::vector<std::size_t> element_lines;
  std::vector<std::size_t> boundary_facet_lines;
  /// Binary files only (Gmsh `-bin`): the byte offset at which each element
  /// and each boundary facet is written, as errors about binary files give it
  /// ("file.msh: byte 1234: ..."). Empty for text files.
  std::vector<std::size_t> element_offsets;
  std::vector<std::size_t> boundary_facet_offsets;

  /// The mesh of dimension D (`mesh_2` or `mesh_3`), for code templated on D.
  template <int D>
  const Indexed_mesh<D>& mesh() const
  {
    static_assert(D == 2 || D == 3, "Mesh_file::mesh: dimension 2 or 3");
    if constexpr(D == 2)
      return mesh_2;
    else
      return mesh_3;
  }
};

/// Reads a mesh file, choosing the format by extension (case-insensitive):
///  - `.mesh`: Medit ASCII (see `read_medit()`),
///  - `.msh`:  Gmsh ASCII or binary, format 2.2 or 4.1 (see `read_gmsh()`).
///  - `.su2`:  SU2 native mesh, single zone (see `read_su2()`).
///
/// How the dimension is decided, for both formats:
///  - tetrahedra present: a 3D mesh; triangles are its labelled boundary facets;
///  - otherwise triangles are the elements of a 2D mesh, and edges (lines)
///    its labelled boundary facets; every vertex must then have z == 0, since
///    surface meshes in 3D are not supported;
///  - neither: an error.
/// Facets of the lower dimension (triangles of a 3D mesh, edges of a 2D mesh)
/// that use a vertex no element uses are a separate, lower-dimensional part
/// of the file (mixed 2D and 3D): an error, since they cannot bound the mesh.
/// Vertex indices become 0-based; unused vertices are kept, in file order.
/// Elements of an unsupported kind in the mesh's own dimension (quadrilaterals
/// in 2D; hexahedra, prisms, pyramids in 3D; any higher-order element) are an
/// error rather than silently dropped, which would leave a hole in the mesh.
///
/// \throws Input_error for every problem with the file (missing, unreadable,
///         unknown extension, malformed), naming the file and the line.
Mesh_file read_mesh(const std::string& path);

/// Reads a Medit ASCII mesh (the `.mesh` format of Medit, MMG, TetGen, CGAL).
///
/// Sections used: `MeshVersionFormatted`, `Dimension` (2 or 3), `Vertices`
/// (coordinates + reference, the reference is ignored), `Triangles`,
/// `Tetrahedra`, `Edges` (vertex indices + reference), `End`. Element
/// references become `element_labels`; the references of `Edges` (2D) or
/// `Triangles` (3D, when there are tetrahedra) become `boundary_labels`.
/// A `Dimension 3` file with triangles only and all z == 0 is read as 2D.
/// Comments start with `#`; a comment `# label N: NAME` (as `write_medit()`
/// writes the label names) names label N. Other sections of known layout (`Corners`,
/// `Ridges`, `Required*`, `Normals`, `Tangents`, ...) are skipped by their
/// count; sections of unknown layout are skipped up to the next keyword.
/// `Vertices` must come before the element sections (every known writer
/// does so), which lets each index be checked where it is read.
///
/// \param name_for_errors the file name used in error messages.
/// \throws Input_error
Mesh_file read_medit(std::istream& in, const std::string& name_for_errors);

/// Reads a Gmsh mesh, format 2.2 or 4.1 (from `$MeshFormat`), ASCII or
/// binary (`gmsh -bin`, `Mesh.Binary = 1`; either byte order, told by the
/// integer 1 after the format line; data size 8: 8-byte doubles and, in 4.1,
/// 8-byte size_t). Errors in the binary part name the byte offset instead of
/// a line ("file.msh: byte 1234: ..."), and `Mesh_file::element_offsets` /
/// `boundary_facet_offsets` replace the lines. Binary element types beyond
/// Gmsh's type 31 are an error (their size is unknown, nothing can skip them);
/// unknown sections are skipped up to their `$End` keyword.
///
/// Element types used: 1 (line), 2 (triangle), 4 (tetrahedron); 15 (point)
/// is read and dropped; other types are skipped unless they are elements of
/// the mesh's own dimension (see `read_mesh()`). An element's label is its
/// physical group (the first one if its entity is in several; 0 if none).
/// In format 2.2 an element in several physical groups is written once per
/// group: the copies are merged, keeping the first label. Node tags may be
/// any positive numbers; they are renumbered 0, 1, ... in file order.
/// `label_names` holds the `$PhysicalNames` of the elements' and boundary
/// facets' dimensions; if both dimensions use the same number, the boundary
/// facets' name wins (boundary conditions are set by boundary labels).
/// Unknown sections (`$NodeData`, `$Periodic`, `$Comments`, ...) are skipped.
///
/// \param name_for_errors the file name used in error messages.
/// \throws Input_error, also for formats other than 2.x, 4.1.
Mesh_file read_gmsh(std::istream& in, const std::string& name_for_errors);

/// Reads an SU2 native mesh (`.su2`, ASCII, one zone).
///
/// Keywords: `NDIME=` (2 or 3) first, then `NELEM=` (elements: the VTK type,
/// the 0-based vertex indices, an optional index column), `NPOIN=` (points:
/// NDIME coordinates and an optional index column; an optional second count
/// on the `NPOIN=` line is ignored), `NMARK=` with, per marker, `MARKER_TAG=`
/// and `MARKER_ELEMS=` (boundary elements). Elements must be triangles (type
/// 5) when NDIME= 2 and tetrahedra (type 10) when NDIME= 3, boundary elements
/// lines (3) or triangles (5): any other type is an error naming it. `%`
/// starts a comment. `NZONE=`/`IZONE=` other than 1 are an error; other
/// keywords (FFD boxes...) are skipped up to the next `KEYWORD=`.
///
/// Markers become boundary labels, named by their tag (`label_names`): a
/// comment `% label N: NAME` (as `write_su2()` writes them) gives the tag
/// NAME the number N; a tag that is an integer is that label, without a
/// name; any other tag gets the smallest positive number not otherwise
/// used, in file order. Elements have no labels in SU2 (all 0). Vertex ids
/// (`Mesh_file::vertex_ids`) are SU2's 0-based indices.
///
/// \param name_for_errors the file name used in error messages.
/// \throws Input_error naming the file and the line.
Mesh_file read_su2(std::istream& in, const std::string& name_for_errors);

} // namespace spring_motion

#endif
