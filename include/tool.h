/* Rigid tools: a tool is a set of parametric patches moving by a prescribed translation ramped
   with the load parameter (or along a piecewise-linear path). Patch types (plane, sphere,
   cylinder, torus, Coons, ...) sit behind a registry of operation tables (src/tool/toolimpl.h,
   one file per type in src/tool/). Geometry kernels on plain arrays (no MPI); options parsing at
   the module boundary. Tools are small and replicated on every rank. */
#ifndef ATRITO_TOOL_H
#define ATRITO_TOOL_H
#include <petscsys.h>
#include <petscviewer.h>
#include "loadcurve.h"

typedef enum { CURVE_LINE = 0, CURVE_ARC } CurveType;

/* A boundary curve of a Coons patch, parametrised by s in [0,1]: a straight segment from a to b,
   or the circular arc from a to b about the centre c (the shorter way; a and b equidistant from c,
   not diametrically opposite). */
typedef struct {
  CurveType type;
  double    a[3], b[3], c[3];
} Curve;

/* A boundary curve prepared for evaluation (PatchPrepare). Line: C(s) = o + s e1. Arc:
   C(s) = o + rho (cos(s th) e1 + sin(s th) e2), o the centre, rho the radius, e1, e2 orthonormal,
   th in (0, pi) the angle from a to b; any s continues along the circle. */
typedef struct {
  int    arc;
  double o[3], e1[3], e2[3], rho, th;
} CurveFrame;

/* Samples of a Coons patch on a TOOL_COONS_GRID^2 grid of (xi, eta), the starting points of its
   projection */
#define TOOL_COONS_GRID 9

/* Every patch maps (xi, eta) in [0,1]^2 to a point x(xi, eta) of its reference position (the tool
   at load 0). Parameters per type (angles in radians):
   plane:    x = o + (u0 + xi (u1-u0)) e1 + (v0 + eta (v1-v0)) e2, e1, e2 orthonormal
   sphere:   centre c, radius R, axis a, reference direction e (unit, normal to a);
             polar angle th = t0 + xi (t1-t0) from a, azimuth ph = s0 + eta (s1-s0) from e
   cylinder: axis point c, axis a, ref e, radius R; azimuth ph = t0 + xi (t1-t0), height z = s0 + eta (s1-s0)
   torus:    centre c, axis a, ref e, major radius R (centre to tube axis), minor radius r;
             azimuth ph = t0 + xi (t1-t0) about a, tube angle ps = s0 + eta (s1-s0), ps = 0
             on the outer equator, ps = +pi/2 towards +a
   coons:    bilinearly blended patch of four curves: bottom C0(xi) (eta = 0), top C1(xi) (eta = 1),
             left D0(eta) (xi = 0), right D1(eta) (xi = 1); corners must coincide.
   The contact normal of the patch is sense * (x_xi × x_eta)/|x_xi × x_eta|, sense = +1 or -1 chosen
   so that it points out of the tool, towards the deformable body. */
typedef struct {
  double o[3], e1[3], e2[3], u0, u1, v0, v1;
} PlaneData;
typedef struct { /* sphere, cylinder, torus: surfaces of revolution about the axis a */
  double c[3], a[3], e[3], R, r;
  double t0, t1, s0, s1; /* parameter ranges: first, second parameter */
} RevolutionData;
typedef struct {
  Curve C0, C1, D0, D1;
} CoonsData;

/* the operations of a patch type (src/tool/toolimpl.h) */
typedef struct _PatchOps PatchOps;

/* A patch: plain data, usable by value in arrays. The small parameters of the built-in types live
   in the union; `data` holds what a type allocates (a Coons patch's prepared frames and samples, a
   meshed surface's facets), freed by PatchDestroy. A copy of a patch shares its `data`: prepare or
   destroy only one of them. */
typedef struct {
  const PatchOps *ops;   /* the type (PatchSetType)                  */
  int             sense; /* +1 or -1                                 */
  union {
    PlaneData      plane;
    RevolutionData rev;
    CoonsData      coons;
  };
  void  *data;
  double bbox[6]; /* reference bounding box (set with the tool) */
  int    has_box; /* bbox is set                              */
} Patch;

/* Registry of patch types: `create` sets a zeroed patch's operations (and defaults) */
PetscErrorCode PatchRegister(const char name[], PetscErrorCode (*create)(Patch *));
/* Registers the built-in types (once; src/tool/register.c) */
PetscErrorCode PatchRegisterAll(void);
/* Clears p (which must hold no allocated data) and gives it the registered type `type`, sense 1 */
PetscErrorCode PatchSetType(Patch *p, const char type[]);
/* The type name ("plane", ...); "" for a patch without a type */
const char    *PatchGetType(const Patch *p);
/* Prepares a patch whose parameters are set, once, for fast evaluation and projection (a Coons
   patch's curve frames and sample grid; nothing for the other types). Must be called again if the
   parameters change. */
PetscErrorCode PatchPrepare(Patch *p);
/* Frees what the patch allocated (PatchPrepare); the parameters stay */
PetscErrorCode PatchDestroy(Patch *p);
/* One line describing the patch (type, sense, parameters) */
PetscErrorCode PatchView(const Patch *p, PetscViewer v);

