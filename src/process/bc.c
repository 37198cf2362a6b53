/* Dirichlet boundary conditions (bc.h): options, the constraint mask of the section, the local
   dof lists, the prescribed values at a process time, the rows of the conditions that stages
   switch on and off, and the reactions. */
#include <string.h>
#include "bc.h"
#include "util.h"
#include "options.h"

static PetscErrorCode ParseComponent(MPI_Comm comm, const char *opt, const char *s, PetscInt *c)
{
  PetscFunctionBeginUser;
  if (!strcmp(s, "x") || !strcmp(s, "0")) *c = 0;
  else if (!strcmp(s, "y") || !strcmp(s, "1")) *c = 1;
  else if (!strcmp(s, "z") || !strcmp(s, "2")) *c = 2;
  else SETERRQ(comm, PETSC_ERR_USER_INPUT, "%s: unknown component '%s' (use x, y, z)", opt, s);
  PetscFunctionReturn(0);
}

PetscErrorCode BCSetFromOptions(MPI_Comm comm, BCs *bcs)
{
  char     *bcnames[ATRITO_MAX_BC];
  PetscInt  n = ATRITO_MAX_BC;
  PetscBool set;

  PetscFunctionBeginUser;
  PetscCall(PetscMemzero(bcs, sizeof(*bcs)));
  PetscOptionsBegin(comm, NULL, "Boundary conditions", NULL);
  PetscCall(PetscOptionsStringArray("-bc_names", "Dirichlet conditions, each described by -bc_<name>_set, _components, _values", NULL, bcnames, &n, &set));
  PetscOptionsEnd();
  bcs->n = set ? n : 0;
  bcs->T = 1.0;
  for (PetscInt b = 0; b < bcs->n; b++) {
    BC      *bc = &bcs->bc[b];
    char    *comps[3], prefix[ATRITO_NAME_LEN + 8], title[ATRITO_NAME_LEN + 32], opt[ATRITO_NAME_LEN + 32];
    PetscInt nc = 3, nvals = 3;
    PetscReal v3[3] = {0, 0, 0};
    char      curve[PETSC_MAX_PATH_LEN] = "";
    PetscBool aset = PETSC_FALSE;

    PetscCall(PetscStrncpy(bc->name, bcnames[b], sizeof(bc->name)));
    PetscCall(PetscFree(bcnames[b]));
    PetscCall(PetscStrncpy(bc->set, bc->name, sizeof(bc->set)));
    PetscCall(PetscSNPrintf(prefix, sizeof(prefix), "bc_%s_", bc->name));
    PetscCall(PetscSNPrintf(title, sizeof(title), "Boundary condition %s", bc->name));
    PetscOptionsBegin(comm, prefix, title, NULL);
    PetscCall(PetscOptionsString("-set", "Mesh set (label) of the condition", NULL, bc->set, bc->set, sizeof(bc->set), NULL));
    PetscCall(PetscSNPrintf(opt, sizeof(opt), "-bc_%s_components", bc->name));
    PetscCall(PetscOptionsStringArray("-components", "Constrained components (x,y,z)", NULL, comps, &nc, &set));
    PetscCheck(set && nc >= 1, comm, PETSC_ERR_USER_INPUT, "%s is required for the boundary condition '%s' (e.g. x,y,z)", opt, bc->name);
    bc->ncomp = nc;
    for (PetscInt k = 0; k < nc; k++) {
      PetscCall(ParseComponent(comm, opt, comps[k], &bc->comp[k]));
      PetscCall(PetscFree(comps[k]));
      for (PetscInt j = 0; j < k; j++) PetscCheck(bc->comp[j] != bc->comp[k], comm, PETSC_ERR_USER_INPUT, "%s: component listed twice", opt);
    }
    PetscCall(PetscSNPrintf(opt, sizeof(opt), "-bc_%s_values", bc->name));
    PetscCall(PetscOptionsRealArray("-values", "Prescribed displacements, times the amplitude a(t) (default t/T: ramped linearly over the process)", NULL, v3, &nvals, &set));
    PetscCheck(!set || nvals == nc, comm, PETSC_ERR_USER_INPUT, "%s needs %" PetscInt_FMT " values (one per component), got %" PetscInt_FMT, opt, nc, nvals);
    PetscCall(AtritoCheckFinite(comm, opt, v3, 3));
    for (int k = 0; k < 3; k++) bc->value[k] = v3[k];
    PetscCall(PetscOptionsString("-amplitude", "Amplitude a(t) of the values, a curve of the process time: t0,a0,t1,a1,... or a file of (t, a) lines (default: t/T, T the total time)", "include/loadcurve.h", curve, curve, sizeof(curve), &aset));
    PetscCall(PetscOptionsBool("-hold", "When a stage switches the condition on, hold its dofs at the displacement they have then (plus value * a(t))", NULL, bc->hold, &bc->hold, NULL));
    bc->always = PETSC_TRUE;
    bc->active = PETSC_TRUE;
    PetscOptionsEnd();
    if (aset) { /* parsed after the block (a file is read on rank 0) */
      PetscCall(PetscSNPrintf(opt, sizeof(opt), "-bc_%s_amplitude", bc->name));
      PetscCall(LoadCurveParse(comm, opt, curve, &bc->amp));
    }
  }
  PetscFunctionReturn(0);
}

