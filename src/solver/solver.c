/* Solver module: assembly of the residual and the exact Jacobian over the local cells,
   SNES, load stepping with cut-back and growth, commit and rollback of the history.

   State lifecycle: hist_c (committed) changes only when a step converges (ProblemSolve); every
   residual or Jacobian evaluation recomputes hist_t (trial) from hist_c and the current iterate. */
#include <math.h>
#include <string.h>
#include "atrito.h"
#include "tensor.h"
#include "output.h"
#include "iorows.h"
#include "lu.h"

static void BoundaryValues(const Problem *pb, PetscScalar *u, PetscReal lambda)
{
  for (PetscInt b = 0; b < pb->nbc; b++)
    for (PetscInt k = 0; k < pb->bc[b].nset; k++) u[pb->bc[b].loff[k]] = lambda * pb->bc[b].val[k];
}

/* Element loop: local residual into Floc (if F), Jacobian into J (if J); per-cell info if asked.
   Failures are counted, and reported collectively. */
static PetscErrorCode Assemble(Problem *pb, Vec U, PetscReal lambda, PetscBool residual, Mat J, PetscBool want_info)
{
  const PetscScalar *u;
  PetscScalar       *f = NULL;
  PetscInt           nfail = 0, badid = PETSC_MAX_INT, badst = 0;
  double             ke[24 * 24], kc[24 * 24];
  PetscInt           gfail;

  PetscFunctionBeginUser;
  PetscCall(DMGlobalToLocal(pb->dm, U, INSERT_VALUES, pb->Uloc));
  PetscCall(VecGetArray(pb->Uloc, (PetscScalar **)&u));
  BoundaryValues(pb, (PetscScalar *)u, lambda);
  if (residual) {
    PetscCall(VecZeroEntries(pb->Floc));
    PetscCall(VecGetArray(pb->Floc, &f));
  }
  if (J && !pb->coo_v) PetscCall(MatZeroEntries(J));
  for (PetscInt e = 0; e < pb->nc; e++) {
    double         X[8][3], ue[8][3], fe[24];
    const PetscInt *cv = pb->cv + 8 * e;
    for (int a = 0; a < 8; a++) {
      const PetscInt o = pb->vloff[cv[a]];
      for (int i = 0; i < 3; i++) {
        X[a][i]  = pb->X[3 * cv[a] + i];
        ue[a][i] = PetscRealPart(u[o + i]);
      }
    }
    const PetscReal(*hn)[MAT_NHIST] = (const PetscReal(*)[MAT_NHIST])(pb->hist_c + (size_t)e * HEX8_NQP * MAT_NHIST);
    PetscReal(*ht)[MAT_NHIST]       = (PetscReal(*)[MAT_NHIST])(pb->hist_t + (size_t)e * HEX8_NQP * MAT_NHIST);
    const int st = hex8_element(&pb->cs->mat, &pb->cs->elem, X, ue, hn, fe, J ? ke : NULL, ht, want_info ? &pb->einfo[e] : NULL);
    if (st != MAT_OK) {
      nfail++;
      if (pb->elem_id[e] < badid) {
        badid = pb->elem_id[e];
        badst = st;
      }
      continue;
    }
    if (residual)
      for (int a = 0; a < 8; a++) {
        const PetscInt o = pb->vloff[cv[a]];
        for (int i = 0; i < 3; i++) f[o + i] += fe[3 * a + i];
      }
    if (J) {
      const PetscInt       n = pb->cndof[e];
      const unsigned char *p = pb->cperm + 24 * e;
      if (pb->coo_v) {
        PetscScalar *v = pb->coo_v + pb->coo_off[e];
        for (PetscInt r = 0; r < n; r++)
          for (PetscInt c = 0; c < n; c++) v[r * n + c] = ke[p[r] * 24 + p[c]];
      } else {
        for (PetscInt r = 0; r < n; r++)
          for (PetscInt c = 0; c < n; c++) kc[r * n + c] = ke[p[r] * 24 + p[c]];
        PetscCall(MatSetValues(J, n, pb->cgdof + 24 * e, n, pb->cgdof + 24 * e, kc, ADD_VALUES));
      }
    }
  }
  PetscCall(ContactAssemble(pb, u, lambda, f, J, pb->coo_v ? pb->coo_v + pb->coo_off[pb->nc] : NULL));
  if (pb->contact_fail && !nfail) badst = ATRITO_ERR_PROJECTION;
  nfail += pb->contact_fail;
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
    PetscInt pair[2] = {badid, badst}, gmin;
    PetscCall(MPIU_Allreduce(&pair[0], &gmin, 1, MPIU_INT, MPI_MIN, pb->comm));
    if (gmin != badid) pair[1] = 0;
    PetscCall(MPIU_Allreduce(MPI_IN_PLACE, &pair[1], 1, MPIU_INT, MPI_MAX, pb->comm));
    pb->bad_cell_id = gmin;
    pb->bad_status  = pair[1];
  }
  PetscFunctionReturn(0);
}

PetscErrorCode ProblemResidualLocal(Problem *pb, Vec U, PetscReal lambda)
{
  PetscFunctionBeginUser;
  PetscCall(Assemble(pb, U, lambda, PETSC_TRUE, NULL, PETSC_TRUE));
  PetscFunctionReturn(0);
}

