// Copyright (c) 2026 SpringMotion developers.
// The partition of a mesh over MPI ranks (internal/geometry/partition.h),
// without MPI: each part's owned rows of the step system must be the whole
// mesh's rows, since a rank inserts them into the distributed matrix as they are.
#include <spring_motion/internal/geometry/partition.h>
#include <spring_motion/spring_motion.h>
#include <spring_motion/stiffness/model_by_name.h>

#include "test_meshes.h"

#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <map>
#include <vector>

using namespace spring_motion;

namespace {

// One row of a step system by network vertex: diagonal, right-hand side,
// and the entries by neighbouring vertex (1 value, or a D x D block).
template <int D>
struct Row
{
  std::vector<double> diagonal;
  std::array<double, D> rhs{};
  std::map<Index, std::vector<double>> entries;
};

// The first step's system of `model` on (net, roles), rows by whole-mesh
// vertex through `global` (identity when empty), for the rows whose vertex
// `keep` accepts. The solve is replaced by the starting iterate: only the
// system matters here.
template <int D, class Motion>
std::map<Index, Row<D>> first_system(Network_deformer<D>& d, const Motion& motion, const std::string& model,
                                     const std::vector<Index>& global, std::size_t keep)
{
  std::map<Index, Row<D>> rows;
  d.system_observer = [&](const Step_system_view<D>& v) {
    const std::size_t w = v.block ? std::size_t(D * D) : 1;
    const auto g = [&](Index local) { return global.empty() ? local : global[local]; };
    for(std::size_t r = 0; r < v.rows; ++r) {
      if(v.vertices[r] >= keep)
        continue;
      Row<D>& row = rows[g(v.vertices[r])];
      row.diagonal.assign(v.diagonal + r * w, v.diagonal + (r + 1) * w);
      row.rhs = v.rhs[r];
      for(Index q = v.row_offsets[r]; q < v.row_offsets[r + 1]; ++q)
        row.entries[g(v.vertices[v.columns[q]])].assign(v.values + q * w, v.values + (q + 1) * w);
    }
  };
  d.solve_override = [](const Step_system_view<D>& v, std::vector<std::array<double, D>>& x) {
    x.assign(v.initial, v.initial + v.rows);
    return Solve_report{};
  };
  Deform_options options;
  options.number_of_steps = 1;
  with_model(model, [&](const auto& m) { return d.run(motion, m, options); });
  return rows;
}

template <int D>
void check_close(const std::vector<double>& a, const std::vector<double>& b, double scale)
{
  REQUIRE(a.size() == b.size());
  for(std::size_t k = 0; k < a.size(); ++k)
    CHECK(std::abs(a[k] - b[k]) <= 1e-12 * scale);
}

template <int D, class Motion>
void check_parts(const Spring_network<D>& net, const std::vector<Vertex_role>& roles, const Motion& motion,
                 const std::string& model, int parts)
{
  INFO("model " << model << ", " << parts << " parts");
  const std::vector<int> owner = internal::partition_vertices(net, parts);
  // balanced: the parts' sizes differ by at most one vertex
  std::vector<std::size_t> size(std::size_t(parts), 0);
  for(int o : owner) {
    REQUIRE(o >= 0);
    REQUIRE(o < parts);
    ++size[std::size_t(o)];
  }
  CHECK(*std::max_element(size.begin(), size.end()) - *std::min_element(size.begin(), size.end()) <= 1);

  Network_deformer<D> whole(net, roles);
  const auto expected = first_system<D>(whole, motion, model, {}, net.number_of_vertices());
  REQUIRE(!expected.empty());
  // the parts' deformers get the planes of the sliding parts fitted on the whole mesh
  const std::vector<Boundary_plane<D>> planes = sliding_planes(net, roles);
  const std::vector<char> solved =
      internal::solved_vertices(used_vertices(net), roles, internal::sliding_set(net, roles, planes));

  std::map<Index, Row<D>> got;
  std::vector<int> counted(net.number_of_elements(), 0);
  std::vector<std::size_t> rows_seen;
  for(int p = 0; p < parts; ++p) {
    internal::Mesh_part<D> part = internal::extract_part(net, roles, solved, owner, parts, p);
    for(std::size_t t = 0; t < part.global_element.size(); ++t)
      counted[part.global_element[t]] += part.counted[t];
    for(std::size_t i = 0; i < part.global_vertex.size(); ++i) {
      const std::size_t row = part.free_row[i];
      // a row for the vertices the whole mesh's system has
      CHECK((row == part.no_row) == (expected.count(part.global_vertex[i]) == 0));
      if(i < part.owned_vertices && row != part.no_row) {
        CHECK(row >= part.first_row);
        CHECK(row < part.first_row + part.owned_rows);
        rows_seen.push_back(row);
      }
    }
    Network_deformer<D> d(std::move(part.network), part.roles, planes, Role_checks::by_caller);
    for(auto& [v, row] : first_system<D>(d, motion, model, part.global_vertex, part.owned_vertices))
      got[v] = std::move(row);
  }
  // every element counted by one part, every free vertex a row of one part
  CHECK(std::all_of(counted.begin(), counted.end(), [](int c) { return c == 1; }));
  std::sort(rows_seen.begin(), rows_seen.end());
  CHECK(rows_seen.size() == expected.size());
  for(std::size_t k = 0; k < rows_seen.size(); ++k)
    CHECK(rows_seen[k] == k);
  // the owned rows are the whole mesh's rows, entry by entry
  REQUIRE(got.size() == expected.size());
  for(const auto& [v, row] : expected) {
    INFO("vertex " << v);
    const Row<D>& mine = got.at(v);
    const double scale = std::abs(row.diagonal[0]);
    check_close<D>(mine.diagonal, row.diagonal, scale);
    check_close<D>(std::vector<double>(mine.rhs.begin(), mine.rhs.end()),
                   std::vector<double>(row.rhs.begin(), row.rhs.end()), scale);
    REQUIRE(mine.entries.size() == row.entries.size());
    for(const auto& [u, values] : row.entries) {
      REQUIRE(mine.entries.count(u) == 1);
      check_close<D>(mine.entries.at(u), values, scale);
    }
  }
}

} // namespace

