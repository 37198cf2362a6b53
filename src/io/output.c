/* Field output: DIR/fields.h5 written collectively with MPI-IO, DIR/fields.xmf an XDMF 2 index
   that ParaView opens. OutputFieldsCreate truncates fields.h5 and removes a stale fields.xmf;
   the index is (re)written atomically by rank 0 after the mesh (the mesh alone) and after every
   step (a temporal collection, one grid per step). An index without any grid is never written:
   ParaView's XDMF 2 reader crashes on one.

   File layout:
     /mesh/coordinates   nv x 3  float64
     /mesh/hexahedra     ne x 8  int64   (global 0-based vertex numbers, hex8 / VTK order)
     /mesh/node_ids      nv      int64   (1-based ids of the source)
     /mesh/element_ids   ne      int64
     /steps/NNNNNN       group, attributes "time" (float64) and "step" (int32)
     /steps/NNNNNN/name  nv x ncomp (node) or ne x ncomp (cell) float64, 1D when ncomp == 1,
                         attribute "center" = "node" or "cell"; in the index ncomp 1, 3, 6, 9
                         are Scalar, Vector, Tensor6 (xx xy xz yy yz zz), Tensor, others Matrix

   Every rank passes a contiguous block of rows of the global numbering; the blocks must tile
   [0, N) (checked collectively, so that a bad call fails on every rank instead of hanging). */
#define _POSIX_C_SOURCE 200809L
#include <errno.h>
#include <fcntl.h>
#include <stdarg.h>
#include <stdint.h>
#include <stdio.h>
#include <string.h>
#include <sys/stat.h>
#include <sys/types.h>
#include <unistd.h>

#include <hdf5.h>
#include <output.h>

#if !defined(H5_HAVE_PARALLEL)
  #error "output.c needs a parallel (MPI-IO) build of HDF5"
#endif

#define OUTPUT_H5_NAME  "fields.h5"
#define OUTPUT_XMF_NAME "fields.xmf"

/* A negative HDF5 return value becomes a PETSc error; the message names the file and object. */
#define OutputCheckH5(ret, ...) PetscCheck((ret) >= 0, PETSC_COMM_SELF, PETSC_ERR_FILE_WRITE, __VA_ARGS__)

typedef struct {
  char     *name;
  PetscInt  ncomp;
  PetscBool cell; /* PETSC_TRUE: cell field, else node field */
} OutputFieldRecord;

typedef struct {
  PetscInt           step;
  PetscReal          time;
  PetscInt           nfield;
  OutputFieldRecord *field;
} OutputStepRecord;

struct _p_OutputFields {
  MPI_Comm    comm; /* private duplicate of the user's communicator */
  PetscMPIInt rank, size;
  char        dir[PETSC_MAX_PATH_LEN];
  char        h5path[PETSC_MAX_PATH_LEN];
  char        xmfpath[PETSC_MAX_PATH_LEN];
  PetscBool   mesh_written;
  PetscInt    nv, ne;                /* global sizes, from WriteMesh */
  PetscInt    nv_local, v_offset;    /* this rank's vertex rows     */
  PetscInt    ne_local, e_offset;    /* this rank's cell rows       */
  PetscInt    nsteps, maxsteps;      /* the steps written, for the XDMF index */
  OutputStepRecord *steps;
};

/* ------------------------------------------------------------------------------------------ */
/* Directories and atomic text files                                                           */

/* mkdir -p; returns 0 or an errno value. */
static int OutputMkdirP(const char *dir)
{
  char        buf[PETSC_MAX_PATH_LEN];
  size_t      len = strlen(dir);
  struct stat st;

  if (len == 0) return ENOENT;
  if (len >= sizeof(buf)) return ENAMETOOLONG;
  memcpy(buf, dir, len + 1);
  for (size_t i = 1; i <= len; i++) {
    if (buf[i] != '/' && buf[i] != '\0') continue;
    if (buf[i - 1] == '/') continue; /* repeated slashes */
    char c = buf[i];
    buf[i] = '\0';
    if (stat(buf, &st) == 0) {
      if (!S_ISDIR(st.st_mode)) return ENOTDIR;
    } else if (mkdir(buf, 0777) != 0 && errno != EEXIST) {
      return errno;
    }
    buf[i] = c;
  }
  if (stat(dir, &st) != 0) return errno;
  if (!S_ISDIR(st.st_mode)) return ENOTDIR;
  return 0;
}

PetscErrorCode OutputEnsureDirectory(MPI_Comm comm, const char *dir)
{
  PetscMPIInt rank;
  int         err = 0;

  PetscFunctionBeginUser;
  PetscCallMPI(MPI_Comm_rank(comm, &rank));
  if (rank == 0) err = dir ? OutputMkdirP(dir) : EINVAL;
  PetscCallMPI(MPI_Bcast(&err, 1, MPI_INT, 0, comm));
  PetscCheck(!err, comm, PETSC_ERR_FILE_OPEN, "Cannot create directory '%s': %s", dir ? dir : "(null)", strerror(err));
  PetscFunctionReturn(0);
}

/* Best effort: make a rename durable by syncing the directory that holds path. */
static void OutputSyncParentDir(const char *path)
{
  char        buf[PETSC_MAX_PATH_LEN];
  const char *slash = strrchr(path, '/');
  int         fd;

  if (!slash) strcpy(buf, ".");
  else if (slash == path) strcpy(buf, "/");
  else {
    size_t n = (size_t)(slash - path);
    if (n >= sizeof(buf)) return;
    memcpy(buf, path, n);
    buf[n] = '\0';
  }
  fd = open(buf, O_RDONLY);
  if (fd >= 0) {
    (void)fsync(fd);
    (void)close(fd);
  }
}

