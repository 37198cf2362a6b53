/* Trilinear hexahedron with F-bar, finite strain, exact tangent.

   Weak form (reference volume, Kirchhoff stress of the modified gradient):
     f_ai = sum_qp w detJ0  taubar_ij g_aj,     g_aj = dN_a/dX_K Finv_Kj  (spatial gradient)
     Fbar = alpha F,  alpha = (J0/J)^(1/3),  J0 = det F at the element centroid.
   Linearisation with respect to nodal displacements u_bm:
     d Fbar_kL = alpha [ delta_km dN_b/dX_L + 1/3 (g0_bm - g_bm) F_kL ]
     d g_aj    = - g_am g_bj
   so that
     K_ai,bm = sum_qp w detJ0 [ alpha g_aj Tau_ij,mL dN_b/dX_L
                               + alpha/3 (g_aj Tau_ij,kL F_kL) (g0_bm - g_bm)
                               - taubar_ij g_bj g_am ]
   with Tau = d tau / d F evaluated at Fbar (material kernel). Without F-bar alpha = 1 and
   the second term vanishes.

   The first part of this file is the formulation on plain arrays (include/element_hex8.h); the
   second is the element type "hex8": its option -fe_fbar, view and descriptor. */
#include <math.h>
#include <string.h>

#include "element_hex8.h"
#include "element_impl.h"
#include "options.h"
#include "tensor.h"

#define GP 0.57735026918962576451

const double hex8_nodes[8][3] = {
  {-1, -1, -1}, {1, -1, -1}, {1, 1, -1}, {-1, 1, -1},
  {-1, -1, 1},  {1, -1, 1},  {1, 1, 1},  {-1, 1, 1}
};

const double hex8_gauss[HEX8_NQP][3] = {
  {-GP, -GP, -GP}, {GP, -GP, -GP}, {GP, GP, -GP}, {-GP, GP, -GP},
  {-GP, -GP, GP},  {GP, -GP, GP},  {GP, GP, GP},  {-GP, GP, GP}
};

const int hex8_faces[6][4] = {
  {0, 3, 2, 1}, {4, 5, 6, 7}, {0, 1, 5, 4}, {1, 2, 6, 5}, {2, 3, 7, 6}, {3, 0, 4, 7}
};

void hex8_shape(const double xi[3], double N[8], double dN[8][3])
{
  for (int a = 0; a < 8; a++) {
    const double s = hex8_nodes[a][0], t = hex8_nodes[a][1], r = hex8_nodes[a][2];
    const double fx = 1 + s * xi[0], fy = 1 + t * xi[1], fz = 1 + r * xi[2];
    if (N) N[a] = 0.125 * fx * fy * fz;
    if (dN) {
      dN[a][0] = 0.125 * s * fy * fz;
      dN[a][1] = 0.125 * t * fx * fz;
      dN[a][2] = 0.125 * r * fx * fy;
    }
  }
}

void hex8_gauss_position(const double X[8][3], const double u[8][3], int q, double x[3])
{
  double N[8];
  hex8_shape(hex8_gauss[q], N, NULL);
  x[0] = x[1] = x[2] = 0;
  for (int a = 0; a < 8; a++)
    for (int i = 0; i < 3; i++) x[i] += N[a] * (X[a][i] + u[a][i]);
}

double hex8_gradient(const double X[8][3], const double xi[3], double dNdX[8][3])
{
  double dN[8][3], Jm[9] = {0}, Ji[9];
  hex8_shape(xi, NULL, dN);
  /* Jm_iK = dX_i / dxi_K */
  for (int a = 0; a < 8; a++)
    for (int i = 0; i < 3; i++)
      for (int k = 0; k < 3; k++) Jm[3 * i + k] += X[a][i] * dN[a][k];
  const double det = t3_inv(Jm, Ji);
  if (det <= 0) return det;
  /* dN/dX_i = dN/dxi_K dxi_K/dX_i = dN/dxi_K Ji_Ki */
  for (int a = 0; a < 8; a++)
    for (int i = 0; i < 3; i++) dNdX[a][i] = dN[a][0] * Ji[i] + dN[a][1] * Ji[3 + i] + dN[a][2] * Ji[6 + i];
  return det;
}

