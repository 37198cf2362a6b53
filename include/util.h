/* Small helpers shared by the modules */
#ifndef ATRITO_UTIL_H
#define ATRITO_UTIL_H
#include <petscsys.h>

/* After work done on rank 0 alone (under PetscReturnErrorHandler), raise its error, with its
   message, on every rank of comm; a no-op when ierr_root is 0. */
PetscErrorCode AtritoRootError(MPI_Comm comm, PetscErrorCode ierr_root);
/* Options checks: every value finite */
PetscErrorCode AtritoCheckFinite(MPI_Comm comm, const char *opt, const PetscReal *v, PetscInt n);
/* Rank 0 opens path (mode as fopen's) and every rank learns whether it could: an error is raised
   collectively, naming the file and the option that chose it. *fp is NULL on the other ranks. */
PetscErrorCode AtritoFileOpenRoot(MPI_Comm comm, const char *path, const char *mode, const char *option, FILE **fp);
#endif
