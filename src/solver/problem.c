/* The discrete problem (problem.h): assembly of the residual and the exact Jacobian over the
   local cells (through the element and material kernels) and the slave nodes (through the
   contact object), the SNES with its solver options, commit of the plastic history.

   State lifecycle: hist_c (committed) changes only in ProblemCommit; every residual or Jacobian
   evaluation recomputes hist_t (trial) from hist_c and the current iterate. */
#include <math.h>
#include <string.h>
#include "problem.h"
#include "bordered.h"
#include "lu.h"
#include "options.h"

#define MAX_EDOF 81 /* element dofs: up to 27 nodes */

PetscErrorCode ProblemGetToolValues(Problem *pb, Vec X, PetscReal *d)
{
  PetscFunctionBeginUser;
  if (!pb->ntu) PetscFunctionReturn(0);
  if (pb->rank == pb->size - 1) {
    const PetscScalar *a;
    PetscInt           n;
    PetscCall(VecGetLocalSize(X, &n));
    PetscCall(VecGetArrayRead(X, &a));
    for (PetscInt k = 0; k < pb->ntu; k++) d[k] = PetscRealPart(a[n - pb->ntu + k]);
    PetscCall(VecRestoreArrayRead(X, &a));
  }
  PetscCallMPI(MPI_Bcast(d, (PetscMPIInt)pb->ntu, MPIU_REAL, pb->size - 1, pb->comm));
  PetscFunctionReturn(0);
}

PetscErrorCode ProblemSetToolValues(Problem *pb, Vec X, const PetscReal *d)
{
  PetscFunctionBeginUser;
  if (!pb->ntu) PetscFunctionReturn(0);
  if (pb->rank == pb->size - 1) {
    PetscScalar *a;
    PetscInt     n;
    PetscCall(VecGetLocalSize(X, &n));
    PetscCall(VecGetArray(X, &a));
    for (PetscInt k = 0; k < pb->ntu; k++) a[n - pb->ntu + k] = d[k];
    PetscCall(VecRestoreArray(X, &a));
  }
  PetscFunctionReturn(0);
}

/* The body part of a global vector X as a DM global vector: X itself without tool unknowns, else
   the view V (its array placed on X's); with the tool values handed to the contact object (read) */
static PetscErrorCode BodyGet(Problem *pb, Vec X, Vec V, PetscBool read, Vec *B)
{
  PetscScalar *a;

  PetscFunctionBeginUser;
  if (!pb->ntu) {
    *B = X;
    PetscFunctionReturn(0);
  }
  if (read) {
    PetscReal d[3 * 64];
    PetscCheck(pb->ntu <= 3 * 64, pb->comm, PETSC_ERR_SUP, "at most 64 force-driven tools");
    PetscCall(ProblemGetToolValues(pb, X, d));
    PetscCall(ContactSetToolUnknowns(pb->contact, d));
    PetscCall(VecGetArrayRead(X, (const PetscScalar **)&a));
  } else PetscCall(VecGetArray(X, &a));
  PetscCall(VecPlaceArray(V, a));
  *B = V;
  PetscFunctionReturn(0);
}

static PetscErrorCode BodyRestore(Problem *pb, Vec X, Vec V, PetscBool read)
{
  PetscFunctionBeginUser;
  if (!pb->ntu) PetscFunctionReturn(0);
  PetscCall(VecResetArray(V));
  if (read) PetscCall(VecRestoreArrayRead(X, NULL));
  else PetscCall(VecRestoreArray(X, NULL));
  PetscFunctionReturn(0);
}

/* Element loop: local residual into Floc (if residual), Jacobian into J (if J); per-cell info if
   asked. Failures are counted, and reported collectively. */
