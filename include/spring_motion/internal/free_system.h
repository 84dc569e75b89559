// Copyright (c) 2026 SpringMotion developers.
#ifndef SPRING_MOTION_INTERNAL_FREE_SYSTEM_H
#define SPRING_MOTION_INTERNAL_FREE_SYSTEM_H

#include <spring_motion/Error.h>
#include <spring_motion/Solver_options.h>
#include <spring_motion/Spring_network.h>
#include <spring_motion/internal/aggregation_multigrid.h>
#include <spring_motion/internal/linear_system.h>
#include <spring_motion/internal/threads.h>

#include <boost/graph/adjacency_list.hpp>
#include <boost/graph/cuthill_mckee_ordering.hpp>
#include <boost/graph/sequential_vertex_coloring.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <numeric>
#include <vector>

namespace spring_motion {
namespace internal {

/// Rows per chunk of every reduction: partial results are formed per fixed
/// chunk and added in chunk order, so sums do not depend on the thread count.
constexpr std::size_t reduction_chunk = 1024;
/// The smallest block of the block-multicolour ordering (blocks are as wide as
/// the reverse Cuthill-McKee bandwidth, at least this).
constexpr std::size_t min_block_rows = 256;

/// The scalar (edge-model) spring system restricted to the free vertices, in
/// flat arrays ordered for speed: free vertices are numbered colour by colour
/// (a greedy colouring of the free spring graph by Boost's
/// `sequential_vertex_coloring`, no two neighbours share a colour), and within
/// a colour in reverse Cuthill-McKee order (Boost's `cuthill_mckee_ordering`)
/// for locality. Gauss-Seidel then runs in parallel over each colour, and
/// gives the same result for any thread count: a row reads only rows of other
/// colours. The ordering is computed once per network; `load` refills the
/// values every step.
template <int D>
class Free_system
{
public:
  using Row = std::array<double, D>;

  bool empty() const { return order_.empty() && !built_; }
  bool built() const { return built_; }
  std::size_t rows() const { return order_.size(); }
  std::size_t blocks() const { return block_offsets_.empty() ? 0 : block_offsets_.size() - 1; }
  std::size_t colours() const { return colour_offsets_.empty() ? 0 : colour_offsets_.size() - 1; }
  std::size_t nonzeros() const { return col_.size(); }
  const std::vector<Index>& order() const { return order_; }

