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
#include "loadcurve.h"

typedef struct _p_Contact *Contact;

/* How a direction (x, y, z) of a tool is driven: by its prescribed displacement (ToolShift, or a
   held position), or by a force: the tool's displacement along it is an unknown solved with the
   body, so that the total force the tool exerts on the body along that axis equals the target. */
typedef enum { TOOL_DRIVE_DISPLACEMENT = 0, TOOL_DRIVE_FORCE } ToolDrive;

/* what contact.csv reports per tool and step, from the committed state (all ranks) */
typedef struct {
  const char *name;
  double shift[3];   /* the tool's displacement                                                  */
  double dir[3];     /* the direction of force and travel: -motion, or the last point of -path (+z if fixed) */
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

/* Force-driven tools (doc/contact.md, "Tools driven by force"). Every tool with a force-driven
   direction (from -tool_<name>_force_x|y|z, or ContactSetToolDrive / ContactReserveToolUnknowns
   before ContactSetUp) owns 3 unknowns, its displacement in x, y, z, appended to the body's
   (ContactNumToolUnknowns; the directions not driven by force are pinned to their prescribed
   displacement by an identity row). The set of such tools is fixed at ContactSetUp.

   ContactSetToolDrive switches direction dir (0, 1, 2) of tool `tool` between the modes (at a
   stage boundary, between steps): to TOOL_DRIVE_FORCE the unknown starts from the committed
   position and the target force is the curve's value at the process time, force->v(t) itself
   (absolute, copied); to TOOL_DRIVE_DISPLACEMENT the direction holds its committed position from
   then on (plus any later change of the tool's prescribed displacement ToolShift). After
   ContactSetUp only a tool that owns unknowns can be switched to force. */
PetscErrorCode ContactSetToolDrive(Contact c, PetscInt tool, PetscInt dir, ToolDrive mode, const LoadCurve *force);
/* Force-controlled release (a stage's -stage_<s>_release): from the committed time t0 to t1 the
   tool is driven by force along the axes in which it carries more than 1e-3 of its force (holding
   its position along the others), the target going linearly from the force it exerts now
   (committed) to zero; it needs unknowns (ContactReserveToolUnknowns before the setup). The release
   is part of the tools' checkpoint. */
PetscErrorCode ContactReleaseTool(Contact c, PetscInt tool, PetscReal t0, PetscReal t1);
/* Release by nodal forces (-stage_<s>_release_mode nodes): the contact force each node carries
   from the tool in the committed state becomes a dead load on it, falling linearly from its value
   at t0 to zero at t1; the tool is removed at once (it pairs no node), its force-driven directions
   held where they are. The nodes' loads are part of the contact checkpoint rows; the tool's result
   (ContactGetToolResult) reports what they still exert. */
PetscErrorCode ContactReleaseToolNodes(Contact c, PetscInt tool, PetscReal t0, PetscReal t1);
/* a tool present or absent in the current stage (stage.h: an absent tool pairs no node; its nodes'
   states become "no contact") */
PetscErrorCode ContactSetToolPresent(Contact c, PetscInt t, PetscBool present);
/* per direction: driven by force, and the target force at time t (0 where not driven) */
PetscErrorCode ContactGetToolTarget(Contact c, PetscInt tool, PetscReal t, PetscBool driven[3], PetscReal F[3]);
/* before ContactSetUp: give the tool its unknowns although no direction is force-driven yet */
PetscErrorCode ContactReserveToolUnknowns(Contact c, PetscInt tool);
/* the first breakpoint after t of the force curves (amplitudes) of the force-driven directions
   (PETSC_INFINITY if none), for the load stepper to land on */
PetscReal      ContactNextKink(Contact c, PetscReal t);
/* 3 x the number of tools with unknowns (0: no tool is force-driven; then nothing below applies) */
PetscInt       ContactNumToolUnknowns(Contact c);
/* the global index of the first tool unknown (they follow the body's) and whether this rank owns
   them; before the first assembly */
PetscErrorCode ContactSetToolDofs(Contact c, PetscInt first, PetscBool owner);
/* the current values of the tool unknowns (3 per tool with unknowns, the same on every rank),
   before an evaluation */
PetscErrorCode ContactSetToolUnknowns(Contact c, const PetscReal *d);
/* after ContactAssemble at the same iterate: the residual rows of the tool unknowns (all ranks,
   collective): along a force-driven direction the force the tool exerts on the body minus the
   target, along another the unknown minus the prescribed displacement */
PetscErrorCode ContactToolResidual(Contact c, PetscReal lambda, PetscReal *r);
/* checkpoint of the tools' committed state (replicated): ContactToolCheckpointWidth() values */
PetscInt       ContactToolCheckpointWidth(Contact c);
PetscErrorCode ContactToolCheckpointPack(Contact c, PetscReal *v);
PetscErrorCode ContactToolCheckpointUnpack(Contact c, const PetscReal *v);
/* -contact_* options and the tools (-tool_names, -tool_<name>_*) */
PetscErrorCode ContactSetFromOptions(Contact c);
/* the sets whose nodes need a tributary area (-contact_penalty_per_area), else n = 0 */
PetscErrorCode ContactGetAreaSets(Contact c, PetscInt *n, char (**sets)[ATRITO_NAME_LEN]);
/* the body's Young's modulus, for the automatic penalty (-contact_penalty_normal auto); before SetUp */
PetscErrorCode ContactSetYoungModulus(Contact c, PetscReal E);
PetscErrorCode ContactSetUp(Contact c, const Mesh *m);
PetscErrorCode ContactDestroy(Contact *c);
PetscInt       ContactNumTools(Contact c);
/* contact pairs between deformable bodies (contact_pair.h), owned by the contact object: their
   number, the object (for their results), and the node sets whose boundary faces they need from
   the mesh (MeshSetFaceSets, before MeshCreate) */
PetscInt       ContactNumPairs(Contact c);
struct _p_ContactPairs *ContactGetPairs(Contact c);
PetscErrorCode ContactGetFaceSets(Contact c, PetscInt *n, char (**sets)[ATRITO_NAME_LEN]);
/* with several bodies (body.h), before ContactSetUp: the Young's modulus of each local cell's
   material, for the pairs' automatic penalties (copied; without it the body's, ContactSetYoungModulus) */
PetscErrorCode ContactSetCellModuli(Contact c, PetscInt nc, const PetscReal *Ec);
/* owned slave nodes on this rank */
PetscInt       ContactNumSlaves(Contact c);

/* frame seeds: from the committed frames (start of a step or a retry) or by eq 30 from the frames
   at the local displacements u (with boundary values; start of a Newton iteration) */
PetscErrorCode ContactSeed(Contact c, const PetscScalar *u, PetscReal lambda, PetscBool from_committed);
/* contributions at u: residual into f (local, may be NULL), tangent into J (MatSetValues) or into
   coo_v (coordinate assembly, in the order of ContactGetCOO); *nfail: failed projections. With
   tool unknowns the tangent includes their rows and columns, and the call is collective. */
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
/* the tools' augmentation alone (-contact_augmented with tools): it sets other defaults */
PetscBool      ContactToolsAugmented(Contact c);
PetscInt       ContactAugmentedMax(Contact c);
PetscErrorCode ContactAugment(Contact c, PetscBool inexact, PetscBool *converged, PetscBool *held, PetscReal *maxpen, PetscReal *dlambda);
/* the start of a step's augmentation, after ContactSeed from the committed state: the penalties'
   factor the step starts from (the committed one with -contact_augmented_growth_keep), and the
   relative residual eta at which a solve is followed by an update (-contact_augmented_inexact; 0:
   every solve fully converged, and always 0 without augmentation) */
PetscErrorCode ContactAugmentStart(Contact c, PetscReal *inexact);
PetscErrorCode ContactAugmentTolerances(Contact c, PetscReal *tol, PetscReal *mtol);
PetscErrorCode ContactAugmentSoften(Contact c, PetscBool *softened, PetscReal *factor);
/* the contact status and normal force of every slave node at the current iterate */
PetscErrorCode ContactRecordActive(Contact c);
/* The predictor of a step, made consistent with the committed contact: every node pressed in the
   committed state on a present tool at rest or driven by force (not on one the step moves by a
   prescribed displacement: the extrapolation moves the whole body with it) is moved along the tool's normal at the
   predicted position (u: local, with boundary values) until its gap is the committed one; the
   correction is added to the global U (constrained components dropped), and skipped where it
   exceeds a tenth of the element size normal to the contact face. Collective. */
PetscErrorCode ContactProjectPressed(Contact c, const PetscScalar *u, PetscReal lambda, Vec U, PetscInt *nmoved, PetscReal *dmax);
/* The longest step x - lambda Y (Y global, as SNES's update) that carries no slave node paired with a
   tool at the iterate (u: local, with boundary values; ytool: the tool unknowns' part of Y) deeper than depth times the element size
   normal to the contact face into it, linearised along the tool's normal (PETSC_MAX_REAL: no
   limit). Collective. */
PetscErrorCode ContactStepLimit(Contact c, const PetscScalar *u, PetscReal lambda, Vec Y, const PetscReal *ytool, PetscReal depth, PetscReal *lmax);
/* per tool, what the last evaluation changed against ContactRecordActive's state (collective) */
typedef struct {
  PetscInt  nin, nout;  /* nodes that entered and left contact with the tool */
  PetscReal fchange;    /* the largest normal force among them (before leaving, after entering) */
  PetscInt  nactive;    /* nodes in contact now */
  PetscInt  nslip;      /* nodes in contact before and now that changed between stick and slip */
  PetscReal pen, fmax;  /* the largest penetration and normal force now */
  PetscReal penh;       /* the largest penetration now over the node's element size normal to the face */
} ContactToolStatus;
/* The contact's part of the last Jacobian, for an active-set correction of the Newton step
   (src/solver/activeset.c). ContactLinearRelease: this rank's slave nodes in contact by the law at
   that Jacobian (not held, not flagged in released[ns]) whose normal force, linearised along the
   step x - Y (ytool: the tool unknowns' part of Y, NULL without), is a pull stronger than tmin;
   their local indices into idx[ns]. ContactLinearBlock: slave node i's contribution to that
   Jacobian and residual on its unknowns (its free components, then its tool's force-driven
   directions; at most 6): the global indices dof[nd], the block M (row-major, leading dimension
   6) and the residual r. */
PetscErrorCode ContactLinearRelease(Contact c, Vec Y, const PetscReal *ytool, PetscReal tmin, const char *released, PetscInt *n, PetscInt *idx);
PetscErrorCode ContactLinearBlock(Contact c, PetscInt i, PetscInt *nd, PetscInt dof[6], PetscReal M[36], PetscReal r[6]);
PetscErrorCode ContactStatusChanges(Contact c, ContactToolStatus *ts);
/* nodes that entered or left contact in the last Newton iteration with a significant normal
   force (before or after: above 1e-3 of the largest normal force of the committed state and the
   last two iterates, and above fmin, the Newton solve's tolerance); count over all ranks and the
   smallest node id */
PetscErrorCode ContactChatter(Contact c, PetscReal fmin, PetscInt *count, PetscInt *node);
/* keep 1 (nodes on frictionless tools), 2 (and on the frictional tools that the step moves by a
   prescribed displacement) or 3 (and on the frictional tools at rest in the step; never a
   force-driven tool's): every such node pressed in the committed state (in contact with a normal
   force) and paired with the same tool now is closed whatever its gap, below the tool as always,
   off it with the normal force continued linearly, t_N = lN - K_N g < 0 (bilateral), until it is
   ended (0: off; the stepper ends it before the first line search).
   With 2 and 3, a held node on a frictional tool keeps the friction of its committed force (the
   cone mu t_N,committed, whatever the gap) and is held tangentially by a spring K_T (I - n n^T)
   anchored at its position when the frame seeds were last set (the predictor), and a node not
   pressed on its tool in the committed state (entering contact) has no friction until the keep
   ends. */
PetscErrorCode ContactKeepCommitted(Contact c, PetscInt keep);
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
