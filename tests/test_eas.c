/* Unit tests of the hexahedron with incompatible modes (hex8_eas): the condensed tangent against
   central finite differences of the condensed force (elastic and plastic J2, and a hyperelastic
   material, on distorted elements, from a non-zero committed alpha), the patch test on a distorted
   2x2x2 patch (exact stress, enhanced parameters zero, no force at the interior node), a rigid
   rotation of 90 degrees, the quadratic convergence of the local Newton, the committed state
   left alone, pure bending of one slender element (exact with the modes, locked without), and the
   type in the registry. */
#include <stdlib.h>
#include <string.h>
#include <petscsys.h>
#include "testutil.h"
#include "element.h"
#include "element_hex8.h"
#include "element_hex8_eas.h"
#include "material_j2.h"
#include "tensor.h"

#define NHE (HEX8_NQP * J2_NHIST + HEX8_EAS_NALPHA)

static double urand(void) { return 2.0 * rand() / (double)RAND_MAX - 1.0; }

static void benchmark_material(J2Params *mp)
{
  memset(mp, 0, sizeof(*mp));
  mp->E      = 69004;
  mp->nu     = 0.3;
  mp->law    = HARDENING_SWIFT;
  mp->swK    = 589;
  mp->sweps0 = 1e-4;
  mp->swn    = 0.216;
  J2ParamsSetup(mp);
}

/* compressible neo-Hooke, tau = G (b - I) + lambda ln J I (no history) */
typedef struct {
  double G, lambda;
} NeoParams;
static int NeoUpdate(const void *ctx, const double F[9], const double *hn, double tau[9], double *dtau, double *h, int *plastic)
{
  const NeoParams *p = (const NeoParams *)ctx;
  double           b[9], Fi[9];
  const double     J = t3_inv(F, Fi);
  if (plastic) *plastic = 0;
  if (!(J > 0)) return MAT_ERR_JACOBIAN;
  t3_mult(F, F, b);
  for (int i = 0; i < 9; i++) tau[i] = p->G * (b[i] - (i % 4 == 0)) + (i % 4 == 0 ? p->lambda * log(J) : 0.0);
  if (dtau)
    for (int i = 0; i < 3; i++)
      for (int j = 0; j < 3; j++)
        for (int k = 0; k < 3; k++)
          for (int L = 0; L < 3; L++) dtau[(3 * i + j) * 9 + 3 * k + L] = p->G * ((i == k) * F[3 * j + L] + F[3 * i + L] * (j == k)) + (i == j) * p->lambda * Fi[3 * L + k];
  return MAT_OK;
}
static void   NeoHistoryInit(const void *ctx, double *h) {}
static double NeoPlasticStrain(const void *ctx, const double *h) { return 0; }

static void distorted_hex(double X[8][3])
{
  for (int a = 0; a < 8; a++)
    for (int i = 0; i < 3; i++) X[a][i] = 0.5 * (hex8_nodes[a][i] + 1) + 0.12 * urand();
}

static void init_hist(const MaterialKernel *mk, double *hn)
{
  memset(hn, 0, NHE * sizeof(double));
  for (int q = 0; q < HEX8_NQP; q++) mk->history_init(mk->ctx, hn + q * mk->nhist);
}

/* relative Frobenius difference between ke and central differences of fe */
static double tangent_fd_error(const Hex8EASOptions *eo, const MaterialKernel *mk, const double X[8][3], const double u[8][3], const double *hn)
{
  double ke[576], fe[24], fp[24], fm[24], up[8][3], um[8][3], h[NHE], num = 0, den = 0;
  if (hex8_eas_element(eo, mk, X, u, hn, fe, ke, h, NULL, NULL) != MAT_OK) return 1e30;
  for (int bm = 0; bm < 24; bm++) {
    const double eps = 1e-7;
    memcpy(up, u, sizeof(up));
    memcpy(um, u, sizeof(um));
    up[bm / 3][bm % 3] += eps;
    um[bm / 3][bm % 3] -= eps;
    if (hex8_eas_element(eo, mk, X, up, hn, fp, NULL, h, NULL, NULL) != MAT_OK) return 1e30;
    if (hex8_eas_element(eo, mk, X, um, hn, fm, NULL, h, NULL, NULL) != MAT_OK) return 1e30;
    for (int ai = 0; ai < 24; ai++) {
      const double fd = (fp[ai] - fm[ai]) / (2 * eps);
      num += (ke[ai * 24 + bm] - fd) * (ke[ai * 24 + bm] - fd);
      den += ke[ai * 24 + bm] * ke[ai * 24 + bm];
    }
  }
  return sqrt(num / den);
}

