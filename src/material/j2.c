/* Finite-strain J2 elasto-plasticity with logarithmic elastic strains
   (Simo 1992; Eterovic & Bathe 1990; de Souza Neto, Peric & Owen (EPO),
   "Computational Methods for Plasticity", ch. 14).

   F = Fe Fp, b_e = Fe Fe^T, Cp^{-1} = Fp^{-1} Fp^{-T}. Trial state b_tr = F Cp^{-1}_n F^T,
   eps_tr = 1/2 ln b_tr; the small-strain J2 radial return (EPO ch. 7) acts on the principal
   logarithmic strains; the exponential-map flow update gives b_e = exp(2 eps_e) coaxial with
   b_tr. Everything is computed in the eigenbasis of b_tr.

   The first part of this file is the model on plain arrays (include/material_j2.h); the second
   is the material type "j2": its options (prefix material_, or the material's own prefix set
   with MaterialSetOptionsPrefix), view and kernel table. */
#include <float.h>
#include <math.h>
#include <stddef.h>
#include <string.h>

#include "material_impl.h"
#include "material_j2.h"
#include "options.h"
#include "tensor.h"

int J2ParamsSetup(J2Params *mp)
{
  if (!(mp->E > 0.0) || !(mp->nu > -1.0) || !(mp->nu < 0.5)) return 1;
  mp->K = mp->E / (3.0 * (1.0 - 2.0 * mp->nu));
  mp->G = mp->E / (2.0 * (1.0 + mp->nu));
  if (mp->rtol <= 0.0) mp->rtol = 1e-12;
  if (mp->maxit <= 0) mp->maxit = 50;
  return 0;
}

double J2YieldStress(const J2Params *mp, double ep, double *dsy)
{
  double sy, h;
  if (mp->law == HARDENING_SWIFT) {
    /* sigma_y = K (eps0 + ep)^n,  d sigma_y/d ep = n K (eps0 + ep)^(n-1) */
    const double x = mp->sweps0 + ep;
    if (x > 0.0) { /* x^n = exp(n ln x): two cheaper calls than pow, the same to a few ulps */
      sy = mp->swK * exp(mp->swn * log(x));
      h  = mp->swn * sy / x;
    } else { /* limit x -> 0+ (slope infinite for n < 1) */
      sy = mp->swn > 0.0 ? 0.0 : mp->swK;
      h  = mp->swn == 1.0 ? mp->swK : (mp->swn < 1.0 && mp->swn > 0.0 ? HUGE_VAL : 0.0);
    }
  } else {
    sy = mp->sy0 + mp->H * ep;
    h  = mp->H;
  }
  if (dsy) *dsy = h;
  return sy;
}

void J2HistoryInit(double h[J2_NHIST])
{
  h[0] = h[1] = h[2] = 1.0;
  h[3] = h[4] = h[5] = 0.0;
  h[J2_HIST_EP] = 0.0;
}

/* sigma_y(ep) >= 0, decided without evaluating the power of the Swift law: for x = eps0 + ep > 0
   K x^n has the sign of K; at x <= 0 J2YieldStress takes the limit (0 for n > 0, K for n = 0). */
static int yield_nonnegative(const J2Params *mp, double ep)
{
  if (mp->law == HARDENING_SWIFT) {
    const double x = mp->sweps0 + ep;
    if (x > 0.0) return mp->swK >= 0.0;
    return (mp->swn > 0.0 ? 0.0 : mp->swK) >= 0.0;
  }
  return mp->sy0 + mp->H * ep >= 0.0;
}

/* Scalar return map (radial return, EPO ch. 7):  r(dg) = q_tr - 3G dg - sigma_y(ep_n + dg) = 0, dg > 0.
   r(0) > 0 and r(q_tr/3G) = -sigma_y <= 0 bracket the root; Newton steps that leave the
   current bracket (or are not finite, e.g. an infinite Swift slope at ep = 0) are replaced
   by bisection; maxit bounds the number of updates. sy_n, Hp_n: sigma_y and its slope at ep_n
   (dg = 0, the first iterate), already evaluated by the caller's yield check. Returns 0 on
   convergence with dg and H' = d sigma_y/d ep at ep_n + dg. */
