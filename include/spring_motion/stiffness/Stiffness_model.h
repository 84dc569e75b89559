// Copyright (c) 2026 SpringMotion developers.
#ifndef SPRING_MOTION_STIFFNESS_STIFFNESS_MODEL_H
#define SPRING_MOTION_STIFFNESS_STIFFNESS_MODEL_H

#include <array>
#include <cstddef>
#include <cstdint>
#include <cstring>
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
  along_edge,
  /// no edge springs at all (k = 0 on every edge; ball-vertex springs
  /// alone): the element matrices make the whole system, and the assembly
  /// neither computes the edges' stiffness nor adds their zero blocks. Only
  /// for element models: an edge model's system would be empty.
  none
};

/// What a model may need besides the edge itself: the dimension and the
/// longest edge of the initial mesh (the paper's `l0`).
struct Stiffness_context
{
  int dimension = 2;
  double longest_initial_edge = 1;
};

/// The angles around an edge given as 1/sin^2 of each (sin^2 floored at
/// 1e-200, so a flat angle gives 1e200), in the order and of the kind the
/// model's `angle_kind` names. Models whose stiffness reads the angles only
/// through 1/sin^2 take this form: the assembly computes it from cross and
/// dot products, without the trigonometry that computing the angles costs.
struct Inverse_sin_squared
{
  const double* values = nullptr;
  std::size_t size = 0;
  /// How many values from `values` on may be read (their own and whatever
  /// follows them); the assembly sets it, any other caller may leave it 0.
  std::size_t readable = 0;

  /// The width of sum()'s branch-free path.
  static constexpr std::size_t padded_size = 8;

