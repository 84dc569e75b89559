// The 2D mesh traits (mesh_traits/Triangulation_2.h, mesh_traits/Surface_mesh.h):
// one triangulation given as a Mesh_2 constrained Delaunay triangulation, as a
// plain CGAL::Triangulation_2 and as a Surface_mesh (2D points, 3D points in
// a plane) yields the same spring network and the same motion.
#include <spring_motion/spring_motion.h>

#include "test_meshes.h"

#include <spring_motion/io/read_mesh.h>

#include <catch2/catch.hpp>

#include <CGAL/Surface_mesh.h>
#include <CGAL/Triangulation_2.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <list>
#include <map>
#include <set>
#include <string>
#include <vector>

using namespace spring_motion;
using namespace spring_motion_test;

namespace {

using K = CGAL::Exact_predicates_inexact_constructions_kernel;
using P2 = std::array<double, 2>;
using Plain_triangulation = CGAL::Triangulation_2<K>;
using Mesh_2d = CGAL::Surface_mesh<K::Point_2>;
using Mesh_3d = CGAL::Surface_mesh<K::Point_3>;

using Coordinate_edge = std::array<P2, 2>;
using Coordinate_triangle = std::array<P2, 3>;

// A network up to vertex numbering: its edges and elements named by the
// coordinates of their vertices, each sorted, plus the boundary vertices.
struct Network_by_coordinates
{
  std::set<Coordinate_edge> edges;
  std::set<Coordinate_triangle> elements;
  std::set<P2> boundary;
  bool operator==(const Network_by_coordinates& o) const
  {
    return edges == o.edges && elements == o.elements && boundary == o.boundary;
  }
};

Network_by_coordinates by_coordinates(const Spring_network<2>& net)
{
  Network_by_coordinates out;
  for(const auto& e : net.edges) {
    Coordinate_edge c{net.points[e[0]], net.points[e[1]]};
    std::sort(c.begin(), c.end());
    out.edges.insert(c);
  }
  for(const auto& t : net.elements) {
    Coordinate_triangle c{net.points[t[0]], net.points[t[1]], net.points[t[2]]};
    std::sort(c.begin(), c.end());
    out.elements.insert(c);
  }
  for(std::size_t i = 0; i < net.number_of_vertices(); ++i)
    if(net.on_boundary[i])
      out.boundary.insert(net.points[i]);
  return out;
}

// Initial point -> final point, for every vertex of the network.
template <class Mesh>
std::map<P2, P2> motion_by_initial_point(const Mesh& before, const Mesh& after)
{
  const auto b = extract_spring_network(before);
  const auto a = extract_spring_network(after);
  REQUIRE(a.network.number_of_vertices() == b.network.number_of_vertices());
  std::map<P2, P2> out;
  // extraction numbers the vertices in the mesh's iteration order, which a
  // copy and deform() keep: the same elements in the same numbering show it
  REQUIRE(a.network.elements == b.network.elements);
  for(std::size_t i = 0; i < b.network.number_of_vertices(); ++i)
    out[b.network.points[i]] = a.network.points[i];
  return out;
}

double max_difference(const std::map<P2, P2>& a, const std::map<P2, P2>& b)
{
  REQUIRE(a.size() == b.size());
  double d = 0;
  for(const auto& [p0, p] : a) {
    const auto it = b.find(p0);
    REQUIRE(it != b.end());
    d = std::max({d, std::abs(p[0] - it->second[0]), std::abs(p[1] - it->second[1])});
  }
  return d;
}

// The domain faces of a CDT as a Surface_mesh with points made by `make`,
// vertices added in reverse order and each face starting at its second
// vertex, so that nothing but the coordinates is shared with the CDT.
template <class Surface, class Make>
Surface surface_from(const CDT& cdt, Make make)
{
  Surface sm;
  std::vector<CDT::Vertex_handle> vs;
  for(auto v : cdt.finite_vertex_handles())
    vs.push_back(v);
  std::map<CDT::Vertex_handle, typename Surface::Vertex_index> index;
  for(auto it = vs.rbegin(); it != vs.rend(); ++it)
    index[*it] = sm.add_vertex(make((*it)->point()));
  for(auto f : cdt.finite_face_handles())
    if(f->is_in_domain())
      REQUIRE(sm.add_face(index[f->vertex(1)], index[f->vertex(2)], index[f->vertex(0)]) != Surface::null_face());
  // a hole leaves vertices no face uses; extraction skips them, so keep them
  return sm;
}

// Boundary vertices on the left side, corners excepted, turn about its
// midpoint; the rest of the boundary is fixed.
auto left_side = [](const P2& p) { return p[0] < -1.99 && std::abs(p[1]) < 1.99; };

template <class Mesh>
std::map<P2, P2> run(Mesh& mesh, const Deform_options& options)
{
  const Mesh before = mesh;
  const auto report = deform(mesh, moving_boundary_where(left_side), Pitch_motion<2>(5, {-2, 0}),
                             Grid_scaled_stiffness{}, options);
  REQUIRE(report.completed);
  REQUIRE(report.converged);
  return motion_by_initial_point(before, mesh);
}

} // namespace

