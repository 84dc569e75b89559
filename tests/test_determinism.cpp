// Determinism: the same input twice gives bitwise the same
// positions, the same report (timings aside) and the same written files.
// (1 thread against N threads: tests/test_thread_determinism.cpp.)
#include <spring_motion/io/network_output.h>
#include <spring_motion/io/write_mesh.h>
#include <spring_motion/spring_motion.h>
#include <spring_motion/stiffness/model_by_name.h>

#include "test_meshes.h"

#include <catch2/catch.hpp>

#include <cstring>
#include <regex>
#include <sstream>

using namespace spring_motion;

namespace {

// The report without its timings and thread counts (chosen by measuring
// the timings), the only fields allowed to differ.
std::string report_without_timings(const Deform_report& r)
{
  std::ostringstream out;
  write_report_json(r, out);
  static const std::regex seconds(R"re("seconds[a-z_]*": (\{[^}]*\}|[-+0-9.eE]+|null))re");
  static const std::regex threads(R"re("threads": [0-9]+)re");
  return std::regex_replace(std::regex_replace(out.str(), seconds, "\"seconds\": -"), threads, "\"threads\": -");
}

struct Outcome
{
  std::vector<double> positions; // flattened
  std::string report, medit, vtu;
};

template <int D>
std::vector<double> flatten(const std::vector<std::array<double, D>>& x)
{
  std::vector<double> f;
  for(const auto& p : x)
    f.insert(f.end(), p.begin(), p.end());
  return f;
}

template <int D>
Outcome outcome(const Spring_network<D>& net, const Network_deformer<D>& d, const Deform_report& r)
{
  Outcome o;
  o.positions = flatten<D>(d.positions());
  o.report = report_without_timings(r);
  std::vector<Data_array> point_data, cell_data;
  motion_data_arrays(net, d.positions(), d.orientation_record(), point_data, cell_data);
  const auto mesh = make_indexed_mesh(net, d.positions());
  std::ostringstream medit, vtu;
  write_medit(mesh, medit);
  write_vtu(mesh, vtu, point_data, cell_data);
  o.medit = medit.str();
  o.vtu = vtu.str();
  return o;
}

void check_same(const Outcome& a, const Outcome& b)
{
  REQUIRE(a.positions.size() == b.positions.size());
  // bitwise: memcmp, not ==, so that even the sign of a zero counts
  CHECK(std::memcmp(a.positions.data(), b.positions.data(), a.positions.size() * sizeof(double)) == 0);
  CHECK(a.report == b.report);
  CHECK(a.medit == b.medit);
  CHECK(a.vtu == b.vtu);
}

// Builds the NACA0012 mesh from scratch (so mesh generation is part of what
// must repeat), runs `model`, and returns everything it produced.
Outcome naca_run(const std::string& model, double amplitude, std::size_t halvings)
{
  const auto [net, roles] = spring_motion_test::naca0012_network();
  Network_deformer<2> d(net, roles);
  Deform_options options;
  options.number_of_steps = 10;
  options.max_substep_halvings = halvings;
  const auto r = with_model(model, [&](const auto& m) { return d.run(Pitch_motion<2>(amplitude, {0.25, 0}), m, options); });
  return outcome<2>(net, d, r);
}

} // namespace

TEST_CASE("determinism: the same NACA0012 pitch twice, every model", "[determinism]")
{
  for(const auto& model : model_names()) {
    INFO("model " << model);
    // 30 deg completes for every model; 60 deg in 10 steps with substepping
    // makes most models split steps and some give up: rollback must repeat too
    check_same(naca_run(model, 30, 0), naca_run(model, 30, 0));
    check_same(naca_run(model, 60, 3), naca_run(model, 60, 3));
  }
}

TEST_CASE("determinism: deform() on a CGAL triangulation twice", "[determinism]")
{
  auto run = [] {
    spring_motion_test::CDT cdt;
    spring_motion_test::make_annulus(cdt);
    Deform_options options;
    options.number_of_steps = 8;
    options.max_substep_halvings = 4;
    const auto r = deform(cdt, moving_boundary_where([](const std::array<double, 2>& p) {
                            return std::hypot(p[0], p[1]) < 1.0;
                          }),
                          Pitch_motion<2>(75, {0, 0}), Zeng_Ethier_semi_torsional_stiffness{}, options);
    std::vector<double> x;
    for(auto v = cdt.finite_vertices_begin(); v != cdt.finite_vertices_end(); ++v) {
      x.push_back(v->point().x());
      x.push_back(v->point().y());
    }
    return std::make_pair(x, report_without_timings(r));
  };
  const auto a = run(), b = run();
  REQUIRE(a.first.size() == b.first.size());
  CHECK(std::memcmp(a.first.data(), b.first.data(), a.first.size() * sizeof(double)) == 0);
  CHECK(a.second == b.second);
}

TEST_CASE("determinism: a 3D run twice", "[determinism]")
{
  // a 2 x 2 x 2 block of cubes split into Kuhn's six tetrahedra each, the
  // centre vertex moved
  Indexed_mesh<3> mesh;
  auto id = [](int i, int j, int k) { return std::uint32_t((k * 3 + j) * 3 + i); };
  for(int k = 0; k < 3; ++k)
    for(int j = 0; j < 3; ++j)
      for(int i = 0; i < 3; ++i)
        mesh.points.push_back({double(i), double(j), double(k)});
  const int perm[6][3] = {{0, 1, 2}, {0, 2, 1}, {1, 0, 2}, {1, 2, 0}, {2, 0, 1}, {2, 1, 0}};
  for(int k = 0; k < 2; ++k)
    for(int j = 0; j < 2; ++j)
      for(int i = 0; i < 2; ++i)
        for(const auto& p : perm) {
          auto corner = [&](unsigned b) { return id(i + (b & 1), j + ((b >> 1) & 1), k + ((b >> 2) & 1)); };
          const unsigned a = 1u << p[0], b = a | (1u << p[1]);
          mesh.elements.push_back({corner(0), corner(a), corner(b), corner(7)});
        }
  const auto net = make_spring_network<3>(mesh.points, mesh.elements);
  // the top face moves, the rest of the boundary is fixed, the centre is free
  const auto roles = assign_roles(net, [](const Vertex_info<3>& v) {
    return !v.on_boundary ? Vertex_role::free : (v.point[2] == 2.0 ? Vertex_role::moving : Vertex_role::fixed);
  });
  for(const auto& model : {std::string("lineal"), std::string("zeng_ethier"), std::string("grid_scaled")}) {
    INFO("model " << model);
    auto run = [&] {
      Network_deformer<3> d(net, roles);
      Deform_options options;
      options.number_of_steps = 5;
      options.max_substep_halvings = 2;
      const auto r = with_model(model, [&](const auto& m) {
        return d.run(Translation_motion<3>{{0.7, 0.3, -0.9}}, m, options);
      });
      return outcome<3>(net, d, r);
    };
    check_same(run(), run());
  }
}
