// Copyright (c) 2026 SpringMotion developers.
#ifndef SPRING_MOTION_INTERNAL_SOLVER_FREE_SYSTEM_H
#define SPRING_MOTION_INTERNAL_SOLVER_FREE_SYSTEM_H

#include <spring_motion/Error.h>
#include <spring_motion/Solver_options.h>
#include <spring_motion/Spring_network.h>
#include <spring_motion/internal/geometry/simplex_tables.h>
#include <spring_motion/internal/solver/aggregation_multigrid.h>
#include <spring_motion/internal/solver/aggregation_refresh.h>
#include <spring_motion/internal/solver/rigid_body_multigrid.h>
#include <spring_motion/internal/solver/block_ops.h>
#include <spring_motion/internal/solver/stopping_test.h>
#include <spring_motion/internal/solver/threads.h>

#include <boost/graph/adjacency_list.hpp>
#include <boost/graph/compressed_sparse_row_graph.hpp>
#include <boost/graph/cuthill_mckee_ordering.hpp>
#include <boost/graph/sequential_vertex_coloring.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <memory>
#include <numeric>
#include <utility>
#include <vector>

namespace spring_motion {
namespace internal {

/// Rows per chunk of every reduction: partial results are formed per fixed
/// chunk and added in chunk order, so sums do not depend on the thread count.
constexpr std::size_t reduction_chunk = 1024;
/// The smallest block of the block-multicolour ordering when its width is
/// the reverse Cuthill-McKee bandwidth (Solver_options::block_rows = 0).
constexpr std::size_t min_block_rows = 256;
/// Elements per chunk of the block assembly (Free_system::element_chunks).
constexpr std::size_t element_chunk = 512;

/// V-cycles on the block multigrid's first coarse level per preconditioner
/// application: Solver_options::multigrid_first_level_cycles, its 0 resolved
/// by the dimension (see there).
template <int D>
std::size_t first_level_cycles(const Solver_options& o)
{
  if(o.multigrid_first_level_cycles > 0)
    return o.multigrid_first_level_cycles;
  return D == 3 ? 3 : 1;
}

/// An allocator whose elements are default-initialised: a vector of
/// doubles resized with it leaves the new values unwritten (and fresh pages
/// untouched) instead of zeroing them.
template <class T>
struct Unwritten_allocator : std::allocator<T>
{
  template <class U>
  struct rebind
  {
    using other = Unwritten_allocator<U>;
  };
  Unwritten_allocator() = default;
  template <class U>
  Unwritten_allocator(const Unwritten_allocator<U>&) noexcept
  {
  }
  template <class U>
  void construct(U* p)
  {
    ::new(static_cast<void*>(p)) U;
  }
  template <class U, class... A>
  void construct(U* p, A&&... a)
  {
    ::new(static_cast<void*>(p)) U(std::forward<A>(a)...);
  }
};

/// The spring system of one step restricted to the free vertices: the only
/// home of a step's linear system, for scalar systems (edge models: one value
/// per nonzero, acting on the D components alike) and block systems (element
/// models: a D x D block per nonzero). Free vertices are numbered in the
/// solver's order: colour by colour (a greedy colouring of the free spring
/// graph, or of its blocks of consecutive reverse Cuthill-McKee rows, by
/// Boost's `sequential_vertex_coloring`) and in reverse Cuthill-McKee order
/// within a colour (Boost's `cuthill_mckee_ordering`) for locality; or in
/// network order (`Vertex_ordering::natural`, one block, one thread).
/// Gauss-Seidel then runs in parallel over the blocks of each colour, and
/// gives the same result for any thread count: a block reads only its own
/// rows and rows of other colours.
///
/// The ordering, the pattern and the multigrid aggregates are the solver
/// state: `build` makes them for a network, a free set, scalar or block, and
/// the options they depend on (`needs_build` says when they are stale); every
/// step then only refills the values (`load_scalar`, or the block assembler
/// of assemble.h) and the start (`set_start`). The aggregates are chosen on
/// the first multigrid solve, and again when solves slow down
/// (Aggregation_refresh).
template <int D>
class Free_system
{
public:
  using Row = std::array<double, D>;
  static constexpr int DD = D * D;
  static constexpr int UD = D * (D + 1) / 2; // a symmetric block's upper triangle
  static constexpr Index none = std::numeric_limits<Index>::max();

  bool built() const { return built_; }
  bool block() const { return block_; }
  std::size_t rows() const { return order_.size(); }
  std::size_t blocks() const { return block_offsets_.empty() ? 0 : block_offsets_.size() - 1; }
  std::size_t colours() const { return colour_offsets_.empty() ? 0 : colour_offsets_.size() - 1; }
  std::size_t nonzeros() const { return col_.size(); }
  /// row -> network vertex
  const std::vector<Index>& order() const { return order_; }
  const std::vector<Index>& row_offsets() const { return row_offsets_; }
  const std::vector<Index>& columns() const { return col_; }
  /// the network edge of each nonzero (free-free entry)
  const std::vector<Index>& nonzero_edges() const { return edge_; }
  /// constrained neighbours of each row: bnd_offsets()[r] .. [r + 1)
  const std::vector<Index>& bnd_offsets() const { return bnd_offsets_; }
  const std::vector<Index>& bnd_vertices() const { return bnd_vertex_; }
  const std::vector<Index>& bnd_edges() const { return bnd_edge_; }
  /// block systems: the elements (all), and for each of them
  /// (D+1)^2 destinations of its element matrix's blocks (a, b) in
  /// block_values() (in blocks of D*D), `none` for rows of constrained vertices.
  /// The elements come in chunks of neighbours (runs of the network's spatial
  /// order), chunk c being elements [element_chunks()[c], [c + 1)); the
  /// chunks are grouped by colour, colour k being chunks
  /// [element_colours()[k], [k + 1)). No two chunks of a colour share a free
  /// vertex, so a colour's chunks can be added in parallel, each serially,
  /// and every block receives its contributions in the same order for any
  /// thread count.
  const std::vector<Index>& assembled_elements() const { return elements_; }
  /// the vertices of assembled_elements(), in that order: read in sequence,
  /// where the network's element list would be read at random
  const std::vector<std::array<Index, D + 1>>& assembled_element_vertices() const { return element_vertices_; }
  const std::vector<Index>& element_destinations() const { return element_dest_; }
  const std::vector<Index>& element_chunks() const { return element_chunk_offsets_; }
  const std::vector<Index>& element_colours() const { return element_colour_offsets_; }
  /// block systems: diagonal blocks (rows), then the off-diagonal blocks
  /// (nonzeros), then the blocks coupling rows to constrained vertices
  double* block_values() { return blocks_.data(); }
  std::size_t off_block(Index q) const { return order_.size() + q; }
  std::size_t bnd_block(Index q) const { return order_.size() + col_.size() + q; }

