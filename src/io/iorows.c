/* Rank-independent row order for output and checkpoints (see iorows.h). */
#include "iorows.h"

PetscErrorCode IORowsCreate(MPI_Comm comm, PetscInt n, const PetscInt src[], IORows *r)
{
  IS isfrom, isto;

  PetscFunctionBeginUser;
  r->n = n;
  PetscCall(VecCreateMPI(comm, n, PETSC_DETERMINE, &r->own));
  PetscCall(VecGetSize(r->own, &r->N));
  PetscCall(VecCreateMPI(comm, PETSC_DECIDE, r->N, &r->blk));
  PetscCall(VecGetLocalSize(r->blk, &r->nb));
  PetscCall(VecGetOwnershipRange(r->blk, &r->off, NULL));
  {
    PetscInt start;
    PetscCall(VecGetOwnershipRange(r->own, &start, NULL));
    PetscCall(ISCreateStride(comm, n, start, 1, &isfrom));
  }
  PetscCall(ISCreateGeneral(comm, n, src, PETSC_COPY_VALUES, &isto));
  PetscCall(VecScatterCreate(r->own, isfrom, r->blk, isto, &r->sc));
  PetscCall(ISDestroy(&isfrom));
  PetscCall(ISDestroy(&isto));
  PetscFunctionReturn(0);
}

PetscErrorCode IORowsDestroy(IORows *r)
{
  PetscFunctionBeginUser;
  PetscCall(VecScatterDestroy(&r->sc));
  PetscCall(VecDestroy(&r->own));
  PetscCall(VecDestroy(&r->blk));
  PetscFunctionReturn(0);
}

PetscErrorCode IORowsToBlock(IORows *r, PetscInt ncomp, const PetscReal own[], PetscReal blk[])
{
  PetscFunctionBeginUser;
  for (PetscInt k = 0; k < ncomp; k++) {
    PetscScalar       *a;
    const PetscScalar *b;
    PetscCall(VecGetArray(r->own, &a));
    for (PetscInt i = 0; i < r->n; i++) a[i] = own[i * ncomp + k];
    PetscCall(VecRestoreArray(r->own, &a));
    PetscCall(VecScatterBegin(r->sc, r->own, r->blk, INSERT_VALUES, SCATTER_FORWARD));
    PetscCall(VecScatterEnd(r->sc, r->own, r->blk, INSERT_VALUES, SCATTER_FORWARD));
    PetscCall(VecGetArrayRead(r->blk, &b));
    for (PetscInt i = 0; i < r->nb; i++) blk[i * ncomp + k] = PetscRealPart(b[i]);
    PetscCall(VecRestoreArrayRead(r->blk, &b));
  }
  PetscFunctionReturn(0);
}

PetscErrorCode IORowsFromBlock(IORows *r, PetscInt ncomp, const PetscReal blk[], PetscReal own[])
{
  PetscFunctionBeginUser;
  for (PetscInt k = 0; k < ncomp; k++) {
    PetscScalar       *b;
    const PetscScalar *a;
    PetscCall(VecGetArray(r->blk, &b));
    for (PetscInt i = 0; i < r->nb; i++) b[i] = blk[i * ncomp + k];
    PetscCall(VecRestoreArray(r->blk, &b));
    PetscCall(VecScatterBegin(r->sc, r->blk, r->own, INSERT_VALUES, SCATTER_REVERSE));
    PetscCall(VecScatterEnd(r->sc, r->blk, r->own, INSERT_VALUES, SCATTER_REVERSE));
    PetscCall(VecGetArrayRead(r->own, &a));
    for (PetscInt i = 0; i < r->n; i++) own[i * ncomp + k] = PetscRealPart(a[i]);
    PetscCall(VecRestoreArrayRead(r->own, &a));
  }
  PetscFunctionReturn(0);
}
