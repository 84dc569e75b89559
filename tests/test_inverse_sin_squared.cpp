// 1/sin^2 of the element angles without trigonometry
// (internal/geometry/angles.h), against the angles themselves, and the edge
// models that read it against the same models fed with angles.
#include <spring_motion/Spring_network.h>
#include <spring_motion/internal/geometry/angles.h>
#include <spring_motion/internal/geometry/capped_math.h>
#include <spring_motion/internal/solver/assemble.h>
#include <spring_motion/stiffness/Grid_scaled_stiffness.h>
#include <spring_motion/stiffness/With_ball_vertex.h>
#include <spring_motion/stiffness/Zeng_Ethier_semi_torsional_stiffness.h>

#include <catch2/catch.hpp>

#include <array>
#include <cmath>
#include <cstring>
#include <limits>
#include <random>
#include <vector>

using namespace spring_motion;
using namespace spring_motion::internal;

namespace {

using P2 = std::array<double, 2>;
using P3 = std::array<double, 3>;

bool close(double a, double b, double rel) { return std::abs(a - b) <= rel * std::abs(b); }

std::array<double, 3> by_angles(const P2& a, const P2& b, const P2& c)
{
  const auto t = triangle_angles<2>(a, b, c);
  return {inverse_sin_squared(t[0]), inverse_sin_squared(t[1]), inverse_sin_squared(t[2])};
}
std::array<double, 6> by_angles(const std::array<P3, 4>& p)
{
  const auto t = dihedral_angles(p);
  std::array<double, 6> r;
  for(std::size_t k = 0; k < 6; ++k)
    r[k] = inverse_sin_squared(t[k]);
  return r;
}

// An edge model that only takes angles: the assembly then computes angles
// and this forwards them to `Base`'s angle form.
template <class Base>
struct Angles_only
{
  Base base;
  Angle_kind angle_kind(int d) const { return base.angle_kind(d); }
  double operator()(double l, const double* a, std::size_t n, const Stiffness_context& c) const
  {
    return base(l, a, n, c);
  }
};

// The unit cube in six tetrahedra around its diagonal 0-7 (the first
// `count` of them), its corners moved at random by up to 0.15 (vertex i at
// the bits of i).
Spring_network<3> perturbed_cube(unsigned seed, std::size_t count = 6)
{
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> d(-0.15, 0.15);
  std::vector<P3> p;
  for(int i = 0; i < 8; ++i)
    p.push_back({(i & 1) + d(rng), ((i >> 1) & 1) + d(rng), ((i >> 2) & 1) + d(rng)});
  std::vector<std::array<Index, 4>> tets;
  const int axes[6][3] = {{1, 2, 4}, {1, 4, 2}, {2, 1, 4}, {2, 4, 1}, {4, 1, 2}, {4, 2, 1}};
  for(const auto& a : axes)
    tets.push_back({0, Index(a[0]), Index(a[0] + a[1]), 7});
  tets.resize(count);
  return internal::with_face_slots(make_spring_network<3>(p, tets)); // face-angle models read them
}

// Random tetrahedra at every scale, slivers, then the degenerate cases:
// flat, a collapsed edge, a point, one huge and one tiny corner offset.
std::vector<std::array<P3, 4>> varied_tetrahedra(std::mt19937& rng)
{
  std::uniform_real_distribution<double> d(-1, 1), scale(-150, 150);
  std::vector<std::array<P3, 4>> tets;
  for(int n = 0; n < 300; ++n) {
    const double s = std::pow(10.0, n % 3 == 0 ? scale(rng) : 0.0);
    std::array<P3, 4> p;
    for(auto& q : p)
      q = {s * d(rng), s * d(rng), s * d(rng)};
    tets.push_back(p);
  }
  for(double h : {1e-4, 1e-9, 0.0})
    tets.push_back({{{0, 0, 0}, {1, 0, h}, {1, 1, 0}, {0, 1, h}}});
  tets.push_back({{{0, 0, 0}, {1, 0, 0}, {1, 0, 0}, {0, 0, 1}}});
  tets.push_back({{{2, 2, 2}, {2, 2, 2}, {2, 2, 2}, {2, 2, 2}}});
  tets.push_back({{{0, 0, 0}, {1e150, 0, 0}, {0, 1e-150, 0}, {0, 0, 1}}});
  return tets;
}

template <class Model>
std::vector<double> stiffness(const Spring_network<3>& net, const Model& model)
{
  std::vector<double> k;
  internal::Stiffness_scratch<3> scratch;
  compute_edge_stiffness(net, net.points, model, Stiffness_context{3, net.longest_initial_edge}, k, scratch, 1);
  return k;
}

} // namespace

