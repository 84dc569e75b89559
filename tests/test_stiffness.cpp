// Stiffness models (include/spring_motion/stiffness/): values on hand-computed
// triangles (docs/method.md, "Stiffness models"), the torsional angle derivatives against
// finite differences, the invariance of the motion under k -> c k, and user
// models passed to deform().
#include <spring_motion/spring_motion.h>
#include <spring_motion/internal/solver/assemble.h>

#include "test_meshes.h"

#include <catch2/catch.hpp>

#include <Eigen/Sparse>
#include <Eigen/SparseCholesky>

#include <array>
#include <cmath>
#include <map>
#include <utility>
#include <vector>

using namespace spring_motion;
using namespace spring_motion_test;

namespace {

using P2 = std::array<double, 2>;
using Edge_key = std::pair<Index, Index>;

// The values below are a few floating-point operations (pow, sin, atan2) on
// O(1) inputs, so they are right to a few ulps: a relative 1e-13 is far above
// that and far below the size of any mistake in a formula.
constexpr double value_tolerance = 1e-13;

// k of every edge of the mesh made of `triangles`, keyed by (smaller, larger)
// vertex: through the library's own path (angles routed from the elements to
// the edges, l0 = the longest initial edge).
template <class Model>
std::map<Edge_key, double> edge_stiffness(std::vector<P2> points, std::vector<std::array<Index, 3>> triangles,
                                          const Model& model)
{
  const auto net = make_spring_network<2>(std::move(points), std::move(triangles));
  std::vector<double> k;
  internal::Stiffness_scratch<2> scratch;
  internal::compute_edge_stiffness(net, net.points, model, Stiffness_context{2, net.longest_initial_edge}, k,
                                   scratch, 1);
  std::map<Edge_key, double> out;
  for(std::size_t e = 0; e < net.number_of_edges(); ++e)
    out[{net.edges[e][0], net.edges[e][1]}] = k[e];
  return out;
}

void check_values(const std::map<Edge_key, double>& got, const std::map<Edge_key, double>& expected)
{
  REQUIRE(got.size() == expected.size());
  for(const auto& [edge, value] : expected) {
    INFO("edge " << edge.first << "-" << edge.second);
    REQUIRE(got.count(edge) == 1);
    CHECK(got.at(edge) == Approx(value).epsilon(value_tolerance));
  }
}

const double pi = internal::pi;

// Equilateral triangle of side 2: every edge has l = 2 and one facing angle
// pi/3 (sin^2 = 3/4, 1/sin^2 = 4/3); l0 = 2.
const std::vector<P2> equilateral{{0, 0}, {2, 0}, {1, std::sqrt(3.0)}};
// Right triangle 3-4-5: edge 0-1 (l = 4) faces the angle at (0,3) with
// sin = 4/5 (1/sin^2 = 25/16, angle atan(4/3)); edge 0-2 (l = 3) faces the
// angle at (4,0) with sin = 3/5 (1/sin^2 = 25/9, angle atan(3/4)); edge 1-2
// (l = 5) faces the right angle (1/sin^2 = 1). l0 = 5.
const std::vector<P2> right{{0, 0}, {4, 0}, {0, 3}};
// Obtuse isosceles triangle: base 0-1 (l = 2) faces the apex angle, whose
// cosine is ((-1)(1) + (-1/2)(-1/2)) / (5/4) = -3/5: sin = 4/5, 1/sin^2 = 25/16,
// angle pi - atan(4/3). Sides 0-2 and 1-2 (l = sqrt(5)/2) face a base angle
// atan(1/2): sin^2 = 1/5, 1/sin^2 = 5. l0 = 2.
const std::vector<P2> obtuse{{0, 0}, {2, 0}, {1, 0.5}};
const std::vector<std::array<Index, 3>> one_triangle{{0, 1, 2}};
// Unit square cut along the diagonal 0-2: the diagonal (l = sqrt 2) has two
// facing angles, both pi/2 (1/sin^2 = 1); each side (l = 1) has one, pi/4
// (1/sin^2 = 2). l0 = sqrt 2.
const std::vector<P2> square{{0, 0}, {1, 0}, {1, 1}, {0, 1}};
const std::vector<std::array<Index, 3>> two_triangles{{0, 1, 2}, {0, 2, 3}};

const double s5 = std::sqrt(5.0), s2 = std::sqrt(2.0);

} // namespace

