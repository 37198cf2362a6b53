/* Contact at the problem level: the slave nodes (owned vertices of a labelled set), pairing with
   the rigid tools (replicated on every rank, bounding-box prefilter), the per-node committed and
   trial states, the seeds of the frame recurrence, the assembly of the nodal forces and their
   tangents, and the per-tool history. Each rank handles only the slave vertices it owns, so no
   contact force is counted twice. */
#include <math.h>
#include <string.h>
#include "atrito.h"

/* The tool whose closest point to y has the smallest gap (bounding boxes first). Returns the tool
   index or -1 when no tool is within the search distance. */
static PetscInt Pair(const Problem *pb, const double y[3], PetscReal lambda, Projection *best)
{
  PetscInt tbest = -1;
  for (PetscInt t = 0; t < pb->ntools; t++) {
    const Tool *tl = &pb->tools[t];
    double      sh[3], d2 = 0;
    Projection  pr;
    ToolShift(tl, lambda, sh);
    for (int k = 0; k < 3; k++) {
      const double lo = tl->bbox[2 * k] + sh[k], hi = tl->bbox[2 * k + 1] + sh[k];
      const double e  = y[k] < lo ? lo - y[k] : (y[k] > hi ? y[k] - hi : 0);
      d2 += e * e;
    }
    if (d2 > pb->search * pb->search) continue;
    if (ToolProject(tl, sh, y, pb->search, &pr)) continue;
    if (tbest < 0 || pr.gap < best->gap) {
      *best = pr;
      tbest = t;
    }
  }
  return tbest;
}

/* Pair for slave node i, through its memo (the same y and lambda give the same result) */
static PetscInt PairNode(const Problem *pb, PetscInt i, const double y[3], PetscReal lambda, Projection *pr)
{
  PairMemo *m = &pb->pmemo[i];
  if (m->tool != -2 && m->lambda == lambda && m->y[0] == y[0] && m->y[1] == y[1] && m->y[2] == y[2]) {
    if (m->tool >= 0) *pr = m->pr;
    return m->tool;
  }
  m->tool = Pair(pb, y, lambda, &m->pr);
  for (int k = 0; k < 3; k++) m->y[k] = y[k];
  m->lambda = lambda;
  if (m->tool >= 0) *pr = m->pr;
  return m->tool;
}

/* chord of eq 28: from the projection to the point at (xi + 0.01, eta) of the same patch */
static void Chord(const Problem *pb, PetscInt tool, const Projection *pr, double chord[3])
{
  const Patch *p = &pb->tools[tool].patch[pr->patch];
  double       x0[3], x1[3], xu[3], xv[3];
  PatchEval(p, pr->xi, pr->eta, x0, xu, xv, NULL, NULL, NULL);
  PatchEval(p, pr->xi + 0.01, pr->eta, x1, xu, xv, NULL, NULL, NULL);
  for (int k = 0; k < 3; k++) chord[k] = x1[k] - x0[k];
}

static void NodePosition(const Problem *pb, PetscInt i, const PetscScalar *u, double y[3])
{
  const PetscInt v = pb->slave[i];
  for (int k = 0; k < 3; k++) y[k] = pb->X[3 * v + k] + PetscRealPart(u[pb->vloff[v] + k]);
}