/* which condition constrains each local (vertex, component); -1 where none */
static PetscErrorCode Owners(BCs *bcs, const Mesh *m, PetscInt *owner, PetscInt *cmask)
{
  PetscBool *mark;
  PetscInt   conflict = -1, conflict_g;

  PetscFunctionBeginUser;
  PetscCall(PetscMalloc1(m->nv, &mark));
  for (PetscInt i = 0; i < 3 * m->nv; i++) owner[i] = -1;
  if (cmask) PetscCall(PetscArrayzero(cmask, m->nv));
  /* the conditions that are not always active first: a dof that an always active condition
     constrains belongs to that one (a section constraint) */
  for (PetscInt bb = 0; bb < 2 * bcs->n; bb++) {
    const PetscInt b  = bb % bcs->n;
    const BC      *bc = &bcs->bc[b];
    PetscBool      found;
    if ((bb < bcs->n) == (bc->always ? 1 : 0)) continue;
    PetscCall(PetscArrayzero(mark, m->nv));
    PetscCall(MeshMarkSetVertices(m, bc->set, mark, &found));
    PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, &found, 1, MPIU_BOOL, MPI_LOR, m->comm));
    PetscCheck(found, m->comm, PETSC_ERR_USER_INPUT, "-bc_%s_set: the mesh has no set named '%s'", bc->name, bc->set);
    for (PetscInt v = 0; v < m->nv; v++) {
      if (!mark[v]) continue;
      for (PetscInt k = 0; k < bc->ncomp; k++) {
        const PetscInt c = bc->comp[k], o = owner[3 * v + c];
        if (o >= 0 && conflict < 0) {
          /* the same component prescribed twice: allowed only when the values agree */
          PetscInt ko = 0;
          while (ko < bcs->bc[o].ncomp && bcs->bc[o].comp[ko] != c) ko++;
          if (bcs->bc[o].value[ko] != bc->value[k]) conflict = b * ATRITO_MAX_BC + o;
        }
        owner[3 * v + c] = b;
        if (cmask && bc->always) cmask[v] |= 1 << c;
      }
    }
  }
  PetscCall(PetscFree(mark));
  PetscCall(MPIU_Allreduce(&conflict, &conflict_g, 1, MPIU_INT, MPI_MAX, m->comm));
  PetscCheck(conflict_g < 0, m->comm, PETSC_ERR_USER_INPUT, "boundary conditions '%s' and '%s' prescribe different values to the same displacement component", bcs->bc[conflict_g / ATRITO_MAX_BC].name, bcs->bc[conflict_g % ATRITO_MAX_BC].name);
  PetscFunctionReturn(0);
}