TEST_CASE("Lineal_stiffness: k = 1/l^p on hand-computed triangles", "[stiffness]")
{
  SECTION("p = 1")
  {
    const Lineal_stiffness m{1.0};
    check_values(edge_stiffness(equilateral, one_triangle, m), {{{0, 1}, 0.5}, {{0, 2}, 0.5}, {{1, 2}, 0.5}});
    check_values(edge_stiffness(right, one_triangle, m), {{{0, 1}, 1.0 / 4}, {{0, 2}, 1.0 / 3}, {{1, 2}, 1.0 / 5}});
    check_values(edge_stiffness(obtuse, one_triangle, m), {{{0, 1}, 0.5}, {{0, 2}, 2 / s5}, {{1, 2}, 2 / s5}});
  }
  SECTION("p = 2 (the paper's Eq. 1 as printed)")
  {
    const Lineal_stiffness m{2.0};
    check_values(edge_stiffness(equilateral, one_triangle, m), {{{0, 1}, 0.25}, {{0, 2}, 0.25}, {{1, 2}, 0.25}});
    check_values(edge_stiffness(right, one_triangle, m),
                 {{{0, 1}, 1.0 / 16}, {{0, 2}, 1.0 / 9}, {{1, 2}, 1.0 / 25}});
    check_values(edge_stiffness(obtuse, one_triangle, m), {{{0, 1}, 0.25}, {{0, 2}, 0.8}, {{1, 2}, 0.8}});
  }
}

TEST_CASE("Blom_semi_torsional_stiffness: k = (1/l) sum 1/theta on hand-computed triangles", "[stiffness]")
{
  const Blom_semi_torsional_stiffness m;
  // equilateral: (1/2) * 1/(pi/3) = 3/(2 pi)
  const double eq = 3 / (2 * pi);
  check_values(edge_stiffness(equilateral, one_triangle, m), {{{0, 1}, eq}, {{0, 2}, eq}, {{1, 2}, eq}});
  // right: (1/4)/atan(4/3), (1/3)/atan(3/4), (1/5)/(pi/2) = 2/(5 pi)
  check_values(edge_stiffness(right, one_triangle, m),
               {{{0, 1}, 0.25 / std::atan(4.0 / 3)}, {{0, 2}, (1.0 / 3) / std::atan(0.75)}, {{1, 2}, 2 / (5 * pi)}});
  // obtuse: (1/2)/(pi - atan(4/3)); (2/sqrt 5)/atan(1/2)
  const double side = (2 / s5) / std::atan(0.5);
  check_values(edge_stiffness(obtuse, one_triangle, m),
               {{{0, 1}, 0.5 / (pi - std::atan(4.0 / 3))}, {{0, 2}, side}, {{1, 2}, side}});
  // two triangles: the diagonal sums both angles, (1/sqrt 2)(2/pi + 2/pi) = 2 sqrt(2)/pi;
  // a side (1/1) * 1/(pi/4) = 4/pi
  const double sq = 4 / pi;
  check_values(edge_stiffness(square, two_triangles, m),
               {{{0, 1}, sq}, {{1, 2}, sq}, {{2, 3}, sq}, {{0, 3}, sq}, {{0, 2}, 2 * s2 / pi}});
}

TEST_CASE("Zeng_Ethier_semi_torsional_stiffness: k = 1/l + sum 1/sin^2 theta on hand-computed triangles",
          "[stiffness]")
{
  const Zeng_Ethier_semi_torsional_stiffness m;
  // equilateral: 1/2 + 4/3 = 11/6
  check_values(edge_stiffness(equilateral, one_triangle, m),
               {{{0, 1}, 11.0 / 6}, {{0, 2}, 11.0 / 6}, {{1, 2}, 11.0 / 6}});
  // right: 1/4 + 25/16 = 29/16; 1/3 + 25/9 = 28/9; 1/5 + 1 = 6/5
  check_values(edge_stiffness(right, one_triangle, m), {{{0, 1}, 29.0 / 16}, {{0, 2}, 28.0 / 9}, {{1, 2}, 1.2}});
  // obtuse: 1/2 + 25/16 = 33/16; 2/sqrt 5 + 5
  check_values(edge_stiffness(obtuse, one_triangle, m),
               {{{0, 1}, 33.0 / 16}, {{0, 2}, 2 / s5 + 5}, {{1, 2}, 2 / s5 + 5}});
  // two triangles: diagonal 1/sqrt 2 + 1 + 1; side 1 + 2 = 3
  check_values(edge_stiffness(square, two_triangles, m),
               {{{0, 1}, 3.0}, {{1, 2}, 3.0}, {{2, 3}, 3.0}, {{0, 3}, 3.0}, {{0, 2}, 1 / s2 + 2}});
}

