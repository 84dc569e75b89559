// A motion computed with 1 and with 2 threads must agree bit for bit: every
// parallel loop either writes disjoint entries (elements, edges, rows of one
// colour) or reduces over fixed chunks in a fixed order.
// Every loop over at least one item takes the parallel path, so that the
// small test meshes exercise it (the library's default cut-off is 16384).
#define SPRING_MOTION_PARALLEL_THRESHOLD 1
#include <spring_motion/spring_motion.h>
#include <spring_motion/internal/solver/free_system.h>
#include <spring_motion/internal/solver/threads.h>

#include "test_meshes.h"

#include <catch2/catch.hpp>

#include <algorithm>
#include <cstring>
#include <limits>
#include <map>
#include <numeric>
#include <random>
#include <stdexcept>
#include <string>
#include <tuple>
#include <type_traits>
#include <utility>
#include <vector>

using namespace spring_motion;
using namespace spring_motion_test;

namespace {

static_assert(internal::parallel_threshold == 1, "the parallel paths must be taken");

bool same_bits(double a, double b) { return std::memcmp(&a, &b, sizeof a) == 0; }

template <int D>
void require_identical(const Network_deformer<D>& a, const Deform_report& ra, const Network_deformer<D>& b,
                       const Deform_report& rb)
{
  REQUIRE(ra.completed == rb.completed);
  REQUIRE(ra.steps.size() == rb.steps.size());
  for(std::size_t i = 0; i < ra.steps.size(); ++i) {
    const auto& s = ra.steps[i];
    const auto& t = rb.steps[i];
    INFO("step " << s.step);
    CHECK(s.iterations == t.iterations);
    CHECK(same_bits(s.max_update, t.max_update));
    CHECK(same_bits(s.residual, t.residual));
    CHECK(same_bits(s.error_estimate, t.error_estimate));
    CHECK(same_bits(s.max_skewness_all, t.max_skewness_all));
    CHECK(same_bits(s.min_size_ratio, t.min_size_ratio));
  }
  CHECK(same_bits(ra.min_size_ratio, rb.min_size_ratio));
  std::size_t differing = 0;
  for(std::size_t i = 0; i < a.positions().size(); ++i)
    for(int c = 0; c < D; ++c)
      differing += !same_bits(a.positions()[i][c], b.positions()[i][c]);
  CHECK(differing == 0);
}

template <int D, class Motion, class Model = Grid_scaled_stiffness>
void compare_threads(const Spring_network<D>& net, const std::vector<Vertex_role>& roles, const Motion& motion,
                     Solver_options solver, std::size_t steps, const Model& model = {})
{
  Deform_options options;
  options.number_of_steps = steps;
  options.solver = solver;
  options.solver.threads = 1;
  Network_deformer<D> one(net, roles);
  const auto r1 = one.run(motion, model, options);
  options.solver.threads = 2;
  Network_deformer<D> two(net, roles);
  const auto r2 = two.run(motion, model, options);
  REQUIRE(r1.steps.size() == steps); // the runs did move the mesh
  REQUIRE(r1.steps.back().iterations > 0);
  require_identical(one, r1, two, r2);
}

// The unit cube in n^3 cubes of 6 tetrahedra, the centre cube removed and
// its 8 corners moving.
Spring_network<3> small_box(std::size_t n)
{
  const std::size_t M = n + 1, mid = n / 2;
  std::vector<std::array<double, 3>> points;
  for(std::size_t k = 0; k < M; ++k)
    for(std::size_t j = 0; j < M; ++j)
      for(std::size_t i = 0; i < M; ++i)
        points.push_back({double(i) / double(n), double(j) / double(n), double(k) / double(n)});
  auto id = [&](std::size_t i, std::size_t j, std::size_t k) { return Index((k * M + j) * M + i); };
  const int perms[6][3] = {{0, 1, 2}, {0, 2, 1}, {1, 0, 2}, {1, 2, 0}, {2, 0, 1}, {2, 1, 0}};
  std::vector<std::array<Index, 4>> tets;
  for(std::size_t k = 0; k < n; ++k)
    for(std::size_t j = 0; j < n; ++j)
      for(std::size_t i = 0; i < n; ++i) {
        if(i == mid && j == mid && k == mid)
          continue;
        for(const auto& p : perms) {
          std::array<std::size_t, 3> v{i, j, k};
          std::array<Index, 4> t;
          t[0] = id(v[0], v[1], v[2]);
          for(int s = 0; s < 3; ++s) {
            ++v[std::size_t(p[s])];
            t[std::size_t(s) + 1] = id(v[0], v[1], v[2]);
          }
          tets.push_back(t);
        }
      }
  return make_spring_network<3>(std::move(points), std::move(tets));
}

// Lineal springs acting along their edges and no element matrix: a 3D block
// system (Edge_spring_form::along_edge).
struct Truss_3
{
  Angle_kind angle_kind(int) const { return Angle_kind::none; }
  double operator()(double l, const double*, std::size_t, const Stiffness_context&) const { return 1.0 / l; }
  void add_element_matrix(const std::array<std::array<double, 3>, 4>&, double*) const {}
  Edge_spring_form edge_spring_form() const { return Edge_spring_form::along_edge; }
};

// An element model that fails on some elements only: it throws on
// elements whose centroid lies right of x = 0.62, and gives an infinite
// entry on those above y = 0.71.
struct Partly_bad_element_model
{
  Angle_kind angle_kind(int) const { return Angle_kind::none; }
  double operator()(double, const double*, std::size_t, const Stiffness_context&) const { return 1.0; }
  void add_element_matrix(const std::array<std::array<double, 2>, 3>& p, double* K) const
  {
    const double x = (p[0][0] + p[1][0] + p[2][0]) / 3, y = (p[0][1] + p[1][1] + p[2][1]) / 3;
    if(x > 0.62)
      throw std::runtime_error("poisoned element at " + std::to_string(x) + ", " + std::to_string(y));
    K[0] += y > 0.71 ? std::numeric_limits<double>::infinity() : 1.0;
  }
};

} // namespace

