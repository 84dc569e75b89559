// Copyright (c) 2026 SpringMotion developers.
#ifndef SPRING_MOTION_INTERNAL_SOLVER_PETSC_SOLVE_H
#define SPRING_MOTION_INTERNAL_SOLVER_PETSC_SOLVE_H

// Only with the CMake option SPRING_MOTION_WITH_PETSC (docs/scaling.md).
#include <spring_motion/Step_system_view.h>

#include <petscksp.h>

#include <algorithm>
#include <array>
#include <vector>

namespace spring_motion {
namespace internal {

/// What one PETSc solve of a step system did.
struct Petsc_solve_report
{
  PetscInt iterations = 0; ///< CG iterations, summed over the components of a scalar system
  bool converged = true;
};

/// Solves a step's free system (the same rows, values, right-hand side and
/// start the shared-memory solver gets) with KSP CG preconditioned by GAMG on
/// the ranks of `comm`. The system is replicated: every rank holds the whole
/// view and inserts only the rows PETSc gives it, so no row is sent; the
/// solution is gathered back to every rank in `x` (one entry per row).
/// A scalar system is an AIJ matrix solved once per component; a block system
/// is an AIJ matrix of block size D, one solve for all components, so GAMG
/// aggregates whole vertices and sees the D x D coupling. `rtol` bounds the preconditioned residual norm
/// relative to the right-hand side's.
template <int D>
PetscErrorCode petsc_solve_step_system(MPI_Comm comm, const Step_system_view<D>& s, double rtol,
                                       std::vector<std::array<double, D>>& x, Petsc_solve_report& report)
{
  const PetscInt n = PetscInt(s.rows);
  const PetscInt bs = s.block ? D : 1;
  // contiguous block rows, as even as can be; a rank may own none
  PetscMPIInt size, rank;
  PetscCallMPI(MPI_Comm_size(comm, &size));
  PetscCallMPI(MPI_Comm_rank(comm, &rank));
  const PetscInt first = n / size * rank + std::min<PetscInt>(rank, n % size);
  const PetscInt end = first + n / size + (rank < n % size ? 1 : 0);
  std::vector<PetscInt> d_nnz(std::size_t(end - first), 1), o_nnz(std::size_t(end - first), 0);
  for(PetscInt r = first; r < end; ++r)
    for(Index q = s.row_offsets[r]; q < s.row_offsets[r + 1]; ++q)
      ++(PetscInt(s.columns[q]) >= first && PetscInt(s.columns[q]) < end ? d_nnz : o_nnz)[std::size_t(r - first)];
  Mat A;
  PetscCall(MatCreate(comm, &A));
  PetscCall(MatSetSizes(A, (end - first) * bs, (end - first) * bs, n * bs, n * bs));
  // AIJ with block size D, not BAIJ: GAMG (PETSc 3.18) builds its graph from
  // AIJ only, and reads the block size as the number of components
  PetscCall(MatSetType(A, MATAIJ));
  PetscCall(MatSetBlockSize(A, bs));
  PetscCall(MatXAIJSetPreallocation(A, bs, d_nnz.data(), o_nnz.data(), nullptr, nullptr));
  {
    std::vector<PetscInt> cols;
    std::vector<PetscScalar> vals;
    for(PetscInt r = first; r < end; ++r) {
      const std::size_t R = std::size_t(r);
      cols.assign(1, r);
      vals.assign(s.diagonal + R * bs * bs, s.diagonal + (R + 1) * bs * bs);
      for(Index q = s.row_offsets[R]; q < s.row_offsets[R + 1]; ++q) {
        cols.push_back(PetscInt(s.columns[q]));
        for(PetscInt a = 0; a < bs * bs; ++a)
          vals.push_back(s.values[std::size_t(q) * bs * bs + a]);
      }
      // values of a row of blocks, laid out as PETSc's row-oriented input:
      // block row a of every entry, entry after entry
      std::vector<PetscScalar> row(vals.size());
      const std::size_t m = cols.size();
      for(std::size_t e = 0; e < m; ++e)
        for(PetscInt a = 0; a < bs; ++a)
          for(PetscInt c = 0; c < bs; ++c)
            row[std::size_t(a) * m * bs + e * bs + c] = vals[e * bs * bs + a * bs + c];
      PetscCall(MatSetValuesBlocked(A, 1, &r, PetscInt(m), cols.data(), row.data(), INSERT_VALUES));
    }
  }
  PetscCall(MatAssemblyBegin(A, MAT_FINAL_ASSEMBLY));
  PetscCall(MatAssemblyEnd(A, MAT_FINAL_ASSEMBLY));
  PetscCall(MatSetOption(A, MAT_SPD, PETSC_TRUE));

  Vec b, u, all;
  PetscCall(MatCreateVecs(A, &u, &b));
  VecScatter to_all;
  PetscCall(VecScatterCreateToAll(u, &to_all, &all));
  KSP ksp;
  PetscCall(KSPCreate(comm, &ksp));
  PetscCall(KSPSetOperators(ksp, A, A));
  PetscCall(KSPSetType(ksp, KSPCG));
  PC pc;
  PetscCall(KSPGetPC(ksp, &pc));
  PetscCall(PCSetType(pc, PCGAMG));
  PetscCall(KSPSetTolerances(ksp, rtol, 0.0, PETSC_DEFAULT, 100000));
  PetscCall(KSPSetInitialGuessNonzero(ksp, PETSC_TRUE));
  PetscCall(KSPSetFromOptions(ksp));

  x.assign(s.rows, std::array<double, D>{});
  report = Petsc_solve_report();
  const int solves = s.block ? 1 : D;
  for(int c = 0; c < solves; ++c) {
    PetscScalar *bv, *uv;
    PetscCall(VecGetArray(b, &bv));
    PetscCall(VecGetArray(u, &uv));
    for(PetscInt r = first; r < end; ++r)
      for(PetscInt k = 0; k < bs; ++k) {
        const PetscInt comp = s.block ? k : c;
        bv[(r - first) * bs + k] = s.rhs[r][comp];
        uv[(r - first) * bs + k] = s.initial[r][comp];
      }
    PetscCall(VecRestoreArray(b, &bv));
    PetscCall(VecRestoreArray(u, &uv));
    PetscCall(KSPSolve(ksp, b, u));
    KSPConvergedReason reason;
    PetscCall(KSPGetConvergedReason(ksp, &reason));
    PetscInt its;
    PetscCall(KSPGetIterationNumber(ksp, &its));
    report.iterations += its;
    report.converged = report.converged && reason > 0;
    PetscCall(VecScatterBegin(to_all, u, all, INSERT_VALUES, SCATTER_FORWARD));
    PetscCall(VecScatterEnd(to_all, u, all, INSERT_VALUES, SCATTER_FORWARD));
    const PetscScalar* av;
    PetscCall(VecGetArrayRead(all, &av));
    for(PetscInt r = 0; r < n; ++r)
      for(PetscInt k = 0; k < bs; ++k)
        x[std::size_t(r)][s.block ? k : c] = PetscRealPart(av[r * bs + k]);
    PetscCall(VecRestoreArrayRead(all, &av));
  }
  PetscCall(KSPDestroy(&ksp));
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