TEST_CASE("Grid_scaled_stiffness: k = (l0/l)(1/l^2 + (sum 1/sin^2 theta)^4) on hand-computed triangles",
          "[stiffness]")
{
  const Grid_scaled_stiffness m; // 2D: alpha = 2, beta = 4
  // equilateral (l0 = l = 2, lambda = 1): 1/4 + (4/3)^4 = 1/4 + 256/81
  const double eq = 0.25 + 256.0 / 81;
  check_values(edge_stiffness(equilateral, one_triangle, m), {{{0, 1}, eq}, {{0, 2}, eq}, {{1, 2}, eq}});
  // right (l0 = 5): (5/4)(1/16 + (25/16)^4); (5/3)(1/9 + (25/9)^4); 1/25 + 1^4 = 26/25
  check_values(edge_stiffness(right, one_triangle, m),
               {{{0, 1}, 1.25 * (1.0 / 16 + std::pow(25.0 / 16, 4))},
                {{0, 2}, (5.0 / 3) * (1.0 / 9 + std::pow(25.0 / 9, 4))},
                {{1, 2}, 26.0 / 25}});
  // obtuse (l0 = 2): base 1/4 + (25/16)^4; side lambda = 2/(sqrt(5)/2) = 4/sqrt 5,
  // (4/sqrt 5)(1/(5/4) + 5^4) = (4/sqrt 5)(4/5 + 625)
  const double side = (4 / s5) * (0.8 + 625);
  check_values(edge_stiffness(obtuse, one_triangle, m),
               {{{0, 1}, 0.25 + std::pow(25.0 / 16, 4)}, {{0, 2}, side}, {{1, 2}, side}});
  // two triangles (l0 = sqrt 2): the angle sum is raised to beta, not each term:
  // diagonal 1 * (1/2 + (1 + 1)^4) = 33/2; side sqrt(2) * (1 + 2^4) = 17 sqrt 2
  check_values(edge_stiffness(square, two_triangles, m), {{{0, 1}, 17 * s2},
                                                           {{1, 2}, 17 * s2},
                                                           {{2, 3}, 17 * s2},
                                                           {{0, 3}, 17 * s2},
                                                           {{0, 2}, 16.5}});
  SECTION("explicit exponents are used as given, 0 included (no sentinel for the paper's values)")
  {
    Grid_scaled_stiffness given;
    given.alpha = 0.0; // 1/l^0 = 1
    given.beta = 1.0;
    CHECK(given.alpha_for(2) == 0.0);
    CHECK(given.alpha_for(3) == 0.0);
    CHECK(given.beta_for(3) == 1.0);
    // equilateral (lambda = 1): 1 + 4/3
    const double v = 1 + 4.0 / 3;
    check_values(edge_stiffness(equilateral, one_triangle, given), {{{0, 1}, v}, {{0, 2}, v}, {{1, 2}, v}});
    CHECK(Grid_scaled_stiffness::paper_alpha(2) == 2.0);
    CHECK(Grid_scaled_stiffness::paper_beta(2) == 4.0);
    CHECK(Grid_scaled_stiffness::paper_alpha(3) == 1.0);
    CHECK(Grid_scaled_stiffness::paper_beta(3) == 3.0);
  }
  SECTION("reference length: lengths are measured in units of L_ref")
  {
    Grid_scaled_stiffness scaled;
    scaled.reference_length = 2;
    // equilateral: l / L_ref = 1, lambda = l0 / l = 1: 1 + 256/81
    const double v = 1 + 256.0 / 81;
    check_values(edge_stiffness(equilateral, one_triangle, scaled), {{{0, 1}, v}, {{0, 2}, v}, {{1, 2}, v}});
  }
  SECTION("the mesh in other units with L_ref in those units gives the same k up to the constant lambda")
  {
    // the obtuse triangle in millimetres (x 1000) with L_ref = 1000: the
    // length term and the angle term are those of the triangle in metres,
    // and lambda = l0 / l is unit-free
    Grid_scaled_stiffness mm;
    mm.reference_length = 1000;
    std::vector<P2> big = obtuse;
    for(auto& p : big)
      for(double& c : p)
        c *= 1000;
    check_values(edge_stiffness(big, one_triangle, mm),
                 {{{0, 1}, 0.25 + std::pow(25.0 / 16, 4)}, {{0, 2}, side}, {{1, 2}, side}});
  }
}

