/* Rigid tools: the Tool object (its patches, motion, bounding boxes), the closest-point projection
   of a point on a tool, the patch-type registry and dispatch, and the options that build the tools
   (doc/tools.md).

   Patch types live behind operation tables (PatchOps, toolimpl.h), one file per type: plane.c,
   sphere.c, cylinder.c, torus.c (these three share revolution.c), coons.c. Adding a patch type
   (e.g. a meshed surface read from a file) is exactly: one new file src/tool/<type>.c defining
   its static PatchOps table and PetscErrorCode PatchCreate_<Type>(Patch *), plus one registration
   line PATCH_TYPE("<type>", PatchCreate_<Type>) in PatchRegisterAll() (register.c). Nothing in
   this file switches on the type. */
#include "facets.h"

#include <float.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "options.h"

/* ------------------------------------------------------------------------------------------ */
/* registry and dispatch                                                                        */
/* ------------------------------------------------------------------------------------------ */

static PetscFunctionList PatchList = NULL;

static PetscErrorCode PatchFinalizePackage(void)
{
  PetscFunctionBeginUser;
  PetscCall(PetscFunctionListDestroy(&PatchList));
  PetscFunctionReturn(0);
}

PetscErrorCode PatchRegister(const char name[], PetscErrorCode (*create)(Patch *))
{
  PetscFunctionBeginUser;
  if (!PatchList) PetscCall(PetscRegisterFinalize(PatchFinalizePackage));
  PetscCall(PetscFunctionListAdd(&PatchList, name, create));
  PetscFunctionReturn(0);
}

/* the create function of a type name (NULL if unknown) */
static PetscErrorCode PatchFind(const char type[], PetscErrorCode (**create)(Patch *))
{
  PetscFunctionBeginUser;
  PetscCall(PatchRegisterAll());
  PetscCall(PetscFunctionListFind(PatchList, type, create));
  PetscFunctionReturn(0);
}

PetscErrorCode PatchSetType(Patch *p, const char type[])
{
  PetscErrorCode (*create)(Patch *) = NULL;

  PetscFunctionBeginUser;
  PetscCall(PatchFind(type, &create));
  PetscCheck(create, PETSC_COMM_SELF, PETSC_ERR_ARG_UNKNOWN_TYPE, "unknown patch type '%s'", type);
  PetscCall(PetscMemzero(p, sizeof(*p)));
  p->sense = 1;
  PetscCall((*create)(p));
  PetscFunctionReturn(0);
}

const char *PatchGetType(const Patch *p) { return p->ops ? p->ops->type : ""; }

PetscErrorCode PatchPrepare(Patch *p)
{
  PetscFunctionBeginUser;
  if (p->ops && p->ops->prepare) PetscCall(p->ops->prepare(p));
  PetscFunctionReturn(0);
}

PetscErrorCode PatchDestroy(Patch *p)
{
  PetscFunctionBeginUser;
  if (p->ops && p->ops->destroy) PetscCall(p->ops->destroy(p));
  p->data = NULL;
  PetscFunctionReturn(0);
}

PetscErrorCode PatchView(const Patch *p, PetscViewer v)
{
  PetscFunctionBeginUser;
  if (p->ops) PetscCall(p->ops->view(p, v));
  else PetscCall(PetscViewerASCIIPrintf(v, "patch without a type\n"));
  PetscFunctionReturn(0);
}

void PatchEval(const Patch *p, double xi, double eta, double x[3], double xu[3], double xv[3], double *xuu, double *xuv, double *xvv) { p->ops->eval(p, xi, eta, x, xu, xv, xuu, xuv, xvv); }

double PatchNormal(const Patch *p, double xi, double eta, double n[3]) { return p->ops->normal(p, xi, eta, n); }

/* a characteristic length of the patch (tolerances) */
static double PatchScale(const Patch *p)
{
  const double L = p->ops->scale ? p->ops->scale(p) : 0.0;
  return L > 0.0 ? L : 1.0;
}

/* dn/dy (the types: plane 0; sphere, cylinder, torus in closed form at interior projections, from
   the stationarity on an edge; Coons from the second derivatives) */
int PatchNormalDerivative(const Patch *p, const double shift[3], const double y[3], const Projection *pr, double dn[9])
{
  for (int i = 0; i < 9; i++) dn[i] = 0.0;
  return p->ops->normalderivative ? p->ops->normalderivative(p, shift, y, pr, dn) : 0;
}

/* ------------------------------------------------------------------------------------------ */
/* projection                                                                                   */
/* ------------------------------------------------------------------------------------------ */

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

/* PatchEval, or the type's own evaluation with its context */
static inline void Eval(const Patch *p, PatchEvalFn eval, const void *ctx, double u, double v, double x[3], double xu[3], double xv[3], double *xuu, double *xuv, double *xvv)
{
  if (eval) eval(p, ctx, u, v, x, xu, xv, xuu, xuv, xvv);
  else PatchEval(p, u, v, x, xu, xv, xuu, xuv, xvv);
}