  /// Matrix entries in the public layout (Step_system_view): scalar: one
  /// value per nonzero and per row; block: D*D each, row-major (after a load
  /// of upper triangles, the whole blocks are written out from them here,
  /// once per load).
  const double* values() const
  {
    if(!block_)
      return val_.data();
    if(off_upper_ && !off_whole_)
      write_whole_off_blocks();
    return blocks_.data() + order_.size() * DD;
  }
  /// Block systems: the off-diagonal blocks' upper triangles (D(D+1)/2
  /// values each, by rows), which a load of symmetric blocks writes instead
  /// of the whole blocks (set_upper_load).
  double* upper_values() { return upper_off_.data(); }
  /// Whether the coming load writes every off-diagonal block as its upper
  /// triangle only, in upper_values() (the blocks are all symmetric: element
  /// models with symmetric blocks and edge springs, no projected rows); the
  /// diagonal blocks and those coupling rows to constrained vertices stay
  /// whole in block_values(). The solver then reads the upper triangles, as
  /// it reads its own copy of them after a load of whole symmetric blocks
  /// (prepare_block_copies): a third fewer values written and cleared in 3D
  /// and no copy to make. Kept until the next call.
  void set_upper_load(bool upper)
  {
    off_upper_ = upper && block_;
    off_whole_ = false;
    if(off_upper_)
      upper_off_.resize(col_.size() * UD);
  }
  bool upper_load() const { return off_upper_; }
  /// whether some rows are projected (set_projectors)
  bool has_projectors() const { return !projector_of_row_.empty(); }
  /// Whether the last block preconditioner read single-precision copies of
  /// the off-diagonal blocks' upper triangles (all of them were symmetric
  /// and fit a float).
  bool smoother_read_upper_triangles() const { return single_fits_ && product_upper_; }
  /// Whether the last block solve's matrix products read the off-diagonal
  /// blocks' upper triangles (in double precision; all of them were
  /// symmetric).
  bool product_read_upper_triangles() const { return product_upper_; }
  const double* diagonal() const { return block_ ? blocks_.data() : diag_.data(); }
  const std::vector<Row>& rhs() const { return b_; }
  const std::vector<Row>& solution() const { return x_; }

  /// Whether the state must be built (again) for these free vertices, this
  /// kind of system and these options.
  bool needs_build(const Spring_network<D>& net, const std::vector<Index>& free_vertices, bool block,
                   const Solver_options& o) const
  {
    return !built_ || block != block_ || o.ordering != ordering_ || o.block_rows != block_rows_ ||
           o.preconditioner != preconditioner_ || o.multigrid_strength != multigrid_.parameters.strength ||
           o.multigrid_coarsest_rows != multigrid_.parameters.coarsest_rows ||
           o.multigrid_max_direct_rows != multigrid_.parameters.max_direct_rows ||
           net.adjacency.size() != network_entries_ || net.number_of_elements() != network_elements_ ||
           free_vertices != free_;
  }

  /// Builds the ordering and the pattern (and, for block systems, the
  /// element matrices' destinations); the multigrid aggregates follow on the
  /// first multigrid solve, from its system.
  void build(const Spring_network<D>& net, const std::vector<Index>& free_vertices, bool block,
             const Solver_options& o)
  {
    block_ = block;
    ordering_ = o.ordering;
    block_rows_ = o.block_rows;
    preconditioner_ = o.preconditioner;
    network_entries_ = net.adjacency.size();
    network_elements_ = net.number_of_elements();
    free_ = free_vertices;
    multigrid_ = Aggregation_multigrid<D>();
    multigrid_.parameters = {o.multigrid_strength, o.multigrid_correction, o.multigrid_coarsest_rows,
                             o.multigrid_max_direct_rows};
    rigid_ = Rigid_body_multigrid<D>();
    rigid_.parameters = multigrid_.parameters;
    refresh_ = Aggregation_refresh();
    kept_solves_ = 0;
    const std::size_t n = net.number_of_vertices();
    const std::size_t nf = free_vertices.size();
    std::vector<Index> row_of(n, none);
    if(o.ordering == Vertex_ordering::natural)
      natural_order(free_vertices);
    else
      coloured_order(net, free_vertices, o.ordering == Vertex_ordering::multicolour ? 1 : o.block_rows);
    for(std::size_t r = 0; r < nf; ++r)
      row_of[order_[r]] = Index(r);
    // pattern: free neighbours by row, constrained neighbours apart
    row_offsets_.assign(nf + 1, 0);
    bnd_offsets_.assign(nf + 1, 0);
    col_.clear();
    edge_.clear();
    bnd_vertex_.clear();
    bnd_edge_.clear();
    // Each row's free neighbours before it in the solver's order first, then
    // those after it (upper_offsets_), each part in network order: a forward
    // sweep from zero reads only the first part, and the residual it leaves
    // only the second (precondition).
    upper_offsets_.assign(nf, 0);
    std::vector<std::pair<Index, Index>> later;
    for(std::size_t r = 0; r < nf; ++r) {
      const Index i = order_[r];
      later.clear();
      for(Index p = net.adjacency_offsets[i]; p < net.adjacency_offsets[i + 1]; ++p) {
        const Index j = net.adjacency[p];
        if(row_of[j] == none) {
          bnd_vertex_.push_back(j);
          bnd_edge_.push_back(net.adjacency_edge[p]);
        } else if(row_of[j] < r) {
          col_.push_back(row_of[j]);
          edge_.push_back(net.adjacency_edge[p]);
        } else {
          later.emplace_back(row_of[j], net.adjacency_edge[p]);
        }
      }
      upper_offsets_[r] = Index(col_.size());
      for(const auto& [c, e] : later) {
        col_.push_back(c);
        edge_.push_back(e);
      }
      row_offsets_[r + 1] = Index(col_.size());
      bnd_offsets_[r + 1] = Index(bnd_vertex_.size());
    }
    // kept for the whole run: no spare capacity
    for(auto* v : {&col_, &edge_, &bnd_vertex_, &bnd_edge_})
      v->shrink_to_fit();
    elements_.clear();
    element_dest_.clear();
    element_vertices_.clear();
    element_chunk_offsets_.clear();
    element_colour_offsets_.clear();
    val_.clear();
    bnd_val_.clear();
    diag_.clear();
    inv_diag_.clear();
    blocks_.clear();
    if(block)
      element_destinations(net, row_of);
    const std::size_t w = block ? DD : 1;
    if(block) {
      // not zeroed: every load writes every block it reads (see blocks_)
      blocks_.resize((nf + col_.size() + bnd_vertex_.size()) * w);
    } else {
      val_.resize(col_.size());
      bnd_val_.resize(bnd_vertex_.size());
      diag_.resize(nf);
    }
    inv_diag_.resize(nf * w);
    b_.resize(nf);
    x_.resize(nf);
    projector_of_row_.clear();
    projectors_.clear();
    built_ = true;
  }

  /// Block systems: restricts the increment of the vertices listed to the
  /// range of their symmetric projectors P (row-major D x D; sliding
  /// vertices, P = I - n n^T per plane). The loaded system becomes
  /// P A P + s (I - P) on those rows and columns, right-hand side P b, which
  /// stays symmetric positive definite and whose solution has no component
  /// outside the range (s, the diagonal block's mean eigenvalue, keeps the
  /// removed directions at the scale of the rest of the spectrum). Kept
  /// until the next build.
  void set_projectors(const std::vector<Index>& vertices, const std::vector<std::array<double, DD>>& projectors)
  {
    SPRING_MOTION_CHECK(block_ || vertices.empty(), "projected rows need a block system");
    std::vector<Index> row_of(free_.empty() ? 0 : *std::max_element(order_.begin(), order_.end()) + 1, none);
    for(std::size_t r = 0; r < order_.size(); ++r)
      row_of[order_[r]] = Index(r);
    projector_of_row_.assign(vertices.empty() ? 0 : order_.size(), none);
    projectors_.clear();
    for(std::size_t k = 0; k < vertices.size(); ++k) {
      const Index v = vertices[k];
      SPRING_MOTION_CHECK(v < row_of.size() && row_of[v] != none, "projected vertex " << v << " is not free");
      projector_of_row_[row_of[v]] = Index(projectors_.size());
      projectors_.push_back(projectors[k]);
    }
  }

