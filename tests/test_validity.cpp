// Exact validity (validity.h, check_input_mesh.h; docs/method.md, "Validity
// and quality") and deform()'s rollback: the elements reported as inverted are
// exactly those whose CGAL::orientation, computed here, differs from the
// initial one, and the mesh is left at the last valid step. Each problem of an
// input mesh is found on a small hand-built mesh, with its exact elements.
#include <spring_motion/spring_motion.h>

#include "test_meshes.h"

#include <catch2/catch.hpp>

#include <array>
#include <cmath>
#include <iterator>
#include <limits>
#include <map>
#include <random>
#include <vector>

using namespace spring_motion;
using namespace spring_motion_test;

namespace {
using P2 = std::array<double, 2>;
using K = CGAL::Exact_predicates_inexact_constructions_kernel;

CGAL::Orientation orientation_of(const std::array<P2, 3>& p)
{
  return CGAL::orientation(K::Point_2(p[0][0], p[0][1]), K::Point_2(p[1][0], p[1][1]), K::Point_2(p[2][0], p[2][1]));
}
} // namespace

TEST_CASE("find_inverted_elements: flipped and flat elements, against CGAL::orientation", "[validity]")
{
  // a fan of six triangles around the centre vertex 6 of a hexagon
  std::vector<P2> pts;
  for(int k = 0; k < 6; ++k)
    pts.push_back({std::cos(k * M_PI / 3), std::sin(k * M_PI / 3)});
  pts.push_back({0, 0});
  std::vector<std::array<Index, 3>> tris;
  for(Index k = 0; k < 6; ++k)
    tris.push_back({k, Index((k + 1) % 6), 6});
  tris[3] = {tris[3][1], tris[3][0], 6}; // one clockwise element: the record keeps each one's own sign
  const auto net = make_spring_network<2>(pts, tris);
  const auto rec = record_orientations(net, net.points);
  for(std::size_t t = 0; t < 6; ++t)
    CHECK(rec.sign[t] == (t == 3 ? -1 : 1));

  auto check_against_cgal = [&](const std::vector<P2>& x) {
    std::vector<std::size_t> found;
    const std::size_t n = find_inverted_elements(net, x, rec, std::back_inserter(found));
    std::vector<std::size_t> expected;
    for(std::size_t t = 0; t < 6; ++t) {
      const std::array<P2, 3> p{x[tris[t][0]], x[tris[t][1]], x[tris[t][2]]};
      const auto initial = orientation_of({pts[tris[t][0]], pts[tris[t][1]], pts[tris[t][2]]});
      if(orientation_of(p) != initial) // zero orientation differs from both signs
        expected.push_back(t);
    }
    CHECK(n == found.size());
    CHECK(found == expected);
    return found;
  };
  auto x = net.points;
  CHECK(check_against_cgal(x).empty());
  // the centre moved along the bisector of edge 0-1, whose distance from the
  // centre is cos 30 deg = 0.866: at 0.8 nothing flips, at 1.0 triangle 0
  // has flipped and its neighbours, still on the same side of their own
  // outer edges, have not
  x[6] = {0.8 * std::cos(M_PI / 6), 0.8 * std::sin(M_PI / 6)};
  CHECK(check_against_cgal(x).empty());
  x[6] = {1.0 * std::cos(M_PI / 6), 1.0 * std::sin(M_PI / 6)};
  CHECK(check_against_cgal(x) == std::vector<std::size_t>{0});
  // onto the midpoint of edge 0-1: rounding may leave it on either side of
  // the line or on it; whatever the exact predicate says, the library agrees
  x[6] = {0.5 * (pts[0][0] + pts[1][0]), 0.5 * (pts[0][1] + pts[1][1])};
  check_against_cgal(x);
  // exactly onto vertex 0: triangles 0 and 5 become flat (orientation zero) and count as inverted
  x[6] = pts[0];
  CHECK(check_against_cgal(x) == std::vector<std::size_t>{0, 5});
  // far across: the centre beyond vertex 0 flips 0 and 5, keeps the rest
  x[6] = {2.0, 0.0};
  CHECK(check_against_cgal(x) == std::vector<std::size_t>{0, 5});
}

