/* Newton's line searches (src/solver/linesearch.c), the watchdog and the energy search, on small systems whose Newton iterates are
   known in closed form, at 1 and 2 ranks; every rank holds its own copy of the system (so 1 and 2 ranks take the
   same steps):
   - Rosenbrock's F = (10 (y - x^2), 1 - x) from (-1.2, 1): the full Newton step lands on x = 1,
     y = -3.84 and raises |R| 9.8 times; the next step is exact. The watchdog takes both (two
     iterations, one relaxed step kept); with a rise bound below 9.8 it backtracks that step, as PETSc's
     backtracking does (14 iterations);
   - F = atan(x) from 1.5: the full step goes to x1 = 1.5 - 3.25 atan(1.5) (|R| 1.05 times
     higher, relaxed), the next full step from there is worse than the origin, so the iterate goes
     back to 1.5 and takes lambda = f^2 / (g^2 + f^2) of the first step (the quadratic model,
     f = atan(1.5), g = |atan(x1)|): checked to round-off;
   - F = sqrt(x) - 1 from 9: the full step leaves the domain (x = -3, a domain error), lambda is
     halved to x = 3, then Newton converges to 1;
   - the energy search of the stages with a tool present (atan: the regula falsi's first step
     length in closed form; sqrt: a trial outside the domain shortens the step);
   - bad input: -newton_linesearch_rise below 1, -newton_linesearch_eta outside (0, 1),
     -newton_linesearch_max_it 0 (an unknown -newton_linesearch_contact: tests/bad_input.txt). */
#include <math.h>
#include <stdio.h>
#include <string.h>
#include "linesearch.h"
#include "testcapture.h"

static int nfail = 0;
static void Ok(int cond, const char *what)
{
  if (!cond) nfail++;
  PetscPrintf(PETSC_COMM_WORLD, "%s - %s\n", cond ? "ok" : "not ok", what);
}

typedef enum { ROSENBROCK, ATAN, SQRT } Problem;
typedef struct {
  Problem   p;
  PetscReal x1, x2; /* the iterates after the first and second iterations (first entry of this rank) */
  PetscInt  nfail;  /* residual evaluations outside the domain (the energy search reads it) */
} Ctx;

static PetscErrorCode Func(SNES snes, Vec X, Vec F, void *ctx)
{
  Ctx               *c = (Ctx *)ctx;
  const PetscScalar *x;
  PetscScalar       *f;
  PetscInt           n;
  PetscBool          bad = PETSC_FALSE;

  PetscFunctionBeginUser;
  PetscCall(VecGetLocalSize(X, &n));
  PetscCall(VecGetArrayRead(X, &x));
  PetscCall(VecGetArray(F, &f));
  if (c->p == ROSENBROCK) {
    f[0] = 10 * (x[1] - x[0] * x[0]);
    f[1] = 1 - x[0];
  } else if (c->p == ATAN) f[0] = atan(x[0]);
  else {
    if (x[0] < 0) bad = PETSC_TRUE;
    else f[0] = sqrt(x[0]) - 1;
  }
  PetscCall(VecRestoreArrayRead(X, &x));
  PetscCall(VecRestoreArray(F, &f));
  if (bad) {
    c->nfail++;
    PetscCall(SNESSetFunctionDomainError(snes));
  }
  PetscFunctionReturn(0);
}

