/* Piecewise-linear curves of the process time (include/loadcurve.h). */
#include <ctype.h>
#include <stdlib.h>
#include <string.h>
#include "loadcurve.h"
#include "util.h"

/* checks the points: finite, times strictly increasing; message names opt */
static PetscErrorCode CheckPoints(MPI_Comm comm, const char opt[], PetscInt n, const PetscReal t[], const PetscReal v[])
{
  PetscFunctionBeginUser;
  PetscCheck(n >= 1, comm, PETSC_ERR_USER_INPUT, "%s: a curve needs at least one point (time, value)", opt);
  for (PetscInt i = 0; i < n; i++) {
    PetscCheck(!PetscIsInfOrNanReal(t[i]) && !PetscIsInfOrNanReal(v[i]), comm, PETSC_ERR_USER_INPUT, "%s: point %" PetscInt_FMT " (%g, %g) is not finite", opt, i, (double)t[i], (double)v[i]);
    PetscCheck(i == 0 || t[i] > t[i - 1], comm, PETSC_ERR_USER_INPUT, "%s: times must increase (point %" PetscInt_FMT ": %g after %g)", opt, i, (double)t[i], (double)t[i - 1]);
  }
  PetscFunctionReturn(0);
}

PetscErrorCode LoadCurveCreate(MPI_Comm comm, const char opt[], PetscInt n, const PetscReal t[], const PetscReal v[], LoadCurve *c)
{
  PetscFunctionBeginUser;
  PetscCall(CheckPoints(comm, opt, n, t, v));
  PetscCall(PetscMalloc2(n, &c->t, n, &c->v));
  PetscCall(PetscArraycpy(c->t, t, n));
  PetscCall(PetscArraycpy(c->v, v, n));
  c->n = n;
  PetscFunctionReturn(0);
}

PetscErrorCode LoadCurveDuplicate(const LoadCurve *a, LoadCurve *c)
{
  PetscFunctionBeginUser;
  c->n = 0;
  c->t = c->v = NULL;
  if (a->n) {
    PetscCall(PetscMalloc2(a->n, &c->t, a->n, &c->v));
    PetscCall(PetscArraycpy(c->t, a->t, a->n));
    PetscCall(PetscArraycpy(c->v, a->v, a->n));
    c->n = a->n;
  }
  PetscFunctionReturn(0);
}

PetscErrorCode LoadCurveDestroy(LoadCurve *c)
{
  PetscFunctionBeginUser;
  if (c->n) PetscCall(PetscFree2(c->t, c->v));
  c->n = 0;
  c->t = c->v = NULL;
  PetscFunctionReturn(0);
}

/* reads numbers from s into a (at most max); *n the count; *bad the first token that is not a
   number (NULL if none) */
static void ParseNumbers(const char *s, PetscReal *a, PetscInt max, PetscInt *n, const char **bad)
{
  *n   = 0;
  *bad = NULL;
  while (*s) {
    char  *end;
    double x;
    while (*s && (isspace((unsigned char)*s) || *s == ',')) s++;
    if (!*s || *s == '#') break;
    x = strtod(s, &end);
    if (end == s) {
      *bad = s;
      return;
    }
    if (*n < max) a[*n] = x;
    (*n)++;
    s = end;
  }
}

/* rank 0: the points of a two-column file; returns 0, or 1 (cannot read), 2 (bad line: *line) */
static int ReadFile(const char *path, PetscInt *n, PetscReal **t, PetscReal **v, PetscInt *line)
{
  FILE    *fp = fopen(path, "r");
  char     buf[4096];
  PetscInt cap = 0;

  *n = 0;
  *t = *v = NULL;
  *line   = 0;
  if (!fp) return 1;
  while (fgets(buf, sizeof(buf), fp)) {
    PetscReal   x[3];
    PetscInt    k;
    const char *bad;
    (*line)++;
    ParseNumbers(buf, x, 3, &k, &bad);
    if (k == 0 && !bad) continue; /* blank or comment */
    if (bad || k != 2) {
      fclose(fp);
      return 2;
    }
    if (*n == cap) {
      cap = cap ? 2 * cap : 64;
      *t  = (PetscReal *)realloc(*t, cap * sizeof(PetscReal));
      *v  = (PetscReal *)realloc(*v, cap * sizeof(PetscReal));
      if (!*t || !*v) {
        fclose(fp);
        return 1;
      }
    }
    (*t)[*n] = x[0];
    (*v)[*n] = x[1];
    (*n)++;
  }
  fclose(fp);
  return 0;
}

