// Copyright (c) 2026 SpringMotion developers.
#ifndef SPRING_MOTION_NETWORK_DEFORMER_H
#define SPRING_MOTION_NETWORK_DEFORMER_H

#include <spring_motion/Boundary_plane.h>
#include <spring_motion/Deform_options.h>
#include <spring_motion/Deform_report.h>
#include <spring_motion/Error.h>
#include <spring_motion/Solver_options.h>
#include <spring_motion/Spring_network.h>
#include <spring_motion/Step_system_view.h>
#include <spring_motion/Vertex_role.h>
#include <spring_motion/internal/geometry/angles.h>
#include <spring_motion/internal/geometry/sliding_planes.h>
#include <spring_motion/internal/solver/assemble.h>
#include <spring_motion/internal/solver/free_system.h>
#include <spring_motion/internal/solver/thread_chooser.h>
#include <spring_motion/internal/solver/threads.h>
#include <spring_motion/internal/solver/traversal_check.h>
#include <spring_motion/internal/solver/warm_start.h>
#include <spring_motion/motion/Motion_description.h>
#include <spring_motion/skewness.h>
#include <spring_motion/validity.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstddef>
#include <functional>
#include <limits>
#include <tuple>
#include <utility>
#include <vector>

namespace spring_motion {

/// A spring network with vertex roles and the current positions: the
/// stateful side of `deform()`, for a flow solver that moves its mesh step
/// by step. Construction checks the roles: at least one moving vertex, and
/// every free vertex connected through free vertices to a constrained one
/// (otherwise the system is singular).
/// Where the checks of the vertex roles are made: on the network given
/// (`here`), or by the caller on the whole mesh, of which the network is one
/// part (`by_caller`): a part of a partitioned mesh may have no moving vertex,
/// and its free vertices may reach a constrained one only through other parts.
enum class Role_checks { here, by_caller };

/// Checks the roles of a whole mesh as `Network_deformer` does: at least one
/// moving vertex, and every free vertex connected through free vertices to a
/// constrained one (otherwise the system is singular). Throws `Error`.
template <int D>
void check_vertex_roles(const Spring_network<D>& net, const std::vector<Vertex_role>& roles)
{
  const std::size_t n = net.number_of_vertices();
  SPRING_MOTION_CHECK(roles.size() == n, "got " << roles.size() << " vertex roles for " << n << " vertices");
  const std::vector<char> used = used_vertices(net);
  bool moving = false;
  for(Index i = 0; i < n && !moving; ++i)
    moving = used[i] && roles[i] == Vertex_role::moving;
  SPRING_MOTION_CHECK(moving, "no vertex is moving: the set of moving vertices is empty");
  const std::vector<Index> unreached = undetermined_vertices(net, roles);
  SPRING_MOTION_VERTEX_CHECK(unreached.empty(), unreached.empty() ? 0 : unreached.front(),
                             unreached.size() << " free vertices (for instance vertex "
                                              << (unreached.empty() ? 0 : unreached.front())
                                              << ") are connected to no constrained vertex: "
                                                 "their displacement is undetermined (singular system)");
}

template <int D>
class Network_deformer
{
public:
  using Point = std::array<double, D>;

  /// `mesh_checks`: whether the input mesh is checked here or has been by
  /// the caller (`record_orientations`).
  Network_deformer(Spring_network<D> network, std::vector<Vertex_role> roles, Role_checks checks = Role_checks::here,
                   Mesh_checks mesh_checks = Mesh_checks::here)
      : Network_deformer(std::move(network), std::move(roles), {}, checks, mesh_checks)
  {
  }

