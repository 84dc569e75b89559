// Copyright (c) 2026 SpringMotion developers.
#ifndef SPRING_MOTION_INTERNAL_AGGREGATION_MULTIGRID_H
#define SPRING_MOTION_INTERNAL_AGGREGATION_MULTIGRID_H

#include <spring_motion/Error.h>
#include <spring_motion/Spring_network.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <vector>

namespace spring_motion {
namespace internal {

/// A view of one level's matrix A = diag(d) - W in compressed rows: W holds
/// the (non-negative) spring weights between the level's unknowns. Every
/// level of the edge-model system has this form: the fine one is the spring
/// Laplacian restricted to the free vertices, and summing it over aggregates
/// (a Galerkin product with a piecewise-constant prolongation) keeps it.
struct Csr_view
{
  std::size_t rows = 0;
  const Index* offsets = nullptr;
  const Index* col = nullptr;
  const double* weight = nullptr;
  const double* diag = nullptr;
};

/// The coarse levels of a multigrid cycle for the scalar spring system, built
/// by plain (unsmoothed) aggregation: the unknowns of a level are grouped
/// into aggregates of strongly coupled neighbours, each aggregate is one
/// unknown of the next level, and the next level's matrix is the sum of the
/// level's matrix over aggregate pairs (P^T A P with P piecewise constant).
/// The aggregates are chosen once, from the first system's weights; the
/// weights are summed again for every new system (`load`), which costs one
/// pass over the fine pattern. The coarsest level is solved by a dense
/// Cholesky factorisation.
///
/// The caller owns the fine level and its smoother; this class holds levels
/// 1, 2, ... and cycles on them. Everything is serial and in a fixed order, so
/// the result does not depend on the thread count.
template <int D>
class Aggregation_multigrid
{
public:
  using Row = std::array<double, D>;

  /// strength threshold: j is a strong neighbour of i when
  /// w_ij >= strength sqrt(d_i d_j) (measured like `correction`: 0.02-0.04
  /// take the fewest iterations on the two NACA0012 meshes together)
  double strength = 0.04;
  /// a level with at most this many unknowns is solved directly
  std::size_t coarsest_rows = 64;
  /// the coarse correction is scaled by this factor: over-correction makes up
  /// for the too-high energy of piecewise-constant coarse functions
  /// (`spring_motion_bench --omega-table` measures it; docs/performance.md
  /// says how 1.3 was chosen and what the latest table says against it)
  double correction = 1.3;

  /// a coarsest level larger than this (coarsening stalled) is smoothed by
  /// symmetric Gauss-Seidel instead of factored
  std::size_t max_direct_rows = 256;

  bool built() const { return built_; }
  std::size_t number_of_levels() const { return levels_.size(); }
  std::size_t rows(std::size_t level) const { return levels_[level].n; }

  /// Chooses the aggregates of every level from the fine matrix.
  void build(const Csr_view& fine)
  {
    levels_.clear();
    built_ = true;
    Csr_view v = fine;
    while(v.rows > coarsest_rows) {
      Level L;
      if(!aggregate(v, L))
        break; // no coarsening possible (no couplings): stop here
      levels_.push_back(std::move(L));
      Level& c = levels_.back();
      // the coarse values of the first system, to aggregate the next level
      sum_values(v, c);
      v = c.view();
    }
  }

  /// Recomputes every coarse level's values from the fine matrix (same
  /// pattern as in `build`) and factors the coarsest.
  void load(const Csr_view& fine)
  {
    Csr_view v = fine;
    for(Level& c : levels_) {
      sum_values(v, c);
      v = c.view();
    }
    factor_coarsest(v);
  }

  /// level 0's right-hand side from the fine residual: sum over each aggregate
  Row* restrict_from(const std::vector<Row>& fine_residual)
  {
    Level& c = levels_.front();
    std::fill(c.rhs.begin(), c.rhs.end(), Row{});
    for(std::size_t i = 0; i < fine_residual.size(); ++i)
      for(int k = 0; k < D; ++k)
        c.rhs[c.parent_of[i]][k] += fine_residual[i][k];
    return c.rhs.data();
  }

  /// Solves approximately on level 0 (a V-cycle over the coarse levels).
  void cycle() { cycle(0); }

  /// Level l's matrix (level 0 is the first coarse level).
  Csr_view matrix(std::size_t level) const { return levels_[level].view(); }
  /// The aggregate of level l that unknown i of the level above belongs to.
  Index parent(std::size_t level, std::size_t i) const { return levels_[level].parent_of[i]; }

