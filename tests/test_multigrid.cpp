// The multigrid preconditioner's coarse levels (internal/aggregation_multigrid.h),
// checked on a spring Laplacian built here: each coarse matrix is the
// Galerkin product P^T A P of the level above (summed independently here),
// the coarsest level is solved exactly, and the coarse correction
// P M_c^{-1} P^T is symmetric and positive semi-definite, which conjugate
// gradients need of a preconditioner. That the preconditioned solver reaches
// the direct solution is in test_solver.cpp.
#include <spring_motion/spring_motion.h>
#include <spring_motion/internal/aggregation_multigrid.h>

#include "test_meshes.h"

#include <catch2/catch.hpp>

#include <array>
#include <cmath>
#include <map>
#include <random>
#include <vector>

using namespace spring_motion;
using namespace spring_motion_test;
using internal::Aggregation_multigrid;
using internal::Csr_view;

namespace {

// A = diag - W on the free (interior) vertices of a Mesh_2 square with a
// hole, with graded weights k = 1/l^2; boundary vertices are constrained, so
// A is symmetric positive definite.
struct Laplacian
{
  std::vector<Index> offsets{0}, col;
  std::vector<double> weight, diag;
  Csr_view view() const { return {diag.size(), offsets.data(), col.data(), weight.data(), diag.data()}; }
};

Laplacian spring_laplacian(const Spring_network<2>& net, const std::vector<Vertex_role>& roles)
{
  const std::size_t n = net.number_of_vertices();
  std::vector<Index> row(n, Index(-1));
  Index nf = 0;
  for(std::size_t i = 0; i < n; ++i)
    if(roles[i] == Vertex_role::free)
      row[i] = nf++;
  Laplacian L;
  for(std::size_t i = 0; i < n; ++i) {
    if(row[i] == Index(-1))
      continue;
    double d = 0;
    for(Index p = net.adjacency_offsets[i]; p < net.adjacency_offsets[i + 1]; ++p) {
      const Index j = net.adjacency[p];
      const double dx = net.points[i][0] - net.points[j][0], dy = net.points[i][1] - net.points[j][1];
      const double w = 1.0 / (dx * dx + dy * dy);
      d += w;
      if(row[j] != Index(-1)) {
        L.col.push_back(row[j]);
        L.weight.push_back(w);
      }
    }
    L.diag.push_back(d);
    L.offsets.push_back(Index(L.col.size()));
  }
  return L;
}

using Vec = std::vector<std::array<double, 2>>;

// y = A x on a level
Vec multiply(const Csr_view& a, const Vec& x)
{
  Vec y(a.rows);
  for(std::size_t i = 0; i < a.rows; ++i)
    for(int c = 0; c < 2; ++c) {
      double s = a.diag[i] * x[i][c];
      for(Index q = a.offsets[i]; q < a.offsets[i + 1]; ++q)
        s -= a.weight[q] * x[a.col[q]][c];
      y[i][c] = s;
    }
  return y;
}

double dot(const Vec& a, const Vec& b)
{
  double s = 0;
  for(std::size_t i = 0; i < a.size(); ++i)
    s += a[i][0] * b[i][0] + a[i][1] * b[i][1];
  return s;
}

// u -> P M_c^{-1} P^T u on the fine level
Vec coarse_correction(Aggregation_multigrid<2>& mg, const Vec& u)
{
  mg.restrict_from(u);
  mg.cycle();
  Vec z(u.size());
  for(std::size_t i = 0; i < u.size(); ++i)
    z[i] = mg.coarse_solution(mg.parent(i));
  return z;
}

struct Setup
{
  Spring_network<2> net;
  Laplacian A;
};

Setup setup()
{
  CDT cdt;
  make_square_with_hole(cdt, 0.5, 10, 0.1); // about 3900 vertices, graded towards the hole
  Setup s;
  s.net = extract_spring_network(cdt).network;
  const auto roles = assign_roles(s.net, [&](const Vertex_info<2>& v) {
    return v.on_boundary ? Vertex_role::fixed : Vertex_role::free;
  });
  s.A = spring_laplacian(s.net, roles);
  return s;
}

} // namespace

