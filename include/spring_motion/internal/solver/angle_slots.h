// Copyright (c) 2026 SpringMotion developers.
#ifndef SPRING_MOTION_INTERNAL_SOLVER_ANGLE_SLOTS_H
#define SPRING_MOTION_INTERNAL_SOLVER_ANGLE_SLOTS_H

#include <spring_motion/internal/solver/threads.h>

#include <array>
#include <cstddef>
#include <cstdint>
#include <vector>

namespace spring_motion {

template <int D>
struct Spring_network;

namespace internal {

/// Where each element (or 3D face) angle goes when the stiffness gathers
/// the angles around an edge: tables that only the assembly reads, so they
/// live inside `Spring_network` but outside its public members.
struct Angle_slots
{
  using Index = std::uint32_t;
  // The element angles are computed in a spatial order of the elements
  // (`ordered_elements`: their vertices, D + 1 per element, elements sorted
  // by the Morton code of their centroid; each vertex by its traversal
  // number, see below) and stored edge by edge, the edges
  // laid out in the order that traversal first meets them: edge
  // layout_edge[q]'s slots are positions layout_slot_offsets[q] ..
  // layout_slot_offsets[q + 1] - 1, in increasing element number (so each
  // edge's angles are summed in the same order whatever the traversal).
  // slot_position[i * edges_per_element + j] is the position of local edge j
  // of the i-th element of the traversal. In the file's order the elements
  // of a Mesh_3 or Gmsh mesh lie scattered through space, and so did the
  // positions they wrote: on the wing that scatter cost three times the
  // angles' arithmetic; in this order both the vertices read and the
  // positions written stay close together.
  std::vector<Index> ordered_elements, slot_position, layout_slot_offsets, layout_edge;
  // The stiffness reads positions through a copy in traversal order:
  // traversal_vertices[v] is the network vertex the traversal meets v-th
  // (vertices of no element are not listed), and layout_edge_ends[q] the
  // traversal numbers of edge layout_edge[q]'s ends, in the edge's own order.
  // Read in network order, the vertices of neighbouring elements and edges
  // lie far apart in memory: on the wing the edge loop's reads of the edge
  // list and of both ends' positions cost more than its arithmetic.
  std::vector<Index> traversal_vertices;
  std::vector<std::array<Index, 2>> layout_edge_ends;

  // 3D only: the unique triangular faces, their edges (local edge k opposite
  // local vertex k) and the same edge-major order for the face slots
  // (face * 3 + local).
  std::vector<std::array<Index, 3>> faces;
  std::vector<Index> face_edges;
  std::vector<Index> edge_face_slot_offsets, face_slot_position;
};

/// The one door to a network's angle slots (the builder fills them, the
/// assembly and white-box tests read them).
struct Network_access
{
  template <int D>
  static Angle_slots& slots(Spring_network<D>& net) { return net.slots_; }
  template <int D>
  static const Angle_slots& slots(const Spring_network<D>& net) { return net.slots_; }
};

template <int D>
const Angle_slots& angle_slots(const Spring_network<D>& net)
{
  return Network_access::slots(net);
}

/// Positions in the traversal's vertex order: xt[v] = x[slots.traversal_vertices[v]]
/// (the stiffness and the exact check read them so).
template <int D>
void copy_in_traversal_order(const Angle_slots& slots, const std::vector<std::array<double, D>>& x,
                             std::vector<std::array<double, D>>& xt, int threads)
{
  const long nt = long(slots.traversal_vertices.size());
  xt.resize(std::size_t(nt));
  in_team(heavy_thread_count(threads, std::size_t(nt)), [&] {
#pragma omp for schedule(static)
    for(long v = 0; v < nt; ++v)
      xt[std::size_t(v)] = x[slots.traversal_vertices[std::size_t(v)]];
  });
}

/// The corners of the traversal's i-th element in place: pointers to their
/// coordinates in xt (copy_in_traversal_order), as the kernels that read two
/// elements at once take them (double_pair.h).
template <int D>
std::array<const double*, D + 1> traversal_element_corners(const Angle_slots& slots,
                                                           const std::vector<std::array<double, D>>& xt,
                                                           std::size_t i)
{
  std::array<const double*, D + 1> c;
  for(std::size_t k = 0; k <= D; ++k)
    c[k] = xt[slots.ordered_elements[i * (D + 1) + k]].data();
  return c;
}

/// The same corners as points.
template <int D>
std::array<std::array<double, D>, D + 1> traversal_element_points(const Angle_slots& slots,
                                                                  const std::vector<std::array<double, D>>& xt,
                                                                  std::size_t i)
{
  const auto c = traversal_element_corners<D>(slots, xt, i);
  std::array<std::array<double, D>, D + 1> p;
  for(std::size_t k = 0; k <= D; ++k)
    for(std::size_t j = 0; j < D; ++j)
      p[k][j] = c[k][j];
  return p;
}

} // namespace internal
} // namespace spring_motion

#endif
