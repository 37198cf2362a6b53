/* Unit tests of the user-material interface (material type "umat", src/material/umat.c):
   the conversion of an Abaqus UMAT's Cauchy stress and DDSDDE to tau and d tau/dF, against
   finite differences, on a hypoelastic (Hencky-like) UMAT written here in C; the Fortran J2 UMAT
   tests/umat_j2.f (bin/umat_j2.so) against the built-in J2 on proportional paths and simple shear;
   PNEWDT and NaN statuses; the options' errors.
   `bin/test_umat -timing` also times the hex8 Jacobian with the Fortran UMAT and the built-in J2.

   Built with -DUMAT_TEST_LIBRARY (bin/umat_ctest.so, for tests/test_umat.sh) only the C UMATs
   are compiled: umat_hypo_, umat_cut_ (PNEWDT = 0.5 on its first call with a nonzero strain
   increment in a process, then as umat_hypo_) and umat_nan_ (a NaN stress for any nonzero strain
   increment; with PROPS(3:4) = NOEL, NPT only at that element and integration point) and
   umat_time_ (umat_hypo_ writing TIME, DTIME, KSTEP, KINC into STATEV(1..6)).
   PROPS of the C UMATs: E, nu. */
#define _POSIX_C_SOURCE 199309L
#include <math.h>
#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#define UMAT_ARGS                                                                                                                                                                                                                                                                                     \
  double *stress, double *statev, double *ddsdde, double *sse, double *spd, double *scd, double *rpl, double *ddsddt, double *drplde, double *drpldt, const double *stran, const double *dstran, const double *time, const double *dtime, const double *temp, const double *dtemp, const double *predef, \
    const double *dpred, const char *cmname, const int *ndi, const int *nshr, const int *ntens, const int *nstatv, const double *props, const int *nprops, const double *coords, const double *drot, double *pnewdt, const double *celent, const double *dfgrd0, const double *dfgrd1, const int *noel,  \
    const int *npt, const int *layer, const int *kspt, const int *kstep, const int *kinc, size_t cmname_len

static double det3cm(const double *A) /* column-major, as the UMAT sees it (same value) */
{
  return A[0] * (A[4] * A[8] - A[7] * A[5]) - A[3] * (A[1] * A[8] - A[7] * A[2]) + A[6] * (A[1] * A[5] - A[4] * A[2]);
}

/* hypoelastic in the Kirchhoff stress: tau = J0 sigma_in + lambda tr(de) 1 + 2 mu de, sigma = tau/J1;
   DDSDDE = (1/J1) d tau/d DSTRAN (exact). One step from the virgin state is the Hencky model. */
void umat_hypo_(UMAT_ARGS);
void umat_hypo_(UMAT_ARGS)
{
  const double E = props[0], nu = props[1], lam = E * nu / ((1 + nu) * (1 - 2 * nu)), mu = E / (2 * (1 + nu));
  const double J0 = det3cm(dfgrd0), J1 = det3cm(dfgrd1), tr = dstran[0] + dstran[1] + dstran[2];
  for (int i = 0; i < 3; i++) {
    stress[i]     = (J0 * stress[i] + lam * tr + 2 * mu * dstran[i]) / J1;
    stress[i + 3] = (J0 * stress[i + 3] + mu * dstran[i + 3]) / J1;
  }
  for (int i = 0; i < 36; i++) ddsdde[i] = 0;
  for (int i = 0; i < 3; i++) {
    for (int k = 0; k < 3; k++) ddsdde[i + 6 * k] = lam / J1;
    ddsdde[i + 6 * i] += 2 * mu / J1;
    ddsdde[(i + 3) * 7] = mu / J1;
  }
}

void umat_cut_(UMAT_ARGS);
void umat_cut_(UMAT_ARGS)
{
  static int asked = 0;
  double     ds    = 0;
  for (int i = 0; i < 6; i++) ds += fabs(dstran[i]);
  if (!asked && ds > 0) { /* the first call with a strain increment */
    asked   = 1;
    *pnewdt = 0.5;
    return;
  }
  umat_hypo_(stress, statev, ddsdde, sse, spd, scd, rpl, ddsddt, drplde, drpldt, stran, dstran, time, dtime, temp, dtemp, predef, dpred, cmname, ndi, nshr, ntens, nstatv, props, nprops, coords, drot, pnewdt, celent, dfgrd0, dfgrd1, noel, npt, layer, kspt, kstep, kinc, cmname_len);
}

void umat_nan_(UMAT_ARGS);
void umat_nan_(UMAT_ARGS)
{
  umat_hypo_(stress, statev, ddsdde, sse, spd, scd, rpl, ddsddt, drplde, drpldt, stran, dstran, time, dtime, temp, dtemp, predef, dpred, cmname, ndi, nshr, ntens, nstatv, props, nprops, coords, drot, pnewdt, celent, dfgrd0, dfgrd1, noel, npt, layer, kspt, kstep, kinc, cmname_len);
  double s = 0;
  for (int i = 0; i < 6; i++) s += fabs(dstran[i]);
  if (s > 0 && (*nprops < 4 || (*noel == (int)props[2] && *npt == (int)props[3]))) stress[0] = NAN;
}

/* umat_hypo_, recording what it was told of the increment: STATEV(1..6) = TIME(1), TIME(2),
   DTIME, KSTEP, KINC, TIME(2) + DTIME, and of the point: STATEV(7..10) = COORDS, CELENT */
void umat_time_(UMAT_ARGS);
void umat_time_(UMAT_ARGS)
{
  umat_hypo_(stress, statev, ddsdde, sse, spd, scd, rpl, ddsddt, drplde, drpldt, stran, dstran, time, dtime, temp, dtemp, predef, dpred, cmname, ndi, nshr, ntens, nstatv, props, nprops, coords, drot, pnewdt, celent, dfgrd0, dfgrd1, noel, npt, layer, kspt, kstep, kinc, cmname_len);
  if (*nstatv < 6) return;
  statev[0] = time[0];
  statev[1] = time[1];
  statev[2] = *dtime;
  statev[3] = *kstep;
  statev[4] = *kinc;
  statev[5] = time[1] + *dtime;
  if (*nstatv < 10) return;
  for (int i = 0; i < 3; i++) statev[6 + i] = coords[i];
  statev[9] = *celent;
}

#ifndef UMAT_TEST_LIBRARY
#include <petscsys.h>
#include "element_hex8.h"
#include "material_hill48.h"
#include "material_impl.h"
#include "material_j2.h"
#include "material_umat.h"
#include "tensor.h"
#include "testutil.h"
#include "testmat.h"

/* F = R (I + a Z), Z random */
static void random_F(unsigned long long *s, double a, double F[9])
{
  double R[9], U[9];
  const double ax[3] = {urand(s), urand(s), urand(s) + 0.1};
  rotation(ax, 3.0 * urand(s), R);
  for (int i = 0; i < 9; i++) U[i] = (i % 4 == 0 ? 1.0 : 0.0) + a * urand(s);
  t3_mul(R, U, F);
}

static double MaxHist[64];