TEST_CASE("thread determinism: of several failing element matrices, the first in element order is reported",
          "[determinism][errors]")
{
  // element matrices are added colour by colour in parallel; the error must
  // be the one a loop over the elements in order meets first
  const int n = 12;
  Indexed_mesh<2> grid;
  for(int j = 0; j <= n; ++j)
    for(int i = 0; i <= n; ++i)
      grid.points.push_back({double(i) / n, double(j) / n});
  // the elements in a scrambled order, so that element order, colour order
  // and position disagree
  std::vector<std::array<Index, 3>> elements;
  for(int j = 0; j < n; ++j)
    for(int i = 0; i < n; ++i) {
      const Index a = Index(j * (n + 1) + i), b = a + 1, c = a + Index(n + 1), d = c + 1;
      elements.push_back({a, b, d});
      elements.push_back({a, d, c});
    }
  for(std::size_t k = 0; k < elements.size(); ++k)
    grid.elements.push_back(elements[(k * 37) % elements.size()]);
  std::string expected;
  for(std::size_t t = 0; t < grid.elements.size() && expected.empty(); ++t) {
    const auto& e = grid.elements[t];
    const auto& p = grid.points;
    const double x = (p[e[0]][0] + p[e[1]][0] + p[e[2]][0]) / 3, y = (p[e[0]][1] + p[e[1]][1] + p[e[2]][1]) / 3;
    if(x > 0.62)
      expected = "poisoned element at " + std::to_string(x) + ", " + std::to_string(y);
    else if(y > 0.71)
      expected = "element stiffness of element " + std::to_string(t) + " is not finite";
  }
  REQUIRE(!expected.empty());
  const Index centre = Index((n / 2) * (n + 1) + n / 2);
  auto roles = [&](const Vertex_info<2>& v) {
    return v.index == centre ? Vertex_role::moving : (v.on_boundary ? Vertex_role::fixed : Vertex_role::free);
  };
  for(int threads : {1, 2}) {
    INFO(threads << " thread(s)");
    Deform_options options;
    options.solver.threads = threads;
    REQUIRE_THROWS_WITH(deform(grid, roles, Translation_motion<2>{{0.01, 0}}, Partly_bad_element_model{}, options),
                        Catch::Contains(expected));
  }
}

