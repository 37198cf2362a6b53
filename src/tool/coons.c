/* Patch type "coons": the bilinearly blended patch of four boundary curves (segments or circular
   arcs), x = (1-v) C0(u) + v C1(u) + (1-u) D0(v) + u D1(v) - B(u,v), B the bilinear interpolant of
   the corners P00 = C0(0), P10 = C0(1), P01 = C1(0), P11 = C1(1). Its projection starts from the
   best of a grid of samples and has safeguards for starts on the boundary and collapsed sides.
   PatchPrepare stores the curve frames and the samples (p->data); a prepared patch evaluates and
   projects bit for bit as an unprepared one. */
#include "toolimpl.h"

#include <float.h>
#include <stdlib.h>
#include <string.h>

#include "options.h"

enum { NG = TOOL_COONS_GRID };

/* the four curves of a Coons patch: bottom C0, top C1, left D0, right D1 */
typedef struct {
  CurveFrame f[4];
} CoonsFrame;

/* what PatchPrepare stores (p->data) */
typedef struct {
  CurveFrame frame[4];
  double     grid[NG][NG][3];
} CoonsPrepared;

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

static void CoonsSetup(const Patch *p, CoonsFrame *F)
{
  const CoonsPrepared *pp = (const CoonsPrepared *)p->data;
  if (pp) {
    for (int k = 0; k < 4; k++) F->f[k] = pp->frame[k];
    return;
  }
  CurveSetup(&p->coons.C0, &F->f[0]);
  CurveSetup(&p->coons.C1, &F->f[1]);
  CurveSetup(&p->coons.D0, &F->f[2]);
  CurveSetup(&p->coons.D1, &F->f[3]);
}

static void CoonsEvalF(const Patch *p, const CoonsFrame *F, double u, double v, double x[3], double xu[3], double xv[3], double *xuu, double *xuv, double *xvv)
{
  double        c0[3], c0p[3], c0pp[3], c1[3], c1p[3], c1pp[3], d0[3], d0p[3], d0pp[3], d1[3], d1p[3], d1pp[3];
  const double *P00 = p->coons.C0.a, *P10 = p->coons.C0.b, *P01 = p->coons.C1.a, *P11 = p->coons.C1.b;
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

/* the evaluation of PatchMinimize with the curves prepared once (ctx: the CoonsFrame) */
static void CoonsEvalCtx(const Patch *p, const void *ctx, double u, double v, double x[3], double xu[3], double xv[3], double *xuu, double *xuv, double *xvv)
{
  CoonsEvalF(p, (const CoonsFrame *)ctx, u, v, x, xu, xv, xuu, xuv, xvv);
}

static void CoonsEval(const Patch *p, double u, double v, double x[3], double xu[3], double xv[3], double *xuu, double *xuv, double *xvv)
{
  CoonsFrame F;
  CoonsSetup(p, &F);
  CoonsEvalF(p, &F, u, v, x, xu, xv, xuu, xuv, xvv);
}

static double CoonsNormal(const Patch *p, double xi, double eta, double n[3])
{
  double x[3], xu[3], xv[3], N[3], J, l;
  CoonsEval(p, xi, eta, x, xu, xv, NULL, NULL, NULL);
  Cross(xu, xv, N);
  J = Norm(N);
  if (!(J > 1e-14 * (Dot(xu, xu) + Dot(xv, xv)))) { /* degenerate point (collapsed edge): the limit from inside */
    const double h = 1e-7;
    CoonsEval(p, xi + h * (0.5 - xi), eta + h * (0.5 - eta), x, xu, xv, NULL, NULL, NULL);
    Cross(xu, xv, N);
  }
  l = Norm(N);
  for (int i = 0; i < 3; i++) n[i] = l > 0.0 ? N[i] / l : 0.0;
  for (int i = 0; i < 3; i++) n[i] *= SenseSign(p);
  return J;
}

static double CoonsScale(const Patch *p)
{
  const CoonsData *g = &p->coons;
  return 0.5 * (sqrt(Dist2(g->C0.a, g->C0.b)) + sqrt(Dist2(g->C1.a, g->C1.b)) + sqrt(Dist2(g->D0.a, g->D0.b)) + sqrt(Dist2(g->D1.a, g->D1.b)));
}

/* Starting points from a 9 x 9 grid of samples: the curves at the grid lines (an arc's angles by
   the rotation recurrence), the blend at the nodes. */
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
  const double *P00 = p->coons.C0.a, *P10 = p->coons.C0.b, *P01 = p->coons.C1.a, *P11 = p->coons.C1.b;
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
  const CoonsPrepared *pp   = (const CoonsPrepared *)p->data;
  double               best = HUGE_VAL;
  if (pp) g->X = pp->grid;
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

/* A collapsed side (x_xi = 0 along eta = 0 or 1, or x_eta = 0 along xi = 0 or 1) maps a whole edge
   to one point, where Newton stops since that edge's parameter has no effect. If c lies there, the
   distance's derivatives along the fan of tangents x_eta(xi_k) (9 samples) are checked, and Newton
   restarted inside along the steepest descending one. */
static void CoonsFan(const Patch *p, const CoonsFrame *F, const double y[3], double L, PatchCandidate *c)
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
        best           = dd;
        z[dir ? 1 : 0] = s;
        z[dir ? 0 : 1] = zb + sg / 16.0;
      }
    }
    if (best < -1e-12 * L) {
      PatchCandidate c2;
      PatchMinimize(p, CoonsEvalCtx, F, y, L, z, &c2);
      if (c2.d2 < c->d2) *c = c2;
    }
  }
}

