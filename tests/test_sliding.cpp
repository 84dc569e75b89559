// Sliding vertices: the label rules, the exact plane, and the mirror test: a
// mesh cut by its symmetry plane(s), the cut sliding, must move as the half
// of the whole mesh under a motion that keeps the symmetry.
#include <spring_motion/spring_motion.h>

#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <map>
#include <set>

using namespace spring_motion;

namespace {

constexpr int hole_label = 2, outer_label = 1;
// the cut planes: label 10 + axis
int plane_label(int axis) { return 10 + axis; }

template <int D>
using Point = std::array<double, D>;

template <int D>
struct Box_mesh
{
  std::vector<Point<D>> points;
  std::vector<std::array<Index, D + 1>> elements;
};

// [-2, 2]^D in cells of 0.5 around the hole [-0.5, 0.5]^D, restricted to
// x_a >= 0 for every axis a in `cut`; each cell split into D! simplices
// (Kuhn) with the diagonal mirrored with the cell, so that the whole mesh is
// the cut one reflected across its planes.
template <int D>
Box_mesh<D> box_mesh(const std::vector<int>& cut)
{
  const int n = 8;
  const double h = 0.5, lo = -2;
  Box_mesh<D> m;
  std::map<std::array<int, D>, Index> index;
  const auto vertex = [&](const std::array<int, D>& g) {
    auto it = index.find(g);
    if(it != index.end())
      return it->second;
    Point<D> p;
    for(int k = 0; k < D; ++k)
      p[k] = lo + h * g[k];
    m.points.push_back(p);
    return index[g] = Index(m.points.size() - 1);
  };
  std::array<int, D> c{};
  for(int flat = 0; flat < (D == 2 ? n * n : n * n * n); ++flat) {
    int f = flat;
    bool keep = true, hole = true;
    for(int k = 0; k < D; ++k) {
      c[k] = f % n;
      f /= n;
      hole = hole && (c[k] == 3 || c[k] == 4);
      if(std::find(cut.begin(), cut.end(), k) != cut.end() && c[k] < n / 2)
        keep = false;
    }
    if(hole || !keep)
      continue;
    // corner (0, ..., 0) of the cell's Kuhn split, mirrored below the middle
    std::array<int, D> origin, dir;
    for(int k = 0; k < D; ++k) {
      dir[k] = c[k] < n / 2 ? -1 : 1;
      origin[k] = dir[k] > 0 ? c[k] : c[k] + 1;
    }
    std::array<int, D> perm;
    for(int k = 0; k < D; ++k)
      perm[k] = k;
    do {
      std::array<Index, D + 1> e;
      std::array<int, D> g = origin;
      e[0] = vertex(g);
      for(int k = 0; k < D; ++k) {
        g[perm[k]] += dir[perm[k]];
        e[k + 1] = vertex(g);
      }
      m.elements.push_back(e);
    } while(std::next_permutation(perm.begin(), perm.end()));
  }
  return m;
}

// boundary facets labelled: on the hole, on a cut plane, or outer
template <int D>
std::vector<Labeled_facet<D>> labelled_facets(const Box_mesh<D>& m, const std::vector<int>& cut)
{
  std::map<std::array<Index, D>, int> count;
  std::map<std::array<Index, D>, std::array<Index, D>> original;
  for(const auto& e : m.elements)
    for(int skip = 0; skip <= D; ++skip) {
      std::array<Index, D> f;
      int j = 0;
      for(int k = 0; k <= D; ++k)
        if(k != skip)
          f[j++] = e[k];
      auto key = f;
      std::sort(key.begin(), key.end());
      ++count[key];
      original[key] = f;
    }
  std::vector<Labeled_facet<D>> facets;
  for(const auto& [key, c] : count) {
    if(c != 1)
      continue;
    bool in_hole = true;
    int on_plane = -1;
    for(int a : cut) {
      bool all = true;
      for(Index v : key)
        all = all && m.points[v][a] == 0;
      if(all)
        on_plane = a;
    }
    for(Index v : key)
      for(int k = 0; k < D; ++k)
        in_hole = in_hole && std::abs(m.points[v][k]) <= 0.5;
    facets.push_back({original[key], in_hole ? hole_label : on_plane >= 0 ? plane_label(on_plane) : outer_label});
  }
  return facets;
}

template <int D>
Spring_network<D> labelled_network(const Box_mesh<D>& m, const std::vector<int>& cut)
{
  return make_spring_network<D>(m.points, m.elements, labelled_facets(m, cut));
}

template <int D>
std::map<Point<D>, Point<D>> by_initial_point(const Spring_network<D>& net, const std::vector<Point<D>>& x)
{
  std::map<Point<D>, Point<D>> out;
  for(Index i = 0; i < net.number_of_vertices(); ++i)
    out[net.points[i]] = x[i];
  return out;
}

struct Mirror_result
{
  double largest_difference = 0; // cut mesh vs the whole one, over the cut mesh's vertices
  double largest_slide = 0;      // in-plane motion of a sliding vertex
  bool planes_kept = true;       // every sliding vertex's cut coordinates bitwise unchanged
  std::size_t sliding = 0;
};

template <int D, class Model>
Mirror_result mirror_run(const std::vector<int>& cut, const Point<D>& shift, const Model& model,
                         bool cut_slides = true)
{
  Deform_options options;
  options.number_of_steps = 4;
  options.solver.tolerance = 1e-15;
  options.solver.max_iterations = 100000;
  Boundary_label_roles rules;
  rules.moving = {hole_label};
  for(int a : cut)
    rules.sliding.push_back(plane_label(a));
  if(!cut_slides)
    rules.sliding.clear();

  auto whole_net = labelled_network<D>(box_mesh<D>({}), {});
  auto whole_roles = assign_roles(whole_net, rules);
  Network_deformer<D> whole(whole_net, whole_roles);
  const auto rw = whole.run(Translation_motion<D>{shift}, model, options);
  REQUIRE(rw.completed);
  REQUIRE(rw.converged);

  auto cut_net = labelled_network<D>(box_mesh<D>(cut), cut);
  auto cut_roles = assign_roles(cut_net, rules);
  Network_deformer<D> half(cut_net, cut_roles);
  const auto rc = half.run(Translation_motion<D>{shift}, model, options);
  REQUIRE(rc.completed);
  REQUIRE(rc.converged);

  Mirror_result out;
  out.sliding = rc.sliding_vertices;
  const auto w = by_initial_point<D>(whole.network(), whole.positions());
  for(Index i = 0; i < cut_net.number_of_vertices(); ++i) {
    const auto& p0 = cut_net.points[i];
    const auto& p = half.positions()[i];
    const auto it = w.find(p0);
    REQUIRE(it != w.end());
    for(int k = 0; k < D; ++k)
      out.largest_difference = std::max(out.largest_difference, std::abs(p[k] - it->second[k]));
    if(half.roles()[i] == Vertex_role::sliding) {
      double slide = 0;
      for(int k = 0; k < D; ++k)
        slide += (p[k] - p0[k]) * (p[k] - p0[k]);
      out.largest_slide = std::max(out.largest_slide, std::sqrt(slide));
      for(int a : cut)
        if(p0[a] == 0 && !(p[a] == p0[a] && std::signbit(p[a]) == std::signbit(p0[a])))
          out.planes_kept = false;
    }
  }
  return out;
}

// Lineal springs (k = 1/l), one step: the increment d must be in
// equilibrium, sum_j k_ij (d_j - d_i) = 0 at free vertices and its in-plane
// part zero at sliding ones (the plane takes the normal force), with k at the
// initial positions. Returns the largest residual of each kind relative to
// sum_j k_ij |d_j - d_i|, and the plane and slide checks.
struct Equilibrium_result
{
  double free_residual = 0, sliding_residual = 0, largest_slide = 0;
  bool planes_kept = true;
};

template <int D>
Equilibrium_result equilibrium_run(const std::vector<int>& cut, const Point<D>& shift, bool cut_slides = true)
{
  Deform_options options;
  options.number_of_steps = 1;
  options.solver.tolerance = 1e-15;
  options.solver.max_iterations = 100000;
  Boundary_label_roles rules;
  rules.moving = {hole_label};
  for(int a : cut)
    rules.sliding.push_back(plane_label(a));
  auto net = labelled_network<D>(box_mesh<D>(cut), cut);
  const auto roles = assign_roles(net, rules);
  Network_deformer<D> d(net, roles);
  REQUIRE(d.number_of_sliding_vertices() > 0);
  // with the plane held fixed instead, its vertices' in-plane forces remain
  Network_deformer<D> run_with(net, cut_slides ? roles : assign_roles(net, Moving_boundary_labels{{hole_label}}));
  REQUIRE(run_with.run(Translation_motion<D>{shift}, Lineal_stiffness{}, options).completed);
  const auto& x = run_with.positions();
  Equilibrium_result out;
  for(Index i = 0; i < net.number_of_vertices(); ++i) {
    if(roles[i] != Vertex_role::free && roles[i] != Vertex_role::sliding)
      continue;
    Point<D> f{};
    double scale = 0;
    for(Index p = net.adjacency_offsets[i]; p < net.adjacency_offsets[i + 1]; ++p) {
      const Index j = net.adjacency[p];
      double l2 = 0;
      for(int k = 0; k < D; ++k)
        l2 += (net.points[j][k] - net.points[i][k]) * (net.points[j][k] - net.points[i][k]);
      const double kij = 1 / std::sqrt(l2);
      double dd = 0;
      for(int k = 0; k < D; ++k) {
        const double e = (x[j][k] - net.points[j][k]) - (x[i][k] - net.points[i][k]);
        f[k] += kij * e;
        dd += e * e;
      }
      scale += kij * std::sqrt(dd);
    }
    if(roles[i] == Vertex_role::sliding) {
      double slide = 0;
      for(int k = 0; k < D; ++k)
        slide += (x[i][k] - net.points[i][k]) * (x[i][k] - net.points[i][k]);
      out.largest_slide = std::max(out.largest_slide, std::sqrt(slide));
      for(int a : cut)
        if(net.points[i][a] == 0) {
          f[a] = 0; // the plane's reaction
          if(!(x[i][a] == 0))
            out.planes_kept = false;
        }
    }
    double r = 0;
    for(int k = 0; k < D; ++k)
      r += f[k] * f[k];
    r = scale > 0 ? std::sqrt(r) / scale : 0;
    double& worst = roles[i] == Vertex_role::sliding ? out.sliding_residual : out.free_residual;
    worst = std::max(worst, r);
  }
  return out;
}

} // namespace

