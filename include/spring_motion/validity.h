// Copyright (c) 2026 SpringMotion developers.
#ifndef SPRING_MOTION_VALIDITY_H
#define SPRING_MOTION_VALIDITY_H

#include <spring_motion/Error.h>
#include <spring_motion/check_input_mesh.h>
#include <spring_motion/Spring_network.h>
#include <spring_motion/internal/geometry/element_points.h>
#include <spring_motion/internal/geometry/exact_orientation.h>
#include <spring_motion/internal/solver/threads.h>

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

/// Who checks the input mesh (`check_input_mesh`: degenerate and
/// overlapping elements, facets in more than two elements) before its
/// orientations are recorded: the recording itself (`here`), or the caller,
/// who has checked the same elements at the same points and found no
/// problem (`by_caller`: a program that reports problems against its own
/// file; the facet tests cost as much as several steps on a large mesh).
/// Either way a degenerate element is refused.
enum class Mesh_checks { here, by_caller };

/// Records the exact orientation of every element at positions x (each its
/// own: elements may be listed in either order). Checks the mesh first
/// (`check_input_mesh`, unless `checks` says the caller has): a mesh with
/// degenerate elements, overlapping elements or a facet in more than two
/// elements cannot be moved validly, and `Element_error` names its first
/// problem element.
template <int D>
Orientation_record record_orientations(const Spring_network<D>& net, const std::vector<typename Spring_network<D>::Point>& x,
                                       Mesh_checks checks = Mesh_checks::here)
{
  Orientation_record rec;
  if(checks == Mesh_checks::by_caller) {
    SPRING_MOTION_CHECK(x.size() == net.number_of_vertices(),
                        "got " << x.size() << " positions for " << net.number_of_vertices() << " vertices");
    internal::element_orientations<D>(x, net.elements, rec.sign, 0);
    Input_mesh_problems problems;
    for(std::size_t t = 0; t < rec.sign.size(); ++t)
      if(rec.sign[t] == 0)
        problems.degenerate.push_back(t);
    SPRING_MOTION_ELEMENT_CHECK(problems.valid(), first_problem_element(problems),
                                describe_input_mesh_problems(problems));
    return rec;
  }
  // the check's exact orientations are the record: none is 0 in a valid mesh
  const Input_mesh_problems problems = internal::check_input_mesh<D>(x, net.elements, rec.sign, 0);
  SPRING_MOTION_ELEMENT_CHECK(problems.valid(), first_problem_element(problems),
                              describe_input_mesh_problems(problems));
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
  // The elements' vertices lie scattered through x (elements in the file's
  // order): their positions are fetched a few elements ahead, so that the
  // misses overlap the filter's arithmetic instead of stalling it.
  constexpr long ahead = 4;
  // thread-safe: the filtered predicates keep their rounding-mode state per call
#pragma omp parallel for schedule(static) num_threads(internal::thread_count(threads, std::size_t(m)))
  for(long t = 0; t < m; ++t) {
    if(t + ahead < m)
      for(const auto v : net.elements[std::size_t(t + ahead)])
        __builtin_prefetch(&x[v]);
    bad[std::size_t(t)] =
        internal::exact_orientation(internal::element_points<D>(net.elements, x, std::size_t(t))) != rec.sign[std::size_t(t)];
  }
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
