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
inline int filtered_orientation(const std::array<std::array<double, 3>, 4>& p)
{
  constexpr double u = 0x1p-53;
  const double ux = p[1][0] - p[0][0], uy = p[1][1] - p[0][1], uz = p[1][2] - p[0][2];
  const double vx = p[2][0] - p[0][0], vy = p[2][1] - p[0][1], vz = p[2][2] - p[0][2];
  const double wx = p[3][0] - p[0][0], wy = p[3][1] - p[0][1], wz = p[3][2] - p[0][2];
  const double mx = std::max(std::abs(ux), std::max(std::abs(vx), std::abs(wx)));
  const double my = std::max(std::abs(uy), std::max(std::abs(vy), std::abs(wy)));
  const double mz = std::max(std::abs(uz), std::max(std::abs(vz), std::abs(wz)));
  // quiet comparisons: a NaN raises no exception
  if(!std::islessequal(std::max(mx, std::max(my, mz)), 0x1p+300))
    return 0;
  const double a1 = vy * wz, a2 = vz * wy, b1 = vz * wx, b2 = vx * wz, c1 = vx * wy, c2 = vy * wx;
  const double det = ux * (a1 - a2) + uy * (b1 - b2) + uz * (c1 - c2);
  // first the sum of absolute values bounded by 6 mx my mz (one bound for
  // all, cheap: it decides well-shaped elements), then the sum itself
  const double coarse = 43 * u * mx * my * mz + 0x1p-760;
  if(det > coarse)
    return 1;
  if(det < -coarse)
    return -1;
  constexpr double bound = (7 + 56 * u) * u;
  const double sum = std::abs(ux) * (std::abs(a1) + std::abs(a2)) + std::abs(uy) * (std::abs(b1) + std::abs(b2)) +
                     std::abs(uz) * (std::abs(c1) + std::abs(c2));
  const double err = bound * sum + 0x1p-760;
  return det > err ? 1 : det < -err ? -1 : 0;
}

/// The first stage of filtered_orientation() on two tetrahedra at once, one
/// per lane of a register (double_pair.h): the same operations in the same
/// order, so each lane's sign, +1 or -1, is the one filtered_orientation()
/// returns; 0 where that stage cannot decide (then ask exact_orientation()).
inline std::array<int, 2> coarse_orientations(const std::array<const double*, 4>& a,
                                              const std::array<const double*, 4>& b)
{
#if SPRING_MOTION_HAS_DOUBLE_PAIR
  constexpr double u = 0x1p-53;
  const auto at = [&](int k, int j) { return Double_pair{a[std::size_t(k)][j], b[std::size_t(k)][j]}; };
  const auto largest = [](Double_pair x, Double_pair y) { return x < y ? y : x; }; // std::max's choice
  const Double_pair x0 = at(0, 0), y0 = at(0, 1), z0 = at(0, 2);
  const Double_pair ux = at(1, 0) - x0, uy = at(1, 1) - y0, uz = at(1, 2) - z0;
  const Double_pair vx = at(2, 0) - x0, vy = at(2, 1) - y0, vz = at(2, 2) - z0;
  const Double_pair wx = at(3, 0) - x0, wy = at(3, 1) - y0, wz = at(3, 2) - z0;
  const Double_pair mx = largest(lane_abs(ux), largest(lane_abs(vx), lane_abs(wx)));
  const Double_pair my = largest(lane_abs(uy), largest(lane_abs(vy), lane_abs(wy)));
  const Double_pair mz = largest(lane_abs(uz), largest(lane_abs(vz), lane_abs(wz)));
  // out of range or NaN in either lane: both go to the scalar filter, which
  // does not form the products that could overflow
  const Double_pair_mask in_range = largest(mx, largest(my, mz)) <= 0x1p+300;
  if(!(in_range[0] && in_range[1]))
    return {0, 0};
  const Double_pair a1 = vy * wz, a2 = vz * wy, b1 = vz * wx, b2 = vx * wz, c1 = vx * wy, c2 = vy * wx;
  const Double_pair det = ux * (a1 - a2) + uy * (b1 - b2) + uz * (c1 - c2);
  const Double_pair coarse = 43 * u * mx * my * mz + 0x1p-760;
  const Double_pair_mask positive = det > coarse, negative = det < -coarse;
  return {positive[0] ? 1 : negative[0] ? -1 : 0, positive[1] ? 1 : negative[1] ? -1 : 0};
#else
  (void)a;
  (void)b;
  return {0, 0};
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