TEST_CASE("thread determinism: 2D NACA0012 pitch, default solver and SOR, 1 vs 2 threads bitwise",
          "[determinism]")
{
  const auto [net, roles] = naca0012_network();
  const Pitch_motion<2> motion(20, {0.25, 0.0});
  SECTION("default solver") { compare_threads(net, roles, motion, Solver_options{}, 5); }
  SECTION("SOR (the paper's solver)") { compare_threads(net, roles, motion, Solver_options::paper(), 2); }
  SECTION("conjugate gradients + symmetric Gauss-Seidel")
  {
    Solver_options o;
    o.preconditioner = Preconditioner::symmetric_gauss_seidel;
    compare_threads(net, roles, motion, o, 3);
  }
  SECTION("torsional springs (block system), default solver")
  {
    compare_threads(net, roles, motion, Solver_options{}, 2, Torsional_stiffness{});
  }
  SECTION("ball-vertex springs k = 1/h^2 (block system, rigid-body multigrid), default solver")
  {
    compare_threads(net, roles, motion, Solver_options{}, 3, Ball_vertex_stiffness{2.0});
  }
  SECTION("torsional springs (block system), SOR")
  {
    compare_threads(net, roles, motion, Solver_options::paper(), 2, Torsional_stiffness{});
  }
  SECTION("torsional springs (block system), conjugate gradients + symmetric Gauss-Seidel, point multicolour")
  {
    Solver_options o;
    o.preconditioner = Preconditioner::symmetric_gauss_seidel;
    o.ordering = Vertex_ordering::multicolour;
    compare_threads(net, roles, motion, o, 2, Torsional_stiffness{});
  }
  SECTION("default solver, point multicolour ordering")
  {
    Solver_options o;
    o.ordering = Vertex_ordering::multicolour;
    compare_threads(net, roles, motion, o, 3);
  }
}

TEST_CASE("thread determinism: 3D structured box, default solver and SOR, 1 vs 2 threads bitwise",
          "[determinism]")
{
  const auto net = small_box(6);
  const auto roles = assign_roles(net, moving_boundary_where([](const std::array<double, 3>& p) {
                                    for(double c : p)
                                      if(c < 1e-9 || c > 1 - 1e-9)
                                        return false;
                                    return true;
                                  }));
  Pitch_motion<3> motion(10, {0.5, 0.5, 0.5});
  motion.axis = {0, 0, 1};
  SECTION("default solver") { compare_threads(net, roles, motion, Solver_options{}, 3); }
  SECTION("SOR") { compare_threads(net, roles, motion, Solver_options::paper(), 2); }
  SECTION("3x3-block system (springs along their edges), default solver")
  {
    compare_threads(net, roles, motion, Solver_options{}, 2, Truss_3{});
  }
  SECTION("ball-vertex springs k = 1/h^2 (3x3 blocks, rigid-body multigrid), default solver")
  {
    compare_threads(net, roles, motion, Solver_options{}, 2, Ball_vertex_stiffness{2.0});
  }
}

