#include <spring_motion/spring_motion.h>
#include <spring_motion/stiffness/model_by_name.h>

#include "test_meshes.h"

#include <catch2/catch.hpp>

#include <Eigen/Sparse>
#include <Eigen/SparseCholesky>

#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <sstream>
#include <type_traits>

using namespace spring_motion;
using namespace spring_motion_test;

namespace {

std::map<std::pair<double, double>, std::array<double, 2>> positions_by_initial_point(
    const CDT& before, const CDT& after)
{
  // vertex handles survive deform(): pair them by iterating both in order
  std::map<std::pair<double, double>, std::array<double, 2>> m;
  auto a = after.finite_vertices_begin();
  for(auto b = before.finite_vertices_begin(); b != before.finite_vertices_end(); ++b, ++a)
    m[{b->point().x(), b->point().y()}] = {a->point().x(), a->point().y()};
  return m;
}

// The annulus of make_annulus() with its inner circle moving, the outer fixed.
struct Annulus
{
  Spring_network<2> net;
  std::vector<Vertex_role> roles;
};
Annulus annulus_turning_inside()
{
  CDT cdt;
  make_annulus(cdt);
  auto net = extract_spring_network(cdt).network;
  auto roles = assign_roles(net, moving_boundary_where([](const std::array<double, 2>& p) {
                              return std::hypot(p[0], p[1]) < 1.0;
                            }));
  return {std::move(net), std::move(roles)};
}

} // namespace

TEST_CASE("deform: a rigid translation of the whole boundary translates every vertex", "[deform]")
{
  CDT cdt;
  make_square_with_hole(cdt);
  CDT original = cdt;
  const std::array<double, 2> d{0.3, -0.2};
  Deform_options options;
  options.number_of_steps = 5;
  // the sweep criterion is not the error (docs/method.md, "Solver"): ask for a
  // criterion far below the round-off level we then check against
  options.solver.tolerance = 1e-16;
  const auto report = deform(cdt, All_boundary_moving{}, Translation_motion<2>{d}, Grid_scaled_stiffness{}, options);
  REQUIRE(report.completed);
  REQUIRE(report.converged);
  const auto moved = positions_by_initial_point(original, cdt);
  double worst = 0;
  for(const auto& [p0, p] : moved) {
    worst = std::max(worst, std::abs(p[0] - (p0.first + d[0])));
    worst = std::max(worst, std::abs(p[1] - (p0.second + d[1])));
  }
  // a uniform field solves every spring system exactly: only round-off remains
  INFO("worst deviation " << worst);
  CHECK(worst < 1e-12);
  CHECK(report.min_size_ratio == Approx(1.0).epsilon(1e-10));
}

TEST_CASE("deform: the warm start extrapolates the increments by the parabola through the last three steps",
          "[deform][warm_start]")
{
  // Every boundary vertex moves by t^3 d, so every vertex's exact increment
  // over step k is (t_k^3 - t_{k-1}^3) d: per unit of fraction 3 m^2 + h^2 / 4
  // at the step's midpoint m (steps of fraction h), a parabola in m. From the
  // fourth step the parabola through the last three increments gives it to
  // rounding; at the third, the line through two is off by g''/2 (m - m1)
  // (m - m2) = 6 h^2 per unit of fraction, 6 h^3 |d_c| in the increment.
  CDT cdt;
  make_square_with_hole(cdt);
  const auto net = extract_spring_network(cdt).network;
  struct Cubic_translation
  {
    std::array<double, 2> d;
    std::array<double, 2> operator()(const std::array<double, 2>& p0, double t) const
    {
      return {p0[0] + t * t * t * d[0], p0[1] + t * t * t * d[1]};
    }
  };
  const Cubic_translation motion{{0.3, -0.2}};
  Deform_options options;
  options.number_of_steps = 6;
  options.solver.tolerance = 1e-14; // the solves end at rounding level: the start's error is the extrapolation's
  const double h = 1.0 / double(options.number_of_steps);
  Network_deformer<2> deformer(net, assign_roles(net, All_boundary_moving{}));
  std::vector<double> start_error; // per step: max over rows of |start - exact increment| / max |d_c|
  deformer.system_observer = [&](const Step_system_view<2>& v) {
    const double t1 = double(start_error.size() + 1) * h, t0 = t1 - h;
    const double f = t1 * t1 * t1 - t0 * t0 * t0;
    double e = 0;
    for(std::size_t r = 0; r < v.rows; ++r)
      for(int c = 0; c < 2; ++c)
        e = std::max(e, std::abs(v.initial[r][c] - f * motion.d[std::size_t(c)]));
    start_error.push_back(e / std::max(std::abs(motion.d[0]), std::abs(motion.d[1])));
  };
  const auto report = deformer.run(motion, Grid_scaled_stiffness{}, options);
  REQUIRE(report.completed);
  REQUIRE(report.converged);
  REQUIRE(start_error.size() == 6);
  INFO("start errors / |d|: " << start_error[2] << " " << start_error[3] << " " << start_error[4] << " "
                              << start_error[5]);
  CHECK(start_error[2] == Approx(6 * h * h * h).epsilon(1e-9));
  for(std::size_t k = 3; k < 6; ++k)
    CHECK(start_error[k] < 1e-11);
}

