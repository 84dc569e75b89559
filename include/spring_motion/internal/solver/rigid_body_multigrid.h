// Copyright (c) 2026 SpringMotion developers.
#ifndef SPRING_MOTION_INTERNAL_SOLVER_RIGID_BODY_MULTIGRID_H
#define SPRING_MOTION_INTERNAL_SOLVER_RIGID_BODY_MULTIGRID_H

#include <spring_motion/Error.h>
#include <spring_motion/Spring_network.h>
#include <spring_motion/internal/solver/aggregation_multigrid.h>
#include <spring_motion/internal/solver/block_ops.h>
#include <spring_motion/internal/solver/chebyshev.h>
#include <spring_motion/internal/solver/threads.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <optional>
#include <type_traits>
#include <vector>

namespace spring_motion {
namespace internal {

/// The coarse levels of a multigrid cycle for block (element-model) systems,
/// whose coarse functions move each aggregate as a rigid body: D
/// translations and D(D-1)/2 rotations about its centre per coarse unknown.
///
/// Ball-vertex, torsional and truss springs resist a change of shape, not a
/// rotation: the linearised energy of an infinitesimal rotation of a group of
/// vertices is zero inside the group. Where the stiffness grows fast towards
/// the body (k = 1/h^2, 1/h^3), the small elements there turn almost rigidly
/// and a coarse space of translations only (Aggregation_multigrid) cannot
/// express that motion: conjugate gradients then need several times the
/// iterations of a scalar system. With the rotations of every aggregate in
/// the coarse space (the near null space of smoothed aggregation, Vanek,
/// Mandel and Brezina, here with unsmoothed prolongation) they do not.
///
/// Level 0 aggregates the fine vertices as Aggregation_multigrid does (the
/// same greedy aggregation on the Frobenius norms of the D x D blocks); a
/// fine vertex i of aggregate a takes the coarse function
/// P_i = [I | S(x_i - c_a)], c_a the mean position of a's vertices and
/// S(d) w the displacement w x d of a rotation w (2D: w (-d_y, d_x)). Level
/// l + 1 aggregates the unknowns of level l (on the norms of the
/// translational D x D parts of their blocks) and moves a member a of an
/// aggregate b by the rigid motion of b: u_a = U_b + S(c_a - c_b) W_b, w_a =
/// W_b. Every level's matrix is the Galerkin product P^T A P of the level
/// above, recomputed from the new values and positions at every `load`;
/// the aggregates are chosen at `build` (when: Aggregation_refresh). The
/// coarsest level is solved by a dense Cholesky factorisation.
///
/// In 3D the Gauss-Seidel sweeps of the coarse levels read a single-precision
/// copy of the off-diagonal blocks, made at `load` when every value fits a
/// float (as the fine level's sweeps do): a 3D block of a coarse level holds
/// 36 values, and level 0's sweeps moved about as many bytes as the fine
/// level's. The copy stores each block by columns, so that two rows' sums
/// (four where AVX runs) take one vector operation per column, with the same
/// bits as by rows (subtract_row_products_by_columns). 2D levels keep double precision
/// (see load_level). The residual
/// restricted after the forward sweep is formed from the entries the sweep
/// read (those after each row), so each level's cycle stays the symmetric
/// V-cycle of its matrix as the sweeps read it; the Galerkin products and
/// the coarsest factorisation stay in double.
///
/// The result does not depend on the thread count: the Gauss-Seidel sweeps
/// of the coarse levels run serially, and every other loop (the Galerkin
/// products, the restrictions, the prolongations) runs over the aggregates
/// and sums each aggregate's values over its members in increasing order,
/// the order of a serial loop over the members.
template <int D>
class Rigid_body_multigrid
{
public:
  /// unknowns per coarse node: D translations, then the rotations
  static constexpr int R = D * (D + 1) / 2;
  static constexpr int DD = D * D, RR = R * R;
  using Row = std::array<double, D>;
  using Coarse_row = std::array<double, R>;

  /// the same parameters as Aggregation_multigrid's
  Multigrid_parameters parameters;
  /// V-cycles per solve on level 0 (see `cycle`)
  std::size_t first_level_cycles = 1;

  bool built() const { return built_; }
  std::size_t number_of_levels() const { return levels_.size(); }
  std::size_t rows(std::size_t level) const { return levels_[level].n; }
  /// whether the sweeps of `level` read single precision (see load_level)
  bool single_precision(std::size_t level) const { return !levels_[level].single.empty(); }
  /// how many times `load` has recomputed the levels
  std::size_t loads() const { return loads_; }

