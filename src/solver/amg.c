/* Preconditioner type "amgsys": hypre's BoomerAMG for the displacement unknowns as a system of
   three functions (x, y, z), each unknown told its component (doc/notes/performance-log.md, "One million
   hexahedra").

   Why: BoomerAMG coarsens an elasticity matrix well only when it keeps the three displacement
   components apart (the "unknown" approach: strength of connection and interpolation within one
   component). PETSc's PCHYPRE does that only through the matrix's block size, which is 3 only
   where every node keeps all three unknowns. A constraint that removes one component of a node
   (a symmetry plane: the quarter blanks of the forming cases) removes its row from the section,
   the rows no longer come in threes, the block size is 1, and BoomerAMG mixes the components:
   on the quarter hemisphere blank of 9 600 hexahedra PCHYPRE needs up to 143 Krylov iterations
   per Newton iteration where the whole blank (block size 3) needs 35; with this type, 35 through
   40 mm. Here the component of every row is read from the mesh's sections (the constrained
   components skipped, as the global numbering skips them) and handed to BoomerAMG
   (HYPRE_BoomerAMGSetDofFunc), whatever the constraints. On the whole blank it also needs fewer
   iterations than PCHYPRE as the mesh grows (100 352 hexahedra: 49 against 68): PCHYPRE relaxes
   in CF order by default, this type in hypre's natural order (-pc_amgsys_relax_order; with
   -pc_hypre_boomeramg_no_CF PCHYPRE's iterations on the whole blank are this type's, one for one).

   Options (prefix: the preconditioner's, e.g. none or -ksp's): -pc_amgsys_strong_threshold,
   -pc_amgsys_coarsen_type, -pc_amgsys_interp_type, -pc_amgsys_P_max, -pc_amgsys_agg_nl,
   -pc_amgsys_agg_interp_type, -pc_amgsys_sweeps, -pc_amgsys_relax_type, -pc_amgsys_relax_order;
   defaults those of cases/solver_amg_sheet.opts (PCHYPRE there) but for the relaxation order,
   hypre's natural one here. cases/solver_amgsys_fast.opts takes one sweep of the symmetric
   hybrid Gauss-Seidel (6, a forward and a backward pass in every sweep) instead of three. Type 3
   makes one forward pass per sweep, going down and going up alike (hypre's SetRelaxType sets the
   same type on both legs, and the Krylov counts equal PCHYPRE's with
   -pc_hypre_boomeramg_relax_type_all SOR/Jacobi): a V-cycle that is not symmetric, whose
   iterations grew to 200 per solve at 200 000 hexahedra as the contact spread.
   The Jacobian is used in hypre's format as it is (-assembly_mat_type hypre), any other type is
   converted at each setup; a Jacobian bordered by force-driven tools (src/solver/bordered.c) gives
   its mesh block, in hypre's format, as it is. One V-cycle per application. hypre's nodal
   coarsening (SetNodal) is not offered: it needs every node to have all three unknowns, which is
   what a constrained component breaks.

   -pc_amgsys_sheet_spacing H (> 0; cases/solver_amgsys_sheet.opts) adds after each V-cycle a
   coarse correction by plate-like modes, y <- y + P A_c^-1 P^T (x - A y) (src/solver/
   sheetcoarse.c, whose comment derives it): the V-cycle leaves a thin sheet's bending modes
   almost untouched, and without it the Krylov iterations grow with the mesh. Its work vectors
   are hypre's right-hand side and solution, free between applications.

   The unknowns of force-driven tools (a blank holder under its force: a few rows after the mesh's
   on the last rank, dense in the columns of the nodes the tool touches) are no elasticity for
   BoomerAMG to coarsen: the V-cycle works on the mesh block alone, and the tools' rows are
   eliminated exactly around it through their Schur complement (BorderSetUp below). The mesh block
   is the bordered Jacobian's own (-assembly_mat_type hypre: no copy) or, from an AIJ Jacobian,
   copied into hypre's format at each setup (MeshBlock). */
#define _DEFAULT_SOURCE /* ffs() in hypre's utilities header */
#include <strings.h>

#include <petscdm.h>
#include <petscmathypre.h>
#include <petsc/private/pcimpl.h>
#include <petscsection.h>

#include <HYPRE.h>
#include <HYPRE_IJ_mv.h>
#include <HYPRE_parcsr_ls.h>
#include <_hypre_parcsr_mv.h>

#include <petscblaslapack.h>

#include "bordered.h"
#include "problem.h"
#include "sheetcoarse.h"

typedef struct {
  HYPRE_Solver    amg;
  HYPRE_IJVector  ib, ix;     /* right-hand side and solution in hypre's format */
  HYPRE_ParVector pb, px;
  Mat             hmat;       /* the operator converted to MATHYPRE when it is not one */
  PetscInt        rstart, n;  /* the local rows */
  PetscReal       theta;      /* strength threshold */
  PetscInt        coarsen, interp, pmax, aggnl, sweeps, relax;
  PetscInt        order;      /* relaxation order: 0 natural, 1 C points then F points (CF) */
  PetscInt        agginterp;  /* interpolation on the aggressive levels (hypre's numbering)  */
  PetscReal       sheetH;     /* -pc_amgsys_sheet_spacing: the sheet's coarse space (0: none) */
  PetscReal       sheetN[3];  /* -pc_amgsys_sheet_normal                                      */
  SheetCoarse     sc;
  Vec             wb, wx;     /* PETSc vectors on hypre's b and x arrays: the coarse space's work
                                 (no memory of their own)                                     */
  /* the unknowns of force-driven tools, bordering the mesh block (the Jacobian's last rows) */
  PetscInt        nm;         /* local mesh rows (the first nm of the local rows)             */
  PetscInt        nt;         /* tool unknowns in all (0: none)                               */
  PetscMPIInt     towner;     /* the rank that holds their rows                               */
  HYPRE_IJMatrix  ij;         /* the mesh block A in hypre's format (hmat wraps it)           */
  PetscBool       border;     /* the operator has tool rows: hmat is its mesh block            */
  Vec            *W, *C;      /* M B_k and the rows C_k of the border, on the mesh's rows     */
  Vec             xm, ym, um; /* work on the mesh's rows; um: the iterate's mesh part         */
  PetscScalar    *S;          /* the Schur complement D - C M B, factored (LAPACK getrf)      */
  PetscBool       sbad;       /* it was singular or not finite: every application fails       */
  PetscBLASInt   *piv;
} PC_AMGSys;

