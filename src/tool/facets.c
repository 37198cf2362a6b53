/* Patch type "facets": a meshed tool surface (triangles; quadrangles are split in two along their
   shorter diagonal) read from a file (facetsio.c), stored compactly (one vertex array, three
   vertex ids, three neighbours and three corner-normal ids per triangle, a bounding-volume
   hierarchy in the tool's reference frame), doc/notes/tools-log.md "Meshed surfaces".

   Parameters: a point of triangle f with local coordinates (u, v) (x = P0 + u (P1 - P0) + v (P2 - P0))
   is (xi, eta) = (4 (f / 1024) + u, 4 (f % 1024) + v): the facet is decoded from the integer part
   of (xi + 1.5)/4 and (eta + 1.5)/4, so that (xi + 0.01, eta) (the frame chord of the contact
   object) stays on the same facet, continued over its plane.

   Projection (closest): the facet of the closest point by the hierarchy (ties: the smallest facet
   index, so that the result is independent of the traversal and of a hint). Smoothed (default):
   each facet is Nagata's quadratic patch through its corner normals; every patch within reach of
   the closest triangle is a candidate, the closest point of each patch is found by Newton (or on
   its edges), and the closest candidate wins; where two candidates are stationary points (the
   foot of y inside the patch, or on its edge) whose distances differ by less than FACETS_TIE of
   the surface's size (a point inside the crease between two patches, on a symmetry plane through
   the edge, or at a vertex), the smaller facet index wins, so that the round-off of y cannot move
   the result from one patch to the other. A closest point on an open edge of the surface with y
   beside it (beyond the edge in the facet's plane by more than 1e-9 of the facet's size) is no
   contact: the patch is skipped. */
#include "facets.h"

#include <float.h>
#include <limits.h>
#include <stdlib.h>
#include <string.h>

#include "options.h"

/* ------------------------------------------------------------------ parameters */

static inline void FacetsEncode(int f, double u, double v, double *xi, double *eta)
{
  *xi  = 4.0 * (double)(f >> 10) + u;
  *eta = 4.0 * (double)(f & 1023) + v;
}

static inline int FacetsDecode(const FacetsData *m, double xi, double eta, double *u, double *v)
{
  const double fh = floor((xi + 1.5) / 4.0), fl = floor((eta + 1.5) / 4.0);
  long         f  = (long)fh * 1024 + (long)fl;
  *u              = xi - 4.0 * fh;
  *v              = eta - 4.0 * fl;
  if (f < 0) f = 0;
  if (f >= m->nf) f = m->nf - 1;
  return (int)f;
}

static inline void Corner(const FacetsData *m, int f, int i, double P[3])
{
  const double *X = &m->V[3 * m->F[3 * f + i]];
  P[0]            = X[0];
  P[1]            = X[1];
  P[2]            = X[2];
}

/* Nagata's curvature coefficient of the edge from a to b (d = b - a) with unit normals na, nb:
   the edge curve a + t d - c t (1 - t) is normal to na at a and to nb at b, c in span(na, nb):
   with v = (na + nb)/2, dv = (na - nb)/2, c = (dv.d)/|v|^2 v (the arc) + (v.d)/|dv|^2 dv (the
   S-shaped part). The S part is capped at 2 |dv| |d| (about the angle between the normals times
   |d|): with nearly parallel normals that are not both normal to d (noise) it would blow up.
   Symmetric: the edge gives the same curve from either facet. */
static void NagataCoefficient(const double d[3], const double na[3], const double nb[3], double c[3])
{
  double       v[3], dv[3];
  for (int i = 0; i < 3; i++) {
    v[i]  = 0.5 * (na[i] + nb[i]);
    dv[i] = 0.5 * (na[i] - nb[i]);
  }
  const double A = Dot(dv, dv), B = Dot(v, v), ld = Norm(d);
  double       ka = B > 0.0 ? Dot(dv, d) / B : 0.0, ks = A > 0.0 ? Dot(v, d) / A : 0.0;
  const double cap = 2.0 * sqrt(A) * ld, ls = fabs(ks) * sqrt(A);
  if (ls > cap) ks *= cap / ls;
  for (int i = 0; i < 3; i++) c[i] = ka * v[i] + ks * dv[i];
}

/* The facet's surface: the plane triangle (raw), or Nagata's quadratic patch
   x = P0 w + P1 u + P2 v - c01 u w - c12 u v - c20 v w (w = 1 - u - v) through its curved edges
   (a sharp edge, one whose sides' normals differ by more than the feature angle, stays straight);
   its data set once per facet (FacetGeomSet) and evaluated (FacetGeomEval) */
typedef struct {
  double P0[3], e1[3], e2[3], c[3][3];
} FacetGeom;

static void FacetGeomSet(const FacetsData *m, int f, FacetGeom *g)
{
  double P[3][3];
  for (int k = 0; k < 3; k++) Corner(m, f, k, P[k]);
  for (int i = 0; i < 3; i++) {
    g->P0[i] = P[0][i];
    g->e1[i] = P[1][i] - P[0][i];
    g->e2[i] = P[2][i] - P[0][i];
  }
  for (int e = 0; e < 3; e++) {
    for (int i = 0; i < 3; i++) g->c[e][i] = 0.0;
    if (m->smooth && (m->curved[f] & (1 << e))) {
      const int    a = e, b = (e + 1) % 3;
      const double d[3] = {P[b][0] - P[a][0], P[b][1] - P[a][1], P[b][2] - P[a][2]};
      NagataCoefficient(d, &m->N[3 * m->C[3 * f + a]], &m->N[3 * m->C[3 * f + b]], g->c[e]);
    }
  }
}

static inline void FacetGeomEval(const FacetGeom *g, double u, double v, double x[3], double xu[3], double xv[3], double *xuu, double *xuv, double *xvv)
{
  const double w = 1.0 - u - v;
  for (int i = 0; i < 3; i++) {
    x[i]  = g->P0[i] + u * g->e1[i] + v * g->e2[i] - g->c[0][i] * u * w - g->c[1][i] * u * v - g->c[2][i] * v * w;
    xu[i] = g->e1[i] - g->c[0][i] * (w - u) - g->c[1][i] * v + g->c[2][i] * v;
    xv[i] = g->e2[i] + g->c[0][i] * u - g->c[1][i] * u - g->c[2][i] * (w - v);
    if (xuu) xuu[i] = 2.0 * g->c[0][i];
    if (xuv) xuv[i] = g->c[0][i] - g->c[1][i] + g->c[2][i];
    if (xvv) xvv[i] = 2.0 * g->c[2][i];
  }
}

static void FacetEvalLocal(const FacetsData *m, int f, double u, double v, double x[3], double xu[3], double xv[3], double *xuu, double *xuv, double *xvv)
{
  FacetGeom g;
  FacetGeomSet(m, f, &g);
  FacetGeomEval(&g, u, v, x, xu, xv, xuu, xuv, xvv);
}

static void FacetsEval(const Patch *p, double xi, double eta, double x[3], double xu[3], double xv[3], double *xuu, double *xuv, double *xvv)
{
  const FacetsData *m = (const FacetsData *)p->data;
  double            u, v;
  const int         f = FacetsDecode(m, xi, eta, &u, &v);
  FacetEvalLocal(m, f, u, v, x, xu, xv, xuu, xuv, xvv);
}

static double FacetsNormal(const Patch *p, double xi, double eta, double n[3])
{
  const FacetsData *m = (const FacetsData *)p->data;
  double            u, v, x[3], xu[3], xv[3], l;
  const int         f = FacetsDecode(m, xi, eta, &u, &v);
  FacetEvalLocal(m, f, u, v, x, xu, xv, NULL, NULL, NULL);
  Cross(xu, xv, n);
  l = Norm(n);
  for (int i = 0; i < 3; i++) n[i] = l > 0.0 ? SenseSign(p) * n[i] / l : 0.0;
  return l;
}

/* ------------------------------------------------------------------ closest point on a triangle */

/* Closest point of y on triangle f (Ericson, Real-Time Collision Detection 5.1.5): local (u, v),
   squared distance, region: 0 interior, 1 + e on edge e (0: P0P1, 1: P1P2, 2: P2P0), 4 + i at
   vertex i */