  /// Chooses the aggregates of every level from the fine block matrix and
  /// the positions of its rows.
  void build(const Csr_view& fine, const Row* points, int threads = 1)
  {
    SPRING_MOTION_CHECK(fine.block, "rigid-body multigrid: the fine system must have D x D blocks");
    levels_.clear();
    built_ = true;
    interval_ = {};
    interval_due_ = true;
    std::size_t n = fine.rows;
    while(n > parameters.coarsest_rows) {
      Aggregates g;
      std::vector<double> scale(n), coupling;
      if(levels_.empty()) {
        coupling.resize(fine.offsets[n]);
        for(std::size_t i = 0; i < n; ++i) {
          scale[i] = block_norm<D>(fine.diag + i * DD);
          for(Index q = fine.offsets[i]; q < fine.offsets[i + 1]; ++q) {
            std::array<double, DD> whole;
            coupling[q] = block_norm<D>(whole_block<D>(fine.values, fine.upper, q, whole));
          }
        }
        // fewer than D vertices lie on one line and cannot feel a rotation
        // about it (see rotation_springs): such aggregates join a neighbour
        if(!aggregate_strong_neighbours(n, fine.offsets, fine.col, scale, coupling, parameters.strength, g,
                                        std::size_t(D)))
          break;
      } else {
        const Level& f = levels_.back();
        coupling.resize(f.col.size());
        for(std::size_t i = 0; i < n; ++i) {
          scale[i] = translation_norm(&f.diag[i * RR]);
          for(Index q = f.offsets[i]; q < f.offsets[i + 1]; ++q)
            coupling[q] = translation_norm(&f.values[std::size_t(q) * RR]);
        }
        if(!aggregate_strong_neighbours(n, f.offsets.data(), f.col.data(), scale, coupling, parameters.strength, g))
          break;
      }
      Level L;
      L.n = g.count;
      L.parent_of = std::move(g.parent_of);
      L.slot_of = std::move(g.slot_of);
      L.offsets = std::move(g.offsets);
      L.col = std::move(g.col);
      L.transposed = transposed_entries(L.offsets, L.col);
      L.values.resize(L.col.size() * RR);
      L.diag.resize(L.n * RR);
      L.inv_diag.resize(L.n * RR);
      L.rhs.resize(L.n);
      L.z.resize(L.n);
      L.residual.resize(L.n);
      L.centre.resize(L.n);
      L.offset.resize(n);
      L.member_offsets = std::move(g.member_offsets);
      L.members = std::move(g.members);
      levels_.push_back(std::move(L));
      // this level's values, to aggregate the next one
      load_level(levels_.size() - 1, fine, points, threads);
      n = levels_.back().n;
    }
  }

  /// Recomputes every level's values from the fine matrix (same pattern as
  /// in `build`) and the positions of its rows, and factors the coarsest.
  void load(const Csr_view& fine, const Row* points, int threads = 1)
  {
    ++loads_;
    for(std::size_t l = 0; l < levels_.size(); ++l)
      load_level(l, fine, points, threads);
    factor_coarsest();
  }

  /// level 0's right-hand side from the fine residual: P^T r
  void restrict_from(const std::vector<Row>& fine_residual, int threads = 1)
  {
    restrict_to(levels_.front(), fine_residual, team(0, threads));
  }

  /// Solves approximately on level 0: `first_level_cycles` V-cycles over
  /// the coarse levels, each on the residual the ones before left, their
  /// corrections weighted as in Chebyshev iteration (see first_level_interval).
  void cycle(int threads = 1)
  {
    Level& L = levels_.front();
    if(first_level_cycles <= 1 || levels_.size() < 2) {
      cycle(0, threads);
      return;
    }
    if(interval_due_) {
      rhs0_ = L.rhs;
      interval_ = estimate_first_level_interval(threads);
      interval_due_ = false;
      L.rhs.swap(rhs0_);
    }
    // z = p(B A) B r, B one V-cycle and p a polynomial of degree
    // first_level_cycles - 1: symmetric with B, so the whole stays a
    // symmetric preconditioner for conjugate gradients. A is level 0's
    // matrix as its sweeps read it. Without an interval p is the sum of
    // (I - B A)^k (each cycle's correction added as it is).
    rhs0_ = L.rhs;
    sum_.assign(L.n, Coarse_row{});
    const bool chebyshev = interval_.valid();
    if(chebyshev)
      step_.assign(L.n, Coarse_row{});
    std::optional<Chebyshev_steps> weights;
    if(chebyshev)
      weights.emplace(interval_);
    const long n = long(L.n);
    const int nt = team(0, threads);
    for(std::size_t k = 0; k < first_level_cycles; ++k) {
      if(k == 0)
        cycle(0, threads);
      else
        with_sweep_values(L, [&](const auto* v) { cycle_on_residual(threads, v); });
      if(chebyshev) {
        const auto w = weights->next();
        in_team(nt, [&] {
#pragma omp for schedule(static)
          for(long i = 0; i < n; ++i)
            for(int c = 0; c < R; ++c) {
              double& d = step_[std::size_t(i)][c];
              d = w.first * d + w.second * L.z[std::size_t(i)][c];
              sum_[std::size_t(i)][c] += d;
            }
        });
      } else {
        in_team(nt, [&] {
#pragma omp for schedule(static)
          for(long i = 0; i < n; ++i)
            for(int c = 0; c < R; ++c)
              sum_[std::size_t(i)][c] += L.z[std::size_t(i)][c];
        });
      }
    }
    L.z.swap(sum_);
    L.rhs.swap(rhs0_);
  }

  /// The interval of B A's eigenvalues on level 0 that its cycles are
  /// weighted for (empty before the first cycle after `build`, and when
  /// first_level_cycles <= 1).
  const Eigen_interval& first_level_interval() const { return interval_; }

  /// (P z)_i: the displacement of fine row i by level 0's solution z.
  Row correction(std::size_t i) const
  {
    const Level& c = levels_.front();
    const Coarse_row& z = c.z[c.parent_of[i]];
    Row u;
    for(int k = 0; k < D; ++k)
      u[k] = z[k];
    add_rotation(z, c.offset[i], u.data());
    return u;
  }

  /// The aggregate of level l that unknown i of the level above belongs to.
  Index parent(std::size_t level, std::size_t i) const { return levels_[level].parent_of[i]; }
  /// Level l's matrix: R x R blocks, row-major, the translations first.
  const std::vector<Index>& offsets(std::size_t level) const { return levels_[level].offsets; }
  const std::vector<Index>& columns(std::size_t level) const { return levels_[level].col; }
  const std::vector<double>& values(std::size_t level) const { return levels_[level].values; }
  const std::vector<double>& diagonal(std::size_t level) const { return levels_[level].diag; }
  /// The centre of unknown a of level l (the mean of its members' positions).
  const Row& centre(std::size_t level, Index a) const { return levels_[level].centre[a]; }