TEST_CASE("Torsional_stiffness: the lineal part is 1/l^p and the element matrix is R^T C R", "[stiffness][torsional]")
{
  const Torsional_stiffness m;
  check_values(edge_stiffness(right, one_triangle, m), {{{0, 1}, 1.0 / 4}, {{0, 2}, 1.0 / 3}, {{1, 2}, 1.0 / 5}});

  // Right isosceles triangle p0 = (0,0), p1 = (1,0), p2 = (0,1), derived by
  // hand. A vertex moved across an edge of length l turns that edge by 1/l
  // per unit, and translating the triangle changes no angle, so each row
  // sums to zero per component.
  // theta0 (pi/2): moving p1 up turns p0->p1 towards p0->p2: d/dy1 = -1;
  //   moving p2 right likewise: d/dx2 = -1; so d/dp0 = (1, 1).
  // theta1 (pi/4): moving p0 up turns p1->p0 towards p1->p2: d/dy0 = -1;
  //   p2 - p1 = (-1, 1) (l = sqrt 2) turns counter-clockwise, towards p1->p0,
  //   for a move along (-1,-1)/sqrt 2 at rate 1/sqrt 2: d/dp2 = (1/2, 1/2);
  //   d/dp1 = -(0, -1) - (1/2, 1/2) = (-1/2, 1/2).
  // theta2 = pi - theta0 - theta1: minus the sum of the two rows above.
  const std::array<std::array<double, 6>, 3> R{{{1, 1, 0, -1, -1, 0},
                                                 {0, -1, -0.5, 0.5, 0.5, 0.5},
                                                 {-1, 0, 0.5, 0.5, 0.5, -0.5}}};
  const std::array<P2, 3> tri{{{0, 0}, {1, 0}, {0, 1}}};
  const auto got = Torsional_stiffness::angle_gradients(tri);
  for(int a = 0; a < 3; ++a)
    for(int c = 0; c < 6; ++c) {
      INFO("angle " << a << ", coordinate " << c);
      CHECK(got[a][c] == Approx(R[a][c]).margin(1e-15));
    }
  // C = 1/sin^2: 1 at the right angle, 2 at both pi/4 angles
  const std::array<double, 3> C{1, 2, 2};
  std::array<double, 36> K{};
  m.add_element_matrix(tri, K.data());
  for(int r = 0; r < 6; ++r)
    for(int q = 0; q < 6; ++q) {
      double expected = 0;
      for(int a = 0; a < 3; ++a)
        expected += C[a] * R[a][r] * R[a][q];
      INFO("K(" << r << ", " << q << ")");
      CHECK(K[6 * r + q] == Approx(expected).margin(1e-14));
    }
  // torsion_scale multiplies every C_i
  Torsional_stiffness scaled;
  scaled.torsion_scale = 3;
  std::array<double, 36> K3{};
  scaled.add_element_matrix(tri, K3.data());
  for(int i = 0; i < 36; ++i)
    CHECK(K3[i] == Approx(3 * K[i]).margin(1e-14));
}

namespace {

// The interior angle at vertex a by the law of cosines: a formula of its own,
// independent of the library's atan2 of cross and dot.
double angle_at(const std::array<P2, 3>& p, int a)
{
  auto d2 = [&](int i, int j) {
    return (p[i][0] - p[j][0]) * (p[i][0] - p[j][0]) + (p[i][1] - p[j][1]) * (p[i][1] - p[j][1]);
  };
  const int b = (a + 1) % 3, c = (a + 2) % 3;
  return std::acos((d2(a, b) + d2(a, c) - d2(b, c)) / (2 * std::sqrt(d2(a, b) * d2(a, c))));
}

} // namespace

