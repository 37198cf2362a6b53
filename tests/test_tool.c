/* Unit tests of the rigid tools: patch derivatives against finite differences, normals, Coons
   patches, closest-point projection against brute force (single patches, the sphere's pole,
   multi-patch tools with seams), the normal derivative against finite differences, options. */
#define _POSIX_C_SOURCE 200809L /* clock_gettime */
#include <stdio.h>
#include <string.h>
#include <time.h>
#include <stdlib.h>
#include <unistd.h>

#include "testutil.h"
#include "tool.h"
#include "../src/tool/facets.h"

static const double PI = 3.14159265358979323846;

/* ------------------------------------------------------------------ small helpers */

static unsigned long long seed = 12345;
static double             urand(void) /* uniform in [0, 1) (64-bit LCG) */
{
  seed = seed * 6364136223846793005ULL + 1442695040888963407ULL;
  return (double)(seed >> 11) / 9007199254740992.0;
}
static double uni(double a, double b) { return a + (b - a) * urand(); }
/* every test that draws random points starts its own sequence from its name, so that a test's
   points do not depend on which tests ran before it (FNV-1a hash) */
static void reseed(const char *name)
{
  seed = 14695981039346656037ULL;
  for (const char *c = name; *c; c++) seed = (seed ^ (unsigned char)*c) * 1099511628211ULL;
}

static double dot(const double a[3], const double b[3]) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }
static double nrm(const double a[3]) { return sqrt(dot(a, a)); }
static double dist(const double a[3], const double b[3])
{
  const double d[3] = {a[0] - b[0], a[1] - b[1], a[2] - b[2]};
  return nrm(d);
}
static void cross(const double a[3], const double b[3], double c[3])
{
  c[0] = a[1] * b[2] - a[2] * b[1];
  c[1] = a[2] * b[0] - a[0] * b[2];
  c[2] = a[0] * b[1] - a[1] * b[0];
}
static void unit(double a[3])
{
  const double l = nrm(a);
  for (int i = 0; i < 3; i++) a[i] /= l;
}
static void set3(double v[3], double x, double y, double z)
{
  v[0] = x;
  v[1] = y;
  v[2] = z;
}
static double deg(double d) { return d * PI / 180.0; }

/* a cleared patch of a registered type */
static void settype(Patch *p, const char *type)
{
  if (PatchSetType(p, type)) {
    printf("not ok - PatchSetType(%s) failed\n", type);
    exit(1);
  }
}
static int istype(const Patch *p, const char *type) { return !strcmp(PatchGetType(p), type); }

/* axis a and reference e orthonormalised */
static void frame(Patch *p, double ax, double ay, double az, double rx, double ry, double rz)
{
  set3(p->rev.a, ax, ay, az);
  unit(p->rev.a);
  set3(p->rev.e, rx, ry, rz);
  const double pa = dot(p->rev.e, p->rev.a);
  for (int i = 0; i < 3; i++) p->rev.e[i] -= pa * p->rev.a[i];
  unit(p->rev.e);
}

static Patch make_plane(void)
{
  Patch p;
  memset(&p, 0, sizeof(p));
  settype(&p, "plane");
  p.sense = 1;
  set3(p.plane.o, 0.3, -0.2, 0.1);
  set3(p.plane.e1, 1, 0.4, -0.3);
  unit(p.plane.e1);
  set3(p.plane.e2, 0.2, 1, 0.5);
  const double pr = dot(p.plane.e2, p.plane.e1);
  for (int i = 0; i < 3; i++) p.plane.e2[i] -= pr * p.plane.e1[i];
  unit(p.plane.e2);
  p.plane.u0 = -0.5;
  p.plane.u1 = 0.7;
  p.plane.v0 = 0.1;
  p.plane.v1 = 1.2;
  return p;
}

/* a patch of revolution (sphere, cylinder, torus): centre c, radii R (and r, the torus's tube),
   axis a and reference direction e (frame()), ranges t0..t1 and s0..s1 in the type's units */
static Patch make_revolution(const char *type, int sense, const double c[3], double R, double r, const double a[3], const double e[3], double t0, double t1, double s0, double s1)
{
  Patch p;
  memset(&p, 0, sizeof(p));
  settype(&p, type);
  p.sense = sense;
  set3(p.rev.c, c[0], c[1], c[2]);
  p.rev.R = R;
  p.rev.r = r;
  frame(&p, a[0], a[1], a[2], e[0], e[1], e[2]);
  p.rev.t0 = t0;
  p.rev.t1 = t1;
  p.rev.s0 = s0;
  p.rev.s1 = s1;
  return p;
}

static Patch make_sphere(int sense)
{
  return make_revolution("sphere", sense, (const double[3]){0.1, 0.2, -0.3}, 1.3, 0, (const double[3]){0.2, 0.3, 1}, (const double[3]){1, 0, 0}, deg(20), deg(110), deg(-30), deg(80));
}

static Patch make_cylinder(int sense)
{
  return make_revolution("cylinder", sense, (const double[3]){-0.2, 0.1, 0.3}, 0.8, 0, (const double[3]){0.3, -0.2, 1}, (const double[3]){0, 1, 0}, deg(10), deg(200), -0.5, 0.9);
}

/* a spindle torus (r > R) on a tube angle range that keeps R + r cos ps >= R + r cos(80 deg) > 0:
   the shape of a punch's corner blend whose plan corner radius is below its profile radius */
static Patch make_spindle_torus(int sense)
{
  return make_revolution("torus", sense, (const double[3]){0.1, 0.2, -0.1}, 0.4, 1.1, (const double[3]){0.1, -0.1, 1}, (const double[3]){1, 0.2, 0}, deg(10), deg(100), deg(-80), deg(60));
}

static Patch make_torus(int sense)
{
  return make_revolution("torus", sense, (const double[3]){0.2, -0.1, 0.05}, 1.2, 0.35, (const double[3]){-0.1, 0.2, 1}, (const double[3]){1, 0.3, 0}, deg(0), deg(120), deg(-60), deg(150));
}

static void curve(Curve *c, CurveType t, const double a[3], const double b[3], const double cc[3])
{
  c->type = t;
  for (int i = 0; i < 3; i++) {
    c->a[i] = a[i];
    c->b[i] = b[i];
    c->c[i] = cc ? cc[i] : 0.0;
  }
}

/* conical Coons patch: two arcs (bottom, top) and two lines */
static Patch make_coons_cone(void)
{
  Patch  p;
  double a0[3], b0[3], c0[3], a1[3], b1[3], c1[3];
  memset(&p, 0, sizeof(p));
  settype(&p, "coons");
  p.sense = 1;
  set3(a0, 1, 0, 0);
  set3(b0, 0, 1, 0);
  set3(c0, 0, 0, 0);
  set3(a1, 1.2, 0, 1);
  set3(b1, 0, 1.2, 1);
  set3(c1, 0, 0, 1);
  curve(&p.coons.C0, CURVE_ARC, a0, b0, c0);
  curve(&p.coons.C1, CURVE_ARC, a1, b1, c1);
  curve(&p.coons.D0, CURVE_LINE, a0, a1, NULL);
  curve(&p.coons.D1, CURVE_LINE, b0, b1, NULL);
  return p;
}

/* the octant x, y, z >= 0 of the sphere |x - c| = R as 3 Coons patches of great-circle arcs,
   split through the centroid G of the spherical triangle and the midpoints of its sides */
static void octant_coons(const double c[3], double R, Patch q[3])
{
  double       N[3], X[3], Y[3], Mzx[3], Mzy[3], Mxy[3], G[3];
  const double s2 = 1.0 / sqrt(2.0), s3 = 1.0 / sqrt(3.0);
  for (int i = 0; i < 3; i++) {
    N[i]   = c[i] + R * (i == 2);
    X[i]   = c[i] + R * (i == 0);
    Y[i]   = c[i] + R * (i == 1);
    Mzx[i] = c[i] + R * s2 * (i != 1);
    Mzy[i] = c[i] + R * s2 * (i != 0);
    Mxy[i] = c[i] + R * s2 * (i != 2);
    G[i]   = c[i] + R * s3;
  }
  /* corners (0,0), (1,0), (1,1), (0,1): counterclockwise seen from outside */
  const double *Q[3][4] = {
    {N, Mzx, G, Mzy},
    {X, Mxy, G, Mzx},
    {Y, Mzy, G, Mxy}
  };
  for (int k = 0; k < 3; k++) {
    memset(&q[k], 0, sizeof(q[k]));
    settype(&q[k], "coons");
    q[k].sense = 1;
    curve(&q[k].coons.C0, CURVE_ARC, Q[k][0], Q[k][1], c); /* bottom: (0,0) -> (1,0) */
    curve(&q[k].coons.C1, CURVE_ARC, Q[k][3], Q[k][2], c); /* top:    (0,1) -> (1,1) */
    curve(&q[k].coons.D0, CURVE_ARC, Q[k][0], Q[k][3], c); /* left:   (0,0) -> (0,1) */
    curve(&q[k].coons.D1, CURVE_ARC, Q[k][1], Q[k][2], c); /* right:  (1,0) -> (1,1) */
  }
}

/* the octant of the unit sphere as one Coons patch whose bottom side is collapsed into the pole:
   left and right are meridians, top the equator arc */
static Patch make_coons_collapsed(void)
{
  Patch        p;
  const double c[3] = {0, 0, 0}, N[3] = {0, 0, 1}, X[3] = {1, 0, 0}, Y[3] = {0, 1, 0};
  memset(&p, 0, sizeof(p));
  settype(&p, "coons");
  p.sense = -1; /* x_xi x x_eta points into the sphere */
  curve(&p.coons.C0, CURVE_LINE, N, N, NULL);
  curve(&p.coons.C1, CURVE_ARC, X, Y, c);
  curve(&p.coons.D0, CURVE_ARC, N, X, c);
  curve(&p.coons.D1, CURVE_ARC, N, Y, c);
  return p;
}

static void tool_init(Tool *t, const char *name, int np, Patch *p)
{
  memset(t, 0, sizeof(*t));
  snprintf(t->name, sizeof(t->name), "%s", name);
  t->npatch = np;
  t->patch  = p;
  for (int i = 0; i < 3; i++) {
    t->bbox[2 * i]     = -1e300;
    t->bbox[2 * i + 1] = 1e300;
  }
}

/* ------------------------------------------------------------------ brute force */

static double d2at(const Patch *p, double u, double v, const double y[3])
{
  double x[3], xu[3], xv[3];
  PatchEval(p, u, v, x, xu, xv, NULL, NULL, NULL);
  return (x[0] - y[0]) * (x[0] - y[0]) + (x[1] - y[1]) * (x[1] - y[1]) + (x[2] - y[2]) * (x[2] - y[2]);
}

/* closest distance by a 101 x 101 grid on [0,1]^2, then zooming in (window +-3h, 13 x 13 points,
   h halved, until h < 1e-10) around each of the 3 best samples with distinct points (a patch with
   a collapsed side has many samples at one point), and each edge as a 1D problem the same way */
static double zoom(const Patch *p, const double y[3], double h, double *u, double *v, double best)
{
  while (h > 1e-10) {
    const double u0 = *u, v0 = *v;
    for (int i = -6; i <= 6; i++)
      for (int j = -6; j <= 6; j++) {
        const double uu = fmin(1.0, fmax(0.0, u0 + 0.5 * i * h)), vv = fmin(1.0, fmax(0.0, v0 + 0.5 * j * h));
        const double d  = d2at(p, uu, vv, y);
        if (d < best) {
          best = d;
          *u   = uu;
          *v   = vv;
        }
      }
    h *= 0.5;
  }
  return best;
}

static double brute(const Patch *p, const double y[3], double *bu, double *bv)
{
  enum { N = 101, K = 3 };
  static double D[N][N], X[N][N][3];
  const double  h = 1.0 / (N - 1);
  double        best = HUGE_VAL, ub = 0, vb = 0;
  int           ka[K], kb[K], nk = 0;
  for (int i = 0; i < N; i++)
    for (int j = 0; j < N; j++) {
      double xu[3], xv[3];
      PatchEval(p, i * h, j * h, X[i][j], xu, xv, NULL, NULL, NULL);
      D[i][j] = dist(X[i][j], y);
    }
  while (nk < K) { /* the next best sample with a point distinct from those taken */
    int    bi = -1, bj = -1;
    double bd = HUGE_VAL;
    for (int i = 0; i < N; i++)
      for (int j = 0; j < N; j++) {
        int dup = 0;
        if (D[i][j] >= bd) continue;
        for (int k = 0; k < nk; k++) dup = dup || (ka[k] == i && kb[k] == j) || dist(X[i][j], X[ka[k]][kb[k]]) < 1e-9;
        if (!dup) {
          bd = D[i][j];
          bi = i;
          bj = j;
        }
      }
    if (bi < 0) break;
    ka[nk] = bi;
    kb[nk] = bj;
    nk++;
  }
  for (int k = 0; k < nk; k++) {
    double       u = ka[k] * h, v = kb[k] * h;
    const double d = zoom(p, y, h, &u, &v, D[ka[k]][kb[k]] * D[ka[k]][kb[k]]);
    if (d < best) {
      best = d;
      ub   = u;
      vb   = v;
    }
  }
  for (int e = 0; e < 4; e++) { /* each edge as a 1D problem: 1001 samples, then zooming */
    const double fix = e % 2;
    const int    alongv = e / 2; /* e = 0, 1: xi free on eta = 0, 1; e = 2, 3: eta free on xi = 0, 1 */
    double       s = 0, hs = 1e-3, bd = HUGE_VAL;
    for (int k = 0; k <= 1000; k++) {
      const double d = alongv ? d2at(p, fix, k * 1e-3, y) : d2at(p, k * 1e-3, fix, y);
      if (d < bd) {
        bd = d;
        s  = k * 1e-3;
      }
    }
    while (hs > 1e-13) {
      const double s0 = s;
      for (int k = -6; k <= 6; k++) {
        const double ss = fmin(1.0, fmax(0.0, s0 + 0.5 * k * hs));
        const double d  = alongv ? d2at(p, fix, ss, y) : d2at(p, ss, fix, y);
        if (d < bd) {
          bd = d;
          s  = ss;
        }
      }
      hs *= 0.5;
    }
    if (bd < best) {
      best = bd;
      ub   = alongv ? fix : s;
      vb   = alongv ? s : fix;
    }
  }
  if (bu) *bu = ub;
  if (bv) *bv = vb;
  return sqrt(best);
}

static double brute_tool(const Tool *t, const double y[3], int *kb)
{
  double best = HUGE_VAL;
  for (int k = 0; k < t->npatch; k++) {
    const double d = brute(&t->patch[k], y, NULL, NULL);
    if (d < best) {
      best = d;
      if (kb) *kb = k;
    }
  }
  return best;
}

/* ------------------------------------------------------------------ 1. derivatives */

