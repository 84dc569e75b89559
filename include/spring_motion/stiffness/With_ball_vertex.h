// Copyright (c) 2026 SpringMotion developers.
#ifndef SPRING_MOTION_STIFFNESS_WITH_BALL_VERTEX_H
#define SPRING_MOTION_STIFFNESS_WITH_BALL_VERTEX_H

#include <spring_motion/stiffness/Ball_vertex_stiffness.h>
#include <spring_motion/stiffness/Stiffness_model.h>

#include <array>
#include <cstddef>
#include <type_traits>

namespace spring_motion {

/// An edge model plus ball-vertex springs (name `EDGE+ball_vertex`, e.g.
/// `grid_scaled+ball_vertex`). The edge springs keep the edge model's
/// stiffness but act along their edge (a truss, `k e e^T / |e|^2`), so the
/// whole model is rotation invariant; the ball-vertex springs add what trusses
/// cannot see, an element flattening without any edge getting shorter.
///
/// `ball_vertex.weight` sets the ball-vertex springs' stiffness against the
/// edge springs': with the default 1 and exponent 1 both are 1/length, the
/// same as lineal springs. Models whose k is much larger than 1/l (grid-scaled
/// springs carry lambda = l0/l and an angle term) make the ball-vertex part
/// relatively weaker; raise the weight to compensate.
template <class Edge_model>
struct With_ball_vertex
{
  static_assert(!internal::Is_element_model<Edge_model, 2>::value && !internal::Is_element_model<Edge_model, 3>::value,
                "With_ball_vertex combines an edge model (not an element model) with ball-vertex springs");

  Edge_model edge{};
  Ball_vertex_stiffness ball_vertex{};

  Angle_kind angle_kind(int dimension) const { return edge.angle_kind(dimension); }
  double operator()(double length, const double* angles, std::size_t n, const Stiffness_context& ctx) const
  {
    return edge(length, angles, n, ctx);
  }
  template <class M = Edge_model, class = std::enable_if_t<internal::Reads_inverse_sin_squared<M>::value>>
  double operator()(double length, Inverse_sin_squared angles, const Stiffness_context& ctx) const
  {
    return edge(length, angles, ctx);
  }
  Edge_spring_form edge_spring_form() const { return Edge_spring_form::along_edge; }

  void add_element_matrix(const std::array<std::array<double, 2>, 3>& p, double* K) const
  {
    ball_vertex.add_element_matrix(p, K);
  }
  void add_element_matrix(const std::array<std::array<double, 3>, 4>& p, double* K) const
  {
    ball_vertex.add_element_matrix(p, K);
  }
  void add_symmetric_blocks(const std::array<std::array<double, 2>, 3>& p, double* S) const
  {
    ball_vertex.add_symmetric_blocks(p, S);
  }
  void add_symmetric_blocks(const std::array<std::array<double, 3>, 4>& p, double* S) const
  {
    ball_vertex.add_symmetric_blocks(p, S);
  }

  bool symmetric_blocks_of_two(const std::array<std::array<double, 2>, 3>& p,
                               const std::array<std::array<double, 2>, 3>& q, double* S, double* T) const
  {
    return ball_vertex.symmetric_blocks_of_two(p, q, S, T);
  }
  bool symmetric_blocks_of_two(const std::array<std::array<double, 3>, 4>& p,
                               const std::array<std::array<double, 3>, 4>& q, double* S, double* T) const
  {
    return ball_vertex.symmetric_blocks_of_two(p, q, S, T);
  }
#if SPRING_MOTION_HAS_DOUBLE_QUAD
  bool symmetric_blocks_of_four(const std::array<const std::array<std::array<double, 2>, 3>*, 4>& p,
                                const std::array<double*, 4>& S) const
  {
    return ball_vertex.symmetric_blocks_of_four(p, S);
  }
  bool symmetric_blocks_of_four(const std::array<const std::array<std::array<double, 3>, 4>*, 4>& p,
                                const std::array<double*, 4>& S) const
  {
    return ball_vertex.symmetric_blocks_of_four(p, S);
  }
#endif

  Model_description description(int dimension) const
  {
    Model_description d = internal::describe_model(edge, dimension);
    d.name += "+ball_vertex";
    for(const auto& [name, value] : ball_vertex.description(dimension).parameters)
      d.parameters.emplace_back("ball_vertex_" + name, value);
    return d;
  }
};

namespace internal {

// the edge model's per-step form: the ball-vertex part is no edge stiffness
template <class Edge_model>
struct Edge_function<With_ball_vertex<Edge_model>> : Edge_function<Edge_model>
{
  Edge_function(const With_ball_vertex<Edge_model>& m, const Stiffness_context& ctx)
      : Edge_function<Edge_model>(m.edge, ctx)
  {}
};

} // namespace internal

} // namespace spring_motion

#endif
