/* Newton's active-set correction of contact (activeset.h): the derivation is there. */
#include "activeset.h"
#include <petscblaslapack.h>
#include "contact.h"

#define BLK 49 /* a released node's block, packed: nd, dof[6], M[36], r[6] */

struct _n_NewtonActiveSet {
  PetscBool always;   /* also with an iterative linear solver                 */
  PetscInt  max_dofs; /* released unknowns per Newton iteration               */
  PetscInt  max_it;   /* rounds of release per Newton iteration               */
  PetscBool monitor;
  PetscBool verify;   /* compare with a direct solve of the modified system (tests)         */
  PetscReal rtol;     /* applied once |R| is at most this fraction of the internal forces' scale */
  Vec      *W;        /* J^-1 U, one column per released unknown (a pool)     */
  PetscInt  nW;
  Vec       Yn;
  PetscInt  corrected, released, solves;
};

PetscErrorCode NewtonActiveSetCreate(MPI_Comm comm, NewtonActiveSet *as)
{
  const char *modes[] = {"off", "direct", "always", "NewtonActiveSet", "ACTIVE_SET_", NULL};
  PetscInt    mode = 1, max_dofs = 240, max_it = 8;
  PetscBool   monitor = PETSC_FALSE, verify = PETSC_FALSE;
  PetscReal   rtol    = 0.1;

  PetscFunctionBeginUser;
  *as = NULL;
  PetscOptionsBegin(comm, NULL, "Newton's active-set correction of contact", NULL);
  PetscCall(PetscOptionsEList("-newton_active_set", "Correct each Newton direction for the slave nodes its linearisation pulls off their tools (they are taken out of the linear system, by the Sherman-Morrison-Woodbury formula, until no further node is pulled): off, with a direct linear solver (direct), or always", "include/activeset.h", modes, 3, modes[mode], &mode, NULL));
  PetscCall(PetscOptionsInt("-newton_active_set_max_dofs", "Active-set correction: the most released unknowns per Newton iteration (each one linear solve with the factorisation, and one vector: at most 25e6 values in all)", "include/activeset.h", max_dofs, &max_dofs, NULL));
  PetscCall(PetscOptionsInt("-newton_active_set_max_it", "Active-set correction: the most rounds of release per Newton iteration", "include/activeset.h", max_it, &max_it, NULL));
  PetscCall(PetscOptionsReal("-newton_active_set_rtol", "Active-set correction: applied once |R| is at most this fraction of the internal forces' scale (far from the solution the linearisation does not tell which nodes leave)", "include/activeset.h", rtol, &rtol, NULL));
  PetscCall(PetscOptionsBool("-newton_active_set_monitor", "Active-set correction: one line per corrected Newton iteration", "include/activeset.h", monitor, &monitor, NULL));
  PetscCall(PetscOptionsBool("-newton_active_set_verify", "Active-set correction: also solve the modified system J - U M U^T directly (a copy of the Jacobian, MUMPS) and print the relative difference of the two directions at each correction (a test of the update)", "include/activeset.h", verify, &verify, NULL));
  PetscOptionsEnd();
  PetscCheck(max_dofs >= 1 && max_dofs <= 4096, comm, PETSC_ERR_USER_INPUT, "-newton_active_set_max_dofs %" PetscInt_FMT " must lie in [1, 4096]", max_dofs);
  PetscCheck(rtol > 0, comm, PETSC_ERR_USER_INPUT, "-newton_active_set_rtol %g must be positive", (double)rtol);
  PetscCheck(max_it >= 1 && max_it <= 100, comm, PETSC_ERR_USER_INPUT, "-newton_active_set_max_it %" PetscInt_FMT " must lie in [1, 100]", max_it);
  if (mode == 0) PetscFunctionReturn(0);
  PetscCall(PetscNew(as));
  (*as)->always   = mode == 2 ? PETSC_TRUE : PETSC_FALSE;
  (*as)->max_dofs = max_dofs;
  (*as)->max_it   = max_it;
  (*as)->monitor  = monitor;
  (*as)->rtol     = rtol;
  (*as)->verify   = verify;
  PetscFunctionReturn(0);
}

/* position of dof d in D[0..n), -1 if absent */
static PetscInt Find(const PetscInt *D, PetscInt n, PetscInt d)
{
  for (PetscInt k = 0; k < n; k++)
    if (D[k] == d) return k;
  return -1;
}

