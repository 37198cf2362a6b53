/* Rigid tools: parametric patches (plane, sphere, cylinder, torus, Coons), their evaluation with
   first and second derivatives, the closest-point projection of a point on a tool, the derivative
   of the contact normal, and the options that build the tools (doc/tools.md).

   Frames: a (axis) and e (reference direction) are unit and orthogonal, f = a x e, so (e, f, a) is
   right-handed; w(ph) = cos ph e + sin ph f is the radial direction at azimuth ph and
   w'(ph) = -sin ph e + cos ph f its derivative. */
#include "tool.h"

#include <float.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#define TOOL_PI 3.14159265358979323846

static inline double Dot(const double a[3], const double b[3]) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }
static inline double Norm(const double a[3]) { return sqrt(Dot(a, a)); }
static inline void   Cross(const double a[3], const double b[3], double c[3])
{
  c[0] = a[1] * b[2] - a[2] * b[1];
  c[1] = a[2] * b[0] - a[0] * b[2];
  c[2] = a[0] * b[1] - a[1] * b[0];
}
static inline double Clamp01(double s) { return s < 0.0 ? 0.0 : (s > 1.0 ? 1.0 : s); }
static inline double Dist2(const double a[3], const double b[3])
{
  const double d[3] = {a[0] - b[0], a[1] - b[1], a[2] - b[2]};
  return Dot(d, d);
}

/* w(ph) and w'(ph) of the patch frame */
static void Radial(const Patch *p, double ph, double w[3], double wp[3])
{
  double       f[3];
  const double c = cos(ph), s = sin(ph);
  Cross(p->a, p->e, f);
  for (int i = 0; i < 3; i++) {
    w[i]  = c * p->e[i] + s * f[i];
    wp[i] = -s * p->e[i] + c * f[i];
  }
}

/* ------------------------------------------------------------------------------------------ */
/* evaluation                                                                                   */
/* ------------------------------------------------------------------------------------------ */

/* A boundary curve prepared for evaluation (CurveFrame, tool.h). Line: o = a, e1 = b - a. Arc:
   o = c, rho = |a - c|, e1 = (a - c)/rho, e2 the unit part of b - c normal to e1. */
static void CurveSetup(const Curve *cv, CurveFrame *F)
{
  double pr, wn;
  F->arc = cv->type == CURVE_ARC;
  if (!F->arc) {
    for (int i = 0; i < 3; i++) {
      F->o[i]  = cv->a[i];
      F->e1[i] = cv->b[i] - cv->a[i];
      F->e2[i] = 0.0;
    }
    F->rho = F->th = 0.0;
    return;
  }
  for (int i = 0; i < 3; i++) {
    F->o[i]  = cv->c[i];
    F->e1[i] = cv->a[i] - cv->c[i];
    F->e2[i] = cv->b[i] - cv->c[i];
  }
  F->rho = Norm(F->e1);
  if (!(F->rho > 0.0)) { /* degenerate: the centre */
    F->rho = F->th = 0.0;
    return;
  }
  for (int i = 0; i < 3; i++) F->e1[i] /= F->rho;
  pr = Dot(F->e2, F->e1);
  for (int i = 0; i < 3; i++) F->e2[i] -= pr * F->e1[i];
  wn    = Norm(F->e2);
  F->th = atan2(wn, pr);
  for (int i = 0; i < 3; i++) F->e2[i] = wn > 0.0 ? F->e2[i] / wn : 0.0;
}

/* point p, first and second derivatives at s */
static inline void CurveFrameEval(const CurveFrame *F, double s, double p[3], double d1[3], double d2[3])
{
  if (!F->arc) {
    for (int i = 0; i < 3; i++) {
      p[i]  = F->o[i] + s * F->e1[i];
      d1[i] = F->e1[i];
      d2[i] = 0.0;
    }
    return;
  }
  const double ct = cos(s * F->th), st = sin(s * F->th), rt = F->rho * F->th;
  for (int i = 0; i < 3; i++) {
    const double r = ct * F->e1[i] + st * F->e2[i];
    p[i]           = F->o[i] + F->rho * r;
    d1[i]          = rt * (-st * F->e1[i] + ct * F->e2[i]);
    d2[i]          = -rt * F->th * r;
  }
}

static void CurveEval(const Curve *cv, double s, double p[3], double d1[3], double d2[3])
{
  CurveFrame F;
  CurveSetup(cv, &F);
  CurveFrameEval(&F, s, p, d1, d2);
}

/* the four curves of a Coons patch: bottom C0, top C1, left D0, right D1 */
typedef struct {
  CurveFrame f[4];
} CoonsFrame;

static void CoonsSetup(const Patch *p, CoonsFrame *F)
{
  if (p->prepared) {
    for (int k = 0; k < 4; k++) F->f[k] = p->frame[k];
    return;
  }
  CurveSetup(&p->C0, &F->f[0]);
  CurveSetup(&p->C1, &F->f[1]);
  CurveSetup(&p->D0, &F->f[2]);
  CurveSetup(&p->D1, &F->f[3]);
}

/* Coons patch: x = (1-v) C0(u) + v C1(u) + (1-u) D0(v) + u D1(v) - B(u,v), B the bilinear
   interpolant of the corners P00 = C0(0), P10 = C0(1), P01 = C1(0), P11 = C1(1). */
static void CoonsEvalF(const Patch *p, const CoonsFrame *F, double u, double v, double x[3], double xu[3], double xv[3], double *xuu, double *xuv, double *xvv)
{
  double        c0[3], c0p[3], c0pp[3], c1[3], c1p[3], c1pp[3], d0[3], d0p[3], d0pp[3], d1[3], d1p[3], d1pp[3];
  const double *P00 = p->C0.a, *P10 = p->C0.b, *P01 = p->C1.a, *P11 = p->C1.b;
  CurveFrameEval(&F->f[0], u, c0, c0p, c0pp);
  CurveFrameEval(&F->f[1], u, c1, c1p, c1pp);
  CurveFrameEval(&F->f[2], v, d0, d0p, d0pp);
  CurveFrameEval(&F->f[3], v, d1, d1p, d1pp);
  for (int i = 0; i < 3; i++) {
    const double B = (1 - u) * (1 - v) * P00[i] + u * (1 - v) * P10[i] + (1 - u) * v * P01[i] + u * v * P11[i];
    x[i]           = (1 - v) * c0[i] + v * c1[i] + (1 - u) * d0[i] + u * d1[i] - B;
    xu[i]          = (1 - v) * c0p[i] + v * c1p[i] - d0[i] + d1[i] - ((1 - v) * (P10[i] - P00[i]) + v * (P11[i] - P01[i]));
    xv[i]          = -c0[i] + c1[i] + (1 - u) * d0p[i] + u * d1p[i] - ((1 - u) * (P01[i] - P00[i]) + u * (P11[i] - P10[i]));
    if (xuu) xuu[i] = (1 - v) * c0pp[i] + v * c1pp[i];
    if (xuv) xuv[i] = -c0p[i] + c1p[i] - d0p[i] + d1p[i] - (P00[i] - P10[i] - P01[i] + P11[i]);
    if (xvv) xvv[i] = (1 - u) * d0pp[i] + u * d1pp[i];
  }
}

static void CoonsEval(const Patch *p, double u, double v, double x[3], double xu[3], double xv[3], double *xuu, double *xuv, double *xvv)
{
  CoonsFrame F;
  CoonsSetup(p, &F);
  CoonsEvalF(p, &F, u, v, x, xu, xv, xuu, xuv, xvv);
}

void PatchEval(const Patch *p, double xi, double eta, double x[3], double xu[3], double xv[3], double *xuu, double *xuv, double *xvv)
{
  const double dt = p->t1 - p->t0, ds = p->s1 - p->s0;
  double       w[3], wp[3], q[3] = {0, 0, 0}, quv[3] = {0, 0, 0}, qvv[3] = {0, 0, 0};
  switch (p->type) {
  case PATCH_PLANE: { /* x = o + u e1 + v e2 */
    const double du = p->u1 - p->u0, dv = p->v1 - p->v0, u = p->u0 + xi * du, v = p->v0 + eta * dv;
    for (int i = 0; i < 3; i++) {
      x[i]  = p->o[i] + u * p->e1[i] + v * p->e2[i];
      xu[i] = du * p->e1[i];
      xv[i] = dv * p->e2[i];
    }
  } break;
  case PATCH_SPHERE: { /* x = c + R (cos th a + sin th w(ph)) */
    const double th = p->t0 + xi * dt, ct = cos(th), st = sin(th), R = p->R;
    Radial(p, p->s0 + eta * ds, w, wp);
    for (int i = 0; i < 3; i++) {
      const double er = ct * p->a[i] + st * w[i];
      x[i]            = p->c[i] + R * er;
      xu[i]           = R * dt * (-st * p->a[i] + ct * w[i]);
      xv[i]           = R * ds * st * wp[i];
      q[i]            = -R * dt * dt * er;
      quv[i]          = R * dt * ds * ct * wp[i];
      qvv[i]          = -R * ds * ds * st * w[i];
    }
  } break;
  case PATCH_CYLINDER: { /* x = c + R w(ph) + z a */
    const double z = p->s0 + eta * ds;
    Radial(p, p->t0 + xi * dt, w, wp);
    for (int i = 0; i < 3; i++) {
      x[i]  = p->c[i] + p->R * w[i] + z * p->a[i];
      xu[i] = p->R * dt * wp[i];
      xv[i] = ds * p->a[i];
      q[i]  = -p->R * dt * dt * w[i];
    }
  } break;
  case PATCH_TORUS: { /* x = c + (R + r cos ps) w(ph) + r sin ps a */
    const double ps = p->s0 + eta * ds, cp = cos(ps), sp = sin(ps), r = p->r, rho = p->R + r * cp;
    Radial(p, p->t0 + xi * dt, w, wp);
    for (int i = 0; i < 3; i++) {
      x[i]   = p->c[i] + rho * w[i] + r * sp * p->a[i];
      xu[i]  = dt * rho * wp[i];
      xv[i]  = ds * r * (-sp * w[i] + cp * p->a[i]);
      q[i]   = -dt * dt * rho * w[i];
      quv[i] = -dt * ds * r * sp * wp[i];
      qvv[i] = -ds * ds * r * (cp * w[i] + sp * p->a[i]);
    }
  } break;
  case PATCH_COONS:
    CoonsEval(p, xi, eta, x, xu, xv, xuu, xuv, xvv);
    return;
  }
  for (int i = 0; i < 3; i++) {
    if (xuu) xuu[i] = q[i];
    if (xuv) xuv[i] = quv[i];
    if (xvv) xvv[i] = qvv[i];
  }
}

