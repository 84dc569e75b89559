// Copyright (c) 2026 SpringMotion developers.
#ifndef SPRING_MOTION_INTERNAL_SOLVER_THREADS_H
#define SPRING_MOTION_INTERNAL_SOLVER_THREADS_H

#include <cstddef>
#include <time.h>

#ifdef _OPENMP
#include <omp.h>
#endif

namespace spring_motion {
namespace internal {

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

/// Starts (or wakes) an OpenMP team of `threads` threads and returns once
/// every one of them has run.
inline void start_team(int threads)
{
#ifdef _OPENMP
#pragma omp parallel num_threads(threads)
  {
  }
#else
  (void)threads;
#endif
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