static PetscErrorCode Jac(SNES snes, Vec X, Mat J, Mat P, void *ctx)
{
  Ctx               *c = (Ctx *)ctx;
  const PetscScalar *x;
  PetscInt           lo;

  PetscFunctionBeginUser;
  (void)snes;
  (void)J;
  PetscCall(VecGetOwnershipRange(X, &lo, NULL));
  PetscCall(VecGetArrayRead(X, &x));
  if (c->p == ROSENBROCK) {
    const PetscInt    rows[2] = {lo, lo + 1};
    const PetscScalar v[4]    = {-20 * x[0], 10, -1, 0};
    PetscCall(MatSetValues(P, 2, rows, 2, rows, v, INSERT_VALUES));
  } else {
    const PetscScalar v = c->p == ATAN ? 1 / (1 + x[0] * x[0]) : 0.5 / sqrt(x[0]);
    PetscCall(MatSetValues(P, 1, &lo, 1, &lo, &v, INSERT_VALUES));
  }
  PetscCall(VecRestoreArrayRead(X, &x));
  PetscCall(MatAssemblyBegin(P, MAT_FINAL_ASSEMBLY));
  PetscCall(MatAssemblyEnd(P, MAT_FINAL_ASSEMBLY));
  PetscFunctionReturn(0);
}

/* a pre-check that must survive the switches of line search type */
static PetscErrorCode PreCheck(SNESLineSearch ls, Vec X, Vec Y, PetscBool *changed, void *ctx)
{
  (void)ls;
  (void)X;
  (void)Y;
  (void)ctx;
  *changed = PETSC_FALSE;
  return 0;
}

static PetscErrorCode Monitor(SNES snes, PetscInt it, PetscReal fnorm, void *ctx)
{
  Ctx               *c = (Ctx *)ctx;
  Vec                X;
  const PetscScalar *x;

  PetscFunctionBeginUser;
  (void)fnorm;
  if (it != 1 && it != 2) PetscFunctionReturn(0);
  PetscCall(SNESGetSolution(snes, &X));
  PetscCall(VecGetArrayRead(X, &x));
  if (it == 1) c->x1 = PetscRealPart(x[0]);
  else c->x2 = PetscRealPart(x[0]);
  PetscCall(VecRestoreArrayRead(X, &x));
  PetscFunctionReturn(0);
}

/* solves problem p from x0 (every rank its copy) with the watchdog of rise (NULL: PETSc's bt), or
   with the energy search (rise "energy": a stage with a tool present); relaxed, reverted count the
   watchdog's steps, or the energy search's searches and residual evaluations */
