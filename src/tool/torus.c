/* Patch type "torus": x = c + (R + r cos ps) w(ph) + r sin ps a, azimuth ph = t0 + xi (t1 - t0)
   about the axis a, tube angle ps = s0 + eta (s1 - s0) (0 on the outer equator, +pi/2 towards +a);
   R from the centre to the tube's core circle, r the tube radius (frames: revolution.c).
   r >= R (a spindle torus: the tube crosses the axis) is accepted where the tube angle range keeps
   the distance from the axis R + r cos ps positive, the part outside the self-intersection (the
   corner blend of a punch whose plan corner radius is smaller than its profile radius): there the
   patch is a regular surface, and the radial projection about the core circle in the point's own
   meridian half-plane is its nearest point as for r < R. */
#include "toolimpl.h"

#include "options.h"

static void TorusEval(const Patch *p, double xi, double eta, double x[3], double xu[3], double xv[3], double *xuu, double *xuv, double *xvv)
{
  const RevolutionData *g  = &p->rev;
  const double          dt = g->t1 - g->t0, ds = g->s1 - g->s0;
  double                w[3], wp[3], q[3] = {0, 0, 0}, quv[3] = {0, 0, 0}, qvv[3] = {0, 0, 0};
  const double          ps = g->s0 + eta * ds, cp = cos(ps), sp = sin(ps), r = g->r, rho = g->R + r * cp;
  Radial(g, g->t0 + xi * dt, w, wp);
  for (int i = 0; i < 3; i++) {
    x[i]   = g->c[i] + rho * w[i] + r * sp * g->a[i];
    xu[i]  = dt * rho * wp[i];
    xv[i]  = ds * r * (-sp * w[i] + cp * g->a[i]);
    q[i]   = -dt * dt * rho * w[i];
    quv[i] = -dt * ds * r * sp * wp[i];
    qvv[i] = -ds * ds * r * (cp * w[i] + sp * g->a[i]);
  }
  for (int i = 0; i < 3; i++) {
    if (xuu) xuu[i] = q[i];
    if (xuv) xuv[i] = quv[i];
    if (xvv) xvv[i] = qvv[i];
  }
}

/* x_xi x x_eta = dt ds r (R + r cos ps) (cos ps w + sin ps a) */
static double TorusNormal(const Patch *p, double xi, double eta, double n[3])
{
  const RevolutionData *g  = &p->rev;
  const double          dt = g->t1 - g->t0, ds = g->s1 - g->s0;
  double                w[3], wp[3], s = SenseSign(p), J;
  const double          ps = g->s0 + eta * ds, cp = cos(ps), sp = sin(ps);
  Radial(g, g->t0 + xi * dt, w, wp);
  for (int i = 0; i < 3; i++) n[i] = cp * w[i] + sp * g->a[i];
  s *= Sgn(dt * ds);
  J = g->r * fabs(dt * ds * (g->R + g->r * cp));
  for (int i = 0; i < 3; i++) n[i] *= s;
  return J;
}

static double TorusScale(const Patch *p) { return p->rev.R + p->rev.r; }

/* Lower bound: the distance to the full torus. Start: the radial projection (azimuth, and the
   tube angle about the core circle), the only local minimum of the distance to the full torus; if
   it falls outside the range, the best point of the four edges (circular arcs, exact) */
static int TorusStart(const Patch *p, const double y[3], double maxdist, double z[2])
{
  const RevolutionData *g = &p->rev;
  double                d[3], f[3], h, pe, pf, rho, ph, ps, sp, sph, best = HUGE_VAL, w[3], wp[3], m[3], s = 0.5, lb;
  for (int i = 0; i < 3; i++) d[i] = y[i] - g->c[i];
  h   = Dot(d, g->a);
  rho = sqrt(fmax(Dot(d, d) - h * h, 0.0));
  lb  = fabs(hypot(rho - g->R, h) - g->r);
  if (lb > maxdist) return 1;
  Cross(g->a, g->e, f);
  for (int i = 0; i < 3; i++) d[i] = y[i] - g->c[i];
  h   = Dot(d, g->a);
  pe  = Dot(d, g->e);
  pf  = Dot(d, f);
  rho = hypot(pe, pf);
  ph  = atan2(pf, pe);
  ps  = atan2(h, rho - g->R); /* in the meridian plane, about the tube's core */
  if (AngleParam(ph, g->t0, g->t1, &sph) && AngleParam(ps, g->s0, g->s1, &sp)) {
    z[0] = sph;
    z[1] = sp;
    return 0;
  }
  for (int k = 0; k < 2; k++) { /* xi = k: tube circle at ph = t_k */
    Radial(g, k ? g->t1 : g->t0, w, wp);
    for (int i = 0; i < 3; i++) m[i] = g->c[i] + g->R * w[i];
    {
      const double d2 = ArcClosest(m, w, g->a, g->r, g->s0, g->s1, y, &s);
      EdgeTry(d2, k, s, &best, z);
    }
  }
  for (int k = 0; k < 2; k++) { /* eta = k: parallel circle ps = s_k */
    const double pk = k ? g->s1 : g->s0;
    for (int i = 0; i < 3; i++) m[i] = g->c[i] + g->r * sin(pk) * g->a[i];
    {
      const double d2 = ArcClosest(m, g->e, f, g->R + g->r * cos(pk), g->t0, g->t1, y, &s);
      EdgeTry(d2, s, k, &best, z);
    }
  }
  return 0;
}

