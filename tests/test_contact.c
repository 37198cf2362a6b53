/* Unit tests of the contact kernels: return map (stick, slip, separation), its consistent
   tangent against finite differences, the nodal tangent on flat and curved tools against finite
   differences, eq 27 on a flat tool, and the frame recurrence along a great circle. */
#define _USE_MATH_DEFINES
#include <stdlib.h>
#include <string.h>
#include "testutil.h"
#include "contact_law.h"

static double urand(void) { return 2.0 * rand() / (double)RAND_MAX - 1.0; }
static double dot(const double a[3], const double b[3]) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }
static double norm3(const double a[3]) { return sqrt(dot(a, a)); }

/* a rigid sphere (centre c, radius Rs), contact from outside: n = (y - c)/|y - c|, g = |y - c| - Rs */
static void sphere_geom(const double c[3], double Rs, const double y[3], double *g, double n[3], double dn[9])
{
  double r[3] = {y[0] - c[0], y[1] - c[1], y[2] - c[2]}, rho = norm3(r);
  for (int i = 0; i < 3; i++) n[i] = r[i] / rho;
  *g = rho - Rs;
  if (dn)
    for (int i = 0; i < 3; i++)
      for (int j = 0; j < 3; j++) dn[3 * i + j] = ((i == j) - n[i] * n[j]) / rho;
}

/* residual of a node at y on the sphere, slip measured from yn (tool fixed) */
static int node_on_sphere(const ContactLaw *law, const double c[3], double Rs, const double y[3], const double yn[3], const double seed[3], const double tTn[2], double R[3], double *K, double t1[3], double tT[2])
{
  double g, n[3], dn[9], ds[3], tN;
  sphere_geom(c, Rs, y, &g, n, dn);
  for (int i = 0; i < 3; i++) ds[i] = y[i] - yn[i];
  return ContactNodeEval(law, g, n, dn, seed, tTn, ds, R, K, t1, &tN, tT);
}

