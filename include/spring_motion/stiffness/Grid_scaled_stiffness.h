// Copyright (c) 2026 SpringMotion developers.
#ifndef SPRING_MOTION_STIFFNESS_GRID_SCALED_STIFFNESS_H
#define SPRING_MOTION_STIFFNESS_GRID_SCALED_STIFFNESS_H

#include <spring_motion/internal/geometry/capped_math.h>
#include <spring_motion/stiffness/Stiffness_model.h>

#include <cmath>
#include <optional>

namespace spring_motion {

namespace internal {

/// The grid-scaled stiffness of an edge from its length and the sum of 1/sin^2
/// of its angles, with the exponents' tests made when constructed: the
/// model's formula, kept by the assembly for all the edges of a step.
class Grid_scaled_terms
{
public:
  Grid_scaled_terms(double alpha, double beta, double reference_length, double longest_initial_edge)
      : length_power_(-alpha), angle_power_(beta), reference_length_(reference_length), l0_(longest_initial_edge)
  {}

  double operator()(double length, double s) const
  {
    const double l = length / reference_length_;
    const double lambda = capped_quotient(l0_, length);
    return capped_product(lambda, length_power_(l) + angle_power_(s));
  }

private:
  Capped_power length_power_, angle_power_;
  double reference_length_, l0_;
};

} // namespace internal

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
    return internal::Grid_scaled_terms(alpha_for(ctx.dimension), beta_for(ctx.dimension), reference_length,
                                       ctx.longest_initial_edge)(length, s);
  }
};

namespace internal {

template <>
struct Edge_function<Grid_scaled_stiffness>
{
  Edge_function(const Grid_scaled_stiffness& m, const Stiffness_context& ctx)
      : model(m), context(ctx),
        terms(m.alpha_for(ctx.dimension), m.beta_for(ctx.dimension), m.reference_length, ctx.longest_initial_edge)
  {}
  double operator()(double length, const double* angles, std::size_t n) const
  {
    return model(length, angles, n, context);
  }
  double operator()(double length, Inverse_sin_squared angles) const { return terms(length, angles.sum()); }

  const Grid_scaled_stiffness& model;
  const Stiffness_context context;
  const Grid_scaled_terms terms;
};

} // namespace internal

} // namespace spring_motion

#endif