static inline double Sgn(double v) { return v < 0.0 ? -1.0 : 1.0; }

double PatchNormal(const Patch *p, double xi, double eta, double n[3])
{
  const double dt = p->t1 - p->t0, ds = p->s1 - p->s0;
  double       w[3], wp[3], s = p->sense < 0 ? -1.0 : 1.0, J = 0.0;
  switch (p->type) {
  case PATCH_PLANE: { /* x_xi x x_eta = du dv e1 x e2 */
    const double duv = (p->u1 - p->u0) * (p->v1 - p->v0);
    Cross(p->e1, p->e2, n);
    s *= Sgn(duv);
    J = fabs(duv);
  } break;
  case PATCH_SPHERE: { /* x_xi x x_eta = R^2 dt ds sin th e_r: the radial direction, also at the poles */
    const double th = p->t0 + xi * dt, ct = cos(th), st = sin(th);
    Radial(p, p->s0 + eta * ds, w, wp);
    for (int i = 0; i < 3; i++) n[i] = ct * p->a[i] + st * w[i];
    s *= Sgn(dt * ds);
    J = p->R * p->R * fabs(dt * ds * st);
  } break;
  case PATCH_CYLINDER: /* R dt ds w(ph) */
    Radial(p, p->t0 + xi * dt, n, wp);
    s *= Sgn(dt * ds);
    J = p->R * fabs(dt * ds);
    break;
  case PATCH_TORUS: { /* dt ds r (R + r cos ps) (cos ps w + sin ps a) */
    const double ps = p->s0 + eta * ds, cp = cos(ps), sp = sin(ps);
    Radial(p, p->t0 + xi * dt, w, wp);
    for (int i = 0; i < 3; i++) n[i] = cp * w[i] + sp * p->a[i];
    s *= Sgn(dt * ds);
    J = p->r * fabs(dt * ds * (p->R + p->r * cp));
  } break;
  case PATCH_COONS: {
    double x[3], xu[3], xv[3], N[3];
    CoonsEval(p, xi, eta, x, xu, xv, NULL, NULL, NULL);
    Cross(xu, xv, N);
    J = Norm(N);
    if (!(J > 1e-14 * (Dot(xu, xu) + Dot(xv, xv)))) { /* degenerate point (collapsed edge): the limit from inside */
      const double h = 1e-7;
      CoonsEval(p, xi + h * (0.5 - xi), eta + h * (0.5 - eta), x, xu, xv, NULL, NULL, NULL);
      Cross(xu, xv, N);
    }
    const double l = Norm(N);
    for (int i = 0; i < 3; i++) n[i] = l > 0.0 ? N[i] / l : 0.0;
  } break;
  }
  for (int i = 0; i < 3; i++) n[i] *= s;
  return J;
}

/* ------------------------------------------------------------------------------------------ */
/* projection                                                                                   */
/* ------------------------------------------------------------------------------------------ */

typedef struct {
  double xi, eta, x[3], d2;
  int    interior;
} Cand;

/* a characteristic length of the patch (tolerances) */
static double PatchScale(const Patch *p)
{
  double L = 0.0;
  switch (p->type) {
  case PATCH_PLANE:
    L = fabs(p->u1 - p->u0) + fabs(p->v1 - p->v0);
    break;
  case PATCH_SPHERE:
    L = p->R;
    break;
  case PATCH_CYLINDER:
    L = p->R + fabs(p->s1 - p->s0);
    break;
  case PATCH_TORUS:
    L = p->R + p->r;
    break;
  case PATCH_COONS:
    L = 0.5 * (sqrt(Dist2(p->C0.a, p->C0.b)) + sqrt(Dist2(p->C1.a, p->C1.b)) + sqrt(Dist2(p->D0.a, p->D0.b)) + sqrt(Dist2(p->D1.a, p->D1.b)));
    break;
  }
  return L > 0.0 ? L : 1.0;
}

/* Angle ang mapped into [a0, a0 + 2 pi): 1 with s = (ang - a0)/(a1 - a0) if it lies in [a0, a1]
   (a0 < a1 <= a0 + 2 pi; a decreasing range is flipped); otherwise 0 with s the nearer end (0 or 1)
   along the circle. */
static int AngleParam(double ang, double a0, double a1, double *s)
{
  if (a1 < a0) {
    const int in = AngleParam(ang, a1, a0, s);
    *s           = 1.0 - *s;
    return in;
  }
  const double span = a1 - a0;
  double       t    = ang - a0;
  t -= 2.0 * TOOL_PI * floor(t / (2.0 * TOOL_PI));
  if (t <= span) {
    *s = t / span;
    return 1;
  }
  *s = (t - span < 2.0 * TOOL_PI - t) ? 1.0 : 0.0;
  return 0;
}

/* Closest point of y on the arc m + rho (cos t p + sin t q), t in [a0, a1] (p, q orthonormal):
   the distance to a circle point grows with the angle from the projection of y, so the arc's
   closest point is that angle if it is in the range, else the nearer end. Returns the squared
   distance and the arc parameter s in [0,1]. */
static double ArcClosest(const double m[3], const double p[3], const double q[3], double rho, double a0, double a1, const double y[3], double *s)
{
  double d[3], u, v, t, x[3];
  for (int i = 0; i < 3; i++) d[i] = y[i] - m[i];
  u = Dot(d, p);
  v = Dot(d, q);
  if (!(rho > 0.0) || (u == 0.0 && v == 0.0)) *s = 0.5; /* every point equidistant */
  else AngleParam(atan2(v, u), a0, a1, s);
  t = a0 + *s * (a1 - a0);
  for (int i = 0; i < 3; i++) x[i] = m[i] + rho * (cos(t) * p[i] + sin(t) * q[i]);
  return Dist2(x, y);
}

/* keep the better of an edge candidate */
static void EdgeTry(double d2, double xi, double eta, double *best, double z[2])
{
  if (d2 < *best) {
    *best = d2;
    z[0]  = xi;
    z[1]  = eta;
  }
}

/* Starting points of the analytic surfaces. The distance from y to a full sphere, an infinite
   cylinder or a full torus has a single local minimum (the radial projection; y off the axis), so
   when it falls outside the patch's range the patch's closest point lies on an edge; every edge
   is a circular arc or a segment, whose closest point is exact (ArcClosest). */
static void SphereStart(const Patch *p, const double y[3], double z[2])
{
  double       d[3], f[3], h, pe, pf, rho, th, ph, st, best = HUGE_VAL, w[3], wp[3], m[3], s = 0.5;
  const double dt = p->t1 - p->t0;
  Cross(p->a, p->e, f);
  for (int i = 0; i < 3; i++) d[i] = y[i] - p->c[i];
  h   = Dot(d, p->a);
  pe  = Dot(d, p->e);
  pf  = Dot(d, f);
  rho = hypot(pe, pf);
  th  = atan2(rho, h); /* polar angle in [0, pi] */
  ph  = atan2(pf, pe); /* azimuth (0 on the axis: any will do) */
  st  = (th - p->t0) / dt;
  if (st >= 0.0 && st <= 1.0 && AngleParam(ph, p->s0, p->s1, &s)) {
    z[0] = st;
    z[1] = s;
    return;
  }
  for (int k = 0; k < 2; k++) { /* xi = k: parallel circle th = t_k */
    const double tk = k ? p->t1 : p->t0;
    for (int i = 0; i < 3; i++) m[i] = p->c[i] + p->R * cos(tk) * p->a[i];
    {
      const double d2 = ArcClosest(m, p->e, f, p->R * sin(tk), p->s0, p->s1, y, &s);
      EdgeTry(d2, k, s, &best, z);
    }
  }
  for (int k = 0; k < 2; k++) { /* eta = k: meridian ph = s_k, th measured from a towards w */
    Radial(p, k ? p->s1 : p->s0, w, wp);
    {
      const double d2 = ArcClosest(p->c, p->a, w, p->R, p->t0, p->t1, y, &s);
      EdgeTry(d2, s, k, &best, z);
    }
  }
}

