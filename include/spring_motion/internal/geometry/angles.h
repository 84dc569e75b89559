// Copyright (c) 2026 SpringMotion developers.
#ifndef SPRING_MOTION_INTERNAL_GEOMETRY_ANGLES_H
#define SPRING_MOTION_INTERNAL_GEOMETRY_ANGLES_H

#include <spring_motion/internal/geometry/double_pair.h>
#include <spring_motion/internal/geometry/simplex_tables.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

namespace spring_motion {
namespace internal {

/// pi (M_PI is not standard C++).
constexpr double pi = 3.141592653589793238462643383279502884;

template <int N>
inline std::array<double, N> sub(const std::array<double, N>& a, const std::array<double, N>& b)
{
  std::array<double, N> r;
  for(int c = 0; c < N; ++c)
    r[c] = a[c] - b[c];
  return r;
}
template <int N>
inline double dot(const std::array<double, N>& a, const std::array<double, N>& b)
{
  double s = 0;
  for(int c = 0; c < N; ++c)
    s += a[c] * b[c];
  return s;
}
inline std::array<double, 3> cross(const std::array<double, 3>& a, const std::array<double, 3>& b)
{
  return {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
}
template <int N>
inline double norm(const std::array<double, N>& a)
{
  return std::sqrt(dot<N>(a, a));
}

/// |a - b|. The plain sqrt of the sum of squares whenever that sum is a
/// normal number (so results stay bitwise what they always were); when it
/// underflows (edges below ~1e-154) the difference is rescaled by its largest
/// component first, so a tiny but non-zero edge never gets length 0 and a
/// 1/l in a stiffness model never divides by zero.
template <int N>
inline double distance(const std::array<double, N>& a, const std::array<double, N>& b)
{
  double l2 = 0;
  for(int c = 0; c < N; ++c)
    l2 += (a[c] - b[c]) * (a[c] - b[c]);
  if(l2 >= std::numeric_limits<double>::min())
    return std::sqrt(l2);
  double big = 0;
  for(int c = 0; c < N; ++c)
    big = std::max(big, std::abs(a[c] - b[c]));
  if(big == 0)
    return 0;
  double s = 0;
  for(int c = 0; c < N; ++c)
    s += ((a[c] - b[c]) / big) * ((a[c] - b[c]) / big);
  return big * std::sqrt(s);
}

/// The angle between two vectors, in [0, pi]. atan2 of |u x v| and u.v stays
/// accurate near 0 and pi, where acos of a normalised dot product does not.
inline double angle_between(const std::array<double, 2>& u, const std::array<double, 2>& v)
{
  return std::atan2(std::abs(u[0] * v[1] - u[1] * v[0]), u[0] * v[0] + u[1] * v[1]);
}
inline double angle_between(const std::array<double, 3>& u, const std::array<double, 3>& v)
{
  return std::atan2(norm<3>(cross(u, v)), dot<3>(u, v));
}

/// The smallest and the largest of some angles; both not a number if one is.
template <std::size_t M>
inline std::array<double, 2> extremes(const std::array<double, M>& a)
{
  for(double v : a)
    if(std::isnan(v))
      return {v, v};
  const auto mm = std::minmax_element(a.begin(), a.end());
  return {*mm.first, *mm.second};
}

/// The interior angle of triangle (p0, p1, p2) at its vertex k.
template <int N>
inline double triangle_angle(int k, const std::array<double, N>& p0, const std::array<double, N>& p1,
                             const std::array<double, N>& p2)
{
  if(k == 0)
    return angle_between(sub<N>(p1, p0), sub<N>(p2, p0));
  if(k == 1)
    return angle_between(sub<N>(p0, p1), sub<N>(p2, p1));
  return angle_between(sub<N>(p0, p2), sub<N>(p1, p2));
}

/// Interior angles of triangle (p0, p1, p2) at each vertex; angle k faces the
/// triangle's local edge k (Simplex_tables<2>).
template <int N>
inline std::array<double, 3> triangle_angles(const std::array<double, N>& p0, const std::array<double, N>& p1,
                                             const std::array<double, N>& p2)
{
  return {triangle_angle<N>(0, p0, p1, p2), triangle_angle<N>(1, p0, p1, p2), triangle_angle<N>(2, p0, p1, p2)};
}

/// An angle in [0, pi] as the point (s, c) = r (sin, cos), r > 0, that
/// atan2 reads: kept as such, angles are ranked without trigonometry.
struct Angle_point
{
  double s = 0, c = 1;
  double angle() const { return std::atan2(s, c); }
};

/// A number in [0, 2] that increases with the angle of `a`: s / (s + c) on
/// the acute side, 2 - s / (s - c) on the obtuse one. Its rounding error is
/// a few units of 1e-16 and its slope in the angle at least 1/2, so two
/// angles whose keys differ by more than 1e-12 are in the keys' order.
/// (0, 0), which atan2 reads as 0 (a triangle whose coordinates are so
/// small that its products underflow), has no key: not a number, returned
/// without computing 0/0, which would raise the invalid-operation flag.
inline double angle_key(const Angle_point& a)
{
  if(a.s == 0 && a.c == 0)
    return std::numeric_limits<double>::quiet_NaN();
  return a.c >= 0 ? a.s / (a.s + a.c) : 2 - a.s / (a.s - a.c);
}

/// The smallest and the largest angle of an element (interior angles of a
/// triangle, dihedral angles of a tetrahedron), before any atan2.
struct Extreme_angles
{
  Angle_point lo, hi;
  bool finite = true; ///< false: an angle is not a number (non-finite coordinates)
  /// true: the angles were computed directly (a rare path), and are
  /// lo_angle and hi_angle rather than lo and hi
  bool direct = false;
  double lo_angle = 0, hi_angle = 0;
  double smallest() const { return direct ? lo_angle : lo.angle(); }
  double largest() const { return direct ? hi_angle : hi.angle(); }
};

/// The triangle's angle at vertex k as an Angle_point: the same (s, c) as
/// triangle_angle() hands to atan2.
template <int N>
inline Angle_point triangle_angle_point(int k, const std::array<double, N>& p0, const std::array<double, N>& p1,
                                        const std::array<double, N>& p2)
{
  const auto& a = k == 0 ? p0 : (k == 1 ? p1 : p2);
  const auto& b = k == 0 ? p1 : p0;
  const auto& c = k == 2 ? p1 : p2;
  const auto u = sub<N>(b, a), v = sub<N>(c, a);
  if constexpr(N == 2)
    return {std::abs(u[0] * v[1] - u[1] * v[0]), u[0] * v[0] + u[1] * v[1]};
  else
    return {norm<3>(cross(u, v)), dot<3>(u, v)};
}

/// The smallest and the largest of triangle_angles(), ranked by the law of
/// sines: the angles are ordered as the lengths of the edges facing them.
/// (Two angles that differ by a rounding error may swap; the value reported
/// then differs by that error.) Non-finite coordinates take the full path.
template <int N>
inline Extreme_angles triangle_extreme_angles(const std::array<double, N>& p0, const std::array<double, N>& p1,
                                              const std::array<double, N>& p2)
{
  const std::array<double, 3> facing{dot<N>(sub<N>(p1, p2), sub<N>(p1, p2)), dot<N>(sub<N>(p0, p2), sub<N>(p0, p2)),
                                     dot<N>(sub<N>(p0, p1), sub<N>(p0, p1))};
  Extreme_angles out;
  if(!std::isfinite(facing[0] + facing[1] + facing[2])) {
    const auto a = extremes(triangle_angles<N>(p0, p1, p2));
    out.finite = std::isfinite(a[0]);
    out.direct = true;
    out.lo_angle = a[0];
    out.hi_angle = a[1];
    return out;
  }
  const auto mm = std::minmax_element(facing.begin(), facing.end());
  out.lo = triangle_angle_point<N>(int(mm.first - facing.begin()), p0, p1, p2);
  out.hi = triangle_angle_point<N>(int(mm.second - facing.begin()), p0, p1, p2);
  return out;
}

/// The smallest and the largest of triangle_angles(), each the same number
/// that function gives (see triangle_extreme_angles), for two atan2 instead
/// of three.
template <int N>
inline std::array<double, 2> triangle_angle_range(const std::array<double, N>& p0, const std::array<double, N>& p1,
                                                  const std::array<double, N>& p2)
{
  const Extreme_angles e = triangle_extreme_angles<N>(p0, p1, p2);
  return {e.smallest(), e.largest()};
}

/// The projections u, w of tetrahedron p's two vertices off its local edge k
/// onto the plane orthogonal to that edge: the dihedral angle at the edge is
/// the angle between them. `scale` multiplies the edge vectors (a power of
/// two, exact: see dihedral_angles).
inline void dihedral_projections(const std::array<std::array<double, 3>, 4>& p, int k, std::array<double, 3>& u,
                                 std::array<double, 3>& w, double scale = 1)
{
  using T = Simplex_tables<3>;
  const auto& a = p[T::edge[k][0]];
  auto e = sub<3>(p[T::edge[k][1]], a);
  u = sub<3>(p[T::other[k][0]], a);
  w = sub<3>(p[T::other[k][1]], a);
  if(scale != 1)
    for(int c = 0; c < 3; ++c) {
      e[c] *= scale;
      u[c] *= scale;
      w[c] *= scale;
    }
  const double ee = dot<3>(e, e);
  const double su = dot<3>(u, e) / ee, sw = dot<3>(w, e) / ee;
  for(int c = 0; c < 3; ++c) {
    u[c] -= su * e[c];
    w[c] -= sw * e[c];
  }
}

/// Interior dihedral angles of tetrahedron p at its six edges, in the local
/// edge order of Simplex_tables<3>: the angle between the projections of the
/// two other vertices onto the plane orthogonal to the edge. The angles do
/// not depend on the size, but the products do: the angle between u and w
/// forms fourth powers of the lengths, which leave the normal numbers for
/// edges below ~2^-255 (and 0 / 0 follows once the squares underflow) or
/// overflow above ~2^255. A tetrahedron whose edge vectors from vertex 0
/// reach outside [2^-200, 2^200] is scaled by a power of two to size about
/// 1 first, which rounds nothing; within that range nothing is scaled.
inline std::array<double, 6> dihedral_angles(const std::array<std::array<double, 3>, 4>& p)
{
  double extent = 0;
  for(int i = 1; i < 4; ++i)
    for(int c = 0; c < 3; ++c)
      extent = std::max(extent, std::abs(p[i][c] - p[0][c]));
  const double scale = extent > 0 && std::isfinite(extent) && !(extent >= 0x1p-200 && extent <= 0x1p200)
                           ? std::ldexp(1.0, -std::ilogb(extent))
                           : 1.0;
  std::array<double, 6> out;
  std::array<double, 3> u, w;
  for(int k = 0; k < 6; ++k) {
    dihedral_projections(p, k, u, w, scale);
    out[std::size_t(k)] = angle_between(u, w);
  }
  return out;
}

/// The smallest and the largest of dihedral_angles() as Angle_points (for
/// dihedral_angle_range: two atan2 instead of six, and no projections). With g_i the gradient of 6V with respect to
/// vertex i (the cross product of face i's edges: twice its area times its
/// normal, all four inward or all four outward), the angle at the edge of
/// length l between faces i and j has sin = 6V l / (|g_i| |g_j|) and
/// cos = -g_i . g_j / (|g_i| |g_j|), so it is atan2(|6V| l, -g_i . g_j):
/// the common factor drops out. The six (s, c) pairs are ranked without
/// trigonometry by the side of pi/2 they lie on (the sign of c) and, within
/// it, by s / (s + |c|), which keeps its relative accuracy near 0 and near
/// pi (where a cosine cannot tell a sliver's angles apart); atan2 runs for
/// the two extremes. The numbers agree with dihedral_angles() to rounding
/// (tests/test_skewness.cpp, against extended precision). A flat element
/// (6V = 0) gives 0 and pi; non-finite coordinates give not-a-number.
inline Extreme_angles dihedral_extreme_angles(const std::array<std::array<double, 3>, 4>& p)
{
  using T = Simplex_tables<3>;
  Extreme_angles out;
  Extreme_angles flat; // 0 and pi
  flat.lo = {0, 1};
  flat.hi = {0, -1};
  std::array<std::array<double, 3>, 4> q{{{0, 0, 0}, sub<3>(p[1], p[0]), sub<3>(p[2], p[0]), sub<3>(p[3], p[0])}};
  double extent = 0, sum = 0;
  for(int v = 1; v < 4; ++v)
    for(int i = 0; i < 3; ++i) {
      extent = std::max(extent, std::abs(q[std::size_t(v)][std::size_t(i)]));
      sum += q[std::size_t(v)][std::size_t(i)];
    }
  if(!std::isfinite(sum)) {
    out.finite = false;
    return out;
  }
  if(extent == 0)
    return flat;
  // scaled by the extent, so that the fourth powers below neither underflow nor overflow
  const double inv = 1.0 / extent;
  for(auto& v : q)
    for(auto& c : v)
      c *= inv;
  const auto& a = q[1];
  const auto& b = q[2];
  const auto& c = q[3];
  std::array<std::array<double, 3>, 4> g;
  g[1] = cross(b, c);
  g[2] = cross(c, a);
  g[3] = cross(a, b);
  for(int i = 0; i < 3; ++i)
    g[0][std::size_t(i)] = -(g[1][std::size_t(i)] + g[2][std::size_t(i)] + g[3][std::size_t(i)]);
  const double volume6 = std::abs(dot<3>(a, g[1]));
  if(volume6 == 0)
    return flat;
  std::array<double, 6> sine, cosine, key;
  std::array<bool, 6> obtuse;
  for(std::size_t k = 0; k < 6; ++k) {
    const auto e = sub<3>(q[std::size_t(T::edge[k][1])], q[std::size_t(T::edge[k][0])]);
    sine[k] = volume6 * std::sqrt(dot<3>(e, e));
    cosine[k] = -dot<3>(g[std::size_t(T::other[k][0])], g[std::size_t(T::other[k][1])]);
    obtuse[k] = cosine[k] < 0;
    key[k] = sine[k] / (sine[k] + std::abs(cosine[k]));
  }
  const auto less = [&](std::size_t x, std::size_t y) {
    if(obtuse[x] != obtuse[y])
      return obtuse[y];
    return obtuse[x] ? key[x] > key[y] : key[x] < key[y];
  };
  std::size_t lo = 0, hi = 0;
  for(std::size_t k = 1; k < 6; ++k) {
    if(less(k, lo))
      lo = k;
    if(less(hi, k))
      hi = k;
  }
  out.lo = {sine[lo], cosine[lo]};
  out.hi = {sine[hi], cosine[hi]};
  return out;
}

/// The smallest and the largest of dihedral_angles() (see
/// dihedral_extreme_angles); not a number for non-finite coordinates.
inline std::array<double, 2> dihedral_angle_range(const std::array<std::array<double, 3>, 4>& p)
{
  const Extreme_angles e = dihedral_extreme_angles(p);
  if(!e.finite)
    return {std::numeric_limits<double>::quiet_NaN(), std::numeric_limits<double>::quiet_NaN()};
  return {e.lo.angle(), e.hi.angle()};
}

/// Whether every dihedral angle theta of tetrahedron p certainly has
/// sin^2(theta) > `sine_squared`, that is lies strictly between alpha and
/// pi - alpha for sin^2(alpha) = sine_squared: a test with no square root,
/// division or trigonometry, for passing over the elements that cannot hold
/// a set's extreme angles (Quality_extremes::add_element). With g_i as in
/// dihedral_extreme_angles, sin^2 at the edge of length l between faces i and
/// j is (6V)^2 l^2 / (|g_i|^2 |g_j|^2): compared by products. It answers false
/// (decides nothing) unless the element is well conditioned, 6|V| >= 1e-6
/// L^3 for its longest edge L, which bounds every edge below by 1e-6 L and
/// every |g_i| below by 1e-6 L^2: the rounding errors of the products are
/// then below 1e-9 of their values, far inside the comparison's margin of
/// 1e-6. L^2 between 1e-60 and 1e60 (an element out of it answers false,
/// its coordinates replaced by zeros before any product of the squared
/// lengths or the edges' cross products; a coordinate that is infinite fails
/// it, one that is not a number fails it or the comparisons) keeps the
/// products finite and normal.
///
/// With two bounds, an acute angle is held to `acute` and an obtuse one to
/// `obtuse`: every angle lies strictly between alpha and pi - beta for
/// sin^2(alpha) = acute and sin^2(beta) = obtuse, a range that need not be
/// centred on a right angle (a Kuhn cube's tetrahedra have right angles, the
/// largest of theirs, beside angles of 45 degrees). Whether an angle is acute
/// is read from the sign of -g_i . g_j, the cosine's numerator: near a right
/// angle, where rounding may give it the wrong sign, sin^2 is within 1e-9 of
/// 1 and passes either bound or neither unless a bound lies within the
/// margin of 1. With one bound (Kinds false) no dot product is formed.
///
/// Written once over the lane type T (double_pair.h), as
/// dihedral_inverse_sin_squared_lanes(): `c` holds the four corners'
/// coordinates, corner by corner, and `above` receives the answer as T's
/// comparison result (a bool, or a mask per lane; not returned, which would
/// pass a four-lane value back).
#if SPRING_MOTION_HAS_DOUBLE_QUAD
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wpsabi" // see double_pair.h
#endif
template <bool Kinds, class T, class Answer>
SPRING_MOTION_LANES_INLINE void dihedral_sines_squared_lanes(const T (&c)[12], double acute, double obtuse,
                                                             Answer& above)
{
  T ax = c[3] - c[0], ay = c[4] - c[1], az = c[5] - c[2];
  T bx = c[6] - c[0], by = c[7] - c[1], bz = c[8] - c[2];
  T cx = c[9] - c[0], cy = c[10] - c[1], cz = c[11] - c[2];
  const T dx = bx - ax, dy = by - ay, dz = bz - az; // edge 12
  const T ex = cx - ax, ey = cy - ay, ez = cz - az; // edge 13
  const T hx = cx - bx, hy = cy - by, hz = cz - bz; // edge 23
  // squared lengths in Simplex_tables<3>::edge order: 01 02 03 12 13 23
  T l01 = ax * ax + ay * ay + az * az, l02 = bx * bx + by * by + bz * bz, l03 = cx * cx + cy * cy + cz * cz,
    l12 = dx * dx + dy * dy + dz * dz, l13 = ex * ex + ey * ey + ez * ez, l23 = hx * hx + hy * hy + hz * hz;
  // std::max's choice among the six: the first largest
  T longest = l01;
  for(const T l : {l02, l03, l12, l13, l23})
    longest = longest < l ? l : longest;
  // before any product of the squared lengths or the edges' cross products:
  // out of this range the normals' squares (fourth powers of the
  // coordinates) and the products of sixth and eighth powers could overflow
  // (and trap under feenableexcept)
  const auto in_range = (longest >= 1e-60) & (longest <= 1e60);
  const T zero = lanes_of<T>(0);
  for(T* v : {&ax, &ay, &az, &bx, &by, &bz, &cx, &cy, &cz, &l01, &l02, &l03, &l12, &l13, &l23, &longest})
    *v = in_range ? *v : zero;
  const T g1x = by * cz - bz * cy, g1y = bz * cx - bx * cz, g1z = bx * cy - by * cx;
  const T g2x = cy * az - cz * ay, g2y = cz * ax - cx * az, g2z = cx * ay - cy * ax;
  const T g3x = ay * bz - az * by, g3y = az * bx - ax * bz, g3z = ax * by - ay * bx;
  const T g0x = -(g1x + g2x + g3x), g0y = -(g1y + g2y + g3y), g0z = -(g1z + g2z + g3z);
  const T v = ax * g1x + ay * g1y + az * g1z;
  const T f0 = g0x * g0x + g0y * g0y + g0z * g0z, f1 = g1x * g1x + g1y * g1y + g1z * g1z,
          f2 = g2x * g2x + g2y * g2y + g2z * g2z, f3 = g3x * g3x + g3y * g3y + g3z * g3z;
  const T v2 = v * v;
  const T ta = lanes_of<T>(acute * (1 + 1e-6)), to = lanes_of<T>(obtuse * (1 + 1e-6));
  // The bound of the angle at edge k, between the faces opposite its two
  // other vertices (Simplex_tables<3>::other). Written out, not through a
  // lambda: a four-lane value would pass to a function not compiled for AVX.
  T b01 = ta, b02 = ta, b03 = ta, b12 = ta, b13 = ta, b23 = ta;
  if constexpr(Kinds) {
    b01 = g2x * g3x + g2y * g3y + g2z * g3z < 0 ? ta : to;
    b02 = g1x * g3x + g1y * g3y + g1z * g3z < 0 ? ta : to;
    b03 = g1x * g2x + g1y * g2y + g1z * g2z < 0 ? ta : to;
    b12 = g0x * g3x + g0y * g3y + g0z * g3z < 0 ? ta : to;
    b13 = g0x * g2x + g0y * g2y + g0z * g2z < 0 ? ta : to;
    b23 = g0x * g1x + g0y * g1y + g0z * g1z < 0 ? ta : to;
  } else
    (void)to;
  // & rather than &&: no branch per edge
  above = in_range & (v2 >= 1e-12 * longest * longest * longest) & (v2 * l01 > b01 * (f2 * f3)) &
          (v2 * l02 > b02 * (f1 * f3)) & (v2 * l03 > b03 * (f1 * f2)) & (v2 * l12 > b12 * (f0 * f3)) &
          (v2 * l13 > b13 * (f0 * f2)) & (v2 * l23 > b23 * (f0 * f1));
}

template <bool Kinds>
inline bool dihedral_sines_squared_test(const std::array<std::array<double, 3>, 4>& p, double acute, double obtuse)
{
  double c[12];
  for(std::size_t k = 0; k < 4; ++k)
    for(std::size_t j = 0; j < 3; ++j)
      c[3 * k + j] = p[k][j];
  bool above;
  dihedral_sines_squared_lanes<Kinds>(c, acute, obtuse, above);
  return above;
}

#if SPRING_MOTION_HAS_DOUBLE_QUAD
/// dihedral_sines_squared_test with one bound (element_sines_squared_above)
/// of four tetrahedra at once, corners t[0] to t[3], one per lane of an AVX
/// register: above[l] is tetrahedron l's answer, the same (each lane performs
/// the scalar test's operations in its order). The per-step quality passes
/// over nearly every tetrahedron of the wing by this test. Call only where
/// four_lanes_available().
__attribute__((target("avx"))) inline void dihedral_sines_squared_above(const std::array<const double*, 4> (&t)[4],
                                                                        double sine_squared, bool (&above)[4])
{
  Double_quad c[12];
  for(std::size_t k = 0; k < 4; ++k)
    for(std::size_t j = 0; j < 3; ++j)
      c[3 * k + j] = Double_quad{t[0][k][j], t[1][k][j], t[2][k][j], t[3][k][j]};
  Double_quad_mask passed;
  dihedral_sines_squared_lanes<false>(c, sine_squared, sine_squared, passed);
  for(std::size_t l = 0; l < 4; ++l)
    above[l] = passed[l] != 0;
}

/// The signed volumes of four tetrahedra at once, corners t[0] to t[3], their
/// coordinates multiplied by `scale` first: out[l] is
/// signed_measure(tetrahedron l's corners times scale), the same bits (each
/// lane performs its operations in its order). Call only where
/// four_lanes_available().
__attribute__((target("avx"))) inline void scaled_signed_measures(const std::array<const double*, 4> (&t)[4],
                                                                  double scale, double (&out)[4])
{
  typedef Double_quad T;
  T c[12];
  const T s = lanes_of<T>(scale);
  for(std::size_t k = 0; k < 4; ++k)
    for(std::size_t j = 0; j < 3; ++j)
      c[3 * k + j] = T{t[0][k][j], t[1][k][j], t[2][k][j], t[3][k][j]} * s;
  const T ax = c[3] - c[0], ay = c[4] - c[1], az = c[5] - c[2];
  const T bx = c[6] - c[0], by = c[7] - c[1], bz = c[8] - c[2];
  const T cx = c[9] - c[0], cy = c[10] - c[1], cz = c[11] - c[2];
  // dot(a, cross(b, c)) as dot() sums it, from 0 (which keeps a zero's sign)
  const T x = by * cz - bz * cy, y = bz * cx - bx * cz, z = bx * cy - by * cx;
  const T m = (((lanes_of<T>(0) + ax * x) + ay * y) + az * z) / lanes_of<T>(6.0);
  for(std::size_t l = 0; l < 4; ++l)
    out[l] = m[l];
}
#pragma GCC diagnostic pop
#endif

/// The same test for the interior angles of triangle p: sin^2 of the angle
/// between the edges u and w leaving a vertex is (u x w)^2 / (|u|^2 |w|^2),
/// compared by products, and the angle is acute where u . w > 0. It decides
/// nothing (answers false) unless |u x w| >= 1e-6 L^2 for the longest edge
/// L, which bounds every edge below by 1e-6 L (twice the area is at most an
/// edge times L): the cross product's rounding error, at most a few ulps of
/// |u| |w| <= L^2, is then below 1e-9 of its value, as are the other
/// products', far inside the comparison's margin of 1e-6. L^2 between 1e-60
/// and 1e60 (checked first) keeps the products finite and normal.
template <bool Kinds>
inline bool triangle_sines_squared_test(const std::array<std::array<double, 2>, 3>& p, double acute, double obtuse)
{
  const double ax = p[1][0] - p[0][0], ay = p[1][1] - p[0][1]; // edge 01
  const double bx = p[2][0] - p[0][0], by = p[2][1] - p[0][1]; // edge 02
  const double dx = bx - ax, dy = by - ay;                     // edge 12
  const double l01 = ax * ax + ay * ay, l02 = bx * bx + by * by, l12 = dx * dx + dy * dy;
  const double longest = std::max({l01, l02, l12});
  // before any product of them: out of this range they could overflow (and
  // trap under feenableexcept)
  if(!(longest >= 1e-60 && longest <= 1e60))
    return false;
  const double z = ax * by - ay * bx, z2 = z * z;
  const double ta = acute * (1 + 1e-6), to = obtuse * (1 + 1e-6);
  // the bound of the angle whose edges have dot product `d`
  auto bound = [&](double d) {
    if constexpr(Kinds)
      return d > 0 ? ta : to;
    else {
      (void)d, (void)to;
      return ta;
    }
  };
  // vertex 0 between edges 01 and 02, vertex 1 between 10 and 12, vertex 2
  // between 20 and 21; & rather than &&: no branch per vertex
  return (z2 >= 1e-12 * longest * longest) & (z2 > bound(ax * bx + ay * by) * (l01 * l02)) &
         (z2 > bound(-(ax * dx + ay * dy)) * (l01 * l12)) & (z2 > bound(bx * dx + by * dy) * (l02 * l12));
}

/// Whether every angle of the element with corners p (3D: dihedral, 2D:
/// interior) certainly has sin^2 above `sine_squared`
/// (dihedral_sines_squared_test, triangle_sines_squared_test).
template <int D>
inline bool element_sines_squared_above(const std::array<std::array<double, D>, D + 1>& p, double sine_squared)
{
  if constexpr(D == 2)
    return triangle_sines_squared_test<false>(p, sine_squared, sine_squared);
  else
    return dihedral_sines_squared_test<false>(p, sine_squared, sine_squared);
}

/// The same with the acute angles held to `acute` and the obtuse ones to
/// `obtuse`.
template <int D>
inline bool element_sines_squared_above(const std::array<std::array<double, D>, D + 1>& p, double acute,
                                        double obtuse)
{
  if constexpr(D == 2)
    return triangle_sines_squared_test<true>(p, acute, obtuse);
  else
    return dihedral_sines_squared_test<true>(p, acute, obtuse);
}

/// 1/sin^2 of the triangle's angle at each vertex, as triangle_angles
/// orders them, without trigonometry: sin^2 at vertex k is |u x w|^2 /
/// (|u|^2 |w|^2) for the two edges u, w leaving it. The triangle is first
/// scaled by its extent (angles do not change), so tiny or huge coordinates
/// neither underflow nor overflow the fourth powers. sin^2 is floored at
/// 1e-200 as in inverse_sin_squared(), so a flat triangle gives 1e200.
///
/// Written once over the lane type T (double_pair.h), as
/// dihedral_inverse_sin_squared_lanes(): `c` holds the three corners'
/// coordinates, corner by corner.
template <int N, class T>
inline void triangle_inverse_sin_squared_lanes(const T (&c)[3 * N], T (&out)[3])
{
  T u[N], w[N];
  for(int k = 0; k < N; ++k) {
    u[k] = c[N + k] - c[k];
    w[k] = c[2 * N + k] - c[k];
  }
  // std::max's choices, in the scalar form's order
  T extent = lanes_of<T>(0);
  for(int k = 0; k < N; ++k) {
    const T a = lane_abs(u[k]), b = lane_abs(w[k]);
    const T larger = a < b ? b : a;
    extent = extent < larger ? larger : extent;
  }
  // no lane divides by zero (see dihedral_inverse_sin_squared_lanes)
  const auto point_like = extent == lanes_of<T>(0);
  const T inv = lanes_of<T>(1.0) / (point_like ? lanes_of<T>(1.0) : extent);
  for(int k = 0; k < N; ++k) {
    u[k] *= inv;
    w[k] *= inv;
  }
  T cross2;
  if constexpr(N == 2) {
    const T z = u[0] * w[1] - u[1] * w[0];
    cross2 = z * z;
  } else {
    const T n[3] = {u[1] * w[2] - u[2] * w[1], u[2] * w[0] - u[0] * w[2], u[0] * w[1] - u[1] * w[0]};
    cross2 = lanes_of<T>(0);
    for(int k = 0; k < 3; ++k)
      cross2 += n[k] * n[k];
  }
  T uu = lanes_of<T>(0), ww = lanes_of<T>(0), vv = lanes_of<T>(0);
  for(int k = 0; k < N; ++k) {
    uu += u[k] * u[k];
    ww += w[k] * w[k];
  }
  for(int k = 0; k < N; ++k) {
    const T d = w[k] - u[k];
    vv += d * d;
  }
  // local edge k is opposite vertex k: vertex 0 lies on u and w, vertex 1 on
  // u and w - u, vertex 2 on w and w - u
  const T den[3] = {uu * ww, uu * vv, ww * vv};
  const T cap = lanes_of<T>(1e200);
  for(int k = 0; k < 3; ++k) {
    const auto finite = (den[k] > 0) & (cross2 > 1e-200 * den[k]) & !point_like;
    out[k] = finite ? den[k] / (finite ? cross2 : lanes_of<T>(1.0)) : cap;
  }
}

template <int N>
inline std::array<double, 3> triangle_inverse_sin_squared(const std::array<double, N>& p0,
                                                          const std::array<double, N>& p1,
                                                          const std::array<double, N>& p2)
{
  double c[3 * N], out[3];
  for(int k = 0; k < N; ++k) {
    c[k] = p0[std::size_t(k)];
    c[N + k] = p1[std::size_t(k)];
    c[2 * N + k] = p2[std::size_t(k)];
  }
  triangle_inverse_sin_squared_lanes<N>(c, out);
  return {out[0], out[1], out[2]};
}

/// triangle_inverse_sin_squared() of two plane triangles, corners a and b,
/// at once: the same values.
inline std::array<std::array<double, 3>, 2> triangle_inverse_sin_squared(const std::array<const double*, 3>& a,
                                                                         const std::array<const double*, 3>& b)
{
  return in_two_lanes<3, 2, 3>(a, b, [](const auto& c, auto& out) { triangle_inverse_sin_squared_lanes<2>(c, out); });
}

/// 1/sin^2 of the tetrahedron's dihedral angle at each edge, in the order of
/// dihedral_angles(), without trigonometry. With n_f the cross product of
/// face f (|n_f| twice its area), V the volume and l the edge's length,
/// V = 2 A_1 A_2 sin(theta) / (3 l) gives sin^2(theta) = (6V)^2 l^2 /
/// (|n_1|^2 |n_2|^2): four cross products and one triple product per
/// tetrahedron instead of six projections and six atan2. Scaled and floored
/// as triangle_inverse_sin_squared().
///
/// Written once over the lane type T (double_pair.h): `c` holds the four
/// corners' coordinates, corner by corner, and `out` receives the six values
/// in edge order; with T = Double_pair each lane is one tetrahedron.
#if SPRING_MOTION_HAS_DOUBLE_QUAD
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wpsabi" // see double_pair.h
#endif
template <class T>
SPRING_MOTION_LANES_INLINE void dihedral_inverse_sin_squared_lanes(const T (&c)[12], T (&out)[6])
{
  // Written in scalars, not through sub/cross/dot on std::array: the
  // compiler kept the arrays on the stack, stored each cross product's
  // components one by one and read two of them back as one vector, a load
  // that store forwarding cannot serve; that stall took a quarter of the
  // function.
  T ax = c[3] - c[0], ay = c[4] - c[1], az = c[5] - c[2];
  T bx = c[6] - c[0], by = c[7] - c[1], bz = c[8] - c[2];
  T cx = c[9] - c[0], cy = c[10] - c[1], cz = c[11] - c[2];
  // std::max's choice among the nine: the first largest
  T extent = lane_abs(ax);
  for(const T v : {ay, az, bx, by, bz, cx, cy, cz})
    extent = extent < lane_abs(v) ? lane_abs(v) : extent;
  // A point-like tetrahedron (extent 0) gives the cap at every edge, below.
  // A vector computes both sides of each choice in every lane, so its
  // divisors are replaced where the choice discards the quotient: no lane
  // divides by zero, and a run with floating-point traps on stays quiet.
  const auto point_like = extent == lanes_of<T>(0);
  const T inv = lanes_of<T>(1.0) / (point_like ? lanes_of<T>(1.0) : extent);
  ax *= inv, ay *= inv, az *= inv;
  bx *= inv, by *= inv, bz *= inv;
  cx *= inv, cy *= inv, cz *= inv;
  // ab = a x b, ac = a x c, bc = b x c
  const T abx = ay * bz - az * by, aby = az * bx - ax * bz, abz = ax * by - ay * bx;
  const T acx = ay * cz - az * cy, acy = az * cx - ax * cz, acz = ax * cy - ay * cx;
  const T bcx = by * cz - bz * cy, bcy = bz * cx - bx * cz, bcz = bx * cy - by * cx;
  const T det = ax * bcx + ay * bcy + az * bcz;
  // the face opposite vertex 0: (b - a) x (c - a) = bc - ac + ab
  const T n0x = bcx - acx + abx, n0y = bcy - acy + aby, n0z = bcz - acz + abz;
  // |n_f|^2 of the face opposite vertex f
  const T f0 = n0x * n0x + n0y * n0y + n0z * n0z, f1 = bcx * bcx + bcy * bcy + bcz * bcz,
          f2 = acx * acx + acy * acy + acz * acz, f3 = abx * abx + aby * aby + abz * abz;
  const T det2 = det * det;
  // Per edge k (Simplex_tables<3>::edge), written out rather than looked up
  // in the tables: read through a table from a small array on the stack, the
  // compiler's vector loads of separately stored values stalled (store
  // forwarding) and cost a fifth of the function. The two faces at edge k
  // are those opposite its two other vertices (Simplex_tables<3>::other).
  const T den[6]{f2 * f3, f1 * f3, f1 * f2, f0 * f3, f0 * f2, f0 * f1};
  const T bax = bx - ax, bay = by - ay, baz = bz - az;
  const T cax = cx - ax, cay = cy - ay, caz = cz - az;
  const T cbx = cx - bx, cby = cy - by, cbz = cz - bz;
  const T l2[6]{ax * ax + ay * ay + az * az,       bx * bx + by * by + bz * bz,
                cx * cx + cy * cy + cz * cz,       bax * bax + bay * bay + baz * baz,
                cax * cax + cay * cay + caz * caz, cbx * cbx + cby * cby + cbz * cbz};
  const T cap = lanes_of<T>(1e200);
  for(int k = 0; k < 6; ++k) {
    const T num = det2 * l2[k];
    const auto finite = (den[k] > 0) & (num > 1e-200 * den[k]) & !point_like;
    out[k] = finite ? den[k] / (finite ? num : lanes_of<T>(1.0)) : cap;
  }
}
#if SPRING_MOTION_HAS_DOUBLE_QUAD
#pragma GCC diagnostic pop
#endif

inline std::array<double, 6> dihedral_inverse_sin_squared(const std::array<std::array<double, 3>, 4>& p)
{
  double c[12], out[6];
  for(int k = 0; k < 4; ++k)
    for(int j = 0; j < 3; ++j)
      c[3 * k + j] = p[std::size_t(k)][std::size_t(j)];
  dihedral_inverse_sin_squared_lanes(c, out);
  return {out[0], out[1], out[2], out[3], out[4], out[5]};
}

/// dihedral_inverse_sin_squared() of two tetrahedra, corners a and b, at
/// once: the same values, in about half the time of two calls.
inline std::array<std::array<double, 6>, 2> dihedral_inverse_sin_squared(const std::array<const double*, 4>& a,
                                                                         const std::array<const double*, 4>& b)
{
  return in_two_lanes<4, 3, 6>(a, b, [](const auto& c, auto& out) { dihedral_inverse_sin_squared_lanes(c, out); });
}

#if SPRING_MOTION_HAS_DOUBLE_QUAD
/// dihedral_inverse_sin_squared() of four tetrahedra at once, corners t[0]
/// to t[3], one per lane of an AVX register (double_pair.h): out[l] gets
/// tetrahedron l's values, the same bits, with the divisions and products
/// of four tetrahedra in one instruction each. Call only where
/// four_lanes_available().
__attribute__((target("avx"))) inline void dihedral_inverse_sin_squared(const std::array<const double*, 4> (&t)[4],
                                                                        double (&out)[4][6])
{
  Double_quad c[12], values[6];
  for(std::size_t k = 0; k < 4; ++k)
    for(std::size_t j = 0; j < 3; ++j)
      c[3 * k + j] = Double_quad{t[0][k][j], t[1][k][j], t[2][k][j], t[3][k][j]};
  dihedral_inverse_sin_squared_lanes(c, values);
  for(std::size_t k = 0; k < 6; ++k)
    for(std::size_t l = 0; l < 4; ++l)
      out[l][k] = values[k][l];
}
#endif

/// Signed area (2D) or volume (3D) of a simplex, positive when the vertices
/// are counter-clockwise / positively oriented.
inline double signed_measure(const std::array<std::array<double, 2>, 3>& p)
{
  return 0.5 * ((p[1][0] - p[0][0]) * (p[2][1] - p[0][1]) - (p[1][1] - p[0][1]) * (p[2][0] - p[0][0]));
}
inline double signed_measure(const std::array<std::array<double, 3>, 4>& p)
{
  return dot<3>(sub<3>(p[1], p[0]), cross(sub<3>(p[2], p[0]), sub<3>(p[3], p[0]))) / 6.0;
}

} // namespace internal
} // namespace spring_motion

#endif
