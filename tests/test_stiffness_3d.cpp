// The 3D stiffness models on a reference tetrahedron, by hand; and, for every
// element-angle model in 2D and 3D, the spatial traversal of the assembly
// against an edge-by-edge computation.
//
// Reference: the trirectangular corner p0 = 0, p1 = e_x, p2 = e_y, p3 = e_z.
//  - edges 0-1, 0-2, 0-3: length 1, dihedral angle pi/2 (sin^2 = 1);
//  - edges 1-2, 1-3, 2-3: length sqrt 2, dihedral angle acos(1/sqrt 3)
//    (cos^2 = 1/3, so 1/sin^2 = 3/2).
// Face angles facing an edge (Zeng-Ethier's 3D choice):
//  - edge 0-1 lies in faces 0-1-2 and 0-1-3, right isosceles triangles with
//    the right angle at 0: the angle facing 0-1 is 45 degrees in both,
//    1/sin^2 = 2 each;
//  - edge 1-2 lies in face 0-1-2 (facing angle 90 degrees at 0: 1/sin^2 = 1)
//    and in the equilateral face 1-2-3 (60 degrees: 1/sin^2 = 4/3).
// The longest initial edge is l0 = sqrt 2 (the paper's lambda = l0 / l).
#include <spring_motion/Spring_network.h>
#include <spring_motion/internal/solver/assemble.h>
#include <spring_motion/stiffness/Blom_semi_torsional_stiffness.h>
#include <spring_motion/stiffness/Grid_scaled_stiffness.h>
#include <spring_motion/stiffness/Lineal_stiffness.h>
#include <spring_motion/stiffness/Torsional_stiffness.h>
#include <spring_motion/stiffness/Zeng_Ethier_semi_torsional_stiffness.h>

#include "test_meshes.h"

#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <vector>

using namespace spring_motion;

namespace {

using P3 = std::array<double, 3>;

// k of edge a-b of the corner tetrahedron under `model`.
struct Corner
{
  Spring_network<3> net =
      internal::with_face_slots(make_spring_network<3>({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}}, {{0, 1, 2, 3}}));
  template <class Model>
  std::vector<double> stiffness(const Model& model) const
  {
    Stiffness_context ctx;
    ctx.dimension = 3;
    ctx.longest_initial_edge = net.longest_initial_edge;
    std::vector<double> k;
    internal::Stiffness_scratch<3> scratch;
    internal::compute_edge_stiffness(net, net.points, model, ctx, k, scratch, 1);
    return k;
  }
  std::size_t edge(Index a, Index b) const
  {
    for(std::size_t e = 0; e < net.edges.size(); ++e)
      if(net.edges[e][0] == a && net.edges[e][1] == b)
        return e;
    FAIL("no edge " << a << "-" << b);
    return 0;
  }
};

// The values combine a few correctly rounded operations and an angle good
// to a few ulps: relative agreement to 1e-13 is round-off, not modelling.
bool close(double a, double b) { return std::abs(a - b) <= 1e-13 * std::abs(b); }

} // namespace

TEST_CASE("3D stiffness: the corner's longest edge is l0 = sqrt 2", "[stiffness][3d]")
{
  Corner c;
  CHECK(close(c.net.longest_initial_edge, std::sqrt(2.0)));
}

TEST_CASE("3D stiffness: lineal, k = 1/l", "[stiffness][3d]")
{
  Corner c;
  const auto k = c.stiffness(Lineal_stiffness{});
  CHECK(close(k[c.edge(0, 1)], 1.0));
  CHECK(close(k[c.edge(1, 2)], 1 / std::sqrt(2.0)));
  const auto k2 = c.stiffness(Lineal_stiffness{2.0});
  CHECK(close(k2[c.edge(2, 3)], 0.5));
}

