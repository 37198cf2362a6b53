/* Unit tests of the node-to-surface kinematics (contact_nts.h): projections on flat faces against
   closed forms, on warped quads and triangles against the stationarity residual, the derivatives
   of xi, g, n and of the slip increment against central finite differences of the projection,
   and the failure modes (degenerate face, far starts on a strongly warped quad). */
#include <stddef.h>
#include <stdlib.h>
#include <string.h>
#include "testutil.h"
#include "contact_nts.h"

static double urand(void) { return 2.0 * rand() / (double)RAND_MAX - 1.0; }
static double dot(const double a[3], const double b[3]) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }
static double norm3(const double a[3]) { return sqrt(dot(a, a)); }
static void   cross(const double a[3], const double b[3], double c[3])
{
  c[0] = a[1] * b[2] - a[2] * b[1];
  c[1] = a[2] * b[0] - a[0] * b[2];
  c[2] = a[0] * b[1] - a[1] * b[0];
}

/* the test's own face geometry: x, a_alpha and the twist a_{1,2} at xi */
static void face(int nen, const double xm[][3], const double xi[2], double x[3], double a[2][3], double b[3])
{
  static const double XA[4] = {-1, 1, 1, -1}, EA[4] = {-1, -1, 1, 1};
  double              N[4], d0[4], d1[4], bb[4];
  for (int k = 0; k < nen; k++) {
    if (nen == 3) {
      N[k]  = k == 0 ? 1 - xi[0] - xi[1] : xi[k - 1];
      d0[k] = k == 0 ? -1 : k == 1;
      d1[k] = k == 0 ? -1 : k == 2;
      bb[k] = 0;
    } else {
      N[k]  = 0.25 * (1 + XA[k] * xi[0]) * (1 + EA[k] * xi[1]);
      d0[k] = 0.25 * XA[k] * (1 + EA[k] * xi[1]);
      d1[k] = 0.25 * EA[k] * (1 + XA[k] * xi[0]);
      bb[k] = 0.25 * XA[k] * EA[k];
    }
  }
  for (int i = 0; i < 3; i++) {
    x[i] = a[0][i] = a[1][i] = b[i] = 0;
    for (int k = 0; k < nen; k++) {
      x[i] += N[k] * xm[k][i];
      a[0][i] += d0[k] * xm[k][i];
      a[1][i] += d1[k] * xm[k][i];
      b[i] += bb[k] * xm[k][i];
    }
  }
}

/* a random face of size ~L: a unit square (or right triangle) with corners moved by 0.2 and, for
   the quad, warped by +-warp out of its plane, then rotated and moved at random */
static void random_face(int nen, double L, double warp, double xm[][3])
{
  const double sq[4][2] = {{0, 0}, {1, 0}, {1, 1}, {0, 1}}, tr[3][2] = {{0, 0}, {1, 0}, {0, 1}};
  double       e[3][3], o[3] = {urand(), urand(), urand()};
  for (int j = 0; j < 3; j++) /* random orthonormal frame (Gram-Schmidt), right-handed */
    for (int i = 0; i < 3; i++) e[j][i] = urand();
  for (int j = 0; j < 2; j++) {
    for (int l = 0; l < j; l++) {
      const double c = dot(e[j], e[l]);
      for (int i = 0; i < 3; i++) e[j][i] -= c * e[l][i];
    }
    const double nn = norm3(e[j]);
    for (int i = 0; i < 3; i++) e[j][i] /= nn;
  }
  cross(e[0], e[1], e[2]);
  for (int k = 0; k < nen; k++) {
    const double u = (nen == 4 ? sq[k][0] : tr[k][0]) + 0.2 * urand(), v = (nen == 4 ? sq[k][1] : tr[k][1]) + 0.2 * urand();
    const double w = nen == 4 ? (k % 2 ? warp : -warp) + 0.05 * urand() : 0.1 * urand();
    for (int i = 0; i < 3; i++) xm[k][i] = L * (o[i] + u * e[0][i] + v * e[1][i] + w * e[2][i]);
  }
}

static int allfinite(const NTSProjection *p)
{
  const double *v = (const double *)&p->xi[0];
  for (size_t i = 0; i < (sizeof *p - offsetof(NTSProjection, xi)) / sizeof(double); i++)
    if (!isfinite(v[i])) return 0;
  return 1;
}

