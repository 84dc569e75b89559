// Copyright (c) 2026 SpringMotion developers.
#ifndef SPRING_MOTION_INTERNAL_SOLVER_AGGREGATION_MULTIGRID_H
#define SPRING_MOTION_INTERNAL_SOLVER_AGGREGATION_MULTIGRID_H

#include <spring_motion/Error.h>
#include <spring_motion/Spring_network.h>
#include <spring_motion/internal/solver/dense_cholesky.h>
#include <spring_motion/internal/solver/threads.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <vector>

namespace spring_motion {
namespace internal {

/// A view of one level's symmetric matrix in compressed rows, off-diagonal
/// entries apart from the diagonal. Scalar (`block == false`): one value per
/// entry, the same for each of the D components (edge models: the matrix is
/// a spring Laplacian, off-diagonal entries -k). Block: a D x D row-major
/// block per entry and per diagonal (element models).
struct Csr_view
{
  std::size_t rows = 0;
  const Index* offsets = nullptr;
  const Index* col = nullptr;
  const double* values = nullptr; // per entry: 1 (scalar) or D*D (block)
  const double* diag = nullptr;   // per row: 1 or D*D
  bool block = false;
  // block systems whose entries are all symmetric blocks may give, instead
  // of `values`, each entry's upper triangle (D(D+1)/2 values, by rows)
  const double* upper = nullptr;
};

/// Parameters of the coarse levels (Solver_options says what each does).
struct Multigrid_parameters
{
  double strength = 0.04;
  double correction = 1.3;
  std::size_t coarsest_rows = 64;
  std::size_t max_direct_rows = 256;
};

/// Unknowns grouped into aggregates, and the next level's pattern: the
/// aggregate pairs joined by an entry of the finer level.
struct Aggregates
{
  std::size_t count = 0;
  std::vector<Index> parent_of; // finer unknown -> aggregate
  std::vector<Index> slot_of;   // finer off-diagonal entry -> coarse entry, or none (inside an aggregate)
  std::vector<Index> offsets, col;
  // aggregate a's finer unknowns, increasing: members[member_offsets[a] ..
  // member_offsets[a + 1] - 1]
  std::vector<Index> member_offsets, members;
};

/// Greedy aggregation (Vanek, Mandel and Brezina) of the n unknowns of a
/// compressed-row pattern: j is a strong neighbour of i when entry q = (i, j)
/// has coupling[q] >= strength sqrt(scale[i] scale[j]). An unknown whose
/// strong neighbours are all free seeds an aggregate with them; the rest join
/// the aggregate they are most strongly coupled to, or group what is left.
/// Last, an aggregate of fewer than `min_size` unknowns joins, whole, the
/// aggregate of at least `min_size` it is most coupled to, if it touches one.
/// False when that would remove less than 20% of the unknowns.
inline bool aggregate_strong_neighbours(std::size_t n, const Index* offsets, const Index* col,
                                        const std::vector<double>& scale, const std::vector<double>& coupling,
                                        double strength, Aggregates& g, std::size_t min_size = 1)
{
  constexpr Index none = std::numeric_limits<Index>::max();
  auto strong = [&](std::size_t i, Index q) {
    const Index j = col[q];
    return coupling[q] >= strength * std::sqrt(scale[i] * scale[j]);
  };
  std::vector<Index> agg(n, none);
  Index count = 0;
  for(std::size_t i = 0; i < n; ++i) {
    if(agg[i] != none)
      continue;
    bool seed = true, any = false;
    for(Index q = offsets[i]; q < offsets[i + 1]; ++q)
      if(strong(i, q)) {
        any = true;
        if(agg[col[q]] != none) {
          seed = false;
          break;
        }
      }
    if(!seed || !any)
      continue;
    agg[i] = count;
    for(Index q = offsets[i]; q < offsets[i + 1]; ++q)
      if(strong(i, q))
        agg[col[q]] = count;
    ++count;
  }
  // join the most strongly coupled aggregate of the first pass
  const std::vector<Index> first = agg;
  for(std::size_t i = 0; i < n; ++i) {
    if(agg[i] != none)
      continue;
    double best = 0;
    for(Index q = offsets[i]; q < offsets[i + 1]; ++q)
      if(first[col[q]] != none && strong(i, q) && coupling[q] > best) {
        best = coupling[q];
        agg[i] = first[col[q]];
      }
  }
  for(std::size_t i = 0; i < n; ++i) {
    if(agg[i] != none)
      continue;
    agg[i] = count;
    for(Index q = offsets[i]; q < offsets[i + 1]; ++q)
      if(agg[col[q]] == none && strong(i, q))
        agg[col[q]] = count;
    ++count;
  }
  if(min_size > 1) {
    std::vector<std::size_t> size(count, 0);
    for(std::size_t i = 0; i < n; ++i)
      ++size[agg[i]];
    // each small aggregate's target from the sizes before any joins, so
    // that no aggregate joins one that is itself leaving
    std::vector<Index> target(count, none);
    std::vector<double> best(count, 0.0);
    for(std::size_t i = 0; i < n; ++i) {
      const Index a = agg[i];
      if(size[a] >= min_size)
        continue;
      for(Index q = offsets[i]; q < offsets[i + 1]; ++q) {
        const Index b = agg[col[q]];
        if(size[b] >= min_size && coupling[q] > best[a]) {
          best[a] = coupling[q];
          target[a] = b;
        }
      }
    }
    // the aggregates left keep their order
    std::vector<Index> renumber(count, none);
    Index kept = 0;
    for(Index a = 0; a < count; ++a)
      if(target[a] == none)
        renumber[a] = kept++;
    for(std::size_t i = 0; i < n; ++i)
      agg[i] = renumber[target[agg[i]] == none ? agg[i] : target[agg[i]]];
    count = kept;
  }
  if(std::size_t(count) * 5 > n * 4) // less than 20% fewer unknowns: not worth a level
    return false;
  g.count = count;
  g.parent_of = std::move(agg);
  g.member_offsets.assign(std::size_t(count) + 1, 0);
  for(const Index a : g.parent_of)
    ++g.member_offsets[std::size_t(a) + 1];
  for(Index a = 0; a < count; ++a)
    g.member_offsets[a + 1] += g.member_offsets[a];
  g.members.resize(n);
  std::vector<Index> next(g.member_offsets.begin(), g.member_offsets.end() - 1);
  for(std::size_t i = 0; i < n; ++i)
    g.members[next[g.parent_of[i]]++] = Index(i);
  // coarse pattern: the aggregate pairs joined by a fine entry
  g.offsets.assign(std::size_t(count) + 1, 0);
  g.col.clear();
  g.slot_of.assign(offsets[n], none);
  std::vector<Index> slot(count, none);
  for(Index A = 0; A < count; ++A) {
    const Index begin = Index(g.col.size());
    for(Index m = g.member_offsets[A]; m < g.member_offsets[A + 1]; ++m)
      for(Index q = offsets[g.members[m]]; q < offsets[g.members[m] + 1]; ++q) {
        const Index B = g.parent_of[col[q]];
        if(B == A)
          continue;
        if(slot[B] == none || slot[B] < begin) {
          slot[B] = Index(g.col.size());
          g.col.push_back(B);
        }
        g.slot_of[q] = slot[B];
      }
    g.offsets[A + 1] = Index(g.col.size());
  }
  return true;
}

/// The coarse levels of a multigrid cycle for a scalar spring system (edge
/// models: one value per entry, the same for the D components), built by
/// plain (unsmoothed) aggregation: the unknowns (vertices) of a level are
/// grouped into aggregates of strongly coupled neighbours, each aggregate is
/// one unknown of the next level, and the next level's matrix is the sum of
/// the level's matrix over aggregate pairs (P^T A P with P piecewise
/// constant). Block systems take Rigid_body_multigrid, whose coarse functions
/// also rotate each aggregate. The aggregates are chosen by `build`, from the
/// values of the system at hand (the caller decides when: Aggregation_refresh);
/// the values are summed again for every new system
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
  static_assert(sizeof(Row) == D * sizeof(double), "a vector of rows is read as one flat array");