/* relative Frobenius error of d tau/dF against central differences of the update */
static double fd_error(const MaterialKernel *mk, const double F[9], const double *hn, int *plastic)
{
  double tau[9], dtau[81], fd[81], tp[9], tm[9];
  int    pl;
  mk->update(mk->ctx, F, hn, tau, dtau, MaxHist, plastic);
  const double step = 1e-7;
  for (int c = 0; c < 9; c++) {
    double Fp[9], Fm[9];
    memcpy(Fp, F, sizeof Fp);
    memcpy(Fm, F, sizeof Fm);
    Fp[c] += step;
    Fm[c] -= step;
    mk->update(mk->ctx, Fp, hn, tp, NULL, MaxHist, &pl);
    mk->update(mk->ctx, Fm, hn, tm, NULL, MaxHist, &pl);
    for (int r = 0; r < 9; r++) fd[9 * r + c] = (tp[r] - tm[r]) / (2.0 * step);
  }
  return fdiff(dtau, fd, 81) / fnorm(fd, 81);
}

static UmatParams hypo_params(void)
{
  UmatParams p;
  memset(&p, 0, sizeof(p));
  p.fn       = umat_hypo_;
  p.nstatev  = 2;
  p.nprops   = 2;
  p.props[0] = 1000;
  p.props[1] = 0.3;
  memset(p.cmname, ' ', sizeof(p.cmname));
  return p;
}

/* (a) the conversion on the C hypoelastic UMAT */
static void test_conversion(void)
{
  UmatParams         p = hypo_params();
  MaterialKernel     mk;
  unsigned long long s = 7;
  double             h0[UMAT_NHIST(2)], h1[UMAT_NHIST(2)], h2[UMAT_NHIST(2)], tau[9], tauj[9];
  UmatKernelInit(&p, &mk);
  TU_CHECK(mk.nhist == 23, "umat history: nstatev + 21 = %d doubles", mk.nhist);

  /* one step from the virgin state = Hencky: tau = lambda tr(ln V) 1 + 2 mu ln V, as the elastic built-in J2 */
  J2Params jp;
  memset(&jp, 0, sizeof(jp));
  jp.E = 1000, jp.nu = 0.3, jp.law = HARDENING_LINEAR, jp.sy0 = 1e30;
  J2ParamsSetup(&jp);
  double worst = 0;
  for (int t = 0; t < 20; t++) {
    double F[9], hj[J2_NHIST], hj1[J2_NHIST];
    random_F(&s, 0.3, F);
    UmatHistoryInit(&p, h0);
    J2HistoryInit(hj);
    mk.update(mk.ctx, F, h0, tau, NULL, h1, NULL);
    J2Update(&jp, F, hj, tauj, NULL, hj1, NULL);
    const double e = fdiff(tau, tauj, 9) / fnorm(tauj, 9);
    if (e > worst) worst = e;
  }
  TU_CHECK(worst < 1e-12, "hypoelastic UMAT, one step from the virgin state = Hencky (built-in J2, elastic): largest relative difference %.2e over 20 random F (< 1e-12)", worst);

  /* tangent vs finite differences: a first increment to F0, then F = F0 + a random finite increment with rotation */
  double worst1 = 0, worst2 = 0;
  for (int t = 0; t < 20; t++) {
    double F0[9], F[9], dR[9], dU[9];
    random_F(&s, 0.2, F0);
    UmatHistoryInit(&p, h0);
    h0[0] = 0.25, h0[1] = -1.5; /* STATEV are copied through */
    if (mk.update(mk.ctx, F0, h0, tau, NULL, h1, NULL)) worst1 = 1e30;
    const double ax[3] = {urand(&s), urand(&s), urand(&s) + 0.2};
    rotation(ax, t < 10 ? 0.05 * urand(&s) : 1.2 * urand(&s), dR);
    for (int i = 0; i < 9; i++) dU[i] = (i % 4 == 0 ? 1.0 : 0.0) + 0.15 * urand(&s);
    double T[9];
    t3_mul(dR, dU, T);
    t3_mul(T, F0, F);
    const double e = fd_error(&mk, F, h1, NULL);
    if (t < 10) worst1 = fmax(worst1, e);
    else worst2 = fmax(worst2, e);
    if (t == 0) {
      mk.update(mk.ctx, F, h1, tau, NULL, h2, NULL);
      TU_CHECK(h2[0] == 0.25 && h2[1] == -1.5 && !memcmp(h2 + UMAT_HIST_F(2), F, sizeof(F)), "STATEV kept, DFGRD1 stored as the next DFGRD0");
    }
  }
  TU_CHECK(worst1 < 1e-6, "d tau/dF from DDSDDE vs central differences, hypoelastic UMAT, finite increments with small rotation: largest relative error %.2e (< 1e-6)", worst1);
  TU_CHECK(worst2 < 1e-6, "... with incremental rotations up to 69 degrees: largest relative error %.2e (< 1e-6)", worst2);

  /* rigid rotation of the increment: sigma rotates with it, STRAN too */
  {
    double F0[9], F[9], Q[9], sig0[9], sig1[9], e0[9], e1[9], r[9];
    const double ax[3] = {0.3, -0.5, 0.8};
    random_F(&s, 0.2, F0);
    UmatHistoryInit(&p, h0);
    mk.update(mk.ctx, F0, h0, tau, NULL, h1, NULL);
    rotation(ax, 1.0, Q);
    t3_mul(Q, F0, F);
    mk.update(mk.ctx, F, h1, tau, NULL, h2, NULL);
    for (int i = 0; i < 3; i++) {
      sig0[4 * i] = h1[UMAT_HIST_STRESS(2) + i], sig1[4 * i] = h2[UMAT_HIST_STRESS(2) + i];
      e0[4 * i] = h1[UMAT_HIST_STRAN(2) + i], e1[4 * i] = h2[UMAT_HIST_STRAN(2) + i];
    }
    sig0[1] = sig0[3] = h1[UMAT_HIST_STRESS(2) + 3], sig0[2] = sig0[6] = h1[UMAT_HIST_STRESS(2) + 4], sig0[5] = sig0[7] = h1[UMAT_HIST_STRESS(2) + 5];
    sig1[1] = sig1[3] = h2[UMAT_HIST_STRESS(2) + 3], sig1[2] = sig1[6] = h2[UMAT_HIST_STRESS(2) + 4], sig1[5] = sig1[7] = h2[UMAT_HIST_STRESS(2) + 5];
    e0[1] = e0[3] = 0.5 * h1[UMAT_HIST_STRAN(2) + 3], e0[2] = e0[6] = 0.5 * h1[UMAT_HIST_STRAN(2) + 4], e0[5] = e0[7] = 0.5 * h1[UMAT_HIST_STRAN(2) + 5];
    e1[1] = e1[3] = 0.5 * h2[UMAT_HIST_STRAN(2) + 3], e1[2] = e1[6] = 0.5 * h2[UMAT_HIST_STRAN(2) + 4], e1[5] = e1[7] = 0.5 * h2[UMAT_HIST_STRAN(2) + 5];
    double T[9];
    t3_mul(Q, sig0, T);
    t3_mult(T, Q, r);
    const double es = fdiff(r, sig1, 9) / fnorm(sig0, 9);
    t3_mul(Q, e0, T);
    t3_mult(T, Q, r);
    const double ee = fdiff(r, e1, 9) / fnorm(e0, 9);
    TU_CHECK(es < 1e-12 && ee < 1e-12, "rigid rotation Q of the increment: stress -> Q sigma Q^T (%.1e), STRAN -> Q STRAN Q^T (%.1e)", es, ee);
  }
}

