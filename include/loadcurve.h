/* Piecewise-linear functions of the process time: amplitudes of prescribed displacements and
   tool motions, force histories of force-driven tools.

   A curve is the list of points (t_0, v_0), (t_1, v_1), ... with t_0 < t_1 < ...; it is linear
   between points and constant beyond the first and the last (v_0 before t_0, v_n-1 after t_n-1).
   An option gives a curve in one of two ways:
     -opt t0,v0,t1,v1,...     inline, at most LOADCURVE_INLINE_MAX points
     -opt PATH                a text file, two numbers per line (time, value), '#' starts a
                              comment; any number of points (data belongs in files)
   Errors (a list of odd length, times not increasing, a NaN or Inf, an unreadable file) are one
   line naming the option. The breakpoints t_i are the kinks of the curve: the load stepper lands
   a step on each, so that no increment straddles a kink. */
#ifndef ATRITO_LOADCURVE_H
#define ATRITO_LOADCURVE_H
#include <petscsys.h>

#define LOADCURVE_INLINE_MAX 64

typedef struct {
  PetscInt   n;     /* number of points (0: not set) */
  PetscReal *t, *v; /* times (increasing) and values   */
} LoadCurve;

/* Parses the option's value `str` (inline list or file) into c (collective: the file is read on
   rank 0 and broadcast). `opt` names the option in errors. */
PetscErrorCode LoadCurveParse(MPI_Comm comm, const char opt[], const char str[], LoadCurve *c);
/* A curve from explicit points (copied); errors name `opt` */
PetscErrorCode LoadCurveCreate(MPI_Comm comm, const char opt[], PetscInt n, const PetscReal t[], const PetscReal v[], LoadCurve *c);
/* A copy of a (c must be empty or destroyed) */
PetscErrorCode LoadCurveDuplicate(const LoadCurve *a, LoadCurve *c);
PetscErrorCode LoadCurveDestroy(LoadCurve *c);
/* v(t); 0 for an empty curve */
PetscReal LoadCurveEval(const LoadCurve *c, PetscReal t);
/* dv/dt at t, from the right (the slope of the piece that starts at or contains t) */
PetscReal LoadCurveSlope(const LoadCurve *c, PetscReal t);
/* the first breakpoint strictly after t (PETSC_INFINITY if none) */
PetscReal LoadCurveNextKink(const LoadCurve *c, PetscReal t);
#endif