/* Projected Newton on f = |x(xi,eta) - y|^2 / 2 over [0,1]^2 from z: gradient g_i = (x - y).x_i,
   Hessian H_ij = x_i.x_j + (x - y).x_ij. A parameter at a bound whose gradient points out of the
   square is held (the 1D problem on that edge, or the corner); steps are clamped to the square and
   backtracked (Armijo); if that fails the Gauss-Newton, then the scaled gradient direction is
   tried. Stops when the step is below 1e-12 in the parameters (or 1e-13 L in space). */
void PatchMinimize(const Patch *p, PatchEvalFn eval, const void *ctx, const double y[3], double L, double z[2], PatchCandidate *c)
{
  double x[3], xu[3], xv[3], xuu[3], xuv[3], xvv[3], r[3], f, g[2] = {0, 0};
  int    mode = 0;
  Eval(p, eval, ctx, z[0], z[1], x, xu, xv, xuu, xuv, xvv);
  for (int i = 0; i < 3; i++) r[i] = x[i] - y[i];
  f = 0.5 * Dot(r, r);
  for (int it = 0; it < 100; it++) {
    double G[3], H[3], d[2], dx[3], alpha = 1.0, zn[2] = {z[0], z[1]}, noise;
    double xn[3], xun[3], xvn[3], xuun[3], xuvn[3], xvvn[3], rn[3], fn = f;
    int    fr[2], ok = 0;
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
      Eval(p, eval, ctx, zn[0], zn[1], xn, xun, xvn, xuun, xuvn, xvvn);
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
  g[0]   = Dot(r, xu);
  g[1]   = Dot(r, xv);
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

/* Closest point of y (reference frame) on one patch: the type's own search, or Newton from the
   type's start; returns 1 if skipped (lower bound of the distance above maxdist) */
static int PatchClosest(const Patch *p, const double y[3], double maxdist, PatchCandidate *c)
{
  const double L    = PatchScale(p);
  double       z[2] = {0.5, 0.5};
  if (p->ops->closest) return p->ops->closest(p, y, maxdist, L, c);
  if (p->ops->start && p->ops->start(p, y, maxdist, z)) return 1;
  PatchMinimize(p, NULL, NULL, y, L, z, c);
  return 0;
}

/* Closest point of y on one patch, with the parameters of an earlier projection on it as a hint
   (the types with a closesthint operation) */
static int PatchClosestHint(const Patch *p, const double y[3], double maxdist, const Projection *hint, PatchCandidate *c)
{
  if (p->ops->closesthint) return p->ops->closesthint(p, y, maxdist, PatchScale(p), hint->xi, hint->eta, c);
  return PatchClosest(p, y, maxdist, c);
}

static int ToolProjectImpl(const Tool *t, const double shift[3], const double y[3], double maxdist, const Projection *hint, Projection *pr);

int ToolProject(const Tool *t, const double shift[3], const double y[3], double maxdist, Projection *pr) { return ToolProjectImpl(t, shift, y, maxdist, NULL, pr); }

int ToolProjectHint(const Tool *t, const double shift[3], const double y[3], double maxdist, const Projection *hint, Projection *pr)
{
  if (hint && (hint->patch < 0 || hint->patch >= t->npatch)) hint = NULL;
  return ToolProjectImpl(t, shift, y, maxdist, hint, pr);
}

/* the projection of yr (reference frame) on candidate c of patch k: the point in the current
   position, the normal, the gap */
static void ProjectionSet(const Tool *t, int k, const PatchCandidate *c, const double yr[3], const double shift[3], Projection *pr)
{
  pr->patch    = k;
  pr->xi       = c->xi;
  pr->eta      = c->eta;
  pr->interior = c->interior;
  PatchNormal(&t->patch[k], c->xi, c->eta, pr->n);
  pr->gap = 0.0;
  for (int i = 0; i < 3; i++) {
    pr->x[i] = c->x[i] + shift[i];
    pr->gap += (yr[i] - c->x[i]) * pr->n[i];
  }
}

static int ToolProjectImpl(const Tool *t, const double shift[3], const double y[3], double maxdist, const Projection *hint, Projection *pr)
{
  double         yr[3], bd = 0.0, tol = 0.0;
  PatchCandidate bi = {0.0, 0.0, {0.0, 0.0, 0.0}, HUGE_VAL, 0}, ba = bi, c, best;
  int            ki = -1, ka = -1, kbest;

  if (t->absent) return 1; /* a tool absent in the current stage gives no point */
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
    if ((hint && hint->patch == k ? PatchClosestHint(&t->patch[k], yr, maxdist, hint, &c) : PatchClosest(&t->patch[k], yr, maxdist, &c)) || !(c.d2 >= 0.0)) continue; /* skipped, or not a number */
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
  ProjectionSet(t, kbest, &best, yr, shift, pr);
  /* held on a patch's boundary with y beside it, in the tangent plane, by more than edge_tol and by
     more than it lies inside (the offset from the normal line through the point above both
     edge_tol and -gap): y is beside the tool, not over it or in it. Without the check the gap
     along the edge's normal presses a node anywhere beyond an open edge (a blank holder's plane
     pressing the sheet under the punch, 40 mm from the holder's inner edge). A node inside the
     tool by more than it is beside the edge is kept: the concave seam between two patches, where
     a penetrating node's closest point is the seam itself. */
  if (!best.interior && t->edge_tol > 0.0) {
    double o2 = 0.0;
    for (int i = 0; i < 3; i++) {
      const double o = yr[i] - best.x[i] - pr->gap * pr->n[i];
      o2 += o * o;
    }
    if (o2 > t->edge_tol * t->edge_tol && (pr->gap >= 0.0 || o2 > pr->gap * pr->gap)) {
      if (ki < 0) return 1;
      ProjectionSet(t, ki, &bi, yr, shift, pr);
    }
  }
  return 0;
}

/* The free parameters' derivatives dz/dy at a projection from the stationarity x_i.(x - y) = 0 of
   the free ones: H dz = x_i^T dy, H_ij = x_i.x_j + (x - y).x_ij. fr: which parameters are free.
   Returns 1 if H is not positive definite. */
int PatchProjectionParamDerivative(const double xu[3], const double xv[3], const double xuu[3], const double xuv[3], const double xvv[3], const double r[3], const int fr[2], double dz[2][3])
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

/* Bounding box of a patch: a 33 x 33 sample grid, enlarged by the interpolation error bound
   (|x_uu| h^2 + 2 |x_uv| h^2 + |x_vv| h^2)/8 (doubled) and 1e-9 of its size */
void PatchBoxSampled(const Patch *p, double b[6])
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

/* ------------------------------------------------------------------------------------------ */
/* motion                                                                                       */
/* ------------------------------------------------------------------------------------------ */

static double tool_total_time = 1.0; /* T of the default amplitude t/T (ToolsSetTotalTime) */

void ToolsSetTotalTime(double T) { tool_total_time = T > 0 ? T : 1.0; }

/* the amplitude of a tool's motion at time t: its curve, or the ramp t/T */
static double ToolAmplitude(const Tool *t, double time) { return t->amp.n > 0 ? (double)LoadCurveEval(&t->amp, time) : time / tool_total_time; }

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
  {
    const double a = ToolAmplitude(t, lambda);
    for (int i = 0; i < 3; i++) shift[i] = a * t->motion[i];
  }
}

double ToolTravel(const Tool *t, double lambda)
{
  double sh[3];
  if (t->npath > 0) { /* the pieces that ToolShift has passed, then the part of the current one */
    const double *P = t->path;
    double        s = 0.0;
    int           k = 0;
    while (k < t->npath - 1 && lambda > P[4 * (k + 1)]) {
      s += sqrt(Dist2(&P[4 * k + 1], &P[4 * (k + 1) + 1]));
      k++;
    }
    if (k == t->npath - 1) return s; /* held at the last point */
    ToolShift(t, lambda, sh);
    return s + sqrt(Dist2(sh, &P[4 * k + 1]));
  }
  if (t->amp.n > 0) { /* |motion| times the variation of the amplitude up to t */
    double s = 0.0, ap = ToolAmplitude(t, 0.0);
    for (PetscInt k = 0; k < t->amp.n && t->amp.t[k] < lambda; k++) {
      if (t->amp.t[k] <= 0) continue;
      const double a = ToolAmplitude(t, t->amp.t[k]);
      s += fabs(a - ap);
      ap = a;
    }
    s += fabs(ToolAmplitude(t, lambda) - ap);
    return s * Norm(t->motion);
  }
  ToolShift(t, lambda, sh);
  return Norm(sh);
}

double ToolNextKink(const Tool *t, double time)
{
  if (t->npath > 0) {
    for (int k = 0; k < t->npath; k++)
      if (t->path[4 * k] > time) return t->path[4 * k];
    return PETSC_INFINITY;
  }
  if (t->amp.n > 0) return (double)LoadCurveNextKink(&t->amp, time);
  return PETSC_INFINITY;
}

PetscErrorCode ToolView(const Tool *t, PetscViewer v)
{
  PetscBool isascii;

  PetscFunctionBeginUser;
  PetscCall(PetscObjectTypeCompare((PetscObject)v, PETSCVIEWERASCII, &isascii));
  if (!isascii) PetscFunctionReturn(0);
  PetscCall(PetscViewerASCIIPrintf(v, "Tool %s: %d patch%s, ", t->name, t->npatch, t->npatch == 1 ? "" : "es"));
  PetscCall(PetscViewerASCIIUseTabs(v, PETSC_FALSE));
  if (t->npath > 0) {
    PetscCall(PetscViewerASCIIPrintf(v, "path (load: shift)"));
    for (int k = 0; k < t->npath; k++) PetscCall(PetscViewerASCIIPrintf(v, "%s %g: %g,%g,%g", k ? "," : "", t->path[4 * k], t->path[4 * k + 1], t->path[4 * k + 2], t->path[4 * k + 3]));
  } else PetscCall(PetscViewerASCIIPrintf(v, "motion %g,%g,%g", t->motion[0], t->motion[1], t->motion[2]));
  PetscCall(PetscViewerASCIIPrintf(v, ", travel at load 1 %g, box [%g, %g] x [%g, %g] x [%g, %g]\n", ToolTravel(t, 1.0), t->bbox[0], t->bbox[1], t->bbox[2], t->bbox[3], t->bbox[4], t->bbox[5]));
  PetscCall(PetscViewerASCIIUseTabs(v, PETSC_TRUE));
  PetscCall(PetscViewerASCIIPushTab(v));
  for (int j = 0; j < t->npatch; j++) {
    PetscCall(PetscViewerASCIIPrintf(v, "patch %d: ", j));
    PetscCall(PetscViewerASCIIUseTabs(v, PETSC_FALSE));
    PetscCall(PatchView(&t->patch[j], v));
    PetscCall(PetscViewerASCIIUseTabs(v, PETSC_TRUE));
  }
  PetscCall(PetscViewerASCIIPopTab(v));
  PetscFunctionReturn(0);
}

/* ------------------------------------------------------------------------------------------ */
/* options                                                                                      */
/* ------------------------------------------------------------------------------------------ */

#define TOOL_MAX_TOOLS 64

PetscErrorCode ToolOptionFullName(PetscOptionItems *PetscOptionsObject, const char opt[], char full[], size_t len)
{
  PetscFunctionBeginUser;
  PetscCall(PetscSNPrintf(full, len, "-%s%s", PetscOptionsObject->prefix ? PetscOptionsObject->prefix : "", opt + 1));
  PetscFunctionReturn(0);
}

/* n reals of option opt; required or not (then *set says whether it was given) */
PetscErrorCode ToolOptionReals(PetscOptionItems *PetscOptionsObject, const char opt[], const char text[], PetscInt n, PetscReal v[], PetscBool required, PetscBool *set)
{
  const MPI_Comm comm = PetscOptionsObject->comm;
  char           full[PETSC_MAX_PATH_LEN];
  PetscReal      buf[16];
  PetscInt       cnt = 16; /* room for more, to report a surplus */
  PetscBool      flg;

  PetscFunctionBeginUser;
  PetscCall(ToolOptionFullName(PetscOptionsObject, opt, full, sizeof(full)));
  for (PetscInt i = 0; i < 16; i++) buf[i] = i < n ? v[i] : 0.0; /* the current values, for -help */
  PetscCall(PetscOptionsRealArray(opt, text, NULL, buf, &cnt, &flg));
  PetscCheck(flg || !required, comm, PETSC_ERR_USER_INPUT, "%s: missing required option (%" PetscInt_FMT " value%s)", full, n, n > 1 ? "s" : "");
  if (flg) {
    PetscCheck(cnt == n, comm, PETSC_ERR_USER_INPUT, "%s: needs %" PetscInt_FMT " value%s, got %" PetscInt_FMT, full, n, n > 1 ? "s" : "", cnt);
    for (PetscInt i = 0; i < n; i++) {
      PetscCheck(!PetscIsInfOrNanReal(buf[i]), comm, PETSC_ERR_USER_INPUT, "%s: value %g is not a finite number", full, (double)buf[i]);
      v[i] = buf[i];
    }
  }
  if (set) *set = flg;
  PetscFunctionReturn(0);
}

/* required vector stem_key */
PetscErrorCode ToolOptionVec(PetscOptionItems *PetscOptionsObject, const char stem[], const char key[], const char text[], double v[3])
{
  char      opt[PETSC_MAX_PATH_LEN];
  PetscReal b[3] = {v[0], v[1], v[2]};

  PetscFunctionBeginUser;
  PetscCall(PetscSNPrintf(opt, sizeof(opt), "%s_%s", stem, key));
  PetscCall(ToolOptionReals(PetscOptionsObject, opt, text, 3, b, PETSC_TRUE, NULL));
  for (int i = 0; i < 3; i++) v[i] = b[i];
  PetscFunctionReturn(0);
}

/* required positive real stem_key */
PetscErrorCode ToolOptionPositive(PetscOptionItems *PetscOptionsObject, const char stem[], const char key[], const char text[], double *v)
{
  char      opt[PETSC_MAX_PATH_LEN], full[PETSC_MAX_PATH_LEN];
  PetscReal b = 0;

  PetscFunctionBeginUser;
  PetscCall(PetscSNPrintf(opt, sizeof(opt), "%s_%s", stem, key));
  PetscCall(ToolOptionFullName(PetscOptionsObject, opt, full, sizeof(full)));
  PetscCall(ToolOptionReals(PetscOptionsObject, opt, text, 1, &b, PETSC_TRUE, NULL));
  PetscCheck(b > 0, PetscOptionsObject->comm, PETSC_ERR_USER_INPUT, "%s %g: must be > 0", full, (double)b);
  *v = b;
  PetscFunctionReturn(0);
}

PetscErrorCode ToolOptionRange(PetscOptionItems *PetscOptionsObject, const char stem[], const char text[], const PetscBool deg[2], double r[4])
{
  const MPI_Comm comm = PetscOptionsObject->comm;
  char           opt[PETSC_MAX_PATH_LEN], full[PETSC_MAX_PATH_LEN];
  PetscReal      b[4] = {0, 0, 0, 0};

  PetscFunctionBeginUser;
  PetscCall(PetscSNPrintf(opt, sizeof(opt), "%s_range", stem));
  PetscCall(ToolOptionFullName(PetscOptionsObject, opt, full, sizeof(full)));
  PetscCall(ToolOptionReals(PetscOptionsObject, opt, text, 4, b, PETSC_TRUE, NULL));
  for (int k = 0; k < 2; k++) {
    PetscCheck(b[2 * k] < b[2 * k + 1], comm, PETSC_ERR_USER_INPUT, "%s %g,%g,%g,%g: empty range (the %s value must exceed the %s)", full, (double)b[0], (double)b[1], (double)b[2], (double)b[3], k ? "fourth" : "second", k ? "third" : "first");
    if (deg[k]) PetscCheck(b[2 * k + 1] - b[2 * k] <= 360.0, comm, PETSC_ERR_USER_INPUT, "%s %g,%g,%g,%g: angular span %g exceeds 360 degrees", full, (double)b[0], (double)b[1], (double)b[2], (double)b[3], (double)(b[2 * k + 1] - b[2 * k]));
  }
  for (int k = 0; k < 4; k++) r[k] = deg[k / 2] ? b[k] * TOOL_PI / 180.0 : b[k];
  PetscFunctionReturn(0);
}

/* the registered type names as "a, b, c or d" */
static PetscErrorCode PatchTypeNames(char list[], size_t len)
{
  const char **names = NULL;
  int          n     = 0;
  size_t       l;

  PetscFunctionBeginUser;
  PetscCall(PatchRegisterAll());
  PetscCall(PetscFunctionListGet(PatchList, &names, &n));
  while (n > 0 && !names[n - 1]) n--; /* the array ends with NULL (counted) */
  list[0] = 0;
  for (int k = 0; k < n; k++) {
    PetscCall(PetscStrlen(list, &l));
    PetscCall(PetscSNPrintf(list + l, len - l, "%s%s", k == 0 ? "" : (k == n - 1 ? " or " : ", "), names[k]));
  }
  PetscCall(PetscFree(names));
  PetscFunctionReturn(0);
}

/* patch stem ("-patch<j>") of the tool whose options block is open: its type, sense and the
   type's own options */
static PetscErrorCode PatchSetFromOptions(PetscOptionItems *PetscOptionsObject, Patch *p, const char stem[])
{
  const MPI_Comm comm = PetscOptionsObject->comm;
  char           opt[PETSC_MAX_PATH_LEN], full[PETSC_MAX_PATH_LEN], typ[64] = "", types[256];
  PetscBool      flg;
  PetscInt       sense = 1;
  PetscErrorCode (*create)(Patch *) = NULL;

  PetscFunctionBeginUser;
  PetscCall(PatchTypeNames(types, sizeof(types)));
  PetscCall(PetscSNPrintf(opt, sizeof(opt), "%s_type", stem));
  PetscCall(ToolOptionFullName(PetscOptionsObject, opt, full, sizeof(full)));
  PetscCall(PetscOptionsFList(opt, "Patch type", "doc/tools.md", PatchList, typ, typ, sizeof(typ), &flg));
  PetscCheck(flg, comm, PETSC_ERR_USER_INPUT, "%s: missing required option (%s)", full, types);
  PetscCall(PatchFind(typ, &create));
  PetscCheck(create, comm, PETSC_ERR_USER_INPUT, "%s %s: unknown patch type (use %s)", full, typ, types);
  PetscCall(PatchSetType(p, typ));
  PetscCall(PetscSNPrintf(opt, sizeof(opt), "%s_sense", stem));
  PetscCall(ToolOptionFullName(PetscOptionsObject, opt, full, sizeof(full)));
  PetscCall(PetscOptionsInt(opt, "Orientation of the contact normal: 1 or -1 (out of the tool, towards the body)", NULL, sense, &sense, NULL));
  PetscCheck(sense == 1 || sense == -1, comm, PETSC_ERR_USER_INPUT, "%s %" PetscInt_FMT ": must be 1 or -1", full, sense);
  p->sense = (int)sense;
  PetscCall(p->ops->setfromoptions(PetscOptionsObject, p, stem));
  PetscFunctionReturn(0);
}

/* the options of tool t inside its block (prefix tool_<name>_): motion or path, the patches */
static PetscErrorCode ToolPatchesFromOptions(PetscOptionItems *PetscOptionsObject, Tool *t);

/* the options of tool t inside its block; *tfile = +-1 (flip) when its patches come from a tool
   file `file`, read afterwards */
static PetscErrorCode ToolSetFromOptions(PetscOptionItems *PetscOptionsObject, Tool *t, char file[], int *tfile)
{
  const MPI_Comm comm = PetscOptionsObject->comm;
  char           pre[PETSC_MAX_PATH_LEN], full[PETSC_MAX_PATH_LEN];
  PetscInt       cnt = 4 * 32;
  PetscReal      mo[3] = {0, 0, 0};
  PetscBool      flg, pset, fset;

  PetscFunctionBeginUser;
  PetscCall(PetscSNPrintf(pre, sizeof(pre), "-tool_%s", t->name));
  PetscCall(ToolOptionReals(PetscOptionsObject, "-motion", "Translation motion * a(t): at the end of the process with the default amplitude a(t) = t/T (default: fixed)", 3, mo, PETSC_FALSE, NULL));
  for (int i = 0; i < 3; i++) t->motion[i] = mo[i];
  {
    char      curve[PETSC_MAX_PATH_LEN] = "";
    PetscBool aset;
    PetscCall(ToolOptionFullName(PetscOptionsObject, "-amplitude", full, sizeof(full)));
    PetscCall(PetscOptionsString("-amplitude", "Amplitude a(t) of -motion, a curve of the process time: t0,a0,t1,a1,... or a file of (t, a) lines (default: t/T, T the total time)", "include/loadcurve.h", curve, curve, sizeof(curve), &aset));
    if (aset) PetscCall(LoadCurveParse(comm, full, curve, &t->amp));
  }
  /* piecewise-linear path: (load, dx, dy, dz) points */
  PetscCall(ToolOptionFullName(PetscOptionsObject, "-path", full, sizeof(full)));
  PetscCall(PetscOptionsRealArray("-path", "Instead of -motion: translation t0,dx,dy,dz,t1,... at process times 0 = t0 < t1 < ... (at most 32 points), linear in between", NULL, t->path, &cnt, &pset));
  if (pset) {
    PetscCheck(cnt >= 8 && cnt % 4 == 0, comm, PETSC_ERR_USER_INPUT, "%s: needs groups of 4 values (load, dx, dy, dz), at least 2 points and at most 32; got %" PetscInt_FMT " values", full, cnt);
    t->npath = (int)(cnt / 4);
    PetscCheck(t->path[0] == 0, comm, PETSC_ERR_USER_INPUT, "%s: the first point must be at time 0, not %g", full, (double)t->path[0]);
    for (int q = 0; q < cnt; q++) PetscCheck(!PetscIsInfOrNanReal(t->path[q]), comm, PETSC_ERR_USER_INPUT, "%s: value %g is not a finite number", full, (double)t->path[q]);
    for (int q = 1; q < t->npath; q++) PetscCheck(t->path[4 * q] > t->path[4 * (q - 1)], comm, PETSC_ERR_USER_INPUT, "%s: the times must increase (point %d at %g)", full, q, (double)t->path[4 * q]);
    PetscCheck(mo[0] == 0 && mo[1] == 0 && mo[2] == 0, comm, PETSC_ERR_USER_INPUT, "%s and %s_motion are exclusive", full, pre);
    PetscCheck(t->amp.n == 0, comm, PETSC_ERR_USER_INPUT, "%s and %s_amplitude are exclusive (the path's times are process times)", full, pre);
  }
  /* the surface from a file: a meshed surface (one facets patch), or a tool file of patches (read
     after this block, ToolsCreateFromOptions) */
  PetscCall(ToolOptionFullName(PetscOptionsObject, "-file", full, sizeof(full)));
  PetscCall(PetscOptionsString("-file", "The tool's surface from a file: .stl, .msh, .inp (a meshed surface) or .tool (patches)", "doc/tools.md", file, file, PETSC_MAX_PATH_LEN, &fset));
  if (fset) {
    char fmt[16] = "", f[16];
    PetscCall(PetscOptionsString("-file_format", "Format of -file: stl, msh, inp or tool (default: from the extension)", NULL, fmt, fmt, sizeof(fmt), NULL));
    FacetsFormat(file, fmt, f);
    PetscCall(PetscOptionsHasName(PetscOptionsObject->options, PetscOptionsObject->prefix, "-patches", &flg));
    PetscCheck(!flg, comm, PETSC_ERR_USER_INPUT, "%s and %s_patches are exclusive", full, pre);
    if (!strcmp(f, "tool")) {
      PetscBool flip = PETSC_FALSE;
      PetscCall(PetscOptionsBool("-flip", "Reverse the normals of the patches of the tool file", NULL, flip, &flip, NULL));
      *tfile = flip ? -1 : 1;
      PetscFunctionReturn(0);
    }
    PetscCall(PetscCalloc1(1, &t->patch));
    t->npatch = 1;
    PetscCall(PatchSetType(&t->patch[0], "facets"));
    PetscCall(FacetsPatchFromOptions(PetscOptionsObject, &t->patch[0], ""));
    PetscFunctionReturn(0);
  }
  PetscCall(ToolPatchesFromOptions(PetscOptionsObject, t));
  PetscFunctionReturn(0);
}

/* the patches of tool t (-patches, -patch<j>_...) inside its block */
static PetscErrorCode ToolPatchesFromOptions(PetscOptionItems *PetscOptionsObject, Tool *t)
{
  const MPI_Comm comm = PetscOptionsObject->comm;
  char           full[PETSC_MAX_PATH_LEN];
  PetscInt       np = 0;
  PetscBool      flg;

  PetscFunctionBeginUser;
  PetscCall(ToolOptionFullName(PetscOptionsObject, "-patches", full, sizeof(full)));
  PetscCall(PetscOptionsInt("-patches", "Number of patches (numbered 0, 1, ...; each configured by -patch<j>_...)", NULL, np, &np, &flg));
  PetscCheck(flg, comm, PETSC_ERR_USER_INPUT, "%s: missing required option (number of patches of tool '%s')", full, t->name);
  PetscCheck(np >= 1, comm, PETSC_ERR_USER_INPUT, "%s %" PetscInt_FMT ": a tool needs at least one patch", full, np);
  PetscCall(PetscCalloc1(np, &t->patch));
  t->npatch = (int)np;
  for (PetscInt j = 0; j < np; j++) {
    char stem[64];
    PetscCall(PetscSNPrintf(stem, sizeof(stem), "-patch%" PetscInt_FMT, j));
    PetscCall(PatchSetFromOptions(PetscOptionsObject, &t->patch[j], stem));
  }
  PetscFunctionReturn(0);
}

/* the patches prepared, their boxes and the tool's */
static PetscErrorCode ToolSetUp(Tool *t)
{
  PetscFunctionBeginUser;
  for (int j = 0; j < t->npatch; j++) PetscCall(PatchPrepare(&t->patch[j]));
  for (int i = 0; i < 3; i++) {
    t->bbox[2 * i]     = HUGE_VAL;
    t->bbox[2 * i + 1] = -HUGE_VAL;
  }
  for (int j = 0; j < t->npatch; j++) {
    Patch *p = &t->patch[j];
    double b[6];
    if (p->ops->box) p->ops->box(p, b);
    else PatchBoxSampled(p, b);
    for (int i = 0; i < 6; i++) p->bbox[i] = b[i];
    p->has_box = 1;
    for (int i = 0; i < 3; i++) {
      t->bbox[2 * i]     = fmin(t->bbox[2 * i], b[2 * i]);
      t->bbox[2 * i + 1] = fmax(t->bbox[2 * i + 1], b[2 * i + 1]);
    }
  }
  PetscFunctionReturn(0);
}

/* A tool file (.tool): lines "key value" with the keys of the tool's patch options without the
   prefix -tool_<name>_ (patches 2, patch0_type sphere, patch0_radius 50.8, ...), '#' starts a
   comment. Read on rank 0, broadcast, and read as options from a private database (the options
   database is not written), in a block of its own; a key the patches do not use is an error. */
static PetscErrorCode ToolPatchesFromFile(MPI_Comm comm, Tool *t, const char prefix[], const char title[], const char file[], int sign)
{
  PetscMPIInt    rank;
  char          *buf = NULL, ttl[PETSC_MAX_PATH_LEN], err[PETSC_MAX_PATH_LEN + 64] = "";
  long           len = 0;
  PetscOptions   o;
  PetscErrorCode ierr = 0;

  PetscFunctionBeginUser;
  PetscCallMPI(MPI_Comm_rank(comm, &rank));
  if (rank == 0) {
    FILE *fp = fopen(file, "rb");
    if (!fp) PetscCall(PetscSNPrintf(err, sizeof(err), "cannot open tool file '%s'", file));
    else {
      fseek(fp, 0, SEEK_END);
      len = ftell(fp);
      fseek(fp, 0, SEEK_SET);
      buf = malloc(len + 1);
      if (!buf || fread(buf, 1, len, fp) != (size_t)len) PetscCall(PetscSNPrintf(err, sizeof(err), "cannot read tool file '%s'", file));
      fclose(fp);
    }
  }
  PetscCallMPI(MPI_Bcast(err, sizeof(err), MPI_CHAR, 0, comm));
  if (err[0]) {
    free(buf);
    SETERRQ(comm, PETSC_ERR_FILE_OPEN, "%s", err);
  }
  PetscCallMPI(MPI_Bcast(&len, 1, MPI_LONG, 0, comm));
  if (rank) buf = malloc(len + 1);
  PetscCallMPI(MPI_Bcast(buf, (int)len, MPI_CHAR, 0, comm));
  buf[len] = 0;
  PetscCall(PetscOptionsCreate(&o));
  {
    int   ln = 0;
    for (char *line = buf, *next; line && !ierr; line = next) {
      char key[256], val[4096], name[PETSC_MAX_PATH_LEN], *h;
      next = strchr(line, '\n');
      if (next) *next++ = 0;
      h = strchr(line, '#');
      ln++;
      if (h) *h = 0;
      const int n = sscanf(line, "%255s %4095s", key, val);
      if (n <= 0) continue;
      if (n == 1) {
        PetscCall(PetscSNPrintf(err, sizeof(err), "tool file %s: '%s' has no value", file, key));
        ierr = 1;
        break;
      }
      PetscCall(PetscSNPrintf(name, sizeof(name), "-%s%s", prefix, key[0] == '-' ? key + 1 : key));
      PetscCall(PetscOptionsSetValue(o, name, val));
    }
  }
  free(buf);
  if (ierr) {
    PetscCall(PetscOptionsDestroy(&o));
    SETERRQ(comm, PETSC_ERR_FILE_UNEXPECTED, "%s", err);
  }
  PetscCall(PetscSNPrintf(ttl, sizeof(ttl), "%s (file %s)", title, file));
  PetscCall(PetscOptionsPush(o));
  PetscOptionsBegin(comm, prefix, ttl, NULL);
  ierr = ToolPatchesFromOptions(PetscOptionsObject, t);
  PetscOptionsEnd();
  PetscCall(PetscOptionsPop());
  if (!ierr) {
    PetscInt N = 0;
    char   **names = NULL, **values = NULL;
    PetscCall(PetscOptionsLeftGet(o, &N, &names, &values));
    if (N > 0) {
      PetscCall(PetscSNPrintf(err, sizeof(err), "tool file %s: key '%s' is not an option of its patches", file, names[0] + strlen(prefix)));
      ierr = 1;
    }
    PetscCall(PetscOptionsLeftRestore(o, &N, &names, &values));
  }
  PetscCall(PetscOptionsDestroy(&o));
  if (ierr == 1) SETERRQ(comm, PETSC_ERR_USER_INPUT, "%s", err);
  PetscCall(ierr);
  for (int j = 0; j < t->npatch; j++) t->patch[j].sense *= sign;
  PetscFunctionReturn(0);
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
  PetscCall(PatchRegisterAll());
  PetscOptionsBegin(comm, NULL, "Tools", NULL);
  PetscCall(PetscOptionsStringArray("-tool_names", "Names of the rigid tools, each configured by the options -tool_<name>_...", NULL, names, &n, &set));
  PetscOptionsEnd();
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
    char           prefix[PETSC_MAX_PATH_LEN], title[PETSC_MAX_PATH_LEN];
    PetscErrorCode ierr = 0;
    PetscCall(PetscSNPrintf(prefix, sizeof(prefix), "tool_%s_", T[k].name));
    PetscCall(PetscSNPrintf(title, sizeof(title), "Tool %s", T[k].name));
    /* an error inside the block is raised after it is closed (nothing of the block leaks) */
    char file[PETSC_MAX_PATH_LEN] = "";
    int  tfile                    = 0;
    PetscOptionsBegin(comm, prefix, title, NULL);
    ierr = ToolSetFromOptions(PetscOptionsObject, &T[k], file, &tfile);
    PetscOptionsEnd();
    PetscCall(ierr);
    if (tfile) PetscCall(ToolPatchesFromFile(comm, &T[k], prefix, title, file, tfile));
    PetscCall(ToolSetUp(&T[k]));
  }
  PetscFunctionReturn(0);
}

PetscErrorCode ToolsDestroy(PetscInt ntools, Tool **tools)
{
  PetscFunctionBeginUser;
  if (!*tools) PetscFunctionReturn(0);
  for (PetscInt k = 0; k < ntools; k++) {
    Tool *t = &(*tools)[k];
    if (t->patch)
      for (int j = 0; j < t->npatch; j++) PetscCall(PatchDestroy(&t->patch[j]));
    PetscCall(PetscFree(t->patch));
    PetscCall(LoadCurveDestroy(&t->amp));
  }
  PetscCall(PetscFree(*tools));
  PetscFunctionReturn(0);
}