TEST_CASE("thread determinism: the element chunks of a colour share no free vertex, and cover every element once",
          "[determinism][block]")
{
  // 10368 tetrahedra: about twenty chunks, several per colour
  const auto net = small_box(12);
  const auto roles = assign_roles(net, moving_boundary_where([](const std::array<double, 3>& p) {
                                    return std::abs(p[0] - 0.5) < 0.2 && std::abs(p[1] - 0.5) < 0.2 &&
                                           std::abs(p[2] - 0.5) < 0.2;
                                  }));
  std::vector<Index> free;
  for(Index v = 0; v < net.number_of_vertices(); ++v)
    if(roles[v] == Vertex_role::free)
      free.push_back(v);
  internal::Free_system<3> fs;
  fs.build(net, free, true, Solver_options{});
  const auto& elements = fs.assembled_elements();
  const auto& chunks = fs.element_chunks();
  const auto& colours = fs.element_colours();
  REQUIRE(chunks.front() == 0);
  REQUIRE(chunks.back() == elements.size());
  REQUIRE(colours.back() + 1 == chunks.size());
  std::vector<Index> sorted = elements;
  std::sort(sorted.begin(), sorted.end());
  for(std::size_t t = 0; t < sorted.size(); ++t)
    REQUIRE(sorted[t] == t);
  REQUIRE(sorted.size() == net.number_of_elements());
  std::size_t most = 0; // chunks in the largest colour
  std::vector<std::size_t> owner(net.number_of_vertices()); // chunk + 1 that last touched a vertex, this colour
  for(std::size_t c = 0; c + 1 < colours.size(); ++c) {
    std::fill(owner.begin(), owner.end(), 0);
    most = std::max(most, std::size_t(colours[c + 1] - colours[c]));
    for(Index h = colours[c]; h < colours[c + 1]; ++h)
      for(Index s = chunks[h]; s < chunks[h + 1]; ++s) {
        const Index t = elements[s];
        CHECK(fs.assembled_element_vertices()[s] == net.elements[t]);
        for(Index v : net.elements[t]) {
          if(roles[v] != Vertex_role::free)
            continue;
          INFO("colour " << c << ", chunk " << h << ", vertex " << v);
          CHECK((owner[v] == 0 || owner[v] == h + 1));
          owner[v] = h + 1;
        }
      }
  }
  CHECK(most >= 2);
  // and the assembly over those chunks, 1 vs 2 threads
  Pitch_motion<3> motion(10, {0.5, 0.5, 0.5});
  compare_threads(net, roles, motion, Solver_options{}, 1, Ball_vertex_stiffness{2.0});
}

TEST_CASE("thread determinism: check_input_mesh finds the problems a direct search finds, on 1 and 2 threads",
          "[threads][validity][check]")
{
  auto mesh = kuhn_grid<3>(5);
  // plant problems: an interior vertex pushed through a neighbour (inverted
  // and overlapping elements), a flat element, a facet in three elements
  mesh.points[std::size_t(1 + 6 + 36)] = {1.0, 1.0, 2.6};
  mesh.elements.push_back({0, 1, 6, 7}); // four corners of the face z = 0
  mesh.elements.push_back(mesh.elements[7]);
  std::swap(mesh.elements.back()[0], mesh.elements.back()[1]);
  const auto orient = [&](std::array<Index, 4> v) {
    std::array<std::array<double, 3>, 4> p;
    for(int k = 0; k < 4; ++k)
      p[std::size_t(k)] = mesh.points[v[std::size_t(k)]];
    return internal::exact_orientation(p);
  };
  // the reference: every facet's elements by a map, each pair's apexes tested directly
  std::map<std::array<Index, 3>, std::vector<std::pair<std::size_t, Index>>> around; // element, apex
  std::vector<int> sign;
  for(std::size_t t = 0; t < mesh.elements.size(); ++t) {
    sign.push_back(orient(mesh.elements[t]));
    for(int k = 0; k < 4; ++k) {
      std::array<Index, 3> f;
      for(int c = 0, j = 0; c < 4; ++c)
        if(c != k)
          f[std::size_t(j++)] = mesh.elements[t][std::size_t(c)];
      std::sort(f.begin(), f.end());
      around[f].push_back({t, mesh.elements[t][std::size_t(k)]});
    }
  }
  const long positive = std::count(sign.begin(), sign.end(), 1), negative = std::count(sign.begin(), sign.end(), -1);
  const int majority = positive >= negative ? 1 : -1;
  std::vector<std::size_t> degenerate, mixed, overlapping, non_manifold;
  std::size_t non_manifold_facets = 0;
  for(std::size_t t = 0; t < sign.size(); ++t) {
    if(sign[t] == 0)
      degenerate.push_back(t);
    if(sign[t] == -majority)
      mixed.push_back(t);
  }
  for(const auto& [f, els] : around) {
    if(els.size() > 2) {
      ++non_manifold_facets;
      for(const auto& e : els)
        non_manifold.push_back(e.first);
    } else if(els.size() == 2 && sign[els[0].first] != 0 && sign[els[1].first] != 0 &&
              orient({f[0], f[1], f[2], els[0].second}) * orient({f[0], f[1], f[2], els[1].second}) >= 0) {
      const bool a_odd = sign[els[0].first] != majority, b_odd = sign[els[1].first] != majority;
      if(a_odd || !b_odd)
        overlapping.push_back(els[0].first);
      if(b_odd || !a_odd)
        overlapping.push_back(els[1].first);
    }
  }
  for(auto* list : {&overlapping, &non_manifold}) {
    std::sort(list->begin(), list->end());
    list->erase(std::unique(list->begin(), list->end()), list->end());
  }
  // the planted problems are there (else this test shows little)
  REQUIRE(degenerate.size() >= 1);
  REQUIRE(overlapping.size() >= 2);
  REQUIRE(non_manifold_facets >= 1);
  for(int threads : {1, 2}) {
    INFO("threads " << threads);
    std::vector<signed char> s;
    const auto p = internal::check_input_mesh<3>(mesh.points, mesh.elements, s, threads);
    CHECK(std::equal(s.begin(), s.end(), sign.begin(), sign.end()));
    CHECK(p.positive == std::size_t(positive));
    CHECK(p.negative == std::size_t(negative));
    CHECK(p.degenerate == degenerate);
    CHECK(p.mixed_orientation == mixed);
    CHECK(p.overlapping == overlapping);
    CHECK(p.non_manifold == non_manifold);
    CHECK(p.non_manifold_facets == non_manifold_facets);
  }
}