void hex8_defgrad(const double u[8][3], const double dNdX[8][3], double F[9])
{
  for (int i = 0; i < 3; i++)
    for (int K = 0; K < 3; K++) {
      double s = (i == K) ? 1.0 : 0.0;
      for (int a = 0; a < 8; a++) s += u[a][i] * dNdX[a][K];
      F[3 * i + K] = s;
    }
}

double hex8_min_jacobian(const double X[8][3])
{
  double dNdX[8][3], m = INFINITY;
  for (int q = 0; q < HEX8_NQP; q++) {
    const double d = hex8_gradient(X, hex8_gauss[q], dNdX);
    if (d < m || isnan(d)) m = d;
  }
  for (int q = 0; q < 8; q++) {
    const double d = hex8_gradient(X, hex8_nodes[q], dNdX);
    if (d < m || isnan(d)) m = d;
  }
  return m;
}

/* ------------------------------------------------------------------------------------------ */
/* the element kernel                                                                          */
/* ------------------------------------------------------------------------------------------ */
/* dN_a/dxi_K at the 8 Gauss points (q = 0..7) and at the centroid (q = 8), component-major:
   DNQ[q][K][a]. Compile-time constants, the same products as hex8_shape's
   0.125 s_a (1 + t_a eta)(1 + r_a zeta) in the same order (bit for bit). */
#define NS(a) (((a) == 1 || (a) == 2 || (a) == 5 || (a) == 6) ? 1.0 : -1.0)
#define NT(a) (((a) == 2 || (a) == 3 || (a) == 6 || (a) == 7) ? 1.0 : -1.0)
#define NR(a) ((a) >= 4 ? 1.0 : -1.0)
#define DNX(a, x, y, z) (0.125 * NS(a) * (1 + NT(a) * (y)) * (1 + NR(a) * (z)))
#define DNY(a, x, y, z) (0.125 * NT(a) * (1 + NS(a) * (x)) * (1 + NR(a) * (z)))
#define DNZ(a, x, y, z) (0.125 * NR(a) * (1 + NS(a) * (x)) * (1 + NT(a) * (y)))
#define ROW8(D, x, y, z) {D(0, x, y, z), D(1, x, y, z), D(2, x, y, z), D(3, x, y, z), D(4, x, y, z), D(5, x, y, z), D(6, x, y, z), D(7, x, y, z)}
#define PT(x, y, z) {ROW8(DNX, x, y, z), ROW8(DNY, x, y, z), ROW8(DNZ, x, y, z)}
#define GQ(q) PT(NS(q) * GP, NT(q) * GP, NR(q) * GP)
static const double DNQ[HEX8_NQP + 1][3][8] = {GQ(0), GQ(1), GQ(2), GQ(3), GQ(4), GQ(5), GQ(6), GQ(7), PT(0.0, 0.0, 0.0)};
#undef GQ
#undef PT
#undef ROW8
#undef DNX
#undef DNY
#undef DNZ
#undef NS
#undef NT
#undef NR

/* Reference gradient at the point q of DNQ, component-major: dX[K][a] = dN_a/dX_K, and
   det(dX/dxi) (dX set only when it is positive). The same sums as hex8_gradient. */
static inline double ref_gradient(const double (*restrict X)[3], int q, double dX[restrict 3][8])
{
  const double(*D)[8] = DNQ[q];
  double Jm[9] = {0}, Ji[9];
  /* Jm_iK = dX_i / dxi_K */
  for (int a = 0; a < 8; a++)
    for (int i = 0; i < 3; i++)
      for (int k = 0; k < 3; k++) Jm[3 * i + k] += X[a][i] * D[k][a];
  const double det = t3_inv(Jm, Ji);
  if (det <= 0) return det;
  for (int i = 0; i < 3; i++)
    for (int a = 0; a < 8; a++) dX[i][a] = D[0][a] * Ji[i] + D[1][a] * Ji[3 + i] + D[2][a] * Ji[6 + i];
  return det;
}

