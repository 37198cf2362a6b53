/* Finite-strain J2 elasto-plasticity with logarithmic elastic strains
   (multiplicative split F = Fe Fp, Hencky elastic law, radial return in principal
   log-strain space, exponential-map flow update), isotropic hardening.
   Pure kernels on plain arrays: no MPI, no PETSc objects. */
#ifndef ATRITO_MATERIAL_H
#define ATRITO_MATERIAL_H

typedef enum { HARDENING_LINEAR = 0, HARDENING_SWIFT = 1 } HardeningLaw;

typedef struct {
  double       E, nu;           /* Young's modulus, Poisson's ratio */
  double       K, G;            /* bulk and shear moduli (set by MaterialParamsSetup) */
  HardeningLaw law;
  double       sy0, H;          /* linear:  sigma_y = sy0 + H * ep               */
  double       swK, sweps0, swn;/* Swift:   sigma_y = swK * (sweps0 + ep)^swn    */
  double       rtol;            /* relative tolerance of the scalar return map     */
  int          maxit;           /* its iteration limit                             */
} MaterialParams;

/* History per quadrature point: inverse plastic right Cauchy-Green tensor
   Cp^{-1} (xx, yy, zz, xy, yz, xz) and the equivalent plastic strain. */
#define MAT_NHIST 7
#define MAT_HIST_EP 6

/* status codes of MaterialUpdate */
#define MAT_OK 0
#define MAT_ERR_JACOBIAN 1   /* det F <= 0 */
#define MAT_ERR_RETURNMAP 2  /* the scalar return map did not converge */

/* derive K, G; fill default tolerances if zero. Returns 0, or nonzero for invalid E/nu. */
int    MaterialParamsSetup(MaterialParams *mp);
/* sigma_y(ep) and its slope d sigma_y / d ep */
double MaterialYieldStress(const MaterialParams *mp, double ep, double *dsy);
/* Cp^{-1} = I, ep = 0 */
void   MaterialHistoryInit(double h[MAT_NHIST]);
/* Given the deformation gradient F (row-major, F[3*i+J]) and the committed history hn,
   compute the Kirchhoff stress tau (full symmetric 3x3, row-major), the updated (trial)
   history h, whether the step is plastic, and -- when dtau is not NULL -- the exact
   derivative dtau[(3*i+j)*9 + 3*k+L] = d tau_ij / d F_kL (consistent with the return map).
   Returns MAT_OK or an error status; never aborts. */
int    MaterialUpdate(const MaterialParams *mp, const double F[9], const double hn[MAT_NHIST],
                      double tau[9], double *dtau, double h[MAT_NHIST], int *plastic);

#endif