/* Newton from the best sample; on the boundary also from the second start, and the fan of a
   collapsed side. No lower bound: never skipped. */
static int CoonsClosest(const Patch *p, const double y[3], double maxdist, double L, PatchCandidate *c)
{
  double     z[2] = {0.5, 0.5}, z2[2];
  CoonsFrame F;
  CoonsGrid  g;
  CoonsSetup(p, &F);
  CoonsStart(p, &F, y, &g, z);
  PatchMinimize(p, CoonsEvalCtx, &F, y, L, z, c);
  if (!c->interior && CoonsSecondStart(&g, z2)) { /* on the boundary: also from the second start */
    PatchCandidate c2;
    PatchMinimize(p, CoonsEvalCtx, &F, y, L, z2, &c2);
    if (c2.d2 < c->d2) *c = c2;
  }
  if (!c->interior) CoonsFan(p, &F, y, L, c);
  return 0;
}

/* n = sense N/|N|, N = x_xi x x_eta, so dn/dxi = sense (I - n n)(x_xixi x x_eta + x_xi x x_xieta)/|N|
   (and likewise for eta), chained with dz/dy. Both parameters are free at an interior projection
   (on a seam too: the patch extends smoothly), one at a projection held on an edge, none at a
   corner. */
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
  if (PatchProjectionParamDerivative(xu, xv, xuu, xuv, xvv, r, fr, dz)) return 1;
  Cross(xuu, xv, a);
  Cross(xu, xuv, b);
  for (int i = 0; i < 3; i++) Nu[i] = a[i] + b[i];
  Cross(xuv, xv, a);
  Cross(xu, xvv, b);
  for (int i = 0; i < 3; i++) Nv[i] = a[i] + b[i];
  {
    const double s = SenseSign(p), pu = Dot(n, Nu), pv = Dot(n, Nv);
    for (int i = 0; i < 3; i++) {
      const double nu = s * (Nu[i] - pu * n[i]) / l, nv = s * (Nv[i] - pv * n[i]) / l;
      for (int j = 0; j < 3; j++) dn[3 * i + j] = nu * dz[0][j] + nv * dz[1][j];
    }
  }
  return 0;
}

