/* The Jacobian bordered by force-driven tools' unknowns, stored as its mesh block and the border
   (include/bordered.h).

   Why: a blank holder driven by its force adds nt = 3 unknowns per tool, whose rows and columns
   are dense over the nodes the tool may touch. In one assembled AIJ matrix they are cheap, but
   the preconditioner for large meshes (-pc_type amgsys, src/solver/amg.c) works on the mesh block
   alone in hypre's format: with an AIJ Jacobian it keeps a second copy of the whole mesh block,
   the largest array of the run after BoomerAMG's hierarchy (1.30 GiB per 100 000 hexahedra on the
   square cup's first steps, against 0.76 for the punch whose Jacobian is assembled in hypre's
   format: doc/notes/process-solver.md). Here the mesh block is the only copy, assembled in
   place, and the border costs 2 nt vectors:

     J = [A  B]      y_A = A x_A + sum_k B_k x_T,k
         [C  D]      y_T,k = C_k . x_A + sum_j D_kj x_T,j

   B_k is the k-th tool column over the mesh's rows, C_k the k-th tool row (stored transposed, over
   the mesh's columns), D the tools' own block, summed over the ranks at each assembly (every rank
   adds its nodes' part; contact.c). The products take the mesh part of x and y in place (the mesh's
   rows come first in every rank's local range), the tools' part of x broadcast from the last rank.

   MatZeroRowsColumns (a condition switched on by a stage: bc.c) zeroes the rows and columns in
   hypre's arrays directly, the diagonal entry set, and the same rows of B_k and columns of C_k:
   MATHYPRE in PETSc 3.18 offers no such operation, and the pattern stays. */
#define _DEFAULT_SOURCE /* ffs() in hypre's utilities header */
#include <strings.h>

#include <petscmathypre.h>
#include <petsc/private/petscimpl.h> /* PetscObjectStateIncrease */
#include <HYPRE.h>
#include <HYPRE_parcsr_mv.h>
#include <_hypre_parcsr_mv.h>

#include "bordered.h"

typedef struct {
  Mat          A;          /* the mesh block                                                  */
  PetscInt     nt;         /* tool unknowns                                                   */
  PetscInt     Nm;         /* global mesh unknowns: the tools' are Nm .. Nm + nt - 1           */
  PetscInt     nm;         /* this rank's mesh rows                                            */
  PetscMPIInt  owner;      /* the rank with the tools' rows (the last)                         */
  Vec         *B, *C;      /* the border, over the mesh's rows                                 */
  PetscScalar *D, *Dloc;   /* D, and this rank's additions to it since the last zeroing        */
  Vec          xm, ym;     /* A's layout, no array of their own: the mesh parts of x and y     */
  PetscInt     ncap;       /* capacity of the scratch below                                    */
  PetscInt    *sc;         /* scratch: one row's mesh columns and values                       */
  PetscScalar *sv;
} Bordered;

static PetscErrorCode BorderedDestroy(void *ctx)
{
  Bordered *b = (Bordered *)ctx;

  PetscFunctionBeginUser;
  PetscCall(MatDestroy(&b->A));
  PetscCall(VecDestroyVecs(b->nt, &b->B));
  PetscCall(VecDestroyVecs(b->nt, &b->C));
  PetscCall(PetscFree2(b->D, b->Dloc));
  PetscCall(VecDestroy(&b->xm));
  PetscCall(VecDestroy(&b->ym));
  PetscCall(PetscFree2(b->sc, b->sv));
  PetscCall(PetscFree(b));
  PetscFunctionReturn(0);
}

