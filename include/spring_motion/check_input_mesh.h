// Copyright (c) 2026 SpringMotion developers.
#ifndef SPRING_MOTION_CHECK_INPUT_MESH_H
#define SPRING_MOTION_CHECK_INPUT_MESH_H

#include <spring_motion/Error.h>
#include <spring_motion/internal/geometry/element_points.h>
#include <spring_motion/internal/geometry/exact_orientation.h>
#include <spring_motion/internal/geometry/simplex_tables.h>
#include <spring_motion/internal/geometry/sorted_faces.h>
#include <spring_motion/internal/solver/threads.h>

#include <algorithm>
#include <array>
#include <cstddef>
#include <cstdint>
#include <sstream>
#include <string>
#include <vector>

namespace spring_motion {

/// What is wrong with a simplex mesh before it is moved, judged with exact
/// predicates (see docs/method.md, "Validity and quality"). Every list holds
/// element indices in increasing order. A mesh is fit to be moved (`valid()`)
/// when it has no degenerate, overlapping or non-manifold elements; elements
/// oriented against the majority are reported but allowed, since inversion is
/// judged against each element's own recorded orientation.
struct Input_mesh_problems
{
  std::size_t positive = 0; ///< elements of positive exact orientation
  std::size_t negative = 0; ///< elements of negative exact orientation

  /// Zero exact orientation: no area (2D) or volume (3D).
  std::vector<std::size_t> degenerate;
  /// Oriented against the rest: the sign the majority of the elements has
  /// (on a tie, the sign of the first non-degenerate element) is the mesh's
  /// orientation, and these elements have the other one. Reported, not an
  /// error: a file may list its elements in either order.
  std::vector<std::size_t> mixed_orientation;
  /// Elements lying on the same side of a facet as the element they share it
  /// with (the two overlap). Of each such pair the element oriented against
  /// the majority is listed, both when their orientations agree.
  std::vector<std::size_t> overlapping;
  /// The elements around a facet that more than two elements share (the mesh
  /// is not a manifold); `non_manifold_facets` counts those facets.
  std::vector<std::size_t> non_manifold;
  std::size_t non_manifold_facets = 0;

