/* Unit tests of src/meshgen.c: box and O-grid blank generators, .inp reader and its errors.
   Run from the repository root (the decks are read from tests/data/). */
#include <stdlib.h> /* qsort */
#include <string.h>
#include <petscsys.h>
#include "meshgen.h"
#include "testutil.h"
#include "testcapture.h"

#define DATA "tests/data/"

/* ---------------------------------------------------------------- helpers (independent of meshgen.c) */
static const double Ref[8][3] = {
  {-1, -1, -1},
  {1,  -1, -1},
  {1,  1,  -1},
  {-1, 1,  -1},
  {-1, -1, 1 },
  {1,  -1, 1 },
  {1,  1,  1 },
  {-1, 1,  1 }
};

static double DetJ(const MeshData *m, PetscInt e, const double xi[3])
{
  double J[3][3] = {{0}};
  for (int a = 0; a < 8; a++) {
    const double *x  = &m->X[3 * m->conn[8 * e + a]];
    const double  d[3] = {0.125 * Ref[a][0] * (1 + Ref[a][1] * xi[1]) * (1 + Ref[a][2] * xi[2]), 0.125 * (1 + Ref[a][0] * xi[0]) * Ref[a][1] * (1 + Ref[a][2] * xi[2]), 0.125 * (1 + Ref[a][0] * xi[0]) * (1 + Ref[a][1] * xi[1]) * Ref[a][2]};
    for (int i = 0; i < 3; i++)
      for (int j = 0; j < 3; j++) J[i][j] += x[i] * d[j];
  }
  return J[0][0] * (J[1][1] * J[2][2] - J[1][2] * J[2][1]) - J[0][1] * (J[1][0] * J[2][2] - J[1][2] * J[2][0]) + J[0][2] * (J[1][0] * J[2][1] - J[1][1] * J[2][0]);
}

/* volume by 2x2x2 Gauss (exact for trilinear hexahedra), smallest det J at the Gauss points */
static PetscErrorCode MeshVolume(const MeshData *m, double *vol, double *mindet)
{
  const double g = 1.0 / sqrt(3.0);

  PetscFunctionBeginUser;
  *vol           = 0;
  *mindet        = 1e300;
  for (PetscInt e = 0; e < m->ne; e++)
    for (int q = 0; q < 8; q++) {
      const double xi[3] = {g * Ref[q][0], g * Ref[q][1], g * Ref[q][2]};
      const double d     = DetJ(m, e, xi);
      *vol += d;
      if (d < *mindet) *mindet = d;
    }
  PetscFunctionReturn(0);
}

/* smallest scaled Jacobian at the corners: det of the three unit edge vectors at each corner */
static PetscErrorCode MinScaledJacobian(const MeshData *m, double *qual)
{
  static const int nb[8][3] = {
    {1, 3, 4},
    {2, 0, 5},
    {3, 1, 6},
    {0, 2, 7},
    {7, 5, 0},
    {4, 6, 1},
    {5, 7, 2},
    {6, 4, 3}
  };
  double mn = 1;

  PetscFunctionBeginUser;
  for (PetscInt e = 0; e < m->ne; e++)
    for (int a = 0; a < 8; a++) {
      double        v[3][3];
      const double *x0 = &m->X[3 * m->conn[8 * e + a]];
      for (int k = 0; k < 3; k++) {
        const double *x1 = &m->X[3 * m->conn[8 * e + nb[a][k]]];
        double        n  = 0;
        for (int i = 0; i < 3; i++) n += (x1[i] - x0[i]) * (x1[i] - x0[i]);
        for (int i = 0; i < 3; i++) v[k][i] = (x1[i] - x0[i]) / sqrt(n);
      }
      const double d = v[0][0] * (v[1][1] * v[2][2] - v[1][2] * v[2][1]) - v[0][1] * (v[1][0] * v[2][2] - v[1][2] * v[2][0]) + v[0][2] * (v[1][0] * v[2][1] - v[1][1] * v[2][0]);
      if (d < mn) mn = d;
    }
  *qual = mn;
  PetscFunctionReturn(0);
}

static const MeshSet *FindSet(const MeshSet *sets, PetscInt n, const char *name)
{
  for (PetscInt s = 0; s < n; s++)
    if (!strcmp(sets[s].name, name)) return &sets[s];
  return NULL;
}
static PetscInt SetSize(const MeshSet *sets, PetscInt n, const char *name)
{
  const MeshSet *s = FindSet(sets, n, name);
  return s ? s->n : -1;
}
/* 1 when the entries are strictly increasing and lie in [0, n) */
static int SetSortedValid(const MeshSet *s, PetscInt n)
{
  if (!s) return 0;
  for (PetscInt i = 0; i < s->n; i++) {
    if (s->idx[i] < 0 || s->idx[i] >= n) return 0;
    if (i && s->idx[i] <= s->idx[i - 1]) return 0;
  }
  return 1;
}
static int SetEquals(const MeshSet *s, PetscInt n, const PetscInt *v)
{
  if (!s || s->n != n) return 0;
  for (PetscInt i = 0; i < n; i++)
    if (s->idx[i] != v[i]) return 0;
  return 1;
}

