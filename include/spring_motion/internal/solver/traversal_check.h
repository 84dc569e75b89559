// Copyright (c) 2026 SpringMotion developers.
#ifndef SPRING_MOTION_INTERNAL_SOLVER_TRAVERSAL_CHECK_H
#define SPRING_MOTION_INTERNAL_SOLVER_TRAVERSAL_CHECK_H

#include <spring_motion/internal/geometry/exact_orientation.h>
#include <spring_motion/internal/solver/angle_slots.h>
#include <spring_motion/internal/solver/threads.h>

#include <algorithm>
#include <array>
#include <cstddef>
#include <vector>

namespace spring_motion {
namespace internal {

// The exact check of a step in the elements' spatial traversal (Angle_slots):
// positions copied in the traversal's vertex order, then each element's
// orientation against its initial one, recorded in the traversal's element
// order. In the file's order (find_inverted_elements) the vertices of
// consecutive elements lie far apart in the positions, and on the wing the
// check waited on those misses; here both the positions read and the signs
// compared stay close together (the positions copied by
// copy_in_traversal_order, angle_slots.h).

/// Every element's exact orientation (+1, -1, 0 when flat), in the
/// traversal's element order, at positions xt (copy_in_traversal_order).
template <int D>
std::vector<signed char> traversal_orientations(const Angle_slots& slots, const std::vector<std::array<double, D>>& xt,
                                                int threads)
{
  const long m = long(slots.ordered_elements.size() / (D + 1));
  std::vector<signed char> sign(static_cast<std::size_t>(m));
  in_team(thread_count(threads, std::size_t(m)), [&] {
#pragma omp for schedule(static)
    for(long i = 0; i < m; ++i)
      sign[std::size_t(i)] =
          static_cast<signed char>(exact_orientation(traversal_element_points<D>(slots, xt, std::size_t(i))));
  });
  return sign;
}

/// Whether some element's exact orientation at positions xt differs from
/// `sign` (traversal_orientations of the initial positions).
template <int D>
bool orientation_changed(const Angle_slots& slots, const std::vector<std::array<double, D>>& xt,
                         const std::vector<signed char>& sign, int threads)
{
  const long m = long(sign.size());
  bool changed = false;
  const auto differs = [&](std::size_t i) {
    return exact_orientation(traversal_element_points<D>(slots, xt, i)) != sign[i];
  };
  if constexpr(D == 3) {
    // two tetrahedra at once where the filter's first stage decides both
    // (coarse_orientations), each alone otherwise; an odd last one is
    // paired with itself
    const long pairs = (m + 1) / 2;
    // thread-safe: the filtered predicates keep their rounding-mode state per call
    in_team(thread_count(threads, std::size_t(m)), [&] {
#pragma omp for schedule(static) reduction(|| : changed)
      for(long h = 0; h < pairs; ++h) {
        const std::size_t i = 2 * std::size_t(h), j = std::min(i + 1, std::size_t(m) - 1);
        const auto s =
            coarse_orientations(traversal_element_corners<3>(slots, xt, i), traversal_element_corners<3>(slots, xt, j));
        changed = changed || (s[0] != 0 ? s[0] != sign[i] : differs(i)) || (s[1] != 0 ? s[1] != sign[j] : differs(j));
      }
    });
  } else {
    in_team(thread_count(threads, std::size_t(m)), [&] {
#pragma omp for schedule(static) reduction(|| : changed)
      for(long i = 0; i < m; ++i)
        changed = changed || differs(std::size_t(i));
    });
  }
  return changed;
}

} // namespace internal
} // namespace spring_motion

#endif
