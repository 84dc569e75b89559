// libFuzzer target: deform() on a small generated 2D or 3D grid mesh (cells
// split into simplices, vertices jittered, coordinates possibly scaled to
// extreme magnitudes) with fuzzed roles, boundary motion, stiffness model,
// step count, substepping and solver.
//
// The property: deform() either returns a report and a mesh in which every
// element keeps its initial exact orientation (re-checked here with
// CGAL::orientation, independently of the library's own check), or throws
// spring_motion::Error. A crash, a sanitizer report, another exception or an
// inverted element in a mesh returned as valid is a finding.
#include <spring_motion/Error.h>
#include <spring_motion/deform.h>
#include <spring_motion/mesh_traits/Indexed_mesh.h>
#include <spring_motion/stiffness/model_by_name.h>

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>

#include <fuzzer/FuzzedDataProvider.h>

#include <array>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <limits>
#include <regex>
#include <sstream>
#include <vector>

namespace sm = spring_motion;
using K = CGAL::Exact_predicates_inexact_constructions_kernel;

namespace {

[[noreturn]] void fail(const char* what)
{
  std::fprintf(stderr, "property violated: %s\n", what);
  std::abort();
}

int orientation(const sm::Indexed_mesh<2>& m, std::size_t t)
{
  const auto& e = m.elements[t];
  auto P = [&](int k) { return K::Point_2(m.points[e[k]][0], m.points[e[k]][1]); };
  return int(CGAL::orientation(P(0), P(1), P(2)));
}
int orientation(const sm::Indexed_mesh<3>& m, std::size_t t)
{
  const auto& e = m.elements[t];
  auto P = [&](int k) { return K::Point_3(m.points[e[k]][0], m.points[e[k]][1], m.points[e[k]][2]); };
  return int(CGAL::orientation(P(0), P(1), P(2), P(3)));
}

// A grid of n[0] x ... cells of unit size, each split into D! simplices
// (2D: two triangles, the diagonal chosen per cell; 3D: Kuhn's six tetrahedra).
template <int D>
sm::Indexed_mesh<D> make_grid(FuzzedDataProvider& in, std::array<int, D>& n)
{
  sm::Indexed_mesh<D> m;
  for(int c = 0; c < D; ++c)
    n[c] = in.ConsumeIntegralInRange<int>(1, D == 2 ? 5 : 3);
  std::array<int, D> nv;
  for(int c = 0; c < D; ++c)
    nv[c] = n[c] + 1;
  auto id = [&](const std::array<int, D>& g) {
    std::uint32_t i = 0;
    for(int c = D - 1; c >= 0; --c)
      i = i * std::uint32_t(nv[c]) + std::uint32_t(g[c]);
    return i;
  };
  std::size_t count = 1;
  for(int c = 0; c < D; ++c)
    count *= std::size_t(nv[c]);
  m.points.resize(count);
  for(std::size_t i = 0; i < count; ++i) {
    std::size_t r = i;
    bool interior = true;
    for(int c = 0; c < D; ++c) {
      const int g = int(r % std::size_t(nv[c]));
      r /= std::size_t(nv[c]);
      m.points[i][c] = g;
      interior = interior && g > 0 && g < n[c];
    }
    if(interior) // jitter up to 0.45 cell: the grid stays valid in 2D
      for(int c = 0; c < D; ++c)
        m.points[i][c] += 0.45 * (in.ConsumeIntegralInRange<int>(-128, 127) / 128.0);
  }
  std::array<int, D> g{};
  for(;;) {
    auto corner = [&](unsigned bits) {
      std::array<int, D> h = g;
      for(int c = 0; c < D; ++c)
        h[c] += (bits >> c) & 1;
      return id(h);
    };
    if constexpr(D == 2) {
      if(in.ConsumeBool()) {
        m.elements.push_back({corner(0), corner(1), corner(3)});
        m.elements.push_back({corner(0), corner(3), corner(2)});
      } else {
        m.elements.push_back({corner(0), corner(1), corner(2)});
        m.elements.push_back({corner(1), corner(3), corner(2)});
      }
    } else {
      const int perm[6][3] = {{0, 1, 2}, {0, 2, 1}, {1, 0, 2}, {1, 2, 0}, {2, 0, 1}, {2, 1, 0}};
      for(const auto& p : perm) {
        const unsigned a = 1u << p[0], b = a | (1u << p[1]);
        m.elements.push_back({corner(0), corner(a), corner(b), corner(7)});
      }
    }
    int c = 0;
    while(c < D && ++g[c] == n[c])
      g[c++] = 0;
    if(c == D)
      break;
  }
  m.element_labels.assign(m.elements.size(), 0);
  return m;
}

// Moving vertices go to p0 + t d_i (each its own displacement) or rotate
// rigidly about the grid's centre; optionally one vertex's position turns
// NaN or infinite beyond t = tau, which deform() must reject.
template <int D>
struct Fuzz_motion
{
  std::vector<std::array<double, D>> p0;
  std::vector<std::array<double, D>> displacement;
  bool rotate = false;
  double angle = 0;
  std::array<double, D> centre{};
  int poison_vertex = -1;
  double poison_after = 2;
  double poison_value = 0;

