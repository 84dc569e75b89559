// Copyright (c) 2026 SpringMotion developers.
#ifndef SPRING_MOTION_INTERNAL_GEOMETRY_EXACT_ORIENTATION_H
#define SPRING_MOTION_INTERNAL_GEOMETRY_EXACT_ORIENTATION_H

#include <spring_motion/internal/geometry/double_pair.h>

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>

#include <algorithm>
#include <array>
#include <cmath>

namespace spring_motion {
namespace internal {

using Exact_predicates_kernel = CGAL::Exact_predicates_inexact_constructions_kernel;

/// The sign of the orientation determinant when a floating-point evaluation
/// proves it, 0 when it cannot decide. The bounds are Shewchuk's first-stage
/// bounds ("Adaptive precision floating-point arithmetic and fast robust
/// geometric predicates", 1997) for this evaluation order: differences to
/// the first point, then 2 x 2 minors, then their combination; the error of
/// the whole evaluation is at most bound * (the same sum of absolute values)
/// when nothing underflows. With every difference at most 2^300 in magnitude
/// nothing overflows, and the products that underflow add at most 2^-770 in
/// all: 2^-760 covers them. In 3D the sum is at most 6 mx my mz (mx: the
/// largest |x difference|, ...), so 43u mx my mz bounds the error too
/// (6 (7 + 56u) u and the roundings of both bounds stay below 43u): tried
/// first, it spares most elements the sum's twelve operations. A fused
/// multiply-add (a compiler may contract a product and a sum) only leaves
/// out roundings the bound allows for. NaN and infinite coordinates fail
/// the size test: CGAL's predicate decides them.
inline int filtered_orientation(const std::array<std::array<double, 2>, 3>& p)
{
  constexpr double u = 0x1p-53;
  constexpr double bound = (3 + 16 * u) * u;
  const double ux = p[1][0] - p[0][0], uy = p[1][1] - p[0][1];
  const double vx = p[2][0] - p[0][0], vy = p[2][1] - p[0][1];
  if(!std::islessequal(std::abs(ux) + std::abs(uy) + std::abs(vx) + std::abs(vy), 0x1p+300))
    return 0;
  const double left = ux * vy, right = uy * vx;
  const double det = left - right;
  const double sum = std::abs(left) + std::abs(right);
  const double err = bound * sum + 0x1p-760;
  return det > err ? 1 : det < -err ? -1 : 0;
}

/// The 3D filter's first stage, written once over the lane type T
/// (double_pair.h; at(k, j): coordinate j of corner k in each lane): the
/// differences to the first corner, the products of the 2 x 2 minors, the
/// determinant, and the bound 43u mx my mz on its error. `in_range` is
/// false when some lane has a difference above 2^300 or a NaN: then nothing
/// past that test is computed (no product overflows), and the lanes are left
/// undecided.
template <class T>
struct Orientation_first_stage
{
  bool in_range;
  T ux, uy, uz, a1, a2, b1, b2, c1, c2, det, coarse;
};

inline bool every_lane_at_most(double v, double bound)
{
  return std::islessequal(v, bound); // quiet: a NaN raises no exception
}
#if SPRING_MOTION_HAS_DOUBLE_PAIR
inline bool every_lane_at_most(Double_pair v, double bound)
{
  const Double_pair_mask m = v <= bound;
  return m[0] && m[1];
}
#endif

template <class T, class At>
inline Orientation_first_stage<T> orientation_first_stage(const At& at)
{
  constexpr double u = 0x1p-53;
  Orientation_first_stage<T> s{};
  const auto largest = [](T x, T y) { return x < y ? y : x; }; // std::max's choice
  const T x0 = at(0, 0), y0 = at(0, 1), z0 = at(0, 2);
  s.ux = at(1, 0) - x0, s.uy = at(1, 1) - y0, s.uz = at(1, 2) - z0;
  const T vx = at(2, 0) - x0, vy = at(2, 1) - y0, vz = at(2, 2) - z0;
  const T wx = at(3, 0) - x0, wy = at(3, 1) - y0, wz = at(3, 2) - z0;
  const T mx = largest(lane_abs(s.ux), largest(lane_abs(vx), lane_abs(wx)));
  const T my = largest(lane_abs(s.uy), largest(lane_abs(vy), lane_abs(wy)));
  const T mz = largest(lane_abs(s.uz), largest(lane_abs(vz), lane_abs(wz)));
  s.in_range = every_lane_at_most(largest(mx, largest(my, mz)), 0x1p+300);
  if(!s.in_range)
    return s;
  s.a1 = vy * wz, s.a2 = vz * wy, s.b1 = vz * wx, s.b2 = vx * wz, s.c1 = vx * wy, s.c2 = vy * wx;
  s.det = s.ux * (s.a1 - s.a2) + s.uy * (s.b1 - s.b2) + s.uz * (s.c1 - s.c2);
  // the sum of absolute values bounded by 6 mx my mz: one bound for all,
  // cheap, it decides well-shaped elements
  s.coarse = 43 * u * mx * my * mz + 0x1p-760;
  return s;
}

inline int filtered_orientation(const std::array<std::array<double, 3>, 4>& p)
{
  constexpr double u = 0x1p-53;
  const auto s = orientation_first_stage<double>([&](int k, int j) { return p[std::size_t(k)][std::size_t(j)]; });
  if(!s.in_range)
    return 0;
  if(s.det > s.coarse)
    return 1;
  if(s.det < -s.coarse)
    return -1;
  // then the sum itself
  constexpr double bound = (7 + 56 * u) * u;
  const double sum = std::abs(s.ux) * (std::abs(s.a1) + std::abs(s.a2)) +
                     std::abs(s.uy) * (std::abs(s.b1) + std::abs(s.b2)) +
                     std::abs(s.uz) * (std::abs(s.c1) + std::abs(s.c2));
  const double err = bound * sum + 0x1p-760;
  return s.det > err ? 1 : s.det < -err ? -1 : 0;
}

/// The first stage of filtered_orientation() on two tetrahedra at once, one
/// per lane of a register (double_pair.h): each lane's sign, +1 or -1, is the
/// one filtered_orientation() returns; 0 where that stage cannot decide (then
/// ask exact_orientation()), for both when either has a difference above
/// 2^300 or a NaN.
inline std::array<int, 2> coarse_orientations(const std::array<const double*, 4>& a,
                                              const std::array<const double*, 4>& b)
{
#if SPRING_MOTION_HAS_DOUBLE_PAIR
  const auto s = orientation_first_stage<Double_pair>(
      [&](int k, int j) { return Double_pair{a[std::size_t(k)][j], b[std::size_t(k)][j]}; });
  if(!s.in_range)
    return {0, 0};
  const Double_pair_mask positive = s.det > s.coarse, negative = s.det < -s.coarse;
  return {positive[0] ? 1 : negative[0] ? -1 : 0, positive[1] ? 1 : negative[1] ? -1 : 0};
#else
  std::array<int, 2> r{};
  for(std::size_t t = 0; t < 2; ++t) {
    const auto& q = t == 0 ? a : b;
    const auto s = orientation_first_stage<double>([&](int k, int j) { return q[std::size_t(k)][j]; });
    if(s.in_range)
      r[t] = s.det > s.coarse ? 1 : s.det < -s.coarse ? -1 : 0;
  }
  return r;
#endif
}

/// CGAL's filtered predicate: the sign of the determinant exactly for the
/// double coordinates given.
inline int cgal_orientation(const std::array<std::array<double, 2>, 3>& p)
{
  using P = Exact_predicates_kernel::Point_2;
  return int(CGAL::orientation(P(p[0][0], p[0][1]), P(p[1][0], p[1][1]), P(p[2][0], p[2][1])));
}
inline int cgal_orientation(const std::array<std::array<double, 3>, 4>& p)
{
  using P = Exact_predicates_kernel::Point_3;
  return int(CGAL::orientation(P(p[0][0], p[0][1], p[0][2]), P(p[1][0], p[1][1], p[1][2]),
                               P(p[2][0], p[2][1], p[2][2]), P(p[3][0], p[3][1], p[3][2])));
}

/// CGAL's predicate out of line: inlined into a loop over elements, its
/// code crowded the filter's registers (the check of a regular 100^3 box
/// took a quarter longer).
#if defined(__GNUC__)
[[gnu::noinline, gnu::cold]]
#endif
inline int rarely_cgal_orientation(const std::array<std::array<double, 2>, 3>& p)
{
  return cgal_orientation(p);
}
#if defined(__GNUC__)
[[gnu::noinline, gnu::cold]]
#endif
inline int rarely_cgal_orientation(const std::array<std::array<double, 3>, 4>& p)
{
  return cgal_orientation(p);
}

/// The exact orientation of an element (+1, -1, or 0 when flat): the
/// floating-point filter decides almost every element of a mesh at a
/// fraction of the cost of CGAL's predicate, which decides the rest.
inline int exact_orientation(const std::array<std::array<double, 2>, 3>& p)
{
  const int s = filtered_orientation(p);
  return s != 0 ? s : rarely_cgal_orientation(p);
}
inline int exact_orientation(const std::array<std::array<double, 3>, 4>& p)
{
  const int s = filtered_orientation(p);
  return s != 0 ? s : rarely_cgal_orientation(p);
}

} // namespace internal
} // namespace spring_motion

#endif
