// Copyright (c) 2026 SpringMotion developers.
#include <naca0012/Naca0012_mesh_2.h>

#include <spring_motion/Error.h>

#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <map>
#include <memory>
#include <set>
#include <vector>

using namespace spring_motion;

namespace {

using Cdt = Mesh_2_cdt;
using Point = Mesh_2_kernel::Point_2;

const Point kFar_field_centre(0.5, 0.0);

// What the tests look at: the domain (faces with is_in_domain()), its
// vertices, and its boundary vertices split by is_on_naca0012_airfoil.
struct Domain
{
  std::vector<Cdt::Face_handle> faces;
  std::set<Cdt::Vertex_handle> nodes;
  std::vector<Point> airfoil;
  std::vector<Point> far_field;
};

Domain domain_of(const Cdt& cdt)
{
  Domain d;
  std::set<Cdt::Vertex_handle> boundary;
  for(Cdt::Face_handle f : cdt.finite_face_handles()) {
    if(!f->is_in_domain())
      continue;
    d.faces.push_back(f);
    for(int i = 0; i < 3; ++i) {
      d.nodes.insert(f->vertex(i));
      const Cdt::Face_handle n = f->neighbor(i);
      if(cdt.is_infinite(n) || !n->is_in_domain()) {
        boundary.insert(f->vertex(Cdt::cw(i)));
        boundary.insert(f->vertex(Cdt::ccw(i)));
      }
    }
  }
  for(Cdt::Vertex_handle v : boundary) {
    const Point& p = v->point();
    (is_on_naca0012_airfoil(p.x(), p.y()) ? d.airfoil : d.far_field).push_back(p);
  }
  return d;
}

// Shared by the test cases: generated once.
const Cdt& default_mesh()
{
  static const std::unique_ptr<Cdt> cdt = [] {
    auto c = std::make_unique<Cdt>();
    make_naca0012_mesh_2(*c);
    return c;
  }();
  return *cdt;
}

// Shared by the test cases: generated once.
const Cdt& fine_mesh()
{
  static const std::unique_ptr<Cdt> cdt = [] {
    auto c = std::make_unique<Cdt>();
    make_naca0012_mesh_2(*c, Naca0012_mesh_2_options::fine());
    return c;
  }();
  return *cdt;
}

void check_boundary_on_curves(const Domain& d, double radius)
{
  for(const Point& p : d.airfoil) {
    INFO("airfoil vertex " << p);
    CHECK(p.x() >= 0.0);
    CHECK(p.x() <= 1.0);
    CHECK(std::abs(std::abs(p.y()) - naca0012_half_thickness(p.x())) <= 1e-9);
  }
  for(const Point& p : d.far_field) {
    INFO("far-field vertex " << p);
    CHECK(std::abs(std::sqrt(CGAL::squared_distance(p, kFar_field_centre)) - radius) <= 1e-9);
  }
}

void check_positively_oriented(const Domain& d)
{
  std::size_t not_positive = 0;
  for(Cdt::Face_handle f : d.faces)
    if(CGAL::orientation(f->vertex(0)->point(), f->vertex(1)->point(), f->vertex(2)->point())
       != CGAL::LEFT_TURN)
      ++not_positive;
  CHECK(not_positive == 0);
}

} // namespace

TEST_CASE("naca0012_half_thickness: closed trailing edge, 12% thick at 30% chord",
          "[naca0012]")
{
  CHECK(naca0012_half_thickness(0.0) == 0.0);
  CHECK(std::abs(naca0012_half_thickness(1.0)) < 1e-15);
  // The coefficients sum to zero: the polynomial itself closes the trailing
  // edge, so the last point before x = 1 is already nearly closed.
  CHECK(naca0012_half_thickness(1.0 - 1e-9) < 1e-9);
  // Hand-evaluated: 0.6 (0.2969 sqrt(0.5) - 0.063 - 0.0879 + 0.0355375 - 0.006475).
  CHECK(naca0012_half_thickness(0.5) == Approx(0.0528615020).margin(1e-9));

  double best_x = 0.0, best_t = 0.0;
  for(int i = 0; i <= 100000; ++i) {
    const double x = i / 100000.0;
    const double t = 2.0 * naca0012_half_thickness(x);
    if(t > best_t) {
      best_t = t;
      best_x = x;
    }
  }
  CHECK(best_t == Approx(0.12).margin(1e-3));
  CHECK(best_x == Approx(0.30).margin(0.01));
}

