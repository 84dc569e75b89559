// Copyright (c) 2026 SpringMotion developers.
#ifndef SPRING_MOTION_MESH_TRAITS_MESH_COMPLEX_3_IN_TRIANGULATION_3_H
#define SPRING_MOTION_MESH_TRAITS_MESH_COMPLEX_3_IN_TRIANGULATION_3_H

#include <spring_motion/mesh_traits/Simplicial_mesh_traits.h>
#include <spring_motion/mesh_traits/Triangulation_3.h>

#include <CGAL/Mesh_complex_3_in_triangulation_3.h>

#include <array>
#include <map>
#include <type_traits>

namespace spring_motion {

/// A CGAL Mesh_3 result, `Mesh_complex_3_in_triangulation_3`. The elements
/// are the cells in the complex (every subdomain), so the outside and the
/// holes of the domain are not part of the network. The far points Mesh_3
/// may add (vertices of dimension -1) are skipped; moved vertices keep their
/// weight.
///
/// Labeled facets are the facets in the complex on the boundary of the
/// meshed region (a facet between two cells in the complex is an internal
/// surface, not a boundary of the network, and is not listed). The label is
/// the facet's surface patch index when that converts to `int` (polyhedral
/// domains: the patch id); otherwise (implicit and labeled-image domains,
/// whose index is a pair of subdomain indices) the distinct indices are
/// numbered 1, 2, ... in increasing order.
template <class Tr, class CornerIndex, class CurveIndex>
struct Simplicial_mesh_traits<CGAL::Mesh_complex_3_in_triangulation_3<Tr, CornerIndex, CurveIndex>>
{
  static constexpr int dimension = 3;
  using C3t3 = CGAL::Mesh_complex_3_in_triangulation_3<Tr, CornerIndex, CurveIndex>;
  using Vertex_handle = typename Tr::Vertex_handle;
  using Surface_patch_index = typename C3t3::Surface_patch_index;

  explicit Simplicial_mesh_traits(const C3t3& c3t3) : c3t3_(c3t3) {}

  template <class F>
  void for_each_vertex(F f) const
  {
    for(auto v : c3t3_.triangulation().finite_vertex_handles())
      if(c3t3_.in_dimension(v) != -1) // a far point
        f(Vertex_handle(v));
  }

  template <class F>
  void for_each_element(F f) const
  {
    for(auto c = c3t3_.cells_in_complex_begin(); c != c3t3_.cells_in_complex_end(); ++c)
      f(std::array<Vertex_handle, 4>{c->vertex(0), c->vertex(1), c->vertex(2), c->vertex(3)});
  }

  template <class F>
  void for_each_labeled_facet(F f) const
  {
    constexpr bool integral = std::is_convertible_v<Surface_patch_index, int>;
    std::map<Surface_patch_index, int> number;
    if constexpr(!integral) {
      for(auto fit = c3t3_.facets_in_complex_begin(); fit != c3t3_.facets_in_complex_end(); ++fit)
        number.emplace(c3t3_.surface_patch_index(*fit), 0);
      int next = 1;
      for(auto& p : number)
        p.second = next++;
    }
    const auto& tr = c3t3_.triangulation();
    for(auto fit = c3t3_.facets_in_complex_begin(); fit != c3t3_.facets_in_complex_end(); ++fit) {
      const auto c = fit->first;
      const int i = fit->second;
      const auto mirror = tr.mirror_facet(*fit);
      const bool inside = c3t3_.is_in_complex(c), inside_mirror = c3t3_.is_in_complex(mirror.first);
      if(inside == inside_mirror)
        continue; // an internal surface (or a facet of no meshed cell)
      const std::array<Vertex_handle, 3> vs{c->vertex((i + 1) & 3), c->vertex((i + 2) & 3), c->vertex((i + 3) & 3)};
      const Surface_patch_index index = c3t3_.surface_patch_index(*fit);
      if constexpr(integral)
        f(vs, int(index));
      else
        f(vs, number.at(index));
    }
  }

  std::array<double, 3> point(Vertex_handle v) const
  {
    return internal::Triangulation_points<Tr, 3>::get(v->point());
  }

  void set_point(C3t3&, Vertex_handle v, const std::array<double, 3>& p) const
  {
    // After deform() the complex is a valid mesh of the moved domain but its
    // triangulation is in general no longer regular: do not refine it further.
    v->set_point(internal::Triangulation_points<Tr, 3>::moved(v->point(), p));
  }

private:
  const C3t3& c3t3_;
};

} // namespace spring_motion

#endif