  /// C += P_i^T A P_j for an F x F block A of the finer level (row-major):
  /// F = D, a fine block, P = [I | S(d)]; F = R, a block of the coarse level
  /// above, P = [[I, S(d)], [0, I]] (the finer node's rotations carry over);
  /// d_i, d_j the two finer unknowns' offsets from their aggregates' centres.
  /// C is R x R, row-major.
  ///
  /// Written by blocks: the rows of T = A P_j are [A_t | A_t S_j (+ A_r)]
  /// (A_t the translational columns of a row, A_r its rotational ones), and
  /// C gains T's translational rows, then S_i^T (T's translational rows) (+
  /// T's rotational rows). S(d)^T v is d x v in 3D (-d_y v_x + d_x v_y in
  /// 2D), two products per entry, where the dense products (F x F times F x
  /// R, then R x F times F x R) multiply by P's zeros and ones: a third of
  /// the multiplications for F = D, a sixth for F = R in 3D. Each entry is
  /// the same sum of the same nonzero products in the same order as in the
  /// dense form, whose other terms are exact zeros and ones.
  template <int F>
  static void add_galerkin_by_blocks(const double* A, const Row& di, const Row& dj, double* C)
  {
    static_assert(F == D || F == R, "a block of the fine level or of a coarse one");
    constexpr int W = R - D; // rotations
    std::array<double, F * R> T;
    for(int r = 0; r < F; ++r) {
      Row a;
      for(int c = 0; c < D; ++c) {
        a[c] = A[r * F + c];
        T[r * R + c] = a[c];
      }
      const auto t = rotation_transpose_times(dj, a);
      for(int m = 0; m < W; ++m)
        T[r * R + D + m] = F == R ? t[m] + A[r * F + D + m] : t[m];
    }
    for(int c = 0; c < R; ++c) {
      Row v;
      for(int r = 0; r < D; ++r) {
        v[r] = T[r * R + c];
        C[r * R + c] += v[r];
      }
      const auto t = rotation_transpose_times(di, v);
      for(int k = 0; k < W; ++k)
        C[(D + k) * R + c] += F == R ? t[k] + T[(D + k) * R + c] : t[k];
    }
  }

private:
  static constexpr Index none = std::numeric_limits<Index>::max();

  struct Level
  {
    std::size_t n = 0;                          // unknowns (aggregates) of this level
    std::vector<Index> parent_of;               // finer unknown -> aggregate
    std::vector<Index> slot_of;                 // finer off-diagonal entry -> entry here, or none
    std::vector<Index> offsets, col;            // this level's pattern
    std::vector<Index> transposed;              // per entry (a, b): the entry (b, a)
    std::vector<double> values, diag, inv_diag; // R x R per entry / row
    std::vector<float> single;                  // values in single precision for the sweeps, each block
                                                // by columns (subtract_row), or empty
    std::vector<Coarse_row> rhs, z;
    std::vector<Coarse_row> residual;           // after the forward sweep (see cycle(l, threads, v, rhs))
    std::vector<Row> centre;                    // per unknown
    std::vector<Row> offset;                    // per finer unknown: its position minus its aggregate's centre
    std::vector<Index> member_offsets, members; // per unknown: the finer unknowns it aggregates, increasing
  };

  // The team for a loop over level l's aggregates or the finer unknowns they
  // aggregate, sized by those finer unknowns. thread_count's threshold is in
  // rows of a dozen or so entries (a fine block row counts as one); an entry
  // of a coarse level holds RR values, so its row counts as RR rows.
  int team(std::size_t l, int threads) const
  {
    const std::size_t finer = levels_[l].parent_of.size();
    return thread_count(threads, l == 0 ? finer : finer * RR);
  }

  // Frobenius norm of the translational D x D part of an R x R block
  static double translation_norm(const double* m)
  {
    double s = 0;
    for(int r = 0; r < D; ++r)
      for(int c = 0; c < D; ++c)
        s += m[r * R + c] * m[r * R + c];
    return std::sqrt(s);
  }

  // column k of S(d): the displacement at offset d of the unit rotation k
  static Row rotation_column(int k, const Row& d)
  {
    if constexpr(D == 2)
      return {-d[1], d[0]};
    else {
      // e_k x d
      if(k == 0)
        return {0.0, -d[2], d[1]};
      if(k == 1)
        return {d[2], 0.0, -d[0]};
      return {-d[1], d[0], 0.0};
    }
  }

  // S(d)^T v, the rotations' part of P^T v: entry k is (e_k x d) . v, which
  // is (d x v)_k in 3D; in 2D (-d_y, d_x) . v. Each entry sums the nonzero
  // entries of column k of S(d) (rotation_column) in increasing row order,
  // as a dense product over that column does.
  static std::array<double, R - D> rotation_transpose_times(const Row& d, const Row& v)
  {
    if constexpr(D == 2)
      return {-d[1] * v[0] + d[0] * v[1]};
    else
      return {-d[2] * v[1] + d[1] * v[2], d[2] * v[0] - d[0] * v[2], -d[1] * v[0] + d[0] * v[1]};
  }

  // u += S(d) w, w the rotations of z
  static void add_rotation(const Coarse_row& z, const Row& d, double* u)
  {
    for(int k = 0; k < R - D; ++k) {
      const Row s = rotation_column(k, d);
      for(int c = 0; c < D; ++c)
        u[c] += z[D + k] * s[c];
    }
  }