TEST_CASE("sliding: the label rules", "[sliding]")
{
  const int moving = 1, slide = 2, other = 3;
  const auto role = [](const Boundary_label_roles& r, bool boundary, std::vector<int> labels) {
    return r(Vertex_info<2>{0, {0, 0}, boundary, labels.data(), labels.data() + labels.size()});
  };
  Boundary_label_roles r;
  r.moving = {moving};
  r.sliding = {slide};
  CHECK(role(r, false, {}) == Vertex_role::free);
  CHECK(role(r, true, {slide}) == Vertex_role::sliding);
  CHECK(role(r, true, {slide, moving}) == Vertex_role::moving);
  CHECK(role(r, true, {slide, other}) == Vertex_role::fixed); // the rest of the boundary is fixed
  CHECK(role(r, true, {}) == Vertex_role::fixed);
  CHECK(role(r, true, {other}) == Vertex_role::fixed);
  r.fixed = {other};
  r.fixed_given = true;
  CHECK(role(r, true, {slide, other}) == Vertex_role::fixed);
  CHECK(role(r, true, {4}) == Vertex_role::free); // with fixed given, unnamed parts are free
  CHECK(role(r, true, {slide, 4}) == Vertex_role::sliding);
}

TEST_CASE("sliding: the plane of a part, axis-aligned exactly or not at all", "[sliding]")
{
  auto net = labelled_network<2>(box_mesh<2>({1}), {1});
  const auto plane = fit_boundary_plane(net, plane_label(1));
  CHECK(plane.axis == 1);
  CHECK(plane.normal[0] == 0.0);
  CHECK(std::abs(plane.normal[1]) == 1.0);
  // the outer boundary is three sides of a rectangle, not a line
  CHECK_THROWS_WITH(fit_boundary_plane(net, outer_label), Catch::Contains("is not planar"));
}

