// Copyright (c) 2026 SpringMotion developers.
#ifndef SPRING_MOTION_MESH_TRAITS_TRIANGULATION_2_H
#define SPRING_MOTION_MESH_TRAITS_TRIANGULATION_2_H

#include <spring_motion/internal/geometry/triangulation_points.h>
#include <spring_motion/mesh_traits/Simplicial_mesh_traits.h>

#include <CGAL/Triangulation_2.h>
#include <CGAL/number_utils.h>

#include <array>
#include <type_traits>
#include <utility>

namespace spring_motion {
namespace internal {

template <class Face, class = void>
struct Has_is_in_domain : std::false_type {};
template <class Face>
struct Has_is_in_domain<Face, std::void_t<decltype(std::declval<const Face&>().is_in_domain())>>
    : std::true_type {};

} // namespace internal

/// Any CGAL `Triangulation_2` and its derived classes (Delaunay, constrained,
/// constrained Delaunay, `Constrained_triangulation_plus_2`, regular: a moved
/// vertex keeps its weight). The elements are
/// the finite faces; when the face type knows `is_in_domain()` (a Mesh_2 face
/// base), only the faces in the domain count, so the holes of a Mesh_2 domain
/// are holes of the spring network too.
template <class Tr>
struct Simplicial_mesh_traits<
    Tr, std::enable_if_t<std::is_base_of_v<CGAL::Triangulation_2<typename Tr::Geom_traits,
                                                                 typename Tr::Triangulation_data_structure>,
                                           Tr>>>
{
  static constexpr int dimension = 2;
  using Vertex_handle = typename Tr::Vertex_handle;
  using Face = typename Tr::Face;

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
    for(auto fh : tr_.finite_face_handles()) {
      if constexpr(internal::Has_is_in_domain<Face>::value)
        if(!fh->is_in_domain())
          continue;
      f(std::array<Vertex_handle, 3>{fh->vertex(0), fh->vertex(1), fh->vertex(2)});
    }
  }

  std::array<double, 2> point(Vertex_handle v) const { return internal::Triangulation_points<Tr, 2>::get(v->point()); }

  void set_point(Tr&, Vertex_handle v, const std::array<double, 2>& p) const
  {
    // Moving points breaks the Delaunay property: after deform() the
    // triangulation is a valid simplicial mesh, not one to insert() into.
    // A regular triangulation's vertex keeps its weight.
    v->set_point(internal::Triangulation_points<Tr, 2>::moved(v->point(), p));
  }

private:
  const Tr& tr_;
};

} // namespace spring_motion

#endif
