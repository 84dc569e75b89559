// Copyright (c) 2026 SpringMotion developers.
#ifndef SPRING_MOTION_INTERNAL_SOLVER_STOPPING_TEST_H
#define SPRING_MOTION_INTERNAL_SOLVER_STOPPING_TEST_H

#include <spring_motion/Error.h>
#include <spring_motion/Solver_options.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

namespace spring_motion {
namespace internal {

/// Whether a scaled residual (the change one Jacobi update would make) is a
/// rounding error of a solution of size `x_max`: conjugate gradients break
/// down (p.Ap <= 0) only once their recurrence residual is exactly zero, and
/// the recomputed residual of that solution is then at this level.
inline bool residual_at_rounding_level(double residual, double x_max)
{
  return residual <= 64 * std::numeric_limits<double>::epsilon() * x_max;
}

/// The one stopping test of every solve (SOR and conjugate gradients,
/// scalar and block systems), fed the max change of each iteration.
///
/// Rule `error_estimate`: with u_k the largest change of iteration k and q
/// the LARGEST ratio u_j / u_{j-1} over the last `window` iterations, the
/// error of the iterate is estimated as u_k q / (1 - q) (the tail of a
/// geometric series contracting by q), infinite while q >= 1 or fewer than
/// window + 1 iterations have run; the solve stops when that estimate is at
/// most tolerance / 2 and u_k is at most the tolerance.
///
/// Why the worst ratio and half the tolerance: the estimate is only as good
/// as q. The geometric mean of the window's ratios (the former rule of the
/// whole-network solvers) averages a slow iteration with fast ones and so
/// underestimates the error whenever the changes do not shrink monotonically,
/// which is the rule for conjugate gradients; the largest ratio bounds the
/// contraction the tail can still show. Even so, with the multigrid
/// preconditioner (a few iterations, each contracting much) the estimate fell
/// short of the true error by up to 1.3x on the benchmark's systems
/// (spring_motion_bench compares with a direct solve), hence the margin of 2.
/// For SOR, whose changes shrink steadily, the worst ratio is close to the
/// mean and the margin costs a few sweeps.
///
/// The same tail counted by pairs of iterations: conjugate gradients'
/// changes often alternate, a change larger than the one before after a
/// much smaller one, while every two iterations together shrink steadily.
/// One such ratio above 1 keeps the estimate infinite for `window` more
/// iterations, and again at the next one: such solves ran several iterations
/// after their changes had shrunk far below the tolerance. With s_k = u_k +
/// u_{k-1} and Q the largest of the last `window` pair ratios s_j / s_{j-2}
/// and of the last ratio u_k / u_{k-1}, the tail s_{k+2} + s_{k+4} + ... is
/// estimated as s_k Q / (1 - Q), infinite before window + 3 iterations; the
/// estimate is the smaller of the two. The last ratio is in Q because a pair
/// ratio averages a slow latest iteration with the fast one before it, the
/// very underestimate the worst ratio avoids; with changes shrinking by a
/// steady q the pair estimate is u_k (1 + q) / (1 - q), above the single one.
/// Why `window` pair ratios (seven changes), not two over the single
/// window's five: with two, a stagnating solve (pairs shrinking fast, then
/// several changes of one size) stopped early: in a trial build the 2D
/// `grid_scaled+ball_vertex` run left errors above the tolerance against a
/// direct solve (spring_motion_bench --cases naca_coarse --every-step-error).
///
/// Before the window is full (the 3rd and 4th changes) the estimate is the
/// same tail from the largest of the ratios so far, and a solve stops early
/// when that estimate is at most tolerance / 16, its latest change at most
/// tolerance / 8 and every change smaller than the one before. Without it
/// every solve of conjugate gradients ran at least window + 1 iterations,
/// and a warm start is often within the tolerance already: most steps of
/// the wing's grid-scaled run took five iterations and ended far below the
/// tolerance against a direct solve. The margins, 8 times stricter than the
/// full window's, stand in for the ratios not yet seen: after a latest change
/// of tolerance / 8, even a next change 3 times larger (conjugate gradients'
/// changes can alternate) and a tail halving from there add only 3/4 of the
/// tolerance. SOR, whose ratios are close to 1, never stops early.
///
/// Rule `max_update` (the paper's Eq. 12): stop when u_k <= tolerance; the
/// estimate is still computed and reported.
class Stopping_test
{
public:
  static constexpr std::size_t window = 4;
  static constexpr double margin = 0.5;
  // changes the pair estimate reads: `window` pair ratios
  static constexpr std::size_t changes = window + 3;
  // the early stop (see the class comment): from this many changes, with
  // these fractions of the tolerance for the estimate and the latest change
  static constexpr std::size_t early_changes = 3;
  static constexpr double early_margin = 1.0 / 16, early_change = 1.0 / 8;
  static_assert(changes > window, "the single estimate reads window + 1 changes");

