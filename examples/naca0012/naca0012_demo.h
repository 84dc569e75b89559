// What examples/naca0012_pitch_2d.cpp and examples/naca0012_wing_3d.cpp
// share: the options both take, the results table with its reports, and the
// search for each model's largest amplitude. The mesh, the motion and the
// choice of models stay in each example.
#ifndef SPRING_MOTION_EXAMPLES_NACA0012_DEMO_H
#define SPRING_MOTION_EXAMPLES_NACA0012_DEMO_H

#include <spring_motion/spring_motion.h>
#include <spring_motion/io/network_output.h>

#include <CLI/CLI.hpp>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <functional>
#include <iostream>
#include <string>
#include <vector>

namespace naca0012_demo {

namespace sm = spring_motion;

struct Options
{
  std::string program; // names the example in its error messages
  double amplitude = 0;
  std::size_t steps = 100;
  std::string report_dir;
  bool max_amplitude = false;
  bool paper_solver = false;            // SOR stopped by the paper's Eq. 12
  std::size_t max_substep_halvings = 0; // Deform_options::max_substep_halvings
  std::vector<std::string> models;

  sm::Deform_options deform_options() const
  {
    sm::Deform_options options;
    options.number_of_steps = steps;
    if(paper_solver)
      options.solver = sm::Solver_options::paper();
    options.max_substep_halvings = max_substep_halvings;
    return options;
  }

  const char* solver_description() const
  {
    return paper_solver ? "SOR, stop when max change <= 5e-6 (the paper's Eq. 12)"
                        : "conjugate gradients + multigrid V-cycle, stop when estimated error <= 1e-6";
  }
};

// Declares the options both demos take on `app`; an example adds its own
// before parsing (CLI11 writes the --help text from these declarations).
inline void add_options(CLI::App& app, Options& o)
{
  app.add_option("--amplitude", o.amplitude, "pitch amplitude alpha_m in degrees (both signs are run)")
      ->capture_default_str();
  app.add_option("--steps", o.steps, "number of steps n")->capture_default_str()->check(CLI::PositiveNumber);
  app.add_option("--report-dir", o.report_dir, "write <model>_pos/_neg.json and .vtu per run into DIR")
      ->type_name("DIR");
  app.add_flag("--max-amplitude", o.max_amplitude, "find each model's largest amplitude by bisection");
  app.add_option("--max-substep-halvings", o.max_substep_halvings,
                 "retry an inverting step as up to 2^K substeps (0: the paper's method)")
      ->capture_default_str()
      ->type_name("K");
  app.add_option_function<std::string>(
         "--solver", [&o](const std::string& v) { o.paper_solver = v == "paper"; },
         "default: CG + multigrid to an estimated error of 1e-6; paper: SOR stopped by the paper's Eq. 12")
      ->check(CLI::IsMember({"default", "paper"}));
  app.add_option("--models", o.models, "comma-separated stiffness models to run")
      ->delimiter(',')
      ->type_name("a,b,...")
      ->capture_default_str();
}

inline std::size_t number_of_moving(const std::vector<sm::Vertex_role>& roles)
{
  return std::size_t(std::count(roles.begin(), roles.end(), sm::Vertex_role::moving));
}

inline std::string histogram(const sm::Skewness_histogram& h)
{
  std::string s;
  for(double f : h.fractions) {
    char b[8];
    std::snprintf(b, sizeof b, "%3.0f", 100 * f);
    s += b;
  }
  return s;
}

// One example's runs: its network, and how it pitches one model to one
// amplitude (in degrees, signed) on the deformer it is given.
template <int D>
struct Pitch_demo
{
  using Pitch = std::function<sm::Deform_report(const std::string& model, double amplitude,
                                                sm::Network_deformer<D>& deformer)>;
  using After_run = std::function<void(const std::string& model, double sign, const sm::Deform_report& report,
                                       const sm::Network_deformer<D>& final_state)>;

  const sm::Spring_network<D>& net;
  const std::vector<sm::Vertex_role>& roles;
  const Options& options;
  Pitch pitch;
  int model_width; // of the table's first column, wide enough for the longest name
  int ms_decimals; // of its last column: 3D steps take hundreds of ms