TEST_CASE("sliding: a cut 2D mesh with its symmetry line sliding moves as half of the whole one", "[sliding]")
{
  const Point<2> along{0.3, 0};
  // Element models split by element: the cut mesh's system is exactly half
  // of the mirrored whole's. (Edge springs do not: an edge in the plane has
  // one spring in both meshes while the springs leaving the plane are
  // doubled by the mirror; their test is equilibrium, below.)
  SECTION("ball-vertex springs (block model, normal component constrained)")
  {
    const auto r = mirror_run<2>({1}, along, Ball_vertex_stiffness{});
    CHECK(r.sliding > 0);
    CHECK(r.planes_kept);
    CHECK(r.largest_slide > 0.01);
    CHECK(r.largest_difference < 1e-10);
  }
  SECTION("held fixed instead, the cut differs from the whole mesh: the comparison can fail")
  {
    const auto r = mirror_run<2>({1}, along, Ball_vertex_stiffness{}, false);
    CHECK(r.sliding == 0);
    CHECK(r.largest_difference > 1e-3);
  }
}

TEST_CASE("sliding: a 3D quarter on two symmetry planes, sliding along their line, moves as the whole", "[sliding]")
{
  // the shift lies in both planes (y = 0 and z = 0): along x
  const auto r = mirror_run<3>({1, 2}, Point<3>{0.25, 0, 0}, Ball_vertex_stiffness{});
  CHECK(r.sliding > 0);
  CHECK(r.planes_kept);
  CHECK(r.largest_slide > 0.01);
  CHECK(r.largest_difference < 1e-10);
  const auto b = mirror_run<3>({2}, Point<3>{0.2, -0.15, 0}, Ball_vertex_stiffness{});
  CHECK(b.planes_kept);
  CHECK(b.largest_slide > 0.01);
  CHECK(b.largest_difference < 1e-10);
}

