/* Unit test of the direct solver (src/lu.c), at any number of ranks.
   1. The nested-dissection ordering of the graph of a hexahedral grid with 3 unknowns per node
      (a thin sheet and a cube): a permutation, the same on every call, and fewer entries in the
      Cholesky factor of the permuted pattern (symbolic elimination) than the natural ordering.
   2. PCSetLUND on an unsymmetric MPIAIJ matrix with that pattern: the solution against the exact
      one; new values refactorise without a new analysis, a new pattern is analysed again; a
      singular matrix fails cleanly (the KSP reports the failure, no abort) and the next good
      matrix is solved again. */
#include <petscksp.h>
#include <lu.h>
#include "testutil.h"

static PetscMPIInt rank = 0;

/* graph of an nx x ny x nz node grid of hexahedra, 3 unknowns per node: unknown (node, c) is
   coupled to every unknown of the nodes sharing an element with it (diagonal left out) */
static PetscErrorCode GridGraph(PetscInt nx, PetscInt ny, PetscInt nz, PetscInt *N, PetscInt **xadj, PetscInt **adj)
{
  PetscInt n = nx * ny * nz, k = 0;

  PetscFunctionBeginUser;
  *N = 3 * n;
  PetscCall(PetscMalloc1(*N + 1, xadj));
  PetscCall(PetscMalloc1(*N * 81, adj));
  (*xadj)[0] = 0;
  for (PetscInt v = 0; v < n; v++) {
    const PetscInt i = v % nx, j = (v / nx) % ny, l = v / (nx * ny);
    for (PetscInt c = 0; c < 3; c++) {
      for (PetscInt dl = -1; dl <= 1; dl++)
        for (PetscInt dj = -1; dj <= 1; dj++)
          for (PetscInt di = -1; di <= 1; di++) {
            const PetscInt ii = i + di, jj = j + dj, ll = l + dl;
            if (ii < 0 || ii >= nx || jj < 0 || jj >= ny || ll < 0 || ll >= nz) continue;
            for (PetscInt cc = 0; cc < 3; cc++) {
              const PetscInt w = 3 * (ii + nx * (jj + ny * ll)) + cc;
              if (w != 3 * v + c) (*adj)[k++] = w;
            }
          }
      (*xadj)[3 * v + c + 1] = k;
    }
  }
  PetscFunctionReturn(0);
}

/* entries of the Cholesky factor L (diagonal included) of the pattern permuted by iperm (row i
   eliminated at position iperm[i]): column structures merged up the elimination tree */
static PetscErrorCode FactorEntries(PetscInt N, const PetscInt xadj[], const PetscInt adj[], const PetscInt iperm[], PetscInt64 *count)
{
  PetscInt  *perm, **col, *ncol, *parent, *buf, *mark;
  PetscInt64 total = 0;

  PetscFunctionBeginUser;
  PetscCall(PetscMalloc6(N, &perm, N, &col, N, &ncol, N, &parent, N, &buf, N, &mark));
  for (PetscInt i = 0; i < N; i++) {
    perm[iperm[i]] = i;
    parent[i] = -1;
    mark[i] = -1;
  }
  for (PetscInt p = 0; p < N; p++) {
    const PetscInt v = perm[p];
    PetscInt       m = 0;
    mark[p] = p;
    for (PetscInt q = xadj[v]; q < xadj[v + 1]; q++) {
      const PetscInt r = iperm[adj[q]];
      if (r > p && mark[r] != p) { mark[r] = p; buf[m++] = r; }
    }
    for (PetscInt c = 0; c < p; c++) /* children of p: columns whose first off-diagonal row is p */
      if (parent[c] == p) {
        for (PetscInt e = 0; e < ncol[c]; e++)
          if (col[c][e] > p && mark[col[c][e]] != p) { mark[col[c][e]] = p; buf[m++] = col[c][e]; }
        PetscCall(PetscFree(col[c])); /* no longer needed: its structure is now in p's */
      }
    PetscCall(PetscSortInt(m, buf));
    PetscCall(PetscMalloc1(PetscMax(m, 1), &col[p]));
    PetscCall(PetscArraycpy(col[p], buf, m));
    ncol[p]   = m;
    parent[p] = m ? buf[0] : -1;
    total += m + 1;
  }
  for (PetscInt p = 0; p < N; p++)
    if (parent[p] < 0) PetscCall(PetscFree(col[p]));
  PetscCall(PetscFree6(perm, col, ncol, parent, buf, mark));
  *count = total;
  PetscFunctionReturn(0);
}

