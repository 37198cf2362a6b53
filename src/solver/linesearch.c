/* Newton's watchdog line search (linesearch.h): a shell line search of PETSc's SNES. */
#include "linesearch.h"
#include "options.h"

struct _n_NewtonLineSearch {
  PetscInt  where;    /* -newton_watchdog: 1 release stages, 2 every stage without contact       */
  PetscBool active;   /* the SNES's line search is this one                                    */
  char      type[64]; /* the line search type it replaced                                      */
  PetscReal rise;     /* kappa: a full step may raise |R| up to this factor (a relaxed step)    */
  PetscReal alpha;    /* the sufficient decrease, as a fraction of the slope                  */
  PetscBool watching; /* the last iteration took a relaxed step: Xr, Fr, Yr, fr its origin     */
  Vec       Xr, Fr, Yr;
  PetscReal fr, gr;   /* |R| at the origin, and at the relaxed step's end                     */
  PetscInt  relaxed, reverted, trials; /* relaxed steps, those undone, residual evaluations */
};

PetscErrorCode NewtonLineSearchCreate(MPI_Comm comm, NewtonLineSearch *nls)
{
  PetscReal   rise = 1000, alpha = 1e-4;
  PetscBool   given;
  const char *where[] = {"none", "release", "contactfree", "NewtonWatchdog", "WATCHDOG_", NULL};
  PetscInt    w       = 1;

  PetscFunctionBeginUser;
  *nls = NULL;
  PetscCall(PetscOptionsHasName(NULL, NULL, "-snes_linesearch_type", &given));
  PetscOptionsBegin(comm, NULL, "Newton's line search", NULL);
  PetscCall(PetscOptionsEList("-newton_watchdog", "Where Newton uses the watchdog line search instead of PETSc's (-snes_linesearch_type, which when given is used everywhere): nowhere, in the stages that release their tools by nodal forces and have no tool present (an elastic unloading), or in every stage without a tool present", "include/linesearch.h", where, 3, where[w], &w, NULL));
  PetscCall(PetscOptionsReal("-newton_linesearch_rise", "Watchdog line search: a full Newton step that raises |R| by at most this factor is taken; the next iteration must bring |R| below that step's origin (Armijo), else the iterate returns to the origin and backtracks along the step", "include/linesearch.h", rise, &rise, NULL));
  PetscCall(PetscOptionsReal("-newton_linesearch_alpha", "Watchdog line search: the sufficient decrease, a fraction of the slope of |R|^2/2 along the Newton step", "include/linesearch.h", alpha, &alpha, NULL));
  PetscOptionsEnd();
  PetscCheck(rise >= 1 && PetscIsNormalReal(rise), comm, PETSC_ERR_USER_INPUT, "-newton_linesearch_rise %g must be at least 1", (double)rise);
  PetscCheck(alpha > 0 && alpha < 0.5, comm, PETSC_ERR_USER_INPUT, "-newton_linesearch_alpha %g must lie in (0, 0.5)", (double)alpha);
  if (w == 0 || given) PetscFunctionReturn(0);
  PetscCall(PetscNew(nls));
  (*nls)->where = w;
  (*nls)->rise  = rise;
  (*nls)->alpha = alpha;
  PetscFunctionReturn(0);
}

/* Monotone backtracking from X along -Y after a failed trial (lambda, |R_t| = g): the minimiser of
   the quadratic through phi(0) = 1/2 f^2, phi'(0) = -f^2 (the slope along the Newton direction;
   an inexact linear solve changes it by its relative residual, which alpha << 1 absorbs) and
   phi(lambda) = 1/2 g^2, lambda^2 f^2 / (g^2 - f^2 + 2 lambda f^2), kept within [0.1, 0.5] lambda;
   the denominator is positive for every failed trial (g^2 > f^2 - 2 alpha lambda f^2). A trial
   whose residual is not finite (an element inverted, a return map failed) halves lambda. On
   success W, G hold the accepted point and its residual. */
