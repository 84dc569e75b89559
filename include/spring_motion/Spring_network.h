// Copyright (c) 2026 SpringMotion developers.
#ifndef SPRING_MOTION_SPRING_NETWORK_H
#define SPRING_MOTION_SPRING_NETWORK_H

#include <spring_motion/Error.h>
#include <spring_motion/internal/geometry/angles.h>
#include <spring_motion/internal/geometry/simplex_tables.h>
#include <spring_motion/internal/geometry/sorted_faces.h>
#include <spring_motion/internal/solver/angle_slots.h>
#include <spring_motion/mesh_traits/Simplicial_mesh_traits.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <numeric>
#include <type_traits>
#include <unordered_map>
#include <utility>
#include <vector>

namespace spring_motion {

using Index = std::uint32_t;

/// The spring network of a simplex mesh in flat, index-based arrays: built
/// once per mesh, then every step works on it and never on mesh handles.
/// Edges are the springs; elements give the angles; facets of exactly one
/// element form the boundary.
template <int D>
struct Spring_network
{
  static_assert(D == 2 || D == 3, "Spring_network: dimension must be 2 or 3");
  static constexpr int dimension = D;
  using Tables = internal::Simplex_tables<D>;
  static constexpr int edges_per_element = Tables::edges;
  using Point = std::array<double, D>;
  using Element = std::array<Index, D + 1>;
  using Facet = std::array<Index, D>;
  using Edge = std::array<Index, 2>;

  std::vector<Point> points;          // initial positions
  std::vector<Element> elements;
  std::vector<Edge> edges;            // unique, edges[e][0] < edges[e][1], sorted
  std::vector<Index> element_edges;   // edges_per_element per element, local numbering of Simplex_tables

  // CSR adjacency: the neighbours of vertex i are adjacency[offsets[i] .. offsets[i+1]),
  // reached through edge adjacency_edge[...]
  std::vector<Index> adjacency_offsets, adjacency, adjacency_edge;

  std::vector<Facet> boundary_facets;
  std::vector<char> on_boundary;      // per vertex
  // labels of the boundary parts each vertex lies on: vertex_labels[offsets[i] .. offsets[i+1])
  std::vector<Index> vertex_label_offsets;
  std::vector<int> vertex_labels;

  double longest_initial_edge = 0;