  /// With the planes of (some of) the parts the sliding vertices lie on
  /// given, instead of fitted on `network`: a symmetry plane known exactly,
  /// or a part of a partitioned mesh, whose planes are fitted on the whole
  /// mesh (`sliding_planes`). The parts whose planes are not given are
  /// fitted on `network`. With planes given every model runs as a block
  /// system, as it does with sliding vertices.
  Network_deformer(Spring_network<D> network, std::vector<Vertex_role> roles, std::vector<Boundary_plane<D>> planes,
                   Role_checks checks = Role_checks::here, Mesh_checks mesh_checks = Mesh_checks::here)
      : net_(std::move(network)), roles_(std::move(roles))
  {
    const std::size_t n = net_.number_of_vertices();
    SPRING_MOTION_CHECK(roles_.size() == n, "got " << roles_.size() << " vertex roles for " << n << " vertices");
    positions_ = net_.points;
    record_ = record_orientations(net_, positions_, mesh_checks);
    const std::vector<char> used = used_vertices(net_);
    sliding_ = internal::sliding_set(net_, roles_, planes);
    planes_given_ = !planes.empty();
    const std::vector<char> solved = internal::solved_vertices(used, roles_, sliding_);
    is_free_.assign(n, 0);
    for(Index i = 0; i < n; ++i) {
      if(!used[i])
        continue; // a vertex no element uses takes no part
      if(solved[i]) {
        free_.push_back(i);
        is_free_[i] = 1;
      } else
        (roles_[i] == Vertex_role::moving ? moving_ : fixed_).push_back(i);
    }
    for(const auto& sv : sliding_.vertices)
      if(used[sv.vertex]) {
        sliding_vertices_.push_back(sv.vertex);
        sliding_projectors_.push_back(sv.projector);
      }
    if(checks == Role_checks::here)
      check_vertex_roles(net_, roles_);
    // a product with a normal power of two rounds as ldexp does, at a
    // fraction of its cost; exponents whose power is not normal keep ldexp
    const double longest = net_.longest_initial_edge;
    measure_exponent_ = longest > 0 && std::isfinite(longest) ? -std::ilogb(longest) : 0;
    measure_scale_ = std::abs(measure_exponent_) <= 1000 ? std::ldexp(1.0, measure_exponent_) : 0.0;
    // each element's initial measure and whether it touches a moving
    // vertex, in the elements' spatial traversal, where the per-step
    // quality reads them (touches_moving() is worked out where asked)
    const internal::Angle_slots& slots = internal::angle_slots(net_);
    const std::size_t m = slots.ordered_elements.size() / (D + 1);
    initial_measure_.resize(m);
    traversal_moving_.assign(m, 0);
    for(std::size_t i = 0; i < m; ++i) {
      initial_measure_[i] = scaled_measure(traversal_points(positions_, i));
      for(int k = 0; k <= D; ++k)
        if(roles_[slots.traversal_vertices[slots.ordered_elements[i * (D + 1) + std::size_t(k)]]] ==
           Vertex_role::moving)
          traversal_moving_[i] = 1;
    }
    for(auto& v : increments_)
      v.assign(n, Point{});
  }

  const Spring_network<D>& network() const { return net_; }
  const std::vector<Vertex_role>& roles() const { return roles_; }
  /// The current positions, one per network vertex. The vector keeps its
  /// storage for the deformer's lifetime (steps, rollbacks and reset() copy
  /// into it), so a pointer to its data stays valid.
  const std::vector<Point>& positions() const { return positions_; }
  const Orientation_record& orientation_record() const { return record_; }
  /// elements with at least one moving vertex
  bool touches_moving(std::size_t element) const
  {
    for(Index v : net_.elements[element])
      if(roles_[v] == Vertex_role::moving)
        return true;
    return false;
  }
  std::size_t number_of_moving_vertices() const { return moving_.size(); }
  /// fixed vertices, sliding ones whose planes pin them included
  std::size_t number_of_fixed_vertices() const { return fixed_.size(); }
  /// vertices that slide in the planes of their parts
  std::size_t number_of_sliding_vertices() const { return sliding_vertices_.size(); }
  double fraction() const { return t_; }

  /// Called, when set, with each step's linear system just before it is
  /// solved (rows in the solver's order, right-hand side, initial iterate):
  /// for benchmarks and diagnostics that re-solve the very same systems.
  std::function<void(const Step_system_view<D>&)> system_observer;

  /// When set, solves each step's linear system instead of the built-in
  /// solver: given the system (as system_observer sees it), it writes the
  /// solution, one entry per row in the view's order, and reports. The step
  /// goes on as with the built-in solve (exact check, rollback, substeps).
  /// The PETSc backend of the command line is such a solve (docs/scaling.md).
  std::function<Solve_report(const Step_system_view<D>&, std::vector<Point>& solution)> solve_override;

  /// When set, a step is accepted only if this returns true, given whether
  /// the step inverted none of this network's elements. For a network that is
  /// one part of a partitioned mesh: the parts agree (an MPI all-reduce), so
  /// that all reject, roll back and substep together.
  std::function<bool(bool)> agree_on_validity;

  /// The moving vertices, in the order `move()` takes their displacements.
  const std::vector<Index>& moving_vertices() const { return moving_; }

  /// Back to the initial positions at t = 0, as after construction (the
  /// warm-start history is cleared; the solver state is kept and rebuilt
  /// only if a later run needs other options).
  void reset()
  {
    std::copy(net_.points.begin(), net_.points.end(), positions_.begin());
    for(auto& v : increments_)
      v.assign(net_.number_of_vertices(), Point{});
    history_ = History{};
    t_ = 0;
    moves_ = 0;
    last_inverted_.clear();
  }

  /// Frees what only steps use (stiffness, angle scratch, the solver state
  /// and the attempts' scratch), about half of a deformer's memory, for a
  /// caller done stepping that writes its results next (the command line,
  /// before its files). Positions, roles and the warm-start history stay; a
  /// later step rebuilds the rest, its multigrid aggregates then chosen from
  /// its own system (so its result is within the solver's tolerance of a
  /// step without the release, not bitwise equal).
  void release_step_memory()
  {
    std::vector<double>().swap(stiffness_);
    stiffness_scratch_.release();
    std::vector<signed char>().swap(traversal_sign_);
    solver_ = internal::Free_system<D>();
    for(std::vector<Point>* v : {&delta_, &candidate_, &moving_targets_, &outside_solution_})
      std::vector<Point>().swap(*v);
  }

