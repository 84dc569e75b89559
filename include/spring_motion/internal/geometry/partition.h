// Copyright (c) 2026 SpringMotion developers.
#ifndef SPRING_MOTION_INTERNAL_GEOMETRY_PARTITION_H
#define SPRING_MOTION_INTERNAL_GEOMETRY_PARTITION_H

#include <spring_motion/Error.h>
#include <spring_motion/Spring_network.h>
#include <spring_motion/Vertex_role.h>
#include <spring_motion/internal/geometry/sliding_planes.h>

#include <algorithm>
#include <array>
#include <cstddef>
#include <limits>
#include <numeric>
#include <vector>

namespace spring_motion {
namespace internal {

/// The rank owning each vertex: recursive coordinate bisection of the
/// vertices some element uses (each cut across the longest side of the
/// set's bounding box, at the count that keeps the parts' sizes in
/// proportion), so that parts are compact and their ghost layers small.
/// Deterministic: ties in a coordinate are broken by the vertex number.
/// Vertices no element uses go to part 0. With more parts than used
/// vertices, some parts own none.
template <int D>
std::vector<int> partition_vertices(const Spring_network<D>& net, int parts)
{
  SPRING_MOTION_CHECK(parts > 0, "partition_vertices: expected a positive number of parts, got " << parts);
  std::vector<int> owner(net.number_of_vertices(), 0);
  const std::vector<char> used = used_vertices(net);
  std::vector<Index> ids;
  for(Index v = 0; v < used.size(); ++v)
    if(used[v])
      ids.push_back(v);
  // [begin, end) of ids goes to parts [first, first + count)
  struct Task
  {
    std::size_t begin, end;
    int first, count;
  };
  std::vector<Task> tasks{{0, ids.size(), 0, parts}};
  while(!tasks.empty()) {
    const Task t = tasks.back();
    tasks.pop_back();
    const std::size_t n = t.end - t.begin;
    if(t.count == 1 || n <= 1) {
      for(std::size_t k = t.begin; k < t.end; ++k)
        owner[ids[k]] = t.first;
      continue;
    }
    std::array<double, D> lo, hi;
    lo.fill(std::numeric_limits<double>::infinity());
    hi.fill(-std::numeric_limits<double>::infinity());
    for(std::size_t k = t.begin; k < t.end; ++k)
      for(int c = 0; c < D; ++c) {
        lo[c] = std::min(lo[c], net.points[ids[k]][c]);
        hi[c] = std::max(hi[c], net.points[ids[k]][c]);
      }
    int axis = 0;
    for(int c = 1; c < D; ++c)
      if(hi[c] - lo[c] > hi[axis] - lo[axis])
        axis = c;
    const int left = t.count / 2;
    const std::size_t cut = t.begin + n * std::size_t(left) / std::size_t(t.count);
    std::nth_element(ids.begin() + std::ptrdiff_t(t.begin), ids.begin() + std::ptrdiff_t(cut),
                     ids.begin() + std::ptrdiff_t(t.end), [&](Index a, Index b) {
                       const double xa = net.points[a][axis], xb = net.points[b][axis];
                       return xa < xb || (xa == xb && a < b);
                     });
    tasks.push_back({t.begin, cut, t.first, left});
    tasks.push_back({cut, t.end, t.first + left, t.count - left});
  }
  return owner;
}

/// One rank's part of a partitioned mesh: the vertices it owns, then one
/// layer of ghosts, and every element that has an owned vertex. So every
/// owned vertex has all its elements here, and its row of the step system
/// (stiffness, diagonal, right-hand side) comes out whole without
/// communication; a ghost's row is incomplete and belongs to its owner.
template <int D>
struct Mesh_part
{
  static constexpr std::size_t no_row = std::numeric_limits<std::size_t>::max();

