// Copyright (c) 2026 SpringMotion developers.
#ifndef SPRING_MOTION_INTERNAL_GEOMETRY_ANGLES_H
#define SPRING_MOTION_INTERNAL_GEOMETRY_ANGLES_H

#include <spring_motion/internal/geometry/simplex_tables.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

namespace spring_motion {
namespace internal {

/// pi (M_PI is not standard C++).
constexpr double pi = 3.141592653589793238462643383279502884;

template <int N>
inline std::array<double, N> sub(const std::array<double, N>& a, const std::array<double, N>& b)
{
  std::array<double, N> r;
  for(int c = 0; c < N; ++c)
    r[c] = a[c] - b[c];
  return r;
}
template <int N>
inline double dot(const std::array<double, N>& a, const std::array<double, N>& b)
{
  double s = 0;
  for(int c = 0; c < N; ++c)
    s += a[c] * b[c];
  return s;
}
inline std::array<double, 3> cross(const std::array<double, 3>& a, const std::array<double, 3>& b)
{
  return {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
}
template <int N>
inline double norm(const std::array<double, N>& a)
{
  return std::sqrt(dot<N>(a, a));
}

/// |a - b|. The plain sqrt of the sum of squares whenever that sum is a
/// normal number (so results stay bitwise what they always were); when it
/// underflows (edges below ~1e-154) the difference is rescaled by its largest
/// component first, so a tiny but non-zero edge never gets length 0 and a
/// 1/l in a stiffness model never divides by zero.
template <int N>
inline double distance(const std::array<double, N>& a, const std::array<double, N>& b)
{
  double l2 = 0;
  for(int c = 0; c < N; ++c)
    l2 += (a[c] - b[c]) * (a[c] - b[c]);
  if(l2 >= std::numeric_limits<double>::min())
    return std::sqrt(l2);
  double big = 0;
  for(int c = 0; c < N; ++c)
    big = std::max(big, std::abs(a[c] - b[c]));
  if(big == 0)
    return 0;
  double s = 0;
  for(int c = 0; c < N; ++c)
    s += ((a[c] - b[c]) / big) * ((a[c] - b[c]) / big);
  return big * std::sqrt(s);
}

/// The angle between two vectors, in [0, pi]. atan2 of |u x v| and u.v stays
/// accurate near 0 and pi, where acos of a normalised dot product does not.
inline double angle_between(const std::array<double, 2>& u, const std::array<double, 2>& v)
{
  return std::atan2(std::abs(u[0] * v[1] - u[1] * v[0]), u[0] * v[0] + u[1] * v[1]);
}
inline double angle_between(const std::array<double, 3>& u, const std::array<double, 3>& v)
{
  return std::atan2(norm<3>(cross(u, v)), dot<3>(u, v));
}

/// Interior angles of triangle (p0, p1, p2) at each vertex; angle k faces the
/// triangle's local edge k (Simplex_tables<2>).
template <int N>
inline std::array<double, 3> triangle_angles(const std::array<double, N>& p0, const std::array<double, N>& p1,
                                             const std::array<double, N>& p2)
{
  const double a0 = angle_between(sub<N>(p1, p0), sub<N>(p2, p0));
  const double a1 = angle_between(sub<N>(p0, p1), sub<N>(p2, p1));
  return {a0, a1, angle_between(sub<N>(p0, p2), sub<N>(p1, p2))};
}

/// Interior dihedral angles of tetrahedron p at its six edges, in the local
/// edge order of Simplex_tables<3>: the angle between the projections of the
/// two other vertices onto the plane orthogonal to the edge.
inline std::array<double, 6> dihedral_angles(const std::array<std::array<double, 3>, 4>& p)
{
  using T = Simplex_tables<3>;
  std::array<double, 6> out;
  for(int k = 0; k < 6; ++k) {
    const auto& a = p[T::edge[k][0]];
    const auto e = sub<3>(p[T::edge[k][1]], a);
    const double ee = dot<3>(e, e);
    auto u = sub<3>(p[T::other[k][0]], a);
    auto w = sub<3>(p[T::other[k][1]], a);
    const double su = dot<3>(u, e) / ee, sw = dot<3>(w, e) / ee;
    for(int c = 0; c < 3; ++c) {
      u[c] -= su * e[c];
      w[c] -= sw * e[c];
    }
    out[k] = angle_between(u, w);
  }
  return out;
}

/// Signed area (2D) or volume (3D) of a simplex, positive when the vertices
/// are counter-clockwise / positively oriented.
inline double signed_measure(const std::array<std::array<double, 2>, 3>& p)
{
  return 0.5 * ((p[1][0] - p[0][0]) * (p[2][1] - p[0][1]) - (p[1][1] - p[0][1]) * (p[2][0] - p[0][0]));
}
inline double signed_measure(const std::array<std::array<double, 3>, 4>& p)
{
  return dot<3>(sub<3>(p[1], p[0]), cross(sub<3>(p[2], p[0]), sub<3>(p[3], p[0]))) / 6.0;
}

} // namespace internal
} // namespace spring_motion

#endif
