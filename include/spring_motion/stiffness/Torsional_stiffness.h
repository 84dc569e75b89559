// Copyright (c) 2026 SpringMotion developers.
#ifndef SPRING_MOTION_STIFFNESS_TORSIONAL_STIFFNESS_H
#define SPRING_MOTION_STIFFNESS_TORSIONAL_STIFFNESS_H

#include <spring_motion/Error.h>
#include <spring_motion/internal/geometry/angles.h>
#include <spring_motion/internal/geometry/capped_math.h>
#include <spring_motion/stiffness/Stiffness_model.h>

#include <array>
#include <cmath>

namespace spring_motion {

/// One of the twelve triangles inside a tetrahedron on which the 3D
/// torsional springs act: local vertex `vertex` of face `face` (the face
/// facing local vertex `apex`), the point j = (1 - lambda) p[edge[0]] +
/// lambda p[edge[1]] on the face's edge facing `vertex`, and the apex.
struct Torsion_triangle
{
  int vertex = 0;
  int apex = 0;
  std::array<int, 2> edge{};
  double lambda = 0;
};

/// Torsional springs: lineal springs `1/l^p` on the edges plus torsion
/// springs `C = 1/sin^2(theta)` at the angles of triangles, assembled as
/// `sum C g g^T` with g the gradient of the angle with respect to the
/// element's coordinates. The torsion couples the coordinate components, so
/// the solver works on D x D blocks.
///
/// 2D (Farhat, Degand, Koobus and Lesoinne 1998): the element's own three
/// angles. 3D (Degand and Farhat 2002): in each of the twelve triangles of
/// torsion_triangles(), each spanned by a vertex i of a face, the apex k
/// facing that face and the point j where the plane through the edge ik
/// perpendicular to the face cuts the face's opposite edge. Its angle at i is
/// the angle between the edge ik and the face, which goes to 0 as the
/// tetrahedron flattens. j moves with that edge's end points (weights
/// 1 - lambda and lambda, frozen in a step). Where the plane cuts the edge's
/// line outside the edge, j is clamped to the nearer end point: the triangle
/// is then a face of the tetrahedron (the paper clamps the weights only and
/// keeps the outside point, which makes the energy see rigid motions).
///
/// Our lineal part acts on each component separately (Batina's springs), as
/// in every other model here, which keeps the system positive definite.
struct Torsional_stiffness
{
  double lineal_exponent = 1.0;
  double torsion_scale = 1.0; ///< multiplies every C_i

  Angle_kind angle_kind(int) const { return Angle_kind::none; }
  double operator()(double length, const double*, std::size_t, const Stiffness_context&) const
  {
    return internal::capped_pow(length, -lineal_exponent);
  }

  /// The twelve triangles of the 3D torsional springs in tetrahedron p: for
  /// each face (in the order of the apex facing it) and each of its vertices.
  static std::array<Torsion_triangle, 12> torsion_triangles(const std::array<std::array<double, 3>, 4>& p)
  {
    std::array<Torsion_triangle, 12> out;
    std::size_t t = 0;
    for(int k = 0; k < 4; ++k) {
      std::array<int, 3> f;
      for(int m = 0, c = 0; m < 4; ++m)
        if(m != k)
          f[std::size_t(c++)] = m;
      const auto n = internal::cross(internal::sub<3>(p[f[1]], p[f[0]]), internal::sub<3>(p[f[2]], p[f[0]]));
      for(int a = 0; a < 3; ++a) {
        Torsion_triangle& tri = out[t++];
        tri.vertex = f[std::size_t(a)];
        tri.apex = k;
        tri.edge = {f[std::size_t((a + 1) % 3)], f[std::size_t((a + 2) % 3)]};
        // j on the line of the edge with (j - p_i) . m = 0, m the normal of
        // the plane spanned by the face normal and the edge ik
        const auto m = internal::cross(n, internal::sub<3>(p[k], p[tri.vertex]));
        const auto e = internal::sub<3>(p[tri.edge[1]], p[tri.edge[0]]);
        const double num = internal::dot<3>(internal::sub<3>(p[tri.vertex], p[tri.edge[0]]), m);
        const double den = internal::dot<3>(e, m);
        const double lambda = den != 0 ? num / den : 0.5;
        tri.lambda = std::isnan(lambda) ? 0.5 : std::min(1.0, std::max(0.0, lambda));
      }
    }
    return out;
  }

