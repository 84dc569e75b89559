// deform() over every supported CGAL mesh type (mesh_traits/): the same
// generic checks on a Triangulation_2, a regular (weighted) Triangulation_2, a
// Mesh_2 constrained Delaunay triangulation, a Surface_mesh with 2D points and
// one in a tilted plane, a Delaunay Triangulation_3 and a Mesh_3 complex.
#include <spring_motion/deform.h>
#include <spring_motion/mesh_traits/Mesh_complex_3_in_triangulation_3.h>
#include <spring_motion/mesh_traits/Surface_mesh.h>
#include <spring_motion/mesh_traits/Triangulation_2.h>
#include <spring_motion/mesh_traits/Triangulation_3.h>
#include <spring_motion/motion/Pitch_motion.h>
#include <spring_motion/stiffness/Grid_scaled_stiffness.h>
#include <spring_motion/stiffness/Lineal_stiffness.h>

#include "mesh_3_ball.h"

#include <catch2/catch.hpp>

#include <CGAL/Constrained_Delaunay_triangulation_2.h>
#include <CGAL/Delaunay_mesh_face_base_2.h>
#include <CGAL/Delaunay_mesh_size_criteria_2.h>
#include <CGAL/Delaunay_mesher_2.h>
#include <CGAL/Delaunay_triangulation_2.h>
#include <CGAL/Delaunay_triangulation_3.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Regular_triangulation_2.h>
#include <CGAL/Surface_mesh.h>

#include <boost/property_map/property_map.hpp>

#include <algorithm>
#include <array>
#include <limits>
#include <cmath>
#include <list>
#include <map>
#include <vector>

using namespace spring_motion;

