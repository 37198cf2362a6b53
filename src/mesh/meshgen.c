/* Serial mesh sources on plain arrays (rank 0 only): structured box, O-grid circular blank,
   and an Abaqus-style .inp reader. See include/meshgen.h for the interface. */
#include <ctype.h>
#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "meshgen.h"
#include "element_hex8.h"

/* Bulge of the core's outer edges towards the rim (O-grid of the blank). In core coordinates
   (u,v) in [0,1]^2 a core vertex sits at x = a u (1 + B (1 - v^2)), y = a v (1 + B (1 - u^2)):
   the edge x = a becomes a parabola through the corner (a,a) whose midpoint (v = 0) is pushed to
   x = a (1 + B), and the tangent at the corner turns by atan(2B). B = tan(15 deg)/2 turns it by
   15 degrees, so the core cell and the two ring cells meeting at a core corner all get 120
   degree angles there instead of 90/135/135 with straight edges. */
#define BLANK_BULGE 0.13397459621556135 /* tan(pi/12)/2 */

/* ------------------------------------------------------------------------------------------ */
/* hex8 geometry                                                                               */
/* ------------------------------------------------------------------------------------------ */
/* ok = PETSC_TRUE when det J > 0 (relative to the cell size) at the 8 corners and the 8 Gauss
   points of the hexahedron with vertices conn[0..7] in X (the element's own check,
   hex8_min_jacobian) */
static PetscErrorCode HexIsValid(const PetscReal *X, const PetscInt *conn, PetscBool *ok)
{
  static const PetscInt edges[12][2] = {
    {0, 1},
    {1, 2},
    {2, 3},
    {3, 0},
    {4, 5},
    {5, 6},
    {6, 7},
    {7, 4},
    {0, 4},
    {1, 5},
    {2, 6},
    {3, 7}
  };
  double    xe[8][3];
  PetscReal L = 0, tol;

  PetscFunctionBeginUser;
  for (PetscInt a = 0; a < 8; a++)
    for (PetscInt i = 0; i < 3; i++) xe[a][i] = X[3 * conn[a] + i];
  for (PetscInt e = 0; e < 12; e++) {
    PetscReal d2 = 0;
    for (PetscInt i = 0; i < 3; i++) d2 += (xe[edges[e][1]][i] - xe[edges[e][0]][i]) * (xe[edges[e][1]][i] - xe[edges[e][0]][i]);
    L = PetscMax(L, PetscSqrtReal(d2));
  }
  tol = 1e-10 * (0.5 * L) * (0.5 * L) * (0.5 * L); /* det J of a cube of side L is (L/2)^3 */
  *ok = (L > 0 && !PetscIsInfOrNanReal(L) && hex8_min_jacobian((const double(*)[3])xe) > tol) ? PETSC_TRUE : PETSC_FALSE;
  PetscFunctionReturn(0);
}

/* ------------------------------------------------------------------------------------------ */
/* sets                                                                                        */
/* ------------------------------------------------------------------------------------------ */
static PetscErrorCode SetFromFlags(MeshSet *s, const char *name, PetscInt n, const PetscBool *flag)
{
  PetscInt cnt = 0;

  PetscFunctionBeginUser;
  PetscCall(PetscStrncpy(s->name, name, sizeof(s->name)));
  for (PetscInt i = 0; i < n; i++)
    if (flag[i]) cnt++;
  s->n = cnt;
  PetscCall(PetscMalloc1(cnt, &s->idx));
  cnt = 0;
  for (PetscInt i = 0; i < n; i++)
    if (flag[i]) s->idx[cnt++] = i;
  PetscFunctionReturn(0);
}

static PetscErrorCode SetAll(MeshSet *s, const char *name, PetscInt n)
{
  PetscFunctionBeginUser;
  PetscCall(PetscStrncpy(s->name, name, sizeof(s->name)));
  s->n = n;
  PetscCall(PetscMalloc1(n, &s->idx));
  for (PetscInt i = 0; i < n; i++) s->idx[i] = i;
  PetscFunctionReturn(0);
}

/* vertices whose coordinate dir lies within tol of value */
static PetscErrorCode SetFromPlane(MeshSet *s, const char *name, PetscInt nv, const PetscReal *X, PetscInt dir, PetscReal value, PetscReal tol, PetscBool *work)
{
  PetscFunctionBeginUser;
  for (PetscInt v = 0; v < nv; v++) work[v] = PetscAbsReal(X[3 * v + dir] - value) <= tol ? PETSC_TRUE : PETSC_FALSE;
  PetscCall(SetFromFlags(s, name, nv, work));
  PetscFunctionReturn(0);
}

PetscErrorCode MeshDataDestroy(MeshData *m)
{
  PetscFunctionBeginUser;
  if (!m) PetscFunctionReturn(0);
  PetscCall(PetscFree(m->X));
  PetscCall(PetscFree(m->conn));
  PetscCall(PetscFree(m->node_id));
  PetscCall(PetscFree(m->elem_id));
  for (PetscInt s = 0; s < m->nnset; s++) PetscCall(PetscFree(m->nsets[s].idx));
  for (PetscInt s = 0; s < m->nelset; s++) PetscCall(PetscFree(m->elsets[s].idx));
  PetscCall(PetscFree(m->nsets));
  PetscCall(PetscFree(m->elsets));
  PetscCall(PetscMemzero(m, sizeof(*m)));
  PetscFunctionReturn(0);
}

/* allocate the arrays of m for nv vertices and ne cells, ids 1..n */
static PetscErrorCode MeshDataAlloc(MeshData *m, PetscInt nv, PetscInt ne)
{
  PetscFunctionBeginUser;
  m->nv = nv;
  m->ne = ne;
  PetscCall(PetscMalloc1(3 * nv, &m->X));
  PetscCall(PetscMalloc1(8 * ne, &m->conn));
  PetscCall(PetscMalloc1(nv, &m->node_id));
  PetscCall(PetscMalloc1(ne, &m->elem_id));
  for (PetscInt v = 0; v < nv; v++) m->node_id[v] = v + 1;
  for (PetscInt e = 0; e < ne; e++) m->elem_id[e] = e + 1;
  PetscFunctionReturn(0);
}

/* ------------------------------------------------------------------------------------------ */
/* box                                                                                         */
/* ------------------------------------------------------------------------------------------ */
PetscErrorCode MeshDataCreateBox(const PetscReal lo[3], const PetscReal hi[3], const PetscInt n[3], MeshData *m)
{
  const PetscReal one[3] = {1, 1, 1};
  PetscFunctionBeginUser;
  PetscCall(MeshDataCreateBoxGraded(lo, hi, n, one, m));
  PetscFunctionReturn(0);
}

/* the coordinate of grid line i of n on [lo, hi] with geometric grading r (the last cell's size
   over the first's): the cell sizes h_k = h_0 q^k, q = r^(1/(n-1)), so that
   x_i = lo + (hi - lo) (q^i - 1)/(q^n - 1); uniform for r = 1 (or n = 1). The end lines are
   exactly lo and hi. */
static PetscReal GradedLine(PetscReal lo, PetscReal hi, PetscInt i, PetscInt n, PetscReal r)
{
  if (i == 0) return lo;
  if (i == n) return hi;
  if (r == 1 || n == 1) return lo + (hi - lo) * (PetscReal)i / (PetscReal)n;
  {
    const PetscReal q = PetscPowReal(r, 1.0 / (PetscReal)(n - 1));
    return lo + (hi - lo) * expm1((double)i * log(q)) / expm1((double)n * log(q));
  }
}