/* PNEWDT and NaN statuses on the C UMATs */
static void test_status(void)
{
  UmatParams     p = hypo_params();
  MaterialKernel mk;
  double         h0[UMAT_NHIST(2)], h1[UMAT_NHIST(2)], tau[9], dtau[81], F[9] = {1.1, 0.1, 0, 0, 1, 0, 0, 0, 0.95};
  int            pl;
  UmatKernelInit(&p, &mk);
  UmatHistoryInit(&p, h0);
  h0[0] = 3;
  p.fn  = umat_cut_;
  for (int i = 0; i < UMAT_NHIST(2); i++) h1[i] = -7;
  int st1 = mk.update(mk.ctx, F, h0, tau, dtau, h1, &pl);
  int ok1 = fnorm(tau, 9) == 0 && fnorm(dtau, 81) == 0 && !memcmp(h0, h1, sizeof(h0));
  int st2 = mk.update(mk.ctx, F, h0, tau, dtau, h1, &pl);
  TU_CHECK(st1 == MAT_ERR_CUTBACK && UmatLastPnewdt() == 0.5 && ok1 && st2 == MAT_OK, "PNEWDT 0.5: MAT_ERR_CUTBACK (status %d, PNEWDT %g, tau = 0, h = hn), the next call MAT_OK (%d)", st1, UmatLastPnewdt(), st2);
  p.fn    = umat_nan_;
  int st3 = mk.update(mk.ctx, F, h0, tau, dtau, h1, &pl);
  TU_CHECK(st3 == MAT_ERR_NAN && fnorm(tau, 9) == 0 && !memcmp(h0, h1, sizeof(h0)), "NaN in the returned stress: MAT_ERR_NAN (status %d)", st3);
  /* NOEL and NPT reach the UMAT (umat_nan_ with PROPS(3:4) = 17, 5 fails at that point only) and
     the failing point is recorded */
  {
    int noel = -1, npt = -1, what, st5, st6, st7;
    p.nprops   = 4;
    p.props[2] = 17;
    p.props[3] = 5;
    mk.set_point(mk.ctx, 17, 4, NULL, 0);
    st5 = mk.update(mk.ctx, F, h0, tau, dtau, h1, &pl);
    mk.set_point(mk.ctx, 16, 5, NULL, 0);
    st6 = mk.update(mk.ctx, F, h0, tau, dtau, h1, &pl);
    mk.set_point(mk.ctx, 17, -1, NULL, 0); /* the element only: the point stays 5 */
    st7  = mk.update(mk.ctx, F, h0, tau, dtau, h1, &pl);
    what = UmatLastNaN(&noel, &npt);
    TU_CHECK(st5 == MAT_OK && st6 == MAT_OK && st7 == MAT_ERR_NAN && what == 1 && noel == 17 && npt == 5 && mk.failed_point(mk.ctx) == 5,
             "NOEL, NPT passed to the UMAT: a NaN at element 17, point 5 only (statuses %d %d %d), recorded as STRESS (%d) at %d, %d", st5, st6, st7, what, noel, npt);
    p.nprops = 2;
  }
  /* the increment reaches the UMAT: TIME(1), TIME(2), DTIME, KSTEP, KINC */
  {
    UmatParams     q = hypo_params();
    MaterialKernel qk;
    double         g0[UMAT_NHIST(10)], g1[UMAT_NHIST(10)];
    const double   xq[3] = {1.5, -2, 0.25};
    q.fn      = umat_time_;
    q.nstatev = 10;
    UmatKernelInit(&q, &qk);
    UmatHistoryInit(&q, g0);
    qk.set_increment(qk.ctx, 0.25, 1.25, 0.5, 2, 7);
    qk.set_point(qk.ctx, 3, 2, xq, 0.7);
    int st = qk.update(qk.ctx, F, g0, tau, NULL, g1, &pl);
    TU_CHECK(st == MAT_OK && g1[0] == 0.25 && g1[1] == 1.25 && g1[2] == 0.5 && g1[3] == 2 && g1[4] == 7 && g1[5] == 1.75,
             "set_increment: the UMAT sees TIME = (%g, %g), DTIME %g, KSTEP %g, KINC %g (given 0.25, 1.25, 0.5, 2, 7)", g1[0], g1[1], g1[2], g1[3], g1[4]);
    TU_CHECK(st == MAT_OK && g1[6] == 1.5 && g1[7] == -2 && g1[8] == 0.25 && g1[9] == 0.7, "set_point: the UMAT sees COORDS = (%g, %g, %g), CELENT %g (given 1.5, -2, 0.25, 0.7)", g1[6], g1[7], g1[8], g1[9]);
    qk.set_increment(qk.ctx, 0, 0, 1, 1, 1); /* as a driver that sets none */
    qk.set_point(qk.ctx, 1, 1, (const double[3]){0, 0, 0}, 1);
  }
  const double Fbad[9] = {1, 0, 0, 0, 1, 0, 0, 0, -0.5};
  p.fn    = umat_hypo_;
  int st4 = mk.update(mk.ctx, Fbad, h0, tau, dtau, h1, &pl);
  TU_CHECK(st4 == MAT_ERR_JACOBIAN, "det F <= 0: MAT_ERR_JACOBIAN (status %d)", st4);
}

/* ---------- the Material object with the Fortran J2 UMAT ---------- */
#define SWIFT_OPTS "-material_type umat -material_umat bin/umat_j2.so -material_umat_props 69004,0.3,589,1e-4,0.216 -material_umat_nstatev 1 -material_umat_statev_ep 1"

static J2Params swift_j2(void)
{
  J2Params jp;
  memset(&jp, 0, sizeof(jp));
  jp.E = 69004, jp.nu = 0.3, jp.law = HARDENING_SWIFT, jp.swK = 589, jp.sweps0 = 1e-4, jp.swn = 0.216;
  J2ParamsSetup(&jp);
  return jp;
}

/* follows F(t), t = 1..n, with both models; returns the largest |tau_umat - tau_j2| / max |tau_j2|
   and the final plastic strains */
static double follow_path(const MaterialKernel *mk, void (*path)(double t, double F[9]), int n, double *ep_umat, double *ep_j2, double *worst_fd, int *nplastic)
{
  const J2Params jp = swift_j2();
  double         h[UMAT_NHIST(1)], hn[UMAT_NHIST(1)], hj[J2_NHIST], hjn[J2_NHIST], tau[9], tauj[9], err = 0, scale = 0;
  mk->history_init(mk->ctx, hn);
  J2HistoryInit(hjn);
  if (worst_fd) *worst_fd = 0;
  if (nplastic) *nplastic = 0;
  for (int k = 1; k <= n; k++) {
    double F[9];
    int    pl;
    path((double)k / n, F);
    if (mk->update(mk->ctx, F, hn, tau, NULL, h, &pl) || J2Update(&jp, F, hjn, tauj, NULL, hj, NULL)) return 1e30;
    if (worst_fd && (k % 7 == 3)) {
      const double e = fd_error(mk, F, hn, &pl);
      *worst_fd      = fmax(*worst_fd, e);
      if (nplastic) *nplastic += pl;
    }
    err   = fmax(err, fdiff(tau, tauj, 9));
    scale = fmax(scale, fnorm(tauj, 9));
    memcpy(hn, h, sizeof(h));
    memcpy(hjn, hj, sizeof(hj));
  }
  *ep_umat = hn[0];
  *ep_j2   = hjn[J2_HIST_EP];
  return err / scale;
}