TEST_CASE("is_on_naca0012_airfoil: airfoil against far field", "[naca0012]")
{
  CHECK(is_on_naca0012_airfoil(0.0, 0.0));
  CHECK(is_on_naca0012_airfoil(1.0, 0.0));
  CHECK(is_on_naca0012_airfoil(0.3, naca0012_half_thickness(0.3)));
  CHECK(is_on_naca0012_airfoil(0.7, -naca0012_half_thickness(0.7)));
  CHECK_FALSE(is_on_naca0012_airfoil(15.5, 0.0));
  CHECK_FALSE(is_on_naca0012_airfoil(-14.5, 0.0));
  CHECK_FALSE(is_on_naca0012_airfoil(0.5, 15.0));
  CHECK_FALSE(is_on_naca0012_airfoil(0.5, -15.0));
}

TEST_CASE("make_naca0012_mesh_2: default size is the paper's within 10%", "[naca0012]")
{
  const Domain d = domain_of(default_mesh());
  INFO(d.nodes.size() << " nodes, " << d.faces.size() << " triangles");
  CHECK(std::abs(double(d.nodes.size()) - 3875.0) <= 0.1 * 3875.0);
  CHECK(std::abs(double(d.faces.size()) - 7587.0) <= 0.1 * 7587.0);
  // Euler for a domain with one hole: the domain is the annulus, no more.
  CHECK(d.faces.size() == 2 * d.nodes.size() - d.airfoil.size() - d.far_field.size());
  // No segment split by Mesh_2: the boundary is exactly the input polylines.
  CHECK(d.airfoil.size() == 130);
  CHECK(d.far_field.size() == 33);
}

TEST_CASE("make_naca0012_mesh_2: domain triangles are positively oriented", "[naca0012]")
{
  const Domain d = domain_of(default_mesh());
  REQUIRE(!d.faces.empty());
  check_positively_oriented(d);
}

TEST_CASE("make_naca0012_mesh_2: domain triangles meet the shape bound", "[naca0012]")
{
  // Shape bound 0.125 is the squared sine of the smallest angle: 20.70 degrees.
  // The only small input angle, the trailing-edge wedge, is outside the domain.
  const double bound_degrees = std::asin(std::sqrt(0.125)) * 180.0 / CGAL_PI;
  const Domain d = domain_of(default_mesh());
  double smallest = 180.0;
  for(Cdt::Face_handle f : d.faces) {
    for(int i = 0; i < 3; ++i) {
      const Point& p = f->vertex(i)->point();
      const auto u = f->vertex(Cdt::cw(i))->point() - p;
      const auto v = f->vertex(Cdt::ccw(i))->point() - p;
      const double angle = std::acos(u * v / std::sqrt(u.squared_length() * v.squared_length()));
      smallest = std::min(smallest, angle * 180.0 / CGAL_PI);
    }
  }
  CHECK(smallest >= bound_degrees - 1e-9);
}

TEST_CASE("make_naca0012_mesh_2: the airfoil's interior is not in the domain", "[naca0012]")
{
  const Cdt& cdt = default_mesh();
  for(double x : {0.01, 0.3, 0.5, 0.9, 0.999}) {
    INFO("x = " << x);
    const Cdt::Face_handle f = cdt.locate(Point(x, 0.0));
    CHECK_FALSE(f->is_in_domain());
  }
  for(const Point& p : {Point(-0.01, 0.0), Point(1.01, 0.0), Point(0.5, 0.07), Point(0.5, 14.9)}) {
    INFO("p = " << p);
    CHECK(cdt.locate(p)->is_in_domain());
  }
}

TEST_CASE("make_naca0012_mesh_2: boundary vertices lie on the curves", "[naca0012]")
{
  const Domain d = domain_of(default_mesh());
  REQUIRE(d.airfoil.size() > 0);
  REQUIRE(d.far_field.size() > 0);
  check_boundary_on_curves(d, 15.0);

  // Both ends of the chord are vertices, and the spacing clusters there.
  CHECK(std::count(d.airfoil.begin(), d.airfoil.end(), Point(0.0, 0.0)) == 1);
  CHECK(std::count(d.airfoil.begin(), d.airfoil.end(), Point(1.0, 0.0)) == 1);
  double nearest_to_trailing_edge = 1.0, largest_gap_in_x = 0.0;
  std::vector<double> upper_x;
  for(const Point& p : d.airfoil) {
    if(p != Point(1.0, 0.0))
      nearest_to_trailing_edge = std::min(nearest_to_trailing_edge, 1.0 - p.x());
    if(p.y() >= 0.0)
      upper_x.push_back(p.x());
  }
  std::sort(upper_x.begin(), upper_x.end());
  for(std::size_t i = 1; i < upper_x.size(); ++i)
    largest_gap_in_x = std::max(largest_gap_in_x, upper_x[i] - upper_x[i - 1]);
  CHECK(nearest_to_trailing_edge < 0.05 * largest_gap_in_x);
}