  sm::Deform_report run(const std::string& model, double amplitude) const
  {
    sm::Network_deformer<D> deformer(net, roles);
    return pitch(model, amplitude, deformer);
  }
};

// The table's head and its row for the undeformed mesh, whose histogram it
// returns (the 3D example also saves it for the figures).
template <int D>
sm::Skewness_histogram print_original(const Pitch_demo<D>& d)
{
  std::printf("%-*s %4s %4s %16s %8s %6s  %-30s %8s %9s %11s %8s\n", d.model_width, "model", "dir", "done",
              "first_invalid", "last_deg", "R_max", "R histogram 0..1 (%)", "min_size", "min_angle", "sweeps",
              "ms/step");
  sm::Network_deformer<D> original(d.net, d.roles);
  std::vector<double> angle;
  const auto r = sm::element_skewness(d.net, original.positions(), 0, &angle);
  const auto h = sm::skewness_histogram(r, [&](std::size_t t) { return original.touches_moving(t); });
  double min_angle = 180;
  for(std::size_t t = 0; t < angle.size(); ++t)
    if(original.touches_moving(t))
      min_angle = std::min(min_angle, angle[t]);
  std::printf("%-*s %4s %4s %16s %8.2f %6.3f  %-30s %8.3f %9.2f %11s %8s\n", d.model_width, "original", "", "", "",
              0.0, h.max, histogram(h).c_str(), 1.0, min_angle, "", "");
  std::fflush(stdout);
  return h;
}

// Pitches every model both ways at the chosen amplitude and prints a row per
// run; with a report folder, writes <model>_pos.json/.vtu and _neg. Then
// `after_run(model, sign, report, final_state)`, if given: the final state is
// the last valid one when the run stopped early.
template <int D>
void run_models(const Pitch_demo<D>& d, const typename Pitch_demo<D>::After_run& after_run = nullptr)
{
  for(const auto& model : d.options.models) {
    for(const double sign : {+1.0, -1.0}) {
      sm::Network_deformer<D> final_state(d.net, d.roles);
      const auto r = d.pitch(model, sign * d.options.amplitude, final_state);
      std::size_t total = 0, most = 0;
      for(const auto& s : r.steps) {
        total += s.iterations;
        most = std::max(most, s.iterations);
      }
      char invalid[32] = "-";
      if(r.first_invalid)
        std::snprintf(invalid, sizeof invalid, "%zu (%.1f deg)", r.first_invalid->step, r.first_invalid->angle_deg);
      char sweeps[32];
      std::snprintf(sweeps, sizeof sweeps, "%.0f/%zu", double(total) / double(r.steps.size()), most);
      std::printf("%-*s %4s %4s %16s %8.2f %6.3f  %-30s %8.3f %9.2f %11s %8.*f\n", d.model_width, model.c_str(),
                  sign > 0 ? "+" : "-", r.completed ? "yes" : "no", invalid, r.final_angle_deg,
                  r.quality_moving.max, histogram(r.quality_moving).c_str(), r.min_size_ratio,
                  r.min_angle_deg_moving, sweeps, d.ms_decimals, 1000 * r.seconds_total / double(r.steps.size()));
      std::fflush(stdout);
      if(after_run)
        after_run(model, sign, r, final_state);
      if(!d.options.report_dir.empty()) {
        const std::string base = d.options.report_dir + "/" + model + (sign > 0 ? "_pos" : "_neg");
        sm::write_report_json(r, base + ".json");
        std::vector<sm::Data_array> point_data, cell_data;
        sm::motion_data_arrays(d.net, final_state.positions(), final_state.orientation_record(), point_data,
                               cell_data);
        sm::write_vtu(sm::make_indexed_mesh(d.net, final_state.positions()), base + ".vtu", point_data, cell_data);
      }
    }
  }
}

// The undeformed mesh as original.vtu, for the figures' "original" panels.
template <int D>
void write_original_vtu(const Pitch_demo<D>& d)
{
  if(d.options.report_dir.empty())
    return;
  sm::Network_deformer<D> original(d.net, d.roles);
  std::vector<sm::Data_array> point_data, cell_data;
  sm::motion_data_arrays(d.net, original.positions(), original.orientation_record(), point_data, cell_data);
  sm::write_vtu(sm::make_indexed_mesh(d.net, original.positions()), d.options.report_dir + "/original.vtu",
                point_data, cell_data);
}

// Largest amplitude in [0, up_to] whose run completes, by bisection to
// `resolution` degrees; `sign` picks the direction.
template <int D>
double largest_amplitude(const Pitch_demo<D>& d, const std::string& model, double sign, double up_to,
                         double resolution)
{
  double lo = 0, hi = up_to;
  if(d.run(model, sign * hi).completed)
    return hi;
  while(hi - lo > resolution) {
    const double mid = 0.5 * (lo + hi);
    (d.run(model, sign * mid).completed ? lo : hi) = mid;
  }
  return lo;
}

// With --max-amplitude, prints each model's largest amplitude both ways
// and, with a report folder, saves them as max_amplitude.json, written under
// another name and then renamed so that a run stopped part way never leaves a
// truncated file for the scripts that read it. False if it cannot be written.
template <int D>
bool print_largest_amplitudes(const Pitch_demo<D>& d, double up_to, double resolution)
{
  const Options& o = d.options;
  if(!o.max_amplitude)
    return true;
  std::printf("\nlargest amplitude whose %zu-step run completes (bisection to %g deg, up to %g):\n", o.steps,
              resolution, up_to);
  std::printf("%-*s %10s %10s\n", d.model_width, "model", "positive", "negative");
  char head[128];
  std::snprintf(head, sizeof head, "{ \"format\": \"spring_motion.max_amplitude/1\", \"steps\": %zu, "
                "\"resolution_deg\": %g, \"models\": {", o.steps, resolution);
  std::string json = head;
  for(std::size_t k = 0; k < o.models.size(); ++k) {
    const auto& model = o.models[k];
    const double pos = largest_amplitude(d, model, +1, up_to, resolution);
    const double neg = largest_amplitude(d, model, -1, up_to, resolution);
    std::printf("%-*s %10.1f %10.1f\n", d.model_width, model.c_str(), pos, neg);
    std::fflush(stdout);
    char entry[160];
    std::snprintf(entry, sizeof entry, "%s \"%s\": { \"positive_deg\": %.1f, \"negative_deg\": %.1f }",
                  k ? "," : "", model.c_str(), pos, neg);
    json += entry;
  }
  json += " } }\n";
  if(o.report_dir.empty())
    return true;
  const std::string path = o.report_dir + "/max_amplitude.json";
  std::FILE* f = std::fopen((path + ".tmp").c_str(), "w");
  if(!f || std::fputs(json.c_str(), f) < 0 || std::fclose(f) != 0 ||
     std::rename((path + ".tmp").c_str(), path.c_str()) != 0) {
    std::cerr << o.program << ": cannot write " << path << "\n";
    return false;
  }
  return true;
}

} // namespace naca0012_demo

#endif // SPRING_MOTION_EXAMPLES_NACA0012_DEMO_H
