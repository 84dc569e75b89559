// deform() on a CGAL Mesh_complex_3_in_triangulation_3 (a Mesh_3 result):
// the cells in the complex are the elements, the facets in the complex on its
// boundary carry their surface patch index as label. Here the complex is read
// from a Medit file, whose triangle references become the patch indices, and
// the cubic hole (patch 2) turns by 20 degrees about the z axis.
//
//   deform_c3t3 [mesh]   (default: data/cube_hole_3d.mesh)
#include <spring_motion/spring_motion.h>

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/IO/File_medit.h>
#include <CGAL/Mesh_3/tet_soup_to_c3t3.h> // defines what read_MEDIT() calls
#include <CGAL/Mesh_complex_3_in_triangulation_3.h>
#include <CGAL/Mesh_triangulation_3.h>

#include <cstdio>
#include <fstream>
#include <string>

using K = CGAL::Exact_predicates_inexact_constructions_kernel;
// A Mesh_3 triangulation needs a domain type only for its index types; the
// Medit references are integers
struct Medit_indices
{
  using Subdomain_index = int;
  using Surface_patch_index = int;
  using Index = int;
};
using Tr = CGAL::Mesh_triangulation_3<Medit_indices, K>::type;
using C3t3 = CGAL::Mesh_complex_3_in_triangulation_3<Tr>;
namespace sm = spring_motion;

int main(int argc, char** argv)
{
  const std::string path = argc > 1 ? argv[1] : SPRING_MOTION_DATA_DIR "/cube_hole_3d.mesh";
  std::ifstream in(path);
  C3t3 c3t3;
  if(!in || !CGAL::IO::read_MEDIT(in, c3t3.triangulation())) {
    std::fprintf(stderr, "%s: cannot read a Medit tetrahedral mesh\n", path.c_str());
    return 1;
  }
  c3t3.rescan_after_load_of_triangulation(); // the cells and facets in the complex

  sm::Pitch_motion<3> turn;
  turn.amplitude_deg = 20;
  turn.center = {0, 0, 0};
  turn.axis = {0, 0, 1};
  sm::Deform_options options;
  options.number_of_steps = 20;
  const auto report =
      sm::deform(c3t3, sm::Moving_boundary_labels{{2}}, turn, sm::Grid_scaled_stiffness{}, options);

  std::printf("%s: %zu cells in the complex; %zu moving, %zu fixed vertices; turned to %.1f deg, %s; "
              "worst skewness near the hole %.3f\n",
              path.c_str(), c3t3.number_of_cells_in_complex(), report.moving_vertices, report.fixed_vertices,
              report.final_angle_deg, report.completed ? "completed" : "stopped", report.quality_moving.max);
  return report.completed ? 0 : 1;
}
