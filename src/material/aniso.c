/* The kinematics shared by the orthotropic log-strain materials (include/material_aniso.h;
   the derivation in full in src/material/hill48.c's header comment, which uses it).

   F = Fe Fp, history Cp^{-1} = Fp^{-1} Fp^{-T} and ep. The polar decomposition F = R U gives the
   rotated trial elastic left Cauchy-Green tensor bb = U Cp^{-1}_n U and the trial log strain
   eb = 1/2 ln bb (material frame); in the orthotropy frame A, e = A^T eb A (Mandel). The model's
   return map gives s, e_e and D_alg = ds/de_tr; tau_b = A s A^T, tau = R tau_b R^T; the flow
   update Cp^{-1}_{n+1} = U^{-1} exp(2 A e_e A^T) U^{-1}; the tangent is the chain
   dF -> (dR, d bb) -> d eb (Daleckii-Krein) -> de -> ds = D_alg de -> d tau. */
#include <math.h>

#include "material_aniso.h"
#include "tensor.h"

static const double SQ2 = 1.41421356237309504880;

int AnisoFrame(const double rd[3], const double nd[3], double A[9])
{
  double       n[3], r[3], t[3];
  const double ln = sqrt(nd[0] * nd[0] + nd[1] * nd[1] + nd[2] * nd[2]);
  const double lr = sqrt(rd[0] * rd[0] + rd[1] * rd[1] + rd[2] * rd[2]);
  if (!(ln > 0.0 && lr > 0.0) || !isfinite(ln + lr)) return 1;
  for (int i = 0; i < 3; i++) {
    n[i] = nd[i] / ln;
    r[i] = rd[i] / lr;
  }
  const double c = r[0] * n[0] + r[1] * n[1] + r[2] * n[2];
  if (fabs(c) > 1e-6) return 1;
  for (int i = 0; i < 3; i++) r[i] -= c * n[i];
  const double l2 = sqrt(r[0] * r[0] + r[1] * r[1] + r[2] * r[2]);
  for (int i = 0; i < 3; i++) r[i] /= l2;
  t[0] = n[1] * r[2] - n[2] * r[1];
  t[1] = n[2] * r[0] - n[0] * r[2];
  t[2] = n[0] * r[1] - n[1] * r[0];
  for (int i = 0; i < 3; i++) {
    A[3 * i + 0] = r[i];
    A[3 * i + 1] = t[i];
    A[3 * i + 2] = n[i];
  }
  return 0;
}

/* ---------- small helpers ---------- */

/* symmetric 3x3 <-> Mandel vector (11, 22, 33, 23, 31, 12) */
void AnisoToMandel(const double T[9], double v[6])
{
  v[0] = T[0];
  v[1] = T[4];
  v[2] = T[8];
  v[3] = SQ2 * 0.5 * (T[5] + T[7]);
  v[4] = SQ2 * 0.5 * (T[6] + T[2]);
  v[5] = SQ2 * 0.5 * (T[1] + T[3]);
}

void AnisoFromMandel(const double v[6], double T[9])
{
  T[0] = v[0];
  T[4] = v[1];
  T[8] = v[2];
  T[5] = T[7] = v[3] / SQ2;
  T[2] = T[6] = v[4] / SQ2;
  T[1] = T[3] = v[5] / SQ2;
}

/* T: the Mandel form of S -> M S M^T, in closed form: with (i, j) the index pair of a Mandel row,
   (p, q) that of a column, w = 1 or sqrt 2 (normal or shear row) and c = 1/2 or 1/sqrt 2 (normal
   or shear column), T_row,col = w c (M_ip M_jq + M_iq M_jp) */
void AnisoMandelRotation(const double M[9], double T[36])
{
  static const int pi[6] = {0, 1, 2, 1, 2, 0}, pj[6] = {0, 1, 2, 2, 0, 1};
  for (int row = 0; row < 6; row++) {
    const int    i = pi[row], j = pj[row];
    const double w = row < 3 ? 1.0 : SQ2;
    for (int col = 0; col < 6; col++) {
      const int    p = pi[col], q = pj[col];
      const double c = col < 3 ? 0.5 : 1.0 / SQ2;
      T[6 * row + col] = w * c * (M[3 * i + p] * M[3 * j + q] + M[3 * i + q] * M[3 * j + p]);
    }
  }
}

