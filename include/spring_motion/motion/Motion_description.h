// Copyright (c) 2026 SpringMotion developers.
#ifndef SPRING_MOTION_MOTION_MOTION_DESCRIPTION_H
#define SPRING_MOTION_MOTION_MOTION_DESCRIPTION_H

#include <array>
#include <cmath>
#include <limits>
#include <string>
#include <type_traits>
#include <utility>

namespace spring_motion {

/// \name Concept `Motion`
/// \code
/// // the prescribed position of a moving vertex at motion fraction t in [0, 1]
/// std::array<double, D> operator()(const std::array<double, D>& p0, double t) const;
/// double angle_deg(double t) const;              // optional: reported per step
/// Motion_description description() const;       // optional: for reports
/// \endcode
/// Positions, not increments: the motion is evaluated from the initial point
/// at every step, so rounding never accumulates.

/// What a motion is, for reports (docs/report_format.md).
struct Motion_description
{
  std::string kind = "custom";
  double amplitude_deg = std::numeric_limits<double>::quiet_NaN();
  double mean_angle_deg = 0;
  std::array<double, 3> center{0, 0, 0};
  std::array<double, 3> axis{0, 0, 1};
  std::array<double, 3> displacement{0, 0, 0};
};

namespace internal {
template <class M, class = void>
struct Has_angle : std::false_type {};
template <class M>
struct Has_angle<M, std::void_t<decltype(std::declval<const M&>().angle_deg(0.0))>> : std::true_type {};
template <class M, class = void>
struct Has_motion_description : std::false_type {};
template <class M>
struct Has_motion_description<M, std::void_t<decltype(std::declval<const M&>().description())>> : std::true_type {};

template <class M>
double motion_angle_deg(const M& m, double t)
{
  if constexpr(Has_angle<M>::value)
    return m.angle_deg(t);
  else
    return std::numeric_limits<double>::quiet_NaN();
}
template <class M>
Motion_description describe_motion(const M& m)
{
  if constexpr(Has_motion_description<M>::value)
    return m.description();
  else
    return Motion_description{};
}
} // namespace internal
} // namespace spring_motion

#endif