  /// Runs the whole motion from the current state (t = 0 for a new deformer).
  template <class Motion, class Model, class Visitor = Default_deform_visitor>
  Deform_report run(const Motion& motion, const Model& model, const Deform_options& options = {},
                    Visitor visitor = {})
  {
    const auto start = Clock::now();
    SPRING_MOTION_CHECK(options.number_of_steps > 0, "number_of_steps must be positive");
    Deform_report rep;
    rep.dimension = D;
    rep.vertices = net_.number_of_vertices();
    rep.elements = net_.number_of_elements();
    rep.moving_vertices = moving_.size();
    rep.fixed_vertices = fixed_.size();
    rep.sliding_vertices = sliding_vertices_.size();
    rep.model = internal::describe_model(model, D);
    rep.motion = internal::describe_motion(motion);
    rep.number_of_steps = options.number_of_steps;
    rep.solver = options.solver;
    rep.max_substep_halvings = options.max_substep_halvings;
    rep.quality_every_step = options.quality_every_step;
    visitor.on_start(rep);
    const std::size_t n = options.number_of_steps;
    rep.completed = true;
    for(std::size_t i = 1; i <= n; ++i) {
      Step_report s;
      s.step = i;
      const double target = double(i) / double(n);
      Attempt failed;
      const auto place = [&](std::size_t k, double t) { return motion(net_.points[moving_[k]], t); };
      const bool ok = advance(place, model, options, target, options.max_substep_halvings, s, failed);
      s.fraction = ok ? target : t_;
      s.angle_deg = internal::motion_angle_deg(motion, target);
      rep.converged = rep.converged && s.converged;
      if(!ok) {
        s.inverted = failed.inverted.size();
        rep.steps.push_back(s);
        Invalid_step inv;
        inv.step = i;
        inv.fraction = target;
        inv.angle_deg = s.angle_deg;
        inv.elements = std::move(failed.inverted);
        rep.first_invalid = std::move(inv);
        rep.completed = false;
        visitor.on_step(rep.steps.back());
        break;
      }
      if(options.quality_every_step) {
        const auto q0 = Clock::now();
        step_quality(s, quality_threads(options));
        s.seconds_check += seconds_since(q0);
      }
      rep.steps.push_back(s);
      visitor.on_step(rep.steps.back());
    }
    rep.final_fraction = t_;
    rep.final_angle_deg = internal::motion_angle_deg(motion, t_);
    std::vector<double> min_angle;
    rep.element_skewness = element_skewness(net_, positions_, quality_threads(options), &min_angle);
    rep.quality_all = skewness_histogram(rep.element_skewness, [](std::size_t) { return true; });
    rep.quality_moving =
        skewness_histogram(rep.element_skewness, [&](std::size_t t) { return touches_moving(t); });
    smallest_angles(min_angle, rep.min_angle_deg_moving, rep.min_angle_deg_all);
    std::tie(rep.min_size_ratio, rep.max_size_ratio) = size_ratio_range(quality_threads(options));
    rep.seconds_total = seconds_since(start);
    return rep;
  }

  /// One time step of a flow solver's mesh motion: moving vertex
  /// moving_vertices()[k] goes to its INITIAL position plus displacement[k],
  /// fixed vertices stay, and the free vertices follow by the spring analogy
  /// with `model` (given per call, so that it may change between steps).
  /// Every element is checked exactly; a step that inverts one is retried in
  /// 2, 4, ... substeps up to options.max_substep_halvings (the moving
  /// vertices then move linearly between their last and new positions).
  /// options.number_of_steps is not used: one call is one step.
  ///
  /// An invalid step does not throw: the state stays at the last valid
  /// positions, and the returned report says so (`inverted` > 0, the
  /// elements in `last_inverted_elements()`). The report's `step` counts the
  /// calls; `fraction` is the number of accepted moves. Calls continue the
  /// warm start of the previous ones; do not mix them with run() without a
  /// reset() in between.
  template <class Model>
  Step_report move(const std::vector<Point>& displacement, const Model& model, const Deform_options& options = {})
  {
    SPRING_MOTION_CHECK(displacement.size() == moving_.size(), "move() got " << displacement.size()
                                                                             << " displacements for "
                                                                             << moving_.size() << " moving vertices");
    move_start_.resize(moving_.size());
    move_end_.resize(moving_.size());
    for(std::size_t k = 0; k < moving_.size(); ++k) {
      const Index i = moving_[k];
      move_start_[k] = positions_[i];
      for(int c = 0; c < D; ++c) {
        move_end_[k][c] = net_.points[i][c] + displacement[k][c];
        SPRING_MOTION_VERTEX_CHECK(std::isfinite(move_end_[k][c]), i,
                                   "move(): non-finite displacement for moving vertex " << i);
      }
    }
    const double t0 = t_, target = t_ + 1;
    // linear between the last and the new positions, exactly the new ones at the end
    const auto place = [&](std::size_t k, double t) {
      if(t == target)
        return move_end_[k];
      Point q;
      for(int c = 0; c < D; ++c)
        q[c] = move_start_[k][c] + (t - t0) * (move_end_[k][c] - move_start_[k][c]);
      return q;
    };
    Step_report s;
    s.step = ++moves_;
    Attempt failed;
    const bool ok = advance(place, model, options, target, options.max_substep_halvings, s, failed);
    s.fraction = t_;
    s.inverted = ok ? 0 : failed.inverted.size();
    last_inverted_ = ok ? std::vector<std::size_t>{} : std::move(failed.inverted);
    if(ok && options.quality_every_step) {
      const auto q0 = Clock::now();
      step_quality(s, quality_threads(options));
      s.seconds_check += seconds_since(q0);
    }
    return s;
  }

