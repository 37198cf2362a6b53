/* Unit tests of the user-material interface (material type "umat", src/material/umat.c):
   the conversion of an Abaqus UMAT's Cauchy stress and DDSDDE to tau and d tau/dF, against
   finite differences, on a hypoelastic (Hencky-like) UMAT written here in C; the Fortran J2 UMAT
   tests/umat_j2.f (bin/umat_j2.so) against the built-in J2 on proportional paths and simple shear;
   PNEWDT and NaN statuses; the options' errors.
   `bin/test_umat -timing` also times the hex8 Jacobian with the Fortran UMAT and the built-in J2.

   Built with -DUMAT_TEST_LIBRARY (bin/umat_ctest.so, for tests/test_umat.sh) only the C UMATs
   are compiled: umat_hypo_, umat_cut_ (PNEWDT = 0.5 on its first call with a nonzero strain
   increment in a process, then as umat_hypo_) and umat_nan_ (a NaN stress for any nonzero strain increment).
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
  if (s > 0) stress[0] = NAN;
}

#ifndef UMAT_TEST_LIBRARY
#include <petscsys.h>
#include "element_hex8.h"
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
  TU_CHECK(st3 == MAT_ERR_RETURNMAP && fnorm(tau, 9) == 0 && !memcmp(h0, h1, sizeof(h0)), "NaN in the returned stress: MAT_ERR_RETURNMAP (status %d)", st3);
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
  if (dotime) PetscCall(timing());
  PetscCall(PetscFinalize());
  TU_RETURN();
}
#endif
