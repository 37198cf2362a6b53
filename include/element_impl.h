/* What the implementation of an element type sees of an Element (see element.h):
   the type's create function (registered with ElementRegister) fills kernel, data and ops. */
#ifndef ATRITO_ELEMENT_IMPL_H
#define ATRITO_ELEMENT_IMPL_H
#include "element.h"

struct _p_Element {
  MPI_Comm      comm;
  char          type_name[64]; /* "" until a type is set */
  ElementKernel kernel;        /* kernel.ctx points into data */
  void         *data;          /* the formulation's options */
  struct {
    PetscErrorCode (*setfromoptions)(Element); /* reads the type's options in its own PetscOptionsBegin block */
    PetscErrorCode (*view)(Element, PetscViewer);
    PetscErrorCode (*destroy)(Element); /* frees data */
  } ops;
};
#endif
