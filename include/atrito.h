/* The problem as the modules share it: the read-only case description, the distributed
   mesh with its per-rank arrays, the boundary conditions, and the committed/trial history. */
#ifndef ATRITO_H
#define ATRITO_H
#include <petscdmplex.h>
#include <petscsnes.h>
#include "material.h"
#include "fe.h"
#include "contact.h"
#include "tool.h"
#include "iorows.h"

#define ATRITO_MAX_BC   32
#define ATRITO_NAME_LEN 256
#define ATRITO_ERR_PROJECTION 3 /* failure status of a contact projection (beside MAT_ERR_*) */

/* ---------------------------------------------------------------- case (read-only) */
typedef enum { MESH_BOX = 0, MESH_BLANK, MESH_GMSH, MESH_INP } MeshSource;
typedef enum { PREDICTOR_NONE = 0, PREDICTOR_EXTRAPOLATE, PREDICTOR_TANGENT, PREDICTOR_AUTO } Predictor;
typedef enum { LU_ORDERING_MUMPS = 0, LU_ORDERING_ND } LUOrdering;

typedef struct {
  char      name[ATRITO_NAME_LEN];  /* as listed in -bc_names                          */
  char      set[ATRITO_NAME_LEN];   /* mesh set (label) the condition applies to       */
  PetscInt  ncomp;                  /* constrained components                          */
  PetscInt  comp[3];                /* 0 = x, 1 = y, 2 = z                             */
  PetscReal value[3];               /* prescribed displacement at load parameter 1     */
} BCSpec;

typedef struct {
  /* mesh */
  MeshSource mesh_source;
  char       mesh_file[PETSC_MAX_PATH_LEN];
  PetscReal  box_lower[3], box_upper[3];
  PetscInt   box_cells[3];
  PetscReal  blank_radius, blank_thickness, blank_core;
  PetscInt   blank_core_cells, blank_radial_cells, blank_layers;
  PetscBool  blank_quarter;
  PetscBool  partition_metis;
  /* material and element */
  MaterialParams mat;
  ElementOptions elem;
  PetscBool      assembly_coo;  /* Jacobian by coordinate (COO) assembly instead of MatSetValues */
  /* boundary conditions */
  PetscInt nbc;
  BCSpec   bc[ATRITO_MAX_BC];
  /* load stepping */
  PetscReal load_dt0, load_dt_min, load_dt_max, load_cut, load_grow;
  PetscInt  load_grow_its, load_max_cuts, load_max_steps;
  Predictor load_predictor;
  PetscInt  stall_its;    /* Newton has stalled when |R| did not fall below stall_factor times */
  PetscReal stall_factor; /* its value stall_its iterations earlier (0: no test)              */
  LUOrdering lu_ordering; /* LU by MUMPS: METIS nested dissection (direct calls) or MUMPS's own */
  /* contact */
  char       contact_set[8][ATRITO_NAME_LEN]; /* slave nodes: the union of these sets       */
  PetscInt   ncontact_set;
  ContactLaw law;
  PetscBool  contact_per_area;   /* K_N, K_T per unit area, times each node's tributary area */
  PetscBool  contact_fd;         /* per-node finite-difference tangent instead of the analytic one */
  PetscReal  contact_search;     /* pairing: skip a tool whose box is farther than this      */
  PetscReal  symmetry;           /* multiplicity of the model (4 for a quarter)             */
  PetscBool  chatter_check;      /* a step whose last Newton iteration changed the active set fails */
  PetscReal  fault_nan_load;     /* testing: once, a NaN in the residual at this load (< 0: off) */
  /* output */
  char      output_dir[PETSC_MAX_PATH_LEN];
  PetscInt  output_interval;        /* write fields every N converged steps (0: none)  */
  PetscInt  checkpoint_interval;    /* write DIR/checkpoint.h5 every N steps (0: none) */
  char      restart[PETSC_MAX_PATH_LEN]; /* continue from this checkpoint            */
  PetscBool thickness_output;
  PetscReal thickness_dir[3];       /* reference sheet normal for the thickness strain */
} Case;

/* ---------------------------------------------------------------- contact state */
/* The last pairing of a slave node: the tool and projection found for the position y at the load
   lambda. Pairing the node again at the same y and lambda (bit for bit) returns it unchanged: the
   residual, the Jacobian and the frame update of a Newton iteration see one node position. */
