/* Unit tests of the Hill 48 material (src/material/hill48.c):
   (1) with r0 = r45 = r90 = 1 the stress, history and tangent equal J2's;
   (2) uniaxial tension at 0, 45 and 90 degrees to the rolling direction (lateral stresses free,
       Newton on the lateral stretches) gives back the r-values;
   (3) the tangent against central differences, elastic and plastic, rotated axes;
   (4) objectivity and the rotation of the axes together with F;
   the Material object of type hill48: its options and their validation. */
#include <math.h>
#include <stdio.h>
#include <string.h>
#include <time.h>

#include <petscsys.h>
#include "material_hill48.h"
#include "options.h"
#include "tensor.h"
#include "testutil.h"
#include "testmat.h"
#include "testaniso.h"

static const double PI = 3.14159265358979323846;

static J2Params swift(void)
{
  J2Params mp;
  J2ParamsDefaults(&mp);
  return mp;
}

static J2Params linear(double sy0, double H)
{
  J2Params mp;
  J2ParamsDefaults(&mp);
  mp.law = HARDENING_LINEAR;
  mp.sy0 = sy0;
  mp.H   = H;
  J2ParamsSetup(&mp);
  return mp;
}

static HillParams hill(J2Params base, double r0, double r45, double r90, const double rd[3], const double nd[3])
{
  HillParams hp;
  memset(&hp, 0, sizeof hp);
  hp.base   = base;
  hp.from_r = 1;
  hp.r0     = r0;
  hp.r45    = r45;
  hp.r90    = r90;
  for (int i = 0; i < 3; i++) {
    hp.rd[i] = rd[i];
    hp.nd[i] = nd[i];
  }
  int ierr = Hill48ParamsSetup(&hp);
  if (ierr) printf("# Hill48ParamsSetup: %d\n", ierr);
  return hp;
}

static const double X1[3] = {1, 0, 0}, Z1[3] = {0, 0, 1};

/* ---------- (1) r = 1: J2 ---------- */
static void test_j2(void)
{
  unsigned long long seed = 11;
  const J2Params     bases[2] = {swift(), linear(250.0, 1200.0)};
  const char        *names[2] = {"Swift", "linear"};
  const double       rd[3] = {0.6, 0.8, 0.0};
  for (int b = 0; b < 2; b++) {
    const HillParams hp = hill(bases[b], 1.0, 1.0, 1.0, rd, Z1);
    double           et = 0, eh = 0, ed = 0;
    int              npl = 0, nel = 0, nst = 0;
    for (int t = 0; t < 60; t++) {
      double F0[9], F1[9], hn[J2_NHIST], h0[J2_NHIST], tj[9], th[9], dj[81], dh[81], hj[J2_NHIST], hh[J2_NHIST];
      int    pj, ph, rj, rh;
      J2HistoryInit(hn);
      /* a committed plastic state, then a step from it: elastic (small) or plastic */
      random_F(&seed, 0.15, F0);
      J2Update(&bases[b], F0, hn, tj, NULL, h0, &pj);
      const double amp = t % 3 == 0 ? 2e-4 : 0.08;
      double       D[9];
      for (int i = 0; i < 9; i++) D[i] = amp * urand(&seed) + (i % 4 == 0 ? 1.0 : 0.0);
      if (t % 3 == 0) {
        elastic_F(&seed, h0, D, F1);
      } else t3_mul(F0, D, F1);
      rj = J2Update(&bases[b], F1, h0, tj, dj, hj, &pj);
      rh = Hill48Update(&hp, F1, h0, th, dh, hh, &ph);
      if (rj || rh || pj != ph) {
        nst++;
        continue;
      }
      npl += pj;
      nel += !pj;
      et = fmax(et, rel(th, tj, 9));
      ed = fmax(ed, rel(dh, dj, 81));
      eh = fmax(eh, rel(hh, hj, J2_NHIST));
    }
    TU_CHECK(nst == 0 && npl >= 20 && nel >= 5 && et < 1e-10 && ed < 1e-10 && eh < 1e-10,
             "r0 = r45 = r90 = 1 (%s, rd at 53 deg) = J2 over %d plastic and %d elastic states: tau %.1e, dtau %.1e, history %.1e (relative), %d mismatched statuses", names[b], npl, nel, et,
             ed, eh, nst);
  }
  {
    double F, G, H, L, M, N;
    Hill48FromR(1, 1, 1, &F, &G, &H, &L, &M, &N);
    TU_CHECK(F == 0.5 && G == 0.5 && H == 0.5 && L == 1.5 && M == 1.5 && N == 1.5, "r-values 1, 1, 1 -> F = G = H = 1/2, L = M = N = 3/2 (von Mises)");
  }
}