PetscErrorCode OutputWriteTextAtomic(const char *path, const char *text)
{
  char   tmp[PETSC_MAX_PATH_LEN];
  FILE  *f;
  size_t len;
  int    n, err = 0;

  PetscFunctionBeginUser;
  PetscCheck(path && text, PETSC_COMM_SELF, PETSC_ERR_ARG_NULL, "OutputWriteTextAtomic: NULL path or text");
  n = snprintf(tmp, sizeof(tmp), "%s.tmp", path);
  PetscCheck(n > 0 && (size_t)n < sizeof(tmp), PETSC_COMM_SELF, PETSC_ERR_ARG_SIZ, "Path too long: '%s'", path);
  f = fopen(tmp, "w");
  PetscCheck(f, PETSC_COMM_SELF, PETSC_ERR_FILE_OPEN, "Cannot open '%s' for writing: %s", tmp, strerror(errno));
  len = strlen(text);
  if (fwrite(text, 1, len, f) != len) err = errno ? errno : EIO;
  if (!err && fflush(f) != 0) err = errno;
  if (!err && fsync(fileno(f)) != 0) err = errno;
  if (fclose(f) != 0 && !err) err = errno;
  if (err) (void)remove(tmp);
  PetscCheck(!err, PETSC_COMM_SELF, PETSC_ERR_FILE_WRITE, "Cannot write '%s' (for '%s'): %s", tmp, path, strerror(err));
  if (rename(tmp, path) != 0) {
    err = errno;
    (void)remove(tmp);
    SETERRQ(PETSC_COMM_SELF, PETSC_ERR_FILE_WRITE, "Cannot rename '%s' to '%s': %s", tmp, path, strerror(err));
  }
  OutputSyncParentDir(path);
  PetscFunctionReturn(0);
}

/* ------------------------------------------------------------------------------------------ */
/* A growing string, for the XDMF text                                                          */

typedef struct {
  char  *s;
  size_t len, cap;
} OutputStr;

static PetscErrorCode OutputStrPrintf(OutputStr *b, const char *fmt, ...)
{
  va_list ap;
  int     n;

  PetscFunctionBeginUser;
  va_start(ap, fmt);
  n = vsnprintf(NULL, 0, fmt, ap);
  va_end(ap);
  PetscCheck(n >= 0, PETSC_COMM_SELF, PETSC_ERR_LIB, "vsnprintf failed");
  if (b->len + (size_t)n + 1 > b->cap) {
    size_t cap = b->cap ? b->cap : 4096;
    while (cap < b->len + (size_t)n + 1) cap *= 2;
    PetscCall(PetscRealloc(cap, &b->s));
    b->cap = cap;
  }
  va_start(ap, fmt);
  (void)vsnprintf(b->s + b->len, (size_t)n + 1, fmt, ap);
  va_end(ap);
  b->len += (size_t)n;
  PetscFunctionReturn(0);
}

/* ------------------------------------------------------------------------------------------ */
/* The XDMF index (rank 0)                                                                      */

static const char *OutputAttributeType(PetscInt ncomp)
{
  switch (ncomp) {
  case 1: return "Scalar";
  case 3: return "Vector";
  case 6: return "Tensor6";
  case 9: return "Tensor";
  default: return "Matrix";
  }
}

static PetscErrorCode OutputXdmfText(OutputFields of, OutputStr *b)
{
  PetscFunctionBeginUser;
  PetscCall(OutputStrPrintf(b, "<?xml version=\"1.0\" ?>\n<!DOCTYPE Xdmf SYSTEM \"Xdmf.dtd\" []>\n"));
  PetscCall(OutputStrPrintf(b, "<Xdmf Version=\"2.0\" xmlns:xi=\"http://www.w3.org/2001/XInclude\">\n  <Domain>\n"));
  if (of->nsteps == 0) {
    /* mesh only (ParaView's XDMF 2 reader crashes on a Domain or a collection without grids) */
    PetscCall(OutputStrPrintf(b, "    <Grid Name=\"mesh\" GridType=\"Uniform\">\n"));
    PetscCall(OutputStrPrintf(b, "      <Topology TopologyType=\"Hexahedron\" NumberOfElements=\"%" PetscInt_FMT "\">\n", of->ne));
    PetscCall(OutputStrPrintf(b, "        <DataItem Dimensions=\"%" PetscInt_FMT " 8\" NumberType=\"Int\" Precision=\"8\" Format=\"HDF\">" OUTPUT_H5_NAME ":/mesh/hexahedra</DataItem>\n", of->ne));
    PetscCall(OutputStrPrintf(b, "      </Topology>\n      <Geometry GeometryType=\"XYZ\">\n"));
    PetscCall(OutputStrPrintf(b, "        <DataItem Dimensions=\"%" PetscInt_FMT " 3\" NumberType=\"Float\" Precision=\"8\" Format=\"HDF\">" OUTPUT_H5_NAME ":/mesh/coordinates</DataItem>\n", of->nv));
    PetscCall(OutputStrPrintf(b, "      </Geometry>\n    </Grid>\n  </Domain>\n</Xdmf>\n"));
    PetscFunctionReturn(0);
  }
  PetscCall(OutputStrPrintf(b, "    <Grid Name=\"fields\" GridType=\"Collection\" CollectionType=\"Temporal\">\n"));
  for (PetscInt s = 0; s < of->nsteps; s++) {
    const OutputStepRecord *st = &of->steps[s];

    PetscCall(OutputStrPrintf(b, "      <Grid Name=\"step_%06" PetscInt_FMT "\" GridType=\"Uniform\">\n", st->step));
    PetscCall(OutputStrPrintf(b, "        <Time Value=\"%.17g\" />\n", (double)st->time));
    PetscCall(OutputStrPrintf(b, "        <Topology TopologyType=\"Hexahedron\" NumberOfElements=\"%" PetscInt_FMT "\">\n", of->ne));
    PetscCall(OutputStrPrintf(b, "          <DataItem Dimensions=\"%" PetscInt_FMT " 8\" NumberType=\"Int\" Precision=\"8\" Format=\"HDF\">" OUTPUT_H5_NAME ":/mesh/hexahedra</DataItem>\n", of->ne));
    PetscCall(OutputStrPrintf(b, "        </Topology>\n        <Geometry GeometryType=\"XYZ\">\n"));
    PetscCall(OutputStrPrintf(b, "          <DataItem Dimensions=\"%" PetscInt_FMT " 3\" NumberType=\"Float\" Precision=\"8\" Format=\"HDF\">" OUTPUT_H5_NAME ":/mesh/coordinates</DataItem>\n", of->nv));
    PetscCall(OutputStrPrintf(b, "        </Geometry>\n"));
    for (PetscInt f = 0; f < st->nfield; f++) {
      const OutputFieldRecord *fr = &st->field[f];
      PetscInt                 N  = fr->cell ? of->ne : of->nv;

      PetscCall(OutputStrPrintf(b, "        <Attribute Name=\"%s\" AttributeType=\"%s\" Center=\"%s\">\n", fr->name, OutputAttributeType(fr->ncomp), fr->cell ? "Cell" : "Node"));
      if (fr->ncomp == 1) PetscCall(OutputStrPrintf(b, "          <DataItem Dimensions=\"%" PetscInt_FMT "\"", N));
      else PetscCall(OutputStrPrintf(b, "          <DataItem Dimensions=\"%" PetscInt_FMT " %" PetscInt_FMT "\"", N, fr->ncomp));
      PetscCall(OutputStrPrintf(b, " NumberType=\"Float\" Precision=\"8\" Format=\"HDF\">" OUTPUT_H5_NAME ":/steps/%06" PetscInt_FMT "/%s</DataItem>\n", st->step, fr->name));
      PetscCall(OutputStrPrintf(b, "        </Attribute>\n"));
    }
    PetscCall(OutputStrPrintf(b, "      </Grid>\n"));
  }
  PetscCall(OutputStrPrintf(b, "    </Grid>\n  </Domain>\n</Xdmf>\n"));
  PetscFunctionReturn(0);
}

