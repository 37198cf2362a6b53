/* Contact kernels on plain arrays: the local frame (eqs 28-30), the friction return map and
   its consistent tangent (eqs 14-23), and the nodal contribution (eq 25) with its exact
   derivative, curvature of the tool and rotation of the frame included. */
#include <math.h>
#include <string.h>
#include "contact_law.h"

static void cross(const double a[3], const double b[3], double c[3])
{
  c[0] = a[1] * b[2] - a[2] * b[1];
  c[1] = a[2] * b[0] - a[0] * b[2];
  c[2] = a[0] * b[1] - a[1] * b[0];
}

/* S = [a]x, so that [a]x b = a x b */
static void skew(const double a[3], double S[9])
{
  S[0] = 0;
  S[1] = -a[2];
  S[2] = a[1];
  S[3] = a[2];
  S[4] = 0;
  S[5] = -a[0];
  S[6] = -a[1];
  S[7] = a[0];
  S[8] = 0;
}

static void mat3mul(const double A[9], const double B[9], double C[9])
{
  for (int i = 0; i < 3; i++)
    for (int j = 0; j < 3; j++) C[3 * i + j] = A[3 * i] * B[j] + A[3 * i + 1] * B[3 + j] + A[3 * i + 2] * B[6 + j];
}

int ContactFrame(const double n[3], const double s[3], double t1[3], double t2[3])
{
  double       v[3];
  const double ns = sqrt(s[0] * s[0] + s[1] * s[1] + s[2] * s[2]);
  cross(n, s, v); /* eq 28 / 30: t2 = n x t1' */
  const double nv = sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
  if (!(nv > 1e-10 * ns) || ns == 0) return 1;
  for (int i = 0; i < 3; i++) t2[i] = v[i] / nv;
  cross(t2, n, t1); /* eq 29: t1 = t2 x n */
  return 0;
}

int ContactFrameCarry(const double n0[3], const double n[3], const double s[3], double r[3])
{
  const double c = n0[0] * n[0] + n0[1] * n[1] + n0[2] * n[2];
  double       k[3], kxs[3], ks;
  if (!(n0[0] * n0[0] + n0[1] * n0[1] + n0[2] * n0[2] > 0.5) || !(c > -0.5)) { /* no n0 (zero) or a turn by more than 120 degrees: the projection */
    for (int j = 0; j < 3; j++) r[j] = s[j];
    return 1;
  }
  cross(n0, n, k);
  cross(k, s, kxs);
  ks = k[0] * s[0] + k[1] * s[1] + k[2] * s[2];
  for (int j = 0; j < 3; j++) r[j] = c * s[j] + kxs[j] + k[j] * ks / (1 + c);
  return 0;
}

int ContactReturnMap(const ContactLaw *law, const double tTn[2], const double dg[2], double tN, double tT[2], double *Y)
{
  if (law->mu == 0.0) { /* frictionless: no tangential pressure at all */
    tT[0] = tT[1] = 0;
    if (Y) memset(Y, 0, 6 * sizeof(double));
    return CONTACT_SLIP;
  }
  /* elastic predictor (eq 14) */
  const double te[2] = {tTn[0] + law->KT * dg[0], tTn[1] + law->KT * dg[1]};
  const double nrm   = sqrt(te[0] * te[0] + te[1] * te[1]);
  if (nrm - law->mu * tN <= 0.0) { /* inside the cone (eq 1): stick */
    tT[0] = te[0];
    tT[1] = te[1];
    if (Y) {
      Y[0] = law->KT;
      Y[1] = 0;
      Y[2] = 0;
      Y[3] = 0;
      Y[4] = law->KT;
      Y[5] = 0;
    }
    return CONTACT_STICK;
  }
  /* radial return (eqs 18-20): tT = beta te, beta = mu tN / |te| */
  const double beta = law->mu * tN / nrm, e[2] = {te[0] / nrm, te[1] / nrm}, ks = law->KT * beta;
  tT[0] = beta * te[0];
  tT[1] = beta * te[1];
  if (Y) { /* eq 23, columns (dg_1, dg_2, penetration) */
    Y[0] = ks * (1 - e[0] * e[0]);
    Y[1] = -ks * e[0] * e[1];
    Y[2] = law->mu * law->KN * e[0];
    Y[3] = -ks * e[0] * e[1];
    Y[4] = ks * (1 - e[1] * e[1]);
    Y[5] = law->mu * law->KN * e[1];
  }
  return CONTACT_SLIP;
}

