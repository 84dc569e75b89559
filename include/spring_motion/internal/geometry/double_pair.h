// Copyright (c) 2026 SpringMotion developers.
#ifndef SPRING_MOTION_INTERNAL_GEOMETRY_DOUBLE_PAIR_H
#define SPRING_MOTION_INTERNAL_GEOMETRY_DOUBLE_PAIR_H

#include <array>
#include <cmath>
#include <cstddef>
#include <type_traits>

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
#endif

inline double lane_abs(double v) { return std::abs(v); }

/// v in every lane of T.
template <class T>
inline T lanes_of(double v)
{
  if constexpr(std::is_same_v<T, double>)
    return v;
  else
    return T{v, v};
}

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
