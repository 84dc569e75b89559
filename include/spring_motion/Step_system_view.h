// Copyright (c) 2026 SpringMotion developers.
#ifndef SPRING_MOTION_STEP_SYSTEM_VIEW_H
#define SPRING_MOTION_STEP_SYSTEM_VIEW_H

#include <spring_motion/Spring_network.h>

#include <array>
#include <cstddef>

namespace spring_motion {

/// One step's linear system as the solver sees it, just before it is solved
/// (Network_deformer::system_observer): K d = b on the free vertices, rows in
/// the solver's order. The pointers stay valid only during the call.
///
/// Scalar systems (`block == false`, edge models): one value per entry, the
/// matrix acting on each of the D components alike: row k of component c
/// reads diagonal[k] d_k[c] + sum_q values[q] d_{columns[q]}[c] = rhs[k][c].
/// Block systems (element models): `values` holds a D x D row-major block
/// per entry (values + q*D*D) and `diagonal` one per row (diagonal + k*D*D):
/// D_k d_k + sum_q V_q d_{columns[q]} = rhs[k].
/// Off-diagonal entries are those between free vertices; the couplings to
/// constrained vertices, times their prescribed increments, are in `rhs`.
template <int D>
struct Step_system_view
{
  bool block = false;
  std::size_t rows = 0;
  const Index* vertices = nullptr;    ///< network vertex of each row
  const Index* row_offsets = nullptr; ///< entries of row k: [row_offsets[k], row_offsets[k + 1])
  const Index* columns = nullptr;     ///< row (not vertex) of each entry's neighbour
  const double* values = nullptr;     ///< per entry: 1 value, or a D x D block
  const double* diagonal = nullptr;   ///< per row: 1 value, or a D x D block
  const std::array<double, D>* rhs = nullptr;     ///< per row
  const std::array<double, D>* initial = nullptr; ///< per row: the solver's starting iterate
};

} // namespace spring_motion

#endif