TEST_CASE("mesh traits: CDT, Triangulation_2 and Surface_mesh of one triangulation give one network and one motion",
          "[mesh_traits]")
{
  // [-2,2]^2 refined by Mesh_2, without a hole: every finite face is in the
  // domain, so a plain triangulation holding the same faces is the same mesh
  CDT cdt;
  cdt.insert_constraint(Point_2(-2, -2), Point_2(2, -2));
  cdt.insert_constraint(Point_2(2, -2), Point_2(2, 2));
  cdt.insert_constraint(Point_2(2, 2), Point_2(-2, 2));
  cdt.insert_constraint(Point_2(-2, 2), Point_2(-2, -2));
  const std::list<Point_2> no_seeds;
  CGAL::refine_Delaunay_mesh_2(cdt, no_seeds.begin(), no_seeds.end(),
                               CGAL::Delaunay_mesh_size_criteria_2<CDT>(0.125, 0.4));
  std::size_t in_domain = 0;
  for(auto f : cdt.finite_face_handles())
    in_domain += f->is_in_domain() ? 1 : 0;
  REQUIRE(in_domain == cdt.number_of_faces());

  // the plain Triangulation_2: a copy of the CDT's combinatorics with
  // CGAL's default vertex and face types (no constraints, no domain marks)
  Plain_triangulation plain;
  struct Vertex_copy
  {
    Plain_triangulation::Vertex operator()(const CDT::Vertex& v) const { return Plain_triangulation::Vertex(v.point()); }
    void operator()(const CDT::Vertex&, Plain_triangulation::Vertex&) const {}
  };
  struct Face_copy
  {
    Plain_triangulation::Face operator()(const CDT::Face&) const { return Plain_triangulation::Face(); }
    void operator()(const CDT::Face&, Plain_triangulation::Face&) const {}
  };
  plain.set_infinite_vertex(plain.tds().copy_tds(cdt.tds(), cdt.infinite_vertex(), Vertex_copy(), Face_copy()));
  REQUIRE(plain.is_valid());
  const Mesh_2d sm2 = surface_from<Mesh_2d>(cdt, [](const Point_2& p) { return K::Point_2(p.x(), p.y()); });
  const double z = 0.375;
  const Mesh_3d sm3 = surface_from<Mesh_3d>(cdt, [&](const Point_2& p) { return K::Point_3(p.x(), p.y(), z); });

  const auto reference = by_coordinates(extract_spring_network(cdt).network);
  CHECK(reference.elements.size() == cdt.number_of_faces());
  CHECK(reference.edges.size() > reference.elements.size());
  CHECK(by_coordinates(extract_spring_network(plain).network) == reference);
  CHECK(by_coordinates(extract_spring_network(sm2).network) == reference);
  CHECK(by_coordinates(extract_spring_network(sm3).network) == reference);

  // The same motion: each run's solves stop at an estimated error of 1e-14
  // (conjugate gradients, whose sweep order follows the vertex numbering,
  // which differs between the structures), three steps; a factor 10 for the
  // estimate and the three steps keeps the difference below 1e-12.
  Deform_options options;
  options.number_of_steps = 3;
  options.solver.tolerance = 1e-14;
  CDT c = cdt;
  Plain_triangulation t = plain;
  Mesh_2d s2 = sm2;
  Mesh_3d s3 = sm3;
  const auto m_cdt = run(c, options);
  double largest = 0;
  for(const auto& [p0, p] : m_cdt)
    largest = std::max({largest, std::abs(p[0] - p0[0]), std::abs(p[1] - p0[1])});
  CHECK(largest > 0.1); // the motion is not trivially zero
  CHECK(max_difference(m_cdt, run(t, options)) < 1e-12);
  CHECK(max_difference(m_cdt, run(s2, options)) < 1e-12);
  CHECK(max_difference(m_cdt, run(s3, options)) < 1e-12);
  // the 3D points stay in their plane
  for(auto v : s3.vertices())
    CHECK(s3.point(v).z() == z);
}

