/* Patch type "sphere": x = c + R (cos th a + sin th w(ph)), polar angle th = t0 + xi (t1 - t0)
   from the axis a, azimuth ph = s0 + eta (s1 - s0) from e (frames: revolution.c) */
#include "toolimpl.h"

#include "options.h"

static void SphereEval(const Patch *p, double xi, double eta, double x[3], double xu[3], double xv[3], double *xuu, double *xuv, double *xvv)
{
  const RevolutionData *g  = &p->rev;
  const double          dt = g->t1 - g->t0, ds = g->s1 - g->s0;
  double                w[3], wp[3], q[3] = {0, 0, 0}, quv[3] = {0, 0, 0}, qvv[3] = {0, 0, 0};
  const double          th = g->t0 + xi * dt, ct = cos(th), st = sin(th), R = g->R;
  Radial(g, g->s0 + eta * ds, w, wp);
  for (int i = 0; i < 3; i++) {
    const double er = ct * g->a[i] + st * w[i];
    x[i]            = g->c[i] + R * er;
    xu[i]           = R * dt * (-st * g->a[i] + ct * w[i]);
    xv[i]           = R * ds * st * wp[i];
    q[i]            = -R * dt * dt * er;
    quv[i]          = R * dt * ds * ct * wp[i];
    qvv[i]          = -R * ds * ds * st * w[i];
  }
  for (int i = 0; i < 3; i++) {
    if (xuu) xuu[i] = q[i];
    if (xuv) xuv[i] = quv[i];
    if (xvv) xvv[i] = qvv[i];
  }
}

/* x_xi x x_eta = R^2 dt ds sin th e_r: the radial direction, also at the poles */
static double SphereNormal(const Patch *p, double xi, double eta, double n[3])
{
  const RevolutionData *g  = &p->rev;
  const double          dt = g->t1 - g->t0, ds = g->s1 - g->s0;
  double                w[3], wp[3], s = SenseSign(p), J;
  const double          th = g->t0 + xi * dt, ct = cos(th), st = sin(th);
  Radial(g, g->s0 + eta * ds, w, wp);
  for (int i = 0; i < 3; i++) n[i] = ct * g->a[i] + st * w[i];
  s *= Sgn(dt * ds);
  J = g->R * g->R * fabs(dt * ds * st);
  for (int i = 0; i < 3; i++) n[i] *= s;
  return J;
}

static double SphereScale(const Patch *p) { return p->rev.R; }

/* Lower bound: the distance to the whole sphere. Start: the radial projection, which is the only
   local minimum of the distance to the full sphere (y off the axis); when it falls outside the
   patch's range the closest point lies on an edge, every edge being a circular arc whose closest
   point is exact (ArcClosest). */
static int SphereStart(const Patch *p, const double y[3], double maxdist, double z[2])
{
  const RevolutionData *g = &p->rev;
  double                d[3], f[3], h, pe, pf, rho, th, ph, st, best = HUGE_VAL, w[3], wp[3], m[3], s = 0.5, lb;
  const double          dt = g->t1 - g->t0;
  for (int i = 0; i < 3; i++) d[i] = y[i] - g->c[i];
  lb = fabs(Norm(d) - g->R);
  if (lb > maxdist) return 1;
  Cross(g->a, g->e, f);
  for (int i = 0; i < 3; i++) d[i] = y[i] - g->c[i];
  h   = Dot(d, g->a);
  pe  = Dot(d, g->e);
  pf  = Dot(d, f);
  rho = hypot(pe, pf);
  th  = atan2(rho, h); /* polar angle in [0, pi] */
  ph  = atan2(pf, pe); /* azimuth (0 on the axis: any will do) */
  st  = (th - g->t0) / dt;
  if (st >= 0.0 && st <= 1.0 && AngleParam(ph, g->s0, g->s1, &s)) {
    z[0] = st;
    z[1] = s;
    return 0;
  }
  for (int k = 0; k < 2; k++) { /* xi = k: parallel circle th = t_k */
    const double tk = k ? g->t1 : g->t0;
    for (int i = 0; i < 3; i++) m[i] = g->c[i] + g->R * cos(tk) * g->a[i];
    {
      const double d2 = ArcClosest(m, g->e, f, g->R * sin(tk), g->s0, g->s1, y, &s);
      EdgeTry(d2, k, s, &best, z);
    }
  }
  for (int k = 0; k < 2; k++) { /* eta = k: meridian ph = s_k, th measured from a towards w */
    Radial(g, k ? g->s1 : g->s0, w, wp);
    {
      const double d2 = ArcClosest(g->c, g->a, w, g->R, g->t0, g->t1, y, &s);
      EdgeTry(d2, s, k, &best, z);
    }
  }
  return 0;
}

