// Copyright (c) 2026 SpringMotion developers.
#ifndef SPRING_MOTION_INTERNAL_GEOMETRY_SORTED_FACES_H
#define SPRING_MOTION_INTERNAL_GEOMETRY_SORTED_FACES_H

#include <spring_motion/Error.h>

#include <algorithm>
#include <array>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <vector>

namespace spring_motion {
namespace internal {

/// One K-vertex face (an edge, a facet) of one element: its vertices in
/// increasing order and the slot it came from, element * F + local face.
template <int K>
struct Face_record
{
  std::array<std::uint32_t, K> vertices;
  std::uint32_t slot;
};

/// Every local face of every element, sorted by (vertices, slot): the
/// copies of a face shared by several elements are adjacent, in increasing
/// element order. `local[f]` lists the local vertices of face f; every
/// vertex index must be below `number_of_vertices`.
///
/// A counting sort by the smallest vertex, then a sort of each vertex's few
/// records (about twenty): on a 320k-tetrahedron mesh a comparison sort of
/// all of them took most of the setup before the first step.
template <int K, std::size_t F, class Elements>
std::vector<Face_record<K>> sorted_faces(const Elements& elements, const std::array<std::array<int, K>, F>& local,
                                         std::size_t number_of_vertices)
{
  const std::size_t m = elements.size();
  SPRING_MOTION_CHECK(m <= std::numeric_limits<std::uint32_t>::max() / F,
                      "too many elements: " << m << " (at most " << std::numeric_limits<std::uint32_t>::max() / F
                                            << ")");
  const auto face = [&](std::size_t t, std::size_t f) {
    Face_record<K> r;
    for(int c = 0; c < K; ++c)
      r.vertices[std::size_t(c)] = std::uint32_t(elements[t][std::size_t(local[f][std::size_t(c)])]);
    std::sort(r.vertices.begin(), r.vertices.end());
    r.slot = std::uint32_t(t * F + f);
    return r;
  };
  std::vector<std::size_t> start(number_of_vertices + 1, 0);
  for(std::size_t t = 0; t < m; ++t)
    for(std::size_t f = 0; f < F; ++f)
      ++start[face(t, f).vertices[0] + 1];
  for(std::size_t v = 0; v < number_of_vertices; ++v)
    start[v + 1] += start[v];
  // placed in slot order, so each vertex's run starts sorted by slot
  std::vector<Face_record<K>> records(m * F);
  std::vector<std::size_t> next(start.begin(), start.end() - 1);
  for(std::size_t t = 0; t < m; ++t)
    for(std::size_t f = 0; f < F; ++f) {
      const Face_record<K> r = face(t, f);
      records[next[r.vertices[0]]++] = r;
    }
  const auto before = [](const Face_record<K>& a, const Face_record<K>& b) {
    for(std::size_t c = 1; c < std::size_t(K); ++c)
      if(a.vertices[c] != b.vertices[c])
        return a.vertices[c] < b.vertices[c];
    return a.slot < b.slot;
  };
  for(std::size_t v = 0; v < number_of_vertices; ++v)
    std::sort(records.begin() + std::ptrdiff_t(start[v]), records.begin() + std::ptrdiff_t(start[v + 1]), before);
  return records;
}

} // namespace internal
} // namespace spring_motion

#endif