  std::array<double, D> operator()(const std::array<double, D>& p, double t) const
  {
    std::array<double, D> q = p;
    std::size_t i = 0;
    while(i < p0.size() && p0[i] != p)
      ++i;
    if(rotate) {
      const double a = angle * t, c = std::cos(a), s = std::sin(a);
      const double x = p[0] - centre[0], y = p[1] - centre[1];
      q[0] = centre[0] + c * x - s * y;
      q[1] = centre[1] + s * x + c * y;
    } else if(i < p0.size())
      for(int k = 0; k < D; ++k)
        q[k] += t * displacement[i][k];
    if(int(i) == poison_vertex && t > poison_after)
      q[0] = poison_value;
    return q;
  }
};

template <int D>
void run(FuzzedDataProvider& in)
{
  std::array<int, D> n;
  sm::Indexed_mesh<D> mesh = make_grid<D>(in, n);
  // extreme magnitudes: tiny or huge meshes must fail cleanly or work
  const double scales[] = {1, 1, 1, 1e-3, 1e3, 1e-150, 1e150, 1e-300, 1e300};
  const double scale = scales[in.ConsumeIntegralInRange<int>(0, 8)];
  for(auto& p : mesh.points)
    for(auto& x : p)
      x *= scale;
  const std::size_t nv = mesh.points.size();

  // roles: boundary vertices moving or fixed (or free), interior ones free
  // (or, rarely, constrained)
  std::vector<sm::Vertex_role> role(nv);
  for(std::size_t i = 0; i < nv; ++i)
    role[i] = sm::Vertex_role(in.ConsumeIntegralInRange<int>(0, 2));
  auto role_of = [&](const sm::Vertex_info<D>& v) { return role[v.index]; };

  Fuzz_motion<D> motion;
  const double magnitudes[] = {0.01, 0.1, 0.3, 1, 3, 100};
  const double magnitude = scale * magnitudes[in.ConsumeIntegralInRange<int>(0, 5)];
  motion.rotate = D == 2 && in.ConsumeBool();
  motion.angle = in.ConsumeIntegralInRange<int>(-180, 180) * M_PI / 180.0;
  for(int c = 0; c < D; ++c)
    motion.centre[c] = scale * 0.5 * n[c];
  for(std::size_t i = 0; i < nv; ++i) {
    motion.p0.push_back(mesh.points[i]);
    std::array<double, D> d;
    for(int c = 0; c < D; ++c)
      d[c] = magnitude * (in.ConsumeIntegralInRange<int>(-128, 127) / 128.0);
    motion.displacement.push_back(d);
  }
  if(in.ConsumeIntegralInRange<int>(0, 7) == 0) {
    motion.poison_vertex = in.ConsumeIntegralInRange<int>(0, int(nv) - 1);
    motion.poison_after = in.ConsumeIntegralInRange<int>(0, 100) / 100.0;
    const double poisons[] = {std::numeric_limits<double>::quiet_NaN(), std::numeric_limits<double>::infinity(),
                              -std::numeric_limits<double>::infinity()};
    motion.poison_value = poisons[in.ConsumeIntegralInRange<int>(0, 2)];
  }

  sm::Deform_options options;
  options.number_of_steps = in.ConsumeIntegralInRange<std::size_t>(1, 12);
  options.max_substep_halvings = in.ConsumeIntegralInRange<std::size_t>(0, 5);
  options.quality_every_step = in.ConsumeBool();
  options.solver.threads = 1;
  options.solver.max_iterations = 3000; // keeps each input fast; unconverged solves are reported
  if(in.ConsumeBool())
    options.solver = sm::Solver_options::paper(), options.solver.threads = 1, options.solver.max_iterations = 3000;
  const auto& names = sm::model_names();
  const std::string model = names[in.ConsumeIntegralInRange<std::size_t>(0, names.size() - 1)];

  const sm::Indexed_mesh<D> initial = mesh;
  std::vector<int> sign(mesh.elements.size());
  for(std::size_t t = 0; t < mesh.elements.size(); ++t)
    sign[t] = orientation(initial, t);

  sm::Deform_report report;
  try {
    report = sm::with_model(model, [&](const auto& m) { return sm::deform(mesh, role_of, motion, m, options); });
  } catch(const sm::Error&) {
    return; // a clean refusal
  }

  // The returned mesh: finite, and every element exactly as oriented as before.
  for(const auto& p : mesh.points)
    for(double x : p)
      if(!std::isfinite(x))
        fail("non-finite coordinate in a returned mesh");
  for(std::size_t t = 0; t < mesh.elements.size(); ++t)
    if(orientation(mesh, t) != sign[t])
      fail("an element of the returned mesh is inverted or flat");
  // The report agrees with itself and with the mesh.
  if(report.completed != !report.first_invalid.has_value())
    fail("completed and first_invalid disagree");
  if(report.completed && report.final_fraction != 1.0)
    fail("a completed run did not reach t = 1");
  if(report.steps.size() > options.number_of_steps)
    fail("more step reports than steps");
  for(const auto& s : report.steps) {
    if(s.substeps == 0 || (s.substeps & (s.substeps - 1)) != 0 ||
       s.substeps > (std::size_t(1) << options.max_substep_halvings))
      fail("substeps not a power of two within the limit");
  }
  if(motion.poison_vertex >= 0 && role[std::size_t(motion.poison_vertex)] == sm::Vertex_role::moving &&
     report.final_fraction > motion.poison_after)
    fail("a NaN/inf motion position was accepted");
  for(std::size_t i = 0; i < nv; ++i) {
    if(role[i] == sm::Vertex_role::fixed && mesh.points[i] != initial.points[i])
      fail("a fixed vertex moved");
    if(role[i] == sm::Vertex_role::moving && report.final_fraction > 0 &&
       mesh.points[i] != motion(initial.points[i], report.final_fraction))
      fail("a moving vertex is not at its prescribed position");
  }
  std::ostringstream json;
  sm::write_report_json(report, json);
  // non-finite numbers are written as null (Deform_report.h)
  static const std::regex non_finite(R"([:\[,]\s*-?(nan|inf))", std::regex::icase);
  if(std::regex_search(json.str(), non_finite))
    fail("the JSON report holds a non-finite number");
}

} // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size)
{
  FuzzedDataProvider in(data, size);
  if(in.ConsumeIntegralInRange<int>(0, 3) == 0)
    run<3>(in);
  else
    run<2>(in);
  return 0;
}