static PetscErrorCode FormFunction(SNES snes, Vec U, Vec F, void *ctx)
{
  Problem *pb = (Problem *)ctx;

  PetscFunctionBeginUser;
  PetscCall(PetscLogEventBegin(pb->ev_residual, 0, 0, 0, 0));
  PetscCall(Assemble(pb, U, pb->lambda, PETSC_TRUE, NULL, PETSC_FALSE));
  PetscCall(VecZeroEntries(F));
  if (pb->ndomain_err) PetscCall(SNESSetFunctionDomainError(snes));
  else PetscCall(DMLocalToGlobal(pb->dm, pb->Floc, ADD_VALUES, F));
  if (pb->cs->fault_nan_load >= 0 && !pb->fault_done && pb->lambda >= pb->cs->fault_nan_load) {
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

static PetscErrorCode FormJacobian(SNES snes, Vec U, Mat J, Mat P, void *ctx)
{
  Problem *pb = (Problem *)ctx;

  PetscFunctionBeginUser;
  PetscCall(PetscLogEventBegin(pb->ev_jacobian, 0, 0, 0, 0));
  PetscCall(Assemble(pb, U, pb->lambda, PETSC_FALSE, P, PETSC_FALSE));
  if (pb->ndomain_err) PetscCall(SNESSetJacobianDomainError(snes));
  if (J != P) {
    PetscCall(MatAssemblyBegin(J, MAT_FINAL_ASSEMBLY));
    PetscCall(MatAssemblyEnd(J, MAT_FINAL_ASSEMBLY));
  }
  PetscCall(PetscLogEventEnd(pb->ev_jacobian, 0, 0, 0, 0));
  PetscFunctionReturn(0);
}

/* Reactions: the assembled internal force at the vertices of each BC set, summed over the
   owned vertices (every vertex counted once), on all ranks. */
PetscErrorCode ProblemReactions(Problem *pb, PetscReal (*R)[3])
{
  Vec                Rg;
  const PetscScalar *r;
  PetscSection       gs;
  PetscInt           rstart;

  PetscFunctionBeginUser;
  PetscCall(DMGetGlobalVector(pb->dmr, &Rg));
  PetscCall(VecZeroEntries(Rg));
  PetscCall(DMLocalToGlobal(pb->dmr, pb->Floc, ADD_VALUES, Rg));
  PetscCall(DMGetGlobalSection(pb->dmr, &gs));
  PetscCall(VecGetOwnershipRange(Rg, &rstart, NULL));
  PetscCall(VecGetArrayRead(Rg, &r));
  for (PetscInt b = 0; b < pb->nbc; b++) {
    R[b][0] = R[b][1] = R[b][2] = 0;
    for (PetscInt k = 0; k < pb->bc[b].nown; k++) {
      PetscInt goff;
      PetscCall(PetscSectionGetOffset(gs, pb->vstart + pb->bc[b].own[k], &goff));
      for (int i = 0; i < 3; i++) R[b][i] += PetscRealPart(r[goff - rstart + i]);
    }
  }
  PetscCall(VecRestoreArrayRead(Rg, &r));
  PetscCall(DMRestoreGlobalVector(pb->dmr, &Rg));
  if (pb->nbc) PetscCall(MPIU_Allreduce(MPI_IN_PLACE, &R[0][0], 3 * pb->nbc, MPIU_REAL, MPIU_SUM, pb->comm));
  PetscFunctionReturn(0);
}

PetscErrorCode HistoryOpen(Problem *pb, FILE **fp, PetscBool append)
{
  char path[PETSC_MAX_PATH_LEN];

  PetscFunctionBeginUser;
  *fp = NULL;
  if (pb->rank) PetscFunctionReturn(0);
  PetscCall(PetscSNPrintf(path, sizeof(path), "%s/history.csv", pb->cs->output_dir));
  *fp = fopen(path, append ? "a" : "w");
  PetscCheck(*fp, PETSC_COMM_SELF, PETSC_ERR_FILE_OPEN, "cannot write '%s' (-output_dir)", path);
  if (append) PetscFunctionReturn(0);
  fprintf(*fp, "step,time,newton_its,residual_initial,residual_final");
  for (PetscInt b = 0; b < pb->nbc; b++) fprintf(*fp, ",%s_fx,%s_fy,%s_fz", pb->cs->bc[b].name, pb->cs->bc[b].name, pb->cs->bc[b].name);
  fprintf(*fp, "\n");
  fflush(*fp);
  PetscFunctionReturn(0);
}

PetscErrorCode HistoryWrite(Problem *pb, FILE *fp, PetscInt step, PetscReal time, PetscInt its, PetscReal r0, PetscReal r)
{
  PetscReal R[ATRITO_MAX_BC][3];
  char      line[64 * (3 * ATRITO_MAX_BC + 8)];
  size_t    len = 0;

  PetscFunctionBeginUser;
  PetscCall(ProblemReactions(pb, R));
  if (pb->rank) PetscFunctionReturn(0);
  /* format the whole row first, then write it at once: a killed run leaves whole rows */
  len += snprintf(line + len, sizeof(line) - len, "%" PetscInt_FMT ",%.12g,%" PetscInt_FMT ",%.6e,%.6e", step, (double)time, its, (double)r0, (double)r);
  for (PetscInt b = 0; b < pb->nbc; b++) len += snprintf(line + len, sizeof(line) - len, ",%.12e,%.12e,%.12e", (double)R[b][0], (double)R[b][1], (double)R[b][2]);
  len += snprintf(line + len, sizeof(line) - len, "\n");
  fwrite(line, 1, len, fp);
  fflush(fp);
  PetscFunctionReturn(0);
}

/* Output rows: the owned vertices and the cells, in the source mesh's order (iorows.h) */
static PetscErrorCode OutputRowsCreate(Problem *pb)
{
  PetscInt *src;

  PetscFunctionBeginUser;
  PetscCall(PetscMalloc2(pb->nv, &pb->vloc, pb->nv, &pb->vrow));
  pb->nvo = 0;
  for (PetscInt v = 0; v < pb->nv; v++) {
    pb->vrow[v] = pb->vowned[v] ? pb->nvo : -1;
    if (pb->vowned[v]) pb->vloc[pb->nvo++] = v;
  }
  PetscCall(PetscMalloc1(PetscMax(pb->nvo, pb->nc), &src));
  for (PetscInt k = 0; k < pb->nvo; k++) src[k] = pb->node_src[pb->vloc[k]];
  PetscCall(IORowsCreate(pb->comm, pb->nvo, src, &pb->rv));
  PetscCall(IORowsCreate(pb->comm, pb->nc, pb->elem_src, &pb->rc));
  PetscCall(PetscFree(src));
  PetscCheck(pb->rv.N == pb->nv_global && pb->rc.N == pb->ne_global, pb->comm, PETSC_ERR_PLIB, "output rows: %" PetscInt_FMT " vertices and %" PetscInt_FMT " cells owned, the mesh has %" PetscInt_FMT " and %" PetscInt_FMT, pb->rv.N, pb->rc.N, pb->nv_global, pb->ne_global);
  PetscFunctionReturn(0);
}

/* owned-item values (real or integer-valued) to this rank's block of rows */
static PetscErrorCode ToBlockInt(IORows *r, PetscInt ncomp, const PetscReal *own, PetscInt *blk)
{
  PetscReal *b;

  PetscFunctionBeginUser;
  PetscCall(PetscMalloc1(r->nb * ncomp + 1, &b));
  PetscCall(IORowsToBlock(r, ncomp, own, b));
  for (PetscInt i = 0; i < r->nb * ncomp; i++) blk[i] = (PetscInt)llround(b[i]);
  PetscCall(PetscFree(b));
  PetscFunctionReturn(0);
}

static PetscErrorCode WriteMesh(Problem *pb, OutputFields of)
{
  PetscReal *X, *Xb, *ids, *conn;
  PetscInt  *nidb, *eidb, *connb;

  PetscFunctionBeginUser;
  PetscCall(PetscMalloc4(3 * pb->nvo + 1, &X, 3 * pb->rv.nb + 1, &Xb, PetscMax(pb->nvo, pb->nc) + 1, &ids, 8 * pb->nc + 1, &conn));
  PetscCall(PetscMalloc3(pb->rv.nb + 1, &nidb, pb->rc.nb + 1, &eidb, 8 * pb->rc.nb + 1, &connb));
  for (PetscInt k = 0; k < pb->nvo; k++) {
    for (int i = 0; i < 3; i++) X[3 * k + i] = pb->X[3 * pb->vloc[k] + i];
    ids[k] = pb->node_id[pb->vloc[k]];
  }
  PetscCall(IORowsToBlock(&pb->rv, 3, X, Xb));
  PetscCall(ToBlockInt(&pb->rv, 1, ids, nidb));
  for (PetscInt c = 0; c < pb->nc; c++) ids[c] = pb->elem_id[c];
  PetscCall(ToBlockInt(&pb->rc, 1, ids, eidb));
  for (PetscInt k = 0; k < 8 * pb->nc; k++) conn[k] = pb->node_src[pb->cv[k]];
  PetscCall(ToBlockInt(&pb->rc, 8, conn, connb));
  PetscCall(OutputFieldsWriteMesh(of, pb->rv.nb, pb->rv.off, pb->nv_global, Xb, nidb, pb->rc.nb, pb->rc.off, pb->ne_global, connb, eidb));
  PetscCall(PetscFree4(X, Xb, ids, conn));
  PetscCall(PetscFree3(nidb, eidb, connb));
  PetscFunctionReturn(0);
}

/* a field on the owned vertices (ncomp values each) or the cells, to the rank's block */
static PetscErrorCode AddField(IORows *r, const char *name, PetscInt ncomp, const PetscReal *own, OutputField *f, PetscReal **store)
{
  PetscFunctionBeginUser;
  PetscCall(PetscMalloc1(r->nb * ncomp + 1, store));
  PetscCall(IORowsToBlock(r, ncomp, own, *store));
  f->name  = name;
  f->ncomp = ncomp;
  f->data  = *store;
  PetscFunctionReturn(0);
}

static PetscErrorCode WriteFields(Problem *pb, OutputFields of, PetscInt step, PetscReal time)
{
  PetscReal         *disp, *ep, *mises, *thick, *store[12];
  const PetscScalar *u;
  OutputField        nf[6], cf[3];
  PetscInt           nn = 0, ncf = 0, ns = 0;

  PetscFunctionBeginUser;
  PetscCall(PetscMalloc4(3 * pb->nvo + 1, &disp, pb->nc + 1, &ep, pb->nc + 1, &mises, pb->nc + 1, &thick));
  /* Uloc holds the converged displacements with the boundary values (set by the last assembly) */
  PetscCall(VecGetArrayRead(pb->Uloc, &u));
  for (PetscInt k = 0; k < pb->nvo; k++)
    for (int i = 0; i < 3; i++) disp[3 * k + i] = PetscRealPart(u[pb->vloff[pb->vloc[k]] + i]);
  PetscCall(VecRestoreArrayRead(pb->Uloc, &u));
  for (PetscInt c = 0; c < pb->nc; c++) {
    ep[c]    = pb->einfo[c].ep;
    mises[c] = pb->einfo[c].mises;
    thick[c] = 0;
    if (pb->cs->thickness_output) {
      /* thickness strain ln(h/h0) = -ln |F^-T N| at the centroid, N the reference normal */
      double        Fi[9], v[3];
      const double *N = pb->cs->thickness_dir;
      t3_inv(pb->einfo[c].F0, Fi);
      for (int i = 0; i < 3; i++) v[i] = Fi[i] * N[0] + Fi[3 + i] * N[1] + Fi[6 + i] * N[2];
      thick[c] = -log(sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]));
    }
  }
  PetscCall(AddField(&pb->rv, "displacement", 3, disp, &nf[nn++], &store[ns++]));
  PetscCall(AddField(&pb->rc, "plastic_strain", 1, ep, &cf[ncf++], &store[ns++]));
  PetscCall(AddField(&pb->rc, "von_mises", 1, mises, &cf[ncf++], &store[ns++]));
  if (pb->cs->thickness_output) PetscCall(AddField(&pb->rc, "thickness_strain", 1, thick, &cf[ncf++], &store[ns++]));
  if (pb->ntools) {
    /* contact node fields: gap, normal force, tangential (friction) force, status, accumulated slip */
    PetscReal *cg, *cn, *ct, *cst, *csl;
    PetscCall(PetscCalloc5(pb->nvo + 1, &cg, pb->nvo + 1, &cn, 3 * pb->nvo + 1, &ct, pb->nvo + 1, &cst, pb->nvo + 1, &csl));
    for (PetscInt k = 0; k < pb->nvo; k++) cg[k] = pb->search;
    for (PetscInt i = 0; i < pb->ns; i++) {
      const ContactState *st = &pb->cst_c[i];
      const PetscInt      r  = pb->vrow[pb->slave[i]];
      cg[r]                  = PetscIsInfReal(st->gap) ? pb->search : st->gap;
      cn[r]                  = st->tN;
      cst[r]                 = st->status;
      csl[r]                 = st->slip;
      for (int k = 0; k < 3; k++) ct[3 * r + k] = st->fT[k];
    }
    PetscCall(AddField(&pb->rv, "contact_gap", 1, cg, &nf[nn++], &store[ns++]));
    PetscCall(AddField(&pb->rv, "contact_normal_force", 1, cn, &nf[nn++], &store[ns++]));
    PetscCall(AddField(&pb->rv, "contact_tangential_force", 3, ct, &nf[nn++], &store[ns++]));
    PetscCall(AddField(&pb->rv, "contact_status", 1, cst, &nf[nn++], &store[ns++]));
    PetscCall(AddField(&pb->rv, "contact_slip", 1, csl, &nf[nn++], &store[ns++]));
    PetscCall(PetscFree5(cg, cn, ct, cst, csl));
  }
  PetscCall(OutputFieldsWriteStep(of, step, time, nn, nf, ncf, cf));
  for (PetscInt k = 0; k < ns; k++) PetscCall(PetscFree(store[k]));
  PetscCall(PetscFree4(disp, ep, mises, thick));
  PetscFunctionReturn(0);
}