PetscErrorCode ContactSetUp(Problem *pb)
{
  const Case  *cs = pb->cs;
  PetscBool   *mark, found;

  PetscFunctionBeginUser;
  PetscCall(PetscLogEventRegister("AtritoContact", DM_CLASSID, &pb->ev_contact));
  PetscCall(PetscLogEventRegister("AtritoPairing", DM_CLASSID, &pb->ev_pairing));
  PetscCall(ToolsCreateFromOptions(pb->comm, &pb->ntools, &pb->tools));
  pb->ns = 0;
  if (!pb->ntools) PetscFunctionReturn(0);
  pb->search = cs->contact_search;
  if (pb->search <= 0) { /* default: 5 % of the largest tool's box diagonal */
    for (PetscInt t = 0; t < pb->ntools; t++) {
      const double *b = pb->tools[t].bbox;
      pb->search      = PetscMax(pb->search, 0.05 * PetscSqrtReal(PetscSqr(b[1] - b[0]) + PetscSqr(b[3] - b[2]) + PetscSqr(b[5] - b[4])));
    }
  }

  PetscCall(PetscCalloc1(pb->nv, &mark));
  for (PetscInt s = 0; s < cs->ncontact_set; s++) {
    PetscCall(ProblemMarkSetVertices(pb, cs->contact_set[s], mark, &found));
    PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, &found, 1, MPIU_BOOL, MPI_LOR, pb->comm));
    PetscCheck(found, pb->comm, PETSC_ERR_USER_INPUT, "-contact_set: the mesh has no set named '%s'", cs->contact_set[s]);
  }
  for (PetscInt v = 0; v < pb->nv; v++)
    if (mark[v] && pb->vowned[v]) pb->ns++;
  PetscCall(PetscMalloc4(pb->ns, &pb->slave, 3 * pb->ns, &pb->sgdof, 3 * pb->ns, &pb->seed, pb->ns, &pb->has_seed));
  PetscCall(PetscCalloc1(pb->ns, &pb->active_prev));
  PetscCall(PetscMalloc1(pb->ns, &pb->pmemo));
  PetscCall(PetscCalloc2(pb->ns, &pb->cst_c, pb->ns, &pb->cst_t));
  pb->ns = 0;
  for (PetscInt v = 0; v < pb->nv; v++) {
    if (!(mark[v] && pb->vowned[v])) continue;
    const PetscInt i = pb->ns++;
    pb->slave[i]     = v;
    PetscCall(ProblemVertexDofs(pb, v, pb->sgdof + 3 * i));
    pb->has_seed[i] = PETSC_FALSE;
    for (int k = 0; k < 3; k++) pb->cst_c[i].y[k] = pb->X[3 * v + k];
    pb->cst_c[i].tool = pb->cst_c[i].patch = -1;
    pb->cst_c[i].gap                       = PETSC_INFINITY;
    pb->cst_t[i]                           = pb->cst_c[i];
    pb->pmemo[i].tool                      = -2;
  }
  PetscCall(PetscFree(mark));
  if (cs->contact_per_area) { /* the tributary areas come with the mesh (pb->varea) */
    PetscReal amin = PETSC_MAX_REAL, amax = 0, asum = 0;
    PetscInt  nzero = 0;
    for (PetscInt i = 0; i < pb->ns; i++) {
      const PetscReal A = pb->varea[pb->slave[i]];
      if (!(A > 0)) nzero++;
      amin = PetscMin(amin, A);
      amax = PetscMax(amax, A);
      asum += A;
    }
    PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, &nzero, 1, MPIU_INT, MPI_SUM, pb->comm));
    PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, &amin, 1, MPIU_REAL, MPI_MIN, pb->comm));
    PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, &amax, 1, MPIU_REAL, MPI_MAX, pb->comm));
    PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, &asum, 1, MPIU_REAL, MPI_SUM, pb->comm));
    PetscCheck(!nzero, pb->comm, PETSC_ERR_USER_INPUT, "-contact_penalty_per_area: %" PetscInt_FMT " slave nodes of -contact_set '%s'%s lie on no boundary face whose four vertices are all in one of the sets, so they have no tributary area", nzero, cs->contact_set[0], cs->ncontact_set > 1 ? ", ..." : "");
    PetscCall(PetscPrintf(pb->comm, "contact: penalties per unit area; tributary areas of the slave nodes: total %.10g, smallest %g, largest %g\n", (double)asum, (double)amin, (double)amax));
  }
  {
    PetscInt n = pb->ns;
    PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, &n, 1, MPIU_INT, MPI_SUM, pb->comm));
    PetscCall(PetscPrintf(pb->comm, "contact: %" PetscInt_FMT " slave nodes (set '%s'%s), %" PetscInt_FMT " tools, K_N %g, K_T %g, mu %g, %s tangent\n", n, cs->contact_set[0], cs->ncontact_set > 1 ? ", ..." : "", pb->ntools, (double)cs->law.KN, (double)cs->law.KT, (double)cs->law.mu, cs->contact_fd ? "finite-difference" : "analytic"));
    PetscCheck(n > 0, pb->comm, PETSC_ERR_USER_INPUT, "-contact_set '%s' holds no vertex", cs->contact_set[0]);
  }
  PetscFunctionReturn(0);
}

