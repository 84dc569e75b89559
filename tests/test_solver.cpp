// The increment solvers (Solver_options.h): SOR for several omega and
// conjugate gradients against a direct sparse solve (Eigen SimplicialLDLT) of
// the system assembled here, for scalar (edge) and 2x2-block (torsional)
// systems; and the paper's max-change criterion (Eq. 12) stopping while the
// true error is still far above its tolerance.
#include <spring_motion/spring_motion.h>
#include <spring_motion/internal/solver/assemble.h>
#include <spring_motion/internal/solver/block_ops.h>
#include <spring_motion/internal/solver/stopping_test.h>
#include <spring_motion/internal/solver/warm_start.h>

#include "test_meshes.h"
#include "test_operators.h"

#include <catch2/catch.hpp>

#include <Eigen/Dense>
#include <Eigen/Sparse>
#include <Eigen/SparseCholesky>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#include <functional>
#include <initializer_list>
#include <limits>
#include <random>
#include <sstream>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

using namespace spring_motion;
using namespace spring_motion_test;

namespace {

using P2 = std::array<double, 2>;

auto on_hole = [](const P2& p) { return std::max(std::abs(p[0]), std::abs(p[1])) < 1.0; };

// How the edges enter the direct solve below: lineal springs k = 1/l on each
// component, the 2x2 block k e e^T / |e|^2 of the same spring along its
// edge, or no edge springs at all.
enum class Edges { per_component, truss, none };
using Element_matrix = std::function<void(const std::array<P2, 3>&, double*)>;

// The increment of one step from the initial mesh, solved directly: the
// global 2n x 2n stiffness is assembled here from the edge springs `edges`
// and, when given, the 6x6 element matrices `element` of every triangle
// (those of the models are checked against finite differences of their
// energies in test_stiffness.cpp); then K_ff d_f = -K_fc d_c.
std::vector<P2> direct_positions(const Spring_network<2>& net, const std::vector<Vertex_role>& roles,
                                 const std::vector<P2>& target, Edges edges, const Element_matrix& element)
{
  const bool truss = edges == Edges::truss;
  const std::size_t n = net.number_of_vertices();
  std::vector<int> unknown(n, -1);
  int nu = 0;
  for(std::size_t i = 0; i < n; ++i)
    if(roles[i] == Vertex_role::free)
      unknown[i] = nu++;
  std::vector<double> prescribed(2 * n, 0.0);
  for(std::size_t i = 0; i < n; ++i)
    for(int c = 0; c < 2; ++c)
      prescribed[2 * i + c] = target[i][c] - net.points[i][c];
  std::vector<Eigen::Triplet<double>> trip;
  Eigen::VectorXd rhs = Eigen::VectorXd::Zero(2 * nu);
  // K(2i + a, 2j + b) += v
  auto add = [&](std::size_t i, int a, std::size_t j, int b, double v) {
    if(unknown[i] < 0)
      return;
    const int r = 2 * unknown[i] + a;
    if(unknown[j] >= 0)
      trip.emplace_back(r, 2 * unknown[j] + b, v);
    else
      rhs(r) -= v * prescribed[2 * j + b];
  };
  for(const auto& e : net.edges) {
    if(edges == Edges::none)
      break;
    const double ex = net.points[e[1]][0] - net.points[e[0]][0], ey = net.points[e[1]][1] - net.points[e[0]][1];
    const double k = 1.0 / std::hypot(ex, ey), l2 = ex * ex + ey * ey;
    const double B[2][2] = {{truss ? k * ex * ex / l2 : k, truss ? k * ex * ey / l2 : 0},
                            {truss ? k * ex * ey / l2 : 0, truss ? k * ey * ey / l2 : k}};
    for(int s = 0; s < 2; ++s)
      for(int r = 0; r < 2; ++r)
        for(int c = 0; c < 2; ++c) {
          add(e[s], r, e[s], c, B[r][c]);
          add(e[s], r, e[1 - s], c, -B[r][c]);
        }
  }
  if(element)
    for(const auto& el : net.elements) {
      const std::array<P2, 3> p{net.points[el[0]], net.points[el[1]], net.points[el[2]]};
      std::array<double, 36> K{};
      element(p, K.data());
      for(int a = 0; a < 3; ++a)
        for(int b = 0; b < 3; ++b)
          for(int r = 0; r < 2; ++r)
            for(int c = 0; c < 2; ++c)
              add(el[a], r, el[b], c, K[(2 * a + r) * 6 + 2 * b + c]);
    }
  Eigen::SparseMatrix<double> A(2 * nu, 2 * nu);
  A.setFromTriplets(trip.begin(), trip.end());
  Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> ldlt(A);
  REQUIRE(ldlt.info() == Eigen::Success);
  const Eigen::VectorXd x = ldlt.solve(rhs);
  // the direct solution's own error is about cond(K) * eps |x|: check its
  // residual so that the comparisons below measure the iterative solver only
  REQUIRE((A * x - rhs).norm() <= 1e-12 * rhs.norm());
  std::vector<P2> out = target;
  for(std::size_t i = 0; i < n; ++i)
    if(unknown[i] >= 0)
      out[i] = {net.points[i][0] + x(2 * unknown[i]), net.points[i][1] + x(2 * unknown[i] + 1)};
  return out;
}

// Lineal springs k = 1/l acting as trusses along their edges, and no
// element matrix: the block system of an element model with
// Edge_spring_form::along_edge.
struct Truss_model
{
  Angle_kind angle_kind(int) const { return Angle_kind::none; }
  double operator()(double l, const double*, std::size_t, const Stiffness_context&) const { return 1.0 / l; }
  void add_element_matrix(const std::array<P2, 3>&, double*) const {}
  Edge_spring_form edge_spring_form() const { return Edge_spring_form::along_edge; }
};

struct Comparison
{
  double error = 0;   // max |solver - direct| over vertices and components
  double largest = 0; // max |direct - initial|: the size of the motion
  Deform_report report;
};

// One step of `model` (Lineal_stiffness{1}, Torsional_stiffness{},
// Truss_model or Ball_vertex_stiffness) turning the hole, compared with the
// direct solve.
template <class Model>
Comparison compare_with_direct(const Spring_network<2>& net, const Model& model, const Pitch_motion<2>& motion,
                               const Solver_options& solver)
{
  const auto roles = assign_roles(net, moving_boundary_where(on_hole));
  std::vector<P2> target = net.points;
  for(std::size_t i = 0; i < net.number_of_vertices(); ++i)
    if(roles[i] == Vertex_role::moving)
      target[i] = motion(net.points[i], 1.0);
  Edges edges = Edges::per_component;
  if(std::is_same<Model, Truss_model>::value)
    edges = Edges::truss;
  else if(std::is_same<Model, Ball_vertex_stiffness>::value)
    edges = Edges::none; // a pure element model
  Element_matrix element;
  if constexpr(!std::is_same<Model, Lineal_stiffness>::value)
    element = [&model](const std::array<P2, 3>& p, double* K) { model.add_element_matrix(p, K); };
  const auto direct = direct_positions(net, roles, target, edges, element);
  Network_deformer<2> deformer(net, roles);
  Deform_options options;
  options.number_of_steps = 1; // one solve, with the stiffness of the initial mesh
  options.solver = solver;
  Comparison out;
  out.report = deformer.run(motion, model, options);
  REQUIRE(out.report.completed);
  for(std::size_t i = 0; i < net.number_of_vertices(); ++i)
    for(int c = 0; c < 2; ++c) {
      out.error = std::max(out.error, std::abs(deformer.positions()[i][c] - direct[i][c]));
      out.largest = std::max(out.largest, std::abs(direct[i][c] - net.points[i][c]));
    }
  return out;
}

// the coarse Mesh_3 wing with its surface moving, and a pitch about its
// quarter chord
struct Coarse_wing
{
  Spring_network<3> net;
  std::vector<Vertex_role> roles;
};

Coarse_wing coarse_wing()
{
  const auto mesh = naca0012_wing_mesh_3(coarse_wing_options());
  Coarse_wing w;
  w.net = make_spring_network<3>(mesh.points, mesh.elements);
  w.roles = assign_roles(w.net, moving_boundary_where([](const std::array<double, 3>& p) {
                           return is_on_naca0012_wing(p[0], p[1], p[2]);
                         }));
  return w;
}

Pitch_motion<3> wing_pitch(double degrees)
{
  Pitch_motion<3> motion(degrees, {0.25, 0.0, 0.0});
  motion.axis = {0, 0, 1};
  return motion;
}

} // namespace

