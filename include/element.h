/* Element formulations: one descriptor, one registry of types (PETSc manner).

   An Element is created on a communicator, gets its formulation from -element_type (default
   "hex8") and the formulation's options; what the assembly calls is its ElementKernel, a
   descriptor with pure functions on plain arrays. The element kernel calls the material only
   through a MaterialKernel, so any material works with any element; the history of an element
   is nqp * material->nhist + nstate doubles.

   Types: "hex8" (trilinear hexahedron, optional F-bar, include/element_hex8.h), "hex8_eas" (nine
   incompatible modes, condensed, for bending with one element through the thickness,
   include/element_hex8_eas.h; doc/elements.md). A new type is
   one file in src/element/ plus one registration line in ElementRegisterAll()
   (src/element/element.c); include/element_impl.h is what a type's file sees of the object. */
#ifndef ATRITO_ELEMENT_H
#define ATRITO_ELEMENT_H
#include "material.h"

typedef struct {
  double ep;       /* mean equivalent plastic strain over the quadrature points */
  double mises;    /* mean von Mises Cauchy stress over the quadrature points   */
  double sigma[6]; /* mean Cauchy stress xx yy zz xy yz xz                       */
  double F0[9];    /* deformation gradient at the centroid                       */
  int    nplastic; /* quadrature points that yielded in this evaluation          */
} ElementInfo;

typedef struct _p_Element *Element;

typedef struct {
  const char *name;
  int         nen;    /* nodes per element (8) */
  int         nqp;    /* quadrature points, each with material->nhist history doubles */
  int         nstate; /* extra history doubles per element (enhanced-strain parameters; 0 for hex8) */
  int         nface;  /* faces, and their corner nodes (local numbers, counter-clockwise seen from outside) */
  const int (*face)[4];
  const void *ctx; /* the formulation's options */
  /* X[nen*3] reference coordinates, u[nen*3] displacements, hn[nqp*nhist + nstate] committed history
     (quadrature point major, then the element's own), fe[3*nen] internal force (node-major), ke[(3 nen)^2]
     exact tangent d fe / d u (row-major; NULL: not wanted), h trial history (same layout), info may be NULL.
     Returns MAT_OK or an error status. */
  int (*kernel)(const void *ctx, const MaterialKernel *mat, const double *X, const double *u, const double *hn, double *fe, double *ke, double *h, ElementInfo *info);
  double (*min_jacobian)(const double *X); /* validity check of the reference geometry */
} ElementKernel;

/* add a type to the registry (create sets the object's kernel and operations) */
PetscErrorCode ElementRegister(const char name[], PetscErrorCode (*create)(Element));
PetscErrorCode ElementCreate(MPI_Comm comm, Element *el);
/* -element_type (default "hex8"), then the type's options; collective */
PetscErrorCode ElementSetFromOptions(Element el);
/* valid after ElementSetFromOptions; owned by el */
PetscErrorCode ElementGetKernel(Element el, const ElementKernel **k);
PetscErrorCode ElementView(Element el, PetscViewer v);
PetscErrorCode ElementDestroy(Element *el);
#endif