TEST_CASE("partition: each part's owned rows are the whole system's, NACA0012 airfoil", "[partition]")
{
  const auto [net, roles] = spring_motion_test::naca0012_network();
  for(const std::string model : {"grid_scaled", "ball_vertex", "grid_scaled+ball_vertex"})
    for(int parts : {1, 3, 4})
      check_parts<2>(net, roles, Pitch_motion<2>(10, {0.25, 0}), model, parts);
}

TEST_CASE("partition: each part's owned rows are the whole system's, 3D block of cubes", "[partition]")
{
  // 5 x 5 x 5 cubes of six tetrahedra each, interior vertices jittered; the top face moves
  const int m = 5;
  const auto grid = spring_motion_test::kuhn_grid<3>(m);
  const auto net = make_spring_network<3>(grid.points, grid.elements);
  const auto roles = assign_roles(net, [&](const Vertex_info<3>& v) {
    return !v.on_boundary ? Vertex_role::free : (v.point[2] == m ? Vertex_role::moving : Vertex_role::fixed);
  });
  for(const std::string model : {"grid_scaled", "ball_vertex"})
    for(int parts : {2, 5})
      check_parts<3>(net, roles, Translation_motion<3>{{0.3, 0.2, -0.4}}, model, parts);
}

// A Kuhn grid [0,m]^D whose faces x_a = 0 (a in `sliding`) slide, label
// a + 1, the face x_{D-1} = m moving (label 10), the others fixed (11).
template <int D>
std::pair<Spring_network<D>, std::vector<Vertex_role>> sliding_grid(int m, const std::vector<int>& sliding)
{
  const auto grid = spring_motion_test::kuhn_grid<D>(m);
  const auto plain = make_spring_network<D>(grid.points, grid.elements);
  std::vector<Labeled_facet<D>> facets;
  for(const auto& f : plain.boundary_facets) {
    int label = 11;
    for(int a = 0; a < D; ++a) {
      const bool all_zero = std::all_of(f.begin(), f.end(), [&](Index v) { return grid.points[v][a] == 0; });
      const bool all_top = std::all_of(f.begin(), f.end(), [&](Index v) { return grid.points[v][a] == m; });
      if(all_zero && std::find(sliding.begin(), sliding.end(), a) != sliding.end())
        label = a + 1;
      if(all_top && a == D - 1)
        label = 10;
    }
    facets.push_back({f, label});
  }
  auto net = make_spring_network<D>(grid.points, grid.elements, facets);
  Boundary_label_roles rules;
  rules.moving = {10};
  for(int a : sliding)
    rules.sliding.push_back(a + 1);
  auto roles = assign_roles(net, rules);
  return {std::move(net), std::move(roles)};
}

