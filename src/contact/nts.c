/* Node-to-surface kinematics on a deformable master face (contact_nts.h): closest-point
   projection by Newton, gap and normal, their exact first derivatives with respect to the slave
   and the master corners (implicit function theorem on the projection), and the slip increment
   between two deformable surfaces. */
#include <math.h>
#include <string.h>
#include "contact_nts.h"

#define NTS_MAXIT 30

static const double XA[4] = {-1, 1, 1, -1}, EA[4] = {-1, -1, 1, 1}; /* quad corners in (xi, eta) */

static void cross(const double a[3], const double b[3], double c[3])
{
  c[0] = a[1] * b[2] - a[2] * b[1];
  c[1] = a[2] * b[0] - a[0] * b[2];
  c[2] = a[0] * b[1] - a[1] * b[0];
}

static double dot(const double a[3], const double b[3]) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }

/* N_a, N_a,alpha, x and a_alpha at xi */
static void Shape(int nen, const double xm[][3], const double xi[2], double N[4], double dN[4][2], double x[3], double a[2][3])
{
  if (nen == 3) {
    N[0]     = 1 - xi[0] - xi[1];
    N[1]     = xi[0];
    N[2]     = xi[1];
    dN[0][0] = dN[0][1] = -1;
    dN[1][0] = dN[2][1] = 1;
    dN[1][1] = dN[2][0] = 0;
  } else
    for (int k = 0; k < 4; k++) {
      N[k]     = (1 + XA[k] * xi[0]) * (1 + EA[k] * xi[1]) / 4;
      dN[k][0] = XA[k] * (1 + EA[k] * xi[1]) / 4;
      dN[k][1] = EA[k] * (1 + XA[k] * xi[0]) / 4;
    }
  for (int i = 0; i < 3; i++) {
    x[i] = a[0][i] = a[1][i] = 0;
    for (int k = 0; k < nen; k++) {
      x[i] += N[k] * xm[k][i];
      a[0][i] += dN[k][0] * xm[k][i];
      a[1][i] += dN[k][1] * xm[k][i];
    }
  }
}

/* Geometry at p->xi, d = x_s - x, the residual r and dr/dxi = J (symmetric:
   J[0] = (1,1), J[1] = (1,2), J[2] = (2,2)). b = a_{1,2} = a_{2,1}, the only second derivative of x
   (the quad's twist, sum_a xi_a eta_a x_a / 4; zero for the triangle). Returns 1 when the face is
   degenerate at xi (a_1, a_2 parallel or zero). */
static int System(const double xs[3], const double xm[][3], const double b[3], NTSProjection *p, double m[3], double d[3], double r[2], double J[3])
{
  Shape(p->nen, xm, p->xi, p->N, p->dN, p->x, p->a);
  for (int i = 0; i < 3; i++) d[i] = xs[i] - p->x[i];
  cross(p->a[0], p->a[1], m);
  r[0] = dot(d, p->a[0]);
  r[1] = dot(d, p->a[1]);
  J[0] = -dot(p->a[0], p->a[0]);
  J[1] = -dot(p->a[0], p->a[1]) + dot(d, b);
  J[2] = -dot(p->a[1], p->a[1]);
  return !(dot(m, m) > 1e-24 * J[0] * J[2]);
}

/* on failure: keep the last iterate's geometry, zero the rest */
static int Fail(NTSProjection *p, int code)
{
  p->inside = 0;
  p->g      = 0;
  memset(p->n, 0, sizeof p->n);
  memset(p->dxi, 0, sizeof p->dxi);
  memset(p->dg, 0, sizeof p->dg);
  memset(p->dn, 0, sizeof p->dn);
  return code;
}

