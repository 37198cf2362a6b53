/* Newton's watchdog line search, used in the stages without contact (no tool present: a springback
   after a release by nodal forces, a body without tools); the stages with tools keep PETSc's line
   search (-snes_linesearch_type, backtracking by default). -newton_linesearch_rise kappa (default
   1000; 0: PETSc's everywhere, as also when -snes_linesearch_type is given). A full Newton step
   x -> x - y is taken when it satisfies the Armijo condition of 1/2 |R|^2, whose slope along the
   Newton direction is -|R_k|^2:

     |R(x - y)|^2 <= (1 - 2 alpha) |R_k|^2.

   A full step that fails it but raises |R| by at most kappa is taken too (a relaxed step); the
   next iteration's full step must then satisfy the condition against the relaxed step's origin,
   else the iterate returns to that origin and backtracks along the relaxed step (the watchdog of
   Chamberlain, Powell, Lemarechal and Pedersen). Backtracking: the minimiser of the quadratic
   through 1/2 |R_k|^2, its slope and the last trial, kept within [0.1, 0.5] lambda, and half lambda
   where the trial's residual is not finite (an element inverted, a return map failed); it fails
   below -snes_linesearch_minlambda.

   Why: Gauss points that the forming left on the yield surface unload in the springback; an
   iterate that leaves one of them just outside the surface gives it the elasto-plastic tangent,
   and the full Newton step from there raises |R| 10 to 1000 times on its way into the quadratic
   basin (one element switching between plastic and elastic). A monotone search crept at
   lambda = 0.01 to 0.1 for 20 to 25 iterations a step instead (the U-channel's release,
   doc/forming.md). The watchdog takes such a step and costs one iteration where the step leads
   nowhere. With contact it was measured worse (a full step that raises |R| there mostly changes
   the active set; the U-channel's draw: 1800 more iterations, most relaxed steps reverted), hence
   the restriction to stages without contact. The state restarts with every Newton solve (a load
   step, a retry, a loop of the augmented Lagrangian, whose residual has other multipliers). The
   line search's pre-check is called as PETSc's line searches call it. */
#ifndef ATRITO_LINESEARCH_H
#define ATRITO_LINESEARCH_H
#include <petscsnes.h>

typedef struct _n_NewtonLineSearch *NewtonLineSearch;

/* reads -newton_linesearch_rise and -newton_linesearch_alpha; *nls is NULL when off */
PetscErrorCode NewtonLineSearchCreate(MPI_Comm comm, NewtonLineSearch *nls);
/* makes the SNES's line search this one (a shell line search), or gives back the one it replaced
   (with its options); nothing when nls is NULL */
PetscErrorCode NewtonLineSearchSetActive(NewtonLineSearch nls, SNES snes, PetscBool on);
/* relaxed steps taken, those of them reverted, and residual evaluations of the line search */
PetscErrorCode NewtonLineSearchGetCounts(NewtonLineSearch nls, PetscInt *relaxed, PetscInt *reverted, PetscInt *trials);
PetscErrorCode NewtonLineSearchDestroy(NewtonLineSearch *nls);
#endif