PetscErrorCode ContactDestroy(Problem *pb)
{
  PetscFunctionBeginUser;
  if (pb->ntools) {
    PetscCall(PetscFree4(pb->slave, pb->sgdof, pb->seed, pb->has_seed));
    PetscCall(PetscFree(pb->active_prev));
    PetscCall(PetscFree(pb->pmemo));
    PetscCall(PetscFree2(pb->cst_c, pb->cst_t));
  }
  PetscCall(ToolsDestroy(pb->ntools, &pb->tools));
  PetscFunctionReturn(0);
}

PetscErrorCode ContactSeed(Problem *pb, Vec Uloc, PetscReal lambda, PetscBool from_committed)
{
  const PetscScalar *u;

  PetscFunctionBeginUser;
  if (!pb->ns) PetscFunctionReturn(0);
  PetscCall(PetscLogEventBegin(pb->ev_pairing, 0, 0, 0, 0));
  PetscCall(VecGetArrayRead(Uloc, &u));
  for (PetscInt i = 0; i < pb->ns; i++) {
    double     y[3], t2[3], t1[3];
    Projection pr;
    PetscInt   tool;
    if (from_committed) {
      /* step start or retry: the committed frame of a node in contact */
      pb->has_seed[i] = (pb->cst_c[i].has_frame && pb->cst_c[i].status != CONTACT_OPEN) ? PETSC_TRUE : PETSC_FALSE;
      if (pb->has_seed[i])
        for (int k = 0; k < 3; k++) pb->seed[3 * i + k] = pb->cst_c[i].t1[k];
    }
    NodePosition(pb, i, u, y);
    tool = PairNode(pb, i, y, lambda, &pr);
    if (tool < 0) {
      pb->has_seed[i] = PETSC_FALSE;
      continue;
    }
    if (!from_committed) {
      /* start of a Newton iteration: eq 30, t2 = n x t1(previous iteration), t1 = t2 x n, for the
         nodes in contact; a node out of contact forgets its frame */
      if (pr.gap <= 0 && pb->has_seed[i] && !ContactFrame(pr.n, pb->seed + 3 * i, t1, t2))
        for (int k = 0; k < 3; k++) pb->seed[3 * i + k] = t1[k];
      else if (pr.gap > 0) pb->has_seed[i] = PETSC_FALSE;
    }
    if (!pb->has_seed[i]) { /* first contact: the chord of eq 28 */
      Chord(pb, tool, &pr, pb->seed + 3 * i);
      pb->has_seed[i] = PETSC_TRUE;
    }
  }
  PetscCall(VecRestoreArrayRead(Uloc, &u));
  PetscCall(PetscLogEventEnd(pb->ev_pairing, 0, 0, 0, 0));
  PetscFunctionReturn(0);
}

