// Copyright (c) 2026 SpringMotion developers.
#ifndef SPRING_MOTION_INTERNAL_ASSEMBLE_H
#define SPRING_MOTION_INTERNAL_ASSEMBLE_H

#include <spring_motion/Error.h>
#include <spring_motion/Spring_network.h>
#include <spring_motion/internal/threads.h>
#include <spring_motion/internal/angles.h>
#include <spring_motion/internal/element_points.h>
#include <spring_motion/internal/linear_system.h>
#include <spring_motion/stiffness/Stiffness_model.h>

#include <algorithm>
#include <array>
#include <cmath>
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

/// Edge stiffness k_e of `model` at positions x. `angles` is scratch space.
/// Throws when the model returns a negative or non-finite value.
///
/// The angles are computed element by element (or face by face) and stored
/// edge by edge, at their slot's position in edge_slots: the edge loop then
/// reads each edge's angles as one contiguous run. Read element by element
/// instead, the angles of an edge lie far apart, and on the wing that gather
/// cost more than computing them.
template <int D, class Model>
void compute_edge_stiffness(const Spring_network<D>& net, const std::vector<typename Spring_network<D>::Point>& x,
                            const Model& model, const Stiffness_context& ctx, std::vector<double>& k,
                            std::vector<double>& angles, int threads)
{
  constexpr int E = Spring_network<D>::edges_per_element;
  const Angle_kind kind = model.angle_kind(D);
  const long m = long(net.number_of_elements());
  const bool by_face = (kind == Angle_kind::face && D == 3);
  if(kind != Angle_kind::none) {
    if(!by_face) {
      angles.resize(std::size_t(m) * E);
#pragma omp parallel for schedule(static) num_threads(internal::heavy_thread_count(threads, std::size_t(m)))
      for(long t = 0; t < m; ++t) {
        const auto a = element_edge_angles<D>(element_points<D>(net.elements, x, std::size_t(t)));
        for(int j = 0; j < E; ++j)
          angles[net.slot_position[std::size_t(t) * E + std::size_t(j)]] = a[std::size_t(j)];
      }
    } else if constexpr(D == 3) {
      const long nf = long(net.faces.size());
      angles.resize(std::size_t(nf) * 3);
#pragma omp parallel for schedule(static) num_threads(internal::heavy_thread_count(threads, std::size_t(nf)))
      for(long f = 0; f < nf; ++f) {
        const auto& F = net.faces[std::size_t(f)];
        const auto a = triangle_angles<3>(x[F[0]], x[F[1]], x[F[2]]);
        for(int j = 0; j < 3; ++j)
          angles[net.face_slot_position[3 * std::size_t(f) + std::size_t(j)]] = a[std::size_t(j)];
      }
    }
  }
  const auto& off = by_face ? net.edge_face_slot_offsets : net.edge_slot_offsets;
  const long ne = long(net.number_of_edges());
  k.resize(std::size_t(ne));
  long bad = -1;
#pragma omp parallel for schedule(static) num_threads(internal::heavy_thread_count(threads, std::size_t(ne)))
  for(long e = 0; e < ne; ++e) {
    const auto& ed = net.edges[std::size_t(e)];
    const double l = distance<D>(x[ed[0]], x[ed[1]]); // > 0 for a tiny edge too
    const double* a = nullptr;
    std::size_t na = 0;
    if(kind != Angle_kind::none) {
      a = angles.data() + off[std::size_t(e)];
      na = off[std::size_t(e) + 1] - off[std::size_t(e)];
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
      model.add_element_matrix(element_points<D>(net.elements, x, t), Ke.data());
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
