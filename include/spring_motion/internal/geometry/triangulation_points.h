// Copyright (c) 2026 SpringMotion developers.
#ifndef SPRING_MOTION_INTERNAL_GEOMETRY_TRIANGULATION_POINTS_H
#define SPRING_MOTION_INTERNAL_GEOMETRY_TRIANGULATION_POINTS_H

#include <CGAL/number_utils.h>

#include <array>
#include <type_traits>

namespace spring_motion {
namespace internal {

/// The bare point of a D-dimensional triangulation vertex and how to replace
/// it keeping the rest: a regular triangulation (Mesh_3's, or a
/// Regular_triangulation_2) stores weighted points, and a moved vertex keeps
/// its weight.
template <class Tr, int D>
struct Triangulation_points
{
  static_assert(D == 2 || D == 3, "Triangulation_points: dimension 2 or 3");
  using Point = typename Tr::Point;
  using Gt = typename Tr::Geom_traits;
  using Bare_point = std::conditional_t<D == 2, typename Gt::Point_2, typename Gt::Point_3>;
  static constexpr bool weighted = !std::is_same_v<Point, Bare_point>;

  static const Bare_point& bare(const Point& p)
  {
    if constexpr(weighted)
      return p.point();
    else
      return p;
  }

  static std::array<double, D> get(const Point& p)
  {
    const Bare_point& q = bare(p);
    if constexpr(D == 2)
      return {CGAL::to_double(q.x()), CGAL::to_double(q.y())};
    else
      return {CGAL::to_double(q.x()), CGAL::to_double(q.y()), CGAL::to_double(q.z())};
  }

  static Point moved(const Point& old, const std::array<double, D>& p)
  {
    Bare_point q;
    if constexpr(D == 2)
      q = Bare_point(p[0], p[1]);
    else
      q = Bare_point(p[0], p[1], p[2]);
    if constexpr(weighted)
      return Point(q, old.weight());
    else
      return q;
  }
};

} // namespace internal
} // namespace spring_motion

#endif
