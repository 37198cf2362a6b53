/* What the surfaces of revolution (sphere, cylinder, torus) share: their frame, the closest point
   of a circular arc (their edges), the axis and reference options, the normal derivative at a
   projection held on an edge, and the view.

   Frames: a (axis) and e (reference direction) are unit and orthogonal, f = a x e, so (e, f, a) is
   right-handed; w(ph) = cos ph e + sin ph f is the radial direction at azimuth ph and
   w'(ph) = -sin ph e + cos ph f its derivative. */
#include "toolimpl.h"

#include "options.h"

void Radial(const RevolutionData *q, double ph, double w[3], double wp[3])
{
  double       f[3];
  const double c = cos(ph), s = sin(ph);
  Cross(q->a, q->e, f);
  for (int i = 0; i < 3; i++) {
    w[i]  = c * q->e[i] + s * f[i];
    wp[i] = -s * q->e[i] + c * f[i];
  }
}

/* Angle ang mapped into [a0, a0 + 2 pi): 1 with s = (ang - a0)/(a1 - a0) if it lies in [a0, a1]
   (a0 < a1 <= a0 + 2 pi; a decreasing range is flipped); otherwise 0 with s the nearer end (0 or 1)
   along the circle. */
int AngleParam(double ang, double a0, double a1, double *s)
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
double ArcClosest(const double m[3], const double p[3], const double q[3], double rho, double a0, double a1, const double y[3], double *s)
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
void EdgeTry(double d2, double xi, double eta, double *best, double z[2])
{
  if (d2 < *best) {
    *best = d2;
    z[0]  = xi;
    z[1]  = eta;
  }
}

/* unit axis a (stem_axis) and reference e (stem_ref) orthonormalised against it */
PetscErrorCode RevolutionFrameFromOptions(PetscOptionItems *PetscOptionsObject, const char stem[], double a[3], double e[3])
{
  const MPI_Comm comm = PetscOptionsObject->comm;
  double         na, ne, ref[3] = {0, 0, 0}, nr, pa;
  char           opt[PETSC_MAX_PATH_LEN], fa[PETSC_MAX_PATH_LEN], fr[PETSC_MAX_PATH_LEN];

  PetscFunctionBeginUser;
  PetscCall(PetscSNPrintf(opt, sizeof(opt), "%s_axis", stem));
  PetscCall(ToolOptionFullName(PetscOptionsObject, opt, fa, sizeof(fa)));
  PetscCall(PetscSNPrintf(opt, sizeof(opt), "%s_ref", stem));
  PetscCall(ToolOptionFullName(PetscOptionsObject, opt, fr, sizeof(fr)));
  PetscCall(ToolOptionVec(PetscOptionsObject, stem, "axis", "Axis direction a (normalised)", a));
  na = Norm(a);
  PetscCheck(na > 0, comm, PETSC_ERR_USER_INPUT, "%s %g,%g,%g: zero vector", fa, a[0], a[1], a[2]);
  for (int i = 0; i < 3; i++) a[i] /= na;
  PetscCall(ToolOptionVec(PetscOptionsObject, stem, "ref", "Reference direction e of the angles (orthonormalised against the axis)", ref));
  nr = Norm(ref);
  pa = Dot(ref, a);
  for (int i = 0; i < 3; i++) e[i] = ref[i] - pa * a[i];
  ne = Norm(e);
  PetscCheck(nr > 0 && ne > 1e-10 * nr, comm, PETSC_ERR_USER_INPUT, "%s %g,%g,%g: zero or parallel to %s", fr, ref[0], ref[1], ref[2], fa);
  for (int i = 0; i < 3; i++) e[i] /= ne;
  PetscFunctionReturn(0);
}

int RevolutionAxial(const RevolutionData *q, const double d[3], double m[3], double P[9], double *rho)
{
  const double h = Dot(d, q->a);
  double       dp[3];
  for (int i = 0; i < 3; i++) dp[i] = d[i] - h * q->a[i];
  *rho = Norm(dp);
  if (!(*rho > 0.0)) return 0;
  for (int i = 0; i < 3; i++) m[i] = dp[i] / *rho;
  for (int i = 0; i < 3; i++)
    for (int j = 0; j < 3; j++) P[3 * i + j] = (i == j) - q->a[i] * q->a[j] - m[i] * m[j]; /* I - a a - w w */
  return 1;
}

/* Projection held on an edge or at a corner: n(xi(y), eta(y)) with the free parameter from the
   stationarity x_i.(x - y) = 0, i.e. H dz = x_i^T dy (0 at a corner) */
int RevolutionEdgeNormalDerivative(const Patch *p, const double shift[3], const double y[3], const Projection *pr, double s, RevolutionNormalDz dndz, double dn[9])
{
  double       x[3], xu[3], xv[3], xuu[3], xuv[3], xvv[3], r[3], nu[3] = {0, 0, 0}, nv[3] = {0, 0, 0}, dz[2][3];
  int          fr[2];
  const double z[2] = {pr->xi, pr->eta};
  for (int i = 0; i < 2; i++) fr[i] = z[i] > 0.0 && z[i] < 1.0;
  if (!fr[0] && !fr[1]) return 0;
  PatchEval(p, z[0], z[1], x, xu, xv, xuu, xuv, xvv);
  for (int i = 0; i < 3; i++) r[i] = x[i] - (y[i] - shift[i]);
  dndz(p, s, z, xu, xv, nu, nv); /* dn/dxi, dn/deta */
  if (PatchProjectionParamDerivative(xu, xv, xuu, xuv, xvv, r, fr, dz)) return 0;
  for (int i = 0; i < 3; i++)
    for (int j = 0; j < 3; j++) dn[3 * i + j] = nu[i] * dz[0][j] + nv[i] * dz[1][j];
  return 0;
}

/* centre, axis, reference direction, the type's own radii (what) and the ranges as in the options
   (deg[i]: pair i in degrees) */
PetscErrorCode RevolutionView(const Patch *p, PetscViewer v, const char *what, const PetscBool deg[2])
{
  const RevolutionData *q    = &p->rev;
  const double          f[2] = {deg[0] ? 180.0 / TOOL_PI : 1.0, deg[1] ? 180.0 / TOOL_PI : 1.0};
  PetscFunctionBeginUser;
  PetscCall(PetscViewerASCIIPrintf(v, "%s, sense %d: centre %g,%g,%g, axis %g,%g,%g, ref %g,%g,%g, %s, range %g,%g,%g,%g\n", PatchGetType(p), p->sense, q->c[0], q->c[1], q->c[2], q->a[0], q->a[1], q->a[2], q->e[0], q->e[1], q->e[2], what, q->t0 * f[0], q->t1 * f[0], q->s0 * f[1], q->s1 * f[1]));
  PetscFunctionReturn(0);
}
