// API misuse: every mistake a caller can make with the
// public API raises spring_motion::Error with a message that names the
// problem, in release builds too (CGAL's own preconditions vanish there).
#include <spring_motion/spring_motion.h>
#include <spring_motion/stiffness/model_by_name.h>

#include "test_meshes.h"

#include <catch2/catch.hpp>

#include <cmath>
#include <limits>

using namespace spring_motion;
using Catch::Contains;

namespace {

constexpr double k_nan = std::numeric_limits<double>::quiet_NaN();
constexpr double k_inf = std::numeric_limits<double>::infinity();

// The unit square split into four triangles around the centre vertex 4.
Indexed_mesh<2> four_triangles()
{
  Indexed_mesh<2> mesh;
  mesh.points = {{0, 0}, {1, 0}, {1, 1}, {0, 1}, {0.5, 0.5}};
  mesh.elements = {{0, 1, 4}, {1, 2, 4}, {2, 3, 4}, {3, 0, 4}};
  return mesh;
}

Vertex_role centre_moves(const Vertex_info<2>& v)
{
  return v.index == 4 ? Vertex_role::moving : Vertex_role::fixed;
}

// An edge model returning the same value on every edge.
struct Bad_edge_model
{
  double value;
  Angle_kind angle_kind(int) const { return Angle_kind::none; }
  double operator()(double, const double*, std::size_t, const Stiffness_context&) const { return value; }
  Model_description description(int) const { return {"bad_edge_model", {}}; }
};

// An element model whose element matrix holds one non-finite entry.
struct Bad_element_model
{
  double entry;
  Angle_kind angle_kind(int) const { return Angle_kind::none; }
  double operator()(double, const double*, std::size_t, const Stiffness_context&) const { return 1.0; }
  void add_element_matrix(const std::array<std::array<double, 2>, 3>&, double* K) const { K[7] += entry; }
};

// A motion that places the moving vertex at `bad` from t > after on.
struct Poisoned_motion
{
  double bad;
  double after;
  std::array<double, 2> operator()(const std::array<double, 2>& p, double t) const
  {
    if(t > after)
      return {bad, p[1]};
    return {p[0] + 0.1 * t, p[1]};
  }
};

} // namespace

TEST_CASE("api misuse: free vertices that reach no constrained vertex", "[errors][api]")
{
  // two triangles sharing nothing: the second has no constrained vertex
  Indexed_mesh<2> mesh;
  mesh.points = {{0, 0}, {1, 0}, {0, 1}, {5, 5}, {6, 5}, {5, 6}};
  mesh.elements = {{0, 1, 2}, {3, 4, 5}};
  auto roles = [](const Vertex_info<2>& v) { return v.index < 3 ? Vertex_role::moving : Vertex_role::free; };
  REQUIRE_THROWS_WITH(deform(mesh, roles, Translation_motion<2>{{0.1, 0}}, Lineal_stiffness{}),
                      Contains("3 free vertices") && Contains("connected to no constrained vertex") &&
                          Contains("singular"));
  // the same network through the stateful interface
  auto net = make_spring_network<2>(mesh.points, mesh.elements);
  REQUIRE_THROWS_WITH(Network_deformer<2>(net, assign_roles(net, roles)), Contains("connected to no constrained vertex"));
}

TEST_CASE("api misuse: no moving vertex, wrong number of roles", "[errors][api]")
{
  auto mesh = four_triangles();
  auto all_fixed = [](const Vertex_info<2>& v) { return v.on_boundary ? Vertex_role::fixed : Vertex_role::free; };
  REQUIRE_THROWS_WITH(deform(mesh, all_fixed, Translation_motion<2>{{0.1, 0}}, Lineal_stiffness{}),
                      Contains("no vertex is moving"));
  auto net = make_spring_network<2>(mesh.points, mesh.elements);
  REQUIRE_THROWS_WITH(Network_deformer<2>(net, std::vector<Vertex_role>(3, Vertex_role::moving)),
                      Contains("got 3 vertex roles for 5 vertices"));
}

TEST_CASE("api misuse: an empty mesh", "[errors][api]")
{
  Indexed_mesh<2> empty;
  REQUIRE_THROWS_WITH(deform(empty, All_boundary_moving{}, Translation_motion<2>{{0.1, 0}}, Lineal_stiffness{}),
                      Contains("the mesh has no elements"));
  // vertices but no elements is empty too
  empty.points = {{0, 0}, {1, 0}, {0, 1}};
  REQUIRE_THROWS_WITH(deform(empty, All_boundary_moving{}, Translation_motion<2>{{0.1, 0}}, Lineal_stiffness{}),
                      Contains("the mesh has no elements"));
  // a CGAL triangulation with no domain face
  spring_motion_test::CDT cdt;
  REQUIRE_THROWS_WITH(deform(cdt, All_boundary_moving{}, Translation_motion<2>{{0.1, 0}}, Lineal_stiffness{}),
                      Contains("the mesh has no elements"));
  Indexed_mesh<3> empty_3;
  REQUIRE_THROWS_WITH(deform(empty_3, All_boundary_moving{}, Translation_motion<3>{{0.1, 0, 0}}, Lineal_stiffness{}),
                      Contains("the mesh has no elements"));
}

TEST_CASE("api misuse: non-finite coordinates", "[errors][api]")
{
  for(double bad : {k_nan, k_inf, -k_inf}) {
    auto mesh = four_triangles();
    mesh.points[2][1] = bad;
    REQUIRE_THROWS_WITH(deform(mesh, centre_moves, Translation_motion<2>{{0.1, 0}}, Lineal_stiffness{}),
                        Contains("vertex 2 has a non-finite coordinate"));
  }
  // an unused vertex is checked too: it is still written back
  auto mesh = four_triangles();
  mesh.points.push_back({k_nan, 0});
  REQUIRE_THROWS_WITH(make_spring_network<2>(mesh.points, mesh.elements), Contains("vertex 5 has a non-finite coordinate"));
}

