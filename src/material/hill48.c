/* Finite-strain Hill 1948 anisotropic elasto-plasticity with logarithmic elastic strains
   (the log-strain framework of j2.c; anisotropic return map on the elastic log strain in the
   orthotropy frame: e.g. de Souza Neto, Peric & Owen, "Computational Methods for Plasticity",
   ch. 14; Caminero, Montans & Bathe 2011).

   Kinematics. F = Fe Fp, history Cp^{-1} = Fp^{-1} Fp^{-T} and the equivalent plastic strain ep
   (as J2). The polar decomposition F = R U gives the rotated trial elastic left Cauchy-Green
   tensor
       bb = R^T b_tr R = U Cp^{-1}_n U,      b_tr = F Cp^{-1}_n F^T,
   and the rotated trial log strain eb = 1/2 ln bb (material frame). With the orthotropy frame
   A = [rd, td = nd x rd, nd] of the sheet, the strain in that frame is e = A^T eb A; everything
   below is written in Mandel notation in that frame, components (11, 22, 33, 23, 31, 12), shear
   entries times sqrt 2.

   Elasticity (Hencky, isotropic): s = D e_e, D = 2G I + (K - 2G/3) m m^T, m = (1,1,1,0,0,0).
   Rotated Kirchhoff stress tau_b = A s A^T, Kirchhoff stress tau = R tau_b R^T.

   Yield (Hill 48, quadratic): phi = q(s) - sigma_y(ep), q^2 = s^T P s, with
       P = [G+H  -H   -G  ]  (normal block)      P_44 = L, P_55 = M, P_66 = N,
           [-H   F+H  -F  ]
           [-G   -F   F+G ]
   i.e. q^2 = F (s22-s33)^2 + G (s33-s11)^2 + H (s11-s22)^2 + 2L s23^2 + 2M s31^2 + 2N s12^2
   (von Mises: F = G = H = 1/2, L = M = N = 3/2). P m = 0: the flow is isochoric.
   r-values (plane stress, sigma_y the rolling-direction yield stress, G + H = 1):
       H = r0/(1+r0), G = 1/(1+r0), F = r0/(r90 (1+r0)), N = (r0+r90)(1+2 r45)/(2 r90 (1+r0)),
   and L = M = 3/2 (out-of-plane shears as von Mises).

   Return map (backward Euler, associated flow, work-equivalent ep):
       e_e = e_tr - lam P s,   s = D e_e,   ep = ep_n + lam q(s),   q(s) = sigma_y(ep).
   Because P m = 0 and D is isotropic, s = Xi(lam) s_tr with Xi = (I + 2G lam P)^{-1} and
   s_tr = D e_tr; in the eigenbasis of P (P = Phi diag(p) Phi^T, fixed by the parameters) it is
   componentwise z_i = z_tr,i / (1 + 2G lam p_i). The consistency condition is one scalar
   equation in lam:
       r(lam) = q(lam) - sigma_y(ep_n + lam q(lam)) = 0,
   with q decreasing and lam q increasing in lam (sigma_y non-decreasing), so r is strictly
   decreasing. It is solved by Newton's method on t = 2G pb lam / (1 + 2G pb lam) in [0, 1),
   pb = sum_i p_i^2 z_tr,i^2 / q_tr^2, safeguarded by bisection in the bracket; q and lam q are
   linear in t when the loaded p_i are equal, nearly linear otherwise. dr/dlam =
   -q [2G m_q^T Xi m_q + H'(1 - 2G lam m_q^T Xi m_q)], m_q = P s / q. For P = 3/2 I_dev (r = 1)
   this is J2's radial return with dg = lam q.

   Flow update (exponential map): eb_e = A e_e A^T, bb_e = exp(2 eb_e),
       Cp^{-1}_{n+1} = F^{-1} R bb_e R^T F^{-T} = U^{-1} bb_e U^{-1}.

   Consistent tangent: ds = D_alg de_tr with
       D_alg = Xi D + v w^T,  v = ds/dlam = -2G Xi P s,  w^T = -(1 - H' lam) m_q^T Xi D / (dr/dlam)
   (elastic: D_alg = D). The chain to dtau/dF, for each dF = e_k (x) E_L:
       dR = R Omega, Omega skew with axial vector omega = (tr U I - U)^{-1} axial(R^T dF - dF^T R)
       (from R^T dF = Omega U + dU and S W(w) + W(w) S = W((tr S I - S) w) for symmetric S);
       d bb = R^T db_tr R + bb Omega - Omega bb,  db_tr = dF Gm + (dF Gm)^T, Gm = Cp^{-1}_n F^T;
       d eb = Q [1/2 Gamma o (Q^T d bb Q)] Q^T (Daleckii-Krein in the eigenbasis Q of bb,
       Gamma_ab = (ln lam_a - ln lam_b)/(lam_a - lam_b), Gamma_aa = 1/lam_a);
       de = A^T d eb A,  ds = D_alg de,  d tau_b = A ds A^T,
       d tau = R (Omega tau_b - tau_b Omega + d tau_b) R^T
   (evaluated as below: vectors in the eigenbasis of bb, one precomputed 6x6 map for the chain
   d eb -> d tau_b, and the spin W(R omega) in the current frame).
   This is the exact derivative of the discrete update (up to the return map's tolerance).

   Objectivity: F -> Q F leaves U, bb, e, s and the history unchanged and gives R -> Q R,
   tau -> Q tau Q^T; rotating the axes and both configurations (F -> Q F Q^T, rd -> Q rd,
   nd -> Q nd, Cp^{-1} -> Q Cp^{-1} Q^T) gives tau -> Q tau Q^T.

   The kinematics (polar decomposition, trial log strain in the frame, flow update, the chain of
   the tangent) are src/material/aniso.c's, shared with yld91; this file holds the return map in
   stress space. The first part of this file is the model on plain arrays
   (include/material_hill48.h); the second is the material type "hill48": its options (prefix
   material_, or the material's own prefix), view and kernel table; elasticity, hardening and
   their options are J2's (material_j2.h). */