TEST_CASE("3D stiffness: Blom, k = (1/l) 1/theta with the dihedral angle", "[stiffness][3d]")
{
  Corner c;
  const auto k = c.stiffness(Blom_semi_torsional_stiffness{});
  CHECK(close(k[c.edge(0, 1)], 2 / internal::pi));
  CHECK(close(k[c.edge(1, 2)], 1 / (std::sqrt(2.0) * std::acos(1 / std::sqrt(3.0)))));
}

TEST_CASE("3D stiffness: Zeng-Ethier with face angles (default) and with dihedral angles", "[stiffness][3d]")
{
  Corner c;
  const auto kf = c.stiffness(Zeng_Ethier_semi_torsional_stiffness{});
  CHECK(close(kf[c.edge(0, 1)], 1 + 2 + 2));
  CHECK(close(kf[c.edge(1, 2)], 1 / std::sqrt(2.0) + 1 + 4.0 / 3));
  Zeng_Ethier_semi_torsional_stiffness dihedral;
  dihedral.angles_3d = Angle_kind::element;
  const auto kd = c.stiffness(dihedral);
  CHECK(close(kd[c.edge(0, 1)], 1 + 1));
  CHECK(close(kd[c.edge(1, 2)], 1 / std::sqrt(2.0) + 1.5));
}

TEST_CASE("3D stiffness: the face slots are built on first use, once, and a face-angle model needs them",
          "[stiffness][3d]")
{
  Spring_network<3> net = make_spring_network<3>({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}}, {{0, 1, 2, 3}});
  const internal::Angle_slots& slots = internal::angle_slots(net);
  CHECK(slots.faces.empty()); // not built with the network: most models never read them
  std::vector<double> k;
  internal::Stiffness_scratch<3> scratch;
  const Stiffness_context ctx{3, net.longest_initial_edge};
  CHECK_THROWS_WITH(internal::compute_edge_stiffness(net, net.points, Zeng_Ethier_semi_torsional_stiffness{}, ctx, k,
                                                     scratch, 1),
                    Catch::Contains("needs the network's face slots"));
  CHECK_NOTHROW(internal::compute_edge_stiffness(net, net.points, Lineal_stiffness{}, ctx, k, scratch, 1));
  internal::build_face_slots(net);
  internal::build_face_slots(net); // a second call keeps what the first built
  CHECK(slots.faces.size() == 4);
  CHECK(slots.face_edges.size() == 12);
  CHECK(slots.edge_face_slot_offsets.back() == 12);
  // the same stiffness as the corner built with its face slots from the start
  internal::compute_edge_stiffness(net, net.points, Zeng_Ethier_semi_torsional_stiffness{}, ctx, k, scratch, 1);
  CHECK(k == Corner().stiffness(Zeng_Ethier_semi_torsional_stiffness{}));
}

TEST_CASE("3D stiffness: grid-scaled, alpha = 1, beta = 3, dihedral angles, lambda = l0/l", "[stiffness][3d]")
{
  Corner c;
  Grid_scaled_stiffness model;
  CHECK(model.alpha_for(3) == 1.0);
  CHECK(model.beta_for(3) == 3.0);
  const auto k = c.stiffness(model);
  // edge 0-1: lambda = sqrt 2, 1/l = 1, (1/sin^2)^3 = 1
  CHECK(close(k[c.edge(0, 1)], std::sqrt(2.0) * (1 + 1)));
  // edge 1-2: lambda = 1, 1/l = 1/sqrt 2, (3/2)^3 = 27/8
  CHECK(close(k[c.edge(1, 2)], 1 / std::sqrt(2.0) + 27.0 / 8));
  // a reference length of 2 halves l in the 1/l term only
  model.reference_length = 2;
  CHECK(close(c.stiffness(model)[c.edge(0, 1)], std::sqrt(2.0) * (2 + 1)));
}