static double Qfix[9];
static void path_proportional(double t, double F[9]) /* fixed principal axes Qfix, stretches exp(t (0.26, -0.1, -0.12)) */
{
  const double d[3] = {exp(0.26 * t), exp(-0.1 * t), exp(-0.12 * t)};
  for (int i = 0; i < 3; i++)
    for (int j = 0; j < 3; j++) F[3 * i + j] = Qfix[3 * i] * d[0] * Qfix[3 * j] + Qfix[3 * i + 1] * d[1] * Qfix[3 * j + 1] + Qfix[3 * i + 2] * d[2] * Qfix[3 * j + 2];
}
static double Gamma = 2.0;
static void path_shear(double t, double F[9]) /* simple shear to Gamma (isochoric) */
{
  const double G[9] = {1, Gamma * t, 0, 0, 1, 0, 0, 0, 1};
  memcpy(F, G, sizeof(G));
}

static PetscErrorCode test_fortran_j2(void)
{
  Material              mat;
  PetscErrorCode        ierr;
  const MaterialKernel *mk;
  double                epu, epj, wfd;
  int                   npl;

  PetscFunctionBeginUser;
  PetscCall(MaterialFromOptions(SWIFT_OPTS, &mat, &ierr));
  TU_CHECK(!ierr, "-material_type umat with bin/umat_j2.so (Swift PROPS, NSTATV 1): loaded%s%s", ierr ? ": " : "", ErrMsg);
  if (ierr) PetscFunctionReturn(0);
  PetscCall(MaterialGetKernel(mat, &mk));
  TU_CHECK(mk->nhist == 22, "history width nstatev + 21 = %d", mk->nhist);

  /* proportional loading, fixed axes: the two formulations coincide */
  const double ax[3] = {0.4, 1.0, -0.3};
  rotation(ax, 0.7, Qfix);
  double e = follow_path(mk, path_proportional, 30, &epu, &epj, &wfd, &npl);
  TU_CHECK(e < 1e-9 && fabs(epu - epj) < 1e-9 * epj, "Fortran J2 UMAT = built-in J2 on a proportional path (rotated axes, 30 increments to ln stretch 0.26): |dtau|/|tau| %.2e (< 1e-9), ep %.6f vs %.6f", e, epu, epj);
  TU_CHECK(wfd < 1e-6 && npl > 0, "Fortran J2 UMAT: d tau/dF vs central differences along the path (%d plastic points): largest relative error %.2e (< 1e-6)", npl, wfd);

  /* non-proportional: simple shear to gamma = 2 (principal axes rotate by 32 degrees) */
  const int ns[3] = {50, 200, 800};
  double    es[3];
  for (int i = 0; i < 3; i++) es[i] = follow_path(mk, path_shear, ns[i], &epu, &epj, i == 0 ? &wfd : NULL, i == 0 ? &npl : NULL);
  TU_CHECK(es[2] < 1e-4, "simple shear to gamma 2: UMAT (additive corotational) vs built-in (exponential map), largest |dtau|/max|tau| %.2e / %.2e / %.2e with %d / %d / %d increments (< 1e-4); ep %.5f vs %.5f", es[0], es[1], es[2], ns[0], ns[1], ns[2], epu, epj);
  TU_CHECK(wfd < 1e-6 && npl > 0, "Fortran J2 UMAT in simple shear: d tau/dF vs central differences (%d plastic points, incremental rotation): largest relative error %.2e (< 1e-6)", npl, wfd);
  PetscCall(MaterialDestroy(&mat));

  /* options: errors */
  PetscCall(MaterialFromOptions("-material_type umat -material_umat bin/no_such_umat.so", &mat, &ierr));
  TU_CHECK(ierr && strstr(ErrMsg, "-material_umat bin/no_such_umat.so") && strstr(ErrMsg, "cannot open") && !strchr(ErrMsg, '\n'), "missing library: '%s'", ErrMsg);
  PetscCall(MaterialFromOptions("-material_type umat -material_umat bin/umat_j2.so -material_umat_symbol vumat_", &mat, &ierr));
  TU_CHECK(ierr && strstr(ErrMsg, "-material_umat_symbol vumat_") && strstr(ErrMsg, "undefined symbol") && !strchr(ErrMsg, '\n'), "missing symbol: '%s'", ErrMsg);
  PetscCall(MaterialFromOptions("-material_type umat", &mat, &ierr));
  TU_CHECK(ierr && strstr(ErrMsg, "-material_umat PATH"), "no library given: '%s'", ErrMsg);
  PetscCall(MaterialFromOptions("-material_type umat -material_umat bin/umat_ctest.so -material_umat_symbol umat_hypo_ -material_umat_props 1000,0.3", &mat, &ierr));
  TU_CHECK(!ierr, "the C UMAT from bin/umat_ctest.so by -material_umat_symbol%s%s", ierr ? ": " : "", ErrMsg);
  if (!ierr) PetscCall(MaterialDestroy(&mat));
  PetscFunctionReturn(0);
}

/* ---------- the Fortran Hill 48 UMAT (tests/umat_hill48.f) against the built-in hill48 ---------- */
/* PROPS: E, nu, IHARD (1 Swift), K, eps0, n, IANI (0 r-values), r0, r45, r90, -, -, -, IAX, rd, nd */
#define HILL_R "1.6,1.2,2.0"
static const double PI = 3.14159265358979323846;
static const char *hill_opts(int iax, double th_deg, char *buf, size_t n)
{
  const double th = th_deg * PI / 180.0;
  snprintf(buf, n,
           "-material_type umat -material_umat bin/umat_hill48.so -material_umat_props 69004,0.3,1,589,1e-4,0.216,0," HILL_R ",0,0,0,%d,%.17g,%.17g,0,0,0,1 -material_umat_nstatev %d -material_umat_statev_ep 1",
           iax, cos(th), sin(th), iax ? 16 : 7);
  return buf;
}

/* the built-in hill48 with the same parameters: Swift, r-values 1.6/1.2/2.0 (or r), rolling direction at th_deg in the x-y plane */
static HillParams hill_builtin(double th_deg, double r0, double r45, double r90)
{
  HillParams   hp;
  const double th = th_deg * PI / 180.0;
  memset(&hp, 0, sizeof hp);
  hp.base   = swift_j2();
  hp.from_r = 1, hp.r0 = r0, hp.r45 = r45, hp.r90 = r90;
  hp.rd[0] = cos(th), hp.rd[1] = sin(th), hp.nd[2] = 1.0;
  Hill48ParamsSetup(&hp);
  return hp;
}

/* the built-in hill48 on J2Params base, r-values, rolling direction rd and normal nd */
static HillParams hill_general(J2Params base, double r0, double r45, double r90, const double rd[3], const double nd[3])
{
  HillParams hp;
  memset(&hp, 0, sizeof hp);
  hp.base   = base;
  hp.from_r = 1, hp.r0 = r0, hp.r45 = r45, hp.r90 = r90;
  for (int i = 0; i < 3; i++) hp.rd[i] = rd[i], hp.nd[i] = nd[i];
  Hill48ParamsSetup(&hp);
  return hp;
}

