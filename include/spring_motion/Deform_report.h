// Copyright (c) 2026 SpringMotion developers.
#ifndef SPRING_MOTION_DEFORM_REPORT_H
#define SPRING_MOTION_DEFORM_REPORT_H

#include <spring_motion/Solver_options.h>
#include <spring_motion/motion/Motion_description.h>
#include <spring_motion/skewness.h>
#include <spring_motion/stiffness/Stiffness_model.h>

#include <cstddef>
#include <iosfwd>
#include <limits>
#include <optional>
#include <string>
#include <vector>

namespace spring_motion {

/// One step of a motion (its JSON form: docs/report_format.md).
struct Step_report
{
  std::size_t step = 0;
  double fraction = 0;  ///< t reached, in [0, 1]
  double angle_deg = std::numeric_limits<double>::quiet_NaN(); ///< when the motion has an angle
  // The solver figures describe the accepted attempt (with substeps: its
  // substeps), or for a rejected step its last attempt.
  std::size_t iterations = 0; ///< sweeps, summed over substeps
  bool converged = true;      ///< every solve of the step met the tolerance
  double max_update = 0;      ///< largest last-sweep change over the step's solves
  double residual = 0;        ///< largest scaled residual over the step's solves
  double error_estimate = 0;  ///< largest error estimate over the step's solves
  std::size_t substeps = 1;   ///< equal substeps the step took (1: none; a power of two)
  /// attempts rejected (an inverted element) before the one described; their
  /// time is included in the timings below
  std::size_t rejected_attempts = 0;
  std::size_t inverted = 0;   ///< elements inverted by the rejected attempt (0 if accepted)
  double min_size_ratio = std::numeric_limits<double>::quiet_NaN();
  double max_size_ratio = std::numeric_limits<double>::quiet_NaN();
  double max_skewness_moving = std::numeric_limits<double>::quiet_NaN();
  double max_skewness_all = std::numeric_limits<double>::quiet_NaN();
  /// smallest angle in degrees (2D interior, 3D dihedral) after the step, of
  /// the elements touching a moving vertex and of all elements
  double min_angle_deg_moving = std::numeric_limits<double>::quiet_NaN();
  double min_angle_deg_all = std::numeric_limits<double>::quiet_NaN();
  double seconds_stiffness = 0, seconds_solve = 0, seconds_check = 0;
  /// OpenMP threads of the step's (last) increment: Solver_options::threads,
  /// or with 0 the thread count chosen by measurement
  int threads = 0;
};

/// The step at which the motion stopped: it inverted these elements (indices
/// in the order the mesh traits list the elements), and the mesh was restored
/// to the step before.
struct Invalid_step
{
  std::size_t step = 0;
  double fraction = 0;
  double angle_deg = std::numeric_limits<double>::quiet_NaN();
  std::vector<std::size_t> elements;
};

struct Deform_report
{
  // the run's setting
  int dimension = 2;
  std::size_t vertices = 0, elements = 0, moving_vertices = 0, fixed_vertices = 0, sliding_vertices = 0;
  /// who solved the steps' systems: "shared" (this library, OpenMP) or
  /// "petsc" (the command line's --backend petsc), on how many MPI ranks
  std::string backend = "shared";
  int ranks = 1;
  /// per MPI rank (petsc backend): the seconds its solves took (summed over
  /// the steps, waiting in PETSc's collectives included) and its whole run
  std::vector<double> rank_seconds_solve, rank_seconds_total;
  /// per MPI rank (petsc backend): its peak resident memory in MiB at the
  /// end of the run (rank 0 holds the whole mesh, the others their parts)
  std::vector<double> rank_peak_mib;
  Model_description model;
  Motion_description motion;
  std::size_t number_of_steps = 0;
  Solver_options solver;
  std::size_t max_substep_halvings = 0; ///< Deform_options::max_substep_halvings of the run
  bool quality_every_step = true;       ///< Deform_options::quality_every_step of the run

  std::vector<Step_report> steps; ///< accepted steps, then the rejected one if any
  bool completed = false;         ///< every step valid: the motion reached t = 1
  bool converged = true;          ///< every solve met its tolerance
  std::optional<Invalid_step> first_invalid;
  double final_fraction = 0;      ///< the last t at which the mesh was valid
  double final_angle_deg = std::numeric_limits<double>::quiet_NaN();
  /// R at the final (last valid) state, over the elements touching the moving
  /// boundary and over all elements
  Skewness_histogram quality_moving, quality_all;
  /// R of each element at the final state, by element number: the values of
  /// both histograms (empty in the command line's report of a partitioned
  /// run, whose parts number their elements each their own way)
  std::vector<double> element_skewness;
  /// smallest angle in degrees (2D interior, 3D dihedral) at the final state,
  /// over the same two sets of elements
  double min_angle_deg_moving = std::numeric_limits<double>::quiet_NaN();
  double min_angle_deg_all = std::numeric_limits<double>::quiet_NaN();
  double min_size_ratio = 1;      ///< min over elements of measure / initial measure, final state
  double max_size_ratio = 1;      ///< max over elements of measure / initial measure, final state
  double seconds_total = 0;
};

/// Writes the report as one JSON object in the format "spring_motion.report/1"
/// of docs/report_format.md. Non-finite numbers are written as null.
void write_report_json(const Deform_report& report, std::ostream& out);

/// Writes the JSON report to `path` through a temporary file, renamed on
/// success so a failure leaves no half-written report.
void write_report_json(const Deform_report& report, const std::string& path);

} // namespace spring_motion

#endif