static PetscErrorCode Assemble(Problem *pb, Vec U, PetscReal lambda, PetscBool residual, Mat J, PetscBool want_info)
{
  const Mesh          *m  = pb->mesh;
  const ElementKernel *ek = pb->ek;
  const int            nen = ek->nen, nd = 3 * ek->nen;
  const PetscScalar   *u;
  PetscScalar         *f = NULL;
  PetscInt             nfail = 0, badid = PETSC_MAX_INT, badst = 0, badpt = 0, cfail = 0, ncut = 0;
  double               ke[MAX_EDOF * MAX_EDOF], kc[MAX_EDOF * MAX_EDOF], X[MAX_EDOF], ue[MAX_EDOF], fe[MAX_EDOF];
  PetscInt             gfail;

  PetscFunctionBeginUser;
  {
    Vec Ub;
    PetscCall(BodyGet(pb, U, pb->Ubv, PETSC_TRUE, &Ub));
    PetscCall(DMGlobalToLocal(m->dm, Ub, INSERT_VALUES, pb->Uloc));
    PetscCall(BodyRestore(pb, U, pb->Ubv, PETSC_TRUE));
  }
  PetscCall(VecGetArray(pb->Uloc, (PetscScalar **)&u));
  BCApply(pb->bcs, (PetscScalar *)u, lambda);
  if (residual) {
    PetscCall(VecZeroEntries(pb->Floc));
    PetscCall(VecGetArray(pb->Floc, &f));
    pb->fsq = 0;
  }
  if (J && !pb->coo_v) PetscCall(MatZeroEntries(J));
  for (PetscInt e = 0; e < m->nc; e++) {
    const PetscInt *cv = m->cv + nen * e;
    for (int a = 0; a < nen; a++) {
      const PetscInt o = m->vloff[cv[a]];
      for (int i = 0; i < 3; i++) {
        X[3 * a + i]  = m->X[3 * cv[a] + i];
        ue[3 * a + i] = PetscRealPart(u[o + i]);
      }
    }
    const MaterialKernel *mk = pb->mks[pb->cmat ? pb->cmat[e] : 0];
    if (mk->set_point) mk->set_point(mk->ctx, (int)m->elem_id[e], -1, NULL, 0.0);
    const int st = ek->kernel(ek->ctx, mk, X, ue, pb->hist_c + (size_t)e * pb->nhc, fe, J ? ke : NULL, pb->hist_t + (size_t)e * pb->nhc, want_info ? &pb->einfo[e] : NULL);
    if (st != MAT_OK) {
      nfail++;
      ncut += st == MAT_ERR_CUTBACK;
      if (m->elem_id[e] < badid) {
        badid = m->elem_id[e];
        badst = st;
        badpt = st == MAT_ERR_NAN && mk->failed_point ? mk->failed_point(mk->ctx) : 0;
      }
      continue;
    }
    if (residual)
      for (int a = 0; a < nen; a++) {
        const PetscInt o = m->vloff[cv[a]];
        for (int i = 0; i < 3; i++) {
          f[o + i] += fe[3 * a + i];
          pb->fsq += fe[3 * a + i] * fe[3 * a + i];
        }
      }
    if (J) {
      const PetscInt       n = m->cndof[e];
      const unsigned char *p = m->cperm + nd * e;
      if (pb->coo_v) {
        PetscScalar *v = pb->coo_v + pb->coo_off[e];
        for (PetscInt r = 0; r < n; r++)
          for (PetscInt c = 0; c < n; c++) v[r * n + c] = ke[p[r] * nd + p[c]];
      } else {
        for (PetscInt r = 0; r < n; r++)
          for (PetscInt c = 0; c < n; c++) kc[r * n + c] = ke[p[r] * nd + p[c]];
        PetscCall(MatSetValues(J, n, m->cgdof + nd * e, n, m->cgdof + nd * e, kc, ADD_VALUES));
      }
    }
  }
  PetscCall(ContactAssemble(pb->contact, u, lambda, f, J, pb->coo_v ? pb->coo_v + pb->coo_off[m->nc] : NULL, &cfail));
  if (cfail && !nfail) badst = ATRITO_ERR_PROJECTION;
  nfail += cfail;
  PetscCall(VecRestoreArray(pb->Uloc, (PetscScalar **)&u));
  if (residual) PetscCall(VecRestoreArray(pb->Floc, &f));
  if (J && pb->coo_v) PetscCall(MatSetValuesCOO(J, pb->coo_v, INSERT_VALUES));
  else if (J) {
    PetscCall(MatAssemblyBegin(J, MAT_FINAL_ASSEMBLY));
    PetscCall(MatAssemblyEnd(J, MAT_FINAL_ASSEMBLY));
  }
  /* collective failure report: count, and the smallest failing element id with its cause */
  PetscCall(MPIU_Allreduce(&nfail, &gfail, 1, MPIU_INT, MPI_SUM, pb->comm));
  pb->ndomain_err = gfail;
  if (gfail) {
    PetscInt pair[3] = {badid, badst, badpt}, gmin;
    PetscCall(MPIU_Allreduce(&pair[0], &gmin, 1, MPIU_INT, MPI_MIN, pb->comm));
    if (gmin != badid) pair[1] = pair[2] = 0;
    PetscCall(MPIU_Allreduce(MPI_IN_PLACE, &pair[1], 2, MPIU_INT, MPI_MAX, pb->comm));
    pb->bad_cell_id = gmin;
    pb->bad_status  = pair[1];
    pb->bad_point   = pair[2];
    PetscCall(MPIU_Allreduce(MPI_IN_PLACE, &ncut, 1, MPIU_INT, MPI_SUM, pb->comm));
    if (ncut) pb->cutback = PETSC_TRUE;
  }
  PetscFunctionReturn(0);
}

PetscErrorCode ProblemEvaluate(Problem *pb, Vec U, PetscReal lambda)
{
  PetscFunctionBeginUser;
  PetscCall(Assemble(pb, U, lambda, PETSC_TRUE, NULL, PETSC_TRUE));
  PetscFunctionReturn(0);
}

PetscErrorCode ProblemFormFunction(SNES snes, Vec U, Vec F, void *ctx)
{
  Problem *pb = (Problem *)ctx;

  PetscFunctionBeginUser;
  PetscCall(PetscLogEventBegin(pb->ev_residual, 0, 0, 0, 0));
  PetscCall(Assemble(pb, U, pb->lambda, PETSC_TRUE, NULL, PETSC_FALSE));
  PetscCall(VecZeroEntries(F));
  if (pb->ndomain_err && pb->trial_norm > 0 && !pb->cutback) {
    /* a trial point of the line search outside the residual's domain: a residual larger than the
       iterate's (trial_norm, twice its norm), so that the backtracking search rejects the point
       and shortens the step, instead of ending the Newton solve and cutting the load step */
    PetscInt N;
    PetscCall(VecGetSize(F, &N));
    PetscCall(VecSet(F, pb->trial_norm / PetscSqrtReal((PetscReal)N)));
    pb->ntrial_fail++;
  } else if (pb->ndomain_err) PetscCall(SNESSetFunctionDomainError(snes));
  else {
    Vec Fb = NULL;
    PetscCall(BodyGet(pb, F, pb->Fbv, PETSC_FALSE, &Fb));
    PetscCall(DMLocalToGlobal(pb->mesh->dm, pb->Floc, ADD_VALUES, Fb));
    PetscCall(BodyRestore(pb, F, pb->Fbv, PETSC_FALSE));
    if (pb->ntu) { /* the rows of the tool unknowns (contact.h) */
      PetscReal r[3 * 64];
      PetscCall(ContactToolResidual(pb->contact, pb->lambda, r));
      PetscCall(ProblemSetToolValues(pb, F, r));
    }
  }
  if (pb->fault_nan_load >= 0 && !pb->fault_done && pb->lambda >= pb->fault_nan_load) {
    /* fault injection for the tests: one NaN, once */
    PetscInt n;
    PetscCall(VecGetLocalSize(F, &n));
    if (!pb->rank && n > 0) {
      PetscScalar *a;
      PetscCall(VecGetArray(F, &a));
      a[0] = NAN;
      PetscCall(VecRestoreArray(F, &a));
    }
    pb->fault_done = PETSC_TRUE;
  }
  PetscCall(PetscLogEventEnd(pb->ev_residual, 0, 0, 0, 0));
  PetscFunctionReturn(0);
}