#include <float.h>
#include <math.h>

#include "material_aniso.h"
#include "material_hill48.h"
#include "material_impl.h"
#include "options.h"
#include "tensor.h"

void Hill48FromR(double r0, double r45, double r90, double *F, double *G, double *H, double *L, double *M, double *N)
{
  *H = r0 / (1.0 + r0);
  *G = 1.0 / (1.0 + r0);
  *F = r0 / (r90 * (1.0 + r0));
  *N = (r0 + r90) * (1.0 + 2.0 * r45) / (2.0 * r90 * (1.0 + r0));
  *L = *M = 1.5;
}

static void hill_eig(const HillParams *hp, double p[6], double Phi[36]);

int Hill48ParamsSetup(HillParams *hp)
{
  if (J2ParamsSetup(&hp->base)) return HILL48_ERR_ELASTIC;
  if (hp->from_r) {
    if (!(hp->r0 > 0.0 && hp->r45 > 0.0 && hp->r90 > 0.0) || !isfinite(hp->r0 + hp->r45 + hp->r90)) return HILL48_ERR_R;
    Hill48FromR(hp->r0, hp->r45, hp->r90, &hp->F, &hp->G, &hp->H, &hp->L, &hp->M, &hp->N);
  }
  {
    const double F = hp->F, G = hp->G, H = hp->H;
    if (!isfinite(F + G + H + hp->L + hp->M + hp->N)) return HILL48_ERR_CONVEX;
    if (!(F + G + H > 0.0 && F * G + G * H + H * F > 0.0 && hp->L > 0.0 && hp->M > 0.0 && hp->N > 0.0)) return HILL48_ERR_CONVEX;
  }
  /* the frame: unit normal, rolling direction made orthogonal to it, td = nd x rd */
  if (AnisoFrame(hp->rd, hp->nd, hp->A)) return HILL48_ERR_AXES;
  for (int i = 0; i < 36; i++) hp->P[i] = 0.0;
  hp->P[0]  = hp->G + hp->H;
  hp->P[1]  = hp->P[6] = -hp->H;
  hp->P[2]  = hp->P[12] = -hp->G;
  hp->P[7]  = hp->F + hp->H;
  hp->P[8]  = hp->P[13] = -hp->F;
  hp->P[14] = hp->F + hp->G;
  hp->P[21] = hp->L;
  hp->P[28] = hp->M;
  hp->P[35] = hp->N;
  hill_eig(hp, hp->p, hp->Phi);
  return HILL48_OK;
}