static void test_derivatives(const char *name, const Patch *p)
{
  reseed(name);
  const double h = 1e-5;
  double       e1 = 0, e2 = 0;
  for (int k = 0; k < 20; k++) {
    const double u = uni(-0.2, 1.2), v = uni(-0.2, 1.2);
    double       x[3], xu[3], xv[3], xuu[3], xuv[3], xvv[3];
    double       xp[3], xm[3], up[3], um[3], vp[3], vm[3];
    double       sc1, sc2;
    PatchEval(p, u, v, x, xu, xv, xuu, xuv, xvv);
    sc1 = fmax(nrm(xu), nrm(xv));
    sc2 = sc1;
    /* d/dxi */
    PatchEval(p, u + h, v, xp, up, vp, NULL, NULL, NULL);
    PatchEval(p, u - h, v, xm, um, vm, NULL, NULL, NULL);
    for (int i = 0; i < 3; i++) {
      e1 = fmax(e1, fabs((xp[i] - xm[i]) / (2 * h) - xu[i]) / sc1);
      e2 = fmax(e2, fabs((up[i] - um[i]) / (2 * h) - xuu[i]) / fmax(sc2, nrm(xuu)));
      e2 = fmax(e2, fabs((vp[i] - vm[i]) / (2 * h) - xuv[i]) / fmax(sc2, nrm(xuv)));
    }
    /* d/deta */
    PatchEval(p, u, v + h, xp, up, vp, NULL, NULL, NULL);
    PatchEval(p, u, v - h, xm, um, vm, NULL, NULL, NULL);
    for (int i = 0; i < 3; i++) {
      e1 = fmax(e1, fabs((xp[i] - xm[i]) / (2 * h) - xv[i]) / sc1);
      e2 = fmax(e2, fabs((up[i] - um[i]) / (2 * h) - xuv[i]) / fmax(sc2, nrm(xuv)));
      e2 = fmax(e2, fabs((vp[i] - vm[i]) / (2 * h) - xvv[i]) / fmax(sc2, nrm(xvv)));
    }
  }
  TU_CHECK(e1 < 1e-6, "%s: first derivatives vs central differences (20 points in [-0.2,1.2]^2): max rel. error %.2e", name, e1);
  TU_CHECK(e2 < 1e-6, "%s: second derivatives vs central differences: max rel. error %.2e", name, e2);
}

/* ------------------------------------------------------------------ 2. normals */

static void test_normals(const char *name, const Patch *p)
{
  reseed(name);
  double eu = 0, ea = 0, ec = 0;
  for (int k = 0; k < 50; k++) {
    const double u = urand(), v = urand();
    double       n[3], x[3], xu[3], xv[3], N[3], an[3] = {0, 0, 0}, J;
    J = PatchNormal(p, u, v, n);
    PatchEval(p, u, v, x, xu, xv, NULL, NULL, NULL);
    cross(xu, xv, N);
    eu = fmax(eu, fabs(nrm(n) - 1.0));
    ec = fmax(ec, fabs(J - nrm(N)) / nrm(N));
    for (int i = 0; i < 3; i++) ec = fmax(ec, fabs(n[i] - p->sense * N[i] / nrm(N)));
    if (istype(p, "sphere"))
      for (int i = 0; i < 3; i++) an[i] = (x[i] - p->rev.c[i]) / p->rev.R;
    else if (istype(p, "cylinder")) {
      double d[3];
      for (int i = 0; i < 3; i++) d[i] = x[i] - p->rev.c[i];
      const double h = dot(d, p->rev.a);
      for (int i = 0; i < 3; i++) an[i] = (d[i] - h * p->rev.a[i]) / p->rev.R;
    } else if (istype(p, "torus")) {
      double d[3], w[3];
      for (int i = 0; i < 3; i++) d[i] = x[i] - p->rev.c[i];
      const double h = dot(d, p->rev.a);
      for (int i = 0; i < 3; i++) w[i] = d[i] - h * p->rev.a[i];
      unit(w);
      for (int i = 0; i < 3; i++) an[i] = (d[i] - p->rev.R * w[i]) / p->rev.r;
    }
    if (istype(p, "sphere") || istype(p, "cylinder") || istype(p, "torus"))
      for (int i = 0; i < 3; i++) ea = fmax(ea, fabs(n[i] - p->sense * an[i]));
  }
  TU_CHECK(eu < 1e-14, "%s: normal has unit length: max | |n| - 1 | = %.2e", name, eu);
  TU_CHECK(ec < 1e-12, "%s: normal = sense (x_xi x x_eta)/|x_xi x x_eta| and the returned Jacobian |x_xi x x_eta|: max error %.2e", name, ec);
  if (istype(p, "sphere") || istype(p, "cylinder") || istype(p, "torus")) TU_CHECK(ea < 1e-14, "%s: normal = analytic sense (x - centre)/radius: max error %.2e", name, ea);
}

/* ------------------------------------------------------------------ 3. Coons */

static void test_coons_shapes(void)
{
  reseed("test_coons_shapes");
  /* planar convex quad with straight sides: the Coons patch is the bilinear patch */
  double o[3], e1[3], e2[3], P[4][3];
  set3(o, 0.2, -0.4, 1.0);
  set3(e1, 1, 0.5, 0.2);
  unit(e1);
  set3(e2, -0.3, 1, 0.4);
  {
    const double pr = dot(e1, e2);
    for (int i = 0; i < 3; i++) e2[i] -= pr * e1[i];
  }
  unit(e2);
  const double ab[4][2] = {
    {0.0, 0.0},
    {2.0, 0.3},
    {-0.2, 1.5},
    {1.7, 1.9}
  }; /* P00, P10, P01, P11 */
  for (int k = 0; k < 4; k++)
    for (int i = 0; i < 3; i++) P[k][i] = o[i] + ab[k][0] * e1[i] + ab[k][1] * e2[i];
  Patch q;
  memset(&q, 0, sizeof(q));
  settype(&q, "coons");
  q.sense = 1;
  curve(&q.coons.C0, CURVE_LINE, P[0], P[1], NULL);
  curve(&q.coons.C1, CURVE_LINE, P[2], P[3], NULL);
  curve(&q.coons.D0, CURVE_LINE, P[0], P[2], NULL);
  curve(&q.coons.D1, CURVE_LINE, P[1], P[3], NULL);
  double ex = 0, ed = 0;
  for (int k = 0; k < 100; k++) {
    const double u = uni(-0.1, 1.1), v = uni(-0.1, 1.1);
    double       x[3], xu[3], xv[3], xuu[3], xuv[3], xvv[3];
    PatchEval(&q, u, v, x, xu, xv, xuu, xuv, xvv);
    for (int i = 0; i < 3; i++) {
      const double b   = (1 - u) * (1 - v) * P[0][i] + u * (1 - v) * P[1][i] + (1 - u) * v * P[2][i] + u * v * P[3][i];
      const double bu  = (1 - v) * (P[1][i] - P[0][i]) + v * (P[3][i] - P[2][i]);
      const double bv  = (1 - u) * (P[2][i] - P[0][i]) + u * (P[3][i] - P[1][i]);
      const double buv = P[0][i] - P[1][i] - P[2][i] + P[3][i];
      ex               = fmax(ex, fabs(x[i] - b));
      ed               = fmax(ed, fmax(fabs(xu[i] - bu), fabs(xv[i] - bv)));
      ed               = fmax(ed, fmax(fmax(fabs(xuu[i]), fabs(xvv[i])), fabs(xuv[i] - buv)));
    }
  }
  TU_CHECK(ex < 1e-14 && ed < 1e-14, "coons from 4 straight sides of a planar quad = bilinear patch: max point error %.2e, max derivative error %.2e", ex, ed);

  /* octant of the unit sphere from 3 Coons patches of great-circle arcs */
  Patch        oc[3];
  const double c[3] = {0.3, -0.2, 0.5};
  octant_coons(c, 1.0, oc);
  double eb = 0, ei = 0, en = 0;
  for (int k = 0; k < 3; k++) {
    for (int j = 0; j <= 200; j++) {
      const double s     = j / 200.0;
      const double uv[4][2] = {
        {s,   0  },
        {s,   1  },
        {0,   s  },
        {1,   s  }
      };
      for (int e = 0; e < 4; e++) {
        double x[3], xu[3], xv[3];
        PatchEval(&oc[k], uv[e][0], uv[e][1], x, xu, xv, NULL, NULL, NULL);
        eb = fmax(eb, fabs(dist(x, c) - 1.0));
      }
    }
    for (int a = 0; a <= 60; a++)
      for (int b = 0; b <= 60; b++) {
        double x[3], n[3], xu[3], xv[3], r[3];
        PatchEval(&oc[k], a / 60.0, b / 60.0, x, xu, xv, NULL, NULL, NULL);
        ei = fmax(ei, fabs(dist(x, c) - 1.0));
        PatchNormal(&oc[k], a / 60.0, b / 60.0, n);
        for (int i = 0; i < 3; i++) r[i] = x[i] - c[i];
        unit(r);
        en = fmax(en, acos(fmin(1.0, dot(n, r))) * 180 / PI);
      }
  }
  TU_CHECK(eb < 1e-14, "coons octant of a unit sphere (3 patches of great-circle arcs): boundary on the sphere, max | |x - c| - R | = %.2e", eb);
  TU_CHECK(ei < 0.02, "coons octant: interior close to the sphere, max | |x - c| - R | / R = %.4e", ei);
  TU_CHECK(en < 5.0, "coons octant: normals (sense 1) point outwards, max angle to the radial direction %.3f degrees", en);
}

/* ------------------------------------------------------------------ 4. projection vs brute force */

typedef struct {
  double maxexcess;  /* max (projected distance - brute force) */
  double maxdeficit; /* max (brute force - projected distance) */
  double maxorth;    /* max tangential residual / L for interior projections */
  double maxcons;    /* consistency: x = PatchEval + shift, gap = (y - x).n, |gap| = |y - x| */
  int    n, fails, interior;
} ProjStats;

static void check_point(const Tool *t, const double shift[3], const double y[3], double L, ProjStats *st)
{
  Projection pr;
  double     yr[3];
  st->n++;
  if (ToolProject(t, shift, y, PETSC_INFINITY, &pr)) {
    st->fails++;
    return;
  }
  for (int i = 0; i < 3; i++) yr[i] = y[i] - shift[i];
  const double bf = brute_tool(t, yr, NULL), dp = dist(y, pr.x);
  st->maxexcess  = fmax(st->maxexcess, dp - bf);
  if (getenv("TOOL_DEBUG") && dp - bf > 1e-9) { /* the points a failing check is about */
    double bu, bv;
    brute(&t->patch[0], yr, &bu, &bv);
    printf("# DEBUG y %.17g %.17g %.17g: proj patch %d (%.17g, %.17g) int %d d %.17g; brute (%.17g %.17g) %.17g\n", yr[0], yr[1], yr[2], pr.patch, pr.xi, pr.eta, pr.interior, dp, bu, bv, bf);
  }
  st->maxdeficit = fmax(st->maxdeficit, bf - dp);
  {
    double x[3], xu[3], xv[3], r[3], n[3];
    PatchEval(&t->patch[pr.patch], pr.xi, pr.eta, x, xu, xv, NULL, NULL, NULL);
    PatchNormal(&t->patch[pr.patch], pr.xi, pr.eta, n);
    for (int i = 0; i < 3; i++) {
      st->maxcons = fmax(st->maxcons, fabs(x[i] + shift[i] - pr.x[i]) / L);
      st->maxcons = fmax(st->maxcons, fabs(n[i] - pr.n[i]));
      r[i]        = y[i] - pr.x[i];
    }
    st->maxcons = fmax(st->maxcons, fabs(pr.gap - dot(r, pr.n)) / L);
    if (pr.interior) {
      st->maxcons = fmax(st->maxcons, fabs(fabs(pr.gap) - dp) / L);
      st->interior++;
      if (nrm(xu) > 0) st->maxorth = fmax(st->maxorth, fabs(dot(r, xu)) / nrm(xu) / L);
      if (nrm(xv) > 0) st->maxorth = fmax(st->maxorth, fabs(dot(r, xv)) / nrm(xv) / L);
    }
  }
}

static void report(const char *name, const ProjStats *st, double L)
{
  TU_CHECK(st->fails == 0 && st->maxexcess <= 1e-9 * fmax(1.0, L), "%s: %d points (%d interior): projected distance - brute force <= %.2e (brute force - projected <= %.2e)", name, st->n, st->interior, st->maxexcess, st->maxdeficit);
  TU_CHECK(st->maxorth <= 1e-10, "%s: interior projections orthogonal: max |(y - x).x_i|/|x_i| / L = %.2e", name, st->maxorth);
  /* |gap| = |y - x| holds only to the projection's tolerance, like the orthogonality above: near a
     Coons patch's collapsed side the error reached 1.8e-12 over 30 sets of random points (and the
     orthogonality 7.9e-12), so the bound here is the orthogonality's */
  TU_CHECK(st->maxcons <= 1e-10, "%s: x = x(xi,eta) + shift, n = PatchNormal, gap = (y - x).n = +-|y - x|: max error %.2e", name, st->maxcons);
}

/* points about one patch: near the surface on both sides (parameters beyond the range too), near
   edges and corners, on the surface, far away */
static void test_projection(const char *name, const Patch *p, double thick, double L)
{
  reseed(name);
  Tool         t;
  Patch        q      = *p;
  const double sh[3]  = {0.3, -0.1, 0.2};
  ProjStats    st     = {0, 0, 0, 0, 0, 0, 0};
  double       cen[3] = {0, 0, 0}, xc[3], xu[3], xv[3];
  tool_init(&t, name, 1, &q);
  PatchEval(p, 0.5, 0.5, xc, xu, xv, NULL, NULL, NULL);
  for (int i = 0; i < 3; i++) cen[i] = xc[i];
  for (int k = 0; k < 240; k++) {
    const int cat = k % 6;
    double    u, v, tt, x[3], n[3], y[3];
    switch (cat) {
    case 0:
    case 1:
      u  = uni(-0.3, 1.3);
      v  = uni(-0.3, 1.3);
      tt = uni(-thick, thick);
      break;
    case 2: /* near an edge */
      if (urand() < 0.5) {
        u = (urand() < 0.5 ? 0 : 1) + uni(-0.03, 0.03);
        v = uni(-0.1, 1.1);
      } else {
        v = (urand() < 0.5 ? 0 : 1) + uni(-0.03, 0.03);
        u = uni(-0.1, 1.1);
      }
      tt = uni(-thick, thick);
      break;
    case 3: /* near a corner */
      u  = (urand() < 0.5 ? 0 : 1) + uni(-0.05, 0.05);
      v  = (urand() < 0.5 ? 0 : 1) + uni(-0.05, 0.05);
      tt = uni(-thick, thick);
      break;
    case 4: /* on the surface, edges included */
      u  = k % 24 == 4 ? 0.0 : urand();
      v  = k % 36 == 10 ? 1.0 : urand();
      tt = 0.0;
      break;
    default: /* far away */
      u = v = tt = 0;
      break;
    }
    if (cat == 5)
      for (int i = 0; i < 3; i++) y[i] = cen[i] + uni(-5, 5) * L;
    else {
      PatchEval(p, u, v, x, xu, xv, NULL, NULL, NULL);
      PatchNormal(p, u, v, n);
      for (int i = 0; i < 3; i++) y[i] = x[i] + tt * n[i];
    }
    for (int i = 0; i < 3; i++) y[i] += sh[i];
    check_point(&t, sh, y, L, &st);
  }
  report(name, &st, L);
}

/* ------------------------------------------------------------------ 5. the sphere's pole */

