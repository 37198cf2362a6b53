/* The discrete problem: the residual R(u, lambda) = f_int - f_contact and its exact Jacobian
   over the local cells and slave nodes, the plastic history (committed and trial), the
   displacement vectors, and the nonlinear solver (SNES with the LU of lu.c by default).

   State lifecycle: hist_c (committed) changes only in ProblemCommit; every residual or Jacobian
   evaluation recomputes hist_t (trial) from hist_c and the current iterate. */
#ifndef ATRITO_PROBLEM_H
#define ATRITO_PROBLEM_H
#include <petscsnes.h>
#include "mesh.h"
#include "bc.h"
#include "contact.h"
#include "material.h"
#include "element.h"

#define ATRITO_ERR_PROJECTION 100 /* failure status of a contact projection (beside the MAT_ERR_* of material.h) */

typedef enum { LU_ORDERING_MUMPS = 0, LU_ORDERING_ND } LUOrdering;

typedef struct {
  MPI_Comm    comm;
  PetscMPIInt rank, size;
  /* the modules, owned by the caller */
  const Mesh *mesh;
  const BCs  *bcs;
  Contact     contact;
  Material    material;
  Element     element;
  const MaterialKernel *mk;  /* the default material's                                     */
  /* the materials of the bodies (body.h): mats[0] the default, cmat[e] each cell's (NULL: all 0) */
#define PROBLEM_MAX_MAT 17
  PetscInt              nmat;
  Material              mats[PROBLEM_MAX_MAT];
  const MaterialKernel *mks[PROBLEM_MAX_MAT];
  PetscInt             *cmat;
  const ElementKernel  *ek;

  /* options */
  PetscBool  assembly_coo;   /* Jacobian by coordinate (COO) assembly instead of MatSetValues */
  PetscBool  assembly_coo_set; /* -assembly_coo was given                                     */
  PetscBool  bordered;       /* the Jacobian is a hypre mesh block bordered by force-driven tools (bordered.h) */
  char       mat_type[64];   /* -assembly_mat_type: the Jacobian's matrix type (empty: the DM's, AIJ) */
  PetscBool  near_null;      /* -assembly_near_null_space: the rigid-body modes on the Jacobian */
  LUOrdering lu_ordering;    /* LU by MUMPS: METIS nested dissection (direct calls) or MUMPS's own */
  PetscReal  fault_nan_load; /* testing: once, a NaN in the residual at this load (< 0: off) */
  PetscBool  fault_done;

  /* history: committed and trial, nhc doubles per cell (nqp x material history + element state) */
  PetscInt     nhc;
  PetscReal   *hist_c, *hist_t;
  ElementInfo *einfo;  /* per cell, from the last evaluation at a converged state */

  /* solution: with force-driven tools (ntu > 0) the global vectors hold the body's unknowns (the
     DM's global layout) followed, on the last rank, by the ntu tool unknowns (contact.h); Ubv and
     Fbv are DM global vectors that view the body part of such a vector (VecPlaceArray) */
  PetscInt  ntu, tbs;        /* tool unknowns; block size of the extended vectors */
  Vec       Ubv, Fbv;
  Vec       U, Uc, Uprev;  /* current iterate, committed, previous committed (global)    */
  Vec       Uloc, Floc;    /* local work vectors                                        */
  PetscReal lambda;        /* load parameter at which the residual is evaluated         */
  PetscInt  ndomain_err;   /* failed element or node evaluations in the last assembly   */
  PetscReal fsq;           /* sum over the local elements of |f_e|^2, the element force vectors of
                              the last residual assembly (ProblemForceScale)                  */
  PetscInt  bad_cell_id;   /* source id of the first failing element, for messages      */
  PetscInt  bad_status;
  PetscInt  bad_point;     /* its integration point (1..nqp) where the material names it, else 0 */
  PetscReal trial_norm;    /* > 0 inside PETSc's backtracking line search (set by the stepper): an
                              evaluation that fails (an element inverted, a return map or a
                              projection that did not converge) returns a residual of this norm
                              instead of a domain error, so that the search shortens the step    */
  PetscInt  ntrial_fail;   /* such evaluations, counted                                          */
  PetscBool cutback;       /* an element's material asked for a smaller increment (a UMAT's PNEWDT
                              < 1) since the flag was last cleared: the step is cut, not searched */

  /* coordinate assembly: offset of each element block in coo_v (the contact blocks last) */
  PetscCount  *coo_off;
  PetscScalar *coo_v;

  SNES snes;
  Mat  J;
  PetscLogEvent ev_residual, ev_jacobian;
} Problem;

/* -assembly_coo, -lu_ordering, -fault_nan_residual_at; the SNES and its options (-snes_*, -ksp_*, -pc_*) */
PetscErrorCode ProblemSetFromOptions(MPI_Comm comm, Problem *pb);
/* registers the preconditioner type "amgsys" (src/solver/amg.c: BoomerAMG with each row told its
   displacement component); ProblemSetFromOptions calls it */
PetscErrorCode AMGSysRegister(void);
/* before ProblemSetUp, with several bodies: the n materials (mats[0] the default) and each local
   cell's (cmat[nc], copied) */
PetscErrorCode ProblemSetMaterials(Problem *pb, PetscInt n, const Material *mats, const PetscInt *cmat, PetscInt nc);
/* on the mesh: history, vectors, the Jacobian (preallocated, COO pattern, near-null space) */
PetscErrorCode ProblemSetUp(Problem *pb, const Mesh *m, const BCs *bcs, Contact contact, Material mat, Element el);
PetscErrorCode ProblemDestroy(Problem *pb);
/* one evaluation at U and lambda: trial history, cell info, local residual in Floc (with the
   boundary values in Uloc), failures counted collectively */
PetscErrorCode ProblemEvaluate(Problem *pb, Vec U, PetscReal lambda);
/* the residual and the Jacobian as SNES calls them (at pb->lambda) */
PetscErrorCode ProblemFormFunction(SNES snes, Vec U, Vec F, void *ctx);
PetscErrorCode ProblemFormJacobian(SNES snes, Vec U, Mat J, Mat P, void *ctx);
/* Uloc = U with the boundary values at lambda */
/* the largest entry of the residual F on the body's unknowns: its size, the node (source id), the
   component (0, 1, 2) and the node's reference position (collective) */
PetscErrorCode ProblemResidualPeak(Problem *pb, Vec F, PetscReal *val, PetscInt *node, PetscInt *comp, PetscReal x[3]);
PetscErrorCode ProblemLocalWithBC(Problem *pb, Vec U, PetscReal lambda);
/* the scale of the internal forces at the last residual assembly: sqrt(sum_e |f_e|^2) over the
   elements' force vectors before assembly (collective) */
PetscErrorCode ProblemForceScale(Problem *pb, PetscReal *F);
/* the tool unknowns of a global vector (ntu values, the same on every rank; collective), and back
   (the owner writes them) */
PetscErrorCode ProblemGetToolValues(Problem *pb, Vec X, PetscReal *d);
PetscErrorCode ProblemSetToolValues(Problem *pb, Vec X, const PetscReal *d);
/* the trial state of the last evaluation (at a converged U) becomes the committed one */
PetscErrorCode ProblemCommit(Problem *pb, PetscReal lambda);
/* after a checkpoint was read: the trial states start from the committed ones */
PetscErrorCode ProblemRestored(Problem *pb);
#endif