/* ---------- the return map ---------- */

/* y = M x (6x6) */
static void mv6(const double M[36], const double x[6], double y[6])
{
  for (int i = 0; i < 6; i++) {
    double s = 0.0;
    for (int j = 0; j < 6; j++) s += M[6 * i + j] * x[j];
    y[i] = s;
  }
}

/* The eigenbasis of P: its normal block by t3_sym_eig, the shear block is diagonal. */
/* The eigenbasis of P: its normal block by t3_sym_eig, the shear block is diagonal. */
static void hill_eig(const HillParams *hp, double p[6], double Phi[36])
{
  const double Pn[9] = {hp->P[0], hp->P[1], hp->P[2], hp->P[6], hp->P[7], hp->P[8], hp->P[12], hp->P[13], hp->P[14]};
  double       lam[3], V[9];
  t3_sym_eig(Pn, lam, V);
  for (int i = 0; i < 36; i++) Phi[i] = 0.0;
  for (int i = 0; i < 3; i++) {
    p[i] = lam[i] > 0.0 ? lam[i] : 0.0; /* the hydrostatic direction: 0 up to round-off */
    for (int j = 0; j < 3; j++) Phi[6 * i + j] = V[3 * i + j];
    p[3 + i]                   = hp->P[7 * (3 + i)];
    Phi[6 * (3 + i) + (3 + i)] = 1.0;
  }
}

/* state of the return map at lam: z (components of s in P's eigenbasis) and q */
static double hill_q(const double p[6], const double ztr[6], double c, double lam, double z[6])
{
  double q2 = 0.0;
  for (int i = 0; i < 6; i++) {
    z[i] = ztr[i] / (1.0 + c * lam * p[i]);
    q2 += p[i] * z[i] * z[i];
  }
  return sqrt(q2);
}

/* Solve r(lam) = q(lam) - sigma_y(ep_n + lam q(lam)) = 0 for lam >= 0, given r(0) > 0.
   The iteration variable is t = c pb lam / (1 + c pb lam) in [0, 1), c = 2G, with pb = the
   trial-weighted eigenvalue sum_i p_i^2 z_tr,i^2 / q_tr^2 of P (the initial slope of q): then
   z_i = z_tr,i (1 - t) / (1 - t + t p_i / pb), so that q and lam q are linear in t when the
   p_i of the loaded modes are equal (von Mises: this is J2's iteration on dg = lam q) and nearly
   linear otherwise. r is strictly decreasing in t; Newton, safeguarded by the bracket [0, 1)
   (bisection). Returns 0 with lam, z, q and H' at the solution. */
