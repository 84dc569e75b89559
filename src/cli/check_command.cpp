// Copyright (c) 2026 SpringMotion developers.
// spring-motion check: validity and quality of a mesh as it is.
#include "Arguments.h"
#include "Mesh_setup.h"
#include "commands.h"

#include <spring_motion/Input_error.h>
#include <spring_motion/internal/geometry/angles.h>
#include <spring_motion/io/read_mesh.h>
#include <spring_motion/skewness.h>
#include <spring_motion/validity.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <ostream>
#include <string>

namespace spring_motion {
namespace cli {

namespace {

std::string fmt(const char* format, double v)
{
  char b[64];
  std::snprintf(b, sizeof b, format, v);
  return b;
}

void print_histogram(std::ostream& out, const char* title, const Skewness_histogram& h)
{
  out << "  " << title << " (" << h.count << " elements): mean " << fmt("%.4f", h.mean) << ", max "
      << fmt("%.4f", h.max) << "\n    R bins 0.0..1.0 (%):";
  for(double f : h.fractions)
    out << fmt(" %5.1f", 100 * f);
  out << "\n";
}

template <int D>
int check(const std::string& path, const Mesh_file& file, std::ostream& out, std::ostream& err)
{
  const Mesh_setup<D> setup = make_mesh_setup<D>(path, file, false);
  const Indexed_mesh<D>& mesh = *setup.mesh;
  std::vector<char> used(mesh.points.size(), 0);
  for(const auto& e : mesh.elements)
    for(auto v : e)
      used[v] = 1;
  const auto unused = std::size_t(std::count(used.begin(), used.end(), 0));
  out << path << ": " << D << "D mesh, " << mesh.points.size() << " vertices";
  if(unused)
    out << " (" << unused << " used by no element, ignored)";
  out << ", " << mesh.elements.size() << " " << (D == 2 ? "triangles" : "tetrahedra") << ", "
      << mesh.boundary_facets.size() << " labelled " << (D == 2 ? "edges" : "triangles") << "\n";
  out << "labels:\n";
  for(const auto& [label, use] : setup.labels) {
    const auto name = mesh.label_names.find(label);
    out << "  " << label;
    if(name != mesh.label_names.end())
      out << " '" << name->second << "'";
    out << ":";
    if(use.boundary_facets)
      out << " " << use.boundary_facets << " boundary " << (D == 2 ? "edges" : "triangles");
    if(use.interior_facets)
      out << " " << use.interior_facets << " interior " << (D == 2 ? "edges" : "triangles") << " (ignored)";
    if(use.elements)
      out << " " << use.elements << " " << (D == 2 ? "triangles" : "tetrahedra");
    out << "\n";
  }
  out << "orientation: " << setup.problems.positive << " positive, " << setup.problems.negative << " negative, "
      << setup.problems.degenerate.size() << " degenerate (exact)\n";
  const auto& p = setup.problems;
  out << "element checks (exact): " << p.degenerate.size() << " degenerate, " << p.mixed_orientation.size()
      << " oriented against the majority, " << p.overlapping.size() << " overlapping a neighbour, "
      << p.non_manifold_facets << " " << (D == 2 ? "edges" : "triangles") << " in more than two "
      << (D == 2 ? "triangles" : "tetrahedra") << "\n";
  if(!p.valid()) {
    std::size_t line = 0;
    const std::string problems = describe_problems(setup, &line);
    out << "INVALID\n";
    err << "spring-motion: " << Input_error(path, line, problems).what() << "\n";
    return exit_invalid;
  }
  const auto& net = setup.network;
  std::size_t boundary_vertices = 0, labelled_boundary_vertices = 0;
  for(Index i = 0; i < net.number_of_vertices(); ++i)
    if(net.on_boundary[i]) {
      ++boundary_vertices;
      labelled_boundary_vertices += net.vertex_label_offsets[i + 1] > net.vertex_label_offsets[i];
    }
  out << "boundary: " << net.boundary_facets.size() << " " << (D == 2 ? "edges" : "triangles") << ", "
      << boundary_vertices << " vertices (" << labelled_boundary_vertices << " on a labelled part)\n";
  double min_measure = std::numeric_limits<double>::infinity(), max_measure = 0;
  for(std::size_t t = 0; t < net.number_of_elements(); ++t) {
    const double v = std::abs(internal::signed_measure(internal::element_points<D>(net.elements, net.points, t)));
    min_measure = std::min(min_measure, v);
    max_measure = std::max(max_measure, v);
  }
  double min_edge = std::numeric_limits<double>::infinity(), max_edge = 0;
  for(const auto& e : net.edges) {
    double l2 = 0;
    for(int c = 0; c < D; ++c)
      l2 += (net.points[e[0]][c] - net.points[e[1]][c]) * (net.points[e[0]][c] - net.points[e[1]][c]);
    min_edge = std::min(min_edge, std::sqrt(l2));
    max_edge = std::max(max_edge, std::sqrt(l2));
  }
  out << (D == 2 ? "area" : "volume") << ": min " << fmt("%.6g", min_measure) << ", max " << fmt("%.6g", max_measure)
      << "; edge length: min " << fmt("%.6g", min_edge) << ", max " << fmt("%.6g", max_edge) << "\n";
  const auto r = element_skewness(net, net.points);
  out << "equiangle skewness R (0 equilateral, 1 degenerate):\n";
  print_histogram(out, "all elements", skewness_histogram(r, [](std::size_t) { return true; }));
  std::vector<char> touches(net.number_of_elements(), 0);
  for(std::size_t t = 0; t < net.number_of_elements(); ++t)
    for(Index v : net.elements[t])
      touches[t] |= net.on_boundary[v];
  print_histogram(out, "elements touching the boundary", skewness_histogram(r, [&](std::size_t t) { return touches[t] != 0; }));
  out << "valid\n";
  return exit_success;
}

} // namespace

int check_command(const std::vector<std::string>& arguments, std::ostream& out, std::ostream& err)
{
  const Arguments a(arguments, {{"help", false}});
  if(a.has("help")) {
    out << check_help();
    return exit_success;
  }
  if(a.operands().size() != 1)
    throw Usage_error(a.operands().empty() ? "expected a mesh file (MESH)" : "expected one mesh file");
  const std::string& path = a.operands()[0];
  const Mesh_file file = read_mesh(path);
  return file.dimension == 2 ? check<2>(path, file, out, err) : check<3>(path, file, out, err);
}

} // namespace cli
} // namespace spring_motion