PetscErrorCode MeshDataCreateBoxGraded(const PetscReal lo[3], const PetscReal hi[3], const PetscInt n[3], const PetscReal grading[3], MeshData *m)
{
  const char *dname = "xyz";
  const char *pname[3][2] = {
    {"xmin", "xmax"},
    {"ymin", "ymax"},
    {"zmin", "zmax"}
  };
  PetscInt   nx, ny, nz, nv, ne;
  PetscInt64 nv64, ne64;
  PetscBool *work;

  PetscFunctionBeginUser;
  PetscCheck(m, PETSC_COMM_SELF, PETSC_ERR_ARG_NULL, "box: output MeshData pointer is NULL");
  PetscCall(PetscMemzero(m, sizeof(*m)));
  for (PetscInt d = 0; d < 3; d++) {
    PetscCheck(n[d] >= 1, PETSC_COMM_SELF, PETSC_ERR_ARG_OUTOFRANGE, "box: number of cells %" PetscInt_FMT " in the %c direction (-box_cells) must be >= 1", n[d], dname[d]);
    PetscCheck(!PetscIsInfOrNanReal(lo[d]) && !PetscIsInfOrNanReal(hi[d]) && hi[d] > lo[d], PETSC_COMM_SELF, PETSC_ERR_ARG_OUTOFRANGE, "box: upper bound %g (-box_upper) must exceed lower bound %g (-box_lower) in the %c direction", (double)hi[d], (double)lo[d], dname[d]);
    PetscCheck(grading[d] > 0 && PetscIsNormalReal(grading[d]), PETSC_COMM_SELF, PETSC_ERR_ARG_OUTOFRANGE, "box: grading %g in the %c direction (-box_grading) must be positive", (double)grading[d], dname[d]);
  }
  nx   = n[0];
  ny   = n[1];
  nz   = n[2];
  nv64 = (PetscInt64)(nx + 1) * (ny + 1) * (nz + 1);
  ne64 = (PetscInt64)nx * ny * nz;
  PetscCheck(8 * ne64 < PETSC_MAX_INT && 3 * nv64 < PETSC_MAX_INT, PETSC_COMM_SELF, PETSC_ERR_ARG_OUTOFRANGE, "box: %" PetscInt_FMT " x %" PetscInt_FMT " x %" PetscInt_FMT " cells overflow PetscInt", nx, ny, nz);
  nv = (PetscInt)nv64;
  ne = (PetscInt)ne64;
  PetscCall(MeshDataAlloc(m, nv, ne));
  for (PetscInt k = 0; k <= nz; k++)
    for (PetscInt j = 0; j <= ny; j++)
      for (PetscInt i = 0; i <= nx; i++) {
        const PetscInt  v     = i + (nx + 1) * (j + (ny + 1) * k);
        const PetscInt  ijk[3] = {i, j, k};
        for (PetscInt d = 0; d < 3; d++) m->X[3 * v + d] = GradedLine(lo[d], hi[d], ijk[d], n[d], grading[d]);
      }
  for (PetscInt k = 0; k < nz; k++)
    for (PetscInt j = 0; j < ny; j++)
      for (PetscInt i = 0; i < nx; i++) {
        const PetscInt e  = i + nx * (j + ny * k);
        const PetscInt v0 = i + (nx + 1) * (j + (ny + 1) * k);
        const PetscInt dy = nx + 1, dz = (nx + 1) * (ny + 1);
        PetscInt      *c  = &m->conn[8 * e];
        c[0] = v0;
        c[1] = v0 + 1;
        c[2] = v0 + 1 + dy;
        c[3] = v0 + dy;
        for (PetscInt a = 0; a < 4; a++) c[4 + a] = c[a] + dz;
      }
  m->nnset  = 6;
  m->nelset = 1;
  PetscCall(PetscCalloc1(m->nnset, &m->nsets));
  PetscCall(PetscCalloc1(m->nelset, &m->elsets));
  PetscCall(PetscMalloc1(nv, &work));
  for (PetscInt d = 0; d < 3; d++) {
    const PetscReal tol = 1e-9 * (hi[d] - lo[d]);
    PetscCall(SetFromPlane(&m->nsets[2 * d], pname[d][0], nv, m->X, d, lo[d], tol, work));
    PetscCall(SetFromPlane(&m->nsets[2 * d + 1], pname[d][1], nv, m->X, d, hi[d], tol, work));
  }
  PetscCall(PetscFree(work));
  PetscCall(SetAll(&m->elsets[0], "all", ne));
  PetscFunctionReturn(0);
}