  // rc += P^T s for a finer unknown at offset d; s has D (fine) or R values
  template <int F>
  static void add_restricted(const double* s, const Row& d, Coarse_row& rc)
  {
    Row v;
    for(int c = 0; c < D; ++c) {
      rc[c] += s[c];
      v[c] = s[c];
    }
    const auto t = rotation_transpose_times(d, v);
    for(int k = 0; k < R - D; ++k)
      rc[D + k] += t[k] + (F == R ? s[D + k] : 0.0);
  }

  // C's right-hand side P^T s from s, one row per finer unknown (D values
  // on the fine level, R on a coarse one), summed aggregate by aggregate.
  // An aggregate's members lie scattered over the finer rows (the fine rows
  // are numbered by colour for the sweeps), and without requests most reads
  // of the wing's fine residuals and offsets waited on memory: each member
  // requests the one ahead_members later. Not when s and the offsets fit
  // the caches: the 2D paper mesh's solve then took 2% more instructions,
  // all in the requests (0.3% more for the test alone, hence two loops).
  template <std::size_t F>
  void restrict_to(Level& C, const std::vector<std::array<double, F>>& s, int nt)
  {
    const long na = long(C.n);
    const Index nm = Index(C.members.size());
    auto restrict_all = [&](auto requesting) {
      in_team(nt, [&] {
#pragma omp for schedule(static)
        for(long a = 0; a < na; ++a) {
          Coarse_row rc{};
          for(Index m = C.member_offsets[std::size_t(a)]; m < C.member_offsets[std::size_t(a) + 1]; ++m) {
            if constexpr(decltype(requesting)::value)
              if(m + ahead_members < nm) {
                const Index f = C.members[m + ahead_members];
                prefetch_range(&s[f], &s[f] + 1);
                prefetch_range(&C.offset[f], &C.offset[f] + 1);
              }
            add_restricted<int(F)>(s[C.members[m]].data(), C.offset[C.members[m]], rc);
          }
          C.rhs[std::size_t(a)] = rc;
        }
      });
    };
    if(std::size_t(nm) * (sizeof(s[0]) + sizeof(Row)) > prefetch_members_above)
      restrict_all(std::true_type{});
    else
      restrict_all(std::false_type{});
  }

  // level l's centres, offsets and values from the level above (the fine
  // matrix for l = 0)
  void load_level(std::size_t l, const Csr_view& fine, const Row* points, int threads)
  {
    Level& L = levels_[l];
    const Row* p = l == 0 ? points : levels_[l - 1].centre.data();
    const long na = long(L.n), n = long(L.parent_of.size());
    bool definite = true, sturdy = true;
    const int nt = team(l, threads);
    const bool in_order = nt == 1;
#pragma omp parallel num_threads(nt) reduction(&& : definite, sturdy)
    {
#pragma omp for schedule(static)
      for(long a = 0; a < na; ++a) {
        Row c{};
        for(Index m = L.member_offsets[std::size_t(a)]; m < L.member_offsets[std::size_t(a) + 1]; ++m)
          for(int k = 0; k < D; ++k)
            c[k] += p[L.members[m]][k];
        const double count = double(L.member_offsets[std::size_t(a) + 1] - L.member_offsets[std::size_t(a)]);
        for(int k = 0; k < D; ++k)
          c[k] /= count;
        L.centre[std::size_t(a)] = c;
      }
#pragma omp for schedule(static)
      for(long i = 0; i < n; ++i)
        for(int k = 0; k < D; ++k)
          L.offset[std::size_t(i)][k] = p[i][k] - L.centre[L.parent_of[std::size_t(i)]][k];
      // on one thread the finer rows in order, in which they lie (the same
      // sums: see sum_galerkin_in_order)
      if(in_order) {
        if(l == 0)
          sum_galerkin_in_order<D>(L, fine.offsets, fine.col, fine.values, fine.diag, fine.upper);
        else {
          const Level& f = levels_[l - 1];
          sum_galerkin_in_order<R>(L, f.offsets.data(), f.col.data(), f.values.data(), f.diag.data());
        }
      }
#pragma omp for schedule(static)
      for(long a = 0; a < na; ++a) {
        if(!in_order) {
          if(l == 0)
            sum_galerkin<D>(L, std::size_t(a), fine.offsets, fine.col, fine.values, fine.diag, fine.upper);
          else {
            const Level& f = levels_[l - 1];
            sum_galerkin<R>(L, std::size_t(a), f.offsets.data(), f.col.data(), f.values.data(), f.diag.data());
          }
        }
        bool block_sturdy = false;
        definite = invert_diagonal(L, std::size_t(a), block_sturdy) && definite;
        sturdy = sturdy && block_sturdy;
      }
      // the entries below the diagonal from those above (sum_galerkin)
#pragma omp for schedule(static)
      for(long a = 0; a < na; ++a)
        for(Index s = L.offsets[std::size_t(a)]; s < L.offsets[std::size_t(a) + 1]; ++s)
          if(L.col[s] < Index(a))
            transpose_block<R>(&L.values[std::size_t(L.transposed[s]) * RR], &L.values[std::size_t(s) * RR]);
    }
    SPRING_MOTION_CHECK(definite, "multigrid: a coarse diagonal block is not positive definite");
    // In 2D a coarse block holds 9 values, and converting them in the
    // sweeps' 3 x 3 products cost the block step more than the bytes saved
    // (docs/performance.md): 2D levels keep double precision.
    bool fits = D == 3 && sturdy;
    if(fits) {
      // sized once (the pattern is the build's), written in place: a value
      // out of a float's range is not converted (it traps under
      // feenableexcept), and then the copy is dropped
      L.single.resize(L.values.size());
      fits = copy_to_single_by_columns<R>(L.values.data(), L.single.data(), long(L.values.size() / RR),
                                          team(l, threads));
    }
    if(!fits)
      L.single.clear();
  }