  std::size_t number_of_vertices() const { return points.size(); }
  std::size_t number_of_elements() const { return elements.size(); }
  std::size_t number_of_edges() const { return edges.size(); }
  Index edge_of(Index element, int local) const { return element_edges[element * edges_per_element + local]; }

private:
  friend struct internal::Network_access;
  internal::Angle_slots slots_;
};

/// A labeled boundary facet given by the mesh (vertex indices into the network).
template <int D>
struct Labeled_facet
{
  std::array<Index, D> vertices;
  int label;
};

/// Per vertex, 1 if some element uses it: a vertex no element uses takes no
/// part in the motion.
template <int D>
std::vector<char> used_vertices(const Spring_network<D>& net)
{
  std::vector<char> used(net.number_of_vertices(), 0);
  for(const auto& e : net.elements)
    for(Index v : e)
      used[v] = 1;
  return used;
}

namespace internal {

/// Bit b of the low 21 bits of x moved to bit 3b (spread_bits_3), of the
/// low 32 bits to bit 2b (spread_bits_2): five shift-and-mask steps instead
/// of a loop over the bits.
inline std::uint64_t spread_bits_3(std::uint64_t x)
{
  x &= 0x1fffff;
  x = (x | x << 32) & 0x1f00000000ffffULL;
  x = (x | x << 16) & 0x1f0000ff0000ffULL;
  x = (x | x << 8) & 0x100f00f00f00f00fULL;
  x = (x | x << 4) & 0x10c30c30c30c30c3ULL;
  x = (x | x << 2) & 0x1249249249249249ULL;
  return x;
}
inline std::uint64_t spread_bits_2(std::uint64_t x)
{
  x &= 0xffffffffULL;
  x = (x | x << 16) & 0x0000ffff0000ffffULL;
  x = (x | x << 8) & 0x00ff00ff00ff00ffULL;
  x = (x | x << 4) & 0x0f0f0f0f0f0f0f0fULL;
  x = (x | x << 2) & 0x3333333333333333ULL;
  x = (x | x << 1) & 0x5555555555555555ULL;
  return x;
}

/// Interleaves the low 21 bits of x, y, z (3D) or the low 32 of x, y (2D):
/// bit b of coordinate c is bit D * b + c of the code.
template <int D>
std::uint64_t morton_code(const std::array<std::uint32_t, D>& q)
{
  if constexpr(D == 3)
    return spread_bits_3(q[0]) | spread_bits_3(q[1]) << 1 | spread_bits_3(q[2]) << 2;
  else
    return spread_bits_2(q[0]) | spread_bits_2(q[1]) << 1;
}

/// The Morton code of each element's centroid, its coordinates scaled to
/// the bounding box of the points and cut to 21 (3D) or 32 (2D) bits.
template <int D>
std::vector<std::uint64_t> centroid_morton_codes(const Spring_network<D>& net)
{
  constexpr int bits = D == 3 ? 21 : 32;
  const std::size_t m = net.elements.size();
  std::array<double, D> lo, hi;
  lo.fill(std::numeric_limits<double>::infinity());
  hi.fill(-std::numeric_limits<double>::infinity());
  for(const auto& p : net.points)
    for(int c = 0; c < D; ++c) {
      lo[c] = std::min(lo[c], p[c]);
      hi[c] = std::max(hi[c], p[c]);
    }
  std::vector<std::uint64_t> code(m);
  const double cells = std::ldexp(1.0, bits) - 1;
  // halves and shares of coordinates, so that no sum or difference of
  // coordinates near the largest double overflows
  for(std::size_t t = 0; t < m; ++t) {
    std::array<std::uint32_t, D> q;
    for(int c = 0; c < D; ++c) {
      double centre = 0;
      for(Index v : net.elements[t])
        centre += net.points[v][c] / (D + 1);
      const double u = hi[c] > lo[c] ? (centre / 2 - lo[c] / 2) / (hi[c] / 2 - lo[c] / 2) : 0.0;
      q[c] = std::uint32_t(std::clamp(u, 0.0, 1.0) * cells);
    }
    code[t] = morton_code<D>(q);
  }
  return code;
}

/// The elements in a spatial order: by the Morton code of their centroid
/// (ties by number). Loops that gather vertices and scatter into per-edge or
/// per-row arrays run in this order so that both stay close together in
/// memory; in the order of a Mesh_3 or Gmsh file, neighbours in the list lie
/// scattered through space.
template <int D>
std::vector<Index> spatial_element_order(const Spring_network<D>& net)
{
  std::vector<std::uint64_t> code = centroid_morton_codes(net);
  const std::size_t m = code.size();
  // A least-significant-digit radix sort, 11 bits a pass: stable, so ties
  // keep the elements' order, the order a comparison sort of (code, element)
  // pairs gives, in two thirds of that sort's time on the wing.
  constexpr int digit_bits = 11;
  constexpr std::size_t buckets = std::size_t(1) << digit_bits;
  std::vector<Index> order(m), sorted(m);
  std::iota(order.begin(), order.end(), Index(0));
  std::vector<std::uint64_t> sorted_code(m);
  std::vector<std::size_t> start(buckets);
  for(int shift = 0; shift < 64; shift += digit_bits) {
    std::fill(start.begin(), start.end(), 0);
    for(std::size_t i = 0; i < m; ++i)
      ++start[(code[i] >> shift) & (buckets - 1)];
    if(std::find(start.begin(), start.end(), m) != start.end())
      continue; // every code has the same digit here: the pass would change nothing
    std::size_t sum = 0;
    for(std::size_t& s : start)
      sum += std::exchange(s, sum);
    for(std::size_t i = 0; i < m; ++i) {
      const std::size_t at = start[(code[i] >> shift) & (buckets - 1)]++;
      sorted[at] = order[i];
      sorted_code[at] = code[i];
    }
    order.swap(sorted);
    code.swap(sorted_code);
  }
  return order;
}

/// The traversal and layout of the element angles (see Angle_slots), from
/// the edges of the network and each slot's rank among its edge's slots.
template <int D>
void build_angle_layout(Spring_network<D>& net, const std::vector<Index>& rank)
{
  constexpr int E = Spring_network<D>::edges_per_element;
  Angle_slots& tab = Network_access::slots(net);
  const std::size_t m = net.elements.size(), ne = net.edges.size();
  const std::vector<Index> order = spatial_element_order(net);
  // edges in the order the traversal first meets them
  constexpr Index unseen = std::numeric_limits<Index>::max();
  std::vector<Index> layout_of(ne, unseen);
  tab.layout_edge.clear();
  tab.layout_edge.reserve(ne);
  for(const Index t : order)
    for(int j = 0; j < E; ++j) {
      const Index e = net.element_edges[std::size_t(t) * E + std::size_t(j)];
      if(layout_of[e] == unseen) {
        layout_of[e] = Index(tab.layout_edge.size());
        tab.layout_edge.push_back(e);
      }
    }
  // the number of slots of each edge is its largest rank + 1
  std::vector<Index> count(ne, 0);
  for(std::size_t s = 0; s < m * E; ++s)
    count[net.element_edges[s]] = std::max(count[net.element_edges[s]], rank[s] + 1);
  tab.layout_slot_offsets.assign(ne + 1, 0);
  for(std::size_t q = 0; q < ne; ++q)
    tab.layout_slot_offsets[q + 1] = tab.layout_slot_offsets[q] + count[tab.layout_edge[q]];
  // vertices numbered in the order the traversal first meets them
  std::vector<Index> local(net.points.size(), unseen);
  tab.traversal_vertices.clear();
  tab.ordered_elements.resize(m * (D + 1));
  tab.slot_position.resize(m * E);
  for(std::size_t i = 0; i < m; ++i) {
    const std::size_t t = order[i];
    for(int k = 0; k <= D; ++k) {
      const Index v = net.elements[t][std::size_t(k)];
      if(local[v] == unseen) {
        local[v] = Index(tab.traversal_vertices.size());
        tab.traversal_vertices.push_back(v);
      }
      tab.ordered_elements[i * (D + 1) + std::size_t(k)] = local[v];
    }
    for(int j = 0; j < E; ++j) {
      const std::size_t s = t * E + std::size_t(j);
      tab.slot_position[i * E + std::size_t(j)] = tab.layout_slot_offsets[layout_of[net.element_edges[s]]] + rank[s];
    }
  }
  tab.traversal_vertices.shrink_to_fit();
  tab.layout_edge_ends.resize(ne);
  for(std::size_t q = 0; q < ne; ++q)
    for(int c = 0; c < 2; ++c)
      tab.layout_edge_ends[q][std::size_t(c)] = local[net.edges[tab.layout_edge[q]][std::size_t(c)]];
}

/// The facets of exactly one element of `net` (whose edges are numbered), in
/// increasing order of their sorted vertices; throws `Error` for a facet of
/// more than two. A facet (a, b, c), a < b < c, is told by a and the number
/// of its edge (b, c): the facets are grouped by a with a counting sort and
/// counted by edge number within a group, which gives the order of (a, b, c)
/// since the edges are numbered in order. No sort of all the facets.
template <int D>
std::vector<std::array<Index, D>> boundary_facets(const Spring_network<D>& net)
{
  using Tables = typename Spring_network<D>::Tables;
  constexpr std::size_t E = Spring_network<D>::edges_per_element;
  const std::size_t m = net.elements.size(), ne = net.edges.size(), n = net.points.size();
  const auto too_many = [](std::size_t count) {
    SPRING_MOTION_CHECK(count <= 2, "a facet is shared by " << count
                                        << " elements: the mesh is not a manifold simplicial complex");
  };
  std::vector<std::array<Index, D>> facets;
  if constexpr(D == 2) {
    // a facet is an edge
    std::vector<Index> count(ne, 0);
    for(const Index e : net.element_edges)
      ++count[e];
    for(std::size_t e = 0; e < ne; ++e) {
      too_many(count[e]);
      if(count[e] == 1)
        facets.push_back(net.edges[e]);
    }
  } else {
    constexpr auto local_edge = internal::local_edges<D>();
    // facet k of element t: its smallest vertex and the edge of the other two
    const auto facet = [&](std::size_t t, std::size_t k) {
      std::array<int, 3> l = Tables::facet[k];
      const auto& v = net.elements[t];
      for(int i : {1, 2})
        if(v[std::size_t(l[std::size_t(i)])] < v[std::size_t(l[0])])
          std::swap(l[0], l[std::size_t(i)]);
      const std::size_t j = std::size_t(local_edge[std::size_t(l[1])][std::size_t(l[2])]);
      return std::pair<Index, Index>{v[std::size_t(l[0])], net.element_edges[t * E + j]};
    };
    // the facets' edges, grouped by their smallest vertex a: [start[a], start[a + 1])
    std::vector<Index> start, edge_of;
    group_slots<4>(
        m, n, [&](std::size_t t, std::size_t k) { return facet(t, k).first; }, facet, start, edge_of);
    Group_counter facets_of_a(ne); // per edge (b, c): the facets (a, b, c)
    for(std::size_t a = 0; a < n; ++a) {
      facets_of_a.start_group();
      for(Index i = start[a]; i < start[a + 1]; ++i)
        facets_of_a.add(edge_of[i]);
      for(const Index e : facets_of_a.sorted_distinct()) {
        too_many(facets_of_a.count(e));
        if(facets_of_a.count(e) == 1)
          facets.push_back({Index(a), net.edges[e][0], net.edges[e][1]});
      }
    }
  }
  return facets;
}

} // namespace internal

/// Builds the network from points and elements. Throws `Error` on
/// non-finite coordinates, vertex indices out of range, repeated vertices in
/// an element, an empty mesh, and labeled facets that are not boundary facets.
/// Vertices used by no element are kept (they take no part in the motion).
template <int D>
Spring_network<D> make_spring_network(std::vector<std::array<double, D>> points,
                                      std::vector<std::array<Index, D + 1>> elements,
                                      const std::vector<Labeled_facet<D>>& labeled_facets = {})
{
  using Net = Spring_network<D>;
  using Tables = typename Net::Tables;
  Net net;
  SPRING_MOTION_CHECK(!elements.empty(), "the mesh has no elements");
  const std::size_t n = points.size();
  SPRING_MOTION_CHECK(n < std::numeric_limits<Index>::max(), "too many vertices: " << n);
  for(std::size_t i = 0; i < n; ++i)
    for(int c = 0; c < D; ++c)
      SPRING_MOTION_CHECK(std::isfinite(points[i][c]),
                          "vertex " << i << " has a non-finite coordinate " << points[i][c]);
  for(std::size_t t = 0; t < elements.size(); ++t)
    for(int a = 0; a <= D; ++a) {
      SPRING_MOTION_CHECK(elements[t][a] < n, "element " << t << " uses vertex " << elements[t][a]
                                                          << ", out of range (" << n << " vertices)");
      for(int b = 0; b < a; ++b)
        SPRING_MOTION_CHECK(elements[t][a] != elements[t][b],
                            "element " << t << " repeats vertex " << elements[t][a]);
    }
  net.points = std::move(points);
  net.elements = std::move(elements);

  // Edges, numbered in increasing (min, max) order.
  {
    std::vector<Index> rank;
    internal::number_edges(net.elements, Tables::edge, n, net.edges, net.element_edges, rank);
    internal::build_angle_layout(net, rank);
  }

  // CSR adjacency, neighbours in increasing order.
  {
    std::vector<Index> degree(n + 1, 0);
    for(const auto& e : net.edges) {
      ++degree[e[0]];
      ++degree[e[1]];
    }
    net.adjacency_offsets.assign(n + 1, 0);
    for(std::size_t i = 0; i < n; ++i)
      net.adjacency_offsets[i + 1] = net.adjacency_offsets[i] + degree[i];
    net.adjacency.resize(2 * net.edges.size());
    net.adjacency_edge.resize(2 * net.edges.size());
    std::vector<Index> fill(net.adjacency_offsets.begin(), net.adjacency_offsets.end() - 1);
    // edges are sorted by (a, b): visiting them in order fills every row sorted,
    // first the smaller neighbours (as b), then the larger ones (as a)
    for(Index e = 0; e < net.edges.size(); ++e) {
      const Index b = net.edges[e][1];
      net.adjacency[fill[b]] = net.edges[e][0];
      net.adjacency_edge[fill[b]++] = e;
    }
    for(Index e = 0; e < net.edges.size(); ++e) {
      const Index a = net.edges[e][0];
      net.adjacency[fill[a]] = net.edges[e][1];
      net.adjacency_edge[fill[a]++] = e;
    }
  }

  // Facets: those of exactly one element are the boundary.
  {
    using Key = std::array<Index, D>;
    net.boundary_facets = internal::boundary_facets(net);
    net.on_boundary.assign(n, 0);
    for(const auto& f : net.boundary_facets)
      for(Index v : f)
        net.on_boundary[v] = 1;

    // Labels: a vertex carries every label of the labeled facets it lies on.
    std::vector<std::pair<Index, int>> vl;
    for(const auto& lf : labeled_facets) {
      Key key = lf.vertices;
      for(Index v : key)
        SPRING_MOTION_CHECK(v < n, "labeled facet uses vertex " << v << ", out of range");
      std::sort(key.begin(), key.end());
      SPRING_MOTION_CHECK(std::binary_search(net.boundary_facets.begin(), net.boundary_facets.end(), key),
                          "a facet with label " << lf.label << " is not on the boundary of the mesh");
      for(Index v : key)
        vl.push_back({v, lf.label});
    }
    std::sort(vl.begin(), vl.end());
    vl.erase(std::unique(vl.begin(), vl.end()), vl.end());
    net.vertex_label_offsets.assign(n + 1, 0);
    for(const auto& p : vl)
      ++net.vertex_label_offsets[p.first + 1];
    for(std::size_t i = 0; i < n; ++i)
      net.vertex_label_offsets[i + 1] += net.vertex_label_offsets[i];
    net.vertex_labels.reserve(vl.size());
    for(const auto& p : vl)
      net.vertex_labels.push_back(p.second);
  }

  for(const auto& e : net.edges)
    net.longest_initial_edge =
        std::max(net.longest_initial_edge, internal::distance<D>(net.points[e[0]], net.points[e[1]]));
  return net;
}

namespace internal {

/// 3D: the unique triangular faces of the network, their edges and the
/// edge-major order of the face slots, which only models on face angles
/// (`Angle_kind::face`) read. Built on first use (by `Network_deformer`
/// before such a model's first step), not with the network: about 80 bytes
/// per tetrahedron that the other models never touch. Does nothing in 2D or
/// when built already.
template <int D>
void build_face_slots(Spring_network<D>& net)
{
  if constexpr(D == 3) {
    using Net = Spring_network<3>;
    Angle_slots& tab = Network_access::slots(net);
    if(!tab.edge_face_slot_offsets.empty())
      return;
    {
      std::vector<std::array<Index, 3>> keys;
      keys.reserve(net.elements.size() * 4);
      for(const auto& t : net.elements)
        for(int k = 0; k < 4; ++k) {
          std::array<Index, 3> key;
          for(int c = 0; c < 3; ++c)
            key[c] = t[Net::Tables::facet[k][c]];
          std::sort(key.begin(), key.end());
          keys.push_back(key);
        }
      std::sort(keys.begin(), keys.end());
      keys.erase(std::unique(keys.begin(), keys.end()), keys.end());
      keys.shrink_to_fit();
      tab.faces = std::move(keys);
    }
    const std::size_t nf = tab.faces.size();
    tab.face_edges.resize(3 * nf);
    std::vector<std::pair<Index, Index>> recs; // edge, slot
    recs.reserve(3 * nf);
    for(std::size_t f = 0; f < nf; ++f)
      for(int k = 0; k < 3; ++k) {
        Index a = tab.faces[f][(k + 1) % 3], b = tab.faces[f][(k + 2) % 3];
        if(a > b)
          std::swap(a, b);
        const auto it = std::lower_bound(net.edges.begin(), net.edges.end(), typename Net::Edge{a, b});
        const Index e = Index(it - net.edges.begin());
        tab.face_edges[3 * f + k] = e;
        recs.push_back({e, Index(3 * f + k)});
      }
    std::sort(recs.begin(), recs.end());
    tab.edge_face_slot_offsets.assign(net.edges.size() + 1, 0);
    tab.face_slot_position.resize(recs.size());
    for(std::size_t r = 0; r < recs.size(); ++r) {
      ++tab.edge_face_slot_offsets[recs[r].first + 1];
      tab.face_slot_position[recs[r].second] = Index(r);
    }
    for(std::size_t e = 0; e < net.edges.size(); ++e)
      tab.edge_face_slot_offsets[e + 1] += tab.edge_face_slot_offsets[e];
  }
}

/// The network with its face slots built (`build_face_slots`).
template <int D>
Spring_network<D> with_face_slots(Spring_network<D> net)
{
  build_face_slots(net);
  return net;
}

struct Any_labeled_facet_visitor
{
  template <class F>
  void operator()(const F&, int) const {}
};
template <class Traits, class = void>
struct Has_labeled_facets : std::false_type {};
template <class Traits>
struct Has_labeled_facets<Traits, std::void_t<decltype(std::declval<const Traits&>().for_each_labeled_facet(
                                      Any_labeled_facet_visitor()))>> : std::true_type {};
} // namespace internal

/// A network extracted from a CGAL (or user) mesh, with the handles needed to
/// write the positions back. `handles[i]` is the mesh vertex of network vertex i.
template <class Mesh, class Traits = Simplicial_mesh_traits<Mesh>>
struct Extracted_network
{
  static constexpr int dimension = Traits::dimension;
  using Vertex_handle = typename Traits::Vertex_handle;
  Spring_network<dimension> network;
  std::vector<Vertex_handle> handles;