static int hill_return_map(const HillParams *hp, const double p[6], const double ztr[6], double q_tr, double ep_n, double *lam_out, double z[6], double *q_out, double *Hp_out)
{
  const J2Params *mp  = &hp->base;
  const double    c   = 2.0 * mp->G;
  const double    tol = mp->rtol * q_tr;
  double          lo = 0.0, hi = 1.0, t = 0.0, lam = 0.0, q, Hp, pb = 0.0;
  for (int i = 0; i < 6; i++) pb += p[i] * p[i] * ztr[i] * ztr[i];
  pb /= q_tr * q_tr;
  if (!(pb > 0.0) || !isfinite(pb)) return 1;
  for (int it = 0;; it++) {
    lam              = t / (c * pb * (1.0 - t));
    q                = hill_q(p, ztr, c, lam, z);
    const double sy  = J2YieldStress(mp, ep_n + lam * q, &Hp);
    const double r   = q - sy;
    double       mXm = 0.0; /* m^T Xi m, m = P s / q */
    for (int i = 0; i < 6; i++) mXm += p[i] * p[i] * z[i] * z[i] / (1.0 + c * lam * p[i]);
    mXm /= q * q;
    if (fabs(r) <= tol) break;
    if (it >= mp->maxit) return 1;
    if (r > 0.0) lo = t;
    else hi = t;
    /* dr/dlam, dlam/dt = 1/(c pb (1-t)^2) */
    const double drl = -q * (c * mXm + Hp * (1.0 - c * lam * mXm));
    const double drt = drl / (c * pb * (1.0 - t) * (1.0 - t));
    double       tn  = t - r / drt;
    if (!(tn > lo && tn < hi)) tn = 0.5 * (lo + hi);
    if (fabs(tn - t) <= 4.0 * DBL_EPSILON * tn) { /* stalled at round-off */
      t   = tn;
      lam = t / (c * pb * (1.0 - t));
      q   = hill_q(p, ztr, c, lam, z);
      J2YieldStress(mp, ep_n + lam * q, &Hp);
      break;
    }
    t = tn;
  }
  /* lam = 0: r(0) within the tolerance, the trial state on the yield surface (a converged plastic
     state evaluated again with no increment: the committed state at the start of a step, or an
     enhanced-strain iteration started from the committed parameters); the plastic branch with no
     flow, as J2's return map. Refusing it failed the element there and sent hex8_eas's local
     iteration to a cold start (doc/materials.md) */
  if (!isfinite(Hp) || !(lam >= 0.0)) return 1;
  *lam_out = lam;
  *q_out   = q;
  *Hp_out  = Hp;
  return 0;
}

/* the return map of AnisoReturnFn (include/material_aniso.h) */
static int hill_stress_return(const void *ctx, const double D[36], const double etr[6], const double str[6], double ep_n, double s[6], double ee[6], double *ep, double *Dalg, int *plastic)
{
  const HillParams *hp = (const HillParams *)ctx;
  const J2Params   *mp = &hp->base;
  const double      G  = mp->G;
  double            Ps[6], q_tr = 0.0;
  mv6(hp->P, str, Ps);
  for (int i = 0; i < 6; i++) q_tr += str[i] * Ps[i];
  q_tr = sqrt(q_tr > 0.0 ? q_tr : 0.0);

  double lam_p = 0.0;
  *plastic = 0;
  *ep      = ep_n;
  for (int i = 0; i < 6; i++) {
    s[i]  = str[i];
    ee[i] = etr[i];
  }
  if (q_tr > 0.0 && q_tr - J2YieldStress(mp, ep_n, NULL) > 0.0) {
    const double *p = hp->p, *Phi = hp->Phi;
    double        ztr[6], z[6], q, Hp;
    for (int i = 0; i < 6; i++) {
      ztr[i] = 0.0;
      for (int j = 0; j < 6; j++) ztr[i] += Phi[6 * j + i] * str[j];
    }
    if (hill_return_map(hp, p, ztr, q_tr, ep_n, &lam_p, z, &q, &Hp)) return 1;
    *plastic = 1;
    /* s = Phi z; e_e = e_tr - lam P s */
    mv6(Phi, z, s);
    mv6(hp->P, s, Ps);
    for (int i = 0; i < 6; i++) ee[i] = etr[i] - lam_p * Ps[i];
    if (Dalg) {
      /* D_alg = Xi D + v w^T, Xi = Phi diag(xi) Phi^T */
      const double c = 2.0 * G;
      double       Xi[36], xi[6], m[6], mXi[6], v[6], mXm = 0.0, w[6];
      for (int i = 0; i < 6; i++) xi[i] = 1.0 / (1.0 + c * lam_p * p[i]);
      for (int i = 0; i < 6; i++)
        for (int j = 0; j < 6; j++) {
          double t = 0.0;
          for (int a = 0; a < 6; a++) t += Phi[6 * i + a] * xi[a] * Phi[6 * j + a];
          Xi[6 * i + j] = t;
        }
      for (int i = 0; i < 6; i++) m[i] = Ps[i] / q;
      mv6(Xi, m, mXi); /* Xi symmetric: Xi m = (m^T Xi)^T */
      for (int i = 0; i < 6; i++) {
        v[i] = -c * q * mXi[i];
        mXm += m[i] * mXi[i];
      }
      const double dr = -q * (c * mXm + Hp * (1.0 - c * lam_p * mXm));
      for (int j = 0; j < 6; j++) {
        double t = 0.0;
        for (int i = 0; i < 6; i++) t += mXi[i] * D[6 * i + j];
        w[j] = -(1.0 - Hp * lam_p) * t / dr;
      }
      for (int i = 0; i < 6; i++)
        for (int j = 0; j < 6; j++) {
          double t = 0.0;
          for (int a = 0; a < 6; a++) t += Xi[6 * i + a] * D[6 * a + j];
          Dalg[6 * i + j] = t + v[i] * w[j];
        }
    }
    *ep = ep_n + lam_p * sqrt(s[0] * Ps[0] + s[1] * Ps[1] + s[2] * Ps[2] + s[3] * Ps[3] + s[4] * Ps[4] + s[5] * Ps[5]);
  } else if (Dalg) {
    for (int i = 0; i < 36; i++) Dalg[i] = D[i];
  }
  return 0;
}