TEST_CASE("deform: one small rotation of an annulus's inner circle matches a direct solve", "[deform]")
{
  CDT cdt;
  make_annulus(cdt);
  const auto ext = extract_spring_network(cdt);
  const auto& net = ext.network;
  const double angle = 2.0; // degrees
  auto inner = [](const std::array<double, 2>& p) { return std::hypot(p[0], p[1]) < 1.0; };

  // Reference: the lineal spring system (k = 1/l) assembled and solved directly,
  // independently of the library's assembly and SOR.
  Pitch_motion<2> motion(angle, {0.0, 0.0});
  const std::size_t n = net.number_of_vertices();
  std::vector<int> unknown(n, -1);
  int nu = 0;
  for(std::size_t i = 0; i < n; ++i)
    if(!net.on_boundary[i])
      unknown[i] = nu++;
  std::vector<std::array<double, 2>> prescribed(n, {0, 0});
  for(std::size_t i = 0; i < n; ++i)
    if(net.on_boundary[i] && inner(net.points[i])) {
      const auto q = motion(net.points[i], 1.0);
      prescribed[i] = {q[0] - net.points[i][0], q[1] - net.points[i][1]};
    }
  std::vector<Eigen::Triplet<double>> trip;
  Eigen::MatrixXd rhs = Eigen::MatrixXd::Zero(nu, 2);
  for(const auto& e : net.edges) {
    const double k = 1.0 / std::hypot(net.points[e[0]][0] - net.points[e[1]][0],
                                      net.points[e[0]][1] - net.points[e[1]][1]);
    for(int s = 0; s < 2; ++s) {
      const std::size_t i = e[s], j = e[1 - s];
      if(unknown[i] < 0)
        continue;
      trip.emplace_back(unknown[i], unknown[i], k);
      if(unknown[j] >= 0)
        trip.emplace_back(unknown[i], unknown[j], -k);
      else
        for(int c = 0; c < 2; ++c)
          rhs(unknown[i], c) += k * prescribed[j][c];
    }
  }
  Eigen::SparseMatrix<double> A(nu, nu);
  A.setFromTriplets(trip.begin(), trip.end());
  Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> ldlt(A);
  REQUIRE(ldlt.info() == Eigen::Success);
  const Eigen::MatrixXd x = ldlt.solve(rhs);

  Deform_options options;
  options.number_of_steps = 1;
  options.solver.tolerance = 1e-14;
  Network_deformer<2> deformer(net, assign_roles(net, moving_boundary_where(inner)));
  const auto report = deformer.run(motion, Lineal_stiffness{}, options);
  REQUIRE(report.completed);
  REQUIRE(report.converged);
  double worst = 0, largest = 0;
  for(std::size_t i = 0; i < n; ++i) {
    std::array<double, 2> expected = net.points[i];
    for(int c = 0; c < 2; ++c)
      expected[c] += unknown[i] >= 0 ? x(unknown[i], c) : prescribed[i][c];
    if(net.on_boundary[i] && inner(net.points[i]))
      expected = motion(net.points[i], 1.0);
    for(int c = 0; c < 2; ++c) {
      worst = std::max(worst, std::abs(deformer.positions()[i][c] - expected[c]));
      largest = std::max(largest, std::abs(expected[c] - net.points[i][c]));
    }
  }
  CHECK(largest > 0.01); // the motion is not trivially zero
  CHECK(worst < 1e-10);
}