  // entry q of a level's matrix (F x F blocks) as a whole block: in place,
  // or, given the fine level's upper triangles (F = D, see Csr_view),
  // expanded from its triangle into `whole` (the same values)
  template <int F>
  static const double* whole_block(const double* values, const double* upper, Index q,
                                   std::array<double, F * F>& whole)
  {
    if constexpr(F == D)
      if(upper) {
        expand_symmetric_block<D>(upper + std::size_t(q) * (D * (D + 1) / 2), whole.data());
        return whole.data();
      }
    return values + std::size_t(q) * F * F;
  }

  // Aggregate a's row of the Galerkin product, summed over its members'
  // entries of the finer level (F x F blocks; of the fine level, F = D, the
  // entries' upper triangles when `upper` is given, see Csr_view): only its
  // entries (a, b) with b > a and its diagonal block. The finer matrix is
  // symmetric, so entry (j, i) adds the transpose of what (i, j) adds: the
  // entries (b, a) are the transposes of the (a, b) (load_level copies them),
  // and of the pairs inside the aggregate one side adds both. Half the block
  // products of summing every entry, and every level's matrix exactly
  // symmetric.
  template <int F>
  static void sum_galerkin(Level& L, std::size_t a, const Index* offsets, const Index* col, const double* values,
                           const double* diag, const double* upper = nullptr)
  {
    clear_galerkin_row(L, a);
    const Index members_end = Index(L.members.size());
    for(Index m = L.member_offsets[a]; m < L.member_offsets[a + 1]; ++m) {
      // the members' rows lie apart (the finer order is not the
      // aggregates'): the next member's row is fetched while this one is
      // summed, its offsets and diagonal block one member earlier
      if(m + 2 < members_end) {
        const std::size_t ahead = L.members[m + 2];
        prefetch_range(&offsets[ahead], &offsets[ahead + 1]);
        prefetch_range(diag + ahead * F * F, diag + (ahead + 1) * F * F);
      }
      if(m + 1 < members_end)
        prefetch_row<F>(L, L.members[m + 1], offsets, col, values, upper);
      add_galerkin_row<F>(L, a, L.members[m], offsets, col, values, diag, upper);
    }
  }

  // The same for every aggregate, the finer rows taken in their order: each
  // coarse block gains the same terms in the same order as from
  // sum_galerkin (its aggregate's members in increasing order, each row's
  // entries in order), so the same bits, from a pass that reads the finer
  // matrix in the order it is stored. On one thread: a block's terms come
  // from rows that different threads would take.
  template <int F>
  static void sum_galerkin_in_order(Level& L, const Index* offsets, const Index* col, const double* values,
                                    const double* diag, const double* upper = nullptr)
  {
    for(std::size_t a = 0; a < L.n; ++a)
      clear_galerkin_row(L, a);
    for(std::size_t i = 0; i < L.parent_of.size(); ++i)
      add_galerkin_row<F>(L, L.parent_of[i], i, offsets, col, values, diag, upper);
  }

  // zeroes what sum_galerkin sums in aggregate a's row
  static void clear_galerkin_row(Level& L, std::size_t a)
  {
    double* dA = &L.diag[a * RR];
    std::fill(dA, dA + RR, 0.0);
    for(Index s = L.offsets[a]; s < L.offsets[a + 1]; ++s)
      if(L.col[s] > Index(a))
        std::fill(&L.values[std::size_t(s) * RR], &L.values[std::size_t(s + 1) * RR], 0.0);
  }

  // adds finer row i's terms to aggregate a's row (see sum_galerkin)
  template <int F>
  static void add_galerkin_row(Level& L, std::size_t a, std::size_t i, const Index* offsets, const Index* col,
                               const double* values, const double* diag, const double* upper)
  {
    double* dA = &L.diag[a * RR];
    const Row& di = L.offset[i];
    add_galerkin_by_blocks<F>(diag + i * F * F, di, di, dA);
    for(Index q = offsets[i]; q < offsets[i + 1]; ++q) {
      const Index s = L.slot_of[q];
      std::array<double, F * F> whole;
      if(s != none) {
        if(L.col[s] > Index(a))
          add_galerkin_by_blocks<F>(whole_block<F>(values, upper, q, whole), di, L.offset[col[q]],
                                    &L.values[std::size_t(s) * RR]);
      } else if(std::size_t(col[q]) > i) {
        std::array<double, RR> X{};
        add_galerkin_by_blocks<F>(whole_block<F>(values, upper, q, whole), di, L.offset[col[q]], X.data());
        for(int r = 0; r < R; ++r)
          for(int c = 0; c < R; ++c)
            dA[r * R + c] += X[std::size_t(r * R + c)] + X[std::size_t(c * R + r)];
      }
    }
  }

  // requests finer row i's entries (their blocks, columns and slots here)
  template <int F>
  static void prefetch_row(const Level& L, Index i, const Index* offsets, const Index* col, const double* values,
                           const double* upper)
  {
    const double* blocks = upper ? upper : values; // upper: triangles of the fine level's blocks
    const std::size_t width = upper ? std::size_t(D * (D + 1) / 2) : std::size_t(F * F);
    prefetch_range(blocks + std::size_t(offsets[i]) * width, blocks + std::size_t(offsets[i + 1]) * width);
    prefetch_range(&col[offsets[i]], &col[offsets[i] + 1]);
    prefetch_range(&L.slot_of[offsets[i]], &L.slot_of[offsets[i] + 1]);
  }

