/* Finite-strain anisotropic elasto-plasticity with Barlat's six-component yield function
   (F. Barlat, D. J. Lege, J. C. Brem, "A six-component yield function for anisotropic
   materials", Int. J. Plasticity 7, 1991), logarithmic elastic strains in the sheet's orthotropy
   frame and isotropic hardening (J2's).

   Why. Hill 1948 with r < 1 (aluminium sheet) puts the equibiaxial yield stress below the
   uniaxial one (sigma_b / sigma_0 = sqrt((1 + r) / 2), 0.91 for r = 0.65), while aluminium
   alloys yield in equibiaxial tension at or above the uniaxial stress (Woodthorpe and Pearce's
   "anomalous" behaviour). A non-quadratic function with the exponent of the crystal structure
   (Hosford 1972; Logan and Hosford 1980: 8 for face-centred cubic metals) keeps the r-values and
   raises the biaxial stress toward the uniaxial one (0.95 for r 0.71/0.58/0.70 and m = 8; Hill
   1948: 0.92).

   Yield function. In the orthotropy frame (rolling direction 1, transverse 2, normal 3), with
   Mandel components (11, 22, 33, 23, 31, 12; shear entries times sqrt 2), the transformed stress
       S~11 = [c3 (s11 - s22) - c2 (s33 - s11)] / 3,
       S~22 = [c1 (s22 - s33) - c3 (s11 - s22)] / 3,
       S~33 = [c2 (s33 - s11) - c1 (s22 - s33)] / 3,
       S~23 = c4 s23,  S~31 = c5 s31,  S~12 = c6 s12,
   i.e. S~ = L s with L symmetric and L (1,1,1,0,0,0) = 0 (pressure-insensitive; c = 1: the
   deviator), and with S1, S2, S3 the principal values of S~
       Phi = (S1 - S2)^m + (S2 - S3)^m + (S3 - S1)^m = 2 sigma_e^m,   m even.
   For m = 2 this is Hill 1948 (Phi = 6 J2(S~)); with c = 1 it is Hosford's isotropic function
   (m = 2: von Mises). Phi is convex in the principal values and isotropic, hence convex in S~,
   and sigma_e is convex and homogeneous of degree one in s.

   Derivatives (exact for even m, also at repeated principal values). With d_ab = S_a - S_b:
       phi_a = dPhi/dS_a:  phi_1 = m (d12^(m-1) - d31^(m-1)), cyclic;
       d2Phi/dS_a^2 = m (m-1) (d_ab^(m-2) + d_ca^(m-2)),  d2Phi/dS_a dS_b = -m (m-1) d_ab^(m-2);
   the gradient of Phi as a function of the tensor is Q diag(phi) Q^T (Q the eigenvectors), and
   its Hessian in the eigenbasis, in Mandel form, is the 3x3 block d2Phi/dS dS beside the shear
   entries theta_ab = (phi_a - phi_b) / (S_a - S_b) (the derivative of an isotropic tensor
   function); for even m, with c the third index,
       theta_ab = m [2 d_ab^(m-2) + sum_{k=0}^{m-2} d_ac^k d_bc^(m-2-k)],
   a polynomial: no division, exact at S_a = S_b. Scaled by k = the largest |d_ab| (no overflow
   for any m): sigma_e = k (Phi^ / 2)^(1/m) with Phi^ of S~ / k, and
       n~ = d sigma_e / dS~ = (sigma_e/k)^(1-m) / (2m) grad Phi^,
       H~ = (sigma_e/k)^(1-m) / (2 m k) Hess Phi^ - (m-1) / sigma_e n~ n~^T;
   in the stress, n = L n~, H = L H~ L.

   Return map (backward Euler, associated flow, work-equivalent ep; sigma_e homogeneous of degree
   one: s : n = sigma_e, so ep = ep_n + dl). n is deviatoric, so D n = 2G n and
       r_s = s - s_tr + 2G dl n(s) = 0,   r_f = sigma_e(s) - sigma_y(ep_n + dl) = 0,
   solved by Newton's method from (s_tr, 0) on the 7 unknowns (its first step is the radial return
   of the trial normal), with a backtracking line search on |r|^2 / 2 (the Newton direction is a
   descent direction of it; needed where m is large and the surface sharply curved) and dl kept
   >= 0. Converged when the largest |r_i| <= rtol sigma_e(s_tr), or, where the line search finds
   no decrease (the round-off floor), when |r| <= 1e3 rtol sigma_e(s_tr); otherwise the return map
   fails (the step is retried smaller). The elastic strain e_e = e_tr - dl n.

   Consistent tangent: the converged equations linearised in e_tr (s_tr = D e_tr),
       [I + 2G dl H, 2G n; n^T, -H'] [ds/de_tr; d dl/de_tr] = [D; 0],
   solved for the six columns at once: D_alg = ds/de_tr (= Mi D - 2G (Mi n)(n^T Mi D) /
   (2G n^T Mi n + H') with Mi = (I + 2G dl H)^{-1}).

   r-values (plane stress, uniaxial tension sigma at angle th: s = sigma (cos^2, sin^2, 0, 0, 0,
   sqrt 2 sin cos)): the flow direction n gives r = (n11 sin^2 + n22 cos^2 - sqrt 2 n12 sin cos)
   / n33. From r0, r45, r90 (c3 = 1; c1, c2, c6 by Newton's method with a difference Jacobian,
   a set-up computation; then c1, c2, c3, c6 scaled so that uniaxial tension along the rolling
   direction has sigma_e = sigma; c4 = c5 = 1).

   The first part of this file is the model on plain arrays (include/material_yld91.h); the
   second is the material type "yld91": its options (prefix material_, or the material's own
   prefix), view and kernel table. */