static const char *const Coarsen[] = {"CLJP", "Ruge-Stueben", "modifiedRuge-Stueben", "Falgout", "PMIS", "HMIS", NULL};
static const int         CoarsenId[] = {0, 1, 3, 6, 8, 10};
static const char *const Interp[]    = {"classical", "direct", "multipass", "ext+i", "ext", "ext+i-mm", NULL};
static const int         InterpId[]  = {0, 3, 4, 6, 14, 17};
static const char *const AggInterp[] = {"multipass", "2s-ext+i", "2s-std", "2s-ext", "2s-ext-mm", "2s-ext+i-mm", "2s-ext+e-mm", NULL};
static const int         AggInterpId[] = {4, 1, 2, 3, 5, 6, 7};
static const char *const Order[]     = {"natural", "CF", NULL};

/* hypre's error flag: any error but a convergence flag is fatal (one V-cycle "does not converge") */
static PetscErrorCode HypreCheck(MPI_Comm comm, HYPRE_Int ierr, const char *what)
{
  PetscFunctionBeginUser;
  if (ierr && !HYPRE_CheckError(ierr, HYPRE_ERROR_CONV)) SETERRQ(comm, PETSC_ERR_LIB, "-pc_type amgsys: hypre error %d in %s", (int)ierr, what);
  if (ierr) HYPRE_ClearAllErrors();
  PetscFunctionReturn(0);
}

static PetscErrorCode BorderFree(PC_AMGSys *a)
{
  PetscFunctionBeginUser;
  if (a->nt) {
    PetscCall(VecDestroyVecs(a->nt, &a->W));
    PetscCall(VecDestroyVecs(a->nt, &a->C));
  }
  if (a->ij) { /* after hmat, which points to its matrix */
    PetscCall(MatDestroy(&a->hmat));
    HYPRE_IJMatrixDestroy(a->ij);
    a->ij = NULL;
  }
  a->border = PETSC_FALSE;
  PetscCall(VecDestroy(&a->xm));
  PetscCall(VecDestroy(&a->ym));
  PetscCall(VecDestroy(&a->um));
  PetscCall(PetscFree2(a->S, a->piv));
  a->nt = 0;
  PetscFunctionReturn(0);
}

static PetscErrorCode PCReset_AMGSys(PC pc)
{
  PC_AMGSys *a = (PC_AMGSys *)pc->data;

  PetscFunctionBeginUser;
  if (a->amg) HYPRE_BoomerAMGDestroy(a->amg);
  if (a->ib) HYPRE_IJVectorDestroy(a->ib);
  if (a->ix) HYPRE_IJVectorDestroy(a->ix);
  a->amg = NULL;
  a->ib = a->ix = NULL;
  PetscCall(MatDestroy(&a->hmat));
  PetscCall(SheetCoarseDestroy(&a->sc));
  PetscCall(VecDestroy(&a->wb));
  PetscCall(VecDestroy(&a->wx));
  PetscCall(BorderFree(a));
  PetscFunctionReturn(0);
}

static PetscErrorCode PCDestroy_AMGSys(PC pc)
{
  PetscFunctionBeginUser;
  PetscCall(PCReset_AMGSys(pc));
  PetscCall(PetscFree(pc->data));
  PetscFunctionReturn(0);
}

/* the component (0, 1, 2) of each local row, from the mesh's local section (dofs and constrained
   components of each point) and its global section (which points this rank owns, at which offset);
   -1 for a row that is no displacement unknown of the mesh (a force-driven tool's, which the
   problem numbers after the mesh's on the last rank). Allocated with malloc: hypre takes it over
   and frees it. *nmesh: the rows with a component; *tail: they are the first *nmesh local rows */
static PetscErrorCode RowComponents(DM dm, PetscInt rstart, PetscInt n, HYPRE_Int **out, PetscInt *nmesh, PetscBool *tail)
{
  PetscSection s, gs;
  PetscInt     pStart, pEnd, nset = 0;
  HYPRE_Int   *f;

  PetscFunctionBeginUser;
  PetscCall(DMGetLocalSection(dm, &s));
  PetscCall(DMGetGlobalSection(dm, &gs));
  f = (HYPRE_Int *)malloc(sizeof(HYPRE_Int) * (size_t)PetscMax(n, 1));
  PetscCheck(f, PETSC_COMM_SELF, PETSC_ERR_MEM, "-pc_type amgsys: out of memory for %" PetscInt_FMT " rows", n);
  for (PetscInt i = 0; i < n; i++) f[i] = -1;
  PetscCall(PetscSectionGetChart(s, &pStart, &pEnd));
  for (PetscInt p = pStart; p < pEnd; p++) {
    PetscInt        dof, cdof, goff, gdof;
    const PetscInt *cind = NULL;
    PetscCall(PetscSectionGetDof(s, p, &dof));
    if (dof <= 0) continue;
    PetscCall(PetscSectionGetDof(gs, p, &gdof));
    PetscCall(PetscSectionGetOffset(gs, p, &goff));
    if (gdof < 0 || goff < 0) continue; /* a ghost: another rank's rows */
    PetscCall(PetscSectionGetConstraintDof(s, p, &cdof));
    if (cdof) PetscCall(PetscSectionGetConstraintIndices(s, p, &cind));
    for (PetscInt c = 0, k = 0, j = 0; c < dof; c++) {
      if (j < cdof && cind[j] == c) { /* constrained: no row (the indices are sorted) */
        j++;
        continue;
      }
      const PetscInt r = goff - rstart + k++;
      if (r >= 0 && r < n && f[r] < 0) {
        f[r] = (HYPRE_Int)(c % 3);
        nset++;
      }
    }
  }
  *tail = PETSC_TRUE;
  for (PetscInt i = 0; i < nset; i++)
    if (f[i] < 0) *tail = PETSC_FALSE;
  *nmesh = nset;
  *out   = f;
  PetscFunctionReturn(0);
}

