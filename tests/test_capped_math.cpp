// Capped arithmetic of the built-in stiffness models
// (include/spring_motion/internal/geometry/capped_math.h): it is machinery, so the
// public concept header must not carry it, and within the cap it returns what
// the plain operation returns.
#include <spring_motion/stiffness/Stiffness_model.h>

// Qualified lookup of internal::capped_pow sees the probe below only when the
// namespace itself declares no capped_pow, i.e. when Stiffness_model.h does
// not drag the machinery into the public interface.
namespace capped_math_probe {
struct Absent {};
template <class... A>
Absent capped_pow(A...);
} // namespace capped_math_probe
namespace spring_motion {
namespace internal {
using namespace capped_math_probe;
}
} // namespace spring_motion
static_assert(std::is_same<decltype(spring_motion::internal::capped_pow(2.0, 3.0)), capped_math_probe::Absent>::value,
              "Stiffness_model.h must not declare the capped arithmetic");

#include <spring_motion/internal/geometry/capped_math.h>

#include <catch2/catch.hpp>

#include <cfenv>
#include <cmath>
#include <limits>

using namespace spring_motion::internal;

TEST_CASE("capped_math: exact below the cap, the cap above it, no overflow on the way", "[stiffness][capped]")
{
  static_assert(std::is_same<decltype(spring_motion::internal::capped_pow(2.0, 3.0)), double>::value,
                "capped_math.h declares capped_pow");
  std::feclearexcept(FE_OVERFLOW);
  CHECK(capped_pow(2.0, 3.0) == 8.0);
  CHECK(capped_pow(2.0, -2.0) == 0.25);
  CHECK(capped_pow(3.0, 0.5) == std::pow(3.0, 0.5));
  CHECK(capped_pow(0.0, -1.0) == max_stiffness);
  CHECK(capped_pow(0.0, 2.0) == 0.0);
  CHECK(capped_pow(1e-200, -2.0) == max_stiffness);
  CHECK(capped_pow(1e300, 4.0) == max_stiffness);
  CHECK(capped_quotient(1.0, 4.0) == 0.25);
  CHECK(capped_quotient(1e300, 1e-300) == max_stiffness);
  CHECK(capped_product(3.0, 4.0) == 12.0);
  CHECK(capped_product(1e200, 1e200) == max_stiffness);
  CHECK(std::fetestexcept(FE_OVERFLOW) == 0);
  CHECK(inverse_sin_squared(std::acos(0.0)) == Approx(1.0).epsilon(1e-15));
  CHECK(inverse_sin_squared(std::asin(0.5)) == Approx(4.0).epsilon(1e-14));
  CHECK(inverse_sin_squared(0.0) == Approx(1e200).epsilon(1e-15));
  CHECK(cap_stiffness(std::numeric_limits<double>::infinity()) == max_stiffness);
}
