// Copyright (c) 2026 SpringMotion developers.
#ifndef SPRING_MOTION_INTERNAL_GEOMETRY_CAPPED_MATH_H
#define SPRING_MOTION_INTERNAL_GEOMETRY_CAPPED_MATH_H

#include <algorithm>
#include <array>
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

/// min(x^e, max_stiffness) for x >= 0, with what depends on e alone (its
/// size, whether it is a small whole number) worked out when made: a loop
/// that raises many values to one exponent then tests only x.
class Capped_power
{
public:
  explicit Capped_power(double e)
      : e_(e), a_(std::abs(e)), whole_(a_ == 1 ? 1 : a_ == 2 ? 2 : a_ == 3 ? 3 : a_ == 4 ? 4 : 0)
  {}

  double operator()(double x) const
  {
    // the usual case first, tested by two comparisons: from x in [2^-198,
    // 2^198) the test below gives |e| (|ilogb x| + 1) <= 4 * 199 < 800
    if(whole_ != 0 && x >= 0x1p-198 && x < 0x1p198)
      return whole_power(x);
    if(x == 0)
      return e_ > 0 ? 0.0 : (e_ == 0 ? 1.0 : max_stiffness);
    // |log2 x| <= |ilogb x| + 1, so below this bound x^e lies in (2^-800,
    // 2^800), far inside the cap: no log needed, and the models' usual
    // exponents (1 to 4, either sign) are a few products instead of pow
    // (within 2 ulp of it; pow is what stiffness costs most)
    if(a_ * double(std::abs(binary_exponent(x)) + 1) < 800)
      return whole_ != 0 ? whole_power(x) : std::pow(x, e_);
    if(e_ * std::log(x) >= std::log(max_stiffness))
      return max_stiffness;
    return std::min(std::pow(x, e_), max_stiffness);
  }

private:
  // x^e for |e| = whole_, from the products x^|e| needs and no others (x^4
  // of an x whose x^1 is in range may overflow)
  double whole_power(double x) const
  {
    double p = x;
    switch(whole_) {
    case 2: p = x * x; break;
    case 3: p = x * x * x; break;
    case 4: {
      const double x2 = x * x;
      p = x2 * x2;
      break;
    }
    default: break;
    }
    return e_ > 0 ? p : 1.0 / p;
  }

  double e_, a_;
  int whole_; // |e| when it is 1, 2, 3 or 4, else 0
};

/// min(x^e, max_stiffness) for x >= 0.
inline double capped_pow(double x, double e) { return Capped_power(e)(x); }

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
  // a b < 2^801, far below the cap: the product, without the division;
  // by comparisons alone where they decide (a, b < 2^399: exponents at most
  // 398 each), else from the exponents
  if(a > 0 && b > 0 && ((a < 0x1p399 && b < 0x1p399) || binary_exponent(a) + binary_exponent(b) < 800))
    return a * b;
  if(b > 0 && a >= max_stiffness / b)
    return max_stiffness;
  return std::min(a * b, max_stiffness);
}

} // namespace internal
} // namespace spring_motion

#endif