static inline double TriClosestPts(const double a[3], const double b[3], const double c[3], const double y[3], double *uo, double *vo, int *region)
{
  double ab[3], ac[3], ap[3], bp[3], cp[3], x[3], u, v;
  int    reg;
  for (int i = 0; i < 3; i++) {
    ab[i] = b[i] - a[i];
    ac[i] = c[i] - a[i];
    ap[i] = y[i] - a[i];
    bp[i] = y[i] - b[i];
    cp[i] = y[i] - c[i];
  }
  const double d1 = Dot(ab, ap), d2 = Dot(ac, ap), d3 = Dot(ab, bp), d4 = Dot(ac, bp), d5 = Dot(ab, cp), d6 = Dot(ac, cp);
  const double vc = d1 * d4 - d3 * d2, vb = d5 * d2 - d1 * d6, va = d3 * d6 - d5 * d4;
  if (d1 <= 0.0 && d2 <= 0.0) {
    u = v = 0.0;
    reg   = 4;
  } else if (d3 >= 0.0 && d4 <= d3) {
    u   = 1.0;
    v   = 0.0;
    reg = 5;
  } else if (vc <= 0.0 && d1 >= 0.0 && d3 <= 0.0) {
    u   = d1 / (d1 - d3);
    v   = 0.0;
    reg = 1;
  } else if (d6 >= 0.0 && d5 <= d6) {
    u   = 0.0;
    v   = 1.0;
    reg = 6;
  } else if (vb <= 0.0 && d2 >= 0.0 && d6 <= 0.0) {
    u   = 0.0;
    v   = d2 / (d2 - d6);
    reg = 3;
  } else if (va <= 0.0 && (d4 - d3) >= 0.0 && (d5 - d6) >= 0.0) {
    const double w = (d4 - d3) / ((d4 - d3) + (d5 - d6));
    u              = 1.0 - w;
    v              = w;
    reg            = 2;
  } else {
    const double den = 1.0 / (va + vb + vc);
    u                = vb * den;
    v                = vc * den;
    reg              = 0;
  }
  for (int i = 0; i < 3; i++) x[i] = a[i] + u * ab[i] + v * ac[i];
  *uo     = u;
  *vo     = v;
  *region = reg;
  return Dist2(x, y);
}

static double TriClosest(const FacetsData *m, int f, const double y[3], double *uo, double *vo, int *region)
{
  double a[3], b[3], c[3];
  Corner(m, f, 0, a);
  Corner(m, f, 1, b);
  Corner(m, f, 2, c);
  return TriClosestPts(a, b, c, y, uo, vo, region);
}

/* ------------------------------------------------------------------ hierarchy */

typedef struct {
  double d2;
  int    f;
} Best;

static inline int Better(double d2, int f, const Best *b) { return d2 < b->d2 || (d2 == b->d2 && f < b->f); }

/* Ties of the smoothed projection: two stationary points (each the foot of y on its patch) whose
   distances differ by less than FACETS_TIE of the surface's size are equally close (a point inside
   the crease between two patches, e.g. on a symmetry plane through their edge, or at a vertex,
   whose distances from either side differ by round-off only): the smaller facet index wins, so
   that the round-off of y (another partition, another summation order) cannot move the result
   from one patch to the other, nor the contact frame's chord of the first contact with it */
#define FACETS_TIE 1e-10

/* the candidates' radius of a smoothed surface: every patch that can be within the tie band of the
   closest one, from the distance d2 (squared) of a plane triangle */
static inline double CandidateRadius2(const FacetsData *m, double d2)
{
  const double r = sqrt(d2) + 2.0 * m->dev + FACETS_TIE * m->L;
  return r * r * (1.0 + 1e-12);
}

static inline double BoxDist2(const FacetsNode *n, const double y[3])
{
  double s = 0.0;
  for (int i = 0; i < 3; i++) {
    const double l = (double)n->lo[i] - y[i], h = y[i] - (double)n->hi[i];
    if (l > 0.0) s += l * l;
    else if (h > 0.0) s += h * h;
  }
  return s;
}

/* A lower bound of the squared distance from y to the facets of node n: the larger of the box's and
   the oriented box's. The oriented box's axes are float-rounded unit vectors, orthogonal to about
   1e-7: the sum of the squared components along them is at most (1 + 1e-6) |y - x|^2, so the sum
   times (1 - 1e-5) bounds |y - x|^2 from below (pruning stays exact, ties included) */
static inline double NodeDist2(const FacetsNode *n, const double y[3])
{
  double a[3][3], s = 0.0;
  const double b = BoxDist2(n, y);
  FacetsNodeAxes(n, a);
  for (int j = 0; j < 3; j++) {
    const double d = a[j][0] * y[0] + a[j][1] * y[1] + a[j][2] * y[2];
    const double l = (double)n->olo[j] - d, h = d - (double)n->ohi[j];
    if (l > 0.0) s += l * l;
    else if (h > 0.0) s += h * h;
  }
  s *= 1.0 - 1e-5;
  return s > b ? s : b;
}

/* the closest facet (smallest squared distance, then the smallest index) among those closer than
   b on entry; b unchanged if none. With list (smoothed surfaces): also every facet within
   sqrt(b) + 2 dev of y (a superset: filtered by FacetsFinish), at most 256 */
static void TreeClosestCollect(const FacetsData *m, const double y[3], Best *b, Best *list, int *nl)
{
  int    stack[128], ns = 0;
  double R2 = b->d2;
  if (!m->nnode) return;
  if (list) {
    *nl = 0;
    R2  = b->d2 < HUGE_VAL ? CandidateRadius2(m, b->d2) : HUGE_VAL;
  }
  stack[ns++] = 0;
  while (ns) {
    const FacetsNode *n = &m->node[stack[--ns]];
    if (NodeDist2(n, y) > R2) continue;
    if (n->count > 0) {
      for (int k = n->first; k < n->first + n->count; k++) {
        double       u, v;
        int          reg;
        const double d2 = TriClosest(m, k, y, &u, &v, &reg);
        if (Better(d2, k, b)) {
          b->d2 = d2;
          b->f  = k;
          if (list) R2 = CandidateRadius2(m, d2);
          else R2 = d2;
        }
        if (list && d2 <= R2 && *nl < 256) {
          list[*nl].d2 = d2;
          list[(*nl)++].f = k;
        }
      }
    } else {
      const int    l = n->first, r = n->first + 1;
      const double dl = NodeDist2(&m->node[l], y), dr = NodeDist2(&m->node[r], y);
      if (dl <= dr) { /* the nearer child is popped first */
        if (dr <= R2 && ns < 128) stack[ns++] = r;
        if (dl <= R2 && ns < 128) stack[ns++] = l;
      } else {
        if (dl <= R2 && ns < 128) stack[ns++] = l;
        if (dr <= R2 && ns < 128) stack[ns++] = r;
      }
    }
  }
}

static void TreeClosest(const FacetsData *m, const double y[3], Best *b) { TreeClosestCollect(m, y, b, NULL, NULL); }


/* ------------------------------------------------------------------ bucket grid */

/* A uniform grid in the tool's reference frame, cells of about a facet's size, hashed: each
   non-empty cell lists the facets whose bounding box meets it. Every point of a facet lies in a
   cell that lists it, so the cells that meet the cube [y - r, y + r] hold every facet within r of
   y: a warm start's bound r (the distance to a facet near the hint) is proved the smallest by
   those few cells, whatever the tool's size. */

#ifndef GRID_MAXCELLS
#define GRID_MAXCELLS 27
#endif
#ifndef GRID_SCALE
#define GRID_SCALE 2.0
#endif

static inline long GridIndex(const FacetsData *m, int i, double x) { return (long)floor((x - m->go[i]) / m->gh); }

/* a cell's key: its indices packed, ix + nx (iy + ny iz) (below INT_MAX: FacetsGridBuild) */
static inline int GridKey(const FacetsData *m, long ix, long iy, long iz) { return (int)(ix + m->gn[0] * (iy + m->gn[1] * iz)); }

