// Equiangle skewness R (paper Eq. 13, docs/method.md "Validity and quality") and its histograms.
#include <spring_motion/skewness.h>

#include <catch2/catch.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <random>
#include <vector>

using namespace spring_motion;

namespace {
using P2 = std::array<double, 2>;
using P3 = std::array<double, 3>;
// R is a few atan2 and divisions on O(1) values: right to a few ulps
constexpr double tol = 1e-14;
} // namespace

TEST_CASE("equiangle_skewness: hand-computed triangles (2D Eq. 13)", "[skewness]")
{
  // equilateral: every angle is Q_e = 60 degrees, both terms vanish
  CHECK(equiangle_skewness(P2{0, 0}, P2{1, 0}, P2{0.5, std::sqrt(3.0) / 2}) == Approx(0).margin(tol));
  // right isosceles, angles 90, 45, 45: (90 - 60)/(180 - 60) = 1/4 and (60 - 45)/60 = 1/4
  CHECK(equiangle_skewness(P2{0, 0}, P2{1, 0}, P2{0, 1}) == Approx(0.25).epsilon(tol));
  // the same triangle turned, scaled and listed clockwise: R depends on the angles only
  CHECK(equiangle_skewness(P2{3, 1}, P2{3 - 2 * 0.6, 1 + 2 * 0.8}, P2{3 + 2 * 0.8, 1 + 2 * 0.6}) ==
        Approx(0.25).epsilon(1e-13));
  // obtuse isosceles (0,0), (2,0), (1,1/2): base angles atan(1/2), apex
  // 180 - 2 atan(1/2); both terms equal 1 - atan(1/2)/(pi/3)
  CHECK(equiangle_skewness(P2{0, 0}, P2{2, 0}, P2{1, 0.5}) == Approx(1 - std::atan(0.5) / (internal::pi / 3)).epsilon(tol));
  // 3-4-5: largest angle 90 gives 1/4, smallest atan(3/4) gives 1 - atan(3/4)/(pi/3) = 0.385...
  CHECK(equiangle_skewness(P2{0, 0}, P2{4, 0}, P2{0, 3}) == Approx(1 - std::atan(0.75) / (internal::pi / 3)).epsilon(tol));
}

TEST_CASE("equiangle_skewness: degenerate triangles give 1", "[skewness]")
{
  // collinear: angles 0, 180, 0, so (180 - 60)/(180 - 60) = 1
  CHECK(equiangle_skewness(P2{0, 0}, P2{1, 0}, P2{2, 0}) == 1.0);
  // collinear with the middle vertex listed first
  CHECK(equiangle_skewness(P2{1, 1}, P2{0, 0}, P2{3, 3}) == 1.0);
  // two coincident vertices: the angles are 0 (no 'angle' exists, and R must still say degenerate)
  CHECK(equiangle_skewness(P2{0, 0}, P2{0, 0}, P2{1, 0}) == 1.0);
  // nearly flat: close to 1 but below it
  const double r = equiangle_skewness(P2{0, 0}, P2{2, 0}, P2{1, 1e-9});
  CHECK(r < 1.0);
  CHECK(r > 1 - 1e-8);
}

TEST_CASE("equiangle_skewness: an angle that is not a number gives 1, never a perfect 0", "[skewness]")
{
  const double nan = std::nan("");
  // wherever the NaN sits (min/max compare false against it)
  for(int k = 0; k < 3; ++k) {
    std::array<double, 3> a{internal::pi / 3, internal::pi / 3, internal::pi / 3};
    a[std::size_t(k)] = nan;
    CHECK(equiangle_skewness_from_angles(a.data(), 3, 2) == 1.0);
  }
  std::array<double, 6> d;
  d.fill(std::acos(1.0 / 3.0));
  d[5] = nan;
  CHECK(equiangle_skewness_from_angles(d.data(), 6, 3) == 1.0);
  // through the geometry: a vertex with a NaN coordinate
  CHECK(equiangle_skewness(P2{0, 0}, P2{1, 0}, P2{nan, 0.5}) == 1.0);
  CHECK(equiangle_skewness(P3{1, 1, 1}, P3{1, -1, -1}, P3{-1, 1, -1}, P3{-1, -1, nan}) == 1.0);
}

TEST_CASE("equiangle_skewness: tetrahedra (3D, dihedral angles)", "[skewness]")
{
  // regular tetrahedron: all six dihedral angles are arccos(1/3) = Q_e
  CHECK(equiangle_skewness(P3{1, 1, 1}, P3{1, -1, -1}, P3{-1, 1, -1}, P3{-1, -1, 1}) == Approx(0).margin(tol));
  // a flat tetrahedron (four coplanar points): dihedral angles 0 and 180
  CHECK(equiangle_skewness(P3{0, 0, 0}, P3{1, 0, 0}, P3{0, 1, 0}, P3{1, 1, 0}) == 1.0);
}

