/* Unit tests of the 3x3 tensor utilities, the finite-strain J2 material kernel, and the
   Material object of type j2: its options, their validation, and its kernel table; materials
   under options prefixes of their own (MaterialSetOptionsPrefix, the bodies' materials) side by
   side with the default one, j2 and UMATs (bin/umat_j2.so, bin/umat_ctest.so). */
#include <math.h>
#include <stdio.h>
#include <string.h>
#include <time.h>

#include <petscsys.h>
#include "material_impl.h" /* MaterialOptionsTitle */
#include "material_j2.h"
#include "options.h"
#include "tensor.h"
#include "testutil.h"
#include "testmat.h"

static const double PI = 3.14159265358979323846;

/* ---------- small helpers ---------- */

static void random_rotation(unsigned long long *s, double R[9])
{
  const double a[3] = {urand(s), urand(s), urand(s) + 0.1};
  rotation(a, 3.0 * urand(s), R);
}

/* R diag(d) R^T */
static void rot_diag(const double R[9], const double d[3], double A[9])
{
  for (int i = 0; i < 3; i++)
    for (int j = 0; j < 3; j++) A[3 * i + j] = R[3 * i] * d[0] * R[3 * j] + R[3 * i + 1] * d[1] * R[3 * j + 1] + R[3 * i + 2] * d[2] * R[3 * j + 2];
}

/* eigen-decomposition errors: |A - Q diag Q^T| / |A| and |Q^T Q - I| */
static void eig_errors(const double A[9], double *rec, double *orth)
{
  double lam[3], Q[9], B[9], QtQ[9];
  const double Id[9] = {1, 0, 0, 0, 1, 0, 0, 0, 1};
  t3_sym_eig(A, lam, Q);
  rot_diag(Q, lam, B);
  t3_tmul(Q, Q, QtQ);
  const double nA = fnorm(A, 9);
  *rec  = fdiff(A, B, 9) / (nA > 0 ? nA : 1.0);
  *orth = fdiff(QtQ, Id, 9);
}

static void sort3(double v[3])
{
  for (int i = 0; i < 2; i++)
    for (int j = 0; j < 2 - i; j++)
      if (v[j] > v[j + 1]) {
        const double t = v[j];
        v[j]           = v[j + 1];
        v[j + 1]       = t;
      }
}

static double von_mises(const double tau[9])
{
  const double p = (tau[0] + tau[4] + tau[8]) / 3.0;
  double       s[9];
  for (int i = 0; i < 9; i++) s[i] = tau[i];
  s[0] -= p;
  s[4] -= p;
  s[8] -= p;
  return sqrt(1.5) * fnorm(s, 9);
}

static J2Params swift_params(void)
{
  J2Params mp;
  memset(&mp, 0, sizeof mp);
  mp.E = 69004.0;
  mp.nu = 0.3;
  mp.law = HARDENING_SWIFT;
  mp.swK = 589.0;
  mp.sweps0 = 1e-4;
  mp.swn = 0.216;
  J2ParamsSetup(&mp);
  return mp;
}

static J2Params linear_params(double sy0, double H)
{
  J2Params mp;
  memset(&mp, 0, sizeof mp);
  mp.E = 69004.0;
  mp.nu = 0.3;
  mp.law = HARDENING_LINEAR;
  mp.sy0 = sy0;
  mp.H = H;
  J2ParamsSetup(&mp);
  return mp;
}

/* relative Frobenius error of the analytic tangent against central differences */
static double tangent_fd_error(const J2Params *mp, const double F[9], const double hn[J2_NHIST], int *plastic)
{
  double tau[9], dtau[81], fd[81], h[J2_NHIST], tp[9], tm[9];
  int    pl;
  J2Update(mp, F, hn, tau, dtau, h, plastic);
  const double step = 1e-7 * fnorm(F, 9) / sqrt(3.0);
  for (int c = 0; c < 9; c++) {
    double Fp[9], Fm[9];
    memcpy(Fp, F, sizeof Fp);
    memcpy(Fm, F, sizeof Fm);
    Fp[c] += step;
    Fm[c] -= step;
    J2Update(mp, Fp, hn, tp, NULL, h, &pl);
    J2Update(mp, Fm, hn, tm, NULL, h, &pl);
    for (int r = 0; r < 9; r++) fd[9 * r + c] = (tp[r] - tm[r]) / (2.0 * step);
  }
  return fdiff(dtau, fd, 81) / fnorm(fd, 81);
}

/* closed-form uniaxial Kirchhoff stress: s = sigma_y(eps - s/E) (bisection) */
static double uniaxial_exact(const J2Params *mp, double eps)
{
  double lo = 0.0, hi = J2YieldStress(mp, eps, NULL);
  for (int it = 0; it < 200; it++) {
    const double s = 0.5 * (lo + hi);
    if (s - J2YieldStress(mp, eps - s / mp->E, NULL) > 0.0) hi = s;
    else lo = s;
  }
  return 0.5 * (lo + hi);
}

/* ---------- tests ---------- */