static PetscErrorCode SetValues_Bordered(Mat J, PetscInt m, const PetscInt *ri, PetscInt n, const PetscInt *ci, const PetscScalar *v, InsertMode mode)
{
  Bordered *b;
  PetscBool mesh = PETSC_TRUE;

  PetscFunctionBeginUser;
  PetscCall(MatShellGetContext(J, &b));
  for (PetscInt i = 0; i < m; i++)
    if (ri[i] >= b->Nm) mesh = PETSC_FALSE;
  for (PetscInt j = 0; j < n; j++)
    if (ci[j] >= b->Nm) mesh = PETSC_FALSE;
  if (mesh) { /* an element's or a node's block: the mesh block alone */
    PetscCall(MatSetValues(b->A, m, ri, n, ci, v, mode));
    PetscFunctionReturn(0);
  }
  PetscCheck(mode == ADD_VALUES, PetscObjectComm((PetscObject)J), PETSC_ERR_SUP, "bordered Jacobian: the rows and columns of force-driven tools take ADD_VALUES only");
  if (n > b->ncap) {
    PetscCall(PetscFree2(b->sc, b->sv));
    b->ncap = n;
    PetscCall(PetscMalloc2(n, &b->sc, n, &b->sv));
  }
  for (PetscInt i = 0; i < m; i++) {
    const PetscInt r = ri[i];
    if (r < 0) continue;
    if (r < b->Nm) { /* a mesh row: A's columns, and B's */
      PetscInt na = 0;
      for (PetscInt j = 0; j < n; j++) {
        const PetscInt c = ci[j];
        if (c < 0) continue;
        if (c < b->Nm) {
          b->sc[na]   = c;
          b->sv[na++] = v[i * n + j];
        } else PetscCall(VecSetValue(b->B[c - b->Nm], r, v[i * n + j], ADD_VALUES));
      }
      if (na) PetscCall(MatSetValues(b->A, 1, &r, na, b->sc, b->sv, ADD_VALUES));
    } else { /* a tool's row: C's columns, and D's */
      const PetscInt k = r - b->Nm;
      PetscCheck(k < b->nt, PETSC_COMM_SELF, PETSC_ERR_ARG_OUTOFRANGE, "bordered Jacobian: row %" PetscInt_FMT " beyond the %" PetscInt_FMT " tool unknowns", r, b->nt);
      for (PetscInt j = 0; j < n; j++) {
        const PetscInt c = ci[j];
        if (c < 0) continue;
        if (c < b->Nm) PetscCall(VecSetValue(b->C[k], c, v[i * n + j], ADD_VALUES));
        else b->Dloc[k * b->nt + (c - b->Nm)] += v[i * n + j];
      }
    }
  }
  PetscFunctionReturn(0);
}

static PetscErrorCode ZeroEntries_Bordered(Mat J)
{
  Bordered *b;

  PetscFunctionBeginUser;
  PetscCall(MatShellGetContext(J, &b));
  PetscCall(MatZeroEntries(b->A));
  for (PetscInt k = 0; k < b->nt; k++) {
    PetscCall(VecZeroEntries(b->B[k]));
    PetscCall(VecZeroEntries(b->C[k]));
  }
  PetscCall(PetscArrayzero(b->D, b->nt * b->nt));
  PetscCall(PetscArrayzero(b->Dloc, b->nt * b->nt));
  PetscFunctionReturn(0);
}

static PetscErrorCode AssemblyBegin_Bordered(Mat J, MatAssemblyType type)
{
  Bordered *b;

  PetscFunctionBeginUser;
  PetscCall(MatShellGetContext(J, &b));
  PetscCall(MatAssemblyBegin(b->A, type));
  for (PetscInt k = 0; k < b->nt; k++) {
    PetscCall(VecAssemblyBegin(b->B[k]));
    PetscCall(VecAssemblyBegin(b->C[k]));
  }
  PetscFunctionReturn(0);
}

static PetscErrorCode AssemblyEnd_Bordered(Mat J, MatAssemblyType type)
{
  Bordered *b;

  PetscFunctionBeginUser;
  PetscCall(MatShellGetContext(J, &b));
  PetscCall(MatAssemblyEnd(b->A, type));
  for (PetscInt k = 0; k < b->nt; k++) {
    PetscCall(VecAssemblyEnd(b->B[k]));
    PetscCall(VecAssemblyEnd(b->C[k]));
  }
  /* D: every rank's additions (collective; a repeated assembly gives the same sum) */
  if (type == MAT_FINAL_ASSEMBLY) PetscCall(MPIU_Allreduce(b->Dloc, b->D, (PetscMPIInt)(b->nt * b->nt), MPIU_SCALAR, MPIU_SUM, PetscObjectComm((PetscObject)J)));
  PetscFunctionReturn(0);
}

/* x_T on every rank (from the tools' owner) */
static PetscErrorCode ToolPart(Bordered *b, MPI_Comm comm, const PetscScalar *xa, PetscScalar *t)
{
  PetscMPIInt rank;

  PetscFunctionBeginUser;
  PetscCallMPI(MPI_Comm_rank(comm, &rank));
  if (rank == b->owner)
    for (PetscInt k = 0; k < b->nt; k++) t[k] = xa[b->nm + k];
  PetscCallMPI(MPI_Bcast(t, (PetscMPIInt)b->nt, MPIU_SCALAR, b->owner, comm));
  PetscFunctionReturn(0);
}

