/* Unit tests of the hex8 kernels: shape functions, the patch test, objectivity, and the exact
   element tangent against central finite differences of the element residual; the element
   registry and descriptor: options, unknown types, any material through the MaterialKernel
   (a hyperelastic test material with its own history width), and the kernel with J2 through
   the interfaces bit for bit against the element written with direct calls of J2Update. */
#include <stdlib.h>
#include <string.h>
#include <petscsys.h>
#include "testutil.h"
#include "testcapture.h"
#include "element.h"
#include "element_hex8.h"
#include "material_impl.h"
#include "material_j2.h"
#include "tensor.h"

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

/* a distorted unit-ish hexahedron */
static void distorted_hex(double X[8][3])
{
  for (int a = 0; a < 8; a++)
    for (int i = 0; i < 3; i++) X[a][i] = 0.5 * (hex8_nodes[a][i] + 1) + 0.12 * urand();
}

static void init_hist(double h[8][J2_NHIST])
{
  for (int q = 0; q < 8; q++) J2HistoryInit(h[q]);
}

/* max relative difference between ke and central differences of fe */
static double tangent_fd_error(const MaterialKernel *mk, const Hex8Options *eo, const double X[8][3], const double u[8][3], const double *hn)
{
  double ke[576], fe[24], fp[24], fm[24], up[8][3], um[8][3];
  double num = 0, den = 0, *h = malloc(HEX8_NQP * (size_t)mk->nhist * sizeof(double));
  if (hex8_element(eo, mk, X, u, hn, fe, ke, h, NULL) != MAT_OK) {
    free(h);
    return 1e30;
  }
  for (int bm = 0; bm < 24; bm++) {
    const double eps = 1e-7;
    memcpy(up, u, sizeof(up));
    memcpy(um, u, sizeof(um));
    up[bm / 3][bm % 3] += eps;
    um[bm / 3][bm % 3] -= eps;
    hex8_element(eo, mk, X, up, hn, fp, NULL, h, NULL);
    hex8_element(eo, mk, X, um, hn, fm, NULL, h, NULL);
    for (int ai = 0; ai < 24; ai++) {
      const double fd = (fp[ai] - fm[ai]) / (2 * eps);
      num += (ke[ai * 24 + bm] - fd) * (ke[ai * 24 + bm] - fd);
      den += ke[ai * 24 + bm] * ke[ai * 24 + bm];
    }
  }
  free(h);
  return sqrt(num / den);
}