  /// Applies the projectors to the loaded block values (before the diagonal
  /// blocks are inverted). Each row changes only its own blocks.
  void apply_projectors(int threads)
  {
    if(projector_of_row_.empty())
      return;
    const auto proj = [&](Index row) {
      const Index p = projector_of_row_[row];
      return p == none ? nullptr : projectors_[p].data();
    };
    // B <- P B (left) or B <- B P (right), P symmetric
    const auto left = [](const double* P, double* B) {
      std::array<double, DD> t{};
      for(int r = 0; r < D; ++r)
        for(int c = 0; c < D; ++c)
          for(int k = 0; k < D; ++k)
            t[r * D + c] += P[r * D + k] * B[k * D + c];
      std::copy(t.begin(), t.end(), B);
    };
    const auto right = [](double* B, const double* P) {
      std::array<double, DD> t{};
      for(int r = 0; r < D; ++r)
        for(int c = 0; c < D; ++c)
          for(int k = 0; k < D; ++k)
            t[r * D + c] += B[r * D + k] * P[k * D + c];
      std::copy(t.begin(), t.end(), B);
    };
    const long nf = long(order_.size());
    in_team(team(threads), [&] {
#pragma omp for schedule(static)
      for(long r = 0; r < nf; ++r) {
        const std::size_t R = std::size_t(r);
        const double* P = proj(Index(R));
        for(Index q = row_offsets_[R]; q < row_offsets_[R + 1]; ++q) {
          const double* Q = proj(col_[q]);
          if(P)
            left(P, &blocks_[off_block(q) * DD]);
          if(Q)
            right(&blocks_[off_block(q) * DD], Q);
        }
        if(!P)
          continue;
        for(Index q = bnd_offsets_[R]; q < bnd_offsets_[R + 1]; ++q)
          left(P, &blocks_[bnd_block(q) * DD]);
        double* d = &blocks_[R * DD];
        double trace = 0;
        for(int c = 0; c < D; ++c)
          trace += d[c * D + c];
        left(P, d);
        right(d, P);
        for(int i = 0; i < DD; ++i)
          d[i] += (trace / D) * ((i / D == i % D ? 1.0 : 0.0) - P[i]);
      }
    });
  }

  /// This step's values of a scalar system from the edge stiffness k (one
  /// value per network edge): read straight into solver order.
  void load_scalar(const Spring_network<D>& net, const std::vector<double>& k, int threads)
  {
    const long nf = long(order_.size());
    long bad = nf;
    in_team(team(threads), [&] {
#pragma omp for schedule(static) reduction(min : bad)
      for(long r = 0; r < nf; ++r) {
        const std::size_t R = std::size_t(r);
        // The rows visit their vertices' springs in the network's order: a
        // cache miss for the vertex's offsets and one for its springs per row
        // on a large mesh (the rows are in the solver's order), most of this
        // loop on the wing. Both are fetched ahead, the offsets twice as far.
        // (Written here: GCC 12 dropped these prefetches, at -O1 and above,
        // when they stood alone in a member function called from here.)
        if(r + 2 * prefetch_rows < nf)
          __builtin_prefetch(&net.adjacency_offsets[order_[std::size_t(r + 2 * prefetch_rows)]]);
        if(r + prefetch_rows < nf) {
          const Index v = order_[std::size_t(r + prefetch_rows)];
          const Index b = net.adjacency_offsets[v], e = net.adjacency_offsets[v + 1];
          if(b < e) {
            __builtin_prefetch(&net.adjacency_edge[b]);
            __builtin_prefetch(&net.adjacency_edge[e - 1]);
          }
        }
        for(Index q = row_offsets_[R]; q < row_offsets_[R + 1]; ++q)
          val_[q] = -k[edge_[q]];
        for(Index q = bnd_offsets_[R]; q < bnd_offsets_[R + 1]; ++q)
          bnd_val_[q] = -k[bnd_edge_[q]];
        // summed in network order, as the vertex's springs are listed
        const Index i = order_[R];
        double d = 0;
        for(Index p = net.adjacency_offsets[i]; p < net.adjacency_offsets[i + 1]; ++p)
          d += k[net.adjacency_edge[p]];
        diag_[R] = d;
        inv_diag_[R] = 1.0 / d;
        if(!(d > 0 && std::isfinite(d)) && r < bad)
          bad = r;
      }
    });
    if(bad < nf)
      SPRING_MOTION_VERTEX_CHECK(false, order_[std::size_t(bad)],
                                 "free vertex " << order_[std::size_t(bad)] << " has zero total stiffness ("
                                                << diag_[std::size_t(bad)]
                                                << "): the model gave k = 0 on all its edges");
  }

  // elements ahead whose edges element_destinations requests
  static constexpr std::size_t destination_prefetch = 8;

  // rows ahead that load_scalar prefetches its vertex's springs
  static constexpr long prefetch_rows = 8;

  /// Inverts the diagonal blocks of a block system once its values are in;
  /// a singular or non-finite block throws Vertex_error naming its vertex.
  void finish_block_load(int threads)
  {
    single_fits_ = false;         // the copies of the old values are stale
    product_upper_ = off_upper_; // unless the load wrote the upper triangles themselves
    const long nf = long(order_.size());
    long bad = nf;
    in_team(team(threads), [&] {
#pragma omp for schedule(static) reduction(min : bad)
      for(long r = 0; r < nf; ++r)
        if(!invert_block<D>(&blocks_[std::size_t(r) * DD], &inv_diag_[std::size_t(r) * DD]) && r < bad)
          bad = r;
    });
    if(bad < nf) {
      const double* m = &blocks_[std::size_t(bad) * DD];
      std::ostringstream block;
      for(int k = 0; k < DD; ++k)
        block << (k ? (k % D ? ", " : "; ") : "") << m[k];
      SPRING_MOTION_VERTEX_CHECK(false, order_[std::size_t(bad)],
                                 "free vertex " << order_[std::size_t(bad)]
                                                << " has a singular or non-finite diagonal stiffness block ["
                                                << block.str() << "]");
    }
  }

  /// The start: the iterate at free vertices and the right-hand side from
  /// the prescribed increments at constrained ones, both read from x (one
  /// entry per network vertex).
  void set_start(const std::vector<Row>& x, int threads)
  {
    const long nf = long(order_.size());
    in_team(team(threads), [&] {
#pragma omp for schedule(static)
      for(long r = 0; r < nf; ++r) {
        const std::size_t R = std::size_t(r);
        Row s{};
        if(block_)
          for(Index q = bnd_offsets_[R]; q < bnd_offsets_[R + 1]; ++q)
            subtract_block_product<D>(s, &blocks_[bnd_block(q) * DD], x[bnd_vertex_[q]]);
        else
          for(Index q = bnd_offsets_[R]; q < bnd_offsets_[R + 1]; ++q)
            for(int c = 0; c < D; ++c)
              s[c] -= bnd_val_[q] * x[bnd_vertex_[q]][c];
        b_[R] = s;
        x_[R] = x[order_[R]];
        if(!projector_of_row_.empty() && projector_of_row_[R] != none)
          x_[R] = block_product<D>(projectors_[projector_of_row_[R]].data(), x_[R]);
      }
    });
  }

  /// Replaces the iterate by a solution computed elsewhere (one entry per
  /// row, in the solver's order): Network_deformer::solve_override.
  void set_solution(const std::vector<Row>& x)
  {
    SPRING_MOTION_CHECK(x.size() == x_.size(), "an outside solve returned " << x.size() << " rows for "
                                                                             << x_.size());
    x_ = x;
  }

