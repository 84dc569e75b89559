// Copyright (c) 2026 SpringMotion developers.
#ifndef SPRING_MOTION_INTERNAL_SOLVER_THREAD_CHOOSER_H
#define SPRING_MOTION_INTERNAL_SOLVER_THREAD_CHOOSER_H

#include <spring_motion/internal/solver/free_cores.h>
#include <spring_motion/internal/solver/threads.h>

#include <cmath>
#include <cstddef>
#include <functional>
#include <limits>
#include <utility>

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
/// thread, and each probe of it costs as much again. A step of the choice
/// that costs more than the other option's last measure changes the choice
/// only when the step before it did too: one slow step (another process's
/// moment on a core, a virtual core's pause: 2.6 to 4.7 ms against 0.8 on
/// the 2D paper mesh) had sent that case to one thread for 32 steps. The
/// first step, which also builds the solver's state and so is not measured,
/// starts on one thread: on a busy machine a team step costs several
/// one-thread steps. Its solve, the costliest of the run (a cold start), and
/// its check go to the team when that start (stiffness and the solver's
/// set-up, tens of milliseconds on the wing) had a core to itself: see
/// after_setup.
///
/// One-thread steps also say whether the cores are crowded without trying
/// the team: the share of their wall time the thread ran on a core (its CPU
/// time over its wall time) is about 1 when a core was free for it, and
/// about 2/3 when two other CPU-bound processes share 2 cores with it (0.5 to
/// 1 step by step: the share is averaged over the last few steps, each half
/// the weight of the next). Below `crowded_share` a team cannot find a core
/// for each of its threads, so a team probe (the first one too) waits until
/// the one-thread steps get a core again: on a busy machine the probes,
/// which cost about five one-thread steps each on the wing, are not run, and
/// a core that frees up is enough to try the team again.
///
/// Neither measure sees the other cores while one thread runs alone on a
/// core (the scheduler tends to leave it there, and two other processes
/// sharing the other core): the team, then stalled, was tried at the first
/// step's solve or the first probe and cost several one-thread steps each
/// time. So no step goes to the team while fewer cores than its threads are
/// free of other processes' runnable threads (free_cores(), read when a team
/// step is about to start and at the first step's start, tens of
/// microseconds a read): such a step runs on one thread instead, as when
/// crowded. A read that found the cores free holds for the steps after it
/// until they have taken `read_holds` of wall time together: a step on the
/// 2D paper mesh takes under a millisecond, and a read every step cost it
/// several per cent.
class Thread_chooser
{
public:
  /// `free_cores`: the source of the count of cores that other processes
  /// leave free (negative when not known); tests give their own.
  explicit Thread_chooser(std::function<int()> free_cores = internal::free_cores)
      : free_cores_(std::move(free_cores))
  {
  }

  /// The thread count for the next step: `requested` when it is positive.
  int next(int requested)
  {
    fixed_ = requested > 0 || thread_count(0) == 1;
    if(fixed_)
      return last_ = thread_count(requested);
    // one thread for the first step (not measured), the team, one thread,
    // then the cheaper with probes of the other
    ++step_;
    if(!warm_) {
      // the first of two reads that after_setup weighs
      team_fits();
      return last_ = 1;
    }
    if(cost_[0] != cost_[0])
      probing_ = 0;
    else if(cost_[1] != cost_[1])
      probing_ = 1;
    else if(since_probe_ >= interval_)
      probing_ = 1 - best_;
    else
      probing_ = best_;
    // a team tried while one thread cannot get a core of its own, or any
    // team step while other processes hold the cores it needs
    waiting_ = probing_ == 0 && (((cost_[0] != cost_[0] || best_ == 1) && crowded()) || !team_fits(true));
    if(waiting_)
      probing_ = 1;
    last_ = probing_ == 0 ? thread_count(0) : 1;
    return last_;
  }

  /// The thread count for the rest of a step whose start (the stiffness and
  /// the solver's set-up) took `seconds` of wall time and `cpu_seconds` of
  /// the calling thread's CPU time (negative when not known). Only the first
  /// step changes: it started on one thread, and goes on with OpenMP's team
  /// when that thread ran at least `crowded_share` of the time, over at
  /// least `least_sample` seconds (a shorter start says little of the load,
  /// and its step costs little) and the cores that other processes leave
  /// free hold the team; its sample then counts as a one-thread step's in
  /// crowded().
  int after_setup(double seconds, double cpu_seconds)
  {
    if(fixed_ || warm_ || last_ != 1 || cpu_seconds < 0 || seconds < least_sample
       || cpu_seconds < crowded_share * seconds || !team_fits())
      return last_;
    cpu_sum_ = 0.5 * cpu_sum_ + cpu_seconds;
    wall_sum_ = 0.5 * wall_sum_ + seconds;
    return last_ = thread_count(0);
  }