PetscErrorCode ProblemFormJacobian(SNES snes, Vec U, Mat J, Mat P, void *ctx)
{
  Problem *pb = (Problem *)ctx;

  PetscFunctionBeginUser;
  PetscCall(PetscLogEventBegin(pb->ev_jacobian, 0, 0, 0, 0));
  PetscCall(Assemble(pb, U, pb->lambda, PETSC_FALSE, P, PETSC_FALSE));
  /* the iterate goes with the Jacobian: -pc_amgsys_sheet_spacing builds its modes at its positions */
  PetscCall(PetscObjectCompose((PetscObject)P, "atrito_iterate", (PetscObject)U));
  if (pb->ndomain_err) PetscCall(SNESSetJacobianDomainError(snes));
  if (J != P) {
    PetscCall(MatAssemblyBegin(J, MAT_FINAL_ASSEMBLY));
    PetscCall(MatAssemblyEnd(J, MAT_FINAL_ASSEMBLY));
  }
  PetscCall(PetscLogEventEnd(pb->ev_jacobian, 0, 0, 0, 0));
  PetscFunctionReturn(0);
}

/* The internal forces' scale for a force-relative Newton tolerance (-newton_force_tol): the
   element force vectors of the last residual assembly before they are summed at the nodes. The
   assembled residual is the nodes' imbalance, which vanishes at equilibrium whatever the stresses;
   this sum does not: a sheet pressed by tools, or holding residual stresses after springback with
   no load left, keeps it at the size of its stresses times its element faces. */
PetscErrorCode ProblemForceScale(Problem *pb, PetscReal *F)
{
  PetscReal s = pb->fsq;

  PetscFunctionBeginUser;
  PetscCall(MPIU_Allreduce(MPI_IN_PLACE, &s, 1, MPIU_REAL, MPIU_SUM, pb->comm));
  *F = PetscSqrtReal(s);
  PetscFunctionReturn(0);
}

PetscErrorCode ProblemResidualPeak(Problem *pb, Vec F, PetscReal *val, PetscInt *node, PetscInt *comp, PetscReal x[3])
{
  const Mesh        *m = pb->mesh;
  Vec                Fb, Fl;
  const PetscScalar *f;
  struct {
    PetscReal v;
    PetscInt  r;
  } loc = {-1, 0}, glob;
  PetscReal buf[5] = {0, 0, 0, 0, 0};

  PetscFunctionBeginUser;
  PetscCall(DMGetLocalVector(m->dm, &Fl));
  PetscCall(VecZeroEntries(Fl));
  PetscCall(BodyGet(pb, F, pb->Fbv, PETSC_TRUE, &Fb));
  PetscCall(DMGlobalToLocal(m->dm, Fb, INSERT_VALUES, Fl));
  PetscCall(BodyRestore(pb, F, pb->Fbv, PETSC_TRUE));
  PetscCall(VecGetArrayRead(Fl, &f));
  for (PetscInt v = 0; v < m->nv; v++) {
    if (!m->vowned[v]) continue;
    for (int k = 0; k < 3; k++) {
      const PetscReal a = PetscAbsReal(PetscRealPart(f[m->vloff[v] + k]));
      if (a > loc.v) {
        loc.v  = a;
        buf[0] = (PetscReal)m->node_id[v];
        buf[1] = k;
        for (int j = 0; j < 3; j++) buf[2 + j] = m->X[3 * v + j];
      }
    }
  }
  PetscCall(VecRestoreArrayRead(Fl, &f));
  PetscCall(DMRestoreLocalVector(m->dm, &Fl));
  PetscCallMPI(MPI_Allreduce(&loc.v, &glob.v, 1, MPIU_REAL, MPIU_MAX, pb->comm));
  loc.r = loc.v == glob.v ? pb->rank : pb->size;
  PetscCallMPI(MPI_Allreduce(&loc.r, &glob.r, 1, MPIU_INT, MPI_MIN, pb->comm));
  PetscCallMPI(MPI_Bcast(buf, 5, MPIU_REAL, (PetscMPIInt)glob.r, pb->comm));
  *val  = glob.v;
  *node = (PetscInt)buf[0];
  *comp = (PetscInt)buf[1];
  for (int j = 0; j < 3; j++) x[j] = buf[2 + j];
  PetscFunctionReturn(0);
}

PetscErrorCode ProblemLocalWithBC(Problem *pb, Vec U, PetscReal lambda)
{
  PetscScalar *u;
  Vec          Ub;

  PetscFunctionBeginUser;
  PetscCall(BodyGet(pb, U, pb->Ubv, PETSC_TRUE, &Ub));
  PetscCall(DMGlobalToLocal(pb->mesh->dm, Ub, INSERT_VALUES, pb->Uloc));
  PetscCall(BodyRestore(pb, U, pb->Ubv, PETSC_TRUE));
  PetscCall(VecGetArray(pb->Uloc, &u));
  BCApply(pb->bcs, u, lambda);
  PetscCall(VecRestoreArray(pb->Uloc, &u));
  PetscFunctionReturn(0);
}