static void TestKernels(void)
{
  J2Params       mp;
  MaterialKernel mk, neo = {0};
  NeoParams      np  = {1000, 1500};
  Hex8EASOptions eo  = {20, 1e-10};
  double         X[8][3], u[8][3], hn[NHE], h[NHE], fe[24];

  srand(4242);
  benchmark_material(&mp);
  J2KernelInit(&mp, &mk);
  neo.nhist = 0, neo.ctx = &np, neo.update = NeoUpdate, neo.history_init = NeoHistoryInit, neo.plastic_strain = NeoPlasticStrain;

  /* patch test on a distorted 2x2x2 patch: a linear field (finite, plastic) gives alpha = 0, the
     exact stress in every element and no force at the interior node */
  {
    double P[27][3], A[9], F[9], tau[9], hq[J2_NHIST], hv[J2_NHIST], force[3] = {0, 0, 0}, scale = 0, serr = 0, amax = 0;
    for (int k = 0; k < 27; k++) {
      P[k][0] = k % 3 * 0.5 + 0.06 * urand();
      P[k][1] = (k / 3) % 3 * 0.5 + 0.06 * urand();
      P[k][2] = k / 9 * 0.5 + 0.06 * urand();
    }
    P[13][0] += 0.11, P[13][1] -= 0.07, P[13][2] += 0.05;
    for (int k = 0; k < 9; k++) A[k] = 0.05 * urand();
    A[0] += 0.08;
    for (int k = 0; k < 9; k++) F[k] = A[k] + (k % 4 == 0);
    J2HistoryInit(hv);
    mk.update(mk.ctx, F, hv, tau, NULL, hq, NULL);
    const double Jd = t3_det(F), sx[6] = {tau[0] / Jd, tau[4] / Jd, tau[8] / Jd, tau[1] / Jd, tau[5] / Jd, tau[2] / Jd};
    int          npl = 0;
    for (int ex = 0; ex < 2; ex++)
      for (int ey = 0; ey < 2; ey++)
        for (int ez = 0; ez < 2; ez++) {
          int         node[8];
          ElementInfo info;
          for (int a = 0; a < 8; a++) {
            const int ix = ex + (hex8_nodes[a][0] > 0), iy = ey + (hex8_nodes[a][1] > 0), iz = ez + (hex8_nodes[a][2] > 0);
            node[a] = ix + 3 * iy + 9 * iz;
            for (int i = 0; i < 3; i++) X[a][i] = P[node[a]][i];
            for (int i = 0; i < 3; i++) u[a][i] = A[3 * i] * X[a][0] + A[3 * i + 1] * X[a][1] + A[3 * i + 2] * X[a][2];
          }
          init_hist(&mk, hn);
          if (hex8_eas_element(&eo, &mk, X, u, hn, fe, NULL, h, &info, NULL) != MAT_OK) printf("# element evaluation failed\n");
          npl += info.nplastic;
          for (int k = 0; k < 6; k++) serr = fmax(serr, fabs(info.sigma[k] - sx[k]));
          for (int k = 0; k < HEX8_EAS_NALPHA; k++) amax = fmax(amax, fabs(h[HEX8_NQP * J2_NHIST + k]));
          for (int a = 0; a < 8; a++) {
            for (int i = 0; i < 3; i++) scale = fmax(scale, fabs(fe[3 * a + i]));
            if (node[a] == 13)
              for (int i = 0; i < 3; i++) force[i] += fe[3 * a + i];
          }
        }
    const double ferr = sqrt(force[0] * force[0] + force[1] * force[1] + force[2] * force[2]) / scale;
    TU_CHECK(npl == 64 && ferr < 1e-12 && serr < 1e-10 * mp.E && amax < 1e-14,
             "patch test (distorted 2x2x2 patch, homogeneous plastic F, %d of 64 points plastic): interior node force %.2e relative, stress error %.2e MPa, max |alpha| %.2e", npl, ferr, serr, amax);
  }

  /* rigid rotation of 90 degrees: no stress, no force, alpha = 0 */
  {
    const double R[9] = {0, -1, 0, 1, 0, 0, 0, 0, 1};
    double       fmax_ = 0, amax = 0;
    ElementInfo  info;
    distorted_hex(X);
    for (int a = 0; a < 8; a++)
      for (int i = 0; i < 3; i++) u[a][i] = R[3 * i] * X[a][0] + R[3 * i + 1] * X[a][1] + R[3 * i + 2] * X[a][2] - X[a][i];
    init_hist(&mk, hn);
    const int st = hex8_eas_element(&eo, &mk, X, u, hn, fe, NULL, h, &info, NULL);
    for (int k = 0; k < 24; k++) fmax_ = fmax(fmax_, fabs(fe[k]));
    for (int k = 0; k < HEX8_EAS_NALPHA; k++) amax = fmax(amax, fabs(h[HEX8_NQP * J2_NHIST + k]));
    TU_CHECK(st == MAT_OK && fmax_ < 1e-9 * mp.E && info.mises < 1e-9 * mp.E && amax < 1e-12, "rigid rotation of 90 deg: max |f| %.2e, von Mises %.2e, max |alpha| %.2e", fmax_, info.mises, amax);
  }

  /* condensed tangent against finite differences of the condensed force */
  {
    double e;
    distorted_hex(X);
    for (int a = 0; a < 8; a++)
      for (int i = 0; i < 3; i++) u[a][i] = 1e-4 * urand();
    init_hist(&mk, hn);
    e = tangent_fd_error(&eo, &mk, X, u, hn);
    TU_CHECK(e < 1e-6, "condensed tangent vs finite differences, J2 elastic, distorted element: %.2e", e);

    /* plastic: a committed plastic state with its committed alpha, then a further step */
    for (int a = 0; a < 8; a++)
      for (int i = 0; i < 3; i++) u[a][i] = 0.04 * urand() + (i == 0 ? 0.1 * X[a][0] : 0) + (i == 2 ? 0.05 * X[a][0] * X[a][0] : 0);
    init_hist(&mk, hn);
    hex8_eas_element(&eo, &mk, X, u, hn, fe, NULL, h, NULL, NULL);
    memcpy(hn, h, sizeof(h));
    double ep = 0, an = 0;
    for (int q = 0; q < 8; q++) ep = fmax(ep, hn[q * J2_NHIST + J2_HIST_EP]);
    for (int k = 0; k < HEX8_EAS_NALPHA; k++) an = fmax(an, fabs(hn[HEX8_NQP * J2_NHIST + k]));
    for (int a = 0; a < 8; a++)
      for (int i = 0; i < 3; i++) u[a][i] += 0.01 * urand() + (i == 1 ? 0.03 * X[a][2] : 0);
    e = tangent_fd_error(&eo, &mk, X, u, hn);
    TU_CHECK(ep > 1e-3 && an > 1e-4 && e < 1e-6, "condensed tangent vs finite differences, J2 plastic (committed ep %.3f, committed max |alpha| %.2e): %.2e", ep, an, e);

    /* hyperelastic, large strain */
    double hz[NHE] = {0};
    for (int a = 0; a < 8; a++)
      for (int i = 0; i < 3; i++) u[a][i] = 0.1 * urand() - (i == 2 ? 0.3 * X[a][2] : 0);
    e = tangent_fd_error(&eo, &neo, X, u, hz);
    TU_CHECK(e < 1e-6, "condensed tangent vs finite differences, neo-Hooke at 30 %% compression, distorted element: %.2e", e);
  }

  /* local Newton: quadratic convergence (tolerance at round-off for the test): r_{k+1} <= C r_k^2
     once r_k < 1e-3, down to the round-off of the material (J2's return map: 1e-12 of the stress) */
  {
    Hex8EASOptions        tight = {20, 1e-15};
    const MaterialKernel *mks[2] = {&neo, &mk};
    const char           *name[2] = {"neo-Hooke", "J2 plastic"};
    const double          C[2] = {10, 1e3}, floor_[2] = {1e-15, 1e-14};
    Hex8EASTrace          tr;
    distorted_hex(X);
    for (int m = 0; m < 2; m++) {
      char seq[512] = "";
      int  quad = 1, n = 0;
      for (int a = 0; a < 8; a++)
        for (int i = 0; i < 3; i++) u[a][i] = 0.03 * urand() + (i == 0 ? 0.05 * X[a][0] : 0) + (i == 2 ? 0.08 * X[a][0] * X[a][0] : 0);
      init_hist(mks[m], hn);
      const int st = hex8_eas_element(&tight, mks[m], X, u, hn, fe, NULL, h, NULL, &tr);
      for (int k = 0; k <= tr.nit; k++) {
        n += snprintf(seq + n, sizeof(seq) - n, " %.1e", tr.res[k]);
        if (k > 0 && tr.res[k - 1] < 1e-3 && tr.res[k] > floor_[m] && tr.res[k] > C[m] * tr.res[k - 1] * tr.res[k - 1]) quad = 0;
      }
      TU_CHECK(st == MAT_OK && quad && tr.nit >= 3 && tr.nit <= 8 && tr.res[tr.nit] < 1e-14, "local Newton converges quadratically (%s, from alpha = 0, r_k+1 <= %g r_k^2): |R_alpha| / scale =%s", name[m], C[m], seq);
    }
    /* from the committed alpha of a nearby state (J2): fewer updates, committed state untouched */
    double hn_copy[NHE];
    Hex8EASTrace tr2;
    memcpy(hn, h, sizeof(h));
    memcpy(hn_copy, hn, sizeof(hn));
    for (int a = 0; a < 8; a++)
      for (int i = 0; i < 3; i++) u[a][i] += 1e-4 * urand();
    hex8_eas_element(&tight, &mk, X, u, hn, fe, NULL, h, NULL, &tr2);
    TU_CHECK(tr2.nit < tr.nit && !memcmp(hn, hn_copy, sizeof(hn)), "from the committed alpha of a nearby state: %d Newton updates (first %.1e), committed state untouched", tr2.nit, tr2.res[0]);
  }

  /* pure bending of a slender element (10 x 1 x 1, plane strain in y): the nodal values of the
     exact field u_x = -k x z, u_z = k/2 (x^2 + nu/(1-nu) z^2); the incompatible modes carry the
     rest of it (energy exact), the F-bar hex8 locks in shear */
  {
    const double Lx = 10, Ht = 1, kap = 1e-5, E = np.G * (3 * np.lambda + 2 * np.G) / (np.lambda + np.G), nu = np.lambda / (2 * (np.lambda + np.G));
    const double Wexact = 0.5 * E / (1 - nu * nu) * Ht * Ht * Ht / 12.0 * kap * kap * Lx; /* unit width */
    Hex8Options  fbar = {1};
    double       fe2[24], W[2] = {0, 0}, hz[NHE] = {0};
    for (int a = 0; a < 8; a++) {
      X[a][0] = 0.5 * (hex8_nodes[a][0] + 1) * Lx;
      X[a][1] = 0.5 * (hex8_nodes[a][1] + 1);
      X[a][2] = 0.5 * hex8_nodes[a][2] * Ht;
      u[a][0] = -kap * X[a][0] * X[a][2];
      u[a][1] = 0;
      u[a][2] = 0.5 * kap * (X[a][0] * X[a][0] + nu / (1 - nu) * X[a][2] * X[a][2]);
    }
    hex8_eas_element(&eo, &neo, X, u, hz, fe, NULL, h, NULL, NULL);
    hex8_element(&fbar, &neo, X, u, hz, fe2, NULL, h, NULL);
    for (int k = 0; k < 24; k++) {
      W[0] += 0.5 * fe[k] * u[k / 3][k % 3];
      W[1] += 0.5 * fe2[k] * u[k / 3][k % 3];
    }
    TU_CHECK(fabs(W[0] / Wexact - 1) < 1e-3 && W[1] / Wexact > 5,
             "one slender element in pure bending (10 x 1, plane strain): energy / exact = %.5f (hex8 F-bar: %.1f, locked)", W[0] / Wexact, W[1] / Wexact);
  }
}

int main(int argc, char **argv)
{
  PetscCall(PetscInitialize(&argc, &argv, NULL, NULL));
  TestKernels();
  /* the type in the registry */
  {
    Element              el;
    const ElementKernel *ek;
    PetscCall(PetscOptionsInsertString(NULL, "-element_type hex8_eas -fe_eas_max_it 12"));
    PetscCall(ElementCreate(PETSC_COMM_WORLD, &el));
    PetscCall(ElementSetFromOptions(el));
    PetscCall(ElementGetKernel(el, &ek));
    TU_CHECK(!strcmp(ek->name, "hex8_eas") && ek->nen == 8 && ek->nqp == HEX8_NQP && ek->nstate == HEX8_EAS_NALPHA && ek->nface == 6 && ((const Hex8EASOptions *)ek->ctx)->max_it == 12,
             "-element_type hex8_eas: %s, nen %d, nqp %d, nstate %d, -fe_eas_max_it read", ek->name, ek->nen, ek->nqp, ek->nstate);
    PetscCall(ElementDestroy(&el));
    PetscCall(PetscOptionsClear(NULL));
  }
  PetscCall(PetscFinalize());
  TU_RETURN();
}
