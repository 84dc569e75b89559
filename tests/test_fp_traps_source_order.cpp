// Copyright (c) 2026 SpringMotion developers.
// Floating point, in the order the source writes it: the tests here are
// compiled without optimisation (tests/CMakeLists.txt), so every product a
// function's source forms is formed where it is written. Optimised, GCC
// moved products that overflow below the branch that skips them, and the
// same test passed in the optimised suite while the function trapped when
// built on its own at -O2 or in a debug build. The traps are those of
// tests/test_fp_traps.cpp (tests/fp_traps.h).
#include <spring_motion/internal/geometry/angles.h>

#include "fp_traps.h"

#include <catch2/catch.hpp>

#include <array>
#include <cfenv>
#include <cstddef>

using namespace spring_motion;
using spring_motion_test::Fp_traps;
using spring_motion_test::trapped;

TEST_CASE("fp traps: the per-step quality's pass-over test on tiny, huge and degenerate elements", "[fp]")
{
  // Scales from 1e-150 to 1e100: the test's products of squared lengths
  // and areas or volumes (eighth powers of the coordinates in 3D) would
  // overflow above about 1e38; out of its range it must answer false
  // (decide nothing) without forming them.
  Fp_traps traps;
  REQUIRE((fegetexcept() & trapped) == trapped);
  const std::array<std::array<double, 2>, 3> triangles[] = {{{{0, 0}, {1, 0}, {0, 1}}},  // right isosceles
                                                            {{{0, 0}, {1, 0}, {2, 0}}},  // flat
                                                            {{{0, 0}, {0, 0}, {0, 0}}}}; // a point
  const std::array<std::array<double, 3>, 4> tetrahedra[] = {{{{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}}},
                                                             {{{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {1, 1, 0}}},
                                                             {{{2, 2, 2}, {2, 2, 2}, {2, 2, 2}, {2, 2, 2}}}};
  for(const double scale : {1e-150, 1e-40, 1e-20, 1.0, 1e20, 1e40, 1e100}) {
    INFO("scale " << scale);
    // well shaped and within the range: decided; else never passed over
    const bool decidable = scale >= 1e-20 && scale <= 1e20;
    const auto scaled = [scale](auto corners) {
      for(auto& q : corners)
        for(auto& x : q)
          x *= scale;
      return corners;
    };
    for(std::size_t s = 0; s < 3; ++s) {
      const auto t = scaled(triangles[s]);
      CHECK(internal::element_sines_squared_above<2>(t, 0.4) == (decidable && s == 0));
      CHECK(internal::element_sines_squared_above<2>(t, 0.4, 0.9) == (decidable && s == 0));
      const auto p = scaled(tetrahedra[s]);
      CHECK(internal::element_sines_squared_above<3>(p, 0.6) == (decidable && s == 0));
      CHECK(internal::element_sines_squared_above<3>(p, 0.6, 0.9) == (decidable && s == 0));
    }
  }
}
