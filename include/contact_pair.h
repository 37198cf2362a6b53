/* Contact between deformable bodies of one mesh (doc/contact.md, "Contact between bodies"): pairs
   of a slave node set and a master surface, the boundary faces whose four vertices lie in a node
   set. Node to surface: each slave node is projected on the master faces near it (contact_nts.h)
   and carries the law of the rigid tools (contact_law.h: penalty, Coulomb friction by return map,
   the frame of eqs 28-30) with the slip measured relative to the master's material point under it;
   its force acts on the slave node and, distributed by the face's shape functions at the closest
   point, on the face's four nodes. The tangent is exact: it couples the slave node with the nodes
   of its master face (the derivatives of the closest point, the normal and the slip with respect
   to them).

   In parallel each rank handles its own slave nodes; the master faces near them, wherever they
   live, are sent to it as ghosts (the candidates, chosen at the start of every Newton iteration by the boxes of
   each rank's slave nodes), their positions refreshed at every evaluation and their forces
   returned to the faces' owners (PetscSF). A face is one cell's, so it has one owner.

   Lifecycle as the contact object's (contact.h), which owns it: SetFromOptions, the face sets
   asked of the mesh (ContactPairsGetFaceSets), SetUp, per step Seed from the committed state (the
   candidates), per Newton iteration Seed (the frames), per evaluation Assemble, Commit. */
#ifndef ATRITO_CONTACT_PAIR_H
#define ATRITO_CONTACT_PAIR_H
#include <petscmat.h>
#include "mesh.h"

typedef struct _p_ContactPairs *ContactPairs;

/* what contact.csv reports per pair (all ranks; from the committed state) */
typedef struct {
  const char *name;
  double      f[3];        /* resultant of the forces on the slave nodes (from the master)          */
  double      fn, ft;      /* magnitudes of its normal and tangential parts (sums over the nodes)   */
  PetscInt    active, stick, slip;
  double      max_pen;     /* largest penetration                                                  */
} ContactPairResult;

PetscErrorCode ContactPairsCreate(MPI_Comm comm, ContactPairs *p);
/* -pair_names and per pair -pair_<name>_slave, _master, _friction, _penalty_normal,
   _penalty_tangential, _penalty_factor, _penalty_ratio, _two_pass, _search_distance */
PetscErrorCode ContactPairsSetFromOptions(ContactPairs p);
PetscInt       ContactPairsNum(ContactPairs p);
/* the node sets whose boundary faces the pairs need (MeshSetFaceSets): masters, and slaves for the
   automatic penalty */
PetscErrorCode ContactPairsGetFaceSets(ContactPairs p, PetscInt *n, char (**sets)[ATRITO_NAME_LEN]);
PetscErrorCode ContactPairsSetYoungModulus(ContactPairs p, PetscReal E);
/* the modulus of each local cell's material (several bodies; copied), before SetUp */
PetscErrorCode ContactPairsSetCellModuli(ContactPairs p, PetscInt nc, const PetscReal *Ec);
PetscErrorCode ContactPairsSetUp(ContactPairs p, const Mesh *m);
PetscErrorCode ContactPairsDestroy(ContactPairs *p);
/* collective. from_committed: the step's start (or a retry): the committed frames become the
   seeds; else (a Newton iteration's start) eq 30 at u; either way the candidate faces of every
   slave node are found again at u (fixed within the Newton iteration) */
PetscErrorCode ContactPairsSeed(ContactPairs p, const PetscScalar *u, PetscBool from_committed);
/* collective: the residual at u (local, with boundary values) into the local f (may be NULL) and
   the tangent into J (may be NULL; MatSetValues, rows of other ranks included); trial states;
   *nfail is increased by the slave nodes whose projection failed at the Jacobian (this rank) */
PetscErrorCode ContactPairsAssemble(ContactPairs p, const PetscScalar *u, PetscScalar *f, Mat J, PetscInt *nfail);
PetscErrorCode ContactPairsCommit(ContactPairs p);
/* the committed node fields added at the owned vertices (rows as the mesh's vloc): gap (where the
   node is paired), normal force, tangential force (3), status, accumulated slip */
PetscErrorCode ContactPairsGetNodeFields(ContactPairs p, PetscReal *gap, PetscReal *fn, PetscReal *ft, PetscReal *status, PetscReal *slip);
/* collective: pair k's resultants */
PetscErrorCode ContactPairsGetResult(ContactPairs p, PetscInt k, ContactPairResult *r);
/* nodes that entered or left contact since ContactPairsRecordActive (collective count) */
PetscErrorCode ContactPairsRecordActive(ContactPairs p);
PetscErrorCode ContactPairsChanges(ContactPairs p, PetscInt *nchange);
/* augmented Lagrangian (-pair_<p>_augmented): whether some pair has it; one Uzawa update of their
   multipliers after a converged Newton solve, converged when every augmented pair's penetration
   and stick slip are below its tolerance (collective); the largest tolerance, for messages */
PetscBool      ContactPairsAugmented(ContactPairs p);
PetscErrorCode ContactPairsAugment(ContactPairs p, PetscBool *converged, PetscReal *maxpen, PetscReal *dlambda);
PetscErrorCode ContactPairsAugmentTolerance(ContactPairs p, PetscReal *tol);
/* checkpoint: the committed states of the slave nodes as rows of the owned vertices (width
   ContactPairsCheckpointWidth; zero rows elsewhere) and back; the unpack takes the committed
   local displacement uc (with boundary values) for the master faces' committed positions */
PetscInt       ContactPairsCheckpointWidth(ContactPairs p);
PetscErrorCode ContactPairsCheckpointPack(ContactPairs p, PetscReal *rows);
PetscErrorCode ContactPairsCheckpointUnpack(ContactPairs p, const PetscReal *rows, const PetscScalar *uc, const char *path);
#endif