/* ---------- (2) uniaxial tension at angle th: r-values ---------- */

/* plastic log strain -1/2 ln Cp^{-1} */
static void plastic_log(const double *h, double Ep[9])
{
  double C[9], lam[3], Q[9];
  hist_to_mat(h, C);
  t3_sym_eig(C, lam, Q);
  for (int i = 0; i < 3; i++)
    for (int j = 0; j < 3; j++) {
      Ep[3 * i + j] = 0.0;
      for (int a = 0; a < 3; a++) Ep[3 * i + j] += Q[3 * i + a] * (-0.5 * log(lam[a])) * Q[3 * j + a];
    }
}

/* the r-value at angle th (radians) to the rolling direction, measured as the ratio of the width
   to the thickness plastic strain at axial stretch lam_end; returns -1 if a Newton fails */
static double uniaxial_r(const HillParams *hp, double th, double lam_end, int nsteps, double *r_inc, double *maxres)
{
  /* load frame T = [d, w, nd] in the sheet plane of rolling direction x, normal z */
  const double T[9] = {cos(th), -sin(th), 0, sin(th), cos(th), 0, 0, 0, 1};
  double       x[3] = {1, 1, 0}, hn[J2_NHIST], h[J2_NHIST], Epp[9];
  double       dres = 0;
  J2HistoryInit(hn);
  for (int st = 1; st <= nsteps; st++) {
    const double lam = 1.0 + (lam_end - 1.0) * st / nsteps;
    int          conv = 0;
    for (int it = 0; it < 30; it++) {
      const double Ul[9] = {lam, x[2], 0, x[2], x[0], 0, 0, 0, x[1]};
      double       Fg[9], tau[9], dtau[81], tl[9], res[3], Jm[9], Ji[9];
      int          pl;
      rot2(T, Ul, Fg);
      if (Hill48Update(hp, Fg, hn, tau, dtau, h, &pl)) return -1;
      double Tt[9];
      t3_transpose(T, Tt);
      rot2(Tt, tau, tl);
      res[0] = tl[4];
      res[1] = tl[8];
      res[2] = tl[1];
      if (fnorm(res, 3) < 1e-10 * fnorm(tau, 9)) {
        conv = 1;
        dres = fmax(dres, fnorm(res, 3) / fnorm(tau, 9));
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
        Jm[3 * 0 + i] = dtl[4];
        Jm[3 * 1 + i] = dtl[8];
        Jm[3 * 2 + i] = dtl[1];
      }
      t3_inv(Jm, Ji);
      for (int i = 0; i < 3; i++) x[i] -= Ji[3 * i] * res[0] + Ji[3 * i + 1] * res[1] + Ji[3 * i + 2] * res[2];
    }
    if (!conv) return -1;
    if (st == nsteps - 1) plastic_log(h, Epp);
    memcpy(hn, h, sizeof hn);
  }
  double Ep[9];
  plastic_log(hn, Ep);
  /* width w = T e_2, thickness nd */
  const double w[3] = {T[1], T[4], T[7]};
  double       eww = 0, eww0 = 0;
  for (int i = 0; i < 3; i++)
    for (int j = 0; j < 3; j++) {
      eww += w[i] * Ep[3 * i + j] * w[j];
      eww0 += w[i] * Epp[3 * i + j] * w[j];
    }
  *r_inc  = (eww - eww0) / (Ep[8] - Epp[8]);
  *maxres = dres;
  return eww / Ep[8];
}

