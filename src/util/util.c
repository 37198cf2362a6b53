/* Small helpers shared by the modules. */
#include "atrito.h"

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