  /// Builds the ordering and the pattern for these free vertices.
  void build(const Spring_network<D>& net, const std::vector<Index>& free_vertices,
             std::size_t block_rows = 0)
  {
    const std::size_t n = net.number_of_vertices();
    const std::size_t nf = free_vertices.size();
    std::vector<Index> compact(n, none);
    for(std::size_t k = 0; k < nf; ++k)
      compact[free_vertices[k]] = Index(k);
    using Graph = boost::adjacency_list<boost::vecS, boost::vecS, boost::undirectedS>;
    Graph g(nf);
    for(std::size_t k = 0; k < nf; ++k) {
      const Index i = free_vertices[k];
      for(Index p = net.adjacency_offsets[i]; p < net.adjacency_offsets[i + 1]; ++p) {
        const Index j = net.adjacency[p];
        if(compact[j] != none && compact[j] > k)
          boost::add_edge(k, compact[j], g);
      }
    }
    // reverse Cuthill-McKee: rcm[r] is the compact index at position r
    std::vector<std::size_t> rcm(nf);
    if(nf > 0)
      boost::cuthill_mckee_ordering(g, rcm.rbegin());
    std::vector<std::size_t> position(nf);
    for(std::size_t r = 0; r < nf; ++r)
      position[rcm[r]] = r;
    // Blocks of `block_rows` consecutive RCM rows; the quotient of the spring
    // graph on the blocks is coloured greedily (blocks in RCM order). With 1
    // row per block this is the plain multicolour ordering of the vertices.
    std::size_t bandwidth = 0;
    for(std::size_t k = 0; k < nf; ++k) {
      const Index i = free_vertices[k];
      for(Index p = net.adjacency_offsets[i]; p < net.adjacency_offsets[i + 1]; ++p)
        if(compact[net.adjacency[p]] != none) {
          const std::size_t a = position[k], b = position[compact[net.adjacency[p]]];
          bandwidth = std::max(bandwidth, a > b ? a - b : b - a);
        }
    }
    // 0: blocks as wide as the RCM bandwidth, so a block touches only the
    // blocks before and after it: two colours
    const std::size_t B = block_rows > 0 ? block_rows : std::max(min_block_rows, bandwidth);
    const std::size_t nb = (nf + B - 1) / B;
    std::vector<std::size_t> colour(nb, 0);
    std::size_t ncolours = 0;
    if(nf > 0) {
      std::vector<std::pair<std::size_t, std::size_t>> links;
      for(std::size_t k = 0; k < nf; ++k) {
        const Index i = free_vertices[k];
        for(Index p = net.adjacency_offsets[i]; p < net.adjacency_offsets[i + 1]; ++p) {
          const Index j = net.adjacency[p];
          if(compact[j] == none)
            continue;
          const std::size_t a = position[k] / B, b = position[compact[j]] / B;
          if(a < b)
            links.emplace_back(a, b);
        }
      }
      std::sort(links.begin(), links.end());
      links.erase(std::unique(links.begin(), links.end()), links.end());
      Graph quotient(nb);
      for(const auto& l : links)
        boost::add_edge(l.first, l.second, quotient);
      ncolours = boost::sequential_vertex_coloring(
          quotient, boost::make_iterator_property_map(colour.begin(), boost::get(boost::vertex_index, quotient)));
    }
    // blocks colour by colour, in RCM order within a colour; rows in RCM order
    std::vector<std::size_t> blocks(nb);
    std::iota(blocks.begin(), blocks.end(), std::size_t(0));
    std::stable_sort(blocks.begin(), blocks.end(),
                     [&](std::size_t a, std::size_t b) { return colour[a] < colour[b]; });
    order_.resize(nf);
    std::vector<Index> row_of(n, none);
    block_offsets_.assign(nb + 1, 0);
    colour_offsets_.assign(ncolours + 1, 0);
    std::size_t r = 0;
    for(std::size_t q = 0; q < nb; ++q) {
      const std::size_t b = blocks[q];
      for(std::size_t pos = b * B; pos < std::min(nf, (b + 1) * B); ++pos, ++r) {
        order_[r] = free_vertices[rcm[pos]];
        row_of[order_[r]] = Index(r);
      }
      block_offsets_[q + 1] = Index(r);
      ++colour_offsets_[colour[b] + 1];
    }
    for(std::size_t c = 0; c < ncolours; ++c)
      colour_offsets_[c + 1] += colour_offsets_[c];
    // pattern: free neighbours by row, constrained neighbours apart
    row_offsets_.assign(nf + 1, 0);
    bnd_offsets_.assign(nf + 1, 0);
    col_.clear();
    src_.clear();
    bnd_vertex_.clear();
    bnd_src_.clear();
    for(std::size_t r = 0; r < nf; ++r) {
      const Index i = order_[r];
      for(Index p = net.adjacency_offsets[i]; p < net.adjacency_offsets[i + 1]; ++p) {
        const Index j = net.adjacency[p];
        if(row_of[j] != none) {
          col_.push_back(row_of[j]);
          src_.push_back(p);
        } else {
          bnd_vertex_.push_back(j);
          bnd_src_.push_back(p);
        }
      }
      row_offsets_[r + 1] = Index(col_.size());
      bnd_offsets_[r + 1] = Index(bnd_vertex_.size());
    }
    val_.resize(col_.size());
    inv_diag_.resize(nf);
    diag_.resize(nf);
    b_.resize(nf);
    x_.resize(nf);
    built_ = true;
  }

