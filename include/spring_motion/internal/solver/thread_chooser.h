// Copyright (c) 2026 SpringMotion developers.
#ifndef SPRING_MOTION_INTERNAL_SOLVER_THREAD_CHOOSER_H
#define SPRING_MOTION_INTERNAL_SOLVER_THREAD_CHOOSER_H

#include <spring_motion/internal/solver/threads.h>

#include <cstddef>
#include <limits>

namespace spring_motion {
namespace internal {

/// Chooses, step by step, between OpenMP's full team and one thread by
/// measuring both (Solver_options::threads = 0).
///
/// Why: on a machine whose cores are shared (a flow solver beside the mesh
/// mover), a thread that is descheduled stalls every barrier of a parallel
/// region while the others spin; the multicolour sweeps have a barrier per
/// colour, and the team can then run several times slower than one thread.
/// On an idle machine the team is faster. Results never depend on the thread
/// count (every parallel loop is deterministic), so the choice may follow the
/// machine's load freely: the cheaper option per unit of work (the step's
/// time over its iterations plus a few for the stiffness and the check) is
/// used, and the other is tried again after 8, 16, 32, ... steps (at most
/// 64), which costs a few per cent when the choice is right and recovers
/// within a few steps when the load changes. When the choice changes the
/// interval starts again at 8, or at 32 when one option cost at least twice
/// the other: a team stalled by a busy machine costs several times one
/// thread, and each probe of it costs as much again. The first step, which
/// also builds the solver's state and so is not measured, runs on one
/// thread: on a busy machine a team step costs several one-thread steps, on
/// an idle one the first step costs a little more.
class Thread_chooser
{
public:
  /// The thread count for the next step: `requested` when it is positive.
  int next(int requested)
  {
    fixed_ = requested > 0 || thread_count(0) == 1;
    if(fixed_)
      return thread_count(requested);
    // one thread for the first step (not measured), the team, one thread,
    // then the cheaper with probes of the other
    if(!warm_)
      return 1;
    if(cost_[0] != cost_[0])
      probing_ = 0;
    else if(cost_[1] != cost_[1])
      probing_ = 1;
    else if(since_probe_ >= interval_)
      probing_ = 1 - best_;
    else
      probing_ = best_;
    return probing_ == 0 ? thread_count(0) : 1;
  }

  /// What the step chosen by the last next() cost.
  void record(double seconds, std::size_t iterations)
  {
    if(fixed_)
      return;
    if(!warm_) {
      warm_ = true;
      return;
    }
    cost_[probing_] = seconds / (double(iterations) + 4);
    if(probing_ != best_)
      since_probe_ = 0;
    else
      ++since_probe_;
    const int cheaper = cost_[1] == cost_[1] && cost_[1] < cost_[0] ? 1 : 0;
    if(cheaper != best_) {
      best_ = cheaper;
      const bool clear = cost_[1 - cheaper] >= 2 * cost_[cheaper];
      interval_ = clear ? 32 : 8;
    } else if(probing_ != best_ && interval_ < 64)
      interval_ *= 2;
  }

  /// The choice so far: the team's thread count or 1.
  int chosen() const { return best_ == 0 ? thread_count(0) : 1; }

private:
  static constexpr double unknown = std::numeric_limits<double>::quiet_NaN();
  double cost_[2] = {unknown, unknown}; // seconds per unit of work: [0] the team, [1] one thread
  int best_ = 0, probing_ = 0;
  std::size_t since_probe_ = 0, interval_ = 8;
  bool fixed_ = true, warm_ = false;
};

} // namespace internal
} // namespace spring_motion

#endif