namespace {

using K = CGAL::Exact_predicates_inexact_constructions_kernel;

// A vertex as stored in the mesh: coordinates (z = 0 in 2D) and weight (0
// when unweighted), compared bitwise.
using Raw = std::array<double, 4>;

template <class P>
Raw raw_of(const P& p)
{
  if constexpr(P::Ambient_dimension::value == 2)
    return {p.x(), p.y(), 0, 0};
  else
    return {p.x(), p.y(), p.z(), 0};
}

// A jittered n x n grid on [-2, 2]^2: deterministic, no four points cocircular.
template <class P>
std::vector<P> jittered_grid_2(int n = 9)
{
  std::vector<P> pts;
  for(int i = 0; i < n; ++i)
    for(int j = 0; j < n; ++j) {
      const bool edge_i = i == 0 || i == n - 1, edge_j = j == 0 || j == n - 1;
      // the hull stays a square: boundary points keep their boundary coordinate
      const double x = -2 + 4.0 * i / (n - 1) + (edge_i ? 0 : 0.05 * std::sin(i + 7 * j));
      const double y = -2 + 4.0 * j / (n - 1) + (edge_j ? 0 : 0.05 * std::sin(3 * i + j));
      pts.emplace_back(x, y);
    }
  return pts;
}

// ---- one fixture per mesh type: make(), and each vertex's raw point ----------

struct Delaunay_2_fixture
{
  using Mesh = CGAL::Delaunay_triangulation_2<K>;
  static Mesh make()
  {
    const auto pts = jittered_grid_2<K::Point_2>();
    return Mesh(pts.begin(), pts.end());
  }
  template <class V>
  static Raw raw(const Mesh&, V v) { return raw_of(v->point()); }
};

struct Regular_2_fixture
{
  using Mesh = CGAL::Regular_triangulation_2<K>;
  static Mesh make()
  {
    Mesh rt;
    // small weights: every point stays a vertex (none is hidden)
    int k = 0;
    for(const auto& p : jittered_grid_2<K::Point_2>())
      rt.insert(K::Weighted_point_2(p, 1e-3 * (1 + (k++ % 5))));
    REQUIRE(rt.number_of_vertices() == 81);
    return rt;
  }
  template <class V>
  static Raw raw(const Mesh&, V v)
  {
    Raw r = raw_of(v->point().point());
    r[3] = v->point().weight();
    return r;
  }
};

using Mesh_2_vb = CGAL::Triangulation_vertex_base_2<K>;
using Mesh_2_fb = CGAL::Delaunay_mesh_face_base_2<K>;
using Mesh_2_cdt = CGAL::Constrained_Delaunay_triangulation_2<
    K, CGAL::Triangulation_data_structure_2<Mesh_2_vb, Mesh_2_fb>>;

// [-2, 2]^2 with the hole [-0.5, 0.5]^2, refined by Mesh_2.
Mesh_2_cdt square_with_hole()
{
  Mesh_2_cdt cdt;
  for(double s : {2.0, 0.5}) {
    const std::array<K::Point_2, 4> c{K::Point_2(-s, -s), K::Point_2(s, -s), K::Point_2(s, s), K::Point_2(-s, s)};
    for(int k = 0; k < 4; ++k)
      cdt.insert_constraint(c[std::size_t(k)], c[std::size_t((k + 1) % 4)]);
  }
  std::list<K::Point_2> seeds{K::Point_2(0, 0)};
  CGAL::refine_Delaunay_mesh_2(cdt, seeds.begin(), seeds.end(),
                               CGAL::Delaunay_mesh_size_criteria_2<Mesh_2_cdt>(0.125, 0.4));
  return cdt;
}

struct Mesh_2_fixture
{
  using Mesh = Mesh_2_cdt;
  static Mesh make() { return square_with_hole(); }
  template <class V>
  static Raw raw(const Mesh&, V v) { return raw_of(v->point()); }
};

// The domain faces of the Mesh_2 triangulation as a Surface_mesh, its points
// mapped by `embed`.
template <class Surface, class Embed>
Surface surface_of_mesh_2(Embed embed)
{
  const Mesh_2_cdt cdt = square_with_hole();
  Surface sm;
  std::map<Mesh_2_cdt::Vertex_handle, typename Surface::Vertex_index> index;
  for(auto v : cdt.finite_vertex_handles())
    index[v] = sm.add_vertex(embed(v->point()));
  for(auto f : cdt.finite_face_handles())
    if(f->is_in_domain())
      sm.add_face(index[f->vertex(0)], index[f->vertex(1)], index[f->vertex(2)]);
  return sm;
}

struct Surface_mesh_2_fixture
{
  using Mesh = CGAL::Surface_mesh<K::Point_2>;
  static Mesh make()
  {
    return surface_of_mesh_2<Mesh>([](const K::Point_2& p) { return p; });
  }
  template <class V>
  static Raw raw(const Mesh& m, V v) { return raw_of(m.point(v)); }
};

// The plane through (0, 0, 1) spanned by (2, 1, 2)/3 and (1, 2, -2)/3.
struct Tilted_surface_mesh_fixture
{
  using Mesh = CGAL::Surface_mesh<K::Point_3>;
  static Mesh make()
  {
    return surface_of_mesh_2<Mesh>([](const K::Point_2& p) {
      return K::Point_3((2 * p.x() + p.y()) / 3, (p.x() + 2 * p.y()) / 3, 1 + (2 * p.x() - 2 * p.y()) / 3);
    });
  }
  template <class V>
  static Raw raw(const Mesh& m, V v) { return raw_of(m.point(v)); }
};

struct Delaunay_3_fixture
{
  using Mesh = CGAL::Delaunay_triangulation_3<K>;
  static Mesh make()
  {
    Mesh dt;
    for(int i = 0; i < 5; ++i)
      for(int j = 0; j < 5; ++j)
        for(int k = 0; k < 5; ++k)
          dt.insert(K::Point_3(i + 0.1 * std::sin(i + 7 * j + 31 * k), j + 0.1 * std::sin(3 * i + j + 11 * k),
                               k + 0.1 * std::sin(5 * i + 13 * j + k)));
    return dt;
  }
  template <class V>
  static Raw raw(const Mesh&, V v) { return raw_of(v->point()); }
};

// A Mesh_3 ball: weighted points, far vertices and cells outside the
// complex, all of which the traits must handle.
struct Mesh_3_fixture
{
  using Mesh = spring_motion_test::Ball_c3t3;
  static Mesh make() { return spring_motion_test::make_ball_c3t3(); }
  template <class V>
  static Raw raw(const Mesh&, V v)
  {
    Raw r = raw_of(v->point().point());
    r[3] = v->point().weight();
    return r;
  }
};

// Every vertex of the mesh's domain (as the traits list them) with its raw point.
template <class Fixture>
auto snapshot(const typename Fixture::Mesh& mesh)
{
  using Traits = Simplicial_mesh_traits<typename Fixture::Mesh>;
  Traits traits(mesh);
  std::map<typename Traits::Vertex_handle, Raw> out;
  traits.for_each_vertex([&](typename Traits::Vertex_handle v) { out[v] = Fixture::raw(mesh, v); });
  return out;
}

template <class Fixture>
constexpr int dimension_of = Simplicial_mesh_traits<typename Fixture::Mesh>::dimension;

} // namespace