/* F_iK = delta_iK + sum_a u_ai dN_a/dX_K */
static inline void defgrad_cm(const double (*restrict u)[3], const double dX[restrict 3][8], double F[restrict 9])
{
  for (int i = 0; i < 3; i++)
    for (int K = 0; K < 3; K++) {
      double s = (i == K) ? 1.0 : 0.0;
      for (int a = 0; a < 8; a++) s += u[a][i] * dX[K][a];
      F[3 * i + K] = s;
    }
}

/* spatial gradient, component-major: g[j][a] = dN_a/dX_K Finv_Kj */
static inline void spatial_gradient_cm(const double dX[restrict 3][8], const double Finv[restrict 9], double g[restrict 3][8])
{
  for (int j = 0; j < 3; j++)
    for (int a = 0; a < 8; a++) g[j][a] = dX[0][a] * Finv[j] + dX[1][a] * Finv[3 + j] + dX[2][a] * Finv[6 + j];
}

/* Per Gauss point, with w = det(dX/dxi) (unit weights), g = the spatial gradient of F,
   taubar = tau(Fbar) and T = dtau/dF at Fbar (K_ai,bm of the header comment, term by term):
     fe[3a+i]       += w sum_j taubar_ij g_aj
     Hm[ij][3b+m]    = alpha sum_L T_ij,mL dN_b/dX_L                             (material)
                     + alpha/3 TF_ij (g0_bm - g_bm),   TF_ij = T_ij,kL F_kL       (F-bar)
     Hm[in][3b+n]   -= sum_j taubar_ij g_bj                                      (geometric)
     ke[3a+i][bm]   += w sum_n g_an Hm[in][bm]
   The reference gradients come from the constant table DNQ (no shape functions evaluated per
   element) and are kept component-major (dX[K][a], g[j][a]: unit stride over the 8 nodes) for
   F, the spatial gradient and the force; the tangent loops run over the 24 columns bm of a
   row, node-major as the interface wants them, on transposed copies. The kernel is compiled
   twice (tangent = 0 or 1, a constant in each copy): the residual evaluation carries none of
   the tangent's code or stack. The arithmetic is that of the formulation term by term, in the
   same order: fe and ke are the same bit for bit as the straightforward implementation
   (tests/test_fe.c). */
