/* The load stepper (stepper.h): increments of the process time with growth and cut-back, the
   stages and the kinks of the curves of the process time, the predictor, the Newton solve with the
   frame recurrence at every iteration and the stall test, the chattering check, the commit and
   the results of every converged step. */
#include <math.h>
#include <string.h>
#include "stepper.h"
#include "options.h"
#include "linesearch.h"

PetscErrorCode StepperSetFromOptions(MPI_Comm comm, Stepper *st)
{
  PetscFunctionBeginUser;
  PetscCall(PetscMemzero(st, sizeof(*st)));
  st->dt0           = 0.1;
  st->dt_min        = 1e-6;
  st->cut           = 0.5;
  st->grow          = 1.5;
  st->grow_its      = 5;
  st->curvature     = 0.5;
  st->shrink        = 0.5;
  st->shrink_its    = 0;
  st->max_cuts      = 10;
  st->stall_its     = 0;
  st->ksp_target    = 0;
  st->stall_factor  = 0.9;
  st->force_tol     = 1e-6;
  st->floor_tol     = 1e-9;
  st->floor_force_tol = 1e-6;
  st->domain_backtrack = PETSC_TRUE;
  st->max_steps     = 100000;
  st->predictor     = PREDICTOR_AUTO;
  st->chatter_check = PETSC_TRUE;
  st->pred_contact  = PETSC_TRUE;
  st->step_depth    = 1;
  st->keep_contact  = 1;
  st->r_true0       = -1;
  st->kink_predictor = PREDICTOR_AUTO;
  PetscOptionsBegin(comm, NULL, "Load stepping and Newton", NULL);
    {
      PetscInt steps = 10;
      PetscCall(PetscOptionsInt("-load_steps", "Initial number of load steps (first increment 1/N)", NULL, steps, &steps, NULL));
      PetscCheck(steps >= 1, comm, PETSC_ERR_USER_INPUT, "-load_steps %" PetscInt_FMT " must be >= 1", steps);
      st->dt0 = 1.0 / steps;
    }
    st->dt_max = st->dt0;
    PetscCall(PetscOptionsReal("-load_dt_max", "Largest load increment", NULL, st->dt_max, &st->dt_max, NULL));
    PetscCall(PetscOptionsReal("-load_dt_min", "Smallest load increment before the run stops", NULL, st->dt_min, &st->dt_min, NULL));
    PetscCall(PetscOptionsReal("-load_cut_factor", "Increment factor after a failed step", NULL, st->cut, &st->cut, NULL));
    PetscCall(PetscOptionsReal("-load_grow_factor", "Increment factor after an easy step", NULL, st->grow, &st->grow, NULL));
    PetscCall(PetscOptionsInt("-load_grow_its", "A step is easy when Newton took at most this many iterations", NULL, st->grow_its, &st->grow_its, NULL));
    PetscCall(PetscOptionsInt("-load_shrink_its", "A converged step is hard when Newton took more than this many iterations: the next increment is multiplied by -load_shrink_factor (0: never)", NULL, st->shrink_its, &st->shrink_its, NULL));
    PetscCall(PetscOptionsReal("-load_shrink_factor", "Increment factor after a hard step (see -load_shrink_its)", NULL, st->shrink, &st->shrink, NULL));
    PetscCall(PetscOptionsInt("-load_max_cuts", "Successive cuts allowed in one step", NULL, st->max_cuts, &st->max_cuts, NULL));
    PetscCall(PetscOptionsInt("-load_max_steps", "Largest number of converged steps", NULL, st->max_steps, &st->max_steps, NULL));
    PetscCall(PetscOptionsInt("-newton_stall_its", "Newton has stalled (the step fails at once) when |R| has not fallen below -newton_stall_factor times its value this many iterations earlier (0: never)", NULL, st->stall_its, &st->stall_its, NULL));
    PetscCall(PetscOptionsReal("-newton_stall_factor", "See -newton_stall_its", NULL, st->stall_factor, &st->stall_factor, NULL));
    PetscCall(PetscOptionsReal("-newton_force_tol", "Newton has converged also when |R| is below this fraction of the internal forces' scale, sqrt(sum over the elements of |f_e|^2) (for steps whose initial residual is itself near equilibrium, where -snes_rtol asks for round-off; 0: -snes_rtol and -snes_atol only)", NULL, st->force_tol, &st->force_tol, NULL));
    PetscCheck(st->force_tol >= 0 && st->force_tol < 1, comm, PETSC_ERR_USER_INPUT, "-newton_force_tol %g must lie in [0, 1)", (double)st->force_tol);
    PetscCall(PetscOptionsBool("-newton_domain_backtrack", "In PETSc's backtracking line search a trial point where the residual cannot be evaluated (an element inverted, a return map or a contact projection that did not converge) is rejected and the step shortened, instead of ending the Newton solve and cutting the load step", NULL, st->domain_backtrack, &st->domain_backtrack, NULL));
    PetscCall(PetscOptionsReal("-newton_floor_tol", "A Newton solve whose line search fails has converged when the Newton correction's largest component is below this fraction of the model's size (the diagonal of the mesh's box): the residual is at the floor that the local solvers' tolerances leave, and no step along the correction lowers it (0: the step is cut instead)", NULL, st->floor_tol, &st->floor_tol, NULL));
    PetscCheck(st->floor_tol >= 0 && st->floor_tol < 1e-3, comm, PETSC_ERR_USER_INPUT, "-newton_floor_tol %g must lie in [0, 1e-3)", (double)st->floor_tol);
    PetscCall(PetscOptionsReal("-newton_floor_force_tol", "The residual's floor (-newton_floor_tol) is accepted only when |R| is also below this fraction of the internal forces' scale, sqrt(sum over the elements of |f_e|^2): a small Newton correction on a large residual is a point where the residual is not smooth (a node at the kink of the contact law at gap 0, or at the edge of a tool's range), not its floor, and the step is cut", NULL, st->floor_force_tol, &st->floor_force_tol, NULL));
    PetscCheck(st->floor_force_tol > 0 && st->floor_force_tol < 1e-2, comm, PETSC_ERR_USER_INPUT, "-newton_floor_force_tol %g must lie in (0, 1e-2)", (double)st->floor_force_tol);
    {
      const char *preds[] = {"none", "extrapolate", "tangent", "auto", "Predictor", "PREDICTOR_", NULL};
      PetscInt    p       = (PetscInt)st->predictor;
      PetscCall(PetscOptionsEList("-load_predictor", "Start of each step: the committed state, the extrapolation of the last two, the tangent response to the load increment, or auto (extrapolation when there is a previous step, else tangent)", NULL, preds, 4, preds[p], &p, NULL));
      st->predictor = (Predictor)p;
    }
    PetscCall(PetscOptionsReal("-load_predictor_curvature", "Extrapolation predictor: the share beta of the quadratic term through the last three converged states added to the linear extrapolation (0: linear, 1: quadratic; default 0.5: doc/notes/contact-defaults.md)", NULL, st->curvature, &st->curvature, NULL));
    PetscCheck(st->curvature >= 0 && st->curvature <= 1, comm, PETSC_ERR_USER_INPUT, "-load_predictor_curvature %g must lie in [0, 1]", (double)st->curvature);
    PetscCheck(st->dt_max > 0 && st->dt_max <= 1, comm, PETSC_ERR_USER_INPUT, "-load_dt_max %g must lie in (0, 1]", (double)st->dt_max);
    PetscCheck(st->dt_min > 0 && st->dt_min <= PetscMin(st->dt0, st->dt_max), comm, PETSC_ERR_USER_INPUT, "-load_dt_min %g must lie in (0, first increment %g] (1/-load_steps within -load_dt_max)", (double)st->dt_min, (double)PetscMin(st->dt0, st->dt_max));
    PetscCheck(st->cut > 0 && st->cut < 1, comm, PETSC_ERR_USER_INPUT, "-load_cut_factor %g must lie in (0, 1)", (double)st->cut);
    PetscCheck(st->grow >= 1 && PetscIsNormalReal(st->grow), comm, PETSC_ERR_USER_INPUT, "-load_grow_factor %g must be >= 1", (double)st->grow);
    PetscCheck(st->shrink_its >= 0, comm, PETSC_ERR_USER_INPUT, "-load_shrink_its %" PetscInt_FMT " must be >= 0", st->shrink_its);
    PetscCheck(st->shrink > 0 && st->shrink <= 1, comm, PETSC_ERR_USER_INPUT, "-load_shrink_factor %g must lie in (0, 1]", (double)st->shrink);
    PetscCheck(st->max_cuts >= 0, comm, PETSC_ERR_USER_INPUT, "-load_max_cuts %" PetscInt_FMT " must be >= 0", st->max_cuts);
    PetscCheck(st->max_steps >= 1, comm, PETSC_ERR_USER_INPUT, "-load_max_steps %" PetscInt_FMT " must be >= 1", st->max_steps);
    PetscCheck(st->stall_its >= 0 && st->stall_its < 256, comm, PETSC_ERR_USER_INPUT, "-newton_stall_its %" PetscInt_FMT " must lie in [0, 255]", st->stall_its);
    PetscCheck(st->stall_factor > 0 && st->stall_factor <= 1, comm, PETSC_ERR_USER_INPUT, "-newton_stall_factor %g must lie in (0, 1]", (double)st->stall_factor);
    PetscCall(PetscOptionsReal("-newton_ksp_target", "Iterative linear solvers: a Newton iteration's linear solve stops once its relative residual is below the larger of -ksp_rtol and this fraction of the Newton tolerance over |R| (the last iteration need not solve beyond the tolerance; 0: -ksp_rtol only)", NULL, st->ksp_target, &st->ksp_target, NULL));
    PetscCheck(st->ksp_target >= 0 && st->ksp_target < 1, comm, PETSC_ERR_USER_INPUT, "-newton_ksp_target %g must lie in [0, 1)", (double)st->ksp_target);

  {
    const char *kc[] = {"none", "frictionless", "moving", "all", "KeepContact", "KEEP_", NULL};
    PetscCall(PetscOptionsEList("-newton_keep_contact", "The first Newton iteration of a step (its residual and Jacobian) holds the nodes pressed in the committed state in contact (bilateral) whatever the predictor's gap, the line search and later iterations use the true law: on no tool, on frictionless tools, on those and the frictional tools moved by the step's prescribed displacement (moving), or on those and the frictional tools at rest in the step (all; never a force-driven tool); a held node on a frictional tool keeps the friction of its committed force and a tangential spring anchored at the predictor, and nodes entering contact have no friction in that iteration; default frictionless, moving with -contact_augmented", "doc/solvers.md", kc, 4, kc[st->keep_contact], &st->keep_contact, &st->keep_contact_set));
  }
  PetscCall(PetscOptionsBool("-load_predictor_contact", "The predictor of a step moves every node pressed on a tool in the committed state along the tool's normal to its committed gap (the extrapolation or the tangent leave lightly pressed nodes open or pushed in)", NULL, st->pred_contact, &st->pred_contact, NULL));
  PetscCall(PetscOptionsReal("-newton_step_depth", "Energy line search: the Newton step is shortened so that no slave node goes deeper into its tool than this many element sizes normal to the contact face (0: no limit)", NULL, st->step_depth, &st->step_depth, NULL));
  PetscCheck(st->step_depth >= 0, comm, PETSC_ERR_USER_INPUT, "-newton_step_depth %g must be >= 0", (double)st->step_depth);
  PetscCall(PetscOptionsBool("-newton_monitor_contact", "One line per Newton iteration: |R| against the internal forces' scale, and per tool the nodes that entered and left contact in the iteration (with the largest normal force among them), the nodes pressed, the largest penetration", NULL, st->monitor, &st->monitor, NULL));
  PetscCall(PetscOptionsBool("-contact_chatter_check", "Fail (and cut) a step whose last Newton iteration still moved a node into or out of contact with a normal force above 1e-3 of the largest and above the Newton tolerance", NULL, st->chatter_check, &st->chatter_check, NULL));
  PetscCall(PetscOptionsBool("-load_kinks", "Land a step on every kink of every curve of the process time (tool paths and amplitudes, condition amplitudes) and never extrapolate across one (default: with stages or an amplitude curve)", NULL, st->kinks, &st->kinks, &st->kinks_set));
  {
    const char     *kp[] = {"none", "tangent", "auto", "KinkPredictor", "KINK_", NULL};
    const Predictor kv[] = {PREDICTOR_NONE, PREDICTOR_TANGENT, PREDICTOR_AUTO};
    PetscInt        p    = st->kink_predictor == PREDICTOR_NONE ? 0 : (st->kink_predictor == PREDICTOR_TANGENT ? 1 : 2);
    PetscCall(PetscOptionsEList("-load_kink_predictor", "Start of a step at a kink or a stage's start (-load_kinks, with -load_predictor auto or extrapolate): the committed state, the tangent predictor, or auto (of the two, the one with the smaller residual at the step's end)", NULL, kp, 3, kp[p], &p, NULL));
    st->kink_predictor = kv[p];
  }
  PetscOptionsEnd();
  PetscCall(NewtonLineSearchCreate(comm, &st->nls));
  PetscCall(NewtonActiveSetCreate(comm, &st->aset));
  {
    PetscInt steps = (PetscInt)(1.0 / st->dt0 + 0.5);
    PetscCall(StagesSetFromOptions(comm, &st->stages, steps, st->dt_max, st->dt_min));
  }
  PetscFunctionReturn(0);
}

