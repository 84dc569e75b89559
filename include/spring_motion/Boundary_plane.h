// Copyright (c) 2026 SpringMotion developers.
#ifndef SPRING_MOTION_BOUNDARY_PLANE_H
#define SPRING_MOTION_BOUNDARY_PLANE_H

#include <spring_motion/Error.h>
#include <spring_motion/Spring_network.h>
#include <spring_motion/Vertex_role.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <sstream>
#include <vector>

namespace spring_motion {

/// The plane (2D: the line) of a labelled boundary part, in which its
/// sliding vertices move: a unit normal, and the coordinate axis it is when
/// it is one (then the normal is exactly e_axis, and a sliding vertex keeps
/// that coordinate bit for bit). Each sliding vertex moves in the plane with
/// this normal through its own initial point.
template <int D>
struct Boundary_plane
{
  int label = 0;
  std::array<double, D> normal{};
  int axis = -1;
};

namespace internal {

// A normal within 1e-12 of an axis becomes that axis exactly.
template <int D>
void snap_normal_to_axis(Boundary_plane<D>& plane)
{
  for(int k = 0; k < D; ++k) {
    bool along = std::abs(std::abs(plane.normal[k]) - 1) < 1e-12;
    for(int j = 0; j < D; ++j)
      along = along && (j == k || std::abs(plane.normal[j]) < 1e-12);
    if(along) {
      plane.normal = std::array<double, D>{};
      plane.normal[k] = 1;
      plane.axis = k;
    }
  }
}

} // namespace internal

/// Fits the plane of the vertices of `net` carrying `label` and checks that
/// they lie on it: the normal from the point farthest from the centroid and
/// the one spanning the largest triangle with it (exact for a planar part up
/// to rounding, and a planar part is what a symmetry plane is); a normal
/// within 1e-12 of an axis becomes that axis exactly. Throws `Error` when the
/// part has too few vertices, lies on a line (3D) or is not planar (off by
/// more than 1e-8 of its size).
template <int D>
Boundary_plane<D> fit_boundary_plane(const Spring_network<D>& net, int label)
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
  Boundary_plane<D> plane;
  plane.label = label;
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
  internal::snap_normal_to_axis(plane);
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


/// A plane given by its normal (any length but zero), checked and made unit;
/// a normal within 1e-12 of an axis becomes that axis exactly.
template <int D>
Boundary_plane<D> boundary_plane(int label, const std::array<double, D>& normal)
{
  double l2 = 0;
  for(double c : normal)
    l2 += c * c;
  SPRING_MOTION_CHECK(std::isfinite(l2) && l2 > 0,
                      "the plane of part " << label << " needs a finite non-zero normal");
  Boundary_plane<D> plane;
  plane.label = label;
  for(int k = 0; k < D; ++k)
    plane.normal[k] = normal[k] / std::sqrt(l2);
  internal::snap_normal_to_axis(plane);
  return plane;
}

/// The fitted planes (`fit_boundary_plane`) of every labelled part that a
/// sliding vertex of `roles` lies on, by increasing label. A
/// `Network_deformer` on a part of `net` takes them (a part may hold too few
/// of a plane's vertices to fit it; a partitioned run fits on the whole mesh).
template <int D>
std::vector<Boundary_plane<D>> sliding_planes(const Spring_network<D>& net, const std::vector<Vertex_role>& roles)
{
  SPRING_MOTION_CHECK(roles.size() == net.number_of_vertices(),
                      "got " << roles.size() << " vertex roles for " << net.number_of_vertices() << " vertices");
  std::vector<int> labels;
  for(Index i = 0; i < net.number_of_vertices(); ++i)
    if(roles[i] == Vertex_role::sliding)
      for(Index q = net.vertex_label_offsets[i]; q < net.vertex_label_offsets[i + 1]; ++q)
        labels.push_back(net.vertex_labels[q]);
  std::sort(labels.begin(), labels.end());
  labels.erase(std::unique(labels.begin(), labels.end()), labels.end());
  std::vector<Boundary_plane<D>> planes;
  for(int l : labels)
    planes.push_back(fit_boundary_plane(net, l));
  return planes;
}

} // namespace spring_motion

#endif