namespace {
// The element the Element_error of record_orientations names, or -1.
template <int D>
long refused_element(const Spring_network<D>& net)
{
  try {
    record_orientations(net, net.points);
  } catch(const Element_error& e) {
    return long(e.element());
  }
  return -1;
}

// A regular hexagon around vertex 6, six counter-clockwise triangles.
Indexed_mesh<2> hexagon_fan()
{
  Indexed_mesh<2> mesh;
  for(int k = 0; k < 6; ++k)
    mesh.points.push_back({std::cos(k * M_PI / 3), std::sin(k * M_PI / 3)});
  mesh.points.push_back({0, 0});
  for(std::uint32_t k = 0; k < 6; ++k)
    mesh.elements.push_back({k, std::uint32_t((k + 1) % 6), 6});
  return mesh;
}

using Elements = std::vector<std::size_t>;
} // namespace

TEST_CASE("record_orientations: a degenerate input element is an error", "[validity][errors]")
{
  const auto net = make_spring_network<2>({{0, 0}, {1, 0}, {2, 0}, {0, 1}}, {{0, 1, 3}, {0, 1, 2}});
  CHECK_THROWS_WITH(record_orientations(net, net.points), Catch::Contains("degenerate") && Catch::Contains("1"));
  CHECK(refused_element(net) == 1);
}

TEST_CASE("check_input_mesh: a valid mesh has no problems", "[validity][check]")
{
  const auto fan = hexagon_fan();
  const auto p = check_input_mesh<2>(fan.points, fan.elements);
  CHECK(p.valid());
  CHECK(p.positive == 6);
  CHECK(p.negative == 0);
  // all clockwise is as valid: the orientation only has to be the same throughout
  auto cw = fan;
  for(auto& e : cw.elements)
    std::swap(e[0], e[1]);
  const auto q = check_input_mesh<2>(cw.points, cw.elements);
  CHECK(q.valid());
  CHECK(q.negative == 6);
}

TEST_CASE("check_input_mesh: degenerate elements (zero exact orientation)", "[validity][check]")
{
  auto fan = hexagon_fan();
  // vertex 6 exactly onto vertex 0: the two triangles using both are flat,
  // the other four keep their area and overlap nothing
  fan.points[6] = fan.points[0];
  const auto p = check_input_mesh<2>(fan.points, fan.elements);
  CHECK(p.degenerate == Elements{0, 5});
  CHECK(p.positive == 4);
  CHECK(p.negative == 0);
  CHECK(p.mixed_orientation.empty());
  CHECK(p.overlapping.empty()); // a flat element overlaps nothing: it is reported as degenerate only
  CHECK(p.non_manifold.empty());
  CHECK_FALSE(p.valid());
  CHECK(first_problem_element(p) == 0);
}

TEST_CASE("check_input_mesh: elements oriented against the majority", "[validity][check]")
{
  auto fan = hexagon_fan();
  std::swap(fan.elements[3][0], fan.elements[3][1]); // same triangle, listed clockwise
  const auto p = check_input_mesh<2>(fan.points, fan.elements);
  CHECK(p.positive == 5);
  CHECK(p.negative == 1);
  CHECK(p.mixed_orientation == Elements{3});
  CHECK(p.degenerate.empty());
  CHECK(p.overlapping.empty()); // geometrically the mesh is fine
  CHECK(p.valid());             // reported, not refused: each element keeps its own sign
  const auto net = make_spring_network<2>(fan.points, fan.elements);
  const auto rec = record_orientations(net, net.points);
  for(std::size_t t = 0; t < 6; ++t)
    CHECK(rec.sign[t] == (t == 3 ? -1 : 1));
  // a tie: the first element's sign is the mesh's
  Indexed_mesh<2> two;
  two.points = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
  two.elements = {{0, 2, 1}, {0, 2, 3}};
  const auto q = check_input_mesh<2>(two.points, two.elements);
  CHECK(q.positive == 1);
  CHECK(q.negative == 1);
  CHECK(q.mixed_orientation == Elements{1});
  CHECK(q.valid());
}

