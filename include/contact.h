/* Contact of the body's nodes with rigid tools, as an object that owns its state: the tools
   (replicated on every rank), the slave nodes (the owned vertices of the contact sets), their
   committed and trial states (status, tangential pressure, the frame t1 of eqs 28-30, pairing),
   the frame seeds of the current Newton iteration and the pairing memo. Each rank handles only
   the slave vertices it owns, so no contact force is counted twice.

   Lifecycle: Create, SetFromOptions (before the mesh: the tools, the law, the sets), SetUp (on
   the distributed mesh), then per step Seed (from the committed frames), per Newton iteration
   Seed (eq 30 at the iterate) and RecordActive, per evaluation Assemble (trial state only), and
   Commit when the step has converged. Kernels: contact_law.h; tools: tool.h. */
#ifndef ATRITO_CONTACT_H
#define ATRITO_CONTACT_H
#include <petscmat.h>
#include "mesh.h"

typedef struct _p_Contact *Contact;

/* what contact.csv reports per tool and step, from the committed state (all ranks) */
typedef struct {
  const char *name;
  double shift[3];   /* the tool's displacement                                                  */
  double dir[3];     /* the direction of force and travel: the motion at load 1 (+z if fixed)    */
  double travel;     /* shift . dir                                                              */
  double path;       /* path length travelled along the tool's path                              */
  double f[3];       /* resultant of the forces the tool exerts on the body (modelled part)      */
  double force;      /* f . dir                                                                  */
  double fn, ft;     /* magnitudes of the normal and tangential (friction) resultants            */
  PetscInt active;   /* nodes pressed against the tool (normal force > 0)                        */
  PetscInt stick, slip; /* of those, sticking and slipping (frictional contact only)             */
  double max_pen;    /* largest penetration                                                      */
  double mean_pen;   /* mean penetration of the pressed nodes                                    */
  PetscInt augmentations; /* Newton solves of the step with -contact_augmented (0 without)        */
  double dlambda;    /* the largest change of a nodal multiplier in the step's last update       */
} ContactToolResult;

PetscErrorCode ContactCreate(MPI_Comm comm, Contact *c);
/* -contact_* options and the tools (-tool_names, -tool_<name>_*) */
PetscErrorCode ContactSetFromOptions(Contact c);
/* the sets whose nodes need a tributary area (-contact_penalty_per_area), else n = 0 */
PetscErrorCode ContactGetAreaSets(Contact c, PetscInt *n, char (**sets)[ATRITO_NAME_LEN]);
/* the body's Young's modulus, for the automatic penalty (-contact_penalty_normal auto); before SetUp */
PetscErrorCode ContactSetYoungModulus(Contact c, PetscReal E);
PetscErrorCode ContactSetUp(Contact c, const Mesh *m);
PetscErrorCode ContactDestroy(Contact *c);
PetscInt       ContactNumTools(Contact c);
/* owned slave nodes on this rank */
PetscInt       ContactNumSlaves(Contact c);

/* frame seeds: from the committed frames (start of a step or a retry) or by eq 30 from the frames
   at the local displacements u (with boundary values; start of a Newton iteration) */
PetscErrorCode ContactSeed(Contact c, const PetscScalar *u, PetscReal lambda, PetscBool from_committed);
/* contributions at u: residual into f (local, may be NULL), tangent into J (MatSetValues) or into
   coo_v (coordinate assembly, in the order of ContactGetCOO); *nfail: failed projections */
PetscErrorCode ContactAssemble(Contact c, const PetscScalar *u, PetscReal lambda, PetscScalar *f, Mat J, PetscScalar *coo_v, PetscInt *nfail);
/* coordinate assembly: the (i, j) of the contact blocks; with ci = cj = NULL only the count */
PetscErrorCode ContactGetCOO(Contact c, PetscCount *n, PetscInt *ci, PetscInt *cj);
/* the trial states of the last evaluation become the committed ones, at load lambda */
PetscErrorCode ContactCommit(Contact c, PetscReal lambda);
/* augmented Lagrangian (-contact_augmented): whether it is on, and the Newton solves allowed per
   step. ContactAugment, after a converged Newton solve (the trial state at the solution): one Uzawa
   update of the nodal multipliers (lN <- <lN - K_N g>, lT <- the Coulomb return of lT + K_T dg_T),
   converged when the largest penetration and stick slip are below the tolerance and the largest
   change of a multiplier is below -contact_augmented_multiplier_tol times the largest multiplier
   (on all ranks). The multipliers are held fixed within a Newton solve; they start every step and
   every retry from the committed ones (ContactSeed from_committed) and are committed with it. */
PetscBool      ContactAugmented(Contact c);
PetscInt       ContactAugmentedMax(Contact c);
PetscErrorCode ContactAugment(Contact c, PetscBool *converged, PetscReal *maxpen, PetscReal *dlambda);
PetscErrorCode ContactAugmentTolerances(Contact c, PetscReal *tol, PetscReal *mtol);
/* the contact status and normal force of every slave node at the current iterate */
PetscErrorCode ContactRecordActive(Contact c);
/* nodes that entered or left contact in the last Newton iteration with a significant normal
   force (before or after); count over all ranks and the smallest node id */
PetscErrorCode ContactChatter(Contact c, PetscInt *count, PetscInt *node);
PetscErrorCode ContactGetToolResult(Contact c, PetscInt tool, PetscReal lambda, ContactToolResult *r);
/* multiplicity of the model (force_full = force * symmetry) */
PetscReal      ContactSymmetry(Contact c);

/* node fields of the committed state on the owned vertices (rows as the mesh's vloc): gap, normal
   force, tangential force (3), status, accumulated slip */
PetscErrorCode ContactGetNodeFields(Contact c, PetscReal *gap, PetscReal *fn, PetscReal *ft, PetscReal *status, PetscReal *slip);
/* checkpoint: the committed state of the slave nodes as rows of the owned vertices (width
   ContactCheckpointWidth(); zero rows for the other vertices) and back */
PetscInt       ContactCheckpointWidth(void);
PetscErrorCode ContactCheckpointPack(Contact c, PetscReal *rows);
PetscErrorCode ContactCheckpointUnpack(Contact c, const PetscReal *rows, PetscReal lambda, const char *path);
/* the sets of the slave nodes (n = 0 without tools), for -partition_balance contact */
PetscErrorCode ContactGetSets(Contact c, PetscInt *n, char (**sets)[ATRITO_NAME_LEN]);
#endif