PetscErrorCode StepperSetUp(Stepper *st, BCs *bcs, Contact contact)
{
  PetscBool amp = PETSC_FALSE;

  PetscFunctionBeginUser;
  st->bcs     = bcs;
  st->contact = contact;
  PetscCall(StagesSetUp(&st->stages, bcs, contact));
  for (PetscInt b = 0; b < bcs->n; b++)
    if (bcs->bc[b].amp.n > 0) amp = PETSC_TRUE;
  for (PetscInt t = 0; t < ContactNumTools(contact); t++) {
    const Tool *tl = NULL;
    PetscCall(ContactGetTool(contact, t, &tl));
    if (tl->amp.n > 0) amp = PETSC_TRUE;
  }
  if (!st->kinks_set) st->kinks = (st->stages.given || amp) ? PETSC_TRUE : PETSC_FALSE;
  /* with the augmented Lagrangian the first iteration holds the moving frictional tools' nodes
     too (-newton_keep_contact moving): at the grown penalties the extrapolated predictor's
     micrometres of gap opened the frictional punch's nodes and the line search cut the first
     Newton step; holding the tools at rest as well (all) failed the aluminium cup (doc/contact.md,
     Augmented Lagrangian) */
  if (!st->keep_contact_set && ContactToolsAugmented(contact)) st->keep_contact = 2;
  PetscFunctionReturn(0);
}

/* The first kink strictly after t of every curve of the process time: the conditions'
   amplitudes, the tools' paths and amplitudes, and the force histories of force-driven tools.
   A new kind of curve adds one line here. */
static PetscReal NextKink(const Stepper *st, PetscReal t)
{
  PetscReal k = BCNextKink(st->bcs, t);
  for (PetscInt i = 0; i < ContactNumTools(st->contact); i++) {
    const Tool *tl = NULL;
    if (ContactGetTool(st->contact, i, &tl)) continue;
    k = PetscMin(k, (PetscReal)ToolNextKink(tl, t));
  }
  k = PetscMin(k, ContactNextKink(st->contact, t)); /* force-driven tools */
  return k;
}

/* the end of the next step at most: the stage's end, and with -load_kinks the next kink */
static PetscReal NextLanding(const Stepper *st, PetscInt stage, PetscReal t)
{
  const PetscReal tol = 1e-12 * st->stages.T;
  PetscReal       e   = st->stages.s[stage].t1;
  if (st->kinks) e = PetscMin(e, NextKink(st, t + tol));
  return e;
}

/* t is a kink of a curve or a stage's start (-load_kinks): the extrapolation of the last two
   converged states would cross it */
static PetscBool AtKink(const Stepper *st, PetscReal t)
{
  const PetscReal tol = 1e-12 * st->stages.T;
  if (!st->kinks) return PETSC_FALSE;
  for (PetscInt k = 0; k < st->stages.n; k++)
    if (PetscAbsReal(t - st->stages.s[k].t0) <= tol) return PETSC_TRUE;
  return NextKink(st, t - tol) <= t + tol ? PETSC_TRUE : PETSC_FALSE;
}

/* the residual and the Jacobian of the SNES with the rows of the conditions that stages switch
   on and off (bc.h); installed only when a case has such conditions */
static PetscErrorCode StepperFormFunction(SNES snes, Vec U, Vec F, void *ctx)
{
  Stepper *st = (Stepper *)ctx;

  PetscFunctionBeginUser;
  PetscCall(ProblemFormFunction(snes, U, F, st->pb));
  if (!st->pb->ndomain_err) PetscCall(BCConstrainRows(st->bcs, U, F, st->pb->lambda));
  PetscFunctionReturn(0);
}

static PetscErrorCode StepperFormJacobian(SNES snes, Vec U, Mat J, Mat P, void *ctx)
{
  Stepper *st = (Stepper *)ctx;

  PetscFunctionBeginUser;
  PetscCall(ProblemFormJacobian(snes, U, J, P, st->pb));
  if (!st->pb->ndomain_err) PetscCall(BCConstrainJacobian(st->bcs, P));
  PetscFunctionReturn(0);
}

/* the start of stage k at the committed time t: its tools and conditions. A tool removed while it
   presses on the body (a force above the solution's accuracy) is removed all the same
   (its force is released in the stage's first step), with a warning naming the force it carried. */