PetscErrorCode LoadCurveParse(MPI_Comm comm, const char opt[], const char str[], LoadCurve *c)
{
  PetscReal   a[2 * LOADCURVE_INLINE_MAX], *t = NULL, *v = NULL;
  PetscInt    n, line = 0;
  const char *bad;
  PetscMPIInt rank;
  int         status = 0;

  PetscFunctionBeginUser;
  c->n = 0;
  c->t = c->v = NULL;
  PetscCheck(str && str[0], comm, PETSC_ERR_USER_INPUT, "%s: empty curve (give t0,v0,t1,v1,... or a file)", opt);
  if (strchr(str, ',')) { /* inline */
    ParseNumbers(str, a, 2 * LOADCURVE_INLINE_MAX, &n, &bad);
    PetscCheck(!bad, comm, PETSC_ERR_USER_INPUT, "%s: '%s' is not a number", opt, bad);
    PetscCheck(n % 2 == 0, comm, PETSC_ERR_USER_INPUT, "%s: %" PetscInt_FMT " numbers; a curve is pairs time,value", opt, n);
    PetscCheck(n <= 2 * LOADCURVE_INLINE_MAX, comm, PETSC_ERR_USER_INPUT, "%s: %" PetscInt_FMT " points inline, at most %d: put the curve in a file", opt, n / 2, LOADCURVE_INLINE_MAX);
    n /= 2;
    PetscCall(PetscMalloc2(n, &t, n, &v));
    for (PetscInt i = 0; i < n; i++) {
      t[i] = a[2 * i];
      v[i] = a[2 * i + 1];
    }
    { /* the copies are freed whether or not the curve is accepted */
      PetscErrorCode ierr = LoadCurveCreate(comm, opt, n, t, v, c);
      PetscCall(PetscFree2(t, v));
      PetscCall(ierr);
    }
    PetscFunctionReturn(0);
  }
  ParseNumbers(str, a, 2, &n, &bad);
  PetscCheck(bad || n != 1, comm, PETSC_ERR_USER_INPUT, "%s: a single number %s; a curve is pairs time,value or a file", opt, str);
  PetscCallMPI(MPI_Comm_rank(comm, &rank));
  if (!rank) status = ReadFile(str, &n, &t, &v, &line);
  PetscCallMPI(MPI_Bcast(&status, 1, MPI_INT, 0, comm));
  if (status) {
    free(t);
    free(v);
  }
  PetscCheck(status != 1, comm, PETSC_ERR_FILE_OPEN, "%s: cannot read the curve file '%s'", opt, str);
  PetscCallMPI(MPI_Bcast(&line, 1, MPIU_INT, 0, comm));
  PetscCheck(status != 2, comm, PETSC_ERR_USER_INPUT, "%s: %s line %" PetscInt_FMT ": expected two numbers (time value)", opt, str, line);
  PetscCallMPI(MPI_Bcast(&n, 1, MPIU_INT, 0, comm));
  if (rank) {
    t = (PetscReal *)malloc(PetscMax(n, 1) * sizeof(PetscReal));
    v = (PetscReal *)malloc(PetscMax(n, 1) * sizeof(PetscReal));
    PetscCheck(t && v, PETSC_COMM_SELF, PETSC_ERR_MEM, "%s: out of memory for %" PetscInt_FMT " points", opt, n);
  }
  if (n) {
    PetscCallMPI(MPI_Bcast(t, (PetscMPIInt)n, MPIU_REAL, 0, comm));
    PetscCallMPI(MPI_Bcast(v, (PetscMPIInt)n, MPIU_REAL, 0, comm));
  }
  {
    PetscErrorCode ierr = LoadCurveCreate(comm, opt, n, t, v, c);
    free(t);
    free(v);
    PetscCall(ierr);
  }
  PetscFunctionReturn(0);
}

/* index i of the piece [t_i, t_i+1] that contains t (t_0 <= t < t_n-1), by bisection */
static PetscInt Piece(const LoadCurve *c, PetscReal t)
{
  PetscInt lo = 0, hi = c->n - 1;
  while (hi - lo > 1) {
    PetscInt mid = (lo + hi) / 2;
    if (c->t[mid] <= t) lo = mid;
    else hi = mid;
  }
  return lo;
}

PetscReal LoadCurveEval(const LoadCurve *c, PetscReal t)
{
  PetscInt i;
  if (!c->n) return 0;
  if (t <= c->t[0]) return c->v[0];
  if (t >= c->t[c->n - 1]) return c->v[c->n - 1];
  i = Piece(c, t);
  return c->v[i] + (c->v[i + 1] - c->v[i]) * (t - c->t[i]) / (c->t[i + 1] - c->t[i]);
}

PetscReal LoadCurveSlope(const LoadCurve *c, PetscReal t)
{
  PetscInt i;
  if (c->n < 2 || t < c->t[0] || t >= c->t[c->n - 1]) return 0;
  i = Piece(c, t);
  return (c->v[i + 1] - c->v[i]) / (c->t[i + 1] - c->t[i]);
}

PetscReal LoadCurveNextKink(const LoadCurve *c, PetscReal t)
{
  for (PetscInt i = 0; i < c->n; i++)
    if (c->t[i] > t) return c->t[i];
  return PETSC_INFINITY;
}