TEMPLATE_TEST_CASE("deform over mesh types: a rigid translation of the whole boundary translates every vertex",
                   "[deform][mesh_traits]", Delaunay_2_fixture, Regular_2_fixture, Mesh_2_fixture,
                   Surface_mesh_2_fixture, Tilted_surface_mesh_fixture, Delaunay_3_fixture, Mesh_3_fixture)
{
  constexpr int D = dimension_of<TestType>;
  auto mesh = TestType::make();
  const auto before = snapshot<TestType>(mesh);
  std::array<double, D> d{};
  for(int c = 0; c < D; ++c)
    d[std::size_t(c)] = 0.1 * (c + 1) * (c % 2 ? -1 : 1);
  Deform_options options;
  options.number_of_steps = 3;
  options.solver.tolerance = 1e-14;
  const Deform_report report = deform(mesh, All_boundary_moving{}, Translation_motion<D>{d}, Lineal_stiffness{}, options);
  REQUIRE(report.completed);
  REQUIRE(report.converged);
  const auto after = snapshot<TestType>(mesh);
  REQUIRE(after.size() == before.size());
  // the displacement of every vertex in the mesh's own coordinates: in the
  // tilted plane, the embedded image of d, whose length is |d|
  double d_length = 0;
  for(double c : d)
    d_length += c * c;
  d_length = std::sqrt(d_length);
  const Raw first_shift = [&] {
    Raw s{};
    const auto& [v, p] = *before.begin();
    for(int c = 0; c < 3; ++c)
      s[std::size_t(c)] = after.at(v)[std::size_t(c)] - p[std::size_t(c)];
    return s;
  }();
  CHECK(std::hypot(first_shift[0], first_shift[1], first_shift[2]) == Approx(d_length).epsilon(1e-12));
  double worst = 0;
  for(const auto& [v, p] : before) {
    const Raw& q = after.at(v);
    for(int c = 0; c < 3; ++c)
      worst = std::max(worst, std::abs(q[std::size_t(c)] - p[std::size_t(c)] - first_shift[std::size_t(c)]));
    CHECK(q[3] == p[3]); // weights are kept
  }
  CHECK(worst < 1e-10);
}

TEMPLATE_TEST_CASE("deform over mesh types: fixed vertices keep their points bitwise and weights are kept",
                   "[deform][mesh_traits]", Delaunay_2_fixture, Regular_2_fixture, Mesh_2_fixture,
                   Surface_mesh_2_fixture, Tilted_surface_mesh_fixture, Delaunay_3_fixture, Mesh_3_fixture)
{
  constexpr int D = dimension_of<TestType>;
  auto mesh = TestType::make();
  const auto before = snapshot<TestType>(mesh);
  const auto net = extract_spring_network(mesh).network;
  // the boundary vertices left of the middle move a little upwards, the
  // rest of the boundary is fixed
  double x_min = std::numeric_limits<double>::infinity(), x_max = -x_min;
  for(const auto& p : net.points) {
    x_min = std::min(x_min, p[0]);
    x_max = std::max(x_max, p[0]);
  }
  const double x_cut = x_min + 0.3 * (x_max - x_min);
  auto left = [x_cut](const std::array<double, D>& p) { return p[0] < x_cut; };
  std::array<double, D> d{};
  d[1] = 1e-3 * (x_max - x_min);
  Deform_options options;
  options.number_of_steps = 2;
  const Deform_report report =
      deform(mesh, moving_boundary_where(left), Translation_motion<D>{d}, Lineal_stiffness{}, options);
  REQUIRE(report.completed);
  REQUIRE(report.fixed_vertices > 0);
  REQUIRE(report.moving_vertices > 0);
  const auto after = snapshot<TestType>(mesh);
  std::size_t fixed_checked = 0, moved = 0;
  for(const auto& [v, p] : before) {
    const Raw& q = after.at(v);
    CHECK(q[3] == p[3]); // weights are kept
    if(q != p)
      ++moved;
  }
  // fixed vertices: on the boundary, right of the cut; they must not move
  // at all (no round trip through another frame may change them)
  using Traits = Simplicial_mesh_traits<typename TestType::Mesh>;
  const auto extracted = extract_spring_network<typename TestType::Mesh, Traits>(mesh);
  for(std::size_t k = 0; k < extracted.handles.size(); ++k)
    if(extracted.network.on_boundary[k] && !(net.points[k][0] < x_cut)) {
      const auto h = extracted.handles[k];
      CHECK(after.at(h) == before.at(h));
      ++fixed_checked;
    }
  CHECK(fixed_checked == report.fixed_vertices);
  CHECK(moved > 0);
}