TEST_CASE("skewness_histogram: ten bins from b/10 up to (b+1)/10, R = 1 in the last, over the selected elements",
          "[skewness]")
{
  const std::vector<double> r{0.0, 0.05, 0.1, 0.25, 0.95, 1.0, 0.5};
  const auto all = skewness_histogram(r, [](std::size_t) { return true; });
  REQUIRE(all.fractions.size() == 10);
  CHECK(all.count == 7);
  const std::vector<double> expected{2.0 / 7, 1.0 / 7, 1.0 / 7, 0, 0, 1.0 / 7, 0, 0, 0, 2.0 / 7};
  for(std::size_t b = 0; b < 10; ++b) {
    INFO("bin " << b);
    CHECK(all.fractions[b] == Approx(expected[b]).margin(1e-15));
  }
  CHECK(all.max == 1.0);
  CHECK(all.mean == Approx((0.05 + 0.1 + 0.25 + 0.95 + 1.0 + 0.5) / 7).epsilon(1e-15));
  // a subset: the even-numbered entries 0, 0.1, 0.95, 0.5
  const auto even = skewness_histogram(r, [](std::size_t t) { return t % 2 == 0; });
  CHECK(even.count == 4);
  CHECK(even.fractions[0] == 0.25);
  CHECK(even.fractions[1] == 0.25);
  CHECK(even.fractions[5] == 0.25);
  CHECK(even.fractions[9] == 0.25);
  CHECK(even.max == 0.95);
  // nothing selected: zero fractions, no division by zero
  const auto none = skewness_histogram(r, [](std::size_t) { return false; });
  CHECK(none.count == 0);
  CHECK(none.mean == 0);
  for(double f : none.fractions)
    CHECK(f == 0);
}

TEST_CASE("element_skewness: smallest angles of known triangles and tetrahedra", "[skewness][angles]")
{
  // right isosceles triangle: 45 degrees; equilateral: 60
  const auto tri = make_spring_network<2>({{0, 0}, {1, 0}, {0, 1}, {2, 0}, {1.5, std::sqrt(3.0) / 2}},
                                          {{0, 1, 2}, {1, 3, 4}});
  std::vector<double> a2;
  const auto r2 = element_skewness(tri, tri.points, 1, &a2);
  REQUIRE(a2.size() == 2);
  CHECK(std::abs(a2[0] - 45.0) < 1e-12);
  CHECK(std::abs(a2[1] - 60.0) < 1e-12);
  CHECK(r2 == element_skewness(tri, tri.points, 1)); // R does not depend on asking for angles

  // regular tetrahedron: every dihedral angle arccos(1/3); corner tetrahedron:
  // three right angles at the corner's edges, three arccos(1/sqrt(3))
  const double s = 1 / std::sqrt(2.0);
  const auto tet = make_spring_network<3>({{1, 0, -s}, {-1, 0, -s}, {0, 1, s}, {0, -1, s},
                                           {10, 0, 0}, {11, 0, 0}, {10, 1, 0}, {10, 0, 1}},
                                          {{0, 1, 2, 3}, {4, 5, 6, 7}});
  std::vector<double> a3;
  element_skewness(tet, tet.points, 1, &a3);
  const double deg = 180 / 3.141592653589793;
  CHECK(std::abs(a3[0] - std::acos(1.0 / 3.0) * deg) < 1e-12);
  CHECK(std::abs(a3[1] - std::acos(1 / std::sqrt(3.0)) * deg) < 1e-12);

  // a flattened tetrahedron (fourth vertex in the base's plane): angle 0
  auto flat = tet.points;
  flat[7] = {10.3, 0.3, 0};
  element_skewness(tet, flat, 1, &a3);
  CHECK(a3[1] < 1e-12);
}

// The dihedral angles of p in extended precision, by projection onto the
// plane orthogonal to each edge (as dihedral_angles() in double): the
// reference for the extremes element_skewness reads.
static std::array<long double, 6> extended_dihedral_angles(const std::array<std::array<double, 3>, 4>& p)
{
  using T = spring_motion::internal::Simplex_tables<3>;
  std::array<long double, 6> out;
  for(int k = 0; k < 6; ++k) {
    long double e[3], u[3], w[3];
    for(int c = 0; c < 3; ++c) {
      const long double a = p[T::edge[k][0]][c];
      e[c] = p[T::edge[k][1]][c] - a;
      u[c] = p[T::other[k][0]][c] - a;
      w[c] = p[T::other[k][1]][c] - a;
    }
    const long double ee = e[0] * e[0] + e[1] * e[1] + e[2] * e[2];
    const long double su = (u[0] * e[0] + u[1] * e[1] + u[2] * e[2]) / ee;
    const long double sw = (w[0] * e[0] + w[1] * e[1] + w[2] * e[2]) / ee;
    for(int c = 0; c < 3; ++c) {
      u[c] -= su * e[c];
      w[c] -= sw * e[c];
    }
    const long double x[3] = {u[1] * w[2] - u[2] * w[1], u[2] * w[0] - u[0] * w[2], u[0] * w[1] - u[1] * w[0]};
    out[std::size_t(k)] =
        std::atan2(std::sqrt(x[0] * x[0] + x[1] * x[1] + x[2] * x[2]), u[0] * w[0] + u[1] * w[1] + u[2] * w[2]);
  }
  return out;
}

