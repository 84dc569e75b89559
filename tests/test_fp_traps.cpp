// Floating point: whole deform() runs of every stiffness
// model with the FE_INVALID, FE_DIVBYZERO and FE_OVERFLOW traps enabled
// (glibc's feenableexcept), so the first NaN, division by zero or overflow
// the library computes raises SIGFPE, which Catch2 reports as a failure at
// that test. Underflow is not trapped: a tiny value flushing towards zero is
// the expected behaviour of a tiny mesh. docs/reliability.md lists what
// each model does at zero-length edges and at angles of 0 and pi.
#include <spring_motion/spring_motion.h>
#include <spring_motion/internal/geometry/angles.h>
#include <spring_motion/stiffness/model_by_name.h>

#include "fp_traps.h"
#include "test_meshes.h"

#include <catch2/catch.hpp>

#include <cfenv>
#include <cmath>
#include <limits>

using namespace spring_motion;
using spring_motion_test::Fp_traps;
using spring_motion_test::trapped;

namespace {

template <int D>
bool all_valid(const Spring_network<D>& net, const std::vector<typename Spring_network<D>::Point>& x,
               const Orientation_record& rec)
{
  std::vector<std::size_t> bad;
  return find_inverted_elements(net, x, rec, std::back_inserter(bad)) == 0;
}

// Runs `model_name` on a copy of the network; the run must end either with a
// valid mesh and a report, or with spring_motion::Error. Returns whether it
// completed.
template <int D, class Motion>
bool run_model(const std::string& model_name, const Spring_network<D>& net, const std::vector<Vertex_role>& roles,
               const Motion& motion, const Deform_options& options)
{
  Network_deformer<D> deformer(net, roles);
  const auto report = with_model(model_name, [&](const auto& m) { return deformer.run(motion, m, options); });
  CHECK(all_valid(net, deformer.positions(), deformer.orientation_record()));
  CHECK(report.completed == !report.first_invalid.has_value());
  return report.completed;
}

} // namespace

TEST_CASE("fp traps: every 2D model on an annulus rotated until it fails", "[fp]")
{
  spring_motion_test::CDT cdt;
  spring_motion_test::make_annulus(cdt);
  const auto net = extract_spring_network(cdt).network;
  const auto roles = assign_roles(net, moving_boundary_where([](const std::array<double, 2>& p) {
                                    return std::hypot(p[0], p[1]) < 1.0;
                                  }));
  Fp_traps traps;
  // 120 deg in 12 steps with up to 4 substeps per step: every model meets
  // nearly flat elements, and most give up, on the way
  Deform_options options;
  options.number_of_steps = 12;
  options.max_substep_halvings = 2;
  for(const auto& name : model_names()) {
    INFO("model " << name);
    run_model<2>(name, net, roles, Pitch_motion<2>(120, {0, 0}), options);
  }
}

TEST_CASE("fp traps: every 2D model on the NACA0012 pitch beyond its limit", "[fp]")
{
  const auto [net, roles] = spring_motion_test::naca0012_network();
  Fp_traps traps;
  Deform_options options;
  options.number_of_steps = 10;
  options.max_substep_halvings = 1;
  for(const auto& name : model_names()) {
    INFO("model " << name);
    // 180 deg in 10 steps: beyond every model's limit but the torsional one's
    run_model<2>(name, net, roles, Pitch_motion<2>(180, {0.25, 0}), options);
  }
}

TEST_CASE("fp traps: every 3D model on a sheared grid of tetrahedra", "[fp]")
{
  const auto mesh = spring_motion_test::kuhn_grid<3>(3, 0.2);
  const auto net = make_spring_network<3>(mesh.points, mesh.elements);
  // top face moving, bottom face and sides fixed
  const auto roles = assign_roles(net, [](const Vertex_info<3>& v) {
    if(!v.on_boundary)
      return Vertex_role::free;
    return v.point[2] == 3.0 ? Vertex_role::moving : Vertex_role::fixed;
  });
  Fp_traps traps;
  Deform_options options;
  options.number_of_steps = 6;
  options.max_substep_halvings = 2;
  // shear the top face by twice the cell size: far enough to flatten tetrahedra
  const Translation_motion<3> shear{{2.0, 0.5, -1.5}};
  for(const auto& name : model_names()) {
    INFO("model " << name);
    run_model<3>(name, net, roles, shear, options);
  }
  Network_deformer<3> dihedral(net, roles);
  dihedral.run(shear, Zeng_Ethier_semi_torsional_stiffness{Angle_kind::element}, options);
  CHECK(all_valid(net, dihedral.positions(), dihedral.orientation_record()));
}

TEST_CASE("fp traps: tiny and huge meshes, every 2D model", "[fp]")
{
  // Lengths from 1e-300 (squared lengths underflow) to 1e100: within this
  // range every model gives a finite, capped stiffness and the run either
  // moves the centre vertex validly or stops with an Error; nothing traps.
  // (Beyond ~1e150 products of coordinates overflow in the exact
  // predicates' interval filter itself, see docs/reliability.md.)
  for(double scale : {1e-300, 1e-200, 1e-150, 1e-100, 1e-8, 1e8, 1e100}) {
    Indexed_mesh<2> mesh;
    mesh.points = {{0, 0}, {1, 0}, {1, 1}, {0, 1}, {0.5, 0.5}, {0.25, 0.5}};
    mesh.elements = {{0, 1, 4}, {1, 2, 4}, {2, 3, 4}, {3, 5, 4}, {3, 0, 5}, {0, 4, 5}};
    for(auto& p : mesh.points)
      for(auto& x : p)
        x *= scale;
    auto net = make_spring_network<2>(mesh.points, mesh.elements);
    // the centre vertex moves, vertex 5 is free
    const auto roles = assign_roles(net, [](const Vertex_info<2>& v) {
      return v.index == 4 ? Vertex_role::moving : (v.index == 5 ? Vertex_role::free : Vertex_role::fixed);
    });
    Fp_traps traps;
    Deform_options options;
    options.number_of_steps = 4;
    options.solver.tolerance = 1e-6 * scale; // in length units (Solver_options)
    for(const auto& name : model_names()) {
      INFO("model " << name << ", scale " << scale);
      try {
        run_model<2>(name, net, roles, Translation_motion<2>{{0.2 * scale, 0.1 * scale}}, options);
      } catch(const Error& e) {
        SUCCEED("refused: " << e.what());
      }
    }
  }
}

