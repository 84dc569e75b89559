// Copyright (c) 2026 SpringMotion developers.
#ifndef SPRING_MOTION_INTERNAL_GEOMETRY_EXACT_ORIENTATION_H
#define SPRING_MOTION_INTERNAL_GEOMETRY_EXACT_ORIENTATION_H

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>

#include <array>

namespace spring_motion {
namespace internal {

using Exact_predicates_kernel = CGAL::Exact_predicates_inexact_constructions_kernel;

/// The exact orientation of an element: CGAL's filtered predicate decides the
/// sign of the determinant exactly for the double coordinates given.
inline int exact_orientation(const std::array<std::array<double, 2>, 3>& p)
{
  using P = Exact_predicates_kernel::Point_2;
  return int(CGAL::orientation(P(p[0][0], p[0][1]), P(p[1][0], p[1][1]), P(p[2][0], p[2][1])));
}
inline int exact_orientation(const std::array<std::array<double, 3>, 4>& p)
{
  using P = Exact_predicates_kernel::Point_3;
  return int(CGAL::orientation(P(p[0][0], p[0][1], p[0][2]), P(p[1][0], p[1][1], p[1][2]),
                               P(p[2][0], p[2][1], p[2][2]), P(p[3][0], p[3][1], p[3][2])));
}

} // namespace internal
} // namespace spring_motion

#endif