PetscErrorCode BCComputeMask(BCs *bcs, const Mesh *m, PetscInt **cmask)
{
  PetscInt *owner;

  PetscFunctionBeginUser;
  PetscCall(PetscMalloc1(m->nv, cmask));
  PetscCall(PetscMalloc1(3 * m->nv, &owner));
  PetscCall(Owners(bcs, m, owner, *cmask));
  PetscCall(PetscFree(owner));
  PetscFunctionReturn(0);
}

PetscErrorCode BCSetUp(BCs *bcs, const Mesh *m)
{
  PetscInt  *owner;
  PetscBool *mark;

  PetscFunctionBeginUser;
  PetscCall(PetscMalloc2(3 * m->nv, &owner, m->nv, &mark));
  PetscCall(Owners(bcs, m, owner, NULL));
  for (PetscInt b = 0; b < bcs->n; b++) {
    BC       *bd = &bcs->bc[b];
    PetscBool found;
    PetscCall(PetscArrayzero(mark, m->nv));
    PetscCall(MeshMarkSetVertices(m, bd->set, mark, &found));
    bd->nset = bd->nown = bd->nrow = 0;
    /* a dof is this condition's when it owns it, or, for a condition that is not always active,
       when no always active condition does */
#define MINE(v, c) (owner[3 * (v) + (c)] == b || (!bd->always && !bcs->bc[owner[3 * (v) + (c)]].always))
    for (PetscInt v = 0; v < m->nv; v++)
      if (mark[v]) {
        for (PetscInt k = 0; k < bd->ncomp; k++)
          if (MINE(v, bd->comp[k])) {
            bd->nset++;
            if (!bd->always && m->vowned[v]) bd->nrow++;
          }
        if (m->vowned[v]) bd->nown++;
      }
    PetscCall(PetscMalloc3(bd->nset, &bd->loff, bd->nset, &bd->val, bd->nown, &bd->own));
    PetscCall(PetscMalloc2(bd->nrow, &bd->grow, bd->nrow, &bd->rval));
    PetscCall(PetscCalloc2(bd->nset, &bd->base, bd->nrow, &bd->rbase));
    bd->nset = bd->nown = bd->nrow = 0;
    for (PetscInt v = 0; v < m->nv; v++)
      if (mark[v]) {
        PetscInt gd[3] = {-1, -1, -1};
        if (!bd->always && m->vowned[v]) PetscCall(MeshVertexDofs(m, v, gd));
        for (PetscInt k = 0; k < bd->ncomp; k++)
          if (MINE(v, bd->comp[k])) {
            bd->loff[bd->nset]  = m->vloff[v] + bd->comp[k];
            bd->val[bd->nset++] = bd->value[k];
            if (!bd->always && m->vowned[v]) {
              PetscCheck(gd[bd->comp[k]] >= 0, PETSC_COMM_SELF, PETSC_ERR_PLIB, "-bc_%s: a dof of the condition is a section constraint", bd->name);
              bd->grow[bd->nrow]   = gd[bd->comp[k]];
              bd->rval[bd->nrow++] = bd->value[k];
            }
          }
        if (m->vowned[v]) bd->own[bd->nown++] = v;
      }
#undef MINE
  }
  PetscCall(PetscFree2(owner, mark));
  bcs->nswitch = 0;
  bcs->mesh    = m;
  {
    PetscInt nz = 0;
    for (PetscInt b = 0; b < bcs->n; b++) {
      if (!bcs->bc[b].always) bcs->nswitch++;
      nz += bcs->bc[b].nrow;
    }
    PetscCall(PetscMalloc1(nz + 1, &bcs->zrows));
  }
  PetscFunctionReturn(0);
}