/* ------------------------------------------------------------------------------------------ */
/* circular blank, O-grid                                                                      */
/* ------------------------------------------------------------------------------------------ */
PetscErrorCode MeshDataCreateBlank(PetscReal R, PetscReal t, PetscReal core, PetscInt ncore, PetscInt nradial, PetscInt nlayers, PetscBool quarter, MeshData *m)
{
  const PetscInt nc = ncore, nr = nradial, nl = nlayers;
  PetscInt       nq2, nquad2, nquadrants, n2, nv, ne, ncore2, nedge;
  PetscInt64     nv64, ne64;
  PetscReal      a, *Q;
  PetscInt      *quad, *ex, *ey, *symxPt, *symyPt, *g;
  PetscBool     *rimq, *rim2, *work;
  PetscReal     *X2;

  PetscFunctionBeginUser;
  PetscCheck(m, PETSC_COMM_SELF, PETSC_ERR_ARG_NULL, "blank: output MeshData pointer is NULL");
  PetscCall(PetscMemzero(m, sizeof(*m)));
  PetscCheck(R > 0 && !PetscIsInfOrNanReal(R), PETSC_COMM_SELF, PETSC_ERR_ARG_OUTOFRANGE, "blank: radius %g (-blank_radius) must be > 0", (double)R);
  PetscCheck(t > 0 && !PetscIsInfOrNanReal(t), PETSC_COMM_SELF, PETSC_ERR_ARG_OUTOFRANGE, "blank: thickness %g (-blank_thickness) must be > 0", (double)t);
  PetscCheck(core > 0 && core < 1, PETSC_COMM_SELF, PETSC_ERR_ARG_OUTOFRANGE, "blank: core fraction %g must lie in (0,1) (-blank_core)", (double)core);
  PetscCheck(core * PetscSqrtReal(2.0) < 1, PETSC_COMM_SELF, PETSC_ERR_ARG_OUTOFRANGE, "blank: core fraction %g puts the corner of the central square at radius %g*R, outside the rim: it must be below 1/sqrt(2) = 0.7071 (-blank_core)", (double)core, (double)(core * PetscSqrtReal(2.0)));
  PetscCheck(ncore >= 1, PETSC_COMM_SELF, PETSC_ERR_ARG_OUTOFRANGE, "blank: ncore %" PetscInt_FMT " (-blank_core_cells, cells along each edge of the core square) must be >= 1", ncore);
  PetscCheck(nradial >= 1, PETSC_COMM_SELF, PETSC_ERR_ARG_OUTOFRANGE, "blank: nradial %" PetscInt_FMT " (-blank_radial_cells, cells from the core to the rim) must be >= 1", nradial);
  PetscCheck(nlayers >= 1, PETSC_COMM_SELF, PETSC_ERR_ARG_OUTOFRANGE, "blank: nlayers %" PetscInt_FMT " (-blank_layers, cells through the thickness) must be >= 1", nlayers);
  {
    const PetscInt64 q2 = (PetscInt64)(nc + 1) * (nc + 1) + (PetscInt64)(2 * nc + 1) * nr;
    const PetscInt64 c2 = (PetscInt64)nc * nc + (PetscInt64)2 * nc * nr;
    nv64                = 4 * q2 * (nl + 1);
    ne64                = 4 * c2 * nl;
    PetscCheck(nc < PETSC_MAX_INT / 4 && nr < PETSC_MAX_INT / 4 && nl < PETSC_MAX_INT / 4 && 8 * ne64 < PETSC_MAX_INT && 3 * nv64 < PETSC_MAX_INT, PETSC_COMM_SELF, PETSC_ERR_ARG_OUTOFRANGE,
               "blank: ncore %" PetscInt_FMT ", nradial %" PetscInt_FMT ", nlayers %" PetscInt_FMT " give too many cells for PetscInt", nc, nr, nl);
  }

  /* ---- one quarter in the plane: local points and quads ---- */
  a      = core * R;
  ncore2 = (nc + 1) * (nc + 1);
  nq2    = ncore2 + (2 * nc + 1) * nr; /* core points + ring points off the core boundary */
  nquad2 = nc * nc + 2 * nc * nr;
  nedge  = nc + nr + 1; /* points on each symmetry edge, centre included */
  PetscCall(PetscMalloc1(2 * nq2, &Q));
  PetscCall(PetscMalloc1(4 * nquad2, &quad));
  PetscCall(PetscMalloc1(nq2, &ex));
  PetscCall(PetscMalloc1(nq2, &ey));
  PetscCall(PetscMalloc1(nq2, &rimq));
  PetscCall(PetscMalloc1(nedge, &symxPt));
  PetscCall(PetscMalloc1(nedge, &symyPt));
#define CORE(i, j) ((i) + (nc + 1) * (j))
#define RING(s, k) ((k) == 0 ? ((s) <= nc ? CORE(nc, (s)) : CORE(2 * nc - (s), nc)) : ncore2 + (s) * nr + (k) - 1)
  for (PetscInt l = 0; l < nq2; l++) {
    ex[l]   = -1;
    ey[l]   = -1;
    rimq[l] = PETSC_FALSE;
  }
  for (PetscInt j = 0; j <= nc; j++)
    for (PetscInt i = 0; i <= nc; i++) {
      const PetscReal u = (PetscReal)i / (PetscReal)nc, v = (PetscReal)j / (PetscReal)nc;
      Q[2 * CORE(i, j) + 0] = a * u * (1 + BLANK_BULGE * (1 - v * v));
      Q[2 * CORE(i, j) + 1] = a * v * (1 + BLANK_BULGE * (1 - u * u));
    }
  for (PetscInt s = 0; s <= 2 * nc; s++) {
    const PetscInt  b = RING(s, 0);
    PetscReal       A[2];
    if (s <= nc) {
      const PetscReal th = (PetscReal)s * PETSC_PI / (PetscReal)(4 * nc);
      A[0]               = R * PetscCosReal(th);
      A[1]               = R * PetscSinReal(th);
    } else { /* mirror image of s' = 2nc - s, so that the quarter is exactly symmetric about x = y */
      const PetscReal ph = (PetscReal)(2 * nc - s) * PETSC_PI / (PetscReal)(4 * nc);
      A[0]               = R * PetscSinReal(ph);
      A[1]               = R * PetscCosReal(ph);
    }
    for (PetscInt k = 1; k <= nr; k++) {
      const PetscReal w = (PetscReal)k / (PetscReal)nr;
      const PetscInt  p = RING(s, k);
      Q[2 * p + 0]      = (1 - w) * Q[2 * b + 0] + w * A[0];
      Q[2 * p + 1]      = (1 - w) * Q[2 * b + 1] + w * A[1];
    }
    rimq[RING(s, nr)] = PETSC_TRUE;
  }
  /* symmetry edges, indexed by distance from the centre: x = 0 (symx) and y = 0 (symy) */
  for (PetscInt e = 0; e < nedge; e++) {
    symxPt[e] = e <= nc ? CORE(0, e) : RING(2 * nc, e - nc);
    symyPt[e] = e <= nc ? CORE(e, 0) : RING(0, e - nc);
    ex[symxPt[e]] = e;
    ey[symyPt[e]] = e;
  }
  {
    PetscInt q = 0;
    for (PetscInt j = 0; j < nc; j++)
      for (PetscInt i = 0; i < nc; i++, q++) {
        quad[4 * q + 0] = CORE(i, j);
        quad[4 * q + 1] = CORE(i + 1, j);
        quad[4 * q + 2] = CORE(i + 1, j + 1);
        quad[4 * q + 3] = CORE(i, j + 1);
      }
    for (PetscInt s = 0; s < 2 * nc; s++)
      for (PetscInt k = 0; k < nr; k++, q++) { /* (radial, tangential) is a right-handed frame */
        quad[4 * q + 0] = RING(s, k);
        quad[4 * q + 1] = RING(s, k + 1);
        quad[4 * q + 2] = RING(s + 1, k + 1);
        quad[4 * q + 3] = RING(s + 1, k);
      }
    PetscCheck(q == nquad2, PETSC_COMM_SELF, PETSC_ERR_PLIB, "blank: internal error, %" PetscInt_FMT " quads instead of %" PetscInt_FMT, q, nquad2);
  }
#undef RING
#undef CORE

  /* ---- quadrants: rotate the quarter by multiples of 90 degrees; points on the seams are taken
          from the neighbouring quadrant, so nothing is duplicated (no tolerance search) ---- */
  nquadrants = quarter ? 1 : 4;
  PetscCall(PetscMalloc1(nquadrants * nq2, &g));
  PetscCall(PetscMalloc1(2 * nquadrants * nq2, &X2));
  PetscCall(PetscMalloc1(nquadrants * nq2, &rim2));
  n2 = 0;
  for (PetscInt q = 0; q < nquadrants; q++)
    for (PetscInt l = 0; l < nq2; l++) {
      /* quadrant q's y = 0 edge is quadrant q-1's x = 0 edge rotated; quadrant 3's x = 0 edge is quadrant 0's y = 0 edge */
      if (q >= 1 && ey[l] >= 0) g[q * nq2 + l] = g[(q - 1) * nq2 + symxPt[ey[l]]];
      else if (q == 3 && ex[l] >= 0) g[q * nq2 + l] = g[symyPt[ex[l]]];
      else {
        const PetscReal x = Q[2 * l], y = Q[2 * l + 1];
        const PetscReal xr[4] = {x, -y, -x, y}, yr[4] = {y, x, -y, -x};
        X2[2 * n2 + 0]        = xr[q] == 0 ? 0.0 : xr[q]; /* no -0.0 */
        X2[2 * n2 + 1]        = yr[q] == 0 ? 0.0 : yr[q];
        rim2[n2]              = rimq[l];
        g[q * nq2 + l]        = n2++;
      }
    }
  PetscCheck(n2 == (quarter ? nq2 : 4 * nq2 - 4 * (nedge - 1) - 3), PETSC_COMM_SELF, PETSC_ERR_PLIB, "blank: internal error, %" PetscInt_FMT " distinct points in the plane", n2);

  /* ---- extrude through the thickness ---- */
  nv = n2 * (nl + 1);
  ne = nquadrants * nquad2 * nl;
  PetscCall(MeshDataAlloc(m, nv, ne));
  for (PetscInt L = 0; L <= nl; L++) {
    const PetscReal z = L == nl ? t : t * (PetscReal)L / (PetscReal)nl;
    for (PetscInt p = 0; p < n2; p++) {
      m->X[3 * (L * n2 + p) + 0] = X2[2 * p + 0];
      m->X[3 * (L * n2 + p) + 1] = X2[2 * p + 1];
      m->X[3 * (L * n2 + p) + 2] = z;
    }
  }
  {
    PetscInt e = 0;
    for (PetscInt L = 0; L < nl; L++)
      for (PetscInt q = 0; q < nquadrants; q++)
        for (PetscInt c = 0; c < nquad2; c++, e++)
          for (PetscInt a4 = 0; a4 < 4; a4++) {
            const PetscInt p       = g[q * nq2 + quad[4 * c + a4]];
            m->conn[8 * e + a4]     = L * n2 + p;
            m->conn[8 * e + 4 + a4] = (L + 1) * n2 + p;
          }
  }

  /* ---- sets ---- */
  m->nnset  = quarter ? 6 : 4;
  m->nelset = 1;
  PetscCall(PetscCalloc1(m->nnset, &m->nsets));
  PetscCall(PetscCalloc1(m->nelset, &m->elsets));
  PetscCall(PetscMalloc1(nv, &work));
  for (PetscInt v = 0; v < nv; v++) work[v] = rim2[v % n2];
  PetscCall(SetFromFlags(&m->nsets[0], "rim", nv, work));
  for (PetscInt v = 0; v < nv; v++) work[v] = v >= nl * n2 ? PETSC_TRUE : PETSC_FALSE;
  PetscCall(SetFromFlags(&m->nsets[1], "top", nv, work));
  for (PetscInt v = 0; v < nv; v++) work[v] = v < n2 ? PETSC_TRUE : PETSC_FALSE;
  PetscCall(SetFromFlags(&m->nsets[2], "bottom", nv, work));
  for (PetscInt v = 0; v < nv; v++) work[v] = (v % n2) == g[0] ? PETSC_TRUE : PETSC_FALSE; /* local point 0 is the centre */
  PetscCall(SetFromFlags(&m->nsets[3], "centre", nv, work));
  if (quarter) { /* quarter: global 2D index == local index */
    for (PetscInt v = 0; v < nv; v++) work[v] = ex[v % n2] >= 0 ? PETSC_TRUE : PETSC_FALSE;
    PetscCall(SetFromFlags(&m->nsets[4], "symx", nv, work));
    for (PetscInt v = 0; v < nv; v++) work[v] = ey[v % n2] >= 0 ? PETSC_TRUE : PETSC_FALSE;
    PetscCall(SetFromFlags(&m->nsets[5], "symy", nv, work));
  }
  PetscCall(SetAll(&m->elsets[0], "all", ne));

  PetscCall(PetscFree(work));
  PetscCall(PetscFree(rim2));
  PetscCall(PetscFree(X2));
  PetscCall(PetscFree(g));
  PetscCall(PetscFree(symyPt));
  PetscCall(PetscFree(symxPt));
  PetscCall(PetscFree(rimq));
  PetscCall(PetscFree(ey));
  PetscCall(PetscFree(ex));
  PetscCall(PetscFree(quad));
  PetscCall(PetscFree(Q));

  /* ---- safety net: every cell positive at its corners and Gauss points ---- */
  for (PetscInt e = 0; e < ne; e++) {
    PetscBool ok;
    PetscCall(HexIsValid(m->X, &m->conn[8 * e], &ok));
    if (!ok) {
      PetscCall(MeshDataDestroy(m));
      SETERRQ(PETSC_COMM_SELF, PETSC_ERR_ARG_OUTOFRANGE, "blank: cell %" PetscInt_FMT " is inverted or degenerate for R %g, core %g, ncore %" PetscInt_FMT ", nradial %" PetscInt_FMT " (internal error or extreme -blank_core)", e + 1, (double)R, (double)core, nc, nr);
    }
  }
  PetscFunctionReturn(0);
}

