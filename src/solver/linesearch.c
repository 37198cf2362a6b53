/* Newton's watchdog line search (linesearch.h): a shell line search of PETSc's SNES. */
#include "linesearch.h"
#include "options.h"

struct _n_NewtonLineSearch {
  PetscInt  where;    /* -newton_watchdog: 0 nowhere, 1 release stages, 2 every stage without contact */
  PetscBool energy;   /* -newton_linesearch_contact energy: the stages with a tool present       */
  PetscInt  mode;     /* the current stage's: 0 PETSc's, 1 the watchdog, 2 the energy search     */
  PetscBool active;   /* the SNES's line search is this one                                    */
  PetscReal eta;      /* energy search: |R(x - lambda y).y| <= eta R(x).y accepts lambda          */
  PetscInt  maxit;    /* energy search: residual evaluations per search                         */
  const PetscInt *nfail; /* the problem's count of evaluations outside the residual's domain     */
  PetscErrorCode (*limit)(void *, Vec, Vec, PetscReal *); /* the longest step the geometry allows */
  void     *limit_ctx;
  PetscInt  limited;  /* energy searches whose first trial the limit shortened */
  PetscInt  searches, energy_trials, energy_fallback; /* energy search: searches, residual evaluations, searches that fell back to |R| */
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
  PetscReal   rise = 1000, alpha = 1e-4, eta = 0.5;
  PetscBool   given;
  const char *where[] = {"none", "release", "contactfree", "NewtonWatchdog", "WATCHDOG_", NULL};
  const char *cont[]  = {"petsc", "energy", "NewtonContactSearch", "NCS_", NULL};
  PetscInt    w = 1, c = 1, maxit = 6;