/* One application of the preconditioner of the mesh block, M ~ A^-1, on vectors of the mesh's
   rows: a V-cycle, then the sheet's coarse correction where there is one */
static PetscErrorCode MeshApply(PC pc, Vec x, Vec y)
{
  PC_AMGSys          *a = (PC_AMGSys *)pc->data;
  Mat                 A;
  hypre_ParCSRMatrix *pA;
  const PetscScalar  *xa;
  PetscScalar        *ya;
  HYPRE_Complex      *b  = hypre_VectorData(hypre_ParVectorLocalVector((hypre_ParVector *)a->pb));
  HYPRE_Complex      *xs = hypre_VectorData(hypre_ParVectorLocalVector((hypre_ParVector *)a->px));

  PetscFunctionBeginUser;
  if (a->border) A = a->hmat;
  else PetscCall(PCGetOperators(pc, NULL, &A));
  PetscCall(MatHYPREGetParCSR(a->hmat ? a->hmat : A, &pA));
  PetscCall(VecGetArrayRead(x, &xa));
  for (PetscInt i = 0; i < a->n; i++) {
    b[i]  = xa[i];
    xs[i] = 0;
  }
  PetscCall(VecRestoreArrayRead(x, &xa));
  PetscCall(HypreCheck(PetscObjectComm((PetscObject)pc), HYPRE_BoomerAMGSolve(a->amg, (HYPRE_ParCSRMatrix)pA, a->pb, a->px), "HYPRE_BoomerAMGSolve"));
  PetscCall(VecGetArrayWrite(y, &ya));
  for (PetscInt i = 0; i < a->n; i++) ya[i] = xs[i];
  PetscCall(VecRestoreArrayWrite(y, &ya));
  if (a->sc) { /* y += P A_c^-1 P^T (x - A y), the residual in hypre's right-hand side, now free */
    PetscCall(VecPlaceArray(a->wb, (PetscScalar *)b));
    PetscCall(MatMult(A, y, a->wb));
    PetscCall(VecAYPX(a->wb, -1.0, x));
    PetscCall(SheetCoarseApply(a->sc, a->wb, y));
    PetscCall(VecResetArray(a->wb));
  }
  PetscFunctionReturn(0);
}

/* The mesh block of a Jacobian whose last nt global rows and columns are tools' unknowns, in
   hypre's format: the mesh's rows and columns are the first N - nt of the global numbering (the
   tools' come after all of them, on the last rank), so a row keeps its global index and drops the
   tools' columns. Row by row from the assembled matrix (MatGetRow), without an intermediate copy:
   the Jacobian, this block and BoomerAMG's hierarchy are the solver's memory. */
static PetscErrorCode MeshBlock(Mat J, PetscInt rstart, PetscInt nm, PetscInt nt, HYPRE_IJMatrix *ij, Mat *B)
{
  const MPI_Comm     comm = PetscObjectComm((PetscObject)J);
  PetscInt           N, ncols, mx = 0;
  const PetscInt    *cols;
  const PetscScalar *vals;
  HYPRE_Int         *dsz, *osz;
  HYPRE_BigInt      *hc;
  HYPRE_Complex     *hv;
  void              *obj;

  PetscFunctionBeginUser;
  PetscCall(MatGetSize(J, &N, NULL));
  const PetscInt Nm = N - nt;
  PetscCall(PetscMalloc2(nm, &dsz, nm, &osz));
  for (PetscInt i = 0; i < nm; i++) {
    PetscCall(MatGetRow(J, rstart + i, &ncols, &cols, NULL));
    dsz[i] = osz[i] = 0;
    for (PetscInt k = 0; k < ncols; k++) {
      if (cols[k] >= Nm) continue;
      if (cols[k] >= rstart && cols[k] < rstart + nm) dsz[i]++;
      else osz[i]++;
    }
    mx = PetscMax(mx, ncols);
    PetscCall(MatRestoreRow(J, rstart + i, &ncols, &cols, NULL));
  }
  PetscCall(HypreCheck(comm, HYPRE_IJMatrixCreate(comm, (HYPRE_BigInt)rstart, (HYPRE_BigInt)(rstart + nm - 1), (HYPRE_BigInt)rstart, (HYPRE_BigInt)(rstart + nm - 1), ij), "HYPRE_IJMatrixCreate"));
  PetscCall(HypreCheck(comm, HYPRE_IJMatrixSetObjectType(*ij, HYPRE_PARCSR), "HYPRE_IJMatrixSetObjectType"));
  PetscCall(HypreCheck(comm, HYPRE_IJMatrixSetDiagOffdSizes(*ij, dsz, osz), "HYPRE_IJMatrixSetDiagOffdSizes"));
  PetscCall(HypreCheck(comm, HYPRE_IJMatrixInitialize(*ij), "HYPRE_IJMatrixInitialize"));
  PetscCall(PetscFree2(dsz, osz));
  PetscCall(PetscMalloc2(PetscMax(mx, 1), &hc, PetscMax(mx, 1), &hv));
  for (PetscInt i = 0; i < nm; i++) {
    HYPRE_Int    n = 0;
    HYPRE_BigInt row = (HYPRE_BigInt)(rstart + i);
    PetscCall(MatGetRow(J, rstart + i, &ncols, &cols, &vals));
    for (PetscInt k = 0; k < ncols; k++)
      if (cols[k] < Nm) {
        hc[n]   = (HYPRE_BigInt)cols[k];
        hv[n++] = (HYPRE_Complex)vals[k];
      }
    PetscCall(MatRestoreRow(J, rstart + i, &ncols, &cols, &vals));
    PetscCall(HypreCheck(comm, HYPRE_IJMatrixSetValues(*ij, 1, &n, &row, hc, hv), "HYPRE_IJMatrixSetValues"));
  }
  PetscCall(PetscFree2(hc, hv));
  PetscCall(HypreCheck(comm, HYPRE_IJMatrixAssemble(*ij), "HYPRE_IJMatrixAssemble"));
  PetscCall(HypreCheck(comm, HYPRE_IJMatrixGetObject(*ij, &obj), "HYPRE_IJMatrixGetObject"));
  PetscCall(MatCreateFromParCSR((hypre_ParCSRMatrix *)obj, MATHYPRE, PETSC_USE_POINTER, B));
  PetscFunctionReturn(0);
}

