/* Unit tests of the hex8 kernels: shape functions, the patch test, objectivity, and the exact
   element tangent against central finite differences of the element residual. */
#include <stdlib.h>
#include <string.h>
#include "testutil.h"
#include "fe.h"
#include "tensor.h"

static double urand(void) { return 2.0 * rand() / (double)RAND_MAX - 1.0; }

static void benchmark_material(MaterialParams *mp)
{
  memset(mp, 0, sizeof(*mp));
  mp->E      = 69004;
  mp->nu     = 0.3;
  mp->law    = HARDENING_SWIFT;
  mp->swK    = 589;
  mp->sweps0 = 1e-4;
  mp->swn    = 0.216;
  MaterialParamsSetup(mp);
}

/* a distorted unit-ish hexahedron */
static void distorted_hex(double X[8][3])
{
  for (int a = 0; a < 8; a++)
    for (int i = 0; i < 3; i++) X[a][i] = 0.5 * (hex8_nodes[a][i] + 1) + 0.12 * urand();
}

static void init_hist(double h[8][MAT_NHIST])
{
  for (int q = 0; q < 8; q++) MaterialHistoryInit(h[q]);
}

/* max relative difference between ke and central differences of fe */
static double tangent_fd_error(const MaterialParams *mp, const ElementOptions *eo, const double X[8][3], const double u[8][3], double hn[8][MAT_NHIST])
{
  double ke[576], fe[24], fp[24], fm[24], h[8][MAT_NHIST], up[8][3], um[8][3];
  double num = 0, den = 0;
  if (hex8_element(mp, eo, X, u, (const double(*)[MAT_NHIST])hn, fe, ke, h, NULL) != MAT_OK) return 1e30;
  for (int bm = 0; bm < 24; bm++) {
    const double eps = 1e-7;
    memcpy(up, u, sizeof(up));
    memcpy(um, u, sizeof(um));
    up[bm / 3][bm % 3] += eps;
    um[bm / 3][bm % 3] -= eps;
    hex8_element(mp, eo, X, up, (const double(*)[MAT_NHIST])hn, fp, NULL, h, NULL);
    hex8_element(mp, eo, X, um, (const double(*)[MAT_NHIST])hn, fm, NULL, h, NULL);
    for (int ai = 0; ai < 24; ai++) {
      const double fd = (fp[ai] - fm[ai]) / (2 * eps);
      num += (ke[ai * 24 + bm] - fd) * (ke[ai * 24 + bm] - fd);
      den += ke[ai * 24 + bm] * ke[ai * 24 + bm];
    }
  }
  return sqrt(num / den);
}