static PetscErrorCode Solve(Problem p, const PetscReal *x0, const char *rise, PetscInt *its, PetscInt *relaxed, PetscInt *reverted, PetscReal *err, PetscReal *x1, PetscReal *x2, SNESConvergedReason *reason)
{
  const PetscInt   n = p == ROSENBROCK ? 2 : 1;
  SNES             snes;
  KSP              ksp;
  PC               pc;
  Vec              X, R;
  Mat              J;
  Ctx              c = {p, NAN, NAN, 0};
  PetscBool        energy = (rise && !strcmp(rise, "energy")) ? PETSC_TRUE : PETSC_FALSE;
  NewtonLineSearch nls = NULL;
  PetscInt         trials;
  PetscScalar     *x;

  PetscFunctionBeginUser;
  PetscCall(VecCreateMPI(PETSC_COMM_WORLD, n, PETSC_DETERMINE, &X));
  PetscCall(VecDuplicate(X, &R));
  PetscCall(MatCreateAIJ(PETSC_COMM_WORLD, n, n, PETSC_DETERMINE, PETSC_DETERMINE, n, NULL, 0, NULL, &J));
  PetscCall(SNESCreate(PETSC_COMM_WORLD, &snes));
  PetscCall(SNESSetFunction(snes, R, Func, &c));
  PetscCall(SNESSetJacobian(snes, J, J, Jac, &c));
  PetscCall(SNESSetTolerances(snes, 1e-14, 1e-12, 0, 50, 1000));
  PetscCall(SNESGetKSP(snes, &ksp));
  PetscCall(KSPSetType(ksp, KSPPREONLY));
  PetscCall(KSPGetPC(ksp, &pc));
  PetscCall(PCSetType(pc, PCBJACOBI)); /* one block per rank: its copy, solved exactly */
  PetscCall(SNESMonitorSet(snes, Monitor, &c, NULL));
  PetscCall(SNESSetFromOptions(snes));
  if (energy) {
    PetscCall(NewtonLineSearchCreate(PETSC_COMM_WORLD, &nls));
    PetscCall(NewtonLineSearchSetFailureCounter(nls, &c.nfail));
    PetscCall(NewtonLineSearchSetStage(nls, snes, PETSC_TRUE, PETSC_FALSE)); /* a stage with a tool present */
  } else if (rise) {
    PetscCall(PetscOptionsSetValue(NULL, "-newton_linesearch_rise", rise));
    PetscCall(NewtonLineSearchCreate(PETSC_COMM_WORLD, &nls));
    PetscCall(PetscOptionsClearValue(NULL, "-newton_linesearch_rise"));
    PetscCall(NewtonLineSearchSetStage(nls, snes, PETSC_FALSE, PETSC_TRUE)); /* a release by nodal forces */
  }
  PetscCall(VecGetArray(X, &x));
  for (PetscInt i = 0; i < n; i++) x[i] = x0[i];
  PetscCall(VecRestoreArray(X, &x));
  PetscCall(SNESSolve(snes, NULL, X));
  PetscCall(SNESGetConvergedReason(snes, reason));
  PetscCall(SNESGetIterationNumber(snes, its));
  if (energy) {
    PetscInt limited, fallback;
    PetscCall(NewtonLineSearchGetCounts(nls, &limited, &fallback, &trials));
    PetscCheck(trials == 0, PETSC_COMM_SELF, PETSC_ERR_PLIB, "the energy search counted %d watchdog evaluations", (int)trials);
    PetscCall(NewtonLineSearchGetEnergyCounts(nls, relaxed, reverted, &limited, &fallback));
  } else PetscCall(NewtonLineSearchGetCounts(nls, relaxed, reverted, &trials));
  PetscCall(VecShift(X, p == ATAN ? 0.0 : -1.0)); /* the solutions: 0, and 1 (and (1, 1)) */
  PetscCall(VecNorm(X, NORM_INFINITY, err));
  *x1 = c.x1;
  *x2 = c.x2;
  PetscCall(NewtonLineSearchDestroy(&nls));
  PetscCall(SNESDestroy(&snes));
  PetscCall(MatDestroy(&J));
  PetscCall(VecDestroy(&X));
  PetscCall(VecDestroy(&R));
  PetscFunctionReturn(0);
}