TEST_CASE("sliding: edge springs (a scalar model, solved in the planes' frame) are in equilibrium within the plane",
          "[sliding]")
{
  SECTION("2D, one line")
  {
    const auto r = equilibrium_run<2>({1}, Point<2>{0.3, 0});
    CHECK(r.planes_kept);
    CHECK(r.largest_slide > 0.01);
    CHECK(r.free_residual < 1e-10);
    CHECK(r.sliding_residual < 1e-10);
  }
  SECTION("3D, two planes and their line")
  {
    const auto r = equilibrium_run<3>({1, 2}, Point<3>{0.25, 0, 0});
    CHECK(r.planes_kept);
    CHECK(r.largest_slide > 0.01);
    CHECK(r.free_residual < 1e-10);
    CHECK(r.sliding_residual < 1e-10);
  }
  SECTION("the plane held fixed: its vertices are not in in-plane equilibrium, the check can fail")
  {
    const auto r = equilibrium_run<2>({1}, Point<2>{0.3, 0}, false);
    CHECK(r.largest_slide == 0);
    CHECK(r.sliding_residual > 1e-3);
  }
}

TEST_CASE("sliding: a plane that is no axis: the vertices stay on it and the motion is the rotated one",
          "[sliding]")
{
  // the cut mesh of the 2D mirror test turned by 30 degrees, its shift too
  const double a = 30 * M_PI / 180, c = std::cos(a), s = std::sin(a);
  const auto turn = [&](const Point<2>& p) { return Point<2>{c * p[0] - s * p[1], s * p[0] + c * p[1]}; };
  auto m = box_mesh<2>({1});
  auto straight = labelled_network<2>(m, {1});
  const auto facets = labelled_facets<2>(m, {1});
  for(auto& p : m.points)
    p = turn(p);
  Boundary_label_roles rules;
  rules.moving = {hole_label};
  rules.sliding = {plane_label(1)};
  // the labels of the straight mesh, on the turned points
  auto turned = make_spring_network<2>(m.points, m.elements, facets);
  Deform_options options;
  options.number_of_steps = 4;
  options.solver.tolerance = 1e-15;
  options.solver.max_iterations = 100000;
  const Point<2> shift{0.3, 0};
  Network_deformer<2> d0(straight, assign_roles(straight, rules));
  Network_deformer<2> d1(turned, assign_roles(turned, rules));
  REQUIRE(d0.run(Translation_motion<2>{shift}, Grid_scaled_stiffness{}, options).completed);
  REQUIRE(d1.run(Translation_motion<2>{turn(shift)}, Grid_scaled_stiffness{}, options).completed);
  // (both solved as block systems: scalar springs are rotation-invariant,
  // so the turned run is the straight one turned, up to the solver tolerance)
  REQUIRE(d1.number_of_sliding_vertices() > 0);
  const Point<2> normal{-s, c};
  double off = 0, diff = 0;
  for(Index i = 0; i < turned.number_of_vertices(); ++i) {
    const auto p = d1.positions()[i], q = turn(d0.positions()[i]);
    for(int k = 0; k < 2; ++k)
      diff = std::max(diff, std::abs(p[k] - q[k]));
    if(d1.roles()[i] == Vertex_role::sliding)
      off = std::max(off, std::abs(normal[0] * (p[0] - m.points[i][0]) + normal[1] * (p[1] - m.points[i][1])));
  }
  CHECK(off < 1e-15);
  CHECK(diff < 1e-10);
}

