// Copyright (c) 2026 SpringMotion developers.
#ifndef SPRING_MOTION_STIFFNESS_GRID_SCALED_STIFFNESS_H
#define SPRING_MOTION_STIFFNESS_GRID_SCALED_STIFFNESS_H

#include <spring_motion/internal/geometry/capped_math.h>
#include <spring_motion/stiffness/Stiffness_model.h>

#include <cmath>
#include <optional>

namespace spring_motion {

/// The paper's grid-scaled springs (Eq. 5-6):
/// `k = lambda (1/l^alpha + (sum_m 1/sin^2 theta_m)^beta)`, `lambda = l0 / l`,
/// with facing angles in 2D and dihedral angles in 3D.
///
/// `l0` is the longest edge of the initial mesh, so lambda >= 1; being one
/// constant for the whole mesh it does not change the motion. Eq. 5 is not
/// unit-invariant (`1/l^alpha` scales with the length unit, the angle term
/// does not): lengths are divided by `reference_length`, so a mesh in
/// millimetres with reference_length = 1000 moves like the same mesh in metres.
struct Grid_scaled_stiffness
{
  /// The paper's exponents: alpha = 2, beta = 4 in 2D; alpha = 1, beta = 3 in 3D.
  static constexpr double paper_alpha(int dimension) { return dimension == 2 ? 2.0 : 1.0; }
  static constexpr double paper_beta(int dimension) { return dimension == 2 ? 4.0 : 3.0; }

  std::optional<double> alpha; ///< unset: paper_alpha(D); any value, 0 included, is used as given
  std::optional<double> beta;  ///< unset: paper_beta(D)
  double reference_length = 1; ///< L_ref

  double alpha_for(int dimension) const { return alpha.value_or(paper_alpha(dimension)); }
  double beta_for(int dimension) const { return beta.value_or(paper_beta(dimension)); }

  Angle_kind angle_kind(int) const { return Angle_kind::element; }
  double operator()(double length, const double* angles, std::size_t n, const Stiffness_context& ctx) const
  {
    double s = 0;
    for(std::size_t m = 0; m < n; ++m)
      s += internal::inverse_sin_squared(angles[m]);
    return from_angle_sum(length, s, ctx);
  }
  double operator()(double length, Inverse_sin_squared angles, const Stiffness_context& ctx) const
  {
    return from_angle_sum(length, angles.sum(), ctx);
  }
  Model_description description(int dimension) const
  {
    return {"grid_scaled", {{"alpha", alpha_for(dimension)}, {"beta", beta_for(dimension)}, {"reference_length", reference_length}}};
  }

private:
  // s = sum_m 1/sin^2 theta_m
  double from_angle_sum(double length, double s, const Stiffness_context& ctx) const
  {
    const double l = length / reference_length;
    const double lambda = internal::capped_quotient(ctx.longest_initial_edge, length);
    return internal::capped_product(lambda, internal::capped_pow(l, -alpha_for(ctx.dimension)) +
                                                internal::capped_pow(s, beta_for(ctx.dimension)));
  }
};

} // namespace spring_motion

#endif
