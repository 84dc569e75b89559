// Copyright (c) 2026 SpringMotion developers.
// The Python module `spring_motion` (pybind11): read a mesh, deform it as
// `spring-motion deform` does, write it. Arrays cross the boundary as numpy
// arrays (copies: a Mesh stays immutable, so one read can feed many runs).
// Reference: python/README.md.
#include <spring_motion/Deform_report.h>
#include <spring_motion/Error.h>
#include <spring_motion/Input_error.h>
#include <spring_motion/Spring_network.h>
#include <spring_motion/Vertex_role.h>
#include <spring_motion/deform.h>
#include <spring_motion/io/read_mesh.h>
#include <spring_motion/io/write_mesh.h>
#include <spring_motion/motion/Pitch_motion.h>
#include <spring_motion/stiffness/model_by_name.h>

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <limits>
#include <map>
#include <memory>
#include <optional>
#include <sstream>
#include <string>
#include <utility>
#include <variant>
#include <vector>

#ifndef SPRING_MOTION_VERSION
#define SPRING_MOTION_VERSION "unknown"
#endif

namespace py = pybind11;

namespace spring_motion {
namespace python {
namespace {

const char* facet_plural(int d) { return d == 2 ? "edges" : "triangles"; }
const char* element_plural(int d) { return d == 2 ? "triangles" : "tetrahedra"; }

// The library appends " [source.cpp:LINE]" to the messages of its checks:
// useful in a debugger, noise for a Python user (the command line drops it too).
std::string without_source_location(std::string message)
{
  if(!message.empty() && message.back() == ']') {
    const auto open = message.rfind(" [");
    if(open != std::string::npos && message.find(':', open) != std::string::npos)
      message.erase(open);
  }
  return message;
}

/// A mesh read from a file. Immutable from Python; shared, so that results
/// can refer back to it without a copy.
struct Mesh
{
  std::shared_ptr<const Mesh_file> file;
  std::string path;
};

template <int D>
py::array_t<double> points_array(const std::vector<std::array<double, D>>& points)
{
  py::array_t<double> a({py::ssize_t(points.size()), py::ssize_t(D)});
  auto r = a.mutable_unchecked<2>();
  for(std::size_t i = 0; i < points.size(); ++i)
    for(int c = 0; c < D; ++c)
      r(py::ssize_t(i), c) = points[i][std::size_t(c)];
  return a;
}

// Vertex indices as int64: numpy's default integer, safe for any arithmetic
// a user does with them.
template <std::size_t K>
py::array_t<std::int64_t> index_array(const std::vector<std::array<std::uint32_t, K>>& rows)
{
  py::array_t<std::int64_t> a({py::ssize_t(rows.size()), py::ssize_t(K)});
  auto r = a.mutable_unchecked<2>();
  for(std::size_t i = 0; i < rows.size(); ++i)
    for(std::size_t c = 0; c < K; ++c)
      r(py::ssize_t(i), py::ssize_t(c)) = rows[i][c];
  return a;
}

template <class T>
py::array_t<std::int64_t> int_array(const std::vector<T>& v)
{
  py::array_t<std::int64_t> a(py::ssize_t(v.size()));
  auto r = a.mutable_unchecked<1>();
  for(std::size_t i = 0; i < v.size(); ++i)
    r(py::ssize_t(i)) = std::int64_t(v[i]);
  return a;
}

/// An (n, D) float64 array, checked, as points.
template <int D>
std::vector<std::array<double, D>> to_points(const py::handle& object, std::size_t n, const char* what)
{
  const auto a = py::array_t<double, py::array::c_style | py::array::forcecast>::ensure(object);
  if(!a || a.ndim() != 2 || a.shape(0) != py::ssize_t(n) || a.shape(1) != D) {
    std::ostringstream msg;
    msg << what << ": expected an array of shape (" << n << ", " << D << ")";
    if(a) {
      msg << ", found shape (";
      for(py::ssize_t k = 0; k < a.ndim(); ++k)
        msg << (k ? ", " : "") << a.shape(k);
      msg << (a.ndim() == 1 ? ",)" : ")");
    }
    throw py::value_error(msg.str());
  }
  const auto r = a.template unchecked<2>();
  std::vector<std::array<double, D>> out(n);
  for(std::size_t i = 0; i < n; ++i)
    for(int c = 0; c < D; ++c) {
      out[i][std::size_t(c)] = r(py::ssize_t(i), c);
      if(!std::isfinite(out[i][std::size_t(c)]))
        throw py::value_error(std::string(what) + ": row " + std::to_string(i) + " is not finite");
    }
  return out;
}

/// A point given as a sequence of numbers, for a D-dimensional mesh (a third
/// coordinate equal to 0 is accepted in 2D, as on the command line).
template <int D>
std::array<double, D> to_point(const std::vector<double>& v, const char* option)
{
  if(v.size() < 2 || v.size() > 3 || (D == 3 && v.size() != 3) || (D == 2 && v.size() == 3 && v[2] != 0))
    throw py::value_error(std::string(option) + ": the mesh is " + (D == 2 ? "2D, expected 2 numbers (or a third one "
                                                                             "equal to 0)"
                                                                           : "3D, expected 3 numbers"));
  std::array<double, D> p;
  for(int c = 0; c < D; ++c) {
    p[std::size_t(c)] = v[std::size_t(c)];
    if(!std::isfinite(p[std::size_t(c)]))
      throw py::value_error(std::string(option) + ": expected finite numbers");
  }
  return p;
}

// ---- labels and roles: the command line's rules (docs/cli.md) --------------

/// How the file uses a label: boundary facets, facets inside the mesh, elements.
struct Label_use
{
  std::size_t boundary_facets = 0, interior_facets = 0, elements = 0;
};

/// The labelled facets that lie on the boundary (those inside the mesh are
/// ignored, as on the command line), and how every label is used.
template <int D>
struct Boundary_labels
{
  std::vector<Labeled_facet<D>> boundary;
  std::map<int, Label_use> uses;
};

template <int D>
Boundary_labels<D> find_boundary_labels(const Indexed_mesh<D>& mesh)
{
  using Key = std::array<std::uint32_t, D>;
  std::map<Key, int> facet_count;
  for(const auto& e : mesh.elements)
    for(int k = 0; k <= D; ++k) {
      Key key; // the facet opposite vertex k
      for(int c = 0, j = 0; c <= D; ++c)
        if(c != k)
          key[std::size_t(j++)] = e[std::size_t(c)];
      std::sort(key.begin(), key.end());
      ++facet_count[key];
    }
  Boundary_labels<D> out;
  for(std::size_t t = 0; t < mesh.elements.size(); ++t)
    ++out.uses[t < mesh.element_labels.size() ? mesh.element_labels[t] : 0].elements;
  for(std::size_t f = 0; f < mesh.boundary_facets.size(); ++f) {
    Key key = mesh.boundary_facets[f];
    std::sort(key.begin(), key.end());
    const int label = f < mesh.boundary_labels.size() ? mesh.boundary_labels[f] : 0;
    const auto it = facet_count.find(key);
    if(it == facet_count.end())
      throw Input_error("", 0, "a labelled facet is not a side of any element"); // read_mesh() rules this out
    if(it->second > 1) {
      ++out.uses[label].interior_facets;
      continue;
    }
    ++out.uses[label].boundary_facets;
    Labeled_facet<D> lf;
    lf.label = label;
    for(int c = 0; c < D; ++c)
      lf.vertices[std::size_t(c)] = mesh.boundary_facets[f][std::size_t(c)];
    out.boundary.push_back(lf);
  }
  return out;
}

using Label = std::variant<long long, std::string>;

/// `moving=` / `fixed=`: one label or a sequence of them, each a number or
/// a name (a physical name wins over a number, as on the command line).
std::vector<Label> to_labels(const py::handle& object, const char* option)
{
  std::vector<Label> out;
  const auto one = [&](const py::handle& item) {
    if(py::isinstance<py::str>(item))
      out.emplace_back(item.cast<std::string>());
    else if(py::isinstance<py::int_>(item) && !py::isinstance<py::bool_>(item))
      out.emplace_back(item.cast<long long>());
    else
      throw py::type_error(std::string(option) + ": expected labels as numbers or names, found " +
                           std::string(py::str(py::type::of(item).attr("__name__"))));
  };
  if(py::isinstance<py::str>(object) || py::isinstance<py::int_>(object))
    one(object);
  else {
    if(!py::isinstance<py::iterable>(object))
      throw py::type_error(std::string(option) + ": expected a label or a sequence of labels");
    for(const auto item : object)
      one(item);
  }
  return out;
}

template <int D>
std::string describe_boundary_labels(const Indexed_mesh<D>& mesh, const Boundary_labels<D>& b)
{
  std::ostringstream out;
  bool first = true;
  for(const auto& [label, use] : b.uses) {
    if(use.boundary_facets == 0)
      continue;
    out << (first ? "" : ", ") << label;
    const auto name = mesh.label_names.find(label);
    if(name != mesh.label_names.end())
      out << " '" << name->second << "'";
    out << " (" << use.boundary_facets << " " << (use.boundary_facets == 1 ? (D == 2 ? "edge" : "triangle")
                                                                            : facet_plural(D))
        << ")";
    first = false;
  }
  if(first)
    out << "none: the file labels no boundary " << facet_plural(D);
  return out.str();
}

template <int D>
std::vector<int> resolve_labels(const std::string& path, const Indexed_mesh<D>& mesh, const Boundary_labels<D>& b,
                                const char* option, const std::vector<Label>& items)
{
  const std::string valid = std::string("; expected labels (numbers or names) of boundary ") + facet_plural(D) +
                            ": " + describe_boundary_labels(mesh, b);
  if(items.empty())
    throw Input_error(path, 0, std::string(option) + " names no label (an empty set)" + valid);
  std::vector<int> labels;
  for(const Label& item : items) {
    std::string text;
    long long value = 0;
    bool found = false;
    if(const auto* name = std::get_if<std::string>(&item)) {
      text = *name;
      for(const auto& [number, label_name] : mesh.label_names)
        if(label_name == *name) {
          value = number;
          found = true;
        }
      if(!found) {
        char* end = nullptr;
        value = std::strtoll(name->c_str(), &end, 10);
        if(name->empty() || end != name->c_str() + name->size())
          throw Input_error(path, 0, std::string(option) + ": unknown label '" + text + "'" + valid);
      }
    } else {
      value = std::get<long long>(item);
      text = std::to_string(value);
    }
    const auto it = value >= std::numeric_limits<int>::min() && value <= std::numeric_limits<int>::max()
                        ? b.uses.find(int(value))
                        : b.uses.end();
    if(it == b.uses.end())
      throw Input_error(path, 0, std::string(option) + ": unknown label '" + text + "'" + valid);
    if(it->second.boundary_facets == 0)
      throw Input_error(path, 0, std::string(option) + ": label '" + text + "' marks " +
                                     (it->second.interior_facets > 0 ? std::string(facet_plural(D)) +
                                                                           " inside the mesh, not on its boundary"
                                                                     : std::string(element_plural(D)) +
                                                                           ", not boundary " + facet_plural(D)) +
                                     valid);
    labels.push_back(int(value));
  }
  return labels;
}

/// The command line's rules (Boundary_label_roles): boundary vertices on a
/// moving part move; with `fixed` given only those on a fixed part are fixed
/// (the rest of the boundary is free), otherwise the whole remaining boundary
/// is fixed, except what slides. Interior vertices are free.
template <int D>
std::vector<Vertex_role> command_line_roles(const Spring_network<D>& net, const std::vector<int>& moving,
                                            const std::optional<std::vector<int>>& fixed,
                                            const std::vector<int>& sliding = {})
{
  Boundary_label_roles rules;
  rules.moving = moving;
  rules.sliding = sliding;
  if(fixed) {
    rules.fixed = *fixed;
    rules.fixed_given = true;
  }
  return assign_roles(net, rules);
}

/// The checks of Network_deformer's constructor, with the command line's
/// messages: the file's vertex numbers and the point, not network indices.
template <int D>
void check_roles(const Mesh& m, const Spring_network<D>& net, const std::vector<Vertex_role>& roles)
{
  std::size_t moving = 0; // among the vertices some element uses
  for(const auto& e : net.elements)
    for(Index v : e)
      moving += roles[v] == Vertex_role::moving;
  if(moving == 0)
    throw Input_error(m.path, 0, "no vertex moves (the moving set is empty): expected a moving boundary part "
                                 "with at least one vertex");
  const std::vector<Index> undetermined = undetermined_vertices(net, roles);
  if(!undetermined.empty()) {
    const Index v = undetermined.front();
    std::ostringstream msg;
    msg << undetermined.size() << " free vertices (for instance vertex " << m.file->vertex_ids[v] << " at (";
    for(int c = 0; c < D; ++c)
      msg << (c ? ", " : "") << net.points[v][std::size_t(c)];
    msg << ")) are connected to no moving or fixed vertex, so their motion is undetermined (a singular system): "
           "expected every part of the mesh to touch a moving or fixed boundary (see fixed=)";
    throw Input_error(m.path, 0, msg.str());
  }
}

// ---- motions -------------------------------------------------------------------

/// `displacement=`: each moving vertex goes to p0 + t * d, looked up by its
/// initial point (a motion sees points, not indices).
template <int D>
struct Displacement_motion
{
  std::map<std::array<double, D>, std::array<double, D>> by_point;