static void test_rvalues(void)
{
  const double r[3] = {1.6, 1.2, 2.0}, ang[3] = {0, 45, 90};
  for (int b = 0; b < 2; b++) {
    const J2Params   base = b ? linear(200.0, 800.0) : swift();
    const HillParams hp   = hill(base, r[0], r[1], r[2], X1, Z1);
    for (int k = 0; k < 3; k++) {
      double       rinc = 0, res = 0;
      const double rv = uniaxial_r(&hp, ang[k] * PI / 180.0, 1.02, 10, &rinc, &res);
      TU_CHECK(rv > 0 && fabs(rv - r[k]) < 0.01 * r[k] && fabs(rinc - r[k]) < 0.01 * r[k],
               "uniaxial tension at %2.0f deg to the rolling direction (%s, 2 %% stretch): r = %.5f (total), %.5f (last step), input %.2f; lateral stresses %.1e", ang[k],
               b ? "linear" : "Swift", rv, rinc, r[k], res);
    }
  }
  /* the rolling direction along y, normal along x: the same r-values in the rotated sheet */
  {
    const double     rd[3] = {0, 1, 0}, nd[3] = {1, 0, 0};
    const HillParams hp0   = hill(swift(), 1.6, 1.2, 2.0, X1, Z1);
    const HillParams hp1   = hill(swift(), 1.6, 1.2, 2.0, rd, nd);
    double           Q[9]  = {0, 0, 1, 1, 0, 0, 0, 1, 0}; /* x -> y, y -> z, z -> x */
    double           F[9], F1[9], hn[J2_NHIST], h0[J2_NHIST], h1[J2_NHIST], t0[9], t1[9], tq[9], d0[81], d1[81];
    int              p0, p1;
    unsigned long long seed = 5;
    double             e = 0;
    int                npl = 0;
    for (int t = 0; t < 20; t++) {
      J2HistoryInit(hn);
      random_F(&seed, 0.1, F);
      rot2(Q, F, F1);
      Hill48Update(&hp0, F, hn, t0, d0, h0, &p0);
      Hill48Update(&hp1, F1, hn, t1, d1, h1, &p1);
      rot2(Q, t0, tq);
      e = fmax(e, rel(t1, tq, 9));
      npl += p0 && p1;
    }
    TU_CHECK(e < 1e-12 && npl == 20, "axes (rd y, normal x) with F -> Q F Q^T (Q: x->y, y->z, z->x) give Q tau Q^T: %.1e over %d plastic states", e, npl);
  }
}

/* ---------- the return map on large steps: converged, on the yield surface, flow rule ---------- */
static void test_robust(void)
{
  unsigned long long seed = 19;
  const double       rd[3] = {1, 2, 0.5}, nd[3] = {-2, 1, 0};
  const HillParams   hps[3] = {hill(swift(), 0.3, 3.0, 0.5, rd, nd), hill(linear(150.0, 0.0), 2.8, 0.4, 1.9, X1, Z1), hill(swift(), 1.6, 1.2, 2.0, X1, Z1)};
  int                nfail = 0, npl = 0;
  double             eyield = 0;
  for (int b = 0; b < 3; b++)
    for (int t = 0; t < 100; t++) {
      double F0[9], F[9], hn[J2_NHIST], h0[J2_NHIST], h[J2_NHIST], tau[9];
      int    pl;
      J2HistoryInit(hn);
      random_F(&seed, 0.3, F0);
      if (Hill48Update(&hps[b], F0, hn, tau, NULL, h0, &pl)) {
        nfail++;
        continue;
      }
      random_F(&seed, 0.5, F);
      if (Hill48Update(&hps[b], F, h0, tau, NULL, h, &pl)) {
        nfail++;
        continue;
      }
      if (!pl) continue;
      npl++;
      /* q of the rotated stress in the orthotropy frame against sigma_y(ep): s = A^T R^T tau R A */
      double C[9], lam[3], Q[9], ui[3], Ui[9], R[9], RA[9], S[9], sv[6], Ps[6], q2 = 0;
      t3_tmul(F, F, C);
      t3_sym_eig(C, lam, Q);
      for (int a = 0; a < 3; a++) ui[a] = 1.0 / sqrt(lam[a]);
      for (int i = 0; i < 3; i++)
        for (int j = 0; j < 3; j++) Ui[3 * i + j] = Q[3 * i] * ui[0] * Q[3 * j] + Q[3 * i + 1] * ui[1] * Q[3 * j + 1] + Q[3 * i + 2] * ui[2] * Q[3 * j + 2];
      t3_mul(F, Ui, R);
      t3_mul(R, hps[b].A, RA);
      double RAt[9];
      t3_transpose(RA, RAt);
      rot2(RAt, tau, S);
      const double r2 = 1.41421356237309504880;
      sv[0] = S[0];
      sv[1] = S[4];
      sv[2] = S[8];
      sv[3] = r2 * S[5];
      sv[4] = r2 * S[2];
      sv[5] = r2 * S[1];
      for (int i = 0; i < 6; i++) {
        Ps[i] = 0;
        for (int j = 0; j < 6; j++) Ps[i] += hps[b].P[6 * i + j] * sv[j];
        q2 += sv[i] * Ps[i];
      }
      const double sy = J2YieldStress(&hps[b].base, h[J2_HIST_EP], NULL);
      eyield          = fmax(eyield, fabs(sqrt(q2) - sy) / sy);
    }
  TU_CHECK(nfail == 0 && npl >= 200 && eyield < 1e-8,
           "large steps (|F - R| up to 0.5, r 0.3/3.0/0.5 oblique, 2.8/0.4/1.9 perfectly plastic, 1.6/1.2/2.0): %d failures, %d plastic, |q(s) - sigma_y(ep)|/sigma_y <= %.1e (tolerance rtol q_tr)", nfail, npl, eyield);
}