TEST_CASE("morton_code: bit b of coordinate c is bit D * b + c", "[network]")
{
  // the definition, bit by bit
  const auto reference = [](const auto& q) {
    constexpr int D = int(std::tuple_size<std::decay_t<decltype(q)>>::value);
    constexpr int bits = D == 3 ? 21 : 32;
    std::uint64_t code = 0;
    for(int b = 0; b < bits; ++b)
      for(int c = 0; c < D; ++c)
        code |= std::uint64_t((q[std::size_t(c)] >> b) & 1u) << (D * b + c);
    return code;
  };
  std::mt19937 rng(7);
  std::size_t same2 = 0, same3 = 0;
  const std::size_t count = 100000;
  for(std::size_t i = 0; i < count; ++i) {
    // full 32-bit words: in 3D the bits above 21 must be left out
    const std::array<std::uint32_t, 2> q2{std::uint32_t(rng()), std::uint32_t(rng())};
    const std::array<std::uint32_t, 3> q3{std::uint32_t(rng()), std::uint32_t(rng()), std::uint32_t(rng())};
    same2 += internal::morton_code<2>(q2) == reference(q2);
    same3 += internal::morton_code<3>(q3) == reference(q3);
  }
  CHECK(same2 == count);
  CHECK(same3 == count);
  CHECK(internal::morton_code<3>({0x1fffff, 0x1fffff, 0x1fffff}) == 0x7fffffffffffffffULL);
  CHECK(internal::morton_code<2>({0xffffffffu, 0}) == 0x5555555555555555ULL);
}

TEST_CASE("group_slots: the order of a stable sort of the slots by key", "[network]")
{
  // keys skewed towards a few values, some keys never used
  std::mt19937 rng(11);
  const std::size_t m = 500, keys = 97;
  std::vector<std::array<std::uint32_t, 3>> key(m);
  for(auto& k : key)
    for(auto& c : k)
      c = std::uint32_t(rng() % 3 == 0 ? rng() % 5 : rng() % keys);
  std::vector<std::uint32_t> start, values;
  internal::group_slots<3>(
      m, keys, [&](std::size_t t, std::size_t f) { return key[t][f]; },
      [&](std::size_t t, std::size_t f) { return std::pair{key[t][f], std::uint32_t(t * 3 + f)}; }, start, values);
  std::vector<std::uint32_t> expected(3 * m);
  std::iota(expected.begin(), expected.end(), 0u);
  std::stable_sort(expected.begin(), expected.end(),
                   [&](std::uint32_t a, std::uint32_t b) { return key[a / 3][a % 3] < key[b / 3][b % 3]; });
  CHECK(values == expected);
  REQUIRE(start.size() == keys + 1);
  std::size_t right_group = 0;
  for(std::size_t k = 0; k < keys; ++k)
    for(std::uint32_t i = start[k]; i < start[k + 1]; ++i)
      right_group += key[values[i] / 3][values[i] % 3] == k;
  CHECK(start.back() == 3 * m);
  CHECK(right_group == 3 * m);
}