static PetscErrorCode TestOrdering(PetscInt nx, PetscInt ny, PetscInt nz, double max_ratio)
{
  PetscInt  *xadj, *adj, N, *ip1, *ip2, *nat, *seen;
  PetscInt64 fnd, fnat;
  PetscBool  isperm = PETSC_TRUE, same = PETSC_TRUE;

  PetscFunctionBeginUser;
  PetscCall(GridGraph(nx, ny, nz, &N, &xadj, &adj));
  PetscCall(PetscMalloc4(N, &ip1, N, &ip2, N, &nat, N, &seen));
  PetscCall(LUNestedDissection(N, xadj, adj, ip1));
  PetscCall(LUNestedDissection(N, xadj, adj, ip2));
  for (PetscInt i = 0; i < N; i++) {
    seen[i] = 0;
    nat[i]  = i;
  }
  for (PetscInt i = 0; i < N; i++) {
    if (ip1[i] < 0 || ip1[i] >= N || seen[ip1[i]]++) isperm = PETSC_FALSE;
    if (ip1[i] != ip2[i]) same = PETSC_FALSE;
  }
  TU_CHECK(isperm && same, "nested dissection of a %" PetscInt_FMT "x%" PetscInt_FMT "x%" PetscInt_FMT " node grid (%" PetscInt_FMT " unknowns): a permutation%s, the same on a second call%s", nx, ny, nz, N, isperm ? "" : " (NOT)", same ? "" : " (NOT)");
  if (isperm) {
    PetscCall(FactorEntries(N, xadj, adj, ip1, &fnd));
    PetscCall(FactorEntries(N, xadj, adj, nat, &fnat));
    TU_CHECK((double)fnd < max_ratio * (double)fnat, "  entries in the factor: %lld with nested dissection, %lld in the natural (banded) order, ratio %.3f (limit %.2f)", (long long)fnd, (long long)fnat, (double)fnd / (double)fnat, max_ratio);
  }
  PetscCall(PetscFree4(ip1, ip2, nat, seen));
  PetscCall(PetscFree(xadj));
  PetscCall(PetscFree(adj));
  PetscFunctionReturn(0);
}

/* the grid matrix, unsymmetric, diagonally dominant; extra: one more coupling (a new pattern);
   singular: row and column 0 zero */
static PetscErrorCode GridMatrix(PetscInt nx, PetscInt ny, PetscInt nz, PetscReal shift, PetscBool extra, PetscBool singular, Mat *A)
{
  PetscInt *xadj, *adj, N, rs, re;

  PetscFunctionBeginUser;
  PetscCall(GridGraph(nx, ny, nz, &N, &xadj, &adj));
  PetscCall(MatCreateAIJ(PETSC_COMM_WORLD, PETSC_DECIDE, PETSC_DECIDE, N, N, 82, NULL, 82, NULL, A));
  PetscCall(MatGetOwnershipRange(*A, &rs, &re));
  for (PetscInt i = rs; i < re; i++) {
    PetscScalar d = shift + (PetscScalar)(xadj[i + 1] - xadj[i]);
    for (PetscInt q = xadj[i]; q < xadj[i + 1]; q++) {
      const PetscInt    j = adj[q];
      const PetscScalar v = (singular && (i == 0 || j == 0)) ? 0.0 : -0.5 - 0.4 * PetscSinReal((PetscReal)(i + 2 * j));
      PetscCall(MatSetValue(*A, i, j, v, INSERT_VALUES));
    }
    if (singular && i == 0) d = 0;
    PetscCall(MatSetValue(*A, i, i, d, INSERT_VALUES));
    if (extra && i == 0) PetscCall(MatSetValue(*A, 0, N - 1, 0.25, INSERT_VALUES));
    if (extra && i == N - 1) PetscCall(MatSetValue(*A, N - 1, 0, -0.25, INSERT_VALUES));
  }
  PetscCall(MatAssemblyBegin(*A, MAT_FINAL_ASSEMBLY));
  PetscCall(MatAssemblyEnd(*A, MAT_FINAL_ASSEMBLY));
  PetscCall(PetscFree(xadj));
  PetscCall(PetscFree(adj));
  PetscFunctionReturn(0);
}