/* a converged plastic state evaluated again with the same F (no increment: the committed state at
   the start of a step, hex8_eas's local iteration started from its committed parameters): the
   trial state lies on the yield surface to round-off, on either side; the update must accept it
   with no further flow (the same stress and history), not report a failed return map */
static void test_reevaluate(void)
{
  unsigned long long seed = 23;
  const double       rd[3] = {1, 2, 0.5}, nd[3] = {-2, 1, 0};
  const HillParams   hps[2] = {hill(swift(), 0.71, 0.58, 0.70, X1, Z1), hill(swift(), 0.3, 3.0, 0.5, rd, nd)};
  int                nfail = 0, npl = 0, nyield = 0;
  double             et = 0, eh = 0;
  for (int b = 0; b < 2; b++)
    for (int t = 0; t < 100; t++) {
      double F[9], hn[J2_NHIST], h1[J2_NHIST], h2[J2_NHIST], t1[9], t2[9];
      int    p1, p2;
      J2HistoryInit(hn);
      random_F(&seed, 0.1, F);
      if (Hill48Update(&hps[b], F, hn, t1, NULL, h1, &p1) || !p1) continue;
      npl++;
      if (Hill48Update(&hps[b], F, h1, t2, NULL, h2, &p2)) {
        nfail++;
        continue;
      }
      nyield += p2;
      et = fmax(et, rel(t2, t1, 9));
      eh = fmax(eh, fabs(h2[J2_HIST_EP] - h1[J2_HIST_EP]) / h1[J2_HIST_EP]);
    }
  TU_CHECK(nfail == 0 && npl >= 150 && nyield > 0 && et < 1e-10 && eh < 1e-10,
           "a converged plastic state evaluated again with no increment: %d failures of %d (%d on the yield surface's plastic side), stress %.1e and plastic strain %.1e from the first evaluation", nfail, npl, nyield, et, eh);
}

/* ---------- (3) tangent against central differences ---------- */
static double tangent_fd_error(const HillParams *hp, const double F[9], const double hn[J2_NHIST], int *plastic)
{
  double tau[9], dtau[81], fd[81], h[J2_NHIST], tp[9], tm[9];
  int    pl;
  Hill48Update(hp, F, hn, tau, dtau, h, plastic);
  const double step = 1e-6 * fnorm(F, 9) / sqrt(3.0);
  for (int c = 0; c < 9; c++) {
    double Fp[9], Fm[9];
    memcpy(Fp, F, sizeof Fp);
    memcpy(Fm, F, sizeof Fm);
    Fp[c] += step;
    Fm[c] -= step;
    Hill48Update(hp, Fp, hn, tp, NULL, h, &pl);
    Hill48Update(hp, Fm, hn, tm, NULL, h, &pl);
    for (int r = 0; r < 9; r++) fd[9 * r + c] = (tp[r] - tm[r]) / (2.0 * step);
  }
  return rel(dtau, fd, 81);
}

