/* The curvature correction of the extrapolation predictor (src/process/predictor.c) against closed
   forms: on a quadratic path U(t) = a + b t + c t^2 the linear extrapolation plus the full term
   (beta = 1) is exact at any step's end, whatever the three increments; beta scales the term
   (beta = 0.5: the middle of the linear and the quadratic extrapolations); on a linear path the
   term vanishes; the increments must be positive. */
#include <math.h>
#include <stdio.h>
#include <string.h>
#include "stepper.h"
#include "testcapture.h"

static int nfail = 0;
static void Ok(int cond, const char *what)
{
  if (!cond) nfail++;
  PetscPrintf(PETSC_COMM_WORLD, "%s - %s\n", cond ? "ok" : "not ok", what);
}

/* U(t)_i = a_i + b_i t + c_i t^2 */
static PetscErrorCode Path(Vec U, PetscReal t, PetscReal quad)
{
  PetscInt     lo, hi;
  PetscScalar *u;

  PetscFunctionBeginUser;
  PetscCall(VecGetOwnershipRange(U, &lo, &hi));
  PetscCall(VecGetArray(U, &u));
  for (PetscInt i = lo; i < hi; i++) u[i - lo] = 0.3 * i - 1.0 + (0.7 - 0.05 * i) * t + quad * (1.5 + 0.2 * i) * t * t;
  PetscCall(VecRestoreArray(U, &u));
  PetscFunctionReturn(0);
}

/* the predictor at t0 + h from the states at t0, t0 - d1, t0 - d1 - d2: its largest difference
   from (1 - beta) U_lin + beta U(t0 + h), U_lin the linear extrapolation */
static PetscErrorCode Check(PetscReal t0, PetscReal h, PetscReal d1, PetscReal d2, PetscReal beta, PetscReal quad, PetscReal *err)
{
  Vec Uc, U1, U2, U, W, E, L;

  PetscFunctionBeginUser;
  PetscCall(VecCreateMPI(PETSC_COMM_WORLD, PETSC_DECIDE, 7, &Uc));
  PetscCall(VecDuplicate(Uc, &U1));
  PetscCall(VecDuplicate(Uc, &U2));
  PetscCall(VecDuplicate(Uc, &U));
  PetscCall(VecDuplicate(Uc, &W));
  PetscCall(VecDuplicate(Uc, &E));
  PetscCall(VecDuplicate(Uc, &L));
  PetscCall(Path(Uc, t0, quad));
  PetscCall(Path(U1, t0 - d1, quad));
  PetscCall(Path(U2, t0 - d1 - d2, quad));
  PetscCall(Path(E, t0 + h, quad));
  /* as the stepper: the linear extrapolation, then the correction */
  PetscCall(VecAXPBYPCZ(L, -h / d1, h / d1, 0.0, U1, Uc));
  PetscCall(VecAXPY(L, 1.0, Uc));
  PetscCall(VecCopy(L, U));
  PetscCall(PredictorCurvature(U, Uc, U1, U2, h, d1, d2, beta, W));
  /* expected: (1 - beta) L + beta E */
  PetscCall(VecAXPBY(E, 1.0 - beta, beta, L));
  PetscCall(VecAXPY(U, -1.0, E));
  PetscCall(VecNorm(U, NORM_INFINITY, err));
  PetscCall(VecDestroy(&Uc));
  PetscCall(VecDestroy(&U1));
  PetscCall(VecDestroy(&U2));
  PetscCall(VecDestroy(&U));
  PetscCall(VecDestroy(&W));
  PetscCall(VecDestroy(&E));
  PetscCall(VecDestroy(&L));
  PetscFunctionReturn(0);
}

int main(int argc, char **argv)
{
  char      what[256];
  PetscReal err;
  const PetscReal cases[4][4] = {{0.3, 0.05, 0.05, 0.05}, {0.41, 0.05, 0.0375, 0.025}, {0.7, 0.02, 0.08, 0.01}, {0.9, 0.1, 0.0125, 0.3}}; /* t0, h, d1, d2 */

  PetscCall(PetscInitialize(&argc, &argv, NULL, NULL));
  for (int k = 0; k < 4; k++) {
    const PetscReal *c = cases[k];
    PetscCall(Check(c[0], c[1], c[2], c[3], 1.0, 1.0, &err));
    snprintf(what, sizeof(what), "quadratic path, beta 1: exact at t0 + h (t0 %g, h %g, d1 %g, d2 %g): error %.2e", (double)c[0], (double)c[1], (double)c[2], (double)c[3], (double)err);
    Ok(err < 1e-12, what);
    PetscCall(Check(c[0], c[1], c[2], c[3], 0.5, 1.0, &err));
    snprintf(what, sizeof(what), "quadratic path, beta 0.5: the middle of the linear and the quadratic extrapolations (t0 %g): error %.2e", (double)c[0], (double)err);
    Ok(err < 1e-12, what);
    PetscCall(Check(c[0], c[1], c[2], c[3], 1.0, 0.0, &err));
    snprintf(what, sizeof(what), "linear path: no correction (t0 %g): error %.2e", (double)c[0], (double)err);
    Ok(err < 1e-13, what);
  }
  PetscCall(Check(0.5, 0.05, 0.05, 0.05, 0.0, 1.0, &err));
  snprintf(what, sizeof(what), "beta 0: the linear extrapolation unchanged: error %.2e", (double)err);
  Ok(err == 0, what);
  {
    Vec            U;
    PetscErrorCode ierr;
    PetscCall(VecCreateMPI(PETSC_COMM_WORLD, PETSC_DECIDE, 3, &U));
    ErrMsg[0] = 0;
    PetscCall(PetscPushErrorHandler(CaptureHandler, NULL));
    ierr = PredictorCurvature(U, U, U, U, 0.1, 0.1, 0.0, 0.5, U);
    PetscCall(PetscPopErrorHandler());
    snprintf(what, sizeof(what), "a zero increment d2 is refused: %s", ErrMsg);
    Ok(ierr != 0 && strstr(ErrMsg, "d2") != NULL, what);
    PetscCall(VecDestroy(&U));
  }
  PetscCall(PetscFinalize());
  return nfail ? 1 : 0;
}