TEMPLATE_TEST_CASE("deform over mesh types: roles from a property map move the mesh as the same roles from a predicate",
                   "[deform][mesh_traits][roles]", Delaunay_2_fixture, Mesh_2_fixture, Surface_mesh_2_fixture,
                   Delaunay_3_fixture, Mesh_3_fixture)
{
  constexpr int D = dimension_of<TestType>;
  using Mesh = typename TestType::Mesh;
  using Traits = Simplicial_mesh_traits<Mesh>;
  using Vh = typename Traits::Vertex_handle;
  auto by_predicate = TestType::make();
  auto by_map = TestType::make();
  auto by_bool_maps = TestType::make();
  const auto extracted = extract_spring_network<Mesh, Traits>(by_map);
  const auto& net = extracted.network;
  double x_min = std::numeric_limits<double>::infinity(), x_max = -x_min;
  for(const auto& p : net.points) {
    x_min = std::min(x_min, p[0]);
    x_max = std::max(x_max, p[0]);
  }
  const double x_cut = x_min + 0.3 * (x_max - x_min);
  auto left = [x_cut](const std::array<double, D>& p) { return p[0] < x_cut; };
  // the same roles as the predicate's, keyed by the mesh's vertex handles
  std::map<Vh, Vertex_role> role_of;
  std::map<Vh, bool> moving, constrained;
  const auto roles = assign_roles(net, moving_boundary_where(left));
  for(std::size_t k = 0; k < extracted.handles.size(); ++k) {
    role_of[extracted.handles[k]] = roles[k];
    moving[extracted.handles[k]] = roles[k] == Vertex_role::moving;
    constrained[extracted.handles[k]] = roles[k] != Vertex_role::free;
  }
  std::array<double, D> d{};
  d[1] = 1e-3 * (x_max - x_min);
  Deform_options options;
  options.number_of_steps = 2;
  const auto r0 = deform(by_predicate, moving_boundary_where(left), Translation_motion<D>{d}, Lineal_stiffness{}, options);
  const auto r1 = deform(by_map, vertex_role_map(boost::associative_property_map<std::map<Vh, Vertex_role>>(role_of)),
                         Translation_motion<D>{d}, Lineal_stiffness{}, options);
  // the maps of the third mesh hold the handles of the second: copy them over by position in the traits' order
  std::map<Vh, bool> moving3, constrained3;
  {
    const auto e3 = extract_spring_network<Mesh, Traits>(by_bool_maps);
    REQUIRE(e3.handles.size() == extracted.handles.size());
    for(std::size_t k = 0; k < e3.handles.size(); ++k) {
      moving3[e3.handles[k]] = moving[extracted.handles[k]];
      constrained3[e3.handles[k]] = constrained[extracted.handles[k]];
    }
  }
  const auto r2 = deform(by_bool_maps,
                         constrained_vertex_maps(boost::associative_property_map<std::map<Vh, bool>>(moving3),
                                                 boost::associative_property_map<std::map<Vh, bool>>(constrained3)),
                         Translation_motion<D>{d}, Lineal_stiffness{}, options);
  REQUIRE(r0.completed);
  REQUIRE(r0.moving_vertices > 0);
  CHECK(r1.moving_vertices == r0.moving_vertices);
  CHECK(r1.fixed_vertices == r0.fixed_vertices);
  CHECK(r2.moving_vertices == r0.moving_vertices);
  CHECK(r2.fixed_vertices == r0.fixed_vertices);
  // bit for bit: the same system, solved the same way
  const auto sorted = [](const auto& snap) {
    std::vector<Raw> v;
    for(const auto& [h, p] : snap)
      v.push_back(p);
    std::sort(v.begin(), v.end());
    return v;
  };
  const auto va = sorted(snapshot<TestType>(by_predicate));
  CHECK(va == sorted(snapshot<TestType>(by_map)));
  CHECK(va == sorted(snapshot<TestType>(by_bool_maps)));
  CHECK(va != sorted(snapshot<TestType>(TestType::make()))); // the mesh did move
}

TEST_CASE("deform: roles from a Surface_mesh vertex property", "[deform][mesh_traits][roles]")
{
  using Mesh = Surface_mesh_2_fixture::Mesh;
  Mesh a = Surface_mesh_2_fixture::make(), b = a;
  // the hole (the boundary near the centre) moves, the outer boundary is fixed
  auto role = b.add_property_map<Mesh::Vertex_index, Vertex_role>("v:role", Vertex_role::free).first;
  const auto near_centre = [](const std::array<double, 2>& p) { return std::hypot(p[0], p[1]) < 1.0; };
  for(auto v : b.vertices()) {
    if(!b.is_border(v))
      continue;
    role[v] = near_centre({b.point(v).x(), b.point(v).y()}) ? Vertex_role::moving : Vertex_role::fixed;
  }
  Deform_options options;
  options.number_of_steps = 3;
  const Translation_motion<2> shift{{0.05, 0.02}};
  const auto r0 = deform(a, moving_boundary_where(near_centre), shift, Grid_scaled_stiffness{}, options);
  const auto r1 = deform(b, vertex_role_map(role), shift, Grid_scaled_stiffness{}, options);
  REQUIRE(r0.completed);
  REQUIRE(r1.moving_vertices == r0.moving_vertices);
  REQUIRE(r1.moving_vertices > 0);
  std::size_t moved = 0;
  for(auto v : a.vertices()) {
    CHECK(a.point(v) == b.point(v));
    moved += a.point(v) != Surface_mesh_2_fixture::make().point(v);
  }
  CHECK(moved > r0.moving_vertices); // the interior followed
}