/* stem_<side>_type line|arc and stem_<side>_points (6 or 9 values) */
static PetscErrorCode CurveFromOptions(PetscOptionItems *PetscOptionsObject, const char stem[], const char side[], Curve *cv)
{
  const MPI_Comm comm = PetscOptionsObject->comm;
  char           opt[PETSC_MAX_PATH_LEN], full[PETSC_MAX_PATH_LEN], fpts[PETSC_MAX_PATH_LEN], typ[64] = "", text[128];
  PetscBool      flg;
  PetscReal      b[9] = {0};
  PetscInt       np;

  PetscFunctionBeginUser;
  PetscCall(PetscSNPrintf(opt, sizeof(opt), "%s_%s_type", stem, side));
  PetscCall(ToolOptionFullName(PetscOptionsObject, opt, full, sizeof(full)));
  PetscCall(PetscSNPrintf(text, sizeof(text), "Type of the %s curve: line or arc", side));
  PetscCall(PetscOptionsString(opt, text, NULL, typ, typ, sizeof(typ), &flg));
  PetscCheck(flg, comm, PETSC_ERR_USER_INPUT, "%s: missing required option (line or arc)", full);
  if (!strcmp(typ, "line")) cv->type = CURVE_LINE;
  else if (!strcmp(typ, "arc")) cv->type = CURVE_ARC;
  else SETERRQ(comm, PETSC_ERR_USER_INPUT, "%s %s: unknown curve type (use line or arc)", full, typ);
  np = cv->type == CURVE_LINE ? 6 : 9;
  PetscCall(PetscSNPrintf(opt, sizeof(opt), "%s_%s_points", stem, side));
  PetscCall(ToolOptionFullName(PetscOptionsObject, opt, fpts, sizeof(fpts)));
  PetscCall(PetscSNPrintf(text, sizeof(text), "The %s curve's end points a,b (line) or a,b and centre c (arc)", side));
  PetscCall(ToolOptionReals(PetscOptionsObject, opt, text, np, b, PETSC_TRUE, NULL));
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
    PetscCheck(ru > 0 && rv > 0, comm, PETSC_ERR_USER_INPUT, "%s: an arc end point coincides with the centre", fpts);
    PetscCheck(fabs(ru - rv) <= 1e-8 * fmax(ru, rv), comm, PETSC_ERR_USER_INPUT, "%s: arc end points not equidistant from the centre: %.12g and %.12g", fpts, ru, rv);
    cs = Dot(u, v) / (ru * rv);
    PetscCheck(cs > -1.0 + 1e-12, comm, PETSC_ERR_USER_INPUT, "%s: arc end points diametrically opposite (the arc is ambiguous; split it)", fpts);
    PetscCheck(Dist2(cv->a, cv->b) > 0, comm, PETSC_ERR_USER_INPUT, "%s: arc end points coincide", fpts);
  }
  PetscFunctionReturn(0);
}

static PetscErrorCode CoonsSetFromOptions(PetscOptionItems *PetscOptionsObject, Patch *p, const char stem[])
{
  CoonsData   *g = &p->coons;
  /* corners: (0,0) C0(0)=D0(0), (1,0) C0(1)=D1(0), (0,1) C1(0)=D0(1), (1,1) C1(1)=D1(1) */
  double       q[4][2][3], t1[3], t2[3], L = 0.0, rmax = 0.0;
  const int    cu[4][2] = {{0, 0}, {1, 0}, {0, 1}, {1, 1}};
  const Curve *cv[4];
  char         pre[PETSC_MAX_PATH_LEN];

  PetscFunctionBeginUser;
  PetscOptionsHeadBegin(PetscOptionsObject, "Coons patch");
  PetscCall(ToolOptionFullName(PetscOptionsObject, stem, pre, sizeof(pre)));
  PetscCall(CurveFromOptions(PetscOptionsObject, stem, "bottom", &g->C0));
  PetscCall(CurveFromOptions(PetscOptionsObject, stem, "top", &g->C1));
  PetscCall(CurveFromOptions(PetscOptionsObject, stem, "left", &g->D0));
  PetscCall(CurveFromOptions(PetscOptionsObject, stem, "right", &g->D1));
  cv[0] = &g->C0;
  cv[1] = &g->C1;
  cv[2] = &g->D0;
  cv[3] = &g->D1;
  for (int k = 0; k < 4; k++) {
    L = fmax(L, sqrt(Dist2(cv[k]->a, cv[k]->b)));
    if (cv[k]->type == CURVE_ARC) rmax = fmax(rmax, sqrt(Dist2(cv[k]->a, cv[k]->c)));
  }
  for (int k = 0; k < 4; k++) {
    const int u = cu[k][0], v = cu[k][1];
    CurveEval(v ? &g->C1 : &g->C0, u, q[k][0], t1, t2); /* bottom/top at xi = u */
    CurveEval(u ? &g->D1 : &g->D0, v, q[k][1], t1, t2); /* left/right at eta = v */
    const double dist = sqrt(Dist2(q[k][0], q[k][1]));
    PetscCheck(dist <= 1e-8 * fmax(L, rmax), PetscOptionsObject->comm, PETSC_ERR_USER_INPUT, "%s: the boundary curves do not meet at corner (xi,eta)=(%d,%d): distance %g", pre, u, v, dist);
  }
  PetscCheck(L > 0, PetscOptionsObject->comm, PETSC_ERR_USER_INPUT, "%s: the boundary curves are all single points", pre);
  PetscFunctionReturn(0);
}