TEST_CASE("Group_counter: counts and distinct values of each group, as a map gives them", "[network]")
{
  std::mt19937 rng(12);
  internal::Group_counter counter(40);
  std::size_t wrong = 0;
  for(int g = 0; g < 200; ++g) {
    counter.start_group();
    std::map<std::uint32_t, std::uint32_t> count;
    const int size = int(rng() % 30);
    for(int i = 0; i < size; ++i) {
      const std::uint32_t v = std::uint32_t(rng() % 40);
      wrong += counter.add(v) != count[v]++; // the number of v met before in this group
    }
    std::vector<std::uint32_t> distinct;
    for(const auto& [v, c] : count) {
      distinct.push_back(v);
      wrong += counter.count(v) != c;
    }
    wrong += counter.sorted_distinct() != distinct;
  }
  CHECK(wrong == 0);
}

// How many records of sorted_faces(elements, local) stand where a
// comparison sort of all of them by (vertices, slot) puts them, and how many
// there are.
template <class Elements, class Local>
std::pair<std::size_t, std::size_t> faces_in_comparison_order(const Elements& elements, const Local& local,
                                                               std::size_t number_of_vertices)
{
  constexpr int K = int(std::tuple_size<std::decay_t<decltype(local[0])>>::value);
  const std::size_t F = local.size();
  const auto got = internal::sorted_faces<K>(elements, local, number_of_vertices);
  std::vector<std::pair<std::array<std::uint32_t, K>, std::uint32_t>> expected;
  for(std::size_t t = 0; t < elements.size(); ++t)
    for(std::size_t f = 0; f < F; ++f) {
      std::array<std::uint32_t, K> v;
      for(int c = 0; c < K; ++c)
        v[std::size_t(c)] = std::uint32_t(elements[t][std::size_t(local[f][std::size_t(c)])]);
      std::sort(v.begin(), v.end());
      expected.push_back({v, std::uint32_t(t * F + f)});
    }
  std::sort(expected.begin(), expected.end());
  REQUIRE(got.size() == expected.size());
  std::size_t same = 0;
  for(std::size_t r = 0; r < got.size(); ++r)
    same += got[r].vertices == expected[r].first && got[r].slot == expected[r].second;
  return {same, got.size()};
}

TEST_CASE("sorted_faces: the order of a comparison sort of all the records", "[threads][network]")
{
  auto mesh = kuhn_grid<3>(4);
  // a scattered element order, so that the counting sort's runs start unsorted
  std::reverse(mesh.elements.begin(), mesh.elements.end());
  std::rotate(mesh.elements.begin(), mesh.elements.begin() + 37, mesh.elements.end());
  for(const auto& [same, all] : {faces_in_comparison_order(mesh.elements, internal::Simplex_tables<3>::edge,
                                                           mesh.points.size()),
                                 faces_in_comparison_order(mesh.elements, internal::Simplex_tables<3>::facet,
                                                           mesh.points.size())})
    CHECK(same == all);
}

TEST_CASE("sorted_faces: a vertex with a long run of faces", "[threads][network]")
{
  // A fan of triangles around vertex 0: its run holds two edges of every
  // triangle, longer than an insertion sort is given, the other runs a few
  // records each; both kinds must come out in the order of (vertices, slot).
  const std::uint32_t fan = 300;
  std::vector<std::array<std::uint32_t, 3>> elements;
  for(std::uint32_t i = 0; i < fan; ++i) {
    // rim vertices numbered out of their order around the fan
    const std::uint32_t a = 1 + (i * 7) % fan, b = 1 + ((i + 1) * 7) % fan;
    elements.push_back(i % 2 ? std::array<std::uint32_t, 3>{a, 0, b} : std::array<std::uint32_t, 3>{b, a, 0});
  }
  const auto& local = internal::Simplex_tables<2>::edge;
  std::size_t run = 0;
  for(const auto& r : internal::sorted_faces<2>(elements, local, fan + 1))
    run += r.vertices[0] == 0;
  CHECK(run == 2 * fan);
  const auto [same, all] = faces_in_comparison_order(elements, local, fan + 1);
  CHECK(same == all);
}

