/* Private interface of the tool module: the operations table of a patch type, and the pieces of
   tool.c and revolution.c that the type files share. Only src/tool/ includes this. */
#ifndef ATRITO_TOOLIMPL_H
#define ATRITO_TOOLIMPL_H
#include "tool.h"

#include <math.h>

#define TOOL_PI 3.14159265358979323846

/* a closest-point candidate on one patch (reference position) */
typedef struct {
  double xi, eta, x[3], d2;
  int    interior;
} PatchCandidate;

/* evaluation with a type's own context (PatchMinimize); NULL: PatchEval */
typedef void (*PatchEvalFn)(const Patch *p, const void *ctx, double xi, double eta, double x[3], double xu[3], double xv[3], double *xuu, double *xuv, double *xvv);

/* The operations of a patch type. Required: type, eval, normal, setfromoptions, view. The others
   may be NULL (the default given). A type file defines one static table and a create function
   PatchCreate_<Type>(Patch *) that sets p->ops to it; register.c registers the create function. */
struct _PatchOps {
  const char *type;
  /* x, x_xi, x_eta and (if not NULL) the second derivatives at (xi, eta) (PatchEval) */
  void (*eval)(const Patch *p, double xi, double eta, double x[3], double xu[3], double xv[3], double *xuu, double *xuv, double *xvv);
  /* unit contact normal sense (x_xi x x_eta)/|..|; returns |x_xi x x_eta| (PatchNormal) */
  double (*normal)(const Patch *p, double xi, double eta, double n[3]);
  /* characteristic length for the tolerances (NULL or <= 0: 1) */
  double (*scale)(const Patch *p);
  /* starting point z of the Newton search for y; returns 1 (skip the patch) if a lower bound of
     the distance exceeds maxdist. NULL: z = (0.5, 0.5), never skipped */
  int (*start)(const Patch *p, const double y[3], double maxdist, double z[2]);
  /* a type's own closest-point search replacing start + PatchMinimize (plane: exact; Coons:
     sample grid, Newton and its safeguards); returns 1 if skipped. L = the patch's scale */
  int (*closest)(const Patch *p, const double y[3], double maxdist, double L, PatchCandidate *c);
  /* closest with a hint: the parameters (hxi, heta) of an earlier projection on this patch; must
     give the same result as closest (only faster). NULL: closest */
  int (*closesthint)(const Patch *p, const double y[3], double maxdist, double L, double hxi, double heta, PatchCandidate *c);
  /* dn/dy at a projection (PatchNormalDerivative; dn is zeroed before). NULL: 0 (plane) */
  int (*normalderivative)(const Patch *p, const double shift[3], const double y[3], const Projection *pr, double dn[9]);
  /* reference bounding box. NULL: PatchBoxSampled */
  void (*box)(const Patch *p, double b[6]);
  /* reads the type's options, named stem_<key> (stem "-patch<j>") in the tool's options block */
  PetscErrorCode (*setfromoptions)(PetscOptionItems *PetscOptionsObject, Patch *p, const char stem[]);
  /* one line describing the patch: type, sense, parameters */
  PetscErrorCode (*view)(const Patch *p, PetscViewer v);
  /* precomputation after the parameters are set (Coons frames and sample grid) */
  PetscErrorCode (*prepare)(Patch *p);
  /* frees p->data */
  PetscErrorCode (*destroy)(Patch *p);
};

/* small vector helpers (the same operations everywhere) */
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
static inline double Sgn(double v) { return v < 0.0 ? -1.0 : 1.0; }
static inline double SenseSign(const Patch *p) { return p->sense < 0 ? -1.0 : 1.0; }

/* tool.c: projected Newton on |x(xi,eta) - y|^2 / 2 over [0,1]^2 from z (eval NULL: PatchEval) */
void PatchMinimize(const Patch *p, PatchEvalFn eval, const void *ctx, const double y[3], double L, double z[2], PatchCandidate *c);
/* tool.c: dz/dy of the free parameters at a projection from the stationarity (1 if H is not
   positive definite) */
int PatchProjectionParamDerivative(const double xu[3], const double xv[3], const double xuu[3], const double xuv[3], const double xvv[3], const double r[3], const int fr[2], double dz[2][3]);
/* tool.c: bounding box from 33 x 33 samples enlarged by the interpolation error bound */
void PatchBoxSampled(const Patch *p, double b[6]);

/* tool.c: options of the patch types, read inside the tool's options block. `opt` is the name
   relative to the block's prefix ("-patch0_radius"); errors name the full option. */
PetscErrorCode ToolOptionFullName(PetscOptionItems *PetscOptionsObject, const char opt[], char full[], size_t len);
PetscErrorCode ToolOptionReals(PetscOptionItems *PetscOptionsObject, const char opt[], const char text[], PetscInt n, PetscReal v[], PetscBool required, PetscBool *set);
PetscErrorCode ToolOptionVec(PetscOptionItems *PetscOptionsObject, const char stem[], const char key[], const char text[], double v[3]);
PetscErrorCode ToolOptionPositive(PetscOptionItems *PetscOptionsObject, const char stem[], const char key[], const char text[], double *v);
/* range stem_range: 4 values (lo0, hi0, lo1, hi1); deg[i] converts pair i from degrees; each pair
   increasing, angular spans at most 360 degrees */
PetscErrorCode ToolOptionRange(PetscOptionItems *PetscOptionsObject, const char stem[], const char text[], const PetscBool deg[2], double r[4]);

/* revolution.c: the frame of the sphere, cylinder and torus (f = a x e, w(ph) = cos ph e + sin ph f
   and w'(ph)), their starting points' arc geometry, options and edge-held normal derivative */
void           Radial(const RevolutionData *q, double ph, double w[3], double wp[3]);
int            AngleParam(double ang, double a0, double a1, double *s);
double         ArcClosest(const double m[3], const double p[3], const double q[3], double rho, double a0, double a1, const double y[3], double *s);
void           EdgeTry(double d2, double xi, double eta, double *best, double z[2]);
PetscErrorCode RevolutionFrameFromOptions(PetscOptionItems *PetscOptionsObject, const char stem[], double a[3], double e[3]);
/* the radial part of y - c about the axis: m = unit, P = I - a a - m m; returns 0 if y is on the axis */
int RevolutionAxial(const RevolutionData *q, const double d[3], double m[3], double P[9], double *rho);
/* dn/dy at a projection held on an edge: dndz gives dn/dxi, dn/deta (s the normal's sign) */
typedef void (*RevolutionNormalDz)(const Patch *p, double s, const double z[2], const double xu[3], const double xv[3], double nu[3], double nv[3]);
int  RevolutionEdgeNormalDerivative(const Patch *p, const double shift[3], const double y[3], const Projection *pr, double s, RevolutionNormalDz dndz, double dn[9]);
/* the sign of the normal relative to x_xi x x_eta's direction: sense * sign(dt ds) */
static inline double RevolutionSign(const Patch *p) { return SenseSign(p) * Sgn((p->rev.t1 - p->rev.t0) * (p->rev.s1 - p->rev.s0)); }
PetscErrorCode RevolutionView(const Patch *p, PetscViewer v, const char *what, const PetscBool deg[2]);
#endif