static PetscErrorCode MultAny(Mat J, Vec x, Vec y, PetscBool trans)
{
  const MPI_Comm     comm = PetscObjectComm((PetscObject)J);
  Bordered          *b;
  const PetscScalar *xa;
  PetscScalar       *ya, t[3 * 64], d[3 * 64];
  PetscMPIInt        rank;

  PetscFunctionBeginUser;
  PetscCall(MatShellGetContext(J, &b));
  PetscCallMPI(MPI_Comm_rank(comm, &rank));
  PetscCall(VecGetArrayRead(x, &xa));
  PetscCall(ToolPart(b, comm, xa, t));
  PetscCall(VecGetArrayWrite(y, &ya));
  PetscCall(VecPlaceArray(b->xm, xa));
  PetscCall(VecPlaceArray(b->ym, ya));
  /* y_A = A x_A + B x_T (transposed: A^T x_A + C^T x_T); d = C x_A (transposed: B^T x_A) */
  if (trans) PetscCall(MatMultTranspose(b->A, b->xm, b->ym));
  else PetscCall(MatMult(b->A, b->xm, b->ym));
  PetscCall(VecMAXPY(b->ym, b->nt, t, trans ? b->C : b->B));
  PetscCall(VecMDot(b->xm, b->nt, trans ? b->B : b->C, d));
  PetscCall(VecResetArray(b->xm));
  PetscCall(VecResetArray(b->ym));
  if (rank == b->owner)
    for (PetscInt k = 0; k < b->nt; k++) {
      PetscScalar s = d[k];
      for (PetscInt j = 0; j < b->nt; j++) s += (trans ? b->D[j * b->nt + k] : b->D[k * b->nt + j]) * t[j];
      ya[b->nm + k] = s;
    }
  PetscCall(VecRestoreArrayWrite(y, &ya));
  PetscCall(VecRestoreArrayRead(x, &xa));
  PetscFunctionReturn(0);
}

static PetscErrorCode Mult_Bordered(Mat J, Vec x, Vec y)
{
  PetscFunctionBeginUser;
  PetscCall(MultAny(J, x, y, PETSC_FALSE));
  PetscFunctionReturn(0);
}

static PetscErrorCode MultTranspose_Bordered(Mat J, Vec x, Vec y)
{
  PetscFunctionBeginUser;
  PetscCall(MultAny(J, x, y, PETSC_TRUE));
  PetscFunctionReturn(0);
}

/* rows (global, this rank's own: MAT_NO_OFF_PROC_ZERO_ROWS) and the same columns zeroed, diag on
   the diagonal; collective. Only the mesh's rows: a tool's unknown is never a condition's. */