  /// Rows: the gradient of each interior angle of the (3D) triangle
  /// (t0, t1, t2) with respect to its nine coordinates (x0 y0 z0 x1 ...).
  static std::array<std::array<double, 9>, 3> angle_gradients(const std::array<double, 3>& t0,
                                                                const std::array<double, 3>& t1,
                                                                const std::array<double, 3>& t2)
  {
    // with u = t_b - t_a, v = t_c - t_a, w = u x v: moving t_b towards v
    // within the plane closes the angle, at rate 1/|u|: d theta/d t_b =
    // -(w x u) / (|w| |u|^2), and likewise d theta/d t_c = -(v x w) / (|w| |v|^2)
    const std::array<const std::array<double, 3>*, 3> t{&t0, &t1, &t2};
    std::array<std::array<double, 9>, 3> G{};
    for(int a = 0; a < 3; ++a) {
      const int b = (a + 1) % 3, c = (a + 2) % 3;
      const auto u = internal::sub<3>(*t[std::size_t(b)], *t[std::size_t(a)]);
      const auto v = internal::sub<3>(*t[std::size_t(c)], *t[std::size_t(a)]);
      const auto w = internal::cross(u, v);
      const double lw = internal::norm<3>(w);
      const auto gb = internal::cross(w, u);
      const auto gc = internal::cross(v, w);
      const double sb = -1 / (lw * internal::dot<3>(u, u)), sc = -1 / (lw * internal::dot<3>(v, v));
      for(int r = 0; r < 3; ++r) {
        G[std::size_t(a)][std::size_t(3 * b + r)] = sb * gb[std::size_t(r)];
        G[std::size_t(a)][std::size_t(3 * c + r)] = sc * gc[std::size_t(r)];
        G[std::size_t(a)][std::size_t(3 * a + r)] = -(sb * gb[std::size_t(r)] + sc * gc[std::size_t(r)]);
      }
    }
    return G;
  }

  /// Rows of R: the gradient of each interior angle with respect to
  /// (x0, y0, x1, y1, x2, y2).
  static std::array<std::array<double, 6>, 3> angle_gradients(const std::array<std::array<double, 2>, 3>& p)
  {
    // theta_a = s (phi(a->c) - phi(a->b)), b = a+1, c = a+2, s the orientation:
    // the turn from the next to the previous vertex is counter-clockwise in a
    // counter-clockwise triangle. d phi(a->b) / d p_b = (-dy, dx) / l^2.
    const double s = internal::signed_measure(p) > 0 ? 1.0 : -1.0;
    std::array<std::array<double, 6>, 3> R{};
    for(int a = 0; a < 3; ++a) {
      const int b = (a + 1) % 3, c = (a + 2) % 3;
      const double ubx = p[b][0] - p[a][0], uby = p[b][1] - p[a][1];
      const double ucx = p[c][0] - p[a][0], ucy = p[c][1] - p[a][1];
      const double lb = ubx * ubx + uby * uby, lc = ucx * ucx + ucy * ucy;
      const double gbx = -uby / lb, gby = ubx / lb; // d phi(a->b) / d p_b
      const double gcx = -ucy / lc, gcy = ucx / lc; // d phi(a->c) / d p_c
      R[a][2 * c] += s * gcx;
      R[a][2 * c + 1] += s * gcy;
      R[a][2 * b] -= s * gbx;
      R[a][2 * b + 1] -= s * gby;
      R[a][2 * a] += s * (gbx - gcx);
      R[a][2 * a + 1] += s * (gby - gcy);
    }
    return R;
  }

  /// Adds R^T C R (6x6, row-major, coordinates ordered x0 y0 x1 y1 x2 y2) to K.
  void add_element_matrix(const std::array<std::array<double, 2>, 3>& p, double* K) const
  {
    // R grows like 1/length and C is at most 1e200 (inverse_sin_squared):
    // C R^T R stays finite for edges longer than ~1e-50. A shorter edge would
    // overflow or, once its squared length underflows, divide by zero.
    for(int a = 0; a < 3; ++a) {
      const double dx = p[(a + 1) % 3][0] - p[a][0], dy = p[(a + 1) % 3][1] - p[a][1];
      SPRING_MOTION_CHECK(dx * dx + dy * dy >= 1e-100,
                          "the torsional model needs edges longer than 1e-50 (found one of squared length "
                              << dx * dx + dy * dy << "): scale the mesh");
    }
    const auto R = angle_gradients(p);
    const auto theta = internal::triangle_angles<2>(p[0], p[1], p[2]);
    for(int a = 0; a < 3; ++a) {
      const double C = torsion_scale * internal::inverse_sin_squared(theta[a]);
      for(int r = 0; r < 6; ++r)
        for(int q = 0; q < 6; ++q)
          K[6 * r + q] += C * R[a][r] * R[a][q];
    }
  }

