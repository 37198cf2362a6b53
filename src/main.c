/* atrito driver: wires the modules together; no physics here.
   mpiexec -n N bin/atrito -options_file cases/X.opts [-option value ...] */
#include <stdio.h>
#include <string.h>
#include "atrito.h"

static const char help[] = "atrito: parallel finite-strain elasto-plastic solver with frictional contact.\n"
                           "Run with -options_file cases/<case>.opts; -help lists the options.\n";

/* One line per error: the message of the error where it was raised, printed once (by rank 0 of
   the communicator it was raised on). -atrito_traceback keeps PETSc's full traceback instead. */
static PetscErrorCode OneLineErrorHandler(MPI_Comm comm, int line, const char *fun, const char *file, PetscErrorCode n, PetscErrorType p, const char *mess, void *ctx)
{
  if (p == PETSC_ERROR_INITIAL) {
    PetscMPIInt rank = 0, wrank = 0, wsize = 1;
    if (comm != MPI_COMM_NULL) MPI_Comm_rank(comm, &rank);
    MPI_Comm_rank(MPI_COMM_WORLD, &wrank);
    MPI_Comm_size(MPI_COMM_WORLD, &wsize);
    if (rank == 0) {
      if (wsize > 1 && comm == PETSC_COMM_SELF) fprintf(stderr, "atrito: error on rank %d: %s\n", wrank, mess ? mess : "(no message)");
      else fprintf(stderr, "atrito: error: %s\n", mess ? mess : "(no message)");
      fflush(stderr);
    }
  }
  return n;
}

static PetscErrorCode Run(void)
{
  Case    cs;
  Problem pb;

  PetscFunctionBeginUser;
  PetscCall(PetscMemzero(&pb, sizeof(pb)));
  pb.comm = PETSC_COMM_WORLD;
  PetscCallMPI(MPI_Comm_rank(pb.comm, &pb.rank));
  PetscCallMPI(MPI_Comm_size(pb.comm, &pb.size));
  PetscLogStage stage_mesh, stage_setup, stage_solve;
  PetscCall(PetscLogStageRegister("Mesh", &stage_mesh));
  PetscCall(PetscLogStageRegister("Setup", &stage_setup));
  PetscCall(PetscLogStageRegister("Solve", &stage_solve));
  PetscCall(CaseRead(pb.comm, &cs));
  pb.cs = &cs;
  PetscCall(PetscLogStagePush(stage_mesh));
  PetscCall(ProblemCreateMesh(&pb));
  PetscCall(PetscLogStagePop());
  PetscCall(PetscLogStagePush(stage_setup));
  PetscCall(ProblemSetUp(&pb));
  PetscCall(PetscLogStagePop());
  PetscCall(PetscLogStagePush(stage_solve));
  PetscCall(ProblemSolve(&pb));
  PetscCall(PetscLogStagePop());
  PetscCall(ProblemDestroy(&pb));
  PetscFunctionReturn(0);
}

/* A misspelt option must not pass silently */
static PetscErrorCode ReportUnusedOptions(void)
{
  PetscInt N;
  char   **names, **values;

  PetscFunctionBeginUser;
  PetscCall(PetscOptionsLeftGet(NULL, &N, &names, &values));
  for (PetscInt i = 0; i < N; i++) PetscCall(PetscPrintf(PETSC_COMM_WORLD, "WARNING: option -%s%s%s was set but never used (misspelt?)\n", names[i], values[i] ? " " : "", values[i] ? values[i] : ""));
  PetscCall(PetscOptionsLeftRestore(NULL, &N, &names, &values));
  PetscFunctionReturn(0);
}

int main(int argc, char **argv)
{
  PetscErrorCode ierr;
  PetscBool      traceback = PETSC_FALSE;

  /* a missing options file is reported before PETSc starts */
  for (int i = 1; i < argc - 1; i++)
    if (!strcmp(argv[i], "-options_file")) {
      FILE *fp = fopen(argv[i + 1], "r");
      if (!fp) {
        fprintf(stderr, "atrito: error: cannot open options file '%s'\n", argv[i + 1]);
        return 1;
      }
      fclose(fp);
    }
  ierr = PetscInitialize(&argc, &argv, NULL, help);
  if (ierr) return 1;
  PetscOptionsGetBool(NULL, NULL, "-atrito_traceback", &traceback, NULL);
  if (!traceback) PetscPushErrorHandler(OneLineErrorHandler, NULL);
  ierr = Run();
  if (!ierr) ierr = ReportUnusedOptions();
  if (!traceback) PetscPopErrorHandler();
  PetscFinalize();
  return ierr ? 1 : 0;
}