PetscErrorCode ProblemCommit(Problem *pb, PetscReal lambda)
{
  PetscFunctionBeginUser;
  PetscCheck(!pb->ndomain_err, pb->comm, PETSC_ERR_PLIB, "element evaluation failed at a converged state");
  PetscCall(PetscArraycpy(pb->hist_c, pb->hist_t, (size_t)pb->mesh->nc * pb->nhc));
  PetscCall(ContactCommit(pb->contact, lambda));
  PetscCall(VecCopy(pb->Uc, pb->Uprev));
  PetscCall(VecCopy(pb->U, pb->Uc));
  PetscFunctionReturn(0);
}

PetscErrorCode ProblemRestored(Problem *pb)
{
  PetscFunctionBeginUser;
  PetscCall(PetscArraycpy(pb->hist_t, pb->hist_c, (size_t)pb->mesh->nc * pb->nhc));
  PetscCall(VecCopy(pb->Uc, pb->U));
  PetscFunctionReturn(0);
}

/* modified Gram-Schmidt on n vectors (a mode may vanish where everything is constrained) */
static PetscErrorCode VecOrthonormalize_Modes(PetscInt n, Vec v[])
{
  PetscFunctionBeginUser;
  for (PetscInt i = 0; i < n; i++) {
    PetscReal nrm;
    for (PetscInt j = 0; j < i; j++) {
      PetscScalar d;
      PetscCall(VecDot(v[i], v[j], &d));
      PetscCall(VecAXPY(v[i], -d, v[j]));
    }
    PetscCall(VecNorm(v[i], NORM_2, &nrm));
    if (nrm > 0) PetscCall(VecScale(v[i], 1.0 / nrm));
  }
  PetscFunctionReturn(0);
}

/* The rigid-body modes (3 translations, 3 rotations about the centroid of the reference
   coordinates) on the unconstrained dofs, as the near-null space of the Jacobian: algebraic
   multigrid (-pc_type gamg) needs them. */
static PetscErrorCode SetNearNullSpace(Problem *pb, Mat J)
{
  Vec          modes[6];
  MatNullSpace nsp;
  PetscInt     rstart;
  const Mesh  *msh = pb->mesh;
  PetscReal    c[3] = {0, 0, 0}, n = msh->nvo;

  PetscFunctionBeginUser;
  for (PetscInt k = 0; k < msh->nvo; k++)
    for (int i = 0; i < 3; i++) c[i] += msh->X[3 * msh->vloc[k] + i];
  PetscCall(MPIU_Allreduce(MPI_IN_PLACE, c, 3, MPIU_REAL, MPIU_SUM, pb->comm));
  PetscCall(MPIU_Allreduce(MPI_IN_PLACE, &n, 1, MPIU_REAL, MPIU_SUM, pb->comm));
  for (int i = 0; i < 3; i++) c[i] /= PetscMax(n, 1);
  for (int m = 0; m < 6; m++) {
    PetscScalar *a;
    if (pb->ntu) PetscCall(VecDuplicate(pb->U, &modes[m]));
    else PetscCall(DMCreateGlobalVector(msh->dm, &modes[m]));
    PetscCall(VecGetOwnershipRange(modes[m], &rstart, NULL));
    PetscCall(VecGetArray(modes[m], &a));
    for (PetscInt k = 0; k < msh->nvo; k++) {
      const PetscReal *X = msh->X + 3 * msh->vloc[k], x[3] = {X[0] - c[0], X[1] - c[1], X[2] - c[2]};
      PetscReal        v[3] = {0, 0, 0};
      PetscInt         idx[3];
      if (m < 3) v[m] = 1;
      else { /* e_r x x for the axis r = m - 3 */
        const int r = m - 3, r1 = (r + 1) % 3, r2 = (r + 2) % 3;
        v[r1] = -x[r2];
        v[r2] = x[r1];
      }
      PetscCall(MeshVertexDofs(msh, msh->vloc[k], idx));
      for (PetscInt d = 0; d < 3; d++)
        if (idx[d] >= 0) a[idx[d] - rstart] = v[d];
    }
    if (pb->ntu && m < 3 && pb->rank == pb->size - 1) { /* a translation moves the tools too */
      PetscInt n;
      PetscCall(VecGetLocalSize(modes[m], &n));
      for (PetscInt b = 0; b < pb->ntu / 3; b++) a[n - pb->ntu + 3 * b + m] = 1;
    }
    PetscCall(VecRestoreArray(modes[m], &a));
  }
  PetscCall(VecOrthonormalize_Modes(6, modes));
  PetscCall(MatNullSpaceCreate(pb->comm, PETSC_FALSE, 6, modes, &nsp));
  PetscCall(MatSetNearNullSpace(J, nsp));
  PetscCall(MatNullSpaceDestroy(&nsp));
  for (int m = 0; m < 6; m++) PetscCall(VecDestroy(&modes[m]));
  PetscFunctionReturn(0);
}