/* Rank 0 rewrites DIR/fields.xmf; the outcome is broadcast so that every rank fails together. */
static PetscErrorCode OutputWriteXdmf(OutputFields of)
{
  PetscErrorCode ierr = 0;
  int            fail = 0;

  PetscFunctionBeginUser;
  if (of->rank == 0) {
    OutputStr b = {NULL, 0, 0};

    ierr = OutputXdmfText(of, &b);
    if (!ierr) ierr = OutputWriteTextAtomic(of->xmfpath, b.s);
    PetscCall(PetscFree(b.s));
    fail = ierr ? 1 : 0;
  }
  PetscCallMPI(MPI_Bcast(&fail, 1, MPI_INT, 0, of->comm));
  PetscCall(ierr);
  PetscCheck(!fail, PETSC_COMM_SELF, PETSC_ERR_FILE_WRITE, "Rank 0 could not write '%s'", of->xmfpath);
  PetscFunctionReturn(0);
}

/* Rank 0 removes DIR/fields.xmf and DIR/fields.xmf.tmp when present. */
static PetscErrorCode OutputRemoveStaleIndex(OutputFields of)
{
  char tmp[PETSC_MAX_PATH_LEN + 8];
  int  err = 0;

  PetscFunctionBeginUser;
  if (of->rank == 0) {
    (void)snprintf(tmp, sizeof(tmp), "%s.tmp", of->xmfpath);
    if (remove(of->xmfpath) != 0 && errno != ENOENT) err = errno;
    if (!err && remove(tmp) != 0 && errno != ENOENT) err = errno;
  }
  PetscCallMPI(MPI_Bcast(&err, 1, MPI_INT, 0, of->comm));
  PetscCheck(!err, of->comm, PETSC_ERR_FILE_WRITE, "Cannot remove the stale index '%s': %s", of->xmfpath, strerror(err));
  PetscFunctionReturn(0);
}

/* ------------------------------------------------------------------------------------------ */
/* HDF5 helpers                                                                                 */

static PetscErrorCode OutputFileOpen(OutputFields of, hid_t *file)
{
  hid_t  fapl;
  herr_t e;

  PetscFunctionBeginUser;
  fapl = H5Pcreate(H5P_FILE_ACCESS);
  OutputCheckH5(fapl, "HDF5: cannot create a file access property list for '%s'", of->h5path);
  e = H5Pset_fapl_mpio(fapl, of->comm, MPI_INFO_NULL);
  OutputCheckH5(e, "HDF5: cannot select the MPI-IO driver for '%s'", of->h5path);
  e = H5Pset_all_coll_metadata_ops(fapl, 1);
  OutputCheckH5(e, "HDF5: cannot set collective metadata reads for '%s'", of->h5path);
  e = H5Pset_coll_metadata_write(fapl, 1);
  OutputCheckH5(e, "HDF5: cannot set collective metadata writes for '%s'", of->h5path);
  *file = H5Fopen(of->h5path, H5F_ACC_RDWR, fapl);
  e     = H5Pclose(fapl);
  OutputCheckH5(*file, "HDF5: cannot open '%s' for writing", of->h5path);
  OutputCheckH5(e, "HDF5: cannot close the file access property list for '%s'", of->h5path);
  PetscFunctionReturn(0);
}

static PetscErrorCode OutputFileClose(OutputFields of, hid_t file)
{
  herr_t e;

  PetscFunctionBeginUser;
  e = H5Fflush(file, H5F_SCOPE_GLOBAL);
  OutputCheckH5(e, "HDF5: cannot flush '%s'", of->h5path);
  e = H5Fclose(file);
  OutputCheckH5(e, "HDF5: cannot close '%s'", of->h5path);
  PetscFunctionReturn(0);
}

/* Create dataset loc/name (N x ncomp, 1D when ncomp == 1) and write this rank's rows
   [offset, offset + nlocal) collectively; a rank with no rows joins with an empty selection. */