static void CylinderStart(const Patch *p, const double y[3], double z[2])
{
  double f[3], s = 0.5;
  Cross(p->a, p->e, f);
  /* separable: azimuth on the circle, height clamped */
  ArcClosest(p->c, p->e, f, p->R, p->t0, p->t1, y, &s);
  z[0] = s;
  z[1] = Clamp01(((y[0] - p->c[0]) * p->a[0] + (y[1] - p->c[1]) * p->a[1] + (y[2] - p->c[2]) * p->a[2] - p->s0) / (p->s1 - p->s0));
}

static void TorusStart(const Patch *p, const double y[3], double z[2])
{
  double d[3], f[3], h, pe, pf, rho, ph, ps, sp, sph, best = HUGE_VAL, w[3], wp[3], m[3], s = 0.5;
  Cross(p->a, p->e, f);
  for (int i = 0; i < 3; i++) d[i] = y[i] - p->c[i];
  h   = Dot(d, p->a);
  pe  = Dot(d, p->e);
  pf  = Dot(d, f);
  rho = hypot(pe, pf);
  ph  = atan2(pf, pe);
  ps  = atan2(h, rho - p->R); /* in the meridian plane, about the tube's core */
  if (AngleParam(ph, p->t0, p->t1, &sph) && AngleParam(ps, p->s0, p->s1, &sp)) {
    z[0] = sph;
    z[1] = sp;
    return;
  }
  for (int k = 0; k < 2; k++) { /* xi = k: tube circle at ph = t_k */
    Radial(p, k ? p->t1 : p->t0, w, wp);
    for (int i = 0; i < 3; i++) m[i] = p->c[i] + p->R * w[i];
    {
      const double d2 = ArcClosest(m, w, p->a, p->r, p->s0, p->s1, y, &s);
      EdgeTry(d2, k, s, &best, z);
    }
  }
  for (int k = 0; k < 2; k++) { /* eta = k: parallel circle ps = s_k */
    const double pk = k ? p->s1 : p->s0;
    for (int i = 0; i < 3; i++) m[i] = p->c[i] + p->r * sin(pk) * p->a[i];
    {
      const double d2 = ArcClosest(m, p->e, f, p->R + p->r * cos(pk), p->t0, p->t1, y, &s);
      EdgeTry(d2, s, k, &best, z);
    }
  }
}

/* Coons starting points from a 9 x 9 grid of samples: the curves at the grid lines (an arc's
   angles by the rotation recurrence), the blend at the nodes. */
enum { NG = TOOL_COONS_GRID };
typedef struct {
  const double (*X)[NG][3]; /* the samples: the patch's prepared grid, or own */
  double Xown[NG][NG][3], d2[NG][NG];
  int    ia, ib; /* the best sample */
} CoonsGrid;

static void CurveGrid(const CurveFrame *F, double P[NG][3])
{
  if (!F->arc) {
    for (int k = 0; k < NG; k++)
      for (int i = 0; i < 3; i++) P[k][i] = F->o[i] + (double)k / (NG - 1) * F->e1[i];
    return;
  }
  const double cd = cos(F->th / (NG - 1)), sd = sin(F->th / (NG - 1));
  double       c = 1.0, s = 0.0;
  for (int k = 0; k < NG; k++) {
    for (int i = 0; i < 3; i++) P[k][i] = F->o[i] + F->rho * (c * F->e1[i] + s * F->e2[i]);
    const double cn = c * cd - s * sd;
    s               = s * cd + c * sd;
    c               = cn;
  }
}

static void CoonsGridPoints(const Patch *p, const CoonsFrame *F, double X[NG][NG][3])
{
  double        C0[NG][3], C1[NG][3], D0[NG][3], D1[NG][3];
  const double *P00 = p->C0.a, *P10 = p->C0.b, *P01 = p->C1.a, *P11 = p->C1.b;
  CurveGrid(&F->f[0], C0);
  CurveGrid(&F->f[1], C1);
  CurveGrid(&F->f[2], D0);
  CurveGrid(&F->f[3], D1);
  for (int a = 0; a < NG; a++) {
    const double u = (double)a / (NG - 1);
    for (int b = 0; b < NG; b++) {
      const double v = (double)b / (NG - 1), w00 = (1 - u) * (1 - v), w10 = u * (1 - v), w01 = (1 - u) * v, w11 = u * v;
      for (int i = 0; i < 3; i++) X[a][b][i] = (1 - v) * C0[a][i] + v * C1[a][i] + (1 - u) * D0[b][i] + u * D1[b][i] - (w00 * P00[i] + w10 * P10[i] + w01 * P01[i] + w11 * P11[i]);
    }
  }
}

static void CoonsStart(const Patch *p, const CoonsFrame *F, const double y[3], CoonsGrid *g, double z[2])
{
  double best = HUGE_VAL;
  if (p->prepared) g->X = p->grid;
  else {
    CoonsGridPoints(p, F, g->Xown);
    g->X = (const double(*)[NG][3])g->Xown;
  }
  g->ia = g->ib = 0;
  for (int a = 0; a < NG; a++)
    for (int b = 0; b < NG; b++) {
      g->d2[a][b] = Dist2(g->X[a][b], y);
      if (g->d2[a][b] < best) {
        best  = g->d2[a][b];
        g->ia = a;
        g->ib = b;
      }
    }
  z[0] = (double)g->ia / (NG - 1);
  z[1] = (double)g->ib / (NG - 1);
}

void PatchPrepare(Patch *p)
{
  p->prepared = 0;
  if (p->type != PATCH_COONS) return;
  CoonsFrame F;
  CoonsSetup(p, &F);
  for (int k = 0; k < 4; k++) p->frame[k] = F.f[k];
  CoonsGridPoints(p, &F, p->grid);
  p->prepared = 1;
}

/* A second start: the best sample at least two cells away from the best one whose point differs
   from it (on a patch with a collapsed side the best sample may be a degenerate point). 0 if none. */
static int CoonsSecondStart(const CoonsGrid *g, double z[2])
{
  const double tol2 = 1e-12 * (Dist2(g->X[0][0], g->X[NG - 1][NG - 1]) + Dist2(g->X[NG - 1][0], g->X[0][NG - 1]));
  double       best = HUGE_VAL;
  int          found = 0;
  for (int a = 0; a < NG; a++)
    for (int b = 0; b < NG; b++) {
      if ((abs(a - g->ia) < 2 && abs(b - g->ib) < 2) || g->d2[a][b] >= best || Dist2(g->X[a][b], g->X[g->ia][g->ib]) <= tol2) continue;
      best  = g->d2[a][b];
      z[0]  = (double)a / (NG - 1);
      z[1]  = (double)b / (NG - 1);
      found = 1;
    }
  return found;
}

/* PatchEval, with the Coons curves prepared once (F) */
static inline void Eval(const Patch *p, const CoonsFrame *F, double u, double v, double x[3], double xu[3], double xv[3], double *xuu, double *xuv, double *xvv)
{
  if (F) CoonsEvalF(p, F, u, v, x, xu, xv, xuu, xuv, xvv);
  else PatchEval(p, u, v, x, xu, xv, xuu, xuv, xvv);
}

/* Search direction on the free parameters: mode 0 Newton (full Hessian H, if positive definite),
   1 Gauss-Newton (G = J^T J), 2 gradient scaled by the diagonal. Falls through to the next mode
   when the matrix is not positive definite. */
static void Direction(int mode, const int fr[2], const double g[2], const double G[3], const double H[3], double d[2])
{
  d[0] = d[1] = 0.0;
  for (int m = mode; m < 2; m++) {
    const double *A = m == 0 ? H : G;
    if (fr[0] && fr[1]) {
      const double det = A[0] * A[2] - A[1] * A[1];
      if (A[0] > 0.0 && A[2] > 0.0 && det > 1e-14 * A[0] * A[2]) {
        d[0] = -(A[2] * g[0] - A[1] * g[1]) / det;
        d[1] = -(A[0] * g[1] - A[1] * g[0]) / det;
        return;
      }
    } else {
      const int    i = fr[0] ? 0 : 1;
      const double a = i ? A[2] : A[0];
      if (a > 0.0) {
        d[i] = -g[i] / a;
        return;
      }
    }
  }
  for (int i = 0; i < 2; i++) {
    const double a = fmax(G[2 * i], fabs(H[2 * i]));
    if (fr[i] && a > 0.0) d[i] = -g[i] / a;
  }
}

/* Projected Newton on f = |x(xi,eta) - y|^2 / 2 over [0,1]^2 from z: gradient g_i = (x - y).x_i,
   Hessian H_ij = x_i.x_j + (x - y).x_ij. A parameter at a bound whose gradient points out of the
   square is held (the 1D problem on that edge, or the corner); steps are clamped to the square and
   backtracked (Armijo); if that fails the Gauss-Newton, then the scaled gradient direction is
   tried. Stops when the step is below 1e-12 in the parameters (or 1e-13 L in space). */
