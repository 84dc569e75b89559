// deform() on a CGAL Triangulation_3 (here the Delaunay triangulation of a
// point set): every finite cell is an element and the convex hull is the
// boundary. The top face of a box slides sideways while the other faces
// stay, shearing the interior.
//
//   deform_triangulation_3 [points]   (default: data/box_points_3d.xyz)
//
// The file holds one point "x y z" per line; the top face is the hull
// vertices at the largest z.
#include <spring_motion/spring_motion.h>

#include <CGAL/Delaunay_triangulation_3.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>

#include <algorithm>
#include <cstdio>
#include <fstream>
#include <string>
#include <vector>

using K = CGAL::Exact_predicates_inexact_constructions_kernel;
using Triangulation = CGAL::Delaunay_triangulation_3<K>;
namespace sm = spring_motion;

int main(int argc, char** argv)
{
  const std::string path = argc > 1 ? argv[1] : SPRING_MOTION_DATA_DIR "/box_points_3d.xyz";
  std::ifstream in(path);
  std::vector<K::Point_3> points;
  for(double x, y, z; in >> x >> y >> z;)
    points.emplace_back(x, y, z);
  if(points.size() < 5) {
    std::fprintf(stderr, "%s: need at least 5 points\n", path.c_str());
    return 1;
  }
  Triangulation tr(points.begin(), points.end());

  const CGAL::Bbox_3 box = CGAL::bbox_3(points.begin(), points.end());
  const double top = box.zmax(), height = box.zmax() - box.zmin();
  auto on_top = [&](const std::array<double, 3>& p) { return p[2] > top - 1e-9 * height; };

  // slide the top by a quarter of the height in x, in 20 equal steps
  sm::Translation_motion<3> slide;
  slide.displacement = {height / 4, 0, 0};
  sm::Deform_options options;
  options.number_of_steps = 20;
  const auto report = sm::deform(tr, sm::moving_boundary_where(on_top), slide, sm::Grid_scaled_stiffness{}, options);

  std::printf("%s: %zu vertices, %zu cells; %zu moving, %zu fixed; %s after %zu steps; "
              "worst skewness %.3f, smallest volume ratio %.3f\n",
              path.c_str(), tr.number_of_vertices(), tr.number_of_finite_cells(), report.moving_vertices,
              report.fixed_vertices, report.completed ? "completed" : "stopped", report.steps.size(),
              report.quality_all.max, report.min_size_ratio);
  // the cells keep their orientation, but the triangulation is no longer
  // Delaunay: do not insert() into it any more
  return report.completed ? 0 : 1;
}