static int return_map(const J2Params *mp, double q_tr, double ep_n, double sy_n, double Hp_n, double *dg_out, double *Hp_out)
{
  const double G3  = 3.0 * mp->G;
  const double tol = mp->rtol * q_tr;
  double       lo = 0.0, hi = q_tr / G3, dg = 0.0, Hp = Hp_n, sy = sy_n;
  if (!yield_nonnegative(mp, ep_n + hi)) return 1; /* no bracket (softening to negative yield stress) */
  for (int it = 0;; it++) {
    if (it > 0) sy = J2YieldStress(mp, ep_n + dg, &Hp);
    const double r = q_tr - G3 * dg - sy;
    if (fabs(r) <= tol) break;
    if (it >= mp->maxit) return 1;
    if (r > 0.0) lo = dg;
    else hi = dg;
    double dn = dg + r / (G3 + Hp); /* Newton: dr/ddg = -(3G + H') */
    if (!(dn > lo && dn < hi)) dn = 0.5 * (lo + hi);
    if (fabs(dn - dg) <= 4.0 * DBL_EPSILON * dn) { /* stalled at round-off */
      dg = dn;
      J2YieldStress(mp, ep_n + dg, &Hp);
      break;
    }
    dg = dn;
  }
  *dg_out = dg;
  *Hp_out = Hp;
  return 0;
}

/* (ln x - ln y)/(x - y) for x, y > 0 from ex = ln x / 2, ey = ln y / 2 (already computed):
   with m = (x+y)/2, t = (x-y)/(x+y):  ln x - ln y = 2 atanh(t), x - y = 2 m t, so the ratio is
   atanh(t)/(m t) = (1 + t^2/3 + t^4/5 + t^6/7 + t^8/9 + ...)/m, the series used for
   |t| < 1e-2 (truncation t^10/11 < 1e-21). Otherwise 2 (ex - ey)/(x - y): x - y is exact to
   an ulp, and the difference of the logarithms has an absolute error of a few ulps of
   max(|ln x|, |ln y|), relative to it at most about 1e-14 max(|ln x|, |ln y|) for |t| >= 1e-2. */
static inline double dlog_ratio(double x, double y, double ex, double ey)
{
  const double t = (x - y) / (x + y);
  if (fabs(t) < 1e-2) {
    const double t2 = t * t;
    return 2.0 * (1.0 + t2 * (1.0 / 3.0 + t2 * (0.2 + t2 * (1.0 / 7.0 + t2 / 9.0)))) / (x + y);
  }
  return 2.0 * (ex - ey) / (x - y);
}

static void fail_outputs(const double hn[J2_NHIST], double tau[9], double *dtau, double h[J2_NHIST])
{
  for (int i = 0; i < 9; i++) tau[i] = 0.0;
  if (dtau)
    for (int i = 0; i < 81; i++) dtau[i] = 0.0;
  for (int i = 0; i < J2_NHIST; i++) h[i] = hn[i];
}