TEST_CASE("deform: a step that pushes a vertex across its opposite edge is rolled back", "[deform][validity]")
{
  // the unit square split into four triangles around the centre vertex 4
  Indexed_mesh<2> mesh;
  mesh.points = {{0, 0}, {1, 0}, {1, 1}, {0, 1}, {0.5, 0.5}};
  mesh.elements = {{0, 1, 4}, {1, 2, 4}, {2, 3, 4}, {3, 0, 4}};
  // centre moves right by 1.2 in 4 steps: x = 0.8, 1.1 (beyond the edge 1-2), ...
  auto centre_moves = [](const Vertex_info<2>& v) {
    return v.index == 4 ? Vertex_role::moving : Vertex_role::fixed;
  };
  Deform_options options;
  options.number_of_steps = 4;
  const auto report = deform(mesh, centre_moves, Translation_motion<2>{{1.2, 0}}, Lineal_stiffness{}, options);
  CHECK_FALSE(report.completed);
  REQUIRE(report.first_invalid);
  CHECK(report.first_invalid->step == 2);
  // at x = 1.1 only the triangle on edge 1-2 has flipped
  CHECK(report.first_invalid->elements == std::vector<std::size_t>{1});
  CHECK(report.final_fraction == Approx(0.25));
  // the mesh is left at the last valid step
  CHECK(mesh.points[4][0] == Approx(0.8));
  CHECK(mesh.points[4][1] == Approx(0.5));
  CHECK(report.steps.size() == 2);
  CHECK(report.steps[1].inverted == 1);
}

TEST_CASE("deform: with substepping a step is split and reported", "[deform][substep]")
{
  Indexed_mesh<2> mesh;
  mesh.points = {{0, 0}, {1, 0}, {1, 1}, {0, 1}, {0.5, 0.5}};
  mesh.elements = {{0, 1, 4}, {1, 2, 4}, {2, 3, 4}, {3, 0, 4}};
  auto centre_moves = [](const Vertex_info<2>& v) {
    return v.index == 4 ? Vertex_role::moving : Vertex_role::fixed;
  };
  // no substep can save a motion whose end is invalid: every retry fails and
  // the mesh is left at the start of the step
  Deform_options options;
  options.number_of_steps = 1;
  options.max_substep_halvings = 3;
  const auto report = deform(mesh, centre_moves, Translation_motion<2>{{0.8, 0}}, Lineal_stiffness{}, options);
  CHECK_FALSE(report.completed);
  CHECK(report.final_fraction == 0.0);
  CHECK(mesh.points[4][0] == 0.5);
  CHECK(report.steps[0].substeps == 8); // the finest division tried
  REQUIRE(report.first_invalid);
  // at the last try, x = 0.5 + 0.8 * 5/8 = 1 puts the centre on edge 1-2
  CHECK(report.first_invalid->elements == std::vector<std::size_t>{1});
}