TEST_CASE("inverse sin^2: triangles agree with 1/sin^2 of their angles", "[stiffness][angles]")
{
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> d(-1, 1);
  for(int n = 0; n < 200; ++n) {
    const P2 a{d(rng), d(rng)}, b{d(rng), d(rng)}, c{d(rng), d(rng)};
    const auto fast = triangle_inverse_sin_squared<2>(a, b, c);
    const auto ref = by_angles(a, b, c);
    // an angle good to a few ulps gives 1/sin^2 to about ulp / sin^2
    for(std::size_t k = 0; k < 3; ++k)
      CHECK(close(fast[k], ref[k], 1e-12 * ref[k]));
    // the same triangle embedded in a tilted plane of 3D
    const auto in3 = [](const P2& q) { return P3{q[0], 0.6 * q[1], 0.8 * q[1]}; };
    const auto fast3 = triangle_inverse_sin_squared<3>(in3(a), in3(b), in3(c));
    for(std::size_t k = 0; k < 3; ++k)
      CHECK(close(fast3[k], ref[k], 1e-12 * ref[k]));
  }
}

TEST_CASE("inverse sin^2: tetrahedra agree with 1/sin^2 of their dihedral angles", "[stiffness][angles]")
{
  // the trirectangular corner by hand: right dihedral angles at the three
  // edges from the corner, cos^2 = 1/3 (1/sin^2 = 3/2) at the others
  const auto corner = dihedral_inverse_sin_squared({{{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}}});
  for(std::size_t k : {0, 1, 2})
    CHECK(close(corner[k], 1.0, 1e-15));
  for(std::size_t k : {3, 4, 5})
    CHECK(close(corner[k], 1.5, 1e-15));

  std::mt19937 rng(11);
  std::uniform_real_distribution<double> d(-1, 1);
  for(int n = 0; n < 200; ++n) {
    std::array<P3, 4> p;
    for(auto& q : p)
      q = {d(rng), d(rng), d(rng)};
    const auto fast = dihedral_inverse_sin_squared(p);
    const auto ref = by_angles(p);
    for(std::size_t k = 0; k < 6; ++k)
      CHECK(close(fast[k], ref[k], 1e-11 * ref[k]));
  }
}