typedef struct {
  char    name[PETSC_MAX_PATH_LEN];
  int     npatch;
  Patch  *patch;
  double  motion[3];     /* translation: motion * a(t), a the amplitude (default t/T); zero: fixed   */
  LoadCurve amp;         /* -tool_<name>_amplitude: a(t) (n = 0: the ramp t/T over the process)       */
  int     npath;         /* > 0: piecewise-linear path instead: points (process time, dx, dy, dz)     */
  double  path[4 * 32];
  int     absent;        /* the tool is absent in the current stage: it pairs no node (ToolProject)  */
  double  bbox[6];       /* reference bounding box of all patches: xmin, xmax, ymin, ymax, zmin, zmax */
  double  edge_tol;      /* > 0: a point beside an open edge of the tool by more than this is no contact
                            (ToolProject; set by the contact, -contact_edge_tolerance); 0: not checked */
} Tool;

/* Evaluation of a patch at (xi, eta) in its reference position: point x, first derivatives
   xu = dx/dxi, xv = dx/deta, and (if not NULL) second derivatives xuu, xuv, xvv. Also valid
   somewhat outside [0,1]^2 (natural extension), which the projection uses. */
void PatchEval(const Patch *p, double xi, double eta, double x[3], double xu[3], double xv[3], double *xuu, double *xuv, double *xvv);
/* Unit contact normal at (xi, eta) (see above); returns |x_xi × x_eta| (0 at a degenerate point) */
double PatchNormal(const Patch *p, double xi, double eta, double n[3]);

/* Result of projecting a point y on a tool */
typedef struct {
  int    patch;        /* index of the patch of the closest point                               */
  double xi, eta;      /* its parameters                                                        */
  double x[3];         /* the closest point (current tool position)                             */
  double n[3];         /* unit contact normal there                                             */
  double gap;          /* signed distance (y - x).n : negative when y has penetrated the tool    */
  int    interior;     /* 1 if (xi,eta) is inside [0,1]^2 (0: clamped to an edge or a corner)    */
} Projection;

/* Closest point of y on the tool displaced by `shift` (the tool's current translation):
   every patch is tried (a bounding-box test first), each by Newton on (xi, eta) with a safeguarded
   fallback (clamped to [0,1]^2, a sampling start when Newton fails); among the patches the
   interior solution of smallest |y - x| wins, so that a point beyond one patch's edge moves to the
   neighbouring patch. With t->edge_tol > 0, a closest point held on a patch's boundary (no patch
   gave an interior point as close: an open edge of the tool), with y beside it in the tangent plane
   by more than edge_tol and by more than y lies inside the tool, is not taken: y is beside the
   tool, not over it (the best interior point of another patch if there is one, else no point;
   doc/tools.md, projection step 7). Returns 0 on
   success, 1 if no patch gave a point. `maxdist`: patches whose bounding box lies farther than this
   from y are skipped (PETSC_INFINITY: none). */
int ToolProject(const Tool *t, const double shift[3], const double y[3], double maxdist, Projection *pr);

/* ToolProject with the projection of an earlier call as a hint (its patch, xi, eta; NULL or a
   patch index out of range: none): the same result, bit for bit, found faster on a meshed surface
   (facets: the hint's facet and a walk over its neighbours bound the search) */
int ToolProjectHint(const Tool *t, const double shift[3], const double y[3], double maxdist, const Projection *hint, Projection *pr);

/* Derivative of the contact normal with respect to the projected point's position y for the
   patches (plane: 0; sphere, cylinder, torus: the curvature of the offset surface through y;
   Coons: from the second derivatives of the patch and the stationarity of the projection).
   dn[3*i+j] = d n_i / d y_j. Returns 0, or 1 where the patch is degenerate at the projected point
   (a collapsed side of a Coons patch: x_xi x x_eta = 0), where the caller must difference. */
int PatchNormalDerivative(const Patch *p, const double shift[3], const double y[3], const Projection *pr, double dn[9]);

/* Options: -tool_names a,b and per tool -tool_<name>_... (see doc/tools.md), read in options
   blocks titled "Tools" and "Tool <name>" (listed by -help). Collective; errors name the option
   and value. */
PetscErrorCode ToolsCreateFromOptions(MPI_Comm comm, PetscInt *ntools, Tool **tools);
PetscErrorCode ToolsDestroy(PetscInt ntools, Tool **tools);
/* The total process time T (the sum of the stages' durations, 1 without stages) of the default
   amplitude t/T; set once before the run (the stepper), 1 until then */
void ToolsSetTotalTime(double T);
/* The tool's translation at process time t: motion * a(t) with a its amplitude curve
   (-tool_<name>_amplitude) or, without one, t/T (today's linear ramp when T = 1), or the
   piecewise-linear interpolation of its path (-tool_<name>_path t0,dx,dy,dz, t1,dx,dy,dz, ... with
   0 = t0 < t1 < ..., process times; held at the last point beyond it) */
void ToolShift(const Tool *t, double time, double shift[3]);
/* Path length travelled by the tool from time 0 to t: the sum of the lengths of the linear pieces
   of its motion (of the path, or motion * a over the pieces of a) up to t */
double ToolTravel(const Tool *t, double time);
/* The first kink of the tool's motion strictly after t (a path point or a breakpoint of the
   amplitude curve; PETSC_INFINITY if none) */
double ToolNextKink(const Tool *t, double time);
/* The tool: name, motion, bounding box, and one line per patch (ASCII viewer) */
PetscErrorCode ToolView(const Tool *t, PetscViewer v);
#endif