static PetscErrorCode TestHex8Kernels(void)
{
  J2Params       mp;
  MaterialKernel mk;
  Hex8Options    fbar = {1}, plain = {0};
  double         X[8][3], u[8][3], hn[8][J2_NHIST], h[8][J2_NHIST], fe[24];

  PetscFunctionBeginUser;
  srand(12345);
  benchmark_material(&mp);
  J2KernelInit(&mp, &mk);

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
          if (hex8_element(&fbar, &mk, X, u, &hn[0][0], fe, NULL, &h[0][0], NULL) != MAT_OK) printf("# element evaluation failed\n");
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
    hex8_element(&fbar, &mk, X, u, &hn[0][0], fe, NULL, &h[0][0], &info);
    for (int k = 0; k < 24; k++) fmax_ = fmax(fmax_, fabs(fe[k]));
    TU_CHECK(fmax_ < 1e-9 * mp.E && info.mises < 1e-9 * mp.E, "rigid rotation of 90 deg: max |f| %.2e, von Mises %.2e", fmax_, info.mises);
  }

  /* exact tangent against finite differences */
  {
    const char *label[2] = {"standard", "F-bar"};
    for (int variant = 0; variant < 2; variant++) {
      const Hex8Options *eo = variant ? &fbar : &plain;
      double                e;
      /* elastic: small displacements */
      distorted_hex(X);
      for (int a = 0; a < 8; a++)
        for (int i = 0; i < 3; i++) u[a][i] = 1e-5 * urand();
      init_hist(hn);
      e = tangent_fd_error(&mk, eo, X, u, &hn[0][0]);
      TU_CHECK(e < 1e-6, "%s element tangent vs finite differences, elastic: %.2e", label[variant], e);
      /* plastic: large non-homogeneous deformation from a plastically deformed committed state */
      for (int a = 0; a < 8; a++)
        for (int i = 0; i < 3; i++) u[a][i] = 0.05 * urand() + (i == 0 ? 0.1 * X[a][0] : 0);
      init_hist(hn);
      hex8_element(eo, &mk, X, u, &hn[0][0], fe, NULL, &h[0][0], NULL);
      memcpy(hn, h, sizeof(h));
      double plastic_ep = 0;
      for (int q = 0; q < 8; q++) plastic_ep = fmax(plastic_ep, hn[q][J2_HIST_EP]);
      for (int a = 0; a < 8; a++)
        for (int i = 0; i < 3; i++) u[a][i] += 0.01 * urand() + (i == 1 ? 0.03 * X[a][2] : 0);
      e = tangent_fd_error(&mk, eo, X, u, &hn[0][0]);
      TU_CHECK(plastic_ep > 1e-3 && e < 1e-6, "%s element tangent vs finite differences, plastic (committed ep %.3f): %.2e", label[variant], plastic_ep, e);
    }
  }

  /* an inverted configuration is reported, not computed */
  {
    distorted_hex(X);
    for (int a = 0; a < 8; a++)
      for (int i = 0; i < 3; i++) u[a][i] = (i == 2) ? -2.0 * X[a][2] : 0; /* mirror through z */
    init_hist(hn);
    const int st = hex8_element(&fbar, &mk, X, u, &hn[0][0], fe, NULL, &h[0][0], NULL);
    TU_CHECK(st == MAT_ERR_JACOBIAN, "inverted element returns MAT_ERR_JACOBIAN (status %d)", st);
  }
  PetscFunctionReturn(0);
}

/* ---------- the element with direct calls of the J2 kernel: the formulation as it was written
   before the material and element interfaces (fixed history width J2_NHIST, J2Update called by
   name), kept here as the reference of the bit-for-bit comparison ---------- */
static void ref_spatial_gradient(const double dNdX[8][3], const double Finv[9], double g[8][3])
{
  for (int a = 0; a < 8; a++)
    for (int j = 0; j < 3; j++) g[a][j] = dNdX[a][0] * Finv[j] + dNdX[a][1] * Finv[3 + j] + dNdX[a][2] * Finv[6 + j];
}