/* -newton_active_set_verify: the direction of the modified system (J - U M U^T) y = F - U dR by a
   factorisation of its own, against y (the Woodbury update); the relative difference of the two */
static PetscErrorCode Verify(KSP ksp, Vec F, const PetscReal *blk, PetscInt nblk, Vec y, PetscReal *diff)
{
  Mat J, Jm;
  Vec b, x;
  KSP k2;
  PC  pc;
  PetscReal ny;

  PetscFunctionBeginUser;
  PetscCall(KSPGetOperators(ksp, &J, NULL));
  PetscCall(MatDuplicate(J, MAT_COPY_VALUES, &Jm));
  PetscCall(VecDuplicate(F, &b));
  PetscCall(VecDuplicate(F, &x));
  PetscCall(VecCopy(F, b));
  PetscCall(MatSetOption(Jm, MAT_NEW_NONZERO_ALLOCATION_ERR, PETSC_FALSE));
  for (PetscInt k = 0; k < nblk; k++) {
    const PetscReal *bk = blk + BLK * k;
    const PetscInt   nd = (PetscInt)bk[0];
    PetscInt         dof[6];
    PetscScalar      m[36], r[6];
    for (PetscInt a = 0; a < nd; a++) {
      dof[a] = (PetscInt)bk[1 + a];
      r[a]   = -bk[43 + a];
      for (PetscInt q = 0; q < nd; q++) m[nd * a + q] = -bk[7 + 6 * a + q];
    }
    /* every rank holds every block: the owner of the row adds it */
    {
      PetscInt rs, re;
      PetscCall(MatGetOwnershipRange(Jm, &rs, &re));
      for (PetscInt a = 0; a < nd; a++)
        if (dof[a] >= rs && dof[a] < re) {
          PetscCall(MatSetValues(Jm, 1, &dof[a], nd, dof, m + nd * a, ADD_VALUES));
          PetscCall(VecSetValue(b, dof[a], r[a], ADD_VALUES));
        }
    }
  }
  PetscCall(MatAssemblyBegin(Jm, MAT_FINAL_ASSEMBLY));
  PetscCall(MatAssemblyEnd(Jm, MAT_FINAL_ASSEMBLY));
  PetscCall(VecAssemblyBegin(b));
  PetscCall(VecAssemblyEnd(b));
  PetscCall(KSPCreate(PetscObjectComm((PetscObject)J), &k2));
  PetscCall(KSPSetOperators(k2, Jm, Jm));
  PetscCall(KSPSetType(k2, KSPPREONLY));
  PetscCall(KSPGetPC(k2, &pc));
  PetscCall(PCSetType(pc, PCLU));
  PetscCall(PCFactorSetMatSolverType(pc, MATSOLVERMUMPS));
  PetscCall(KSPSolve(k2, b, x));
  PetscCall(VecAXPY(x, -1.0, y));
  PetscCall(VecNorm(x, NORM_2, diff));
  PetscCall(VecNorm(y, NORM_2, &ny));
  if (ny > 0) *diff /= ny;
  PetscCall(KSPDestroy(&k2));
  PetscCall(MatDestroy(&Jm));
  PetscCall(VecDestroy(&b));
  PetscCall(VecDestroy(&x));
  PetscFunctionReturn(0);
}