  // per entry (a, b) of a pattern, the entry (b, a); the pattern of a
  // symmetric matrix has both
  static std::vector<Index> transposed_entries(const std::vector<Index>& offsets, const std::vector<Index>& col)
  {
    std::vector<Index> t(col.size(), none);
    for(std::size_t a = 0; a + 1 < offsets.size(); ++a)
      for(Index s = offsets[a]; s < offsets[a + 1]; ++s)
        for(Index u = offsets[col[s]]; u < offsets[col[s] + 1]; ++u)
          if(col[u] == Index(a)) {
            t[s] = u;
            break;
          }
    SPRING_MOTION_CHECK(std::find(t.begin(), t.end(), none) == t.end(),
                        "rigid-body multigrid: the pattern of the finer matrix is not symmetric");
    return t;
  }

  // T = M^T for F x F row-major blocks
  template <int F>
  static void transpose_block(const double* M, double* T)
  {
    for(int r = 0; r < F; ++r)
      for(int c = 0; c < F; ++c)
        T[c * F + r] = M[r * F + c];
  }

  // An aggregate whose vertices lie on one line (a single vertex; two in 3D)
  // does not feel a rotation about that line: its rotations' diagonal is then
  // singular, and their coupling to everything else zero. `build` joins the
  // aggregates of fewer than D vertices to a neighbour, since such a block
  // also keeps the whole level's sweeps in double precision (single_pivot);
  // the springs are for what is left (collinear vertices, an aggregate
  // with no neighbour to join). A tiny spring on
  // them (1e-13 of the largest diagonal entry) makes the block invertible
  // without changing any other unknown's solution. On the next level such an
  // aggregate's rotation is felt only through that spring, so an aggregate
  // of two of them (3D) has a direction about 1e-13 as stiff as its
  // diagonal, below what invert_spd_block accepts (a pivot above 1e-12 of
  // its diagonal entry): the spring then grows to 1e-10 and, failing that,
  // 1e-7. A stiffer spring on a nearly free direction only weakens the
  // preconditioner there; the solution conjugate gradients converge to is
  // the same.
  static constexpr std::array<double, 3> rotation_springs{1e-13, 1e-10, 1e-7};

  // A level's sweeps read single precision only when every diagonal block's
  // weakest direction keeps at least this fraction of its diagonal entry:
  // rounding the couplings to a float (relative 6e-8) could otherwise
  // outweigh a nearly free rotation and leave the level's matrix, as the
  // sweeps read it, indefinite (conjugate gradients then break down).
  static constexpr double single_pivot = 1e-4;

  // `sturdy`: whether no direction of the block is weaker than
  // single_pivot of its diagonal (see load_level)
  static bool invert_diagonal(Level& L, std::size_t a, bool& sturdy)
  {
    double* m = &L.diag[a * RR];
    double weakest = 0;
    if(invert_spd_block<R>(m, &L.inv_diag[a * RR], &weakest)) {
      sturdy = weakest >= single_pivot;
      return true;
    }
    sturdy = false;
    double top = 0;
    std::array<double, R> own{};
    for(int k = 0; k < R; ++k) {
      top = std::max(top, std::abs(m[k * R + k]));
      own[k] = m[k * R + k];
    }
    for(const double spring : rotation_springs) {
      for(int k = D; k < R; ++k)
        m[k * R + k] = own[k] + spring * top;
      if(invert_spd_block<R>(m, &L.inv_diag[a * RR]))
        return true;
    }
    return false;
  }

  void factor_coarsest()
  {
    if(levels_.empty())
      return;
    const Level& L = levels_.back();
    if(L.n > parameters.max_direct_rows)
      return;
    const std::size_t n = L.n * R;
    std::vector<double> a(n * n, 0.0);
    std::vector<std::size_t> first(n);
    double top = 0;
    for(std::size_t i = 0; i < L.n; ++i) {
      std::size_t f = i;
      for(Index q = L.offsets[i]; q < L.offsets[i + 1]; ++q)
        f = std::min(f, std::size_t(L.col[q]));
      for(std::size_t r = 0; r < R; ++r) {
        first[i * R + r] = f * R;
        for(std::size_t c = 0; c < R; ++c)
          a[(i * R + r) * n + i * R + c] = L.diag[i * RR + r * R + c];
        for(Index q = L.offsets[i]; q < L.offsets[i + 1]; ++q)
          for(std::size_t c = 0; c < R; ++c)
            a[(i * R + r) * n + L.col[q] * R + c] += L.values[std::size_t(q) * RR + r * R + c];
        top = std::max(top, std::abs(a[(i * R + r) * n + i * R + r]));
      }
    }
    envelope_ = Dense_envelope::from_first(std::move(first));
    chol_ = a;
    if(try_dense_cholesky(chol_, n, envelope_, 0.0))
      return;
    // a rotation felt only through the springs of invert_diagonal can leave
    // the whole level a direction as nearly free: the same springs
    // (rotation_springs), growing, on every rotation (and the same pivot test as the diagonal blocks')
    for(const double spring : rotation_springs) {
      chol_ = a;
      for(std::size_t i = 0; i < L.n; ++i)
        for(std::size_t k = D; k < std::size_t(R); ++k)
          chol_[(i * R + k) * n + i * R + k] += spring * top;
      if(try_dense_cholesky(chol_, n, envelope_, 1e-12))
        return;
    }
    SPRING_MOTION_CHECK(false, "multigrid: the coarsest matrix is not positive definite");
  }

