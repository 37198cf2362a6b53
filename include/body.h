/* Bodies: parts of the mesh with materials of their own (doc/materials.md, "Several bodies").
   -body_names die,blank names them; -body_<b>_set gives each its element set (an .inp *ELSET, a
   Gmsh physical volume), and its material is read under the prefix -body_<b>_material_ (every
   option of -material_..., e.g. -body_die_material_E 2.1e5). The cells in no body's set take the
   default material (-material_...). Contact between the bodies: contact_pair.h.

   Lifecycle: SetFromOptions (with the other modules' options), then on the distributed mesh
   CellMap: each local cell's material (0 the default, k + 1 body k). */
#ifndef ATRITO_BODY_H
#define ATRITO_BODY_H
#include "mesh.h"
#include "material.h"

#define BODY_MAX 16

typedef struct {
  MPI_Comm comm;
  PetscInt n;                             /* bodies given (0: one material for the whole mesh) */
  char     name[BODY_MAX][ATRITO_NAME_LEN];
  char     set[BODY_MAX][ATRITO_NAME_LEN];
  Material mat[BODY_MAX];
} Bodies;

/* -body_names and each body's -body_<b>_set and material (collective) */
PetscErrorCode BodiesSetFromOptions(MPI_Comm comm, Bodies *b);
/* cmat[nc]: the material of each local cell, 0 the default one, k + 1 body k's; a cell in two
   bodies' sets, or a set the mesh does not have, is an error (collective) */
PetscErrorCode BodiesCellMap(const Bodies *b, const Mesh *m, PetscInt *cmat);
PetscErrorCode BodiesDestroy(Bodies *b);
#endif