/* largest |coordinate dir - value| over a node set (or 1e300 when missing/empty) */
static double SetMaxDev(const MeshData *m, const char *name, int dir, double value)
{
  const MeshSet *s = FindSet(m->nsets, m->nnset, name);
  double         d = 0;
  if (!s || !s->n) return 1e300;
  for (PetscInt i = 0; i < s->n; i++) d = fmax(d, fabs(m->X[3 * s->idx[i] + dir] - value));
  return d;
}

/* faces: sorted vertex quadruples */
typedef struct {
  PetscInt v[4];
} Face;
static int CmpFace(const void *a, const void *b)
{
  const Face *f = a, *g = b;
  for (int i = 0; i < 4; i++)
    if (f->v[i] != g->v[i]) return f->v[i] < g->v[i] ? -1 : 1;
  return 0;
}
/* counts faces used once (boundary) and faces used more than twice (non-manifold) */
static PetscErrorCode FaceCounts(const MeshData *m, PetscInt *nbnd, PetscInt *nbad)
{
  static const int fv[6][4] = {
    {0, 1, 2, 3},
    {4, 5, 6, 7},
    {0, 1, 5, 4},
    {1, 2, 6, 5},
    {2, 3, 7, 6},
    {3, 0, 4, 7}
  };
  Face    *F;
  PetscInt n = 6 * m->ne;

  PetscFunctionBeginUser;
  PetscCall(PetscMalloc1(n, &F));
  for (PetscInt e = 0; e < m->ne; e++)
    for (int f = 0; f < 6; f++) {
      PetscInt *v = F[6 * e + f].v;
      for (int i = 0; i < 4; i++) v[i] = m->conn[8 * e + fv[f][i]];
      for (int i = 1; i < 4; i++)
        for (int j = i; j > 0 && v[j] < v[j - 1]; j--) {
          PetscInt t = v[j];
          v[j]       = v[j - 1];
          v[j - 1]   = t;
        }
    }
  qsort(F, (size_t)n, sizeof(Face), CmpFace);
  *nbnd = *nbad = 0;
  for (PetscInt i = 0; i < n;) {
    PetscInt j = i;
    while (j < n && !CmpFace(&F[i], &F[j])) j++;
    if (j - i == 1) (*nbnd)++;
    if (j - i > 2) (*nbad)++;
    i = j;
  }
  PetscCall(PetscFree(F));
  PetscFunctionReturn(0);
}

/* number of vertex pairs closer than tol, number of vertices used by no cell */
static PetscErrorCode VertexChecks(const MeshData *m, double tol, PetscInt *ndup, PetscInt *nunused)
{
  PetscBool *used;

  PetscFunctionBeginUser;
  PetscCall(PetscCalloc1(m->nv, &used));
  *ndup = *nunused = 0;
  for (PetscInt i = 0; i < m->nv; i++)
    for (PetscInt j = i + 1; j < m->nv; j++) {
      const double *a = &m->X[3 * i], *b = &m->X[3 * j];
      if (fabs(a[0] - b[0]) <= tol && fabs(a[1] - b[1]) <= tol && fabs(a[2] - b[2]) <= tol) (*ndup)++;
    }
  for (PetscInt k = 0; k < 8 * m->ne; k++) used[m->conn[k]] = PETSC_TRUE;
  for (PetscInt i = 0; i < m->nv; i++)
    if (!used[i]) (*nunused)++;
  PetscCall(PetscFree(used));
  PetscFunctionReturn(0);
}

/* the deck must fail with a non-zero code, a message containing both needles, and a zeroed m */
static PetscErrorCode ExpectInpError(const char *file, const char *needle1, const char *needle2)
{
  MeshData       m;
  PetscErrorCode ierr;

  PetscFunctionBeginUser;
  ErrMsg[0] = '\0';
  memset(&m, 0xff, sizeof(m));
  PetscCall(PetscPushErrorHandler(CaptureHandler, NULL));
  ierr = MeshDataReadInp(file, &m);
  PetscCall(PetscPopErrorHandler());
  TU_CHECK(ierr != 0, "%s: error code %d is non-zero", file, (int)ierr);
  TU_CHECK(strstr(ErrMsg, needle1) && strstr(ErrMsg, needle2), "%s: message names '%s' and '%s' [%s]", file, needle1, needle2, ErrMsg);
  TU_CHECK(m.nv == 0 && m.ne == 0 && !m.X && !m.conn && m.nnset == 0, "%s: output left empty (nv %d, ne %d)", file, (int)m.nv, (int)m.ne);
  if (!ierr) PetscCall(MeshDataDestroy(&m));
  PetscFunctionReturn(0);
}

static PetscErrorCode ExpectBlankError(PetscReal R, PetscReal t, PetscReal core, PetscInt nc, PetscInt nr, PetscInt nl, const char *needle)
{
  MeshData       m;
  PetscErrorCode ierr;

  PetscFunctionBeginUser;
  ErrMsg[0] = '\0';
  PetscCall(PetscPushErrorHandler(CaptureHandler, NULL));
  ierr = MeshDataCreateBlank(R, t, core, nc, nr, nl, PETSC_TRUE, &m);
  PetscCall(PetscPopErrorHandler());
  TU_CHECK(ierr != 0 && strstr(ErrMsg, needle), "blank R %g t %g core %g ncore %d nradial %d nlayers %d: error %d naming '%s' [%s]", (double)R, (double)t, (double)core, (int)nc, (int)nr, (int)nl, (int)ierr, needle, ErrMsg);
  if (!ierr) PetscCall(MeshDataDestroy(&m));
  PetscFunctionReturn(0);
}

