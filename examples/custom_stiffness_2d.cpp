// A stiffness model of your own, passed to deform().
//
// An edge model is any type with angle_kind() (which angles it reads) and
// operator() (k from the edge's current length and those angles); see the
// EdgeStiffnessModel concept in spring_motion/stiffness/Stiffness_model.h.
// description() is optional: it names the model in reports.
//
//   custom_stiffness_2d [mesh]   (default: data/square_hole_2d.mesh)
//
// The hole (boundary label 2) turns by 60 degrees about the origin.
#include <spring_motion/spring_motion.h>
#include <spring_motion/io/read_mesh.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>

namespace sm = spring_motion;

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

int main(int argc, char** argv)
{
  const std::string path = argc > 1 ? argv[1] : SPRING_MOTION_DATA_DIR "/square_hole_2d.mesh";
  const sm::Mesh_file file = sm::read_mesh(path);
  if(file.dimension != 2) {
    std::fprintf(stderr, "%s is not a 2D mesh\n", path.c_str());
    return 1;
  }

  // the hole turns by 60 degrees in 30 steps; the outer boundary stays
  sm::Deform_options options;
  options.number_of_steps = 30;
  const sm::Pitch_motion<2> motion(60, {0, 0});
  sm::Indexed_mesh<2> lineal = file.mesh_2, ours = file.mesh_2;
  const auto with_lineal = sm::deform(lineal, sm::Moving_boundary_labels{{2}}, motion, sm::Lineal_stiffness{}, options);
  const auto with_ours = sm::deform(ours, sm::Moving_boundary_labels{{2}}, motion, Cotangent_stiffness{}, options);

  std::printf("%-10s %-9s %10s %18s\n", "model", "completed", "last_deg", "worst_R_near_hole");
  for(const auto* r : {&with_lineal, &with_ours})
    std::printf("%-10s %-9s %10.2f %18.3f\n", r->model.name.c_str(), r->completed ? "yes" : "no", r->final_angle_deg,
                r->quality_moving.max);
}
