// Copyright (c) 2026 SpringMotion developers.
#ifndef SPRING_MOTION_INTERNAL_GEOMETRY_SIMPLEX_TABLES_H
#define SPRING_MOTION_INTERNAL_GEOMETRY_SIMPLEX_TABLES_H

#include <array>
#include <cstddef>

namespace spring_motion {
namespace internal {

/// Local numbering of a simplex's edges. In a triangle, local edge k is the
/// one opposite vertex k, so its facing angle is the angle at vertex k.
template <int D>
struct Simplex_tables;

template <>
struct Simplex_tables<2>
{
  static constexpr int vertices = 3;
  static constexpr int edges = 3;
  static constexpr int facets = 3;
  static constexpr std::array<std::array<int, 2>, 3> edge{{{1, 2}, {0, 2}, {0, 1}}};
  // facet k is opposite vertex k
  static constexpr std::array<std::array<int, 2>, 3> facet{{{1, 2}, {0, 2}, {0, 1}}};
};

template <>
struct Simplex_tables<3>
{
  static constexpr int vertices = 4;
  static constexpr int edges = 6;
  static constexpr int facets = 4;
  static constexpr std::array<std::array<int, 2>, 6> edge{{{0, 1}, {0, 2}, {0, 3}, {1, 2}, {1, 3}, {2, 3}}};
  // the two vertices not on edge k: the dihedral angle at edge k lies between
  // the faces (edge, other[0]) and (edge, other[1])
  static constexpr std::array<std::array<int, 2>, 6> other{{{2, 3}, {1, 3}, {1, 2}, {0, 3}, {0, 2}, {0, 1}}};
  static constexpr std::array<std::array<int, 3>, 4> facet{{{1, 2, 3}, {0, 2, 3}, {0, 1, 3}, {0, 1, 2}}};
};

/// The local edge between local vertices a and b (a != b) of a simplex:
/// local_edges<D>()[a][b], the inverse of Simplex_tables<D>::edge (the
/// diagonal is not an edge and reads 0).
template <int D>
constexpr std::array<std::array<int, D + 1>, D + 1> local_edges()
{
  std::array<std::array<int, D + 1>, D + 1> t{};
  for(int j = 0; j < Simplex_tables<D>::edges; ++j) {
    const auto& e = Simplex_tables<D>::edge[std::size_t(j)];
    t[std::size_t(e[0])][std::size_t(e[1])] = j;
    t[std::size_t(e[1])][std::size_t(e[0])] = j;
  }
  return t;
}
static_assert(local_edges<2>()[2][1] == 0 && local_edges<2>()[0][2] == 1 && local_edges<2>()[1][0] == 2);
static_assert(local_edges<3>()[1][0] == 0 && local_edges<3>()[3][1] == 4 && local_edges<3>()[2][3] == 5);

} // namespace internal
} // namespace spring_motion

#endif
