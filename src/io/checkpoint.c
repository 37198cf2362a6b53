/* Checkpoint and restart. DIR/checkpoint.h5 holds all committed state in the source mesh's row
   order (iorows.h), so that it reads back on any number of ranks: the displacements of the last
   two converged steps (three with -load_predictor_curvature: the datasets *_previous2 and the
   attribute dl_prev2, absent otherwise, so that a run restarted with the curvature term repeats
   the uninterrupted one), the plastic history of every Gauss point, the contact state of every slave
   node (frame of eqs 28-30 included), the step counter, load level and increments, and a format
   version. It is written to checkpoint.h5.tmp and renamed: a run killed at any moment leaves the
   previous checkpoint whole. */
#include "contact_pair.h"
#include <stdio.h>
#include <string.h>
#include <hdf5.h>
#include "results.h"

#define CKPT_VERSION 4 /* 2: the stage; 3: the augmented Lagrangian's kept penalty factor in the contact rows; 4: the release by nodal forces in the contact rows */

#define CheckH5(ret, ...) PetscCheck((ret) >= 0, PETSC_COMM_SELF, PETSC_ERR_FILE_UNEXPECTED, __VA_ARGS__)

static PetscErrorCode OpenFile(MPI_Comm comm, const char *path, PetscBool create, hid_t *file)
{
  hid_t fapl = H5Pcreate(H5P_FILE_ACCESS);

  PetscFunctionBeginUser;
  CheckH5(fapl, "HDF5: cannot create a property list for '%s'", path);
  CheckH5(H5Pset_fapl_mpio(fapl, comm, MPI_INFO_NULL), "HDF5: cannot select MPI-IO for '%s'", path);
  *file = create ? H5Fcreate(path, H5F_ACC_TRUNC, H5P_DEFAULT, fapl) : H5Fopen(path, H5F_ACC_RDONLY, fapl);
  H5Pclose(fapl);
  PetscCheck(*file >= 0, comm, PETSC_ERR_FILE_OPEN, "cannot %s checkpoint '%s'", create ? "create" : "open", path);
  PetscFunctionReturn(0);
}