static void test_eig(void)
{
  unsigned long long seed = 12345;
  double             rmax = 0.0, omax = 0.0, rec, orth;
  for (int t = 0; t < 10000; t++) {
    double A[9];
    for (int i = 0; i < 3; i++)
      for (int j = i; j < 3; j++) A[3 * i + j] = A[3 * j + i] = urand(&seed) * pow(10.0, 3.0 * urand(&seed));
    eig_errors(A, &rec, &orth);
    rmax = fmax(rmax, rec);
    omax = fmax(omax, orth);
  }
  TU_CHECK(rmax < 1e-13 && omax < 1e-13, "t3_sym_eig random symmetric (10000): max reconstruction %.2e, max |Q^T Q - I| %.2e", rmax, omax);

  /* repeated eigenvalues: rotated diag(2,2,5), diag(3,3,3), diag(-1,4,4), near-repeated */
  const double D[5][3] = {{2, 2, 5}, {3, 3, 3}, {-1, 4, 4}, {1, 1 + 1e-12, 4}, {0, 0, 1}};
  double       lerr = 0.0;
  rmax = omax = 0.0;
  for (int c = 0; c < 5; c++)
    for (int t = 0; t < 200; t++) {
      double R[9], A[9], lam[3], Q[9], d[3] = {D[c][0], D[c][1], D[c][2]};
      random_rotation(&seed, R);
      rot_diag(R, d, A);
      eig_errors(A, &rec, &orth);
      rmax = fmax(rmax, rec);
      omax = fmax(omax, orth);
      t3_sym_eig(A, lam, Q);
      sort3(lam);
      sort3(d);
      for (int a = 0; a < 3; a++) lerr = fmax(lerr, fabs(lam[a] - d[a]) / 5.0);
    }
  TU_CHECK(rmax < 1e-13 && omax < 1e-13 && lerr < 1e-14,
           "t3_sym_eig repeated eigenvalues (rotated diag(2,2,5), (3,3,3), ...): reconstruction %.2e, orthogonality %.2e, eigenvalue error %.2e",
           rmax, omax, lerr);

  /* t3_inv / products */
  double A[9], Ai[9], P[9], P2[9], At[9];
  const double Id[9] = {1, 0, 0, 0, 1, 0, 0, 0, 1};
  for (int i = 0; i < 9; i++) A[i] = urand(&seed) + (i % 4 == 0 ? 2.0 : 0.0);
  const double det = t3_inv(A, Ai);
  t3_mul(A, Ai, P);
  const double e1 = fdiff(P, Id, 9);
  t3_transpose(A, At);
  t3_tmul(At, Ai, P);  /* A Ai */
  t3_mult(Ai, At, P2); /* Ai A  */
  const double e2 = fdiff(P, Id, 9) + fdiff(P2, Id, 9);
  TU_CHECK(e1 < 1e-14 && e2 < 1e-14 && fabs(det - t3_det(A)) < 1e-14 * fabs(det),
           "t3_inv/t3_mul/t3_tmul/t3_mult/t3_transpose: |A A^-1 - I| = %.2e, %.2e", e1, e2);
}

static void test_setup(void)
{
  J2Params mp = swift_params();
  TU_CHECK(fabs(mp.K - 69004.0 / 1.2) < 1e-9 && fabs(mp.G - 69004.0 / 2.6) < 1e-9 && mp.rtol == 1e-12 && mp.maxit == 50,
           "J2ParamsSetup: K = %.6f, G = %.6f, rtol = %g, maxit = %d", mp.K, mp.G, mp.rtol, mp.maxit);
  J2Params bad = mp;
  int            r1, r2, r3;
  bad.nu = 0.5;
  r1 = J2ParamsSetup(&bad);
  bad.nu = -1.0;
  r2 = J2ParamsSetup(&bad);
  bad.nu = 0.3;
  bad.E = 0.0;
  r3 = J2ParamsSetup(&bad);
  TU_CHECK(r1 && r2 && r3, "J2ParamsSetup rejects nu = 0.5 (%d), nu = -1 (%d), E = 0 (%d)", r1, r2, r3);

  /* yield stress and slope */
  J2Params lin = linear_params(250.0, 1000.0);
  double         d1, d2, e = 0.03, h = 1e-6;
  const double   s1 = J2YieldStress(&mp, e, &d1);
  const double   fd1 = (J2YieldStress(&mp, e + h, NULL) - J2YieldStress(&mp, e - h, NULL)) / (2 * h);
  const double   s2 = J2YieldStress(&lin, e, &d2);
  TU_CHECK(fabs(s1 - 589.0 * pow(1e-4 + e, 0.216)) < 1e-12 * s1 && fabs(d1 - fd1) < 1e-7 * d1 && s2 == 280.0 && d2 == 1000.0,
           "J2YieldStress: Swift sy(0.03) = %.6f, slope %.6f (FD %.6f); linear sy = %g, slope %g", s1, d1, fd1, s2, d2);
}

static void test_elastic(void)
{
  J2Params     mp = swift_params();
  unsigned long long seed = 777;
  double             hn[J2_NHIST], h[J2_NHIST], tau[9], F[9], H[9];
  int                pl, rc;
  J2HistoryInit(hn);

  /* small strain: tau ~ K tr(eps) I + 2G dev(eps), eps = sym(F - I) */
  for (int i = 0; i < 9; i++) H[i] = urand(&seed);
  for (int i = 0; i < 9; i++) F[i] = (i % 4 == 0 ? 1.0 : 0.0) + 1e-6 * H[i];
  rc = J2Update(&mp, F, hn, tau, NULL, h, &pl);
  double eps[9], lin[9];
  for (int i = 0; i < 3; i++)
    for (int j = 0; j < 3; j++) eps[3 * i + j] = 0.5e-6 * (H[3 * i + j] + H[3 * j + i]);
  const double tr = eps[0] + eps[4] + eps[8];
  for (int i = 0; i < 9; i++) lin[i] = 2.0 * mp.G * eps[i] + (i % 4 == 0 ? (mp.K - 2.0 * mp.G / 3.0) * tr : 0.0);
  const double esmall = fdiff(tau, lin, 9) / fnorm(lin, 9);
  TU_CHECK(rc == MAT_OK && !pl && esmall < 1e-5 && fdiff(h, hn, J2_NHIST) == 0.0,
           "elastic small strain F = I + 1e-6 H: |tau - tau_lin|/|tau_lin| = %.2e (O(1e-6) expected), history unchanged", esmall);

  /* pure rotations of the undeformed state: zero stress */
  const double z[3] = {0, 0, 1}, ob[3] = {1, -2, 0.7};
  double       R[9], Rz[9], Rob[9];
  rotation(z, 0.5 * PI, Rz);
  rotation(ob, 0.5 * PI, Rob);
  rc = J2Update(&mp, Rz, hn, tau, NULL, h, &pl);
  const double t1 = fnorm(tau, 9) / mp.E;
  int          rc2 = J2Update(&mp, Rob, hn, tau, NULL, h, &pl);
  const double t2 = fnorm(tau, 9) / mp.E;
  TU_CHECK(rc == MAT_OK && rc2 == MAT_OK && t1 < 1e-9 && t2 < 1e-9,
           "pure rotation 90 deg (z, oblique axis) of the undeformed state: |tau|/E = %.2e, %.2e", t1, t2);

  /* superposed 90-degree rotation of a pre-stretched state: tau(R F0) = R tau(F0) R^T, same history.
     Elastic pre-stretch, and a plastic one with a committed history Cp^{-1} != I, ep > 0. */
  const double F0[9] = {1.0008, 0.0003, -0.0002, 0.0001, 0.9996, 0.0004, -0.0003, 0.0002, 1.0002};
  const double F1[9] = {1.08, 0.03, -0.02, 0.01, 0.96, 0.04, -0.03, 0.02, 1.01};
  const double F2[9] = {1.12, 0.05, -0.01, 0.02, 0.93, 0.07, -0.05, 0.03, 1.04};
  double       hc[J2_NHIST];
  J2Update(&mp, F1, hn, tau, NULL, hc, &pl); /* committed plastic history */
  const double *Fs[2] = {F0, F2};
  const double *Hs[2] = {hn, hc};
  const char   *name[2] = {"elastic", "plastic, Cp^-1 != I"};
  for (int c = 0; c < 2; c++) {
    double tau0[9], h0[J2_NHIST], maxe = 0.0, maxh = 0.0;
    int    pl0;
    J2Update(&mp, Fs[c], Hs[c], tau0, NULL, h0, &pl0);
    for (int r = 0; r < 2; r++) {
      double RF[9], Rt[9], T[9], h1[J2_NHIST];
      memcpy(R, r == 0 ? Rz : Rob, sizeof R);
      t3_mul(R, Fs[c], RF);
      J2Update(&mp, RF, Hs[c], tau, NULL, h1, &pl);
      t3_mul(R, tau0, T);
      t3_mult(T, R, Rt);
      maxe = fmax(maxe, fdiff(tau, Rt, 9) / fnorm(tau0, 9));
      maxh = fmax(maxh, fdiff(h1, h0, J2_NHIST));
      if (pl != pl0) maxe = 1.0;
    }
    TU_CHECK(maxe < 1e-10 && maxh < 1e-12 && pl0 == c,
             "objectivity (%s, plastic=%d): 90 deg about z and oblique axis: |tau(RF) - R tau R^T|/|tau| = %.2e, |h(RF) - h(F)| = %.2e",
             name[c], pl0, maxe, maxh);
  }
}