  /// Writes the solution into the free entries of x.
  void store(std::vector<Row>& x, int threads = 1) const
  {
    const long nf = long(order_.size());
    in_team(team(threads), [&] {
#pragma omp for schedule(static)
      for(long r = 0; r < nf; ++r)
        x[order_[std::size_t(r)]] = x_[std::size_t(r)];
    });
  }

  /// One SOR sweep in the solver's order on the loaded system; returns the
  /// largest change.
  double sor_sweep(double omega, int threads)
  {
    return block_ ? loaded_sweep<true>(omega, threads) : loaded_sweep<false>(omega, threads);
  }

  /// Bytes one scalar sweep must move at least: the pattern and values once,
  /// the right-hand side and inverse diagonal once, the solution read and
  /// written.
  double bytes_per_sweep() const
  {
    const double nf = double(order_.size()), nnz = double(col_.size()), w = block_ ? DD : 1;
    return nnz * (sizeof(Index) + w * sizeof(double)) +
           nf * (sizeof(Index) + w * sizeof(double) + D * sizeof(double) + 2.0 * D * sizeof(double));
  }

  /// Solves the loaded system from the loaded start with the method the
  /// options select.
  Solve_report solve(const Solver_options& options)
  {
    check_options(options);
    if(options.method == Solver_method::sor)
      return block_ ? solve_sor<true>(options) : solve_sor<false>(options);
    return block_ ? solve_conjugate_gradient<true>(options) : solve_conjugate_gradient<false>(options);
  }

  /// M^{-1} r for the loaded system (rows in the solver's order), M the
  /// preconditioner of a conjugate-gradient solve under `options`: for
  /// checking it against its definition.
  std::vector<Row> preconditioned(const std::vector<Row>& r, const Solver_options& options)
  {
    SPRING_MOTION_CHECK(r.size() == order_.size(), "preconditioned: " << r.size() << " rows for " << order_.size());
    if(r.empty()) // no free vertex: nothing to load
      return {};
    r_ = r;
    z_.resize(r.size());
    if(block_) {
      prepare_block_copies(options.threads);
      apply_preconditioner<true>(load_preconditioner<true>(options, false), options);
    } else
      apply_preconditioner<false>(load_preconditioner<false>(options, false), options);
    return z_;
  }

  /// The multigrid levels of the last multigrid-preconditioned solve: of a
  /// scalar system, and of a block system.
  const Aggregation_multigrid<D>& multigrid() const { return multigrid_; }
  const Rigid_body_multigrid<D>& rigid_body_multigrid() const { return rigid_; }

  /// The positions of the network's vertices, whose rigid motions a block
  /// system's multigrid builds its coarse levels from; read at the solves
  /// that compute those levels, so they must outlive the solver's use.
  void set_positions(const std::vector<Row>& positions) { positions_ = &positions; }

private:
  int team(int threads) const { return thread_count(threads, order_.size()); }

  void natural_order(const std::vector<Index>& free_vertices)
  {
    order_ = free_vertices;
    block_offsets_ = {0, Index(order_.size())};
    colour_offsets_ = {0, 1};
  }

  void coloured_order(const Spring_network<D>& net, const std::vector<Index>& free_vertices,
                      std::size_t block_rows)
  {
    const std::size_t n = net.number_of_vertices();
    const std::size_t nf = free_vertices.size();
    std::vector<Index> compact(n, none);
    for(std::size_t k = 0; k < nf; ++k)
      compact[free_vertices[k]] = Index(k);
    // reverse Cuthill-McKee: rcm[r] is the compact index at position r. The
    // free graph in compressed rows, each edge in both directions, each
    // vertex's neighbours in increasing order (the order an adjacency_list
    // built edge by edge visits them, so the ordering is the same), at a
    // fifth of an adjacency_list's memory: this was the run's peak.
    std::vector<std::size_t> rcm(nf);
    {
      std::vector<std::pair<Index, Index>> arcs;
      for(std::size_t k = 0; k < nf; ++k) {
        const Index i = free_vertices[k];
        for(Index p = net.adjacency_offsets[i]; p < net.adjacency_offsets[i + 1]; ++p)
          if(compact[net.adjacency[p]] != none)
            arcs.emplace_back(Index(k), compact[net.adjacency[p]]);
      }
      using Free_graph = boost::compressed_sparse_row_graph<boost::directedS, boost::no_property, boost::no_property,
                                                            boost::no_property, Index, Index>;
      const Free_graph g(boost::edges_are_sorted, arcs.begin(), arcs.end(), nf);
      std::vector<std::pair<Index, Index>>().swap(arcs);
      if(nf > 0)
        boost::cuthill_mckee_ordering(g, rcm.rbegin());
    }
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
    using Graph = boost::adjacency_list<boost::vecS, boost::vecS, boost::undirectedS>;
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
    block_offsets_.assign(nb + 1, 0);
    colour_offsets_.assign(ncolours + 1, 0);
    std::size_t r = 0;
    for(std::size_t q = 0; q < nb; ++q) {
      const std::size_t b = blocks[q];
      for(std::size_t pos = b * B; pos < std::min(nf, (b + 1) * B); ++pos, ++r)
        order_[r] = free_vertices[rcm[pos]];
      block_offsets_[q + 1] = Index(r);
      ++colour_offsets_[colour[b] + 1];
    }
    for(std::size_t c = 0; c < ncolours; ++c)
      colour_offsets_[c + 1] += colour_offsets_[c];
  }

