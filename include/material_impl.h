/* What the implementation of a material type sees of a Material (see material.h):
   the type's create function (registered with MaterialRegister) fills kernel, data and ops. */
#ifndef ATRITO_MATERIAL_IMPL_H
#define ATRITO_MATERIAL_IMPL_H
#include "material.h"

struct _p_Material {
  MPI_Comm       comm;
  char           type_name[64]; /* "" until a type is set */
  char           prefix[256];   /* the options prefix, without the dash: "material_" after
                                   MaterialCreate (MaterialSetOptionsPrefix); every
                                   PetscOptionsBegin of the material and of its type uses it, and
                                   a message names an option as "-%sE", prefix */
  MaterialKernel kernel;        /* kernel.ctx points into data */
  void          *data;          /* the type's parameters */
  PetscReal      modulus;       /* Young's modulus of the elastic response, set by the type's
                                   SetFromOptions (0: the type does not know it, e.g. a UMAT) */
  struct {
    PetscErrorCode (*setfromoptions)(Material); /* reads the type's options in its own PetscOptionsBegin block, prefix mat->prefix */
    PetscErrorCode (*view)(Material, PetscViewer);
    PetscErrorCode (*destroy)(Material); /* frees data */
  } ops;
};

/* the title of a type's group in -help: "Material <type>: <what>" under the default prefix,
   "Material <type> (-<prefix>): <what>" under another one (what = NULL: no ": <what>"; type =
   NULL: "Material" alone, the group of the options common to all types) */
PetscErrorCode MaterialOptionsTitle(Material mat, const char type[], const char what[], char title[], size_t len);
#endif
