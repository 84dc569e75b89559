// Copyright (c) 2026 SpringMotion developers.
#ifndef SPRING_MOTION_INTERNAL_GEOMETRY_SORTED_FACES_H
#define SPRING_MOTION_INTERNAL_GEOMETRY_SORTED_FACES_H

#include <spring_motion/Error.h>

#include <algorithm>
#include <array>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <utility>
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

/// The slots of `m` elements, F per element (slot t * F + f), grouped by a key
/// below `number_of_keys`: `keyed_value(t, f)` gives a slot's key and value
/// as a pair, `key_of(t, f)` its key alone; group k holds the values of the
/// slots of key k, in slot order, at [start[k], start[k + 1]) of `values`.
/// A counting sort: two passes over the slots and none of the comparisons a
/// sort of all of them would make (on the set-up of a mesh, the key is a
/// vertex and the groups are a few dozen slots each).
template <std::size_t F, class Value, class Key_of, class Keyed_value>
void group_slots(std::size_t m, std::size_t number_of_keys, const Key_of& key_of, const Keyed_value& keyed_value,
                 std::vector<std::uint32_t>& start, std::vector<Value>& values)
{
  SPRING_MOTION_CHECK(m <= std::numeric_limits<std::uint32_t>::max() / F,
                      "too many elements: " << m << " (at most " << std::numeric_limits<std::uint32_t>::max() / F
                                            << ")");
  start.assign(number_of_keys + 1, 0);
  for(std::size_t t = 0; t < m; ++t)
    for(std::size_t f = 0; f < F; ++f)
      ++start[std::size_t(key_of(t, f)) + 1];
  for(std::size_t k = 0; k < number_of_keys; ++k)
    start[k + 1] += start[k];
  values.resize(m * F);
  std::vector<std::uint32_t> next(start.begin(), start.end() - 1);
  for(std::size_t t = 0; t < m; ++t)
    for(std::size_t f = 0; f < F; ++f) {
      const auto [key, value] = keyed_value(t, f);
      values[next[std::size_t(key)]++] = value;
    }
}

/// How often each value below `number_of_values` occurs in one group of
/// values at a time, and the group's distinct values. Each value keeps the
/// number of the group that met it last, so starting a group clears
/// nothing: a per-value table cleared for each of a mesh's vertices would
/// cost the square of its size. At most 2^32 - 1 groups.
class Group_counter
{
public:
  explicit Group_counter(std::size_t number_of_values) : entry_(number_of_values) {}

  void start_group()
  {
    ++group_;
    distinct_.clear();
  }
  /// Counts one more v in this group; returns how many came before it.
  std::uint32_t add(std::uint32_t v)
  {
    Entry& e = entry_[v];
    if(e.group != group_) {
      e.group = group_;
      e.count = 0;
      distinct_.push_back(v);
    }
    return e.count++;
  }
  /// How often v occurs in this group; v must have been added in it.
  std::uint32_t count(std::uint32_t v) const { return entry_[v].count; }
  /// This group's distinct values, in increasing order.
  const std::vector<std::uint32_t>& sorted_distinct()
  {
    std::sort(distinct_.begin(), distinct_.end());
    return distinct_;
  }

private:
  struct Entry
  {
    std::uint32_t group = 0, count = 0; // group 0: none yet
  };
  std::vector<Entry> entry_;
  std::vector<std::uint32_t> distinct_;
  std::uint32_t group_ = 0;
};

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
  const auto smallest = [&](std::size_t t, std::size_t f) {
    std::uint32_t v = std::uint32_t(elements[t][std::size_t(local[f][0])]);
    for(int c = 1; c < K; ++c)
      v = std::min(v, std::uint32_t(elements[t][std::size_t(local[f][std::size_t(c)])]));
    return v;
  };
  const auto keyed_face = [&](std::size_t t, std::size_t f) {
    Face_record<K> r;
    for(int c = 0; c < K; ++c)
      r.vertices[std::size_t(c)] = std::uint32_t(elements[t][std::size_t(local[f][std::size_t(c)])]);
    sort_small(r.vertices);
    r.slot = std::uint32_t(t * F + f);
    return std::pair{r.vertices[0], r};
  };
  const std::size_t n = number_of_vertices;
  std::vector<std::uint32_t> start; // vertex v's records: [start[v], start[v + 1]), in slot order
  std::vector<Face_record<K>> records;
  group_slots<F>(elements.size(), n, smallest, keyed_face, start, records);
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
  const std::size_t m = elements.size(), n = number_of_vertices;
  struct Slot
  {
    std::uint32_t other, slot; // the larger vertex, element * E + local edge
  };
  const auto end = [&](std::size_t t, std::size_t j, std::size_t c) {
    return std::uint32_t(elements[t][std::size_t(local[j][c])]);
  };
  const auto smaller = [&](std::size_t t, std::size_t j) { return std::min(end(t, j, 0), end(t, j, 1)); };
  const auto slot = [&](std::size_t t, std::size_t j) {
    const std::uint32_t a = end(t, j, 0), b = end(t, j, 1);
    return std::pair{std::min(a, b), Slot{std::max(a, b), std::uint32_t(t * E + j)}};
  };
  std::vector<std::uint32_t> start; // vertex v's slots: [start[v], start[v + 1]), in slot order
  std::vector<Slot> slots;
  group_slots<E>(m, n, smaller, slot, start, slots);
  // the slots of the edge (v, w) in slot order give each its rank; v's
  // distinct neighbours in increasing order give the edge numbers
  Group_counter neighbours(n);
  std::vector<std::uint32_t> edge_to(n); // per neighbour w of the vertex at hand
  edges.clear();
  element_edges.resize(m * E);
  rank.resize(m * E);
  for(std::size_t v = 0; v < n; ++v) {
    const Slot* first = slots.data() + start[v];
    const Slot* last = slots.data() + start[v + 1];
    neighbours.start_group();
    for(const Slot* s = first; s != last; ++s)
      rank[s->slot] = neighbours.add(s->other);
    for(const std::uint32_t w : neighbours.sorted_distinct()) {
      edge_to[w] = std::uint32_t(edges.size());
      edges.push_back({std::uint32_t(v), w});
    }
    for(const Slot* s = first; s != last; ++s)
      element_edges[s->slot] = edge_to[s->other];
  }
  edges.shrink_to_fit(); // kept for the whole run: no spare capacity
}

} // namespace internal
} // namespace spring_motion

#endif
