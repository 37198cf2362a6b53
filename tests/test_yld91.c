/* Unit tests of the Barlat 1991 material (src/material/yld91.c):
   (1) exponent 2 is Hill 1948: stress, history and tangent equal hill48's for the same r-values;
   (2) the fit: the flow rule's r-values at 0, 45, 90 deg are the input ones, the rolling
       direction's effective stress is the tension; Hosford's isotropic closed forms (plane
       strain, pure shear, equibiaxial) for c = 1;
   (3) the effective stress's gradient and Hessian against central differences, at distinct and
       at repeated principal values;
   (4) the tangent dtau/dF against central differences, elastic and plastic, rotated axes;
   (5) large steps: no failure, a converged state evaluated again flows no further;
   (6) objectivity;
   the Material object of type yld91: its options and their validation. */
#include <math.h>
#include <stdio.h>
#include <string.h>
#include <time.h>

#include <petscsys.h>
#include "material_hill48.h"
#include "material_yld91.h"
#include "options.h"
#include "tensor.h"
#include "testutil.h"
#include "testmat.h"
#include "testaniso.h"

static const double PI = 3.14159265358979323846;
static const double X1[3] = {1, 0, 0}, Z1[3] = {0, 0, 1};

static J2Params swift(void)
{
  J2Params mp;
  J2ParamsDefaults(&mp);
  J2ParamsSetup(&mp);
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

static Yld91Params yld(J2Params base, int m, double r0, double r45, double r90, const double rd[3], const double nd[3], int *status)
{
  Yld91Params yp;
  memset(&yp, 0, sizeof yp);
  yp.base   = base;
  yp.m      = m;
  yp.from_r = 1;
  yp.r0     = r0;
  yp.r45    = r45;
  yp.r90    = r90;
  for (int i = 0; i < 3; i++) {
    yp.rd[i] = rd[i];
    yp.nd[i] = nd[i];
  }
  *status = Yld91ParamsSetup(&yp);
  return yp;
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
  Hill48ParamsSetup(&hp);
  return hp;
}

/* ---------- (1) m = 2: Hill 1948 ---------- */
static void test_hill(void)
{
  unsigned long long seed = 31;
  const double       rd[3] = {0.6, 0.8, 0.0};
  const double       rv[2][3] = {
    {0.71, 0.58, 0.70},
    {1.6,  1.2,  2.0 }
  };
  for (int b = 0; b < 2; b++) {
    int               st;
    const Yld91Params yp = yld(b ? linear(250.0, 1200.0) : swift(), 2, rv[b][0], rv[b][1], rv[b][2], rd, Z1, &st);
    const HillParams  hp = hill(b ? linear(250.0, 1200.0) : swift(), rv[b][0], rv[b][1], rv[b][2], rd, Z1);
    double            et = 0, eh = 0, ed = 0;
    int               npl = 0, nel = 0, nst = 0;
    for (int t = 0; t < 60 && !st; t++) {
      double F0[9], F1[9], hn[J2_NHIST], h0[J2_NHIST], ty[9], th[9], dy[81], dh[81], hy[J2_NHIST], hh[J2_NHIST], D[9];
      int    py, ph, ry, rh;
      J2HistoryInit(hn);
      random_F(&seed, 0.15, F0);
      Hill48Update(&hp, F0, hn, th, NULL, h0, &ph);
      const double amp = t % 3 == 0 ? 2e-4 : 0.08;
      for (int i = 0; i < 9; i++) D[i] = amp * urand(&seed) + (i % 4 == 0 ? 1.0 : 0.0);
      if (t % 3 == 0) elastic_F(&seed, h0, D, F1);
      else t3_mul(F0, D, F1);
      ry = Yld91Update(&yp, F1, h0, ty, dy, hy, &py);
      rh = Hill48Update(&hp, F1, h0, th, dh, hh, &ph);
      if (ry || rh || py != ph) {
        nst++;
        continue;
      }
      npl += py;
      nel += !py;
      et = fmax(et, rel(ty, th, 9));
      ed = fmax(ed, rel(dy, dh, 81));
      eh = fmax(eh, rel(hy, hh, J2_NHIST));
    }
    TU_CHECK(!st && nst == 0 && npl >= 20 && nel >= 5 && et < 1e-9 && ed < 1e-8 && eh < 1e-9,
             "exponent 2 = hill48 (r %.2f/%.2f/%.2f, rd at 53 deg) over %d plastic and %d elastic states: tau %.1e, dtau %.1e, history %.1e (relative), %d mismatches, setup %d", rv[b][0], rv[b][1],
             rv[b][2], npl, nel, et, ed, eh, nst, st);
  }
}

/* ---------- (2) the fit and the isotropic closed forms ---------- */
static void test_fit(void)
{
  const double rv[3][3] = {
    {0.71, 0.58, 0.70},
    {1.79, 1.51, 2.27},
    {0.3,  3.0,  0.5 }
  };
  const int ms[3] = {8, 6, 12};
  for (int b = 0; b < 3; b++)
    for (int k = 0; k < 3; k++) {
      int               st;
      const Yld91Params yp = yld(swift(), ms[k], rv[b][0], rv[b][1], rv[b][2], X1, Z1, &st);
      const double      one[6] = {1, 0, 0, 0, 0, 0};
      double            e = 0;
      for (int a = 0; a < 3 && !st; a++) e = fmax(e, fabs(Yld91RValue(&yp, a * 0.25 * PI) / rv[b][a] - 1.0));
      const double se = st ? 0 : Yld91Effective(&yp, one, NULL, NULL);
      TU_CHECK(!st && e < 1e-10 && fabs(se - 1.0) < 1e-14, "exponent %2d fitted to r %.2f/%.2f/%.2f: r-values to %.1e, rolling-direction tension's effective stress 1 + %.1e (c = %.4f %.4f %.4f %.4f; setup %d)",
               ms[k], rv[b][0], rv[b][1], rv[b][2], e, se - 1.0, yp.c[0], yp.c[1], yp.c[2], yp.c[5], st);
    }
  /* Hosford, c = 1: plane strain (1, 1/2, 0) has principal deviator (1/2, 0, -1/2), Phi = 1 + 2^(1-m);
     pure shear (1, -1, 0): Phi = 2^m + 2; equibiaxial (1, 1, 0): Phi = 2 */
  for (int k = 0; k < 3; k++) {
    int               st;
    const int         m  = ms[k];
    const Yld91Params yp = yld(swift(), m, 1, 1, 1, X1, Z1, &st);
    const double      ps[6] = {1, 0.5, 0, 0, 0, 0}, sh[6] = {1, -1, 0, 0, 0, 0}, bi[6] = {1, 1, 0, 0, 0, 0}, sh12[6] = {0, 0, 0, 0, 0, sqrt(2.0)};
    const double      eps = fabs(Yld91Effective(&yp, ps, NULL, NULL) - pow(0.5 * (1.0 + pow(2.0, 1.0 - m)), 1.0 / m));
    const double      esh = fabs(Yld91Effective(&yp, sh, NULL, NULL) - pow(0.5 * (pow(2.0, m) + 2.0), 1.0 / m));
    const double      ebi = fabs(Yld91Effective(&yp, bi, NULL, NULL) - 1.0);
    const double      e12 = fabs(Yld91Effective(&yp, sh12, NULL, NULL) - pow(0.5 * (pow(2.0, m) + 2.0), 1.0 / m));
    TU_CHECK(!st && yp.c[0] == 1 && yp.c[5] == 1 && eps < 1e-14 && esh < 1e-14 && ebi < 1e-14 && e12 < 1e-14,
             "exponent %2d, r-values 1: c = 1 (Hosford), plane strain, pure shear, shear s12 and equibiaxial effective stresses to closed forms (%.1e %.1e %.1e %.1e)", m, eps, esh, e12, ebi);
  }
  {
    int               st;
    const Yld91Params yp = yld(swift(), 8, 0.71, 0.58, 0.70, X1, Z1, &st);
    const double      bi[6] = {1, 1, 0, 0, 0, 0};
    const double      rb    = 1.0 / Yld91Effective(&yp, bi, NULL, NULL);
    /* Hill 1948 with the same r0, r90: sigma_b / sigma_0 = sqrt((1 + r0) r90 / (r0 + r90)) */
    const double rh = sqrt((1.0 + 0.71) * 0.70 / (0.71 + 0.70));
    TU_CHECK(!st && rb > rh + 0.02 && rb < 1.0, "aluminium (r 0.71/0.58/0.70), exponent 8: equibiaxial / uniaxial yield stress %.4f, between Hill 1948's %.4f and Hosford's isotropic 1", rb, rh);
  }
}

/* ---------- (3) gradient and Hessian against central differences ---------- */
static void test_derivatives(void)
{
  unsigned long long seed = 41;
  const int          ms[2] = {8, 6};
  for (int k = 0; k < 2; k++) {
    int               st;
    const double      rd[3] = {1, 1, 0.3}, nd[3] = {-1, 1, 0};
    const Yld91Params yp = yld(swift(), ms[k], 0.71, 0.58, 0.70, rd, nd, &st);
    double            eg = 0, eH = 0, ehom = 0;
    for (int t = 0; t < 40 && !st; t++) {
      double s[6], n[6], H[36], nf[6], Hf[36];
      for (int i = 0; i < 6; i++) s[i] = 300.0 * urand(&seed);
      if (t % 4 == 1) s[3] = s[4] = s[5] = 0, s[1] = s[0]; /* repeated principal values of S~ when L keeps the axes */
      if (t % 4 == 2) s[1] = s[2] = s[3] = s[4] = s[5] = 0;  /* uniaxial along the rolling direction */
      if (t % 4 == 3) s[2] = s[3] = s[4] = 0, s[0] = s[1] = 200.0, s[5] = 0; /* equibiaxial */
      const double se = Yld91Effective(&yp, s, n, H);
      const double hs = 1e-5 * fnorm(s, 6);
      for (int j = 0; j < 6; j++) {
        double sp[6], sm[6], np[6], nm[6];
        memcpy(sp, s, sizeof sp);
        memcpy(sm, s, sizeof sm);
        sp[j] += hs;
        sm[j] -= hs;
        nf[j] = (Yld91Effective(&yp, sp, np, NULL) - Yld91Effective(&yp, sm, nm, NULL)) / (2 * hs);
        for (int i = 0; i < 6; i++) Hf[6 * i + j] = (np[i] - nm[i]) / (2 * hs);
      }
      eg = fmax(eg, rel(n, nf, 6));
      eH = fmax(eH, rel(H, Hf, 36));
      /* homogeneous of degree one: s . n = sigma_e, H s = 0 */
      double sn = 0, Hs[6];
      for (int i = 0; i < 6; i++) sn += s[i] * n[i];
      for (int i = 0; i < 6; i++) {
        Hs[i] = 0;
        for (int j = 0; j < 6; j++) Hs[i] += H[6 * i + j] * s[j];
      }
      ehom = fmax(ehom, fmax(fabs(sn - se) / se, fnorm(Hs, 6) / (fnorm(H, 36) * fnorm(s, 6))));
    }
    TU_CHECK(!st && eg < 1e-8 && eH < 1e-6 && ehom < 1e-12, "exponent %d, oblique axes: gradient %.1e and Hessian %.1e against central differences (relative; distinct, repeated, uniaxial, equibiaxial states), s.n = sigma_e and H s = 0 to %.1e",
             ms[k], eg, eH, ehom);
  }
}

/* ---------- (4) tangent against central differences ---------- */
static double tangent_fd_error(const Yld91Params *yp, const double F[9], const double hn[J2_NHIST], int *plastic)
{
  double tau[9], dtau[81], fd[81], h[J2_NHIST], tp[9], tm[9];
  int    pl;
  if (Yld91Update(yp, F, hn, tau, dtau, h, plastic)) return 1.0;
  const double step = 1e-6 * fnorm(F, 9) / sqrt(3.0);
  for (int c = 0; c < 9; c++) {
    double Fp[9], Fm[9];
    memcpy(Fp, F, sizeof Fp);
    memcpy(Fm, F, sizeof Fm);
    Fp[c] += step;
    Fm[c] -= step;
    Yld91Update(yp, Fp, hn, tp, NULL, h, &pl);
    Yld91Update(yp, Fm, hn, tm, NULL, h, &pl);
    for (int r = 0; r < 9; r++) fd[9 * r + c] = (tp[r] - tm[r]) / (2.0 * step);
  }
  return rel(dtau, fd, 81);
}

static void test_tangent(void)
{
  unsigned long long seed = 7;
  const double       rd[3] = {1, 1, 0.3}, nd[3] = {-1, 1, 0};
  int                s0, s1, s2;
  const Yld91Params  yps[3] = {yld(swift(), 8, 0.71, 0.58, 0.70, X1, Z1, &s0), yld(linear(150.0, 900.0), 6, 1.6, 1.2, 2.0, rd, nd, &s1), yld(linear(150.0, 0.0), 8, 0.7, 2.5, 1.3, rd, nd, &s2)};
  const char        *names[3] = {"exponent 8, aluminium, Swift, rd x", "exponent 6, linear, rotated axes", "exponent 8, perfect plasticity, r 0.7/2.5/1.3, rotated axes"};
  for (int b = 0; b < 3; b++) {
    double emax[2] = {0, 0};
    int    cnt[2]  = {0, 0};
    for (int t = 0; t < 30 && !(s0 || s1 || s2); t++) {
      double F0[9], F1[9], D[9], hn[J2_NHIST], h0[J2_NHIST], tau[9];
      int    pl;
      J2HistoryInit(hn);
      random_F(&seed, 0.12, F0);
      if (Yld91Update(&yps[b], F0, hn, tau, NULL, h0, &pl)) continue;
      const double amp = t % 2 ? 3e-4 : 0.06;
      for (int i = 0; i < 9; i++) D[i] = amp * urand(&seed) + (i % 4 == 0 ? 1.0 : 0.0);
      if (t % 2) elastic_F(&seed, h0, D, F1);
      else t3_mul(F0, D, F1);
      const double e = tangent_fd_error(&yps[b], F1, h0, &pl);
      emax[pl] = fmax(emax[pl], e);
      cnt[pl]++;
    }
    TU_CHECK(cnt[0] >= 10 && cnt[1] >= 10 && emax[0] < 1e-7 && emax[1] < 1e-6, "tangent vs central differences (%s): elastic %.1e over %d, plastic %.1e over %d (relative)", names[b], emax[0], cnt[0],
             emax[1], cnt[1]);
  }
}

/* ---------- (5) large steps; a converged state evaluated again ---------- */
static void test_robust(void)
{
  unsigned long long seed = 19;
  const double       rd[3] = {1, 2, 0.5}, nd[3] = {-2, 1, 0};
  int                s0, s1, s2;
  const Yld91Params  yps[3] = {yld(swift(), 8, 0.3, 3.0, 0.5, rd, nd, &s0), yld(linear(150.0, 0.0), 12, 2.8, 0.4, 1.9, X1, Z1, &s1), yld(swift(), 8, 0.71, 0.58, 0.70, X1, Z1, &s2)};
  int                nfail = 0, npl = 0, nrefail = 0;
  double             et = 0, eh = 0;
  for (int b = 0; b < 3; b++)
    for (int t = 0; t < 100; t++) {
      double F0[9], F[9], hn[J2_NHIST], h0[J2_NHIST], h[J2_NHIST], h2[J2_NHIST], tau[9], t2[9];
      int    pl, p2;
      J2HistoryInit(hn);
      random_F(&seed, 0.3, F0);
      if (Yld91Update(&yps[b], F0, hn, tau, NULL, h0, &pl)) {
        nfail++;
        continue;
      }
      random_F(&seed, 0.5, F);
      if (Yld91Update(&yps[b], F, h0, tau, NULL, h, &pl)) {
        nfail++;
        continue;
      }
      if (!pl) continue;
      npl++;
      if (Yld91Update(&yps[b], F, h, t2, NULL, h2, &p2)) {
        nrefail++;
        continue;
      }
      et = fmax(et, rel(t2, tau, 9));
      eh = fmax(eh, fabs(h2[J2_HIST_EP] - h[J2_HIST_EP]) / h[J2_HIST_EP]);
    }
  TU_CHECK(!(s0 || s1 || s2) && nfail == 0 && npl >= 200 && nrefail == 0 && et < 1e-9 && eh < 1e-9,
           "large steps (|F - R| up to 0.5; exponents 8, 12, 8; oblique axes, perfect plasticity): %d failures, %d plastic; evaluated again with no increment: %d failures, stress %.1e, plastic strain %.1e",
           nfail, npl, nrefail, et, eh);
}

/* ---------- (6) objectivity ---------- */
static void test_objectivity(void)
{
  unsigned long long seed = 3;
  int                st;
  const Yld91Params  yp = yld(swift(), 8, 0.71, 0.58, 0.70, X1, Z1, &st);
  double             e = 0, ehh = 0, ed = 0;
  int                npl = 0;
  for (int t = 0; t < 20 && !st; t++) {
    double F0[9], F[9], hn[J2_NHIST], h0[J2_NHIST], tau[9], dtau[81], h[J2_NHIST], tau0[9], Q[9], QF[9], t2[9], d2[81], h2[J2_NHIST], tex[9], dex[81];
    int    pl;
    J2HistoryInit(hn);
    random_F(&seed, 0.1, F0);
    Yld91Update(&yp, F0, hn, tau0, NULL, h0, &pl);
    random_F(&seed, 0.15, F);
    Yld91Update(&yp, F, h0, tau, dtau, h, &pl);
    npl += pl;
    random_rotation(&seed, Q);
    t3_mul(Q, F, QF);
    Yld91Update(&yp, QF, h0, t2, d2, h2, &pl);
    rot2(Q, tau, tex);
    for (int i = 0; i < 81; i++) {
      const int a = i / 27, b = (i / 9) % 3, c = (i / 3) % 3, d = i % 3;
      double    s = 0;
      for (int pa = 0; pa < 3; pa++)
        for (int pb = 0; pb < 3; pb++)
          for (int pc = 0; pc < 3; pc++) s += Q[3 * a + pa] * Q[3 * b + pb] * Q[3 * c + pc] * dtau[9 * (3 * pa + pb) + 3 * pc + d];
      dex[9 * (3 * a + b) + 3 * c + d] = s;
    }
    e   = fmax(e, rel(t2, tex, 9));
    ehh = fmax(ehh, rel(h2, h, J2_NHIST));
    ed  = fmax(ed, rel(d2, dex, 81));
  }
  TU_CHECK(!st && npl >= 15 && e < 1e-11 && ehh < 1e-11 && ed < 1e-10, "objectivity, F -> Q F: tau -> Q tau Q^T %.1e, history unchanged %.1e, dtau rotated %.1e (%d plastic of 20)", e, ehh, ed, npl);
}

/* ---------- the Material object ---------- */
static PetscErrorCode test_object(void)
{
  Material              mat;
  PetscErrorCode        ierr;
  const MaterialKernel *mk;

  PetscFunctionBeginUser;
  PetscCall(MaterialFromOptions("-material_type yld91", &mat, &ierr));
  TU_CHECK(!ierr, "-material_type yld91 (status %d) [%s]", (int)ierr, ErrMsg);
  if (ierr) PetscFunctionReturn(0);
  PetscCall(MaterialGetKernel(mat, &mk));
  {
    const Yld91Params *yp = (const Yld91Params *)mk->ctx;
    TU_CHECK(mk->nhist == YLD91_NHIST && yp->m == 8 && yp->c[0] == 1 && yp->c[2] == 1 && yp->c[5] == 1 && yp->A[0] == 1 && yp->A[8] == 1, "defaults: exponent 8, r-values 1 (c = 1: Hosford), rolling direction x, normal z, nhist %d",
             mk->nhist);
  }
  PetscCall(MaterialDestroy(&mat));

  PetscCall(MaterialFromOptions("-material_type yld91 -material_yld91_exponent 6 -material_yld91_r0 1.6 -material_yld91_r45 1.2 -material_yld91_r90 2.0 -material_yld91_rd 0,2,0 -material_yld91_normal 1,0,0 "
                                "-material_hardening linear -material_yield 250 -material_hardening_modulus 1000",
                                &mat, &ierr));
  if (!ierr) {
    PetscCall(MaterialGetKernel(mat, &mk));
    const Yld91Params *yp    = (const Yld91Params *)mk->ctx;
    const double       yd[3] = {0, 1, 0}, xd[3] = {1, 0, 0};
    int                st;
    const Yld91Params  ex   = yld(linear(250.0, 1000.0), 6, 1.6, 1.2, 2.0, yd, xd, &st);
    double             F[9] = {1.06, 0.04, -0.03, 0.02, 0.97, 0.05, -0.04, 0.01, 0.99}, hn[J2_NHIST], h1[J2_NHIST], h2[J2_NHIST], t1[9], t2[9], d1[81], d2[81];
    int                p1, p2, r1, r2;
    mk->history_init(mk->ctx, hn);
    r1 = Yld91Update(&ex, F, hn, t1, d1, h1, &p1);
    r2 = mk->update(mk->ctx, F, hn, t2, d2, h2, &p2);
    TU_CHECK(yp->m == 6 && yp->base.law == HARDENING_LINEAR && yp->base.sy0 == 250 && yp->r90 == 2.0 && yp->A[3] == 1 && yp->A[7] == 1 && yp->A[2] == 1,
             "-material_yld91_exponent, _r0, _r45, _r90, _rd, _normal and J2's hardening options read (frame rd y, td z, normal x)");
    ierr = MaterialView(mat, PETSC_VIEWER_STDOUT_SELF);
    TU_CHECK(!ierr, "MaterialView of yld91 (status %d)", (int)ierr);
    TU_CHECK(!st && r1 == r2 && p1 == p2 && p1 && !memcmp(t1, t2, sizeof t1) && !memcmp(d1, d2, sizeof d1) && !memcmp(h1, h2, sizeof h1) && mk->plastic_strain(mk->ctx, h2) == h2[YLD91_HIST_EP],
             "MaterialKernel.update of yld91 = Yld91Update bit for bit, plastic_strain = h[6] = %.4f", h2[YLD91_HIST_EP]);
    PetscCall(MaterialDestroy(&mat));
  } else TU_CHECK(0, "r-value options: error %d [%s]", (int)ierr, ErrMsg);

  PetscCall(MaterialFromOptions("-material_type yld91 -material_yld91_c 1.1,0.9,1.2,1,1,1.05", &mat, &ierr));
  if (!ierr) {
    PetscCall(MaterialGetKernel(mat, &mk));
    const Yld91Params *yp = (const Yld91Params *)mk->ctx;
    TU_CHECK(!yp->from_r && yp->c[0] == 1.1 && yp->c[1] == 0.9 && yp->c[2] == 1.2 && yp->c[5] == 1.05 && fabs(yp->L[0] - (0.9 + 1.2) / 3) < 1e-15, "-material_yld91_c read as given");
    PetscCall(MaterialDestroy(&mat));
  } else TU_CHECK(0, "coefficient options: error %d [%s]", (int)ierr, ErrMsg);

  {
    const char *bad[][2] = {
      {"-material_type yld91 -material_yld91_exponent 3",                      "-material_yld91_exponent 3 must be an even integer"},
      {"-material_type yld91 -material_yld91_exponent 0",                      "-material_yld91_exponent 0 must be an even integer"},
      {"-material_type yld91 -material_yld91_r0 0",                            "-material_yld91_r0 0. must be positive"           },
      {"-material_type yld91 -material_yld91_r45 -1",                          "-material_yld91_r45 -1. must be positive"         },
      {"-material_type yld91 -material_yld91_c 1,1,1,1,1",                     "-material_yld91_c needs 6 coefficients"           },
      {"-material_type yld91 -material_yld91_c 1,1,1,1,0,1",                   "c5 = 0. must be positive"                         },
      {"-material_type yld91 -material_yld91_c 0,0,1,1,1,1",                   "degenerate yield function"                        },
      {"-material_type yld91 -material_yld91_r0 2 -material_yld91_c 1,1,1,1,1,1", "exclude each other"                            },
      {"-material_type yld91 -material_yld91_rd 1,0,0 -material_yld91_normal 1,0,1", "must be non-zero and orthogonal"             },
      {"-material_type yld91 -material_yld91_normal 1,0",                      "-material_yld91_normal needs 3 components"        },
      {"-material_type yld91 -material_yld91_r0 100 -material_yld91_r45 100 -material_yld91_r90 0.01", "to these r-values did not converge"},
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
  int               st;
  const Yld91Params yp = yld(swift(), 8, 0.71, 0.58, 0.70, X1, Z1, &st);
  const HillParams  hp = hill(swift(), 0.71, 0.58, 0.70, X1, Z1);
  double            hn[J2_NHIST], hc[J2_NHIST], h[J2_NHIST], tau[9], dtau[81], acc = 0.0;
  int               pl = 0;
  J2HistoryInit(hn);
  const double F1[9] = {1.06, 0.04, -0.03, 0.02, 0.97, 0.05, -0.04, 0.01, 0.99};
  double       F2[9] = {1.10, 0.09, -0.02, 0.05, 0.94, 0.08, -0.06, 0.04, 1.01};
  Yld91Update(&yp, F1, hn, tau, NULL, hc, &pl);
  const int       N = 20000;
  struct timespec t0, t1;
  for (int model = 0; model < 2; model++)
    for (int pass = 0; pass < 2; pass++) {
      timespec_get(&t0, TIME_UTC);
      for (int i = 0; i < N; i++) {
        F2[0] = 1.10 + 1e-9 * (i & 7);
        if (model) Hill48Update(&hp, F2, hc, tau, pass ? NULL : dtau, h, &pl);
        else Yld91Update(&yp, F2, hc, tau, pass ? NULL : dtau, h, &pl);
        acc += tau[0] + (pass ? 0.0 : dtau[40]);
      }
      timespec_get(&t1, TIME_UTC);
      const double ns = ((t1.tv_sec - t0.tv_sec) * 1e9 + (t1.tv_nsec - t0.tv_nsec)) / N;
      printf("# timing: %s plastic (Swift, r 0.71/0.58/0.70%s) %s tangent: %.0f ns/call (plastic=%d, checksum %.3e)\n", model ? "Hill48Update" : "Yld91Update", model ? "" : ", exponent 8",
             pass ? "without" : "with", ns, pl, acc);
    }
}

int main(int argc, char **argv)
{
  PetscCall(PetscInitialize(&argc, &argv, NULL, NULL));
  test_hill();
  test_fit();
  test_derivatives();
  test_tangent();
  test_robust();
  test_objectivity();
  PetscCall(test_object());
  timing();
  PetscCall(PetscFinalize());
  TU_RETURN();
}
