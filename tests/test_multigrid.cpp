// The multigrid preconditioner's coarse levels: of scalar systems
// (internal/solver/aggregation_multigrid.h), checked on a spring Laplacian,
// and of block systems (internal/solver/rigid_body_multigrid.h), checked on a
// 2x2-block spring system, both built here. Each coarse matrix is the
// Galerkin product P^T A P of the level above (summed independently here),
// the coarsest level is solved exactly (for block systems: every rigid motion
// of the mesh is reproduced), and the coarse correction P M_c^{-1} P^T is
// symmetric and positive semi-definite, which conjugate gradients need of a
// preconditioner. That the preconditioned solver reaches the direct solution
// is in test_solver.cpp.
// Loops of any size take the parallel path where two threads are asked for,
// so that the small systems here exercise it.
#define SPRING_MOTION_PARALLEL_THRESHOLD 1
#include <spring_motion/spring_motion.h>
#include <spring_motion/internal/solver/aggregation_multigrid.h>
#include <spring_motion/internal/solver/aggregation_refresh.h>
#include <spring_motion/internal/solver/chebyshev.h>
#include <spring_motion/internal/solver/dense_cholesky.h>
#include <spring_motion/internal/solver/rigid_body_multigrid.h>

#include "test_meshes.h"
#include "test_operators.h"

#include <Eigen/Dense>
#include <Eigen/Sparse>
#include <catch2/catch.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <random>
#include <string>
#include <vector>

using namespace spring_motion;
using namespace spring_motion_test;
using internal::Aggregation_multigrid;
using internal::Csr_view;

