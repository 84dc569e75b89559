// Element models (include/spring_motion/stiffness/): ball-vertex springs in 2D
// and 3D, the 3D torsional springs, an edge model plus ball-vertex springs,
// and the table of model names. Element matrices are checked against finite
// differences of the quantities the springs are defined on (the altitudes;
// the angles of the torsion triangles), which the test computes itself.
#include <spring_motion/spring_motion.h>
#include <spring_motion/stiffness/model_by_name.h>

#include "test_meshes.h"

#include <catch2/catch.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#include <random>
#include <string>
#include <vector>

using namespace spring_motion;

namespace {

template <int D>
using Simplex = std::array<std::array<double, D>, D + 1>;

template <int D, class Model>
std::vector<double> element_matrix(const Model& model, const Simplex<D>& p)
{
  constexpr int ND = (D + 1) * D;
  std::vector<double> K(ND * ND, 0.0);
  model.add_element_matrix(p, K.data());
  return K;
}

double max_abs(const std::vector<double>& v)
{
  double m = 0;
  for(double x : v)
    m = std::max(m, std::abs(x));
  return m;
}

// largest |K_rq - K_qr| and largest |(K u)_r| over the rigid motions u,
// relative to max |K| |u|
template <int D>
double asymmetry(const std::vector<double>& K)
{
  constexpr int ND = (D + 1) * D;
  double worst = 0;
  for(int r = 0; r < ND; ++r)
    for(int q = 0; q < ND; ++q)
      worst = std::max(worst, std::abs(K[r * ND + q] - K[q * ND + r]));
  return worst / max_abs(K);
}

template <int D>
std::vector<std::vector<double>> rigid_motions(const Simplex<D>& p)
{
  constexpr int ND = (D + 1) * D;
  std::vector<std::vector<double>> modes;
  for(int c = 0; c < D; ++c) { // translations
    std::vector<double> u(ND, 0.0);
    for(int v = 0; v <= D; ++v)
      u[v * D + c] = 1;
    modes.push_back(u);
  }
  // infinitesimal rotations: w x p
  const std::vector<std::array<double, 3>> axes =
      D == 2 ? std::vector<std::array<double, 3>>{{0, 0, 1}}
             : std::vector<std::array<double, 3>>{{1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
  for(const auto& w : axes) {
    std::vector<double> u(ND, 0.0);
    for(int v = 0; v <= D; ++v) {
      const std::array<double, 3> x{p[v][0], p[v][1], D == 3 ? p[v][D - 1] : 0.0};
      const auto r = internal::cross(w, x);
      for(int c = 0; c < D; ++c)
        u[v * D + c] = r[c];
    }
    modes.push_back(u);
  }
  return modes;
}

template <int D>
double rigid_residual(const std::vector<double>& K, const std::vector<double>& u)
{
  constexpr int ND = (D + 1) * D;
  double worst = 0;
  for(int r = 0; r < ND; ++r) {
    double s = 0;
    for(int q = 0; q < ND; ++q)
      s += K[r * ND + q] * u[q];
    worst = std::max(worst, std::abs(s));
  }
  return worst / (max_abs(K) * max_abs(u));
}

// The altitude from vertex i, from the measure of the simplex and of the
// facet facing i (not from the model's normal and foot).
double altitude(const Simplex<2>& p, int i)
{
  const auto& a = p[(i + 1) % 3];
  const auto& b = p[(i + 2) % 3];
  const double twice_area = std::abs((a[0] - p[i][0]) * (b[1] - p[i][1]) - (a[1] - p[i][1]) * (b[0] - p[i][0]));
  return twice_area / std::hypot(b[0] - a[0], b[1] - a[1]);
}
double altitude(const Simplex<3>& p, int i)
{
  std::vector<std::array<double, 3>> f;
  for(int m = 0; m < 4; ++m)
    if(m != i)
      f.push_back(p[m]);
  const auto N = internal::cross(internal::sub<3>(f[1], f[0]), internal::sub<3>(f[2], f[0]));
  return std::abs(internal::dot<3>(internal::sub<3>(p[i], f[0]), N)) / internal::norm<3>(N);
}

// K of ball-vertex springs from their definition: the springs' stretch is the
// first variation of the altitude, so K = sum_i k(h_i) grad h_i grad h_i^T,
// grad h_i by central differences of altitude().
template <int D>
std::vector<double> ball_vertex_by_differences(const Simplex<D>& p, double exponent)
{
  constexpr int ND = (D + 1) * D;
  std::vector<double> K(ND * ND, 0.0);
  const double step = 1e-6;
  for(int i = 0; i <= D; ++i) {
    std::vector<double> g(ND);
    for(int r = 0; r < ND; ++r) {
      Simplex<D> plus = p, minus = p;
      plus[r / D][r % D] += step;
      minus[r / D][r % D] -= step;
      g[r] = (altitude(plus, i) - altitude(minus, i)) / (2 * step);
    }
    const double k = 1 / std::pow(altitude(p, i), exponent);
    for(int r = 0; r < ND; ++r)
      for(int q = 0; q < ND; ++q)
        K[r * ND + q] += k * g[r] * g[q];
  }
  return K;
}

double relative_difference(const std::vector<double>& a, const std::vector<double>& b)
{
  double worst = 0;
  for(std::size_t k = 0; k < a.size(); ++k)
    worst = std::max(worst, std::abs(a[k] - b[k]));
  return worst / max_abs(b);
}

const Simplex<2> triangle{{{0.1, -0.2}, {1.3, 0.15}, {0.45, 0.9}}};
const Simplex<2> obtuse_triangle{{{0, 0}, {2, 0}, {1.7, 0.3}}}; // feet of two altitudes outside their facet
const Simplex<3> tetrahedron{{{0.1, 0.0, -0.1}, {1.2, 0.1, 0.05}, {0.3, 0.95, 0.1}, {0.2, 0.25, 1.1}}};
// a sliver: four points near the square's corners, 0.05 off its plane
const Simplex<3> sliver{{{0, 0, 0}, {1, 0, 0.05}, {1, 1, 0}, {0, 1, 0.05}}};

// 3D rotation by angle t about the unit axis a (Rodrigues)
std::array<std::array<double, 3>, 3> rotation(std::array<double, 3> a, double t)
{
  const double n = internal::norm<3>(a);
  for(double& c : a)
    c /= n;
  const double c = std::cos(t), s = std::sin(t);
  std::array<std::array<double, 3>, 3> R;
  for(int r = 0; r < 3; ++r)
    for(int q = 0; q < 3; ++q)
      R[r][q] = (r == q ? c : 0.0) + (1 - c) * a[r] * a[q];
  R[0][1] -= s * a[2];
  R[0][2] += s * a[1];
  R[1][0] += s * a[2];
  R[1][2] -= s * a[0];
  R[2][0] -= s * a[1];
  R[2][1] += s * a[0];
  return R;
}

} // namespace

TEST_CASE("ball-vertex: altitude, foot and normal of the model agree with the geometry", "[stiffness][ball_vertex]")
{
  for(const auto& p : {triangle, obtuse_triangle})
    for(int i = 0; i < 3; ++i) {
      const auto a = Ball_vertex_stiffness::altitude(p, i);
      CHECK(a.height == Approx(altitude(p, i)).epsilon(1e-14));
      CHECK(a.foot[i] == 0.0);
      CHECK(a.foot[0] + a.foot[1] + a.foot[2] == Approx(1).epsilon(1e-14));
      for(int c = 0; c < 2; ++c) { // p_i - h n is the foot
        const double foot = a.foot[0] * p[0][c] + a.foot[1] * p[1][c] + a.foot[2] * p[2][c];
        CHECK(p[i][c] - a.height * a.normal[c] == Approx(foot).margin(1e-14));
      }
    }
  for(const auto& p : {tetrahedron, sliver})
    for(int i = 0; i < 4; ++i) {
      const auto a = Ball_vertex_stiffness::altitude(p, i);
      CHECK(a.height == Approx(altitude(p, i)).epsilon(1e-13));
      CHECK(a.foot[i] == 0.0);
      CHECK(a.foot[0] + a.foot[1] + a.foot[2] + a.foot[3] == Approx(1).epsilon(1e-14));
      for(int c = 0; c < 3; ++c) {
        double foot = 0;
        for(int v = 0; v < 4; ++v)
          foot += a.foot[v] * p[v][c];
        CHECK(p[i][c] - a.height * a.normal[c] == Approx(foot).margin(1e-14));
      }
    }
  // the obtuse triangle: the foot from its obtuse-angled neighbours falls outside the facing edge
  const auto outside = Ball_vertex_stiffness::altitude(obtuse_triangle, 0);
  CHECK(std::min(outside.foot[1], outside.foot[2]) < 0);
}

TEST_CASE("ball-vertex: element matrix = sum k(h) grad h grad h^T, grad h by finite differences (2D and 3D)",
          "[stiffness][ball_vertex]")
{
  // central differences with step 1e-6 on O(1) coordinates: truncation and
  // round-off both near 1e-10 of max |K|
  const double tolerance = 1e-7;
  for(double exponent : {1.0, 1.5, 2.0, 2.5, 3.0}) {
    INFO("exponent " << exponent);
    Ball_vertex_stiffness m;
    m.exponent = exponent;
    for(const auto& p : {triangle, obtuse_triangle})
      CHECK(relative_difference(element_matrix<2>(m, p), ball_vertex_by_differences<2>(p, exponent)) < tolerance);
    for(const auto& p : {tetrahedron, sliver})
      CHECK(relative_difference(element_matrix<3>(m, p), ball_vertex_by_differences<3>(p, exponent)) < tolerance);
  }
  // K(s p) = s^-p K(p): with s a power of two the scaling is exact in every
  // product, and at these scales the kernel leaves its quotient-free form for
  // k computed from the height (|V|^p would leave the normal range)
  for(double exponent : {1.0, 1.5, 2.0, 2.5, 3.0})
    for(int e : {-150, 150}) {
      INFO("exponent " << exponent << ", scale 2^" << e);
      Ball_vertex_stiffness m;
      m.exponent = exponent;
      const double s = std::ldexp(1.0, e);
      auto scaled = [&](auto p) {
        for(auto& x : p)
          for(double& c : x)
            c *= s;
        return p;
      };
      auto times = [&](std::vector<double> K) {
        for(double& x : K)
          x *= std::pow(s, -exponent);
        return K;
      };
      for(const auto& p : {triangle, obtuse_triangle})
        CHECK(relative_difference(element_matrix<2>(m, scaled(p)), times(element_matrix<2>(m, p))) < 1e-14);
      for(const auto& p : {tetrahedron, sliver})
        CHECK(relative_difference(element_matrix<3>(m, scaled(p)), times(element_matrix<3>(m, p))) < 1e-14);
    }
  // the weight multiplies K
  Ball_vertex_stiffness heavy;
  heavy.weight = 3;
  const auto K1 = element_matrix<3>(Ball_vertex_stiffness{}, tetrahedron);
  const auto K3 = element_matrix<3>(heavy, tetrahedron);
  for(std::size_t k = 0; k < K1.size(); ++k)
    CHECK(K3[k] == Approx(3 * K1[k]).margin(1e-15 * max_abs(K1)));
  // no edge springs
  CHECK(Ball_vertex_stiffness{}(0.5, nullptr, 0, Stiffness_context{}) == 0.0);
  CHECK(Ball_vertex_stiffness{}.angle_kind(3) == Angle_kind::none);
}

TEST_CASE("ball-vertex: symmetric, rigid motions in the null space, positive on the flattening of a sliver",
          "[stiffness][ball_vertex]")
{
  for(const auto& p : {triangle, obtuse_triangle}) {
    const auto K = element_matrix<2>(Ball_vertex_stiffness{}, p);
    CHECK(asymmetry<2>(K) < 1e-15);
    for(const auto& u : rigid_motions<2>(p))
      CHECK(rigid_residual<2>(K, u) < 1e-14);
  }
  for(const auto& p : {tetrahedron, sliver}) {
    const auto K = element_matrix<3>(Ball_vertex_stiffness{}, p);
    CHECK(asymmetry<3>(K) < 1e-15);
    for(const auto& u : rigid_motions<3>(p))
      CHECK(rigid_residual<3>(K, u) < 1e-14);
  }
  // flattening the sliver (its raised vertices 1 and 3 down, the others up)
  // changes every edge length at a rate of at most 0.1 (twice its thickness),
  // while its altitudes change at rates near 2: the springs resist it
  std::vector<double> u(12, 0.0);
  u[2] = 1, u[5] = -1, u[8] = 1, u[11] = -1;
  const auto K = element_matrix<3>(Ball_vertex_stiffness{}, sliver);
  double energy = 0;
  for(int r = 0; r < 12; ++r)
    for(int q = 0; q < 12; ++q)
      energy += u[r] * K[r * 12 + q] * u[q];
  CHECK(energy > 1.0);
  for(int a = 0; a < 4; ++a) // first-order change of each edge length
    for(int b = a + 1; b < 4; ++b) {
      double s = 0;
      for(int c = 0; c < 3; ++c)
        s += (sliver[b][c] - sliver[a][c]) * (u[3 * b + c] - u[3 * a + c]);
      CHECK(std::abs(s) / internal::norm<3>(internal::sub<3>(sliver[b], sliver[a])) <= 0.1 + 1e-15);
    }
}

TEST_CASE("ball-vertex: the element matrix turns with the element, K(Rp) = R K(p) R^T", "[stiffness][ball_vertex]")
{
  {
    const double t = 0.7, c = std::cos(t), s = std::sin(t);
    Simplex<2> q;
    for(int v = 0; v < 3; ++v)
      q[v] = {c * triangle[v][0] - s * triangle[v][1] + 0.3, s * triangle[v][0] + c * triangle[v][1] - 1.1};
    const auto K = element_matrix<2>(Ball_vertex_stiffness{}, triangle);
    const auto KR = element_matrix<2>(Ball_vertex_stiffness{}, q);
    const double R[2][2] = {{c, -s}, {s, c}};
    for(int a = 0; a < 3; ++a)
      for(int b = 0; b < 3; ++b)
        for(int r = 0; r < 2; ++r)
          for(int col = 0; col < 2; ++col) {
            double v = 0; // (R K_ab R^T)_{r,col}
            for(int x = 0; x < 2; ++x)
              for(int y = 0; y < 2; ++y)
                v += R[r][x] * K[(a * 2 + x) * 6 + b * 2 + y] * R[col][y];
            CHECK(KR[(a * 2 + r) * 6 + b * 2 + col] == Approx(v).margin(1e-13 * max_abs(K)));
          }
  }
  {
    const auto R = rotation({0.3, -0.5, 0.8}, 1.1);
    Simplex<3> q;
    for(int v = 0; v < 4; ++v)
      for(int r = 0; r < 3; ++r)
        q[v][r] = R[r][0] * tetrahedron[v][0] + R[r][1] * tetrahedron[v][1] + R[r][2] * tetrahedron[v][2] + 0.5 * r;
    const auto K = element_matrix<3>(Ball_vertex_stiffness{}, tetrahedron);
    const auto KR = element_matrix<3>(Ball_vertex_stiffness{}, q);
    for(int a = 0; a < 4; ++a)
      for(int b = 0; b < 4; ++b)
        for(int r = 0; r < 3; ++r)
          for(int col = 0; col < 3; ++col) {
            double v = 0;
            for(int x = 0; x < 3; ++x)
              for(int y = 0; y < 3; ++y)
                v += R[r][x] * K[(a * 3 + x) * 12 + b * 3 + y] * R[col][y];
            CHECK(KR[(a * 3 + r) * 12 + b * 3 + col] == Approx(v).margin(1e-13 * max_abs(K)));
          }
  }
}

namespace {

// Energy of the 3D torsional springs of tetrahedron p displaced by d, with
// the triangles' interpolation weights frozen at p:
// E(d) = 1/2 sum_triangles sum_angles C (theta(p + d) - theta(p))^2, C = 1/sin^2 theta(p).
double torsion_energy(const Simplex<3>& p, const std::array<Torsion_triangle, 12>& triangles, const std::vector<double>& d)
{
  Simplex<3> x = p;
  for(int v = 0; v < 4; ++v)
    for(int c = 0; c < 3; ++c)
      x[v][c] += d[3 * v + c];
  auto corners = [](const Simplex<3>& s, const Torsion_triangle& t) {
    std::array<double, 3> j;
    for(int c = 0; c < 3; ++c)
      j[c] = (1 - t.lambda) * s[t.edge[0]][c] + t.lambda * s[t.edge[1]][c];
    return internal::triangle_angles<3>(s[t.vertex], j, s[t.apex]);
  };
  double e = 0;
  for(const auto& t : triangles) {
    const auto a0 = corners(p, t), a = corners(x, t);
    for(int k = 0; k < 3; ++k)
      e += 0.5 / (std::sin(a0[k]) * std::sin(a0[k])) * (a[k] - a0[k]) * (a[k] - a0[k]);
  }
  return e;
}

} // namespace

TEST_CASE("torsional 3D: the twelve triangles stand on the faces, perpendicular to them", "[stiffness][torsional][3d]")
{
  for(const auto& p : {tetrahedron, sliver}) {
    const auto tris = Torsional_stiffness::torsion_triangles(p);
    int inside = 0;
    for(const auto& t : tris) {
      CHECK(t.vertex != t.apex);
      CHECK(t.edge[0] != t.vertex);
      CHECK(t.edge[1] != t.vertex);
      CHECK(t.edge[0] != t.apex);
      CHECK(t.edge[1] != t.apex);
      CHECK(t.edge[0] != t.edge[1]);
      CHECK(t.lambda >= 0);
      CHECK(t.lambda <= 1);
      if(t.lambda <= 0 || t.lambda >= 1)
        continue;
      ++inside;
      // an inner cut: the angle at the vertex is the angle between the edge
      // to the apex and the face, asin(height of the apex / edge length)
      std::array<double, 3> j;
      for(int c = 0; c < 3; ++c)
        j[c] = (1 - t.lambda) * p[t.edge[0]][c] + t.lambda * p[t.edge[1]][c];
      const double angle = internal::triangle_angles<3>(p[t.vertex], j, p[t.apex])[0];
      const double edge = internal::norm<3>(internal::sub<3>(p[t.apex], p[t.vertex]));
      CHECK(angle == Approx(std::asin(altitude(p, t.apex) / edge)).epsilon(1e-12));
    }
    CHECK(inside >= 1);
  }
  // the regular tetrahedron: every cut is at the middle of the opposite edge
  const Simplex<3> regular{{{1, 1, 1}, {1, -1, -1}, {-1, 1, -1}, {-1, -1, 1}}};
  for(const auto& t : Torsional_stiffness::torsion_triangles(regular))
    CHECK(t.lambda == Approx(0.5).epsilon(1e-14));
}

TEST_CASE("torsional 3D: element matrix = Hessian of the torsion energy at frozen weights (finite differences)",
          "[stiffness][torsional][3d]")
{
  // second differences of E with step 1e-4: truncation ~1e-8 and round-off
  // ~1e-16 / 1e-8 of max |K|
  const double h = 1e-4, tolerance = 1e-6;
  Torsional_stiffness m;
  for(const auto& p : {tetrahedron, sliver}) {
    const auto tris = Torsional_stiffness::torsion_triangles(p);
    std::vector<double> H(144);
    for(int r = 0; r < 12; ++r)
      for(int q = 0; q < 12; ++q) {
        auto E = [&](double sr, double sq) {
          std::vector<double> d(12, 0.0);
          d[r] += sr * h;
          d[q] += sq * h;
          return torsion_energy(p, tris, d);
        };
        H[r * 12 + q] = (E(1, 1) - E(1, -1) - E(-1, 1) + E(-1, -1)) / (4 * h * h);
      }
    const auto K = element_matrix<3>(m, p);
    CHECK(relative_difference(K, H) < tolerance);
    CHECK(asymmetry<3>(K) < 1e-15);
    for(const auto& u : rigid_motions<3>(p))
      CHECK(rigid_residual<3>(K, u) < 1e-13);
  }
  // torsion_scale multiplies the element matrix; the lineal part is 1/l^p
  Torsional_stiffness scaled;
  scaled.torsion_scale = 2;
  const auto K1 = element_matrix<3>(m, tetrahedron), K2 = element_matrix<3>(scaled, tetrahedron);
  for(std::size_t k = 0; k < K1.size(); ++k)
    CHECK(K2[k] == Approx(2 * K1[k]).margin(1e-15 * max_abs(K1)));
  CHECK(m(2.0, nullptr, 0, Stiffness_context{3, 1}) == 0.5);
  CHECK(internal::edge_spring_form(m) == Edge_spring_form::per_coordinate);
  // the element matrix is added to what K holds (the assembly may hand a
  // matrix that other terms already filled)
  std::vector<double> K0(144), K3(144);
  for(std::size_t k = 0; k < K0.size(); ++k)
    K3[k] = K0[k] = double(k % 13) - 6;
  m.add_element_matrix(sliver, K3.data());
  const auto Ks = element_matrix<3>(m, sliver);
  for(std::size_t k = 0; k < K3.size(); ++k)
    CHECK(K3[k] - K0[k] == Approx(Ks[k]).margin(1e-13 * max_abs(Ks)));
}

TEST_CASE("torsional 3D: the sliver's flattening costs far more than in a well-shaped tetrahedron",
          "[stiffness][torsional][3d]")
{
  // the same flattening mode (raised vertices down, the others up), per unit
  // squared displacement: the angle springs see what edge springs cannot
  auto flattening_energy = [](const Simplex<3>& p, const std::vector<double>& u) {
    const auto K = element_matrix<3>(Torsional_stiffness{}, p);
    double e = 0;
    for(int r = 0; r < 12; ++r)
      for(int q = 0; q < 12; ++q)
        e += u[r] * K[r * 12 + q] * u[q];
    return e;
  };
  std::vector<double> u(12, 0.0);
  u[2] = 1, u[5] = -1, u[8] = 1, u[11] = -1;
  const Simplex<3> fat{{{0, 0, 0}, {1, 0, 0.7}, {1, 1, 0}, {0, 1, 0.7}}};
  CHECK(flattening_energy(sliver, u) > 20 * flattening_energy(fat, u));
}

TEST_CASE("EDGE+ball_vertex: edge springs of the edge model acting along the edge, plus ball-vertex springs",
          "[stiffness][ball_vertex][combination]")
{
  const With_ball_vertex<Grid_scaled_stiffness> m{};
  const auto d = m.description(3);
  CHECK(d.name == "grid_scaled+ball_vertex");
  auto has = [&](const std::string& name, double value) {
    for(const auto& [n, v] : d.parameters)
      if(n == name)
        return v == value;
    return false;
  };
  CHECK(has("alpha", 1.0));
  CHECK(has("beta", 3.0));
  CHECK(has("ball_vertex_exponent", 1.0));
  CHECK(has("ball_vertex_weight", 1.0));
  CHECK(internal::edge_spring_form(m) == Edge_spring_form::along_edge);
  CHECK(m.angle_kind(3) == Angle_kind::element);
  const double angles[2] = {0.7, 1.9};
  const Stiffness_context ctx{3, 4.0};
  CHECK(m(0.5, angles, 2, ctx) == Grid_scaled_stiffness{}(0.5, angles, 2, ctx));
  CHECK(element_matrix<3>(m, sliver) == element_matrix<3>(Ball_vertex_stiffness{}, sliver));
  CHECK(element_matrix<2>(m, triangle) == element_matrix<2>(Ball_vertex_stiffness{}, triangle));
  CHECK(internal::Is_element_model<With_ball_vertex<Lineal_stiffness>, 2>::value);
  CHECK(internal::Is_element_model<With_ball_vertex<Lineal_stiffness>, 3>::value);
}

TEST_CASE("model table: one name per built-in model, each giving that model, bad names listing the valid ones",
          "[stiffness][model_table]")
{
  const std::vector<std::string> expected{"lineal",
                                          "lineal_p2",
                                          "blom",
                                          "zeng_ethier",
                                          "grid_scaled",
                                          "torsional",
                                          "ball_vertex",
                                          "ball_vertex_p2",
                                          "ball_vertex_p2.5",
                                          "ball_vertex_p3",
                                          "lineal+ball_vertex",
                                          "lineal_p2+ball_vertex",
                                          "blom+ball_vertex",
                                          "zeng_ethier+ball_vertex",
                                          "grid_scaled+ball_vertex"};
  CHECK(model_names() == expected);
  CHECK(model_names(2) == expected);
  CHECK(model_names(3) == expected);
  for(const auto& e : model_table()) {
    INFO(e.name);
    CHECK(!e.summary.empty());
    CHECK(e.summary.find('\n') == std::string::npos);
    // the reports name the model as the table does; a _pN name reports as
    // the model without it and exponent N (lineal_p2: lineal, exponent 2;
    // ball_vertex_p2.5: ball_vertex, exponent 2.5)
    const auto described = with_model(e.name, [](const auto& model) { return internal::describe_model(model, 2); });
    std::string name = e.name;
    const auto p = name.find("_p");
    if(p != std::string::npos) {
      const auto end = std::min(name.find('+', p), name.size());
      const double exponent = std::stod(name.substr(p + 2, end - p - 2));
      name.erase(p, end - p);
      const auto& ps = described.parameters;
      CHECK(std::count(ps.begin(), ps.end(), std::make_pair(std::string("exponent"), exponent)) == 1);
    }
    CHECK(described.name == name);
  }
  const bool element_model = with_model("ball_vertex", [](const auto& model) {
    return internal::Is_element_model<std::decay_t<decltype(model)>, 3>::value;
  });
  CHECK(element_model);
  using Catch::Matchers::Contains;
  CHECK_THROWS_AS(with_model("springy", [](const auto&) { return 0; }), Error);
  CHECK_THROWS_WITH(with_model("springy", [](const auto&) { return 0; }),
                    Contains("unknown stiffness model 'springy'") && Contains("grid_scaled+ball_vertex") &&
                        Contains("torsional"));
  for(const std::string bad : {"torsional+ball_vertex", "ball_vertex+ball_vertex", "springy+ball_vertex"}) {
    INFO(bad);
    CHECK_THROWS_AS(check_model_name(bad), Error);
    CHECK_THROWS_WITH(with_model(bad, [](const auto&) { return 0; }),
                      Contains("combine with an edge model only") && Contains("valid models: lineal"));
  }
  CHECK_NOTHROW(check_model_name("zeng_ethier+ball_vertex", 3));
  CHECK_THROWS_WITH(check_model_name("ball_vertex+", 2), Contains("unknown stiffness model"));
}

namespace {

template <int D>
double worst_translation_error(const std::string& model_name, const std::array<double, D>& d)
{
  const Indexed_mesh<D> original = spring_motion_test::kuhn_grid<D>(D == 2 ? 5 : 3);
  Indexed_mesh<D> mesh = original;
  Deform_options options;
  options.number_of_steps = 2;
  // a uniform field is every system's exact solution: ask for a criterion far
  // below the round-off checked against
  options.solver.tolerance = 1e-16;
  const auto report = with_model(model_name, [&](const auto& m) {
    return deform(mesh, All_boundary_moving{}, Translation_motion<D>{d}, m, options);
  });
  REQUIRE(report.completed);
  CHECK(report.converged);
  CHECK(report.vertices > report.moving_vertices + report.fixed_vertices); // some vertices are solved for
  double worst = 0;
  for(std::size_t v = 0; v < mesh.points.size(); ++v)
    for(int c = 0; c < D; ++c)
      worst = std::max(worst, std::abs(mesh.points[v][c] - (original.points[v][c] + d[c])));
  return worst;
}

} // namespace

TEST_CASE("deform with element models: a rigid translation of the boundary translates every vertex (2D, 3D)",
          "[deform][ball_vertex][torsional]")
{
  for(const std::string name : {"ball_vertex", "torsional", "grid_scaled+ball_vertex", "lineal+ball_vertex"}) {
    INFO(name);
    CHECK(worst_translation_error<2>(name, {0.3, -0.45}) < 1e-12);
    CHECK(worst_translation_error<3>(name, {0.3, -0.2, 0.5}) < 1e-12);
  }
}

namespace {

// block (v, w), v <= w, of add_symmetric_blocks, entry (r, c)
template <int D>
double symmetric_block_entry(const std::vector<double>& S, int v, int w, int r, int c)
{
  constexpr int U = D * (D + 1) / 2;
  const int a = std::min(v, w), b = std::max(v, w), i = std::min(r, c), j = std::max(r, c);
  const int pair = a * (D + 1) - a * (a - 1) / 2 + (b - a);
  return S[std::size_t(pair * U + i * D - i * (i - 1) / 2 + (j - i))];
}

template <int D, class Model>
void check_symmetric_blocks(const Model& model, const Simplex<D>& p)
{
  constexpr int ND = (D + 1) * D;
  const auto K = element_matrix<D>(model, p);
  std::vector<double> S((D + 1) * (D + 2) / 2 * D * (D + 1) / 2, 0.0);
  model.add_symmetric_blocks(p, S.data());
  for(int v = 0; v <= D; ++v)
    for(int w = 0; w <= D; ++w)
      for(int r = 0; r < D; ++r)
        for(int c = 0; c < D; ++c) // the same bits, not just close
          REQUIRE(symmetric_block_entry<D>(S, v, w, r, c) == K[std::size_t((v * D + r) * ND + w * D + c)]);
}

} // namespace

TEST_CASE("ball-vertex: the distinct blocks the assembly reads are the element matrix's values",
          "[stiffness][ball_vertex]")
{
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for(double exponent : {1.0, 2.0, 2.5, 3.0}) {
    Ball_vertex_stiffness m;
    m.exponent = exponent;
    const With_ball_vertex<Grid_scaled_stiffness> combined{{}, m};
    for(const auto& p : {triangle, obtuse_triangle}) {
      check_symmetric_blocks<2>(m, p);
      check_symmetric_blocks<2>(combined, p);
    }
    for(const auto& p : {tetrahedron, sliver}) {
      check_symmetric_blocks<3>(m, p);
      check_symmetric_blocks<3>(combined, p);
    }
    for(int trial = 0; trial < 200; ++trial) {
      Simplex<2> t;
      Simplex<3> s;
      for(auto& x : t)
        for(double& c : x)
          c = u(rng);
      for(auto& x : s)
        for(double& c : x)
          c = u(rng);
      check_symmetric_blocks<2>(m, t);
      check_symmetric_blocks<3>(m, s);
    }
  }
  // torsional blocks are not symmetric: the assembly reads its whole matrix
  CHECK(internal::Has_symmetric_blocks<Ball_vertex_stiffness, 3>::value);
  CHECK(internal::Has_symmetric_blocks<With_ball_vertex<Lineal_stiffness>, 2>::value);
  CHECK_FALSE(internal::Has_symmetric_blocks<Torsional_stiffness, 2>::value);
  CHECK_FALSE(internal::Has_symmetric_blocks<Torsional_stiffness, 3>::value);
}

namespace {

template <int D>
Simplex<D> random_simplex(std::mt19937& rng)
{
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  Simplex<D> p;
  for(auto& x : p)
    for(double& c : x)
      c = u(rng);
  return p;
}

Ball_vertex_stiffness ball_vertex_of_power(double exponent)
{
  Ball_vertex_stiffness m;
  m.exponent = exponent;
  m.weight = 0.7;
  return m;
}

// symmetric_blocks_of_two(p, q) against add_symmetric_blocks on each
// (from zero): stored over a non-zero start; returns whether the pair form
// was taken (false: S and T must be as they were).
template <int D, class Model>
bool check_blocks_of_two(const Model& model, const Simplex<D>& p, const Simplex<D>& q, std::mt19937& rng)
{
  const std::size_t n = (D + 1) * (D + 2) / 2 * D * (D + 1) / 2;
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  std::vector<double> start(2 * n);
  for(double& x : start)
    x = u(rng);
  std::vector<double> S(start.begin(), start.begin() + long(n)), T(start.begin() + long(n), start.end());
  const bool taken = model.symmetric_blocks_of_two(p, q, S.data(), T.data());
  if(!taken) {
    CHECK(S == std::vector<double>(start.begin(), start.begin() + long(n)));
    CHECK(T == std::vector<double>(start.begin() + long(n), start.end()));
    return false;
  }
  std::vector<double> one(n, 0.0), other(n, 0.0);
  model.add_symmetric_blocks(p, one.data());
  model.add_symmetric_blocks(q, other.data());
  for(std::size_t k = 0; k < n; ++k) { // the same bits, not just close
    CHECK(std::memcmp(&S[k], &one[k], sizeof(double)) == 0);
    CHECK(std::memcmp(&T[k], &other[k], sizeof(double)) == 0);
  }
  return true;
}

template <int D>
Simplex<D> scaled(Simplex<D> p, double f)
{
  for(auto& x : p)
    for(double& c : x)
      c *= f;
  return p;
}

} // namespace

TEST_CASE("ball-vertex: two simplices at once give each one's distinct blocks, bit for bit",
          "[stiffness][ball_vertex]")
{
  std::mt19937 rng(11);
  for(double exponent : {1.0, 2.0, 2.5, 3.0}) {
    const Ball_vertex_stiffness m = ball_vertex_of_power(exponent);
    const With_ball_vertex<Grid_scaled_stiffness> combined{{}, m};
    int taken = 0;
    for(int trial = 0; trial < 300; ++trial) {
      taken += check_blocks_of_two<2>(m, random_simplex<2>(rng), random_simplex<2>(rng), rng);
      taken += check_blocks_of_two<3>(m, random_simplex<3>(rng), random_simplex<3>(rng), rng);
    }
    CHECK(taken == 600); // ordinary simplices take the pair form
    CHECK(check_blocks_of_two<2>(combined, triangle, obtuse_triangle, rng));
    CHECK(check_blocks_of_two<3>(combined, sliver, tetrahedron, rng));
    // either lane outside the uncapped range, flat, or with a tiny edge:
    // declined, whichever lane it is
    for(const double f : {1e-60, 1e-200, 1e160}) {
      CHECK_FALSE(check_blocks_of_two<2>(m, scaled<2>(triangle, f), triangle, rng));
      CHECK_FALSE(check_blocks_of_two<3>(m, tetrahedron, scaled<3>(sliver, f), rng));
    }
    const Simplex<2> flat{{{0, 0}, {1, 0}, {2, 0}}};
    const Simplex<3> tiny_edge{{{0, 0, 0}, {1e-60, 0, 0}, {0, 1, 0}, {0, 0, 1}}};
    CHECK_FALSE(check_blocks_of_two<2>(m, triangle, flat, rng));
    CHECK_FALSE(check_blocks_of_two<3>(m, tiny_edge, tetrahedron, rng));
  }
  Ball_vertex_stiffness other_power;
  other_power.exponent = 1.5;
  CHECK_FALSE(check_blocks_of_two<2>(other_power, triangle, obtuse_triangle, rng));
  CHECK_FALSE(check_blocks_of_two<3>(other_power, tetrahedron, sliver, rng));
  CHECK(internal::Has_symmetric_blocks_of_two<With_ball_vertex<Lineal_stiffness>, 3>::value);
  CHECK_FALSE(internal::Has_symmetric_blocks_of_two<Torsional_stiffness, 2>::value);
}

#if SPRING_MOTION_HAS_DOUBLE_QUAD
namespace {

// symmetric_blocks_of_four(p) against add_symmetric_blocks on each (from
// zero), as check_blocks_of_two
template <int D, class Model>
bool check_blocks_of_four(const Model& model, const std::array<Simplex<D>, 4>& p, std::mt19937& rng)
{
  const std::size_t n = (D + 1) * (D + 2) / 2 * D * (D + 1) / 2;
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  std::array<std::vector<double>, 4> start, S;
  for(std::size_t l = 0; l < 4; ++l) {
    start[l].resize(n);
    for(double& x : start[l])
      x = u(rng);
    S[l] = start[l];
  }
  const bool taken = model.symmetric_blocks_of_four({&p[0], &p[1], &p[2], &p[3]},
                                                    {S[0].data(), S[1].data(), S[2].data(), S[3].data()});
  for(std::size_t l = 0; l < 4; ++l) {
    if(!taken) {
      CHECK(S[l] == start[l]);
      continue;
    }
    std::vector<double> one(n, 0.0);
    model.add_symmetric_blocks(p[l], one.data());
    for(std::size_t k = 0; k < n; ++k) // the same bits, not just close
      CHECK(std::memcmp(&S[l][k], &one[k], sizeof(double)) == 0);
  }
  return taken;
}

} // namespace

TEST_CASE("ball-vertex: four simplices at once give each one's distinct blocks, bit for bit",
          "[stiffness][ball_vertex]")
{
  if(!internal::four_lanes_available()) {
    WARN("this processor has no AVX: the four-lane form is not used here");
    return;
  }
  std::mt19937 rng(13);
  auto four_random = [&](auto dimension) {
    constexpr int D = decltype(dimension)::value;
    return std::array<Simplex<D>, 4>{random_simplex<D>(rng), random_simplex<D>(rng), random_simplex<D>(rng),
                                     random_simplex<D>(rng)};
  };
  for(double exponent : {1.0, 2.0, 2.5, 3.0}) {
    const Ball_vertex_stiffness m = ball_vertex_of_power(exponent);
    const With_ball_vertex<Grid_scaled_stiffness> combined{{}, m};
    int taken = 0;
    for(int trial = 0; trial < 200; ++trial) {
      taken += check_blocks_of_four<2>(m, four_random(std::integral_constant<int, 2>{}), rng);
      taken += check_blocks_of_four<3>(m, four_random(std::integral_constant<int, 3>{}), rng);
    }
    CHECK(taken == 400); // ordinary simplices take the four-lane form
    CHECK(check_blocks_of_four<2>(combined, {triangle, obtuse_triangle, obtuse_triangle, triangle}, rng));
    CHECK(check_blocks_of_four<3>(combined, {sliver, tetrahedron, tetrahedron, sliver}, rng));
    // one lane outside the uncapped range, flat, or with a tiny edge:
    // declined, whichever lane it is
    const Simplex<2> flat{{{0, 0}, {1, 0}, {2, 0}}};
    const Simplex<3> tiny_edge{{{0, 0, 0}, {1e-60, 0, 0}, {0, 1, 0}, {0, 0, 1}}};
    for(std::size_t lane = 0; lane < 4; ++lane) {
      for(const double f : {1e-60, 1e-200, 1e160}) {
        std::array<Simplex<2>, 4> t{triangle, obtuse_triangle, triangle, obtuse_triangle};
        std::array<Simplex<3>, 4> s{tetrahedron, sliver, tetrahedron, sliver};
        t[lane] = scaled<2>(triangle, f);
        s[lane] = scaled<3>(sliver, f);
        CHECK_FALSE(check_blocks_of_four<2>(m, t, rng));
        CHECK_FALSE(check_blocks_of_four<3>(m, s, rng));
      }
      std::array<Simplex<2>, 4> t{triangle, triangle, triangle, triangle};
      std::array<Simplex<3>, 4> s{tetrahedron, tetrahedron, tetrahedron, tetrahedron};
      t[lane] = flat;
      s[lane] = tiny_edge;
      CHECK_FALSE(check_blocks_of_four<2>(m, t, rng));
      CHECK_FALSE(check_blocks_of_four<3>(m, s, rng));
    }
  }
  Ball_vertex_stiffness other_power;
  other_power.exponent = 1.5;
  CHECK_FALSE(check_blocks_of_four<2>(other_power, {triangle, triangle, obtuse_triangle, obtuse_triangle}, rng));
  CHECK_FALSE(check_blocks_of_four<3>(other_power, {tetrahedron, sliver, sliver, tetrahedron}, rng));
  CHECK(internal::Has_symmetric_blocks_of_four<With_ball_vertex<Lineal_stiffness>, 3>::value);
  CHECK_FALSE(internal::Has_symmetric_blocks_of_four<Torsional_stiffness, 2>::value);
}
#endif

namespace {

// Ball-vertex springs that do not say they have no edge springs: the
// assembly then computes k = 0 on every edge and adds their zero blocks,
// the path every model took before Edge_spring_form::none
struct Ball_vertex_with_zero_edges : Ball_vertex_stiffness
{
  Edge_spring_form edge_spring_form() const { return Edge_spring_form::per_coordinate; }
};

// no edge springs and no element matrix: nothing to solve
struct No_springs
{
  Angle_kind angle_kind(int) const { return Angle_kind::none; }
  double operator()(double, const double*, std::size_t, const Stiffness_context&) const { return 0.0; }
  Edge_spring_form edge_spring_form() const { return Edge_spring_form::none; }
};

template <int D, class Motion>
void check_same_bits_without_edge_springs(const Spring_network<D>& net, const std::vector<Vertex_role>& roles,
                                          const Motion& motion)
{
  Ball_vertex_stiffness model;
  model.exponent = 2;
  Ball_vertex_with_zero_edges zero_edges;
  zero_edges.exponent = 2;
  REQUIRE(internal::edge_spring_form(model) == Edge_spring_form::none);
  Deform_options options;
  options.number_of_steps = 4;
  Network_deformer<D> skipped(net, roles), computed(net, roles);
  const auto a = skipped.run(motion, model, options), b = computed.run(motion, zero_edges, options);
  REQUIRE(a.completed);
  REQUIRE(b.completed);
  // every step's system is a new one (the blocks of the last step cleared):
  // the same iterations and the same bits
  for(std::size_t s = 0; s < a.steps.size(); ++s)
    CHECK(a.steps[s].iterations == b.steps[s].iterations);
  CHECK(skipped.positions() == computed.positions());
  CHECK(skipped.positions() != net.points);
}

} // namespace

TEST_CASE("ball-vertex springs alone: no edge stiffness computed, the same system as zero edge springs give",
          "[deform][ball_vertex]")
{
  SECTION("2D NACA0012")
  {
    const auto n = spring_motion_test::naca0012_network();
    check_same_bits_without_edge_springs<2>(n.network, n.roles, Pitch_motion<2>(20, {0.25, 0.0}));
  }
  SECTION("3D Kuhn grid, its boundary turning")
  {
    const Indexed_mesh<3> mesh = spring_motion_test::kuhn_grid<3>(4);
    auto net = make_spring_network<3>(mesh.points, mesh.elements);
    const auto roles = assign_roles(net, All_boundary_moving{});
    check_same_bits_without_edge_springs<3>(net, roles, Pitch_motion<3>(10, {2.0, 2.0, 2.0}));
  }
  SECTION("a model with neither edge springs nor element matrices is refused")
  {
    const auto n = spring_motion_test::naca0012_network();
    Network_deformer<2> d(n.network, n.roles);
    Deform_options options;
    options.number_of_steps = 1;
    CHECK_THROWS_WITH(d.run(Pitch_motion<2>(20, {0.25, 0.0}), No_springs{}, options),
                      Catch::Contains("has neither edge springs nor element matrices"));
  }
}
