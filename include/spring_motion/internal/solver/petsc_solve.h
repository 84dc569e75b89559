// Copyright (c) 2026 SpringMotion developers.
#ifndef SPRING_MOTION_INTERNAL_SOLVER_PETSC_SOLVE_H
#define SPRING_MOTION_INTERNAL_SOLVER_PETSC_SOLVE_H

// Only with the CMake option SPRING_MOTION_WITH_PETSC (docs/scaling.md).
#include <spring_motion/Solver_options.h>
#include <spring_motion/Step_system_view.h>
#include <spring_motion/internal/solver/stopping_test.h>

#include <petscksp.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <vector>

namespace spring_motion {
namespace internal {

/// What one PETSc solve of a step system did.
struct Petsc_solve_report
{
  PetscInt iterations = 0; ///< CG iterations, summed over the components of a scalar system
  bool converged = true;
  double last_max_update = 0, error_estimate = 0; ///< the largest over the components
};

// KSP's convergence test replaced by the shared solver's (Stopping_test):
// fed the largest change of the iterate in each CG iteration, a global
// maximum, so that every rank stops at the same iteration. A zero residual
// norm (CG's natural norm, sqrt(r.z), zero only with r) ends the solve
// at once: the iterate is the solution, its error zero. So does CG itself
// when r.z vanishes before the test decides (`decided` false).
struct Petsc_stopping
{
  Stopping_test test;
  Vec previous = nullptr, change = nullptr;
  bool decided = false;