static int ref_hex8_j2(const J2Params *mp, int fbar, const double X[8][3], const double u[8][3], const double hn[][J2_NHIST], double fe[24], double *ke, double h[][J2_NHIST], ElementInfo *info)
{
  static const double centre[3] = {0, 0, 0};
  double              dNdX0[8][3], F0[9], F0inv[9], g0[8][3], J0 = 1.0;
  double              dtau[81], tau[9];
  int                 nplastic = 0;

  memset(fe, 0, 24 * sizeof(double));
  if (ke) memset(ke, 0, 24 * 24 * sizeof(double));
  if (info) memset(info, 0, sizeof(*info));
  if (fbar || info) {
    if (hex8_gradient(X, centre, dNdX0) <= 0) return MAT_ERR_JACOBIAN;
    hex8_defgrad(u, dNdX0, F0);
    J0 = t3_inv(F0, F0inv);
    if (J0 <= 0) return MAT_ERR_JACOBIAN;
    ref_spatial_gradient(dNdX0, F0inv, g0);
    if (info) memcpy(info->F0, F0, sizeof(F0));
  }
  for (int q = 0; q < HEX8_NQP; q++) {
    double       dNdX[8][3], F[9], Finv[9], Fb[9], g[8][3];
    const double detX = hex8_gradient(X, hex8_gauss[q], dNdX);
    if (detX <= 0) return MAT_ERR_JACOBIAN;
    hex8_defgrad(u, dNdX, F);
    const double J = t3_inv(F, Finv);
    if (J <= 0) return MAT_ERR_JACOBIAN;
    ref_spatial_gradient(dNdX, Finv, g);
    double alpha = 1.0;
    if (fbar) alpha = cbrt(J0 / J);
    for (int k = 0; k < 9; k++) Fb[k] = alpha * F[k];
    int       plastic = 0;
    const int st      = J2Update(mp, Fb, hn[q], tau, ke ? dtau : NULL, h[q], &plastic);
    if (st != MAT_OK) return st;
    nplastic += plastic;
    const double w = detX;
    for (int a = 0; a < 8; a++)
      for (int i = 0; i < 3; i++) fe[3 * a + i] += w * (tau[3 * i] * g[a][0] + tau[3 * i + 1] * g[a][1] + tau[3 * i + 2] * g[a][2]);
    if (info) {
      const double Jb = alpha * alpha * alpha * J, s[6] = {tau[0] / Jb, tau[4] / Jb, tau[8] / Jb, tau[1] / Jb, tau[5] / Jb, tau[2] / Jb};
      const double p = (s[0] + s[1] + s[2]) / 3.0, d0 = s[0] - p, d1 = s[1] - p, d2 = s[2] - p;
      info->mises += sqrt(1.5 * (d0 * d0 + d1 * d1 + d2 * d2 + 2 * (s[3] * s[3] + s[4] * s[4] + s[5] * s[5]))) / HEX8_NQP;
      info->ep += h[q][J2_HIST_EP] / HEX8_NQP;
      for (int k = 0; k < 6; k++) info->sigma[k] += s[k] / HEX8_NQP;
    }
    if (!ke) continue;
    double Hm[9][24], c3 = alpha / 3.0, dg[24];
    for (int ij = 0; ij < 9; ij++) {
      const double *T = dtau + 9 * ij;
      for (int b = 0; b < 8; b++)
        for (int m = 0; m < 3; m++) Hm[ij][3 * b + m] = alpha * (T[3 * m] * dNdX[b][0] + T[3 * m + 1] * dNdX[b][1] + T[3 * m + 2] * dNdX[b][2]);
    }
    if (fbar) {
      for (int b = 0; b < 8; b++)
        for (int m = 0; m < 3; m++) dg[3 * b + m] = c3 * (g0[b][m] - g[b][m]);
      for (int ij = 0; ij < 9; ij++) {
        double t = 0;
        for (int kL = 0; kL < 9; kL++) t += dtau[9 * ij + kL] * F[kL];
        for (int bm = 0; bm < 24; bm++) Hm[ij][bm] += t * dg[bm];
      }
    }
    for (int b = 0; b < 8; b++)
      for (int i = 0; i < 3; i++) {
        const double sb = tau[3 * i] * g[b][0] + tau[3 * i + 1] * g[b][1] + tau[3 * i + 2] * g[b][2];
        for (int n = 0; n < 3; n++) Hm[3 * i + n][3 * b + n] -= sb;
      }
    for (int a = 0; a < 8; a++) {
      const double ga0 = w * g[a][0], ga1 = w * g[a][1], ga2 = w * g[a][2];
      for (int i = 0; i < 3; i++) {
        double       *row = ke + (3 * a + i) * 24;
        const double *H0 = Hm[3 * i], *H1 = Hm[3 * i + 1], *H2 = Hm[3 * i + 2];
        for (int bm = 0; bm < 24; bm++) row[bm] += ga0 * H0[bm] + ga1 * H1[bm] + ga2 * H2[bm];
      }
    }
  }
  if (info) info->nplastic = nplastic;
  return MAT_OK;
}

static int info_same(const ElementInfo *a, const ElementInfo *b)
{
  return !memcmp(&a->ep, &b->ep, sizeof(double)) && !memcmp(&a->mises, &b->mises, sizeof(double)) && !memcmp(a->sigma, b->sigma, sizeof(a->sigma)) && !memcmp(a->F0, b->F0, sizeof(a->F0)) && a->nplastic == b->nplastic;
}

