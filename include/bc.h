/* Dirichlet boundary conditions: each condition (-bc_names a,b,...; per condition
   -bc_<name>_set, _components, _values) prescribes displacement components on a mesh set, ramped
   with the load parameter: u = lambda * value. The constrained components are section
   constraints (absent from the global vector and the matrix); the local vector carries their
   values. The reaction of a condition is the force its supports exert on the body, in the global
   axes, summed over the set: the assembled residual (internal minus contact forces) at the set's
   vertices, for the constrained components only. */
#ifndef ATRITO_BC_H
#define ATRITO_BC_H
#include "mesh.h"

#define ATRITO_MAX_BC 32

typedef struct {
  char      name[ATRITO_NAME_LEN];  /* as listed in -bc_names                          */
  char      set[ATRITO_NAME_LEN];   /* mesh set (label) the condition applies to       */
  PetscInt  ncomp;                  /* constrained components                          */
  PetscInt  comp[3];                /* 0 = x, 1 = y, 2 = z                             */
  PetscReal value[3];               /* prescribed displacement at load parameter 1     */
  /* after BCSetUp */
  PetscInt   nset;   /* local dofs constrained by this condition */
  PetscInt  *loff;   /* their offsets in the local vector        */
  PetscReal *val;    /* their values at load parameter 1         */
  PetscInt   nown;   /* owned vertices of the set (reactions)    */
  PetscInt  *own;    /* local vertex indices                     */
} BC;

typedef struct {
  PetscInt n;
  BC       bc[ATRITO_MAX_BC];
} BCs;

PetscErrorCode BCSetFromOptions(MPI_Comm comm, BCs *bcs);
/* the constraint mask of every local vertex (for MeshSetConstraints); checks the sets exist and
   that no component gets two different values */
PetscErrorCode BCComputeMask(BCs *bcs, const Mesh *m, PetscInt **cmask);
/* after MeshSetConstraints: the local dof lists */
PetscErrorCode BCSetUp(BCs *bcs, const Mesh *m);
PetscErrorCode BCDestroy(BCs *bcs);
/* the prescribed values at lambda into a local vector's array */
void BCApply(const BCs *bcs, PetscScalar *u, PetscReal lambda);
/* reactions R[b][c] of every condition (all ranks), from the local residual Floc */
PetscErrorCode BCReactions(const BCs *bcs, const Mesh *m, Vec Floc, PetscReal (*R)[3]);
#endif