/* The border of force-driven tools' unknowns. The Jacobian, its mesh rows first and the nt tool
   rows last,

     J = [A  B]      B: how the tools' positions move the nodes' contact forces (columns),
         [C  D]      C: how the nodes move the tools' force balance (rows), D: nt x nt,

   is preconditioned by its block factorisation with M ~ A^-1 (the V-cycle, and the sheet's coarse
   space) in place of A^-1:

     P^-1 = [I  -M B] [M  0   ] [ I    0]        S = D - C M B  (nt x nt, dense),
            [0   I  ] [0  S^-1] [-C M  I]

   applied as z = M x_A;  y_T = S^-1 (x_T - C z);  y_A = z - (M B) y_T. With M = A^-1 it is J^-1;
   with the V-cycle, P^-1 J - I = [M A - I, 0; 0, 0] + a term of rank nt, so a Krylov method
   takes at most nt iterations more than on the mesh block alone, instead of the tool rows, dense
   and not an elasticity, entering BoomerAMG's coarsening. The setup applies M to the nt columns
   of B (W = M B, kept) and factors S: nt + 1 V-cycles per Jacobian; each application one V-cycle,
   nt dot products and nt vector updates. B, C and D come from products of J with unit vectors of
   the tool rows (one MatMult and one MatMultTranspose each), so any assembled format serves. */
static PetscErrorCode BorderSetUp(PC pc, Mat J, PetscInt nt, PetscMPIInt owner)
{
  PC_AMGSys   *a    = (PC_AMGSys *)pc->data;
  const MPI_Comm comm = PetscObjectComm((PetscObject)pc);
  Vec          e, col;
  PetscInt     N;
  PetscMPIInt  rank;
  PetscScalar *dots;
  PetscBLASInt bn, info = 0;

  PetscFunctionBeginUser;
  PetscCallMPI(MPI_Comm_rank(comm, &rank));
  PetscCall(MatGetSize(J, &N, NULL));
  PetscCall(MatCreateVecs(J, &e, &col));
  PetscCall(VecCreateMPI(comm, a->n, PETSC_DETERMINE, &a->xm));
  PetscCall(VecDuplicate(a->xm, &a->ym));
  PetscCall(VecDuplicateVecs(a->xm, nt, &a->W));
  PetscCall(VecDuplicateVecs(a->xm, nt, &a->C));
  PetscCall(PetscMalloc2(nt * nt, &a->S, nt, &a->piv));
  PetscCall(PetscMalloc1(nt, &dots));
  a->nt     = nt;
  a->towner = owner;
  for (PetscInt k = 0; k < nt; k++) {
    const PetscScalar *c;
    PetscScalar       *m;
    PetscCall(VecZeroEntries(e));
    if (rank == owner) PetscCall(VecSetValue(e, N - nt + k, 1.0, INSERT_VALUES));
    PetscCall(VecAssemblyBegin(e));
    PetscCall(VecAssemblyEnd(e));
    /* column k: B_k on the mesh's rows, D(:, k) on the tools' */
    PetscCall(MatMult(J, e, col));
    PetscCall(VecGetArrayRead(col, &c));
    PetscCall(VecGetArrayWrite(a->xm, &m));
    for (PetscInt i = 0; i < a->n; i++) m[i] = c[i];
    PetscCall(VecRestoreArrayWrite(a->xm, &m));
    if (rank == owner)
      for (PetscInt i = 0; i < nt; i++) a->S[i + nt * k] = c[a->n + i];
    PetscCall(VecRestoreArrayRead(col, &c));
    PetscCall(MeshApply(pc, a->xm, a->W[k]));
    /* row k: C_k */
    PetscCall(MatMultTranspose(J, e, col));
    PetscCall(VecGetArrayRead(col, &c));
    PetscCall(VecGetArrayWrite(a->C[k], &m));
    for (PetscInt i = 0; i < a->n; i++) m[i] = c[i];
    PetscCall(VecRestoreArrayWrite(a->C[k], &m));
    PetscCall(VecRestoreArrayRead(col, &c));
  }
  PetscCallMPI(MPI_Bcast(a->S, (PetscMPIInt)(nt * nt), MPIU_SCALAR, owner, comm));
  for (PetscInt k = 0; k < nt; k++) {
    PetscCall(VecMDot(a->W[k], nt, a->C, dots));
    for (PetscInt i = 0; i < nt; i++) a->S[i + nt * k] -= dots[i];
  }
  { /* a pivot below 1e-12 of the largest entry, or an entry that is not finite: the V-cycle's
       approximation of A^-1 B (one V-cycle per column) did not hold at this Jacobian (it diverges
       on a mesh block it cannot smooth), or a tool unknown has no stiffness. Not an error of the
       run: every application of the preconditioner then gives a vector that is not finite, the
       Krylov method stops on it (KSP_DIVERGED_NANORINF) and the step is retried smaller, as for
       any failed linear solve */
    PetscReal smax = 0, pmin = PETSC_MAX_REAL;
    PetscBool finite = PETSC_TRUE;
    for (PetscInt i = 0; i < nt * nt; i++) {
      if (PetscIsInfOrNanScalar(a->S[i])) finite = PETSC_FALSE;
      smax = PetscMax(smax, PetscAbsScalar(a->S[i]));
    }
    PetscCall(PetscBLASIntCast(nt, &bn));
    if (finite) PetscCallBLAS("LAPACKgetrf", LAPACKgetrf_(&bn, &bn, a->S, &bn, a->piv, &info));
    for (PetscInt i = 0; i < nt; i++) pmin = PetscMin(pmin, PetscAbsScalar(a->S[i + nt * i]));
    a->sbad = (PetscBool)(!finite || info != 0 || !(pmin > 1e-12 * smax));
    if (a->sbad) PetscCall(PetscPrintf(comm, "amgsys: the Schur complement of the %" PetscInt_FMT " force-driven tool unknowns is singular or not finite (smallest pivot %g of %g): this linear solve fails\n", nt, (double)pmin, (double)smax));
  }
  PetscCall(PetscFree(dots));
  PetscCall(VecDestroy(&e));
  PetscCall(VecDestroy(&col));
  PetscFunctionReturn(0);
}

