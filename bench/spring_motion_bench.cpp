// SpringMotion benchmark (docs/performance.md): one table of where the time of a motion
// goes, how the increment solver compares with Eigen's solvers on the very
// same linear systems, how close one SOR sweep comes to the memory-traffic
// bound, and 1 versus 2 threads; then the performance targets, each with
// target / measured / met.
//
//   cmake -S . -B build-bench -DCMAKE_BUILD_TYPE=Release -DSPRING_MOTION_BUILD_BENCH=ON
//   cmake --build build-bench --target spring_motion_bench
//   ./build-bench/bench/spring_motion_bench            # full run (minutes)
//   ./build-bench/bench/spring_motion_bench --quick    # smoke run (seconds)
//
// Options: --quick, --cases a,b,... (naca_coarse, naca_fine, wing, box, cli),
// --box N (cubes per side of the structured box; 100 gives ~1M nodes),
// --repeats R (runs per case and thread count for the medians; rounds of
// the block-vs-scalar tables, at most 3 on the wing),
// --omega-table (instead of the table: SOR sweeps and preconditioned CG
// iterations against the relaxation factor on the 2D cases' systems),
// --every-step-error (the 2D cases' err columns over the systems of all their
// steps, not steps 1, middle and last: what a change of the stopping rule
// does to the error of every solve),
// --write-box FILE (nothing measured: the box of --box N written as a Medit
// file, its block's surface labelled 1 and the cube's faces 2, for runs of
// `spring-motion` on the very mesh the box rows measure).
// The case `cli` runs the `spring-motion` program on the 2D and wing meshes
// written to Medit files: whole-process time, peak memory, and the wing with
// two CPU-bound processes beside it (default threads against one thread).
// Progress goes to stderr, the tables to stdout.
#include <spring_motion/internal/solver/free_cores.h>
#include <spring_motion/io/write_mesh.h>
#include <spring_motion/spring_motion.h>
#include <naca0012/Naca0012_mesh_2.h>
#if __has_include(<naca0012/Naca0012_wing_mesh_3.h>)
#include <naca0012/Naca0012_wing_mesh_3.h>
#define SPRING_MOTION_BENCH_HAS_WING 1
#endif

#include <Eigen/IterativeLinearSolvers>
#include <Eigen/SparseCholesky>
#include <Eigen/Sparse>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <numeric>
#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <functional>
#include <limits>
#include <map>
#include <iostream>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

#include <fcntl.h>
#include <signal.h>
#include <spawn.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#ifdef _OPENMP
#include <omp.h>
#endif

namespace sm = spring_motion;
using Clock = std::chrono::steady_clock;