/* ------------------------------------------------------------------------------------------ */
/* Abaqus-style .inp reader                                                                    */
/* ------------------------------------------------------------------------------------------ */
typedef struct {
  char      name[PETSC_MAX_PATH_LEN];
  PetscBool isnode;    /* node set (else element set)             */
  PetscInt  n, cap;
  PetscInt *id, *line; /* deck ids and the lines that named them  */
} InpSet;

typedef struct {
  const char *file;
  char       *buf;
  PetscInt    nv, capv, ne, cape, nset, capset;
  PetscInt   *vid, *vline;         /* node ids, lines                      */
  PetscReal  *X;                   /* 3 per node                           */
  PetscInt   *eid, *eline, *econn; /* element ids, lines, 8 deck node ids  */
  InpSet     *sets;
  /* work for the resolution step */
  PetscInt  *svid, *vperm, *seid, *eperm;
  PetscBool *used;
  MeshData   out;
} InpCtx;

static PetscErrorCode GrowInt(PetscInt **arr, PetscInt n, PetscInt newcap)
{
  PetscInt *b;

  PetscFunctionBeginUser;
  PetscCall(PetscMalloc1(newcap, &b));
  if (n) PetscCall(PetscArraycpy(b, *arr, n));
  PetscCall(PetscFree(*arr));
  *arr = b;
  PetscFunctionReturn(0);
}

static PetscErrorCode GrowReal(PetscReal **arr, PetscInt n, PetscInt newcap)
{
  PetscReal *b;

  PetscFunctionBeginUser;
  PetscCall(PetscMalloc1(newcap, &b));
  if (n) PetscCall(PetscArraycpy(b, *arr, n));
  PetscCall(PetscFree(*arr));
  *arr = b;
  PetscFunctionReturn(0);
}

static PetscErrorCode NewCap(InpCtx *c, PetscInt cap, PetscInt *newcap)
{
  PetscFunctionBeginUser;
  PetscCheck(cap < PETSC_MAX_INT / 32, PETSC_COMM_SELF, PETSC_ERR_ARG_OUTOFRANGE, "mesh file '%s' is too large for PetscInt", c->file);
  *newcap = cap < 64 ? 64 : 2 * cap;
  PetscFunctionReturn(0);
}

static PetscErrorCode InpCtxDestroy(InpCtx *c)
{
  PetscFunctionBeginUser;
  PetscCall(PetscFree(c->buf));
  PetscCall(PetscFree(c->vid));
  PetscCall(PetscFree(c->vline));
  PetscCall(PetscFree(c->X));
  PetscCall(PetscFree(c->eid));
  PetscCall(PetscFree(c->eline));
  PetscCall(PetscFree(c->econn));
  for (PetscInt s = 0; s < c->nset; s++) {
    PetscCall(PetscFree(c->sets[s].id));
    PetscCall(PetscFree(c->sets[s].line));
  }
  PetscCall(PetscFree(c->sets));
  PetscCall(PetscFree(c->svid));
  PetscCall(PetscFree(c->vperm));
  PetscCall(PetscFree(c->seid));
  PetscCall(PetscFree(c->eperm));
  PetscCall(PetscFree(c->used));
  PetscCall(MeshDataDestroy(&c->out));
  PetscCall(PetscMemzero(c, sizeof(*c)));
  PetscFunctionReturn(0);
}

