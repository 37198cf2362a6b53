/* atrito driver: wires the modules together; no physics here.
   mpiexec -n N bin/atrito -options_file cases/X.opts [-option value ...] */
#include <stdio.h>
#include <string.h>
#include "mesh.h"
#include "bc.h"
#include "contact.h"
#include "material.h"
#include "element.h"
#include "problem.h"
#include "body.h"
#include "stepper.h"
#include "results.h"
#include "options.h"

static const char help[] = "atrito: parallel finite-strain elasto-plastic solver with frictional contact.\n"
                           "usage: mpiexec -n N bin/atrito -options_file cases/<case>.opts [-option value ...]\n";

/* One line per error: the message of the error where it was raised, printed once (by rank 0 of
   the communicator it was raised on). An error that PETSc's options functions raise on
   PETSC_COMM_SELF (an unknown value of a list option) is raised alike on every rank, since every
   rank holds the same options: it is printed by rank 0 of the world alone. -atrito_traceback keeps
   PETSc's full traceback instead. */
static PetscErrorCode OneLineErrorHandler(MPI_Comm comm, int line, const char *fun, const char *file, PetscErrorCode n, PetscErrorType p, const char *mess, void *ctx)
{
  if (p == PETSC_ERROR_INITIAL) {
    PetscMPIInt     rank = 0, wrank = 0, wsize = 1;
    const PetscBool replicated = (comm == PETSC_COMM_SELF && fun && !strncmp(fun, "PetscOptions", 12)) ? PETSC_TRUE : PETSC_FALSE;
    if (comm != MPI_COMM_NULL) MPI_Comm_rank(comm, &rank);
    MPI_Comm_rank(MPI_COMM_WORLD, &wrank);
    MPI_Comm_size(MPI_COMM_WORLD, &wsize);
    if (replicated) {
      if (wrank == 0) {
        fprintf(stderr, "atrito: error: %s\n", mess ? mess : "(no message)");
        fflush(stderr);
      }
    } else if (rank == 0) {
      if (wsize > 1 && comm == PETSC_COMM_SELF) fprintf(stderr, "atrito: error on rank %d: %s\n", wrank, mess ? mess : "(no message)");
      else fprintf(stderr, "atrito: error: %s\n", mess ? mess : "(no message)");
      fflush(stderr);
    }
  }
  return n;
}

/* -memory_phases: the memory in use after a phase of the setup, summed over the ranks: PetscMalloc()ed
   (counted with -log_view_memory or -malloc_debug, else 0) and the resident set size (doc/notes/performance-log.md,
   "Memory") */
static PetscErrorCode MemoryPhase(MPI_Comm comm, PetscBool on, const char *phase, Mat J)
{
  PetscLogDouble v[2] = {0, 0};
  PetscBool      aij  = PETSC_FALSE;

  PetscFunctionBeginUser;
  if (!on) PetscFunctionReturn(0);
  PetscCall(PetscMallocGetCurrentUsage(&v[0]));
  PetscCall(PetscMemoryGetCurrentUsage(&v[1]));
  PetscCall(MPIU_Allreduce(MPI_IN_PLACE, v, 2, MPIU_PETSCLOGDOUBLE, MPI_SUM, comm));
  PetscCall(PetscPrintf(comm, "memory: after %s: PetscMalloc()ed %.1f MiB, resident %.1f MiB", phase, v[0] / 1048576.0, v[1] / 1048576.0));
  if (J) PetscCall(PetscObjectTypeCompareAny((PetscObject)J, &aij, MATSEQAIJ, MATMPIAIJ, ""));
  if (aij) { /* (other types, hypre's, may not count their entries) */
    MatInfo info;
    PetscCall(MatGetInfo(J, MAT_GLOBAL_SUM, &info));
    PetscCall(PetscPrintf(comm, "; Jacobian %.0f nonzeros (values and column indices %.1f MiB)", info.nz_allocated, info.nz_allocated * (sizeof(PetscScalar) + sizeof(PetscInt)) / 1048576.0));
  }
  PetscCall(PetscPrintf(comm, "\n"));
  PetscFunctionReturn(0);
}