static PetscErrorCode PCSetUp_AMGSys(PC pc)
{
  PC_AMGSys          *a = (PC_AMGSys *)pc->data;
  const MPI_Comm      comm = PetscObjectComm((PetscObject)pc);
  Mat                 A, Aop, Ab = NULL;
  PetscBool           ishypre, isbord;
  hypre_ParCSRMatrix *pA;
  HYPRE_Int          *dof = NULL;
  PetscInt            rstart, rend, nm = 0, nt = 0;
  PetscMPIInt         rank, owner = -1;
  DM                  dm;

  PetscFunctionBeginUser;
  PetscCallMPI(MPI_Comm_rank(comm, &rank));
  PetscCall(PCGetOperators(pc, NULL, &Aop));
  PetscCall(PCGetDM(pc, &dm));
  PetscCheck(dm, comm, PETSC_ERR_ARG_WRONGSTATE, "-pc_type amgsys: the preconditioner has no mesh to read the unknowns' components from");
  PetscCall(MatGetOwnershipRange(Aop, &rstart, &rend));
  { /* the mesh's rows first on every rank; the tools' rows after them, on one rank (a mismatch on
       one rank is raised on all: the setup below is collective) */
    PetscBool   tail = PETSC_FALSE;
    PetscInt    l[2], g[2];
    PetscMPIInt lo, go;
    PetscCall(RowComponents(dm, rstart, rend - rstart, &dof, &nm, &tail));
    l[0] = !tail;
    l[1] = rend - rstart - nm;
    PetscCall(MPIU_Allreduce(l, g, 2, MPIU_INT, MPI_SUM, comm));
    lo = l[1] > 0 ? rank : -1;
    PetscCallMPI(MPI_Allreduce(&lo, &go, 1, MPI_INT, MPI_MAX, comm));
    nt    = g[1];
    owner = go;
    PetscMPIInt size;
    PetscCallMPI(MPI_Comm_size(comm, &size));
    if (g[0] || (l[1] > 0 && l[1] != nt) || (nt > 0 && go != size - 1)) l[0] = 1; /* the tools' rows: the global tail */
    PetscCall(MPIU_Allreduce(MPI_IN_PLACE, l, 1, MPIU_INT, MPI_MAX, comm));
    if (l[0] || nt > 3 * 64) free(dof);
    PetscCheck(!l[0], comm, PETSC_ERR_SUP, "-pc_type amgsys: the Jacobian has rows that are neither the mesh's displacement unknowns nor, after them on the last rank, force-driven tools' unknowns");
    PetscCheck(nt <= 3 * 64, comm, PETSC_ERR_SUP, "-pc_type amgsys: %" PetscInt_FMT " force-driven tool unknowns, at most 192", nt);
  }
  PetscCall(BorderFree(a));
  PetscCall(MatDestroy(&a->hmat));
  A = Aop;
  PetscCall(MatBorderedGetBlocks(Aop, &isbord, &Ab, NULL, NULL, NULL, NULL));
  if (nt && isbord) { /* the Jacobian keeps its mesh block apart (bordered.h): taken as it is */
    PetscCall(PetscObjectTypeCompare((PetscObject)Ab, MATHYPRE, &ishypre));
    PetscCheck(ishypre, comm, PETSC_ERR_SUP, "-pc_type amgsys: a bordered Jacobian's mesh block must be in hypre's format (-assembly_mat_type hypre)");
    PetscCall(PetscObjectReference((PetscObject)Ab));
    a->hmat   = Ab;
    a->border = PETSC_TRUE;
    A         = a->hmat;
  } else if (nt) { /* the mesh block, copied straight into hypre's format */
    PetscCall(MeshBlock(Aop, rstart, nm, nt, &a->ij, &a->hmat));
    a->border = PETSC_TRUE;
    A         = a->hmat;
  } else {
    PetscCall(PetscObjectTypeCompare((PetscObject)A, MATHYPRE, &ishypre));
    if (!ishypre) {
      PetscCall(MatConvert(A, MATHYPRE, MAT_INITIAL_MATRIX, &a->hmat));
      A = a->hmat;
    }
  }
  PetscCall(MatHYPREGetParCSR(A, &pA));
  PetscCall(MatGetOwnershipRange(A, &rstart, &rend));
  if (a->amg) HYPRE_BoomerAMGDestroy(a->amg);
  a->amg = NULL;
  if (!a->ib || a->rstart != rstart || a->n != rend - rstart) { /* hypre's vectors of this row range */
    if (a->ib) HYPRE_IJVectorDestroy(a->ib);
    if (a->ix) HYPRE_IJVectorDestroy(a->ix);
    a->rstart = rstart;
    a->n      = rend - rstart;
    HYPRE_IJVector *v[2] = {&a->ib, &a->ix};
    HYPRE_ParVector *pv[2] = {&a->pb, &a->px};
    for (int k = 0; k < 2; k++) {
      void *obj;
      PetscCall(HypreCheck(comm, HYPRE_IJVectorCreate(comm, (HYPRE_BigInt)a->rstart, (HYPRE_BigInt)rend - 1, v[k]), "HYPRE_IJVectorCreate"));
      PetscCall(HypreCheck(comm, HYPRE_IJVectorSetObjectType(*v[k], HYPRE_PARCSR), "HYPRE_IJVectorSetObjectType"));
      PetscCall(HypreCheck(comm, HYPRE_IJVectorInitialize(*v[k]), "HYPRE_IJVectorInitialize"));
      PetscCall(HypreCheck(comm, HYPRE_IJVectorAssemble(*v[k]), "HYPRE_IJVectorAssemble"));
      PetscCall(HypreCheck(comm, HYPRE_IJVectorGetObject(*v[k], &obj), "HYPRE_IJVectorGetObject"));
      *pv[k] = (HYPRE_ParVector)obj;
    }
  }
  PetscCall(HypreCheck(comm, HYPRE_BoomerAMGCreate(&a->amg), "HYPRE_BoomerAMGCreate"));
  HYPRE_BoomerAMGSetPrintLevel(a->amg, 0);
  HYPRE_BoomerAMGSetMaxIter(a->amg, 1);
  HYPRE_BoomerAMGSetTol(a->amg, 0.0);
  HYPRE_BoomerAMGSetStrongThreshold(a->amg, a->theta);
  HYPRE_BoomerAMGSetCoarsenType(a->amg, (HYPRE_Int)a->coarsen);
  HYPRE_BoomerAMGSetInterpType(a->amg, (HYPRE_Int)a->interp);
  HYPRE_BoomerAMGSetPMaxElmts(a->amg, (HYPRE_Int)a->pmax);
  HYPRE_BoomerAMGSetAggNumLevels(a->amg, (HYPRE_Int)a->aggnl);
  HYPRE_BoomerAMGSetAggInterpType(a->amg, (HYPRE_Int)a->agginterp);
  HYPRE_BoomerAMGSetRelaxOrder(a->amg, (HYPRE_Int)a->order);
  HYPRE_BoomerAMGSetNumSweeps(a->amg, (HYPRE_Int)a->sweeps);
  HYPRE_BoomerAMGSetCycleNumSweeps(a->amg, 1, 3); /* the coarsest level: one direct solve */
  HYPRE_BoomerAMGSetRelaxType(a->amg, (HYPRE_Int)a->relax);
  HYPRE_BoomerAMGSetCycleRelaxType(a->amg, 9, 3);
  HYPRE_BoomerAMGSetNumFunctions(a->amg, 3);
  HYPRE_BoomerAMGSetDofFunc(a->amg, dof); /* taken over by hypre (its first a->n entries read) */
  PetscCall(HypreCheck(comm, HYPRE_BoomerAMGSetup(a->amg, (HYPRE_ParCSRMatrix)pA, a->pb, a->px), "HYPRE_BoomerAMGSetup"));
  if (a->sheetH > 0) { /* the sheet's coarse space at the positions of the Jacobian's iterate */
    Mat         Ablk = a->border ? a->hmat : Aop;
    PetscObject U;
    Vec         Um = NULL;
    PetscCall(PetscObjectQuery((PetscObject)Aop, "atrito_iterate", &U));
    if (U && a->border) { /* its mesh part */
      const PetscScalar *ua;
      PetscScalar       *ma;
      PetscCall(VecCreateMPI(comm, a->n, PETSC_DETERMINE, &a->um));
      PetscCall(VecGetArrayRead((Vec)U, &ua));
      PetscCall(VecGetArrayWrite(a->um, &ma));
      for (PetscInt i = 0; i < a->n; i++) ma[i] = ua[i];
      PetscCall(VecRestoreArrayWrite(a->um, &ma));
      PetscCall(VecRestoreArrayRead((Vec)U, &ua));
      Um = a->um;
    } else Um = (Vec)U;
    HYPRE_Complex *b  = hypre_VectorData(hypre_ParVectorLocalVector((hypre_ParVector *)a->pb));
    HYPRE_Complex *xs = hypre_VectorData(hypre_ParVectorLocalVector((hypre_ParVector *)a->px));
    if (!a->sc) PetscCall(SheetCoarseCreate(comm, a->sheetH, a->sheetN, &a->sc));
    if (a->wb) { /* hypre's vectors may have been made anew (the row range) */
      PetscInt n;
      PetscCall(VecGetLocalSize(a->wb, &n));
      if (n != a->n) {
        PetscCall(VecDestroy(&a->wb));
        PetscCall(VecDestroy(&a->wx));
      }
    }
    if (!a->wb) {
      PetscCall(VecCreateMPIWithArray(comm, 1, a->n, PETSC_DECIDE, NULL, &a->wb));
      PetscCall(VecCreateMPIWithArray(comm, 1, a->n, PETSC_DECIDE, NULL, &a->wx));
    }
    PetscCall(VecPlaceArray(a->wb, (PetscScalar *)b));
    PetscCall(VecPlaceArray(a->wx, (PetscScalar *)xs));
    PetscCall(SheetCoarseSetUp(a->sc, dm, Ablk, Um, a->wb, a->wx));
    PetscCall(VecResetArray(a->wb));
    PetscCall(VecResetArray(a->wx));
  }
  if (nt) PetscCall(BorderSetUp(pc, Aop, nt, owner));
  PetscFunctionReturn(0);
}

