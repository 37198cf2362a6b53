/* Unit test of the field output (src/output.c): a small nx x 1 x 1 hexahedral mesh split in
   contiguous blocks over the ranks, two steps with a node vector field and cell scalar and
   6-component fields, read back on rank 0 with the HDF5 C API and compared exactly; the XDMF
   index is checked as text. Options: -output_dir DIR (default: a fresh directory under /tmp,
   removed at the end unless -keep), -nx N (cells along x, default 2). */
#define _XOPEN_SOURCE 700
#include <ftw.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include <hdf5.h>
#include <output.h>
#include "testutil.h"

static PetscMPIInt rank = 0;


/* the test mesh: (nx+1) x 2 x 2 vertices, vertex (i,j,k) = i + (nx+1)*(j + 2*k) */
static PetscReal Coord(PetscInt v, PetscInt c, PetscInt nx)
{
  PetscInt i = v % (nx + 1), j = (v / (nx + 1)) % 2, k = v / (2 * (nx + 1));
  return c == 0 ? 0.1 * (PetscReal)i : (c == 1 ? 0.7 * (PetscReal)j : 1.3 * (PetscReal)k);
}
static PetscInt Conn(PetscInt e, PetscInt a, PetscInt nx)
{
  const PetscInt di[8] = {0, 1, 1, 0, 0, 1, 1, 0}, dj[8] = {0, 0, 1, 1, 0, 0, 1, 1}, dk[8] = {0, 0, 0, 0, 1, 1, 1, 1};
  return (e + di[a]) + (nx + 1) * (dj[a] + 2 * dk[a]);
}
static PetscInt  NodeId(PetscInt v) { return 10 * v + 1; }
static PetscInt  ElemId(PetscInt e) { return 100 + e; }
static PetscReal DispValue(PetscInt v, PetscInt c, PetscInt step) { return 0.25 * (PetscReal)(3 * v + c) + (PetscReal)step / 7.0; }
static PetscReal EqpsValue(PetscInt e, PetscInt step) { return (PetscReal)e / 3.0 + (PetscReal)step; }
static PetscReal StressValue(PetscInt e, PetscInt c, PetscInt step) { return -1e9 * (PetscReal)(e + 1) + (PetscReal)c / 11.0 + (PetscReal)step; }

static void Block(PetscInt n, PetscMPIInt r, PetscMPIInt size, PetscInt *lo, PetscInt *hi)
{
  *lo = n * r / size;
  *hi = n * (r + 1) / size;
}

/* Read a dataset as memtype (rank 0, serial HDF5); *ok false when anything fails. */
static PetscErrorCode ReadDataset(hid_t file, const char *path, hid_t memtype, size_t elsize, int *ndims, hsize_t dims[2], void **buf, PetscBool *ok)
{
  hid_t   dset, space;
  hsize_t n = 1;

  PetscFunctionBeginUser;
  *ok   = PETSC_FALSE;
  *buf  = NULL;
  *ndims = -1;
  dims[0] = dims[1] = 0;
  dset = H5Dopen2(file, path, H5P_DEFAULT);
  if (dset < 0) PetscFunctionReturn(0);
  space = H5Dget_space(dset);
  if (space >= 0) {
    *ndims = H5Sget_simple_extent_ndims(space);
    if (*ndims >= 1 && *ndims <= 2 && H5Sget_simple_extent_dims(space, dims, NULL) >= 0) {
      for (int d = 0; d < *ndims; d++) n *= dims[d];
      PetscCall(PetscMalloc(elsize * (size_t)(n + 1), buf));
      if (H5Dread(dset, memtype, H5S_ALL, H5S_ALL, H5P_DEFAULT, *buf) >= 0) *ok = PETSC_TRUE;
    }
    (void)H5Sclose(space);
  }
  (void)H5Dclose(dset);
  PetscFunctionReturn(0);
}