int Hill48Update(const HillParams *hp, const double F[9], const double hn[HILL48_NHIST], double tau[9], double *dtau, double h[HILL48_NHIST], int *plastic)
{
  return AnisoLogUpdate(&hp->base, hp->A, hill_stress_return, hp, F, hn, tau, dtau, h, plastic);
}


/* ------------------------------------------------------------------------------------------ */
/* the kernel table                                                                            */
/* ------------------------------------------------------------------------------------------ */
static int Hill48KernelUpdate(const void *ctx, const double F[9], const double *hn, double tau[9], double *dtau, double *h, int *plastic)
{
  return Hill48Update((const HillParams *)ctx, F, hn, tau, dtau, h, plastic);
}

static void Hill48KernelHistoryInit(const void *ctx, double *h)
{
  (void)ctx;
  J2HistoryInit(h);
}

static double Hill48KernelPlasticStrain(const void *ctx, const double *h)
{
  (void)ctx;
  return h[HILL48_HIST_EP];
}

void Hill48KernelInit(const HillParams *hp, MaterialKernel *k)
{
  k->nhist          = HILL48_NHIST;
  k->ctx            = hp;
  k->update         = Hill48KernelUpdate;
  k->history_init   = Hill48KernelHistoryInit;
  k->plastic_strain = Hill48KernelPlasticStrain;
  k->set_point      = NULL;
  k->failed_point   = NULL;
  k->set_increment  = NULL;
}

