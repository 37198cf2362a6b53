/* Results of a run, in -output_dir: history.csv (one row per converged step: process time, Newton
   iterations, residual norms, the reactions of the boundary conditions on their constrained
   components, the stage), contact.csv (one row per step and tool), fields.h5 + fields.xmf (every
   -output_interval steps) and checkpoint.h5 (every -checkpoint_interval steps; -restart continues
   a run). Every file is written by rank 0 or collectively; rows are written whole and flushed. */
#ifndef ATRITO_RESULTS_H
#define ATRITO_RESULTS_H
#include "problem.h"
#include "output.h"

typedef struct {
  /* options */
  char      dir[PETSC_MAX_PATH_LEN];
  PetscInt  interval;              /* fields every N converged steps (0: none)           */
  PetscInt  checkpoint_interval;   /* DIR/checkpoint.h5 every N steps (0: none)          */
  char      restart[PETSC_MAX_PATH_LEN];
  PetscBool thickness;             /* thickness strain field                             */
  PetscBool thickness_set;
  PetscReal thickness_dir[3];      /* reference sheet normal                             */
  /* files */
  FILE        *hist, *chist;
  OutputFields of;
  PetscLogEvent ev_output;
} Results;

typedef struct {
  PetscInt  step, total_its, total_cuts, stage; /* stage: the index of the last step's stage */
  PetscReal lambda, dl, dl_prev;
  Vec       hold; /* the bases of the holding conditions (bc.h; NULL: none), written and read */
  /* the converged state before the previous one and its increment, for the predictor's curvature
     term (-load_predictor_curvature): written when prev2 is set and dl_prev2 > 0; read into
     prev2 when it is set and the checkpoint has them (dl_prev2 0 otherwise: the first step after
     the restart extrapolates linearly) */
  Vec       prev2;
  PetscReal dl_prev2;
} CheckpointInfo;

PetscErrorCode ResultsSetFromOptions(MPI_Comm comm, Results *res);
/* opens the files: new ones, or on restart (ci from the checkpoint) those of the run continued,
   truncated to its step; writes the mesh and, at a fresh start, the fields of step 0 */
PetscErrorCode ResultsOpen(Results *res, Problem *pb, const CheckpointInfo *ci);
/* the rows of a converged step, and its fields when due */
PetscErrorCode ResultsWriteStep(Results *res, Problem *pb, PetscInt step, PetscReal time, PetscInt its, PetscReal r0, PetscReal r, PetscBool last, const char *stage);
PetscErrorCode ResultsClose(Results *res);

/* history.c */
PetscErrorCode HistoryOpen(Results *res, Problem *pb, PetscBool append);
PetscErrorCode HistoryWrite(Results *res, Problem *pb, PetscInt step, PetscReal time, PetscInt its, PetscReal r0, PetscReal r, const char *stage);
PetscErrorCode ContactHistoryOpen(Results *res, Problem *pb, PetscBool append);
PetscErrorCode ContactHistoryWrite(Results *res, Problem *pb, PetscInt step, PetscReal time, PetscInt its, const char *stage);
/* restart: keep the header and the rows of steps <= step of DIR/name; whether it existed */
PetscErrorCode HistoryTruncate(MPI_Comm comm, const char *dir, const char *name, PetscInt step, PetscBool *existed);

/* fields.c */
PetscErrorCode FieldsWriteMesh(Results *res, Problem *pb);
PetscErrorCode FieldsWriteStep(Results *res, Problem *pb, PetscInt step, PetscReal time);

/* checkpoint.c */
PetscErrorCode CheckpointWrite(Results *res, Problem *pb, const CheckpointInfo *ci);
PetscErrorCode CheckpointRead(Problem *pb, const char *path, CheckpointInfo *ci);
#endif
