// Copyright (c) 2026 SpringMotion developers.
#ifndef SPRING_MOTION_INTERNAL_SOLVER_THREADS_H
#define SPRING_MOTION_INTERNAL_SOLVER_THREADS_H

#include <atomic>
#include <condition_variable>
#include <cstddef>
#include <exception>
#include <mutex>
#include <time.h>

#ifdef _OPENMP
#include <omp.h>
#endif
#ifdef __linux__
#include <sched.h>
#endif

namespace spring_motion {
namespace internal {

/// The calling thread's number in its OpenMP team: 0 outside a parallel
/// region, or without OpenMP.
inline int thread_number()
{
#ifdef _OPENMP
  return omp_get_thread_num();
#else
  return 0;
#endif
}

/// The thread count for an OpenMP region: `requested`, or OpenMP's default
/// when it is 0 (num_threads(0) is not allowed).
inline int thread_count(int requested)
{
#ifdef _OPENMP
  return requested > 0 ? requested : omp_get_max_threads();
#else
  (void)requested;
  return 1;
#endif
}

/// Loops over fewer items than this run on one thread when the thread count
/// is OpenMP's default (0): a parallel region costs more than such a loop,
/// and far more when the cores are shared with other processes (a
/// descheduled thread stalls the region's barrier), and a default team is
/// nobody's measured choice. A count given explicitly, by the thread chooser
/// (a step's team, taken only where it measured cheaper and other processes
/// leave the cores free) or by the caller, goes parallel from
/// `chosen_parallel_threshold` items: the 2D paper mesh's 3,844 rows then
/// share out the solver's loops (docs/performance.md, "Small loops on a
/// chosen team"). Results never depend on either (every parallel loop is
/// deterministic). Constants of the build: a test program that must exercise
/// the parallel paths on small meshes defines SPRING_MOTION_PARALLEL_THRESHOLD
/// (to 1, for both) before including the library.
#ifndef SPRING_MOTION_PARALLEL_THRESHOLD
constexpr std::size_t parallel_threshold = 16384;
constexpr std::size_t chosen_parallel_threshold = 2048;
#else
constexpr std::size_t parallel_threshold = SPRING_MOTION_PARALLEL_THRESHOLD;
constexpr std::size_t chosen_parallel_threshold = SPRING_MOTION_PARALLEL_THRESHOLD;
#endif

inline std::size_t threshold_for(int requested)
{
  return requested > 0 ? chosen_parallel_threshold : parallel_threshold;
}

/// The thread count for a loop over `items` items.
inline int thread_count(int requested, std::size_t items)
{
  return items < threshold_for(requested) ? 1 : thread_count(requested);
}

/// The thread count for a loop over `items` items that each cost as much as
/// several cheap ones (transcendental functions: angles, stiffness): such a
/// loop pays for its parallel region at a sixteenth of the items.
inline int heavy_thread_count(int requested, std::size_t items)
{
  return items * 16 < threshold_for(requested) ? 1 : thread_count(requested);
}

// The core the calling thread runs on (-1 where not known).
inline int current_cpu()
{
#ifdef __linux__
  return sched_getcpu();
#else
  return -1;
#endif
}

inline void yield_core()
{
#ifdef __linux__
  sched_yield();
#endif
}

// Moves the calling thread off `cpu`, to any other core it may run on, and
// gives it back the cores it had (the scheduler then leaves it where it is).
inline void move_off_cpu(int cpu)
{
#ifdef __linux__
  cpu_set_t allowed, others;
  if(cpu < 0 || cpu >= CPU_SETSIZE || sched_getaffinity(0, sizeof allowed, &allowed) != 0)
    return;
  others = allowed;
  CPU_CLR(cpu, &others);
  if(CPU_COUNT(&others) == 0 || sched_setaffinity(0, sizeof others, &others) != 0)
    return;
  sched_setaffinity(0, sizeof allowed, &allowed);
#else
  (void)cpu;
#endif
}

/// Runs `f` on a team of `threads` threads (a parallel region; at least 1),
/// whose worksharing loops (`#pragma omp for` inside `f`) share out their
/// iterations; with one thread, on the calling thread outside any region,
/// where the same loops run whole (an orphaned `omp for`), in the same
/// order. Why: libgomp sets up a team for a region of one thread as well and
/// ends it with a futex wake-up, a system call, whoever waits: about 1.4 us
/// a region on the virtual machines measured here, and a step of the 2D
/// paper mesh, which the thread chooser runs on one thread, enters some 75
/// of them (`strace -c -f spring-motion deform ...` counts the futex calls).
/// Called inside a parallel region (a caller's own threads each
/// moving a mesh), a team of one is a region again: there an orphaned loop
/// would share its iterations among the caller's threads.
template <class F>
void in_team(int threads, F&& f)
{
#ifdef _OPENMP
  if(threads > 1 || omp_get_level() > 0) {
#pragma omp parallel num_threads(threads > 1 ? threads : 1)
    f();
    return;
  }
#else
  (void)threads;
#endif
  f();
}

/// Runs `f` on the calling thread inside a parallel region of `threads`
/// threads (OpenMP's default when 0) whose other threads do nothing, and
/// returns the count of threads that ran the region, once all have. Why: a
/// team's threads start the first time a region asks for them, which can
/// take milliseconds (a new thread may wait for a scheduler tick); serial
/// work given as `f` (reading the mesh) hides it. An exception from `f` is
/// thrown again after the region.
///
/// A thread found on the core of the calling thread moves off it, while
/// the calling thread yields its core until each has. On a virtual machine
/// Linux counts an idle virtual core that the host has descheduled as busy,
/// and so may start or wake a team thread on the core of the thread that
/// asked for it; the two then take turns on that core, 4 ms (a scheduler
/// tick) at a time, until the load balancer moves one: 4 to 20 ms for the
/// first team step after one-thread steps on the 2D paper mesh, whose steps
/// take 1 ms.
template <class F>
int run_while_team_starts(int threads, F&& f)
{
#ifdef _OPENMP
  const int team = thread_count(threads);
  if(team > 1) {
    std::atomic<int> placed{0}; // the other threads, each once it has checked its core
    int caller_cpu = -1;
    bool caller_done = false;
    std::mutex m;
    std::condition_variable done;
    std::exception_ptr error;
#pragma omp parallel num_threads(team)
    {
      const int others = omp_get_num_threads() - 1;
      if(omp_get_thread_num() == 0) {
        try {
          f();
        } catch(...) {
          error = std::current_exception();
        }
        {
          const std::lock_guard<std::mutex> lock(m);
          caller_cpu = current_cpu();
          caller_done = true;
        }
        done.notify_all();
        while(placed.load() < others)
          yield_core();
      } else {
        // asleep while `f` runs (reading a large mesh takes seconds)
        std::unique_lock<std::mutex> lock(m);
        done.wait(lock, [&] { return caller_done; });
        const int cpu = caller_cpu;
        lock.unlock();
        if(cpu >= 0 && current_cpu() == cpu)
          move_off_cpu(cpu);
        ++placed;
      }
    }
    if(error)
      std::rethrow_exception(error);
    return placed.load() + 1;
  }
#else
  (void)threads;
#endif
  f();
  return 1;
}

/// Starts (or wakes) an OpenMP team of `threads` threads and returns the
/// count that ran, once every one of them has.
inline int start_team(int threads)
{
  return run_while_team_starts(threads, [] {});
}

/// The CPU time of the calling thread in seconds, or -1 where the platform
/// does not tell (the thread chooser then never sees crowded cores).
inline double thread_cpu_seconds()
{
#ifdef CLOCK_THREAD_CPUTIME_ID
  timespec ts;
  if(clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts) == 0)
    return double(ts.tv_sec) + 1e-9 * double(ts.tv_nsec);
#endif
  return -1;
}

} // namespace internal
} // namespace spring_motion

#endif