typedef struct {
  PetscReal  y[3], lambda;
  PetscInt   tool; /* -1: no tool within the search distance; -2: empty */
  Projection pr;
} PairMemo;

typedef struct {
  PetscInt  status;     /* CONTACT_OPEN / STICK / SLIP                                   */
  PetscInt  tool, patch;/* pairing: tool and patch of the closest point, -1 when none      */
  PetscReal xi, eta;    /* its parameters                                                 */
  PetscReal tT[2];      /* tangential pressure, components on t1, t2                      */
  PetscReal t1[3];      /* the local frame's t1 (eqs 28-30)                               */
  PetscBool has_frame;
  PetscReal y[3];       /* node position                                                   */
  PetscReal gap, tN;    /* gap and normal pressure                                         */
  PetscReal f[3];       /* contact force on the node                                       */
  PetscReal fT[3];      /* its tangential (friction) part                                  */
  PetscReal slip;       /* accumulated tangential slip                                     */
} ContactState;

/* ---------------------------------------------------------------- problem */
typedef struct {
  PetscInt  nset;     /* local dofs constrained by this BC             */
  PetscInt *loff;     /* their offsets in the local vector             */
  PetscReal *val;     /* their values at load parameter 1              */
  PetscInt  nown;     /* owned vertices of the set (for reactions)     */
  PetscInt *own;      /* local vertex indices                          */
} BCData;

typedef struct {
  MPI_Comm    comm;
  PetscMPIInt rank, size;
  const Case *cs;

  /* mesh */
  DM        dm;        /* distributed mesh, section with the Dirichlet constraints     */
  DM        dmr;       /* same mesh, unconstrained section (reactions)                 */
  PetscInt  nc;        /* local cells                                                  */
  PetscInt  nv;        /* local vertices (owned and ghost)                             */
  PetscInt  vstart;    /* first vertex point                                           */
  PetscInt *cv;        /* nc*8 local vertex indices, standard hex8 order               */
  PetscReal *X;        /* nv*3 reference coordinates                                   */
  PetscInt *vloff;     /* nv: offset of the vertex's 3 dofs in the local vector        */
  PetscInt *cgdof;     /* nc*24: the element's unconstrained global dofs, sorted          */
  unsigned char *cperm;/* nc*24: the element-local dof (3a+c) of each of them             */
  PetscInt *cndof;     /* nc: how many                                                   */
  PetscCount  *coo_off; /* coordinate assembly: offset of each element block in coo_v    */
  PetscScalar *coo_v;
  PetscBool *vowned;   /* nv                                                           */
  PetscInt *node_id, *elem_id; /* source ids (1-based) per local vertex / cell          */
  PetscInt *node_src, *elem_src; /* 0-based position in the source mesh: the rank-independent
                                  numbering of the output and checkpoint rows              */
  PetscInt  nv_global, ne_global;
  PetscReal *varea;    /* nv: tributary area on the contact faces (-contact_penalty_per_area), else NULL */

  /* output and checkpoint rows, in the source mesh's order */
  PetscInt  nvo;       /* owned vertices                                                 */
  PetscInt *vloc;      /* their local indices                                           */
  PetscInt *vrow;      /* per local vertex: its row among the owned ones, -1 if a ghost */
  IORows    rv, rc;    /* owned vertices, cells                                         */

  /* boundary conditions */
  PetscInt nbc;
  BCData   bc[ATRITO_MAX_BC];

  /* history: committed and trial, nc*HEX8_NQP*MAT_NHIST each */
  PetscReal *hist_c, *hist_t;
  ElementInfo *einfo;  /* per cell, from the last evaluation at a converged state */

  /* solution */
  Vec       U, Uc, Uprev;  /* current iterate, committed, previous committed (global)    */
  Vec       Uloc, Floc;    /* local work vectors                                        */
  PetscReal lambda;        /* load parameter at which the residual is evaluated         */
  PetscInt  ndomain_err;   /* failed element evaluations in the last residual           */
  PetscInt  bad_cell_id;   /* source id of the first failing element, for messages      */
  PetscInt  bad_status;
  PetscBool stalled;          /* the last Newton solve stopped as stalled                  */
  PetscReal stall_fnorm;      /* its |R| then                                               */
  PetscReal fnorm_hist[256];  /* |R| of its iterations                                      */

  /* contact: tools (replicated), owned slave vertices and their states */
  PetscInt      ntools;
  Tool         *tools;
  PetscInt      ns;            /* owned slave vertices                                       */
  PetscInt     *slave;         /* their local vertex indices                                 */
  PetscInt     *sgdof;         /* ns*3 global dofs, -1 where constrained                    */
  ContactState *cst_c, *cst_t; /* committed and trial                                        */
  PetscReal    *seed;          /* ns*3 frame seed of the current Newton iteration (eqs 28-30) */
  PetscBool    *has_seed;
  PetscReal     lambda_c;      /* load parameter of the committed state                      */
  PetscInt      contact_fail;  /* projections that failed in the last evaluation            */
  PetscReal     search;        /* pairing distance                                           */
  PetscBool    *active_prev;   /* ns: in contact at the start of the current Newton iteration */
  PairMemo     *pmemo;         /* ns: the last pairing of each node                          */
  PetscBool     fault_done;

  PetscLogEvent ev_residual, ev_jacobian, ev_contact, ev_pairing, ev_output;
} Problem;

