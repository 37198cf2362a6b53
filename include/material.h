/* Materials: one interface, one registry of types (PETSc manner).

   A Material is created on a communicator, gets its type from -material_type (default "j2")
   and its parameters from the type's own options (-material_E, ...; under another options
   prefix set with MaterialSetOptionsPrefix, e.g. "body_die_material_", every one of them is
   read as -body_die_material_type, -body_die_material_E, ..., so that several materials
   coexist); what the element kernels call is its MaterialKernel, a table of pure functions on
   plain arrays (no PETSc objects, no MPI), with the history width per quadrature point chosen
   by the type at run time.

   Types: "j2" (finite-strain J2 plasticity, include/material_j2.h), "hill48" (Hill 48 anisotropic
   plasticity in the same log-strain framework, include/material_hill48.h; doc/materials.md),
   "umat" (an Abaqus/Standard UMAT from a shared library, include/material_umat.h; doc/umat.md).
   A new type is one file in
   src/material/ plus one registration line in MaterialRegisterAll() (src/material/material.c);
   include/material_impl.h is what a type's file (or a program registering its own type with
   MaterialRegister) sees of the object. */
#ifndef ATRITO_MATERIAL_H
#define ATRITO_MATERIAL_H
#include <petscsys.h>
#include <petscviewer.h>

/* status codes of MaterialKernel.update (and of the element kernels) */
#define MAT_OK 0
#define MAT_ERR_JACOBIAN 1  /* det F <= 0 */
#define MAT_ERR_RETURNMAP 2 /* the local return map (or any local iteration) did not converge */
#define MAT_ERR_CUTBACK 3   /* the material asks for a smaller increment (a user material's PNEWDT < 1) */
#define MAT_ERR_NAN 4       /* the material returned NaN or Inf (a user material's STRESS or DDSDDE) */

typedef struct _p_Material *Material;

/* what the element kernels call, on plain arrays: no PETSc objects, no MPI */
typedef struct {
  int         nhist; /* history doubles per quadrature point (chosen at run time by the type) */
  const void *ctx;   /* the model's parameters, read-only in the kernels */
  /* Given the deformation gradient F (row-major, F[3*i+J]) and the committed history hn[nhist],
     compute the Kirchhoff stress tau (full symmetric 3x3, row-major), the updated (trial)
     history h[nhist], whether the step is plastic (plastic may be NULL), and -- when dtau is
     not NULL -- the exact derivative dtau[(3*i+j)*9 + 3*k+L] = d tau_ij / d F_kL.
     Returns MAT_OK or an error status (then tau, dtau are zero and h = hn); never aborts. */
  int (*update)(const void *ctx, const double F[9], const double *hn, double tau[9], double *dtau, double *h, int *plastic);
  /* the history of the virgin material */
  void (*history_init)(const void *ctx, double *h);
  /* equivalent plastic strain of a history, for output */
  double (*plastic_strain)(const void *ctx, const double *h);
  /* optional (NULL for the built-in models): the material point of the next calls of update, for
     a model that passes it on or reports it (a user material's NOEL, NPT, COORDS, CELENT):
     noel >= 0 sets the element (its id in the mesh file; the assembly, before each element),
     npt >= 1 the integration point (1..nqp in the element's order), coords its current position
     and celent the element's length (the element kernel, before each update); a negative noel or
     npt, NULL coords or celent <= 0 leave that one as it was */
  void (*set_point)(const void *ctx, int noel, int npt, const double coords[3], double celent);
  /* optional: the integration point of the last update that failed with MAT_ERR_NAN, 0 if none */
  int (*failed_point)(const void *ctx);
  /* optional: the increment of the next calls of update (the load stepping, before each attempt
     of a step): the stage's time and the process time at its start, its length, the stage
     (1-based) and the step number of the run (a user material's TIME(1), TIME(2), DTIME, KSTEP,
     KINC) */
  void (*set_increment)(const void *ctx, double time_stage, double time_total, double dtime, int kstep, int kinc);
} MaterialKernel;

/* add a type to the registry (create sets the object's kernel and operations) */
PetscErrorCode MaterialRegister(const char name[], PetscErrorCode (*create)(Material));
PetscErrorCode MaterialCreate(MPI_Comm comm, Material *mat);
/* The prefix of the material's options, without the leading dash: "material_" after
   MaterialCreate; NULL restores it. Every option of the material and of its type is read under
   it (-<prefix>type, -<prefix>E, ...), and the messages and -help group titles name the options
   with it. It must not be empty, start with '-' or contain white space, and should end with '_';
   at most 255 characters. Call it before MaterialSetFromOptions (which reads the options anew
   under the current prefix when called again). */
PetscErrorCode MaterialSetOptionsPrefix(Material mat, const char prefix[]);
/* the current prefix (owned by mat) */
PetscErrorCode MaterialGetOptionsPrefix(Material mat, const char *prefix[]);
/* -material_type (default "j2"), then the type's own options (under the options prefix, by
   default "material_"); collective */
PetscErrorCode MaterialSetFromOptions(Material mat);
/* valid after MaterialSetFromOptions; owned by mat */
PetscErrorCode MaterialGetKernel(Material mat, const MaterialKernel **k);
/* Young's modulus of the elastic response (for penalties scaled by the body's stiffness); 0 when
   the type does not know it */
PetscErrorCode MaterialGetYoungModulus(Material mat, PetscReal *E);
/* the type's name ("j2", ...); valid after MaterialSetFromOptions, owned by mat */
PetscErrorCode MaterialGetType(Material mat, const char **type);
PetscErrorCode MaterialView(Material mat, PetscViewer v);
PetscErrorCode MaterialDestroy(Material *mat);
#endif