TEST_CASE("Torsional_stiffness: angle derivatives and element matrix match central finite differences",
          "[stiffness][torsional]")
{
  // acute, obtuse, thin, and clockwise triangles, edges of length O(1)
  const std::vector<std::array<P2, 3>> triangles{{{{0.1, 0.2}, {1.3, -0.1}, {0.5, 0.9}}},
                                                  {{{0, 0}, {2, 0}, {1.1, 0.35}}},
                                                  {{{-0.3, 0.4}, {0.9, 0.55}, {0.2, 0.65}}},
                                                  {{{0.1, 0.2}, {0.5, 0.9}, {1.3, -0.1}}}};
  // Step h = 1e-5: the central difference's truncation error h^2/6 |theta'''|
  // is about 2e-11 |theta'''| and its round-off eps |theta| / h about 1e-10;
  // with |theta'''| <= 1/l_min^3 = O(100) on these triangles both stay below
  // 1e-8, which is also far below the O(1) entries a sign or index error changes.
  const double h = 1e-5, tol = 1e-8;
  for(const auto& tri : triangles) {
    std::array<std::array<double, 6>, 3> fd{};
    for(int v = 0; v < 3; ++v)
      for(int c = 0; c < 2; ++c) {
        auto plus = tri, minus = tri;
        plus[v][c] += h;
        minus[v][c] -= h;
        for(int a = 0; a < 3; ++a)
          fd[a][2 * v + c] = (angle_at(plus, a) - angle_at(minus, a)) / (2 * h);
      }
    const auto R = Torsional_stiffness::angle_gradients(tri);
    for(int a = 0; a < 3; ++a)
      for(int k = 0; k < 6; ++k) {
        INFO("triangle (" << tri[0][0] << "," << tri[0][1] << ")..., angle " << a << ", coordinate " << k);
        CHECK(R[a][k] == Approx(fd[a][k]).margin(tol));
      }
    // the element matrix: sum over vertices of C_a (grad theta_a)(grad theta_a)^T
    std::array<double, 36> K{};
    Torsional_stiffness{}.add_element_matrix(tri, K.data());
    double largest = 0;
    for(int r = 0; r < 6; ++r)
      for(int q = 0; q < 6; ++q) {
        double expected = 0;
        for(int a = 0; a < 3; ++a) {
          const double s = std::sin(angle_at(tri, a));
          expected += fd[a][r] * fd[a][q] / (s * s);
        }
        largest = std::max(largest, std::abs(expected));
        INFO("K(" << r << ", " << q << ")");
        // the fd gradient's error enters linearly, times |C| |grad theta| <= O(100)
        CHECK(K[6 * r + q] == Approx(expected).margin(100 * tol));
      }
    CHECK(largest > 1); // the comparison is not between zeros
    // angles do not change under translation, rotation about the origin and
    // scaling: those four motions are in the null space of K
    std::array<std::array<double, 6>, 4> rigid{};
    for(int v = 0; v < 3; ++v) {
      rigid[0][2 * v] = 1;
      rigid[1][2 * v + 1] = 1;
      rigid[2][2 * v] = -tri[v][1];
      rigid[2][2 * v + 1] = tri[v][0];
      rigid[3][2 * v] = tri[v][0];
      rigid[3][2 * v + 1] = tri[v][1];
    }
    for(const auto& u : rigid)
      for(int r = 0; r < 6; ++r) {
        double y = 0;
        for(int q = 0; q < 6; ++q)
          y += K[6 * r + q] * u[q];
        // round-off of a sum of six O(largest) products
        CHECK(std::abs(y) <= 1e-13 * largest);
      }
  }
}