/* B = M^T S M (S symmetric; B symmetrized) */
static void congruence_t(const double M[9], const double S[9], double B[9])
{
  double Y[9];
  t3_mul(S, M, Y);
  t3_tmul(M, Y, B);
  B[1] = B[3] = 0.5 * (B[1] + B[3]);
  B[2] = B[6] = 0.5 * (B[2] + B[6]);
  B[5] = B[7] = 0.5 * (B[5] + B[7]);
}

/* B = M S M^T (S symmetric; B symmetrized) */
static void congruence(const double M[9], const double S[9], double B[9])
{
  double Y[9];
  t3_mult(S, M, Y);
  t3_mul(M, Y, B);
  B[1] = B[3] = 0.5 * (B[1] + B[3]);
  B[2] = B[6] = 0.5 * (B[2] + B[6]);
  B[5] = B[7] = 0.5 * (B[5] + B[7]);
}

/* Q diag(d) Q^T */
static void eig_compose(const double Q[9], const double d[3], double A[9])
{
  for (int i = 0; i < 3; i++)
    for (int j = i; j < 3; j++) A[3 * i + j] = A[3 * j + i] = Q[3 * i] * d[0] * Q[3 * j] + Q[3 * i + 1] * d[1] * Q[3 * j + 1] + Q[3 * i + 2] * d[2] * Q[3 * j + 2];
}

/* (ln x - ln y)/(x - y), accurate for x ~ y too (as in j2.c) */
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

/* y = M x (6x6) */
static void mv6(const double M[36], const double x[6], double y[6])
{
  for (int i = 0; i < 6; i++) {
    double s = 0.0;
    for (int j = 0; j < 6; j++) s += M[6 * i + j] * x[j];
    y[i] = s;
  }
}

