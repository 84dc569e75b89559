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
/// ones stay at their initial point, `free` ones follow the springs, and
/// `sliding` ones follow the springs within the plane (2D: the line) of every
/// labelled boundary part they lie on: a symmetry plane (docs/method.md,
/// "Vertex roles").
enum class Vertex_role : unsigned char { free, fixed, moving, sliding };

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

/// The command line's rules (`--moving`, `--fixed`, `--sliding`), for
/// labelled boundary parts: a boundary vertex on a `moving` part moves; else
/// it is fixed if it lies on a `fixed` part (when `fixed` is not given: on
/// any part that is not sliding, or on no labelled part); else it slides if
/// it lies on a `sliding` part; else (only when `fixed` is given) it is
/// free. Interior vertices are free. So a vertex on a sliding and a moving
/// part moves, on a sliding and a fixed part it stays.
struct Boundary_label_roles
{
  std::vector<int> moving;
  std::vector<int> sliding;
  std::vector<int> fixed;
  bool fixed_given = false;  ///< false: every part that neither moves nor slides is fixed

  template <int D>
  Vertex_role operator()(const Vertex_info<D>& v) const
  {
    if(!v.on_boundary)
      return Vertex_role::free;
    const auto has_any = [&](const std::vector<int>& labels) {
      return std::any_of(labels.begin(), labels.end(), [&](int l) { return v.has_label(l); });
    };
    if(has_any(moving))
      return Vertex_role::moving;
    const bool on_other_part =
      v.labels_begin == v.labels_end ||
      std::any_of(v.labels_begin, v.labels_end,
                  [&](int l) { return std::find(sliding.begin(), sliding.end(), l) == sliding.end(); });
    if(fixed_given ? has_any(fixed) : on_other_part)
      return Vertex_role::fixed;
    if(has_any(sliding))
      return Vertex_role::sliding;
    return Vertex_role::free;
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

/// The free (or sliding) vertices that no path of springs joins to a moving
/// or fixed vertex, in increasing order: their displacement is undetermined (the
/// system is singular), so a well-posed problem has none. Vertices that no
/// element uses take no part and are never listed.
template <int D>
std::vector<Index> undetermined_vertices(const Spring_network<D>& net, const std::vector<Vertex_role>& roles)
{
  const std::size_t n = net.number_of_vertices();
  const std::vector<char> used = used_vertices(net);
  std::vector<char> reached(n, 0);
  std::deque<Index> queue;
  for(Index i = 0; i < n; ++i)
    if(used[i] && (roles[i] == Vertex_role::moving || roles[i] == Vertex_role::fixed)) {
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
