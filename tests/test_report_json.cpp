// The JSON report (docs/report_format.md): written by write_report_json,
// read back here with nlohmann-json, every field equal to the Deform_report
// it was written from; a run that stops at an inverted step reports it.
#include <spring_motion/spring_motion.h>

#include "test_meshes.h"

#include <catch2/catch.hpp>
#include <nlohmann/json.hpp>

#include <cmath>
#include <sstream>

using namespace spring_motion;
using namespace spring_motion_test;
using Json = nlohmann::json;

namespace {

Json written(const Deform_report& r)
{
  std::ostringstream out;
  write_report_json(r, out);
  return Json::parse(out.str());
}

// A finite number as written, or null when it is not finite.
void check_number(const Json& j, double v)
{
  if(std::isfinite(v)) {
    REQUIRE(j.is_number());
    CHECK(j.get<double>() == v); // written to round-trip exactly
  } else
    CHECK(j.is_null());
}

void check_histogram(const Json& j, const Skewness_histogram& h)
{
  REQUIRE(j["histogram"].size() == h.fractions.size());
  for(std::size_t i = 0; i < h.fractions.size(); ++i)
    check_number(j["histogram"][i], h.fractions[i]);
  CHECK(j["count"].get<std::size_t>() == h.count);
  check_number(j["mean"], h.mean);
  check_number(j["max"], h.max);
}

void check_report(const Json& j, const Deform_report& r)
{
  CHECK(j["format"] == "spring_motion.report/1");
  CHECK(j["mesh"]["dimension"].get<int>() == r.dimension);
  CHECK(j["mesh"]["vertices"].get<std::size_t>() == r.vertices);
  CHECK(j["mesh"]["elements"].get<std::size_t>() == r.elements);
  CHECK(j["mesh"]["moving_vertices"].get<std::size_t>() == r.moving_vertices);
  CHECK(j["mesh"]["fixed_vertices"].get<std::size_t>() == r.fixed_vertices);
  CHECK(j["model"]["name"] == r.model.name);
  CHECK(j["model"]["parameters"].size() == r.model.parameters.size());
  for(const auto& [name, value] : r.model.parameters)
    check_number(j["model"]["parameters"][name], value);
  CHECK(j["motion"]["kind"] == r.motion.kind);
  check_number(j["motion"]["amplitude_deg"], r.motion.amplitude_deg);
  CHECK(j["motion"]["steps"].get<std::size_t>() == r.number_of_steps);
  for(int c = 0; c < 3; ++c) {
    check_number(j["motion"]["center"][c], r.motion.center[c]);
    check_number(j["motion"]["axis"][c], r.motion.axis[c]);
    check_number(j["motion"]["displacement"][c], r.motion.displacement[c]);
  }
  const Json& s = j["solver"];
  const Solver_options& o = r.solver;
  CHECK(s["name"] == (o.method == Solver_method::sor ? "sor" : "conjugate_gradient"));
  CHECK(s["preconditioner"] == (o.method == Solver_method::sor                  ? "none"
                                : o.preconditioner == Preconditioner::multigrid ? "multigrid"
                                                                                : "symmetric_gauss_seidel"));
  CHECK(s["stopping"] == (o.stopping == Stopping_rule::max_update ? "max_update" : "error_estimate"));
  check_number(s["relaxation_factor"], o.relaxation_factor);
  check_number(s["preconditioner_relaxation_factor"], o.preconditioner_relaxation_factor);
  check_number(s["tolerance"], o.tolerance);
  CHECK(s["max_iterations"].get<std::size_t>() == o.max_iterations);
  CHECK(s["warm_start"].get<bool>() == o.warm_start);
  CHECK(s["extrapolate"].get<bool>() == o.extrapolate);
  CHECK(s["ordering"] == (o.ordering == Vertex_ordering::natural       ? "natural"
                          : o.ordering == Vertex_ordering::multicolour ? "multicolour"
                                                                       : "block_multicolour"));
  CHECK(s["threads"].get<int>() == o.threads);
  CHECK(s["block_rows"].get<std::size_t>() == o.block_rows);
  check_number(s["multigrid_strength"], o.multigrid_strength);
  check_number(s["multigrid_correction"], o.multigrid_correction);
  CHECK(s["multigrid_coarsest_rows"].get<std::size_t>() == o.multigrid_coarsest_rows);
  CHECK(s["multigrid_max_direct_rows"].get<std::size_t>() == o.multigrid_max_direct_rows);
  CHECK(s["multigrid_coarse_interval"].get<std::size_t>() == o.multigrid_coarse_interval);
  CHECK(s["multigrid_first_level_cycles"].get<std::size_t>() == o.multigrid_first_level_cycles);
  REQUIRE(j["steps"].size() == r.steps.size());
  for(std::size_t i = 0; i < r.steps.size(); ++i) {
    const Json& js = j["steps"][i];
    const Step_report& st = r.steps[i];
    CHECK(js["step"].get<std::size_t>() == st.step);
    check_number(js["fraction"], st.fraction);
    check_number(js["angle_deg"], st.angle_deg);
    CHECK(js["iterations"].get<std::size_t>() == st.iterations);
    CHECK(js["converged"].get<bool>() == st.converged);
    check_number(js["max_update"], st.max_update);
    check_number(js["residual"], st.residual);
    check_number(js["error_estimate"], st.error_estimate);
    CHECK(js["substeps"].get<std::size_t>() == st.substeps);
    CHECK(js["inverted"].get<std::size_t>() == st.inverted);
    CHECK(js["rejected_attempts"].get<std::size_t>() == st.rejected_attempts);
    check_number(js["min_size_ratio"], st.min_size_ratio);
    check_number(js["max_size_ratio"], st.max_size_ratio);
    check_number(js["max_skewness_moving"], st.max_skewness_moving);
    check_number(js["max_skewness_all"], st.max_skewness_all);
    check_number(js["min_angle_deg_moving"], st.min_angle_deg_moving);
    check_number(js["min_angle_deg_all"], st.min_angle_deg_all);
    check_number(js["seconds"]["stiffness"], st.seconds_stiffness);
    check_number(js["seconds"]["solve"], st.seconds_solve);
    check_number(js["seconds"]["check"], st.seconds_check);
  }
  CHECK(j["completed"].get<bool>() == r.completed);
  CHECK(j["converged"].get<bool>() == r.converged);
  if(r.first_invalid) {
    const Json& f = j["first_invalid"];
    CHECK(f["step"].get<std::size_t>() == r.first_invalid->step);
    check_number(f["fraction"], r.first_invalid->fraction);
    check_number(f["angle_deg"], r.first_invalid->angle_deg);
    CHECK(f["elements"].get<std::vector<std::size_t>>() == r.first_invalid->elements);
  } else
    CHECK(j["first_invalid"].is_null());
  check_number(j["final_fraction"], r.final_fraction);
  check_number(j["final_angle_deg"], r.final_angle_deg);
  check_number(j["min_size_ratio"], r.min_size_ratio);
  check_number(j["max_size_ratio"], r.max_size_ratio);
  check_histogram(j["quality"]["moving_boundary"], r.quality_moving);
  check_histogram(j["quality"]["all"], r.quality_all);
  check_number(j["quality"]["moving_boundary"]["min_angle_deg"], r.min_angle_deg_moving);
  check_number(j["quality"]["all"]["min_angle_deg"], r.min_angle_deg_all);
  CHECK(j["options"]["max_substep_halvings"].get<std::size_t>() == r.max_substep_halvings);
  CHECK(j["options"]["quality_every_step"].get<bool>() == r.quality_every_step);
  check_number(j["seconds_total"], r.seconds_total);
}

} // namespace