static inline unsigned GridSlot(long ix, long iy, long iz, int cap)
{ /* blocks of 4 x 4 x 4 cells on 64 consecutive slots (neighbouring cells share cache lines), the
     blocks scattered by splitmix64's finaliser */
  unsigned long long z = ((unsigned long long)(ix >> 2) << 42) | ((unsigned long long)(iy >> 2) << 21) | (unsigned long long)(iz >> 2);
  z                    = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ULL;
  z                    = (z ^ (z >> 27)) * 0x94D049BB133111EBULL;
  z ^= z >> 31;
  return (unsigned)((z << 6) | (unsigned long long)(((ix & 3) << 4) | ((iy & 3) << 2) | (iz & 3))) & (unsigned)(cap - 1);
}

static const FacetsCell *GridFind(const FacetsData *m, long ix, long iy, long iz)
{
  const int key = GridKey(m, ix, iy, iz);
  for (unsigned s = GridSlot(ix, iy, iz, m->gcap);; s = (s + 1) & (unsigned)(m->gcap - 1)) {
    const FacetsCell *c = &m->gcell[s];
    if (c->key == key) return c;
    if (c->key < 0) return NULL;
  }
}

/* the grid's table while it is built: a cell's key, its list's start and length */
typedef struct {
  int key, start, count;
} GridBuildCell;

static GridBuildCell *GridInsert(GridBuildCell *cell, int cap, int key, long ix, long iy, long iz)
{
  for (unsigned s = GridSlot(ix, iy, iz, cap);; s = (s + 1) & (unsigned)(cap - 1)) {
    if (cell[s].key == key) return &cell[s];
    if (cell[s].key < 0) {
      cell[s].key   = key;
      cell[s].count = 0;
      return &cell[s];
    }
  }
}

static void FacetBoxCells(const FacetsData *m, int f, long lo[3], long hi[3])
{
  for (int i = 0; i < 3; i++) {
    double a = HUGE_VAL, b = -HUGE_VAL;
    for (int k = 0; k < 3; k++) {
      a = fmin(a, m->V[3 * m->F[3 * f + k] + i]);
      b = fmax(b, m->V[3 * m->F[3 * f + k] + i]);
    }
    lo[i] = GridIndex(m, i, a);
    hi[i] = GridIndex(m, i, b);
  }
}

/* Cells of GRID_SCALE times the facets' mean largest box extent (a cube y -+ r with r below about a
   facet's size meets at most 8 cells), grown where the cells' count would not fit an int key. The
   table: a cell's key and the start of its list, the last facet of each list stored as -1 - f, at
   most half full (slots a power of 2). */
PetscErrorCode FacetsGridBuild(FacetsData *m)
{
  double         bl[3] = {HUGE_VAL, HUGE_VAL, HUGE_VAL}, bh[3] = {-HUGE_VAL, -HUGE_VAL, -HUGE_VAL}, h = 0.0;
  int            ncell = 0, cap = 64;
  long long      total = 0;
  GridBuildCell *cell;

  PetscFunctionBeginUser;
  m->gcap   = 0;
  m->nglist = 0;
  m->gcell  = NULL;
  m->glist  = NULL;
  if (m->nf <= 0) PetscFunctionReturn(0);
  for (int k = 0; k < m->nv; k++)
    for (int i = 0; i < 3; i++) {
      bl[i] = fmin(bl[i], m->V[3 * k + i]);
      bh[i] = fmax(bh[i], m->V[3 * k + i]);
    }
  for (int f = 0; f < m->nf; f++) { /* the mean of the facets' largest box extents */
    double e = 0.0;
    for (int i = 0; i < 3; i++) {
      double a = HUGE_VAL, b = -HUGE_VAL;
      for (int k = 0; k < 3; k++) {
        a = fmin(a, m->V[3 * m->F[3 * f + k] + i]);
        b = fmax(b, m->V[3 * m->F[3 * f + k] + i]);
      }
      e = fmax(e, b - a);
    }
    h += e / m->nf;
  }
  h *= GRID_SCALE;
  if (!(h > 0.0) || !isfinite(h)) PetscFunctionReturn(0);
  for (;; h *= 1.25) { /* the cells' count within an int: ix + nx (iy + ny iz) a key */
    double n = 1.0;
    for (int i = 0; i < 3; i++) n *= floor((bh[i] - bl[i]) / h) + 5.0;
    if (n < 0.5 * INT_MAX) break;
  }
  m->gh = h;
  for (int i = 0; i < 3; i++) {
    m->go[i] = bl[i] - 2.0 * h;
    m->gn[i] = GridIndex(m, i, bh[i]) + 3; /* the tool's cells 2 .. gn - 3 */
  }
  for (int f = 0; f < m->nf; f++) {
    long lo[3], hi[3];
    FacetBoxCells(m, f, lo, hi);
    total += (long long)(hi[0] - lo[0] + 1) * (hi[1] - lo[1] + 1) * (hi[2] - lo[2] + 1);
  }
  if (total > INT_MAX / 2) PetscFunctionReturn(0); /* no grid: the hierarchy alone */
  PetscCall(PetscMalloc1((size_t)cap, &cell));
  for (int s = 0; s < cap; s++) cell[s].key = -1;
  /* three passes over the cells of each facet's box: count the facets per cell (growing the
     table), give each list its start in the order the facets first meet the cells (the
     hierarchy's order: neighbouring cells' lists are near), fill the lists */
  for (int pass = 0; pass < 3; pass++) {
    int start = 0;
    if (pass == 1) {
      PetscCall(PetscMalloc1((size_t)total, &m->glist));
      for (int s = 0; s < cap; s++) cell[s].start = -1;
    }
    for (int f = 0; f < m->nf; f++) {
      long lo[3], hi[3];
      FacetBoxCells(m, f, lo, hi);
      for (long ix = lo[0]; ix <= hi[0]; ix++)
        for (long iy = lo[1]; iy <= hi[1]; iy++)
          for (long iz = lo[2]; iz <= hi[2]; iz++) {
            GridBuildCell *c = GridInsert(cell, cap, GridKey(m, ix, iy, iz), ix, iy, iz);
            if (pass == 1) {
              if (c->start < 0) {
                c->start = start;
                start += c->count;
                c->count = 0;
              }
              continue;
            }
            if (pass == 2) m->glist[c->start + c->count] = f;
            else if (c->count == 0) ncell++;
            c->count++;
            if (pass == 0 && 2 * ncell > cap) { /* grow: rehash at twice the size */
              GridBuildCell *old = cell;
              const int      oc  = cap;
              cap *= 2;
              PetscCall(PetscMalloc1((size_t)cap, &cell));
              for (int s = 0; s < cap; s++) cell[s].key = -1;
              for (int s = 0; s < oc; s++)
                if (old[s].key >= 0) { /* the key's cell indices back */
                  const long k = old[s].key, kx = k % m->gn[0], ky = (k / m->gn[0]) % m->gn[1], kz = k / ((long)m->gn[0] * m->gn[1]);
                  *GridInsert(cell, cap, old[s].key, kx, ky, kz) = old[s];
                }
              PetscCall(PetscFree(old));
            }
          }
    }
    if (pass == 1) m->nglist = start;
  }
  PetscCall(PetscMalloc1((size_t)cap, &m->gcell));
  for (int s = 0; s < cap; s++) {
    m->gcell[s].key   = cell[s].key;
    m->gcell[s].start = cell[s].start;
    if (cell[s].key >= 0) m->glist[cell[s].start + cell[s].count - 1] = -1 - m->glist[cell[s].start + cell[s].count - 1]; /* the list's end */
  }
  PetscCall(PetscFree(cell));
  m->gcap = cap;
  PetscFunctionReturn(0);
}

/* a facet whose distance is known (the walk's and the grid's evaluations; listed: in the list of
   candidates) */
typedef struct {
  int    f, listed;
  double d2;
} Seen;

#define SEEN_MAX 64

/* facet k's squared distance to y, computed once (a facet found again takes its record: seen).
   Returns 1 when k needs nothing more (seen before, and no list is kept or it is listed already);
   *q: its record, -1 when the records are full */
