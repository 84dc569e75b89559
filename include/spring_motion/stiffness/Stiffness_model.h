// Copyright (c) 2026 SpringMotion developers.
#ifndef SPRING_MOTION_STIFFNESS_STIFFNESS_MODEL_H
#define SPRING_MOTION_STIFFNESS_STIFFNESS_MODEL_H

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

namespace spring_motion {

/// Which angles an edge stiffness model reads.
enum class Angle_kind
{
  none,    ///< length only
  element, ///< the element's own angle at the edge: the facing angle of each
           ///< triangle (2D), the dihedral angle of each tetrahedron (3D)
  face     ///< the angle facing the edge in each triangular face containing it
           ///< (2D: the same as `element`; 3D: Zeng and Ethier's choice)
};

/// How the edge springs of an element model act in its coupled (D x D block)
/// system. Edge models alone always act per coordinate: their system is one
/// scalar Laplacian for all D components.
enum class Edge_spring_form
{
  /// k I: the edge pulls each coordinate separately (the classic lineal
  /// springs of the torsional model). Not rotation invariant.
  per_coordinate,
  /// k e e^T / |e|^2 with e the edge vector: a truss along the edge, which
  /// resists stretching only and is rotation invariant. What an edge model
  /// combined with ball-vertex springs uses.
  along_edge
};

/// What a model may need besides the edge itself: the dimension and the
/// longest edge of the initial mesh (the paper's `l0`).
struct Stiffness_context
{
  int dimension = 2;
  double longest_initial_edge = 1;
};

/// A model's name and numeric parameters, for reports.
struct Model_description
{
  std::string name;
  std::vector<std::pair<std::string, double>> parameters;
};

/// \name Concept `EdgeStiffnessModel`
/// \code
/// Angle_kind angle_kind(int dimension) const;
/// double operator()(double length, const double* angles, std::size_t number_of_angles,
///                   const Stiffness_context&) const;   // >= 0 and finite
/// Model_description description(int dimension) const;               // optional
/// \endcode
/// Concept `ElementStiffnessModel` (torsional springs) refines it with
/// \code
/// // adds the element's (D+1)D x (D+1)D stiffness matrix (row-major) to K
/// void add_element_matrix(const std::array<std::array<double, D>, D + 1>& p, double* K) const;
/// \endcode
/// and couples the coordinate components: the solver then works on D x D blocks.
/// An element model may also say how its edge springs act in that system
/// (default `Edge_spring_form::per_coordinate`):
/// \code
/// Edge_spring_form edge_spring_form() const;
/// \endcode
/// Scaling every stiffness of a model by one constant does not change the motion.

namespace internal {

/// Stiffness values of the built-in models are capped here: large enough to
/// freeze a collapsing element in place, small enough that a vertex's sum of
/// a hundred such springs stays finite.
constexpr double max_stiffness = 1e250;

/// 1/sin^2(theta), with sin^2 floored so an angle of exactly 0 or pi gives the
/// cap instead of infinity. Such an angle means the element is already flat:
/// the validity check rejects that state before its stiffness is ever used,
/// so the floor only guards round-off.
inline double inverse_sin_squared(double theta)
{
  const double s = std::sin(theta);
  return 1.0 / std::max(s * s, 1e-200);
}

inline double cap_stiffness(double k) { return std::min(k, max_stiffness); }

// The capped operations below give min(result, max_stiffness) without ever
// computing an overflowing intermediate (an overflow is an FE_OVERFLOW trap
// under feenableexcept even when the cap would clip it). Within the cap they
// return exactly what the plain operation returns.

/// min(x^e, max_stiffness) for x >= 0.
inline double capped_pow(double x, double e)
{
  if(x == 0)
    return e > 0 ? 0.0 : (e == 0 ? 1.0 : max_stiffness);
  // |log2 x| <= |ilogb x| + 1, so below this bound x^e lies in (2^-800,
  // 2^800), far inside the cap: no log needed, and the models' usual
  // exponents (1 to 4, either sign) are a few products instead of pow
  // (within 2 ulp of it; pow is what stiffness costs most)
  if(std::abs(e) * double(std::abs(std::ilogb(x)) + 1) < 800) {
    const double a = std::abs(e);
    if(a == 1 || a == 2 || a == 3 || a == 4) {
      const double x2 = x * x;
      const double p = a == 1 ? x : a == 2 ? x2 : a == 3 ? x2 * x : x2 * x2;
      return e > 0 ? p : 1.0 / p;
    }
    return std::pow(x, e);
  }
  if(e * std::log(x) >= std::log(max_stiffness))
    return max_stiffness;
  return std::min(std::pow(x, e), max_stiffness);
}
/// min(a / b, max_stiffness) for a >= 0, b > 0.
inline double capped_quotient(double a, double b)
{
  if(a / max_stiffness >= b)
    return max_stiffness;
  return std::min(a / b, max_stiffness);
}
/// min(a b, max_stiffness) for a, b >= 0 and finite.
inline double capped_product(double a, double b)
{
  if(b > 0 && a >= max_stiffness / b)
    return max_stiffness;
  return std::min(a * b, max_stiffness);
}

template <class Model, class = void>
struct Has_description : std::false_type {};
template <class Model>
struct Has_description<Model, std::void_t<decltype(std::declval<const Model&>().description(2))>> : std::true_type {};

template <class Model, int D, class = void>
struct Is_element_model : std::false_type {};
template <class Model, int D>
struct Is_element_model<Model, D,
                        std::void_t<decltype(std::declval<const Model&>().add_element_matrix(
                            std::declval<const std::array<std::array<double, D>, D + 1>&>(),
                            std::declval<double*>()))>> : std::true_type {};

template <class Model, class = void>
struct Has_edge_spring_form : std::false_type {};
template <class Model>
struct Has_edge_spring_form<Model, std::void_t<decltype(std::declval<const Model&>().edge_spring_form())>>
    : std::true_type {};

/// How the edge springs of `model` act in a block system.
template <class Model>
Edge_spring_form edge_spring_form(const Model& model)
{
  if constexpr(Has_edge_spring_form<Model>::value)
    return model.edge_spring_form();
  else
    return Edge_spring_form::per_coordinate;
}

template <class Model>
Model_description describe_model(const Model& model, int dimension)
{
  if constexpr(Has_description<Model>::value)
    return model.description(dimension);
  else
    return Model_description{"custom", {}};
}

} // namespace internal
} // namespace spring_motion

#endif