/* ---------------------------------------------------------------- box */
static PetscErrorCode TestBox(void)
{
  const PetscReal lo[3] = {-1, 0, 0.5}, hi[3] = {1, 1, 3.5};
  const PetscInt  n[3]  = {2, 3, 4};
  MeshData        m;
  double          vol, mindet;
  PetscInt        nbnd, nbad, ndup, nunused, idok = 1;

  PetscFunctionBeginUser;
  PetscCall(MeshDataCreateBox(lo, hi, n, &m));
  TU_CHECK(m.nv == 60, "box: %d vertices (expected 3*4*5 = 60)", (int)m.nv);
  TU_CHECK(m.ne == 24, "box: %d cells (expected 2*3*4 = 24)", (int)m.ne);
  PetscCall(MeshVolume(&m, &vol, &mindet));
  TU_CHECK(tu_reldiff(vol, 2.0 * 1.0 * 3.0, 1e-300) < 1e-13, "box: volume %.15g (expected 6)", vol);
  TU_CHECK(fabs(mindet - (1.0 / 2) * (1.0 / 6) * (3.0 / 8)) < 1e-14, "box: det J %.15g at every Gauss point equals hx*hy*hz/8 = %.15g", mindet, (1.0 / 2) * (1.0 / 6) * (3.0 / 8));
  TU_CHECK(fabs(m.X[3 * 1 + 0] - 0.0) < 1e-15 && m.X[3 * 1 + 1] == 0 && m.X[3 * 1 + 2] == 0.5, "box: vertex 1 at (%g, %g, %g) (x fastest: expected (0, 0, 0.5))", m.X[3], m.X[4], m.X[5]);
  TU_CHECK(fabs(m.X[3 * 3 + 1] - 1.0 / 3) < 1e-15 && m.X[3 * 3 + 0] == -1, "box: vertex 3 at (%g, %g) (then y: expected (-1, 1/3))", m.X[9], m.X[10]);
  TU_CHECK(m.X[3 * 12 + 2] == 1.25 && m.X[3 * 59 + 0] == 1 && m.X[3 * 59 + 1] == 1 && m.X[3 * 59 + 2] == 3.5, "box: vertex 12 at z %g (expected 1.25), last vertex at (%g, %g, %g)", m.X[38], m.X[177], m.X[178], m.X[179]);
  TU_CHECK(m.conn[0] == 0 && m.conn[1] == 1 && m.conn[2] == 4 && m.conn[3] == 3 && m.conn[4] == 12 && m.conn[5] == 13 && m.conn[6] == 16 && m.conn[7] == 15, "box: first cell %d %d %d %d %d %d %d %d (expected 0 1 4 3 12 13 16 15)", (int)m.conn[0], (int)m.conn[1], (int)m.conn[2], (int)m.conn[3], (int)m.conn[4], (int)m.conn[5], (int)m.conn[6], (int)m.conn[7]);
  TU_CHECK(m.nnset == 6 && m.nelset == 1, "box: %d node sets (expected 6), %d element sets (expected 1)", (int)m.nnset, (int)m.nelset);
  TU_CHECK(SetSize(m.nsets, m.nnset, "xmin") == 20 && SetSize(m.nsets, m.nnset, "xmax") == 20, "box: xmin %d, xmax %d vertices (expected 20)", (int)SetSize(m.nsets, m.nnset, "xmin"), (int)SetSize(m.nsets, m.nnset, "xmax"));
  TU_CHECK(SetSize(m.nsets, m.nnset, "ymin") == 15 && SetSize(m.nsets, m.nnset, "ymax") == 15, "box: ymin %d, ymax %d vertices (expected 15)", (int)SetSize(m.nsets, m.nnset, "ymin"), (int)SetSize(m.nsets, m.nnset, "ymax"));
  TU_CHECK(SetSize(m.nsets, m.nnset, "zmin") == 12 && SetSize(m.nsets, m.nnset, "zmax") == 12, "box: zmin %d, zmax %d vertices (expected 12)", (int)SetSize(m.nsets, m.nnset, "zmin"), (int)SetSize(m.nsets, m.nnset, "zmax"));
  TU_CHECK(SetSize(m.elsets, m.nelset, "all") == 24 && SetSortedValid(FindSet(m.elsets, m.nelset, "all"), m.ne), "box: element set all has %d cells (expected 24)", (int)SetSize(m.elsets, m.nelset, "all"));
  {
    const char *nm[6]  = {"xmin", "xmax", "ymin", "ymax", "zmin", "zmax"};
    double      dev    = 0;
    int         sorted = 1;
    for (int s = 0; s < 6; s++) {
      dev = fmax(dev, SetMaxDev(&m, nm[s], s / 2, s % 2 ? hi[s / 2] : lo[s / 2]));
      sorted &= SetSortedValid(FindSet(m.nsets, m.nnset, nm[s]), m.nv);
    }
    TU_CHECK(dev == 0 && sorted, "box: node sets lie on their planes (largest deviation %g), sorted and unique (%d)", dev, sorted);
  }
  for (PetscInt v = 0; v < m.nv; v++) idok &= m.node_id[v] == v + 1;
  for (PetscInt e = 0; e < m.ne; e++) idok &= m.elem_id[e] == e + 1;
  TU_CHECK(idok, "box: node_id = 1..%d and elem_id = 1..%d (%d)", (int)m.nv, (int)m.ne, idok);
  PetscCall(FaceCounts(&m, &nbnd, &nbad));
  TU_CHECK(nbnd == 2 * (2 * 3 + 3 * 4 + 2 * 4) && nbad == 0, "box: %d boundary faces (expected 52), %d non-manifold", (int)nbnd, (int)nbad);
  PetscCall(VertexChecks(&m, 1e-12, &ndup, &nunused));
  TU_CHECK(ndup == 0 && nunused == 0, "box: %d duplicate vertices, %d unused (expected 0, 0)", (int)ndup, (int)nunused);
  PetscCall(MeshDataDestroy(&m));
  TU_CHECK(m.nv == 0 && m.X == NULL && m.nsets == NULL, "destroy: struct zeroed (nv %d)", (int)m.nv);

  { /* errors */
    const PetscInt  nbad0[3] = {2, 0, 4};
    const PetscReal hbad[3]  = {1, 1, 0.5};
    PetscErrorCode  ierr;
    PetscCall(PetscPushErrorHandler(CaptureHandler, NULL));
    ierr = MeshDataCreateBox(lo, hi, nbad0, &m);
    PetscCall(PetscPopErrorHandler());
    TU_CHECK(ierr != 0 && strstr(ErrMsg, "y direction"), "box: 0 cells in y gives error %d [%s]", (int)ierr, ErrMsg);
    PetscCall(PetscPushErrorHandler(CaptureHandler, NULL));
    ierr = MeshDataCreateBox(lo, hbad, n, &m);
    PetscCall(PetscPopErrorHandler());
    TU_CHECK(ierr != 0 && strstr(ErrMsg, "z direction"), "box: hi z 0.5 <= lo z 0.5 gives error %d [%s]", (int)ierr, ErrMsg);
  }
  PetscFunctionReturn(0);
}

