// Test helper for tests/cli: the NACA0012 demo mesh as a Medit file, and the
// library's own deform() on it, to compare with what spring-motion computes
// from that file.
//
//   naca0012_cli_reference export OUT.mesh
//       the mesh of examples/naca0012_pitch_2d (coarse), vertices and
//       triangles in the order deform() numbers them; boundary edges labelled
//       1 (airfoil) and 2 (far field)
//   naca0012_cli_reference compare CLI.mesh --pitch DEG --steps N [--model NAME] [--threads T]
//       runs deform() on the CGAL triangulation itself with the demo's motion
//       (quarter-sine pitch about the quarter chord (0.25, 0), airfoil
//       vertices moving, far field fixed) and prints the largest difference
//       from the positions in CLI.mesh; exit status 0 when it is at most 1e-12.
#include <spring_motion/deform.h>
#include <naca0012/Naca0012_mesh_2.h>
#include <spring_motion/io/read_mesh.h>
#include <spring_motion/io/write_mesh.h>
#include <spring_motion/mesh_traits/Triangulation_2.h>
#include <spring_motion/motion/Pitch_motion.h>
#include <spring_motion/stiffness/model_by_name.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <string>

namespace sm = spring_motion;

namespace {

bool on_airfoil(const std::array<double, 2>& p) { return sm::is_on_naca0012_airfoil(p[0], p[1]); }

int usage()
{
  std::fprintf(stderr, "usage: naca0012_cli_reference export OUT.mesh\n"
                       "       naca0012_cli_reference compare CLI.mesh --pitch DEG --steps N [--model NAME] "
                       "[--threads T]\n");
  return 2;
}

int export_mesh(const std::string& path)
{
  sm::Mesh_2_cdt cdt;
  sm::make_naca0012_mesh_2(cdt);
  const auto extracted = sm::extract_spring_network(cdt);
  const auto& net = extracted.network;
  sm::Indexed_mesh<2> mesh;
  mesh.points = net.points;
  mesh.elements = net.elements;
  mesh.element_labels.assign(net.number_of_elements(), 0);
  for(const auto& f : net.boundary_facets) {
    mesh.boundary_facets.push_back(f);
    mesh.boundary_labels.push_back(on_airfoil(net.points[f[0]]) && on_airfoil(net.points[f[1]]) ? 1 : 2);
  }
  mesh.label_names = {{1, "airfoil"}, {2, "farfield"}};
  sm::write_medit(mesh, path);
  std::printf("wrote %s: %zu vertices, %zu triangles, %zu boundary edges\n", path.c_str(), mesh.points.size(),
              mesh.elements.size(), mesh.boundary_facets.size());
  return 0;
}

int compare(int argc, char** argv)
{
  const std::string cli_path = argv[2];
  double pitch = std::nan("");
  std::size_t steps = 0;
  std::string model = "grid_scaled";
  int threads = 0;
  for(int i = 3; i + 1 < argc; i += 2) {
    const std::string o = argv[i], v = argv[i + 1];
    if(o == "--pitch")
      pitch = std::stod(v);
    else if(o == "--steps")
      steps = std::stoul(v);
    else if(o == "--model")
      model = v;
    else if(o == "--threads")
      threads = std::stoi(v);
    else
      return usage();
  }
  if(!std::isfinite(pitch) || steps == 0)
    return usage();

  sm::Mesh_2_cdt cdt;
  sm::make_naca0012_mesh_2(cdt);
  sm::Deform_options options; // the demo's defaults, as the CLI's
  options.number_of_steps = steps;
  options.solver.threads = threads;
  const sm::Pitch_motion<2> motion(pitch, {0.25, 0.0});
  const auto report = sm::with_model(model, [&](const auto& m) {
    return sm::deform(cdt, sm::moving_boundary_where(on_airfoil), motion, m, options);
  });
  const auto library = sm::extract_spring_network(cdt).network; // deformed positions, same numbering

  const sm::Mesh_file cli = sm::read_mesh(cli_path);
  if(cli.dimension != 2 || cli.mesh_2.points.size() != library.points.size() ||
     cli.mesh_2.elements != library.elements) {
    std::printf("FAIL: %s is not the same mesh (%zu vertices, %zu triangles; library %zu, %zu)\n", cli_path.c_str(),
                cli.mesh_2.points.size(), cli.mesh_2.elements.size(), library.points.size(),
                library.elements.size());
    return 1;
  }
  double worst = 0, largest_motion = 0;
  std::size_t differing = 0;
  for(std::size_t i = 0; i < library.points.size(); ++i) {
    const auto& p = cli.mesh_2.points[i];
    const auto& q = library.points[i];
    const double d = std::max(std::abs(p[0] - q[0]), std::abs(p[1] - q[1]));
    worst = std::max(worst, d);
    differing += d != 0;
  }
  // how far the mesh moved, so that a match is not a match of two unmoved meshes
  sm::Mesh_2_cdt initial;
  sm::make_naca0012_mesh_2(initial);
  const auto start = sm::extract_spring_network(initial).network;
  for(std::size_t i = 0; i < start.points.size(); ++i)
    largest_motion = std::max(largest_motion, std::hypot(start.points[i][0] - library.points[i][0],
                                                         start.points[i][1] - library.points[i][1]));
  std::printf("library deform(): %s, final angle %.6g deg; largest vertex motion %.6g chord\n",
              report.completed ? "completed" : "stopped", report.final_angle_deg, largest_motion);
  std::printf("CLI vs library: max |difference| = %.3g over %zu vertices (%zu differ)\n", worst,
              library.points.size(), differing);
  // The two runs do the same floating-point operations on the same numbers
  // (the Medit file holds every coordinate bit for bit), so the difference
  // is expected to be exactly 0; 1e-12 chord is the bound the tests accept.
  const bool ok = worst <= 1e-12 && largest_motion > 0.1;
  std::printf("%s\n", ok ? "PASS" : "FAIL");
  return ok ? 0 : 1;
}

} // namespace

int main(int argc, char** argv)
{
  try {
    if(argc == 3 && std::string(argv[1]) == "export")
      return export_mesh(argv[2]);
    if(argc >= 3 && std::string(argv[1]) == "compare")
      return compare(argc, argv);
    return usage();
  } catch(const std::exception& e) {
    std::fprintf(stderr, "naca0012_cli_reference: %s\n", e.what());
    return 1;
  }
}
