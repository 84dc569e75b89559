// Copyright (c) 2026 SpringMotion developers.
#ifndef SPRING_MOTION_INTERNAL_SOLVER_CHEBYSHEV_H
#define SPRING_MOTION_INTERNAL_SOLVER_CHEBYSHEV_H

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <utility>
#include <vector>

namespace spring_motion {
namespace internal {

/// An interval [low, high] of eigenvalues; empty (not `valid`) when no
/// estimate could be made.
struct Eigen_interval
{
  double low = 0, high = 0;
  bool valid() const { return low > 0 && high > low && std::isfinite(high); }
};

/// The smallest and largest eigenvalues of the Lanczos matrix of k steps of
/// preconditioned conjugate gradients, from their step lengths alpha_j and
/// ratios beta_j = (r_{j+1}.z_{j+1}) / (r_j.z_j): the tridiagonal matrix
/// with diagonal 1/alpha_j + beta_{j-1}/alpha_{j-1} and off-diagonal
/// sqrt(beta_j)/alpha_j (Saad, "Iterative methods for sparse linear
/// systems", 6.7.3). Its eigenvalues (Ritz values) lie inside the spectrum
/// of B A, the extreme ones approaching its ends within a few steps.
/// Found by bisection on Sturm counts, to the last bits.
inline Eigen_interval lanczos_extremes(const std::vector<double>& alpha, const std::vector<double>& beta)
{
  const std::size_t k = std::min(alpha.size(), beta.size());
  if(k == 0)
    return {};
  std::vector<double> d(k), e(k);
  double bound = 0; // Gershgorin
  for(std::size_t j = 0; j < k; ++j) {
    if(!(alpha[j] > 0) || !(beta[j] >= 0))
      return {};
    d[j] = 1 / alpha[j] + (j > 0 ? beta[j - 1] / alpha[j - 1] : 0.0);
    e[j] = std::sqrt(beta[j]) / alpha[j]; // e[j] couples j and j + 1
  }
  for(std::size_t j = 0; j < k; ++j)
    bound = std::max(bound, std::abs(d[j]) + (j > 0 ? e[j - 1] : 0.0) + (j + 1 < k ? e[j] : 0.0));
  if(!std::isfinite(bound))
    return {};
  // eigenvalues below x: the negative pivots of T - x I
  auto below = [&](double x) {
    std::size_t count = 0;
    double pivot = 1;
    for(std::size_t j = 0; j < k; ++j) {
      pivot = d[j] - x - (j > 0 ? e[j - 1] * e[j - 1] / pivot : 0.0);
      if(pivot == 0)
        pivot = -1e-300; // x is an eigenvalue: count it below
      count += pivot < 0;
    }
    return count;
  };
  // the eigenvalue of rank `index` (0: the smallest)
  auto eigenvalue = [&](std::size_t index) {
    double lo = -bound, hi = bound;
    for(int it = 0; it < 200 && lo < hi; ++it) {
      const double mid = lo + (hi - lo) / 2;
      if(mid <= lo || mid >= hi)
        break;
      (below(mid) > index ? hi : lo) = mid;
    }
    return lo + (hi - lo) / 2;
  };
  return {eigenvalue(0), eigenvalue(k - 1)};
}

/// The weights of Chebyshev iteration on an interval [low, high] of the
/// eigenvalues of B A (Saad, algorithm 12.1 with a preconditioner): step k
/// updates the solution by d_k = keep d_{k-1} + add B r_k, r_k the residual
/// after the steps before. After k steps from zero the error is T_k(
/// (high + low - 2 t) / (high - low)) / T_k((high + low) / (high - low)) on
/// an eigenvector of B A with eigenvalue t: at most 2 q^k / (1 + q^{2k}),
/// q = (sqrt(high) - sqrt(low)) / (sqrt(high) + sqrt(low)), over the
/// interval, where k steps of plain corrections (d_k = B r_k) leave (1 - t)^k,
/// close to 1 for the small t. The weights depend only on the interval and
/// on k, so k steps are a fixed polynomial in B A times B: symmetric when B
/// and A are. It stays positive definite for every t in (0, low + high),
/// the error's polynomial there below 1 (for every t > 0 when k is odd).
class Chebyshev_steps
{
public:
  explicit Chebyshev_steps(const Eigen_interval& i)
      : theta_((i.high + i.low) / 2), delta_((i.high - i.low) / 2), sigma_(theta_ / delta_), rho_(1 / sigma_)
  {
  }

  /// (keep, add) of the next step
  std::pair<double, double> next()
  {
    if(first_) {
      first_ = false;
      return {0.0, 1 / theta_};
    }
    const double rho = 1 / (2 * sigma_ - rho_);
    const std::pair<double, double> w{rho * rho_, 2 * rho / delta_};
    rho_ = rho;
    return w;
  }

private:
  double theta_, delta_, sigma_, rho_;
  bool first_ = true;
};

} // namespace internal
} // namespace spring_motion

#endif
