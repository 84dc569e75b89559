// Copyright (c) 2026 SpringMotion developers.
// Private to the spring-motion executable, built with PETSc only: the mesh
// partitioned over the MPI ranks (--backend petsc, docs/scaling.md).
#ifndef SPRING_MOTION_SRC_CLI_PARTITIONED_RUN_H
#define SPRING_MOTION_SRC_CLI_PARTITIONED_RUN_H

#include <spring_motion/Boundary_plane.h>
#include <spring_motion/Deform_report.h>
#include <spring_motion/Error.h>
#include <spring_motion/Network_deformer.h>
#include <spring_motion/internal/geometry/partition.h>
#include <spring_motion/internal/solver/petsc_solve.h>
#include <spring_motion/skewness.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <string>
#include <tuple>
#include <vector>

namespace spring_motion {
namespace cli {

/// One rank's share of a run on PETSc. Rank 0 has read the mesh and
/// assigned the roles; it partitions the mesh and sends every other rank its
/// part (owned vertices, one layer of ghosts). Each rank runs a
/// Network_deformer on its part: it computes the stiffness of its elements,
/// inserts its owned rows into the distributed matrix, gets its ghosts'
/// solution back from their owners, checks its elements exactly, and agrees
/// with the other ranks on the step's validity. Rank 0 gathers the positions
/// to write them.
template <int D>
class Partitioned_run
{
public:
  using Point = std::array<double, D>;

  /// Rank 0: partitions the whole mesh (whose roles were checked), sends
  /// every other rank its part and keeps its own. `planes`: those of the
  /// parts the sliding vertices lie on, fitted on the whole mesh
  /// (`sliding_planes`). `vertex_number`: the file's number of each network
  /// vertex, for the other ranks' error messages.
  Partitioned_run(MPI_Comm comm, const Spring_network<D>& whole, const std::vector<Vertex_role>& roles,
                  std::vector<Boundary_plane<D>> planes, const std::vector<std::size_t>& vertex_number)
      : comm_(comm), planes_(std::move(planes))
  {
    int ranks;
    MPI_Comm_size(comm_, &ranks);
    MPI_Comm_rank(comm_, &rank_);
    counts_.vertices = whole.number_of_vertices();
    counts_.elements = whole.number_of_elements();
    // counted as the whole mesh's deformer counts them: sliding vertices
    // that their planes pin are fixed
    const std::vector<char> used = used_vertices(whole);
    const std::vector<char> solved = internal::solved_vertices(used, roles, internal::sliding_set(whole, roles, planes_));
    for(Index v = 0; v < used.size(); ++v)
      if(used[v] && !solved[v])
        ++(roles[v] == Vertex_role::moving ? counts_.moving_vertices : counts_.fixed_vertices);
      else if(solved[v] && roles[v] == Vertex_role::sliding)
        ++counts_.sliding_vertices;
    const std::vector<int> owner = internal::partition_vertices(whole, ranks);
    for(int r = 1; r < ranks; ++r) {
      const std::vector<double> message = pack(internal::extract_part(whole, roles, solved, owner, ranks, r), vertex_number);
      unsigned long long size = message.size();
      MPI_Send(&size, 1, MPI_UNSIGNED_LONG_LONG, r, 0, comm_);
      MPI_Send(message.data(), int(message.size()), MPI_DOUBLE, r, 1, comm_);
    }
    part_ = internal::extract_part(whole, roles, solved, owner, ranks, 0);
    for(Index v : part_.global_vertex)
      vertex_number_.push_back(vertex_number[v]);
    set_rows();
  }

  /// Any other rank: receives its part from rank 0.
  explicit Partitioned_run(MPI_Comm comm) : comm_(comm)
  {
    MPI_Comm_rank(comm_, &rank_);
    unsigned long long size = 0;
    MPI_Recv(&size, 1, MPI_UNSIGNED_LONG_LONG, 0, 0, comm_, MPI_STATUS_IGNORE);
    std::vector<double> message(size);
    MPI_Recv(message.data(), int(size), MPI_DOUBLE, 0, 1, comm_, MPI_STATUS_IGNORE);
    unpack(message);
    set_rows();
  }

  int rank() const { return rank_; }

  /// The part's network, roles and sliding planes, for the deformer (taken once).
  Spring_network<D> take_network() { return std::move(part_.network); }
  std::vector<Vertex_role> take_roles() { return std::move(part_.roles); }
  std::vector<Boundary_plane<D>> take_planes() { return std::move(planes_); }