static PetscBool ReadAttrDouble(hid_t obj, const char *name, double *v)
{
  hid_t  a = H5Aopen(obj, name, H5P_DEFAULT);
  herr_t e;
  if (a < 0) return PETSC_FALSE;
  e = H5Aread(a, H5T_NATIVE_DOUBLE, v);
  (void)H5Aclose(a);
  return e >= 0 ? PETSC_TRUE : PETSC_FALSE;
}

static PetscBool ReadAttrInt(hid_t obj, const char *name, int *v)
{
  hid_t  a = H5Aopen(obj, name, H5P_DEFAULT);
  herr_t e;
  if (a < 0) return PETSC_FALSE;
  e = H5Aread(a, H5T_NATIVE_INT, v);
  (void)H5Aclose(a);
  return e >= 0 ? PETSC_TRUE : PETSC_FALSE;
}

/* Whole file into a NUL-terminated buffer (NULL when it cannot be read). */
static PetscErrorCode Slurp(const char *path, char **text)
{
  FILE *f = fopen(path, "rb");
  long  n;

  PetscFunctionBeginUser;
  *text = NULL;
  if (!f) PetscFunctionReturn(0);
  if (fseek(f, 0, SEEK_END) == 0 && (n = ftell(f)) >= 0 && fseek(f, 0, SEEK_SET) == 0) {
    PetscCall(PetscMalloc1((size_t)n + 1, text));
    if (fread(*text, 1, (size_t)n, f) != (size_t)n) PetscCall(PetscFree(*text));
    else (*text)[n] = '\0';
  }
  (void)fclose(f);
  PetscFunctionReturn(0);
}

static int CountOccurrences(const char *s, const char *pat)
{
  int n = 0;
  for (const char *p = strstr(s, pat); p; p = strstr(p + 1, pat)) n++;
  return n;
}

static int RemoveEntry(const char *path, const struct stat *sb, int flag, struct FTW *ftw)
{
  (void)sb;
  (void)flag;
  (void)ftw;
  return remove(path);
}

