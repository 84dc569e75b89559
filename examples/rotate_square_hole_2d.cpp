// Rotates the hole of a 2D mesh file by 30 degrees in 30 steps with every
// stiffness model and prints one table row per model.
//
//   rotate_square_hole_2d [mesh]   (default: data/square_hole_2d.mesh)
//
// The mesh is read with read_mesh() (Medit or Gmsh); its boundary edges with
// label 2 (the hole) turn about the origin, the rest of the boundary stays.
#include <spring_motion/spring_motion.h>
#include <spring_motion/io/read_mesh.h>

#include <algorithm>
#include <cstdio>
#include <string>

namespace sm = spring_motion;

template <class Model>
void run(const sm::Indexed_mesh<2>& input, const std::string& name, const Model& model)
{
  sm::Indexed_mesh<2> mesh = input; // deform() moves the mesh it is given
  sm::Deform_options options;
  options.number_of_steps = 30;
  // the quarter-sine pitch schedule of the paper, 30 degrees about the origin
  const auto report =
      sm::deform(mesh, sm::Moving_boundary_labels{{2}}, sm::Pitch_motion<2>(30, {0, 0}), model, options);
  std::size_t total = 0, most = 0;
  for(const auto& s : report.steps) {
    total += s.iterations;
    most = std::max(most, s.iterations);
  }
  std::printf("%-14s %-9s %12s %10.2f %10.3f %7.0f / %-5zu %8.3f\n", name.c_str(), report.completed ? "yes" : "no",
              report.first_invalid ? std::to_string(report.first_invalid->step).c_str() : "-", report.final_angle_deg,
              report.quality_moving.max, double(total) / double(report.steps.size()), most, report.seconds_total);
}

int main(int argc, char** argv)
{
  const std::string path = argc > 1 ? argv[1] : SPRING_MOTION_DATA_DIR "/square_hole_2d.mesh";
  const sm::Mesh_file file = sm::read_mesh(path);
  if(file.dimension != 2) {
    std::fprintf(stderr, "%s is not a 2D mesh\n", path.c_str());
    return 1;
  }
  std::printf("%s: %zu vertices, %zu triangles; hole (label 2) rotated 30 deg in 30 steps\n\n", path.c_str(),
              file.mesh_2.points.size(), file.mesh_2.elements.size());
  std::printf("%-14s %-9s %12s %10s %10s %15s %8s\n", "model", "completed", "first_invalid", "last_deg", "worst_R",
              "sweeps mean/max", "seconds");
  run(file.mesh_2, "lineal", sm::Lineal_stiffness{});
  run(file.mesh_2, "blom", sm::Blom_semi_torsional_stiffness{});
  run(file.mesh_2, "zeng_ethier", sm::Zeng_Ethier_semi_torsional_stiffness{});
  run(file.mesh_2, "grid_scaled", sm::Grid_scaled_stiffness{});
  run(file.mesh_2, "torsional", sm::Torsional_stiffness{});
}
