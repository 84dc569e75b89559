// Copyright (c) 2026 SpringMotion developers.
#include "Mesh_setup.h"
#include "Arguments.h"
#include "commands.h"

#include <spring_motion/Error.h>
#include <spring_motion/Input_error.h>
#include <spring_motion/internal/geometry/simplex_tables.h>
#include <spring_motion/mesh_traits/Indexed_mesh.h>

#include <algorithm>
#include <array>
#include <cctype>
#include <sstream>
#include <utility>

namespace spring_motion {
namespace cli {

const char* element_noun(int dimension) { return dimension == 2 ? "triangle" : "tetrahedron"; }
const char* facet_noun(int dimension) { return dimension == 2 ? "edge" : "triangle"; }

namespace {

const char* element_plural(int dimension) { return dimension == 2 ? "triangles" : "tetrahedra"; }
const char* facet_plural(int dimension) { return dimension == 2 ? "edges" : "triangles"; }


// "lines 14, 15, 20 and 3 more"; for a binary file, which has no lines,
// "bytes 1234, ..." (the offsets at which the elements are written)
std::string line_list(const std::vector<std::size_t>& elements, const Mesh_file& file)
{
  const bool binary = !file.element_offsets.empty();
  const auto& where = binary ? file.element_offsets : file.element_lines;
  std::ostringstream out;
  out << (binary ? "byte" : "line") << (elements.size() == 1 ? " " : "s ");
  const std::size_t shown = std::min<std::size_t>(elements.size(), 5);
  for(std::size_t i = 0; i < shown; ++i)
    out << (i ? ", " : "") << where[elements[i]];
  if(elements.size() > shown)
    out << " and " << elements.size() - shown << " more";
  return out.str();
}

// An error about entry i of the file's elements (or boundary facets): a text
// file names its line, a binary file the byte offset of the entry, as the
// readers' own errors do ("file.msh: byte 1234: ...").
Input_error entry_error(const std::string& path, const Mesh_file& file, bool facet, std::size_t i,
                        const std::string& message)
{
  const auto& offsets = facet ? file.boundary_facet_offsets : file.element_offsets;
  if(i < offsets.size())
    return Input_error(path, 0, "byte " + std::to_string(offsets[i]) + ": " + message);
  const auto& lines = facet ? file.boundary_facet_lines : file.element_lines;
  return Input_error(path, i < lines.size() ? lines[i] : 0, message);
}

template <int D>
std::string vertex_list(const Mesh_file& file, const std::array<std::uint32_t, D>& f)
{
  std::ostringstream out;
  for(int k = 0; k < D; ++k)
    out << (k ? " " : "") << file.vertex_ids[f[k]];
  return out.str();
}

template <int D>
std::string point_text(const std::array<double, D>& p)
{
  std::ostringstream out;
  out << "(";
  for(int c = 0; c < D; ++c)
    out << (c ? ", " : "") << p[c];
  out << ")";
  return out.str();
}

} // namespace

template <int D>
Mesh_setup<D> make_mesh_setup(const std::string& path, const Mesh_file& file, bool require_valid)
{
  using Tables = internal::Simplex_tables<D>;
  using Key = std::array<std::uint32_t, D>;
  Mesh_setup<D> setup;
  setup.path = path;
  setup.file = &file;
  const Indexed_mesh<D>& mesh = file.mesh<D>();
  setup.mesh = &mesh;
  const std::size_t m = mesh.elements.size();
  setup.problems = check_input_mesh<D>(mesh.points, mesh.elements);

  // Labelled facets: how many elements each is a side of. None: an error of
  // the file; one: on the boundary, naming a part of it; two: inside, ignored.
  for(std::size_t t = 0; t < m; ++t)
    ++setup.labels[t < mesh.element_labels.size() ? mesh.element_labels[t] : 0].elements;
  std::vector<std::pair<Key, std::size_t>> labelled; // sorted facet, index in the file's list
  labelled.reserve(mesh.boundary_facets.size());
  for(std::size_t f = 0; f < mesh.boundary_facets.size(); ++f) {
    Key key = mesh.boundary_facets[f];
    std::sort(key.begin(), key.end());
    labelled.push_back({key, f});
  }
  std::sort(labelled.begin(), labelled.end());
  std::vector<std::size_t> sides(mesh.boundary_facets.size(), 0);
  // only a facet whose vertices all lie on labelled facets can be one: most
  // facets of a mesh are skipped before the search
  std::vector<char> labelled_vertex(mesh.points.size(), 0);
  for(const auto& f : mesh.boundary_facets)
    for(const std::uint32_t v : f)
      if(v < labelled_vertex.size())
        labelled_vertex[v] = 1;
  for(std::size_t t = 0; t < m; ++t)
    for(int k = 0; k <= D; ++k) {
      Key key;
      bool candidate = true;
      for(int c = 0; c < D; ++c) {
        key[c] = mesh.elements[t][Tables::facet[k][c]];
        candidate = candidate && labelled_vertex[key[c]];
      }
      if(!candidate)
        continue;
      std::sort(key.begin(), key.end());
      for(auto it = std::lower_bound(labelled.begin(), labelled.end(), std::make_pair(key, std::size_t(0)));
          it != labelled.end() && it->first == key; ++it)
        ++sides[it->second];
    }
  Boundary_labelled_mesh<D> view;
  view.mesh = &mesh;
  view.on_boundary.assign(mesh.boundary_facets.size(), 0);
  for(std::size_t f = 0; f < mesh.boundary_facets.size(); ++f) {
    const int label = f < mesh.boundary_labels.size() ? mesh.boundary_labels[f] : 0;
    if(sides[f] == 0) {
      std::ostringstream msg;
      msg << "this " << facet_noun(D) << " (vertices " << vertex_list<D>(file, mesh.boundary_facets[f])
          << ", label " << label << ") is not a side of any " << element_noun(D) << ": expected "
          << facet_plural(D) << " on the boundary of the mesh";
      throw entry_error(path, file, true, f, msg.str());
    }
    Label_use& use = setup.labels[label];
    if(sides[f] > 1) {
      if(use.interior_facets++ == 0)
        use.first_interior_facet = f;
    } else {
      ++use.boundary_facets;
      view.on_boundary[f] = 1;
    }
  }

  if(!setup.problems.valid()) {
    if(require_valid) {
      std::size_t line = 0;
      const std::string message = describe_problems(setup, &line);
      throw Input_error(path, line, message);
    }
    return setup;
  }
  auto extracted = extract_spring_network(view);
  setup.network = std::move(extracted.network);
  setup.file_vertex = std::move(extracted.handles);
  setup.network_vertex.assign(mesh.points.size(), Mesh_setup<D>::no_vertex);
  for(Index i = 0; i < setup.file_vertex.size(); ++i)
    setup.network_vertex[setup.file_vertex[i]] = i;
  return setup;
}

template <int D>
std::string describe_problems(const Mesh_setup<D>& setup, std::size_t* first_line)
{
  const auto& p = setup.problems;
  const auto& lines = setup.file->element_lines; // all 0 for a binary file
  std::ostringstream out;
  const char* separator = "";
  const auto part = [&](const std::vector<std::size_t>& elements, const std::string& what) {
    if(elements.empty())
      return;
    out << separator << elements.size() << " " << what << " at " << line_list(elements, *setup.file);
    if(first_line && !*separator)
      *first_line = lines[elements.front()];
    separator = "; ";
  };
  const auto noun = [](std::size_t count) { return count == 1 ? element_noun(D) : element_plural(D); };
  part(p.degenerate, std::string("degenerate ") + noun(p.degenerate.size()) + " (zero " +
                         (D == 2 ? "area" : "volume") + ", exact test)");
  if(p.non_manifold_facets > 0)
    part(p.non_manifold, noun(p.non_manifold.size()) + std::string(" around ") +
                             std::to_string(p.non_manifold_facets) + " " +
                             (p.non_manifold_facets == 1 ? facet_noun(D) : facet_plural(D)) + " shared by more than two " +
                             element_plural(D) + " (not a manifold)");
  part(p.overlapping, std::string("inverted ") + noun(p.overlapping.size()) +
                          " (overlapping a neighbour across a shared " + facet_noun(D) + ", exact test)");
  if(!out.str().empty())
    out << ": expected a valid mesh, every " << element_noun(D) << " of non-zero " << (D == 2 ? "area" : "volume")
        << " and on its own side of each " << facet_noun(D) << " it shares, each " << facet_noun(D)
        << " in at most two " << element_plural(D);
  return out.str();
}

template <int D>
Input_error file_error(const Mesh_setup<D>& setup, const Error& error)
{
  const std::string message = without_source_location(error.what());
  if(const auto* v = dynamic_cast<const Vertex_error*>(&error))
    if(v->vertex() < setup.file_vertex.size()) {
      // the library names the vertex "vertex <network index>": the file's number replaces it
      std::ostringstream named;
      named << "vertex " << setup.vertex_number(Index(v->vertex())) << " at "
            << point_text<D>(setup.mesh->points[setup.file_vertex[v->vertex()]]);
      const std::string network_name = "vertex " + std::to_string(v->vertex());
      for(std::size_t at = message.find(network_name); at != std::string::npos;
          at = message.find(network_name, at + 1)) {
        const std::size_t end = at + network_name.size();
        if(end == message.size() || !std::isdigit(static_cast<unsigned char>(message[end])))
          return Input_error(setup.path, 0, message.substr(0, at) + named.str() + message.substr(end));
      }
      return Input_error(setup.path, 0, named.str() + ": " + message);
    }
  if(const auto* e = dynamic_cast<const Element_error*>(&error))
    if(e->element() < setup.file->element_lines.size())
      return entry_error(setup.path, *setup.file, false, e->element(),
                         std::string("this ") + element_noun(D) + ": " + message);
  return Input_error(setup.path, 0, message);
}

template <int D>
std::string describe_boundary_labels(const Mesh_setup<D>& setup)
{
  std::ostringstream out;
  bool first = true;
  for(const auto& [label, use] : setup.labels) {
    if(use.boundary_facets == 0)
      continue;
    out << (first ? "" : ", ") << label;
    const auto name = setup.mesh->label_names.find(label);
    if(name != setup.mesh->label_names.end())
      out << " '" << name->second << "'";
    out << " (" << use.boundary_facets << " " << (use.boundary_facets == 1 ? facet_noun(D) : facet_plural(D)) << ")";
    first = false;
  }
  if(first)
    out << "none: the file labels no boundary " << facet_plural(D);
  return out.str();
}

template <int D>
std::vector<int> resolve_labels(const Mesh_setup<D>& setup, const std::string& option, const std::string& list)
{
  const std::string valid = "; expected labels (numbers or names) of boundary " + std::string(facet_plural(D)) +
                            ": " + describe_boundary_labels(setup);
  std::vector<int> labels;
  if(list.empty())
    throw Input_error(setup.path, 0, "--" + option + " names no label (an empty set)" + valid);
  for(const std::string& item : split_list(list)) {
    if(item.empty())
      throw Input_error(setup.path, 0, "--" + option + " '" + list + "' has an empty item" + valid);
    int label = 0;
    bool found = false;
    // a physical name wins over a number (a name may be made of digits)
    for(const auto& [number, name] : setup.mesh->label_names)
      if(name == item) {
        label = number;
        found = true;
      }
    if(!found) {
      char* end = nullptr;
      const long value = std::strtol(item.c_str(), &end, 10);
      if(end != item.c_str() + item.size() || value < std::numeric_limits<int>::min() ||
         value > std::numeric_limits<int>::max())
        throw Input_error(setup.path, 0, "--" + option + ": unknown label '" + item + "'" + valid);
      label = int(value);
    }
    const auto it = setup.labels.find(label);
    if(it == setup.labels.end() || (it->second.boundary_facets == 0 && it->second.interior_facets == 0 &&
                                    it->second.elements == 0))
      throw Input_error(setup.path, 0, "--" + option + ": unknown label '" + item + "'" + valid);
    if(it->second.boundary_facets == 0) {
      if(it->second.interior_facets > 0)
        throw entry_error(setup.path, *setup.file, true, it->second.first_interior_facet,
                          "--" + option + ": label '" + item + "' marks " + facet_plural(D) +
                            " inside the mesh, not on its boundary" + valid);
      throw Input_error(setup.path, 0,
                        "--" + option + ": label '" + item + "' marks " + element_plural(D) + ", not boundary " +
                          facet_plural(D) + valid);
    }
    labels.push_back(label);
  }
  return labels;
}

template <int D>
std::vector<Vertex_role> assign_command_line_roles(const Mesh_setup<D>& setup, const Boundary_label_roles& rules,
                                                   const std::vector<char>& prescribed)
{
  std::vector<Vertex_role> roles = assign_roles(setup.network, rules);
  for(Index i = 0; i < Index(prescribed.size()); ++i)
    if(prescribed[i])
      roles[i] = Vertex_role::moving;
  return roles;
}

#define SPRING_MOTION_CLI_INSTANTIATE(D)                                                                      \
  template Mesh_setup<D> make_mesh_setup<D>(const std::string&, const Mesh_file&, bool);                     \
  template std::string describe_problems<D>(const Mesh_setup<D>&, std::size_t*);                            \
  template std::string describe_boundary_labels<D>(const Mesh_setup<D>&);                                   \
  template std::vector<int> resolve_labels<D>(const Mesh_setup<D>&, const std::string&, const std::string&); \
  template std::vector<Vertex_role> assign_command_line_roles<D>(const Mesh_setup<D>&, const Boundary_label_roles&, \
                                                                 const std::vector<char>&);                 \
  template Input_error file_error<D>(const Mesh_setup<D>&, const Error&);
SPRING_MOTION_CLI_INSTANTIATE(2)
SPRING_MOTION_CLI_INSTANTIATE(3)

} // namespace cli
} // namespace spring_motion