static PetscErrorCode ZeroRowsColumns_Bordered(Mat J, PetscInt n, const PetscInt rows[], PetscScalar diag, Vec x, Vec bb)
{
  const MPI_Comm      comm = PetscObjectComm((PetscObject)J);
  Bordered           *b;
  hypre_ParCSRMatrix *pA;
  PetscInt            rstart, rend, N = 0, *all = NULL;
  PetscMPIInt         size, nn, *cnt, *dsp;
  PetscBool          *zr;

  PetscFunctionBeginUser;
  PetscCall(MatShellGetContext(J, &b));
  PetscCheck(!x && !bb, comm, PETSC_ERR_SUP, "bordered Jacobian: MatZeroRowsColumns without x and b only");
  PetscCall(MatGetOwnershipRange(b->A, &rstart, &rend));
  { /* every row this rank's own mesh row (checked on all ranks together: collectives follow) */
    PetscInt bad = -1, gbad;
    for (PetscInt i = 0; i < n; i++)
      if (rows[i] < rstart || rows[i] >= rend) bad = rows[i];
    PetscCall(MPIU_Allreduce(&bad, &gbad, 1, MPIU_INT, MPI_MAX, comm));
    PetscCheck(gbad < 0, comm, PETSC_ERR_ARG_OUTOFRANGE, "bordered Jacobian: row %" PetscInt_FMT " to zero is not one of its rank's mesh rows", gbad);
  }
  /* every rank's rows: the columns to zero in the off-diagonal parts */
  PetscCallMPI(MPI_Comm_size(comm, &size));
  PetscCall(PetscMalloc2(size, &cnt, size + 1, &dsp));
  PetscCall(PetscMPIIntCast(n, &nn));
  PetscCallMPI(MPI_Allgather(&nn, 1, MPI_INT, cnt, 1, MPI_INT, comm));
  dsp[0] = 0;
  for (PetscMPIInt r = 0; r < size; r++) dsp[r + 1] = dsp[r] + cnt[r];
  N = dsp[size];
  PetscCall(PetscMalloc1(N + 1, &all));
  PetscCallMPI(MPI_Allgatherv(rows, nn, MPIU_INT, all, cnt, dsp, MPIU_INT, comm));
  PetscCall(PetscSortInt(N, all));
  PetscCall(PetscCalloc1(rend - rstart + 1, &zr));
  for (PetscInt i = 0; i < n; i++) zr[rows[i] - rstart] = PETSC_TRUE;
  PetscCall(MatHYPREGetParCSR(b->A, &pA));
  {
    hypre_CSRMatrix *dg = hypre_ParCSRMatrixDiag(pA), *od = hypre_ParCSRMatrixOffd(pA);
    HYPRE_Int       *di = hypre_CSRMatrixI(dg), *dj = hypre_CSRMatrixJ(dg), *oi = hypre_CSRMatrixI(od), *oj = hypre_CSRMatrixJ(od);
    HYPRE_Complex   *dv = hypre_CSRMatrixData(dg), *ov = hypre_CSRMatrixData(od);
    HYPRE_BigInt    *cmap = hypre_ParCSRMatrixColMapOffd(pA);
    const PetscInt   nloc = rend - rstart;
    PetscInt         nodiag = -1;
    for (PetscInt i = 0; i < nloc; i++) {
      PetscBool hit = PETSC_FALSE;
      for (HYPRE_Int k = di[i]; k < di[i + 1]; k++)
        if (zr[i] || zr[dj[k]]) {
          const PetscBool d = (zr[i] && dj[k] == i) ? PETSC_TRUE : PETSC_FALSE;
          dv[k] = d ? diag : 0;
          hit   = (PetscBool)(hit || d);
        }
      if (zr[i] && !hit) nodiag = rstart + i;
      if (oi)
        for (HYPRE_Int k = oi[i]; k < oi[i + 1]; k++) {
          PetscInt loc;
          if (zr[i]) ov[k] = 0;
          else {
            PetscCall(PetscFindInt((PetscInt)cmap[oj[k]], N, all, &loc));
            if (loc >= 0) ov[k] = 0;
          }
        }
    }
    PetscCall(MPIU_Allreduce(MPI_IN_PLACE, &nodiag, 1, MPIU_INT, MPI_MAX, comm));
    PetscCheck(nodiag < 0, comm, PETSC_ERR_PLIB, "bordered Jacobian: row %" PetscInt_FMT " has no diagonal entry in the mesh block's pattern", nodiag);
  }
  PetscCall(PetscObjectStateIncrease((PetscObject)b->A));
  for (PetscInt k = 0; k < b->nt; k++) { /* B's rows and C's columns (C stored transposed: rows) */
    PetscScalar *ba, *ca;
    PetscCall(VecGetArray(b->B[k], &ba));
    PetscCall(VecGetArray(b->C[k], &ca));
    for (PetscInt i = 0; i < n; i++) ba[rows[i] - rstart] = ca[rows[i] - rstart] = 0;
    PetscCall(VecRestoreArray(b->B[k], &ba));
    PetscCall(VecRestoreArray(b->C[k], &ca));
  }
  PetscCall(PetscFree(zr));
  PetscCall(PetscFree(all));
  PetscCall(PetscFree2(cnt, dsp));
  PetscFunctionReturn(0);
}

static PetscErrorCode SetOption_Bordered(Mat J, MatOption op, PetscBool flg)
{
  PetscFunctionBeginUser;
  (void)J;
  (void)op;
  (void)flg; /* the mesh block keeps its pattern (hypre's assembled matrix), the border is dense */
  PetscFunctionReturn(0);
}

static PetscErrorCode View_Bordered(Mat J, PetscViewer v)
{
  Bordered *b;
  PetscBool ascii;

  PetscFunctionBeginUser;
  PetscCall(MatShellGetContext(J, &b));
  PetscCall(PetscObjectTypeCompare((PetscObject)v, PETSCVIEWERASCII, &ascii));
  if (ascii) {
    MatType t;
    PetscCall(MatGetType(b->A, &t));
    PetscCall(PetscViewerASCIIPrintf(v, "bordered Jacobian: the mesh block (%s, %" PetscInt_FMT " unknowns) and %" PetscInt_FMT " force-driven tool unknowns (dense border)\n", t, b->Nm, b->nt));
  }
  PetscFunctionReturn(0);
}