static PetscErrorCode PCApply_AMGSys(PC pc, Vec x, Vec y)
{
  PC_AMGSys         *a = (PC_AMGSys *)pc->data;
  const MPI_Comm     comm = PetscObjectComm((PetscObject)pc);
  const PetscInt     nt = a->nt;
  const PetscScalar *xa;
  PetscScalar       *ma, *ya, t[3 * 64], mt[3 * 64];
  PetscMPIInt        rank;
  PetscBLASInt       bn, one = 1, info = 0;

  PetscFunctionBeginUser;
  if (!nt) {
    PetscCall(MeshApply(pc, x, y));
    PetscFunctionReturn(0);
  }
  if (a->sbad) { /* BorderSetUp: the Schur complement was singular; the solve fails and is retried */
    PetscCall(VecSet(y, NAN));
    PetscFunctionReturn(0);
  }
  PetscCallMPI(MPI_Comm_rank(comm, &rank));
  PetscCall(VecGetArrayRead(x, &xa));
  PetscCall(VecGetArrayWrite(a->xm, &ma));
  for (PetscInt i = 0; i < a->n; i++) ma[i] = xa[i];
  if (rank == a->towner)
    for (PetscInt k = 0; k < nt; k++) t[k] = xa[a->n + k];
  PetscCall(VecRestoreArrayWrite(a->xm, &ma));
  PetscCall(VecRestoreArrayRead(x, &xa));
  PetscCallMPI(MPI_Bcast(t, (PetscMPIInt)nt, MPIU_SCALAR, a->towner, comm));
  PetscCall(MeshApply(pc, a->xm, a->ym)); /* z = M x_A */
  PetscCall(VecMDot(a->ym, nt, a->C, mt));
  for (PetscInt k = 0; k < nt; k++) t[k] -= mt[k]; /* x_T - C z */
  PetscCall(PetscBLASIntCast(nt, &bn));
  PetscCallBLAS("LAPACKgetrs", LAPACKgetrs_("N", &bn, &one, a->S, &bn, a->piv, t, &bn, &info));
  PetscCheck(info == 0, comm, PETSC_ERR_LIB, "-pc_type amgsys: LAPACK getrs failed (%d) on the tools' Schur complement", (int)info);
  for (PetscInt k = 0; k < nt; k++) mt[k] = -t[k];
  PetscCall(VecMAXPY(a->ym, nt, mt, a->W)); /* y_A = z - M B y_T */
  PetscCall(VecGetArrayRead(a->ym, &xa));
  PetscCall(VecGetArrayWrite(y, &ya));
  for (PetscInt i = 0; i < a->n; i++) ya[i] = xa[i];
  if (rank == a->towner)
    for (PetscInt k = 0; k < nt; k++) ya[a->n + k] = t[k];
  PetscCall(VecRestoreArrayWrite(y, &ya));
  PetscCall(VecRestoreArrayRead(a->ym, &xa));
  PetscFunctionReturn(0);
}