static void test_pole(void)
{
  reseed("test_pole");
  Patch p;
  Tool  t;
  memset(&p, 0, sizeof(p));
  settype(&p, "sphere");
  p.sense = 1;
  set3(p.rev.c, 0, 0, 0);
  p.rev.R = 1.0;
  frame(&p, 0, 0, 1, 1, 0, 0);
  const double ranges[3][4] = {
    {0,         deg(90),  0,        deg(90) }, /* quarter hemisphere, pole at a corner edge (th = 0) */
    {0,         deg(40),  0,        2 * PI  }, /* full-azimuth cap                                   */
    {deg(120), PI,        deg(-45), deg(200)}  /* around the south pole (th = 180)                    */
  };
  const char *names[3] = {"quarter hemisphere", "full cap", "south-pole patch"};
  for (int r = 0; r < 3; r++) {
    p.rev.t0 = ranges[r][0];
    p.rev.t1 = ranges[r][1];
    p.rev.s0 = ranges[r][2];
    p.rev.s1 = ranges[r][3];
    tool_init(&t, "pole", 1, &p);
    const double sh[3] = {0, 0, 0}, sgn = r == 2 ? -1.0 : 1.0;
    double       eax = 0, enx = 0, egp = 0, eb = 0, eo = 0, eg = 0;
    int          nint = 0, fails = 0, npt = 0;
    /* on the axis: x = pole, n = +-axis, gap = |z| - 1 */
    const double zs[] = {3.0, 1.0 + 1e-12, 1.0, 1.0 - 1e-12, 0.999, 0.5, 1e-3};
    for (int k = 0; k < (int)(sizeof(zs) / sizeof(zs[0])); k++) {
      double     y[3] = {0, 0, sgn * zs[k]}, pole[3] = {0, 0, sgn};
      Projection pr;
      npt++;
      if (ToolProject(&t, sh, y, PETSC_INFINITY, &pr)) {
        fails++;
        continue;
      }
      eax = fmax(eax, dist(pr.x, pole));
      enx = fmax(enx, fabs(pr.n[2] - sgn) + fabs(pr.n[0]) + fabs(pr.n[1]));
      egp = fmax(egp, fabs(pr.gap - (zs[k] - 1.0)));
      nint += pr.interior;
    }
    /* off the axis by 1e-12 .. 1e-2, in and out of the azimuth range */
    const double offs[] = {1e-12, 1e-9, 1e-6, 1e-3, 1e-2}, phs[] = {30, 100, 180, 225, 300}, zz[] = {1.5, 1.0, 0.9};
    for (int a = 0; a < 5; a++)
      for (int b = 0; b < 5; b++)
        for (int c = 0; c < 3; c++) {
          double     y[3] = {offs[a] * cos(deg(phs[b])), offs[a] * sin(deg(phs[b])), sgn * zz[c]}, r3[3], x[3], xu[3], xv[3];
          Projection pr;
          npt++;
          if (ToolProject(&t, sh, y, PETSC_INFINITY, &pr)) {
            fails++;
            continue;
          }
          const double bf = brute(&p, y, NULL, NULL);
          eb              = fmax(eb, dist(y, pr.x) - bf);
          PatchEval(&p, pr.xi, pr.eta, x, xu, xv, NULL, NULL, NULL);
          for (int i = 0; i < 3; i++) r3[i] = y[i] - pr.x[i];
          if (pr.interior) {
            if (nrm(xu) > 0) eo = fmax(eo, fabs(dot(r3, xu)) / nrm(xu));
            if (nrm(xv) > 1e-300) eo = fmax(eo, fabs(dot(r3, xv)) / nrm(xv));
          }
          if (pr.interior) eg = fmax(eg, fabs(fabs(pr.gap) - dist(y, pr.x)));
        }
    TU_CHECK(fails == 0 && eax < 1e-15 && enx < 1e-12 && egp < 1e-15 && nint == 7, "sphere pole, %s: 7 points on the axis project on the pole (max distance %.1e), n = axis (error %.1e), gap = |z| - R (error %.1e), %d interior", names[r], eax, enx, egp, nint);
    TU_CHECK(fails == 0 && eb <= 1e-9 && eo <= 1e-10 && eg <= 1e-10, "sphere pole, %s: %d points near the axis (offsets 1e-12..1e-2, azimuths in and out of range): projected - brute force <= %.2e, orthogonality residual %.1e, | |gap| - |y - x| | %.1e (interior)", names[r], npt - 7, eb, eo, eg);
  }
}

/* ------------------------------------------------------------------ 6. multi-patch tools */

/* A point beside an open edge of a tool (its closest point held on a patch boundary that no patch
   continues): no contact when it lies beside the edge by more than t->edge_tol and by more than
   it lies inside; with edge_tol 0 the gap along the edge's normal, as before */
static void test_open_edge(void)
{
  reseed("test_open_edge");
  Patch P[2];
  Tool  t;
  const double sh[3] = {0, 0, 0};
  for (int k = 0; k < 2; k++) {
    memset(&P[k], 0, sizeof(P[k]));
    settype(&P[k], "plane");
    P[k].sense = 1;
    set3(P[k].plane.o, k, 0, 0);
    set3(P[k].plane.e1, 1, 0, 0);
    set3(P[k].plane.e2, 0, 1, 0);
    P[k].plane.u0 = 0;
    P[k].plane.u1 = 1;
    P[k].plane.v0 = 0;
    P[k].plane.v1 = 1;
  }
  tool_init(&t, "edge", 2, P);
  Projection pr;
  double     n[3], y[3];
  /* the normal of the planes (the side a node comes from) */
  set3(y, 0.5, 0.5, 0.1);
  (void)ToolProject(&t, sh, y, PETSC_INFINITY, &pr);
  for (int i = 0; i < 3; i++) n[i] = pr.n[i];
  /* beside the edge x = 0 by 0.5 at 1e-7 inside the plane's level */
  for (int i = 0; i < 3; i++) y[i] = (i == 0 ? -0.5 : i == 1 ? 0.5 : 0.0) - 1e-7 * n[i];
  t.edge_tol = 0;
  int r = ToolProject(&t, sh, y, PETSC_INFINITY, &pr);
  TU_CHECK(r == 0 && !pr.interior && fabs(pr.gap + 1e-7) < 1e-12, "open edge, edge_tol 0: a point 0.5 beside the edge keeps the gap along the edge's normal (%d, interior %d, gap %.3e)", r, pr.interior, pr.gap);
  t.edge_tol = 1e-3;
  r          = ToolProject(&t, sh, y, PETSC_INFINITY, &pr);
  TU_CHECK(r == 1, "open edge, edge_tol 1e-3: a point 0.5 beside the edge is no contact (returns %d)", r);
  /* beside by 5e-4 < edge_tol: kept */
  for (int i = 0; i < 3; i++) y[i] = (i == 0 ? -5e-4 : i == 1 ? 0.5 : 0.0) - 1e-4 * n[i];
  r = ToolProject(&t, sh, y, PETSC_INFINITY, &pr);
  TU_CHECK(r == 0 && fabs(pr.gap + 1e-4) < 1e-12, "open edge: a point 5e-4 beside the edge (edge_tol 1e-3) is kept (%d, gap %.3e)", r, pr.gap);
  /* beside by 0.01, inside by 0.02: kept (a concave seam's corner) */
  for (int i = 0; i < 3; i++) y[i] = (i == 0 ? -0.01 : i == 1 ? 0.5 : 0.0) - 0.02 * n[i];
  r = ToolProject(&t, sh, y, PETSC_INFINITY, &pr);
  TU_CHECK(r == 0 && fabs(pr.gap + 0.02) < 1e-12, "open edge: a point 0.01 beside the edge but 0.02 inside is kept (%d, gap %.3e)", r, pr.gap);
  /* beside by 0.02, inside by 0.01: no contact */
  for (int i = 0; i < 3; i++) y[i] = (i == 0 ? -0.02 : i == 1 ? 0.5 : 0.0) - 0.01 * n[i];
  r = ToolProject(&t, sh, y, PETSC_INFINITY, &pr);
  TU_CHECK(r == 1, "open edge: a point 0.02 beside the edge and 0.01 inside is no contact (returns %d)", r);
  /* over the seam x = 1 between the two planes and over the second one: interior, kept */
  for (int i = 0; i < 3; i++) y[i] = (i == 0 ? 1.0 : i == 1 ? 0.5 : 0.0) - 1e-7 * n[i];
  r = ToolProject(&t, sh, y, PETSC_INFINITY, &pr);
  TU_CHECK(r == 0 && fabs(pr.gap + 1e-7) < 1e-12, "open edge: a point on the seam between two patches is kept (%d, gap %.3e)", r, pr.gap);
  for (int i = 0; i < 3; i++) y[i] = (i == 0 ? 1.3 : i == 1 ? 0.5 : 0.0) - 1e-7 * n[i];
  r = ToolProject(&t, sh, y, PETSC_INFINITY, &pr);
  TU_CHECK(r == 0 && pr.interior && pr.patch == 1, "open edge: a point beyond the first patch's edge over the second is on the second (%d, patch %d)", r, pr.patch);
  /* beside the far edge x = 2 by 0.5: no contact; beside the side edge y = 0 by 0.5: no contact */
  for (int i = 0; i < 3; i++) y[i] = (i == 0 ? 2.5 : i == 1 ? 0.5 : 0.0) - 1e-7 * n[i];
  r = ToolProject(&t, sh, y, PETSC_INFINITY, &pr);
  TU_CHECK(r == 1, "open edge: a point beside the far edge is no contact (returns %d)", r);
  for (int i = 0; i < 3; i++) y[i] = (i == 0 ? 1.5 : i == 1 ? -0.5 : 0.0) - 1e-7 * n[i];
  r = ToolProject(&t, sh, y, PETSC_INFINITY, &pr);
  TU_CHECK(r == 1, "open edge: a point beside the seam's end (a corner of both patches) is no contact (returns %d)", r);
}

static void test_multipatch(void)
{
  reseed("test_multipatch");
  const double c[3] = {0, 0, 0}, sh[3] = {0.0, 0.0, 0.7};
  Patch        P[4];
  Tool         t;
  Patch        plane;
  memset(&plane, 0, sizeof(plane));
  settype(&plane, "plane");
  plane.sense = 1;
  set3(plane.plane.o, 0, 0, 0);
  set3(plane.plane.e1, 1, 0, 0);
  set3(plane.plane.e2, 0, 1, 0);
  plane.plane.u0 = 0;
  plane.plane.u1 = 1.5;
  plane.plane.v0 = 0;
  plane.plane.v1 = 1.5;

  /* (a) the quarter hemisphere from two sphere patches split at ph = 45 degrees + the equator plane */
  for (int k = 0; k < 2; k++) {
    memset(&P[k], 0, sizeof(P[k]));
    settype(&P[k], "sphere");
    P[k].sense = 1;
    P[k].rev.R     = 1.0;
    frame(&P[k], 0, 0, 1, 1, 0, 0);
    P[k].rev.t0 = 0;
    P[k].rev.t1 = deg(90);
    P[k].rev.s0 = deg(45 * k);
    P[k].rev.s1 = deg(45 * (k + 1));
  }
  P[2] = plane;
  tool_init(&t, "split", 3, P);
  {
    ProjStats st = {0, 0, 0, 0, 0, 0, 0};
    int       moved = 0, nmove = 0, seam = 0, nseam = 0;
    for (int k = 0; k < 240; k++) {
      double th = deg(uni(0, 80)), ph = deg(uni(0, 90)), tt = uni(-0.15, 0.2), y[3];
      if (k % 4 == 0) ph = deg(45);                  /* exactly on the seam */
      if (k % 4 == 1) ph = deg(45 + uni(0.01, 15));  /* beyond patch 0's edge */
      if (k % 8 == 0) tt = 0.0;                      /* on the surface */
      for (int i = 0; i < 3; i++) y[i] = sh[i] + (1 + tt) * (i == 2 ? cos(th) : sin(th) * (i == 0 ? cos(ph) : sin(ph)));
      check_point(&t, sh, y, 1.0, &st);
      Projection pr;
      ToolProject(&t, sh, y, PETSC_INFINITY, &pr);
      if (k % 4 == 1) {
        nmove++;
        moved += pr.patch == 1 && pr.interior;
      }
      if (k % 4 == 0) {
        nseam++;
        seam += (pr.patch == 0 || pr.patch == 1) && pr.interior && fabs(pr.gap - tt) < 1e-13;
      }
    }
    report("two sphere patches + plane", &st, 1.0);
    TU_CHECK(moved == nmove, "two sphere patches: %d of %d points beyond patch 0's edge (ph = 45..60 deg) project inside patch 1", moved, nmove);
    TU_CHECK(seam == nseam, "two sphere patches: %d of %d points on the seam ph = 45 deg project as interior with gap = radial offset", seam, nseam);
  }

  /* selection: beside an open edge of the tool (the symmetry plane ph = 0 of the octant) a point
     keeps the near solution held on the edge rather than a far interior one (a plane under the
     whole hemisphere) */
  {
    Patch Q[2] = {P[0], plane};
    Tool  t2;
    Q[1].plane.u0 = Q[1].plane.v0 = -1.5;
    tool_init(&t2, "open", 2, Q);
    const double th = deg(30), ph = deg(-5), y[3] = {1.2 * sin(th) * cos(ph), 1.2 * sin(th) * sin(ph), 1.2 * cos(th)};
    Projection   pr;
    const int    r = ToolProject(&t2, c, y, PETSC_INFINITY, &pr);
    TU_CHECK(r == 0 && pr.patch == 0 && !pr.interior && fabs(dist(y, pr.x) - brute_tool(&t2, y, NULL)) < 1e-12, "selection: a point 0.2 outside the sphere, 5 deg beyond its open edge: sphere patch %d held on the edge (interior %d, distance %.6f), not the plane 1.04 below", pr.patch, pr.interior, dist(y, pr.x));
  }

  /* (b) the quarter hemisphere from 3 Coons patches + the equator plane */
  octant_coons(c, 1.0, P);
  P[3] = plane;
  tool_init(&t, "coons3", 4, P);
  {
    ProjStats st = {0, 0, 0, 0, 0, 0, 0};
    int       nseam = 0, seam = 0;
    for (int k = 0; k < 240; k++) {
      double th = deg(uni(0, 80)), ph = deg(uni(0, 90)), tt = uni(-0.1, 0.2), y[3];
      if (k % 8 == 0) tt = 0.0;
      for (int i = 0; i < 3; i++) y[i] = sh[i] + (1 + tt) * (i == 2 ? cos(th) : sin(th) * (i == 0 ? cos(ph) : sin(ph)));
      if (k % 4 == 1) { /* on a seam of the Coons patches: patch k%3's right or top edge (shared) */
        double x[3], xu[3], xv[3], n[3];
        const int pk = (k / 4) % 3;
        const double s = urand();
        if ((k / 12) % 2) PatchEval(&P[pk], 1.0, s, x, xu, xv, NULL, NULL, NULL);
        else PatchEval(&P[pk], s, 1.0, x, xu, xv, NULL, NULL, NULL);
        PatchNormal(&P[pk], (k / 12) % 2 ? 1.0 : s, (k / 12) % 2 ? s : 1.0, n);
        for (int i = 0; i < 3; i++) y[i] = sh[i] + x[i] + tt * n[i];
        Projection pr;
        nseam++;
        if (!ToolProject(&t, sh, y, PETSC_INFINITY, &pr) && tt == 0.0) seam += dist(pr.x, y) < 1e-12;
        else if (tt != 0.0) seam++;
      }
      check_point(&t, sh, y, 1.0, &st);
    }
    report("3 coons patches + plane", &st, 1.0);
    TU_CHECK(seam == nseam, "3 coons patches: %d of %d points on or off the seams handled (points on a seam project on themselves)", seam, nseam);
  }
}

