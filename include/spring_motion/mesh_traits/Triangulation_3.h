// Copyright (c) 2026 SpringMotion developers.
#ifndef SPRING_MOTION_MESH_TRAITS_TRIANGULATION_3_H
#define SPRING_MOTION_MESH_TRAITS_TRIANGULATION_3_H

#include <spring_motion/internal/geometry/triangulation_points.h>
#include <spring_motion/mesh_traits/Simplicial_mesh_traits.h>

#include <CGAL/Triangulation_3.h>
#include <CGAL/number_utils.h>

#include <array>
#include <type_traits>
#include <utility>

namespace spring_motion {
namespace internal {

// Derived from some CGAL::Triangulation_3 (the base's lock parameter is not
// recoverable from the derived class's typedefs, so match by conversion).
template <class Gt, class Tds, class Lock>
std::true_type derives_from_triangulation_3(const CGAL::Triangulation_3<Gt, Tds, Lock>*);
std::false_type derives_from_triangulation_3(...);
template <class T>
constexpr bool is_triangulation_3 = decltype(derives_from_triangulation_3(std::declval<const T*>()))::value;

} // namespace internal

/// Any CGAL `Triangulation_3` and its derived classes (Delaunay, regular, the
/// triangulation of a Mesh_3 complex). The elements are the finite cells; all
/// of them count, so a triangulation used as a mesh of its convex hull. For a
/// Mesh_3 result, whose domain is only the cells in the complex, use the
/// `Mesh_complex_3_in_triangulation_3` traits instead.
template <class Tr>
struct Simplicial_mesh_traits<Tr, std::enable_if_t<internal::is_triangulation_3<Tr>>>
{
  static constexpr int dimension = 3;
  using Vertex_handle = typename Tr::Vertex_handle;

  explicit Simplicial_mesh_traits(const Tr& tr) : tr_(tr) {}

  template <class F>
  void for_each_vertex(F f) const
  {
    for(auto v : tr_.finite_vertex_handles())
      f(Vertex_handle(v));
  }

  template <class F>
  void for_each_element(F f) const
  {
    for(auto c : tr_.finite_cell_handles())
      f(std::array<Vertex_handle, 4>{c->vertex(0), c->vertex(1), c->vertex(2), c->vertex(3)});
  }

  std::array<double, 3> point(Vertex_handle v) const
  {
    return internal::Triangulation_points<Tr, 3>::get(v->point());
  }

  void set_point(Tr&, Vertex_handle v, const std::array<double, 3>& p) const
  {
    // Moving points breaks the Delaunay (regular) property: after deform()
    // the triangulation is a valid simplicial mesh, not one to insert() into.
    v->set_point(internal::Triangulation_points<Tr, 3>::moved(v->point(), p));
  }

private:
  const Tr& tr_;
};

} // namespace spring_motion

#endif
