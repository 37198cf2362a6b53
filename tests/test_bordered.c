/* Unit test of the bordered Jacobian (src/solver/bordered.c), at any number of ranks: the same
   entries added to a bordered matrix (a hypre mesh block and nt = 3 tool unknowns) and to one
   assembled AIJ matrix of the same layout give the same products.
   1. Element blocks over the mesh (rows of other ranks among them, negative indices skipped),
      node-tool and tool-node blocks from every rank, tool-tool blocks from every rank: MatMult
      and MatMultTranspose of a vector agree to 1e-13 of the product's norm.
   2. MatZeroRowsColumns of some of every rank's rows (diagonal 1): the products agree again.
   3. MatZeroEntries and new values (a second Jacobian): they agree again, nothing of the first
      left.
   4. INSERT_VALUES into a tool's row is refused with an error, not taken. */
#define _DEFAULT_SOURCE /* ffs() in hypre's utilities header */
#include <strings.h>

#include <petscmat.h>
#include <petscmathypre.h>
#include <bordered.h>
#include "testutil.h"

static PetscMPIInt rank = 0, size = 1;

/* a deterministic value of the entry (i, j) in pass p, the same on every rank count */
static PetscScalar Val(PetscInt i, PetscInt j, PetscInt p)
{
  unsigned long h = (unsigned long)(i + 1) * 2654435761UL ^ (unsigned long)(j + 7) * 40503UL ^ (unsigned long)(p + 3) * 97UL;
  h ^= h >> 13;
  h *= 0x5bd1e995UL;
  h ^= h >> 15;
  return (PetscScalar)((double)(h % 20001UL) / 10000.0 - 1.0);
}

/* element e couples nodes e and e+1 of a chain (3 unknowns per node); component 1 of every fifth
   node is given as -1 (skipped, as a constrained component); a node-tool and tool-node block per
   owned node, a tool-tool block per rank */
static PetscErrorCode Fill(Mat M, PetscInt nn, PetscInt n0, PetscInt n1, PetscInt p)
{
  const PetscInt Nm = 3 * nn, nt = 3;
  PetscScalar    v[36];

  PetscFunctionBeginUser;
  for (PetscInt e = n0; e < n1 && e < nn - 1; e++) {
    PetscInt idx[6];
    for (int a = 0; a < 2; a++)
      for (int c = 0; c < 3; c++) idx[3 * a + c] = ((e + a) % 5 == 0 && c == 1) ? -1 : 3 * (e + a) + c;
    for (int r = 0; r < 6; r++)
      for (int c = 0; c < 6; c++) v[6 * r + c] = Val(3 * e + r, 3 * e + c, p) + (r == c ? 10.0 : 0.0);
    PetscCall(MatSetValues(M, 6, idx, 6, idx, v, ADD_VALUES));
  }
  for (PetscInt i = n0; i < n1; i++) {
    PetscInt sg[3], td[3];
    for (int c = 0; c < 3; c++) {
      sg[c] = (i % 5 == 0 && c == 1) ? -1 : 3 * i + c;
      td[c] = Nm + c;
    }
    for (int r = 0; r < 3; r++)
      for (int c = 0; c < 3; c++) v[3 * r + c] = Val(sg[r], td[c], p);
    PetscCall(MatSetValues(M, 3, sg, 3, td, v, ADD_VALUES));
    for (int r = 0; r < 3; r++)
      for (int c = 0; c < 3; c++) v[3 * r + c] = Val(td[r] + 1000, sg[c], p);
    PetscCall(MatSetValues(M, 3, td, 3, sg, v, ADD_VALUES));
  }
  {
    PetscInt td[3];
    for (int c = 0; c < 3; c++) td[c] = Nm + c;
    for (int r = 0; r < 3; r++)
      for (int c = 0; c < nt; c++) v[3 * r + c] = Val(rank, 3 * r + c, p) + (r == c ? 5.0 : 0.0);
    PetscCall(MatSetValues(M, 3, td, 3, td, v, ADD_VALUES));
  }
  PetscCall(MatAssemblyBegin(M, MAT_FINAL_ASSEMBLY));
  PetscCall(MatAssemblyEnd(M, MAT_FINAL_ASSEMBLY));
  PetscFunctionReturn(0);
}

static PetscErrorCode Compare(Mat Jb, Mat J0, const char *what, PetscReal tol)
{
  Vec       x, y0, y1;
  PetscReal e, n;
  PetscInt  lo, hi;

  PetscFunctionBeginUser;
  PetscCall(MatCreateVecs(J0, &x, &y0));
  PetscCall(VecDuplicate(y0, &y1));
  PetscCall(VecGetOwnershipRange(x, &lo, &hi));
  for (PetscInt i = lo; i < hi; i++) PetscCall(VecSetValue(x, i, Val(i, 77, 9), INSERT_VALUES));
  PetscCall(VecAssemblyBegin(x));
  PetscCall(VecAssemblyEnd(x));
  for (int t = 0; t < 2; t++) {
    if (t) {
      PetscCall(MatMultTranspose(J0, x, y0));
      PetscCall(MatMultTranspose(Jb, x, y1));
    } else {
      PetscCall(MatMult(J0, x, y0));
      PetscCall(MatMult(Jb, x, y1));
    }
    PetscCall(VecNorm(y0, NORM_2, &n));
    PetscCall(VecAXPY(y1, -1.0, y0));
    PetscCall(VecNorm(y1, NORM_2, &e));
    CHECK_ALL(e <= tol * n, "%s: %s agrees with AIJ's (|diff| %.2e of %.2e)", what, t ? "MatMultTranspose" : "MatMult", (double)e, (double)n);
  }
  PetscCall(VecDestroy(&x));
  PetscCall(VecDestroy(&y0));
  PetscCall(VecDestroy(&y1));
  PetscFunctionReturn(0);
}

