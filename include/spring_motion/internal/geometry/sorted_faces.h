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

/// Whether two records are copies of one face. Compared value by value:
/// std::array's operator== calls memcmp, a library call per record.
template <int K>
inline bool same_face(const Face_record<K>& a, const Face_record<K>& b)
{
  bool same = true;
  for(std::size_t c = 0; c < std::size_t(K); ++c)
    same = same & (a.vertices[c] == b.vertices[c]);
  return same;
}

/// The K values in increasing order (compare-exchanges, no branches).
template <std::size_t K>
inline void sort_small(std::array<std::uint32_t, K>& v)
{
  const auto exchange = [&](std::size_t i, std::size_t j) {
    const std::uint32_t lo = std::min(v[i], v[j]), hi = std::max(v[i], v[j]);
    v[i] = lo;
    v[j] = hi;
  };
  if constexpr(K == 2) {
    exchange(0, 1);
  } else if constexpr(K == 3) {
    exchange(0, 1);
    exchange(1, 2);
    exchange(0, 1);
  } else {
    std::sort(v.begin(), v.end());
  }
}

/// Every local face of every element, sorted by (vertices, slot): the
/// copies of a face shared by several elements are adjacent, in increasing
/// element order. `local[f]` lists the local vertices of face f; every
/// vertex index must be below `number_of_vertices`.
///
/// A counting sort by the smallest vertex, then a sort of each vertex's few
/// records (a few dozen): on a 320k-tetrahedron mesh a comparison sort of
/// all of them took most of the setup before the first step. On one
/// thread, as the rest of the set-up: beside a busy machine's other
/// processes, barriers wait for descheduled threads (a parallel version was
/// faster on the idle machine and slower beside two busy processes).
template <int K, std::size_t F, class Elements>
std::vector<Face_record<K>> sorted_faces(const Elements& elements, const std::array<std::array<int, K>, F>& local,
                                         std::size_t number_of_vertices)
{
  const std::size_t m = elements.size();
  SPRING_MOTION_CHECK(m <= std::numeric_limits<std::uint32_t>::max() / F,
                      "too many elements: " << m << " (at most " << std::numeric_limits<std::uint32_t>::max() / F
                                            << ")");
  const std::size_t n = number_of_vertices;
  const auto face = [&](std::size_t t, std::size_t f) {
    Face_record<K> r;
    for(int c = 0; c < K; ++c)
      r.vertices[std::size_t(c)] = std::uint32_t(elements[t][std::size_t(local[f][std::size_t(c)])]);
    sort_small(r.vertices);
    r.slot = std::uint32_t(t * F + f);
    return r;
  };
  std::vector<std::uint32_t> start(n + 1, 0); // vertex v's records: [start[v], start[v + 1])
  for(std::size_t t = 0; t < m; ++t)
    for(std::size_t f = 0; f < F; ++f) {
      std::uint32_t v = std::uint32_t(elements[t][std::size_t(local[f][0])]);
      for(int c = 1; c < K; ++c)
        v = std::min(v, std::uint32_t(elements[t][std::size_t(local[f][std::size_t(c)])]));
      ++start[v + 1];
    }
  for(std::size_t v = 0; v < n; ++v)
    start[v + 1] += start[v];
  // placed in slot order, so each vertex's run starts sorted by slot
  std::vector<Face_record<K>> records(m * F);
  std::vector<std::uint32_t> next(start.begin(), start.end() - 1);
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
  // A run arrives in slot order, so a stable sort by the other vertices
  // alone gives the order by (vertices, slot): for an edge or a triangle
  // those make one integer, and an insertion sort by it (stable) handles the
  // runs of a tetrahedral mesh (a few dozen records) in about half the time
  // std::sort took with the comparison above. A longer run (a vertex shared
  // by hundreds of elements) still goes to std::sort. The order is the same:
  // no two records are equal in (vertices, slot).
  static_assert(K == 2 || K == 3, "faces are edges or triangles");
  const auto key = [](const Face_record<K>& r) {
    if constexpr(K == 2)
      return std::uint64_t(r.vertices[1]);
    else
      return std::uint64_t(r.vertices[1]) << 32 | r.vertices[2];
  };
  constexpr std::ptrdiff_t insertion_limit = 160;
  for(std::size_t v = 0; v < n; ++v) {
    Face_record<K>* first = records.data() + start[v];
    Face_record<K>* last = records.data() + start[v + 1];
    if(last - first > insertion_limit) {
      std::sort(first, last, before);
      continue;
    }
    for(Face_record<K>* i = first + 1; i < last; ++i) {
      const Face_record<K> r = *i;
      const std::uint64_t k = key(r);
      Face_record<K>* j = i;
      for(; j > first && key(j[-1]) > k; --j)
        *j = j[-1];
      *j = r;
    }
  }
  return records;
}