  // The elements in chunks (see element_chunks) and, for every element,
  // where each of its (D+1)^2 blocks goes: a diagonal block, an off-diagonal
  // one, a coupling to a constrained vertex, or nowhere (a constrained
  // vertex's row).
  //
  // Chunks of `element_chunk` consecutive elements of the spatial order,
  // coloured greedily in that order: each chunk takes the first colour that
  // no chunk at its free vertices has taken. Colouring single elements made
  // each colour a sample of the whole mesh, so that every colour's pass went
  // through all the blocks again (dozens of passes on a tetrahedral mesh); a
  // chunk's elements are neighbours, and their blocks stay in cache while the
  // chunk adds to them.
  void element_destinations(const Spring_network<D>& net, const std::vector<Index>& row_of)
  {
    const std::vector<Index> spatial = spatial_element_order(net);
    const std::size_t ne = spatial.size(), nc = (ne + element_chunk - 1) / element_chunk;
    std::vector<std::vector<Index>> taken(order_.size()); // per free row: colours of its chunks
    std::vector<Index> colour(nc), seen;                  // seen[k] == c + 1: k is forbidden for chunk c
    for(std::size_t c = 0; c < nc; ++c) {
      const std::size_t begin = c * element_chunk, end = std::min(ne, begin + element_chunk);
      for(std::size_t s = begin; s < end; ++s)
        for(Index v : net.elements[spatial[s]])
          if(row_of[v] != none)
            for(Index k : taken[row_of[v]]) {
              if(k >= seen.size())
                seen.resize(std::size_t(k) + 1, 0);
              seen[k] = Index(c + 1);
            }
      Index k = 0;
      while(k < seen.size() && seen[k] == Index(c + 1))
        ++k;
      colour[c] = k;
      for(std::size_t s = begin; s < end; ++s)
        for(Index v : net.elements[spatial[s]])
          if(row_of[v] != none && (taken[row_of[v]].empty() || taken[row_of[v]].back() != k))
            taken[row_of[v]].push_back(k);
    }
    std::vector<std::vector<Index>>().swap(taken);
    const Index colours = colour.empty() ? 0 : *std::max_element(colour.begin(), colour.end()) + 1;
    element_colour_offsets_.assign(std::size_t(colours) + 1, 0);
    for(Index k : colour)
      ++element_colour_offsets_[std::size_t(k) + 1];
    std::partial_sum(element_colour_offsets_.begin(), element_colour_offsets_.end(), element_colour_offsets_.begin());
    // chunks colour by colour, in the spatial order within a colour
    std::vector<Index> chunks(nc);
    std::iota(chunks.begin(), chunks.end(), Index(0));
    std::stable_sort(chunks.begin(), chunks.end(), [&](Index a, Index b) { return colour[a] < colour[b]; });
    elements_.clear();
    elements_.reserve(ne);
    element_chunk_offsets_.assign(1, 0);
    for(const Index c : chunks) {
      const std::size_t begin = std::size_t(c) * element_chunk, end = std::min(ne, begin + element_chunk);
      elements_.insert(elements_.end(), spatial.begin() + long(begin), spatial.begin() + long(end));
      element_chunk_offsets_.push_back(Index(elements_.size()));
    }
    element_vertices_.resize(ne);
    for(std::size_t s = 0; s < ne; ++s)
      element_vertices_[s] = net.elements[elements_[s]];
    // Each network edge's block in the row of its first vertex and in the
    // row of its second (edges[e][0] < edges[e][1]): an off-diagonal block,
    // a coupling to a constrained vertex, or none (that vertex has no row).
    // An element then finds its blocks through its edges; searching its
    // rows' columns instead, with the rows of its vertices in distant parts
    // of the pattern, took a fifth of a one-step wing run (perf).
    std::vector<std::array<Index, 2>> edge_block(net.number_of_edges(), {none, none});
    for(std::size_t r = 0; r < order_.size(); ++r) {
      const Index i = order_[r];
      const auto side = [&](Index e) { return std::size_t(net.edges[e][0] == i ? 0 : 1); };
      for(Index q = row_offsets_[r]; q < row_offsets_[r + 1]; ++q)
        edge_block[edge_[q]][side(edge_[q])] = Index(off_block(q));
      for(Index q = bnd_offsets_[r]; q < bnd_offsets_[r + 1]; ++q)
        edge_block[bnd_edge_[q]][side(bnd_edge_[q])] = Index(bnd_block(q));
    }
    using Tables = Simplex_tables<D>;
    constexpr auto local_edge = local_edges<D>();
    element_dest_.resize(ne * (D + 1) * (D + 1));
    Index* to = element_dest_.data();
    for(std::size_t s = 0; s < ne; ++s) {
      // every element, those with no free vertex too: their matrices go
      // nowhere, but computing them checks the model everywhere, every step.
      // The vertices from their copy in this order; the edges of an element
      // a few places ahead requested (in network order they lie far apart).
#if defined(__GNUC__)
      if(s + destination_prefetch < ne)
        __builtin_prefetch(&net.element_edges[std::size_t(elements_[s + destination_prefetch]) * Tables::edges]);
#endif
      const Index t = elements_[s];
      const auto& el = element_vertices_[s];
      std::array<Index, D + 1> row;
      for(int a = 0; a <= D; ++a)
        row[std::size_t(a)] = row_of[el[std::size_t(a)]];
      for(int a = 0; a <= D; ++a)
        for(int b = 0; b <= D; ++b, ++to) {
          const Index r = row[std::size_t(a)];
          if(r == none)
            *to = none;
          else if(a == b)
            *to = r;
          else {
            const Index e = net.edge_of(t, local_edge[std::size_t(a)][std::size_t(b)]);
            *to = edge_block[e][el[std::size_t(a)] < el[std::size_t(b)] ? 0 : 1];
            SPRING_MOTION_CHECK(*to != none, "element " << t << ": an edge is missing from the network");
          }
        }
    }
    SPRING_MOTION_CHECK((order_.size() + col_.size() + bnd_vertex_.size()) < std::size_t(none),
                        "too many stiffness blocks for 32-bit indices");
  }

  // s = rhs - sum over the off-diagonal entries [begin, end) of A_kj x_j
  // (a part of row k), the entries read from `off` (values(), or their
  // single-precision copy, Upper: of the upper triangles). The sweeps and
  // the restriction's residual both sum here (written inline in the
  // restriction, GCC 12 kept the 2D sum on the stack, a store and a load per
  // entry; the solve took no less time without them: docs/performance.md).
  template <bool B, class V, bool Upper = false>
  Row off_residual(const std::vector<Row>& x, const Row& rhs, Index begin, Index end, const V* off) const
  {
    Row s = rhs;
    // 2D rows keep a loop of their own: through symmetric_row_products (its
    // scalar form in 2D, the same bits) GCC 12 compiled the 2D sweep with
    // other registers and the 2D ball-vertex solve took about 1.03 times as
    // long (alternated runs); the product below likewise
    if constexpr(B && Upper && D == 3) {
      symmetric_row_products<Row_products::subtract, D>(s, off, col_.data(), begin, end, x.data());
    } else if constexpr(B && Upper) {
      for(Index q = begin; q < end; ++q)
        subtract_symmetric_block_product<D>(s, off + std::size_t(q) * UD, x[col_[q]]);
    } else if constexpr(B) {
      for(Index q = begin; q < end; ++q)
        subtract_block_product<D>(s, off + std::size_t(q) * DD, x[col_[q]]);
    } else {
      for(Index q = begin; q < end; ++q) {
        const double v = double(off[q]);
        const Row& xj = x[col_[q]];
        for(int c = 0; c < D; ++c)
          s[c] -= v * xj[c];
      }
    }
    return s;
  }

  // (A x)_k over the free vertices (constrained neighbours are in b)
  template <bool B>
  Row apply(const std::vector<Row>& x, std::size_t k) const
  {
    if constexpr(B) {
      Row y = block_product<D>(&blocks_[k * DD], x[k]);
      auto add = [&](const Row& t) {
        for(int c = 0; c < D; ++c)
          y[c] += t[c];
      };
      if(product_upper_ && D == 3)
        symmetric_row_products<Row_products::add, D>(y, upper_off_.data(), col_.data(), row_offsets_[k],
                                                     row_offsets_[k + 1], x.data());
      else if(product_upper_)
        for(Index q = row_offsets_[k]; q < row_offsets_[k + 1]; ++q)
          add(symmetric_block_product<D>(&upper_off_[std::size_t(q) * UD], x[col_[q]]));
      else
        for(Index q = row_offsets_[k]; q < row_offsets_[k + 1]; ++q)
          add(block_product<D>(&blocks_[off_block(q) * DD], x[col_[q]]));
      return y;
    } else {
      Row s{};
      for(Index q = row_offsets_[k]; q < row_offsets_[k + 1]; ++q) {
        const double v = val_[q];
        const Row& xj = x[col_[q]];
        for(int c = 0; c < D; ++c)
          s[c] += v * xj[c];
      }
      Row y;
      for(int c = 0; c < D; ++c)
        y[c] = diag_[k] * x[k][c] + s[c];
      return y;
    }
  }

  // A backward sweep reads the rows from the last to the first but each
  // row's entries upwards, a pattern the hardware prefetcher does not follow:
  // a 3D block system's backward sweep took three times its forward one.
  // The values of the row this many rows ahead are requested explicitly
  // (no arithmetic changes).
  static constexpr std::size_t backward_prefetch_rows = 8;

  template <bool B, bool Upper, class V>
  void prefetch_row(const V* off, std::size_t k) const
  {
    constexpr std::size_t w = B ? (Upper ? UD : DD) : 1;
    prefetch_range(off + std::size_t(row_offsets_[k]) * w, off + std::size_t(row_offsets_[k + 1]) * w);
  }