  /// The aggregate (level-0 unknown) of fine row i, and level 0's solution.
  Index parent(std::size_t i) const { return levels_.front().parent_of[i]; }
  const Row& coarse_solution(Index a) const { return levels_.front().z[a]; }

private:
  struct Level
  {
    std::size_t n = 0;                  // unknowns of this level
    std::vector<Index> parent_of;       // finer unknown -> aggregate (this level's unknown)
    std::vector<Index> slot_of;         // finer off-diagonal entry -> entry here, or none (inside an aggregate)
    std::vector<Index> offsets, col;    // this level's pattern
    std::vector<double> weight, diag, inv_diag;
    std::vector<Row> rhs, z, res;
    Csr_view view() const { return {n, offsets.data(), col.data(), weight.data(), diag.data()}; }
  };

  static constexpr Index none = std::numeric_limits<Index>::max();

  // Greedy aggregation (Vanek, Mandel and Brezina): an unknown whose strong
  // neighbours are all free seeds an aggregate with them; the rest join the
  // aggregate they are most strongly coupled to, or group what is left.
  bool aggregate(const Csr_view& a, Level& L) const
  {
    const std::size_t n = a.rows;
    auto strong = [&](std::size_t i, Index q) {
      const Index j = a.col[q];
      return a.weight[q] >= strength * std::sqrt(a.diag[i] * a.diag[j]);
    };
    std::vector<Index> agg(n, none);
    Index count = 0;
    for(std::size_t i = 0; i < n; ++i) {
      if(agg[i] != none)
        continue;
      bool seed = true, any = false;
      for(Index q = a.offsets[i]; q < a.offsets[i + 1]; ++q)
        if(strong(i, q)) {
          any = true;
          if(agg[a.col[q]] != none) {
            seed = false;
            break;
          }
        }
      if(!seed || !any)
        continue;
      agg[i] = count;
      for(Index q = a.offsets[i]; q < a.offsets[i + 1]; ++q)
        if(strong(i, q))
          agg[a.col[q]] = count;
      ++count;
    }
    // join the most strongly coupled aggregate of the first pass
    const std::vector<Index> first = agg;
    for(std::size_t i = 0; i < n; ++i) {
      if(agg[i] != none)
        continue;
      double best = 0;
      for(Index q = a.offsets[i]; q < a.offsets[i + 1]; ++q)
        if(first[a.col[q]] != none && strong(i, q) && a.weight[q] > best) {
          best = a.weight[q];
          agg[i] = first[a.col[q]];
        }
    }
    for(std::size_t i = 0; i < n; ++i) {
      if(agg[i] != none)
        continue;
      agg[i] = count;
      for(Index q = a.offsets[i]; q < a.offsets[i + 1]; ++q)
        if(agg[a.col[q]] == none && strong(i, q))
          agg[a.col[q]] = count;
      ++count;
    }
    if(std::size_t(count) * 5 > n * 4) // less than 20% fewer unknowns: not worth a level
      return false;
    L.n = count;
    L.parent_of = std::move(agg);
    // coarse pattern: the aggregate pairs joined by a fine entry
    std::vector<std::vector<Index>> members(count);
    for(std::size_t i = 0; i < n; ++i)
      members[L.parent_of[i]].push_back(Index(i));
    L.offsets.assign(std::size_t(count) + 1, 0);
    L.col.clear();
    L.slot_of.assign(a.offsets[n], none);
    std::vector<Index> slot(count, none);
    for(Index A = 0; A < count; ++A) {
      const Index begin = Index(L.col.size());
      for(Index i : members[A])
        for(Index q = a.offsets[i]; q < a.offsets[i + 1]; ++q) {
          const Index B = L.parent_of[a.col[q]];
          if(B == A)
            continue;
          if(slot[B] == none || slot[B] < begin) {
            slot[B] = Index(L.col.size());
            L.col.push_back(B);
          }
          L.slot_of[q] = slot[B];
        }
      L.offsets[A + 1] = Index(L.col.size());
    }
    L.weight.resize(L.col.size());
    L.diag.resize(count);
    L.inv_diag.resize(count);
    L.rhs.resize(count);
    L.z.resize(count);
    L.res.resize(count);
    return true;
  }

  // L's values from the finer level a: weights summed over aggregate pairs;
  // the diagonal is the aggregate's row sums of A, i.e. its diagonals minus
  // the weights inside it (both directions)
  static void sum_values(const Csr_view& a, Level& L)
  {
    std::fill(L.weight.begin(), L.weight.end(), 0.0);
    std::fill(L.diag.begin(), L.diag.end(), 0.0);
    for(std::size_t i = 0; i < a.rows; ++i) {
      const Index A = L.parent_of[i];
      double d = a.diag[i];
      for(Index q = a.offsets[i]; q < a.offsets[i + 1]; ++q) {
        const Index s = L.slot_of[q];
        if(s == none)
          d -= a.weight[q];
        else
          L.weight[s] += a.weight[q];
      }
      L.diag[A] += d;
    }
    for(std::size_t A = 0; A < L.n; ++A) {
      SPRING_MOTION_CHECK(L.diag[A] > 0, "multigrid: a coarse diagonal is not positive (" << L.diag[A] << ")");
      L.inv_diag[A] = 1.0 / L.diag[A];
    }
  }