#include <math.h>

#include "material_aniso.h"
#include "material_impl.h"
#include "material_yld91.h"
#include "options.h"
#include "tensor.h"

static const double SQ2 = 1.41421356237309504880;
static const double PI  = 3.14159265358979323846;

/* x^k for a small non-negative integer k */
static inline double ipow(double x, int k)
{
  double r = 1.0;
  for (int i = 0; i < k; i++) r *= x;
  return r;
}

/* x^(1/m) for x >= 0: square roots where m is a power of two (2, 4, 8, 16, 32) */
static inline double root_m(double x, int m)
{
  if ((m & (m - 1)) == 0) {
    for (int k = m; k > 1; k >>= 1) x = sqrt(x);
    return x;
  }
  return pow(x, 1.0 / m);
}

/* the transformation L from c1..c6 */
static void yld91_L(const double c[6], double L[36])
{
  for (int i = 0; i < 36; i++) L[i] = 0.0;
  L[0]  = (c[1] + c[2]) / 3.0;
  L[1]  = L[6] = -c[2] / 3.0;
  L[2]  = L[12] = -c[1] / 3.0;
  L[7]  = (c[0] + c[2]) / 3.0;
  L[8]  = L[13] = -c[0] / 3.0;
  L[14] = (c[0] + c[1]) / 3.0;
  L[21] = c[3];
  L[28] = c[4];
  L[35] = c[5];
}

static void mv6(const double M[36], const double x[6], double y[6])
{
  for (int i = 0; i < 6; i++) {
    double s = 0.0;
    for (int j = 0; j < 6; j++) s += M[6 * i + j] * x[j];
    y[i] = s;
  }
}

/* what the return map keeps of an evaluation at s: sigma_e, the scale k, the scaled principal
   differences a, the eigenvectors Q of S~; with the gradient also the factor f, the rotation T of
   the eigenbasis and the gradient nt with respect to S~ (frame, Mandel) */
typedef struct {
  double se, k, Phi, a[3], Q[9], f, T[36], nt[6];
} Yld91Point;

/* sigma_e at s, and in pt the data of its derivatives */
static double yld91_eval(const Yld91Params *yp, const double s[6], Yld91Point *pt)
{
  const int m = yp->m;
  double    St[6], S3[9], Sl[3];
  mv6(yp->L, s, St);
  AnisoFromMandel(St, S3);
  t3_sym_eig(S3, Sl, pt->Q);
  const double d12 = Sl[0] - Sl[1], d23 = Sl[1] - Sl[2], d31 = Sl[2] - Sl[0];
  const double k   = fmax(fabs(d12), fmax(fabs(d23), fabs(d31)));
  pt->k            = k;
  pt->se           = 0.0;
  if (!(k > 0.0)) return 0.0;
  double *a = pt->a;
  a[0]      = d12 / k; /* (S1-S2)/k, (S2-S3)/k, (S3-S1)/k */
  a[1]      = d23 / k;
  a[2]      = d31 / k;
  pt->Phi   = ipow(a[0], m) + ipow(a[1], m) + ipow(a[2], m);
  pt->se    = k * root_m(0.5 * pt->Phi, m);
  return pt->se;
}

