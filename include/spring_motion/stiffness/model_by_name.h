// Copyright (c) 2026 SpringMotion developers.
#ifndef SPRING_MOTION_STIFFNESS_MODEL_BY_NAME_H
#define SPRING_MOTION_STIFFNESS_MODEL_BY_NAME_H

#include <spring_motion/Error.h>
#include <spring_motion/stiffness/Blom_semi_torsional_stiffness.h>
#include <spring_motion/stiffness/Grid_scaled_stiffness.h>
#include <spring_motion/stiffness/Lineal_stiffness.h>
#include <spring_motion/stiffness/Torsional_stiffness.h>
#include <spring_motion/stiffness/Zeng_Ethier_semi_torsional_stiffness.h>

#include <string>
#include <vector>

namespace spring_motion {

/// The model names of the command line and the reports (docs/report_format.md),
/// plus `lineal_p2`: lineal springs with p = 2, the paper's Eq. 1 as printed.
inline const std::vector<std::string>& model_names()
{
  static const std::vector<std::string> names{"lineal", "lineal_p2", "blom", "zeng_ethier", "grid_scaled",
                                              "torsional"};
  return names;
}

/// Calls f(model) (a const lvalue) with the built-in model called `name` (default parameters)
/// and returns what f returns. An unknown name throws, listing the valid ones.
template <class F>
decltype(auto) with_model(const std::string& name, F&& f)
{
  if(name == "lineal")
    {
    const Lineal_stiffness model{};
    return f(model);
  }
  if(name == "lineal_p2")
    {
    const Lineal_stiffness model{2.0};
    return f(model);
  }
  if(name == "blom")
    {
    const Blom_semi_torsional_stiffness model{};
    return f(model);
  }
  if(name == "zeng_ethier")
    {
    const Zeng_Ethier_semi_torsional_stiffness model{};
    return f(model);
  }
  if(name == "grid_scaled")
    {
    const Grid_scaled_stiffness model{};
    return f(model);
  }
  if(name == "torsional")
    {
    const Torsional_stiffness model{};
    return f(model);
  }
  std::string valid;
  for(const auto& n : model_names())
    valid += (valid.empty() ? "" : ", ") + n;
  SPRING_MOTION_CHECK(false, "unknown stiffness model '" << name << "'; valid models: " << valid);
}

} // namespace spring_motion

#endif