static PetscErrorCode OutputWriteRows(OutputFields of, hid_t loc, const char *path, const char *name, hid_t filetype, hid_t memtype, PetscInt N, PetscInt ncomp, PetscInt nlocal, PetscInt offset, const void *buf)
{
  const int dummy   = 0;
  int       rank    = ncomp == 1 ? 1 : 2;
  hsize_t   dims[2] = {(hsize_t)N, (hsize_t)ncomp};
  hsize_t   start[2] = {(hsize_t)offset, 0}, count[2] = {(hsize_t)nlocal, (hsize_t)ncomp};
  hsize_t   one[2]   = {1, (hsize_t)ncomp};
  hid_t     fspace, mspace, dcpl, dxpl, dset;
  herr_t    e;

  PetscFunctionBeginUser;
  fspace = H5Screate_simple(rank, dims, NULL);
  OutputCheckH5(fspace, "HDF5: cannot create the dataspace of '%s' in '%s'", path, of->h5path);
  dcpl = H5Pcreate(H5P_DATASET_CREATE);
  OutputCheckH5(dcpl, "HDF5: cannot create a dataset creation property list for '%s' in '%s'", path, of->h5path);
  e = H5Pset_fill_time(dcpl, H5D_FILL_TIME_NEVER);
  OutputCheckH5(e, "HDF5: cannot set the fill time of '%s' in '%s'", path, of->h5path);
  e = H5Pset_alloc_time(dcpl, H5D_ALLOC_TIME_EARLY);
  OutputCheckH5(e, "HDF5: cannot set the allocation time of '%s' in '%s'", path, of->h5path);
  dset = H5Dcreate2(loc, name, filetype, fspace, H5P_DEFAULT, dcpl, H5P_DEFAULT);
  OutputCheckH5(dset, "HDF5: cannot create dataset '%s' in '%s'", path, of->h5path);
  e = H5Pclose(dcpl);
  OutputCheckH5(e, "HDF5: cannot close the creation property list of '%s' in '%s'", path, of->h5path);

  if (nlocal > 0) {
    e = H5Sselect_hyperslab(fspace, H5S_SELECT_SET, start, NULL, count, NULL);
    OutputCheckH5(e, "HDF5: cannot select rows [%" PetscInt_FMT ", %" PetscInt_FMT ") of '%s' in '%s'", offset, offset + nlocal, path, of->h5path);
    mspace = H5Screate_simple(rank, count, NULL);
    OutputCheckH5(mspace, "HDF5: cannot create the memory dataspace for '%s' in '%s'", path, of->h5path);
  } else {
    e = H5Sselect_none(fspace);
    OutputCheckH5(e, "HDF5: cannot select nothing in '%s' in '%s'", path, of->h5path);
    mspace = H5Screate_simple(rank, one, NULL);
    OutputCheckH5(mspace, "HDF5: cannot create the memory dataspace for '%s' in '%s'", path, of->h5path);
    e = H5Sselect_none(mspace);
    OutputCheckH5(e, "HDF5: cannot select nothing in memory for '%s' in '%s'", path, of->h5path);
    buf = &dummy; /* never read */
  }
  dxpl = H5Pcreate(H5P_DATASET_XFER);
  OutputCheckH5(dxpl, "HDF5: cannot create a transfer property list for '%s' in '%s'", path, of->h5path);
  e = H5Pset_dxpl_mpio(dxpl, H5FD_MPIO_COLLECTIVE);
  OutputCheckH5(e, "HDF5: cannot request collective transfers for '%s' in '%s'", path, of->h5path);
  e = H5Dwrite(dset, memtype, mspace, fspace, dxpl, buf);
  OutputCheckH5(e, "HDF5: cannot write '%s' in '%s'", path, of->h5path);
  e = H5Pclose(dxpl);
  OutputCheckH5(e, "HDF5: cannot close the transfer property list of '%s' in '%s'", path, of->h5path);
  e = H5Sclose(mspace);
  OutputCheckH5(e, "HDF5: cannot close the memory dataspace of '%s' in '%s'", path, of->h5path);
  e = H5Sclose(fspace);
  OutputCheckH5(e, "HDF5: cannot close the dataspace of '%s' in '%s'", path, of->h5path);
  e = H5Dclose(dset);
  OutputCheckH5(e, "HDF5: cannot close dataset '%s' in '%s'", path, of->h5path);
  PetscFunctionReturn(0);
}

static PetscErrorCode OutputWriteReals(OutputFields of, hid_t loc, const char *path, const char *name, PetscInt N, PetscInt ncomp, PetscInt nlocal, PetscInt offset, const PetscReal *v)
{
#if defined(PETSC_USE_REAL_DOUBLE)
  PetscFunctionBeginUser;
  PetscCall(OutputWriteRows(of, loc, path, name, H5T_IEEE_F64LE, H5T_NATIVE_DOUBLE, N, ncomp, nlocal, offset, v));
#else
  double *d;

  PetscFunctionBeginUser;
  PetscCall(PetscMalloc1(nlocal * ncomp + 1, &d));
  for (PetscInt i = 0; i < nlocal * ncomp; i++) d[i] = (double)v[i];
  PetscCall(OutputWriteRows(of, loc, path, name, H5T_IEEE_F64LE, H5T_NATIVE_DOUBLE, N, ncomp, nlocal, offset, d));
  PetscCall(PetscFree(d));
#endif
  PetscFunctionReturn(0);
}

static PetscErrorCode OutputWriteInts(OutputFields of, hid_t loc, const char *path, const char *name, PetscInt N, PetscInt ncomp, PetscInt nlocal, PetscInt offset, const PetscInt *v)
{
  int64_t *d;

  PetscFunctionBeginUser;
  PetscCall(PetscMalloc1(nlocal * ncomp + 1, &d));
  for (PetscInt i = 0; i < nlocal * ncomp; i++) d[i] = (int64_t)v[i];
  PetscCall(OutputWriteRows(of, loc, path, name, H5T_STD_I64LE, H5T_NATIVE_INT64, N, ncomp, nlocal, offset, d));
  PetscCall(PetscFree(d));
  PetscFunctionReturn(0);
}

static PetscErrorCode OutputWriteScalarAttribute(OutputFields of, hid_t obj, const char *objpath, const char *name, hid_t filetype, hid_t memtype, const void *value)
{
  hid_t  space, attr;
  herr_t e;

  PetscFunctionBeginUser;
  space = H5Screate(H5S_SCALAR);
  OutputCheckH5(space, "HDF5: cannot create the dataspace of attribute '%s' of '%s' in '%s'", name, objpath, of->h5path);
  attr = H5Acreate2(obj, name, filetype, space, H5P_DEFAULT, H5P_DEFAULT);
  OutputCheckH5(attr, "HDF5: cannot create attribute '%s' of '%s' in '%s'", name, objpath, of->h5path);
  e = H5Awrite(attr, memtype, value);
  OutputCheckH5(e, "HDF5: cannot write attribute '%s' of '%s' in '%s'", name, objpath, of->h5path);
  e = H5Aclose(attr);
  OutputCheckH5(e, "HDF5: cannot close attribute '%s' of '%s' in '%s'", name, objpath, of->h5path);
  e = H5Sclose(space);
  OutputCheckH5(e, "HDF5: cannot close the dataspace of attribute '%s' of '%s' in '%s'", name, objpath, of->h5path);
  PetscFunctionReturn(0);
}

static PetscErrorCode OutputWriteStringAttribute(OutputFields of, hid_t obj, const char *objpath, const char *name, const char *value)
{
  hid_t  type;
  herr_t e;

  PetscFunctionBeginUser;
  type = H5Tcopy(H5T_C_S1);
  OutputCheckH5(type, "HDF5: cannot create a string type for attribute '%s' of '%s' in '%s'", name, objpath, of->h5path);
  e = H5Tset_size(type, strlen(value) + 1);
  OutputCheckH5(e, "HDF5: cannot size the string type for attribute '%s' of '%s' in '%s'", name, objpath, of->h5path);
  e = H5Tset_strpad(type, H5T_STR_NULLTERM);
  OutputCheckH5(e, "HDF5: cannot set the string padding for attribute '%s' of '%s' in '%s'", name, objpath, of->h5path);
  PetscCall(OutputWriteScalarAttribute(of, obj, objpath, name, type, type, value));
  e = H5Tclose(type);
  OutputCheckH5(e, "HDF5: cannot close the string type of attribute '%s' of '%s' in '%s'", name, objpath, of->h5path);
  PetscFunctionReturn(0);
}