  /// strength of connection: j is a strong neighbour of i when
  /// -A_ij >= strength sqrt(A_ii A_jj);
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
  void build(const Csr_view& fine, int threads = 1)
  {
    SPRING_MOTION_CHECK(!fine.block, "aggregation multigrid: a block system takes Rigid_body_multigrid");
    levels_.clear();
    built_ = true;
    Csr_view v = fine;
    while(v.rows > parameters.coarsest_rows) {
      Level L;
      if(!aggregate(v, L))
        break; // no coarsening possible (no couplings): stop here
      levels_.push_back(std::move(L));
      Level& c = levels_.back();
      // the coarse values of the first system, to aggregate the next level
      sum_values(v, c, threads);
      v = c.view();
    }
  }

  /// Recomputes every coarse level's values from the fine matrix (same
  /// pattern as in `build`) and factors the coarsest.
  void load(const Csr_view& fine, int threads = 1)
  {
    Csr_view v = fine;
    for(Level& c : levels_) {
      sum_values(v, c, threads);
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
    std::vector<Index> slot_of;         // finer off-diagonal entry -> entry here, or a spare (inside an aggregate)
    std::vector<Index> offsets, col;    // this level's pattern
    std::vector<Index> member_offsets, members; // aggregate -> its finer unknowns (Aggregates)
    std::vector<double> values, diag, inv_diag; // per entry, then spares never read (see sum_values) / per row
    std::vector<Row> rhs, z;
    Csr_view view() const { return {n, offsets.data(), col.data(), values.data(), diag.data(), false}; }
  };

  static constexpr Index none = std::numeric_limits<Index>::max();
  static constexpr Index spare_slots = 8;
  // the spares of the team pass's threads lie this far apart: 128 bytes, so
  // no two threads write to one cache line
  static constexpr Index spare_stride = 2 * spare_slots;

  // the aggregates of level a (the next level's unknowns and pattern)
  bool aggregate(const Csr_view& a, Level& L) const
  {
    const std::size_t n = a.rows;
    // coupling of entry q and scale of row i: -A_ij and A_ii (a spring Laplacian)
    std::vector<double> scale(a.diag, a.diag + n), coupling(a.offsets[n]);
    for(Index q = 0; q < a.offsets[n]; ++q)
      coupling[q] = -a.values[q];
    Aggregates g;
    if(!aggregate_strong_neighbours(n, a.offsets, a.col, scale, coupling, parameters.strength, g))
      return false;
    L.n = g.count;
    L.parent_of = std::move(g.parent_of);
    L.slot_of = std::move(g.slot_of);
    L.offsets = std::move(g.offsets);
    L.col = std::move(g.col);
    L.member_offsets = std::move(g.member_offsets);
    L.members = std::move(g.members);
    // entries inside an aggregate point at spare slots past the pattern's
    // (finer_row_sum says why), entry q at spare q mod spare_slots
    const Index entries = Index(L.col.size());
    for(Index q = 0; q < a.offsets[n]; ++q)
      if(L.slot_of[q] == none)
        L.slot_of[q] = entries + q % spare_slots;
    // the spares of a team of OpenMP's default size, allocated here: made
    // at the first team step, the larger copies of the levels' values
    // raised the wing run's peak memory by 2 MB
    L.values.resize(L.col.size() + std::size_t(spare_stride) * std::size_t(thread_count(0)));
    L.diag.resize(L.n);
    L.inv_diag.resize(L.n);
    L.rhs.resize(L.n);
    L.z.resize(L.n);
    return true;
  }

  // L's values from the finer level a: entries summed over aggregate pairs;
  // an aggregate's diagonal is the sum of its members' diagonals and of the
  // entries between its members (both directions).
  //
  // On one thread, in one pass over the finer rows. On more, aggregate by
  // aggregate from its members' rows in increasing order: an aggregate's row
  // of L gets exactly its members' finer rows, so the aggregates are
  // independent, and each sum takes its terms in the order of the pass. Both
  // give the same bits (the thread-determinism tests compare them). On one
  // thread the pass is the faster (it reads the finer rows in order, the
  // members' rows lie apart); on two, the aggregates share out work that
  // kept the second thread waiting. Each thread adds its entries inside an
  // aggregate to spares of its own (finer_row_sum), spare_stride apart past
  // the pattern's entries: shared, their cache lines would pass between the
  // cores at every row.
  static void sum_values(const Csr_view& a, Level& L, int threads)
  {
    const int nt = thread_count(threads, a.rows);
    if(nt == 1) {
      std::fill(L.values.begin(), L.values.end(), 0.0);
      std::fill(L.diag.begin(), L.diag.end(), 0.0);
      for(std::size_t i = 0; i < a.rows; ++i)
        L.diag[L.parent_of[i]] += finer_row_sum(a, L, i);
    } else {
      const long na = long(L.n);
      const std::size_t spares = L.col.size() + std::size_t(spare_stride) * std::size_t(nt);
      if(L.values.size() < spares)
        L.values.resize(spares);
      in_team(nt, [&] {
        const Index spare_base = Index(thread_number()) * spare_stride;
#pragma omp for schedule(static)
        for(long A = 0; A < na; ++A) {
          const std::size_t b = std::size_t(A);
          std::fill(L.values.begin() + long(L.offsets[b]), L.values.begin() + long(L.offsets[b + 1]), 0.0);
          double dA = 0;
          for(Index m = L.member_offsets[b]; m < L.member_offsets[b + 1]; ++m) {
            // the next members' rows are fetched while this one is summed
            if(m + 2 < Index(L.members.size())) {
              __builtin_prefetch(&a.offsets[L.members[m + 2]]);
              __builtin_prefetch(&a.diag[L.members[m + 2]]);
            }
            if(m + 1 < Index(L.members.size())) {
              __builtin_prefetch(&a.values[a.offsets[L.members[m + 1]]]);
              __builtin_prefetch(&L.slot_of[a.offsets[L.members[m + 1]]]);
            }
            dA += finer_row_sum(a, L, L.members[m], spare_base);
          }
          L.diag[b] = dA;
        }
      });
    }
    for(std::size_t A = 0; A < L.n; ++A) {
      SPRING_MOTION_CHECK(L.diag[A] > 0, "multigrid: a coarse diagonal is not positive (" << L.diag[A] << ")");
      L.inv_diag[A] = 1.0 / L.diag[A];
    }
  }

  // Adds finer row i's entries between aggregates to their entries of L and
  // returns its part of its aggregate's diagonal: its own diagonal plus its
  // entries inside the aggregate.
  //
  // Without a branch: whether an entry lies inside its aggregate follows no
  // pattern the processor can predict, and on the 2D paper mesh this loop
  // took a third of the scalar solve's own time (perf annotate) at the two
  // branches' targets. Every entry adds to both sums, 0 to the one it does
  // not belong to: an entry inside adds 0 to a spare slot, whose values are
  // never read (the spares vary with q, so one slot's additions do not
  // chain), and an entry between aggregates adds 0 to d, which leaves d's
  // bits as they were (d is never -0: it starts at a positive diagonal, and
  // a sum rounds to -0 only from two -0 terms). `spare_base`: the calling
  // thread's spares lie that far past slot_of's (see sum_values).
  static double finer_row_sum(const Csr_view& a, Level& L, std::size_t i, Index spare_base = 0)
  {
    const Index entries = Index(L.col.size());
    double d = a.diag[i];
    for(Index q = a.offsets[i]; q < a.offsets[i + 1]; ++q) {
      const Index slot = L.slot_of[q];
      const double v = a.values[q];
      const bool inside = slot >= entries;
      // as masks: GCC turns the two choices of a value into a branch
      const Index s = slot + (spare_base & (Index(0) - Index(inside)));
      std::uint64_t bits, in = 0 - std::uint64_t(inside);
      std::memcpy(&bits, &v, sizeof v);
      const std::uint64_t to_d = bits & in, to_entry = bits & ~in;
      double vd, ve;
      std::memcpy(&vd, &to_d, sizeof vd);
      std::memcpy(&ve, &to_entry, sizeof ve);
      d += vd;
      L.values[s] += ve;
    }
    return d;
  }

  // dense Cholesky of the coarsest level's n x n matrix, shared by the D
  // components (the fine matrix itself when no level was built: then the
  // caller never cycles)
  void factor_coarsest(const Csr_view& a)
  {
    if(levels_.empty() || a.rows > parameters.max_direct_rows)
      return;
    const std::size_t n = a.rows;
    chol_.assign(n * n, 0.0);
    std::vector<std::size_t> first(n);
    for(std::size_t i = 0; i < n; ++i) {
      chol_[i * n + i] = a.diag[i];
      first[i] = i;
      for(Index q = a.offsets[i]; q < a.offsets[i + 1]; ++q) {
        chol_[i * n + a.col[q]] += a.values[q];
        first[i] = std::min(first[i], std::size_t(a.col[q]));
      }
    }
    envelope_ = Dense_envelope::from_first(std::move(first));
    SPRING_MOTION_CHECK(try_dense_cholesky(chol_, n, envelope_, 0.0),
                        "multigrid: the coarsest matrix is not positive definite");
  }

  void solve_coarsest(Level& L) const
  {
    dense_cholesky_solve<D>(chol_, L.n, envelope_, L.rhs[0].data(), L.z[0].data());
  }

  // rhs_i - sum_j A_ij z_j over the off-diagonal entries of row i
  static Row off_residual(const Level& L, std::size_t i)
  {
    Row s = L.rhs[i];
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
      const Row s = off_residual(L, i);
      for(int c = 0; c < D; ++c)
        C.rhs[C.parent_of[i]][c] += s[c] - L.diag[i] * L.z[i][c];
    }
    cycle(l + 1);
    for(std::size_t i = 0; i < L.n; ++i)
      for(int c = 0; c < D; ++c)
        L.z[i][c] += parameters.correction * C.z[C.parent_of[i]][c];
    gauss_seidel(L, false);
  }

  std::vector<Level> levels_;
  std::vector<double> chol_;
  Dense_envelope envelope_;
  bool built_ = false;
};

} // namespace internal
} // namespace spring_motion

#endif