static void test_tangent(void)
{
  unsigned long long seed = 7;
  const double       rd[3] = {1, 1, 0.3}, nd[3] = {-1, 1, 0};
  const HillParams   hps[3] = {hill(swift(), 1.6, 1.2, 2.0, X1, Z1), hill(linear(150.0, 900.0), 1.6, 1.2, 2.0, rd, nd), hill(linear(150.0, 0.0), 0.7, 2.5, 1.3, rd, nd)};
  const char        *names[3] = {"Swift, rd x", "linear, rotated axes", "perfect plasticity, r 0.7/2.5/1.3, rotated axes"};
  for (int b = 0; b < 3; b++) {
    double emax[2] = {0, 0};
    int    cnt[2]  = {0, 0};
    for (int t = 0; t < 30; t++) {
      double F0[9], F1[9], D[9], hn[J2_NHIST], h0[J2_NHIST], tau[9];
      int    pl;
      J2HistoryInit(hn);
      random_F(&seed, 0.12, F0);
      if (Hill48Update(&hps[b], F0, hn, tau, NULL, h0, &pl)) continue;
      const double amp = t % 2 ? 3e-4 : 0.06;
      for (int i = 0; i < 9; i++) D[i] = amp * urand(&seed) + (i % 4 == 0 ? 1.0 : 0.0);
      if (t % 2) {
        elastic_F(&seed, h0, D, F1);
      } else t3_mul(F0, D, F1);
      const double e = tangent_fd_error(&hps[b], F1, h0, &pl);
      emax[pl] = fmax(emax[pl], e);
      cnt[pl]++;
    }
    TU_CHECK(cnt[0] >= 10 && cnt[1] >= 10 && emax[0] < 1e-7 && emax[1] < 1e-6, "tangent vs central differences (%s): elastic %.1e over %d, plastic %.1e over %d (relative)", names[b], emax[0],
             cnt[0], emax[1], cnt[1]);
  }
}