/* n = d sigma_e / ds at the point of yld91_eval (0 where sigma_e = 0), and the data of the Hessian */
static void yld91_gradient(const Yld91Params *yp, Yld91Point *pt, double n[6])
{
  const int     m = yp->m;
  const double *a = pt->a;
  for (int i = 0; i < 6; i++) n[i] = pt->nt[i] = 0.0;
  if (!(pt->k > 0.0)) return;
  pt->f = pt->se / (pt->k * m * pt->Phi); /* (sigma_e/k)^(1-m) / (2m), with (sigma_e/k)^m = Phi/2 */
  /* phi_1 = m (a12^(m-1) - a31^(m-1)), phi_2 = m (a23^(m-1) - a12^(m-1)), phi_3 = m (a31^(m-1) - a23^(m-1)) */
  const double p[3]  = {m * (ipow(a[0], m - 1) - ipow(a[2], m - 1)), m * (ipow(a[1], m - 1) - ipow(a[0], m - 1)), m * (ipow(a[2], m - 1) - ipow(a[1], m - 1))};
  double       ne[6] = {pt->f * p[0], pt->f * p[1], pt->f * p[2], 0.0, 0.0, 0.0};
  AnisoMandelRotation(pt->Q, pt->T); /* eigenbasis Mandel -> frame Mandel */
  mv6(pt->T, ne, pt->nt);
  mv6(yp->L, pt->nt, n);
}

/* the Hessian d2 sigma_e / ds2 at the point of yld91_gradient (0 where sigma_e = 0) */
static void yld91_hessian(const Yld91Params *yp, const Yld91Point *pt, double H[36])
{
  const int     m = yp->m;
  const double *a = pt->a, *T = pt->T, *L = yp->L, k = pt->k;
  double        He[36], Ht[36], Y[36];
  for (int i = 0; i < 36; i++) H[i] = 0.0;
  if (!(k > 0.0)) return;
  /* Hessian of Phi^ in the eigenbasis (Mandel): normal block and theta_23, theta_31, theta_12 */
  const double mm = (double)m * (m - 1);
  const double q12 = ipow(a[0], m - 2), q23 = ipow(a[1], m - 2), q31 = ipow(a[2], m - 2);
  for (int i = 0; i < 36; i++) He[i] = 0.0;
  He[0]  = mm * (q12 + q31);
  He[7]  = mm * (q12 + q23);
  He[14] = mm * (q23 + q31);
  He[1] = He[6] = -mm * q12;
  He[8] = He[13] = -mm * q23;
  He[2] = He[12] = -mm * q31;
  /* theta_ab = m [2 d_ab^(m-2) + sum_k d_ac^k d_bc^(m-2-k)] for (a,b,c) = (2,3,1), (3,1,2), (1,2,3) */
  {
    const double dab[3] = {a[1], a[2], a[0]};    /* S2-S3, S3-S1, S1-S2 */
    const double dac[3] = {-a[0], -a[1], -a[2]}; /* S2-S1, S3-S2, S1-S3 */
    const double dbc[3] = {a[2], a[0], a[1]};    /* S3-S1, S1-S2, S2-S3 */
    for (int j = 0; j < 3; j++) {
      double sum = 0.0;
      for (int e = 0; e <= m - 2; e++) sum += ipow(dac[j], e) * ipow(dbc[j], m - 2 - e);
      He[7 * (3 + j)] = m * (2.0 * ipow(dab[j], m - 2) + sum);
    }
  }
  /* Y = He T^T (He: a 3x3 block and a diagonal) */
  for (int i = 0; i < 6; i++)
    for (int j = 0; j < 6; j++) Y[6 * i + j] = i < 3 ? He[6 * i] * T[6 * j] + He[6 * i + 1] * T[6 * j + 1] + He[6 * i + 2] * T[6 * j + 2] : He[7 * i] * T[6 * j + i];
  /* Ht = f/k T Y - (m-1)/se nt nt^T (d2 sigma_e / dS~2) */
  for (int i = 0; i < 6; i++)
    for (int j = i; j < 6; j++) {
      double s = 0.0;
      for (int l = 0; l < 6; l++) s += T[6 * i + l] * Y[6 * l + j];
      Ht[6 * i + j] = Ht[6 * j + i] = pt->f / k * s - (m - 1) / pt->se * pt->nt[i] * pt->nt[j];
    }
  /* H = L Ht L (L: a symmetric 3x3 block and the diagonal c4, c5, c6) */
  for (int i = 0; i < 6; i++)
    for (int j = 0; j < 6; j++) Y[6 * i + j] = j < 3 ? Ht[6 * i] * L[j] + Ht[6 * i + 1] * L[6 + j] + Ht[6 * i + 2] * L[12 + j] : Ht[6 * i + j] * L[7 * j];
  for (int i = 0; i < 6; i++)
    for (int j = 0; j < 6; j++) H[6 * i + j] = i < 3 ? L[6 * i] * Y[j] + L[6 * i + 1] * Y[6 + j] + L[6 * i + 2] * Y[12 + j] : L[7 * i] * Y[6 * i + j];
}