/* rows [off, off+nb) of an N x ncomp dataset of doubles, collectively */
static PetscErrorCode Rows(hid_t file, const char *name, PetscBool write, PetscInt N, PetscInt ncomp, PetscInt nb, PetscInt off, PetscReal *buf, const char *path)
{
  hsize_t dims[2] = {(hsize_t)N, (hsize_t)ncomp}, start[2] = {(hsize_t)off, 0}, count[2] = {(hsize_t)nb, (hsize_t)ncomp}, one[2] = {1, (hsize_t)ncomp};
  hid_t   fs, ms, ds, xp;
  double  dummy[64];

  PetscFunctionBeginUser;
  if (write) {
    fs = H5Screate_simple(2, dims, NULL);
    ds = H5Dcreate2(file, name, H5T_IEEE_F64LE, fs, H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
  } else {
    ds = H5Dopen2(file, name, H5P_DEFAULT);
    CheckH5(ds, "checkpoint '%s' has no dataset %s", path, name);
    fs = H5Dget_space(ds);
    hsize_t fd[2] = {0, 0};
    H5Sget_simple_extent_dims(fs, fd, NULL);
    PetscCheck(fd[0] == (hsize_t)N && fd[1] == (hsize_t)ncomp, PETSC_COMM_SELF, PETSC_ERR_FILE_UNEXPECTED, "checkpoint '%s': %s is %d x %d, this run expects %d x %d (not the same mesh or case?)", path, name, (int)fd[0], (int)fd[1], (int)N, (int)ncomp);
  }
  CheckH5(ds, "HDF5: cannot %s %s in '%s'", write ? "create" : "open", name, path);
  if (nb > 0) {
    CheckH5(H5Sselect_hyperslab(fs, H5S_SELECT_SET, start, NULL, count, NULL), "HDF5: cannot select rows of %s in '%s'", name, path);
    ms = H5Screate_simple(2, count, NULL);
  } else {
    H5Sselect_none(fs);
    ms = H5Screate_simple(2, one, NULL);
    H5Sselect_none(ms);
    buf = dummy;
  }
  xp = H5Pcreate(H5P_DATASET_XFER);
  H5Pset_dxpl_mpio(xp, H5FD_MPIO_COLLECTIVE);
  if (write) CheckH5(H5Dwrite(ds, H5T_NATIVE_DOUBLE, ms, fs, xp, buf), "HDF5: cannot write %s in '%s'", name, path);
  else CheckH5(H5Dread(ds, H5T_NATIVE_DOUBLE, ms, fs, xp, buf), "HDF5: cannot read %s in '%s'", name, path);
  H5Pclose(xp);
  H5Sclose(ms);
  H5Sclose(fs);
  H5Dclose(ds);
  PetscFunctionReturn(0);
}

/* owned items (own[n*ncomp]) through this rank's block of rows */
static PetscErrorCode OwnedRows(hid_t file, const char *name, PetscBool write, IORows *r, PetscInt ncomp, PetscReal *own, const char *path)
{
  PetscReal *blk;

  PetscFunctionBeginUser;
  PetscCall(PetscMalloc1(r->nb * ncomp + 1, &blk));
  if (write) PetscCall(IORowsToBlock(r, ncomp, own, blk));
  PetscCall(Rows(file, name, write, r->N, ncomp, r->nb, r->off, blk, path));
  if (!write) PetscCall(IORowsFromBlock(r, ncomp, blk, own));
  PetscCall(PetscFree(blk));
  PetscFunctionReturn(0);
}

/* the 3 displacement components of every owned vertex <-> a global vector (constrained
   components are not in it: they come from the boundary values) */
static PetscErrorCode VertexValues(const Mesh *pb, Vec U, PetscReal *own, PetscBool to_vec)
{
  PetscScalar *u;
  PetscInt     rstart;

  PetscFunctionBeginUser;
  PetscCall(VecGetOwnershipRange(U, &rstart, NULL));
  PetscCall(VecGetArray(U, &u));
  for (PetscInt k = 0; k < pb->nvo; k++) {
    PetscInt idx[3];
    PetscCall(MeshVertexDofs(pb, pb->vloc[k], idx));
    for (PetscInt c = 0; c < 3; c++) {
      if (idx[c] < 0) {
        if (!to_vec) own[3 * k + c] = 0;
      } else if (to_vec) u[idx[c] - rstart] = own[3 * k + c];
      else own[3 * k + c] = PetscRealPart(u[idx[c] - rstart]);
    }
  }
  PetscCall(VecRestoreArray(U, &u));
  PetscFunctionReturn(0);
}

static PetscErrorCode Attr(hid_t file, const char *name, PetscBool write, double *v, const char *path)
{
  hid_t sp, a;

  PetscFunctionBeginUser;
  if (write) {
    sp = H5Screate(H5S_SCALAR);
    a  = H5Acreate2(file, name, H5T_IEEE_F64LE, sp, H5P_DEFAULT, H5P_DEFAULT);
    CheckH5(a, "HDF5: cannot create attribute %s in '%s'", name, path);
    CheckH5(H5Awrite(a, H5T_NATIVE_DOUBLE, v), "HDF5: cannot write attribute %s in '%s'", name, path);
    H5Sclose(sp);
  } else {
    a = H5Aopen(file, name, H5P_DEFAULT);
    CheckH5(a, "checkpoint '%s' has no attribute %s", path, name);
    CheckH5(H5Aread(a, H5T_NATIVE_DOUBLE, v), "HDF5: cannot read attribute %s in '%s'", name, path);
  }
  H5Aclose(a);
  PetscFunctionReturn(0);
}

/* the material type, a string attribute: written; on reading compared with this case's where the
   checkpoint has it (the history of another type of the same width would be read without a word,
   and the run go on with another model's state) */
static PetscErrorCode MaterialTypeAttr(hid_t file, PetscBool write, const char *type, MPI_Comm comm, const char *path)
{
  char   have[64] = "";
  hid_t  st, sp, a;
  size_t n = strlen(type);

  PetscFunctionBeginUser;
  PetscCheck(n > 0 && n < sizeof(have), comm, PETSC_ERR_ARG_OUTOFRANGE, "material type name of %d characters", (int)n);
  st = H5Tcopy(H5T_C_S1);
  CheckH5(st, "HDF5: cannot make a string type for '%s'", path);
  if (write) {
    CheckH5(H5Tset_size(st, n + 1), "HDF5: cannot size a string type for '%s'", path);
    sp = H5Screate(H5S_SCALAR);
    a  = H5Acreate2(file, "material_type", st, sp, H5P_DEFAULT, H5P_DEFAULT);
    CheckH5(a, "HDF5: cannot create attribute material_type in '%s'", path);
    CheckH5(H5Awrite(a, st, type), "HDF5: cannot write attribute material_type in '%s'", path);
    H5Sclose(sp);
    H5Aclose(a);
  } else if (H5Aexists(file, "material_type") > 0) {
    CheckH5(H5Tset_size(st, sizeof(have)), "HDF5: cannot size a string type for '%s'", path);
    a = H5Aopen(file, "material_type", H5P_DEFAULT);
    CheckH5(a, "checkpoint '%s': cannot open attribute material_type", path);
    hid_t ft = H5Aget_type(a);
    PetscCheck(H5Tget_class(ft) == H5T_STRING && H5Tget_size(ft) < sizeof(have), comm, PETSC_ERR_FILE_UNEXPECTED, "-restart %s: the attribute material_type is not a short string", path);
    H5Tclose(ft);
    CheckH5(H5Aread(a, st, have), "HDF5: cannot read attribute material_type in '%s'", path);
    H5Aclose(a);
    have[sizeof(have) - 1] = '\0';
    PetscCheck(!strcmp(have, type), comm, PETSC_ERR_FILE_UNEXPECTED, "-restart %s: the checkpoint's material is %s, this case's -material_type %s (not the same case)", path, have, type);
  }
  H5Tclose(st);
  PetscFunctionReturn(0);
}

/* the whole committed state, written (write) or read */
static PetscErrorCode Transfer(Problem *problem, hid_t file, PetscBool write, CheckpointInfo *ci, const char *path)
{
  const Mesh *pb = problem->mesh;
  const PetscInt ncs = ContactCheckpointWidth();
  PetscReal *own, *cst;
  double     a[11];
  const char *names[11] = {"format_version", "step", "lambda", "dl", "dl_prev", "total_its", "total_cuts", "vertices", "cells", "slave_nodes", "stage"};
  PetscInt   nsg = ContactNumSlaves(problem->contact);
  PetscBool  has2 = PETSC_FALSE; /* the state before the previous one is transferred */

  PetscFunctionBeginUser;
  PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, &nsg, 1, MPIU_INT, MPI_SUM, pb->comm));
  if (write) {
    a[0] = CKPT_VERSION;
    a[1] = ci->step;
    a[2] = ci->lambda;
    a[3] = ci->dl;
    a[4] = ci->dl_prev;
    a[5] = ci->total_its;
    a[6] = ci->total_cuts;
    a[7] = pb->nv_global;
    a[8] = pb->ne_global;
    a[9] = nsg;
    a[10] = ci->stage;
  }
  for (int k = 0; k < 11; k++) {
    PetscCall(Attr(file, names[k], write, &a[k], path));
    PetscCheck(write || k || a[0] == CKPT_VERSION, pb->comm, PETSC_ERR_FILE_UNEXPECTED, "-restart %s: checkpoint format %d, this program reads format %d", path, (int)a[0], CKPT_VERSION);
  }
  {
    const char *mtype;
    PetscCall(MaterialGetType(problem->material, &mtype));
    PetscCall(MaterialTypeAttr(file, write, mtype, pb->comm, path));
  }
  if (!write) {
    PetscCheck(a[7] == pb->nv_global && a[8] == pb->ne_global && a[9] == nsg, pb->comm, PETSC_ERR_FILE_UNEXPECTED, "-restart %s: the checkpoint has %" PetscInt_FMT " vertices, %" PetscInt_FMT " cells and %" PetscInt_FMT " slave nodes, this case %" PetscInt_FMT ", %" PetscInt_FMT " and %" PetscInt_FMT " (not the same mesh or case)", path, (PetscInt)a[7], (PetscInt)a[8], (PetscInt)a[9], pb->nv_global, pb->ne_global, nsg);
    ci->step       = (PetscInt)a[1];
    ci->lambda     = a[2];
    ci->dl         = a[3];
    ci->dl_prev    = a[4];
    ci->total_its  = (PetscInt)a[5];
    ci->total_cuts = (PetscInt)a[6];
    ci->stage      = (PetscInt)a[10];
  }
  PetscCall(PetscMalloc2(3 * pb->nvo + 1, &own, ncs * pb->nvo + 1, &cst));
  /* displacements of the last two converged steps */
  if (write) PetscCall(VertexValues(pb, problem->Uc, own, PETSC_FALSE));
  PetscCall(OwnedRows(file, "displacement", write, (IORows *)&pb->rv, 3, own, path));
  if (!write) PetscCall(VertexValues(pb, problem->Uc, own, PETSC_TRUE));
  if (write) PetscCall(VertexValues(pb, problem->Uprev, own, PETSC_FALSE));
  PetscCall(OwnedRows(file, "displacement_previous", write, (IORows *)&pb->rv, 3, own, path));
  if (!write) PetscCall(VertexValues(pb, problem->Uprev, own, PETSC_TRUE));
  /* the state before the previous one (-load_predictor_curvature), where there is one: written
     when the run has it, read when the run uses it and the checkpoint has it */
  if (write) has2 = (ci->prev2 && ci->dl_prev2 > 0) ? PETSC_TRUE : PETSC_FALSE;
  else {
    ci->dl_prev2 = 0;
    has2         = (ci->prev2 && H5Lexists(file, "displacement_previous2", H5P_DEFAULT) > 0 && H5Aexists(file, "dl_prev2") > 0) ? PETSC_TRUE : PETSC_FALSE;
  }
  if (has2) {
    double d2 = ci->dl_prev2;
    PetscCall(Attr(file, "dl_prev2", write, &d2, path));
    if (write) PetscCall(VertexValues(pb, ci->prev2, own, PETSC_FALSE));
    PetscCall(OwnedRows(file, "displacement_previous2", write, (IORows *)&pb->rv, 3, own, path));
    if (!write) {
      PetscCheck(d2 > 0, pb->comm, PETSC_ERR_FILE_UNEXPECTED, "-restart %s: the attribute dl_prev2 is %g (an increment must be > 0)", path, d2);
      PetscCall(VertexValues(pb, ci->prev2, own, PETSC_TRUE));
      ci->dl_prev2 = d2;
    }
  }
  /* the bases of the conditions that hold their dofs where a stage switched them on */
  if (ci->hold) {
    if (write) PetscCall(VertexValues(pb, ci->hold, own, PETSC_FALSE));
    PetscCall(OwnedRows(file, "displacement_hold", write, (IORows *)&pb->rv, 3, own, path));
    if (!write) PetscCall(VertexValues(pb, ci->hold, own, PETSC_TRUE));
  }
  /* plastic history of every Gauss point */
  PetscCall(OwnedRows(file, "plastic_history", write, (IORows *)&pb->rc, problem->nhc, problem->hist_c, path));
  /* contact state per vertex (zero rows for the vertices that are not slave nodes) */
  if (ContactNumTools(problem->contact)) {
    if (write) PetscCall(ContactCheckpointPack(problem->contact, cst));
    PetscCall(OwnedRows(file, "contact_state", write, (IORows *)&pb->rv, ncs, cst, path));
    if (!write) PetscCall(ContactCheckpointUnpack(problem->contact, cst, ci->lambda, path));
  }
  PetscCall(PetscFree2(own, cst));
  /* contact pairs between bodies: their slave nodes' committed states per vertex */
  if (ContactNumPairs(problem->contact) || !write) {
    ContactPairs   pr  = ContactGetPairs(problem->contact);
    const PetscInt npw = ContactPairsCheckpointWidth(pr);
    htri_t         has = write ? 1 : H5Lexists(file, "pair_state", H5P_DEFAULT);
    PetscCheck((has > 0) == (npw > 0), pb->comm, PETSC_ERR_FILE_UNEXPECTED, "-restart %s: the checkpoint %s contact pairs, this case %s (not the same case)", path, has > 0 ? "has" : "has no", npw > 0 ? "has" : "has none");
    if (npw) {
      PetscReal *rows;
      PetscCall(PetscMalloc1(npw * pb->nvo + 1, &rows));
      if (write) PetscCall(ContactPairsCheckpointPack(pr, rows));
      PetscCall(OwnedRows(file, "pair_state", write, (IORows *)&pb->rv, npw, rows, path));
      if (!write) {
        PetscScalar *u;
        PetscCall(ProblemLocalWithBC(problem, problem->Uc, ci->lambda));
        PetscCall(VecGetArray(problem->Uloc, &u));
        PetscCall(ContactPairsCheckpointUnpack(pr, rows, u, path));
        PetscCall(VecRestoreArray(problem->Uloc, &u));
      }
      PetscCall(PetscFree(rows));
    }
  }
  /* force-driven tools: their unknowns in the last two converged steps and the tools' committed
     state (drive, held offsets, displacement, path), replicated: written by rank 0, read by all */
  if (problem->ntu || !write) {
    PetscInt   ntu = problem->ntu, nw = ContactToolCheckpointWidth(problem->contact);
    PetscReal *tv;
    htri_t     has = 1;
    if (!write) {
      has = H5Lexists(file, "tool_unknowns", H5P_DEFAULT);
      PetscCheck((has > 0) == (ntu > 0), pb->comm, PETSC_ERR_FILE_UNEXPECTED, "-restart %s: the checkpoint %s tool unknowns, this case %s (not the same case)", path, has > 0 ? "has" : "has no", ntu > 0 ? "drives tools by force" : "drives no tool by force");
    }
    if (ntu) {
      PetscCall(PetscMalloc1(2 * ntu + nw, &tv));
      if (write) {
        PetscCall(ProblemGetToolValues(problem, problem->Uc, tv));
        PetscCall(ProblemGetToolValues(problem, problem->Uprev, tv + ntu));
        PetscCall(ContactToolCheckpointPack(problem->contact, tv + 2 * ntu));
      }
      PetscCall(Rows(file, "tool_unknowns", write, 1, 2 * ntu + nw, write ? (pb->rank == 0 ? 1 : 0) : 1, 0, tv, path));
      if (!write) {
        PetscCall(ProblemSetToolValues(problem, problem->Uc, tv));
        PetscCall(ProblemSetToolValues(problem, problem->Uprev, tv + ntu));
        PetscCall(ContactToolCheckpointUnpack(problem->contact, tv + 2 * ntu));
      }
      if (has2) { /* and in the state before the previous one */
        if (write) PetscCall(ProblemGetToolValues(problem, ci->prev2, tv));
        PetscCall(Rows(file, "tool_unknowns_previous2", write, 1, ntu, write ? (pb->rank == 0 ? 1 : 0) : 1, 0, tv, path));
        if (!write) PetscCall(ProblemSetToolValues(problem, ci->prev2, tv));
      }
      PetscCall(PetscFree(tv));
    }
  }
  PetscFunctionReturn(0);
}