static PetscErrorCode InpReadFile(InpCtx *c)
{
  FILE  *fp;
  size_t n = 0, cap = 1 << 16, got;
  int    ferr;

  PetscFunctionBeginUser;
  fp = fopen(c->file, "rb");
  PetscCheck(fp, PETSC_COMM_SELF, PETSC_ERR_FILE_OPEN, "cannot open mesh file '%s': %s", c->file, strerror(errno));
  PetscCall(PetscMalloc1(cap, &c->buf));
  for (;;) {
    if (n + 1 >= cap) {
      char *b;
      PetscCall(PetscMalloc1(2 * cap, &b));
      PetscCall(PetscArraycpy(b, c->buf, n));
      PetscCall(PetscFree(c->buf));
      c->buf = b;
      cap *= 2;
    }
    got = fread(c->buf + n, 1, cap - n - 1, fp);
    n += got;
    if (got == 0) break;
  }
  ferr = ferror(fp);
  fclose(fp);
  PetscCheck(!ferr, PETSC_COMM_SELF, PETSC_ERR_FILE_READ, "error while reading mesh file '%s'", c->file);
  PetscCheck(!memchr(c->buf, '\0', n), PETSC_COMM_SELF, PETSC_ERR_FILE_UNEXPECTED, "mesh file '%s' contains NUL bytes: not a text deck", c->file);
  c->buf[n] = '\0';
  PetscFunctionReturn(0);
}

/* *out = s without leading and trailing white space (trailing part cut in place) */
static PetscErrorCode Trim(char *s, char **out)
{
  char *e;

  PetscFunctionBeginUser;
  while (*s && isspace((unsigned char)*s)) s++;
  e = s + strlen(s);
  while (e > s && isspace((unsigned char)e[-1])) *--e = '\0';
  *out = s;
  PetscFunctionReturn(0);
}

/* next comma-separated field of *cur (trimmed, NUL-terminated in place); *cur becomes NULL after the last */
static PetscErrorCode NextField(char **cur, char **field, PetscBool *last)
{
  char *s = *cur, *e;

  PetscFunctionBeginUser;
  e = strchr(s, ',');
  if (e) {
    *e    = '\0';
    *cur  = e + 1;
    *last = PETSC_FALSE;
  } else {
    *cur  = NULL;
    *last = PETSC_TRUE;
  }
  PetscCall(Trim(s, field));
  PetscFunctionReturn(0);
}

static PetscErrorCode ParseId(InpCtx *c, PetscInt line, const char *f, const char *what, PetscInt *val)
{
  char *end;
  long  v;

  PetscFunctionBeginUser;
  errno = 0;
  v     = strtol(f, &end, 10);
  PetscCheck(*f && end != f && *end == '\0', PETSC_COMM_SELF, PETSC_ERR_FILE_UNEXPECTED, "mesh file '%s', line %" PetscInt_FMT ": '%s' is not a valid %s (integer expected)", c->file, line, f, what);
  PetscCheck(errno == 0 && v >= 1 && v <= PETSC_MAX_INT, PETSC_COMM_SELF, PETSC_ERR_FILE_UNEXPECTED, "mesh file '%s', line %" PetscInt_FMT ": %s %s out of range (positive integer expected)", c->file, line, what, f);
  *val = (PetscInt)v;
  PetscFunctionReturn(0);
}

static PetscErrorCode ParseReal(InpCtx *c, PetscInt line, char *f, const char *what, PetscReal *val)
{
  char  *end;
  double v;

  PetscFunctionBeginUser;
  for (char *p = f; *p; p++)
    if (*p == 'd' || *p == 'D') *p = 'e'; /* Fortran exponent 1.0D+00 */
  errno = 0;
  v     = strtod(f, &end);
  PetscCheck(*f && end != f && *end == '\0' && errno != ERANGE && !PetscIsInfOrNanReal((PetscReal)v), PETSC_COMM_SELF, PETSC_ERR_FILE_UNEXPECTED, "mesh file '%s', line %" PetscInt_FMT ": '%s' is not a valid %s (finite number expected)", c->file, line, f, what);
  *val = (PetscReal)v;
  PetscFunctionReturn(0);
}

/* set named name of the given kind, created when missing (names compare case-insensitively) */
static PetscErrorCode InpGetSet(InpCtx *c, PetscInt line, const char *name, PetscBool isnode, PetscInt *s)
{
  size_t len;

  PetscFunctionBeginUser;
  PetscCall(PetscStrlen(name, &len));
  PetscCheck(len > 0, PETSC_COMM_SELF, PETSC_ERR_FILE_UNEXPECTED, "mesh file '%s', line %" PetscInt_FMT ": empty %s name", c->file, line, isnode ? "NSET" : "ELSET");
  PetscCheck(len < PETSC_MAX_PATH_LEN, PETSC_COMM_SELF, PETSC_ERR_FILE_UNEXPECTED, "mesh file '%s', line %" PetscInt_FMT ": set name '%.40s...' is too long", c->file, line, name);
  for (PetscInt i = 0; i < c->nset; i++) {
    PetscBool eq;
    if (c->sets[i].isnode != isnode) continue;
    PetscCall(PetscStrcasecmp(c->sets[i].name, name, &eq));
    if (eq) {
      *s = i;
      PetscFunctionReturn(0);
    }
  }
  if (c->nset == c->capset) {
    InpSet        *b;
    const PetscInt cap = c->capset < 8 ? 8 : 2 * c->capset;
    PetscCall(PetscCalloc1(cap, &b));
    if (c->nset) PetscCall(PetscArraycpy(b, c->sets, c->nset));
    PetscCall(PetscFree(c->sets));
    c->sets   = b;
    c->capset = cap;
  }
  PetscCall(PetscMemzero(&c->sets[c->nset], sizeof(InpSet)));
  PetscCall(PetscStrncpy(c->sets[c->nset].name, name, sizeof(c->sets[c->nset].name)));
  c->sets[c->nset].isnode = isnode;
  *s                      = c->nset++;
  PetscFunctionReturn(0);
}

static PetscErrorCode InpSetAdd(InpCtx *c, PetscInt s, PetscInt id, PetscInt line)
{
  InpSet *set = &c->sets[s];

  PetscFunctionBeginUser;
  if (set->n == set->cap) {
    PetscInt cap = 0;
    PetscCall(NewCap(c, set->cap, &cap));
    PetscCall(GrowInt(&set->id, set->n, cap));
    PetscCall(GrowInt(&set->line, set->n, cap));
    set->cap = cap;
  }
  set->id[set->n]   = id;
  set->line[set->n] = line;
  set->n++;
  PetscFunctionReturn(0);
}

static PetscErrorCode InpAddNode(InpCtx *c, PetscInt id, const PetscReal x[3], PetscInt line)
{
  PetscFunctionBeginUser;
  if (c->nv == c->capv) {
    PetscInt cap = 0;
    PetscCall(NewCap(c, c->capv, &cap));
    PetscCall(GrowInt(&c->vid, c->nv, cap));
    PetscCall(GrowInt(&c->vline, c->nv, cap));
    PetscCall(GrowReal(&c->X, 3 * c->nv, 3 * cap));
    c->capv = cap;
  }
  c->vid[c->nv]   = id;
  c->vline[c->nv] = line;
  for (PetscInt i = 0; i < 3; i++) c->X[3 * c->nv + i] = x[i];
  c->nv++;
  PetscFunctionReturn(0);
}