static inline __attribute__((always_inline)) int hex8_element_impl(const Hex8Options *eo, const MaterialKernel *mat, const double X[8][3], const double u[8][3], const double *hn, double fe[24], double *ke, double *h, ElementInfo *info, const int tangent)
{
  double       dX0[3][8], F0[9], F0inv[9], g0[3][8], J0 = 1.0;
  double       dtau[81], tau[9], fc[3][8];
  int          nplastic = 0;
  const int    nh       = mat->nhist; /* history doubles per quadrature point */
  const int    fbar     = eo->fbar;
  const double(*restrict Xr)[3] = X;
  const double(*restrict ur)[3] = u;

  if (info) memset(info, 0, sizeof(*info));
  memset(fc, 0, sizeof(fc));
  if (tangent) memset(ke, 0, 24 * 24 * sizeof(double));

  if (fbar || info) {
    if (ref_gradient(Xr, HEX8_NQP, dX0) <= 0) goto fail_jac;
    defgrad_cm(ur, dX0, F0);
    J0 = t3_inv(F0, F0inv);
    if (J0 <= 0) goto fail_jac;
    spatial_gradient_cm(dX0, F0inv, g0);
    if (info) memcpy(info->F0, F0, sizeof(F0));
  }

  double celent = 0; /* the cube root of the reference volume, for a material that wants it */
  if (mat->set_point) {
    double dXv[3][8];
    for (int q = 0; q < HEX8_NQP; q++) celent += ref_gradient(Xr, q, dXv);
    celent = cbrt(celent);
  }
  for (int q = 0; q < HEX8_NQP; q++) {
    double       dX[3][8], F[9], Finv[9], Fb[9], g[3][8];
    const double detX = ref_gradient(Xr, q, dX);
    if (detX <= 0) goto fail_jac;
    defgrad_cm(ur, dX, F);
    const double J = t3_inv(F, Finv);
    if (J <= 0) goto fail_jac;
    spatial_gradient_cm(dX, Finv, g);

    double alpha = 1.0;
    if (fbar) alpha = cbrt(J0 / J);
    for (int k = 0; k < 9; k++) Fb[k] = alpha * F[k];

    int plastic = 0;
    if (mat->set_point) { /* a material that wants the point (a user material's NPT, COORDS, CELENT) */
      double xq[3];
      hex8_gauss_position(Xr, ur, q, xq);
      mat->set_point(mat->ctx, -1, q + 1, xq, celent);
    }
    const int st = mat->update(mat->ctx, Fb, hn + (size_t)q * nh, tau, tangent ? dtau : NULL, h + (size_t)q * nh, &plastic);
    if (st != MAT_OK) {
      if (tangent) memset(ke, 0, 24 * 24 * sizeof(double));
      memset(fe, 0, 24 * sizeof(double));
      return st;
    }
    nplastic += plastic;
    const double w = detX; /* unit Gauss weights */

    /* internal force */
    for (int i = 0; i < 3; i++)
      for (int a = 0; a < 8; a++) fc[i][a] += w * (tau[3 * i] * g[0][a] + tau[3 * i + 1] * g[1][a] + tau[3 * i + 2] * g[2][a]);

    if (info) {
      const double Jb = alpha * alpha * alpha * J, s[6] = {tau[0] / Jb, tau[4] / Jb, tau[8] / Jb, tau[1] / Jb, tau[5] / Jb, tau[2] / Jb};
      const double p = (s[0] + s[1] + s[2]) / 3.0, d0 = s[0] - p, d1 = s[1] - p, d2 = s[2] - p;
      info->mises += sqrt(1.5 * (d0 * d0 + d1 * d1 + d2 * d2 + 2 * (s[3] * s[3] + s[4] * s[4] + s[5] * s[5]))) / HEX8_NQP;
      info->ep += mat->plastic_strain(mat->ctx, h + (size_t)q * nh) / HEX8_NQP;
      for (int k = 0; k < 6; k++) info->sigma[k] += s[k] / HEX8_NQP;
    }

    if (!tangent) continue;
    /* the tangent in the node-major order: the gradients transposed */
    double dNdX[8][3], gn[8][3];
    for (int a = 0; a < 8; a++)
      for (int k = 0; k < 3; k++) {
        dNdX[a][k] = dX[k][a];
        gn[a][k]   = g[k][a];
      }
    double Hm[9][24], c3 = alpha / 3.0, dg[24];
    for (int ij = 0; ij < 9; ij++) {
      const double *T = dtau + 9 * ij;
      for (int b = 0; b < 8; b++)
        for (int m = 0; m < 3; m++) Hm[ij][3 * b + m] = alpha * (T[3 * m] * dNdX[b][0] + T[3 * m + 1] * dNdX[b][1] + T[3 * m + 2] * dNdX[b][2]);
    }
    if (fbar) {
      for (int b = 0; b < 8; b++)
        for (int m = 0; m < 3; m++) dg[3 * b + m] = c3 * (g0[m][b] - gn[b][m]);
      for (int ij = 0; ij < 9; ij++) {
        double t = 0;
        for (int kL = 0; kL < 9; kL++) t += dtau[9 * ij + kL] * F[kL];
        for (int bm = 0; bm < 24; bm++) Hm[ij][bm] += t * dg[bm];
      }
    }
    for (int b = 0; b < 8; b++)
      for (int i = 0; i < 3; i++) {
        const double sb = tau[3 * i] * gn[b][0] + tau[3 * i + 1] * gn[b][1] + tau[3 * i + 2] * gn[b][2];
        for (int n = 0; n < 3; n++) Hm[3 * i + n][3 * b + n] -= sb;
      }
    for (int a = 0; a < 8; a++) {
      const double ga0 = w * gn[a][0], ga1 = w * gn[a][1], ga2 = w * gn[a][2];
      for (int i = 0; i < 3; i++) {
        double       *row = ke + (3 * a + i) * 24;
        const double *H0 = Hm[3 * i], *H1 = Hm[3 * i + 1], *H2 = Hm[3 * i + 2];
        for (int bm = 0; bm < 24; bm++) row[bm] += ga0 * H0[bm] + ga1 * H1[bm] + ga2 * H2[bm];
      }
    }
  }
  /* back to the node-major layout of the interface */
  for (int a = 0; a < 8; a++)
    for (int i = 0; i < 3; i++) fe[3 * a + i] = fc[i][a];
  if (info) info->nplastic = nplastic;
  return MAT_OK;

fail_jac:
  memset(fe, 0, 24 * sizeof(double));
  if (tangent) memset(ke, 0, 24 * 24 * sizeof(double));
  return MAT_ERR_JACOBIAN;
}

