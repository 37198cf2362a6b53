#ifndef ATRITO_BORDERED_H
#define ATRITO_BORDERED_H

#include <petscmat.h>

/* A Jacobian bordered by the unknowns of force-driven tools (a blank holder under its force),

     J = [A  B]     A: the mesh block (any assembled matrix; hypre's format for -pc_type amgsys),
         [C  D]     B: nt columns, C: nt rows over the mesh's unknowns, D: nt x nt,

   the tools' nt unknowns numbered after all of the mesh's, their rows on the last rank. The
   border is kept as 2 nt vectors over the mesh's rows (B_k, the transposed rows C_k) and D dense
   on every rank, so the mesh block is stored once, in the format its preconditioner uses, and the
   few dense rows and columns of the tools never enter it (src/solver/bordered.c, the derivation).
   MatSetValues with ADD_VALUES (or INSERT_VALUES on the mesh block) at the Jacobian's global
   indices, negative ones ignored, MatZeroEntries, the assemblies, MatMult, MatMultTranspose and
   MatZeroRowsColumns act on the pieces; anything else (a factorisation, MatDuplicate, MatGetRow)
   is refused by PETSc as for any shell matrix. */

/* A takes the mesh's rows, nt the tools' unknowns; the result holds a reference to A */
PetscErrorCode MatCreateBordered(Mat A, PetscInt nt, Mat *J);
/* Whether J is a bordered matrix; if so its pieces (borrowed; NULL arguments skipped) */
PetscErrorCode MatBorderedGetBlocks(Mat J, PetscBool *is, Mat *A, PetscInt *nt, const Vec **B, const Vec **C, const PetscScalar **D);

#endif
