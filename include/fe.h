/* Trilinear 8-node hexahedron: shape functions, 2x2x2 Gauss rule, finite-strain element
   residual and exact tangent with the F-bar treatment of the volumetric part.
   Pure kernels on plain arrays. */
#ifndef ATRITO_FE_H
#define ATRITO_FE_H
#include "material.h"

#define HEX8_NQP 8

/* Natural coordinates of the nodes in the standard order (0-3 at zeta = -1 counter-clockwise
   seen from +zeta, 4-7 above them). */
extern const double hex8_nodes[8][3];
/* Gauss points (+-1/sqrt 3), unit weights */
extern const double hex8_gauss[HEX8_NQP][3];

/* N and dN/dxi at xi */
void hex8_shape(const double xi[3], double N[8], double dN[8][3]);
/* dN/dX and det(dX/dxi) at xi for reference nodal coordinates X; returns det J */
double hex8_gradient(const double X[8][3], const double xi[3], double dNdX[8][3]);
/* F = I + sum_a u_a (x) dN_a/dX */
void hex8_defgrad(const double u[8][3], const double dNdX[8][3], double F[9]);

typedef struct {
  int    fbar;   /* 1: F-bar (centroid dilatation), 0: standard displacement element */
} ElementOptions;

typedef struct {
  double ep;      /* mean equivalent plastic strain over the Gauss points     */
  double mises;   /* mean von Mises Cauchy stress over the Gauss points       */
  double sigma[6];/* mean Cauchy stress xx yy zz xy yz xz                      */
  double F0[9];   /* deformation gradient at the centroid                      */
  int    nplastic;/* Gauss points that yielded in this evaluation              */
} ElementInfo;

/* Element kernel. Inputs: reference coordinates X, displacements u, committed history hn
   (8 x MAT_NHIST). Outputs: internal force fe[24] (node-major: fe[3a+i]), the exact tangent
   ke[24*24] = d fe / d u (row-major, may be NULL), the trial history h, and info (may be NULL).
   Returns MAT_OK, MAT_ERR_JACOBIAN (reference or current Jacobian not positive) or
   MAT_ERR_RETURNMAP. */
int hex8_element(const MaterialParams *mp, const ElementOptions *eo, const double X[8][3], const double u[8][3], const double hn[][MAT_NHIST], double fe[24], double *ke, double h[][MAT_NHIST], ElementInfo *info);

/* Smallest det(dX/dxi) over the 8 Gauss points and the 8 corners (element validity check) */
double hex8_min_jacobian(const double X[8][3]);
#endif
