// Copyright (c) 2026 SpringMotion developers.
#include "output_files.h"

#include <spring_motion/Input_error.h>
#include <spring_motion/io/network_output.h>

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <set>

namespace spring_motion {
namespace cli {

namespace fs = std::filesystem;

namespace {
bool has_extension(const std::string& path, const std::string& ext)
{
  std::string e = fs::path(path).extension().string();
  std::transform(e.begin(), e.end(), e.begin(), [](unsigned char c) { return char(std::tolower(c)); });
  return e == ext;
}
} // namespace

Output_file classify_output(const std::string& path)
{
  if(has_extension(path, ".vtu"))
    return {path, Output_file::Kind::vtu};
  if(has_extension(path, ".mesh"))
    return {path, Output_file::Kind::medit};
  if(has_extension(path, ".pvd"))
    return {path, Output_file::Kind::pvd};
  if(has_extension(path, ".msh"))
    return {path, Output_file::Kind::gmsh};
  if(has_extension(path, ".su2"))
    return {path, Output_file::Kind::su2};
  const std::string ext = fs::path(path).extension().string();
  throw Input_error(path, 0, (ext.empty() ? std::string("no file extension") : "unknown output extension '" + ext + "'") +
                               ": expected .vtu (final mesh), .pvd (time series), .mesh (Medit), .msh (Gmsh 4.1) or "
                               ".su2 (SU2)");
}

bool same_file(const std::string& a, const std::string& b)
{
  if(a.empty() || b.empty())
    return false;
  std::error_code error;
  if(fs::equivalent(a, b, error))
    return true;
  return fs::absolute(a, error).lexically_normal() == fs::absolute(b, error).lexically_normal();
}

void check_outputs(const std::vector<std::string>& inputs, const std::vector<Output_file>& outputs,
                   const std::string& report)
{
  std::vector<std::string> all;
  for(const auto& o : outputs)
    all.push_back(o.path);
  if(!report.empty())
    all.push_back(report);
  for(std::size_t i = 0; i < all.size(); ++i) {
    for(const auto& input : inputs)
      if(same_file(all[i], input))
        throw Input_error(all[i], 0, "this output is an input (" + input +
                                       "), which is never modified: expected another path");
    for(std::size_t j = 0; j < i; ++j)
      if(same_file(all[i], all[j]))
        throw Input_error(all[i], 0, "given as two outputs: expected a path per output");
    const fs::path dir = fs::path(all[i]).parent_path();
    std::error_code error;
    if(!dir.empty() && !fs::is_directory(dir, error))
      throw Input_error(all[i], 0, "directory '" + dir.string() + "' does not exist: expected an existing directory");
    if(fs::is_directory(all[i], error))
      throw Input_error(all[i], 0, "is a directory: expected a file path");
  }
}

namespace {
// The file's mesh at the state's positions: a vertex no element uses stays where it is.
template <int D>
Indexed_mesh<D> moved_mesh(const Mesh_setup<D>& setup, const Mesh_state<D>& state)
{
  Indexed_mesh<D> mesh = *setup.mesh;
  const auto& x = state.positions;
  for(Index i = 0; i < x.size(); ++i)
    mesh.points[setup.file_vertex[i]] = x[i];
  return mesh;
}
} // namespace

template <int D>
void state_arrays(const Mesh_setup<D>& setup, const Mesh_state<D>& state, std::vector<Data_array>& point_data,
                  std::vector<Data_array>& cell_data)
{
  motion_data_arrays(state.network, state.positions, state.record, point_data, cell_data, state.skewness);
  // per network vertex -> per file vertex (zero for a vertex no element uses)
  for(Data_array& a : point_data) {
    std::vector<double> values(setup.mesh->points.size() * std::size_t(a.components), 0.0);
    for(std::size_t i = 0; i < setup.file_vertex.size(); ++i)
      for(int c = 0; c < a.components; ++c)
        values[setup.file_vertex[i] * std::size_t(a.components) + std::size_t(c)] =
            a.values[i * std::size_t(a.components) + std::size_t(c)];
    a.values = std::move(values);
  }
  Data_array label{"label", 1, {}};
  label.values.reserve(setup.mesh->elements.size());
  for(std::size_t t = 0; t < setup.mesh->elements.size(); ++t)
    label.values.push_back(t < setup.mesh->element_labels.size() ? setup.mesh->element_labels[t] : 0);
  cell_data.push_back(std::move(label));
}

template <int D>
void write_final_mesh(const Output_file& output, const Mesh_setup<D>& setup, const Mesh_state<D>& state)
{
  const Indexed_mesh<D> mesh = moved_mesh(setup, state);
  if(output.kind == Output_file::Kind::medit)
    write_medit(mesh, output.path);
  else if(output.kind == Output_file::Kind::gmsh || output.kind == Output_file::Kind::su2)
    write_mesh(output.path, mesh); // by extension: Gmsh 4.1 ASCII or SU2
  else {
    std::vector<Data_array> point_data, cell_data;
    state_arrays(setup, state, point_data, cell_data);
    write_vtu(mesh, output.path, point_data, cell_data);
  }
}

Pvd_series::Pvd_series(std::string path, std::size_t steps) : path_(std::move(path))
{
  const fs::path p(path_);
  stem_ = (p.parent_path() / p.stem()).string();
  digits_ = int(std::to_string(steps).size());
}

template <int D>
void Pvd_series::add_frame(std::size_t step, const Mesh_setup<D>& setup, const Mesh_state<D>& state)
{
  char number[32];
  std::snprintf(number, sizeof number, "_%0*zu.vtu", digits_, step);
  const std::string file = stem_ + number;
  const Indexed_mesh<D> mesh = moved_mesh(setup, state);
  std::vector<Data_array> point_data, cell_data;
  state_arrays(setup, state, point_data, cell_data);
  written_.push_back(file);
  write_vtu(mesh, file, point_data, cell_data);
  // stored relative to the .pvd's directory: the frames sit beside it
  entries_.push_back({double(step), fs::path(file).filename().string()});
}

void Pvd_series::finish()
{
  write_pvd(path_, entries_);
  written_.clear();
}

void Pvd_series::discard()
{
  std::error_code ignored;
  for(const auto& f : written_)
    fs::remove(f, ignored);
  written_.clear();
  entries_.clear();
}

template void state_arrays<2>(const Mesh_setup<2>&, const Mesh_state<2>&, std::vector<Data_array>&,
                              std::vector<Data_array>&);
template void state_arrays<3>(const Mesh_setup<3>&, const Mesh_state<3>&, std::vector<Data_array>&,
                              std::vector<Data_array>&);
template void write_final_mesh<2>(const Output_file&, const Mesh_setup<2>&, const Mesh_state<2>&);
template void write_final_mesh<3>(const Output_file&, const Mesh_setup<3>&, const Mesh_state<3>&);
template void Pvd_series::add_frame<2>(std::size_t, const Mesh_setup<2>&, const Mesh_state<2>&);
template void Pvd_series::add_frame<3>(std::size_t, const Mesh_setup<3>&, const Mesh_state<3>&);

} // namespace cli
} // namespace spring_motion
