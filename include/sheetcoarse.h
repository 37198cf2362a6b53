/* A coarse space of plate-like modes for thin sheets, used by -pc_type amgsys beside its V-cycle
   (src/solver/sheetcoarse.c; doc/notes/performance-log.md, "One million hexahedra"). */
#ifndef ATRITO_SHEETCOARSE_H
#define ATRITO_SHEETCOARSE_H
#include <petscmat.h>
#include <petscdm.h>

typedef struct _p_SheetCoarse *SheetCoarse;

/* the value of coarse mode m (0-2: translation along x, y, z; 3-5: rotation about x, y, z, scaled
   by 1/H) at a displacement component c (0-2) of a node at arm d from the coarse node */
PetscReal SheetModeValue(PetscInt m, PetscInt c, const PetscReal d[3], PetscReal H);

PetscErrorCode SheetCoarseCreate(MPI_Comm comm, PetscReal H, const PetscReal normal[3], SheetCoarse *sc);
/* the rows' positions from the mesh (reference coordinates, plus U where given: the iterate at
   which A was assembled, in A's row layout), the coarse operator P^T A P and its factors; wz, wy:
   work vectors of A's layout, or NULL (made and freed here) */
PetscErrorCode SheetCoarseSetUp(SheetCoarse sc, DM dm, Mat A, Vec U, Vec wz, Vec wy);
/* y += P (P^T A P)^-1 P^T r; y is set to NaN when r is not finite or the coarse solve fails:
   the Krylov method then stops (KSP_DIVERGED_NANORINF) and Newton retries the step */
PetscErrorCode SheetCoarseApply(SheetCoarse sc, Vec r, Vec y);
/* the basis P as an assembled matrix (rows: A's; columns: 6 per active coarse node) and the
   coarse operator (on rank 0; NULL on the others): for tests */
PetscErrorCode SheetCoarseGetBasis(SheetCoarse sc, Mat *P);
PetscErrorCode SheetCoarseGetOperator(SheetCoarse sc, Mat *Ac);
PetscErrorCode SheetCoarseGetSize(SheetCoarse sc, PetscInt *nodes, PetscInt *colours);
PetscErrorCode SheetCoarseDestroy(SheetCoarse *sc);
#endif