// The edges, each slot's edge and its rank among the edge's slots as the
// comparison sort of all (smaller vertex, larger vertex, slot) records gives
// them, against number_edges.
template <class Elements, std::size_t E>
void check_edge_numbering(const Elements& elements, const std::array<std::array<int, 2>, E>& local,
                          std::size_t number_of_vertices)
{
  std::vector<std::pair<std::array<std::uint32_t, 2>, std::uint32_t>> records;
  for(std::size_t t = 0; t < elements.size(); ++t)
    for(std::size_t j = 0; j < E; ++j) {
      std::array<std::uint32_t, 2> v{std::uint32_t(elements[t][std::size_t(local[j][0])]),
                                     std::uint32_t(elements[t][std::size_t(local[j][1])])};
      std::sort(v.begin(), v.end());
      records.push_back({v, std::uint32_t(t * E + j)});
    }
  std::sort(records.begin(), records.end());
  std::vector<std::array<std::uint32_t, 2>> edges;
  std::vector<std::uint32_t> element_edges(records.size()), rank(records.size());
  for(std::size_t r = 0, first = 0; r < records.size(); ++r) {
    if(r == 0 || records[r].first != records[r - 1].first) {
      edges.push_back(records[r].first);
      first = r;
    }
    element_edges[records[r].second] = std::uint32_t(edges.size() - 1);
    rank[records[r].second] = std::uint32_t(r - first);
  }
  std::vector<std::array<std::uint32_t, 2>> got_edges;
  std::vector<std::uint32_t> got_element_edges, got_rank;
  internal::number_edges(elements, local, number_of_vertices, got_edges, got_element_edges, got_rank);
  CHECK(got_edges == edges);
  CHECK(got_element_edges == element_edges);
  CHECK(got_rank == rank);
}

TEST_CASE("number_edges: the numbering of a comparison sort of all the edge slots", "[threads][network]")
{
  auto grid3 = kuhn_grid<3>(4);
  auto grid2 = kuhn_grid<2>(7);
  // scattered element orders, so that each vertex's slots arrive unsorted
  std::reverse(grid3.elements.begin(), grid3.elements.end());
  std::rotate(grid3.elements.begin(), grid3.elements.begin() + 37, grid3.elements.end());
  std::mt19937 rng(3);
  std::shuffle(grid2.elements.begin(), grid2.elements.end(), rng);
  check_edge_numbering(grid3.elements, internal::Simplex_tables<3>::edge, grid3.points.size());
  check_edge_numbering(grid2.elements, internal::Simplex_tables<2>::edge, grid2.points.size());
  // a fan of 300 triangles around vertex 0, its rim numbered out of order:
  // one vertex with hundreds of neighbours
  const std::uint32_t fan = 300;
  std::vector<std::array<std::uint32_t, 3>> elements;
  for(std::uint32_t i = 0; i < fan; ++i) {
    const std::uint32_t a = 1 + (i * 7) % fan, b = 1 + ((i + 1) * 7) % fan;
    elements.push_back(i % 2 ? std::array<std::uint32_t, 3>{a, 0, b} : std::array<std::uint32_t, 3>{b, a, 0});
  }
  check_edge_numbering(elements, internal::Simplex_tables<2>::edge, fan + 1);
}

// spatial_element_order against a comparison sort of (centroid code, element)
template <int D>
void check_spatial_order(const Spring_network<D>& net)
{
  const std::vector<std::uint64_t> code = internal::centroid_morton_codes(net);
  std::vector<std::pair<std::uint64_t, Index>> key;
  for(std::size_t t = 0; t < code.size(); ++t)
    key.push_back({code[t], Index(t)});
  std::sort(key.begin(), key.end());
  std::vector<Index> expected;
  for(const auto& k : key)
    expected.push_back(k.second);
  CHECK(internal::spatial_element_order(net) == expected);
}