TEST_CASE("solvers: SOR and conjugate gradients match a direct sparse solve", "[solver]")
{
  // two small Mesh_2 domains (about 480 and 300 vertices); the inner boundary turns
  CDT cdt;
  if(GENERATE(0, 1) == 0)
    make_square_with_hole(cdt);
  else
    make_annulus(cdt);
  const auto net = extract_spring_network(cdt).network;
  const Pitch_motion<2> motion(5, {0, 0});
  // Both solvers stop (default rule) when the estimated error of the iterate,
  // the last change times q/(1-q) with q the contraction observed over the
  // last four iterations, is at most tol. That extrapolates the geometric
  // tail of the iteration, which SOR and CG follow once they contract
  // steadily; the factor 10 covers q varying over the window. Below tol =
  // 1e-9 the comparison would reach the direct solve's own round-off (cond(K)
  // eps |d|, about 1e-13 here), so 1e-9 keeps the two apart.
  const double tol = 1e-9;
  const double bound = 10 * tol;
  // every ordering: the paper's network order, point and block multicolour
  const Vertex_ordering ordering =
      GENERATE(Vertex_ordering::block_multicolour, Vertex_ordering::multicolour, Vertex_ordering::natural);
  struct Case
  {
    const char* name;
    Solver_method method;
    double omega;
    Preconditioner preconditioner = Preconditioner::multigrid;
  };
  for(const Case& c : {Case{"Gauss-Seidel", Solver_method::sor, 1.0}, Case{"SOR omega = 1.5", Solver_method::sor, 1.5},
                       Case{"SOR omega = 0.8", Solver_method::sor, 0.8},
                       Case{"conjugate gradients + multigrid", Solver_method::conjugate_gradient, 1.0},
                       Case{"conjugate gradients + symmetric Gauss-Seidel", Solver_method::conjugate_gradient, 1.0,
                            Preconditioner::symmetric_gauss_seidel}}) {
    Solver_options o;
    o.method = c.method;
    o.relaxation_factor = c.omega;
    o.preconditioner = c.preconditioner;
    o.tolerance = tol;
    o.ordering = ordering;
    o.block_rows = ordering == Vertex_ordering::block_multicolour ? 64 : 0; // several blocks on these small meshes
    INFO("ordering " << int(ordering));
    SECTION(std::string("scalar system (lineal springs), ") + c.name)
    {
      const auto r = compare_with_direct(net, Lineal_stiffness{1.0}, motion, o);
      INFO("error " << r.error << ", motion " << r.largest << ", iterations " << r.report.steps[0].iterations);
      CHECK(r.report.converged);
      CHECK(r.largest > 1e-2); // the motion is not trivially zero
      CHECK(r.error <= bound);
    }
    SECTION(std::string("2x2-block system (torsional springs), ") + c.name)
    {
      const auto r = compare_with_direct(net, Torsional_stiffness{}, motion, o);
      INFO("error " << r.error << ", motion " << r.largest << ", iterations " << r.report.steps[0].iterations);
      CHECK(r.report.converged);
      CHECK(r.largest > 1e-2);
      CHECK(r.error <= bound);
    }
    SECTION(std::string("2x2-block system (ball-vertex springs, k = 1/h^2), ") + c.name)
    {
      const auto r = compare_with_direct(net, Ball_vertex_stiffness{2.0}, motion, o);
      INFO("error " << r.error << ", motion " << r.largest << ", iterations " << r.report.steps[0].iterations);
      CHECK(r.report.converged);
      CHECK(r.largest > 1e-2);
      CHECK(r.error <= bound);
    }
    SECTION(std::string("2x2-block system with entries beyond single precision, ") + c.name)
    {
      // ball-vertex springs scaled by 1e40: the same motion, but entries no
      // float can hold, so the preconditioner's sweeps must keep to doubles
      Ball_vertex_stiffness scaled{2.0};
      scaled.weight = 1e40;
      const auto r = compare_with_direct(net, scaled, motion, o);
      INFO("error " << r.error << ", motion " << r.largest << ", iterations " << r.report.steps[0].iterations);
      CHECK(r.report.converged);
      CHECK(r.largest > 1e-2);
      CHECK(r.error <= bound);
    }
    SECTION(std::string("2x2-block system (springs along their edges), ") + c.name)
    {
      const auto r = compare_with_direct(net, Truss_model{}, motion, o);
      INFO("error " << r.error << ", motion " << r.largest << ", iterations " << r.report.steps[0].iterations);
      CHECK(r.report.converged);
      CHECK(r.largest > 1e-2);
      CHECK(r.error <= bound);
    }
  }
}

// Large aggregates in 3D: an aggregate of one vertex (or of two, on a line)
// does not feel a rotation about that line, and the multigrid gives that
// rotation a tiny spring; on the next level an aggregate of two such nodes
// is then nearly free and its block (or the coarsest matrix) fails a plain
// Cholesky. With a strength of connection of 0.15 or 0.2 on a coarse Mesh_3
// wing every 3D element model met it; the solves must go through and reach
// the solution that conjugate gradients preconditioned by symmetric
// Gauss-Seidel alone (no coarse levels) reach.
TEST_CASE("solvers: 3D block systems whose multigrid has nearly free rotations converge", "[solver][block][multigrid]")
{
  const Coarse_wing wing = coarse_wing();
  const auto& net = wing.net;
  const auto& roles = wing.roles;
  const Pitch_motion<3> motion = wing_pitch(5);
  auto positions = [&](const auto& model, const Solver_options& solver) {
    Network_deformer<3> deformer(net, roles);
    Deform_options options;
    options.number_of_steps = 1;
    options.solver = solver;
    const auto report = deformer.run(motion, model, options);
    REQUIRE(report.completed);
    CHECK(report.converged);
    return deformer.positions();
  };
  auto compare = [&](const auto& model) {
    for(const double strength : {0.15, 0.2}) {
      Solver_options mg;
      mg.tolerance = 1e-9;
      mg.multigrid_strength = strength;
      Solver_options sgs = mg;
      sgs.preconditioner = Preconditioner::symmetric_gauss_seidel;
      const auto a = positions(model, mg), b = positions(model, sgs);
      double error = 0, motion_size = 0;
      for(std::size_t i = 0; i < a.size(); ++i)
        for(int c = 0; c < 3; ++c) {
          error = std::max(error, std::abs(a[i][c] - b[i][c]));
          motion_size = std::max(motion_size, std::abs(a[i][c] - net.points[i][c]));
        }
      INFO("strength " << strength << ": max difference " << error << ", motion " << motion_size);
      CHECK(motion_size > 1e-2);
      CHECK(error <= 1e-7);
    }
  };
  SECTION("ball-vertex springs, k = 1/h^2") { compare(Ball_vertex_stiffness{2.0}); }
  SECTION("ball-vertex springs, k = 1/h^3") { compare(Ball_vertex_stiffness{3.0}); }
  SECTION("torsional springs") { compare(Torsional_stiffness{}); }
}

TEST_CASE("solvers: block and scalar systems take iterations of the same order", "[solver][block]")
{
  CDT cdt;
  make_square_with_hole(cdt, 0.5, 10, 0.1); // about 3900 vertices
  const auto net = extract_spring_network(cdt).network;
  const Pitch_motion<2> motion(5, {0, 0});
  Solver_options o;
  o.tolerance = 1e-9;
  const auto scalar = compare_with_direct(net, Lineal_stiffness{1.0}, motion, o);
  const auto torsional = compare_with_direct(net, Torsional_stiffness{}, motion, o);
  const auto ball_vertex = compare_with_direct(net, Ball_vertex_stiffness{2.0}, motion, o);
  const std::size_t n_scalar = scalar.report.steps[0].iterations;
  INFO("iterations: scalar " << n_scalar << ", torsional " << torsional.report.steps[0].iterations
                             << ", ball-vertex " << ball_vertex.report.steps[0].iterations);
  CHECK(torsional.error <= 10 * o.tolerance);
  CHECK(ball_vertex.error <= 10 * o.tolerance);
  // the multigrid V-cycle on 2x2 blocks (aggregates by block norm, a coarse
  // space that translates and rotates each aggregate, Galerkin coarse
  // operators) keeps the block systems' iterations of the order of the
  // scalar system's
  CHECK(torsional.report.steps[0].iterations <= 2 * n_scalar);
  CHECK(ball_vertex.report.steps[0].iterations <= 2 * n_scalar);
}

namespace {
// per-coordinate edge springs k = 0 and no element matrix: every diagonal
// block is zero
struct Zero_block_model
{
  Angle_kind angle_kind(int) const { return Angle_kind::none; }
  double operator()(double, const double*, std::size_t, const Stiffness_context&) const { return 0.0; }
  void add_element_matrix(const std::array<P2, 3>&, double*) const {}
};
} // namespace

TEST_CASE("solvers: a singular diagonal block names its vertex", "[solver][block][errors]")
{
  Indexed_mesh<2> mesh;
  mesh.points = {{0, 0}, {1, 0}, {1, 1}, {0, 1}, {0.5, 0.5}};
  mesh.elements = {{0, 1, 4}, {1, 2, 4}, {2, 3, 4}, {3, 0, 4}};
  auto net = make_spring_network<2>(mesh.points, mesh.elements);
  Network_deformer<2> deformer(net, assign_roles(net, All_boundary_moving{}));
  try {
    deformer.run(Translation_motion<2>{{0.1, 0}}, Zero_block_model{});
    FAIL("no error");
  } catch(const Vertex_error& e) {
    CHECK(e.vertex() == 4);
    CHECK_THAT(e.what(), Catch::Contains("free vertex 4 has a singular or non-finite diagonal stiffness block"));
  }
}

TEST_CASE("solvers: a NaN in the maxima that stop a solve sticks, whatever values follow it", "[solver][errors]")
{
  // the solver's maxima (updates, residuals: per chunk of rows, then over
  // the chunks) are runs of sticky_max; a NaN that a later finite value
  // replaced would let a solve pass for converged
  const double nan = std::numeric_limits<double>::quiet_NaN(), inf = std::numeric_limits<double>::infinity();
  auto run = [](std::initializer_list<double> values) {
    double m = 0;
    for(double v : values)
      internal::sticky_max(m, v);
    return m;
  };
  CHECK(std::isnan(run({nan})));
  CHECK(std::isnan(run({nan, 1.0})));
  CHECK(std::isnan(run({2.0, nan, 1.0, 3.0})));
  CHECK(std::isnan(run({1.0, nan, inf})));
  CHECK(std::isnan(run({inf, nan, 0.0})));
  // without a NaN, the plain maximum
  CHECK(run({}) == 0.0);
  CHECK(run({1.0, 3.0, 2.0}) == 3.0);
  CHECK(run({1.0, inf, 2.0}) == inf);
}

TEST_CASE("solvers: a zero-length edge is reported as coincident vertices", "[solver][errors]")
{
  Indexed_mesh<2> mesh;
  mesh.points = {{0, 0}, {1, 0}, {1, 1}, {0, 1}, {0.5, 0.5}};
  mesh.elements = {{0, 1, 4}, {1, 2, 4}, {2, 3, 4}, {3, 0, 4}};
  const auto net = make_spring_network<2>(mesh.points, mesh.elements);
  auto x = net.points;
  x[4] = x[2]; // the state a collapsing step would reach
  std::vector<double> k;
  internal::Stiffness_scratch<2> scratch;
  try {
    internal::compute_edge_stiffness(net, x, Lineal_stiffness{}, Stiffness_context{2, 1.0}, k, scratch, 1);
    FAIL("no error");
  } catch(const Vertex_error& e) {
    CHECK(e.vertex() == 2);
    CHECK_THAT(e.what(), Catch::Contains("coincident vertices 2 and 4"));
  }
}

