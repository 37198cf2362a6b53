/* Small dense 3x3 tensor utilities on plain arrays (row-major, A[3*i+j]): the symmetric
   eigen-decomposition (the products are inline in include/tensor.h), and a small dense solve. */
#include "tensor.h"

#include <float.h>
#include <math.h>

/* Closed-form symmetric eigen-decomposition (Scherzinger & Dohrmann, "A robust algorithm for
   finding the eigenvalues and eigenvectors of 3x3 symmetric matrices", CMAME 197 (2008)).

   B = A - m I, m = tr A / 3 (the deviator; the eigenvectors are A's, the eigenvalues shifted
   by m), scaled by an exact power of two so that max |B_ij| lies in [1, 2) (no overflow or
   underflow in the invariants, no rounding from the scaling) when it lies far from 1 (beyond
   2^-200 or 2^200). With the invariants
     J2 = 1/2 B:B = ((b00-b11)^2 + (b11-b22)^2 + (b22-b00)^2)/6 + b01^2 + b02^2 + b12^2,
     J3 = det B,
   the eigenvalues of the traceless B are eta_k = 2 sqrt(J2/3) cos(alpha + 2 pi k/3),
   3 alpha = acos(J3/2 (3/J2)^(3/2)), alpha in [0, pi/3]: eta_0 the largest, eta_1 the
   smallest, eta_2 the middle one. For alpha < pi/6 eta_0 is farther from the middle one than
   eta_1 is, otherwise eta_1: that one, the most distinct, is computed first. Its distance to the
   other two is at least sqrt(J2) (of the order of |B|), and at alpha = 0 or pi/3 (a double
   eigenvalue) the cosine is stationary in alpha, so it is accurate to round-off even when the
   other two coincide, unlike the other two roots of the cubic.
   Its eigenvector v1 spans the null space of C = B - eta I, whose rows span the plane
   orthogonal to v1: s1 = the longest row, normalised; s2 = the longest of the other two rows
   with its s1 component removed, normalised; v1 = s1 x s2. The restriction of B to the plane
   (s1, s2) is the 2x2 matrix [s1.B s1, s1.B s2; s2.B s1, s2.B s2], diagonalised by one Jacobi
   rotation (the same formulas as t3_sym_eig_jacobi), which is accurate whatever the gap
   between its eigenvalues. The first eigenvalue is taken as the Rayleigh quotient v1.B v1
   (error of second order in that of v1). (v1, v2, v3) is right-handed: v2 x v3 = s1 x s2 = v1.
   Only when the second row is no longer independent of the first (all three eigenvalues equal
   up to round-off relative to |B|, or a non-finite entry) does it fall back to Jacobi. */