static PetscErrorCode InpAddElement(InpCtx *c, const PetscInt v[9], PetscInt line)
{
  PetscFunctionBeginUser;
  if (c->ne == c->cape) {
    PetscInt cap = 0;
    PetscCall(NewCap(c, c->cape, &cap));
    PetscCall(GrowInt(&c->eid, c->ne, cap));
    PetscCall(GrowInt(&c->eline, c->ne, cap));
    PetscCall(GrowInt(&c->econn, 8 * c->ne, 8 * cap));
    c->cape = cap;
  }
  c->eid[c->ne]   = v[0];
  c->eline[c->ne] = line;
  for (PetscInt a = 0; a < 8; a++) c->econn[8 * c->ne + a] = v[1 + a];
  c->ne++;
  PetscFunctionReturn(0);
}

typedef enum {
  BLK_NONE,
  BLK_SKIP,
  BLK_NODE,
  BLK_ELEMENT,
  BLK_SET
} InpBlock;

typedef struct {
  InpBlock  blk;
  PetscInt  set;      /* set receiving the ids of this block, or -1 */
  PetscBool generate; /* GENERATE on *NSET or *ELSET               */
  PetscBool isnode;   /* *NSET (else *ELSET)                        */
  PetscInt  pend[9];  /* element data collected so far              */
  PetscInt  npend, pendline;
} InpState;

/* keyword line (without the leading '*') */
static PetscErrorCode InpKeyword(InpCtx *c, PetscInt line, char *text, InpState *st)
{
  char     *cur = text, *kw, *f;
  PetscBool last, eq;
  char     *type = NULL, *nset = NULL, *elset = NULL, *system = NULL;
  PetscBool generate = PETSC_FALSE;

  PetscFunctionBeginUser;
  PetscCall(NextField(&cur, &kw, &last));
  while (cur) {
    char *eqs, *key, *val = NULL;
    PetscCall(NextField(&cur, &f, &last));
    if (!*f) continue;
    eqs = strchr(f, '=');
    if (eqs) {
      *eqs = '\0';
      PetscCall(Trim(eqs + 1, &val));
      if (val[0] == '"') { /* quoted value */
        size_t l = strlen(val);
        if (l >= 2 && val[l - 1] == '"') {
          val[l - 1] = '\0';
          val++;
        }
      }
    }
    PetscCall(Trim(f, &key));
    PetscCall(PetscStrcasecmp(key, "TYPE", &eq));
    if (eq && val) type = val;
    PetscCall(PetscStrcasecmp(key, "NSET", &eq));
    if (eq && val) nset = val;
    PetscCall(PetscStrcasecmp(key, "ELSET", &eq));
    if (eq && val) elset = val;
    PetscCall(PetscStrcasecmp(key, "SYSTEM", &eq));
    if (eq && val) system = val;
    PetscCall(PetscStrcasecmp(key, "GENERATE", &eq));
    if (eq) generate = PETSC_TRUE;
  }
  st->blk      = BLK_SKIP;
  st->set      = -1;
  st->generate = PETSC_FALSE;

  PetscCall(PetscStrcasecmp(kw, "NODE", &eq));
  if (eq) {
    if (system) {
      PetscCall(PetscStrcasecmp(system, "R", &eq));
      PetscCheck(eq, PETSC_COMM_SELF, PETSC_ERR_SUP, "mesh file '%s', line %" PetscInt_FMT ": *NODE, SYSTEM=%s is not supported (only rectangular coordinates)", c->file, line, system);
    }
    st->blk = BLK_NODE;
    if (nset) PetscCall(InpGetSet(c, line, nset, PETSC_TRUE, &st->set));
    PetscFunctionReturn(0);
  }
  PetscCall(PetscStrcasecmp(kw, "ELEMENT", &eq));
  if (eq) {
    static const char *types[] = {"C3D8", "C3D8R", "C3D8I", "C3D8H"};
    PetscBool          known   = PETSC_FALSE;
    PetscCheck(type, PETSC_COMM_SELF, PETSC_ERR_FILE_UNEXPECTED, "mesh file '%s', line %" PetscInt_FMT ": *ELEMENT without TYPE=", c->file, line);
    for (PetscInt i = 0; i < 4 && !known; i++) PetscCall(PetscStrcasecmp(type, types[i], &known));
    PetscCheck(known, PETSC_COMM_SELF, PETSC_ERR_SUP, "mesh file '%s', line %" PetscInt_FMT ": element type %s is not supported (only 8-node hexahedra C3D8, C3D8R, C3D8I, C3D8H)", c->file, line, type);
    st->blk = BLK_ELEMENT;
    if (elset) PetscCall(InpGetSet(c, line, elset, PETSC_FALSE, &st->set));
    PetscFunctionReturn(0);
  }
  PetscCall(PetscStrcasecmp(kw, "NSET", &eq));
  if (eq) {
    PetscCheck(nset, PETSC_COMM_SELF, PETSC_ERR_FILE_UNEXPECTED, "mesh file '%s', line %" PetscInt_FMT ": *NSET without NSET=name", c->file, line);
    PetscCheck(!elset, PETSC_COMM_SELF, PETSC_ERR_SUP, "mesh file '%s', line %" PetscInt_FMT ": *NSET, NSET=%s, ELSET=%s (nodes of an element set) is not supported", c->file, line, nset, elset);
    st->blk      = BLK_SET;
    st->isnode   = PETSC_TRUE;
    st->generate = generate;
    PetscCall(InpGetSet(c, line, nset, PETSC_TRUE, &st->set));
    PetscFunctionReturn(0);
  }
  PetscCall(PetscStrcasecmp(kw, "ELSET", &eq));
  if (eq) {
    PetscCheck(elset, PETSC_COMM_SELF, PETSC_ERR_FILE_UNEXPECTED, "mesh file '%s', line %" PetscInt_FMT ": *ELSET without ELSET=name", c->file, line);
    st->blk      = BLK_SET;
    st->isnode   = PETSC_FALSE;
    st->generate = generate;
    PetscCall(InpGetSet(c, line, elset, PETSC_FALSE, &st->set));
    PetscFunctionReturn(0);
  }
  PetscCall(PetscStrcasecmp(kw, "INCLUDE", &eq));
  PetscCheck(!eq, PETSC_COMM_SELF, PETSC_ERR_SUP, "mesh file '%s', line %" PetscInt_FMT ": *INCLUDE is not supported; merge the included file into the deck", c->file, line);
  PetscFunctionReturn(0); /* any other keyword: skipped with its data lines */
}

