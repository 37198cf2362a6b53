/* Direct solver: LU factorisation by MUMPS, called directly, with a fill-reducing METIS
   nested-dissection ordering of the whole matrix graph handed to its analysis (PETSc 3.18's MUMPS
   interface takes no user ordering in parallel, and Debian's MUMPS has neither METIS nor SCOTCH
   built in: it orders with PORD). */
#ifndef ATRITO_LU_H
#define ATRITO_LU_H
#include <petscksp.h>

/* Makes pc (of any type) a PCSHELL that factors its (Seq|MPI)AIJ operator: the ordering and the
   MUMPS analysis whenever the nonzero pattern changes (in practice once per run), a numerical
   factorisation whenever the values change. MUMPS control values are read from the options
   -mat_mumps_icntl_<i> and -mat_mumps_cntl_<i> under pc's prefix, as PETSc's interface does;
   those that fix the ordering and the data layout (ICNTL 6, 7, 18, 20, 21, 28, 29) are refused. */
PetscErrorCode PCSetLUND(PC pc);
/* Refuses the MUMPS controls that PCSetLUND sets itself (-mat_mumps_icntl_ 6, 7, 18, 20, 21, 28, 29) */
PetscErrorCode LUNDCheckOptions(MPI_Comm comm, const char prefix[]);
/* How many analyses (ordering + MUMPS analysis) and successful factorisations pc has done */
PetscErrorCode PCLUNDGetCounts(PC pc, PetscInt *nanalysis, PetscInt *nfactor);

/* The fill-reducing ordering alone, for the tests: N rows, CSR graph (xadj, adj) without the
   diagonal, symmetric; iperm[i] = position of row i in the elimination order */
PetscErrorCode LUNestedDissection(PetscInt N, const PetscInt xadj[], const PetscInt adj[], PetscInt iperm[]);
#endif