PetscErrorCode MatCreateBordered(Mat A, PetscInt nt, Mat *J)
{
  const MPI_Comm comm = PetscObjectComm((PetscObject)A);
  Bordered      *b;
  PetscMPIInt    rank, size;
  PetscInt       nm, bs;

  PetscFunctionBeginUser;
  PetscCheck(nt > 0 && nt <= 3 * 64, comm, PETSC_ERR_ARG_OUTOFRANGE, "bordered Jacobian: %" PetscInt_FMT " tool unknowns, 1 to 192", nt);
  PetscCallMPI(MPI_Comm_rank(comm, &rank));
  PetscCallMPI(MPI_Comm_size(comm, &size));
  PetscCall(PetscNew(&b));
  PetscCall(PetscObjectReference((PetscObject)A));
  b->A     = A;
  b->nt    = nt;
  b->owner = size - 1;
  PetscCall(MatGetLocalSize(A, &nm, NULL));
  PetscCall(MatGetSize(A, &b->Nm, NULL));
  b->nm = nm;
  PetscCall(MatCreateVecs(A, &b->xm, NULL));
  PetscCall(VecDuplicateVecs(b->xm, nt, &b->B));
  PetscCall(VecDuplicateVecs(b->xm, nt, &b->C));
  PetscCall(VecDestroy(&b->xm));
  PetscCall(VecCreateMPIWithArray(comm, 1, nm, PETSC_DECIDE, NULL, &b->xm));
  PetscCall(VecCreateMPIWithArray(comm, 1, nm, PETSC_DECIDE, NULL, &b->ym));
  PetscCall(PetscCalloc2(nt * nt, &b->D, nt * nt, &b->Dloc));
  {
    const PetscInt nl = nm + (rank == b->owner ? nt : 0);
    PetscCall(MatCreateShell(comm, nl, nl, b->Nm + nt, b->Nm + nt, b, J));
  }
  PetscCall(MatGetBlockSize(A, &bs));
  if (bs > 1 && nt % bs == 0 && nm % bs == 0) PetscCall(MatSetBlockSize(*J, bs));
  PetscCall(MatShellSetManageScalingShifts(*J)); /* this shell owns its assembly and products */
  PetscCall(MatShellSetContextDestroy(*J, BorderedDestroy));
  PetscCall(MatShellSetOperation(*J, MATOP_SET_VALUES, (void (*)(void))SetValues_Bordered));
  PetscCall(MatShellSetOperation(*J, MATOP_ZERO_ENTRIES, (void (*)(void))ZeroEntries_Bordered));
  PetscCall(MatShellSetOperation(*J, MATOP_ASSEMBLY_BEGIN, (void (*)(void))AssemblyBegin_Bordered));
  PetscCall(MatShellSetOperation(*J, MATOP_ASSEMBLY_END, (void (*)(void))AssemblyEnd_Bordered));
  PetscCall(MatShellSetOperation(*J, MATOP_MULT, (void (*)(void))Mult_Bordered));
  PetscCall(MatShellSetOperation(*J, MATOP_MULT_TRANSPOSE, (void (*)(void))MultTranspose_Bordered));
  PetscCall(MatShellSetOperation(*J, MATOP_ZERO_ROWS_COLUMNS, (void (*)(void))ZeroRowsColumns_Bordered));
  PetscCall(MatShellSetOperation(*J, MATOP_SET_OPTION, (void (*)(void))SetOption_Bordered));
  PetscCall(MatShellSetOperation(*J, MATOP_VIEW, (void (*)(void))View_Bordered));
  PetscCall(PetscObjectComposeFunction((PetscObject)*J, "MatBorderedGetBlocks_C", MatBorderedGetBlocks));
  PetscFunctionReturn(0);
}

PetscErrorCode MatBorderedGetBlocks(Mat J, PetscBool *is, Mat *A, PetscInt *nt, const Vec **B, const Vec **C, const PetscScalar **D)
{
  PetscErrorCode (*f)(void) = NULL;
  Bordered *b = NULL;

  PetscFunctionBeginUser;
  PetscCall(PetscObjectQueryFunction((PetscObject)J, "MatBorderedGetBlocks_C", &f));
  if (is) *is = f ? PETSC_TRUE : PETSC_FALSE;
  if (!f) PetscFunctionReturn(0);
  PetscCall(MatShellGetContext(J, &b));
  if (A) *A = b->A;
  if (nt) *nt = b->nt;
  if (B) *B = b->B;
  if (C) *C = b->C;
  if (D) *D = b->D;
  PetscFunctionReturn(0);
}
