/* Stages of the process: -stage_names a,b,... follow each other in process time, each with its
   duration, its first and largest increment, the tools present and the Dirichlet conditions
   active in it, the tools it releases by force (-stage_<s>_duration, _steps, _dt_max, _tools,
   _bcs, _release, _release_mode: each released tool driven by its falling force, or removed and
   its nodal forces falling; _predictor: the start of its steps, default -load_predictor). Without -stage_names the
   process is one stage, "load", of duration 1: the process time is the load parameter of the
   -load_* options. Options only; the stepper enters the stages (stepper.c). */
#ifndef ATRITO_STAGE_H
#define ATRITO_STAGE_H
#include "bc.h"
#include "contact.h"
#include "tool.h"

#define STAGE_MAX 32
#define STAGE_MAX_TOOLS 64

/* how a stage releases its tools: the tool driven by force, the target falling to zero
   (ContactReleaseTool), or removed at the stage's start and its nodal forces falling to zero
   (ContactReleaseToolNodes) */
enum { STAGE_RELEASE_TOOL = 0, STAGE_RELEASE_NODES = 1 };

typedef struct {
  char      name[64];
  PetscReal t0, t1;                /* start and end in process time                         */
  PetscReal dt0, dt_max, dt_min;   /* first, largest and smallest increment                 */
  PetscInt  ntools, nbcs;          /* -1: all (the default); else how many are listed        */
  char      tools[STAGE_MAX_TOOLS][64], bcs[ATRITO_MAX_BC][64]; /* as listed ("none": empty) */
  PetscBool tool_on[STAGE_MAX_TOOLS], bc_on[ATRITO_MAX_BC];      /* after StagesSetUp        */
  PetscInt  nrelease;              /* -stage_<s>_release: tools released by force (<= 0: none) */
  char      release[STAGE_MAX_TOOLS][64];
  PetscInt  release_mode;          /* -stage_<s>_release_mode: STAGE_RELEASE_TOOL or _NODES       */
  PetscBool tool_release[STAGE_MAX_TOOLS];                        /* after StagesSetUp        */
  PetscInt  predictor;             /* -stage_<s>_predictor: a Predictor (stepper.h), or -1: -load_predictor */
} Stage;

typedef struct {
  PetscInt  n;       /* >= 1                                   */
  PetscBool given;   /* -stage_names was given                 */
  PetscReal T;       /* total process time                     */
  Stage     s[STAGE_MAX];
} Stages;

/* -stage_names and the per-stage options; the defaults of the increments from the -load_*
   options (steps, and dt_max, dt_min as fractions of a stage's duration) */
PetscErrorCode StagesSetFromOptions(MPI_Comm comm, Stages *sg, PetscInt load_steps, PetscReal dt_max, PetscReal dt_min);
/* the names of -stage_<s>_tools and _bcs against the tools and conditions of the case (one-line
   errors naming the option); marks the conditions that some stage leaves inactive (not section
   constraints: bc.h) and gives the total time to the conditions and tools; the tools a stage
   releases by tool get their unknowns (before the contact set-up); a tool removed while a force still
   drives it is refused */
PetscErrorCode StagesSetUp(Stages *sg, BCs *bcs, Contact contact);
/* defined in src/contact/contact.c: read access to tool t (a tool present or absent in the current
   stage: ContactSetToolPresent, contact.h) */
PetscErrorCode ContactGetTool(Contact c, PetscInt t, const Tool **tool);
/* the stage the step after the committed time t belongs to (a time on a stage end: the next) */
PetscInt StageAt(const Stages *sg, PetscReal t);
#endif