  // Gauss-Seidel over the colours in order, rows in order within a block
  // (backward: all in reverse), the blocks of a colour in parallel: a block
  // reads only its own rows and rows of other colours, so any schedule gives
  // the same result. `off`: the off-diagonal entries (see off_residual).
  // `track`: return the max change. `from_zero` (forward only): the sweep
  // starts from x = 0 without x being zeroed: a row reads only the rows
  // before it in sweep order (those after it would still be zero), which
  // this sweep has written, and its own old value is taken as 0; every row
  // is written. That spares a pass over x and a parallel region in every
  // preconditioner application.
  template <bool B, class V, bool Upper = false>
  double sweep(std::vector<Row>& x, const std::vector<Row>& rhs, const V* off, double omega, int threads,
               bool forward, bool track = true, bool from_zero = false)
  {
    const int nt = team(threads);
    const std::size_t nc = colours();
    double m = 0;
    for(std::size_t cc = 0; cc < nc; ++cc) {
      const std::size_t colour = forward ? cc : nc - 1 - cc;
      double cm = 0;
      in_team(nt, [&] { sweep_colour<B, V, Upper>(x, rhs, off, omega, colour, forward, track, from_zero, cm); });
      sticky_max(m, cm);
    }
    return m;
  }

  // One colour of `sweep`, its blocks shared out by the team that calls it
  // (an orphaned loop); cm (shared by the team) raised to the largest
  // change when `track`. Its own function, the parameters by value: in a
  // lambda capturing them by reference, GCC read omega and the flags again
  // after every store to x.
  template <bool B, class V, bool Upper>
  void sweep_colour(std::vector<Row>& x, const std::vector<Row>& rhs, const V* off, double omega, std::size_t colour,
                    bool forward, bool track, bool from_zero, double& cm)
  {
    const long first = long(colour_offsets_[colour]), last = long(colour_offsets_[colour + 1]);
#pragma omp for schedule(static) reduction(max : cm)
    for(long bq = first; bq < last; ++bq) {
      const long rb = long(block_offsets_[std::size_t(bq)]), re = long(block_offsets_[std::size_t(bq) + 1]);
      for(long kk = 0; kk < re - rb; ++kk) {
        const std::size_t K = std::size_t(forward ? rb + kk : re - 1 - kk);
        if(!forward && K >= backward_prefetch_rows)
          prefetch_row<B, Upper>(off, K - backward_prefetch_rows);
        const Index row_end = from_zero ? upper_offsets_[K] : row_offsets_[K + 1];
        const Row s = off_residual<B, V, Upper>(x, rhs[K], row_offsets_[K], row_end, off);
        Row y;
        if constexpr(B) // the block row's local solve D_K^{-1} s, relaxed
          y = block_product<D>(&inv_diag_[K * DD], s);
        if(track)
          for(int c = 0; c < D; ++c) {
            const double old = from_zero ? 0.0 : x[K][c];
            double nv;
            if constexpr(B)
              nv = (1 - omega) * old + omega * y[c];
            else
              nv = (1 - omega) * old + omega * s[c] * inv_diag_[K];
            const double d = std::abs(nv - old);
            // a NaN must stick: !(d <= cm) holds for NaN, which becomes +inf
            if(!(d <= cm))
              cm = std::isnan(d) ? std::numeric_limits<double>::infinity() : d;
            x[K][c] = nv;
          }
        else
          for(int c = 0; c < D; ++c) {
            const double old = from_zero ? 0.0 : x[K][c];
            if constexpr(B)
              x[K][c] = omega == 1 ? y[c] : (1 - omega) * old + omega * y[c];
            else
              x[K][c] = omega == 1 ? s[c] * inv_diag_[K] : (1 - omega) * old + omega * s[c] * inv_diag_[K];
          }
      }
    }
  }

  // one forward SOR sweep of x_ on the loaded values (whole blocks, or the
  // upper triangles of an upper load)
  template <bool B>
  double loaded_sweep(double omega, int threads)
  {
    if constexpr(B)
      if(off_upper_)
        return sweep<B, double, true>(x_, b_, upper_off_.data(), omega, threads, true);
    return sweep<B>(x_, b_, values(), omega, threads, true);
  }

  template <bool B>
  Solve_report solve_sor(const Solver_options& options)
  {
    Solve_report report;
    Stopping_test stop(options);
    while(report.iterations < options.max_iterations) {
      const double update = loaded_sweep<B>(options.relaxation_factor, options.threads);
      ++report.iterations;
      SPRING_MOTION_CHECK(std::isfinite(update),
                          "the solver produced a non-finite value at sweep " << report.iterations);
      if(stop.done(update)) {
        report.converged = true;
        break;
      }
    }
    report.last_max_update = stop.last();
    report.error_estimate = stop.estimate();
    report.residual = scaled_residual<B>(options.threads);
    SPRING_MOTION_CHECK(std::isfinite(report.residual), "the solver produced a non-finite value");
    return report;
  }

  // Conjugate gradients preconditioned by a symmetric Gauss-Seidel sweep in
  // the solver's order, or by one multigrid V-cycle, from the loaded start.
  template <bool B>
  Solve_report solve_conjugate_gradient(const Solver_options& options)
  {
    const int threads = options.threads;
    const int nt = team(threads);
    Solve_report report;
    const long nf = long(order_.size());
    r_.resize(order_.size());
    z_.resize(order_.size());
    p_.resize(order_.size());
    q_.resize(order_.size());
    if constexpr(B)
      prepare_block_copies(threads);
    // r = b - A x
    in_team(nt, [&] {
#pragma omp for schedule(static)
      for(long k = 0; k < nf; ++k) {
        const Row y = apply<B>(x_, std::size_t(k));
        for(int c = 0; c < D; ++c)
          r_[std::size_t(k)][c] = b_[std::size_t(k)][c] - y[c];
      }
    });
    const double r_max = max_abs(r_, threads);
    SPRING_MOTION_CHECK(std::isfinite(r_max), "the solver's initial residual is not finite");
    Stopping_test stop(options);
    Preconditioner_state pc;
    if(r_max > 0 && nf > 0)
      pc = load_preconditioner<B>(options, true);
    auto precondition = [&] { apply_preconditioner<B>(pc, options); };
    if(r_max > 0 && nf > 0) {
      precondition();
      copy(z_, p_, threads);
      double rz = dot(r_, z_, threads);
      while(report.iterations < options.max_iterations) {
        in_team(nt, [&] {
#pragma omp for schedule(static)
          for(long k = 0; k < nf; ++k)
            q_[std::size_t(k)] = apply<B>(p_, std::size_t(k));
        });
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
        in_team(nt, [&] {
#pragma omp for schedule(static)
          for(long k = 0; k < nf; ++k)
            for(int c = 0; c < D; ++c)
              p_[std::size_t(k)][c] = z_[std::size_t(k)][c] + beta * p_[std::size_t(k)][c];
        });
      }
    }
    if(pc.cycle && report.converged)
      refresh_.record(report.iterations);
    // A converged solve reports the residual its recurrence carries, b - A x
    // up to the rounding of a few updates (within 3e-9 of it on the wing),
    // rather than one more product with the matrix: that product cost 6% of
    // a ball-vertex solve on the wing. A solve that did not converge, or
    // whose recurrence vanished, recomputes it.
    report.residual = report.converged ? max_scaled<B>([&](std::size_t k) { return r_[k]; }, threads)
                                       : scaled_residual<B>(threads);
    SPRING_MOTION_CHECK(std::isfinite(report.residual), "the solver produced a non-finite value");
    if(!report.converged && report.iterations < options.max_iterations) // a vanishing recurrence residual
      report.converged = residual_at_rounding_level(report.residual, max_abs(x_, threads)) || nf == 0 || r_max == 0;
    report.last_max_update = stop.last();
    report.error_estimate = report.converged && report.iterations == 0 ? 0 : stop.estimate();
    return report;
  }

