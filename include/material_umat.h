/* Material type "umat": an Abaqus/Standard user material (SUBROUTINE UMAT), loaded at run time
   from a shared library, called with Abaqus's finite-strain (NLGEOM) conventions for solid
   elements; see src/material/umat.c and doc/umat.md for the conventions and the conversion of
   its stress and DDSDDE to the Kirchhoff stress and d tau/dF of this code.
   Pure kernels on plain arrays: no MPI, no PETSc objects. */
#ifndef ATRITO_MATERIAL_UMAT_H
#define ATRITO_MATERIAL_UMAT_H
#include <stddef.h>

#include "material.h"

/* SUBROUTINE UMAT(STRESS, STATEV, DDSDDE, SSE, SPD, SCD, RPL, DDSDDT, DRPLDE, DRPLDT, STRAN,
   DSTRAN, TIME, DTIME, TEMP, DTEMP, PREDEF, DPRED, CMNAME, NDI, NSHR, NTENS, NSTATV, PROPS,
   NPROPS, COORDS, DROT, PNEWDT, CELENT, DFGRD0, DFGRD1, NOEL, NPT, LAYER, KSPT, KSTEP, KINC)
   as gfortran calls it: every argument by reference, default INTEGER = int, DOUBLE PRECISION =
   double, arrays column-major, and the hidden length of CHARACTER*80 CMNAME at the end. */
typedef void (*UmatFunction)(double *stress, double *statev, double *ddsdde, double *sse, double *spd, double *scd, double *rpl, double *ddsddt, double *drplde, double *drpldt, const double *stran, const double *dstran, const double *time, const double *dtime, const double *temp, const double *dtemp, const double *predef, const double *dpred, const char *cmname, const int *ndi, const int *nshr, const int *ntens, const int *nstatv, const double *props, const int *nprops, const double *coords, const double *drot, double *pnewdt, const double *celent, const double *dfgrd0, const double *dfgrd1, const int *noel, const int *npt, const int *layer, const int *kspt, const int *kstep, const int *kinc, size_t cmname_len);

#define UMAT_MAXPROPS 256

typedef struct {
  UmatFunction fn;                    /* the subroutine */
  int          nstatev;               /* NSTATV */
  int          nprops;                /* NPROPS */
  double       props[UMAT_MAXPROPS];  /* PROPS */
  int          ep_statev;             /* 1-based STATEV index of an equivalent plastic strain (output, plastic flag); 0: none */
  char         cmname[80];            /* CMNAME, blank padded */
  void        *dl;                    /* dlopen handle (NULL when fn was set by a program) */
  char         path[4096], symbol[256];
} UmatParams;

/* History per quadrature point (nstatev + 21 doubles):
     [0, nstatev)         STATEV
     nstatev + [0, 6)     Cauchy stress at the end of the increment (11, 22, 33, 12, 13, 23)
     nstatev + [6, 12)    total logarithmic strain STRAN (same order, engineering shears)
     nstatev + [12, 21)   the deformation gradient F (row-major): DFGRD0 of the next increment */
#define UMAT_HIST_STRESS(ns) (ns)
#define UMAT_HIST_STRAN(ns)  ((ns) + 6)
#define UMAT_HIST_F(ns)      ((ns) + 12)
#define UMAT_NHIST(ns)       ((ns) + 21)

/* Calls the UMAT for the increment from the committed history hn (stress, strain, DFGRD0) to
   the deformation gradient F (DFGRD1); returns the Kirchhoff stress tau = det(F) sigma, the new
   history h, whether STATEV(ep_statev) grew (plastic), and when dtau is not NULL
   d tau_ij / d F_kL built from DDSDDE (doc/umat.md). Returns MAT_OK, MAT_ERR_JACOBIAN
   (det F <= 0 or det of the increment <= 0), MAT_ERR_CUTBACK (the UMAT set PNEWDT < 1) or
   MAT_ERR_NAN (NaN or Inf in the returned STRESS or DDSDDE); on error tau, dtau = 0, h = hn.
   NOEL, NPT, COORDS, CELENT: those of the kernel's last set_point (1, 1, 0, 1 if none); TIME,
   DTIME, KSTEP, KINC: of its last set_increment ((0, 0), 1, 1, 1 if none). */
int    UmatUpdate(const UmatParams *p, const double F[9], const double *hn, double tau[9], double *dtau, double *h, int *plastic);
/* zero STATEV, stress and strain; F = I */
void   UmatHistoryInit(const UmatParams *p, double *h);
/* the PNEWDT of the last call on this process that returned MAT_ERR_CUTBACK (for the message) */
double UmatLastPnewdt(void);
/* the last call on this process that returned MAT_ERR_NAN: 1 (STRESS) or 2 (DDSDDE), 0 if none;
   its NOEL and NPT (either pointer may be NULL) */
int UmatLastNaN(int *noel, int *npt);
/* the MaterialKernel on the parameters p (kept by pointer: p must outlive k) */
void   UmatKernelInit(const UmatParams *p, MaterialKernel *k);
#endif
