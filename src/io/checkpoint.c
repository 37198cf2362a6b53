/* Checkpoint and restart. DIR/checkpoint.h5 holds all committed state in the source mesh's row
   order (iorows.h), so that it reads back on any number of ranks: the displacements of the last
   two converged steps, the plastic history of every Gauss point, the contact state of every slave
   node (frame of eqs 28-30 included), the step counter, load level and increments, and a format
   version. It is written to checkpoint.h5.tmp and renamed: a run killed at any moment leaves the
   previous checkpoint whole. */
#include <stdio.h>
#include <hdf5.h>
#include "atrito.h"

#define CKPT_VERSION 1
#define CKPT_NCS     24 /* doubles per vertex for the contact state */

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
static PetscErrorCode VertexValues(Problem *pb, Vec U, PetscReal *own, PetscBool to_vec)
{
  PetscScalar *u;
  PetscInt     rstart;

  PetscFunctionBeginUser;
  PetscCall(VecGetOwnershipRange(U, &rstart, NULL));
  PetscCall(VecGetArray(U, &u));
  for (PetscInt k = 0; k < pb->nvo; k++) {
    PetscInt idx[3];
    PetscCall(ProblemVertexDofs(pb, pb->vloc[k], idx));
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

static void PackContact(const ContactState *s, PetscReal *d)
{
  PetscReal v[CKPT_NCS] = {1, (PetscReal)s->status, (PetscReal)s->tool, (PetscReal)s->patch, s->xi, s->eta, s->tT[0], s->tT[1], s->t1[0], s->t1[1], s->t1[2], (PetscReal)s->has_frame, s->y[0], s->y[1], s->y[2], s->gap, s->tN, s->f[0], s->f[1], s->f[2], s->fT[0], s->fT[1], s->fT[2], s->slip};
  for (int k = 0; k < CKPT_NCS; k++) d[k] = v[k];
}

static void UnpackContact(const PetscReal *d, ContactState *s)
{
  s->status    = (PetscInt)d[1];
  s->tool      = (PetscInt)d[2];
  s->patch     = (PetscInt)d[3];
  s->xi        = d[4];
  s->eta       = d[5];
  s->tT[0]     = d[6];
  s->tT[1]     = d[7];
  s->has_frame = d[11] != 0 ? PETSC_TRUE : PETSC_FALSE;
  for (int k = 0; k < 3; k++) {
    s->t1[k] = d[8 + k];
    s->y[k]  = d[12 + k];
    s->f[k]  = d[17 + k];
    s->fT[k] = d[20 + k];
  }
  s->gap  = d[15];
  s->tN   = d[16];
  s->slip = d[23];
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

/* the whole committed state, written (write) or read */
static PetscErrorCode Transfer(Problem *pb, hid_t file, PetscBool write, CheckpointInfo *ci, const char *path)
{
  PetscReal *own, *cst;
  double     a[10];
  const char *names[10] = {"format_version", "step", "lambda", "dl", "dl_prev", "total_its", "total_cuts", "vertices", "cells", "slave_nodes"};
  PetscInt   nsg = pb->ns;

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
  }
  for (int k = 0; k < 10; k++) PetscCall(Attr(file, names[k], write, &a[k], path));
  if (!write) {
    PetscCheck(a[0] == CKPT_VERSION, pb->comm, PETSC_ERR_FILE_UNEXPECTED, "-restart %s: checkpoint format %d, this program reads format %d", path, (int)a[0], CKPT_VERSION);
    PetscCheck(a[7] == pb->nv_global && a[8] == pb->ne_global && a[9] == nsg, pb->comm, PETSC_ERR_FILE_UNEXPECTED, "-restart %s: the checkpoint has %" PetscInt_FMT " vertices, %" PetscInt_FMT " cells and %" PetscInt_FMT " slave nodes, this case %" PetscInt_FMT ", %" PetscInt_FMT " and %" PetscInt_FMT " (not the same mesh or case)", path, (PetscInt)a[7], (PetscInt)a[8], (PetscInt)a[9], pb->nv_global, pb->ne_global, nsg);
    ci->step       = (PetscInt)a[1];
    ci->lambda     = a[2];
    ci->dl         = a[3];
    ci->dl_prev    = a[4];
    ci->total_its  = (PetscInt)a[5];
    ci->total_cuts = (PetscInt)a[6];
  }
  PetscCall(PetscMalloc2(3 * pb->nvo + 1, &own, CKPT_NCS * pb->nvo + 1, &cst));
  /* displacements of the last two converged steps */
  if (write) PetscCall(VertexValues(pb, pb->Uc, own, PETSC_FALSE));
  PetscCall(OwnedRows(file, "displacement", write, &pb->rv, 3, own, path));
  if (!write) PetscCall(VertexValues(pb, pb->Uc, own, PETSC_TRUE));
  if (write) PetscCall(VertexValues(pb, pb->Uprev, own, PETSC_FALSE));
  PetscCall(OwnedRows(file, "displacement_previous", write, &pb->rv, 3, own, path));
  if (!write) PetscCall(VertexValues(pb, pb->Uprev, own, PETSC_TRUE));
  /* plastic history of every Gauss point */
  PetscCall(OwnedRows(file, "plastic_history", write, &pb->rc, HEX8_NQP * MAT_NHIST, pb->hist_c, path));
  /* contact state per vertex (zero rows for the vertices that are not slave nodes) */
  if (pb->ntools) {
    PetscCall(PetscArrayzero(cst, CKPT_NCS * pb->nvo));
    if (write)
      for (PetscInt i = 0; i < pb->ns; i++) PackContact(&pb->cst_c[i], cst + CKPT_NCS * pb->vrow[pb->slave[i]]);
    PetscCall(OwnedRows(file, "contact_state", write, &pb->rv, CKPT_NCS, cst, path));
    if (!write)
      for (PetscInt i = 0; i < pb->ns; i++) {
        const PetscReal *d = cst + CKPT_NCS * pb->vrow[pb->slave[i]];
        PetscCheck(d[0] == 1, PETSC_COMM_SELF, PETSC_ERR_FILE_UNEXPECTED, "-restart %s: node id %" PetscInt_FMT " is a slave node here but not in the checkpoint", path, pb->node_id[pb->slave[i]]);
        UnpackContact(d, &pb->cst_c[i]);
      }
  }
  PetscCall(PetscFree2(own, cst));
  PetscFunctionReturn(0);
}

PetscErrorCode CheckpointWrite(Problem *pb, const CheckpointInfo *ci)
{
  char  path[PETSC_MAX_PATH_LEN], tmp[PETSC_MAX_PATH_LEN];
  hid_t file;

  PetscFunctionBeginUser;
  PetscCall(PetscLogEventBegin(pb->ev_output, 0, 0, 0, 0));
  PetscCall(PetscSNPrintf(path, sizeof(path), "%s/checkpoint.h5", pb->cs->output_dir));
  PetscCall(PetscSNPrintf(tmp, sizeof(tmp), "%s.tmp", path));
  PetscCall(OpenFile(pb->comm, tmp, PETSC_TRUE, &file));
  PetscCall(Transfer(pb, file, PETSC_TRUE, (CheckpointInfo *)ci, tmp));
  CheckH5(H5Fflush(file, H5F_SCOPE_GLOBAL), "HDF5: cannot flush '%s'", tmp);
  CheckH5(H5Fclose(file), "HDF5: cannot close '%s'", tmp);
  PetscCallMPI(MPI_Barrier(pb->comm));
  if (!pb->rank) PetscCheck(!rename(tmp, path), PETSC_COMM_SELF, PETSC_ERR_FILE_WRITE, "cannot rename '%s' to '%s'", tmp, path);
  PetscCallMPI(MPI_Barrier(pb->comm));
  PetscCall(PetscLogEventEnd(pb->ev_output, 0, 0, 0, 0));
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
  PetscCall(PetscArraycpy(pb->hist_t, pb->hist_c, (size_t)pb->nc * HEX8_NQP * MAT_NHIST));
  if (pb->ns) PetscCall(PetscArraycpy(pb->cst_t, pb->cst_c, pb->ns));
  pb->lambda_c = ci->lambda;
  PetscFunctionReturn(0);
}

/* Restart: keep the header and the rows of steps <= step of a CSV history, rewritten atomically
   (rank 0); returns whether the file existed. */
PetscErrorCode HistoryTruncate(Problem *pb, const char *name, PetscInt step, PetscBool *existed)
{
  char  path[PETSC_MAX_PATH_LEN], tmp[PETSC_MAX_PATH_LEN], line[65536];
  FILE *in, *out;
  int   ex = 0;

  PetscFunctionBeginUser;
  if (!pb->rank) {
    PetscCall(PetscSNPrintf(path, sizeof(path), "%s/%s", pb->cs->output_dir, name));
    PetscCall(PetscSNPrintf(tmp, sizeof(tmp), "%s.tmp", path));
    in = fopen(path, "r");
    if (in) {
      ex  = 1;
      out = fopen(tmp, "w");
      PetscCheck(out, PETSC_COMM_SELF, PETSC_ERR_FILE_OPEN, "cannot write '%s'", tmp);
      if (fgets(line, sizeof(line), in)) fputs(line, out); /* header */
      while (fgets(line, sizeof(line), in)) {
        size_t len = strlen(line);
        if (len == 0 || line[len - 1] != '\n') break; /* a partial last row of a killed run */
        if (atol(line) <= (long)step) fputs(line, out);
      }
      fclose(in);
      fclose(out);
      PetscCheck(!rename(tmp, path), PETSC_COMM_SELF, PETSC_ERR_FILE_WRITE, "cannot rename '%s' to '%s'", tmp, path);
    }
  }
  PetscCallMPI(MPI_Bcast(&ex, 1, MPI_INT, 0, pb->comm));
  *existed = ex ? PETSC_TRUE : PETSC_FALSE;
  PetscFunctionReturn(0);
}