static void Minimize(const Patch *p, const CoonsFrame *F, const double y[3], double L, double z[2], Cand *c)
{
  double x[3], xu[3], xv[3], xuu[3], xuv[3], xvv[3], r[3], f, g[2] = {0, 0};
  int    mode = 0;
  Eval(p, F, z[0], z[1], x, xu, xv, xuu, xuv, xvv);
  for (int i = 0; i < 3; i++) r[i] = x[i] - y[i];
  f = 0.5 * Dot(r, r);
  for (int it = 0; it < 100; it++) {
    double       G[3], H[3], d[2], dx[3], alpha = 1.0, zn[2] = {z[0], z[1]}, noise;
    double       xn[3], xun[3], xvn[3], xuun[3], xuvn[3], xvvn[3], rn[3], fn = f;
    int          fr[2], ok = 0;
    g[0] = Dot(r, xu);
    g[1] = Dot(r, xv);
    G[0] = Dot(xu, xu);
    G[1] = Dot(xu, xv);
    G[2] = Dot(xv, xv);
    H[0] = G[0] + Dot(r, xuu);
    H[1] = G[1] + Dot(r, xuv);
    H[2] = G[2] + Dot(r, xvv);
    for (int i = 0; i < 2; i++) fr[i] = !((z[i] <= 0.0 && g[i] > 0.0) || (z[i] >= 1.0 && g[i] < 0.0));
    if (!fr[0] && !fr[1]) break; /* corner, multipliers of the right sign */
    Direction(mode, fr, g, G, H, d);
    for (int i = 0; i < 3; i++) dx[i] = d[0] * xu[i] + d[1] * xv[i];
    if ((fabs(d[0]) <= 1e-12 && fabs(d[1]) <= 1e-12) || Norm(dx) <= 1e-13 * L) break;
    /* round-off level of f (coordinates of size M): below it f cannot rank the points, the
       (locally convergent) step is taken as it is */
    {
      double M = 0.0;
      for (int i = 0; i < 3; i++) M = fmax(M, fmax(fabs(x[i]), fabs(y[i])));
      noise = 8.0 * DBL_EPSILON * (sqrt(2.0 * f) * M + f);
    }
    for (int ls = 0; ls < 40; ls++) {
      zn[0] = Clamp01(z[0] + alpha * d[0]);
      zn[1] = Clamp01(z[1] + alpha * d[1]);
      Eval(p, F, zn[0], zn[1], xn, xun, xvn, xuun, xuvn, xvvn);
      for (int i = 0; i < 3; i++) rn[i] = xn[i] - y[i];
      fn = 0.5 * Dot(rn, rn);
      if (fn <= f + 1e-4 * fmin(0.0, g[0] * (zn[0] - z[0]) + g[1] * (zn[1] - z[1])) + noise) {
        ok = 1;
        break;
      }
      alpha *= 0.5;
    }
    if (!ok) {
      if (++mode > 2) break; /* no descent in any direction: stationary to round-off */
      continue;
    }
    if (zn[0] == z[0] && zn[1] == z[1]) break; /* no motion left */
    mode = 0;
    z[0] = zn[0];
    z[1] = zn[1];
    f    = fn;
    for (int i = 0; i < 3; i++) {
      x[i]   = xn[i];
      xu[i]  = xun[i];
      xv[i]  = xvn[i];
      xuu[i] = xuun[i];
      xuv[i] = xuvn[i];
      xvv[i] = xvvn[i];
      r[i]   = rn[i];
    }
  }
  g[0] = Dot(r, xu);
  g[1] = Dot(r, xv);
  c->xi  = z[0];
  c->eta = z[1];
  for (int i = 0; i < 3; i++) c->x[i] = x[i];
  c->d2 = 2.0 * f;
  /* interior: not at a bound, or at a bound with y - x normal to the surface there too
     (tangential offset |g_i| / |x_i| below 1e-10 L): a point on a seam is interior */
  c->interior = 1;
  {
    const double *xi_[2] = {xu, xv};
    for (int i = 0; i < 2; i++)
      if ((z[i] <= 0.0 || z[i] >= 1.0) && fabs(g[i]) > 1e-10 * L * Norm(xi_[i])) c->interior = 0;
  }
}

/* A collapsed side of a Coons patch (x_xi = 0 along eta = 0 or 1, or x_eta = 0 along xi = 0 or 1)
   maps a whole edge to one point, where Newton stops since that edge's parameter has no effect.
   If c lies there, the distance's derivatives along the fan of tangents x_eta(xi_k) (9 samples)
   are checked, and Newton restarted inside along the steepest descending one. */
static void CoonsFan(const Patch *p, const CoonsFrame *F, const double y[3], double L, Cand *c)
{
  double x[3], xu[3], xv[3], r[3];
  CoonsEvalF(p, F, c->xi, c->eta, x, xu, xv, NULL, NULL, NULL);
  for (int i = 0; i < 3; i++) r[i] = x[i] - y[i];
  for (int dir = 0; dir < 2; dir++) { /* dir 0: side eta = const collapsed (x_xi = 0) */
    const double *ta = dir ? xv : xu, *tb = dir ? xu : xv, zb = dir ? c->xi : c->eta;
    if (!(zb <= 0.0 || zb >= 1.0) || !(Norm(ta) <= 1e-10 * Norm(tb))) continue;
    const double sg = zb <= 0.0 ? 1.0 : -1.0; /* into the square */
    double       best = -1e-12 * L, z[2] = {0, 0}, pu[3], pv[3], px[3];
    for (int k = 0; k <= 8; k++) {
      const double s = k / 8.0;
      CoonsEvalF(p, F, dir ? zb : s, dir ? s : zb, px, pu, pv, NULL, NULL, NULL);
      const double *t = dir ? pu : pv, nt = Norm(t);
      if (!(nt > 0.0)) continue;
      const double dd = sg * Dot(r, t) / nt; /* d|x - y|^2/2 per unit length along the tangent */
      if (dd < best) {
        best          = dd;
        z[dir ? 1 : 0] = s;
        z[dir ? 0 : 1] = zb + sg / 16.0;
      }
    }
    if (best < -1e-12 * L) {
      Cand c2;
      Minimize(p, F, y, L, z, &c2);
      if (c2.d2 < c->d2) *c = c2;
    }
  }
}

/* Closest point of y (reference frame) on one patch; returns 1 if skipped (lower bound of the
   distance above maxdist) */
static int PatchClosest(const Patch *p, const double y[3], double maxdist, Cand *c)
{
  const double L = PatchScale(p);
  double       z[2] = {0.5, 0.5}, d[3], lb = 0.0;
  CoonsFrame   F;
  switch (p->type) {
  case PATCH_PLANE: { /* exact: separable, clamped */
    double n[3];
    for (int i = 0; i < 3; i++) d[i] = y[i] - p->o[i];
    Cross(p->e1, p->e2, n);
    if (fabs(Dot(d, n)) > maxdist) return 1;
    z[0] = Clamp01((Dot(d, p->e1) - p->u0) / (p->u1 - p->u0));
    z[1] = Clamp01((Dot(d, p->e2) - p->v0) / (p->v1 - p->v0));
    double xu[3], xv[3], g[2];
    PatchEval(p, z[0], z[1], c->x, xu, xv, NULL, NULL, NULL);
    c->xi  = z[0];
    c->eta = z[1];
    c->d2  = Dist2(c->x, y);
    for (int i = 0; i < 3; i++) d[i] = c->x[i] - y[i];
    g[0]        = Dot(d, xu);
    g[1]        = Dot(d, xv);
    c->interior = !(((z[0] <= 0.0 || z[0] >= 1.0) && fabs(g[0]) > 1e-10 * L * Norm(xu)) || ((z[1] <= 0.0 || z[1] >= 1.0) && fabs(g[1]) > 1e-10 * L * Norm(xv)));
    return 0;
  }
  case PATCH_SPHERE: /* lower bound: distance to the whole sphere */
    for (int i = 0; i < 3; i++) d[i] = y[i] - p->c[i];
    lb = fabs(Norm(d) - p->R);
    if (lb > maxdist) return 1;
    SphereStart(p, y, z);
    break;
  case PATCH_CYLINDER: { /* distance to the finite full cylinder */
    double h, rho2, dz;
    for (int i = 0; i < 3; i++) d[i] = y[i] - p->c[i];
    h    = Dot(d, p->a);
    rho2 = fmax(Dot(d, d) - h * h, 0.0);
    dz   = fmax(0.0, fmax(fmin(p->s0, p->s1) - h, h - fmax(p->s0, p->s1)));
    lb   = hypot(sqrt(rho2) - p->R, dz);
    if (lb > maxdist) return 1;
    CylinderStart(p, y, z);
  } break;
  case PATCH_TORUS: { /* distance to the full torus */
    double h, rho;
    for (int i = 0; i < 3; i++) d[i] = y[i] - p->c[i];
    h   = Dot(d, p->a);
    rho = sqrt(fmax(Dot(d, d) - h * h, 0.0));
    lb  = fabs(hypot(rho - p->R, h) - p->r);
    if (lb > maxdist) return 1;
    TorusStart(p, y, z);
  } break;
  case PATCH_COONS: {
    double    z2[2];
    CoonsGrid g;
    CoonsSetup(p, &F);
    CoonsStart(p, &F, y, &g, z);
    Minimize(p, &F, y, L, z, c);
    if (!c->interior && CoonsSecondStart(&g, z2)) { /* on the boundary: also from the second start */
      Cand c2;
      Minimize(p, &F, y, L, z2, &c2);
      if (c2.d2 < c->d2) *c = c2;
    }
    if (!c->interior) CoonsFan(p, &F, y, L, c);
    return 0;
  }
  }
  Minimize(p, NULL, y, L, z, c);
  return 0;
}