/* ------------------------------------------------------------------ 7. normal derivative */

static void test_normal_derivative(const char *name, const Patch *p, double thick, int edges)
{
  reseed(name);
  Tool         t;
  Patch        q     = *p;
  const double sh[3] = {-0.1, 0.25, 0.4}, h = 1e-6;
  double       emax  = 0.0;
  int          bad = 0, nint = 0, nedge = 0;
  tool_init(&t, name, 1, &q);
  for (int k = 0; k < 40; k++) {
    double     u = uni(0.15, 0.85), v = uni(0.15, 0.85), x[3], xu[3], xv[3], n[3], y[3], dn[9], fd[9];
    Projection pr, pp, pm;
    if (edges && k % 2) { /* beyond an edge: the projection is held on it */
      if (k % 4 == 1) u = uni(-0.3, -0.1);
      else v = uni(1.1, 1.3);
    }
    PatchEval(p, u, v, x, xu, xv, NULL, NULL, NULL);
    PatchNormal(p, u, v, n);
    const double tt = (k % 2 ? 1 : -1) * uni(0.2, 1.0) * thick;
    for (int i = 0; i < 3; i++) y[i] = x[i] + tt * n[i] + sh[i];
    if (ToolProject(&t, sh, y, PETSC_INFINITY, &pr)) {
      bad++;
      continue;
    }
    nint += pr.interior;
    nedge += !pr.interior;
    if (PatchNormalDerivative(&q, sh, y, &pr, dn)) {
      bad++;
      continue;
    }
    for (int j = 0; j < 3; j++) {
      double yp[3] = {y[0], y[1], y[2]}, ym[3] = {y[0], y[1], y[2]};
      yp[j] += h;
      ym[j] -= h;
      ToolProject(&t, sh, yp, PETSC_INFINITY, &pp);
      ToolProject(&t, sh, ym, PETSC_INFINITY, &pm);
      for (int i = 0; i < 3; i++) fd[3 * i + j] = (pp.n[i] - pm.n[i]) / (2 * h);
    }
    double num = 0, den = 0;
    for (int i = 0; i < 9; i++) {
      num += (fd[i] - dn[i]) * (fd[i] - dn[i]);
      den += dn[i] * dn[i];
    }
    /* relative to |dn| (of order 1/radius), absolute where dn vanishes (a cone held on its
       straight edge) */
    emax = fmax(emax, istype(p, "plane") ? sqrt(num) : sqrt(num / fmax(den, 1e-6)));
  }
  if (istype(p, "plane")) TU_CHECK(bad == 0 && emax < 1e-9, "%s: dn/dy = 0 and finite differences of the projected normal agree: max |FD| = %.2e", name, emax);
  else TU_CHECK(bad == 0 && emax < 1e-6, "%s: dn/dy vs central differences of the projected normal (%d interior, %d held on an edge): max rel. error %.2e", name, nint, nedge, emax);
}

/* PatchPrepare: the prepared patch evaluates, and projects, exactly as the unprepared one */
static void test_prepared(const Patch *a, const Patch *b, const Patch *c)
{
  reseed("test_prepared");
  const Patch *P[3] = {a, b, c};
  int          diff = 0, n = 0;
  for (int k = 0; k < 3; k++) {
    Patch      q = *P[k], qp = *P[k];
    Tool       t, tp;
    const double sh[3] = {0.1, -0.2, 0.05};
    PatchPrepare(&qp);
    if (k == 0) TU_CHECK(qp.data != NULL, "PatchPrepare: a Coons patch holds its prepared frames and samples");
    tool_init(&t, "raw", 1, &q);
    tool_init(&tp, "prepared", 1, &qp);
    for (int j = 0; j < 200; j++) {
      const double u = uni(-0.2, 1.2), v = uni(-0.2, 1.2), tt = uni(-0.3, 0.3);
      double       x[6][3], xp[6][3], nn[3], np[3], y[3];
      Projection   pr, prp;
      PatchEval(&q, u, v, x[0], x[1], x[2], x[3], x[4], x[5]);
      PatchEval(&qp, u, v, xp[0], xp[1], xp[2], xp[3], xp[4], xp[5]);
      diff += memcmp(x, xp, sizeof(x)) != 0;
      PatchNormal(&q, u, v, nn);
      PatchNormal(&qp, u, v, np);
      diff += memcmp(nn, np, sizeof(nn)) != 0;
      for (int i = 0; i < 3; i++) y[i] = x[0][i] + tt * nn[i] + sh[i];
      const int r = ToolProject(&t, sh, y, PETSC_INFINITY, &pr), rp = ToolProject(&tp, sh, y, PETSC_INFINITY, &prp);
      diff += r != rp || (!r && (pr.patch != prp.patch || pr.xi != prp.xi || pr.eta != prp.eta || pr.gap != prp.gap || pr.interior != prp.interior));
      n++;
    }
    PatchDestroy(&qp);
  }
  TU_CHECK(diff == 0, "PatchPrepare: %d points on 3 Coons patches, evaluation, normal and projection bit for bit those of the unprepared patch (%d differ)", n, diff);
}

/* ------------------------------------------------------------------ 8. options */

static char errmsg[4096];

static PetscErrorCode Capture(MPI_Comm comm, int line, const char *fun, const char *file, PetscErrorCode n, PetscErrorType p, const char *mess, void *ctx)
{
  if (p == PETSC_ERROR_INITIAL) snprintf(errmsg, sizeof(errmsg), "%s", mess ? mess : "");
  return n;
}

static const char *good_options = "-tool_names punch,die,roll,quad "
                                  "-tool_punch_motion 0,0,30 "
                                  "-tool_punch_patches 1 "
                                  "-tool_punch_patch0_type sphere "
                                  "-tool_punch_patch0_center 0,0,-50.8 "
                                  "-tool_punch_patch0_radius 50.8 "
                                  "-tool_punch_patch0_axis 0,0,2 "
                                  "-tool_punch_patch0_ref 1,0,1 "
                                  "-tool_punch_patch0_range 0,90,0,90 "
                                  "-tool_die_patches 2 "
                                  "-tool_die_patch0_type torus "
                                  "-tool_die_patch0_sense -1 "
                                  "-tool_die_patch0_center 0,0,7.35 "
                                  "-tool_die_patch0_axis 0,0,1 "
                                  "-tool_die_patch0_ref 1,0,0 "
                                  "-tool_die_patch0_major 65.53 "
                                  "-tool_die_patch0_minor 6.35 "
                                  "-tool_die_patch0_range 0,90,180,270 "
                                  "-tool_die_patch1_type plane "
                                  "-tool_die_patch1_origin 0,0,1 "
                                  "-tool_die_patch1_e1 2,0,0 "
                                  "-tool_die_patch1_e2 1,1,0 "
                                  "-tool_die_patch1_range 65.53,100,0,100 "
                                  "-tool_roll_patches 1 "
                                  "-tool_roll_patch0_type cylinder "
                                  "-tool_roll_patch0_center 0,0,10 "
                                  "-tool_roll_patch0_axis 0,1,0 "
                                  "-tool_roll_patch0_ref 0,0,-1 "
                                  "-tool_roll_patch0_radius 5 "
                                  "-tool_roll_patch0_range -90,90,-1,21 "
                                  "-tool_quad_patches 1 "
                                  "-tool_quad_patch0_type coons "
                                  "-tool_quad_patch0_bottom_type arc "
                                  "-tool_quad_patch0_bottom_points 1,0,0,0,1,0,0,0,0 "
                                  "-tool_quad_patch0_top_type arc "
                                  "-tool_quad_patch0_top_points 1.2,0,1,0,1.2,1,0,0,1 "
                                  "-tool_quad_patch0_left_type line "
                                  "-tool_quad_patch0_left_points 1,0,0,1.2,0,1 "
                                  "-tool_quad_patch0_right_type line "
                                  "-tool_quad_patch0_right_points 0,1,0,0,1.2,1";

static PetscErrorCode test_options(void)
{
  PetscInt n;
  Tool    *T;
  double   e = 0;

  PetscFunctionBeginUser;
  PetscCall(PetscOptionsClear(NULL));
  PetscCall(PetscOptionsInsertString(NULL, good_options));
  PetscCall(ToolsCreateFromOptions(PETSC_COMM_WORLD, &n, &T));
  TU_CHECK(n == 4 && !strcmp(T[0].name, "punch") && !strcmp(T[3].name, "quad") && T[0].npatch == 1 && T[1].npatch == 2, "options: %d tools (punch, die, roll, quad), patches %d %d %d %d", (int)n, T[0].npatch, T[1].npatch, T[2].npatch, T[3].npatch);
  {
    const Patch *s = &T[0].patch[0];
    e              = fabs(s->rev.R - 50.8) + fabs(s->rev.c[2] + 50.8) + fabs(s->rev.a[2] - 1) + fabs(s->rev.e[0] - 1) + fabs(s->rev.e[2]) + fabs(s->rev.t1 - PI / 2) + fabs(s->rev.s1 - PI / 2) + fabs(T[0].motion[2] - 30);
    TU_CHECK(istype(s, "sphere") && s->sense == 1 && e < 1e-14, "options: sphere punch (axis 0,0,2 normalised, ref 1,0,1 orthonormalised, degrees to radians, motion): error %.1e", e);
    double sh[3];
    ToolShift(&T[0], 0.5, sh);
    TU_CHECK(sh[0] == 0 && sh[1] == 0 && sh[2] == 15, "ToolShift: lambda 0.5 of motion 0,0,30 = %g,%g,%g", sh[0], sh[1], sh[2]);
  }
  {
    const Patch *tr = &T[1].patch[0], *pl = &T[1].patch[1];
    e = fabs(tr->rev.R - 65.53) + fabs(tr->rev.r - 6.35) + fabs(tr->rev.s0 - PI) + fabs(tr->rev.s1 - 1.5 * PI) + fabs(pl->plane.e1[0] - 1) + fabs(pl->plane.e2[1] - 1) + fabs(pl->plane.e2[0]) + fabs(pl->plane.u0 - 65.53) + fabs(pl->plane.v1 - 100);
    TU_CHECK(istype(tr, "torus") && tr->sense == -1 && istype(pl, "plane") && e < 1e-13, "options: die torus (sense -1) and plane (e2 orthonormalised against e1): error %.1e", e);
  }
  {
    const Patch *cy = &T[2].patch[0], *co = &T[3].patch[0];
    e = fabs(cy->rev.R - 5) + fabs(cy->rev.a[1] - 1) + fabs(cy->rev.e[2] + 1) + fabs(cy->rev.t0 + PI / 2) + fabs(cy->rev.s1 - 21) + fabs(co->coons.C0.c[2]) + fabs(co->coons.C1.a[0] - 1.2) + fabs(co->coons.D1.b[2] - 1);
    TU_CHECK(istype(cy, "cylinder") && istype(co, "coons") && co->coons.C0.type == CURVE_ARC && co->coons.D0.type == CURVE_LINE && e < 1e-14, "options: cylinder and coons data: error %.1e", e);
  }
  /* bounding boxes contain every sampled point and are tight (margin below 1 % of the size) */
  for (PetscInt k = 0; k < n; k++) {
    double lo[3] = {HUGE_VAL, HUGE_VAL, HUGE_VAL}, hi[3] = {-HUGE_VAL, -HUGE_VAL, -HUGE_VAL}, out = 0, marg = 0, size = 0;
    for (int j = 0; j < T[k].npatch; j++)
      for (int a = 0; a <= 200; a++)
        for (int b = 0; b <= 200; b++) {
          double x[3], xu[3], xv[3];
          PatchEval(&T[k].patch[j], a / 200.0, b / 200.0, x, xu, xv, NULL, NULL, NULL);
          for (int i = 0; i < 3; i++) {
            lo[i] = fmin(lo[i], x[i]);
            hi[i] = fmax(hi[i], x[i]);
          }
        }
    for (int i = 0; i < 3; i++) {
      out  = fmax(out, fmax(T[k].bbox[2 * i] - lo[i], hi[i] - T[k].bbox[2 * i + 1]));
      marg = fmax(marg, fmax(lo[i] - T[k].bbox[2 * i], T[k].bbox[2 * i + 1] - hi[i]));
      size = fmax(size, hi[i] - lo[i]);
    }
    TU_CHECK(out <= 0 && marg < 0.01 * size, "options: tool %s bbox [%g,%g]x[%g,%g]x[%g,%g] contains the samples (excess %.1e) with margin %.2e (size %g)", T[k].name, T[k].bbox[0], T[k].bbox[1], T[k].bbox[2], T[k].bbox[3], T[k].bbox[4], T[k].bbox[5], out, marg, size);
  }
  /* the punch built from options projects like the analytic sphere; maxdist skips far points */
  {
    const double sh[3] = {0, 0, 10}, y[3] = {3, 4, 12}, yf[3] = {300, 0, 0};
    Projection   pr;
    double       d[3] = {y[0], y[1], y[2] + 50.8 - 10};
    const int    r    = ToolProject(&T[0], sh, y, PETSC_INFINITY, &pr);
    TU_CHECK(r == 0 && pr.interior && fabs(pr.gap - (nrm(d) - 50.8)) < 1e-12, "options: punch at shift 10: gap %.15g = |y - c| - R", pr.gap);
    const int r1 = ToolProject(&T[0], sh, yf, 5.0, &pr), r2 = ToolProject(&T[0], sh, y, 5.0, &pr);
    TU_CHECK(r1 == 1 && r2 == 0, "ToolProject maxdist 5: far point skipped (returns %d), near point found (returns %d)", r1, r2);
  }
  PetscCall(ToolsDestroy(n, &T));
  TU_CHECK(T == NULL, "ToolsDestroy sets the array to NULL");

  /* no -tool_names: no tools */
  PetscCall(PetscOptionsClear(NULL));
  PetscCall(ToolsCreateFromOptions(PETSC_COMM_WORLD, &n, &T));
  TU_CHECK(n == 0 && T == NULL, "options: no -tool_names gives %d tools", (int)n);

  /* bad input: an error code and a message naming the option */
  const char *sph  = "-tool_names t -tool_t_patches 1 -tool_t_patch0_type sphere -tool_t_patch0_center 0,0,0 -tool_t_patch0_radius 1 -tool_t_patch0_axis 0,0,1 -tool_t_patch0_ref 1,0,0 -tool_t_patch0_range 0,90,0,90 ";
  const char *tor  = "-tool_names t -tool_t_patches 1 -tool_t_patch0_type torus -tool_t_patch0_center 0,0,0 -tool_t_patch0_axis 0,0,1 -tool_t_patch0_ref 1,0,0 -tool_t_patch0_major 2 -tool_t_patch0_minor 0.5 -tool_t_patch0_range 0,90,0,90 ";
  const char *pla  = "-tool_names t -tool_t_patches 1 -tool_t_patch0_type plane -tool_t_patch0_origin 0,0,0 -tool_t_patch0_e1 1,0,0 -tool_t_patch0_e2 0,1,0 -tool_t_patch0_range 0,1,0,1 ";
  const char *coo  = "-tool_names t -tool_t_patches 1 -tool_t_patch0_type coons -tool_t_patch0_bottom_type line -tool_t_patch0_bottom_points 0,0,0,1,0,0 -tool_t_patch0_top_type line -tool_t_patch0_top_points 0,1,0,1,1,0 -tool_t_patch0_left_type line -tool_t_patch0_left_points 0,0,0,0,1,0 -tool_t_patch0_right_type line -tool_t_patch0_right_points 1,0,0,1,1,0 ";
  const char *cases[][3] = {
    {"-tool_names t -tool_t_patches 1 -tool_t_patch0_radius 1", "missing type", "-tool_t_patch0_type: missing"},
    {"-tool_names t -tool_t_patches 0", "no patches", "-tool_t_patches 0"},
    {"-tool_names t", "missing patch count", "-tool_t_patches: missing"},
    {"-tool_t_patch0_radius 0", "radius <= 0", "-tool_t_patch0_radius 0|must be > 0"},
    {"-tool_t_patch0_radius -2", "radius < 0", "-tool_t_patch0_radius -2|must be > 0"},
    {"-tool_t_patch0_center 0,0", "wrong count of values (2 of 3)", "-tool_t_patch0_center: needs 3 values, got 2"},
    {"-tool_t_patch0_range 0,90,0,90,5", "wrong count of values (5 of 4)", "-tool_t_patch0_range: needs 4 values, got 5"},
    {"-tool_t_patch0_axis 0,0,0", "zero axis", "-tool_t_patch0_axis 0|zero vector"},
    {"-tool_t_patch0_ref 0,0,3", "ref parallel to axis", "-tool_t_patch0_ref 0|zero or parallel to -tool_t_patch0_axis"},
    {"-tool_t_patch0_range 0,90,40,40", "empty range", "-tool_t_patch0_range|empty range"},
    {"-tool_t_patch0_range 0,190,0,90", "polar angle beyond 180", "-tool_t_patch0_range|must lie in [0, 180]"},
    {"-tool_t_patch0_type cone", "unknown type", "-tool_t_patch0_type cone: unknown"},
    {"-tool_t_patch0_sense 2", "sense 2", "-tool_t_patch0_sense 2: must be 1 or -1"},
    {"TOR-tool_t_patch0_minor 2 -tool_t_patch0_range 0,90,0,180", "minor = major, the tube angle reaching the axis", "-tool_t_patch0_minor 2|>= -tool_t_patch0_major 2|must keep R + r cos(ps) > 0"},
    {"TOR-tool_t_patch0_minor 3 -tool_t_patch0_range 0,90,-30,140", "minor > major, the tube angle past the axis", "-tool_t_patch0_minor 3|range -30|140|must keep"},
    {"TOR-tool_t_patch0_minor 3 -tool_t_patch0_range 0,90,170,200", "minor > major, the tube angle about pi", "-tool_t_patch0_minor 3|must keep R + r cos(ps) > 0"},
    {"PLA-tool_t_patch0_e2 2,0,0", "plane e2 parallel to e1", "-tool_t_patch0_e2 2|zero or parallel to -tool_t_patch0_e1"},
    {"COO-tool_t_patch0_right_points 1.3,0,0,1.3,1,0", "coons corners not meeting", "-tool_t_patch0: the boundary curves do not meet at corner (xi,eta)=(1,0): distance 0.3"},
    {"COO-tool_t_patch0_bottom_type arc -tool_t_patch0_bottom_points 0,0,0,1,0,0,0.4,-1,0", "arc not equidistant", "-tool_t_patch0_bottom_points: arc end points not equidistant"},
    {"COO-tool_t_patch0_bottom_type arc -tool_t_patch0_bottom_points 0,0,0,1,0,0,0.5,0,0", "arc diametrically opposite", "-tool_t_patch0_bottom_points|diametrically opposite"},
    {"COO-tool_t_patch0_left_type arc", "arc with 6 values", "-tool_t_patch0_left_points: needs 9 values, got 6"},
    {"COO-tool_t_patch0_top_type spline", "unknown curve type", "-tool_t_patch0_top_type spline: unknown"},
    {"-tool_names t,t", "duplicate name", "-tool_names|given twice"},
  };
  for (size_t k = 0; k < sizeof(cases) / sizeof(cases[0]); k++) {
    char           buf[4096];
    const char    *bad = cases[k][0], *base = sph;
    PetscErrorCode ierr;
    if (!strncmp(bad, "TOR", 3)) base = tor, bad += 3;
    else if (!strncmp(bad, "PLA", 3)) base = pla, bad += 3;
    else if (!strncmp(bad, "COO", 3)) base = coo, bad += 3;
    else if (!strncmp(bad, "-tool_names", 11)) base = "";
    snprintf(buf, sizeof(buf), "%s %s", base, bad);
    PetscCall(PetscOptionsClear(NULL));
    PetscCall(PetscOptionsInsertString(NULL, buf));
    errmsg[0] = 0;
    n         = -1;
    T         = NULL;
    PetscCall(PetscPushErrorHandler(Capture, NULL));
    ierr = ToolsCreateFromOptions(PETSC_COMM_WORLD, &n, &T);
    PetscCall(PetscPopErrorHandler());
    PetscCall(ToolsDestroy(n, &T));
    int  found = 1;
    char want[512], *tok, *save = NULL;
    snprintf(want, sizeof(want), "%s", cases[k][2]);
    for (tok = strtok_r(want, "|", &save); tok; tok = strtok_r(NULL, "|", &save)) found = found && strstr(errmsg, tok) != NULL;
    TU_CHECK(ierr != 0 && found, "bad options (%s): error code %d, message \"%s\"", cases[k][1], (int)ierr, errmsg);
  }
  /* the reference cases themselves are accepted */
  {
    const char *bases[4] = {sph, tor, pla, coo};
    int         okc      = 0;
    for (int k = 0; k < 4; k++) {
      PetscCall(PetscOptionsClear(NULL));
      PetscCall(PetscOptionsInsertString(NULL, bases[k]));
      PetscCall(ToolsCreateFromOptions(PETSC_COMM_WORLD, &n, &T));
      okc += n == 1;
      PetscCall(ToolsDestroy(n, &T));
    }
    TU_CHECK(okc == 4, "options: the 4 reference sets of the bad-input cases are valid (%d of 4)", okc);
  }
  PetscCall(PetscOptionsClear(NULL));
  PetscFunctionReturn(0);
}