  Solve_report solve(const Step_system_view<D>& view, std::vector<Point>& x, const Solver_options& options)
  {
    internal::Petsc_solve_report pr;
    if(internal::petsc_solve_step_system<D>(comm_, view, rows_, options, x, pr) != 0)
      throw Error("PETSc's solve of a step failed");
    Solve_report r;
    r.iterations = std::size_t(pr.iterations);
    r.converged = pr.converged;
    r.last_max_update = pr.last_max_update;
    r.error_estimate = pr.error_estimate;
    return r;
  }

  bool agree(bool valid) const
  {
    int mine = valid ? 1 : 0, all = 0;
    MPI_Allreduce(&mine, &all, 1, MPI_INT, MPI_LAND, comm_);
    return all != 0;
  }

  /// The positions of the whole mesh on rank 0, which gives the `whole`
  /// network (elsewhere null, `positions` left as they are): every rank
  /// sends its owned vertices'; a vertex no element uses keeps its initial
  /// point. Collective.
  void gather(const Network_deformer<D>& deformer, const Spring_network<D>* whole, std::vector<Point>& positions) const
  {
    std::vector<double> mine;
    for(std::size_t i = 0; i < part_.owned_vertices; ++i) {
      mine.push_back(double(part_.global_vertex[i]));
      for(int c = 0; c < D; ++c)
        mine.push_back(deformer.positions()[i][std::size_t(c)]);
    }
    const std::vector<double> all = gather_to_root(mine);
    if(rank_ != 0)
      return;
    positions = whole->points;
    for(std::size_t k = 0; k < all.size(); k += D + 1)
      for(int c = 0; c < D; ++c)
        positions[std::size_t(all[k])][std::size_t(c)] = all[k + 1 + std::size_t(c)];
  }

  /// The report of the whole mesh from the parts' reports, on every rank:
  /// the extremes of every step and of the final state over all parts, the
  /// final histograms over each part's counted elements (an element is
  /// counted by one part only), the elements of an invalid step by their
  /// whole-mesh numbers (on rank 0). Collective.
  void reduce(Deform_report& rep, const Network_deformer<D>& deformer) const
  {
    rep.vertices = counts_.vertices;
    rep.elements = counts_.elements;
    rep.moving_vertices = counts_.moving_vertices;
    rep.fixed_vertices = counts_.fixed_vertices;
    rep.sliding_vertices = counts_.sliding_vertices;
    std::vector<double> lows, highs;
    for(const Step_report& s : rep.steps) {
      lows.insert(lows.end(), {s.min_angle_deg_moving, s.min_angle_deg_all, s.min_size_ratio});
      highs.insert(highs.end(), {s.max_skewness_moving, s.max_skewness_all, s.max_size_ratio});
    }
    // the part's final R by its own element numbers: histograms here, not
    // passed on (the whole mesh's numbering is rank 0's)
    std::vector<double> r = std::move(rep.element_skewness);
    rep.element_skewness.clear();
    std::vector<char> all(r.size()), moving(r.size());
    for(std::size_t t = 0; t < r.size(); ++t) {
      all[t] = part_.counted[t];
      moving[t] = part_.counted[t] && deformer.touches_moving(t);
    }
    const Skewness_histogram h_all = skewness_histogram(r, [&](std::size_t t) { return all[t] != 0; });
    const Skewness_histogram h_moving = skewness_histogram(r, [&](std::size_t t) { return moving[t] != 0; });
    lows.insert(lows.end(), {rep.min_angle_deg_moving, rep.min_angle_deg_all, rep.min_size_ratio});
    highs.insert(highs.end(), {rep.max_size_ratio, h_all.max, h_moving.max});
    MPI_Allreduce(MPI_IN_PLACE, lows.data(), int(lows.size()), MPI_DOUBLE, MPI_MIN, comm_);
    MPI_Allreduce(MPI_IN_PLACE, highs.data(), int(highs.size()), MPI_DOUBLE, MPI_MAX, comm_);
    for(std::size_t i = 0; i < rep.steps.size(); ++i) {
      Step_report& s = rep.steps[i];
      std::tie(s.min_angle_deg_moving, s.min_angle_deg_all, s.min_size_ratio) =
          std::make_tuple(lows[3 * i], lows[3 * i + 1], lows[3 * i + 2]);
      std::tie(s.max_skewness_moving, s.max_skewness_all, s.max_size_ratio) =
          std::make_tuple(highs[3 * i], highs[3 * i + 1], highs[3 * i + 2]);
    }
    const std::size_t f = 3 * rep.steps.size();
    rep.min_angle_deg_moving = lows[f];
    rep.min_angle_deg_all = lows[f + 1];
    rep.min_size_ratio = lows[f + 2];
    rep.max_size_ratio = highs[f];
    rep.quality_all = sum(h_all, highs[f + 1]);
    rep.quality_moving = sum(h_moving, highs[f + 2]);
    int converged = rep.converged ? 1 : 0;
    MPI_Allreduce(MPI_IN_PLACE, &converged, 1, MPI_INT, MPI_LAND, comm_);
    rep.converged = converged != 0;
    if(rep.first_invalid) {
      std::vector<double> mine;
      for(std::size_t t : rep.first_invalid->elements)
        mine.push_back(double(part_.global_element[t]));
      std::vector<double> every = gather_to_root(mine);
      std::sort(every.begin(), every.end());
      every.erase(std::unique(every.begin(), every.end()), every.end());
      rep.first_invalid->elements.assign(every.begin(), every.end());
      rep.steps.back().inverted = every.size();
    }
  }