static PetscErrorCode EnterStage(Stepper *st, PetscInt k, PetscReal t, PetscBool announce, PetscBool restart)
{
  const Stage *s = &st->stages.s[k];
  PetscReal    F = 0;

  PetscFunctionBeginUser;
  if (announce && st->contact) PetscCall(ProblemForceScale(st->pb, &F));
  for (PetscInt i = 0; i < ContactNumTools(st->contact); i++) {
    const Tool *tl = NULL;
    PetscCall(ContactGetTool(st->contact, i, &tl));
    if (announce && !s->tool_on[i] && !tl->absent) {
      ContactToolResult r;
      PetscCall(ContactGetToolResult(st->contact, i, t, &r));
      const PetscReal fmag = PetscSqrtReal(r.f[0] * r.f[0] + r.f[1] * r.f[1] + r.f[2] * r.f[2]);
      /* a force within the last Newton solve's tolerance, or below -newton_floor_force_tol of
         the internal forces' scale, is zero to the solution's accuracy (a release that ends on a
         node still touching at round-off) */
      if (r.active > 0 && fmag > PetscMax(st->newton_tol, st->floor_force_tol * F))
        PetscCall(PetscPrintf(PETSC_COMM_WORLD, "WARNING: stage %s removes tool %s while it carries a force of %.6e (fx %.6e, fy %.6e, fz %.6e; %" PetscInt_FMT " nodes pressed): released at once in the stage's first step (a stage in which the tool retracts releases it gradually)\n", s->name, tl->name, (double)fmag, r.f[0], r.f[1], r.f[2], r.active));
    }
    /* a release by nodal forces removes the tool and keeps its nodes' forces as loads (a restart
       finds them in the checkpoint) */
    if (s->tool_release[i] && s->release_mode == STAGE_RELEASE_NODES) {
      if (!restart) {
        ContactToolResult r;
        if (announce) PetscCall(ContactGetToolResult(st->contact, i, t, &r)); /* collective: announce is the same on every rank */
        PetscCall(ContactReleaseToolNodes(st->contact, i, s->t0, s->t1));
        if (announce) PetscCall(PetscPrintf(PETSC_COMM_WORLD, "stage %s: tool %s removed, the forces of its %" PetscInt_FMT " pressed nodes (fx %.6e, fy %.6e, fz %.6e) released from time %g to %g\n", s->name, tl->name, r.active, r.f[0], r.f[1], r.f[2], (double)s->t0, (double)s->t1));
      } else PetscCall(ContactSetToolPresent(st->contact, i, PETSC_FALSE));
      continue;
    }
    PetscCall(ContactSetToolPresent(st->contact, i, s->tool_on[i]));
    /* a release starts from the force the tool exerts now (a restart finds it in the checkpoint) */
    if (!restart && s->tool_release[i]) {
      PetscCall(ContactReleaseTool(st->contact, i, s->t0, s->t1));
      if (announce) PetscCall(PetscPrintf(PETSC_COMM_WORLD, "stage %s: tool %s released by force from time %g to %g\n", s->name, tl->name, (double)s->t0, (double)s->t1));
    }
  }
  {
    /* the watchdog line search in a release by nodal forces without contact (linesearch.h) */
    PetscBool contact = PETSC_FALSE;
    for (PetscInt i = 0; i < ContactNumTools(st->contact); i++) {
      const Tool *tl = NULL;
      PetscCall(ContactGetTool(st->contact, i, &tl));
      if (!tl->absent) contact = PETSC_TRUE;
    }
    PetscCall(NewtonLineSearchSetStage(st->nls, st->pb->snes, contact, (s->nrelease > 0 && s->release_mode == STAGE_RELEASE_NODES) ? PETSC_TRUE : PETSC_FALSE));
  }
  for (PetscInt b = 0; b < st->bcs->n; b++) {
    BC *bc = &st->bcs->bc[b];
    /* a holding condition switched on holds its dofs where they are now (on a restart: where the
       checkpoint says it held them) */
    if (bc->hold && !bc->always && s->bc_on[b] && (restart || !bc->active)) PetscCall(BCHold(st->bcs, b, restart ? st->Uhold : st->pb->Uc, st->Uhold));
    bc->active = s->bc_on[b];
  }
  if (announce && st->stages.given) PetscCall(PetscPrintf(PETSC_COMM_WORLD, "stage %s: time %g to %g, first increment %g\n", s->name, (double)s->t0, (double)s->t1, (double)s->dt0));
  PetscFunctionReturn(0);
}

/* Tangent predictor: U = Uc - J(Uc)^-1 [R(Uc, lam_c) + dR/dlam dl], the response of the committed
   state, linearised, to the increment of the prescribed displacements (the derivative along the
   load by a one-sided difference: it only seeds Newton, the Jacobian itself stays exact). */
static PetscErrorCode TangentPredictor(Stepper *st, Problem *pb, Vec R, Vec W, PetscReal lam_c, PetscReal dl, PetscBool *ok)
{
  KSP                 ksp;
  KSPConvergedReason  kr;
  const PetscReal     eps = 1e-6;

  SNES                snes = pb->snes;
  Mat                 J    = pb->J;

  PetscFunctionBeginUser;
  *ok = PETSC_FALSE;
  pb->lambda = lam_c;
  PetscCall(StepperFormJacobian(snes, pb->Uc, J, J, st));
  if (pb->ndomain_err) PetscFunctionReturn(0);
  PetscCall(StepperFormFunction(snes, pb->Uc, W, st));
  pb->lambda = lam_c + eps * dl;
  PetscCall(StepperFormFunction(snes, pb->Uc, R, st));
  if (pb->ndomain_err) PetscFunctionReturn(0);
  /* R <- W + (R - W)/eps */
  PetscCall(VecAXPBY(R, 1.0 - 1.0 / eps, 1.0 / eps, W));
  PetscCall(VecScale(R, -1.0));
  PetscCall(SNESGetKSP(snes, &ksp));
  PetscCall(KSPSetOperators(ksp, J, J));
  PetscCall(KSPSolve(ksp, R, W));
  PetscCall(KSPGetConvergedReason(ksp, &kr));
  if (kr < 0) PetscFunctionReturn(0);
  PetscCall(VecWAXPY(pb->U, 1.0, pb->Uc, W));
  *ok = PETSC_TRUE;
  PetscFunctionReturn(0);
}

/* -newton_monitor_contact: |R|, its ratio to the internal forces' scale, and per tool the status
   changes of the iteration (the last evaluation is the accepted iterate's) */
static PetscErrorCode MonitorContact(Stepper *st, PetscInt it, PetscReal fnorm)
{
  PetscReal          F  = 0;
  const PetscInt     nt = ContactNumTools(st->pb->contact);
  ContactToolStatus *ts;
  char               line[1024];
  size_t             l;

  PetscFunctionBeginUser;
  PetscCall(ProblemForceScale(st->pb, &F));
  PetscCall(PetscSNPrintf(line, sizeof(line), "    %2d |R| %.3e  |R|/F %.2e", (int)it, (double)fnorm, (double)(F > 0 ? fnorm / F : 0)));
  {
    Vec       R;
    PetscReal v, x[3];
    PetscInt  nd, cp;
    PetscCall(SNESGetFunction(st->pb->snes, &R, NULL, NULL));
    PetscCall(ProblemResidualPeak(st->pb, R, &v, &nd, &cp, x));
    PetscCall(PetscStrlen(line, &l));
    PetscCall(PetscSNPrintf(line + l, sizeof(line) - l, "  peak %.2e at node %d %c (%.4g, %.4g, %.4g)", (double)v, (int)nd, "xyz"[cp], (double)x[0], (double)x[1], (double)x[2]));
  }
  if (st->pb->ntu) { /* the tool unknowns' rows */
    Vec       R;
    PetscReal d[3 * 64], m = 0;
    PetscCall(SNESGetFunction(st->pb->snes, &R, NULL, NULL));
    PetscCall(ProblemGetToolValues(st->pb, R, d));
    for (PetscInt k = 0; k < st->pb->ntu; k++) m = PetscMax(m, PetscAbsReal(d[k]));
    PetscCall(PetscStrlen(line, &l));
    PetscCall(PetscSNPrintf(line + l, sizeof(line) - l, "  tools' rows %.2e", (double)m));
  }
  if (nt) {
    PetscCall(PetscMalloc1(nt, &ts));
    PetscCall(ContactStatusChanges(st->pb->contact, ts));
    for (PetscInt t = 0; t < nt; t++) {
      const Tool *tl = NULL;
      PetscCall(ContactGetTool(st->pb->contact, t, &tl));
      PetscCall(PetscStrlen(line, &l));
      PetscCall(PetscSNPrintf(line + l, sizeof(line) - l, "  %s +%d -%d (%.1e) ss %d on %d pen %.1e", tl->name, (int)ts[t].nin, (int)ts[t].nout, (double)ts[t].fchange, (int)ts[t].nslip, (int)ts[t].nactive, (double)ts[t].pen));
    }
    PetscCall(PetscFree(ts));
  }
  PetscCall(PetscPrintf(st->pb->comm, "%s\n", line));
  PetscFunctionReturn(0);
}

/* PETSc's convergence test, and a stall test: the iteration stops as diverged when |R| has not
   fallen below stall_factor times its value stall_its iterations earlier (a step whose active set
   or stick/slip pattern keeps Newton from making progress is cut at once instead of running to the
   iteration limit) */