TEST_CASE("mesh traits: a Mesh_2 domain with a hole and the Surface_mesh of its domain faces agree",
          "[mesh_traits]")
{
  CDT cdt;
  make_square_with_hole(cdt);
  std::size_t in_domain = 0;
  for(auto f : cdt.finite_face_handles())
    in_domain += f->is_in_domain() ? 1 : 0;
  REQUIRE(in_domain < cdt.number_of_faces()); // the hole's faces are not in the domain
  const Mesh_2d sm = surface_from<Mesh_2d>(cdt, [](const Point_2& p) { return K::Point_2(p.x(), p.y()); });

  const auto net = extract_spring_network(cdt).network;
  CHECK(net.number_of_elements() == in_domain);
  const auto reference = by_coordinates(net);
  CHECK(by_coordinates(extract_spring_network(sm).network) == reference);
  // the hole's rim is boundary: its vertices are boundary vertices of the network
  std::size_t rim = 0;
  for(const auto& p : reference.boundary)
    rim += std::max(std::abs(p[0]), std::abs(p[1])) < 1 ? 1 : 0;
  CHECK(rim == 32); // 4 sides of 8 segments each (Mesh_2 splits none: they are shorter than the size bound)

  // turning the hole
  Deform_options options;
  options.number_of_steps = 3;
  options.solver.tolerance = 1e-14;
  auto hole = [](const P2& p) { return std::max(std::abs(p[0]), std::abs(p[1])) < 1; };
  CDT c = cdt;
  Mesh_2d s = sm;
  const CDT c0 = c;
  const Mesh_2d s0 = s;
  REQUIRE(deform(c, moving_boundary_where(hole), Pitch_motion<2>(20, {0, 0}), Grid_scaled_stiffness{}, options).completed);
  REQUIRE(deform(s, moving_boundary_where(hole), Pitch_motion<2>(20, {0, 0}), Grid_scaled_stiffness{}, options).completed);
  // same bound as in the test above
  CHECK(max_difference(motion_by_initial_point(c0, c), motion_by_initial_point(s0, s)) < 1e-12);
}

TEST_CASE("mesh traits: a Surface_mesh in a tilted plane moves within its plane", "[mesh_traits]")
{
  CDT cdt;
  make_square_with_hole(cdt);
  // the plane through (0, 0, 1) spanned by the orthonormal u = (2, 1, 2)/3 and
  // w = (1, 2, -2)/3 (u.w = 0)
  const std::array<double, 3> u{2.0 / 3, 1.0 / 3, 2.0 / 3}, w{1.0 / 3, 2.0 / 3, -2.0 / 3};
  const std::array<double, 3> normal{u[1] * w[2] - u[2] * w[1], u[2] * w[0] - u[0] * w[2], u[0] * w[1] - u[1] * w[0]};
  auto embed = [&](const Point_2& p) {
    return K::Point_3(p.x() * u[0] + p.y() * w[0], p.x() * u[1] + p.y() * w[1], 1 + p.x() * u[2] + p.y() * w[2]);
  };
  Mesh_3d sm = surface_from<Mesh_3d>(cdt, embed);
  // the network is congruent to the flat one: same edge lengths, edge by
  // edge (the reversed vertex order is undone by sorting the lengths)
  const auto flat = extract_spring_network(cdt).network;
  const auto tilted = extract_spring_network(sm).network;
  REQUIRE(flat.number_of_edges() == tilted.number_of_edges());
  REQUIRE(flat.number_of_elements() == tilted.number_of_elements());
  auto lengths = [](const Spring_network<2>& n) {
    std::vector<double> l;
    for(const auto& e : n.edges)
      l.push_back(std::hypot(n.points[e[0]][0] - n.points[e[1]][0], n.points[e[0]][1] - n.points[e[1]][1]));
    std::sort(l.begin(), l.end());
    return l;
  };
  const auto lf = lengths(flat), lt = lengths(tilted);
  for(std::size_t e = 0; e < lf.size(); ++e)
    CHECK(lt[e] == Approx(lf[e]).epsilon(1e-14)); // a projection onto an orthonormal frame: round-off only

  // a rigid translation of the whole boundary by d in the plane's own
  // coordinates moves every vertex by one 3D vector, of length |d|, in the plane
  const Mesh_3d before = sm;
  Deform_options options;
  options.number_of_steps = 2;
  options.solver.tolerance = 1e-16; // the exact solution is uniform: only round-off remains
  const std::array<double, 2> d{0.3, -0.4};
  REQUIRE(deform(sm, All_boundary_moving{}, Translation_motion<2>{d}, Lineal_stiffness{}, options).completed);
  const auto v0 = *before.vertices().begin();
  const auto shift = sm.point(v0) - before.point(v0);
  CHECK(std::sqrt(CGAL::to_double(shift.squared_length())) == Approx(0.5).epsilon(1e-12));
  CHECK(std::abs(shift.x() * normal[0] + shift.y() * normal[1] + shift.z() * normal[2]) < 1e-12);
  double worst = 0;
  for(auto v : sm.vertices()) {
    const auto s = sm.point(v) - before.point(v);
    worst = std::max({worst, std::abs(s.x() - shift.x()), std::abs(s.y() - shift.y()), std::abs(s.z() - shift.z())});
  }
  CHECK(worst < 1e-12);
}

