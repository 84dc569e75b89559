// Copyright (c) 2026 SpringMotion developers.
#ifndef SPRING_MOTION_STIFFNESS_BLOM_SEMI_TORSIONAL_STIFFNESS_H
#define SPRING_MOTION_STIFFNESS_BLOM_SEMI_TORSIONAL_STIFFNESS_H

#include <spring_motion/internal/geometry/capped_math.h>
#include <spring_motion/stiffness/Stiffness_model.h>

#include <algorithm>

namespace spring_motion {

/// Blom's semi-torsional springs (paper Eq. 3), `k = (1/l) sum_m 1/theta_m`,
/// summed over the elements sharing the edge (our reading of Eq. 3): facing
/// angles in 2D, dihedral angles in 3D.
struct Blom_semi_torsional_stiffness
{
  Angle_kind angle_kind(int) const { return Angle_kind::element; }
  double operator()(double length, const double* angles, std::size_t n, const Stiffness_context&) const
  {
    double s = 0;
    for(std::size_t m = 0; m < n; ++m)
      s += 1.0 / std::max(angles[m], 1e-200);
    return internal::capped_quotient(s, length);
  }
  Model_description description(int) const { return {"blom", {}}; }
};

} // namespace spring_motion

#endif
