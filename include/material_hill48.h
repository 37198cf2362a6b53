/* Material type "hill48": finite-strain Hill 1948 anisotropic elasto-plasticity with logarithmic
   elastic strains (multiplicative split, Hencky law, return map on the elastic log strain in the
   orthotropy frame of the sheet, exponential-map flow update), isotropic hardening of J2
   (linear or Swift). See src/material/hill48.c and doc/materials.md.
   Pure kernels on plain arrays: no MPI, no PETSc objects. */
#ifndef ATRITO_MATERIAL_HILL48_H
#define ATRITO_MATERIAL_HILL48_H
#include "material_j2.h"

typedef struct {
  J2Params base;                    /* elasticity, hardening law, return-map controls (J2's) */
  int      from_r;                  /* 1: F..N from the r-values; 0: given directly         */
  double   r0, r45, r90;            /* Lankford coefficients at 0, 45, 90 deg to rolling    */
  double   F, G, H, L, M, N;        /* Hill 48 coefficients (von Mises: 1/2 x 3, 3/2 x 3)   */
  double   rd[3], nd[3];            /* rolling direction and sheet normal (as given)        */
  double   A[9];                    /* set by Hill48ParamsSetup: orthotropy frame, columns
                                       rd, td = nd x rd, nd (unit, orthogonal)             */
  double   P[36];                   /* Hill matrix in Mandel notation in that frame,
                                       components (11, 22, 33, 23, 31, 12)                  */
  double   p[6], Phi[36];           /* P = Phi diag(p) Phi^T (set by Hill48ParamsSetup)     */
} HillParams;

/* History per quadrature point: as J2's (Cp^{-1}: xx, yy, zz, xy, yz, xz; equivalent plastic strain) */
#define HILL48_NHIST J2_NHIST
#define HILL48_HIST_EP J2_HIST_EP

/* status of Hill48ParamsSetup */
#define HILL48_OK 0
#define HILL48_ERR_ELASTIC 1 /* E, nu (J2ParamsSetup) */
#define HILL48_ERR_R 2       /* an r-value not positive */
#define HILL48_ERR_AXES 3    /* zero or non-orthogonal axes */
#define HILL48_ERR_CONVEX 4  /* F..N do not give a convex, bounded yield surface */

/* the plane-stress r-value relations (yield stress sigma_y = the rolling-direction one, G + H = 1):
   H = r0/(1+r0), G = 1/(1+r0), F = r0/(r90 (1+r0)), N = (r0+r90)(1+2 r45)/(2 r90 (1+r0)), L = M = 3/2 */
void Hill48FromR(double r0, double r45, double r90, double *F, double *G, double *H, double *L, double *M, double *N);
/* base setup, F..N from the r-values when from_r, the frame A (rd made exactly orthogonal to nd
   when within 1e-6 of it) and P. Returns HILL48_OK or a HILL48_ERR_ code. */
int  Hill48ParamsSetup(HillParams *hp);
/* the update of MaterialKernel (see material.h), exact dtau/dF */
int  Hill48Update(const HillParams *hp, const double F[9], const double hn[HILL48_NHIST], double tau[9], double *dtau, double h[HILL48_NHIST], int *plastic);
/* the MaterialKernel on hp (kept by pointer) */
void Hill48KernelInit(const HillParams *hp, MaterialKernel *k);
#endif
