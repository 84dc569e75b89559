// Copyright (c) 2026 SpringMotion developers.
#ifndef SPRING_MOTION_SOLVER_OPTIONS_H
#define SPRING_MOTION_SOLVER_OPTIONS_H

#include <cstddef>

namespace spring_motion {

/// Options of the increment solver (METHOD.md section 4).
struct Solver_options
{
  /// omega; 1 is Gauss-Seidel. Must lie in (0, 2).
  double relaxation_factor = 1.0;
  /// epsilon of the paper's Eq. 12: the sweep stops when no component of any
  /// free vertex changed by more than this (mesh length units).
  double tolerance = 5e-6;
  /// A solve that reaches this many sweeps stops unconverged and says so.
  std::size_t max_iterations = 100000;
  /// Start from the previous step's increment instead of zero.
  bool warm_start = true;
  /// OpenMP threads for stiffness, checks and quality; 0: OpenMP's default.
  int threads = 0;
};

/// What one linear solve did.
struct Solve_report
{
  std::size_t iterations = 0;
  bool converged = false;
  /// max |delta^{k+1} - delta^k| of the last sweep (the paper's criterion)
  double last_max_update = 0;
  /// max over free vertices and components of the Jacobi-scaled residual
  /// |(K_ii)^{-1} (K delta)_i|, in length units: the change one more exact
  /// local solve would make. Small max-updates with a large residual mean
  /// the sweep stalled rather than converged.
  double residual = 0;
};

} // namespace spring_motion

#endif
