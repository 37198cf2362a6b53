/* The CSV histories of a run (results.h), written by rank 0 in whole rows, flushed after each:
   a killed run leaves readable files.

   history.csv: step, time (the process time; without stages the load parameter), newton_its,
   residual_initial, residual_final, then for every boundary condition and every component it
   constrains, <name>_f<x|y|z>: its reaction, the force its supports exert on the body (bc.h; zero
   up to the Newton tolerance while a stage leaves the condition inactive), and last stage (the
   name of the step's stage; "load" without stages).

   contact.csv, one row per step and tool: step, time, tool, travel (the displacement along the
   tool's direction: its -motion vector, or the displacement at the last point of its -path, +z
   for a fixed tool), force (the force the tool exerts
   on the modelled part along that direction), force_full (times -model_symmetry), newton_its,
   active (nodes pressed against the tool), stick, slip (of those; counted with friction only),
   max_penetration, then dx, dy, dz (the tool's displacement), path_length (travelled along its
   path), fx, fy, fz (the resultant force the tool exerts on the modelled part), force_normal and
   force_tangential (magnitudes of the normal and friction resultants), mean_penetration (of the
   pressed nodes), augmentations (Newton solves of the step with -contact_augmented, 0 without)
   and multiplier_change (the largest change of a nodal multiplier in the step's last update), and
   last stage (as in history.csv). */
#include "contact_pair.h"
#include <stdio.h>
#include <string.h>
#include "results.h"
#include "util.h"

static const char comp_name[3] = {'x', 'y', 'z'};

static PetscErrorCode CsvOpen(Results *res, Problem *pb, const char *name, PetscBool append, FILE **fp)
{
  char path[PETSC_MAX_PATH_LEN];

  PetscFunctionBeginUser;
  PetscCall(PetscSNPrintf(path, sizeof(path), "%s/%s", res->dir, name));
  PetscCall(AtritoFileOpenRoot(pb->comm, path, append ? "a" : "w", "-output_dir", fp));
  PetscFunctionReturn(0);
}

PetscErrorCode HistoryOpen(Results *res, Problem *pb, PetscBool append)
{
  const BCs *bcs = pb->bcs;

  PetscFunctionBeginUser;
  PetscCall(CsvOpen(res, pb, "history.csv", append, &res->hist));
  if (pb->rank || append) PetscFunctionReturn(0);
  fprintf(res->hist, "step,time,newton_its,residual_initial,residual_final");
  for (PetscInt b = 0; b < bcs->n; b++)
    for (int c = 0; c < 3; c++)
      for (PetscInt k = 0; k < bcs->bc[b].ncomp; k++)
        if (bcs->bc[b].comp[k] == c) fprintf(res->hist, ",%s_f%c", bcs->bc[b].name, comp_name[c]);
  fprintf(res->hist, ",stage\n");
  fflush(res->hist);
  PetscFunctionReturn(0);
}

PetscErrorCode HistoryWrite(Results *res, Problem *pb, PetscInt step, PetscReal time, PetscInt its, PetscReal r0, PetscReal r, const char *stage)
{
  const BCs *bcs = pb->bcs;
  PetscReal  R[ATRITO_MAX_BC][3];
  char       line[64 * (3 * ATRITO_MAX_BC + 8)];
  size_t     len = 0;

  PetscFunctionBeginUser;
  PetscCall(BCReactions(bcs, pb->mesh, pb->Floc, R));
  if (pb->rank) PetscFunctionReturn(0);
  /* format the whole row first, then write it at once: a killed run leaves whole rows */
  len += snprintf(line + len, sizeof(line) - len, "%" PetscInt_FMT ",%.12g,%" PetscInt_FMT ",%.6e,%.6e", step, (double)time, its, (double)r0, (double)r);
  for (PetscInt b = 0; b < bcs->n; b++)
    for (int c = 0; c < 3; c++)
      for (PetscInt k = 0; k < bcs->bc[b].ncomp; k++)
        if (bcs->bc[b].comp[k] == c) len += snprintf(line + len, sizeof(line) - len, ",%.12e", (double)R[b][c]);
  len += snprintf(line + len, sizeof(line) - len, ",%s\n", stage);
  fwrite(line, 1, len, res->hist);
  fflush(res->hist);
  PetscFunctionReturn(0);
}

PetscErrorCode ContactHistoryOpen(Results *res, Problem *pb, PetscBool append)
{
  PetscFunctionBeginUser;
  res->chist = NULL;
  if (!ContactNumTools(pb->contact) && !ContactNumPairs(pb->contact)) PetscFunctionReturn(0);
  PetscCall(CsvOpen(res, pb, "contact.csv", append, &res->chist));
  if (pb->rank) PetscFunctionReturn(0);
  if (!append) fprintf(res->chist, "step,time,tool,travel,force,force_full,newton_its,active,stick,slip,max_penetration,dx,dy,dz,path_length,fx,fy,fz,force_normal,force_tangential,mean_penetration,augmentations,multiplier_change,stage\n");
  fflush(res->chist);
  PetscFunctionReturn(0);
}