static void test_uniaxial(void)
{
  J2Params mp = swift_params();
  double         hn[J2_NHIST], h[J2_NHIST], tau[9], dtau[81];
  const int      ninc = 200;
  double         lat = 1.0, maxerr = 0.0, maxlat = 0.0, maxres = 0.0, maxsym = 0.0, sig_end = 0.0;
  int            nplastic = 0, fail = 0, maxnewt = 0;
  J2HistoryInit(hn);
  for (int inc = 1; inc <= ninc; inc++) {
    const double eps = 0.5 * inc / ninc, lam = exp(eps);
    int          pl = 0, it;
    /* Newton on the lateral stretch: tau_22(lat) = 0 */
    for (it = 0; it < 30; it++) {
      const double F[9] = {lam, 0, 0, 0, lat, 0, 0, 0, lat};
      if (J2Update(&mp, F, hn, tau, dtau, h, &pl) != MAT_OK) { fail = 1; break; }
      if (fabs(tau[4]) <= 1e-11 * fabs(tau[0])) break;
      lat -= tau[4] / (dtau[4 * 9 + 4] + dtau[4 * 9 + 8]);
    }
    if (it > maxnewt) maxnewt = it;
    if (fail) break;
    maxres = fmax(maxres, fabs(tau[4]) / fabs(tau[0]));
    maxsym = fmax(maxsym, fabs(tau[8] - tau[4]) / fabs(tau[0]) + (fabs(tau[1]) + fabs(tau[2]) + fabs(tau[5])) / fabs(tau[0]));
    memcpy(hn, h, sizeof h);
    if (!pl) continue;
    nplastic++;
    const double J = lam * lat * lat, sig = tau[0] / J;
    const double s = uniaxial_exact(&mp, eps), Jex = exp((1.0 - 2.0 * mp.nu) * s / mp.E);
    const double ep = eps - s / mp.E, latex = exp(-mp.nu * s / mp.E - 0.5 * ep);
    maxerr = fmax(maxerr, fabs(sig - s / Jex) / (s / Jex));
    maxlat = fmax(maxlat, fabs(lat - latex) / latex);
    sig_end = sig;
  }
  TU_CHECK(!fail && nplastic == ninc && maxres < 1e-11,
           "uniaxial Swift: %d/%d plastic increments, lateral Newton <= %d iterations, max |tau_22/tau_11| = %.2e",
           nplastic, ninc, maxnewt, maxres);
  TU_CHECK(!fail && maxerr < 5e-3 && maxerr < 1e-9,
           "uniaxial Swift to 50%% log strain: max rel. error of sigma_11 vs closed form = %.2e (sigma_11 at end %.4f)",
           maxerr, sig_end);
  TU_CHECK(!fail && maxlat < 1e-9 && maxsym < 1e-12,
           "uniaxial Swift: lateral stretch vs exp(-nu s/E - ep/2): max rel. error %.2e; tau_33 = tau_22, no shear: %.2e",
           maxlat, maxsym);
}