int J2Update(const J2Params *mp, const double F[9], const double hn[J2_NHIST], double tau[9], double *dtau, double h[J2_NHIST], int *plastic)
{
  const double K = mp->K, G = mp->G;
  const double s32 = 1.224744871391589049; /* sqrt(3/2) */
  if (plastic) *plastic = 0;

  const double J = t3_det(F);
  if (!(J > 0.0) || !isfinite(J)) {
    fail_outputs(hn, tau, dtau, h);
    return MAT_ERR_JACOBIAN;
  }

  /* trial elastic left Cauchy-Green tensor b_tr = F Cp^{-1}_n F^T */
  const double Cpi[9] = {hn[0], hn[3], hn[5], hn[3], hn[1], hn[4], hn[5], hn[4], hn[2]};
  double       Gm[9], b[9], lam[3], Q[9];
  t3_mult(Cpi, F, Gm); /* Gm = Cp^{-1} F^T */
  t3_mul(F, Gm, b);
  b[1] = b[3] = 0.5 * (b[1] + b[3]);
  b[2] = b[6] = 0.5 * (b[2] + b[6]);
  b[5] = b[7] = 0.5 * (b[5] + b[7]);
  t3_sym_eig(b, lam, Q);
  if (!(lam[0] > 0.0 && lam[1] > 0.0 && lam[2] > 0.0)) {
    fail_outputs(hn, tau, dtau, h);
    return MAT_ERR_JACOBIAN;
  }

  /* principal trial log strains, volumetric/deviatoric split, trial von Mises stress */
  double e[3], ed[3];
  for (int a = 0; a < 3; a++) e[a] = 0.5 * log(lam[a]);
  const double ev = e[0] + e[1] + e[2];
  for (int a = 0; a < 3; a++) ed[a] = e[a] - ev / 3.0;
  const double nrm  = sqrt(ed[0] * ed[0] + ed[1] * ed[1] + ed[2] * ed[2]);
  const double q_tr = s32 * 2.0 * G * nrm; /* q = sqrt(3/2) |2G dev eps| */
  const double ep_n = hn[J2_HIST_EP];

  /* c1, c2: coefficients of the small-strain consistent J2 tangent (EPO ch. 7)
     D = K 1(x)1 + 2G c1 I_dev + c2 N(x)N,  elastic: c1 = 1, c2 = 0 */
  double c1 = 1.0, c2 = 0.0, dg = 0.0, n[3] = {0.0, 0.0, 0.0};
  int    isplastic = 0;
  if (q_tr > 0.0) {
    double       Hp_n;
    const double sy_n = J2YieldStress(mp, ep_n, &Hp_n);
    if (q_tr - sy_n > 0.0) {
      double Hp;
      if (return_map(mp, q_tr, ep_n, sy_n, Hp_n, &dg, &Hp)) {
        fail_outputs(hn, tau, dtau, h);
        return MAT_ERR_RETURNMAP;
      }
      isplastic = 1;
      for (int a = 0; a < 3; a++) n[a] = ed[a] / nrm;
      c1 = 1.0 - 3.0 * G * dg / q_tr;
      c2 = 6.0 * G * G * (dg / q_tr - 1.0 / (3.0 * G + Hp));
      if (!isfinite(c2)) c2 = 6.0 * G * G * dg / q_tr; /* non-finite H': take 1/(3G+H') -> 0 */
    }
  }

  /* principal Kirchhoff stress (Hencky law + radial return): tau_a = K ev + 2G (1 - 3G dg/q_tr) ed_a */
  double tp[3];
  for (int a = 0; a < 3; a++) tp[a] = K * ev + 2.0 * G * c1 * ed[a];
  /* tau = Q diag(tp) Q^T */
  for (int i = 0; i < 3; i++)
    for (int j = i; j < 3; j++) {
      const double v = Q[3 * i] * tp[0] * Q[3 * j] + Q[3 * i + 1] * tp[1] * Q[3 * j + 1] + Q[3 * i + 2] * tp[2] * Q[3 * j + 2];
      tau[3 * i + j] = tau[3 * j + i] = v;
    }

  /* history update */
  if (isplastic) {
    /* eps_e = eps_tr - dg sqrt(3/2) n; b_e = exp(2 eps_e) = Q diag(lam_a exp(-2 sqrt(3/2) dg n_a)) Q^T;
       Cp^{-1} = F^{-1} b_e F^{-T} (exponential-map flow update; det F = J > 0 checked above) */
    double be[3], Fi[9], B[9], Y[9], C[9];
    for (int a = 0; a < 3; a++) be[a] = exp(2.0 * (e[a] - dg * s32 * n[a]));
    for (int i = 0; i < 3; i++)
      for (int j = i; j < 3; j++)
        B[3 * i + j] = B[3 * j + i] = Q[3 * i] * be[0] * Q[3 * j] + Q[3 * i + 1] * be[1] * Q[3 * j + 1] + Q[3 * i + 2] * be[2] * Q[3 * j + 2];
    const double iJ = 1.0 / J;
    Fi[0] = (F[4] * F[8] - F[5] * F[7]) * iJ;
    Fi[1] = (F[2] * F[7] - F[1] * F[8]) * iJ;
    Fi[2] = (F[1] * F[5] - F[2] * F[4]) * iJ;
    Fi[3] = (F[5] * F[6] - F[3] * F[8]) * iJ;
    Fi[4] = (F[0] * F[8] - F[2] * F[6]) * iJ;
    Fi[5] = (F[2] * F[3] - F[0] * F[5]) * iJ;
    Fi[6] = (F[3] * F[7] - F[4] * F[6]) * iJ;
    Fi[7] = (F[1] * F[6] - F[0] * F[7]) * iJ;
    Fi[8] = (F[0] * F[4] - F[1] * F[3]) * iJ;
    t3_mul(Fi, B, Y);
    t3_mult(Y, Fi, C);
    h[0] = C[0];
    h[1] = C[4];
    h[2] = C[8];
    h[3] = 0.5 * (C[1] + C[3]);
    h[4] = 0.5 * (C[5] + C[7]);
    h[5] = 0.5 * (C[2] + C[6]);
    h[J2_HIST_EP] = ep_n + dg;
  } else {
    for (int i = 0; i < J2_NHIST; i++) h[i] = hn[i];
  }
  if (plastic) *plastic = isplastic;
  if (!dtau) return MAT_OK;

  /* Tangent d tau / d F_kL, in the eigenbasis q_a (columns of Q) of b_tr.
     d b_tr = dF Gm + (dF Gm)^T; for dF = e_k (x) E_L:  X_ab = (Q^T db Q)_ab = u_a w_b + w_a u_b,
     u_a = Q_ka, w_a = (Gm Q)_La.  d eps_ab = 1/2 Gamma_ab X_ab with Gamma_ab = (ln lam_a -
     ln lam_b)/(lam_a - lam_b) (Daleckii-Krein), Gamma_aa = 1/lam_a; d tau' = D : d eps' on the
     diagonal (D_ab = K - 2G c1/3 + 2G c1 delta_ab + c2 n_a n_b), and the off-diagonal entries
     d tau'_ab = (tau_a - tau_b)/(lam_a - lam_b) X_ab = 2G c1 (1/2 Gamma_ab) X_ab. Then
     d tau = Q d tau' Q^T:
       d tau_ij/d F_kL = sum_a N_a,ij P_a,kL + sum_{a<b} M_ab,ij g_ab S_ab,kL
     with N_a = q_a (x) q_a, M_ab = q_a (x) q_b + q_b (x) q_a (symmetric in ij),
       V_b,kL = Q_kb w_b / lam_b        (= d eps'_bb for dF = e_k (x) E_L),
       P_a,kL = sum_b D_ab V_b,kL       (= d tau'_aa),
       S_ab,kL = Q_ka w_b + w_a Q_kb    (= X_ab),   g_ab = G c1 Gamma_ab.
     Six rank-one terms on the 6 x 9 array of the independent ij (00 11 22 01 12 02), copied to
     the symmetric rows. */
  double GQ[9]; /* GQ[3L+a] = (Gm Q)_La = w_a for the column L */
  t3_mul(Gm, Q, GQ);
  const double G2c1 = 2.0 * G * c1, Kd = K - G2c1 / 3.0;
  const double g01 = G * c1 * dlog_ratio(lam[0], lam[1], e[0], e[1]);
  const double g02 = G * c1 * dlog_ratio(lam[0], lam[2], e[0], e[2]);
  const double g12 = G * c1 * dlog_ratio(lam[1], lam[2], e[1], e[2]);
  const double il[3] = {1.0 / lam[0], 1.0 / lam[1], 1.0 / lam[2]};
  double       R[6][9]; /* rows: P_0, P_1, P_2, g01 S_01, g12 S_12, g02 S_02 (kL = 3k + L) */
  for (int k = 0; k < 3; k++)
    for (int L = 0; L < 3; L++) {
      const int     kL = 3 * k + L;
      const double *u = Q + 3 * k, *w = GQ + 3 * L;
      const double  v0 = u[0] * w[0] * il[0], v1 = u[1] * w[1] * il[1], v2 = u[2] * w[2] * il[2];
      const double  vol = Kd * (v0 + v1 + v2), nv = c2 * (n[0] * v0 + n[1] * v1 + n[2] * v2);
      R[0][kL] = vol + G2c1 * v0 + n[0] * nv;
      R[1][kL] = vol + G2c1 * v1 + n[1] * nv;
      R[2][kL] = vol + G2c1 * v2 + n[2] * nv;
      R[3][kL] = g01 * (u[0] * w[1] + w[0] * u[1]);
      R[4][kL] = g12 * (u[1] * w[2] + w[1] * u[2]);
      R[5][kL] = g02 * (u[0] * w[2] + w[0] * u[2]);
    }
  /* the coefficients of the six rows for each independent ij */
  static const int I6[6] = {0, 1, 2, 0, 1, 0}, J6[6] = {0, 1, 2, 1, 2, 2};
  for (int r = 0; r < 6; r++) {
    const int    i = I6[r], j = J6[r];
    const double qi0 = Q[3 * i], qi1 = Q[3 * i + 1], qi2 = Q[3 * i + 2], qj0 = Q[3 * j], qj1 = Q[3 * j + 1], qj2 = Q[3 * j + 2];
    const double a0 = qi0 * qj0, a1 = qi1 * qj1, a2 = qi2 * qj2;
    const double m01 = qi0 * qj1 + qi1 * qj0, m12 = qi1 * qj2 + qi2 * qj1, m02 = qi0 * qj2 + qi2 * qj0;
    double      *row = dtau + 9 * (3 * i + j);
    for (int kL = 0; kL < 9; kL++) row[kL] = a0 * R[0][kL] + a1 * R[1][kL] + a2 * R[2][kL] + m01 * R[3][kL] + m12 * R[4][kL] + m02 * R[5][kL];
    if (i != j)
      for (int kL = 0; kL < 9; kL++) dtau[9 * (3 * j + i) + kL] = row[kL];
  }
  return MAT_OK;
}