/* ---------- (4) objectivity ---------- */
static void test_objectivity(void)
{
  unsigned long long seed = 3;
  const double       rd[3] = {0.8, 0.6, 0}, z[3] = {0, 0, 1};
  const HillParams   hp    = hill(swift(), 1.6, 1.2, 2.0, rd, z);
  double             Q90[9];
  rotation(z, 0.5 * PI, Q90);
  const double     rdq[3] = {Q90[0] * rd[0] + Q90[1] * rd[1], Q90[3] * rd[0] + Q90[4] * rd[1], 0};
  const HillParams hq     = hill(swift(), 1.6, 1.2, 2.0, rdq, z);
  double           e1 = 0, e1h = 0, e1d = 0, e2 = 0, e2h = 0, e2d = 0, ediff = 0;
  int              npl = 0;
  for (int t = 0; t < 20; t++) {
    double F0[9], F[9], hn[J2_NHIST], h0[J2_NHIST], tau[9], dtau[81], h[J2_NHIST], tau0[9];
    int    pl;
    J2HistoryInit(hn);
    random_F(&seed, 0.1, F0);
    Hill48Update(&hp, F0, hn, tau0, NULL, h0, &pl);
    random_F(&seed, 0.15, F);
    Hill48Update(&hp, F, h0, tau, dtau, h, &pl);
    npl += pl;
    /* 90 degree rotation of the axes, of F (both configurations) and of the history */
    {
      double Fq[9], C0[9], Cq[9], hq0[J2_NHIST], hq1[J2_NHIST], tq[9], dq[81], Ch[9], Chq[9], tex[9], dex[81];
      rot2(Q90, F, Fq);
      hist_to_mat(h0, C0);
      rot2(Q90, C0, Cq);
      memcpy(hq0, h0, sizeof hq0);
      mat_to_hist(Cq, hq0);
      Hill48Update(&hq, Fq, hq0, tq, dq, hq1, &pl);
      rot2(Q90, tau, tex);
      hist_to_mat(h, Ch);
      rot2(Q90, Ch, Chq);
      double hex[J2_NHIST];
      mat_to_hist(Chq, hex);
      hex[J2_HIST_EP] = h[J2_HIST_EP];
      /* d tau'_ij / d F'_kL = Q_ia Q_jb Q_kc Q_Ld dtau_ab,cd */
      for (int i = 0; i < 81; i++) {
        const int a = i / 27, b = (i / 9) % 3, c = (i / 3) % 3, d = i % 3;
        double    s = 0;
        for (int p = 0; p < 81; p++) {
          const int pa = p / 27, pb = (p / 9) % 3, pc = (p / 3) % 3, pd = p % 3;
          s += Q90[3 * a + pa] * Q90[3 * b + pb] * Q90[3 * c + pc] * Q90[3 * d + pd] * dtau[9 * (3 * pa + pb) + 3 * pc + pd];
        }
        dex[9 * (3 * a + b) + 3 * c + d] = s;
      }
      e1  = fmax(e1, rel(tq, tex, 9));
      e1h = fmax(e1h, rel(hq1, hex, J2_NHIST));
      e1d = fmax(e1d, rel(dq, dex, 81));
      /* the same F with the unrotated axes: a different (anisotropic) answer */
      ediff = fmax(ediff, rel(tq, tau, 9) > 0 ? fdiff(tex, tau, 9) / fnorm(tau, 9) : 0);
    }
    /* F -> Q F (superposed rigid rotation), axes fixed in the material */
    {
      double Q[9], QF[9], t2[9], d2[81], h2[J2_NHIST], tex[9], dex[81];
      random_rotation(&seed, Q);
      t3_mul(Q, F, QF);
      Hill48Update(&hp, QF, h0, t2, d2, h2, &pl);
      rot2(Q, tau, tex);
      /* d tau'_ij / d F'_kL = Q_ia Q_jb Q_kc dtau_ab,cL */
      for (int i = 0; i < 81; i++) {
        const int a = i / 27, b = (i / 9) % 3, c = (i / 3) % 3, d = i % 3;
        double    s = 0;
        for (int pa = 0; pa < 3; pa++)
          for (int pb = 0; pb < 3; pb++)
            for (int pc = 0; pc < 3; pc++) s += Q[3 * a + pa] * Q[3 * b + pb] * Q[3 * c + pc] * dtau[9 * (3 * pa + pb) + 3 * pc + d];
        dex[9 * (3 * a + b) + 3 * c + d] = s;
      }
      e2  = fmax(e2, rel(t2, tex, 9));
      e2h = fmax(e2h, rel(h2, h, J2_NHIST));
      e2d = fmax(e2d, rel(d2, dex, 81));
    }
  }
  TU_CHECK(npl >= 15 && e1 < 1e-12 && e1h < 1e-12 && e1d < 1e-11 && ediff > 1e-3,
           "axes rotated 90 deg about the normal with F and the history: tau %.1e, history %.1e, dtau %.1e (%d plastic of 20; unrotated axes differ by %.2f)", e1, e1h, e1d, npl, ediff);
  TU_CHECK(e2 < 1e-12 && e2h < 1e-12 && e2d < 1e-11, "objectivity, F -> Q F: tau -> Q tau Q^T %.1e, history unchanged %.1e, dtau rotated %.1e", e2, e2h, e2d);
}