TEST_CASE("check_input_mesh: elements overlapping across a shared facet", "[validity][check]")
{
  // two counter-clockwise triangles on the same side of their shared edge 0-1
  Indexed_mesh<2> fold;
  fold.points = {{0, 0}, {1, 0}, {0.5, 1}, {0.5, 0.5}};
  fold.elements = {{0, 1, 2}, {0, 1, 3}};
  const auto p = check_input_mesh<2>(fold.points, fold.elements);
  CHECK(p.positive == 2);
  CHECK(p.mixed_orientation.empty());
  CHECK(p.overlapping == Elements{0, 1}); // same orientation: both are listed
  CHECK(p.degenerate.empty());
  CHECK_FALSE(p.valid());

  // a fan whose vertex 6 moved beyond the edge 0-1: triangle 0 turned over and
  // overlaps its neighbours 1 and 5 across the edges 6-1 and 6-0
  auto fan = hexagon_fan();
  fan.points[6] = {0.9 * std::cos(M_PI / 6) * 1.2, 0.9 * std::sin(M_PI / 6) * 1.2};
  const auto q = check_input_mesh<2>(fan.points, fan.elements);
  CHECK(q.negative == 1);
  CHECK(q.mixed_orientation == Elements{0});
  CHECK(q.overlapping == Elements{0}); // of each pair, the one against the majority
  CHECK(refused_element(make_spring_network<2>(fan.points, fan.elements)) == 0);

  // 3D: two tetrahedra on the same side of their shared triangle 0-1-2
  std::vector<std::array<double, 3>> pts{{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}, {0, 0, -1}, {0.1, 0.1, 0.5}};
  std::vector<std::array<Index, 4>> good{{0, 1, 2, 3}, {0, 2, 1, 4}}, bad{{0, 1, 2, 3}, {0, 1, 2, 5}};
  const auto g = check_input_mesh<3>(pts, good);
  CHECK(g.valid());
  CHECK(g.positive == 2);
  const auto b = check_input_mesh<3>(pts, bad);
  CHECK(b.positive == 2);
  CHECK(b.overlapping == Elements{0, 1});
  CHECK(refused_element(make_spring_network<3>(pts, bad)) == 0);
}

TEST_CASE("record_orientations: with the mesh checked by the caller, the same record, and no flat element",
          "[validity][check]")
{
  // the same signs as with the check, the fan's orientations as given (one flipped)
  auto fan = hexagon_fan();
  std::swap(fan.elements[2][0], fan.elements[2][1]);
  const auto net = make_spring_network<2>(fan.points, fan.elements);
  const auto here = record_orientations(net, net.points);
  const auto by_caller = record_orientations(net, net.points, Mesh_checks::by_caller);
  CHECK(by_caller.sign == here.sign);
  CHECK(by_caller.sign == std::vector<signed char>{1, 1, -1, 1, 1, 1});
  // a degenerate element is still refused, by its number
  const auto flat = make_spring_network<2>({{0, 0}, {1, 0}, {2, 0}, {0, 1}}, {{0, 1, 3}, {0, 1, 2}});
  try {
    record_orientations(flat, flat.points, Mesh_checks::by_caller);
    FAIL("a degenerate element was recorded");
  } catch(const Element_error& e) {
    CHECK(e.element() == 1);
    CHECK_THAT(e.what(), Catch::Contains("degenerate"));
  }
  // the facet tests are the caller's: two overlapping tetrahedra pass here
  std::vector<std::array<double, 3>> pts{{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}, {0.1, 0.1, 0.5}};
  const auto fold = make_spring_network<3>(pts, {{0, 1, 2, 3}, {0, 1, 2, 4}});
  CHECK_THROWS_AS(record_orientations(fold, fold.points), Element_error);
  CHECK(record_orientations(fold, fold.points, Mesh_checks::by_caller).sign == std::vector<signed char>{1, 1});
  CHECK_THROWS(record_orientations(fold, {pts[0], pts[1]}, Mesh_checks::by_caller)); // too few positions
}