/* ------------------------------------------------------------------------------------------ */
/* the kernel table                                                                            */
/* ------------------------------------------------------------------------------------------ */
static int J2KernelUpdate(const void *ctx, const double F[9], const double *hn, double tau[9], double *dtau, double *h, int *plastic)
{
  return J2Update((const J2Params *)ctx, F, hn, tau, dtau, h, plastic);
}

static void J2KernelHistoryInit(const void *ctx, double *h)
{
  (void)ctx;
  J2HistoryInit(h);
}

static double J2KernelPlasticStrain(const void *ctx, const double *h)
{
  (void)ctx;
  return h[J2_HIST_EP];
}

void J2KernelInit(const J2Params *mp, MaterialKernel *k)
{
  k->nhist          = J2_NHIST;
  k->ctx            = mp;
  k->update         = J2KernelUpdate;
  k->history_init   = J2KernelHistoryInit;
  k->plastic_strain = J2KernelPlasticStrain;
  k->set_point      = NULL;
  k->failed_point   = NULL;
  k->set_increment  = NULL;
}

/* ------------------------------------------------------------------------------------------ */
/* the material type "j2"                                                                      */
/* ------------------------------------------------------------------------------------------ */
/* The options of J2Params (elasticity, hardening law, return-map controls), read inside the
   caller's PetscOptionsBegin block with the caller's prefix (the material's: "material_" by
   default, e.g. "body_die_material_" for a body's), validated -- the messages name the options
   under that prefix, PetscOptionsObject->prefix --, then J2ParamsSetup.
   Shared by the types built on J2's elasticity and hardening (j2, hill48, yld91). */