TEST_CASE("mesh traits: the Medit file in data/ as Indexed_mesh and as Surface_mesh moves alike", "[mesh_traits][data]")
{
  // data/square_hole_2d.mesh (made by Gmsh from data/square_hole_2d.geo):
  // the hole's edges carry reference 2
  const auto file = read_mesh(std::string(SPRING_MOTION_TEST_DATA_DIR) + "/../../data/square_hole_2d.mesh");
  REQUIRE(file.dimension == 2);
  Indexed_mesh<2> indexed = file.mesh_2;
  Mesh_2d sm;
  for(const auto& p : indexed.points)
    sm.add_vertex(K::Point_2(p[0], p[1]));
  for(const auto& t : indexed.elements)
    REQUIRE(sm.add_face(Mesh_2d::Vertex_index(t[0]), Mesh_2d::Vertex_index(t[1]), Mesh_2d::Vertex_index(t[2])) !=
            Mesh_2d::null_face());
  REQUIRE(by_coordinates(extract_spring_network(indexed).network) ==
          by_coordinates(extract_spring_network(sm).network));

  Deform_options options;
  options.number_of_steps = 10;
  options.solver.tolerance = 1e-14;
  const Pitch_motion<2> motion(30, {0, 0});
  const Indexed_mesh<2> before = indexed;
  // by label in the file, and by position for the Surface_mesh, which has no labels
  const auto r1 = deform(indexed, Moving_boundary_labels{{2}}, motion, Grid_scaled_stiffness{}, options);
  auto hole = [](const P2& p) { return std::max(std::abs(p[0]), std::abs(p[1])) < 1; };
  const auto r2 = deform(sm, moving_boundary_where(hole), motion, Grid_scaled_stiffness{}, options);
  REQUIRE(r1.completed);
  REQUIRE(r2.completed);
  CHECK(r1.moving_vertices == r2.moving_vertices);
  std::vector<char> on_rim(indexed.points.size(), 0);
  for(std::size_t f = 0; f < before.boundary_facets.size(); ++f)
    if(before.boundary_labels[f] == 2)
      for(auto v : before.boundary_facets[f])
        on_rim[v] = 1;
  double worst = 0, on_hole = 0;
  for(std::size_t i = 0; i < indexed.points.size(); ++i) {
    const auto q = sm.point(Mesh_2d::Vertex_index(Index(i)));
    worst = std::max({worst, std::abs(indexed.points[i][0] - q.x()), std::abs(indexed.points[i][1] - q.y())});
    if(on_rim[i]) { // exactly at the rotated position: computed from the initial point
      const auto target = motion(before.points[i], 1.0);
      on_hole = std::max({on_hole, std::abs(indexed.points[i][0] - target[0]), std::abs(indexed.points[i][1] - target[1])});
    }
  }
  CHECK(worst < 1e-12); // as in the tests above
  CHECK(on_hole == 0);
}