PetscErrorCode CheckpointWrite(Results *res, Problem *pb, const CheckpointInfo *ci)
{
  char  path[PETSC_MAX_PATH_LEN], tmp[PETSC_MAX_PATH_LEN];
  hid_t file;

  PetscFunctionBeginUser;
  PetscCall(PetscLogEventBegin(res->ev_output, 0, 0, 0, 0));
  PetscCall(PetscSNPrintf(path, sizeof(path), "%s/checkpoint.h5", res->dir));
  PetscCall(PetscSNPrintf(tmp, sizeof(tmp), "%s.tmp", path));
  PetscCall(OpenFile(pb->comm, tmp, PETSC_TRUE, &file));
  PetscCall(Transfer(pb, file, PETSC_TRUE, (CheckpointInfo *)ci, tmp));
  CheckH5(H5Fflush(file, H5F_SCOPE_GLOBAL), "HDF5: cannot flush '%s'", tmp);
  CheckH5(H5Fclose(file), "HDF5: cannot close '%s'", tmp);
  PetscCallMPI(MPI_Barrier(pb->comm));
  if (!pb->rank) PetscCheck(!rename(tmp, path), PETSC_COMM_SELF, PETSC_ERR_FILE_WRITE, "cannot rename '%s' to '%s'", tmp, path);
  PetscCallMPI(MPI_Barrier(pb->comm));
  PetscCall(PetscLogEventEnd(res->ev_output, 0, 0, 0, 0));
  PetscFunctionReturn(0);
}

PetscErrorCode CheckpointRead(Problem *pb, const char *path, CheckpointInfo *ci)
{
  hid_t file;
  FILE *fp = NULL;
  int   exists = 0;

  PetscFunctionBeginUser;
  if (!pb->rank) {
    fp     = fopen(path, "r");
    exists = fp != NULL;
    if (fp) fclose(fp);
  }
  PetscCallMPI(MPI_Bcast(&exists, 1, MPI_INT, 0, pb->comm));
  PetscCheck(exists, pb->comm, PETSC_ERR_FILE_OPEN, "-restart: cannot open checkpoint '%s'", path);
  PetscCall(OpenFile(pb->comm, path, PETSC_FALSE, &file));
  PetscCall(Transfer(pb, file, PETSC_FALSE, ci, path));
  H5Fclose(file);
  /* the trial states start from the committed ones */
  PetscCall(ProblemRestored(pb));
  PetscFunctionReturn(0);
}