int NTSProject(int nen, const double xs[3], const double xm[][3], const double xi0[2], double tol, int derivs, NTSProjection *p)
{
  double b[3] = {0, 0, 0}, m[3], r[2], J[3], Ji[3], d[3], det = 0, prev = HUGE_VAL;
  int    conv = 0;

  memset(p, 0, sizeof *p);
  if (nen != 3 && nen != 4) return -1;
  p->nen   = nen;
  p->ncomp = 3 + 3 * nen;
  p->xi[0] = xi0 ? xi0[0] : (nen == 3 ? 1.0 / 3 : 0);
  p->xi[1] = xi0 ? xi0[1] : (nen == 3 ? 1.0 / 3 : 0);
  if (nen == 4)
    for (int i = 0; i < 3; i++)
      for (int k = 0; k < 4; k++) b[i] += XA[k] * EA[k] * xm[k][i] / 4;

  /* Newton on r = 0, i.e. on the stationarity of f = |x_s - x|^2/2 (gradient -r, Hessian -J):
     dxi = -J^{-1} r where -J is positive definite; elsewhere (a node far on the concave side of a
     warped face, where plain Newton may cycle) the Gauss-Newton step dxi = G^{-1} r with the metric
     G = a_alpha.a_beta. Both descend f: the step h is cut to length 1 and halved (not below 1e-8)
     until f decreases, the change computed without cancellation from the exact expansion of the
     bilinear map, x(xi + h) = x + dx, dx = a_1 h_1 + a_2 h_2 + b h_1 h_2:
     df = -d.dx + |dx|^2/2 = -h.r - h_1 h_2 d.b + |dx|^2/2. Converged when |dxi| < 1e-13, or when
     the steps stop shrinking below 1e-10 (the round-off floor of a node far off the face). */
  for (int it = 0;; it++) {
    if (System(xs, xm, b, p, m, d, r, J)) return Fail(p, 1);
    det = J[0] * J[2] - J[1] * J[1];
    if (conv) break; /* the geometry is now evaluated at the converged xi */
    if (it == NTS_MAXIT) return Fail(p, 2);
    double dxi[2];
    if (det > 1e-12 * (J[0] * J[0] + J[2] * J[2] + 2 * J[1] * J[1])) {
      dxi[0] = -(J[2] * r[0] - J[1] * r[1]) / det;
      dxi[1] = -(J[0] * r[1] - J[1] * r[0]) / det;
    } else {
      const double g01 = dot(p->a[0], p->a[1]), dG = J[0] * J[2] - g01 * g01; /* det G = |m|^2 > 0 */
      dxi[0]           = (-J[2] * r[0] - g01 * r[1]) / dG;
      dxi[1]           = (-J[0] * r[1] - g01 * r[0]) / dG;
    }
    double       s = sqrt(dxi[0] * dxi[0] + dxi[1] * dxi[1]), c = s > 1 ? 1 / s : 1;
    const double db = dot(d, b);
    if (!(s < HUGE_VAL)) return Fail(p, 2);
    for (; c * s >= 1e-8; c /= 2) {
      const double h0 = c * dxi[0], h1 = c * dxi[1];
      double       dx[3];
      for (int i = 0; i < 3; i++) dx[i] = p->a[0][i] * h0 + p->a[1][i] * h1 + b[i] * h0 * h1;
      if (-h0 * r[0] - h1 * r[1] - h0 * h1 * db + dot(dx, dx) / 2 <= 0) break;
    }
    p->xi[0] += c * dxi[0];
    p->xi[1] += c * dxi[1];
    s *= c;
    conv = s < 1e-13 || (s < 1e-10 && s >= prev);
    prev = s;
  }
  /* dr/dxi at the solution, for the implicit function theorem */
  if (!(fabs(det) > 1e-12 * (J[0] * J[0] + J[2] * J[2] + 2 * J[1] * J[1]))) return Fail(p, 1);
  Ji[0] = J[2] / det;
  Ji[1] = -J[1] / det;
  Ji[2] = J[0] / det;

  const double mm = sqrt(dot(m, m));
  for (int i = 0; i < 3; i++) p->n[i] = m[i] / mm;
  p->g = dot(d, p->n);
  if (nen == 4)
    p->inside = fabs(p->xi[0]) <= 1 + tol && fabs(p->xi[1]) <= 1 + tol;
  else
    p->inside = p->xi[0] >= -tol && p->xi[1] >= -tol && p->xi[0] + p->xi[1] <= 1 + tol;
  if (!derivs) return 0;

  const int nc = p->ncomp;
  for (int c = 0; c < nc; c++) {
    const int k = c / 3 - 1, j = c % 3; /* node k (-1: the slave), component j */
    double    dr[2], da[2][3], dm[3], t[3];
    /* dr_alpha/dX: a_alpha^T for x_s; -N_a a_alpha^T + N_a,alpha (x_s - x)^T for x_a */
    for (int al = 0; al < 2; al++) dr[al] = k < 0 ? p->a[al][j] : -p->N[k] * p->a[al][j] + p->dN[k][al] * d[j];
    /* implicit function theorem on r(xi, X) = 0 */
    const double x0 = -(Ji[0] * dr[0] + Ji[1] * dr[1]), x1 = -(Ji[1] * dr[0] + Ji[2] * dr[1]);
    p->dxi[c]      = x0;
    p->dxi[nc + c] = x1;
    /* dg = (dx_s - sum N_a dx_a - a_beta dxi_beta).n + (x_s - x).dn: a_beta.n = 0, and at the
       projection x_s - x = g n (r = 0 makes it orthogonal to both tangents) with n.dn = 0 (|n| = 1),
       so the variations of xi and n drop out */
    p->dg[c] = k < 0 ? p->n[j] : -p->N[k] * p->n[j];
    /* da_alpha = sum N_a,alpha dx_a + a_{alpha,beta} dxi_beta (only the mixed a_{1,2} = b);
       dm = da_1 x a_2 + a_1 x da_2, dn = (I - n n^T) dm / |m| */
    for (int i = 0; i < 3; i++) {
      da[0][i] = b[i] * x1 + (k >= 0 && i == j ? p->dN[k][0] : 0);
      da[1][i] = b[i] * x0 + (k >= 0 && i == j ? p->dN[k][1] : 0);
    }
    cross(da[0], p->a[1], dm);
    cross(p->a[0], da[1], t);
    for (int i = 0; i < 3; i++) dm[i] += t[i];
    const double nd = dot(p->n, dm);
    for (int i = 0; i < 3; i++) p->dn[i * nc + c] = (dm[i] - p->n[i] * nd) / mm;
  }
  return 0;
}