PetscErrorCode BCDestroy(BCs *bcs)
{
  PetscFunctionBeginUser;
  for (PetscInt b = 0; b < bcs->n; b++) {
    PetscCall(PetscFree3(bcs->bc[b].loff, bcs->bc[b].val, bcs->bc[b].own));
    PetscCall(PetscFree2(bcs->bc[b].grow, bcs->bc[b].rval));
    PetscCall(PetscFree2(bcs->bc[b].base, bcs->bc[b].rbase));
    PetscCall(LoadCurveDestroy(&bcs->bc[b].amp));
  }
  PetscCall(PetscFree(bcs->zrows));
  PetscFunctionReturn(0);
}

PetscReal BCAmplitude(const BCs *bcs, PetscInt b, PetscReal t) { return bcs->bc[b].amp.n > 0 ? LoadCurveEval(&bcs->bc[b].amp, t) : t / bcs->T; }

PetscReal BCNextKink(const BCs *bcs, PetscReal t)
{
  PetscReal k = PETSC_INFINITY;
  for (PetscInt b = 0; b < bcs->n; b++)
    if (bcs->bc[b].amp.n > 0) k = PetscMin(k, LoadCurveNextKink(&bcs->bc[b].amp, t));
  return k;
}

void BCApply(const BCs *bcs, PetscScalar *u, PetscReal t)
{
  for (PetscInt b = 0; b < bcs->n; b++) {
    const PetscReal a = BCAmplitude(bcs, b, t);
    if (!bcs->bc[b].active) continue; /* released: its dofs are free */
    for (PetscInt k = 0; k < bcs->bc[b].nset; k++) u[bcs->bc[b].loff[k]] = bcs->bc[b].base[k] + a * bcs->bc[b].val[k];
  }
}

PetscBool BCHasHold(const BCs *bcs)
{
  for (PetscInt b = 0; b < bcs->n; b++)
    if (bcs->bc[b].hold && !bcs->bc[b].always) return PETSC_TRUE;
  return PETSC_FALSE;
}

PetscErrorCode BCHold(BCs *bcs, PetscInt b, Vec src, Vec hold)
{
  BC                *bc = &bcs->bc[b];
  Vec                L;
  const PetscScalar *s, *l;
  PetscScalar       *h;
  PetscInt           rstart;

  PetscFunctionBeginUser;
  PetscCall(VecGetOwnershipRange(hold, &rstart, NULL));
  if (src != hold) {
    PetscCall(VecGetArrayRead(src, &s));
    PetscCall(VecGetArray(hold, &h));
    for (PetscInt k = 0; k < bc->nrow; k++) h[bc->grow[k] - rstart] = s[bc->grow[k] - rstart];
    PetscCall(VecRestoreArray(hold, &h));
    PetscCall(VecRestoreArrayRead(src, &s));
  }
  PetscCall(DMGetLocalVector(bcs->mesh->dm, &L));
  PetscCall(DMGlobalToLocal(bcs->mesh->dm, hold, INSERT_VALUES, L));
  PetscCall(VecGetArrayRead(L, &l));
  for (PetscInt k = 0; k < bc->nset; k++) bc->base[k] = PetscRealPart(l[bc->loff[k]]);
  PetscCall(VecRestoreArrayRead(L, &l));
  PetscCall(DMRestoreLocalVector(bcs->mesh->dm, &L));
  PetscCall(VecGetArrayRead(hold, &s));
  for (PetscInt k = 0; k < bc->nrow; k++) bc->rbase[k] = PetscRealPart(s[bc->grow[k] - rstart]);
  PetscCall(VecRestoreArrayRead(hold, &s));
  PetscFunctionReturn(0);
}

