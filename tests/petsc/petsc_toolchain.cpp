// Checks the toolchain the PETSc backend stands on: an MPIAIJ matrix whose
// rows are spread over the ranks, solved with KSP CG preconditioned by GAMG,
// the pair the backend uses for the spring systems (docs/scaling.md).
// The system is the 1D Laplacian tridiag(-1, 2, -1) with the right-hand side
// e_n, whose solution x_i = (i + 1) / (n + 1) is known exactly, so the check
// fails on a wrong distribution or a preconditioner that is not symmetric.
// n = 1 runs too: on 2 ranks one rank then owns no row, as a mesh with fewer
// free vertices than ranks would leave it.
#include <petscksp.h>

#include <cmath>
#include <cstdio>

namespace {

PetscErrorCode solve_laplacian(PetscInt n, PetscReal* max_error, PetscInt* iterations)
{
  Mat A;
  PetscCall(MatCreateAIJ(PETSC_COMM_WORLD, PETSC_DECIDE, PETSC_DECIDE, n, n, 3, nullptr, 2, nullptr, &A));
  PetscInt first, end;
  PetscCall(MatGetOwnershipRange(A, &first, &end));
  for (PetscInt i = first; i < end; ++i) {
    if (i > 0) PetscCall(MatSetValue(A, i, i - 1, -1.0, INSERT_VALUES));
    PetscCall(MatSetValue(A, i, i, 2.0, INSERT_VALUES));
    if (i + 1 < n) PetscCall(MatSetValue(A, i, i + 1, -1.0, INSERT_VALUES));
  }
  PetscCall(MatAssemblyBegin(A, MAT_FINAL_ASSEMBLY));
  PetscCall(MatAssemblyEnd(A, MAT_FINAL_ASSEMBLY));
  PetscCall(MatSetOption(A, MAT_SPD, PETSC_TRUE));

  Vec x, b;
  PetscCall(MatCreateVecs(A, &x, &b));
  PetscCall(VecSet(b, 0.0));
  if (first <= n - 1 && n - 1 < end) PetscCall(VecSetValue(b, n - 1, 1.0, INSERT_VALUES));
  PetscCall(VecAssemblyBegin(b));
  PetscCall(VecAssemblyEnd(b));

  KSP ksp;
  PetscCall(KSPCreate(PETSC_COMM_WORLD, &ksp));
  PetscCall(KSPSetOperators(ksp, A, A));
  PetscCall(KSPSetType(ksp, KSPCG));
  PC pc;
  PetscCall(KSPGetPC(ksp, &pc));
  PetscCall(PCSetType(pc, PCGAMG));
  PetscCall(KSPSetTolerances(ksp, 1e-13, 1e-50, PETSC_DEFAULT, 10000));
  PetscCall(KSPSetFromOptions(ksp));
  PetscCall(KSPSolve(ksp, b, x));
  KSPConvergedReason reason;
  PetscCall(KSPGetConvergedReason(ksp, &reason));
  PetscCall(KSPGetIterationNumber(ksp, iterations));

  const PetscScalar* xv;
  PetscCall(VecGetArrayRead(x, &xv));
  PetscReal local = 0;
  for (PetscInt i = first; i < end; ++i)
    local = std::fmax(local, std::fabs(PetscRealPart(xv[i - first]) - double(i + 1) / double(n + 1)));
  PetscCall(VecRestoreArrayRead(x, &xv));
  PetscCallMPI(MPI_Allreduce(&local, max_error, 1, MPIU_REAL, MPIU_MAX, PETSC_COMM_WORLD));
  if (reason < 0) *max_error = PETSC_INFINITY;

  PetscCall(KSPDestroy(&ksp));
  PetscCall(VecDestroy(&x));
  PetscCall(VecDestroy(&b));
  PetscCall(MatDestroy(&A));
  return 0;
}

} // namespace

int main(int argc, char** argv)
{
  PetscCall(PetscInitialize(&argc, &argv, nullptr, nullptr));
  PetscMPIInt size;
  PetscCallMPI(MPI_Comm_size(PETSC_COMM_WORLD, &size));
  int failures = 0;
  for (PetscInt n : {PetscInt(1), PetscInt(2), PetscInt(1000)}) {
    PetscReal error = 0;
    PetscInt iterations = 0;
    PetscCall(solve_laplacian(n, &error, &iterations));
    // cond(A) ~ 4 n^2 / pi^2 ~ 4e5 for n = 1000: a relative residual of 1e-13
    // leaves an error far below 1e-8 in a solution of size 1
    const bool ok = error < 1e-8;
    failures += ok ? 0 : 1;
    PetscCall(PetscPrintf(PETSC_COMM_WORLD, "%d ranks, n = %d: %d CG+GAMG iterations, max error %g %s\n",
                          int(size), int(n), int(iterations), double(error), ok ? "ok" : "FAILED"));
  }
  PetscCall(PetscFinalize());
  return failures == 0 ? 0 : 1;
}