TEST_CASE("check_input_mesh: a facet in more than two elements", "[validity][check]")
{
  Indexed_mesh<2> fin;
  fin.points = {{0, 0}, {1, 0}, {0.5, 1}, {0.5, -1}, {0.5, 2}};
  fin.elements = {{0, 1, 2}, {1, 0, 3}, {0, 1, 4}}; // all counter-clockwise, all on the edge 0-1
  const auto p = check_input_mesh<2>(fin.points, fin.elements);
  CHECK(p.positive == 3);
  CHECK(p.non_manifold_facets == 1);
  CHECK(p.non_manifold == Elements{0, 1, 2});
  CHECK(p.overlapping.empty()); // judged between two elements only
  CHECK(p.mixed_orientation.empty());
  CHECK_FALSE(p.valid());
  // an element using a vertex that does not exist is an error, not a problem to report
  fin.elements[2][2] = 7;
  CHECK_THROWS_AS(check_input_mesh<2>(fin.points, fin.elements), Element_error);
}

TEST_CASE("deform: an overlapping input mesh is refused before any motion", "[validity][deform][errors]")
{
  auto fan = hexagon_fan();
  fan.points[6] = {0.9 * std::cos(M_PI / 6) * 1.2, 0.9 * std::sin(M_PI / 6) * 1.2};
  const auto centre_moves = [](const Vertex_info<2>& v) {
    return v.index == 6 ? Vertex_role::moving : Vertex_role::fixed;
  };
  try {
    deform(fan, centre_moves, Translation_motion<2>{{-0.1, 0}}, Lineal_stiffness{});
    FAIL("deform accepted an overlapping mesh");
  } catch(const Element_error& e) {
    CHECK(e.element() == 0);
    CHECK_THAT(e.what(), Catch::Contains("1 element(s) overlapping a neighbour in the input mesh"));
  }
}

