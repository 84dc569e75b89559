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
#include <spring_motion/internal/geometry/double_pair.h>

#include <catch2/catch.hpp>

#include <algorithm>
#include <array>
#include <cfenv>
#include <cmath>
#include <cstring>
#include <limits>
#include <random>
#include <vector>

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

namespace {
// The capped operations as first written (a library ilogb, a division in
// every capped product): the fast paths must give the same bits.
double reference_pow(double x, double e)
{
  if(x == 0)
    return e > 0 ? 0.0 : (e == 0 ? 1.0 : max_stiffness);
  if(std::abs(e) * double(std::abs(std::ilogb(x)) + 1) < 800) {
    const double a = std::abs(e);
    if(a == 1 || a == 2 || a == 3 || a == 4) {
      const double x2 = x * x;
      const double p = a == 1 ? x : a == 2 ? x2 : a == 3 ? x2 * x : x2 * x2;
      return e > 0 ? p : 1.0 / p;
    }
    return std::pow(x, e);
  }
  if(e * std::log(x) >= std::log(max_stiffness))
    return max_stiffness;
  return std::min(std::pow(x, e), max_stiffness);
}
double reference_product(double a, double b)
{
  if(b > 0 && a >= max_stiffness / b)
    return max_stiffness;
  return std::min(a * b, max_stiffness);
}
bool same_bits(double a, double b) { return std::memcmp(&a, &b, sizeof a) == 0; }
} // namespace

TEST_CASE("capped_math: the exponent from the bits and the division-free product give the same bits",
          "[stiffness][capped]")
{
  std::mt19937_64 random(7);
  std::uniform_real_distribution<double> mantissa(1.0, 2.0);
  std::uniform_int_distribution<int> exponent(-1074, 1023);
  const double exponents[] = {1, 2, 3, 4, -1, -2, -3, -4, 0.5, -0.75, -0.76, 2.5, -3.7};
  std::size_t pow_same = 0, product_same = 0, exponent_same = 0, n = 0;
  for(int i = 0; i < 200000; ++i) {
    const double x = std::ldexp(mantissa(random), exponent(random)); // normal and subnormal
    const double y = std::ldexp(mantissa(random), exponent(random));
    exponent_same += binary_exponent(x) == std::ilogb(x);
    const double e = exponents[std::size_t(i) % (sizeof exponents / sizeof exponents[0])];
    pow_same += same_bits(capped_pow(x, e), reference_pow(x, e));
    product_same += same_bits(capped_product(x, y), reference_product(x, y));
    ++n;
  }
  CHECK(exponent_same == n);
  CHECK(pow_same == n);
  CHECK(product_same == n);
  // around the product's shortcut (a b near 2^801) and the cap (1e250)
  for(double a : {std::ldexp(1.0, 400), std::ldexp(1.5, 400), 1e125, std::nextafter(1e125, 2e125)})
    for(double b : {std::ldexp(1.0, 399), std::ldexp(1.9, 399), std::ldexp(1.0, 400), 1e125, 1e124,
                    std::nextafter(1e125, 0.0), 0.0}) {
      INFO(a << " * " << b);
      CHECK(same_bits(capped_product(a, b), reference_product(a, b)));
    }
  // around the power's shortcut (2^-198, 2^198) and the bound of its
  // products (|e| (|ilogb x| + 1) = 800), every exponent, with no overflow
  // (the reference squares x for |e| = 1 too, which may overflow: it is
  // called after the overflow flag is read)
  for(double e : exponents)
    for(int k : {-798, -400, -266, -265, -199, -198, -197, 197, 198, 199, 265, 266, 399, 400, 798, 799})
      for(double x : {std::ldexp(1.0, k), std::nextafter(std::ldexp(1.0, k), 0.0), std::ldexp(1.7, k)}) {
        INFO(x << " ^ " << e);
        std::feclearexcept(FE_OVERFLOW);
        const double got = capped_pow(x, e);
        CHECK(std::fetestexcept(FE_OVERFLOW) == 0);
        CHECK(same_bits(got, reference_pow(x, e)));
      }
  for(double a : {std::ldexp(1.0, 398), std::nextafter(std::ldexp(1.0, 399), 0.0), std::ldexp(1.0, 399)})
    for(double b : {std::ldexp(1.0, 398), std::nextafter(std::ldexp(1.0, 399), 0.0), std::ldexp(1.0, 399), 1e-300}) {
      INFO(a << " * " << b);
      CHECK(same_bits(capped_product(a, b), reference_product(a, b)));
    }
  CHECK(binary_exponent(std::numeric_limits<double>::denorm_min()) == -1074);
  CHECK(binary_exponent(std::numeric_limits<double>::infinity()) == 1024);
  CHECK(binary_exponent(1.0) == 0);
  CHECK(binary_exponent(0.75) == -1);
}

