/* Newton's active-set correction of contact (src/solver/activeset.c; doc/solvers.md, Newton;
   measurements: doc/notes/contact-defaults.md, "Nodes leaving contact within a Newton iteration").

   The penalty law makes each slave node's normal force a function t_N(g) that vanishes on the open
   side; the Newton direction y solves the system linearised at the iterate x, where each node in
   contact is linearised as if it stayed in contact. Along the step x - y a node may be pulled
   (its linearised normal force t_N + dt_N/dy . (-y) < 0): in the next iteration it is open, its
   neighbours lose its support, some of them are pulled in turn, and so on: a sheet peeling off a
   flat tool loses a row of nodes per Newton iteration, and Newton converges linearly over them
   (doc/notes/contact-defaults.md). The correction solves the linearised problem with the nodes'
   complementarity instead, as a semismooth Newton method solves its linear model: the pulled
   nodes are taken out of the linear system (their residual r_i and Jacobian block M_i, on their
   free components and the force-driven directions of their tool), the direction recomputed, and
   again while the new direction pulls further nodes in contact. The modified system is J - U M U^T
   with U the columns of the released unknowns D, and by the Sherman-Morrison-Woodbury formula

       y' = y + W c,   W = J^-1 U,   c = -dR + M (I - A M)^-1 (y_D - A dR),   A = U^T W,

   dR the released residual: |D| solves with the factorisation of J (a direct solver; with an
   iterative one the correction is off by default), and a dense |D| x |D| system. Nodes only
   leave: a node released in the linear model stays released for the iteration, and the next
   Newton iteration (the true law at the new iterate) decides again. It applies once |R| is at
   most _rtol (0.1) of the internal forces' scale F: far from the solution the linearisation's
   pulled nodes are not those that leave (measured: 60 to 80 released per iteration that the true
   law keeps, and a stall). A pull weaker than 1e-8 F is round-off (a tool whose force has gone to
   zero): not released, so that the rank count's round-off does not decide. Options:
   -newton_active_set off | direct (the default: with a direct linear solver) | always; _rtol;
   _max_dofs, the most released unknowns per Newton iteration (and at most 25e6 values of W);
   _max_it, the most rounds of release; _monitor; _verify. */
#ifndef ATRITO_ACTIVESET_H
#define ATRITO_ACTIVESET_H
#include <petscksp.h>
#include "problem.h"

typedef struct _n_NewtonActiveSet *NewtonActiveSet;

/* reads -newton_active_set, _max_dofs, _max_it, _rtol, _monitor, _verify; *as NULL when off */
PetscErrorCode NewtonActiveSetCreate(MPI_Comm comm, NewtonActiveSet *as);
/* correct the Newton direction Y (the step X - Y; F the residual at X, fnorm its norm) for the
   nodes its linearisation pulls off their tools; *changed when it did. ksp holds the factorisation
   of the Jacobian that gave Y; zrows[nz]: this rank's rows of the conditions a stage switched on,
   sorted (identity rows and columns of that Jacobian). Collective */
PetscErrorCode NewtonActiveSetApply(NewtonActiveSet as, Problem *pb, KSP ksp, PetscInt nz, const PetscInt *zrows, Vec F, PetscReal fnorm, Vec Y, PetscBool *changed);
/* released nodes and their solves over the run, and the Newton iterations corrected */
PetscErrorCode NewtonActiveSetGetCounts(NewtonActiveSet as, PetscInt *corrected, PetscInt *released, PetscInt *solves);
PetscErrorCode NewtonActiveSetDestroy(NewtonActiveSet *as);
#endif