// element_skewness reads only the extreme angles (two atan2 per element); on
// random elements of every shape (needles, caps, slivers squashed to 1e-9)
// they must be the extremes of the angles computed in extended precision,
// the smallest one to a relative error (it is the reported one, and a
// sliver's is tiny). In 2D they are the very numbers triangle_angles gives.
TEST_CASE("angle ranges: the extremes of the angles, for two atan2 per element", "[skewness][angles]")
{
  namespace si = spring_motion::internal;
  std::mt19937_64 rng(20261125);
  std::uniform_real_distribution<double> u(-1, 1);
  std::uniform_int_distribution<int> squash(0, 3);
  for(int trial = 0; trial < 20000; ++trial) {
    // a random simplex, one of its coordinates often squashed towards a plane
    const double f = std::pow(10.0, -3 * squash(rng));
    std::array<std::array<double, 3>, 4> p;
    for(auto& q : p)
      q = {u(rng), u(rng), f * u(rng)};
    const auto ref = extended_dihedral_angles(p);
    const auto mm3 = std::minmax_element(ref.begin(), ref.end());
    const auto r3 = si::dihedral_angle_range(p);
    INFO("trial " << trial << ", squash " << f);
    CHECK(std::abs(r3[0] - double(*mm3.first)) <= 1e-9 * double(*mm3.first) + 1e-300);
    CHECK(std::abs(r3[1] - double(*mm3.second)) <= 1e-13);
    // and the angles of dihedral_angles() to rounding
    const auto all3 = si::dihedral_angles(p);
    CHECK(r3[0] == Approx(*std::min_element(all3.begin(), all3.end())).margin(1e-13));
    CHECK(r3[1] == Approx(*std::max_element(all3.begin(), all3.end())).margin(1e-13));

    const std::array<double, 2> a{p[0][0], f * p[0][1]}, b{p[1][0], f * p[1][1]}, c{p[2][0], f * p[2][1]};
    const auto all2 = si::triangle_angles<2>(a, b, c);
    const auto r2 = si::triangle_angle_range<2>(a, b, c);
    const auto mm2 = std::minmax_element(all2.begin(), all2.end());
    CHECK(r2[0] == Approx(*mm2.first).margin(1e-14).epsilon(1e-13));
    CHECK(r2[1] == Approx(*mm2.second).margin(1e-14).epsilon(1e-13));
    CHECK((std::find(all2.begin(), all2.end(), r2[0]) != all2.end()));
    CHECK((std::find(all2.begin(), all2.end(), r2[1]) != all2.end()));
  }
  // the regular tetrahedron: every angle arccos(1/3)
  const double h = 1 / std::sqrt(2.0);
  const std::array<std::array<double, 3>, 4> regular{{{1, 0, -h}, {-1, 0, -h}, {0, 1, h}, {0, -1, h}}};
  const auto rr = si::dihedral_angle_range(regular);
  CHECK(rr[0] == Approx(std::acos(1.0 / 3.0)).epsilon(1e-14));
  CHECK(rr[1] == Approx(std::acos(1.0 / 3.0)).epsilon(1e-14));
  // degenerate: coincident vertices (angles 0 by atan2(0, 0)), collinear, flat
  const std::array<double, 2> o{0, 0}, x1{1, 0}, x2{2, 0};
  CHECK(si::triangle_angle_range<2>(o, o, x1) == (std::array<double, 2>{0, 0}));
  CHECK(si::triangle_angle_range<2>(o, x1, x2) == (std::array<double, 2>{0, si::pi}));
  // a flat tetrahedron and one with two coincident vertices: angles 0 and pi, R = 1
  const std::array<std::array<double, 3>, 4> flat{{{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {1, 1, 0}}};
  CHECK(si::dihedral_angle_range(flat) == (std::array<double, 2>{0, si::pi}));
  const std::array<std::array<double, 3>, 4> pinched{{{0, 0, 0}, {0, 0, 0}, {0, 1, 0}, {0, 0, 1}}};
  CHECK(si::dihedral_angle_range(pinched) == (std::array<double, 2>{0, si::pi}));
  // a coordinate that is not a number makes both extremes not a number
  const std::array<double, 2> bad{std::nan(""), 0};
  const auto rn = si::triangle_angle_range<2>(o, x1, bad);
  CHECK(std::isnan(rn[0]));
  CHECK(std::isnan(rn[1]));
  auto bad3 = regular;
  bad3[2][1] = std::numeric_limits<double>::infinity();
  const auto rb = si::dihedral_angle_range(bad3);
  CHECK(std::isnan(rb[0]));
  CHECK(std::isnan(rb[1]));
}