PetscErrorCode ContactHistoryWrite(Results *res, Problem *pb, PetscInt step, PetscReal time, PetscInt its, const char *stage)
{
  PetscFunctionBeginUser;
  for (PetscInt t = 0; t < ContactNumTools(pb->contact); t++) {
    ContactToolResult r;
    PetscCall(ContactGetToolResult(pb->contact, t, time, &r));
    if (!pb->rank) {
      char      line[1024];
      const int len = snprintf(line, sizeof(line), "%" PetscInt_FMT ",%.12g,%s,%.12g,%.12e,%.12e,%" PetscInt_FMT ",%d,%d,%d,%.6e,%.12g,%.12g,%.12g,%.12g,%.12e,%.12e,%.12e,%.12e,%.12e,%.6e,%d,%.6e,%s\n", step, (double)time, r.name, r.travel, r.force, r.force * (double)ContactSymmetry(pb->contact), its, (int)r.active, (int)r.stick, (int)r.slip, r.max_pen, r.shift[0], r.shift[1], r.shift[2], r.path, r.f[0], r.f[1], r.f[2], r.fn, r.ft, r.mean_pen, (int)r.augmentations, r.dlambda, stage);
      fwrite(line, 1, (size_t)len, res->chist);
      fflush(res->chist);
    }
  }
  /* a contact pair between bodies: its name as the tool's; force the sum of the slave nodes'
     normal forces, f the resultant on the slave set; no travel, path or multipliers */
  for (PetscInt k = 0; k < ContactNumPairs(pb->contact); k++) {
    ContactPairResult r;
    PetscCall(ContactPairsGetResult(ContactGetPairs(pb->contact), k, &r));
    if (!pb->rank) {
      char      line[1024];
      const int len = snprintf(line, sizeof(line), "%" PetscInt_FMT ",%.12g,%s,0,%.12e,%.12e,%" PetscInt_FMT ",%d,%d,%d,%.6e,0,0,0,0,%.12e,%.12e,%.12e,%.12e,%.12e,0,0,0,%s\n", step, (double)time, r.name, r.fn, r.fn * (double)ContactSymmetry(pb->contact), its, (int)r.active, (int)r.stick, (int)r.slip, r.max_pen, r.f[0], r.f[1], r.f[2], r.fn, r.ft, stage);
      fwrite(line, 1, (size_t)len, res->chist);
      fflush(res->chist);
    }
  }
  PetscFunctionReturn(0);
}

/* Restart: keep the header and the rows of steps <= step of a CSV history, rewritten atomically
   (rank 0); returns whether the file existed. */
PetscErrorCode HistoryTruncate(MPI_Comm comm, const char *dir, const char *name, PetscInt step, PetscBool *existed)
{
  char        path[PETSC_MAX_PATH_LEN], tmp[PETSC_MAX_PATH_LEN], line[65536];
  FILE       *in, *out;
  int         ex = 0, ok = 1;
  PetscMPIInt rank;

  PetscFunctionBeginUser;
  PetscCallMPI(MPI_Comm_rank(comm, &rank));
  PetscCall(PetscSNPrintf(path, sizeof(path), "%s/%s", dir, name));
  PetscCall(PetscSNPrintf(tmp, sizeof(tmp), "%s.tmp", path));
  if (!rank) {
    in = fopen(path, "r");
    if (in) {
      ex  = 1;
      out = fopen(tmp, "w");
      if (out) {
        if (fgets(line, sizeof(line), in)) fputs(line, out); /* header */
        while (fgets(line, sizeof(line), in)) {
          size_t len = strlen(line);
          if (len == 0 || line[len - 1] != '\n') break; /* a partial last row of a killed run */
          if (atol(line) <= (long)step) fputs(line, out);
        }
        fclose(out);
        ok = !rename(tmp, path);
      } else ok = 0;
      fclose(in);
    }
  }
  PetscCallMPI(MPI_Bcast(&ok, 1, MPI_INT, 0, comm));
  PetscCheck(ok, comm, PETSC_ERR_FILE_WRITE, "cannot rewrite '%s' (through '%s') for the restart", path, tmp);
  PetscCallMPI(MPI_Bcast(&ex, 1, MPI_INT, 0, comm));
  *existed = ex ? PETSC_TRUE : PETSC_FALSE;
  PetscFunctionReturn(0);
}
