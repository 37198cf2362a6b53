/* Small dense 3x3 tensor utilities on plain arrays (row-major, A[3*i+j]). The products are
   inline: they sit in the innermost loops of the element and material kernels. */
#ifndef ATRITO_TENSOR_H
#define ATRITO_TENSOR_H

/* determinant of a 3x3 matrix */
static inline double t3_det(const double A[9])
{
  return A[0] * (A[4] * A[8] - A[5] * A[7]) - A[1] * (A[3] * A[8] - A[5] * A[6]) + A[2] * (A[3] * A[7] - A[4] * A[6]);
}

/* inverse of a 3x3 matrix (adjugate / determinant); returns the determinant (Ainv is set to
   zero when it is 0). Ainv may not alias A. */
static inline double t3_inv(const double A[9], double Ainv[9])
{
  const double c00 = A[4] * A[8] - A[5] * A[7];
  const double c01 = A[5] * A[6] - A[3] * A[8];
  const double c02 = A[3] * A[7] - A[4] * A[6];
  const double det = A[0] * c00 + A[1] * c01 + A[2] * c02;
  if (det == 0.0) {
    for (int i = 0; i < 9; i++) Ainv[i] = 0.0;
    return 0.0;
  }
  const double id = 1.0 / det;
  Ainv[0] = c00 * id;
  Ainv[1] = (A[2] * A[7] - A[1] * A[8]) * id;
  Ainv[2] = (A[1] * A[5] - A[2] * A[4]) * id;
  Ainv[3] = c01 * id;
  Ainv[4] = (A[0] * A[8] - A[2] * A[6]) * id;
  Ainv[5] = (A[2] * A[3] - A[0] * A[5]) * id;
  Ainv[6] = c02 * id;
  Ainv[7] = (A[1] * A[6] - A[0] * A[7]) * id;
  Ainv[8] = (A[0] * A[4] - A[1] * A[3]) * id;
  return det;
}

/* C = A B (C may alias A or B) */
static inline void t3_mul(const double A[9], const double B[9], double C[9])
{
  double T[9];
  for (int i = 0; i < 3; i++)
    for (int j = 0; j < 3; j++) T[3 * i + j] = A[3 * i] * B[j] + A[3 * i + 1] * B[3 + j] + A[3 * i + 2] * B[6 + j];
  for (int i = 0; i < 9; i++) C[i] = T[i];
}

/* C = A^T B (C may alias A or B) */
static inline void t3_tmul(const double A[9], const double B[9], double C[9])
{
  double T[9];
  for (int i = 0; i < 3; i++)
    for (int j = 0; j < 3; j++) T[3 * i + j] = A[i] * B[j] + A[3 + i] * B[3 + j] + A[6 + i] * B[6 + j];
  for (int i = 0; i < 9; i++) C[i] = T[i];
}

/* C = A B^T (C may alias A or B) */
static inline void t3_mult(const double A[9], const double B[9], double C[9])
{
  double T[9];
  for (int i = 0; i < 3; i++)
    for (int j = 0; j < 3; j++) T[3 * i + j] = A[3 * i] * B[3 * j] + A[3 * i + 1] * B[3 * j + 1] + A[3 * i + 2] * B[3 * j + 2];
  for (int i = 0; i < 9; i++) C[i] = T[i];
}

/* B = A^T (B may alias A) */
static inline void t3_transpose(const double A[9], double B[9])
{
  double T[9];
  for (int i = 0; i < 3; i++)
    for (int j = 0; j < 3; j++) T[3 * j + i] = A[3 * i + j];
  for (int i = 0; i < 9; i++) B[i] = T[i];
}

/* Eigen-decomposition of a symmetric 3x3 matrix (only the upper triangle is read):
   A = Q diag(lam) Q^T, Q orthogonal with det Q = +1 and the eigenvectors as columns
   (Q[3*i+a] = i-th component of eigenvector a). Closed form (the most distinct eigenvalue from
   the invariants of the deviator, its eigenvector by cross products, the other two from a 2x2
   problem solved by one Jacobi rotation), falling back to t3_sym_eig_jacobi in the degenerate
   cases it cannot resolve. Accurate to round-off for repeated eigenvalues too: eigenvalues to
   a few ulps of |A|, Q orthogonal to round-off. */
void t3_sym_eig(const double A[9], double lam[3], double Q[9]);
/* the same by cyclic Jacobi rotations (iterative: 3 to 5 sweeps) */
void t3_sym_eig_jacobi(const double A[9], double lam[3], double Q[9]);

/* Solve A X = B in place (A n x n row-major, destroyed; B n x nrhs row-major, overwritten by X),
   Gaussian elimination with partial pivoting; returns 0, or 1 when A is singular (a pivot below
   1e-14 of A's largest entry) or not finite */
int dense_solve(int n, double *A, int nrhs, double *B);

#endif
