// Copyright (c) 2026 SpringMotion developers.
#ifndef SPRING_MOTION_INTERNAL_SOLVER_ASSEMBLE_H
#define SPRING_MOTION_INTERNAL_SOLVER_ASSEMBLE_H

#include <spring_motion/Error.h>
#include <spring_motion/Spring_network.h>
#include <spring_motion/internal/solver/threads.h>
#include <spring_motion/internal/geometry/angles.h>
#include <spring_motion/internal/geometry/capped_math.h>
#include <spring_motion/internal/geometry/double_pair.h>
#include <spring_motion/internal/geometry/element_points.h>
#include <spring_motion/internal/solver/free_system.h>
#include <spring_motion/stiffness/Stiffness_model.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <exception>
#include <limits>
#include <utility>
#include <vector>

namespace spring_motion {
namespace internal {


/// The element's angle at each of its local edges: facing angles of a
/// triangle, dihedral angles of a tetrahedron.
template <int D>
inline std::array<double, Spring_network<D>::edges_per_element> element_edge_angles(
    const std::array<std::array<double, D>, D + 1>& p)
{
  if constexpr(D == 2)
    return triangle_angles<2>(p[0], p[1], p[2]);
  else
    return dihedral_angles(p);
}

/// The same as 1/sin^2 of each, computed without trigonometry.
template <int D>
inline std::array<double, Spring_network<D>::edges_per_element> element_edge_inverse_sin_squared(
    const std::array<std::array<double, D>, D + 1>& p)
{
  if constexpr(D == 2)
    return triangle_inverse_sin_squared<2>(p[0], p[1], p[2]);
  else
    return dihedral_inverse_sin_squared(p);
}

/// The same for two elements at once (the pair forms of angles.h), corners a and b.
template <int D>
inline std::array<std::array<double, Spring_network<D>::edges_per_element>, 2> element_edge_inverse_sin_squared(
    const std::array<const double*, D + 1>& a, const std::array<const double*, D + 1>& b)
{
  if constexpr(D == 2)
    return triangle_inverse_sin_squared(a, b);
  else
    return dihedral_inverse_sin_squared(a, b);
}

/// What compute_edge_stiffness keeps between calls: the angles (or 1/sin^2
/// of them for a model that reads only that, Reads_inverse_sin_squared) and
/// the positions in the traversal's order (Angle_slots).
template <int D>
struct Stiffness_scratch
{
  std::vector<double> angles;
  std::vector<std::array<double, D>> points;