static PetscErrorCode InpNodeLine(InpCtx *c, PetscInt line, char *text, InpState *st)
{
  char     *cur = text, *f;
  PetscBool last;
  PetscInt  nf = 0, id = 0;
  PetscReal x[3] = {0, 0, 0};

  PetscFunctionBeginUser;
  while (cur) {
    PetscCall(NextField(&cur, &f, &last));
    if (!*f && last && nf > 0) break; /* trailing comma */
    PetscCheck(nf < 4, PETSC_COMM_SELF, PETSC_ERR_FILE_UNEXPECTED, "mesh file '%s', line %" PetscInt_FMT ": node data line has more than 4 values (expected id, x[, y[, z]])", c->file, line);
    if (nf == 0) {
      PetscCheck(*f, PETSC_COMM_SELF, PETSC_ERR_FILE_UNEXPECTED, "mesh file '%s', line %" PetscInt_FMT ": node data line without a node id", c->file, line);
      PetscCall(ParseId(c, line, f, "node id", &id));
    } else if (*f) PetscCall(ParseReal(c, line, f, "node coordinate", &x[nf - 1])); /* empty field: 0 */
    nf++;
  }
  PetscCheck(nf >= 2, PETSC_COMM_SELF, PETSC_ERR_FILE_UNEXPECTED, "mesh file '%s', line %" PetscInt_FMT ": node %" PetscInt_FMT " has no coordinates (expected id, x[, y[, z]])", c->file, line, id);
  PetscCall(InpAddNode(c, id, x, line));
  if (st->set >= 0) PetscCall(InpSetAdd(c, st->set, id, line));
  PetscFunctionReturn(0);
}

static PetscErrorCode InpElementLine(InpCtx *c, PetscInt line, char *text, InpState *st)
{
  char     *cur = text, *f;
  PetscBool last, endcomma;
  size_t    len = strlen(text);

  PetscFunctionBeginUser;
  endcomma = (len > 0 && text[len - 1] == ',') ? PETSC_TRUE : PETSC_FALSE;
  if (st->npend == 0) st->pendline = line;
  while (cur) {
    PetscCall(NextField(&cur, &f, &last));
    if (!*f && last) break; /* trailing comma */
    PetscCheck(*f, PETSC_COMM_SELF, PETSC_ERR_FILE_UNEXPECTED, "mesh file '%s', line %" PetscInt_FMT ": empty value in element data", c->file, line);
    PetscCheck(st->npend < 9, PETSC_COMM_SELF, PETSC_ERR_FILE_UNEXPECTED, "mesh file '%s', line %" PetscInt_FMT ": element data has more than 9 values (expected id and 8 node ids)", c->file, line);
    PetscCall(ParseId(c, line, f, st->npend ? "node id" : "element id", &st->pend[st->npend]));
    st->npend++;
  }
  if (st->npend == 9) {
    PetscCall(InpAddElement(c, st->pend, st->pendline));
    if (st->set >= 0) PetscCall(InpSetAdd(c, st->set, st->pend[0], st->pendline));
    st->npend = 0;
  } else
    PetscCheck(endcomma, PETSC_COMM_SELF, PETSC_ERR_FILE_UNEXPECTED, "mesh file '%s', line %" PetscInt_FMT ": truncated element data, %" PetscInt_FMT " values instead of 9 (element id and 8 node ids; a line ending with a comma continues on the next line)", c->file, line, st->npend);
  PetscFunctionReturn(0);
}

static PetscErrorCode InpSetLine(InpCtx *c, PetscInt line, char *text, InpState *st)
{
  char       *cur = text, *f;
  PetscBool   last;
  PetscInt    v[3], nf = 0;
  const char *what = st->isnode ? "node id" : "element id";

  PetscFunctionBeginUser;
  while (cur) {
    PetscCall(NextField(&cur, &f, &last));
    if (!*f && last) break; /* trailing comma */
    PetscCheck(*f, PETSC_COMM_SELF, PETSC_ERR_FILE_UNEXPECTED, "mesh file '%s', line %" PetscInt_FMT ": empty value in set '%s'", c->file, line, c->sets[st->set].name);
    if (st->generate) {
      PetscCheck(nf < 3, PETSC_COMM_SELF, PETSC_ERR_FILE_UNEXPECTED, "mesh file '%s', line %" PetscInt_FMT ": GENERATE line of set '%s' has more than 3 values (expected first, last[, increment])", c->file, line, c->sets[st->set].name);
      PetscCall(ParseId(c, line, f, nf == 2 ? "GENERATE increment" : what, &v[nf]));
      nf++;
    } else {
      PetscInt id;
      PetscCall(ParseId(c, line, f, what, &id));
      PetscCall(InpSetAdd(c, st->set, id, line));
    }
  }
  if (st->generate) {
    PetscCheck(nf >= 2, PETSC_COMM_SELF, PETSC_ERR_FILE_UNEXPECTED, "mesh file '%s', line %" PetscInt_FMT ": GENERATE line of set '%s' has %" PetscInt_FMT " values (expected first, last[, increment])", c->file, line, c->sets[st->set].name, nf);
    if (nf == 2) v[2] = 1;
    PetscCheck(v[1] >= v[0], PETSC_COMM_SELF, PETSC_ERR_FILE_UNEXPECTED, "mesh file '%s', line %" PetscInt_FMT ": GENERATE range of set '%s' ends (%" PetscInt_FMT ") before it starts (%" PetscInt_FMT ")", c->file, line, c->sets[st->set].name, v[1], v[0]);
    PetscCheck((v[1] - v[0]) / v[2] < 100000000, PETSC_COMM_SELF, PETSC_ERR_FILE_UNEXPECTED, "mesh file '%s', line %" PetscInt_FMT ": GENERATE range of set '%s' is implausibly large", c->file, line, c->sets[st->set].name);
    for (PetscInt id = v[0]; id <= v[1]; id += v[2]) {
      PetscCall(InpSetAdd(c, st->set, id, line));
      if (id > PETSC_MAX_INT - v[2]) break;
    }
  }
  PetscFunctionReturn(0);
}

static PetscErrorCode InpParse(InpCtx *c)
{
  char    *p = c->buf;
  PetscInt lineno = 0;
  InpState st;

  PetscFunctionBeginUser;
  PetscCall(PetscMemzero(&st, sizeof(st)));
  st.blk = BLK_NONE;
  st.set = -1;
  while (*p) {
    char *text = p, *nl = strchr(p, '\n');
    if (nl) {
      *nl = '\0';
      p   = nl + 1;
    } else p = text + strlen(text);
    lineno++;
    PetscCall(Trim(text, &text)); /* also drops a trailing '\r' */
    if (!*text) continue;
    if (text[0] == '*' && text[1] == '*') continue; /* comment */
    if (text[0] == '*') {
      PetscCheck(st.npend == 0, PETSC_COMM_SELF, PETSC_ERR_FILE_UNEXPECTED, "mesh file '%s', line %" PetscInt_FMT ": truncated element data, %" PetscInt_FMT " values instead of 9 (the element continues with a keyword line)", c->file, st.pendline, st.npend);
      PetscCall(InpKeyword(c, lineno, text + 1, &st));
      continue;
    }
    switch (st.blk) {
    case BLK_NONE:
      SETERRQ(PETSC_COMM_SELF, PETSC_ERR_FILE_UNEXPECTED, "mesh file '%s', line %" PetscInt_FMT ": data line before any keyword", c->file, lineno);
    case BLK_SKIP:
      break;
    case BLK_NODE:
      PetscCall(InpNodeLine(c, lineno, text, &st));
      break;
    case BLK_ELEMENT:
      PetscCall(InpElementLine(c, lineno, text, &st));
      break;
    case BLK_SET:
      PetscCall(InpSetLine(c, lineno, text, &st));
      break;
    }
  }
  PetscCheck(st.npend == 0, PETSC_COMM_SELF, PETSC_ERR_FILE_UNEXPECTED, "mesh file '%s', line %" PetscInt_FMT ": truncated element data, %" PetscInt_FMT " values instead of 9 (end of file)", c->file, st.pendline, st.npend);
  PetscFunctionReturn(0);
}