PetscErrorCode ProblemSetFromOptions(MPI_Comm comm, Problem *pb)
{
  KSP ksp;
  PC  pc;

  PetscFunctionBeginUser;
  PetscCall(PetscMemzero(pb, sizeof(*pb)));
  pb->comm           = comm;
  pb->lu_ordering    = LU_ORDERING_ND;
  pb->assembly_coo   = PETSC_TRUE; /* coordinate assembly by default: the faster Jacobian (doc/notes/performance-log.md) */
  pb->fault_nan_load = -1;
  pb->near_null      = PETSC_TRUE;
  PetscCallMPI(MPI_Comm_rank(comm, &pb->rank));
  PetscCallMPI(MPI_Comm_size(comm, &pb->size));
  PetscOptionsBegin(comm, NULL, "Assembly and linear solver", NULL);
  PetscCall(PetscOptionsBool("-assembly_coo", "Assemble the Jacobian in coordinate form (faster, more memory; not with contact pairs, whose pattern changes)", NULL, pb->assembly_coo, &pb->assembly_coo, &pb->assembly_coo_set));
  PetscCall(PetscOptionsString("-assembly_mat_type", "Matrix type of the Jacobian (default: the mesh's, AIJ; hypre: assembled in hypre's format, which -pc_type hypre then uses without a copy; with force-driven tools its mesh block, bordered by their unknowns, for -pc_type amgsys)", NULL, pb->mat_type, pb->mat_type, sizeof(pb->mat_type), NULL));
  PetscCall(PetscOptionsBool("-assembly_near_null_space", "Attach the six rigid-body modes to the Jacobian as its near null space (GAMG's coarse spaces; BoomerAMG uses them only with -pc_hypre_boomeramg_vec_interp_variant, but PCHYPRE copies them)", NULL, pb->near_null, &pb->near_null, NULL));
  {
    const char *ords[] = {"mumps", "nd", "LUOrdering", "LU_ORDERING_", NULL};
    PetscInt    o      = (PetscInt)pb->lu_ordering;
    PetscCall(PetscOptionsEList("-lu_ordering", "Ordering of the LU factorisation (-pc_type lu with MUMPS): nd = METIS nested dissection of the Jacobian's graph, MUMPS called directly; mumps = MUMPS's own ordering (PORD here) through PETSc's interface", NULL, ords, 2, ords[o], &o, NULL));
    pb->lu_ordering = (LUOrdering)o;
  }
  PetscCall(PetscOptionsReal("-fault_nan_residual_at", "Testing: once, put a NaN into the residual at the first evaluation at or beyond this load", NULL, pb->fault_nan_load, &pb->fault_nan_load, NULL));
  PetscOptionsEnd();
  if (pb->lu_ordering == LU_ORDERING_ND) PetscCall(LUNDCheckOptions(comm, NULL));

  /* Newton with the backtracking line search, LU by MUMPS; every -snes_, -ksp_, -pc_ option
     applies on top */
  PetscCall(AMGSysRegister());
  PetscCall(SNESCreate(comm, &pb->snes));
  PetscCall(SNESSetTolerances(pb->snes, 1e-10, 1e-9, 1e-12, 25, -1));
  PetscCall(SNESGetKSP(pb->snes, &ksp));
  PetscCall(KSPSetType(ksp, KSPPREONLY));
  PetscCall(KSPGetPC(ksp, &pc));
  PetscCall(PCSetType(pc, PCLU));
  PetscCall(PCFactorSetMatSolverType(pc, MATSOLVERMUMPS));
  PetscCall(SNESSetFromOptions(pb->snes));
  PetscFunctionReturn(0);
}

/* The Jacobian in hypre's format (-assembly_mat_type hypre), preallocated and filled with zeros on
   the DM's pattern as DMCreateMatrix() does, but told before its preallocation that whole rows
   will come (MAT_SORTED_FULL). PETSc 3.18's MATHYPRE otherwise keeps beside the matrix hypre's
   auxiliary assembly structure: per row, arrays of column indices and values that it fills first
   and copies into the matrix at the assembly (NeedAux), and which it creates anew after every
   assembly (MatAssemblyEnd_HYPRE). With the option, on more than one rank hypre writes the zeros
   of the pattern straight into its matrix (exact row sizes from the preallocation), and on any
   number of ranks no auxiliary structure is made again after an assembly. What later assemblies
   add goes straight into the assembled matrix in every case: hypre's AddToValues on an assembled
   matrix looks each (row, column) up in the row and adds (an entry off the pattern is an error);
   rows of other ranks travel in hypre's own off-processor buffers, made when needed and freed at
   the assembly. So MAT_SORTED_FULL, whose name speaks of the first fill, only changes what is
   kept, not what is assembled (doc/notes/performance-log.md, "Where the memory goes").
   With coordinate assembly (-assembly_coo 1, cases/solver_amgsys_fast.opts) the matrix is left
   bare: MatSetPreallocationCOO (ProblemSetUp) makes its pattern through an AIJ matrix whose value
   arrays are hypre's own, so each Jacobian's MatSetValuesCOO writes hypre's values in place (no
   auxiliary structure either; about 12 kB more per hexahedron, 2.6 times faster than
   MatSetValues: doc/notes/performance-log.md, "The smoother"). */
static PetscErrorCode CreateHypreJacobian(Problem *pb, Mat *J)
{
  const Mesh *m = pb->mesh;
  PetscInt    nl, N, bs, *dnz, *onz, *dnzu, *onzu;
  Vec         g;

  PetscFunctionBeginUser;
  PetscCall(DMGetGlobalVector(m->dm, &g));
  PetscCall(VecGetLocalSize(g, &nl));
  PetscCall(VecGetSize(g, &N));
  PetscCall(VecGetBlockSize(g, &bs));
  PetscCall(DMRestoreGlobalVector(m->dm, &g));
  PetscCall(MatCreate(pb->comm, J));
  PetscCall(MatSetSizes(*J, nl, nl, N, N));
  PetscCall(MatSetBlockSize(*J, bs));
  PetscCall(MatSetType(*J, MATHYPRE));
  if (pb->assembly_coo) PetscFunctionReturn(0); /* bare: the coordinate preallocation makes the pattern */
  PetscCall(MatSetOption(*J, MAT_SORTED_FULL, PETSC_TRUE));
  PetscCall(PetscCalloc4(nl / bs, &dnz, nl / bs, &onz, nl / bs, &dnzu, nl / bs, &onzu));
  PetscCall(DMPlexPreallocateOperator(m->dm, bs, dnz, onz, dnzu, onzu, *J, PETSC_TRUE));
  PetscCall(PetscFree4(dnz, onz, dnzu, onzu));
  PetscFunctionReturn(0);
}

