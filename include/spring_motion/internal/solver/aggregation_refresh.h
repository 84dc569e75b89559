// Copyright (c) 2026 SpringMotion developers.
#ifndef SPRING_MOTION_INTERNAL_SOLVER_AGGREGATION_REFRESH_H
#define SPRING_MOTION_INTERNAL_SOLVER_AGGREGATION_REFRESH_H

#include <algorithm>
#include <cstddef>
#include <limits>

namespace spring_motion {
namespace internal {

/// When to choose the multigrid's aggregates again. They are chosen from the
/// system of the first solve and kept, since choosing them costs about three
/// iterations of a wing solve; only their values follow the stiffness. But
/// the strong couplings move as the mesh deforms, and aggregates chosen from
/// the first system can stop matching them. Which aggregates the greedy
/// choice makes depends on the vertex numbering: the same wing with its
/// vertices numbered along a Morton curve went from 5 iterations a step to
/// 10 to 14 over a 30-degree pitch, where its file's numbering kept mostly 5
/// (aggregates chosen again every step kept 5 to 8 on both, but at about
/// three iterations' cost each).
///
/// The rule: the aggregates are chosen again once `streak` solves in a row
/// need at least 3/2 of the fewest iterations any solve on them has needed
/// and at least 3 more. The first solve on a set of aggregates is no
/// reference: the cold start of a run needs many iterations whatever the
/// preconditioner. Isolated slow solves (a step whose warm start guessed
/// badly) do not trigger it. A rebuild that did not help does not bring
/// another a few solves later: the fewest count starts again with the new
/// aggregates, so a system that is simply harder sets a higher reference.
class Aggregation_refresh
{
public:
  static constexpr std::size_t streak = 3;

  /// Feeds the iterations of a solve preconditioned by the current aggregates.
  void record(std::size_t iterations)
  {
    if(++solves_ == 1)
      return;
    fewest_ = std::min(fewest_, iterations);
    const bool slow = 2 * iterations >= 3 * fewest_ && iterations >= fewest_ + 3;
    run_ = slow ? run_ + 1 : 0;
  }

  /// Whether the next solve should choose its aggregates again.
  bool due() const { return run_ >= streak; }

  /// The aggregates were chosen (again).
  void rebuilt() { *this = Aggregation_refresh(); }

private:
  std::size_t solves_ = 0, run_ = 0;
  std::size_t fewest_ = std::numeric_limits<std::size_t>::max();
};

} // namespace internal
} // namespace spring_motion

#endif
