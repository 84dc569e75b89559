// Small meshes shared by the tests: Mesh_2 domains, the NACA0012 airfoil
// as a spring network with its roles, Kuhn grids.
#ifndef SPRING_MOTION_TESTS_TEST_MESHES_H
#define SPRING_MOTION_TESTS_TEST_MESHES_H

#include <naca0012/Naca0012_mesh_2.h>
#include <naca0012/Naca0012_wing_mesh_3.h>
#include <spring_motion/spring_motion.h>

#include <CGAL/Delaunay_mesh_size_criteria_2.h>
#include <CGAL/Delaunay_mesher_2.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
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

/// The NACA0012 airfoil's Mesh_2 domain, built from scratch, as a spring
/// network whose airfoil vertices move (the rest by assign_roles' defaults).
struct Naca0012_network
{
  spring_motion::Spring_network<2> network;
  std::vector<spring_motion::Vertex_role> roles;
};

inline Naca0012_network naca0012_network()
{
  CDT cdt;
  spring_motion::make_naca0012_mesh_2(cdt);
  Naca0012_network n{spring_motion::extract_spring_network(cdt).network, {}};
  n.roles = spring_motion::assign_roles(n.network, spring_motion::moving_boundary_where([](const std::array<double, 2>& p) {
                                          return spring_motion::is_on_naca0012_airfoil(p[0], p[1]);
                                        }));
  return n;
}

// A coarse Mesh_3 wing (about 6000 tetrahedra, meshed in about a second):
// smaller sizes, a near far field, none of the optimisers, so it keeps many
// of Mesh_3's slivers and small aggregates
inline spring_motion::Naca0012_wing_mesh_3_options coarse_wing_options()
{
  spring_motion::Naca0012_wing_mesh_3_options o;
  o.section_intervals = 40;
  o.span_intervals = 10;
  o.sphere_subdivisions = 2;
  o.far_field_radius = 4;
  o.size_at_wing = 0.2;
  o.size_at_trailing_edge = 0.1;
  o.size_growth = 0.6;
  o.odt_iterations = 0;
  o.sliver_smoothing_bound = 0;
  return o;
}

// [0,n]^D cut into simplices (Kuhn: each cell along the permutations of its
// axes), interior vertices jittered by up to `jitter` (0: the exact lattice)
template <int D>
inline spring_motion::Indexed_mesh<D> kuhn_grid(int n, double jitter = 0.15)
{
  spring_motion::Indexed_mesh<D> mesh;
  const int s = n + 1;
  auto index = [&](std::array<int, D> c) {
    int k = 0;
    for(int a = D - 1; a >= 0; --a)
      k = k * s + c[a];
    return std::uint32_t(k);
  };
  const int total = D == 2 ? s * s : s * s * s;
  for(int k = 0; k < total; ++k) {
    std::array<double, D> p;
    bool interior = true;
    int r = k;
    for(int a = 0; a < D; ++a) {
      const int c = r % s;
      r /= s;
      p[a] = c;
      interior = interior && c > 0 && c < n;
    }
    if(interior)
      for(int a = 0; a < D; ++a)
        p[a] += jitter * std::sin(7.0 * k + 3.0 * a);
    mesh.points.push_back(p);
  }
  std::array<int, D> perm;
  for(int a = 0; a < D; ++a)
    perm[a] = a;
  const int cells = D == 2 ? n * n : n * n * n;
  for(int cell = 0; cell < cells; ++cell) {
    std::array<int, D> base;
    int r = cell;
    for(int a = 0; a < D; ++a) {
      base[a] = r % n;
      r /= n;
    }
    std::array<int, D> order = perm;
    do {
      typename spring_motion::Indexed_mesh<D>::Element e;
      std::array<int, D> c = base;
      e[0] = index(c);
      for(int a = 0; a < D; ++a) {
        ++c[order[a]];
        e[a + 1] = index(c);
      }
      mesh.elements.push_back(e);
    } while(std::next_permutation(order.begin(), order.end()));
  }
  mesh.element_labels.assign(mesh.elements.size(), 0);
  return mesh;
}

} // namespace spring_motion_test

#endif
