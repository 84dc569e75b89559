// Copyright (c) 2026 SpringMotion developers.
#ifndef SPRING_MOTION_INTERNAL_SOLVER_BLOCK_OPS_H
#define SPRING_MOTION_INTERNAL_SOLVER_BLOCK_OPS_H

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

#include <spring_motion/internal/geometry/double_pair.h>

#if defined(__SSE2__)
#include <emmintrin.h>
#endif
#if SPRING_MOTION_HAS_DOUBLE_QUAD
#include <immintrin.h>
#endif

namespace spring_motion {
namespace internal {

/// Requests the cache lines of [begin, end) for reading (no effect on any
/// value): rows whose order the hardware prefetcher does not follow.
template <class T>
inline void prefetch_range(const T* begin, const T* end)
{
#if defined(__GNUC__)
  for(const char* a = reinterpret_cast<const char*>(begin); a < reinterpret_cast<const char*>(end); a += 64)
    __builtin_prefetch(a);
#else
  (void)begin;
  (void)end;
#endif
}

/// The inverse of the D x D row-major block m, or false when m is singular
/// or not finite: |det m| must exceed a rounding error of the product of its
/// row norms (Hadamard's bound on |det m|), so the test does not depend on
/// the scale of the stiffness.
template <int D>
inline bool invert_block(const double* m, double* r)
{
  double det, bound = 1;
  for(int i = 0; i < D; ++i) {
    double s = 0;
    for(int j = 0; j < D; ++j)
      s += m[i * D + j] * m[i * D + j];
    bound *= std::sqrt(s);
  }
  if constexpr(D == 2) {
    det = m[0] * m[3] - m[1] * m[2];
    if(!(std::isfinite(det) && std::abs(det) > 64 * std::numeric_limits<double>::epsilon() * bound))
      return false;
    const double v[4] = {m[3] / det, -m[1] / det, -m[2] / det, m[0] / det};
    for(int k = 0; k < 4; ++k)
      r[k] = v[k];
  } else {
    const double c00 = m[4] * m[8] - m[5] * m[7], c01 = m[5] * m[6] - m[3] * m[8], c02 = m[3] * m[7] - m[4] * m[6];
    det = m[0] * c00 + m[1] * c01 + m[2] * c02;
    if(!(std::isfinite(det) && std::abs(det) > 64 * std::numeric_limits<double>::epsilon() * bound))
      return false;
    const double v[9] = {c00 / det, (m[2] * m[7] - m[1] * m[8]) / det, (m[1] * m[5] - m[2] * m[4]) / det,
                         c01 / det, (m[0] * m[8] - m[2] * m[6]) / det, (m[2] * m[3] - m[0] * m[5]) / det,
                         c02 / det, (m[1] * m[6] - m[0] * m[7]) / det, (m[0] * m[4] - m[1] * m[3]) / det};
    for(int k = 0; k < 9; ++k)
      r[k] = v[k];
  }
  return std::isfinite(bound);
}

/// The inverse of the symmetric N x N row-major block m by Cholesky's
/// factorisation, or false when a pivot is not positive beyond rounding
/// (below 1e-12 of its diagonal entry): m is not positive definite.
/// `weakest`, if given, becomes the least ratio of a pivot to its diagonal
/// entry (how nearly singular m is).
template <int N>
inline bool invert_spd_block(const double* m, double* r, double* weakest = nullptr)
{
  double l[N * N] = {};
  double least = 1;
  for(int j = 0; j < N; ++j) {
    double d = m[j * N + j];
    for(int k = 0; k < j; ++k)
      d -= l[j * N + k] * l[j * N + k];
    if(!(std::isfinite(d) && d > 1e-12 * m[j * N + j]))
      return false;
    least = std::min(least, d / m[j * N + j]);
    l[j * N + j] = std::sqrt(d);
    for(int i = j + 1; i < N; ++i) {
      double s = m[i * N + j];
      for(int k = 0; k < j; ++k)
        s -= l[i * N + k] * l[j * N + k];
      l[i * N + j] = s / l[j * N + j];
    }
  }
  for(int c = 0; c < N; ++c) { // column c of the inverse: L L^T x = e_c
    double y[N];
    for(int i = 0; i < N; ++i) {
      double s = i == c ? 1.0 : 0.0;
      for(int k = 0; k < i; ++k)
        s -= l[i * N + k] * y[k];
      y[i] = s / l[i * N + i];
    }
    for(int i = N; i-- > 0;) {
      double s = y[i];
      for(int k = i + 1; k < N; ++k)
        s -= l[k * N + i] * y[k];
      y[i] = s / l[i * N + i];
    }
    for(int i = 0; i < N; ++i)
      r[i * N + c] = y[i];
  }
  if(weakest)
    *weakest = least;
  return true;
}

/// Frobenius norm of a D x D block: the strength of a block coupling.
template <int D>
inline double block_norm(const double* m)
{
  double s = 0;
  for(int k = 0; k < D * D; ++k)
    s += m[k] * m[k];
  return std::sqrt(s);
}

/// s -= M x for a D x D block M (of doubles, or of floats read as doubles).
template <int D, class T>
inline void subtract_block_product(std::array<double, D>& s, const T* M, const std::array<double, D>& x)
{
  for(int r = 0; r < D; ++r)
    for(int c = 0; c < D; ++c)
      s[r] -= double(M[r * D + c]) * x[c];
}

/// Index of entry (r, c), r <= c, of a symmetric D x D block stored as its
/// upper triangle by rows (D(D+1)/2 values).
template <int D>
constexpr int upper_triangle_index(int r, int c)
{
  return r * D - r * (r - 1) / 2 + (c - r);
}

/// The upper triangle of the D x D block m as T values (see
/// upper_triangle_index).
template <int D, class T>
inline void copy_upper_triangle(const double* m, T* u)
{
  for(int r = 0; r < D; ++r)
    for(int c = r; c < D; ++c)
      u[upper_triangle_index<D>(r, c)] = T(m[r * D + c]);
}

/// Entry (r, c), any r and c, of a symmetric D x D block stored as its upper
/// triangle.
template <int D, class T>
constexpr T symmetric_entry(const T* U, int r, int c)
{
  return U[r <= c ? upper_triangle_index<D>(r, c) : upper_triangle_index<D>(c, r)];
}

/// The whole D x D block m (row-major) of a symmetric block stored as its
/// upper triangle U.
template <int D>
inline void expand_symmetric_block(const double* U, double* m)
{
  for(int r = 0; r < D; ++r)
    for(int c = 0; c < D; ++c)
      m[r * D + c] = symmetric_entry<D>(U, r, c);
}

/// s -= M x for a symmetric D x D block M stored as its upper triangle (of
/// doubles, or of floats read as doubles): the products and sums of
/// subtract_block_product on the full block, in its order, so the same bits.
template <int D, class T>
inline void subtract_symmetric_block_product(std::array<double, D>& s, const T* U, const std::array<double, D>& x)
{
  for(int r = 0; r < D; ++r)
    for(int c = 0; c < D; ++c)
      s[r] -= double(symmetric_entry<D>(U, r, c)) * x[c];
}

/// M x for a D x D block M.
template <int D>
inline std::array<double, D> block_product(const double* M, const std::array<double, D>& x)
{
  std::array<double, D> y{};
  for(int r = 0; r < D; ++r)
    for(int c = 0; c < D; ++c)
      y[r] += M[r * D + c] * x[c];
  return y;
}

/// M x for a symmetric D x D block M of doubles stored as its upper
/// triangle: the products and sums of block_product on the full block, in
/// its order, so the same bits.
template <int D>
inline std::array<double, D> symmetric_block_product(const double* U, const std::array<double, D>& x)
{
  std::array<double, D> y{};
  for(int r = 0; r < D; ++r)
    for(int c = 0; c < D; ++c)
      y[r] += symmetric_entry<D>(U, r, c) * x[c];
  return y;
}

/// How symmetric_row_products takes a row's block products into its sums:
/// `subtract` each product's terms one by one (the sweeps' residual, as
/// subtract_symmetric_block_product), or `add` each product formed alone
/// from zero (conjugate gradients' product, as symmetric_block_product).
enum class Row_products
{
  subtract,
  add
};

#if SPRING_MOTION_HAS_DOUBLE_QUAD
// The three columns of a symmetric 3 x 3 block from its upper triangle u =
// (m00, m01, m02, m11, m12, m22), given a = u0..u3 and b = u2..u5 (both
// inside the block): column c in lanes 0-2 of col[c]. Lane 3 holds another
// entry of the same block, so it is finite where the block is.
__attribute__((target("avx"))) inline void symmetric_columns_3(__m256d a, __m256d b, __m256d (&col)[3])
{
  col[0] = a;                                                         // m00 m01 m02 (m11)
  col[1] = _mm256_blend_pd(b, _mm256_permute_pd(a, 1), 1);            // m01 m11 m12 (m22)
  col[2] = _mm256_shuffle_pd(b, _mm256_permute2f128_pd(b, b, 1), 4); // m02 m12 m22 (m02)
}

__attribute__((target("avx"))) inline void symmetric_columns_3(const double* u, __m256d (&col)[3])
{
  symmetric_columns_3(_mm256_loadu_pd(u), _mm256_loadu_pd(u + 2), col);
}

__attribute__((target("avx"))) inline void symmetric_columns_3(const float* u, __m256d (&col)[3])
{
  symmetric_columns_3(_mm256_cvtps_pd(_mm_loadu_ps(u)), _mm256_cvtps_pd(_mm_loadu_ps(u + 2)), col);
}

__attribute__((target("avx"))) inline void store_three_lanes(__m256d t, std::array<double, 3>& s)
{
  _mm_storeu_pd(&s[0], _mm256_castpd256_pd128(t));
  _mm_store_sd(&s[2], _mm256_extractf128_pd(t, 1));
}

// symmetric_row_products for D = 3 with AVX: the row's three sums in one
// register, each lane taking its products in the order of the columns as
// the scalar forms do (AVX alone brings no fused multiply-add): the same
// bits. Lane 3 sums products of other entries of the same blocks and is
// never stored.
template <Row_products P, class T, class I, class X>
__attribute__((target("avx"))) inline void symmetric_row_products_3_avx(std::array<double, 3>& s, const T* v,
                                                                         const I* col, I first, I last, const X* x)
{
  __m256d t = _mm256_set_pd(0.0, s[2], s[1], s[0]);
  for(I q = first; q < last; ++q) {
    __m256d m[3];
    symmetric_columns_3(v + std::size_t(q) * 6, m);
    const double* y = x[col[q]].data();
    if constexpr(P == Row_products::subtract) {
      for(int c = 0; c < 3; ++c)
        t = _mm256_sub_pd(t, _mm256_mul_pd(m[c], _mm256_broadcast_sd(y + c)));
    } else {
      __m256d p = _mm256_setzero_pd();
      for(int c = 0; c < 3; ++c)
        p = _mm256_add_pd(p, _mm256_mul_pd(m[c], _mm256_broadcast_sd(y + c)));
      t = _mm256_add_pd(t, p);
    }
  }
  store_three_lanes(t, s);
}
#endif

/// s -= (P subtract) or s += (P add) the sum over the entries q in [first,
/// last) of M_q x[col[q]], the symmetric D x D blocks M_q stored as upper
/// triangles (of doubles, or of floats read as doubles) at v + q D (D + 1) /
/// 2: block after block by subtract_symmetric_block_product or
/// symmetric_block_product, or, for D = 3 where the processor has AVX, the
/// three rows at once with the same bits (one at a time, a 3D block took
/// about 35 instructions, with a conversion per float; three rows at once
/// take about 20, and a one-thread ball-vertex solve of the wing 0.90 times
/// as long).
template <Row_products P, int D, class T, class I, class X>
inline void symmetric_row_products(std::array<double, D>& s, const T* v, const I* col, I first, I last, const X* x)
{
#if SPRING_MOTION_HAS_DOUBLE_QUAD
  if constexpr(D == 3)
    if(four_lanes_available()) {
      symmetric_row_products_3_avx<P>(s, v, col, first, last, x);
      return;
    }
#endif
  constexpr int U = D * (D + 1) / 2;
  for(I q = first; q < last; ++q) {
    if constexpr(P == Row_products::subtract) {
      subtract_symmetric_block_product<D>(s, v + std::size_t(q) * U, x[col[q]]);
    } else {
      const std::array<double, D> t = symmetric_block_product<D>(v + std::size_t(q) * U, x[col[q]]);
      for(int c = 0; c < D; ++c)
        s[std::size_t(c)] += t[std::size_t(c)];
    }
  }
}

/// The magnitudes a float keeps to 24 bits, besides 0: capped stiffness
/// reaches 1e250, and converting such a value traps under feenableexcept.
/// fits_single and copy_to_single's vector form both read these two.
constexpr double single_low = 1e-30;
constexpr double single_high = 1e30;

/// Whether a float keeps 24 bits of value a: 0, or a magnitude in
/// [single_low, single_high].
inline bool fits_single(double a)
{
  a = std::abs(a);
  return a == 0 || (a >= single_low && a <= single_high);
}

/// single[k] = values[k] as a float for k < n, on `threads` threads; 0 where
/// a value does not fit (it is not converted: that traps under
/// feenableexcept). Whether every value fit.
///
/// Two values at a time and without branches where SSE2 is: one at a time,
/// GCC branched on each of fits_single's tests, and on the 2D paper mesh,
/// whose rows stay in the caches, the copy took 5% of a ball-vertex run
/// (perf), most of it at those branches. A value that does not fit is
/// masked to +0 before the conversion, as the scalar form writes 0; the
/// comparisons are those of fits_single, so the same floats and the same
/// answer.
inline bool copy_to_single(const double* values, float* single, long n, int threads)
{
  bool fits = true;
  long k0 = 0;
#if defined(__SSE2__)
  const long pairs = n / 2;
  in_team(threads, [&] {
#pragma omp for schedule(static) reduction(&& : fits)
    for(long p = 0; p < pairs; ++p) {
      const __m128d v = _mm_loadu_pd(values + 2 * p);
      const __m128d a = _mm_andnot_pd(_mm_set1_pd(-0.0), v);
      const __m128d ok = _mm_or_pd(_mm_cmpeq_pd(a, _mm_setzero_pd()),
                                   _mm_and_pd(_mm_cmpge_pd(a, _mm_set1_pd(single_low)),
                                              _mm_cmple_pd(a, _mm_set1_pd(single_high))));
      // two floats (8 bytes) from the low half; __m64 may alias them
      _mm_storel_pi(reinterpret_cast<__m64*>(single + 2 * p), _mm_cvtpd_ps(_mm_and_pd(v, ok)));
      fits = fits && _mm_movemask_pd(ok) == 3;
    }
  });
  k0 = 2 * pairs;
#endif
  // the odd last value after the pairs (on the calling thread), or, without
  // SSE2, every value
  in_team(k0 == 0 ? threads : 1, [&] {
#pragma omp for schedule(static) reduction(&& : fits)
    for(long k = k0; k < n; ++k) {
      const double v = values[k];
      const bool f = fits_single(v);
      single[k] = float(f ? v : 0.0);
      fits = fits && f;
    }
  });
  return fits;
}

/// Each D x D block of `values` (row-major doubles) transposed into
/// `single` as floats: block q's entry (r, c) at single[q D^2 + c D + r];
/// 0 where a value does not fit (it is not converted: that traps under
/// feenableexcept). Whether every value fit. On `threads` threads.
template <int D>
inline bool copy_to_single_by_columns(const double* values, float* single, long blocks, int threads)
{
  constexpr int DD = D * D;
  bool fits = true;
  in_team(threads, [&] {
#pragma omp for schedule(static) reduction(&& : fits)
    for(long q = 0; q < blocks; ++q) {
      const double* m = values + std::size_t(q) * DD;
      float* t = single + std::size_t(q) * DD;
      bool block_fits = true;
      for(int r = 0; r < D; ++r)
        for(int c = 0; c < D; ++c) {
          const double a = m[r * D + c];
          const bool f = fits_single(a);
          t[c * D + r] = float(f ? a : 0.0);
          block_fits &= f;
        }
      fits = fits && block_fits;
    }
  });
  return fits;
}

/// s -= M x for a D x D block of floats stored by columns (Mt[c D + r] =
/// M(r, c), copy_to_single_by_columns). Each row subtracts its products in
/// the order of its columns, as subtract_block_product does on the row-major
/// block: the same bits. Stored by columns, two rows' sums share a register
/// and each column is one vector product (by rows, inside the multigrid's
/// sweeps, GCC converted and multiplied the floats one at a time).
template <int D>
inline void subtract_block_product_by_columns(std::array<double, D>& s, const float* Mt,
                                              const std::array<double, D>& x)
{
#if defined(__SSE2__)
  if constexpr(D % 2 == 0) {
    __m128d t[D / 2];
    for(int k = 0; k < D / 2; ++k)
      t[k] = _mm_loadu_pd(&s[std::size_t(2 * k)]);
    for(int c = 0; c < D; ++c) {
      const __m128d y = _mm_set1_pd(x[std::size_t(c)]);
      for(int k = 0; k < D / 2; ++k) {
        // two floats (8 bytes) into the low half; __m64 may alias them
        const __m128 m = _mm_loadl_pi(_mm_setzero_ps(), reinterpret_cast<const __m64*>(Mt + c * D + 2 * k));
        t[k] = _mm_sub_pd(t[k], _mm_mul_pd(_mm_cvtps_pd(m), y));
      }
    }
    for(int k = 0; k < D / 2; ++k)
      _mm_storeu_pd(&s[std::size_t(2 * k)], t[k]);
    return;
  }
#endif
  for(int c = 0; c < D; ++c)
    for(int r = 0; r < D; ++r)
      s[std::size_t(r)] -= double(Mt[c * D + r]) * x[std::size_t(c)];
}

#if SPRING_MOTION_HAS_DOUBLE_QUAD
// subtract_row_products_by_columns for D = 6 with AVX: rows 0-3 in one
// register, rows 4-5 in another, the row's sums kept in them from block to
// block. Each lane subtracts its products in the order of the columns, as
// subtract_block_product_by_columns does (AVX alone brings no fused
// multiply-add): the same bits.
template <class I, class X, class Keep>
__attribute__((target("avx"))) inline void subtract_row_products_6_avx(std::array<double, 6>& s, const float* v,
                                                                        const I* col, I first, I last, const X* x,
                                                                        Keep keep)
{
  __m256d s03 = _mm256_loadu_pd(&s[0]);
  __m128d s45 = _mm_loadu_pd(&s[4]);
  for(I q = first; q < last; ++q) {
    if(!keep(col[q]))
      continue;
    const float* M = v + std::size_t(q) * 36;
    const double* y = x[col[q]].data();
    for(int c = 0; c < 6; ++c) {
      // column c: rows 0-3 in 16 bytes, rows 4-5 in the next 8 (__m64 may alias them)
      const __m256d top = _mm256_cvtps_pd(_mm_loadu_ps(M + 6 * c));
      const __m128d low = _mm_cvtps_pd(_mm_loadl_pi(_mm_setzero_ps(), reinterpret_cast<const __m64*>(M + 6 * c + 4)));
      s03 = _mm256_sub_pd(s03, _mm256_mul_pd(top, _mm256_set1_pd(y[c])));
      s45 = _mm_sub_pd(s45, _mm_mul_pd(low, _mm_set1_pd(y[c])));
    }
  }
  _mm256_storeu_pd(&s[0], s03);
  _mm_storeu_pd(&s[4], s45);
}
#endif

/// s -= the sum over the entries q in [first, last) with keep(col[q]) of
/// M_q x[col[q]], the D x D blocks M_q of floats stored by columns at v + q
/// D^2: block after block by subtract_block_product_by_columns, or, for D =
/// 6 (the rigid-body levels in 3D) where the processor has AVX, four rows
/// at a time with the same bits.
template <int D, class I, class X, class Keep>
inline void subtract_row_products_by_columns(std::array<double, D>& s, const float* v, const I* col, I first,
                                             I last, const X* x, Keep keep)
{
#if SPRING_MOTION_HAS_DOUBLE_QUAD
  if constexpr(D == 6)
    if(four_lanes_available()) {
      subtract_row_products_6_avx(s, v, col, first, last, x, keep);
      return;
    }
#endif
  for(I q = first; q < last; ++q)
    if(keep(col[q]))
      subtract_block_product_by_columns<D>(s, v + std::size_t(q) * D * D, x[col[q]]);
}

/// A max that a NaN sticks to, so a NaN can never pass for convergence:
/// a NaN v is taken (v <= m fails), and a NaN m is kept (m == m fails),
/// whatever values come after it.
inline void sticky_max(double& m, double v)
{
  if(!(v <= m) && m == m)
    m = v;
}

} // namespace internal
} // namespace spring_motion

#endif