static void test_tangent(void)
{
  J2Params     sw = swift_params(), lin = linear_params(200.0, 2000.0), stiff = linear_params(1e9, 0.0);
  unsigned long long seed = 4242;
  double             hn[J2_NHIST], hc[J2_NHIST], tau[9], err;
  int                pl, pl1;
  J2HistoryInit(hn);

  /* elastic, small strain (Swift) */
  double F[9];
  for (int i = 0; i < 9; i++) F[i] = (i % 4 == 0 ? 1.0 : 0.0) + 4e-4 * urand(&seed);
  err = tangent_fd_error(&sw, F, hn, &pl);
  TU_CHECK(!pl && err < 1e-6, "tangent vs FD, elastic small strain: rel. error %.2e", err);

  /* elastic, finite strain (very high yield stress) */
  for (int i = 0; i < 9; i++) F[i] = (i % 4 == 0 ? 1.0 : 0.0) + 0.3 * urand(&seed);
  err = tangent_fd_error(&stiff, F, hn, &pl);
  TU_CHECK(!pl && err < 1e-6, "tangent vs FD, elastic finite strain (det F = %.3f): rel. error %.2e", t3_det(F), err);

  /* plastic, general non-symmetric F, committed history with Cp^{-1} != I and ep > 0 */
  const double F1[9] = {1.06, 0.04, -0.03, 0.02, 0.97, 0.05, -0.04, 0.01, 0.99};
  const double F2[9] = {1.10, 0.09, -0.02, 0.05, 0.94, 0.08, -0.06, 0.04, 1.01};
  const J2Params *mps[2] = {&lin, &sw};
  const char           *nm[2] = {"linear hardening", "Swift"};
  for (int c = 0; c < 2; c++) {
    J2Update(mps[c], F1, hn, tau, NULL, hc, &pl1);
    const double cpdev = fabs(hc[0] - 1) + fabs(hc[1] - 1) + fabs(hc[2] - 1) + fabs(hc[3]) + fabs(hc[4]) + fabs(hc[5]);
    err = tangent_fd_error(mps[c], F2, hc, &pl);
    TU_CHECK(pl1 && pl && cpdev > 1e-2 && hc[J2_HIST_EP] > 0 && err < 1e-6,
             "tangent vs FD, plastic (%s), general F, committed ep = %.4f, sum|Cp^-1 - I| = %.3f: rel. error %.2e", nm[c],
             hc[J2_HIST_EP], cpdev, err);
  }

  /* two equal trial eigenvalues: F = R diag(l1, l2, l2), elastic and plastic; F = I (triple) */
  double R[9], Fd[9];
  random_rotation(&seed, R);
  const double Dp[9] = {1.1, 0, 0, 0, 0.96, 0, 0, 0, 0.96};
  const double De[9] = {1.0005, 0, 0, 0, 0.99975, 0, 0, 0, 0.99975};
  t3_mul(R, Dp, Fd);
  err = tangent_fd_error(&sw, Fd, hn, &pl);
  TU_CHECK(pl && err < 1e-6, "tangent vs FD, plastic (Swift), two equal trial eigenvalues F = R diag(1.1,0.96,0.96): rel. error %.2e", err);
  {
    double FdR[9];
    t3_mul(R, Dp, FdR);
    t3_mult(FdR, R, Fd); /* symmetric R D R^T */
    err = tangent_fd_error(&lin, Fd, hn, &pl);
    TU_CHECK(pl && err < 1e-6, "tangent vs FD, plastic (linear), two equal eigenvalues F = R D R^T: rel. error %.2e", err);
  }
  t3_mul(R, De, Fd);
  err = tangent_fd_error(&sw, Fd, hn, &pl);
  TU_CHECK(!pl && err < 1e-6, "tangent vs FD, elastic, two equal trial eigenvalues: rel. error %.2e", err);
  const double Id[9] = {1, 0, 0, 0, 1, 0, 0, 0, 1};
  err = tangent_fd_error(&sw, Id, hn, &pl);
  /* at F = I the exact tangent is the linear elastic one: dtau_ij/dF_kL = lambda d_ij d_kL + G (d_ik d_jL + d_iL d_jk) */
  double dtau[81], h[J2_NHIST], C[81], lam = sw.K - 2.0 * sw.G / 3.0;
  J2Update(&sw, Id, hn, tau, dtau, h, &pl);
  for (int i = 0; i < 3; i++)
    for (int j = 0; j < 3; j++)
      for (int k = 0; k < 3; k++)
        for (int L = 0; L < 3; L++)
          C[(3 * i + j) * 9 + 3 * k + L] = lam * (i == j) * (k == L) + sw.G * ((i == k) * (j == L) + (i == L) * (j == k));
  const double eI = fdiff(dtau, C, 81) / fnorm(C, 81);
  TU_CHECK(!pl && err < 1e-6 && eI < 1e-14, "tangent at F = I (triple eigenvalue): vs FD %.2e, vs isotropic elasticity tensor %.2e", err, eI);
}

static void test_failures(void)
{
  J2Params mp = swift_params();
  double         hn[J2_NHIST], h[J2_NHIST], tau[9], dtau[81];
  int            pl, rc;
  J2HistoryInit(hn);
  const double Fbig[9] = {1.3, 0.02, 0, 0, 0.88, 0, 0.01, 0, 0.87};

  J2Params m1 = mp;
  m1.maxit = 1;
  rc = J2Update(&m1, Fbig, hn, tau, dtau, h, &pl);
  TU_CHECK(rc == MAT_ERR_RETURNMAP && fdiff(h, hn, J2_NHIST) == 0.0,
           "maxit = 1, large plastic step (Swift): status %d (MAT_ERR_RETURNMAP = %d), history left at hn", rc, MAT_ERR_RETURNMAP);
  J2Params l1 = linear_params(200.0, 1500.0);
  l1.maxit = 1;
  rc = J2Update(&l1, Fbig, hn, tau, NULL, h, &pl);
  TU_CHECK(rc == MAT_OK && pl, "maxit = 1, linear hardening: one Newton step is exact, status %d", rc);

  const double Fneg[9] = {-1, 0, 0, 0, 1, 0, 0, 0, 1}, Fzero[9] = {1, 0, 0, 1, 0, 0, 0, 0, 1};
  const int    rneg = J2Update(&mp, Fneg, hn, tau, dtau, h, &pl);
  const int    rzero = J2Update(&mp, Fzero, hn, tau, dtau, h, &pl);
  TU_CHECK(rneg == MAT_ERR_JACOBIAN && rzero == MAT_ERR_JACOBIAN, "det F < 0: status %d, det F = 0: status %d (MAT_ERR_JACOBIAN = %d)",
           rneg, rzero, MAT_ERR_JACOBIAN);

  /* safeguard: Swift with a tiny (1e-12) and zero eps0 (infinite slope at ep = 0) still converges,
     and the result is on the yield surface q(tau) = sigma_y(ep) */
  const double e0s[3] = {1e-4, 1e-12, 0.0};
  for (int c = 0; c < 3; c++) {
    J2Params m = mp;
    m.sweps0 = e0s[c];
    double       F[9];
    const double Fsmall[9] = {1.004, 0, 0, 0, 0.999, 0, 0, 0, 0.999};
    double       worst = 0.0;
    int          allok = 1;
    for (int s = 0; s < 2; s++) {
      memcpy(F, s == 0 ? Fbig : Fsmall, sizeof F);
      rc = J2Update(&m, F, hn, tau, dtau, h, &pl);
      if (rc != MAT_OK || !pl) allok = 0;
      const double sy = J2YieldStress(&m, h[J2_HIST_EP], NULL);
      worst = fmax(worst, fabs(von_mises(tau) - sy) / sy);
    }
    TU_CHECK(allok && worst < 1e-11, "Swift eps0 = %g: return map converges for large and small steps, |q - sigma_y|/sigma_y = %.2e",
             e0s[c], worst);
  }
}