PetscErrorCode BCConstrainRows(const BCs *bcs, Vec U, Vec F, PetscReal t)
{
  PetscScalar       *f;
  const PetscScalar *u;
  PetscInt           rstart;

  PetscFunctionBeginUser;
  if (!bcs->nswitch) PetscFunctionReturn(0);
  PetscCall(VecGetOwnershipRange(F, &rstart, NULL));
  PetscCall(VecGetArray(F, &f));
  PetscCall(VecGetArrayRead(U, &u));
  for (PetscInt b = 0; b < bcs->n; b++) {
    const BC       *bc = &bcs->bc[b];
    const PetscReal a  = BCAmplitude(bcs, b, t);
    if (bc->always || !bc->active) continue;
    for (PetscInt k = 0; k < bc->nrow; k++) f[bc->grow[k] - rstart] = u[bc->grow[k] - rstart] - (bc->rbase[k] + a * bc->rval[k]);
  }
  PetscCall(VecRestoreArrayRead(U, &u));
  PetscCall(VecRestoreArray(F, &f));
  PetscFunctionReturn(0);
}

PetscErrorCode BCSwitchedRows(BCs *bcs, PetscInt *n, const PetscInt **rows)
{
  PetscFunctionBeginUser;
  *n    = 0;
  *rows = NULL;
  if (!bcs->nswitch) PetscFunctionReturn(0);
  for (PetscInt b = 0; b < bcs->n; b++) {
    const BC *bc = &bcs->bc[b];
    if (bc->always || !bc->active) continue;
    for (PetscInt k = 0; k < bc->nrow; k++) bcs->zrows[(*n)++] = bc->grow[k];
  }
  PetscCall(PetscSortRemoveDupsInt(n, bcs->zrows));
  *rows = bcs->zrows;
  PetscFunctionReturn(0);
}

PetscErrorCode BCConstrainJacobian(BCs *bcs, Mat P)
{
  PetscInt        n = 0;
  const PetscInt *rows;

  PetscFunctionBeginUser;
  if (!bcs->nswitch) PetscFunctionReturn(0);
  PetscCall(BCSwitchedRows(bcs, &n, &rows));
  /* collective, also on a rank without such rows; the nonzero pattern stays (the LU's analysis) */
  PetscCall(MatSetOption(P, MAT_KEEP_NONZERO_PATTERN, PETSC_TRUE));
  PetscCall(MatSetOption(P, MAT_NO_OFF_PROC_ZERO_ROWS, PETSC_TRUE));
  PetscCall(MatZeroRowsColumns(P, n, bcs->zrows, 1.0, NULL, NULL));
  PetscFunctionReturn(0);
}

/* The assembled residual at the vertices of each set, summed over the owned vertices (every
   vertex counted once; through the unconstrained twin DM, whose global vector holds every
   component), on all ranks. */
PetscErrorCode BCReactions(const BCs *bcs, const Mesh *m, Vec Floc, PetscReal (*R)[3])
{
  Vec                Rg;
  const PetscScalar *r;
  PetscSection       gs;
  PetscInt           rstart;

  PetscFunctionBeginUser;
  PetscCall(DMGetGlobalVector(m->dmr, &Rg));
  PetscCall(VecZeroEntries(Rg));
  PetscCall(DMLocalToGlobal(m->dmr, Floc, ADD_VALUES, Rg));
  PetscCall(DMGetGlobalSection(m->dmr, &gs));
  PetscCall(VecGetOwnershipRange(Rg, &rstart, NULL));
  PetscCall(VecGetArrayRead(Rg, &r));
  for (PetscInt b = 0; b < bcs->n; b++) {
    R[b][0] = R[b][1] = R[b][2] = 0;
    for (PetscInt k = 0; k < bcs->bc[b].nown; k++) {
      PetscInt goff;
      PetscCall(PetscSectionGetOffset(gs, m->vstart + bcs->bc[b].own[k], &goff));
      for (int i = 0; i < 3; i++) R[b][i] += PetscRealPart(r[goff - rstart + i]);
    }
  }
  PetscCall(VecRestoreArrayRead(Rg, &r));
  PetscCall(DMRestoreGlobalVector(m->dmr, &Rg));
  if (bcs->n) PetscCall(MPIU_Allreduce(MPI_IN_PLACE, &R[0][0], 3 * bcs->n, MPIU_REAL, MPIU_SUM, m->comm));
  PetscFunctionReturn(0);
}
