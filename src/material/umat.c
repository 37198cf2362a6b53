/* Abaqus/Standard user materials (SUBROUTINE UMAT) loaded at run time: the material type "umat".

   Conventions (those of Abaqus/Standard with NLGEOM for solid elements without *ORIENTATION;
   derivation in doc/umat.md). The element hands F = F_{n+1} (DFGRD1) and the committed history,
   which holds F_n (DFGRD0), the Cauchy stress sigma_n and the strain STRAN_n of the previous
   increment, and STATEV. With the incremental deformation gradient dF = F_{n+1} F_n^{-1} and its
   polar decomposition dF = dR dU:
     DROT    = dR, the incremental rotation;
     DSTRAN  = dR ln(dU) dR^T = ln(dV), the logarithmic strain increment in the rotated frame;
     STRESS  = dR sigma_n dR^T on entry (rotated for the rigid motion of the increment), the
               Cauchy stress sigma_{n+1} on return;
     STRAN   = dR STRAN_n dR^T, stored afterwards as STRAN + DSTRAN;
     DDSDDE  = C, read as Abaqus defines it for finite strains: the Jacobian of the Jaumann rate of
               Kirchhoff stress over J, C = (1/J) d(J sigma)/d DSTRAN at fixed entry STRESS
               (= d sigma/d DSTRAN + sigma (x) 1).
   NDI = NSHR = 3, NTENS = 6, order 11, 22, 33, 12, 13, 23, engineering shear strains.

   What this code returns: tau = J sigma_{n+1} (J = det F_{n+1}), and for every dF_{n+1}
       d tau = dW tau - tau dW + J C : (dR d ln(dU) dR^T),   dW = d(dR) dR^T (skew),
   with d ln(dU) and d(dR) the exact derivatives of the kinematics (Daleckii-Krein formulas in the
   eigenbasis of dU^2). This d tau/dF is exact -- the derivative of the tau this code returns --
   as far as (1) DDSDDE is the exact Jacobian above of the user's update and (2) that update is
   isotropic (objective): rotating its entry STRESS and DSTRAN (and DROT, DFGRD0, DFGRD1
   accordingly) rotates its result, and it depends on DFGRD1 otherwise only through DSTRAN (e.g.
   through det DFGRD1 = det DFGRD0 exp(tr DSTRAN)). A UMAT that returns only d sigma/d DSTRAN
   (common in small-strain codes) gives a tangent off by sigma (x) 1, relative size sigma/E;
   Newton then converges linearly in its last digits.

   Not available through the kernel interface, passed as constants: TEMP = DTEMP = 0, no
   predefined fields, LAYER = KSPT = 1; SSE, SPD, SCD start at 0 every call and are not kept.
   NOEL, NPT, COORDS and CELENT are the element's id, the integration point (1..8), its current
   position and the element's length set through the kernel's set_point, TIME, DTIME, KSTEP,
   KINC the increment set through its set_increment (the load stepping); a caller that sets none
   (a material driver) gets NOEL = NPT = 1, COORDS = 0, CELENT = 1, TIME = (0, 0), DTIME = 1,
   KSTEP = KINC = 1.
   Status: PNEWDT < 1 -> MAT_ERR_CUTBACK (the value is kept for UmatLastPnewdt()); NaN or Inf in
   STRESS or DDSDDE -> MAT_ERR_NAN (the point is kept for UmatLastNaN()). */
#include <dlfcn.h>
#include <math.h>
#include <string.h>

#include "material_impl.h"
#include "material_umat.h"
#include "options.h"
#include "tensor.h"

static double LastPnewdt = 1.0;
/* the material point of the next calls (set_point) and the last one that returned NaN or Inf:
   one process evaluates its elements one at a time, so a process-wide record is that point */
static int    CurNoel = 1, CurNpt = 1, NanNoel = 0, NanNpt = 0, NanWhat = 0;
static double CurCoords[3] = {0, 0, 0}, CurCelent = 1;
/* the increment of the next calls (set_increment) */
static double CurTime[2] = {0, 0}, CurDtime = 1;
static int    CurKstep = 1, CurKinc = 1;

double UmatLastPnewdt(void)
{
  return LastPnewdt;
}

int UmatLastNaN(int *noel, int *npt)
{
  if (noel) *noel = NanNoel;
  if (npt) *npt = NanNpt;
  return NanWhat;
}

