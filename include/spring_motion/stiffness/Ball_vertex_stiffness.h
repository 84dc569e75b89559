// Copyright (c) 2026 SpringMotion developers.
#ifndef SPRING_MOTION_STIFFNESS_BALL_VERTEX_STIFFNESS_H
#define SPRING_MOTION_STIFFNESS_BALL_VERTEX_STIFFNESS_H

#include <spring_motion/Error.h>
#include <spring_motion/internal/geometry/angles.h>
#include <spring_motion/internal/geometry/capped_math.h>
#include <spring_motion/internal/geometry/double_pair.h>
#include <spring_motion/stiffness/Stiffness_model.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <limits>

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
  Edge_spring_form edge_spring_form() const { return Edge_spring_form::none; }

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
    return altitudes(p)[std::size_t(i)];
  }

  /// The four altitudes of tetrahedron p, from its facet normals N_i (twice
  /// the facet's area, all pointing to the same side): with 6V = N_i . (p_i -
  /// any vertex of facet i), the same for every i, h_i = |6V| / |N_i|, and the
  /// foot of altitude i, p_i - (6V / |N_i|^2) N_i, has the barycentric
  /// coordinates b_j = -N_i . N_j / |N_i|^2 (the gradients of the barycentric
  /// functions are N_j / 6V). Ten dot products instead of three cross
  /// products per altitude.
  static std::array<Altitude<3>, 4> altitudes(const std::array<std::array<double, 3>, 4>& p)
  {
    const auto f = facet_normals(p);
    const double s = f.measure >= 0 ? 1.0 : -1.0;
    std::array<Altitude<3>, 4> a;
    for(std::size_t i = 0; i < 4; ++i) {
      const auto& N = f.normal;
      const double NN = internal::dot<3>(N[i], N[i]);
      SPRING_MOTION_CHECK(NN > 0 && std::isfinite(NN), "ball-vertex springs need facets of non-zero size");
      const double len = std::sqrt(NN);
      for(std::size_t j = 0; j < 4; ++j)
        a[i].foot[j] = j == i ? 0.0 : -internal::dot<3>(N[i], N[j]) / NN;
      for(std::size_t k = 0; k < 3; ++k)
        a[i].normal[k] = s * N[i][k] / len;
      a[i].height = std::abs(f.measure) / len;
    }
    return a;
  }

  /// The three altitudes of triangle p.
  static std::array<Altitude<2>, 3> altitudes(const std::array<std::array<double, 2>, 3>& p)
  {
    return {altitude(p, 0), altitude(p, 1), altitude(p, 2)};
  }

  /// Spring stiffness of an altitude of length h.
  double spring_stiffness(double h) const { return weight * internal::capped_pow(h, -exponent); }

  void add_element_matrix(const std::array<std::array<double, 2>, 3>& p, double* K) const { add<2>(p, K); }
  void add_element_matrix(const std::array<std::array<double, 3>, 4>& p, double* K) const { add<3>(p, K); }

  /// The same matrix by its distinct values: block (v, w) equals block (w,
  /// v) and is symmetric, so the (D+1)(D+2)/2 blocks v <= w (in the order
  /// (0,0), (0,1), ..., (D,D)), each as its upper triangle by rows, are added
  /// to S. The assembly reads these instead of the whole matrix.
  void add_symmetric_blocks(const std::array<std::array<double, 2>, 3>& p, double* S) const
  {
    blocks<2>(p, [&](int, int, int, int, int m, int pair, double b) { S[pair * 3 + m] += b; });
  }
  void add_symmetric_blocks(const std::array<std::array<double, 3>, 4>& p, double* S) const
  {
    blocks<3>(p, [&](int, int, int, int, int m, int pair, double b) { S[pair * 6 + m] += b; });
  }

  /// The values add_symmetric_blocks adds, of two simplices at once,
  /// stored (not added): p's in S and q's in T, the two simplices'
  /// arithmetic in the two lanes of one register. Returns false, leaving S
  /// and T as they were, when either needs what only the one-simplex form
  /// does (an edge or a facet too small, a stiffness outside the range
  /// where it is not capped, an exponent other than 1, 2, 5/2 or 3, a value
  /// that is not finite): call
  /// add_symmetric_blocks for each, which also reports what is wrong.
  bool symmetric_blocks_of_two(const std::array<std::array<double, 2>, 3>& p,
                               const std::array<std::array<double, 2>, 3>& q, double* S, double* T) const
  {
#if SPRING_MOTION_HAS_DOUBLE_PAIR
    return blocks_in_lanes<2, internal::Double_pair, 2>({&p, &q}, {S, T});
#else
    return false;
#endif
  }
  bool symmetric_blocks_of_two(const std::array<std::array<double, 3>, 4>& p,
                               const std::array<std::array<double, 3>, 4>& q, double* S, double* T) const
  {
#if SPRING_MOTION_HAS_DOUBLE_PAIR
    return blocks_in_lanes<3, internal::Double_pair, 2>({&p, &q}, {S, T});
#else
    return false;
#endif
  }

  /// The same for four simplices at once, p[l]'s values stored in S[l], one
  /// simplex per lane of an AVX register; false when any of them needs the
  /// one-simplex form. Call only where internal::four_lanes_available().