  /// What the step chosen by the last next() cost: its wall time, its solver
  /// iterations and the CPU time of the calling thread in it (negative when
  /// not known).
  void record(double seconds, std::size_t iterations, double cpu_seconds = -1)
  {
    if(fixed_)
      return;
    held_ += seconds;
    if(last_ == 1 && cpu_seconds >= 0) {
      cpu_sum_ = 0.5 * cpu_sum_ + cpu_seconds;
      wall_sum_ = 0.5 * wall_sum_ + seconds;
    }

    if(!warm_) {
      warm_ = true;
      return;
    }
    if(waiting_) {
      // one thread in place of a team probe: its cost, nothing else changes
      cost_[1] = seconds / (double(iterations) + 4);
      return;
    }
    const double cost = seconds / (double(iterations) + 4);
    if(probing_ == best_) {
      ++since_probe_;
      // one dearer step of the choice is not measured: the second in a row is
      // the comparisons with a cost that may be unknown (NaN) are the quiet
      // ones: an ordered comparison with a NaN raises FE_INVALID, a SIGFPE
      // in a program that traps it
      const bool dearer = std::isgreater(cost, cost_[1 - best_]);
      dearer_ = dearer ? dearer_ + 1 : 0;
      if(dearer_ == 1)
        return;
    } else {
      since_probe_ = 0;
      dearer_ = 0;
    }
    cost_[probing_] = cost;
    const int cheaper = std::isless(cost_[1], cost_[0]) ? 1 : 0;
    if(cheaper != best_) {
      best_ = cheaper;
      dearer_ = 0;
      const bool clear = std::isgreaterequal(cost_[1 - cheaper], 2 * cost_[cheaper]);
      interval_ = clear ? 32 : 8;
    } else if(probing_ != best_ && interval_ < 64)
      interval_ *= 2;
  }

  /// The thread count of the last step (0 before any: OpenMP's default).
  int chosen() const { return last_; }

  /// One-thread steps whose thread ran less than this share of their wall
  /// time (averaged) say the cores are crowded.
  static constexpr double crowded_share = 0.9;

  /// The shortest start of a first step that after_setup reads, in seconds.
  static constexpr double least_sample = 0.01;

  /// How long (the wall time of the steps recorded since) a free-core read
  /// that found the team's cores free holds, in seconds.
  static constexpr double read_holds = 0.01;

  /// Whether the last one-thread steps say the cores are crowded.
  bool crowded() const { return cpu_sum_ < crowded_share * wall_sum_; }

private:
  // Whether the cores that other processes leave free hold a team (true
  // when not known). Processes that run for a moment (a system daemon, a
  // machine's monitoring) take a core in some reads even on an idle
  // machine: a read that finds too few free cores is outvoted by a read in
  // this step or the one before that found enough. Only an older read does
  // not count (the load may have come since), and a probe then waits a step.
  // With `may_reuse`, a read that fitted less than read_holds ago (steps'
  // wall time) is taken as this step's instead of reading again.
  bool team_fits(bool may_reuse = false)
  {
    if(may_reuse && fit_ && held_ < read_holds) {
      read_step_ = step_;
      return true;
    }
    const int free = free_cores_();
    const bool fits = free < 0 || free >= thread_count(0);
    const bool fitted = read_step_ + 1 >= step_ && fit_;
    fit_ = fits;
    read_step_ = step_;
    if(fits)
      held_ = 0;
    return fits || fitted;
  }

  std::function<int()> free_cores_;
  std::size_t step_ = 0, read_step_ = 0; // next() calls; that of the last free-core read
  bool fit_ = false;                      // what the last free-core read said
  double held_ = std::numeric_limits<double>::infinity(); // steps' seconds since the last read that fitted
  static constexpr double unknown = std::numeric_limits<double>::quiet_NaN();
  double cost_[2] = {unknown, unknown}; // seconds per unit of work: [0] the team, [1] one thread
  double cpu_sum_ = 0, wall_sum_ = 0;   // one-thread steps' CPU and wall times, decayed
  int best_ = 0, probing_ = 0, last_ = 0;
  std::size_t since_probe_ = 0, interval_ = 8;
  int dearer_ = 0; // steps in a row of the choice that cost more than the other option
  bool fixed_ = true, warm_ = false, waiting_ = false;
};

} // namespace internal
} // namespace spring_motion

#endif