/* ---------------------------------------------------------------- graded box */
static PetscErrorCode TestBoxGraded(void)
{
  const PetscReal lo[3] = {0, -1, 0}, hi[3] = {3, 1, 2};
  const PetscInt  n[3]  = {6, 1, 4};
  const PetscReal gr[3] = {10, 5, 0.125}; /* last cell over first: x 10, y (one cell) ignored, z 1/8 */
  MeshData        m;
  double          vol, mindet, ratio_dev = 0;
  PetscErrorCode  ierr;

  PetscFunctionBeginUser;
  PetscCall(MeshDataCreateBoxGraded(lo, hi, n, gr, &m));
  /* the grid lines along x (vertices 0..6 of the first row) and z (every (7*2)th vertex) */
  {
    double x[7], z[5], hx[6], hz[4];
    for (int i = 0; i <= 6; i++) x[i] = m.X[3 * i];
    for (int k = 0; k <= 4; k++) z[k] = m.X[3 * (7 * 2 * k) + 2];
    for (int i = 0; i < 6; i++) hx[i] = x[i + 1] - x[i];
    for (int k = 0; k < 4; k++) hz[k] = z[k + 1] - z[k];
    TU_CHECK(x[0] == 0 && x[6] == 3 && z[0] == 0 && z[4] == 2, "graded box: end lines exactly on the bounds (x %g..%g, z %g..%g)", x[0], x[6], z[0], z[4]);
    TU_CHECK(fabs(hx[5] / hx[0] - 10) < 1e-12 && fabs(hz[3] / hz[0] - 0.125) < 1e-12, "graded box: last over first cell %.15g along x (expected 10), %.15g along z (expected 0.125)", hx[5] / hx[0], hz[3] / hz[0]);
    /* sizes in geometric progression: q = 10^(1/5) along x, (1/8)^(1/3) = 1/2 along z */
    for (int i = 0; i < 5; i++) ratio_dev = PetscMax(ratio_dev, fabs(hx[i + 1] / hx[i] - pow(10, 0.2)));
    for (int k = 0; k < 3; k++) ratio_dev = PetscMax(ratio_dev, fabs(hz[k + 1] / hz[k] - 0.5));
    TU_CHECK(ratio_dev < 1e-12, "graded box: successive cells in the ratio q = r^(1/(n-1)) (largest deviation %g)", ratio_dev);
    TU_CHECK(fabs(hz[0] - 2 * 8.0 / 15) < 1e-14, "graded box: first z cell %.15g (expected 2 * 8/15 for sizes 8, 4, 2, 1)", hz[0]);
    TU_CHECK(m.X[3 * 7 + 1] == 1 && m.X[1] == -1, "graded box: a single cell spans its direction whatever the grading (y %g..%g)", m.X[1], m.X[3 * 7 + 1]);
  }
  PetscCall(MeshVolume(&m, &vol, &mindet));
  TU_CHECK(tu_reldiff(vol, 3.0 * 2.0 * 2.0, 1e-300) < 1e-13 && mindet > 0, "graded box: volume %.15g (expected 12), smallest det J %g > 0", vol, mindet);
  PetscCall(MeshDataDestroy(&m));
  { /* uniform grading repeats the plain box bit for bit */
    const PetscReal one[3] = {1, 1, 1};
    MeshData        a, b;
    int             same = 1;
    PetscCall(MeshDataCreateBox(lo, hi, n, &a));
    PetscCall(MeshDataCreateBoxGraded(lo, hi, n, one, &b));
    for (PetscInt i = 0; i < 3 * a.nv; i++) same = same && a.X[i] == b.X[i];
    TU_CHECK(same, "graded box: grading 1,1,1 gives the plain box's coordinates exactly");
    PetscCall(MeshDataDestroy(&a));
    PetscCall(MeshDataDestroy(&b));
  }
  { /* a grading that is not positive */
    const PetscReal bad[3] = {1, 0, 1};
    PetscCall(PetscPushErrorHandler(CaptureHandler, NULL));
    ierr = MeshDataCreateBoxGraded(lo, hi, n, bad, &m);
    PetscCall(PetscPopErrorHandler());
    TU_CHECK(ierr != 0 && strstr(ErrMsg, "grading") && strstr(ErrMsg, "y direction"), "graded box: grading 0 in y gives error %d [%s]", (int)ierr, ErrMsg);
  }
  PetscFunctionReturn(0);
}