TEST_CASE("partition: with sliding vertices, each part's owned rows are the whole system's", "[partition]")
{
  // sliding vertices' rows are projected (P A P + s (I - P)): a part's rows
  // need its ghosts' planes too, which it gets fitted on the whole mesh
  {
    const auto [net, roles] = sliding_grid<2>(8, {0, 1});
    CHECK(std::count(roles.begin(), roles.end(), Vertex_role::sliding) == 8 + 7);
    for(const std::string model : {"grid_scaled", "ball_vertex"})
      for(int parts : {3, 7})
        check_parts<2>(net, roles, Translation_motion<2>{{0.3, -0.2}}, model, parts);
  }
  {
    // three planes: vertices on two slide along their line, the corner is pinned
    const auto [net, roles] = sliding_grid<3>(4, {0, 1, 2});
    CHECK(std::count(roles.begin(), roles.end(), Vertex_role::sliding) == 3 * 3 * 3 + 3 * 3 + 1);
    for(const std::string model : {"grid_scaled", "ball_vertex"})
      for(int parts : {2, 5})
        check_parts<3>(net, roles, Translation_motion<3>{{0.3, 0.2, -0.4}}, model, parts);
  }
}

TEST_CASE("partition: a part may hold too few of a plane's vertices to fit it, the whole mesh's planes serve it",
          "[partition]")
{
  // a part that owns one vertex next to the planes: its ghosts on a plane
  // may lie on a line, which spans no plane
  const auto [net, roles] = sliding_grid<3>(3, {0, 1, 2});
  const std::vector<Boundary_plane<3>> planes = sliding_planes(net, roles);
  REQUIRE(planes.size() == 3);
  const std::vector<char> solved =
      internal::solved_vertices(used_vertices(net), roles, internal::sliding_set(net, roles, planes));
  std::size_t found = 0;
  for(Index v = 0; v < net.number_of_vertices(); ++v) {
    std::vector<int> owner(net.number_of_vertices(), 0);
    owner[v] = 1;
    const auto part = internal::extract_part(net, roles, solved, owner, 2, 1);
    try {
      Network_deformer<3>(part.network, part.roles, Role_checks::by_caller);
    } catch(const Error& e) {
      INFO("vertex " << v << ": " << e.what());
      CHECK_THAT(e.what(), Catch::Contains("spans no plane") || Catch::Contains("too few to span a plane"));
      CHECK_NOTHROW(Network_deformer<3>(part.network, part.roles, planes, Role_checks::by_caller));
      ++found;
    }
  }
  CHECK(found > 0);
}

TEST_CASE("partition: more parts than vertices leaves parts without vertices, each still a valid network",
          "[partition]")
{
  const auto net = make_spring_network<2>({{0, 0}, {1, 0}, {0, 1}, {1, 1}}, {{0, 1, 2}, {1, 3, 2}});
  const std::vector<Vertex_role> roles(4, Vertex_role::moving);
  const std::vector<int> owner = internal::partition_vertices(net, 6);
  for(int p = 0; p < 6; ++p) {
    const auto part = internal::extract_part(net, roles, std::vector<char>(4, 0), owner, 6, p);
    const std::size_t owned = std::size_t(std::count(owner.begin(), owner.end(), p));
    CHECK(part.owned_vertices == owned);
    CHECK(part.network.number_of_elements() >= 1);
    if(owned == 0)
      CHECK(std::none_of(part.counted.begin(), part.counted.end(), [](char c) { return c != 0; }));
  }
  // four vertices over six parts: one each for four parts, two parts empty
  for(int p = 0; p < 6; ++p)
    CHECK(std::count(owner.begin(), owner.end(), p) <= 1);
  std::vector<int> sorted(owner);
  std::sort(sorted.begin(), sorted.end());
  CHECK(std::unique(sorted.begin(), sorted.end()) == sorted.end());
}

TEST_CASE("partition: a step is accepted only when every part agrees", "[partition]")
{
  // the part's own check passes (a small rotation), but another part's
  // verdict is "invalid": the step must be rejected and the state kept
  const auto [net, roles] = spring_motion_test::naca0012_network();
  Network_deformer<2> d(net, roles);
  std::vector<bool> verdicts;
  d.agree_on_validity = [&](bool valid) {
    verdicts.push_back(valid);
    return false;
  };
  Deform_options options;
  options.number_of_steps = 2;
  options.max_substep_halvings = 1;
  const auto r = d.run(Pitch_motion<2>(2, {0.25, 0}), Grid_scaled_stiffness{}, options);
  CHECK_FALSE(r.completed);
  REQUIRE(r.first_invalid.has_value());
  CHECK(r.first_invalid->step == 1);
  CHECK(r.first_invalid->elements.empty()); // none inverted here
  CHECK(d.fraction() == 0);
  CHECK(d.positions() == net.points);
  // asked once for the whole step and once for each of its two substeps' first
  REQUIRE(verdicts.size() == 2);
  CHECK(verdicts[0]);
  CHECK(verdicts[1]);
}
