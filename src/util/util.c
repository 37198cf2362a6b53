/* Small helpers shared by the modules. */
#include "util.h"

PetscErrorCode AtritoRootError(MPI_Comm comm, PetscErrorCode ierr_root)
{
  PetscMPIInt rank;
  int         code = (int)ierr_root;
  char        msg[1024] = "";

  PetscFunctionBeginUser;
  PetscCallMPI(MPI_Comm_rank(comm, &rank));
  PetscCallMPI(MPI_Bcast(&code, 1, MPI_INT, 0, comm));
  if (!code) PetscFunctionReturn(0);
  if (rank == 0) {
    char *specific = NULL;
    PetscCall(PetscErrorMessage(code, NULL, &specific));
    PetscCall(PetscStrncpy(msg, specific ? specific : "unknown error", sizeof(msg)));
  }
  PetscCallMPI(MPI_Bcast(msg, sizeof(msg), MPI_CHAR, 0, comm));
  SETERRQ(comm, (PetscErrorCode)code, "%s", msg);
}

PetscErrorCode AtritoCheckFinite(MPI_Comm comm, const char *opt, const PetscReal *v, PetscInt n)
{
  PetscFunctionBeginUser;
  for (PetscInt i = 0; i < n; i++) PetscCheck(PetscIsNormalReal(v[i]) || v[i] == 0, comm, PETSC_ERR_USER_INPUT, "%s: value %g is not a finite number", opt, (double)v[i]);
  PetscFunctionReturn(0);
}

PetscErrorCode AtritoFileOpenRoot(MPI_Comm comm, const char *path, const char *mode, const char *option, FILE **fp)
{
  PetscMPIInt rank;
  int         ok = 1;

  PetscFunctionBeginUser;
  *fp = NULL;
  PetscCallMPI(MPI_Comm_rank(comm, &rank));
  if (!rank) {
    *fp = fopen(path, mode);
    ok  = *fp != NULL;
  }
  PetscCallMPI(MPI_Bcast(&ok, 1, MPI_INT, 0, comm));
  PetscCheck(ok, comm, PETSC_ERR_FILE_OPEN, "cannot %s '%s' (%s)", mode[0] == 'r' ? "read" : "write", path, option);
  PetscFunctionReturn(0);
}