TEST_CASE("deform: pushing a vertex across its opposite edge flags exactly the flipped elements and rolls back",
          "[validity][deform]")
{
  // A Mesh_2 domain; one interior vertex v moves, every other vertex is
  // fixed, so the candidate positions of each step are known here exactly:
  // only v moves, to p0 + (i/n) d.
  CDT cdt;
  make_square_with_hole(cdt);
  const auto ext = extract_spring_network(cdt);
  const auto& net = ext.network;
  // the interior vertex closest to (1.2, 1.0)
  Index v = 0;
  double best = 1e300;
  for(Index i = 0; i < net.number_of_vertices(); ++i)
    if(!net.on_boundary[i]) {
      const double d = std::hypot(net.points[i][0] - 1.2, net.points[i][1] - 1.0);
      if(d < best) {
        best = d;
        v = i;
      }
    }
  const P2 v0 = net.points[v];
  // its neighbours: the farthest sets the length of the push, so v crosses
  // the far side of its link; the nearest gives a push through a neighbour,
  // which flips the two elements on the edge to it at once
  double reach = 0, nearest = 1e300;
  P2 towards{};
  for(Index p = net.adjacency_offsets[v]; p < net.adjacency_offsets[v + 1]; ++p) {
    const auto& q = net.points[net.adjacency[p]];
    const double l = std::hypot(q[0] - v0[0], q[1] - v0[1]);
    reach = std::max(reach, l);
    if(l < nearest) {
      nearest = l;
      towards = {q[0] - v0[0], q[1] - v0[1]};
    }
  }
  // (steps, push): small steps cross one edge first; a long step through a neighbour crosses two
  const int setting = GENERATE(0, 1, 2);
  std::size_t n = 12;
  P2 d{1.5 * reach * std::cos(0.3), 1.5 * reach * std::sin(0.3)};
  if(setting == 1) {
    n = 3;
    d = {2.5 * reach * std::cos(2.0), 2.5 * reach * std::sin(2.0)};
  } else if(setting == 2) {
    n = 2;
    d = {1.3 * towards[0], 1.3 * towards[1]};
  }
  const Translation_motion<2> motion{d};
  auto at_step = [&](std::size_t i) {
    auto x = net.points;
    x[v] = motion(v0, double(i) / double(n));
    return x;
  };
  // the first step at which CGAL::orientation sees a flipped (or flat)
  // element, and which elements: computed here, independently of the library
  std::size_t first_bad = 0;
  std::vector<std::size_t> flipped;
  for(std::size_t i = 1; i <= n && first_bad == 0; ++i) {
    const auto x = at_step(i);
    for(std::size_t t = 0; t < net.number_of_elements(); ++t) {
      const auto& e = net.elements[t];
      if(orientation_of({x[e[0]], x[e[1]], x[e[2]]}) !=
         orientation_of({net.points[e[0]], net.points[e[1]], net.points[e[2]]}))
        flipped.push_back(t);
    }
    if(!flipped.empty())
      first_bad = i;
  }
  INFO("setting " << setting << ": first invalid step " << first_bad << " of " << n << ", " << flipped.size()
                   << " flipped");
  REQUIRE(first_bad >= 1);
  if(setting == 2) // through the neighbour: both elements on the edge to it
    CHECK(flipped.size() >= 2);

  auto only_v_moves = [&](const Vertex_info<2>& info) {
    return info.index == v ? Vertex_role::moving : Vertex_role::fixed;
  };
  Deform_options options;
  options.number_of_steps = n;
  CDT moved = cdt;
  const auto report = deform(moved, only_v_moves, motion, Lineal_stiffness{}, options);
  CHECK_FALSE(report.completed);
  REQUIRE(report.first_invalid);
  CHECK(report.first_invalid->step == first_bad);
  CHECK(report.first_invalid->fraction == Approx(double(first_bad) / double(n)));
  // element indices are in the order the traits list the domain faces,
  // which is the order of the network extracted above
  CHECK(report.first_invalid->elements == flipped);
  CHECK(report.steps.size() == first_bad);
  CHECK(report.steps.back().inverted == flipped.size());
  CHECK(report.final_fraction == Approx(double(first_bad - 1) / double(n)));

  // the mesh is at the last valid step: v exactly where the motion put it
  // then, every other vertex unmoved, every domain face as oriented as before
  const auto last_valid = at_step(first_bad - 1);
  std::map<std::pair<double, double>, P2> expected;
  for(Index i = 0; i < net.number_of_vertices(); ++i)
    expected[{net.points[i][0], net.points[i][1]}] = last_valid[i];
  auto a = moved.finite_vertices_begin();
  std::size_t matched = 0;
  for(auto b = cdt.finite_vertices_begin(); b != cdt.finite_vertices_end(); ++b, ++a) {
    const auto it = expected.find({b->point().x(), b->point().y()});
    if(it == expected.end())
      continue; // a vertex no domain face uses
    ++matched;
    CHECK(a->point().x() == it->second[0]);
    CHECK(a->point().y() == it->second[1]);
  }
  CHECK(matched == net.number_of_vertices());
  for(auto f = moved.finite_faces_begin(); f != moved.finite_faces_end(); ++f)
    if(f->is_in_domain())
      CHECK(CGAL::orientation(f->vertex(0)->point(), f->vertex(1)->point(), f->vertex(2)->point()) ==
            CGAL::LEFT_TURN);
}

