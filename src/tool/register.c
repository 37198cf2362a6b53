/* The registry of the built-in patch types: one line per type. A new type is its own file in
   src/tool/ (an operations table and PatchCreate_<Type>, toolimpl.h) plus one line here. */
#include "toolimpl.h"

/* declares the type's create function and registers it under the option value `name` */
#define PATCH_TYPE(name, create) \
  do { \
    PetscErrorCode create(Patch *); \
    PetscCall(PatchRegister(name, create)); \
  } while (0)

static PetscBool PatchRegisterAllCalled = PETSC_FALSE;

static PetscErrorCode PatchRegisterAllReset(void)
{
  PetscFunctionBeginUser;
  PatchRegisterAllCalled = PETSC_FALSE;
  PetscFunctionReturn(0);
}

PetscErrorCode PatchRegisterAll(void)
{
  PetscFunctionBeginUser;
  if (PatchRegisterAllCalled) PetscFunctionReturn(0);
  PatchRegisterAllCalled = PETSC_TRUE;
  PetscCall(PetscRegisterFinalize(PatchRegisterAllReset));
  PATCH_TYPE("plane", PatchCreate_Plane);       /* plane.c    */
  PATCH_TYPE("sphere", PatchCreate_Sphere);     /* sphere.c   */
  PATCH_TYPE("cylinder", PatchCreate_Cylinder); /* cylinder.c */
  PATCH_TYPE("torus", PatchCreate_Torus);       /* torus.c    */
  PATCH_TYPE("coons", PatchCreate_Coons);       /* coons.c    */
  PATCH_TYPE("facets", PatchCreate_Facets);     /* facets.c   */
  PetscFunctionReturn(0);
}
