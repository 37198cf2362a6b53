/* Piecewise-linear curves (src/util/loadcurve.c): values and slopes against the closed form,
   kinks, inline and file input, and the one-line errors of bad input (at 1 and 2 ranks). */
#include <stdio.h>
#include "loadcurve.h"
#include "testcapture.h"

static int nfail = 0, ntest = 0;
static void Ok(int cond, const char *what)
{
  ntest++;
  if (!cond) nfail++;
  PetscPrintf(PETSC_COMM_WORLD, "%s - %s\n", cond ? "ok" : "not ok", what);
}

/* parsing str must fail with a message containing want */
static PetscErrorCode ExpectError(const char *str, const char *want)
{
  LoadCurve      c;
  PetscErrorCode ierr;
  char           what[512];

  PetscFunctionBeginUser;
  ErrMsg[0] = 0;
  PetscCall(PetscPushErrorHandler(CaptureHandler, NULL));
  ierr = LoadCurveParse(PETSC_COMM_WORLD, "-bc_x_amplitude", str, &c);
  PetscCall(PetscPopErrorHandler());
  snprintf(what, sizeof(what), "'%s' refused naming the option: %s", str, ErrMsg);
  Ok(ierr != 0 && strstr(ErrMsg, "-bc_x_amplitude") && strstr(ErrMsg, want), what);
  PetscFunctionReturn(0);
}

int main(int argc, char **argv)
{
  LoadCurve   c, d, f;
  PetscMPIInt rank;
  const char *path = "test_loadcurve.dat";

  PetscCall(PetscInitialize(&argc, &argv, NULL, NULL));
  PetscCallMPI(MPI_Comm_rank(PETSC_COMM_WORLD, &rank));
  PetscCall(LoadCurveParse(PETSC_COMM_WORLD, "-opt", "0,0, 1,2, 3,-1", &c));
  Ok(c.n == 3, "inline: three points");
  Ok(LoadCurveEval(&c, -1) == 0 && LoadCurveEval(&c, 5) == -1, "constant beyond the ends");
  Ok(PetscAbsReal(LoadCurveEval(&c, 0.25) - 0.5) < 1e-15 && PetscAbsReal(LoadCurveEval(&c, 2) - 0.5) < 1e-15, "linear between points");
  Ok(LoadCurveEval(&c, 1) == 2, "exact at a point");
  Ok(LoadCurveSlope(&c, 0.5) == 2 && LoadCurveSlope(&c, 1) == -1.5 && LoadCurveSlope(&c, 3) == 0, "slope from the right");
  Ok(LoadCurveNextKink(&c, 0) == 1 && LoadCurveNextKink(&c, 1) == 3 && LoadCurveNextKink(&c, 3) == PETSC_INFINITY, "next kink");
  /* a file with comments and blank lines gives the same curve */
  if (!rank) {
    FILE *fp = fopen(path, "w");
    fprintf(fp, "# time value\n0 0\n\n1 2   # peak\n3 -1\n");
    fclose(fp);
  }
  PetscCallMPI(MPI_Barrier(PETSC_COMM_WORLD));
  PetscCall(LoadCurveParse(PETSC_COMM_WORLD, "-opt", path, &f));
  Ok(f.n == 3 && f.t[1] == 1 && f.v[2] == -1 && LoadCurveEval(&f, 2) == LoadCurveEval(&c, 2), "file: the same curve on every rank");
  PetscCall(LoadCurveDuplicate(&f, &d));
  Ok(d.n == 3 && d.t != f.t && LoadCurveEval(&d, 0.7) == LoadCurveEval(&c, 0.7), "duplicate");
  PetscCall(LoadCurveDestroy(&c));
  PetscCall(LoadCurveDestroy(&d));
  PetscCall(LoadCurveDestroy(&f));
  Ok(c.n == 0 && LoadCurveEval(&c, 1) == 0, "destroyed curve is empty");
  if (!rank) {
    FILE *fp = fopen(path, "w");
    fprintf(fp, "0 0\n1 nan\n");
    fclose(fp);
  }
  PetscCallMPI(MPI_Barrier(PETSC_COMM_WORLD));
  PetscCall(ExpectError(path, "not finite"));
  if (!rank) {
    FILE *fp = fopen(path, "w");
    fprintf(fp, "0 0\n1 2 3\n");
    fclose(fp);
    remove("test_loadcurve.missing");
  }
  PetscCallMPI(MPI_Barrier(PETSC_COMM_WORLD));
  PetscCall(ExpectError(path, "line 2"));
  PetscCall(ExpectError("test_loadcurve.missing", "cannot read"));
  PetscCall(ExpectError("0,0,1", "pairs"));
  PetscCall(ExpectError("0,0,1,x", "not a number"));
  PetscCall(ExpectError("0,0,0,1", "times must increase"));
  PetscCall(ExpectError("0,nan", "not finite"));
  PetscCall(ExpectError("2.5", "single number"));
  if (!rank) remove(path);
  PetscCall(PetscPrintf(PETSC_COMM_WORLD, "%d passed, %d failed\n", ntest - nfail, nfail));
  PetscCall(PetscFinalize());
  return nfail != 0;
}
