/* Trilinear hexahedron with incompatible modes on the deformation gradient ("hex8_eas"):
   finite-strain enhanced assumed strain element, static condensation by a local Newton, exact
   condensed tangent.

   Formulation (Simo & Armero 1992 / Simo, Armero & Taylor 1993 "H1/ME9", the finite-strain form
   of Wilson-Taylor's incompatible modes used by CalculiX's C3D8I; chosen because its nine modes
   are exactly the quadratic displacement fields that a one-layer hexahedron lacks in bending and
   that make it volumetric-locking free, while the Taylor-Beresford-Wilson mapping below makes it
   pass the patch test on distorted meshes and keeps the element free of extra nodes):

     F(xi) = I + sum_a u_a (x) dN_a/dX + sum_k alpha_k (x) G_k(xi),        a = 1..8, k = 1..3
     G_k(xi) = (j0 / j(xi)) J0^-T dM_k/dxi,   M_k = 1 - xi_k^2,  dM_k/dxi_L = -2 xi_k delta_kL

   with J(xi) = dX/dxi, j = det J, J0 and j0 at the element centre; alpha_k (k = 1..3) are three
   vectors, nine parameters. Since int_V0 G_k dV0 = j0 J0^-T int dM_k/dxi dxi = 0 (exactly under
   the 2x2x2 Gauss rule), a homogeneous F gives R_alpha = 0 at alpha = 0: the patch test passes
   on any hexahedron. The weak form is the displacement one of hex8.c with eleven "nodes" (the
   eight nodes and the three modes), on the reference volume with the Kirchhoff stress tau(F):

     R_ai = sum_qp w j  tau_ij g_aj,     g_aj = D_aK Finv_Kj,    D_a = dN_a/dX (a <= 8), G_k
     K_ai,bm = dR_ai / dd_bm = sum_qp w j [ g_aj Tau_ij,mL D_bL - tau_ij g_bj g_am ]

   (Tau = dtau/dF from the material), giving the 33 x 33 blocks K_uu, K_ua, K_au, K_aa.
   Static condensation: at every evaluation the enhanced residual R_alpha(u, alpha) = 0 is solved
   by Newton (K_aa dalpha = -R_alpha, with step halving when the residual grows or the material
   fails), starting from the committed alpha (the element state, nstate = 9, committed with the
   step and stored in the checkpoint). At the converged alpha

     f = R_u - K_ua K_aa^-1 R_alpha,    K = K_uu - K_ua K_aa^-1 K_au

   (the first term's correction is the linearised remainder of the local solve: it makes f
   accurate to second order in the local residual, so that K is its exact derivative to round-off).
   The trial alpha (alpha - K_aa^-1 R_alpha) goes to the trial history h, never to hn.

   Known limit: like every enhanced element at finite strain, the formulation can show spurious
   hourglass instabilities in strong compression (Wriggers & Reese 1996); see doc/elements.md for
   what the compression tests show. */
#include <float.h>
#include <math.h>
#include <string.h>

#include "element_hex8_eas.h"
#include "element_impl.h"
#include "options.h"
#include "tensor.h"

#define NF 11              /* eight nodes and three modes */
#define ND (3 * NF)        /* 33 unknowns of the uncondensed element */
#define NA HEX8_EAS_NALPHA /* 9 */

typedef struct {
  double D[HEX8_NQP][NF][3]; /* reference gradients dN_a/dX and G_k at the Gauss points */
  double w[HEX8_NQP];        /* det J (unit Gauss weights) */
  double len;                /* cube root of the volume */
  const double (*X)[3];      /* the reference nodal coordinates */
} EasGeom;

static int eas_geometry(const double X[8][3], EasGeom *g)
{
  static const double centre[3] = {0, 0, 0};
  double              dN[8][3], J0[9] = {0}, J0i[9], vol = 0;

  hex8_shape(centre, NULL, dN);
  for (int a = 0; a < 8; a++)
    for (int i = 0; i < 3; i++)
      for (int k = 0; k < 3; k++) J0[3 * i + k] += X[a][i] * dN[a][k];
  const double j0 = t3_inv(J0, J0i); /* J0i[3 k + K] = dxi_k / dX_K at the centre */
  if (!(j0 > 0)) return MAT_ERR_JACOBIAN;
  for (int q = 0; q < HEX8_NQP; q++) {
    double       dNdX[8][3];
    const double j = hex8_gradient(X, hex8_gauss[q], dNdX);
    if (!(j > 0)) return MAT_ERR_JACOBIAN;
    memcpy(g->D[q], dNdX, sizeof(dNdX));
    for (int k = 0; k < HEX8_EAS_NMODE; k++) {
      const double c = (j0 / j) * (-2.0 * hex8_gauss[q][k]);
      for (int K = 0; K < 3; K++) g->D[q][8 + k][K] = c * J0i[3 * k + K];
    }
    g->w[q] = j;
    vol += j;
  }
  g->len = cbrt(vol);
  g->X   = X;
  return MAT_OK;
}

