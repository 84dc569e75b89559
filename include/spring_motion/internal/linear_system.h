// Copyright (c) 2026 SpringMotion developers.
#ifndef SPRING_MOTION_INTERNAL_LINEAR_SYSTEM_H
#define SPRING_MOTION_INTERNAL_LINEAR_SYSTEM_H

#include <spring_motion/Error.h>
#include <spring_motion/Solver_options.h>
#include <spring_motion/Spring_network.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <vector>

namespace spring_motion {
namespace internal {

/// The spring system of one step on the network's CSR pattern. Scalar
/// systems (edge models) store one weight per adjacency entry and act on the
/// D components independently; block systems (element models) store a D x D
/// block per entry and per diagonal.
template <int D>
struct Linear_system
{
  bool block = false;
  std::vector<double> weight;   // scalar: k_ij per adjacency entry (the matrix entry is -k_ij)
  std::vector<double> diagonal; // scalar: sum_j k_ij per vertex
  std::vector<double> off_blocks;       // block: K_ij, D*D per adjacency entry, row-major
  std::vector<double> diagonal_blocks;  // block: K_ii, D*D per vertex
  std::vector<double> diagonal_inverse; // block: K_ii^{-1}, D*D per vertex
};

template <int D>
inline std::array<double, D * D> invert_block(const double* m)
{
  std::array<double, D * D> r;
  if constexpr(D == 2) {
    const double det = m[0] * m[3] - m[1] * m[2];
    r = {m[3] / det, -m[1] / det, -m[2] / det, m[0] / det};
  } else {
    const double c00 = m[4] * m[8] - m[5] * m[7], c01 = m[5] * m[6] - m[3] * m[8], c02 = m[3] * m[7] - m[4] * m[6];
    const double det = m[0] * c00 + m[1] * c01 + m[2] * c02;
    r = {c00 / det, (m[2] * m[7] - m[1] * m[8]) / det, (m[1] * m[5] - m[2] * m[4]) / det,
         c01 / det, (m[0] * m[8] - m[2] * m[6]) / det, (m[2] * m[3] - m[0] * m[5]) / det,
         c02 / det, (m[1] * m[6] - m[0] * m[7]) / det, (m[0] * m[4] - m[1] * m[3]) / det};
  }
  return r;
}

template <int D>
using Field = std::vector<typename Spring_network<D>::Point>;

/// The value of vertex i that satisfies its own equation (K x)_i = rhs given
/// its neighbours' values: the local solve of Gauss-Seidel.
template <int D>
inline std::array<double, D> local_solve(const Spring_network<D>& net, const Linear_system<D>& sys,
                                         const Field<D>& x, Index i, const typename Spring_network<D>::Point& rhs = {})
{
  std::array<double, D> s = rhs;
  const Index b = net.adjacency_offsets[i], e = net.adjacency_offsets[i + 1];
  if(!sys.block) {
    for(Index p = b; p < e; ++p) {
      const double w = sys.weight[p];
      const auto& xj = x[net.adjacency[p]];
      for(int c = 0; c < D; ++c)
        s[c] += w * xj[c];
    }
    const double inv = 1.0 / sys.diagonal[i];
    for(int c = 0; c < D; ++c)
      s[c] *= inv;
    return s;
  }
  for(Index p = b; p < e; ++p) {
    const double* K = &sys.off_blocks[std::size_t(p) * D * D];
    const auto& xj = x[net.adjacency[p]];
    for(int r = 0; r < D; ++r)
      for(int c = 0; c < D; ++c)
        s[r] -= K[r * D + c] * xj[c];
  }
  const double* Ki = &sys.diagonal_inverse[std::size_t(i) * D * D];
  std::array<double, D> out{};
  for(int r = 0; r < D; ++r)
    for(int c = 0; c < D; ++c)
      out[r] += Ki[r * D + c] * s[c];
  return out;
}

/// (K x)_i
template <int D>
inline std::array<double, D> apply_row(const Spring_network<D>& net, const Linear_system<D>& sys, const Field<D>& x,
                                       Index i)
{
  std::array<double, D> y{};
  const Index b = net.adjacency_offsets[i], e = net.adjacency_offsets[i + 1];
  if(!sys.block) {
    for(int c = 0; c < D; ++c)
      y[c] = sys.diagonal[i] * x[i][c];
    for(Index p = b; p < e; ++p) {
      const double w = sys.weight[p];
      const auto& xj = x[net.adjacency[p]];
      for(int c = 0; c < D; ++c)
        y[c] -= w * xj[c];
    }
    return y;
  }
  const double* Kd = &sys.diagonal_blocks[std::size_t(i) * D * D];
  for(int r = 0; r < D; ++r)
    for(int c = 0; c < D; ++c)
      y[r] += Kd[r * D + c] * x[i][c];
  for(Index p = b; p < e; ++p) {
    const double* K = &sys.off_blocks[std::size_t(p) * D * D];
    const auto& xj = x[net.adjacency[p]];
    for(int r = 0; r < D; ++r)
      for(int c = 0; c < D; ++c)
        y[r] += K[r * D + c] * xj[c];
  }
  return y;
}

/// A max that a NaN sticks to, so a NaN can never pass for convergence.
inline void sticky_max(double& m, double v)
{
  if(!(v <= m))
    m = v;
}

/// max over free vertices and components of |x_i - local_solve(i)|.
template <int D>
double scaled_residual(const Spring_network<D>& net, const Linear_system<D>& sys, const Field<D>& x,
                       const std::vector<Index>& free_vertices)
{
  double r = 0;
  for(Index i : free_vertices) {
    const auto y = local_solve(net, sys, x, i);
    for(int c = 0; c < D; ++c)
      sticky_max(r, std::abs(x[i][c] - y[c]));
  }
  return r;
}

/// Whether a scaled residual (the change one Jacobi update would make) is a
/// rounding error of a solution of size `x_max`: conjugate gradients break
/// down (p.Ap <= 0) only once their recurrence residual is exactly zero, and
/// the recomputed residual of that solution is then at this level.
inline bool residual_at_rounding_level(double residual, double x_max)
{
  return residual <= 64 * std::numeric_limits<double>::epsilon() * x_max;
}

/// The stopping test of both solvers, from the sequence of max changes.
class Stopping_test
{
public:
  /// `worst_ratio`: take q as the largest single-iteration ratio of the
  /// window instead of its geometric mean, for iterations whose changes do not
  /// shrink monotonically (conjugate gradients).
  explicit Stopping_test(const Solver_options& o, bool worst_ratio = false)
      : rule_(o.stopping), tol_(o.tolerance), worst_(worst_ratio), margin_(worst_ratio ? 0.5 : 1.0)
  {
  }