namespace {

// On the free (interior) vertices of a Mesh_2 square with a hole (boundary
// vertices constrained, so the matrix is symmetric positive definite), with
// graded springs k = 1/l^2: scalar: the spring Laplacian (entries -k);
// block: each edge adds the D x D block B = k (e e^T / |e|^2 + I / 4) (a
// truss along the edge plus a weaker per-coordinate spring), +B on both
// diagonals and -B off the diagonal, as element models' edge springs do.
struct Laplacian
{
  bool block = false;
  std::vector<Index> offsets{0}, col;
  std::vector<double> values, diag; // 1 or D * D per entry / row
  std::size_t rows() const { return offsets.size() - 1; }
  Csr_view view() const { return {rows(), offsets.data(), col.data(), values.data(), diag.data(), block}; }
};

template <int D>
Laplacian spring_laplacian(const Spring_network<D>& net, const std::vector<Vertex_role>& roles, bool block)
{
  const std::size_t n = net.number_of_vertices();
  std::vector<Index> row(n, Index(-1));
  Index nf = 0;
  for(std::size_t i = 0; i < n; ++i)
    if(roles[i] == Vertex_role::free)
      row[i] = nf++;
  Laplacian L;
  L.block = block;
  for(std::size_t i = 0; i < n; ++i) {
    if(row[i] == Index(-1))
      continue;
    const int w = block ? D * D : 1;
    std::array<double, D * D> d{};
    for(Index p = net.adjacency_offsets[i]; p < net.adjacency_offsets[i + 1]; ++p) {
      const Index j = net.adjacency[p];
      std::array<double, D> e;
      double l2 = 0;
      for(int c = 0; c < D; ++c) {
        e[std::size_t(c)] = net.points[i][std::size_t(c)] - net.points[j][std::size_t(c)];
        l2 += e[std::size_t(c)] * e[std::size_t(c)];
      }
      const double k = 1.0 / l2;
      std::array<double, D * D> B{};
      if(!block)
        B[0] = k;
      else
        for(int r = 0; r < D; ++r)
          for(int c = 0; c < D; ++c)
            B[std::size_t(r * D + c)] = r == c ? k * (e[std::size_t(r)] * e[std::size_t(r)] / l2 + 0.25)
                                               : k * e[std::size_t(r)] * e[std::size_t(c)] / l2;
      for(int c = 0; c < w; ++c)
        d[std::size_t(c)] += B[std::size_t(c)];
      if(row[j] != Index(-1)) {
        L.col.push_back(row[j]);
        for(int c = 0; c < w; ++c)
          L.values.push_back(-B[std::size_t(c)]);
      }
    }
    for(int c = 0; c < w; ++c)
      L.diag.push_back(d[std::size_t(c)]);
    L.offsets.push_back(Index(L.col.size()));
  }
  return L;
}

// y = A x on a level
Vec multiply(const Csr_view& a, const Vec& x)
{
  Vec y(a.rows);
  for(std::size_t i = 0; i < a.rows; ++i)
    for(int r = 0; r < 2; ++r) {
      double s = 0;
      if(a.block) {
        for(int c = 0; c < 2; ++c)
          s += a.diag[4 * i + std::size_t(2 * r + c)] * x[i][std::size_t(c)];
        for(Index q = a.offsets[i]; q < a.offsets[i + 1]; ++q)
          for(int c = 0; c < 2; ++c)
            s += a.values[4 * q + std::size_t(2 * r + c)] * x[a.col[q]][std::size_t(c)];
      } else {
        s = a.diag[i] * x[i][std::size_t(r)];
        for(Index q = a.offsets[i]; q < a.offsets[i + 1]; ++q)
          s += a.values[q] * x[a.col[q]][std::size_t(r)];
      }
      y[i][std::size_t(r)] = s;
    }
  return y;
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

Setup setup(bool block, double size = 0.1)
{
  CDT cdt;
  make_square_with_hole(cdt, 0.5, 10, size); // size 0.1: about 3900 vertices, graded towards the hole
  Setup s;
  s.net = extract_spring_network(cdt).network;
  const auto roles = assign_roles(s.net, [&](const Vertex_info<2>& v) {
    return v.on_boundary ? Vertex_role::fixed : Vertex_role::free;
  });
  s.A = spring_laplacian(s.net, roles, block);
  return s;
}

} // namespace

TEST_CASE("multigrid: every coarse matrix is the Galerkin product P^T A P of the level above", "[solver][multigrid]")
{
  const Setup s = setup(false);
  const std::size_t w = 1;
  Aggregation_multigrid<2> mg;
  mg.build(s.A.view());
  mg.load(s.A.view());
  REQUIRE(mg.number_of_levels() >= 2); // a smoothed level above the directly solved one
  Csr_view fine = s.A.view();
  for(std::size_t l = 0; l < mg.number_of_levels(); ++l) {
    INFO("level " << l << ": " << fine.rows << " -> " << mg.rows(l) << " unknowns");
    CHECK(mg.rows(l) * 2 < fine.rows); // it coarsens
    // (P^T A P)_{AB} = sum over i in A, j in B of A_ij (blocks for a block
    // system), summed here entry by entry
    std::map<std::pair<Index, Index>, std::array<double, 4>> expected;
    for(std::size_t i = 0; i < fine.rows; ++i) {
      const Index a = mg.parent(l, i);
      for(std::size_t k = 0; k < w; ++k)
        expected[{a, a}][k] += fine.diag[i * w + k];
      for(Index q = fine.offsets[i]; q < fine.offsets[i + 1]; ++q)
        for(std::size_t k = 0; k < w; ++k)
          expected[{a, mg.parent(l, fine.col[q])}][k] += fine.values[q * w + k];
    }
    const Csr_view c = mg.matrix(l);
    REQUIRE(!c.block);
    std::size_t entries = 0;
    double worst = 0;
    // relative to the largest value of the block: a block's small entries
    // are sums of cancelling terms
    auto compare = [&](const double* got, const std::array<double, 4>& e) {
      double scale = 0;
      for(std::size_t k = 0; k < w; ++k)
        scale = std::max(scale, std::abs(e[k]));
      for(std::size_t k = 0; k < w; ++k)
        worst = std::max(worst, std::abs(got[k] - e[k]) / scale);
    };
    for(std::size_t a = 0; a < c.rows; ++a) {
      compare(c.diag + a * w, expected.at({Index(a), Index(a)}));
      ++entries;
      for(Index q = c.offsets[a]; q < c.offsets[a + 1]; ++q) {
        compare(c.values + q * w, expected.at({Index(a), c.col[q]}));
        ++entries;
      }
    }
    CHECK(entries == expected.size()); // the pattern has every non-zero, once
    CHECK(worst < 1e-12);
    fine = c;
  }
}

namespace {

// The block spring system of a 3D Kuhn grid (interior vertices free) with
// the couplings of one vertex, row and column, scaled by 1e-3: it then has
// no strong neighbour, and plain aggregation leaves it alone (a one-vertex
// aggregate, which cannot carry a rotation). Still symmetric positive
// definite: the diagonal is kept. Returns the weakened row.
Index weaken_one_vertex(Laplacian& A)
{
  const Index v = Index(A.rows() / 2);
  const int w = A.block ? 9 : 1;
  for(std::size_t i = 0; i < A.rows(); ++i)
    for(Index q = A.offsets[i]; q < A.offsets[i + 1]; ++q)
      if(Index(i) == v || A.col[q] == v)
        for(int c = 0; c < w; ++c)
          A.values[std::size_t(q) * std::size_t(w) + std::size_t(c)] *= 1e-3;
  return v;
}

Laplacian kuhn_grid_system(bool block)
{
  const auto mesh = kuhn_grid<3>(12);
  const auto net = make_spring_network<3>(mesh.points, mesh.elements);
  const auto roles = assign_roles(net, [&](const Vertex_info<3>& v) {
    return v.on_boundary ? Vertex_role::fixed : Vertex_role::free;
  });
  return spring_laplacian(net, roles, block);
}

std::vector<std::size_t> aggregate_sizes(const internal::Aggregates& g)
{
  std::vector<std::size_t> size(g.count, 0);
  for(const Index a : g.parent_of)
    ++size[a];
  return size;
}

} // namespace

TEST_CASE("multigrid: with a minimum size, every smaller aggregate joins, whole, the neighbour it is most coupled to",
          "[solver][multigrid]")
{
  Laplacian A = kuhn_grid_system(false);
  const Index v = weaken_one_vertex(A);
  const std::size_t n = A.rows();
  std::vector<double> coupling(A.values.size());
  for(std::size_t q = 0; q < coupling.size(); ++q)
    coupling[q] = -A.values[q];
  internal::Aggregates plain, joined;
  REQUIRE(internal::aggregate_strong_neighbours(n, A.offsets.data(), A.col.data(), A.diag, coupling, 0.04, plain));
  REQUIRE(internal::aggregate_strong_neighbours(n, A.offsets.data(), A.col.data(), A.diag, coupling, 0.04, joined,
                                                3));
  const auto plain_size = aggregate_sizes(plain), joined_size = aggregate_sizes(joined);
  REQUIRE(plain_size[plain.parent_of[v]] == 1); // the case the minimum is for
  for(const std::size_t s : joined_size)
    CHECK(s >= 3);
  // every plain aggregate of at least 3 keeps its members together and
  // apart from the other such aggregates; each smaller one moves whole into
  // the large one it is most coupled to (the largest entry from any member)
  std::map<Index, Index> image; // plain aggregate -> joined aggregate
  std::size_t small = 0;
  for(std::size_t i = 0; i < n; ++i) {
    const Index a = plain.parent_of[i];
    const auto [it, fresh] = image.emplace(a, joined.parent_of[i]);
    CHECK(it->second == joined.parent_of[i]);
    if(fresh && plain_size[a] < 3)
      ++small;
  }
  CHECK(joined.count == plain.count - small);
  for(Index a = 0; a < Index(plain.count); ++a) {
    if(plain_size[a] >= 3)
      continue;
    double best = 0;
    Index to = Index(-1);
    for(Index m = plain.member_offsets[a]; m < plain.member_offsets[a + 1]; ++m)
      for(Index q = A.offsets[plain.members[m]]; q < A.offsets[plain.members[m] + 1]; ++q)
        if(plain_size[plain.parent_of[A.col[q]]] >= 3 && coupling[q] > best) {
          best = coupling[q];
          to = plain.parent_of[A.col[q]];
        }
    REQUIRE(to != Index(-1));
    CHECK(image[a] == image[to]);
  }
  // the members lists and the coarse pattern describe the joined aggregates
  for(Index a = 0; a < Index(joined.count); ++a) {
    CHECK(joined.member_offsets[a + 1] - joined.member_offsets[a] == Index(joined_size[a]));
    for(Index m = joined.member_offsets[a]; m < joined.member_offsets[a + 1]; ++m)
      CHECK(joined.parent_of[joined.members[m]] == a);
  }
  for(std::size_t i = 0; i < n; ++i)
    for(Index q = A.offsets[i]; q < A.offsets[i + 1]; ++q) {
      const Index a = joined.parent_of[i], b = joined.parent_of[A.col[q]];
      if(a == b)
        CHECK(joined.slot_of[q] == Index(-1));
      else
        CHECK(joined.col[joined.slot_of[q]] == b);
    }
}

TEST_CASE("multigrid: the coarsest level is solved exactly", "[solver][multigrid]")
{
  const Setup s = setup(false);
  Aggregation_multigrid<2> mg;
  mg.parameters.coarsest_rows = 2000; // one coarse level, which is then the coarsest
  mg.parameters.max_direct_rows = 2000;
  mg.build(s.A.view());
  mg.load(s.A.view());
  REQUIRE(mg.number_of_levels() == 1);
  REQUIRE(mg.rows(0) <= mg.parameters.max_direct_rows);
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> u(-1, 1);
  Vec r(s.A.rows());
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
  const Setup s = setup(false);
  Aggregation_multigrid<2> mg;
  mg.build(s.A.view());
  mg.load(s.A.view());
  REQUIRE(mg.number_of_levels() >= 2);
  check_symmetric_positive([&](const Vec& u) { return coarse_correction(mg, u); }, s.A.rows(), 7);
}

// ---- block systems: coarse functions that move each aggregate rigidly ----

namespace {

using internal::Rigid_body_multigrid;
using Rigid = Rigid_body_multigrid<2>;
constexpr int R = Rigid::R; // 2 translations and a rotation

// the positions of the vertices not on the boundary, in index order
template <int D>
std::vector<std::array<double, D>> free_points(const Spring_network<D>& net)
{
  std::vector<std::array<double, D>> p;
  for(std::size_t i = 0; i < net.number_of_vertices(); ++i)
    if(!net.on_boundary[i])
      p.push_back(net.points[i]);
  return p;
}

// the D x R prolongation block of a point at offset d from its aggregate's
// centre, written out here: translations, and the rotation w (-d_y, d_x)
std::array<double, 2 * R> rigid_block(const std::array<double, 2>& d)
{
  return {1, 0, -d[1], 0, 1, d[0]};
}

// u -> P M_c^{-1} P^T u on the fine level, P the rigid motions of the aggregates
Vec rigid_correction(Rigid& mg, const Vec& u)
{
  mg.restrict_from(u);
  mg.cycle();
  Vec z(u.size());
  for(std::size_t i = 0; i < u.size(); ++i)
    z[i] = mg.correction(i);
  return z;
}

} // namespace

TEST_CASE("rigid-body multigrid: level 0 is the Galerkin product P^T A P with rigid motions of the aggregates",
          "[solver][multigrid]")
{
  const Setup s = setup(true);
  const auto points = free_points(s.net);
  REQUIRE(points.size() == s.A.rows());
  Rigid mg;
  mg.build(s.A.view(), points.data());
  mg.load(s.A.view(), points.data());
  REQUIRE(mg.number_of_levels() >= 2);
  const Csr_view fine = s.A.view();
  // centres as the mean of the members, and P_i from them, independently
  const std::size_t na = mg.rows(0);
  std::vector<std::array<double, 2>> centre(na, {0.0, 0.0});
  std::vector<double> count(na, 0);
  for(std::size_t i = 0; i < fine.rows; ++i) {
    const Index a = mg.parent(0, i);
    centre[a][0] += points[i][0];
    centre[a][1] += points[i][1];
    count[a] += 1;
  }
  for(std::size_t a = 0; a < na; ++a)
    for(int c = 0; c < 2; ++c) {
      centre[a][std::size_t(c)] /= count[a];
      CHECK(std::abs(mg.centre(0, Index(a))[std::size_t(c)] - centre[a][std::size_t(c)]) <= 1e-12);
    }
  auto P = [&](std::size_t i) {
    const Index a = mg.parent(0, i);
    return rigid_block({points[i][0] - centre[a][0], points[i][1] - centre[a][1]});
  };
  std::map<std::pair<Index, Index>, std::array<double, R * R>> expected;
  auto add = [&](Index a, Index b, const double* A, const std::array<double, 2 * R>& Pi,
                 const std::array<double, 2 * R>& Pj) {
    auto& e = expected[{a, b}];
    for(int r = 0; r < R; ++r)
      for(int c = 0; c < R; ++c)
        for(int k = 0; k < 2; ++k)
          for(int m = 0; m < 2; ++m)
            e[std::size_t(r * R + c)] += Pi[std::size_t(k * R + r)] * A[k * 2 + m] * Pj[std::size_t(m * R + c)];
  };
  for(std::size_t i = 0; i < fine.rows; ++i) {
    add(mg.parent(0, i), mg.parent(0, i), fine.diag + 4 * i, P(i), P(i));
    for(Index q = fine.offsets[i]; q < fine.offsets[i + 1]; ++q)
      add(mg.parent(0, i), mg.parent(0, fine.col[q]), fine.values + 4 * q, P(i), P(fine.col[q]));
  }
  double worst = 0;
  std::size_t entries = 0;
  auto compare = [&](const double* got, const std::array<double, R * R>& e) {
    double scale = 0;
    for(double v : e)
      scale = std::max(scale, std::abs(v));
    for(std::size_t k = 0; k < R * R; ++k)
      worst = std::max(worst, std::abs(got[k] - e[k]) / scale);
    ++entries;
  };
  const auto& off = mg.offsets(0);
  for(std::size_t a = 0; a < na; ++a) {
    compare(&mg.diagonal(0)[a * R * R], expected.at({Index(a), Index(a)}));
    for(Index q = off[a]; q < off[a + 1]; ++q)
      compare(&mg.values(0)[q * R * R], expected.at({Index(a), mg.columns(0)[q]}));
  }
  CHECK(entries == expected.size());
  CHECK(worst < 1e-12);
}

namespace {

// C = P_i^T A P_j summed densely for an F x F block A: P = [I | S(d)] (F =
// D, a fine vertex) or [[I, S(d)], [0, I]] (F = R, a coarse node whose
// rotations carry over), column k of S(d) the displacement at offset d of
// unit rotation k, written out here: in 3D e_k x d
template <int D, int F>
std::vector<double> dense_rigid_galerkin(const std::vector<double>& A, const std::array<double, D>& di,
                                         const std::array<double, D>& dj)
{
  constexpr int RD = D * (D + 1) / 2;
  auto P = [](const std::array<double, D>& d) {
    std::vector<double> p(std::size_t(F * RD), 0.0);
    for(int c = 0; c < D; ++c)
      p[std::size_t(c * RD + c)] = 1;
    if constexpr(D == 2) {
      p[2] = -d[1];
      p[5] = d[0];
    } else {
      const double x = d[0], y = d[1], z = d[2];
      const double S[3][3] = {{0, z, -y}, {-z, 0, x}, {y, -x, 0}}; // S[r][k] = (e_k x d)_r
      for(int r = 0; r < 3; ++r)
        for(int k = 0; k < 3; ++k)
          p[std::size_t(r * RD + 3 + k)] = S[r][k];
    }
    if constexpr(F == RD)
      for(int k = D; k < RD; ++k)
        p[std::size_t(k * RD + k)] = 1;
    return p;
  };
  const auto Pi = P(di), Pj = P(dj);
  std::vector<double> C(std::size_t(RD * RD), 0.0);
  for(int r = 0; r < RD; ++r)
    for(int c = 0; c < RD; ++c)
      for(int k = 0; k < F; ++k)
        for(int m = 0; m < F; ++m)
          C[std::size_t(r * RD + c)] += Pi[std::size_t(k * RD + r)] * A[std::size_t(k * F + m)] *
                                        Pj[std::size_t(m * RD + c)];
  return C;
}

template <int D, int F>
void check_galerkin_by_blocks()
{
  using M = Rigid_body_multigrid<D>;
  std::mt19937 gen(17 + 10 * D + F);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for(int trial = 0; trial < 20; ++trial) {
    std::vector<double> A(std::size_t(F * F));
    for(double& a : A)
      a = u(gen);
    std::array<double, D> di, dj;
    for(int c = 0; c < D; ++c) {
      di[std::size_t(c)] = 3 * u(gen);
      dj[std::size_t(c)] = 3 * u(gen);
    }
    const auto expected = dense_rigid_galerkin<D, F>(A, di, dj);
    std::vector<double> C(expected.size(), 0.5); // added to, not overwritten
    M::template add_galerkin_by_blocks<F>(A.data(), di, dj, C.data());
    for(std::size_t k = 0; k < C.size(); ++k)
      CHECK(std::abs((C[k] - 0.5) - expected[k]) <= 1e-13 * (1 + std::abs(expected[k])));
  }
}

} // namespace

TEST_CASE("rigid-body multigrid: the blockwise Galerkin product of a block equals the dense P_i^T A P_j",
          "[solver][multigrid]")
{
  SECTION("2D, fine block") { check_galerkin_by_blocks<2, 2>(); }
  SECTION("2D, coarse block") { check_galerkin_by_blocks<2, 3>(); }
  SECTION("3D, fine block") { check_galerkin_by_blocks<3, 3>(); }
  SECTION("3D, coarse block") { check_galerkin_by_blocks<3, 6>(); }
}

// Each level's matrix against the dense Galerkin product of the level above
// it (the fine matrix for level 0), the offsets from the levels' centres,
// and its entries (b, a) the exact transposes of its (a, b); on two threads
// (the aggregates shared out) the bits of one (the finer rows in order)
TEST_CASE("rigid-body multigrid: in 3D every level is the Galerkin product of the level above, exactly symmetric",
          "[solver][multigrid]")
{
  constexpr int R = 6;
  const Laplacian A = kuhn_grid_system(true);
  const auto mesh = kuhn_grid<3>(12);
  const auto points = free_points(make_spring_network<3>(mesh.points, mesh.elements));
  REQUIRE(points.size() == A.rows());
  Rigid_body_multigrid<3> mg;
  mg.parameters.coarsest_rows = 8; // a coarse level below level 0
  mg.build(A.view(), points.data());
  mg.load(A.view(), points.data());
  REQUIRE(mg.number_of_levels() >= 2);
  for(std::size_t l = 0; l < mg.number_of_levels(); ++l) {
    INFO("level " << l << ", " << mg.rows(l) << " rows");
    // the level above: its pattern, blocks (F x F) and positions
    const bool fine = l == 0;
    const int F = fine ? 3 : R;
    const std::vector<Index>& off = fine ? A.offsets : mg.offsets(l - 1);
    const std::vector<Index>& col = fine ? A.col : mg.columns(l - 1);
    const std::vector<double>& val = fine ? A.values : mg.values(l - 1);
    const std::vector<double>& dia = fine ? A.diag : mg.diagonal(l - 1);
    const std::size_t n = off.size() - 1;
    auto offset = [&](std::size_t i) {
      const auto& c = mg.centre(l, mg.parent(l, i));
      const auto& p = fine ? points[i] : mg.centre(l - 1, Index(i));
      return std::array<double, 3>{p[0] - c[0], p[1] - c[1], p[2] - c[2]};
    };
    std::map<std::pair<Index, Index>, std::vector<double>> expected;
    auto add = [&](std::size_t i, std::size_t j, const double* block) {
      const std::vector<double> a(block, block + F * F);
      const auto C = fine ? dense_rigid_galerkin<3, 3>(a, offset(i), offset(j))
                          : dense_rigid_galerkin<3, R>(a, offset(i), offset(j));
      auto& e = expected[{mg.parent(l, i), mg.parent(l, j)}];
      e.resize(R * R, 0.0);
      for(std::size_t k = 0; k < C.size(); ++k)
        e[k] += C[k];
    };
    for(std::size_t i = 0; i < n; ++i) {
      add(i, i, &dia[i * std::size_t(F * F)]);
      for(Index q = off[i]; q < off[i + 1]; ++q)
        add(i, col[q], &val[std::size_t(q) * std::size_t(F * F)]);
    }
    double worst = 0;
    auto compare = [&](const double* got, const std::vector<double>& e) {
      double scale = 0;
      for(double v : e)
        scale = std::max(scale, std::abs(v));
      for(std::size_t k = 0; k < R * R; ++k)
        worst = std::max(worst, std::abs(got[k] - e[k]) / scale);
    };
    const auto& o = mg.offsets(l);
    const auto& c = mg.columns(l);
    const auto& v = mg.values(l);
    std::size_t entries = 0, asymmetric = 0;
    for(std::size_t a = 0; a < mg.rows(l); ++a) {
      compare(&mg.diagonal(l)[a * R * R], expected.at({Index(a), Index(a)}));
      ++entries;
      for(Index q = o[a]; q < o[a + 1]; ++q, ++entries) {
        compare(&v[q * R * R], expected.at({Index(a), c[q]}));
        // the entry (b, a)
        const Index b = c[q];
        const auto t = std::find(c.begin() + o[b], c.begin() + o[b + 1], Index(a));
        REQUIRE(t != c.begin() + o[b + 1]);
        const double* vt = &v[std::size_t(t - c.begin()) * R * R];
        for(int r = 0; r < R; ++r)
          for(int k = 0; k < R; ++k)
            asymmetric += v[q * R * R + std::size_t(r * R + k)] != vt[k * R + r]; // bits
      }
    }
    CHECK(entries == expected.size());
    CHECK(worst < 1e-12);
    CHECK(asymmetric == 0);
  }
  Rigid_body_multigrid<3> two;
  two.parameters.coarsest_rows = 8;
  two.build(A.view(), points.data(), 2);
  two.load(A.view(), points.data(), 2);
  REQUIRE(two.number_of_levels() == mg.number_of_levels());
  for(std::size_t l = 0; l < mg.number_of_levels(); ++l) {
    CHECK(two.values(l) == mg.values(l)); // bits
    CHECK(two.diagonal(l) == mg.diagonal(l));
  }
  // three Chebyshev-weighted cycles on level 0 (the 3D default), their
  // interval estimated at the first: the same interval and correction
  std::vector<std::array<double, 3>> r(A.rows());
  for(std::size_t i = 0; i < r.size(); ++i)
    r[i] = {std::sin(0.7 * double(i)), std::cos(1.3 * double(i)), 0.5 - double(i % 7) / 7};
  mg.first_level_cycles = two.first_level_cycles = 3;
  mg.restrict_from(r, 1);
  mg.cycle(1);
  two.restrict_from(r, 2);
  two.cycle(2);
  REQUIRE(mg.first_level_interval().valid());
  CHECK(two.first_level_interval().low == mg.first_level_interval().low); // bits
  CHECK(two.first_level_interval().high == mg.first_level_interval().high);
  std::size_t differ = 0;
  for(std::size_t i = 0; i < r.size(); ++i)
    differ += two.correction(i) != mg.correction(i);
  CHECK(differ == 0);
}

TEST_CASE("rigid-body multigrid: with the coarsest level solved exactly, the coarse correction reproduces every "
          "rigid motion",
          "[solver][multigrid]")
{
  // One coarse level solved directly: T = P A_c^{-1} P^T A is the A-orthogonal
  // projection onto the coarse space, so T u = u exactly when u is a
  // translation or rotation of the whole mesh.
  const Setup s = setup(true);
  const auto points = free_points(s.net);
  const Csr_view A = s.A.view();
  const double angle = GENERATE(0.0, 1.0);
  INFO((angle == 0 ? "translation" : "rotation") << " of the whole mesh");
  Vec u(A.rows);
  for(std::size_t i = 0; i < u.size(); ++i)
    u[i] = angle == 0 ? std::array<double, 2>{0.3, -0.7}
                      : std::array<double, 2>{-(points[i][1] - 0.2), points[i][0] - 0.1};
  const Vec Au = multiply(A, u);
  auto error = [&](const Vec& Tu) {
    double e = 0, scale = 0;
    for(std::size_t i = 0; i < u.size(); ++i)
      for(int c = 0; c < 2; ++c) {
        e = std::max(e, std::abs(Tu[i][std::size_t(c)] - u[i][std::size_t(c)]));
        scale = std::max(scale, std::abs(u[i][std::size_t(c)]));
      }
    return e / scale;
  };
  Rigid mg;
  mg.parameters.coarsest_rows = 2000;
  mg.parameters.max_direct_rows = 2000;
  mg.build(A, points.data());
  mg.load(A, points.data());
  REQUIRE(mg.number_of_levels() == 1);
  CHECK(error(rigid_correction(mg, Au)) <= 1e-8);
}

TEST_CASE("rigid-body multigrid: the coarse correction is symmetric and positive semi-definite", "[solver][multigrid]")
{
  const Setup s = setup(true);
  const auto points = free_points(s.net);
  Rigid mg;
  mg.first_level_cycles = GENERATE(1, 2, 3);
  INFO(mg.first_level_cycles << " cycles on the first coarse level");
  mg.build(s.A.view(), points.data());
  mg.load(s.A.view(), points.data());
  REQUIRE(mg.number_of_levels() >= 2);
  check_symmetric_positive([&](const Vec& u) { return rigid_correction(mg, u); }, s.A.rows(), 11);
  // with more than one cycle, the Chebyshev-weighted ones (not the plain sum)
  CHECK(mg.first_level_interval().valid() == (mg.first_level_cycles > 1));
}

TEST_CASE("rigid-body multigrid: repeated cycles on the first coarse level converge to its exact solution",
          "[solver][multigrid]")
{
  // Each cycle after the first corrects by one cycle on the residual the
  // ones before left, so the level-0 solution approaches A_0^{-1} P^T r,
  // here from a sparse direct solve of level 0's matrix (assembled from its
  // blocks), with an error that shrinks at every cycle. Measured on the
  // fine level: |P e|_A = |e|_{A_0}, A_0 = P^T A P.
  const Setup s = setup(true);
  const auto points = free_points(s.net);
  const Csr_view A = s.A.view();
  Rigid mg;
  mg.build(A, points.data());
  mg.load(A, points.data());
  REQUIRE(mg.number_of_levels() >= 2); // level 0 is cycled, not solved directly
  const std::size_t n0 = mg.rows(0), N = n0 * R;
  std::vector<Eigen::Triplet<double>> entries;
  for(std::size_t a = 0; a < n0; ++a)
    for(int r = 0; r < R; ++r)
      for(int c = 0; c < R; ++c) {
        entries.emplace_back(int(a * R + r), int(a * R + c), mg.diagonal(0)[a * R * R + r * R + c]);
        for(Index q = mg.offsets(0)[a]; q < mg.offsets(0)[a + 1]; ++q)
          entries.emplace_back(int(a * R + r), int(mg.columns(0)[q] * R + c), mg.values(0)[q * R * R + r * R + c]);
      }
  Eigen::SparseMatrix<double> A0(static_cast<int>(N), static_cast<int>(N));
  A0.setFromTriplets(entries.begin(), entries.end());
  Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> ldlt(A0);
  REQUIRE(ldlt.info() == Eigen::Success);
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> d(-1, 1);
  Vec r(A.rows);
  for(auto& v : r)
    v = {d(rng), d(rng)};
  auto P = [&](std::size_t i) {
    const Index a = mg.parent(0, i);
    return rigid_block({points[i][0] - mg.centre(0, a)[0], points[i][1] - mg.centre(0, a)[1]});
  };
  Eigen::VectorXd y = Eigen::VectorXd::Zero(int(N)); // P^T r
  for(std::size_t i = 0; i < A.rows; ++i)
    for(int k = 0; k < R; ++k)
      for(int c = 0; c < 2; ++c)
        y[int(mg.parent(0, i) * R + k)] += P(i)[std::size_t(c * R + k)] * r[i][std::size_t(c)];
  const Eigen::VectorXd x = ldlt.solve(y);
  Vec exact(A.rows);
  for(std::size_t i = 0; i < A.rows; ++i)
    for(int c = 0; c < 2; ++c) {
      exact[i][std::size_t(c)] = 0;
      for(int k = 0; k < R; ++k)
        exact[i][std::size_t(c)] += P(i)[std::size_t(c * R + k)] * x[int(mg.parent(0, i) * R + k)];
    }
  auto energy_error = [&](std::size_t cycles) {
    mg.first_level_cycles = cycles;
    Vec e = rigid_correction(mg, r);
    for(std::size_t i = 0; i < e.size(); ++i)
      for(int c = 0; c < 2; ++c)
        e[i][std::size_t(c)] -= exact[i][std::size_t(c)];
    return std::sqrt(dot(e, multiply(A, e)));
  };
  const double size = std::sqrt(dot(exact, multiply(A, exact)));
  REQUIRE(size > 0);
  double before = energy_error(1) / size;
  INFO("relative energy error after 1 cycle: " << before);
  CHECK(before < 1);
  for(std::size_t k = 2; k <= 6; ++k) {
    const double now = energy_error(k) / size;
    INFO("after " << k << " cycles: " << now);
    CHECK(now < 0.9 * before);
    before = now;
  }
  CHECK(energy_error(80) / size <= 1e-9); // about 0.63 per cycle from the sixth on
}

namespace {

// The coarse correction of the block system A on rows at `points`, for the
// residual r: of A as it is, and of A scaled by 2^130 (exactly, and beyond a
// float's range, so that its coarse levels keep double precision) with the
// correction scaled back. Returns the largest difference between the two,
// relative to the largest entry of the first.
template <int D>
double unscaled_against_scaled(const Laplacian& A, const std::vector<std::array<double, D>>& points,
                               std::size_t levels_at_least)
{
  using Mg = Rigid_body_multigrid<D>;
  Laplacian big = A;
  const double scale = std::ldexp(1.0, 130);
  for(double& v : big.values)
    v *= scale;
  for(double& v : big.diag)
    v *= scale;
  Mg mg, mg_big;
  mg.build(A.view(), points.data());
  mg.load(A.view(), points.data());
  mg_big.build(big.view(), points.data());
  mg_big.load(big.view(), points.data());
  REQUIRE(mg.number_of_levels() >= levels_at_least); // levels with Gauss-Seidel sweeps
  REQUIRE(mg_big.number_of_levels() == mg.number_of_levels());
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  std::vector<std::array<double, D>> r(A.rows());
  for(auto& v : r)
    for(auto& c : v)
      c = u(rng);
  mg.restrict_from(r);
  mg.cycle();
  mg_big.restrict_from(r);
  mg_big.cycle();
  double difference = 0, size = 0;
  for(std::size_t i = 0; i < r.size(); ++i) {
    const auto z = mg.correction(i), z_big = mg_big.correction(i);
    for(std::size_t c = 0; c < std::size_t(D); ++c) {
      REQUIRE(std::isfinite(z_big[c]));
      difference = std::max(difference, std::abs(z[c] - z_big[c] * scale));
      size = std::max(size, std::abs(z[c]));
    }
  }
  REQUIRE(size > 0);
  return difference / size;
}

} // namespace

// Scaling a system by a power of two scales every double-precision step of
// the cycle exactly, so the scaled system's correction, scaled back, is the
// bits of the unscaled system's cycle in double precision.
TEST_CASE("Chebyshev weights: k steps leave the Chebyshev polynomial's error on every eigenvalue",
          "[solver][multigrid]")
{
  // One eigenvector of B A with eigenvalue t: B A = t, the solution 1/t.
  // After k steps from zero the error t (1/t - x_k) = 1 - t x_k is
  // T_k((b + a - 2t) / (b - a)) / T_k((b + a) / (b - a)), T_k(cos u) =
  // cos(k u) and T_k(cosh u) = cosh(k u) (and (-1)^k of it for -cosh u).
  auto T = [](int k, double x) {
    if(std::abs(x) <= 1)
      return std::cos(k * std::acos(x));
    const double c = std::cosh(k * std::acosh(std::abs(x)));
    return x < 0 && k % 2 ? -c : c;
  };
  const internal::Eigen_interval interval{0.2, 1.1};
  for(const double t : {0.05, 0.2, 0.5, 0.9, 1.1, 1.25, 2.0}) {
    internal::Chebyshev_steps weights(interval);
    double x = 0, d = 0;
    for(int k = 1; k <= 7; ++k) {
      const auto w = weights.next();
      d = w.first * d + w.second * (1 - t * x); // B r = residual for B = 1, A = t
      x += d;
      const double expected = T(k, (1.1 + 0.2 - 2 * t) / 0.9) / T(k, 1.3 / 0.9);
      INFO("t = " << t << ", step " << k);
      CHECK(std::abs((1 - t * x) - expected) <= 1e-12);
      if(t >= 0.2 && t <= 1.1) // inside the interval: the minimax bound
        CHECK(std::abs(1 - t * x) <= 1 / T(k, 1.3 / 0.9) * (1 + 1e-12));
    }
  }
}

TEST_CASE("Lanczos extremes: conjugate gradients' coefficients give Ritz values inside the spectrum, exact after "
          "n steps",
          "[solver][multigrid]")
{
  // Conjugate gradients with B = I on a diagonal matrix of known eigenvalues.
  const std::vector<double> eigenvalues{0.03, 0.1, 0.35, 0.4, 0.8, 1.7, 2.5, 4.0};
  const std::size_t n = eigenvalues.size();
  auto run = [&](std::size_t steps) {
    std::vector<double> r(n), p, alpha, beta;
    for(std::size_t i = 0; i < n; ++i)
      r[i] = 1.0 + 0.1 * double(i);
    p = r;
    double rr = 0;
    for(const double v : r)
      rr += v * v;
    for(std::size_t j = 0; j < steps; ++j) {
      double pq = 0;
      for(std::size_t i = 0; i < n; ++i)
        pq += p[i] * eigenvalues[i] * p[i];
      const double a = rr / pq;
      double next = 0;
      for(std::size_t i = 0; i < n; ++i) {
        r[i] -= a * eigenvalues[i] * p[i];
        next += r[i] * r[i];
      }
      alpha.push_back(a);
      beta.push_back(next / rr);
      for(std::size_t i = 0; i < n; ++i)
        p[i] = r[i] + beta.back() * p[i];
      rr = next;
    }
    return internal::lanczos_extremes(alpha, beta);
  };
  for(std::size_t steps = 2; steps < n; ++steps) {
    const internal::Eigen_interval i = run(steps);
    INFO(steps << " steps: [" << i.low << ", " << i.high << "]");
    CHECK(i.low >= 0.03 * (1 - 1e-12));
    CHECK(i.high <= 4.0 * (1 + 1e-12));
    CHECK(i.low < i.high);
  }
  const internal::Eigen_interval all = run(n);
  CHECK(all.low == Approx(0.03).epsilon(1e-8));
  CHECK(all.high == Approx(4.0).epsilon(1e-8));
  // the bisection against a dense solve of the same tridiagonal matrix
  const std::vector<double> alpha{0.9, 0.5, 1.3, 0.7}, beta{0.4, 0.8, 0.2, 0.6};
  Eigen::Matrix4d t = Eigen::Matrix4d::Zero();
  for(int j = 0; j < 4; ++j) {
    t(j, j) = 1 / alpha[j] + (j > 0 ? beta[j - 1] / alpha[j - 1] : 0.0);
    if(j + 1 < 4)
      t(j, j + 1) = t(j + 1, j) = std::sqrt(beta[j]) / alpha[j];
  }
  const Eigen::Vector4d dense = Eigen::SelfAdjointEigenSolver<Eigen::Matrix4d>(t).eigenvalues();
  const internal::Eigen_interval i = internal::lanczos_extremes(alpha, beta);
  CHECK(i.low == Approx(dense[0]).epsilon(1e-12));
  CHECK(i.high == Approx(dense[3]).epsilon(1e-12));
}

TEST_CASE("rigid-body multigrid: the first coarse level's interval holds the spectrum of one cycle times its matrix",
          "[solver][multigrid]")
{
  // The nonzero eigenvalues of C A, C = P B P^T the fine-level correction of
  // one cycle, are those of B A_0 (A_0 = P^T A P). Dense: C A is similar to
  // L^T C L, A = L L^T. On a coarse mesh, whose dense matrices are small;
  // a low coarsest size keeps a level under level 0, which is then cycled.
  const Setup s = setup(true, 0.3);
  const auto points = free_points(s.net);
  Rigid mg;
  mg.parameters.coarsest_rows = 4;
  mg.first_level_cycles = 3;
  mg.build(s.A.view(), points.data());
  mg.load(s.A.view(), points.data());
  REQUIRE(mg.number_of_levels() >= 2);
  const std::size_t rows = s.A.rows(), N = 2 * rows;
  Vec u(rows);
  for(std::size_t i = 0; i < rows; ++i)
    u[i] = {1.0, -0.5};
  rigid_correction(mg, u); // the first cycle after build estimates the interval
  const internal::Eigen_interval interval = mg.first_level_interval();
  REQUIRE(interval.valid());
  mg.first_level_cycles = 1;
  Eigen::MatrixXd C(N, N), A(N, N);
  for(std::size_t j = 0; j < N; ++j) {
    Vec e(rows, {0.0, 0.0});
    e[j / 2][j % 2] = 1;
    const Vec c = rigid_correction(mg, e), a = multiply(s.A.view(), e);
    for(std::size_t i = 0; i < N; ++i) {
      C(Eigen::Index(i), Eigen::Index(j)) = c[i / 2][i % 2];
      A(Eigen::Index(i), Eigen::Index(j)) = a[i / 2][i % 2];
    }
  }
  const Eigen::MatrixXd L = Eigen::LLT<Eigen::MatrixXd>(A).matrixL();
  const Eigen::MatrixXd S = L.transpose() * C * L;
  const Eigen::VectorXd lambda = Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd>(0.5 * (S + S.transpose())).eigenvalues();
  const double top = lambda.maxCoeff();
  double bottom = top;
  std::size_t nonzero = 0;
  for(Eigen::Index k = 0; k < lambda.size(); ++k)
    if(lambda[k] > 1e-9 * top) {
      bottom = std::min(bottom, lambda[k]);
      ++nonzero;
    }
  INFO(rows << " rows, " << mg.rows(0) << " aggregates; spectrum of B A_0: [" << bottom << ", " << top << "], "
             << nonzero << " eigenvalues; interval [" << interval.low << ", " << interval.high << "]");
  CHECK(nonzero == mg.rows(0) * 3);               // P has full rank: every unknown of level 0
  CHECK(interval.low >= bottom * (1 - 1e-9));     // Ritz values lie inside the spectrum
  CHECK(interval.high / 1.05 <= top * (1 + 1e-9)); // (the upper end raised by the margin)
  CHECK(interval.high >= top);                    // the margin covers the largest
}

TEST_CASE("rigid-body multigrid: in 3D the Gauss-Seidel sweeps of the coarse levels read single precision where "
          "every value fits (double precision where one does not), in 2D double precision",
          "[solver][multigrid]")
{
  SECTION("2D: the same bits as in double precision")
  {
    const Setup s = setup(true);
    CHECK(unscaled_against_scaled<2>(s.A, free_points(s.net), 2) == 0);
  }
  SECTION("3D: single-precision rounding, no more")
  {
    const auto mesh = kuhn_grid<3>(16); // 15^3 free vertices
    const auto net = make_spring_network<3>(mesh.points, mesh.elements);
    const auto roles = assign_roles(net, [&](const Vertex_info<3>& v) {
      return v.on_boundary ? Vertex_role::fixed : Vertex_role::free;
    });
    const double difference = unscaled_against_scaled<3>(spring_laplacian(net, roles, true), free_points(net), 2);
    CHECK(difference > 0); // the unscaled system's sweeps did read floats
    CHECK(difference <= 1e-6);
  }
}

// A one-vertex aggregate has a free rotation, a block too weak for its
// couplings rounded to floats: were it kept, its level and the levels
// above it would keep double precision.
TEST_CASE("rigid-body multigrid: in 3D a vertex with no strong neighbour joins an aggregate, and every level reads "
          "single precision",
          "[solver][multigrid]")
{
  Laplacian A = kuhn_grid_system(true);
  weaken_one_vertex(A);
  const auto mesh = kuhn_grid<3>(12);
  const auto net = make_spring_network<3>(mesh.points, mesh.elements);
  const auto points = free_points(net);
  REQUIRE(points.size() == A.rows());
  Rigid_body_multigrid<3> mg;
  mg.build(A.view(), points.data());
  mg.load(A.view(), points.data());
  REQUIRE(mg.number_of_levels() >= 2);
  for(std::size_t l = 0; l < mg.number_of_levels(); ++l) {
    INFO("level " << l << ", " << mg.rows(l) << " rows");
    CHECK(mg.single_precision(l));
  }
}

namespace {

// The factorisation and solve as plain row-by-row loops: each entry one sum
// over k = 0, 1, ... (forward) or k = n-1, ..., i+1 (backward) in order.
bool reference_cholesky(std::vector<double>& a, std::size_t n, double relative)
{
  for(std::size_t j = 0; j < n; ++j) {
    double d = a[j * n + j];
    const double own = d;
    for(std::size_t k = 0; k < j; ++k)
      d -= a[j * n + k] * a[j * n + k];
    if(!(std::isfinite(d) && d > relative * own))
      return false;
    const double l = std::sqrt(d);
    a[j * n + j] = l;
    for(std::size_t i = j + 1; i < n; ++i) {
      double s = a[i * n + j];
      for(std::size_t k = 0; k < j; ++k)
        s -= a[i * n + k] * a[j * n + k];
      a[i * n + j] = s / l;
    }
  }
  return true;
}

template <int M>
void reference_cholesky_solve(const std::vector<double>& l, std::size_t n, const double* b, double* z)
{
  for(std::size_t i = 0; i < n; ++i)
    for(int c = 0; c < M; ++c) {
      double s = b[i * M + c];
      for(std::size_t k = 0; k < i; ++k)
        s -= l[i * n + k] * z[k * M + c];
      z[i * M + c] = s / l[i * n + i];
    }
  for(std::size_t i = n; i-- > 0;)
    for(int c = 0; c < M; ++c) {
      double s = z[i * M + c];
      for(std::size_t k = i + 1; k < n; ++k)
        s -= l[k * n + i] * z[k * M + c];
      z[i * M + c] = s / l[i * n + i];
    }
}

// ours (inside the envelope e) against the row-by-row factorisation and
// solve over the whole triangle: the same bits
template <int M>
void check_dense_cholesky(const std::vector<double>& a, std::size_t n, const internal::Dense_envelope& e,
                          std::mt19937& rng)
{
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  std::vector<double> ours = a, ref = a;
  REQUIRE(internal::try_dense_cholesky(ours, n, e, 0.0));
  REQUIRE(reference_cholesky(ref, n, 0.0));
  for(std::size_t i = 0; i < n; ++i)
    for(std::size_t j = 0; j <= i; ++j)
      REQUIRE(ours[i * n + j] == ref[i * n + j]); // the same bits, not just close
  for(std::size_t i = 0; i < n; ++i) // L^T in the upper triangle, for the backward pass
    for(std::size_t j = i + 1; j < n; ++j)
      REQUIRE(ours[i * n + j] == ours[j * n + i]);
  std::vector<double> b(n * M), z(n * M), zr(n * M);
  for(double& v : b)
    v = u(rng);
  internal::dense_cholesky_solve<M>(ours, n, e, b.data(), z.data());
  reference_cholesky_solve<M>(ref, n, b.data(), zr.data());
  for(std::size_t i = 0; i < n * M; ++i)
    REQUIRE(z[i] == zr[i]);
  // and it solves A z = b
  for(std::size_t i = 0; i < n; ++i)
    for(int c = 0; c < M; ++c) {
      double r = b[i * M + c];
      for(std::size_t j = 0; j < n; ++j)
        r -= a[i * n + j] * z[j * M + c];
      REQUIRE(std::abs(r) <= 1e-12 * double(n) * double(n));
    }
}

// A = G G^T + n I: symmetric positive definite, dense, entries of mixed signs
std::vector<double> dense_spd(std::size_t n, std::mt19937& rng)
{
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  std::vector<double> g(n * n), a(n * n, 0.0);
  for(double& v : g)
    v = u(rng);
  for(std::size_t i = 0; i < n; ++i)
    for(std::size_t j = 0; j < n; ++j) {
      for(std::size_t k = 0; k < n; ++k)
        a[i * n + j] += g[i * n + k] * g[j * n + k];
      a[i * n + j] += i == j ? double(n) : 0.0;
    }
  return a;
}

// symmetric, diagonally dominant (so positive definite), row i nonzero
// only from column first[i], and there only at random: zeros inside the
// envelope that the factor fills
std::vector<double> enveloped_spd(const std::vector<std::size_t>& first, std::mt19937& rng)
{
  const std::size_t n = first.size();
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  std::vector<double> a(n * n, 0.0), row(n, 0.0);
  for(std::size_t i = 0; i < n; ++i)
    for(std::size_t j = first[i]; j < i; ++j)
      if(u(rng) > 0) {
        a[i * n + j] = a[j * n + i] = u(rng);
        row[i] += std::abs(a[i * n + j]);
        row[j] += std::abs(a[i * n + j]);
      }
  for(std::size_t i = 0; i < n; ++i)
    a[i * n + i] = row[i] + 0.5 + 0.5 * std::abs(u(rng));
  return a;
}

} // namespace

TEST_CASE("dense Cholesky: the interleaved rows give the bits of a row-by-row factorisation and solve",
          "[solver][multigrid]")
{
  std::mt19937 rng(7);
  // every remainder of the four interleaved rows, and more than one group
  for(std::size_t n = 1; n <= 23; ++n) {
    CAPTURE(n);
    const std::vector<double> a = dense_spd(n, rng);
    check_dense_cholesky<1>(a, n, internal::Dense_envelope::full(n), rng);
    check_dense_cholesky<3>(a, n, internal::Dense_envelope::full(n), rng);
  }
  // a pivot at or below `relative` times its own diagonal entry is refused
  const internal::Dense_envelope two = internal::Dense_envelope::full(2);
  std::vector<double> singular{1, 1, 1, 1};
  CHECK_FALSE(internal::try_dense_cholesky(singular, 2, two, 0.0));
  std::vector<double> weak{1, 1, 1, 1 + 1e-13};
  CHECK_FALSE(internal::try_dense_cholesky(weak, 2, two, 1e-12));
  std::vector<double> fine{1, 1, 1, 1 + 1e-11};
  CHECK(internal::try_dense_cholesky(fine, 2, two, 1e-12));
}

TEST_CASE("dense Cholesky inside an envelope: the bits of the whole triangle's factorisation and solve",
          "[solver][multigrid]")
{
  std::mt19937 rng(11);
  for(std::size_t n = 1; n <= 40; ++n)
    for(int round = 0; round < 4; ++round) {
      CAPTURE(n, round);
      // rows reaching back a random distance (0 to n, so from banded to
      // dense), not monotone: a row can start before the row above it
      std::vector<std::size_t> first(n);
      const std::size_t reach = std::uniform_int_distribution<std::size_t>(0, n)(rng);
      for(std::size_t i = 0; i < n; ++i)
        first[i] = i - std::uniform_int_distribution<std::size_t>(0, std::min(i, reach))(rng);
      const internal::Dense_envelope e = internal::Dense_envelope::from_first(first);
      for(std::size_t j = 0; j < n; ++j) { // last[j]: the lowest row reaching column j
        std::size_t last = j;
        for(std::size_t i = j; i < n; ++i)
          if(first[i] <= j)
            last = i;
        REQUIRE(e.last[j] == last);
      }
      const std::vector<double> a = enveloped_spd(first, rng);
      check_dense_cholesky<1>(a, n, e, rng);
      check_dense_cholesky<3>(a, n, e, rng);
    }
}

namespace {
// The decisions of an Aggregation_refresh fed `iterations`, one solve each:
// 'R' where the next solve chooses its aggregates again (and they are), '.'
// where it does not.
std::string refresh_decisions(const std::vector<std::size_t>& iterations)
{
  internal::Aggregation_refresh refresh;
  std::string out;
  for(std::size_t it : iterations) {
    refresh.record(it);
    out += refresh.due() ? 'R' : '.';
    if(refresh.due())
      refresh.rebuilt();
  }
  return out;
}
} // namespace

TEST_CASE("multigrid: the aggregates are chosen again only after a streak of slow solves", "[solver][multigrid]")
{
  // the cold start (17, 10) is no reference; then five iterations a step
  CHECK(refresh_decisions({17, 10, 5, 6, 7, 5, 5, 5}) == "........");
  // isolated slow solves (a warm start that guessed badly), even periodic ones
  CHECK(refresh_decisions({17, 6, 5, 5, 9, 5, 5, 9, 5, 5, 9, 5, 9, 9, 5}) == "...............");
  // slow means at least 3/2 of the fewest and at least 3 more: 7 is neither
  // 3/2 of 5 nor 5 + 3 ...
  CHECK(refresh_decisions({17, 5, 7, 7, 7, 7, 7}) == ".......");
  // ... 8 is both: the third 8 in a row triggers the rebuild, a fourth does
  // not count against the new aggregates, whose first solve is no reference
  CHECK(refresh_decisions({17, 5, 8, 8, 8, 8, 5, 5}) == "....R...");
  // the wing numbered along a Morton curve, shortened (its run's start, then the
  // solves before its rebuild): the streak 8, 14, 14 triggers it
  CHECK(refresh_decisions({17, 10, 5, 6, 6, 7, 7, 5, 8, 5, 7, 5, 8, 7, 8, 14, 14, 5, 5}) ==
        "................R..");
  // with few iterations the margin of 3 decides: 2 -> 3 and 4 -> 6 are 3/2
  // but not slow; with many the ratio does: 8 -> 11 is 3 more but not slow
  CHECK(refresh_decisions({9, 2, 3, 3, 3, 3}) == "......");
  CHECK(refresh_decisions({9, 4, 6, 6, 6, 6}) == "......");
  CHECK(refresh_decisions({9, 2, 5, 5, 5, 5}) == "....R.");
  CHECK(refresh_decisions({17, 8, 11, 11, 11, 11}) == "......");
  CHECK(refresh_decisions({17, 8, 12, 12, 12, 12}) == "....R.");
  // the first solve is no reference even when it is the fastest
  CHECK(refresh_decisions({5, 17, 17, 17, 17}) == ".....");
  // a rebuild that did not help sets a higher reference: no rebuild every
  // few solves on a system that is simply harder
  CHECK(refresh_decisions({17, 5, 10, 10, 10, 10, 10, 10, 10, 10, 10, 10}) == "....R.......");
  // a streak broken by a fast solve starts again
  CHECK(refresh_decisions({17, 5, 9, 9, 5, 9, 9, 5, 9, 9, 9}) == "..........R");
}