namespace {
using P3 = std::array<double, 3>;

// Nearly flat elements: the last point placed on the line (plane) through the
// others by rounded arithmetic, then moved by up to three units in the last
// place, far from the origin so that the differences cancel. Their exact
// orientations are +1, -1 and 0, decided by a few units of rounding.
template <int D>
std::array<std::array<double, D>, D + 1> nearly_flat(std::mt19937_64& rng, double offset)
{
  std::uniform_real_distribution<double> coordinate(-1, 1), weight(-0.5, 1.5);
  std::uniform_int_distribution<int> ulps(-3, 3);
  std::array<std::array<double, D>, D + 1> p;
  for(int k = 0; k < D; ++k)
    for(int c = 0; c < D; ++c)
      p[k][c] = offset + coordinate(rng);
  std::array<double, D> w;
  for(int k = 1; k < D; ++k)
    w[k] = weight(rng);
  for(int c = 0; c < D; ++c) {
    double v = p[0][c];
    for(int k = 1; k < D; ++k)
      v += w[k] * (p[k][c] - p[0][c]);
    for(int s = ulps(rng); s != 0; s += s > 0 ? -1 : 1)
      v = std::nextafter(v, s > 0 ? HUGE_VAL : -HUGE_VAL);
    p[D][c] = v;
  }
  return p;
}

template <int D>
std::array<std::array<double, D>, D + 1> scaled(std::array<std::array<double, D>, D + 1> p, double s)
{
  for(auto& q : p)
    for(auto& c : q)
      c *= s;
  return p;
}

// Runs the filter and CGAL's predicate on `count` elements from `make`:
// every sign the filter gives is CGAL's; returns how many it left to CGAL.
template <int D, class Make>
std::size_t undecided_against_cgal(std::size_t count, Make make, std::size_t& cgal_zero)
{
  std::size_t undecided = 0;
  cgal_zero = 0;
  for(std::size_t i = 0; i < count; ++i) {
    const auto p = make();
    const int exact = internal::cgal_orientation(p);
    const int filtered = internal::filtered_orientation(p);
    cgal_zero += exact == 0;
    if(filtered == 0)
      ++undecided;
    else
      REQUIRE(filtered == exact);
    REQUIRE(internal::exact_orientation(p) == exact);
  }
  return undecided;
}
} // namespace

TEMPLATE_TEST_CASE_SIG("exact_orientation: the floating-point filter gives only CGAL's signs", "[validity][orientation]",
                       ((int D), D), 2, 3)
{
  std::mt19937_64 rng(20261126);
  std::uniform_real_distribution<double> coordinate(-1, 1);
  std::size_t zero = 0;
  SECTION("well-shaped elements: the filter decides every one")
  {
    const auto random_element = [&] {
      std::array<std::array<double, D>, D + 1> p;
      for(auto& q : p)
        for(auto& c : q)
          c = coordinate(rng);
      return p;
    };
    CHECK(undecided_against_cgal<D>(20000, random_element, zero) == 0);
  }
  SECTION("nearly flat elements: the filter decides some, CGAL the rest, never a different sign")
  {
    for(const double offset : {0.0, 1.0, 1000.0}) {
      const std::size_t count = 20000;
      const std::size_t undecided =
          undecided_against_cgal<D>(count, [&] { return nearly_flat<D>(rng, offset); }, zero);
      INFO("offset " << offset << ": " << undecided << " undecided, " << zero << " flat");
      // the filter is not idle (it decides a share) and not blind (the
      // flat ones, and more, are left to CGAL)
      CHECK(undecided > zero);
      CHECK(undecided < count);
    }
  }
  SECTION("tiny and huge coordinates: beyond the filter's range CGAL decides")
  {
    for(const double s : {0x1p-1000, 0x1p-600, 0x1p-515, 0x1p-343, 0x1p+400, 0x1p+900}) {
      std::size_t undecided = undecided_against_cgal<D>(
          2000, [&] { return scaled<D>(nearly_flat<D>(rng, 1.0), s); }, zero);
      INFO("scale " << s);
      CHECK(undecided > zero);
      undecided = undecided_against_cgal<D>(
          2000,
          [&] {
            std::array<std::array<double, D>, D + 1> p;
            for(auto& q : p)
              for(auto& c : q)
                c = coordinate(rng);
            return scaled<D>(p, s);
          },
          zero);
      // past 2^300 the filter gives every element to CGAL; below, the
      // additive slack for underflow leaves the tiniest ones to CGAL too
      if(s > 1)
        CHECK(undecided == 2000);
      if(s == 0x1p-1000)
        CHECK(undecided == 2000);
    }
  }
}