/* Uncondensed residual f[33] and tangent K[33*33] (row-major; NULL: not wanted) at the unknowns
   d = (u, alpha); trial material history into h; element info into info (not NULL). */
static int eas_eval(const MaterialKernel *mat, const EasGeom *g, const double d[ND], const double *hn, double f[ND], double *K, double *h, ElementInfo *info)
{
  const int nh       = mat->nhist;
  int       nplastic = 0;

  memset(f, 0, ND * sizeof(double));
  if (K) memset(K, 0, ND * ND * sizeof(double));
  memset(info, 0, sizeof(*info));
  for (int q = 0; q < HEX8_NQP; q++) {
    const double(*D)[3] = g->D[q];
    double F[9], Finv[9], gs[NF][3], tau[9], dtau[81];
    for (int i = 0; i < 3; i++)
      for (int L = 0; L < 3; L++) {
        double s = (i == L) ? 1.0 : 0.0;
        for (int a = 0; a < NF; a++) s += d[3 * a + i] * D[a][L];
        F[3 * i + L] = s;
      }
    const double J = t3_inv(F, Finv);
    if (!(J > 0)) return MAT_ERR_JACOBIAN;
    for (int a = 0; a < NF; a++)
      for (int j = 0; j < 3; j++) gs[a][j] = D[a][0] * Finv[j] + D[a][1] * Finv[3 + j] + D[a][2] * Finv[6 + j];
    int plastic = 0;
    if (mat->set_point) { /* a material that wants the point (a user material's NPT, COORDS, CELENT) */
      double xq[3];
      hex8_gauss_position(g->X, (const double(*)[3])d, q, xq);
      mat->set_point(mat->ctx, -1, q + 1, xq, g->len);
    }
    const int st = mat->update(mat->ctx, F, hn + (size_t)q * nh, tau, K ? dtau : NULL, h + (size_t)q * nh, &plastic);
    if (st != MAT_OK) return st;
    nplastic += plastic;
    const double w = g->w[q];
    for (int a = 0; a < NF; a++)
      for (int i = 0; i < 3; i++) f[3 * a + i] += w * (tau[3 * i] * gs[a][0] + tau[3 * i + 1] * gs[a][1] + tau[3 * i + 2] * gs[a][2]);

    {
      const double s[6] = {tau[0] / J, tau[4] / J, tau[8] / J, tau[1] / J, tau[5] / J, tau[2] / J};
      const double p = (s[0] + s[1] + s[2]) / 3.0, d0 = s[0] - p, d1 = s[1] - p, d2 = s[2] - p;
      info->mises += sqrt(1.5 * (d0 * d0 + d1 * d1 + d2 * d2 + 2 * (s[3] * s[3] + s[4] * s[4] + s[5] * s[5]))) / HEX8_NQP;
      info->ep += mat->plastic_strain(mat->ctx, h + (size_t)q * nh) / HEX8_NQP;
      for (int k = 0; k < 6; k++) info->sigma[k] += s[k] / HEX8_NQP;
    }
    if (!K) continue;
    /* K_ai,bm += w sum_j g_aj Hm[ij][bm]: material Tau_ij,mL D_bL, geometric -tau_ij g_bj (m = n) */
    double Hm[9][ND];
    for (int ij = 0; ij < 9; ij++) {
      const double *T = dtau + 9 * ij;
      for (int b = 0; b < NF; b++)
        for (int m = 0; m < 3; m++) Hm[ij][3 * b + m] = T[3 * m] * D[b][0] + T[3 * m + 1] * D[b][1] + T[3 * m + 2] * D[b][2];
    }
    for (int b = 0; b < NF; b++)
      for (int i = 0; i < 3; i++) {
        const double sb = tau[3 * i] * gs[b][0] + tau[3 * i + 1] * gs[b][1] + tau[3 * i + 2] * gs[b][2];
        for (int n = 0; n < 3; n++) Hm[3 * i + n][3 * b + n] -= sb;
      }
    for (int a = 0; a < NF; a++) {
      const double ga0 = w * gs[a][0], ga1 = w * gs[a][1], ga2 = w * gs[a][2];
      for (int i = 0; i < 3; i++) {
        double       *row = K + (3 * a + i) * ND;
        const double *H0 = Hm[3 * i], *H1 = Hm[3 * i + 1], *H2 = Hm[3 * i + 2];
        for (int bm = 0; bm < ND; bm++) row[bm] += ga0 * H0[bm] + ga1 * H1[bm] + ga2 * H2[bm];
      }
    }
  }
  info->nplastic = nplastic;
  return MAT_OK;
}

