// Copyright (c) 2026 SpringMotion developers.
// The JSON report of a run (docs/report_format.md), written with nlohmann-json.
#include <spring_motion/Deform_report.h>
#include <spring_motion/Error.h>

#include <nlohmann/json.hpp>

#include <cmath>
#include <cstdio>
#include <fstream>
#include <ostream>
#include <string>

namespace spring_motion {
namespace {

// Fields in the order docs/report_format.md lists them.
using Json = nlohmann::ordered_json;

// JSON has no NaN or infinity: a value that is not finite (an angle of a
// motion without one, for instance) is written as null.
Json number(double v) { return std::isfinite(v) ? Json(v) : Json(nullptr); }

template <class Range>
Json numbers(const Range& values)
{
  Json a = Json::array();
  for(const auto& v : values)
    a.push_back(number(double(v)));
  return a;
}

Json histogram(const Skewness_histogram& h)
{
  return Json{{"histogram", numbers(h.fractions)}, {"count", h.count}, {"mean", number(h.mean)}, {"max", number(h.max)}};
}

const char* method_name(Solver_method m) { return m == Solver_method::sor ? "sor" : "conjugate_gradient"; }

const char* preconditioner_name(const Solver_options& o)
{
  if(o.method == Solver_method::sor)
    return "none";
  return o.preconditioner == Preconditioner::multigrid ? "multigrid" : "symmetric_gauss_seidel";
}

const char* ordering_name(Vertex_ordering o)
{
  switch(o) {
  case Vertex_ordering::multicolour: return "multicolour";
  case Vertex_ordering::natural: return "natural";
  case Vertex_ordering::block_multicolour: return "block_multicolour";
  }
  return "unknown";
}

// Every field of Solver_options. Fields added to Solver_options are added
// here (and to docs/report_format.md), after the existing ones: readers of
// format 1 ignore fields they do not know.
Json solver(const Solver_options& o)
{
  Json s;
  s["name"] = method_name(o.method);
  s["preconditioner"] = preconditioner_name(o);
  s["stopping"] = o.stopping == Stopping_rule::max_update ? "max_update" : "error_estimate";
  s["relaxation_factor"] = number(o.relaxation_factor);
  s["tolerance"] = number(o.tolerance);
  s["max_iterations"] = o.max_iterations;
  s["warm_start"] = o.warm_start;
  s["preconditioner_relaxation_factor"] = number(o.preconditioner_relaxation_factor);
  s["extrapolate"] = o.extrapolate;
  s["ordering"] = ordering_name(o.ordering);
  s["threads"] = o.threads;
  s["block_rows"] = o.block_rows;
  s["multigrid_strength"] = number(o.multigrid_strength);
  s["multigrid_correction"] = number(o.multigrid_correction);
  s["multigrid_coarsest_rows"] = o.multigrid_coarsest_rows;
  s["multigrid_max_direct_rows"] = o.multigrid_max_direct_rows;
  s["multigrid_coarse_interval"] = o.multigrid_coarse_interval;
  s["multigrid_first_level_cycles"] = o.multigrid_first_level_cycles;
  return s;
}

Json step(const Step_report& s)
{
  Json j;
  j["step"] = s.step;
  j["fraction"] = number(s.fraction);
  j["angle_deg"] = number(s.angle_deg);
  j["iterations"] = s.iterations;
  j["converged"] = s.converged;
  j["max_update"] = number(s.max_update);
  j["residual"] = number(s.residual);
  j["error_estimate"] = number(s.error_estimate);
  j["substeps"] = s.substeps;
  j["inverted"] = s.inverted;
  j["rejected_attempts"] = s.rejected_attempts;
  j["threads"] = s.threads;
  j["min_size_ratio"] = number(s.min_size_ratio);
  j["max_size_ratio"] = number(s.max_size_ratio);
  j["max_skewness_moving"] = number(s.max_skewness_moving);
  j["max_skewness_all"] = number(s.max_skewness_all);
  j["min_angle_deg_moving"] = number(s.min_angle_deg_moving);
  j["min_angle_deg_all"] = number(s.min_angle_deg_all);
  j["seconds"] = Json{{"stiffness", number(s.seconds_stiffness)},
                      {"solve", number(s.seconds_solve)},
                      {"check", number(s.seconds_check)}};
  return j;
}

} // namespace

void write_report_json(const Deform_report& r, std::ostream& out)
{
  Json j;
  j["format"] = "spring_motion.report/1";
  j["backend"] = Json{{"name", r.backend}, {"ranks", r.ranks}};
  if(!r.rank_seconds_solve.empty()) {
    j["backend"]["seconds_solve_per_rank"] = numbers(r.rank_seconds_solve);
    j["backend"]["seconds_total_per_rank"] = numbers(r.rank_seconds_total);
    if(!r.rank_peak_mib.empty())
      j["backend"]["peak_mib_per_rank"] = numbers(r.rank_peak_mib);
  }
  j["mesh"] = Json{{"dimension", r.dimension},
                   {"vertices", r.vertices},
                   {"elements", r.elements},
                   {"moving_vertices", r.moving_vertices},
                   {"fixed_vertices", r.fixed_vertices},
                   {"sliding_vertices", r.sliding_vertices}};
  Json parameters = Json::object();
  for(const auto& [name, value] : r.model.parameters)
    parameters[name] = number(value);
  j["model"] = Json{{"name", r.model.name}, {"parameters", parameters}};
  const auto& m = r.motion;
  j["motion"] = Json{{"kind", m.kind},
                     {"amplitude_deg", number(m.amplitude_deg)},
                     {"mean_angle_deg", number(m.mean_angle_deg)},
                     {"steps", r.number_of_steps},
                     {"center", numbers(m.center)},
                     {"axis", numbers(m.axis)},
                     {"displacement", numbers(m.displacement)}};
  j["solver"] = solver(r.solver);
  j["options"] = Json{{"max_substep_halvings", r.max_substep_halvings},
                      {"quality_every_step", r.quality_every_step}};
  j["steps"] = Json::array();
  for(const auto& s : r.steps)
    j["steps"].push_back(step(s));
  j["completed"] = r.completed;
  j["converged"] = r.converged;
  if(r.first_invalid) {
    const auto& f = *r.first_invalid;
    j["first_invalid"] = Json{{"step", f.step},
                              {"fraction", number(f.fraction)},
                              {"angle_deg", number(f.angle_deg)},
                              {"elements", f.elements}};
  } else
    j["first_invalid"] = nullptr;
  j["final_fraction"] = number(r.final_fraction);
  j["final_angle_deg"] = number(r.final_angle_deg);
  j["min_size_ratio"] = number(r.min_size_ratio);
  j["max_size_ratio"] = number(r.max_size_ratio);
  Json moving = histogram(r.quality_moving), all = histogram(r.quality_all);
  moving["min_angle_deg"] = number(r.min_angle_deg_moving);
  all["min_angle_deg"] = number(r.min_angle_deg_all);
  j["quality"] = Json{{"moving_boundary", moving}, {"all", all}};
  j["seconds_total"] = number(r.seconds_total);
  out << j.dump(2) << "\n";
}

void write_report_json(const Deform_report& report, const std::string& path)
{
  const std::string tmp = path + ".tmp";
  {
    std::ofstream f(tmp);
    SPRING_MOTION_CHECK(f, "cannot open " << tmp << " for writing");
    write_report_json(report, f);
    f.close();
    if(!f) {
      std::remove(tmp.c_str());
      SPRING_MOTION_CHECK(false, "writing " << tmp << " failed");
    }
  }
  if(std::rename(tmp.c_str(), path.c_str()) != 0) {
    std::remove(tmp.c_str());
    SPRING_MOTION_CHECK(false, "cannot rename " << tmp << " to " << path);
  }
}

} // namespace spring_motion