namespace {

// The check the deformer runs on every attempt, in the elements' spatial
// traversal: the same verdict as find_inverted_elements in element order.
template <int D>
void check_traversal_verdicts(int n, int trials)
{
  const Indexed_mesh<D> mesh = kuhn_grid<D>(n);
  const auto net = make_spring_network<D>(mesh.points, mesh.elements);
  const auto rec = record_orientations(net, net.points);
  const auto& slots = internal::angle_slots(net);
  // the traversal's elements are the network's, vertex order kept: each one's
  // recorded sign, found by its vertices
  std::map<std::array<Index, D + 1>, int> sign_of;
  for(std::size_t t = 0; t < net.number_of_elements(); ++t)
    sign_of[net.elements[t]] = rec.sign[t];
  std::vector<std::array<double, D>> xt;
  internal::copy_in_traversal_order<D>(slots, net.points, xt, 1);
  const auto sign = internal::traversal_orientations<D>(slots, xt, 2);
  REQUIRE(sign.size() == net.number_of_elements());
  for(std::size_t i = 0; i < sign.size(); ++i) {
    std::array<Index, D + 1> e;
    for(int k = 0; k <= D; ++k)
      e[std::size_t(k)] = slots.traversal_vertices[slots.ordered_elements[i * (D + 1) + std::size_t(k)]];
    REQUIRE(sign_of.count(e) == 1);
    CHECK(sign[i] == sign_of[e]);
  }
  // one vertex moved at random, by up to two cells, or onto a neighbour
  // (flat elements): some attempts invert elements, some do not
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> u(-2.0, 2.0);
  int inverted = 0, valid = 0;
  for(int trial = 0; trial < trials; ++trial) {
    auto x = net.points;
    const Index v = Index(rng() % x.size());
    if(trial % 5 == 0)
      x[v] = x[net.adjacency[net.adjacency_offsets[v]]];
    else
      for(int c = 0; c < D; ++c)
        x[v][c] += u(rng);
    std::vector<std::size_t> found;
    find_inverted_elements(net, x, rec, std::back_inserter(found));
    for(int threads : {1, 2}) {
      internal::copy_in_traversal_order<D>(slots, x, xt, threads);
      CHECK(internal::orientation_changed<D>(slots, xt, sign, threads) == !found.empty());
    }
    (found.empty() ? valid : inverted) += 1;
  }
  CHECK(inverted > trials / 4);
  CHECK(valid > trials / 10);
}

} // namespace

TEST_CASE("traversal check: the deformer's check in the spatial traversal agrees with find_inverted_elements",
          "[validity]")
{
  check_traversal_verdicts<2>(12, 200);
  check_traversal_verdicts<3>(5, 200);
}