static void UmatKernelSetPoint(const void *ctx, int noel, int npt, const double coords[3], double celent)
{
  (void)ctx;
  if (noel >= 0) CurNoel = noel;
  if (npt >= 1) CurNpt = npt;
  if (coords)
    for (int i = 0; i < 3; i++) CurCoords[i] = coords[i];
  if (celent > 0) CurCelent = celent;
}

static void UmatKernelSetIncrement(const void *ctx, double time_stage, double time_total, double dtime, int kstep, int kinc)
{
  (void)ctx;
  CurTime[0] = time_stage;
  CurTime[1] = time_total;
  CurDtime   = dtime;
  CurKstep   = kstep;
  CurKinc    = kinc;
}

static int UmatKernelFailedPoint(const void *ctx)
{
  (void)ctx;
  return NanNpt;
}

/* (ln x - ln y)/(x - y) for x, y > 0, accurate for x ~ y (series in t = (x-y)/(x+y)) */
static inline double dlog_ratio(double x, double y)
{
  const double m = 0.5 * (x + y), t = (x - y) / (x + y);
  if (fabs(t) < 1e-4) {
    const double t2 = t * t;
    return (1.0 + t2 * (1.0 / 3.0 + 0.2 * t2)) / m;
  }
  return atanh(t) / (m * t);
}

/* symmetric tensor <-> Abaqus vectors (11, 22, 33, 12, 13, 23) */
static void t2v_stress(const double A[9], double v[6])
{
  v[0] = A[0];
  v[1] = A[4];
  v[2] = A[8];
  v[3] = 0.5 * (A[1] + A[3]);
  v[4] = 0.5 * (A[2] + A[6]);
  v[5] = 0.5 * (A[5] + A[7]);
}
static void t2v_strain(const double A[9], double v[6]) /* engineering shears */
{
  v[0] = A[0];
  v[1] = A[4];
  v[2] = A[8];
  v[3] = A[1] + A[3];
  v[4] = A[2] + A[6];
  v[5] = A[5] + A[7];
}
static void v2t_stress(const double v[6], double A[9])
{
  A[0] = v[0];
  A[4] = v[1];
  A[8] = v[2];
  A[1] = A[3] = v[3];
  A[2] = A[6] = v[4];
  A[5] = A[7] = v[5];
}
static void v2t_strain(const double v[6], double A[9])
{
  A[0] = v[0];
  A[4] = v[1];
  A[8] = v[2];
  A[1] = A[3] = 0.5 * v[3];
  A[2] = A[6] = 0.5 * v[4];
  A[5] = A[7] = 0.5 * v[5];
}
/* B = Q A Q^T */
static void rotate(const double Q[9], const double A[9], double B[9])
{
  double T[9];
  t3_mul(Q, A, T);
  t3_mult(T, Q, B);
}

static int fail_outputs(int status, int nh, const double *hn, double tau[9], double *dtau, double *h)
{
  for (int i = 0; i < 9; i++) tau[i] = 0.0;
  if (dtau)
    for (int i = 0; i < 81; i++) dtau[i] = 0.0;
  if (h != hn)
    for (int i = 0; i < nh; i++) h[i] = hn[i];
  return status;
}

/* a NaN or Inf in STRESS (what = 1) or DDSDDE (2) at the current point: recorded, MAT_ERR_NAN */
static int nan_outputs(int what, int nh, const double *hn, double tau[9], double *dtau, double *h)
{
  NanNoel = CurNoel;
  NanNpt  = CurNpt;
  NanWhat = what;
  return fail_outputs(MAT_ERR_NAN, nh, hn, tau, dtau, h);
}

void UmatHistoryInit(const UmatParams *p, double *h)
{
  const int ns = p->nstatev;
  for (int i = 0; i < UMAT_NHIST(ns); i++) h[i] = 0.0;
  h[UMAT_HIST_F(ns) + 0] = h[UMAT_HIST_F(ns) + 4] = h[UMAT_HIST_F(ns) + 8] = 1.0;
}

