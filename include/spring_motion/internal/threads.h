// Copyright (c) 2026 SpringMotion developers.
#ifndef SPRING_MOTION_INTERNAL_THREADS_H
#define SPRING_MOTION_INTERNAL_THREADS_H

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

} // namespace internal
} // namespace spring_motion

#endif
