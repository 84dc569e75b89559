// Copyright (c) 2026 SpringMotion developers.
// Private to the spring-motion executable: the files a run writes.
#ifndef SPRING_MOTION_SRC_CLI_OUTPUT_FILES_H
#define SPRING_MOTION_SRC_CLI_OUTPUT_FILES_H

#include "Mesh_setup.h"

#include <spring_motion/deform.h>
#include <spring_motion/io/write_mesh.h>

#include <cstddef>
#include <string>
#include <vector>

namespace spring_motion {
namespace cli {

/// An --output, by extension: the final mesh as .vtu (with the point
/// displacement and per-cell R, validity and label), .mesh (Medit), .msh
/// (Gmsh 4.1 ASCII) or .su2 (SU2), the last three with the file's labels; or a
/// .pvd time series of .vtu frames.
struct Output_file
{
  enum class Kind { vtu, medit, pvd, gmsh, su2 };
  std::string path;
  Kind kind = Kind::vtu;
};

/// Throws Input_error for an extension other than .vtu, .mesh, .msh, .su2, .pvd.
Output_file classify_output(const std::string& path);

/// Whether two paths name the same existing file (or are the same path).
bool same_file(const std::string& a, const std::string& b);

/// Before anything is read: no output may be an input, two outputs may not
/// share a path, and every output's directory must exist. Throws Input_error.
void check_outputs(const std::vector<std::string>& inputs, const std::vector<Output_file>& outputs,
                   const std::string& report);

/// A state of the whole mesh to write: its network, the positions (one per
/// network vertex) and the orientations validity is judged against. From a
/// deformer, or gathered from the parts of a partitioned run.
template <int D>
struct Mesh_state
{
  const Spring_network<D>& network;
  const std::vector<std::array<double, D>>& positions;
  const Orientation_record& record;
  /// R of each element at `positions` when the run has it (its final
  /// report's), else null: computed by the writers
  const std::vector<double>* skewness = nullptr;
};

template <int D>
Mesh_state<D> state_of(const Network_deformer<D>& deformer)
{
  return {deformer.network(), deformer.positions(), deformer.orientation_record()};
}

/// The arrays written with a state of the mesh: point "displacement" from
/// the initial points, cell "skewness" (R), "valid" (1, or 0 for an element
/// inverted against its initial orientation) and "label".
template <int D>
void state_arrays(const Mesh_setup<D>& setup, const Mesh_state<D>& state, std::vector<Data_array>& point_data,
                  std::vector<Data_array>& cell_data);

/// Writes `state` to a .vtu or .mesh output.
template <int D>
void write_final_mesh(const Output_file& output, const Mesh_setup<D>& setup, const Mesh_state<D>& state);

/// A .pvd time series: frames NAME_<step>.vtu beside NAME.pvd, time = step
/// number. The .pvd is written once, by finish(); discard() removes the
/// frames written so far, so that a failed run leaves nothing behind.
class Pvd_series
{
public:
  Pvd_series(std::string path, std::size_t steps);
  template <int D>
  void add_frame(std::size_t step, const Mesh_setup<D>& setup, const Mesh_state<D>& state);
  void finish();
  void discard();
  const std::string& path() const { return path_; }
  std::size_t frames() const { return entries_.size(); }
  /// The step of the last frame added (none: -1 as a size_t).
  std::size_t last_step() const { return entries_.empty() ? std::size_t(-1) : std::size_t(entries_.back().time); }

private:
  std::string path_, stem_;
  int digits_;
  std::vector<std::string> written_;
  std::vector<Pvd_entry> entries_;
};

} // namespace cli
} // namespace spring_motion

#endif