/* one call of the UMAT fn (the bridge's fixed arguments) */
static void call_umat(const UmatParams *p, double stress[6], double *statev, double ddsdde[36], const double dstran[6], const double drot[9], const double f0[9], const double f1[9], double *pnewdt)
{
  double       sse = 0, spd = 0, scd = 0, rpl = 0, ddsddt[6] = {0}, drplde[6] = {0}, drpldt = 0, stran[6] = {0};
  const double time[2] = {0, 0}, dtime = 1, temp = 0, dtemp = 0, predef[1] = {0}, dpred[1] = {0}, coords[3] = {0, 0, 0}, celent = 1;
  const int    ndi = 3, nshr = 3, ntens = 6, nstatv = p->nstatev, nprops = p->nprops, one = 1;
  *pnewdt                                                                                              = 1.0;
  p->fn(stress, statev, ddsdde, &sse, &spd, &scd, &rpl, ddsddt, drplde, &drpldt, stran, dstran, time, &dtime, &temp, &dtemp, predef, dpred, p->cmname, &ndi, &nshr, &ntens, &nstatv, p->props, &nprops, coords, drot, pnewdt, &celent, f0, f1, &one, &one, &one, &one, &one, &one, sizeof(p->cmname));
}

/* DDSDDE against central differences of STRESS in DSTRAN (fixed entry STRESS, STATEV, DROT,
   DFGRD0, DFGRD1): returns the largest relative error over ntries random plastic states */
static double ddsdde_fd(const UmatParams *p, unsigned long long *s, int ntries, int *nplastic)
{
  double worst = 0;
  *nplastic    = 0;
  for (int t = 0; t < ntries; t++) {
    double F0[9], F1[9], R[9], dR[9], sig[6], de[6], sv[16] = {0}, sv1[16], st[6], C[36], fd[36], pn;
    random_F(s, 0.1, F0);
    const double ax[3] = {urand(s), urand(s), urand(s) + 0.2};
    rotation(ax, 0.3 * urand(s), dR);
    t3_mul(dR, F0, R);
    for (int i = 0; i < 9; i++) F1[i] = R[i] + 0.01 * urand(s);
    for (int i = 0; i < 6; i++) {
      sig[i] = (i < 3 ? 250.0 : 120.0) * urand(s);
      de[i]  = 0.01 * urand(s);
    }
    sv[0] = 0.05 * (1 + urand(s));
    double cm0[9], cm1[9], cmr[9]; /* column-major */
    for (int i = 0; i < 3; i++)
      for (int j = 0; j < 3; j++) cm0[i + 3 * j] = F0[3 * i + j], cm1[i + 3 * j] = F1[3 * i + j], cmr[i + 3 * j] = dR[3 * i + j];
    memcpy(st, sig, sizeof st), memcpy(sv1, sv, sizeof sv);
    call_umat(p, st, sv1, C, de, cmr, cm0, cm1, &pn);
    if (pn < 1 || !isfinite(st[0])) return 1e30;
    *nplastic += sv1[0] > sv[0];
    const double h = 1e-7;
    for (int k = 0; k < 6; k++) {
      double sp[6], sm[6], dp[6], dm[6], Cd[36];
      memcpy(dp, de, sizeof dp), memcpy(dm, de, sizeof dm);
      dp[k] += h, dm[k] -= h;
      memcpy(sp, sig, sizeof sp), memcpy(sv1, sv, sizeof sv);
      call_umat(p, sp, sv1, Cd, dp, cmr, cm0, cm1, &pn);
      memcpy(sm, sig, sizeof sm), memcpy(sv1, sv, sizeof sv);
      call_umat(p, sm, sv1, Cd, dm, cmr, cm0, cm1, &pn);
      for (int i = 0; i < 6; i++) fd[i + 6 * k] = (sp[i] - sm[i]) / (2 * h);
    }
    worst = fmax(worst, fdiff(C, fd, 36) / fnorm(fd, 36));
  }
  return worst;
}

/* follows F(t), t = 1..n, with two kernels; the largest |tau_a - tau_b| / max |tau_b|, the final
   plastic strains; d tau/dF of a against central differences every 7th increment */
static double follow2(const MaterialKernel *a, const MaterialKernel *b, void (*path)(double t, double F[9]), int n, double *ep_a, double *ep_b, double *worst_fd, int *nplastic)
{
  double *ha = malloc(sizeof(double) * 2 * a->nhist), *hb = malloc(sizeof(double) * 2 * b->nhist), tau_a[9], tau_b[9], err = 0, scale = 0;
  double *ha1 = ha + a->nhist, *hb1 = hb + b->nhist;
  a->history_init(a->ctx, ha);
  b->history_init(b->ctx, hb);
  if (worst_fd) *worst_fd = 0;
  if (nplastic) *nplastic = 0;
  for (int k = 1; k <= n; k++) {
    double F[9];
    int    pl;
    path((double)k / n, F);
    if (a->update(a->ctx, F, ha, tau_a, NULL, ha1, &pl) || b->update(b->ctx, F, hb, tau_b, NULL, hb1, NULL)) {
      free(ha), free(hb);
      return 1e30;
    }
    if (worst_fd && k % 7 == 3) {
      *worst_fd = fmax(*worst_fd, fd_error(a, F, ha, &pl));
      if (nplastic) *nplastic += pl;
    }
    err   = fmax(err, fdiff(tau_a, tau_b, 9));
    scale = fmax(scale, fnorm(tau_b, 9));
    memcpy(ha, ha1, sizeof(double) * a->nhist);
    memcpy(hb, hb1, sizeof(double) * b->nhist);
  }
  *ep_a = a->plastic_strain(a->ctx, ha);
  *ep_b = b->plastic_strain(b->ctx, hb);
  free(ha), free(hb);
  return err / scale;
}

/* y = T x T^T */
static void rot2(const double T[9], const double X[9], double Y[9])
{
  double W[9];
  t3_mul(T, X, W);
  t3_mult(W, T, Y);
}

/* uniaxial tension at angle th to x (the load frame T = [d, w, z]) to axial stretch lam_end in
   nsteps: Newton on the lateral stretches and the in-plane shear (zero lateral and shear
   Kirchhoff stresses). Returns the r-value of the last step, from the plastic strain increments
   of the UMAT's STATEV(2..7) (width over thickness), and the final axial tau; -1 on failure */