  /// start + values[0] + ... + values[size - 1], added in that order.
  ///
  /// A tetrahedral mesh's edge has 3 to 10 angles, in no pattern the branch
  /// predictor can follow, so a loop over them mispredicts its exit at many
  /// edges. When `padded_size` values are readable and size <= padded_size,
  /// all of them are added instead, those past `size` replaced by +0 through
  /// a bit mask, with no branch: a seventh less time in the 3D edge loop of
  /// the stiffness on the wing (perf samples). s + 0 == s for every s but
  /// -0, and start is never -0 in the models here (0, 1/l), so the sum has
  /// the loop's bits.
  double sum(double start = 0) const
  {
    double s = start;
    if(readable >= padded_size && size <= padded_size) {
      for(std::size_t m = 0; m < padded_size; ++m) {
        std::uint64_t bits;
        std::memcpy(&bits, values + m, sizeof bits);
        bits &= std::uint64_t(0) - std::uint64_t(m < size);
        double v;
        std::memcpy(&v, &bits, sizeof v);
        s += v;
      }
      return s;
    }
    for(std::size_t m = 0; m < size; ++m)
      s += values[m];
    return s;
  }
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
/// // optional: the same stiffness from 1/sin^2 of the angles, which the
/// // assembly then prefers (it never computes the angles themselves)
/// double operator()(double length, Inverse_sin_squared, const Stiffness_context&) const;
/// \endcode
/// Concept `ElementStiffnessModel` (torsional springs, ball-vertex springs)
/// refines it with
/// \code
/// // adds the element's (D+1)D x (D+1)D stiffness matrix (row-major) to K
/// void add_element_matrix(const std::array<std::array<double, D>, D + 1>& p, double* K) const;
/// \endcode
/// and couples the coordinate components: the solver then works on D x D blocks.
/// When every D x D block (v, w) of that matrix is symmetric and equal to
/// block (w, v) (ball-vertex springs), the model may also give only those
/// distinct values, which the assembly then reads instead:
/// \code
/// // adds blocks (v, w), v <= w, in the order (0,0), (0,1), ..., (D,D), each
/// // as its upper triangle by rows (D(D+1)/2 values), to S
/// void add_symmetric_blocks(const std::array<std::array<double, D>, D + 1>& p, double* S) const;
/// \endcode
/// and, as a further option, those values of two elements at once, stored
/// rather than added (false: nothing stored, the assembly then calls the
/// one-element form for each; true only when every value stored is finite,
/// as the assembly tests only the one-element form's values):
/// \code
/// bool symmetric_blocks_of_two(const std::array<std::array<double, D>, D + 1>& p,
///                              const std::array<std::array<double, D>, D + 1>& q, double* S, double* T) const;
/// \endcode
/// and of four (called only on processors with AVX, p[l]'s values in S[l]):
/// \code
/// bool symmetric_blocks_of_four(const std::array<const std::array<std::array<double, D>, D + 1>*, 4>& p,
///                               const std::array<double*, 4>& S) const;
/// \endcode
/// An element model may also say how its edge springs act in that system,
/// or that it has none (default `Edge_spring_form::per_coordinate`):
/// \code
/// Edge_spring_form edge_spring_form() const;
/// \endcode
/// Scaling every stiffness of a model by one constant does not change the motion.

namespace internal {

template <class Model, class = void>
struct Has_description : std::false_type {};
template <class Model>
struct Has_description<Model, std::void_t<decltype(std::declval<const Model&>().description(2))>> : std::true_type {};

template <class Model, class = void>
struct Reads_inverse_sin_squared : std::false_type {};
template <class Model>
struct Reads_inverse_sin_squared<Model, std::void_t<decltype(std::declval<const Model&>()(
                                            1.0, Inverse_sin_squared{}, std::declval<const Stiffness_context&>()))>>
    : std::true_type {};

template <class Model, int D, class = void>
struct Is_element_model : std::false_type {};
template <class Model, int D>
struct Is_element_model<Model, D,
                        std::void_t<decltype(std::declval<const Model&>().add_element_matrix(
                            std::declval<const std::array<std::array<double, D>, D + 1>&>(),
                            std::declval<double*>()))>> : std::true_type {};

template <class Model, int D, class = void>
struct Has_symmetric_blocks : std::false_type {};
template <class Model, int D>
struct Has_symmetric_blocks<Model, D,
                            std::void_t<decltype(std::declval<const Model&>().add_symmetric_blocks(
                                std::declval<const std::array<std::array<double, D>, D + 1>&>(),
                                std::declval<double*>()))>> : std::true_type {};

template <class Model, int D, class = void>
struct Has_symmetric_blocks_of_two : std::false_type {};
template <class Model, int D>
struct Has_symmetric_blocks_of_two<Model, D,
                                   std::void_t<decltype(std::declval<const Model&>().symmetric_blocks_of_two(
                                       std::declval<const std::array<std::array<double, D>, D + 1>&>(),
                                       std::declval<const std::array<std::array<double, D>, D + 1>&>(),
                                       std::declval<double*>(), std::declval<double*>()))>> : std::true_type {};

template <class Model, int D, class = void>
struct Has_symmetric_blocks_of_four : std::false_type {};
template <class Model, int D>
struct Has_symmetric_blocks_of_four<
    Model, D,
    std::void_t<decltype(std::declval<const Model&>().symmetric_blocks_of_four(
        std::declval<const std::array<const std::array<std::array<double, D>, D + 1>*, 4>&>(),
        std::declval<const std::array<double*, 4>&>()))>> : std::true_type {};

template <class Model, class = void>
struct Has_edge_spring_form : std::false_type {};
template <class Model>
struct Has_edge_spring_form<Model, std::void_t<decltype(std::declval<const Model&>().edge_spring_form())>>
    : std::true_type {};

/// A model's stiffness of one edge at one context, for all the edges of a
/// step: `Edge_function<Model> f(model, ctx)`, then `f(length, angles, n)`
/// or, for a model that reads 1/sin^2, `f(length, Inverse_sin_squared)`.
/// The assembly makes one per thread, a local that the loop's stores cannot
/// alias, so that the terms of the context alone (l0 / max_stiffness) are
/// computed once. The model is called through the reference given; a
/// built-in model whose terms depend on its parameters and the context
/// alone specialises this to work them out once (Grid_scaled_stiffness.h)
/// instead of at every edge.
template <class Model>
struct Edge_function
{
  const Model& model;
  const Stiffness_context context;

  Edge_function(const Model& m, const Stiffness_context& ctx) : model(m), context(ctx) {}
  double operator()(double length, const double* angles, std::size_t n) const
  {
    return model(length, angles, n, context);
  }
  template <class M = Model, class = std::enable_if_t<Reads_inverse_sin_squared<M>::value>>
  double operator()(double length, Inverse_sin_squared angles) const
  {
    return model(length, angles, context);
  }
};

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