static PetscErrorCode CoonsView(const Patch *p, PetscViewer v)
{
  const Curve *cv[4]   = {&p->coons.C0, &p->coons.C1, &p->coons.D0, &p->coons.D1};
  const char  *side[4] = {"bottom", "top", "left", "right"};
  char         line[1024];
  size_t       len;

  PetscFunctionBeginUser;
  PetscCall(PetscSNPrintf(line, sizeof(line), "%s, sense %d%s:", PatchGetType(p), p->sense, p->data ? ", prepared" : ""));
  for (int k = 0; k < 4; k++) {
    const Curve *c = cv[k];
    PetscCall(PetscStrlen(line, &len));
    if (c->type == CURVE_ARC) PetscCall(PetscSNPrintf(line + len, sizeof(line) - len, "%s %s arc %g,%g,%g to %g,%g,%g about %g,%g,%g", k ? "," : "", side[k], c->a[0], c->a[1], c->a[2], c->b[0], c->b[1], c->b[2], c->c[0], c->c[1], c->c[2]));
    else PetscCall(PetscSNPrintf(line + len, sizeof(line) - len, "%s %s line %g,%g,%g to %g,%g,%g", k ? "," : "", side[k], c->a[0], c->a[1], c->a[2], c->b[0], c->b[1], c->b[2]));
  }
  PetscCall(PetscViewerASCIIPrintf(v, "%s\n", line));
  PetscFunctionReturn(0);
}

/* the curve frames and the sample grid, in p->data (allocated once, recomputed at each call) */
static PetscErrorCode CoonsPrepare(Patch *p)
{
  CoonsPrepared *pp = (CoonsPrepared *)p->data;
  CoonsFrame     F;

  PetscFunctionBeginUser;
  if (!pp) PetscCall(PetscNew(&pp));
  p->data = NULL; /* the frames from the curves, not from a previous preparation */
  CoonsSetup(p, &F);
  for (int k = 0; k < 4; k++) pp->frame[k] = F.f[k];
  CoonsGridPoints(p, &F, pp->grid);
  p->data = pp;
  PetscFunctionReturn(0);
}

static PetscErrorCode CoonsDestroy(Patch *p)
{
  PetscFunctionBeginUser;
  PetscCall(PetscFree(p->data));
  PetscFunctionReturn(0);
}

static const PatchOps CoonsOps = {
  .type             = "coons",
  .eval             = CoonsEval,
  .normal           = CoonsNormal,
  .scale            = CoonsScale,
  .closest          = CoonsClosest,
  .normalderivative = CoonsNormalDerivative,
  .setfromoptions   = CoonsSetFromOptions,
  .view             = CoonsView,
  .prepare          = CoonsPrepare,
  .destroy          = CoonsDestroy,
};

PetscErrorCode PatchCreate_Coons(Patch *p)
{
  PetscFunctionBeginUser;
  p->ops = &CoonsOps;
  PetscFunctionReturn(0);
}
