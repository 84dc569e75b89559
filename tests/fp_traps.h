// Copyright (c) 2026 SpringMotion developers.
// Floating-point traps for the tests that run the library under them.
#ifndef SPRING_MOTION_TESTS_FP_TRAPS_H
#define SPRING_MOTION_TESTS_FP_TRAPS_H

#include <cfenv>

#ifdef _OPENMP
#include <omp.h>
#endif

namespace spring_motion_test {

constexpr int trapped = FE_INVALID | FE_DIVBYZERO | FE_OVERFLOW;

// Enables the traps in this thread and in every OpenMP worker (the trap mask
// is per thread), and clears them again at the end of the test.
struct Fp_traps
{
  Fp_traps() { set(true); }
  ~Fp_traps() { set(false); }
  static void set(bool on)
  {
    auto apply = [on] {
      std::feclearexcept(FE_ALL_EXCEPT);
      if(on)
        feenableexcept(trapped);
      else
        fedisableexcept(trapped);
    };
    apply();
#ifdef _OPENMP
#pragma omp parallel
    apply();
#endif
  }
};

} // namespace spring_motion_test

#endif