  PetscFunctionBeginUser;
  *nls = NULL;
  PetscCall(PetscOptionsHasName(NULL, NULL, "-snes_linesearch_type", &given));
  PetscOptionsBegin(comm, NULL, "Newton's line search", NULL);
  PetscCall(PetscOptionsEList("-newton_watchdog", "Where Newton uses the watchdog line search instead of PETSc's (-snes_linesearch_type, which when given is used everywhere): nowhere, in the stages that release their tools by nodal forces and have no tool present (an elastic unloading), or in every stage without a tool present", "include/linesearch.h", where, 3, where[w], &w, NULL));
  PetscCall(PetscOptionsReal("-newton_linesearch_rise", "Watchdog line search: a full Newton step that raises |R| by at most this factor is taken; the next iteration must bring |R| below that step's origin (Armijo), else the iterate returns to the origin and backtracks along the step", "include/linesearch.h", rise, &rise, NULL));
  PetscCall(PetscOptionsReal("-newton_linesearch_alpha", "Watchdog line search: the sufficient decrease, a fraction of the slope of |R|^2/2 along the Newton step", "include/linesearch.h", alpha, &alpha, NULL));
  PetscCall(PetscOptionsEList("-newton_linesearch_contact", "The line search of the stages with a tool present: PETSc's (-snes_linesearch_type), or energy (the step length where the residual is orthogonal to the Newton direction, the stationary point of the energy along it; a trial point outside the residual's domain shortens the step)", "include/linesearch.h", cont, 2, cont[c], &c, NULL));
  PetscCall(PetscOptionsReal("-newton_linesearch_eta", "Energy line search: a step length lambda is accepted when |R(x - lambda y).y| <= eta R(x).y", "include/linesearch.h", eta, &eta, NULL));
  PetscCall(PetscOptionsInt("-newton_linesearch_max_it", "Energy line search: residual evaluations per search", "include/linesearch.h", maxit, &maxit, NULL));
  PetscOptionsEnd();
  PetscCheck(rise >= 1 && PetscIsNormalReal(rise), comm, PETSC_ERR_USER_INPUT, "-newton_linesearch_rise %g must be at least 1", (double)rise);
  PetscCheck(alpha > 0 && alpha < 0.5, comm, PETSC_ERR_USER_INPUT, "-newton_linesearch_alpha %g must lie in (0, 0.5)", (double)alpha);
  PetscCheck(eta > 0 && eta < 1, comm, PETSC_ERR_USER_INPUT, "-newton_linesearch_eta %g must lie in (0, 1)", (double)eta);
  PetscCheck(maxit >= 1 && maxit <= 100, comm, PETSC_ERR_USER_INPUT, "-newton_linesearch_max_it %" PetscInt_FMT " must lie in [1, 100]", maxit);
  if ((w == 0 && c == 0) || given) PetscFunctionReturn(0);
  PetscCall(PetscNew(nls));
  (*nls)->where  = w;
  (*nls)->energy = c == 1 ? PETSC_TRUE : PETSC_FALSE;
  (*nls)->rise   = rise;
  (*nls)->alpha  = alpha;
  (*nls)->eta    = eta;
  (*nls)->maxit  = maxit;
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

/* Energy line search (linesearch.h): the step length lambda along -Y where the residual is
   orthogonal to the Newton direction, s(lambda) = R(X - lambda Y).Y = 0. Where the problem has a
   potential Pi (elasticity, frictionless penalty contact, the incremental potential of plasticity)
   s = -dPi/dlambda along the step, so the search finds the stationary point of the energy along
   it: a node that the full step carries deep into a tool, or a floppy sheet that it overshoots,
   raises |R| at the full step although the energy has a minimum near it, which a search on |R|
   rejects (PETSc's backtracking took lambda = 0.01 to 0.1 for tens of iterations there,
   doc/contact.md). Accepted: |s(lambda)| <= eta s(0) (Crisfield's criterion); the full step is taken
   also when the energy still falls at it (s(1) > 0). Otherwise the zero of s is bracketed and found
   by the Illinois variant of regula falsi. A trial point outside the residual's domain (an inverted
   element, a return map that does not converge) shortens the step towards the bracket's lower end.
   Where Y is not a descent direction of the energy (s(0) <= 0: a non-symmetric or indefinite
   Jacobian), or no point was evaluated, the monotone backtracking on |R| takes over. */
static PetscErrorCode EnergySearch(NewtonLineSearch nls, SNESLineSearch ls, SNES snes, PetscViewer mon, Vec X, Vec F, Vec Y, Vec W, Vec G, PetscReal fnorm, PetscReal *lambda_out, PetscReal *g_out, PetscBool *ok)
{
  PetscScalar s0s;
  PetscReal   s0, lo = 0, slo, hi = -1, shi = 0, lam = 1, best = -1, bests = PETSC_MAX_REAL, minlambda;
  PetscInt    side = 0; /* Illinois: which end was kept last */
  PetscBool   failed;

  PetscFunctionBeginUser;
  *ok = PETSC_FALSE;
  PetscCall(SNESLineSearchGetTolerances(ls, &minlambda, NULL, NULL, NULL, NULL, NULL));
  PetscCall(VecDot(F, Y, &s0s));
  s0  = PetscRealPart(s0s);
  slo = s0;
  if (nls->limit) { /* the longest step the geometry allows (contact: no node driven deep into a tool) */
    PetscReal lmax = PETSC_MAX_REAL;
    PetscCall(nls->limit(nls->limit_ctx, X, Y, &lmax));
    if (lmax < 1) {
      lam = PetscMax(lmax, minlambda);
      nls->limited++;
      if (mon) PetscCall(PetscViewerASCIIPrintf(mon, "      Line search (energy): step limited to lambda %g by the contact geometry\n", (double)lam));
    }
  }
  if (!(s0 > 0) || PetscIsInfOrNanReal(s0)) {
    /* not a descent direction of the energy: backtracking on |R| */
    PetscReal g;
    nls->energy_fallback++;
    PetscCall(VecWAXPY(W, -1.0, Y, X));
    PetscCall(SNESComputeFunction(snes, W, G));
    PetscCall(VecNorm(G, NORM_2, &g));
    nls->trials++;
    if (mon) PetscCall(PetscViewerASCIIPrintf(mon, "      Line search (energy): R.Y = %g at the iterate, not a descent direction: backtracking on |R|\n", (double)s0));
    if (!PetscIsInfOrNanReal(g) && g * g <= (1 - 2 * nls->alpha) * fnorm * fnorm) {
      *lambda_out = 1;
      *g_out      = g;
      *ok         = PETSC_TRUE;
    } else PetscCall(Backtrack(nls, ls, snes, mon, X, Y, W, G, fnorm, 1.0, g, lambda_out, g_out, ok));
    PetscFunctionReturn(0);
  }
  for (PetscInt k = 0; k < nls->maxit; k++) {
    PetscScalar ss;
    PetscReal   s, g;
    PetscInt    nf0 = nls->nfail ? *nls->nfail : 0;
    if (lam < minlambda) break;
    PetscCall(VecWAXPY(W, -lam, Y, X));
    PetscCall(SNESComputeFunction(snes, W, G));
    nls->trials++;
    PetscCall(VecNorm(G, NORM_2, &g));
    failed = (PetscIsInfOrNanReal(g) || (nls->nfail && *nls->nfail != nf0)) ? PETSC_TRUE : PETSC_FALSE;
    if (failed) {
      if (mon) PetscCall(PetscViewerASCIIPrintf(mon, "      Line search (energy): lambda %g outside the residual's domain\n", (double)lam));
      hi  = lam;
      shi = -PETSC_MAX_REAL;
      lam = lo + 0.5 * (lam - lo);
      continue;
    }
    PetscCall(VecDot(G, Y, &ss));
    s = PetscRealPart(ss);
    if (mon) PetscCall(PetscViewerASCIIPrintf(mon, "      Line search (energy): lambda %g: R.Y %g of %g, |R| %g against %g\n", (double)lam, (double)s, (double)s0, (double)g, (double)fnorm));
    if (PetscAbsReal(s) < bests) {
      bests = PetscAbsReal(s);
      best  = lam;
    }
    if (PetscAbsReal(s) <= nls->eta * s0 || (s > 0 && hi < 0)) { /* accepted, or the energy still falls at the longest step */
      *lambda_out = lam;
      *g_out      = g;
      *ok         = PETSC_TRUE;
      PetscFunctionReturn(0);
    }
    if (s > 0) { /* below the stationary point */
      lo  = lam;
      slo = s;
      if (side == 1) shi *= 0.5; /* Illinois */
      side = 1;
    } else {
      hi  = lam;
      shi = s;
      if (side == -1) slo *= 0.5;
      side = -1;
    }
    if (shi == -PETSC_MAX_REAL) lam = lo + 0.5 * (hi - lo);
    else {
      const PetscReal z = lo - slo * (hi - lo) / (shi - slo); /* regula falsi */
      lam               = PetscMin(lo + 0.9 * (hi - lo), PetscMax(lo + 0.1 * (hi - lo), z));
    }
  }
  /* no point met the criterion: the evaluated one closest to stationary, evaluated again */
  if (best > 0) {
    PetscReal g;
    PetscCall(VecWAXPY(W, -best, Y, X));
    PetscCall(SNESComputeFunction(snes, W, G));
    nls->trials++;
    PetscCall(VecNorm(G, NORM_2, &g));
    if (!PetscIsInfOrNanReal(g)) {
      if (mon) PetscCall(PetscViewerASCIIPrintf(mon, "      Line search (energy): %d evaluations, lambda %g taken (|R.Y| %g of %g)\n", (int)nls->maxit, (double)best, (double)bests, (double)s0));
      *lambda_out = best;
      *g_out      = g;
      *ok         = PETSC_TRUE;
      PetscFunctionReturn(0);
    }
  }
  if (mon) PetscCall(PetscViewerASCIIPrintf(mon, "      Line search (energy): failed, no evaluable point down to lambda %g\n", (double)lam));
  PetscFunctionReturn(0);
}

/* the end of a search: the accepted point W, its residual G (norm g) and lambda become the line
   search's result, or the search failed */
static PetscErrorCode Accept(SNESLineSearch ls, PetscBool ok, Vec X, Vec F, Vec Y, Vec W, Vec G, PetscReal lambda, PetscReal g)
{
  PetscReal xnorm, ynorm;

  PetscFunctionBeginUser;
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
  if (nls->mode == 2) {
    const PetscInt t0 = nls->trials;
    PetscCall(EnergySearch(nls, ls, snes, mon, X, F, Y, W, G, fnorm, &lambda, &g, &ok));
    nls->searches++;
    nls->energy_trials += nls->trials - t0; /* counted apart from the watchdog's */
    nls->trials = t0;
    PetscCall(Accept(ls, ok, X, F, Y, W, G, lambda, g));
    PetscFunctionReturn(0);
  }
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
  PetscCall(Accept(ls, ok, X, F, Y, W, G, lambda, g));
  PetscFunctionReturn(0);
}

PetscErrorCode NewtonLineSearchSetStage(NewtonLineSearch nls, SNES snes, PetscBool contact, PetscBool nodal_release)
{
  SNESLineSearch ls;
  PetscInt       mode;

  PetscFunctionBeginUser;
  if (!nls) PetscFunctionReturn(0);
  mode = (!contact && nls->where > 0 && (nls->where == 2 || nodal_release)) ? 1 : ((contact && nls->energy) ? 2 : 0);
  if (mode == nls->mode) PetscFunctionReturn(0);
  PetscCall(SNESGetLineSearch(snes, &ls));
  if (mode && !nls->active) {
    SNESLineSearchType type;
    PetscCall(SNESLineSearchGetType(ls, &type));
    PetscCall(PetscStrncpy(nls->type, type, sizeof(nls->type)));
    PetscCall(SNESLineSearchSetType(ls, SNESLINESEARCHSHELL));
    PetscCall(SNESLineSearchShellSetUserFunc(ls, NewtonLineSearchApply, nls));
    nls->active = PETSC_TRUE;
  } else if (!mode && nls->active) {
    /* the line search it replaced, with its options again (the pre-check stays set) */
    PetscCall(SNESLineSearchSetType(ls, nls->type));
    PetscCall(SNESLineSearchSetFromOptions(ls));
    nls->active = PETSC_FALSE;
  }
  nls->mode     = mode;
  nls->watching = PETSC_FALSE;
  PetscFunctionReturn(0);
}

PetscBool NewtonLineSearchEnergy(NewtonLineSearch nls) { return (nls && nls->mode == 2) ? PETSC_TRUE : PETSC_FALSE; }

PetscErrorCode NewtonLineSearchSetStepLimit(NewtonLineSearch nls, PetscErrorCode (*limit)(void *, Vec, Vec, PetscReal *), void *ctx)
{
  PetscFunctionBeginUser;
  if (!nls) PetscFunctionReturn(0);
  nls->limit     = limit;
  nls->limit_ctx = ctx;
  PetscFunctionReturn(0);
}

PetscErrorCode NewtonLineSearchSetFailureCounter(NewtonLineSearch nls, const PetscInt *nfail)
{
  PetscFunctionBeginUser;
  if (nls) nls->nfail = nfail;
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

PetscErrorCode NewtonLineSearchGetEnergyCounts(NewtonLineSearch nls, PetscInt *searches, PetscInt *trials, PetscInt *limited, PetscInt *fallback)
{
  PetscFunctionBeginUser;
  *searches = nls ? nls->searches : 0;
  *trials   = nls ? nls->energy_trials : 0;
  *limited  = nls ? nls->limited : 0;
  *fallback = nls ? nls->energy_fallback : 0;
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
