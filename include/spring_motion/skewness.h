// Copyright (c) 2026 SpringMotion developers.
#ifndef SPRING_MOTION_SKEWNESS_H
#define SPRING_MOTION_SKEWNESS_H

#include <spring_motion/Spring_network.h>
#include <spring_motion/internal/solver/threads.h>
#include <spring_motion/internal/geometry/angles.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <limits>
#include <vector>

namespace spring_motion {

/// Q_e of Eq. 13: the angle of the equilateral element (2D: pi/3; 3D: the
/// dihedral angle of the regular tetrahedron, arccos(1/3)).
inline double equiangular_angle(int dimension)
{
  return dimension == 2 ? internal::pi / 3 : std::acos(1.0 / 3.0);
}

/// Equiangle skewness (paper Eq. 13) from an element's angles:
/// R = max((Q_max - Q_e)/(pi - Q_e), (Q_e - Q_min)/Q_e), clamped to [0, 1].
/// 0 is the equilateral element, 1 a degenerate one. An angle that is not a
/// number (an element with coincident or non-finite vertices) gives 1: NaN
/// compares false, so min/max would otherwise skip it or clamp it to a
/// "perfect" 0.
inline double equiangle_skewness_from_angles(const double* angles, std::size_t n, int dimension)
{
  for(std::size_t k = 0; k < n; ++k)
    if(!std::isfinite(angles[k]))
      return 1.0;
  const double qe = equiangular_angle(dimension);
  const auto mm = std::minmax_element(angles, angles + n);
  const double r = std::max((*mm.second - qe) / (internal::pi - qe), (qe - *mm.first) / qe);
  return std::min(1.0, std::max(0.0, r));
}

/// R of a triangle, from its interior angles.
inline double equiangle_skewness(const std::array<double, 2>& p, const std::array<double, 2>& q,
                                 const std::array<double, 2>& r)
{
  const auto a = internal::triangle_angles<2>(p, q, r);
  return equiangle_skewness_from_angles(a.data(), 3, 2);
}

/// R of a tetrahedron, from its six dihedral angles.
inline double equiangle_skewness(const std::array<double, 3>& p, const std::array<double, 3>& q,
                                 const std::array<double, 3>& r, const std::array<double, 3>& s)
{
  const auto a = internal::dihedral_angles({p, q, r, s});
  return equiangle_skewness_from_angles(a.data(), 6, 3);
}

/// Ten-bin (by default) histogram of R over a set of elements, as fractions,
/// with the mean and the max. Bin b holds [b/B, (b+1)/B); R = 1 falls in the last.
struct Skewness_histogram
{
  std::vector<double> fractions;
  std::size_t count = 0;
  double mean = 0;
  double max = 0;
};

namespace internal {
/// R of element t at positions x and its smallest angle in degrees (2D:
/// interior angles; 3D: dihedral angles), both from the two extreme angles
/// only; an angle that is not a number gives R = 1 and a smallest angle of 0.
template <int D>
std::array<double, 2> skewness_and_smallest_angle(const Spring_network<D>& net,
                                                  const std::vector<typename Spring_network<D>::Point>& x, std::size_t t)
{
  const auto& e = net.elements[t];
  const auto a = [&] {
    if constexpr(D == 2)
      return triangle_angle_range<2>(x[e[0]], x[e[1]], x[e[2]]);
    else
      return dihedral_angle_range({x[e[0]], x[e[1]], x[e[2]], x[e[3]]});
  }();
  return {equiangle_skewness_from_angles(a.data(), a.size(), D),
          std::isfinite(a[0]) ? std::min(pi, a[0]) * (180 / pi) : 0.0};
}
} // namespace internal

namespace internal {
/// The extreme angles of the element with corners p (skewness_and_smallest_angle's).
template <int D>
Extreme_angles element_extreme_angles(const std::array<std::array<double, D>, D + 1>& p)
{
  if constexpr(D == 2)
    return triangle_extreme_angles<2>(p[0], p[1], p[2]);
  else
    return dihedral_extreme_angles(p);
}

/// The largest R and the smallest angle over a set of elements: the same
/// numbers as the largest skewness_and_smallest_angle()[0] and the smallest
/// [1] of its elements, with atan2 only for the elements that can change
/// them. R is monotone in an element's extreme angles, so the set's R is the
/// R of its smallest and its largest angle; an element whose angle key lies
/// beyond the best key so far by more than the keys' error (angle_key)
/// cannot be an extreme and is passed over. On the wing nearly every
/// element is, and the pass costs half what one atan2 pair per element did.
class Quality_extremes
{
public:
  void add(const Extreme_angles& e)
  {
    ++count_;
    if(!e.finite) {
      not_a_number_ = true;
      return;
    }
    if(e.direct) {
      take(e.lo_angle, e.hi_angle);
      return;
    }
    const double kl = angle_key(e.lo), kh = angle_key(e.hi);
    // a key that is not a number (atan2(0, 0)) decides nothing; tested
    // first, since an ordered comparison with it would raise the
    // invalid-operation flag
    if(std::isnan(kl) || std::isnan(kh)) {
      take(e.lo.angle(), e.hi.angle());
      return;
    }
    // nearly equal extremes may come out of atan2 swapped: R reads the min
    // and max of both
    if(kh - kl <= slack)
      take(e.lo.angle(), e.hi.angle());
    else {
      if(kl <= min_key_ + slack) {
        const double a = e.lo.angle();
        smallest_ = std::min(smallest_, a);
        r_lo_ = std::min(r_lo_, a);
      }
      if(kh >= max_key_ - slack)
        r_hi_ = std::max(r_hi_, e.hi.angle());
    }
    min_key_ = std::min(min_key_, kl);
    max_key_ = std::max(max_key_, kh);
  }
  /// Adds the element with corners p, as add(element_extreme_angles<D>(p))
  /// would, and returns true when it was passed over without computing its
  /// extreme angles: every angle (2D: interior, 3D: dihedral) lies strictly
  /// between the smallest angle so far and the largest, so it changes neither
  /// (element_sines_squared_above). On the wing and on the 2D paper mesh
  /// nearly all elements are passed over.
  template <int D>
  bool add_element(const std::array<std::array<double, D>, D + 1>& p)
  {
    if(try_pass_over<D>(p))
      return true;
    add(element_extreme_angles<D>(p));
    return false;
  }
  /// add_element's bound tests alone: counts the element with corners p and
  /// returns true when add_element would pass it over; false, with nothing
  /// added, otherwise (then its angles are still to be added).
  template <int D>
  bool try_pass_over(const std::array<std::array<double, D>, D + 1>& p)
  {
    refresh_bounds();
    if(!not_a_number_) {
      // first the larger bound for all the angles, which on the wing passes
      // nearly every element over; then the bound of each kind of angle, while
      // it passes over at least a quarter of the elements that reach it (on
      // the box most, on the wing few: there its dot products cost more than
      // they save), and every 32nd of them after, to notice a change
      const double larger = std::max(acute_bound_, obtuse_bound_);
      bool passed = larger < 1 && element_sines_squared_above<D>(p, larger);
      if(!passed && acute_bound_ != obtuse_bound_ && std::min(acute_bound_, obtuse_bound_) < 1 &&
         (kind_tries_ < 256 || 4 * kind_passes_ >= kind_tries_ || ++kind_skips_ % 32 == 0)) {
        ++kind_tries_;
        passed = element_sines_squared_above<D>(p, acute_bound_, obtuse_bound_);
        kind_passes_ += passed;
      }
      if(passed) {
        ++count_;
        return true;
      }
    }
    return false;
  }
  /// The bound add_element tests an element's sin^2 against first, for a
  /// test of several elements at once; at least 1 when none can be passed
  /// over by it.
  double first_bound()
  {
    refresh_bounds();
    return not_a_number_ ? never_passed : std::max(acute_bound_, obtuse_bound_);
  }
  /// Counts an element that passed the test at first_bound(), read before
  /// some elements were added, as add_element would count it: the bound only
  /// falls as elements are added (the extremes only widen, and a range that
  /// contains a right angle keeps containing it), so the element would pass
  /// the bound of now too. Or one that another set, holding only elements
  /// this one holds, passed over (try_pass_over): its angles lie inside that
  /// set's extremes, so inside these. False, with nothing counted, when an
  /// angle that is not a number has been added: then add_element.
  bool pass_over()
  {
    if(not_a_number_)
      return false;
    ++count_;
    return true;
  }
  /// Passes over, besides, the elements whose angles all lie strictly
  /// inside (lo, hi), a guess of the set's extremes (a motion's previous
  /// step's, moved inwards): on a structured mesh most elements share the
  /// extreme angles of its undisturbed part exactly, which no bound drawn
  /// from the extremes so far passes over. The result is the set's only when
  /// guess_held() after the last element (and the merges); otherwise the set
  /// must be added again without the guess.
  void guess(double lo, double hi)
  {
    guess_lo_ = lo;
    guess_hi_ = hi;
  }
  /// Whether the extremes found lie at or beyond the guess, so that no
  /// element passed over by it could hold one (true without a guess: its
  /// infinite ends lie beyond anything found).
  bool guess_held() const { return not_a_number_ || (smallest_ <= guess_lo_ && r_hi_ >= guess_hi_); }
  /// The smallest and the largest angle found (radians; infinite while no
  /// element was added; the largest is R's).
  double smallest_angle() const { return smallest_; }
  double largest_angle() const { return r_hi_; }
  void merge(const Quality_extremes& o)
  {
    count_ += o.count_;
    not_a_number_ = not_a_number_ || o.not_a_number_;
    smallest_ = std::min(smallest_, o.smallest_);
    r_lo_ = std::min(r_lo_, o.r_lo_);
    r_hi_ = std::max(r_hi_, o.r_hi_);
    min_key_ = std::min(min_key_, o.min_key_);
    max_key_ = std::max(max_key_, o.max_key_);
  }
  /// 0 for no element, 1 when an angle is not a number
  double max_skewness(int dimension) const
  {
    if(count_ == 0)
      return 0;
    if(not_a_number_)
      return 1;
    const std::array<double, 2> a{r_lo_, r_hi_};
    return equiangle_skewness_from_angles(a.data(), 2, dimension);
  }
  /// In degrees: 180 for no element, 0 when an angle is not a number.
  double min_angle_deg() const
  {
    if(not_a_number_)
      return 0;
    return count_ == 0 ? 180.0 : std::min(180.0, std::min(pi, smallest_) * (180 / pi));
  }

private:
  static constexpr double slack = 1e-12;
  void refresh_bounds()
  {
    const double lo = std::min(smallest_, guess_lo_), hi = std::max(r_hi_, guess_hi_);
    if(lo != bound_smallest_ || hi != bound_largest_) {
      bound_smallest_ = lo;
      bound_largest_ = hi;
      // sin^2 bounds of the acute and the obtuse angles, never_passed where
      // no angle of that kind can pass: no element yet, or the range (lo, hi)
      // not containing a right angle (sin^2 alone would not bound its far end)
      const bool around_right = lo >= 0 && lo < pi / 2 && hi > pi / 2 && hi <= pi;
      acute_bound_ = around_right ? std::sin(lo) * std::sin(lo) : never_passed;
      obtuse_bound_ = around_right ? std::sin(hi) * std::sin(hi) : never_passed;
    }
  }
  void take(double lo, double hi)
  {
    smallest_ = std::min(smallest_, lo);
    r_lo_ = std::min(r_lo_, std::min(lo, hi));
    r_hi_ = std::max(r_hi_, std::max(lo, hi));
  }
  std::size_t count_ = 0;
  bool not_a_number_ = false;
  double min_key_ = std::numeric_limits<double>::infinity(), max_key_ = -min_key_;
  double smallest_ = min_key_;          // the smallest of the elements' smallest angles
  double r_lo_ = min_key_, r_hi_ = -r_lo_; // what R reads: min and max over both extremes
  // add_element's sin^2 bounds and the range they were computed from
  static constexpr double never_passed = 2; // above any sin^2 (finite: no inf * 0 for a flat element)
  static constexpr double no_guess = std::numeric_limits<double>::infinity();
  double acute_bound_ = never_passed, obtuse_bound_ = never_passed;
  double bound_smallest_ = 0, bound_largest_ = 0;
  double guess_lo_ = no_guess, guess_hi_ = -no_guess;
  std::size_t kind_tries_ = 0, kind_passes_ = 0, kind_skips_ = 0; // the second bound's use so far
};
} // namespace internal

/// R of every element of the network at positions x. With `min_angle_deg`,
/// also each element's smallest angle in degrees from the same angles
/// (2D: interior angles; 3D: dihedral angles, which go to zero when a
/// tetrahedron flattens, even a sliver whose faces all stay well shaped); an
/// angle that is not a number counts as 0.
template <int D>
std::vector<double> element_skewness(const Spring_network<D>& net, const std::vector<typename Spring_network<D>::Point>& x,
                                     int threads = 0, std::vector<double>* min_angle_deg = nullptr)
{
  const long m = long(net.number_of_elements());
  std::vector<double> r(static_cast<std::size_t>(m));
  if(min_angle_deg)
    min_angle_deg->resize(std::size_t(m));
#pragma omp parallel for schedule(static) num_threads(internal::thread_count(threads, std::size_t(m)))
  for(long t = 0; t < m; ++t) {
    const auto q = internal::skewness_and_smallest_angle(net, x, std::size_t(t));
    r[std::size_t(t)] = q[0];
    if(min_angle_deg)
      (*min_angle_deg)[std::size_t(t)] = q[1];
  }
  return r;
}

/// Histogram of the values r[t] for the elements t where select(t) is true.
template <class Select>
Skewness_histogram skewness_histogram(const std::vector<double>& r, Select select, std::size_t bins = 10)
{
  Skewness_histogram h;
  h.fractions.assign(bins, 0.0);
  double sum = 0;
  for(std::size_t t = 0; t < r.size(); ++t) {
    if(!select(t))
      continue;
    const std::size_t b = std::min(bins - 1, std::size_t(r[t] * double(bins)));
    h.fractions[b] += 1;
    sum += r[t];
    h.max = std::max(h.max, r[t]);
    ++h.count;
  }
  if(h.count > 0) {
    for(double& f : h.fractions)
      f /= double(h.count);
    h.mean = sum / double(h.count);
  }
  return h;
}

} // namespace spring_motion

#endif