int UmatUpdate(const UmatParams *p, const double F[9], const double *hn, double tau[9], double *dtau, double *h, int *plastic)
{
  const int     ns = p->nstatev, nh = UMAT_NHIST(ns);
  const double *F0 = hn + UMAT_HIST_F(ns);
  double        F0i[9], dF[9], C[9], c[3], N[9], s[3], l[3], Ui[9], R[9], M[9];

  if (plastic) *plastic = 0;
  const double J = t3_det(F), J0 = t3_inv(F0, F0i);
  if (!(J > 0.0) || !isfinite(J) || !(J0 > 0.0)) return fail_outputs(MAT_ERR_JACOBIAN, nh, hn, tau, dtau, h);

  /* increment dF = F F0^{-1} = dR dU, dU^2 = dF^T dF = N diag(c) N^T */
  t3_mul(F, F0i, dF);
  t3_tmul(dF, dF, C);
  t3_sym_eig(C, c, N);
  if (!(c[0] > 0.0 && c[1] > 0.0 && c[2] > 0.0)) return fail_outputs(MAT_ERR_JACOBIAN, nh, hn, tau, dtau, h);
  for (int a = 0; a < 3; a++) {
    s[a] = sqrt(c[a]);
    l[a] = 0.5 * log(c[a]);
  }
  {
    const double is[3] = {1.0 / s[0], 1.0 / s[1], 1.0 / s[2]};
    for (int i = 0; i < 3; i++)
      for (int j = 0; j < 3; j++) Ui[3 * i + j] = N[3 * i] * is[0] * N[3 * j] + N[3 * i + 1] * is[1] * N[3 * j + 1] + N[3 * i + 2] * is[2] * N[3 * j + 2];
  }
  t3_mul(dF, Ui, R); /* dR = dF dU^{-1} */
  t3_mul(R, N, M);   /* eigenvectors of dV = dR dU dR^T */

  /* the UMAT's arguments */
  double deps[9], sig_n[9], eps_n[9], sig_in[9], eps_in[9];
  double stress[6], stran[6], dstran[6], ddsdde[36] = {0}, drot[9], dfgrd0[9], dfgrd1[9];
  for (int i = 0; i < 3; i++)
    for (int j = 0; j < 3; j++) deps[3 * i + j] = M[3 * i] * l[0] * M[3 * j] + M[3 * i + 1] * l[1] * M[3 * j + 1] + M[3 * i + 2] * l[2] * M[3 * j + 2];
  v2t_stress(hn + UMAT_HIST_STRESS(ns), sig_n);
  v2t_strain(hn + UMAT_HIST_STRAN(ns), eps_n);
  rotate(R, sig_n, sig_in);
  rotate(R, eps_n, eps_in);
  t2v_stress(sig_in, stress);
  t2v_strain(eps_in, stran);
  t2v_strain(deps, dstran);
  for (int i = 0; i < 3; i++)
    for (int j = 0; j < 3; j++) { /* column-major */
      drot[i + 3 * j]   = R[3 * i + j];
      dfgrd0[i + 3 * j] = F0[3 * i + j];
      dfgrd1[i + 3 * j] = F[3 * i + j];
    }
  if (h != hn)
    for (int i = 0; i < ns; i++) h[i] = hn[i];
  {
    double       sse = 0, spd = 0, scd = 0, rpl = 0, ddsddt[6] = {0}, drplde[6] = {0}, drpldt = 0, pnewdt = 1.0;
    const double time[2] = {CurTime[0], CurTime[1]}, dtime = CurDtime, temp = 0, dtemp = 0, predef[1] = {0}, dpred[1] = {0}, coords[3] = {CurCoords[0], CurCoords[1], CurCoords[2]}, celent = CurCelent;
    const int    ndi = 3, nshr = 3, ntens = 6, nstatv = ns, nprops = p->nprops, noel = CurNoel, npt = CurNpt, layer = 1, kspt = 1, kstep = CurKstep, kinc = CurKinc;
    p->fn(stress, h, ddsdde, &sse, &spd, &scd, &rpl, ddsddt, drplde, &drpldt, stran, dstran, time, &dtime, &temp, &dtemp, predef, dpred, p->cmname, &ndi, &nshr, &ntens, &nstatv, p->props, &nprops, coords, drot, &pnewdt, &celent, dfgrd0, dfgrd1, &noel, &npt, &layer, &kspt, &kstep, &kinc, sizeof(p->cmname));
    if (pnewdt < 1.0) {
      LastPnewdt = pnewdt;
      return fail_outputs(MAT_ERR_CUTBACK, nh, hn, tau, dtau, h);
    }
  }
  for (int i = 0; i < 6; i++)
    if (!isfinite(stress[i])) return nan_outputs(1, nh, hn, tau, dtau, h);
  for (int i = 0; i < 36; i++)
    if (!isfinite(ddsdde[i])) return nan_outputs(2, nh, hn, tau, dtau, h);

  /* tau = J sigma_{n+1}; the new history */
  double sig[9];
  v2t_stress(stress, sig);
  for (int i = 0; i < 9; i++) tau[i] = J * sig[i];
  for (int i = 0; i < 6; i++) {
    h[UMAT_HIST_STRESS(ns) + i] = stress[i];
    h[UMAT_HIST_STRAN(ns) + i]  = stran[i] + dstran[i];
  }
  for (int i = 0; i < 9; i++) h[UMAT_HIST_F(ns) + i] = F[i];
  if (plastic && p->ep_statev > 0 && p->ep_statev <= ns) *plastic = h[p->ep_statev - 1] > hn[p->ep_statev - 1];
  if (!dtau) return MAT_OK;

  /* d tau / d F_kL (doc/umat.md). For dF_{n+1} = e_k (x) E_L: d(dF) = e_k (x) g~, g~ = row L of
     F0^{-1}; in the eigenbasis N of dU^2, with g = N^T g~ and A = dF N = M diag(s):
       d(dU^2)_ab = g_a A_kb + A_ka g_b
       d ln(dU)_ab = 1/2 Gamma_ab d(dU^2)_ab,   Gamma_ab = (ln c_a - ln c_b)/(c_a - c_b)
       d dU_ab     = d(dU^2)_ab / (s_a + s_b)
     and in the basis M = dR N:  M^T dW M = M_ka g_b / s_b - d dU_ab / s_b  (skew),
     d eps^ = dR d ln(dU) dR^T = M (d ln dU) M^T. */
  double G1[6], is[3] = {1.0 / s[0], 1.0 / s[1], 1.0 / s[2]}; /* 1/2 Gamma_ab, pairs 00 11 22 01 02 12 */
  static const int pa[6] = {0, 1, 2, 0, 0, 1}, pb[6] = {0, 1, 2, 1, 2, 2};
  for (int q = 0; q < 6; q++) G1[q] = pa[q] == pb[q] ? 0.5 / c[pa[q]] : 0.5 * dlog_ratio(c[pa[q]], c[pb[q]]);
  for (int k = 0; k < 3; k++) {
    const double *u = M + 3 * k;
    for (int L = 0; L < 3; L++) {
      double g[3], X[9], dC[6], Wm[9], Y[9], Z[9], dev[6], w[3], T[9];
      for (int b = 0; b < 3; b++) g[b] = F0i[3 * L] * N[b] + F0i[3 * L + 1] * N[3 + b] + F0i[3 * L + 2] * N[6 + b];
      for (int q = 0; q < 6; q++) {
        const int a = pa[q], b = pb[q];
        dC[q]                        = g[a] * u[b] * s[b] + u[a] * s[a] * g[b];
        X[3 * a + b] = X[3 * b + a] = G1[q] * dC[q];
      }
      /* M^T dW M (skew) */
      Wm[0] = Wm[4] = Wm[8] = 0.0;
      Wm[1] = (u[0] * g[1] - dC[3] / (s[0] + s[1])) * is[1];
      Wm[2] = (u[0] * g[2] - dC[4] / (s[0] + s[2])) * is[2];
      Wm[5] = (u[1] * g[2] - dC[5] / (s[1] + s[2])) * is[2];
      Wm[3] = -Wm[1], Wm[6] = -Wm[2], Wm[7] = -Wm[5];
      /* d eps^ = M X M^T, engineering Voigt */
      t3_mul(M, X, Y);
      for (int q = 0; q < 6; q++) {
        const int i = pa[q], j = pb[q];
        dev[q] = (i == j ? 1.0 : 2.0) * (Y[3 * i] * M[3 * j] + Y[3 * i + 1] * M[3 * j + 1] + Y[3 * i + 2] * M[3 * j + 2]);
      }
      /* dW = M Wm M^T (global, skew: w = its 01, 02, 12), T = dW tau; dW tau - tau dW = T + T^T */
      t3_mul(M, Wm, Z);
      w[0] = Z[0] * M[3] + Z[1] * M[4] + Z[2] * M[5];
      w[1] = Z[0] * M[6] + Z[1] * M[7] + Z[2] * M[8];
      w[2] = Z[3] * M[6] + Z[4] * M[7] + Z[5] * M[8];
      {
        const double dW[9] = {0, w[0], w[1], -w[0], 0, w[2], -w[1], -w[2], 0};
        t3_mul(dW, tau, T);
      }
      const int col = 3 * k + L;
      for (int q = 0; q < 6; q++) {
        const int i = pa[q], j = pb[q];
        double    v = 0.0;
        for (int n = 0; n < 6; n++) v += ddsdde[q + 6 * n] * dev[n];
        v = J * v + T[3 * i + j] + T[3 * j + i];
        dtau[(3 * i + j) * 9 + col] = dtau[(3 * j + i) * 9 + col] = v;
      }
    }
  }
  return MAT_OK;
}