TEST_CASE("deform: substepping rescues a rotation that one increment would invert", "[deform][substep]")
{
  CDT cdt;
  make_annulus(cdt);
  auto inner = [](const std::array<double, 2>& p) { return std::hypot(p[0], p[1]) < 1.0; };
  Deform_options options;
  options.number_of_steps = 1;
  CDT once = cdt;
  const auto plain = deform(once, moving_boundary_where(inner), Pitch_motion<2>(60, {0, 0}), Grid_scaled_stiffness{}, options);
  REQUIRE_FALSE(plain.completed);
  options.max_substep_halvings = 8;
  const auto rescued = deform(cdt, moving_boundary_where(inner), Pitch_motion<2>(60, {0, 0}), Grid_scaled_stiffness{}, options);
  CHECK(rescued.completed);
  // the report says how many equal substeps the step took: a power of two
  const std::size_t k = rescued.steps[0].substeps;
  CHECK(k > 1);
  CHECK((k & (k - 1)) == 0);
  // the result is valid by the exact predicate
  const auto ext = extract_spring_network(cdt);
  for(auto f = cdt.finite_faces_begin(); f != cdt.finite_faces_end(); ++f)
    if(f->is_in_domain())
      CHECK(CGAL::orientation(f->vertex(0)->point(), f->vertex(1)->point(), f->vertex(2)->point()) ==
            CGAL::LEFT_TURN);
}

TEST_CASE("deform: free vertices that reach no constrained vertex are an error", "[deform][errors]")
{
  // two triangles sharing nothing: the second has no constrained vertex
  Indexed_mesh<2> mesh;
  mesh.points = {{0, 0}, {1, 0}, {0, 1}, {5, 5}, {6, 5}, {5, 6}};
  mesh.elements = {{0, 1, 2}, {3, 4, 5}};
  auto roles = [](const Vertex_info<2>& v) { return v.index < 3 ? Vertex_role::moving : Vertex_role::free; };
  CHECK_THROWS_WITH(deform(mesh, roles, Translation_motion<2>{{0.1, 0}}, Lineal_stiffness{}),
                    Catch::Contains("connected to no constrained vertex"));
}

TEST_CASE("deform: a rigid translation of the whole boundary translates every vertex, with every model",
          "[deform][models]")
{
  CDT cdt;
  make_square_with_hole(cdt);
  const CDT original = cdt;
  const std::array<double, 2> d{-0.25, 0.4};
  Deform_options options;
  options.number_of_steps = 3;
  // a uniform increment solves every model's system exactly (springs do not
  // stretch, angles do not change, so the torsion terms vanish too): ask for
  // a criterion at the round-off level
  options.solver.tolerance = 1e-15;
  for(const auto& name : model_names()) {
    INFO("model " << name);
    CDT moved = original;
    const auto report = with_model(name, [&](const auto& model) {
      return deform(moved, All_boundary_moving{}, Translation_motion<2>{d}, model, options);
    });
    REQUIRE(report.completed);
    CHECK(report.converged);
    double worst = 0;
    for(const auto& [p0, p] : positions_by_initial_point(original, moved))
      worst = std::max({worst, std::abs(p[0] - (p0.first + d[0])), std::abs(p[1] - (p0.second + d[1]))});
    CHECK(worst < 1e-12); // round-off on coordinates of size 2
  }
}

TEST_CASE("deform: the reports give the smallest and largest area ratio", "[deform][quality]")
{
  // the unit square split into four triangles around the centre vertex 4;
  // moving the centre by (0.2, 0) changes the heights over the right and
  // left sides from 1/2 to 0.3 and 0.7: area ratios 0.6 and 1.4, the other
  // two triangles keep theirs
  Indexed_mesh<2> mesh;
  mesh.points = {{0, 0}, {1, 0}, {1, 1}, {0, 1}, {0.5, 0.5}};
  mesh.elements = {{0, 1, 4}, {1, 2, 4}, {2, 3, 4}, {3, 0, 4}};
  auto centre_moves = [](const Vertex_info<2>& v) {
    return v.index == 4 ? Vertex_role::moving : Vertex_role::fixed;
  };
  Deform_options options;
  options.number_of_steps = 2;
  const auto report = deform(mesh, centre_moves, Translation_motion<2>{{0.2, 0}}, Lineal_stiffness{}, options);
  REQUIRE(report.completed);
  // a few roundings in the areas
  CHECK(report.min_size_ratio == Approx(0.6).epsilon(1e-14));
  CHECK(report.max_size_ratio == Approx(1.4).epsilon(1e-14));
  // halfway: heights 0.4 and 0.6
  REQUIRE(report.steps.size() == 2);
  CHECK(report.steps[0].min_size_ratio == Approx(0.8).epsilon(1e-14));
  CHECK(report.steps[0].max_size_ratio == Approx(1.2).epsilon(1e-14));
  std::ostringstream json;
  write_report_json(report, json);
  CHECK_THAT(json.str(), Catch::Contains("\"max_size_ratio\": 1.4"));
}