/* solve A x = A x_exact; returns the largest error and the KSP's reason */
static PetscErrorCode Solve(KSP ksp, Mat A, PetscReal *err, KSPConvergedReason *reason)
{
  Vec       x, b, xe;
  PetscInt  rs, re;

  PetscFunctionBeginUser;
  PetscCall(MatCreateVecs(A, &x, &b));
  PetscCall(VecDuplicate(x, &xe));
  PetscCall(VecGetOwnershipRange(xe, &rs, &re));
  for (PetscInt i = rs; i < re; i++) PetscCall(VecSetValue(xe, i, 1.0 + PetscSinReal(0.1 * (PetscReal)i), INSERT_VALUES));
  PetscCall(VecAssemblyBegin(xe));
  PetscCall(VecAssemblyEnd(xe));
  PetscCall(MatMult(A, xe, b));
  PetscCall(KSPSetOperators(ksp, A, A));
  PetscCall(KSPSolve(ksp, b, x));
  PetscCall(KSPGetConvergedReason(ksp, reason));
  PetscCall(VecAXPY(x, -1.0, xe));
  PetscCall(VecNorm(x, NORM_INFINITY, err));
  PetscCall(VecDestroy(&x));
  PetscCall(VecDestroy(&b));
  PetscCall(VecDestroy(&xe));
  PetscFunctionReturn(0);
}

int main(int argc, char **argv)
{
  KSP                ksp;
  PC                 pc;
  Mat                A;
  PetscReal          err;
  KSPConvergedReason reason;
  PetscInt           na, nf;
  PetscMPIInt        size;

  PetscCall(PetscInitialize(&argc, &argv, NULL, NULL));
  PetscCallMPI(MPI_Comm_rank(PETSC_COMM_WORLD, &rank));
  PetscCallMPI(MPI_Comm_size(PETSC_COMM_WORLD, &size));

  if (rank == 0) {
    PetscCall(TestOrdering(24, 24, 3, 0.5)); /* a sheet: banded fill grows with the width */
    PetscCall(TestOrdering(10, 10, 10, 0.8));
  }

  PetscCall(KSPCreate(PETSC_COMM_WORLD, &ksp));
  PetscCall(KSPSetType(ksp, KSPPREONLY));
  PetscCall(KSPGetPC(ksp, &pc));
  PetscCall(PCSetLUND(pc));

  PetscCall(GridMatrix(12, 10, 3, 1.0, PETSC_FALSE, PETSC_FALSE, &A));
  PetscCall(Solve(ksp, A, &err, &reason));
  PetscCall(PCLUNDGetCounts(pc, &na, &nf));
  CHECK_ALL(reason > 0 && err < 1e-12 && na == 1 && nf == 1, "LU (nested dissection), %d rank(s), unsymmetric 1080 x 1080 grid matrix: largest error %.2e, %" PetscInt_FMT " analysis, %" PetscInt_FMT " factorisation", size, (double)err, na, nf);

  /* new values, same pattern: factorised again, not analysed again */
  PetscCall(MatShift(A, 0.5));
  PetscCall(MatScale(A, 3.0));
  PetscCall(Solve(ksp, A, &err, &reason));
  PetscCall(PCLUNDGetCounts(pc, &na, &nf));
  CHECK_ALL(reason > 0 && err < 1e-12 && na == 1 && nf == 2, "new values: largest error %.2e, still %" PetscInt_FMT " analysis, %" PetscInt_FMT " factorisations", (double)err, na, nf);
  PetscCall(MatDestroy(&A));

  /* a new pattern: analysed again */
  PetscCall(GridMatrix(12, 10, 3, 1.0, PETSC_TRUE, PETSC_FALSE, &A));
  PetscCall(Solve(ksp, A, &err, &reason));
  PetscCall(PCLUNDGetCounts(pc, &na, &nf));
  CHECK_ALL(reason > 0 && err < 1e-12 && na == 2 && nf == 3, "new pattern (one coupling more): largest error %.2e, %" PetscInt_FMT " analyses, %" PetscInt_FMT " factorisations", (double)err, na, nf);
  PetscCall(MatDestroy(&A));

  /* singular: the solve reports the failure, and the next matrix is solved again */
  PetscCall(GridMatrix(12, 10, 3, 1.0, PETSC_FALSE, PETSC_TRUE, &A));
  PetscCall(Solve(ksp, A, &err, &reason));
  PetscCall(PCLUNDGetCounts(pc, &na, &nf));
  CHECK_ALL(reason < 0 && !(err < 1e300) && nf == 3, "singular matrix (a zero row and column): the KSP fails (%s), solution not finite, no factorisation counted", KSPConvergedReasons[reason]);
  PetscCall(MatDestroy(&A));
  PetscCall(GridMatrix(12, 10, 3, 2.0, PETSC_FALSE, PETSC_FALSE, &A));
  PetscCall(Solve(ksp, A, &err, &reason));
  CHECK_ALL(reason > 0 && err < 1e-12, "after the failure, a regular matrix: largest error %.2e (%s)", (double)err, KSPConvergedReasons[reason]);
  PetscCall(MatDestroy(&A));

  PetscCall(KSPDestroy(&ksp));
  PetscCall(PetscFinalize());
  TU_RETURN();
}