static PetscErrorCode OutputCreateGroup(OutputFields of, hid_t loc, const char *name, hid_t *grp)
{
  PetscFunctionBeginUser;
  *grp = H5Gcreate2(loc, name, H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
  OutputCheckH5(*grp, "HDF5: cannot create group '%s' in '%s'", name, of->h5path);
  PetscFunctionReturn(0);
}

static PetscErrorCode OutputCloseGroup(OutputFields of, hid_t grp, const char *name)
{
  herr_t e;

  PetscFunctionBeginUser;
  e = H5Gclose(grp);
  OutputCheckH5(e, "HDF5: cannot close group '%s' in '%s'", name, of->h5path);
  PetscFunctionReturn(0);
}

/* ------------------------------------------------------------------------------------------ */
/* Collective argument checks                                                                   */

/* Do the blocks (off[r], n[r]) tile [0, N) exactly? */
static PetscErrorCode OutputBlocksTile(PetscMPIInt size, const PetscInt off[], const PetscInt n[], PetscInt N, PetscBool *ok)
{
  PetscInt *o, *l, m = 0, next = 0;

  PetscFunctionBeginUser;
  *ok = PETSC_TRUE;
  PetscCall(PetscMalloc2(size, &o, size, &l));
  for (PetscMPIInt r = 0; r < size; r++) {
    if (n[r] < 0 || off[r] < 0) *ok = PETSC_FALSE;
    if (n[r] > 0) {
      o[m] = off[r];
      l[m] = n[r];
      m++;
    }
  }
  PetscCall(PetscSortIntWithArray(m, o, l));
  for (PetscInt i = 0; i < m; i++) {
    if (o[i] != next) *ok = PETSC_FALSE;
    next = o[i] + l[i];
  }
  if (next != N) *ok = PETSC_FALSE;
  PetscCall(PetscFree2(o, l));
  PetscFunctionReturn(0);
}

/* A field name must be a plain HDF5 link name that needs no escaping in XML. */
static PetscBool OutputNameValid(const char *name)
{
  if (!name || !name[0] || !strcmp(name, ".") || !strcmp(name, "..")) return PETSC_FALSE;
  if (strlen(name) >= 256) return PETSC_FALSE;
  for (const char *c = name; *c; c++) {
    if (*c <= ' ' || *c > '~' || strchr("/&<>\"':", *c)) return PETSC_FALSE;
  }
  return PETSC_TRUE;
}

static uint64_t OutputHash(uint64_t h, const void *p, size_t n)
{
  const unsigned char *c = (const unsigned char *)p;
  for (size_t i = 0; i < n; i++) h = (h ^ c[i]) * 1099511628211ULL; /* FNV-1a */
  return h;
}

/* ------------------------------------------------------------------------------------------ */
/* Public interface                                                                             */

PetscErrorCode OutputFieldsCreate(MPI_Comm comm, const char *dir, OutputFields *of_out)
{
  OutputFields o;
  size_t       len;
  int          n1, n2;
  hid_t        fapl, file, grp;
  herr_t       e;

  PetscFunctionBeginUser;
  PetscCheck(of_out, comm, PETSC_ERR_ARG_NULL, "OutputFieldsCreate: NULL output argument");
  *of_out = NULL;
  PetscCheck(dir && dir[0], comm, PETSC_ERR_ARG_WRONG, "OutputFieldsCreate: empty output directory");
  PetscCall(PetscNew(&o));
  PetscCallMPI(MPI_Comm_dup(comm, &o->comm));
  PetscCallMPI(MPI_Comm_rank(o->comm, &o->rank));
  PetscCallMPI(MPI_Comm_size(o->comm, &o->size));
  len = strlen(dir);
  PetscCheck(len < sizeof(o->dir), comm, PETSC_ERR_ARG_SIZ, "Output directory name too long: '%s'", dir);
  memcpy(o->dir, dir, len + 1);
  while (len > 1 && o->dir[len - 1] == '/') o->dir[--len] = '\0';
  n1 = snprintf(o->h5path, sizeof(o->h5path), "%s/%s", o->dir, OUTPUT_H5_NAME);
  n2 = snprintf(o->xmfpath, sizeof(o->xmfpath), "%s/%s", o->dir, OUTPUT_XMF_NAME);
  PetscCheck(n1 > 0 && (size_t)n1 < sizeof(o->h5path) && n2 > 0 && (size_t)n2 < sizeof(o->xmfpath), comm, PETSC_ERR_ARG_SIZ, "Output directory name too long: '%s'", dir);

  PetscCall(OutputEnsureDirectory(o->comm, o->dir));

  fapl = H5Pcreate(H5P_FILE_ACCESS);
  OutputCheckH5(fapl, "HDF5: cannot create a file access property list for '%s'", o->h5path);
  e = H5Pset_fapl_mpio(fapl, o->comm, MPI_INFO_NULL);
  OutputCheckH5(e, "HDF5: cannot select the MPI-IO driver for '%s'", o->h5path);
  file = H5Fcreate(o->h5path, H5F_ACC_TRUNC, H5P_DEFAULT, fapl);
  e    = H5Pclose(fapl);
  OutputCheckH5(file, "HDF5: cannot create '%s'", o->h5path);
  OutputCheckH5(e, "HDF5: cannot close the file access property list for '%s'", o->h5path);
  PetscCall(OutputCreateGroup(o, file, "/mesh", &grp));
  PetscCall(OutputCloseGroup(o, grp, "/mesh"));
  PetscCall(OutputCreateGroup(o, file, "/steps", &grp));
  PetscCall(OutputCloseGroup(o, grp, "/steps"));
  PetscCall(OutputFileClose(o, file));

  /* a stale index from an earlier run would point into the truncated file: remove it; the
     index is written once the mesh is (an index without grids is not readable by ParaView) */
  PetscCall(OutputRemoveStaleIndex(o));
  *of_out = o;
  PetscFunctionReturn(0);
}

PetscErrorCode OutputFieldsWriteMesh(OutputFields of, PetscInt nv_local, PetscInt v_offset, PetscInt nv_global, const PetscReal *X, const PetscInt *node_id, PetscInt ne_local, PetscInt e_offset, PetscInt ne_global, const PetscInt *conn, const PetscInt *elem_id)
{
  PetscInt  mine[7], *all;
  PetscInt *voff, *vn, *eoff, *en;
  PetscBool vok, eok, same = PETSC_TRUE, bad = PETSC_FALSE;
  hid_t     file, grp;

  PetscFunctionBeginUser;
  PetscCheck(of, PETSC_COMM_SELF, PETSC_ERR_ARG_NULL, "OutputFieldsWriteMesh: NULL OutputFields");
  PetscCheck(!of->mesh_written, of->comm, PETSC_ERR_ORDER, "OutputFieldsWriteMesh: the mesh of '%s' is already written", of->h5path);

  /* every rank gathers everyone's arguments, so all reach the same verdict */
  mine[0] = v_offset;
  mine[1] = nv_local;
  mine[2] = nv_global;
  mine[3] = e_offset;
  mine[4] = ne_local;
  mine[5] = ne_global;
  mine[6] = 0;
  if (nv_local > 0 && (!X || !node_id)) mine[6] = 1;
  if (ne_local > 0 && (!conn || !elem_id)) mine[6] = 1;
  if (!mine[6] && ne_local > 0) {
    for (PetscInt i = 0; i < 8 * ne_local; i++)
      if (conn[i] < 0 || conn[i] >= nv_global) mine[6] = 2;
  }
  PetscCall(PetscMalloc5(7 * of->size, &all, of->size, &voff, of->size, &vn, of->size, &eoff, of->size, &en));
  PetscCallMPI(MPI_Allgather(mine, 7, MPIU_INT, all, 7, MPIU_INT, of->comm));
  for (PetscMPIInt r = 0; r < of->size; r++) {
    voff[r] = all[7 * r + 0];
    vn[r]   = all[7 * r + 1];
    eoff[r] = all[7 * r + 3];
    en[r]   = all[7 * r + 4];
    if (all[7 * r + 2] != nv_global || all[7 * r + 5] != ne_global) same = PETSC_FALSE;
    if (all[7 * r + 6]) bad = PETSC_TRUE;
  }
  PetscCall(OutputBlocksTile(of->size, voff, vn, nv_global, &vok));
  PetscCall(OutputBlocksTile(of->size, eoff, en, ne_global, &eok));
  PetscCall(PetscFree5(all, voff, vn, eoff, en));
  PetscCheck(same, of->comm, PETSC_ERR_ARG_INCOMP, "OutputFieldsWriteMesh ('%s'): the ranks disagree on the global sizes", of->h5path);
  PetscCheck(vok, of->comm, PETSC_ERR_ARG_OUTOFRANGE, "OutputFieldsWriteMesh ('%s'): the vertex blocks (offset, count) of the ranks do not tile [0, %" PetscInt_FMT ")", of->h5path, nv_global);
  PetscCheck(eok, of->comm, PETSC_ERR_ARG_OUTOFRANGE, "OutputFieldsWriteMesh ('%s'): the cell blocks (offset, count) of the ranks do not tile [0, %" PetscInt_FMT ")", of->h5path, ne_global);
  PetscCheck(!bad, of->comm, PETSC_ERR_ARG_WRONG, "OutputFieldsWriteMesh ('%s'): a rank passed NULL arrays or a connectivity entry outside [0, %" PetscInt_FMT ")", of->h5path, nv_global);

  PetscCall(OutputFileOpen(of, &file));
  grp = H5Gopen2(file, "/mesh", H5P_DEFAULT);
  OutputCheckH5(grp, "HDF5: cannot open group '/mesh' in '%s'", of->h5path);
  PetscCall(OutputWriteReals(of, grp, "/mesh/coordinates", "coordinates", nv_global, 3, nv_local, v_offset, X));
  PetscCall(OutputWriteInts(of, grp, "/mesh/hexahedra", "hexahedra", ne_global, 8, ne_local, e_offset, conn));
  PetscCall(OutputWriteInts(of, grp, "/mesh/node_ids", "node_ids", nv_global, 1, nv_local, v_offset, node_id));
  PetscCall(OutputWriteInts(of, grp, "/mesh/element_ids", "element_ids", ne_global, 1, ne_local, e_offset, elem_id));
  PetscCall(OutputCloseGroup(of, grp, "/mesh"));
  PetscCall(OutputFileClose(of, file));

  of->nv           = nv_global;
  of->ne           = ne_global;
  of->nv_local     = nv_local;
  of->v_offset     = v_offset;
  of->ne_local     = ne_local;
  of->e_offset     = e_offset;
  of->mesh_written = PETSC_TRUE;
  PetscCall(OutputWriteXdmf(of));
  PetscFunctionReturn(0);
}

PetscErrorCode OutputFieldsWriteStep(OutputFields of, PetscInt step, PetscReal time, PetscInt nnode, const OutputField node[], PetscInt ncell, const OutputField cell[])
{
  uint64_t          h = 1469598103934665603ULL, red[3], loc[3];
  double            t = (double)time;
  int               istep;
  PetscBool         valid = PETSC_TRUE, dup = PETSC_FALSE;
  char              gname[64], dpath[512];
  hid_t             file, grp;
  OutputStepRecord *rec;

  PetscFunctionBeginUser;
  PetscCheck(of, PETSC_COMM_SELF, PETSC_ERR_ARG_NULL, "OutputFieldsWriteStep: NULL OutputFields");
  PetscCheck(of->mesh_written, of->comm, PETSC_ERR_ORDER, "OutputFieldsWriteStep ('%s'): write the mesh first", of->h5path);
  PetscCheck(step >= 0 && step <= (PetscInt)INT32_MAX, of->comm, PETSC_ERR_ARG_OUTOFRANGE, "OutputFieldsWriteStep ('%s'): step %" PetscInt_FMT " out of range", of->h5path, step);
  PetscCheck(nnode >= 0 && ncell >= 0 && (!nnode || node) && (!ncell || cell), of->comm, PETSC_ERR_ARG_WRONG, "OutputFieldsWriteStep ('%s'): bad field lists", of->h5path);
  for (PetscInt s = 0; s < of->nsteps; s++)
    if (of->steps[s].step == step) dup = PETSC_TRUE;
  PetscCheck(!dup, of->comm, PETSC_ERR_ARG_WRONG, "OutputFieldsWriteStep ('%s'): step %" PetscInt_FMT " already written", of->h5path, step);

  /* the ranks must agree on the step, time and field list (HDF5 metadata is collective) and
     each field must be usable; checked on all ranks so that a bad call fails everywhere */
  h = OutputHash(h, &step, sizeof(step));
  h = OutputHash(h, &t, sizeof(t));
  h = OutputHash(h, &nnode, sizeof(nnode));
  h = OutputHash(h, &ncell, sizeof(ncell));
  for (PetscInt k = 0; k < nnode + ncell; k++) {
    const OutputField *f     = k < nnode ? &node[k] : &cell[k - nnode];
    PetscInt           nloc  = k < nnode ? of->nv_local : of->ne_local;

    if (!OutputNameValid(f->name) || f->ncomp < 1 || (nloc > 0 && !f->data)) {
      valid = PETSC_FALSE;
      continue;
    }
    for (PetscInt j = 0; j < k; j++) {
      const OutputField *g = j < nnode ? &node[j] : &cell[j - nnode];
      if (g->name && !strcmp(g->name, f->name)) valid = PETSC_FALSE;
    }
    h = OutputHash(h, f->name, strlen(f->name) + 1);
    h = OutputHash(h, &f->ncomp, sizeof(f->ncomp));
  }
  loc[0] = h;
  loc[1] = ~h;
  loc[2] = valid ? 0 : 1;
  PetscCallMPI(MPI_Allreduce(loc, red, 3, MPI_UINT64_T, MPI_MAX, of->comm));
  PetscCheck(!red[2], of->comm, PETSC_ERR_ARG_WRONG, "OutputFieldsWriteStep ('%s', step %" PetscInt_FMT "): invalid field (a name must be non-empty, unique, without '/', spaces or &<>\"':, ncomp >= 1, data non-NULL)", of->h5path, step);
  PetscCheck(red[0] == ~red[1], of->comm, PETSC_ERR_ARG_INCOMP, "OutputFieldsWriteStep ('%s', step %" PetscInt_FMT "): the ranks disagree on the step, time or field list", of->h5path, step);

  istep = (int)step;
  PetscCall(PetscSNPrintf(gname, sizeof(gname), "/steps/%06" PetscInt_FMT, step));
  PetscCall(OutputFileOpen(of, &file));
  PetscCall(OutputCreateGroup(of, file, gname, &grp));
  PetscCall(OutputWriteScalarAttribute(of, grp, gname, "time", H5T_IEEE_F64LE, H5T_NATIVE_DOUBLE, &t));
  PetscCall(OutputWriteScalarAttribute(of, grp, gname, "step", H5T_STD_I32LE, H5T_NATIVE_INT, &istep));
  for (PetscInt k = 0; k < nnode + ncell; k++) {
    const OutputField *f      = k < nnode ? &node[k] : &cell[k - nnode];
    PetscBool          iscell = k < nnode ? PETSC_FALSE : PETSC_TRUE;
    hid_t              dset;
    herr_t             e;

    PetscCall(PetscSNPrintf(dpath, sizeof(dpath), "%s/%s", gname, f->name));
    if (iscell) PetscCall(OutputWriteReals(of, grp, dpath, f->name, of->ne, f->ncomp, of->ne_local, of->e_offset, f->data));
    else PetscCall(OutputWriteReals(of, grp, dpath, f->name, of->nv, f->ncomp, of->nv_local, of->v_offset, f->data));
    dset = H5Dopen2(grp, f->name, H5P_DEFAULT);
    OutputCheckH5(dset, "HDF5: cannot open dataset '%s' in '%s'", dpath, of->h5path);
    PetscCall(OutputWriteStringAttribute(of, dset, dpath, "center", iscell ? "cell" : "node"));
    e = H5Dclose(dset);
    OutputCheckH5(e, "HDF5: cannot close dataset '%s' in '%s'", dpath, of->h5path);
  }
  PetscCall(OutputCloseGroup(of, grp, gname));
  PetscCall(OutputFileClose(of, file));

  /* remember the step for the XDMF index */
  if (of->nsteps == of->maxsteps) {
    PetscInt m = of->maxsteps ? 2 * of->maxsteps : 16;
    PetscCall(PetscRealloc(m * sizeof(OutputStepRecord), &of->steps));
    of->maxsteps = m;
  }
  rec         = &of->steps[of->nsteps];
  rec->step   = step;
  rec->time   = time;
  rec->nfield = nnode + ncell;
  PetscCall(PetscCalloc1(rec->nfield + 1, &rec->field));
  for (PetscInt k = 0; k < nnode + ncell; k++) {
    const OutputField *f = k < nnode ? &node[k] : &cell[k - nnode];
    PetscCall(PetscStrallocpy(f->name, &rec->field[k].name));
    rec->field[k].ncomp = f->ncomp;
    rec->field[k].cell  = k < nnode ? PETSC_FALSE : PETSC_TRUE;
  }
  of->nsteps++;

  PetscCall(OutputWriteXdmf(of));
  PetscFunctionReturn(0);
}

PetscErrorCode OutputFieldsDestroy(OutputFields *of)
{
  PetscFunctionBeginUser;
  if (!of || !*of) PetscFunctionReturn(0);
  for (PetscInt s = 0; s < (*of)->nsteps; s++) {
    for (PetscInt k = 0; k < (*of)->steps[s].nfield; k++) PetscCall(PetscFree((*of)->steps[s].field[k].name));
    PetscCall(PetscFree((*of)->steps[s].field));
  }
  PetscCall(PetscFree((*of)->steps));
  if ((*of)->comm != MPI_COMM_NULL) PetscCallMPI(MPI_Comm_free(&(*of)->comm));
  PetscCall(PetscFree(*of));
  PetscFunctionReturn(0);
}

/* ------------------------------------------------------------------------------------------ */
/* Restart: continue an existing fields.h5                                                     */

typedef struct {
  OutputFields of;
  hid_t        steps;
  PetscInt     keep;
  PetscInt     ndel;
  char       (*del)[32];
} OutputScan;

/* one group of /steps: remember it (step <= keep) or mark it for deletion */
static herr_t OutputScanStep(hid_t grp, const char *name, const H5L_info_t *info, void *ctx)
{
  OutputScan       *sc = (OutputScan *)ctx;
  OutputFields      of = sc->of;
  hid_t             g, a, d, sp, ca, at;
  int               stepv = -1;
  double            tv    = 0;
  hsize_t           dims[2];
  H5G_info_t        gi;
  OutputStepRecord *rec;
  (void)info;

  g = H5Gopen2(grp, name, H5P_DEFAULT);
  if (g < 0) return -1;
  a = H5Aopen(g, "step", H5P_DEFAULT);
  if (a < 0 || H5Aread(a, H5T_NATIVE_INT, &stepv) < 0) return -1;
  H5Aclose(a);
  a = H5Aopen(g, "time", H5P_DEFAULT);
  if (a < 0 || H5Aread(a, H5T_NATIVE_DOUBLE, &tv) < 0) return -1;
  H5Aclose(a);
  if (stepv > sc->keep) {
    H5Gclose(g);
    if (sc->ndel % 64 == 0 && PetscRealloc((size_t)(sc->ndel + 64) * sizeof(*sc->del), &sc->del)) return -1;
    snprintf(sc->del[sc->ndel++], 32, "%s", name);
    return 0;
  }
  if (of->nsteps == of->maxsteps) {
    PetscInt m = of->maxsteps ? 2 * of->maxsteps : 16;
    if (PetscRealloc(m * sizeof(OutputStepRecord), &of->steps)) return -1;
    of->maxsteps = m;
  }
  rec         = &of->steps[of->nsteps++];
  rec->step   = stepv;
  rec->time   = tv;
  rec->nfield = 0;
  if (H5Gget_info(g, &gi) < 0 || PetscCalloc1(gi.nlinks + 1, &rec->field)) return -1;
  for (hsize_t k = 0; k < gi.nlinks; k++) {
    char    fname[256], center[16] = "";
    ssize_t      len;
    H5E_auto2_t  efunc;
    void        *edata;
    /* the order of creation where the file tracks it, else by name: the first try is silent */
    H5Eget_auto2(H5E_DEFAULT, &efunc, &edata);
    H5Eset_auto2(H5E_DEFAULT, NULL, NULL);
    len = H5Lget_name_by_idx(g, ".", H5_INDEX_CRT_ORDER, H5_ITER_INC, k, fname, sizeof(fname), H5P_DEFAULT);
    H5Eset_auto2(H5E_DEFAULT, efunc, edata);
    if (len < 0) len = H5Lget_name_by_idx(g, ".", H5_INDEX_NAME, H5_ITER_INC, k, fname, sizeof(fname), H5P_DEFAULT);
    if (len < 0) return -1;
    d  = H5Dopen2(g, fname, H5P_DEFAULT);
    sp = H5Dget_space(d);
    int nd = H5Sget_simple_extent_dims(sp, dims, NULL);
    ca = H5Aopen(d, "center", H5P_DEFAULT);
    at = H5Aget_type(ca);
    if (d < 0 || sp < 0 || nd < 1 || ca < 0 || H5Aread(ca, at, center) < 0) return -1;
    H5Tclose(at);
    H5Aclose(ca);
    H5Sclose(sp);
    H5Dclose(d);
    if (PetscStrallocpy(fname, &rec->field[rec->nfield].name)) return -1;
    rec->field[rec->nfield].ncomp = nd == 1 ? 1 : (PetscInt)dims[1];
    rec->field[rec->nfield].cell  = !strncmp(center, "cell", 4) ? PETSC_TRUE : PETSC_FALSE;
    rec->nfield++;
  }
  H5Gclose(g);
  return 0;
}

static int OutputStepCompare(const void *a, const void *b)
{
  const PetscInt x = ((const OutputStepRecord *)a)->step, y = ((const OutputStepRecord *)b)->step;
  return (x > y) - (x < y);
}

PetscErrorCode OutputFieldsReopen(MPI_Comm comm, const char *dir, PetscInt keep_step, PetscInt nv_local, PetscInt v_offset, PetscInt ne_local, PetscInt e_offset, OutputFields *of_out)
{
  OutputFields o;
  OutputScan   sc;
  hid_t        file, d, sp;
  hsize_t      dims[2];
  herr_t       e;

  PetscFunctionBeginUser;
  *of_out = NULL;
  PetscCall(PetscNew(&o));
  PetscCallMPI(MPI_Comm_dup(comm, &o->comm));
  PetscCallMPI(MPI_Comm_rank(o->comm, &o->rank));
  PetscCallMPI(MPI_Comm_size(o->comm, &o->size));
  PetscCall(PetscStrncpy(o->dir, dir, sizeof(o->dir)));
  PetscCall(PetscSNPrintf(o->h5path, sizeof(o->h5path), "%s/%s", dir, OUTPUT_H5_NAME));
  PetscCall(PetscSNPrintf(o->xmfpath, sizeof(o->xmfpath), "%s/%s", dir, OUTPUT_XMF_NAME));
  PetscCall(OutputFileOpen(o, &file));
  d = H5Dopen2(file, "/mesh/coordinates", H5P_DEFAULT);
  OutputCheckH5(d, "HDF5: '%s' has no /mesh/coordinates: cannot continue it", o->h5path);
  sp = H5Dget_space(d);
  H5Sget_simple_extent_dims(sp, dims, NULL);
  o->nv = (PetscInt)dims[0];
  H5Sclose(sp);
  H5Dclose(d);
  d = H5Dopen2(file, "/mesh/hexahedra", H5P_DEFAULT);
  OutputCheckH5(d, "HDF5: '%s' has no /mesh/hexahedra: cannot continue it", o->h5path);
  sp = H5Dget_space(d);
  H5Sget_simple_extent_dims(sp, dims, NULL);
  o->ne = (PetscInt)dims[0];
  H5Sclose(sp);
  H5Dclose(d);
  /* the steps up to keep_step stay; later ones (written after the checkpoint) go */
  PetscCall(PetscMemzero(&sc, sizeof(sc)));
  sc.of    = o;
  sc.keep  = keep_step;
  sc.steps = H5Gopen2(file, "/steps", H5P_DEFAULT);
  OutputCheckH5(sc.steps, "HDF5: '%s' has no /steps: cannot continue it", o->h5path);
  e = H5Literate(sc.steps, H5_INDEX_NAME, H5_ITER_INC, NULL, OutputScanStep, &sc);
  OutputCheckH5(e, "HDF5: cannot read the steps of '%s'", o->h5path);
  for (PetscInt k = 0; k < sc.ndel; k++) {
    e = H5Ldelete(sc.steps, sc.del[k], H5P_DEFAULT);
    OutputCheckH5(e, "HDF5: cannot remove /steps/%s from '%s'", sc.del[k], o->h5path);
  }
  PetscCall(PetscFree(sc.del));
  H5Gclose(sc.steps);
  PetscCall(OutputFileClose(o, file));
  qsort(o->steps, (size_t)o->nsteps, sizeof(OutputStepRecord), OutputStepCompare);
  o->nv_local     = nv_local;
  o->v_offset     = v_offset;
  o->ne_local     = ne_local;
  o->e_offset     = e_offset;
  o->mesh_written = PETSC_TRUE;
  PetscCall(OutputWriteXdmf(o));
  *of_out = o;
  PetscFunctionReturn(0);
}