static PetscErrorCode NewtonConverged(SNES snes, PetscInt it, PetscReal xnorm, PetscReal snorm, PetscReal fnorm, SNESConvergedReason *reason, void *ctx)
{
  Stepper       *pb = (Stepper *)ctx;
  const PetscInt w  = pb->stall_its;

  PetscFunctionBeginUser;
  /* the first iteration's residual is the one of the committed contact set (-newton_keep_contact):
     the tolerances are relative to the true residual at the start, as without it */
  if (it == 0 && pb->r_true0 >= 0) fnorm = pb->r_true0;
  PetscCall(SNESConvergedDefault(snes, it, xnorm, snorm, fnorm, reason, NULL));
  if (pb->pb->cutback) { /* the material asked for a smaller increment: the step fails at once */
    *reason = SNES_DIVERGED_FUNCTION_DOMAIN;
    PetscFunctionReturn(0);
  }
  if (it == 0) pb->stalled = PETSC_FALSE;
  if (*reason == SNES_CONVERGED_ITERATING && it > 0 && pb->force_tol > 0) {
    /* -newton_force_tol: |R| against the internal forces (the last residual assembly was at this
       iterate: the line search evaluates the point it accepts last) rather than against |R_0|,
       which is itself tiny when the step starts near equilibrium */
    PetscReal F = 0;
    PetscCall(ProblemForceScale(pb->pb, &F));
    if (fnorm <= pb->force_tol * F) *reason = SNES_CONVERGED_FNORM_ABS;
  }
  if (it > 0 && pb->kry_on) { /* the linear solve of the iteration just made */
    KSP      ksp;
    PetscInt kits;
    PetscCall(SNESGetKSP(snes, &ksp));
    PetscCall(KSPGetIterationNumber(ksp, &kits));
    pb->kry_sum += kits;
    pb->kry_max = PetscMax(pb->kry_max, kits);
  }
  if (it < 256) pb->fnorm_hist[it] = fnorm;
  if (pb->monitor) PetscCall(MonitorContact(pb, it, fnorm));
  if (pb->kry_on && pb->ksp_target > 0) {
    /* inexact Newton's tail: the next linear solve need only bring |R| well below the Newton
       tolerance tol, not a further factor -ksp_rtol below |R| (at the last iteration |R| is often
       within a few times tol, and reducing it by 1e-3 cost the most Krylov iterations of the
       step: the residual left there sits at the contact zone's edge). Its relative residual
       rtol_k = max(-ksp_rtol, eta tol / |R_k|); near the solution the quadratic term's part of
       the next residual is far below tol, so the linear solve's error is what remains */
    KSP       ksp;
    PetscReal rt, atol, rtol, stol;
    PetscInt  maxit, maxf;
    PetscCall(SNESGetKSP(snes, &ksp));
    if (it == 0) { /* the largest of Newton's tolerances (-snes_atol, -snes_rtol, -newton_force_tol) */
      PetscCall(SNESGetTolerances(snes, &atol, &rtol, &stol, &maxit, &maxf));
      pb->newton_tol = PetscMax(atol, rtol * fnorm);
      if (pb->force_tol > 0) {
        PetscReal F = 0;
        PetscCall(ProblemForceScale(pb->pb, &F));
        pb->newton_tol = PetscMax(pb->newton_tol, pb->force_tol * F);
      }
    }
    rt = pb->ksp_rtol0;
    if (*reason == SNES_CONVERGED_ITERATING && fnorm > 0) rt = PetscMax(rt, PetscMin(0.5, pb->ksp_target * pb->newton_tol / fnorm));
    PetscCall(KSPSetTolerances(ksp, rt, PETSC_DEFAULT, PETSC_DEFAULT, PETSC_DEFAULT)); /* the others as set */
  }
  if (*reason == SNES_CONVERGED_ITERATING && w > 0 && it >= w && it < 256 && !(fnorm < pb->stall_factor * pb->fnorm_hist[it - w])) {
    *reason         = SNES_DIVERGED_DTOL;
    pb->stalled     = PETSC_TRUE;
    pb->stall_fnorm = fnorm;
  }
  PetscFunctionReturn(0);
}

/* the line search's pre-check, before every line search: the end of -newton_keep_contact (before
   the line search of the first Newton iteration, after its Jacobian, so that -snes_test_jacobian
   compares that Jacobian with the residual it belongs to), and the iterate's |R| for
   -newton_domain_backtrack */
static PetscErrorCode LineSearchPreCheck(SNESLineSearch ls, Vec X, Vec Y, PetscBool *changed, void *ctx)
{
  Stepper *st = (Stepper *)ctx;

  PetscFunctionBeginUser;
  (void)X;
  *changed = PETSC_FALSE;
  if (st->pb && st->pb->contact) PetscCall(ContactKeepCommitted(st->pb->contact, 0));
  if (st->pb && st->aset) {
    SNES      snes;
    KSP       ksp;
    PetscReal fnorm;
    Vec       F;
    PetscCall(SNESLineSearchGetSNES(ls, &snes));
    PetscCall(SNESGetKSP(snes, &ksp));
    PetscCall(SNESLineSearchGetNorms(ls, NULL, &fnorm, NULL));
    PetscCall(SNESGetFunction(snes, &F, NULL, NULL));
    PetscInt        nz;
    const PetscInt *zrows;
    PetscCall(BCSwitchedRows(st->bcs, &nz, &zrows));
    PetscCall(NewtonActiveSetApply(st->aset, st->pb, ksp, nz, zrows, F, fnorm, Y, changed));
  }
  if (st->pb && st->domain_backtrack) {
    /* -newton_domain_backtrack: in PETSc's backtracking search a failed trial evaluation reads as
       a residual twice the iterate's (ProblemFormFunction); the other searches as before (the
       watchdog's relaxed steps would take such a point) */
    PetscBool bt;
    PetscReal fnorm;
    PetscCall(PetscObjectTypeCompare((PetscObject)ls, SNESLINESEARCHBT, &bt));
    bt = bt || NewtonLineSearchEnergy(st->nls);
    PetscCall(SNESLineSearchGetNorms(ls, NULL, &fnorm, NULL));
    st->pb->trial_norm = (bt && fnorm > 0 && PetscIsNormalReal(fnorm)) ? 2 * fnorm : 0;
  }
  PetscFunctionReturn(0);
}

/* the end of a line search that found its point: evaluations outside the line search (a Jacobian's
   finite-difference test) report a failure as a domain error again (-newton_domain_backtrack) */
static PetscErrorCode TrialEnd(SNESLineSearch ls, Vec X, Vec Y, Vec W, PetscBool *changed_y, PetscBool *changed_w, void *ctx)
{
  Stepper *st = (Stepper *)ctx;

  PetscFunctionBeginUser;
  (void)ls;
  (void)X;
  (void)Y;
  (void)W;
  *changed_y = *changed_w = PETSC_FALSE;
  if (st->pb) st->pb->trial_norm = 0;
  PetscFunctionReturn(0);
}

/* the energy line search's step limit: no slave node carried deeper than an element into a tool
   (ContactStepLimit) */
static PetscErrorCode StepLimit(void *ctx, Vec X, Vec Y, PetscReal *lmax)
{
  Stepper           *st = (Stepper *)ctx;
  Problem           *pb = st->pb;
  const PetscScalar *u;
  PetscReal          yt[3 * 64];

  PetscFunctionBeginUser;
  *lmax = PETSC_MAX_REAL;
  if (!ContactNumTools(pb->contact) || !(st->step_depth > 0)) PetscFunctionReturn(0);
  PetscCall(ProblemGetToolValues(pb, Y, yt));
  PetscCall(ProblemLocalWithBC(pb, X, pb->lambda));
  PetscCall(VecGetArrayRead(pb->Uloc, &u));
  PetscCall(ContactStepLimit(pb->contact, u, pb->lambda, Y, pb->ntu ? yt : NULL, st->step_depth, lmax));
  PetscCall(VecRestoreArrayRead(pb->Uloc, &u));
  PetscFunctionReturn(0);
}

/* Start of every Newton iteration: the frame recurrence of eq 30 at the current iterate */
static PetscErrorCode NewtonUpdate(SNES snes, PetscInt it)
{
  Problem           *pb;
  Vec                X;
  const PetscScalar *u;

  PetscFunctionBeginUser;
  PetscCall(SNESGetApplicationContext(snes, &pb));
  if (!ContactNumSlaves(pb->contact)) PetscFunctionReturn(0);
  PetscCall(SNESGetSolution(snes, &X));
  PetscCall(ProblemLocalWithBC(pb, X, pb->lambda));
  PetscCall(VecGetArrayRead(pb->Uloc, &u));
  PetscCall(ContactSeed(pb->contact, u, pb->lambda, PETSC_FALSE));
  PetscCall(VecRestoreArrayRead(pb->Uloc, &u));
  PetscCall(ContactRecordActive(pb->contact));
  PetscFunctionReturn(0);
}

