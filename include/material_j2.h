/* Material type "j2": finite-strain J2 elasto-plasticity with logarithmic elastic strains
   (multiplicative split F = Fe Fp, Hencky elastic law, radial return in principal log-strain
   space, exponential-map flow update), isotropic hardening (linear or Swift).
   Pure kernels on plain arrays: no MPI, no PETSc objects. */
#ifndef ATRITO_MATERIAL_J2_H
#define ATRITO_MATERIAL_J2_H
#include "material.h"

typedef enum { HARDENING_LINEAR = 0, HARDENING_SWIFT = 1 } HardeningLaw;

typedef struct {
  double       E, nu;            /* Young's modulus, Poisson's ratio */
  double       K, G;             /* bulk and shear moduli (set by J2ParamsSetup) */
  HardeningLaw law;
  double       sy0, H;           /* linear:  sigma_y = sy0 + H * ep               */
  double       swK, sweps0, swn; /* Swift:   sigma_y = swK * (sweps0 + ep)^swn    */
  double       rtol;             /* relative tolerance of the scalar return map     */
  int          maxit;            /* its iteration limit                             */
} J2Params;

/* History per quadrature point: inverse plastic right Cauchy-Green tensor
   Cp^{-1} (xx, yy, zz, xy, yz, xz) and the equivalent plastic strain. */
#define J2_NHIST 7
#define J2_HIST_EP 6

/* derive K, G; fill default tolerances if zero. Returns 0, or nonzero for invalid E/nu. */
int    J2ParamsSetup(J2Params *mp);
/* sigma_y(ep) and its slope d sigma_y / d ep */
double J2YieldStress(const J2Params *mp, double ep, double *dsy);
/* Cp^{-1} = I, ep = 0 */
void   J2HistoryInit(double h[J2_NHIST]);
/* Given the deformation gradient F (row-major, F[3*i+J]) and the committed history hn,
   compute the Kirchhoff stress tau (full symmetric 3x3, row-major), the updated (trial)
   history h, whether the step is plastic, and -- when dtau is not NULL -- the exact
   derivative dtau[(3*i+j)*9 + 3*k+L] = d tau_ij / d F_kL (consistent with the return map).
   Returns MAT_OK or an error status; never aborts. */
int    J2Update(const J2Params *mp, const double F[9], const double hn[J2_NHIST], double tau[9], double *dtau, double h[J2_NHIST], int *plastic);
/* the MaterialKernel of the J2 model on the parameters mp (kept by pointer: mp must outlive k);
   what the "j2" type hands out, usable without a Material object */
void   J2KernelInit(const J2Params *mp, MaterialKernel *k);

/* Shared with the types built on J2's elasticity and hardening (hill48): the defaults of the
   options (Swift aluminium of the benchmark), the options (-material_E, _nu, _hardening, _yield,
   _hardening_modulus, _swift_K, _swift_eps0, _swift_n, _return_rtol, _return_maxit) read and
   validated inside the caller's PetscOptionsBegin block (its prefix: "material_", or a body's
   "body_<b>_material_"), and the view of the elasticity and hardening. */
void           J2ParamsDefaults(J2Params *mp);
PetscErrorCode J2ParamsSetFromOptions(PetscOptionItems *PetscOptionsObject, MPI_Comm comm, J2Params *mp);
PetscErrorCode J2ParamsView(const J2Params *mp, PetscViewer v);
#endif