/* Every module reads its options first (so that -help lists them all and a misspelt one stops
   the run before any work), then the mesh, the conditions, contact and the problem are set up,
   and the stepper runs. */
static PetscErrorCode Run(PetscBool *stop)
{
  MPI_Comm      comm = PETSC_COMM_WORLD;
  MeshOptions   mo;
  Mesh          mesh;
  BCs           bcs;
  Contact       contact;
  Material      material;
  Bodies        bodies;
  Element       element;
  Problem       pb;
  Stepper       st;
  Results       res;
  PetscBool     help;
  PetscLogStage stage_mesh, stage_setup, stage_solve;
  PetscBool     memph = PETSC_FALSE;

  PetscFunctionBeginUser;
  *stop = PETSC_FALSE;
  {
    PetscBool tb = PETSC_FALSE;
    PetscOptionsBegin(comm, NULL, "Diagnostics", NULL);
    PetscCall(PetscOptionsBool("-memory_phases", "Print the memory allocated and resident (summed over the ranks) after each phase: mesh, contact setup, problem setup, solve", NULL, memph, &memph, NULL));
    PetscCall(PetscOptionsBool("-atrito_traceback", "PETSc's error traceback instead of the one-line error (read at start-up)", NULL, tb, &tb, NULL));
    PetscOptionsEnd();
  }
  PetscCall(PetscMemzero(&mesh, sizeof(mesh)));
  PetscCall(PetscLogStageRegister("Mesh", &stage_mesh));
  PetscCall(PetscLogStageRegister("Setup", &stage_setup));
  PetscCall(PetscLogStageRegister("Solve", &stage_solve));
  PetscCall(MeshSetFromOptions(comm, &mo));
  PetscCall(MaterialCreate(comm, &material));
  PetscCall(MaterialSetFromOptions(material));
  PetscCall(BodiesSetFromOptions(comm, &bodies));
  PetscCall(ElementCreate(comm, &element));
  PetscCall(ElementSetFromOptions(element));
  PetscCall(BCSetFromOptions(comm, &bcs));
  PetscCall(ContactCreate(comm, &contact));
  PetscCall(ContactSetFromOptions(contact));
  PetscCall(StepperSetFromOptions(comm, &st));
  PetscCall(ResultsSetFromOptions(comm, &res));
  PetscCall(ProblemSetFromOptions(comm, &pb));
  PetscCall(PetscOptionsHasHelp(NULL, &help));
  if (help) { /* the options are listed: nothing to run */
    *stop = PETSC_TRUE;
  } else {
    PetscCheck(mo.given, comm, PETSC_ERR_USER_INPUT, "no mesh: give a case (-options_file cases/<case>.opts) or -mesh_type / -mesh_file; usage: mpiexec -n N bin/atrito -options_file cases/<case>.opts [-option value ...]; -help lists the options");
    PetscCall(AtritoOptionsCheckUnknown(comm));
    /* the stages against the tools and conditions; the conditions they switch are not section
       constraints (before the mesh's constraints) */
    PetscCall(StepperSetUp(&st, &bcs, contact));

    PetscCall(PetscLogStagePush(stage_mesh));
    {
      PetscInt  na, *cmask;
      char    (*sets)[ATRITO_NAME_LEN];
      PetscCall(ContactGetAreaSets(contact, &na, &sets));
      PetscCall(MeshSetAreaSets(&mesh, na, sets));
      PetscCall(ContactGetSets(contact, &na, &sets));
      PetscCall(MeshSetContactSets(&mesh, na, sets));
      PetscCall(ContactGetFaceSets(contact, &na, &sets));
      PetscCall(MeshSetFaceSets(&mesh, na, sets));
      PetscCall(MeshCreate(comm, &mo, &mesh));
      PetscCall(BCComputeMask(&bcs, &mesh, &cmask));
      PetscCall(MeshSetConstraints(&mesh, cmask));
      PetscCall(PetscFree(cmask));
      PetscCall(BCSetUp(&bcs, &mesh));
    }
    PetscCall(PetscLogStagePop());
    PetscCall(MemoryPhase(comm, memph, "the mesh and conditions", NULL));
    PetscCall(PetscLogStagePush(stage_setup));
    {
      PetscReal E = 0;
      PetscCall(MaterialGetYoungModulus(material, &E));
      PetscCall(ContactSetYoungModulus(contact, E));
    }
    if (bodies.n) { /* several bodies: each cell's material, and its modulus for the contact pairs' penalties */
      PetscInt  *cmat;
      PetscReal *Ec, Em[BODY_MAX + 1];
      Material   mats[BODY_MAX + 1];
      mats[0] = material;
      for (PetscInt k = 0; k < bodies.n; k++) mats[k + 1] = bodies.mat[k];
      for (PetscInt k = 0; k <= bodies.n; k++) PetscCall(MaterialGetYoungModulus(mats[k], &Em[k]));
      PetscCall(PetscMalloc2(mesh.nc + 1, &cmat, mesh.nc + 1, &Ec));
      PetscCall(BodiesCellMap(&bodies, &mesh, cmat));
      for (PetscInt c = 0; c < mesh.nc; c++) Ec[c] = Em[cmat[c]];
      PetscCall(ProblemSetMaterials(&pb, bodies.n + 1, mats, cmat, mesh.nc));
      PetscCall(ContactSetCellModuli(contact, mesh.nc, Ec));
      PetscCall(PetscFree2(cmat, Ec));
    }
    PetscCall(ContactSetUp(contact, &mesh));
    PetscCall(MemoryPhase(comm, memph, "the contact setup", NULL));
    if (mesh.size > 1 && ContactNumTools(contact)) { /* the contact work per rank, beside the cells per rank of the mesh line */
      PetscInt ns = ContactNumSlaves(contact), nmax, nsum;
      PetscCallMPI(MPI_Allreduce(&ns, &nmax, 1, MPIU_INT, MPI_MAX, comm));
      PetscCallMPI(MPI_Allreduce(&ns, &nsum, 1, MPIU_INT, MPI_SUM, comm));
      PetscCall(PetscPrintf(comm, "contact: slave nodes per rank: largest %" PetscInt_FMT ", mean %.1f (imbalance %.3f)\n", nmax, (double)nsum / mesh.size, (double)nmax * mesh.size / PetscMax(nsum, 1)));
    }
    PetscCall(ProblemSetUp(&pb, &mesh, &bcs, contact, material, element));
    PetscCall(PetscLogStagePop());
    PetscCall(MemoryPhase(comm, memph, "the problem setup (fields, history, Jacobian)", pb.J));
    PetscCall(PetscLogStagePush(stage_solve));
    PetscCall(StepperRun(&st, &pb, &res));
    PetscCall(PetscLogStagePop());
    PetscCall(MemoryPhase(comm, memph, "the solve", NULL));
    PetscCall(BCDestroy(&bcs));
    PetscCall(MeshDestroy(&mesh));
  }
  PetscCall(ProblemDestroy(&pb));
  PetscCall(ContactDestroy(&contact));
  PetscCall(ElementDestroy(&element));
  PetscCall(MaterialDestroy(&material));
  PetscCall(BodiesDestroy(&bodies));
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
  PetscBool stop = PETSC_FALSE;
  ierr = Run(&stop);
  if (!ierr && !stop) ierr = ReportUnusedOptions();
  if (!traceback) PetscPopErrorHandler();
  PetscFinalize();
  return ierr ? 1 : 0;
}