TEST_CASE("inverse sin^2: scale-free from 1e-150 to 1e150, slivers, flat and collapsed elements",
          "[stiffness][angles]")
{
  const std::array<P3, 4> t{{{0.1, 0.2, 0.05}, {1.3, 0.1, -0.2}, {0.4, 1.1, 0.3}, {0.5, 0.4, 0.9}}};
  const auto unit = dihedral_inverse_sin_squared(t);
  for(double s : {1e-150, 1e150}) {
    std::array<P3, 4> q = t;
    for(auto& v : q)
      for(double& c : v)
        c *= s;
    const auto scaled = dihedral_inverse_sin_squared(q);
    for(std::size_t k = 0; k < 6; ++k)
      CHECK(close(scaled[k], unit[k], 1e-13));
    const auto tri = triangle_inverse_sin_squared<3>(q[0], q[1], q[2]);
    const auto tri1 = triangle_inverse_sin_squared<3>(t[0], t[1], t[2]);
    for(std::size_t k = 0; k < 3; ++k)
      CHECK(close(tri[k], tri1[k], 1e-13));
  }

  // a sliver: the four corners of a unit square, two of them lifted by h.
  // The dihedral angles at the diagonals 0-2 and 1-3 are close to pi, so
  // sin is about 2h / (1/sqrt 2)... measured against the trigonometric path,
  // both losing digits like 1/h
  for(double h : {1e-4, 1e-7}) {
    const std::array<P3, 4> s{{{0, 0, 0}, {1, 0, h}, {1, 1, 0}, {0, 1, h}}};
    const auto fast = dihedral_inverse_sin_squared(s);
    const auto ref = by_angles(s);
    for(std::size_t k = 0; k < 6; ++k)
      CHECK(close(fast[k], ref[k], 1e-14 / h));
    CHECK(fast[1] > 0.1 / (h * h)); // edge 0-2: nearly flat
  }

  // flat and collapsed: the cap of inverse_sin_squared, never inf or NaN
  const auto flat = dihedral_inverse_sin_squared({{{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {1, 1, 0}}});
  for(double v : flat)
    CHECK(v == 1e200);
  const auto point = dihedral_inverse_sin_squared({{{2, 2, 2}, {2, 2, 2}, {2, 2, 2}, {2, 2, 2}}});
  for(double v : point)
    CHECK(v == 1e200);
  const auto line = triangle_inverse_sin_squared<2>({0, 0}, {1, 1}, {3, 3});
  for(double v : line)
    CHECK(v == 1e200);
  const auto pair = triangle_inverse_sin_squared<2>({0, 0}, {0, 0}, {3, 1});
  for(double v : pair)
    CHECK(v == 1e200);
}

TEST_CASE("inverse sin^2: two tetrahedra at once give each one's values bitwise", "[stiffness][angles]")
{
  std::mt19937 rng(5);
  const auto tets = varied_tetrahedra(rng);
  const auto corners = [](const std::array<P3, 4>& p) {
    return std::array<const double*, 4>{p[0].data(), p[1].data(), p[2].data(), p[3].data()};
  };
  const auto same = [](const std::array<double, 6>& a, const std::array<double, 6>& b) {
    return std::memcmp(a.data(), b.data(), sizeof a) == 0;
  };
  std::uniform_int_distribution<std::size_t> any(0, tets.size() - 1);
  for(std::size_t i = 0; i < tets.size(); ++i) {
    const std::size_t j = i % 4 == 0 ? i : any(rng); // a tetrahedron with itself too
    INFO("tetrahedra " << i << " and " << j);
    const auto both = dihedral_inverse_sin_squared(corners(tets[i]), corners(tets[j]));
    CHECK(same(both[0], dihedral_inverse_sin_squared(tets[i])));
    CHECK(same(both[1], dihedral_inverse_sin_squared(tets[j])));
  }
}

TEST_CASE("inverse sin^2: four tetrahedra at once give each one's values bitwise", "[stiffness][angles]")
{
  if(!four_lanes_available()) {
    WARN("this processor has no AVX: the four-lane form is not used here, and not tested");
    return;
  }
#if SPRING_MOTION_HAS_DOUBLE_QUAD
  // the pair test's shapes, each in every lane
  std::mt19937 rng(7);
  const auto tets = varied_tetrahedra(rng);
  const auto corners = [](const std::array<P3, 4>& p) {
    return std::array<const double*, 4>{p[0].data(), p[1].data(), p[2].data(), p[3].data()};
  };
  std::uniform_int_distribution<std::size_t> any(0, tets.size() - 1);
  for(std::size_t i = 0; i < tets.size(); ++i) {
    // tetrahedron i in lane i % 4, the others at random (itself too)
    std::size_t in[4];
    for(std::size_t l = 0; l < 4; ++l)
      in[l] = l == i % 4 ? i : (i % 5 == 0 ? i : any(rng));
    const std::array<const double*, 4> t[4] = {corners(tets[in[0]]), corners(tets[in[1]]), corners(tets[in[2]]),
                                               corners(tets[in[3]])};
    double out[4][6];
    dihedral_inverse_sin_squared(t, out);
    for(std::size_t l = 0; l < 4; ++l) {
      INFO("tetrahedron " << in[l] << " in lane " << l);
      const auto one = dihedral_inverse_sin_squared(tets[in[l]]);
      CHECK(std::memcmp(out[l], one.data(), sizeof out[l]) == 0);
    }
  }
#endif
}

TEST_CASE("inverse sin^2: the 3D stiffness pass gives each tetrahedron's values bitwise, any count",
          "[stiffness][angles]")
{
  // the pass takes the tetrahedra four (AVX) or two at a time, the last
  // group filled with the last one: the grid-scaled stiffness of 1 to 6
  // tetrahedra against the same sums formed from one tetrahedron at a time
  for(std::size_t count = 1; count <= 6; ++count) {
    const auto net = perturbed_cube(unsigned(10 + count), count);
    const auto fast = stiffness(net, Grid_scaled_stiffness{});
    std::vector<std::vector<double>> sines(net.number_of_edges());
    for(std::size_t t = 0; t < net.number_of_elements(); ++t) {
      std::array<P3, 4> p;
      for(std::size_t v = 0; v < 4; ++v)
        p[v] = net.points[net.elements[t][v]];
      const auto s = dihedral_inverse_sin_squared(p);
      for(std::size_t q = 0; q < 6; ++q)
        sines[net.element_edges[t * 6 + q]].push_back(s[q]);
    }
    REQUIRE(fast.size() == sines.size());
    for(std::size_t e = 0; e < fast.size(); ++e) {
      INFO(count << " tetrahedra, edge " << e);
      const auto& ed = net.edges[e];
      const double ref =
          Grid_scaled_stiffness{}(distance<3>(net.points[ed[0]], net.points[ed[1]]),
                                  Inverse_sin_squared{sines[e].data(), sines[e].size()},
                                  Stiffness_context{3, net.longest_initial_edge});
      CHECK(std::memcmp(&fast[e], &ref, sizeof ref) == 0);
    }
  }
}

TEST_CASE("inverse sin^2: two triangles at once give each one's values bitwise", "[stiffness][angles]")
{
  std::mt19937 rng(6);
  std::uniform_real_distribution<double> d(-1, 1), scale(-150, 150);
  std::vector<std::array<P2, 3>> tris;
  for(int n = 0; n < 300; ++n) {
    const double s = std::pow(10.0, n % 3 == 0 ? scale(rng) : 0.0);
    tris.push_back({P2{s * d(rng), s * d(rng)}, P2{s * d(rng), s * d(rng)}, P2{s * d(rng), s * d(rng)}});
  }
  // flat, a collapsed edge, a point, a needle, mixed scales
  tris.push_back({P2{0, 0}, P2{1, 1}, P2{3, 3}});
  tris.push_back({P2{0, 0}, P2{0, 0}, P2{3, 1}});
  tris.push_back({P2{2, 2}, P2{2, 2}, P2{2, 2}});
  tris.push_back({P2{0, 0}, P2{1, 1e-9}, P2{2, 0}});
  tris.push_back({P2{0, 0}, P2{1e150, 0}, P2{0, 1e-150}});
  const auto corners = [](const std::array<P2, 3>& p) {
    return std::array<const double*, 3>{p[0].data(), p[1].data(), p[2].data()};
  };
  const auto same = [](const std::array<double, 3>& a, const std::array<double, 3>& b) {
    return std::memcmp(a.data(), b.data(), sizeof a) == 0;
  };
  std::uniform_int_distribution<std::size_t> any(0, tris.size() - 1);
  for(std::size_t i = 0; i < tris.size(); ++i) {
    const std::size_t j = i % 4 == 0 ? i : any(rng);
    INFO("triangles " << i << " and " << j);
    const auto both = triangle_inverse_sin_squared(corners(tris[i]), corners(tris[j]));
    CHECK(same(both[0], triangle_inverse_sin_squared<2>(tris[i][0], tris[i][1], tris[i][2])));
    CHECK(same(both[1], triangle_inverse_sin_squared<2>(tris[j][0], tris[j][1], tris[j][2])));
  }
}

TEST_CASE("inverse sin^2: the 2D stiffness pass, triangles two at a time, odd counts too", "[stiffness][angles]")
{
  // a fan of n triangles around the origin, corners moved at random: the
  // grid-scaled stiffness from 1/sin^2 (the pass's pairs) against the same
  // model fed with angles (one triangle at a time)
  for(std::size_t n : {std::size_t(3), std::size_t(5), std::size_t(6)}) {
    std::mt19937 rng{unsigned(n)};
    std::uniform_real_distribution<double> d(-0.1, 0.1);
    std::vector<P2> p{{d(rng), d(rng)}};
    std::vector<std::array<Index, 3>> tris;
    for(std::size_t k = 0; k < n; ++k) {
      const double t = 2 * std::acos(-1.0) * double(k) / double(n);
      p.push_back({std::cos(t) + d(rng), std::sin(t) + d(rng)});
      tris.push_back({0, Index(1 + k), Index(1 + (k + 1) % n)});
    }
    const auto net = make_spring_network<2>(p, tris);
    const auto run = [&](const auto& model) {
      std::vector<double> k;
      internal::Stiffness_scratch<2> scratch;
      compute_edge_stiffness(net, net.points, model, Stiffness_context{2, net.longest_initial_edge}, k, scratch, 1);
      return k;
    };
    const auto fast = run(Grid_scaled_stiffness{});
    const auto ref = run(Angles_only<Grid_scaled_stiffness>{Grid_scaled_stiffness{}});
    REQUIRE(fast.size() == ref.size());
    for(std::size_t e = 0; e < fast.size(); ++e) {
      INFO(n << " triangles, edge " << e);
      CHECK(close(fast[e], ref[e], 1e-11)); // (sum 1/sin^2)^4
    }
  }
}

TEST_CASE("inverse sin^2: the models that read it give the stiffness of their angle form", "[stiffness][angles]")
{
  static_assert(Reads_inverse_sin_squared<Grid_scaled_stiffness>::value, "");
  static_assert(Reads_inverse_sin_squared<Zeng_Ethier_semi_torsional_stiffness>::value, "");
  static_assert(Reads_inverse_sin_squared<With_ball_vertex<Grid_scaled_stiffness>>::value, "");
  static_assert(!Reads_inverse_sin_squared<Angles_only<Grid_scaled_stiffness>>::value, "");
  // five tetrahedra: the stiffness pass takes them in pairs, the last alone
  for(unsigned seed : {1u, 2u, 3u, 4u}) {
    const auto net = perturbed_cube(seed, seed == 4 ? 5 : 6);
    const auto check = [&](const auto& model, double rel) {
      const auto fast = stiffness(net, model);
      const auto ref = stiffness(net, Angles_only<std::decay_t<decltype(model)>>{model});
      REQUIRE(fast.size() == ref.size());
      for(std::size_t e = 0; e < fast.size(); ++e)
        CHECK(close(fast[e], ref[e], rel));
    };
    // (sum 1/sin^2)^3 triples the relative error of the sum
    check(Grid_scaled_stiffness{}, 1e-11);
    check(Zeng_Ethier_semi_torsional_stiffness{}, 1e-12);
    check(Zeng_Ethier_semi_torsional_stiffness{Angle_kind::element}, 1e-12);
  }
}

TEST_CASE("inverse sin^2: the assembly's per-step edge function gives each model's stiffness bitwise",
          "[stiffness][angles]")
{
  // the grid-scaled formula written from the capped operations, apart from
  // the model's own code and the per-step form's
  const auto formula = [](double alpha, double beta, double reference, double l0, double length, double s) {
    return capped_product(capped_quotient(l0, length),
                          capped_pow(length / reference, -alpha) + capped_pow(s, beta));
  };
  std::mt19937 rng(11);
  // most values in a mesh's range, every fifth trial's anywhere up to the cap
  std::uniform_real_distribution<double> exponent(-6, 6), wide(-250, 250);
  std::uniform_int_distribution<int> how_many(1, 10);
  std::vector<double> values(10 + Inverse_sin_squared::padded_size, 1.0);
  const auto same = [](double a, double b) { return std::memcmp(&a, &b, sizeof a) == 0; };
  int checked = 0;
  for(int dimension : {2, 3})
    for(const auto& parameters : {std::array<double, 3>{0, 0, 1}, std::array<double, 3>{1.5, 2, 1e-3},
                                  std::array<double, 3>{3, 0.5, 1000}}) {
      Grid_scaled_stiffness model;
      if(parameters[0] > 0) {
        model.alpha = parameters[0];
        model.beta = parameters[1];
      }
      model.reference_length = parameters[2];
      const With_ball_vertex<Grid_scaled_stiffness> combined{model, {}};
      const Zeng_Ethier_semi_torsional_stiffness other;
      const Stiffness_context ctx{dimension, std::pow(10.0, exponent(rng))};
      const Edge_function<Grid_scaled_stiffness> f(model, ctx);
      const Edge_function<With_ball_vertex<Grid_scaled_stiffness>> g(combined, ctx);
      const Edge_function<Zeng_Ethier_semi_torsional_stiffness> h(other, ctx);
      for(int trial = 0; trial < 500; ++trial) {
        auto& range = trial % 5 == 0 ? wide : exponent;
        const std::size_t n = std::size_t(how_many(rng));
        for(std::size_t m = 0; m < n; ++m)
          values[m] = 1 + std::pow(10.0, range(rng));
        const Inverse_sin_squared angles{values.data(), n, values.size()};
        const double length = std::pow(10.0, range(rng));
        const double expected = formula(model.alpha_for(dimension), model.beta_for(dimension),
                                        model.reference_length, ctx.longest_initial_edge, length, angles.sum());
        INFO("dimension " << dimension << " alpha " << model.alpha_for(dimension) << " length " << length);
        CHECK(same(model(length, angles, ctx), expected));
        CHECK(same(f(length, angles), expected));
        CHECK(same(g(length, angles), expected));
        CHECK(same(h(length, angles), other(length, angles, ctx)));
        ++checked;
      }
    }
  CHECK(checked == 2 * 3 * 500);
}

TEST_CASE("inverse sin^2: sum() adds the values in order, bitwise, whatever follows them", "[stiffness][angles]")
{
  // values of every size the branch-free path takes (0..8) and more, then
  // padding that must not count: NaN, infinities, huge and negative values
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> exponent(-300, 200);
  const double junk[] = {std::numeric_limits<double>::quiet_NaN(), std::numeric_limits<double>::infinity(),
                         -std::numeric_limits<double>::infinity(), -1e300, 1e300, -0.0};
  int checked = 0;
  for(std::size_t size = 0; size <= 12; ++size)
    for(double fill : junk)
      for(int trial = 0; trial < 20; ++trial) {
        std::vector<double> v(size + Inverse_sin_squared::padded_size, fill);
        for(std::size_t m = 0; m < size; ++m)
          v[m] = std::pow(10.0, exponent(rng)); // sums that round
        for(double start : {0.0, 1.5, 1e200, std::pow(10.0, exponent(rng))}) {
          double expected = start;
          for(std::size_t m = 0; m < size; ++m)
            expected += v[m];
          // readable: none said, exactly the values, the padded width, all
          for(std::size_t readable : {std::size_t(0), size, Inverse_sin_squared::padded_size, v.size()}) {
            const double s = Inverse_sin_squared{v.data(), size, readable}.sum(start);
            INFO("size " << size << " readable " << readable << " fill " << fill << " start " << start);
            CHECK(std::memcmp(&s, &expected, sizeof s) == 0);
            ++checked;
          }
        }
      }
  CHECK(checked == 13 * 6 * 20 * 4 * 4);
  // a NaN start stays NaN (the models' check then reports the edge)
  const std::vector<double> v(Inverse_sin_squared::padded_size, 1.0);
  CHECK(std::isnan(Inverse_sin_squared{v.data(), 3, v.size()}.sum(std::numeric_limits<double>::quiet_NaN())));
}