static PetscErrorCode Backtrack(NewtonLineSearch nls, SNESLineSearch ls, SNES snes, PetscViewer mon, Vec X, Vec Y, Vec W, Vec G, PetscReal f, PetscReal lambda, PetscReal g, PetscReal *lambda_out, PetscReal *g_out, PetscBool *ok)
{
  const PetscReal f2 = f * f;
  PetscReal       minlambda;

  PetscFunctionBeginUser;
  PetscCall(SNESLineSearchGetTolerances(ls, &minlambda, NULL, NULL, NULL, NULL, NULL));
  *ok = PETSC_FALSE;
  for (;;) {
    if (PetscIsInfOrNanReal(g)) lambda *= 0.5;
    else lambda = PetscMin(0.5 * lambda, PetscMax(0.1 * lambda, lambda * lambda * f2 / (g * g - f2 + 2 * lambda * f2)));
    if (lambda < minlambda) {
      if (mon) PetscCall(PetscViewerASCIIPrintf(mon, "      Line search (watchdog): failed, lambda below %g (-snes_linesearch_minlambda)\n", (double)minlambda));
      PetscFunctionReturn(0);
    }
    PetscCall(VecWAXPY(W, -lambda, Y, X));
    PetscCall(SNESComputeFunction(snes, W, G));
    PetscCall(VecNorm(G, NORM_2, &g));
    nls->trials++;
    if (mon) PetscCall(PetscViewerASCIIPrintf(mon, "      Line search (watchdog): lambda %g: |R| %g against %g\n", (double)lambda, (double)g, (double)f));
    if (!PetscIsInfOrNanReal(g) && g * g <= f2 - 2 * nls->alpha * lambda * f2) break;
  }
  *lambda_out = lambda;
  *g_out      = g;
  *ok         = PETSC_TRUE;
  PetscFunctionReturn(0);
}

/* the line search: see linesearch.h */
static PetscErrorCode NewtonLineSearchApply(SNESLineSearch ls, void *ctx)
{
  NewtonLineSearch nls = (NewtonLineSearch)ctx;
  SNES             snes;
  Vec              X, F, Y, W, G;
  PetscReal        xnorm, fnorm, ynorm, g, lambda = 1;
  PetscBool        changed, ok = PETSC_TRUE;
  PetscInt         it;
  PetscViewer      mon;

  PetscFunctionBeginUser;
  PetscCall(SNESLineSearchGetSNES(ls, &snes));
  PetscCall(SNESGetIterationNumber(snes, &it));
  PetscCall(SNESLineSearchGetVecs(ls, &X, &F, &Y, &W, &G));
  PetscCall(SNESLineSearchGetNorms(ls, &xnorm, &fnorm, &ynorm));
  PetscCall(SNESLineSearchGetDefaultMonitor(ls, &mon));
  PetscCall(SNESLineSearchPreCheck(ls, X, Y, &changed));
  PetscCall(SNESLineSearchSetReason(ls, SNES_LINESEARCH_SUCCEEDED));
  if (it == 0) nls->watching = PETSC_FALSE; /* a new solve: the residual may be another (the
                                               augmented Lagrangian's multipliers) */
  if (!nls->Xr) {
    PetscCall(VecDuplicate(X, &nls->Xr));
    PetscCall(VecDuplicate(X, &nls->Fr));
    PetscCall(VecDuplicate(X, &nls->Yr));
  }
  PetscCall(VecWAXPY(W, -1.0, Y, X));
  PetscCall(SNESComputeFunction(snes, W, G));
  PetscCall(VecNorm(G, NORM_2, &g));
  nls->trials++;
  if (nls->watching) {
    /* the iteration after a relaxed step: its full step must bring |R| below the origin's by the
       Armijo amount of the origin's full step, else back to the origin */
    nls->watching = PETSC_FALSE;
    if (!PetscIsInfOrNanReal(g) && g * g <= (1 - 2 * nls->alpha) * nls->fr * nls->fr) {
      if (mon) PetscCall(PetscViewerASCIIPrintf(mon, "      Line search (watchdog): full step |R| %g -> %g, below the relaxed step's origin %g\n", (double)fnorm, (double)g, (double)nls->fr));
    } else {
      nls->reverted++;
      if (mon) PetscCall(PetscViewerASCIIPrintf(mon, "      Line search (watchdog): full step |R| %g -> %g, not below the relaxed step's origin %g: back there\n", (double)fnorm, (double)g, (double)nls->fr));
      PetscCall(VecCopy(nls->Xr, X));
      PetscCall(VecCopy(nls->Fr, F));
      PetscCall(VecCopy(nls->Yr, Y));
      fnorm = nls->fr;
      PetscCall(Backtrack(nls, ls, snes, mon, X, Y, W, G, fnorm, 1.0, nls->gr, &lambda, &g, &ok));
    }
  } else if (!PetscIsInfOrNanReal(g) && g * g <= (1 - 2 * nls->alpha) * fnorm * fnorm) {
    if (mon) PetscCall(PetscViewerASCIIPrintf(mon, "      Line search (watchdog): full step |R| %g -> %g\n", (double)fnorm, (double)g));
  } else if (!PetscIsInfOrNanReal(g) && g <= nls->rise * fnorm) {
    /* a relaxed step: taken whole, its origin kept */
    nls->relaxed++;
    nls->watching = PETSC_TRUE;
    nls->fr       = fnorm;
    nls->gr       = g;
    PetscCall(VecCopy(X, nls->Xr));
    PetscCall(VecCopy(F, nls->Fr));
    PetscCall(VecCopy(Y, nls->Yr));
    if (mon) PetscCall(PetscViewerASCIIPrintf(mon, "      Line search (watchdog): relaxed full step |R| %g -> %g (at most %g times, -newton_linesearch_rise)\n", (double)fnorm, (double)g, (double)nls->rise));
  } else {
    if (mon) PetscCall(PetscViewerASCIIPrintf(mon, "      Line search (watchdog): full step |R| %g -> %g: backtracking\n", (double)fnorm, (double)g));
    PetscCall(Backtrack(nls, ls, snes, mon, X, Y, W, G, fnorm, 1.0, g, &lambda, &g, &ok));
  }
  if (!ok) {
    PetscCall(SNESLineSearchSetReason(ls, SNES_LINESEARCH_FAILED_REDUCT));
    PetscFunctionReturn(0);
  }
  PetscCall(VecNorm(Y, NORM_2, &ynorm));
  PetscCall(VecCopy(W, X));
  PetscCall(VecCopy(G, F));
  PetscCall(VecNorm(X, NORM_2, &xnorm));
  PetscCall(SNESLineSearchSetLambda(ls, lambda));
  PetscCall(SNESLineSearchSetNorms(ls, xnorm, g, ynorm));
  PetscFunctionReturn(0);
}