/* ---------- a hyperelastic test material with 3 history doubles per point ----------
   compressible neo-Hookean, Kirchhoff stress tau = G (b - I) + lambda ln J I, b = F F^T;
   d tau_ij / d F_kL = G (d_ik F_jL + F_iL d_jk) + lambda d_ij Finv_Lk.
   History (for the layout test only): h = {J, tr b, number of updates since the virgin state};
   its "plastic strain" is h[2]. */
typedef struct {
  double G, lambda;
} NeoParams;
#define NEO_NHIST 3

static int NeoUpdate(const void *ctx, const double F[9], const double *hn, double tau[9], double *dtau, double *h, int *plastic)
{
  const NeoParams *p = (const NeoParams *)ctx;
  double           b[9], Fi[9];
  const double     J = t3_inv(F, Fi);
  if (plastic) *plastic = 0;
  if (!(J > 0)) {
    memset(tau, 0, 9 * sizeof(double));
    if (dtau) memset(dtau, 0, 81 * sizeof(double));
    memcpy(h, hn, NEO_NHIST * sizeof(double));
    return MAT_ERR_JACOBIAN;
  }
  t3_mult(F, F, b);
  const double lnJ = log(J);
  for (int i = 0; i < 9; i++) tau[i] = p->G * (b[i] - (i % 4 == 0)) + (i % 4 == 0 ? p->lambda * lnJ : 0.0);
  h[0] = J;
  h[1] = b[0] + b[4] + b[8];
  h[2] = hn[2] + 1;
  if (dtau)
    for (int i = 0; i < 3; i++)
      for (int j = 0; j < 3; j++)
        for (int k = 0; k < 3; k++)
          for (int L = 0; L < 3; L++) dtau[(3 * i + j) * 9 + 3 * k + L] = p->G * ((i == k) * F[3 * j + L] + F[3 * i + L] * (j == k)) + (i == j) * p->lambda * Fi[3 * L + k];
  return MAT_OK;
}

static void NeoHistoryInit(const void *ctx, double *h)
{
  h[0] = 1;
  h[1] = 3;
  h[2] = 0;
}

static double NeoPlasticStrain(const void *ctx, const double *h) { return h[2]; }

static PetscErrorCode MaterialDestroy_Neo(Material mat)
{
  PetscFunctionBeginUser;
  PetscCall(PetscFree(mat->data));
  PetscFunctionReturn(0);
}

static PetscErrorCode MaterialCreate_Neo(Material mat)
{
  NeoParams *p;

  PetscFunctionBeginUser;
  PetscCall(PetscNew(&p));
  p->G                       = 1000;
  p->lambda                  = 1500;
  mat->data                  = p;
  mat->ops.destroy           = MaterialDestroy_Neo;
  mat->kernel.nhist          = NEO_NHIST;
  mat->kernel.ctx            = p;
  mat->kernel.update         = NeoUpdate;
  mat->kernel.history_init   = NeoHistoryInit;
  mat->kernel.plastic_strain = NeoPlasticStrain;
  PetscFunctionReturn(0);
}

/* create an Element and a Material from the options in opts; ierr: the first error, objects NULL then */
static PetscErrorCode CreateFromOptions(const char *opts, Element *el, Material *mat, PetscErrorCode *ierr)
{
  PetscFunctionBeginUser;
  *el     = NULL;
  *mat    = NULL;
  *ierr   = 0;
  ErrMsg[0] = '\0';
  PetscCall(PetscOptionsClear(NULL));
  PetscCall(PetscOptionsInsertString(NULL, opts));
  PetscCall(ElementCreate(PETSC_COMM_WORLD, el));
  PetscCall(MaterialCreate(PETSC_COMM_WORLD, mat));
  PetscCall(PetscPushErrorHandler(CaptureHandler, NULL));
  *ierr = ElementSetFromOptions(*el);
  if (!*ierr) *ierr = MaterialSetFromOptions(*mat);
  PetscCall(PetscPopErrorHandler());
  PetscCall(PetscOptionsClear(NULL));
  if (*ierr) {
    PetscCall(ElementDestroy(el));
    PetscCall(MaterialDestroy(mat));
  }
  PetscFunctionReturn(0);
}

