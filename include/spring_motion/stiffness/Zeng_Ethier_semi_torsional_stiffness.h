// Copyright (c) 2026 SpringMotion developers.
#ifndef SPRING_MOTION_STIFFNESS_ZENG_ETHIER_SEMI_TORSIONAL_STIFFNESS_H
#define SPRING_MOTION_STIFFNESS_ZENG_ETHIER_SEMI_TORSIONAL_STIFFNESS_H

#include <spring_motion/internal/geometry/capped_math.h>
#include <spring_motion/stiffness/Stiffness_model.h>

namespace spring_motion {

/// Zeng and Ethier's semi-torsional springs (paper Eq. 4),
/// `k = 1/l + sum_m 1/sin^2(theta_m)`. In 3D Zeng and Ethier take the angles
/// facing the edge in the triangular faces that contain it (`Angle_kind::face`,
/// the default); `Angle_kind::element` uses the dihedral angles instead.
struct Zeng_Ethier_semi_torsional_stiffness
{
  Angle_kind angles_3d = Angle_kind::face;

  Angle_kind angle_kind(int dimension) const { return dimension == 2 ? Angle_kind::element : angles_3d; }
  double operator()(double length, const double* angles, std::size_t n, const Stiffness_context&) const
  {
    double s = internal::capped_quotient(1.0, length);
    for(std::size_t m = 0; m < n; ++m)
      s += internal::inverse_sin_squared(angles[m]);
    return internal::cap_stiffness(s);
  }
  double operator()(double length, Inverse_sin_squared angles, const Stiffness_context&) const
  {
    return internal::cap_stiffness(angles.sum(internal::capped_quotient(1.0, length)));
  }
  Model_description description(int) const
  {
    return {"zeng_ethier", {{"dihedral_angles_3d", angles_3d == Angle_kind::element ? 1.0 : 0.0}}};
  }
};

} // namespace spring_motion

#endif