/* Rank 0: check the mesh and the given steps in DIR/fields.h5. */
static PetscErrorCode CheckFile(const char *h5path, PetscInt nx, PetscInt nsteps, const PetscInt steps[], const PetscReal times[])
{
  const PetscInt nv = 4 * (nx + 1), ne = nx;
  hid_t          file;
  int            nd;
  hsize_t        dims[2];
  PetscBool      ok, good;
  double        *d;
  int64_t       *l;

  PetscFunctionBeginUser;
  file = H5Fopen(h5path, H5F_ACC_RDONLY, H5P_DEFAULT);
  TU_CHECK(file >= 0, "open %s read-only", h5path);
  if (file < 0) PetscFunctionReturn(0);

  PetscCall(ReadDataset(file, "/mesh/coordinates", H5T_NATIVE_DOUBLE, sizeof(double), &nd, dims, (void **)&d, &ok));
  TU_CHECK(ok && nd == 2 && dims[0] == (hsize_t)nv && dims[1] == 3, "/mesh/coordinates is %" PetscInt_FMT " x 3", nv);
  good = ok && nd == 2 && dims[0] == (hsize_t)nv && dims[1] == 3;
  for (PetscInt v = 0; good && v < nv; v++)
    for (PetscInt c = 0; c < 3; c++)
      if (d[3 * v + c] != (double)Coord(v, c, nx)) good = PETSC_FALSE;
  TU_CHECK(good, "/mesh/coordinates values exact");
  PetscCall(PetscFree(d));

  PetscCall(ReadDataset(file, "/mesh/hexahedra", H5T_NATIVE_INT64, sizeof(int64_t), &nd, dims, (void **)&l, &ok));
  good = ok && nd == 2 && dims[0] == (hsize_t)ne && dims[1] == 8;
  TU_CHECK(good, "/mesh/hexahedra is %" PetscInt_FMT " x 8", ne);
  for (PetscInt e = 0; good && e < ne; e++)
    for (PetscInt a = 0; a < 8; a++)
      if (l[8 * e + a] != (int64_t)Conn(e, a, nx)) good = PETSC_FALSE;
  TU_CHECK(good, "/mesh/hexahedra values exact");
  PetscCall(PetscFree(l));

  PetscCall(ReadDataset(file, "/mesh/node_ids", H5T_NATIVE_INT64, sizeof(int64_t), &nd, dims, (void **)&l, &ok));
  good = ok && nd == 1 && dims[0] == (hsize_t)nv;
  for (PetscInt v = 0; good && v < nv; v++)
    if (l[v] != (int64_t)NodeId(v)) good = PETSC_FALSE;
  TU_CHECK(good, "/mesh/node_ids: 1D, %" PetscInt_FMT " values exact", nv);
  PetscCall(PetscFree(l));

  PetscCall(ReadDataset(file, "/mesh/element_ids", H5T_NATIVE_INT64, sizeof(int64_t), &nd, dims, (void **)&l, &ok));
  good = ok && nd == 1 && dims[0] == (hsize_t)ne;
  for (PetscInt e = 0; good && e < ne; e++)
    if (l[e] != (int64_t)ElemId(e)) good = PETSC_FALSE;
  TU_CHECK(good, "/mesh/element_ids: 1D, %" PetscInt_FMT " values exact", ne);
  PetscCall(PetscFree(l));

  for (PetscInt s = 0; s < nsteps; s++) {
    char   g[64], p[128];
    hid_t  grp;
    double t = -1;
    int    is = -1;

    PetscCall(PetscSNPrintf(g, sizeof(g), "/steps/%06" PetscInt_FMT, steps[s]));
    grp = H5Gopen2(file, g, H5P_DEFAULT);
    TU_CHECK(grp >= 0, "group %s exists", g);
    if (grp < 0) continue;
    TU_CHECK(ReadAttrDouble(grp, "time", &t) && t == (double)times[s], "%s time attribute = %.17g (got %.17g)", g, (double)times[s], t);
    TU_CHECK(ReadAttrInt(grp, "step", &is) && is == (int)steps[s], "%s step attribute = %" PetscInt_FMT " (got %d)", g, steps[s], is);
    (void)H5Gclose(grp);

    PetscCall(PetscSNPrintf(p, sizeof(p), "%s/displacement", g));
    PetscCall(ReadDataset(file, p, H5T_NATIVE_DOUBLE, sizeof(double), &nd, dims, (void **)&d, &ok));
    good = ok && nd == 2 && dims[0] == (hsize_t)nv && dims[1] == 3;
    TU_CHECK(good, "%s is %" PetscInt_FMT " x 3", p, nv);
    for (PetscInt v = 0; good && v < nv; v++)
      for (PetscInt c = 0; c < 3; c++)
        if (d[3 * v + c] != (double)DispValue(v, c, steps[s])) good = PETSC_FALSE;
    TU_CHECK(good, "%s values exact", p);
    PetscCall(PetscFree(d));

    PetscCall(PetscSNPrintf(p, sizeof(p), "%s/eqps", g));
    PetscCall(ReadDataset(file, p, H5T_NATIVE_DOUBLE, sizeof(double), &nd, dims, (void **)&d, &ok));
    good = ok && nd == 1 && dims[0] == (hsize_t)ne;
    TU_CHECK(good, "%s is 1D of length %" PetscInt_FMT, p, ne);
    for (PetscInt e = 0; good && e < ne; e++)
      if (d[e] != (double)EqpsValue(e, steps[s])) good = PETSC_FALSE;
    TU_CHECK(good, "%s values exact", p);
    PetscCall(PetscFree(d));

    PetscCall(PetscSNPrintf(p, sizeof(p), "%s/stress", g));
    PetscCall(ReadDataset(file, p, H5T_NATIVE_DOUBLE, sizeof(double), &nd, dims, (void **)&d, &ok));
    good = ok && nd == 2 && dims[0] == (hsize_t)ne && dims[1] == 6;
    TU_CHECK(good, "%s is %" PetscInt_FMT " x 6", p, ne);
    for (PetscInt e = 0; good && e < ne; e++)
      for (PetscInt c = 0; c < 6; c++)
        if (d[6 * e + c] != (double)StressValue(e, c, steps[s])) good = PETSC_FALSE;
    TU_CHECK(good, "%s values exact", p);
    PetscCall(PetscFree(d));
  }
  TU_CHECK(H5Fclose(file) >= 0, "close %s", h5path);
  PetscFunctionReturn(0);
}