/* ------------------------------------------------------------------------------------------ */
/* the material type "hill48"                                                                  */
/* ------------------------------------------------------------------------------------------ */
static PetscErrorCode MaterialSetFromOptions_Hill48(Material mat)
{
  HillParams *hp   = (HillParams *)mat->data;
  MPI_Comm    comm = mat->comm;
  const char *pre  = mat->prefix; /* the options' names in the messages: -<pre>hill_r0, ... */
  char        title[512];

  PetscFunctionBeginUser;
  PetscCall(MaterialOptionsTitle(mat, "hill48", "finite-strain Hill 1948 anisotropic plasticity (log strains, isotropic hardening)", title, sizeof(title)));
  PetscOptionsBegin(comm, mat->prefix, title, "Material");
  {
    const char *rname[3] = {"hill_r0", "hill_r45", "hill_r90"};
    const char *cname[6] = {"hill_F", "hill_G", "hill_H", "hill_L", "hill_M", "hill_N"};
    double     *rv[3]    = {&hp->r0, &hp->r45, &hp->r90};
    double     *cv[6]    = {&hp->F, &hp->G, &hp->H, &hp->L, &hp->M, &hp->N};
    PetscBool   rset = PETSC_FALSE, cset = PETSC_FALSE, set;
    PetscInt    n;
    PetscReal   v[3];

    PetscCall(J2ParamsSetFromOptions(PetscOptionsObject, comm, &hp->base));
    PetscCall(PetscOptionsReal("-hill_r0", "Hill 48: r-value at 0 deg to the rolling direction", NULL, hp->r0, &hp->r0, &set));
    rset = rset || set;
    PetscCall(PetscOptionsReal("-hill_r45", "Hill 48: r-value at 45 deg", NULL, hp->r45, &hp->r45, &set));
    rset = rset || set;
    PetscCall(PetscOptionsReal("-hill_r90", "Hill 48: r-value at 90 deg", NULL, hp->r90, &hp->r90, &set));
    rset = rset || set;
    PetscCall(PetscOptionsReal("-hill_F", "Hill 48 coefficient F (instead of the r-values)", NULL, hp->F, &hp->F, &set));
    cset = cset || set;
    PetscCall(PetscOptionsReal("-hill_G", "Hill 48 coefficient G", NULL, hp->G, &hp->G, &set));
    cset = cset || set;
    PetscCall(PetscOptionsReal("-hill_H", "Hill 48 coefficient H", NULL, hp->H, &hp->H, &set));
    cset = cset || set;
    PetscCall(PetscOptionsReal("-hill_L", "Hill 48 coefficient L (23 shear)", NULL, hp->L, &hp->L, &set));
    cset = cset || set;
    PetscCall(PetscOptionsReal("-hill_M", "Hill 48 coefficient M (31 shear)", NULL, hp->M, &hp->M, &set));
    cset = cset || set;
    PetscCall(PetscOptionsReal("-hill_N", "Hill 48 coefficient N (12 shear)", NULL, hp->N, &hp->N, &set));
    cset = cset || set;
    PetscCheck(!(rset && cset), comm, PETSC_ERR_USER_INPUT, "-%shill_r0/r45/r90 and -%shill_F/G/H/L/M/N exclude each other: give one set", pre, pre);
    if (cset) hp->from_r = 0;
    if (rset) hp->from_r = 1;
    for (int i = 0; i < 3 && hp->from_r; i++)
      PetscCheck(*rv[i] > 0 && PetscIsNormalReal(*rv[i]), comm, PETSC_ERR_USER_INPUT, "-%s%s %g must be positive", pre, rname[i], (double)*rv[i]);
    if (!hp->from_r) {
      for (int i = 0; i < 6; i++) PetscCheck(PetscIsNormalReal(*cv[i]) || *cv[i] == 0, comm, PETSC_ERR_USER_INPUT, "-%s%s %g must be finite", pre, cname[i], (double)*cv[i]);
      for (int i = 3; i < 6; i++) PetscCheck(*cv[i] > 0, comm, PETSC_ERR_USER_INPUT, "-%s%s %g must be positive", pre, cname[i], (double)*cv[i]);
      PetscCheck(hp->F + hp->G + hp->H > 0 && hp->F * hp->G + hp->G * hp->H + hp->H * hp->F > 0, comm, PETSC_ERR_USER_INPUT,
                 "-%shill_F %g, -%shill_G %g, -%shill_H %g give a non-convex yield surface (need F+G+H > 0 and FG+GH+HF > 0)", pre, (double)hp->F, pre, (double)hp->G, pre,
                 (double)hp->H);
    }
    for (int i = 0; i < 3; i++) v[i] = hp->rd[i];
    n = 3;
    PetscCall(PetscOptionsRealArray("-hill_rd", "Hill 48: rolling direction x,y,z", NULL, v, &n, &set));
    PetscCheck(!set || n == 3, comm, PETSC_ERR_USER_INPUT, "-%shill_rd needs 3 components x,y,z (got %d)", pre, (int)n);
    for (int i = 0; i < 3; i++) hp->rd[i] = v[i];
    for (int i = 0; i < 3; i++) v[i] = hp->nd[i];
    n = 3;
    PetscCall(PetscOptionsRealArray("-hill_normal", "Hill 48: sheet normal x,y,z", NULL, v, &n, &set));
    PetscCheck(!set || n == 3, comm, PETSC_ERR_USER_INPUT, "-%shill_normal needs 3 components x,y,z (got %d)", pre, (int)n);
    for (int i = 0; i < 3; i++) hp->nd[i] = v[i];
    {
      const double lr = sqrt(hp->rd[0] * hp->rd[0] + hp->rd[1] * hp->rd[1] + hp->rd[2] * hp->rd[2]);
      const double ln = sqrt(hp->nd[0] * hp->nd[0] + hp->nd[1] * hp->nd[1] + hp->nd[2] * hp->nd[2]);
      const double c  = (hp->rd[0] * hp->nd[0] + hp->rd[1] * hp->nd[1] + hp->rd[2] * hp->nd[2]) / (lr * ln);
      PetscCheck(lr > 0 && PetscIsNormalReal(lr), comm, PETSC_ERR_USER_INPUT, "-%shill_rd %g,%g,%g must be a non-zero vector", pre, hp->rd[0], hp->rd[1], hp->rd[2]);
      PetscCheck(ln > 0 && PetscIsNormalReal(ln), comm, PETSC_ERR_USER_INPUT, "-%shill_normal %g,%g,%g must be a non-zero vector", pre, hp->nd[0], hp->nd[1], hp->nd[2]);
      PetscCheck(fabs(c) <= 1e-6, comm, PETSC_ERR_USER_INPUT, "-%shill_rd %g,%g,%g and -%shill_normal %g,%g,%g must be orthogonal (cosine %g)", pre, hp->rd[0], hp->rd[1], hp->rd[2], pre, hp->nd[0],
                 hp->nd[1], hp->nd[2], c);
    }
    PetscCheck(Hill48ParamsSetup(hp) == HILL48_OK, comm, PETSC_ERR_USER_INPUT, "invalid Hill 48 parameters");
  }
  PetscOptionsEnd();
  mat->modulus = hp->base.E;
  PetscFunctionReturn(0);
}