/* ------------------------------------------------------------------------------------------ */
/* the kernel table                                                                            */
/* ------------------------------------------------------------------------------------------ */
static int UmatKernelUpdate(const void *ctx, const double F[9], const double *hn, double tau[9], double *dtau, double *h, int *plastic)
{
  return UmatUpdate((const UmatParams *)ctx, F, hn, tau, dtau, h, plastic);
}

static void UmatKernelHistoryInit(const void *ctx, double *h)
{
  UmatHistoryInit((const UmatParams *)ctx, h);
}

static double UmatKernelPlasticStrain(const void *ctx, const double *h)
{
  const UmatParams *p = (const UmatParams *)ctx;
  return p->ep_statev > 0 && p->ep_statev <= p->nstatev ? h[p->ep_statev - 1] : 0.0;
}

void UmatKernelInit(const UmatParams *p, MaterialKernel *k)
{
  k->nhist          = UMAT_NHIST(p->nstatev);
  k->ctx            = p;
  k->update         = UmatKernelUpdate;
  k->history_init   = UmatKernelHistoryInit;
  k->plastic_strain = UmatKernelPlasticStrain;
  k->set_point      = UmatKernelSetPoint;
  k->failed_point   = UmatKernelFailedPoint;
  k->set_increment  = UmatKernelSetIncrement;
}

