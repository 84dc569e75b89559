// Copyright (c) 2026 SpringMotion developers.
#ifndef SPRING_MOTION_INTERNAL_GEOMETRY_DOUBLE_PAIR_H
#define SPRING_MOTION_INTERNAL_GEOMETRY_DOUBLE_PAIR_H

#include <array>
#include <cmath>
#include <cstddef>
#include <type_traits>
#if defined(__GNUC__) && defined(__x86_64__)
#include <immintrin.h>
#endif

// Two elements' arithmetic in the two lanes of one SSE2 register, through
// GCC's vector extension (which Clang also reads). The library builds for
// the baseline x86-64 instruction set, whose vectors hold two doubles; GCC
// does not vectorise an element kernel's scalar code by itself. Each lane
// runs the same IEEE operations in the same order as the scalar code, so
// the results are the same bits. A kernel written once over a lane type T
// (double or Double_pair) with the helpers below serves both.
#if defined(__GNUC__)
#define SPRING_MOTION_HAS_DOUBLE_PAIR 1
#else
#define SPRING_MOTION_HAS_DOUBLE_PAIR 0
#endif

// Four elements in the four lanes of one AVX register, on processors that
// have AVX (four_lanes_available(), asked at run time: the build still runs
// on any x86-64 machine). A kernel's four-lane form is called only from a
// function compiled for AVX (target attribute) into which the kernel is
// always inlined; the helpers that take or return a four-lane value are
// compiled for AVX themselves, so such a value never passes between code
// of the two instruction sets. GCC still warns that the kernel's calls of
// them would pass it differently without AVX (-Wpsabi): silenced around
// the kernels that have a four-lane form, and only there. Each lane runs
// the scalar code's IEEE operations in its order (AVX alone brings no fused
// multiply-add), so the values are the same bits.
#if SPRING_MOTION_HAS_DOUBLE_PAIR && defined(__x86_64__)
#define SPRING_MOTION_HAS_DOUBLE_QUAD 1
#else
#define SPRING_MOTION_HAS_DOUBLE_QUAD 0
#endif

#if defined(__GNUC__)
#define SPRING_MOTION_LANES_INLINE inline __attribute__((always_inline))
#define SPRING_MOTION_LANES_STATIC static inline __attribute__((always_inline)) // the same, for static members
#else
#define SPRING_MOTION_LANES_INLINE inline
#define SPRING_MOTION_LANES_STATIC static inline
#endif