/* ------------------------------------------------------------------ 8b. travel, registry, view */

/* ToolTravel: a straight ramp |lambda motion|; a path with a kink: the lengths of its pieces */
static void test_travel(void)
{
  Tool         t;
  Patch        q;
  const double path[12] = {0, 0, 0, 0, 0.5, 3, 4, 0, 1, 3, 4, 12}; /* pieces of length 5 and 12 */
  double       e = 0;
  settype(&q, "plane");
  tool_init(&t, "travel", 1, &q);
  set3(t.motion, 3, -4, 12); /* |motion| = 13 */
  {
    const double lam[5] = {0, 0.25, 0.5, 1, -0.2}, want[5] = {0, 3.25, 6.5, 13, 2.6};
    for (int k = 0; k < 5; k++) e = fmax(e, fabs(ToolTravel(&t, lam[k]) - want[k]));
  }
  TU_CHECK(e < 1e-14, "ToolTravel, straight ramp (motion 3,-4,12): |lambda| 13 at lambda 0, 0.25, 0.5, 1, -0.2: max error %.1e", e);
  t.npath = 3;
  memcpy(t.path, path, sizeof(path));
  e = 0;
  {
    /* the first piece 5 long over loads [0, 0.5], the second (the kink: +z) 12 long over [0.5, 1] */
    const double lam[7] = {0, 0.1, 0.5, 0.6, 0.75, 1, 1.5}, want[7] = {0, 1, 5, 5 + 2.4, 5 + 6, 17, 17};
    for (int k = 0; k < 7; k++) e = fmax(e, fabs(ToolTravel(&t, lam[k]) - want[k]));
  }
  {
    double sh[3];
    ToolShift(&t, 0.75, sh);
    e = fmax(e, fabs(sh[0] - 3) + fabs(sh[1] - 4) + fabs(sh[2] - 6));
  }
  TU_CHECK(e < 1e-14, "ToolTravel, path 0:(0,0,0) 0.5:(3,4,0) 1:(3,4,12): 0, 1, 5, 7.4, 11, 17 at loads 0, 0.1, 0.5, 0.6, 0.75, 1, held (17) at 1.5: max error %.1e", e);
  t.npath = 2; /* a path ending at load 0.5: held after it */
  TU_CHECK(ToolTravel(&t, 0.9) == 5.0 && ToolTravel(&t, 0.5) == 5.0, "ToolTravel: a path ending at load 0.5 holds its length 5 after it (%g at 0.9)", ToolTravel(&t, 0.9));
}

/* a type registered at run time: a plane under another name (the registry, not the files, decides
   which option values are types) */
static PetscErrorCode CreateSlab(Patch *p)
{
  PetscFunctionBeginUser;
  PetscCall(PatchSetType(p, "plane"));
  PetscFunctionReturn(0);
}

static PetscErrorCode test_registry(void)
{
  const char    *pla = "-tool_names t -tool_t_patches 1 -tool_t_patch0_origin 0,0,0 -tool_t_patch0_e1 1,0,0 -tool_t_patch0_e2 0,1,0 -tool_t_patch0_range 0,1,0,1 -tool_t_patch0_type ";
  char           buf[1024];
  PetscInt       n = -1;
  Tool          *T = NULL;
  PetscErrorCode ierr;
  Patch          p;

  PetscFunctionBeginUser;
  /* an unknown type: a one-line error naming the option, its value and the registered types */
  snprintf(buf, sizeof(buf), "%sslab", pla);
  PetscCall(PetscOptionsClear(NULL));
  PetscCall(PetscOptionsInsertString(NULL, buf));
  errmsg[0] = 0;
  PetscCall(PetscPushErrorHandler(Capture, NULL));
  ierr = ToolsCreateFromOptions(PETSC_COMM_WORLD, &n, &T);
  PetscCall(PetscPopErrorHandler());
  PetscCall(ToolsDestroy(n, &T));
  TU_CHECK(ierr != 0 && !strcmp(errmsg, "-tool_t_patch0_type slab: unknown patch type (use plane, sphere, cylinder, torus, coons or facets)"), "registry: an unknown patch type is refused with one line naming the option: \"%s\"", errmsg);
  memset(&p, 0, sizeof(p));
  PetscCall(PetscPushErrorHandler(Capture, NULL));
  ierr = PatchSetType(&p, "slab");
  PetscCall(PetscPopErrorHandler());
  TU_CHECK(ierr != 0 && strstr(errmsg, "unknown patch type 'slab'") && !strchr(errmsg, '\n'), "registry: PatchSetType with an unregistered name fails: \"%s\"", errmsg);
  /* registered, the name is a type */
  PetscCall(PatchRegister("slab", CreateSlab));
  PetscCall(PetscOptionsInsertString(NULL, buf));
  PetscCall(ToolsCreateFromOptions(PETSC_COMM_WORLD, &n, &T));
  {
    Projection pr;
    const double sh[3] = {0, 0, 0}, y[3] = {0.3, 0.4, 0.25};
    const int    r     = ToolProject(&T[0], sh, y, PETSC_INFINITY, &pr);
    TU_CHECK(n == 1 && istype(&T[0].patch[0], "plane") && r == 0 && pr.gap == 0.25 && pr.xi == 0.3 && pr.eta == 0.4, "registry: a type registered at run time (\"slab\", a plane) builds from options and projects (gap %g)", pr.gap);
  }
  PetscCall(ToolsDestroy(n, &T));
  PetscCall(PetscOptionsClear(NULL));
  PetscFunctionReturn(0);
}

/* ToolView: one line for the tool and one per patch */
static PetscErrorCode test_view(void)
{
  char        path[PETSC_MAX_PATH_LEN], line[1024];
  PetscViewer v;
  PetscInt    n;
  Tool       *T;
  int         nl = 0, ok = 1, np = 0;
  FILE       *fp;

  PetscFunctionBeginUser;
  PetscCall(PetscOptionsClear(NULL));
  PetscCall(PetscOptionsInsertString(NULL, good_options));
  PetscCall(ToolsCreateFromOptions(PETSC_COMM_WORLD, &n, &T));
  snprintf(path, sizeof(path), "/tmp/atrito_test_tool_view_%ld.txt", (long)getpid());
  PetscCall(PetscViewerASCIIOpen(PETSC_COMM_SELF, path, &v));
  for (PetscInt k = 0; k < n; k++) {
    PetscCall(ToolView(&T[k], v));
    np += T[k].npatch;
  }
  PetscCall(PetscViewerDestroy(&v));
  fp = fopen(path, "r");
  while (fp && fgets(line, sizeof(line), fp)) {
    nl++;
    if (nl == 1) ok = ok && strstr(line, "Tool punch: 1 patch, motion 0.,0.,30., travel at load 1 30.") != NULL;
    if (nl == 2) ok = ok && strstr(line, "patch 0: sphere, sense 1: centre 0.,0.,-50.8") && strstr(line, "radius 50.8") && strstr(line, "range 0.,90.,0.,90.");
  }
  if (fp) fclose(fp);
  remove(path);
  TU_CHECK(fp && ok && nl == n + np, "ToolView: %d lines for %d tools and %d patches (a line per tool, then per patch: type, sense, parameters in the options' units)", nl, (int)n, np);
  PetscCall(ToolsDestroy(n, &T));
  PetscCall(PetscOptionsClear(NULL));
  PetscFunctionReturn(0);
}

/* ------------------------------------------------------------------ 9. the examples of doc/tools.md */

/* each ``` block of the document, newlines as spaces; returns the number of blocks */
static int doc_blocks(const char *path, char blocks[][4096], int maxb)
{
  FILE *fp = fopen(path, "r");
  char  line[1024];
  int   nb = 0, in = 0;
  if (!fp) return -1;
  while (fgets(line, sizeof(line), fp)) {
    if (!strncmp(line, "```", 3)) {
      if (in) nb++;
      else if (nb < maxb) blocks[nb][0] = 0;
      in = !in;
      continue;
    }
    if (in && nb < maxb) {
      for (char *c = line; *c; c++)
        if (*c == '\n') *c = ' ';
      strncat(blocks[nb], line, 4095 - strlen(blocks[nb]));
    }
  }
  fclose(fp);
  return nb < maxb ? nb : maxb;
}