TEST_CASE("sliding: planes given instead of fitted", "[sliding]")
{
  CHECK(boundary_plane<2>(5, {0, -2}).axis == 1);
  CHECK(boundary_plane<2>(5, {0, -2}).normal == Point<2>{0, 1});
  CHECK_THROWS_WITH(boundary_plane<2>(5, {0, 0}), Catch::Contains("part 5 needs a finite non-zero normal"));
  CHECK_THROWS_WITH(boundary_plane<3>(5, {0, NAN, 1}), Catch::Contains("part 5 needs a finite non-zero normal"));

  auto m = box_mesh<2>({1});
  Boundary_label_roles rules;
  rules.moving = {hole_label};
  rules.sliding = {plane_label(1)};
  Deform_options options;
  options.number_of_steps = 4;
  options.solver.tolerance = 1e-15;
  const Point<2> shift{0.3, 0.2};
  {
    // the cut line y = 0 given as the line x = 0: the vertices keep their x
    // (the given plane is used, not the fitted one) and move along y
    auto net = labelled_network<2>(m, {1});
    const auto roles = assign_roles(net, rules);
    Network_deformer<2> d(net, roles, {boundary_plane<2>(plane_label(1), {1, 0})});
    REQUIRE(d.run(Translation_motion<2>{shift}, Grid_scaled_stiffness{}, options).completed);
    REQUIRE(d.number_of_sliding_vertices() > 0);
    double moved = 0;
    for(Index i = 0; i < net.number_of_vertices(); ++i)
      if(roles[i] == Vertex_role::sliding) {
        CHECK(d.positions()[i][0] == net.points[i][0]);
        moved = std::max(moved, std::abs(d.positions()[i][1] - net.points[i][1]));
      }
    CHECK(moved > 0.01);
  }
  {
    // a plane that is no axis, given with a normal of length 3: the same
    // motion as with the fitted plane, the vertices on it
    const double a = 30 * M_PI / 180, c = std::cos(a), s = std::sin(a);
    for(auto& p : m.points)
      p = Point<2>{c * p[0] - s * p[1], s * p[0] + c * p[1]};
    auto net = make_spring_network<2>(m.points, m.elements, labelled_facets<2>(box_mesh<2>({1}), {1}));
    const auto roles = assign_roles(net, rules);
    Network_deformer<2> fitted(net, roles);
    Network_deformer<2> given(net, roles, {boundary_plane<2>(plane_label(1), {-3 * s, 3 * c})});
    REQUIRE(fitted.run(Translation_motion<2>{shift}, Grid_scaled_stiffness{}, options).completed);
    REQUIRE(given.run(Translation_motion<2>{shift}, Grid_scaled_stiffness{}, options).completed);
    double off = 0, diff = 0;
    for(Index i = 0; i < net.number_of_vertices(); ++i) {
      for(int k = 0; k < 2; ++k)
        diff = std::max(diff, std::abs(given.positions()[i][k] - fitted.positions()[i][k]));
      if(roles[i] == Vertex_role::sliding)
        off = std::max(off, std::abs(-s * (given.positions()[i][0] - m.points[i][0]) +
                                     c * (given.positions()[i][1] - m.points[i][1])));
    }
    CHECK(off < 1e-15);
    CHECK(diff < 1e-12);
  }
}

TEST_CASE("sliding: a sliding part that is not planar is refused, naming it", "[sliding]")
{
  auto net = labelled_network<2>(box_mesh<2>({1}), {1});
  Boundary_label_roles rules;
  rules.moving = {hole_label};
  rules.sliding = {outer_label}; // three sides of a rectangle
  CHECK_THROWS_WITH((Network_deformer<2>(net, assign_roles(net, rules))),
                    Catch::Contains("sliding part 1 is not planar"));
}
