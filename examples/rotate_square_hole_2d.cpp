// Rotates the square hole of a Mesh_2 domain by 30 degrees in 30 steps with
// every stiffness model and prints one table row per model.
#include <spring_motion/spring_motion.h>
#include <naca0012/Naca0012_mesh_2.h>

#include <CGAL/Delaunay_mesh_size_criteria_2.h>
#include <CGAL/Delaunay_mesher_2.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <list>
#include <string>

namespace sm = spring_motion;
using CDT = sm::Mesh_2_cdt;

// [-2,2]^2 with the hole [-0.5,0.5]^2, refined by Mesh_2
CDT make_domain()
{
  CDT cdt;
  auto square = [&](double s) {
    const CDT::Point c[4] = {{-s, -s}, {s, -s}, {s, s}, {-s, s}};
    for(int i = 0; i < 4; ++i)
      cdt.insert_constraint(c[i], c[(i + 1) % 4]);
  };
  square(2.0);
  square(0.5);
  std::list<CDT::Point> seeds{CDT::Point(0, 0)}; // the hole
  CGAL::refine_Delaunay_mesh_2(cdt, seeds.begin(), seeds.end(), CGAL::Delaunay_mesh_size_criteria_2<CDT>(0.125, 0.15));
  return cdt;
}

template <class Model>
void run(const std::string& name, const Model& model)
{
  CDT cdt = make_domain();
  auto on_hole = [](const std::array<double, 2>& p) { return std::max(std::abs(p[0]), std::abs(p[1])) < 1.0; };
  sm::Deform_options options;
  options.number_of_steps = 30;
  // the quarter-sine pitch schedule of the paper, 30 degrees about the centre
  const auto report = sm::deform(cdt, sm::moving_boundary_where(on_hole), sm::Pitch_motion<2>(30, {0, 0}), model, options);
  std::size_t total = 0, most = 0;
  for(const auto& s : report.steps) {
    total += s.iterations;
    most = std::max(most, s.iterations);
  }
  std::printf("%-14s %-9s %12s %10.2f %10.3f %7.0f / %-5zu %8.3f\n", name.c_str(), report.completed ? "yes" : "no",
              report.first_invalid ? std::to_string(report.first_invalid->step).c_str() : "-", report.final_angle_deg,
              report.quality_moving.max, double(total) / double(report.steps.size()), most, report.seconds_total);
}

int main()
{
  const CDT cdt = make_domain();
  std::printf("square [-2,2]^2 with hole [-0.5,0.5]^2: %zu vertices, hole rotated 30 deg in 30 steps\n\n",
              cdt.number_of_vertices());
  std::printf("%-14s %-9s %12s %10s %10s %15s %8s\n", "model", "completed", "first_invalid", "last_deg",
              "worst_R", "sweeps mean/max", "seconds");
  run("lineal", sm::Lineal_stiffness{});
  run("blom", sm::Blom_semi_torsional_stiffness{});
  run("zeng_ethier", sm::Zeng_Ethier_semi_torsional_stiffness{});
  run("grid_scaled", sm::Grid_scaled_stiffness{});
  run("torsional", sm::Torsional_stiffness{});
}