namespace {

// Multiplies the stiffness of an edge model by a constant.
template <class Model>
struct Scaled_edge_model
{
  Model base;
  double factor;
  Angle_kind angle_kind(int d) const { return base.angle_kind(d); }
  double operator()(double l, const double* a, std::size_t n, const Stiffness_context& ctx) const
  {
    return factor * base(l, a, n, ctx);
  }
};

// Multiplies both the edge springs and the element matrices of the torsional model.
struct Scaled_torsional
{
  Torsional_stiffness base;
  double factor;
  Angle_kind angle_kind(int d) const { return base.angle_kind(d); }
  double operator()(double l, const double* a, std::size_t n, const Stiffness_context& ctx) const
  {
    return factor * base(l, a, n, ctx);
  }
  void add_element_matrix(const std::array<P2, 3>& p, double* K) const
  {
    std::array<double, 36> k{};
    base.add_element_matrix(p, k.data());
    for(int i = 0; i < 36; ++i)
      K[i] += factor * k[i];
  }
};

auto inner_circle = [](const P2& p) { return std::hypot(p[0], p[1]) < 1.0; };

template <class Model>
std::vector<P2> rotate_annulus(const CDT& mesh, const Model& model, const Deform_options& options)
{
  const auto ext = extract_spring_network(mesh);
  Network_deformer<2> deformer(ext.network, assign_roles(ext.network, moving_boundary_where(inner_circle)));
  const auto report = deformer.run(Pitch_motion<2>(20, {0, 0}), model, options);
  REQUIRE(report.completed);
  REQUIRE(report.converged);
  return deformer.positions();
}

double max_difference(const std::vector<P2>& a, const std::vector<P2>& b)
{
  double d = 0;
  for(std::size_t i = 0; i < a.size(); ++i)
    for(int c = 0; c < 2; ++c)
      d = std::max(d, std::abs(a[i][c] - b[i][c]));
  return d;
}

} // namespace

TEST_CASE("stiffness models: multiplying every k by one constant does not change the motion",
          "[stiffness][invariance]")
{
  CDT cdt;
  make_annulus(cdt);
  Deform_options options;
  options.number_of_steps = 4;
  options.solver.tolerance = 1e-10;
  // Each solve stops when its estimated error is below tol, and both runs
  // solve the same equations; what differs between them at one step also
  // changes the next step's stiffness by a Lipschitz amount of order one on
  // this mesh, so after n steps the motions differ by about 2 n tol. The
  // bound allows a factor 10 because the stopping rule's error is an
  // estimate, not a bound.
  const double bound = 10 * 2 * double(options.number_of_steps) * options.solver.tolerance;
  auto check_model = [&](const auto& model, const char* name) {
    INFO("model " << name);
    const auto reference = rotate_annulus(cdt, model, options);
    for(double c : {1e3, 1e-3}) {
      INFO("factor " << c);
      const auto scaled = rotate_annulus(cdt, Scaled_edge_model<std::decay_t<decltype(model)>>{model, c}, options);
      CHECK(max_difference(reference, scaled) <= bound);
    }
  };
  check_model(Lineal_stiffness{1.0}, "lineal");
  check_model(Lineal_stiffness{2.0}, "lineal p = 2");
  check_model(Blom_semi_torsional_stiffness{}, "blom");
  check_model(Zeng_Ethier_semi_torsional_stiffness{}, "zeng_ethier");
  check_model(Grid_scaled_stiffness{}, "grid_scaled");
  {
    INFO("model torsional");
    const auto reference = rotate_annulus(cdt, Torsional_stiffness{}, options);
    for(double c : {1e3, 1e-3}) {
      INFO("factor " << c);
      CHECK(max_difference(reference, rotate_annulus(cdt, Scaled_torsional{Torsional_stiffness{}, c}, options)) <=
            bound);
    }
  }
  // the bound can tell models apart: a stiffness that is not a constant
  // multiple (p = 2 instead of p = 1) moves the mesh by far more than it
  const double differ = max_difference(rotate_annulus(cdt, Lineal_stiffness{1.0}, options),
                                       rotate_annulus(cdt, Lineal_stiffness{2.0}, options));
  INFO("lineal p = 1 vs p = 2: " << differ);
  CHECK(differ > 1e4 * bound);
}

namespace {

// A model of the user's own: every spring has the same stiffness.
struct Unit_springs
{
  Angle_kind angle_kind(int) const { return Angle_kind::none; }
  double operator()(double, const double*, std::size_t, const Stiffness_context&) const { return 1.0; }
};

} // namespace