TEST_CASE("solvers: the paper's max-change criterion stops far from the solution, and the report shows it",
          "[solver][paper]")
{
  // A finer mesh (about 3900 vertices): Gauss-Seidel contracts the error by
  // about q = 1 - O(h^2) per sweep, so when one sweep changes nothing by more
  // than tol the error left is about tol q / (1 - q), a hundred times tol.
  CDT cdt;
  make_square_with_hole(cdt, 0.5, 10, 0.1);
  const auto net = extract_spring_network(cdt).network;
  const Pitch_motion<2> motion(5, {0, 0});
  const Solver_options paper = Solver_options::paper(); // SOR, omega = 1, Eq. 12, eps = 5e-6
  REQUIRE(paper.stopping == Stopping_rule::max_update);
  const auto r = compare_with_direct(net, Lineal_stiffness{1.0}, motion, paper);
  const Step_report& s = r.report.steps[0];
  INFO("error " << r.error << ", iterations " << s.iterations << ", last change " << s.max_update << ", residual "
                << s.residual << ", error estimate " << s.error_estimate);
  // Eq. 12 was met: the solve reports convergence by the paper's criterion...
  CHECK(s.converged);
  CHECK(s.max_update <= paper.tolerance);
  // ...while the true error is still far above the tolerance
  CHECK(r.error > 30 * paper.tolerance);
  // The report says so: the residual (one more local solve's change) is of
  // the order of tol, like the last change, and so not the error; the error
  // estimate, computed under either rule from the observed contraction, is of
  // the order of the true error.
  CHECK(s.residual > 0);
  CHECK(s.residual <= 2 * paper.tolerance);
  CHECK(s.error_estimate > 10 * paper.tolerance);
  CHECK(s.error_estimate == Approx(r.error).epsilon(0.5));
  // The default rule on the same system stops only when that estimate is
  // below tol, and then the error is too.
  Solver_options sor = paper;
  sor.stopping = Stopping_rule::error_estimate;
  const auto d = compare_with_direct(net, Lineal_stiffness{1.0}, motion, sor);
  INFO("default rule: error " << d.error << ", iterations " << d.report.steps[0].iterations);
  CHECK(d.report.steps[0].iterations > s.iterations);
  CHECK(d.error <= 10 * sor.tolerance); // factor 10 as in the test above
  // the JSON report carries these fields for every step
  std::ostringstream json;
  write_report_json(r.report, json);
  CHECK_THAT(json.str(), Catch::Contains("\"residual\": ") && Catch::Contains("\"error_estimate\": ") &&
                             Catch::Contains("\"max_update\": "));
}

TEST_CASE("solvers: the error estimate counts the tail by single iterations and by pairs, whichever is smaller",
          "[solver]")
{
  // Changes u_k in units of `unit` against the default tolerance 1e-6: a
  // solve may stop once the estimate is at most 5e-7 (before five changes:
  // 6.25e-8, with the change at most 1.25e-7). Each expected estimate is the
  // tail of a geometric series worked out by hand: by single iterations u_k
  // q / (1 - q), q the largest of the last four ratios (before five changes:
  // of the ratios so far; infinite before three changes); by pairs s_k Q /
  // (1 - Q), s_k = u_k + u_{k-1}, Q the largest of the last four s_j /
  // s_{j-2} and of the last ratio u_k / u_{k-1} (infinite before seven
  // changes).
  struct Feed
  {
    bool done;
    double estimate;
  };
  auto feed = [](std::initializer_list<double> changes, double unit) {
    internal::Stopping_test test{Solver_options{}};
    std::vector<Feed> out;
    for(double u : changes) {
      const bool done = test.done(u * unit);
      out.push_back({done, test.estimate()});
    }
    return out;
  };
  // the first n feeds do not stop the solve; the first two give no estimate
  auto undecided = [](const std::vector<Feed>& f, std::size_t n) {
    for(std::size_t k = 0; k < n; ++k) {
      CHECK_FALSE(f[k].done);
      if(k < 2)
        CHECK(f[k].estimate == std::numeric_limits<double>::infinity());
    }
  };
  SECTION("a steady contraction: the single iterations' tail, the smaller")
  {
    // q = 1/2. Five changes: by single iterations 0.5 (1/2) / (1/2) = 0.5;
    // seven: 0.125 by single iterations, by pairs Q = max(1/4, 1/2) and
    // s = 0.375, so 0.375
    const auto f = feed({8, 4, 2, 1, 0.5, 0.25, 0.125}, 1e-7);
    undecided(f, 4);
    // before five changes: 2 (1/2) / (1/2) = 2, then 1, above 0.625
    CHECK(f[2].estimate == Approx(2e-7).epsilon(1e-12));
    CHECK(f[3].estimate == Approx(1e-7).epsilon(1e-12));
    CHECK(f[4].done);
    CHECK(f[4].estimate == Approx(0.5e-7).epsilon(1e-12));
    CHECK(f[6].estimate == Approx(0.125e-7).epsilon(1e-12));
  }
  SECTION("changes larger than the ones before: the pairs' tail")
  {
    // ratios 1/4, 2, 1/2, 3/5, 4/3, 1/8: by single iterations infinite; by
    // pairs s = 25, 15, 15, 8, 7, 4.5 and s_j / s_{j-2} = 3/5, 8/15, 7/15,
    // 9/16, with the last ratio 1/8: Q = 3/5, the oldest pair's, so
    // 4.5 (3/5) / (2/5) = 6.75
    const auto f = feed({20, 5, 10, 5, 3, 4, 0.5}, 1e-8);
    undecided(f, 6);
    CHECK(f[6].done);
    CHECK(f[6].estimate == Approx(6.75e-8).epsilon(1e-12));
    // the same seven changes after three others: only the last seven count
    // (before, a ratio or a pair ratio above 1 in each window keeps both
    // estimates infinite)
    const auto g = feed({1, 1, 1, 20, 5, 10, 5, 3, 4, 0.5}, 1e-8);
    undecided(g, 9);
    CHECK(g[9].done);
    CHECK(g[9].estimate == Approx(6.75e-8).epsilon(1e-12));
  }
  SECTION("a slower last iteration is not averaged away by its pair")
  {
    // ratios 1/4, 2, 1/4, 1/2, 1/2, 0.9: by single iterations 0.45 * 9 =
    // 4.05 (in units 2e-7: 8.1e-7, above 5e-7); by pairs s = 20, 12, 10, 3,
    // 1.5, 0.95 contract by at most 1/2, but the last ratio 0.9 is in Q:
    // 0.95 * 9 = 8.55. The smaller, 8.1e-7, does not stop the solve.
    const auto f = feed({16, 4, 8, 2, 1, 0.5, 0.45}, 2e-7);
    CHECK_FALSE(f[6].done);
    CHECK(f[6].estimate == Approx(8.1e-7).epsilon(1e-12));
  }
  SECTION("before five changes, a solve stops only far below the tolerance")
  {
    // ratios 1/8, 1/2: u = 0.5 <= 1.25 and 0.5 (1/2) / (1/2) = 0.5 <= 0.625
    const auto f = feed({8, 1, 0.5}, 1e-7);
    undecided(f, 2);
    CHECK(f[2].done);
    CHECK(f[2].estimate == Approx(0.5e-7).epsilon(1e-12));
    // the estimate passes (ratios 0.13, 0.1: 1.3 (0.13) / 0.87) but the
    // change 1.3 is above 1.25; the next, 0.26 (q = 0.2: 0.065), stops it
    const auto g = feed({100, 13, 1.3, 0.26}, 1e-7);
    undecided(g, 3);
    CHECK(g[2].estimate == Approx(1.3e-7 * 0.13 / 0.87).epsilon(1e-12));
    CHECK(g[3].done);
    CHECK(g[3].estimate == Approx(0.065e-7).epsilon(1e-12));
    // the change passes but the estimate, 1 (1/2) / (1/2) = 1, is above 0.625
    const auto h = feed({4, 2, 1}, 1e-7);
    undecided(h, 3);
    CHECK(h[2].estimate == Approx(1e-7).epsilon(1e-12));
    // one change larger than the one before (ratio 1.25) counts until the
    // window is full: no early stop, however small the changes after it
    const auto k = feed({8, 0.4, 0.5, 0.05}, 1e-7);
    undecided(k, 4);
    CHECK(k[3].estimate == std::numeric_limits<double>::infinity());
  }
}

TEST_CASE("solvers: an iteration cap stops a solve unconverged, and every report says so", "[solver][errors]")
{
  CDT cdt;
  make_square_with_hole(cdt);
  const auto net = extract_spring_network(cdt).network;
  Solver_options capped = Solver_options::paper();
  capped.max_iterations = 3; // far fewer sweeps than the ~60 this solve needs
  Network_deformer<2> deformer(net, assign_roles(net, moving_boundary_where(on_hole)));
  Deform_options options;
  options.number_of_steps = 2;
  options.solver = capped;
  const auto report = deformer.run(Pitch_motion<2>(2, {0, 0}), Lineal_stiffness{}, options);
  CHECK_FALSE(report.converged);
  REQUIRE_FALSE(report.steps.empty());
  for(const auto& s : report.steps) {
    CHECK_FALSE(s.converged);
    CHECK(s.iterations == 3);
    CHECK(s.max_update > capped.tolerance); // the criterion was not met
  }
  std::ostringstream json;
  write_report_json(report, json);
  CHECK_THAT(json.str(), Catch::Contains("\"converged\": false"));
}