  static PetscErrorCode converged(KSP ksp, PetscInt n, PetscReal rnorm, KSPConvergedReason* reason, void* self)
  {
    auto& me = *static_cast<Petsc_stopping*>(self);
    Vec x;
    PetscCall(KSPBuildSolution(ksp, nullptr, &x));
    *reason = KSP_CONVERGED_ITERATING;
    if(rnorm == 0) {
      *reason = KSP_CONVERGED_ATOL;
      return 0;
    }
    if(n == 0) {
      PetscCall(VecCopy(x, me.previous));
      return 0;
    }
    PetscCall(VecWAXPY(me.change, -1.0, me.previous, x));
    PetscReal update;
    PetscCall(VecNorm(me.change, NORM_INFINITY, &update));
    PetscCall(VecCopy(x, me.previous));
    if(!std::isfinite(double(update)))
      *reason = KSP_DIVERGED_NANORINF;
    else if(me.test.done(double(update))) {
      *reason = KSP_CONVERGED_ATOL;
      me.decided = true;
    }
    return 0;
  }
};

/// Where the rows of a step system go in a distributed PETSc matrix:
/// `vertex_row[v]` is the row of the whole system of the view's network
/// vertex v (a free vertex); this rank owns rows [first, first + owned) of
/// `total`. The view may hold more rows than this rank owns (the ghosts of a
/// mesh part, or the whole system when it is replicated): only the owned
/// ones are inserted, and every row of the view gets its solution back.
struct Petsc_rows
{
  const std::size_t* vertex_row = nullptr;
  std::size_t first = 0, owned = 0, total = 0;
};

/// Solves a step's free system (the same rows, values, right-hand side and
/// start the shared-memory solver gets) with KSP CG preconditioned by GAMG on
/// the ranks of `comm`. Each rank inserts the rows it owns under `rows`, and
/// receives the solution of every row of its view in `x` (in the view's order).
/// A scalar system is an AIJ matrix solved once per component; a block system
/// is an AIJ matrix of block size D, one solve for all components, so GAMG
/// aggregates whole vertices and sees the D x D coupling. Each solve stops
/// by the shared solver's rule (`options.stopping`, `tolerance`,
/// `max_iterations`: Stopping_test), fed the largest change of the iterate
/// over all ranks, per component for a scalar system.
template <int D>
PetscErrorCode petsc_solve_step_system(MPI_Comm comm, const Step_system_view<D>& s, const Petsc_rows& rows,
                                       const Solver_options& options, std::vector<std::array<double, D>>& x,
                                       Petsc_solve_report& report)
{
  const PetscInt bs = s.block ? D : 1;
  const PetscInt first = PetscInt(rows.first), end = PetscInt(rows.first + rows.owned);
  // the whole system's row of each row of the view
  std::vector<PetscInt> global(s.rows);
  for(std::size_t r = 0; r < s.rows; ++r)
    global[r] = PetscInt(rows.vertex_row[s.vertices[r]]);
  const auto owned = [&](PetscInt g) { return g >= first && g < end; };
  std::vector<PetscInt> d_nnz(std::size_t(end - first), 1), o_nnz(std::size_t(end - first), 0);
  for(std::size_t r = 0; r < s.rows; ++r)
    if(owned(global[r]))
      for(Index q = s.row_offsets[r]; q < s.row_offsets[r + 1]; ++q)
        ++(owned(global[s.columns[q]]) ? d_nnz : o_nnz)[std::size_t(global[r] - first)];
  Mat A;
  PetscCall(MatCreate(comm, &A));
  PetscCall(MatSetSizes(A, (end - first) * bs, (end - first) * bs, PetscInt(rows.total) * bs,
                        PetscInt(rows.total) * bs));
  // AIJ with block size D, not BAIJ: GAMG (PETSc 3.18) builds its graph from
  // AIJ only, and reads the block size as the number of components
  PetscCall(MatSetType(A, MATAIJ));
  PetscCall(MatSetBlockSize(A, bs));
  PetscCall(MatXAIJSetPreallocation(A, bs, d_nnz.data(), o_nnz.data(), nullptr, nullptr));
  {
    std::vector<PetscInt> cols;
    std::vector<PetscScalar> vals, row;
    for(std::size_t R = 0; R < s.rows; ++R) {
      if(!owned(global[R]))
        continue;
      cols.assign(1, global[R]);
      vals.assign(s.diagonal + R * bs * bs, s.diagonal + (R + 1) * bs * bs);
      for(Index q = s.row_offsets[R]; q < s.row_offsets[R + 1]; ++q) {
        cols.push_back(global[s.columns[q]]);
        for(PetscInt a = 0; a < bs * bs; ++a)
          vals.push_back(s.values[std::size_t(q) * bs * bs + a]);
      }
      // values of a row of blocks, laid out as PETSc's row-oriented input:
      // block row a of every entry, entry after entry
      row.resize(vals.size());
      const std::size_t m = cols.size();
      for(std::size_t e = 0; e < m; ++e)
        for(PetscInt a = 0; a < bs; ++a)
          for(PetscInt c = 0; c < bs; ++c)
            row[std::size_t(a) * m * bs + e * bs + c] = vals[e * bs * bs + a * bs + c];
      PetscCall(MatSetValuesBlocked(A, 1, &global[R], PetscInt(m), cols.data(), row.data(), INSERT_VALUES));
    }
  }
  PetscCall(MatAssemblyBegin(A, MAT_FINAL_ASSEMBLY));
  PetscCall(MatAssemblyEnd(A, MAT_FINAL_ASSEMBLY));
  PetscCall(MatSetOption(A, MAT_SPD, PETSC_TRUE));

  Vec b, u, all;
  PetscCall(MatCreateVecs(A, &u, &b));
  // every row of the view, owned or not, gets its solution from its owner
  IS wanted;
  PetscCall(ISCreateBlock(PETSC_COMM_SELF, bs, PetscInt(s.rows), global.data(), PETSC_COPY_VALUES, &wanted));
  PetscCall(VecCreateSeq(PETSC_COMM_SELF, PetscInt(s.rows) * bs, &all));
  VecScatter to_all;
  PetscCall(VecScatterCreate(u, wanted, all, nullptr, &to_all));
  PetscCall(ISDestroy(&wanted));
  KSP ksp;
  PetscCall(KSPCreate(comm, &ksp));
  PetscCall(KSPSetOperators(ksp, A, A));
  PetscCall(KSPSetType(ksp, KSPCG));
  PC pc;
  PetscCall(KSPGetPC(ksp, &pc));
  PetscCall(PCSetType(pc, PCGAMG));
  PetscCall(KSPSetTolerances(ksp, PETSC_DEFAULT, PETSC_DEFAULT, PETSC_DEFAULT, PetscInt(options.max_iterations)));
  PetscCall(KSPSetInitialGuessNonzero(ksp, PETSC_TRUE));
  // the test below needs no residual norm; CG's natural norm costs no reduction
  PetscCall(KSPSetNormType(ksp, KSP_NORM_NATURAL));
  PetscCall(KSPSetFromOptions(ksp));
  Petsc_stopping stopping{Stopping_test(options)};
  PetscCall(VecDuplicate(u, &stopping.previous));
  PetscCall(VecDuplicate(u, &stopping.change));
  PetscCall(KSPSetConvergenceTest(ksp, &Petsc_stopping::converged, &stopping, nullptr));

  x.assign(s.rows, std::array<double, D>{});
  report = Petsc_solve_report();
  const int solves = s.block ? 1 : D;
  for(int c = 0; c < solves; ++c) {
    PetscScalar *bv, *uv;
    PetscCall(VecGetArray(b, &bv));
    PetscCall(VecGetArray(u, &uv));
    for(std::size_t r = 0; r < s.rows; ++r)
      if(owned(global[r]))
        for(PetscInt k = 0; k < bs; ++k) {
          const PetscInt comp = s.block ? k : c;
          bv[(global[r] - first) * bs + k] = s.rhs[r][comp];
          uv[(global[r] - first) * bs + k] = s.initial[r][comp];
        }
    PetscCall(VecRestoreArray(b, &bv));
    PetscCall(VecRestoreArray(u, &uv));
    stopping.test = Stopping_test(options);
    stopping.decided = false;
    PetscCall(KSPSolve(ksp, b, u));
    KSPConvergedReason reason;
    PetscCall(KSPGetConvergedReason(ksp, &reason));
    PetscInt its;
    PetscCall(KSPGetIterationNumber(ksp, &its));
    report.iterations += its;
    report.converged = report.converged && reason > 0;
    report.last_max_update = std::max(report.last_max_update, stopping.test.last());
    if(stopping.decided || reason <= 0)
      report.error_estimate = std::max(report.error_estimate, stopping.test.estimate());
    PetscCall(VecScatterBegin(to_all, u, all, INSERT_VALUES, SCATTER_FORWARD));
    PetscCall(VecScatterEnd(to_all, u, all, INSERT_VALUES, SCATTER_FORWARD));
    const PetscScalar* av;
    PetscCall(VecGetArrayRead(all, &av));
    for(std::size_t r = 0; r < s.rows; ++r)
      for(PetscInt k = 0; k < bs; ++k)
        x[r][s.block ? k : c] = PetscRealPart(av[PetscInt(r) * bs + k]);
    PetscCall(VecRestoreArrayRead(all, &av));
  }
  PetscCall(KSPDestroy(&ksp));
  PetscCall(VecDestroy(&stopping.change));
  PetscCall(VecDestroy(&stopping.previous));
  PetscCall(VecScatterDestroy(&to_all));
  PetscCall(VecDestroy(&all));
  PetscCall(VecDestroy(&u));
  PetscCall(VecDestroy(&b));
  PetscCall(MatDestroy(&A));
  return 0;
}

} // namespace internal
} // namespace spring_motion

#endif