static PetscErrorCode PCSetFromOptions_AMGSys(PC pc, PetscOptionItems *PetscOptionsObject)
{
  PC_AMGSys *a = (PC_AMGSys *)pc->data;
  PetscInt   ci = 5, ii = 3, ai = 0, oi = a->order;

  PetscFunctionBeginUser;
  for (int k = 0; Coarsen[k]; k++)
    if (CoarsenId[k] == a->coarsen) ci = k;
  for (int k = 0; Interp[k]; k++)
    if (InterpId[k] == a->interp) ii = k;
  for (int k = 0; AggInterp[k]; k++)
    if (AggInterpId[k] == a->agginterp) ai = k;
  PetscOptionsHeadBegin(PetscOptionsObject, "BoomerAMG for the displacements as a system of 3 functions (-pc_type amgsys)");
  PetscCall(PetscOptionsReal("-pc_amgsys_strong_threshold", "Strength threshold (3D elasticity: 0.5 to 0.9)", NULL, a->theta, &a->theta, NULL));
  PetscCall(PetscOptionsEList("-pc_amgsys_coarsen_type", "Coarsening", NULL, Coarsen, 6, Coarsen[ci], &ci, NULL));
  PetscCall(PetscOptionsEList("-pc_amgsys_interp_type", "Interpolation", NULL, Interp, 6, Interp[ii], &ii, NULL));
  PetscCall(PetscOptionsInt("-pc_amgsys_P_max", "Largest number of entries per row of the interpolation (0: no limit)", NULL, a->pmax, &a->pmax, NULL));
  PetscCall(PetscOptionsInt("-pc_amgsys_agg_nl", "Levels of aggressive coarsening", NULL, a->aggnl, &a->aggnl, NULL));
  PetscCall(PetscOptionsEList("-pc_amgsys_agg_interp_type", "Interpolation on the levels of aggressive coarsening (multipass, or hypre's two-stage ones)", NULL, AggInterp, 7, AggInterp[ai], &ai, NULL));
  PetscCall(PetscOptionsEList("-pc_amgsys_relax_order", "Order of the smoothing: natural (hypre's default), or CF (coarse points first going down, fine first going up: PCHYPRE's default)", NULL, Order, 2, Order[oi], &oi, NULL));
  PetscCall(PetscOptionsInt("-pc_amgsys_sweeps", "Smoothing sweeps down and up", NULL, a->sweeps, &a->sweeps, NULL));
  PetscCall(PetscOptionsReal("-pc_amgsys_sheet_spacing", "Spacing of the grid of the sheet's coarse space (plate-like modes) applied after each V-cycle, in model length units; 0: none", NULL, a->sheetH, &a->sheetH, NULL));
  {
    PetscInt  nn = 3;
    PetscBool set;
    PetscCall(PetscOptionsRealArray("-pc_amgsys_sheet_normal", "The sheet's normal in its reference configuration (the grid lies in the plane normal to it)", NULL, a->sheetN, &nn, &set));
    PetscCheck(!set || nn == 3, PetscObjectComm((PetscObject)pc), PETSC_ERR_USER_INPUT, "-pc_amgsys_sheet_normal: give three components (%" PetscInt_FMT " given)", nn);
  }
  PetscCall(PetscOptionsInt("-pc_amgsys_relax_type", "hypre's relaxation type (6: symmetric Gauss-Seidel/Jacobi hybrid; 3: Gauss-Seidel/Jacobi hybrid, forward passes down and up, half of 6's cost per sweep, not symmetric; 8: l1 symmetric Gauss-Seidel; 18: l1 Jacobi)", NULL, a->relax, &a->relax, NULL));
  PetscOptionsHeadEnd();
  PetscCheck(a->theta > 0 && a->theta < 1, PetscObjectComm((PetscObject)pc), PETSC_ERR_USER_INPUT, "-pc_amgsys_strong_threshold %g: between 0 and 1", (double)a->theta);
  PetscCheck(a->sheetH >= 0, PetscObjectComm((PetscObject)pc), PETSC_ERR_USER_INPUT, "-pc_amgsys_sheet_spacing %g: at least 0 (0: no coarse space)", (double)a->sheetH);
  PetscCheck(a->sheetN[0] != 0 || a->sheetN[1] != 0 || a->sheetN[2] != 0, PetscObjectComm((PetscObject)pc), PETSC_ERR_USER_INPUT, "-pc_amgsys_sheet_normal: the sheet's normal must not be zero");
  PetscCheck(a->sweeps >= 1 && a->pmax >= 0 && a->aggnl >= 0, PetscObjectComm((PetscObject)pc), PETSC_ERR_USER_INPUT, "-pc_amgsys_sweeps at least 1, -pc_amgsys_P_max and -pc_amgsys_agg_nl at least 0");
  a->coarsen = CoarsenId[ci];
  a->interp  = InterpId[ii];
  a->agginterp = AggInterpId[ai];
  a->order     = oi;
  PetscFunctionReturn(0);
}