TEST_CASE("deform: a user-written model is honoured", "[stiffness][user_model]")
{
  CDT cdt;
  make_annulus(cdt);
  const auto ext = extract_spring_network(cdt);
  const auto& net = ext.network;
  const std::size_t n = net.number_of_vertices();
  const Pitch_motion<2> motion(10, {0, 0});

  // Reference: the increment that balances the graph Laplacian (k = 1 on
  // every edge) with the inner circle turned and the outer one fixed, solved
  // directly.
  std::vector<int> unknown(n, -1);
  int nu = 0;
  for(std::size_t i = 0; i < n; ++i)
    if(!net.on_boundary[i])
      unknown[i] = nu++;
  std::vector<P2> target = net.points;
  for(std::size_t i = 0; i < n; ++i)
    if(net.on_boundary[i] && inner_circle(net.points[i]))
      target[i] = motion(net.points[i], 1.0);
  std::vector<Eigen::Triplet<double>> trip;
  Eigen::MatrixXd rhs = Eigen::MatrixXd::Zero(nu, 2);
  for(const auto& e : net.edges)
    for(int s = 0; s < 2; ++s) {
      const Index i = e[s], j = e[1 - s];
      if(unknown[i] < 0)
        continue;
      trip.emplace_back(unknown[i], unknown[i], 1.0);
      if(unknown[j] >= 0)
        trip.emplace_back(unknown[i], unknown[j], -1.0);
      else
        for(int c = 0; c < 2; ++c)
          rhs(unknown[i], c) += target[j][c] - net.points[j][c];
    }
  Eigen::SparseMatrix<double> A(nu, nu);
  A.setFromTriplets(trip.begin(), trip.end());
  Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> ldlt(A);
  REQUIRE(ldlt.info() == Eigen::Success);
  const Eigen::MatrixXd x = ldlt.solve(rhs);

  Deform_options options;
  options.number_of_steps = 1; // one step: the stiffness is that of the initial mesh
  options.solver.tolerance = 1e-12;
  CDT user = cdt, p0 = cdt, p1 = cdt;
  const auto r_user = deform(user, moving_boundary_where(inner_circle), motion, Unit_springs{}, options);
  const auto r_p0 = deform(p0, moving_boundary_where(inner_circle), motion, Lineal_stiffness{0.0}, options);
  const auto r_p1 = deform(p1, moving_boundary_where(inner_circle), motion, Lineal_stiffness{1.0}, options);
  REQUIRE(r_user.completed);
  REQUIRE(r_p0.completed);
  REQUIRE(r_p1.completed);
  CHECK(r_user.model.name == "custom"); // a model without description() is reported as such

  // vertex handles keep their order through deform(): walk the copies together
  double vs_direct = 0, vs_p0 = 0, vs_p1 = 0;
  auto u = user.finite_vertices_begin(), a = p0.finite_vertices_begin(), b = p1.finite_vertices_begin();
  std::map<std::pair<double, double>, std::size_t> index_of;
  for(std::size_t i = 0; i < n; ++i)
    index_of[{net.points[i][0], net.points[i][1]}] = i;
  for(auto v = cdt.finite_vertices_begin(); v != cdt.finite_vertices_end(); ++v, ++u, ++a, ++b) {
    const std::size_t i = index_of.at({v->point().x(), v->point().y()});
    P2 expected = target[i];
    if(unknown[i] >= 0)
      expected = {net.points[i][0] + x(unknown[i], 0), net.points[i][1] + x(unknown[i], 1)};
    vs_direct = std::max({vs_direct, std::abs(u->point().x() - expected[0]), std::abs(u->point().y() - expected[1])});
    vs_p0 = std::max({vs_p0, std::abs(u->point().x() - a->point().x()), std::abs(u->point().y() - a->point().y())});
    vs_p1 = std::max({vs_p1, std::abs(u->point().x() - b->point().x()), std::abs(u->point().y() - b->point().y())});
  }
  INFO("user model vs direct " << vs_direct << ", vs p = 0 " << vs_p0 << ", vs p = 1 " << vs_p1);
  // both iterative solves stop at an estimated error of 1e-12; a factor 10 for the estimate
  CHECK(vs_direct < 1e-11);
  CHECK(vs_p0 < 2e-11);
  // and the user's model was used, not a default one
  CHECK(vs_p1 > 1e-4);
}