void t3_sym_eig(const double A[9], double lam[3], double Q[9])
{
  const double m = (A[0] + A[4] + A[8]) / 3.0;
  double       b[3][3];
  b[0][0] = A[0] - m;
  b[1][1] = A[4] - m;
  b[2][2] = A[8] - m;
  b[0][1] = b[1][0] = A[1];
  b[0][2] = b[2][0] = A[2];
  b[1][2] = b[2][1] = A[5];
  /* non-finite entries: to Jacobi, which propagates them */
  if (!isfinite(A[0] + A[1] + A[2] + A[4] + A[5] + A[8])) {
    t3_sym_eig_jacobi(A, lam, Q);
    return;
  }
  double mx = 0.0;
  for (int i = 0; i < 3; i++)
    for (int j = i; j < 3; j++) mx = fabs(b[i][j]) > mx ? fabs(b[i][j]) : mx;
  if (mx == 0.0) { /* A = m I exactly (the diagonal entries all equal m) */
    lam[0] = A[0];
    lam[1] = A[4];
    lam[2] = A[8];
    for (int i = 0; i < 9; i++) Q[i] = (i % 4 == 0) ? 1.0 : 0.0;
    return;
  }
  /* far from 1, scale by an exact power of two (J2^(3/2) and its inverse must not overflow or
     underflow); otherwise use B as it is */
  double sc = 1.0;
  if (mx < 0x1p-200 || mx > 0x1p200) {
    sc = ldexp(1.0, -ilogb(mx));
    for (int i = 0; i < 3; i++)
      for (int j = 0; j < 3; j++) b[i][j] *= sc;
  }

  const double d01 = b[0][0] - b[1][1], d12 = b[1][1] - b[2][2], d20 = b[2][2] - b[0][0];
  const double J2 = (d01 * d01 + d12 * d12 + d20 * d20) / 6.0 + b[0][1] * b[0][1] + b[0][2] * b[0][2] + b[1][2] * b[1][2];
  const double J3 = b[0][0] * (b[1][1] * b[2][2] - b[1][2] * b[1][2]) - b[0][1] * (b[0][1] * b[2][2] - b[1][2] * b[0][2]) + b[0][2] * (b[0][1] * b[1][2] - b[1][1] * b[0][2]);
  const double qi = sqrt(3.0 / J2);
  double       r  = 0.5 * J3 * qi * qi * qi;
  r               = r > 1.0 ? 1.0 : (r < -1.0 ? -1.0 : r);
  const double alpha = acos(r) / 3.0;
  const double PI3   = 1.04719755119659774615; /* pi/3 */
  const double eta   = (2.0 / qi) * (alpha < 0.5 * PI3 ? cos(alpha) : cos(alpha + 2.0 * PI3));

  /* rows of C = B - eta I */
  double c[3][3], n2[3];
  for (int i = 0; i < 3; i++) {
    for (int j = 0; j < 3; j++) c[i][j] = b[i][j];
    c[i][i] -= eta;
    n2[i] = c[i][0] * c[i][0] + c[i][1] * c[i][1] + c[i][2] * c[i][2];
  }
  const int    i1 = (n2[0] >= n2[1] && n2[0] >= n2[2]) ? 0 : (n2[1] >= n2[2] ? 1 : 2);
  const int    ja = (i1 + 1) % 3, jb = (i1 + 2) % 3;
  const double in1 = 1.0 / sqrt(n2[i1]);
  double       s1[3], ta[3], tb[3];
  for (int k = 0; k < 3; k++) s1[k] = c[i1][k] * in1;
  const double pa = s1[0] * c[ja][0] + s1[1] * c[ja][1] + s1[2] * c[ja][2];
  const double pb = s1[0] * c[jb][0] + s1[1] * c[jb][1] + s1[2] * c[jb][2];
  for (int k = 0; k < 3; k++) {
    ta[k] = c[ja][k] - pa * s1[k];
    tb[k] = c[jb][k] - pb * s1[k];
  }
  const double na = ta[0] * ta[0] + ta[1] * ta[1] + ta[2] * ta[2], nb = tb[0] * tb[0] + tb[1] * tb[1] + tb[2] * tb[2];
  const double n22 = na >= nb ? na : nb;
  /* in exact arithmetic n22 >= J2/4 for the most distinct eigenvalue; far below that only in
     the degenerate cases */
  if (!(n22 > 1e-6 * J2)) {
    t3_sym_eig_jacobi(A, lam, Q);
    return;
  }
  const double *t   = na >= nb ? ta : tb;
  const double  in2 = 1.0 / sqrt(n22);
  const double  s2[3] = {t[0] * in2, t[1] * in2, t[2] * in2};
  const double  v1[3] = {s1[1] * s2[2] - s1[2] * s2[1], s1[2] * s2[0] - s1[0] * s2[2], s1[0] * s2[1] - s1[1] * s2[0]};

  /* B s1, B s2, B v1 and the projections */
  double Bs1[3], Bs2[3], Bv1[3];
  for (int i = 0; i < 3; i++) {
    Bs1[i] = b[i][0] * s1[0] + b[i][1] * s1[1] + b[i][2] * s1[2];
    Bs2[i] = b[i][0] * s2[0] + b[i][1] * s2[1] + b[i][2] * s2[2];
    Bv1[i] = b[i][0] * v1[0] + b[i][1] * v1[1] + b[i][2] * v1[2];
  }
  const double e1  = v1[0] * Bv1[0] + v1[1] * Bv1[1] + v1[2] * Bv1[2];
  const double a11 = s1[0] * Bs1[0] + s1[1] * Bs1[1] + s1[2] * Bs1[2];
  const double a22 = s2[0] * Bs2[0] + s2[1] * Bs2[1] + s2[2] * Bs2[2];
  const double a12 = 0.5 * (s1[0] * Bs2[0] + s1[1] * Bs2[1] + s1[2] * Bs2[2] + s2[0] * Bs1[0] + s2[1] * Bs1[1] + s2[2] * Bs1[2]);

  /* one Jacobi rotation of the 2x2 block: tan phi = t, the smaller root of t^2 + 2 theta t - 1 = 0 */
  double tn = 0.0, cs = 1.0, sn = 0.0;
  if (a12 != 0.0) {
    const double theta = 0.5 * (a22 - a11) / a12;
    if (fabs(theta) > 1e150) tn = 0.5 / theta;
    else tn = (theta >= 0.0 ? 1.0 : -1.0) / (fabs(theta) + sqrt(theta * theta + 1.0));
    cs = 1.0 / sqrt(tn * tn + 1.0);
    sn = tn * cs;
  }
  const double e2 = a11 - tn * a12, e3 = a22 + tn * a12;
  const double isc = 1.0 / sc; /* exact */
  lam[0] = m + e1 * isc;
  lam[1] = m + e2 * isc;
  lam[2] = m + e3 * isc;
  for (int i = 0; i < 3; i++) {
    Q[3 * i]     = v1[i];
    Q[3 * i + 1] = cs * s1[i] - sn * s2[i];
    Q[3 * i + 2] = sn * s1[i] + cs * s2[i];
  }
}

