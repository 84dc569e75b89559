// A stiffness model of your own, passed to deform().
//
// An edge model is any type with angle_kind() (which angles it reads) and
// operator() (k from the edge's current length and those angles); see the
// EdgeStiffnessModel concept in spring_motion/stiffness/Stiffness_model.h.
// description() is optional: it names the model in reports.
#include <spring_motion/spring_motion.h>
#include <naca0012/Naca0012_mesh_2.h>

#include <CGAL/Delaunay_mesh_size_criteria_2.h>
#include <CGAL/Delaunay_mesher_2.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <list>

namespace sm = spring_motion;
using CDT = sm::Mesh_2_cdt;

// Lineal springs stiffened by the cotangents of the facing angles:
// k = (1/l) (1 + sum_m cot^2 theta_m). cot^2 grows without bound as an angle
// closes (theta -> 0) or opens (theta -> pi), so an edge facing a collapsing
// triangle resists; it vanishes at right angles.
struct Cotangent_stiffness
{
  sm::Angle_kind angle_kind(int /*dimension*/) const { return sm::Angle_kind::element; }

  double operator()(double length, const double* angles, std::size_t n, const sm::Stiffness_context&) const
  {
    double s = 1;
    for(std::size_t m = 0; m < n; ++m) {
      const double t = std::tan(angles[m]);
      s += 1 / std::max(t * t, 1e-200); // a flat element gives a huge finite k
    }
    return std::min(s / length, 1e250);
  }

  sm::Model_description description(int) const { return {"cotangent", {}}; }
};

int main()
{
  // [-2,2]^2 with the hole [-0.5,0.5]^2, refined by Mesh_2
  CDT mesh;
  auto square = [&](double s) {
    const CDT::Point c[4] = {{-s, -s}, {s, -s}, {s, s}, {-s, s}};
    for(int i = 0; i < 4; ++i)
      mesh.insert_constraint(c[i], c[(i + 1) % 4]);
  };
  square(2.0);
  square(0.5);
  std::list<CDT::Point> seeds{CDT::Point(0, 0)}; // the hole
  CGAL::refine_Delaunay_mesh_2(mesh, seeds.begin(), seeds.end(), CGAL::Delaunay_mesh_size_criteria_2<CDT>(0.125, 0.15));

  // the hole turns by 60 degrees in 30 steps; the outer square stays
  auto on_hole = [](const std::array<double, 2>& p) { return std::max(std::abs(p[0]), std::abs(p[1])) < 1.0; };
  sm::Deform_options options;
  options.number_of_steps = 30;
  CDT lineal = mesh;
  const auto with_lineal = sm::deform(lineal, sm::moving_boundary_where(on_hole), sm::Pitch_motion<2>(60, {0, 0}),
                                      sm::Lineal_stiffness{}, options);
  const auto with_ours = sm::deform(mesh, sm::moving_boundary_where(on_hole), sm::Pitch_motion<2>(60, {0, 0}),
                                    Cotangent_stiffness{}, options);

  std::printf("%-10s %-9s %10s %18s\n", "model", "completed", "last_deg", "worst_R_near_hole");
  for(const auto* r : {&with_lineal, &with_ours})
    std::printf("%-10s %-9s %10.2f %18.3f\n", r->model.name.c_str(), r->completed ? "yes" : "no", r->final_angle_deg,
                r->quality_moving.max);
}