static inline int SeenDistance(const FacetsData *m, int k, const double y[3], int listing, Seen *seen, int *ns, int *q, double *d2)
{
  *q = 0;
  while (*q < *ns && seen[*q].f != k) (*q)++;
  if (*q < *ns) {
    if (!listing || seen[*q].listed) return 1;
    *d2 = seen[*q].d2;
  } else {
    double u, v;
    int    reg;
    *d2 = TriClosest(m, k, y, &u, &v, &reg);
    if (*ns < SEEN_MAX) {
      seen[*ns].f      = k;
      seen[*ns].listed = 0;
      seen[(*ns)++].d2 = *d2;
    } else *q = -1; /* not recorded */
  }
  return 0;
}

/* candidate k (record q) into the list, once; returns 1 when the list is full */
static inline int ListAdd(Best *list, int *nl, Seen *seen, int q, int k, double d2)
{
  if (q < 0) { /* not recorded: listed already? */
    for (int t = 0; t < *nl; t++)
      if (list[t].f == k) return 0;
  } else seen[q].listed = 1;
  if (*nl == 256) return 1;
  list[*nl].d2    = d2;
  list[(*nl)++].f = k;
  return 0;
}

/* The closest facet as TreeClosestCollect from b (a facet's distance: the warm start's bound),
   searching only the grid's cells within that bound; seen: the facets already evaluated (each
   facet is evaluated once, though it is listed in several cells). Returns 1 (b, list untouched or
   to be redone) when the bound spans more than GRID_MAXCELLS cells or the list would overflow: the
   hierarchy's turn */
static int GridClosestCollect(const FacetsData *m, const double y[3], Best *b, Best *list, int *nl, Seen *seen, int *ns)
{
  double R2 = b->d2;
  long   lo[3], hi[3];
  if (!m->gcap || !(b->d2 < HUGE_VAL)) return 1;
  if (list) {
    *nl = 0;
    R2  = CandidateRadius2(m, b->d2);
  }
  {
    const double r = sqrt(R2) * (1.0 + 1e-9) + 1e-12 * m->L; /* outwards of the rounding of y -+ r */
    long         n = 1;
    for (int i = 0; i < 3; i++) {
      lo[i] = GridIndex(m, i, y[i] - r);
      hi[i] = GridIndex(m, i, y[i] + r);
      if (lo[i] < 0) lo[i] = 0;
      if (hi[i] > m->gn[i] - 1) hi[i] = m->gn[i] - 1;
      if (hi[i] < lo[i]) return 0; /* no cell of the tool within r: none closer than b */
      n *= hi[i] - lo[i] + 1;
    }
    if (n > GRID_MAXCELLS) return 1;
  }
  for (long ix = lo[0]; ix <= hi[0]; ix++)
    for (long iy = lo[1]; iy <= hi[1]; iy++)
      for (long iz = lo[2]; iz <= hi[2]; iz++) {
        const long idx[3] = {ix, iy, iz};
        double     bd = 0.0;
        for (int i = 0; i < 3; i++) { /* the cell's distance from y (rounded down) */
          const double a = m->go[i] + idx[i] * m->gh, o = fmax(a - y[i], y[i] - (a + m->gh));
          if (o > 0.0) bd += o * o;
        }
        if (bd * (1.0 - 1e-9) > R2) continue;
        const FacetsCell *c = GridFind(m, ix, iy, iz);
        int               j, last;
        if (!c) continue;
        j = c->start;
        do { /* the cell's list, its last facet stored as -1 - f */
          int    k = m->glist[j++], q;
          double d2;
          last = k < 0;
          if (last) k = -1 - k;
          if (SeenDistance(m, k, y, list != NULL, seen, ns, &q, &d2)) continue;
          if (Better(d2, k, b)) {
            b->d2 = d2;
            b->f  = k;
            if (list) R2 = CandidateRadius2(m, d2);
            else R2 = d2;
          }
          if (list && d2 <= R2 && ListAdd(list, nl, seen, q, k, d2)) return 1;
        } while (!last);
      }
  return 0;
}

/* ------------------------------------------------------------------ local certificate */

/* Each triangle's clearance c_f: a lower bound of its distance to every triangle that shares no
   vertex with it. A point y at distance d_w of triangle f (the warm start's walk) has every facet
   within r of it within d_w + r of f; if d_w + r < c_f, those facets share a vertex with f, and
   the facets around f's three vertices alone give the closest facet (and the smoothed candidates
   within r), exactly as the hierarchy does, without the grid or the hierarchy: a node near the
   surface touches its own few facets, whatever the tool's size. */

/* a hint to the processor that *a will be read soon (no effect on the results) */
static inline void Prefetch(const void *a)
{
#if defined(__GNUC__)
  __builtin_prefetch(a);
#else
  (void)a;
#endif
}

/* squared distance between the segments p1 q1 and p2 q2 (Ericson 5.1.9; non-degenerate segments) */
static double SegSeg2(const double p1[3], const double q1[3], const double p2[3], const double q2[3])
{
  double d1[3], d2[3], r[3], c1[3], c2[3], s, t;
  for (int i = 0; i < 3; i++) {
    d1[i] = q1[i] - p1[i];
    d2[i] = q2[i] - p2[i];
    r[i]  = p1[i] - p2[i];
  }
  const double a = Dot(d1, d1), e = Dot(d2, d2), f = Dot(d2, r), c = Dot(d1, r), b = Dot(d1, d2), den = a * e - b * b;
  s = den > 0.0 ? Clamp01((b * f - c * e) / den) : 0.0;
  t = (b * s + f) / e;
  if (t < 0.0) {
    t = 0.0;
    s = Clamp01(-c / a);
  } else if (t > 1.0) {
    t = 1.0;
    s = Clamp01((b - c) / a);
  }
  for (int i = 0; i < 3; i++) {
    c1[i] = p1[i] + d1[i] * s;
    c2[i] = p2[i] + d2[i] * t;
  }
  return Dist2(c1, c2);
}

/* 1 if the segment p q crosses the plane of triangle T inside it (or on its boundary) */
static int SegPierces(const double p[3], const double q[3], const double T[3][3])
{
  double e1[3], e2[3], n[3], x[3], w[3][3];
  for (int i = 0; i < 3; i++) {
    e1[i] = T[1][i] - T[0][i];
    e2[i] = T[2][i] - T[0][i];
  }
  Cross(e1, e2, n);
  const double dp = (p[0] - T[0][0]) * n[0] + (p[1] - T[0][1]) * n[1] + (p[2] - T[0][2]) * n[2];
  const double dq = (q[0] - T[0][0]) * n[0] + (q[1] - T[0][1]) * n[1] + (q[2] - T[0][2]) * n[2];
  if ((dp > 0.0 && dq > 0.0) || (dp < 0.0 && dq < 0.0) || dp == dq) return 0; /* one side, or in the plane (the distances of the vertices and edges decide) */
  const double t = dp / (dp - dq);
  for (int i = 0; i < 3; i++) x[i] = p[i] + t * (q[i] - p[i]);
  for (int k = 0; k < 3; k++) { /* inside: x on the inner side of every edge (with a margin) */
    double ek[3], xk[3];
    for (int i = 0; i < 3; i++) {
      ek[i] = T[(k + 1) % 3][i] - T[k][i];
      xk[i] = x[i] - T[k][i];
    }
    Cross(ek, xk, w[k]);
    if (Dot(w[k], n) < -1e-9 * Dot(n, n)) return 0;
  }
  return 1;
}

/* squared distance between two triangles: 0 if one crosses the other, else the least of the
   vertex-triangle and edge-edge distances */
static double TriTri2(const double A[3][3], const double B[3][3])
{
  double best = HUGE_VAL, u, v;
  int    reg;
  for (int k = 0; k < 3; k++)
    if (SegPierces(A[k], A[(k + 1) % 3], B) || SegPierces(B[k], B[(k + 1) % 3], A)) return 0.0;
  for (int k = 0; k < 3; k++) {
    best = fmin(best, TriClosestPts(B[0], B[1], B[2], A[k], &u, &v, &reg));
    best = fmin(best, TriClosestPts(A[0], A[1], A[2], B[k], &u, &v, &reg));
    for (int j = 0; j < 3; j++) best = fmin(best, SegSeg2(A[k], A[(k + 1) % 3], B[j], B[(j + 1) % 3]));
  }
  return best;
}