static void SphereNormalDz(const Patch *p, double s, const double z[2], const double xu[3], const double xv[3], double nu[3], double nv[3])
{
  for (int i = 0; i < 3; i++) {
    nu[i] = s * xu[i] / p->rev.R;
    nv[i] = s * xv[i] / p->rev.R;
  }
}

/* interior: s (I - n n)/|y - c| */
static int SphereNormalDerivative(const Patch *p, const double shift[3], const double y[3], const Projection *pr, double dn[9])
{
  const double s = RevolutionSign(p);
  double       d[3], m[3];
  for (int i = 0; i < 3; i++) d[i] = y[i] - shift[i] - p->rev.c[i];
  if (!pr->interior) return RevolutionEdgeNormalDerivative(p, shift, y, pr, s, SphereNormalDz, dn);
  const double l = Norm(d);
  if (!(l > 0.0)) return 0;
  for (int i = 0; i < 3; i++) m[i] = d[i] / l;
  for (int i = 0; i < 3; i++)
    for (int j = 0; j < 3; j++) dn[3 * i + j] = s * ((i == j) - m[i] * m[j]) / l;
  return 0;
}

static PetscErrorCode SphereSetFromOptions(PetscOptionItems *PetscOptionsObject, Patch *p, const char stem[])
{
  RevolutionData *g      = &p->rev;
  const PetscBool deg[2] = {PETSC_TRUE, PETSC_TRUE};
  double          r[4]   = {0, 0, 0, 0};
  char            opt[PETSC_MAX_PATH_LEN], full[PETSC_MAX_PATH_LEN];

  PetscFunctionBeginUser;
  PetscOptionsHeadBegin(PetscOptionsObject, "Sphere patch");
  PetscCall(ToolOptionVec(PetscOptionsObject, stem, "center", "Sphere centre", g->c));
  PetscCall(ToolOptionPositive(PetscOptionsObject, stem, "radius", "Sphere radius", &g->R));
  PetscCall(RevolutionFrameFromOptions(PetscOptionsObject, stem, g->a, g->e));
  PetscCall(ToolOptionRange(PetscOptionsObject, stem, "Polar angle from the axis th0,th1 and azimuth from ref ph0,ph1 (degrees)", deg, r));
  PetscCall(PetscSNPrintf(opt, sizeof(opt), "%s_range", stem));
  PetscCall(ToolOptionFullName(PetscOptionsObject, opt, full, sizeof(full)));
  PetscCheck(r[0] >= 0 && r[1] <= TOOL_PI * (1 + 1e-15), PetscOptionsObject->comm, PETSC_ERR_USER_INPUT, "%s: polar angles %g to %g must lie in [0, 180] degrees", full, r[0] * 180 / TOOL_PI, r[1] * 180 / TOOL_PI);
  g->t0 = r[0];
  g->t1 = fmin(r[1], TOOL_PI);
  g->s0 = r[2];
  g->s1 = r[3];
  PetscFunctionReturn(0);
}

static PetscErrorCode SphereView(const Patch *p, PetscViewer v)
{
  char            what[64];
  const PetscBool deg[2] = {PETSC_TRUE, PETSC_TRUE};
  PetscFunctionBeginUser;
  PetscCall(PetscSNPrintf(what, sizeof(what), "radius %g", p->rev.R));
  PetscCall(RevolutionView(p, v, what, deg));
  PetscFunctionReturn(0);
}

static const PatchOps SphereOps = {
  .type             = "sphere",
  .eval             = SphereEval,
  .normal           = SphereNormal,
  .scale            = SphereScale,
  .start            = SphereStart,
  .normalderivative = SphereNormalDerivative,
  .setfromoptions   = SphereSetFromOptions,
  .view             = SphereView,
};

PetscErrorCode PatchCreate_Sphere(Patch *p)
{
  PetscFunctionBeginUser;
  p->ops = &SphereOps;
  PetscFunctionReturn(0);
}