static PetscErrorCode TestRegistry(void)
{
  Element              el;
  Material             mat;
  PetscErrorCode       ierr;
  const ElementKernel *ek;

  PetscFunctionBeginUser;
  /* defaults: hex8 with F-bar, the face table in the descriptor */
  PetscCall(CreateFromOptions("", &el, &mat, &ierr));
  TU_CHECK(!ierr && el, "element and material from no options (status %d)", (int)ierr);
  if (!el) PetscFunctionReturn(0);
  PetscCall(ElementGetKernel(el, &ek));
  {
    const Hex8Options *eo = (const Hex8Options *)ek->ctx;
    TU_CHECK(!strcmp(ek->name, "hex8") && ek->nen == 8 && ek->nqp == HEX8_NQP && ek->nstate == 0 && ek->nface == 6 && eo->fbar == 1,
             "default -element_type: %s, nen %d, nqp %d, nstate %d, nface %d, F-bar %d", ek->name, ek->nen, ek->nqp, ek->nstate, ek->nface, eo->fbar);
    /* every face: its corners span the reference face, counter-clockwise seen from outside */
    int good = 0;
    for (int f = 0; f < ek->nface; f++) {
      const double *p0 = hex8_nodes[ek->face[f][0]], *p1 = hex8_nodes[ek->face[f][1]], *p3 = hex8_nodes[ek->face[f][3]];
      double        c[3] = {0, 0, 0}, e1[3], e2[3], n[3];
      for (int k = 0; k < 4; k++)
        for (int i = 0; i < 3; i++) c[i] += 0.25 * hex8_nodes[ek->face[f][k]][i];
      for (int i = 0; i < 3; i++) {
        e1[i] = p1[i] - p0[i];
        e2[i] = p3[i] - p0[i];
      }
      n[0] = e1[1] * e2[2] - e1[2] * e2[1];
      n[1] = e1[2] * e2[0] - e1[0] * e2[2];
      n[2] = e1[0] * e2[1] - e1[1] * e2[0];
      const int planar = fabs(fabs(c[0]) + fabs(c[1]) + fabs(c[2]) - 1) == 0;
      if (planar && n[0] * c[0] + n[1] * c[1] + n[2] * c[2] > 0) good++;
    }
    TU_CHECK(good == 6, "hex8 face table: %d of 6 faces are reference faces with the outward normal by the right-hand rule", good);
  }
  PetscCall(ElementDestroy(&el));
  PetscCall(MaterialDestroy(&mat));

  /* the option of the formulation */
  PetscCall(CreateFromOptions("-element_type hex8 -fe_fbar false", &el, &mat, &ierr));
  if (el) {
    PetscCall(ElementGetKernel(el, &ek));
    TU_CHECK(!ierr && ((const Hex8Options *)ek->ctx)->fbar == 0, "-fe_fbar false: F-bar off");
    PetscCall(ElementView(el, PETSC_VIEWER_STDOUT_WORLD));
    PetscCall(MaterialView(mat, PETSC_VIEWER_STDOUT_WORLD));
  } else TU_CHECK(0, "-fe_fbar false: error %d [%s]", (int)ierr, ErrMsg);
  PetscCall(ElementDestroy(&el));
  PetscCall(MaterialDestroy(&mat));

  /* unknown types are refused, naming the option */
  PetscCall(CreateFromOptions("-element_type hex27", &el, &mat, &ierr));
  TU_CHECK(ierr && strstr(ErrMsg, "-element_type") && strstr(ErrMsg, "hex27"), "unknown -element_type: error %d [%s]", (int)ierr, ErrMsg);
  PetscCall(CreateFromOptions("-material_type umat_nosuch", &el, &mat, &ierr));
  TU_CHECK(ierr && strstr(ErrMsg, "-material_type") && strstr(ErrMsg, "umat_nosuch"), "unknown -material_type: error %d [%s]", (int)ierr, ErrMsg);
  PetscFunctionReturn(0);
}