double Yld91Effective(const Yld91Params *yp, const double s[6], double n[6], double H[36])
{
  Yld91Point   pt;
  double       nb[6];
  const double se = yld91_eval(yp, s, &pt);
  if (n || H) yld91_gradient(yp, &pt, n ? n : nb);
  if (H) yld91_hessian(yp, &pt, H);
  return se;
}

double Yld91RValue(const Yld91Params *yp, double th)
{
  const double c = cos(th), s = sin(th);
  const double sig[6] = {c * c, s * s, 0.0, 0.0, 0.0, SQ2 * s * c};
  double       n[6];
  Yld91Effective(yp, sig, n, NULL);
  return (n[0] * s * s + n[1] * c * c - SQ2 * n[5] * s * c) / n[2];
}

int Yld91ParamsSetup(Yld91Params *yp)
{
  if (J2ParamsSetup(&yp->base)) return YLD91_ERR_ELASTIC;
  if (!(yp->m >= 2 && yp->m <= 32 && yp->m % 2 == 0)) return YLD91_ERR_EXPONENT;
  if (AnisoFrame(yp->rd, yp->nd, yp->A)) return YLD91_ERR_AXES;
  if (yp->from_r) {
    const double rt[3] = {yp->r0, yp->r45, yp->r90}, th[3] = {0.0, 0.25 * PI, 0.5 * PI};
    if (!(yp->r0 > 0.0 && yp->r45 > 0.0 && yp->r90 > 0.0) || !isfinite(yp->r0 + yp->r45 + yp->r90)) return YLD91_ERR_R;
    /* Newton on x = (c1, c2, c6), c3 = 1, from the isotropic function; difference Jacobian */
    double x[3] = {1.0, 1.0, 1.0}, res[3];
    int    ok   = 0;
    for (int it = 0; it < 60; it++) {
      double c[6] = {x[0], x[1], 1.0, 1.0, 1.0, x[2]}, J[9], dx[3], nr = 0.0;
      for (int i = 0; i < 6; i++) yp->c[i] = c[i];
      yld91_L(yp->c, yp->L);
      for (int i = 0; i < 3; i++) {
        res[i] = Yld91RValue(yp, th[i]) / rt[i] - 1.0;
        nr     = fmax(nr, fabs(res[i]));
      }
      if (!isfinite(nr)) break;
      if (nr < 1e-13) {
        ok = 1;
        break;
      }
      for (int j = 0; j < 3; j++) {
        const double hstep = 1e-7 * fmax(1.0, fabs(x[j]));
        double       xp[3] = {x[0], x[1], x[2]};
        xp[j] += hstep;
        const double cp[6] = {xp[0], xp[1], 1.0, 1.0, 1.0, xp[2]};
        for (int i = 0; i < 6; i++) yp->c[i] = cp[i];
        yld91_L(yp->c, yp->L);
        for (int i = 0; i < 3; i++) J[3 * i + j] = (Yld91RValue(yp, th[i]) / rt[i] - 1.0 - res[i]) / hstep;
      }
      for (int i = 0; i < 3; i++) dx[i] = -res[i];
      if (dense_solve(3, J, 1, dx)) break;
      /* damped: no coefficient changes by more than half its size in one step */
      double damp = 1.0;
      for (int i = 0; i < 3; i++)
        if (fabs(dx[i]) > 0.5 * fabs(x[i])) damp = fmin(damp, 0.5 * fabs(x[i]) / fabs(dx[i]));
      for (int i = 0; i < 3; i++) x[i] += damp * dx[i];
    }
    if (!ok) return YLD91_ERR_FIT;
    /* scale c1, c2, c3, c6 (Phi is homogeneous of degree m in them) so that sigma_e of uniaxial
       tension along the rolling direction is that tension */
    {
      const double one[6] = {1, 0, 0, 0, 0, 0};
      const double se     = Yld91Effective(yp, one, NULL, NULL);
      if (!(se > 0.0) || !isfinite(se)) return YLD91_ERR_FIT;
      yp->c[0] /= se;
      yp->c[1] /= se;
      yp->c[2] /= se;
      yp->c[5] /= se;
      yp->c[3] = yp->c[4] = 1.0;
    }
  }
  for (int i = 0; i < 6; i++)
    if (!isfinite(yp->c[i])) return YLD91_ERR_COEF;
  if (!(yp->c[3] > 0.0 && yp->c[4] > 0.0 && yp->c[5] > 0.0)) return YLD91_ERR_COEF;
  /* the normal block must not vanish on any deviatoric direction: (c1 c2 + c2 c3 + c3 c1) != 0 */
  if (!(fabs(yp->c[0] * yp->c[1] + yp->c[1] * yp->c[2] + yp->c[2] * yp->c[0]) > 0.0)) return YLD91_ERR_COEF;
  yld91_L(yp->c, yp->L);
  return YLD91_OK;
}