PetscErrorCode J2ParamsSetFromOptions(PetscOptionItems *PetscOptionsObject, MPI_Comm comm, J2Params *mp)
{
  const char *hard_types[] = {"linear", "swift", "HardeningLaw", "HARDENING_", NULL};
  PetscInt    ht           = (PetscInt)mp->law, maxit;
  const char *pre          = PetscOptionsObject->prefix ? PetscOptionsObject->prefix : "";

  PetscFunctionBeginUser;
  PetscCall(PetscOptionsReal("-E", "Young's modulus", NULL, mp->E, &mp->E, NULL));
  PetscCall(PetscOptionsReal("-nu", "Poisson's ratio", NULL, mp->nu, &mp->nu, NULL));
  PetscCall(PetscOptionsEList("-hardening", "Hardening law", NULL, hard_types, 2, hard_types[ht], &ht, NULL));
  mp->law = (HardeningLaw)ht;
  PetscCall(PetscOptionsReal("-yield", "Linear hardening: initial yield stress", NULL, mp->sy0, &mp->sy0, NULL));
  PetscCall(PetscOptionsReal("-hardening_modulus", "Linear hardening: slope", NULL, mp->H, &mp->H, NULL));
  PetscCall(PetscOptionsReal("-swift_K", "Swift: K in K (eps0 + ep)^n", NULL, mp->swK, &mp->swK, NULL));
  PetscCall(PetscOptionsReal("-swift_eps0", "Swift: eps0", NULL, mp->sweps0, &mp->sweps0, NULL));
  PetscCall(PetscOptionsReal("-swift_n", "Swift: exponent n", NULL, mp->swn, &mp->swn, NULL));
  PetscCheck(mp->E > 0 && PetscIsNormalReal(mp->E), comm, PETSC_ERR_USER_INPUT, "-%sE %g must be positive", pre, (double)mp->E);
  PetscCheck(mp->nu > -1 && mp->nu < 0.5, comm, PETSC_ERR_USER_INPUT, "-%snu %g must lie in (-1, 0.5)", pre, (double)mp->nu);
  if (mp->law == HARDENING_LINEAR) {
    PetscCheck(mp->sy0 > 0 && PetscIsNormalReal(mp->sy0), comm, PETSC_ERR_USER_INPUT, "-%syield %g must be positive", pre, (double)mp->sy0);
    PetscCheck(mp->H >= 0 && (mp->H == 0 || PetscIsNormalReal(mp->H)), comm, PETSC_ERR_USER_INPUT, "-%shardening_modulus %g must be >= 0", pre, (double)mp->H);
  } else {
    PetscCheck(mp->swK > 0 && PetscIsNormalReal(mp->swK), comm, PETSC_ERR_USER_INPUT, "-%sswift_K %g must be positive", pre, (double)mp->swK);
    PetscCheck(mp->sweps0 > 0 && PetscIsNormalReal(mp->sweps0), comm, PETSC_ERR_USER_INPUT, "-%sswift_eps0 %g must be positive", pre, (double)mp->sweps0);
    PetscCheck(mp->swn >= 0 && mp->swn < 1, comm, PETSC_ERR_USER_INPUT, "-%sswift_n %g must lie in [0, 1)", pre, (double)mp->swn);
  }
  maxit = mp->maxit;
  PetscCall(PetscOptionsReal("-return_rtol", "Relative tolerance of the local return map", NULL, mp->rtol, &mp->rtol, NULL));
  PetscCall(PetscOptionsInt("-return_maxit", "Iteration limit of the local return map", NULL, maxit, &maxit, NULL));
  PetscCheck(mp->rtol > 0 && mp->rtol < 1, comm, PETSC_ERR_USER_INPUT, "-%sreturn_rtol %g must lie in (0, 1)", pre, (double)mp->rtol);
  PetscCheck(maxit >= 1, comm, PETSC_ERR_USER_INPUT, "-%sreturn_maxit %d must be >= 1", pre, (int)maxit);
  mp->maxit = (int)maxit;
  PetscCheck(J2ParamsSetup(mp) == 0, comm, PETSC_ERR_USER_INPUT, "invalid material parameters");
  PetscFunctionReturn(0);
}