  /// The elements the last rejected move() inverted (empty after a valid one).
  const std::vector<std::size_t>& last_inverted_elements() const { return last_inverted_; }

  /// min over elements of (current measure / initial measure)
  double min_size_ratio(int threads = 0) const { return size_ratio_range(threads).first; }

  /// max over elements of (current measure / initial measure)
  double max_size_ratio(int threads = 0) const { return size_ratio_range(threads).second; }

  /// (min, max) over elements of (current measure / initial measure), in one
  /// pass over the elements
  std::pair<double, double> size_ratio_range(int threads = 0) const
  {
    const long m = long(initial_measure_.size());
    double mn = std::numeric_limits<double>::infinity(), mx = -mn;
    internal::in_team(internal::thread_count(threads, std::size_t(m)), [&] {
#pragma omp for reduction(min : mn) reduction(max : mx) schedule(static)
      for(long t = 0; t < m; ++t) {
        const double r = scaled_measure(traversal_points(positions_, std::size_t(t))) / initial_measure_[std::size_t(t)];
        mn = std::min(mn, r);
        mx = std::max(mx, r);
      }
    });
    return {mn, mx};
  }

private:
  using Clock = std::chrono::steady_clock;
  static double seconds_since(Clock::time_point t0)
  {
    return std::chrono::duration<double>(Clock::now() - t0).count();
  }

  // the corners of the traversal's i-th element (Angle_slots), read from x
  // in network order
  std::array<Point, D + 1> traversal_points(const std::vector<Point>& x, std::size_t i) const
  {
    const internal::Angle_slots& slots = internal::angle_slots(net_);
    std::array<Point, D + 1> p;
    for(std::size_t k = 0; k <= D; ++k)
      p[k] = x[slots.traversal_vertices[slots.ordered_elements[i * (D + 1) + k]]];
    return p;
  }

  // The element's signed measure with coordinates scaled by the power of two
  // nearest 1/longest edge: the scaling is exact, so every ratio of measures
  // is bitwise unchanged, and a tiny mesh's measures do not underflow to 0
  // (which made min_size_ratio 0/0).
  double scaled_measure(std::array<Point, D + 1> p) const
  {
    for(auto& q : p)
      for(auto& c : q)
        c = measure_scale_ != 0 ? c * measure_scale_ : std::ldexp(c, measure_exponent_);
    return internal::signed_measure(p);
  }

  // over the elements touching a moving vertex, and over all
  void smallest_angles(const std::vector<double>& min_angle, double& moving, double& all) const
  {
    moving = all = 180;
    for(std::size_t t = 0; t < min_angle.size(); ++t) {
      all = std::min(all, min_angle[t]);
      if(touches_moving(t))
        moving = std::min(moving, min_angle[t]);
    }
  }

