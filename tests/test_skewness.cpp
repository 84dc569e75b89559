// Equiangle skewness R (paper Eq. 13, docs/method.md "Validity and quality") and its histograms.
#include <spring_motion/skewness.h>

#include <catch2/catch.hpp>

#include <algorithm>
#include <cfenv>
#include <cstring>
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

namespace {
// The largest R and the smallest angle of a set of elements, element by
// element from their angle ranges, as element_skewness() computes them.
template <class Range>
std::array<double, 2> quality_by_element(const std::vector<Range>& ranges, int dimension)
{
  double r = 0, a = 180;
  for(const auto& q : ranges) {
    r = std::max(r, spring_motion::equiangle_skewness_from_angles(q.data(), 2, dimension));
    a = std::min(a, std::isfinite(q[0]) ? std::min(spring_motion::internal::pi, q[0]) * (180 / spring_motion::internal::pi)
                                        : 0.0);
  }
  return {r, a};
}
} // namespace

TEST_CASE("Quality_extremes: a set's largest R and smallest angle, with atan2 only where they can change, equal "
          "the element-by-element values bitwise",
          "[skewness][angles]")
{
  namespace si = spring_motion::internal;
  std::mt19937_64 rng(20261126);
  std::uniform_real_distribution<double> u(-1, 1);
  std::uniform_int_distribution<int> squash(0, 4);
  const double h = 1 / std::sqrt(2.0);
  const std::array<std::array<double, 3>, 4> regular{{{1, 0, -h}, {-1, 0, -h}, {0, 1, h}, {0, -1, h}}};
  std::size_t evaluated_sets = 0, swapped = 0;
  for(int set = 0; set < 300; ++set) {
    // near-regular sets small, so that one element's swapped extremes decide
    const int n = 1 + int(rng() % (set % 5 == 3 ? 2 : 400));
    std::vector<si::Extreme_angles> e3, e2;
    std::vector<std::array<double, 2>> r3, r2;
    // the same element moved by a rounding-sized amount many times: keys that
    // tie or differ in the last bits, where pruning must not skip the extreme
    std::array<std::array<double, 3>, 4> base;
    for(auto& q : base)
      q = {u(rng), u(rng), std::pow(10.0, -3 * squash(rng)) * u(rng)};
    for(int i = 0; i < n; ++i) {
      std::array<std::array<double, 3>, 4> p = base;
      // one set in five: near-regular elements only, whose R (nearly 0) no
      // other element's hides
      const int kind = set % 5 == 3 ? 6 : int(rng() % 8);
      if(kind < 3)
        p[rng() % 4][rng() % 3] *= 1 + 1e-15 * double(rng() % 8);
      else if(kind < 6)
        for(auto& q : p)
          q = {u(rng), u(rng), std::pow(10.0, -3 * squash(rng)) * u(rng)};
      else if(kind == 6) {
        // every angle equal but for a few units of rounding: atan2 may give
        // the smaller value to the extreme ranked the larger
        p = regular;
        for(auto& q : p)
          for(auto& x : q)
            x *= 1 + 1e-16 * double(int(rng() % 9) - 4);
      }
      else if(rng() % 40 == 0)
        p[1] = p[0]; // flat (coincident vertices): 0 and pi
      if(set % 50 == 7 && i == n / 2)
        p[2][0] = std::nan(""); // a coordinate that is not a number
      e3.push_back(si::dihedral_extreme_angles(p));
      r3.push_back(si::dihedral_angle_range(p));
      swapped += r3.back()[0] > r3.back()[1];
      std::array<double, 2> a{p[0][0], p[0][1]}, b{p[1][0], p[1][1]}, c{p[2][0], p[2][1]};
      if(kind == 6) { // the equilateral triangle, as above
        a = {0, 0};
        b = {1, 0};
        c = {0.5, std::sqrt(3.0) / 2};
        for(auto* v : {&a, &b, &c})
          for(auto& x : *v)
            x *= 1 + 1e-16 * double(int(rng() % 9) - 4);
      }
      e2.push_back(si::triangle_extreme_angles<2>(a, b, c));
      r2.push_back(si::triangle_angle_range<2>(a, b, c));
      swapped += r2.back()[0] > r2.back()[1];
    }
    for(int dimension : {2, 3}) {
      const auto& e = dimension == 2 ? e2 : e3;
      const auto expected = quality_by_element(dimension == 2 ? r2 : r3, dimension);
      // one accumulator, and the set split in two and merged (as threads do)
      si::Quality_extremes whole, first, second;
      const std::size_t split = rng() % e.size();
      for(std::size_t i = 0; i < e.size(); ++i) {
        whole.add(e[i]);
        (i < split ? first : second).add(e[i]);
      }
      first.merge(second);
      INFO("set " << set << ", dimension " << dimension << ", " << e.size() << " elements");
      CHECK(whole.max_skewness(dimension) == expected[0]);
      CHECK(whole.min_angle_deg() == expected[1]);
      CHECK(first.max_skewness(dimension) == expected[0]);
      CHECK(first.min_angle_deg() == expected[1]);
      evaluated_sets += expected[1] > 0;
    }
  }
  CHECK(evaluated_sets > 300); // most sets have no element that is not a number
  CHECK(swapped > 10);          // and the swapped extremes were met
  // found by a search: near-regular elements whose extremes atan2 returns
  // swapped by an ulp, beside elements that are not swapped; the set's R
  // reads the swapped element's smaller value
  {
    const std::array<std::array<double, 3>, 4> swapped3{{{0.99999999999999978, 0, -0.70710678118654735},
                                                         {-1.0000000000000004, 0, -0.70710678118654746},
                                                         {0, 0.99999999999999956, 0.70710678118654779},
                                                         {0, -1.0000000000000002, 0.70710678118654746}}};
    const std::array<double, 2> o{0, 0}, b{1.0000000000000002, 0}, c{0.50000000000000011, 0.86602540378443893};
    // partners whose two extremes both equal the swapped pair's larger value
    const std::array<std::array<double, 3>, 4> even3{{{0.99999999999999956, 0, -0.70710678118654779},
                                                      {-1.0000000000000002, 0, -0.70710678118654757},
                                                      {0, 1.0000000000000002, 0.70710678118654757},
                                                      {0, -0.99999999999999989, 0.70710678118654757}}};
    const std::array<double, 2> b1{0.99999999999999956, 0}, c1{0.49999999999999978, 0.86602540378443826};
    REQUIRE(si::dihedral_angle_range(swapped3)[0] > si::dihedral_angle_range(swapped3)[1]);
    REQUIRE(si::triangle_angle_range<2>(o, b, c)[0] > si::triangle_angle_range<2>(o, b, c)[1]);
    for(int order = 0; order < 2; ++order) {
      std::vector<std::array<std::array<double, 3>, 4>> tets{swapped3, even3};
      std::vector<std::array<std::array<double, 2>, 3>> tris{{o, b, c}, {o, b1, c1}};
      if(order == 1) {
        std::swap(tets[0], tets[1]);
        std::swap(tris[0], tris[1]);
      }
      si::Quality_extremes q3, q2;
      std::vector<std::array<double, 2>> r3, r2;
      for(const auto& p : tets) {
        q3.add(si::dihedral_extreme_angles(p));
        r3.push_back(si::dihedral_angle_range(p));
      }
      for(const auto& p : tris) {
        q2.add(si::triangle_extreme_angles<2>(p[0], p[1], p[2]));
        r2.push_back(si::triangle_angle_range<2>(p[0], p[1], p[2]));
      }
      CHECK(q3.max_skewness(3) == quality_by_element(r3, 3)[0]);
      CHECK(q3.min_angle_deg() == quality_by_element(r3, 3)[1]);
      CHECK(q2.max_skewness(2) == quality_by_element(r2, 2)[0]);
      CHECK(q2.min_angle_deg() == quality_by_element(r2, 2)[1]);
    }
  }
  si::Quality_extremes none;
  CHECK(none.max_skewness(3) == 0);
  CHECK(none.min_angle_deg() == 180);
}