/* ---------------------------------------------------------------- blank */
static PetscErrorCode CheckBlank(PetscReal R, PetscReal t, PetscReal core, PetscInt nc, PetscInt nr, PetscInt nl, PetscBool quarter, PetscBool verbose)
{
  MeshData       m;
  char           tag[128];
  const PetscInt nq2   = (nc + 1) * (nc + 1) + (2 * nc + 1) * nr;     /* points per quarter plane */
  const PetscInt n2    = quarter ? nq2 : 4 * nq2 - 4 * (nc + nr) - 3; /* seams shared, centre 4x */
  const PetscInt ncell = (nc * nc + 2 * nc * nr) * nl * (quarter ? 1 : 4);
  const PetscInt nseg  = (quarter ? 2 : 8) * nc;       /* chords along the rim */
  const double   theta = (quarter ? 0.5 : 2) * PETSC_PI / nseg; /* angle of one chord */
  const double   Apoly = 0.5 * nseg * R * R * sin(theta);    /* area of the polygon of rim vertices */
  const double   Aexact = (quarter ? 0.25 : 1) * PETSC_PI * R * R;
  double         vol, mindet, rimdev = 0, qual;
  PetscInt       nbnd, nbad, ndup, nunused, nrim_found = 0;

  PetscFunctionBeginUser;
  snprintf(tag, sizeof(tag), "blank %s R %g t %g core %g ncore %d nradial %d nlayers %d", quarter ? "quarter" : "full", (double)R, (double)t, (double)core, (int)nc, (int)nr, (int)nl);
  PetscCall(MeshDataCreateBlank(R, t, core, nc, nr, nl, quarter, &m));
  TU_CHECK(m.nv == n2 * (nl + 1), "%s: %d vertices (expected %d)", tag, (int)m.nv, (int)(n2 * (nl + 1)));
  TU_CHECK(m.ne == ncell, "%s: %d cells (expected %d)", tag, (int)m.ne, (int)ncell);
  PetscCall(MeshVolume(&m, &vol, &mindet));
  TU_CHECK(mindet > 0, "%s: smallest det J at the 8 Gauss points of every cell %.3g > 0", tag, mindet);
  TU_CHECK(tu_reldiff(vol, Apoly * t, 1e-300) < 1e-12, "%s: volume %.15g equals polygon area * t = %.15g (rel. diff %.2g < 1e-12)", tag, vol, Apoly * t, tu_reldiff(vol, Apoly * t, 1e-300));
  /* chordal error: the inscribed polygon misses a relative area 1 - sin(theta)/theta <= theta^2/6 */
  TU_CHECK(vol < Aexact * t && (Aexact * t - vol) / (Aexact * t) <= theta * theta / 6, "%s: volume %.10g vs %spi R^2 t = %.10g: rel. deficit %.3g within the chordal bound theta^2/6 = %.3g", tag, vol, quarter ? "1/4 " : "", Aexact * t, (Aexact * t - vol) / (Aexact * t), theta * theta / 6);
  PetscCall(MinScaledJacobian(&m, &qual));
  TU_CHECK(qual > 0.75, "%s: smallest scaled corner Jacobian %.3f > 0.75 (0.707 without the core bulge)", tag, qual);
  { /* rim */
    const MeshSet *s = FindSet(m.nsets, m.nnset, "rim");
    for (PetscInt i = 0; s && i < s->n; i++) rimdev = fmax(rimdev, fabs(hypot(m.X[3 * s->idx[i]], m.X[3 * s->idx[i] + 1]) - R));
    for (PetscInt v = 0; v < m.nv; v++)
      if (fabs(hypot(m.X[3 * v], m.X[3 * v + 1]) - R) < 1e-9 * R) nrim_found++;
    TU_CHECK(s && s->n == (nseg + (quarter ? 1 : 0)) * (nl + 1) && rimdev <= 1e-12 * R && SetSortedValid(s, m.nv), "%s: rim has %d vertices (expected %d), all at radius R within %.2g <= 1e-12 R", tag, s ? (int)s->n : -1, (int)((nseg + (quarter ? 1 : 0)) * (nl + 1)), rimdev);
    TU_CHECK(nrim_found == (s ? s->n : -2), "%s: %d vertices lie at r = R, all of them in rim", tag, (int)nrim_found);
  }
  TU_CHECK(SetSize(m.nsets, m.nnset, "top") == n2 && SetMaxDev(&m, "top", 2, t) == 0 && SetSortedValid(FindSet(m.nsets, m.nnset, "top"), m.nv), "%s: top has %d vertices (expected %d) at z = t", tag, (int)SetSize(m.nsets, m.nnset, "top"), (int)n2);
  TU_CHECK(SetSize(m.nsets, m.nnset, "bottom") == n2 && SetMaxDev(&m, "bottom", 2, 0) == 0, "%s: bottom has %d vertices (expected %d) at z = 0", tag, (int)SetSize(m.nsets, m.nnset, "bottom"), (int)n2);
  TU_CHECK(SetSize(m.nsets, m.nnset, "centre") == nl + 1 && SetMaxDev(&m, "centre", 0, 0) == 0 && SetMaxDev(&m, "centre", 1, 0) == 0, "%s: centre has %d vertices (expected %d) on the axis", tag, (int)SetSize(m.nsets, m.nnset, "centre"), (int)(nl + 1));
  if (quarter) {
    PetscInt nx0 = 0, ny0 = 0;
    for (PetscInt v = 0; v < m.nv; v++) {
      if (m.X[3 * v] == 0) nx0++;
      if (m.X[3 * v + 1] == 0) ny0++;
    }
    TU_CHECK(SetSize(m.nsets, m.nnset, "symx") == (nc + nr + 1) * (nl + 1) && SetMaxDev(&m, "symx", 0, 0) <= 1e-12 * R && nx0 == (nc + nr + 1) * (nl + 1), "%s: symx has %d vertices (expected %d) on x = 0; %d vertices have x = 0", tag, (int)SetSize(m.nsets, m.nnset, "symx"), (int)((nc + nr + 1) * (nl + 1)), (int)nx0);
    TU_CHECK(SetSize(m.nsets, m.nnset, "symy") == (nc + nr + 1) * (nl + 1) && SetMaxDev(&m, "symy", 1, 0) <= 1e-12 * R && ny0 == (nc + nr + 1) * (nl + 1), "%s: symy has %d vertices (expected %d) on y = 0; %d vertices have y = 0", tag, (int)SetSize(m.nsets, m.nnset, "symy"), (int)((nc + nr + 1) * (nl + 1)), (int)ny0);
    {
      double xmin = 1e300, ymin = 1e300;
      for (PetscInt v = 0; v < m.nv; v++) {
        xmin = fmin(xmin, m.X[3 * v]);
        ymin = fmin(ymin, m.X[3 * v + 1]);
      }
      TU_CHECK(xmin == 0 && ymin == 0, "%s: smallest x %g and y %g (expected 0, the quarter x, y >= 0)", tag, xmin, ymin);
    }
  } else {
    TU_CHECK(m.nnset == 4 && !FindSet(m.nsets, m.nnset, "symx"), "%s: %d node sets (expected 4: rim top bottom centre, no symmetry sets)", tag, (int)m.nnset);
  }
  TU_CHECK(SetSize(m.elsets, m.nelset, "all") == ncell, "%s: element set all has %d cells (expected %d)", tag, (int)SetSize(m.elsets, m.nelset, "all"), (int)ncell);
  PetscCall(FaceCounts(&m, &nbnd, &nbad));
  {
    const PetscInt nc2  = ncell / nl;
    const PetscInt expb = 2 * nc2 + nseg * nl + (quarter ? 2 * (nc + nr) * nl : 0);
    TU_CHECK(nbnd == expb && nbad == 0, "%s: %d boundary faces (expected %d: top, bottom, rim%s), %d non-manifold: the mesh is conforming", tag, (int)nbnd, (int)expb, quarter ? ", symmetry planes" : "", (int)nbad);
  }
  PetscCall(VertexChecks(&m, 1e-9 * R, &ndup, &nunused));
  TU_CHECK(ndup == 0 && nunused == 0, "%s: %d duplicate vertex coordinates (tol 1e-9 R), %d unused vertices (expected 0, 0)", tag, (int)ndup, (int)nunused);
  if (verbose) PetscCall(PetscPrintf(PETSC_COMM_SELF, "# %s: %d vertices, %d cells, volume %.10g, min scaled Jacobian %.3f\n", tag, (int)m.nv, (int)m.ne, vol, qual));
  PetscCall(MeshDataDestroy(&m));
  PetscFunctionReturn(0);
}

