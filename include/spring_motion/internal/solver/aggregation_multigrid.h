// Copyright (c) 2026 SpringMotion developers.
#ifndef SPRING_MOTION_INTERNAL_SOLVER_AGGREGATION_MULTIGRID_H
#define SPRING_MOTION_INTERNAL_SOLVER_AGGREGATION_MULTIGRID_H

#include <spring_motion/Error.h>
#include <spring_motion/Spring_network.h>
#include <spring_motion/internal/solver/block_ops.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <vector>

namespace spring_motion {
namespace internal {

/// A view of one level's symmetric matrix in compressed rows, off-diagonal
/// entries apart from the diagonal. Scalar (`block == false`): one value per
/// entry, the same for each of the D components (edge models: the matrix is
/// a spring Laplacian, off-diagonal entries -k). Block: a D x D row-major
/// block per entry and per diagonal (element models). Summing a level over
/// aggregates (a Galerkin product with a piecewise-constant prolongation)
/// keeps its form, scalar or block.
struct Csr_view
{
  std::size_t rows = 0;
  const Index* offsets = nullptr;
  const Index* col = nullptr;
  const double* values = nullptr; // per entry: 1 (scalar) or D*D (block)
  const double* diag = nullptr;   // per row: 1 or D*D
  bool block = false;
};

/// Parameters of the coarse levels (Solver_options says what each does).
struct Multigrid_parameters
{
  double strength = 0.04;
  double correction = 1.3;
  std::size_t coarsest_rows = 64;
  std::size_t max_direct_rows = 256;
};

/// The coarse levels of a multigrid cycle for the spring system, built by
/// plain (unsmoothed) aggregation: the unknowns (vertices) of a level are
/// grouped into aggregates of strongly coupled neighbours, each aggregate is
/// one unknown of the next level, and the next level's matrix is the sum of
/// the level's matrix over aggregate pairs (P^T A P with P piecewise constant,
/// the same for the D components: for block systems each coarse entry is the
/// sum of D x D blocks). The aggregates are chosen once, from the first
/// system's values; the values are summed again for every new system
/// (`load`), which costs one pass over the fine pattern. The coarsest level is
/// solved by a dense Cholesky factorisation.
///
/// The caller owns the fine level and its smoother; this class holds levels
/// 1, 2, ... and cycles on them. Everything is serial and in a fixed order, so
/// the result does not depend on the thread count.
template <int D>
class Aggregation_multigrid
{
public:
  using Row = std::array<double, D>;
  static constexpr int DD = D * D;
  static_assert(sizeof(Row) == D * sizeof(double), "a vector of rows is read as one flat array");

  /// strength of connection: j is a strong neighbour of i when
  /// |A_ij| >= strength sqrt(|A_ii| |A_jj|) (Frobenius norms for blocks);
  /// the coarse correction is scaled by `correction`: over-correction makes
  /// up for the too-high energy of piecewise-constant coarse functions; a
  /// level with at most `coarsest_rows` unknowns is the coarsest, solved
  /// directly if it has at most `max_direct_rows` (coarsening stalled above
  /// that: symmetric Gauss-Seidel instead)
  Multigrid_parameters parameters;

  bool built() const { return built_; }
  std::size_t number_of_levels() const { return levels_.size(); }
  std::size_t rows(std::size_t level) const { return levels_[level].n; }

