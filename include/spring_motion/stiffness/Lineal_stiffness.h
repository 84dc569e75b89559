// Copyright (c) 2026 SpringMotion developers.
#ifndef SPRING_MOTION_STIFFNESS_LINEAL_STIFFNESS_H
#define SPRING_MOTION_STIFFNESS_LINEAL_STIFFNESS_H

#include <spring_motion/internal/geometry/capped_math.h>
#include <spring_motion/stiffness/Stiffness_model.h>

#include <cmath>

namespace spring_motion {

/// Batina's lineal springs, `k = 1 / l^p`. The paper's Eq. 1 as printed,
/// `1/(l^2)^alpha` with alpha = 1, is p = 2; Batina's original is p = 1.
struct Lineal_stiffness
{
  double exponent = 1.0; ///< p

  Angle_kind angle_kind(int) const { return Angle_kind::none; }
  double operator()(double length, const double*, std::size_t, const Stiffness_context&) const
  {
    return internal::capped_pow(length, -exponent);
  }
  Model_description description(int) const { return {"lineal", {{"exponent", exponent}}}; }
};

} // namespace spring_motion

#endif