TEST_CASE("multigrid: every coarse matrix is the Galerkin product P^T A P of the level above", "[solver][multigrid]")
{
  const Setup s = setup();
  Aggregation_multigrid<2> mg;
  mg.build(s.A.view());
  mg.load(s.A.view());
  REQUIRE(mg.number_of_levels() >= 2); // a smoothed level above the directly solved one
  Csr_view fine = s.A.view();
  for(std::size_t l = 0; l < mg.number_of_levels(); ++l) {
    INFO("level " << l << ": " << fine.rows << " -> " << mg.rows(l) << " unknowns");
    CHECK(mg.rows(l) * 2 < fine.rows); // it coarsens
    // (P^T A P)_{AB} = sum over i in A, j in B of A_ij, summed here entry by entry
    std::map<std::pair<Index, Index>, double> expected;
    for(std::size_t i = 0; i < fine.rows; ++i) {
      const Index a = mg.parent(l, i);
      expected[{a, a}] += fine.diag[i];
      for(Index q = fine.offsets[i]; q < fine.offsets[i + 1]; ++q)
        expected[{a, mg.parent(l, fine.col[q])}] -= fine.weight[q];
    }
    const Csr_view c = mg.matrix(l);
    std::size_t entries = 0;
    double worst = 0;
    for(std::size_t a = 0; a < c.rows; ++a) {
      const double e = expected.at({Index(a), Index(a)});
      worst = std::max(worst, std::abs(c.diag[a] - e) / std::abs(e));
      ++entries;
      for(Index q = c.offsets[a]; q < c.offsets[a + 1]; ++q) {
        const double v = expected.at({Index(a), c.col[q]});
        worst = std::max(worst, std::abs(-c.weight[q] - v) / std::abs(v));
        ++entries;
      }
    }
    CHECK(entries == expected.size()); // the pattern has every non-zero, once
    CHECK(worst < 1e-12);
    fine = c;
  }
}

TEST_CASE("multigrid: the coarsest level is solved exactly", "[solver][multigrid]")
{
  const Setup s = setup();
  Aggregation_multigrid<2> mg;
  mg.coarsest_rows = 2000; // one coarse level, which is then the coarsest
  mg.max_direct_rows = 2000;
  mg.build(s.A.view());
  mg.load(s.A.view());
  REQUIRE(mg.number_of_levels() == 1);
  REQUIRE(mg.rows(0) <= mg.max_direct_rows);
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> u(-1, 1);
  Vec r(s.A.diag.size());
  for(auto& v : r)
    v = {u(rng), u(rng)};
  mg.restrict_from(r);
  mg.cycle();
  // A_c z = P^T r
  Vec z(mg.rows(0)), rc(mg.rows(0), {0.0, 0.0});
  for(std::size_t a = 0; a < z.size(); ++a)
    z[a] = mg.coarse_solution(Index(a));
  for(std::size_t i = 0; i < r.size(); ++i)
    for(int c = 0; c < 2; ++c)
      rc[mg.parent(i)][c] += r[i][c];
  const Vec Az = multiply(mg.matrix(0), z);
  double err = 0, scale = 0;
  for(std::size_t a = 0; a < z.size(); ++a)
    for(int c = 0; c < 2; ++c) {
      err = std::max(err, std::abs(Az[a][c] - rc[a][c]));
      scale = std::max(scale, std::abs(rc[a][c]));
    }
  CHECK(err <= 1e-10 * scale);
}

TEST_CASE("multigrid: the coarse correction is symmetric and positive semi-definite", "[solver][multigrid]")
{
  const Setup s = setup();
  Aggregation_multigrid<2> mg;
  mg.build(s.A.view());
  mg.load(s.A.view());
  REQUIRE(mg.number_of_levels() >= 2);
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> d(-1, 1);
  for(int trial = 0; trial < 5; ++trial) {
    Vec u(s.A.diag.size()), v(s.A.diag.size());
    for(std::size_t i = 0; i < u.size(); ++i) {
      u[i] = {d(rng), d(rng)};
      v[i] = {d(rng), d(rng)};
    }
    const Vec Tu = coarse_correction(mg, u), Tv = coarse_correction(mg, v);
    const double a = dot(Tu, v), b = dot(u, Tv);
    INFO("<Tu, v> = " << a << ", <u, Tv> = " << b);
    CHECK(std::abs(a - b) <= 1e-10 * std::sqrt(dot(Tu, Tu) * dot(v, v)));
    CHECK(dot(Tu, u) > 0);
  }
}