static double res_alpha(const double f[ND])
{
  double r = 0;
  for (int k = 24; k < ND; k++) r = fmax(r, fabs(f[k]));
  return r;
}

int hex8_eas_element(const Hex8EASOptions *eo, const MaterialKernel *mat, const double X[8][3], const double u[8][3], const double *hn, double fe[24], double *ke, double *h, ElementInfo *info, Hex8EASTrace *trace)
{
  const size_t na = (size_t)HEX8_NQP * mat->nhist; /* material history doubles */
  EasGeom      g;
  double       d[ND], dt[ND], fA[ND], fB[ND], KA[ND * ND], KB[ND * ND], hs[na + 1];
  double      *fc = fA, *Kc = KA, *ft = fB, *Kt = KB, *hc = h, *ht = hs;
  ElementInfo  ic, it;
  int          st, nit = 0;

  memset(fe, 0, 24 * sizeof(double));
  if (ke) memset(ke, 0, 24 * 24 * sizeof(double));
  if (info) memset(info, 0, sizeof(*info));
  if (trace) memset(trace, 0, sizeof(*trace));
  if ((st = eas_geometry(X, &g)) != MAT_OK) return st;
  for (int a = 0; a < 8; a++)
    for (int i = 0; i < 3; i++) d[3 * a + i] = u[a][i];
  memcpy(d + 24, hn + na, NA * sizeof(double));

  st = eas_eval(mat, &g, d, hn, fc, Kc, hc, &ic);
  if (st != MAT_OK) {
    /* the committed alpha may not fit this iterate at all: start from alpha = 0 */
    memset(d + 24, 0, NA * sizeof(double));
    st = eas_eval(mat, &g, d, hn, fc, Kc, hc, &ic);
    if (st != MAT_OK) return st;
  }
  /* scale of R_alpha: stiffness of the modes times the element size */
  double scale = 0;
  for (int k = 24; k < ND; k++) scale = fmax(scale, fabs(Kc[k * ND + k]));
  scale *= g.len;
  if (!(scale > 0) || !isfinite(scale)) return MAT_ERR_RETURNMAP;
  double r = res_alpha(fc) / scale;
  if (trace) trace->res[0] = r;

  while (r > eo->rtol) {
    double A[NA * NA], da[NA];
    if (nit >= eo->max_it) return MAT_ERR_RETURNMAP;
    for (int k = 0; k < NA; k++) {
      for (int l = 0; l < NA; l++) A[k * NA + l] = Kc[(24 + k) * ND + 24 + l];
      da[k] = -fc[24 + k];
    }
    if (dense_solve(NA, A, 1, da)) return MAT_ERR_RETURNMAP;
    double step = 1, rt = INFINITY;
    int    accepted = 0;
    for (int ls = 0; ls < 12 && !accepted; ls++, step *= 0.5) {
      memcpy(dt, d, 24 * sizeof(double));
      for (int k = 0; k < NA; k++) dt[24 + k] = d[24 + k] + step * da[k];
      st = eas_eval(mat, &g, dt, hn, ft, Kt, ht, &it);
      if (st != MAT_OK) continue;
      rt = res_alpha(ft) / scale;
      accepted = rt < r || rt <= eo->rtol;
    }
    if (!accepted) {
      /* no decrease: round-off level (then the linearised correction below finishes the job) */
      if (r <= 1e3 * eo->rtol) break;
      return st != MAT_OK ? st : MAT_ERR_RETURNMAP;
    }
    double *t;
    memcpy(d, dt, sizeof(d));
    t = fc, fc = ft, ft = t;
    t = Kc, Kc = Kt, Kt = t;
    t = hc, hc = ht, ht = t;
    ic = it;
    r  = rt;
    nit++;
    if (trace) trace->res[nit] = r;
  }
  if (hc != h) memcpy(h, hc, na * sizeof(double));
  if (trace) trace->nit = nit;

  /* static condensation: [K_aa] [Y | y] = [K_au | R_alpha] */
  {
    double A[NA * NA], B[NA * 25];
    for (int k = 0; k < NA; k++) {
      for (int l = 0; l < NA; l++) A[k * NA + l] = Kc[(24 + k) * ND + 24 + l];
      for (int c = 0; c < 24; c++) B[k * 25 + c] = Kc[(24 + k) * ND + c];
      B[k * 25 + 24] = fc[24 + k];
    }
    if (dense_solve(NA, A, 25, B)) return MAT_ERR_RETURNMAP;
    for (int r_ = 0; r_ < 24; r_++) {
      const double *Kua = Kc + r_ * ND + 24;
      double        s   = fc[r_];
      for (int k = 0; k < NA; k++) s -= Kua[k] * B[k * 25 + 24];
      fe[r_] = s;
      if (ke)
        for (int c = 0; c < 24; c++) {
          double v = Kc[r_ * ND + c];
          for (int k = 0; k < NA; k++) v -= Kua[k] * B[k * 25 + c];
          ke[r_ * 24 + c] = v;
        }
    }
    for (int k = 0; k < NA; k++) h[na + k] = d[24 + k] - B[k * 25 + 24];
    if (trace)
      for (int k = 0; k < NA; k++) trace->alpha[k] = h[na + k];
  }
  if (info) {
    double dNdX0[8][3];
    static const double centre[3] = {0, 0, 0};
    *info = ic;
    hex8_gradient(X, centre, dNdX0);
    hex8_defgrad(u, dNdX0, info->F0); /* the modes vanish at the centre */
  }
  return MAT_OK;
}