  std::array<double, D> operator()(const std::array<double, D>& p0, double t) const
  {
    const auto it = by_point.find(p0);
    SPRING_MOTION_CHECK(it != by_point.end(), "no displacement for a moving vertex");
    std::array<double, D> q;
    for(std::size_t c = 0; c < std::size_t(D); ++c)
      q[c] = p0[c] + t * it->second[c];
    return q;
  }
};

struct Deform_arguments
{
  std::vector<Label> moving;
  std::optional<std::vector<Label>> fixed;
  std::vector<Label> sliding;
  std::string model;
  std::optional<double> pitch;
  std::optional<std::vector<double>> center, axis, translate;
  py::object displacement;
  Deform_options options;
};

std::string report_text(const Deform_report& report)
{
  std::ostringstream out;
  write_report_json(report, out);
  return out.str();
}

template <int D>
std::pair<std::vector<std::array<double, D>>, std::string> run_deform(const Mesh& m, const Deform_arguments& a)
{
  const Indexed_mesh<D>& mesh = m.file->template mesh<D>();
  // motion arguments are checked before labels, as the command line checks its options first
  std::optional<Pitch_motion<D>> pitch;
  std::optional<Translation_motion<D>> translation;
  std::vector<std::array<double, D>> displacement;
  if(a.pitch) {
    pitch.emplace(*a.pitch, to_point<D>(*a.center, "center"));
    if(a.axis) {
      const auto& v = *a.axis;
      if(v.size() != 3 || (v[0] == 0 && v[1] == 0 && v[2] == 0))
        throw py::value_error("axis: expected a non-zero vector of 3 numbers");
      if constexpr(D == 2) {
        if(v[0] != 0 || v[1] != 0 || v[2] <= 0)
          throw py::value_error("axis: a 2D mesh turns about +z (counter-clockwise positive), expected no axis or "
                                "(0, 0, 1); for a clockwise pitch give a negative angle");
      } else
        pitch->axis = {v[0], v[1], v[2]};
    }
  } else if(a.translate) {
    translation.emplace();
    translation->displacement = to_point<D>(*a.translate, "translate");
  } else
    displacement = to_points<D>(a.displacement, mesh.points.size(), "displacement");

  const Boundary_labels<D> b = find_boundary_labels(mesh);
  const std::vector<int> moving = resolve_labels(m.path, mesh, b, "moving", a.moving);
  std::optional<std::vector<int>> fixed;
  if(a.fixed)
    fixed = resolve_labels(m.path, mesh, b, "fixed", *a.fixed);
  std::vector<int> sliding;
  if(!a.sliding.empty())
    sliding = resolve_labels(m.path, mesh, b, "sliding", a.sliding);

  std::optional<Displacement_motion<D>> by_point;
  std::vector<std::array<double, D>> positions;
  std::string report;
  {
    // Everything from here on touches no Python object.
    py::gil_scoped_release release;
    try {
      // All the file's vertices, in file order (unused ones stay put), so that
      // positions line up with mesh.points, as in the command line's output.
      Spring_network<D> net = make_spring_network<D>(mesh.points, mesh.elements, b.boundary);
      std::vector<Vertex_role> roles = command_line_roles(net, moving, fixed, sliding);
      if(!pitch && !translation) {
        by_point.emplace();
        for(Index v = 0; v < roles.size(); ++v)
          if(roles[v] == Vertex_role::moving) {
            const auto [it, inserted] = by_point->by_point.emplace(net.points[v], displacement[v]);
            if(!inserted && it->second != displacement[v])
              throw Input_error(m.path, 0, "displacement: moving vertex " + std::to_string(m.file->vertex_ids[v]) +
                                               " lies at the same point as another moving vertex with a different "
                                               "displacement: expected one displacement per point");
          }
      }
      check_roles(m, net, roles);
      Network_deformer<D> deformer(std::move(net), std::move(roles));
      const Deform_report r = with_model(a.model, [&](const auto& model) {
        if(pitch)
          return deformer.run(*pitch, model, a.options);
        if(translation)
          return deformer.run(*translation, model, a.options);
        return deformer.run(*by_point, model, a.options);
      });
      positions = deformer.positions();
      report = report_text(r);
    } catch(const Input_error&) {
      throw;
    } catch(const Error& e) {
      // the library's checks (no moving vertex, an undetermined region, a
      // model's value): about this mesh, so named after its file as the
      // command line does
      throw Input_error(m.path, 0, without_source_location(e.what()));
    }
  }
  return {std::move(positions), std::move(report)};
}

/// The command line's --solver, --omega, --tolerance, ... (docs/cli.md).
Deform_options deform_options(const std::string& solver, const std::optional<double>& omega,
                              const std::optional<double>& tolerance, const std::optional<long long>& max_iterations,
                              long long max_substep_halvings, int threads)
{
  Deform_options o;
  if(solver == "paper")
    o.solver = Solver_options::paper();
  else if(solver == "sor")
    o.solver.method = Solver_method::sor;
  else if(solver == "cg-sgs")
    o.solver.preconditioner = Preconditioner::symmetric_gauss_seidel;
  else if(solver != "cg")
    throw py::value_error("solver: expected cg, cg-sgs, sor or paper, found '" + solver + "'");
  if(omega) {
    if(solver == "cg" || solver == "cg-sgs")
      throw py::value_error("omega is the relaxation factor of SOR: use it with solver='sor' or 'paper'");
    if(!(*omega > 0 && *omega < 2))
      throw py::value_error("omega: expected a number in (0, 2)");
    o.solver.relaxation_factor = *omega;
  }
  if(tolerance) {
    if(!(*tolerance > 0) || !std::isfinite(*tolerance))
      throw py::value_error("tolerance: expected a positive number");
    o.solver.tolerance = *tolerance;
  }
  if(max_iterations) {
    if(*max_iterations < 1)
      throw py::value_error("max_iterations: expected a positive number");
    o.solver.max_iterations = std::size_t(*max_iterations);
  }
  if(max_substep_halvings < 0 || max_substep_halvings > 20)
    throw py::value_error("max_substep_halvings: expected 0 to 20");
  o.max_substep_halvings = std::size_t(max_substep_halvings);
  if(threads < 0)
    throw py::value_error("threads: expected 0 (chosen by measurement) or a positive number");
  o.solver.threads = threads;
  return o;
}

void check_model_name(const std::string& model)
{
  const auto& names = model_names();
  if(std::find(names.begin(), names.end(), model) == names.end()) {
    std::string valid;
    for(const auto& n : names)
      valid += (valid.empty() ? "" : ", ") + n;
    throw py::value_error("model: unknown stiffness model '" + model + "': expected one of " + valid);
  }
}

py::tuple deform(const Mesh& m, const py::object& moving, const py::object& fixed, const py::object& sliding,
                 const std::string& model,
                 const std::optional<double>& pitch, const std::optional<std::vector<double>>& center,
                 const std::optional<std::vector<double>>& axis, const std::optional<std::vector<double>>& translate,
                 const py::object& displacement, long long steps, const std::string& solver,
                 const std::optional<double>& omega, const std::optional<double>& tolerance,
                 const std::optional<long long>& max_iterations, long long max_substep_halvings, int threads)
{
  Deform_arguments a;
  const int motions = int(pitch.has_value()) + int(translate.has_value()) + int(!displacement.is_none());
  if(motions != 1)
    throw py::value_error(motions == 0 ? "expected a motion: pitch=DEG with center=(x, y[, z]), translate=(dx, dy[, dz]) "
                                         "or displacement=ARRAY"
                                       : "expected one motion, found several of pitch, translate, displacement");
  if(pitch && !std::isfinite(*pitch))
    throw py::value_error("pitch: expected a finite angle in degrees");
  if(pitch && !center)
    throw py::value_error("pitch needs center=(x, y) (2D) or (x, y, z) (3D): the point the rotation turns about");
  if(!pitch && (center || axis))
    throw py::value_error("center and axis go with pitch only");
  if(moving.is_none())
    throw py::value_error("expected moving=: the boundary labels (numbers or names) that move");
  a.moving = to_labels(moving, "moving");
  if(!fixed.is_none())
    a.fixed = to_labels(fixed, "fixed");
  if(!sliding.is_none())
    a.sliding = to_labels(sliding, "sliding");
  check_model_name(model);
  a.model = model;
  a.pitch = pitch;
  a.center = center;
  a.axis = axis;
  a.translate = translate;
  a.displacement = displacement;
  if(steps < 1)
    throw py::value_error("steps: expected a positive number of steps, found " + std::to_string(steps));
  a.options = deform_options(solver, omega, tolerance, max_iterations, max_substep_halvings, threads);
  a.options.number_of_steps = std::size_t(steps);

  py::object positions;
  std::string report;
  if(m.file->dimension == 2) {
    auto r = run_deform<2>(m, a);
    positions = points_array<2>(r.first);
    report = std::move(r.second);
  } else {
    auto r = run_deform<3>(m, a);
    positions = points_array<3>(r.first);
    report = std::move(r.second);
  }
  return py::make_tuple(positions, py::module_::import("json").attr("loads")(report));
}

/// `point_data=` / `cell_data=`: {name: array of shape (count,) or (count, k)}.
std::vector<Data_array> to_data_arrays(const py::object& object, std::size_t count, const char* what)
{
  std::vector<Data_array> out;
  if(object.is_none())
    return out;
  for(const auto& [key, value] : object.cast<py::dict>()) {
    Data_array d;
    d.name = key.cast<std::string>();
    const auto a = py::array_t<double, py::array::c_style | py::array::forcecast>::ensure(value);
    if(!a || (a.ndim() != 1 && a.ndim() != 2) || a.shape(0) != py::ssize_t(count) ||
       (a.ndim() == 2 && (a.shape(1) < 1 || a.shape(1) > 9)))
      throw py::value_error(std::string(what) + " '" + d.name + "': expected an array of shape (" +
                            std::to_string(count) + ",) or (" + std::to_string(count) + ", k), 1 <= k <= 9");
    d.components = a.ndim() == 1 ? 1 : int(a.shape(1));
    d.values.assign(a.data(), a.data() + a.size());
    out.push_back(std::move(d));
  }
  return out;
}

template <int D>
void write_with(const std::string& path, const Mesh& m, const py::object& positions, const py::object& point_data,
                const py::object& cell_data)
{
  Indexed_mesh<D> mesh = m.file->template mesh<D>();
  if(!positions.is_none())
    mesh.points = to_points<D>(positions, mesh.points.size(), "positions");
  const auto pd = to_data_arrays(point_data, mesh.points.size(), "point_data");
  const auto cd = to_data_arrays(cell_data, mesh.elements.size(), "cell_data");
  py::gil_scoped_release release;
  write_mesh<D>(path, mesh, pd, cd);
}

void write(const std::string& path, const Mesh& m, const py::object& positions, const py::object& point_data,
           const py::object& cell_data)
{
  if(m.file->dimension == 2)
    write_with<2>(path, m, positions, point_data, cell_data);
  else
    write_with<3>(path, m, positions, point_data, cell_data);
}


// ---- the per-time-step deformer ------------------------------------------------

/// What one Deformer.move() did: the library's Step_report.
struct Step
{
  Step_report report;
  std::vector<std::size_t> inverted_elements;
  bool valid() const { return report.inverted == 0; }
};

py::dict step_dict(const Step& s)
{
  const Step_report& r = s.report;
  py::dict d;
  d["valid"] = s.valid();
  d["step"] = r.step;
  d["moves"] = r.fraction;
  d["iterations"] = r.iterations;
  d["converged"] = r.converged;
  d["max_update"] = r.max_update;
  d["residual"] = r.residual;
  d["error_estimate"] = r.error_estimate;
  d["substeps"] = r.substeps;
  d["rejected_attempts"] = r.rejected_attempts;
  d["inverted"] = r.inverted;
  d["threads"] = r.threads;
  d["min_size_ratio"] = r.min_size_ratio;
  d["max_size_ratio"] = r.max_size_ratio;
  d["max_skewness_moving"] = r.max_skewness_moving;
  d["max_skewness_all"] = r.max_skewness_all;
  d["min_angle_deg_moving"] = r.min_angle_deg_moving;
  d["min_angle_deg_all"] = r.min_angle_deg_all;
  d["seconds"] = py::dict(py::arg("stiffness") = r.seconds_stiffness, py::arg("solve") = r.seconds_solve,
                          py::arg("check") = r.seconds_check);
  return d;
}

/// Network_deformer over all the file's vertices in file order (so that
/// indices are mesh.points' rows), with the command line's roles and checks.
class Deformer
{
public:
  Deformer(const Mesh& m, const py::object& moving, const py::object& fixed, const py::object& sliding,
           const std::string& model, Deform_options options)
      : mesh_(m), model_(model), options_(options)
  {
    if(moving.is_none())
      throw py::value_error("expected moving=: the boundary labels (numbers or names) that move");
    check_model_name(model);
    const std::vector<Label> mv = to_labels(moving, "moving");
    std::optional<std::vector<Label>> fx;
    if(!fixed.is_none())
      fx = to_labels(fixed, "fixed");
    std::vector<Label> sl;
    if(!sliding.is_none())
      sl = to_labels(sliding, "sliding");
    if(m.file->dimension == 2)
      d2_ = build<2>(mv, fx, sl);
    else
      d3_ = build<3>(mv, fx, sl);
  }

