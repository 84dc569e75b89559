// Copyright (c) 2026 SpringMotion developers.
#ifndef SPRING_MOTION_STIFFNESS_TORSIONAL_STIFFNESS_H
#define SPRING_MOTION_STIFFNESS_TORSIONAL_STIFFNESS_H

#include <spring_motion/Error.h>
#include <spring_motion/internal/angles.h>
#include <spring_motion/internal/capped_math.h>
#include <spring_motion/stiffness/Stiffness_model.h>

#include <array>
#include <cmath>

namespace spring_motion {

/// Farhat's torsional springs (Farhat, Degand, Koobus, Lesoinne 1998), 2D:
/// lineal springs `1/l^p` on the edges plus, in every triangle, a torsion
/// spring of stiffness `C_i = 1/sin^2(theta_i)` at each vertex, assembled as
/// `R^T C R` where R holds the derivatives of the three angles with respect
/// to the six coordinates. The torsion couples x and y, so the solver works
/// on 2x2 blocks.
///
/// Our lineal part acts on each component separately (Batina's springs), as
/// in every other model here, which keeps the system positive definite.
struct Torsional_stiffness
{
  double lineal_exponent = 1.0;
  double torsion_scale = 1.0; ///< multiplies every C_i

  Angle_kind angle_kind(int dimension) const
  {
    // without a 3D element matrix the model would silently be lineal springs
    SPRING_MOTION_CHECK(dimension == 2, "the torsional model is implemented in 2D only");
    return Angle_kind::none;
  }
  double operator()(double length, const double*, std::size_t, const Stiffness_context&) const
  {
    return internal::capped_pow(length, -lineal_exponent);
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

  Model_description description(int) const
  {
    return {"torsional", {{"lineal_exponent", lineal_exponent}, {"torsion_scale", torsion_scale}}};
  }
};

} // namespace spring_motion

#endif
