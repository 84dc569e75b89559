// Copyright (c) 2026 SpringMotion developers.
#ifndef SPRING_MOTION_DEFORM_OPTIONS_H
#define SPRING_MOTION_DEFORM_OPTIONS_H

#include <spring_motion/Deform_report.h>
#include <spring_motion/Solver_options.h>

#include <cstddef>

namespace spring_motion {

/// Options of a motion run (docs/method.md, "Time stepping and substepping").
struct Deform_options
{
  /// n: the motion is applied in this many increments
  std::size_t number_of_steps = 100;
  Solver_options solver;
  /// Adaptive substepping: a step that inverts an element is retried from
  /// the last valid state as 2, 4, ... 2^k equal substeps (stiffness
  /// recomputed at each) up to k = max_substep_halvings. 0 is the paper's
  /// method: the run stops at the first invalid step.
  std::size_t max_substep_halvings = 0;
  /// Compute R and size ratios after every step (for the step reports); the
  /// final state's quality is computed in any case.
  bool quality_every_step = true;
};

/// Progress callbacks with no-op defaults; derive and override what you need.
struct Default_deform_visitor
{
  void on_start(const Deform_report&) {}
  void on_step(const Step_report&) {}
};

} // namespace spring_motion

#endif