PetscErrorCode ProblemSetUp(Problem *pb, const Mesh *m, const BCs *bcs, Contact contact, Material mat, Element el)
{
  Vec       R;
  KSP       ksp;
  PC        pc;
  PetscBool ishypre;

  PetscFunctionBeginUser;
  pb->mesh     = m;
  pb->bcs      = bcs;
  pb->contact  = contact;
  pb->material = mat;
  pb->element  = el;
  if (ContactNumPairs(contact)) {
    /* contact between bodies couples each slave node with the nodes of the face it meets: a
       pattern that changes as the bodies slide, so the Jacobian is assembled by MatSetValues and
       takes new nonzeros (the LU analyses a changed pattern again) */
    PetscCheck(!(pb->assembly_coo && pb->assembly_coo_set), pb->comm, PETSC_ERR_USER_INPUT, "-assembly_coo 1: not with contact pairs (-pair_names), whose Jacobian pattern changes; leave it out");
    PetscCheck(!pb->mat_type[0], pb->comm, PETSC_ERR_USER_INPUT, "-assembly_mat_type %s: not with contact pairs (-pair_names), whose Jacobian pattern changes; leave it out", pb->mat_type);
    pb->assembly_coo = PETSC_FALSE;
  }
  PetscCall(MaterialGetKernel(mat, &pb->mk));
  if (!pb->nmat) { /* one material for the whole mesh */
    pb->nmat    = 1;
    pb->mats[0] = mat;
  }
  for (PetscInt k = 0; k < pb->nmat; k++) PetscCall(MaterialGetKernel(pb->mats[k], &pb->mks[k]));
  PetscCall(ElementGetKernel(el, &pb->ek));
  PetscCheck(pb->ek->nen == 8, pb->comm, PETSC_ERR_SUP, "-element_type %s: the mesh has 8-node hexahedra, the element %d nodes", pb->ek->name, pb->ek->nen);
  PetscCall(PetscLogEventRegister("AtritoResidual", DM_CLASSID, &pb->ev_residual));
  PetscCall(PetscLogEventRegister("AtritoJacobian", DM_CLASSID, &pb->ev_jacobian));
  {
    /* per cell the history of its material's points, then the element's state (at the offset its
       material's width sets): the widest material's */
    int nh = 0;
    for (PetscInt k = 0; k < pb->nmat; k++) nh = PetscMax(nh, pb->mks[k]->nhist);
    pb->nhc = (PetscInt)pb->ek->nqp * nh + pb->ek->nstate;
  }
  PetscCall(PetscMalloc2((size_t)m->nc * pb->nhc, &pb->hist_c, (size_t)m->nc * pb->nhc, &pb->hist_t));
  PetscCall(PetscArrayzero(pb->hist_c, (size_t)m->nc * pb->nhc));
  for (PetscInt e = 0; e < m->nc; e++)
    for (int q = 0; q < pb->ek->nqp; q++) {
      const MaterialKernel *mk = pb->mks[pb->cmat ? pb->cmat[e] : 0];
      mk->history_init(mk->ctx, pb->hist_c + (size_t)e * pb->nhc + (size_t)q * mk->nhist);
    }
  PetscCall(PetscArraycpy(pb->hist_t, pb->hist_c, (size_t)m->nc * pb->nhc));
  PetscCall(PetscCalloc1(m->nc, &pb->einfo));
  PetscCall(DMCreateGlobalVector(m->dm, &pb->U));
  pb->ntu = ContactNumToolUnknowns(contact);
  if (pb->ntu) {
    /* the tool unknowns follow the body's, on the last rank: the body's global numbering stays */
    PetscInt nbl, N;
    pb->Ubv = pb->U;
    PetscCall(VecDuplicate(pb->Ubv, &pb->Fbv));
    PetscCall(VecGetLocalSize(pb->Ubv, &nbl));
    PetscCall(VecGetSize(pb->Ubv, &N));
    PetscCall(VecCreateMPI(pb->comm, nbl + (pb->rank == pb->size - 1 ? pb->ntu : 0), PETSC_DETERMINE, &pb->U));
    {
      /* the body's block size (3 when no component is constrained apart from whole vertices) stays:
         the tools add 3 unknowns each */
      PetscInt bs, ok;
      PetscCall(VecGetBlockSize(pb->Ubv, &bs));
      ok = (bs > 1 && nbl % bs == 0 && 3 % bs == 0) ? 1 : 0;
      PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, &ok, 1, MPIU_INT, MPI_MIN, pb->comm));
      pb->tbs = ok ? bs : 1;
      if (ok) PetscCall(VecSetBlockSize(pb->U, bs));
    }
    PetscCall(ContactSetToolDofs(contact, N, pb->rank == pb->size - 1 ? PETSC_TRUE : PETSC_FALSE));
  }
  PetscCall(VecDuplicate(pb->U, &pb->Uc));
  PetscCall(VecDuplicate(pb->U, &pb->Uprev));
  PetscCall(DMCreateLocalVector(m->dm, &pb->Uloc));
  PetscCall(VecDuplicate(pb->Uloc, &pb->Floc));

  PetscCall(PetscStrcmp(pb->mat_type, MATHYPRE, &ishypre));
  {
    PetscBool isaij;
    PetscCall(PetscStrcmp(pb->mat_type, MATAIJ, &isaij));
    PetscCheck(!pb->mat_type[0] || !pb->ntu || ishypre || isaij, pb->comm, PETSC_ERR_SUP, "-assembly_mat_type %s: not with force-driven tools (their unknowns extend an AIJ matrix, or border a hypre one); give aij or hypre, or leave it out", pb->mat_type);
  }
  if (pb->ntu && ishypre) {
    /* the mesh block in hypre's format, bordered by the tools' unknowns (include/bordered.h): the
       one copy of the mesh block that -pc_type amgsys needs, by MatSetValues */
    Mat A;
    PetscCheck(!(pb->assembly_coo && pb->assembly_coo_set), pb->comm, PETSC_ERR_USER_INPUT, "-assembly_coo 1: not with -assembly_mat_type hypre and force-driven tools (the border is assembled by MatSetValues); leave it out");
    pb->assembly_coo = PETSC_FALSE;
    PetscCall(CreateHypreJacobian(pb, &A));
    PetscCall(MatSetOption(A, MAT_NEW_NONZERO_ALLOCATION_ERR, PETSC_TRUE));
    PetscCall(MatCreateBordered(A, pb->ntu, &pb->J));
    PetscCall(MatDestroy(&A));
    pb->bordered = PETSC_TRUE;
  } else if (!pb->ntu) {
    PetscCheck(!pb->mat_type[0] || ishypre || !pb->assembly_coo, pb->comm, PETSC_ERR_SUP, "-assembly_mat_type %s needs the MatSetValues assembly: add -assembly_coo 0", pb->mat_type);
    if (ishypre) PetscCall(CreateHypreJacobian(pb, &pb->J));
    else {
      if (pb->mat_type[0]) PetscCall(DMSetMatType(m->dm, pb->mat_type));
      PetscCall(DMCreateMatrix(m->dm, &pb->J));
    }
  }
  else {
    /* the DM's pattern extended by the rows and columns of the tool unknowns: every slave node
       that may touch a force-driven tool couples with its unknowns (a fixed set) */
    PetscInt nl;
    PetscCall(VecGetLocalSize(pb->U, &nl));
    PetscCall(MatCreate(pb->comm, &pb->J));
    PetscCall(MatSetSizes(pb->J, nl, nl, PETSC_DETERMINE, PETSC_DETERMINE));
    PetscCall(MatSetBlockSize(pb->J, pb->tbs));
    PetscCall(MatSetType(pb->J, MATAIJ));
    if (!pb->assembly_coo) {
      const PetscInt     nd = 3 * pb->ek->nen;
      static PetscScalar zeros[MAX_EDOF * MAX_EDOF];
      Mat                pre;
      PetscCount         nct;
      PetscInt          *ci, *cj;
      PetscCall(MatCreate(pb->comm, &pre));
      PetscCall(MatSetSizes(pre, nl, nl, PETSC_DETERMINE, PETSC_DETERMINE));
      PetscCall(MatSetType(pre, MATPREALLOCATOR));
      PetscCall(MatSetUp(pre));
      for (PetscInt e = 0; e < m->nc; e++) PetscCall(MatSetValues(pre, m->cndof[e], m->cgdof + nd * e, m->cndof[e], m->cgdof + nd * e, zeros, INSERT_VALUES));
      PetscCall(ContactGetCOO(contact, &nct, NULL, NULL));
      PetscCall(PetscMalloc2(nct + 1, &ci, nct + 1, &cj));
      PetscCall(ContactGetCOO(contact, &nct, ci, cj));
      for (PetscCount k = 0; k < nct; k++) PetscCall(MatSetValues(pre, 1, &ci[k], 1, &cj[k], zeros, INSERT_VALUES));
      PetscCall(PetscFree2(ci, cj));
      PetscCall(MatAssemblyBegin(pre, MAT_FINAL_ASSEMBLY));
      PetscCall(MatAssemblyEnd(pre, MAT_FINAL_ASSEMBLY));
      PetscCall(MatPreallocatorPreallocate(pre, PETSC_TRUE, pb->J));
      PetscCall(MatDestroy(&pre));
    }
  }
  if (pb->near_null) PetscCall(SetNearNullSpace(pb, pb->J));
  if (pb->bordered) { /* only amgsys takes it: a factorisation needs an assembled matrix */
    PetscBool isamg;
    PetscCall(SNESGetKSP(pb->snes, &ksp));
    PetscCall(KSPGetPC(ksp, &pc));
    PetscCall(PetscObjectTypeCompare((PetscObject)pc, "amgsys", &isamg));
    PetscCheck(isamg, pb->comm, PETSC_ERR_USER_INPUT, "-assembly_mat_type hypre with force-driven tools: the Jacobian is the mesh block bordered by the tools' unknowns, which only -pc_type amgsys takes; give -pc_type amgsys or leave -assembly_mat_type out");
    { /* PETSc's test compares assembled matrices only: with a bordered one it would print nothing */
      PetscBool test;
      PetscCall(PetscOptionsHasName(NULL, NULL, "-snes_test_jacobian", &test));
      PetscCheck(!test, pb->comm, PETSC_ERR_USER_INPUT, "-snes_test_jacobian: not with the bordered Jacobian (-assembly_mat_type hypre and force-driven tools), which PETSc cannot compare; test with -assembly_mat_type aij, the same entries");
    }
  }
  if (ContactNumPairs(contact)) PetscCall(MatSetOption(pb->J, MAT_NEW_NONZERO_ALLOCATION_ERR, PETSC_FALSE));
  else if (!(pb->ntu && pb->assembly_coo) && !pb->bordered) PetscCall(MatSetOption(pb->J, MAT_NEW_NONZERO_ALLOCATION_ERR, PETSC_TRUE)); /* (not before the preallocation of an extended matrix) */
  if (pb->assembly_coo) {
    /* coordinate assembly: the element blocks' (i, j) once, then the contact blocks; each
       Jacobian then only fills values */
    const PetscInt nd = 3 * pb->ek->nen;
    PetscCount     ncoo = 0, nct;
    PetscInt      *ci, *cj;
    PetscCall(PetscMalloc1(m->nc + 1, &pb->coo_off));
    for (PetscInt e = 0; e < m->nc; e++) {
      pb->coo_off[e] = ncoo;
      ncoo += m->cndof[e] * m->cndof[e];
    }
    pb->coo_off[m->nc] = ncoo;
    PetscCall(ContactGetCOO(contact, &nct, NULL, NULL));
    PetscCall(PetscMalloc2(ncoo + nct, &ci, ncoo + nct, &cj));
    for (PetscInt e = 0; e < m->nc; e++) {
      const PetscInt n = m->cndof[e], *g = m->cgdof + nd * e;
      for (PetscInt r = 0; r < n; r++)
        for (PetscInt c = 0; c < n; c++) {
          ci[pb->coo_off[e] + r * n + c] = g[r];
          cj[pb->coo_off[e] + r * n + c] = g[c];
        }
    }
    PetscCall(ContactGetCOO(contact, &nct, ci + ncoo, cj + ncoo));
    PetscCall(MatSetPreallocationCOO(pb->J, ncoo + nct, ci, cj));
    if (pb->ntu) PetscCall(MatSetOption(pb->J, MAT_NEW_NONZERO_ALLOCATION_ERR, PETSC_TRUE));
    PetscCall(PetscFree2(ci, cj));
    PetscCall(PetscCalloc1(ncoo + nct, &pb->coo_v));
  }
  PetscCall(VecDuplicate(pb->U, &R));
  PetscCall(SNESSetFunction(pb->snes, R, ProblemFormFunction, pb));
  PetscCall(VecDestroy(&R));
  PetscCall(SNESSetJacobian(pb->snes, pb->J, pb->J, ProblemFormJacobian, pb));
  PetscCall(SNESSetApplicationContext(pb->snes, pb));
  PetscCall(SNESGetKSP(pb->snes, &ksp));
  PetscCall(KSPGetPC(ksp, &pc));
  { /* -pc_type amgsys reads each row's displacement component from the mesh's sections (a force-driven
       tool's rows, after them, it eliminates through their Schur complement) */
    PetscBool isamg;
    PetscCall(PetscObjectTypeCompare((PetscObject)pc, "amgsys", &isamg));
    if (isamg) PetscCall(PCSetDM(pc, m->dm));
  }
  if (pb->lu_ordering == LU_ORDERING_ND) {
    /* LU by MUMPS, unless the options chose another preconditioner or package: MUMPS called
       directly with a METIS nested-dissection ordering (fewer flops than PORD, and balanced
       subtrees for the ranks; doc/notes/design-log.md) */
    PetscBool     islu;
    MatSolverType st;
    PetscCall(PetscObjectTypeCompare((PetscObject)pc, PCLU, &islu));
    if (islu) {
      PetscCall(PCFactorGetMatSolverType(pc, &st));
      if (st && !strcmp(st, MATSOLVERMUMPS)) PetscCall(PCSetLUND(pc));
    }
  }
  PetscFunctionReturn(0);
}