TEST_CASE("write_report_json: a completed pitch run reads back field by field", "[report]")
{
  CDT cdt;
  make_square_with_hole(cdt);
  const auto hole_moves = [](const Vertex_info<2>& v) {
    // the hole is the square |x|, |y| <= 0.5; the outer boundary |x|, |y| = 2
    return std::abs(v.point[0]) < 0.6 && std::abs(v.point[1]) < 0.6 && v.on_boundary ? Vertex_role::moving : Vertex_role::fixed;
  };
  Deform_options options;
  options.number_of_steps = 3;
  options.solver.preconditioner = Preconditioner::symmetric_gauss_seidel;
  options.solver.ordering = Vertex_ordering::natural;
  options.solver.threads = 1;
  // settings other than the defaults, so the check below cannot pass on defaults
  options.solver.block_rows = 300;
  options.solver.multigrid_strength = 0.03;
  options.solver.multigrid_correction = 1.1;
  options.solver.multigrid_coarsest_rows = 32;
  options.solver.multigrid_max_direct_rows = 128;
  options.solver.multigrid_coarse_interval = 3;
  options.solver.multigrid_first_level_cycles = 2;
  const auto report = deform(cdt, hole_moves, Pitch_motion<2>(10.0, {0.0, 0.0}), Zeng_Ethier_semi_torsional_stiffness{},
                             options);
  REQUIRE(report.completed);
  REQUIRE(report.moving_vertices > 0);
  const Json j = written(report);
  check_report(j, report);
  CHECK(j["solver"]["ordering"] == "natural");
  CHECK(j["solver"]["preconditioner"] == "symmetric_gauss_seidel");
  CHECK(j["first_invalid"].is_null());
  CHECK(j["motion"]["kind"] == "pitch");
  CHECK(j["solver"]["block_rows"] == 300);
  CHECK(j["solver"]["multigrid_strength"] == 0.03);
  CHECK(j["solver"]["multigrid_correction"] == 1.1);
  CHECK(j["solver"]["multigrid_coarsest_rows"] == 32);
  CHECK(j["solver"]["multigrid_max_direct_rows"] == 128);
  CHECK(j["solver"]["multigrid_coarse_interval"] == 3);
  CHECK(j["solver"]["multigrid_first_level_cycles"] == 2);
}

TEST_CASE("write_report_json: a stopped run reports its first invalid step, non-finite values as null",
          "[report]")
{
  CDT cdt;
  make_square_with_hole(cdt);
  const auto hole_moves = [](const Vertex_info<2>& v) {
    return std::abs(v.point[0]) < 0.6 && std::abs(v.point[1]) < 0.6 && v.on_boundary ? Vertex_role::moving : Vertex_role::fixed;
  };
  Deform_options options;
  options.number_of_steps = 2;
  options.solver = Solver_options::paper();
  options.max_substep_halvings = 2;
  // a translation far beyond the gap to the outer boundary must invert elements
  const auto report = deform(cdt, hole_moves, Translation_motion<2>{{2.0, 0.0}}, Lineal_stiffness{}, options);
  REQUIRE_FALSE(report.completed);
  REQUIRE(report.first_invalid);
  const Json j = written(report);
  check_report(j, report);
  CHECK(j["options"]["max_substep_halvings"] == 2); // the run's options, so that it can be reproduced
  CHECK(j["solver"]["name"] == "sor");
  CHECK(j["solver"]["preconditioner"] == "none");
  CHECK(j["final_angle_deg"].is_null()); // a translation has no angle
  CHECK_FALSE(j["first_invalid"]["elements"].empty());
  // the failed step was tried whole, as 2 and as 4 substeps: two attempts
  // rejected before the last one, which failed too
  CHECK(j["steps"].back()["rejected_attempts"] == 2);
  CHECK(j["steps"].back()["substeps"] == 4);
}