  // The step's extremes in one pass over the elements, nothing stored per
  // element: the same numbers as element_skewness() and size_ratio_range().
  // In the elements' spatial traversal, from a copy of the positions in its
  // order (the exact check's, traversal_check.h): in the file's order the
  // gathers of the wing's corners missed the caches, a fifth of this
  // pass's samples (perf). Each extreme is a minimum or maximum over the
  // elements, so the order does not change it.
  void step_quality(Step_report& s, int threads)
  {
    const internal::Angle_slots& slots = internal::angle_slots(net_);
    auto& xt = stiffness_scratch_.points;
    internal::copy_in_traversal_order<D>(slots, positions_, xt, threads);
    const long m = long(initial_measure_.size());
    internal::Quality_extremes all, moving;
    double lo = std::numeric_limits<double>::infinity(), hi = -lo;
    // the last step's extremes, moved inwards, as a guess that passes over
    // the elements inside them (Quality_extremes::guess); a pass whose guess
    // did not hold is made again without it, and the next guess moved
    // farther in
    const bool guessed = quality_guess_.valid;
    auto pass = [&](bool guess) {
      all = moving = internal::Quality_extremes();
      lo = std::numeric_limits<double>::infinity();
      hi = -lo;
      if(guess)
        all.guess(quality_guess_.smallest + quality_guess_.inset, quality_guess_.largest - quality_guess_.inset);
      // tetrahedra four at a time where the processor has AVX: the bound
      // test and the measures of a group's four in AVX registers
      // (test_four_quality_lanes)
      const long group = four_quality_lanes() ? 4 : 1, groups = (m + group - 1) / group;
      internal::in_team(internal::thread_count(threads, std::size_t(m)), [&] {
        internal::Quality_extremes my_all = all, my_moving;
        double my_lo = lo, my_hi = hi;
#pragma omp for schedule(static) nowait
        for(long h = 0; h < groups; ++h) {
          const long first = h * group, last = std::min(m, first + group);
          bool passed[4] = {false, false, false, false};
          double measures[4];
          const bool measured =
              last - first == 4 && test_four_quality_lanes(slots, xt, std::size_t(first), my_all, passed, measures);
          for(long t = first; t < last; ++t) {
            const std::size_t l = std::size_t(t - first);
            double measure;
            // Most elements can hold neither an extreme angle (passed over by
            // a cheap bound) nor an extreme size ratio: a measure farther
            // than 1e-12 (relative) inside the extremes so far times the
            // initial one gives a quotient inside them too, and is not
            // divided.
            if(measured && passed[l] && my_all.pass_over())
              measure = measures[l];
            else {
              const auto p = internal::traversal_element_points<D>(slots, xt, std::size_t(t));
              if(traversal_moving_[std::size_t(t)]) {
                // passed over by the bound of the moving set's extremes, it
                // lies inside all's too: all holds every element moving holds
                if(my_moving.try_pass_over<D>(p)) {
                  if(!my_all.pass_over())
                    my_all.add(internal::element_extreme_angles<D>(p));
                } else {
                  const auto e = internal::element_extreme_angles<D>(p);
                  my_all.add(e);
                  my_moving.add(e);
                }
              } else
                my_all.add_element<D>(p);
              measure = measured ? measures[l] : scaled_measure(p);
            }
            const double initial = initial_measure_[std::size_t(t)];
            const double below = my_lo * initial, above = my_hi * initial;
            if(!(initial > 0 && measure - below > 1e-12 * std::abs(below) &&
                 above - measure > 1e-12 * std::abs(above))) {
              const double ratio = measure / initial;
              my_lo = std::min(my_lo, ratio);
              my_hi = std::max(my_hi, ratio);
            }
          }
        }
#pragma omp critical(spring_motion_step_quality)
        {
          all.merge(my_all);
          moving.merge(my_moving);
          lo = std::min(lo, my_lo);
          hi = std::max(hi, my_hi);
        }
      });
    };
    pass(guessed);
    if(guessed) {
      const bool held = all.guess_held();
      if(!held)
        pass(false);
      // farther in after a miss, slowly back towards the least inset after
      // a hit (a motion that turns back improves its extremes for many steps)
      quality_guess_.inset = held ? std::max(Quality_guess::least_inset, quality_guess_.inset * 0.75)
                                  : std::min(Quality_guess::most_inset, quality_guess_.inset * 4);
    }
    quality_guess_.smallest = all.smallest_angle();
    quality_guess_.largest = all.largest_angle();
    quality_guess_.valid = std::isfinite(quality_guess_.smallest) && std::isfinite(quality_guess_.largest);
    s.max_skewness_all = all.max_skewness(D);
    s.max_skewness_moving = moving.max_skewness(D);
    s.min_angle_deg_all = all.min_angle_deg();
    s.min_angle_deg_moving = moving.min_angle_deg();
    s.min_size_ratio = lo;
    s.max_size_ratio = hi;
  }

  static bool four_quality_lanes()
  {
#if SPRING_MOTION_HAS_DOUBLE_QUAD
    return D == 3 && internal::four_lanes_available();
#else
    return false;
#endif
  }

