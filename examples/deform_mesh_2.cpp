// deform() on a CGAL constrained Delaunay triangulation refined by Mesh_2:
// the holes of a polygonal domain turn by 20 degrees about the origin and
// the interior follows.
//
//   deform_mesh_2 [polygons]   (default: data/plate_in_square_2d.txt)
//
// Each line of the file is a closed polygon "x1 y1 x2 y2 ...": the first is
// the outer boundary, the others are convex holes. Faces outside the domain
// (Mesh_2's is_in_domain() false) take no part in the motion.
#include <spring_motion/spring_motion.h>

#include <CGAL/Constrained_Delaunay_triangulation_2.h>
#include <CGAL/Delaunay_mesh_face_base_2.h>
#include <CGAL/Delaunay_mesh_size_criteria_2.h>
#include <CGAL/Delaunay_mesh_vertex_base_2.h>
#include <CGAL/Delaunay_mesher_2.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/centroid.h>

#include <cstdio>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

using K = CGAL::Exact_predicates_inexact_constructions_kernel;
using Tds = CGAL::Triangulation_data_structure_2<CGAL::Delaunay_mesh_vertex_base_2<K>,
                                                 CGAL::Delaunay_mesh_face_base_2<K>>;
using CDT = CGAL::Constrained_Delaunay_triangulation_2<K, Tds, CGAL::Exact_predicates_tag>;
using Point = CDT::Point;
namespace sm = spring_motion;

int main(int argc, char** argv)
{
  const std::string path = argc > 1 ? argv[1] : SPRING_MOTION_DATA_DIR "/plate_in_square_2d.txt";
  std::ifstream in(path);
  std::vector<std::vector<Point>> polygons;
  for(std::string line; std::getline(in, line);) {
    std::istringstream s(line);
    std::vector<Point> polygon;
    for(double x, y; s >> x >> y;)
      polygon.emplace_back(x, y);
    if(polygon.size() >= 3)
      polygons.push_back(polygon);
  }
  if(polygons.size() < 2) {
    std::fprintf(stderr, "%s: need an outer polygon and at least one hole\n", path.c_str());
    return 1;
  }

  CDT cdt;
  std::vector<Point> seeds; // Mesh_2 leaves the regions of these points out
  for(const auto& polygon : polygons)
    cdt.insert_constraint(polygon.begin(), polygon.end(), true);
  for(std::size_t h = 1; h < polygons.size(); ++h)
    seeds.push_back(CGAL::centroid(polygons[h].begin(), polygons[h].end()));
  CGAL::refine_Delaunay_mesh_2(cdt, seeds.begin(), seeds.end(), CGAL::Delaunay_mesh_size_criteria_2<CDT>(0.125, 0.2));

  // a boundary vertex inside the bounding box of the holes moves with them
  CGAL::Bbox_2 holes = CGAL::bbox_2(polygons[1].begin(), polygons[1].end());
  for(std::size_t h = 2; h < polygons.size(); ++h)
    holes += CGAL::bbox_2(polygons[h].begin(), polygons[h].end());
  auto on_hole = [&](const std::array<double, 2>& p) {
    return p[0] >= holes.xmin() && p[0] <= holes.xmax() && p[1] >= holes.ymin() && p[1] <= holes.ymax();
  };
  sm::Deform_options options;
  options.number_of_steps = 20;
  const auto report = sm::deform(cdt, sm::moving_boundary_where(on_hole), sm::Pitch_motion<2>(20, {0, 0}),
                                 sm::Grid_scaled_stiffness{}, options);
  std::printf("%s: %zu vertices; %zu moving, %zu fixed; turned to %.1f deg, %s; worst skewness near the holes %.3f\n",
              path.c_str(), cdt.number_of_vertices(), report.moving_vertices, report.fixed_vertices,
              report.final_angle_deg, report.completed ? "completed" : "stopped", report.quality_moving.max);
  return report.completed ? 0 : 1;
}
