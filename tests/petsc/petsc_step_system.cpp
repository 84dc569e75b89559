// The PETSc solve of a step system (internal/solver/petsc_solve.h) against a
// direct solve (Eigen) of the same system, scalar and D x D block, on as many
// ranks as it is started on. The system is a grid Laplacian in the step
// system's layout (free rows, off-diagonal entries by row, constrained
// neighbours in the right-hand side); the block one is that Laplacian times a
// symmetric positive definite 2 x 2 block, which couples the components.
#include <spring_motion/internal/solver/petsc_solve.h>

#include <Eigen/Dense>

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace {

using spring_motion::Index;
constexpr int D = 2;

struct Grid_system
{
  std::vector<Index> vertices, offsets{0}, columns;
  std::vector<double> values, diagonal;
  std::vector<std::array<double, D>> rhs, initial;
};

// m x m free vertices of a (m + 2) x (m + 2) grid, Dirichlet data from the border
Grid_system grid(int m, bool block)
{
  const double B[4] = {2.0, 0.5, 0.5, 1.0};
  const int w = block ? D * D : 1;
  Grid_system g;
  for(int i = 0; i < m; ++i)
    for(int j = 0; j < m; ++j) {
      const int r = i * m + j;
      g.vertices.push_back(Index(r));
      for(int a = 0; a < w; ++a)
        g.diagonal.push_back(4.0 * (block ? B[a] : 1.0));
      std::array<double, D> b{};
      const int ni[4] = {i - 1, i + 1, i, i};
      const int nj[4] = {j, j, j - 1, j + 1};
      for(int k = 0; k < 4; ++k) {
        if(ni[k] < 0 || ni[k] >= m || nj[k] < 0 || nj[k] >= m) {
          // border value (sin of the position, per component) times the coupling
          const std::array<double, D> u{std::sin(0.3 * ni[k] + 0.1 * nj[k]), std::cos(0.2 * nj[k])};
          for(int c = 0; c < D; ++c)
            for(int e = 0; e < D; ++e)
              b[c] += block ? B[c * D + e] * u[e] : (c == e ? u[e] : 0.0);
          continue;
        }
        g.columns.push_back(Index(ni[k] * m + nj[k]));
        for(int a = 0; a < w; ++a)
          g.values.push_back(-(block ? B[a] : 1.0));
      }
      g.offsets.push_back(Index(g.columns.size()));
      g.rhs.push_back(b);
      g.initial.push_back({0.01 * r, -0.02 * r});
    }
  return g;
}

// the largest difference between the PETSc solution, stopped by the
// shared solver's error estimate at `tolerance`, and Eigen's
double check(MPI_Comm comm, int m, bool block, double tolerance, PetscInt& iterations)
{
  const Grid_system g = grid(m, block);
  spring_motion::Step_system_view<D> v;
  v.block = block;
  v.rows = g.vertices.size();
  v.vertices = g.vertices.data();
  v.row_offsets = g.offsets.data();
  v.columns = g.columns.data();
  v.values = g.values.data();
  v.diagonal = g.diagonal.data();
  v.rhs = g.rhs.data();
  v.initial = g.initial.data();
  std::vector<std::array<double, D>> x;
  spring_motion::internal::Petsc_solve_report report;
  // the view replicated on every rank; the whole system numbers the rows in
  // reverse, so that the view's order and PETSc's differ, and each rank owns
  // a contiguous range of the reversed rows (a rank may own none)
  std::vector<std::size_t> vertex_row(v.rows);
  for(std::size_t r = 0; r < v.rows; ++r)
    vertex_row[g.vertices[r]] = v.rows - 1 - r;
  int size, rank;
  MPI_Comm_size(comm, &size);
  MPI_Comm_rank(comm, &rank);
  spring_motion::internal::Petsc_rows rows;
  rows.vertex_row = vertex_row.data();
  rows.total = v.rows;
  rows.first = v.rows / std::size_t(size) * std::size_t(rank) + std::min<std::size_t>(std::size_t(rank), v.rows % std::size_t(size));
  rows.owned = v.rows / std::size_t(size) + (std::size_t(rank) < v.rows % std::size_t(size) ? 1 : 0);
  spring_motion::Solver_options options;
  options.tolerance = tolerance;
  if(spring_motion::internal::petsc_solve_step_system<D>(comm, v, rows, options, x, report) != 0 ||
     !report.converged || !(report.error_estimate <= 0.5 * tolerance) || !(report.last_max_update <= tolerance))
    return INFINITY;
  iterations = report.iterations;

  const int n = int(v.rows) * D;
  Eigen::MatrixXd A = Eigen::MatrixXd::Zero(n, n);
  Eigen::VectorXd b(n);
  auto put = [&](int r, int col, const double* M) {
    for(int c = 0; c < D; ++c)
      for(int e = 0; e < D; ++e)
        A(r * D + c, col * D + e) += block ? M[c * D + e] : (c == e ? M[0] : 0.0);
  };
  const int w = block ? D * D : 1;
  for(int r = 0; r < int(v.rows); ++r) {
    put(r, r, &g.diagonal[std::size_t(r * w)]);
    for(Index q = g.offsets[r]; q < g.offsets[r + 1]; ++q)
      put(r, int(g.columns[q]), &g.values[std::size_t(q) * w]);
    for(int c = 0; c < D; ++c)
      b(r * D + c) = g.rhs[r][c];
  }
  const Eigen::VectorXd u = A.llt().solve(b);
  double err = 0;
  for(int r = 0; r < int(v.rows); ++r)
    for(int c = 0; c < D; ++c)
      err = std::max(err, std::fabs(x[r][c] - u(r * D + c)));
  return err;
}

} // namespace

int main(int argc, char** argv)
{
  PetscCall(PetscInitialize(&argc, &argv, nullptr, nullptr));
  int failures = 0;
  // m = 1: one free vertex, so on 2 ranks one rank owns no row
  for(int m : {1, 3, 20})
    for(bool block : {false, true}) {
      PetscInt its = 0;
      // the stopping rule's promise: an error within the tolerance
      const double tolerance = 1e-9;
      const double err = check(PETSC_COMM_WORLD, m, block, tolerance, its);
      const bool ok = err <= tolerance;
      failures += ok ? 0 : 1;
      PetscCall(PetscPrintf(PETSC_COMM_WORLD, "%s %dx%d: %d iterations, max difference to the direct solve %g %s\n",
                            block ? "block " : "scalar", m, m, int(its), err, ok ? "ok" : "FAILED"));
    }
  PetscCall(PetscFinalize());
  return failures == 0 ? 0 : 1;
}