  /// Takes this step's values from `sys` and the initial iterate from x (free
  /// entries: the start; constrained entries: the prescribed increments).
  void load(const Linear_system<D>& sys, const Field<D>& x, int threads)
  {
    const long nf = long(order_.size());
    const int nt = team(threads);
#pragma omp parallel for schedule(static) num_threads(nt)
    for(long r = 0; r < nf; ++r) {
      const std::size_t R = std::size_t(r);
      for(Index q = row_offsets_[R]; q < row_offsets_[R + 1]; ++q)
        val_[q] = sys.weight[src_[q]];
      Row s{};
      for(Index q = bnd_offsets_[R]; q < bnd_offsets_[R + 1]; ++q) {
        const double w = sys.weight[bnd_src_[q]];
        for(int c = 0; c < D; ++c)
          s[c] += w * x[bnd_vertex_[q]][c];
      }
      b_[R] = s;
      diag_[R] = sys.diagonal[order_[R]];
      inv_diag_[R] = 1.0 / diag_[R];
      x_[R] = x[order_[R]];
    }
  }

  /// Writes the solution into the free entries of x.
  void store(Field<D>& x) const
  {
    for(std::size_t r = 0; r < order_.size(); ++r)
      x[order_[r]] = x_[r];
  }

  /// One multicolour SOR sweep on the loaded system; returns the largest change.
  double sor_sweep(double omega, int threads) { return sweep(x_, b_, omega, threads, true); }

  /// Bytes one sweep must move at least: the pattern and values once, the
  /// right-hand side and inverse diagonal once, the solution read and written.
  double bytes_per_sweep() const
  {
    const double nf = double(order_.size()), nnz = double(col_.size());
    return nnz * (sizeof(Index) + sizeof(double)) +
           nf * (sizeof(Index) + sizeof(double) + D * sizeof(double) + 2.0 * D * sizeof(double));
  }

  /// Successive over-relaxation on the loaded system from the loaded start.
  Solve_report solve_sor(const Solver_options& options)
  {
    check_options(options);
    Solve_report report;
    Stopping_test stop(options);
    while(report.iterations < options.max_iterations) {
      stop.before_next();
      const double update = sor_sweep(options.relaxation_factor, options.threads);
      ++report.iterations;
      SPRING_MOTION_CHECK(std::isfinite(update), "the solver produced a non-finite value at sweep " << report.iterations);
      if(stop.done(update)) {
        report.converged = true;
        break;
      }
    }
    report.last_max_update = stop.last();
    report.error_estimate = stop.estimate();
    report.residual = scaled_residual(options.threads);
    SPRING_MOTION_CHECK(std::isfinite(report.residual), "the solver produced a non-finite value");
    return report;
  }