/* Contribution of slave node i at position y: residual R, tangent K (if asked), trial state */
static int NodeEval(Problem *pb, PetscInt i, const double y[3], PetscReal lambda, double R[3], double *K, ContactState *st)
{
  const ContactState *cc = &pb->cst_c[i];
  Projection          pr;
  double              sh[3], shc[3], ds[3], tTn[2] = {0, 0}, dn[9], *dnp = NULL;
  PetscInt            tool;
  ContactLaw          law = pb->cs->law;

  memset(R, 0, 3 * sizeof(double));
  if (K) memset(K, 0, 9 * sizeof(double));
  *st = *cc;
  for (int k = 0; k < 3; k++) {
    st->y[k]  = y[k];
    st->f[k]  = 0;
    st->fT[k] = 0;
  }
  st->tT[0] = st->tT[1] = 0;
  st->tN                = 0;
  st->status            = CONTACT_OPEN;
  st->has_frame         = PETSC_FALSE;
  tool                  = PairNode(pb, i, y, lambda, &pr);
  st->tool              = tool;
  st->gap               = tool < 0 ? PETSC_INFINITY : pr.gap;
  if (tool < 0) return 0;
  st->patch = pr.patch;
  st->xi    = pr.xi;
  st->eta   = pr.eta;
  if (pr.gap > 0) return 0;

  const Tool *tl = &pb->tools[tool];
  ToolShift(tl, lambda, sh);
  ToolShift(tl, pb->lambda_c, shc);
  /* slip increment: the node's displacement relative to the tool over the step */
  for (int k = 0; k < 3; k++) ds[k] = (y[k] - cc->y[k]) - (sh[k] - shc[k]);
  if (cc->status != CONTACT_OPEN && cc->tool == tool) {
    tTn[0] = cc->tT[0];
    tTn[1] = cc->tT[1];
  }
  if (K && !pb->cs->contact_fd) {
    if (PatchNormalDerivative(&tl->patch[pr.patch], sh, y, &pr, dn)) {
      /* no closed form (Coons patch): the derivative of the normal by central differences */
      const double h = 1e-6 * (1.0 + fabs(y[0]) + fabs(y[1]) + fabs(y[2]));
      for (int j = 0; j < 3; j++) {
        double     yp[3] = {y[0], y[1], y[2]}, ym[3] = {y[0], y[1], y[2]};
        Projection pp, pm;
        yp[j] += h;
        ym[j] -= h;
        if (ToolProject(tl, sh, yp, pb->search, &pp) || ToolProject(tl, sh, ym, pb->search, &pm)) return 1;
        for (int k = 0; k < 3; k++) dn[3 * k + j] = (pp.n[k] - pm.n[k]) / (2 * h);
      }
    }
    dnp = dn;
  }
  if (pb->varea) { /* penalties per unit area times the node's tributary area */
    law.KN *= pb->varea[pb->slave[i]];
    law.KT *= pb->varea[pb->slave[i]];
  }
  st->status    = ContactNodeEval(&law, pr.gap, pr.n, dnp, pb->seed + 3 * i, tTn, ds, R, pb->cs->contact_fd ? NULL : K, st->t1, &st->tN, st->tT);
  st->has_frame = PETSC_TRUE;
  for (int k = 0; k < 3; k++) {
    st->f[k]  = -R[k];
    st->fT[k] = st->f[k] - st->tN * pr.n[k];
  }
  {
    const double dsn = ds[0] * pr.n[0] + ds[1] * pr.n[1] + ds[2] * pr.n[2];
    double       dt2 = 0;
    for (int k = 0; k < 3; k++) dt2 += (ds[k] - dsn * pr.n[k]) * (ds[k] - dsn * pr.n[k]);
    st->slip = cc->slip + sqrt(dt2);
  }
  if (K && pb->cs->contact_fd) {
    /* per-node 3x3 finite-difference tangent: the contact block of a node depends on that node only */
    const double h = 1e-7 * (1.0 + fabs(y[0]) + fabs(y[1]) + fabs(y[2]));
    for (int j = 0; j < 3; j++) {
      double       yp[3] = {y[0], y[1], y[2]}, ym[3] = {y[0], y[1], y[2]}, Rp[3], Rm[3];
      ContactState sp;
      yp[j] += h;
      ym[j] -= h;
      if (NodeEval(pb, i, yp, lambda, Rp, NULL, &sp) || NodeEval(pb, i, ym, lambda, Rm, NULL, &sp)) return 1;
      for (int k = 0; k < 3; k++) K[3 * k + j] = (Rp[k] - Rm[k]) / (2 * h);
    }
  }
  return 0;
}