namespace {

double seconds_since(Clock::time_point t0) { return std::chrono::duration<double>(Clock::now() - t0).count(); }

double median(std::vector<double> v)
{
  if(v.empty())
    return std::nan("");
  std::sort(v.begin(), v.end());
  const std::size_t n = v.size();
  return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

void progress(const std::string& s)
{
  std::cerr << "[bench] " << s << std::endl;
}

struct Setup
{
  bool quick = false;
  std::vector<std::string> cases = {"naca_coarse", "naca_fine", "wing", "box", "cli"};
  std::size_t box = 100;
  int repeats = 5;
  bool omega_table = false;
  bool every_step_error = false;
  std::string write_box; // --write-box: only write the box there
};

// STREAM-like triad a = b + s c over arrays far larger than the caches, best
// of several passes; bytes counted as STREAM does (3 x 8 per element).
double triad_bandwidth(int threads, std::size_t n)
{
  std::vector<double> a(n, 0.0), b(n, 1.0), c(n, 2.0);
  const long ln = long(n);
  double best = 1e300;
  for(int pass = 0; pass < 6; ++pass) {
    const auto t0 = Clock::now();
#pragma omp parallel for schedule(static) num_threads(threads)
    for(long i = 0; i < ln; ++i)
      a[std::size_t(i)] = b[std::size_t(i)] + 3.0 * c[std::size_t(i)];
    const double t = seconds_since(t0);
    if(pass > 0) // the first pass pays the page faults
      best = std::min(best, t);
  }
  volatile double sink = a[n / 2];
  (void)sink;
  return 24.0 * double(n) / best;
}

// The first `steps` steps of a longer schedule: t in [0, 1] here is t * scale
// of the underlying motion. Lets a huge case run a few representative steps.
template <class Motion>
struct Partial_motion
{
  Motion base;
  double scale = 1;
  template <class P>
  P operator()(const P& p, double t) const { return base(p, t * scale); }
  sm::Motion_description description() const { return base.description(); }
};

// A copy of one step's system as Network_deformer::system_observer shows it
// (public Step_system_view), and our solution of it: the step's increment at
// the free vertices, read from the positions before and after the step.
template <int D>
struct Captured_system
{
  bool block = false;
  std::vector<sm::Index> vertices, offsets, columns;
  std::vector<double> values, diagonal;
  std::vector<std::array<double, D>> rhs, x0, solution;
  std::vector<std::array<double, D>> before; // positions at the start of the step
  std::size_t step = 0;
  double seconds = 0;         // our solve, from the step report (1 thread)
  std::size_t iterations = 0; // ours

  static Captured_system from(const sm::Step_system_view<D>& v, std::size_t step,
                              const std::vector<std::array<double, D>>& positions)
  {
    Captured_system c;
    const std::size_t w = v.block ? D * D : 1, nnz = v.row_offsets[v.rows];
    c.block = v.block;
    c.vertices.assign(v.vertices, v.vertices + v.rows);
    c.offsets.assign(v.row_offsets, v.row_offsets + v.rows + 1);
    c.columns.assign(v.columns, v.columns + nnz);
    c.values.assign(v.values, v.values + nnz * w);
    c.diagonal.assign(v.diagonal, v.diagonal + v.rows * w);
    c.rhs.assign(v.rhs, v.rhs + v.rows);
    c.x0.assign(v.initial, v.initial + v.rows);
    c.before = positions;
    c.step = step;
    return c;
  }
};

template <int D>
struct Case
{
  std::string name;
  sm::Spring_network<D> net;
  std::vector<sm::Vertex_role> roles;
  sm::Pitch_motion<D> motion;
  std::size_t steps = 100;      // steps of the run
  std::size_t of_steps = 100;   // of a schedule with this many steps (steps < of_steps: partial run)
  int repeats = 3;
  bool direct_reference = true; // SimplicialLDLT affordable
  std::vector<std::size_t> capture_steps;
};

struct Run_stats
{
  int threads = 1;
  bool completed = false;
  double total = 0; // median over repeats, s
  double stiffness = 0, solve = 0, check = 0; // median per step, s
  double iterations = 0; // mean per step
  std::size_t steps_run = 0; // steps reported by the last repeat (fewer if it stopped)
};

struct Compare_stats
{
  std::string reference;   // "LDLT" or "CG 1e-12"
  double error = 0;        // max |ours - reference| over captured systems
  double ours_seconds = 0; // sums over captured systems
  double ic_seconds = 0, ldlt_seconds = 0;
  double ic_error = 0;
  bool ic_reached = true;
  double ic_tol = 0;
  bool ldlt = false;
};

struct Sweep_stats
{
  double seconds = 0, bound = 0; // one SOR sweep; traffic bytes / bandwidth (medians)
  double ratio = 0;              // median over the repetitions of sweep / bound, each bound measured beside its sweep
  double bytes = 0;
};

struct Row
{
  std::string name;
  std::size_t nodes = 0, elements = 0, free = 0, steps = 0, of_steps = 0;
  std::vector<Run_stats> runs; // 1 and 2 threads
  Compare_stats cmp;
  std::vector<Sweep_stats> sweeps; // 1 and 2 threads
  bool available = true;
  std::string note;
};

// ---- Eigen on the captured systems -------------------------------------------------

template <int D>
struct Eigen_system
{
  Eigen::SparseMatrix<double> A; // free x free (scalar system: one matrix for all D components)
  Eigen::MatrixXd b, x0;         // nf x D
};

// The system as one sparse matrix: nf x nf for a scalar system (the same for
// every component), nf D x nf D for a block system (then b and x0 are one
// column, component-major per row, reshaped to nf x D by the callers).
template <int D>
Eigen_system<D> to_eigen(const Captured_system<D>& c)
{
  const long nf = long(c.vertices.size());
  const int w = c.block ? D : 1;
  Eigen_system<D> e;
  e.b = Eigen::MatrixXd::Zero(nf, D);
  e.x0 = Eigen::MatrixXd::Zero(nf, D);
  std::vector<Eigen::Triplet<double>> trip;
  for(long k = 0; k < nf; ++k) {
    for(int d = 0; d < D; ++d) {
      e.x0(k, d) = c.x0[std::size_t(k)][d];
      e.b(k, d) = c.rhs[std::size_t(k)][d];
    }
    for(int r = 0; r < w; ++r)
      for(int q = 0; q < w; ++q)
        trip.emplace_back(k * w + r, k * w + q, c.diagonal[std::size_t((k * w + r) * w + q)]);
    for(sm::Index p = c.offsets[std::size_t(k)]; p < c.offsets[std::size_t(k) + 1]; ++p)
      for(int r = 0; r < w; ++r)
        for(int q = 0; q < w; ++q)
          trip.emplace_back(k * w + r, long(c.columns[p]) * w + q, c.values[(std::size_t(p) * w + r) * w + q]);
  }
  e.A.resize(nf * w, nf * w);
  e.A.setFromTriplets(trip.begin(), trip.end());
  return e;
}

// Right-hand sides as Eigen wants them: nf x D (scalar) or one column (block).
template <int D>
Eigen::MatrixXd eigen_rhs(const Captured_system<D>& c, const Eigen::MatrixXd& m)
{
  if(!c.block)
    return m;
  Eigen::MatrixXd v(m.rows() * D, 1);
  for(long k = 0; k < m.rows(); ++k)
    for(int d = 0; d < D; ++d)
      v(k * D + d, 0) = m(k, d);
  return v;
}
template <int D>
Eigen::MatrixXd from_eigen(const Captured_system<D>& c, const Eigen::MatrixXd& v)
{
  if(!c.block)
    return v;
  Eigen::MatrixXd m(v.rows() / D, D);
  for(long k = 0; k < m.rows(); ++k)
    for(int d = 0; d < D; ++d)
      m(k, d) = v(k * D + d, 0);
  return m;
}

template <int D>
double max_difference(const Eigen::MatrixXd& a, const Eigen::MatrixXd& b)
{
  return (a - b).cwiseAbs().maxCoeff();
}

template <int D>
Eigen::MatrixXd as_matrix(const std::vector<std::array<double, D>>& x)
{
  Eigen::MatrixXd m(long(x.size()), D);
  for(std::size_t k = 0; k < x.size(); ++k)
    for(int d = 0; d < D; ++d)
      m(long(k), d) = x[k][d];
  return m;
}

// ---- the cases -------------------------------------------------------------------------

Case<2> naca_case(bool fine, const Setup& setup)
{
  Case<2> c;
  c.name = fine ? "NACA0012 2D fine" : "NACA0012 2D coarse";
  sm::Mesh_2_cdt cdt;
  sm::make_naca0012_mesh_2(cdt, fine ? sm::Naca0012_mesh_2_options::fine() : sm::Naca0012_mesh_2_options{});
  c.net = sm::extract_spring_network(cdt).network;
  c.roles = sm::assign_roles(c.net, sm::moving_boundary_where([](const std::array<double, 2>& p) {
                               return sm::is_on_naca0012_airfoil(p[0], p[1]);
                             }));
  c.motion = sm::Pitch_motion<2>(45, {0.25, 0.0});
  c.steps = c.of_steps = setup.quick ? 20 : 100;
  c.repeats = setup.quick ? 1 : (fine ? 3 : setup.repeats);
  c.capture_steps = {1, c.steps / 2, c.steps};
  if(setup.every_step_error) {
    c.capture_steps.resize(c.steps);
    std::iota(c.capture_steps.begin(), c.capture_steps.end(), std::size_t(1));
  }
  return c;
}

#ifdef SPRING_MOTION_BENCH_HAS_WING
// The paper's 3D case: the NACA0012 wing in a sphere pitching about the
// quarter-chord line (z axis) to 30 degrees in 100 steps. --quick: 10 steps.
Case<3> wing_case(const Setup& setup)
{
  Case<3> c;
  c.name = "wing 3D";
  std::filesystem::create_directories("spring_motion_bench_cache");
  const auto mesh = sm::naca0012_wing_mesh_3({}, "spring_motion_bench_cache");
  auto points = mesh.points;
  std::vector<std::array<sm::Index, 4>> tets(mesh.elements.begin(), mesh.elements.end());
  c.net = sm::make_spring_network<3>(std::move(points), std::move(tets));
  c.roles = sm::assign_roles(c.net, sm::moving_boundary_where([](const std::array<double, 3>& p) {
                               return sm::is_on_naca0012_wing(p[0], p[1], p[2]);
                             }));
  c.motion = sm::Pitch_motion<3>(30, {0.25, 0.0, 0.0});
  c.motion.axis = {0, 0, 1};
  c.steps = c.of_steps = setup.quick ? 10 : 100;
  c.repeats = 1;
  // a quarter of the way: chosen when the wing of the time stopped at step 49
  // (half way captured that refused step's system); the default wing now
  // completes its 100 steps, and the step stays so that the err columns
  // compare with the earlier runs'
  c.capture_steps = {c.steps / 4};
  return c;
}
#endif

// A structured tetrahedral grid: the unit cube in N^3 cubes of 6 tetrahedra
// each (Kuhn split, conforming), minus a centred cubic block of (N/4)^3
// cubes whose surface pitches about the z axis through the centre. About
// (N+1)^3 nodes: N = 100 gives 1.03 million nodes and 5.9 million tetrahedra.
Case<3> box_case(std::size_t N, const Setup& setup)
{
  Case<3> c;
  std::ostringstream name;
  const std::size_t lo = (3 * N) / 8, hi = lo + std::max<std::size_t>(1, N / 4);
  auto in_block_cube = [&](std::size_t i, std::size_t j, std::size_t k) {
    return i >= lo && i < hi && j >= lo && j < hi && k >= lo && k < hi;
  };
  auto strictly_inside = [&](std::size_t i, std::size_t j, std::size_t k) {
    return i > lo && i < hi && j > lo && j < hi && k > lo && k < hi;
  };
  const std::size_t M = N + 1;
  std::vector<sm::Index> id(M * M * M, sm::Index(-1));
  std::vector<std::array<double, 3>> points;
  for(std::size_t k = 0; k < M; ++k)
    for(std::size_t j = 0; j < M; ++j)
      for(std::size_t i = 0; i < M; ++i)
        if(!strictly_inside(i, j, k)) {
          id[(k * M + j) * M + i] = sm::Index(points.size());
          points.push_back({double(i) / double(N), double(j) / double(N), double(k) / double(N)});
        }
  std::vector<std::array<sm::Index, 4>> tets;
  tets.reserve(6 * N * N * N);
  const int perms[6][3] = {{0, 1, 2}, {0, 2, 1}, {1, 0, 2}, {1, 2, 0}, {2, 0, 1}, {2, 1, 0}};
  const bool odd[6] = {false, true, true, false, false, true};
  for(std::size_t k = 0; k < N; ++k)
    for(std::size_t j = 0; j < N; ++j)
      for(std::size_t i = 0; i < N; ++i) {
        if(in_block_cube(i, j, k))
          continue;
        for(int p = 0; p < 6; ++p) {
          std::array<std::size_t, 3> v{i, j, k};
          std::array<sm::Index, 4> t;
          t[0] = id[(v[2] * M + v[1]) * M + v[0]];
          for(int s = 0; s < 3; ++s) {
            ++v[std::size_t(perms[p][s])];
            t[std::size_t(s) + 1] = id[(v[2] * M + v[1]) * M + v[0]];
          }
          if(odd[p]) // all elements positively oriented
            std::swap(t[2], t[3]);
          tets.push_back(t);
        }
      }
  c.net = sm::make_spring_network<3>(std::move(points), std::move(tets));
  name << "box 3D " << N << "^3 x6 tets";
  c.name = name.str();
  const double eps = 0.25 / double(N);
  c.roles = sm::assign_roles(c.net, sm::moving_boundary_where([&](const std::array<double, 3>& p) {
                               for(int d = 0; d < 3; ++d)
                                 if(p[d] < eps || p[d] > 1 - eps)
                                   return false;
                               return true; // a boundary vertex off the outer box: the block's surface
                             }));
  c.motion = sm::Pitch_motion<3>(30, {0.5, 0.5, 0.5});
  c.motion.axis = {0, 0, 1};
  c.of_steps = 100;
  // the first 10 of the 100 steps (the largest increments): the medians
  // per step then read the steps after the first, which includes the
  // set-up, and the second, whose arrays the machine may still be mapping
  // (docs/performance.md, "The box's median step")
  c.steps = setup.quick ? 2 : 10;
  c.repeats = 1;
  c.direct_reference = c.net.number_of_vertices() <= 300000;
  c.capture_steps = {c.steps};
  return c;
}

// ---- measurements ----------------------------------------------------------------------

// Fills each captured system's solution (the step's increment at its free
// vertices) and solve time once its step is done. run() takes the visitor by
// value: the captures it must fill are reached through a pointer.
template <int D>
struct Capture_visitor
{
  const sm::Network_deformer<D>* deformer = nullptr;
  const std::vector<Captured_system<D>*>* pending = nullptr;
  void on_start(const sm::Deform_report&) {}
  void on_step(const sm::Step_report& s)
  {
    for(Captured_system<D>* c : *pending)
      if(c->step == s.step && c->solution.empty()) {
        for(sm::Index v : c->vertices) {
          std::array<double, D> d;
          for(int k = 0; k < D; ++k)
            d[k] = deformer->positions()[v][k] - c->before[v][k];
          c->solution.push_back(d);
        }
        c->seconds = s.seconds_solve;
        c->iterations = s.iterations;
      }
  }
};

// One run of the case's motion with these solver options and model; captures
// the systems of c.capture_steps (or the last one, if the run stops before).
template <int D, class Model = sm::Grid_scaled_stiffness>
sm::Deform_report run_once(const Case<D>& c, const sm::Solver_options& solver, std::vector<Captured_system<D>>* capture,
                           const Model& model = {}, std::size_t steps = 0)
{
  sm::Network_deformer<D> deformer(c.net, c.roles);
  std::size_t call = 0;
  std::optional<Captured_system<D>> latest; // if the run stops before a capture step
  std::vector<Captured_system<D>> got;
  got.reserve(c.capture_steps.size());
  std::vector<Captured_system<D>*> pending;
  Capture_visitor<D> visitor;
  visitor.deformer = &deformer;
  visitor.pending = &pending;
  if(capture)
    deformer.system_observer = [&](const sm::Step_system_view<D>& v) {
      ++call;
      if(std::find(c.capture_steps.begin(), c.capture_steps.end(), call) != c.capture_steps.end()) {
        got.push_back(Captured_system<D>::from(v, call, deformer.positions()));
        pending.push_back(&got.back());
      } else if(got.empty()) {
        latest = Captured_system<D>::from(v, call, deformer.positions());
        pending.assign(1, &*latest);
      }
    };
  sm::Deform_options options;
  options.number_of_steps = steps ? steps : c.steps;
  options.solver = solver;
  options.quality_every_step = false; // the exact validity check still runs every step
  const Partial_motion<sm::Pitch_motion<D>> motion{c.motion, double(options.number_of_steps) / double(c.of_steps)};
  const auto rep = deformer.run(motion, model, options, visitor);
  for(const auto* p : pending)
    SPRING_MOTION_CHECK(p->solution.size() == p->vertices.size(), "step " << p->step << ": no solution captured");
  if(capture) {
    if(got.empty() && latest)
      got.push_back(std::move(*latest));
    for(auto& g : got)
      capture->push_back(std::move(g));
  }
  return rep;
}

template <int D, class Model = sm::Grid_scaled_stiffness>
Run_stats run_case(const Case<D>& c, int threads, std::vector<Captured_system<D>>* capture, const Model& model = {})
{
  Run_stats st;
  st.threads = threads;
  std::vector<double> totals, stiff, solve, check;
  double iterations = 0;
  std::size_t counted = 0;
  for(int r = 0; r < c.repeats; ++r) {
    sm::Solver_options solver;
    solver.threads = threads;
    const auto rep = run_once(c, solver, r == 0 ? capture : nullptr, model);
    st.completed = rep.completed;
    st.steps_run = rep.steps.size();
    if(!rep.completed && rep.first_invalid)
      progress(c.name + ": step " + std::to_string(rep.first_invalid->step) + " inverted " +
               std::to_string(rep.first_invalid->elements.size()) + " element(s)");
    totals.push_back(rep.seconds_total);
    for(const auto& s : rep.steps) {
      stiff.push_back(s.seconds_stiffness);
      solve.push_back(s.seconds_solve);
      check.push_back(s.seconds_check);
      iterations += double(s.iterations);
      ++counted;
    }
    progress(c.name + ": run " + std::to_string(r + 1) + "/" + std::to_string(c.repeats) + " with " +
             std::to_string(threads) + " thread(s): " + std::to_string(rep.seconds_total) + " s" +
             (rep.completed ? "" : " (NOT completed)"));
  }
  st.total = median(totals);
  st.stiffness = median(stiff);
  st.solve = median(solve);
  st.check = median(check);
  st.iterations = counted ? iterations / double(counted) : 0;
  return st;
}

// The reference solution of a captured system: SimplicialLDLT, or for the
// largest case Eigen's CG + incomplete Cholesky to a relative residual of 1e-14.
template <int D>
Eigen::MatrixXd reference_solution(const Captured_system<D>& cap, const Eigen_system<D>& e, bool direct,
                                   double* seconds = nullptr)
{
  const auto t0 = Clock::now();
  Eigen::MatrixXd x;
  if(direct) {
    Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> ldlt(e.A);
    SPRING_MOTION_CHECK(ldlt.info() == Eigen::Success, "LDLT failed");
    x = from_eigen<D>(cap, ldlt.solve(eigen_rhs<D>(cap, e.b)));
  } else {
    Eigen::ConjugateGradient<Eigen::SparseMatrix<double>, Eigen::Lower | Eigen::Upper,
                             Eigen::IncompleteCholesky<double>>
        cg;
    cg.setTolerance(1e-14);
    cg.setMaxIterations(100000);
    cg.compute(e.A);
    const Eigen::MatrixXd b = eigen_rhs<D>(cap, e.b), x0 = eigen_rhs<D>(cap, e.x0);
    Eigen::MatrixXd v(b.rows(), b.cols());
    for(long d = 0; d < b.cols(); ++d)
      v.col(d) = cg.solveWithGuess(b.col(d), x0.col(d));
    x = from_eigen<D>(cap, v);
  }
  if(seconds)
    *seconds += seconds_since(t0);
  return x;
}

// Our default solver (the captured step's own solve in the 1-thread run:
// its solution and time), Eigen's CG + incomplete Cholesky and SimplicialLDLT
// on the captured systems, all from the run's initial iterate. Eigen's CG
// tolerance is tightened by 10x until its error is at most ours ("equal
// error").
template <int D>
Compare_stats compare_solvers(const Case<D>& c, const std::vector<Captured_system<D>>& caps)
{
  Compare_stats out;
  out.ldlt = c.direct_reference;
  out.reference = c.direct_reference ? "LDLT" : "CG 1e-14";
  for(const auto& cap : caps) {
    progress(c.name + ": solver comparison on the system of step " + std::to_string(cap.step));
    const auto e = to_eigen<D>(cap);
    const Eigen::MatrixXd reference = reference_solution<D>(cap, e, c.direct_reference, &out.ldlt_seconds);
    const double err = max_difference<D>(as_matrix<D>(cap.solution), reference);
    out.ours_seconds += cap.seconds;
    out.error = std::max(out.error, err);
    // Eigen CG + IC at equal error
    bool reached = false;
    double t_ic = 0, e_ic = 0, tol = 1e-4;
    const Eigen::MatrixXd b = eigen_rhs<D>(cap, e.b), x0 = eigen_rhs<D>(cap, e.x0);
    for(; tol >= 1e-15; tol /= 10) {
      const auto t0 = Clock::now();
      Eigen::ConjugateGradient<Eigen::SparseMatrix<double>, Eigen::Lower | Eigen::Upper,
                               Eigen::IncompleteCholesky<double>>
          cg;
      cg.setTolerance(tol);
      cg.setMaxIterations(100000);
      cg.compute(e.A);
      Eigen::MatrixXd x(b.rows(), b.cols());
      for(long d = 0; d < b.cols(); ++d)
        x.col(d) = cg.solveWithGuess(b.col(d), x0.col(d));
      t_ic = seconds_since(t0);
      e_ic = max_difference<D>(from_eigen<D>(cap, x), reference);
      if(e_ic <= err) {
        reached = true;
        break;
      }
      if(t_ic > 120) // give up: the table then shows "> ratio"
        break;
    }
    out.ic_seconds += t_ic;
    out.ic_error = std::max(out.ic_error, e_ic);
    out.ic_reached = out.ic_reached && reached;
    out.ic_tol = std::max(out.ic_tol, tol);
  }
  return out;
}

// One SOR sweep in the solver's order, on the system of the motion's second
// step (through Network_deformer::move: the first step solved by the
// default solver, the second by SOR capped at `reps` and at 2 `reps` sweeps
// with the tolerance out of reach); the difference of their solve times over
// `reps` is the time of a sweep, the solve's fixed costs cancelling. (From a
// zero start, as in a first step, the sweeps spread values so small that
// they are subnormal, and slow.) The bytes a scalar sweep must move at least:
// pattern and values once, right-hand side and inverse diagonal once,
// solution read and written. The bound is those bytes over the triad
// bandwidth measured just before each repetition, not at the start of the
// benchmark, minutes earlier: the bandwidth a process gets on a shared host
// changes in between, and the same code's ratio had read 1.28x in one run
// and 2.55x in another.
template <int D>
Sweep_stats time_sweep(const Case<D>& c, const Captured_system<D>& cap, int threads, std::size_t triad_n)
{
  Sweep_stats s;
  const int reps = c.net.number_of_vertices() > 200000 ? 7 : 31;
  auto solve_seconds = [&](int sweeps) {
    sm::Network_deformer<D> deformer(c.net, c.roles);
    auto displacement = [&](std::size_t step) {
      std::vector<std::array<double, D>> d;
      for(sm::Index v : deformer.moving_vertices()) {
        const auto q = c.motion(c.net.points[v], double(step) / double(c.of_steps));
        std::array<double, D> u;
        for(int k = 0; k < D; ++k)
          u[k] = q[k] - c.net.points[v][k];
        d.push_back(u);
      }
      return d;
    };
    sm::Deform_options options;
    options.quality_every_step = false;
    options.solver.threads = threads;
    deformer.move(displacement(1), sm::Grid_scaled_stiffness{}, options);
    options.solver.method = sm::Solver_method::sor;
    options.solver.relaxation_factor = 1.0;
    options.solver.tolerance = 1e-300;
    options.solver.max_iterations = std::size_t(sweeps);
    const auto step = deformer.move(displacement(2), sm::Grid_scaled_stiffness{}, options);
    SPRING_MOTION_CHECK(step.iterations == std::size_t(sweeps), "the sweep run did not sweep");
    return step.seconds_solve;
  };
  const double nf = double(cap.vertices.size()), nnz = double(cap.columns.size());
  s.bytes = nnz * (sizeof(sm::Index) + sizeof(double)) +
            nf * (sizeof(sm::Index) + sizeof(double) + D * sizeof(double) + 2.0 * D * sizeof(double));
  std::vector<double> ts, bounds, ratios;
  for(int r = 0; r < 3; ++r) {
    bounds.push_back(s.bytes / triad_bandwidth(threads, triad_n));
    ts.push_back((solve_seconds(2 * reps) - solve_seconds(reps)) / double(reps));
    ratios.push_back(ts.back() / bounds.back());
  }
  s.seconds = median(ts);
  s.bound = median(bounds);
  s.ratio = median(ratios);
  return s;
}

template <int D>
Row measure(const Case<D>& c, std::size_t triad_n)
{
  Row row;
  row.name = c.name;
  row.nodes = c.net.number_of_vertices();
  row.elements = c.net.number_of_elements();
  row.steps = c.steps;
  row.of_steps = c.of_steps;
  for(auto r : c.roles)
    row.free += r == sm::Vertex_role::free;
  std::vector<Captured_system<D>> caps;
  for(int threads : {1, 2})
    row.runs.push_back(run_case(c, threads, threads == 1 ? &caps : nullptr));
  SPRING_MOTION_CHECK(!caps.empty(), "the run stopped (inverted element) before the step whose system is compared");
  row.cmp = compare_solvers(c, caps);
  progress(c.name + ": SOR sweep timing");
  for(int threads : {1, 2})
    row.sweeps.push_back(time_sweep(c, caps.back(), threads, triad_n));
  return row;
}

// The case with its vertices numbered along a Morton curve (by the code of
// their position) and its elements by their smallest new vertex, as meshers
// and converters that sort their output in space number a mesh. The
// solver's ordering and its multigrid aggregates are chosen from the
// numbering, so the iterations a run needs may depend on it.
template <int D>
Case<D> spatially_numbered(const Case<D>& c)
{
  const std::size_t n = c.net.number_of_vertices();
  std::array<double, D> lo, hi;
  lo.fill(std::numeric_limits<double>::infinity());
  hi.fill(-std::numeric_limits<double>::infinity());
  for(const auto& p : c.net.points)
    for(int k = 0; k < D; ++k) {
      lo[k] = std::min(lo[k], p[k]);
      hi[k] = std::max(hi[k], p[k]);
    }
  std::vector<std::pair<std::uint64_t, sm::Index>> key(n);
  for(std::size_t i = 0; i < n; ++i) {
    std::array<std::uint32_t, D> q;
    for(int k = 0; k < D; ++k)
      q[k] = std::uint32_t((c.net.points[i][k] - lo[k]) / (hi[k] - lo[k]) * double((1u << 20) - 1));
    key[i] = {sm::internal::morton_code<D>(q), sm::Index(i)};
  }
  std::sort(key.begin(), key.end());
  std::vector<sm::Index> new_of(n);
  std::vector<std::array<double, D>> points(n);
  Case<D> r;
  r.roles.resize(n);
  for(std::size_t k = 0; k < n; ++k) {
    new_of[key[k].second] = sm::Index(k);
    points[k] = c.net.points[key[k].second];
    r.roles[k] = c.roles[key[k].second];
  }
  std::vector<std::array<sm::Index, D + 1>> elements;
  for(const auto& e : c.net.elements) {
    std::array<sm::Index, D + 1> f;
    for(int k = 0; k <= D; ++k)
      f[std::size_t(k)] = new_of[e[std::size_t(k)]];
    elements.push_back(f);
  }
  std::stable_sort(elements.begin(), elements.end(), [](const auto& a, const auto& b) {
    return *std::min_element(a.begin(), a.end()) < *std::min_element(b.begin(), b.end());
  });
  r.name = c.name;
  r.net = sm::make_spring_network<D>(std::move(points), std::move(elements));
  r.motion = c.motion;
  r.steps = c.steps;
  r.of_steps = c.of_steps;
  return r;
}

// The whole run (default threads) on the case as meshed and numbered along
// a Morton curve: solver iterations and run time of each, as a table.
template <int D>
std::string numbering_table(const Case<D>& c)
{
  progress(c.name + ": the run as meshed and with the vertices numbered along a Morton curve");
  const Case<D> spatial = spatially_numbered(c);
  std::ostringstream out;
  char line[160];
  std::snprintf(line, sizeof line, "\nVertex numbering, %s, grid-scaled, %zu steps, default threads:\n", c.name.c_str(),
                c.steps);
  out << line;
  std::snprintf(line, sizeof line, "%-34s %10s %8s\n", "numbering", "iterations", "run s");
  out << line;
  for(const Case<D>* k : {&c, &spatial}) {
    const auto rep = run_once<D>(*k, sm::Solver_options{}, nullptr);
    std::size_t iterations = 0;
    for(const auto& s : rep.steps)
      iterations += s.iterations;
    std::snprintf(line, sizeof line, "%-34s %10zu %8.3f%s\n", k == &c ? "as meshed" : "along a Morton curve",
                  iterations, rep.seconds_total, rep.completed ? "" : " (not completed)");
    out << line;
  }
  return out.str();
}

// ---- relaxation factor ------------------------------------------------------------------

// The solver's parameters on the first three steps of a case's motion (one
// thread): SOR (error-estimate rule, tolerance 1e-6) and conjugate gradients
// with a symmetric-SOR(omega) preconditioner against the relaxation factor,
// then the multigrid's strength and correction factor about their defaults:
// iterations and solve time summed over the steps, and the largest true
// error of a step's solve against SimplicialLDLT on its captured system.
template <int D>
void omega_table(const Case<D>& c)
{
  Case<D> first = c;
  first.of_steps = c.of_steps * 3 / c.steps; // the schedule's first three steps...
  first.steps = 3;
  first.capture_steps = {1, 2, 3};
  auto row = [&](const sm::Solver_options& o, std::size_t& iters, double& ms, double& err) {
    std::vector<Captured_system<D>> caps;
    run_once(first, o, &caps);
    iters = 0;
    ms = 0;
    err = 0;
    for(const auto& cap : caps) {
      iters += cap.iterations;
      ms += 1e3 * cap.seconds;
      const auto e = to_eigen<D>(cap);
      err = std::max(err, max_difference<D>(as_matrix<D>(cap.solution), reference_solution<D>(cap, e, true)));
    }
  };
  std::printf("\n%s: relaxation factor, summed over the systems of steps 1-3 of %zu (1 thread)\n%6s %12s %12s %12s "
              "%12s %12s\n",
              c.name.c_str(), c.steps, "omega", "SOR sweeps", "SOR max err", "CG iters", "CG ms", "CG max err");
  for(double omega : {1.0, 1.1, 1.2, 1.3, 1.4, 1.5, 1.6, 1.7, 1.8, 1.85, 1.9, 1.95, 1.98}) {
    progress(c.name + ": omega " + std::to_string(omega));
    sm::Solver_options sor;
    sor.threads = 1;
    sor.method = sm::Solver_method::sor;
    sor.relaxation_factor = omega;
    sor.max_iterations = 20000;
    std::size_t sweeps = 0, iters = 0;
    double sor_ms = 0, sor_err = 0, ms = 0, err = 0;
    row(sor, sweeps, sor_ms, sor_err);
    sm::Solver_options cg;
    cg.threads = 1;
    cg.preconditioner_relaxation_factor = omega;
    row(cg, iters, ms, err);
    std::printf("%6.2f %12zu %12.2e %12zu %12.2f %12.2e\n", omega, sweeps, sor_err, iters, ms, err);
  }
  std::printf("\n%s: multigrid preconditioner (default solver otherwise), same steps, 1 thread\n%9s %11s %12s "
              "%10s %12s\n",
              c.name.c_str(), "strength", "correction", "CG iters", "CG ms", "CG max err");
  const sm::Solver_options defaults;
  auto multigrid_row = [&](double strength, double correction) {
    sm::Solver_options o;
    o.threads = 1;
    o.multigrid_strength = strength;
    o.multigrid_correction = correction;
    std::size_t iters = 0;
    double ms = 0, err = 0;
    row(o, iters, ms, err);
    std::printf("%9.2f %11.2f %12zu %10.2f %12.2e\n", strength, correction, iters, ms, err);
  };
  for(double strength : {0.0, 0.02, 0.04, 0.08, 0.12, 0.16, 0.25})
    multigrid_row(strength, defaults.multigrid_correction);
  for(double correction : {1.0, 1.1, 1.2, 1.3, 1.4, 1.5, 1.6, 1.8})
    multigrid_row(defaults.multigrid_strength, correction);
}

// ---- output ----------------------------------------------------------------------------

void print_table(const std::vector<Row>& rows)
{
  std::printf("\nPer case and thread count. Run: whole motion with the grid-scaled model (median over repeats);\n"
              "ms/step: median per step of stiffness / solve / exact check; it: solver iterations per step (mean);\n"
              "err: max |ours - reference| on the captured systems (ref: SimplicialLDLT, or for the largest case a\n"
              "CG solve to 1e-13); IC x, LDLT x: Eigen's time / ours on the same systems at equal or smaller error;\n"
              "sweep: one SOR sweep vs the traffic bound (bytes / triad bandwidth measured beside each sweep; medians of\n"
              "3); x2thr: 1-thread run / 2-thread run.\n\n");
  std::printf("%-26s %9s %4s %6s %9s %8s %8s %8s %6s %9s %5s %7s %7s %8s %8s %6s %6s\n", "case", "nodes", "thr",
              "steps", "run s", "stiff", "solve", "check", "it", "err", "ref", "IC x", "LDLT x", "sweep ms", "bound ms",
              "ratio", "x2thr");
  for(const auto& r : rows) {
    if(!r.available) {
      std::printf("%-26s %s\n", r.name.c_str(), r.note.c_str());
      continue;
    }
    for(std::size_t k = 0; k < r.runs.size(); ++k) {
      const auto& s = r.runs[k];
      const auto& w = r.sweeps[k];
      char steps[32];
      if(r.steps == r.of_steps)
        std::snprintf(steps, sizeof steps, "%zu", r.steps);
      else
        std::snprintf(steps, sizeof steps, "%zu/%zu", r.steps, r.of_steps);
      char ic[16], ld[16];
      std::snprintf(ic, sizeof ic, "%s%.2f", r.cmp.ic_reached ? "" : ">", r.cmp.ic_seconds / r.cmp.ours_seconds);
      if(r.cmp.ldlt)
        std::snprintf(ld, sizeof ld, "%.2f", r.cmp.ldlt_seconds / r.cmp.ours_seconds);
      else
        std::snprintf(ld, sizeof ld, "n/a");
      std::printf("%-26s %9zu %4d %6s %9.3f %8.3f %8.3f %8.3f %6.1f %9.2e %5s %7s %7s %8.3f %8.3f %6.2f %6.2f%s\n",
                  k == 0 ? r.name.c_str() : "", r.nodes, s.threads, steps, s.total, 1e3 * s.stiffness,
                  1e3 * s.solve, 1e3 * s.check, s.iterations, r.cmp.error, k == 0 ? (r.cmp.ldlt ? "LDLT" : "CG") : "",
                  k == 0 ? ic : "", k == 0 ? ld : "", 1e3 * w.seconds, 1e3 * w.bound, w.ratio,
                  k == 0 ? 1.0 : r.runs[0].total / s.total, s.completed ? "" : " (not completed)");
    }
  }
}

struct Target
{
  std::string what, target, measured;
  bool met;
  std::string margin;
};

// Block (element-model) against scalar (edge-model) systems on one mesh, one
// thread: the 2D torsional and ball-vertex models (alone and added to the
// grid-scaled springs) and the grid-scaled model through the same solver
// (ordering, block Gauss-Seidel, multigrid on D x D blocks).
struct Block_row
{
  std::string model;
  std::size_t steps = 0;
  double iterations = 0;    // per step, mean
  double solve_ms = 0;      // per step, median
  double stiffness_ms = 0;  // per step, median (assembly included)
  double ms_per_iteration = 0;
  double error = -1;        // max |ours - LDLT| on the captured systems; -1: not computed
  // every step's times, over all rounds
  std::vector<double> solve, stiffness;
  std::size_t iterations_total = 0;
};

// One run of `model` added to row b: its steps' times, and in the first
// round the iterations and (`steps` 0: the whole motion) the error on the
// captured systems. `steps`: only the first steps of the case's schedule,
// and no comparison with a direct solve (the wing's block systems are too
// large for one).
template <int D, class Model>
void add_block_run(const Case<D>& c, const Model& model, std::size_t steps, bool first_round, Block_row& b)
{
  progress(c.name + ": " + b.model + " (1 thread)");
  std::vector<Captured_system<D>> caps;
  sm::Solver_options o;
  o.threads = 1;
  const auto rep = run_once(c, o, steps || !first_round ? nullptr : &caps, model, steps);
  for(const auto& s : rep.steps) {
    b.solve.push_back(s.seconds_solve);
    b.stiffness.push_back(s.seconds_stiffness);
    b.iterations_total += s.iterations;
  }
  if(!first_round)
    return;
  b.steps = rep.steps.size();
  for(const auto& cap : caps)
    b.error = std::max(b.error, max_difference<D>(as_matrix<D>(cap.solution),
                                                  reference_solution<D>(cap, to_eigen<D>(cap), true)));
}

// The block table's rows, one per model, measured in `rounds` rounds that
// each run every model once, in turn: a slow spell of a shared machine then
// falls on all models alike instead of on the one that ran during it, and
// the ratios between rows (the cost targets) compare like with like. Times:
// medians over the steps of all rounds.
template <int D, class... Models>
std::vector<Block_row> block_rows_alternated(const Case<D>& c, std::size_t steps, int rounds,
                                             const std::vector<std::string>& names, const Models&... models)
{
  std::vector<Block_row> rows(sizeof...(Models));
  for(std::size_t k = 0; k < rows.size(); ++k)
    rows[k].model = names[k];
  for(int r = 0; r < rounds; ++r) {
    std::size_t k = 0;
    (add_block_run(c, models, steps, r == 0, rows[k++]), ...);
  }
  for(auto& b : rows) {
    const std::size_t samples = std::max<std::size_t>(1, b.solve.size());
    b.iterations = double(b.iterations_total) / double(samples);
    b.solve_ms = 1e3 * median(b.solve);
    b.stiffness_ms = 1e3 * median(b.stiffness);
    double total_solve = 0;
    for(double t : b.solve)
      total_solve += t;
    b.ms_per_iteration = 1e3 * total_solve / double(std::max<std::size_t>(1, b.iterations_total));
  }
  return rows;
}

// time per step (stiffness + solve, medians) of row k over row 0's
double step_ratio(const std::vector<Block_row>& rows, std::size_t k)
{
  return (rows[k].solve_ms + rows[k].stiffness_ms) / (rows[0].solve_ms + rows[0].stiffness_ms);
}

void print_block_rows(const std::string& mesh, const std::vector<Block_row>& rows, int rounds)
{
  std::printf("\nBlock vs scalar systems, %s, 1 thread, default solver; ms: medians over the steps of %d "
              "rounds, each running every model in turn (err: max |ours - LDLT| on the captured systems):\n"
              "%-28s %6s %8s %10s %10s %12s %9s\n",
              mesh.c_str(), rounds, "model", "steps", "it/step", "solve ms", "stiff ms", "ms/iteration", "err");
  for(const auto& r : rows) {
    char err[16] = "n/a";
    if(r.error >= 0)
      std::snprintf(err, sizeof err, "%.2e", r.error);
    std::printf("%-28s %6zu %8.1f %10.3f %10.3f %12.4f %9s\n", r.model.c_str(), r.steps, r.iterations, r.solve_ms,
                r.stiffness_ms, r.ms_per_iteration, err);
  }
  for(std::size_t k = 1; k < rows.size(); ++k)
    std::printf("%s / %s: %.2fx the iterations per step, %.2fx the time per iteration, %.2fx the time per step\n",
                rows[k].model.c_str(), rows[0].model.c_str(), rows[k].iterations / rows[0].iterations,
                rows[k].ms_per_iteration / rows[0].ms_per_iteration, step_ratio(rows, k));
}

// The cost targets of the robust models: time per step (stiffness + solve)
// against the grid-scaled model's on the same mesh, one thread.
void block_targets(const std::vector<Block_row>& rows, const std::string& mesh, const std::string& model,
                   double bound, std::vector<Target>& ts)
{
  for(std::size_t k = 1; k < rows.size(); ++k)
    if(rows[k].model.rfind(model + " (", 0) == 0) { // "ball_vertex_p2 (", not "ball_vertex_p2.5 ("
      const double x = step_ratio(rows, k);
      char buf[160], b[32], m[64];
      std::snprintf(buf, sizeof buf, "%.2fx (%.1f / %.1f ms)", x, rows[k].solve_ms + rows[k].stiffness_ms,
                    rows[0].solve_ms + rows[0].stiffness_ms);
      std::snprintf(b, sizeof b, "<= %gx", bound);
      std::snprintf(m, sizeof m, "%.2fx vs %gx", x, bound);
      ts.push_back({mesh + ", " + model + " / grid-scaled per step", b, buf, x <= bound, m});
    }
}


// ---- the command-line program, as a user runs it ---------------------------------------

// The case's mesh as a Medit file with labelled boundary facets: 1 on the
// moving body (every vertex of the facet moving), 2 elsewhere.
template <int D>
void write_case_mesh(const Case<D>& c, const std::string& path)
{
  sm::Indexed_mesh<D> m;
  m.points = c.net.points;
  for(const auto& e : c.net.elements) {
    typename sm::Indexed_mesh<D>::Element el;
    for(int k = 0; k <= D; ++k)
      el[std::size_t(k)] = std::uint32_t(e[std::size_t(k)]);
    m.elements.push_back(el);
    m.element_labels.push_back(10);
  }
  // the network's boundary facets (a map of all facets would take gigabytes on the box)
  for(const auto& bf : c.net.boundary_facets) {
    std::array<std::uint32_t, D> f;
    bool moving = true;
    for(int k = 0; k < D; ++k) {
      f[std::size_t(k)] = std::uint32_t(bf[std::size_t(k)]);
      moving = moving && c.roles[bf[std::size_t(k)]] == sm::Vertex_role::moving;
    }
    m.boundary_facets.push_back(f);
    m.boundary_labels.push_back(moving ? 1 : 2);
  }
  m.label_names = {{1, "body"}, {2, "outer"}};
  sm::write_medit(m, path);
}

#ifdef SPRING_MOTION_BENCH_CLI

struct Process_stats
{
  double seconds = 0;     // wall clock, fork to exit
  double peak_mib = std::numeric_limits<double>::quiet_NaN(); // the child's peak resident memory, NaN: not measured
  int status = -1;        // exit status
};

// GNU time, which reports the peak memory of a child it forks itself.
const char* const gnu_time = "/usr/bin/time";

// Runs `args` with stdout and stderr sent to `log`: wall time, exit status
// and peak resident memory. The memory comes from GNU time, not from wait4:
// a child forked from this (large) process inherits its resident pages, and
// the kernel carries that high-water mark into the child's ru_maxrss across
// exec, so wait4 would report the benchmark's own size. Without GNU time
// (Debian package `time`) the memory is not measured.
//
// Started by posix_spawn, which glibc runs as a vfork (the child shares this
// process's memory until its exec), not by fork: fork copies the page tables
// of the benchmark, several hundred MiB resident after the box, and that
// copy was timed as part of the command's run (the 2D paper case read about
// 30 ms slower here than from a shell).
Process_stats run_process(const std::vector<std::string>& args, const std::string& log)
{
  const bool timed = access(gnu_time, X_OK) == 0;
  const std::string peak_file = log + ".peak";
  std::vector<std::string> full;
  if(timed)
    full = {gnu_time, "-f", "%M", "-o", peak_file};
  full.insert(full.end(), args.begin(), args.end());
  std::vector<char*> argv;
  for(const auto& a : full)
    argv.push_back(const_cast<char*>(a.c_str()));
  argv.push_back(nullptr);
  posix_spawn_file_actions_t files;
  posix_spawn_file_actions_init(&files);
  posix_spawn_file_actions_addopen(&files, 1, log.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
  posix_spawn_file_actions_adddup2(&files, 1, 2);
  const auto t0 = Clock::now();
  pid_t pid = -1;
  if(posix_spawn(&pid, argv[0], &files, nullptr, argv.data(), environ) != 0)
    pid = -1;
  posix_spawn_file_actions_destroy(&files);
  Process_stats p;
  int status = 0;
  if(pid > 0 && waitpid(pid, &status, 0) == pid) {
    p.seconds = seconds_since(t0);
    p.status = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
    if(timed) {
      // the last line holds %M in KiB (a failed command adds a line before it)
      std::ifstream in(peak_file);
      std::string line, last;
      while(std::getline(in, line))
        if(!line.empty())
          last = line;
      if(!last.empty() && last.find_first_not_of("0123456789") == std::string::npos)
        p.peak_mib = std::stod(last) / 1024.0;
      std::remove(peak_file.c_str());
    }
  }
  return p;
}

// Two processes that only spin, as a flow solver beside the mesh mover would.
struct Busy_cores
{
  std::vector<pid_t> pids;
  explicit Busy_cores(int n)
  {
    for(int i = 0; i < n; ++i) {
      const pid_t pid = fork();
      if(pid == 0) {
        volatile double x = 1;
        for(;;)
          x = x * 1.0000001 + 1e-9;
      }
      pids.push_back(pid);
    }
  }
  ~Busy_cores()
  {
    for(pid_t p : pids)
      if(p > 0) {
        kill(p, SIGKILL);
        waitpid(p, nullptr, 0);
      }
  }
};

struct Cli_row
{
  std::string what;
  std::size_t elements = 0;
  Process_stats median; // seconds: median of the repeats; peak: largest
  int runs = 0;
};

Cli_row cli_runs(const std::string& what, const std::vector<std::string>& args, std::size_t elements, int repeats,
                 const std::string& log)
{
  Cli_row r;
  r.what = what;
  r.elements = elements;
  std::vector<double> t;
  for(int i = 0; i < repeats; ++i) {
    const auto p = run_process(args, log);
    t.push_back(p.seconds);
    r.median.peak_mib = std::fmax(r.median.peak_mib, p.peak_mib); // NaN (not measured) only if every run's is
    if(i == 0 || r.median.status == 0)
      r.median.status = p.status; // the first failure's status
  }
  r.median.seconds = median(t);
  r.runs = repeats;
  return r;
}

struct Cli_results
{
  std::vector<Cli_row> rows;
  std::optional<Cli_row> busy_default, busy_one; // the wing beside two spinning processes
};

// The 2D paper case and the wing through `spring-motion deform`, as the
// targets are stated: the whole process, reading and writing included.
Cli_results measure_cli(const Setup& setup)
{
  Cli_results out;
  const std::string dir = "spring_motion_bench_cache";
  std::filesystem::create_directories(dir);
  const std::string cli = SPRING_MOTION_BENCH_CLI;
  const std::string steps = setup.quick ? "20" : "100";
  {
    const auto c = naca_case(false, setup);
    write_case_mesh(c, dir + "/naca0012_2d_paper.mesh");
    progress("spring-motion on the 2D paper case (" + std::to_string(c.net.number_of_elements()) + " triangles)");
    out.rows.push_back(cli_runs("2D paper case, grid_scaled, " + steps + " steps to 45 deg",
                                {cli, "deform", dir + "/naca0012_2d_paper.mesh", "--moving", "1", "--pitch", "45",
                                 "--center", "0.25,0", "--steps", steps, "--quiet", "--output", dir + "/cli_2d.vtu"},
                                c.net.number_of_elements(), setup.quick ? 1 : setup.repeats, dir + "/cli_2d.log"));
  }
#ifdef SPRING_MOTION_BENCH_HAS_WING
  try {
    const auto c = wing_case(setup);
    const std::string mesh = dir + "/wing_3d.mesh";
    write_case_mesh(c, mesh);
    const std::string wsteps = setup.quick ? "10" : "100";
    const std::vector<std::string> wing = {cli, "deform", mesh, "--moving", "1", "--pitch", "30", "--center",
                                           "0.25,0,0", "--steps", wsteps, "--quiet"};
    auto with = [&](std::vector<std::string> a, const std::vector<std::string>& more) {
      a.insert(a.end(), more.begin(), more.end());
      return a;
    };
    const std::size_t tets = c.net.number_of_elements();
    // the target's model runs 3 times (its time varies by about 1 s run to
    // run on these machines: the median), the slower ball-vertex model once
    for(const std::string model : {"grid_scaled", "ball_vertex_p2"}) {
      progress("spring-motion on the wing, " + model);
      const int runs = setup.quick || model != "grid_scaled" ? 1 : 3;
      out.rows.push_back(cli_runs("wing, " + model + ", " + wsteps + " steps to 30 deg",
                                  with(wing, {"--model", model, "--output", dir + "/cli_wing.vtu"}), tets, runs,
                                  dir + "/cli_wing_" + model + ".log"));
    }
    // the busy machine: two spinning processes on the 2 cores; default
    // threads and one thread alternately, 20 steps each, median of 3
    progress("spring-motion on the wing beside two CPU-bound processes");
    const std::vector<std::string> busy = {cli,        "deform", mesh,     "--moving", "1",
                                           "--pitch",  "10",     "--center", "0.25,0,0", "--steps",
                                           setup.quick ? "5" : "20", "--quiet"};
    Busy_cores spin(2);
    std::vector<double> td, t1;
    for(int i = 0; i < (setup.quick ? 1 : 3); ++i) {
      td.push_back(run_process(busy, dir + "/cli_busy.log").seconds);
      t1.push_back(run_process(with(busy, {"--threads", "1"}), dir + "/cli_busy.log").seconds);
    }
    out.busy_default = Cli_row{"wing, default threads, busy", tets, {median(td), 0, 0}, int(td.size())};
    out.busy_one = Cli_row{"wing, 1 thread, busy", tets, {median(t1), 0, 0}, int(t1.size())};
  } catch(const std::exception& e) {
    progress(std::string("the wing through the command line: not available: ") + e.what());
  }
#endif
  if(!setup.quick) {
    // peak memory on the largest mesh: it does not depend on the number of
    // steps, so 2 small ones (the time is not a target)
    const auto c = box_case(setup.box, setup);
    const std::string mesh = dir + "/box_3d.mesh";
    progress("writing the box as " + mesh);
    write_case_mesh(c, mesh);
    progress("spring-motion on the box (" + std::to_string(c.net.number_of_elements()) + " tetrahedra)");
    out.rows.push_back(cli_runs(c.name + ", grid_scaled, 2 steps to 1 deg",
                                {cli, "deform", mesh, "--moving", "1", "--pitch", "1", "--center", "0.5,0.5,0.5",
                                 "--steps", "2", "--quiet", "--output", dir + "/cli_box.vtu"},
                                c.net.number_of_elements(), 1, dir + "/cli_box.log"));
    std::filesystem::remove(mesh); // a few hundred MB
  }
  return out;
}

void print_cli(const Cli_results& r)
{
  std::printf("\nThe command-line program (whole process: reading, every step with its exact check, writing "
              "the VTU):\n");
  std::printf("%-50s %9s %8s %6s %9s %10s %s\n", "run", "elements", "wall s", "runs", "peak MiB", "B/element",
              "exit");
  for(const auto& c : r.rows)
    std::printf("%-50s %9zu %8.3f %6d %9.1f %10.0f %d\n", c.what.c_str(), c.elements, c.median.seconds, c.runs,
                c.median.peak_mib, c.median.peak_mib * 1048576.0 / double(c.elements), c.median.status);
  if(r.busy_default && r.busy_one)
    std::printf("%-50s %9zu %8.3f %6d\n%-50s %9zu %8.3f %6d\n", r.busy_default->what.c_str(),
                r.busy_default->elements, r.busy_default->median.seconds, r.busy_default->runs,
                r.busy_one->what.c_str(), r.busy_one->elements, r.busy_one->median.seconds, r.busy_one->runs);
}
#endif

#ifndef SPRING_MOTION_BENCH_CLI
struct Cli_results
{
};
#endif

// The targets the command-line runs decide: whole process, peak memory, the
// busy machine.
void cli_targets(const Cli_results& cli, std::vector<Target>& ts)
{
#ifdef SPRING_MOTION_BENCH_CLI
  char buf[160], m[160];
  auto find = [&](const std::string& prefix) -> const Cli_row* {
    for(const auto& r : cli.rows)
      if(r.what.rfind(prefix, 0) == 0)
        return &r;
    return nullptr;
  };
  auto whole = [&](const std::string& prefix, const std::string& what, double bound) {
    const Cli_row* r = find(prefix);
    if(!r)
      return;
    const bool completed = r->median.status == 0;
    std::snprintf(buf, sizeof buf, "%.3f s (exit %d)", r->median.seconds, r->median.status);
    if(completed)
      std::snprintf(m, sizeof m, "%.2fx the target", r->median.seconds / bound);
    else
      std::snprintf(m, sizeof m, "run NOT completed (exit %d: an element would invert)", r->median.status);
    char b[32];
    std::snprintf(b, sizeof b, "<= %g s", bound);
    ts.push_back({what, b, buf, completed && r->median.seconds <= bound, m});
  };
  whole("2D paper case", "2D paper case, spring-motion process, 100 steps to 45 deg", 0.1);
  whole("wing, grid_scaled", "wing, spring-motion process, grid_scaled", 4);
  whole("wing, ball_vertex_p2", "wing, spring-motion process, ball_vertex_p2", 8);
  if(const Cli_row* r = find("wing, grid_scaled")) {
    const double b = r->median.peak_mib * 1048576.0 / double(r->elements);
    if(std::isnan(b))
      std::snprintf(buf, sizeof buf, "not measured (no %s)", gnu_time);
    else
      std::snprintf(buf, sizeof buf, "%.0f B (%.1f MiB, %zu tets)", b, r->median.peak_mib, r->elements);
    std::snprintf(m, sizeof m, "%.2fx the target", b / 400);
    ts.push_back({"peak memory per tetrahedron, wing, spring-motion", "<= 400 B", buf, b <= 400, m});
  }
  if(const Cli_row* w = find("wing, grid_scaled"))
    if(const Cli_row* b = find("box")) {
      // peak memory against elements, wing -> box
      const double p = std::log(b->median.peak_mib / w->median.peak_mib) / std::log(double(b->elements) / double(w->elements));
      std::snprintf(buf, sizeof buf, "n^%.2f (%.0f -> %.0f MiB, %.0f -> %.0f B/tet)", p, w->median.peak_mib,
                    b->median.peak_mib, w->median.peak_mib * 1048576.0 / double(w->elements),
                    b->median.peak_mib * 1048576.0 / double(b->elements));
      std::snprintf(m, sizeof m, "exponent %.2f vs 1.0", p);
      ts.push_back({"peak memory growth, spring-motion, wing -> box", "<= n^1.0", buf, p <= 1.0, m});
    }
  if(cli.busy_default && cli.busy_one) {
    const double x = cli.busy_default->median.seconds / cli.busy_one->median.seconds;
    std::snprintf(buf, sizeof buf, "%.2fx (%.2f s / %.2f s, median of %d)", x, cli.busy_default->median.seconds,
                  cli.busy_one->median.seconds, cli.busy_default->runs);
    std::snprintf(m, sizeof m, "%.2fx vs 1.25x", x);
    ts.push_back({"busy machine: default threads / 1 thread, wing", "<= 1.25x", buf, x <= 1.25, m});
  }
#else
  (void)cli;
  (void)ts;
#endif
}

void print_targets(const std::vector<Row>& rows, const Cli_results& cli, bool quick,
                   const std::vector<Block_row>& block_2d, const std::vector<Block_row>& block_wing)
{
  std::vector<Target> ts;
  auto find = [&](const std::string& prefix) -> const Row* {
    for(const auto& r : rows)
      if(r.available && r.name.rfind(prefix, 0) == 0)
        return &r;
    return nullptr;
  };
  auto best = [](const Row& r) {
    double t = 1e300;
    for(const auto& s : r.runs)
      t = std::min(t, s.total);
    return t;
  };
  char buf[160];
  // the run's time on the benchmark's own clock (reading, writing and process
  // start-up aside: the command line adds those, see docs/performance.md)
  auto run_target = [&](const Row& r, const std::string& what, double bound) {
    const double t = best(r);
    std::snprintf(buf, sizeof buf, "%.3f s, err %.1e", t, r.cmp.error);
    char m[128];
    std::snprintf(m, sizeof m, "%.2fx the target", t / bound);
    if(!r.runs[0].completed) { // what the whole run would take at the same cost per step
      const double whole = t * double(r.steps) / double(std::max<std::size_t>(1, r.runs[0].steps_run));
      std::snprintf(m, sizeof m, "run NOT completed (stopped at step %zu); %zu steps pro rata %.2f s",
                    r.runs[0].steps_run, r.steps, whole);
    }
    char b[32];
    std::snprintf(b, sizeof b, "<= %g s", bound);
    ts.push_back({what, b, buf, t <= bound && r.cmp.error <= 1e-6 && r.runs[0].completed, m});
  };
  // the median step's stiffness phase, best thread count
  auto stiffness_ms = [](const Row& r) {
    double t = 1e300;
    for(const auto& s : r.runs)
      t = std::min(t, s.stiffness);
    return 1e3 * t;
  };
  auto stiffness_target = [&](const Row& r, double bound_ms) {
    const double t = stiffness_ms(r);
    std::snprintf(buf, sizeof buf, "%.1f ms (%s)", t, r.name.c_str());
    char m[64], b[32];
    std::snprintf(m, sizeof m, "%.2fx the target", t / bound_ms);
    std::snprintf(b, sizeof b, "<= %g ms", bound_ms);
    ts.push_back({"stiffness per step, " + r.name, b, buf, t <= bound_ms, m});
  };
  if(const Row* r = find("NACA0012 2D coarse"))
    run_target(*r, "2D paper case, grid-scaled, " + std::to_string(r->steps) + " steps to 45 deg", 0.1);
  if(const Row* r = find("wing")) {
    run_target(*r, "3D wing, grid-scaled, " + std::to_string(r->steps) + " steps to 30 deg", 4);
    stiffness_target(*r, 15);
  }
  if(const Row* r = find("box"))
    stiffness_target(*r, 150);
  {
    const Row* a = find("wing");
    std::string from = "wing";
    if(!a) {
      a = find("NACA0012 2D fine");
      from = "2D fine (no wing mesh)";
    }
    const Row* b = find("box");
    if(a && b) {
      // the median step's stiffness + solve + check, best thread count: the
      // run time per step would also spread the one-off costs (ordering,
      // aggregation, the final quality pass over every element) over the
      // steps run, 100 on the wing but 10 on the box
      auto per_step = [&](const Row& r) {
        double t = 1e300;
        for(const auto& s : r.runs)
          t = std::min(t, s.stiffness + s.solve + s.check);
        return t;
      };
      const double p = std::log(per_step(*b) / per_step(*a)) / std::log(double(b->nodes) / double(a->nodes));
      std::snprintf(buf, sizeof buf, "n^%.2f (%s -> box, median step)", p, from.c_str());
      char m[64];
      std::snprintf(m, sizeof m, "exponent %+.2f vs 1.0", p - 1.0);
      ts.push_back({"cost per step scaling", "<= n^1.0", buf, p <= 1.0, m});
    }
  }
  {
    const Row* r = find("box");
    if(!r)
      r = find("NACA0012 2D fine");
    if(r) {
      const auto& w = r->sweeps[0];
      std::snprintf(buf, sizeof buf, "%.2fx bound (%s, 1 thr)", w.ratio, r->name.c_str());
      char m[64];
      std::snprintf(m, sizeof m, "%.2fx vs 1.5x", w.ratio);
      ts.push_back({"one SOR sweep vs traffic bound", "<= 1.5x", buf, w.ratio <= 1.5, m});
    }
  }
  {
    double worst = 1e300;
    std::string where;
    for(const auto& r : rows)
      if(r.available) {
        const double x = r.cmp.ic_seconds / r.cmp.ours_seconds;
        if(x < worst) {
          worst = x;
          where = r.name;
        }
      }
    if(!where.empty()) {
      std::snprintf(buf, sizeof buf, "%.2fx (worst: %s)", worst, where.c_str());
      char m[64];
      std::snprintf(m, sizeof m, "%.2fx vs 2x", worst);
      ts.push_back({"default solver vs Eigen CG+IC", ">= 2x faster", buf, worst >= 2, m});
    }
  }
  if(!block_2d.empty())
    block_targets(block_2d, "2D paper mesh", "ball_vertex_p2", 1.5, ts);
  if(!block_wing.empty()) {
    block_targets(block_wing, "wing", "ball_vertex_p2", 3, ts);
    block_targets(block_wing, "wing", "ball_vertex_p2.5", 3, ts);
    block_targets(block_wing, "wing", "ball_vertex_p3", 3, ts);
  }
  cli_targets(cli, ts);
  std::printf("\nTargets%s:\n", quick ? " -- QUICK RUN, smaller cases: not the real check" : "");
  std::printf("%-58s %-14s %-44s %-5s %s\n", "target", "bound", "measured", "met?", "by how much");
  for(const auto& t : ts)
    std::printf("%-58s %-14s %-44s %-5s %s\n", t.what.c_str(), t.target.c_str(), t.measured.c_str(),
                t.met ? "yes" : "NO", t.margin.c_str());
  std::printf("Measured elsewhere: OpenFOAM side by side (bench/openfoam/compare.sh, docs/performance.md).\n");
}

Setup parse(int argc, char** argv)
{
  Setup s;
  bool box_given = false;
  for(int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    auto value = [&]() -> std::string {
      if(i + 1 >= argc) {
        std::cerr << "spring_motion_bench: " << a << " needs a value\n";
        std::exit(2);
      }
      return argv[++i];
    };
    if(a == "--quick")
      s.quick = true;
    else if(a == "--box") {
      s.box = std::stoul(value());
      box_given = true;
    } else if(a == "--write-box")
      s.write_box = value();
    else if(a == "--omega-table")
      s.omega_table = true;
    else if(a == "--every-step-error")
      s.every_step_error = true;
    else if(a == "--repeats")
      s.repeats = std::stoi(value());
    else if(a == "--cases") {
      s.cases.clear();
      std::stringstream in(value());
      for(std::string m; std::getline(in, m, ',');)
        s.cases.push_back(m);
    } else {
      std::cerr << "usage: spring_motion_bench [--quick] [--cases naca_coarse,naca_fine,wing,box,cli] [--box N]"
                   " [--repeats R] [--omega-table] [--every-step-error] [--write-box FILE]\n";
      std::exit(a == "--help" ? 0 : 2);
    }
  }
  if(s.quick && !box_given)
    s.box = 16;
  return s;
}

bool wanted(const Setup& s, const std::string& c)
{
  return std::find(s.cases.begin(), s.cases.end(), c) != s.cases.end();
}

} // namespace

int main(int argc, char** argv)
{
  const Setup setup = parse(argc, argv);
  if(!setup.write_box.empty()) {
    const auto c = box_case(setup.box, setup);
    try {
      write_case_mesh(c, setup.write_box); // nothing left behind on failure (write_medit)
    } catch(const std::exception& e) {
      std::cerr << "spring_motion_bench: " << e.what() << "\n";
      return 1;
    }
    std::printf("wrote %s: %zu vertices, %zu tetrahedra (%s)\n", setup.write_box.c_str(), c.net.points.size(),
                c.net.number_of_elements(), c.name.c_str());
    return 0;
  }
  progress("measuring memory bandwidth (triad)");
  const std::size_t triad_n = setup.quick ? (std::size_t(1) << 22) : (std::size_t(1) << 25);
  const std::vector<double> bandwidth = {triad_bandwidth(1, triad_n), triad_bandwidth(2, triad_n)};
  std::printf("SpringMotion benchmark%s. Triad bandwidth: %.2f GB/s (1 thread), %.2f GB/s (2 threads).\n",
              setup.quick ? " (--quick)" : "", bandwidth[0] * 1e-9, bandwidth[1] * 1e-9);
  {
    // what the thread chooser pays for each look at the other processes'
    // load, once a team step is about to start
    std::vector<double> us;
    int free = -1;
    for(int i = 0; i < 200; ++i) {
      const auto t0 = std::chrono::steady_clock::now();
      free = spring_motion::internal::free_cores();
      us.push_back(1e6 * std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count());
    }
    std::printf("Free-core read (thread chooser): %.1f us (median of 200), %d core(s) free of other processes.\n",
                median(us), free);
  }
  if(setup.every_step_error)
    std::printf("err of the 2D cases: over the systems of every step (--every-step-error).\n");
  if(setup.omega_table) {
    if(wanted(setup, "naca_coarse"))
      omega_table(naca_case(false, setup));
    if(wanted(setup, "naca_fine"))
      omega_table(naca_case(true, setup));
    return 0;
  }
  std::vector<Row> rows;
  std::vector<Block_row> block_rows, wing_block_rows, wing_torsional_rows;
  // rounds of the block tables (the wing's cost about 40 s each)
  const int block_rounds = setup.quick ? 1 : setup.repeats;
  const int wing_block_rounds = setup.quick ? 1 : std::min(setup.repeats, 3);
  std::string numbering; // the wing's iterations as meshed and numbered along a Morton curve
  if(wanted(setup, "naca_coarse")) {
    progress("building the coarse NACA0012 mesh");
    const auto c = naca_case(false, setup);
    rows.push_back(measure(c, triad_n));
    block_rows = block_rows_alternated(
        c, 0, block_rounds,
        {"grid-scaled (scalar)", "torsional (2x2 blocks)", "ball_vertex (2x2 blocks)", "ball_vertex_p2 (2x2 blocks)",
         "ball_vertex_p3 (2x2 blocks)", "grid_scaled+ball_vertex"},
        sm::Grid_scaled_stiffness{}, sm::Torsional_stiffness{}, sm::Ball_vertex_stiffness{},
        sm::Ball_vertex_stiffness{2.0}, sm::Ball_vertex_stiffness{3.0}, sm::With_ball_vertex<sm::Grid_scaled_stiffness>{});
  }
  if(wanted(setup, "naca_fine")) {
    progress("building the fine NACA0012 mesh");
    rows.push_back(measure(naca_case(true, setup), triad_n));
  }
  if(wanted(setup, "wing")) {
#ifdef SPRING_MOTION_BENCH_HAS_WING
    progress("building (or reading from ./spring_motion_bench_cache) the 3D wing mesh");
    try {
      const auto c = wing_case(setup);
      rows.push_back(measure(c, triad_n));
      // the robust models' cost on the same mesh over the whole motion: the
      // first steps alone take 5-20 iterations where most later steps take
      // 3, and read the block models cheaper than a whole run does
      // (docs/performance.md, "The wing's block ratio over the whole
      // motion"); the torsional model, whose stiffness costs 20 grid-scaled
      // steps, over the first steps only
      wing_block_rows = block_rows_alternated(c, setup.quick ? 3 : c.steps, wing_block_rounds,
                                              {"grid-scaled (scalar)", "ball_vertex_p2 (3x3 blocks)",
                                               "ball_vertex_p2.5 (3x3 blocks)", "ball_vertex_p3 (3x3 blocks)"},
                                              sm::Grid_scaled_stiffness{}, sm::Ball_vertex_stiffness{2.0},
                                              sm::Ball_vertex_stiffness{2.5}, sm::Ball_vertex_stiffness{3.0});
      wing_torsional_rows = block_rows_alternated(c, setup.quick ? 3 : 10, wing_block_rounds,
                                                  {"grid-scaled (scalar)", "torsional (3x3 blocks)"},
                                                  sm::Grid_scaled_stiffness{}, sm::Torsional_stiffness{});
      numbering = numbering_table(c);
    } catch(const std::exception& e) {
      Row r;
      r.name = "wing 3D";
      r.available = false;
      r.note = std::string("not available: ") + e.what();
      rows.push_back(r);
    }
#else
    Row r;
    r.name = "wing 3D";
    r.available = false;
    r.note = "not available: no 3D wing mesh in this build";
    rows.push_back(r);
#endif
  }
  if(wanted(setup, "box")) {
    progress("building the structured box mesh, N = " + std::to_string(setup.box));
    try {
      rows.push_back(measure(box_case(setup.box, setup), triad_n));
    } catch(const std::exception& e) {
      Row r;
      r.name = "box 3D";
      r.available = false;
      r.note = std::string("not available: ") + e.what();
      rows.push_back(r);
    }
  }
  print_table(rows);
  if(!block_rows.empty())
    print_block_rows("NACA0012 2D coarse (the paper's mesh)", block_rows, block_rounds);
  if(!wing_block_rows.empty())
    print_block_rows("wing 3D, the whole motion", wing_block_rows, wing_block_rounds);
  if(!wing_torsional_rows.empty())
    print_block_rows("wing 3D, the first steps of the run", wing_torsional_rows, wing_block_rounds);
  std::printf("%s", numbering.c_str());
  Cli_results cli;
#ifdef SPRING_MOTION_BENCH_CLI
  if(wanted(setup, "cli")) {
    cli = measure_cli(setup);
    print_cli(cli);
  }
#endif
  print_targets(rows, cli, setup.quick, block_rows, wing_block_rows);
  return 0;
}
