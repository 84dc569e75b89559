// Copyright (c) 2026 SpringMotion developers.
#ifndef SPRING_MOTION_MESH_TRAITS_SIMPLICIAL_MESH_TRAITS_H
#define SPRING_MOTION_MESH_TRAITS_SIMPLICIAL_MESH_TRAITS_H

namespace spring_motion {

/// How SpringMotion reads and writes a simplicial mesh: one specialisation per
/// mesh structure, the way CGAL's `graph_traits` adapt structures for the BGL.
/// Add a mesh type of your own by writing one. A traits object is built from
/// the mesh (`Simplicial_mesh_traits<Mesh> traits(mesh)`) so that it may cache
/// what it needs, such as the plane of a planar `Surface_mesh`.
///
/// Concept `SimplicialMeshTraits`:
/// \code
/// static constexpr int dimension;          // 2: triangles, 3: tetrahedra
/// using Vertex_handle = ...;               // hashable with std::hash, equality comparable
/// explicit Simplicial_mesh_traits(const Mesh&);
/// template <class F> void for_each_vertex(F f) const;   // f(Vertex_handle)
/// template <class F> void for_each_element(F f) const;  // f(const std::array<Vertex_handle, dimension + 1>&)
///                                                       //   domain elements only
/// std::array<double, dimension> point(Vertex_handle) const;
/// void set_point(Mesh&, Vertex_handle, const std::array<double, dimension>&) const;
/// // optional: boundary facets with integer labels (surface patches, file references)
/// template <class F> void for_each_labeled_facet(F f) const; // f(const std::array<Vertex_handle, dimension>&, int)
/// \endcode
///
/// Vertices that no domain element uses are ignored. The boundary itself is
/// found from the elements (a facet of exactly one element), so labels are
/// only names for parts of it.
template <class Mesh, class Enable = void>
struct Simplicial_mesh_traits;

} // namespace spring_motion

#endif