  /// Feeds the max change of one iteration; true when the solve may stop.
  bool done(double update)
  {
    if(count_ > 0)
      ratio_[count_ % window_] = last_ > 0 ? update / last_ : std::numeric_limits<double>::infinity();
    history_[count_++ % window_] = update;
    last_ = update;
    if(update == 0) {
      estimate_ = 0;
      return true;
    }
    if(count_ <= window_) {
      estimate_ = std::numeric_limits<double>::infinity();
    } else {
      // the change `window_` iterations ago sits where this one was just
      // written before overwriting; we keep it in `oldest_`
      const double q = worst_ ? *std::max_element(ratio_.begin(), ratio_.end())
                              : std::pow(update / oldest_, 1.0 / double(window_));
      estimate_ = q < 1 ? update * q / (1 - q) : std::numeric_limits<double>::infinity();
    }
    // Eq. 12 stops on the change alone, but the estimate is still reported:
    // a slowly contracting sweep stops there with an error far above tol
    if(rule_ == Stopping_rule::max_update)
      return update <= tol_;
    // Conjugate gradients stop at half the tolerance: their changes shrink
    // irregularly, and with the multigrid preconditioner (a few iterations,
    // each contracting much) the estimate fell short of the true error by up
    // to 1.3x on the benchmark's systems (spring_motion_bench --omega-table)
    return estimate_ <= margin_ * tol_ && update <= tol_;
  }
  void before_next() { oldest_ = history_[count_ % window_]; }
  double estimate() const { return estimate_; }
  double last() const { return last_; }

private:
  static constexpr std::size_t window_ = 4;
  Stopping_rule rule_;
  double tol_;
  bool worst_;
  double margin_;
  std::array<double, window_> history_{}, ratio_{};
  std::size_t count_ = 0;
  double oldest_ = 0, last_ = 0, estimate_ = std::numeric_limits<double>::infinity();
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
}

/// One SOR sweep in the order of `free_vertices`; returns the largest change.
template <int D>
double sor_sweep(const Spring_network<D>& net, const Linear_system<D>& sys, const std::vector<Index>& free_vertices,
                 Field<D>& x, double omega, int /*threads*/ = 1)
{
  double max_update = 0;
  for(Index i : free_vertices) {
    const auto y = local_solve(net, sys, x, i);
    for(int c = 0; c < D; ++c) {
      const double nv = (1 - omega) * x[i][c] + omega * y[c];
      sticky_max(max_update, std::abs(nv - x[i][c]));
      x[i][c] = nv;
    }
  }
  return max_update;
}

/// Successive over-relaxation in the order of `free_vertices`; the entries
/// of x at constrained vertices are the prescribed increments and stay put.
template <int D>
Solve_report solve_sor(const Spring_network<D>& net, const Linear_system<D>& sys,
                       const std::vector<Index>& free_vertices, Field<D>& x, const Solver_options& options)
{
  check_options(options);
  const double omega = options.relaxation_factor;
  Solve_report report;
  Stopping_test stop(options);
  while(report.iterations < options.max_iterations) {
    stop.before_next();
    const double max_update = sor_sweep(net, sys, free_vertices, x, omega);
    ++report.iterations;
    SPRING_MOTION_CHECK(std::isfinite(max_update),
                        "the solver produced a non-finite value at sweep " << report.iterations);
    if(stop.done(max_update)) {
      report.converged = true;
      break;
    }
  }
  report.last_max_update = stop.last();
  report.error_estimate = stop.estimate();
  report.residual = scaled_residual(net, sys, x, free_vertices);
  SPRING_MOTION_CHECK(std::isfinite(report.residual), "the solver produced a non-finite value");
  return report;
}

/// z = M^{-1} r with M the symmetric Gauss-Seidel splitting of K restricted
/// to the free vertices: a forward then a backward Gauss-Seidel sweep on
/// K z = r from z = 0 (constrained entries of z stay 0).
template <int D>
void symmetric_gauss_seidel(const Spring_network<D>& net, const Linear_system<D>& sys,
                            const std::vector<Index>& free_vertices, const Field<D>& r, Field<D>& z)
{
  for(Index i : free_vertices)
    z[i] = {};
  for(Index i : free_vertices)
    z[i] = local_solve(net, sys, z, i, r[i]);
  for(auto it = free_vertices.rbegin(); it != free_vertices.rend(); ++it)
    z[*it] = local_solve(net, sys, z, *it, r[*it]);
}

/// Preconditioned conjugate gradients on the free vertices, the constrained
/// entries of x being the prescribed increments. The system restricted to
/// the free vertices is symmetric positive definite when each free component
/// reaches a constrained vertex, which the deformer checks beforehand.
template <int D>
Solve_report solve_conjugate_gradient(const Spring_network<D>& net, const Linear_system<D>& sys,
                                      const std::vector<Index>& free_vertices, Field<D>& x,
                                      const Solver_options& options)
{
  check_options(options);
  Solve_report report;
  const std::size_t n = x.size();
  Field<D> r(n, std::array<double, D>{}), z(n, std::array<double, D>{}), p(n, std::array<double, D>{}),
      q(n, std::array<double, D>{});
  auto dot = [&](const Field<D>& a, const Field<D>& b) {
    double s = 0;
    for(Index i : free_vertices)
      for(int c = 0; c < D; ++c)
        s += a[i][c] * b[i][c];
    return s;
  };
  double r_max = 0;
  for(Index i : free_vertices) {
    const auto y = apply_row(net, sys, x, i);
    for(int c = 0; c < D; ++c) {
      r[i][c] = -y[c];
      sticky_max(r_max, std::abs(r[i][c]));
    }
  }
  SPRING_MOTION_CHECK(std::isfinite(r_max), "the solver's initial residual is not finite");
  Stopping_test stop(options);
  if(r_max > 0 && !free_vertices.empty()) {
    symmetric_gauss_seidel(net, sys, free_vertices, r, z);
    for(Index i : free_vertices)
      p[i] = z[i];
    double rz = dot(r, z);
    while(report.iterations < options.max_iterations) {
      stop.before_next();
      for(Index i : free_vertices)
        q[i] = apply_row(net, sys, p, i);
      const double pq = dot(p, q);
      if(!(pq > 0)) // p = 0: the residual vanished exactly
        break;
      const double alpha = rz / pq;
      double update = 0;
      for(Index i : free_vertices)
        for(int c = 0; c < D; ++c) {
          x[i][c] += alpha * p[i][c];
          r[i][c] -= alpha * q[i][c];
          sticky_max(update, std::abs(alpha * p[i][c]));
        }
      ++report.iterations;
      SPRING_MOTION_CHECK(std::isfinite(update),
                          "the solver produced a non-finite value at iteration " << report.iterations);
      if(stop.done(update)) {
        report.converged = true;
        break;
      }
      symmetric_gauss_seidel(net, sys, free_vertices, r, z);
      const double rz_new = dot(r, z);
      const double beta = rz_new / rz;
      rz = rz_new;
      for(Index i : free_vertices)
        for(int c = 0; c < D; ++c)
          p[i][c] = z[i][c] + beta * p[i][c];
    }
  }
  report.residual = scaled_residual(net, sys, x, free_vertices);
  SPRING_MOTION_CHECK(std::isfinite(report.residual), "the solver produced a non-finite value");
  if(!report.converged && report.iterations < options.max_iterations) {
    // stopped on a vanishing recurrence residual, or with nothing to solve
    double x_max = 0;
    for(Index i : free_vertices)
      for(int c = 0; c < D; ++c)
        sticky_max(x_max, std::abs(x[i][c]));
    report.converged = residual_at_rounding_level(report.residual, x_max) || free_vertices.empty() || r_max == 0;
  }
  report.last_max_update = stop.last();
  report.error_estimate = report.converged && report.iterations == 0 ? 0 : stop.estimate();
  return report;
}

/// Solves with the method the options select.
template <int D>
Solve_report solve(const Spring_network<D>& net, const Linear_system<D>& sys, const std::vector<Index>& free_vertices,
                   Field<D>& x, const Solver_options& options)
{
  if(options.method == Solver_method::sor)
    return solve_sor(net, sys, free_vertices, x, options);
  return solve_conjugate_gradient(net, sys, free_vertices, x, options);
}

} // namespace internal
} // namespace spring_motion

#endif