int ToolProject(const Tool *t, const double shift[3], const double y[3], double maxdist, Projection *pr)
{
  double yr[3], bd = 0.0, tol = 0.0;
  Cand   bi = {0.0, 0.0, {0.0, 0.0, 0.0}, HUGE_VAL, 0}, ba = bi, c, best;
  int    ki = -1, ka = -1, kbest;
  for (int i = 0; i < 3; i++) {
    yr[i]          = y[i] - shift[i]; /* work in the reference position */
    const double o = fmax(t->bbox[2 * i] - yr[i], yr[i] - t->bbox[2 * i + 1]);
    if (o > 0.0) bd += o * o;
  }
  if (sqrt(bd) > maxdist) return 1;
  /* patches in order of the distance to their boxes; a patch whose box is farther than maxdist, or
     than the best interior solution so far, cannot win */
  int    order[64], np = t->npatch < 64 ? t->npatch : 64;
  double bdist[64];
  for (int k = 0; k < np; k++) {
    double b2 = 0.0;
    if (t->patch[k].has_box)
      for (int i = 0; i < 3; i++) {
        const double o = fmax(t->patch[k].bbox[2 * i] - yr[i], yr[i] - t->patch[k].bbox[2 * i + 1]);
        if (o > 0.0) b2 += o * o;
      }
    bdist[k] = sqrt(b2);
    int j    = k;
    while (j > 0 && bdist[order[j - 1]] > bdist[k]) {
      order[j] = order[j - 1];
      j--;
    }
    order[j] = k;
  }
  for (int kk = 0; kk < t->npatch; kk++) {
    const int k = kk < np ? order[kk] : kk;
    if (kk < np && (bdist[k] > maxdist || (ki >= 0 && bdist[k] > sqrt(bi.d2)))) continue;
    if (PatchClosest(&t->patch[k], yr, maxdist, &c) || !(c.d2 >= 0.0)) continue; /* skipped, or not a number */
    if (c.interior && c.d2 < bi.d2) {
      bi = c;
      ki = k;
    }
    if (c.d2 < ba.d2) {
      ba  = c;
      ka  = k;
      tol = 1e-6 * PatchScale(&t->patch[k]);
    }
  }
  if (ka < 0) return 1;
  /* the interior solution of smallest distance, unless a solution held on an edge is closer by
     more than 1e-6 of its patch's size (a point beside an open edge of the tool, e.g. on a
     symmetry plane, must not jump to a far patch) */
  if (ki >= 0 && sqrt(bi.d2) <= sqrt(ba.d2) + tol) {
    best  = bi;
    kbest = ki;
  } else {
    best  = ba;
    kbest = ka;
  }
  pr->patch    = kbest;
  pr->xi       = best.xi;
  pr->eta      = best.eta;
  pr->interior = best.interior;
  PatchNormal(&t->patch[kbest], best.xi, best.eta, pr->n);
  pr->gap = 0.0;
  for (int i = 0; i < 3; i++) {
    pr->x[i] = best.x[i] + shift[i];
    pr->gap += (yr[i] - best.x[i]) * pr->n[i];
  }
  return 0;
}

/* The free parameters' derivatives dz/dy at a projection from the stationarity x_i.(x - y) = 0 of
   the free ones: H dz = x_i^T dy, H_ij = x_i.x_j + (x - y).x_ij. fr: which parameters are free.
   Returns 1 if H is not positive definite. */
static int ProjectionParamDerivative(const double xu[3], const double xv[3], const double xuu[3], const double xuv[3], const double xvv[3], const double r[3], const int fr[2], double dz[2][3])
{
  const double H[3] = {Dot(xu, xu) + Dot(r, xuu), Dot(xu, xv) + Dot(r, xuv), Dot(xv, xv) + Dot(r, xvv)};
  for (int j = 0; j < 3; j++) dz[0][j] = dz[1][j] = 0.0;
  if (fr[0] && fr[1]) {
    const double det = H[0] * H[2] - H[1] * H[1];
    if (!(det > 0.0)) return 1;
    for (int j = 0; j < 3; j++) {
      dz[0][j] = (H[2] * xu[j] - H[1] * xv[j]) / det;
      dz[1][j] = (H[0] * xv[j] - H[1] * xu[j]) / det;
    }
  } else if (fr[0] || fr[1]) {
    const int     i  = fr[0] ? 0 : 1;
    const double  a  = i ? H[2] : H[0];
    const double *xi = i ? xv : xu;
    if (!(a > 0.0)) return 1;
    for (int j = 0; j < 3; j++) dz[i][j] = xi[j] / a;
  }
  return 0;
}

/* Coons: n = sense N/|N|, N = x_xi x x_eta, so dn/dxi = sense (I - n n)(x_xixi x x_eta + x_xi x
   x_xieta)/|N| (and likewise for eta), chained with dz/dy. Both parameters are free at an interior
   projection (on a seam too: the patch extends smoothly), one at a projection held on an edge,
   none at a corner. */
static int CoonsNormalDerivative(const Patch *p, const double shift[3], const double y[3], const Projection *pr, double dn[9])
{
  const double z[2] = {pr->xi, pr->eta};
  double       x[3], xu[3], xv[3], xuu[3], xuv[3], xvv[3], r[3], N[3], Nu[3], Nv[3], a[3], b[3], n[3], l, dz[2][3];
  int          fr[2];
  for (int i = 0; i < 2; i++) fr[i] = pr->interior || (z[i] > 0.0 && z[i] < 1.0);
  if (!fr[0] && !fr[1]) return 0;
  PatchEval(p, z[0], z[1], x, xu, xv, xuu, xuv, xvv);
  Cross(xu, xv, N);
  l = Norm(N);
  if (!(l > 1e-10 * (Dot(xu, xu) + Dot(xv, xv)))) return 1; /* collapsed side */
  for (int i = 0; i < 3; i++) {
    n[i] = N[i] / l;
    r[i] = x[i] - (y[i] - shift[i]);
  }
  if (ProjectionParamDerivative(xu, xv, xuu, xuv, xvv, r, fr, dz)) return 1;
  Cross(xuu, xv, a);
  Cross(xu, xuv, b);
  for (int i = 0; i < 3; i++) Nu[i] = a[i] + b[i];
  Cross(xuv, xv, a);
  Cross(xu, xvv, b);
  for (int i = 0; i < 3; i++) Nv[i] = a[i] + b[i];
  {
    const double s = p->sense < 0 ? -1.0 : 1.0, pu = Dot(n, Nu), pv = Dot(n, Nv);
    for (int i = 0; i < 3; i++) {
      const double nu = s * (Nu[i] - pu * n[i]) / l, nv = s * (Nv[i] - pv * n[i]) / l;
      for (int j = 0; j < 3; j++) dn[3 * i + j] = nu * dz[0][j] + nv * dz[1][j];
    }
  }
  return 0;
}

/* dn/dy. Interior projections of the analytic surfaces in closed form (n = s m, m the unit radial
   direction of the offset surface through y: d(m)/dy = (I - m m) d(y - q)/dy / |y - q|, q the
   centre, the axis point or the core-circle point). Projections held on an edge: n(xi(y), eta(y))
   with the free parameter from the stationarity x_i.(x - y) = 0, i.e. H dz = x_i^T dy. */