// A Kuhn grid (two triangles a square, six tetrahedra a cube) with a hole
// that turns and then jumps back, its interior vertices jittered or not
// (then far from the hole most elements keep the angles of the undisturbed
// lattice, 45 and 90 degrees, 60 too in 3D, to the bit). A step's quality
// pass guesses its extremes from the step before. Each step's figures must
// be those of every element's angles computed one by one, also at the jump
// back, where the extremes improve past the guess and the pass is made
// again. With `squeezed`, the vertex next to a corner of the box is moved
// towards its neighbour: the worst elements then lie far from the hole, and
// the moving set's extremes inside the whole set's (the pass tests an
// element at the hole against the moving set's own bound).
TEMPLATE_TEST_CASE("deform: each step's quality on a Kuhn grid equals the elements' own, the guess of the extremes "
                   "missed or not",
                   "[deform][quality]", (std::integral_constant<int, 2>), (std::integral_constant<int, 3>))
{
  constexpr int D = TestType::value;
  using Point = std::array<double, D>;
  const double jitter = GENERATE(0.0, 0.15);
  const bool squeezed = GENERATE(false, true);
  INFO("jitter " << jitter << (squeezed ? ", squeezed" : ""));
  // the 8^D cells' elements, without those of the 2^D cells around the centre
  Indexed_mesh<D> box = spring_motion_test::kuhn_grid<D>(8, jitter);
  if(squeezed)
    box.points[D == 2 ? 1 + 9 : 1 + 9 + 81][0] += 0.4; // the lattice's (1, 1) or (1, 1, 1)
  // the hole and its vertices found on the unjittered lattice (the same numbering)
  const Indexed_mesh<D> lattice = spring_motion_test::kuhn_grid<D>(8, 0.0);
  const auto in_hole = [](const Point& p, bool closed) {
    return std::all_of(p.begin(), p.end(), [&](double x) { return closed ? x >= 3 && x <= 5 : x > 3 && x < 5; });
  };
  std::vector<std::array<Index, D + 1>> elements;
  for(const auto& e : box.elements) {
    Point c{};
    for(const Index v : e)
      for(int a = 0; a < D; ++a)
        c[std::size_t(a)] += lattice.points[v][std::size_t(a)] / (D + 1);
    if(!in_hole(c, false))
      elements.push_back(e);
  }
  auto net = make_spring_network<D>(box.points, elements);
  const auto roles = assign_roles(net, [&](const Vertex_info<D>& v) {
    if(!v.on_boundary)
      return Vertex_role::free;
    return in_hole(lattice.points[v.index], true) ? Vertex_role::moving : Vertex_role::fixed;
  });
  Network_deformer<D> deformer(net, roles);
  const auto& moving = deformer.moving_vertices();
  REQUIRE(moving.size() == (D == 2 ? 8u : 26u));
  const double pi = std::acos(-1.0);
  std::size_t step = 0;
  for(const double degrees : {2.0, 4.0, 6.0, 8.0, 10.0, 12.0, 10.0, 0.0, 3.0, 0.0}) {
    ++step;
    const double a = degrees * pi / 180;
    // a turn about the hole's centre in the xy plane
    std::vector<Point> d;
    for(const Index v : moving) {
      const auto& p = net.points[v];
      Point q{};
      q[0] = 4 + std::cos(a) * (p[0] - 4) - std::sin(a) * (p[1] - 4) - p[0];
      q[1] = 4 + std::sin(a) * (p[0] - 4) + std::cos(a) * (p[1] - 4) - p[1];
      d.push_back(q);
    }
    for(const int threads : {1, 2}) {
      Deform_options options;
      options.solver.threads = threads;
      Network_deformer<D> copy = deformer; // each thread count from the same state
      const Step_report s = copy.move(d, Grid_scaled_stiffness{}, options);
      REQUIRE(s.inverted == 0);
      std::vector<double> min_angle;
      const auto r = element_skewness(copy.network(), copy.positions(), 1, &min_angle);
      double r_moving = 0, angle_moving = 180;
      for(std::size_t t = 0; t < r.size(); ++t) {
        bool touches = false;
        for(const Index v : copy.network().elements[t])
          touches = touches || roles[v] == Vertex_role::moving;
        if(touches) {
          r_moving = std::max(r_moving, r[t]);
          angle_moving = std::min(angle_moving, min_angle[t]);
        }
      }
      INFO("step " << step << " (" << degrees << " degrees), " << threads << " thread(s)");
      if(squeezed) // the premise: the smallest angle lies away from the hole
        CHECK(angle_moving > *std::min_element(min_angle.begin(), min_angle.end()));
      CHECK(s.max_skewness_all == *std::max_element(r.begin(), r.end()));
      CHECK(s.min_angle_deg_all == *std::min_element(min_angle.begin(), min_angle.end()));
      CHECK(s.max_skewness_moving == r_moving);
      CHECK(s.min_angle_deg_moving == angle_moving);
      if(threads == 2)
        deformer = std::move(copy);
    }
  }
  CHECK(step == 10);
}

