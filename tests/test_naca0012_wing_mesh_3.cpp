// The wing domain's pass that gives to the wing the tetrahedra lying in folds
// of its surface (absorb_body_slivers), checked on a coarse Mesh_3 wing with
// many of them: the mesh stays conforming with exactly its labelled facets
// as boundary, the wing's surface stays closed and manifold, and the volume
// it encloses grows by exactly the volume of the tetrahedra it took.
#include <naca0012/Naca0012_wing_mesh_3.h>
#include <spring_motion/internal/geometry/angles.h>

#include "test_meshes.h"

#include <catch2/catch.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <set>
#include <vector>

using namespace spring_motion;

namespace {

using Facet = std::array<std::uint32_t, 3>;
using Element = Indexed_mesh<3>::Element;

Facet sorted(Facet f)
{
  std::sort(f.begin(), f.end());
  return f;
}

Element sorted(Element e)
{
  std::sort(e.begin(), e.end());
  return e;
}

double volume(const Indexed_mesh<3>& m, const Element& e)
{
  std::array<std::array<double, 3>, 4> p;
  for(int k = 0; k < 4; ++k)
    p[k] = m.points[e[k]];
  return internal::signed_measure(p);
}

// Each facet of the mesh's tetrahedra with the tetrahedra it belongs to.
std::map<Facet, std::vector<std::size_t>> facet_owners(const Indexed_mesh<3>& m)
{
  std::map<Facet, std::vector<std::size_t>> owners;
  for(std::size_t t = 0; t < m.elements.size(); ++t) {
    const auto& e = m.elements[t];
    for(int k = 0; k < 4; ++k)
      owners[sorted(Facet{e[(k + 1) & 3], e[(k + 2) & 3], e[(k + 3) & 3]})].push_back(t);
  }
  return owners;
}

// The facets that belong to one tetrahedron only: the mesh's boundary.
std::set<Facet> boundary_of_elements(const Indexed_mesh<3>& m)
{
  std::set<Facet> b;
  for(const auto& [f, owners] : facet_owners(m)) {
    REQUIRE(owners.size() <= 2); // conforming: no facet in three tetrahedra
    if(owners.size() == 1)
      b.insert(f);
  }
  return b;
}

std::set<Facet> labelled_facets(const Indexed_mesh<3>& m, int label)
{
  std::set<Facet> s;
  for(std::size_t f = 0; f < m.boundary_facets.size(); ++f)
    if(label < 0 || m.boundary_labels[f] == label)
      REQUIRE(s.insert(sorted(m.boundary_facets[f])).second); // no facet twice
  return s;
}

// The volume the body's facets enclose, each facet turned to face its
// tetrahedron (away from the body): the divergence theorem.
double enclosed_volume(const Indexed_mesh<3>& m, int body)
{
  const auto owners = facet_owners(m);
  double v = 0;
  for(const auto& f : labelled_facets(m, body)) {
    const auto& e = m.elements[owners.at(f).at(0)];
    std::uint32_t apex = 0;
    for(const auto u : e)
      if(u != f[0] && u != f[1] && u != f[2])
        apex = u;
    const double s = volume(m, {f[0], f[1], f[2], apex}) > 0 ? 1 : -1;
    const auto &a = m.points[f[0]], &b = m.points[f[1]], &c = m.points[f[2]];
    const double det = a[0] * (b[1] * c[2] - b[2] * c[1]) - a[1] * (b[0] * c[2] - b[2] * c[0]) +
                       a[2] * (b[0] * c[1] - b[1] * c[0]);
    // (f, apex) positive: f's normal points to the apex, into the fluid,
    // out of the body
    v += s * det / 6;
  }
  return v;
}

std::size_t vertices_on(const std::set<Facet>& facets)
{
  std::set<std::uint32_t> v;
  for(const auto& f : facets)
    v.insert(f.begin(), f.end());
  return v.size();
}

// Every edge of the surface in exactly two of its facets; returns the edge count.
std::size_t manifold_edges(const std::set<Facet>& facets)
{
  std::map<std::array<std::uint32_t, 2>, int> uses;
  for(const auto& f : facets)
    for(int k = 0; k < 3; ++k)
      ++uses[{std::min(f[k], f[(k + 1) % 3]), std::max(f[k], f[(k + 1) % 3])}];
  std::size_t bad = 0;
  for(const auto& [e, n] : uses)
    bad += n != 2;
  CHECK(bad == 0);
  return uses.size();
}

double smallest_dihedral_deg(const Indexed_mesh<3>& m, const Element& e)
{
  std::array<std::array<double, 3>, 4> p;
  for(int k = 0; k < 4; ++k)
    p[k] = m.points[e[k]];
  const auto a = internal::dihedral_angles(p);
  return *std::min_element(a.begin(), a.end()) * 180 / M_PI;
}

} // namespace

