/* Unit test of the sheet's coarse space (src/solver/sheetcoarse.c), at any number of ranks, on a
   quarter blank with its symmetry planes and clamped rim (rows of single components removed) and
   an unsymmetric matrix with the mesh's cell couplings (random element blocks, diagonally
   dominant):
   1. the modes in closed form: translations, and rotations e_m x d / H;
   2. the hats are a partition of unity: P times the x translation of every coarse node is 1 on
      every x row and 0 on the others;
   3. the coarse operator gathered by colouring equals the Galerkin product P^T A P (formed here
      with PETSc's MatPtAP), on random coarse vectors, for a spacing larger than the cells (reach
      2, 25 colours) and one smaller (a larger reach);
   4. the correction y = P A_c^-1 P^T r leaves a residual r - A y orthogonal to the coarse space. */
#include <petscksp.h>
#include "testutil.h"
#include "mesh.h"
#include "bc.h"
#include "sheetcoarse.h"

static PetscMPIInt rank;

/* a value in [-1, 1) from integers: the same on any number of ranks */
static PetscReal Hash(PetscInt a, PetscInt b, PetscInt c)
{
  unsigned long long h = 1469598103934665603ULL;
  h = (h ^ (unsigned long long)a) * 1099511628211ULL;
  h = (h ^ (unsigned long long)b) * 1099511628211ULL;
  h = (h ^ (unsigned long long)c) * 1099511628211ULL;
  h ^= h >> 29;
  return (PetscReal)(h % 2000003ULL) / 1000001.5 - 1.0;
}

/* y = P^T A P v (parallel, then on every rank), for a coarse vector v given on every rank */
static PetscErrorCode Galerkin(Mat Ptap, const PetscScalar *v, PetscInt N, PetscScalar *y)
{
  Vec                cv, cw, all;
  VecScatter         sct;
  PetscInt           lo, hi;
  const PetscScalar *a;

  PetscFunctionBeginUser;
  PetscCall(MatCreateVecs(Ptap, &cv, &cw));
  PetscCall(VecGetOwnershipRange(cv, &lo, &hi));
  for (PetscInt i = lo; i < hi; i++) PetscCall(VecSetValue(cv, i, v[i], INSERT_VALUES));
  PetscCall(VecAssemblyBegin(cv));
  PetscCall(VecAssemblyEnd(cv));
  PetscCall(MatMult(Ptap, cv, cw));
  PetscCall(VecScatterCreateToAll(cw, &sct, &all));
  PetscCall(VecScatterBegin(sct, cw, all, INSERT_VALUES, SCATTER_FORWARD));
  PetscCall(VecScatterEnd(sct, cw, all, INSERT_VALUES, SCATTER_FORWARD));
  PetscCall(VecGetArrayRead(all, &a));
  for (PetscInt i = 0; i < N; i++) y[i] = a[i];
  PetscCall(VecRestoreArrayRead(all, &a));
  PetscCall(VecScatterDestroy(&sct));
  PetscCall(VecDestroy(&all));
  PetscCall(VecDestroy(&cv));
  PetscCall(VecDestroy(&cw));
  PetscFunctionReturn(0);
}