/* ------------------------------------------------------------------------------------------ */
/* the material type "umat"                                                                    */
/* ------------------------------------------------------------------------------------------ */
static void UmatClose(UmatParams *p)
{
  if (p->dl) dlclose(p->dl);
  p->dl = NULL;
  p->fn = NULL;
}

static PetscErrorCode MaterialSetFromOptions_Umat(Material mat)
{
  UmatParams *p    = (UmatParams *)mat->data;
  MPI_Comm    comm = mat->comm;
  char        path[sizeof(p->path)], symbol[sizeof(p->symbol)];
  PetscInt    nprops = UMAT_MAXPROPS, nstatev = p->nstatev, ep = p->ep_statev;
  PetscBool   setpath, setprops, help;
  double      props[UMAT_MAXPROPS];
  const char *pre = mat->prefix; /* the options' names in the messages: -<pre>umat, ... */
  char        title[512];

  PetscFunctionBeginUser;
  PetscCall(PetscStrncpy(path, p->path, sizeof(path)));
  PetscCall(PetscStrncpy(symbol, p->symbol, sizeof(symbol)));
  PetscCall(MaterialOptionsTitle(mat, "umat", "an Abaqus/Standard user material (SUBROUTINE UMAT) from a shared library", title, sizeof(title)));
  PetscOptionsBegin(comm, mat->prefix, title, "Material");
  PetscCall(PetscOptionsString("-umat", "Shared library with the UMAT", NULL, path, path, sizeof(path), &setpath));
  PetscCall(PetscOptionsString("-umat_symbol", "Its symbol (umat_ for gfortran's SUBROUTINE UMAT; umat is tried after umat_)", NULL, symbol, symbol, sizeof(symbol), NULL));
  PetscCall(PetscOptionsRealArray("-umat_props", "PROPS, comma-separated", NULL, props, &nprops, &setprops));
  PetscCall(PetscOptionsInt("-umat_nstatev", "NSTATV, the number of solution-dependent state variables", NULL, nstatev, &nstatev, NULL));
  PetscCall(PetscOptionsInt("-umat_statev_ep", "1-based STATEV index of the equivalent plastic strain (output), 0: none", NULL, ep, &ep, NULL));
  PetscOptionsEnd();
  PetscCall(PetscOptionsHasHelp(NULL, &help));
  if (help && !path[0]) PetscFunctionReturn(0); /* -help lists the options; nothing runs */
  PetscCheck(path[0], comm, PETSC_ERR_USER_INPUT, "-%stype umat needs -%sumat PATH (a shared library with SUBROUTINE UMAT)", pre, pre);
  PetscCheck(nstatev >= 0 && nstatev <= 100000, comm, PETSC_ERR_USER_INPUT, "-%sumat_nstatev %d must lie in [0, 100000]", pre, (int)nstatev);
  PetscCheck(ep >= 0 && ep <= nstatev, comm, PETSC_ERR_USER_INPUT, "-%sumat_statev_ep %d must lie in [0, nstatev = %d]", pre, (int)ep, (int)nstatev);
  if (setprops) {
    PetscCheck(nprops <= UMAT_MAXPROPS, comm, PETSC_ERR_USER_INPUT, "-%sumat_props: at most %d values", pre, UMAT_MAXPROPS);
    for (PetscInt i = 0; i < nprops; i++) PetscCheck(isfinite(props[i]), comm, PETSC_ERR_USER_INPUT, "-%sumat_props: value %d is not a finite number", pre, (int)i + 1);
    p->nprops = (int)nprops;
    for (PetscInt i = 0; i < nprops; i++) p->props[i] = props[i];
  }
  p->nstatev   = (int)nstatev;
  p->ep_statev = (int)ep;
  if (!p->fn || strcmp(path, p->path) || strcmp(symbol, p->symbol)) {
    void       *dl, *fn;
    const char *err;
    UmatClose(p);
    dl = dlopen(path, RTLD_NOW | RTLD_LOCAL);
    PetscCheck(dl, comm, PETSC_ERR_USER_INPUT, "-%sumat %s: cannot load the library: %s", pre, path, (err = dlerror()) ? err : "unknown error");
    dlerror();
    fn  = dlsym(dl, symbol);
    err = dlerror();
    if ((!fn || err) && !strcmp(symbol, "umat_")) { /* the default: also the unmangled name */
      fn  = dlsym(dl, "umat");
      err = fn ? NULL : err;
    }
    if (!fn || err) {
      char msg[1024];
      snprintf(msg, sizeof(msg), "%s", err ? err : "null symbol");
      dlclose(dl);
      SETERRQ(comm, PETSC_ERR_USER_INPUT, "-%sumat_symbol %s: not found in %s: %s", pre, symbol, path, msg);
    }
    p->dl = dl;
    *(void **)&p->fn = fn;
    PetscCall(PetscStrncpy(p->path, path, sizeof(p->path)));
    PetscCall(PetscStrncpy(p->symbol, symbol, sizeof(p->symbol)));
  }
  UmatKernelInit(p, &mat->kernel);
  PetscFunctionReturn(0);
}

