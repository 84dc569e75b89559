// Copyright (c) 2026 SpringMotion developers.
#ifndef SPRING_MOTION_STIFFNESS_MODEL_BY_NAME_H
#define SPRING_MOTION_STIFFNESS_MODEL_BY_NAME_H

#include <spring_motion/Error.h>
#include <spring_motion/stiffness/Ball_vertex_stiffness.h>
#include <spring_motion/stiffness/Blom_semi_torsional_stiffness.h>
#include <spring_motion/stiffness/Grid_scaled_stiffness.h>
#include <spring_motion/stiffness/Lineal_stiffness.h>
#include <spring_motion/stiffness/Torsional_stiffness.h>
#include <spring_motion/stiffness/With_ball_vertex.h>
#include <spring_motion/stiffness/Zeng_Ethier_semi_torsional_stiffness.h>

#include <string>
#include <utility>
#include <vector>

namespace spring_motion {

/// One built-in model of the name table: what the command line, the
/// examples and the reports call it, a line for --help, and the dimensions
/// it works in.
struct Model_entry
{
  std::string name;
  std::string summary;
  bool in_2d = true;
  bool in_3d = true;
};

/// The suffix that adds ball-vertex springs to an edge model.
inline const std::string& ball_vertex_suffix()
{
  static const std::string s = "+ball_vertex";
  return s;
}

/// The one table of built-in model names, in the order of --help and of the
/// demos' tables: the edge models, the element models, then every edge model
/// plus ball-vertex springs (`EDGE+ball_vertex`).
inline const std::vector<Model_entry>& model_table()
{
  static const std::vector<Model_entry> table = [] {
    std::vector<Model_entry> t{
        {"lineal", "lineal springs, k = 1/l (Batina)"},
        {"lineal_p2", "lineal springs, k = 1/l^2 (the paper's Eq. 1 as printed)"},
        {"blom", "semi-torsional springs, k = (1/l) sum 1/theta (Blom)"},
        {"zeng_ethier", "semi-torsional springs, k = 1/l + sum 1/sin^2 theta (Zeng and Ethier)"},
        {"grid_scaled", "the paper's grid-scaled springs, k = (l0/l)(1/l^alpha + (sum 1/sin^2 theta)^beta)"},
        {"torsional", "lineal springs plus torsion springs 1/sin^2 theta at element angles (Farhat; Degand and Farhat in 3D)"},
        {"ball_vertex", "ball-vertex springs only: each vertex tied to its facing facet along the altitude, k = 1/h (Bottasso)"},
        {"ball_vertex_p2", "ball-vertex springs with k = 1/h^2: short altitudes, flattening elements, stiffen faster"},
        {"ball_vertex_p2.5", "ball-vertex springs with k = 1/h^2.5, between the second and the third power"},
        {"ball_vertex_p3", "ball-vertex springs with k = 1/h^3: the elements next to the body stay closer to rigid"}};
    const std::size_t edge_models = 5;
    for(std::size_t m = 0; m < edge_models; ++m)
      t.push_back({t[m].name + ball_vertex_suffix(), t[m].name + " springs acting along their edges, plus ball-vertex springs"});
    return t;
  }();
  return table;
}

/// The names of model_table(), in its order.
inline const std::vector<std::string>& model_names()
{
  static const std::vector<std::string> names = [] {
    std::vector<std::string> n;
    for(const auto& e : model_table())
      n.push_back(e.name);
    return n;
  }();
  return names;
}

/// The names of the models that work in `dimension` (2 or 3).
inline std::vector<std::string> model_names(int dimension)
{
  std::vector<std::string> n;
  for(const auto& e : model_table())
    if(dimension == 2 ? e.in_2d : e.in_3d)
      n.push_back(e.name);
  return n;
}

namespace internal {

inline std::string comma_list(const std::vector<std::string>& names)
{
  std::string s;
  for(const auto& n : names)
    s += (s.empty() ? "" : ", ") + n;
  return s;
}

template <class F>
decltype(auto) with_edge_model(const std::string& name, F&& f)
{
  if(name == "lineal") {
    const Lineal_stiffness model{};
    return f(model);
  }
  if(name == "lineal_p2") {
    const Lineal_stiffness model{2.0};
    return f(model);
  }
  if(name == "blom") {
    const Blom_semi_torsional_stiffness model{};
    return f(model);
  }
  if(name == "zeng_ethier") {
    const Zeng_Ethier_semi_torsional_stiffness model{};
    return f(model);
  }
  SPRING_MOTION_CHECK(name == "grid_scaled", "not an edge model: '" << name << "'");
  const Grid_scaled_stiffness model{};
  return f(model);
}

inline bool is_edge_model_name(const std::string& name)
{
  return name == "lineal" || name == "lineal_p2" || name == "blom" || name == "zeng_ethier" || name == "grid_scaled";
}

} // namespace internal

/// Throws unless `name` is in the table and works in `dimension` (2 or 3; 0:
/// either). The message lists the valid names.
inline void check_model_name(const std::string& name, int dimension = 0)
{
  const auto& s = ball_vertex_suffix();
  if(name.size() > s.size() && name.compare(name.size() - s.size(), s.size(), s) == 0) {
    const std::string base = name.substr(0, name.size() - s.size());
    SPRING_MOTION_CHECK(internal::is_edge_model_name(base),
                        "stiffness model '" << name << "': ball-vertex springs combine with an edge model only ('"
                                            << base << "' is not one); valid models: "
                                            << internal::comma_list(model_names()));
  }
  for(const auto& e : model_table())
    if(e.name == name) {
      SPRING_MOTION_CHECK(dimension == 0 || (dimension == 2 ? e.in_2d : e.in_3d),
                          "stiffness model '" << name << "' does not work in " << dimension
                                              << "D; valid models: " << internal::comma_list(model_names(dimension)));
      return;
    }
  SPRING_MOTION_CHECK(false, "unknown stiffness model '" << name << "'; valid models: "
                                                         << internal::comma_list(model_names()));
}

/// Calls f(model) (a const lvalue) with the built-in model called `name`
/// (default parameters) and returns what f returns. A name not in
/// model_table() throws, listing the valid ones.
template <class F>
decltype(auto) with_model(const std::string& name, F&& f)
{
  check_model_name(name);
  if(name == "torsional") {
    const Torsional_stiffness model{};
    return f(model);
  }
  if(name == "ball_vertex") {
    const Ball_vertex_stiffness model{};
    return f(model);
  }
  if(name == "ball_vertex_p2") {
    const Ball_vertex_stiffness model{2.0};
    return f(model);
  }
  if(name == "ball_vertex_p2.5") {
    const Ball_vertex_stiffness model{2.5};
    return f(model);
  }
  if(name == "ball_vertex_p3") {
    const Ball_vertex_stiffness model{3.0};
    return f(model);
  }
  const auto& s = ball_vertex_suffix();
  if(name.size() > s.size() && name.compare(name.size() - s.size(), s.size(), s) == 0)
    return internal::with_edge_model(name.substr(0, name.size() - s.size()), [&](const auto& edge) -> decltype(auto) {
      const With_ball_vertex<std::decay_t<decltype(edge)>> model{edge, {}};
      return f(model);
    });
  return internal::with_edge_model(name, f);
}

} // namespace spring_motion

#endif