  // What the preconditioner of a solve reads: the multigrid's coarse
  // levels (`cycle`) and the sweeps' single-precision entries (`single`;
  // upper triangles when the blocks are symmetric, product_upper_).
  struct Preconditioner_state
  {
    bool cycle = false, single = false;
  };

  // Loads the preconditioner `options` select for the loaded system; a
  // block system's coarse levels are kept from an earlier solve when `keep`
  // and options.multigrid_coarse_interval allow.
  template <bool B>
  Preconditioner_state load_preconditioner(const Solver_options& options, bool keep)
  {
    const bool mg = options.preconditioner == Preconditioner::multigrid;
    multigrid_.parameters.correction = options.multigrid_correction; // used per cycle only
    rigid_.parameters.correction = options.multigrid_correction;
    rigid_.first_level_cycles = first_level_cycles<D>(options); // used per cycle only
    if(mg) {
      Csr_view fine{order_.size(), row_offsets_.data(), col_.data(), nullptr, diagonal(), B};
      if(B && off_upper_)
        fine.upper = upper_off_.data();
      else
        fine.values = values();
      if constexpr(B) {
        // solves counted since the levels were last computed: the count, not
        // the thread count or a timing, decides, so the results stay the same
        // for any thread count
        const bool choose = !rigid_.built() || refresh_.due();
        if(choose || !keep || ++kept_solves_ >= options.multigrid_coarse_interval) {
          // checked where read (a search of the whole order, not at every solve)
          SPRING_MOTION_CHECK(positions_ && positions_->size() > *std::max_element(order_.begin(), order_.end()),
                              "the block system's multigrid needs the vertices' positions (set_positions)");
          row_points_.resize(order_.size());
          for(std::size_t r = 0; r < order_.size(); ++r)
            row_points_[r] = (*positions_)[order_[r]];
          if(choose) {
            rigid_.build(fine, row_points_.data(), options.threads);
            refresh_.rebuilt();
          }
          rigid_.load(fine, row_points_.data(), options.threads);
          kept_solves_ = 0;
        }
      } else {
        if(!multigrid_.built() || refresh_.due()) {
          multigrid_.build(fine, options.threads);
          refresh_.rebuilt();
        }
        multigrid_.load(fine, options.threads);
      }
    }
    Preconditioner_state pc;
    pc.cycle = mg && (B ? rigid_.number_of_levels() : multigrid_.number_of_levels()) > 0;
    pc.single = B && single_fits_;
    return pc;
  }

  // z_ = M^{-1} r_
  template <bool B>
  void apply_preconditioner(const Preconditioner_state& pc, const Solver_options& options)
  {
    const double omega = options.preconditioner_relaxation_factor;
    if constexpr(B)
      if(pc.single)
        return product_upper_ ? precondition<B, float, true>(single_off_.data(), omega, options.threads, pc.cycle)
                              : precondition<B>(single_off_.data(), omega, options.threads, pc.cycle);
    if constexpr(B)
      if(off_upper_)
        return precondition<B, double, true>(upper_off_.data(), omega, options.threads, pc.cycle);
    precondition<B>(values(), omega, options.threads, pc.cycle);
  }

  // z = M^{-1} r from z = 0: a forward sweep on A z = r, with `multigrid`
  // the coarse correction of the residual left, and a backward sweep. Without
  // it M is the symmetric Gauss-Seidel (SSOR for omega != 1) splitting of A in
  // the solver's order; with it, one V-cycle. The same smoothing before and
  // after, and a symmetric coarse cycle, keep M symmetric positive definite
  // (omega in (0, 2)).
  //
  // The sweeps read the off-diagonal entries from `off`: for block systems
  // their copy in single precision when it was made (prepare_block_copies),
  // which halves the bytes a block sweep moves, and a sweep is bound by those
  // bytes. M stays symmetric (a block and its transpose round alike) and close
  // to the double one; conjugate gradients' own products and the stopping
  // test stay in double, so the solution's accuracy is the same. (A scalar
  // sweep moves a column index with each value: a float saved 3% of a wing
  // step, not worth its copy.) `Upper`: `off` holds each block's upper
  // triangle, see prepare_block_copies.
  template <bool B, class V, bool Upper = false>
  void precondition(const V* off, double omega, int threads, bool multigrid)
  {
    sweep<B, V, Upper>(z_, r_, off, omega, threads, true, false, true);
    if(multigrid)
      coarse_correction<B, V, Upper>(off, threads, omega == 1);
    sweep<B, V, Upper>(z_, r_, off, omega, threads, false, false);
  }

  // The copies of a block system's off-diagonal blocks that a solve reads
  // instead of the blocks themselves, made once per solve.
  //
  // When every off-diagonal block is exactly symmetric (ball-vertex springs,
  // springs along their edges: each element adds the same value to (r, c)
  // and (c, r) in the same order), conjugate gradients' products read each
  // block's upper triangle in double precision (upper_off_, product_upper_):
  // 6 values of 9 in 3D, and a product is bound by the bytes it reads; the
  // same products in the same order (symmetric_block_product), so the same
  // bits.
  //
  // The preconditioner's sweeps read a single-precision copy (single_off_),
  // made when every entry is 0 or of magnitude in [single_low, single_high], where a
  // float keeps 24 bits of it (capped stiffness reaches 1e250; otherwise the
  // sweeps read the doubles, single_fits_ false); of the upper triangles too
  // when the blocks are symmetric (product_upper_), with the same products in
  // the same order (subtract_symmetric_block_product).
  //
  // Both upper triangles are written in the pass that checks the blocks
  // (each block's float copy only when its own values fit, as a conversion
  // out of range traps under feenableexcept); blocks found not symmetric
  // (torsional springs) are copied whole in a second pass.
  //
  // After an upper load (set_upper_load) the upper triangles are the
  // values themselves: only the single-precision copy is made, from them.
  void prepare_block_copies(int threads)
  {
    const std::size_t nb = col_.size();
    if(off_upper_) {
      single_off_.resize(nb * UD);
      single_fits_ = copy_to_single(upper_off_.data(), single_off_.data(), long(nb * UD), team(threads));
      product_upper_ = true;
      return;
    }
    const double* v = values();
    bool fits = true, symmetric = true;
    upper_off_.resize(nb * UD);
    single_off_.resize(nb * UD);
    in_team(team(threads), [&] {
#pragma omp for schedule(static) reduction(&& : fits, symmetric)
      for(long q = 0; q < long(nb); ++q) {
        const double* m = v + std::size_t(q) * DD;
        // & rather than &&: every entry tested, no early exit to branch on
        bool block_fits = true, block_symmetric = true;
        for(int k = 0; k < DD; ++k)
          block_fits &= fits_single(m[k]);
        for(int r = 0; r < D; ++r)
          for(int c = r + 1; c < D; ++c)
            block_symmetric &= m[r * D + c] == m[c * D + r];
        fits = fits && block_fits;
        symmetric = symmetric && block_symmetric;
        copy_upper_triangle<D>(m, &upper_off_[std::size_t(q) * UD]);
        if(block_fits)
          copy_upper_triangle<D>(m, &single_off_[std::size_t(q) * UD]);
      }
    });
    single_fits_ = fits;
    product_upper_ = symmetric;
    if(!fits || symmetric)
      return;
    single_off_.resize(nb * DD);
    in_team(team(threads), [&] {
#pragma omp for schedule(static)
      for(long q = 0; q < long(nb); ++q) {
        const double* m = v + std::size_t(q) * DD;
        float* out = &single_off_[std::size_t(q) * DD];
        for(int k = 0; k < DD; ++k)
          out[k] = float(m[k]);
      }
    });
  }

