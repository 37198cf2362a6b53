/* Small dense 3x3 tensor utilities on plain arrays (row-major, A[3*i+j]). */
#ifndef ATRITO_TENSOR_H
#define ATRITO_TENSOR_H

/* determinant of a 3x3 matrix */
double t3_det(const double A[9]);
/* inverse of a 3x3 matrix; returns the determinant (inverse undefined when it is 0) */
double t3_inv(const double A[9], double Ainv[9]);
/* C = A B */
void t3_mul(const double A[9], const double B[9], double C[9]);
/* C = A^T B */
void t3_tmul(const double A[9], const double B[9], double C[9]);
/* C = A B^T */
void t3_mult(const double A[9], const double B[9], double C[9]);
/* B = A^T */
void t3_transpose(const double A[9], double B[9]);
/* Eigen-decomposition of a symmetric 3x3 matrix by cyclic Jacobi rotations:
   A = Q diag(lam) Q^T, Q orthogonal with the eigenvectors as columns (Q[3*i+a] = i-th
   component of eigenvector a). Accurate to round-off for repeated eigenvalues too. */
void t3_sym_eig(const double A[9], double lam[3], double Q[9]);

#endif
