// Copyright (c) 2026 SpringMotion developers.
#ifndef SPRING_MOTION_INTERNAL_GEOMETRY_SLIDING_PLANES_H
#define SPRING_MOTION_INTERNAL_GEOMETRY_SLIDING_PLANES_H

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

/// The plane (2D: the line) of a labelled boundary part: a unit normal, and
/// the axis it is when it is one (then the normal is exactly +-e_axis).
template <int D>
struct Part_plane
{
  std::array<double, D> normal{};
  int axis = -1;
};

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

/// Fits the plane of the vertices carrying `label` and checks that they lie
/// on it: the normal from the point farthest from the centroid and the one
/// spanning the largest triangle with it (exact for a planar part up to
/// rounding, and a planar part is what a symmetry plane is); a normal within
/// 1e-12 of an axis becomes that axis exactly.
template <int D>
Part_plane<D> fit_part_plane(const Spring_network<D>& net, int label)
{
  using Point = std::array<double, D>;
  std::vector<Point> p;
  for(Index i = 0; i < net.number_of_vertices(); ++i)
    for(Index q = net.vertex_label_offsets[i]; q < net.vertex_label_offsets[i + 1]; ++q)
      if(net.vertex_labels[q] == label) {
        p.push_back(net.points[i]);
        break;
      }
  SPRING_MOTION_CHECK(p.size() >= std::size_t(D), "sliding part " << label << " has " << p.size()
                                                                  << " vertices: too few to span a plane");
  Point c{};
  for(const auto& q : p)
    for(int k = 0; k < D; ++k)
      c[k] += q[k] / double(p.size());
  const auto minus = [](const Point& a, const Point& b) {
    Point d;
    for(int k = 0; k < D; ++k)
      d[k] = a[k] - b[k];
    return d;
  };
  const auto dot = [](const Point& a, const Point& b) {
    double s = 0;
    for(int k = 0; k < D; ++k)
      s += a[k] * b[k];
    return s;
  };
  Point a{};
  double extent = 0;
  for(const auto& q : p) {
    const Point d = minus(q, c);
    if(dot(d, d) > extent) {
      extent = dot(d, d);
      a = d;
    }
  }
  extent = std::sqrt(extent);
  SPRING_MOTION_CHECK(extent > 0, "sliding part " << label << " is a single point");
  Part_plane<D> plane;
  if constexpr(D == 2) {
    plane.normal = {-a[1] / extent, a[0] / extent};
  } else {
    const auto cross = [](const Point& u, const Point& v) {
      return Point{u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0]};
    };
    Point best{};
    double largest = 0;
    for(const auto& q : p) {
      const Point n = cross(a, minus(q, c));
      if(dot(n, n) > largest) {
        largest = dot(n, n);
        best = n;
      }
    }
    SPRING_MOTION_CHECK(largest > 1e-24 * extent * extent * extent * extent,
                        "sliding part " << label << " lies on a line: it spans no plane");
    const double l = std::sqrt(largest);
    for(int k = 0; k < D; ++k)
      plane.normal[k] = best[k] / l;
  }
  for(int k = 0; k < D; ++k) {
    bool along = std::abs(std::abs(plane.normal[k]) - 1) < 1e-12;
    for(int j = 0; j < D; ++j)
      along = along && (j == k || std::abs(plane.normal[j]) < 1e-12);
    if(along) {
      plane.normal = Point{};
      plane.normal[k] = 1;
      plane.axis = k;
    }
  }
  double off = 0;
  Index worst = 0;
  for(std::size_t i = 0; i < p.size(); ++i) {
    const double d = std::abs(dot(plane.normal, minus(p[i], c)));
    if(d > off) {
      off = d;
      worst = Index(i);
    }
  }
  if(!(off <= 1e-8 * extent)) {
    std::ostringstream at;
    for(int k = 0; k < D; ++k)
      at << (k ? ", " : "") << p[worst][k];
    SPRING_MOTION_CHECK(false, "sliding part " << label << " is not planar: its vertex at (" << at.str() << ") lies "
                                               << off << " off its plane (part size " << extent
                                               << "): expected a plane" << (D == 2 ? " (a straight line in 2D)" : ""));
  }
  return plane;
}

/// The sliding vertices of `roles` with the planes of the labelled parts
/// each lies on.
template <int D>
Sliding_set<D> sliding_set(const Spring_network<D>& net, const std::vector<Vertex_role>& roles)
{
  Sliding_set<D> out;
  std::map<int, Part_plane<D>> planes;
  for(Index i = 0; i < net.number_of_vertices(); ++i) {
    if(roles[i] != Vertex_role::sliding)
      continue;
    const Index lb = net.vertex_label_offsets[i], le = net.vertex_label_offsets[i + 1];
    SPRING_MOTION_VERTEX_CHECK(lb < le, i, "sliding vertex " << i << " lies on no labelled boundary part: "
                                                                 "expected a part whose plane it slides in");
    // axis-aligned normals first: Gram-Schmidt then leaves them exact
    std::vector<Part_plane<D>> mine;
    for(Index q = lb; q < le; ++q) {
      const int l = net.vertex_labels[q];
      auto it = planes.find(l);
      if(it == planes.end())
        it = planes.emplace(l, fit_part_plane(net, l)).first;
      mine.push_back(it->second);
    }
    std::stable_sort(mine.begin(), mine.end(),
                     [](const Part_plane<D>& x, const Part_plane<D>& y) { return (x.axis >= 0) > (y.axis >= 0); });
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