  int dimension() const { return mesh_.file->dimension; }

  py::array_t<std::int64_t> moving_vertices() const
  {
    return d2_ ? int_array(d2_->moving_vertices()) : int_array(d3_->moving_vertices());
  }

  /// A read-only view of the positions (no copy; `self` keeps it alive).
  static py::array positions(const py::object& self)
  {
    const Deformer& d = self.cast<const Deformer&>();
    const double* data = d.d2_ ? d.d2_->positions().front().data() : d.d3_->positions().front().data();
    const py::ssize_t n = py::ssize_t(d.d2_ ? d.d2_->positions().size() : d.d3_->positions().size());
    const py::ssize_t D = d.dimension();
    py::array a(py::dtype::of<double>(), {n, D}, {D * py::ssize_t(sizeof(double)), py::ssize_t(sizeof(double))},
                data, self);
    a.attr("flags").attr("writeable") = false;
    return a;
  }

  Step move(const py::handle& displacement)
  {
    return d2_ ? move_with<2>(*d2_, displacement) : move_with<3>(*d3_, displacement);
  }

  void reset()
  {
    if(d2_)
      d2_->reset();
    else
      d3_->reset();
  }

  std::size_t sliding_vertices() const
  {
    return d2_ ? d2_->number_of_sliding_vertices() : d3_->number_of_sliding_vertices();
  }

private:
  template <int D>
  std::unique_ptr<Network_deformer<D>> build(const std::vector<Label>& mv, const std::optional<std::vector<Label>>& fx,
                                             const std::vector<Label>& sl)
  {
    const Mesh& m = mesh_;
    const Indexed_mesh<D>& mesh = m.file->template mesh<D>();
    const Boundary_labels<D> b = find_boundary_labels(mesh);
    const std::vector<int> moving = resolve_labels(m.path, mesh, b, "moving", mv);
    std::optional<std::vector<int>> fixed;
    if(fx)
      fixed = resolve_labels(m.path, mesh, b, "fixed", *fx);
    std::vector<int> sliding;
    if(!sl.empty())
      sliding = resolve_labels(m.path, mesh, b, "sliding", sl);
    py::gil_scoped_release release;
    try {
      Spring_network<D> net = make_spring_network<D>(mesh.points, mesh.elements, b.boundary);
      std::vector<Vertex_role> roles = command_line_roles(net, moving, fixed, sliding);
      check_roles(m, net, roles);
      return std::make_unique<Network_deformer<D>>(std::move(net), std::move(roles));
    } catch(const Input_error&) {
      throw;
    } catch(const Error& e) {
      throw Input_error(m.path, 0, without_source_location(e.what()));
    }
  }