PetscErrorCode ProblemSetUp(Problem *pb)
{
  PetscFunctionBeginUser;
  PetscCall(PetscLogEventRegister("AtritoResidual", DM_CLASSID, &pb->ev_residual));
  PetscCall(PetscLogEventRegister("AtritoJacobian", DM_CLASSID, &pb->ev_jacobian));
  PetscCall(PetscLogEventRegister("AtritoOutput", DM_CLASSID, &pb->ev_output));
  PetscCall(PetscMalloc2((size_t)pb->nc * HEX8_NQP * MAT_NHIST, &pb->hist_c, (size_t)pb->nc * HEX8_NQP * MAT_NHIST, &pb->hist_t));
  for (PetscInt q = 0; q < pb->nc * HEX8_NQP; q++) {
    MaterialHistoryInit(pb->hist_c + (size_t)q * MAT_NHIST);
    MaterialHistoryInit(pb->hist_t + (size_t)q * MAT_NHIST);
  }
  PetscCall(DMCreateGlobalVector(pb->dm, &pb->U));
  PetscCall(VecDuplicate(pb->U, &pb->Uc));
  PetscCall(VecDuplicate(pb->U, &pb->Uprev));
  PetscCall(DMCreateLocalVector(pb->dm, &pb->Uloc));
  PetscCall(VecDuplicate(pb->Uloc, &pb->Floc));
  PetscCall(ContactSetUp(pb));
  PetscCall(OutputRowsCreate(pb));
  PetscFunctionReturn(0);
}