/* the return map's Newton matrix d(r_s, r_f)/d(s, dl) = [I + c dl H, c n; n^T, -H'] (7x7) */
static void newton_matrix(double c, double dl, const double Hs[36], const double n[6], double Hp, double J[49])
{
  for (int i = 0; i < 6; i++) {
    for (int j = 0; j < 6; j++) J[7 * i + j] = (i == j ? 1.0 : 0.0) + c * dl * Hs[6 * i + j];
    J[7 * i + 6] = c * n[i];
    J[7 * 6 + i] = n[i];
  }
  J[48] = -Hp;
}

/* the return map's residual r = (s - s_tr + c dl n(s), sigma_e(s) - sigma_y(ep_n + dl)), c = 2G;
   n(s) and the point's data (pt) on output; returns |r|^2 */
static double yld91_residual(const Yld91Params *yp, const double str[6], double c, double ep_n, const double s[6], double dl, Yld91Point *pt, double n[6], double r[7])
{
  const double se  = yld91_eval(yp, s, pt);
  double       psi = 0.0;
  yld91_gradient(yp, pt, n);
  for (int i = 0; i < 6; i++) r[i] = s[i] - str[i] + c * dl * n[i];
  r[6] = se - J2YieldStress(&yp->base, ep_n + dl, NULL);
  for (int i = 0; i < 7; i++) psi += r[i] * r[i];
  return psi;
}