/* hex8 with J2 through the Material and Element objects, against the reference element with
   direct J2Update calls: fe, ke, trial history and info bit for bit, elastic and plastic,
   with and without F-bar, Swift and linear hardening, with and without tangent */
static PetscErrorCode TestBitForBit(void)
{
  const char *opts[4] = {"-fe_fbar 0", "", "-fe_fbar 0 -material_hardening linear -material_yield 200 -material_hardening_modulus 1500", "-material_hardening linear -material_yield 200 -material_hardening_modulus 1500"};
  int         nsame = 0, ncases = 0, nplastic = 0;

  PetscFunctionBeginUser;
  for (int c = 0; c < 4; c++) {
    Element               el;
    Material              mat;
    PetscErrorCode        ierr;
    const ElementKernel  *ek = NULL;
    const MaterialKernel *mk = NULL;
    PetscCall(CreateFromOptions(opts[c], &el, &mat, &ierr));
    if (ierr) {
      TU_CHECK(0, "options '%s': error %d [%s]", opts[c], (int)ierr, ErrMsg);
      continue;
    }
    PetscCall(ElementGetKernel(el, &ek));
    PetscCall(MaterialGetKernel(mat, &mk));
    const J2Params *mp   = (const J2Params *)mk->ctx;
    const int       fbar = ((const Hex8Options *)ek->ctx)->fbar;
    double          X[8][3], u[8][3], hn[8][J2_NHIST], h[8][J2_NHIST], hr[8][J2_NHIST], fe[24], fr[24], ke[576], kr[576];
    ElementInfo     info, ir;
    srand(777 + c);
    distorted_hex(X);
    for (int q = 0; q < 8; q++) mk->history_init(mk->ctx, hn[q]);
    for (int step = 0; step < 3; step++) {
      for (int a = 0; a < 8; a++)
        for (int i = 0; i < 3; i++) u[a][i] = (step == 0 ? 1e-5 : 0.04) * urand() + (i == 0 ? 0.05 * step * X[a][0] : 0) + (i == 1 ? 0.02 * step * X[a][2] : 0);
      for (int withk = 0; withk < 2; withk++) {
        memset(h, 0xa5, sizeof h);
        memset(hr, 0x5a, sizeof hr);
        const int st  = ek->kernel(ek->ctx, mk, &X[0][0], &u[0][0], &hn[0][0], fe, withk ? ke : NULL, &h[0][0], &info);
        const int str = ref_hex8_j2(mp, fbar, X, u, (const double(*)[J2_NHIST])hn, fr, withk ? kr : NULL, hr, &ir);
        ncases++;
        if (st == str && st == MAT_OK && !memcmp(fe, fr, sizeof fe) && (!withk || !memcmp(ke, kr, sizeof ke)) && !memcmp(h, hr, sizeof h) && info_same(&info, &ir)) nsame++;
        else printf("# differs: options '%s', step %d, tangent %d, status %d/%d\n", opts[c], step, withk, st, str);
      }
      nplastic += info.nplastic;
      memcpy(hn, h, sizeof h);
    }
    PetscCall(ElementDestroy(&el));
    PetscCall(MaterialDestroy(&mat));
  }
  TU_CHECK(nsame == ncases && nplastic > 0, "hex8 + J2 through ElementKernel/MaterialKernel vs direct J2Update calls: %d of %d evaluations identical bit for bit in fe, ke, h, info (%d plastic point evaluations)", nsame, ncases, nplastic);
  PetscFunctionReturn(0);
}

