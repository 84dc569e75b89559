// The stateful side of deform(): a Network_deformer keeps the spring network
// and the current positions between the time steps of a flow solver. Here
// the hole of a 2D mesh oscillates, alpha(t) = 15 sin(2 pi t / T) degrees,
// and each time step moves the mesh to the new angle from where it is.
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

  // one run() per time step, of a single step: the motion gives the hole's
  // position at the new time from its initial points
  sm::Deform_options options;
  options.number_of_steps = 1;
  // the warm start's extrapolation assumes increasing motion fractions within
  // one run; every run here is the fraction 0 -> 1 again
  options.solver.extrapolate = false;
  const sm::Grid_scaled_stiffness model;

  const int steps_per_period = 20, time_steps = 40; // two periods
  std::printf("%5s %8s %9s %7s %15s\n", "step", "alpha", "completed", "sweeps", "min_area_ratio");
  for(int n = 1; n <= time_steps; ++n) {
    const double alpha = 15 * std::sin(2 * M_PI * n / steps_per_period);
    // a Pitch_motion's angle at fraction 1 is its amplitude
    const auto report = deformer.run(sm::Pitch_motion<2>(alpha, {0, 0}), model, options);
    // ... here the flow solver would advance on deformer.positions() ...
    std::printf("%5d %8.2f %9s %7zu %15.3f\n", n, alpha, report.completed ? "yes" : "no",
                report.steps.back().iterations, deformer.min_size_ratio());
    if(!report.completed)
      return 1;
  }
}