static PetscErrorCode TestBlank(void)
{
  PetscFunctionBeginUser;
  PetscCall(CheckBlank(2.0, 0.5, 0.4, 3, 4, 2, PETSC_TRUE, PETSC_TRUE));
  PetscCall(CheckBlank(2.0, 0.5, 0.4, 3, 4, 2, PETSC_FALSE, PETSC_TRUE));
  PetscCall(CheckBlank(1.0, 0.1, 0.5, 1, 1, 1, PETSC_TRUE, PETSC_FALSE));
  PetscCall(CheckBlank(1.0, 0.1, 0.5, 1, 1, 1, PETSC_FALSE, PETSC_FALSE));
  PetscCall(CheckBlank(50.0, 1.2, 0.7, 8, 2, 3, PETSC_FALSE, PETSC_TRUE));
  PetscCall(CheckBlank(50.0, 1.2, 0.1, 4, 6, 1, PETSC_TRUE, PETSC_TRUE));
  PetscCall(CheckBlank(50.0, 1.2, 0.35, 6, 8, 4, PETSC_FALSE, PETSC_TRUE));
  PetscCall(ExpectBlankError(-1, 1, 0.4, 2, 2, 1, "radius"));
  PetscCall(ExpectBlankError(1, 0, 0.4, 2, 2, 1, "thickness"));
  PetscCall(ExpectBlankError(1, 1, 1.2, 2, 2, 1, "core fraction 1.2 must lie in (0,1)"));
  PetscCall(ExpectBlankError(1, 1, 0, 2, 2, 1, "must lie in (0,1)"));
  PetscCall(ExpectBlankError(1, 1, 0.75, 2, 2, 1, "1/sqrt(2)"));
  PetscCall(ExpectBlankError(1, 1, 0.4, 0, 2, 1, "ncore 0"));
  PetscCall(ExpectBlankError(1, 1, 0.4, 2, 0, 1, "nradial 0"));
  PetscCall(ExpectBlankError(1, 1, 0.4, 2, 2, 0, "nlayers 0"));
  PetscFunctionReturn(0);
}