int ContactNodeEval(const ContactLaw *law, double g, const double n[3], const double *dn, const double s[3], const double tTn[2], const double ds[3], double R[3], double *K, double t1[3], double *tN, double tT[2])
{
  return ContactNodeEvalAug(law, 0.0, g, n, dn, s, tTn, ds, R, K, t1, tN, tT);
}

int ContactNodeEvalAug(const ContactLaw *law, double lN, double g, const double n[3], const double *dn, const double s[3], const double tTn[2], const double ds[3], double R[3], double *K, double t1[3], double *tN, double tT[2])
{
  double t2[3], dg[2], Y[6];
  int    status;

  memset(R, 0, 3 * sizeof(double));
  if (K) memset(K, 0, 9 * sizeof(double));
  tT[0] = tT[1] = 0;
  *tN           = 0;
  if (ContactFrame(n, s, t1, t2)) {
    /* seed parallel to the normal: any tangent will do as a new seed */
    const double a[3] = {fabs(n[0]) < 0.9 ? 1.0 : 0.0, fabs(n[0]) < 0.9 ? 0.0 : 1.0, 0.0};
    ContactFrame(n, a, t1, t2);
  }
  /* active when penetrated, or when the multiplier still holds the node (t_N = lN - K_N g > 0);
     touching (g = 0) is active, with zero force (lN = 0) and full stiffness.
     With law->delta > 0 the bracket t_N = <x>, x = lN - K_N g, is smoothed over |x| < w = K_N delta:
     t_N = (x + w)^2 / (4 w), dt_N/dx = (x + w) / (2 w) there (C1: t_N = w and slope 1 at x = w,
     0 and 0 at x = -w), so that a node resting near g = 0 does not switch between no force and
     full stiffness from one iterate to the next; the force starts at the gap delta (without
     multiplier). The tangent uses the local stiffness K_N dt_N/dx (lw below). */
  ContactLaw   lw = *law;
  const double p  = -g;
  if (law->delta > 0) {
    const double x = lN - law->KN * g, w = law->KN * law->delta;
    if (!(x > -w)) return CONTACT_OPEN;
    *tN   = x >= w ? x : (x + w) * (x + w) / (4 * w);
    lw.KN = x >= w ? law->KN : law->KN * (x + w) / (2 * w);
  } else if (law->reg > 0) {
    /* the band -a < x < b: t_N = (x + a)^2 / (2 (a + b)), dt_N/dx = (x + a)/(a + b) (C1: 0 and 0 at
       x = -a, (a + b)/2 and 1 at x = b); beyond it x - (b - a)/2. A node touching at zero force
       keeps the stiffness a/(a+b) K_N, and only nodes within a/K_N of the tool carry force at a gap */
    const double x = lN - law->KN * g, b = law->KN * law->reg, a = CONTACT_REG_GAP * b;
    if (!(x > -a)) return CONTACT_OPEN;
    *tN   = x >= b ? x - 0.5 * (b - a) : (x + a) * (x + a) / (2 * (a + b));
    lw.KN = x >= b ? law->KN : law->KN * (x + a) / (a + b);
  } else {
    if (g > 0 && !(lN - law->KN * g > 0)) return CONTACT_OPEN;
    *tN = lN > 0 ? lN + law->KN * p : law->KN * p;
  }
  law    = &lw;
  dg[0]  = t1[0] * ds[0] + t1[1] * ds[1] + t1[2] * ds[2];
  dg[1]  = t2[0] * ds[0] + t2[1] * ds[1] + t2[2] * ds[2];
  status = ContactReturnMap(law, tTn, dg, *tN, tT, K ? Y : NULL);
  for (int i = 0; i < 3; i++) R[i] = -(*tN) * n[i] + tT[0] * t1[i] + tT[1] * t2[i];
  if (!K) return status;

  /* frame derivatives with the seed fixed: v = n x s, t2 = v/|v|, t1 = t2 x n
     Dv = -[s]x Dn,  Dt2 = (I - t2 t2^T) Dv / |v|,  Dt1 = -[n]x Dt2 + [t2]x Dn */
  double Dt1[9] = {0}, Dt2[9] = {0};
  if (dn) {
    double Ss[9], Sn[9], St2[9], Dv[9], P[9], v[3], A[9], B[9];
    cross(n, s, v);
    const double nv = sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
    skew(s, Ss);
    skew(n, Sn);
    skew(t2, St2);
    mat3mul(Ss, dn, Dv);
    for (int k = 0; k < 9; k++) Dv[k] = -Dv[k];
    for (int i = 0; i < 3; i++)
      for (int j = 0; j < 3; j++) P[3 * i + j] = ((i == j) - t2[i] * t2[j]) / nv;
    mat3mul(P, Dv, Dt2);
    mat3mul(Sn, Dt2, A);
    mat3mul(St2, dn, B);
    for (int k = 0; k < 9; k++) Dt1[k] = -A[k] + B[k];
  }
  /* rows: d dg_a / dy = t_a^T + ds^T Dt_a,  d p / dy = -n^T */
  double ddg[2][3];
  for (int j = 0; j < 3; j++) {
    ddg[0][j] = t1[j] + ds[0] * Dt1[j] + ds[1] * Dt1[3 + j] + ds[2] * Dt1[6 + j];
    ddg[1][j] = t2[j] + ds[0] * Dt2[j] + ds[1] * Dt2[3 + j] + ds[2] * Dt2[6 + j];
  }
  double dtT[2][3];
  for (int a = 0; a < 2; a++)
    for (int j = 0; j < 3; j++) dtT[a][j] = Y[3 * a] * ddg[0][j] + Y[3 * a + 1] * ddg[1][j] - Y[3 * a + 2] * n[j];
  /* K = K_N n n^T - tN Dn + sum_a [ t_a (x) d tT_a + tT_a Dt_a ] */
  for (int i = 0; i < 3; i++)
    for (int j = 0; j < 3; j++) {
      double k = law->KN * n[i] * n[j] + t1[i] * dtT[0][j] + t2[i] * dtT[1][j] + tT[0] * Dt1[3 * i + j] + tT[1] * Dt2[3 * i + j];
      if (dn) k -= (*tN) * dn[3 * i + j];
      K[3 * i + j] = k;
    }
  return status;
}

void ContactQuadAreas(const double x[4][3], double a[4])
{
  static const double xa[4] = {-1, 1, 1, -1}, ea[4] = {-1, -1, 1, 1};
  const double        gq    = 0.57735026918962576451; /* 1/sqrt(3) */
  for (int i = 0; i < 4; i++) a[i] = 0;
  for (int q = 0; q < 4; q++) {
    const double xi = xa[q] * gq, eta = ea[q] * gq;
    double       dxi[3] = {0, 0, 0}, deta[3] = {0, 0, 0}, nrm[3];
    for (int i = 0; i < 4; i++)
      for (int k = 0; k < 3; k++) {
        dxi[k] += 0.25 * xa[i] * (1 + ea[i] * eta) * x[i][k];
        deta[k] += 0.25 * ea[i] * (1 + xa[i] * xi) * x[i][k];
      }
    cross(dxi, deta, nrm);
    const double J = sqrt(nrm[0] * nrm[0] + nrm[1] * nrm[1] + nrm[2] * nrm[2]);
    for (int i = 0; i < 4; i++) a[i] += 0.25 * (1 + xa[i] * xi) * (1 + ea[i] * eta) * J; /* Gauss weights 1 */
  }
}
