// Copyright (c) 2026 SpringMotion developers.
#ifndef SPRING_MOTION_STIFFNESS_BALL_VERTEX_STIFFNESS_H
#define SPRING_MOTION_STIFFNESS_BALL_VERTEX_STIFFNESS_H

#include <spring_motion/Error.h>
#include <spring_motion/internal/geometry/angles.h>
#include <spring_motion/internal/geometry/capped_math.h>
#include <spring_motion/stiffness/Stiffness_model.h>

#include <array>
#include <cmath>
#include <cstddef>

namespace spring_motion {

/// The altitude of a simplex from one vertex to the facet facing it: its
/// length h, the facet's unit normal n pointing towards the vertex, and the
/// barycentric coordinates (in the facet) of its foot, indexed by the
/// simplex's local vertices (the vertex itself has b = 0).
template <int D>
struct Altitude
{
  double height = 0;
  std::array<double, D> normal{};
  std::array<double, D + 1> foot{};
};

/// Ball-vertex springs (Bottasso, Detomi and Serra, CMAME 194, 2005): in
/// every element, each vertex i is tied to the facet facing it by a spring
/// along the altitude, acting on the normal component of the vertex's
/// displacement relative to the foot of the altitude, the foot moving with
/// the facet (interpolated by its barycentric coordinates b_j):
/// `E = (k_i / 2) (n . (d_i - sum_j b_j d_j))^2`, `k_i = weight / h_i^p`.
/// That normal component is the first variation of the altitude h_i itself,
/// so the springs resist exactly the flattening that edge springs cannot see
/// (a sliver flattens without any edge getting shorter).
///
/// A pure element model: no edge springs (k = 0 on every edge); see
/// With_ball_vertex for an edge model plus these springs. The element matrix
/// is rotation covariant and has the rigid motions in its null space.
struct Ball_vertex_stiffness
{
  double exponent = 1.0; ///< p in k = weight / h^p
  double weight = 1.0;   ///< multiplies every k

  Angle_kind angle_kind(int) const { return Angle_kind::none; }
  double operator()(double, const double*, std::size_t, const Stiffness_context&) const { return 0.0; }

  /// The altitude from local vertex i of triangle p.
  static Altitude<2> altitude(const std::array<std::array<double, 2>, 3>& p, int i)
  {
    const int j = (i + 1) % 3, l = (i + 2) % 3;
    const auto e = internal::sub<2>(p[l], p[j]);
    const double ee = internal::dot<2>(e, e);
    SPRING_MOTION_CHECK(ee > 0 && std::isfinite(ee), "ball-vertex springs need facets of non-zero size");
    const auto r = internal::sub<2>(p[i], p[j]);
    const double t = internal::dot<2>(r, e) / ee; // foot = p_j + t e
    Altitude<2> a;
    a.foot[std::size_t(j)] = 1 - t;
    a.foot[std::size_t(l)] = t;
    // the perpendicular of e, turned towards p_i; the height from the cross
    // product (twice the area over the base), not from the foot, so that it
    // stays accurate for a nearly flat triangle
    const double len = std::sqrt(ee);
    const double c = e[0] * r[1] - e[1] * r[0];
    const double s = c >= 0 ? 1.0 : -1.0;
    a.normal = {-s * e[1] / len, s * e[0] / len};
    a.height = std::abs(c) / len;
    return a;
  }

  /// The altitude from local vertex i of tetrahedron p.
  static Altitude<3> altitude(const std::array<std::array<double, 3>, 4>& p, int i)
  {
    std::array<int, 3> q;
    for(int m = 0, c = 0; m < 4; ++m)
      if(m != i)
        q[std::size_t(c++)] = m;
    const auto N = internal::cross(internal::sub<3>(p[q[1]], p[q[0]]), internal::sub<3>(p[q[2]], p[q[0]]));
    const double NN = internal::dot<3>(N, N);
    SPRING_MOTION_CHECK(NN > 0 && std::isfinite(NN), "ball-vertex springs need facets of non-zero size");
    Altitude<3> a;
    // b_m: the signed area of the sub-triangle facing q_m, seen from p_i,
    // over the facet's area. The offset from the foot to p_i is parallel to
    // N, so measuring from p_i instead of the foot changes nothing.
    for(int m = 0; m < 3; ++m) {
      const auto u = internal::sub<3>(p[q[std::size_t((m + 1) % 3)]], p[i]);
      const auto v = internal::sub<3>(p[q[std::size_t((m + 2) % 3)]], p[i]);
      a.foot[std::size_t(q[std::size_t(m)])] = internal::dot<3>(internal::cross(u, v), N) / NN;
    }
    const double len = std::sqrt(NN);
    const double c = internal::dot<3>(internal::sub<3>(p[i], p[q[0]]), N) / len;
    const double s = c >= 0 ? 1.0 : -1.0;
    for(int k = 0; k < 3; ++k)
      a.normal[std::size_t(k)] = s * N[std::size_t(k)] / len;
    a.height = std::abs(c);
    return a;
  }

  /// Spring stiffness of an altitude of length h.
  double spring_stiffness(double h) const { return weight * internal::capped_pow(h, -exponent); }

  void add_element_matrix(const std::array<std::array<double, 2>, 3>& p, double* K) const { add<2>(p, K); }
  void add_element_matrix(const std::array<std::array<double, 3>, 4>& p, double* K) const { add<3>(p, K); }

  Model_description description(int) const
  {
    return {"ball_vertex", {{"exponent", exponent}, {"weight", weight}}};
  }

private:
  // K += sum_i k_i a_i a_i^T with a_i = (n at vertex i, -b_j n at each vertex j)
  template <int D>
  void add(const std::array<std::array<double, D>, D + 1>& p, double* K) const
  {
    constexpr int ND = (D + 1) * D;
    // The block solver inverts D x D sums of these matrices and of the edge
    // springs (up to 1/l^2): its determinant, a product of D such entries,
    // stays finite for edges longer than ~1e-50, as with torsional springs.
    for(int a = 0; a <= D; ++a)
      for(int b = a + 1; b <= D; ++b) {
        const auto e = internal::sub<D>(p[b], p[a]);
        const double ee = internal::dot<D>(e, e);
        SPRING_MOTION_CHECK(ee >= 1e-100, "ball-vertex springs need edges longer than 1e-50 (found one of squared length "
                                              << ee << "): scale the mesh");
      }
    for(int i = 0; i <= D; ++i) {
      const Altitude<D> alt = altitude(p, i);
      const double k = spring_stiffness(alt.height);
      std::array<double, ND> a;
      for(int v = 0; v <= D; ++v)
        for(int c = 0; c < D; ++c)
          a[std::size_t(v * D + c)] = (v == i ? 1.0 : -alt.foot[std::size_t(v)]) * alt.normal[std::size_t(c)];
      for(int r = 0; r < ND; ++r)
        for(int q = 0; q < ND; ++q)
          K[r * ND + q] += k * a[std::size_t(r)] * a[std::size_t(q)];
    }
  }
};

} // namespace spring_motion

#endif
