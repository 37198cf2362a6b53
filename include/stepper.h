/* The load stepper: the process time t from 0 to T through the stages (stage.h; without stages
   one stage, t = the load parameter from 0 to 1) in increments that grow after easy steps and are
   cut after failed ones; a step lands exactly on every stage end and, with -load_kinks, on every
   kink of every curve of the process time (tool paths and amplitudes, condition amplitudes), and
   the extrapolation predictor is not used across a kink. Per step the predictor, the Newton solve
   (with the frame seeds of eqs 28-30 updated at every iteration and an optional stall test), the
   chattering check, and on convergence the commit, the result rows, the fields and the
   checkpoint. At a stage's start the tools absent in it are removed (a warning names the force
   a removed tool carried) and its conditions switched on or off. */
#ifndef ATRITO_STEPPER_H
#define ATRITO_STEPPER_H
#include "problem.h"
#include "results.h"
#include "stage.h"
#include "linesearch.h"
#include "activeset.h"

typedef enum { PREDICTOR_NONE = 0, PREDICTOR_EXTRAPOLATE, PREDICTOR_TANGENT, PREDICTOR_AUTO } Predictor;

typedef struct {
  /* options */
  PetscReal dt0, dt_min, dt_max, cut, grow, shrink;
  PetscInt  grow_its, shrink_its, max_cuts, max_steps;
  Predictor predictor;
  PetscReal curvature;     /* -load_predictor_curvature: the share of the quadratic term added to
                              the extrapolation (0: the linear extrapolation)                    */
  Vec       Uprev2;        /* the converged state before Uprev, at dl_prev2 before it (curvature) */
  PetscReal dl_prev2;      /* (0: none yet, or a restart from a checkpoint without it: linear)   */
  PetscInt  stall_its;     /* Newton has stalled when |R| did not fall below stall_factor times */
  PetscReal stall_factor;  /* its value stall_its iterations earlier (0: no test)              */
  PetscReal force_tol;     /* -newton_force_tol: Newton has converged also when |R| is below this
                              fraction of the internal forces' scale (ProblemForceScale; 0: no) */
  PetscReal floor_tol;     /* -newton_floor_tol: a solve whose line search fails on a Newton
                              correction below this fraction of the model's size has converged
                              (the residual at its floor; 0: never)                          */
  PetscReal floor_force_tol; /* -newton_floor_force_tol: ... and only when |R| is below this
                              fraction of the internal forces' scale (ProblemForceScale): a
                              small correction on a large residual is a kink, not the floor   */
  PetscReal model_size;    /* the diagonal of the mesh's bounding box                          */
  PetscInt  nfloor;        /* solves accepted so                                              */
  PetscInt  njump;         /* solves that ended so on a correction as small but a residual
                              above -newton_floor_force_tol of the forces' scale (cut)       */
  PetscBool domain_backtrack; /* -newton_domain_backtrack: a failed trial point of PETSc's
                              backtracking search is rejected, not the end of the solve       */
  PetscBool chatter_check; /* a step whose last Newton iteration changed the active set fails  */
  PetscBool monitor;       /* -newton_monitor_contact: one line per Newton iteration            */
  PetscReal step_depth;    /* -newton_step_depth: the energy search's contact step limit        */
  PetscBool pred_contact;  /* -load_predictor_contact: the predictor keeps the pressed nodes' gaps */
  PetscInt  keep_contact;  /* the first Newton iteration holds the committed pressed nodes closed:
                              0 no, 1 on frictionless tools, 2 and on frictional tools moved by
                              a prescribed displacement, 3 and on those at rest too
                              (-newton_keep_contact none, frictionless, moving, all) */
  PetscBool keep_contact_set; /* given by the option (else: 1, and 2 with -contact_augmented) */
  PetscReal r_true0;       /* |R| at the start of the solve with the true contact law (< 0: none) */
  PetscReal ksp_target;    /* -newton_ksp_target: a Newton iteration's linear solve stops at this
                              fraction of the Newton tolerance (0: at -ksp_rtol only)           */
  PetscReal ksp_rtol0;     /* -ksp_rtol as set, restored after every Newton solve             */
  PetscReal newton_tol;    /* the Newton solve's tolerance max(atol, rtol |R_0|)               */
  NewtonLineSearch nls;    /* -newton_watchdog: the watchdog line search, or NULL             */
  NewtonActiveSet  aset;   /* -newton_active_set: the active-set correction, or NULL          */
  /* the Newton monitor */
  Problem  *pb;
  PetscBool stalled;
  PetscReal stall_fnorm;
  PetscReal fnorm_hist[256];
  PetscBool kry_on;        /* an iterative linear solver: its Krylov iterations are counted   */
  PetscInt  kry_sum, kry_max; /* in the step's converged attempt: total, most in one Newton iteration */
  /* the augmented Lagrangian of the current step: Newton solves, failure, last update */
  PetscInt  aug_loops;
  PetscBool aug_failed;
  PetscReal aug_pen, aug_dlam;
  /* stages and curves of the process time */
  Stages    stages;
  PetscBool kinks, kinks_set; /* land on every kink, no extrapolation across one (-load_kinks) */
  Predictor kink_predictor;   /* the start of a step at a kink: PREDICTOR_NONE or _TANGENT      */
  BCs      *bcs;
  Contact   contact;
  Vec       Uhold;            /* the bases of the holding conditions (BCHold), or NULL         */
} Stepper;

/* the curvature correction of the extrapolation predictor (predictor.c): U += beta h (h + d1)
   [Uc, U1, U2], the second divided difference of the last three converged states at the increments
   d1 (Uc - U1) and d2 (U1 - U2); h the step's increment; W a work vector */
PetscErrorCode PredictorCurvature(Vec U, Vec Uc, Vec U1, Vec U2, PetscReal h, PetscReal d1, PetscReal d2, PetscReal beta, Vec W);
/* -load_*, -newton_stall_*, -contact_chatter_check, the stages (-stage_*) */
PetscErrorCode StepperSetFromOptions(MPI_Comm comm, Stepper *st);
/* after every module has read its options: the stages' names against the tools and conditions,
   the conditions that stages switch (before BCComputeMask), the total time */
PetscErrorCode StepperSetUp(Stepper *st, BCs *bcs, Contact contact);
/* runs the load steps from the start or from the checkpoint of -restart */
PetscErrorCode StepperRun(Stepper *st, Problem *pb, Results *res);
#endif
