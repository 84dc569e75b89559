// The paper's 2D case: a NACA0012 airfoil in a circular far field pitches
// about its quarter chord to +45 and to -45 degrees in 100 quarter-sine steps,
// with every stiffness model. Prints one table; optionally writes a JSON report
// and a VTU file of the final mesh per run, and finds each model's largest
// amplitude.
//
//   naca0012_pitch_2d [--mesh coarse|fine] [--amplitude DEG] [--steps N]
//                     [--report-dir DIR] [--max-amplitude] [--models a,b,...]
//                     [--solver default|paper] [--max-substep-halvings K]
//
// --solver paper: SOR stopped when no component changes by more than 5e-6
// (the paper's Eq. 12); default: conjugate gradients stopped when the
// estimated error is below 1e-6 chord.
#include <spring_motion/spring_motion.h>
#include <spring_motion/domains/Naca0012_mesh_2.h>
#include <spring_motion/io/network_output.h>
#include <spring_motion/stiffness/model_by_name.h>

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <iostream>
#include <sstream>
#include <string>
#include <vector>

namespace sm = spring_motion;

struct Setup
{
  std::string mesh = "coarse";
  double amplitude = 45;
  std::size_t steps = 100;
  std::string report_dir;
  bool max_amplitude = false;
  bool paper_solver = false; // SOR stopped by the paper's Eq. 12
  std::size_t max_substep_halvings = 0; // Deform_options::max_substep_halvings
  std::vector<std::string> models = sm::model_names();
};

// One pitch run of one model on a copy of the network.
sm::Deform_report pitch(const sm::Spring_network<2>& net, const std::vector<sm::Vertex_role>& roles,
                        const std::string& model, double amplitude, const Setup& setup,
                        sm::Network_deformer<2>* keep = nullptr)
{
  sm::Network_deformer<2> deformer(net, roles);
  sm::Deform_options options;
  options.number_of_steps = setup.steps;
  if(setup.paper_solver)
    options.solver = sm::Solver_options::paper();
  options.max_substep_halvings = setup.max_substep_halvings;
  const sm::Pitch_motion<2> motion(amplitude, {0.25, 0.0}); // quarter chord
  auto report = sm::with_model(model, [&](const auto& m) { return deformer.run(motion, m, options); });
  if(keep)
    *keep = std::move(deformer);
  return report;
}

// Largest amplitude in [0, 180] whose run completes, by bisection to 0.5 deg.
double largest_amplitude(const sm::Spring_network<2>& net, const std::vector<sm::Vertex_role>& roles,
                         const std::string& model, double sign, const Setup& setup)
{
  double lo = 0, hi = 180;
  if(pitch(net, roles, model, sign * hi, setup).completed)
    return hi;
  while(hi - lo > 0.5) {
    const double mid = 0.5 * (lo + hi);
    (pitch(net, roles, model, sign * mid, setup).completed ? lo : hi) = mid;
  }
  return lo;
}

std::string histogram(const sm::Skewness_histogram& h)
{
  std::string s;
  for(double f : h.fractions) {
    char b[8];
    std::snprintf(b, sizeof b, "%3.0f", 100 * f);
    s += b;
  }
  return s;
}

Setup parse(int argc, char** argv)
{
  Setup s;
  for(int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    auto value = [&]() -> std::string {
      if(i + 1 >= argc) {
        std::cerr << "naca0012_pitch_2d: " << a << " needs a value\n";
        std::exit(2);
      }
      return argv[++i];
    };
    if(a == "--mesh")
      s.mesh = value();
    else if(a == "--amplitude")
      s.amplitude = std::stod(value());
    else if(a == "--steps")
      s.steps = std::stoul(value());
    else if(a == "--report-dir")
      s.report_dir = value();
    else if(a == "--max-amplitude")
      s.max_amplitude = true;
    else if(a == "--max-substep-halvings")
      s.max_substep_halvings = std::stoul(value());
    else if(a == "--solver") {
      const std::string v = value();
      if(v != "paper" && v != "default") {
        std::cerr << "naca0012_pitch_2d: --solver takes paper or default\n";
        std::exit(2);
      }
      s.paper_solver = v == "paper";
    }
    else if(a == "--models") {
      s.models.clear();
      std::stringstream in(value());
      for(std::string m; std::getline(in, m, ',');)
        s.models.push_back(m);
    } else {
      std::cerr << "usage: naca0012_pitch_2d [--mesh coarse|fine] [--amplitude DEG] [--steps N]\n"
                   "                         [--report-dir DIR] [--max-amplitude] [--models a,b,...]\n"
                   "                         [--solver default|paper] [--max-substep-halvings K]\n";
      std::exit(a == "--help" ? 0 : 2);
    }
  }
  if(s.mesh != "coarse" && s.mesh != "fine") {
    std::cerr << "naca0012_pitch_2d: --mesh takes coarse or fine, not '" << s.mesh << "'\n";
    std::exit(2);
  }
  return s;
}