static void timing(void)
{
  J2Params mp = swift_params();
  double         hn[J2_NHIST], hc[J2_NHIST], h[J2_NHIST], tau[9], dtau[81], acc = 0.0;
  int            pl;
  J2HistoryInit(hn);
  const double F1[9] = {1.06, 0.04, -0.03, 0.02, 0.97, 0.05, -0.04, 0.01, 0.99};
  double       F2[9] = {1.10, 0.09, -0.02, 0.05, 0.94, 0.08, -0.06, 0.04, 1.01};
  J2Update(&mp, F1, hn, tau, NULL, hc, &pl);
  const int       N = 400000;
  struct timespec t0, t1;
  for (int pass = 0; pass < 2; pass++) {
    timespec_get(&t0, TIME_UTC);
    for (int i = 0; i < N; i++) {
      F2[0] = 1.10 + 1e-9 * (i & 7);
      J2Update(&mp, F2, hc, tau, pass ? NULL : dtau, h, &pl);
      acc += tau[0] + (pass ? 0.0 : dtau[40]);
    }
    timespec_get(&t1, TIME_UTC);
    const double ns = ((t1.tv_sec - t0.tv_sec) * 1e9 + (t1.tv_nsec - t0.tv_nsec)) / N;
    printf("# timing: J2Update plastic (Swift) %s tangent: %.0f ns/call (plastic=%d, checksum %.3e)\n", pass ? "without" : "with",
           ns, pl, acc);
  }
}

/* ---------- the Material object ---------- */
static int same_params(const J2Params *a, const J2Params *b)
{
  return a->E == b->E && a->nu == b->nu && a->K == b->K && a->G == b->G && a->law == b->law && a->swK == b->swK && a->sweps0 == b->sweps0 && a->swn == b->swn &&
         a->rtol == b->rtol && a->maxit == b->maxit && (a->law == HARDENING_SWIFT || (a->sy0 == b->sy0 && a->H == b->H));
}

static PetscErrorCode test_object(void)
{
  Material              mat;
  PetscErrorCode        ierr;
  const MaterialKernel *mk;

  PetscFunctionBeginUser;
  /* defaults: j2 with the Swift law of swift_params(); the kernel table gives J2Update's results bit for bit */
  PetscCall(MaterialFromOptions("", &mat, &ierr));
  TU_CHECK(!ierr, "Material from no options (status %d) [%s]", (int)ierr, ErrMsg);
  if (ierr) PetscFunctionReturn(0);
  PetscCall(MaterialGetKernel(mat, &mk));
  {
    const J2Params sw = swift_params();
    double         hn[J2_NHIST], hi[J2_NHIST], hc[J2_NHIST], h1[J2_NHIST], h2[J2_NHIST], t1[9], t2[9], d1[81], d2[81];
    int            p1, p2, r1, r2;
    const double   F1[9] = {1.06, 0.04, -0.03, 0.02, 0.97, 0.05, -0.04, 0.01, 0.99};
    const double   F2[9] = {1.10, 0.09, -0.02, 0.05, 0.94, 0.08, -0.06, 0.04, 1.01};
    J2HistoryInit(hn);
    mk->history_init(mk->ctx, hi);
    J2Update(&sw, F1, hn, t1, NULL, hc, &p1);
    r1 = J2Update(&sw, F2, hc, t1, d1, h1, &p1);
    r2 = mk->update(mk->ctx, F2, hc, t2, d2, h2, &p2);
    TU_CHECK(mk->nhist == J2_NHIST && same_params((const J2Params *)mk->ctx, &sw) && !memcmp(hi, hn, sizeof hn),
             "default -material_type j2: nhist %d, parameters = the Swift defaults (E %g, nu %g, K %g, n %g, rtol %g, maxit %d)", mk->nhist, ((const J2Params *)mk->ctx)->E,
             ((const J2Params *)mk->ctx)->nu, ((const J2Params *)mk->ctx)->swK, ((const J2Params *)mk->ctx)->swn, ((const J2Params *)mk->ctx)->rtol, ((const J2Params *)mk->ctx)->maxit);
    TU_CHECK(r1 == r2 && p1 == p2 && p1 && !memcmp(t1, t2, sizeof t1) && !memcmp(d1, d2, sizeof d1) && !memcmp(h1, h2, sizeof h1) && mk->plastic_strain(mk->ctx, h2) == h2[J2_HIST_EP],
             "MaterialKernel.update of j2 = J2Update bit for bit (tau, dtau, h, plastic), plastic_strain = h[J2_HIST_EP] = %.4f", h2[J2_HIST_EP]);
  }
  PetscCall(MaterialDestroy(&mat));

  /* every option read, under its name */
  PetscCall(MaterialFromOptions("-material_type j2 -material_E 70000 -material_nu 0.25 -material_hardening linear -material_yield 250 -material_hardening_modulus 1000 -material_return_rtol 1e-10 -material_return_maxit 7", &mat, &ierr));
  if (!ierr) {
    J2Params ex = linear_params(250.0, 1000.0);
    ex.E        = 70000;
    ex.nu       = 0.25;
    ex.rtol     = 1e-10;
    ex.maxit    = 7;
    ex.swK      = 589.0; /* the Swift defaults stay */
    ex.sweps0   = 1e-4;
    ex.swn      = 0.216;
    J2ParamsSetup(&ex);
    PetscCall(MaterialGetKernel(mat, &mk));
    TU_CHECK(same_params((const J2Params *)mk->ctx, &ex), "-material_E, _nu, _hardening linear, _yield, _hardening_modulus, _return_rtol, _return_maxit read");
    PetscCall(MaterialDestroy(&mat));
  } else TU_CHECK(0, "linear-hardening options: error %d [%s]", (int)ierr, ErrMsg);
  PetscCall(MaterialFromOptions("-material_swift_K 600 -material_swift_eps0 0.002 -material_swift_n 0.3", &mat, &ierr));
  if (!ierr) {
    const J2Params *mp = NULL;
    PetscCall(MaterialGetKernel(mat, &mk));
    mp = (const J2Params *)mk->ctx;
    TU_CHECK(mp->law == HARDENING_SWIFT && mp->swK == 600 && mp->sweps0 == 0.002 && mp->swn == 0.3, "-material_swift_K, _eps0, _n read");
    PetscCall(MaterialDestroy(&mat));
  } else TU_CHECK(0, "Swift options: error %d [%s]", (int)ierr, ErrMsg);
  {
    const char *closest = AtritoOptionsClosest("-material_swift_k");
    TU_CHECK(closest && !strcmp(closest, "-material_swift_K"), "options recorded with their prefix: closest to -material_swift_k is %s", closest ? closest : "(none)");
  }

  /* validation: the messages of the case module, and unknown types */
  {
    const char *bad[][2] = {
      {"-material_nu 0.5",                                          "-material_nu 0.5 must lie in (-1, 0.5)"       },
      {"-material_E -1",                                            "-material_E -1. must be positive"              },
      {"-material_swift_n 1.5",                                     "-material_swift_n 1.5 must lie in [0, 1)"      },
      {"-material_swift_K 0",                                       "-material_swift_K 0. must be positive"         },
      {"-material_swift_eps0 -1",                                   "-material_swift_eps0 -1. must be positive"     },
      {"-material_hardening linear -material_yield -5",             "-material_yield -5. must be positive"          },
      {"-material_hardening linear -material_hardening_modulus -1", "-material_hardening_modulus -1. must be >= 0"  },
      {"-material_return_rtol 2",                                   "-material_return_rtol 2. must lie in (0, 1)"   },
      {"-material_return_maxit 0",                                  "-material_return_maxit 0 must be >= 1"         },
      {"-material_type hill48_nosuch",                              "-material_type hill48_nosuch: unknown material"},
    };
    for (size_t i = 0; i < sizeof(bad) / sizeof(bad[0]); i++) {
      PetscCall(MaterialFromOptions(bad[i][0], &mat, &ierr));
      TU_CHECK(ierr == PETSC_ERR_USER_INPUT && !mat && strstr(ErrMsg, bad[i][1]), "%s: refused with '%s' [%s]", bad[i][0], bad[i][1], ErrMsg);
    }
  }
  PetscFunctionReturn(0);
}