int main(int argc, char **argv)
{
  MeshOptions mo;
  Mesh        m;
  BCs         bcs;
  PetscInt   *cmask;
  Mat         A;
  Vec         U;

  PetscCall(PetscInitialize(&argc, &argv, NULL, NULL));
  PetscCallMPI(MPI_Comm_rank(PETSC_COMM_WORLD, &rank));
  PetscCall(PetscOptionsInsertString(NULL, "-mesh_type blank -blank_radius 10 -blank_thickness 1 -blank_core 0.4 -blank_core_cells 3 -blank_radial_cells 5 -blank_layers 2 -blank_quarter true "
                                           "-bc_names clamp,symx,symy -bc_clamp_set rim -bc_clamp_components x,y,z -bc_symx_set symx -bc_symx_components x -bc_symy_set symy -bc_symy_components y"));

  /* 1. the modes */
  {
    const PetscReal d[3] = {1, 2, 3}, H = 2;
    PetscReal       e = 0;
    const PetscReal want[6][3] = {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}, {0, -1.5, 1}, {1.5, 0, -0.5}, {-1, 0.5, 0}};
    for (PetscInt mm = 0; mm < 6; mm++)
      for (PetscInt c = 0; c < 3; c++) e = PetscMax(e, PetscAbsReal(SheetModeValue(mm, c, d, H) - want[mm][c]));
    CHECK_ALL(e == 0, "sheet modes: translations and rotations e_m x d / H in closed form (largest error %g)", (double)e);
  }

  PetscCall(PetscMemzero(&m, sizeof(m)));
  PetscCall(MeshSetFromOptions(PETSC_COMM_WORLD, &mo));
  PetscCall(BCSetFromOptions(PETSC_COMM_WORLD, &bcs));
  PetscCall(MeshCreate(PETSC_COMM_WORLD, &mo, &m));
  PetscCall(BCComputeMask(&bcs, &m, &cmask));
  PetscCall(MeshSetConstraints(&m, cmask));
  PetscCall(PetscFree(cmask));

  /* the matrix: per cell a random unsymmetric block on its unconstrained dofs, 24 on the diagonal */
  PetscCall(DMCreateMatrix(m.dm, &A));
  PetscCall(MatSetOption(A, MAT_NEW_NONZERO_ALLOCATION_ERR, PETSC_TRUE));
  for (PetscInt c = 0; c < m.nc; c++) {
    const PetscInt  n = m.cndof[c], *g = &m.cgdof[24 * c];
    const unsigned char *p = &m.cperm[24 * c];
    PetscScalar     Ke[24 * 24];
    for (PetscInt i = 0; i < n; i++)
      for (PetscInt j = 0; j < n; j++) Ke[i * n + j] = Hash(m.elem_src[c], p[i], p[j]) + (i == j ? 24.0 : 0.0);
    PetscCall(MatSetValues(A, n, g, n, g, Ke, ADD_VALUES));
  }
  PetscCall(MatAssemblyBegin(A, MAT_FINAL_ASSEMBLY));
  PetscCall(MatAssemblyEnd(A, MAT_FINAL_ASSEMBLY));
  PetscCall(DMCreateGlobalVector(m.dm, &U));
  {
    PetscInt lo, hi;
    PetscCall(VecGetOwnershipRange(U, &lo, &hi));
    for (PetscInt i = lo; i < hi; i++) PetscCall(VecSetValue(U, i, 0.3 * Hash(i, 7, 11), INSERT_VALUES));
    PetscCall(VecAssemblyBegin(U));
    PetscCall(VecAssemblyEnd(U));
  }

  for (PetscInt t = 0; t < 2; t++) {
    const PetscReal H = t ? 0.6 : 3.0, nrm[3] = {0, 0, 2};
    SheetCoarse     sc;
    Mat             P, Ptap, Ac;
    PetscInt        nodes, colours, N;
    PetscScalar    *v, *y1, *y2;
    PetscReal       err = 0, scale = 0;

    PetscCall(SheetCoarseCreate(PETSC_COMM_WORLD, H, nrm, &sc));
    /* set up first at the reference positions, then at the iterate U: the second setup keeps the
       grid and refreshes the positions, and must give the basis of a fresh setup at U */
    PetscCall(SheetCoarseSetUp(sc, m.dm, A, NULL, NULL, NULL));
    {
      Mat         P0, P2;
      SheetCoarse sc2;
      PetscReal   d0, d2, n2;
      PetscCall(SheetCoarseGetBasis(sc, &P0));
      PetscCall(SheetCoarseSetUp(sc, m.dm, A, U, NULL, NULL));
      PetscCall(SheetCoarseGetBasis(sc, &P));
      PetscCall(SheetCoarseCreate(PETSC_COMM_WORLD, H, nrm, &sc2));
      PetscCall(SheetCoarseSetUp(sc2, m.dm, A, U, NULL, NULL));
      PetscCall(SheetCoarseGetBasis(sc2, &P2));
      PetscCall(MatNorm(P2, NORM_FROBENIUS, &n2));
      PetscCall(MatAXPY(P0, -1.0, P, DIFFERENT_NONZERO_PATTERN));
      PetscCall(MatAXPY(P2, -1.0, P, DIFFERENT_NONZERO_PATTERN));
      PetscCall(MatNorm(P0, NORM_FROBENIUS, &d0));
      PetscCall(MatNorm(P2, NORM_FROBENIUS, &d2));
      CHECK_ALL(n2 > 0 && d2 == 0 && d0 > 1e-3 * n2, "spacing %g: a second setup at another iterate gives the basis of a fresh one (difference %.2e; %.2e from the first setup's, of %.2e)", (double)H, (double)d2, (double)d0, (double)n2);
      PetscCall(MatDestroy(&P0));
      PetscCall(MatDestroy(&P2));
      PetscCall(SheetCoarseDestroy(&sc2));
    }
    PetscCall(SheetCoarseGetSize(sc, &nodes, &colours));
    PetscCall(SheetCoarseGetOperator(sc, &Ac));
    N = 6 * nodes;

    /* 2. partition of unity */
    {
      Vec       cv, f;
      PetscInt  lo, hi, r0;
      PetscReal e = 0;
      const PetscScalar *fa;
      PetscCall(MatCreateVecs(P, &cv, &f));
      PetscCall(VecGetOwnershipRange(cv, &lo, &hi));
      for (PetscInt i = lo; i < hi; i++) PetscCall(VecSetValue(cv, i, i % 6 == 0 ? 1.0 : 0.0, INSERT_VALUES));
      PetscCall(VecAssemblyBegin(cv));
      PetscCall(VecAssemblyEnd(cv));
      PetscCall(MatMult(P, cv, f));
      PetscCall(VecGetOwnershipRange(f, &r0, NULL));
      PetscCall(VecGetArrayRead(f, &fa));
      for (PetscInt v = 0; v < m.nv; v++) {
        PetscInt idx[3];
        PetscCall(MeshVertexDofs(&m, v, idx));
        if (!m.vowned[v]) continue;
        for (int c = 0; c < 3; c++)
          if (idx[c] >= 0) e = PetscMax(e, PetscAbsReal(PetscRealPart(fa[idx[c] - r0]) - (c == 0 ? 1.0 : 0.0)));
      }
      PetscCall(VecRestoreArrayRead(f, &fa));
      CHECK_ALL(e < 1e-12, "spacing %g: P times the x translations is 1 on the x rows, 0 on the others (largest error %.2e; %" PetscInt_FMT " grid nodes)", (double)H, (double)e, nodes);
      PetscCall(VecDestroy(&cv));
      PetscCall(VecDestroy(&f));
    }

    /* 3. A_c against P^T A P */
    PetscCall(MatPtAP(A, P, MAT_INITIAL_MATRIX, 2.0, &Ptap));
    PetscCall(PetscMalloc3(N, &v, N, &y1, N, &y2));
    for (PetscInt k = 0; k < 3; k++) { /* A_c lives on rank 0 only */
      for (PetscInt i = 0; i < N; i++) v[i] = Hash(k, i, 3);
      if (rank == 0) {
        Vec vs, ys;
        PetscCall(VecCreateSeqWithArray(PETSC_COMM_SELF, 1, N, v, &vs));
        PetscCall(VecCreateSeqWithArray(PETSC_COMM_SELF, 1, N, y1, &ys));
        PetscCall(MatMult(Ac, vs, ys));
        PetscCall(VecDestroy(&vs));
        PetscCall(VecDestroy(&ys));
      }
      PetscCall(Galerkin(Ptap, v, N, y2));
      for (PetscInt i = 0; i < N && rank == 0; i++) {
        err   = PetscMax(err, PetscAbsScalar(y1[i] - y2[i]));
        scale = PetscMax(scale, PetscAbsScalar(y2[i]));
      }
    }
    if (rank) scale = 1;
    CHECK_ALL((rank == 0) == (Ac != NULL) && scale > 0 && err <= 1e-9 * scale, "spacing %g (%" PetscInt_FMT " colours): A_c by colouring = P^T A P on 3 random vectors (largest difference %.2e of %.2e)", (double)H, colours, (double)err, (double)scale);
    if (t == 0) CHECK_ALL(colours == 25, "spacing %g, cells smaller than it: 25 colours (%" PetscInt_FMT ")", (double)H, colours);
    else CHECK_ALL(colours > 25, "spacing %g, cells larger than it: a larger reach, %" PetscInt_FMT " colours", (double)H, colours);

    /* 4. Galerkin orthogonality of the correction */
    {
      Vec       r, yv, res, pr, pres;
      PetscReal a, b;
      PetscInt  lo, hi;
      PetscCall(MatCreateVecs(A, &yv, &r));
      PetscCall(VecDuplicate(r, &res));
      PetscCall(VecGetOwnershipRange(r, &lo, &hi));
      for (PetscInt i = lo; i < hi; i++) PetscCall(VecSetValue(r, i, Hash(i, 5, 9), INSERT_VALUES));
      PetscCall(VecAssemblyBegin(r));
      PetscCall(VecAssemblyEnd(r));
      PetscCall(VecSet(yv, 0));
      PetscCall(SheetCoarseApply(sc, r, yv));
      PetscCall(MatMult(A, yv, res));
      PetscCall(VecAYPX(res, -1.0, r));
      PetscCall(MatCreateVecs(P, &pr, NULL));
      PetscCall(VecDuplicate(pr, &pres));
      PetscCall(MatMultTranspose(P, r, pr));
      PetscCall(MatMultTranspose(P, res, pres));
      PetscCall(VecNorm(pr, NORM_INFINITY, &a));
      PetscCall(VecNorm(pres, NORM_INFINITY, &b));
      CHECK_ALL(a > 0 && b <= 1e-6 * a, "spacing %g: P^T (r - A y) = %.2e of P^T r after the correction", (double)H, (double)(b / a));
      /* a residual that is not finite (a Krylov breakdown): the correction is NaN everywhere, so
         that the Krylov method stops on it, not an error that ends the run */
      if (rank == 0 && lo < hi) PetscCall(VecSetValue(r, lo, NAN, INSERT_VALUES));
      PetscCall(VecAssemblyBegin(r));
      PetscCall(VecAssemblyEnd(r));
      PetscCall(VecSet(yv, 0));
      PetscCall(SheetCoarseApply(sc, r, yv));
      {
        PetscInt           nl, nnan = 0;
        const PetscScalar *ya;
        PetscCall(VecGetLocalSize(yv, &nl));
        PetscCall(VecGetArrayRead(yv, &ya));
        for (PetscInt i = 0; i < nl; i++) nnan += PetscIsInfOrNanScalar(ya[i]) ? 1 : 0;
        PetscCall(VecRestoreArrayRead(yv, &ya));
        CHECK_ALL(nnan == nl, "spacing %g: a residual that is not finite on one rank gives a correction that is NaN on every rank (%" PetscInt_FMT " of %" PetscInt_FMT " local entries here)", (double)H, nnan, nl);
      }
      PetscCall(VecDestroy(&r));
      PetscCall(VecDestroy(&yv));
      PetscCall(VecDestroy(&res));
      PetscCall(VecDestroy(&pr));
      PetscCall(VecDestroy(&pres));
    }
    PetscCall(PetscFree3(v, y1, y2));
    PetscCall(MatDestroy(&Ptap));
    PetscCall(MatDestroy(&P));
    PetscCall(SheetCoarseDestroy(&sc));
  }

  /* bad input: one line naming the option */
  {
    SheetCoarse    sc;
    const PetscReal nrm[3] = {0, 0, 0};
    PetscErrorCode ierr;
    PetscCall(PetscPushErrorHandler(PetscReturnErrorHandler, NULL));
    ierr = SheetCoarseCreate(PETSC_COMM_WORLD, 1.0, nrm, &sc);
    PetscCall(PetscPopErrorHandler());
    CHECK_ALL(ierr == PETSC_ERR_USER_INPUT, "a zero normal is refused (-pc_amgsys_sheet_normal)");
  }
  PetscCall(VecDestroy(&U));
  PetscCall(MatDestroy(&A));
  PetscCall(BCDestroy(&bcs));
  PetscCall(MeshDestroy(&m));
  PetscCall(PetscFinalize());
  TU_RETURN();
}