TEST_CASE("capped_math: all_finite from the bits agrees with std::isfinite", "[stiffness][capped]")
{
  using limits = std::numeric_limits<double>;
  // the values next to the boundary between finite and not, either sign
  const double specials[] = {limits::quiet_NaN(), -limits::quiet_NaN(), limits::signaling_NaN(), limits::infinity(),
                             -limits::infinity(), limits::max(),        -limits::max(),          limits::denorm_min(),
                             -limits::denorm_min(), limits::min(),      0.0,                     -0.0,
                             1.0,                   std::ldexp(1.0, 1023), std::ldexp(1.5, 1023)};
  std::mt19937_64 random(11);
  std::uniform_real_distribution<double> value(-1e3, 1e3);
  std::vector<double> v(144);
  std::size_t agree = 0, flagged = 0, n = 0;
  for(const double s : specials)
    for(std::size_t at = 0; at < v.size(); ++at)
      for(std::size_t length : {v.size(), at + 1, std::size_t(1) + at / 2}) {
        for(double& x : v)
          x = value(random);
        v[at] = s;
        const bool expected =
            std::all_of(v.begin(), v.begin() + long(length), [](double x) { return std::isfinite(x); });
        agree += all_finite(v.data(), length) == expected;
        flagged += !expected;
        ++n;
      }
  CHECK(agree == n);
  CHECK(flagged > n / 10); // non-finite values are tested (and, past the range's end, ignored)
  CHECK(all_finite(v.data(), 0));
}

#if SPRING_MOTION_HAS_DOUBLE_PAIR
// Lane_finiteness over N values of T (L lanes): each special value in each
// of the N places of each lane, the other values random and finite. Counts
// of lanes whose flag agrees with std::isfinite, of lanes that hold a value
// that is not finite, and of lanes tested. Always inlined, so that the
// four-lane form runs inside a function compiled for AVX.
template <class T, std::size_t L, std::size_t N>
SPRING_MOTION_LANES_INLINE std::array<std::size_t, 3> lane_finiteness_counts(const double* specials,
                                                                             const bool* finite, std::size_t count)
{
  std::mt19937_64 random(13);
  std::uniform_real_distribution<double> value(-1e3, 1e3);
  std::array<T, N> v;
  std::size_t agree = 0, flagged = 0, n = 0;
  for(std::size_t k = 0; k < count; ++k)
    for(std::size_t at = 0; at < N; ++at)
      for(std::size_t lane = 0; lane < L; ++lane) {
        for(T& x : v)
          for(std::size_t l = 0; l < L; ++l)
            x[l] = value(random);
        v[at][lane] = specials[k];
        Lane_finiteness<T> f;
        for(const T& x : v)
          f.add(x);
        for(std::size_t l = 0; l < L; ++l) {
          const bool expected = l != lane || finite[k];
          agree += f.finite(l) == expected;
          flagged += !expected;
          ++n;
        }
      }
  return {agree, flagged, n};
}

std::array<std::size_t, 3> pair_counts(const double* specials, const bool* finite, std::size_t count)
{
  return lane_finiteness_counts<Double_pair, 2, 60>(specials, finite, count);
}

#if SPRING_MOTION_HAS_DOUBLE_QUAD
__attribute__((target("avx"))) std::array<std::size_t, 3> quad_counts(const double* specials, const bool* finite,
                                                                      std::size_t count)
{
  return lane_finiteness_counts<Double_quad, 4, 60>(specials, finite, count);
}
#endif

TEST_CASE("capped_math: Lane_finiteness flags exactly the lanes with a value that is not finite",
          "[stiffness][capped]")
{
  using limits = std::numeric_limits<double>;
  const double specials[] = {limits::quiet_NaN(), -limits::quiet_NaN(), limits::signaling_NaN(),
                             limits::infinity(),  -limits::infinity(),  limits::max(),
                             -limits::max(),      limits::denorm_min(), -limits::denorm_min(),
                             0.0,                 -0.0,                 std::ldexp(1.5, 1023)};
  constexpr std::size_t count = std::size(specials);
  // (std::isfinite of a signalling NaN may itself raise FE_INVALID: asked
  // before the flags are cleared)
  bool finite[count];
  for(std::size_t k = 0; k < count; ++k)
    finite[k] = std::isfinite(specials[k]);
  auto check = [&](const std::array<std::size_t, 3>& c, std::size_t lanes) {
    const auto [agree, flagged, n] = c;
    CHECK(agree == n);
    CHECK(flagged == 5 * 60 * lanes); // each of the five in each place of each lane
    CHECK(n == count * 60 * lanes * lanes);
  };
  std::feclearexcept(FE_ALL_EXCEPT);
  SECTION("two lanes") { check(pair_counts(specials, finite, count), 2); }
#if SPRING_MOTION_HAS_DOUBLE_QUAD
  SECTION("four lanes")
  {
    if(!four_lanes_available()) {
      WARN("this processor has no AVX: the four-lane test is not run");
      return;
    }
    check(quad_counts(specials, finite, count), 4);
  }
#endif
  // the arithmetic flags nothing, so it cannot trap under feenableexcept
  CHECK(std::fetestexcept(FE_INVALID | FE_OVERFLOW | FE_DIVBYZERO) == 0);
}
#endif