static inline double BoxBox2(const FacetsNode *n, const double lo[3], const double hi[3])
{
  double s = 0.0;
  for (int i = 0; i < 3; i++) {
    const double o = fmax((double)n->lo[i] - hi[i], lo[i] - (double)n->hi[i]);
    if (o > 0.0) s += o * o;
  }
  return s;
}

PetscErrorCode FacetsLocalBuild(FacetsData *m)
{
  int *vfs, *vf, stack[128];

  PetscFunctionBeginUser;
  PetscCall(PetscCalloc1((size_t)m->nv + 1, &vfs)); /* the facets around each vertex, increasing */
  PetscCall(PetscMalloc1(3 * (size_t)m->nf, &vf));
  for (int k = 0; k < 3 * m->nf; k++) vfs[m->F[k] + 1]++;
  for (int k = 0; k < m->nv; k++) vfs[k + 1] += vfs[k];
  {
    int *fill;
    PetscCall(PetscCalloc1((size_t)m->nv, &fill));
    for (int f = 0; f < m->nf; f++)
      for (int c = 0; c < 3; c++) {
        const int k              = m->F[3 * f + c];
        vf[vfs[k] + fill[k]++] = f;
      }
    PetscCall(PetscFree(fill));
  }
  m->vfs = vfs;
  m->vf  = vf;
  PetscCall(PetscMalloc1((size_t)m->nf, &m->clear));
  for (int f = 0; f < m->nf; f++) {
    double    A[3][3], lo[3], hi[3], h2 = 0.0, cl, cl2;
    int       ns = 0;
    const int *Ff = &m->F[3 * f];
    for (int c = 0; c < 3; c++) Corner(m, f, c, A[c]);
    for (int i = 0; i < 3; i++) {
      lo[i] = fmin(A[0][i], fmin(A[1][i], A[2][i]));
      hi[i] = fmax(A[0][i], fmax(A[1][i], A[2][i]));
    }
    for (int c = 0; c < 3; c++) h2 = fmax(h2, Dist2(A[c], A[(c + 1) % 3]));
    cl          = sqrt(h2); /* searched up to the longest edge: beyond it, the bound itself */
    cl2         = h2;
    stack[ns++] = 0;
    while (ns) {
      const FacetsNode *n = &m->node[stack[--ns]];
      if (BoxBox2(n, lo, hi) >= cl2) continue;
      if (n->count > 0) {
        for (int g = n->first; g < n->first + n->count; g++) {
          double B[3][3], bl[3], bh[3], o2 = 0.0;
          int    in = 0; /* in f's star: sharing a vertex with it */
          for (int c = 0; c < 3 && !in; c++) in = m->F[3 * g + c] == Ff[0] || m->F[3 * g + c] == Ff[1] || m->F[3 * g + c] == Ff[2];
          if (in) continue;
          for (int c = 0; c < 3; c++) Corner(m, g, c, B[c]);
          for (int i = 0; i < 3; i++) { /* the boxes first */
            bl[i]          = fmin(B[0][i], fmin(B[1][i], B[2][i]));
            bh[i]          = fmax(B[0][i], fmax(B[1][i], B[2][i]));
            const double o = fmax(bl[i] - hi[i], lo[i] - bh[i]);
            if (o > 0.0) o2 += o * o;
          }
          if (o2 >= cl2) continue;
          const double d2 = TriTri2(A, B);
          if (d2 < cl2) {
            cl2 = d2;
            cl  = sqrt(d2);
          }
        }
      } else if (ns < 127) {
        stack[ns++] = n->first;
        stack[ns++] = n->first + 1;
      } else cl = cl2 = 0.0; /* too deep: no certificate for this facet */
    }
    cl *= 1.0 - 1e-9; /* the round-off of the distances */
    m->clear[f] = (float)cl;
    if ((double)m->clear[f] > cl) m->clear[f] = nextafterf(m->clear[f], 0.0f);
  }
  PetscFunctionReturn(0);
}

/* The closest facet as TreeClosestCollect, from the facets around the vertices of b's facet, when
   b's clearance proves that they hold every facet within the search radius (b: the walk's facet
   and its distance). Returns 1 (b, list to be redone) when it does not, or the list would overflow */
static int LocalClosestCollect(const FacetsData *m, const double y[3], Best *b, Best *list, int *nl, Seen *seen, int *ns)
{
  const int    f0 = b->f;
  const double R2 = list ? CandidateRadius2(m, b->d2) : b->d2;
  if (!m->clear || f0 == INT_MAX) return 1;
  if (sqrt(b->d2) * (1.0 + 1e-12) + sqrt(R2) * (1.0 + 1e-12) >= (double)m->clear[f0]) return 1;
  if (list) *nl = 0;
  {
    const int *V0 = &m->F[3 * f0];
    for (int c = 0; c < 3; c++) /* the star's facets, then their vertices: their cache misses overlap */
      for (int j = m->vfs[V0[c]]; j < m->vfs[V0[c] + 1]; j++) Prefetch(&m->F[3 * m->vf[j]]);
    for (int c = 0; c < 3; c++)
      for (int j = m->vfs[V0[c]]; j < m->vfs[V0[c] + 1]; j++)
        for (int i = 0; i < 3; i++) Prefetch(&m->V[3 * m->F[3 * m->vf[j] + i]]);
    for (int c = 0; c < 3; c++)
      for (int j = m->vfs[V0[c]]; j < m->vfs[V0[c] + 1]; j++) {
        const int  k = m->vf[j], *Fk = &m->F[3 * k];
        int        q, dup = 0;
        double     d2;
        for (int c2 = 0; c2 < c && !dup; c2++) dup = Fk[0] == V0[c2] || Fk[1] == V0[c2] || Fk[2] == V0[c2]; /* met around an earlier vertex */
        if (dup) continue;
        if (SeenDistance(m, k, y, list != NULL, seen, ns, &q, &d2)) continue;
        if (Better(d2, k, b)) {
          b->d2 = d2;
          b->f  = k;
        }
        if (list && d2 <= R2 && ListAdd(list, nl, seen, q, k, d2)) return 1;
      }
  }
  return 0;
}

/* ------------------------------------------------------------------ projection */

/* Newton on |x(u, v) - y|^2 / 2 over facet f's (extended) patch from (u, v); returns 0 when it
   converged (inside the facet or not) */
static int PatchNewton(const FacetGeom *gm, const double y[3], double *uo, double *vo)
{
  double u = *uo, v = *vo, last = HUGE_VAL;
  for (int it = 0; it < 40; it++) {
    double x[3], xu[3], xv[3], xuu[3], xuv[3], xvv[3], r[3], g[2], H[3], det, d[2];
    FacetGeomEval(gm, u, v, x, xu, xv, xuu, xuv, xvv);
    for (int i = 0; i < 3; i++) r[i] = x[i] - y[i];
    g[0] = Dot(r, xu);
    g[1] = Dot(r, xv);
    H[0] = Dot(xu, xu) + Dot(r, xuu);
    H[1] = Dot(xu, xv) + Dot(r, xuv);
    H[2] = Dot(xv, xv) + Dot(r, xvv);
    det  = H[0] * H[2] - H[1] * H[1];
    if (!(H[0] > 0.0 && det > 1e-14 * H[0] * H[2])) { /* Gauss-Newton */
      H[0] = Dot(xu, xu);
      H[1] = Dot(xu, xv);
      H[2] = Dot(xv, xv);
      det  = H[0] * H[2] - H[1] * H[1];
      if (!(det > 0.0)) return 1;
    }
    d[0] = -(H[2] * g[0] - H[1] * g[1]) / det;
    d[1] = -(H[0] * g[1] - H[1] * g[0]) / det;
    const double dl = fabs(d[0]) + fabs(d[1]);
    if (dl > 0.5) {
      d[0] *= 0.5 / dl;
      d[1] *= 0.5 / dl;
    }
    u += d[0];
    v += d[1];
    last = fabs(d[0]) + fabs(d[1]);
    if (last < 1e-13) {
      *uo = u;
      *vo = v;
      return 0;
    }
    if (u < -1.0 || v < -1.0 || u + v > 2.0) break;
  }
  *uo = u;
  *vo = v;
  return last < 1e-9 ? 0 : 2; /* converged to round-off; or no convergence within the neighbourhood */
}

