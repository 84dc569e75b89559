// Copyright (c) 2026 SpringMotion developers.
#ifndef SPRING_MOTION_INTERNAL_GEOMETRY_ELEMENT_POINTS_H
#define SPRING_MOTION_INTERNAL_GEOMETRY_ELEMENT_POINTS_H

#include <array>
#include <cstddef>

namespace spring_motion {
namespace internal {

/// The D + 1 corner points of element t: `elements[t]` indexes `points`.
/// The one way to gather an element's points, for a Spring_network
/// (`element_points<D>(net.elements, x, t)`) and a file's Indexed_mesh alike.
template <int D, class Elements, class Points>
inline std::array<std::array<double, D>, D + 1> element_points(const Elements& elements, const Points& points,
                                                               std::size_t t)
{
  std::array<std::array<double, D>, D + 1> p;
  for(int k = 0; k <= D; ++k)
    p[std::size_t(k)] = points[elements[t][std::size_t(k)]];
  return p;
}

} // namespace internal
} // namespace spring_motion

#endif