  /// Writes positions (one per network vertex) into the mesh.
  void write_back(Mesh& mesh, const std::vector<std::array<double, dimension>>& positions) const
  {
    Traits traits(mesh);
    for(std::size_t i = 0; i < handles.size(); ++i)
      traits.set_point(mesh, handles[i], positions[i]);
  }
};

namespace internal {

/// The index of each vertex handle in the traits' vertex order (`absent`
/// for a handle never added; the first index given to a handle stays).
/// Integral handles, the vertex numbers of an indexed mesh, index a vector;
/// others (CGAL's handles) go through a hash map, whose lookup per element
/// vertex took a tenth of the network set-up of a 320k-tetrahedron mesh.
template <class Vh, bool = std::is_integral_v<Vh>>
class Vertex_index_map
{
public:
  static constexpr Index absent = std::numeric_limits<Index>::max();
  void add(Vh v, Index i) { map_.emplace(v, i); }
  Index find(Vh v) const
  {
    const auto it = map_.find(v);
    return it == map_.end() ? absent : it->second;
  }

private:
  std::unordered_map<Vh, Index> map_;
};

template <class Vh>
class Vertex_index_map<Vh, true>
{
public:
  static constexpr Index absent = std::numeric_limits<Index>::max();
  void add(Vh v, Index i)
  {
    SPRING_MOTION_CHECK(below(v, absent), "vertex handle " << v << " out of range");
    if(!below(v, index_.size()))
      index_.resize(std::size_t(v) + 1, absent);
    if(index_[std::size_t(v)] == absent)
      index_[std::size_t(v)] = i;
  }
  Index find(Vh v) const { return below(v, index_.size()) ? index_[std::size_t(v)] : absent; }

private:
  static bool below(Vh v, std::size_t bound)
  {
    if constexpr(std::is_signed_v<Vh>)
      if(v < 0)
        return false;
    return std::uint64_t(v) < bound;
  }