/* project X = (x_s, x_1, ..., x_nen) from xi0 */
static int projectX(int nen, const double *X, const double xi0[2], int derivs, NTSProjection *p)
{
  return NTSProject(nen, X, (const double(*)[3])(X + 3), xi0, 1e-8, derivs, p);
}

/* largest entry-wise |A - B| over the largest |B| */
static double relerr(int n, const double *A, const double *B)
{
  double e = 0, s = 1e-300;
  for (int i = 0; i < n; i++) {
    e = fmax(e, fabs(A[i] - B[i]));
    s = fmax(s, fabs(B[i]));
  }
  return e / s;
}

/* dxi, dg, dn and dds of the projection of X against central differences; err[4] accumulates the
   worst relative errors, *twist the smallest |(x_s - x).a_12|/(|a_1||a_2|), the weight of the
   curvature term of dr/dxi */
static int fd_check(int nen, const double *X, const double *X0, double L, double err[4], double *twist)
{
  const int     nc = 3 + 3 * nen;
  NTSProjection p, pp, pm;
  double        ds[3], dds[3 * NTS_MAXCOMP], fxi[2 * NTS_MAXCOMP], fg[NTS_MAXCOMP], fn[3 * NTS_MAXCOMP], fs[3 * NTS_MAXCOMP];
  if (projectX(nen, X, NULL, 1, &p)) return 1;
  NTSSlip(&p, X, X0, (const double(*)[3])(X + 3), (const double(*)[3])(X0 + 3), ds, dds);
  {
    double x[3], a[2][3], b[3], d[3];
    face(nen, (const double(*)[3])(X + 3), p.xi, x, a, b);
    for (int i = 0; i < 3; i++) d[i] = X[i] - x[i];
    *twist = fmin(*twist, fabs(dot(d, b)) / (norm3(a[0]) * norm3(a[1])));
  }
  for (int c = 0; c < nc; c++) {
    const double h = 1e-6 * L;
    double       Xp[NTS_MAXCOMP], Xm[NTS_MAXCOMP], dsp[3], dsm[3];
    memcpy(Xp, X, nc * sizeof(double));
    memcpy(Xm, X, nc * sizeof(double));
    Xp[c] += h;
    Xm[c] -= h;
    if (projectX(nen, Xp, p.xi, 0, &pp) || projectX(nen, Xm, p.xi, 0, &pm)) return 1;
    NTSSlip(&pp, Xp, X0, (const double(*)[3])(Xp + 3), (const double(*)[3])(X0 + 3), dsp, NULL);
    NTSSlip(&pm, Xm, X0, (const double(*)[3])(Xm + 3), (const double(*)[3])(X0 + 3), dsm, NULL);
    fg[c] = (pp.g - pm.g) / (2 * h);
    for (int r = 0; r < 2; r++) fxi[r * nc + c] = (pp.xi[r] - pm.xi[r]) / (2 * h);
    for (int r = 0; r < 3; r++) {
      fn[r * nc + c] = (pp.n[r] - pm.n[r]) / (2 * h);
      fs[r * nc + c] = (dsp[r] - dsm[r]) / (2 * h);
    }
  }
  err[0] = fmax(err[0], relerr(2 * nc, p.dxi, fxi));
  err[1] = fmax(err[1], relerr(nc, p.dg, fg));
  err[2] = fmax(err[2], relerr(3 * nc, p.dn, fn));
  err[3] = fmax(err[3], relerr(3 * nc, dds, fs));
  return 0;
}