PetscErrorCode J2ParamsView(const J2Params *mp, PetscViewer v)
{
  PetscFunctionBeginUser;
  PetscCall(PetscViewerASCIIPrintf(v, "E = %g, nu = %g (K = %g, G = %g)\n", mp->E, mp->nu, mp->K, mp->G));
  if (mp->law == HARDENING_LINEAR) PetscCall(PetscViewerASCIIPrintf(v, "linear hardening: sigma_y = %g + %g ep\n", mp->sy0, mp->H));
  else PetscCall(PetscViewerASCIIPrintf(v, "Swift hardening: sigma_y = %g (%g + ep)^%g\n", mp->swK, mp->sweps0, mp->swn));
  PetscFunctionReturn(0);
}

/* the defaults of J2Params' options (those of the benchmark's aluminium) */
void J2ParamsDefaults(J2Params *mp)
{
  memset(mp, 0, sizeof(*mp));
  mp->E      = 69004;
  mp->nu     = 0.3;
  mp->law    = HARDENING_SWIFT;
  mp->sy0    = 100;
  mp->H      = 0;
  mp->swK    = 589;
  mp->sweps0 = 1e-4;
  mp->swn    = 0.216;
  mp->rtol   = 1e-12;
  mp->maxit  = 50;
  J2ParamsSetup(mp);
}