int main(void)
{
  ContactLaw law = {1e5, 5e3, 0.15, 0, 0};
  srand(4321);

  /* return map: stick, slip, the cone, separation */
  {
    double tTn[2] = {10, -5}, dg[2] = {1e-3, 2e-3}, tT[2], Y[6];
    const double tN = 1e4; /* cone radius 1500 */
    int st = ContactReturnMap(&law, tTn, dg, tN, tT, Y);
    TU_CHECK(st == CONTACT_STICK && fabs(tT[0] - 15) < 1e-12 && fabs(tT[1] - 5) < 1e-12, "return map: stick below the cone, tT = (%g, %g) = tTn + K_T dg", tT[0], tT[1]);
    dg[0] = 0.4;
    dg[1] = -0.3;
    st    = ContactReturnMap(&law, tTn, dg, tN, tT, Y);
    const double te[2] = {tTn[0] + law.KT * dg[0], tTn[1] + law.KT * dg[1]};
    const double r = sqrt(tT[0] * tT[0] + tT[1] * tT[1]), cosang = (tT[0] * te[0] + tT[1] * te[1]) / (r * sqrt(te[0] * te[0] + te[1] * te[1]));
    TU_CHECK(st == CONTACT_SLIP && fabs(r - law.mu * tN) < 1e-9 * tN && fabs(cosang - 1) < 1e-14, "return map: slip returns to the cone |tT| = mu tN (error %.1e) along the predictor (cos %.15f)", fabs(r - law.mu * tN), cosang);
    double R[3], K[9], t1[3], tNo, n[3] = {0, 0, 1}, s[3] = {1, 0, 0}, ds[3] = {0.1, 0.2, 0};
    st = ContactNodeEval(&law, 1e-3, n, NULL, s, tTn, ds, R, K, t1, &tNo, tT);
    TU_CHECK(st == CONTACT_OPEN && norm3(R) == 0 && tNo == 0 && tT[0] == 0 && tT[1] == 0, "separation (g > 0): no force, tangential pressure reset");
  }

  /* consistent tangent Y (eq 23) against finite differences of the return map */
  {
    double worst = 0;
    for (int k = 0; k < 12; k++) {
      const double ang = 2 * 3.14159265358979323846 * k / 12.0 + 0.1;
      double       tTn[2] = {200 * urand(), 200 * urand()}, dg[2] = {0.05 * cos(ang), 0.05 * sin(ang)}, p = 0.01, tT[2], Y[6];
      int          st = ContactReturnMap(&law, tTn, dg, law.KN * p, tT, Y);
      if (st != CONTACT_SLIP) continue;
      for (int col = 0; col < 3; col++) {
        const double h = 1e-7 * (col < 2 ? 0.05 : p);
        double       dgp[2] = {dg[0], dg[1]}, dgm[2] = {dg[0], dg[1]}, pp = p, pm = p, tp[2], tm[2];
        if (col < 2) {
          dgp[col] += h;
          dgm[col] -= h;
        } else {
          pp += h;
          pm -= h;
        }
        ContactReturnMap(&law, tTn, dgp, law.KN * pp, tp, NULL);
        ContactReturnMap(&law, tTn, dgm, law.KN * pm, tm, NULL);
        for (int a = 0; a < 2; a++) {
          const double fd = (tp[a] - tm[a]) / (2 * h), sc = fmax(fabs(Y[3 * a + col]), law.KT * 1e-3);
          worst           = fmax(worst, fabs(fd - Y[3 * a + col]) / sc);
        }
      }
    }
    TU_CHECK(worst < 1e-6, "slip tangent Y (eq 23) vs finite differences, 12 slip directions: largest relative error %.2e", worst);
  }

  /* flat tool: the nodal tangent is eta^T K eta (stick) and eta^T Y eta (slip) (eqs 26-27) */
  {
    const double n[3] = {0, 0.6, 0.8}, s[3] = {1, 0, 0}, tTn[2] = {30, -20};
    double       R[3], K[9], t1[3], t2[3], tN, tT[2], Y[6], Yfull[9], eta[9], ds[3];
    const int    cases[2] = {CONTACT_STICK, CONTACT_SLIP};
    for (int c = 0; c < 2; c++) {
      const double amp = c == 0 ? 1e-4 : 0.5;
      ds[0]            = amp;
      ds[1]            = -0.5 * amp;
      ds[2]            = 0.3 * amp;
      const int st     = ContactNodeEval(&law, -0.02, n, NULL, s, tTn, ds, R, K, t1, &tN, tT);
      ContactFrame(n, s, t1, t2);
      for (int j = 0; j < 3; j++) {
        eta[j]     = t1[j];
        eta[3 + j] = t2[j];
        eta[6 + j] = n[j];
      }
      const double dg[2] = {dot(t1, ds), dot(t2, ds)};
      double       tt[2];
      ContactReturnMap(&law, tTn, dg, tN, tt, Y);
      /* local components (T1, T2, N) of dR with respect to the node's motion: rows t_a, -N (the
         residual is -f), columns in terms of (dg1, dg2, -penetration) */
      for (int a = 0; a < 2; a++)
        for (int b = 0; b < 3; b++) Yfull[3 * a + b] = (b < 2 ? Y[3 * a + b] : -Y[3 * a + 2]);
      Yfull[6] = Yfull[7] = 0;
      Yfull[8]            = law.KN;
      /* eta^T Yfull eta */
      double maxerr = 0, scale = 0;
      for (int i = 0; i < 3; i++)
        for (int j = 0; j < 3; j++) {
          double v = 0;
          for (int a = 0; a < 3; a++)
            for (int b = 0; b < 3; b++) v += eta[3 * a + i] * Yfull[3 * a + b] * eta[3 * b + j];
          maxerr        = fmax(maxerr, fabs(v - K[3 * i + j]));
          scale         = fmax(scale, fabs(K[3 * i + j]));
        }
      TU_CHECK(st == cases[c] && maxerr < 1e-12 * scale, "flat tool, %s: nodal tangent = eta^T %s eta (eq 27), error %.1e", c == 0 ? "stick" : "slip", c == 0 ? "K" : "Y", maxerr / scale);
    }
  }

  /* nodal tangent on a sphere (curvature and frame rotation included) against finite differences */
  {
    const double c[3] = {0.1, -0.2, 0.3}, Rs = 2.0;
    const char  *label[3] = {"stick", "slip", "frictionless"};
    for (int k = 0; k < 3; k++) {
      ContactLaw   lw = law;
      double       worst = 0;
      int          status = -1;
      if (k == 2) lw.mu = 0;
      for (int trial = 0; trial < 5; trial++) {
        double dir[3] = {urand(), urand(), urand()}, y[3], yn[3], seed[3] = {urand(), urand(), urand()}, tTn[2] = {50 * urand(), 50 * urand()};
        const double nd = norm3(dir), pen = 0.01 * (1 + trial);
        for (int i = 0; i < 3; i++) {
          y[i]  = c[i] + (Rs - pen) * dir[i] / nd;
          yn[i] = y[i] + (k == 0 ? 1e-4 : 0.5) * urand();
        }
        double R[3], K[9], t1[3], tT[2];
        const int st = node_on_sphere(&lw, c, Rs, y, yn, seed, tTn, R, K, t1, tT);
        if (trial == 0 || st != status) status = (trial == 0 ? st : -1);
        for (int j = 0; j < 3; j++) {
          const double h = 1e-7;
          double       yp[3] = {y[0], y[1], y[2]}, ym[3] = {y[0], y[1], y[2]}, Rp[3], Rm[3];
          yp[j] += h;
          ym[j] -= h;
          node_on_sphere(&lw, c, Rs, yp, yn, seed, tTn, Rp, NULL, t1, tT);
          node_on_sphere(&lw, c, Rs, ym, yn, seed, tTn, Rm, NULL, t1, tT);
          for (int i = 0; i < 3; i++) worst = fmax(worst, fabs((Rp[i] - Rm[i]) / (2 * h) - K[3 * i + j]) / lw.KN);
        }
      }
      TU_CHECK(worst < 1e-6 && status == (k == 0 ? CONTACT_STICK : CONTACT_SLIP), "sphere, %s: nodal tangent vs finite differences, largest error %.2e (relative to K_N)", label[k], worst);
    }
  }

  /* augmented Lagrangian kernel: lN = 0 is the penalty kernel bit for bit; with lN > 0,
     t_N = lN + K_N p, a node standing off by less than lN/K_N stays active, the slip force stays on
     the cone, and the tangent at fixed multipliers is exact (sphere, stick and slip) */
  {
    const double c[3] = {0.1, -0.2, 0.3}, Rs = 2.0;
    int          same = 1;
    for (int trial = 0; trial < 20; trial++) {
      double n[3] = {urand(), urand(), urand()}, s[3] = {urand(), urand(), urand()}, ds[3] = {urand(), urand(), 0.1 * urand()}, tTn[2] = {100 * urand(), 100 * urand()};
      double R1[3], K1[9], t11[3], tN1, tT1[2], R2[3], K2[9], t12[3], tN2, tT2[2];
      const double nn = norm3(n), g = 0.01 * urand();
      for (int i = 0; i < 3; i++) n[i] /= nn;
      const int s1 = ContactNodeEval(&law, g, n, NULL, s, tTn, ds, R1, K1, t11, &tN1, tT1);
      const int s2 = ContactNodeEvalAug(&law, 0.0, g, n, NULL, s, tTn, ds, R2, K2, t12, &tN2, tT2);
      same = same && s1 == s2 && !memcmp(R1, R2, sizeof(R1)) && !memcmp(K1, K2, sizeof(K1)) && tN1 == tN2 && !memcmp(tT1, tT2, sizeof(tT1));
    }
    TU_CHECK(same, "augmented kernel with lN = 0: the penalty kernel bit for bit (20 random nodes, open and closed)");
    {
      const double n[3] = {0, 0, 1}, s[3] = {1, 0, 0}, ds[3] = {0, 0, 0}, tTn[2] = {0, 0}, lN = 500;
      double       R[3], t1[3], tN, tT[2];
      const int    a = ContactNodeEvalAug(&law, lN, 0.5 * lN / law.KN, n, NULL, s, tTn, ds, R, NULL, t1, &tN, tT);
      const int    b = ContactNodeEvalAug(&law, lN, 1.5 * lN / law.KN, n, NULL, s, tTn, ds, R, NULL, t1, &tN, tT);
      double       tNa;
      ContactNodeEvalAug(&law, lN, -1e-3, n, NULL, s, tTn, ds, R, NULL, t1, &tNa, tT);
      TU_CHECK(a != CONTACT_OPEN && b == CONTACT_OPEN && fabs(tNa - (lN + law.KN * 1e-3)) < 1e-12 * tNa, "augmented kernel: t_N = lN + K_N p (%.6g); held by the multiplier up to a gap lN/K_N, open beyond", tNa);
    }
    const char *label[2] = {"stick", "slip"};
    for (int k = 0; k < 2; k++) {
      double worst = 0, cone = 0;
      int    status = -1;
      for (int trial = 0; trial < 5; trial++) {
        double dir[3] = {urand(), urand(), urand()}, y[3], yn[3], seed[3] = {urand(), urand(), urand()}, tTn[2] = {50 * urand(), 50 * urand()};
        const double nd = norm3(dir), gap = (trial % 2 ? 0.002 : -0.01) * (1 + trial), lN = 1000 * (1 + trial);
        for (int i = 0; i < 3; i++) {
          y[i]  = c[i] + (Rs + gap) * dir[i] / nd;
          yn[i] = y[i] + (k == 0 ? 1e-4 : 0.5) * urand();
        }
        double R[3], K[9], t1[3], tT[2], g, nv[3], dn[9], dsv[3], tN;
        sphere_geom(c, Rs, y, &g, nv, dn);
        for (int i = 0; i < 3; i++) dsv[i] = y[i] - yn[i];
        const int st = ContactNodeEvalAug(&law, lN, g, nv, dn, seed, tTn, dsv, R, K, t1, &tN, tT);
        if (trial == 0 || st != status) status = (trial == 0 ? st : -1);
        if (st == CONTACT_SLIP) cone = fmax(cone, fabs(sqrt(tT[0] * tT[0] + tT[1] * tT[1]) - law.mu * tN) / (law.mu * tN));
        for (int j = 0; j < 3; j++) {
          const double h = 1e-7;
          double       yp[3] = {y[0], y[1], y[2]}, ym[3] = {y[0], y[1], y[2]}, Rp[3], Rm[3];
          yp[j] += h;
          ym[j] -= h;
          for (int sgn = 0; sgn < 2; sgn++) {
            const double *yy = sgn ? ym : yp;
            double        gg, nn2[3], dd[3], tt1[3], ttT[2], ttN;
            sphere_geom(c, Rs, yy, &gg, nn2, NULL);
            for (int i = 0; i < 3; i++) dd[i] = yy[i] - yn[i];
            ContactNodeEvalAug(&law, lN, gg, nn2, NULL, seed, tTn, dd, sgn ? Rm : Rp, NULL, tt1, &ttN, ttT);
          }
          for (int i = 0; i < 3; i++) worst = fmax(worst, fabs((Rp[i] - Rm[i]) / (2 * h) - K[3 * i + j]) / law.KN);
        }
      }
      TU_CHECK(worst < 1e-6 && status == (k == 0 ? CONTACT_STICK : CONTACT_SLIP) && cone < 1e-12, "augmented kernel on a sphere, %s (lN > 0, penetrated and standing off): tangent vs finite differences %.2e (relative to K_N), slip on the cone to %.1e", label[k], worst, cone);
    }
    /* gap smoothing (law.delta > 0): the tangent against central differences in the band and
       beyond it, stick and slip, with and without a multiplier; t_N continuous and C1 at the band's
       ends; the same as the plain bracket beyond it */
    {
      ContactLaw   ls = law;
      double       worst = 0, jump = 0;
      const double n[3] = {0, 0.6, 0.8}, s[3] = {1, 0, 0}, tTn[2] = {30, -20};
      ls.delta = 1e-3;
      for (int c2 = 0; c2 < 12; c2++) {
        const double g = -2e-3 + c2 * 3.5e-4, lN = (c2 % 3 == 0) ? 20.0 : 0.0, dsx = (c2 % 2) ? 1e-5 : 1e-2;
        const double ds[3] = {dsx, -0.5 * dsx, 0.3 * dsx};
        double       R[3], K[9], t1[3], tT[2], tN;
        if (ContactNodeEvalAug(&ls, lN, g, n, NULL, s, tTn, ds, R, K, t1, &tN, tT) == CONTACT_OPEN) continue;
        for (int j = 0; j < 3; j++) {
          const double h = 1e-8;
          double       Rp[3], Rm[3], tt1[3], ttT[2], ttN;
          /* a move of the node by dy along j: gap g + n.dy, slip increment ds + dy */
          const double dgp = h * n[j], dsp[3] = {ds[0] + (j == 0) * h, ds[1] + (j == 1) * h, ds[2] + (j == 2) * h}, dsm[3] = {ds[0] - (j == 0) * h, ds[1] - (j == 1) * h, ds[2] - (j == 2) * h};
          ContactNodeEvalAug(&ls, lN, g + dgp, n, NULL, s, tTn, dsp, Rp, NULL, tt1, &ttN, ttT);
          ContactNodeEvalAug(&ls, lN, g - dgp, n, NULL, s, tTn, dsm, Rm, NULL, tt1, &ttN, ttT);
          for (int i = 0; i < 3; i++) worst = fmax(worst, fabs((Rp[i] - Rm[i]) / (2 * h) - K[3 * i + j]) / ls.KN);
        }
      }
      for (int side = -1; side <= 1; side += 2) { /* the band's ends x = -w, x = w (lN = 0: g = delta, g = -delta) */
        const double ge = -side * ls.delta, ds[3] = {0, 0, 0};
        double       R[3], t1[3], tT[2], tNa, tNb;
        ContactNodeEvalAug(&ls, 0.0, ge * (1 - 1e-9), n, NULL, s, tTn, ds, R, NULL, t1, &tNa, tT);
        ContactNodeEvalAug(&ls, 0.0, ge * (1 + 1e-9), n, NULL, s, tTn, ds, R, NULL, t1, &tNb, tT);
        jump = fmax(jump, fabs(tNa - tNb) / (ls.KN * ls.delta));
      }
      {
        double R1[3], R2[3], t1[3], tT[2], tN1, tN2;
        const double ds[3] = {1e-4, 0, 0};
        ContactNodeEvalAug(&law, 0.0, -5e-3, n, NULL, s, tTn, ds, R1, NULL, t1, &tN1, tT);
        ContactNodeEvalAug(&ls, 0.0, -5e-3, n, NULL, s, tTn, ds, R2, NULL, t1, &tN2, tT);
        TU_CHECK(worst < 1e-6 && jump < 1e-6 && tN1 == tN2 && R1[0] == R2[0] && R1[1] == R2[1] && R1[2] == R2[2], "gap smoothing: tangent vs finite differences %.2e (relative to K_N) in and beyond the band, stick and slip, with and without a multiplier; t_N continuous at the band's ends (%.1e of K_N delta); the plain law beyond the band", worst, jump);
      }
    }
    /* the regularised law (law.reg > 0, -contact_regularization): with x = lN + K_N p, b = K_N reg,
       a = CONTACT_REG_GAP b: t_N = (x + a)^2 / (2 (a + b)) in the band -a < x < b, x - (b - a)/2
       beyond, 0 below -a (open). Its values in closed form at the band's ends and at touching,
       the slope K_N a / (a + b) = K_N / 11 at touching, the tangent against central differences in
       and beyond the band (stick and slip, with and without a multiplier), open beyond a gap of
       CONTACT_REG_GAP reg */
    {
      ContactLaw   lr = law;
      double       worst = 0, vals = 0, slope;
      const double n[3] = {0, 0.6, 0.8}, s[3] = {1, 0, 0}, tTn[2] = {30, -20}, ds0[3] = {0, 0, 0};
      lr.reg = 1e-3;
      const double b = lr.KN * lr.reg, a = CONTACT_REG_GAP * b;
      for (int c2 = 0; c2 < 14; c2++) {
        const double g = 1.5e-4 - c2 * 1.7e-4, lN = (c2 % 3 == 0) ? 20.0 : 0.0, dsx = (c2 % 2) ? 1e-5 : 1e-2;
        const double ds[3] = {dsx, -0.5 * dsx, 0.3 * dsx};
        double       R[3], K[9], t1[3], tT[2], tN;
        if (ContactNodeEvalAug(&lr, lN, g, n, NULL, s, tTn, ds, R, K, t1, &tN, tT) == CONTACT_OPEN) continue;
        for (int j = 0; j < 3; j++) {
          const double h = 1e-9;
          double       Rp[3], Rm[3], tt1[3], ttT[2], ttN;
          const double dgp = h * n[j], dsp[3] = {ds[0] + (j == 0) * h, ds[1] + (j == 1) * h, ds[2] + (j == 2) * h}, dsm[3] = {ds[0] - (j == 0) * h, ds[1] - (j == 1) * h, ds[2] - (j == 2) * h};
          ContactNodeEvalAug(&lr, lN, g + dgp, n, NULL, s, tTn, dsp, Rp, NULL, tt1, &ttN, ttT);
          ContactNodeEvalAug(&lr, lN, g - dgp, n, NULL, s, tTn, dsm, Rm, NULL, tt1, &ttN, ttT);
          for (int i = 0; i < 3; i++) worst = fmax(worst, fabs((Rp[i] - Rm[i]) / (2 * h) - K[3 * i + j]) / lr.KN);
        }
      }
      {
        /* closed forms (lN = 0, x = K_N p): touching, the band's inner end p = reg, beyond it,
           the open side's end and past it */
        double       R[3], t1[3], tT[2], tN[5], tp, tm;
        const double gs[5] = {0, -lr.reg, -3 * lr.reg, CONTACT_REG_GAP * lr.reg * (1 - 1e-9), CONTACT_REG_GAP * lr.reg * (1 + 1e-9)};
        const double want[5] = {a * a / (2 * (a + b)), b - 0.5 * (b - a), 3 * b - 0.5 * (b - a), 0, 0};
        int          st[5];
        for (int k = 0; k < 5; k++) {
          st[k] = ContactNodeEvalAug(&lr, 0.0, gs[k], n, NULL, s, tTn, ds0, R, NULL, t1, &tN[k], tT);
          if (st[k] == CONTACT_OPEN) tN[k] = 0;
          vals = fmax(vals, fabs(tN[k] - want[k]) / b);
        }
        ContactNodeEvalAug(&lr, 0.0, -1e-9, n, NULL, s, tTn, ds0, R, NULL, t1, &tp, tT);
        ContactNodeEvalAug(&lr, 0.0, 1e-9, n, NULL, s, tTn, ds0, R, NULL, t1, &tm, tT);
        slope = (tp - tm) / (2e-9 * lr.KN);
        TU_CHECK(worst < 1e-6 && vals < 1e-9 && st[4] == CONTACT_OPEN && st[0] != CONTACT_OPEN && fabs(slope - 1.0 / 11) < 1e-6,
                 "regularised law: tangent vs finite differences %.2e (relative to K_N) in and beyond the band, stick and slip, with and without a multiplier; t_N at touching, the band's ends and beyond against the closed form to %.1e of K_N reg; slope at touching %.6f of K_N (1/11); open beyond a gap of %g reg", worst, vals, slope, CONTACT_REG_GAP);
      }
    }
    /* Uzawa on one node pushed by a spring k_s = K_N into a rigid wall: lN <- lN + K_N p drives
       the penetration to zero and lN to the exact contact force */
    {
      const double ks = law.KN, d = 0.1, n[3] = {0, 0, 1}, s[3] = {1, 0, 0}, tTn[2] = {0, 0}, ds[3] = {0, 0, 0};
      double       lN = 0, x = 0, p = 0;
      int          it;
      for (it = 0; it < 200; it++) {
        for (int nit = 0; nit < 20; nit++) { /* Newton: ks (x - d) + t_N = 0, the node at height -x */
          double R[3], K[9], t1[3], tN, tT[2];
          ContactNodeEvalAug(&law, lN, -x, n, NULL, s, tTn, ds, R, K, t1, &tN, tT);
          const double r = ks * (x - d) + tN, kk = ks + K[8];
          x -= r / kk;
        }
        p = x;
        lN += law.KN * p;
        if (fabs(p) < 1e-12 * d) break;
      }
      TU_CHECK(fabs(p) < 1e-12 * d && fabs(lN - ks * d) < 1e-9 * ks * d, "Uzawa on a spring against a wall: penetration %.1e after %d updates, multiplier = spring force to %.1e", p, it + 1, fabs(lN - ks * d) / (ks * d));
    }
  }

  /* frame recurrence along a great circle of a sphere: t1 stays continuous and orthonormal, and
     the friction force opposes the slip */
  {
    const double c[3] = {0, 0, 0}, Rs = 1.0;
    const int    N = 400;
    double       seed[3] = {0, 1, 0}, tTn[2] = {0, 0}, yprev[3], t1prev[3] = {0, 0, 0}, worstjump = 0, worstorth = 0, worstopp = 1;
    ContactLaw   lw = {1e4, 1e3, 0.3, 0, 0};
    for (int k = 0; k <= N; k++) {
      /* node sliding in the x-z plane, slightly inside the sphere */
      const double th = 0.5 * 3.14159265358979323846 * k / N, r = Rs - 1e-3;
      const double y[3] = {r * sin(th), 0, r * cos(th)};
      if (k == 0) {
        for (int i = 0; i < 3; i++) yprev[i] = y[i];
        /* first contact: the chord seed, here along the motion */
        seed[0] = 1;
        seed[1] = 0.3;
        seed[2] = 0;
      }
      double g, n[3], R[3], t1[3], t2[3], tN, tT[2], ds[3];
      sphere_geom(c, Rs, y, &g, n, NULL);
      for (int i = 0; i < 3; i++) ds[i] = y[i] - yprev[i];
      const int st = ContactNodeEval(&lw, g, n, NULL, seed, tTn, ds, R, NULL, t1, &tN, tT);
      ContactFrame(n, seed, t1, t2);
      worstorth = fmax(worstorth, fmax(fabs(dot(t1, n)), fmax(fabs(dot(t1, t2)), fabs(norm3(t1) - 1))));
      if (k > 0) {
        const double dth = 0.5 * 3.14159265358979323846 / N, d[3] = {t1[0] - t1prev[0], t1[1] - t1prev[1], t1[2] - t1prev[2]};
        worstjump        = fmax(worstjump, norm3(d) / dth); /* <= 1: no more than the normal's rotation */
        if (st == CONTACT_SLIP) {
          const double f[3] = {-(tT[0] * t1[0] + tT[1] * t2[0]), -(tT[0] * t1[1] + tT[1] * t2[1]), -(tT[0] * t1[2] + tT[1] * t2[2])};
          const double sn   = dot(ds, n), dsT[3] = {ds[0] - sn * n[0], ds[1] - sn * n[1], ds[2] - sn * n[2]};
          worstopp          = fmin(worstopp, -dot(f, dsT) / (norm3(f) * norm3(dsT)));
        }
      }
      /* converged step: commit, and the frame seeds the next one (eq 30) */
      for (int i = 0; i < 3; i++) {
        seed[i]   = t1[i];
        t1prev[i] = t1[i];
        yprev[i]  = y[i];
      }
      tTn[0] = tT[0];
      tTn[1] = tT[1];
    }
    TU_CHECK(worstjump <= 1.0 + 1e-9, "frame recurrence on a great circle: largest |dt1|/(rotation of n) = %.6f (<= 1: continuous, no spin)", worstjump);
    TU_CHECK(worstorth < 1e-14, "frame recurrence: t1, t2, n orthonormal to %.1e", worstorth);
    TU_CHECK(worstopp > 1 - 1e-9, "friction force opposite to the tangential slip: smallest cos(-f, ds_T) = %.12f", worstopp);
  }
  /* the frame carried from n0 to n (ContactFrameCarry): closed form for n0 = z, n turned by th
     about y (x -> (cos th, 0, -sin th), y -> y); and for random n0, n and two frames of the same
     plane, a traction given by its components carries to the same vector (frame-independent),
     in the new plane, with its length; the projection (eq 30) turns it by an angle that depends
     on the frame */
  {
    const double th = 0.3, z[3] = {0, 0, 1}, nt[3] = {sin(th), 0, cos(th)}, ex[3] = {1, 0, 0}, ey[3] = {0, 1, 0};
    double       rx[3], ry[3], worst = 0, worstproj = 0;
    int          fb = ContactFrameCarry(z, nt, ex, rx) + ContactFrameCarry(z, nt, ey, ry);
    const double err = fmax(fmax(fabs(rx[0] - cos(th)), fabs(rx[1])), fmax(fabs(rx[2] + sin(th)), fmax(fabs(ry[0]), fmax(fabs(ry[1] - 1), fabs(ry[2])))));
    for (int k = 0; k < 200; k++) {
      double n0[3] = {urand(), urand(), urand()}, n[3], a[3], t1[3], t2[3], u1[3], u2[3], c1[3], c2[3], d1[3], d2[3], p1[3], p2[3], q1[3], q2[3];
      const double al = urand(), be = urand(), l0 = norm3(n0);
      for (int i = 0; i < 3; i++) {
        n0[i] /= l0;
        n[i] = n0[i] + 0.4 * urand(); /* a turn of up to about 35 degrees */
        a[i] = urand();
      }
      const double ln = norm3(n);
      for (int i = 0; i < 3; i++) n[i] /= ln;
      ContactFrame(n0, a, t1, t2); /* two frames of the plane of n0 */
      for (int i = 0; i < 3; i++) a[i] = urand();
      ContactFrame(n0, a, u1, u2);
      fb += ContactFrameCarry(n0, n, t1, c1) + ContactFrameCarry(n0, n, u1, d1);
      ContactFrame(n, c1, c1, c2); /* the frames now: t2 = n x t1 */
      ContactFrame(n, d1, d1, d2);
      ContactFrame(n, t1, p1, p2); /* the projection */
      ContactFrame(n, u1, q1, q2);
      /* the traction al t1 + be t2 = (al t1 + be t2).u1 u1 + (...).u2 u2 in the second frame */
      double v[3], ac, bc, cv[3], dv[3], pv[3], qv[3];
      for (int i = 0; i < 3; i++) v[i] = al * t1[i] + be * t2[i];
      ac = dot(v, u1);
      bc = dot(v, u2);
      for (int i = 0; i < 3; i++) {
        cv[i] = al * c1[i] + be * c2[i];
        dv[i] = ac * d1[i] + bc * d2[i];
        pv[i] = al * p1[i] + be * p2[i];
        qv[i] = ac * q1[i] + bc * q2[i];
      }
      const double e[3] = {cv[0] - dv[0], cv[1] - dv[1], cv[2] - dv[2]}, ep[3] = {pv[0] - qv[0], pv[1] - qv[1], pv[2] - qv[2]};
      worst     = fmax(worst, fmax(norm3(e), fmax(fabs(dot(cv, n)), fabs(norm3(cv) - norm3(v)))) / norm3(v));
      worstproj = fmax(worstproj, norm3(ep) / norm3(v));
    }
    const double zero[3] = {0, 0, 0};
    double       r0[3];
    TU_CHECK(err < 1e-15 && fb == 0, "frame carried from n0 to n: the rotation about n0 x n, x -> (cos th, 0, -sin th), y -> y to %.1e", err);
    TU_CHECK(worst < 1e-13 && worstproj > 1e-3, "frame carried: 200 random turns, a traction carries to the same vector in the new plane with its length whatever the frame (%.1e; by projection the frames disagree by %.2f)", worst, worstproj);
    TU_CHECK(ContactFrameCarry(zero, nt, ex, r0) == 1 && r0[0] == 1 && r0[1] == 0 && r0[2] == 0, "frame carried: without n0 the seed is left to the projection");
  }
  /* tributary areas of a face: a plane trapezoid against the closed form a_i = J0 + (J1 xi_i + J2 eta_i)/3
     (J = J0 + J1 xi + J2 eta: here 1.5 - 0.5 eta, so 5/3 at the long side, 4/3 at the short), rotated
     and moved in space; a warped face (a cylinder strip) sums to its area to the quadrature error */
  {
    const double q[4][3] = {{0, 0, 0}, {4, 0, 0}, {3, 2, 0}, {1, 2, 0}}, ex[4] = {5. / 3, 5. / 3, 4. / 3, 4. / 3};
    const double c = cos(0.7), sn = sin(0.7);
    double       x[4][3], a[4], err = 0, sum = 0;
    for (int i = 0; i < 4; i++) { /* x = Rz(0.7) Rx(0.7) q + (1, -2, 3) */
      const double y1 = q[i][1] * c - q[i][2] * sn, z1 = q[i][1] * sn + q[i][2] * c;
      x[i][0] = q[i][0] * c - y1 * sn + 1;
      x[i][1] = q[i][0] * sn + y1 * c - 2;
      x[i][2] = z1 + 3;
    }
    ContactQuadAreas(x, a);
    for (int i = 0; i < 4; i++) {
      err = fmax(err, fabs(a[i] - ex[i]));
      sum += a[i];
    }
    TU_CHECK(err < 1e-14 && fabs(sum - 6) < 1e-14, "face tributary areas: plane trapezoid in space, (%.15g, %.15g, %.15g, %.15g) against (5/3, 5/3, 4/3, 4/3)", a[0], a[1], a[2], a[3]);
    /* a strip of the cylinder r = 2 spanning 0.1 rad and 0.5 in z: the bilinear face is the chord
       plane, area 0.5 * 2 * 2 sin(0.05) */
    const double R = 2, th = 0.1;
    const double w[4][3] = {{R, 0, 0}, {R * cos(th), R * sin(th), 0}, {R * cos(th), R * sin(th), 0.5}, {R, 0, 0.5}};
    ContactQuadAreas(w, a);
    const double chord = 2 * R * sin(th / 2);
    TU_CHECK(fabs(a[0] + a[1] + a[2] + a[3] - 0.5 * chord) < 1e-14 && fabs(a[0] - a[1]) < 1e-15 && fabs(a[0] - a[3]) < 1e-15, "face tributary areas: a rectangle gives a quarter of its area %.6g to each corner", 0.5 * chord);
    /* a warped face (corners not coplanar): the sum against a 200 x 200 midpoint rule */
    const double h[4][3] = {{0, 0, 0}, {1, 0, 0.3}, {1.2, 1, -0.2}, {0, 0.9, 0.1}};
    double       fine = 0;
    for (int p = 0; p < 200; p++)
      for (int r = 0; r < 200; r++) {
        const double xi = -1 + (p + 0.5) / 100, eta = -1 + (r + 0.5) / 100;
        double       dxi[3], deta[3];
        for (int k = 0; k < 3; k++) {
          dxi[k]  = 0.25 * (-(1 - eta) * h[0][k] + (1 - eta) * h[1][k] + (1 + eta) * h[2][k] - (1 + eta) * h[3][k]);
          deta[k] = 0.25 * (-(1 - xi) * h[0][k] - (1 + xi) * h[1][k] + (1 + xi) * h[2][k] + (1 - xi) * h[3][k]);
        }
        const double nx = dxi[1] * deta[2] - dxi[2] * deta[1], ny = dxi[2] * deta[0] - dxi[0] * deta[2], nz = dxi[0] * deta[1] - dxi[1] * deta[0];
        fine += sqrt(nx * nx + ny * ny + nz * nz) * 1e-4;
      }
    ContactQuadAreas(h, a);
    TU_CHECK(fabs(a[0] + a[1] + a[2] + a[3] - fine) < 2e-3 * fine, "face tributary areas: a warped face sums to its area %.6f (2x2 Gauss %.6f)", fine, a[0] + a[1] + a[2] + a[3]);
  }

  TU_RETURN();
}