int main(int argc, char **argv)
{
  const PetscInt nn = 23, nt = 3, Nm = 3 * nn;
  PetscInt       n0, n1, nl, *dnz, *onz, mlo;
  Mat            A, Jb, J0;

  PetscCall(PetscInitialize(&argc, &argv, NULL, NULL));
  PetscCallMPI(MPI_Comm_rank(PETSC_COMM_WORLD, &rank));
  PetscCallMPI(MPI_Comm_size(PETSC_COMM_WORLD, &size));
  n0 = (nn * rank) / size;
  n1 = (nn * (rank + 1)) / size;
  nl = 3 * (n1 - n0);
  mlo = 3 * n0;
  /* the mesh block in hypre's format, preallocated for the chain's three-node rows */
  PetscCall(MatCreate(PETSC_COMM_WORLD, &A));
  PetscCall(MatSetSizes(A, nl, nl, Nm, Nm));
  PetscCall(MatSetType(A, MATHYPRE));
  PetscCall(PetscMalloc2(nl, &dnz, nl, &onz));
  for (PetscInt r = 0; r < nl; r++) {
    const PetscInt node = (mlo + r) / 3;
    dnz[r] = onz[r] = 0;
    for (PetscInt w = node - 1; w <= node + 1; w++) {
      if (w < 0 || w >= nn) continue;
      if (w >= n0 && w < n1) dnz[r] += 3;
      else onz[r] += 3;
    }
  }
  PetscCall(MatHYPRESetPreallocation(A, 0, dnz, 0, onz));
  PetscCall(PetscFree2(dnz, onz));
  PetscCall(MatCreateBordered(A, nt, &Jb));
  PetscCall(MatDestroy(&A));
  {
    PetscBool is;
    Mat       Ab;
    PetscInt  ntb;
    PetscCall(MatBorderedGetBlocks(Jb, &is, &Ab, &ntb, NULL, NULL, NULL));
    CHECK_ALL(is && ntb == nt && Ab, "MatBorderedGetBlocks: a bordered matrix with %d tool unknowns", (int)nt);
  }
  PetscCall(MatCreateAIJ(PETSC_COMM_WORLD, nl + (rank == size - 1 ? nt : 0), nl + (rank == size - 1 ? nt : 0), PETSC_DETERMINE, PETSC_DETERMINE, 12, NULL, 12, NULL, &J0));
  PetscCall(MatSetOption(J0, MAT_NEW_NONZERO_ALLOCATION_ERR, PETSC_FALSE));
  {
    PetscInt m, N;
    PetscCall(MatGetSize(Jb, &N, NULL));
    PetscCall(MatGetLocalSize(Jb, &m, NULL));
    CHECK_ALL(N == Nm + nt && m == nl + (rank == size - 1 ? nt : 0), "layout: %d global unknowns, the tools' on the last rank", (int)(Nm + nt));
  }

  /* 1. the first Jacobian */
  PetscCall(MatZeroEntries(Jb));
  PetscCall(Fill(Jb, nn, n0, n1, 0));
  PetscCall(Fill(J0, nn, n0, n1, 0));
  PetscCall(Compare(Jb, J0, "assembled", 1e-13));

  /* 2. rows and columns of conditions switched on: every third row of each rank's */
  {
    PetscInt rows[3 * 23], nr = 0;
    for (PetscInt r = mlo; r < mlo + nl; r++)
      if (r % 3 == 2 && (r / 3) % 5 != 0) rows[nr++] = r;
    PetscCall(MatSetOption(Jb, MAT_NO_OFF_PROC_ZERO_ROWS, PETSC_TRUE));
    PetscCall(MatZeroRowsColumns(Jb, nr, rows, 1.0, NULL, NULL));
    PetscCall(MatZeroRowsColumns(J0, nr, rows, 1.0, NULL, NULL));
    PetscCall(Compare(Jb, J0, "rows and columns zeroed", 1e-13));
  }

  /* 3. a second Jacobian on the same matrices */
  PetscCall(MatZeroEntries(Jb));
  PetscCall(MatZeroEntries(J0));
  PetscCall(Fill(Jb, nn, n0, n1, 1));
  PetscCall(Fill(J0, nn, n0, n1, 1));
  PetscCall(Compare(Jb, J0, "zeroed and filled again", 1e-13));

  /* 4. INSERT_VALUES into a tool's row: an error */
  {
    PetscErrorCode ierr;
    PetscInt       r = Nm, c = 0;
    PetscScalar    one = 1;
    PetscCall(PetscPushErrorHandler(PetscReturnErrorHandler, NULL));
    ierr = MatSetValues(Jb, 1, &r, 1, &c, &one, INSERT_VALUES);
    PetscCall(PetscPopErrorHandler());
    CHECK_ALL(ierr != 0, "INSERT_VALUES into a tool's row refused");
  }
  PetscCall(MatDestroy(&Jb));
  PetscCall(MatDestroy(&J0));
    PetscCall(PetscFinalize());
  TU_RETURN();
}