/* closest point on edge e of facet f's patch (1D Newton on the edge parameter, clamped) */
static void EdgeClosest(const FacetGeom *gm, int e, const double y[3], double *uo, double *vo)
{
  double t = e == 0 ? *uo : (e == 1 ? *vo : 1.0 - *vo);
  t        = Clamp01(t);
  for (int it = 0; it < 40; it++) {
    double x[3], xu[3], xv[3], xuu[3], xuv[3], xvv[3], xt[3], xtt[3], r[3], u, v;
    if (e == 0) u = t, v = 0.0;
    else if (e == 1) u = 1.0 - t, v = t;
    else u = 0.0, v = 1.0 - t;
    FacetGeomEval(gm, u, v, x, xu, xv, xuu, xuv, xvv);
    for (int i = 0; i < 3; i++) {
      r[i] = x[i] - y[i];
      if (e == 0) xt[i] = xu[i], xtt[i] = xuu[i];
      else if (e == 1) xt[i] = xv[i] - xu[i], xtt[i] = xuu[i] - 2.0 * xuv[i] + xvv[i];
      else xt[i] = -xv[i], xtt[i] = xvv[i];
    }
    double h = Dot(xt, xt) + Dot(r, xtt);
    if (!(h > 0.0)) h = Dot(xt, xt);
    const double tn = Clamp01(t - Dot(r, xt) / h), dt = tn - t;
    t               = tn;
    if (fabs(dt) < 1e-14) break;
  }
  if (e == 0) *uo = t, *vo = 0.0;
  else if (e == 1) *uo = 1.0 - t, *vo = t;
  else *uo = 0.0, *vo = 1.0 - t;
}

/* closest point of y on facet f's patch (its triangle): Newton inside, else the best of its three
   edges; *edge = -1 inside, else the edge (0: P0P1, 1: P1P2, 2: P2P0) */
static double PatchClosestLocal(const FacetsData *m, int f, const double y[3], double *uo, double *vo, int *edge)
{
  double    u, v, x[3], xu[3], xv[3], best = HUGE_VAL;
  int       reg;
  FacetGeom gm;
  TriClosest(m, f, y, &u, &v, &reg);
  FacetGeomSet(m, f, &gm);
  {
    double uc = u, vc = v;
    if (!PatchNewton(&gm, y, &uc, &vc) && uc >= 0.0 && vc >= 0.0 && uc + vc <= 1.0) {
      FacetGeomEval(&gm, uc, vc, x, xu, xv, NULL, NULL, NULL);
      *uo   = uc;
      *vo   = vc;
      *edge = -1;
      return Dist2(x, y);
    }
  }
  for (int e = 0; e < 3; e++) {
    double ue = u, ve = v;
    EdgeClosest(&gm, e, y, &ue, &ve);
    FacetGeomEval(&gm, ue, ve, x, xu, xv, NULL, NULL, NULL);
    const double d2 = Dist2(x, y);
    if (d2 < best) {
      best  = d2;
      *uo   = ue;
      *vo   = ve;
      *edge = e;
    }
  }
  return best;
}

/* an edge-held closest point of facet f's patch that is stationary all the same: y - x normal to
   the patch there (tangential offset below 1e-9 of the facet's size; the foot of y on the edge) */
static int Stationary(const FacetsData *m, int f, const double y[3], double u, double v)
{
  double x[3], xu[3], xv[3], n[3], r[3], P0[3], P1[3], P2[3];
  FacetEvalLocal(m, f, u, v, x, xu, xv, NULL, NULL, NULL);
  Cross(xu, xv, n);
  const double ln = Norm(n);
  if (!(ln > 0.0)) return 0;
  for (int i = 0; i < 3; i++) {
    n[i] /= ln;
    r[i] = y[i] - x[i];
  }
  const double rn = Dot(r, n), t2 = Dot(r, r) - rn * rn;
  Corner(m, f, 0, P0);
  Corner(m, f, 1, P1);
  Corner(m, f, 2, P2);
  const double hf2 = fmax(Dist2(P0, P1), fmax(Dist2(P1, P2), Dist2(P2, P0)));
  return t2 <= 1e-18 * hf2;
}

/* The closest point from the hierarchy's answer b (the closest plane triangle). Raw facets: that
   triangle. Smoothed: every facet whose triangle lies within sqrt(b) + 2 dev + tie of y (dev: the
   largest distance of a patch from its triangle) is a candidate; on each, the closest point of its
   patch; the smallest distance wins (equal distances: the smaller facet index), except that among
   two or more stationary points within the tie band of the smallest distance the smallest facet
   index wins (FACETS_TIE). A point beside an open edge (its tangential offset above 1e-9 of the
   facet's size) is no contact (1). */
static int FacetsFinish(const Patch *p, const FacetsData *m, const double y[3], double L, const Best *b, Best *list, const int *nl, PatchCandidate *c)
{
  double u, v, x[3], xu[3], xv[3];
  int    reg, f = b->f;
  TriClosest(m, f, y, &u, &v, &reg);
  if (m->smooth) {
    Best         tmp;
    double       cd[256], cu[256], cv[256], dmin = HUGE_VAL;
    int          ce[256], cs[256], edge = -1, nc = 0, ne = 0, win = -1, anys = 0;
    const double r2 = CandidateRadius2(m, b->d2), tie = FACETS_TIE * m->L;
    for (int k = 0; k < *nl; k++) /* the candidates within sqrt(b) + 2 dev + tie, by distance, then index */
      if (list[k].d2 <= r2) {
        int j = nc++;
        tmp   = list[k];
        while (j > 0 && Better(tmp.d2, tmp.f, &list[j - 1])) {
          list[j] = list[j - 1];
          j--;
        }
        list[j] = tmp;
      }
    for (int k = 0; k < nc; k++, ne++) {
      if (sqrt(list[k].d2) - m->dev > (dmin + tie) * (1.0 + 1e-12)) break; /* no patch farther on can be within the tie band */
      ce[k] = -1;
      cd[k] = sqrt(PatchClosestLocal(m, list[k].f, y, &cu[k], &cv[k], &ce[k]));
      cs[k] = ce[k] < 0 || Stationary(m, list[k].f, y, cu[k], cv[k]);
      if (cd[k] < dmin) dmin = cd[k];
    }
    for (int k = 0; k < ne; k++) {
      if (cd[k] <= dmin + tie && cs[k]) anys++;
      if (win < 0 || cd[k] < cd[win] || (cd[k] == cd[win] && list[k].f < list[win].f)) win = k;
    }
    if (anys > 1) /* two stationary points within the tie band: the smallest facet index */
      for (int k = 0; k < ne; k++)
        if (cd[k] <= dmin + tie && cs[k] && (!(cd[win] <= dmin + tie && cs[win]) || list[k].f < list[win].f)) win = k;
    Best bb = {HUGE_VAL, INT_MAX};
    if (win >= 0) {
      bb.f = list[win].f;
      u    = cu[win];
      v    = cv[win];
      edge = ce[win];
    }
    if (bb.f != INT_MAX) f = bb.f;
    reg = edge < 0 ? 0 : 1 + edge;
    if (reg && m->adj[3 * f + edge] != -1) { /* on a shared edge: at an open vertex? */
      const double w = 1.0 - u - v;
      if (u <= 0.0 && v <= 0.0) reg = 4;
      else if (u >= 1.0) reg = 5;
      else if (v >= 1.0) reg = 6;
      else if (w >= 1.0) reg = 4;
    }
  }
  /* beside an open edge or at an open vertex: no contact */
  if (reg) {
    int open = 0;
    if (reg <= 3) open = m->adj[3 * f + reg - 1] == -1;
    else open = m->vbnd[m->F[3 * f + reg - 4]];
    /* y must lie on the patch's normal there (the foot on the edge), else it is beside the tool */
    if (open && !Stationary(m, f, y, u, v)) return 1;
  }
  FacetEvalLocal(m, f, u, v, x, xu, xv, NULL, NULL, NULL);
  FacetsEncode(f, u, v, &c->xi, &c->eta);
  for (int i = 0; i < 3; i++) c->x[i] = x[i];
  c->d2       = Dist2(x, y);
  c->interior = 1;
  (void)L;
  return 0;
}