int PatchNormalDerivative(const Patch *p, const double shift[3], const double y[3], const Projection *pr, double dn[9])
{
  const double s = (p->sense < 0 ? -1.0 : 1.0) * Sgn((p->t1 - p->t0) * (p->s1 - p->s0));
  double       d[3], m[3], P[9];
  for (int i = 0; i < 9; i++) dn[i] = 0.0;
  if (p->type == PATCH_COONS) return CoonsNormalDerivative(p, shift, y, pr, dn);
  if (p->type == PATCH_PLANE) return 0;
  for (int i = 0; i < 3; i++) d[i] = y[i] - shift[i] - p->c[i];
  if (pr->interior) {
    if (p->type == PATCH_SPHERE) { /* (I - n n)/|y - c| */
      const double l = Norm(d);
      if (!(l > 0.0)) return 0;
      for (int i = 0; i < 3; i++) m[i] = d[i] / l;
      for (int i = 0; i < 3; i++)
        for (int j = 0; j < 3; j++) dn[3 * i + j] = s * ((i == j) - m[i] * m[j]) / l;
      return 0;
    }
    const double h = Dot(d, p->a);
    double       dp[3], rho;
    for (int i = 0; i < 3; i++) dp[i] = d[i] - h * p->a[i];
    rho = Norm(dp);
    if (!(rho > 0.0)) return 0;
    for (int i = 0; i < 3; i++) m[i] = dp[i] / rho;
    for (int i = 0; i < 3; i++)
      for (int j = 0; j < 3; j++) P[3 * i + j] = (i == j) - p->a[i] * p->a[j] - m[i] * m[j]; /* I - a a - w w */
    if (p->type == PATCH_CYLINDER) {                                                        /* (I - a a - n n)/rho */
      for (int i = 0; i < 9; i++) dn[i] = s * P[i] / rho;
      return 0;
    }
    /* torus: u = y - q, q = c + R w, dq/dy = R (I - a a - w w)/rho; dn/dy = s (I - n n)(I - dq/dy)/|u| */
    double u[3], l, A[9];
    for (int i = 0; i < 3; i++) u[i] = d[i] - p->R * m[i];
    l = Norm(u);
    if (!(l > 0.0)) return 0;
    for (int i = 0; i < 3; i++) u[i] /= l;
    for (int i = 0; i < 9; i++) A[i] = ((i % 4) == 0) - p->R * P[i] / rho;
    for (int i = 0; i < 3; i++)
      for (int j = 0; j < 3; j++) {
        double v = 0.0;
        for (int k = 0; k < 3; k++) v += ((i == k) - u[i] * u[k]) * A[3 * k + j];
        dn[3 * i + j] = s * v / l;
      }
    return 0;
  }
  /* held on an edge or at a corner */
  {
    const double dt = p->t1 - p->t0, ds = p->s1 - p->s0;
    double       x[3], xu[3], xv[3], xuu[3], xuv[3], xvv[3], r[3], nu[3] = {0, 0, 0}, nv[3] = {0, 0, 0}, w[3], wp[3];
    int          fr[2];
    const double z[2] = {pr->xi, pr->eta};
    for (int i = 0; i < 2; i++) fr[i] = z[i] > 0.0 && z[i] < 1.0;
    if (!fr[0] && !fr[1]) return 0;
    PatchEval(p, z[0], z[1], x, xu, xv, xuu, xuv, xvv);
    for (int i = 0; i < 3; i++) r[i] = x[i] - (y[i] - shift[i]);
    /* dn/dxi, dn/deta */
    if (p->type == PATCH_SPHERE) {
      for (int i = 0; i < 3; i++) {
        nu[i] = s * xu[i] / p->R;
        nv[i] = s * xv[i] / p->R;
      }
    } else if (p->type == PATCH_CYLINDER) {
      for (int i = 0; i < 3; i++) nu[i] = s * xu[i] / p->R;
    } else { /* torus */
      const double ps = p->s0 + z[1] * ds;
      Radial(p, p->t0 + z[0] * dt, w, wp);
      for (int i = 0; i < 3; i++) {
        nu[i] = s * dt * cos(ps) * wp[i];
        nv[i] = s * xv[i] / p->r;
      }
    }
    double dz[2][3];
    if (ProjectionParamDerivative(xu, xv, xuu, xuv, xvv, r, fr, dz)) return 0;
    for (int i = 0; i < 3; i++)
      for (int j = 0; j < 3; j++) dn[3 * i + j] = nu[i] * dz[0][j] + nv[i] * dz[1][j];
  }
  return 0;
}

void ToolShift(const Tool *t, double lambda, double shift[3])
{
  if (t->npath > 0) {
    const double *P = t->path;
    int           k = 0;
    while (k < t->npath - 1 && lambda > P[4 * (k + 1)]) k++;
    if (k == t->npath - 1) {
      for (int i = 0; i < 3; i++) shift[i] = P[4 * k + 1 + i];
      return;
    }
    const double w = (lambda - P[4 * k]) / (P[4 * (k + 1)] - P[4 * k]);
    for (int i = 0; i < 3; i++) shift[i] = (1 - w) * P[4 * k + 1 + i] + w * P[4 * (k + 1) + 1 + i];
    return;
  }
  for (int i = 0; i < 3; i++) shift[i] = lambda * t->motion[i];
}

/* ------------------------------------------------------------------------------------------ */
/* options                                                                                      */
/* ------------------------------------------------------------------------------------------ */

#define TOOL_MAX_TOOLS 64

/* n reals of option <pre>_<key>; required or not (then *set says whether it was given) */
static PetscErrorCode GetReals(MPI_Comm comm, const char *pre, const char *key, PetscInt n, PetscReal *v, PetscBool required, PetscBool *set)
{
  char      opt[PETSC_MAX_PATH_LEN];
  PetscReal buf[16];
  PetscInt  cnt = 16; /* room for more, to report a surplus */
  PetscBool flg;

  PetscFunctionBeginUser;
  PetscCall(PetscSNPrintf(opt, sizeof(opt), "%s_%s", pre, key));
  PetscCall(PetscOptionsGetRealArray(NULL, NULL, opt, buf, &cnt, &flg));
  PetscCheck(flg || !required, comm, PETSC_ERR_USER_INPUT, "%s: missing required option (%" PetscInt_FMT " value%s)", opt, n, n > 1 ? "s" : "");
  if (flg) {
    PetscCheck(cnt == n, comm, PETSC_ERR_USER_INPUT, "%s: needs %" PetscInt_FMT " value%s, got %" PetscInt_FMT, opt, n, n > 1 ? "s" : "", cnt);
    for (PetscInt i = 0; i < n; i++) {
      PetscCheck(!PetscIsInfOrNanReal(buf[i]), comm, PETSC_ERR_USER_INPUT, "%s: value %g is not a finite number", opt, (double)buf[i]);
      v[i] = buf[i];
    }
  }
  if (set) *set = flg;
  PetscFunctionReturn(0);
}

static PetscErrorCode GetVec(MPI_Comm comm, const char *pre, const char *key, double v[3])
{
  PetscReal b[3] = {0, 0, 0};
  PetscFunctionBeginUser;
  PetscCall(GetReals(comm, pre, key, 3, b, PETSC_TRUE, NULL));
  for (int i = 0; i < 3; i++) v[i] = b[i];
  PetscFunctionReturn(0);
}

static PetscErrorCode GetPositive(MPI_Comm comm, const char *pre, const char *key, double *v)
{
  PetscReal b = 0;
  PetscFunctionBeginUser;
  PetscCall(GetReals(comm, pre, key, 1, &b, PETSC_TRUE, NULL));
  PetscCheck(b > 0, comm, PETSC_ERR_USER_INPUT, "%s_%s %g: must be > 0", pre, key, (double)b);
  *v = b;
  PetscFunctionReturn(0);
}

/* unit axis a (option key) and reference e (option rkey) orthonormalised against it */
static PetscErrorCode GetFrame(MPI_Comm comm, const char *pre, const char *key, const char *rkey, double a[3], double e[3])
{
  double na, ne, ref[3] = {0, 0, 0}, nr, pa;
  PetscFunctionBeginUser;
  PetscCall(GetVec(comm, pre, key, a));
  na = Norm(a);
  PetscCheck(na > 0, comm, PETSC_ERR_USER_INPUT, "%s_%s %g,%g,%g: zero vector", pre, key, a[0], a[1], a[2]);
  for (int i = 0; i < 3; i++) a[i] /= na;
  PetscCall(GetVec(comm, pre, rkey, ref));
  nr = Norm(ref);
  pa = Dot(ref, a);
  for (int i = 0; i < 3; i++) e[i] = ref[i] - pa * a[i];
  ne = Norm(e);
  PetscCheck(nr > 0 && ne > 1e-10 * nr, comm, PETSC_ERR_USER_INPUT, "%s_%s %g,%g,%g: zero or parallel to %s_%s", pre, rkey, ref[0], ref[1], ref[2], pre, key);
  for (int i = 0; i < 3; i++) e[i] /= ne;
  PetscFunctionReturn(0);
}

/* range option: 4 values (lo0, hi0, lo1, hi1); deg[i] converts pair i from degrees; each pair
   must be increasing, angular spans at most 360 degrees */
static PetscErrorCode GetRange(MPI_Comm comm, const char *pre, const PetscBool deg[2], double r[4])
{
  PetscReal b[4] = {0, 0, 0, 0};
  PetscFunctionBeginUser;
  PetscCall(GetReals(comm, pre, "range", 4, b, PETSC_TRUE, NULL));
  for (int k = 0; k < 2; k++) {
    PetscCheck(b[2 * k] < b[2 * k + 1], comm, PETSC_ERR_USER_INPUT, "%s_range %g,%g,%g,%g: empty range (the %s value must exceed the %s)", pre, (double)b[0], (double)b[1], (double)b[2], (double)b[3], k ? "fourth" : "second", k ? "third" : "first");
    if (deg[k]) PetscCheck(b[2 * k + 1] - b[2 * k] <= 360.0, comm, PETSC_ERR_USER_INPUT, "%s_range %g,%g,%g,%g: angular span %g exceeds 360 degrees", pre, (double)b[0], (double)b[1], (double)b[2], (double)b[3], (double)(b[2 * k + 1] - b[2 * k]));
  }
  for (int k = 0; k < 4; k++) r[k] = deg[k / 2] ? b[k] * TOOL_PI / 180.0 : b[k];
  PetscFunctionReturn(0);
}