static double uniaxial_umat(const MaterialKernel *mk, double th, double lam_end, int nsteps, double *tau_dd)
{
  const double T[9] = {cos(th), -sin(th), 0, sin(th), cos(th), 0, 0, 0, 1};
  double       x[3] = {1, 1, 0}, *hn = malloc(sizeof(double) * 2 * mk->nhist), *h = hn + mk->nhist, epw = 0, epz = 0, r = -1;
  mk->history_init(mk->ctx, hn);
  for (int st = 1; st <= nsteps; st++) {
    const double lam  = 1.0 + (lam_end - 1.0) * st / nsteps;
    int          conv = 0;
    double       tl[9];
    for (int it = 0; it < 60 && !conv; it++) {
      const double Ul[9] = {lam, x[2], 0, x[2], x[0], 0, 0, 0, x[1]};
      double       Fg[9], tau[9], dtau[81], res[3], Jm[9], Ji[9], Tt[9];
      int          pl;
      rot2(T, Ul, Fg);
      if (mk->update(mk->ctx, Fg, hn, tau, dtau, h, &pl)) goto done;
      t3_transpose(T, Tt);
      rot2(Tt, tau, tl);
      res[0] = tl[4], res[1] = tl[8], res[2] = tl[1];
      if (fnorm(res, 3) < 1e-11 * fnorm(tau, 9)) {
        conv = 1;
        break;
      }
      for (int i = 0; i < 3; i++) {
        double dU[9] = {0}, dFg[9], dtg[9], dtl[9];
        if (i == 0) dU[4] = 1;
        else if (i == 1) dU[8] = 1;
        else dU[1] = dU[3] = 1;
        rot2(T, dU, dFg);
        for (int a = 0; a < 9; a++) {
          dtg[a] = 0;
          for (int c = 0; c < 9; c++) dtg[a] += dtau[9 * a + c] * dFg[c];
        }
        rot2(Tt, dtg, dtl);
        Jm[3 * 0 + i] = dtl[4], Jm[3 * 1 + i] = dtl[8], Jm[3 * 2 + i] = dtl[1];
      }
      t3_inv(Jm, Ji);
      for (int i = 0; i < 3; i++) x[i] -= Ji[3 * i] * res[0] + Ji[3 * i + 1] * res[1] + Ji[3 * i + 2] * res[2];
    }
    if (!conv) goto done;
    if (st == nsteps) { /* plastic strain increments of the last step, width w = T e_2 and thickness z */
      const double w[3] = {T[1], T[4], T[7]};
      double       E0[9], E1[9];
      for (int q = 0; q < 2; q++) {
        const double *v = (q ? h : hn) + 1;
        double       *E = q ? E1 : E0;
        E[0] = v[0], E[4] = v[1], E[8] = v[2], E[1] = E[3] = 0.5 * v[3], E[2] = E[6] = 0.5 * v[4], E[5] = E[7] = 0.5 * v[5];
      }
      for (int i = 0; i < 3; i++)
        for (int j = 0; j < 3; j++) epw += w[i] * (E1[3 * i + j] - E0[3 * i + j]) * w[j];
      epz     = E1[8] - E0[8];
      r       = epw / epz;
      *tau_dd = tl[0];
    }
    memcpy(hn, h, sizeof(double) * mk->nhist);
  }
done:
  free(hn);
  return r;
}