int AnisoLogUpdate(const J2Params *mp, const double Ax[9], AnisoReturnFn ret, const void *ctx, const double F[9], const double hn[J2_NHIST], double tau[9], double *dtau, double h[J2_NHIST],
                   int *plastic)
{
  const double K = mp->K, G = mp->G;
  if (plastic) *plastic = 0;

  const double J = t3_det(F);
  if (!(J > 0.0) || !isfinite(J)) {
    fail_outputs(hn, tau, dtau, h);
    return MAT_ERR_JACOBIAN;
  }

  /* polar decomposition F = R U from C = F^T F = V diag(c) V^T */
  double C[9], cl[3], V[9], u[3], ui[3], U[9], Ui[9], R[9];
  t3_tmul(F, F, C);
  C[1] = C[3] = 0.5 * (C[1] + C[3]);
  C[2] = C[6] = 0.5 * (C[2] + C[6]);
  C[5] = C[7] = 0.5 * (C[5] + C[7]);
  t3_sym_eig(C, cl, V);
  if (!(cl[0] > 0.0 && cl[1] > 0.0 && cl[2] > 0.0)) {
    fail_outputs(hn, tau, dtau, h);
    return MAT_ERR_JACOBIAN;
  }
  for (int a = 0; a < 3; a++) {
    u[a]  = sqrt(cl[a]);
    ui[a] = 1.0 / u[a];
  }
  eig_compose(V, u, U);
  eig_compose(V, ui, Ui);
  t3_mul(F, Ui, R);

  /* rotated trial elastic left Cauchy-Green tensor bb = U Cp^{-1}_n U, its eigenbasis */
  const double Cpi[9] = {hn[0], hn[3], hn[5], hn[3], hn[1], hn[4], hn[5], hn[4], hn[2]};
  double       bb[9], lam[3], Q[9];
  congruence(U, Cpi, bb);
  t3_sym_eig(bb, lam, Q);
  if (!(lam[0] > 0.0 && lam[1] > 0.0 && lam[2] > 0.0)) {
    fail_outputs(hn, tau, dtau, h);
    return MAT_ERR_JACOBIAN;
  }

  /* trial log strain in the orthotropy frame: e = W^T diag(ln lam / 2) W, W = Q^T A */
  double W[9], el[3], E3[9], etr[6];
  t3_tmul(Q, Ax, W);
  for (int a = 0; a < 3; a++) el[a] = 0.5 * log(lam[a]);
  {
    double Dg[9] = {el[0], 0, 0, 0, el[1], 0, 0, 0, el[2]};
    congruence_t(W, Dg, E3);
  }
  AnisoToMandel(E3, etr);

  /* trial stress s_tr = D e_tr; the model's return map */
  const double lmb = K - 2.0 * G / 3.0;
  double       str[6], s[6], D[36], Dalg[36], ee[6], ep;
  int          isplastic = 0;
  for (int i = 0; i < 36; i++) D[i] = 0.0;
  for (int i = 0; i < 6; i++) D[7 * i] = 2.0 * G;
  for (int i = 0; i < 3; i++)
    for (int j = 0; j < 3; j++) D[6 * i + j] += lmb;
  mv6(D, etr, str);
  if (ret(ctx, D, etr, str, hn[J2_HIST_EP], s, ee, &ep, dtau ? Dalg : NULL, &isplastic)) {
    fail_outputs(hn, tau, dtau, h);
    return MAT_ERR_RETURNMAP;
  }

  /* tau_b = A s A^T, tau = R tau_b R^T */
  double S3[9], tb[9];
  AnisoFromMandel(s, S3);
  congruence(Ax, S3, tb);
  congruence(R, tb, tau);

  /* history: bb_e = exp(2 A e_e A^T), Cp^{-1} = U^{-1} bb_e U^{-1} */
  if (isplastic) {
    double Ee[9], eb[9], lb[3], Qb[9], be[3], Bb[9], Cn[9];
    AnisoFromMandel(ee, Ee);
    congruence(Ax, Ee, eb);
    t3_sym_eig(eb, lb, Qb);
    for (int a = 0; a < 3; a++) be[a] = exp(2.0 * lb[a]);
    eig_compose(Qb, be, Bb);
    congruence(Ui, Bb, Cn);
    h[0]                = Cn[0];
    h[1]                = Cn[4];
    h[2]                = Cn[8];
    h[3]                = Cn[1];
    h[4]                = Cn[5];
    h[5]                = Cn[2];
    h[J2_HIST_EP]       = ep;
  } else {
    for (int i = 0; i < J2_NHIST; i++) h[i] = hn[i];
  }
  if (plastic) *plastic = isplastic;
  if (!dtau) return MAT_OK;

  /* The tangent, one column dF = e_k (x) E_L at a time. In the eigenbasis Q of bb (with
     a~ = Q^T R^T e_k, c~ = Q^T R^T Gm^T E_L, omega~ = det Q Q^T omega):
       (Q^T d bb Q)_ab = a~_a c~_b + c~_a a~_b + (lam_a - lam_b) W(omega~)_ab;
     the chain d eb' -> de -> ds -> R A ds A^T R^T is one 6x6 map K = T(R A) D_alg T(W^T) on
     Mandel vectors (T(M): the Mandel form of S -> M S M^T), and
     R (Omega tau_b - tau_b Omega) R^T = W(R omega) tau - tau W(R omega). */
  double Gm[9], Zi[9], Z[9], Gam[9], K6[36];
  t3_mult(Cpi, F, Gm); /* Cp^{-1} F^T */
  {
    const double tr = U[0] + U[4] + U[8];
    for (int i = 0; i < 9; i++) Zi[i] = -U[i];
    Zi[0] += tr;
    Zi[4] += tr;
    Zi[8] += tr;
    t3_inv(Zi, Z);
  }
  for (int a = 0; a < 3; a++)
    for (int b = 0; b < 3; b++) Gam[3 * a + b] = 0.5 * (a == b ? 1.0 / lam[a] : dlog_ratio(lam[a], lam[b]));
  {
    double Wt[9], RA[9], T1[36], T2[36], Y[36];
    t3_transpose(W, Wt);
    t3_mul(R, Ax, RA);
    AnisoMandelRotation(Wt, T1);
    AnisoMandelRotation(RA, T2);
    for (int i = 0; i < 6; i++)
      for (int j = 0; j < 6; j++) {
        double t = 0.0;
        for (int m = 0; m < 6; m++) t += Dalg[6 * i + m] * T1[6 * m + j];
        Y[6 * i + j] = t;
      }
    for (int i = 0; i < 6; i++)
      for (int j = 0; j < 6; j++) {
        double t = 0.0;
        for (int m = 0; m < 6; m++) t += T2[6 * i + m] * Y[6 * m + j];
        K6[6 * i + j] = t;
      }
  }
  const double dQ = t3_det(Q) > 0.0 ? 1.0 : -1.0;
  for (int k = 0; k < 3; k++) {
    const double av[3] = {R[3 * k], R[3 * k + 1], R[3 * k + 2]}; /* R^T e_k */
    double       at[3];
    for (int i = 0; i < 3; i++) at[i] = Q[i] * av[0] + Q[3 + i] * av[1] + Q[6 + i] * av[2];
    for (int L = 0; L < 3; L++) {
      double cv[3], ct[3], ax[3] = {0, 0, 0}, om[3], ot[3], os[3];
      /* c = R^T (row L of Gm), c~ = Q^T c */
      for (int i = 0; i < 3; i++) cv[i] = R[i] * Gm[3 * L] + R[3 + i] * Gm[3 * L + 1] + R[6 + i] * Gm[3 * L + 2];
      for (int i = 0; i < 3; i++) ct[i] = Q[i] * cv[0] + Q[3 + i] * cv[1] + Q[6 + i] * cv[2];
      /* omega = Z (E_L x a), omega~ = det Q Q^T omega, R omega */
      if (L == 0) {
        ax[1] = -av[2];
        ax[2] = av[1];
      } else if (L == 1) {
        ax[0] = av[2];
        ax[2] = -av[0];
      } else {
        ax[0] = -av[1];
        ax[1] = av[0];
      }
      for (int i = 0; i < 3; i++) om[i] = Z[3 * i] * ax[0] + Z[3 * i + 1] * ax[1] + Z[3 * i + 2] * ax[2];
      for (int i = 0; i < 3; i++) {
        ot[i] = dQ * (Q[i] * om[0] + Q[3 + i] * om[1] + Q[6 + i] * om[2]);
        os[i] = R[3 * i] * om[0] + R[3 * i + 1] * om[1] + R[3 * i + 2] * om[2];
      }
      /* d eb' (Mandel, eigenbasis of bb); W(w)_01 = -w2, W_02 = w1, W_12 = -w0 */
      double x[6], ds[6];
      x[0] = Gam[0] * 2.0 * at[0] * ct[0];
      x[1] = Gam[4] * 2.0 * at[1] * ct[1];
      x[2] = Gam[8] * 2.0 * at[2] * ct[2];
      x[3] = SQ2 * Gam[5] * (at[1] * ct[2] + ct[1] * at[2] + (lam[1] - lam[2]) * -ot[0]);
      x[4] = SQ2 * Gam[2] * (at[2] * ct[0] + ct[2] * at[0] + (lam[2] - lam[0]) * -ot[1]);
      x[5] = SQ2 * Gam[1] * (at[0] * ct[1] + ct[0] * at[1] + (lam[0] - lam[1]) * -ot[2]);
      mv6(K6, x, ds);
      /* d tau = (ds as a tensor) + W(R omega) tau - tau W(R omega) */
      double dt[9];
      AnisoFromMandel(ds, dt);
      const double Ws[9] = {0, -os[2], os[1], os[2], 0, -os[0], -os[1], os[0], 0};
      double       T1[9], T2[9];
      t3_mul(Ws, tau, T1);
      t3_mul(tau, Ws, T2);
      const int col = 3 * k + L;
      for (int i = 0; i < 3; i++)
        for (int j = i; j < 3; j++) {
          const double v = dt[3 * i + j] + T1[3 * i + j] - T2[3 * i + j];
          dtau[9 * (3 * i + j) + col] = v;
          dtau[9 * (3 * j + i) + col] = v;
        }
    }
  }
  return MAT_OK;
}