TEST_CASE("solvers: a warm start from the previous increment gives the same motion in fewer iterations",
          "[solver][warm_start]")
{
  CDT cdt;
  make_square_with_hole(cdt);
  const auto net = extract_spring_network(cdt).network;
  Deform_options options;
  options.number_of_steps = 10;
  options.solver.method = Solver_method::sor;
  options.solver.tolerance = 1e-9;
  auto run = [&](bool warm, bool extrapolate, std::size_t& iterations) {
    options.solver.warm_start = warm;
    options.solver.extrapolate = extrapolate;
    Network_deformer<2> deformer(net, assign_roles(net, moving_boundary_where(on_hole)));
    const auto report = deformer.run(Pitch_motion<2>(20, {0, 0}), Grid_scaled_stiffness{}, options);
    REQUIRE(report.completed);
    REQUIRE(report.converged);
    iterations = 0;
    for(const auto& s : report.steps)
      iterations += s.iterations;
    return deformer.positions();
  };
  std::size_t cold_iterations = 0, warm_iterations = 0, extrapolated_iterations = 0;
  const auto cold = run(false, false, cold_iterations);
  const auto warm = run(true, false, warm_iterations);
  const auto extrapolated = run(true, true, extrapolated_iterations);
  INFO("sweeps: cold " << cold_iterations << ", previous increment " << warm_iterations << ", extrapolated "
                       << extrapolated_iterations);
  CHECK(warm_iterations < cold_iterations);
  CHECK(extrapolated_iterations < cold_iterations);
  // the starting point changes the iterates, not the equations: each step's
  // solve ends within about tol of the same solution, and as in
  // test_stiffness.cpp differences carried into the next step's stiffness add
  // up over the n steps; a factor 10 because the error is an estimate
  double d1 = 0, d2 = 0;
  for(std::size_t i = 0; i < cold.size(); ++i)
    for(int c = 0; c < 2; ++c) {
      d1 = std::max(d1, std::abs(cold[i][c] - warm[i][c]));
      d2 = std::max(d2, std::abs(cold[i][c] - extrapolated[i][c]));
    }
  const double bound = 10 * 2 * double(options.number_of_steps) * options.solver.tolerance;
  CHECK(d1 <= bound);
  CHECK(d2 <= bound);
}

TEST_CASE("solvers: the warm start's weights extrapolate increments by the polynomial through the last ones",
          "[solver][warm_start]")
{
  // intervals of unequal fraction (as after substeps), newest first: [0.8,
  // 0.85], [0.6, 0.8], [0.5, 0.6]; the step to start is [0.85, 0.88]
  const std::array<double, 3> hj{0.05, 0.2, 0.1}, mj{0.825, 0.7, 0.55};
  const double h = 0.03, m = 0.865;
  // increments whose rate per unit of fraction is g at each midpoint: the
  // start must be h g(m) when g is a parabola (three increments) or a line
  // (two), whatever the intervals
  const auto start = [&](const internal::Warm_start_weights& w, double (*g)(double)) {
    double v = 0;
    for(std::size_t j = 0; j < w.used; ++j)
      v += w.weight[j] * hj[j] * g(mj[j]);
    return v;
  };
  double (*parabola)(double) = [](double x) { return 0.3 - 1.7 * x + 2.9 * x * x; };
  double (*line)(double) = [](double x) { return 0.3 - 1.7 * x; };
  const auto w3 = internal::warm_start_weights(h, m, hj, mj, 3, true);
  CHECK(w3.used == 3);
  CHECK(start(w3, parabola) == Approx(h * parabola(m)).epsilon(1e-13));
  const auto w2 = internal::warm_start_weights(h, m, hj, mj, 2, true);
  CHECK(w2.used == 2);
  CHECK(start(w2, line) == Approx(h * line(m)).epsilon(1e-13));
  // the line does not follow the parabola: the test can tell them apart
  CHECK(std::abs(start(w2, parabola) - h * parabola(m)) > 1e-4);
  // one increment, or no extrapolation: the last increment as it is
  for(const auto& w : {internal::warm_start_weights(h, m, hj, mj, 1, true),
                       internal::warm_start_weights(h, m, hj, mj, 3, false)}) {
    CHECK(w.used == 1);
    CHECK(w.weight[0] == 1.0);
  }
  CHECK(internal::warm_start_weights(h, m, hj, mj, 0, true).used == 0);
}

// One free vertex: conjugate gradients solve it exactly in one iteration, its
// recurrence residual is then exactly zero while the recomputed one is a
// rounding error. That breakdown is convergence, not a failed solve (it used
// to be reported as unconverged: seen by the CLI on a 3D box).
TEMPLATE_TEST_CASE_SIG("solvers: a single free vertex converges in one conjugate-gradient iteration",
                       "[solver]", ((int D), D), 2, 3)
{
  Indexed_mesh<D> mesh;
  if constexpr(D == 2) {
    mesh.points = {{0, 0}, {1, 0}, {1, 1}, {0, 1}, {0.5, 0.5}};
    mesh.elements = {{0, 1, 4}, {1, 2, 4}, {2, 3, 4}, {3, 0, 4}};
  } else {
    // the unit cube's faces, two triangles each, joined to its centre (vertex 8)
    for(int k = 0; k < 8; ++k)
      mesh.points.push_back({double(k & 1), double((k >> 1) & 1), double((k >> 2) & 1)});
    mesh.points.push_back({0.5, 0.5, 0.5});
    const std::uint32_t faces[12][3] = {{0, 1, 3}, {0, 3, 2}, {4, 5, 7}, {4, 7, 6}, {0, 1, 5}, {0, 5, 4},
                                        {2, 3, 7}, {2, 7, 6}, {0, 2, 6}, {0, 6, 4}, {1, 3, 7}, {1, 7, 5}};
    for(const auto& f : faces)
      mesh.elements.push_back({f[0], f[1], f[2], 8});
  }
  const std::uint32_t centre = std::uint32_t(mesh.points.size() - 1);
  const auto p0 = mesh.points;
  Deform_options options;
  options.number_of_steps = 10;
  REQUIRE(options.solver.method == Solver_method::conjugate_gradient);
  std::array<double, D> centre_of_rotation{};
  centre_of_rotation[0] = 0.2;
  centre_of_rotation[1] = 0.1;
  const auto report = deform(mesh, All_boundary_moving{}, Pitch_motion<D>(30.0, centre_of_rotation),
                             Lineal_stiffness{}, options);
  REQUIRE(report.completed);
  CHECK(report.converged);
  for(const auto& s : report.steps)
    CHECK(s.converged);
  // With lineal springs (k = 1/l, evaluated on the previous step's geometry)
  // the free vertex ends where the final step's weighted mean puts it; the
  // rigid rotation of the whole square is the check that it moved with it.
  const double a = 30.0 * std::acos(-1.0) / 180.0;
  for(std::uint32_t v = 0; v < centre; ++v) {
    const double x = p0[v][0] - centre_of_rotation[0], y = p0[v][1] - centre_of_rotation[1];
    CHECK(mesh.points[v][0] == Approx(centre_of_rotation[0] + std::cos(a) * x - std::sin(a) * y).margin(1e-14));
    CHECK(mesh.points[v][1] == Approx(centre_of_rotation[1] + std::sin(a) * x + std::cos(a) * y).margin(1e-14));
  }
  // the centre of a symmetric cell under a rigid rotation is rotated rigidly
  const double x = p0[centre][0] - centre_of_rotation[0], y = p0[centre][1] - centre_of_rotation[1];
  CHECK(mesh.points[centre][0] == Approx(centre_of_rotation[0] + std::cos(a) * x - std::sin(a) * y).margin(1e-12));
  CHECK(mesh.points[centre][1] == Approx(centre_of_rotation[1] + std::sin(a) * x + std::cos(a) * y).margin(1e-12));
}

namespace {
// An annulus (Mesh_2) whose inner boundary moves: its network, the roles and
// the free vertices.
struct Annulus
{
  Spring_network<2> net;
  std::vector<Vertex_role> roles;
  std::vector<Index> free;
};

Annulus annulus()
{
  CDT cdt;
  make_annulus(cdt);
  Annulus a;
  a.net = extract_spring_network(cdt).network;
  a.roles = assign_roles(a.net, moving_boundary_where([](const P2& p) { return std::hypot(p[0], p[1]) < 1.0; }));
  for(Index i = 0; i < Index(a.net.number_of_vertices()); ++i)
    if(a.roles[i] == Vertex_role::free)
      a.free.push_back(i);
  return a;
}
} // namespace

