// Copyright (c) 2026 SpringMotion developers.
#ifndef SPRING_MOTION_INTERNAL_SOLVER_WARM_START_H
#define SPRING_MOTION_INTERNAL_SOLVER_WARM_START_H

#include <array>
#include <cstddef>

namespace spring_motion {
namespace internal {

/// How a step's solve starts from the last accepted increments d_j (newest
/// first): the start is sum_{j < used} weight[j] d_j.
struct Warm_start_weights
{
  std::array<double, 3> weight{};
  std::size_t used = 0;
};

/// The weights of the warm start of a step of motion fraction h with
/// midpoint m, from the last `count` accepted increments over fractions
/// h_j with midpoints m_j (newest first). The increments per unit of
/// fraction, d_j / h_j at m_j, are extrapolated to m by the parabola
/// through the last three (the line through two when only two are known)
/// and scaled by h: on a smooth motion the parabola is off by O(h^3) per
/// unit of fraction where the line is off by O(h^2), and the start's error
/// is what the solve removes. With one increment, midpoints that do not
/// increase, or `extrapolate` false, the last increment as it is.
inline Warm_start_weights warm_start_weights(double h, double m, const std::array<double, 3>& hj,
                                             const std::array<double, 3>& mj, std::size_t count, bool extrapolate)
{
  Warm_start_weights w;
  if(count == 0)
    return w;
  const double m1 = mj[0], m2 = mj[1], m3 = mj[2];
  if(extrapolate && count >= 3 && m1 > m2 && m2 > m3) {
    w.weight = {h * ((m - m2) * (m - m3)) / ((m1 - m2) * (m1 - m3)) / hj[0],
                h * ((m - m1) * (m - m3)) / ((m2 - m1) * (m2 - m3)) / hj[1],
                h * ((m - m1) * (m - m2)) / ((m3 - m1) * (m3 - m2)) / hj[2]};
    w.used = 3;
  } else if(extrapolate && count >= 2 && m1 > m2) {
    const double e = (m - m1) / (m1 - m2);
    w.weight = {h * (1 + e) / hj[0], -(h * e / hj[1]), 0};
    w.used = 2;
  } else {
    w.weight = {1, 0, 0};
    w.used = 1;
  }
  return w;
}

} // namespace internal
} // namespace spring_motion

#endif
