// Copyright (c) 2026 SpringMotion developers.
#include "Mesh_setup.h"

#include <spring_motion/Error.h>
#include <spring_motion/Input_error.h>
#include <spring_motion/internal/simplex_tables.h>
#include <spring_motion/validity.h>

#include <algorithm>
#include <array>
#include <sstream>
#include <utility>

namespace spring_motion {
namespace cli {

const char* element_noun(int dimension) { return dimension == 2 ? "triangle" : "tetrahedron"; }
const char* facet_noun(int dimension) { return dimension == 2 ? "edge" : "triangle"; }

namespace {

const char* element_plural(int dimension) { return dimension == 2 ? "triangles" : "tetrahedra"; }
const char* facet_plural(int dimension) { return dimension == 2 ? "edges" : "triangles"; }


// "lines 14, 15, 20 and 3 more"
std::string line_list(const std::vector<std::size_t>& elements, const std::vector<std::size_t>& lines)
{
  std::ostringstream out;
  out << (elements.size() == 1 ? "line " : "lines ");
  const std::size_t shown = std::min<std::size_t>(elements.size(), 5);
  for(std::size_t i = 0; i < shown; ++i)
    out << (i ? ", " : "") << lines[elements[i]];
  if(elements.size() > shown)
    out << " and " << elements.size() - shown << " more";
  return out.str();
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
  const Indexed_mesh<D>& mesh = [&]() -> const Indexed_mesh<D>& {
    if constexpr(D == 2)
      return file.mesh_2;
    else
      return file.mesh_3;
  }();
  setup.mesh = &mesh;
  const std::size_t m = mesh.elements.size();
  const auto& element_lines = file.element_lines;

  // Exact orientation of every element.
  std::vector<int> sign(m);
  for(std::size_t t = 0; t < m; ++t) {
    sign[t] = internal::exact_orientation(internal::element_points<D>(mesh.elements, mesh.points, t));
    if(sign[t] == 0)
      setup.problems.degenerate.push_back(t);
    else
      ++(sign[t] > 0 ? setup.problems.positive : setup.problems.negative);
  }

  // Facets of the elements: sorted vertex triple/pair, element, local facet.
  struct Rec
  {
    Key key;
    std::uint32_t element;
    int local;
  };
  std::vector<Rec> recs;
  recs.reserve(m * (D + 1));
  for(std::size_t t = 0; t < m; ++t)
    for(int k = 0; k <= D; ++k) {
      Key key;
      for(int c = 0; c < D; ++c)
        key[c] = mesh.elements[t][Tables::facet[k][c]];
      std::sort(key.begin(), key.end());
      recs.push_back({key, std::uint32_t(t), k});
    }
  std::sort(recs.begin(), recs.end(), [](const Rec& a, const Rec& b) {
    return a.key != b.key ? a.key < b.key : a.element < b.element;
  });
  std::vector<std::size_t> overlap_pairs; // element indices, two per pair
  for(std::size_t r = 0; r < recs.size();) {
    std::size_t s = r;
    while(s < recs.size() && recs[s].key == recs[r].key)
      ++s;
    if(s - r > 2) {
      std::ostringstream msg;
      msg << "this " << element_noun(D) << " shares the " << facet_noun(D) << " with vertices "
          << vertex_list<D>(file, recs[r].key) << " with " << (s - r - 1) << " other " << element_plural(D)
          << " (lines " << element_lines[recs[r].element] << ", " << element_lines[recs[r + 1].element]
          << "): expected each " << facet_noun(D) << " in at most two " << element_plural(D)
          << " (a manifold mesh)";
      throw Input_error(path, element_lines[recs[r + 2].element], msg.str());
    }
    if(s - r == 2 && sign[recs[r].element] != 0 && sign[recs[r + 1].element] != 0) {
      // the apexes of the two elements must lie on opposite sides of the facet
      const std::uint32_t a = recs[r].element, b = recs[r + 1].element;
      const std::uint32_t apex_a = mesh.elements[a][recs[r].local], apex_b = mesh.elements[b][recs[r + 1].local];
      std::array<std::array<double, D>, D + 1> pa, pb;
      for(int c = 0; c < D; ++c)
        pa[c] = pb[c] = mesh.points[recs[r].key[c]];
      pa[D] = mesh.points[apex_a];
      pb[D] = mesh.points[apex_b];
      const int oa = internal::exact_orientation(pa), ob = internal::exact_orientation(pb);
      if(oa * ob >= 0) {
        overlap_pairs.push_back(a);
        overlap_pairs.push_back(b);
      }
    }
    r = s;
  }
  const int majority = setup.problems.positive >= setup.problems.negative ? 1 : -1;
  for(std::size_t i = 0; i < overlap_pairs.size(); i += 2) {
    const std::size_t a = overlap_pairs[i], b = overlap_pairs[i + 1];
    const bool a_odd = sign[a] != majority, b_odd = sign[b] != majority;
    if(a_odd || !b_odd)
      setup.problems.inverted.push_back(a);
    if(b_odd || !a_odd)
      setup.problems.inverted.push_back(b);
  }
  std::sort(setup.problems.inverted.begin(), setup.problems.inverted.end());
  setup.problems.inverted.erase(std::unique(setup.problems.inverted.begin(), setup.problems.inverted.end()),
                                setup.problems.inverted.end());

  // Labelled facets: each must be a side of an element; those on the
  // boundary name parts of it, those inside are ignored.
  for(std::size_t t = 0; t < m; ++t)
    ++setup.labels[t < mesh.element_labels.size() ? mesh.element_labels[t] : 0].elements;
  std::vector<Labeled_facet<D>> labeled;
  for(std::size_t f = 0; f < mesh.boundary_facets.size(); ++f) {
    Key key = mesh.boundary_facets[f];
    std::sort(key.begin(), key.end());
    const int label = f < mesh.boundary_labels.size() ? mesh.boundary_labels[f] : 0;
    const auto it = std::lower_bound(recs.begin(), recs.end(), key,
                                     [](const Rec& a, const Key& k) { return a.key < k; });
    if(it == recs.end() || it->key != key) {
      std::ostringstream msg;
      msg << "this " << facet_noun(D) << " (vertices " << vertex_list<D>(file, mesh.boundary_facets[f])
          << ", label " << label << ") is not a side of any " << element_noun(D) << ": expected "
          << facet_plural(D) << " on the boundary of the mesh";
      throw Input_error(path, file.boundary_facet_lines[f], msg.str());
    }
    const bool interior = it + 1 != recs.end() && (it + 1)->key == key;
    Label_use& use = setup.labels[label];
    if(interior) {
      if(use.interior_facets++ == 0)
        use.first_interior_line = file.boundary_facet_lines[f];
    } else {
      ++use.boundary_facets;
      Labeled_facet<D> lf;
      lf.label = label;
      for(int c = 0; c < D; ++c)
        lf.vertices[c] = mesh.boundary_facets[f][c];
      labeled.push_back(lf);
    }
  }

  const bool valid = setup.problems.degenerate.empty() && setup.problems.inverted.empty();
  if(!valid) {
    if(require_valid) {
      std::size_t line = 0;
      const std::string message = describe_problems(setup, &line);
      throw Input_error(path, line, message);
    }
    return setup;
  }
  setup.network = make_spring_network<D>(mesh.points, mesh.elements, labeled);
  return setup;
}

template <int D>
std::string describe_problems(const Mesh_setup<D>& setup, std::size_t* first_line)
{
  const auto& p = setup.problems;
  const auto& lines = setup.file->element_lines;
  std::ostringstream out;
  if(!p.degenerate.empty()) {
    out << p.degenerate.size() << " degenerate " << (p.degenerate.size() == 1 ? element_noun(D) : element_plural(D))
        << " (zero " << (D == 2 ? "area" : "volume") << ", exact test) at " << line_list(p.degenerate, lines);
    if(first_line)
      *first_line = lines[p.degenerate.front()];
  }
  if(!p.inverted.empty()) {
    out << (p.degenerate.empty() ? "" : "; ") << p.inverted.size() << " inverted "
        << (p.inverted.size() == 1 ? element_noun(D) : element_plural(D)) << " (overlapping a neighbour across a shared "
        << facet_noun(D) << ", exact test) at " << line_list(p.inverted, lines);
    if(first_line && p.degenerate.empty())
      *first_line = lines[p.inverted.front()];
  }
  if(!out.str().empty())
    out << ": expected a valid mesh, every " << element_noun(D) << " of positive " << (D == 2 ? "area" : "volume")
        << " and on its own side of each " << facet_noun(D) << " it shares";
  return out.str();
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
  for(const std::string& item : [&] {
        std::vector<std::string> items;
        std::string::size_type start = 0;
        for(;;) {
          const auto comma = list.find(',', start);
          items.push_back(list.substr(start, comma == std::string::npos ? std::string::npos : comma - start));
          if(comma == std::string::npos)
            return items;
          start = comma + 1;
        }
      }()) {
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
        throw Input_error(setup.path, it->second.first_interior_line,
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
std::vector<Vertex_role> assign_command_line_roles(const Mesh_setup<D>& setup, const std::vector<int>& moving,
                                                   const std::vector<int>& fixed, bool fixed_given,
                                                   const std::vector<char>& prescribed)
{
  const auto& net = setup.network;
  std::vector<Vertex_role> roles(net.number_of_vertices(), Vertex_role::free);
  for(Index i = 0; i < net.number_of_vertices(); ++i) {
    const int* lb = net.vertex_labels.data() + net.vertex_label_offsets[i];
    const int* le = net.vertex_labels.data() + net.vertex_label_offsets[i + 1];
    const auto has_any = [&](const std::vector<int>& labels) {
      for(int l : labels)
        if(std::find(lb, le, l) != le)
          return true;
      return false;
    };
    if((!prescribed.empty() && prescribed[i]) || (net.on_boundary[i] && has_any(moving)))
      roles[i] = Vertex_role::moving;
    else if(net.on_boundary[i] && (!fixed_given || has_any(fixed)))
      roles[i] = Vertex_role::fixed;
  }
  return roles;
}

template <int D>
void check_roles(const Mesh_setup<D>& setup, const std::vector<Vertex_role>& roles)
{
  const auto& net = setup.network;
  std::size_t moving = 0; // among the vertices some element uses
  for(const auto& e : net.elements)
    for(Index v : e)
      moving += roles[v] == Vertex_role::moving;
  if(moving == 0)
    throw Input_error(setup.path, 0, "no vertex moves (the moving set is empty): expected a moving boundary part "
                                     "with at least one vertex");
  const std::vector<Index> undetermined = undetermined_vertices(net, roles);
  const std::size_t unreached = undetermined.size();
  const Index example = unreached > 0 ? undetermined.front() : 0;
  if(unreached > 0) {
    std::ostringstream msg;
    msg << unreached << " free vertices (for instance vertex " << setup.file->vertex_ids[example] << " at "
        << point_text<D>(net.points[example]) << ") are connected to no moving or fixed vertex, so their motion is "
        << "undetermined (a singular system): expected every part of the mesh to touch a moving or fixed boundary "
        << "(see --fixed)";
    throw Input_error(setup.path, 0, msg.str());
  }
}

#define SPRING_MOTION_CLI_INSTANTIATE(D)                                                                      \
  template Mesh_setup<D> make_mesh_setup<D>(const std::string&, const Mesh_file&, bool);                     \
  template std::string describe_problems<D>(const Mesh_setup<D>&, std::size_t*);                            \
  template std::string describe_boundary_labels<D>(const Mesh_setup<D>&);                                   \
  template std::vector<int> resolve_labels<D>(const Mesh_setup<D>&, const std::string&, const std::string&); \
  template std::vector<Vertex_role> assign_command_line_roles<D>(const Mesh_setup<D>&, const std::vector<int>&, \
                                                                 const std::vector<int>&, bool,             \
                                                                 const std::vector<char>&);                 \
  template void check_roles<D>(const Mesh_setup<D>&, const std::vector<Vertex_role>&);
SPRING_MOTION_CLI_INSTANTIATE(2)
SPRING_MOTION_CLI_INSTANTIATE(3)

} // namespace cli
} // namespace spring_motion