int main(int argc, char **argv)
{
  char                what[512];
  const PetscReal     rb[2] = {-1.2, 1}, at = 1.5, sq = 9;
  PetscInt            its, relaxed, reverted, its_bt, r0, v0;
  PetscReal           err, x1, x2;
  SNESConvergedReason reason;
  NewtonLineSearch    nls;
  PetscErrorCode      ierr;

  PetscCall(PetscInitialize(&argc, &argv, NULL, NULL));
  /* Rosenbrock: the watchdog takes the rising full step and is exact at the second iteration */
  PetscCall(Solve(ROSENBROCK, rb, "1000", &its, &relaxed, &reverted, &err, &x1, &x2, &reason));
  snprintf(what, sizeof(what), "Rosenbrock, rise 1000: %d iterations (2), relaxed %d (1), reverted %d (0), error %.2e", (int)its, (int)relaxed, (int)reverted, (double)err);
  Ok(reason > 0 && its == 2 && relaxed == 1 && reverted == 0 && err < 1e-12, what);
  /* with PETSc's backtracking, and with a rise bound below the step's 9.8: no relaxed step */
  PetscCall(Solve(ROSENBROCK, rb, NULL, &its_bt, &r0, &v0, &err, &x1, &x2, &reason));
  snprintf(what, sizeof(what), "Rosenbrock, PETSc's bt: converged in %d iterations (more than 2), error %.2e", (int)its_bt, (double)err);
  Ok(reason > 0 && its_bt > 2 && err < 1e-12, what);
  PetscCall(Solve(ROSENBROCK, rb, "5", &its, &relaxed, &reverted, &err, &x1, &x2, &reason));
  snprintf(what, sizeof(what), "Rosenbrock, rise 5 (the first step rises 9.8 times): that step backtracked, converged in %d iterations (more than 2), error %.2e", (int)its, (double)err);
  Ok(reason > 0 && its > 2 && err < 1e-12, what);
  /* atan: relaxed, reverted, and the backtracked iterate of the quadratic model */
  {
    const PetscReal f = atan(at), xf = at - f * (1 + at * at), g = fabs(atan(xf)), lam = f * f / (g * g + f * f);
    const PetscReal want = at - lam * f * (1 + at * at);
    PetscCall(Solve(ATAN, &at, "1000", &its, &relaxed, &reverted, &err, &x1, &x2, &reason));
    snprintf(what, sizeof(what), "atan from 1.5: relaxed %d (1), reverted %d (1), converged (%s) to %.2e", (int)relaxed, (int)reverted, SNESConvergedReasons[reason], (double)err);
    Ok(reason > 0 && relaxed == 1 && reverted == 1 && err < 1e-12, what);
    snprintf(what, sizeof(what), "atan from 1.5: back at the origin, lambda %.6f of the first step: iterate %.15g against %.15g", (double)lam, (double)x2, (double)want);
    Ok(PetscAbsReal(x2 - want) < 1e-14 && lam > 0.1 && lam < 0.5, what);
    PetscCall(Solve(ATAN, &at, NULL, &its, &r0, &v0, &err, &x1, &x2, &reason));
    snprintf(what, sizeof(what), "atan from 1.5, PETSc's bt: converged (%s) to %.2e", SNESConvergedReasons[reason], (double)err);
    Ok(reason > 0 && err < 1e-12, what);
  }
  /* sqrt: the full step leaves the domain, half of it is taken */
  PetscCall(Solve(SQRT, &sq, "1000", &its, &relaxed, &reverted, &err, &x1, &x2, &reason));
  snprintf(what, sizeof(what), "sqrt(x) - 1 from 9: the full step to -3 a domain error, lambda halved; converged (%s) to %.2e in %d iterations, no relaxed step (%d)", SNESConvergedReasons[reason], (double)err, (int)its, (int)relaxed);
  Ok(reason > 0 && err < 1e-12 && relaxed == 0, what);
  /* the energy search: s(lambda) = R(x - lambda y).y. atan from 1.5: the full step overshoots
     (s(1) = -1.05 s(0), outside eta = 0.5), regula falsi on [0, 1] gives z = s0 / (s0 - s1), where
     |s| is 0.06 s0: taken. sqrt from 9: the full step to -3 is outside the domain, half of it is
     taken (s(1/2) = (sqrt(3) - 1) 12 > 0 at the longest evaluable step) */
  {
    const PetscReal f = atan(at), y = f * (1 + at * at), s0 = f * y, s1 = atan(at - y) * y, z = s0 / (s0 - s1), want = at - z * y;
    PetscCall(Solve(ATAN, &at, "energy", &its, &relaxed, &reverted, &err, &x1, &x2, &reason));
    snprintf(what, sizeof(what), "energy search, atan from 1.5: first iterate %.15g against the regula falsi's %.15g (lambda %.6f), converged (%s) to %.2e in %d iterations, %d searches, %d residual evaluations", (double)x1, (double)want, (double)z, SNESConvergedReasons[reason], (double)err, (int)its, (int)relaxed, (int)reverted);
    Ok(reason > 0 && err < 1e-12 && PetscAbsReal(x1 - want) < 1e-14 && fabs(atan(want) * y) <= 0.5 * s0 && relaxed == its && reverted > its, what);
    PetscCall(Solve(SQRT, &sq, "energy", &its, &relaxed, &reverted, &err, &x1, &x2, &reason));
    snprintf(what, sizeof(what), "energy search, sqrt(x) - 1 from 9: the full step to -3 outside the domain, the first iterate %.15g (3), converged (%s) to %.2e in %d iterations", (double)x1, SNESConvergedReasons[reason], (double)err, (int)its);
    Ok(reason > 0 && err < 1e-12 && PetscAbsReal(x1 - 3) < 1e-14, what);
  }
  /* bad input */
  PetscCall(PetscOptionsSetValue(NULL, "-newton_linesearch_rise", "0.5"));
  ErrMsg[0] = 0;
  PetscCall(PetscPushErrorHandler(CaptureHandler, NULL));
  ierr = NewtonLineSearchCreate(PETSC_COMM_WORLD, &nls);
  PetscCall(PetscPopErrorHandler());
  PetscCall(PetscOptionsClearValue(NULL, "-newton_linesearch_rise"));
  snprintf(what, sizeof(what), "-newton_linesearch_rise 0.5 refused naming the option: %s", ErrMsg);
  Ok(ierr != 0 && strstr(ErrMsg, "-newton_linesearch_rise"), what);
  /* where it applies: -newton_watchdog release (default) in a release by nodal forces without a
     tool present only, contactfree in every stage without one, none nowhere */
  {
    const char *modes[3] = {"release", "contactfree", "none"};
    const int   want[3][3] = {{1, 0, 0}, {1, 1, 0}, {0, 0, 0}}; /* (no contact, release), (no contact, no release), (contact, release) */
    for (int m = 0; m < 3; m++) {
      int got[3];
      for (int k = 0; k < 3; k++) {
        SNES               snes;
        SNESLineSearch     ls;
        SNESLineSearchType type;
        PetscBool          shell;
        PetscCall(SNESCreate(PETSC_COMM_WORLD, &snes));
        PetscCall(SNESGetLineSearch(snes, &ls));
        PetscCall(SNESLineSearchSetType(ls, SNESLINESEARCHBT));
        PetscCall(SNESLineSearchSetPreCheck(ls, PreCheck, NULL));
        PetscCall(PetscOptionsSetValue(NULL, "-newton_watchdog", modes[m]));
        PetscCall(PetscOptionsSetValue(NULL, "-newton_linesearch_contact", "petsc"));
        PetscCall(NewtonLineSearchCreate(PETSC_COMM_WORLD, &nls));
        PetscCall(PetscOptionsClearValue(NULL, "-newton_watchdog"));
        PetscCall(PetscOptionsClearValue(NULL, "-newton_linesearch_contact"));
        PetscCall(NewtonLineSearchSetStage(nls, snes, k == 2 ? PETSC_TRUE : PETSC_FALSE, k == 1 ? PETSC_FALSE : PETSC_TRUE));
        PetscCall(SNESLineSearchGetType(ls, &type));
        PetscCall(PetscStrcmp(type, SNESLINESEARCHSHELL, &shell));
        got[k] = shell ? 1 : 0;
        /* and back to PETSc's at a stage with contact */
        PetscCall(NewtonLineSearchSetStage(nls, snes, PETSC_TRUE, PETSC_TRUE));
        PetscCall(SNESLineSearchGetType(ls, &type));
        PetscCall(PetscStrcmp(type, SNESLINESEARCHBT, &shell));
        if (!shell) got[k] = -1;
        {
          PetscErrorCode (*pre)(SNESLineSearch, Vec, Vec, PetscBool *, void *) = NULL;
          PetscCall(SNESLineSearchGetPreCheck(ls, &pre, NULL));
          if (pre != PreCheck) got[k] = -2;
        }
        PetscCall(NewtonLineSearchDestroy(&nls));
        PetscCall(SNESDestroy(&snes));
      }
      snprintf(what, sizeof(what), "-newton_watchdog %s, -newton_linesearch_contact petsc: used in a release without contact %d, a stage without contact %d, a release with contact %d; PETSc's bt back at a stage with contact, the pre-check kept", modes[m], got[0], got[1], got[2]);
      Ok(got[0] == want[m][0] && got[1] == want[m][1] && got[2] == want[m][2], what);
    }
  }
  /* the defaults: the energy search in a stage with a tool present, PETSc's bt in a stage without
     one that releases nothing; -newton_watchdog none -newton_linesearch_contact petsc: none at all */
  {
    SNES               snes;
    SNESLineSearch     ls;
    SNESLineSearchType type;
    PetscBool          shell, bt;
    PetscBool          e1, e0;
    PetscCall(SNESCreate(PETSC_COMM_WORLD, &snes));
    PetscCall(SNESGetLineSearch(snes, &ls));
    PetscCall(SNESLineSearchSetType(ls, SNESLINESEARCHBT));
    PetscCall(NewtonLineSearchCreate(PETSC_COMM_WORLD, &nls));
    PetscCall(NewtonLineSearchSetStage(nls, snes, PETSC_TRUE, PETSC_FALSE));
    PetscCall(SNESLineSearchGetType(ls, &type));
    PetscCall(PetscStrcmp(type, SNESLINESEARCHSHELL, &shell));
    e1 = NewtonLineSearchEnergy(nls);
    PetscCall(NewtonLineSearchSetStage(nls, snes, PETSC_FALSE, PETSC_FALSE));
    PetscCall(SNESLineSearchGetType(ls, &type));
    PetscCall(PetscStrcmp(type, SNESLINESEARCHBT, &bt));
    e0 = NewtonLineSearchEnergy(nls);
    PetscCall(NewtonLineSearchDestroy(&nls));
    PetscCall(SNESDestroy(&snes));
    PetscCall(PetscOptionsSetValue(NULL, "-newton_watchdog", "none"));
    PetscCall(PetscOptionsSetValue(NULL, "-newton_linesearch_contact", "petsc"));
    PetscCall(NewtonLineSearchCreate(PETSC_COMM_WORLD, &nls));
    PetscCall(PetscOptionsClearValue(NULL, "-newton_watchdog"));
    PetscCall(PetscOptionsClearValue(NULL, "-newton_linesearch_contact"));
    snprintf(what, sizeof(what), "defaults: the energy search in a stage with a tool (%d, %d), PETSc's bt in one without (%d, %d); none at all with -newton_watchdog none -newton_linesearch_contact petsc (%d)", (int)shell, (int)e1, (int)bt, (int)!e0, (int)!nls);
    Ok(shell && e1 && bt && !e0 && !nls, what);
    PetscCall(NewtonLineSearchDestroy(&nls));
  }
  /* bad input of the energy search */
  {
    const char *opt[3][2] = {{"-newton_linesearch_eta", "1"}, {"-newton_linesearch_eta", "0"}, {"-newton_linesearch_max_it", "0"}};
    for (int k = 0; k < 3; k++) {
      PetscCall(PetscOptionsSetValue(NULL, opt[k][0], opt[k][1]));
      ErrMsg[0] = 0;
      PetscCall(PetscPushErrorHandler(CaptureHandler, NULL));
      ierr = NewtonLineSearchCreate(PETSC_COMM_WORLD, &nls);
      PetscCall(PetscPopErrorHandler());
      PetscCall(PetscOptionsClearValue(NULL, opt[k][0]));
      snprintf(what, sizeof(what), "%s %s refused naming the option: %s", opt[k][0], opt[k][1], ErrMsg);
      Ok(ierr != 0 && strstr(ErrMsg, opt[k][0] + 1), what);
      if (!ierr) PetscCall(NewtonLineSearchDestroy(&nls));
    }
  }
  PetscCall(PetscFinalize());
  return nfail ? 1 : 0;
}