namespace {
// A pitch that counts its evaluations.
struct Counting_motion
{
  Pitch_motion<2> pitch;
  std::size_t* calls;
  std::array<double, 2> operator()(const std::array<double, 2>& p, double t) const
  {
    ++*calls;
    return pitch(p, t);
  }
};
} // namespace

TEST_CASE("deform: the motion is evaluated once per moving vertex and attempt", "[deform]")
{
  const Annulus annulus = annulus_turning_inside();
  const auto& net = annulus.net;
  const auto& roles = annulus.roles;
  std::size_t calls = 0;
  Network_deformer<2> d(net, roles);
  Deform_options options;
  options.number_of_steps = 4;
  const auto r = d.run(Counting_motion{Pitch_motion<2>(10, {0, 0}), &calls}, Grid_scaled_stiffness{}, options);
  REQUIRE(r.completed);
  CHECK(calls == options.number_of_steps * d.number_of_moving_vertices());
}

TEST_CASE("deform: a second run with other solver options rebuilds the solver state", "[deform][solver]")
{
  CDT cdt;
  make_square_with_hole(cdt);
  const auto net = extract_spring_network(cdt).network;
  const auto roles = assign_roles(net, moving_boundary_where([](const std::array<double, 2>& p) {
                                    return std::max(std::abs(p[0]), std::abs(p[1])) < 1.0;
                                  }));
  const Pitch_motion<2> motion(20, {0, 0});
  Deform_options first, second;
  first.number_of_steps = second.number_of_steps = 5;
  first.solver.ordering = Vertex_ordering::multicolour;
  // another ordering, and for the block system the same ordering with other
  // multigrid aggregates: each must give what a fresh deformer gives
  const int variant = GENERATE(0, 1, 2);
  if(variant == 0)
    second.solver.ordering = Vertex_ordering::natural;
  else if(variant == 1)
    second.solver.block_rows = 32;
  else {
    second.solver.ordering = Vertex_ordering::multicolour;
    second.solver.multigrid_strength = 0.2;
  }
  auto check = [&](const auto& model) {
    Network_deformer<2> reused(net, roles);
    REQUIRE(reused.run(motion, model, first).completed);
    reused.reset();
    CHECK(reused.fraction() == 0.0);
    const auto a = reused.run(motion, model, second);
    Network_deformer<2> fresh(net, roles);
    const auto b = fresh.run(motion, model, second);
    REQUIRE(a.completed);
    REQUIRE(b.completed);
    for(std::size_t i = 0; i < a.steps.size(); ++i)
      CHECK(a.steps[i].iterations == b.steps[i].iterations);
    CHECK(reused.positions() == fresh.positions()); // bit for bit
  };
  SECTION("scalar system") { check(Grid_scaled_stiffness{}); }
  SECTION("block system") { check(Torsional_stiffness{}); }
}