int main(int argc, char** argv)
{
  const Setup setup = parse(argc, argv);
  const auto t0 = std::chrono::steady_clock::now();
  sm::Mesh_2_cdt cdt;
  sm::make_naca0012_mesh_2(cdt, setup.mesh == "fine" ? sm::Naca0012_mesh_2_options::fine()
                                                     : sm::Naca0012_mesh_2_options{});
  const auto extracted = sm::extract_spring_network(cdt);
  const auto& net = extracted.network;
  const auto roles = sm::assign_roles(net, sm::moving_boundary_where([](const std::array<double, 2>& p) {
                                        return sm::is_on_naca0012_airfoil(p[0], p[1]);
                                      }));
  std::size_t moving = 0;
  for(auto r : roles)
    moving += r == sm::Vertex_role::moving;
  std::printf("NACA0012 (%s mesh): %zu nodes, %zu triangles, %zu airfoil nodes (built in %.2f s)\n"
              "pitch about (0.25, 0), alpha = alpha_m sin(pi i / 2n), n = %zu, alpha_m = +/-%g deg\n"
              "solver: %s\n"
              "R = equiangle skewness (Eq. 13) of the triangles touching the airfoil; histogram in %% per 0.1 bin\n\n",
              setup.mesh.c_str(), net.number_of_vertices(), net.number_of_elements(), moving,
              std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count(), setup.steps,
              setup.amplitude,
              setup.paper_solver ? "SOR, stop when max change <= 5e-6 (the paper's Eq. 12)"
                                 : "conjugate gradients + symmetric Gauss-Seidel, stop when estimated error <= 1e-6");
  std::printf("%-11s %4s %4s %16s %8s %6s  %-30s %8s %11s %8s\n", "model", "dir", "done", "first_invalid",
              "last_deg", "R_max", "R histogram 0..1 (%)", "min_size", "sweeps", "ms/step");
  {
    // the undeformed mesh, for reference (the paper's Fig. 5a)
    sm::Network_deformer<2> original(net, roles);
    const auto r = sm::element_skewness(net, original.positions());
    const auto h = sm::skewness_histogram(r, [&](std::size_t t) { return original.touches_moving(t); });
    std::printf("%-11s %4s %4s %16s %8.2f %6.3f  %-30s %8.3f %11s %8s\n", "original", "", "", "", 0.0, h.max,
                histogram(h).c_str(), 1.0, "", "");
  }
  for(const auto& model : setup.models) {
    for(const double sign : {+1.0, -1.0}) {
      sm::Network_deformer<2> final_state(net, roles);
      const auto r = pitch(net, roles, model, sign * setup.amplitude, setup, &final_state);
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
      std::printf("%-11s %4s %4s %16s %8.2f %6.3f  %-30s %8.3f %11s %8.2f\n", model.c_str(), sign > 0 ? "+" : "-",
                  r.completed ? "yes" : "no", invalid, r.final_angle_deg, r.quality_moving.max,
                  histogram(r.quality_moving).c_str(), r.min_size_ratio, sweeps,
                  1000 * r.seconds_total / double(r.steps.size()));
      std::fflush(stdout);
      if(!setup.report_dir.empty()) {
        const std::string base = setup.report_dir + "/" + model + (sign > 0 ? "_pos" : "_neg");
        sm::write_report_json(r, base + ".json");
        std::vector<sm::Data_array> point_data, cell_data;
        sm::motion_data_arrays(net, final_state.positions(), final_state.orientation_record(), point_data, cell_data);
        sm::write_vtu(sm::make_indexed_mesh(net, final_state.positions()), base + ".vtu", point_data, cell_data);
      }
    }
  }
  if(!setup.report_dir.empty()) {
    // the undeformed mesh, for the figures' "original" panels
    sm::Network_deformer<2> original(net, roles);
    std::vector<sm::Data_array> point_data, cell_data;
    sm::motion_data_arrays(net, original.positions(), original.orientation_record(), point_data, cell_data);
    sm::write_vtu(sm::make_indexed_mesh(net, original.positions()), setup.report_dir + "/original.vtu", point_data,
                  cell_data);
  }
  if(setup.max_amplitude) {
    std::printf("\nlargest amplitude whose %zu-step run completes (bisection to 0.5 deg, up to 180):\n",
                setup.steps);
    std::printf("%-11s %10s %10s\n", "model", "positive", "negative");
    std::string json = "{ \"format\": \"spring_motion.max_amplitude/1\", \"steps\": " + std::to_string(setup.steps) +
                       ", \"resolution_deg\": 0.5, \"models\": {";
    for(std::size_t k = 0; k < setup.models.size(); ++k) {
      const auto& model = setup.models[k];
      const double pos = largest_amplitude(net, roles, model, +1, setup);
      const double neg = largest_amplitude(net, roles, model, -1, setup);
      std::printf("%-11s %10.1f %10.1f\n", model.c_str(), pos, neg);
      std::fflush(stdout);
      char entry[160];
      std::snprintf(entry, sizeof entry, "%s \"%s\": { \"positive_deg\": %.1f, \"negative_deg\": %.1f }",
                    k ? "," : "", model.c_str(), pos, neg);
      json += entry;
    }
    json += " } }\n";
    if(!setup.report_dir.empty()) {
      const std::string path = setup.report_dir + "/max_amplitude.json";
      std::FILE* f = std::fopen((path + ".tmp").c_str(), "w");
      if(!f || std::fputs(json.c_str(), f) < 0 || std::fclose(f) != 0 ||
         std::rename((path + ".tmp").c_str(), path.c_str()) != 0) {
        std::cerr << "naca0012_pitch_2d: cannot write " << path << "\n";
        return 1;
      }
    }
  }
  return 0;
}
