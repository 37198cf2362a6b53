/* Shared by the unit tests of the orthotropic log-strain materials (test_hill48, test_yld91):
   relative differences, random rotations and deformation gradients, rotation of tensors, the
   history's Cp^{-1} as a matrix, and an elastic step from a committed state. */
#ifndef ATRITO_TESTANISO_H
#define ATRITO_TESTANISO_H
#include <math.h>
#include <string.h>
#include "tensor.h"
#include "testmat.h"

static inline double rel(const double *A, const double *B, int n)
{
  const double s = fnorm(B, n);
  return fdiff(A, B, n) / (s > 0 ? s : 1.0);
}

static inline void random_rotation(unsigned long long *s, double R[9])
{
  const double a[3] = {urand(s), urand(s), urand(s) + 0.1};
  rotation(a, 3.0 * urand(s), R);
}

/* F = Q (I + amp X), X random */
static inline void random_F(unsigned long long *s, double amp, double F[9])
{
  double Q[9], X[9];
  random_rotation(s, Q);
  for (int i = 0; i < 9; i++) X[i] = amp * urand(s) + (i % 4 == 0 ? 1.0 : 0.0);
  t3_mul(Q, X, F);
}

/* B = Q A Q^T */
static inline void rot2(const double Q[9], const double A[9], double B[9])
{
  double Y[9];
  t3_mult(A, Q, Y);
  t3_mul(Q, Y, B);
}

static inline void hist_to_mat(const double *h, double C[9])
{
  const double c[9] = {h[0], h[3], h[5], h[3], h[1], h[4], h[5], h[4], h[2]};
  memcpy(C, c, sizeof c);
}

static inline void mat_to_hist(const double C[9], double *h)
{
  h[0] = C[0];
  h[1] = C[4];
  h[2] = C[8];
  h[3] = C[1];
  h[4] = C[5];
  h[5] = C[2];
}

/* F = R Cp^{1/2} D for the history h (Cp^{-1}): trial elastic strain of the order of D - I */
static inline void elastic_F(unsigned long long *seed, const double *h, const double D[9], double F[9])
{
  double C[9], lam[3], Q[9], s[3], U[9], R[9], Y[9];
  hist_to_mat(h, C);
  t3_sym_eig(C, lam, Q);
  for (int a = 0; a < 3; a++) s[a] = 1.0 / sqrt(lam[a]);
  for (int i = 0; i < 3; i++)
    for (int j = 0; j < 3; j++) U[3 * i + j] = Q[3 * i] * s[0] * Q[3 * j] + Q[3 * i + 1] * s[1] * Q[3 * j + 1] + Q[3 * i + 2] * s[2] * Q[3 * j + 2];
  random_rotation(seed, R);
  t3_mul(U, D, Y);
  t3_mul(R, Y, F);
}

#endif