TEST_CASE("api misuse: malformed elements and degenerate input", "[errors][api]")
{
  auto mesh = four_triangles();
  mesh.elements[1][2] = 9;
  REQUIRE_THROWS_WITH(make_spring_network<2>(mesh.points, mesh.elements), Contains("element 1 uses vertex 9, out of range"));
  mesh = four_triangles();
  mesh.elements[3] = {3, 0, 3};
  REQUIRE_THROWS_WITH(make_spring_network<2>(mesh.points, mesh.elements), Contains("element 3 repeats vertex 3"));
  // a flat triangle: its orientation is zero, no motion can keep it valid
  mesh = four_triangles();
  mesh.points[4] = {0.5, 0.0};
  REQUIRE_THROWS_WITH(deform(mesh, centre_moves, Translation_motion<2>{{0.1, 0}}, Lineal_stiffness{}),
                      Contains("1 degenerate element(s) in the input mesh") && Contains(": 0"));
  // a zero-length edge: two vertices at the same point
  mesh = four_triangles();
  mesh.points[4] = mesh.points[1];
  REQUIRE_THROWS_WITH(deform(mesh, centre_moves, Translation_motion<2>{{0.1, 0}}, Lineal_stiffness{}),
                      Contains("degenerate element(s) in the input mesh"));
}

TEST_CASE("api misuse: a motion functor that returns NaN or infinity", "[errors][api]")
{
  for(double bad : {k_nan, k_inf, -k_inf}) {
    auto mesh = four_triangles();
    const auto before = mesh.points;
    Deform_options options;
    options.number_of_steps = 4;
    // the first two steps are fine, the third gives a non-finite position
    REQUIRE_THROWS_WITH(deform(mesh, centre_moves, Poisoned_motion{bad, 0.6}, Lineal_stiffness{}, options),
                        Contains("the motion gave a non-finite position for vertex 4 at motion fraction 0.75"));
    // deform() throws before writing back: the mesh is untouched
    CHECK(mesh.points == before);
  }
}

TEST_CASE("api misuse: a stiffness model returning a negative or non-finite value", "[errors][api]")
{
  for(double bad : {-1.0, k_nan, k_inf, -k_inf}) {
    auto mesh = four_triangles();
    REQUIRE_THROWS_WITH(deform(mesh, centre_moves, Translation_motion<2>{{0.1, 0}}, Bad_edge_model{bad}),
                        Contains("stiffness model 'bad_edge_model' gave k = ") &&
                            Contains("expected a finite value >= 0"));
  }
  // zero is allowed on some edges, but a free vertex needs some stiffness
  Indexed_mesh<2> strip;
  strip.points = {{0, 0}, {1, 0}, {2, 0}, {0, 1}, {1, 1}, {2, 1}, {0.5, 0.5}};
  strip.elements = {{0, 1, 6}, {1, 4, 6}, {4, 3, 6}, {3, 0, 6}, {1, 2, 5}, {1, 5, 4}};
  auto roles = [](const Vertex_info<2>& v) {
    return v.index == 6 ? Vertex_role::free : (v.index == 2 ? Vertex_role::moving : Vertex_role::fixed);
  };
  REQUIRE_THROWS_WITH(deform(strip, roles, Translation_motion<2>{{0.1, 0}}, Bad_edge_model{0.0}),
                      Contains("free vertex 6 has zero total stiffness"));
  // an element model whose matrix is not finite
  for(double bad : {k_nan, k_inf}) {
    auto mesh = four_triangles();
    REQUIRE_THROWS_WITH(deform(mesh, centre_moves, Translation_motion<2>{{0.1, 0}}, Bad_element_model{bad}),
                        Contains("element stiffness of element 0 is not finite"));
  }
}

TEST_CASE("api misuse: options out of range", "[errors][api]")
{
  auto mesh = four_triangles();
  Deform_options options;
  options.number_of_steps = 0;
  REQUIRE_THROWS_WITH(deform(mesh, centre_moves, Translation_motion<2>{{0.1, 0}}, Lineal_stiffness{}, options),
                      Contains("number_of_steps must be positive"));
  for(double omega : {0.0, 2.0, k_nan}) {
    options = Deform_options{};
    options.solver.method = Solver_method::sor;
    options.solver.relaxation_factor = omega;
    REQUIRE_THROWS_WITH(deform(mesh, centre_moves, Translation_motion<2>{{0.1, 0}}, Lineal_stiffness{}, options),
                        Contains("relaxation"));
  }
  for(double tol : {0.0, -1.0, k_nan, k_inf}) {
    options = Deform_options{};
    options.solver.tolerance = tol;
    REQUIRE_THROWS_WITH(deform(mesh, centre_moves, Translation_motion<2>{{0.1, 0}}, Lineal_stiffness{}, options),
                        Contains("tolerance"));
  }
  REQUIRE_THROWS_WITH(with_model("springy", [](const auto&) { return 0; }),
                      Contains("unknown stiffness model 'springy'") && Contains("grid_scaled"));
}

TEST_CASE("api misuse: torsional springs do not combine with ball-vertex springs", "[errors][api]")
{
  REQUIRE_THROWS_WITH(with_model("torsional+ball_vertex", [](const auto&) { return 0; }),
                      Contains("combine with an edge model only") && Contains("grid_scaled+ball_vertex"));
}