static PetscErrorCode PCView_AMGSys(PC pc, PetscViewer v)
{
  PC_AMGSys *a = (PC_AMGSys *)pc->data;
  PetscBool  ascii;

  PetscFunctionBeginUser;
  PetscCall(PetscObjectTypeCompare((PetscObject)v, PETSCVIEWERASCII, &ascii));
  if (ascii) PetscCall(PetscViewerASCIIPrintf(v, "  BoomerAMG, 3 functions from the mesh's sections: strength %g, coarsening %d, interpolation %d, P_max %d, aggressive levels %d (interpolation %d), sweeps %d, relaxation %d (%s order)\n", (double)a->theta, (int)a->coarsen, (int)a->interp, (int)a->pmax, (int)a->aggnl, (int)a->agginterp, (int)a->sweeps, (int)a->relax, Order[a->order]));
  if (ascii && a->sc) {
    PetscInt nodes, colours;
    PetscCall(SheetCoarseGetSize(a->sc, &nodes, &colours));
    PetscCall(PetscViewerASCIIPrintf(v, "  sheet coarse space: spacing %g, normal (%g, %g, %g), %" PetscInt_FMT " grid nodes (%" PetscInt_FMT " unknowns), %" PetscInt_FMT " colours\n", (double)a->sheetH, (double)a->sheetN[0], (double)a->sheetN[1], (double)a->sheetN[2], nodes, 6 * nodes, colours));
  }
  if (ascii && a->nt) PetscCall(PetscViewerASCIIPrintf(v, "  bordered by %" PetscInt_FMT " force-driven tool unknowns: block factorisation with their Schur complement (dense, %" PetscInt_FMT " x %" PetscInt_FMT ")\n", a->nt, a->nt, a->nt));
  PetscFunctionReturn(0);
}

static PetscErrorCode PCCreate_AMGSys(PC pc)
{
  PC_AMGSys *a;

  PetscFunctionBeginUser;
  PetscCall(PetscNew(&a));
  a->theta   = 0.7;
  a->coarsen = 10; /* HMIS */
  a->interp  = 6;  /* ext+i */
  a->pmax    = 4;
  a->aggnl   = 1;
  a->sweeps  = 2;
  a->relax   = 6;
  a->order     = 0;
  a->agginterp = 4; /* multipass */
  a->sheetN[2]  = 1;
  pc->data                = a;
  pc->ops->setup          = PCSetUp_AMGSys;
  pc->ops->apply          = PCApply_AMGSys;
  pc->ops->reset          = PCReset_AMGSys;
  pc->ops->destroy        = PCDestroy_AMGSys;
  pc->ops->setfromoptions = PCSetFromOptions_AMGSys;
  pc->ops->view           = PCView_AMGSys;
  PetscFunctionReturn(0);
}

PetscErrorCode AMGSysRegister(void)
{
  static PetscBool done = PETSC_FALSE;

  PetscFunctionBeginUser;
  if (done) PetscFunctionReturn(0);
  done = PETSC_TRUE;
  PetscCall(PCRegister("amgsys", PCCreate_AMGSys));
  PetscFunctionReturn(0);
}