TEST_CASE("traversal check: three separate tetrahedra, each flipped alone, two at a time or the last alone",
          "[validity]")
{
  // the check takes the traversal's tetrahedra in pairs and an odd last one
  // alone: whichever element is flipped, the verdict must see it
  std::vector<std::array<double, 3>> points;
  std::vector<std::array<Index, 4>> tets;
  for(int t = 0; t < 3; ++t) {
    const double x = 3.0 * t;
    for(const auto& p : {std::array<double, 3>{x, 0, 0}, {x + 1, 0, 0}, {x, 1, 0}, {x, 0, 1}})
      points.push_back(p);
    tets.push_back({Index(4 * t), Index(4 * t + 1), Index(4 * t + 2), Index(4 * t + 3)});
  }
  const auto net = make_spring_network<3>(points, tets);
  const auto& slots = internal::angle_slots(net);
  std::vector<std::array<double, 3>> xt;
  internal::copy_in_traversal_order<3>(slots, net.points, xt, 1);
  const auto sign = internal::traversal_orientations<3>(slots, xt, 1);
  for(int threads : {1, 2})
    CHECK_FALSE(internal::orientation_changed<3>(slots, xt, sign, threads));
  for(int t = 0; t < 3; ++t)
    for(double z : {-1.0, 0.0}) { // through its base, or onto it (flat)
      auto x = net.points;
      x[std::size_t(4 * t + 3)][2] = z;
      internal::copy_in_traversal_order<3>(slots, x, xt, 1);
      for(int threads : {1, 2}) {
        INFO("tetrahedron " << t << " apex at z = " << z << ", " << threads << " threads");
        CHECK(internal::orientation_changed<3>(slots, xt, sign, threads));
      }
    }
}

TEST_CASE("coarse_orientations: two tetrahedra's first-stage signs are filtered_orientation's",
          "[validity][orientation]")
{
  std::mt19937_64 rng(20261130);
  std::uniform_real_distribution<double> coordinate(-1, 1);
  using T = std::array<std::array<double, 3>, 4>;
  std::vector<T> tets;
  std::vector<int> kind; // 0, 5: random; 1, 2: nearly flat; 3: huge or tiny; 4: NaN or infinite
  for(int n = 0; n < 3000; ++n) {
    T p;
    for(auto& q : p)
      for(auto& c : q)
        c = coordinate(rng);
    kind.push_back(n % 6);
    if(kind.back() == 1)
      p = nearly_flat<3>(rng, 1.0);
    else if(kind.back() == 2)
      p = nearly_flat<3>(rng, 1000.0);
    else if(kind.back() == 3)
      p = scaled<3>(p, (n / 6) % 2 == 0 ? 0x1p+400 : 0x1p-600); // beyond the filter's range, or tiny
    else if(kind.back() == 4)
      p[std::size_t(n % 4)][0] = (n / 6) % 2 == 0 ? std::numeric_limits<double>::infinity() : std::nan("");
    tets.push_back(p);
  }
  const auto corners = [](const T& p) {
    return std::array<const double*, 4>{p[0].data(), p[1].data(), p[2].data(), p[3].data()};
  };
  const auto random = [&](std::size_t t) { return kind[t] == 0 || kind[t] == 5; };
  std::size_t decided = 0, random_pairs = 0, random_undecided = 0;
  for(std::size_t i = 0; i < tets.size(); ++i)
    for(const std::size_t j : {i, (i * 7919 + 13) % tets.size()}) {
      const auto s = internal::coarse_orientations(corners(tets[i]), corners(tets[j]));
      for(std::size_t k = 0; k < 2; ++k) {
        const std::size_t t = k == 0 ? i : j;
        INFO("tetrahedra " << i << " and " << j << ", lane " << k);
        if(s[k] != 0) {
          CHECK(s[k] == internal::filtered_orientation(tets[t]));
          ++decided;
        }
        if(random(i) && random(j)) {
          ++random_pairs;
          random_undecided += s[k] == 0;
        }
      }
      if(kind[i] == 4 || kind[j] == 4 || (kind[i] == 3 && (i / 6) % 2 == 0))
        CHECK(s == std::array<int, 2>{0, 0}); // NaN, infinity or 2^400 in a lane: both to the scalar filter
    }
  // the first stage decides most elements, and random ones almost always
  INFO(decided << " decided; random pairs: " << random_undecided << " of " << random_pairs << " undecided");
  CHECK(decided > tets.size());
  CHECK(random_pairs > 1000);
  CHECK(random_undecided * 100 < random_pairs);
}