static PetscErrorCode test_fortran_hill(void)
{
  Material              mat, mat1, matj;
  PetscErrorCode        ierr;
  const MaterialKernel *mk, *mk1, *mkj;
  char                  buf[512];
  double                epu, epb, wfd;
  int                   npl;
  unsigned long long    s = 11;

  PetscFunctionBeginUser;
  PetscCall(MaterialFromOptions(hill_opts(0, 0, buf, sizeof buf), &mat, &ierr));
  TU_CHECK(!ierr, "-material_type umat with bin/umat_hill48.so (Swift, r 1.6/1.2/2.0, NSTATV 7): loaded%s%s", ierr ? ": " : "", ErrMsg);
  if (ierr) PetscFunctionReturn(0);
  PetscCall(MaterialGetKernel(mat, &mk));
  PetscCall(MaterialFromOptions(hill_opts(1, 0, buf, sizeof buf), &mat1, &ierr));
  TU_CHECK(!ierr, "... and with its frame rotated by the increments' DROT (IAX 1, NSTATV 16)%s%s", ierr ? ": " : "", ErrMsg);
  if (ierr) PetscFunctionReturn(0);
  PetscCall(MaterialGetKernel(mat1, &mk1));

  /* (1) DDSDDE = d STRESS / d DSTRAN at fixed J1 (= (1/J1) d tau/d DSTRAN): central differences */
  {
    const char *names[4] = {"r 1.6/1.2/2.0, Swift, IAX 0", "the same, IAX 1", "F..N given, linear hardening, oblique axes, IAX 0", "r 1/1/1 (von Mises)"};
    const char *props[4] = {NULL, NULL, "69004,0.3,0,150,800,0,1,0.3,0.7,0.5,1.2,1.9,2.4,0,1,2,0.5,-2,1,0", "69004,0.3,1,589,1e-4,0.216,0,1,1,1,0,0,0,0"};
    for (int c = 0; c < 4; c++) {
      UmatParams p = *(const UmatParams *)(c == 1 ? mk1 : mk)->ctx;
      if (props[c]) {
        double v[20];
        int    n = 0;
        for (const char *q = props[c]; *q; q++) {
          v[n++] = strtod(q, (char **)&q);
          if (!*q) break;
        }
        p.nprops = n;
        for (int i = 0; i < n; i++) p.props[i] = v[i];
      }
      const double e = ddsdde_fd(&p, &s, 20, &npl);
      TU_CHECK(e < 1e-6 && npl >= 10, "Hill UMAT DDSDDE vs central differences of STRESS in DSTRAN (%s; %d of 20 random states plastic): largest relative error %.2e (< 1e-6)", names[c], npl, e);
    }
  }

  /* (1b) one step from the virgin state: both trial states are the log strain ln V = R ln U R^T
     in the frame R A and both returns solve the same equation, so UMAT (IAX 0) = built-in for any
     F; large random F (stretches up to 30 %, any rotation), three parameter sets */
  {
    J2Params lin;
    memset(&lin, 0, sizeof lin);
    lin.E = 69004, lin.nu = 0.3, lin.law = HARDENING_LINEAR, lin.sy0 = 150, lin.H = 0;
    J2ParamsSetup(&lin);
    const double rdx[3] = {1, 0, 0}, ndz[3] = {0, 0, 1}, rdo[3] = {1, 2, 0.5}, ndo[3] = {-2, 1, 0};
    const HillParams hps[3]   = {hill_general(swift_j2(), 1.6, 1.2, 2.0, rdx, ndz), hill_general(swift_j2(), 0.3, 3.0, 0.5, rdo, ndo), hill_general(lin, 2.8, 0.4, 1.9, rdx, ndz)};
    const double     pr[3][20] = {{69004, 0.3, 1, 589, 1e-4, 0.216, 0, 1.6, 1.2, 2.0, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1},
                                  {69004, 0.3, 1, 589, 1e-4, 0.216, 0, 0.3, 3.0, 0.5, 0, 0, 0, 0, 1, 2, 0.5, -2, 1, 0},
                                  {69004, 0.3, 0, 150, 0, 0, 0, 2.8, 0.4, 1.9, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1}};
    double worst = 0;
    int    npl = 0, nfail = 0;
    for (int b = 0; b < 3; b++) {
      UmatParams     p = *(const UmatParams *)mk->ctx;
      MaterialKernel uk, bk;
      p.nprops = 20;
      for (int i = 0; i < 20; i++) p.props[i] = pr[b][i];
      UmatKernelInit(&p, &uk);
      Hill48KernelInit(&hps[b], &bk);
      for (int t = 0; t < 100; t++) {
        double F[9], hu0[UMAT_NHIST(7)], hu1[UMAT_NHIST(7)], hb0[HILL48_NHIST], hb1[HILL48_NHIST], tu[9], tb[9];
        int    plu, plb;
        random_F(&s, 0.3, F);
        uk.history_init(uk.ctx, hu0);
        bk.history_init(bk.ctx, hb0);
        if (uk.update(uk.ctx, F, hu0, tu, NULL, hu1, &plu) || bk.update(bk.ctx, F, hb0, tb, NULL, hb1, &plb) || plu != plb) {
          nfail++;
          continue;
        }
        npl += plu;
        worst = fmax(worst, fdiff(tu, tb, 9) / fnorm(tb, 9));
        worst = fmax(worst, fabs(hu1[0] - hb1[HILL48_HIST_EP]) / fmax(hb1[HILL48_HIST_EP], 1e-3));
      }
    }
    TU_CHECK(worst < 1e-9 && nfail == 0 && npl > 200, "one step from the virgin state, 300 random F = R (1 + 0.3 Z) (Z entries in [-1, 1), any rotation R; r 1.6/1.2/2.0, r 0.3/3.0/0.5 on oblique axes, perfect plasticity): Hill UMAT = built-in hill48 to %.1e in tau and ep (< 1e-9), %d plastic, %d failed or disagreeing on yielding", worst, npl, nfail);
  }

  /* (2) r-values 1: the Fortran J2 UMAT's update, in simple shear to 2 */
  {
    Material              matr;
    const MaterialKernel *mkr;
    PetscCall(MaterialFromOptions(SWIFT_OPTS, &matj, &ierr));
    PetscCall(MaterialGetKernel(matj, &mkj));
    PetscCall(MaterialFromOptions("-material_type umat -material_umat bin/umat_hill48.so -material_umat_props 69004,0.3,1,589,1e-4,0.216,0,1,1,1,0,0,0 -material_umat_nstatev 7 -material_umat_statev_ep 1", &matr, &ierr));
    PetscCall(MaterialGetKernel(matr, &mkr));
    Gamma          = 2.0;
    const double e = follow2(mkr, mkj, path_shear, 50, &epu, &epb, NULL, NULL);
    TU_CHECK(e < 1e-10 && fabs(epu - epb) < 1e-10 * epb, "Hill UMAT with r-values 1 = Fortran J2 UMAT, simple shear to 2 (50 increments): |dtau|/max|tau| %.2e (< 1e-10), ep %.6f vs %.6f", e, epu, epb);
    PetscCall(MaterialDestroy(&matj));
    PetscCall(MaterialDestroy(&matr));
  }

  /* (3) against the built-in hill48, rolling direction x (the UMAT's default frame) */
  HillParams     hp = hill_builtin(0, 1.6, 1.2, 2.0);
  MaterialKernel hk;
  Hill48KernelInit(&hp, &hk);
  {
    /* proportional stretches along the orthotropy axes: the two formulations coincide */
    for (int i = 0; i < 9; i++) Qfix[i] = i % 4 == 0;
    double e = follow2(mk, &hk, path_proportional, 30, &epu, &epb, &wfd, &npl);
    TU_CHECK(e < 1e-9 && fabs(epu - epb) < 1e-9 * epb, "Hill UMAT = built-in hill48, stretches along the orthotropy axes (30 increments to ln stretch 0.26): |dtau|/max|tau| %.2e (< 1e-9), ep %.6f vs %.6f", e, epu, epb);
    TU_CHECK(wfd < 1e-3 && npl > 0, "Hill UMAT (IAX 0) d tau/dF vs central differences on that path (%d plastic points, no rotation): %.2e (< 1e-3: the derivative of the polar frame is missing)", npl, wfd);
    /* the same stretches along axes rotated by 0.7 rad about (0.4, 1, -0.3): not coaxial with the orthotropy */
    const double ax[3] = {0.4, 1.0, -0.3};
    rotation(ax, 0.7, Qfix);
    double e30 = follow2(mk, &hk, path_proportional, 30, &epu, &epb, NULL, NULL), eu = epu, eb = epb;
    double e120 = follow2(mk, &hk, path_proportional, 120, &epu, &epb, NULL, NULL);
    TU_CHECK(e30 < 2e-6 && e120 < 2e-6, "Hill UMAT vs built-in, the same stretches along rotated axes (plastic flow not coaxial with the strain): |dtau|/max|tau| %.2e / %.2e with 30 / 120 increments (< 2e-6); ep %.5f vs %.5f", e30, e120, eu, eb);
    e = follow2(mk1, &hk, path_proportional, 30, &epu, &epb, &wfd, &npl);
    TU_CHECK(wfd < 1e-6 && npl > 0, "Hill UMAT (IAX 1) d tau/dF vs central differences on that path (%d plastic points): %.2e (< 1e-6)", npl, wfd);
  }
  {
    /* simple shear to 2: the frame turns by atan(1) = 45 degrees (polar) */
    const int ns[3] = {50, 200, 800};
    double    es[3], e1[3], fd0 = 0, fd1 = 0, ep1u = 0;
    int       np0 = 0, np1 = 0;
    Gamma           = 2.0;
    for (int i = 0; i < 3; i++) es[i] = follow2(mk, &hk, path_shear, ns[i], &epu, &epb, i == 0 ? &fd0 : NULL, i == 0 ? &np0 : NULL);
    TU_CHECK(es[2] < 1e-4 && es[2] < 0.5 * es[0], "simple shear to 2: Hill UMAT (IAX 0) vs built-in hill48, largest |dtau|/max|tau| %.2e / %.2e / %.2e with %d / %d / %d increments (< 1e-4, halved at least); ep %.5f vs %.5f", es[0], es[1], es[2], ns[0], ns[1], ns[2], epu, epb);
    for (int i = 0; i < 3; i++) e1[i] = follow2(mk1, &hk, path_shear, ns[i], &ep1u, &epb, i == 0 ? &fd1 : NULL, i == 0 ? &np1 : NULL);
    TU_CHECK(e1[2] > 10 * es[2], "... with the frame turned by the increments' DROT (IAX 1, the spin: 1 rad instead of 45 degrees) the difference does not vanish: %.2e / %.2e / %.2e; ep %.5f", e1[0], e1[1], e1[2], ep1u);
    TU_CHECK(fd1 < 1e-6 && np1 > 0, "Hill UMAT (IAX 1) in simple shear: d tau/dF vs central differences (%d plastic points): %.2e (< 1e-6, the bridge's tangent is exact)", np1, fd1);
    TU_CHECK(fd0 < 1e-2 && np0 > 0, "Hill UMAT (IAX 0) in simple shear: d tau/dF vs central differences (%d plastic points): %.2e (< 1e-2: the derivative of the polar frame is missing)", np0, fd0);
  }

  /* (4) r-values at 0, 45, 90 degrees: uniaxial tension to 2 % in 10 steps */
  {
    const double rin[3] = {1.6, 1.2, 2.0}, ang[3] = {0, 45, 90};
    for (int k = 0; k < 3; k++) {
      Material              mt;
      const MaterialKernel *mkt;
      double                tu = 0, tb = 0;
      PetscCall(MaterialFromOptions(hill_opts(0, 0, buf, sizeof buf), &mt, &ierr));
      PetscCall(MaterialGetKernel(mt, &mkt));
      const double r = uniaxial_umat(mkt, ang[k] * PI / 180.0, 1.02, 10, &tu);
      /* the built-in along the same load path: the axial stress */
      HillParams     hb = hill_builtin(0, 1.6, 1.2, 2.0);
      MaterialKernel bk;
      Hill48KernelInit(&hb, &bk);
      (void)uniaxial_umat(&bk, ang[k] * PI / 180.0, 1.02, 10, &tb); /* its r from STATEV is meaningless here: only tau */
      TU_CHECK(r > 0 && fabs(r - rin[k]) < 1e-3 * rin[k] && fabs(tu - tb) < 1e-8 * tb, "Hill UMAT, uniaxial tension at %2.0f deg to the rolling direction (2 %% stretch): r = %.6f from the last step's plastic strain increments (input %.2f, to 1e-3), axial tau %.4f vs built-in %.4f (%.1e, < 1e-8)", ang[k], r, rin[k], tu, tb, fabs(tu - tb) / tb);
      PetscCall(MaterialDestroy(&mt));
    }
  }
  PetscCall(MaterialDestroy(&mat));
  PetscCall(MaterialDestroy(&mat1));
  PetscFunctionReturn(0);
}

