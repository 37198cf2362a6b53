/* Patch type "plane": x = o + u e1 + v e2, u = u0 + xi (u1 - u0), v = v0 + eta (v1 - v0), e1 and
   e2 orthonormal. Its closest point is exact (the problem separates). */
#include "toolimpl.h"

#include "options.h"

static void PlaneEval(const Patch *p, double xi, double eta, double x[3], double xu[3], double xv[3], double *xuu, double *xuv, double *xvv)
{
  const PlaneData *g  = &p->plane;
  const double     du = g->u1 - g->u0, dv = g->v1 - g->v0, u = g->u0 + xi * du, v = g->v0 + eta * dv;
  for (int i = 0; i < 3; i++) {
    x[i]  = g->o[i] + u * g->e1[i] + v * g->e2[i];
    xu[i] = du * g->e1[i];
    xv[i] = dv * g->e2[i];
  }
  for (int i = 0; i < 3; i++) {
    if (xuu) xuu[i] = 0.0;
    if (xuv) xuv[i] = 0.0;
    if (xvv) xvv[i] = 0.0;
  }
}

/* x_xi x x_eta = du dv e1 x e2 */
static double PlaneNormal(const Patch *p, double xi, double eta, double n[3])
{
  const PlaneData *g   = &p->plane;
  const double     duv = (g->u1 - g->u0) * (g->v1 - g->v0);
  double           s   = SenseSign(p), J;
  Cross(g->e1, g->e2, n);
  s *= Sgn(duv);
  J = fabs(duv);
  for (int i = 0; i < 3; i++) n[i] *= s;
  return J;
}

static double PlaneScale(const Patch *p) { return fabs(p->plane.u1 - p->plane.u0) + fabs(p->plane.v1 - p->plane.v0); }

/* exact: separable, each parameter clamped; skipped if the distance to the plane exceeds maxdist */
static int PlaneClosest(const Patch *p, const double y[3], double maxdist, double L, PatchCandidate *c)
{
  const PlaneData *g = &p->plane;
  double           z[2], d[3], n[3], xu[3], xv[3], gr[2];
  for (int i = 0; i < 3; i++) d[i] = y[i] - g->o[i];
  Cross(g->e1, g->e2, n);
  if (fabs(Dot(d, n)) > maxdist) return 1;
  z[0] = Clamp01((Dot(d, g->e1) - g->u0) / (g->u1 - g->u0));
  z[1] = Clamp01((Dot(d, g->e2) - g->v0) / (g->v1 - g->v0));
  PatchEval(p, z[0], z[1], c->x, xu, xv, NULL, NULL, NULL);
  c->xi  = z[0];
  c->eta = z[1];
  c->d2  = Dist2(c->x, y);
  for (int i = 0; i < 3; i++) d[i] = c->x[i] - y[i];
  gr[0]       = Dot(d, xu);
  gr[1]       = Dot(d, xv);
  c->interior = !(((z[0] <= 0.0 || z[0] >= 1.0) && fabs(gr[0]) > 1e-10 * L * Norm(xu)) || ((z[1] <= 0.0 || z[1] >= 1.0) && fabs(gr[1]) > 1e-10 * L * Norm(xv)));
  return 0;
}

static PetscErrorCode PlaneSetFromOptions(PetscOptionItems *PetscOptionsObject, Patch *p, const char stem[])
{
  PlaneData      *g      = &p->plane;
  const MPI_Comm  comm   = PetscOptionsObject->comm;
  const PetscBool deg[2] = {PETSC_FALSE, PETSC_FALSE};
  double          n1, n2, pr, r[4] = {0, 0, 0, 0}, e2[3] = {0, 0, 0};
  char            opt[PETSC_MAX_PATH_LEN], f1[PETSC_MAX_PATH_LEN], f2[PETSC_MAX_PATH_LEN];

  PetscFunctionBeginUser;
  PetscOptionsHeadBegin(PetscOptionsObject, "Plane patch");
  PetscCall(PetscSNPrintf(opt, sizeof(opt), "%s_e1", stem));
  PetscCall(ToolOptionFullName(PetscOptionsObject, opt, f1, sizeof(f1)));
  PetscCall(PetscSNPrintf(opt, sizeof(opt), "%s_e2", stem));
  PetscCall(ToolOptionFullName(PetscOptionsObject, opt, f2, sizeof(f2)));
  PetscCall(ToolOptionVec(PetscOptionsObject, stem, "origin", "Origin o of the plane's coordinates", g->o));
  PetscCall(ToolOptionVec(PetscOptionsObject, stem, "e1", "First in-plane direction (normalised)", g->e1));
  PetscCall(ToolOptionVec(PetscOptionsObject, stem, "e2", "Second in-plane direction (orthonormalised against e1)", e2));
  n1 = Norm(g->e1);
  PetscCheck(n1 > 0, comm, PETSC_ERR_USER_INPUT, "%s %g,%g,%g: zero vector", f1, g->e1[0], g->e1[1], g->e1[2]);
  for (int i = 0; i < 3; i++) g->e1[i] /= n1;
  pr = Dot(e2, g->e1);
  for (int i = 0; i < 3; i++) g->e2[i] = e2[i] - pr * g->e1[i];
  n2 = Norm(g->e2);
  PetscCheck(n2 > 1e-10 * Norm(e2) && n2 > 0, comm, PETSC_ERR_USER_INPUT, "%s %g,%g,%g: zero or parallel to %s", f2, e2[0], e2[1], e2[2], f1);
  for (int i = 0; i < 3; i++) g->e2[i] /= n2;
  PetscCall(ToolOptionRange(PetscOptionsObject, stem, "Coordinates along e1 u0,u1 and along e2 v0,v1 (lengths)", deg, r));
  g->u0 = r[0];
  g->u1 = r[1];
  g->v0 = r[2];
  g->v1 = r[3];
  PetscFunctionReturn(0);
}

static PetscErrorCode PlaneView(const Patch *p, PetscViewer v)
{
  const PlaneData *g = &p->plane;
  PetscFunctionBeginUser;
  PetscCall(PetscViewerASCIIPrintf(v, "%s, sense %d: origin %g,%g,%g, e1 %g,%g,%g, e2 %g,%g,%g, range %g,%g,%g,%g\n", PatchGetType(p), p->sense, g->o[0], g->o[1], g->o[2], g->e1[0], g->e1[1], g->e1[2], g->e2[0], g->e2[1], g->e2[2], g->u0, g->u1, g->v0, g->v1));
  PetscFunctionReturn(0);
}

static const PatchOps PlaneOps = {
  .type           = "plane",
  .eval           = PlaneEval,
  .normal         = PlaneNormal,
  .scale          = PlaneScale,
  .closest        = PlaneClosest,
  .setfromoptions = PlaneSetFromOptions,
  .view           = PlaneView,
};

PetscErrorCode PatchCreate_Plane(Patch *p)
{
  PetscFunctionBeginUser;
  p->ops = &PlaneOps;
  PetscFunctionReturn(0);
}