static PetscErrorCode test_doc_examples(void)
{
  static char blocks[16][4096];
  char        path[PETSC_MAX_PATH_LEN] = "doc/tools.md";
  int         nb, nok = 0;
  Tool       *sph = NULL, *coo = NULL, *die = NULL;
  PetscInt    nsph = 0, ncoo = 0, ndie = 0;

  PetscFunctionBeginUser;
  nb = doc_blocks(path, blocks, 16);
  TU_CHECK(nb >= 5, "doc examples: %d option blocks in %s (run from the repository root)", nb, path);
  for (int b = 0; b < nb; b++) {
    PetscInt n;
    Tool    *T;
    PetscCall(PetscOptionsClear(NULL));
    PetscCall(PetscOptionsInsertString(NULL, blocks[b]));
    PetscCall(ToolsCreateFromOptions(PETSC_COMM_WORLD, &n, &T));
    nok += n == 1;
    if (n == 1 && !strcmp(T[0].name, "punch") && T[0].npatch == 1 && !sph) sph = T, nsph = n;
    else if (n == 1 && !strcmp(T[0].name, "punch") && T[0].npatch == 4 && !coo) coo = T, ncoo = n;
    else if (n == 1 && !strcmp(T[0].name, "die") && !die) die = T, ndie = n;
    else PetscCall(ToolsDestroy(n, &T));
  }
  TU_CHECK(nb > 0 && nok == nb && sph && coo && die, "doc examples: %d of %d blocks build one tool each (sphere punch, Coons punch, die found)", nok, nb);
  if (sph && coo) {
    const double sh[3] = {0, 0, 12.5}, R = 50.8;
    double       emax = 0;
    int          bad = 0, n = 0;
    for (int a = 0; a <= 17; a++)
      for (int b = 0; b <= 18; b++)
        for (int k = 0; k < 3; k++) {
          const double th = deg(5.0 * a), ph = deg(5.0 * b), t = -1.0 + 2.0 * k;
          double       y[3] = {(R + t) * sin(th) * cos(ph), (R + t) * sin(th) * sin(ph), -R + (R + t) * cos(th) + sh[2]};
          Projection   ps, pc;
          n++;
          if (ToolProject(sph, sh, y, PETSC_INFINITY, &ps) || ToolProject(coo, sh, y, PETSC_INFINITY, &pc) || pc.patch == 3 || fabs(ps.gap - t) > 1e-12) { /* the far shoulder plane must not win */
            if (getenv("TOOL_DEBUG")) printf("# DEBUG th %g ph %g t %g: sphere gap %.17g, coons patch %d gap %.17g\n", 5.0 * a, 5.0 * b, t, ps.gap, pc.patch, pc.gap);
            bad++;
            continue;
          }
          emax = fmax(emax, fabs(pc.gap - ps.gap) / R);
        }
    TU_CHECK(bad == 0 && emax < 0.0104, "doc punch: sphere and 3 Coons patches + plane, %d points 1 above to 1 below the sphere (symmetry planes included): gaps differ by at most %.4f R", n, emax);
    const double yq[3] = {55, 10, -50.8 + 0.5 + sh[2]};
    Projection   pq;
    const int    r = ToolProject(coo, sh, yq, PETSC_INFINITY, &pq);
    TU_CHECK(r == 0 && pq.patch == 3 && pq.interior && fabs(pq.gap - 0.5) < 1e-12, "doc punch: a point 0.5 above the shoulder plane beyond the equator: patch %d, gap %.15g", pq.patch, pq.gap);
  }
  if (die) {
    const double sh[3] = {0, 0, 0}, y1[3] = {60 * cos(deg(20)), 60 * sin(deg(20)), 0.5}, y2[3] = {48 * cos(deg(20)), 48 * sin(deg(20)), 0.0};
    const double q[3] = {51.35 * cos(deg(20)), 51.35 * sin(deg(20)), 7.35};
    Projection   p1, p2;
    const int    r1 = ToolProject(die, sh, y1, PETSC_INFINITY, &p1), r2 = ToolProject(die, sh, y2, PETSC_INFINITY, &p2);
    TU_CHECK(r1 == 0 && p1.patch == 1 && p1.interior && fabs(p1.gap - 0.5) < 1e-12 && fabs(p1.n[2] + 1) < 1e-15, "doc die: 0.5 below the flat face (Coons annulus): patch %d, gap %.15g, n_z %g", p1.patch, p1.gap, p1.n[2]);
    TU_CHECK(r2 == 0 && p2.patch == 0 && p2.interior && fabs(p2.gap - (dist(y2, q) - 6.35)) < 1e-12, "doc die: under the shoulder (torus): patch %d, gap %.15g = |y - q| - r", p2.patch, p2.gap);
  }
  PetscCall(ToolsDestroy(nsph, &sph));
  PetscCall(ToolsDestroy(ncoo, &coo));
  PetscCall(ToolsDestroy(ndie, &die));
  PetscCall(PetscOptionsClear(NULL));
  PetscFunctionReturn(0);
}

/* ------------------------------------------------------------------ timing (not a test) */

/* ------------------------------------------------------------------ meshed surfaces (facets) */

/* the tools of an options string (NULL and the error text on failure) */
static Tool *facets_tools(const char *opts, PetscInt *n, PetscErrorCode *ierr)
{
  Tool *T = NULL;
  *n      = 0;
  PetscOptionsClear(NULL);
  PetscOptionsInsertString(NULL, opts);
  errmsg[0] = 0;
  PetscPushErrorHandler(Capture, NULL);
  *ierr = ToolsCreateFromOptions(PETSC_COMM_WORLD, n, &T);
  PetscPopErrorHandler();
  if (*ierr) {
    ToolsDestroy(*n, &T);
    return NULL;
  }
  return T;
}

static int facets_count(const Tool *t) { return t && t->npatch == 1 && istype(&t->patch[0], "facets") ? ((const FacetsData *)t->patch[0].data)->nf : -1; }

static void test_facets_readers(void)
{
  reseed("test_facets_readers");
  PetscInt       n;
  PetscErrorCode ierr;
  Tool          *T;
  Projection     pr;
  const double   sh[3] = {0, 0, 0};
  struct {
    const char *opts, *what;
    int         nf, nopen;
    double      y[3], gap, nz;
  } cases[] = {
    {"-tool_names a -tool_a_file tests/data/tool_tet.stl -tool_a_smooth 0", "ASCII STL, closed tetrahedron", 4, 0, {1, 1, 1}, 2.0 / sqrt(3.0), 1.0 / sqrt(3.0)},
    {"-tool_names a -tool_a_file tests/data/tool_square_bin.stl", "binary STL, square", 2, 4, {0.3, 0.6, 0.5}, 0.5, 1.0},
    {"-tool_names a -tool_a_file tests/data/tool_quads.msh -tool_a_file_group top", "Gmsh 4.1, group 'top' (2 quadrangles)", 4, 6, {1.5, 0.5, 1.25}, 0.25, 1.0},
    {"-tool_names a -tool_a_file tests/data/tool_quads.msh -tool_a_file_group side", "Gmsh 4.1, group 'side' (1 triangle)", 1, 3, {0.5, 0.3, 0.5}, -0.3, 0.0},
    {"-tool_names a -tool_a_file tests/data/tool_quads.msh", "Gmsh 4.1, every surface element", 5, -1, {1.5, 0.5, 1.25}, 0.25, 1.0},
    {"-tool_names a -tool_a_file tests/data/tool_quads22.msh -tool_a_file_group top", "Gmsh 2.2, group 'top'", 4, 6, {1.5, 0.5, 0.75}, -0.25, 1.0},
    {"-tool_names a -tool_a_file tests/data/tool_quads22.msh -tool_a_file_group top -tool_a_flip", "Gmsh 2.2 flipped", 4, 6, {1.5, 0.5, 0.75}, 0.25, -1.0},
    {"-tool_names a -tool_a_file tests/data/tool_surface.inp", "Abaqus *SURFACE on a C3D8 face (S2, out of the solid)", 2, 4, {0.5, 0.5, 1.5}, 0.5, 1.0},
    {"-tool_names a -tool_a_file tests/data/tool_surface.inp -tool_a_file_group RIGID", "Abaqus R3D4 element set", 4, 6, {1.5, 0.5, 3.5}, 0.5, 1.0},
    {"-tool_names a -tool_a_file tests/data/tool_surface.inp -tool_a_file_group TOP -tool_a_file_format inp", "Abaqus named surface, format given", 2, 4, {0.2, 0.7, 0.9}, -0.1, 1.0},
    {"-tool_names a -tool_a_file tests/data/tool_rigid.inp -tool_a_file_group UPPER", "Abaqus R3D4 surface, SPOS", 4, 6, {1.5, 0.5, 3.5}, 0.5, 1.0},
    {"-tool_names a -tool_a_file tests/data/tool_rigid.inp -tool_a_file_group LOWER", "Abaqus R3D4 surface, SNEG", 4, 6, {1.5, 0.5, 3.5}, -0.5, -1.0},
  };
  for (size_t k = 0; k < sizeof(cases) / sizeof(cases[0]); k++) {
    T            = facets_tools(cases[k].opts, &n, &ierr);
    const int nf = facets_count(T), r = T ? ToolProject(&T[0], sh, cases[k].y, PETSC_INFINITY, &pr) : 1;
    const int no = T ? ((const FacetsData *)T[0].patch[0].data)->nopen : -2;
    TU_CHECK(T && nf == cases[k].nf && (cases[k].nopen < 0 || no == cases[k].nopen) && r == 0 && fabs(pr.gap - cases[k].gap) < 1e-12 && fabs(pr.n[2] - cases[k].nz) < 1e-12, "facets reader: %s: %d triangles (%d expected), %d open edges, gap %.15g (%.15g), n_z %g %s", cases[k].what, nf, cases[k].nf, no, r ? 0 : pr.gap, cases[k].gap, r ? 0 : pr.n[2], errmsg);
    if (T) ToolsDestroy(n, &T);
  }
  /* the open edge: a point beside the square is not in contact, one above its edge is */
  T = facets_tools("-tool_names a -tool_a_file tests/data/tool_square_bin.stl", &n, &ierr);
  if (T) {
    const double yo[3] = {1.5, 0.5, 0.1}, ye[3] = {1.0, 0.5, 0.2}, yc[3] = {1.0, 1.0, -0.3};
    Projection   pe, pc;
    const int    ro = ToolProject(&T[0], sh, yo, PETSC_INFINITY, &pr), re = ToolProject(&T[0], sh, ye, PETSC_INFINITY, &pe), rc = ToolProject(&T[0], sh, yc, PETSC_INFINITY, &pc);
    TU_CHECK(ro == 1 && re == 0 && fabs(pe.gap - 0.2) < 1e-14 && rc == 0 && fabs(pc.gap + 0.3) < 1e-14, "facets: beside an open edge no contact (returns %d), above the edge (%d, gap %g) and below a corner (%d, gap %g) in contact", ro, re, pe.gap, rc, pc.gap);
    ToolsDestroy(n, &T);
  } else TU_CHECK(0, "facets: square: %s", errmsg);
  /* a tool file of patches gives the same tool as the options */
  {
    PetscInt n2;
    Tool    *A = facets_tools("-tool_names a -tool_a_file tests/data/tool_patches.tool", &n, &ierr);
    Tool    *B = facets_tools("-tool_names a -tool_a_patches 2 -tool_a_patch0_type plane -tool_a_patch0_origin 0,0,0 -tool_a_patch0_e1 1,0,0 -tool_a_patch0_e2 0,1,0 -tool_a_patch0_range 0,1,0,1 -tool_a_patch1_type sphere -tool_a_patch1_center 0,0,-1 -tool_a_patch1_radius 1 -tool_a_patch1_axis 0,0,1 -tool_a_patch1_ref 1,0,0 -tool_a_patch1_range 0,90,0,90", &n2, &ierr);
    int      same = A && B && A[0].npatch == 2 && B[0].npatch == 2;
    for (int k = 0; same && k < 200; k++) {
      const double y[3] = {uni(-0.2, 1.2), uni(-0.2, 1.2), uni(-0.5, 0.5)};
      Projection   pa, pb;
      const int    ra = ToolProject(&A[0], sh, y, PETSC_INFINITY, &pa), rb = ToolProject(&B[0], sh, y, PETSC_INFINITY, &pb);
      same            = ra == rb && (ra || (pa.patch == pb.patch && pa.gap == pb.gap && pa.xi == pb.xi && pa.eta == pb.eta));
    }
    TU_CHECK(same, "tool file (.tool): the same patches as the options, bit for bit on 200 points %s", errmsg);
    if (A) ToolsDestroy(n, &A);
    if (B) ToolsDestroy(n2, &B);
  }
}

static void test_facets_errors(void)
{
  PetscInt n;
  PetscErrorCode ierr;
  const struct {
    const char *opts, *expect;
  } bad[] = {
    {"-tool_names a -tool_a_file tests/data/no_such.stl", "cannot open tool file 'tests/data/no_such.stl'"},
    {"-tool_names a -tool_a_file tests/data/bad_tool_garbage.stl", "tool file tests/data/bad_tool_garbage.stl: not an STL file"},
    {"-tool_names a -tool_a_file tests/data/bad_tool_empty.stl", "tool file tests/data/bad_tool_empty.stl: empty surface"},
    {"-tool_names a -tool_a_file tests/data/bad_tool_orient.stl", "tool file tests/data/bad_tool_orient.stl: the surface is not consistently oriented: facet 2 and facet 1"},
    {"-tool_names a -tool_a_file tests/data/bad_tool_nonmanifold.stl", "tool file tests/data/bad_tool_nonmanifold.stl: non-manifold edge shared by 3 facets"},
    {"-tool_names a -tool_a_file tests/data/bad_tool_nan.stl", "tool file tests/data/bad_tool_nan.stl: vertex"},
    {"-tool_names a -tool_a_file tests/data/bad_tool_type.msh", "tool file tests/data/bad_tool_type.msh: element 2: unknown element type 9"},
    {"-tool_names a -tool_a_file tests/data/bad_tool_type.inp", "tool file tests/data/bad_tool_type.inp: line 19: unknown element type S8R"},
    {"-tool_names a -tool_a_file tests/data/bad_tool_face.inp", "tool file tests/data/bad_tool_face.inp: surface face SPOS of solid element 1 (S1 to S6)"},
    {"-tool_names a -tool_a_file tests/data/tool_quads.msh -tool_a_file_group nowhere", "no physical surface named 'nowhere'"},
    {"-tool_names a -tool_a_file tests/data/tool_quads.txt", "-tool_a_file tests/data/tool_quads.txt: unknown format 'txt'"},
    {"-tool_names a -tool_a_file tests/data/bad_tool_key.tool", "tool file tests/data/bad_tool_key.tool: key 'patch1_colour' is not an option of its patches"},
    {"-tool_names a -tool_a_file tests/data/tool_tet.stl -tool_a_patches 1", "-tool_a_file and -tool_a_patches are exclusive"},
  };
  for (size_t k = 0; k < sizeof(bad) / sizeof(bad[0]); k++) {
    Tool *T = facets_tools(bad[k].opts, &n, &ierr);
    TU_CHECK(!T && ierr && strstr(errmsg, bad[k].expect) && !strchr(errmsg, '\n'), "facets error, one line: \"%s\"", errmsg);
  }
  /* without smoothing a non-manifold edge is accepted */
  Tool *T = facets_tools("-tool_names a -tool_a_file tests/data/bad_tool_nonmanifold.stl -tool_a_smooth 0", &n, &ierr);
  TU_CHECK(T && facets_count(T) == 3, "facets: a non-manifold surface is accepted with -smooth 0 %s", errmsg);
  if (T) ToolsDestroy(n, &T);
}

/* a sphere of radius R about c triangulated from an octahedron, each face split into k^2 */
static void write_sphere_stl(const char *path, double R, int k)
{
  FILE        *fp = fopen(path, "w");
  const double O[6][3] = {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}};
  const int    Fc[8][3] = {{0, 2, 4}, {2, 1, 4}, {1, 3, 4}, {3, 0, 4}, {2, 0, 5}, {1, 2, 5}, {3, 1, 5}, {0, 3, 5}};
  fprintf(fp, "solid s\n");
  for (int f = 0; f < 8; f++)
    for (int i = 0; i < k; i++)
      for (int j = 0; j < k - i; j++)
        for (int up = 0; up < 2; up++) {
          if (up && j == k - i - 1) continue;
          const int b[3][2] = {{i, j}, {i + 1, j}, {i, j + 1}}, t[3][2] = {{i + 1, j}, {i + 1, j + 1}, {i, j + 1}};
          fprintf(fp, "facet normal 0 0 0\n outer loop\n");
          for (int c = 0; c < 3; c++) {
            const int *ij = up ? t[c] : b[c];
            double     p[3], l;
            for (int d = 0; d < 3; d++) p[d] = O[Fc[f][0]][d] + (O[Fc[f][1]][d] - O[Fc[f][0]][d]) * ij[0] / k + (O[Fc[f][2]][d] - O[Fc[f][0]][d]) * ij[1] / k;
            l = nrm(p);
            fprintf(fp, "  vertex %.17g %.17g %.17g\n", R * p[0] / l, R * p[1] / l, R * p[2] / l);
          }
          fprintf(fp, " endloop\nendfacet\n");
        }
  fprintf(fp, "endsolid s\n");
  fclose(fp);
}