static const char *FailureCause(const Stepper *st, const Problem *pb, SNESConvergedReason reason, char *buf, size_t len)
{
  if (st->aug_failed) {
    PetscReal tol, mtol;
    (void)ContactAugmentTolerances(pb->contact, &tol, &mtol);
    snprintf(buf, len, "augmented Lagrangian: penetration %.3g after %d loops (tolerance %.3g, -contact_augmented_tol), largest multiplier change %.3g (-contact_augmented_multiplier_tol %g), -contact_augmented_max %d", (double)st->aug_pen, (int)st->aug_loops, (double)tol, (double)st->aug_dlam, (double)mtol, (int)st->aug_loops);
  } else if (reason == SNES_DIVERGED_DTOL && st->stalled)
    snprintf(buf, len, "Newton stalled (|R| %.3g did not fall below %g times its value %d iterations earlier, -newton_stall_its)", (double)st->stall_fnorm, (double)st->stall_factor, (int)st->stall_its);
  else if (reason == SNES_DIVERGED_INNER && pb->bad_status < 0) snprintf(buf, len, "contact chattering: %d nodes still entering or leaving contact at the last Newton iteration (node id %d)", (int)-pb->bad_status, (int)pb->bad_cell_id);
  else if (pb->cutback) snprintf(buf, len, "the material asked for a smaller increment (a user material's PNEWDT < 1; element id %d)", (int)pb->bad_cell_id);
  else if (reason == SNES_DIVERGED_FUNCTION_DOMAIN || reason == SNES_DIVERGED_JACOBIAN_DOMAIN || pb->ndomain_err) {
    if (pb->bad_status == MAT_ERR_RETURNMAP) snprintf(buf, len, "the local return map did not converge (element id %d)", (int)pb->bad_cell_id);
    else if (pb->bad_status == MAT_ERR_NAN) snprintf(buf, len, "NaN or Inf in the material's stress or tangent (a user material's STRESS or DDSDDE; element id %d, integration point %d)", (int)pb->bad_cell_id, (int)pb->bad_point);
    else if (pb->bad_status == ATRITO_ERR_PROJECTION) snprintf(buf, len, "the projection of a slave node on a tool failed");
    else snprintf(buf, len, "an element inverted (element id %d)", (int)pb->bad_cell_id);
  } else if (reason == SNES_DIVERGED_FNORM_NAN) snprintf(buf, len, "NaN or Inf in the residual");
  else if (reason == SNES_DIVERGED_MAX_IT) snprintf(buf, len, "Newton did not converge in the allowed iterations");
  else snprintf(buf, len, "Newton diverged (%s)", SNESConvergedReasons[reason]);
  return buf;
}

/* a failed Newton solve explained (collective; written to buf, empty where there is nothing to
   add): |R| against the internal forces'
   scale, where its peak is, and the tool whose contact changed most at the last iteration, with
   the nodes that entered, left or changed between stick and slip, its deepest penetration (also
   in element sizes) and largest normal force, and what to try */
static PetscErrorCode ExplainFailure(Stepper *st, Problem *pb, char *buf, size_t len)
{
  const PetscInt     nt = ContactNumTools(pb->contact);
  PetscReal          F = 0, fnorm, v, x[3];
  PetscInt           nd, cp, worst = -1, wch = -1;
  Vec                R;
  ContactToolStatus *ts;
  size_t             l;

  PetscFunctionBeginUser;
  buf[0] = 0;
  PetscCall(SNESGetFunction(pb->snes, &R, NULL, NULL));
  PetscCall(VecNorm(R, NORM_2, &fnorm));
  if (PetscIsInfOrNanReal(fnorm)) PetscFunctionReturn(0);
  PetscCall(ProblemForceScale(pb, &F));
  PetscCall(ProblemResidualPeak(pb, R, &v, &nd, &cp, x));
  PetscCall(PetscSNPrintf(buf, len, "|R| %.3g (%.2g of the forces' scale), largest at node %d %c", (double)fnorm, (double)(F > 0 ? fnorm / F : 0), (int)nd, "xyz"[cp]));
  if (!nt) PetscFunctionReturn(0);
  PetscCall(PetscMalloc1(nt, &ts));
  PetscCall(ContactStatusChanges(pb->contact, ts));
  for (PetscInt t = 0; t < nt; t++) {
    const PetscInt ch = ts[t].nin + ts[t].nout + ts[t].nslip;
    if (ch > wch || (ch == wch && worst >= 0 && ts[t].penh > ts[worst].penh)) {
      wch   = ch;
      worst = t;
    }
  }
  if (worst >= 0 && (wch > 0 || ts[worst].nactive > 0)) {
    const Tool *tl = NULL;
    PetscCall(ContactGetTool(pb->contact, worst, &tl));
    PetscCall(PetscStrlen(buf, &l));
    PetscCall(PetscSNPrintf(buf + l, len - l, "; tool %s at the last iteration: %d nodes entered contact, %d left, %d changed between stick and slip, %d in contact, penetration up to %.3g (%.2g of the element size), normal force up to %.3g", tl->name, (int)ts[worst].nin, (int)ts[worst].nout, (int)ts[worst].nslip, (int)ts[worst].nactive, (double)ts[worst].pen, (double)ts[worst].penh, (double)ts[worst].fmax));
    PetscCall(PetscStrlen(buf, &l));
    if (ts[worst].penh > 0.5) PetscCall(PetscSNPrintf(buf + l, len - l, "; try: a stiffer penalty for it (-tool_%s_penalty_normal) or -contact_augmented", tl->name));
    else if (ts[worst].nin + ts[worst].nout > 0) PetscCall(PetscSNPrintf(buf + l, len - l, "; try: a wider switching band (-contact_regularization_relative) or -newton_monitor_contact to follow the nodes per iteration"));
    else if (ts[worst].nslip > 0) PetscCall(PetscSNPrintf(buf + l, len - l, "; try: -contact_tangent or -newton_monitor_contact to follow the nodes per iteration"));
    else PetscCall(PetscSNPrintf(buf + l, len - l, "; try: -newton_monitor_contact to follow |R| and the contact per iteration"));
  }
  PetscCall(PetscFree(ts));
  (void)st;
  PetscFunctionReturn(0);
}

/* frame seeds of the contact nodes at U: from the committed frames (a step, or a retry, starts
   again from them) */
static PetscErrorCode SeedFrames(Problem *pb, Vec U, PetscReal lambda)
{
  const PetscScalar *u;

  PetscFunctionBeginUser;
  PetscCall(ProblemLocalWithBC(pb, U, lambda));
  PetscCall(VecGetArrayRead(pb->Uloc, &u));
  PetscCall(ContactSeed(pb->contact, u, lambda, PETSC_TRUE));
  PetscCall(VecRestoreArrayRead(pb->Uloc, &u));
  PetscFunctionReturn(0);
}