static PetscErrorCode MaterialView_Hill48(Material mat, PetscViewer v)
{
  const HillParams *hp = (const HillParams *)mat->data;

  PetscFunctionBeginUser;
  PetscCall(J2ParamsView(&hp->base, v));
  if (hp->from_r) PetscCall(PetscViewerASCIIPrintf(v, "Hill 48 from r0 = %g, r45 = %g, r90 = %g: F = %g, G = %g, H = %g, L = %g, M = %g, N = %g\n", hp->r0, hp->r45, hp->r90, hp->F, hp->G, hp->H, hp->L, hp->M, hp->N));
  else PetscCall(PetscViewerASCIIPrintf(v, "Hill 48: F = %g, G = %g, H = %g, L = %g, M = %g, N = %g\n", hp->F, hp->G, hp->H, hp->L, hp->M, hp->N));
  PetscCall(PetscViewerASCIIPrintf(v, "rolling direction (%g, %g, %g), transverse (%g, %g, %g), normal (%g, %g, %g)\n", hp->A[0], hp->A[3], hp->A[6], hp->A[1], hp->A[4], hp->A[7], hp->A[2], hp->A[5],
                                   hp->A[8]));
  PetscCall(PetscViewerASCIIPrintf(v, "return map: rtol %g, maxit %d; history %d doubles per point\n", hp->base.rtol, hp->base.maxit, HILL48_NHIST));
  PetscFunctionReturn(0);
}

static PetscErrorCode MaterialDestroy_Hill48(Material mat)
{
  PetscFunctionBeginUser;
  PetscCall(PetscFree(mat->data));
  PetscFunctionReturn(0);
}

/* the defaults: J2's elasticity and hardening, isotropic r-values, rolling direction x, normal z */
PETSC_INTERN PetscErrorCode MaterialCreate_Hill48(Material mat);
PetscErrorCode MaterialCreate_Hill48(Material mat)
{
  HillParams *hp;

  PetscFunctionBeginUser;
  PetscCall(PetscNew(&hp));
  J2ParamsDefaults(&hp->base);
  hp->from_r = 1;
  hp->r0 = hp->r45 = hp->r90 = 1.0;
  hp->rd[0]                  = 1.0;
  hp->nd[2]                  = 1.0;
  PetscCheck(Hill48ParamsSetup(hp) == HILL48_OK, mat->comm, PETSC_ERR_PLIB, "invalid default Hill 48 parameters");
  mat->data               = hp;
  mat->ops.setfromoptions = MaterialSetFromOptions_Hill48;
  mat->ops.view           = MaterialView_Hill48;
  mat->ops.destroy        = MaterialDestroy_Hill48;
  Hill48KernelInit(hp, &mat->kernel);
  PetscFunctionReturn(0);
}