TEST_CASE("3D stiffness: the torsional model's edge springs are its lineal part, 1/l", "[stiffness][3d]")
{
  Corner c;
  const auto k = c.stiffness(Torsional_stiffness{});
  CHECK(close(k[c.edge(0, 1)], 1.0));
  CHECK(close(k[c.edge(1, 2)], 1 / std::sqrt(2.0)));
}

namespace {
// Weighs the m-th angle of an edge by m + 1: any change in the order in which
// an edge's angles reach the model changes k.
struct Order_sensitive_model
{
  Angle_kind angle_kind(int) const { return Angle_kind::element; }
  double operator()(double length, const double* angles, std::size_t n, const Stiffness_context&) const
  {
    double s = length;
    for(std::size_t m = 0; m < n; ++m)
      s += double(m + 1) * angles[m];
    return s;
  }
};

// k of every edge from its angles gathered edge by edge in increasing
// element order, the order the element-angle models are specified in.
template <int D, class Model>
std::vector<double> stiffness_by_edge(const Spring_network<D>& net, const Model& model, const Stiffness_context& ctx)
{
  constexpr int E = Spring_network<D>::edges_per_element;
  std::vector<std::vector<double>> around(net.number_of_edges());
  for(std::size_t t = 0; t < net.number_of_elements(); ++t) {
    const auto p = internal::element_points<D>(net.elements, net.points, t);
    std::array<double, E> a;
    if constexpr(internal::Reads_inverse_sin_squared<Model>::value)
      a = internal::element_edge_inverse_sin_squared<D>(p);
    else
      a = internal::element_edge_angles<D>(p);
    for(int j = 0; j < E; ++j)
      around[net.edge_of(Index(t), j)].push_back(a[std::size_t(j)]);
  }
  std::vector<double> k;
  for(std::size_t e = 0; e < net.number_of_edges(); ++e) {
    const double l = internal::distance<D>(net.points[net.edges[e][0]], net.points[net.edges[e][1]]);
    if constexpr(internal::Reads_inverse_sin_squared<Model>::value)
      k.push_back(model(l, Inverse_sin_squared{around[e].data(), around[e].size()}, ctx));
    else
      k.push_back(model(l, around[e].data(), around[e].size(), ctx));
  }
  return k;
}

template <int D, class Model>
void check_traversal_keeps_values(const Model& model)
{
  const auto mesh = spring_motion_test::kuhn_grid<D>(D == 2 ? 24 : 7);
  const auto net = make_spring_network<D>(mesh.points, mesh.elements);
  // the traversal is not the element order (else this test shows nothing)
  const auto& slots = internal::angle_slots(net);
  std::size_t moved = 0;
  for(std::size_t i = 0; i < net.number_of_elements(); ++i)
    for(int k = 0; k <= D; ++k)
      if(net.elements[i][std::size_t(k)] != slots.traversal_vertices[slots.ordered_elements[i * (D + 1) + std::size_t(k)]]) {
        ++moved;
        break;
      }
  CHECK(moved > net.number_of_elements() / 2);
  const Stiffness_context ctx{D, net.longest_initial_edge};
  const auto expected = stiffness_by_edge(net, model, ctx);
  for(int threads : {1, 2}) {
    std::vector<double> k;
    internal::Stiffness_scratch<D> scratch;
    internal::compute_edge_stiffness(net, net.points, model, ctx, k, scratch, threads);
    INFO("threads " << threads);
    CHECK(k == expected); // bitwise
  }
}
} // namespace

TEST_CASE("Stiffness: the spatial traversal of the elements gives every edge the value of an edge-by-edge sum in "
          "element order, bitwise",
          "[stiffness][3d][2d]")
{
  check_traversal_keeps_values<3>(Order_sensitive_model{});
  check_traversal_keeps_values<3>(Grid_scaled_stiffness{});
  check_traversal_keeps_values<3>(Blom_semi_torsional_stiffness{});
  check_traversal_keeps_values<2>(Order_sensitive_model{});
  check_traversal_keeps_values<2>(Grid_scaled_stiffness{});
}
