// Copyright (c) 2026 SpringMotion developers.
#ifndef SPRING_MOTION_MESH_TRAITS_INDEXED_MESH_H
#define SPRING_MOTION_MESH_TRAITS_INDEXED_MESH_H

#include <spring_motion/Indexed_mesh.h>
#include <spring_motion/mesh_traits/Simplicial_mesh_traits.h>

#include <array>
#include <cstdint>

namespace spring_motion {

/// `Indexed_mesh<D>`: vertices are indices; labeled boundary facets are the
/// file's boundary references.
template <int D>
struct Simplicial_mesh_traits<Indexed_mesh<D>>
{
  static constexpr int dimension = D;
  using Vertex_handle = std::uint32_t;
  using Mesh = Indexed_mesh<D>;

  explicit Simplicial_mesh_traits(const Mesh& mesh) : mesh_(mesh) {}

  template <class F>
  void for_each_vertex(F f) const
  {
    for(std::uint32_t v = 0; v < mesh_.points.size(); ++v)
      f(v);
  }
  template <class F>
  void for_each_element(F f) const
  {
    for(const auto& e : mesh_.elements)
      f(e);
  }
  template <class F>
  void for_each_labeled_facet(F f) const
  {
    for(std::size_t i = 0; i < mesh_.boundary_facets.size(); ++i)
      f(mesh_.boundary_facets[i], i < mesh_.boundary_labels.size() ? mesh_.boundary_labels[i] : 0);
  }
  std::array<double, D> point(Vertex_handle v) const { return mesh_.points[v]; }
  void set_point(Mesh& mesh, Vertex_handle v, const std::array<double, D>& p) const { mesh.points[v] = p; }

private:
  const Mesh& mesh_;
};

} // namespace spring_motion

#endif
