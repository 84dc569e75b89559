// 3D angles, skewness and exact validity: dihedral and face angles of
// tetrahedra, their use around the edges of a network built from a CGAL
// Triangulation_3, R of Eq. 13 with Q_e = arccos(1/3), exact orientation.
#include <spring_motion/Spring_network.h>
#include <spring_motion/internal/geometry/angles.h>
#include <spring_motion/mesh_traits/Triangulation_3.h>
#include <spring_motion/skewness.h>
#include <spring_motion/validity.h>

#include <CGAL/Delaunay_triangulation_3.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>

#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <iterator>
#include <random>
#include <vector>

using namespace spring_motion;
using P3 = std::array<double, 3>;

namespace {

// Angles come from atan2 of exactly rounded products: a few ulps of pi.
constexpr double angle_tolerance = 1e-14;

const std::array<P3, 4> regular{{{1, 1, 1}, {1, -1, -1}, {-1, 1, -1}, {-1, -1, 1}}};
// the trirectangular corner: right dihedral angles at the edges from the
// origin, arccos(1/sqrt(3)) at the others (between z = 0 and x + y + z = 1,
// whose unit normals have dot product 1/sqrt(3))
const std::array<P3, 4> corner{{{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}}};

} // namespace

TEST_CASE("3D angles: every dihedral angle of a regular tetrahedron is arccos(1/3)", "[angles][3d]")
{
  for(const double a : internal::dihedral_angles(regular))
    CHECK(std::abs(a - std::acos(1.0 / 3.0)) < angle_tolerance);
  const auto f = internal::triangle_angles<3>(regular[0], regular[1], regular[2]);
  for(const double a : f)
    CHECK(std::abs(a - M_PI / 3) < angle_tolerance);
}

TEST_CASE("3D angles: dihedral angles of the trirectangular corner, in local edge order", "[angles][3d]")
{
  const auto a = internal::dihedral_angles(corner);
  // local edges 0-1, 0-2, 0-3 meet at the origin; 1-2, 1-3, 2-3 lie on the slanted face
  for(int k = 0; k < 3; ++k)
    CHECK(std::abs(a[k] - M_PI / 2) < angle_tolerance);
  for(int k = 3; k < 6; ++k)
    CHECK(std::abs(a[k] - std::acos(1 / std::sqrt(3.0))) < angle_tolerance);
}

TEST_CASE("3D angles: dihedral angles of tetrahedra scaled by powers of two are the same bits", "[angles][3d]")
{
  // Scaling by 2^k rounds nothing, so the angles must not change at all:
  // at 2^-1000 the squared edges underflow and at 2^1000 the products
  // overflow unless the function rescales first (dihedral_angles).
  std::mt19937 random(7);
  std::uniform_real_distribution<double> coordinate(-1, 1);
  for(int t = 0; t < 200; ++t) {
    std::array<P3, 4> p;
    for(auto& q : p)
      for(auto& x : q)
        x = coordinate(random);
    const auto reference = internal::dihedral_angles(p);
    for(const int k : {-1000, -700, -300, 300, 700, 1000}) {
      INFO("tetrahedron " << t << " scaled by 2^" << k);
      auto scaled = p;
      for(auto& q : scaled)
        for(auto& x : q)
          x = std::ldexp(x, k);
      const auto a = internal::dihedral_angles(scaled);
      for(std::size_t e = 0; e < 6; ++e)
        CHECK(a[e] == reference[e]);
    }
  }
}