static int FacetsClosest(const Patch *p, const double y[3], double maxdist, double L, PatchCandidate *c)
{
  const FacetsData *m = (const FacetsData *)p->data;
  Best              b = {maxdist < HUGE_VAL ? maxdist * maxdist : HUGE_VAL, INT_MAX}, list[256];
  int               nl = 0;
  TreeClosestCollect(m, y, &b, m->smooth ? list : NULL, &nl);
  if (b.f == INT_MAX) return 1;
  return FacetsFinish(p, m, y, L, &b, list, &nl, c);
}

/* The same result as FacetsClosest: the hint's facet's star when its clearance allows; else a
   greedy walk from it over the neighbours gives a facet and a bound; the facet's star proves (or
   improves) it when the facet's clearance allows
   (LocalClosestCollect), else the grid's cells within that bound; where the bound spans more
   cells, the hierarchy from its root with that bound (a walk that ends beyond maxdist: maxdist) */
static int FacetsClosestHint(const Patch *p, const double y[3], double maxdist, double L, double hxi, double heta, PatchCandidate *c)
{
  const FacetsData *m = (const FacetsData *)p->data;
  double            u, v;
  int               reg, f = FacetsDecode(m, hxi, heta, &u, &v), nl = 0, ns = 1;
  Best              b;
  Best              list[256];
  if (m->clear) {
    Prefetch(&m->clear[f]);
    Prefetch(&m->adj[3 * f]);
  }
  b.d2 = TriClosest(m, f, y, &u, &v, &reg);
  b.f  = f;
  Seen              seen[SEEN_MAX] = {{f, 0, b.d2}};
  /* the hint's facet first: where its clearance proves its star holds every facet within reach (a
     node that moved less than about its facet's size since), the star alone decides, without the
     walk (whose farther facets and their stars are more cache lines to read) */
  if (!(maxdist < HUGE_VAL && b.d2 > maxdist * maxdist) && !LocalClosestCollect(m, y, &b, m->smooth ? list : NULL, &nl, seen, &ns)) return FacetsFinish(p, m, y, L, &b, list, &nl, c);
  for (int step = 0; step < 64; step++) {
    int moved = 0;
    for (int e = 0; e < 3; e++) {
      const int nb = m->adj[3 * b.f + e];
      int       q  = 0;
      if (nb < 0) continue;
      while (q < ns && seen[q].f != nb) q++;
      if (q < ns) continue; /* evaluated already, not better */
      const double d2 = TriClosest(m, nb, y, &u, &v, &reg);
      if (ns < SEEN_MAX) {
        seen[ns].f        = nb;
        seen[ns].listed   = 0;
        seen[ns++].d2     = d2;
      }
      if (Better(d2, nb, &b)) {
        b.d2  = d2;
        b.f   = nb;
        moved = 1;
      }
    }
    if (!moved) break;
  }
  if (maxdist < HUGE_VAL && b.d2 > maxdist * maxdist) {
    b.d2 = maxdist * maxdist;
    b.f  = INT_MAX;
  }
  if (!LocalClosestCollect(m, y, &b, m->smooth ? list : NULL, &nl, seen, &ns)) return FacetsFinish(p, m, y, L, &b, list, &nl, c);
  for (int q = 0; q < ns; q++) seen[q].listed = 0; /* the grid lists again */
  if (GridClosestCollect(m, y, &b, m->smooth ? list : NULL, &nl, seen, &ns)) TreeClosestCollect(m, y, &b, m->smooth ? list : NULL, &nl);
  if (b.f == INT_MAX) return 1;
  return FacetsFinish(p, m, y, L, &b, list, &nl, c);
}

/* dn/dy: raw facets 0 (the facet's normal). Smoothed, at a projection inside the facet: from the
   stationarity of the closest point, H dz = [x_u x_v]^T dy (PatchProjectionParamDerivative),
   n = s N/|N|, N = x_u x x_v, dn = (I - n n) s (N_u dz_u + N_v dz_v)/|N|. Returns 1 on an edge
   (held there), where the caller differences. */
static int FacetsNormalDerivative(const Patch *p, const double shift[3], const double y[3], const Projection *pr, double dn[9])
{
  const FacetsData *m = (const FacetsData *)p->data;
  double            u, v, x[3], xu[3], xv[3], xuu[3], xuv[3], xvv[3], r[3], dz[2][3], N[3], Nu[3], Nv[3], a[3], b[3], n[3], l;
  const int         fr[2] = {1, 1};
  if (!m->smooth) return 0;
  const int f = FacetsDecode(m, pr->xi, pr->eta, &u, &v);
  if (u < -1e-9 || v < -1e-9 || 1.0 - u - v < -1e-9) return 1;
  FacetEvalLocal(m, f, u, v, x, xu, xv, xuu, xuv, xvv);
  for (int i = 0; i < 3; i++) r[i] = x[i] - (y[i] - shift[i]);
  {
    const double g0 = Dot(r, xu) / Norm(xu), g1 = Dot(r, xv) / Norm(xv);
    if (fabs(g0) + fabs(g1) > 1e-8 * (Norm(r) + Norm(xu))) return 1; /* not stationary: held */
  }
  if (PatchProjectionParamDerivative(xu, xv, xuu, xuv, xvv, r, fr, dz)) return 1;
  Cross(xu, xv, N);
  Cross(xuu, xv, a);
  Cross(xu, xuv, b);
  for (int i = 0; i < 3; i++) Nu[i] = a[i] + b[i];
  Cross(xuv, xv, a);
  Cross(xu, xvv, b);
  for (int i = 0; i < 3; i++) Nv[i] = a[i] + b[i];
  l = Norm(N);
  if (!(l > 0.0)) return 1;
  for (int i = 0; i < 3; i++) n[i] = N[i] / l;
  const double pu = Dot(n, Nu), pv = Dot(n, Nv), s = SenseSign(p);
  for (int i = 0; i < 3; i++) {
    const double nu = s * (Nu[i] - n[i] * pu) / l, nv = s * (Nv[i] - n[i] * pv) / l;
    for (int j = 0; j < 3; j++) dn[3 * i + j] = nu * dz[0][j] + nv * dz[1][j];
  }
  return 0;
}

static void FacetsBox(const Patch *p, double b[6])
{
  const FacetsData *m = (const FacetsData *)p->data;
  double            diag = 0.0;
  for (int i = 0; i < 3; i++) {
    b[2 * i]     = HUGE_VAL;
    b[2 * i + 1] = -HUGE_VAL;
  }
  for (int k = 0; k < m->nv; k++)
    for (int i = 0; i < 3; i++) {
      b[2 * i]     = fmin(b[2 * i], m->V[3 * k + i]);
      b[2 * i + 1] = fmax(b[2 * i + 1], m->V[3 * k + i]);
    }
  for (int i = 0; i < 3; i++) diag += (b[2 * i + 1] - b[2 * i]) * (b[2 * i + 1] - b[2 * i]);
  diag = 1e-9 * sqrt(diag);
  for (int i = 0; i < 3; i++) {
    b[2 * i] -= diag;
    b[2 * i + 1] += diag;
  }
}

static double FacetsScale(const Patch *p) { return ((const FacetsData *)p->data)->L; }

static PetscErrorCode FacetsSetFromOptions(PetscOptionItems *PetscOptionsObject, Patch *p, const char stem[])
{
  PetscFunctionBeginUser;
  PetscCall(FacetsPatchFromOptions(PetscOptionsObject, p, stem));
  PetscFunctionReturn(0);
}

