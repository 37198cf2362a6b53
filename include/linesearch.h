/* Newton's line searches (shell line searches of PETSc's SNES). In the stages with a tool present,
   the energy line search (-newton_linesearch_contact energy, the default; src/solver/linesearch.c,
   EnergySearch, and doc/contact.md, Contact without tuning): the step length where R(x - lambda y).y
   = 0, limited first by the contact's geometry (NewtonLineSearchSetStepLimit). In the stages that
   release their tools by nodal forces and have no tool present (the springback's unloading), the
   watchdog line search below; the other stages keep PETSc's line search (-snes_linesearch_type,
   backtracking by default; when it is given, it is used everywhere). -newton_watchdog none|release|contactfree
   (default release; contactfree: every stage without a tool present; when -snes_linesearch_type
   is given PETSc's is used everywhere). A full Newton step x -> x - y is taken when it satisfies
   the Armijo condition of 1/2 |R|^2, whose slope along the Newton direction is -|R_k|^2:

     |R(x - y)|^2 <= (1 - 2 alpha) |R_k|^2   (-newton_linesearch_alpha, default 1e-4).

   A full step that fails it but raises |R| by at most kappa (-newton_linesearch_rise, default
   1000) is taken too (a relaxed step); the next iteration's full step must then satisfy the
   condition against the relaxed step's origin, else the iterate returns to that origin and
   backtracks along the relaxed step (the watchdog of Chamberlain, Powell, Lemarechal and
   Pedersen). Backtracking: the minimiser of the quadratic through 1/2 |R_k|^2, its slope and the
   last trial, kept within [0.1, 0.5] lambda, and half lambda where the trial's residual is not
   finite (an element inverted, a return map failed); it fails below -snes_linesearch_minlambda.

   Why: Gauss points that the forming left on the yield surface unload in the springback; an
   iterate that leaves one of them just outside the surface gives it the elasto-plastic tangent,
   and the full Newton step from there raises |R| 10 to 130 times (measured) on its way into the
   quadratic basin (one element switching between plastic and elastic). The backtracking search
   crept at lambda = 0.01 to 0.1 for 16 to 25 iterations a step instead (the U-channel's release,
   doc/notes/forming-log.md). The watchdog takes such a step and costs one iteration where the step leads
   nowhere. Why not everywhere: with contact it was measured worse (a full step that raises |R|
   there mostly changes the active set; the U-channel's draw: 1 800 more iterations, most relaxed
   steps reverted); and where the equilibrium is not unique its long steps can land on another
   branch: a Hill 1948 tension bar pulled at 45 degrees to the rolling direction past its
   necking (tests/test_umat.sh) ended at a force 2.6 % lower with the watchdog, both converged.
   An unloading from a converged state, as the release by nodal forces, has the one answer.
   The state restarts with every Newton solve (a load step, a retry, a loop of the augmented
   Lagrangian, whose residual has other multipliers). The line search's pre-check is called as
   PETSc's line searches call it. */
#ifndef ATRITO_LINESEARCH_H
#define ATRITO_LINESEARCH_H
#include <petscsnes.h>

typedef struct _n_NewtonLineSearch *NewtonLineSearch;

/* reads -newton_watchdog, -newton_linesearch_rise, -newton_linesearch_alpha,
   -newton_linesearch_contact, -newton_linesearch_eta and -newton_linesearch_max_it; *nls is NULL
   when neither search is used anywhere (or -snes_linesearch_type is given) */
PetscErrorCode NewtonLineSearchCreate(MPI_Comm comm, NewtonLineSearch *nls);
/* at a stage's start: whether a tool is present, whether the stage releases tools by nodal forces;
   makes the SNES's line search this one (a shell line search) where -newton_watchdog or
   -newton_linesearch_contact asks for it,
   else gives back the one it replaced (with its options); nothing when nls is NULL */
PetscErrorCode NewtonLineSearchSetStage(NewtonLineSearch nls, SNES snes, PetscBool contact, PetscBool nodal_release);
/* whether the current stage uses the energy line search (-newton_linesearch_contact energy) */
PetscBool      NewtonLineSearchEnergy(NewtonLineSearch nls);
/* the problem's count of residual evaluations outside its domain (the energy search shortens the
   step where it grows) */
PetscErrorCode NewtonLineSearchSetFailureCounter(NewtonLineSearch nls, const PetscInt *nfail);
/* the longest step x - lambda y along the Newton direction that the geometry allows (lmax; the
   energy search starts there when it is below 1) */
PetscErrorCode NewtonLineSearchSetStepLimit(NewtonLineSearch nls, PetscErrorCode (*limit)(void *, Vec, Vec, PetscReal *), void *ctx);
/* the watchdog's relaxed steps, those of them reverted, and its residual evaluations */
PetscErrorCode NewtonLineSearchGetCounts(NewtonLineSearch nls, PetscInt *relaxed, PetscInt *reverted, PetscInt *trials);
/* the energy search's searches, residual evaluations, searches whose first trial the step limit
   shortened, and searches that fell back to backtracking on |R| (not a descent direction) */
PetscErrorCode NewtonLineSearchGetEnergyCounts(NewtonLineSearch nls, PetscInt *searches, PetscInt *trials, PetscInt *limited, PetscInt *fallback);
PetscErrorCode NewtonLineSearchDestroy(NewtonLineSearch *nls);
#endif