/* Tangent predictor: U = Uc - J(Uc)^-1 [R(Uc, lam_c) + dR/dlam dl], the response of the committed
   state, linearised, to the increment of the prescribed displacements (the derivative along the
   load by a one-sided difference: it only seeds Newton, the Jacobian itself stays exact). */
static PetscErrorCode TangentPredictor(Problem *pb, SNES snes, Mat J, Vec R, Vec W, PetscReal lam_c, PetscReal dl, PetscBool *ok)
{
  KSP                 ksp;
  KSPConvergedReason  kr;
  const PetscReal     eps = 1e-6;

  PetscFunctionBeginUser;
  *ok = PETSC_FALSE;
  pb->lambda = lam_c;
  PetscCall(FormJacobian(snes, pb->Uc, J, J, pb));
  if (pb->ndomain_err) PetscFunctionReturn(0);
  PetscCall(FormFunction(snes, pb->Uc, W, pb));
  pb->lambda = lam_c + eps * dl;
  PetscCall(FormFunction(snes, pb->Uc, R, pb));
  if (pb->ndomain_err) PetscFunctionReturn(0);
  /* R <- W + (R - W)/eps */
  PetscCall(VecAXPBY(R, 1.0 - 1.0 / eps, 1.0 / eps, W));
  PetscCall(VecScale(R, -1.0));
  PetscCall(SNESGetKSP(snes, &ksp));
  PetscCall(KSPSetOperators(ksp, J, J));
  PetscCall(KSPSolve(ksp, R, W));
  PetscCall(KSPGetConvergedReason(ksp, &kr));
  if (kr < 0) PetscFunctionReturn(0);
  PetscCall(VecWAXPY(pb->U, 1.0, pb->Uc, W));
  *ok = PETSC_TRUE;
  PetscFunctionReturn(0);
}

