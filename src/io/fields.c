/* Field output of a run (results.h): the mesh once, then per output step the displacement,
   the plastic strain, the von Mises stress, the thickness strain of sheets and the contact node
   fields, in the source mesh's row order (iorows.h), through the HDF5/XDMF writer (output.h). */
#include <math.h>
#include "results.h"
#include "tensor.h"

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

PetscErrorCode FieldsWriteMesh(Results *res, Problem *problem)
{
  PetscReal *X, *Xb, *ids, *conn;
  PetscInt  *nidb, *eidb, *connb;

  const Mesh  *pb = problem->mesh;
  OutputFields of = res->of;

  PetscFunctionBeginUser;
  PetscCall(PetscMalloc4(3 * pb->nvo + 1, &X, 3 * pb->rv.nb + 1, &Xb, PetscMax(pb->nvo, pb->nc) + 1, &ids, 8 * pb->nc + 1, &conn));
  PetscCall(PetscMalloc3(pb->rv.nb + 1, &nidb, pb->rc.nb + 1, &eidb, 8 * pb->rc.nb + 1, &connb));
  for (PetscInt k = 0; k < pb->nvo; k++) {
    for (int i = 0; i < 3; i++) X[3 * k + i] = pb->X[3 * pb->vloc[k] + i];
    ids[k] = pb->node_id[pb->vloc[k]];
  }
  PetscCall(IORowsToBlock((IORows *)&pb->rv, 3, X, Xb));
  PetscCall(ToBlockInt((IORows *)&pb->rv, 1, ids, nidb));
  for (PetscInt c = 0; c < pb->nc; c++) ids[c] = pb->elem_id[c];
  PetscCall(ToBlockInt((IORows *)&pb->rc, 1, ids, eidb));
  for (PetscInt k = 0; k < 8 * pb->nc; k++) conn[k] = pb->node_src[pb->cv[k]];
  PetscCall(ToBlockInt((IORows *)&pb->rc, 8, conn, connb));
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

PetscErrorCode FieldsWriteStep(Results *res, Problem *pb, PetscInt step, PetscReal time)
{
  PetscReal         *disp, *ep, *mises, *thick, *store[12];
  const PetscScalar *u;
  OutputField        nf[6], cf[3];
  PetscInt           nn = 0, ncf = 0, ns = 0;

  const Mesh        *m  = pb->mesh;
  OutputFields       of = res->of;
  IORows            *rv = (IORows *)&m->rv, *rc = (IORows *)&m->rc;

  PetscFunctionBeginUser;
  PetscCall(PetscLogEventBegin(res->ev_output, 0, 0, 0, 0));
  PetscCall(PetscMalloc4(3 * m->nvo + 1, &disp, m->nc + 1, &ep, m->nc + 1, &mises, m->nc + 1, &thick));
  /* Uloc holds the converged displacements with the boundary values (set by the last assembly) */
  PetscCall(VecGetArrayRead(pb->Uloc, &u));
  for (PetscInt k = 0; k < m->nvo; k++)
    for (int i = 0; i < 3; i++) disp[3 * k + i] = PetscRealPart(u[m->vloff[m->vloc[k]] + i]);
  PetscCall(VecRestoreArrayRead(pb->Uloc, &u));
  for (PetscInt c = 0; c < m->nc; c++) {
    ep[c]    = pb->einfo[c].ep;
    mises[c] = pb->einfo[c].mises;
    thick[c] = 0;
    if (res->thickness) {
      /* thickness strain ln(h/h0) = -ln |F^-T N| at the centroid, N the reference normal */
      double        Fi[9], v[3];
      const double *N = res->thickness_dir;
      t3_inv(pb->einfo[c].F0, Fi);
      for (int i = 0; i < 3; i++) v[i] = Fi[i] * N[0] + Fi[3 + i] * N[1] + Fi[6 + i] * N[2];
      thick[c] = -log(sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]));
    }
  }
  PetscCall(AddField(rv, "displacement", 3, disp, &nf[nn++], &store[ns++]));
  PetscCall(AddField(rc, "plastic_strain", 1, ep, &cf[ncf++], &store[ns++]));
  PetscCall(AddField(rc, "von_mises", 1, mises, &cf[ncf++], &store[ns++]));
  if (res->thickness) PetscCall(AddField(rc, "thickness_strain", 1, thick, &cf[ncf++], &store[ns++]));
  if (ContactNumTools(pb->contact) || ContactNumPairs(pb->contact)) {
    /* contact node fields: gap, normal force (a nodal force, not a pressure), tangential (friction)
       force, status, accumulated slip */
    PetscReal *cg, *cn, *ct, *cst, *csl;
    PetscCall(PetscMalloc5(m->nvo + 1, &cg, m->nvo + 1, &cn, 3 * m->nvo + 1, &ct, m->nvo + 1, &cst, m->nvo + 1, &csl));
    PetscCall(ContactGetNodeFields(pb->contact, cg, cn, ct, cst, csl));
    PetscCall(AddField(rv, "contact_gap", 1, cg, &nf[nn++], &store[ns++]));
    PetscCall(AddField(rv, "contact_normal_force", 1, cn, &nf[nn++], &store[ns++]));
    PetscCall(AddField(rv, "contact_tangential_force", 3, ct, &nf[nn++], &store[ns++]));
    PetscCall(AddField(rv, "contact_status", 1, cst, &nf[nn++], &store[ns++]));
    PetscCall(AddField(rv, "contact_slip", 1, csl, &nf[nn++], &store[ns++]));
    PetscCall(PetscFree5(cg, cn, ct, cst, csl));
  }
  PetscCall(OutputFieldsWriteStep(of, step, time, nn, nf, ncf, cf));
  for (PetscInt k = 0; k < ns; k++) PetscCall(PetscFree(store[k]));
  PetscCall(PetscFree4(disp, ep, mises, thick));
  PetscCall(PetscLogEventEnd(res->ev_output, 0, 0, 0, 0));
  PetscFunctionReturn(0);
}