/* the return map of AnisoReturnFn (include/material_aniso.h) */
static int yld91_stress_return(const void *ctx, const double D[36], const double etr[6], const double str[6], double ep_n, double s[6], double ee[6], double *ep, double *Dalg, int *plastic)
{
  const Yld91Params *yp = (const Yld91Params *)ctx;
  const J2Params    *mp = &yp->base;
  const double       c  = 2.0 * mp->G;
  double             n[6], Hs[36], Hp, dl = 0.0, r[7], psi;
  Yld91Point         pt;
  const double       se_tr = yld91_eval(yp, str, &pt);

  *plastic = 0;
  *ep      = ep_n;
  for (int i = 0; i < 6; i++) {
    s[i]  = str[i];
    ee[i] = etr[i];
  }
  if (!(se_tr > 0.0 && se_tr - J2YieldStress(mp, ep_n, NULL) > 0.0)) {
    if (Dalg)
      for (int i = 0; i < 36; i++) Dalg[i] = D[i];
    return 0;
  }
  /* the residual at (s_tr, 0): r_s = 0 */
  *plastic = 1;
  yld91_gradient(yp, &pt, n);
  for (int i = 0; i < 6; i++) r[i] = 0.0;
  r[6] = se_tr - J2YieldStress(mp, ep_n, NULL);
  psi  = r[6] * r[6];
  const double tol = mp->rtol * se_tr;
  int          conv = 0;
  for (int it = 0; it <= mp->maxit; it++) {
    double nr = 0.0;
    for (int i = 0; i < 7; i++) nr = fmax(nr, fabs(r[i]));
    if (nr <= tol) {
      conv = 1;
      break;
    }
    if (it == mp->maxit) break;
    /* Newton: [I + c dl H, c n; n^T, -H'] [ds; ddl] = -r */
    double J[49], d[7];
    yld91_hessian(yp, &pt, Hs);
    J2YieldStress(mp, ep_n + dl, &Hp);
    newton_matrix(c, dl, Hs, n, Hp, J);
    for (int i = 0; i < 7; i++) d[i] = -r[i];
    if (dense_solve(7, J, 1, d)) return 1;
    /* backtracking on psi = |r|^2 (Armijo, quadratic model, lambda in [0.1, 0.5] of the last) */
    double     lam = 1.0, sn[6], dln, nn[6], rn[7], psin = 0.0;
    Yld91Point ptn;
    int    acc = 0;
    for (int ls = 0; ls < 40; ls++) {
      for (int i = 0; i < 6; i++) sn[i] = s[i] + lam * d[i];
      dln = fmax(dl + lam * d[6], 0.0);
      psin = yld91_residual(yp, str, c, ep_n, sn, dln, &ptn, nn, rn);
      if (isfinite(psin) && psin <= (1.0 - 2e-4 * lam) * psi) {
        acc = 1;
        break;
      }
      const double lq = isfinite(psin) ? lam * lam * psi / (psin - psi + 2.0 * lam * psi) : 0.5 * lam;
      lam             = fmin(fmax(lq, 0.1 * lam), 0.5 * lam);
    }
    if (!acc) {
      /* no decrease: at the round-off floor of the residual if it is already small */
      if (sqrt(psi) <= 1e3 * tol) conv = 1;
      break;
    }
    for (int i = 0; i < 6; i++) {
      s[i] = sn[i];
      n[i] = nn[i];
    }
    dl  = dln;
    psi = psin;
    pt  = ptn;
    for (int i = 0; i < 7; i++) r[i] = rn[i];
  }
  if (!conv) return 1;
  if (Dalg) yld91_hessian(yp, &pt, Hs);
  J2YieldStress(mp, ep_n + dl, &Hp);
  if (!isfinite(Hp)) return 1;
  for (int i = 0; i < 6; i++) ee[i] = etr[i] - dl * n[i];
  *ep = ep_n + dl;
  if (Dalg) {
    /* the return map's equations linearised in e_tr: J [ds/de_tr; ddl/de_tr] = [D; 0] */
    double J[49], B[42];
    newton_matrix(c, dl, Hs, n, Hp, J);
    for (int i = 0; i < 36; i++) B[i] = D[i];
    for (int j = 0; j < 6; j++) B[36 + j] = 0.0;
    if (dense_solve(7, J, 6, B)) return 1;
    for (int i = 0; i < 36; i++) Dalg[i] = B[i];
  }
  return 0;
}

int Yld91Update(const Yld91Params *yp, const double F[9], const double hn[YLD91_NHIST], double tau[9], double *dtau, double h[YLD91_NHIST], int *plastic)
{
  return AnisoLogUpdate(&yp->base, yp->A, yld91_stress_return, yp, F, hn, tau, dtau, h, plastic);
}

/* ------------------------------------------------------------------------------------------ */
/* the kernel table                                                                            */
/* ------------------------------------------------------------------------------------------ */
static int Yld91KernelUpdate(const void *ctx, const double F[9], const double *hn, double tau[9], double *dtau, double *h, int *plastic)
{
  return Yld91Update((const Yld91Params *)ctx, F, hn, tau, dtau, h, plastic);
}

static void Yld91KernelHistoryInit(const void *ctx, double *h)
{
  (void)ctx;
  J2HistoryInit(h);
}

static double Yld91KernelPlasticStrain(const void *ctx, const double *h)
{
  (void)ctx;
  return h[YLD91_HIST_EP];
}

void Yld91KernelInit(const Yld91Params *yp, MaterialKernel *k)
{
  k->nhist          = YLD91_NHIST;
  k->ctx            = yp;
  k->update         = Yld91KernelUpdate;
  k->history_init   = Yld91KernelHistoryInit;
  k->plastic_strain = Yld91KernelPlasticStrain;
  k->set_point      = NULL;
  k->failed_point   = NULL;
  k->set_increment  = NULL;
}

