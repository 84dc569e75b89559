// Small Mesh_2 domains shared by the tests.
#ifndef SPRING_MOTION_TESTS_TEST_MESHES_H
#define SPRING_MOTION_TESTS_TEST_MESHES_H

#include <naca0012/Naca0012_mesh_2.h>

#include <CGAL/Delaunay_mesh_size_criteria_2.h>
#include <CGAL/Delaunay_mesher_2.h>

#include <cmath>
#include <list>
#include <vector>

namespace spring_motion_test {

using CDT = spring_motion::Mesh_2_cdt;
using Point_2 = CDT::Point;

inline void insert_polygon(CDT& cdt, const std::vector<Point_2>& poly)
{
  for(std::size_t i = 0; i < poly.size(); ++i)
    cdt.insert_constraint(poly[i], poly[(i + 1) % poly.size()]);
}

/// [-2,2]^2 with the hole [-h,h]^2, boundaries split in `per_side` segments.
inline void make_square_with_hole(CDT& cdt, double h = 0.5, int per_side = 8, double size = 0.3)
{
  cdt.clear();
  auto square = [&](double s) {
    std::vector<Point_2> p;
    for(int side = 0; side < 4; ++side)
      for(int k = 0; k < per_side; ++k) {
        const double u = -s + 2 * s * k / per_side;
        if(side == 0) p.emplace_back(u, -s);
        if(side == 1) p.emplace_back(s, u);
        if(side == 2) p.emplace_back(-u, s);
        if(side == 3) p.emplace_back(-s, -u);
      }
    return p;
  };
  insert_polygon(cdt, square(2.0));
  insert_polygon(cdt, square(h));
  std::list<Point_2> seeds{Point_2(0, 0)};
  CGAL::refine_Delaunay_mesh_2(cdt, seeds.begin(), seeds.end(),
                               CGAL::Delaunay_mesh_size_criteria_2<CDT>(0.125, size));
}

/// Annulus a <= r <= b, polygons with n1 and n2 vertices.
inline void make_annulus(CDT& cdt, double a = 0.5, double b = 2.0, int n1 = 24, int n2 = 48, double size = 0.25)
{
  cdt.clear();
  auto circle = [](double r, int n) {
    std::vector<Point_2> p;
    for(int k = 0; k < n; ++k)
      p.emplace_back(r * std::cos(2 * M_PI * k / n), r * std::sin(2 * M_PI * k / n));
    return p;
  };
  insert_polygon(cdt, circle(a, n1));
  insert_polygon(cdt, circle(b, n2));
  std::list<Point_2> seeds{Point_2(0, 0)};
  CGAL::refine_Delaunay_mesh_2(cdt, seeds.begin(), seeds.end(),
                               CGAL::Delaunay_mesh_size_criteria_2<CDT>(0.125, size));
}

} // namespace spring_motion_test

#endif
