// Copyright (c) 2026 SpringMotion developers.
// spring-motion deform: read a mesh, move its moving boundary, write the result.
#include "Arguments.h"
#include "Displacement_file.h"
#include "Mesh_setup.h"
#include "Progress_bar.h"
#include "commands.h"
#include "output_files.h"

#include <spring_motion/Error.h>
#include <spring_motion/Input_error.h>
#include <spring_motion/deform.h>
#include <spring_motion/internal/solver/threads.h>
#include <spring_motion/io/network_output.h>
#include <spring_motion/io/read_mesh.h>
#include <spring_motion/io/write_mesh.h>
#include <spring_motion/motion/Pitch_motion.h>
#include <spring_motion/stiffness/model_by_name.h>
#ifdef SPRING_MOTION_WITH_PETSC
#include "Partitioned_run.h"

#include <sys/resource.h>
#endif
#ifdef _OPENMP
#include <omp.h>
#endif

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <iomanip>
#include <filesystem>
#include <functional>
#include <optional>
#include <ostream>
#include <sstream>
#include <type_traits>

namespace spring_motion {
namespace cli {

#ifndef SPRING_MOTION_WITH_PETSC
template <int D>
class Partitioned_run; // only in a build with PETSc: a null pointer here
#endif

namespace {

// A --model name not in the model table, or one that does not work in
// `dimension` (0: before the mesh is read), is a usage error; the table's
// message lists the valid names.
void check_model(const std::string& name, int dimension)
{
  try {
    check_model_name(name, dimension);
  } catch(const Error& e) {
    throw Usage_error("--model: " + without_source_location(e.what()));
  }
}

namespace fs = std::filesystem;
using Clock = std::chrono::steady_clock;

// What the command line asks for, checked before the mesh is read.
struct Deform_settings
{
  std::string mesh_path;
  std::optional<std::string> moving, fixed, sliding;
  enum class Motion_kind { pitch, translate, displacement } motion = Motion_kind::pitch;
  double pitch_deg = 0;
  std::vector<double> center, axis, translation;
  std::string displacement_path;
  std::string model = "grid_scaled";
  Deform_options options;
  std::vector<Output_file> outputs;
  bool series = false; // a .pvd output (known on every rank, which all take part in gathering a frame)
  std::size_t every = 1;
  std::string report_path;
  bool quiet = false, force_progress = false;
  bool petsc = false; // --backend petsc
};

const std::vector<Option_spec>& deform_options()
{
  static const std::vector<Option_spec> specs{
    {"moving"}, {"fixed"}, {"sliding"}, {"pitch"}, {"center"}, {"axis"}, {"translate"}, {"displacement"}, {"steps"},
    {"model"}, {"solver"}, {"omega"}, {"tolerance"}, {"max-iterations"}, {"max-substep-halvings"},
    {"threads"}, {"backend"}, {"output", true, true}, {"every"}, {"report"}, {"quiet", false}, {"progress", false},
    {"help", false}};
  return specs;
}

Deform_settings parse_deform(const Arguments& a)
{
  Deform_settings s;
  if(a.operands().size() != 1)
    throw Usage_error(a.operands().empty() ? "expected a mesh file (MESH)"
                                           : "expected one mesh file, found " + std::to_string(a.operands().size()) +
                                               " operands: '" + a.operands()[0] + "', '" + a.operands()[1] + "'");
  s.mesh_path = a.operands()[0];
  s.moving = a.value("moving");
  s.fixed = a.value("fixed");
  s.sliding = a.value("sliding");

  const int motions = int(a.has("pitch")) + int(a.has("translate")) + int(a.has("displacement"));
  if(motions != 1)
    throw Usage_error(motions == 0 ? "expected a motion: --pitch DEG --center X,Y[,Z], --translate DX,DY[,DZ] or "
                                     "--displacement FILE"
                                   : "expected one motion, found several of --pitch, --translate, --displacement");
  if(a.has("pitch")) {
    s.motion = Deform_settings::Motion_kind::pitch;
    s.pitch_deg = a.number("pitch", 0);
    if(!a.has("center"))
      throw Usage_error("--pitch needs --center X,Y (2D) or X,Y,Z (3D): the point the rotation turns about");
    s.center = a.numbers("center", 2, 3);
    s.axis = a.numbers("axis", 3, 3);
    if(!s.axis.empty() && s.axis[0] == 0 && s.axis[1] == 0 && s.axis[2] == 0)
      throw Usage_error("--axis: expected a non-zero vector, found 0,0,0");
  } else {
    if(a.has("center") || a.has("axis"))
      throw Usage_error("--center and --axis go with --pitch only");
    if(a.has("translate")) {
      s.motion = Deform_settings::Motion_kind::translate;
      s.translation = a.numbers("translate", 2, 3);
    } else {
      s.motion = Deform_settings::Motion_kind::displacement;
      s.displacement_path = *a.value("displacement");
    }
  }
  if(!s.moving && s.motion != Deform_settings::Motion_kind::displacement)
    throw Usage_error("expected --moving REF[,REF...]: the boundary labels (numbers or names) that move");

  s.options.number_of_steps = std::size_t(a.integer("steps", 100, 1, 100000000));
  if(const auto model = a.value("model")) {
    s.model = *model;
    check_model(s.model, 0); // the dimension is checked once the mesh is read
  }
  const std::string solver = a.value("solver").value_or(a.has("omega") ? "sor" : "cg");
  if(solver == "paper")
    s.options.solver = Solver_options::paper();
  else if(solver == "sor")
    s.options.solver.method = Solver_method::sor;
  else if(solver == "cg-sgs")
    s.options.solver.preconditioner = Preconditioner::symmetric_gauss_seidel;
  else if(solver != "cg")
    throw Usage_error("--solver: expected cg, cg-sgs, sor or paper, found '" + solver + "'");
  if(a.has("omega")) {
    if(solver == "cg" || solver == "cg-sgs")
      throw Usage_error("--omega is the relaxation factor of SOR: use it with --solver sor or paper");
    const double omega = a.number("omega", 1);
    if(!(omega > 0 && omega < 2))
      throw Usage_error("--omega: expected a number in (0, 2), found '" + *a.value("omega") + "'");
    s.options.solver.relaxation_factor = omega;
  }
  if(a.has("tolerance")) {
    const double tol = a.number("tolerance", 0);
    if(!(tol > 0))
      throw Usage_error("--tolerance: expected a positive number, found '" + *a.value("tolerance") + "'");
    s.options.solver.tolerance = tol;
  }
  s.options.solver.max_iterations =
      std::size_t(a.integer("max-iterations", (long long)s.options.solver.max_iterations, 1, 1000000000));
  s.options.max_substep_halvings = std::size_t(a.integer("max-substep-halvings", 0, 0, 20));
  s.options.solver.threads = int(a.integer("threads", 0, 0, 1024));
  if(const auto backend = a.value("backend")) {
    if(*backend == "petsc") {
#ifdef SPRING_MOTION_WITH_PETSC
      s.petsc = true;
#else
      throw Usage_error("--backend petsc: this spring-motion was built without PETSc; configure with "
                        "-DSPRING_MOTION_WITH_PETSC=ON (docs/scaling.md)");
#endif
    } else if(*backend != "shared")
      throw Usage_error("--backend: expected shared or petsc, found '" + *backend + "'");
  }

  for(const std::string& path : a.values("output"))
    s.outputs.push_back(classify_output(path));
  const bool has_pvd = std::any_of(s.outputs.begin(), s.outputs.end(),
                                   [](const Output_file& o) { return o.kind == Output_file::Kind::pvd; });
  if(a.has("every") && !has_pvd)
    throw Usage_error("--every K sets the steps of a .pvd time series: expected an --output ending in .pvd");
  s.series = has_pvd;
  s.every = std::size_t(a.integer("every", 1, 1, 100000000));
  s.report_path = a.value("report").value_or("");
  s.quiet = a.has("quiet");
  s.force_progress = a.has("progress");
  if(s.quiet && s.force_progress)
    throw Usage_error("--quiet and --progress contradict each other");
  return s;
}

template <int D>
std::array<double, D> to_point(const std::vector<double>& v, const char* option)
{
  if(D == 2 && v.size() == 3 && v[2] != 0)
    throw Usage_error(std::string("--") + option + ": the mesh is 2D, expected 2 numbers (or a third one equal to 0)");
  if(D == 3 && v.size() != 3)
    throw Usage_error(std::string("--") + option + ": the mesh is 3D, expected 3 numbers");
  std::array<double, D> p;
  for(int c = 0; c < D; ++c)
    p[c] = v[std::size_t(c)];
  return p;
}

// The frames of a .pvd series and the state the visitor shares with the run.
struct Run_context
{
  const Deform_settings* settings = nullptr;
  Progress_bar* bar = nullptr;
  Clock::time_point start;
  std::vector<Pvd_series> series;
  // adds the current state to every series; called on every rank (a
  // partitioned run gathers the positions first)
  std::function<void(std::size_t step)> add_frame;
  std::size_t last_frame = std::size_t(-1);
};

struct Command_visitor
{
  Run_context* context;
  void on_start(const Deform_report&) {}
  void on_step(const Step_report& step)
  {
    Run_context& c = *context;
    if(c.bar)
      c.bar->update(step, std::chrono::duration<double>(Clock::now() - c.start).count());
    if(interrupted())
      throw Interrupted();
    const bool accepted = step.inverted == 0;
    const bool last = step.step == c.settings->options.number_of_steps;
    if(c.settings->series && accepted && (step.step % c.settings->every == 0 || last))
      c.add_frame(step.step);
  }
};

std::string summary_line(const Deform_report& r, const std::vector<Output_file>& outputs,
                         const std::string& report_path, const std::vector<std::size_t>& frames)
{
  std::ostringstream out;
  out.precision(4);
  if(r.completed)
    out << "completed " << r.number_of_steps << "/" << r.number_of_steps << " steps";
  else
    out << "stopped at step " << r.first_invalid->step << "/" << r.number_of_steps << ": it inverted "
        << r.first_invalid->elements.size() << " element(s); kept the last valid state";
  if(std::isfinite(r.final_angle_deg))
    out << ", last valid angle " << std::fixed << std::setprecision(2) << r.final_angle_deg << " deg";
  else
    out << ", last valid fraction " << std::fixed << std::setprecision(3) << r.final_fraction << " of the motion";
  std::size_t iterations = 0;
  for(const auto& s : r.steps)
    iterations += s.iterations;
  const char* angle = r.dimension == 2 ? "min angle " : "min dihedral angle ";
  out << std::setprecision(3) << ", worst R " << r.quality_moving.max << " near the moving boundary ("
      << r.quality_all.max << " overall), " << angle << std::setprecision(2) << r.min_angle_deg_moving
      << " deg near the moving boundary (" << r.min_angle_deg_all << " overall)" << std::setprecision(3)
      << ", min size ratio " << r.min_size_ratio << ", " << iterations
      << " solver iterations, " << std::setprecision(2) << r.seconds_total << " s";
  if(!r.converged)
    out << ", SOME SOLVES DID NOT CONVERGE";
  for(std::size_t i = 0; i < outputs.size(); ++i) {
    out << (i == 0 ? "; wrote " : ", ") << outputs[i].path;
    if(outputs[i].kind == Output_file::Kind::pvd)
      out << " (" << frames[i] << " frames)";
  }
  if(!report_path.empty())
    out << (outputs.empty() ? "; wrote " : ", ") << report_path;
  return out.str();
}

#ifdef SPRING_MOTION_WITH_PETSC
/// MPI and PETSc for the run (--backend petsc), finalized on the way out,
/// also by an exception: every rank meets the same one, since every rank
/// reads the same files and checks the same roles (an error of one rank
/// during the steps ends the run with MPI_Abort, see run_motion).
struct Petsc_session
{
  explicit Petsc_session(bool on) : on_(on)
  {
    if(on_ && PetscInitializeNoArguments() != 0)
      throw Error("PETSc failed to start");
  }
  ~Petsc_session()
  {
    if(on_)
      PetscFinalize();
  }
  int rank() const
  {
    int r = 0;
    if(on_)
      MPI_Comm_rank(PETSC_COMM_WORLD, &r);
    return r;
  }
  int ranks() const
  {
    int n = 1;
    if(on_)
      MPI_Comm_size(PETSC_COMM_WORLD, &n);
    return n;
  }
  Petsc_session(const Petsc_session&) = delete;
  Petsc_session& operator=(const Petsc_session&) = delete;

private:
  bool on_;
};
#endif

#ifdef SPRING_MOTION_WITH_PETSC
// Rank 0 of a partitioned run reads the mesh while the other ranks wait for
// their parts. It first tells them whether it got that far: a header (status
// 0 and the dimension, then a displacement motion's data) or the failure it
// met (its exit status and the line main() prints), which every rank then
// prints as its own. Set once the header went out.
bool header_sent = false;

void send_failure(const Failure& f)
{
  double header[2] = {double(f.status), 0};
  MPI_Bcast(header, 2, MPI_DOUBLE, 0, PETSC_COMM_WORLD);
  int length = int(f.line.size());
  MPI_Bcast(&length, 1, MPI_INT, 0, PETSC_COMM_WORLD);
  std::string line = f.line;
  MPI_Bcast(line.data(), length, MPI_CHAR, 0, PETSC_COMM_WORLD);
  header_sent = true;
}

// Rank 0: the header, then the motion's data a rank cannot make from the
// command line (the displacements by point of a displacement file).
template <int D, class Motion>
void send_header(const Motion& motion)
{
  double header[2] = {0, double(D)};
  MPI_Bcast(header, 2, MPI_DOUBLE, 0, PETSC_COMM_WORLD);
  header_sent = true;
  if constexpr(std::is_same_v<Motion, Displacement_motion<D>>) {
    std::vector<double> data;
    for(const auto& [p, d] : motion.by_point) {
      data.insert(data.end(), p.begin(), p.end());
      data.insert(data.end(), d.begin(), d.end());
    }
    unsigned long long size = data.size();
    MPI_Bcast(&size, 1, MPI_UNSIGNED_LONG_LONG, 0, PETSC_COMM_WORLD);
    MPI_Bcast(data.data(), int(size), MPI_DOUBLE, 0, PETSC_COMM_WORLD);
  }
}

template <int D>
void receive_displacements(Displacement_motion<D>& motion)
{
  unsigned long long size = 0;
  MPI_Bcast(&size, 1, MPI_UNSIGNED_LONG_LONG, 0, PETSC_COMM_WORLD);
  std::vector<double> data(size);
  MPI_Bcast(data.data(), int(size), MPI_DOUBLE, 0, PETSC_COMM_WORLD);
  for(std::size_t k = 0; k + 2 * D <= data.size(); k += 2 * D) {
    std::array<double, D> p, d;
    std::copy(data.begin() + std::ptrdiff_t(k), data.begin() + std::ptrdiff_t(k + D), p.begin());
    std::copy(data.begin() + std::ptrdiff_t(k + D), data.begin() + std::ptrdiff_t(k + 2 * D), d.begin());
    motion.by_point.emplace(p, d);
  }
}

// Within a catch block, on any rank of a partitioned run once the parts
// are out: prints the exception in flight as main() would, naming a vertex
// or element as the whole mesh (on rank 0: as the file) does, then aborts
// every rank, which would otherwise wait in the next collective call.
template <int D>
[[noreturn]] void abort_partitioned_run(const Mesh_setup<D>* setup, const Partitioned_run<D>& run, std::ostream& err)
{
  Failure f;
  try {
    try {
      throw;
    } catch(const Input_error&) {
      throw;
    } catch(const Usage_error&) {
      throw;
    } catch(const Interrupted&) {
      throw;
    } catch(const Error& e) {
      try {
        run.rethrow_for_whole_mesh(e);
      } catch(const Error& named) {
        if(setup)
          throw file_error(*setup, named);
        throw;
      }
    }
  } catch(...) {
    f = describe_failure("deform");
  }
  err << f.line + "\n";
  err.flush();
  MPI_Abort(PETSC_COMM_WORLD, f.status);
  std::abort();
}
#endif

// Whether the progress line is drawn (on stderr).
bool shows_progress(const Deform_settings& s, bool err_is_terminal)
{
  return !s.quiet && (err_is_terminal || s.force_progress);
}

// Runs the motion with `deformer` and writes what the command line asks
// for. `setup` is the file's mesh (null on the ranks of a partitioned run
// other than 0, which hold only their part); `partitioned` is the rank's
// share of a run on PETSc (null on the shared backend).
template <int D, class Motion>
int run_deformer(const Deform_settings& s, Mesh_setup<D>* setup, Network_deformer<D>& deformer,
                 [[maybe_unused]] Partitioned_run<D>* partitioned, const Motion& motion, std::ostream& out,
                 std::ostream& err, bool err_is_terminal)
{
#ifdef SPRING_MOTION_WITH_PETSC
  using Point = std::array<double, D>;
  // rank 0 keeps the whole network to write it
  std::vector<Point> whole_positions;
  Orientation_record whole_record;
  if(partitioned) {
    if(partitioned->rank() == 0)
      whole_record = record_orientations(setup->network, setup->network.points, Mesh_checks::by_caller);
    deformer.solve_override = [&](const Step_system_view<D>& view, std::vector<Point>& x) {
      return partitioned->solve(view, x, s.options.solver);
    };
    deformer.agree_on_validity = [&](bool valid) { return partitioned->agree(valid); };
  }
#endif
  // the state to write: the deformer's, or the parts' gathered on rank 0 (collective)
  const auto state_now = [&]() -> Mesh_state<D> {
#ifdef SPRING_MOTION_WITH_PETSC
    if(partitioned) {
      partitioned->gather(deformer, setup ? &setup->network : nullptr, whole_positions);
      if(!setup) // a rank other than 0: nothing to write
        return state_of(deformer);
      return {setup->network, whole_positions, whole_record};
    }
#endif
    return state_of(deformer);
  };
  Progress_bar bar(err, shows_progress(s, err_is_terminal), s.options.number_of_steps);
  Run_context context;
  context.settings = &s;
  context.bar = &bar;
  context.start = Clock::now();
  for(const auto& o : s.outputs)
    if(o.kind == Output_file::Kind::pvd)
      context.series.emplace_back(o.path, s.options.number_of_steps);
  context.add_frame = [&](std::size_t step) {
    const Mesh_state<D> state = state_now();
    for(auto& series : context.series)
      series.add_frame(step, *setup, state);
    context.last_frame = step;
  };
  Deform_report report;
  std::vector<std::string> written; // finished outputs, removed if a later one fails
  try {
    if(s.series)
      context.add_frame(0);
    report = with_model(s.model, [&](const auto& model) {
      return deformer.run(motion, model, s.options, Command_visitor{&context});
    });
    report.backend = s.petsc ? "petsc" : "shared";
    // the steps are over: their memory goes before the outputs take theirs
    deformer.release_step_memory();
#ifdef SPRING_MOTION_WITH_PETSC
    if(partitioned) {
      partitioned->reduce(report, deformer);
      MPI_Comm_size(PETSC_COMM_WORLD, &report.ranks);
      rusage usage{};
      getrusage(RUSAGE_SELF, &usage); // ru_maxrss in KiB on Linux
      double mine[3] = {0, report.seconds_total, double(usage.ru_maxrss) / 1024};
      for(const auto& step : report.steps)
        mine[0] += step.seconds_solve;
      std::vector<double> all(3 * std::size_t(report.ranks));
      MPI_Gather(mine, 3, MPI_DOUBLE, all.data(), 3, MPI_DOUBLE, 0, PETSC_COMM_WORLD);
      for(int r = 0; r < report.ranks; ++r) {
        report.rank_seconds_solve.push_back(all[3 * std::size_t(r)]);
        report.rank_seconds_total.push_back(all[3 * std::size_t(r) + 1]);
        report.rank_peak_mib.push_back(all[3 * std::size_t(r) + 2]);
      }
    }
#endif
    bar.clear();
    // the last valid state closes the series, whatever --every says
    if(s.series && !report.completed && context.last_frame != report.first_invalid->step - 1)
      context.add_frame(report.first_invalid->step - 1);
    Mesh_state<D> final_state = state_now();
    // the run's final R, when it numbers the elements as the written mesh
    // does (not a partitioned run's parts)
    if(report.element_skewness.size() == final_state.network.number_of_elements())
      final_state.skewness = &report.element_skewness;
    std::vector<std::size_t> frames;
    for(const auto& o : s.outputs) {
      written.push_back(o.path);
      if(o.kind == Output_file::Kind::pvd) {
        auto it = std::find_if(context.series.begin(), context.series.end(),
                               [&](const Pvd_series& p) { return p.path() == o.path; });
        it->finish();
        frames.push_back(it->frames());
      } else {
        write_final_mesh(o, *setup, final_state);
        frames.push_back(0);
      }
    }
    if(!s.report_path.empty()) {
      written.push_back(s.report_path);
      write_file_atomically(s.report_path, [&](std::ostream& f) { write_report_json(report, f); });
    }
    out << summary_line(report, s.outputs, s.report_path, frames) << "\n";
#ifdef SPRING_MOTION_WITH_PETSC
    // mpiexec ends every rank as soon as one exits with a non-zero status
    // (3: an inverting step): no rank leaves before rank 0 has written its
    // files and its summary line
    out.flush();
    if(partitioned)
      MPI_Barrier(PETSC_COMM_WORLD);
#endif
  } catch(...) {
    bar.clear();
    for(auto& series : context.series)
      series.discard();
    std::error_code ignored;
    for(const auto& path : written)
      fs::remove(path, ignored);
#ifdef SPRING_MOTION_WITH_PETSC
    // An error of one rank's part during the steps (a non-finite position,
    // a degenerate element's stiffness) is not seen by the other ranks,
    // which wait in the next collective call: this rank reports it and ends
    // every rank.
    if(partitioned)
      abort_partitioned_run(setup, *partitioned, err);
#endif
    throw;
  }
  return report.completed ? exit_success : exit_invalid;
}

// The file's mesh with its roles and motion: the shared backend runs it
// whole; a partitioned run's rank 0 checks the roles on the whole mesh,
// sends the other ranks their parts and runs its own.
template <int D, class Motion>
int run_motion(const Deform_settings& s, Mesh_setup<D>& setup, std::vector<Vertex_role> roles, const Motion& motion,
               std::ostream& out, std::ostream& err, bool err_is_terminal)
{
#ifdef SPRING_MOTION_WITH_PETSC
  if(s.petsc) {
    check_vertex_roles(setup.network, roles); // a part may have no moving vertex
    // fitted on the whole mesh: a part may hold too few of a plane's vertices
    std::vector<Boundary_plane<D>> planes = sliding_planes(setup.network, roles);
    send_header<D>(motion);
    std::vector<std::size_t> numbers(setup.network.number_of_vertices());
    for(Index v = 0; v < numbers.size(); ++v)
      numbers[v] = setup.vertex_number(v);
    Partitioned_run<D> partitioned(PETSC_COMM_WORLD, setup.network, roles, std::move(planes), numbers);
    Network_deformer<D> deformer(partitioned.take_network(), partitioned.take_roles(), partitioned.take_planes(),
                               Role_checks::by_caller);
    return run_deformer<D>(s, &setup, deformer, &partitioned, motion, out, err, err_is_terminal);
  }
#endif
  // make_mesh_setup has checked the file's mesh, reporting against its lines
  Network_deformer<D> deformer(std::move(setup.network), std::move(roles), Role_checks::here, Mesh_checks::by_caller);
  return run_deformer<D>(s, &setup, deformer, nullptr, motion, out, err, err_is_terminal);
}

// The command line's motion, with the checks that need the dimension (a
// displacement motion's displacements are read with the mesh, run_deform).
template <int D>
struct Motions
{
  std::optional<Pitch_motion<D>> pitch;
  std::optional<Translation_motion<D>> translation;
  std::optional<Displacement_motion<D>> displacement;