  void solve_coarsest(Level& L) const
  {
    dense_cholesky_solve<1>(chol_, L.n * R, envelope_, L.rhs[0].data(), L.z[0].data());
  }

  // s -= the sum over the entries q of row i with keep(col[q]) of A_q
  // x[col[q]], the blocks as the sweeps read them: doubles by rows, or the
  // single-precision copy by columns (the same bits)
  template <class T, class Keep>
  static void subtract_row(Coarse_row& s, const Level& L, const T* v, std::size_t i, const std::vector<Coarse_row>& x,
                           Keep keep)
  {
    if constexpr(std::is_same_v<T, float>) {
      subtract_row_products_by_columns<R>(s, v, L.col.data(), L.offsets[i], L.offsets[i + 1], x.data(), keep);
    } else {
      for(Index q = L.offsets[i]; q < L.offsets[i + 1]; ++q)
        if(keep(L.col[q]))
          subtract_block_product<R>(s, v + std::size_t(q) * RR, x[L.col[q]]);
    }
  }

  // calls f with the off-diagonal values the level's sweeps read: the
  // single-precision copy where load_level made one, else the doubles
  template <class F>
  static void with_sweep_values(const Level& L, F&& f)
  {
    if(L.single.empty())
      f(L.values.data());
    else
      f(L.single.data());
  }

  // rhs_i - sum_j A_ij z_j over the off-diagonal entries of row i, read
  // from v (the level's values or their single-precision copy)
  template <class T>
  static Coarse_row off_residual(const Level& L, const T* v, std::size_t i)
  {
    Coarse_row s = L.rhs[i];
    subtract_row(s, L, v, i, L.z, [](Index) { return true; });
    return s;
  }

  // Forward Gauss-Seidel from z = 0: when row i is reached z_j is still 0
  // for every j > i, so only the entries j < i change the sum (skipping the
  // others halves the blocks the sweep reads; the sum is the same).
  // `rhs(i)`: row i's right-hand side, asked for when the sweep reaches
  // the row (see cycle_on_residual).
  template <class T, class Rhs>
  static void forward_gauss_seidel_from_zero(Level& L, const T* v, Rhs rhs)
  {
    std::fill(L.z.begin(), L.z.end(), Coarse_row{});
    for(std::size_t i = 0; i < L.n; ++i) {
      if(i + ahead_rows < L.n)
        prefetch_row(L, v, i + ahead_rows);
      Coarse_row s = rhs(i);
      subtract_row(s, L, v, i, L.z, [i](Index j) { return j < i; });
      L.z[i] = block_product<R>(&L.inv_diag[i * RR], s);
    }
  }

  // row i's residual after forward_gauss_seidel_from_zero: row i's equation
  // then holds with the rows after i at zero, so the residual is
  // -(sum over j > i of A_ij z_j); half the row's entries and not its
  // diagonal (the same quantity as rhs - A z, rounded differently)
  template <class T>
  static Coarse_row residual_after_forward_sweep(const Level& L, const T* v, std::size_t i)
  {
    Coarse_row s{};
    subtract_row(s, L, v, i, L.z, [i](Index j) { return j > i; });
    return s;
  }

  template <class T>
  static void backward_gauss_seidel(Level& L, const T* v)
  {
    for(std::size_t i = L.n; i-- > 0;) {
      if(i >= ahead_rows)
        prefetch_row(L, v, i - ahead_rows);
      L.z[i] = block_product<R>(&L.inv_diag[i * RR], off_residual(L, v, i));
    }
  }

  // the row a sweep takes after the next: level 0's blocks outgrow the
  // second-level cache (4.6 MB in single precision on the paper-size wing)
  // and, without this, most of the sweeps' profiler samples wait on the
  // first load of a block. 2D levels (9 values a block) fit the caches,
  // where the requests only add instructions.
  static constexpr std::size_t ahead_rows = 2;
  static constexpr Index ahead_members = 32;
  static constexpr std::size_t prefetch_members_above = std::size_t(1) << 20; // bytes
  template <class T>
  static void prefetch_row(const Level& L, const T* v, std::size_t i)
  {
    if constexpr(D == 3)
      prefetch_range(v + std::size_t(L.offsets[i]) * RR, v + std::size_t(L.offsets[i + 1]) * RR);
  }

  // a symmetric V-cycle on level l from z = 0: forward Gauss-Seidel, coarse
  // correction, backward Gauss-Seidel
  void cycle(std::size_t l, int threads)
  {
    Level& L = levels_[l];
    if(l + 1 == levels_.size() && L.n <= parameters.max_direct_rows)
      solve_coarsest(L);
    else
      with_sweep_values(L, [&](const auto* v) { cycle(l, threads, v); });
  }

  // the next of level 0's cycles (see `cycle`), on rhs0 - A sum: each
  // row's residual is formed as the forward sweep reaches the row (its
  // diagonal block, then its entries) and kept for the backward sweep.
  // The sweep then reads the row's blocks again from the first-level
  // cache, where a pass of its own before the sweep read the level's
  // blocks from memory once more (level 0 of the paper-size wing does not
  // fit the second-level cache).
  template <class T>
  void cycle_on_residual(int threads, const T* v)
  {
    Level& L = levels_.front();
    cycle(0, threads, v, [&](std::size_t i) {
      Coarse_row r = rhs0_[i];
      subtract_block_product<R>(r, &L.diag[i * RR], sum_[i]);
      subtract_row(r, L, v, i, sum_, [](Index) { return true; });
      L.rhs[i] = r;
      return r;
    });
  }

