/* Element type "hex8": trilinear 8-node hexahedron, 2x2x2 Gauss rule, finite-strain element
   residual and exact tangent, optionally with the F-bar treatment of the volumetric part.
   Pure kernels on plain arrays. */
#ifndef ATRITO_ELEMENT_HEX8_H
#define ATRITO_ELEMENT_HEX8_H
#include "element.h"

#define HEX8_NQP 8

/* Natural coordinates of the nodes in the standard order (0-3 at zeta = -1 counter-clockwise
   seen from +zeta, 4-7 above them). */
extern const double hex8_nodes[8][3];
/* Gauss points (+-1/sqrt 3), unit weights */
extern const double hex8_gauss[HEX8_NQP][3];
/* faces zeta=-1, zeta=+1, eta=-1, xi=+1, eta=+1, xi=-1: corner nodes counter-clockwise seen from outside */
extern const int hex8_faces[6][4];

/* N and dN/dxi at xi (either may be NULL) */
void   hex8_shape(const double xi[3], double N[8], double dN[8][3]);
/* dN/dX and det(dX/dxi) at xi for reference nodal coordinates X; returns det J (dNdX is set only when det J > 0) */
double hex8_gradient(const double X[8][3], const double xi[3], double dNdX[8][3]);
/* F = I + sum_a u_a (x) dN_a/dX */
void   hex8_defgrad(const double u[8][3], const double dNdX[8][3], double F[9]);
/* the current position sum_a N_a(xi_q) (X_a + u_a) of Gauss point q */
void   hex8_gauss_position(const double X[8][3], const double u[8][3], int q, double x[3]);
/* Smallest det(dX/dxi) over the 8 Gauss points and the 8 corners (element validity check);
   NaN when one of them is NaN */
double hex8_min_jacobian(const double X[8][3]);

typedef struct {
  int fbar; /* 1: F-bar (centroid dilatation), 0: standard displacement element */
} Hex8Options;

/* Element kernel. Inputs: reference coordinates X, displacements u, committed history hn
   (HEX8_NQP x mat->nhist, point-major). Outputs: internal force fe[24] (node-major: fe[3a+i]),
   the exact tangent ke[24*24] = d fe / d u (row-major, may be NULL), the trial history h (same
   layout as hn), and info (may be NULL). Returns MAT_OK, MAT_ERR_JACOBIAN (reference or current
   Jacobian not positive) or the material's error status. */
int hex8_element(const Hex8Options *eo, const MaterialKernel *mat, const double X[8][3], const double u[8][3], const double *hn, double fe[24], double *ke, double *h, ElementInfo *info);
#endif