/* ---------- timing: hex8 Jacobian, Fortran J2 UMAT vs built-in J2 ---------- */
static double now(void)
{
  struct timespec ts;
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts); /* CPU time: the machine may be shared */
  return ts.tv_sec + 1e-9 * ts.tv_nsec;
}

#define NEL 64
static double time_jacobian(const MaterialKernel *mk, double *rate_res)
{
  static double X[NEL][8][3], U1[NEL][8][3], U2[NEL][8][3];
  double       *H0 = malloc(sizeof(double) * NEL * HEX8_NQP * mk->nhist), *H1 = malloc(sizeof(double) * NEL * HEX8_NQP * mk->nhist), *Ht = malloc(sizeof(double) * NEL * HEX8_NQP * mk->nhist);
  const int     nh = HEX8_NQP * mk->nhist;
  Hex8Options   eo = {1};
  double        fe[24], ke[576], sink = 0, rate[2];
  unsigned long long s = 3;
  for (int e = 0; e < NEL; e++) {
    for (int a = 0; a < 8; a++)
      for (int i = 0; i < 3; i++) X[e][a][i] = 0.05 * (hex8_nodes[a][i] + 1) + 0.005 * urand(&s);
    for (int a = 0; a < 8; a++) {
      const double gu[3][3] = {{0.004, 0.0, 0.01}, {0.0, -0.002, 0.0}, {0.002, 0.0, -0.002}};
      for (int i = 0; i < 3; i++) {
        double v = 0;
        for (int k = 0; k < 3; k++) v += gu[i][k] * X[e][a][k];
        U1[e][a][i] = v;
        U2[e][a][i] = 1.6 * v;
      }
    }
    for (int q = 0; q < HEX8_NQP; q++) mk->history_init(mk->ctx, H0 + e * nh + q * mk->nhist);
    hex8_element(&eo, mk, X[e], U1[e], H0 + e * nh, fe, NULL, H1 + e * nh, NULL);
  }
  for (int jac = 0; jac < 2; jac++) {
    long   passes = 1;
    double dt;
    for (;;) {
      const double t0 = now();
      for (long p = 0; p < passes; p++)
        for (int e = 0; e < NEL; e++) {
          hex8_element(&eo, mk, X[e], U2[e], H1 + e * nh, fe, jac ? ke : NULL, Ht + e * nh, NULL);
          sink += fe[e % 24];
        }
      dt = now() - t0;
      if (dt > 0.5) break;
      passes *= 2;
    }
    rate[jac] = passes * NEL / dt;
  }
  free(H0), free(H1), free(Ht);
  *rate_res = rate[0] + 0 * sink;
  return rate[1];
}

static PetscErrorCode timing(void)
{
  Material              mat;
  PetscErrorCode        ierr;
  const MaterialKernel *mk;
  J2Params              jp = swift_j2();
  MaterialKernel        jk;
  double                rj, ru, rjr, rur;

  PetscFunctionBeginUser;
  J2KernelInit(&jp, &jk);
  PetscCall(MaterialFromOptions(SWIFT_OPTS, &mat, &ierr));
  if (ierr) PetscFunctionReturn(0);
  PetscCall(MaterialGetKernel(mat, &mk));
  /* alternating repetitions, the best of each (the machine may be shared) */
  rj = ru = rjr = rur = 0;
  for (int r = 0; r < 5; r++) {
    double a, b;
    a = time_jacobian(&jk, &b), rj = fmax(rj, a), rjr = fmax(rjr, b);
    a = time_jacobian(mk, &b), ru = fmax(ru, a), rur = fmax(rur, b);
  }
  printf("# hex8 (F-bar), plastic trial state, elements per CPU second (best of 5): residual: built-in J2 %.0f, UMAT %.0f (%.2fx); Jacobian: built-in J2 %.0f, UMAT %.0f (%.2fx)\n", rjr, rur, rjr / rur, rj, ru, rj / ru);
  PetscCall(MaterialDestroy(&mat));

  /* the same for Hill 48: built-in hill48 and the Fortran UMAT with its polar frame (IAX 0) and
     with the frame turned by DROT (IAX 1) */
  {
    HillParams     hp = hill_builtin(0, 1.6, 1.2, 2.0);
    MaterialKernel hk;
    Material       m0, m1;
    const MaterialKernel *k0, *k1;
    char           buf[512];
    double         rh = 0, rhr = 0, r0 = 0, r0r = 0, r1 = 0, r1r = 0;
    Hill48KernelInit(&hp, &hk);
    PetscCall(MaterialFromOptions(hill_opts(0, 0, buf, sizeof buf), &m0, &ierr));
    if (ierr) PetscFunctionReturn(0);
    PetscCall(MaterialFromOptions(hill_opts(1, 0, buf, sizeof buf), &m1, &ierr));
    if (ierr) PetscFunctionReturn(0);
    PetscCall(MaterialGetKernel(m0, &k0));
    PetscCall(MaterialGetKernel(m1, &k1));
    for (int r = 0; r < 5; r++) {
      double a, b;
      a = time_jacobian(&hk, &b), rh = fmax(rh, a), rhr = fmax(rhr, b);
      a = time_jacobian(k0, &b), r0 = fmax(r0, a), r0r = fmax(r0r, b);
      a = time_jacobian(k1, &b), r1 = fmax(r1, a), r1r = fmax(r1r, b);
    }
    printf("# hex8 (F-bar), plastic trial state, elements per CPU second (best of 5): residual: built-in hill48 %.0f, Hill UMAT IAX 0 %.0f (%.2fx), IAX 1 %.0f (%.2fx); Jacobian: built-in hill48 %.0f, Hill UMAT IAX 0 %.0f (%.2fx), IAX 1 %.0f (%.2fx)\n", rhr, r0r, rhr / r0r, r1r,
           rhr / r1r, rh, r0, rh / r0, r1, rh / r1);
    PetscCall(MaterialDestroy(&m0));
    PetscCall(MaterialDestroy(&m1));
  }
  PetscFunctionReturn(0);
}

int main(int argc, char **argv)
{
  PetscBool dotime = PETSC_FALSE;
  PetscCall(PetscInitialize(&argc, &argv, NULL, NULL));
  PetscCall(PetscOptionsHasName(NULL, NULL, "-timing", &dotime));
  test_conversion();
  test_status();
  PetscCall(test_fortran_j2());
  PetscCall(test_fortran_hill());
  if (dotime) PetscCall(timing());
  PetscCall(PetscFinalize());
  TU_RETURN();
}
#endif