  /// Throws `e`, a library error of this rank's part, again as the whole
  /// mesh names it: on rank 0 a vertex or element by its whole-network
  /// index (which file_error then names as the file does); on the other
  /// ranks, which hold no file, a vertex by the file's number. Called in the
  /// catch block of `e`, which any other error rethrows as it is.
  [[noreturn]] void rethrow_for_whole_mesh(const Error& e) const
  {
    const auto renamed = [](std::string message, const std::string& noun, std::size_t from, std::size_t to) {
      const std::string old_name = noun + " " + std::to_string(from), new_name = noun + " " + std::to_string(to);
      for(std::size_t at = message.find(old_name); at != std::string::npos; at = message.find(old_name, at + 1)) {
        const std::size_t end = at + old_name.size();
        if(end == message.size() || !std::isdigit(static_cast<unsigned char>(message[end]))) {
          message.replace(at, old_name.size(), new_name);
          at += new_name.size() - 1;
        }
      }
      return message;
    };
    if(const auto* v = dynamic_cast<const Vertex_error*>(&e))
      if(v->vertex() < part_.global_vertex.size()) {
        const std::size_t g = part_.global_vertex[v->vertex()];
        if(rank_ != 0)
          throw Error(renamed(e.what(), "vertex", v->vertex(), vertex_number_[v->vertex()]));
        throw Vertex_error(renamed(e.what(), "vertex", v->vertex(), g), g);
      }
    if(const auto* t = dynamic_cast<const Element_error*>(&e))
      if(t->element() < part_.global_element.size()) {
        const std::size_t g = part_.global_element[t->element()];
        throw Element_error(renamed(e.what(), "element", t->element(), g), g);
      }
    throw;
  }

private:
  void set_rows()
  {
    rows_.vertex_row = part_.free_row.data();
    rows_.first = part_.first_row;
    rows_.owned = part_.owned_rows;
    rows_.total = part_.total_rows;
  }

  // A part as one message of doubles (every integer here is below 2^53):
  // sizes and whole-mesh counts, then the part's arrays.
  std::vector<double> pack(const internal::Mesh_part<D>& p, const std::vector<std::size_t>& vertex_number) const
  {
    const std::size_t nv = p.global_vertex.size(), ne = p.global_element.size();
    std::vector<double> m{double(nv), double(ne), double(p.owned_vertices), double(p.first_row),
                          double(p.owned_rows), double(p.total_rows), p.network.longest_initial_edge,
                          double(counts_.vertices), double(counts_.elements), double(counts_.moving_vertices),
                          double(counts_.fixed_vertices), double(counts_.sliding_vertices),
                          double(planes_.size())};
    m.reserve(m.size() + nv * (D + 5) + ne * (D + 3) + p.network.vertex_labels.size() + planes_.size() * (D + 2));
    for(const Boundary_plane<D>& pl : planes_) {
      m.push_back(double(pl.label));
      m.push_back(double(pl.axis));
      m.insert(m.end(), pl.normal.begin(), pl.normal.end());
    }
    for(const auto& q : p.network.points)
      m.insert(m.end(), q.begin(), q.end());
    for(const auto& e : p.network.elements)
      for(Index v : e)
        m.push_back(double(v));
    for(std::size_t i = 0; i < nv; ++i) {
      m.push_back(double(int(p.roles[i])));
      m.push_back(double(p.global_vertex[i]));
      m.push_back(p.free_row[i] == p.no_row ? -1.0 : double(p.free_row[i]));
      m.push_back(double(vertex_number[p.global_vertex[i]]));
      const Index lb = p.network.vertex_label_offsets[i], le = p.network.vertex_label_offsets[i + 1];
      m.push_back(double(le - lb));
      for(Index q = lb; q < le; ++q)
        m.push_back(double(p.network.vertex_labels[q]));
    }
    for(std::size_t t = 0; t < ne; ++t) {
      m.push_back(double(p.global_element[t]));
      m.push_back(double(p.counted[t]));
    }
    return m;
  }