/* ---------- the Material object ---------- */
static PetscErrorCode test_object(void)
{
  Material              mat;
  PetscErrorCode        ierr;
  const MaterialKernel *mk;

  PetscFunctionBeginUser;
  PetscCall(MaterialFromOptions("-material_type hill48", &mat, &ierr));
  TU_CHECK(!ierr, "-material_type hill48 (status %d) [%s]", (int)ierr, ErrMsg);
  if (ierr) PetscFunctionReturn(0);
  PetscCall(MaterialGetKernel(mat, &mk));
  {
    const HillParams *hp = (const HillParams *)mk->ctx;
    J2Params          sw = swift();
    TU_CHECK(mk->nhist == HILL48_NHIST && hp->F == 0.5 && hp->G == 0.5 && hp->H == 0.5 && hp->N == 1.5 && hp->A[0] == 1 && hp->A[4] == 1 && hp->A[8] == 1 && !memcmp(&hp->base, &sw, sizeof sw),
             "defaults: J2's elasticity and Swift hardening, r-values 1 (F = G = H = 1/2, N = 3/2), rolling direction x, normal z, nhist %d", mk->nhist);
  }
  PetscCall(MaterialDestroy(&mat));

  PetscCall(MaterialFromOptions("-material_type hill48 -material_hill_r0 1.6 -material_hill_r45 1.2 -material_hill_r90 2.0 -material_hill_rd 0,2,0 -material_hill_normal 1,0,0 -material_hardening "
                                "linear -material_yield 250 -material_hardening_modulus 1000",
                                &mat, &ierr));
  if (!ierr) {
    PetscCall(MaterialGetKernel(mat, &mk));
    const HillParams *hp  = (const HillParams *)mk->ctx;
    const double      yd[3] = {0, 1, 0}, xd[3] = {1, 0, 0};
    const HillParams  ex  = hill(linear(250.0, 1000.0), 1.6, 1.2, 2.0, yd, xd);
    double            F[9] = {1.06, 0.04, -0.03, 0.02, 0.97, 0.05, -0.04, 0.01, 0.99}, hn[J2_NHIST], h1[J2_NHIST], h2[J2_NHIST], t1[9], t2[9], d1[81], d2[81];
    int               p1, p2, r1, r2;
    mk->history_init(mk->ctx, hn);
    r1 = Hill48Update(&ex, F, hn, t1, d1, h1, &p1);
    r2 = mk->update(mk->ctx, F, hn, t2, d2, h2, &p2);
    TU_CHECK(hp->base.law == HARDENING_LINEAR && hp->base.sy0 == 250 && hp->r90 == 2.0 && fabs(hp->H - 1.6 / 2.6) < 1e-15 && hp->A[3] == 1 && hp->A[7] == 1 && hp->A[2] == 1,
             "-material_hill_r0, _r45, _r90, _rd, _normal and J2's hardening options read (H = %.4f, frame rd y, td z, normal x)", hp->H);
    ierr = MaterialView(mat, PETSC_VIEWER_STDOUT_SELF);
    TU_CHECK(!ierr, "MaterialView of hill48 (status %d)", (int)ierr);
    TU_CHECK(r1 == r2 && p1 == p2 && p1 && !memcmp(t1, t2, sizeof t1) && !memcmp(d1, d2, sizeof d1) && !memcmp(h1, h2, sizeof h1) && mk->plastic_strain(mk->ctx, h2) == h2[HILL48_HIST_EP],
             "MaterialKernel.update of hill48 = Hill48Update bit for bit, plastic_strain = h[6] = %.4f", h2[HILL48_HIST_EP]);
    PetscCall(MaterialDestroy(&mat));
  } else TU_CHECK(0, "r-value options: error %d [%s]", (int)ierr, ErrMsg);

  PetscCall(MaterialFromOptions("-material_type hill48 -material_hill_F 0.3 -material_hill_G 0.4 -material_hill_H 0.6 -material_hill_N 1.9", &mat, &ierr));
  if (!ierr) {
    PetscCall(MaterialGetKernel(mat, &mk));
    const HillParams *hp = (const HillParams *)mk->ctx;
    TU_CHECK(!hp->from_r && hp->F == 0.3 && hp->G == 0.4 && hp->H == 0.6 && hp->L == 1.5 && hp->M == 1.5 && hp->N == 1.9 && hp->P[0] == 1.0 && hp->P[35] == 1.9,
             "-material_hill_F, _G, _H, _N read (L, M stay 3/2)");
    PetscCall(MaterialDestroy(&mat));
  } else TU_CHECK(0, "coefficient options: error %d [%s]", (int)ierr, ErrMsg);
  {
    const char *closest = AtritoOptionsClosest("-material_hill_normall");
    TU_CHECK(closest && !strcmp(closest, "-material_hill_normal"), "options recorded: closest to -material_hill_normall is %s", closest ? closest : "(none)");
  }

  {
    const char *bad[][2] = {
      {"-material_type hill48 -material_hill_r0 0",                                            "-material_hill_r0 0. must be positive"        },
      {"-material_type hill48 -material_hill_r45 -1",                                          "-material_hill_r45 -1. must be positive"      },
      {"-material_type hill48 -material_hill_rd 1,0,0 -material_hill_normal 1,0,1",            "must be orthogonal"                           },
      {"-material_type hill48 -material_hill_rd 0,0,0",                                        "-material_hill_rd 0.,0.,0. must be a non-zero"},
      {"-material_type hill48 -material_hill_normal 1,0",                                      "-material_hill_normal needs 3 components"     },
      {"-material_type hill48 -material_hill_F -1 -material_hill_G -1",                        "give a non-convex yield surface"              },
      {"-material_type hill48 -material_hill_L 0",                                             "-material_hill_L 0. must be positive"         },
      {"-material_type hill48 -material_hill_r0 2 -material_hill_H 0.5",                       "exclude each other"                           },
      {"-material_type hill48 -material_swift_n 1.5",                                          "-material_swift_n 1.5 must lie in [0, 1)"     },
    };
    for (size_t i = 0; i < sizeof(bad) / sizeof(bad[0]); i++) {
      PetscCall(MaterialFromOptions(bad[i][0], &mat, &ierr));
      TU_CHECK(ierr == PETSC_ERR_USER_INPUT && !mat && strstr(ErrMsg, bad[i][1]), "%s: refused with '%s' [%s]", bad[i][0], bad[i][1], ErrMsg);
    }
  }
  PetscFunctionReturn(0);
}