  bool valid() const
  {
    return degenerate.empty() && overlapping.empty() && non_manifold.empty();
  }
};

namespace internal {

/// The exact orientation of every element (+1, -1 or 0) into `sign`, on
/// `threads` threads (0: OpenMP's default). Every vertex index must be in
/// range.
template <int D, class Points, class Elements>
void element_orientations(const Points& points, const Elements& elements, std::vector<signed char>& sign, int threads)
{
  const std::size_t m = elements.size();
  sign.assign(m, 0);
  // in parallel: the filtered predicates keep their rounding-mode state per call
#pragma omp parallel for schedule(static) num_threads(internal::thread_count(threads, m))
  for(long t = 0; t < long(m); ++t)
    sign[std::size_t(t)] =
        static_cast<signed char>(internal::exact_orientation(internal::element_points<D>(elements, points, std::size_t(t))));
}

/// The sign (+1 or -1) of the permutation taking an element's vertices
/// `element` (D + 1 distinct indices) to the order (`facet`..., apex), where
/// `facet` lists the other D vertices and `apex` is a local index.
template <int D, class Element, class Facet>
int permutation_sign(const Element& element, const Facet& facet, std::size_t apex)
{
  std::array<std::size_t, D + 1> local;
  for(std::size_t c = 0; c < std::size_t(D); ++c)
    for(std::size_t k = 0; k <= std::size_t(D); ++k)
      if(std::size_t(element[k]) == std::size_t(facet[c]))
        local[c] = k;
  local[std::size_t(D)] = apex;
  int inversions = 0;
  for(std::size_t i = 0; i <= std::size_t(D); ++i)
    for(std::size_t j = i + 1; j <= std::size_t(D); ++j)
      inversions += local[i] > local[j];
  return inversions % 2 == 0 ? 1 : -1;
}

/// check_input_mesh(), also giving each element's exact orientation (`sign`:
/// +1, -1 or 0), on `threads` threads (0: OpenMP's default).
template <int D, class Points, class Elements>
Input_mesh_problems check_input_mesh(const Points& points, const Elements& elements, std::vector<signed char>& sign,
                                     int threads)
{
  static_assert(D == 2 || D == 3, "check_input_mesh: dimension must be 2 or 3");
  using Tables = internal::Simplex_tables<D>;
  Input_mesh_problems problems;
  const std::size_t m = elements.size();
  for(std::size_t t = 0; t < m; ++t)
    for(int k = 0; k <= D; ++k)
      SPRING_MOTION_ELEMENT_CHECK(std::size_t(elements[t][std::size_t(k)]) < points.size(), t,
                                  "element " << t << " uses vertex " << elements[t][std::size_t(k)]
                                             << ", out of range (" << points.size() << " vertices)");

  // the exact tests in parallel, the lists in order
  element_orientations<D>(points, elements, sign, threads);
  int first_sign = 0;
  for(std::size_t t = 0; t < m; ++t) {
    const int o = sign[t];
    if(o == 0)
      problems.degenerate.push_back(t);
    else {
      ++(o > 0 ? problems.positive : problems.negative);
      if(first_sign == 0)
        first_sign = o;
    }
  }
  const int majority = problems.positive != problems.negative ? (problems.positive > problems.negative ? 1 : -1)
                                                              : first_sign;
  for(std::size_t t = 0; t < m; ++t)
    if(sign[t] == -majority)
      problems.mixed_orientation.push_back(t);

  // Facets as sorted vertex tuples: equal ones are one facet shared.
  constexpr std::uint32_t F = D + 1;
  const auto recs = internal::sorted_faces<D>(elements, Tables::facet, points.size());
  const long nr = long(recs.size());
  const auto same = [&](long a, long b) { return internal::same_face(recs[std::size_t(a)], recs[std::size_t(b)]); };
  // overlap[r]: the facet of records r and r + 1 is shared by exactly those
  // two non-degenerate elements, and their apexes lie on the same side of it
  std::vector<char> overlap(recs.size(), 0);
#pragma omp parallel for schedule(static) num_threads(internal::thread_count(threads, recs.size()))
  for(long r = 0; r < nr - 1; ++r) {
    if(!same(r, r + 1) || (r > 0 && same(r - 1, r)) || (r + 2 < nr && same(r, r + 2)))
      continue;
    const auto& ra = recs[std::size_t(r)];
    const auto& rb = recs[std::size_t(r) + 1];
    const std::uint32_t a = ra.slot / F, b = rb.slot / F;
    if(sign[a] == 0 || sign[b] == 0)
      continue;
    // the orientation of (sorted facet vertices, apex) is the element's
    // exact orientation times the sign of the permutation that reorders its
    // vertices so: no predicate needs to be evaluated again
    const int side_a = sign[a] * permutation_sign<D>(elements[a], ra.vertices, ra.slot % F);
    const int side_b = sign[b] * permutation_sign<D>(elements[b], rb.vertices, rb.slot % F);
    overlap[std::size_t(r)] = side_a == side_b;
  }
  for(long r = 0; r < nr;) {
    long s = r;
    while(s < nr && same(s, r))
      ++s;
    if(s - r > 2) {
      ++problems.non_manifold_facets;
      for(long i = r; i < s; ++i)
        problems.non_manifold.push_back(recs[std::size_t(i)].slot / F);
    } else if(s - r == 2 && overlap[std::size_t(r)]) {
      const std::uint32_t a = recs[std::size_t(r)].slot / F, b = recs[std::size_t(r) + 1].slot / F;
      const bool a_odd = sign[a] != majority, b_odd = sign[b] != majority;
      if(a_odd || !b_odd)
        problems.overlapping.push_back(a);
      if(b_odd || !a_odd)
        problems.overlapping.push_back(b);
    }
    r = s;
  }
  for(auto* list : {&problems.overlapping, &problems.non_manifold}) {
    std::sort(list->begin(), list->end());
    list->erase(std::unique(list->begin(), list->end()), list->end());
  }
  return problems;
}

} // namespace internal

/// Checks the elements of a mesh given by `points` and `elements` (each
/// element D + 1 indices into `points`; a `Spring_network`'s arrays or an
/// `Indexed_mesh`'s). Throws `Element_error` for an element that uses a
/// vertex out of range; every other problem is reported, not thrown.
template <int D, class Points, class Elements>
Input_mesh_problems check_input_mesh(const Points& points, const Elements& elements)
{
  std::vector<signed char> sign;
  return internal::check_input_mesh<D>(points, elements, sign, 0);
}

/// The first problem element: the first degenerate one, else the first
/// around a non-manifold facet, else the first overlapping one. `problems`
/// must not be valid.
inline std::size_t first_problem_element(const Input_mesh_problems& problems)
{
  for(const auto* list : {&problems.degenerate, &problems.non_manifold, &problems.overlapping})
    if(!list->empty())
      return list->front();
  return 0;
}

/// "1 degenerate element(s) in the input mesh (zero area or volume, exact
/// test): 4": what `Element_error` says about an invalid input mesh, one
/// such part per kind of problem, with the first few elements of each.
inline std::string describe_input_mesh_problems(const Input_mesh_problems& problems)
{
  std::ostringstream out;
  const char* separator = "";
  const auto part = [&](std::size_t count, const char* what, const std::vector<std::size_t>& elements) {
    if(count == 0)
      return;
    out << separator << count << " " << what << ": ";
    for(std::size_t i = 0; i < std::min<std::size_t>(5, elements.size()); ++i)
      out << (i ? ", " : "") << elements[i];
    out << (elements.size() > 5 ? ", ..." : "");
    separator = "; ";
  };
  part(problems.degenerate.size(), "degenerate element(s) in the input mesh (zero area or volume, exact test)",
       problems.degenerate);
  part(problems.non_manifold_facets,
       "facet(s) shared by more than two elements in the input mesh (not a manifold), around elements",
       problems.non_manifold);
  part(problems.overlapping.size(),
       "element(s) overlapping a neighbour in the input mesh (on the same side of the facet they share, exact test)",
       problems.overlapping);
  return out.str();
}

} // namespace spring_motion

#endif
