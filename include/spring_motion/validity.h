// Copyright (c) 2026 SpringMotion developers.
#ifndef SPRING_MOTION_VALIDITY_H
#define SPRING_MOTION_VALIDITY_H

#include <spring_motion/Error.h>
#include <spring_motion/Spring_network.h>
#include <spring_motion/internal/element_points.h>
#include <spring_motion/internal/threads.h>

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>

#include <algorithm>
#include <array>
#include <cstddef>
#include <iterator>
#include <sstream>
#include <vector>

namespace spring_motion {

/// The orientation of every element of a mesh as it was when recorded: the
/// reference against which inversion is judged.
struct Orientation_record
{
  std::vector<signed char> sign; // +1 or -1 per element
};

namespace internal {

using Exact_predicates_kernel = CGAL::Exact_predicates_inexact_constructions_kernel;

/// The exact orientation of an element: CGAL's filtered predicate decides the
/// sign of the determinant exactly for the double coordinates given.
inline int exact_orientation(const std::array<std::array<double, 2>, 3>& p)
{
  using P = Exact_predicates_kernel::Point_2;
  return int(CGAL::orientation(P(p[0][0], p[0][1]), P(p[1][0], p[1][1]), P(p[2][0], p[2][1])));
}
inline int exact_orientation(const std::array<std::array<double, 3>, 4>& p)
{
  using P = Exact_predicates_kernel::Point_3;
  return int(CGAL::orientation(P(p[0][0], p[0][1], p[0][2]), P(p[1][0], p[1][1], p[1][2]),
                               P(p[2][0], p[2][1], p[2][2]), P(p[3][0], p[3][1], p[3][2])));
}


} // namespace internal

/// Records the exact orientation of every element at positions x. Throws
/// `Error` listing the first few degenerate (zero-orientation) elements: a
/// mesh that is already degenerate cannot be moved validly.
template <int D>
Orientation_record record_orientations(const Spring_network<D>& net, const std::vector<typename Spring_network<D>::Point>& x)
{
  Orientation_record rec;
  rec.sign.resize(net.number_of_elements());
  std::vector<std::size_t> degenerate;
  for(std::size_t t = 0; t < net.number_of_elements(); ++t) {
    const int o = internal::exact_orientation(internal::element_points<D>(net.elements, x, t));
    rec.sign[t] = static_cast<signed char>(o);
    if(o == 0)
      degenerate.push_back(t);
  }
  if(!degenerate.empty()) {
    std::ostringstream list;
    for(std::size_t i = 0; i < std::min<std::size_t>(5, degenerate.size()); ++i)
      list << (i ? ", " : "") << degenerate[i];
    SPRING_MOTION_CHECK(false, degenerate.size() << " degenerate element(s) in the input mesh (zero area or volume): "
                                                 << list.str() << (degenerate.size() > 5 ? ", ..." : ""));
  }
  return rec;
}

/// Writes to `out` the index of every element whose exact orientation at x
/// differs from the record (zero orientation counts as inverted), in
/// increasing order, and returns how many there are.
template <int D, class OutputIterator>
std::size_t find_inverted_elements(const Spring_network<D>& net, const std::vector<typename Spring_network<D>::Point>& x,
                                   const Orientation_record& rec, OutputIterator out, int threads = 0)
{
  SPRING_MOTION_CHECK(rec.sign.size() == net.number_of_elements(),
                      "orientation record has " << rec.sign.size() << " elements, the mesh "
                                                << net.number_of_elements());
  const long m = long(net.number_of_elements());
  std::vector<char> bad(std::size_t(m), 0);
  // thread-safe: the filtered predicates keep their rounding-mode state per call
#pragma omp parallel for schedule(static) num_threads(internal::thread_count(threads, std::size_t(m)))
  for(long t = 0; t < m; ++t)
    bad[std::size_t(t)] =
        internal::exact_orientation(internal::element_points<D>(net.elements, x, std::size_t(t))) != rec.sign[std::size_t(t)];
  std::size_t count = 0;
  for(long t = 0; t < m; ++t)
    if(bad[std::size_t(t)]) {
      *out++ = std::size_t(t);
      ++count;
    }
  return count;
}

} // namespace spring_motion

#endif