TEST_CASE("spatial_element_order: the order of a comparison sort of (code, element)", "[network]")
{
  auto grid3 = kuhn_grid<3>(6);
  std::mt19937 rng(5);
  std::shuffle(grid3.elements.begin(), grid3.elements.end(), rng);
  const auto net3 = make_spring_network<3>(grid3.points, grid3.elements);
  check_spatial_order(net3);
  auto grid2 = kuhn_grid<2>(9);
  std::shuffle(grid2.elements.begin(), grid2.elements.end(), rng);
  check_spatial_order(make_spring_network<2>(grid2.points, grid2.elements));
  // codes that tie: every point in one place gives every element the code 0,
  // and ties keep the elements' order
  auto flat = grid3;
  for(auto& p : flat.points)
    p = {0.0, 0.0, 0.0};
  const auto tied = make_spring_network<3>(flat.points, flat.elements);
  const std::vector<std::uint64_t> codes = internal::centroid_morton_codes(tied);
  CHECK(std::all_of(codes.begin(), codes.end(), [](std::uint64_t c) { return c == 0; }));
  check_spatial_order(tied);
}

// The facets of exactly one element, from a comparison sort of all the
// facets' sorted vertex triples (pairs in 2D).
template <int D, class Elements>
std::vector<std::array<Index, D>> facets_of_one_element(const Elements& elements)
{
  std::vector<std::array<Index, D>> all;
  for(const auto& t : elements)
    for(const auto& local : internal::Simplex_tables<D>::facet) {
      std::array<Index, D> f;
      for(int c = 0; c < D; ++c)
        f[std::size_t(c)] = t[std::size_t(local[std::size_t(c)])];
      std::sort(f.begin(), f.end());
      all.push_back(f);
    }
  std::sort(all.begin(), all.end());
  std::vector<std::array<Index, D>> once;
  for(std::size_t r = 0; r < all.size();) {
    std::size_t s = r;
    while(s < all.size() && all[s] == all[r])
      ++s;
    if(s - r == 1)
      once.push_back(all[r]);
    r = s;
  }
  return once;
}

TEST_CASE("make_spring_network: the boundary facets are those of one element, in order", "[network]")
{
  std::mt19937 rng(11);
  auto grid3 = kuhn_grid<3>(5);
  std::shuffle(grid3.elements.begin(), grid3.elements.end(), rng);
  const auto net3 = make_spring_network<3>(grid3.points, grid3.elements);
  CHECK(net3.boundary_facets == facets_of_one_element<3>(grid3.elements));
  CHECK(net3.boundary_facets.size() == 6 * 2 * 5 * 5); // two triangles per square of the cube's faces
  auto grid2 = kuhn_grid<2>(6);
  std::shuffle(grid2.elements.begin(), grid2.elements.end(), rng);
  const auto net2 = make_spring_network<2>(grid2.points, grid2.elements);
  CHECK(net2.boundary_facets == facets_of_one_element<2>(grid2.elements));
  CHECK(net2.boundary_facets.size() == 4 * 6);
}

TEST_CASE("make_spring_network: a facet of three elements is an error", "[network][errors]")
{
  // three tetrahedra on the triangle (0, 1, 2), and in 2D three triangles on the edge (0, 1)
  const std::vector<std::array<double, 3>> points3{{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}, {0, 0, -1}, {1, 1, 1}};
  const std::vector<std::array<Index, 4>> tets{{0, 1, 2, 3}, {0, 2, 1, 4}, {0, 1, 2, 5}};
  CHECK_THROWS_WITH(make_spring_network<3>(points3, tets),
                    Catch::Contains("a facet is shared by 3 elements: the mesh is not a manifold"));
  const std::vector<std::array<double, 2>> points2{{0, 0}, {1, 0}, {0, 1}, {0, -1}, {1, 1}};
  const std::vector<std::array<Index, 3>> triangles{{0, 1, 2}, {1, 0, 3}, {0, 1, 4}};
  CHECK_THROWS_WITH(make_spring_network<2>(points2, triangles),
                    Catch::Contains("a facet is shared by 3 elements: the mesh is not a manifold"));
}