/* PETSc's convergence test, and a stall test: the iteration stops as diverged when |R| has not
   fallen below stall_factor times its value stall_its iterations earlier (a step whose active set
   or stick/slip pattern keeps Newton from making progress is cut at once instead of running to the
   iteration limit) */
static PetscErrorCode NewtonConverged(SNES snes, PetscInt it, PetscReal xnorm, PetscReal snorm, PetscReal fnorm, SNESConvergedReason *reason, void *ctx)
{
  Problem       *pb = (Problem *)ctx;
  const PetscInt w  = pb->cs->stall_its;

  PetscFunctionBeginUser;
  PetscCall(SNESConvergedDefault(snes, it, xnorm, snorm, fnorm, reason, NULL));
  if (it == 0) pb->stalled = PETSC_FALSE;
  if (it < 256) pb->fnorm_hist[it] = fnorm;
  if (*reason == SNES_CONVERGED_ITERATING && w > 0 && it >= w && it < 256 && !(fnorm < pb->cs->stall_factor * pb->fnorm_hist[it - w])) {
    *reason         = SNES_DIVERGED_DTOL;
    pb->stalled     = PETSC_TRUE;
    pb->stall_fnorm = fnorm;
  }
  PetscFunctionReturn(0);
}

/* Start of every Newton iteration: the frame recurrence of eq 30 at the current iterate */
static PetscErrorCode NewtonUpdate(SNES snes, PetscInt it)
{
  Problem *pb;
  Vec      X;

  PetscFunctionBeginUser;
  PetscCall(SNESGetApplicationContext(snes, &pb));
  if (!pb->ns) PetscFunctionReturn(0);
  PetscCall(SNESGetSolution(snes, &X));
  PetscCall(DMGlobalToLocal(pb->dm, X, INSERT_VALUES, pb->Uloc));
  {
    PetscScalar *u;
    PetscCall(VecGetArray(pb->Uloc, &u));
    BoundaryValues(pb, u, pb->lambda);
    PetscCall(VecRestoreArray(pb->Uloc, &u));
  }
  PetscCall(ContactSeed(pb, pb->Uloc, pb->lambda, PETSC_FALSE));
  PetscCall(ContactRecordActive(pb));
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
  PetscReal    c[3] = {0, 0, 0}, n = pb->nvo;

  PetscFunctionBeginUser;
  for (PetscInt k = 0; k < pb->nvo; k++)
    for (int i = 0; i < 3; i++) c[i] += pb->X[3 * pb->vloc[k] + i];
  PetscCall(MPIU_Allreduce(MPI_IN_PLACE, c, 3, MPIU_REAL, MPIU_SUM, pb->comm));
  PetscCall(MPIU_Allreduce(MPI_IN_PLACE, &n, 1, MPIU_REAL, MPIU_SUM, pb->comm));
  for (int i = 0; i < 3; i++) c[i] /= PetscMax(n, 1);
  for (int m = 0; m < 6; m++) {
    PetscScalar *a;
    PetscCall(DMCreateGlobalVector(pb->dm, &modes[m]));
    PetscCall(VecGetOwnershipRange(modes[m], &rstart, NULL));
    PetscCall(VecGetArray(modes[m], &a));
    for (PetscInt k = 0; k < pb->nvo; k++) {
      const PetscReal *X = pb->X + 3 * pb->vloc[k], x[3] = {X[0] - c[0], X[1] - c[1], X[2] - c[2]};
      PetscReal        v[3] = {0, 0, 0};
      PetscInt         idx[3];
      if (m < 3) v[m] = 1;
      else { /* e_r x x for the axis r = m - 3 */
        const int r = m - 3, r1 = (r + 1) % 3, r2 = (r + 2) % 3;
        v[r1] = -x[r2];
        v[r2] = x[r1];
      }
      PetscCall(ProblemVertexDofs(pb, pb->vloc[k], idx));
      for (PetscInt d = 0; d < 3; d++)
        if (idx[d] >= 0) a[idx[d] - rstart] = v[d];
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

/* local vector of a global one with the boundary values at lambda */
static PetscErrorCode LocalWithBC(Problem *pb, Vec U, PetscReal lambda)
{
  PetscScalar *u;

  PetscFunctionBeginUser;
  PetscCall(DMGlobalToLocal(pb->dm, U, INSERT_VALUES, pb->Uloc));
  PetscCall(VecGetArray(pb->Uloc, &u));
  BoundaryValues(pb, u, lambda);
  PetscCall(VecRestoreArray(pb->Uloc, &u));
  PetscFunctionReturn(0);
}

static const char *FailureCause(Problem *pb, SNESConvergedReason reason, char *buf, size_t len)
{
  if (reason == SNES_DIVERGED_DTOL && pb->stalled)
    snprintf(buf, len, "Newton stalled (|R| %.3g did not fall below %g times its value %d iterations earlier, -newton_stall_its)", (double)pb->stall_fnorm, (double)pb->cs->stall_factor, (int)pb->cs->stall_its);
  else if (reason == SNES_DIVERGED_INNER && pb->bad_status < 0) snprintf(buf, len, "contact chattering: %d nodes still entering or leaving contact at the last Newton iteration (node id %d)", (int)-pb->bad_status, (int)pb->bad_cell_id);
  else if (reason == SNES_DIVERGED_FUNCTION_DOMAIN || reason == SNES_DIVERGED_JACOBIAN_DOMAIN || pb->ndomain_err) {
    if (pb->bad_status == MAT_ERR_RETURNMAP) snprintf(buf, len, "the local return map did not converge (element id %d)", (int)pb->bad_cell_id);
    else if (pb->bad_status == ATRITO_ERR_PROJECTION) snprintf(buf, len, "the projection of a slave node on a tool failed");
    else snprintf(buf, len, "an element inverted (element id %d)", (int)pb->bad_cell_id);
  } else if (reason == SNES_DIVERGED_FNORM_NAN) snprintf(buf, len, "NaN or Inf in the residual");
  else if (reason == SNES_DIVERGED_MAX_IT) snprintf(buf, len, "Newton did not converge in the allowed iterations");
  else snprintf(buf, len, "Newton diverged (%s)", SNESConvergedReasons[reason]);
  return buf;
}

PetscErrorCode ProblemSolve(Problem *pb)
{
  const Case  *cs = pb->cs;
  SNES         snes;
  KSP          ksp;
  PC           pc;
  Mat          J;
  Vec          R, W;
  FILE        *hist = NULL, *chist = NULL;
  OutputFields of   = NULL;
  PetscReal    lam_c = 0, dl = cs->load_dt0, dl_prev = 0, rhist[256];
  PetscInt     itshist[256], step = 0, total_its = 0, total_cuts = 0;
  CheckpointInfo ci;
  PetscLogDouble t0, t1;

  PetscFunctionBeginUser;
  PetscCall(PetscTime(&t0));
  PetscCall(OutputEnsureDirectory(pb->comm, cs->output_dir));
  if (cs->restart[0]) {
    /* continue: the committed state of the checkpoint; the histories and fields keep what was
       written up to its step and go on from there */
    PetscBool hexist, cexist, fexist;
    PetscCall(CheckpointRead(pb, cs->restart, &ci));
    step       = ci.step;
    lam_c      = ci.lambda;
    dl         = ci.dl;
    dl_prev    = ci.dl_prev;
    total_its  = ci.total_its;
    total_cuts = ci.total_cuts;
    PetscCall(HistoryTruncate(pb, "history.csv", step, &hexist));
    PetscCall(HistoryTruncate(pb, "contact.csv", step, &cexist));
    PetscCall(HistoryOpen(pb, &hist, hexist));
    PetscCall(ContactHistoryOpen(pb, &chist, cexist));
    if (cs->output_interval > 0) {
      char h5[PETSC_MAX_PATH_LEN];
      int  ex = 0;
      PetscCall(PetscSNPrintf(h5, sizeof(h5), "%s/fields.h5", cs->output_dir));
      if (!pb->rank) {
        FILE *fp = fopen(h5, "r");
        ex       = fp != NULL;
        if (fp) fclose(fp);
      }
      PetscCallMPI(MPI_Bcast(&ex, 1, MPI_INT, 0, pb->comm));
      fexist = ex ? PETSC_TRUE : PETSC_FALSE;
      if (fexist) PetscCall(OutputFieldsReopen(pb->comm, cs->output_dir, step, pb->rv.nb, pb->rv.off, pb->rc.nb, pb->rc.off, &of));
      else {
        PetscCall(OutputFieldsCreate(pb->comm, cs->output_dir, &of));
        PetscCall(WriteMesh(pb, of));
      }
    }
    PetscCall(PetscPrintf(pb->comm, "restart from %s: step %" PetscInt_FMT ", load %.6g\n", cs->restart, step, (double)lam_c));
  } else {
    PetscCall(HistoryOpen(pb, &hist, PETSC_FALSE));
    PetscCall(ContactHistoryOpen(pb, &chist, PETSC_FALSE));
    if (cs->output_interval > 0) {
      PetscCall(OutputFieldsCreate(pb->comm, cs->output_dir, &of));
      PetscCall(WriteMesh(pb, of));
    }
  }

  PetscCall(DMCreateMatrix(pb->dm, &J));
  PetscCall(SetNearNullSpace(pb, J));
  PetscCall(MatSetOption(J, MAT_NEW_NONZERO_ALLOCATION_ERR, PETSC_TRUE));
  if (cs->assembly_coo) {
    /* coordinate assembly: the element blocks' (i, j) once; each Jacobian then only fills values */
    PetscCount ncoo = 0;
    PetscInt  *ci, *cj;
    PetscCall(PetscMalloc1(pb->nc + 1, &pb->coo_off));
    for (PetscInt e = 0; e < pb->nc; e++) {
      pb->coo_off[e] = ncoo;
      ncoo += pb->cndof[e] * pb->cndof[e];
    }
    pb->coo_off[pb->nc] = ncoo;
    for (PetscInt i = 0; i < pb->ns; i++)
      for (int r = 0; r < 3; r++)
        for (int c = 0; c < 3; c++) ncoo += (pb->sgdof[3 * i + r] >= 0 && pb->sgdof[3 * i + c] >= 0);
    PetscCall(PetscMalloc2(ncoo, &ci, ncoo, &cj));
    for (PetscInt e = 0; e < pb->nc; e++) {
      const PetscInt n = pb->cndof[e], *g = pb->cgdof + 24 * e;
      for (PetscInt r = 0; r < n; r++)
        for (PetscInt c = 0; c < n; c++) {
          ci[pb->coo_off[e] + r * n + c] = g[r];
          cj[pb->coo_off[e] + r * n + c] = g[c];
        }
    }
    {
      PetscCount m = pb->coo_off[pb->nc];
      for (PetscInt i = 0; i < pb->ns; i++)
        for (int r = 0; r < 3; r++)
          for (int c = 0; c < 3; c++)
            if (pb->sgdof[3 * i + r] >= 0 && pb->sgdof[3 * i + c] >= 0) {
              ci[m]   = pb->sgdof[3 * i + r];
              cj[m++] = pb->sgdof[3 * i + c];
            }
    }
    PetscCall(MatSetPreallocationCOO(J, ncoo, ci, cj));
    PetscCall(PetscFree2(ci, cj));
    PetscCall(PetscCalloc1(ncoo, &pb->coo_v));
  }
  PetscCall(VecDuplicate(pb->U, &R));
  PetscCall(VecDuplicate(pb->U, &W));
  PetscCall(SNESCreate(pb->comm, &snes));
  PetscCall(SNESSetFunction(snes, R, FormFunction, pb));
  PetscCall(SNESSetJacobian(snes, J, J, FormJacobian, pb));
  PetscCall(SNESSetTolerances(snes, 1e-10, 1e-9, 1e-12, 25, -1));
  PetscCall(SNESGetKSP(snes, &ksp));
  PetscCall(KSPSetType(ksp, KSPPREONLY));
  PetscCall(KSPGetPC(ksp, &pc));
  PetscCall(PCSetType(pc, PCLU));
  PetscCall(PCFactorSetMatSolverType(pc, MATSOLVERMUMPS));
  {
    /* MUMPS without its automatic scaling unless asked for: the unknowns are all displacements and
       the penalties are of the order of the element stiffness, and the factorisation is about 10 %
       faster (doc/design.md) */
    PetscBool set;
    PetscCall(PetscOptionsHasName(NULL, NULL, "-mat_mumps_icntl_8", &set));
    if (!set) PetscCall(PetscOptionsSetValue(NULL, "-mat_mumps_icntl_8", "0"));
  }
  PetscCall(SNESSetConvergenceHistory(snes, rhist, itshist, 256, PETSC_TRUE));
  PetscCall(SNESSetApplicationContext(snes, pb));
  PetscCall(SNESSetUpdate(snes, NewtonUpdate));
  PetscCall(SNESSetConvergenceTest(snes, NewtonConverged, pb, NULL));
  PetscCall(SNESSetFromOptions(snes));
  if (cs->lu_ordering == LU_ORDERING_ND) {
    /* LU by MUMPS, unless the options chose another preconditioner or package: MUMPS called
       directly with a METIS nested-dissection ordering (fewer flops than PORD, and balanced
       subtrees for the ranks; doc/design.md) */
    PetscBool     islu;
    MatSolverType st;
    PetscCall(PetscObjectTypeCompare((PetscObject)pc, PCLU, &islu));
    if (islu) {
      PetscCall(PCFactorGetMatSolverType(pc, &st));
      if (st && !strcmp(st, MATSOLVERMUMPS)) PetscCall(PCSetLUND(pc));
    }
  }

  /* the initial state */
  if (!cs->restart[0]) {
    PetscCall(VecZeroEntries(pb->U));
    PetscCall(VecZeroEntries(pb->Uc));
    PetscCall(VecZeroEntries(pb->Uprev));
    PetscCall(ProblemResidualLocal(pb, pb->U, 0.0));
    if (of) PetscCall(WriteFields(pb, of, 0, 0.0));
  } else PetscCall(VecCopy(pb->Uc, pb->U));

  while (lam_c < 1.0 - 1e-12) {
    SNESConvergedReason reason;
    PetscInt            its = 0, cuts = 0, nres;
    PetscReal           lam_t;

    PetscCheck(step < cs->load_max_steps, pb->comm, PETSC_ERR_NOT_CONVERGED, "-load_max_steps %" PetscInt_FMT " reached at load %g", cs->load_max_steps, (double)lam_c);
    for (;;) {
      dl    = PetscMin(dl, 1.0 - lam_c);
      lam_t = (1.0 - lam_c - dl < 1e-12) ? 1.0 : lam_c + dl; /* the last step ends exactly at 1 */
      pb->lambda = lam_t;
      PetscCall(VecCopy(pb->Uc, pb->U));
      /* a fresh factorisation for every step, so that a step depends only on the committed state:
         a run restarted from a checkpoint repeats the same iterations (PETSc's MUMPS interface:
         analysis and scaling again; -lu_ordering nd keeps its analysis, a function of the
         nonzero pattern alone) */
      PetscCall(PCReset(pc));
      /* frame seeds from the committed state (a retry starts again from the committed frames) */
      PetscCall(LocalWithBC(pb, pb->Uc, lam_c));
      PetscCall(ContactSeed(pb, pb->Uloc, lam_c, PETSC_TRUE));
      const PetscBool extrapolate = (cs->load_predictor == PREDICTOR_EXTRAPOLATE || cs->load_predictor == PREDICTOR_AUTO) && dl_prev > 0;
      if (cs->load_predictor == PREDICTOR_TANGENT || (cs->load_predictor == PREDICTOR_AUTO && !extrapolate)) {
        PetscBool ok;
        PetscCall(TangentPredictor(pb, snes, J, R, W, lam_c, dl, &ok));
        if (!ok) PetscCall(VecCopy(pb->Uc, pb->U));
      } else if (extrapolate) PetscCall(VecAXPBYPCZ(pb->U, -dl / dl_prev, dl / dl_prev, 1.0, pb->Uprev, pb->Uc));
      pb->lambda     = lam_t;
      pb->bad_status = 0;
      PetscCall(LocalWithBC(pb, pb->U, lam_t));
      PetscCall(ContactSeed(pb, pb->Uloc, lam_t, PETSC_TRUE));
      PetscCall(SNESSolve(snes, NULL, pb->U));
      PetscCall(SNESGetConvergedReason(snes, &reason));
      PetscCall(SNESGetIterationNumber(snes, &its));
      /* converged: one more evaluation at the solution (trial states, cell info, reactions) */
      if (reason > 0) PetscCall(ProblemResidualLocal(pb, pb->U, lam_t));
      if (reason > 0 && pb->ntools && cs->chatter_check && its > 0) {
        /* the active set must have settled: a node entering or leaving contact with a
           significant force in the last iteration means the step is not converged */
        PetscInt nch, nodeid;
        PetscCall(ContactChatter(pb, &nch, &nodeid));
        if (nch) {
          reason         = SNES_DIVERGED_INNER; /* reported below as chattering */
          pb->bad_status = -nch;
          pb->bad_cell_id = nodeid;
        }
      }
      if (reason > 0) break;
      {
        char buf[256];
        FailureCause(pb, reason, buf, sizeof(buf));
        cuts++;
        total_cuts++;
        PetscCheck(cuts <= cs->load_max_cuts && dl * cs->load_cut >= cs->load_dt_min, pb->comm, PETSC_ERR_NOT_CONVERGED,
                   "step %" PetscInt_FMT " failed at load %.6g (increment %.3g) after %" PetscInt_FMT " cuts: %s; the results up to load %.6g are complete in %s",
                   step + 1, (double)lam_t, (double)dl, cuts - 1, buf, (double)lam_c, cs->output_dir);
        PetscCall(PetscPrintf(pb->comm, "step %" PetscInt_FMT " at load %.6g: %s; retrying with increment %.3g\n", step + 1, (double)lam_t, buf, (double)(dl * cs->load_cut)));
        dl *= cs->load_cut;
      }
    }
    /* commit the trial states of that evaluation */
    PetscCheck(!pb->ndomain_err, pb->comm, PETSC_ERR_PLIB, "element evaluation failed at a converged state");
    PetscCall(PetscArraycpy(pb->hist_c, pb->hist_t, (size_t)pb->nc * HEX8_NQP * MAT_NHIST));
    PetscCall(ContactCommit(pb));
    pb->lambda_c = lam_t;
    PetscCall(VecCopy(pb->Uc, pb->Uprev));
    PetscCall(VecCopy(pb->U, pb->Uc));
    dl_prev = dl;
    lam_c   = lam_t;
    step++;
    total_its += its;
    PetscCall(SNESGetConvergenceHistory(snes, NULL, NULL, &nres));
    PetscCall(HistoryWrite(pb, hist, step, lam_c, its, rhist[0], rhist[PetscMax(nres - 1, 0)]));
    PetscCall(ContactHistoryWrite(pb, chist, step, lam_c, its));
    PetscCall(PetscTime(&t1));
    PetscCall(PetscPrintf(pb->comm, "step %4" PetscInt_FMT "  time %.6f  its %2" PetscInt_FMT "  |R| %.3e  elapsed %.2f s\n", step, (double)lam_c, its, (double)rhist[PetscMax(nres - 1, 0)], t1 - t0));
    if (of && (step % cs->output_interval == 0 || lam_c >= 1.0 - 1e-12)) PetscCall(WriteFields(pb, of, step, lam_c));
    if (its <= cs->load_grow_its) dl = PetscMin(dl * cs->load_grow, cs->load_dt_max);
    if (cs->checkpoint_interval > 0 && (step % cs->checkpoint_interval == 0 || lam_c >= 1.0 - 1e-12)) {
      ci.step       = step;
      ci.lambda     = lam_c;
      ci.dl         = dl;
      ci.dl_prev    = dl_prev;
      ci.total_its  = total_its;
      ci.total_cuts = total_cuts;
      PetscCall(CheckpointWrite(pb, &ci));
    }
  }
  PetscCall(PetscTime(&t1));
  PetscCall(PetscPrintf(pb->comm, "done: %" PetscInt_FMT " steps, %" PetscInt_FMT " Newton iterations, %" PetscInt_FMT " cuts, %.2f s\n", step, total_its, total_cuts, t1 - t0));

  if (hist) fclose(hist);
  if (chist) fclose(chist);
  PetscCall(OutputFieldsDestroy(&of));
  PetscCall(SNESDestroy(&snes));
  PetscCall(MatDestroy(&J));
  PetscCall(VecDestroy(&R));
  PetscCall(VecDestroy(&W));
  PetscCall(PetscFree(pb->coo_off));
  PetscCall(PetscFree(pb->coo_v));
  PetscFunctionReturn(0);
}

PetscErrorCode ProblemDestroy(Problem *pb)
{
  PetscFunctionBeginUser;
  PetscCall(VecDestroy(&pb->U));
  PetscCall(VecDestroy(&pb->Uc));
  PetscCall(VecDestroy(&pb->Uprev));
  PetscCall(VecDestroy(&pb->Uloc));
  PetscCall(VecDestroy(&pb->Floc));
  PetscCall(PetscFree2(pb->hist_c, pb->hist_t));
  PetscCall(ContactDestroy(pb));
  PetscCall(IORowsDestroy(&pb->rv));
  PetscCall(IORowsDestroy(&pb->rc));
  PetscCall(PetscFree2(pb->vloc, pb->vrow));
  PetscCall(ProblemDestroyMesh(pb));
  PetscFunctionReturn(0);
}