int main(void)
{
  srand(2718);

  /* flat faces: closed forms */
  {
    const double  q[4][3] = {{1, 2, 3}, {3, 2, 3}, {3, 4, 3}, {1, 4, 3}}, xs[3] = {2.5, 2.4, 3.3}, xo[3] = {3.5, 3, 2.8};
    NTSProjection p;
    double        t[3];
    int           rc = NTSProject(4, xs, q, NULL, 1e-8, 0, &p);
    TU_CHECK(rc == 0 && fabs(p.xi[0] - 0.5) < 1e-14 && fabs(p.xi[1] + 0.6) < 1e-14 && fabs(p.g - 0.3) < 1e-14 && fabs(p.n[2] - 1) < 1e-15 && p.n[0] == 0 && p.n[1] == 0 && p.inside, "flat square: xi = (%.15g, %.15g), g = %.15g, n = (%g, %g, %g), inside", p.xi[0], p.xi[1], p.g, p.n[0], p.n[1], p.n[2]);
    NTSChord(&p, q, t);
    TU_CHECK(fabs(t[0] - 0.01) < 1e-15 && t[1] == 0 && t[2] == 0, "flat square: chord (eq 28) = 0.01 a_1 = (%g, %g, %g)", t[0], t[1], t[2]);
    rc           = NTSProject(4, xo, q, NULL, 1e-8, 0, &p);
    const int in = p.inside;
    NTSProject(4, xo, q, NULL, 0.6, 0, &p);
    TU_CHECK(rc == 0 && fabs(p.xi[0] - 1.5) < 1e-14 && fabs(p.xi[1]) < 1e-14 && fabs(p.g + 0.2) < 1e-14 && !in && p.inside, "flat square, beyond an edge: xi = (%.15g, %.15g) unclamped, g = %.15g (penetration), outside; inside with tol 0.6", p.xi[0], p.xi[1], p.g);
    /* a planar trapezoid, tilted (e_1 = (0.6, 0, 0.8), e_2 = (0, 1, 0), n = (-0.8, 0, 0.6)): the
       projection along n is the same at any distance; far off, the Newton steps stall at the
       round-off floor (about 1e-16 distance / size) */
    const double uv[4][2] = {{0, 0}, {2, 0}, {1.6, 1.5}, {0.3, 1.2}}, e1[3] = {0.6, 0, 0.8}, e2[3] = {0, 1, 0}, e3[3] = {-0.8, 0, 0.6};
    double       tz[4][3], xi1[2], dev = 0;
    int          fails = 0;
    for (int k = 0; k < 4; k++)
      for (int i = 0; i < 3; i++) tz[k][i] = 1 + uv[k][0] * e1[i] + uv[k][1] * e2[i];
    for (double dist = 1; dist < 2e6; dist *= 10) {
      double xf[3];
      for (int i = 0; i < 3; i++) xf[i] = 1 + 0.9 * e1[i] + 0.7 * e2[i] + dist * e3[i];
      fails += NTSProject(4, xf, tz, NULL, 1e-8, 0, &p) != 0;
      if (dist == 1) memcpy(xi1, p.xi, sizeof xi1);
      dev = fmax(dev, fmax(fabs(p.xi[0] - xi1[0]), fabs(p.xi[1] - xi1[1])));
    }
    TU_CHECK(fails == 0 && dev < 1e-8, "planar trapezoid, slave 1 to 1e6 off: %d failures, xi the same to %.1e", fails, dev);
    const double tri[3][3] = {{0, 0, 0}, {2, 0, 0}, {0, 2, 0}}, ys[3] = {0.5, 0.6, -0.1}, yo[3] = {1.5, 1.5, 0.2};
    rc = NTSProject(3, ys, tri, NULL, 1e-8, 0, &p);
    TU_CHECK(rc == 0 && fabs(p.xi[0] - 0.25) < 1e-14 && fabs(p.xi[1] - 0.3) < 1e-14 && fabs(p.g + 0.1) < 1e-14 && fabs(p.n[2] - 1) < 1e-15 && p.inside, "flat triangle: xi = (%.15g, %.15g), g = %.15g, inside", p.xi[0], p.xi[1], p.g);
    rc = NTSProject(3, yo, tri, NULL, 0.1, 0, &p);
    TU_CHECK(rc == 0 && fabs(p.xi[0] - 0.75) < 1e-14 && fabs(p.xi[1] - 0.75) < 1e-14 && !p.inside, "flat triangle, beyond the hypotenuse: xi = (%.15g, %.15g), outside with tol 0.1", p.xi[0], p.xi[1]);
  }

  /* warped quads and triangles: the slave placed at x(xi*) + g n(xi*) projects back on xi*;
     stationarity residual and |x_s - x| = |g| */
  for (int nen = 4; nen >= 3; nen--) {
    const double L = 2.0;
    double       rmax = 0, dmax = 0, ximax = 0;
    int          fails = 0;
    for (int trial = 0; trial < 20; trial++) {
      double xm[4][3], x[3], a[2][3], b[3], m[3], xs[3], xi[2];
      random_face(nen, L, 0.2, xm);
      if (nen == 4) {
        xi[0] = 0.6 * urand();
        xi[1] = 0.6 * urand();
      } else {
        xi[0] = 0.3 + 0.2 * urand();
        xi[1] = 0.3 + 0.2 * urand();
      }
      face(nen, xm, xi, x, a, b);
      cross(a[0], a[1], m);
      const double g = (trial % 2 ? -0.3 : 0.3) * L * (1 + 0.5 * urand()), mm = norm3(m);
      for (int i = 0; i < 3; i++) xs[i] = x[i] + g * m[i] / mm;
      NTSProjection p;
      if (NTSProject(nen, xs, xm, NULL, 1e-8, 0, &p)) {
        fails++;
        continue;
      }
      double d[3], r[2];
      face(nen, xm, p.xi, x, a, b);
      for (int i = 0; i < 3; i++) d[i] = xs[i] - x[i];
      for (int al = 0; al < 2; al++) r[al] = fabs(dot(d, a[al])) / (norm3(a[al]) * L);
      rmax  = fmax(rmax, fmax(r[0], r[1]));
      dmax  = fmax(dmax, fabs(norm3(d) - fabs(p.g)) / L);
      ximax = fmax(ximax, fmax(fabs(p.xi[0] - xi[0]), fabs(p.xi[1] - xi[1])));
    }
    TU_CHECK(fails == 0 && rmax < 1e-12 && dmax < 1e-12 && ximax < 1e-12, "%s, 20 random faces, slave above and below: |r_alpha|/(|a_alpha| L) <= %.1e, ||x_s - x| - |g||/L <= %.1e, xi* recovered to %.1e", nen == 4 ? "warped quad" : "triangle", rmax, dmax, ximax);
  }

  /* derivatives against central differences of the projection itself */
  for (int nen = 4; nen >= 3; nen--)
    for (int side = 0; side < 2; side++) {
      const double L   = 1.5;
      double       err[4] = {0, 0, 0, 0}, twist = 1e300;
      int          fails  = 0;
      for (int trial = 0; trial < 5; trial++) {
        double xm[4][3], x[3], a[2][3], b[3], m[3], X[NTS_MAXCOMP], X0[NTS_MAXCOMP], xi[2] = {0.5 * urand(), 0.5 * urand()};
        random_face(nen, L, 0.2, xm);
        if (nen == 3) {
          xi[0] = 0.3 + 0.25 * xi[0];
          xi[1] = 0.3 + 0.25 * xi[1];
        }
        face(nen, xm, xi, x, a, b);
        cross(a[0], a[1], m);
        const double g = (side ? -0.2 : 0.4) * L, mm = norm3(m);
        for (int i = 0; i < 3; i++) X[i] = x[i] + g * m[i] / mm + 0.05 * L * urand(); /* a little off the normal */
        memcpy(X + 3, xm, 3 * nen * sizeof(double));
        for (int c = 0; c < 3 + 3 * nen; c++) X0[c] = X[c] + 0.1 * L * urand();
        fails += fd_check(nen, X, X0, L, err, &twist);
      }
      const char *what = nen == 4 ? "warped quad" : "triangle", *where = side ? "below (penetration)" : "above";
      if (nen == 4) /* dropping the curvature term of dr/dxi would err by about this much */
        TU_CHECK(twist > 1e-3, "%s, slave %s: the twist term |(x_s - x).a_12| is at least %.1e of |a_1||a_2|", what, where, twist);
      TU_CHECK(fails == 0 && err[0] < 1e-6, "%s, slave %s: dxi/dX vs finite differences, relative error %.1e", what, where, err[0]);
      TU_CHECK(fails == 0 && err[1] < 1e-6, "%s, slave %s: dg/dX vs finite differences, relative error %.1e", what, where, err[1]);
      TU_CHECK(fails == 0 && err[2] < 1e-6, "%s, slave %s: dn/dX vs finite differences, relative error %.1e", what, where, err[2]);
      TU_CHECK(fails == 0 && err[3] < 1e-6, "%s, slave %s: d(ds)/dX (slip) vs finite differences, relative error %.1e", what, where, err[3]);
    }

  /* degenerate faces: nonzero return, nothing but finite numbers */
  {
    const double  line4[4][3] = {{0, 0, 0}, {1, 1, 0}, {2, 2, 0}, {3, 3, 0}}, line3[3][3] = {{0, 0, 0}, {1, 0, 1}, {2, 0, 2}}, xs[3] = {0.5, 0.2, 0.7};
    NTSProjection p, t;
    const int     r4 = NTSProject(4, xs, line4, NULL, 1e-8, 1, &p), r3 = NTSProject(3, xs, line3, NULL, 1e-8, 1, &t);
    TU_CHECK(r4 == 1 && r3 == 1 && allfinite(&p) && allfinite(&t) && !p.inside && !t.inside, "degenerate faces (corners on a line): quad returns %d, triangle %d (1: degenerate), no NaN", r4, r3);
  }

  /* far starts on a strongly warped quad (a hyperbolic paraboloid): converges to a stationary
     point or reports failure, never a NaN */
  {
    const double q[4][3] = {{0, 0, 0}, {1, 0, 1}, {1, 1, 0}, {0, 1, 1}}, starts[5] = {-25, -4, 0, 3, 25};
    int          conv = 0, fail = 0, bad = 0, nearconv = 0, near = 0;
    double       rmax = 0;
    for (int trial = 0; trial < 20; trial++) {
      const double xs[3] = {0.5 + 1.5 * urand(), 0.5 + 1.5 * urand(), 0.5 + 1.5 * urand()};
      for (int i = 0; i < 5; i++)
        for (int j = 0; j < 5; j++) {
          const double  xi0[2] = {starts[i], starts[j]};
          NTSProjection p;
          const int     rc = NTSProject(4, xs, q, xi0, 1e-8, 1, &p), isnear = fabs(xi0[0]) < 5 && fabs(xi0[1]) < 5;
          near += isnear;
          if (!allfinite(&p)) bad++;
          if (rc) {
            fail++;
            continue;
          }
          double x[3], a[2][3], b[3], d[3];
          conv++;
          nearconv += isnear;
          face(4, q, p.xi, x, a, b);
          for (int k = 0; k < 3; k++) d[k] = xs[k] - x[k];
          const double sc = fmax(1, norm3(d)) * fmax(norm3(a[0]), norm3(a[1]));
          rmax            = fmax(rmax, fmax(fabs(dot(d, a[0])), fabs(dot(d, a[1]))) / sc);
        }
    }
    TU_CHECK(bad == 0 && rmax < 1e-12, "far starts (|xi0| up to 25) on a hyperbolic paraboloid, 500 runs: %d converged (residual <= %.1e), %d reported failure, %d with NaN", conv, rmax, fail, bad);
    TU_CHECK(nearconv >= 0.95 * near, "hyperbolic paraboloid, starts with |xi0| <= 4: %d of %d converge (plain Newton cycles in about 30%% of them)", nearconv, near);
  }
  /* projection along an interpolated normal field (NTSProjectNormal): its derivatives against
     finite differences with the corner normals held, the flat face's closed form, and the
     continuity across a shared edge */
  {
    double worst[3] = {0, 0, 0};
    int    fails    = 0;
    for (int trial = 0; trial < 20; trial++) {
      double xm[4][3], nb[4][3], X[15];
      NTSProjection p;
      for (int k = 0; k < 4; k++) {
        const double c[4][2] = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
        xm[k][0] = c[k][0] + 0.1 * urand();
        xm[k][1] = c[k][1] + 0.1 * urand();
        xm[k][2] = 0.15 * urand();
        nb[k][0] = 0.2 * urand();
        nb[k][1] = 0.2 * urand();
        nb[k][2] = 1;
      }
      X[0] = 0.5 + 0.2 * urand();
      X[1] = 0.5 + 0.2 * urand();
      X[2] = (trial % 2 ? -0.1 : 0.3) + 0.05 * urand();
      memcpy(X + 3, xm, sizeof xm);
      if (NTSProjectNormal(4, X, (const double(*)[3])(X + 3), (const double(*)[3])nb, NULL, 1e-10, 1, &p)) {
        fails++;
        continue;
      }
      {
        double r[3], e = 0;
        for (int i = 0; i < 3; i++) r[i] = X[i] - p.x[i] - p.g * p.n[i];
        e = norm3(r);
        worst[2] = fmax(worst[2], e);
      }
      for (int c = 0; c < 15; c++) {
        const double  h = 1e-6;
        double        Xp[15], Xm[15];
        NTSProjection pp, pm;
        memcpy(Xp, X, sizeof Xp);
        memcpy(Xm, X, sizeof Xm);
        Xp[c] += h;
        Xm[c] -= h;
        if (NTSProjectNormal(4, Xp, (const double(*)[3])(Xp + 3), (const double(*)[3])nb, p.xi, 1e-10, 0, &pp) || NTSProjectNormal(4, Xm, (const double(*)[3])(Xm + 3), (const double(*)[3])nb, p.xi, 1e-10, 0, &pm)) {
          fails++;
          continue;
        }
        for (int a = 0; a < 2; a++) worst[0] = fmax(worst[0], fabs((pp.xi[a] - pm.xi[a]) / (2 * h) - p.dxi[15 * a + c]));
        worst[0] = fmax(worst[0], fabs((pp.g - pm.g) / (2 * h) - p.dg[c]));
        for (int i = 0; i < 3; i++) worst[1] = fmax(worst[1], fabs((pp.n[i] - pm.n[i]) / (2 * h) - p.dn[15 * i + c]));
      }
    }
    TU_CHECK(fails == 0 && worst[2] < 1e-12, "normal-field projection, 20 warped quads with tilted corner normals: x_s = x + g n to %.1e", worst[2]);
    TU_CHECK(fails == 0 && worst[0] < 1e-6, "normal-field projection: dxi/dX and dg/dX (corner normals held) vs finite differences, error %.1e", worst[0]);
    TU_CHECK(fails == 0 && worst[1] < 1e-6, "normal-field projection: dn/dX vs finite differences, error %.1e", worst[1]);
  }
  {
    /* flat face, the face's own normal at every corner: the closest point and the face's gap */
    const double  xm[4][3] = {{0, 0, 0}, {2, 0, 0}, {2, 2, 0}, {0, 2, 0}}, nb[4][3] = {{0, 0, 1}, {0, 0, 1}, {0, 0, 1}, {0, 0, 1}}, xs[3] = {1.5, 0.5, -0.3};
    NTSProjection p;
    const int     rc = NTSProjectNormal(4, xs, xm, nb, NULL, 1e-10, 1, &p);
    TU_CHECK(rc == 0 && fabs(p.xi[0] - 0.5) < 1e-14 && fabs(p.xi[1] + 0.5) < 1e-14 && fabs(p.g + 0.3) < 1e-14 && p.inside, "normal-field projection, flat face and its normal: xi (%g, %g), g %g (closed form 0.5, -0.5, -0.3)", p.xi[0], p.xi[1], p.g);
  }
  {
    /* two faces meeting at an angle along the edge x = 1, the shared corners' normal the mean of
       the two faces': a point projecting onto the edge from either face gives the same x, g, n */
    const double  A[4][3] = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}}, B[4][3] = {{1, 0, 0}, {2, 0, 0.3}, {2, 1, 0.3}, {1, 1, 0}};
    const double  nA[3] = {0, 0, 1}, nBf[3] = {-0.3 / sqrt(1.09), 0, 1 / sqrt(1.09)};
    double        ne[3], nbA[4][3], nbB[4][3], xs[3];
    NTSProjection pa, pb;
    for (int i = 0; i < 3; i++) ne[i] = 0.5 * (nA[i] + nBf[i]);
    for (int i = 0; i < 3; i++) {
      nbA[0][i] = nbA[3][i] = nA[i];
      nbA[1][i] = nbA[2][i] = ne[i];
      nbB[0][i] = nbB[3][i] = ne[i];
      nbB[1][i] = nbB[2][i] = nBf[i];
    }
    /* a point on the normal at the edge's middle */
    {
      const double nn = norm3(ne);
      for (int i = 0; i < 3; i++) xs[i] = (i == 0 ? 1.0 : (i == 1 ? 0.5 : 0.0)) + 0.2 * ne[i] / nn;
    }
    const int ra = NTSProjectNormal(4, xs, A, nbA, NULL, 1e-10, 0, &pa), rb = NTSProjectNormal(4, xs, B, nbB, NULL, 1e-10, 0, &pb);
    double    dx = 0, dn = 0;
    for (int i = 0; i < 3; i++) {
      dx = fmax(dx, fabs(pa.x[i] - pb.x[i]));
      dn = fmax(dn, fabs(pa.n[i] - pb.n[i]));
    }
    TU_CHECK(ra == 0 && rb == 0 && dx < 1e-13 && dn < 1e-13 && fabs(pa.g - pb.g) < 1e-13 && fabs(pa.xi[0] - 1) < 1e-12 && fabs(pb.xi[0] + 1) < 1e-12, "normal-field projection across a 17-degree edge: both faces give the same point, gap and normal (%.1e, %.1e, %.1e)", dx, fabs(pa.g - pb.g), dn);
  }
  TU_RETURN();
}
