/* For the unit-test programs that check error messages: an error handler that keeps the message
   of the error where it was raised in ErrMsg (push it around the call that should fail). */
#ifndef ATRITO_TESTCAPTURE_H
#define ATRITO_TESTCAPTURE_H
#include <stdio.h>
#include <petscsys.h>

static char ErrMsg[4096];

static inline PetscErrorCode CaptureHandler(MPI_Comm comm, int line, const char *fun, const char *file, PetscErrorCode n, PetscErrorType p, const char *mess, void *ctx)
{
  (void)comm;
  (void)line;
  (void)fun;
  (void)file;
  (void)ctx;
  if (p == PETSC_ERROR_INITIAL) snprintf(ErrMsg, sizeof(ErrMsg), "%s", mess ? mess : "");
  return n;
}
#endif