TEST_CASE("3D skewness: R from the six dihedral angles with Q_e = arccos(1/3)", "[skewness][3d]")
{
  const double qe = std::acos(1.0 / 3.0);
  CHECK(equiangular_angle(3) == qe);
  // regular: every angle is Q_e, R = 0 up to the angles' rounding
  CHECK(equiangle_skewness(regular[0], regular[1], regular[2], regular[3]) < angle_tolerance);
  // corner: Q_min = arccos(1/sqrt 3) gives (Q_e - Q_min)/Q_e = 0.2239, larger
  // than (pi/2 - Q_e)/(pi - Q_e) = 0.1779 from Q_max
  const double expected = (qe - std::acos(1 / std::sqrt(3.0))) / qe;
  CHECK(std::abs(equiangle_skewness(corner[0], corner[1], corner[2], corner[3]) - expected) < angle_tolerance);
  CHECK(expected > (M_PI / 2 - qe) / (M_PI - qe));
  // flat: angles 0 and pi, R = 1
  CHECK(equiangle_skewness(P3{0, 0, 0}, P3{1, 0, 0}, P3{0, 1, 0}, P3{1, 1, 0}) == 1.0);
}

TEST_CASE("3D angles: around the edges of a Triangulation_3 the dihedral angles fill the space", "[angles][3d]")
{
  // the cube's corners and its centre: 12 tetrahedra, two per face, around
  // the centre. Around an interior edge (centre-corner) the angles sum to
  // 2 pi; around a cube edge to pi/2; around a face diagonal to pi.
  using K = CGAL::Exact_predicates_inexact_constructions_kernel;
  CGAL::Delaunay_triangulation_3<K> dt;
  for(int i = 0; i < 8; ++i)
    dt.insert(K::Point_3(i & 1, (i >> 1) & 1, (i >> 2) & 1));
  dt.insert(K::Point_3(0.5, 0.5, 0.5));
  // with the face slots, which are built on first use
  const auto net = internal::with_face_slots(extract_spring_network(dt).network);
  REQUIRE(net.number_of_elements() == 12);
  REQUIRE(net.number_of_vertices() == 9);
  REQUIRE(net.number_of_edges() == 8 + 12 + 6);
  REQUIRE(net.boundary_facets.size() == 12);
  std::vector<double> angle_of_slot(net.number_of_elements() * 6);
  for(std::size_t t = 0; t < net.number_of_elements(); ++t) {
    std::array<P3, 4> p;
    for(int k = 0; k < 4; ++k)
      p[k] = net.points[net.elements[t][k]];
    CHECK(internal::exact_orientation(p) == 1); // CGAL's cells are positively oriented
    const auto a = internal::dihedral_angles(p);
    for(int k = 0; k < 6; ++k)
      angle_of_slot[t * 6 + k] = a[k];
  }
  const internal::Angle_slots& slots = internal::angle_slots(net);
  // into the edge-major layout, as the assembly scatters them from its
  // traversal (which lists every element once)
  std::vector<double> angle_at(angle_of_slot.size());
  std::vector<int> traversed(net.number_of_elements(), 0);
  for(std::size_t i = 0; i < net.number_of_elements(); ++i) {
    Spring_network<3>::Element v;
    for(std::size_t k = 0; k < 4; ++k)
      v[k] = slots.traversal_vertices[slots.ordered_elements[i * 4 + k]];
    const auto t = std::find(net.elements.begin(), net.elements.end(), v);
    REQUIRE(t != net.elements.end());
    ++traversed[std::size_t(t - net.elements.begin())];
    for(int k = 0; k < 6; ++k)
      angle_at[slots.slot_position[i * 6 + std::size_t(k)]] = angle_of_slot[std::size_t(t - net.elements.begin()) * 6 + std::size_t(k)];
  }
  CHECK(std::count(traversed.begin(), traversed.end(), 1) == long(net.number_of_elements()));
  std::vector<int> laid_out(net.number_of_edges(), 0);
  for(Index e : slots.layout_edge)
    ++laid_out[e];
  CHECK(std::count(laid_out.begin(), laid_out.end(), 1) == long(net.number_of_edges()));
  // every vertex once in the traversal's numbering, and each laid-out edge's
  // ends (in the edge's order) through it
  std::vector<int> numbered(net.number_of_vertices(), 0);
  for(Index v : slots.traversal_vertices)
    ++numbered[v];
  CHECK(std::count(numbered.begin(), numbered.end(), 1) == long(net.number_of_vertices()));
  REQUIRE(slots.layout_edge_ends.size() == net.number_of_edges());
  std::size_t ends_found = 0;
  for(std::size_t q = 0; q < net.number_of_edges(); ++q)
    ends_found += slots.traversal_vertices[slots.layout_edge_ends[q][0]] == net.edges[slots.layout_edge[q]][0] &&
                  slots.traversal_vertices[slots.layout_edge_ends[q][1]] == net.edges[slots.layout_edge[q]][1];
  CHECK(ends_found == net.number_of_edges());
  int interior = 0, cube_edges = 0, diagonals = 0;
  for(std::size_t q = 0; q < net.number_of_edges(); ++q) {
    const std::size_t e = slots.layout_edge[q];
    double sum = 0;
    for(Index s = slots.layout_slot_offsets[q]; s < slots.layout_slot_offsets[q + 1]; ++s)
      sum += angle_at[s];
    const auto& a = net.points[net.edges[e][0]];
    const auto& b = net.points[net.edges[e][1]];
    const double l2 = (a[0] - b[0]) * (a[0] - b[0]) + (a[1] - b[1]) * (a[1] - b[1]) + (a[2] - b[2]) * (a[2] - b[2]);
    const double expected = l2 < 0.9 ? 2 * M_PI : (l2 < 1.1 ? M_PI / 2 : M_PI);
    (l2 < 0.9 ? interior : (l2 < 1.1 ? cube_edges : diagonals))++;
    INFO("edge " << e << " squared length " << l2);
    CHECK(std::abs(sum - expected) < 8 * angle_tolerance); // up to 8 angles summed
  }
  CHECK(interior == 8);
  CHECK(cube_edges == 12);
  CHECK(diagonals == 6);
  // faces: the 12 boundary triangles and one (centre, a, b) per boundary edge
  // a-b (12 cube edges + 6 diagonals); each face lists its three edges
  CHECK(slots.faces.size() == 12 + 18);
  CHECK(slots.face_slot_position.size() == 3 * slots.faces.size());
  CHECK(slots.edge_face_slot_offsets.back() == 3 * slots.faces.size());
}