// 6|V| over the longest edge cubed, in extended precision
static long double extended_shape(const std::array<std::array<double, 3>, 4>& p)
{
  long double v[3][3], longest = 0;
  for(int k = 0; k < 3; ++k)
    for(int c = 0; c < 3; ++c)
      v[k][c] = (long double)(p[std::size_t(k) + 1][std::size_t(c)]) - p[0][std::size_t(c)];
  const long double volume6 = std::abs(v[0][0] * (v[1][1] * v[2][2] - v[1][2] * v[2][1]) -
                                       v[0][1] * (v[1][0] * v[2][2] - v[1][2] * v[2][0]) +
                                       v[0][2] * (v[1][0] * v[2][1] - v[1][1] * v[2][0]));
  for(int a = 0; a < 4; ++a)
    for(int b = 0; b < a; ++b) {
      long double l2 = 0;
      for(int c = 0; c < 3; ++c)
        l2 += ((long double)(p[std::size_t(a)][std::size_t(c)]) - p[std::size_t(b)][std::size_t(c)]) *
              ((long double)(p[std::size_t(a)][std::size_t(c)]) - p[std::size_t(b)][std::size_t(c)]);
      longest = std::max(longest, std::sqrt(l2));
    }
  return volume6 / (longest * longest * longest);
}