  void release()
  {
    std::vector<double>().swap(angles);
    std::vector<std::array<double, D>>().swap(points);
  }
};

/// 1/sin^2 of the dihedral angles of the m tetrahedra of the traversal,
/// four at a time (double_pair.h) where the processor has AVX, written to
/// their slots in `angles`; false, with nothing written, in 2D or without
/// AVX. The last group of a count not a multiple of 4 repeats the last
/// tetrahedron.
template <int D>
bool element_inverse_sin_squared_in_fours(const Angle_slots& slots, const std::vector<std::array<double, D>>& xt,
                                          long m, std::vector<double>& angles, int threads)
{
#if SPRING_MOTION_HAS_DOUBLE_QUAD
  if constexpr(D == 3) {
    if(!four_lanes_available())
      return false;
    constexpr std::size_t E = 6;
    const long quads = (m + 3) / 4;
    in_team(internal::heavy_thread_count(threads, std::size_t(m)), [&] {
#pragma omp for schedule(static)
      for(long h = 0; h < quads; ++h) {
        std::size_t e[4];
        std::array<const double*, 4> t[4];
        for(std::size_t l = 0; l < 4; ++l) {
          e[l] = std::min(4 * std::size_t(h) + l, std::size_t(m) - 1);
          t[l] = traversal_element_corners<3>(slots, xt, e[l]);
        }
        double a[4][6];
        dihedral_inverse_sin_squared(t, a);
        for(std::size_t l = 0; l < 4; ++l)
          for(std::size_t q = 0; q < E; ++q)
            angles[slots.slot_position[e[l] * E + q]] = a[l][q];
      }
    });
    return true;
  }
#endif
  (void)slots, (void)xt, (void)m, (void)angles, (void)threads;
  return false;
}

/// Edge stiffness k_e of `model` at positions x.
/// Throws when the model returns a negative or non-finite value.
///
/// The angles are computed element by element (or face by face) and stored
/// edge by edge, at their slot's position in an edge-major order: the edge
/// loop then reads each edge's angles as one contiguous run. Read element by
/// element instead, the angles of an edge lie far apart, and on the wing that
/// gather cost more than computing them. Element angles are computed in the
/// network's spatial traversal (Angle_slots), from a copy of the positions
/// in that traversal's order, and the edges then visited in its layout;
/// each edge's value depends on neither order.
template <int D, class Model>
void compute_edge_stiffness(const Spring_network<D>& net, const std::vector<typename Spring_network<D>::Point>& x,
                            const Model& model, const Stiffness_context& ctx, std::vector<double>& k,
                            Stiffness_scratch<D>& scratch, int threads)
{
  constexpr int E = Spring_network<D>::edges_per_element;
  const Angle_slots& slots = angle_slots(net);
  const Angle_kind kind = model.angle_kind(D);
  const long m = long(net.number_of_elements());
  const bool by_face = (kind == Angle_kind::face && D == 3);
  SPRING_MOTION_CHECK(!by_face || !slots.edge_face_slot_offsets.empty(),
                      "a model on face angles needs the network's face slots (internal::build_face_slots)");
  constexpr bool sines = Reads_inverse_sin_squared<Model>::value;
  // element angles: edges in the layout's order; face angles: in edge order
  const bool by_layout = kind != Angle_kind::none && !by_face;
  std::vector<double>& angles = scratch.angles;
  // Readable values after the last edge's angles, so that every edge's
  // Inverse_sin_squared::sum may take its branch-free path. Only in 3D: in 2D
  // an edge has one or two angles, a loop whose exit the predictor gets right.
  constexpr std::size_t padding = (D == 3 && sines) ? Inverse_sin_squared::padded_size : 0;
  auto& xt = scratch.points;
  if(by_layout) {
    copy_in_traversal_order<D>(slots, x, xt, threads);
    angles.resize(std::size_t(m) * E + padding);
    if constexpr(sines) {
      if(!element_inverse_sin_squared_in_fours<D>(slots, xt, m, angles, threads)) {
        // two elements at once (double_pair.h); an odd last one is paired
        // with itself
        const long pairs = (m + 1) / 2;
        in_team(internal::heavy_thread_count(threads, std::size_t(m)), [&] {
#pragma omp for schedule(static)
          for(long h = 0; h < pairs; ++h) {
            const std::size_t i = 2 * std::size_t(h), j = std::min(i + 1, std::size_t(m) - 1);
            const auto a = element_edge_inverse_sin_squared<D>(traversal_element_corners<D>(slots, xt, i),
                                                               traversal_element_corners<D>(slots, xt, j));
            for(std::size_t q = 0; q < E; ++q)
              angles[slots.slot_position[i * E + q]] = a[0][q];
            for(std::size_t q = 0; q < E; ++q)
              angles[slots.slot_position[j * E + q]] = a[1][q];
          }
        });
      }
    } else {
      in_team(internal::heavy_thread_count(threads, std::size_t(m)), [&] {
#pragma omp for schedule(static)
        for(long i = 0; i < m; ++i) {
          const auto p = traversal_element_points<D>(slots, xt, std::size_t(i));
          const std::array<double, E> a = element_edge_angles<D>(p);
          for(int j = 0; j < E; ++j)
            angles[slots.slot_position[std::size_t(i) * E + std::size_t(j)]] = a[std::size_t(j)];
        }
      });
    }
  } else if(by_face) {
    if constexpr(D == 3) {
      const long nf = long(slots.faces.size());
      angles.resize(std::size_t(nf) * 3 + padding);
      in_team(internal::heavy_thread_count(threads, std::size_t(nf)), [&] {
#pragma omp for schedule(static)
        for(long f = 0; f < nf; ++f) {
          const auto& F = slots.faces[std::size_t(f)];
          std::array<double, 3> a;
          if constexpr(sines)
            a = triangle_inverse_sin_squared<3>(x[F[0]], x[F[1]], x[F[2]]);
          else
            a = triangle_angles<3>(x[F[0]], x[F[1]], x[F[2]]);
          for(int j = 0; j < 3; ++j)
            angles[slots.face_slot_position[3 * std::size_t(f) + std::size_t(j)]] = a[std::size_t(j)];
        }
      });
    }
  }
  const auto& off = by_face ? slots.edge_face_slot_offsets : slots.layout_slot_offsets;
  const long ne = long(net.number_of_edges());
  k.resize(std::size_t(ne));
  long bad = ne, coincident = ne;
  in_team(internal::heavy_thread_count(threads, std::size_t(ne)), [&] {
    // each thread's own (Edge_function): the model's terms of the context and
    // its parameters alone are then worked out once, not per edge
    const Edge_function<Model> stiffness_of(model, ctx);
#pragma omp for schedule(static) reduction(min : bad, coincident)
    for(long q = 0; q < ne; ++q) {
      long e = q;
      double l; // > 0 for a tiny edge too
      if(by_layout) {
        e = long(slots.layout_edge[std::size_t(q)]);
        const auto& ends = slots.layout_edge_ends[std::size_t(q)];
        l = distance<D>(xt[ends[0]], xt[ends[1]]);
      } else {
        const auto& ed = net.edges[std::size_t(e)];
        l = distance<D>(x[ed[0]], x[ed[1]]);
      }
      const double* a = nullptr;
      std::size_t na = 0, readable = 0;
      if(kind != Angle_kind::none) {
        a = angles.data() + off[std::size_t(q)];
        na = off[std::size_t(q) + 1] - off[std::size_t(q)];
        if(padding > 0)
          readable = angles.size() - off[std::size_t(q)];
      }
      // a zero-length edge (coincident vertices) never reaches a model's 1/l
      double v = 0.0;
      if(l > 0) {
        if constexpr(sines)
          v = stiffness_of(l, Inverse_sin_squared{a, na, readable});
        else
          v = stiffness_of(l, a, na);
      }
      k[std::size_t(e)] = v;
      if(l == 0)
        coincident = std::min(coincident, e);
      else if(!(v >= 0 && std::isfinite(v)))
        bad = std::min(bad, e);
    }
  });
  if(coincident < ne) {
    const auto& ed = net.edges[std::size_t(coincident)];
    SPRING_MOTION_VERTEX_CHECK(false, ed[0], "coincident vertices " << ed[0] << " and " << ed[1]
                                                 << ": the spring between them has zero length");
  }
  if(bad < ne) {
    const auto& ed = net.edges[std::size_t(bad)];
    SPRING_MOTION_CHECK(false, "stiffness model '" << describe_model(model, D).name << "' gave k = "
                                                   << k[std::size_t(bad)] << " on edge " << ed[0] << "-" << ed[1]
                                                   << ": expected a finite value >= 0");
  }
}

// Inside a handler: keeps the exception in flight if element t is the
// smallest failing element so far.
inline void keep_failure(std::size_t t, long& first_bad, std::exception_ptr& error)
{
#pragma omp critical(spring_motion_element_matrix_error)
  if(long(t) < first_bad) {
    first_bad = long(t);
    error = std::current_exception();
  }
}

// finite_or_kept's path for values not all finite: the error made and kept
template <std::size_t N>
bool keep_not_finite(const std::array<double, N>& Ke, std::size_t t, long& first_bad, std::exception_ptr& error)
{
  try {
    // all of it, rows of constrained vertices too: a model that breaks
    // there breaks elsewhere on another step
    SPRING_MOTION_ELEMENT_CHECK(all_finite(Ke.data(), Ke.size()), t,
                                "element stiffness of element " << t << " is not finite");
    return true;
  } catch(...) {
    keep_failure(t, first_bad, error);
    return false;
  }
}

// Whether element t's values Ke are all finite; if not, the failure is
// kept if t is the smallest failing element so far.
template <std::size_t N>
bool finite_or_kept(const std::array<double, N>& Ke, std::size_t t, long& first_bad, std::exception_ptr& error)
{
  // the test inline, the error's path (a throw caught here) only on failure
  return all_finite(Ke.data(), Ke.size()) || keep_not_finite(Ke, t, first_bad, error);
}

// What a model gives for one element: the distinct blocks (a model with
// Has_symmetric_blocks: the 60 values of a tetrahedron, not the 144 of its
// whole matrix) or the whole matrix.
template <int D, class Model>
using Element_values = std::array<double, Has_symmetric_blocks<Model, D>::value
                                              ? (D + 1) * (D + 2) / 2 * (D * (D + 1) / 2)
                                              : (D + 1) * D * (D + 1) * D>;

// Where element matrices go: Free_system::block_values(), whose blocks the
// destinations count; after an upper load (Free_system::set_upper_load) the
// off-diagonal ones, destinations [off_begin, off_end), go to their upper
// triangles in `upper` instead.
struct Block_targets
{
  double* blocks = nullptr;
  double* upper = nullptr; // none: whole blocks everywhere
  Index off_begin = 0, off_end = 0;