static PetscErrorCode GetCurve(MPI_Comm comm, const char *pre, const char *side, Curve *cv)
{
  char      key[64], typ[64], opt[PETSC_MAX_PATH_LEN];
  PetscBool flg;
  PetscReal b[9] = {0};
  PetscInt  np;

  PetscFunctionBeginUser;
  PetscCall(PetscSNPrintf(opt, sizeof(opt), "%s_%s_type", pre, side));
  PetscCall(PetscOptionsGetString(NULL, NULL, opt, typ, sizeof(typ), &flg));
  PetscCheck(flg, comm, PETSC_ERR_USER_INPUT, "%s: missing required option (line or arc)", opt);
  if (!strcmp(typ, "line")) cv->type = CURVE_LINE;
  else if (!strcmp(typ, "arc")) cv->type = CURVE_ARC;
  else SETERRQ(comm, PETSC_ERR_USER_INPUT, "%s %s: unknown curve type (use line or arc)", opt, typ);
  np = cv->type == CURVE_LINE ? 6 : 9;
  PetscCall(PetscSNPrintf(key, sizeof(key), "%s_points", side));
  PetscCall(GetReals(comm, pre, key, np, b, PETSC_TRUE, NULL));
  for (int i = 0; i < 3; i++) {
    cv->a[i] = b[i];
    cv->b[i] = b[3 + i];
    cv->c[i] = np == 9 ? b[6 + i] : 0.0;
  }
  if (cv->type == CURVE_ARC) {
    double u[3], v[3], ru, rv, cs;
    for (int i = 0; i < 3; i++) {
      u[i] = cv->a[i] - cv->c[i];
      v[i] = cv->b[i] - cv->c[i];
    }
    ru = Norm(u);
    rv = Norm(v);
    PetscCheck(ru > 0 && rv > 0, comm, PETSC_ERR_USER_INPUT, "%s_%s_points: an arc end point coincides with the centre", pre, side);
    PetscCheck(fabs(ru - rv) <= 1e-8 * fmax(ru, rv), comm, PETSC_ERR_USER_INPUT, "%s_%s_points: arc end points not equidistant from the centre: %.12g and %.12g", pre, side, ru, rv);
    cs = Dot(u, v) / (ru * rv);
    PetscCheck(cs > -1.0 + 1e-12, comm, PETSC_ERR_USER_INPUT, "%s_%s_points: arc end points diametrically opposite (the arc is ambiguous; split it)", pre, side);
    PetscCheck(Dist2(cv->a, cv->b) > 0, comm, PETSC_ERR_USER_INPUT, "%s_%s_points: arc end points coincide", pre, side);
  }
  PetscFunctionReturn(0);
}

static PetscErrorCode GetPatch(MPI_Comm comm, const char *pre, Patch *p)
{
  char      opt[PETSC_MAX_PATH_LEN], typ[64];
  PetscBool flg;
  PetscInt  sense = 1;

  PetscFunctionBeginUser;
  PetscCall(PetscMemzero(p, sizeof(*p)));
  PetscCall(PetscSNPrintf(opt, sizeof(opt), "%s_type", pre));
  PetscCall(PetscOptionsGetString(NULL, NULL, opt, typ, sizeof(typ), &flg));
  PetscCheck(flg, comm, PETSC_ERR_USER_INPUT, "%s: missing required option (plane, sphere, cylinder, torus or coons)", opt);
  if (!strcmp(typ, "plane")) p->type = PATCH_PLANE;
  else if (!strcmp(typ, "sphere")) p->type = PATCH_SPHERE;
  else if (!strcmp(typ, "cylinder")) p->type = PATCH_CYLINDER;
  else if (!strcmp(typ, "torus")) p->type = PATCH_TORUS;
  else if (!strcmp(typ, "coons")) p->type = PATCH_COONS;
  else SETERRQ(comm, PETSC_ERR_USER_INPUT, "%s %s: unknown patch type (use plane, sphere, cylinder, torus or coons)", opt, typ);
  PetscCall(PetscSNPrintf(opt, sizeof(opt), "%s_sense", pre));
  PetscCall(PetscOptionsGetInt(NULL, NULL, opt, &sense, NULL));
  PetscCheck(sense == 1 || sense == -1, comm, PETSC_ERR_USER_INPUT, "%s %" PetscInt_FMT ": must be 1 or -1", opt, sense);
  p->sense = (int)sense;

  switch (p->type) {
  case PATCH_PLANE: {
    const PetscBool deg[2] = {PETSC_FALSE, PETSC_FALSE};
    double          n1, n2, pr, r[4] = {0, 0, 0, 0}, e2[3] = {0, 0, 0};
    PetscCall(GetVec(comm, pre, "origin", p->o));
    PetscCall(GetVec(comm, pre, "e1", p->e1));
    PetscCall(GetVec(comm, pre, "e2", e2));
    n1 = Norm(p->e1);
    PetscCheck(n1 > 0, comm, PETSC_ERR_USER_INPUT, "%s_e1 %g,%g,%g: zero vector", pre, p->e1[0], p->e1[1], p->e1[2]);
    for (int i = 0; i < 3; i++) p->e1[i] /= n1;
    pr = Dot(e2, p->e1);
    for (int i = 0; i < 3; i++) p->e2[i] = e2[i] - pr * p->e1[i];
    n2 = Norm(p->e2);
    PetscCheck(n2 > 1e-10 * Norm(e2) && n2 > 0, comm, PETSC_ERR_USER_INPUT, "%s_e2 %g,%g,%g: zero or parallel to %s_e1", pre, e2[0], e2[1], e2[2], pre);
    for (int i = 0; i < 3; i++) p->e2[i] /= n2;
    PetscCall(GetRange(comm, pre, deg, r));
    p->u0 = r[0];
    p->u1 = r[1];
    p->v0 = r[2];
    p->v1 = r[3];
  } break;
  case PATCH_SPHERE: {
    const PetscBool deg[2] = {PETSC_TRUE, PETSC_TRUE};
    double          r[4] = {0, 0, 0, 0};
    PetscCall(GetVec(comm, pre, "center", p->c));
    PetscCall(GetPositive(comm, pre, "radius", &p->R));
    PetscCall(GetFrame(comm, pre, "axis", "ref", p->a, p->e));
    PetscCall(GetRange(comm, pre, deg, r));
    PetscCheck(r[0] >= 0 && r[1] <= TOOL_PI * (1 + 1e-15), comm, PETSC_ERR_USER_INPUT, "%s_range: polar angles %g to %g must lie in [0, 180] degrees", pre, r[0] * 180 / TOOL_PI, r[1] * 180 / TOOL_PI);
    p->t0 = r[0];
    p->t1 = fmin(r[1], TOOL_PI);
    p->s0 = r[2];
    p->s1 = r[3];
  } break;
  case PATCH_CYLINDER: {
    const PetscBool deg[2] = {PETSC_TRUE, PETSC_FALSE};
    double          r[4] = {0, 0, 0, 0};
    PetscCall(GetVec(comm, pre, "center", p->c));
    PetscCall(GetFrame(comm, pre, "axis", "ref", p->a, p->e));
    PetscCall(GetPositive(comm, pre, "radius", &p->R));
    PetscCall(GetRange(comm, pre, deg, r));
    p->t0 = r[0];
    p->t1 = r[1];
    p->s0 = r[2];
    p->s1 = r[3];
  } break;
  case PATCH_TORUS: {
    const PetscBool deg[2] = {PETSC_TRUE, PETSC_TRUE};
    double          r[4] = {0, 0, 0, 0};
    PetscCall(GetVec(comm, pre, "center", p->c));
    PetscCall(GetFrame(comm, pre, "axis", "ref", p->a, p->e));
    PetscCall(GetPositive(comm, pre, "major", &p->R));
    PetscCall(GetPositive(comm, pre, "minor", &p->r));
    PetscCheck(p->r < p->R, comm, PETSC_ERR_USER_INPUT, "%s_minor %g: must be smaller than %s_major %g", pre, p->r, pre, p->R);
    PetscCall(GetRange(comm, pre, deg, r));
    p->t0 = r[0];
    p->t1 = r[1];
    p->s0 = r[2];
    p->s1 = r[3];
  } break;
  case PATCH_COONS: {
    /* corners: (0,0) C0(0)=D0(0), (1,0) C0(1)=D1(0), (0,1) C1(0)=D0(1), (1,1) C1(1)=D1(1) */
    double       q[4][2][3], t1[3], t2[3], L = 0.0, rmax = 0.0;
    const int    cu[4][2] = {{0, 0}, {1, 0}, {0, 1}, {1, 1}};
    const Curve *cv[4];
    PetscCall(GetCurve(comm, pre, "bottom", &p->C0));
    PetscCall(GetCurve(comm, pre, "top", &p->C1));
    PetscCall(GetCurve(comm, pre, "left", &p->D0));
    PetscCall(GetCurve(comm, pre, "right", &p->D1));
    cv[0] = &p->C0;
    cv[1] = &p->C1;
    cv[2] = &p->D0;
    cv[3] = &p->D1;
    for (int k = 0; k < 4; k++) {
      L = fmax(L, sqrt(Dist2(cv[k]->a, cv[k]->b)));
      if (cv[k]->type == CURVE_ARC) rmax = fmax(rmax, sqrt(Dist2(cv[k]->a, cv[k]->c)));
    }
    for (int k = 0; k < 4; k++) {
      const int u = cu[k][0], v = cu[k][1];
      CurveEval(v ? &p->C1 : &p->C0, u, q[k][0], t1, t2); /* bottom/top at xi = u */
      CurveEval(u ? &p->D1 : &p->D0, v, q[k][1], t1, t2); /* left/right at eta = v */
      const double dist = sqrt(Dist2(q[k][0], q[k][1]));
      PetscCheck(dist <= 1e-8 * fmax(L, rmax), comm, PETSC_ERR_USER_INPUT, "%s: the boundary curves do not meet at corner (xi,eta)=(%d,%d): distance %g", pre, u, v, dist);
    }
    PetscCheck(L > 0, comm, PETSC_ERR_USER_INPUT, "%s: the boundary curves are all single points", pre);
  } break;
  }
  PetscFunctionReturn(0);
}

