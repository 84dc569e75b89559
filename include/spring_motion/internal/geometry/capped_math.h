// Copyright (c) 2026 SpringMotion developers.
#ifndef SPRING_MOTION_INTERNAL_GEOMETRY_CAPPED_MATH_H
#define SPRING_MOTION_INTERNAL_GEOMETRY_CAPPED_MATH_H

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <cstring>

namespace spring_motion {
namespace internal {

/// Stiffness values of the built-in models are capped here: large enough to
/// freeze a collapsing element in place, small enough that a vertex's sum of
/// a hundred such springs stays finite.
constexpr double max_stiffness = 1e250;

/// 1/sin^2(theta), with sin^2 floored so an angle of exactly 0 or pi gives the
/// cap instead of infinity. Such an angle means the element is already flat:
/// the validity check rejects that state before its stiffness is ever used,
/// so the floor only guards round-off.
inline double inverse_sin_squared(double theta)
{
  const double s = std::sin(theta);
  return 1.0 / std::max(s * s, 1e-200);
}

inline double cap_stiffness(double k) { return std::min(k, max_stiffness); }

// The capped operations below give min(result, max_stiffness) without ever
// computing an overflowing intermediate (an overflow is an FE_OVERFLOW trap
// under feenableexcept even when the cap would clip it). Within the cap they
// return exactly what the plain operation returns.

/// std::ilogb(x) for a finite x != 0, read from the bits where x is normal
/// (the library call cost as much as the rest of a grid-scaled spring's
/// capping); 1024 for an infinite or NaN x.
inline int binary_exponent(double x)
{
  std::uint64_t bits;
  std::memcpy(&bits, &x, sizeof bits);
  const int biased = int((bits >> 52) & 0x7ff);
  if(biased == 0x7ff)
    return 1024;
  return biased != 0 ? biased - 1023 : std::ilogb(x);
}

/// Whether the n values at v are all finite, read from the bits: a value is
/// infinite or NaN exactly when its exponent field is all ones, and adding one
/// to that field then carries into the sign bit. The loop has no branch and
/// no floating-point operation (nothing to trap), so it runs as vector integer
/// operations: a loop of std::isfinite over an element matrix of a tetrahedron
/// was a third of the time spent scattering it.
inline bool all_finite(const double* v, std::size_t n)
{
  constexpr std::uint64_t exponent = 0x7ff0000000000000u, one = 0x0010000000000000u;
  std::uint64_t carries = 0;
  for(std::size_t i = 0; i < n; ++i) {
    std::uint64_t bits;
    std::memcpy(&bits, v + i, sizeof bits);
    carries |= (bits & exponent) + one;
  }
  return (carries >> 63) == 0;
}

/// min(x^e, max_stiffness) for x >= 0.
inline double capped_pow(double x, double e)
{
  if(x == 0)
    return e > 0 ? 0.0 : (e == 0 ? 1.0 : max_stiffness);
  // |log2 x| <= |ilogb x| + 1, so below this bound x^e lies in (2^-800,
  // 2^800), far inside the cap: no log needed, and the models' usual
  // exponents (1 to 4, either sign) are a few products instead of pow
  // (within 2 ulp of it; pow is what stiffness costs most)
  if(std::abs(e) * double(std::abs(binary_exponent(x)) + 1) < 800) {
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
/// min(a / b, max_stiffness) for a >= 0, b > 0.
inline double capped_quotient(double a, double b)
{
  if(a / max_stiffness >= b)
    return max_stiffness;
  return std::min(a / b, max_stiffness);
}
/// min(a b, max_stiffness) for a, b >= 0 and finite.
inline double capped_product(double a, double b)
{
  // a b < 2^801, far below the cap: the product, without the division
  if(a > 0 && b > 0 && binary_exponent(a) + binary_exponent(b) < 800)
    return a * b;
  if(b > 0 && a >= max_stiffness / b)
    return max_stiffness;
  return std::min(a * b, max_stiffness);
}

} // namespace internal
} // namespace spring_motion

#endif