  // For the traversal's tetrahedra first to first + 3, four at a time in
  // AVX registers: passed[l], whether tetrahedron first + l passes the
  // first bound test of `all` (as add_element would begin), and measures[l],
  // its scaled_measure; false, with neither written, for a group with a
  // tetrahedron at the moving boundary (tested one at a time against the
  // bound of the moving set's extremes, which a lane does not read), when
  // no bound can pass an element, or when the scale is not a plain product.
  bool test_four_quality_lanes(const internal::Angle_slots& slots, const std::vector<Point>& xt, std::size_t first,
                               internal::Quality_extremes& all, bool (&passed)[4], double (&measures)[4]) const
  {
#if SPRING_MOTION_HAS_DOUBLE_QUAD
    if constexpr(D == 3) {
      for(std::size_t l = 0; l < 4; ++l)
        if(traversal_moving_[first + l])
          return false;
      const double bound = all.first_bound();
      if(!(bound < 1) || measure_scale_ == 0)
        return false;
      std::array<const double*, 4> t[4];
      for(std::size_t l = 0; l < 4; ++l)
        t[l] = internal::traversal_element_corners<3>(slots, xt, first + l);
      internal::dihedral_sines_squared_above(t, bound, passed);
      internal::scaled_signed_measures(t, measure_scale_, measures);
      return true;
    }
#endif
    (void)slots, (void)xt, (void)first, (void)all, (void)passed, (void)measures;
    return false;
  }

  struct Attempt
  {
    std::vector<std::size_t> inverted;
  };

  // Moves from the current t to `target`. When an increment inverts an
  // element, the whole step is retried from the state at its start as 2, 4,
  // ... 2^halvings equal substeps (stiffness recomputed at each). On failure
  // the state is the one at the start of the step. The solver figures of `s`
  // describe the accepted attempt (or, on failure, the last one tried); the
  // attempts rejected before it are counted in s.rejected_attempts and their
  // time stays in s's timings.
  // `place(k, t)`: the position of moving vertex moving_[k] at fraction t.
  template <class Place, class Model>
  bool advance(const Place& place, const Model& model, const Deform_options& options, double target,
               std::size_t halvings, Step_report& s, Attempt& failed)
  {
    const double t_start = t_;
    // a single attempt changes the state only when it is accepted; substeps
    // may be rejected after accepted ones, so the state at the start is
    // kept to return to (copies of the size of the mesh: only when needed)
    std::vector<Point> saved_positions;
    std::array<std::vector<Point>, 3> saved_increments;
    if(halvings > 0) {
      saved_positions = positions_;
      saved_increments = increments_;
    }
    const History saved_history = history_;
    for(std::size_t level = 0;; ++level) {
      const std::size_t parts = std::size_t(1) << level;
      s.substeps = 0;
      s.iterations = 0;
      s.converged = true;
      s.max_update = s.residual = s.error_estimate = 0;
      bool ok = true;
      for(std::size_t k = 1; k <= parts && ok; ++k) {
        const double t = k == parts ? target : t_start + (target - t_start) * double(k) / double(parts);
        ok = try_increment(place, model, options, t, s, failed);
      }
      if(ok)
        return true;
      if(halvings > 0) {
        std::copy(saved_positions.begin(), saved_positions.end(), positions_.begin());
        increments_ = saved_increments;
      }
      history_ = saved_history;
      t_ = t_start;
      if(level == halvings) {
        s.substeps = parts; // the finest division tried
        return false;
      }
      ++s.rejected_attempts;
    }
  }

  // The quality passes run on the last step's thread count when the chooser
  // picks it: on a crowded machine that is one thread, and a team would stall.
  int quality_threads(const Deform_options& options) const
  {
    return options.solver.threads > 0 ? options.solver.threads : threads_.chosen();
  }