/* Bounding box of a patch: a 33 x 33 sample grid, enlarged by the interpolation error bound
   (|x_uu| h^2 + 2 |x_uv| h^2 + |x_vv| h^2)/8 (doubled) and 1e-9 of its size */
static void PatchBox(const Patch *p, double b[6])
{
  enum { NB = 33 };
  const double h = 1.0 / (NB - 1);
  double       marg = 0.0, x[3], xu[3], xv[3], xuu[3], xuv[3], xvv[3], diag;
  for (int i = 0; i < 3; i++) {
    b[2 * i]     = HUGE_VAL;
    b[2 * i + 1] = -HUGE_VAL;
  }
  for (int a = 0; a < NB; a++)
    for (int c = 0; c < NB; c++) {
      PatchEval(p, a * h, c * h, x, xu, xv, xuu, xuv, xvv);
      for (int i = 0; i < 3; i++) {
        b[2 * i]     = fmin(b[2 * i], x[i]);
        b[2 * i + 1] = fmax(b[2 * i + 1], x[i]);
      }
      marg = fmax(marg, (Norm(xuu) + 2.0 * Norm(xuv) + Norm(xvv)) * h * h / 8.0);
    }
  diag = sqrt((b[1] - b[0]) * (b[1] - b[0]) + (b[3] - b[2]) * (b[3] - b[2]) + (b[5] - b[4]) * (b[5] - b[4]));
  marg = 2.0 * marg + 1e-9 * diag;
  for (int i = 0; i < 3; i++) {
    b[2 * i] -= marg;
    b[2 * i + 1] += marg;
  }
}

PetscErrorCode ToolsCreateFromOptions(MPI_Comm comm, PetscInt *ntools, Tool **tools)
{
  char     *names[TOOL_MAX_TOOLS];
  PetscInt  n = TOOL_MAX_TOOLS;
  PetscBool set;
  Tool     *T;

  PetscFunctionBeginUser;
  *ntools = 0;
  *tools  = NULL;
  PetscCall(PetscOptionsGetStringArray(NULL, NULL, "-tool_names", names, &n, &set));
  if (!set || n == 0) PetscFunctionReturn(0);
  /* owned by the caller from here: on error, ToolsDestroy frees what was built */
  PetscCall(PetscCalloc1(n, &T));
  *tools  = T;
  *ntools = n;
  for (PetscInt k = 0; k < n; k++) {
    PetscCall(PetscStrncpy(T[k].name, names[k], sizeof(T[k].name)));
    PetscCall(PetscFree(names[k]));
  }
  for (PetscInt k = 0; k < n; k++) {
    size_t len;
    PetscCall(PetscStrlen(T[k].name, &len));
    PetscCheck(len > 0 && len < 64, comm, PETSC_ERR_USER_INPUT, "-tool_names: tool %" PetscInt_FMT ": empty name or longer than 63 characters", k);
    for (const char *c = T[k].name; *c; c++) PetscCheck((*c >= 'a' && *c <= 'z') || (*c >= 'A' && *c <= 'Z') || (*c >= '0' && *c <= '9') || *c == '_', comm, PETSC_ERR_USER_INPUT, "-tool_names: name '%s' may only contain letters, digits and _", T[k].name);
    for (PetscInt j = 0; j < k; j++) PetscCheck(strcmp(T[j].name, T[k].name), comm, PETSC_ERR_USER_INPUT, "-tool_names: name '%s' given twice", T[k].name);
  }
  for (PetscInt k = 0; k < n; k++) {
    Tool     *t = &T[k];
    char      pre[PETSC_MAX_PATH_LEN], opt[PETSC_MAX_PATH_LEN];
    PetscInt  np = 0;
    PetscReal mo[3] = {0, 0, 0};
    PetscBool flg;
    PetscCall(PetscSNPrintf(pre, sizeof(pre), "-tool_%s", t->name));
    PetscCall(GetReals(comm, pre, "motion", 3, mo, PETSC_FALSE, NULL));
    for (int i = 0; i < 3; i++) t->motion[i] = mo[i];
    {
      /* piecewise-linear path: (load, dx, dy, dz) points */
      PetscInt  cnt = 4 * 32;
      PetscBool pset;
      PetscCall(PetscSNPrintf(opt, sizeof(opt), "%s_path", pre));
      PetscCall(PetscOptionsGetRealArray(NULL, NULL, opt, t->path, &cnt, &pset));
      if (pset) {
        PetscCheck(cnt >= 8 && cnt % 4 == 0, comm, PETSC_ERR_USER_INPUT, "%s: needs groups of 4 values (load, dx, dy, dz), at least 2 points and at most 32; got %" PetscInt_FMT " values", opt, cnt);
        t->npath = (int)(cnt / 4);
        PetscCheck(t->path[0] == 0, comm, PETSC_ERR_USER_INPUT, "%s: the first point must be at load 0, not %g", opt, (double)t->path[0]);
        for (int q = 0; q < cnt; q++) PetscCheck(!PetscIsInfOrNanReal(t->path[q]), comm, PETSC_ERR_USER_INPUT, "%s: value %g is not a finite number", opt, (double)t->path[q]);
        for (int q = 1; q < t->npath; q++) PetscCheck(t->path[4 * q] > t->path[4 * (q - 1)] && t->path[4 * q] <= 1, comm, PETSC_ERR_USER_INPUT, "%s: the loads must increase within [0, 1] (point %d at %g)", opt, q, (double)t->path[4 * q]);
        PetscCheck(mo[0] == 0 && mo[1] == 0 && mo[2] == 0, comm, PETSC_ERR_USER_INPUT, "%s and %s_motion are exclusive", opt, pre);
      }
    }
    PetscCall(PetscSNPrintf(opt, sizeof(opt), "%s_patches", pre));
    PetscCall(PetscOptionsGetInt(NULL, NULL, opt, &np, &flg));
    PetscCheck(flg, comm, PETSC_ERR_USER_INPUT, "%s: missing required option (number of patches of tool '%s')", opt, t->name);
    PetscCheck(np >= 1, comm, PETSC_ERR_USER_INPUT, "%s %" PetscInt_FMT ": a tool needs at least one patch", opt, np);
    PetscCall(PetscCalloc1(np, &t->patch));
    t->npatch = (int)np;
    for (PetscInt j = 0; j < np; j++) {
      char pp[PETSC_MAX_PATH_LEN];
      PetscCall(PetscSNPrintf(pp, sizeof(pp), "%s_patch%" PetscInt_FMT, pre, j));
      PetscCall(GetPatch(comm, pp, &t->patch[j]));
      PatchPrepare(&t->patch[j]);
    }
    for (int i = 0; i < 3; i++) {
      t->bbox[2 * i]     = HUGE_VAL;
      t->bbox[2 * i + 1] = -HUGE_VAL;
    }
    for (int j = 0; j < t->npatch; j++) {
      double b[6];
      PatchBox(&t->patch[j], b);
      for (int i = 0; i < 6; i++) t->patch[j].bbox[i] = b[i];
      t->patch[j].has_box = 1;
      for (int i = 0; i < 3; i++) {
        t->bbox[2 * i]     = fmin(t->bbox[2 * i], b[2 * i]);
        t->bbox[2 * i + 1] = fmax(t->bbox[2 * i + 1], b[2 * i + 1]);
      }
    }
  }
  PetscFunctionReturn(0);
}

PetscErrorCode ToolsDestroy(PetscInt ntools, Tool **tools)
{
  PetscFunctionBeginUser;
  if (!*tools) PetscFunctionReturn(0);
  for (PetscInt k = 0; k < ntools; k++) PetscCall(PetscFree((*tools)[k].patch));
  PetscCall(PetscFree(*tools));
  PetscFunctionReturn(0);
}