PetscErrorCode NewtonActiveSetApply(NewtonActiveSet as, Problem *pb, KSP ksp, PetscInt nz, const PetscInt *zrows, Vec F, PetscReal fnorm, Vec Y, PetscBool *changed)
{
  Contact         contact = pb->contact;
  const PetscInt  ns      = ContactNumSlaves(contact);
  MPI_Comm        comm;
  PetscMPIInt     size;
  PetscInt       *idx = NULL, *D = NULL, nD = 0, nblk = 0, rstart, rend, round, nrel = 0, cap, nD_ok = 0, nblk_ok = 0, nrel_ok = 0;
  PetscReal      *blk = NULL, *loc = NULL, *A = NULL, *M = NULL, *dR = NULL, *yD = NULL, *B = NULL, *z = NULL;
  PetscScalar    *c = NULL;
  char           *released = NULL;
  PetscMPIInt    *cnt = NULL, *displ = NULL;
  PetscBool       applied = PETSC_FALSE;
  KSPConvergedReason kr = KSP_CONVERGED_ITERATING;
  PetscReal       Fs; /* the internal forces' scale */

  PetscFunctionBeginUser;
  *changed = PETSC_FALSE;
  if (!as || !ContactNumTools(contact)) PetscFunctionReturn(0);
  if (!as->always) {
    PetscBool preonly;
    PetscCall(PetscObjectTypeCompare((PetscObject)ksp, KSPPREONLY, &preonly));
    if (!preonly) PetscFunctionReturn(0);
  }
  PetscCall(ProblemForceScale(pb, &Fs));
  if (!(fnorm <= as->rtol * Fs)) PetscFunctionReturn(0);
  PetscCall(PetscObjectGetComm((PetscObject)Y, &comm));
  PetscCallMPI(MPI_Comm_size(comm, &size));
  PetscCall(VecGetOwnershipRange(Y, &rstart, &rend));
  if (!as->Yn) PetscCall(VecDuplicate(Y, &as->Yn));
  PetscCall(PetscCalloc3(ns + 1, &released, ns + 1, &idx, BLK * (ns + 1), &loc));
  PetscCall(PetscMalloc2(size, &cnt, size, &displ));
  {
    /* the columns W take at most 25e6 values (200 MB) however large the mesh */
    PetscInt N;
    PetscCall(VecGetSize(Y, &N));
    cap = PetscMin(as->max_dofs, PetscMax(30, (PetscInt)(25e6 / (PetscReal)N)));
  }
  PetscCall(PetscMalloc1(cap, &D));
  PetscCall(VecCopy(Y, as->Yn));
  for (round = 0; round < as->max_it; round++) {
    PetscReal yt[3 * 64];
    PetscInt  nc, ntot = 0, nD1 = nD;
    PetscMPIInt nl;
    PetscCall(ProblemGetToolValues(pb, as->Yn, yt));
    /* a pull below 1e-8 of the forces' scale is a node at zero force to round-off (a tool whose
       force has gone to zero): whether it is released would be decided by the round-off of the
       rank count, and it changes nothing the Newton tolerance sees */
    PetscCall(ContactLinearRelease(contact, as->Yn, pb->ntu ? yt : NULL, 1e-8 * Fs, released, &nc, idx));
    for (PetscInt k = 0; k < nc; k++) {
      PetscReal *b = loc + BLK * k;
      PetscInt   nd, dof[6];
      PetscReal  Mi[36], ri[6];
      PetscInt   keep[6], nk = 0;
      PetscCall(ContactLinearBlock(contact, idx[k], &nd, dof, Mi, ri));
      /* the rows and columns of a condition that a stage switched on are identity in the Jacobian:
         the block has none there */
      for (PetscInt a = 0; a < nd; a++) {
        PetscInt loc_z = -1;
        if (nz) PetscCall(PetscFindInt(dof[a], nz, zrows, &loc_z));
        if (loc_z < 0) keep[nk++] = a;
      }
      PetscCall(PetscArrayzero(b, BLK));
      b[0] = (PetscReal)nk;
      for (PetscInt a = 0; a < nk; a++) {
        b[1 + a]  = (PetscReal)dof[keep[a]];
        b[43 + a] = ri[keep[a]];
        for (PetscInt q = 0; q < nk; q++) b[7 + 6 * a + q] = Mi[6 * keep[a] + keep[q]];
      }
    }
    nl = (PetscMPIInt)(BLK * nc);
    PetscCallMPI(MPI_Allgather(&nl, 1, MPI_INT, cnt, 1, MPI_INT, comm));
    for (PetscMPIInt p = 0; p < size; p++) {
      displ[p] = (PetscMPIInt)(BLK * (nblk + ntot));
      ntot += cnt[p] / BLK;
    }
    if (!ntot) break;
    PetscCall(PetscRealloc(sizeof(PetscReal) * BLK * (nblk + ntot), &blk));
    PetscCallMPI(MPI_Allgatherv(loc, nl, MPIU_REAL, blk, cnt, displ, MPIU_REAL, comm));
    /* the new unknowns (every rank the same list) */
    for (PetscInt k = nblk; k < nblk + ntot; k++) {
      const PetscReal *b = blk + BLK * k;
      for (PetscInt a = 0; a < (PetscInt)b[0]; a++) {
        const PetscInt d = (PetscInt)b[1 + a];
        if (Find(D, nD1, d) >= 0) continue;
        if (nD1 == cap) {
          nD1 = -1;
          break;
        }
        D[nD1++] = d;
      }
      if (nD1 < 0) break;
    }
    if (nD1 < 0) break; /* too many: the last round's direction stands */
    for (PetscInt k = 0; k < nc; k++) released[idx[k]] = 1;
    /* W's new columns: J^-1 e_d */
    if (as->nW < nD1) {
      PetscCall(PetscRealloc(sizeof(Vec) * nD1, &as->W));
      for (PetscInt j = as->nW; j < nD1; j++) PetscCall(VecDuplicate(Y, &as->W[j]));
      as->nW = nD1;
    }
    if (nD1 > nD) { /* the new columns' unit vectors, solved together (KSPMatSolve) */
      Mat      E, X;
      PetscInt nloc, N;
      Vec      col;
      PetscCall(VecGetLocalSize(Y, &nloc));
      PetscCall(VecGetSize(Y, &N));
      PetscCall(MatCreateDense(comm, nloc, PETSC_DECIDE, N, nD1 - nD, NULL, &E));
      PetscCall(MatZeroEntries(E));
      for (PetscInt j = nD; j < nD1; j++)
        if (D[j] >= rstart && D[j] < rend) PetscCall(MatSetValue(E, D[j], j - nD, 1.0, INSERT_VALUES));
      PetscCall(MatAssemblyBegin(E, MAT_FINAL_ASSEMBLY));
      PetscCall(MatAssemblyEnd(E, MAT_FINAL_ASSEMBLY));
      PetscCall(MatDuplicate(E, MAT_DO_NOT_COPY_VALUES, &X));
      PetscCall(KSPMatSolve(ksp, E, X));
      PetscCall(KSPGetConvergedReason(ksp, &kr));
      as->solves += nD1 - nD;
      for (PetscInt j = nD; j < nD1 && kr >= 0; j++) {
        PetscCall(MatDenseGetColumnVecRead(X, j - nD, &col));
        PetscCall(VecCopy(col, as->W[j]));
        PetscCall(MatDenseRestoreColumnVecRead(X, j - nD, &col));
      }
      PetscCall(MatDestroy(&E));
      PetscCall(MatDestroy(&X));
    }
    if (kr < 0) break; /* the last round's direction stands */
    nD   = nD1;
    nblk += ntot;
    nrel += ntot;
    /* A = U^T W, y_D (each rank its own rows, then summed), M, dR */
    PetscCall(PetscFree6(A, M, dR, yD, B, z));
    PetscCall(PetscFree(c));
    PetscCall(PetscCalloc6(nD * nD, &A, nD * nD, &M, nD, &dR, nD, &yD, nD * nD, &B, nD, &z));
    PetscCall(PetscCalloc1(nD, &c));
    {
      const PetscScalar *w;
      for (PetscInt j = 0; j < nD; j++) {
        PetscCall(VecGetArrayRead(as->W[j], &w));
        for (PetscInt k = 0; k < nD; k++)
          if (D[k] >= rstart && D[k] < rend) A[k + nD * j] = PetscRealPart(w[D[k] - rstart]);
        PetscCall(VecRestoreArrayRead(as->W[j], &w));
      }
      PetscCall(VecGetArrayRead(Y, &w));
      for (PetscInt k = 0; k < nD; k++)
        if (D[k] >= rstart && D[k] < rend) yD[k] = PetscRealPart(w[D[k] - rstart]);
      PetscCall(VecRestoreArrayRead(Y, &w));
    }
    PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, A, (PetscMPIInt)(nD * nD), MPIU_REAL, MPI_SUM, comm));
    PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, yD, (PetscMPIInt)nD, MPIU_REAL, MPI_SUM, comm));
    for (PetscInt k = 0; k < nblk; k++) {
      const PetscReal *b  = blk + BLK * k;
      const PetscInt   nd = (PetscInt)b[0];
      PetscInt         pos[6];
      for (PetscInt a = 0; a < nd; a++) pos[a] = Find(D, nD, (PetscInt)b[1 + a]);
      for (PetscInt a = 0; a < nd; a++) {
        dR[pos[a]] += b[43 + a];
        for (PetscInt q = 0; q < nd; q++) M[pos[a] + nD * pos[q]] += b[7 + 6 * a + q];
      }
    }
    /* B = I - A M, z = y_D - A dR; B z' = z; c = -dR + M z'. M holds the nodes' blocks (at
       most 6 x 6 each, the tool's columns shared): its zeros are skipped */
    for (PetscInt r = 0; r < nD; r++) {
      z[r] = yD[r];
      for (PetscInt q = 0; q < nD; q++) z[r] -= A[r + nD * q] * dR[q];
    }
    for (PetscInt q = 0; q < nD; q++) {
      PetscReal *Bq = B + nD * q;
      Bq[q] = 1.0;
      for (PetscInt l = 0; l < nD; l++) {
        const PetscReal mlq = M[l + nD * q], *Al = A + nD * l;
        if (mlq == 0) continue;
        for (PetscInt r = 0; r < nD; r++) Bq[r] -= Al[r] * mlq;
      }
    }
    {
      PetscBLASInt n, one = 1, info, *piv;
      PetscCall(PetscBLASIntCast(nD, &n));
      PetscCall(PetscMalloc1(nD, &piv));
      LAPACKgesv_(&n, &one, B, &n, piv, z, &n, &info);
      PetscCall(PetscFree(piv));
      if (info) break; /* singular: the last round's direction stands (the same on every rank) */
    }
    {
      PetscBool finite = PETSC_TRUE;
      for (PetscInt r = 0; r < nD; r++) {
        PetscReal v = -dR[r];
        for (PetscInt q = 0; q < nD; q++) v += M[r + nD * q] * z[q];
        c[r] = v;
        if (PetscIsInfOrNanReal(v)) finite = PETSC_FALSE;
      }
      if (!finite) break; /* a failed solve with the factorisation: the last round's direction stands */
    }
    PetscCall(VecCopy(Y, as->Yn));
    PetscCall(VecMAXPY(as->Yn, nD, c, as->W));
    applied = PETSC_TRUE;
    nD_ok   = nD;
    nblk_ok = nblk;
    nrel_ok = nrel;
  }
  if (applied && as->verify) {
    PetscReal d;
    PetscCall(Verify(ksp, F, blk, nblk_ok, as->Yn, &d));
    PetscCall(PetscPrintf(comm, "      active set verify: %" PetscInt_FMT " nodes, %" PetscInt_FMT " unknowns, relative difference from the direct solve %.3e\n", nrel_ok, nD_ok, (double)d));
  }
  if (applied) {
    PetscCall(VecCopy(as->Yn, Y));
    *changed = PETSC_TRUE;
    as->corrected++;
    as->released += nrel_ok;
    if (as->monitor) PetscCall(PetscPrintf(comm, "      active set: %" PetscInt_FMT " nodes released in %" PetscInt_FMT " rounds, %" PetscInt_FMT " unknowns\n", nrel_ok, round, nD_ok));
  }
  PetscCall(PetscFree6(A, M, dR, yD, B, z));
  PetscCall(PetscFree(c));
  PetscCall(PetscFree(blk));
  PetscCall(PetscFree(D));
  PetscCall(PetscFree2(cnt, displ));
  PetscCall(PetscFree3(released, idx, loc));
  PetscFunctionReturn(0);
}

PetscErrorCode NewtonActiveSetGetCounts(NewtonActiveSet as, PetscInt *corrected, PetscInt *released, PetscInt *solves)
{
  PetscFunctionBeginUser;
  *corrected = as ? as->corrected : 0;
  *released  = as ? as->released : 0;
  *solves    = as ? as->solves : 0;
  PetscFunctionReturn(0);
}

PetscErrorCode NewtonActiveSetDestroy(NewtonActiveSet *as)
{
  PetscFunctionBeginUser;
  if (!*as) PetscFunctionReturn(0);
  if ((*as)->W) PetscCall(VecDestroyVecs((*as)->nW, &(*as)->W));
  PetscCall(VecDestroy(&(*as)->Yn));
  PetscCall(PetscFree(*as));
  PetscFunctionReturn(0);
}