/// The edges of a mesh, numbered: `edges` gets each edge once as (a, b),
/// a < b, in increasing order; `element_edges[t * E + j]` the number of
/// local edge j of element t (E = local.size()); `rank` the place of that
/// slot among its edge's slots, in increasing slot order. The same as
/// numbering the unique records of sorted_faces<2>, without sorting them:
/// each vertex's slots (those whose smaller vertex it is) arrive in slot
/// order, and only its distinct neighbours, a third of its slots in a
/// tetrahedral mesh, are sorted.
template <std::size_t E, class Elements>
void number_edges(const Elements& elements, const std::array<std::array<int, 2>, E>& local,
                  std::size_t number_of_vertices, std::vector<std::array<std::uint32_t, 2>>& edges,
                  std::vector<std::uint32_t>& element_edges, std::vector<std::uint32_t>& rank)
{
  const std::size_t m = elements.size();
  SPRING_MOTION_CHECK(m <= std::numeric_limits<std::uint32_t>::max() / E,
                      "too many elements: " << m << " (at most " << std::numeric_limits<std::uint32_t>::max() / E
                                            << ")");
  const std::size_t n = number_of_vertices;
  struct Slot
  {
    std::uint32_t other, slot; // the larger vertex, element * E + local edge
  };
  const auto ends = [&](std::size_t t, std::size_t j) {
    const auto a = std::uint32_t(elements[t][std::size_t(local[j][0])]);
    const auto b = std::uint32_t(elements[t][std::size_t(local[j][1])]);
    return std::array<std::uint32_t, 2>{std::min(a, b), std::max(a, b)};
  };
  std::vector<std::uint32_t> start(n + 1, 0); // vertex v's slots: [start[v], start[v + 1])
  for(std::size_t t = 0; t < m; ++t)
    for(std::size_t j = 0; j < E; ++j)
      ++start[ends(t, j)[0] + 1];
  for(std::size_t v = 0; v < n; ++v)
    start[v + 1] += start[v];
  std::vector<Slot> slots(m * E);
  {
    std::vector<std::uint32_t> next(start.begin(), start.end() - 1);
    for(std::size_t t = 0; t < m; ++t)
      for(std::size_t j = 0; j < E; ++j) {
        const auto e = ends(t, j);
        slots[next[e[0]]++] = {e[1], std::uint32_t(t * E + j)};
      }
  }
  // per neighbour w of the vertex at hand: the vertex + 1 that saw it last,
  // the number of the edge to it and the slots of that edge met so far
  struct Neighbour
  {
    std::uint32_t seen = 0, edge = 0, slots = 0;
  };
  std::vector<Neighbour> neighbour(n);
  std::vector<std::uint32_t> others;
  edges.clear();
  element_edges.resize(m * E);
  rank.resize(m * E);
  for(std::size_t v = 0; v < n; ++v) {
    const Slot* first = slots.data() + start[v];
    const Slot* last = slots.data() + start[v + 1];
    others.clear();
    for(const Slot* s = first; s != last; ++s)
      if(neighbour[s->other].seen != v + 1) {
        neighbour[s->other].seen = std::uint32_t(v + 1);
        others.push_back(s->other);
      }
    std::sort(others.begin(), others.end());
    for(const std::uint32_t w : others) {
      neighbour[w].edge = std::uint32_t(edges.size());
      neighbour[w].slots = 0;
      edges.push_back({std::uint32_t(v), w});
    }
    for(const Slot* s = first; s != last; ++s) {
      Neighbour& w = neighbour[s->other];
      element_edges[s->slot] = w.edge;
      rank[s->slot] = w.slots++;
    }
  }
  edges.shrink_to_fit(); // kept for the whole run: no spare capacity
}

} // namespace internal
} // namespace spring_motion

#endif