int main(void)
{
  MaterialParams mp;
  ElementOptions fbar = {1}, plain = {0};
  double         X[8][3], u[8][3], hn[8][MAT_NHIST], h[8][MAT_NHIST], fe[24];
  srand(12345);
  benchmark_material(&mp);

  /* shape functions: Kronecker property, partition of unity, derivatives sum to zero */
  {
    double N[8], dN[8][3], e1 = 0, e2 = 0;
    for (int b = 0; b < 8; b++) {
      hex8_shape(hex8_nodes[b], N, NULL);
      for (int a = 0; a < 8; a++) e1 = fmax(e1, fabs(N[a] - (a == b)));
    }
    const double xi[3] = {0.3, -0.7, 0.1};
    hex8_shape(xi, N, dN);
    double s = 0, d[3] = {0, 0, 0};
    for (int a = 0; a < 8; a++) {
      s += N[a];
      for (int k = 0; k < 3; k++) d[k] += dN[a][k];
    }
    e2 = fmax(fabs(s - 1), fmax(fabs(d[0]), fmax(fabs(d[1]), fabs(d[2]))));
    TU_CHECK(e1 < 1e-15, "shape functions: N_a(node_b) = delta_ab, max error %.2e", e1);
    TU_CHECK(e2 < 1e-15, "shape functions: partition of unity and zero-sum derivatives, max error %.2e", e2);
  }

  /* patch test: a linear displacement field gives the exact constant gradient at every point */
  {
    double A[9], err = 0;
    distorted_hex(X);
    for (int k = 0; k < 9; k++) A[k] = 0.2 * urand();
    for (int a = 0; a < 8; a++)
      for (int i = 0; i < 3; i++) u[a][i] = 0.01 * i + A[3 * i] * X[a][0] + A[3 * i + 1] * X[a][1] + A[3 * i + 2] * X[a][2];
    for (int q = 0; q < 8; q++) {
      double dNdX[8][3], F[9];
      hex8_gradient(X, hex8_gauss[q], dNdX);
      hex8_defgrad(u, dNdX, F);
      for (int k = 0; k < 9; k++) err = fmax(err, fabs(F[k] - A[k] - (k % 4 == 0)));
    }
    TU_CHECK(err < 1e-13, "patch test: linear field reproduced exactly in F on a distorted hex, error %.2e", err);
  }

  /* patch test of the forces: 2x2x2 block with a randomly moved centre node under a homogeneous
     finite plastic deformation: the assembled force at the interior node vanishes */
  {
    double P[27][3], A[9], force[3] = {0, 0, 0}, scale = 0;
    for (int k = 0; k < 27; k++) {
      P[k][0] = k % 3 * 0.5;
      P[k][1] = (k / 3) % 3 * 0.5;
      P[k][2] = k / 9 * 0.5;
    }
    P[13][0] += 0.11;
    P[13][1] -= 0.07;
    P[13][2] += 0.05;
    for (int k = 0; k < 9; k++) A[k] = 0.08 * urand();
    A[0] += 0.1;
    for (int ex = 0; ex < 2; ex++)
      for (int ey = 0; ey < 2; ey++)
        for (int ez = 0; ez < 2; ez++) {
          int node[8];
          for (int a = 0; a < 8; a++) {
            const int ix = ex + (hex8_nodes[a][0] > 0), iy = ey + (hex8_nodes[a][1] > 0), iz = ez + (hex8_nodes[a][2] > 0);
            node[a] = ix + 3 * iy + 9 * iz;
            for (int i = 0; i < 3; i++) X[a][i] = P[node[a]][i];
            for (int i = 0; i < 3; i++) u[a][i] = A[3 * i] * X[a][0] + A[3 * i + 1] * X[a][1] + A[3 * i + 2] * X[a][2];
          }
          init_hist(hn);
          if (hex8_element(&mp, &fbar, X, u, (const double(*)[MAT_NHIST])hn, fe, NULL, h, NULL) != MAT_OK) printf("# element evaluation failed\n");
          for (int a = 0; a < 8; a++) {
            for (int i = 0; i < 3; i++) scale = fmax(scale, fabs(fe[3 * a + i]));
            if (node[a] == 13)
              for (int i = 0; i < 3; i++) force[i] += fe[3 * a + i];
          }
        }
    const double err = sqrt(force[0] * force[0] + force[1] * force[1] + force[2] * force[2]) / scale;
    TU_CHECK(err < 1e-12, "patch test: interior node force under homogeneous plastic deformation, relative %.2e", err);
  }

  /* objectivity: a rigid rotation of 90 degrees produces no stress and no force */
  {
    const double R[9] = {0, -1, 0, 1, 0, 0, 0, 0, 1};
    double       fmax_ = 0;
    distorted_hex(X);
    for (int a = 0; a < 8; a++)
      for (int i = 0; i < 3; i++) u[a][i] = R[3 * i] * X[a][0] + R[3 * i + 1] * X[a][1] + R[3 * i + 2] * X[a][2] - X[a][i];
    init_hist(hn);
    ElementInfo info;
    hex8_element(&mp, &fbar, X, u, (const double(*)[MAT_NHIST])hn, fe, NULL, h, &info);
    for (int k = 0; k < 24; k++) fmax_ = fmax(fmax_, fabs(fe[k]));
    TU_CHECK(fmax_ < 1e-9 * mp.E && info.mises < 1e-9 * mp.E, "rigid rotation of 90 deg: max |f| %.2e, von Mises %.2e", fmax_, info.mises);
  }

  /* exact tangent against finite differences */
  {
    const char *label[2] = {"standard", "F-bar"};
    for (int variant = 0; variant < 2; variant++) {
      const ElementOptions *eo = variant ? &fbar : &plain;
      double                e;
      /* elastic: small displacements */
      distorted_hex(X);
      for (int a = 0; a < 8; a++)
        for (int i = 0; i < 3; i++) u[a][i] = 1e-5 * urand();
      init_hist(hn);
      e = tangent_fd_error(&mp, eo, X, u, hn);
      TU_CHECK(e < 1e-6, "%s element tangent vs finite differences, elastic: %.2e", label[variant], e);
      /* plastic: large non-homogeneous deformation from a plastically deformed committed state */
      for (int a = 0; a < 8; a++)
        for (int i = 0; i < 3; i++) u[a][i] = 0.05 * urand() + (i == 0 ? 0.1 * X[a][0] : 0);
      init_hist(hn);
      hex8_element(&mp, eo, X, u, (const double(*)[MAT_NHIST])hn, fe, NULL, h, NULL);
      memcpy(hn, h, sizeof(h));
      double plastic_ep = 0;
      for (int q = 0; q < 8; q++) plastic_ep = fmax(plastic_ep, hn[q][MAT_HIST_EP]);
      for (int a = 0; a < 8; a++)
        for (int i = 0; i < 3; i++) u[a][i] += 0.01 * urand() + (i == 1 ? 0.03 * X[a][2] : 0);
      e = tangent_fd_error(&mp, eo, X, u, hn);
      TU_CHECK(plastic_ep > 1e-3 && e < 1e-6, "%s element tangent vs finite differences, plastic (committed ep %.3f): %.2e", label[variant], plastic_ep, e);
    }
  }

  /* an inverted configuration is reported, not computed */
  {
    distorted_hex(X);
    for (int a = 0; a < 8; a++)
      for (int i = 0; i < 3; i++) u[a][i] = (i == 2) ? -2.0 * X[a][2] : 0; /* mirror through z */
    init_hist(hn);
    const int st = hex8_element(&mp, &fbar, X, u, (const double(*)[MAT_NHIST])hn, fe, NULL, h, NULL);
    TU_CHECK(st == MAT_ERR_JACOBIAN, "inverted element returns MAT_ERR_JACOBIAN (status %d)", st);
  }
  TU_RETURN();
}