// The conjugate-gradient solves' preconditioner on the system it is built
// for, against its definition. Symmetric Gauss-Seidel (SSOR): a forward then
// a backward sweep from zero in the solver's row order, computed here row by
// row from the matrix the solver holds (a block system's sweeps read its
// off-diagonal blocks rounded to float, and so does the reference); with the
// multigrid the preconditioner must stay symmetric and positive definite.
// Several blocks of rows per colour, so that the parallel sweeps' order is
// the row order only through the colouring.
TEST_CASE("solvers: the preconditioner is the symmetric Gauss-Seidel of the solver's order, and symmetric with "
          "the multigrid",
          "[solver][preconditioner]")
{
  const Annulus a = annulus();
  const auto& net = a.net;
  const auto& free = a.free;
  REQUIRE(free.size() > 100);
  const auto positions = net.points;

  // ball-vertex blocks are exactly symmetric, torsional ones are not: the
  // sweeps read the single-precision upper triangles of the first and the
  // whole blocks of the second, and both must match the reference
  const int system = GENERATE(0, 1, 2);
  const bool block = system > 0, symmetric_blocks = system == 1;
  INFO((system == 1   ? "2x2-block system (ball-vertex springs, k = 1/h^2)"
        : system == 2 ? "2x2-block system (torsional springs)"
                      : "scalar system (lineal springs)"));
  Solver_options o;
  o.threads = GENERATE(1, 2);
  o.block_rows = 16;
  internal::Free_system<2> fs;
  fs.build(net, free, block, o);
  REQUIRE(fs.blocks() > 2 * fs.colours());
  std::vector<double> k(net.number_of_edges(), 0.0);
  if(system != 1) // ball-vertex springs alone: no edge springs
    for(std::size_t e = 0; e < k.size(); ++e)
      k[e] = 1.0 + double(e % 5);
  if(system == 1)
    internal::assemble_block_system<2>(positions, Ball_vertex_stiffness{2.0}, k, fs, o.threads);
  else if(system == 2)
    internal::assemble_block_system<2>(positions, Torsional_stiffness{}, k, fs, o.threads);
  else
    fs.load_scalar(net, k, o.threads);
  fs.set_positions(positions);
  const std::size_t n = fs.rows();
  const std::size_t w = block ? 4 : 1;
  const Index* off = fs.row_offsets().data();
  const Index* col = fs.columns().data();
  // entry (k, c, j, d) of block (or value) q, as the sweeps read it
  auto entry = [&](const double* v, std::size_t q, int c, int d) {
    return block ? double(float(v[q * w + std::size_t(2 * c + d)])) : (c == d ? v[q] : 0.0);
  };
  auto diagonal_solve = [&](std::size_t r, const P2& s) {
    const double* m = fs.diagonal() + r * w;
    if(!block)
      return P2{s[0] / m[0], s[1] / m[0]};
    const double det = m[0] * m[3] - m[1] * m[2];
    return P2{(m[3] * s[0] - m[1] * s[1]) / det, (m[0] * s[1] - m[2] * s[0]) / det};
  };
  auto ssor = [&](const std::vector<P2>& r, double omega) {
    std::vector<P2> z(n, P2{0, 0});
    auto update = [&](std::size_t row) {
      P2 s = r[row];
      for(Index q = off[row]; q < off[row + 1]; ++q)
        for(int c = 0; c < 2; ++c)
          for(int d = 0; d < 2; ++d)
            s[std::size_t(c)] -= entry(fs.values(), q, c, d) * z[col[q]][std::size_t(d)];
      const P2 y = diagonal_solve(row, s);
      for(int c = 0; c < 2; ++c)
        z[row][std::size_t(c)] = (1 - omega) * z[row][std::size_t(c)] + omega * y[std::size_t(c)];
    };
    for(std::size_t row = 0; row < n; ++row)
      update(row);
    for(std::size_t row = n; row-- > 0;)
      update(row);
    return z;
  };
  std::vector<P2> r1(n);
  for(std::size_t row = 0; row < n; ++row)
    r1[row] = {std::sin(1.0 + 3.0 * double(row)), std::cos(0.5 * double(row))};
  auto largest = [](const std::vector<P2>& z) {
    double m = 0;
    for(const auto& v : z)
      m = std::max({m, std::abs(v[0]), std::abs(v[1])});
    return m;
  };

  SECTION("symmetric Gauss-Seidel and SSOR")
  {
    o.preconditioner = Preconditioner::symmetric_gauss_seidel;
    for(const double omega : {1.0, 1.3}) {
      o.preconditioner_relaxation_factor = omega;
      const auto z = fs.preconditioned(r1, o);
      CHECK(fs.smoother_read_upper_triangles() == symmetric_blocks);
      CHECK(fs.product_read_upper_triangles() == symmetric_blocks);
      const auto ref = ssor(r1, omega);
      double error = 0;
      for(std::size_t row = 0; row < n; ++row)
        for(int c = 0; c < 2; ++c)
          error = std::max(error, std::abs(z[row][std::size_t(c)] - ref[row][std::size_t(c)]));
      INFO("omega " << omega << ": max |z - reference| " << error << ", max |z| " << largest(ref));
      CHECK(largest(ref) > 1e-3);
      CHECK(error <= 1e-12 * largest(ref));
    }
  }
  SECTION("multigrid: symmetric, positive definite")
  {
    o.preconditioner = Preconditioner::multigrid;
    check_symmetric_positive([&](const Vec& r) { return fs.preconditioned(r, o); }, n, 5, 1e-12);
    REQUIRE((block ? fs.rigid_body_multigrid().number_of_levels() : fs.multigrid().number_of_levels()) > 0);
  }

}

// A block system's multigrid keeps its coarse levels for
// multigrid_coarse_interval solves: a sequence of systems, each on a mesh
// deformed a little further (so that each matrix differs from the last), is
// solved with the levels recomputed at solves 1, 5, 9 (interval 4) or at every
// solve (interval 1). Every solution must equal a direct solve of its own
// loaded system: kept coarse levels only change the preconditioner. The count
// of recomputations shows the levels were kept; the solutions do not depend
// on the thread count.
TEST_CASE("solvers: a block system's multigrid keeps its coarse levels between recomputations, and the solutions "
          "stay those of a direct solve",
          "[solver][block][multigrid]")
{
  const Annulus a = annulus();
  const auto& net = a.net;
  const auto& roles = a.roles;
  const auto& free = a.free;
  REQUIRE(free.size() > 100);
  const std::vector<double> k(net.number_of_edges(), 0.0); // ball-vertex springs alone
  const std::size_t solves = 9;

  // the solutions of the `solves` systems under the options
  auto run = [&](const Solver_options& o, std::vector<std::size_t>& loads, std::vector<double>& errors) {
    internal::Free_system<2> fs;
    fs.build(net, free, true, o);
    std::vector<P2> positions = net.points;
    fs.set_positions(positions);
    std::vector<std::vector<P2>> solutions;
    for(std::size_t s = 1; s <= solves; ++s) {
      // a smooth shear growing with s (at most 1% of the annulus), and a
      // turn of the inner boundary as the prescribed increment
      const double shear = 0.002 * double(s);
      std::vector<P2> increment(net.number_of_vertices(), P2{0, 0});
      for(std::size_t i = 0; i < positions.size(); ++i) {
        const P2& p = net.points[i];
        positions[i] = {p[0] + shear * std::sin(p[1]), p[1] + shear * std::sin(2 * p[0])};
        if(roles[i] == Vertex_role::moving)
          increment[i] = {-0.01 * p[1], 0.01 * p[0]};
      }
      internal::assemble_block_system<2>(positions, Ball_vertex_stiffness{2.0}, k, fs, o.threads);
      fs.set_start(increment, o.threads);
      const Solve_report r = fs.solve(o);
      CHECK(r.converged);
      loads.push_back(fs.rigid_body_multigrid().loads());
      // the loaded system, assembled into Eigen and solved directly
      const std::size_t n = fs.rows();
      const Index* off = fs.row_offsets().data();
      const Index* col = fs.columns().data();
      std::vector<Eigen::Triplet<double>> trip;
      for(std::size_t row = 0; row < n; ++row)
        for(int c = 0; c < 2; ++c)
          for(int d = 0; d < 2; ++d) {
            trip.emplace_back(int(2 * row) + c, int(2 * row) + d, fs.diagonal()[row * 4 + std::size_t(2 * c + d)]);
            for(Index q = off[row]; q < off[row + 1]; ++q)
              trip.emplace_back(int(2 * row) + c, int(2 * col[q]) + d, fs.values()[q * 4 + std::size_t(2 * c + d)]);
          }
      Eigen::SparseMatrix<double> A(int(2 * n), int(2 * n));
      A.setFromTriplets(trip.begin(), trip.end());
      Eigen::VectorXd b(2 * n);
      for(std::size_t row = 0; row < n; ++row)
        for(int c = 0; c < 2; ++c)
          b(int(2 * row) + c) = fs.rhs()[row][std::size_t(c)];
      Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> ldlt(A);
      REQUIRE(ldlt.info() == Eigen::Success);
      const Eigen::VectorXd x = ldlt.solve(b);
      REQUIRE((A * x - b).norm() <= 1e-12 * b.norm());
      double error = 0, largest = 0;
      for(std::size_t row = 0; row < n; ++row)
        for(int c = 0; c < 2; ++c) {
          error = std::max(error, std::abs(fs.solution()[row][std::size_t(c)] - x(int(2 * row) + c)));
          largest = std::max(largest, std::abs(x(int(2 * row) + c)));
        }
      CHECK(largest > 1e-3); // the increment is not trivially zero
      errors.push_back(error);
      solutions.push_back(fs.solution());
    }
    return solutions;
  };
  Solver_options o;
  o.tolerance = 1e-9;
  o.block_rows = 16;
  std::vector<std::size_t> loads1, loads4, loads4_two;
  std::vector<double> errors1, errors4, errors4_two;
  o.threads = 1;
  o.multigrid_coarse_interval = 1;
  run(o, loads1, errors1);
  o.multigrid_coarse_interval = 4;
  const auto one_thread = run(o, loads4, errors4);
  o.threads = 2;
  const auto two_threads = run(o, loads4_two, errors4_two);
  for(std::size_t s = 0; s < solves; ++s) {
    INFO("solve " << s + 1 << ": error " << errors1[s] << " (every solve), " << errors4[s] << " (every 4th)");
    CHECK(loads1[s] == s + 1);
    CHECK(loads4[s] == 1 + s / 4);
    CHECK(errors1[s] <= 10 * o.tolerance);
    CHECK(errors4[s] <= 10 * o.tolerance);
    CHECK(loads4_two[s] == loads4[s]);
    CHECK(errors4_two[s] == errors4[s]);
    CHECK(std::memcmp(one_thread[s].data(), two_threads[s].data(), one_thread[s].size() * sizeof(P2)) == 0);
  }
  // an interval of 0 would never recompute them: it is refused
  o.multigrid_coarse_interval = 0;
  std::vector<std::size_t> none_loads;
  std::vector<double> none_errors;
  CHECK_THROWS_WITH(run(o, none_loads, none_errors), Catch::Contains("multigrid coarse interval must be at least 1"));
}