  template <class Place, class Model>
  bool try_increment(const Place& place, const Model& model, const Deform_options& options, double target,
                     Step_report& s, Attempt& failed)
  {
    constexpr bool element_model = internal::Is_element_model<Model, D>::value;
    Solver_options solver_options = options.solver;
    const int threads_before = threads_.chosen();
    int threads = solver_options.threads = threads_.next(options.solver.threads);
    // A team step after one-thread steps first starts the team's threads, or
    // wakes them, each on a core of its own (start_team): a thread woken on
    // this thread's core had made a 1 ms step cost 4 to 20, and the thread
    // chooser then kept one thread for 32 steps.
    if(threads > 1 && threads_before <= 1)
      internal::start_team(threads);
    const auto attempt_start = Clock::now();
    const double cpu_start = internal::thread_cpu_seconds();
    s.threads = threads;
    const std::size_t n = net_.number_of_vertices();
    auto t0 = Clock::now();
    // The per-vertex passes of a step run on the step's threads (serial, they
    // kept the other thread waiting at every step), one parallel region each:
    // on a busy machine every region's end waits for a thread that may be
    // descheduled. Every attempt writes the increment of every free, moving
    // and fixed vertex; the others' stay 0.
    int nt = internal::thread_count(threads, n);
    const long nfree = long(free_.size());
    if(delta_.size() != n)
      delta_.assign(n, Point{});
    {
      const bool warm = options.solver.warm_start;
      internal::Warm_start_weights w{};
      if(warm)
        w = internal::warm_start_weights(target - t_, 0.5 * (target + t_), history_.h, history_.m, history_.count,
                                         options.solver.extrapolate);
      internal::in_team(nt, [&] {
#pragma omp for schedule(static)
        for(long f = 0; f < nfree; ++f) {
          const Index i = free_[std::size_t(f)];
          for(int c = 0; c < D; ++c) {
            double v = 0;
            if(warm) {
              v = w.weight[0] * increments_[0][i][c];
              for(std::size_t j = 1; j < w.used; ++j)
                v += w.weight[j] * increments_[j][i][c];
            }
            delta_[i][c] = v;
          }
        }
      });
    }
    // the motion is evaluated once per moving vertex and attempt
    moving_targets_.resize(moving_.size());
    for(std::size_t k = 0; k < moving_.size(); ++k) {
      const Index i = moving_[k];
      const Point q = place(k, target);
      for(int c = 0; c < D; ++c) {
        SPRING_MOTION_VERTEX_CHECK(std::isfinite(q[c]), i, "the motion gave a non-finite position for vertex "
                                                               << i << " at motion fraction " << target);
        delta_[i][c] = q[c] - positions_[i][c];
      }
      moving_targets_[k] = q;
    }
    for(Index i : fixed_)
      for(int c = 0; c < D; ++c)
        delta_[i][c] = net_.points[i][c] - positions_[i][c];
    Stiffness_context ctx{D, net_.longest_initial_edge};
    // a model without edge springs (ball-vertex springs alone) gives k = 0
    // on every edge: nothing to compute
    const bool edge_springs = internal::edge_spring_form(model) != Edge_spring_form::none;
    SPRING_MOTION_CHECK(edge_springs || element_model, "stiffness model '"
                                                           << internal::describe_model(model, D).name
                                                           << "' has neither edge springs nor element matrices");
    if(edge_springs && model.angle_kind(D) == Angle_kind::face)
      internal::build_face_slots(net_);
    if(edge_springs)
      internal::compute_edge_stiffness(net_, positions_, model, ctx, stiffness_, stiffness_scratch_, threads);
    // sliding vertices couple the coordinates: then every model runs as a
    // block system (an edge model's k I blocks are its scalar system); so it
    // does with planes given, so that every part of a partitioned mesh runs
    // the block system of the whole, whether or not it holds sliding vertices
    const bool block = element_model || !sliding_vertices_.empty() || planes_given_;
    if(solver_.needs_build(net_, free_, block, options.solver)) {
      solver_.build(net_, free_, block, options.solver);
      solver_.set_projectors(sliding_vertices_, sliding_projectors_);
    }
    if(block)
      internal::assemble_block_system<D>(positions_, model, stiffness_, solver_, threads);
    else
      solver_.load_scalar(net_, stiffness_, threads);
    solver_.set_start(delta_, threads);
    solver_.set_positions(positions_);
    s.seconds_stiffness += seconds_since(t0);
    // the first step's solve and check may go to the team (after_setup)
    const double setup_cpu = internal::thread_cpu_seconds();
    threads = solver_options.threads = threads_.after_setup(
        seconds_since(attempt_start), cpu_start >= 0 && setup_cpu >= 0 ? setup_cpu - cpu_start : -1);
    s.threads = threads;
    nt = internal::thread_count(threads, n);

    Step_system_view<D> view;
    if(system_observer || solve_override) {
      view.block = solver_.block();
      view.rows = solver_.rows();
      view.vertices = solver_.order().data();
      view.row_offsets = solver_.row_offsets().data();
      view.columns = solver_.columns().data();
      view.values = solver_.values();
      view.diagonal = solver_.diagonal();
      view.rhs = solver_.rhs().data();
      view.initial = solver_.solution().data();
    }
    if(system_observer)
      system_observer(view);
    t0 = Clock::now();
    Solve_report sr;
    if(solve_override) {
      sr = solve_override(view, outside_solution_);
      solver_.set_solution(outside_solution_);
    } else
      sr = solver_.solve(solver_options);
    solver_.store(delta_, threads);
    s.seconds_solve += seconds_since(t0);
    s.iterations += sr.iterations;
    s.converged = s.converged && sr.converged;
    s.max_update = std::max(s.max_update, sr.last_max_update);
    s.residual = std::max(s.residual, sr.residual);
    s.error_estimate = std::max(s.error_estimate, sr.error_estimate);

    t0 = Clock::now();
    candidate_.resize(n);
    internal::in_team(nt, [&] {
#pragma omp for schedule(static)
      for(long i = 0; i < long(n); ++i) {
        const std::size_t I = std::size_t(i);
        candidate_[I] = positions_[I];
        if(is_free_[I])
          for(int c = 0; c < D; ++c)
            candidate_[I][c] += delta_[I][c];
      }
    });
    // constrained vertices land exactly on their prescribed positions
    for(std::size_t k = 0; k < moving_.size(); ++k)
      candidate_[moving_[k]] = moving_targets_[k];
    for(Index i : fixed_)
      candidate_[i] = net_.points[i];
    for(const auto& sv : sliding_.vertices)
      internal::snap_to_planes<D>(sv, net_.points[sv.vertex], candidate_[sv.vertex]);
    failed.inverted.clear();
    // in the elements' spatial traversal (traversal_check.h); the elements
    // that failed are listed in element order only when some did
    const internal::Angle_slots& slots = internal::angle_slots(net_);
    if(traversal_sign_.empty()) {
      internal::copy_in_traversal_order<D>(slots, net_.points, stiffness_scratch_.points, threads);
      traversal_sign_ = internal::traversal_orientations<D>(slots, stiffness_scratch_.points, threads);
    }
    internal::copy_in_traversal_order<D>(slots, candidate_, stiffness_scratch_.points, threads);
    if(internal::orientation_changed<D>(slots, stiffness_scratch_.points, traversal_sign_, threads))
      find_inverted_elements(net_, candidate_, record_, std::back_inserter(failed.inverted), threads);
    s.seconds_check += seconds_since(t0);
    const double wall = seconds_since(attempt_start), cpu_end = internal::thread_cpu_seconds();
    threads_.record(wall, sr.iterations, cpu_start >= 0 && cpu_end >= 0 ? cpu_end - cpu_start : -1);
    const bool valid = failed.inverted.empty();
    if(!(agree_on_validity ? agree_on_validity(valid) : valid))
      return false;
    // the oldest increment's storage takes the newest (only free vertices'
    // entries are ever written: the others stay 0); the positions are
    // copied, not swapped: positions() keeps its storage for the deformer's
    // lifetime, so a view of it (the Python module's) stays valid
    increments_[2].swap(increments_[1]);
    increments_[1].swap(increments_[0]);
    internal::in_team(nt, [&] {
#pragma omp for schedule(static)
      for(long i = 0; i < long(n); ++i) {
        const std::size_t I = std::size_t(i);
        positions_[I] = candidate_[I];
        if(is_free_[I])
          increments_[0][I] = delta_[I];
      }
    });
    history_.h = {target - t_, history_.h[0], history_.h[1]};
    history_.m = {0.5 * (target + t_), history_.m[0], history_.m[1]};
    ++history_.count;
    t_ = target;
    ++s.substeps;
    return true;
  }

