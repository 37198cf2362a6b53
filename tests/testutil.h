/* Minimal assertion helpers for the unit-test programs: every check prints one line
   "ok - ..." or "not ok - ...", and the program's exit code is the number of failures. */
#ifndef ATRITO_TESTUTIL_H
#define ATRITO_TESTUTIL_H
#include <stdio.h>
#include <math.h>

static int tu_failed = 0, tu_passed = 0;

#define TU_CHECK(cond, ...)                                                                   \
  do {                                                                                        \
    if (cond) { tu_passed++; printf("ok - "); } else { tu_failed++; printf("not ok - "); }    \
    printf(__VA_ARGS__);                                                                      \
    printf("\n");                                                                             \
    fflush(stdout);                                                                           \
  } while (0)

/* relative difference with a floor on the scale */
static inline double tu_reldiff(double a, double b, double floor_)
{
  double s = fabs(b) > floor_ ? fabs(b) : floor_;
  return fabs(a - b) / s;
}

#define TU_RETURN() return (tu_failed > 255 ? 255 : tu_failed)

#ifdef PETSCSYS_H
/* a check that every rank evaluates: it passes when it holds on all of them; rank 0 (the file's
   PetscMPIInt rank) prints */
#define CHECK_ALL(cond, ...)                                                                 \
  do {                                                                                       \
    int c_ = (cond) ? 1 : 0, g_ = 0;                                                         \
    PetscCallMPI(MPI_Allreduce(&c_, &g_, 1, MPI_INT, MPI_MIN, PETSC_COMM_WORLD));            \
    if (rank == 0) TU_CHECK(g_, __VA_ARGS__);                                                \
  } while (0)
#endif
#endif