// Solver_options::multigrid_first_level_cycles = 0 (the default) takes one
// V-cycle on the block multigrid's first coarse level in 2D and three in 3D:
// a one-step ball-vertex motion with the default must give, bit for bit, the
// positions and iterations of the resolved count given explicitly, and not
// those of the other count (so that the count is seen to matter).
template <int D, class Roles>
void check_first_level_cycles_by_dimension(const Spring_network<D>& net, const Roles& roles,
                                           const Pitch_motion<D>& motion)
{
  auto run = [&](std::size_t cycles, std::size_t& iterations) {
    Network_deformer<D> deformer(net, roles);
    Deform_options options;
    options.number_of_steps = 1;
    options.solver.tolerance = 1e-9;
    // small coarse levels, so that these meshes have levels below the first
    options.solver.multigrid_coarsest_rows = 8;
    options.solver.multigrid_max_direct_rows = 16;
    options.solver.multigrid_first_level_cycles = cycles;
    const auto report = deformer.run(motion, Ball_vertex_stiffness{2.0}, options);
    REQUIRE(report.completed);
    CHECK(report.converged);
    iterations = report.steps[0].iterations;
    return deformer.positions();
  };
  const std::size_t resolved = D == 3 ? 3 : 1, other = D == 3 ? 1 : 3;
  std::size_t by_default = 0, explicit_count = 0, other_count = 0;
  const auto a = run(0, by_default), b = run(resolved, explicit_count), c = run(other, other_count);
  INFO(D << "D: iterations " << by_default << " (default), " << explicit_count << " (" << resolved << " cycles), "
         << other_count << " (" << other << " cycles)");
  CHECK(by_default == explicit_count);
  CHECK(std::memcmp(a.data(), b.data(), a.size() * sizeof(a[0])) == 0);
  CHECK((other_count != by_default || std::memcmp(a.data(), c.data(), a.size() * sizeof(a[0])) != 0));
}

namespace {
// A conjugate-gradient solve of a scalar (lineal springs k = 1/l) or block
// (ball-vertex springs alone) system whose moving vertices turn by 0.01 rad
// about the z axis: its reported residual against max_k |D_k^{-1} (b - A x)_k|
// computed here from the matrix the solver holds and the solution it
// returns (the solver takes the first from its recurrence: a stale or
// unscaled one fails this).
template <int D>
void check_reported_residual(const Spring_network<D>& net, const std::vector<Vertex_role>& roles, bool block)
{
  using P = std::array<double, D>;
  std::vector<Index> free;
  std::vector<P> increment(net.number_of_vertices(), P{});
  for(Index i = 0; i < Index(net.number_of_vertices()); ++i)
    if(roles[i] == Vertex_role::free)
      free.push_back(i);
    else if(roles[i] == Vertex_role::moving) {
      increment[i][0] = -0.01 * net.points[i][1];
      increment[i][1] = 0.01 * net.points[i][0];
    }
  const Solver_options o;
  REQUIRE(o.method == Solver_method::conjugate_gradient);
  internal::Free_system<D> fs;
  fs.build(net, free, block, o);
  fs.set_positions(net.points);
  std::vector<double> k(net.number_of_edges(), 0.0);
  if(block)
    internal::assemble_block_system<D>(net.points, Ball_vertex_stiffness{2.0}, k, fs, 1);
  else {
    for(std::size_t e = 0; e < k.size(); ++e) {
      double l2 = 0;
      for(int c = 0; c < D; ++c)
        l2 += std::pow(net.points[net.edges[e][1]][c] - net.points[net.edges[e][0]][c], 2);
      k[e] = 1 / std::sqrt(l2);
    }
    fs.load_scalar(net, k, 1);
  }
  fs.set_start(increment, 1);
  const Solve_report r = fs.solve(o);
  REQUIRE(r.converged);
  REQUIRE(r.iterations > 1);
  const std::size_t n = fs.rows(), B = block ? std::size_t(D * D) : 1;
  const auto& x = fs.solution();
  double largest = 0;
  for(std::size_t row = 0; row < n; ++row) {
    Eigen::Matrix<double, D, D> d = Eigen::Matrix<double, D, D>::Zero();
    Eigen::Matrix<double, D, 1> s;
    for(int c = 0; c < D; ++c)
      s(c) = fs.rhs()[row][std::size_t(c)];
    // s = b - A x, one block (or one value per coordinate) at a time
    auto subtract = [&](const double* m, const P& v) {
      for(int c = 0; c < D; ++c)
        for(int e = 0; e < D; ++e)
          s(c) -= (block ? m[c * D + e] : (c == e ? m[0] : 0.0)) * v[std::size_t(e)];
    };
    subtract(fs.diagonal() + row * B, x[row]);
    for(Index q = fs.row_offsets()[row]; q < fs.row_offsets()[row + 1]; ++q)
      subtract(fs.values() + std::size_t(q) * B, x[fs.columns()[q]]);
    for(int c = 0; c < D; ++c)
      for(int e = 0; e < D; ++e)
        d(c, e) = block ? fs.diagonal()[row * B + std::size_t(c * D + e)] : (c == e ? fs.diagonal()[row] : 0.0);
    largest = std::max(largest, (d.inverse() * s).cwiseAbs().maxCoeff());
  }
  INFO("reported " << r.residual << ", recomputed " << largest << ", iterations " << r.iterations);
  CHECK(largest > 0);
  CHECK(r.residual == Approx(largest).epsilon(1e-6));
}
} // namespace

TEMPLATE_TEST_CASE_SIG("solvers: a converged solve reports the scaled residual of its solution", "[solver]",
                       ((int D), D), 2, 3)
{
  Spring_network<D> net;
  std::vector<Vertex_role> roles;
  if constexpr(D == 2) {
    Annulus a = annulus();
    net = std::move(a.net);
    roles = std::move(a.roles);
  } else {
    const auto mesh = kuhn_grid<3>(6);
    net = make_spring_network<3>(mesh.points, mesh.elements);
    // the face x = 0 turns, the rest of the boundary stays
    roles = assign_roles(net, moving_boundary_where([](const std::array<double, 3>& p) { return p[0] == 0; }));
  }
  SECTION("scalar system") { check_reported_residual<D>(net, roles, false); }
  SECTION("block system") { check_reported_residual<D>(net, roles, true); }
}

TEST_CASE("solvers: the block multigrid cycles its first coarse level once in 2D and three times in 3D by default",
          "[solver][block][multigrid]")
{
  SECTION("2D")
  {
    const Annulus a = annulus();
    check_first_level_cycles_by_dimension<2>(a.net, a.roles, Pitch_motion<2>(5, {0, 0}));
  }
  SECTION("3D")
  {
    const Coarse_wing wing = coarse_wing();
    check_first_level_cycles_by_dimension<3>(wing.net, wing.roles, wing_pitch(5));
  }
}

// The preconditioner's sweeps (in single precision) and conjugate gradients'
// products (in double) read a symmetric block from its upper triangle (6 of 9
// values in 3D): the product must be that of the full block, bit for bit, so
// that the solver's results do not depend on the storage. The blocks are
// converted in one pass and multiplied in another, as in the solver (GCC 12
// at -O3, seeing a float stored and read back in one basic block, was seen to
// use the double it was converted from).
template <int D, class T>
void check_upper_triangle_product(std::mt19937_64& random)
{
  constexpr int U = D * (D + 1) / 2;
  const std::size_t n = 2000;
  std::uniform_real_distribution<double> value(-1.0, 1.0);
  std::uniform_int_distribution<int> exponent(-40, 40);
  std::vector<double> m(n * D * D);
  for(std::size_t t = 0; t < n; ++t)
    for(int r = 0; r < D; ++r)
      for(int c = r; c < D; ++c) {
        const double v = t % 7 == 0 && r != c ? 0.0 : std::ldexp(value(random), exponent(random));
        m[t * D * D + std::size_t(r * D + c)] = m[t * D * D + std::size_t(c * D + r)] = v;
      }
  std::vector<T> full(n * D * D), upper(n * U);
  for(std::size_t k = 0; k < full.size(); ++k)
    full[k] = T(m[k]);
  for(std::size_t t = 0; t < n; ++t)
    internal::copy_upper_triangle<D>(&m[t * D * D], &upper[t * U]);
  std::size_t same = 0, same_product = 0;
  for(std::size_t t = 0; t < n; ++t) {
    std::array<double, D> x, a, b;
    for(int c = 0; c < D; ++c) {
      x[std::size_t(c)] = std::ldexp(value(random), exponent(random));
      a[std::size_t(c)] = b[std::size_t(c)] = value(random);
    }
    internal::subtract_block_product<D>(a, &full[t * D * D], x);
    internal::subtract_symmetric_block_product<D>(b, &upper[t * U], x);
    same += std::memcmp(a.data(), b.data(), sizeof a) == 0;
    if constexpr(std::is_same<T, double>::value) {
      const auto y = internal::block_product<D>(&full[t * D * D], x);
      const auto z = internal::symmetric_block_product<D>(&upper[t * U], x);
      same_product += std::memcmp(y.data(), z.data(), sizeof y) == 0;
    }
  }
  CHECK(same == n);
  CHECK(same_product == (std::is_same<T, double>::value ? n : 0));
}

TEST_CASE("solvers: a symmetric block read from its upper triangle gives the full block's product, bit for bit",
          "[solver][block]")
{
  std::mt19937_64 random(5);
  check_upper_triangle_product<2, float>(random);
  check_upper_triangle_product<3, float>(random);
  check_upper_triangle_product<2, double>(random);
  check_upper_triangle_product<3, double>(random);
  // the layout: rows of the upper triangle, one after another
  CHECK(internal::upper_triangle_index<3>(0, 0) == 0);
  CHECK(internal::upper_triangle_index<3>(0, 2) == 2);
  CHECK(internal::upper_triangle_index<3>(1, 1) == 3);
  CHECK(internal::upper_triangle_index<3>(1, 2) == 4);
  CHECK(internal::upper_triangle_index<3>(2, 2) == 5);
  CHECK(internal::upper_triangle_index<2>(1, 1) == 2);
}