void NTSSlip(const NTSProjection *p, const double xs[3], const double xs0[3], const double xm[][3], const double xm0[][3], double ds[3], double *dds)
{
  const int nen = p->nen, nc = p->ncomp;
  for (int i = 0; i < 3; i++) {
    ds[i] = xs[i] - xs0[i];
    for (int k = 0; k < nen; k++) ds[i] -= p->N[k] * (xm[k][i] - xm0[k][i]);
  }
  if (!dds) return;
  /* d(ds) = dx_s - sum N_a dx_a - sum (x_a - x_a0) N_a,beta dxi_beta */
  for (int i = 0; i < 3; i++)
    for (int c = 0; c < nc; c++) {
      const int k = c / 3 - 1;
      double    v = c % 3 != i ? 0 : k < 0 ? 1 : -p->N[k];
      for (int a = 0; a < nen; a++) v -= (xm[a][i] - xm0[a][i]) * (p->dN[a][0] * p->dxi[c] + p->dN[a][1] * p->dxi[nc + c]);
      dds[i * nc + c] = v;
    }
}

void NTSChord(const NTSProjection *p, const double xm[][3], double t[3])
{
  const double xi[2] = {p->xi[0] + 0.01, p->xi[1]};
  double       N[4], dN[4][2], x[3], a[2][3];
  Shape(p->nen, xm, xi, N, dN, x, a);
  for (int i = 0; i < 3; i++) t[i] = x[i] - p->x[i];
}

/* s(xi) = sum_a N_a nbar_a, n = s/|s|, and n_,alpha = (I - n n^T) s_,alpha / |s|; returns 1 if |s| ~ 0 */
static int NormalField(int nen, const double nb[][3], const double N[4], const double dN[4][2], double n[3], double dn[2][3])
{
  double s[3] = {0, 0, 0}, ds[2][3] = {{0, 0, 0}, {0, 0, 0}}, ns;
  for (int k = 0; k < nen; k++)
    for (int i = 0; i < 3; i++) {
      s[i] += N[k] * nb[k][i];
      ds[0][i] += dN[k][0] * nb[k][i];
      ds[1][i] += dN[k][1] * nb[k][i];
    }
  ns = sqrt(dot(s, s));
  if (!(ns > 1e-12)) return 1;
  for (int i = 0; i < 3; i++) n[i] = s[i] / ns;
  for (int al = 0; al < 2; al++) {
    const double c = dot(n, ds[al]);
    for (int i = 0; i < 3; i++) dn[al][i] = (ds[al][i] - c * n[i]) / ns;
  }
  return 0;
}

/* 3x3 inverse (row-major); returns 1 when singular relative to the entries' scale */
static int Inverse3(const double A[9], double B[9])
{
  const double det = A[0] * (A[4] * A[8] - A[5] * A[7]) - A[1] * (A[3] * A[8] - A[5] * A[6]) + A[2] * (A[3] * A[7] - A[4] * A[6]);
  double       sc  = 0;
  for (int k = 0; k < 9; k++) sc = fmax(sc, fabs(A[k]));
  if (!(fabs(det) > 1e-14 * sc * sc * sc)) return 1;
  B[0] = (A[4] * A[8] - A[5] * A[7]) / det;
  B[1] = (A[2] * A[7] - A[1] * A[8]) / det;
  B[2] = (A[1] * A[5] - A[2] * A[4]) / det;
  B[3] = (A[5] * A[6] - A[3] * A[8]) / det;
  B[4] = (A[0] * A[8] - A[2] * A[6]) / det;
  B[5] = (A[2] * A[3] - A[0] * A[5]) / det;
  B[6] = (A[3] * A[7] - A[4] * A[6]) / det;
  B[7] = (A[1] * A[6] - A[0] * A[7]) / det;
  B[8] = (A[0] * A[4] - A[1] * A[3]) / det;
  return 0;
}