/* sorted copy of ids with the permutation to the original positions; errors on duplicates */
static PetscErrorCode InpSortIds(InpCtx *c, PetscInt n, const PetscInt *ids, const PetscInt *lines, const char *what, PetscInt **sorted, PetscInt **perm)
{
  PetscFunctionBeginUser;
  PetscCall(PetscMalloc1(n, sorted));
  PetscCall(PetscMalloc1(n, perm));
  for (PetscInt i = 0; i < n; i++) {
    (*sorted)[i] = ids[i];
    (*perm)[i]   = i;
  }
  PetscCall(PetscSortIntWithArray(n, *sorted, *perm));
  for (PetscInt i = 0; i + 1 < n; i++) {
    const PetscInt l0 = lines[(*perm)[i]], l1 = lines[(*perm)[i + 1]];
    PetscCheck((*sorted)[i] != (*sorted)[i + 1], PETSC_COMM_SELF, PETSC_ERR_FILE_UNEXPECTED, "mesh file '%s', line %" PetscInt_FMT ": duplicate %s id %" PetscInt_FMT " (first defined on line %" PetscInt_FMT ")", c->file, PetscMax(l0, l1), what, (*sorted)[i], PetscMin(l0, l1));
  }
  PetscFunctionReturn(0);
}

static PetscErrorCode InpBuild(InpCtx *c)
{
  MeshData *m = &c->out;
  PetscInt  nn = 0, ne = 0;

  PetscFunctionBeginUser;
  PetscCheck(c->ne > 0, PETSC_COMM_SELF, PETSC_ERR_FILE_UNEXPECTED, "mesh file '%s' defines no elements (expected *ELEMENT, TYPE=C3D8 with data lines)", c->file);
  PetscCall(InpSortIds(c, c->nv, c->vid, c->vline, "node", &c->svid, &c->vperm));
  PetscCall(InpSortIds(c, c->ne, c->eid, c->eline, "element", &c->seid, &c->eperm));

  m->nv = c->nv;
  m->ne = c->ne;
  PetscCall(PetscMalloc1(3 * m->nv, &m->X));
  PetscCall(PetscMalloc1(8 * m->ne, &m->conn));
  PetscCall(PetscMalloc1(m->nv, &m->node_id));
  PetscCall(PetscMalloc1(m->ne, &m->elem_id));
  PetscCall(PetscArraycpy(m->X, c->X, 3 * m->nv));
  PetscCall(PetscArraycpy(m->node_id, c->vid, m->nv));
  PetscCall(PetscArraycpy(m->elem_id, c->eid, m->ne));

  PetscCall(PetscCalloc1(m->nv, &c->used));
  for (PetscInt e = 0; e < m->ne; e++)
    for (PetscInt a = 0; a < 8; a++) {
      const PetscInt id = c->econn[8 * e + a];
      PetscInt       loc;
      PetscCall(PetscFindInt(id, m->nv, c->svid, &loc));
      PetscCheck(loc >= 0, PETSC_COMM_SELF, PETSC_ERR_FILE_UNEXPECTED, "mesh file '%s', line %" PetscInt_FMT ": element id %" PetscInt_FMT " references undefined node id %" PetscInt_FMT, c->file, c->eline[e], c->eid[e], id);
      m->conn[8 * e + a]       = c->vperm[loc];
      c->used[c->vperm[loc]] = PETSC_TRUE;
    }
  for (PetscInt v = 0; v < m->nv; v++) PetscCheck(c->used[v], PETSC_COMM_SELF, PETSC_ERR_FILE_UNEXPECTED, "mesh file '%s', line %" PetscInt_FMT ": node id %" PetscInt_FMT " is referenced by no element", c->file, c->vline[v], c->vid[v]);
  for (PetscInt e = 0; e < m->ne; e++) {
    PetscBool ok;
    PetscCall(HexIsValid(m->X, &m->conn[8 * e], &ok));
    PetscCheck(ok, PETSC_COMM_SELF, PETSC_ERR_FILE_UNEXPECTED, "mesh file '%s', line %" PetscInt_FMT ": element id %" PetscInt_FMT " is inverted or degenerate (det J <= 0 at a corner or Gauss point; expected nodes 1-4 counter-clockwise seen from nodes 5-8)", c->file, c->eline[e], c->eid[e]);
  }

  for (PetscInt s = 0; s < c->nset; s++) {
    if (c->sets[s].isnode) nn++;
    else ne++;
  }
  PetscCall(PetscCalloc1(nn, &m->nsets));
  PetscCall(PetscCalloc1(ne, &m->elsets));
  for (PetscInt s = 0; s < c->nset; s++) {
    const InpSet   *in   = &c->sets[s];
    MeshSet        *out  = in->isnode ? &m->nsets[m->nnset++] : &m->elsets[m->nelset++];
    const PetscInt *sid  = in->isnode ? c->svid : c->seid;
    const PetscInt *perm = in->isnode ? c->vperm : c->eperm;
    const PetscInt  n    = in->isnode ? m->nv : m->ne;
    PetscCall(PetscStrncpy(out->name, in->name, sizeof(out->name)));
    PetscCall(PetscMalloc1(in->n, &out->idx));
    for (PetscInt i = 0; i < in->n; i++) {
      PetscInt loc;
      PetscCall(PetscFindInt(in->id[i], n, sid, &loc));
      PetscCheck(loc >= 0, PETSC_COMM_SELF, PETSC_ERR_FILE_UNEXPECTED, "mesh file '%s', line %" PetscInt_FMT ": %s set '%s' names missing %s id %" PetscInt_FMT, c->file, in->line[i], in->isnode ? "node" : "element", in->name, in->isnode ? "node" : "element", in->id[i]);
      out->idx[i] = perm[loc];
    }
    out->n = in->n;
    PetscCall(PetscSortRemoveDupsInt(&out->n, out->idx));
  }
  PetscFunctionReturn(0);
}

PetscErrorCode MeshDataReadInp(const char *file, MeshData *m)
{
  InpCtx         c;
  PetscErrorCode ierr;

  PetscFunctionBeginUser;
  PetscCheck(m, PETSC_COMM_SELF, PETSC_ERR_ARG_NULL, "MeshDataReadInp: output MeshData pointer is NULL");
  PetscCheck(file, PETSC_COMM_SELF, PETSC_ERR_ARG_NULL, "MeshDataReadInp: mesh file name is NULL");
  PetscCall(PetscMemzero(m, sizeof(*m)));
  PetscCall(PetscMemzero(&c, sizeof(c)));
  c.file = file;
  /* the parse is run for its error code so that the partial data are freed before the error
     propagates (the message has already been issued where the error was detected) */
  ierr = InpReadFile(&c);
  if (!ierr) ierr = InpParse(&c);
  if (!ierr) ierr = InpBuild(&c);
  if (!ierr) {
    *m = c.out;
    PetscCall(PetscMemzero(&c.out, sizeof(c.out)));
  }
  PetscCall(InpCtxDestroy(&c));
  PetscCall(ierr);
  PetscFunctionReturn(0);
}