PetscErrorCode NewtonLineSearchSetStage(NewtonLineSearch nls, SNES snes, PetscBool contact, PetscBool nodal_release)
{
  SNESLineSearch ls;
  PetscBool      on;

  PetscFunctionBeginUser;
  if (!nls) PetscFunctionReturn(0);
  on = (!contact && (nls->where == 2 || nodal_release)) ? PETSC_TRUE : PETSC_FALSE;
  if (on == nls->active) PetscFunctionReturn(0);
  PetscCall(SNESGetLineSearch(snes, &ls));
  if (on) {
    SNESLineSearchType type;
    PetscCall(SNESLineSearchGetType(ls, &type));
    PetscCall(PetscStrncpy(nls->type, type, sizeof(nls->type)));
    PetscCall(SNESLineSearchSetType(ls, SNESLINESEARCHSHELL));
    PetscCall(SNESLineSearchShellSetUserFunc(ls, NewtonLineSearchApply, nls));
  } else {
    /* the line search it replaced, with its options again (the pre-check stays set) */
    PetscCall(SNESLineSearchSetType(ls, nls->type));
    PetscCall(SNESLineSearchSetFromOptions(ls));
  }
  nls->active = on;
  PetscFunctionReturn(0);
}

PetscErrorCode NewtonLineSearchGetCounts(NewtonLineSearch nls, PetscInt *relaxed, PetscInt *reverted, PetscInt *trials)
{
  PetscFunctionBeginUser;
  *relaxed  = nls ? nls->relaxed : 0;
  *reverted = nls ? nls->reverted : 0;
  *trials   = nls ? nls->trials : 0;
  PetscFunctionReturn(0);
}

PetscErrorCode NewtonLineSearchDestroy(NewtonLineSearch *nls)
{
  PetscFunctionBeginUser;
  if (!*nls) PetscFunctionReturn(0);
  PetscCall(VecDestroy(&(*nls)->Xr));
  PetscCall(VecDestroy(&(*nls)->Fr));
  PetscCall(VecDestroy(&(*nls)->Yr));
  PetscCall(PetscFree(*nls));
  PetscFunctionReturn(0);
}
