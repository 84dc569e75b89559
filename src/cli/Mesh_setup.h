// Copyright (c) 2026 SpringMotion developers.
// Private to the spring-motion executable: from a mesh file to a spring
// network with vertex roles, with every problem reported against the file.
#ifndef SPRING_MOTION_SRC_CLI_MESH_SETUP_H
#define SPRING_MOTION_SRC_CLI_MESH_SETUP_H

#include <spring_motion/Error.h>
#include <spring_motion/Indexed_mesh.h>
#include <spring_motion/Input_error.h>
#include <spring_motion/check_input_mesh.h>
#include <spring_motion/Spring_network.h>
#include <spring_motion/Vertex_role.h>
#include <spring_motion/io/read_mesh.h>
#include <spring_motion/mesh_traits/Indexed_mesh.h>

#include <cstddef>
#include <cstdint>
#include <limits>
#include <map>
#include <string>
#include <vector>

namespace spring_motion {
namespace cli {

/// The boundary labels of a file and what they mark.
struct Label_use
{
  std::size_t boundary_facets = 0; ///< facets of the label on the mesh's boundary
  std::size_t interior_facets = 0; ///< facets of the label inside the mesh (ignored)
  std::size_t first_interior_facet = 0; ///< index in the file's boundary facets
  std::size_t elements = 0;        ///< elements with this label
};

/// The mesh of a file and the labelled facets to hand to the library: those
/// on the boundary (a labelled facet inside the mesh marks no boundary part
/// and is ignored).
template <int D>
struct Boundary_labelled_mesh
{
  const Indexed_mesh<D>* mesh = nullptr;
  std::vector<char> on_boundary; ///< per labelled facet of the file
};

/// A mesh file made into a spring network through the library's extraction
/// (`extract_spring_network`), with the way back to the file: the network
/// numbers the vertices some element uses, in file order.
template <int D>
struct Mesh_setup
{
  std::string path;
  const Mesh_file* file = nullptr;
  const Indexed_mesh<D>* mesh = nullptr;
  /// Built here, then moved into the Network_deformer that runs the motion
  /// (one copy of the network in memory): after that, only the maps and the
  /// file describe the mesh.
  Spring_network<D> network;
  std::vector<std::uint32_t> file_vertex;   ///< network vertex -> vertex index in the file's arrays
  std::vector<Index> network_vertex;        ///< file vertex index -> network vertex (no_vertex when unused)
  std::map<int, Label_use> labels;
  Input_mesh_problems problems;

  static constexpr Index no_vertex = std::numeric_limits<Index>::max();
  /// The number the file gives network vertex i.
  std::size_t vertex_number(Index i) const { return file->vertex_ids[file_vertex[i]]; }
};

/// Checks the elements (`check_input_mesh`) and the labelled facets (each a
/// side of an element), and builds the network. With `require_valid`, an
/// invalid mesh throws Input_error listing the first few problem elements
/// with their lines; without it (`check`), the problems are left in
/// `problems` and no network is built when there are any.
template <int D>
Mesh_setup<D> make_mesh_setup(const std::string& path, const Mesh_file& file, bool require_valid);

/// The one-line description of the problems: "2 degenerate triangles at
/// lines 14, 15: expected ...". Empty when there are none.
template <int D>
std::string describe_problems(const Mesh_setup<D>& setup, std::size_t* first_line);

/// A library error about one vertex or element of the network, as an
/// Input_error naming the vertex by its number in the file, or the line of
/// the element; other errors keep their message, against the mesh file.
template <int D>
Input_error file_error(const Mesh_setup<D>& setup, const Error& error);

/// The labels named in a comma-separated list, each a number or a Gmsh
/// physical name; throws Input_error for an unknown label, a label that
/// marks no boundary facet, or an empty list, listing the valid labels.
template <int D>
std::vector<int> resolve_labels(const Mesh_setup<D>& setup, const std::string& option, const std::string& list);

/// "1 'outer' (16 edges), 2 'hole' (8 edges)": the labels a user can pick.
template <int D>
std::string describe_boundary_labels(const Mesh_setup<D>& setup);

/// Vertex roles of the command line (see `deform --help`): the library's
/// rules for labelled parts (Boundary_label_roles), and a vertex in
/// `prescribed` (a displacement file's) moves.
template <int D>
std::vector<Vertex_role> assign_command_line_roles(const Mesh_setup<D>& setup, const Boundary_label_roles& rules,
                                                   const std::vector<char>& prescribed);

/// "triangle" / "tetrahedron", "edge" / "triangle", "area" / "volume"
const char* element_noun(int dimension);
const char* facet_noun(int dimension);

} // namespace cli

/// The traits of a file's mesh: those of `Indexed_mesh`, listing only the
/// labelled facets on the boundary.
template <int D>
struct Simplicial_mesh_traits<cli::Boundary_labelled_mesh<D>> : Simplicial_mesh_traits<Indexed_mesh<D>>
{
  explicit Simplicial_mesh_traits(const cli::Boundary_labelled_mesh<D>& m)
      : Simplicial_mesh_traits<Indexed_mesh<D>>(*m.mesh), labelled_(m)
  {
  }
  template <class F>
  void for_each_labeled_facet(F f) const
  {
    const Indexed_mesh<D>& mesh = *labelled_.mesh;
    for(std::size_t i = 0; i < mesh.boundary_facets.size(); ++i)
      if(labelled_.on_boundary[i])
        f(mesh.boundary_facets[i], i < mesh.boundary_labels.size() ? mesh.boundary_labels[i] : 0);
  }

private:
  const cli::Boundary_labelled_mesh<D>& labelled_;
};

} // namespace spring_motion

#endif