// Factors of an element's smallest sin^2 that the pass-over tests are tried at.
constexpr double bound_factors[] = {0.0, 0.5, 0.99, 1 - 1e-5, 1 - 1e-9, 1 + 1e-9, 1.01, 2.0};

// The one-bound pass-over test of element p at bounds around its smallest
// sin^2 (from extended precision): never true unless the smallest is above
// the bound; on a well-shaped element true below 0.99 of it.
template <int D>
void check_one_bound(const std::array<std::array<double, D>, D + 1>& p, long double smallest, bool well_shaped,
                     std::size_t& said_true, std::size_t& decided)
{
  for(const double factor : bound_factors) {
    const double bound = double(smallest) * factor;
    const bool above = spring_motion::internal::element_sines_squared_above<D>(p, bound);
    said_true += above;
    if(above)
      CHECK(smallest > bound);
    if(well_shaped && factor <= 0.99) {
      CHECK(above);
      ++decided;
    }
  }
}

// The pass-over test of the per-step quality: where it says every sin^2 of a
// dihedral angle exceeds the bound, the angles computed in extended precision
// agree; and on well-shaped elements with a bound clearly below their
// smallest sin^2 it decides (else it would pass over nothing).
TEST_CASE("element_sines_squared_above for tetrahedra: certain when true, and true for well-shaped elements",
          "[skewness][angles]")
{
  namespace si = spring_motion::internal;
  std::mt19937_64 rng(20261128);
  std::uniform_real_distribution<double> u(-1, 1);
  std::uniform_int_distribution<int> squash(0, 3);
  std::size_t said_true = 0, decided = 0;
  for(int trial = 0; trial < 20000; ++trial) {
    const double f = std::pow(10.0, -2 * squash(rng));
    std::array<std::array<double, 3>, 4> p;
    for(auto& q : p)
      q = {u(rng), u(rng), f * u(rng)};
    // sizes far from 1 too: the products of lengths must not over- or underflow
    const double size = std::pow(10.0, double(int(rng() % 41) - 20));
    for(auto& q : p)
      for(auto& x : q)
        x *= size;
    const auto angles = extended_dihedral_angles(p);
    long double smallest = 1;
    for(const long double a : angles)
      smallest = std::min(smallest, std::sin(a) * std::sin(a));
    const long double shape = extended_shape(p);
    const bool well_shaped = shape >= 1e-5L;
    INFO("trial " << trial << ", smallest sin^2 " << double(smallest) << ", 6V / L^3 " << double(shape));
    check_one_bound<3>(p, smallest, well_shaped, said_true, decided);
  }
  CHECK(said_true > 10000);
  CHECK(decided > 10000);
  // flat, coincident and non-finite corners: never passed over
  const std::array<std::array<double, 3>, 4> flat{{{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {1, 1, 0}}};
  CHECK_FALSE(si::element_sines_squared_above<3>(flat, 0));
  const std::array<std::array<double, 3>, 4> pinched{{{0, 0, 0}, {0, 0, 0}, {0, 1, 0}, {0, 0, 1}}};
  CHECK_FALSE(si::element_sines_squared_above<3>(pinched, 0));
  std::array<std::array<double, 3>, 4> corner{{{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}}};
  CHECK(si::element_sines_squared_above<3>(corner, 0.5)); // sin^2 of its angles: 1 and 2/3
  CHECK_FALSE(si::element_sines_squared_above<3>(corner, 0.7));
  corner[3][2] = std::numeric_limits<double>::infinity();
  CHECK_FALSE(si::element_sines_squared_above<3>(corner, 0));
  corner[3][2] = std::nan("");
  CHECK_FALSE(si::element_sines_squared_above<3>(corner, 0));
}

// With a bound for the acute angles and another for the obtuse ones: each
// angle certainly above its own kind's bound when the test says true, and
// true for well-shaped elements whose angles clear both bounds by 1%; the
// kinds swapped would fail one or the other.
TEST_CASE("element_sines_squared_above for tetrahedra with two bounds: certain when true, and true for "
          "well-shaped elements",
          "[skewness][angles]")
{
  namespace si = spring_motion::internal;
  std::mt19937_64 rng(20261204);
  std::uniform_real_distribution<double> u(-1, 1);
  std::uniform_int_distribution<int> squash(0, 2);
  std::size_t said_true = 0, decided = 0, both_kinds = 0;
  for(int trial = 0; trial < 20000; ++trial) {
    const double f = std::pow(10.0, -squash(rng));
    std::array<std::array<double, 3>, 4> p;
    for(auto& q : p)
      q = {u(rng), u(rng), f * u(rng)};
    const auto angles = extended_dihedral_angles(p);
    // the smallest sin^2 of each kind (1 where the element has none of it)
    long double acute = 1, obtuse = 1;
    bool has_acute = false, has_obtuse = false;
    for(const long double a : angles) {
      const bool is_acute = a < 1.5707963267948966192L;
      (is_acute ? has_acute : has_obtuse) = true;
      long double& m = is_acute ? acute : obtuse;
      m = std::min(m, std::sin(a) * std::sin(a));
    }
    both_kinds += has_acute && has_obtuse;
    const bool well_shaped = extended_shape(p) >= 1e-5L;
    INFO("trial " << trial << ", smallest sin^2 acute " << double(acute) << ", obtuse " << double(obtuse));
    for(const double fa : {0.5, 0.99, 1 - 1e-9, 1.01})
      for(const double fo : {0.0, 0.9, 0.99, 1 + 1e-9, 1.5}) {
        const double ab = double(acute) * fa, ob = double(obtuse) * fo;
        const bool above = si::element_sines_squared_above<3>(p, ab, ob);
        said_true += above;
        if(above) {
          CHECK((!has_acute || acute > ab));
          CHECK((!has_obtuse || obtuse > ob));
        }
        if(well_shaped && fa <= 0.99 && fo <= 0.99) {
          CHECK(above);
          ++decided;
        }
      }
  }
  CHECK(both_kinds > 5000);
  CHECK(said_true > 20000);
  CHECK(decided > 20000);
  // the corner tetrahedron: three right angles (sin^2 1, the cosine's
  // numerator exactly 0) and three of sin^2 2/3
  const std::array<std::array<double, 3>, 4> corner{{{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}}};
  CHECK(si::element_sines_squared_above<3>(corner, 0.6, 0.99));
  CHECK_FALSE(si::element_sines_squared_above<3>(corner, 0.7, 0.5));
  CHECK_FALSE(si::element_sines_squared_above<3>(corner, 0.6, 1.0)); // a right angle is not above 1
  const std::array<std::array<double, 3>, 4> flat{{{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {1, 1, 0}}};
  CHECK_FALSE(si::element_sines_squared_above<3>(flat, 0, 0.5));
}

// The one-bound test of four tetrahedra at once (one per lane of an AVX
// register) answers what the scalar test answers for each, at bounds right
// at each lane's smallest sin^2, on random shapes of sizes out of the test's
// range too (those lanes answer false without forming the products that
// could overflow) and on flat, coincident and non-finite corners in every
// lane; and it raises no overflow, invalid or division flag that the scalar
// tests of the same four do not.
TEST_CASE("element_sines_squared_above for four tetrahedra at once answers as for each", "[skewness][angles]")
{
  namespace si = spring_motion::internal;
#if SPRING_MOTION_HAS_DOUBLE_QUAD
  if(!si::four_lanes_available()) {
    WARN("no AVX on this processor: the four-lane test is not used, nor tested");
    return;
  }
  using Tet = std::array<std::array<double, 3>, 4>;
  std::mt19937_64 rng(20261207);
  std::uniform_real_distribution<double> u(-1, 1);
  std::uniform_int_distribution<int> squash(0, 3);
  std::vector<Tet> shapes;
  std::vector<double> smallest;
  for(int trial = 0; trial < 8000; ++trial) {
    const double f = std::pow(10.0, -2 * squash(rng));
    Tet p;
    for(auto& q : p)
      q = {u(rng), u(rng), f * u(rng)};
    const double size = std::pow(10.0, double(int(rng() % 81) - 40));
    for(auto& q : p)
      for(auto& x : q)
        x *= size;
    long double least = 1;
    for(const long double a : extended_dihedral_angles(p))
      least = std::min(least, std::sin(a) * std::sin(a));
    shapes.push_back(p);
    smallest.push_back(double(least));
  }
  const double inf = std::numeric_limits<double>::infinity(), nan = std::nan("");
  const std::vector<Tet> special{{{{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {1, 1, 0}}},
                                 {{{0, 0, 0}, {0, 0, 0}, {0, 1, 0}, {0, 0, 1}}},
                                 {{{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, inf}}},
                                 {{{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, nan}}},
                                 {{{0, 0, 0}, {1e-31, 0, 0}, {0, 1e-31, 0}, {0, 0, 1e-31}}},
                                 {{{0, 0, 0}, {1e31, 0, 0}, {0, 1e31, 0}, {0, 0, 1e31}}},
                                 {{{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}}}};
  // each special shape in each lane, the other lanes random
  for(std::size_t k = 0; k < special.size(); ++k)
    for(std::size_t l = 0; l < 4; ++l) {
      const std::size_t at = shapes.size() - 4 * (k * 4 + l + 1) + l;
      shapes[at] = special[k];
      smallest[at] = 0.5;
    }
  std::size_t lanes_true = 0, lanes_false = 0;
  for(std::size_t g = 0; g + 4 <= shapes.size(); g += 4) {
    std::array<const double*, 4> t[4];
    for(std::size_t l = 0; l < 4; ++l)
      for(std::size_t k = 0; k < 4; ++k)
        t[l][k] = shapes[g + l][k].data();
    for(std::size_t at = 0; at < 4; ++at)
      for(const double factor : bound_factors) {
        const double bound = smallest[g + at] * factor;
        std::feclearexcept(FE_ALL_EXCEPT);
        bool scalar[4];
        for(std::size_t l = 0; l < 4; ++l)
          scalar[l] = si::element_sines_squared_above<3>(shapes[g + l], bound);
        const int scalar_flags = std::fetestexcept(FE_OVERFLOW | FE_INVALID | FE_DIVBYZERO);
        std::feclearexcept(FE_ALL_EXCEPT);
        bool lanes[4];
        si::dihedral_sines_squared_above(t, bound, lanes);
        const int lane_flags = std::fetestexcept(FE_OVERFLOW | FE_INVALID | FE_DIVBYZERO);
        INFO("group " << g << ", bound " << bound);
        CHECK((lane_flags & ~scalar_flags) == 0);
        for(std::size_t l = 0; l < 4; ++l) {
          CHECK(lanes[l] == scalar[l]);
          ++(lanes[l] ? lanes_true : lanes_false);
        }
      }
  }
  CHECK(lanes_true > 20000);
  CHECK(lanes_false > 20000);
  // the volumes of the same four, scaled: signed_measure's bits, a zero's
  // sign too (the flat shapes)
  std::size_t zeros = 0;
  for(std::size_t g = 0; g + 4 <= shapes.size(); g += 4) {
    std::array<const double*, 4> t[4];
    for(std::size_t l = 0; l < 4; ++l)
      for(std::size_t k = 0; k < 4; ++k)
        t[l][k] = shapes[g + l][k].data();
    for(const double scale : {1.0, std::ldexp(1.0, -20), std::ldexp(1.0, 30), 0.75})
      for(int mirror = 0; mirror < 2; ++mirror) {
        // mirrored (two corners swapped): the other sign, and the other zero
        std::array<const double*, 4> m[4];
        for(std::size_t l = 0; l < 4; ++l) {
          m[l] = t[l];
          if(mirror)
            std::swap(m[l][1], m[l][2]);
        }
        double lanes[4];
        si::scaled_signed_measures(m, scale, lanes);
        for(std::size_t l = 0; l < 4; ++l) {
          Tet p;
          for(std::size_t k = 0; k < 4; ++k)
            for(std::size_t c = 0; c < 3; ++c)
              p[k][c] = m[l][k][c] * scale;
          const double scalar = si::signed_measure(p);
          INFO("group " << g << ", lane " << l << ", scale " << scale);
          CHECK(std::memcmp(&lanes[l], &scalar, sizeof(double)) == 0);
          zeros += scalar == 0;
        }
      }
  }
  CHECK(zeros >= 8);
#else
  WARN("no four-lane form in this build");
#endif
}

// Copies of the elements holding the smallest and the largest angle, moved
// by rounding-sized amounts, at random places after them: where a pass-over
// would have to be exact to the last bit.
template <int D, class Rng>
void add_rounded_copies(std::vector<std::array<std::array<double, D>, D + 1>>& elements, Rng& rng)
{
  namespace si = spring_motion::internal;
  const auto range = [](const std::array<std::array<double, D>, D + 1>& t) {
    if constexpr(D == 2)
      return si::triangle_angle_range<2>(t[0], t[1], t[2]);
    else
      return si::dihedral_angle_range(t);
  };
  for(const bool largest : {false, true}) {
    std::size_t e = 0;
    for(std::size_t i = 1; i < elements.size(); ++i) {
      const auto a = range(elements[i]), b = range(elements[e]);
      if(largest ? a[1] > b[1] : a[0] < b[0])
        e = i;
    }
    for(int copy = 0; copy < 20; ++copy) {
      auto t = elements[e];
      for(auto& q : t)
        for(auto& x : q)
          x *= 1 + 1e-16 * double(int(rng() % 9) - 4);
      elements.insert(elements.begin() + long(e + 1 + rng() % (elements.size() - e)), t);
    }
  }
}

// Quality_extremes::add_element<D> over `elements`: add()'s numbers of
// every element, bitwise, in one set and in two (the first `split` elements
// and the rest) merged, as threads do; the same with guesses of the
// extremes inside them (as a motion's last step moved inwards), the guess
// held; with guesses outside them, held never (their elements may be
// passed over). Counts the elements passed over without a guess and with.
template <int D>
void check_pass_over(const std::vector<std::array<std::array<double, D>, D + 1>>& elements, std::size_t split,
                     std::size_t& passed, std::size_t& guessed_passed)
{
  namespace si = spring_motion::internal;
  si::Quality_extremes every, passing, first, second;
  for(std::size_t i = 0; i < elements.size(); ++i) {
    every.add(si::element_extreme_angles<D>(elements[i]));
    passed += passing.add_element<D>(elements[i]);
    (i < split ? first : second).add_element<D>(elements[i]);
  }
  first.merge(second);
  CHECK(passing.max_skewness(D) == every.max_skewness(D));
  CHECK(passing.min_angle_deg() == every.min_angle_deg());
  CHECK(first.max_skewness(D) == every.max_skewness(D));
  CHECK(first.min_angle_deg() == every.min_angle_deg());
  const double smallest = every.smallest_angle(), largest = every.largest_angle();
  for(const double inset : {1e-3, 0.05, 0.3}) {
    si::Quality_extremes guessed, half, other;
    for(auto* q : {&guessed, &half, &other})
      q->guess(smallest + inset, largest - inset);
    for(std::size_t i = 0; i < elements.size(); ++i) {
      guessed_passed += guessed.add_element<D>(elements[i]);
      (i < split ? half : other).add_element<D>(elements[i]);
    }
    half.merge(other);
    CHECK(guessed.guess_held());
    CHECK(half.guess_held());
    CHECK(guessed.max_skewness(D) == every.max_skewness(D));
    CHECK(guessed.min_angle_deg() == every.min_angle_deg());
    CHECK(half.max_skewness(D) == every.max_skewness(D));
    CHECK(half.min_angle_deg() == every.min_angle_deg());
  }
  for(const double outset : {1e-3, 0.05}) {
    si::Quality_extremes low, high;
    low.guess(smallest - outset, largest - 1e-3);
    high.guess(smallest + 1e-3, largest + outset);
    for(const auto& e : elements) {
      low.add_element<D>(e);
      high.add_element<D>(e);
    }
    CHECK_FALSE(low.guess_held());
    CHECK_FALSE(high.guess_held());
  }
}

// Quality_extremes::add_element on jittered lattices of tetrahedra with
// slivers, needles and flat elements among them, and copies of the extreme
// elements moved by rounding-sized amounts (where a pass-over would have
// to be exact to the last bit): the same numbers as add() of every element,
// bitwise, with most elements passed over.
TEST_CASE("Quality_extremes::add_element in 3D: add()'s numbers bitwise, most elements passed over",
          "[skewness][angles]")
{
  namespace si = spring_motion::internal;
  using Tet = std::array<std::array<double, 3>, 4>;
  std::mt19937_64 rng(202611281);
  std::uniform_real_distribution<double> u(-1, 1);
  // the six tetrahedra of a cube around its diagonal 0-7 (corner c = x + 2y + 4z)
  const int kuhn[6][4] = {{0, 1, 3, 7}, {0, 3, 2, 7}, {0, 2, 6, 7}, {0, 6, 4, 7}, {0, 4, 5, 7}, {0, 5, 1, 7}};
  std::size_t passed = 0, total = 0, guessed_passed = 0;
  for(int set = 0; set < 40; ++set) {
    const int n = 4 + set % 4;
    // the wedge's sets nearly regular (angles near 45, 60 and 90 degrees):
    // the wedge then holds the largest angle, and R, with its smallest angle
    // above the lattice's
    const double jitter = set % 2 == 1 ? 0.01 : 0.05 + 0.3 * double(set % 5) / 4;
    std::vector<P3> grid;
    for(int z = 0; z <= n; ++z)
      for(int y = 0; y <= n; ++y)
        for(int x = 0; x <= n; ++x)
          grid.push_back({x + jitter * u(rng), y + jitter * u(rng), z + jitter * u(rng)});
    const auto at = [&](int x, int y, int z) { return grid[std::size_t((z * (n + 1) + y) * (n + 1) + x)]; };
    std::vector<Tet> tets;
    for(int z = 0; z < n; ++z)
      for(int y = 0; y < n; ++y)
        for(int x = 0; x < n; ++x)
          for(const auto& k : kuhn) {
            Tet t;
            for(int v = 0; v < 4; ++v)
              t[std::size_t(v)] = at(x + (k[v] & 1), y + (k[v] >> 1 & 1), z + (k[v] >> 2));
            tets.push_back(t);
          }
    // odd elements at random places: a sliver (its smallest angle decides
    // R) or a wedge (angles from 52 to 122 degrees), a needle, a flat one
    for(int i = 0; i < 3; ++i) {
      Tet t = tets[rng() % tets.size()];
      if(i == 0 && set % 2 == 0)
        t[3] = {(t[0][0] + t[1][0] + t[2][0]) / 3 + 1e-3 * u(rng), (t[0][1] + t[1][1] + t[2][1]) / 3,
                (t[0][2] + t[1][2] + t[2][2]) / 3};
      else if(i == 0)
        for(int v = 1; v < 4; ++v)
          t[std::size_t(v)] = {t[0][0] + (v == 1 ? 1 : 0.5), t[0][1] + (v == 1 ? 0 : v == 2 ? 0.9 : -0.9),
                               t[0][2] + (v == 1 ? 0 : 0.5)};
      else if(i == 1)
        t[3] = {t[0][0] + 50, t[0][1] + 1e-2, t[0][2]};
      else if(set % 10 == 3)
        t[3] = t[0];
      tets.insert(tets.begin() + long(rng() % tets.size()), t);
    }
    add_rounded_copies<3>(tets, rng);
    INFO("set " << set << ", " << tets.size() << " elements, jitter " << jitter);
    check_pass_over<3>(tets, rng() % tets.size(), passed, guessed_passed);
    total += tets.size();
  }
  CHECK(passed > total / 2);
  INFO("passed over: " << passed << " of " << total << " unguessed, " << guessed_passed << " guessed");
  CHECK(guessed_passed > passed * 3); // three guesses per set, each passing over at least the unguessed
}

// The interior angles of triangle p in extended precision, and twice its
// area over its longest edge squared.
static std::array<long double, 3> extended_triangle_angles(const std::array<P2, 3>& p, long double& shape)
{
  std::array<long double, 3> angles;
  long double longest = 0, cross = 0;
  for(int k = 0; k < 3; ++k) {
    const P2 &a = p[std::size_t(k)], &b = p[std::size_t(k + 1) % 3], &c = p[std::size_t(k + 2) % 3];
    const long double ux = (long double)(b[0]) - a[0], uy = (long double)(b[1]) - a[1];
    const long double wx = (long double)(c[0]) - a[0], wy = (long double)(c[1]) - a[1];
    cross = ux * wy - uy * wx;
    angles[std::size_t(k)] = std::atan2(std::abs(cross), ux * wx + uy * wy);
    longest = std::max(longest, ux * ux + uy * uy);
  }
  shape = std::abs(cross) / longest;
  return angles;
}

// The 2D pass-over test: where it says every sin^2 of a triangle's interior
// angles exceeds the bound (one bound, or one for the acute angles and one
// for the obtuse), the angles computed in extended precision agree; on
// well-shaped triangles with bounds 1% below their smallest sin^2 of each
// kind it decides.
TEST_CASE("element_sines_squared_above for triangles: certain when true, and true for well-shaped elements",
          "[skewness][angles]")
{
  namespace si = spring_motion::internal;
  std::mt19937_64 rng(20261204);
  std::uniform_real_distribution<double> u(-1, 1);
  std::uniform_int_distribution<int> squash(0, 3);
  std::size_t said_true = 0, decided = 0, obtuse_ones = 0;
  for(int trial = 0; trial < 20000; ++trial) {
    const double f = std::pow(10.0, -2 * squash(rng));
    std::array<P2, 3> p;
    for(auto& q : p)
      q = {u(rng), f * u(rng)};
    // sizes far from 1 too: the products of lengths must not over- or underflow
    const double size = std::pow(10.0, double(int(rng() % 41) - 20));
    for(auto& q : p)
      for(auto& x : q)
        x *= size;
    long double shape = 0;
    const auto angles = extended_triangle_angles(p, shape);
    long double smallest = 1, acute = 1, obtuse = 1;
    bool has_obtuse = false;
    for(const long double a : angles) {
      const long double s2 = std::sin(a) * std::sin(a);
      smallest = std::min(smallest, s2);
      const bool is_acute = a < 1.5707963267948966192L;
      has_obtuse = has_obtuse || !is_acute;
      long double& m = is_acute ? acute : obtuse;
      m = std::min(m, s2);
    }
    obtuse_ones += has_obtuse;
    const bool well_shaped = shape >= 1e-5L;
    INFO("trial " << trial << ", smallest sin^2 " << double(smallest) << ", 2A / L^2 " << double(shape));
    check_one_bound<2>(p, smallest, well_shaped, said_true, decided);
    for(const double factor : bound_factors) {
      // each kind held to its own bound
      const double ab = double(acute) * factor, ob = double(obtuse) * factor;
      const bool kinds = si::element_sines_squared_above<2>(p, ab, ob);
      said_true += kinds;
      if(kinds) {
        CHECK(acute > ab);
        CHECK((!has_obtuse || obtuse > ob));
      }
      if(well_shaped && factor <= 0.99)
        CHECK(kinds);
    }
    // one kind's bound 1% above its smallest sin^2: never true, whatever
    // the other kind's (a test reading the kinds swapped would pass some)
    if(has_obtuse) {
      CHECK_FALSE(si::element_sines_squared_above<2>(p, double(acute) * 1.01, double(obtuse) * 0.5));
      CHECK_FALSE(si::element_sines_squared_above<2>(p, double(acute) * 0.5, double(obtuse) * 1.01));
    }
  }
  CHECK(obtuse_ones > 5000);
  CHECK(said_true > 20000);
  CHECK(decided > 10000);
  // the right isosceles triangle: sin^2 1 (the dot product exactly 0) and 1/2
  const std::array<P2, 3> corner{{{0, 0}, {1, 0}, {0, 1}}};
  CHECK(si::element_sines_squared_above<2>(corner, 0.49));
  CHECK_FALSE(si::element_sines_squared_above<2>(corner, 0.51));
  CHECK(si::element_sines_squared_above<2>(corner, 0.49, 0.99));
  CHECK_FALSE(si::element_sines_squared_above<2>(corner, 0.49, 1.0)); // a right angle is not above 1
  // flat, coincident and non-finite corners: never passed over
  const double inf = std::numeric_limits<double>::infinity();
  for(const std::array<P2, 3>& bad : {std::array<P2, 3>{{{0, 0}, {1, 0}, {2, 0}}},
                                      std::array<P2, 3>{{{0, 0}, {0, 0}, {0, 1}}},
                                      std::array<P2, 3>{{{0, 0}, {1, 0}, {0, std::nan("")}}},
                                      std::array<P2, 3>{{{0, 0}, {1, 0}, {0, inf}}}}) {
    CHECK_FALSE(si::element_sines_squared_above<2>(bad, 0));
    CHECK_FALSE(si::element_sines_squared_above<2>(bad, 0, 0));
  }
}

// Quality_extremes::add_element on jittered lattices of triangles with a
// needle, an obtuse triangle, a flat one among them, and copies of the
// extreme elements moved by rounding-sized amounts: the same numbers as
// add() of every element, bitwise, with most elements passed over, with and
// without a guess of the extremes.
TEST_CASE("Quality_extremes::add_element in 2D: add()'s numbers bitwise, most elements passed over",
          "[skewness][angles]")
{
  namespace si = spring_motion::internal;
  using Tri = std::array<P2, 3>;
  std::mt19937_64 rng(202612042);
  std::uniform_real_distribution<double> u(-1, 1);
  std::size_t passed = 0, total = 0, guessed_passed = 0;
  for(int set = 0; set < 40; ++set) {
    const int n = 6 + set % 5;
    const double jitter = set % 2 == 1 ? 0.01 : 0.05 + 0.3 * double(set % 5) / 4;
    std::vector<P2> grid;
    for(int y = 0; y <= n; ++y)
      for(int x = 0; x <= n; ++x)
        grid.push_back({x + jitter * u(rng), y + jitter * u(rng)});
    const auto at = [&](int x, int y) { return grid[std::size_t(y * (n + 1) + x)]; };
    std::vector<Tri> tris;
    for(int y = 0; y < n; ++y)
      for(int x = 0; x < n; ++x) {
        tris.push_back({at(x, y), at(x + 1, y), at(x + 1, y + 1)});
        tris.push_back({at(x, y), at(x + 1, y + 1), at(x, y + 1)});
      }
    // a needle (its smallest angle decides the minimum) or an obtuse
    // triangle (its largest decides R), and a flat one
    for(int i = 0; i < 2; ++i) {
      Tri t = tris[rng() % tris.size()];
      if(i == 0 && set % 2 == 0)
        t[2] = {t[0][0] + 30, t[0][1] + 0.5};
      else if(i == 0)
        t[2] = {(t[0][0] + t[1][0]) / 2 + 0.01 * u(rng), (t[0][1] + t[1][1]) / 2 + 0.05};
      else if(set % 10 == 3)
        t[2] = t[0];
      tris.insert(tris.begin() + long(rng() % tris.size()), t);
    }
    add_rounded_copies<2>(tris, rng);
    INFO("set " << set << ", " << tris.size() << " elements, jitter " << jitter);
    check_pass_over<2>(tris, rng() % tris.size(), passed, guessed_passed);
    total += tris.size();
  }
  INFO("passed over: " << passed << " of " << total << " unguessed, " << guessed_passed << " guessed");
  CHECK(passed > total / 2);
  CHECK(guessed_passed > passed * 3);
}