  template <int D>
  Step move_with(Network_deformer<D>& d, const py::handle& displacement)
  {
    const auto disp = to_points<D>(displacement, d.moving_vertices().size(), "displacement");
    Step s;
    py::gil_scoped_release release;
    s.report = with_model(model_, [&](const auto& model) { return d.move(disp, model, options_); });
    s.inverted_elements = d.last_inverted_elements();
    return s;
  }

  Mesh mesh_;
  std::string model_;
  Deform_options options_;
  std::unique_ptr<Network_deformer<2>> d2_;
  std::unique_ptr<Network_deformer<3>> d3_;
};

} // namespace
} // namespace python
} // namespace spring_motion

PYBIND11_MODULE(spring_motion, m)
{
  using namespace spring_motion;
  using namespace spring_motion::python;
  m.doc() = "SpringMotion: move the interior of a triangle or tetrahedral mesh by spring analogy "
            "(the Python side of the spring-motion command; see python/README.md).";

  static py::exception<Error> error(m, "Error");
  static py::exception<Input_error> input_error(m, "Input_error", error.ptr());
  error.doc() = "Every error of the library: bad input (Input_error) or a failed check.";
  input_error.doc() = "Bad input, naming the file (and line): attributes file, line, message.";
  py::register_exception_translator([](std::exception_ptr p) {
    try {
      if(p)
        std::rethrow_exception(p);
    } catch(const Input_error& e) {
      py::object instance = py::reinterpret_borrow<py::object>(input_error.ptr())(e.what());
      instance.attr("file") = e.file();
      instance.attr("line") = e.line();
      instance.attr("message") = e.message();
      PyErr_SetObject(input_error.ptr(), instance.ptr());
    } catch(const Error& e) {
      error(without_source_location(e.what()).c_str());
    }
  });

  py::class_<Mesh>(m, "Mesh", "A simplex mesh read from a file (immutable; arrays are copies).")
      .def_property_readonly("dimension", [](const Mesh& x) { return x.file->dimension; })
      .def_property_readonly("path", [](const Mesh& x) { return x.path; })
      .def_property_readonly(
          "points",
          [](const Mesh& x) -> py::object {
            return x.file->dimension == 2 ? py::object(points_array<2>(x.file->mesh_2.points))
                                          : py::object(points_array<3>(x.file->mesh_3.points));
          },
          "(n, d) float64 array of the vertices' coordinates, in file order")
      .def_property_readonly(
          "elements",
          [](const Mesh& x) -> py::object {
            return x.file->dimension == 2 ? py::object(index_array(x.file->mesh_2.elements))
                                          : py::object(index_array(x.file->mesh_3.elements));
          },
          "(m, d+1) int64 array of 0-based vertex indices (triangles or tetrahedra)")
      .def_property_readonly(
          "element_labels",
          [](const Mesh& x) {
            return int_array(x.file->dimension == 2 ? x.file->mesh_2.element_labels : x.file->mesh_3.element_labels);
          },
          "(m,) int64 array: each element's label (0 when the file gives none)")
      .def_property_readonly(
          "boundary_facets",
          [](const Mesh& x) -> py::object {
            return x.file->dimension == 2 ? py::object(index_array(x.file->mesh_2.boundary_facets))
                                          : py::object(index_array(x.file->mesh_3.boundary_facets));
          },
          "(k, d) int64 array: the labelled facets (edges in 2D, triangles in 3D)")
      .def_property_readonly(
          "boundary_labels",
          [](const Mesh& x) {
            return int_array(x.file->dimension == 2 ? x.file->mesh_2.boundary_labels
                                                    : x.file->mesh_3.boundary_labels);
          },
          "(k,) int64 array: the label of each boundary facet")
      .def_property_readonly(
          "label_names",
          [](const Mesh& x) {
            return x.file->dimension == 2 ? x.file->mesh_2.label_names : x.file->mesh_3.label_names;
          },
          "{label: name}: the file's physical names")
      .def_property_readonly(
          "vertex_ids", [](const Mesh& x) { return int_array(x.file->vertex_ids); },
          "(n,) int64 array: the number the file gives each vertex (Medit: 1-based index; Gmsh: node tag)")
      .def("__repr__", [](const Mesh& x) {
        const std::size_t n = x.file->dimension == 2 ? x.file->mesh_2.points.size() : x.file->mesh_3.points.size();
        const std::size_t e = x.file->dimension == 2 ? x.file->mesh_2.elements.size() : x.file->mesh_3.elements.size();
        return "<spring_motion.Mesh '" + x.path + "': " + std::to_string(x.file->dimension) + "D, " +
               std::to_string(n) + " vertices, " + std::to_string(e) + " " + element_plural(x.file->dimension) + ">";
      });

  m.def(
      "read_mesh",
      [](const py::object& path) {
        const std::string p = py::str(py::module_::import("os").attr("fspath")(path));
        std::shared_ptr<Mesh_file> file;
        {
          py::gil_scoped_release release;
          file = std::make_shared<Mesh_file>(read_mesh(p));
        }
        return Mesh{std::move(file), p};
      },
      py::arg("path"),
      "Reads a mesh file (.mesh: Medit; .msh: Gmsh), as spring-motion does. Raises Input_error naming the file.");

  m.def(
      "deform",
      [](const Mesh& mesh, const py::object& moving, const py::object& fixed, const py::object& sliding,
         const std::string& model, std::optional<double> pitch, std::optional<std::vector<double>> center,
         std::optional<std::vector<double>> axis, std::optional<std::vector<double>> translate,
         const py::object& displacement, long long steps, const std::string& solver, std::optional<double> omega,
         std::optional<double> tolerance, std::optional<long long> max_iterations, long long max_substep_halvings,
         int threads) {
        return deform(mesh, moving, fixed, sliding, model, pitch, center, axis, translate, displacement, steps, solver, omega,
                      tolerance, max_iterations, max_substep_halvings, threads);
      },
      py::arg("mesh"), py::arg("moving") = py::none(), py::arg("fixed") = py::none(),
      py::arg("sliding") = py::none(), py::kw_only(), py::arg("model") = "grid_scaled", py::arg("pitch") = py::none(), py::arg("center") = py::none(),
      py::arg("axis") = py::none(), py::arg("translate") = py::none(), py::arg("displacement") = py::none(),
      py::arg("steps") = 100, py::arg("solver") = "cg", py::arg("omega") = py::none(),
      py::arg("tolerance") = py::none(), py::arg("max_iterations") = py::none(),
      py::arg("max_substep_halvings") = 0, py::arg("threads") = 0,
      R"(Moves the mesh's interior while its `moving` boundary follows the motion, as
`spring-motion deform` does (same options, same numbers). Returns
(positions, report): the (n, d) final positions (the last valid state if a
step inverted an element) and the JSON report (docs/report_format.md) as a dict.

moving, fixed, sliding: a label or a sequence of labels, each a number or a
physical name. The boundary not named moving (or sliding) is fixed; with
`fixed` given, only those parts are fixed and the rest of the boundary is
free. Vertices of `sliding` parts (planar: a symmetry plane) move within
their plane.
One motion: pitch=DEG with center=(x, y[, z]) (and axis=(ax, ay, az) in 3D),
translate=(dx, dy[, dz]), or displacement=(n, d) array (the final displacement
of each moving vertex; other rows are ignored).
The GIL is released while the run solves.)");


  py::class_<Step>(m, "Step", "What one Deformer.move() did (the library's step report).")
      .def_property_readonly("valid", &Step::valid,
                             "False when the step inverted an element: the positions stayed at the last valid state")
      .def_property_readonly("step", [](const Step& s) { return s.report.step; }, "calls of move() so far, this one included")
      .def_property_readonly("iterations", [](const Step& s) { return s.report.iterations; })
      .def_property_readonly("converged", [](const Step& s) { return s.report.converged; })
      .def_property_readonly("error_estimate", [](const Step& s) { return s.report.error_estimate; })
      .def_property_readonly("residual", [](const Step& s) { return s.report.residual; })
      .def_property_readonly("substeps", [](const Step& s) { return s.report.substeps; })
      .def_property_readonly("rejected_attempts", [](const Step& s) { return s.report.rejected_attempts; })
      .def_property_readonly("inverted", [](const Step& s) { return s.report.inverted; },
                             "elements the rejected step inverted (0 for a valid step)")
      .def_property_readonly("inverted_elements", [](const Step& s) { return int_array(s.inverted_elements); },
                             "their indices (rows of mesh.elements)")
      .def_property_readonly("threads", [](const Step& s) { return s.report.threads; })
      .def_property_readonly("min_size_ratio", [](const Step& s) { return s.report.min_size_ratio; })
      .def_property_readonly("max_skewness_moving", [](const Step& s) { return s.report.max_skewness_moving; })
      .def_property_readonly("min_angle_deg_moving", [](const Step& s) { return s.report.min_angle_deg_moving; })
      .def("as_dict", &step_dict, "every field as a dict")
      .def("__repr__", [](const Step& s) {
        return std::string("<spring_motion.Step ") + (s.valid() ? "valid" : "INVALID") + ", " +
               std::to_string(s.report.iterations) + " iterations>";
      });

  py::class_<Deformer>(m, "Deformer",
                       R"(A mesh moved time step by time step (the library's Network_deformer).

Built once (spring network, ordering, solver state); each move(displacement)
places the moving vertices at their INITIAL positions plus `displacement`
(so nothing drifts), moves the rest with the model, checks every element
exactly and, if one inverted, keeps the last valid positions and says so.)")
      .def(py::init([](const Mesh& mesh, const py::object& moving, const py::object& fixed, const py::object& sliding,
                       const std::string& model, const std::string& solver, std::optional<double> omega,
                       std::optional<double> tolerance, std::optional<long long> max_iterations,
                       long long max_substep_halvings, int threads) {
             return std::make_unique<Deformer>(
                 mesh, moving, fixed, sliding, model,
                 deform_options(solver, omega, tolerance, max_iterations, max_substep_halvings, threads));
           }),
           py::arg("mesh"), py::arg("moving") = py::none(), py::arg("fixed") = py::none(),
           py::arg("sliding") = py::none(), py::kw_only(), py::arg("model") = "grid_scaled",
           py::arg("solver") = "cg", py::arg("omega") = py::none(), py::arg("tolerance") = py::none(),
           py::arg("max_iterations") = py::none(), py::arg("max_substep_halvings") = 0, py::arg("threads") = 0,
           R"(moving, fixed, sliding: labels (numbers or names) as in deform(); vertices of
`sliding` parts (planar ones: symmetry planes) move within their plane.
model and the solver options as in deform().)")
      .def_property_readonly("dimension", &Deformer::dimension)
      .def_property_readonly("moving_vertices", &Deformer::moving_vertices,
                             "indices into mesh.points of the moving vertices, in the order move() takes them")
      .def_property_readonly("positions", &Deformer::positions,
                             "(n, d) read-only view of the current positions (no copy: it changes with move())")
      .def_property_readonly("sliding_vertices", &Deformer::sliding_vertices, "how many vertices slide")
      .def("move", &Deformer::move, py::arg("displacement"),
           R"(One time step: `displacement` is a (len(moving_vertices), d) array, the
displacement of each moving vertex from its initial position. Returns a Step;
an invalid step (step.valid False) leaves the positions at the last valid
state and does not raise. The GIL is released while it runs.)")
      .def("reset", &Deformer::reset, "back to the initial mesh");

  m.def(
      "write_mesh",
      [](const py::object& path, const Mesh& mesh, const py::object& positions, const py::object& point_data,
         const py::object& cell_data) {
        write(py::str(py::module_::import("os").attr("fspath")(path)), mesh, positions, point_data, cell_data);
      },
      py::arg("path"), py::arg("mesh"), py::arg("positions") = py::none(), py::kw_only(),
      py::arg("point_data") = py::none(), py::arg("cell_data") = py::none(),
      R"(Writes `mesh` (with `positions` instead of its points, when given) by
extension: .vtu (with point_data / cell_data: {name: (count,) or (count, k)
array}) or .mesh (Medit). The file is written whole or not at all.)");

  m.attr("model_names") = model_names();
  m.attr("__version__") = SPRING_MOTION_VERSION;
}
