/* The results of a run (results.h): options, opening (fresh or continued after a restart), the
   rows and fields of every converged step, closing. */
#include <stdio.h>
#include "results.h"
#include "options.h"

PetscErrorCode ResultsSetFromOptions(MPI_Comm comm, Results *res)
{
  PetscReal v3[3];
  PetscInt  n;
  PetscBool set;

  PetscFunctionBeginUser;
  PetscCall(PetscMemzero(res, sizeof(*res)));
  res->interval = 1;
  PetscCall(PetscStrncpy(res->dir, "out", sizeof(res->dir)));
  PetscCall(PetscLogEventRegister("AtritoOutput", DM_CLASSID, &res->ev_output));
  PetscOptionsBegin(comm, NULL, "Results: histories, fields, checkpoints", NULL);
    PetscCall(PetscOptionsString("-output_dir", "Output directory", NULL, res->dir, res->dir, sizeof(res->dir), NULL));
    PetscCall(PetscOptionsInt("-output_interval", "Write fields every N converged steps (0: never)", NULL, res->interval, &res->interval, NULL));
    PetscCheck(res->interval >= 0, comm, PETSC_ERR_USER_INPUT, "-output_interval %" PetscInt_FMT " must be >= 0", res->interval);
    PetscCall(PetscOptionsInt("-checkpoint_interval", "Write DIR/checkpoint.h5 every N converged steps and at the end (0: never)", NULL, res->checkpoint_interval, &res->checkpoint_interval, NULL));
    PetscCheck(res->checkpoint_interval >= 0, comm, PETSC_ERR_USER_INPUT, "-checkpoint_interval %" PetscInt_FMT " must be >= 0", res->checkpoint_interval);
    PetscCall(PetscOptionsString("-restart", "Continue from this checkpoint (same case; any number of ranks)", NULL, res->restart, res->restart, sizeof(res->restart), NULL));
    v3[0] = 0;
    v3[1] = 0;
    v3[2] = 1;
    n     = 3;
    PetscCall(PetscOptionsRealArray("-output_thickness_direction", "Reference sheet normal: enables the thickness strain field", NULL, v3, &n, &set));
    if (set) {
      PetscReal nrm;
      PetscCheck(n == 3, comm, PETSC_ERR_USER_INPUT, "-output_thickness_direction needs 3 values");
      nrm = PetscSqrtReal(v3[0] * v3[0] + v3[1] * v3[1] + v3[2] * v3[2]);
      PetscCheck(nrm > 0 && PetscIsNormalReal(nrm), comm, PETSC_ERR_USER_INPUT, "-output_thickness_direction must be a nonzero vector");
      for (int k = 0; k < 3; k++) v3[k] /= nrm;
      res->thickness_set = PETSC_TRUE;
    }
    for (int k = 0; k < 3; k++) res->thickness_dir[k] = v3[k];
  PetscOptionsEnd();
  PetscFunctionReturn(0);
}

PetscErrorCode ResultsOpen(Results *res, Problem *pb, const CheckpointInfo *ci)
{
  const Mesh *m = pb->mesh;

  PetscFunctionBeginUser;
  /* the thickness strain: asked for, or by default for the built-in blank (normal +z) */
  res->thickness = (res->thickness_set || m->opt.source == MESH_BLANK) ? PETSC_TRUE : PETSC_FALSE;
  PetscCall(OutputEnsureDirectory(pb->comm, res->dir));
  if (ci) {
    /* continue: the histories and fields keep what was written up to the checkpoint's step and
       go on from there */
    PetscBool hexist, cexist;
    PetscCall(HistoryTruncate(pb->comm, res->dir, "history.csv", ci->step, &hexist));
    PetscCall(HistoryTruncate(pb->comm, res->dir, "contact.csv", ci->step, &cexist));
    PetscCall(HistoryOpen(res, pb, hexist));
    PetscCall(ContactHistoryOpen(res, pb, cexist));
    if (res->interval > 0) {
      char h5[PETSC_MAX_PATH_LEN];
      int  ex = 0;
      PetscCall(PetscSNPrintf(h5, sizeof(h5), "%s/fields.h5", res->dir));
      if (!pb->rank) {
        FILE *fp = fopen(h5, "r");
        ex       = fp != NULL;
        if (fp) fclose(fp);
      }
      PetscCallMPI(MPI_Bcast(&ex, 1, MPI_INT, 0, pb->comm));
      if (ex) PetscCall(OutputFieldsReopen(pb->comm, res->dir, ci->step, m->rv.nb, m->rv.off, m->rc.nb, m->rc.off, &res->of));
      else {
        PetscCall(OutputFieldsCreate(pb->comm, res->dir, &res->of));
        PetscCall(FieldsWriteMesh(res, pb));
      }
    }
  } else {
    PetscCall(HistoryOpen(res, pb, PETSC_FALSE));
    PetscCall(ContactHistoryOpen(res, pb, PETSC_FALSE));
    if (res->interval > 0) {
      PetscCall(OutputFieldsCreate(pb->comm, res->dir, &res->of));
      PetscCall(FieldsWriteMesh(res, pb));
      PetscCall(FieldsWriteStep(res, pb, 0, 0.0));
    }
  }
  PetscFunctionReturn(0);
}

PetscErrorCode ResultsWriteStep(Results *res, Problem *pb, PetscInt step, PetscReal lambda, PetscInt its, PetscReal r0, PetscReal r, PetscBool last, const char *stage)
{
  PetscFunctionBeginUser;
  PetscCall(HistoryWrite(res, pb, step, lambda, its, r0, r, stage));
  if (ContactNumTools(pb->contact) || ContactNumPairs(pb->contact)) PetscCall(ContactHistoryWrite(res, pb, step, lambda, its, stage)); /* collective: every rank */
  if (res->of && (step % res->interval == 0 || last)) PetscCall(FieldsWriteStep(res, pb, step, lambda));
  PetscFunctionReturn(0);
}

PetscErrorCode ResultsClose(Results *res)
{
  PetscFunctionBeginUser;
  if (res->hist) fclose(res->hist);
  if (res->chist) fclose(res->chist);
  res->hist = res->chist = NULL;
  PetscCall(OutputFieldsDestroy(&res->of));
  PetscFunctionReturn(0);
}
