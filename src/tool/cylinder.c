/* Patch type "cylinder": x = c + R w(ph) + z a, azimuth ph = t0 + xi (t1 - t0) from e, height
   z = s0 + eta (s1 - s0) along the axis a from the axis point c (frames: revolution.c) */
#include "toolimpl.h"

#include "options.h"

static void CylinderEval(const Patch *p, double xi, double eta, double x[3], double xu[3], double xv[3], double *xuu, double *xuv, double *xvv)
{
  const RevolutionData *g  = &p->rev;
  const double          dt = g->t1 - g->t0, ds = g->s1 - g->s0;
  double                w[3], wp[3], q[3] = {0, 0, 0}, quv[3] = {0, 0, 0}, qvv[3] = {0, 0, 0};
  const double          z = g->s0 + eta * ds;
  Radial(g, g->t0 + xi * dt, w, wp);
  for (int i = 0; i < 3; i++) {
    x[i]  = g->c[i] + g->R * w[i] + z * g->a[i];
    xu[i] = g->R * dt * wp[i];
    xv[i] = ds * g->a[i];
    q[i]  = -g->R * dt * dt * w[i];
  }
  for (int i = 0; i < 3; i++) {
    if (xuu) xuu[i] = q[i];
    if (xuv) xuv[i] = quv[i];
    if (xvv) xvv[i] = qvv[i];
  }
}

/* x_xi x x_eta = R dt ds w(ph) */
static double CylinderNormal(const Patch *p, double xi, double eta, double n[3])
{
  const RevolutionData *g  = &p->rev;
  const double          dt = g->t1 - g->t0, ds = g->s1 - g->s0;
  double                wp[3], s = SenseSign(p), J;
  Radial(g, g->t0 + xi * dt, n, wp);
  s *= Sgn(dt * ds);
  J = g->R * fabs(dt * ds);
  for (int i = 0; i < 3; i++) n[i] *= s;
  return J;
}

static double CylinderScale(const Patch *p) { return p->rev.R + fabs(p->rev.s1 - p->rev.s0); }

/* Lower bound: the distance to the finite full cylinder. Start: separable, the azimuth on the
   circle (ArcClosest), the height clamped. */
static int CylinderStart(const Patch *p, const double y[3], double maxdist, double z[2])
{
  const RevolutionData *g = &p->rev;
  double                d[3], f[3], h, rho2, dz, lb, s = 0.5;
  for (int i = 0; i < 3; i++) d[i] = y[i] - g->c[i];
  h    = Dot(d, g->a);
  rho2 = fmax(Dot(d, d) - h * h, 0.0);
  dz   = fmax(0.0, fmax(fmin(g->s0, g->s1) - h, h - fmax(g->s0, g->s1)));
  lb   = hypot(sqrt(rho2) - g->R, dz);
  if (lb > maxdist) return 1;
  Cross(g->a, g->e, f);
  ArcClosest(g->c, g->e, f, g->R, g->t0, g->t1, y, &s);
  z[0] = s;
  z[1] = Clamp01(((y[0] - g->c[0]) * g->a[0] + (y[1] - g->c[1]) * g->a[1] + (y[2] - g->c[2]) * g->a[2] - g->s0) / (g->s1 - g->s0));
  return 0;
}

static void CylinderNormalDz(const Patch *p, double s, const double z[2], const double xu[3], const double xv[3], double nu[3], double nv[3])
{
  for (int i = 0; i < 3; i++) nu[i] = s * xu[i] / p->rev.R;
}

/* interior: s (I - a a - n n)/rho, rho the distance of y to the axis */
static int CylinderNormalDerivative(const Patch *p, const double shift[3], const double y[3], const Projection *pr, double dn[9])
{
  const double s = RevolutionSign(p);
  double       d[3], m[3], P[9], rho;
  for (int i = 0; i < 3; i++) d[i] = y[i] - shift[i] - p->rev.c[i];
  if (!pr->interior) return RevolutionEdgeNormalDerivative(p, shift, y, pr, s, CylinderNormalDz, dn);
  if (!RevolutionAxial(&p->rev, d, m, P, &rho)) return 0;
  for (int i = 0; i < 9; i++) dn[i] = s * P[i] / rho;
  return 0;
}

static PetscErrorCode CylinderSetFromOptions(PetscOptionItems *PetscOptionsObject, Patch *p, const char stem[])
{
  RevolutionData *g      = &p->rev;
  const PetscBool deg[2] = {PETSC_TRUE, PETSC_FALSE};
  double          r[4]   = {0, 0, 0, 0};

  PetscFunctionBeginUser;
  PetscOptionsHeadBegin(PetscOptionsObject, "Cylinder patch");
  PetscCall(ToolOptionVec(PetscOptionsObject, stem, "center", "A point of the axis (height 0)", g->c));
  PetscCall(RevolutionFrameFromOptions(PetscOptionsObject, stem, g->a, g->e));
  PetscCall(ToolOptionPositive(PetscOptionsObject, stem, "radius", "Cylinder radius", &g->R));
  PetscCall(ToolOptionRange(PetscOptionsObject, stem, "Azimuth from ref ph0,ph1 (degrees) and height along the axis z0,z1", deg, r));
  g->t0 = r[0];
  g->t1 = r[1];
  g->s0 = r[2];
  g->s1 = r[3];
  PetscFunctionReturn(0);
}

static PetscErrorCode CylinderView(const Patch *p, PetscViewer v)
{
  char            what[64];
  const PetscBool deg[2] = {PETSC_TRUE, PETSC_FALSE};
  PetscFunctionBeginUser;
  PetscCall(PetscSNPrintf(what, sizeof(what), "radius %g", p->rev.R));
  PetscCall(RevolutionView(p, v, what, deg));
  PetscFunctionReturn(0);
}

static const PatchOps CylinderOps = {
  .type             = "cylinder",
  .eval             = CylinderEval,
  .normal           = CylinderNormal,
  .scale            = CylinderScale,
  .start            = CylinderStart,
  .normalderivative = CylinderNormalDerivative,
  .setfromoptions   = CylinderSetFromOptions,
  .view             = CylinderView,
};

PetscErrorCode PatchCreate_Cylinder(Patch *p)
{
  PetscFunctionBeginUser;
  p->ops = &CylinderOps;
  PetscFunctionReturn(0);
}
