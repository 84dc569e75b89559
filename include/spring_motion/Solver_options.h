// Copyright (c) 2026 SpringMotion developers.
#ifndef SPRING_MOTION_SOLVER_OPTIONS_H
#define SPRING_MOTION_SOLVER_OPTIONS_H

#include <cstddef>

namespace spring_motion {

/// How each step's increment is solved. Both methods have the same fixed
/// point: the spring equilibrium of docs/method.md ("Spring network").
enum class Solver_method
{
  /// conjugate gradients with the preconditioner of
  /// `Solver_options::preconditioner` (a multigrid cycle by default): the
  /// default, many times fewer sweeps than SOR on graded meshes
  conjugate_gradient,
  /// successive over-relaxation, the paper's solver (omega = 1: Gauss-Seidel)
  sor
};

/// What preconditions conjugate gradients, for scalar (edge-model) and block
/// (element-model) systems alike.
enum class Preconditioner
{
  /// a symmetric Gauss-Seidel (SSOR) sweep in the solver's vertex ordering
  symmetric_gauss_seidel,
  /// one multigrid V-cycle: a symmetric Gauss-Seidel sweep on the mesh, the
  /// coarse levels by aggregation of strongly coupled vertices (the
  /// aggregates chosen from the first system the solver state is built for,
  /// their springs or D x D blocks summed every step),
  /// the coarsest solved directly. The default: several times fewer
  /// iterations on graded meshes, where single-level sweeps converge slowly.
  multigrid
};

/// The order in which Gauss-Seidel visits the free vertices (SOR sweeps and
/// the conjugate-gradient preconditioner), for scalar and block systems.
enum class Vertex_ordering
{
  /// colour by colour (no two neighbours share a colour), reverse
  /// Cuthill-McKee within a colour: runs in parallel within each colour and
  /// gives bitwise the same result for any thread count.
  multicolour,
  /// the network's vertex order, one thread (the paper's SOR sweep)
  natural,
  /// blocks of consecutive reverse Cuthill-McKee rows as wide as the ordering's
  /// bandwidth, the blocks coloured (two colours, typically): Gauss-Seidel in
  /// RCM order inside a block, the blocks of a colour in parallel. Locality
  /// and convergence of the natural order, and bitwise the same result for
  /// any thread count. The default.
  block_multicolour
};

/// When a solve stops.
enum class Stopping_rule
{
  /// when the estimated error of the iterate is at most half the tolerance
  /// (and the last change at most the tolerance): the last change u_k times
  /// q / (1 - q), q the largest ratio of successive changes over the last
  /// four iterations, or the same tail counted by pairs of iterations if
  /// smaller; before five iterations, with margins 8 times stricter, from
  /// the ratios so far. The default; docs/method.md ("Solver") says why.
  error_estimate,
  /// the paper's Eq. 12: when no component changed by more than the
  /// tolerance in the last iteration. This is not the error: a slowly
  /// converging sweep stops with an error far above the tolerance.
  max_update
};

/// Options of the increment solver (docs/method.md, "Solver").
struct Solver_options
{
  Solver_method method = Solver_method::conjugate_gradient;
  Stopping_rule stopping = Stopping_rule::error_estimate;
  /// omega of SOR; 1 is Gauss-Seidel. Must lie in (0, 2). The default is the
  /// measured best on the NACA0012 meshes (docs/performance.md: 14x fewer
  /// sweeps than Gauss-Seidel on the coarse mesh, 20x on the fine one).
  double relaxation_factor = 1.9;
  /// omega of the symmetric SOR sweep that preconditions conjugate gradients,
  /// alone or as the multigrid smoother (1: Gauss-Seidel). Must lie in (0, 2).
  double preconditioner_relaxation_factor = 1.0;
  Preconditioner preconditioner = Preconditioner::multigrid;
  /// epsilon, in mesh length units (see `stopping`)
  double tolerance = 1e-6;
  /// A solve that reaches this many iterations stops unconverged and says so.
  std::size_t max_iterations = 100000;
  /// Start from the previous step's increment instead of zero.
  bool warm_start = true;
  /// With `warm_start`: start from the extrapolation of the last increments
  /// (per unit of motion fraction) instead of the last one: the parabola
  /// through the last three, the line through two at the third step. The
  /// fixed point is the same; the start is closer by two orders of the step.
  bool extrapolate = true;
  /// Gauss-Seidel order.
  Vertex_ordering ordering = Vertex_ordering::block_multicolour;
  /// Rows per block of the `block_multicolour` ordering; 0: the bandwidth of
  /// the reverse Cuthill-McKee ordering of the free vertices, at least 256
  /// (then a block touches only the blocks before and after it: two colours).
  std::size_t block_rows = 0;
  /// Multigrid strength of connection: vertex j is a strong neighbour of i
  /// when |K_ij| >= multigrid_strength sqrt(|K_ii| |K_jj|) (Frobenius norms of
  /// the D x D blocks for element models); aggregates group strong
  /// neighbours. 0.02-0.04 took the fewest iterations on the two NACA0012
  /// meshes (spring_motion_bench --omega-table).
  double multigrid_strength = 0.04;
  /// The coarse correction of the V-cycle is scaled by this factor, in
  /// (0, 2): over-correction makes up for the too-high energy of piecewise
  /// constant coarse functions (measured like the strength).
  double multigrid_correction = 1.3;
  /// A multigrid level with at most this many vertices is the coarsest.
  std::size_t multigrid_coarsest_rows = 64;
  /// The coarsest level is solved by dense Cholesky when it has at most this
  /// many vertices (coarsening can stall above it: then a symmetric
  /// Gauss-Seidel sweep smooths it instead).
  std::size_t multigrid_max_direct_rows = 256;
  /// Block systems (element models): their multigrid's coarse levels (the
  /// Galerkin products of every level and the coarsest factorisation) are
  /// recomputed at the first solve and then at every this-many-th solve,
  /// and kept in between; 1: at every solve. Must be at least 1. The fine
  /// level always reads the current system, and a kept coarse level is still
  /// symmetric positive definite, so conjugate gradients converge to the same
  /// solution; only the preconditioner is a little further from the current
  /// matrix; the iterations stay about the same (docs/performance.md, "Coarse
  /// levels kept"). Scalar systems recompute theirs at every solve: their
  /// sums of spring weights cost little.
  std::size_t multigrid_coarse_interval = 4;
  /// Block systems (element models): V-cycles per preconditioner application
  /// on the multigrid's first coarse level, each on the residual the ones
  /// before left, weighted as in Chebyshev iteration on an interval of the
  /// level's spectrum estimated when the aggregates are chosen (a symmetric
  /// polynomial in one cycle, positive for an odd count, so conjugate
  /// gradients still see a symmetric positive definite preconditioner;
  /// docs/method.md, "Solver"). The first coarse level carries the
  /// aggregates' rigid motions, and one cycle leaves most of its error
  /// there; more cycles save iterations, each of which then costs more
  /// (docs/performance.md, "The first coarse level solved more closely").
  /// 0: by dimension, 3 in 3D and 1 in 2D, where three cycles cost the 2D
  /// paper mesh's `ball_vertex_p2` steps more time than they saved
  /// iterations. Scalar systems take one cycle.
  std::size_t multigrid_first_level_cycles = 0;
  /// OpenMP threads for stiffness, solve, checks and quality. 0: step by
  /// step OpenMP's default team or one thread, whichever measures cheaper
  /// (on a machine whose cores other processes use, the team's barriers wait
  /// for descheduled threads; Network_deformer tries both, and the other
  /// again every 8-64 steps); the final quality pass uses OpenMP's default,
  /// as do the checks of Network_deformer's constructor (omp_set_num_threads
  /// caps those; `spring-motion deform --threads T` does so for the whole
  /// run). The result does not depend on it: every parallel loop gives the
  /// same numbers for any thread count.
  int threads = 0;

  /// The paper's solver exactly: SOR (Gauss-Seidel) stopped by Eq. 12 with
  /// epsilon = 5e-6.
  static Solver_options paper()
  {
    Solver_options o;
    o.method = Solver_method::sor;
    o.stopping = Stopping_rule::max_update;
    o.tolerance = 5e-6;
    o.relaxation_factor = 1.0; // Gauss-Seidel
    o.extrapolate = false;     // the paper starts from the previous increment
    return o;
  }
};

/// What one linear solve did.
struct Solve_report
{
  std::size_t iterations = 0;
  bool converged = false;
  /// max |delta^{k+1} - delta^k| of the last iteration (the paper's criterion)
  double last_max_update = 0;
  /// the error estimate of the last iteration (infinite while the iteration
  /// is not yet contracting)
  double error_estimate = 0;
  /// max over free vertices and components of the Jacobi-scaled residual
  /// |(K_ii)^{-1} (K delta)_i|, in length units: the change one more exact
  /// local solve would make.
  double residual = 0;
};

} // namespace spring_motion

#endif