#if SPRING_MOTION_HAS_DOUBLE_QUAD
  __attribute__((target("avx"))) bool symmetric_blocks_of_four(
      const std::array<const std::array<std::array<double, 2>, 3>*, 4>& p, const std::array<double*, 4>& S) const
  {
    return blocks_in_lanes<2, internal::Double_quad, 4>(p, S);
  }
  __attribute__((target("avx"))) bool symmetric_blocks_of_four(
      const std::array<const std::array<std::array<double, 3>, 4>*, 4>& p, const std::array<double*, 4>& S) const
  {
    return blocks_in_lanes<3, internal::Double_quad, 4>(p, S);
  }
#endif

  Model_description description(int) const
  {
    return {"ball_vertex", {{"exponent", exponent}, {"weight", weight}}};
  }

private:
#if SPRING_MOTION_HAS_DOUBLE_QUAD
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wpsabi" // see double_pair.h
#endif
  // The simplex's facet normals N_i (facet i faces vertex i), each as long
  // as its facet's measure (2D: the edge's length; 3D: twice the triangle's
  // area) and all pointing to the same side, and the signed measure V with
  // N_i . (p_i - any vertex of facet i) = V for every i (2D: twice the area;
  // 3D: six times the volume). Then h_i = |V| / |N_i|, and the foot of
  // altitude i has the barycentric coordinates b_j = -N_i . N_j / |N_i|^2
  // (the gradients of the barycentric functions are N_j / V).
  //
  // Written over the lane type T (double, or Double_pair for two simplices
  // at once, double_pair.h) with the helpers below, which do angles.h's
  // sub, dot and cross in their order: the same bits either way.
  template <int D, class T = double>
  struct Facet_normals
  {
    std::array<std::array<T, D>, D + 1> normal;
    T measure;
  };
  template <class T>
  SPRING_MOTION_LANES_STATIC Facet_normals<2, T> facet_normals(const std::array<std::array<T, 2>, 3>& p)
  {
    Facet_normals<2, T> f;
    for(int i = 0; i < 3; ++i) { // the edge from p_j to p_l turned a quarter
      const auto& j = p[std::size_t((i + 1) % 3)];
      const auto& l = p[std::size_t((i + 2) % 3)];
      f.normal[std::size_t(i)] = {l[1] - j[1], j[0] - l[0]};
    }
    dot<2>(sub<2>(p[0], p[1]), f.normal[0], f.measure);
    return f;
  }
  template <class T>
  SPRING_MOTION_LANES_STATIC Facet_normals<3, T> facet_normals(const std::array<std::array<T, 3>, 4>& p)
  {
    const auto e1 = sub<3>(p[1], p[0]), e2 = sub<3>(p[2], p[0]), e3 = sub<3>(p[3], p[0]);
    // N_0 from its own facet's edges, not as -(N_1 + N_2 + N_3): no
    // cancellation when facet 0 is small
    Facet_normals<3, T> f;
    f.normal = {cross(sub<3>(p[3], p[1]), sub<3>(p[2], p[1])), cross(e2, e3), cross(e3, e1), cross(e1, e2)};
    dot<3>(e1, f.normal[1], f.measure);
    return f;
  }

  template <int D, class T>
  SPRING_MOTION_LANES_STATIC std::array<T, D> sub(const std::array<T, D>& a, const std::array<T, D>& b)
  {
    std::array<T, D> r;
    for(std::size_t c = 0; c < D; ++c)
      r[c] = a[c] - b[c];
    return r;
  }
  template <int D, class T>
  SPRING_MOTION_LANES_STATIC void dot(const std::array<T, D>& a, const std::array<T, D>& b, T& s)
  {
    // s as an argument, not returned: a four-lane value returned from code
    // not compiled for AVX would change the ABI (double_pair.h)
    s = internal::lanes_of<T>(0.0);
    for(std::size_t c = 0; c < D; ++c)
      s += a[c] * b[c];
  }
  template <class T>
  SPRING_MOTION_LANES_STATIC std::array<T, 3> cross(const std::array<T, 3>& a, const std::array<T, 3>& b)
  {
    return {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
  }

  // |p_b - p_a|^2 of the simplex's edges, a < b
  template <int D, class T>
  SPRING_MOTION_LANES_STATIC std::array<T, D*(D + 1) / 2> squared_edges(const std::array<std::array<T, D>, D + 1>& p)
  {
    std::array<T, D*(D + 1) / 2> ee;
    for(std::size_t a = 0, k = 0; a <= D; ++a)
      for(std::size_t b = a + 1; b <= D; ++b, ++k) {
        const auto e = sub<D>(p[b], p[a]);
        dot<D>(e, e, ee[k]);
      }
    return ee;
  }

  // N_i . N_j
  template <int D, class T>
  SPRING_MOTION_LANES_STATIC std::array<std::array<T, D + 1>, D + 1> gram(const std::array<std::array<T, D>, D + 1>& N)
  {
    std::array<std::array<T, D + 1>, D + 1> G;
    for(std::size_t i = 0; i <= D; ++i)
      for(std::size_t j = i; j <= D; ++j) {
        dot<D>(N[i], N[j], G[i][j]);
        G[j][i] = G[i][j];
      }
    return G;
  }

  // The block solver inverts D x D sums of these matrices and of the edge
  // springs (up to 1/l^2): its determinant, a product of D such entries,
  // stays finite for edges longer than ~1e-50, as with torsional springs.
  static constexpr double min_squared_edge = 1e-100;
  // In 3D the facet normals' products (N_i . N_j) are fourth powers of the
  // lengths, which overflow for edges beyond ~1e77: 3D edges must be
  // shorter than 1e50 (in 2D they are squares, no bound needed).
  template <int D>
  static constexpr double max_squared_edge = D == 3 ? 1e100 : std::numeric_limits<double>::infinity();

  // 2p for the powers p of k = weight / h^p that blocks() forms from the
  // facet normals without a power function (1, 2, 5/2 and 3), else 0
  int doubled_power() const
  {
    return exponent == 1 ? 2 : exponent == 2 ? 4 : exponent == 2.5 ? 5 : exponent == 3 ? 6 : 0;
  }
  // The power the range tests below take: p rounded up (|V|^3 normal
  // implies |V|^(5/2) normal, and so for the heights)
  static int bound_power(int doubled) { return (doubled + 1) / 2; }

  // Whether |V|^p is a normal number (vexp: log2 |V|), and whether h_i^-p,
  // h_i = |V| / |N_i|, lies far enough inside the range where capped_pow
  // does not cap it (log2 h_i within 2 of vexp - log2 |N_i|): blocks()'s
  // products of the facet normals then give k without a power function.
  static bool volume_uncapped(int power, double volume, int vexp)
  {
    return power > 0 && volume > 0 && power * (std::abs(vexp) + 1) < 1000;
  }
  static bool height_uncapped(int power, int vexp, double NN)
  {
    return power * (std::abs(vexp - internal::binary_exponent(NN) / 2) + 3) < 790;
  }

  // k_i / |N_i|^2 = weight |N_i|^(p-2) / |V|^p in its two pieces, on lanes T
  // (one function for blocks() and its lanes, so that both run the same
  // operations): 1 / |V|^p, formed once per element (p = 5/2: 1 / |V|^2),
  // and the factor of facet i, |N_i|^(p-2) (p = 5/2: sqrt(|N_i| / |V|), the
  // |V|^(-1/2) left over taken with it). Results as arguments, as in dot().
  template <class T>
  SPRING_MOTION_LANES_STATIC void inverse_volume_power(int doubled, const T& volume, const T& one, T& result)
  {
    result = one / (doubled == 2 ? volume : doubled <= 5 ? volume * volume : volume * volume * volume);
  }
  template <class T>
  SPRING_MOTION_LANES_STATIC void times_facet_factor(int doubled, const T& NN, const T& volume, T& g)
  {
    if(doubled == 4)
      return;
    const T len = internal::lane_sqrt(NN);
    g = doubled == 2 ? g / len : doubled == 6 ? g * len : g * internal::lane_sqrt(len / volume);
  }

  // The blocks v <= w (in the order of add_symmetric_blocks, each as its
  // upper triangle) of sum_i k_i c_iv c_iw n_i n_i^T, from knn[i] = k_i n_i
  // n_i^T (upper triangle) and c[i][v], on lanes T (double, or two or four
  // elements' lanes): the blocks v <= w < D from the springs; the
  // last vertex's from the others: each block row sums to zero (sum_v c_iv
  // = 0, the feet's coordinates summing to 1), so a rigid translation is in
  // the null space by construction, and the tetrahedron needs 6 of its 10
  // blocks.
  template <int D, class T>
  SPRING_MOTION_LANES_STATIC std::array<std::array<T, D*(D + 1) / 2>, (D + 1) * (D + 2) / 2> sum_blocks(
      const std::array<std::array<T, D*(D + 1) / 2>, D + 1>& knn, const std::array<std::array<T, D + 1>, D + 1>& c)
  {
    constexpr int S = D * (D + 1) / 2;
    auto pair_of = [](int v, int w) { // v <= w
      return v * (2 * D + 3 - v) / 2 + (w - v);
    };
    std::array<std::array<T, S>, (D + 1) * (D + 2) / 2> B{};
#pragma GCC unroll 4
    for(int v = 0; v < D; ++v)
#pragma GCC unroll 4
      for(int w = v; w < D; ++w) {
        auto& b = B[std::size_t(pair_of(v, w))];
#pragma GCC unroll 4
        for(int i = 0; i <= D; ++i) {
          const T f = c[std::size_t(i)][std::size_t(v)] * c[std::size_t(i)][std::size_t(w)];
          for(int m = 0; m < S; ++m)
            b[std::size_t(m)] += f * knn[std::size_t(i)][std::size_t(m)];
        }
      }
#pragma GCC unroll 4
    for(int v = 0; v <= D; ++v) { // B(v, D) = -sum_{w < D} B(v, w)
      auto& last = B[std::size_t(pair_of(v, D))];
#pragma GCC unroll 4
      for(int w = 0; w < D; ++w) {
        const auto& b = B[std::size_t(v == D ? pair_of(w, D) : pair_of(std::min(v, w), std::max(v, w)))];
        for(int m = 0; m < S; ++m)
          last[std::size_t(m)] -= b[std::size_t(m)];
      }
    }
    return B;
  }

  // Block (v, w) of sum_i k_i a_i a_i^T, a_i = (n_i at vertex i, -b_v n_i at
  // each other vertex v), is sum_i k_i c_iv c_iw n_i n_i^T (c_ii = 1, c_iv =
  // -b_v): symmetric and equal to block (w, v), so only the (D+1)(D+2)/2
  // blocks v <= w are formed, each from its D(D+1)/2 distinct entries, and
  // each entry (r, q), r <= q, handed to out(v, w, r, q, m, pair, value) (m:
  // its place in the upper triangle by rows, pair: the block's place among
  // the blocks v <= w).
  //
  // Formed from the facet normals without normalising them: k_i n_i n_i^T =
  // (k_i / |N_i|^2) N_i N_i^T and c_iv = N_i . N_v / |N_i|^2, and with k =
  // weight / h^p, h_i = |V| / |N_i|, the factor k_i / |N_i|^2 is weight
  // |N_i|^(p-2) / |V|^p: for p = 2 the same for all altitudes, with no square
  // root (the square roots and quotients of the unit normals, heights and
  // feet were most of the kernel's time). Where that product could leave
  // the range in which k is not capped, k is taken from the height as
  // spring_stiffness() gives it.
  template <int D, class Out>
  void blocks(const std::array<std::array<double, D>, D + 1>& p, Out out) const
  {
    constexpr int S = D * (D + 1) / 2;
    for(const double ee : squared_edges<D>(p))
      SPRING_MOTION_CHECK(ee >= min_squared_edge && ee <= max_squared_edge<D>,
                          "ball-vertex springs need edges longer than 1e-50" << (D == 3 ? " and shorter than 1e50" : "")
                                                                             << " (found one of squared length " << ee
                                                                             << "): scale the mesh");
    const auto facets = facet_normals(p);
    const auto& N = facets.normal;
    const auto G = gram<D>(N);
    const double volume = std::abs(facets.measure);
    const int vexp = internal::binary_exponent(volume);
    const int doubled = doubled_power(), power = bound_power(doubled);
    double inverse_power = 0.0; // unless |V|^p is a normal number
    if(volume_uncapped(power, volume, vexp))
      inverse_volume_power(doubled, volume, 1.0, inverse_power);
    std::array<std::array<double, S>, D + 1> knn; // k_i n_i n_i^T, upper triangle by rows
    std::array<double, D + 1> inverse_NN;
    // The loops over the altitudes and blocks unrolled: left to itself the
    // compiler kept them run-time loops, and a tetrahedron's blocks took a
    // third longer (bench/element_kernels; the same operations in the same
    // order, so the same bits)
#pragma GCC unroll 4
    for(int i = 0; i <= D; ++i) {
      auto n = N[std::size_t(i)];
      const double NN = G[std::size_t(i)][std::size_t(i)];
      SPRING_MOTION_CHECK(NN > 0 && std::isfinite(NN), "ball-vertex springs need facets of non-zero size");
      inverse_NN[std::size_t(i)] = 1.0 / NN;
      double g; // k_i / |N_i|^2, or k_i with n the unit normal
      if(inverse_power > 0 && height_uncapped(power, vexp, NN)) {
        g = weight * inverse_power;
        times_facet_factor(doubled, NN, volume, g);
      } else {
        const double len = std::sqrt(NN);
        for(double& x : n)
          x /= len;
        g = spring_stiffness(volume / len);
      }
      for(int r = 0, m = 0; r < D; ++r)
        for(int q = r; q < D; ++q, ++m)
          knn[std::size_t(i)][std::size_t(m)] = g * n[std::size_t(r)] * n[std::size_t(q)];
    }
    const auto B = sum_blocks<D>(knn, coefficients<D>(G, inverse_NN, 1.0));
    for(int v = 0, pair = 0; v <= D; ++v)
      for(int w = v; w <= D; ++w, ++pair)
        for(int r = 0, m = 0; r < D; ++r)
          for(int q = r; q < D; ++q, ++m)
            out(v, w, r, q, m, pair, B[std::size_t(pair)][std::size_t(m)]);
  }

  // c[i][v]: 1 for v = i, else N_i . N_v / |N_i|^2 (the negated foot
  // coordinate b_v of altitude i)
  template <int D, class T>
  SPRING_MOTION_LANES_STATIC std::array<std::array<T, D + 1>, D + 1> coefficients(
      const std::array<std::array<T, D + 1>, D + 1>& G, const std::array<T, D + 1>& inverse_NN, const T& one)
  {
    std::array<std::array<T, D + 1>, D + 1> c;
    for(std::size_t i = 0; i <= D; ++i)
      for(std::size_t v = 0; v <= D; ++v)
        c[i][v] = v == i ? one : G[i][v] * inverse_NN[i];
    return c;
  }

#if SPRING_MOTION_HAS_DOUBLE_PAIR
  // blocks() on L simplices, one per lane of T (Double_pair, or Double_quad
  // inlined into the four-lane entry point, which is compiled for AVX), its
  // path for capped-free stiffness only: every lane runs blocks()'s
  // operations in its order (sums from 0 in the same order, the same
  // products grouped alike), so each gets the same bits; the tests compare
  // them. Whether all take that path is decided first, lane by lane, by
  // blocks()'s own tests.
  template <int D, class T, std::size_t L>
  SPRING_MOTION_LANES_INLINE bool blocks_in_lanes(
      const std::array<const std::array<std::array<double, D>, D + 1>*, L>& q, const std::array<double*, L>& out) const
  {
    constexpr int S = D * (D + 1) / 2;
    const int doubled = doubled_power(), power = bound_power(doubled);
    if(doubled == 0)
      return false;
    std::array<std::array<T, D>, D + 1> p;
    for(std::size_t v = 0; v <= D; ++v)
      for(std::size_t c = 0; c < D; ++c)
        for(std::size_t l = 0; l < L; ++l)
          p[v][c][l] = (*q[l])[v][c];
    for(const T ee : squared_edges<D>(p)) {
      const auto fits =
          (ee >= internal::lanes_of<T>(min_squared_edge)) & (ee <= internal::lanes_of<T>(max_squared_edge<D>));
      for(std::size_t l = 0; l < L; ++l)
        if(!fits[l])
          return false;
    }
    const auto facets = facet_normals(p);
    const auto& N = facets.normal;
    const auto G = gram<D>(N);
    const T volume = internal::lane_abs(facets.measure);
    for(std::size_t t = 0; t < L; ++t) { // blocks()'s tests for its uncapped path, per lane
      const int vexp = internal::binary_exponent(volume[t]);
      if(!volume_uncapped(power, volume[t], vexp))
        return false;
      for(std::size_t i = 0; i <= D; ++i)
        if(!(G[i][i][t] > 0 && std::isfinite(G[i][i][t]) && height_uncapped(power, vexp, G[i][i][t])))
          return false;
    }
    const T one = internal::lanes_of<T>(1.0);
    T inverse_power;
    inverse_volume_power(doubled, volume, one, inverse_power);
    for(std::size_t t = 0; t < L; ++t)
      if(!(inverse_power[t] > 0))
        return false;
    std::array<std::array<T, S>, D + 1> knn;
    std::array<T, D + 1> inverse_NN;
#pragma GCC unroll 4
    for(std::size_t i = 0; i <= D; ++i) {
      const auto& n = N[i];
      const T NN = G[i][i];
      inverse_NN[i] = one / NN;
      T g = internal::lanes_of<T>(weight) * inverse_power;
      times_facet_factor(doubled, NN, volume, g); // NN > 0 and finite (tested above), so is g
      for(std::size_t r = 0, m = 0; r < D; ++r)
        for(std::size_t c = r; c < D; ++c, ++m)
          knn[i][m] = g * n[r] * n[c];
    }
    constexpr int pairs = (D + 1) * (D + 2) / 2;
    const auto B = sum_blocks<D>(knn, coefficients<D>(G, inverse_NN, one));
    // value j of the flat list (u * S + m) of every lane
    auto at = [&](std::size_t j) -> const T& { return B[j / S][j % S]; };
    constexpr std::size_t n = std::size_t(pairs) * S;
    // a lane with a value that is not finite declines, before anything is
    // stored: the one-element form then reports it (the assembly tests only
    // that form's values)
    internal::Lane_finiteness<T> finiteness;
#pragma GCC unroll 60
    for(std::size_t k = 0; k < n; ++k)
      finiteness.add(at(k));
    for(std::size_t l = 0; l < L; ++l)
      if(!finiteness.finite(l))
        return false;
    std::size_t j = 0;
#pragma GCC unroll 30
    for(; j + L <= n; j += L)
      if constexpr(L == 4)
        internal::store_transposed(at(j), at(j + 1), at(j + 2), at(j + 3), out, j);
      else
        internal::store_transposed(at(j), at(j + 1), out, j);
    for(; j < n; ++j) // in four lanes, the last 2 of 2D's 18 values
      for(std::size_t l = 0; l < L; ++l)
        out[l][j] = at(j)[l];
    return true;
  }
#endif
#if SPRING_MOTION_HAS_DOUBLE_QUAD
#pragma GCC diagnostic pop
#endif

  // K += the whole matrix, each distinct value written to its places
  template <int D>
  void add(const std::array<std::array<double, D>, D + 1>& p, double* K) const
  {
    constexpr int ND = (D + 1) * D;
    blocks<D>(p, [&](int v, int w, int r, int q, int, int, double b) {
      K[(v * D + r) * ND + w * D + q] += b;
      if(q != r)
        K[(v * D + q) * ND + w * D + r] += b;
      if(w != v) {
        K[(w * D + q) * ND + v * D + r] += b;
        if(q != r)
          K[(w * D + r) * ND + v * D + q] += b;
      }
    });
  }
};

} // namespace spring_motion

#endif