/* ------------------------------------------------------------------------------------------ */
/* the material type "yld91"                                                                   */
/* ------------------------------------------------------------------------------------------ */
static PetscErrorCode MaterialSetFromOptions_Yld91(Material mat)
{
  Yld91Params *yp   = (Yld91Params *)mat->data;
  MPI_Comm     comm = mat->comm;
  const char  *pre  = mat->prefix; /* the options' names in the messages: -<pre>yld91_r0, ... */
  char         title[512];

  PetscFunctionBeginUser;
  PetscCall(MaterialOptionsTitle(mat, "yld91", "finite-strain Barlat 1991 anisotropic plasticity (log strains, isotropic hardening)", title, sizeof(title)));
  PetscOptionsBegin(comm, mat->prefix, title, "Material");
  {
    const char *rname[3] = {"yld91_r0", "yld91_r45", "yld91_r90"};
    double     *rv[3]    = {&yp->r0, &yp->r45, &yp->r90};
    PetscBool   rset = PETSC_FALSE, cset, set;
    PetscInt    nc = 6, n, m = yp->m;
    PetscReal   v[6];
    int         st;

    PetscCall(J2ParamsSetFromOptions(PetscOptionsObject, comm, &yp->base));
    PetscCall(PetscOptionsInt("-yld91_exponent", "Barlat 1991: exponent m (an even integer; 8 for fcc metals such as aluminium, 6 for bcc; 2 is Hill 1948)", NULL, m, &m, NULL));
    PetscCheck(m >= 2 && m <= 32 && m % 2 == 0, comm, PETSC_ERR_USER_INPUT, "-%syld91_exponent %d must be an even integer in [2, 32]", pre, (int)m);
    yp->m = (int)m;
    PetscCall(PetscOptionsReal("-yld91_r0", "Barlat 1991: r-value at 0 deg to the rolling direction (c1..c6 fitted to the three)", NULL, yp->r0, &yp->r0, &set));
    rset = rset || set;
    PetscCall(PetscOptionsReal("-yld91_r45", "Barlat 1991: r-value at 45 deg", NULL, yp->r45, &yp->r45, &set));
    rset = rset || set;
    PetscCall(PetscOptionsReal("-yld91_r90", "Barlat 1991: r-value at 90 deg", NULL, yp->r90, &yp->r90, &set));
    rset = rset || set;
    for (int i = 0; i < 6; i++) v[i] = yp->c[i];
    PetscCall(PetscOptionsRealArray("-yld91_c", "Barlat 1991: c1,c2,c3,c4,c5,c6 (instead of the r-values; the effective stress as they define it)", NULL, v, &nc, &cset));
    PetscCheck(!(rset && cset), comm, PETSC_ERR_USER_INPUT, "-%syld91_r0/r45/r90 and -%syld91_c exclude each other: give one set", pre, pre);
    if (cset) {
      PetscCheck(nc == 6, comm, PETSC_ERR_USER_INPUT, "-%syld91_c needs 6 coefficients c1,c2,c3,c4,c5,c6 (got %d)", pre, (int)nc);
      for (int i = 0; i < 6; i++) PetscCheck(PetscIsNormalReal(v[i]) || v[i] == 0, comm, PETSC_ERR_USER_INPUT, "-%syld91_c: c%d = %g must be finite", pre, i + 1, (double)v[i]);
      for (int i = 3; i < 6; i++) PetscCheck(v[i] > 0, comm, PETSC_ERR_USER_INPUT, "-%syld91_c: c%d = %g must be positive", pre, i + 1, (double)v[i]);
      PetscCheck(fabs(v[0] * v[1] + v[1] * v[2] + v[2] * v[0]) > 0, comm, PETSC_ERR_USER_INPUT, "-%syld91_c: c1 c2 + c2 c3 + c3 c1 = 0 gives a degenerate yield function", pre);
      for (int i = 0; i < 6; i++) yp->c[i] = v[i];
      yp->from_r = 0;
    }
    if (rset) yp->from_r = 1;
    for (int i = 0; i < 3 && yp->from_r; i++)
      PetscCheck(*rv[i] > 0 && PetscIsNormalReal(*rv[i]), comm, PETSC_ERR_USER_INPUT, "-%s%s %g must be positive", pre, rname[i], (double)*rv[i]);
    for (int i = 0; i < 3; i++) v[i] = yp->rd[i];
    n = 3;
    PetscCall(PetscOptionsRealArray("-yld91_rd", "Barlat 1991: rolling direction x,y,z", NULL, v, &n, &set));
    PetscCheck(!set || n == 3, comm, PETSC_ERR_USER_INPUT, "-%syld91_rd needs 3 components x,y,z (got %d)", pre, (int)n);
    for (int i = 0; i < 3; i++) yp->rd[i] = v[i];
    for (int i = 0; i < 3; i++) v[i] = yp->nd[i];
    n = 3;
    PetscCall(PetscOptionsRealArray("-yld91_normal", "Barlat 1991: sheet normal x,y,z", NULL, v, &n, &set));
    PetscCheck(!set || n == 3, comm, PETSC_ERR_USER_INPUT, "-%syld91_normal needs 3 components x,y,z (got %d)", pre, (int)n);
    for (int i = 0; i < 3; i++) yp->nd[i] = v[i];
    {
      double A[9];
      PetscCheck(AnisoFrame(yp->rd, yp->nd, A) == 0, comm, PETSC_ERR_USER_INPUT, "-%syld91_rd %g,%g,%g and -%syld91_normal %g,%g,%g must be non-zero and orthogonal", pre, yp->rd[0], yp->rd[1],
                 yp->rd[2], pre, yp->nd[0], yp->nd[1], yp->nd[2]);
    }
    st = Yld91ParamsSetup(yp);
    PetscCheck(st != YLD91_ERR_FIT, comm, PETSC_ERR_USER_INPUT, "-%syld91_r0 %g, -%syld91_r45 %g, -%syld91_r90 %g: the fit of c1..c6 (exponent %d) to these r-values did not converge", pre, yp->r0, pre,
               yp->r45, pre, yp->r90, yp->m);
    PetscCheck(st == YLD91_OK, comm, PETSC_ERR_USER_INPUT, "invalid Barlat 1991 parameters (status %d)", st);
  }
  PetscOptionsEnd();
  mat->modulus = yp->base.E;
  PetscFunctionReturn(0);
}