PetscErrorCode StepperRun(Stepper *st, Problem *pb, Results *res)
{
  SNES           snes = pb->snes;
  KSP            ksp;
  PC             pc;
  Vec            R, W;
  PetscReal      lam_c = 0, dl = st->stages.s[0].dt0, dl_prev = 0, rhist[256];
  PetscInt       stage = 0;
  const PetscReal T = st->stages.T, tol = 1e-12 * T;
  PetscInt       itshist[256], step = 0, total_its = 0, total_cuts = 0, total_soft = 0;
  CheckpointInfo ci;
  PetscLogDouble t0, t1;
  const PetscBool contact = ContactNumTools(pb->contact) > 0 ? PETSC_TRUE : PETSC_FALSE;

  PetscFunctionBeginUser;
  PetscCall(PetscTime(&t0));
  st->pb = pb;
  PetscCall(NewtonLineSearchSetFailureCounter(st->nls, &pb->ntrial_fail));
  PetscCall(NewtonLineSearchSetStepLimit(st->nls, StepLimit, st));
  PetscCall(SNESGetKSP(snes, &ksp));
  PetscCall(KSPGetPC(ksp, &pc));
  PetscCall(VecDuplicate(pb->U, &R));
  PetscCall(VecDuplicate(pb->U, &W));
  st->Uprev2   = NULL;
  st->dl_prev2 = 0; /* after a restart: the checkpoint's, where it has the state (else the first step extrapolates linearly) */
  if (st->curvature > 0) PetscCall(VecDuplicate(pb->U, &st->Uprev2));
  ci.prev2    = st->Uprev2;
  ci.dl_prev2 = 0;
  PetscCall(SNESSetConvergenceHistory(snes, rhist, itshist, 256, PETSC_TRUE));
  PetscCall(SNESSetUpdate(snes, NewtonUpdate));
  {
    SNESLineSearch ls;
    PetscCall(SNESGetLineSearch(snes, &ls));
    PetscCall(SNESLineSearchSetPreCheck(ls, LineSearchPreCheck, st));
    PetscCall(SNESLineSearchSetPostCheck(ls, TrialEnd, st));
  }
  PetscCall(SNESSetConvergenceTest(snes, NewtonConverged, st, NULL));
  {
    PetscReal gmin[3] = {0, 0, 0}, gmax[3] = {0, 0, 0};
    PetscCall(DMGetBoundingBox(pb->mesh->dm, gmin, gmax));
    st->model_size = PetscSqrtReal(PetscSqr(gmax[0] - gmin[0]) + PetscSqr(gmax[1] - gmin[1]) + PetscSqr(gmax[2] - gmin[2]));
    st->nfloor     = 0;
    st->njump      = 0;
  }
  {
    PetscBool preonly;
    PetscCall(PetscObjectTypeCompare((PetscObject)ksp, KSPPREONLY, &preonly));
    st->kry_on = preonly ? PETSC_FALSE : PETSC_TRUE;
    PetscCall(KSPGetTolerances(ksp, &st->ksp_rtol0, NULL, NULL, NULL));
  }
  if (st->bcs->nswitch) { /* conditions that stages switch: their rows (bc.h) */
    PetscCall(SNESSetFunction(snes, NULL, StepperFormFunction, st));
    PetscCall(SNESSetJacobian(snes, NULL, NULL, StepperFormJacobian, st));
  }
  ci.hold   = NULL;
  st->Uhold = NULL;
  if (BCHasHold(st->bcs)) {
    PetscCall(VecDuplicate(pb->U, &st->Uhold));
    PetscCall(VecZeroEntries(st->Uhold));
    ci.hold = st->Uhold;
  }
  if (res->restart[0]) {
    /* continue: the committed state of the checkpoint */
    PetscCall(CheckpointRead(pb, res->restart, &ci));
    step       = ci.step;
    lam_c      = ci.lambda;
    dl         = ci.dl;
    dl_prev    = ci.dl_prev;
    st->dl_prev2 = ci.dl_prev2;
    total_its  = ci.total_its;
    total_cuts = ci.total_cuts;
    stage      = ci.stage;
    PetscCheck(stage >= 0 && stage < st->stages.n, pb->comm, PETSC_ERR_FILE_UNEXPECTED, "-restart %s: the checkpoint is in stage %" PetscInt_FMT ", this case has %" PetscInt_FMT " (-stage_names)", res->restart, stage, st->stages.n);
    PetscCall(EnterStage(st, stage, lam_c, PETSC_FALSE, PETSC_TRUE));
    PetscCall(ResultsOpen(res, pb, &ci));
    if (st->stages.given) PetscCall(PetscPrintf(pb->comm, "restart from %s: step %" PetscInt_FMT ", time %.6g, stage %s\n", res->restart, step, (double)lam_c, st->stages.s[stage].name));
    else PetscCall(PetscPrintf(pb->comm, "restart from %s: step %" PetscInt_FMT ", load %.6g\n", res->restart, step, (double)lam_c));
  } else {
    PetscCall(VecZeroEntries(pb->Uc));
    PetscCall(EnterStage(st, 0, 0.0, PETSC_TRUE, PETSC_FALSE));
    PetscCall(VecZeroEntries(pb->U));
    PetscCall(VecZeroEntries(pb->Uc));
    PetscCall(VecZeroEntries(pb->Uprev));
    PetscCall(ProblemEvaluate(pb, pb->U, 0.0));
    PetscCall(ResultsOpen(res, pb, NULL));
  }

  while (lam_c < T - tol) {
    SNESConvergedReason reason;
    PetscInt            its = 0, its_max = 0, cuts = 0, nres;
    PetscBool           softened = PETSC_FALSE; /* this step has been retried at softer penalties */
    PetscReal           lam_t, r0 = 0, h, next;
    const PetscBool     aug = ContactAugmented(pb->contact);

    PetscCheck(step < st->max_steps, pb->comm, PETSC_ERR_NOT_CONVERGED, "-load_max_steps %" PetscInt_FMT " reached at %s %g", st->max_steps, st->stages.given ? "time" : "load", (double)lam_c);
    if (StageAt(&st->stages, lam_c) != stage) { /* the stage ended: the next starts with its own increment */
      stage = StageAt(&st->stages, lam_c);
      PetscCall(EnterStage(st, stage, lam_c, PETSC_TRUE, PETSC_FALSE));
      dl = st->stages.s[stage].dt0;
    }
    const Stage *sg = &st->stages.s[stage];
    next = NextLanding(st, stage, lam_c);
    for (;;) {
      h     = PetscMin(dl, next - lam_c);
      /* a step that reaches a stage end or a kink ends exactly on it; with -load_kinks also one
         that would leave less than 1 % of itself before it (no sliver of a step after it) */
      if (st->kinks && next - lam_c - h < 0.01 * h) h = next - lam_c;
      lam_t = (next - lam_c - h < tol) ? next : lam_c + h;
      pb->lambda  = lam_t;
      /* the increment, for a material that uses it (a user material's TIME, DTIME, KSTEP, KINC) */
      for (PetscInt k = 0; k < pb->nmat; k++)
        if (pb->mks[k]->set_increment) pb->mks[k]->set_increment(pb->mks[k]->ctx, (double)(lam_c - sg->t0), (double)lam_c, (double)(lam_t - lam_c), (int)stage + 1, (int)step + 1);
      pb->cutback = PETSC_FALSE; /* a request of the predictor's evaluations counts for this attempt */
      PetscCall(VecCopy(pb->Uc, pb->U));
      /* a fresh factorisation for every step, so that a step depends only on the committed state:
         a run restarted from a checkpoint repeats the same iterations (PETSc's MUMPS interface:
         analysis and scaling again; -lu_ordering nd keeps its analysis, a function of the
         nonzero pattern alone) */
      PetscCall(PCReset(pc));
      /* frame seeds from the committed state (a retry starts again from the committed frames) */
      PetscCall(SeedFrames(pb, pb->Uc, lam_c));
      /* the extrapolation of the last two converged states only within one linear piece of every
         curve (with -load_kinks): at a kink or a stage's start, the tangent predictor (auto) or
         the committed state */
      const Predictor pred        = sg->predictor >= 0 ? (Predictor)sg->predictor : st->predictor; /* -stage_<s>_predictor */
      const PetscBool kink        = (pred == PREDICTOR_EXTRAPOLATE || pred == PREDICTOR_AUTO) && dl_prev > 0 && AtKink(st, lam_c);
      const PetscBool extrapolate = (pred == PREDICTOR_EXTRAPOLATE || pred == PREDICTOR_AUTO) && dl_prev > 0 && !kink;
      if (kink && st->kink_predictor == PREDICTOR_NONE) {
        /* the committed state (U = Uc already) */
      } else if (kink && st->kink_predictor == PREDICTOR_AUTO) {
        /* the committed state or the tangent predictor, whichever leaves the smaller residual at
           the step's end: a tool that retracts from a body that stays in contact is followed by
           the tangent (from the committed state every node is open at the first iteration and
           the contact-free Newton step overshoots), one the body separates from is not (the
           linearised penalty would pull the body along with the tool) */
        PetscBool ok;
        PetscReal rc = PETSC_INFINITY, rt = PETSC_INFINITY;
        pb->lambda = lam_t;
        PetscCall(StepperFormFunction(snes, pb->Uc, R, st));
        if (!pb->ndomain_err) PetscCall(VecNorm(R, NORM_2, &rc));
        PetscCall(TangentPredictor(st, pb, R, W, lam_c, h, &ok));
        if (ok) {
          pb->lambda = lam_t;
          PetscCall(StepperFormFunction(snes, pb->U, R, st));
          if (!pb->ndomain_err) PetscCall(VecNorm(R, NORM_2, &rt));
        }
        if (!ok || !(rt < rc)) PetscCall(VecCopy(pb->Uc, pb->U));
        PetscCall(PetscInfo(snes, "kink predictor: |R| %g at the committed state, %g at the tangent predictor: %s\n", (double)rc, (double)rt, ok && rt < rc ? "tangent" : "committed"));
        pb->ndomain_err = 0;
      } else if (pred == PREDICTOR_TANGENT || kink || (pred == PREDICTOR_AUTO && !extrapolate)) {
        PetscBool ok;
        PetscCall(TangentPredictor(st, pb, R, W, lam_c, h, &ok));
        if (!ok) PetscCall(VecCopy(pb->Uc, pb->U));
      } else if (extrapolate) {
        PetscCall(VecAXPBYPCZ(pb->U, -h / dl_prev, h / dl_prev, 1.0, pb->Uprev, pb->Uc));
        /* -load_predictor_curvature: the quadratic term through the state before, when that step
           lies in the same linear piece of every curve (no kink at its end) */
        if (st->curvature > 0 && st->dl_prev2 > 0 && !AtKink(st, lam_c - dl_prev)) PetscCall(PredictorCurvature(pb->U, pb->Uc, pb->Uprev, st->Uprev2, h, dl_prev, st->dl_prev2, st->curvature, W));
      }
      pb->lambda     = lam_t;
      pb->bad_status = 0;
      if (contact && st->pred_contact && step > 0) {
        /* -load_predictor_contact: the pressed nodes keep their committed gaps */
        const PetscScalar *u;
        PetscInt           nmv;
        PetscReal          dmx;
        PetscCall(ProblemLocalWithBC(pb, pb->U, lam_t));
        PetscCall(VecGetArrayRead(pb->Uloc, &u));
        PetscCall(ContactProjectPressed(pb->contact, u, lam_t, pb->U, &nmv, &dmx));
        PetscCall(VecRestoreArrayRead(pb->Uloc, &u));
        PetscCall(PetscInfo(snes, "predictor: %d pressed nodes moved to their committed gaps, by at most %g\n", (int)nmv, (double)dmx));
      }
      PetscCall(SeedFrames(pb, pb->U, lam_t));
      its             = 0;
      its_max         = 0;
      st->kry_sum     = 0;
      st->kry_max     = 0;
      st->aug_failed  = PETSC_FALSE;
      st->aug_loops   = 0;
      PetscReal atol0 = 0, rtol = 0, stol = 0, eta = 0;
      PetscInt  maxit = 0, maxf = 0;
      PetscBool tol_changed = PETSC_FALSE, inexact;
      /* the start of the augmentation: the penalties' factor, the inexact solves' relative residual */
      PetscCall(ContactAugmentStart(pb->contact, &eta));
      inexact = (aug && eta > 0) ? PETSC_TRUE : PETSC_FALSE;
      if (aug) PetscCall(SNESGetTolerances(snes, &atol0, &rtol, &stol, &maxit, &maxf));
      /* the first Newton iteration of the step solves with the committed contact set: a node
         pressed in the committed state stays closed in its residual and its Jacobian whatever the
         predictor's gap (ContactKeepCommitted; LineSearchPreCheck ends the keep before the first line search:
         the line search and every later iteration see the true law). The extrapolation leaves lightly pressed
         nodes a few micrometres off the tool (their committed penetration t_N/K_N is smaller than
         the predictor's error): open, they have no stiffness, and the plastic sheet's Newton step
         drove them millimetres into the tool, the line search cutting it to 1 % (doc/notes/performance-log.md) */
      st->r_true0 = -1;
      PetscBool newtonls;
      PetscCall(PetscObjectTypeCompare((PetscObject)snes, SNESNEWTONLS, &newtonls)); /* the keep ends at the line search */
      if (contact && st->keep_contact > 0 && newtonls) {
        /* the true residual at the start: the tolerances and the reported initial residual */
        pb->lambda = lam_t;
        PetscCall(StepperFormFunction(snes, pb->U, R, st));
        if (!pb->ndomain_err) PetscCall(VecNorm(R, NORM_2, &st->r_true0));
        pb->ndomain_err = 0;
        PetscCall(ContactKeepCommitted(pb->contact, st->keep_contact));
      }
      /* Newton solves at fixed contact multipliers; with -contact_augmented the multipliers are
         updated after each (ContactAugment) until the penetration is below the tolerance */
      for (;;) {
        PetscInt  its1;
        PetscBool aconv = PETSC_FALSE, held = PETSC_FALSE;
        if (aug && (st->aug_loops > 0 || inexact)) {
          /* the later solves of the step are converged to the accuracy the first one reached: |R|
             below rtol times the first solve's initial residual r0 (or their own rtol); with
             -contact_augmented_inexact a solve that another follows stops at eta r0 (the first
             one: eta times its own initial residual) */
          PetscReal a = st->aug_loops > 0 ? PetscMax(atol0, rtol * r0) : atol0, rt = rtol;
          if (inexact && st->aug_loops == 0) rt = PetscMax(rtol, eta);
          else if (inexact) a = PetscMax(a, eta * r0);
          PetscCall(SNESSetTolerances(snes, a, rt, stol, maxit, maxf));
          tol_changed = PETSC_TRUE;
        }
        /* a solve after a multiplier update makes at least one Newton iteration: with none (its
           residual already below the raised tolerance) the displacements do not answer the update,
           the next update adds the same penalty force again, and the multipliers drift from a
           frozen state until a solve iterates and jumps (a decision that round-off made: 2-rank
           runs of the seed punch with friction took 140 or 145 iterations) */
        if (aug) PetscCall(SNESSetForceIteration(snes, st->aug_loops > 0 ? PETSC_TRUE : PETSC_FALSE));
        PetscCall(SNESSolve(snes, NULL, pb->U));
        pb->trial_norm = 0; /* (-newton_domain_backtrack: set by the line search's pre-check) */
        if (contact) PetscCall(ContactKeepCommitted(pb->contact, 0)); /* (a solve that ended before its first line search) */
        if (st->kry_on && st->ksp_target > 0) PetscCall(KSPSetTolerances(ksp, st->ksp_rtol0, PETSC_DEFAULT, PETSC_DEFAULT, PETSC_DEFAULT)); /* (-newton_ksp_target) */
        PetscCall(SNESGetConvergedReason(snes, &reason));
        PetscCall(SNESGetIterationNumber(snes, &its1));
        if ((reason == SNES_DIVERGED_LINE_SEARCH || reason == SNES_DIVERGED_MAX_IT) && st->floor_tol > 0) {
          /* the residual's floor (-newton_floor_tol): the line search found no decrease along a
             Newton correction far below any length of the model. The residual is then at the level
             that the local solvers' tolerances (return maps, enhanced parameters) leave in it, and
             the state is the solution to within that correction; cutting the step cannot help, since
             a smaller step starts from the same floor (seen: the U-channel's springback stage, which
             starts in equilibrium at |R| 1.5e-8 N and whose Newton correction of 3e-9 mm raised |R|
             at every length down to 1e-13 of itself). The same holds for a solve that ran out of
             iterations with its last Newton correction that small: at the floor, round-off can let
             the line search find ever smaller decreases instead of none (2-rank runs of
             tests/test_stages.sh's floor case, whose round-off varies from run to run, ended either
             way); its state lies within (1 - lambda) of that correction of Newton's estimate. The
             correction is the line search's Y: PETSc's backtracking and the watchdog
             (linesearch.c) scale only the step they take, never Y, whether they fail or not.
             A small correction alone does not make the floor: where the residual is not smooth (a
             node at the kink of the contact law at gap 0, or at the edge of a tool's range), Newton's
             correction shrinks towards the kink while |R| stays at the size of the forces (seen: a whole blank
             of 96 hexahedra pushed 3.75 mm in one step stalled at |R| 2.3e4 N, 0.4 of the forces'
             scale, on a correction of 4.6e-9 mm). The residual must also be below
             -newton_floor_force_tol of the internal forces' scale (ProblemForceScale, from the
             last residual assembly, a trial point at most a correction away): at the floor it is
             round-off and the local solvers' tolerances, 1e-13 to 1e-12 of that scale in
             tests/test_stages.sh's floor case, against 1e-3 and more at the jumps seen. */
          SNESLineSearch ls;
          Vec            Y, R;
          PetscReal      ymax, rnorm, fscale;
          PetscCall(SNESGetLineSearch(snes, &ls));
          PetscCall(SNESLineSearchGetVecs(ls, NULL, NULL, &Y, NULL, NULL));
          PetscCall(VecNorm(Y, NORM_INFINITY, &ymax));
          PetscCall(SNESGetFunction(snes, &R, NULL, NULL));
          PetscCall(VecNorm(R, NORM_2, &rnorm));
          PetscCall(ProblemForceScale(pb, &fscale));
          if (ymax <= st->floor_tol * st->model_size) {
            const PetscBool floor = rnorm <= st->floor_force_tol * fscale ? PETSC_TRUE : PETSC_FALSE;
            if (floor) {
              reason = SNES_CONVERGED_SNORM_RELATIVE;
              st->nfloor++;
            } else st->njump++;
            PetscCall(PetscInfo(snes, "%s: Newton correction %g <= %g, |R| %g %s %g\n", floor ? "converged at the residual's floor" : "not at the residual's floor", (double)ymax, (double)(st->floor_tol * st->model_size), (double)rnorm, floor ? "<=" : ">", (double)(st->floor_force_tol * fscale)));
          }
        }
        if (st->aug_loops == 0) r0 = st->r_true0 >= 0 ? st->r_true0 : rhist[0];
        st->r_true0 = -1;
        its += its1;
        its_max = PetscMax(its_max, its1);
        /* converged: one more evaluation at the solution (trial states, cell info, reactions) */
        if (reason > 0) PetscCall(ProblemEvaluate(pb, pb->U, lam_t));
        if (reason > 0 && contact && st->chatter_check && its1 > 0 && !inexact) {
          /* the active set must have settled: a node entering or leaving contact with a
             significant force in the last iteration means the step is not converged */
          PetscInt nch, nodeid;
          PetscCall(ContactChatter(pb->contact, st->newton_tol, &nch, &nodeid));
          if (nch) {
            reason         = SNES_DIVERGED_INNER; /* reported below as chattering */
            pb->bad_status = -nch;
            pb->bad_cell_id = nodeid;
          }
        }
        if (reason <= 0 || !aug) break;
        st->aug_loops++;
        PetscCall(ContactAugment(pb->contact, inexact, &aconv, &held, &st->aug_pen, &st->aug_dlam));
        /* an inexact solve that met the penetration tolerance: ContactAugment held the
           multipliers; the solve is completed at them (fully converged) and checked again, and the
           rest of the step's solves are exact */
        if (held) inexact = PETSC_FALSE;
        else if (aconv) break;
        if (st->aug_loops >= ContactAugmentedMax(pb->contact)) {
          reason         = SNES_DIVERGED_INNER; /* reported below as the augmentation's failure */
          st->aug_failed = PETSC_TRUE;
          break;
        }
      }
      if (tol_changed) PetscCall(SNESSetTolerances(snes, atol0, rtol, stol, maxit, maxf));
      if (aug) PetscCall(SNESSetForceIteration(snes, PETSC_FALSE));
      if (reason > 0) break;
      if (aug && !st->aug_failed && !softened) {
        /* -contact_augmented_soften: a failed Newton solve of an augmented step is retried once at
           the same increment with softer penalties (ContactAugmentSoften), then cut as usual */
        PetscReal f;
        PetscCall(ContactAugmentSoften(pb->contact, &softened, &f));
        if (softened) {
          char buf[256], why[768];
          FailureCause(st, pb, reason, buf, sizeof(buf));
          PetscCall(ExplainFailure(st, pb, why, sizeof(why)));
          total_soft++;
          PetscCall(PetscPrintf(pb->comm, "step %" PetscInt_FMT " at %s %.6g: %s; retrying with the penalties' factor %g (-contact_augmented_soften)\n", step + 1, st->stages.given ? "time" : "load", (double)lam_t, buf, (double)f));
          if (why[0]) PetscCall(PetscPrintf(pb->comm, "  %s\n", why));
          continue;
        }
      }
      {
        char buf[256], why[768];
        FailureCause(st, pb, reason, buf, sizeof(buf));
        PetscCall(ExplainFailure(st, pb, why, sizeof(why)));
        cuts++;
        total_cuts++;
        /* without stages the time is the load, as the messages have always said */
        const char *tw = st->stages.given ? "time" : "load";
        char        sn[96] = "";
        if (st->stages.given) PetscCall(PetscSNPrintf(sn, sizeof(sn), "stage %s, ", sg->name));
        PetscCheck(cuts <= st->max_cuts && h * st->cut >= sg->dt_min, pb->comm, PETSC_ERR_NOT_CONVERGED,
                   "step %" PetscInt_FMT " failed at %s %.6g (%sincrement %.3g) after %" PetscInt_FMT " cuts: %s%s%s; the results up to %s %.6g are complete in %s",
                   step + 1, tw, (double)lam_t, sn, (double)h, cuts - 1, buf, why[0] ? "; " : "", why, tw, (double)lam_c, res->dir);
        PetscCall(PetscPrintf(pb->comm, "step %" PetscInt_FMT " at %s %.6g: %s; retrying with increment %.3g\n", step + 1, tw, (double)lam_t, buf, (double)(h * st->cut)));
        if (why[0]) PetscCall(PetscPrintf(pb->comm, "  %s\n", why));
        dl = h * st->cut;
      }
    }
    /* the state before the previous one, for -load_predictor_curvature (ProblemCommit moves Uc to
       Uprev) */
    if (st->Uprev2) {
      PetscCall(VecCopy(pb->Uprev, st->Uprev2));
      st->dl_prev2 = dl_prev;
    }
    /* commit the trial states of that evaluation */
    PetscCall(ProblemCommit(pb, lam_t));
    dl_prev = h;
    lam_c   = lam_t;
    step++;
    total_its += its;
    PetscCall(SNESGetConvergenceHistory(snes, NULL, NULL, &nres));
    PetscCall(ResultsWriteStep(res, pb, step, lam_c, its, r0, rhist[PetscMax(nres - 1, 0)], lam_c >= T - tol ? PETSC_TRUE : PETSC_FALSE, sg->name));
    PetscCall(PetscTime(&t1));
    {
      char cline[160] = "";
      if (contact) { /* penetration over all tools: the largest, and the mean of the pressed nodes */
        PetscReal pmax = 0, psum = 0;
        PetscInt  npr  = 0;
        for (PetscInt t = 0; t < ContactNumTools(pb->contact); t++) {
          ContactToolResult r;
          PetscCall(ContactGetToolResult(pb->contact, t, lam_c, &r));
          pmax = PetscMax(pmax, r.max_pen);
          psum += r.mean_pen * r.active;
          npr += r.active;
        }
        if (aug) PetscCall(PetscSNPrintf(cline, sizeof(cline), "  penetration %.3e mean %.3e  augmentations %" PetscInt_FMT "  multiplier change %.3e", (double)pmax, (double)(npr ? psum / npr : 0), st->aug_loops, (double)st->aug_dlam));
        else PetscCall(PetscSNPrintf(cline, sizeof(cline), "  penetration %.3e mean %.3e", (double)pmax, (double)(npr ? psum / npr : 0)));
      }
      char kline[96] = ""; /* an iterative linear solver: its iterations in the step, the most in one Newton iteration */
      if (st->kry_on) PetscCall(PetscSNPrintf(kline, sizeof(kline), "  krylov %" PetscInt_FMT " (most %" PetscInt_FMT ")", st->kry_sum, st->kry_max));
      PetscCall(PetscPrintf(pb->comm, "step %4" PetscInt_FMT "  time %.6f  its %2" PetscInt_FMT "%s  |R| %.3e  elapsed %.2f s%s  stage %s\n", step, (double)lam_c, its, kline, (double)rhist[PetscMax(nres - 1, 0)], t1 - t0, cline, sg->name));
    }
    /* growth and shrinking: on the Newton iterations of the hardest solve of the step (all of
       them without augmentation). A step that converged only after many iterations shrinks the
       next one: growing back to the increment that failed makes a phase that needs smaller
       steps alternate hard steps and cuts (doc/solvers.md, Load stepping) */
    if (its_max <= st->grow_its) dl = PetscMin(dl * st->grow, sg->dt_max);
    else if (st->shrink_its > 0 && its_max > st->shrink_its) dl = PetscMax(dl * st->shrink, sg->dt_min);
    if (res->checkpoint_interval > 0 && (step % res->checkpoint_interval == 0 || lam_c >= T - tol)) {
      ci.stage      = stage;
      ci.step       = step;
      ci.lambda     = lam_c;
      ci.dl         = dl;
      ci.dl_prev    = dl_prev;
      ci.dl_prev2   = st->dl_prev2;
      ci.total_its  = total_its;
      ci.total_cuts = total_cuts;
      PetscCall(CheckpointWrite(res, pb, &ci));
    }
  }
  PetscCall(PetscTime(&t1));
  PetscCall(PetscPrintf(pb->comm, "done: %" PetscInt_FMT " steps, %" PetscInt_FMT " Newton iterations, %" PetscInt_FMT " cuts, %.2f s\n", step, total_its, total_cuts, t1 - t0));
  if (total_soft) PetscCall(PetscPrintf(pb->comm, "augmented Lagrangian: %" PetscInt_FMT " steps retried at softer penalties (-contact_augmented_soften)\n", total_soft));
  if (pb->ntrial_fail) PetscCall(PetscPrintf(pb->comm, "line search: %" PetscInt_FMT " trial points where the residual could not be evaluated, rejected (-newton_domain_backtrack)\n", pb->ntrial_fail));
  if (st->nfloor) PetscCall(PetscPrintf(pb->comm, "residual floor: %" PetscInt_FMT " Newton solves ended by a failed line search or the iteration limit on a correction below %g with |R| below %g of the forces' scale, accepted as converged (-newton_floor_tol, -newton_floor_force_tol)\n", st->nfloor, (double)(st->floor_tol * st->model_size), (double)st->floor_force_tol));
  if (st->njump) PetscCall(PetscPrintf(pb->comm, "residual jumps: %" PetscInt_FMT " Newton solves ended on a correction below %g with |R| above %g of the forces' scale, not converged (-newton_floor_force_tol)\n", st->njump, (double)(st->floor_tol * st->model_size), (double)st->floor_force_tol));
  if (st->nls) {
    PetscInt relaxed, reverted, trials;
    PetscCall(NewtonLineSearchGetCounts(st->nls, &relaxed, &reverted, &trials));
    if (trials) PetscCall(PetscPrintf(pb->comm, "line search: %" PetscInt_FMT " residual evaluations, %" PetscInt_FMT " relaxed steps, %" PetscInt_FMT " of them reverted (-newton_watchdog)\n", trials, relaxed, reverted));
    {
      PetscInt searches, etrials, limited, fallback;
      PetscCall(NewtonLineSearchGetEnergyCounts(st->nls, &searches, &etrials, &limited, &fallback));
      if (searches) PetscCall(PetscPrintf(pb->comm, "energy line search: %" PetscInt_FMT " searches, %" PetscInt_FMT " residual evaluations, %" PetscInt_FMT " first steps shortened by the contact step limit (-newton_step_depth), %" PetscInt_FMT " backtracked on |R| (-newton_linesearch_contact)\n", searches, etrials, limited, fallback));
    }
  }
  {
    PetscInt corrected, released, solves;
    PetscCall(NewtonActiveSetGetCounts(st->aset, &corrected, &released, &solves));
    if (corrected) PetscCall(PetscPrintf(pb->comm, "active set: %" PetscInt_FMT " Newton directions corrected for %" PetscInt_FMT " nodes pulled off their tools, %" PetscInt_FMT " solves with the factorisation (-newton_active_set)\n", corrected, released, solves));
  }

  PetscCall(ResultsClose(res));
  PetscCall(VecDestroy(&R));
  PetscCall(VecDestroy(&W));
  PetscCall(VecDestroy(&st->Uhold));
  PetscCall(VecDestroy(&st->Uprev2));
  PetscCall(NewtonLineSearchDestroy(&st->nls)); /* the SNES calls its line search no more */
  PetscCall(NewtonActiveSetDestroy(&st->aset));
  PetscFunctionReturn(0);
}
