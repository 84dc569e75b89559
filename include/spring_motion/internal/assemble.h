// Copyright (c) 2026 SpringMotion developers.
#ifndef SPRING_MOTION_INTERNAL_ASSEMBLE_H
#define SPRING_MOTION_INTERNAL_ASSEMBLE_H

#include <spring_motion/Error.h>
#include <spring_motion/Spring_network.h>
#include <spring_motion/internal/threads.h>
#include <spring_motion/internal/angles.h>
#include <spring_motion/internal/linear_system.h>
#include <spring_motion/stiffness/Stiffness_model.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <vector>

namespace spring_motion {
namespace internal {

template <int D>
inline std::array<std::array<double, D>, D + 1> element_points(const Spring_network<D>& net,
                                                               const std::vector<typename Spring_network<D>::Point>& x,
                                                               std::size_t t)
{
  std::array<std::array<double, D>, D + 1> p;
  for(int k = 0; k <= D; ++k)
    p[k] = x[net.elements[t][k]];
  return p;
}

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

/// The angle of element t at its local edge k: the facing angle of a
/// triangle, the dihedral angle of a tetrahedron (bitwise
/// element_edge_angles(...)[k]).
template <int D>
inline double element_edge_angle(const Spring_network<D>& net, const std::vector<typename Spring_network<D>::Point>& x,
                                  std::size_t t, int k)
{
  const auto& el = net.elements[t];
  if constexpr(D == 2)
    return triangle_angle<2>(x[el[0]], x[el[1]], x[el[2]], k);
  else
    return dihedral_angle({x[el[0]], x[el[1]], x[el[2]], x[el[3]]}, k);
}

/// Edge stiffness k_e of `model` at positions x. Throws when the model returns
/// a negative or non-finite value.
///
/// Each edge computes the angles it needs itself, from its slots (element
/// t, local edge k) and the positions: every angle belongs to exactly one
/// edge, so no angle is computed twice, and the edge loop reads only the
/// positions (tens of bytes a vertex) instead of gathering from an angle
/// array by element (a random read from 48 bytes a tetrahedron, which on a
/// large mesh misses the cache at almost every angle).
template <int D, class Model>
void compute_edge_stiffness(const Spring_network<D>& net, const std::vector<typename Spring_network<D>::Point>& x,
                            const Model& model, const Stiffness_context& ctx, std::vector<double>& k, int threads)
{
  constexpr int E = Spring_network<D>::edges_per_element;
  const Angle_kind kind = model.angle_kind(D);
  const bool by_face = (kind == Angle_kind::face && D == 3);
  const long ne = long(net.number_of_edges());
  k.resize(std::size_t(ne));
  long bad = -1;
#pragma omp parallel for schedule(static) num_threads(internal::heavy_thread_count(threads, std::size_t(ne)))
  for(long e = 0; e < ne; ++e) {
    const auto& ed = net.edges[std::size_t(e)];
    const double l = distance<D>(x[ed[0]], x[ed[1]]); // > 0 for a tiny edge too
    // enough for any edge of a sane mesh; a wilder one takes the slow path
    std::array<double, 64> local;
    std::vector<double> spill;
    const double* a = nullptr;
    std::size_t na = 0;
    if(kind != Angle_kind::none) {
      const auto& off = by_face ? net.edge_face_slot_offsets : net.edge_slot_offsets;
      const auto& slots = by_face ? net.edge_face_slots : net.edge_slots;
      na = off[std::size_t(e) + 1] - off[std::size_t(e)];
      double* buf = local.data();
      if(na > local.size()) {
        spill.resize(na);
        buf = spill.data();
      }
      for(std::size_t s = 0; s < na; ++s) {
        const Index slot = slots[off[std::size_t(e)] + s];
        if constexpr(D == 3) {
          if(by_face) { // slot 3 f + j: face f's angle at its vertex j
            const auto& F = net.faces[slot / 3];
            buf[s] = triangle_angle<3>(x[F[0]], x[F[1]], x[F[2]], int(slot % 3));
            continue;
          }
        }
        buf[s] = element_edge_angle<D>(net, x, slot / E, int(slot % E));
      }
      a = buf;
    }
    // a zero-length edge (coincident vertices) never reaches a model's 1/l
    const double v = l > 0 ? model(l, a, na, ctx) : 0.0;
    k[std::size_t(e)] = v;
    if(!(v >= 0 && std::isfinite(v)) || l == 0) {
#pragma omp critical(spring_motion_bad_stiffness)
      if(bad < 0 || e < bad)
        bad = e;
    }
  }
  if(bad >= 0) {
    const auto& ed = net.edges[std::size_t(bad)];
    SPRING_MOTION_CHECK(false, "stiffness model '" << describe_model(model, D).name << "' gave k = "
                                                   << k[std::size_t(bad)] << " on edge " << ed[0] << "-" << ed[1]
                                                   << ": expected a finite value >= 0 on an edge of non-zero length");
  }
}

/// Assembles the step's system from the edge stiffness (and, for element
/// models, the element matrices) on the network's CSR pattern.
template <int D, class Model>
void assemble_system(const Spring_network<D>& net, const std::vector<typename Spring_network<D>::Point>& x, const Model& model,
                     const std::vector<double>& k, Linear_system<D>& sys, int threads)
{
  const std::size_t n = net.number_of_vertices();
  const long ln = long(n);
  constexpr bool element_model = Is_element_model<Model, D>::value;
  sys.block = element_model;
  if constexpr(!element_model) {
    sys.weight.resize(net.adjacency.size());
    sys.diagonal.resize(n);
#pragma omp parallel for schedule(static) num_threads(internal::thread_count(threads, n))
    for(long i = 0; i < ln; ++i) {
      double d = 0;
      for(Index p = net.adjacency_offsets[std::size_t(i)]; p < net.adjacency_offsets[std::size_t(i) + 1]; ++p) {
        const double w = k[net.adjacency_edge[p]];
        sys.weight[p] = w;
        d += w;
      }
      sys.diagonal[std::size_t(i)] = d;
    }
  } else {
    constexpr int DD = D * D;
    constexpr int ND = (D + 1) * D;
    sys.off_blocks.assign(net.adjacency.size() * DD, 0.0);
    sys.diagonal_blocks.assign(n * DD, 0.0);
    for(std::size_t i = 0; i < n; ++i)
      for(Index p = net.adjacency_offsets[i]; p < net.adjacency_offsets[i + 1]; ++p) {
        const double w = k[net.adjacency_edge[p]];
        for(int c = 0; c < D; ++c) {
          sys.off_blocks[p * DD + c * D + c] -= w;
          sys.diagonal_blocks[i * DD + c * D + c] += w;
        }
      }
    std::array<double, ND * ND> Ke;
    for(std::size_t t = 0; t < net.number_of_elements(); ++t) {
      Ke.fill(0.0);
      model.add_element_matrix(element_points(net, x, t), Ke.data());
      const auto& el = net.elements[t];
      for(int a = 0; a <= D; ++a)
        for(int b = 0; b <= D; ++b) {
          double* dst;
          if(a == b) {
            dst = &sys.diagonal_blocks[std::size_t(el[a]) * DD];
          } else {
            const auto first = net.adjacency.begin() + net.adjacency_offsets[el[a]];
            const auto last = net.adjacency.begin() + net.adjacency_offsets[el[a] + 1];
            const auto it = std::lower_bound(first, last, el[b]);
            dst = &sys.off_blocks[std::size_t(it - net.adjacency.begin()) * DD];
          }
          for(int r = 0; r < D; ++r)
            for(int c = 0; c < D; ++c) {
              const double v = Ke[(a * D + r) * ND + (b * D + c)];
              SPRING_MOTION_CHECK(std::isfinite(v), "element stiffness of element " << t << " is not finite");
              dst[r * D + c] += v;
            }
        }
    }
    sys.diagonal_inverse.resize(n * DD);
    for(std::size_t i = 0; i < n; ++i) {
      if(net.adjacency_offsets[i] == net.adjacency_offsets[i + 1])
        continue; // isolated vertex: never solved for
      const auto inv = invert_block<D>(&sys.diagonal_blocks[i * DD]);
      std::copy(inv.begin(), inv.end(), sys.diagonal_inverse.begin() + std::ptrdiff_t(i * DD));
    }
  }
}

} // namespace internal
} // namespace spring_motion

#endif