TEST_CASE("deform: move() step by step reproduces run() with the same schedule", "[deform][move]")
{
  const Annulus annulus = annulus_turning_inside();
  const auto& net = annulus.net;
  const auto& roles = annulus.roles;
  const Pitch_motion<2> pitch(30, {0.1, 0});
  Deform_options options;
  options.number_of_steps = 6;
  options.solver.tolerance = 1e-9;
  Network_deformer<2> whole(net, roles);
  const auto report = whole.run(pitch, Grid_scaled_stiffness{}, options);
  REQUIRE(report.completed);

  Network_deformer<2> stepped(net, roles);
  const auto& moving = stepped.moving_vertices();
  REQUIRE(moving.size() == stepped.number_of_moving_vertices());
  const std::vector<std::array<double, 2>>* positions = &stepped.positions();
  const std::array<double, 2>* storage = stepped.positions().data();
  // the moving vertices' displacements at step i of the schedule
  const auto displacement = [&](std::size_t i) {
    const double t = double(i) / double(options.number_of_steps);
    std::vector<std::array<double, 2>> d;
    for(Index v : moving) {
      const auto q = pitch(net.points[v], t);
      d.push_back({q[0] - net.points[v][0], q[1] - net.points[v][1]});
    }
    return d;
  };
  for(std::size_t i = 1; i <= options.number_of_steps; ++i) {
    const Step_report s = stepped.move(displacement(i), Grid_scaled_stiffness{}, options);
    CHECK(s.inverted == 0);
    CHECK(s.converged);
    CHECK(s.step == i);
    CHECK(s.max_skewness_all == Approx(report.steps[i - 1].max_skewness_all).epsilon(1e-6));
  }
  CHECK(&stepped.positions() == positions); // read in place, no copy
  CHECK(stepped.positions().data() == storage); // the same storage: a view of it (Python's) stays valid
  // each step's solve ends within about tol of the same solution; the
  // differences carry into the next step's stiffness and add up over the
  // steps (as in test_solver.cpp), a factor 10 because the error is an estimate
  double diff = 0;
  for(std::size_t v = 0; v < net.number_of_vertices(); ++v)
    for(int c = 0; c < 2; ++c)
      diff = std::max(diff, std::abs(stepped.positions()[v][c] - whole.positions()[v][c]));
  CHECK(diff <= 10 * 2 * double(options.number_of_steps) * options.solver.tolerance);

  // the step memory released after every step: each step rebuilds it and
  // goes on from the same state
  Network_deformer<2> released(net, roles);
  for(std::size_t i = 1; i <= options.number_of_steps; ++i) {
    const Step_report s = released.move(displacement(i), Grid_scaled_stiffness{}, options);
    CHECK(s.converged);
    CHECK(s.step == i);
    released.release_step_memory();
  }
  double diff_released = 0;
  for(std::size_t v = 0; v < net.number_of_vertices(); ++v)
    for(int c = 0; c < 2; ++c)
      diff_released = std::max(diff_released, std::abs(released.positions()[v][c] - whole.positions()[v][c]));
  CHECK(diff_released <= 10 * 2 * double(options.number_of_steps) * options.solver.tolerance);
}

