// deform() in 3D on CGAL meshes: a Delaunay Triangulation_3 and a Mesh_3
// complex (a box with a box-shaped hole, made by the library's Mesh_3 domain).
#include <spring_motion/deform.h>
#include "test_meshes.h"
#include <naca0012/Naca0012_wing_mesh_3.h>
#include <spring_motion/mesh_traits/Mesh_complex_3_in_triangulation_3.h>
#include <spring_motion/mesh_traits/Triangulation_3.h>
#include <spring_motion/motion/Pitch_motion.h>
#include <spring_motion/stiffness/Grid_scaled_stiffness.h>
#include <spring_motion/stiffness/Lineal_stiffness.h>
#include <spring_motion/stiffness/model_by_name.h>

#include <CGAL/Delaunay_triangulation_3.h>

#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <map>
#include <vector>

using namespace spring_motion;

namespace {

using K = Mesh_3_kernel;
using Tr = Mesh_3_c3t3::Triangulation;

// Initial position (and weight) of every complex vertex, by handle.
struct Snapshot
{
  std::map<Tr::Vertex_handle, std::array<double, 4>> v;
  explicit Snapshot(const Mesh_3_c3t3& c)
  {
    for(auto h : c.triangulation().finite_vertex_handles()) {
      const auto& wp = h->point();
      v[h] = {wp.x(), wp.y(), wp.z(), wp.weight()};
    }
  }
};

const Mesh_3_c3t3& box_with_hole()
{
  static const Mesh_3_c3t3 c3t3 = [] {
    Mesh_3_c3t3 c;
    make_box_with_hole_mesh_3(c);
    return c;
  }();
  return c3t3;
}

// Every cell in the complex is positively oriented (CGAL's convention, and
// that of the unmoved mesh), decided by the exact predicate.
std::size_t non_positive_cells(const Mesh_3_c3t3& c)
{
  std::size_t bad = 0;
  for(auto cit = c.cells_in_complex_begin(); cit != c.cells_in_complex_end(); ++cit) {
    std::array<K::Point_3, 4> p;
    for(int k = 0; k < 4; ++k)
      p[k] = cit->vertex(k)->point().point();
    bad += CGAL::orientation(p[0], p[1], p[2], p[3]) != CGAL::POSITIVE;
  }
  return bad;
}

double box_norm(const std::array<double, 4>& p) { return std::max({std::abs(p[0]), std::abs(p[1]), std::abs(p[2])}); }

} // namespace

TEST_CASE("deform 3D: a rigid translation of a Triangulation_3's hull translates every vertex", "[deform][3d]")
{
  CGAL::Delaunay_triangulation_3<K> dt;
  // a jittered 5x5x5 grid: deterministic, no four points cospherical
  for(int i = 0; i < 5; ++i)
    for(int j = 0; j < 5; ++j)
      for(int k = 0; k < 5; ++k)
        dt.insert(K::Point_3(i + 0.1 * std::sin(i + 7 * j + 31 * k), j + 0.1 * std::sin(3 * i + j + 11 * k),
                             k + 0.1 * std::sin(5 * i + 13 * j + k)));
  const auto before = extract_spring_network(dt).network;
  REQUIRE(before.number_of_vertices() == 125);
  const std::array<double, 3> d{0.3, -0.2, 0.7};
  Deform_options options;
  options.number_of_steps = 4;
  // the stopping criterion is not the error: ask for one far below the
  // round-off we then check against (a uniform field is every system's exact solution)
  options.solver.tolerance = 1e-16;
  const auto report = deform(dt, All_boundary_moving{}, Translation_motion<3>{d}, Grid_scaled_stiffness{}, options);
  REQUIRE(report.completed);
  REQUIRE(report.converged);
  CHECK(report.dimension == 3);
  const auto after = extract_spring_network(dt).network; // same traversal order: same numbering
  REQUIRE(after.number_of_vertices() == before.number_of_vertices());
  double worst = 0;
  for(std::size_t i = 0; i < before.number_of_vertices(); ++i)
    for(int c = 0; c < 3; ++c)
      worst = std::max(worst, std::abs(after.points[i][c] - (before.points[i][c] + d[c])));
  INFO("worst deviation " << worst);
  CHECK(worst < 1e-12);
}

