/* Material type "yld91": finite-strain anisotropic elasto-plasticity with the six-component yield
   function of Barlat et al. 1991 (a linear transformation of the stress and Hosford's
   non-quadratic isotropic function of its principal values, exponent m), logarithmic elastic
   strains in the sheet's orthotropy frame (the kinematics of hill48: include/material_aniso.h),
   isotropic hardening of J2. m = 2 is Hill 1948; m = 8 the exponent of face-centred cubic
   metals (aluminium), 6 of body-centred cubic ones. See src/material/yld91.c and
   doc/materials.md. Pure kernels on plain arrays: no MPI, no PETSc objects. */
#ifndef ATRITO_MATERIAL_YLD91_H
#define ATRITO_MATERIAL_YLD91_H
#include "material_j2.h"

typedef struct {
  J2Params base;         /* elasticity, hardening law, return-map controls (J2's)             */
  int      m;            /* exponent: an even integer >= 2                                     */
  int      from_r;       /* 1: c1..c6 fitted to the r-values; 0: given                        */
  double   r0, r45, r90; /* Lankford coefficients at 0, 45, 90 deg to rolling                  */
  double   c[6];         /* c1..c6 (set by Yld91ParamsSetup when from_r)                       */
  double   rd[3], nd[3]; /* rolling direction and sheet normal (as given)                     */
  double   A[9];         /* set by Yld91ParamsSetup: orthotropy frame, columns rd, td, nd      */
  double   L[36];        /* the transformation S~ = L s in Mandel notation in that frame       */
} Yld91Params;

#define YLD91_NHIST J2_NHIST
#define YLD91_HIST_EP J2_HIST_EP

/* status of Yld91ParamsSetup */
#define YLD91_OK 0
#define YLD91_ERR_ELASTIC 1  /* E, nu (J2ParamsSetup) */
#define YLD91_ERR_R 2        /* an r-value not positive */
#define YLD91_ERR_AXES 3     /* zero or non-orthogonal axes */
#define YLD91_ERR_EXPONENT 4 /* m not an even integer in [2, 32] */
#define YLD91_ERR_FIT 5      /* the r-values could not be fitted */
#define YLD91_ERR_COEF 6     /* c1..c6 not finite, or a degenerate transformation */

/* base setup, the frame, c1..c6 from the r-values when from_r (c3 = 1, c1, c2, c6 by Newton's
   method on the three r-values, then all of c1, c2, c3, c6 scaled so that the effective stress of
   uniaxial tension along the rolling direction is that tension; c4 = c5 = 1: the out-of-plane
   shears as the isotropic function's), and L. Returns YLD91_OK or a YLD91_ERR_ code. */
int    Yld91ParamsSetup(Yld91Params *yp);
/* the effective stress sigma_e(s) of the Mandel stress s (orthotropy frame), with its gradient
   n = d sigma_e / ds and Hessian H (6x6) where not NULL (0 where sigma_e = 0) */
double Yld91Effective(const Yld91Params *yp, const double s[6], double n[6], double H[36]);
/* the plane-stress r-value at angle th (radians) to the rolling direction: the flow rule's ratio
   of width to thickness strain rates in uniaxial tension */
double Yld91RValue(const Yld91Params *yp, double th);
/* the update of MaterialKernel (see material.h), exact dtau/dF */
int    Yld91Update(const Yld91Params *yp, const double F[9], const double hn[YLD91_NHIST], double tau[9], double *dtau, double h[YLD91_NHIST], int *plastic);
/* the MaterialKernel on yp (kept by pointer) */
void   Yld91KernelInit(const Yld91Params *yp, MaterialKernel *k);
#endif
