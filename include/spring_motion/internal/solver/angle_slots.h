// Copyright (c) 2026 SpringMotion developers.
#ifndef SPRING_MOTION_INTERNAL_SOLVER_ANGLE_SLOTS_H
#define SPRING_MOTION_INTERNAL_SOLVER_ANGLE_SLOTS_H

#include <array>
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
  // slot (element * edges_per_element + local edge) -> its position in the
  // edge-major order, where the slots of edge e are positions
  // edge_slot_offsets[e] .. edge_slot_offsets[e + 1] - 1. The inverse map
  // is not kept: the assembly only scatters into that order.
  std::vector<Index> edge_slot_offsets, slot_position;

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

} // namespace internal
} // namespace spring_motion

#endif
