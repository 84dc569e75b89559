// Copyright (c) 2026 SpringMotion developers.
#ifndef SPRING_MOTION_INTERNAL_GEOMETRY_DOUBLE_PAIR_H
#define SPRING_MOTION_INTERNAL_GEOMETRY_DOUBLE_PAIR_H

#include <cmath>
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

} // namespace internal
} // namespace spring_motion

#endif