TEST_CASE("deform: an invalid move() is rolled back and reported", "[deform][move]")
{
  const Annulus annulus = annulus_turning_inside();
  const auto& net = annulus.net;
  const auto& roles = annulus.roles;
  Network_deformer<2> d(net, roles);
  auto displacement = [&](double degrees) {
    const Pitch_motion<2> turn(degrees, {0, 0});
    std::vector<std::array<double, 2>> out;
    for(Index v : d.moving_vertices()) {
      const auto q = turn(net.points[v], 1.0);
      out.push_back({q[0] - net.points[v][0], q[1] - net.points[v][1]});
    }
    return out;
  };
  const Step_report first = d.move(displacement(5), Grid_scaled_stiffness{});
  REQUIRE(first.inverted == 0);
  const auto valid = d.positions();
  // 60 degrees in one increment inverts elements (test_substepping.cpp)
  const Step_report bad = d.move(displacement(60), Grid_scaled_stiffness{});
  CHECK(bad.inverted > 0);
  CHECK(bad.inverted == d.last_inverted_elements().size());
  CHECK(d.positions() == valid); // bit for bit the last valid state
  CHECK(d.fraction() == 1.0);    // one accepted move
  // and the deformer goes on from there
  const Step_report next = d.move(displacement(8), Grid_scaled_stiffness{});
  CHECK(next.inverted == 0);
  CHECK(d.last_inverted_elements().empty());
  CHECK(d.fraction() == 2.0);
}

TEST_CASE("deform: the report's smallest angles and each element's R are those of the final positions",
          "[deform][angles]")
{
  const Annulus annulus = annulus_turning_inside();
  const auto& net = annulus.net;
  const auto& roles = annulus.roles;
  Network_deformer<2> d(net, roles);
  Deform_options options;
  options.number_of_steps = 6;
  const auto r = d.run(Pitch_motion<2>(40, {0, 0}), Grid_scaled_stiffness{}, options);
  REQUIRE(r.completed);
  // law of cosines on the written positions: independent of the library's angles
  double moving = 180, all = 180;
  const auto& x = d.positions();
  REQUIRE(r.element_skewness.size() == net.number_of_elements());
  for(std::size_t t = 0; t < net.number_of_elements(); ++t) {
    const auto& e = net.elements[t];
    double lo = 180, hi = 0;
    for(int k = 0; k < 3; ++k) {
      const auto& p = x[e[k]];
      const auto& q = x[e[(k + 1) % 3]];
      const auto& o = x[e[(k + 2) % 3]];
      const double a2 = (q[0] - o[0]) * (q[0] - o[0]) + (q[1] - o[1]) * (q[1] - o[1]);
      const double b2 = (p[0] - o[0]) * (p[0] - o[0]) + (p[1] - o[1]) * (p[1] - o[1]);
      const double c2 = (p[0] - q[0]) * (p[0] - q[0]) + (p[1] - q[1]) * (p[1] - q[1]);
      // angle at o, opposite the side p-q
      const double angle = std::acos((a2 + b2 - c2) / (2 * std::sqrt(a2 * b2))) * 180 / 3.141592653589793;
      all = std::min(all, angle);
      if(d.touches_moving(t))
        moving = std::min(moving, angle);
      lo = std::min(lo, angle);
      hi = std::max(hi, angle);
    }
    // each element's R (Eq. 13) from the same angles
    const double skewness = std::max((hi - 60) / 120, (60 - lo) / 60);
    INFO("element " << t << ": report " << r.element_skewness[t] << ", recomputed " << skewness);
    CHECK(std::abs(r.element_skewness[t] - skewness) < 1e-9);
  }
  CHECK(*std::max_element(r.element_skewness.begin(), r.element_skewness.end()) == r.quality_all.max);
  INFO("report " << r.min_angle_deg_moving << " / " << r.min_angle_deg_all << ", recomputed " << moving << " / "
                 << all);
  CHECK(std::abs(r.min_angle_deg_moving - moving) < 1e-9);
  CHECK(std::abs(r.min_angle_deg_all - all) < 1e-9);
  CHECK(moving < 60); // not the default of an empty set
  // the last step's figures describe the same final state
  CHECK(r.steps.back().min_angle_deg_moving == r.min_angle_deg_moving);
  CHECK(r.steps.back().min_angle_deg_all == r.min_angle_deg_all);
  // the motion squeezed the mesh: smaller than at the start
  Network_deformer<2> initial(net, roles);
  std::vector<double> a;
  element_skewness(net, initial.positions(), 0, &a);
  CHECK(r.min_angle_deg_all <= *std::min_element(a.begin(), a.end()));
}