PetscErrorCode ProblemSetMaterials(Problem *pb, PetscInt n, const Material *mats, const PetscInt *cmat, PetscInt nc)
{
  PetscFunctionBeginUser;
  PetscCheck(n >= 1 && n <= PROBLEM_MAX_MAT, PETSC_COMM_SELF, PETSC_ERR_ARG_OUTOFRANGE, "at most %d materials", PROBLEM_MAX_MAT);
  pb->nmat = n;
  for (PetscInt k = 0; k < n; k++) pb->mats[k] = mats[k];
  PetscCall(PetscFree(pb->cmat));
  PetscCall(PetscMalloc1(nc + 1, &pb->cmat));
  PetscCall(PetscArraycpy(pb->cmat, cmat, nc));
  PetscFunctionReturn(0);
}

PetscErrorCode ProblemDestroy(Problem *pb)
{
  PetscFunctionBeginUser;
  PetscCall(PetscFree(pb->cmat));
  PetscCall(SNESDestroy(&pb->snes));
  PetscCall(MatDestroy(&pb->J));
  PetscCall(VecDestroy(&pb->U));
  PetscCall(VecDestroy(&pb->Uc));
  PetscCall(VecDestroy(&pb->Uprev));
  PetscCall(VecDestroy(&pb->Ubv));
  PetscCall(VecDestroy(&pb->Fbv));
  PetscCall(VecDestroy(&pb->Uloc));
  PetscCall(VecDestroy(&pb->Floc));
  PetscCall(PetscFree2(pb->hist_c, pb->hist_t));
  PetscCall(PetscFree(pb->einfo));
  PetscCall(PetscFree(pb->coo_off));
  PetscCall(PetscFree(pb->coo_v));
  PetscFunctionReturn(0);
}