  /// Conjugate gradients preconditioned by a symmetric multicolour
  /// Gauss-Seidel sweep, from the loaded start.
  Solve_report solve_conjugate_gradient(const Solver_options& options)
  {
    check_options(options);
    const int threads = options.threads;
    const int nt = team(threads);
    Solve_report report;
    const long nf = long(order_.size());
    r_.resize(order_.size());
    z_.resize(order_.size());
    p_.resize(order_.size());
    q_.resize(order_.size());
    // r = b - A x
#pragma omp parallel for schedule(static) num_threads(nt)
    for(long k = 0; k < nf; ++k) {
      const Row y = apply(x_, std::size_t(k));
      for(int c = 0; c < D; ++c)
        r_[std::size_t(k)][c] = b_[std::size_t(k)][c] - y[c];
    }
    const double r_max = max_abs(r_, threads);
    SPRING_MOTION_CHECK(std::isfinite(r_max), "the solver's initial residual is not finite");
    Stopping_test stop(options, true);
    const bool mg = options.preconditioner == Preconditioner::multigrid;
    if(mg && r_max > 0 && nf > 0) {
      const Csr_view fine{order_.size(), row_offsets_.data(), col_.data(), val_.data(), diag_.data()};
      if(!multigrid_.built())
        multigrid_.build(fine);
      multigrid_.load(fine);
    }
    const auto precondition = [&] {
      this->precondition(options.preconditioner_relaxation_factor, threads, mg && multigrid_.number_of_levels() > 0);
    };
    if(r_max > 0 && nf > 0) {
      precondition();
      copy(z_, p_, threads);
      double rz = dot(r_, z_, threads);
      while(report.iterations < options.max_iterations) {
        stop.before_next();
#pragma omp parallel for schedule(static) num_threads(nt)
        for(long k = 0; k < nf; ++k) {
          const Row y = apply(p_, std::size_t(k));
          for(int c = 0; c < D; ++c)
            q_[std::size_t(k)][c] = y[c];
        }
        const double pq = dot(p_, q_, threads);
        if(!(pq > 0)) // p = 0: the residual vanished exactly
          break;
        const double alpha = rz / pq;
        const double update = axpy_max(alpha, threads);
        ++report.iterations;
        SPRING_MOTION_CHECK(std::isfinite(update), "the solver produced a non-finite value at iteration "
                                                       << report.iterations);
        if(stop.done(update)) {
          report.converged = true;
          break;
        }
        precondition();
        const double rz_new = dot(r_, z_, threads);
        const double beta = rz_new / rz;
        rz = rz_new;
#pragma omp parallel for schedule(static) num_threads(nt)
        for(long k = 0; k < nf; ++k)
          for(int c = 0; c < D; ++c)
            p_[std::size_t(k)][c] = z_[std::size_t(k)][c] + beta * p_[std::size_t(k)][c];
      }
    }
    report.residual = scaled_residual(threads);
    SPRING_MOTION_CHECK(std::isfinite(report.residual), "the solver produced a non-finite value");
    if(!report.converged && report.iterations < options.max_iterations) // a vanishing recurrence residual
      report.converged = residual_at_rounding_level(report.residual, max_abs(x_, threads)) || nf == 0 || r_max == 0;
    report.last_max_update = stop.last();
    report.error_estimate = report.converged && report.iterations == 0 ? 0 : stop.estimate();
    return report;
  }

private:
  static constexpr Index none = std::numeric_limits<Index>::max();

  int team(int threads) const { return thread_count(threads, order_.size()); }

  // (A x)_k = d_k x_k - sum_j w_kj x_j over free neighbours (constrained
  // neighbours are in b)
  Row apply(const std::vector<Row>& x, std::size_t k) const
  {
    Row s{};
    for(Index q = row_offsets_[k]; q < row_offsets_[k + 1]; ++q) {
      const double w = val_[q];
      const Row& xj = x[col_[q]];
      for(int c = 0; c < D; ++c)
        s[c] += w * xj[c];
    }
    Row y;
    for(int c = 0; c < D; ++c)
      y[c] = diag_[k] * x[k][c] - s[c];
    return y;
  }

  // Gauss-Seidel over the colours in order, rows in order within a block
  // (backward: all in reverse), the blocks of a colour in parallel: a block
  // reads only its own rows and rows of other colours, so any schedule gives
  // the same result. `track`: return the max change.
  double sweep(std::vector<Row>& x, const std::vector<Row>& rhs, double omega, int threads, bool forward,
               bool track = true)
  {
    const int nt = team(threads);
    const std::size_t nc = colours();
    double m = 0;
    for(std::size_t cc = 0; cc < nc; ++cc) {
      const std::size_t colour = forward ? cc : nc - 1 - cc;
      const long first = long(colour_offsets_[colour]), last = long(colour_offsets_[colour + 1]);
      double cm = 0;
#pragma omp parallel for schedule(static) num_threads(nt) reduction(max : cm)
      for(long bq = first; bq < last; ++bq) {
        const long rb = long(block_offsets_[std::size_t(bq)]), re = long(block_offsets_[std::size_t(bq) + 1]);
        for(long kk = 0; kk < re - rb; ++kk) {
          const std::size_t K = std::size_t(forward ? rb + kk : re - 1 - kk);
          Row s = rhs[K];
          for(Index q = row_offsets_[K]; q < row_offsets_[K + 1]; ++q) {
            const double w = val_[q];
            const Row& xj = x[col_[q]];
            for(int c = 0; c < D; ++c)
              s[c] += w * xj[c];
          }
          if(track)
            for(int c = 0; c < D; ++c) {
              const double nv = (1 - omega) * x[K][c] + omega * s[c] * inv_diag_[K];
              const double d = std::abs(nv - x[K][c]);
              // a NaN must stick: !(d <= cm) holds for NaN, which becomes +inf
              if(!(d <= cm))
                cm = std::isnan(d) ? std::numeric_limits<double>::infinity() : d;
              x[K][c] = nv;
            }
          else
            for(int c = 0; c < D; ++c)
              x[K][c] = omega == 1 ? s[c] * inv_diag_[K] : (1 - omega) * x[K][c] + omega * s[c] * inv_diag_[K];
        }
      }
      sticky_max(m, cm);
    }
    return m;
  }