/* the warm start on larger spheres (1e4, 1e5 facets): nodes that move by steps of 0.1 to 3 facet
   sizes, each query hinted by the node's previous hinted result (as the contact object does): the
   same projection as ToolProject bit for bit, raw and smoothed, with and without a search
   distance; raw: the facet is the brute-force closest one */
static void test_facets_hint_large(void)
{
  reseed("test_facets_hint_large");
  PetscInt       n;
  PetscErrorCode ierr;
  const double   sh[3] = {0.1, -0.2, 0.3};
  const int      ks[2] = {36, 112};
  char           opts[512], path[256];
  snprintf(path, sizeof(path), "%s/facets_hint_%d.stl", getenv("TMPDIR") ? getenv("TMPDIR") : "/tmp", (int)getpid());
  for (int kk = 0; kk < 2; kk++) {
    write_sphere_stl(path, 1.0, ks[kk]);
    for (int smooth = 0; smooth < 2; smooth++) {
      snprintf(opts, sizeof(opts), "-tool_names s -tool_s_file %s -tool_s_file_format stl -tool_s_smooth %d", path, smooth);
      Tool *T = facets_tools(opts, &n, &ierr);
      if (!T) {
        TU_CHECK(0, "facets hint sphere: %s", errmsg);
        continue;
      }
      const Patch      *p = &T[0].patch[0];
      const FacetsData *m = (const FacetsData *)p->data;
      const double      hf = 2.2 / ks[kk]; /* about a facet's size */
      int               same = 1, brute = 1, nq = 0, nbrute = 0, ncert = 0;
      for (int node = 0; node < 60; node++) {
        double       y[3], dir[3], l;
        const double th = uni(0, PI), ph = uni(0, 2 * PI), band = node % 3 == 0 ? 1e-4 : (node % 3 == 1 ? 1e-2 : 0.05);
        Projection   prev;
        int          has = 0;
        const double maxdist = node % 2 ? PETSC_INFINITY : 0.03;
        dir[0] = sin(th) * cos(ph);
        dir[1] = sin(th) * sin(ph);
        dir[2] = cos(th);
        for (int step = 0; step < 25; step++) {
          const double r = 1.0 + uni(-band, band), st = hf * (step % 5 == 4 ? 3.0 : 0.1);
          for (int i = 0; i < 3; i++) dir[i] += st * uni(-1, 1);
          l = nrm(dir);
          for (int i = 0; i < 3; i++) y[i] = r * dir[i] / l + sh[i];
          Projection pr, ph_;
          const int  r0 = ToolProject(&T[0], sh, y, maxdist, &pr), r1 = ToolProjectHint(&T[0], sh, y, maxdist, has ? &prev : NULL, &ph_);
          nq++;
          {
            double yr[3], d2t;
            for (int i = 0; i < 3; i++) yr[i] = y[i] - sh[i];
            ncert += FacetsStarCertifies(p, FacetsTreeClosest(p, yr, &d2t), yr);
          }
          if (r0 != r1 || (!r0 && (ph_.patch != pr.patch || ph_.xi != pr.xi || ph_.eta != pr.eta || ph_.gap != pr.gap || ph_.n[0] != pr.n[0] || ph_.n[1] != pr.n[1] || ph_.n[2] != pr.n[2]))) same = 0;
          if (!smooth && !r0 && kk == 0) {
            double yr[3], d2b, u, v;
            for (int i = 0; i < 3; i++) yr[i] = y[i] - sh[i];
            nbrute++;
            if (FacetsBruteClosest(p, yr, &d2b) != FacetsOfParameters(p, ph_.xi, ph_.eta, &u, &v)) brute = 0;
          }
          if (!r1) {
            prev = ph_;
            has  = 1;
          }
        }
      }
      TU_CHECK(same && ncert > nq / 4, "facets sphere (%d triangles, %s): ToolProjectHint on %d queries along 60 node paths (hint: the node's previous result) gives ToolProject's result bit for bit (%d of them decided by the closest facet's star alone)", m->nf, smooth ? "smoothed" : "raw", nq, ncert);
      if (!smooth && kk == 0) TU_CHECK(brute && nbrute > 100, "facets sphere (%d triangles, raw): the hinted facet is the brute-force closest on %d points", m->nf, nbrute);
      ToolsDestroy(n, &T);
    }
  }
  remove(path);
}

/* squared distance of two triangles by sampling both (barycentric grids of n + 1 points a side):
   at least the exact distance, at most about the grid's spacing more */
static double tritri_sampled(const double A[3][3], const double B[3][3], int n)
{
  double best = HUGE_VAL;
  for (int i = 0; i <= n; i++)
    for (int j = 0; i + j <= n; j++) {
      double a[3];
      for (int c = 0; c < 3; c++) a[c] = A[0][c] + (A[1][c] - A[0][c]) * i / n + (A[2][c] - A[0][c]) * j / n;
      for (int k = 0; k <= n; k++)
        for (int l = 0; k + l <= n; l++) {
          double d2 = 0;
          for (int c = 0; c < 3; c++) {
            const double e = a[c] - (B[0][c] + (B[1][c] - B[0][c]) * k / n + (B[2][c] - B[0][c]) * l / n);
            d2 += e * e;
          }
          if (d2 < best) best = d2;
        }
    }
  return best;
}

/* the local certificate's pieces: the distance of two triangles against sampling (apart, parallel,
   coplanar, crossing), and each facet's clearance on a sphere a lower bound of its distance to
   every facet outside its star (brute force), not far below the sampled distance */
static void test_facets_clearance(void)
{
  reseed("test_facets_clearance");
  double worst = 0, over = 0;
  int    ncross = 0, okcross = 1;
  for (int k = 0; k < 300; k++) {
    double A[3][3], B[3][3];
    const int kind = k % 4; /* 0: random; 1: B a shifted copy of A (parallel); 2: coplanar; 3: B through A */
    for (int v = 0; v < 3; v++)
      for (int c = 0; c < 3; c++) A[v][c] = uni(-1, 1);
    for (int v = 0; v < 3; v++)
      for (int c = 0; c < 3; c++) B[v][c] = kind == 1 ? A[v][c] + (c == 2 ? 0.3 : 0.5) : uni(-1, 1) + (kind == 0 ? 1.0 : 0.0);
    if (kind == 2)
      for (int v = 0; v < 3; v++) A[v][2] = B[v][2] = 0.25, B[v][0] += 1.2;
    if (kind == 3) { /* the segment B0 B1 through A's centroid, across its plane */
      double g[3], n[3], e1[3], e2[3];
      for (int c = 0; c < 3; c++) {
        g[c]  = (A[0][c] + A[1][c] + A[2][c]) / 3;
        e1[c] = A[1][c] - A[0][c];
        e2[c] = A[2][c] - A[0][c];
      }
      n[0] = e1[1] * e2[2] - e1[2] * e2[1];
      n[1] = e1[2] * e2[0] - e1[0] * e2[2];
      n[2] = e1[0] * e2[1] - e1[1] * e2[0];
      const double ln = nrm(n);
      for (int c = 0; c < 3; c++) {
        B[0][c] = g[c] + 0.4 * n[c] / ln;
        B[1][c] = g[c] - 0.4 * n[c] / ln;
      }
      ncross++;
      okcross = okcross && FacetsTriTriDistance2(A, B) == 0.0;
      continue;
    }
    const double d = sqrt(FacetsTriTriDistance2(A, B)), ds = sqrt(tritri_sampled(A, B, 40));
    over  = fmax(over, d - ds);             /* the exact distance above a sampled one: wrong */
    worst = fmax(worst, (ds - d) / 0.1);    /* below it by more than about the spacing (2.8 / 40): wrong */
  }
  TU_CHECK(over <= 1e-12 && worst <= 1.0 && okcross && ncross > 0, "facets: distance of two triangles against sampling on 225 pairs (never above it: %.1e; below it by %.2f of the sampling's spacing at most) and 0 for %d crossing pairs", over, worst, ncross);
  {
    PetscInt       n;
    PetscErrorCode ierr;
    char           opts[512], path[256];
    snprintf(path, sizeof(path), "%s/facets_clear_%d.stl", getenv("TMPDIR") ? getenv("TMPDIR") : "/tmp", (int)getpid());
    write_sphere_stl(path, 1.0, 8);
    snprintf(opts, sizeof(opts), "-tool_names s -tool_s_file %s -tool_s_file_format stl -tool_s_smooth 0", path);
    Tool *T = facets_tools(opts, &n, &ierr);
    if (!T) TU_CHECK(0, "facets clearance sphere: %s", errmsg);
    else {
      const Patch      *p = &T[0].patch[0];
      const FacetsData *m = (const FacetsData *)p->data;
      double            low = 1.0;
      int               lower = 1, starok = 1;
      for (int f = 0; f < m->nf; f += 7) {
        int        ns = 0, st[256];
        double     A[3][3], dmin = HUGE_VAL, h = 0;
        const double cl = FacetsClearance(p, f, &ns, st, 256);
        for (int v = 0; v < 3; v++)
          for (int c = 0; c < 3; c++) A[v][c] = m->V[3 * m->F[3 * f + v] + c];
        for (int v = 0; v < 3; v++) h = fmax(h, sqrt(pow(A[v][0] - A[(v + 1) % 3][0], 2) + pow(A[v][1] - A[(v + 1) % 3][1], 2) + pow(A[v][2] - A[(v + 1) % 3][2], 2)));
        for (int g = 0; g < m->nf; g++) {
          int in = 0, shares = 0;
          for (int t = 0; t < ns; t++) in = in || st[t] == g;
          for (int v = 0; v < 3; v++)
            for (int w = 0; w < 3; w++) shares = shares || m->F[3 * g + v] == m->F[3 * f + w];
          if (in != shares) starok = 0; /* the star: exactly the facets sharing a vertex with f */
          if (in) continue;
          double B[3][3];
          for (int v = 0; v < 3; v++)
            for (int c = 0; c < 3; c++) B[v][c] = m->V[3 * m->F[3 * g + v] + c];
          dmin = fmin(dmin, sqrt(tritri_sampled(A, B, 12)));
        }
        if (cl > dmin) lower = 0;
        low  = fmin(low, cl / fmin(dmin, h));
      }
      TU_CHECK(lower && low > 0.7 && starok, "facets: each facet's clearance (sphere of %d triangles, every 7th facet) at most its distance to the facets outside its star (brute force), and at least %.2f of it (or of the longest edge, the search's reach); the star from the vertices' facet lists is exactly the facets sharing a vertex", m->nf, low);
      ToolsDestroy(n, &T);
    }
    remove(path);
  }
}

/* ties of the smoothed projection: points inside the crease of two Nagata patches (a sphere of
   512 triangles, below the midpoints of 40 edges), on the surface where both feet are equally far
   (found by bisection across the edge): a shift of the point by 1e-13 either way across it gives the
   same facet, the smaller index, and the strict minimum would have given both */
static void test_facets_ties(void)
{
  reseed("test_facets_ties");
  PetscInt       n;
  PetscErrorCode ierr;
  char           opts[512], path[256];
  snprintf(path, sizeof(path), "%s/facets_tie_%d.stl", getenv("TMPDIR") ? getenv("TMPDIR") : "/tmp", (int)getpid());
  write_sphere_stl(path, 1.0, 8);
  snprintf(opts, sizeof(opts), "-tool_names s -tool_s_file %s -tool_s_file_format stl -tool_s_smooth 1", path);
  Tool *T = facets_tools(opts, &n, &ierr);
  if (!T) {
    TU_CHECK(0, "facets ties: %s", errmsg);
    remove(path);
    return;
  }
  const Patch      *p = &T[0].patch[0];
  const FacetsData *m = (const FacetsData *)p->data;
  const double      sh[3] = {0, 0, 0};
  int               nt = 0, same = 1, smaller = 1, sides = 0;
  for (int f = 0; f < m->nf && nt < 40; f += 5) {
    const int g = m->adj[3 * f];
    if (g < 0) continue;
    double a[3], b[3], mid[3], t[3], o[3], lo, hi;
    for (int i = 0; i < 3; i++) {
      a[i]   = m->V[3 * m->F[3 * f] + i];
      b[i]   = m->V[3 * m->F[3 * f + 1] + i];
      mid[i] = 0.5 * (a[i] + b[i]);
    }
    const double lm = nrm(mid); /* inside the sphere, below the edge's midpoint, and across the edge */
    double       e[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]};
    t[0] = mid[1] * e[2] - mid[2] * e[1];
    t[1] = mid[2] * e[0] - mid[0] * e[2];
    t[2] = mid[0] * e[1] - mid[1] * e[0];
    const double lt = nrm(t);
    for (int i = 0; i < 3; i++) {
      o[i] = mid[i] * (1.0 - 2e-3) / lm * lm;
      t[i] /= lt;
    }
    lo = -0.05 * nrm(e);
    hi = 0.05 * nrm(e);
    double y[3], dl, dh;
    int    sf, sg;
#define TIE_AT(s_, out_)                                                                 \
  do {                                                                                   \
    for (int i = 0; i < 3; i++) y[i] = o[i] + (s_) * t[i];                               \
    out_ = sqrt(FacetsPatchDistance2(p, f, y, &sf)) - sqrt(FacetsPatchDistance2(p, g, y, &sg)); \
  } while (0)
    TIE_AT(lo, dl);
    TIE_AT(hi, dh);
    if (!(dl * dh < 0)) continue;
    for (int it = 0; it < 200 && hi - lo > 1e-15; it++) {
      double dm;
      const double s = 0.5 * (lo + hi);
      TIE_AT(s, dm);
      if ((dm < 0) == (dl < 0)) lo = s, dl = dm;
      else hi = s;
    }
    TIE_AT(0.5 * (lo + hi), dl);
#undef TIE_AT
    if (!sf || !sg) continue; /* both feet inside their patches: the crease from inside */
    nt++;
    int fs[2] = {-1, -2}, strict[2] = {-1, -1};
    for (int k = 0; k < 2; k++) {
      double     yk[3], u, v;
      Projection pr;
      for (int i = 0; i < 3; i++) yk[i] = y[i] + (k ? 1e-13 : -1e-13) * t[i];
      if (ToolProject(&T[0], sh, yk, PETSC_INFINITY, &pr)) {
        same = 0;
        continue;
      }
      fs[k] = FacetsOfParameters(p, pr.xi, pr.eta, &u, &v);
      int s1, s2;
      strict[k] = FacetsPatchDistance2(p, f, yk, &s1) < FacetsPatchDistance2(p, g, yk, &s2) ? f : g; /* the strict minimum */
    }
    sides += strict[0] != strict[1];
    if (fs[0] != fs[1]) same = 0;
    if (fs[0] != (f < g ? f : g)) smaller = 0;
  }
  TU_CHECK(nt >= 10 && same && smaller && sides > 0, "facets: %d points inside the crease of two smoothed patches, equally far from both: shifted by 1e-13 across it, the same facet (the smaller index) on both sides (the strict minimum changes side at %d of them)", nt, sides);
  ToolsDestroy(n, &T);
  remove(path);
}