static PetscErrorCode FacetsView(const Patch *p, PetscViewer v)
{
  const FacetsData *m = (const FacetsData *)p->data;

  PetscFunctionBeginUser;
  if (!m) {
    PetscCall(PetscViewerASCIIPrintf(v, "facets (empty)\n"));
    PetscFunctionReturn(0);
  }
  PetscCall(PetscViewerASCIIPrintf(v, "facets from %s: %d triangles, %d vertices, %d open edges, sense %d, %s (feature angle %g), %.0f bytes per facet\n", m->file, m->nf, m->nv, m->nopen, p->sense, m->smooth ? "smoothed (Nagata patches)" : "raw facets", m->feature_deg, (double)FacetsBytes(m) / m->nf));
  PetscFunctionReturn(0);
}

static PetscErrorCode FacetsDestroy(Patch *p)
{
  FacetsData *m = (FacetsData *)p->data;

  PetscFunctionBeginUser;
  if (!m) PetscFunctionReturn(0);
  PetscCall(PetscFree(m->V));
  PetscCall(PetscFree(m->F));
  PetscCall(PetscFree(m->adj));
  PetscCall(PetscFree(m->C));
  PetscCall(PetscFree(m->N));
  PetscCall(PetscFree(m->vbnd));
  PetscCall(PetscFree(m->curved));
  PetscCall(PetscFree(m->node));
  PetscCall(PetscFree(m->gcell));
  PetscCall(PetscFree(m->glist));
  PetscCall(PetscFree(m->clear));
  PetscCall(PetscFree(m->vfs));
  PetscCall(PetscFree(m->vf));
  PetscCall(PetscFree(m));
  p->data = NULL;
  PetscFunctionReturn(0);
}

size_t FacetsBytes(const FacetsData *m)
{
  return sizeof(*m) + (size_t)m->nv * (3 * sizeof(double) + 1) + (size_t)m->nf * (9 * sizeof(int) + 1) + (size_t)m->nn * 3 * sizeof(double) + (size_t)m->nnode * sizeof(FacetsNode) + (size_t)m->gcap * sizeof(FacetsCell) + (size_t)m->nglist * sizeof(int) + (m->clear ? (size_t)m->nf * (sizeof(float) + 3 * sizeof(int)) + ((size_t)m->nv + 1) * sizeof(int) : 0);
}

/* the storage of FacetsBytes per array, in bytes per facet (scripts/bench_tool_facets.c -bench_bytes) */
void FacetsBytesBreakdown(const FacetsData *m, FILE *fp)
{
  const double nf = (double)m->nf;
  fprintf(fp, "facets %d vertices %d normals %d nodes %d grid slots %d grid entries %d\n", m->nf, m->nv, m->nn, m->nnode, m->gcap, m->nglist);
  fprintf(fp, "V %.1f vbnd %.1f F %.1f adj %.1f C %.1f curved %.1f N %.1f node %.1f gcell %.1f glist %.1f clear %.1f vfs+vf %.1f total %.1f\n", 24.0 * m->nv / nf, m->nv / nf, 12.0, 12.0, 12.0, 1.0, 24.0 * m->nn / nf, (double)sizeof(FacetsNode) * m->nnode / nf, (double)sizeof(FacetsCell) * m->gcap / nf, 4.0 * m->nglist / nf, m->clear ? 4.0 : 0.0, m->clear ? (12.0 * nf + 4.0 * (m->nv + 1)) / nf : 0.0, (double)FacetsBytes(m) / nf);
}

int FacetsBruteClosest(const Patch *p, const double y[3], double *d2)
{
  const FacetsData *m = (const FacetsData *)p->data;
  Best              b = {HUGE_VAL, INT_MAX};
  for (int k = 0; k < m->nf; k++) {
    double    u, v;
    int       reg;
    const double e = TriClosest(m, k, y, &u, &v, &reg);
    if (Better(e, k, &b)) {
      b.d2 = e;
      b.f  = k;
    }
  }
  *d2 = b.d2;
  return b.f;
}

int FacetsTreeClosest(const Patch *p, const double y[3], double *d2)
{
  const FacetsData *m = (const FacetsData *)p->data;
  Best              b = {HUGE_VAL, INT_MAX};
  TreeClosest(m, y, &b);
  *d2 = b.d2;
  return b.f;
}

/* for the tests: the number of hierarchy nodes whose lower bound (NodeDist2) exceeds the squared
   distance from y to one of their facets (0: every bound holds at y), and the smallest margin
   (facet distance minus bound, squared distances) over the nodes */
static double SubtreeMin2(const FacetsData *m, int k, const double y[3])
{
  const FacetsNode *n = &m->node[k];
  double            d = HUGE_VAL;
  if (n->count > 0) {
    for (int f = n->first; f < n->first + n->count; f++) {
      double u, v;
      int    reg;
      d = fmin(d, TriClosest(m, f, y, &u, &v, &reg));
    }
    return d;
  }
  return fmin(SubtreeMin2(m, n->first, y), SubtreeMin2(m, n->first + 1, y));
}

int FacetsCheckNodeBounds(const Patch *p, const double y[3], double *margin)
{
  const FacetsData *m   = (const FacetsData *)p->data;
  int               bad = 0;
  *margin               = HUGE_VAL;
  for (int k = 0; k < m->nnode; k++) {
    const double d = SubtreeMin2(m, k, y), b = NodeDist2(&m->node[k], y);
    if (b > d) bad++;
    *margin = fmin(*margin, d - b);
  }
  return bad;
}

void FacetsEvalLocal(const FacetsData *m, int f, double u, double v, double x[3], double xu[3], double xv[3], double *xuu, double *xuv, double *xvv) { FacetEvalLocal(m, f, u, v, x, xu, xv, xuu, xuv, xvv); }

void FacetsEncodeForTest(int f, double u, double v, double *xi, double *eta) { FacetsEncode(f, u, v, xi, eta); }

double FacetsTriTriDistance2(const double A[3][3], const double B[3][3]) { return TriTri2(A, B); }

double FacetsPatchDistance2(const Patch *p, int f, const double y[3], int *stationary)
{
  const FacetsData *m = (const FacetsData *)p->data;
  double            u, v;
  int               e = -1;
  const double      d2 = PatchClosestLocal(m, f, y, &u, &v, &e);
  *stationary           = e < 0 || Stationary(m, f, y, u, v);
  return d2;
}

double FacetsClearance(const Patch *p, int f, int *nstar, int star[], int maxstar)
{ /* the star: the facets around f's vertices, each once */
  const FacetsData *m = (const FacetsData *)p->data;
  *nstar              = 0;
  if (!m->clear) return 0.0;
  for (int c = 0; c < 3; c++)
    for (int j = m->vfs[m->F[3 * f + c]]; j < m->vfs[m->F[3 * f + c] + 1]; j++) {
      int in = 0;
      for (int t = 0; t < *nstar && !in; t++) in = star[t] == m->vf[j];
      if (!in && *nstar < maxstar) star[(*nstar)++] = m->vf[j];
    }
  return (double)m->clear[f];
}

int FacetsStarCertifies(const Patch *p, int f, const double y[3])
{
  const FacetsData *m = (const FacetsData *)p->data;
  double            u, v;
  int               reg;
  const double      d2 = TriClosest(m, f, y, &u, &v, &reg), R2 = m->smooth ? CandidateRadius2(m, d2) : d2;
  return m->clear && sqrt(d2) * (1.0 + 1e-12) + sqrt(R2) * (1.0 + 1e-12) < (double)m->clear[f];
}

int FacetsOfParameters(const Patch *p, double xi, double eta, double *u, double *v) { return FacetsDecode((const FacetsData *)p->data, xi, eta, u, v); }

static const PatchOps FacetsOps = {
  .type             = "facets",
  .eval             = FacetsEval,
  .normal           = FacetsNormal,
  .scale            = FacetsScale,
  .closest          = FacetsClosest,
  .closesthint      = FacetsClosestHint,
  .normalderivative = FacetsNormalDerivative,
  .box              = FacetsBox,
  .setfromoptions   = FacetsSetFromOptions,
  .view             = FacetsView,
  .destroy          = FacetsDestroy,
};

PetscErrorCode PatchCreate_Facets(Patch *p)
{
  PetscFunctionBeginUser;
  p->ops = &FacetsOps;
  PetscFunctionReturn(0);
}
