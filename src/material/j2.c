/* Finite-strain J2 elasto-plasticity with logarithmic elastic strains
   (Simo 1992; Eterovic & Bathe 1990; de Souza Neto, Peric & Owen (EPO),
   "Computational Methods for Plasticity", ch. 14).

   F = Fe Fp, b_e = Fe Fe^T, Cp^{-1} = Fp^{-1} Fp^{-T}. Trial state b_tr = F Cp^{-1}_n F^T,
   eps_tr = 1/2 ln b_tr; the small-strain J2 radial return (EPO ch. 7) acts on the principal
   logarithmic strains; the exponential-map flow update gives b_e = exp(2 eps_e) coaxial with
   b_tr. Everything is computed in the eigenbasis of b_tr.

   The first part of this file is the model on plain arrays (include/material_j2.h); the second
   is the material type "j2": its options (prefix material_), view and kernel table. */
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
    if (x > 0.0) {
      sy = mp->swK * pow(x, mp->swn);
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

/* Scalar return map (radial return, EPO ch. 7):  r(dg) = q_tr - 3G dg - sigma_y(ep_n + dg) = 0, dg > 0.
   r(0) > 0 and r(q_tr/3G) = -sigma_y <= 0 bracket the root; Newton steps that leave the
   current bracket (or are not finite, e.g. an infinite Swift slope at ep = 0) are replaced
   by bisection; maxit bounds the number of updates. Returns 0 on convergence with dg and
   H' = d sigma_y/d ep at ep_n + dg. */
static int return_map(const J2Params *mp, double q_tr, double ep_n, double *dg_out, double *Hp_out)
{
  const double G3  = 3.0 * mp->G;
  const double tol = mp->rtol * q_tr;
  double       lo = 0.0, hi = q_tr / G3, dg = 0.0, Hp;
  {
    const double syhi = J2YieldStress(mp, ep_n + hi, NULL);
    if (!(syhi >= 0.0)) return 1; /* no bracket (softening to negative yield stress) */
  }
  for (int it = 0;; it++) {
    const double sy = J2YieldStress(mp, ep_n + dg, &Hp);
    const double r  = q_tr - G3 * dg - sy;
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

/* (ln x - ln y)/(x - y) for x, y > 0, accurate also for x ~ y: with m = (x+y)/2,
   t = (x-y)/(x+y):  ln x - ln y = 2 atanh(t), x - y = 2 m t  =>  atanh(t)/(m t),
   series 1 + t^2/3 + t^4/5 for |t| < 1e-4 (truncation t^6/7 < 1e-24). */
static inline double dlog_ratio(double x, double y)
{
  const double m = 0.5 * (x + y), t = (x - y) / (x + y);
  if (fabs(t) < 1e-4) {
    const double t2 = t * t;
    return (1.0 + t2 * (1.0 / 3.0 + 0.2 * t2)) / m;
  }
  return atanh(t) / (m * t);
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
  if (q_tr > 0.0 && q_tr - J2YieldStress(mp, ep_n, NULL) > 0.0) {
    double Hp;
    if (return_map(mp, q_tr, ep_n, &dg, &Hp)) {
      fail_outputs(hn, tau, dtau, h);
      return MAT_ERR_RETURNMAP;
    }
    isplastic = 1;
    for (int a = 0; a < 3; a++) n[a] = ed[a] / nrm;
    c1 = 1.0 - 3.0 * G * dg / q_tr;
    c2 = 6.0 * G * G * (dg / q_tr - 1.0 / (3.0 * G + Hp));
    if (!isfinite(c2)) c2 = 6.0 * G * G * dg / q_tr; /* non-finite H': take 1/(3G+H') -> 0 */
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
       Cp^{-1} = F^{-1} b_e F^{-T} (exponential-map flow update) */
    double be[3], Fi[9], B[9], Y[9], C[9];
    for (int a = 0; a < 3; a++) be[a] = exp(2.0 * (e[a] - dg * s32 * n[a]));
    for (int i = 0; i < 3; i++)
      for (int j = i; j < 3; j++)
        B[3 * i + j] = B[3 * j + i] = Q[3 * i] * be[0] * Q[3 * j] + Q[3 * i + 1] * be[1] * Q[3 * j + 1] + Q[3 * i + 2] * be[2] * Q[3 * j + 2];
    t3_inv(F, Fi);
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

  /* Tangent d tau / d F_kL, in the eigenbasis of b_tr:
     d b_tr = dF Gm + (dF Gm)^T; for dF = e_k (x) E_L:  (Q^T db Q)_ab = u_a w_b + w_a u_b with
     u_a = Q_ka, w_a = sum_n Gm_Ln Q_na = (Gm Q)_La.
     d eps_ab = 1/2 Gamma_ab (Q^T db Q)_ab, Gamma_ab = (ln lam_a - ln lam_b)/(lam_a - lam_b)
     (Daleckii-Krein), Gamma_aa = 1/lam_a.  d tau' = D : d eps', d tau = Q d tau' Q^T. */
  double GQ[9];
  t3_mul(Gm, Q, GQ);
  const double g01 = G * c1 * dlog_ratio(lam[0], lam[1]); /* 2G c1 * (1/2 Gamma_ab) */
  const double g02 = G * c1 * dlog_ratio(lam[0], lam[2]);
  const double g12 = G * c1 * dlog_ratio(lam[1], lam[2]);
  const double il[3] = {1.0 / lam[0], 1.0 / lam[1], 1.0 / lam[2]};
  const double G2c1 = 2.0 * G * c1;
  for (int k = 0; k < 3; k++) {
    const double *u = Q + 3 * k;
    for (int L = 0; L < 3; L++) {
      const double *w = GQ + 3 * L;
      /* diagonal of d eps' : 1/2 Gamma_aa * 2 u_a w_a */
      const double d0 = u[0] * w[0] * il[0], d1 = u[1] * w[1] * il[1], d2 = u[2] * w[2] * il[2];
      const double tr = d0 + d1 + d2, nd = n[0] * d0 + n[1] * d1 + n[2] * d2;
      const double vol = (K - G2c1 / 3.0) * tr;
      double       X[9];
      X[0] = vol + G2c1 * d0 + c2 * n[0] * nd;
      X[4] = vol + G2c1 * d1 + c2 * n[1] * nd;
      X[8] = vol + G2c1 * d2 + c2 * n[2] * nd;
      X[1] = X[3] = g01 * (u[0] * w[1] + w[0] * u[1]);
      X[2] = X[6] = g02 * (u[0] * w[2] + w[0] * u[2]);
      X[5] = X[7] = g12 * (u[1] * w[2] + w[1] * u[2]);
      /* Y = Q X, T = Y Q^T (symmetric) */
      double Y[9];
      t3_mul(Q, X, Y);
      const int col = 3 * k + L;
      for (int i = 0; i < 3; i++)
        for (int j = i; j < 3; j++) {
          const double v = Y[3 * i] * Q[3 * j] + Y[3 * i + 1] * Q[3 * j + 1] + Y[3 * i + 2] * Q[3 * j + 2];
          dtau[(3 * i + j) * 9 + col] = v;
          dtau[(3 * j + i) * 9 + col] = v;
        }
    }
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
}

/* ------------------------------------------------------------------------------------------ */
/* the material type "j2"                                                                      */
/* ------------------------------------------------------------------------------------------ */
/* The options of J2Params (elasticity, hardening law, return-map controls), read inside the
   caller's PetscOptionsBegin block with the prefix "material_", validated, then J2ParamsSetup.
   Shared by the types built on J2's elasticity and hardening (j2, hill48). */
PetscErrorCode J2ParamsSetFromOptions(PetscOptionItems *PetscOptionsObject, MPI_Comm comm, J2Params *mp)
{
  const char *hard_types[] = {"linear", "swift", "HardeningLaw", "HARDENING_", NULL};
  PetscInt    ht           = (PetscInt)mp->law, maxit;

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
  PetscCheck(mp->E > 0 && PetscIsNormalReal(mp->E), comm, PETSC_ERR_USER_INPUT, "-material_E %g must be positive", (double)mp->E);
  PetscCheck(mp->nu > -1 && mp->nu < 0.5, comm, PETSC_ERR_USER_INPUT, "-material_nu %g must lie in (-1, 0.5)", (double)mp->nu);
  if (mp->law == HARDENING_LINEAR) {
    PetscCheck(mp->sy0 > 0 && PetscIsNormalReal(mp->sy0), comm, PETSC_ERR_USER_INPUT, "-material_yield %g must be positive", (double)mp->sy0);
    PetscCheck(mp->H >= 0 && (mp->H == 0 || PetscIsNormalReal(mp->H)), comm, PETSC_ERR_USER_INPUT, "-material_hardening_modulus %g must be >= 0", (double)mp->H);
  } else {
    PetscCheck(mp->swK > 0 && PetscIsNormalReal(mp->swK), comm, PETSC_ERR_USER_INPUT, "-material_swift_K %g must be positive", (double)mp->swK);
    PetscCheck(mp->sweps0 > 0 && PetscIsNormalReal(mp->sweps0), comm, PETSC_ERR_USER_INPUT, "-material_swift_eps0 %g must be positive", (double)mp->sweps0);
    PetscCheck(mp->swn >= 0 && mp->swn < 1, comm, PETSC_ERR_USER_INPUT, "-material_swift_n %g must lie in [0, 1)", (double)mp->swn);
  }
  maxit = mp->maxit;
  PetscCall(PetscOptionsReal("-return_rtol", "Relative tolerance of the local return map", NULL, mp->rtol, &mp->rtol, NULL));
  PetscCall(PetscOptionsInt("-return_maxit", "Iteration limit of the local return map", NULL, maxit, &maxit, NULL));
  PetscCheck(mp->rtol > 0 && mp->rtol < 1, comm, PETSC_ERR_USER_INPUT, "-material_return_rtol %g must lie in (0, 1)", (double)mp->rtol);
  PetscCheck(maxit >= 1, comm, PETSC_ERR_USER_INPUT, "-material_return_maxit %d must be >= 1", (int)maxit);
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

  PetscFunctionBeginUser;
  PetscOptionsBegin(comm, "material_", "Material j2: finite-strain J2 plasticity (log strains, isotropic hardening)", "Material");
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