/* a material registered by the program, with 3 history doubles per point, through the hex8 kernel */
static PetscErrorCode TestOtherMaterial(void)
{
  Element               el;
  Material              mat;
  PetscErrorCode        ierr;
  const ElementKernel  *ek = NULL;
  const MaterialKernel *mk = NULL;
  const int             guard = 5;

  PetscFunctionBeginUser;
  PetscCall(MaterialRegister("test_neohooke", MaterialCreate_Neo));
  for (int variant = 0; variant < 2; variant++) {
    PetscCall(CreateFromOptions(variant ? "-material_type test_neohooke" : "-material_type test_neohooke -fe_fbar 0", &el, &mat, &ierr));
    if (ierr) {
      TU_CHECK(0, "-material_type test_neohooke: error %d [%s]", (int)ierr, ErrMsg);
      PetscFunctionReturn(0);
    }
    PetscCall(ElementGetKernel(el, &ek));
    PetscCall(MaterialGetKernel(mat, &mk));
    const int nh = mk->nhist, n = ek->nqp * nh + ek->nstate, fbar = ((const Hex8Options *)ek->ctx)->fbar;
    double    X[8][3], u[8][3], fe[24], *hn, *h, worst = 0, err;
    int       layout = 1;
    PetscCall(PetscMalloc2(n, &hn, n + guard, &h));
    srand(4321 + variant);
    distorted_hex(X);
    for (int q = 0; q < ek->nqp; q++) mk->history_init(mk->ctx, hn + q * nh);
    for (int a = 0; a < 8; a++)
      for (int i = 0; i < 3; i++) u[a][i] = 0.05 * urand() + (i == 0 ? 0.2 * X[a][0] : 0) + (i == 2 ? 0.1 * X[a][1] : 0);
    for (int k = 0; k < n + guard; k++) h[k] = -7.0;
    ElementInfo info;
    const int   st = ek->kernel(ek->ctx, mk, &X[0][0], &u[0][0], hn, fe, NULL, h, &info);
    /* the trial history of point q lies at h + q nhist: J and tr b there are those of (F-bar) F at that point */
    for (int q = 0; q < ek->nqp; q++) {
      double dNdX[8][3], F[9], Fi[9], F0[9], Fi0[9], dNdX0[8][3], b[9];
      const double xc[3] = {0, 0, 0};
      hex8_gradient(X, hex8_gauss[q], dNdX);
      hex8_defgrad(u, dNdX, F);
      double J = t3_inv(F, Fi), alpha = 1;
      if (fbar) {
        hex8_gradient(X, xc, dNdX0);
        hex8_defgrad(u, dNdX0, F0);
        alpha = cbrt(t3_inv(F0, Fi0) / J);
      }
      for (int k = 0; k < 9; k++) F[k] *= alpha;
      t3_mult(F, F, b);
      J = t3_det(F);
      worst = fmax(worst, fabs(h[q * nh] - J) / J + fabs(h[q * nh + 1] - (b[0] + b[4] + b[8])) / 3);
      if (h[q * nh + 2] != 1.0) layout = 0;
    }
    for (int k = n; k < n + guard; k++)
      if (h[k] != -7.0) layout = 0;
    TU_CHECK(st == MAT_OK && nh == NEO_NHIST && layout && worst < 1e-13 && info.ep == 1.0,
             "test material with nhist %d through hex8 (F-bar %d): history at point q at h + q*nhist (J, tr b: max error %.2e), nothing written past nqp*nhist = %d, ElementInfo.ep from plastic_strain = %g",
             nh, fbar, worst, n, info.ep);
    err = tangent_fd_error(mk, (const Hex8Options *)ek->ctx, X, u, hn);
    TU_CHECK(err < 1e-6, "hex8 (F-bar %d) element tangent vs finite differences with the test material: %.2e", fbar, err);
    PetscCall(PetscFree2(hn, h));
    PetscCall(ElementDestroy(&el));
    PetscCall(MaterialDestroy(&mat));
  }
  PetscFunctionReturn(0);
}

int main(int argc, char **argv)
{
  PetscCall(PetscInitialize(&argc, &argv, NULL, NULL));
  PetscCall(TestHex8Kernels());
  PetscCall(TestRegistry());
  PetscCall(TestBitForBit());
  PetscCall(TestOtherMaterial());
  PetscCall(PetscFinalize());
  TU_RETURN();
}
