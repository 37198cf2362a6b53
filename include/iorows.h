/* Rank-independent row order for output and checkpoints: items (vertices or cells) owned by the
   ranks are moved to their position in the source mesh and split into contiguous blocks, one per
   rank, so that the files are the same whatever the number of ranks and a checkpoint can be read
   back on another number of ranks. */
#ifndef ATRITO_IOROWS_H
#define ATRITO_IOROWS_H
#include <petscvec.h>

typedef struct {
  PetscInt   n;       /* items owned by this rank                 */
  PetscInt   N;       /* items in all                             */
  PetscInt   nb, off; /* this rank's block of rows: [off, off+nb) */
  Vec        own, blk;
  VecScatter sc;      /* own -> blk                               */
} IORows;

/* src[n]: the source position of each owned item (a permutation of 0..N-1 over the ranks) */
PetscErrorCode IORowsCreate(MPI_Comm comm, PetscInt n, const PetscInt src[], IORows *r);
PetscErrorCode IORowsDestroy(IORows *r);
/* own[n*ncomp] (item-major) -> blk[nb*ncomp] */
PetscErrorCode IORowsToBlock(IORows *r, PetscInt ncomp, const PetscReal own[], PetscReal blk[]);
/* blk[nb*ncomp] -> own[n*ncomp] */
PetscErrorCode IORowsFromBlock(IORows *r, PetscInt ncomp, const PetscReal blk[], PetscReal own[]);
#endif
