// Copyright (c) 2026 SpringMotion developers.
#ifndef SPRING_MOTION_INTERNAL_GEOMETRY_SLIDING_PLANES_H
#define SPRING_MOTION_INTERNAL_GEOMETRY_SLIDING_PLANES_H

#include <spring_motion/Boundary_plane.h>
#include <spring_motion/Error.h>
#include <spring_motion/Spring_network.h>
#include <spring_motion/Vertex_role.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <sstream>
#include <vector>

namespace spring_motion {
namespace internal {

/// What a sliding vertex may do: move within the intersection of the planes
/// of its parts. `normals` are orthonormal (count of them in use), axis-aligned
/// ones first and exact, so that snapping keeps those coordinates bitwise.
template <int D>
struct Sliding_vertex
{
  Index vertex;
  int count = 0;
  std::array<std::array<double, D>, D> normals{};
  std::array<int, D> axes{};   ///< the axis of normals[j], or -1
  std::array<double, D * D> projector{}; ///< I - sum n n^T, row-major
};

/// Sliding vertices and those whose planes leave no freedom (a corner of
/// three planes in 3D, of two lines in 2D), which are held fixed.
template <int D>
struct Sliding_set
{
  std::vector<Sliding_vertex<D>> vertices;
  std::vector<Index> pinned;
};

/// The sliding vertices of `roles` with the planes of the labelled parts
/// each lies on: those of `given`, the others fitted on `net`.
template <int D>
Sliding_set<D> sliding_set(const Spring_network<D>& net, const std::vector<Vertex_role>& roles,
                           const std::vector<Boundary_plane<D>>& given = {})
{
  Sliding_set<D> out;
  std::map<int, Boundary_plane<D>> planes;
  for(const Boundary_plane<D>& pl : given)
    SPRING_MOTION_CHECK(planes.emplace(pl.label, pl).second, "two planes given for part " << pl.label);
  for(Index i = 0; i < net.number_of_vertices(); ++i) {
    if(roles[i] != Vertex_role::sliding)
      continue;
    const Index lb = net.vertex_label_offsets[i], le = net.vertex_label_offsets[i + 1];
    SPRING_MOTION_VERTEX_CHECK(lb < le, i, "sliding vertex " << i << " lies on no labelled boundary part: "
                                                                 "expected a part whose plane it slides in");
    // axis-aligned normals first: Gram-Schmidt then leaves them exact
    std::vector<Boundary_plane<D>> mine;
    for(Index q = lb; q < le; ++q) {
      const int l = net.vertex_labels[q];
      auto it = planes.find(l);
      if(it == planes.end())
        it = planes.emplace(l, fit_boundary_plane(net, l)).first;
      mine.push_back(it->second);
    }
    std::stable_sort(mine.begin(), mine.end(),
                     [](const Boundary_plane<D>& x, const Boundary_plane<D>& y) { return (x.axis >= 0) > (y.axis >= 0); });
    Sliding_vertex<D> s;
    s.vertex = i;
    for(const auto& pl : mine) {
      auto n = pl.normal;
      for(int j = 0; j < s.count; ++j) {
        double d = 0;
        for(int k = 0; k < D; ++k)
          d += n[k] * s.normals[j][k];
        for(int k = 0; k < D; ++k)
          n[k] -= d * s.normals[j][k];
      }
      double l2 = 0;
      for(int k = 0; k < D; ++k)
        l2 += n[k] * n[k];
      if(l2 < 1e-12) // the same plane again (or one the others already imply)
        continue;
      if(s.count == D)
        break;
      const double l = std::sqrt(l2);
      for(int k = 0; k < D; ++k)
        s.normals[s.count][k] = pl.axis >= 0 ? n[k] : n[k] / l;
      s.axes[s.count] = pl.axis;
      ++s.count;
    }
    if(s.count == D) {
      out.pinned.push_back(i);
      continue;
    }
    for(int r = 0; r < D; ++r)
      for(int c = 0; c < D; ++c) {
        double v = r == c ? 1.0 : 0.0;
        for(int j = 0; j < s.count; ++j)
          v -= s.normals[j][r] * s.normals[j][c];
        s.projector[r * D + c] = v;
      }
    out.vertices.push_back(s);
  }
  return out;
}

/// The vertices whose increments a step solves for: those some element uses
/// (`used`) that are free, or sliding and not pinned by their planes. The
/// one rule the deformer's rows, a partition's row numbering and its vertex
/// counts share.
template <int D>
std::vector<char> solved_vertices(const std::vector<char>& used, const std::vector<Vertex_role>& roles,
                                  const Sliding_set<D>& sliding)
{
  std::vector<char> solved(roles.size(), 0);
  for(Index v = 0; v < roles.size(); ++v)
    solved[v] = used[v] && (roles[v] == Vertex_role::free || roles[v] == Vertex_role::sliding);
  for(Index v : sliding.pinned)
    solved[v] = 0;
  return solved;
}

/// Puts x back on the planes through the vertex's initial point x0 (the
/// solve keeps it there only to its tolerance); an axis-aligned plane's
/// coordinate is x0's, bit for bit.
template <int D>
void snap_to_planes(const Sliding_vertex<D>& s, const std::array<double, D>& x0, std::array<double, D>& x)
{
  for(int j = 0; j < s.count; ++j) {
    double d = 0;
    for(int k = 0; k < D; ++k)
      d += s.normals[j][k] * (x[k] - x0[k]);
    for(int k = 0; k < D; ++k)
      x[k] -= d * s.normals[j][k];
  }
  for(int j = 0; j < s.count; ++j)
    if(s.axes[j] >= 0)
      x[s.axes[j]] = x0[s.axes[j]];
}

} // namespace internal
} // namespace spring_motion

#endif