  void unpack(const std::vector<double>& m)
  {
    std::size_t k = 0;
    const auto next = [&] { return m.at(k++); };
    const std::size_t nv = std::size_t(next()), ne = std::size_t(next());
    part_.owned_vertices = std::size_t(next());
    part_.first_row = std::size_t(next());
    part_.owned_rows = std::size_t(next());
    part_.total_rows = std::size_t(next());
    const double longest = next();
    counts_.vertices = std::size_t(next());
    counts_.elements = std::size_t(next());
    counts_.moving_vertices = std::size_t(next());
    counts_.fixed_vertices = std::size_t(next());
    counts_.sliding_vertices = std::size_t(next());
    planes_.resize(std::size_t(next()));
    for(Boundary_plane<D>& pl : planes_) {
      pl.label = int(next());
      pl.axis = int(next());
      for(auto& c : pl.normal)
        c = next();
    }
    std::vector<std::array<double, D>> points(nv);
    for(auto& q : points)
      for(auto& c : q)
        c = next();
    std::vector<std::array<Index, D + 1>> elements(ne);
    for(auto& e : elements)
      for(auto& v : e)
        v = Index(next());
    std::vector<Index> label_offsets{0};
    std::vector<int> vertex_labels;
    for(std::size_t i = 0; i < nv; ++i) {
      part_.roles.push_back(Vertex_role(int(next())));
      part_.global_vertex.push_back(Index(next()));
      const double row = next();
      part_.free_row.push_back(row < 0 ? part_.no_row : std::size_t(row));
      vertex_number_.push_back(std::size_t(next()));
      const std::size_t labels = std::size_t(next());
      for(std::size_t q = 0; q < labels; ++q)
        vertex_labels.push_back(int(next()));
      label_offsets.push_back(Index(vertex_labels.size()));
    }
    for(std::size_t t = 0; t < ne; ++t) {
      part_.global_element.push_back(std::size_t(next()));
      part_.counted.push_back(char(next()));
    }
    part_.network = make_spring_network<D>(std::move(points), std::move(elements));
    part_.network.longest_initial_edge = longest;
    part_.network.vertex_label_offsets = std::move(label_offsets);
    part_.network.vertex_labels = std::move(vertex_labels);
  }

  // the concatenation of every rank's `mine` on rank 0 (empty elsewhere)
  std::vector<double> gather_to_root(const std::vector<double>& mine) const
  {
    int ranks;
    MPI_Comm_size(comm_, &ranks);
    int count = int(mine.size());
    std::vector<int> counts(std::size_t(ranks), 0), offsets(std::size_t(ranks) + 1, 0);
    MPI_Gather(&count, 1, MPI_INT, counts.data(), 1, MPI_INT, 0, comm_);
    for(int r = 0; r < ranks; ++r)
      offsets[std::size_t(r) + 1] = offsets[std::size_t(r)] + counts[std::size_t(r)];
    std::vector<double> all(rank_ == 0 ? std::size_t(offsets.back()) : 0);
    MPI_Gatherv(mine.data(), count, MPI_DOUBLE, all.data(), counts.data(), offsets.data(), MPI_DOUBLE, 0, comm_);
    return all;
  }

  // a histogram of all parts' counted elements, from each part's
  Skewness_histogram sum(const Skewness_histogram& mine, double max) const
  {
    std::vector<double> bins(mine.fractions.size() + 2);
    for(std::size_t b = 0; b < mine.fractions.size(); ++b)
      bins[b] = std::round(mine.fractions[b] * double(mine.count));
    bins[mine.fractions.size()] = double(mine.count);
    bins[mine.fractions.size() + 1] = mine.count > 0 ? mine.mean * double(mine.count) : 0.0;
    MPI_Allreduce(MPI_IN_PLACE, bins.data(), int(bins.size()), MPI_DOUBLE, MPI_SUM, comm_);
    Skewness_histogram h;
    h.count = std::size_t(bins[mine.fractions.size()]);
    h.fractions.assign(mine.fractions.size(), 0.0);
    if(h.count > 0) {
      for(std::size_t b = 0; b < h.fractions.size(); ++b)
        h.fractions[b] = bins[b] / double(h.count);
      h.mean = bins[mine.fractions.size() + 1] / double(h.count);
    }
    h.max = max;
    return h;
  }

  MPI_Comm comm_;
  int rank_ = 0;
  internal::Mesh_part<D> part_;
  std::vector<Boundary_plane<D>> planes_;
  internal::Petsc_rows rows_;
  Deform_report counts_; // the whole mesh's vertices, elements, moving, fixed and sliding vertices
  std::vector<std::size_t> vertex_number_; // per local vertex: the file's number
};

} // namespace cli
} // namespace spring_motion

#endif