  Spring_network<D> net_;
  std::vector<Vertex_role> roles_;
  std::vector<Index> free_, moving_, fixed_;
  std::vector<char> is_free_; // per vertex: 1 for those in free_
  // sliding vertices: their planes, and (those some element uses) their
  // projectors, in the form the solver takes
  internal::Sliding_set<D> sliding_;
  bool planes_given_ = false;
  std::vector<Index> sliding_vertices_;
  std::vector<std::array<double, D * D>> sliding_projectors_;
  std::vector<Point> positions_;
  // the last three accepted increments, the newest first (the warm start's history)
  std::array<std::vector<Point>, 3> increments_;
  // their fraction intervals (h) and midpoints (m), the newest first
  struct History
  {
    std::array<double, 3> h{}, m{};
    std::size_t count = 0;
  } history_;
  Orientation_record record_;
  // the initial orientations in the elements' spatial traversal (the check's
  // order; made at the first check)
  std::vector<signed char> traversal_sign_;
  // per element in the spatial traversal (Angle_slots): its initial
  // scaled_measure(), and whether it touches a moving vertex
  std::vector<double> initial_measure_;
  // step_quality's guess: the last step's smallest and largest angle
  // (radians) and how far inside them the next pass guesses. The least
  // inset (0.06 degrees) keeps the guess beyond the angles of a structured
  // mesh's undisturbed part when a small motion has moved the extremes
  // little past them.
  struct Quality_guess
  {
    static constexpr double least_inset = 1e-3, most_inset = 0.3;
    bool valid = false;
    double smallest = 0, largest = 0, inset = least_inset;
  };
  Quality_guess quality_guess_;
  std::vector<char> traversal_moving_;
  // scaled_measure(): coordinates times 2^measure_exponent_ (measure_scale_ when that is normal, else 0)
  int measure_exponent_ = 0;
  double measure_scale_ = 0;
  std::vector<double> stiffness_;
  internal::Stiffness_scratch<D> stiffness_scratch_;
  // the solver state: ordering, pattern and multigrid aggregates, rebuilt
  // when the options they depend on change (Free_system::needs_build)
  internal::Free_system<D> solver_;
  // Solver_options::threads = 0: the team or one thread, by measurement
  internal::Thread_chooser threads_;
  // scratch of every attempt, kept to avoid allocating in the step loop
  std::vector<Point> delta_, candidate_, moving_targets_, outside_solution_;
  // move(): the moving vertices' positions before and after the call
  std::vector<Point> move_start_, move_end_;
  std::vector<std::size_t> last_inverted_;
  std::size_t moves_ = 0;
  double t_ = 0;
};

} // namespace spring_motion

#endif