static void test_facets_sphere(void)
{
  reseed("test_facets_sphere");
  PetscInt       n;
  PetscErrorCode ierr;
  const double   sh[3] = {0.1, -0.2, 0.3};
  char           opts[512], path[256];
  snprintf(path, sizeof(path), "%s/facets_sphere_%d.stl", getenv("TMPDIR") ? getenv("TMPDIR") : "/tmp", (int)getpid());
  write_sphere_stl(path, 1.0, 16);
  for (int smooth = 0; smooth < 2; smooth++) {
    snprintf(opts, sizeof(opts), "-tool_names s -tool_s_file %s -tool_s_file_format stl -tool_s_smooth %d", path, smooth);
    Tool *T = facets_tools(opts, &n, &ierr);
    if (!T) {
      TU_CHECK(0, "facets sphere: %s", errmsg);
      continue;
    }
    const Patch *p = &T[0].patch[0];
    int          same = 1, hint_same = 1, nfd = 0, nbad = 0;
    double       egap = 0, en = 0, edn = 0, chord = HUGE_VAL;
    for (int k = 0; k < 2000; k++) {
      double       y[3], d2t, d2b, yr[3];
      const double th = uni(0, PI), ph = uni(0, 2 * PI), r = uni(0.7, 1.3);
      y[0] = r * sin(th) * cos(ph) + sh[0];
      y[1] = r * sin(th) * sin(ph) + sh[1];
      y[2] = r * cos(th) + sh[2];
      for (int i = 0; i < 3; i++) yr[i] = y[i] - sh[i];
      const int ft = FacetsTreeClosest(p, yr, &d2t), fb = FacetsBruteClosest(p, yr, &d2b);
      if (ft != fb || d2t != d2b) same = 0;
      if (k < 200) { /* every node's lower bound (box and oriented box) below its facets' distance */
        double mg;
        nbad += FacetsCheckNodeBounds(p, yr, &mg);
        if (mg < 0) nbad++;
      }
      Projection pr, ph_, hint;
      if (ToolProject(&T[0], sh, y, PETSC_INFINITY, &pr)) {
        same = 0;
        continue;
      }
      /* a hint from a random facet gives the same projection, bit for bit */
      hint       = pr;
      hint.patch = 0;
      {
        const int fr = (int)(urand() * ((const FacetsData *)p->data)->nf);
        hint.xi      = 4.0 * (fr >> 10) + 0.3;
        hint.eta     = 4.0 * (fr & 1023) + 0.3;
      }
      if (ToolProjectHint(&T[0], sh, y, PETSC_INFINITY, &hint, &ph_) || ph_.xi != pr.xi || ph_.eta != pr.eta || ph_.gap != pr.gap) hint_same = 0;
      egap = fmax(egap, fabs(pr.gap - (r - 1.0)));
      {
        const double na[3] = {sin(th) * cos(ph), sin(th) * sin(ph), cos(th)};
        en                 = fmax(en, dist(na, pr.n));
      }
      /* the frame chord of the contact object: (xi + 0.01, eta) on the same facet */
      {
        double x0[3], x1[3], xu[3], xv[3], u0, v0, u1, v1;
        PatchEval(p, pr.xi, pr.eta, x0, xu, xv, NULL, NULL, NULL);
        PatchEval(p, pr.xi + 0.01, pr.eta, x1, xu, xv, NULL, NULL, NULL);
        if (FacetsOfParameters(p, pr.xi, pr.eta, &u0, &v0) != FacetsOfParameters(p, pr.xi + 0.01, pr.eta, &u1, &v1)) chord = 0;
        chord = fmin(chord, dist(x0, x1));
      }
      if (smooth && k < 300) { /* dn/dy against central differences of the projected normal */
        double dn[9];
        if (PatchNormalDerivative(p, sh, y, &pr, dn)) {
          nfd++;
          continue;
        }
        for (int j = 0; j < 3; j++) {
          const double h  = 1e-6;
          double       yp[3] = {y[0], y[1], y[2]}, ym[3] = {y[0], y[1], y[2]};
          Projection   pp, pm;
          yp[j] += h;
          ym[j] -= h;
          ToolProject(&T[0], sh, yp, PETSC_INFINITY, &pp);
          ToolProject(&T[0], sh, ym, PETSC_INFINITY, &pm);
          for (int i = 0; i < 3; i++) edn = fmax(edn, fabs((pp.n[i] - pm.n[i]) / (2 * h) - dn[3 * i + j]));
        }
      }
    }
    const FacetsData *m = (const FacetsData *)p->data;
    TU_CHECK(same, "facets sphere (%d triangles, %s): the hierarchy gives the brute-force closest facet (same index, same distance) on 2000 points", m->nf, smooth ? "smoothed" : "raw");
    TU_CHECK(hint_same, "facets sphere (%s): ToolProjectHint from a random facet gives ToolProject's result bit for bit", smooth ? "smoothed" : "raw");
    TU_CHECK(nbad == 0, "facets sphere (%s): every hierarchy node's lower bound (box and oriented box) is below the distance of each of its facets at 200 points from 0.7 to 1.3 R (%d violations)", smooth ? "smoothed" : "raw", nbad);
    TU_CHECK(smooth ? (egap < 2e-3 && en < 1e-2) : (egap < 2.5e-2 && en < 0.15), "facets sphere (%s): gap within %.2e of the sphere's, normal within %.2e", smooth ? "smoothed" : "raw", egap, en);
    TU_CHECK(chord > 1e-4, "facets sphere (%s): the frame chord (xi + 0.01, eta) stays on the facet, length >= %.2e", smooth ? "smoothed" : "raw", chord);
    if (smooth) TU_CHECK(edn < 1e-6 && nfd < 30, "facets sphere dn/dy against central differences of the projected normal: max error %.2e (%d edge-held points differenced by the caller)", edn, nfd);
    if (smooth) { /* the normal across facet edges: the same at vertices, a small jump along edges */
      const double mid[3][2] = {{0.5, 0}, {0.5, 0.5}, {0, 0.5}}, cor[3][2] = {{0, 0}, {1, 0}, {0, 1}};
      double       jmid = 0, jv = 0;
      for (int f = 0; f < m->nf; f++)
        for (int e = 0; e < 3; e++) {
          const int g = m->adj[3 * f + e], a = m->F[3 * f + e], b = m->F[3 * f + (e + 1) % 3];
          int       eg = -1, ca = -1;
          for (int q = 0; q < 3; q++) {
            if (m->F[3 * g + q] == b && m->F[3 * g + (q + 1) % 3] == a) eg = q;
            if (m->F[3 * g + q] == a) ca = q;
          }
          double n1[3], n2[3], xi, eta;
          FacetsEncodeForTest(f, mid[e][0], mid[e][1], &xi, &eta);
          PatchNormal(p, xi, eta, n1);
          FacetsEncodeForTest(g, mid[eg][0], mid[eg][1], &xi, &eta);
          PatchNormal(p, xi, eta, n2);
          jmid = fmax(jmid, dist(n1, n2));
          FacetsEncodeForTest(f, cor[e][0], cor[e][1], &xi, &eta);
          PatchNormal(p, xi, eta, n1);
          FacetsEncodeForTest(g, cor[ca][0], cor[ca][1], &xi, &eta);
          PatchNormal(p, xi, eta, n2);
          jv = fmax(jv, dist(n1, n2));
        }
      TU_CHECK(jv < 1e-12 && jmid < 2e-2, "facets sphere smoothed: the normal is continuous at vertices (jump %.1e) and jumps by at most %.2e rad across edges (midpoints)", jv, jmid);
      TU_CHECK((double)FacetsBytes(m) / m->nf <= 200.0, "facets sphere (%d triangles): the tool's storage %.0f bytes per facet, at most 200", m->nf, (double)FacetsBytes(m) / m->nf);
    }
    ToolsDestroy(n, &T);
  }
  remove(path);
}

static double project_ns(const Patch *p, double thick)
{
  enum { NP = 4000 };
  static double Y[NP][3];
  Tool          t;
  Patch         q     = *p;
  const double  sh[3] = {0, 0, 0};
  struct timespec t0, t1;
  Projection      pr;
  double          acc = 0;
  tool_init(&t, "time", 1, &q);
  for (int k = 0; k < NP; k++) {
    double x[3], xu[3], xv[3], n[3];
    const double u = uni(-0.1, 1.1), v = uni(-0.1, 1.1), tt = uni(-thick, thick);
    PatchEval(p, u, v, x, xu, xv, NULL, NULL, NULL);
    PatchNormal(p, u, v, n);
    for (int i = 0; i < 3; i++) Y[k][i] = x[i] + tt * n[i];
  }
  clock_gettime(CLOCK_MONOTONIC, &t0);
  for (int rep = 0; rep < 5; rep++)
    for (int k = 0; k < NP; k++) {
      ToolProject(&t, sh, Y[k], PETSC_INFINITY, &pr);
      acc += pr.gap;
    }
  clock_gettime(CLOCK_MONOTONIC, &t1);
  if (acc == 12345.678) printf("#\n");
  return ((t1.tv_sec - t0.tv_sec) * 1e9 + (t1.tv_nsec - t0.tv_nsec)) / (5.0 * NP);
}

int main(int argc, char **argv)
{
  Patch oct[3];
  const double c0[3] = {0, 0, 0};
  PetscCall(PetscInitialize(&argc, &argv, NULL, NULL));
  octant_coons(c0, 1.0, oct);
  const Patch pl = make_plane(), sp = make_sphere(1), spm = make_sphere(-1), cy = make_cylinder(1), cym = make_cylinder(-1), to = make_torus(1), tom = make_torus(-1), ts = make_spindle_torus(1), tsm = make_spindle_torus(-1), cc = make_coons_cone(), cz = make_coons_collapsed();

  /* 1. derivatives */
  test_derivatives("plane", &pl);
  test_derivatives("sphere", &sp);
  test_derivatives("cylinder", &cy);
  test_derivatives("torus", &to);
  test_derivatives("coons (2 arcs, 2 lines)", &cc);
  test_derivatives("coons (4 great-circle arcs)", &oct[0]);

  /* 2. normals */
  test_normals("plane", &pl);
  test_normals("sphere", &sp);
  test_normals("sphere sense -1", &spm);
  test_normals("cylinder", &cy);
  test_normals("torus", &to);
  test_normals("coons", &cc);

  /* 3. Coons shapes */
  test_coons_shapes();

  /* 4. projection vs brute force */
  test_projection("project plane", &pl, 0.5, 2.3);
  test_projection("project sphere", &sp, 0.4, 1.3);
  test_projection("project cylinder", &cy, 0.3, 2.2);
  test_projection("project torus", &to, 0.2, 1.55);
  test_projection("project coons (2 arcs, 2 lines)", &cc, 0.3, 1.6);
  test_projection("project coons (spherical quad)", &oct[1], 0.3, 1.0);
  test_projection("project coons (octant, one side collapsed into the pole)", &cz, 0.3, 1.0);
  {
    double n[3], emax = 0, J = 0;
    for (int k = 0; k <= 10; k++) {
      J    = fmax(J, PatchNormal(&cz, k / 10.0, 0.0, n));
      emax = fmax(emax, fabs(n[2] - 1) + fabs(n[0]) + fabs(n[1]));
    }
    TU_CHECK(J == 0 && emax < 1e-6, "coons with a collapsed side: |x_xi x x_eta| = %g there, normal = the limit from inside (+z at the pole): error %.1e", J, emax);
  }

  /* 5. pole */
  test_pole();

  /* 6. multi-patch */
  test_multipatch();
  test_open_edge();

  /* 7. normal derivative */
  test_normal_derivative("dn/dy plane", &pl, 0.5, 1);
  test_normal_derivative("dn/dy sphere", &sp, 0.4, 1);
  test_normal_derivative("dn/dy sphere sense -1", &spm, 0.4, 1);
  test_normal_derivative("dn/dy cylinder", &cy, 0.3, 1);
  test_normal_derivative("dn/dy cylinder sense -1", &cym, 0.3, 1);
  test_normal_derivative("dn/dy torus", &to, 0.2, 1);
  test_normal_derivative("dn/dy torus sense -1", &tom, 0.2, 1);
  {
    Patch ccp = cc, ocp = oct[1];
    PatchPrepare(&ccp);
    PatchPrepare(&ocp);
    test_normal_derivative("dn/dy coons (2 arcs, 2 lines)", &cc, 0.3, 1);
    test_normal_derivative("dn/dy coons (2 arcs, 2 lines), prepared", &ccp, 0.3, 1);
    test_normal_derivative("dn/dy coons (spherical quad), prepared", &ocp, 0.3, 1);
    PatchDestroy(&ccp);
    PatchDestroy(&ocp);
  }
  {
    /* a point above the collapsed side of the octant: projected onto the pole, where the normal has
       no derivative from the parametrisation; the caller differences */
    Tool       t;
    Patch      q = cz;
    Projection pr;
    double     dn[9], y[3] = {0, 0, 1.3}, sh[3] = {0, 0, 0};
    tool_init(&t, "collapsed", 1, &q);
    const int rp = ToolProject(&t, sh, y, PETSC_INFINITY, &pr), rd = rp ? -1 : PatchNormalDerivative(&q, sh, y, &pr, dn);
    TU_CHECK(rp == 0 && (pr.eta == 0.0 || pr.eta == 1.0 || pr.xi == 0.0 || pr.xi == 1.0) && rd == 1, "dn/dy coons at a collapsed side (projection at xi %g, eta %g): returns 1, the caller differences", pr.xi, pr.eta);
  }
  test_prepared(&cc, &oct[0], &cz);

  /* 8. options */
  PetscCall(test_options());
  test_travel();
  PetscCall(test_registry());
  PetscCall(test_view());

  /* 8b. the checks of 1, 2, 4 and 7 on a spindle torus (r > R), on a range outside its
     self-intersection */
  test_derivatives("spindle torus (r > R)", &ts);
  test_normals("spindle torus (r > R)", &ts);
  test_normals("spindle torus (r > R) sense -1", &tsm);
  test_projection("project spindle torus (r > R)", &ts, 0.2, 1.6);
  test_normal_derivative("dn/dy spindle torus (r > R)", &ts, 0.2, 1);
  test_normal_derivative("dn/dy spindle torus (r > R) sense -1", &tsm, 0.2, 1);

  /* 9. the examples of doc/tools.md */
  PetscCall(test_doc_examples());

  /* 10. meshed surfaces */
  test_facets_readers();
  test_facets_errors();
  test_facets_clearance();
  test_facets_ties();
  test_facets_sphere();
  test_facets_hint_large();
  PetscCall(PetscOptionsClear(NULL));

  /* timing */
  {
    Patch op = oct[0];
    PatchPrepare(&op);
    printf("# timing: ToolProject %.0f ns/call (sphere patch), %.0f ns/call (torus patch), %.0f ns/call (coons patch, 4 great-circle arcs), %.0f ns/call (the same, prepared), %.0f ns/call (coons, 2 arcs + 2 lines)\n", project_ns(&sp, 0.3), project_ns(&to, 0.2), project_ns(&oct[0], 0.3), project_ns(&op, 0.3), project_ns(&cc, 0.3));
    PatchDestroy(&op);
  }

  PetscCall(PetscFinalize());
  TU_RETURN();
}