  // z = M^{-1} r from z = 0: a forward sweep on A z = r, with `multigrid`
  // the coarse correction of the residual left, and a backward sweep. Without
  // it M is the symmetric Gauss-Seidel (SSOR for omega != 1) splitting of A in
  // the multicolour order; with it, one V-cycle. The same smoothing before
  // and after, and a symmetric coarse cycle, keep M symmetric positive
  // definite (omega in (0, 2)).
  void precondition(double omega, int threads, bool multigrid)
  {
    const int nt = team(threads);
    const long nf = long(order_.size());
#pragma omp parallel for schedule(static) num_threads(nt)
    for(long k = 0; k < nf; ++k)
      z_[std::size_t(k)] = Row{};
    sweep(z_, r_, omega, threads, true, false);
    if(multigrid)
      coarse_correction(threads);
    sweep(z_, r_, omega, threads, false, false);
  }

  // z += correction P cycle(P^T (r - A z))
  void coarse_correction(int threads)
  {
    const int nt = team(threads);
    const long nf = long(order_.size());
    s_.resize(order_.size());
#pragma omp parallel for schedule(static) num_threads(nt)
    for(long k = 0; k < nf; ++k) {
      const Row y = apply(z_, std::size_t(k));
      for(int c = 0; c < D; ++c)
        s_[std::size_t(k)][c] = r_[std::size_t(k)][c] - y[c];
    }
    multigrid_.restrict_from(s_);
    multigrid_.cycle();
    const double a = multigrid_.correction;
#pragma omp parallel for schedule(static) num_threads(nt)
    for(long k = 0; k < nf; ++k) {
      const Row& e = multigrid_.coarse_solution(multigrid_.parent(std::size_t(k)));
      for(int c = 0; c < D; ++c)
        z_[std::size_t(k)][c] += a * e[c];
    }
  }

  void copy(const std::vector<Row>& a, std::vector<Row>& b, int threads)
  {
    const int nt = team(threads);
    const long nf = long(a.size());
#pragma omp parallel for schedule(static) num_threads(nt)
    for(long k = 0; k < nf; ++k)
      b[std::size_t(k)] = a[std::size_t(k)];
  }

  // Fixed-chunk reductions: body(begin, end) reduces the rows [begin, end)
  // of one chunk, and the chunks' results are folded in chunk order, so the
  // result is the same for any thread count.
  template <class Body, class Combine>
  double chunked_reduce(Body&& body, Combine&& combine, int threads)
  {
    const std::size_t nf = order_.size();
    const long chunks = long((nf + reduction_chunk - 1) / reduction_chunk);
    partial_.assign(std::size_t(chunks), 0.0);
    const int nt = team(threads);
#pragma omp parallel for schedule(static) num_threads(nt)
    for(long ch = 0; ch < chunks; ++ch) {
      const std::size_t b = std::size_t(ch) * reduction_chunk;
      partial_[std::size_t(ch)] = body(b, std::min(nf, b + reduction_chunk));
    }
    double m = 0;
    for(double v : partial_)
      m = combine(m, v);
    return m;
  }