  // values(): the whole off-diagonal blocks of an upper load, from their
  // upper triangles
  void write_whole_off_blocks() const
  {
    double* whole = blocks_.data() + order_.size() * DD;
    for(std::size_t q = 0; q < col_.size(); ++q)
      expand_symmetric_block<D>(&upper_off_[q * UD], whole + q * DD);
    off_whole_ = true;
  }

  // z += correction P cycle(P^T (r - A z)). After a forward Gauss-Seidel
  // sweep from z = 0 (`after_gauss_seidel`), row k's equation holds with the
  // rows after it still at zero, so r - A z is -(sum over j > k of A_kj z_j):
  // the rows are numbered in sweep order (the rows of other blocks of k's
  // colour are not its neighbours), and only each row's upper part is read.
  template <bool B, class V, bool Upper = false>
  void coarse_correction(const V* off, int threads, bool after_gauss_seidel)
  {
    const int nt = team(threads);
    const long nf = long(order_.size());
    s_.resize(order_.size());
    if(after_gauss_seidel) {
      // Rows of the first colours hold most of the entries after them in the
      // solver's order, the last colours' rows almost none: equal ranges of
      // rows would leave one thread most of the work.
      in_team(nt, [&] {
#pragma omp for schedule(dynamic, 256)
        for(long k = 0; k < nf; ++k)
          s_[std::size_t(k)] =
              off_residual<B, V, Upper>(z_, Row{}, upper_offsets_[std::size_t(k)], row_offsets_[std::size_t(k) + 1], off);
      });
    } else {
      in_team(nt, [&] {
#pragma omp for schedule(static)
        for(long k = 0; k < nf; ++k) {
          const Row y = apply<B>(z_, std::size_t(k));
          for(int c = 0; c < D; ++c)
            s_[std::size_t(k)][c] = r_[std::size_t(k)][c] - y[c];
        }
      });
    }
    const double a = multigrid_.parameters.correction;
    if constexpr(B) {
      rigid_.restrict_from(s_, threads);
      rigid_.cycle(threads);
      in_team(nt, [&] {
#pragma omp for schedule(static)
        for(long k = 0; k < nf; ++k) {
          const Row e = rigid_.correction(std::size_t(k));
          for(int c = 0; c < D; ++c)
            z_[std::size_t(k)][c] += a * e[c];
        }
      });
    } else {
      multigrid_.restrict_from(s_);
      multigrid_.cycle();
      in_team(nt, [&] {
#pragma omp for schedule(static)
        for(long k = 0; k < nf; ++k) {
          const Row& e = multigrid_.coarse_solution(multigrid_.parent(std::size_t(k)));
          for(int c = 0; c < D; ++c)
            z_[std::size_t(k)][c] += a * e[c];
        }
      });
    }
  }

  void copy(const std::vector<Row>& a, std::vector<Row>& b, int threads)
  {
    const int nt = team(threads);
    const long nf = long(a.size());
    in_team(nt, [&] {
#pragma omp for schedule(static)
      for(long k = 0; k < nf; ++k)
        b[std::size_t(k)] = a[std::size_t(k)];
    });
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
    in_team(nt, [&] {
#pragma omp for schedule(static)
      for(long ch = 0; ch < chunks; ++ch) {
        const std::size_t b = std::size_t(ch) * reduction_chunk;
        partial_[std::size_t(ch)] = body(b, std::min(nf, b + reduction_chunk));
      }
    });
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

  // max over rows and components of |D_k^{-1} s_k|, s_k = residual(k)
  template <bool B, class Residual>
  double max_scaled(Residual&& residual, int threads)
  {
    return chunked_reduce(
        [&](std::size_t b, std::size_t e) {
          double m = 0;
          for(std::size_t k = b; k < e; ++k) {
            const Row s = residual(k);
            if constexpr(B) {
              const Row t = block_product<D>(&inv_diag_[k * DD], s);
              for(int c = 0; c < D; ++c)
                sticky_max(m, std::abs(t[c]));
            } else {
              for(int c = 0; c < D; ++c)
                sticky_max(m, std::abs(s[c] * inv_diag_[k]));
            }
          }
          return m;
        },
        sticky_combine, threads);
  }

  // max over rows and components of |x_k - local solve_k| = |D_k^{-1} (b - A x)_k|
  template <bool B>
  double scaled_residual(int threads)
  {
    return max_scaled<B>(
        [&](std::size_t k) {
          const Row y = apply<B>(x_, k);
          Row s;
          for(int c = 0; c < D; ++c)
            s[c] = b_[k][c] - y[c];
          return s;
        },
        threads);
  }

  // the structure's key: what `needs_build` compares
  bool built_ = false, block_ = false;
  Vertex_ordering ordering_ = Vertex_ordering::block_multicolour;
  std::size_t block_rows_ = 0;
  Preconditioner preconditioner_ = Preconditioner::multigrid;
  std::size_t network_entries_ = 0, network_elements_ = 0;
  std::vector<Index> free_;

  std::vector<Index> order_, block_offsets_, colour_offsets_; // colour_offsets_: into the blocks
  std::vector<Index> row_offsets_, upper_offsets_, col_, edge_; // upper_offsets_: see build
  std::vector<Index> bnd_offsets_, bnd_vertex_, bnd_edge_;
  std::vector<Index> elements_, element_dest_, element_chunk_offsets_, element_colour_offsets_;
  std::vector<std::array<Index, D + 1>> element_vertices_;
  std::vector<Index> projector_of_row_;          // empty, or one per row: into projectors_ or none
  std::vector<std::array<double, DD>> projectors_;
  std::vector<double> val_, bnd_val_, diag_, inv_diag_, partial_;
  // block systems: diagonal blocks, off-diagonal ones, those to constrained
  // vertices (block_values()); after an upper load the off-diagonal ones
  // are written out only when values() asks (so mutable). Left unwritten
  // when allocated: the pages of the off-diagonal blocks, which upper loads
  // never touch, then take no memory (a third of the wing's block arrays).
  mutable std::vector<double, Unwritten_allocator<double>> blocks_;
  bool off_upper_ = false;         // set_upper_load
  mutable bool off_whole_ = false; // blocks_ holds an upper load's whole off-diagonal blocks
  std::vector<float> single_off_;   // prepare_block_copies
  bool single_fits_ = false;        // single_off_ holds this load's values (upper triangles if product_upper_)
  std::vector<double> upper_off_;   // an upper load's values, or prepare_block_copies' copy
  bool product_upper_ = false;      // upper_off_ holds this load's values, apply reads it
  std::vector<Row> b_, x_, r_, z_, p_, q_, s_;
  Aggregation_multigrid<D> multigrid_;
  Rigid_body_multigrid<D> rigid_;
  Aggregation_refresh refresh_; // when the multigrid's aggregates are chosen again
  std::size_t kept_solves_ = 0;  // solves since a block system's coarse levels were computed
  const std::vector<Row>* positions_ = nullptr;
  std::vector<Row> row_points_;
};

} // namespace internal
} // namespace spring_motion

#endif
