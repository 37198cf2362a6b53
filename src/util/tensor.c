/* Small dense 3x3 tensor utilities on plain arrays (row-major, A[3*i+j]). */
#include "tensor.h"

#include <float.h>
#include <math.h>

double t3_det(const double A[9])
{
  return A[0] * (A[4] * A[8] - A[5] * A[7]) - A[1] * (A[3] * A[8] - A[5] * A[6]) +
         A[2] * (A[3] * A[7] - A[4] * A[6]);
}

double t3_inv(const double A[9], double Ainv[9])
{
  /* adjugate / determinant */
  const double c00 = A[4] * A[8] - A[5] * A[7];
  const double c01 = A[5] * A[6] - A[3] * A[8];
  const double c02 = A[3] * A[7] - A[4] * A[6];
  const double det = A[0] * c00 + A[1] * c01 + A[2] * c02;
  if (det == 0.0) return 0.0;
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

void t3_mul(const double A[9], const double B[9], double C[9])
{
  double T[9];
  for (int i = 0; i < 3; i++)
    for (int j = 0; j < 3; j++) T[3 * i + j] = A[3 * i] * B[j] + A[3 * i + 1] * B[3 + j] + A[3 * i + 2] * B[6 + j];
  for (int i = 0; i < 9; i++) C[i] = T[i];
}

void t3_tmul(const double A[9], const double B[9], double C[9])
{
  double T[9];
  for (int i = 0; i < 3; i++)
    for (int j = 0; j < 3; j++) T[3 * i + j] = A[i] * B[j] + A[3 + i] * B[3 + j] + A[6 + i] * B[6 + j];
  for (int i = 0; i < 9; i++) C[i] = T[i];
}

void t3_mult(const double A[9], const double B[9], double C[9])
{
  double T[9];
  for (int i = 0; i < 3; i++)
    for (int j = 0; j < 3; j++)
      T[3 * i + j] = A[3 * i] * B[3 * j] + A[3 * i + 1] * B[3 * j + 1] + A[3 * i + 2] * B[3 * j + 2];
  for (int i = 0; i < 9; i++) C[i] = T[i];
}

void t3_transpose(const double A[9], double B[9])
{
  double T[9];
  for (int i = 0; i < 3; i++)
    for (int j = 0; j < 3; j++) T[3 * j + i] = A[3 * i + j];
  for (int i = 0; i < 9; i++) B[i] = T[i];
}

/* Cyclic Jacobi (Golub & Van Loan, Alg. 8.4.3; rotation formulas as in Numerical Recipes
   "jacobi"). Only the upper triangle of A is read (A is assumed symmetric). Each rotation
   annihilates a_pq exactly; sweeps continue until every off-diagonal entry is zero or below
   round-off relative to the two diagonal entries it couples (quadratic convergence: 3-5 sweeps). */
void t3_sym_eig(const double A[9], double lam[3], double Q[9])
{
  /* pair k = (p,q) = (P[k],R[k]), r the third index: o[IP[k]] = a_rp, o[IQ[k]] = a_rq */
  static const int P[3] = {0, 0, 1}, R[3] = {1, 2, 2};
  static const int IP[3] = {1, 0, 0}, IQ[3] = {2, 2, 1};
  double d[3] = {A[0], A[4], A[8]};
  double o[3] = {A[1], A[2], A[5]}; /* o[k] = a(P[k],R[k]): (0,1), (0,2), (1,2) */
  for (int i = 0; i < 9; i++) Q[i] = 0.0;
  Q[0] = Q[4] = Q[8] = 1.0;

  for (int sweep = 0; sweep < 64; sweep++) {
    if (o[0] == 0.0 && o[1] == 0.0 && o[2] == 0.0) break;
    for (int k = 0; k < 3; k++) {
      const int    p = P[k], q = R[k];
      const double apq = o[k];
      if (apq == 0.0) continue;
      /* negligible coupling: |a_pq| below 1% of an ulp of the diagonal entries (dropping it is a
         round-off-level backward error; continuing would only rotate by round-off-driven angles
         when a_pp == a_qq in floating point, e.g. for repeated eigenvalues) */
      if (fabs(apq) <= 0.01 * DBL_EPSILON * (fabs(d[p]) + fabs(d[q]))) {
        o[k] = 0.0;
        continue;
      }
      /* rotation angle: theta = (a_qq - a_pp) / (2 a_pq), t = tan(phi) (smaller root) */
      const double theta = 0.5 * (d[q] - d[p]) / apq;
      double       t;
      if (fabs(theta) > 1e150) t = 0.5 / theta;
      else t = (theta >= 0.0 ? 1.0 : -1.0) / (fabs(theta) + sqrt(theta * theta + 1.0));
      const double c = 1.0 / sqrt(t * t + 1.0), s = t * c;
      d[p] -= t * apq;
      d[q] += t * apq;
      o[k] = 0.0;
      /* rotate the two remaining off-diagonal entries a_rp, a_rq */
      const int    ip = IP[k], iq = IQ[k];
      const double arp = o[ip], arq = o[iq];
      o[ip] = c * arp - s * arq;
      o[iq] = s * arp + c * arq;
      /* accumulate Q <- Q J */
      for (int i = 0; i < 3; i++) {
        const double qp = Q[3 * i + p], qq = Q[3 * i + q];
        Q[3 * i + p] = c * qp - s * qq;
        Q[3 * i + q] = s * qp + c * qq;
      }
    }
  }
  lam[0] = d[0];
  lam[1] = d[1];
  lam[2] = d[2];
}