// The multigrid's coarse sweeps read a single-precision copy of each block
// stored by columns: its products must be those of the row-major block of
// the same floats, bit for bit, and the copy must hold each value where the
// by-columns product reads it (blocks not symmetric, so a transposition
// shows), with 0 and `false` for a value a float cannot hold.
template <int D>
void check_block_product_by_columns(std::mt19937_64& random)
{
  const std::size_t n = 2000;
  std::uniform_real_distribution<double> value(-1.0, 1.0);
  std::uniform_int_distribution<int> exponent(-40, 40);
  std::vector<double> m(n * D * D);
  for(double& v : m)
    v = std::ldexp(value(random), exponent(random));
  std::vector<float> by_columns(m.size());
  REQUIRE(internal::copy_to_single_by_columns<D>(m.data(), by_columns.data(), long(n), 2));
  std::size_t placed = 0, same = 0;
  for(std::size_t t = 0; t < n; ++t)
    for(int r = 0; r < D; ++r)
      for(int c = 0; c < D; ++c)
        placed += by_columns[t * D * D + std::size_t(c * D + r)] == float(m[t * D * D + std::size_t(r * D + c)]);
  std::vector<float> by_rows(m.size());
  for(std::size_t k = 0; k < m.size(); ++k)
    by_rows[k] = float(m[k]);
  for(std::size_t t = 0; t < n; ++t) {
    std::array<double, D> x, a, b;
    for(int c = 0; c < D; ++c) {
      x[std::size_t(c)] = std::ldexp(value(random), exponent(random));
      a[std::size_t(c)] = b[std::size_t(c)] = value(random);
    }
    internal::subtract_block_product<D>(a, &by_rows[t * D * D], x);
    internal::subtract_block_product_by_columns<D>(b, &by_columns[t * D * D], x);
    same += std::memcmp(a.data(), b.data(), sizeof a) == 0;
  }
  CHECK(placed == n * D * D);
  CHECK(same == n);
  // out of a float's range: not converted, and reported
  m[D * D + 1] = 1e40;
  CHECK_FALSE(internal::copy_to_single_by_columns<D>(m.data(), by_columns.data(), long(n), 1));
  CHECK(by_columns[D * D + D] == 0.0f);
}

TEST_CASE("solvers: a row's block products by columns, four rows at a time where AVX runs, bit for bit",
          "[solver][block][multigrid]")
{
  // a row of 6 x 6 blocks as the rigid-body levels store them in 3D, its
  // entries filtered by column as the sweeps filter them; where AVX runs the
  // row takes the four-row kernel, compared here with block after block
  constexpr int D = 6;
  std::mt19937_64 random(12);
  std::uniform_real_distribution<double> value(-1.0, 1.0);
  std::uniform_int_distribution<int> exponent(-30, 30);
  std::uniform_int_distribution<unsigned> column(0, 39);
  const unsigned n = 400;
  std::vector<float> v(std::size_t(n) * D * D);
  for(float& f : v)
    f = float(std::ldexp(value(random), exponent(random)));
  std::vector<unsigned> col(n);
  for(unsigned& c : col)
    c = column(random);
  std::vector<std::array<double, D>> x(40);
  for(auto& r : x)
    for(double& e : r)
      e = std::ldexp(value(random), exponent(random));
  const auto below = [](unsigned j) { return j < 20; };
  for(unsigned first = 0; first < n; first += 40) {
    const unsigned last = first + 40;
    std::array<double, D> expected, s;
    for(int c = 0; c < D; ++c)
      expected[std::size_t(c)] = s[std::size_t(c)] = value(random);
    std::size_t kept = 0;
    for(unsigned q = first; q < last; ++q)
      if(below(col[q])) {
        internal::subtract_block_product_by_columns<D>(expected, &v[std::size_t(q) * D * D], x[col[q]]);
        ++kept;
      }
    REQUIRE(kept > 0);
    REQUIRE(kept < 40);
    internal::subtract_row_products_by_columns<D>(s, v.data(), col.data(), first, last, x.data(), below);
    CHECK(std::memcmp(s.data(), expected.data(), sizeof s) == 0);
  }
}

// A row of symmetric blocks stored as upper triangles, as the sweeps (floats
// or doubles) and conjugate gradients' products (doubles) read it: the row's
// sums must be those of block after block, bit for bit (in 3D, where AVX
// runs, the three rows are summed at once). Every third row is one block of
// one sign times x = +0 from a sum of -0, so each of its products is a zero
// of that sign: a zero sum keeps the sign the scalar sums give (-0 - +0 is
// -0; a block's product summed from +0 is +0, never -0).
template <int D, class T>
void check_symmetric_row_products(std::mt19937_64& random)
{
  constexpr int U = D * (D + 1) / 2;
  std::uniform_real_distribution<double> value(-1.0, 1.0);
  std::uniform_int_distribution<int> exponent(-30, 30);
  std::uniform_int_distribution<unsigned> column(0, 39);
  const unsigned n = 400, zero_column = 40;
  std::vector<T> v(std::size_t(n) * U);
  for(std::size_t k = 0; k < v.size(); ++k)
    v[k] = k % 11 == 0 ? T(0) : T(std::ldexp(value(random), exponent(random)));
  std::vector<unsigned> col(n);
  for(unsigned& c : col)
    c = column(random);
  std::vector<std::array<double, D>> x(zero_column + 1);
  for(auto& r : x)
    for(double& e : r)
      e = std::ldexp(value(random), exponent(random));
  x[zero_column].fill(0.0);
  std::size_t same = 0, same_sum = 0, rows = 0, negative_zeros = 0;
  for(unsigned first = 0; first < n; first += 20, ++rows) {
    const bool zeros = rows % 3 == 0;
    const unsigned last = first + (zeros ? 1 : 1 + rows % 19);
    std::array<double, D> expected, s, expected_sum, sum;
    for(int c = 0; c < D; ++c) {
      expected[std::size_t(c)] = s[std::size_t(c)] = zeros ? -0.0 : value(random);
      expected_sum[std::size_t(c)] = sum[std::size_t(c)] = zeros ? -0.0 : value(random);
    }
    if(zeros) {
      col[first] = zero_column;
      for(int k = 0; k < U; ++k)
        v[std::size_t(first) * U + std::size_t(k)] = T(rows % 2 ? 0.5 : -0.5);
    }
    for(unsigned q = first; q < last; ++q) {
      internal::subtract_symmetric_block_product<D>(expected, &v[std::size_t(q) * U], x[col[q]]);
      if constexpr(std::is_same<T, double>::value) {
        const auto t = internal::symmetric_block_product<D>(&v[std::size_t(q) * U], x[col[q]]);
        for(int c = 0; c < D; ++c)
          expected_sum[std::size_t(c)] += t[std::size_t(c)];
      }
    }
    for(double e : expected)
      negative_zeros += e == 0 && std::signbit(e);
    internal::symmetric_row_products<internal::Row_products::subtract, D>(s, v.data(), col.data(), first, last, x.data());
    same += std::memcmp(s.data(), expected.data(), sizeof s) == 0;
    if constexpr(std::is_same<T, double>::value) {
      internal::symmetric_row_products<internal::Row_products::add, D>(sum, v.data(), col.data(), first, last, x.data());
      same_sum += std::memcmp(sum.data(), expected_sum.data(), sizeof sum) == 0;
    }
  }
  CHECK(same == rows);
  CHECK(same_sum == (std::is_same<T, double>::value ? rows : 0));
  CHECK(negative_zeros > 0);
}

TEST_CASE("solvers: a row of symmetric blocks read from their upper triangles sums as block after block, bit for bit",
          "[solver][block]")
{
  std::mt19937_64 random(13);
  check_symmetric_row_products<2, float>(random);
  check_symmetric_row_products<3, float>(random);
  check_symmetric_row_products<2, double>(random);
  check_symmetric_row_products<3, double>(random);
}

TEST_CASE("solvers: a block of floats stored by columns gives the row-major block's product, bit for bit",
          "[solver][block][multigrid]")
{
  std::mt19937_64 random(11);
  check_block_product_by_columns<2>(random);
  check_block_product_by_columns<3>(random);
  check_block_product_by_columns<6>(random);
}

// The sweeps' single-precision copy: each value that a float holds to 24
// bits (0, or a magnitude in [1e-30, 1e30]) converted, sign of zero
// included; every other value (too small, too large, infinite, NaN) 0, and
// the answer false; for odd and even lengths, on one and two threads.
TEST_CASE("solvers: the single-precision copy converts the values a float holds and zeroes the others",
          "[solver][block]")
{
  const double specials[] = {0.0,   -0.0,   1e-30, -1e-30, 0.99e-30, 1e30, -1e30, 1.01e30, 1e40, -1e-300,
                             1e250, 1.0 / 3.0, -2.5, std::numeric_limits<double>::infinity(),
                             -std::numeric_limits<double>::infinity(), std::numeric_limits<double>::quiet_NaN()};
  std::mt19937_64 random(13);
  std::uniform_real_distribution<double> value(-1.0, 1.0);
  std::uniform_int_distribution<int> exponent(-110, 110);
  for(long n : {0L, 1L, 2L, 7L, 1000L, 1001L})
    for(bool with_specials : {false, true})
      for(int threads : {1, 2}) {
        std::vector<double> v(static_cast<std::size_t>(n));
        for(double& a : v)
          a = std::ldexp(value(random), exponent(random) / 4); // within a float's range
        if(with_specials)
          for(std::size_t k = 0; k < v.size(); ++k)
            if(random() % 3 == 0)
              v[k] = specials[random() % (sizeof specials / sizeof specials[0])];
        bool expected_fits = true;
        std::vector<float> expected(v.size()), single(v.size(), 7.0f);
        for(std::size_t k = 0; k < v.size(); ++k) {
          const double a = std::abs(v[k]);
          const bool f = a == 0 || (a >= 1e-30 && a <= 1e30);
          expected[k] = f ? float(v[k]) : 0.0f;
          expected_fits = expected_fits && f;
        }
        CHECK(internal::copy_to_single(v.data(), single.data(), n, threads) == expected_fits);
        // bit for bit, the sign of zero included (memcmp takes no null pointer: n = 0 is left out)
        CHECK((single.empty() || std::memcmp(single.data(), expected.data(), single.size() * sizeof(float)) == 0));
        if(!with_specials)
          CHECK(expected_fits);
      }
}