  static double sticky_combine(double a, double v)
  {
    sticky_max(a, v);
    return a;
  }

  // sum over rows of f(k)
  template <class F>
  double chunked_sum(F&& f, int threads)
  {
    return chunked_reduce(
        [&](std::size_t b, std::size_t e) {
          double s = 0;
          for(std::size_t k = b; k < e; ++k)
            s += f(k);
          return s;
        },
        [](double a, double v) { return a + v; }, threads);
  }

  // max over rows and components of f(k, c); a NaN wins (sticky_max)
  template <class F>
  double chunked_max(F&& f, int threads)
  {
    return chunked_reduce(
        [&](std::size_t b, std::size_t e) {
          double m = 0;
          for(std::size_t k = b; k < e; ++k)
            for(int c = 0; c < D; ++c)
              sticky_max(m, f(k, c));
          return m;
        },
        sticky_combine, threads);
  }

  double dot(const std::vector<Row>& a, const std::vector<Row>& b, int threads)
  {
    return chunked_sum(
        [&](std::size_t k) {
          double s = 0;
          for(int c = 0; c < D; ++c)
            s += a[k][c] * b[k][c];
          return s;
        },
        threads);
  }

  double max_abs(const std::vector<Row>& a, int threads)
  {
    return chunked_max([&](std::size_t k, int c) { return std::abs(a[k][c]); }, threads);
  }

  // x += alpha p, r -= alpha q; returns max |alpha p|
  double axpy_max(double alpha, int threads)
  {
    return chunked_max(
        [&](std::size_t k, int c) {
          const double d = alpha * p_[k][c];
          x_[k][c] += d;
          r_[k][c] -= alpha * q_[k][c];
          return std::abs(d);
        },
        threads);
  }

  // max over rows and components of |x_k - local solve_k|: d_k^{-1} |(b - A x)_k|
  double scaled_residual(int threads)
  {
    return chunked_reduce(
        [&](std::size_t b, std::size_t e) {
          double m = 0;
          for(std::size_t k = b; k < e; ++k) {
            const Row y = apply(x_, k);
            for(int c = 0; c < D; ++c)
              sticky_max(m, std::abs((b_[k][c] - y[c]) * inv_diag_[k]));
          }
          return m;
        },
        sticky_combine, threads);
  }

  bool built_ = false;
  std::vector<Index> order_, block_offsets_, colour_offsets_; // colour_offsets_: into the blocks
  std::vector<Index> row_offsets_, col_, src_;
  std::vector<Index> bnd_offsets_, bnd_vertex_, bnd_src_;
  std::vector<double> val_, diag_, inv_diag_, partial_;
  std::vector<Row> b_, x_, r_, z_, p_, q_, s_;
  Aggregation_multigrid<D> multigrid_;

public:
  /// The multigrid levels of the last multigrid-preconditioned solve.
  const Aggregation_multigrid<D>& multigrid() const { return multigrid_; }
  Aggregation_multigrid<D>& multigrid() { return multigrid_; }
};

/// Solves a scalar system through `fs` (built on first use for these free
/// vertices), block systems by the generic solvers.
template <int D>
Solve_report solve(const Spring_network<D>& net, const Linear_system<D>& sys, const std::vector<Index>& free_vertices,
                   Field<D>& x, const Solver_options& options, Free_system<D>& fs)
{
  if(sys.block || options.ordering == Vertex_ordering::natural)
    return solve(net, sys, free_vertices, x, options);
  if(!fs.built())
    fs.build(net, free_vertices, options.ordering == Vertex_ordering::multicolour ? 1 : 0);
  fs.load(sys, x, options.threads);
  const Solve_report r = options.method == Solver_method::sor ? fs.solve_sor(options)
                                                             : fs.solve_conjugate_gradient(options);
  fs.store(x);
  return r;
}

} // namespace internal
} // namespace spring_motion

#endif