/* ---------- cost per call (informative, no check) ---------- */
static void timing(void)
{
  const J2Params   mp = swift();
  const HillParams hp = hill(swift(), 1.6, 1.2, 2.0, X1, Z1);
  double           hn[J2_NHIST], hc[J2_NHIST], h[J2_NHIST], tau[9], dtau[81], acc = 0.0;
  int              pl = 0;
  J2HistoryInit(hn);
  const double F1[9] = {1.06, 0.04, -0.03, 0.02, 0.97, 0.05, -0.04, 0.01, 0.99};
  double       F2[9] = {1.10, 0.09, -0.02, 0.05, 0.94, 0.08, -0.06, 0.04, 1.01};
  Hill48Update(&hp, F1, hn, tau, NULL, hc, &pl);
  const int       N = 100000;
  struct timespec t0, t1;
  for (int model = 0; model < 2; model++)
    for (int pass = 0; pass < 2; pass++) {
      timespec_get(&t0, TIME_UTC);
      for (int i = 0; i < N; i++) {
        F2[0] = 1.10 + 1e-9 * (i & 7);
        if (model) J2Update(&mp, F2, hc, tau, pass ? NULL : dtau, h, &pl);
        else Hill48Update(&hp, F2, hc, tau, pass ? NULL : dtau, h, &pl);
        acc += tau[0] + (pass ? 0.0 : dtau[40]);
      }
      timespec_get(&t1, TIME_UTC);
      const double ns = ((t1.tv_sec - t0.tv_sec) * 1e9 + (t1.tv_nsec - t0.tv_nsec)) / N;
      printf("# timing: %s plastic (Swift%s) %s tangent: %.0f ns/call (plastic=%d, checksum %.3e)\n", model ? "J2Update" : "Hill48Update", model ? "" : ", r 1.6/1.2/2.0",
             pass ? "without" : "with", ns, pl, acc);
    }
}

int main(int argc, char **argv)
{
  PetscCall(PetscInitialize(&argc, &argv, NULL, NULL));
  test_j2();
  test_rvalues();
  test_tangent();
  test_robust();
  test_reevaluate();
  test_objectivity();
  PetscCall(test_object());
  timing();
  PetscCall(PetscFinalize());
  TU_RETURN();
}