static PetscErrorCode MaterialSetFromOptions_J2(Material mat)
{
  J2Params *mp   = (J2Params *)mat->data;
  MPI_Comm  comm = mat->comm;
  char      title[512];

  PetscFunctionBeginUser;
  PetscCall(MaterialOptionsTitle(mat, "j2", "finite-strain J2 plasticity (log strains, isotropic hardening)", title, sizeof(title)));
  PetscOptionsBegin(comm, mat->prefix, title, "Material");
  PetscCall(J2ParamsSetFromOptions(PetscOptionsObject, comm, mp));
  PetscOptionsEnd();
  mat->modulus = mp->E;
  PetscFunctionReturn(0);
}

static PetscErrorCode MaterialView_J2(Material mat, PetscViewer v)
{
  const J2Params *mp = (const J2Params *)mat->data;

  PetscFunctionBeginUser;
  PetscCall(J2ParamsView(mp, v));
  PetscCall(PetscViewerASCIIPrintf(v, "return map: rtol %g, maxit %d; history %d doubles per point\n", mp->rtol, mp->maxit, J2_NHIST));
  PetscFunctionReturn(0);
}

static PetscErrorCode MaterialDestroy_J2(Material mat)
{
  PetscFunctionBeginUser;
  PetscCall(PetscFree(mat->data));
  PetscFunctionReturn(0);
}

/* the defaults of the options */
PETSC_INTERN PetscErrorCode MaterialCreate_J2(Material mat);
PetscErrorCode MaterialCreate_J2(Material mat)
{
  J2Params *mp;

  PetscFunctionBeginUser;
  PetscCall(PetscNew(&mp));
  J2ParamsDefaults(mp);
  PetscCheck(J2ParamsSetup(mp) == 0, mat->comm, PETSC_ERR_PLIB, "invalid default J2 parameters");
  mat->data               = mp;
  mat->ops.setfromoptions = MaterialSetFromOptions_J2;
  mat->ops.view           = MaterialView_J2;
  mat->ops.destroy        = MaterialDestroy_J2;
  J2KernelInit(mp, &mat->kernel);
  PetscFunctionReturn(0);
}
