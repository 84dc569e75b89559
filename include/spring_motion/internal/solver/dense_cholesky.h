// Copyright (c) 2026 SpringMotion developers.
#ifndef SPRING_MOTION_INTERNAL_SOLVER_DENSE_CHOLESKY_H
#define SPRING_MOTION_INTERNAL_SOLVER_DENSE_CHOLESKY_H

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <vector>

namespace spring_motion {
namespace internal {

/// Where the nonzeros of a symmetric n x n matrix lie: row i has none left
/// of column first[i] (<= i), and column j none below row last[j], the
/// largest i with first[i] <= j. A Cholesky factor keeps this envelope (no
/// fill outside it), so the factorisation and the solves skip the terms
/// outside it. Those terms are products with exact zeros, so skipping them
/// gives the bits of the whole-triangle sums (up to the sign of a zero).
///
/// The multigrids' coarsest matrices are sparse (an aggregate couples with a
/// handful of others) and their aggregates are numbered along the fine rows,
/// which are numbered along the mesh: in that order a row's nonzeros lie
/// near the diagonal, and the part of the triangle before them stays zero in
/// the factor, which need not be read or summed.
struct Dense_envelope
{
  std::vector<std::size_t> first, last;

  /// The whole lower triangle: first[i] = 0.
  static Dense_envelope full(std::size_t n) { return from_first(std::vector<std::size_t>(n, 0)); }

  /// From the first column of every row that may be nonzero.
  static Dense_envelope from_first(std::vector<std::size_t> first)
  {
    Dense_envelope e;
    const std::size_t n = first.size();
    e.last.resize(n);
    // last[j] = max{i : first[i] <= j}: the running maximum from the right
    // of the rows, each of which reaches back to its first column
    std::vector<std::size_t> reach(n, 0);
    for(std::size_t i = 0; i < n; ++i)
      reach[first[i]] = std::max(reach[first[i]], i);
    std::size_t top = 0;
    for(std::size_t j = 0; j < n; ++j) {
      top = std::max({top, reach[j], j});
      e.last[j] = top;
    }
    e.first = std::move(first);
    return e;
  }
};

/// Replaces the symmetric n x n row-major matrix a, zero outside the
/// envelope e, by its Cholesky factor L in the lower triangle and L^T in
/// the upper one (which dense_cholesky_solve's backward pass reads along
/// rows); false, with a half-factored, if a pivot is not above `relative`
/// times its diagonal entry. The multigrids' coarsest levels are small
/// enough for a dense factorisation.
inline bool try_dense_cholesky(std::vector<double>& a, std::size_t n, const Dense_envelope& e, double relative)
{
  // Each entry is one sum, in the order k = 0, 1, ..., whose additions wait
  // for each other; the entries of column j below the diagonal are
  // independent, so four rows are summed side by side (the same operations
  // in the same order per entry: the same bits). Entry (i, j) sums from
  // column max(first[i], first[j]); four rows together from the least of
  // theirs (the extra terms are products with zeros).
  constexpr std::size_t w = 4;
  for(std::size_t j = 0; j < n; ++j) {
    const double* J = &a[j * n];
    const std::size_t fj = e.first[j], end = e.last[j] + 1;
    double d = J[j];
    const double own = d;
    for(std::size_t k = fj; k < j; ++k)
      d -= J[k] * J[k];
    if(!(std::isfinite(d) && d > relative * own))
      return false;
    const double l = std::sqrt(d);
    a[j * n + j] = l;
    std::size_t i = j + 1;
    for(; i + w <= end; i += w) {
      double* A[w];
      double s[w];
      std::size_t from = j;
      for(std::size_t t = 0; t < w; ++t) {
        A[t] = &a[(i + t) * n];
        s[t] = A[t][j];
        from = std::min(from, e.first[i + t]);
      }
      for(std::size_t k = std::max(from, fj); k < j; ++k)
        for(std::size_t t = 0; t < w; ++t)
          s[t] -= A[t][k] * J[k];
      for(std::size_t t = 0; t < w; ++t)
        a[j * n + i + t] = A[t][j] = s[t] / l;
    }
    for(; i < end; ++i) {
      double s = a[i * n + j];
      for(std::size_t k = std::max(e.first[i], fj); k < j; ++k)
        s -= a[i * n + k] * J[k];
      a[j * n + i] = a[i * n + j] = s / l;
    }
  }
  return true;
}

/// Solves L L^T z = b for M right-hand sides stored interleaved (b[i * M + c]
/// is row i of right-hand side c), L from try_dense_cholesky with the same
/// envelope.
template <int M>
void dense_cholesky_solve(const std::vector<double>& l, std::size_t n, const Dense_envelope& e, const double* b,
                          double* z)
{
  // forward: rows i..i+3 share the terms k < i (four independent sums, as in
  // try_dense_cholesky), then each takes its terms k >= i in order once the
  // rows before it are solved: every sum in the order k = 0, 1, ...
  constexpr std::size_t w = 4;
  std::size_t i = 0;
  for(; i + w <= n; i += w) {
    std::array<std::array<double, M>, w> s;
    std::size_t from = i;
    for(std::size_t t = 0; t < w; ++t) {
      from = std::min(from, e.first[i + t]);
      for(int c = 0; c < M; ++c)
        s[t][std::size_t(c)] = b[(i + t) * M + c];
    }
    for(std::size_t k = from; k < i; ++k)
      for(std::size_t t = 0; t < w; ++t)
        for(int c = 0; c < M; ++c)
          s[t][std::size_t(c)] -= l[(i + t) * n + k] * z[k * M + c];
    for(std::size_t t = 0; t < w; ++t) {
      for(std::size_t k = i; k < i + t; ++k)
        for(int c = 0; c < M; ++c)
          s[t][std::size_t(c)] -= l[(i + t) * n + k] * z[k * M + c];
      for(int c = 0; c < M; ++c)
        z[(i + t) * M + c] = s[t][std::size_t(c)] / l[(i + t) * n + i + t];
    }
  }
  for(; i < n; ++i) {
    std::array<double, M> s{};
    for(int c = 0; c < M; ++c)
      s[c] = b[i * M + c];
    for(std::size_t k = e.first[i]; k < i; ++k)
      for(int c = 0; c < M; ++c)
        s[c] -= l[i * n + k] * z[k * M + c];
    for(int c = 0; c < M; ++c)
      z[i * M + c] = s[c] / l[i * n + i];
  }
  for(std::size_t ii = n; ii-- > 0;) {
    std::array<double, M> s{};
    for(int c = 0; c < M; ++c)
      s[c] = z[ii * M + c];
    // L's column ii read as row ii of L^T: one cache line for eight terms,
    // not one per term
    for(std::size_t k = ii + 1; k <= e.last[ii]; ++k)
      for(int c = 0; c < M; ++c)
        s[c] -= l[ii * n + k] * z[k * M + c];
    for(int c = 0; c < M; ++c)
      z[ii * M + c] = s[c] / l[ii * n + ii];
  }
}

} // namespace internal
} // namespace spring_motion

#endif // SPRING_MOTION_INTERNAL_SOLVER_DENSE_CHOLESKY_H