static void TorusNormalDz(const Patch *p, double s, const double z[2], const double xu[3], const double xv[3], double nu[3], double nv[3])
{
  const RevolutionData *g  = &p->rev;
  const double          dt = g->t1 - g->t0, ds = g->s1 - g->s0, ps = g->s0 + z[1] * ds;
  double                w[3], wp[3];
  Radial(g, g->t0 + z[0] * dt, w, wp);
  for (int i = 0; i < 3; i++) {
    nu[i] = s * dt * cos(ps) * wp[i];
    nv[i] = s * xv[i] / g->r;
  }
}

/* interior: u = y - q, q = c + R w the nearest point of the core circle, dq/dy = R (I - a a - w w)/rho;
   dn/dy = s (I - n n)(I - dq/dy)/|u| */
static int TorusNormalDerivative(const Patch *p, const double shift[3], const double y[3], const Projection *pr, double dn[9])
{
  const double s = RevolutionSign(p);
  double       d[3], m[3], P[9], rho, u[3], l, A[9];
  for (int i = 0; i < 3; i++) d[i] = y[i] - shift[i] - p->rev.c[i];
  if (!pr->interior) return RevolutionEdgeNormalDerivative(p, shift, y, pr, s, TorusNormalDz, dn);
  if (!RevolutionAxial(&p->rev, d, m, P, &rho)) return 0;
  for (int i = 0; i < 3; i++) u[i] = d[i] - p->rev.R * m[i];
  l = Norm(u);
  if (!(l > 0.0)) return 0;
  for (int i = 0; i < 3; i++) u[i] /= l;
  for (int i = 0; i < 9; i++) A[i] = ((i % 4) == 0) - p->rev.R * P[i] / rho;
  for (int i = 0; i < 3; i++)
    for (int j = 0; j < 3; j++) {
      double v = 0.0;
      for (int k = 0; k < 3; k++) v += ((i == k) - u[i] * u[k]) * A[3 * k + j];
      dn[3 * i + j] = s * v / l;
    }
  return 0;
}

static PetscErrorCode TorusSetFromOptions(PetscOptionItems *PetscOptionsObject, Patch *p, const char stem[])
{
  RevolutionData *g      = &p->rev;
  const PetscBool deg[2] = {PETSC_TRUE, PETSC_TRUE};
  double          r[4]   = {0, 0, 0, 0};
  char            opt[PETSC_MAX_PATH_LEN], fmin_[PETSC_MAX_PATH_LEN], fmaj[PETSC_MAX_PATH_LEN];

  PetscFunctionBeginUser;
  PetscOptionsHeadBegin(PetscOptionsObject, "Torus patch");
  PetscCall(ToolOptionVec(PetscOptionsObject, stem, "center", "Torus centre", g->c));
  PetscCall(RevolutionFrameFromOptions(PetscOptionsObject, stem, g->a, g->e));
  PetscCall(ToolOptionPositive(PetscOptionsObject, stem, "major", "Major radius R (centre to the tube's core circle)", &g->R));
  PetscCall(ToolOptionPositive(PetscOptionsObject, stem, "minor", "Minor radius r (tube); r >= R only where the tube angle range keeps R + r cos(ps) > 0", &g->r));
  PetscCall(PetscSNPrintf(opt, sizeof(opt), "%s_minor", stem));
  PetscCall(ToolOptionFullName(PetscOptionsObject, opt, fmin_, sizeof(fmin_)));
  PetscCall(PetscSNPrintf(opt, sizeof(opt), "%s_major", stem));
  PetscCall(ToolOptionFullName(PetscOptionsObject, opt, fmaj, sizeof(fmaj)));
  PetscCall(ToolOptionRange(PetscOptionsObject, stem, "Azimuth about the axis ph0,ph1 and tube angle ps0,ps1 (degrees)", deg, r));
  g->t0 = r[0];
  g->t1 = r[1];
  g->s0 = r[2];
  g->s1 = r[3];
  if (g->r >= g->R) {
    /* the smallest distance from the axis over the tube angle range: at pi (mod 2 pi) if the range
       holds it, else at an end */
    const double lo = fmin(g->s0, g->s1), hi = fmax(g->s0, g->s1), k = ceil((lo - TOOL_PI) / (2 * TOOL_PI));
    const double cmin = (TOOL_PI + 2 * TOOL_PI * k <= hi) ? -1.0 : fmin(cos(lo), cos(hi));
    PetscCheck(g->R + g->r * cmin > 1e-9 * (g->R + g->r), PetscOptionsObject->comm, PETSC_ERR_USER_INPUT, "%s %g >= %s %g: the tube angle range %g,%g must keep R + r cos(ps) > 0 (the part of the spindle torus outside its self-intersection)", fmin_, g->r, fmaj, g->R, r[2] * 180.0 / TOOL_PI, r[3] * 180.0 / TOOL_PI);
  }
  PetscFunctionReturn(0);
}

static PetscErrorCode TorusView(const Patch *p, PetscViewer v)
{
  char            what[96];
  const PetscBool deg[2] = {PETSC_TRUE, PETSC_TRUE};
  PetscFunctionBeginUser;
  PetscCall(PetscSNPrintf(what, sizeof(what), "major %g, minor %g", p->rev.R, p->rev.r));
  PetscCall(RevolutionView(p, v, what, deg));
  PetscFunctionReturn(0);
}

static const PatchOps TorusOps = {
  .type             = "torus",
  .eval             = TorusEval,
  .normal           = TorusNormal,
  .scale            = TorusScale,
  .start            = TorusStart,
  .normalderivative = TorusNormalDerivative,
  .setfromoptions   = TorusSetFromOptions,
  .view             = TorusView,
};

PetscErrorCode PatchCreate_Torus(Patch *p)
{
  PetscFunctionBeginUser;
  p->ops = &TorusOps;
  PetscFunctionReturn(0);
}
