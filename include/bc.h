/* Dirichlet boundary conditions: each condition (-bc_names a,b,...; per condition
   -bc_<name>_set, _components, _values, _amplitude) prescribes displacement components on a mesh
   set, u = a(t) * value at the process time t, a the condition's amplitude curve (default t/T, T
   the total process time: the linear ramp of the load parameter without stages). A condition
   active in every stage is a section constraint (absent from the global vector and the matrix;
   the local vector carries its values). A condition that some stage leaves inactive keeps its
   dofs in the global system: while it is active, the local vector carries its values (the
   residual and the Jacobian of the other rows see exactly the prescribed displacement), its rows
   are u - g and its rows and columns of the Jacobian are those of the identity (BCConstrainRows,
   BCConstrainJacobian), which is the same elimination as the section's; while it is inactive its
   dofs are free. The reaction of a condition is the force its supports exert on the body, in the global
   axes, summed over the set: the assembled residual (internal minus contact forces) at the set's
   vertices, for the constrained components only. */
#ifndef ATRITO_BC_H
#define ATRITO_BC_H
#include "mesh.h"
#include "loadcurve.h"

#define ATRITO_MAX_BC 32

typedef struct {
  char      name[ATRITO_NAME_LEN];  /* as listed in -bc_names                          */
  char      set[ATRITO_NAME_LEN];   /* mesh set (label) the condition applies to       */
  PetscInt  ncomp;                  /* constrained components                          */
  PetscInt  comp[3];                /* 0 = x, 1 = y, 2 = z                             */
  PetscReal value[3];               /* prescribed displacement: value * a(t)            */
  LoadCurve amp;                    /* a(t) (n = 0: t/T)                                */
  PetscBool always;                 /* active in every stage: a section constraint      */
  PetscBool active;                 /* active in the current stage                      */
  PetscBool hold;                   /* -bc_<name>_hold: u = base + value * a(t), base the
                                       displacement when a stage switches it on            */
  /* after BCSetUp */
  PetscInt   nset;   /* local dofs constrained by this condition */
  PetscInt  *loff;   /* their offsets in the local vector        */
  PetscReal *val;    /* their values at load parameter 1         */
  PetscInt   nown;   /* owned vertices of the set (reactions)    */
  PetscInt  *own;    /* local vertex indices                     */
  PetscInt   nrow;   /* a condition that is not always active: its dofs on owned vertices */
  PetscInt  *grow;   /* their global rows                        */
  PetscReal *rval;   /* their values (times a(t))                */
  PetscReal *base, *rbase; /* hold: the base of the nset local dofs and of the nrow rows */
} BC;

typedef struct {
  PetscInt  n;
  BC        bc[ATRITO_MAX_BC];
  PetscReal T;          /* total process time (the default amplitude t/T)             */
  PetscInt  nswitch;    /* conditions that are not active in every stage              */
  PetscInt *zrows;      /* work: the rows of the active ones on this rank              */
  const Mesh *mesh;     /* after BCSetUp                                               */
} BCs;

PetscErrorCode BCSetFromOptions(MPI_Comm comm, BCs *bcs);
/* the constraint mask of every local vertex (for MeshSetConstraints); checks the sets exist and
   that no component gets two different values */
PetscErrorCode BCComputeMask(BCs *bcs, const Mesh *m, PetscInt **cmask);
/* after MeshSetConstraints: the local dof lists */
PetscErrorCode BCSetUp(BCs *bcs, const Mesh *m);
PetscErrorCode BCDestroy(BCs *bcs);
/* the prescribed values at process time t into a local vector's array (active conditions only) */
void BCApply(const BCs *bcs, PetscScalar *u, PetscReal t);
/* the amplitude of condition b at time t */
PetscReal BCAmplitude(const BCs *bcs, PetscInt b, PetscReal t);
/* the first kink of any condition's amplitude strictly after t (PETSC_INFINITY if none) */
PetscReal BCNextKink(const BCs *bcs, PetscReal t);
/* the switchable conditions (not active in every stage): the rows u - g of the active ones in the
   global residual F at the global iterate U, and their identity rows and columns in the Jacobian
   (nonzero pattern kept) */
PetscErrorCode BCConstrainRows(const BCs *bcs, Vec U, Vec F, PetscReal t);
PetscErrorCode BCConstrainJacobian(BCs *bcs, Mat P);
/* the global rows of the active switchable conditions on this rank, sorted (the identity rows
   and columns of the Jacobian; valid until the next call) */
PetscErrorCode BCSwitchedRows(BCs *bcs, PetscInt *n, const PetscInt **rows);
/* a holding condition b (-bc_<name>_hold) switched on: its base is the displacement of the global
   vector src at its dofs, copied into the global vector hold (the bases of all holding
   conditions, for the checkpoint); src = hold: the bases from a checkpoint. Collective. */
PetscErrorCode BCHold(BCs *bcs, PetscInt b, Vec src, Vec hold);
/* whether any condition holds (-bc_<name>_hold) and is switched by stages */
PetscBool BCHasHold(const BCs *bcs);
/* reactions R[b][c] of every condition (all ranks), from the local residual Floc */
PetscErrorCode BCReactions(const BCs *bcs, const Mesh *m, Vec Floc, PetscReal (*R)[3]);
#endif