/* ---------- materials under options prefixes of their own ---------- */
/* a Material with the options prefix prefix from the options opts; on error (*ierr != 0, message
   in ErrMsg) *mat is NULL */
static PetscErrorCode PrefixedFromOptions(const char *prefix, const char *opts, Material *mat, PetscErrorCode *ierr)
{
  PetscFunctionBeginUser;
  ErrMsg[0] = '\0';
  PetscCall(PetscOptionsClear(NULL));
  PetscCall(PetscOptionsInsertString(NULL, opts));
  PetscCall(MaterialCreate(PETSC_COMM_WORLD, mat));
  PetscCall(MaterialSetOptionsPrefix(*mat, prefix));
  PetscCall(PetscPushErrorHandler(CaptureHandler, NULL));
  *ierr = MaterialSetFromOptions(*mat);
  PetscCall(PetscPopErrorHandler());
  PetscCall(PetscOptionsClear(NULL));
  if (*ierr) PetscCall(MaterialDestroy(mat));
  PetscFunctionReturn(0);
}

static PetscErrorCode test_prefix(void)
{
  Material              a = NULL, b = NULL, mat = NULL;
  const MaterialKernel *ka, *kb;
  const char           *pa = NULL, *ta = NULL, *tb = NULL;
  PetscErrorCode        ierr;
  PetscReal             Ea = 0, Eb = 0;

  PetscFunctionBeginUser;
  /* the API: default prefix, set, get, NULL restores it, invalid prefixes refused */
  PetscCall(MaterialCreate(PETSC_COMM_WORLD, &a));
  PetscCall(MaterialGetOptionsPrefix(a, &pa));
  TU_CHECK(pa && !strcmp(pa, "material_"), "MaterialCreate: options prefix '%s' (material_)", pa ? pa : "(null)");
  PetscCall(MaterialSetOptionsPrefix(a, "body_x_material_"));
  PetscCall(MaterialGetOptionsPrefix(a, &pa));
  TU_CHECK(!strcmp(pa, "body_x_material_"), "MaterialSetOptionsPrefix / MaterialGetOptionsPrefix: '%s'", pa);
  PetscCall(MaterialSetOptionsPrefix(a, NULL));
  PetscCall(MaterialGetOptionsPrefix(a, &pa));
  TU_CHECK(!strcmp(pa, "material_"), "MaterialSetOptionsPrefix(NULL) restores material_: '%s'", pa);
  {
    const char    *badp[3] = {"", "-body_x_material_", "body x_"};
    PetscErrorCode e[3];
    PetscCall(PetscPushErrorHandler(PetscReturnErrorHandler, NULL));
    for (int i = 0; i < 3; i++) e[i] = MaterialSetOptionsPrefix(a, badp[i]);
    PetscCall(PetscPopErrorHandler());
    PetscCall(MaterialGetOptionsPrefix(a, &pa));
    TU_CHECK(e[0] && e[1] && e[2] && !strcmp(pa, "material_"), "MaterialSetOptionsPrefix refuses an empty prefix (%d), a leading '-' (%d), white space (%d), keeping '%s'", (int)e[0], (int)e[1], (int)e[2], pa);
  }
  {
    char t1[512], t2[512];
    PetscCall(MaterialOptionsTitle(a, "j2", "what", t1, sizeof t1));
    PetscCall(MaterialSetOptionsPrefix(a, "body_x_material_"));
    PetscCall(MaterialOptionsTitle(a, "j2", "what", t2, sizeof t2));
    TU_CHECK(!strcmp(t1, "Material j2: what") && !strcmp(t2, "Material j2 (-body_x_material_): what"), "-help group titles: '%s' under material_, '%s' under body_x_material_", t1, t2);
  }
  PetscCall(MaterialDestroy(&a));

  /* two materials, each reading its own options: the default one and one of body x */
  PetscCall(PetscOptionsClear(NULL));
  PetscCall(PetscOptionsSetValue(NULL, "-material_E", "70000"));
  PetscCall(PetscOptionsSetValue(NULL, "-body_x_material_E", "1234"));
  PetscCall(PetscOptionsSetValue(NULL, "-body_x_material_nu", "0.25"));
  PetscCall(PetscOptionsSetValue(NULL, "-body_x_material_hardening", "linear"));
  PetscCall(PetscOptionsSetValue(NULL, "-body_x_material_yield", "12"));
  PetscCall(MaterialCreate(PETSC_COMM_WORLD, &a));
  PetscCall(MaterialCreate(PETSC_COMM_WORLD, &b));
  PetscCall(MaterialSetOptionsPrefix(b, "body_x_material_"));
  ErrMsg[0] = '\0';
  PetscCall(PetscPushErrorHandler(CaptureHandler, NULL));
  ierr = MaterialSetFromOptions(a);
  if (!ierr) ierr = MaterialSetFromOptions(b);
  PetscCall(PetscPopErrorHandler());
  PetscCall(PetscOptionsClear(NULL));
  TU_CHECK(!ierr, "a default material and one under body_x_material_ set from the same options (status %d) [%s]", (int)ierr, ErrMsg);
  if (!ierr) {
    J2Params ea = swift_params(), eb = linear_params(12.0, 0.0);
    ea.E  = 70000;
    eb.E  = 1234;
    eb.nu = 0.25;
    eb.swK = 589.0, eb.sweps0 = 1e-4, eb.swn = 0.216; /* the Swift defaults stay */
    J2ParamsSetup(&ea);
    J2ParamsSetup(&eb);
    PetscCall(MaterialGetKernel(a, &ka));
    PetscCall(MaterialGetKernel(b, &kb));
    PetscCall(MaterialGetYoungModulus(a, &Ea));
    PetscCall(MaterialGetYoungModulus(b, &Eb));
    TU_CHECK(same_params((const J2Params *)ka->ctx, &ea) && Ea == 70000, "the default material keeps its own options: -material_E %g, nu %g, Swift (Young's modulus %g)", ((const J2Params *)ka->ctx)->E, ((const J2Params *)ka->ctx)->nu, Ea);
    TU_CHECK(same_params((const J2Params *)kb->ctx, &eb) && Eb == 1234, "the material under body_x_material_ reads -body_x_material_E %g, _nu %g, _hardening linear, _yield %g (Young's modulus %g)", ((const J2Params *)kb->ctx)->E,
             ((const J2Params *)kb->ctx)->nu, ((const J2Params *)kb->ctx)->sy0, Eb);
    {
      const double F[9] = {1.004, 0.001, 0, 0.002, 0.998, 0, 0, 0, 0.999};
      double       hn[J2_NHIST], h1[J2_NHIST], h2[J2_NHIST], ta1[9], ta2[9], tb1[9], tb2[9];
      int          pl1, pl2;
      J2HistoryInit(hn);
      ka->update(ka->ctx, F, hn, ta1, NULL, h1, &pl1);
      kb->update(kb->ctx, F, hn, tb1, NULL, h2, &pl2);
      J2Update(&ea, F, hn, ta2, NULL, h1, &pl1);
      J2Update(&eb, F, hn, tb2, NULL, h2, &pl2);
      TU_CHECK(!memcmp(ta1, ta2, sizeof ta1) && !memcmp(tb1, tb2, sizeof tb1) && fabs(ta1[0] - tb1[0]) > 1, "each kernel evaluates its own parameters (tau_xx %g and %g)", ta1[0], tb1[0]);
    }
  }
  PetscCall(MaterialDestroy(&a));
  PetscCall(MaterialDestroy(&b));

  /* the type under the prefix: body x hill48, the default material j2 */
  PetscCall(PetscOptionsClear(NULL));
  PetscCall(PetscOptionsSetValue(NULL, "-body_x_material_type", "hill48"));
  PetscCall(PetscOptionsSetValue(NULL, "-body_x_material_hill_r0", "1.6"));
  PetscCall(MaterialCreate(PETSC_COMM_WORLD, &a));
  PetscCall(MaterialCreate(PETSC_COMM_WORLD, &b));
  PetscCall(MaterialSetOptionsPrefix(b, "body_x_material_"));
  PetscCall(PetscPushErrorHandler(CaptureHandler, NULL));
  ierr = MaterialSetFromOptions(a);
  if (!ierr) ierr = MaterialSetFromOptions(b);
  PetscCall(PetscPopErrorHandler());
  PetscCall(PetscOptionsClear(NULL));
  if (!ierr) {
    PetscCall(MaterialGetType(a, &ta));
    PetscCall(MaterialGetType(b, &tb));
  }
  TU_CHECK(!ierr && !strcmp(ta, "j2") && !strcmp(tb, "hill48"), "-body_x_material_type hill48: types %s (default) and %s (body x) [%s]", ta ? ta : "-", tb ? tb : "-", ierr ? ErrMsg : "");
  PetscCall(MaterialDestroy(&a));
  PetscCall(MaterialDestroy(&b));

  /* UMATs beside each other and beside j2: the default material the Fortran J2 UMAT, body x the C
     hypoelastic UMAT (another library, other PROPS and NSTATV), body y the built-in j2; evaluated
     in turns, each gives what it gives alone */
  {
    Material              c = NULL;
    const MaterialKernel *kc;
    PetscCall(PetscOptionsClear(NULL));
    PetscCall(PetscOptionsInsertString(NULL, "-material_type umat -material_umat bin/umat_j2.so -material_umat_props 69004,0.3,589,1e-4,0.216 -material_umat_nstatev 1 -material_umat_statev_ep 1 "
                                             "-body_x_material_type umat -body_x_material_umat bin/umat_ctest.so -body_x_material_umat_symbol umat_hypo_ -body_x_material_umat_props 1000,0.3 "
                                             "-body_y_material_type j2"));
    PetscCall(MaterialCreate(PETSC_COMM_WORLD, &a));
    PetscCall(MaterialCreate(PETSC_COMM_WORLD, &b));
    PetscCall(MaterialCreate(PETSC_COMM_WORLD, &c));
    PetscCall(MaterialSetOptionsPrefix(b, "body_x_material_"));
    PetscCall(MaterialSetOptionsPrefix(c, "body_y_material_"));
    ErrMsg[0] = '\0';
    PetscCall(PetscPushErrorHandler(CaptureHandler, NULL));
    ierr = MaterialSetFromOptions(a);
    if (!ierr) ierr = MaterialSetFromOptions(b);
    if (!ierr) ierr = MaterialSetFromOptions(c);
    PetscCall(PetscPopErrorHandler());
    PetscCall(PetscOptionsClear(NULL));
    TU_CHECK(!ierr, "two UMATs (bin/umat_j2.so as material_, bin/umat_ctest.so umat_hypo_ as body_x_material_) and j2 (body_y_material_) set up (status %d) [%s]", (int)ierr, ErrMsg);
    if (!ierr) {
      const double F1[9] = {1.0005, 0, 0, 0, 0.99975, 0, 0, 0, 0.99975}, F2[9] = {1.006, 0, 0, 0, 0.997, 0, 0, 0, 0.997};
      double       ha0[32], hb0[32], hc0[J2_NHIST], ha1[32], hb1[32], hc1[J2_NHIST], hx[32], ta1[9], tb1[9], tc1[9], ta2[9], tb2[9], tc2[9], tx[9], hooke[9] = {0};
      int          sa[4], sb[4], sc[4], pl;
      PetscCall(MaterialGetKernel(a, &ka));
      PetscCall(MaterialGetKernel(b, &kb));
      PetscCall(MaterialGetKernel(c, &kc));
      ka->history_init(ka->ctx, ha0);
      kb->history_init(kb->ctx, hb0);
      kc->history_init(kc->ctx, hc0);
      /* in turns: a, b, c at F1, then again from their new histories at F2 */
      sa[0] = ka->update(ka->ctx, F1, ha0, ta1, NULL, ha1, &pl);
      sb[0] = kb->update(kb->ctx, F1, hb0, tb1, NULL, hb1, &pl);
      sc[0] = kc->update(kc->ctx, F1, hc0, tc1, NULL, hc1, &pl);
      sa[1] = ka->update(ka->ctx, F2, ha1, ta2, NULL, hx, &pl);
      sb[1] = kb->update(kb->ctx, F2, hb1, tb2, NULL, hx, &pl);
      sc[1] = kc->update(kc->ctx, F2, hc1, tc2, NULL, hx, &pl);
      /* a alone (after b's calls): the same bits */
      sa[2] = ka->update(ka->ctx, F1, ha0, tx, NULL, hx, &pl);
      const int same_a = !memcmp(tx, ta1, sizeof tx);
      sb[2] = kb->update(kb->ctx, F1, hb0, tx, NULL, hx, &pl);
      const int same_b = !memcmp(tx, tb1, sizeof tx);
      sa[3] = sb[3] = sc[2] = sc[3] = MAT_OK;
      /* one step from the virgin state of the hypoelastic UMAT: Hencky, tau = lambda tr(e) 1 + 2 mu e, e = ln V */
      {
        const double E = 1000, nu = 0.3, lam = E * nu / ((1 + nu) * (1 - 2 * nu)), mu = E / (2 * (1 + nu));
        const double e[3] = {log(F1[0]), log(F1[4]), log(F1[8])}, tr = e[0] + e[1] + e[2];
        for (int i = 0; i < 3; i++) hooke[4 * i] = lam * tr + 2 * mu * e[i];
      }
      const double eb = fdiff(tb1, hooke, 9) / fnorm(hooke, 9), ea1 = fdiff(ta1, tc1, 9) / fnorm(tc1, 9), ea2 = fdiff(ta2, tc2, 9) / fnorm(tc2, 9);
      int          allok = 1;
      for (int i = 0; i < 4; i++) allok = allok && sa[i] == MAT_OK && sb[i] == MAT_OK && sc[i] == MAT_OK;
      TU_CHECK(allok && same_a && same_b, "UMATs of two materials in turns: each one's tau is the same, bit for bit, before and after the other's calls");
      TU_CHECK(allok && eb < 1e-12 && ea1 < 1e-9 && ea2 < 1e-9 && ka->nhist == 22 && kb->nhist == 21,
               "UMAT beside UMAT beside j2: body x's hypoelastic UMAT (E 1000) = Hencky to %.1e, the default's Fortran J2 UMAT = body y's built-in j2 to %.1e, %.1e (elastic, plastic step); nhist %d, %d", eb, ea1, ea2, ka->nhist, kb->nhist);
    }
    PetscCall(MaterialDestroy(&a));
    PetscCall(MaterialDestroy(&b));
    PetscCall(MaterialDestroy(&c));
  }

  /* validation under the prefix: the messages name the prefixed options; the default material
     reads none of them, the prefixed one none of the default's */
  {
    const char *bad[][2] = {
      {"-body_x_material_nu 0.5",                                             "-body_x_material_nu 0.5 must lie in (-1, 0.5)"                                   },
      {"-body_x_material_E -1",                                               "-body_x_material_E -1. must be positive"                                          },
      {"-body_x_material_hardening linear -body_x_material_yield -5",         "-body_x_material_yield -5. must be positive"                                      },
      {"-body_x_material_return_maxit 0",                                     "-body_x_material_return_maxit 0 must be >= 1"                                     },
      {"-body_x_material_type nosuch",                                        "-body_x_material_type nosuch: unknown material"                                   },
      {"-body_x_material_type hill48 -body_x_material_hill_r0 -1",            "-body_x_material_hill_r0 -1. must be positive"                                    },
      {"-body_x_material_type hill48 -body_x_material_hill_r0 2 -body_x_material_hill_F 1", "-body_x_material_hill_r0/r45/r90 and -body_x_material_hill_F/G/H/L/M/N exclude each other"},
      {"-body_x_material_type yld91 -body_x_material_yld91_exponent 3",       "-body_x_material_yld91_exponent 3 must be an even integer in [2, 32]"             },
      {"-body_x_material_type umat",                                          "-body_x_material_type umat needs -body_x_material_umat PATH"                      },
      {"-body_x_material_type umat -body_x_material_umat bin/no_such_umat.so", "-body_x_material_umat bin/no_such_umat.so: cannot load the library"              },
    };
    for (size_t i = 0; i < sizeof(bad) / sizeof(bad[0]); i++) {
      PetscCall(PrefixedFromOptions("body_x_material_", bad[i][0], &mat, &ierr));
      TU_CHECK(ierr == PETSC_ERR_USER_INPUT && !mat && strstr(ErrMsg, bad[i][1]), "under body_x_material_, %s: refused with '%s' [%s]", bad[i][0], bad[i][1], ErrMsg);
      PetscCall(MaterialFromOptions(bad[i][0], &mat, &ierr));
      TU_CHECK(!ierr && mat, "the default material ignores %s (status %d) [%s]", bad[i][0], (int)ierr, ErrMsg);
      PetscCall(MaterialDestroy(&mat));
    }
    PetscCall(PrefixedFromOptions("body_x_material_", "-material_nu 0.5 -material_type nosuch", &mat, &ierr));
    TU_CHECK(!ierr && mat, "the material under body_x_material_ ignores -material_nu 0.5 -material_type nosuch (status %d) [%s]", (int)ierr, ErrMsg);
    PetscCall(MaterialDestroy(&mat));
  }
  PetscFunctionReturn(0);
}

int main(int argc, char **argv)
{
  PetscCall(PetscInitialize(&argc, &argv, NULL, NULL));
  test_eig();
  test_setup();
  test_elastic();
  test_uniaxial();
  test_tangent();
  test_failures();
  PetscCall(test_object());
  PetscCall(test_prefix());
  timing();
  PetscCall(PetscFinalize());
  TU_RETURN();
}
