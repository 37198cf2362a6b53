/* The curvature correction of the extrapolation predictor (-load_predictor_curvature, stepper.h).

   The extrapolation of the last two converged states, U_lin(t) = Uc + (t - t0) (Uc - U1)/d1, is
   the first-order Newton interpolant through (t0, Uc), (t1, U1), t1 = t0 - d1. The third
   converged state (t2, U2), t2 = t1 - d2, adds the second-order term

       U_quad(t) = U_lin(t) + (t - t0)(t - t1) [Uc, U1, U2],
       [Uc, U1, U2] = ((Uc - U1)/d1 - (U1 - U2)/d2) / (d1 + d2)   (second divided difference),

   so that at the step's end t = t0 + h the correction is h (h + d1) [Uc, U1, U2]. The predictor
   adds beta times it: beta = 0 is the paper's linear extrapolation, beta = 1 the quadratic one.
   Measured on the hemisphere cases (doc/notes/performance-log.md, Newton iterations): the quadratic term
   takes most of the extrapolation's error away from the contact zone's edge, but at the edge,
   where a node's path has a kink when it touches the tool, the linear extrapolation leaves the
   nodes entering contact up to 0.12 mm inside the punch and the quadratic one leaves nodes pressed
   in the committed state up to 0.13 mm off it: half of the term sits between the two. */
#include "stepper.h"

PetscErrorCode PredictorCurvature(Vec U, Vec Uc, Vec U1, Vec U2, PetscReal h, PetscReal d1, PetscReal d2, PetscReal beta, Vec W)
{
  PetscFunctionBeginUser;
  PetscCheck(h > 0 && d1 > 0 && d2 > 0, PetscObjectComm((PetscObject)U), PETSC_ERR_ARG_OUTOFRANGE, "PredictorCurvature: increments h %g, d1 %g, d2 %g must be positive", (double)h, (double)d1, (double)d2);
  if (beta == 0) PetscFunctionReturn(0);
  /* W = (Uc - U1)/d1 - (U1 - U2)/d2 */
  PetscCall(VecAXPBYPCZ(W, 1.0 / d1, -(1.0 / d1 + 1.0 / d2), 0.0, Uc, U1));
  PetscCall(VecAXPY(W, 1.0 / d2, U2));
  PetscCall(VecAXPY(U, beta * h * (h + d1) / (d1 + d2), W));
  PetscFunctionReturn(0);
}