  std::vector<Index> index_;
};

} // namespace internal

/// Extracts the spring network of `mesh` through its `Simplicial_mesh_traits`.
/// Vertices are numbered in the traits' vertex order, skipping vertices no
/// domain element uses (the inside of a Mesh_2 hole, for instance).
template <class Mesh, class Traits = Simplicial_mesh_traits<Mesh>>
Extracted_network<Mesh, Traits> extract_spring_network(const Mesh& mesh)
{
  constexpr int D = Traits::dimension;
  using Vh = typename Traits::Vertex_handle;
  Traits traits(mesh);
  std::vector<Vh> all;
  internal::Vertex_index_map<Vh> index_of;
  traits.for_each_vertex([&](Vh v) {
    index_of.add(v, Index(all.size()));
    all.push_back(v);
  });
  std::vector<std::array<Index, D + 1>> elements;
  std::vector<char> used(all.size(), 0);
  traits.for_each_element([&](const std::array<Vh, D + 1>& e) {
    std::array<Index, D + 1> t;
    for(int k = 0; k <= D; ++k) {
      t[k] = index_of.find(e[k]);
      SPRING_MOTION_CHECK(t[k] != index_of.absent, "an element uses a vertex the mesh does not list");
      used[t[k]] = 1;
    }
    elements.push_back(t);
  });
  // the network keeps these arrays for the whole run: no spare capacity
  elements.shrink_to_fit();
  // renumber the used vertices densely, keeping the traits' order
  std::vector<Index> renumber(all.size(), std::numeric_limits<Index>::max());
  Extracted_network<Mesh, Traits> out;
  std::vector<std::array<double, D>> points;
  const auto number_used = std::size_t(std::count(used.begin(), used.end(), 1));
  points.reserve(number_used);
  out.handles.reserve(number_used);
  for(std::size_t i = 0; i < all.size(); ++i)
    if(used[i]) {
      renumber[i] = Index(out.handles.size());
      out.handles.push_back(all[i]);
      points.push_back(traits.point(all[i]));
    }
  for(auto& t : elements)
    for(auto& v : t)
      v = renumber[v];
  std::vector<Labeled_facet<D>> labeled;
  if constexpr(internal::Has_labeled_facets<Traits>::value) {
    traits.for_each_labeled_facet([&](const std::array<Vh, D>& f, int label) {
      Labeled_facet<D> lf;
      lf.label = label;
      for(int k = 0; k < D; ++k) {
        const Index i = index_of.find(f[k]);
        SPRING_MOTION_CHECK(i != index_of.absent && renumber[i] != std::numeric_limits<Index>::max(),
                            "a labeled facet uses a vertex that no element uses");
        lf.vertices[k] = renumber[i];
      }
      labeled.push_back(lf);
    });
  }
  out.network = make_spring_network<D>(std::move(points), std::move(elements), labeled);
  return out;
}

} // namespace spring_motion

#endif
