// A shortened run of the paper's 2D case (the full one is the demo
// examples/naca0012_pitch_2d): 20 steps to 20 degrees on the coarse mesh.
#include <spring_motion/spring_motion.h>
#include <naca0012/Naca0012_mesh_2.h>

#include <catch2/catch.hpp>

#include <cmath>

namespace sm = spring_motion;

TEST_CASE("naca0012 pitch: the grid-scaled model pitches the coarse mesh to 20 degrees validly", "[naca0012][deform]")
{
  sm::Mesh_2_cdt cdt;
  sm::make_naca0012_mesh_2(cdt);
  const auto extracted = sm::extract_spring_network(cdt);
  const auto& net = extracted.network;
  // the paper's 3875 nodes and 7587 triangles, within 10%
  CHECK(std::abs(double(net.number_of_vertices()) - 3875) <= 387.5);
  CHECK(std::abs(double(net.number_of_elements()) - 7587) <= 758.7);

  auto on_airfoil = [](const std::array<double, 2>& p) { return sm::is_on_naca0012_airfoil(p[0], p[1]); };
  for(const double amplitude : {20.0, -20.0}) {
    sm::Network_deformer<2> deformer(net, sm::assign_roles(net, sm::moving_boundary_where(on_airfoil)));
    sm::Deform_options options;
    options.number_of_steps = 20;
    const sm::Pitch_motion<2> motion(amplitude, {0.25, 0.0});
    const auto report = deformer.run(motion, sm::Grid_scaled_stiffness{}, options);
    REQUIRE(report.completed);
    CHECK(report.converged);
    CHECK(report.final_angle_deg == Approx(amplitude));

    // no element inverted, by the exact predicate, independently of the deformer's own check
    for(std::size_t t = 0; t < net.number_of_elements(); ++t) {
      const auto& e = net.elements[t];
      const auto o0 = CGAL::orientation(sm::Mesh_2_kernel::Point_2(net.points[e[0]][0], net.points[e[0]][1]),
                                        sm::Mesh_2_kernel::Point_2(net.points[e[1]][0], net.points[e[1]][1]),
                                        sm::Mesh_2_kernel::Point_2(net.points[e[2]][0], net.points[e[2]][1]));
      const auto& x = deformer.positions();
      const auto o1 = CGAL::orientation(sm::Mesh_2_kernel::Point_2(x[e[0]][0], x[e[0]][1]),
                                        sm::Mesh_2_kernel::Point_2(x[e[1]][0], x[e[1]][1]),
                                        sm::Mesh_2_kernel::Point_2(x[e[2]][0], x[e[2]][1]));
      REQUIRE(o0 != CGAL::COLLINEAR);
      REQUIRE(o1 == o0);
    }

    // airfoil nodes exactly at their rotated positions, far field unmoved
    const double a = amplitude * M_PI / 180;
    std::size_t airfoil = 0, far = 0;
    for(std::size_t i = 0; i < net.number_of_vertices(); ++i) {
      const auto& p = net.points[i];
      const auto& q = deformer.positions()[i];
      if(!net.on_boundary[i])
        continue;
      if(on_airfoil(p)) {
        ++airfoil;
        const double x = p[0] - 0.25, y = p[1];
        CHECK(q[0] == Approx(0.25 + std::cos(a) * x - std::sin(a) * y).margin(1e-14));
        CHECK(q[1] == Approx(std::sin(a) * x + std::cos(a) * y).margin(1e-14));
      } else {
        ++far;
        CHECK(std::hypot(p[0] - 0.5, p[1]) == Approx(15.0).epsilon(1e-9));
        CHECK(q == p);
      }
    }
    CHECK(airfoil > 100);
    CHECK(far > 20);
  }
}