TEST_CASE("fp traps: tiny and huge meshes, every 3D model", "[fp]")
{
  // The 2D test's scales on Kuhn tetrahedra: every model, the per-step
  // quality and the exact checks; a run moves its vertex validly or stops
  // with an Error, nothing traps.
  const auto unit = spring_motion_test::kuhn_grid<3>(3, 0.2);
  for(double scale : {1e-300, 1e-200, 1e-150, 1e-100, 1e-8, 1e8, 1e100}) {
    auto mesh = unit;
    for(auto& p : mesh.points)
      for(auto& x : p)
        x *= scale;
    const auto net = make_spring_network<3>(mesh.points, mesh.elements);
    // vertex (1, 1, 1) moves, the other interior vertices are free
    const auto roles = assign_roles(net, [](const Vertex_info<3>& v) {
      if(v.on_boundary)
        return Vertex_role::fixed;
      return v.index == (1 * 4 + 1) * 4 + 1 ? Vertex_role::moving : Vertex_role::free;
    });
    Fp_traps traps;
    Deform_options options;
    options.number_of_steps = 4;
    options.solver.tolerance = 1e-6 * scale;
    const Translation_motion<3> motion{{0.2 * scale, 0.1 * scale, -0.15 * scale}};
    for(const auto& name : model_names()) {
      INFO("model " << name << ", scale " << scale);
      try {
        run_model<3>(name, net, roles, motion, options);
      } catch(const Error& e) {
        SUCCEED("refused: " << e.what());
      }
    }
    INFO("Zeng-Ethier on dihedral angles, scale " << scale);
    try {
      Network_deformer<3> dihedral(net, roles);
      dihedral.run(motion, Zeng_Ethier_semi_torsional_stiffness{Angle_kind::element}, options);
      CHECK(all_valid(net, dihedral.positions(), dihedral.orientation_record()));
    } catch(const Error& e) {
      SUCCEED("refused: " << e.what());
    }
  }
}

TEST_CASE("fp traps: models at angles of 0 and pi and at extreme lengths", "[fp]")
{
  Fp_traps traps;
  REQUIRE((fegetexcept() & trapped) == trapped); // the traps are really on
  const double pi = std::acos(-1.0);
  const double dm = std::numeric_limits<double>::denorm_min();
  const double lengths[] = {dm, 1e-300, 1e-160, 1e-20, 1, 1e20, 1e160, 1e300};
  const double angles[][3] = {{0, 0, 0}, {pi, pi, pi}, {0, pi, 0}, {dm, pi - 1e-16, 1e-300}, {1, 2, 0.5}};
  for(double l : lengths)
    for(const auto& a : angles)
      for(std::size_t na : {std::size_t(1), std::size_t(3)})
        for(const auto& name : model_names())
          for(double l0 : {1e-300, 1.0, 1e300}) {
            INFO("model " << name << ", length " << l << ", angle " << a[0] << ", l0 " << l0);
            const Stiffness_context ctx{2, l0};
            const double k = with_model(name, [&](const auto& m) { return m(l, a, na, ctx); });
            // guarded by design: finite, non-negative, capped
            CHECK(std::isfinite(k));
            CHECK(k >= 0);
            CHECK(k <= internal::max_stiffness);
          }
}

TEST_CASE("fp traps: the tetrahedra's 1/sin^2, one and two at once, on flat and point-like elements", "[fp]")
{
  // Two at once, a vector computes both sides of every choice in each
  // lane: a flat element's quotient or a point's 1/extent would divide by
  // zero there if not guarded.
  Fp_traps traps;
  REQUIRE((fegetexcept() & trapped) == trapped);
  using T = std::array<std::array<double, 3>, 4>;
  const T shapes[] = {{{{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}}},  // regular corner
                      {{{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {1, 1, 0}}},  // flat
                      {{{0, 0, 0}, {1, 0, 0}, {1, 0, 0}, {0, 0, 1}}},  // a collapsed edge
                      {{{2, 2, 2}, {2, 2, 2}, {2, 2, 2}, {2, 2, 2}}},  // a point
                      {{{0, 0, 0}, {1, 0, 1e-9}, {1, 1, 0}, {0, 1, 1e-9}}}}; // a sliver
  const auto corners = [](const T& p) {
    return std::array<const double*, 4>{p[0].data(), p[1].data(), p[2].data(), p[3].data()};
  };
  for(const auto& a : shapes)
    for(const auto& b : shapes) {
      const auto both = internal::dihedral_inverse_sin_squared(corners(a), corners(b));
      const auto one = internal::dihedral_inverse_sin_squared(a);
      for(std::size_t k = 0; k < 6; ++k) {
        CHECK(both[0][k] == one[k]);
        CHECK(both[0][k] >= 1);
        CHECK(both[0][k] <= 1e200);
      }
    }
}