/* ------------------------------------------------------------------------------------------ */
/* the element type "hex8_eas"                                                                 */
/* ------------------------------------------------------------------------------------------ */
static int Hex8EASKernel(const void *ctx, const MaterialKernel *mat, const double *X, const double *u, const double *hn, double *fe, double *ke, double *h, ElementInfo *info)
{
  return hex8_eas_element((const Hex8EASOptions *)ctx, mat, (const double(*)[3])X, (const double(*)[3])u, hn, fe, ke, h, info, NULL);
}

static double Hex8EASMinJacobian(const double *X)
{
  return hex8_min_jacobian((const double(*)[3])X);
}

static PetscErrorCode ElementSetFromOptions_Hex8EAS(Element el)
{
  Hex8EASOptions *eo = (Hex8EASOptions *)el->data;
  PetscInt        it = eo->max_it;
  PetscReal       rt = eo->rtol;

  PetscFunctionBeginUser;
  PetscOptionsBegin(el->comm, "fe_", "Element hex8_eas: hexahedron with nine incompatible modes", "Element");
  PetscCall(PetscOptionsInt("-eas_max_it", "Local Newton iterations on the enhanced parameters", NULL, it, &it, NULL));
  PetscCall(PetscOptionsReal("-eas_rtol", "Local Newton tolerance: |R_alpha| / (stiffness of the modes x element size)", NULL, rt, &rt, NULL));
  PetscOptionsEnd();
  PetscCheck(it >= 1 && it <= HEX8_EAS_MAXIT, el->comm, PETSC_ERR_USER_INPUT, "-fe_eas_max_it %" PetscInt_FMT " must be in 1..%d", it, HEX8_EAS_MAXIT);
  PetscCheck(rt > 0 && rt < 1e-3, el->comm, PETSC_ERR_USER_INPUT, "-fe_eas_rtol %g must be in (0, 1e-3)", (double)rt);
  eo->max_it = (int)it;
  eo->rtol   = rt;
  PetscFunctionReturn(0);
}

static PetscErrorCode ElementView_Hex8EAS(Element el, PetscViewer v)
{
  const Hex8EASOptions *eo = (const Hex8EASOptions *)el->data;

  PetscFunctionBeginUser;
  PetscCall(PetscViewerASCIIPrintf(v, "8 nodes, 2x2x2 Gauss points, 9 incompatible modes on F condensed by a local Newton (at most %d iterations, rtol %g)\n", eo->max_it, eo->rtol));
  PetscFunctionReturn(0);
}

static PetscErrorCode ElementDestroy_Hex8EAS(Element el)
{
  PetscFunctionBeginUser;
  PetscCall(PetscFree(el->data));
  PetscFunctionReturn(0);
}

PETSC_INTERN PetscErrorCode ElementCreate_Hex8EAS(Element el);
PetscErrorCode ElementCreate_Hex8EAS(Element el)
{
  Hex8EASOptions *eo;

  PetscFunctionBeginUser;
  PetscCall(PetscNew(&eo));
  eo->max_it              = 20;
  eo->rtol                = 1e-10;
  el->data                = eo;
  el->ops.setfromoptions  = ElementSetFromOptions_Hex8EAS;
  el->ops.view            = ElementView_Hex8EAS;
  el->ops.destroy         = ElementDestroy_Hex8EAS;
  el->kernel.name         = "hex8_eas";
  el->kernel.nen          = 8;
  el->kernel.nqp          = HEX8_NQP;
  el->kernel.nstate       = HEX8_EAS_NALPHA;
  el->kernel.nface        = 6;
  el->kernel.face         = hex8_faces;
  el->kernel.ctx          = eo;
  el->kernel.kernel       = Hex8EASKernel;
  el->kernel.min_jacobian = Hex8EASMinJacobian;
  PetscFunctionReturn(0);
}