static PetscErrorCode MaterialView_Umat(Material mat, PetscViewer v)
{
  const UmatParams *p = (const UmatParams *)mat->data;

  PetscFunctionBeginUser;
  PetscCall(PetscViewerASCIIPrintf(v, "UMAT %s from %s; NSTATV %d, NPROPS %d; history %d doubles per point\n", p->symbol, p->path[0] ? p->path : "(none)", p->nstatev, p->nprops, UMAT_NHIST(p->nstatev)));
  if (p->nprops) {
    PetscCall(PetscViewerASCIIPrintf(v, "PROPS"));
    PetscCall(PetscViewerASCIIUseTabs(v, PETSC_FALSE));
    for (int i = 0; i < p->nprops; i++) PetscCall(PetscViewerASCIIPrintf(v, " %g", p->props[i]));
    PetscCall(PetscViewerASCIIPrintf(v, "\n"));
    PetscCall(PetscViewerASCIIUseTabs(v, PETSC_TRUE));
  }
  PetscFunctionReturn(0);
}

static PetscErrorCode MaterialDestroy_Umat(Material mat)
{
  PetscFunctionBeginUser;
  UmatClose((UmatParams *)mat->data);
  PetscCall(PetscFree(mat->data));
  PetscFunctionReturn(0);
}

PETSC_INTERN PetscErrorCode MaterialCreate_Umat(Material mat);
PetscErrorCode MaterialCreate_Umat(Material mat)
{
  UmatParams *p;

  PetscFunctionBeginUser;
  PetscCall(PetscNew(&p));
  PetscCall(PetscStrncpy(p->symbol, "umat_", sizeof(p->symbol)));
  memset(p->cmname, ' ', sizeof(p->cmname));
  memcpy(p->cmname, "UMAT", 4);
  mat->data               = p;
  mat->ops.setfromoptions = MaterialSetFromOptions_Umat;
  mat->ops.view           = MaterialView_Umat;
  mat->ops.destroy        = MaterialDestroy_Umat;
  UmatKernelInit(p, &mat->kernel);
  PetscFunctionReturn(0);
}