  Spring_network<D> network;           ///< local numbering: owned vertices first
  std::vector<Vertex_role> roles;      ///< per local vertex
  std::vector<Index> global_vertex;    ///< local vertex -> whole-mesh vertex
  std::size_t owned_vertices = 0;      ///< local vertices [0, owned_vertices) are this part's
  std::vector<std::size_t> global_element; ///< local element -> whole-mesh element
  std::vector<char> counted;           ///< per local element: counted by this part (its first vertex is owned)
  /// per local vertex: the row of the whole free system (free vertices
  /// numbered part after part, by whole-mesh number within a part), or no_row
  std::vector<std::size_t> free_row;
  std::size_t first_row = 0, owned_rows = 0, total_rows = 0; ///< this part's rows: [first_row, first_row + owned_rows)
};

/// Part `part` of the mesh under `owner` (partition_vertices). The part's
/// network has the whole mesh's longest initial edge, which scales the
/// stiffness, and its vertices' boundary labels. A part that owns no vertex
/// holds element 0 as a ghost, so that it is a valid network and its rank
/// takes part in every step like the others. `solved`: the vertices with a
/// row (`solved_vertices` of the whole mesh, its sliding planes fitted on the
/// whole mesh, which the part's deformer is then given).
template <int D>
Mesh_part<D> extract_part(const Spring_network<D>& net, const std::vector<Vertex_role>& roles,
                          const std::vector<char>& solved, const std::vector<int>& owner, int parts, int part)
{
  const std::size_t n = net.number_of_vertices();
  SPRING_MOTION_CHECK(roles.size() == n && owner.size() == n && solved.size() == n,
                      "extract_part: one role, owner and row flag per vertex expected");
  const std::vector<char> used = used_vertices(net);
  Mesh_part<D> p;
  // the whole free system's rows: part after part, by vertex number within a part
  std::vector<std::size_t> rows_of(std::size_t(parts) + 1, 0), row(n, Mesh_part<D>::no_row);
  for(Index v = 0; v < n; ++v)
    if(solved[v])
      ++rows_of[std::size_t(owner[v]) + 1];
  std::partial_sum(rows_of.begin(), rows_of.end(), rows_of.begin());
  {
    std::vector<std::size_t> next(rows_of.begin(), rows_of.end() - 1);
    for(Index v = 0; v < n; ++v)
      if(solved[v])
        row[v] = next[std::size_t(owner[v])]++;
  }
  p.first_row = rows_of[std::size_t(part)];
  p.owned_rows = rows_of[std::size_t(part) + 1] - p.first_row;
  p.total_rows = rows_of.back();

  std::vector<Index> local(n, std::numeric_limits<Index>::max());
  for(Index v = 0; v < n; ++v)
    if(used[v] && owner[v] == part) {
      local[v] = Index(p.global_vertex.size());
      p.global_vertex.push_back(v);
    }
  p.owned_vertices = p.global_vertex.size();
  for(std::size_t t = 0; t < net.number_of_elements(); ++t)
    if(std::any_of(net.elements[t].begin(), net.elements[t].end(), [&](Index v) { return owner[v] == part; }))
      p.global_element.push_back(t);
  if(p.global_element.empty())
    p.global_element.push_back(0);
  std::vector<Index> ghosts;
  for(std::size_t t : p.global_element)
    for(Index v : net.elements[t])
      if(owner[v] != part)
        ghosts.push_back(v);
  std::sort(ghosts.begin(), ghosts.end());
  ghosts.erase(std::unique(ghosts.begin(), ghosts.end()), ghosts.end());
  for(Index v : ghosts) {
    local[v] = Index(p.global_vertex.size());
    p.global_vertex.push_back(v);
  }
  std::vector<std::array<double, D>> points;
  for(Index v : p.global_vertex) {
    points.push_back(net.points[v]);
    p.roles.push_back(roles[v]);
    p.free_row.push_back(row[v]);
  }
  std::vector<std::array<Index, D + 1>> elements;
  for(std::size_t t : p.global_element) {
    std::array<Index, D + 1> e;
    for(int k = 0; k <= D; ++k)
      e[std::size_t(k)] = local[net.elements[t][std::size_t(k)]];
    elements.push_back(e);
    p.counted.push_back(owner[net.elements[t][0]] == part);
  }
  p.network = make_spring_network<D>(std::move(points), std::move(elements));
  p.network.longest_initial_edge = net.longest_initial_edge;
  p.network.vertex_label_offsets.assign(1, 0);
  p.network.vertex_labels.clear();
  for(Index v : p.global_vertex) {
    const auto first = net.vertex_labels.begin();
    p.network.vertex_labels.insert(p.network.vertex_labels.end(), first + std::ptrdiff_t(net.vertex_label_offsets[v]),
                                   first + std::ptrdiff_t(net.vertex_label_offsets[v + 1]));
    p.network.vertex_label_offsets.push_back(Index(p.network.vertex_labels.size()));
  }
  return p;
}

} // namespace internal
} // namespace spring_motion

#endif