  /// Adds sum over the twelve triangles of torsion_triangles() and their
  /// angles of C g g^T (12x12, row-major, coordinates ordered x0 y0 z0 x1 ...),
  /// g the angle's gradient with j's part shared out to the edge's ends.
  void add_element_matrix(const std::array<std::array<double, 3>, 4>& p, double* K) const
  {
    // as in 2D: g grows like 1/length and C is at most 1e200; and the
    // torsion triangles' construction forms fourth powers of the lengths
    // (a face normal's cross product with an edge, dotted with an edge),
    // which overflow for edges beyond ~1e77
    for(int a = 0; a < 4; ++a)
      for(int b = a + 1; b < 4; ++b) {
        const auto e = internal::sub<3>(p[b], p[a]);
        const double ee = internal::dot<3>(e, e);
        SPRING_MOTION_CHECK(ee >= 1e-100 && ee <= 1e100,
                            "the torsional model in 3D needs edges between 1e-50 and 1e50 long (found one of squared "
                            "length " << ee << "): scale the mesh");
      }
    // The 36 angles' C and gradients first, then each entry of K summed over
    // them in that order: the products and sums of adding C g g^T angle by
    // angle, so the same bits, with a row of K held in registers instead of
    // loaded and stored 36 times (that traffic was most of the model's time).
    std::array<std::array<double, 12>, 36> g{};
    std::array<double, 36> C;
    std::size_t i = 0;
    for(const Torsion_triangle& tri : torsion_triangles(p)) {
      std::array<double, 3> j;
      for(int c = 0; c < 3; ++c)
        j[std::size_t(c)] = (1 - tri.lambda) * p[tri.edge[0]][std::size_t(c)] + tri.lambda * p[tri.edge[1]][std::size_t(c)];
      const auto& pv = p[tri.vertex];
      const auto& pk = p[tri.apex];
      const double w2 = internal::dot<3>(internal::cross(internal::sub<3>(j, pv), internal::sub<3>(pk, pv)),
                                         internal::cross(internal::sub<3>(j, pv), internal::sub<3>(pk, pv)));
      SPRING_MOTION_CHECK(w2 > 0 && std::isfinite(w2), "the torsional model needs tetrahedra that are not flat");
      const auto G = angle_gradients(pv, j, pk);
      const auto theta = internal::triangle_angles<3>(pv, j, pk);
      for(int a = 0; a < 3; ++a, ++i) {
        for(int c = 0; c < 3; ++c) {
          g[i][std::size_t(3 * tri.vertex + c)] += G[std::size_t(a)][std::size_t(c)];
          g[i][std::size_t(3 * tri.edge[0] + c)] += (1 - tri.lambda) * G[std::size_t(a)][std::size_t(3 + c)];
          g[i][std::size_t(3 * tri.edge[1] + c)] += tri.lambda * G[std::size_t(a)][std::size_t(3 + c)];
          g[i][std::size_t(3 * tri.apex + c)] += G[std::size_t(a)][std::size_t(6 + c)];
        }
        C[i] = torsion_scale * internal::inverse_sin_squared(theta[std::size_t(a)]);
      }
    }
    for(int r = 0; r < 12; ++r) {
      std::array<double, 12> row;
      for(int q = 0; q < 12; ++q)
        row[std::size_t(q)] = K[12 * r + q];
      for(std::size_t t = 0; t < 36; ++t) {
        const double cg = C[t] * g[t][std::size_t(r)];
        for(int q = 0; q < 12; ++q)
          row[std::size_t(q)] += cg * g[t][std::size_t(q)];
      }
      for(int q = 0; q < 12; ++q)
        K[12 * r + q] = row[std::size_t(q)];
    }
  }

  Model_description description(int) const
  {
    return {"torsional", {{"lineal_exponent", lineal_exponent}, {"torsion_scale", torsion_scale}}};
  }
};

} // namespace spring_motion

#endif
