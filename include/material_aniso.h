/* The kinematics shared by the orthotropic log-strain materials (hill48, yld91): the polar
   decomposition, the rotated trial elastic log strain in the sheet's orthotropy frame, the flow
   update by the exponential map and the chain from the return map's algorithmic modulus to the
   exact dtau/dF (src/material/aniso.c). A model supplies its return map in stress space.
   Pure kernels on plain arrays: no MPI, no PETSc objects. */
#ifndef ATRITO_MATERIAL_ANISO_H
#define ATRITO_MATERIAL_ANISO_H
#include "material_j2.h"

/* The model's return map, in Mandel notation (11, 22, 33, 23, 31, 12; shear entries times
   sqrt 2) in the orthotropy frame. Given the isotropic elasticity D (6x6), the trial elastic
   log strain etr, the trial stress str = D etr and the committed equivalent plastic strain ep_n:
   the stress s, the elastic log strain ee, the new ep, whether the point flows (*plastic) and,
   when Dalg is not NULL, the algorithmic modulus ds/de_tr. Elastic: s = str, ee = etr,
   ep = ep_n, Dalg = D. Returns 0, or nonzero where the return map fails. */
typedef int (*AnisoReturnFn)(const void *ctx, const double D[36], const double etr[6], const double str[6], double ep_n, double s[6], double ee[6], double *ep, double *Dalg, int *plastic);

/* the orthotropy frame A (row-major; columns rd, td = nd x rd, nd, unit) from the rolling
   direction rd and the sheet normal nd (rd made exactly orthogonal to nd when within 1e-6 of
   it). Returns 0, or nonzero for a zero or non-orthogonal pair. */
int  AnisoFrame(const double rd[3], const double nd[3], double A[9]);
/* the update of MaterialKernel (see material.h) for the model's return map ret on ctx, with the
   elasticity of base and the orthotropy frame A: tau, the history (J2's layout: Cp^{-1}, ep)
   and, when dtau is not NULL, the exact dtau/dF. Returns MAT_OK or a MAT_ERR_ status. */
int  AnisoLogUpdate(const J2Params *base, const double A[9], AnisoReturnFn ret, const void *ctx, const double F[9], const double hn[J2_NHIST], double tau[9], double *dtau, double h[J2_NHIST],
                    int *plastic);
/* Mandel helpers: symmetric 3x3 <-> vector, and T, the Mandel form of S -> M S M^T */
void AnisoToMandel(const double T[9], double v[6]);
void AnisoFromMandel(const double v[6], double T[9]);
void AnisoMandelRotation(const double M[9], double T[36]);
#endif