TEST_CASE("3D validity: exact orientation flags the flipped and the flat tetrahedron", "[validity][3d]")
{
  std::vector<P3> pts{{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}, {1, 1, 1}};
  // two tetrahedra sharing the face 1-2-3, on either side of it
  auto net = make_spring_network<3>(pts, {{0, 1, 2, 3}, {4, 2, 1, 3}});
  const auto rec = record_orientations(net, pts);
  CHECK(rec.sign[0] == 1);
  CHECK(rec.sign[1] == 1);
  std::vector<std::size_t> bad;
  CHECK(find_inverted_elements(net, pts, rec, std::back_inserter(bad)) == 0);
  // vertex 4 exactly onto the plane x + y + z = 1 (0.5 + 0.25 + 0.25 is exact):
  // orientation zero, which is invalid, while element 0 is untouched
  auto x = pts;
  x[4] = {0.5, 0.25, 0.25};
  CHECK(find_inverted_elements(net, x, rec, std::back_inserter(bad)) == 1);
  CHECK(bad == std::vector<std::size_t>{1});
  // just across the plane by one ulp in z: inverted, found by the exact predicate
  x[4][2] = std::nextafter(0.25, 0.0);
  bad.clear();
  CHECK(find_inverted_elements(net, x, rec, std::back_inserter(bad)) == 1);
  CHECK(bad == std::vector<std::size_t>{1});
  // and one ulp on the right side: valid
  x[4][2] = std::nextafter(0.25, 1.0);
  bad.clear();
  CHECK(find_inverted_elements(net, x, rec, std::back_inserter(bad)) == 0);
}
