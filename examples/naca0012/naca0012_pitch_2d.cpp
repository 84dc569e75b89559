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
// estimated error is below 1e-6 chord. The table, the reports and the
// amplitude search are shared with the 3D wing, in naca0012_demo.h.
#include "naca0012_demo.h"

#include <spring_motion/spring_motion.h>
#include <naca0012/Naca0012_mesh_2.h>
#include <spring_motion/stiffness/model_by_name.h>

#include <chrono>
#include <cstdio>
#include <string>

namespace sm = spring_motion;
namespace demo = naca0012_demo;

int main(int argc, char** argv)
{
  demo::Options options;
  options.program = "naca0012_pitch_2d";
  options.amplitude = 45;
  // the paper's comparison; --models picks any name of sm::model_table()
  options.models = {"lineal", "lineal_p2", "blom", "zeng_ethier", "grid_scaled", "torsional"};
  std::string mesh = "coarse";
  CLI::App app("The paper's 2D case: a NACA0012 airfoil pitching about its quarter chord, every stiffness model.",
               "naca0012_pitch_2d");
  app.add_option("--mesh", mesh, "coarse: the paper's size (3875 nodes); fine: about 4x as many nodes")
      ->check(CLI::IsMember({"coarse", "fine"}))
      ->capture_default_str();
  demo::add_options(app, options);
  CLI11_PARSE(app, argc, argv);

  const auto t0 = std::chrono::steady_clock::now();
  sm::Mesh_2_cdt cdt;
  sm::make_naca0012_mesh_2(cdt, mesh == "fine" ? sm::Naca0012_mesh_2_options::fine() : sm::Naca0012_mesh_2_options{});
  const auto extracted = sm::extract_spring_network(cdt);
  const auto& net = extracted.network;
  const auto roles = sm::assign_roles(net, sm::moving_boundary_where([](const std::array<double, 2>& p) {
                                        return sm::is_on_naca0012_airfoil(p[0], p[1]);
                                      }));
  std::printf("NACA0012 (%s mesh): %zu nodes, %zu triangles, %zu airfoil nodes (built in %.2f s)\n"
              "pitch about (0.25, 0), alpha = alpha_m sin(pi i / 2n), n = %zu, alpha_m = +/-%g deg\n"
              "solver: %s\n"
              "R = equiangle skewness (Eq. 13) of the triangles touching the airfoil; histogram in %% per 0.1 bin;\n"
              "min_angle = their smallest interior angle (deg)\n\n",
              mesh.c_str(), net.number_of_vertices(), net.number_of_elements(), demo::number_of_moving(roles),
              std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count(), options.steps,
              options.amplitude, options.solver_description());

  const demo::Pitch_demo<2> runs{
      net, roles, options,
      [&](const std::string& model, double amplitude, sm::Network_deformer<2>& deformer) {
        const sm::Pitch_motion<2> motion(amplitude, {0.25, 0.0}); // quarter chord
        const sm::Deform_options deform = options.deform_options();
        return sm::with_model(model, [&](const auto& m) { return deformer.run(motion, m, deform); });
      },
      11, 2};
  demo::print_original(runs); // the paper's Fig. 5a
  demo::run_models(runs);
  demo::write_original_vtu(runs);
  return demo::print_largest_amplitudes(runs, 180, 0.5) ? 0 : 1;
}
