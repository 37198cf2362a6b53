/* Element type "hex8_eas": trilinear hexahedron with nine incompatible modes on the deformation
   gradient (enhanced assumed strain at finite strain), condensed at element level by a local
   Newton; see src/element/hex8_eas.c for the formulation. Pure kernels on plain arrays. */
#ifndef ATRITO_ELEMENT_HEX8_EAS_H
#define ATRITO_ELEMENT_HEX8_EAS_H
#include "element.h"
#include "element_hex8.h"

#define HEX8_EAS_NMODE 3  /* bubbles 1 - xi_k^2, k = 1..3 */
#define HEX8_EAS_NALPHA 9 /* one vector per bubble: alpha[3 k + i] */
#define HEX8_EAS_MAXIT 40 /* bound on -fe_eas_max_it */

typedef struct {
  int    max_it; /* local Newton iterations on the enhanced parameters */
  double rtol;   /* converged when |R_alpha|_inf <= rtol * max diag K_aa * h (h = cbrt of the volume) */
} Hex8EASOptions;

/* what the local Newton did in the last evaluation (for the tests) */
typedef struct {
  int    nit;                         /* Newton updates taken */
  double res[HEX8_EAS_MAXIT + 1];     /* |R_alpha|_inf / scale before each update and at the end */
  double alpha[HEX8_EAS_NALPHA];      /* converged enhanced parameters */
} Hex8EASTrace;

/* Element kernel. Inputs: reference coordinates X, displacements u, committed history hn
   (HEX8_NQP x mat->nhist, point-major, then the HEX8_EAS_NALPHA committed enhanced parameters).
   Outputs: the condensed internal force fe[24], the exact condensed tangent ke[24*24] = d fe / d u
   (row-major, may be NULL), the trial history h (same layout, the converged enhanced parameters
   at its end), info (may be NULL) and trace (may be NULL). Returns MAT_OK, MAT_ERR_JACOBIAN, the
   material's error status, or MAT_ERR_RETURNMAP when the local Newton does not converge. */
int hex8_eas_element(const Hex8EASOptions *eo, const MaterialKernel *mat, const double X[8][3], const double u[8][3], const double *hn, double fe[24], double *ke, double *h, ElementInfo *info, Hex8EASTrace *trace);
#endif