PetscErrorCode ContactAssemble(Problem *pb, const PetscScalar *u, PetscReal lambda, PetscScalar *f, Mat J, PetscScalar *coo_v)
{
  PetscInt nfail = 0;

  PetscFunctionBeginUser;
  if (!pb->ns) PetscFunctionReturn(0);
  PetscCall(PetscLogEventBegin(pb->ev_contact, 0, 0, 0, 0));
  /* pairing phase: every slave node to its tool and patch (kept in the node's memo) */
  PetscCall(PetscLogEventBegin(pb->ev_pairing, 0, 0, 0, 0));
  for (PetscInt i = 0; i < pb->ns; i++) {
    double     y[3];
    Projection pr;
    NodePosition(pb, i, u, y);
    (void)PairNode(pb, i, y, lambda, &pr);
  }
  PetscCall(PetscLogEventEnd(pb->ev_pairing, 0, 0, 0, 0));
  for (PetscInt i = 0; i < pb->ns; i++) {
    double         y[3], R[3], K[9];
    const PetscInt v = pb->slave[i];
    NodePosition(pb, i, u, y);
    if (NodeEval(pb, i, y, lambda, R, J ? K : NULL, &pb->cst_t[i])) {
      nfail++;
      if (J) PetscCall(PetscArrayzero(K, 9)); /* keep the coordinate-assembly slots aligned */
      if (!J) continue;
    }
    if (f)
      for (int k = 0; k < 3; k++) f[pb->vloff[v] + k] += R[k];
    if (J) {
      if (coo_v) {
        PetscInt m = 0;
        for (int r = 0; r < 3; r++)
          for (int c = 0; c < 3; c++)
            if (pb->sgdof[3 * i + r] >= 0 && pb->sgdof[3 * i + c] >= 0) coo_v[m++] = K[3 * r + c];
        coo_v += m;
      } else PetscCall(MatSetValues(J, 3, pb->sgdof + 3 * i, 3, pb->sgdof + 3 * i, K, ADD_VALUES));
    }
  }
  pb->contact_fail = nfail;
  PetscCall(PetscLogEventEnd(pb->ev_contact, 0, 0, 0, 0));
  PetscFunctionReturn(0);
}

PetscErrorCode ContactCommit(Problem *pb)
{
  PetscFunctionBeginUser;
  if (pb->ns) PetscCall(PetscArraycpy(pb->cst_c, pb->cst_t, pb->ns));
  PetscFunctionReturn(0);
}

PetscErrorCode ContactHistoryOpen(Problem *pb, FILE **fp, PetscBool append)
{
  char path[PETSC_MAX_PATH_LEN];

  PetscFunctionBeginUser;
  *fp = NULL;
  if (pb->rank || !pb->ntools) PetscFunctionReturn(0);
  PetscCall(PetscSNPrintf(path, sizeof(path), "%s/contact.csv", pb->cs->output_dir));
  *fp = fopen(path, append ? "a" : "w");
  PetscCheck(*fp, PETSC_COMM_SELF, PETSC_ERR_FILE_OPEN, "cannot write '%s' (-output_dir)", path);
  if (!append) fprintf(*fp, "step,time,tool,travel,force,force_full,newton_its,active,stick,slip,max_penetration\n");
  fflush(*fp);
  PetscFunctionReturn(0);
}

/* direction along which a tool's force and travel are reported: its motion at load 1, or +z for a
   fixed tool */
static void ToolDirection(const Tool *t, double m[3])
{
  double sh[3], nrm;
  ToolShift(t, 1.0, sh);
  nrm = sqrt(sh[0] * sh[0] + sh[1] * sh[1] + sh[2] * sh[2]);
  if (nrm > 0)
    for (int k = 0; k < 3; k++) m[k] = sh[k] / nrm;
  else {
    m[0] = m[1] = 0;
    m[2]        = 1;
  }
}