TEST_CASE("deform 3D: the Mesh_3 box with a hole has labelled boundary patches", "[deform][3d][mesh_3]")
{
  const auto& c3t3 = box_with_hole();
  const auto net = extract_spring_network(c3t3).network;
  INFO(net.number_of_vertices() << " vertices, " << net.number_of_elements() << " tetrahedra");
  CHECK(net.number_of_elements() > 500);
  CHECK(net.number_of_elements() < 5000);
  CHECK(net.number_of_elements() == c3t3.number_of_cells_in_complex());
  // every boundary vertex lies on the hole (label 1) or on the outer box
  // (label 2), never both; Mesh_3 constructs surface points by intersection,
  // so they are on the planes up to its construction's rounding
  const Box_with_hole_mesh_3_options o;
  std::size_t on_hole = 0, on_outer = 0;
  for(Index i = 0; i < net.number_of_vertices(); ++i) {
    const int* b = net.vertex_labels.data() + net.vertex_label_offsets[i];
    const int* e = net.vertex_labels.data() + net.vertex_label_offsets[i + 1];
    const auto& p = net.points[i];
    const double r = std::max({std::abs(p[0]), std::abs(p[1]), std::abs(p[2])});
    if(!net.on_boundary[i]) {
      CHECK(b == e);
      continue;
    }
    REQUIRE(e - b == 1);
    if(*b == body_patch) {
      ++on_hole;
      CHECK(std::abs(r - o.inner) < 1e-12);
    } else {
      CHECK(*b == outer_patch);
      ++on_outer;
      CHECK(std::abs(r - o.outer) < 1e-12);
    }
  }
  CHECK(on_hole > 8);
  CHECK(on_outer > on_hole);
}

TEST_CASE("deform 3D: a rigid translation of the whole C3T3 boundary translates every vertex", "[deform][3d][mesh_3]")
{
  Mesh_3_c3t3 c3t3 = box_with_hole();
  const Snapshot s0(c3t3);
  const std::array<double, 3> d{-0.25, 0.5, 0.125};
  Deform_options options;
  options.number_of_steps = 2;
  options.solver.tolerance = 1e-16; // as above: far below the checked round-off
  const auto report = deform(c3t3, All_boundary_moving{}, Translation_motion<3>{d}, Lineal_stiffness{}, options);
  REQUIRE(report.completed);
  double worst = 0;
  for(const auto& [h, p0] : s0.v) {
    const auto& wp = h->point();
    if(c3t3.in_dimension(h) == -1)
      continue;
    worst = std::max({worst, std::abs(wp.x() - (p0[0] + d[0])), std::abs(wp.y() - (p0[1] + d[1])),
                      std::abs(wp.z() - (p0[2] + d[2]))});
    CHECK(wp.weight() == p0[3]); // the weight is kept
  }
  INFO("worst deviation " << worst);
  CHECK(worst < 1e-12);
}

TEST_CASE("deform 3D: the hole of the Mesh_3 box turns by 20 degrees with every 3D model", "[deform][3d][mesh_3]")
{
  for(const std::string model : {"lineal", "blom", "zeng_ethier", "grid_scaled"}) {
    DYNAMIC_SECTION(model)
    {
      Mesh_3_c3t3 c3t3 = box_with_hole();
      const Snapshot s0(c3t3);
      Pitch_motion<3> motion;
      motion.amplitude_deg = 20;
      motion.center = {0, 0, 0};
      motion.axis = {0.0, 0.0, 1.0};
      Deform_options options;
      options.number_of_steps = 10;
      const auto report = with_model(model, [&](const auto& m) {
        return deform(c3t3, Moving_boundary_labels{{body_patch}}, motion, m, options);
      });
      INFO(report.moving_vertices << " moving, " << report.fixed_vertices << " fixed vertices");
      REQUIRE(report.completed);
      CHECK(report.converged);
      CHECK(report.moving_vertices > 8);
      // checked independently of the library: every cell still positive
      CHECK(non_positive_cells(c3t3) == 0);
      // the hole's vertices exactly where the motion puts them, the outer
      // box's exactly where they were
      const Box_with_hole_mesh_3_options o;
      std::size_t moved = 0, kept = 0;
      for(const auto& [h, p0] : s0.v) {
        if(c3t3.in_dimension(h) > 2)
          continue; // interior
        const auto& wp = h->point();
        const std::array<double, 3> now{wp.x(), wp.y(), wp.z()};
        if(box_norm(p0) < 0.5 * (o.inner + o.outer)) {
          CHECK(now == motion({p0[0], p0[1], p0[2]}, 1.0));
          ++moved;
        } else {
          CHECK(now == std::array<double, 3>{p0[0], p0[1], p0[2]});
          ++kept;
        }
      }
      CHECK(moved == report.moving_vertices);
      CHECK(kept == report.fixed_vertices);
      // the last step's quality, found in one pass that passes over most
      // elements, equals the final report's, computed element by element
      const auto& last = report.steps.back();
      CHECK(last.max_skewness_all == report.quality_all.max);
      CHECK(last.max_skewness_moving == report.quality_moving.max);
      CHECK(last.min_angle_deg_all == report.min_angle_deg_all);
      CHECK(last.min_angle_deg_moving == report.min_angle_deg_moving);
      CHECK(last.min_size_ratio == report.min_size_ratio);
      CHECK(last.max_size_ratio == report.max_size_ratio);
    }
  }
}