namespace {

// A model's symmetric element blocks written out as whole element matrices
// (add_element_matrix), which the assembly loads as whole blocks ...
template <int D, class Model>
struct Whole_blocks_of
{
  Model model;
  Edge_spring_form form;
  Edge_spring_form edge_spring_form() const { return form; }
  void add_element_matrix(const std::array<std::array<double, D>, D + 1>& p, double* K) const
  {
    constexpr int S = D * (D + 1) / 2, ND = (D + 1) * D;
    std::array<double, (D + 1) * (D + 2) / 2 * S> blocks{};
    model.add_symmetric_blocks(p, blocks.data());
    int u = 0;
    for(int a = 0; a <= D; ++a)
      for(int b = a; b <= D; ++b, ++u)
        for(int r = 0; r < D; ++r)
          for(int c = 0; c < D; ++c) {
            const double v = internal::symmetric_entry<D>(&blocks[std::size_t(u * S)], r, c);
            K[(a * D + r) * ND + b * D + c] += v;
            if(a != b) // block (b, a) is block (a, b) transposed, which is itself
              K[(b * D + r) * ND + a * D + c] += v;
          }
  }
};

// ... and the same model giving its distinct symmetric blocks as well
// (add_symmetric_blocks, one element at a time), which the assembly reads
// instead, loading the off-diagonal blocks as upper triangles.
template <int D, class Model>
struct Symmetric_blocks_of : Whole_blocks_of<D, Model>
{
  void add_symmetric_blocks(const std::array<std::array<double, D>, D + 1>& p, double* S) const
  {
    this->model.add_symmetric_blocks(p, S);
  }
};

// The loaded system and the solutions of conjugate gradients (multigrid)
// and SOR on a jittered Kuhn grid, the boundary turned a little.
template <int D>
struct Loaded
{
  bool upper = false;
  std::vector<double> values, diagonal;
  std::vector<std::array<double, D>> cg, sor;
  std::size_t cg_iterations = 0;
};

template <int D, class Model>
Loaded<D> load_and_solve(const Spring_network<D>& net, const std::vector<Index>& free, const Model& model,
                         const std::vector<double>& k, int threads)
{
  Solver_options o;
  o.threads = threads;
  o.tolerance = 1e-10;
  internal::Free_system<D> fs;
  fs.build(net, free, true, o);
  internal::assemble_block_system<D>(net.points, model, k, fs, threads);
  fs.set_positions(net.points);
  std::vector<std::array<double, D>> start(net.number_of_vertices());
  for(std::size_t i = 0; i < start.size(); ++i)
    for(int c = 0; c < D; ++c) // the free vertices' entries are the start, the others prescribed
      start[i][c] = 0.02 * std::sin(3.0 * double(i) + double(c)) + 0.05 * net.points[i][(c + 1) % D];
  Loaded<D> out;
  out.upper = fs.upper_load();
  const double* v = fs.values();
  out.values.assign(v, v + fs.nonzeros() * D * D);
  out.diagonal.assign(fs.diagonal(), fs.diagonal() + fs.rows() * D * D);
  fs.set_start(start, threads);
  const auto report = fs.solve(o);
  CHECK(report.converged);
  out.cg = fs.solution();
  out.cg_iterations = report.iterations;
  o.method = Solver_method::sor;
  o.relaxation_factor = 1.5;
  o.max_iterations = 40;
  fs.set_start(start, threads);
  fs.solve(o);
  out.sor = fs.solution();
  return out;
}

// The network of a jittered Kuhn grid of n cells a side and its interior
// vertices (the free ones; the boundary is fixed), in order.
template <int D>
std::pair<Spring_network<D>, std::vector<Index>> kuhn_network_and_interior(int n)
{
  const auto mesh = spring_motion_test::kuhn_grid<D>(n);
  auto net = make_spring_network<D>(mesh.points, mesh.elements);
  const auto roles = assign_roles(net, [&](const Vertex_info<D>& v) {
    return v.on_boundary ? Vertex_role::fixed : Vertex_role::free;
  });
  std::vector<Index> free;
  for(Index i = 0; i < Index(net.number_of_vertices()); ++i)
    if(roles[i] == Vertex_role::free)
      free.push_back(i);
  return {std::move(net), std::move(free)};
}

template <int D>
void check_upper_load_against_whole_blocks(int n)
{
  const auto grid = kuhn_network_and_interior<D>(n);
  const auto& net = grid.first;
  const auto& free = grid.second;
  REQUIRE(free.size() > 100);
  const Ball_vertex_stiffness ball{2.0};
  // ball-vertex springs alone, and with edge springs along the edges (the
  // edge loop writes the upper triangles too)
  for(const int threads : {1, 2})
    for(const Edge_spring_form form : {Edge_spring_form::none, Edge_spring_form::along_edge}) {
      std::vector<double> k(net.number_of_edges(), 0.0);
      if(form != Edge_spring_form::none)
        for(std::size_t e = 0; e < k.size(); ++e)
          k[e] = 1.0 + double(e % 7);
      INFO(D << "D, " << (form == Edge_spring_form::none ? "ball-vertex springs" : "with springs along the edges")
             << ", " << threads << " thread(s)");
      const auto upper = load_and_solve<D>(net, free, Symmetric_blocks_of<D, Ball_vertex_stiffness>{{ball, form}}, k,
                                           threads);
      const auto whole = load_and_solve<D>(net, free, Whole_blocks_of<D, Ball_vertex_stiffness>{ball, form}, k,
                                           threads);
      REQUIRE(upper.upper);
      REQUIRE_FALSE(whole.upper);
      CHECK(upper.cg_iterations > 2);
      // every value, every solution: bit for bit
      CHECK(upper.values == whole.values);
      CHECK(upper.diagonal == whole.diagonal);
      CHECK(upper.cg == whole.cg);
      CHECK(upper.sor == whole.sor);
      CHECK(upper.cg_iterations == whole.cg_iterations);
      if(form == Edge_spring_form::none) {
        // the model itself (its blocks two elements at a time) loads the same
        const auto own = load_and_solve<D>(net, free, ball, k, threads);
        CHECK(own.upper);
        CHECK(own.values == whole.values);
        CHECK(own.cg == whole.cg);
      }
    }
}


// A load without edge springs, into blocks filled with NaN first: every
// value must equal the load with springs along the edges of stiffness 0
// (whose edge loop writes every block before the elements add to it), the
// coupling blocks too (through the right-hand side). A block left out of
// the clearing keeps its NaN. (Blocks fresh from the allocator often hold
// zeros already, which would hide it.)
template <int D, class Model, class With_springs>
void check_blocks_start_from_zero(const Model& model, const With_springs& with_springs, bool upper, int threads)
{
  const auto grid = kuhn_network_and_interior<D>(D == 2 ? 40 : 9);
  const auto& net = grid.first;
  const auto& free = grid.second;
  std::vector<std::array<double, D>> start(net.number_of_vertices());
  for(std::size_t i = 0; i < start.size(); ++i)
    for(int c = 0; c < D; ++c)
      start[i][c] = 0.01 * std::cos(2.0 * double(i) + double(c));
  const std::vector<double> k(net.number_of_edges(), 0.0);
  Solver_options o;
  o.threads = threads;
  auto load = [&](const auto& m, std::vector<double>& values, std::vector<double>& diagonal,
                  std::vector<std::array<double, D>>& rhs) {
    internal::Free_system<D> fs;
    fs.build(net, free, true, o);
    fs.set_upper_load(upper);
    const auto poison = std::numeric_limits<double>::quiet_NaN();
    std::fill_n(fs.block_values(), fs.bnd_block(Index(fs.bnd_vertices().size())) * D * D, poison);
    if(upper)
      std::fill_n(fs.upper_values(), fs.nonzeros() * D * (D + 1) / 2, poison);
    internal::assemble_block_system<D>(net.points, m, k, fs, threads);
    REQUIRE(fs.upper_load() == upper);
    fs.set_positions(net.points);
    fs.set_start(start, threads);
    values.assign(fs.values(), fs.values() + fs.nonzeros() * D * D);
    diagonal.assign(fs.diagonal(), fs.diagonal() + fs.rows() * D * D);
    rhs = fs.rhs();
  };
  std::vector<double> values, diagonal, values_springs, diagonal_springs;
  std::vector<std::array<double, D>> rhs, rhs_springs;
  REQUIRE(internal::edge_spring_form(model) == Edge_spring_form::none);
  REQUIRE(internal::edge_spring_form(with_springs) == Edge_spring_form::along_edge);
  load(model, values, diagonal, rhs);
  load(with_springs, values_springs, diagonal_springs, rhs_springs);
  REQUIRE(values.size() > 1000);
  CHECK(values == values_springs); // a NaN compares unequal
  CHECK(diagonal == diagonal_springs);
  CHECK(rhs == rhs_springs);
}
} // namespace

TEST_CASE("solvers: a block load without edge springs starts every block from zero, whatever the blocks held",
          "[solver][block]")
{
  // the model itself (its blocks four or two elements at a time, as upper
  // triangles), and its whole element matrices (whole blocks)
  const Ball_vertex_stiffness ball{2.0};
  const auto none = Edge_spring_form::none, along = Edge_spring_form::along_edge;
  for(const int threads : {1, 2}) {
    INFO(threads << " thread(s)");
    check_blocks_start_from_zero<2>(ball, Symmetric_blocks_of<2, Ball_vertex_stiffness>{{ball, along}}, true,
                                      threads);
    check_blocks_start_from_zero<3>(ball, Symmetric_blocks_of<3, Ball_vertex_stiffness>{{ball, along}}, true,
                                      threads);
    check_blocks_start_from_zero<2>(Whole_blocks_of<2, Ball_vertex_stiffness>{ball, none},
                                      Whole_blocks_of<2, Ball_vertex_stiffness>{ball, along}, false, threads);
    check_blocks_start_from_zero<3>(Whole_blocks_of<3, Ball_vertex_stiffness>{ball, none},
                                      Whole_blocks_of<3, Ball_vertex_stiffness>{ball, along}, false, threads);
  }
}

TEST_CASE("solvers: a load of symmetric blocks as upper triangles gives the values and solutions of whole blocks, "
          "bit for bit",
          "[solver][block]")
{
  check_upper_load_against_whole_blocks<2>(24);
  check_upper_load_against_whole_blocks<3>(7);
}