  // dense Cholesky of the coarsest level (the fine matrix itself when no
  // level was built: then the caller never cycles)
  void factor_coarsest(const Csr_view& a)
  {
    if(levels_.empty() || a.rows > max_direct_rows)
      return;
    const std::size_t n = a.rows;
    chol_.assign(n * n, 0.0);
    for(std::size_t i = 0; i < n; ++i) {
      chol_[i * n + i] = a.diag[i];
      for(Index q = a.offsets[i]; q < a.offsets[i + 1]; ++q)
        chol_[i * n + a.col[q]] -= a.weight[q];
    }
    for(std::size_t j = 0; j < n; ++j) {
      double d = chol_[j * n + j];
      for(std::size_t k = 0; k < j; ++k)
        d -= chol_[j * n + k] * chol_[j * n + k];
      SPRING_MOTION_CHECK(d > 0, "multigrid: the coarsest matrix is not positive definite");
      const double l = std::sqrt(d);
      chol_[j * n + j] = l;
      for(std::size_t i = j + 1; i < n; ++i) {
        double s = chol_[i * n + j];
        for(std::size_t k = 0; k < j; ++k)
          s -= chol_[i * n + k] * chol_[j * n + k];
        chol_[i * n + j] = s / l;
      }
    }
  }

  void solve_coarsest(Level& L) const
  {
    const std::size_t n = L.n;
    for(std::size_t i = 0; i < n; ++i) {
      Row s = L.rhs[i];
      for(std::size_t k = 0; k < i; ++k)
        for(int c = 0; c < D; ++c)
          s[c] -= chol_[i * n + k] * L.z[k][c];
      for(int c = 0; c < D; ++c)
        L.z[i][c] = s[c] / chol_[i * n + i];
    }
    for(std::size_t ii = n; ii-- > 0;) {
      Row s = L.z[ii];
      for(std::size_t k = ii + 1; k < n; ++k)
        for(int c = 0; c < D; ++c)
          s[c] -= chol_[k * n + ii] * L.z[k][c];
      for(int c = 0; c < D; ++c)
        L.z[ii][c] = s[c] / chol_[ii * n + ii];
    }
  }

  static void gauss_seidel(Level& L, bool forward)
  {
    for(std::size_t kk = 0; kk < L.n; ++kk) {
      const std::size_t i = forward ? kk : L.n - 1 - kk;
      Row s = L.rhs[i];
      for(Index q = L.offsets[i]; q < L.offsets[i + 1]; ++q)
        for(int c = 0; c < D; ++c)
          s[c] += L.weight[q] * L.z[L.col[q]][c];
      for(int c = 0; c < D; ++c)
        L.z[i][c] = s[c] * L.inv_diag[i];
    }
  }

  // a symmetric V-cycle on level l from z = 0: forward Gauss-Seidel, coarse
  // correction, backward Gauss-Seidel
  void cycle(std::size_t l)
  {
    Level& L = levels_[l];
    if(l + 1 == levels_.size()) {
      if(L.n <= max_direct_rows)
        solve_coarsest(L);
      else { // symmetric, so the cycle stays a symmetric preconditioner
        std::fill(L.z.begin(), L.z.end(), Row{});
        gauss_seidel(L, true);
        gauss_seidel(L, false);
      }
      return;
    }
    std::fill(L.z.begin(), L.z.end(), Row{});
    gauss_seidel(L, true);
    Level& C = levels_[l + 1];
    std::fill(C.rhs.begin(), C.rhs.end(), Row{});
    for(std::size_t i = 0; i < L.n; ++i) {
      Row s = L.rhs[i];
      for(Index q = L.offsets[i]; q < L.offsets[i + 1]; ++q)
        for(int c = 0; c < D; ++c)
          s[c] += L.weight[q] * L.z[L.col[q]][c];
      for(int c = 0; c < D; ++c)
        C.rhs[C.parent_of[i]][c] += s[c] - L.diag[i] * L.z[i][c];
    }
    cycle(l + 1);
    for(std::size_t i = 0; i < L.n; ++i)
      for(int c = 0; c < D; ++c)
        L.z[i][c] += correction * C.z[C.parent_of[i]][c];
    gauss_seidel(L, false);
  }

  std::vector<Level> levels_;
  std::vector<double> chol_;
  bool built_ = false;
};

} // namespace internal
} // namespace spring_motion

#endif
