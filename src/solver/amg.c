/* Preconditioner type "amgsys": hypre's BoomerAMG for the displacement unknowns as a system of
   three functions (x, y, z), each unknown told its component (doc/performance.md, "One million
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
   converted at each setup. One V-cycle per application. hypre's nodal coarsening (SetNodal) is
   not offered: it needs every node to have all three unknowns, which is what a constrained
   component breaks.

   -pc_amgsys_sheet_spacing H (> 0; cases/solver_amgsys_sheet.opts) adds after each V-cycle a
   coarse correction by plate-like modes, y <- y + P A_c^-1 P^T (x - A y) (src/solver/
   sheetcoarse.c, whose comment derives it): the V-cycle leaves a thin sheet's bending modes
   almost untouched, and without it the Krylov iterations grow with the mesh. Its work vectors
   are hypre's right-hand side and solution, free between applications. */
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
   allocated with malloc: hypre takes it over and frees it. *ok: every local row is a displacement
   unknown of the mesh (not so with the unknowns of force-driven tools) */
static PetscErrorCode RowComponents(DM dm, PetscInt rstart, PetscInt n, HYPRE_Int **out, PetscBool *ok)
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
  *ok  = nset == n ? PETSC_TRUE : PETSC_FALSE;
  *out = f;
  PetscFunctionReturn(0);
}

static PetscErrorCode PCSetUp_AMGSys(PC pc)
{
  PC_AMGSys          *a = (PC_AMGSys *)pc->data;
  const MPI_Comm      comm = PetscObjectComm((PetscObject)pc);
  Mat                 A;
  PetscBool           ishypre;
  hypre_ParCSRMatrix *pA;
  HYPRE_Int          *dof = NULL;
  PetscInt            rstart, rend, lerr = 0, gerr;

  PetscFunctionBeginUser;
  PetscCall(PCGetOperators(pc, NULL, &A));
  PetscCall(PetscObjectTypeCompare((PetscObject)A, MATHYPRE, &ishypre));
  if (!ishypre) {
    PetscCall(MatDestroy(&a->hmat));
    PetscCall(MatConvert(A, MATHYPRE, MAT_INITIAL_MATRIX, &a->hmat));
    A = a->hmat;
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
  { /* a mismatch on one rank is raised on all (the setup below is collective) */
    DM        dm;
    PetscBool ok = PETSC_FALSE;
    PetscCall(PCGetDM(pc, &dm));
    PetscCheck(dm, comm, PETSC_ERR_ARG_WRONGSTATE, "-pc_type amgsys: the preconditioner has no mesh to read the unknowns' components from");
    PetscCall(RowComponents(dm, a->rstart, a->n, &dof, &ok));
    lerr = !ok;
    PetscCall(MPIU_Allreduce(&lerr, &gerr, 1, MPIU_INT, MPI_MAX, comm));
    if (gerr) free(dof);
    PetscCheck(!gerr, comm, PETSC_ERR_SUP, "-pc_type amgsys: the Jacobian has rows that are not the mesh's displacement unknowns (force-driven tools add unknowns of their own: use -pc_type hypre there)");
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
  HYPRE_BoomerAMGSetDofFunc(a->amg, dof); /* taken over by hypre */
  PetscCall(HypreCheck(comm, HYPRE_BoomerAMGSetup(a->amg, (HYPRE_ParCSRMatrix)pA, a->pb, a->px), "HYPRE_BoomerAMGSetup"));
  if (a->sheetH > 0) { /* the sheet's coarse space at the positions of the Jacobian's iterate */
    DM        dm;
    Mat       Aop;
    PetscObject U;
    PetscCall(PCGetDM(pc, &dm));
    PetscCall(PCGetOperators(pc, NULL, &Aop));
    PetscCall(PetscObjectQuery((PetscObject)Aop, "atrito_iterate", &U));
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
    PetscCall(SheetCoarseSetUp(a->sc, dm, Aop, (Vec)U, a->wb, a->wx));
    PetscCall(VecResetArray(a->wb));
    PetscCall(VecResetArray(a->wx));
  }
  PetscFunctionReturn(0);
}

static PetscErrorCode PCApply_AMGSys(PC pc, Vec x, Vec y)
{
  PC_AMGSys          *a = (PC_AMGSys *)pc->data;
  Mat                 A;
  hypre_ParCSRMatrix *pA;
  const PetscScalar  *xa;
  PetscScalar        *ya;
  HYPRE_Complex      *b  = hypre_VectorData(hypre_ParVectorLocalVector((hypre_ParVector *)a->pb));
  HYPRE_Complex      *xs = hypre_VectorData(hypre_ParVectorLocalVector((hypre_ParVector *)a->px));

  PetscFunctionBeginUser;
  PetscCall(PCGetOperators(pc, NULL, &A));
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
