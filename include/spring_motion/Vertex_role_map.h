// Copyright (c) 2026 SpringMotion developers.
#ifndef SPRING_MOTION_VERTEX_ROLE_MAP_H
#define SPRING_MOTION_VERTEX_ROLE_MAP_H

#include <spring_motion/Spring_network.h>
#include <spring_motion/Vertex_role.h>

#include <boost/property_map/property_map.hpp>

#include <type_traits>
#include <utility>
#include <vector>

namespace spring_motion {

/// Roles read from a property map over the mesh's vertex handles, the way a
/// CGAL algorithm takes `vertex_is_constrained_map`: `get(map, v)` is the
/// Vertex_role of vertex v (a `Surface_mesh` vertex property, a
/// `boost::associative_property_map` over a `std::map`, ...). Pass it where
/// deform() takes a role function: `deform(mesh, vertex_role_map(m), ...)`.
template <class Role_map>
struct Vertex_role_map
{
  Role_map map;
  template <class Vertex_handle, int D>
  Vertex_role operator()(const Vertex_info<D>&, const Vertex_handle& v) const
  {
    return static_cast<Vertex_role>(get(map, v));
  }
};
template <class Role_map>
Vertex_role_map<Role_map> vertex_role_map(Role_map map)
{
  return {std::move(map)};
}

/// Roles from two Boolean property maps over the vertex handles: vertices
/// with `get(moving, v)` move, others with `get(is_constrained, v)` are
/// fixed, the rest are free (CGAL's "constrained vertices keep their
/// place"). `constrained_vertex_maps(moving, boundary_fixed)`.
template <class Moving_map, class Constrained_map>
struct Constrained_vertex_maps
{
  Moving_map moving;
  Constrained_map is_constrained;
  template <class Vertex_handle, int D>
  Vertex_role operator()(const Vertex_info<D>&, const Vertex_handle& v) const
  {
    if(get(moving, v))
      return Vertex_role::moving;
    return get(is_constrained, v) ? Vertex_role::fixed : Vertex_role::free;
  }
};
template <class Moving_map, class Constrained_map>
Constrained_vertex_maps<Moving_map, Constrained_map> constrained_vertex_maps(Moving_map moving,
                                                                          Constrained_map is_constrained)
{
  return {std::move(moving), std::move(is_constrained)};
}

namespace internal {
template <class Role, int D, class Vertex_handle, class = void>
struct Takes_vertex_handle : std::false_type {};
template <class Role, int D, class Vertex_handle>
struct Takes_vertex_handle<Role, D, Vertex_handle,
                           std::void_t<decltype(std::declval<const Role&>()(std::declval<const Vertex_info<D>&>(),
                                                                              std::declval<const Vertex_handle&>()))>>
    : std::true_type {};
} // namespace internal

/// Applies a role function to every vertex of an extracted network: one
/// that takes (Vertex_info, vertex handle), such as a Vertex_role_map, sees
/// the mesh's handle of each vertex; one that takes a Vertex_info alone is
/// applied as by assign_roles(network, role).
template <class Mesh, class Traits, class Role_function>
std::vector<Vertex_role> assign_roles(const Extracted_network<Mesh, Traits>& extracted, const Role_function& role)
{
  constexpr int D = Traits::dimension;
  using Vh = typename Traits::Vertex_handle;
  if constexpr(internal::Takes_vertex_handle<Role_function, D, Vh>::value) {
    const auto& net = extracted.network;
    std::vector<Vertex_role> roles(net.number_of_vertices());
    for(Index i = 0; i < net.number_of_vertices(); ++i) {
      const int* lb = net.vertex_labels.data() + net.vertex_label_offsets[i];
      const int* le = net.vertex_labels.data() + net.vertex_label_offsets[i + 1];
      roles[i] = role(Vertex_info<D>{i, net.points[i], bool(net.on_boundary[i]), lb, le}, extracted.handles[i]);
    }
    return roles;
  } else
    return assign_roles(extracted.network, role);
}

} // namespace spring_motion

#endif