  template <class T>
  void cycle(std::size_t l, int threads, const T* v)
  {
    const Level& L = levels_[l];
    cycle(l, threads, v, [&L](std::size_t i) { return L.rhs[i]; });
  }

  template <class T, class Rhs>
  void cycle(std::size_t l, int threads, const T* v, Rhs rhs)
  {
    Level& L = levels_[l];
    forward_gauss_seidel_from_zero(L, v, rhs);
    if(l + 1 == levels_.size()) { // symmetric, so the cycle stays a symmetric preconditioner
      backward_gauss_seidel(L, v);
      return;
    }
    Level& C = levels_[l + 1];
    const long n = long(L.n);
    const int nt = team(l + 1, threads);
    // the residual in row order, where the rows' blocks can be requested
    // ahead (prefetch_row), then restricted aggregate by aggregate: formed
    // in the restriction's order, the members of an aggregate lie scattered
    // over the level and most reads of their blocks waited on memory
    in_team(nt, [&] {
#pragma omp for schedule(static)
      for(long i = 0; i < n; ++i) {
        if(std::size_t(i) + ahead_rows < L.n)
          prefetch_row(L, v, std::size_t(i) + ahead_rows);
        L.residual[std::size_t(i)] = residual_after_forward_sweep(L, v, std::size_t(i));
      }
    });
    restrict_to(C, L.residual, nt);
    cycle(l + 1, threads);
    const double a = parameters.correction;
    in_team(nt, [&] {
#pragma omp for schedule(static)
      for(long i = 0; i < n; ++i) {
        const Coarse_row& Z = C.z[C.parent_of[std::size_t(i)]];
        Row u{};
        add_rotation(Z, C.offset[std::size_t(i)], u.data());
        for(int c = 0; c < D; ++c)
          L.z[std::size_t(i)][c] += a * (Z[c] + u[c]);
        for(int k = D; k < R; ++k)
          L.z[std::size_t(i)][k] += a * Z[k];
      }
    });
    backward_gauss_seidel(L, v);
  }

  // The interval for level 0's cycles: the extreme Ritz values of
  // `lanczos_steps` steps of conjugate gradients on level 0 preconditioned
  // by one cycle, from a fixed start, the upper end raised by
  // `interval_margin` (Lanczos approaches the largest eigenvalue from below,
  // and an eigenvalue above the interval is reduced less; the smallest Ritz
  // value lies above the smallest eigenvalue, whose error then still
  // shrinks, more slowly). Made once per `build` (the aggregates), at the
  // first cycle after it: the values change a little from step to step.
  // Serial sums, so the same interval for any thread count
  // (docs/performance.md, "Chebyshev weights for the first coarse level's
  // cycles").
  static constexpr int lanczos_steps = 10;
  static constexpr double interval_margin = 1.05;
  Eigen_interval estimate_first_level_interval(int threads)
  {
    Level& L = levels_.front();
    const std::size_t n = L.n;
    std::vector<Coarse_row> r(n), p, q(n);
    std::uint64_t state = 0x9e3779b97f4a7c15ULL; // a fixed start: the same interval every run
    for(Coarse_row& row : r)
      for(double& v : row) {
        state = state * 6364136223846793005ULL + 1442695040888963407ULL;
        v = double(state >> 11) * 0x1.0p-53 - 0.5;
      }
    auto dot = [n](const std::vector<Coarse_row>& x, const std::vector<Coarse_row>& y) {
      double t = 0;
      for(std::size_t i = 0; i < n; ++i)
        for(int c = 0; c < R; ++c)
          t += x[i][c] * y[i][c];
      return t;
    };
    auto precondition = [&](const std::vector<Coarse_row>& x) {
      L.rhs = x;
      cycle(0, threads);
      return L.z;
    };
    std::vector<Coarse_row> z = precondition(r);
    p = z;
    double rz = dot(r, z);
    std::vector<double> alpha, beta;
    for(int j = 0; j < lanczos_steps && rz > 0; ++j) {
      for(std::size_t i = 0; i < n; ++i) {
        Coarse_row s = block_product<R>(&L.diag[i * RR], p[i]);
        for(Index e = L.offsets[i]; e < L.offsets[i + 1]; ++e) {
          const Coarse_row t = block_product<R>(&L.values[std::size_t(e) * RR], p[L.col[e]]);
          for(int c = 0; c < R; ++c)
            s[c] += t[c];
        }
        q[i] = s;
      }
      const double pq = dot(p, q);
      if(!(pq > 0))
        break;
      const double a = rz / pq;
      for(std::size_t i = 0; i < n; ++i)
        for(int c = 0; c < R; ++c)
          r[i][c] -= a * q[i][c];
      z = precondition(r);
      const double rz_next = dot(r, z);
      alpha.push_back(a);
      beta.push_back(rz_next / rz);
      rz = rz_next;
      for(std::size_t i = 0; i < n; ++i)
        for(int c = 0; c < R; ++c)
          p[i][c] = z[i][c] + beta.back() * p[i][c];
    }
    Eigen_interval i = lanczos_extremes(alpha, beta);
    i.high *= interval_margin;
    return i.valid() ? i : Eigen_interval{};
  }

  std::vector<Level> levels_;
  std::vector<Coarse_row> rhs0_, sum_, step_; // level 0's right-hand side, sum of cycles, last step (see `cycle`)
  Eigen_interval interval_;
  bool interval_due_ = false;
  std::vector<double> chol_;
  Dense_envelope envelope_;
  bool built_ = false;
  std::size_t loads_ = 0;
};

} // namespace internal
} // namespace spring_motion

#endif