static PetscErrorCode MaterialView_Yld91(Material mat, PetscViewer v)
{
  const Yld91Params *yp = (const Yld91Params *)mat->data;

  PetscFunctionBeginUser;
  PetscCall(J2ParamsView(&yp->base, v));
  if (yp->from_r)
    PetscCall(PetscViewerASCIIPrintf(v, "Barlat 1991, exponent %d, from r0 = %g, r45 = %g, r90 = %g: c1..c6 = %g, %g, %g, %g, %g, %g\n", yp->m, yp->r0, yp->r45, yp->r90, yp->c[0], yp->c[1], yp->c[2],
                                     yp->c[3], yp->c[4], yp->c[5]));
  else PetscCall(PetscViewerASCIIPrintf(v, "Barlat 1991, exponent %d: c1..c6 = %g, %g, %g, %g, %g, %g\n", yp->m, yp->c[0], yp->c[1], yp->c[2], yp->c[3], yp->c[4], yp->c[5]));
  {
    const double b[6] = {1, 1, 0, 0, 0, 0};
    PetscCall(PetscViewerASCIIPrintf(v, "r-values %g, %g, %g; equibiaxial yield stress / uniaxial %g\n", Yld91RValue(yp, 0.0), Yld91RValue(yp, 0.25 * PI), Yld91RValue(yp, 0.5 * PI),
                                     1.0 / Yld91Effective(yp, b, NULL, NULL)));
  }
  PetscCall(PetscViewerASCIIPrintf(v, "rolling direction (%g, %g, %g), transverse (%g, %g, %g), normal (%g, %g, %g)\n", yp->A[0], yp->A[3], yp->A[6], yp->A[1], yp->A[4], yp->A[7], yp->A[2], yp->A[5],
                                   yp->A[8]));
  PetscCall(PetscViewerASCIIPrintf(v, "return map: rtol %g, maxit %d; history %d doubles per point\n", yp->base.rtol, yp->base.maxit, YLD91_NHIST));
  PetscFunctionReturn(0);
}

static PetscErrorCode MaterialDestroy_Yld91(Material mat)
{
  PetscFunctionBeginUser;
  PetscCall(PetscFree(mat->data));
  PetscFunctionReturn(0);
}

/* the defaults: J2's elasticity and hardening, exponent 8, isotropic r-values, rolling direction
   x, normal z */
PETSC_INTERN PetscErrorCode MaterialCreate_Yld91(Material mat);
PetscErrorCode MaterialCreate_Yld91(Material mat)
{
  Yld91Params *yp;

  PetscFunctionBeginUser;
  PetscCall(PetscNew(&yp));
  J2ParamsDefaults(&yp->base);
  yp->m      = 8;
  yp->from_r = 1;
  yp->r0 = yp->r45 = yp->r90 = 1.0;
  yp->rd[0]                  = 1.0;
  yp->nd[2]                  = 1.0;
  PetscCheck(Yld91ParamsSetup(yp) == YLD91_OK, mat->comm, PETSC_ERR_PLIB, "invalid default Barlat 1991 parameters");
  mat->data               = yp;
  mat->ops.setfromoptions = MaterialSetFromOptions_Yld91;
  mat->ops.view           = MaterialView_Yld91;
  mat->ops.destroy        = MaterialDestroy_Yld91;
  Yld91KernelInit(yp, &mat->kernel);
  PetscFunctionReturn(0);
}