/* two instances of the kernel, with and without the tangent, each compiled for its case */
int hex8_element(const Hex8Options *eo, const MaterialKernel *mat, const double X[8][3], const double u[8][3], const double *hn, double fe[24], double *ke, double *h, ElementInfo *info)
{
  if (ke) return hex8_element_impl(eo, mat, X, u, hn, fe, ke, h, info, 1);
  return hex8_element_impl(eo, mat, X, u, hn, fe, NULL, h, info, 0);
}

/* ------------------------------------------------------------------------------------------ */
/* the element type "hex8"                                                                     */
/* ------------------------------------------------------------------------------------------ */
static int Hex8Kernel(const void *ctx, const MaterialKernel *mat, const double *X, const double *u, const double *hn, double *fe, double *ke, double *h, ElementInfo *info)
{
  return hex8_element((const Hex8Options *)ctx, mat, (const double(*)[3])X, (const double(*)[3])u, hn, fe, ke, h, info);
}

static double Hex8MinJacobian(const double *X)
{
  return hex8_min_jacobian((const double(*)[3])X);
}

static PetscErrorCode ElementSetFromOptions_Hex8(Element el)
{
  Hex8Options *eo   = (Hex8Options *)el->data;
  PetscBool    fbar = eo->fbar ? PETSC_TRUE : PETSC_FALSE;

  PetscFunctionBeginUser;
  PetscOptionsBegin(el->comm, "fe_", "Element hex8: trilinear hexahedron", "Element");
  PetscCall(PetscOptionsBool("-fbar", "F-bar treatment of the volumetric part", NULL, fbar, &fbar, NULL));
  PetscOptionsEnd();
  eo->fbar = fbar ? 1 : 0;
  PetscFunctionReturn(0);
}

static PetscErrorCode ElementView_Hex8(Element el, PetscViewer v)
{
  const Hex8Options *eo = (const Hex8Options *)el->data;

  PetscFunctionBeginUser;
  PetscCall(PetscViewerASCIIPrintf(v, "8 nodes, 2x2x2 Gauss points, %s\n", eo->fbar ? "F-bar (centroid dilatation)" : "standard displacement formulation"));
  PetscFunctionReturn(0);
}

static PetscErrorCode ElementDestroy_Hex8(Element el)
{
  PetscFunctionBeginUser;
  PetscCall(PetscFree(el->data));
  PetscFunctionReturn(0);
}

PETSC_INTERN PetscErrorCode ElementCreate_Hex8(Element el);
PetscErrorCode ElementCreate_Hex8(Element el)
{
  Hex8Options *eo;

  PetscFunctionBeginUser;
  PetscCall(PetscNew(&eo));
  eo->fbar               = 1;
  el->data               = eo;
  el->ops.setfromoptions = ElementSetFromOptions_Hex8;
  el->ops.view           = ElementView_Hex8;
  el->ops.destroy        = ElementDestroy_Hex8;
  el->kernel.name         = "hex8";
  el->kernel.nen          = 8;
  el->kernel.nqp          = HEX8_NQP;
  el->kernel.nstate       = 0;
  el->kernel.nface        = 6;
  el->kernel.face         = hex8_faces;
  el->kernel.ctx          = eo;
  el->kernel.kernel       = Hex8Kernel;
  el->kernel.min_jacobian = Hex8MinJacobian;
  PetscFunctionReturn(0);
}
