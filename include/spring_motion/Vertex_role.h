// Copyright (c) 2026 SpringMotion developers.
#ifndef SPRING_MOTION_VERTEX_ROLE_H
#define SPRING_MOTION_VERTEX_ROLE_H

#include <spring_motion/Spring_network.h>

#include <algorithm>
#include <array>
#include <deque>
#include <vector>

namespace spring_motion {

/// What happens to a vertex: the motion places `moving` vertices, `fixed`
/// ones stay at their initial point, `free` ones follow the springs.
enum class Vertex_role : unsigned char { free, fixed, moving };

/// What a role function sees of a vertex.
template <int D>
struct Vertex_info
{
  Index index;                       ///< in the network
  std::array<double, D> point;       ///< initial position
  bool on_boundary;
  const int* labels_begin;           ///< labels of the boundary parts it lies on
  const int* labels_end;
  bool has_label(int l) const { return std::find(labels_begin, labels_end, l) != labels_end; }
};

/// Boundary vertices whose initial point satisfies `pred` move, the rest of
/// the boundary is fixed, interior vertices are free.
template <class Pred>
struct Moving_boundary_where
{
  Pred pred;
  template <int D>
  Vertex_role operator()(const Vertex_info<D>& v) const
  {
    if(!v.on_boundary)
      return Vertex_role::free;
    return pred(v.point) ? Vertex_role::moving : Vertex_role::fixed;
  }
};
template <class Pred>
Moving_boundary_where<Pred> moving_boundary_where(Pred pred)
{
  return {pred};
}

/// Boundary vertices on a part with one of `labels` move (also when they lie
/// on another part too), the rest of the boundary is fixed.
struct Moving_boundary_labels
{
  std::vector<int> labels;
  template <int D>
  Vertex_role operator()(const Vertex_info<D>& v) const
  {
    if(!v.on_boundary)
      return Vertex_role::free;
    for(int l : labels)
      if(v.has_label(l))
        return Vertex_role::moving;
    return Vertex_role::fixed;
  }
};

/// Every boundary vertex moves (for instance a rigid translation of the
/// whole domain).
struct All_boundary_moving
{
  template <int D>
  Vertex_role operator()(const Vertex_info<D>& v) const
  {
    return v.on_boundary ? Vertex_role::moving : Vertex_role::free;
  }
};

/// Applies a role function to every vertex of the network.
template <int D, class Role_function>
std::vector<Vertex_role> assign_roles(const Spring_network<D>& net, const Role_function& role)
{
  std::vector<Vertex_role> roles(net.number_of_vertices());
  for(Index i = 0; i < net.number_of_vertices(); ++i) {
    const int* lb = net.vertex_labels.data() + net.vertex_label_offsets[i];
    const int* le = net.vertex_labels.data() + net.vertex_label_offsets[i + 1];
    roles[i] = role(Vertex_info<D>{i, net.points[i], bool(net.on_boundary[i]), lb, le});
  }
  return roles;
}

/// The free vertices that no path of springs joins to a moving or fixed
/// vertex, in increasing order: their displacement is undetermined (the
/// system is singular), so a well-posed problem has none. Vertices that no
/// element uses take no part and are never listed.
template <int D>
std::vector<Index> undetermined_vertices(const Spring_network<D>& net, const std::vector<Vertex_role>& roles)
{
  const std::size_t n = net.number_of_vertices();
  std::vector<char> used(n, 0), reached(n, 0);
  for(const auto& e : net.elements)
    for(Index v : e)
      used[v] = 1;
  std::deque<Index> queue;
  for(Index i = 0; i < n; ++i)
    if(used[i] && roles[i] != Vertex_role::free) {
      reached[i] = 1;
      queue.push_back(i);
    }
  while(!queue.empty()) {
    const Index i = queue.front();
    queue.pop_front();
    for(Index p = net.adjacency_offsets[i]; p < net.adjacency_offsets[i + 1]; ++p)
      if(!reached[net.adjacency[p]]) {
        reached[net.adjacency[p]] = 1;
        queue.push_back(net.adjacency[p]);
      }
  }
  std::vector<Index> out;
  for(Index i = 0; i < n; ++i)
    if(used[i] && !reached[i])
      out.push_back(i);
  return out;
}

} // namespace spring_motion

#endif