/* case.c */
PetscErrorCode CaseRead(MPI_Comm comm, Case *cs);

/* mesh.c: build, partition, distribute, label and index the mesh */
PetscErrorCode ProblemCreateMesh(Problem *pb);
PetscErrorCode ProblemDestroyMesh(Problem *pb);
PetscErrorCode ProblemMarkSetVertices(Problem *pb, const char *set, PetscBool *mark, PetscBool *found);
PetscErrorCode ProblemVertexDofs(Problem *pb, PetscInt v, PetscInt idx[3]);

/* solver.c */
PetscErrorCode ProblemSetUp(Problem *pb);
PetscErrorCode ProblemSolve(Problem *pb);
PetscErrorCode ProblemDestroy(Problem *pb);
PetscErrorCode ProblemResidualLocal(Problem *pb, Vec U, PetscReal lambda);

/* history: per-step CSV (rank 0), written whole rows only; append: continue a restarted run */
PetscErrorCode HistoryOpen(Problem *pb, FILE **fp, PetscBool append);
PetscErrorCode HistoryWrite(Problem *pb, FILE *fp, PetscInt step, PetscReal time, PetscInt its, PetscReal r0, PetscReal r);
PetscErrorCode ProblemReactions(Problem *pb, PetscReal (*R)[3]);

/* contact_problem.c */
PetscErrorCode ContactSetUp(Problem *pb);
PetscErrorCode ContactDestroy(Problem *pb);
/* seeds of the frame recurrence: from the committed frames (step start) or from the frames at
   the iterate U (start of a Newton iteration); chords for the nodes that have none */
PetscErrorCode ContactSeed(Problem *pb, Vec Uloc_with_bc, PetscReal lambda, PetscBool from_committed);
/* contact contributions at the local displacements u (with boundary values) */
PetscErrorCode ContactAssemble(Problem *pb, const PetscScalar *u, PetscReal lambda, PetscScalar *f, Mat J, PetscScalar *coo_v);
PetscErrorCode ContactCommit(Problem *pb);
PetscErrorCode ContactRecordActive(Problem *pb);
PetscErrorCode ContactChatter(Problem *pb, PetscInt *count, PetscInt *node);
PetscErrorCode ContactHistoryOpen(Problem *pb, FILE **fp, PetscBool append);
PetscErrorCode ContactHistoryWrite(Problem *pb, FILE *fp, PetscInt step, PetscReal time, PetscInt its);

/* checkpoint.c */
typedef struct {
  PetscInt  step, total_its, total_cuts;
  PetscReal lambda, dl, dl_prev;
} CheckpointInfo;
PetscErrorCode CheckpointWrite(Problem *pb, const CheckpointInfo *ci);
PetscErrorCode CheckpointRead(Problem *pb, const char *path, CheckpointInfo *ci);
PetscErrorCode HistoryTruncate(Problem *pb, const char *name, PetscInt step, PetscBool *existed);

/* util.c */
/* After work done on rank 0 alone (under PetscReturnErrorHandler), raise its error, with its
   message, on every rank of comm; a no-op when ierr_root is 0. */
PetscErrorCode AtritoRootError(MPI_Comm comm, PetscErrorCode ierr_root);
#endif