  template <int D>
  static Block_targets of(Free_system<D>& fs)
  {
    Block_targets t;
    t.blocks = fs.block_values();
    if(fs.upper_load()) {
      t.upper = fs.upper_values();
      t.off_begin = Index(fs.off_block(0));
      t.off_end = Index(fs.off_block(Index(fs.nonzeros())));
    }
    return t;
  }
  // whether destination `dest` is an upper triangle's
  bool upper_at(Index dest) const { return upper && dest >= off_begin && dest < off_end; }
};

// Adds element values Ke to the blocks through the element's (D+1)^2
// destinations `to` (none: a constrained vertex's row).
template <int D, class Model>
void scatter_element_values(const Element_values<D, Model>& Ke, const Index* to, const Block_targets& t)
{
  constexpr int DD = D * D;
  constexpr int ND = (D + 1) * D;
  constexpr int S = D * (D + 1) / 2;
  auto add_to = [&](Index dest, const std::array<double, DD>& block) {
    if(dest == Free_system<D>::none)
      return;
    double* out = t.blocks + std::size_t(dest) * DD;
    for(int k = 0; k < DD; ++k)
      out[k] += block[std::size_t(k)];
  };
  if constexpr(Has_symmetric_blocks<Model, D>::value) {
    // distinct block u = (a, b), a <= b, goes to (a, b) and to (b, a):
    // expanded from its upper triangle once for both (each block is read
    // from them with the same values as from the whole matrix, which holds
    // each distinct value once per place). Unrolled: left to itself the
    // compiler kept the tetrahedron's ten pairs a run-time loop (16% more
    // instructions in the scatter, valgrind's count)
    int u = 0;
#pragma GCC unroll 4
    for(int a = 0; a <= D; ++a)
#pragma GCC unroll 4
      for(int b = a; b <= D; ++b, ++u) {
        const Index ab = to[a * (D + 1) + b];
        if(a != b && t.upper_at(ab)) {
          // both vertices free: (b, a) is an entry of the pattern too, and
          // each takes the upper triangle as it is
          for(const Index dest : {ab, to[b * (D + 1) + a]}) {
            double* out = t.upper + std::size_t(dest - t.off_begin) * S;
            for(int k = 0; k < S; ++k)
              out[k] += Ke[std::size_t(u * S + k)];
          }
          continue;
        }
        std::array<double, DD> full;
        for(int r = 0; r < D; ++r)
          for(int c = 0; c < D; ++c)
            full[std::size_t(r * D + c)] = symmetric_entry<D>(&Ke[std::size_t(u * S)], r, c);
        add_to(ab, full);
        if(a != b)
          add_to(to[b * (D + 1) + a], full);
      }
  } else
    for(int a = 0; a <= D; ++a)
      for(int b = 0; b <= D; ++b) {
        std::array<double, DD> block;
        for(int r = 0; r < D; ++r)
          for(int c = 0; c < D; ++c)
            block[std::size_t(r * D + c)] = Ke[std::size_t((a * D + r) * ND + (b * D + c))];
        add_to(to[a * (D + 1) + b], block);
      }
}

// Adds the matrix of network element t, corners p, through its (D+1)^2
// destinations `to`; a failure is kept if t is the smallest so far.
template <int D, class Model>
void add_element_matrix(const std::array<std::array<double, D>, D + 1>& p, const Model& model, std::size_t t,
                        const Index* to, const Block_targets& blocks, long& first_bad, std::exception_ptr& error)
{
  Element_values<D, Model> Ke;
  Ke.fill(0.0);
  try {
    if constexpr(Has_symmetric_blocks<Model, D>::value)
      model.add_symmetric_blocks(p, Ke.data());
    else
      model.add_element_matrix(p, Ke.data());
  } catch(...) {
    keep_failure(t, first_bad, error);
    return;
  }
  if(finite_or_kept(Ke, t, first_bad, error))
    scatter_element_values<D, Model>(Ke, to, blocks);
}

// The same for two elements at once (Has_symmetric_blocks_of_two: the
// model's arithmetic for both in one register); false, with nothing added,
// when the model declines the pair: then each takes add_element_matrix. A
// model declines values that are not finite, so those stored here are not
// tested again; add_element_matrix reports them. Each element's blocks are
// added as add_element_matrix adds them, p's first: the same sums in the
// same order.
template <int D, class Model>
bool add_element_matrices_of_two(const std::array<std::array<double, D>, D + 1>& p,
                                 const std::array<std::array<double, D>, D + 1>& q, const Model& model,
                                 const Index* to_p, const Index* to_q, const Block_targets& blocks)
{
  // stored by the model, so not cleared first (a clearing took a third of
  // this loop's time on the 2D paper mesh: the compiler's string store)
  Element_values<D, Model> Kp, Kq;
  if(!model.symmetric_blocks_of_two(p, q, Kp.data(), Kq.data()))
    return false;
  scatter_element_values<D, Model>(Kp, to_p, blocks);
  scatter_element_values<D, Model>(Kq, to_q, blocks);
  return true;
}

// The same for four elements at once (Has_symmetric_blocks_of_four, where
// four_lanes_available()), in the order of the pairs' form: the same sums in
// the same order.
template <int D, class Model>
bool add_element_matrices_of_four(const std::array<std::array<std::array<double, D>, D + 1>, 4>& p,
                                  const Model& model, const Index* to, const Block_targets& blocks)
{
  std::array<Element_values<D, Model>, 4> K;
  if(!model.symmetric_blocks_of_four({&p[0], &p[1], &p[2], &p[3]},
                                     {K[0].data(), K[1].data(), K[2].data(), K[3].data()}))
    return false;
  for(std::size_t l = 0; l < 4; ++l)
    scatter_element_values<D, Model>(K[l], to + l * (D + 1) * (D + 1), blocks);
  return true;
}

// The element's blocks lie in the rows of its D + 1 vertices, which belong
// to different colours and so to distant parts of the block array: the
// scatter waited on cache misses for half its time (perf annotate, wing,
// ball-vertex springs). The blocks of the element this many places ahead are
// requested for writing while the current one is computed (no arithmetic
// changes).
constexpr long prefetch_elements = 2;
// bytes of blocks above which they are requested
constexpr std::size_t prefetch_above = std::size_t(8) << 20;

#if defined(__GNUC__)
#define SPRING_MOTION_ALWAYS_INLINE inline __attribute__((always_inline))
#else
#define SPRING_MOTION_ALWAYS_INLINE inline
#endif

// Forced inline, like the two below: GCC finds a function that only
// requests memory "pure" and deletes the calls whose result is unused.
template <int D>
SPRING_MOTION_ALWAYS_INLINE void prefetch_destination(Index d, const Block_targets& blocks)
{
#if defined(__GNUC__)
  constexpr int DD = D * D, S = D * (D + 1) / 2;
  if(d == Free_system<D>::none)
    return;
  if(blocks.upper_at(d)) {
    const double* b = blocks.upper + std::size_t(d - blocks.off_begin) * S;
    __builtin_prefetch(b, 1);
    __builtin_prefetch(b + S - 1, 1);
  } else {
    const double* b = blocks.blocks + std::size_t(d) * DD;
    __builtin_prefetch(b, 1);
    __builtin_prefetch(b + DD - 1, 1);
  }
#else
  (void)d;
  (void)blocks;
#endif
}

// One request after another, not a loop (which GCC may delete for the
// same reason when it has not unrolled it).
template <int D, std::size_t... A>
SPRING_MOTION_ALWAYS_INLINE void prefetch_destinations(const Index* to, const Block_targets& blocks,
                                                       std::index_sequence<A...>)
{
  (prefetch_destination<D>(to[A], blocks), ...);
}

template <int D>
SPRING_MOTION_ALWAYS_INLINE void prefetch_destinations(const Index* to, const Block_targets& blocks)
{
  prefetch_destinations<D>(to, blocks, std::make_index_sequence<(D + 1) * (D + 1)>());
}

// The corners' positions are read at random too: the block array streamed
// through the cache since the last step has evicted most of them.
template <int D, class Points>
inline void prefetch_points(const std::array<Index, D + 1>& element, const Points& x)
{
#if defined(__GNUC__)
  for(int v = 0; v <= D; ++v)
    __builtin_prefetch(x[element[std::size_t(v)]].data());
#else
  (void)element;
  (void)x;
#endif
}

// Element matrices chunk by chunk (Free_system::element_chunks): the chunks
// of a colour share no free vertex, so they are added in parallel, and each
// block gets its contributions in the same order whatever the thread count.
// An element whose matrix throws or is not finite stops the step with the
// error of the first such element in network order, as a serial loop would.
template <int D, class Model>
void add_element_matrices(const std::vector<typename Spring_network<D>::Point>& x, const Model& model,
                          Free_system<D>& fs, int threads)
{
  const Block_targets blocks = Block_targets::of(fs);
  const auto& elements = fs.assembled_elements();
  const auto& vertices = fs.assembled_element_vertices();
  const auto& dest = fs.element_destinations();
  const auto& chunks = fs.element_chunks();
  const auto& colours = fs.element_colours();
  const int nt = internal::thread_count(threads, elements.size());
  // blocks that stay in the caches are not requested: the requests then
  // only cost instructions (the 2D paper mesh's stiffness, 0.85 MB of
  // blocks, took 7% longer with them)
  const bool prefetching = fs.bnd_block(Index(fs.bnd_vertices().size())) * D * D * sizeof(double) > prefetch_above;
  const bool fours = four_lanes_available();
  constexpr long no_error = std::numeric_limits<long>::max();
  long first_bad = no_error; // the smallest network element whose matrix failed
  std::exception_ptr error;
  for(std::size_t c = 0; c + 1 < colours.size(); ++c) {
    const long first = long(colours[c]), last = long(colours[c + 1]);
    in_team(nt, [&] {
#pragma omp for schedule(dynamic)
      for(long h = first; h < last; ++h) {
        const long end = long(chunks[std::size_t(h) + 1]);
        for(long s = long(chunks[std::size_t(h)]); s < end;) {
          const Index* to = &dest[std::size_t(s) * (D + 1) * (D + 1)];
          // the elements after this one (or pair, or four) requested
          const long ahead = !prefetching                                    ? 0
                             : Has_symmetric_blocks_of_four<Model, D>::value && fours ? 4
                             : Has_symmetric_blocks_of_two<Model, D>::value  ? 2
                                                                             : 1;
          for(long a = s + prefetch_elements; a < std::min(end, s + prefetch_elements + ahead); ++a) {
            prefetch_destinations<D>(&dest[std::size_t(a) * (D + 1) * (D + 1)], blocks);
            prefetch_points<D>(vertices[std::size_t(a)], x);
          }
          if constexpr(Has_symmetric_blocks_of_four<Model, D>::value)
            if(fours && s + 3 < end &&
               add_element_matrices_of_four<D>({element_points<D>(vertices, x, std::size_t(s)),
                                                element_points<D>(vertices, x, std::size_t(s + 1)),
                                                element_points<D>(vertices, x, std::size_t(s + 2)),
                                                element_points<D>(vertices, x, std::size_t(s + 3))},
                                               model, to, blocks)) {
              s += 4;
              continue;
            }
          if constexpr(Has_symmetric_blocks_of_two<Model, D>::value)
            if(s + 1 < end &&
               add_element_matrices_of_two<D>(element_points<D>(vertices, x, std::size_t(s)),
                                              element_points<D>(vertices, x, std::size_t(s + 1)), model, to,
                                              to + (D + 1) * (D + 1), blocks)) {
              s += 2;
              continue;
            }
          add_element_matrix<D>(element_points<D>(vertices, x, std::size_t(s)), model, elements[std::size_t(s)], to,
                                blocks, first_bad, error);
          ++s;
        }
      }
    });
  }
  if(error)
    std::rethrow_exception(error);
}

// v[0, n) = 0, in large pieces shared out by a team of nt threads
inline void clear_in_team(double* v, std::size_t n, int nt)
{
  constexpr std::size_t piece = std::size_t(1) << 15;
  const long pieces = long((n + piece - 1) / piece);
  in_team(nt, [&] {
#pragma omp for schedule(static)
    for(long p = 0; p < pieces; ++p)
      std::fill(v + std::size_t(p) * piece, v + std::min(n, std::size_t(p + 1) * piece), 0.0);
  });
}

/// Fills the block system `fs` (element models, or any model with sliding
/// vertices), built for the network, with this step's values: the edge springs (k I per coordinate, or the truss
/// k e e^T / |e|^2 along the edge, as `edge_spring_form(model)` says; `k` is
/// not read when it says none) row by row, then each element matrix scattered through the precomputed
/// destinations; then the diagonal blocks are inverted (a singular one
/// throws Vertex_error).
template <int D, class Model>
void assemble_block_system(const std::vector<typename Spring_network<D>::Point>& x, const Model& model,
                           const std::vector<double>& k, Free_system<D>& fs, int threads)
{
  constexpr int DD = D * D;
  const Edge_spring_form form = edge_spring_form(model);
  const bool along_edge = form == Edge_spring_form::along_edge;
  const auto& order = fs.order();
  const auto& offsets = fs.row_offsets();
  const auto& col = fs.columns();
  const auto& edge = fs.nonzero_edges();
  const auto& bnd_offsets = fs.bnd_offsets();
  const auto& bnd_vertex = fs.bnd_vertices();
  const auto& bnd_edge = fs.bnd_edges();
  // every block symmetric (the model's, and springs' k I or k e e^T): the
  // off-diagonal ones loaded as upper triangles (Free_system::set_upper_load)
  fs.set_upper_load(Has_symmetric_blocks<Model, D>::value && !fs.has_projectors());
  constexpr int S = D * (D + 1) / 2;
  double* blocks = fs.block_values();
  double* upper = fs.upper_load() ? fs.upper_values() : nullptr;
  const long nf = long(order.size());
  // the spring block B of edge e between i and j: row i gets +B on its
  // diagonal and -B at (i, j)
  auto spring = [&](Index e, Index i, Index j, double* off, double* diag) {
    const double w = k[e];
    if(!along_edge) {
      for(int r = 0; r < DD; ++r)
        off[r] = 0;
      for(int c = 0; c < D; ++c) {
        off[c * D + c] = -w;
        diag[c * D + c] += w;
      }
      return;
    }
    // e e^T / |e|^2 from the edge vector scaled by its largest component:
    // |e|^2 of a tiny edge (1e-300) would underflow to 0 and divide by it
    std::array<double, D> d;
    double largest = 0;
    for(int c = 0; c < D; ++c) {
      d[c] = x[j][c] - x[i][c];
      largest = std::max(largest, std::abs(d[c]));
    }
    double l2 = 0;
    for(int c = 0; c < D; ++c) {
      d[c] /= largest;
      l2 += d[c] * d[c];
    }
    for(int r = 0; r < D; ++r)
      for(int c = 0; c < D; ++c) {
        const double b = w * (d[r] * d[c] / l2);
        off[r * D + c] = -b;
        diag[r * D + c] += b;
      }
  };
  const int nt = internal::thread_count(threads, std::size_t(nf));
  if(form == Edge_spring_form::none) {
    // No springs: the blocks are only cleared for the element matrices. The
    // diagonal, off-diagonal and boundary blocks each lie together, so each
    // is cleared as one range: three fills a row (of 4 to 30 values in 2D)
    // took 0.02 ms of a 1.4 ms 2D ball-vertex step (stiffness 0.31 -> 0.29 ms).
    clear_in_team(blocks, std::size_t(nf) * DD, nt);
    if(upper)
      clear_in_team(upper, fs.nonzeros() * S, nt);
    else
      clear_in_team(blocks + fs.off_block(0) * DD, fs.nonzeros() * DD, nt);
    clear_in_team(blocks + fs.bnd_block(0) * DD, bnd_vertex.size() * DD, nt);
  } else
    in_team(nt, [&] {
#pragma omp for schedule(static)
      for(long r = 0; r < nf; ++r) {
        const std::size_t R = std::size_t(r);
        const Index i = order[R];
        double* diag = blocks + R * DD;
        for(int c = 0; c < DD; ++c)
          diag[c] = 0;
        for(Index q = offsets[R]; q < offsets[R + 1]; ++q)
          if(upper) {
            std::array<double, DD> off;
            spring(edge[q], i, order[col[q]], off.data(), diag);
            copy_upper_triangle<D>(off.data(), upper + std::size_t(q) * S);
          } else
            spring(edge[q], i, order[col[q]], blocks + fs.off_block(q) * DD, diag);
        for(Index q = bnd_offsets[R]; q < bnd_offsets[R + 1]; ++q)
          spring(bnd_edge[q], i, bnd_vertex[q], blocks + fs.bnd_block(q) * DD, diag);
      }
    });
  if constexpr(Is_element_model<Model, D>::value)
    add_element_matrices<D>(x, model, fs, threads);
  fs.apply_projectors(threads);
  fs.finish_block_load(threads);
}

} // namespace internal
} // namespace spring_motion

#endif