  explicit Stopping_test(const Solver_options& o) : rule_(o.stopping), tol_(o.tolerance) {}

  /// Feeds the max change of one iteration; true when the solve may stop.
  bool done(double update)
  {
    change_[count_ % changes] = update;
    ++count_;
    if(update == 0) {
      estimate_ = 0;
      return true;
    }
    if(count_ <= window) { // the early stop, from the ratios so far
      estimate_ = count_ >= early_changes ? tail(count_ - 1) : infinity;
      if(rule_ == Stopping_rule::max_update)
        return update <= tol_;
      return estimate_ <= early_margin * tol_ && update <= early_change * tol_;
    }
    estimate_ = std::min(tail(window), pair_estimate());
    if(rule_ == Stopping_rule::max_update)
      return update <= tol_;
    return estimate_ <= margin * tol_ && update <= tol_;
  }
  double estimate() const { return estimate_; }
  double last() const { return count_ > 0 ? change(0) : 0.0; }

private:
  static constexpr double infinity = std::numeric_limits<double>::infinity();

  // u_{k-back}, with k the latest iteration (back < changes)
  double change(std::size_t back) const { return change_[(count_ - 1 - back) % changes]; }

  // u_{k-back} / u_{k-back-1}
  double ratio(std::size_t back) const
  {
    return change(back + 1) > 0 ? change(back) / change(back + 1) : infinity;
  }

  // The tail by single iterations, u_k q / (1 - q), q the largest of the
  // last n ratios (n < count_).
  double tail(std::size_t n) const
  {
    double q = ratio(0);
    for(std::size_t i = 1; i < n; ++i)
      q = std::max(q, ratio(i));
    return q < 1 ? change(0) * q / (1 - q) : infinity;
  }

  // The tail counted by pairs of iterations (see the class comment). Every
  // change fed is positive: a zero change ends the solve.
  double pair_estimate() const
  {
    if(count_ < changes)
      return infinity;
    double q = ratio(0);
    for(std::size_t i = 0; i < window; ++i)
      q = std::max(q, (change(i) + change(i + 1)) / (change(i + 2) + change(i + 3)));
    return q < 1 ? (change(0) + change(1)) * q / (1 - q) : infinity;
  }

  Stopping_rule rule_;
  double tol_;
  // the last `changes` changes fed, a ring
  std::array<double, changes> change_{};
  std::size_t count_ = 0;
  double estimate_ = infinity;
};

inline void check_options(const Solver_options& o)
{
  SPRING_MOTION_CHECK(o.relaxation_factor > 0 && o.relaxation_factor < 2,
                      "SOR relaxation factor must lie in (0, 2), got " << o.relaxation_factor);
  SPRING_MOTION_CHECK(o.preconditioner_relaxation_factor > 0 && o.preconditioner_relaxation_factor < 2,
                      "preconditioner relaxation factor must lie in (0, 2), got "
                          << o.preconditioner_relaxation_factor);
  SPRING_MOTION_CHECK(o.tolerance > 0 && std::isfinite(o.tolerance),
                      "solver tolerance must be positive and finite, got " << o.tolerance);
  SPRING_MOTION_CHECK(o.multigrid_strength >= 0 && std::isfinite(o.multigrid_strength),
                      "multigrid strength must be finite and >= 0, got " << o.multigrid_strength);
  SPRING_MOTION_CHECK(o.multigrid_correction > 0 && o.multigrid_correction < 2,
                      "multigrid correction factor must lie in (0, 2), got " << o.multigrid_correction);
  SPRING_MOTION_CHECK(o.multigrid_coarse_interval >= 1,
                      "multigrid coarse interval must be at least 1 (solves), got " << o.multigrid_coarse_interval);
}

} // namespace internal
} // namespace spring_motion

#endif
