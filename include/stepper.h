/* The load stepper: the load parameter lambda from 0 to 1 in increments that grow after easy
   steps and are cut after failed ones; per step the predictor, the Newton solve (with the frame
   seeds of eqs 28-30 updated at every iteration and an optional stall test), the chattering
   check, and on convergence the commit, the result rows, the fields and the checkpoint. */
#ifndef ATRITO_STEPPER_H
#define ATRITO_STEPPER_H
#include "problem.h"
#include "results.h"

typedef enum { PREDICTOR_NONE = 0, PREDICTOR_EXTRAPOLATE, PREDICTOR_TANGENT, PREDICTOR_AUTO } Predictor;

typedef struct {
  /* options */
  PetscReal dt0, dt_min, dt_max, cut, grow;
  PetscInt  grow_its, max_cuts, max_steps;
  Predictor predictor;
  PetscInt  stall_its;     /* Newton has stalled when |R| did not fall below stall_factor times */
  PetscReal stall_factor;  /* its value stall_its iterations earlier (0: no test)              */
  PetscBool chatter_check; /* a step whose last Newton iteration changed the active set fails  */
  /* the Newton monitor */
  Problem  *pb;
  PetscBool stalled;
  PetscReal stall_fnorm;
  PetscReal fnorm_hist[256];
  /* the augmented Lagrangian of the current step: Newton solves, failure, last update */
  PetscInt  aug_loops;
  PetscBool aug_failed;
  PetscReal aug_pen, aug_dlam;
} Stepper;

/* -load_*, -newton_stall_*, -contact_chatter_check */
PetscErrorCode StepperSetFromOptions(MPI_Comm comm, Stepper *st);
/* runs the load steps from the start or from the checkpoint of -restart */
PetscErrorCode StepperRun(Stepper *st, Problem *pb, Results *res);
#endif