int main(int argc, char **argv)
{
  char         base[PETSC_MAX_PATH_LEN] = "", dir[PETSC_MAX_PATH_LEN], path[PETSC_MAX_PATH_LEN], tmp[PETSC_MAX_PATH_LEN];
  PetscBool    given = PETSC_FALSE, keep = PETSC_FALSE;
  PetscInt     nx = 2, nv, ne, vlo, vhi, elo, ehi;
  PetscMPIInt  size;
  OutputFields of = NULL;
  PetscReal   *X, *disp, *eqps, *stress;
  PetscInt    *nid, *conn, *eid;
  const PetscInt  steps[2] = {0, 5};
  const PetscReal times[2] = {0.1, 1.0 / 3.0};
  PetscErrorCode  ierr;
  int             total;

  PetscCall(PetscInitialize(&argc, &argv, NULL, NULL));
  PetscCallMPI(MPI_Comm_rank(PETSC_COMM_WORLD, &rank));
  PetscCallMPI(MPI_Comm_size(PETSC_COMM_WORLD, &size));
  PetscCall(PetscOptionsGetString(NULL, NULL, "-output_dir", base, sizeof(base), &given));
  PetscCall(PetscOptionsGetBool(NULL, NULL, "-keep", &keep, NULL));
  PetscCall(PetscOptionsGetInt(NULL, NULL, "-nx", &nx, NULL));
  PetscCheck(nx >= 1, PETSC_COMM_WORLD, PETSC_ERR_ARG_OUTOFRANGE, "-nx must be >= 1");
  if (!given) {
    int fail = 0;
    if (rank == 0) {
      PetscCall(PetscStrncpy(base, "/tmp/test_output_XXXXXX", sizeof(base)));
      if (!mkdtemp(base)) fail = 1;
    }
    PetscCallMPI(MPI_Bcast(&fail, 1, MPI_INT, 0, PETSC_COMM_WORLD));
    PetscCheck(!fail, PETSC_COMM_WORLD, PETSC_ERR_FILE_OPEN, "mkdtemp failed under /tmp");
    PetscCallMPI(MPI_Bcast(base, sizeof(base), MPI_CHAR, 0, PETSC_COMM_WORLD));
    /* nested and not yet existing: exercises mkdir -p */
    PetscCall(PetscSNPrintf(dir, sizeof(dir), "%s/run/out", base));
  } else PetscCall(PetscStrncpy(dir, base, sizeof(dir)));
  if (rank == 0) printf("# output directory %s, %d rank(s), nx = %" PetscInt_FMT "\n", dir, (int)size, nx);

  /* the mesh, each rank holding a contiguous block of vertices and of cells */
  nv = 4 * (nx + 1);
  ne = nx;
  Block(nv, rank, size, &vlo, &vhi);
  Block(ne, rank, size, &elo, &ehi);
  PetscCall(PetscMalloc3(3 * (vhi - vlo) + 1, &X, (vhi - vlo) + 1, &nid, 3 * (vhi - vlo) + 1, &disp));
  PetscCall(PetscMalloc4(8 * (ehi - elo) + 1, &conn, (ehi - elo) + 1, &eid, (ehi - elo) + 1, &eqps, 6 * (ehi - elo) + 1, &stress));
  for (PetscInt v = vlo; v < vhi; v++) {
    for (PetscInt c = 0; c < 3; c++) X[3 * (v - vlo) + c] = Coord(v, c, nx);
    nid[v - vlo] = NodeId(v);
  }
  for (PetscInt e = elo; e < ehi; e++) {
    for (PetscInt a = 0; a < 8; a++) conn[8 * (e - elo) + a] = Conn(e, a, nx);
    eid[e - elo] = ElemId(e);
  }

  /* a stale index from an earlier run, which OutputFieldsCreate must remove */
  PetscCall(OutputEnsureDirectory(PETSC_COMM_WORLD, dir));
  PetscCall(PetscSNPrintf(path, sizeof(path), "%s/fields.xmf", dir));
  PetscCall(PetscSNPrintf(tmp, sizeof(tmp), "%s/fields.xmf.tmp", dir));
  if (rank == 0) {
    PetscCall(OutputWriteTextAtomic(path, "stale"));
    PetscCall(OutputWriteTextAtomic(tmp, "stale"));
  }
  PetscCall(OutputFieldsCreate(PETSC_COMM_WORLD, dir, &of));
  if (rank == 0) TU_CHECK(access(path, F_OK) != 0 && access(tmp, F_OK) != 0, "OutputFieldsCreate removes a stale fields.xmf and fields.xmf.tmp");
  PetscCall(OutputFieldsWriteMesh(of, vhi - vlo, vlo, nv, X, nid, ehi - elo, elo, ne, conn, eid));
  if (rank == 0) {
    char *xmf;
    PetscCall(Slurp(path, &xmf));
    TU_CHECK(xmf && CountOccurrences(xmf, "<Time ") == 0 && strstr(xmf, "TopologyType=\"Hexahedron\"") && !strstr(xmf, "Collection"), "after the mesh: fields.xmf holds the mesh alone");
    PetscCall(PetscFree(xmf));
  }

  for (PetscInt s = 0; s < 2; s++) {
    OutputField node[1], cell[2];

    for (PetscInt v = vlo; v < vhi; v++)
      for (PetscInt c = 0; c < 3; c++) disp[3 * (v - vlo) + c] = DispValue(v, c, steps[s]);
    for (PetscInt e = elo; e < ehi; e++) {
      eqps[e - elo] = EqpsValue(e, steps[s]);
      for (PetscInt c = 0; c < 6; c++) stress[6 * (e - elo) + c] = StressValue(e, c, steps[s]);
    }
    node[0].name  = "displacement";
    node[0].ncomp = 3;
    node[0].data  = disp;
    cell[0].name  = "eqps";
    cell[0].ncomp = 1;
    cell[0].data  = eqps;
    cell[1].name  = "stress";
    cell[1].ncomp = 6;
    cell[1].data  = stress;
    PetscCall(OutputFieldsWriteStep(of, steps[s], times[s], 1, node, 2, cell));
  }

  /* misuse fails on every rank, before anything is written */
  PetscCall(PetscPushErrorHandler(PetscReturnErrorHandler, NULL));
  {
    OutputField bad = {"a/b", 1, eqps};
    OutputField dup = {"eqps", 1, eqps};
    ierr            = OutputFieldsWriteStep(of, steps[1], 2.0, 0, NULL, 1, &dup);
    CHECK_ALL(ierr != 0, "writing step %" PetscInt_FMT " twice is an error", steps[1]);
    ierr = OutputFieldsWriteStep(of, 7, 2.0, 0, NULL, 1, &bad);
    CHECK_ALL(ierr != 0, "a field name with '/' is an error");
    ierr = OutputFieldsWriteMesh(of, vhi - vlo, vlo, nv, X, nid, ehi - elo, elo, ne, conn, eid);
    CHECK_ALL(ierr != 0, "writing the mesh twice is an error");
  }
  PetscCall(PetscSNPrintf(tmp, sizeof(tmp), "%s/fields.h5/sub", dir));
  ierr = OutputEnsureDirectory(PETSC_COMM_WORLD, tmp);
  CHECK_ALL(ierr != 0, "OutputEnsureDirectory under a regular file is an error");
  ierr = OutputWriteTextAtomic("/nonexistent-dir-of-test_output/x.txt", "x");
  CHECK_ALL(ierr != 0, "OutputWriteTextAtomic into a missing directory is an error");
  PetscCall(PetscPopErrorHandler());
  PetscCall(OutputFieldsDestroy(&of));
  CHECK_ALL(of == NULL, "OutputFieldsDestroy clears the handle");

  if (rank == 0) {
    char *xmf, *note;
    char  h5path[PETSC_MAX_PATH_LEN], tpath[PETSC_MAX_PATH_LEN];

    PetscCall(PetscSNPrintf(h5path, sizeof(h5path), "%s/fields.h5", dir));
    PetscCall(CheckFile(h5path, nx, 2, steps, times));

    PetscCall(Slurp(path, &xmf));
    TU_CHECK(xmf != NULL, "%s exists", path);
    if (xmf) {
      TU_CHECK(CountOccurrences(xmf, "<Time ") == 2, "fields.xmf has 2 <Time entries (%d)", CountOccurrences(xmf, "<Time "));
      TU_CHECK(strstr(xmf, "Hexahedron") != NULL, "fields.xmf has a Hexahedron topology");
      TU_CHECK(strstr(xmf, "Version=\"2.0\"") && strstr(xmf, "CollectionType=\"Temporal\""), "fields.xmf is XDMF 2 with a temporal collection");
      TU_CHECK(strstr(xmf, "<Time Value=\"0.10000000000000001\"") && strstr(xmf, "<Time Value=\"0.33333333333333331\""), "fields.xmf times printed with %%.17g");
      TU_CHECK(CountOccurrences(xmf, ">fields.h5:/mesh/hexahedra<") == 2 && CountOccurrences(xmf, ">fields.h5:/mesh/coordinates<") == 2, "fields.xmf refers to the mesh by a relative file name");
      TU_CHECK(strstr(xmf, dir) == NULL, "fields.xmf holds no absolute path");
      TU_CHECK(strstr(xmf, ">fields.h5:/steps/000005/displacement<") && strstr(xmf, "Center=\"Node\"") && strstr(xmf, "AttributeType=\"Vector\""), "fields.xmf: node vector attribute");
      TU_CHECK(strstr(xmf, ">fields.h5:/steps/000005/eqps<") && strstr(xmf, "Center=\"Cell\"") && strstr(xmf, "AttributeType=\"Scalar\""), "fields.xmf: cell scalar attribute");
      TU_CHECK(CountOccurrences(xmf, "<Attribute ") == 6, "fields.xmf: 3 attributes per step");
      TU_CHECK(CountOccurrences(xmf, "</Grid>") == 3 && CountOccurrences(xmf, "</Attribute>") == 6 && strstr(xmf, "</Xdmf>"), "fields.xmf elements closed");
    }
    PetscCall(PetscFree(xmf));
    PetscCall(PetscSNPrintf(tpath, sizeof(tpath), "%s.tmp", path));
    TU_CHECK(access(tpath, F_OK) != 0, "no leftover %s", tpath);

    PetscCall(PetscSNPrintf(tpath, sizeof(tpath), "%s/note.txt", dir));
    ierr = OutputWriteTextAtomic(tpath, "first\n");
    ierr = ierr ? ierr : OutputWriteTextAtomic(tpath, "hello, atomic\n");
    PetscCall(Slurp(tpath, &note));
    TU_CHECK(!ierr && note && !strcmp(note, "hello, atomic\n"), "OutputWriteTextAtomic replaces the content");
    PetscCall(PetscFree(note));
    PetscCall(PetscStrlcat(tpath, ".tmp", sizeof(tpath)));
    TU_CHECK(access(tpath, F_OK) != 0, "OutputWriteTextAtomic leaves no .tmp");
  }

  PetscCall(PetscFree3(X, nid, disp));
  PetscCall(PetscFree4(conn, eid, eqps, stress));
  PetscCallMPI(MPI_Barrier(PETSC_COMM_WORLD));
  if (rank == 0 && !given && !keep) (void)nftw(base, RemoveEntry, 16, FTW_DEPTH | FTW_PHYS);

  /* same exit code on every rank */
  PetscCallMPI(MPI_Allreduce(&tu_failed, &total, 1, MPI_INT, MPI_SUM, PETSC_COMM_WORLD));
  tu_failed = total;
  if (rank == 0) printf("# %d passed, %d failed\n", tu_passed, tu_failed);
  PetscCall(PetscFinalize());
  TU_RETURN();
}