/* ---------------------------------------------------------------- .inp */
static PetscErrorCode TestInpTwoHex(void)
{
  MeshData       m;
  double         vol, mindet;
  const PetscInt ids[12]   = {101, 102, 103, 111, 112, 113, 201, 202, 203, 211, 212, 213};
  const PetscInt conn0[8]  = {0, 1, 4, 3, 6, 7, 10, 9}, conn1[8] = {1, 2, 5, 4, 7, 8, 11, 10};
  const PetscInt left[4]   = {0, 3, 6, 9}, right[4] = {2, 5, 8, 11}, bottom[6] = {0, 1, 2, 3, 4, 5};
  const PetscInt block[2]  = {0, 1}, second[1] = {1};
  int            ok        = 1;
  PetscInt       nbnd, nbad;

  PetscFunctionBeginUser;
  PetscCall(MeshDataReadInp(DATA "two_hex.inp", &m));
  TU_CHECK(m.nv == 12 && m.ne == 2, "two_hex: %d nodes, %d elements (expected 12, 2)", (int)m.nv, (int)m.ne);
  for (int i = 0; i < 12; i++) ok &= m.node_id[i] == ids[i];
  TU_CHECK(ok, "two_hex: node ids kept in deck order (node_id[0] %d, node_id[11] %d)", (int)m.node_id[0], (int)m.node_id[11]);
  TU_CHECK(m.elem_id[0] == 20 && m.elem_id[1] == 7, "two_hex: element ids %d %d (expected 20 7, deck order)", (int)m.elem_id[0], (int)m.elem_id[1]);
  ok = 1;
  for (int a = 0; a < 8; a++) ok &= m.conn[a] == conn0[a] && m.conn[8 + a] == conn1[a];
  TU_CHECK(ok, "two_hex: connectivity mapped to 0-based indices (element 7 read over a continuation line: %d %d %d %d %d %d %d %d)", (int)m.conn[8], (int)m.conn[9], (int)m.conn[10], (int)m.conn[11], (int)m.conn[12], (int)m.conn[13], (int)m.conn[14], (int)m.conn[15]);
  TU_CHECK(m.X[3 * 2 + 0] == 2 && m.X[3 * 9 + 1] == 1 && m.X[3 * 9 + 2] == 1, "two_hex: node 103 at x %g, node 211 at (y, z) = (%g, %g)", m.X[6], m.X[28], m.X[29]);
  PetscCall(MeshVolume(&m, &vol, &mindet));
  TU_CHECK(fabs(vol - 2) < 1e-14 && fabs(mindet - 0.125) < 1e-15, "two_hex: volume %.15g (expected 2), det J %.15g (expected 1/8)", vol, mindet);
  PetscCall(FaceCounts(&m, &nbnd, &nbad));
  TU_CHECK(nbnd == 10, "two_hex: %d boundary faces (expected 10: the elements share one face)", (int)nbnd);
  TU_CHECK(m.nnset == 3 && m.nelset == 2, "two_hex: %d node sets, %d element sets (expected 3, 2)", (int)m.nnset, (int)m.nelset);
  TU_CHECK(SetEquals(FindSet(m.nsets, m.nnset, "Left"), 4, left) && SetEquals(FindSet(m.nsets, m.nnset, "Right"), 4, right), "two_hex: NSET Left = {0,3,6,9}, Right = {2,5,8,11} (sizes %d %d)", (int)SetSize(m.nsets, m.nnset, "Left"), (int)SetSize(m.nsets, m.nnset, "Right"));
  TU_CHECK(SetEquals(FindSet(m.nsets, m.nnset, "Bottom"), 6, bottom), "two_hex: NSET Bottom from GENERATE = {0..5} (size %d)", (int)SetSize(m.nsets, m.nnset, "Bottom"));
  TU_CHECK(SetEquals(FindSet(m.elsets, m.nelset, "Block"), 2, block) && SetEquals(FindSet(m.elsets, m.nelset, "Second"), 1, second), "two_hex: ELSET Block (from *ELEMENT) = {0,1} size %d, ELSET Second = {1} size %d", (int)SetSize(m.elsets, m.nelset, "Block"), (int)SetSize(m.elsets, m.nelset, "Second"));
  PetscCall(MeshDataDestroy(&m));
  PetscFunctionReturn(0);
}

