// Copyright (c) 2026 SpringMotion developers.
#ifndef SPRING_MOTION_INTERNAL_LINEAR_SYSTEM_H
#define SPRING_MOTION_INTERNAL_LINEAR_SYSTEM_H

#include <spring_motion/Error.h>
#include <spring_motion/Solver_options.h>
#include <spring_motion/Spring_network.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <vector>

namespace spring_motion {
namespace internal {

/// The spring system of one step on the network's CSR pattern. Scalar
/// systems (edge models) store one weight per adjacency entry and solve the
/// D components independently; block systems (element models) store a D x D
/// block per entry and per diagonal.
template <int D>
struct Linear_system
{
  bool block = false;
  std::vector<double> weight;   // scalar: k_ij per adjacency entry
  std::vector<double> diagonal; // scalar: sum_j k_ij per vertex
  std::vector<double> off_blocks;       // block: D*D per adjacency entry, row-major
  std::vector<double> diagonal_blocks;  // block: D*D per vertex
  std::vector<double> diagonal_inverse; // block: D*D per vertex
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

/// The new value of free vertex i from its neighbours (the exact local solve).
template <int D>
inline std::array<double, D> local_solve(const Spring_network<D>& net, const Linear_system<D>& sys,
                                         const std::vector<typename Spring_network<D>::Point>& x, Index i)
{
  std::array<double, D> s{};
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

/// max over free vertices and components of |x_i - local_solve(i)|.
template <int D>
double scaled_residual(const Spring_network<D>& net, const Linear_system<D>& sys,
                       const std::vector<typename Spring_network<D>::Point>& x, const std::vector<Index>& free_vertices)
{
  double r = 0;
  for(Index i : free_vertices) {
    const auto y = local_solve(net, sys, x, i);
    for(int c = 0; c < D; ++c) {
      const double d = std::abs(x[i][c] - y[c]);
      if(!(d <= r))
        r = d;
    }
  }
  return r;
}

/// Successive over-relaxation in the order of `free_vertices`; the entries
/// of x at constrained vertices are the prescribed increments and stay put.
template <int D>
Solve_report solve_sor(const Spring_network<D>& net, const Linear_system<D>& sys,
                       const std::vector<Index>& free_vertices, std::vector<typename Spring_network<D>::Point>& x,
                       const Solver_options& options)
{
  SPRING_MOTION_CHECK(options.relaxation_factor > 0 && options.relaxation_factor < 2,
                      "SOR relaxation factor must lie in (0, 2), got " << options.relaxation_factor);
  SPRING_MOTION_CHECK(options.tolerance > 0, "solver tolerance must be positive, got " << options.tolerance);
  const double omega = options.relaxation_factor;
  Solve_report report;
  while(report.iterations < options.max_iterations) {
    double max_update = 0;
    for(Index i : free_vertices) {
      const auto y = local_solve(net, sys, x, i);
      for(int c = 0; c < D; ++c) {
        const double nv = (1 - omega) * x[i][c] + omega * y[c];
        const double change = std::abs(nv - x[i][c]);
        if(!(change <= max_update)) // NaN-sticky max: a NaN must never pass for convergence
          max_update = change;
        x[i][c] = nv;
      }
    }
    ++report.iterations;
    SPRING_MOTION_CHECK(std::isfinite(max_update),
                        "the solver produced a non-finite value at sweep " << report.iterations);
    report.last_max_update = max_update;
    if(max_update <= options.tolerance) {
      report.converged = true;
      break;
    }
  }
  report.residual = scaled_residual(net, sys, x, free_vertices);
  SPRING_MOTION_CHECK(std::isfinite(report.residual), "the solver produced a non-finite value");
  return report;
}

} // namespace internal
} // namespace spring_motion

#endif