  template <class F>
  int visit(F&& f) const
  {
    if(pitch)
      return f(*pitch);
    if(translation)
      return f(*translation);
    return f(*displacement);
  }
};

template <int D>
Motions<D> command_line_motion(const Deform_settings& s)
{
  Motions<D> m;
  if(s.motion == Deform_settings::Motion_kind::pitch) {
    m.pitch.emplace(s.pitch_deg, to_point<D>(s.center, "center"));
    if(!s.axis.empty()) {
      if constexpr(D == 2) {
        if(s.axis[0] != 0 || s.axis[1] != 0 || s.axis[2] <= 0)
          throw Usage_error("--axis: a 2D mesh turns about +z (counter-clockwise positive), expected no --axis or "
                            "0,0,1; for a clockwise pitch give a negative angle");
      } else
        m.pitch->axis = {s.axis[0], s.axis[1], s.axis[2]};
    }
  } else if(s.motion == Deform_settings::Motion_kind::translate) {
    m.translation.emplace();
    m.translation->displacement = to_point<D>(s.translation, "translate");
  } else
    m.displacement.emplace();
  return m;
}

template <int D>
int run_deform(const Deform_settings& s, const Mesh_file& file, std::ostream& out, std::ostream& err,
               bool err_is_terminal)
{
  check_model(s.model, D);
  Mesh_setup<D> setup = make_mesh_setup<D>(s.mesh_path, file, true);
  const std::vector<int> moving = s.moving ? resolve_labels(setup, "moving", *s.moving) : std::vector<int>{};
  Boundary_label_roles rules;
  rules.moving = moving;
  if(s.fixed) {
    rules.fixed = resolve_labels(setup, "fixed", *s.fixed);
    rules.fixed_given = true;
  }
  if(s.sliding)
    rules.sliding = resolve_labels(setup, "sliding", *s.sliding);
  Motions<D> motion = command_line_motion<D>(s);
  std::vector<char> prescribed;
  // Roles before reading a displacement file, which must then cover the moving set.
  auto roles = assign_command_line_roles(setup, rules, prescribed);
  if(s.motion == Deform_settings::Motion_kind::displacement) {
    const auto df = read_displacement_file<D>(s.displacement_path, file.vertex_ids);
    prescribed.assign(setup.network.number_of_vertices(), 0);
    for(std::size_t k = 0; k < df.vertices.size(); ++k) {
      const std::string id = std::to_string(file.vertex_ids[df.vertices[k]]);
      const Index v = setup.network_vertex[df.vertices[k]];
      if(v == Mesh_setup<D>::no_vertex)
        throw Input_error(df.path, df.lines[k], "vertex " + id + " belongs to no " + element_noun(D) +
                                                    ": expected a vertex of the mesh's elements");
      if(s.moving && roles[v] != Vertex_role::moving)
        throw Input_error(df.path, df.lines[k], "vertex " + id + " is not on a moving boundary part (--moving " +
                                                    *s.moving + "): expected moving vertices only");
      const auto& p = setup.network.points[v];
      const auto [it, inserted] = motion.displacement->by_point.emplace(p, df.displacements[k]);
      if(!inserted && it->second != df.displacements[k])
        throw Input_error(df.path, df.lines[k], "vertex " + id + " lies at the same point as another listed vertex "
                                                    "with a different displacement: expected one displacement per point");
      prescribed[v] = 1;
    }
    if(s.moving) {
      for(Index v = 0; v < roles.size(); ++v)
        if(roles[v] == Vertex_role::moving && !prescribed[v])
          throw Input_error(df.path, 0, "no line for moving vertex " + std::to_string(setup.vertex_number(v)) +
                                            ": expected a displacement for every vertex of --moving " + *s.moving);
    } else
      roles = assign_command_line_roles(setup, rules, prescribed);
  }
  try { // the library checks the roles (Network_deformer)
    return motion.visit([&](const auto& m) {
      return run_motion<D>(s, setup, std::move(roles), m, out, err, err_is_terminal);
    });
  } catch(const Input_error&) {
    throw; // already names its file (an Input_error is an Error too)
  } catch(const Usage_error&) {
    throw;
  } catch(const Interrupted&) {
    throw;
  } catch(const Error& e) {
    // the library's own checks (vertex roles, a model's value, a non-finite
    // position), naming a vertex or an element as the file does
    throw file_error(setup, e);
  }
}

#ifdef SPRING_MOTION_WITH_PETSC
// A rank other than 0 of a partitioned run: it reads no file. It waits for
// rank 0's header (or the failure rank 0 met, printed here too), makes the
// motion from the same command line, receives its part and runs it.
template <int D>
int run_received_part(const Deform_settings& s, std::ostream& out, std::ostream& err)
{
  Motions<D> motion = command_line_motion<D>(s);
  if(motion.displacement)
    receive_displacements(*motion.displacement);
  Partitioned_run<D> partitioned(PETSC_COMM_WORLD);
  Network_deformer<D> deformer(partitioned.take_network(), partitioned.take_roles(), partitioned.take_planes(),
                               Role_checks::by_caller);
  return motion.visit([&](const auto& m) {
    return run_deformer<D>(s, nullptr, deformer, &partitioned, m, out, err, false);
  });
}

int receive_part(const Deform_settings& s, std::ostream& out, std::ostream& err)
{
  double header[2];
  MPI_Bcast(header, 2, MPI_DOUBLE, 0, PETSC_COMM_WORLD);
  if(header[0] != 0) {
    int length = 0;
    MPI_Bcast(&length, 1, MPI_INT, 0, PETSC_COMM_WORLD);
    std::string line(std::size_t(length), ' ');
    MPI_Bcast(line.data(), length, MPI_CHAR, 0, PETSC_COMM_WORLD);
    throw Relayed_error({int(header[0]), line});
  }
  install_interrupt_handlers();
  return header[1] == 2 ? run_received_part<2>(s, out, err) : run_received_part<3>(s, out, err);
}
#endif

// --threads T caps every parallel region of the run at T threads, the
// set-up's checks and the output's formatting as well as the steps: a run
// held to one thread beside a flow solver then starts no other (an idle
// OpenMP thread spins on its core for a while before it sleeps).
void cap_threads(int threads)
{
#ifdef _OPENMP
  if(threads > 0)
    omp_set_num_threads(threads);
#else
  (void)threads;
#endif
}

} // namespace

int deform_command(const std::vector<std::string>& arguments, std::ostream& out, std::ostream& err,
                   bool err_is_terminal)
{
  const Arguments a(arguments, deform_options());
  if(a.has("help")) {
    out << deform_help();
    return exit_success;
  }
  Deform_settings s = parse_deform(a);
  cap_threads(s.options.solver.threads);
  // Each step's quality (R, smallest angle) is shown only by the progress
  // line and the report; without either, only the final state's is (the
  // summary line), and measuring every step costs about what computing the
  // stiffness does.
  s.options.quality_every_step = shows_progress(s, err_is_terminal) || !s.report_path.empty();
#ifdef SPRING_MOTION_WITH_PETSC
  const Petsc_session petsc(s.petsc);
  try {
    if(s.petsc) { // rank 0's choice on every rank: the parts' step reports are reduced together
      int every = s.options.quality_every_step ? 1 : 0;
      MPI_Bcast(&every, 1, MPI_INT, 0, PETSC_COMM_WORLD);
      s.options.quality_every_step = every != 0;
    }
    if(petsc.rank() != 0) { // rank 0 reads, writes and prints; every rank reports its errors
      s.outputs.clear();
      s.report_path.clear();
      s.quiet = true;
      s.force_progress = false;
      std::ostringstream elsewhere;
      return receive_part(s, elsewhere, err);
    }
#endif
    std::vector<std::string> inputs{s.mesh_path};
    if(!s.displacement_path.empty())
      inputs.push_back(s.displacement_path);
    check_outputs(inputs, s.outputs, s.report_path);
    // The team's other threads start while the mesh is read: a first start
    // takes milliseconds, and on the 2D paper mesh the first region that
    // needs them is a step's.
    Mesh_file file;
    internal::run_while_team_starts(s.options.solver.threads, [&] { file = read_mesh(s.mesh_path); });
    install_interrupt_handlers(); // from here on outputs may exist: Ctrl-C removes them
    if(file.dimension == 2)
      return run_deform<2>(s, file, out, err, err_is_terminal);
    return run_deform<3>(s, file, out, err, err_is_terminal);
#ifdef SPRING_MOTION_WITH_PETSC
  } catch(...) {
    if(!s.petsc)
      throw;
    // Rank 0 failed before the parts went out (a bad file, label or role):
    // the other ranks, waiting for their parts, print the same line. Every
    // rank prints before any leaves: mpiexec ends them all when the first
    // exits with a non-zero status.
    const Failure f = describe_failure("deform");
    if(petsc.rank() == 0 && petsc.ranks() > 1 && !header_sent)
      send_failure(f);
    err << f.line + "\n";
    err.flush();
    MPI_Barrier(PETSC_COMM_WORLD);
    throw Reported_error(f.status);
  }
#endif
}

} // namespace cli
} // namespace spring_motion
