// Copyright (c) 2026 SpringMotion developers.
// Private to the spring-motion executable: from a mesh file to a spring
// network with vertex roles, with every problem reported against the file.
#ifndef SPRING_MOTION_SRC_CLI_MESH_SETUP_H
#define SPRING_MOTION_SRC_CLI_MESH_SETUP_H

#include <spring_motion/Indexed_mesh.h>
#include <spring_motion/Spring_network.h>
#include <spring_motion/Vertex_role.h>
#include <spring_motion/io/read_mesh.h>

#include <cstddef>
#include <map>
#include <string>
#include <vector>

namespace spring_motion {
namespace cli {

/// The mesh of a file as it stands, judged with exact predicates.
struct Element_problems
{
  std::vector<std::size_t> degenerate; ///< zero area / volume
  /// Elements that overlap a neighbour across a shared facet (the apexes of
  /// the two elements lie on the same side of it). Of each overlapping pair,
  /// the element whose orientation differs from the majority's is listed
  /// (meshers write every element with one orientation); both when the file
  /// orients its elements arbitrarily.
  std::vector<std::size_t> inverted;
  std::size_t positive = 0, negative = 0; ///< elements by the sign of their orientation
};

/// The boundary labels of a file and what they mark.
struct Label_use
{
  std::size_t boundary_facets = 0; ///< facets of the label on the mesh's boundary
  std::size_t interior_facets = 0; ///< facets of the label inside the mesh (ignored)
  std::size_t first_interior_line = 0;
  std::size_t elements = 0;        ///< elements with this label
};

/// A mesh file made into a spring network whose vertices are the file's
/// vertices, in file order (a vertex no element uses takes no part).
template <int D>
struct Mesh_setup
{
  std::string path;
  const Mesh_file* file = nullptr;
  const Indexed_mesh<D>* mesh = nullptr;
  Spring_network<D> network;
  std::map<int, Label_use> labels;
  Element_problems problems;
};

/// Checks the elements (exact orientation, overlaps, facets shared by more
/// than two elements) and the labelled facets (each a side of an element),
/// and builds the network. With `require_valid`, degenerate or inverted
/// elements throw Input_error listing the first few with their lines;
/// without it (`check`), they are left in `problems` and no network is built
/// when there are any.
template <int D>
Mesh_setup<D> make_mesh_setup(const std::string& path, const Mesh_file& file, bool require_valid);

/// The one-line description of the problems: "2 degenerate triangles at
/// lines 14, 15: expected ...". Empty when there are none.
template <int D>
std::string describe_problems(const Mesh_setup<D>& setup, std::size_t* first_line);

/// The labels named in a comma-separated list, each a number or a Gmsh
/// physical name; throws Input_error for an unknown label, a label that
/// marks no boundary facet, or an empty list, listing the valid labels.
template <int D>
std::vector<int> resolve_labels(const Mesh_setup<D>& setup, const std::string& option, const std::string& list);

/// "1 'outer' (16 edges), 2 'hole' (8 edges)": the labels a user can pick.
template <int D>
std::string describe_boundary_labels(const Mesh_setup<D>& setup);

/// Vertex roles of the command line (see `deform --help`): a boundary vertex
/// on a moving part moves (also when it lies on a fixed part), a vertex in
/// `prescribed` moves; without `fixed_given` every other boundary vertex is
/// fixed; with it only those on a fixed part, the rest of the boundary is free.
template <int D>
std::vector<Vertex_role> assign_command_line_roles(const Mesh_setup<D>& setup, const std::vector<int>& moving,
                                                   const std::vector<int>& fixed, bool fixed_given,
                                                   const std::vector<char>& prescribed);

/// Throws Input_error when no vertex moves, or when free vertices reach no
/// moving or fixed vertex (the system would be singular), naming a vertex by
/// its number in the file.
template <int D>
void check_roles(const Mesh_setup<D>& setup, const std::vector<Vertex_role>& roles);

/// "triangle" / "tetrahedron", "edge" / "triangle", "area" / "volume"
const char* element_noun(int dimension);
const char* facet_noun(int dimension);

} // namespace cli
} // namespace spring_motion

#endif