/* Cyclic Jacobi (Golub & Van Loan, Alg. 8.4.3; rotation formulas as in Numerical Recipes
   "jacobi"). Only the upper triangle of A is read (A is assumed symmetric). Each rotation
   annihilates a_pq exactly; sweeps continue until every off-diagonal entry is zero or below
   round-off relative to the two diagonal entries it couples (quadratic convergence: 3-5 sweeps). */
void t3_sym_eig_jacobi(const double A[9], double lam[3], double Q[9])
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

/* Solve A X = B in place (A n x n row-major, destroyed; B n x nrhs row-major, overwritten by X),
   Gaussian elimination with partial pivoting; returns 0, or 1 when A is singular */
int dense_solve(int n, double *A, int nrhs, double *B)
{
  double amax = 0;
  for (int i = 0; i < n * n; i++) amax = fmax(amax, fabs(A[i]));
  if (!(amax > 0) || !isfinite(amax)) return 1;
  for (int c = 0; c < n; c++) {
    int p = c;
    for (int r = c + 1; r < n; r++)
      if (fabs(A[r * n + c]) > fabs(A[p * n + c])) p = r;
    if (!(fabs(A[p * n + c]) > 1e-14 * amax)) return 1;
    if (p != c) {
      for (int k = 0; k < n; k++) {
        const double t = A[c * n + k];
        A[c * n + k]   = A[p * n + k];
        A[p * n + k]   = t;
      }
      for (int k = 0; k < nrhs; k++) {
        const double t  = B[c * nrhs + k];
        B[c * nrhs + k] = B[p * nrhs + k];
        B[p * nrhs + k] = t;
      }
    }
    for (int r = c + 1; r < n; r++) {
      const double l = A[r * n + c] / A[c * n + c];
      if (l == 0) continue;
      for (int k = c + 1; k < n; k++) A[r * n + k] -= l * A[c * n + k];
      for (int k = 0; k < nrhs; k++) B[r * nrhs + k] -= l * B[c * nrhs + k];
    }
  }
  for (int c = n - 1; c >= 0; c--)
    for (int k = 0; k < nrhs; k++) {
      double s = B[c * nrhs + k];
      for (int j = c + 1; j < n; j++) s -= A[c * n + j] * B[j * nrhs + k];
      B[c * nrhs + k] = s / A[c * n + c];
    }
  return 0;
}