PetscErrorCode ContactHistoryWrite(Problem *pb, FILE *fp, PetscInt step, PetscReal time, PetscInt its)
{
  PetscFunctionBeginUser;
  for (PetscInt t = 0; t < pb->ntools; t++) {
    double    m[3], sh[3], loc[5] = {0, 0, 0, 0, 0}, pen = 0; /* force, active, stick, slip */
    PetscReal gl[5], gpen;
    ToolDirection(&pb->tools[t], m);
    ToolShift(&pb->tools[t], time, sh);
    for (PetscInt i = 0; i < pb->ns; i++) {
      const ContactState *st = &pb->cst_c[i];
      if (st->tool != t || st->status == CONTACT_OPEN) continue;
      loc[0] += st->f[0] * m[0] + st->f[1] * m[1] + st->f[2] * m[2];
      loc[1] += 1;
      loc[2] += st->status == CONTACT_STICK;
      loc[3] += st->status == CONTACT_SLIP;
      pen = PetscMax(pen, -st->gap);
    }
    PetscCall(MPIU_Allreduce(loc, gl, 4, MPIU_REAL, MPIU_SUM, pb->comm));
    PetscCall(MPIU_Allreduce(&pen, &gpen, 1, MPIU_REAL, MPIU_MAX, pb->comm));
    if (!pb->rank) {
      char         line[1024];
      const double travel = sh[0] * m[0] + sh[1] * m[1] + sh[2] * m[2];
      const int    len    = snprintf(line, sizeof(line), "%" PetscInt_FMT ",%.12g,%s,%.12g,%.12e,%.12e,%" PetscInt_FMT ",%d,%d,%d,%.6e\n", step, (double)time, pb->tools[t].name, travel, (double)gl[0], (double)(gl[0] * pb->cs->symmetry), its, (int)gl[1], (int)gl[2], (int)gl[3], (double)gpen);
      fwrite(line, 1, (size_t)len, fp);
      fflush(fp);
    }
  }
  PetscFunctionReturn(0);
}

/* Chattering: nodes whose contact status changed in the last Newton iteration although they carry
   a significant force (more than 1e-3 of the largest normal force). Returns the count over all
   ranks and the smallest such node id. */
PetscErrorCode ContactChatter(Problem *pb, PetscInt *count, PetscInt *node)
{
  PetscReal tmax = 0;
  PetscInt  c = 0, id = PETSC_MAX_INT;

  PetscFunctionBeginUser;
  for (PetscInt i = 0; i < pb->ns; i++) tmax = PetscMax(tmax, pb->cst_t[i].tN);
  PetscCall(MPIU_Allreduce(MPI_IN_PLACE, &tmax, 1, MPIU_REAL, MPIU_MAX, pb->comm));
  for (PetscInt i = 0; i < pb->ns; i++) {
    const PetscBool active = pb->cst_t[i].status != CONTACT_OPEN;
    if (active != pb->active_prev[i] && pb->cst_t[i].tN > 1e-3 * tmax) {
      c++;
      id = PetscMin(id, pb->node_id[pb->slave[i]]);
    }
  }
  PetscCall(MPIU_Allreduce(&c, count, 1, MPIU_INT, MPI_SUM, pb->comm));
  PetscCall(MPIU_Allreduce(&id, node, 1, MPIU_INT, MPI_MIN, pb->comm));
  PetscFunctionReturn(0);
}

/* the contact status of every slave node at the current iterate (start of a Newton iteration) */
PetscErrorCode ContactRecordActive(Problem *pb)
{
  PetscFunctionBeginUser;
  for (PetscInt i = 0; i < pb->ns; i++) pb->active_prev[i] = pb->cst_t[i].status != CONTACT_OPEN;
  PetscFunctionReturn(0);
}