TEST_CASE("wing mesh: tetrahedra in folds of the wing's surface are given to the wing", "[mesh_3][wing]")
{
  // coarse and without the optimisers, so Mesh_3 is short and leaves many
  Naca0012_wing_mesh_3_options o = spring_motion_test::coarse_wing_options();
  o.wing_sliver_bound = 0;
  const Indexed_mesh<3> before = naca0012_wing_mesh_3(o);
  Indexed_mesh<3> m = before;
  const double bound = 30;
  const std::size_t given = absorb_body_slivers(m, body_patch, bound);
  INFO(before.elements.size() << " tetrahedra, " << given << " given to the wing");
  REQUIRE(given >= 5);

  // the points stay; the elements left are the old ones less `given`
  CHECK(m.points == before.points);
  REQUIRE(m.elements.size() == before.elements.size() - given);
  REQUIRE(m.element_labels.size() == m.elements.size());
  std::multiset<Element> old_elements, new_elements;
  for(const auto& e : before.elements)
    old_elements.insert(sorted(e));
  for(const auto& e : m.elements)
    new_elements.insert(sorted(e));
  std::vector<Element> taken;
  std::set_difference(old_elements.begin(), old_elements.end(), new_elements.begin(), new_elements.end(),
                      std::back_inserter(taken));
  REQUIRE(taken.size() == given);

  // each taken tetrahedron qualified: four wing vertices, below the bound
  const auto old_wing = labelled_facets(before, body_patch);
  std::set<std::uint32_t> wing_vertices;
  for(const auto& f : old_wing)
    wing_vertices.insert(f.begin(), f.end());
  double taken_volume = 0;
  for(const auto& e : taken) {
    for(const auto v : e)
      CHECK(wing_vertices.count(v) == 1);
    CHECK(smallest_dihedral_deg(before, e) < bound);
    taken_volume += std::abs(volume(before, e));
  }

  // the boundary of the tetrahedra is exactly the labelled facets, before and after
  CHECK(boundary_of_elements(before) == labelled_facets(before, -1));
  CHECK(boundary_of_elements(m) == labelled_facets(m, -1));
  CHECK(labelled_facets(m, outer_patch) == labelled_facets(before, outer_patch));

  // the wing's surface: closed, manifold, same vertices, still a sphere
  // (V - E + F = 2), and it encloses the taken tetrahedra's volume more
  const auto new_wing = labelled_facets(m, body_patch);
  CHECK(new_wing.size() == old_wing.size()); // each flip trades two facets for two
  CHECK(new_wing != old_wing);
  CHECK(vertices_on(new_wing) == vertices_on(old_wing));
  const std::size_t old_edges = manifold_edges(old_wing), new_edges = manifold_edges(new_wing);
  CHECK(vertices_on(old_wing) + old_wing.size() == old_edges + 2);
  CHECK(vertices_on(new_wing) + new_wing.size() == new_edges + 2);
  const double v0 = enclosed_volume(before, body_patch), v1 = enclosed_volume(m, body_patch);
  INFO("wing volume " << v0 << " -> " << v1 << ", taken " << taken_volume);
  CHECK(v0 > 0.05); // about 0.16: the section's area 0.082 times the span 2
  CHECK(v1 - v0 == Approx(taken_volume).epsilon(1e-9));

  // nothing left to give: every tetrahedron still made of four wing vertices
  // with two wing facets is above the bound or its flip would break the
  // surface; a second pass gives nothing
  CHECK(absorb_body_slivers(m, body_patch, bound) == 0);
  CHECK(absorb_body_slivers(m, body_patch, 0) == 0);
}