/* Projection along the interpolated normal field: F(xi, g) = x_s - x(xi) - g n(xi) = 0, three
   equations in (xi_1, xi_2, g), Newton with dF/d(xi_beta, g) = [-a_beta - g n_,beta | -n]. The
   corner normals nbar are data (fixed: the derivatives below hold them constant), so
   dF/dx_s = I, dF/dx_a = -N_a I, and by the implicit function theorem
   d(xi, g)/dX = -A^-1 [I, -N_1 I, ..., -N_nen I],  A = dF/d(xi, g);
   dn/dX = n_,beta dxi_beta/dX. The map is continuous across faces that share an edge and its
   corner normals: a node does not jump where two faces meet at an angle. */
int NTSProjectNormal(int nen, const double xs[3], const double xm[][3], const double nbar[][3], const double xi0[2], double tol, int derivs, NTSProjection *p)
{
  double n[3], dn[2][3], d[3], A[9], Ai[9], size = 0;

  if (nen != 3 && nen != 4) return -1;
  memset(p, 0, sizeof(*p));
  p->nen   = nen;
  p->ncomp = 3 + 3 * nen;
  if (xi0) {
    p->xi[0] = xi0[0];
    p->xi[1] = xi0[1];
  } else p->xi[0] = p->xi[1] = nen == 3 ? 1.0 / 3 : 0;
  for (int k = 1; k < nen; k++) {
    double e[3];
    for (int i = 0; i < 3; i++) e[i] = xm[k][i] - xm[0][i];
    size = fmax(size, sqrt(dot(e, e)));
  }
  Shape(nen, xm, p->xi, p->N, p->dN, p->x, p->a);
  if (NormalField(nen, nbar, p->N, p->dN, n, dn)) return Fail(p, 1);
  for (int i = 0; i < 3; i++) d[i] = xs[i] - p->x[i];
  p->g = dot(d, n); /* the start of g: the distance along the start's normal */
  for (int it = 0;; it++) {
    double F[3], step[3], st = 0;
    for (int i = 0; i < 3; i++) F[i] = xs[i] - p->x[i] - p->g * n[i];
    for (int i = 0; i < 3; i++) {
      A[3 * i]     = -p->a[0][i] - p->g * dn[0][i];
      A[3 * i + 1] = -p->a[1][i] - p->g * dn[1][i];
      A[3 * i + 2] = -n[i];
    }
    if (Inverse3(A, Ai)) return Fail(p, 1);
    for (int i = 0; i < 3; i++) step[i] = -(Ai[3 * i] * F[0] + Ai[3 * i + 1] * F[1] + Ai[3 * i + 2] * F[2]);
    {
      const double l = sqrt(step[0] * step[0] + step[1] * step[1]);
      const double c = l > 1 ? 1 / l : 1; /* at most 1 in the parameters */
      for (int i = 0; i < 3; i++) step[i] *= c;
      st = l * c;
    }
    p->xi[0] += step[0];
    p->xi[1] += step[1];
    p->g += step[2];
    Shape(nen, xm, p->xi, p->N, p->dN, p->x, p->a);
    if (NormalField(nen, nbar, p->N, p->dN, n, dn)) return Fail(p, 1);
    if (st < 1e-13 && fabs(step[2]) <= 1e-13 * (size + fabs(p->g))) break;
    if (it >= NTS_MAXIT) return Fail(p, 2);
  }
  for (int i = 0; i < 3; i++) {
    p->n[i] = n[i];
    A[3 * i]     = -p->a[0][i] - p->g * dn[0][i];
    A[3 * i + 1] = -p->a[1][i] - p->g * dn[1][i];
    A[3 * i + 2] = -n[i];
  }
  if (Inverse3(A, Ai)) return Fail(p, 1);
  if (nen == 3) p->inside = p->xi[0] >= -tol && p->xi[1] >= -tol && p->xi[0] + p->xi[1] <= 1 + tol;
  else p->inside = fabs(p->xi[0]) <= 1 + tol && fabs(p->xi[1]) <= 1 + tol;
  if (!derivs) return 0;
  /* d(xi, g)/dX = -Ai dF/dX: column block of node k is -Ai c_k with c_0 = 1, c_a = -N_a */
  for (int k = 0; k <= nen; k++) {
    const double c = k == 0 ? 1.0 : -p->N[k - 1];
    for (int j = 0; j < 3; j++) {
      const int col = 3 * k + j;
      p->dxi[col]                = -c * Ai[j];
      p->dxi[p->ncomp + col]     = -c * Ai[3 + j];
      p->dg[col]                 = -c * Ai[6 + j];
      for (int i = 0; i < 3; i++) p->dn[p->ncomp * i + col] = dn[0][i] * p->dxi[col] + dn[1][i] * p->dxi[p->ncomp + col];
    }
  }
  return 0;
}