namespace spring_motion {
namespace internal {

#if SPRING_MOTION_HAS_DOUBLE_PAIR
typedef double Double_pair __attribute__((vector_size(16)));
typedef long long Double_pair_mask __attribute__((vector_size(16)));

inline Double_pair lane_abs(Double_pair v)
{
  // std::abs's result: the sign bit cleared
  return Double_pair(Double_pair_mask(v) & ~Double_pair_mask(Double_pair{-0.0, -0.0}));
}

/// std::sqrt of each lane (of a positive finite value: no errno to set),
/// one instruction for all lanes where there is one; IEEE square roots are
/// correctly rounded, so the same bits as the scalar code's.
inline Double_pair lane_sqrt(Double_pair v)
{
#if defined(__x86_64__)
  return Double_pair(_mm_sqrt_pd(__m128d(v)));
#else
  return Double_pair{std::sqrt(v[0]), std::sqrt(v[1])};
#endif
}
#endif

#if SPRING_MOTION_HAS_DOUBLE_QUAD
typedef double Double_quad __attribute__((vector_size(32)));
typedef long long Double_quad_mask __attribute__((vector_size(32)));

__attribute__((target("avx"))) inline Double_quad lane_abs(Double_quad v)
{
  return Double_quad(Double_quad_mask(v) & ~Double_quad_mask(Double_quad{-0.0, -0.0, -0.0, -0.0}));
}

__attribute__((target("avx"))) inline Double_quad lane_sqrt(Double_quad v)
{
  return Double_quad(_mm256_sqrt_pd(__m256d(v)));
}

/// Whether this processor (and its operating system) runs AVX code: the
/// kernels four elements at a time are called only then.
inline bool four_lanes_available()
{
  static const bool avx = __builtin_cpu_supports("avx");
  return avx;
}
#else
inline bool four_lanes_available() { return false; }
#endif

SPRING_MOTION_LANES_INLINE double lane_abs(double v) { return std::abs(v); }
SPRING_MOTION_LANES_INLINE double lane_sqrt(double v) { return std::sqrt(v); }

/// v in every lane of T.
template <class T>
SPRING_MOTION_LANES_INLINE T lanes_of(double v)
{
  if constexpr(std::is_same_v<T, double>)
    return v;
  else
    return T{v, v};
}

#if SPRING_MOTION_HAS_DOUBLE_QUAD
template <>
__attribute__((target("avx"))) inline Double_quad lanes_of<Double_quad>(double v)
{
  return Double_quad{v, v, v, v};
}
#endif

// Lane l of the L vectors a, b, ... stored as L consecutive values at
// out[l] + k: the lanes transposed in registers, one store per lane instead
// of one per value. Stored value by value, an element's 60 blocks took 240
// stores per four tetrahedra, and the 16-byte loads that read them next
// waited for the stores to reach the cache (a load that spans two stores is
// not forwarded from them).
#if SPRING_MOTION_HAS_DOUBLE_PAIR
#if defined(__clang__)
#define SPRING_MOTION_SHUFFLE(a, b, M, ...) __builtin_shufflevector(a, b, __VA_ARGS__)
#else
#define SPRING_MOTION_SHUFFLE(a, b, M, ...) __builtin_shuffle(a, b, M{__VA_ARGS__})
#endif

SPRING_MOTION_LANES_INLINE void store_transposed(const Double_pair& a, const Double_pair& b,
                                                 const std::array<double*, 2>& out, std::size_t k)
{
  const Double_pair first = SPRING_MOTION_SHUFFLE(a, b, Double_pair_mask, 0, 2);
  const Double_pair second = SPRING_MOTION_SHUFFLE(a, b, Double_pair_mask, 1, 3);
  typedef double Unaligned __attribute__((vector_size(16), aligned(8), may_alias));
  *reinterpret_cast<Unaligned*>(out[0] + k) = first;
  *reinterpret_cast<Unaligned*>(out[1] + k) = second;
}
#endif

#if SPRING_MOTION_HAS_DOUBLE_QUAD
// (always inlined into the four-lane kernel, so compiled for AVX with it)
SPRING_MOTION_LANES_INLINE void store_transposed(const Double_quad& a, const Double_quad& b, const Double_quad& c,
                                                 const Double_quad& d, const std::array<double*, 4>& out,
                                                 std::size_t k)
{
  const Double_quad ab_even = SPRING_MOTION_SHUFFLE(a, b, Double_quad_mask, 0, 4, 2, 6); // a0 b0 a2 b2
  const Double_quad ab_odd = SPRING_MOTION_SHUFFLE(a, b, Double_quad_mask, 1, 5, 3, 7);  // a1 b1 a3 b3
  const Double_quad cd_even = SPRING_MOTION_SHUFFLE(c, d, Double_quad_mask, 0, 4, 2, 6);
  const Double_quad cd_odd = SPRING_MOTION_SHUFFLE(c, d, Double_quad_mask, 1, 5, 3, 7);
  // stored as they are, not through a copy (which went by the stack)
  typedef double Unaligned __attribute__((vector_size(32), aligned(8), may_alias));
  *reinterpret_cast<Unaligned*>(out[0] + k) = SPRING_MOTION_SHUFFLE(ab_even, cd_even, Double_quad_mask, 0, 1, 4, 5);
  *reinterpret_cast<Unaligned*>(out[1] + k) = SPRING_MOTION_SHUFFLE(ab_odd, cd_odd, Double_quad_mask, 0, 1, 4, 5);
  *reinterpret_cast<Unaligned*>(out[2] + k) = SPRING_MOTION_SHUFFLE(ab_even, cd_even, Double_quad_mask, 2, 3, 6, 7);
  *reinterpret_cast<Unaligned*>(out[3] + k) = SPRING_MOTION_SHUFFLE(ab_odd, cd_odd, Double_quad_mask, 2, 3, 6, 7);
}
#endif

/// Per lane, whether every value passed to add() was finite, read from the
/// bits: a value's exponent field alone, as a double, is +inf exactly when
/// the value is infinite or NaN and a finite power of two or 0 otherwise,
/// so the largest of them is +inf in a lane exactly when one of its values
/// was not. Neither operation can trap (no operand is a NaN). For a
/// kernel's values while they are in its registers: tested after they were
/// stored, the 60 values of a ball-vertex tetrahedron took 15 loads, and
/// the test held 4% of a one-thread ball-vertex run on the wing (perf).
template <class T>
struct Lane_finiteness;

#if SPRING_MOTION_HAS_DOUBLE_PAIR
template <>
struct Lane_finiteness<Double_pair>
{
  Double_pair largest = {0.0, 0.0};
  SPRING_MOTION_LANES_INLINE void add(const Double_pair& v)
  {
    const Double_pair_mask exponent = {0x7ff0000000000000ll, 0x7ff0000000000000ll};
    const Double_pair e = Double_pair(Double_pair_mask(v) & exponent);
    largest = largest > e ? largest : e;
  }
  SPRING_MOTION_LANES_INLINE bool finite(std::size_t l) const { return largest[l] != HUGE_VAL; }
};
#endif

#if SPRING_MOTION_HAS_DOUBLE_QUAD
template <>
struct Lane_finiteness<Double_quad>
{
  Double_quad largest = {0.0, 0.0, 0.0, 0.0};
  SPRING_MOTION_LANES_INLINE void add(const Double_quad& v)
  {
    const Double_quad_mask exponent = {0x7ff0000000000000ll, 0x7ff0000000000000ll, 0x7ff0000000000000ll,
                                       0x7ff0000000000000ll};
    const Double_quad e = Double_quad(Double_quad_mask(v) & exponent);
    largest = largest > e ? largest : e;
  }
  SPRING_MOTION_LANES_INLINE bool finite(std::size_t l) const { return largest[l] != HUGE_VAL; }
};
#endif

/// kernel(c, out), a kernel written over the lane type, on two inputs at
/// once, one per lane: `a` and `b` each point to C corners of N
/// coordinates, which fill c corner by corner; out holds M values. Without
/// the vector extension, one call per input on double lanes: the same
/// values.
template <int C, int N, int M, class Kernel>
inline std::array<std::array<double, M>, 2> in_two_lanes(const std::array<const double*, C>& a,
                                                          const std::array<const double*, C>& b, Kernel kernel)
{
  std::array<std::array<double, M>, 2> r;
#if SPRING_MOTION_HAS_DOUBLE_PAIR
  Double_pair c[C * N], out[M];
  for(int k = 0; k < C; ++k)
    for(int j = 0; j < N; ++j)
      c[N * k + j] = Double_pair{a[std::size_t(k)][j], b[std::size_t(k)][j]};
  kernel(c, out);
  for(std::size_t k = 0; k < std::size_t(M); ++k) {
    r[0][k] = out[k][0];
    r[1][k] = out[k][1];
  }
#else
  for(std::size_t t = 0; t < 2; ++t) {
    const auto& q = t == 0 ? a : b;
    double c[C * N], out[M];
    for(int k = 0; k < C; ++k)
      for(int j = 0; j < N; ++j)
        c[N * k + j] = q[std::size_t(k)][j];
    kernel(c, out);
    for(std::size_t k = 0; k < std::size_t(M); ++k)
      r[t][k] = out[k];
  }
#endif
  return r;
}

} // namespace internal
} // namespace spring_motion

#endif