  /// Chooses the aggregates of every level from the fine matrix.
  void build(const Csr_view& fine)
  {
    levels_.clear();
    built_ = true;
    Csr_view v = fine;
    while(v.rows > parameters.coarsest_rows) {
      Level L;
      L.block = fine.block;
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
    bool block = false;
    std::size_t n = 0;                  // unknowns of this level
    std::vector<Index> parent_of;       // finer unknown -> aggregate (this level's unknown)
    std::vector<Index> slot_of;         // finer off-diagonal entry -> entry here, or none (inside an aggregate)
    std::vector<Index> offsets, col;    // this level's pattern
    std::vector<double> values, diag, inv_diag; // 1 or D*D per entry / row
    std::vector<Row> rhs, z;
    Csr_view view() const { return {n, offsets.data(), col.data(), values.data(), diag.data(), block}; }
  };

  static constexpr Index none = std::numeric_limits<Index>::max();

  // Greedy aggregation (Vanek, Mandel and Brezina): an unknown whose strong
  // neighbours are all free seeds an aggregate with them; the rest join the
  // aggregate they are most strongly coupled to, or group what is left.
  bool aggregate(const Csr_view& a, Level& L) const
  {
    const std::size_t n = a.rows;
    // coupling of entry q and scale of row i: -A_ij and A_ii for scalar
    // systems (a spring Laplacian), Frobenius norms for block systems
    std::vector<double> scale(n), coupling(a.offsets[n]);
    for(std::size_t i = 0; i < n; ++i) {
      scale[i] = a.block ? block_norm<D>(a.diag + i * DD) : a.diag[i];
      for(Index q = a.offsets[i]; q < a.offsets[i + 1]; ++q)
        coupling[q] = a.block ? block_norm<D>(a.values + std::size_t(q) * DD) : -a.values[q];
    }
    const double strength = parameters.strength;
    auto strong = [&](std::size_t i, Index q) {
      const Index j = a.col[q];
      return coupling[q] >= strength * std::sqrt(scale[i] * scale[j]);
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
        if(first[a.col[q]] != none && strong(i, q) && coupling[q] > best) {
          best = coupling[q];
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
    const std::size_t w = L.block ? DD : 1;
    L.values.resize(L.col.size() * w);
    L.diag.resize(count * w);
    L.inv_diag.resize(count * w);
    L.rhs.resize(count);
    L.z.resize(count);
    return true;
  }

  // L's values from the finer level a: entries summed over aggregate pairs;
  // an aggregate's diagonal is the sum of its members' diagonals and of the
  // entries between its members (both directions)
  static void sum_values(const Csr_view& a, Level& L)
  {
    std::fill(L.values.begin(), L.values.end(), 0.0);
    std::fill(L.diag.begin(), L.diag.end(), 0.0);
    if(!a.block) {
      for(std::size_t i = 0; i < a.rows; ++i) {
        const Index A = L.parent_of[i];
        double d = a.diag[i];
        for(Index q = a.offsets[i]; q < a.offsets[i + 1]; ++q) {
          const Index s = L.slot_of[q];
          if(s == none)
            d += a.values[q];
          else
            L.values[s] += a.values[q];
        }
        L.diag[A] += d;
      }
      for(std::size_t A = 0; A < L.n; ++A) {
        SPRING_MOTION_CHECK(L.diag[A] > 0, "multigrid: a coarse diagonal is not positive (" << L.diag[A] << ")");
        L.inv_diag[A] = 1.0 / L.diag[A];
      }
      return;
    }
    for(std::size_t i = 0; i < a.rows; ++i) {
      double* dA = &L.diag[std::size_t(L.parent_of[i]) * DD];
      for(int k = 0; k < DD; ++k)
        dA[k] += a.diag[i * DD + std::size_t(k)];
      for(Index q = a.offsets[i]; q < a.offsets[i + 1]; ++q) {
        const Index s = L.slot_of[q];
        double* dst = s == none ? dA : &L.values[std::size_t(s) * DD];
        for(int k = 0; k < DD; ++k)
          dst[k] += a.values[std::size_t(q) * DD + std::size_t(k)];
      }
    }
    for(std::size_t A = 0; A < L.n; ++A)
      SPRING_MOTION_CHECK(invert_block<D>(&L.diag[A * DD], &L.inv_diag[A * DD]),
                          "multigrid: a coarse diagonal block is singular");
  }

  // dense Cholesky of the coarsest level (the fine matrix itself when no
  // level was built: then the caller never cycles); scalar levels factor the
  // n x n matrix shared by the components, block levels the nD x nD one
  void factor_coarsest(const Csr_view& a)
  {
    if(levels_.empty() || a.rows > parameters.max_direct_rows)
      return;
    const std::size_t w = a.block ? D : 1;
    const std::size_t n = a.rows * w;
    chol_.assign(n * n, 0.0);
    for(std::size_t i = 0; i < a.rows; ++i)
      for(std::size_t r = 0; r < w; ++r) {
        for(std::size_t c = 0; c < w; ++c)
          chol_[(i * w + r) * n + i * w + c] = a.diag[(i * w + r) * w + c];
        for(Index q = a.offsets[i]; q < a.offsets[i + 1]; ++q)
          for(std::size_t c = 0; c < w; ++c)
            chol_[(i * w + r) * n + a.col[q] * w + c] += a.values[(std::size_t(q) * w + r) * w + c];
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
    if(L.block) { // one right-hand side of length nD: the rows' components in turn
      const std::size_t n = L.n * D;
      double* z = L.z[0].data();
      const double* b = L.rhs[0].data();
      for(std::size_t i = 0; i < n; ++i) {
        double s = b[i];
        for(std::size_t k = 0; k < i; ++k)
          s -= chol_[i * n + k] * z[k];
        z[i] = s / chol_[i * n + i];
      }
      for(std::size_t ii = n; ii-- > 0;) {
        double s = z[ii];
        for(std::size_t k = ii + 1; k < n; ++k)
          s -= chol_[k * n + ii] * z[k];
        z[ii] = s / chol_[ii * n + ii];
      }
      return;
    }
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

  // rhs_i - sum_j A_ij z_j over the off-diagonal entries of row i
  static Row off_residual(const Level& L, std::size_t i)
  {
    Row s = L.rhs[i];
    if(L.block)
      for(Index q = L.offsets[i]; q < L.offsets[i + 1]; ++q)
        subtract_block_product<D>(s, &L.values[std::size_t(q) * DD], L.z[L.col[q]]);
    else
      for(Index q = L.offsets[i]; q < L.offsets[i + 1]; ++q)
        for(int c = 0; c < D; ++c)
          s[c] -= L.values[q] * L.z[L.col[q]][c];
    return s;
  }

  static void gauss_seidel(Level& L, bool forward)
  {
    for(std::size_t kk = 0; kk < L.n; ++kk) {
      const std::size_t i = forward ? kk : L.n - 1 - kk;
      const Row s = off_residual(L, i);
      if(L.block)
        L.z[i] = block_product<D>(&L.inv_diag[i * DD], s);
      else
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
      if(L.n <= parameters.max_direct_rows)
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
      Row s = off_residual(L, i);
      if(L.block)
        subtract_block_product<D>(s, &L.diag[i * DD], L.z[i]);
      for(int c = 0; c < D; ++c)
        C.rhs[C.parent_of[i]][c] += L.block ? s[c] : s[c] - L.diag[i] * L.z[i][c];
    }
    cycle(l + 1);
    for(std::size_t i = 0; i < L.n; ++i)
      for(int c = 0; c < D; ++c)
        L.z[i][c] += parameters.correction * C.z[C.parent_of[i]][c];
    gauss_seidel(L, false);
  }

  std::vector<Level> levels_;
  std::vector<double> chol_;
  bool built_ = false;
};

} // namespace internal
} // namespace spring_motion

#endif