TEST_CASE("make_naca0012_mesh_2: the same options give the same triangulation", "[naca0012]")
{
  Cdt first, second;
  make_naca0012_mesh_2(first);
  std::vector<int> garbage(12345, 7); // shift the heap so addresses differ
  make_naca0012_mesh_2(second);

  REQUIRE(first.number_of_vertices() == second.number_of_vertices());
  REQUIRE(first.number_of_faces() == second.number_of_faces());
  std::map<Cdt::Vertex_handle, std::size_t> index_first, index_second;
  auto v1 = first.finite_vertices_begin();
  auto v2 = second.finite_vertices_begin();
  std::size_t differing_points = 0;
  for(std::size_t i = 0; v1 != first.finite_vertices_end(); ++v1, ++v2, ++i) {
    const double a[2] = {v1->point().x(), v1->point().y()};
    const double b[2] = {v2->point().x(), v2->point().y()};
    if(std::memcmp(a, b, sizeof a) != 0)
      ++differing_points;
    index_first[v1] = i;
    index_second[v2] = i;
  }
  CHECK(differing_points == 0);

  std::size_t differing_faces = 0;
  auto f1 = first.finite_faces_begin();
  auto f2 = second.finite_faces_begin();
  for(; f1 != first.finite_faces_end(); ++f1, ++f2) {
    bool same = f1->is_in_domain() == f2->is_in_domain();
    for(int i = 0; i < 3; ++i)
      same = same && index_first[f1->vertex(i)] == index_second[f2->vertex(i)];
    if(!same)
      ++differing_faces;
  }
  CHECK(differing_faces == 0);
}

TEST_CASE("Naca0012_mesh_2_options::fine: about four times the nodes, same guarantees",
          "[naca0012]")
{
  const Domain coarse = domain_of(default_mesh());
  const Domain d = domain_of(fine_mesh());
  const double ratio = double(d.nodes.size()) / double(coarse.nodes.size());
  INFO(d.nodes.size() << " nodes, " << d.faces.size() << " triangles, ratio " << ratio);
  CHECK(ratio > 3.5);
  CHECK(ratio < 4.5);
  CHECK(d.airfoil.size() == 260);
  CHECK(d.far_field.size() == 66);
  CHECK(d.faces.size() == 2 * d.nodes.size() - d.airfoil.size() - d.far_field.size());
  check_positively_oriented(d);
  check_boundary_on_curves(d, 15.0);
}

TEST_CASE("make_naca0012_mesh_2: segments Mesh_2 would split are refined on the curve",
          "[naca0012]")
{
  // A uniform size at the airfoil finer than the mid-chord spacing makes
  // Mesh_2 split segments there; the generator must re-mesh with the curve
  // points instead of keeping midpoints of chords.
  Naca0012_mesh_2_options options;
  options.size_at_airfoil = 0.01;
  options.far_field_radius = 10.0;
  Cdt cdt;
  make_naca0012_mesh_2(cdt, options);
  const Domain d = domain_of(cdt);
  CHECK(d.airfoil.size() > options.airfoil_nodes);
  CHECK(d.faces.size() == 2 * d.nodes.size() - d.airfoil.size() - d.far_field.size());
  check_positively_oriented(d);
  check_boundary_on_curves(d, 10.0);
}

TEST_CASE("make_naca0012_mesh_2: invalid options throw", "[naca0012]")
{
  Cdt cdt;
  Naca0012_mesh_2_options odd;
  odd.airfoil_nodes = 131;
  CHECK_THROWS_AS(make_naca0012_mesh_2(cdt, odd), Error);
  Naca0012_mesh_2_options small_circle;
  small_circle.far_field_radius = 0.5;
  CHECK_THROWS_AS(make_naca0012_mesh_2(cdt, small_circle), Error);
  Naca0012_mesh_2_options bad_shape;
  bad_shape.shape_bound = 0.2;
  CHECK_THROWS_AS(make_naca0012_mesh_2(cdt, bad_shape), Error);
}