static PetscErrorCode TestInpFeatures(void)
{
  MeshData       m;
  double         vol, mindet;
  const PetscInt base[4] = {0, 1, 2, 3}, top[4] = {4, 5, 6, 7}, body[1] = {0};

  PetscFunctionBeginUser;
  PetscCall(MeshDataReadInp(DATA "features.inp", &m));
  TU_CHECK(m.nv == 8 && m.ne == 1 && m.elem_id[0] == 1000, "features: %d nodes, %d elements, element id %d (expected 8, 1, 1000)", (int)m.nv, (int)m.ne, (int)(m.ne ? m.elem_id[0] : -1));
  TU_CHECK(m.X[3 * 1 + 0] == 2 && m.X[3 * 1 + 2] == 0 && m.X[3 * 3 + 2] == 0 && m.X[3 * 7 + 0] == 0 && m.X[3 * 6 + 2] == 1.5, "features: 2.0D0 read as %g, missing z as %g, empty x as %g, 15e-1 as %g", m.X[3], m.X[5], m.X[21], m.X[20]);
  PetscCall(MeshVolume(&m, &vol, &mindet));
  TU_CHECK(fabs(vol - 3) < 1e-14, "features: volume %.15g (expected 2*1*1.5 = 3)", vol);
  TU_CHECK(m.nnset == 2 && SetEquals(FindSet(m.nsets, m.nnset, "Base"), 4, base), "features: %d node sets; Base from *NODE, NSET= has %d nodes (expected 2 sets, 4 nodes)", (int)m.nnset, (int)SetSize(m.nsets, m.nnset, "Base"));
  TU_CHECK(SetEquals(FindSet(m.nsets, m.nnset, "Top"), 4, top), "features: Top (GENERATE 50,80,10 merged with TOP 50,50) has %d unique nodes (expected 4)", (int)SetSize(m.nsets, m.nnset, "Top"));
  TU_CHECK(m.nelset == 1 && SetEquals(FindSet(m.elsets, m.nelset, "Body"), 1, body), "features: %d element sets; quoted \"Body\" merged with body has %d element (expected 1, 1)", (int)m.nelset, (int)SetSize(m.elsets, m.nelset, "Body"));
  PetscCall(MeshDataDestroy(&m));
  PetscFunctionReturn(0);
}

static PetscErrorCode TestInpErrors(void)
{
  PetscFunctionBeginUser;
  PetscCall(ExpectInpError(DATA "no_such_deck.inp", "cannot open mesh file 'tests/data/no_such_deck.inp'", "no_such_deck"));
  PetscCall(ExpectInpError(DATA "bad_type.inp", "line 11", "C3D20"));
  PetscCall(ExpectInpError(DATA "bad_truncated.inp", "bad_truncated.inp', line 12", "truncated"));
  PetscCall(ExpectInpError(DATA "bad_truncated_eof.inp", "line 12", "truncated"));
  PetscCall(ExpectInpError(DATA "bad_undefined_node.inp", "line 12", "undefined node id 99"));
  PetscCall(ExpectInpError(DATA "bad_inverted.inp", "line 12", "element id 1 is inverted or degenerate"));
  PetscCall(ExpectInpError(DATA "bad_degenerate.inp", "line 12", "element id 1 is inverted or degenerate"));
  PetscCall(ExpectInpError(DATA "bad_set_missing.inp", "line 15", "names missing node id 99"));
  PetscCall(ExpectInpError(DATA "bad_elset_missing.inp", "line 14", "names missing element id 5"));
  PetscCall(ExpectInpError(DATA "bad_unreferenced.inp", "line 11", "node id 9 is referenced by no element"));
  PetscCall(ExpectInpError(DATA "bad_duplicate_node.inp", "line 11", "duplicate node id 3"));
  PetscCall(ExpectInpError(DATA "bad_duplicate_element.inp", "line 13", "duplicate element id 1"));
  PetscCall(ExpectInpError(DATA "bad_nonnumeric.inp", "line 6", "'one'"));
  PetscCall(ExpectInpError(DATA "bad_node_values.inp", "line 10", "more than 4 values"));
  PetscCall(ExpectInpError(DATA "bad_no_elements.inp", "bad_no_elements.inp", "no elements"));
  { /* how mesh.c consumes the errors: silent handler, then PetscErrorMessage() for the text */
    MeshData       m;
    PetscErrorCode ierr;
    char          *specific = NULL;
    PetscCall(PetscPushErrorHandler(PetscReturnErrorHandler, NULL));
    ierr = MeshDataReadInp(DATA "bad_undefined_node.inp", &m);
    PetscCall(PetscPopErrorHandler());
    PetscCall(PetscErrorMessage(ierr, NULL, &specific));
    TU_CHECK(ierr == PETSC_ERR_FILE_UNEXPECTED && specific && strstr(specific, "line 12: element id 1 references undefined node id 99"), "silent handler: error %d, PetscErrorMessage gives [%s]", (int)ierr, specific ? specific : "(null)");
  }
  PetscFunctionReturn(0);
}

int main(int argc, char **argv)
{
  PetscCall(PetscInitialize(&argc, &argv, NULL, NULL));
  PetscCall(TestBox());
  PetscCall(TestBoxGraded());
  PetscCall(TestBlank());
  PetscCall(TestInpTwoHex());
  PetscCall(TestInpFeatures());
  PetscCall(TestInpErrors());
  PetscCall(PetscPrintf(PETSC_COMM_SELF, "# %d passed, %d failed\n", tu_passed, tu_failed));
  PetscCall(PetscFinalize());
  TU_RETURN();
}
