/* Shared by the material unit tests (test_material, test_hill48, test_umat): random numbers,
   norms, rotations, and a Material created from an options string with its error captured. */
#ifndef ATRITO_TESTMAT_H
#define ATRITO_TESTMAT_H
#include <math.h>
#include "material.h"
#include "testcapture.h"

static inline double urand(unsigned long long *s) /* uniform in [-1, 1) (64-bit LCG) */
{
  *s = *s * 6364136223846793005ULL + 1442695040888963407ULL;
  return 2.0 * (double)(*s >> 11) / 9007199254740992.0 - 1.0;
}

static inline double fnorm(const double *A, int n)
{
  double s = 0.0;
  for (int i = 0; i < n; i++) s += A[i] * A[i];
  return sqrt(s);
}

static inline double fdiff(const double *A, const double *B, int n)
{
  double s = 0.0;
  for (int i = 0; i < n; i++) s += (A[i] - B[i]) * (A[i] - B[i]);
  return sqrt(s);
}

/* rotation by angle th about the axis a (Rodrigues) */
static inline void rotation(const double a_[3], double th, double R[9])
{
  const double l = sqrt(a_[0] * a_[0] + a_[1] * a_[1] + a_[2] * a_[2]);
  const double a[3] = {a_[0] / l, a_[1] / l, a_[2] / l}, c = cos(th), s = sin(th);
  for (int i = 0; i < 3; i++)
    for (int j = 0; j < 3; j++) R[3 * i + j] = (i == j ? c : 0.0) + (1.0 - c) * a[i] * a[j];
  R[1] -= s * a[2];
  R[2] += s * a[1];
  R[3] += s * a[2];
  R[5] -= s * a[0];
  R[6] -= s * a[1];
  R[7] += s * a[0];
}

/* a Material from the options opts; on error (*ierr != 0, message in ErrMsg) *mat is NULL */
static inline PetscErrorCode MaterialFromOptions(const char *opts, Material *mat, PetscErrorCode *ierr)
{
  PetscFunctionBeginUser;
  ErrMsg[0] = '\0';
  PetscCall(PetscOptionsClear(NULL));
  PetscCall(PetscOptionsInsertString(NULL, opts));
  PetscCall(MaterialCreate(PETSC_COMM_WORLD, mat));
  PetscCall(PetscPushErrorHandler(CaptureHandler, NULL));
  *ierr = MaterialSetFromOptions(*mat);
  PetscCall(PetscPopErrorHandler());
  PetscCall(PetscOptionsClear(NULL));
  if (*ierr) PetscCall(MaterialDestroy(mat));
  PetscFunctionReturn(0);
}
#endif
