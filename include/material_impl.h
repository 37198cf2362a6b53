/* What the implementation of a material type sees of a Material (see material.h):
   the type's create function (registered with MaterialRegister) fills kernel, data and ops. */
#ifndef ATRITO_MATERIAL_IMPL_H
#define ATRITO_MATERIAL_IMPL_H
#include "material.h"

struct _p_Material {
  MPI_Comm       comm;
  char           type_name[64]; /* "" until a type is set */
  MaterialKernel kernel;        /* kernel.ctx points into data */
  void          *data;          /* the type's parameters */
  PetscReal      modulus;       /* Young's modulus of the elastic response, set by the type's
                                   SetFromOptions (0: the type does not know it, e.g. a UMAT) */
  struct {
    PetscErrorCode (*setfromoptions)(Material); /* reads the type's options in its own PetscOptionsBegin block */
    PetscErrorCode (*view)(Material, PetscViewer);
    PetscErrorCode (*destroy)(Material); /* frees data */
  } ops;
};
#endif
