// A flow solver's time loop: a Network_deformer keeps the spring network,
// its solver state and the current positions between time steps, and each
// move() is given the body's displacement from its INITIAL position (so
// nothing drifts). Here the hole of a 2D mesh oscillates,
// alpha(t) = 15 sin(2 pi t / T) degrees, for two periods.
//
//   network_deformer_2d [mesh]   (default: data/square_hole_2d.mesh)
//
// The hole is the boundary with label 2; it turns about the origin. The
// interior's path matters: back at 0 degrees the mesh is not the initial one
// (the smallest area ratio stays below 1).
#include <spring_motion/spring_motion.h>
#include <spring_motion/io/read_mesh.h>

#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

namespace sm = spring_motion;

int main(int argc, char** argv)
{
  const std::string path = argc > 1 ? argv[1] : SPRING_MOTION_DATA_DIR "/square_hole_2d.mesh";
  const sm::Mesh_file file = sm::read_mesh(path);
  if(file.dimension != 2) {
    std::fprintf(stderr, "%s is not a 2D mesh\n", path.c_str());
    return 1;
  }
  auto network = sm::extract_spring_network(file.mesh_2).network;
  auto roles = sm::assign_roles(network, sm::Moving_boundary_labels{{2}});
  sm::Network_deformer<2> deformer(std::move(network), std::move(roles));
  const sm::Grid_scaled_stiffness model;

  const int steps_per_period = 20, time_steps = 40; // two periods
  const auto& moving = deformer.moving_vertices();
  std::vector<std::array<double, 2>> displacement(moving.size());
  std::printf("%5s %8s %6s %7s %15s\n", "step", "alpha", "valid", "sweeps", "min_area_ratio");
  for(int n = 1; n <= time_steps; ++n) {
    const double alpha = 15 * std::sin(2 * M_PI * n / steps_per_period) * M_PI / 180;
    // ... here the structure solver would give the body's new position ...
    for(std::size_t k = 0; k < moving.size(); ++k) {
      const auto& p = deformer.network().points[moving[k]];
      displacement[k] = {std::cos(alpha) * p[0] - std::sin(alpha) * p[1] - p[0],
                         std::sin(alpha) * p[0] + std::cos(alpha) * p[1] - p[1]};
    }
    const sm::Step_report step = deformer.move(displacement, model);
    // ... and the flow solver would advance on deformer.positions() ...
    std::printf("%5d %8.2f %6s %7zu %15.3f\n", n, alpha * 180 / M_PI, step.inverted == 0 ? "yes" : "no",
                step.iterations, deformer.min_size_ratio());
    if(step.inverted != 0)
      return 1; // the positions are still the last valid ones
  }
}
