/* A coarse space of plate-like modes for thin sheets: the coarse correction of -pc_type amgsys
   with -pc_amgsys_sheet_spacing H (src/solver/amg.c; doc/notes/performance-log.md, "One million
   hexahedra").

   Why: BoomerAMG's V-cycle on a sheet of a few hexahedra through its thickness leaves the sheet's
   bending modes almost untouched. The displacements of a bending mode vary smoothly in the plane,
   but their through-thickness pattern (a rotation of each fibre) is one that the unknown approach
   (each displacement component coarsened and interpolated on its own) does not interpolate: on the
   whole blank of 25 600 hexahedra the V-cycle alone, as a stationary iteration, reduces the
   residual by 0.996 per cycle, and the Krylov method spends its iterations on these modes, more
   of them as the mesh is refined (up to 38, 51, 54 and 78 iterations per Newton iteration at
   25 600, 100 352, 250 512 and 1 010 224 hexahedra; with this space 4, 5, 7 and 7). A coarse space that holds them: bilinear hats on a
   square grid of spacing H in the sheet's plane, each times the six rigid-body modes,

       P e_(K,m) = phi_K(s(X)) r_m(x - c_K),      m = translations x, y, z; rotations about x, y, z,

   with s(X) the reference position projected on the plane (two orthonormal axes normal to
   -pc_amgsys_sheet_normal), x the current position (reference plus the iterate at which the
   Jacobian was assembled), c_K the grid node in 3D. Piecewise rigid motions blended by the hats:
   a fibre's rotation is a rotation mode, the sheet's smooth deflection a combination of the
   translation and rotation modes of neighbouring nodes. The Galerkin operator A_c = P^T A P is
   small (six unknowns per grid node: 4 680 for H = 4 mm on the 118 mm blank) and factored by LU
   on rank 0 (the restricted residual summed there, the coarse solution broadcast); amgsys
   applies it after its V-cycle, on the V-cycle's residual:

       y = B r,   y <- y + P A_c^-1 P^T (r - A y).

   A_c by colouring, without forming A P: hat K's support is the open square of side 2H around
   c_K, and A couples nodes of one cell, whose in-plane extent is at most hmax. So
   (P e_L)^T A (P e_K) vanishes unless |L - K| < 2 + hmax / H in both grid directions (in grid
   units), i.e. |L - K| <= reach = ceil(2 + hmax/H) - 1 (2 when the cells are smaller than H).
   Colour the grid nodes by (i mod q, j mod q), q = 2 reach + 1: two nodes of one colour lie q
   apart in some direction, so every L sees at most one node K of a colour within its reach, and
   one product A z, with z the sum of mode m over the colour's nodes, gives the blocks
   A_c[(L, m'), (K, m)] of all L at once: q^2 x 6 products in all (150 for reach 2).

   The approximations (reference positions for the hats, the positions at the Jacobian's iterate
   for the rotations, the constrained components left out) only change the preconditioner: the
   Krylov method still solves with the assembled Jacobian. A_c is singular where a grid node's
   support is one column of nodes (a rotation about the normal there is a translation): a shift of
   1e-12 of its largest diagonal entry makes it definite, and since P v = 0 for such a v the
   correction is unchanged. */
#include <petscksp.h>
#include <petscdmplex.h>
#include <petscsection.h>

#include "sheetcoarse.h"

struct _p_SheetCoarse {
  MPI_Comm   comm;
  PetscReal  H, e[3][3];   /* spacing; in-plane axes e[0], e[1], normal e[2]                */
  PetscReal  o[2];         /* grid origin in plane coordinates                              */
  PetscInt   ng[2];        /* grid nodes per direction                                      */
  PetscInt   reach, q;     /* couplings within reach grid nodes; colours modulo q           */
  PetscInt   n, rstart;    /* the local rows of the operator                                */
  PetscInt   nv;           /* owned mesh nodes with rows; per node (a few bytes per row):  */
  PetscInt  *row0, *base;  /*   its first local row; grid index of its hat cell's corner   */
  unsigned char *mask;     /*   bit c: component c has a row (the next one)                */
  float     *uw, *x;       /*   position in the hat cell (2); current position (3): single
                                precision, the same in the setup and every application     */
  PetscInt  *act, nc;      /* grid node -> active coarse node (or -1); active nodes         */
  PetscReal *w, *xv;       /* 6 nc: the restricted residual; 6 nc + 1: the coarse solution and
                              a flag, broadcast from rank 0                                 */
  PetscMPIInt rank;
  Mat        Ac;           /* rank 0 only: A_c, its LU, its vectors                          */
  KSP        ksp;
  Vec        bc, xc;
};

PetscReal SheetModeValue(PetscInt m, PetscInt c, const PetscReal d[3], PetscReal H)
{
  switch (m) {
  case 0:
  case 1:
  case 2:
    return m == c ? 1.0 : 0.0;
  case 3: /* e_x x d = (0, -d_z, d_y) */
    return c == 1 ? -d[2] / H : c == 2 ? d[1] / H : 0.0;
  case 4: /* e_y x d = (d_z, 0, -d_x) */
    return c == 0 ? d[2] / H : c == 2 ? -d[0] / H : 0.0;
  default: /* e_z x d = (-d_y, d_x, 0) */
    return c == 0 ? -d[1] / H : c == 1 ? d[0] / H : 0.0;
  }
}

PetscErrorCode SheetCoarseCreate(MPI_Comm comm, PetscReal H, const PetscReal normal[3], SheetCoarse *out)
{
  SheetCoarse sc;
  PetscReal   nn = PetscSqrtReal(normal[0] * normal[0] + normal[1] * normal[1] + normal[2] * normal[2]), a[3] = {0, 0, 0}, ad;

  PetscFunctionBeginUser;
  PetscCheck(H > 0, comm, PETSC_ERR_USER_INPUT, "-pc_amgsys_sheet_spacing %g: the coarse grid's spacing must be > 0", (double)H);
  PetscCheck(nn > 0, comm, PETSC_ERR_USER_INPUT, "-pc_amgsys_sheet_normal: the sheet's normal must not be zero");
  PetscCall(PetscNew(&sc));
  sc->comm = comm;
  PetscCallMPI(MPI_Comm_rank(comm, &sc->rank));
  sc->H    = H;
  for (int k = 0; k < 3; k++) sc->e[2][k] = normal[k] / nn;
  a[PetscAbsReal(sc->e[2][0]) < 0.9 ? 0 : 1] = 1; /* an axis not along the normal */
  ad = a[0] * sc->e[2][0] + a[1] * sc->e[2][1] + a[2] * sc->e[2][2];
  for (int k = 0; k < 3; k++) sc->e[0][k] = a[k] - ad * sc->e[2][k];
  nn = PetscSqrtReal(sc->e[0][0] * sc->e[0][0] + sc->e[0][1] * sc->e[0][1] + sc->e[0][2] * sc->e[0][2]);
  for (int k = 0; k < 3; k++) sc->e[0][k] /= nn;
  sc->e[1][0] = sc->e[2][1] * sc->e[0][2] - sc->e[2][2] * sc->e[0][1];
  sc->e[1][1] = sc->e[2][2] * sc->e[0][0] - sc->e[2][0] * sc->e[0][2];
  sc->e[1][2] = sc->e[2][0] * sc->e[0][1] - sc->e[2][1] * sc->e[0][0];
  *out = sc;
  PetscFunctionReturn(0);
}

static PetscErrorCode FreeLayout(SheetCoarse sc)
{
  PetscFunctionBeginUser;
  PetscCall(PetscFree(sc->row0));
  PetscCall(PetscFree(sc->base));
  PetscCall(PetscFree(sc->mask));
  PetscCall(PetscFree(sc->uw));
  PetscCall(PetscFree(sc->x));
  PetscCall(PetscFree(sc->act));
  PetscCall(PetscFree(sc->w));
  PetscCall(PetscFree(sc->xv));
  PetscCall(MatDestroy(&sc->Ac));
  PetscCall(KSPDestroy(&sc->ksp));
  PetscCall(VecDestroy(&sc->bc));
  PetscCall(VecDestroy(&sc->xc));
  sc->n  = 0;
  sc->nv = 0;
  sc->nc = 0;
  PetscFunctionReturn(0);
}

PetscErrorCode SheetCoarseDestroy(SheetCoarse *sc)
{
  PetscFunctionBeginUser;
  if (!*sc) PetscFunctionReturn(0);
  PetscCall(FreeLayout(*sc));
  PetscCall(PetscFree(*sc));
  PetscFunctionReturn(0);
}

/* the 4 hats of node i: grid node, weight (0 where the node lies on the hat's edge), arm x - c_K */
static inline void Hats(SheetCoarse sc, PetscInt i, PetscInt g[4], PetscReal phi[4], PetscReal d[4][3])
{
  const PetscInt  b = sc->base[i], bx = b % sc->ng[0], by = b / sc->ng[0];
  const PetscReal u = (PetscReal)sc->uw[2 * i], w = (PetscReal)sc->uw[2 * i + 1];
  for (PetscInt k = 0; k < 4; k++) {
    const PetscInt  ax = k & 1, ay = k >> 1;
    const PetscReal s0 = sc->o[0] + (PetscReal)(bx + ax) * sc->H, s1 = sc->o[1] + (PetscReal)(by + ay) * sc->H;
    g[k]   = b + ax + ay * sc->ng[0];
    phi[k] = (ax ? u : 1 - u) * (ay ? w : 1 - w);
    for (int c = 0; c < 3; c++) d[k][c] = (PetscReal)sc->x[3 * i + c] - (s0 * sc->e[0][c] + s1 * sc->e[1][c]);
  }
}

/* rows: component, reference and current position, hat cell; the grid and its active nodes. All
   but the current positions depend on the reference configuration only: they are built at the
   first setup (and again if the row layout changes); later setups refresh the positions. */
static PetscErrorCode Layout(SheetCoarse sc, DM dm, Mat A, Vec U)
{
  PetscSection       s, gs, cs;
  Vec                cl;
  const PetscScalar *ca, *ua = NULL;
  PetscInt           pStart, pEnd, rend, nset = 0, lerr, gerr;
  PetscReal          lo[4], hi[4], hmax = 0, *sp = NULL;
  PetscBool          build = PETSC_FALSE;
  DM                 cdm;

  PetscFunctionBeginUser;
  PetscCall(MatGetOwnershipRange(A, &sc->rstart, &rend));
  PetscCall(DMGetLocalSection(dm, &s));
  PetscCall(DMGetGlobalSection(dm, &gs));
  PetscCall(DMGetCoordinateSection(dm, &cs));
  PetscCall(DMGetCoordinatesLocal(dm, &cl));
  PetscCall(PetscSectionGetChart(s, &pStart, &pEnd));
  if (sc->n != rend - sc->rstart || !sc->base) { /* the owned nodes with rows, in the rows' order */
    PetscInt nv = 0;
    build = PETSC_TRUE;
    PetscCall(FreeLayout(sc));
    sc->n = rend - sc->rstart;
    for (PetscInt p = pStart; p < pEnd; p++) {
      PetscInt dof, cdof, gdof, goff;
      PetscCall(PetscSectionGetDof(s, p, &dof));
      PetscCall(PetscSectionGetConstraintDof(s, p, &cdof));
      if (dof - cdof <= 0) continue;
      PetscCall(PetscSectionGetDof(gs, p, &gdof));
      PetscCall(PetscSectionGetOffset(gs, p, &goff));
      if (gdof > 0 && goff >= 0) nv++;
    }
    sc->nv = nv;
    PetscCall(PetscMalloc1(nv, &sc->row0));
    PetscCall(PetscMalloc1(nv, &sc->base));
    PetscCall(PetscMalloc1(nv, &sc->mask));
    PetscCall(PetscMalloc1(2 * nv, &sc->uw));
    PetscCall(PetscMalloc1(3 * nv, &sc->x));
  }
  if (build) PetscCall(PetscMalloc1(2 * sc->nv, &sp));
  PetscCall(VecGetArrayRead(cl, &ca));
  if (U) {
    PetscInt un;
    PetscCall(VecGetLocalSize(U, &un));
    if (un == sc->n) PetscCall(VecGetArrayRead(U, &ua)); /* else: the reference positions */
  }
  for (PetscInt p = pStart, v = 0; p < pEnd; p++) {
    PetscInt        dof, cdof, goff, gdof, coff, ncd, r0 = -1;
    const PetscInt *cind = NULL;
    PetscReal       X[3] = {0, 0, 0}, u[3] = {0, 0, 0};
    unsigned char   mask = 0;
    PetscCall(PetscSectionGetDof(s, p, &dof));
    PetscCall(PetscSectionGetConstraintDof(s, p, &cdof));
    if (dof - cdof <= 0) continue;
    PetscCall(PetscSectionGetDof(gs, p, &gdof));
    PetscCall(PetscSectionGetOffset(gs, p, &goff));
    if (gdof <= 0 || goff < 0) continue;
    PetscCall(PetscSectionGetDof(cs, p, &ncd));
    PetscCall(PetscSectionGetOffset(cs, p, &coff));
    for (PetscInt c = 0; c < PetscMin(ncd, 3); c++) X[c] = PetscRealPart(ca[coff + c]);
    if (cdof) PetscCall(PetscSectionGetConstraintIndices(s, p, &cind));
    for (PetscInt c = 0, k = 0, j = 0; c < dof && c < 3; c++) {
      if (j < cdof && cind[j] == c) {
        j++;
        continue;
      }
      const PetscInt r = goff - sc->rstart + k++;
      if (r < 0 || r >= sc->n) continue;
      if (r0 < 0) r0 = r;
      mask |= (unsigned char)(1u << c);
      nset++;
      if (ua) u[c] = PetscRealPart(ua[r]);
    }
    if (v >= sc->nv) { /* more nodes than counted: the layout changed, caught below */
      nset = -1;
      break;
    }
    sc->row0[v] = r0;
    sc->mask[v] = mask;
    for (int c = 0; c < 3; c++) sc->x[3 * v + c] = (float)(X[c] + u[c]);
    if (sp) {
      sp[2 * v]     = X[0] * sc->e[0][0] + X[1] * sc->e[0][1] + X[2] * sc->e[0][2];
      sp[2 * v + 1] = X[0] * sc->e[1][0] + X[1] * sc->e[1][1] + X[2] * sc->e[1][2];
    }
    v++;
  }
  PetscCall(VecRestoreArrayRead(cl, &ca));
  if (ua) PetscCall(VecRestoreArrayRead(U, &ua));
  lerr = nset != sc->n;
  PetscCall(MPIU_Allreduce(&lerr, &gerr, 1, MPIU_INT, MPI_MAX, sc->comm));
  if (gerr) PetscCall(PetscFree(sp));
  PetscCheck(!gerr, sc->comm, PETSC_ERR_SUP, "-pc_amgsys_sheet_spacing: the Jacobian has rows that are not the mesh's displacement unknowns");
  if (!build) PetscFunctionReturn(0);

  /* the grid: the bounding box of the reference positions in the plane; the largest in-plane
     extent of a cell (the reach of A's couplings) */
  {
    PetscInt cStart, cEnd;
    PetscCall(DMGetCoordinateDM(dm, &cdm));
    PetscCall(DMPlexGetHeightStratum(dm, 0, &cStart, &cEnd));
    for (PetscInt c = cStart; c < cEnd; c++) {
      PetscScalar *cc = NULL;
      PetscInt     sz;
      PetscReal    l0 = PETSC_MAX_REAL, l1 = PETSC_MAX_REAL, h0 = -PETSC_MAX_REAL, h1 = -PETSC_MAX_REAL;
      PetscCall(DMPlexVecGetClosure(cdm, cs, cl, c, &sz, &cc));
      for (PetscInt v = 0; v + 2 < sz; v += 3) {
        const PetscReal a0 = PetscRealPart(cc[v]) * sc->e[0][0] + PetscRealPart(cc[v + 1]) * sc->e[0][1] + PetscRealPart(cc[v + 2]) * sc->e[0][2];
        const PetscReal a1 = PetscRealPart(cc[v]) * sc->e[1][0] + PetscRealPart(cc[v + 1]) * sc->e[1][1] + PetscRealPart(cc[v + 2]) * sc->e[1][2];
        l0 = PetscMin(l0, a0), h0 = PetscMax(h0, a0), l1 = PetscMin(l1, a1), h1 = PetscMax(h1, a1);
      }
      PetscCall(DMPlexVecRestoreClosure(cdm, cs, cl, c, &sz, &cc));
      hmax = PetscMax(hmax, PetscMax(h0 - l0, h1 - l1));
    }
  }
  lo[0] = lo[1] = PETSC_MAX_REAL;
  hi[0] = hi[1] = -PETSC_MAX_REAL;
  for (PetscInt i = 0; i < sc->nv; i++)
    for (int k = 0; k < 2; k++) lo[k] = PetscMin(lo[k], sp[2 * i + k]), hi[k] = PetscMax(hi[k], sp[2 * i + k]);
  lo[2] = -hi[0], lo[3] = -hi[1], hi[2] = hmax;
  {
    PetscReal g[4];
    PetscCall(MPIU_Allreduce(lo, g, 4, MPIU_REAL, MPIU_MIN, sc->comm));
    PetscCall(MPIU_Allreduce(&hi[2], &hmax, 1, MPIU_REAL, MPIU_MAX, sc->comm));
    sc->o[0] = g[0], sc->o[1] = g[1], hi[0] = -g[2], hi[1] = -g[3];
  }
  {
    const PetscReal n0 = (hi[0] - sc->o[0]) / sc->H + 2, n1 = (hi[1] - sc->o[1]) / sc->H + 2;
    PetscCheck(n0 * n1 <= 1e7, sc->comm, PETSC_ERR_USER_INPUT, "-pc_amgsys_sheet_spacing %g: a grid of %g x %g nodes over the sheet is too fine (at most 1e7 nodes)", (double)sc->H, (double)n0, (double)n1);
    sc->ng[0] = PetscMax(2, (PetscInt)n0);
    sc->ng[1] = PetscMax(2, (PetscInt)n1);
  }
  sc->reach = (PetscInt)PetscCeilReal(2 + hmax / sc->H) - 1;
  sc->q     = 2 * sc->reach + 1;
  for (PetscInt i = 0; i < sc->nv; i++) {
    const PetscReal f0 = (sp[2 * i] - sc->o[0]) / sc->H, f1 = (sp[2 * i + 1] - sc->o[1]) / sc->H;
    const PetscInt  bx = PetscMin(PetscMax((PetscInt)PetscFloorReal(f0), 0), sc->ng[0] - 2);
    const PetscInt  by = PetscMin(PetscMax((PetscInt)PetscFloorReal(f1), 0), sc->ng[1] - 2);
    sc->base[i]       = bx + by * sc->ng[0];
    sc->uw[2 * i]     = (float)PetscMin(PetscMax(f0 - (PetscReal)bx, 0.0), 1.0);
    sc->uw[2 * i + 1] = (float)PetscMin(PetscMax(f1 - (PetscReal)by, 0.0), 1.0);
  }
  PetscCall(PetscFree(sp));

  /* active nodes: those with a row of positive weight, on any rank */
  {
    const PetscInt ng = sc->ng[0] * sc->ng[1];
    PetscMPIInt   *f, *gf;
    PetscCall(PetscFree(sc->act));
    PetscCall(PetscCalloc1(ng, &f));
    PetscCall(PetscMalloc1(ng, &gf));
    for (PetscInt i = 0; i < sc->nv; i++) {
      PetscInt  g[4];
      PetscReal phi[4], d[4][3];
      Hats(sc, i, g, phi, d);
      for (int k = 0; k < 4; k++)
        if (phi[k] > 0) f[g[k]] = 1;
    }
    PetscCall(MPIU_Allreduce(f, gf, (PetscMPIInt)ng, MPI_INT, MPI_MAX, sc->comm));
    PetscCall(PetscMalloc1(ng, &sc->act));
    sc->nc = 0;
    for (PetscInt g = 0; g < ng; g++) sc->act[g] = gf[g] ? sc->nc++ : -1;
    PetscCall(PetscFree(f));
    PetscCall(PetscFree(gf));
  }
  PetscFunctionReturn(0);
}

PetscErrorCode SheetCoarseSetUp(SheetCoarse sc, DM dm, Mat A, Vec U, Vec wz, Vec wy)
{
  PetscInt       q, R, nblk;
  Vec            z = wz, y = wy;
  PetscReal     *blk;

  PetscFunctionBeginUser;
  PetscCall(Layout(sc, dm, A, U));
  q    = sc->q;
  R    = sc->reach;
  PetscCheck((PetscInt64)sc->nc * q * q * 36 < PETSC_MPI_INT_MAX, sc->comm, PETSC_ERR_SUP, "-pc_amgsys_sheet_spacing %g: %" PetscInt_FMT " coarse nodes are too many; take a larger spacing", (double)sc->H, sc->nc);
  nblk = sc->nc * q * q * 36;
  PetscCall(PetscCalloc1(nblk, &blk));
  if (!wz) PetscCall(MatCreateVecs(A, &z, NULL));
  if (!wy) PetscCall(MatCreateVecs(A, NULL, &y));
  for (PetscInt cy = 0; cy < q; cy++)
    for (PetscInt cx = 0; cx < q; cx++)
      for (PetscInt m = 0; m < 6; m++) {
        PetscScalar       *za;
        const PetscScalar *ya;
        PetscCall(VecGetArrayWrite(z, &za));
        for (PetscInt v = 0; v < sc->nv; v++) {
          PetscInt  g[4];
          PetscReal phi[4], d[4][3];
          Hats(sc, v, g, phi, d);
          for (PetscInt c = 0, r = sc->row0[v]; c < 3; c++) {
            PetscReal val = 0;
            if (!(sc->mask[v] >> c & 1)) continue;
            for (int k = 0; k < 4; k++) {
              const PetscInt gx = g[k] % sc->ng[0], gy = g[k] / sc->ng[0];
              if (phi[k] > 0 && gx % q == cx && gy % q == cy && sc->act[g[k]] >= 0) val += phi[k] * SheetModeValue(m, c, d[k], sc->H);
            }
            za[r++] = val;
          }
        }
        PetscCall(VecRestoreArrayWrite(z, &za));
        PetscCall(MatMult(A, z, y));
        PetscCall(VecGetArrayRead(y, &ya));
        for (PetscInt v = 0; v < sc->nv; v++) {
          PetscInt  g[4], off[4];
          PetscReal phi[4], d[4][3];
          Hats(sc, v, g, phi, d);
          for (int k = 0; k < 4; k++) { /* the block of hat k's node L with the colour's node K near it */
            const PetscInt L = sc->act[g[k]], lx = g[k] % sc->ng[0], ly = g[k] / sc->ng[0];
            PetscInt       ox, oy, kx, ky;
            off[k] = -1;
            if (phi[k] <= 0 || L < 0) continue;
            ox = ((cx - lx) % q + q) % q;
            oy = ((cy - ly) % q + q) % q;
            if (ox > R) ox -= q;
            if (oy > R) oy -= q;
            kx = lx + ox, ky = ly + oy;
            if (kx < 0 || ky < 0 || kx >= sc->ng[0] || ky >= sc->ng[1] || sc->act[kx + ky * sc->ng[0]] < 0) continue;
            off[k] = ((L * q * q) + (ox + R) + q * (oy + R)) * 36 + m;
          }
          for (PetscInt c = 0, r = sc->row0[v]; c < 3; c++) {
            PetscReal yr;
            if (!(sc->mask[v] >> c & 1)) continue;
            yr = PetscRealPart(ya[r++]);
            if (yr == 0) continue;
            for (int k = 0; k < 4; k++)
              if (off[k] >= 0)
                for (PetscInt mp = 0; mp < 6; mp++) blk[off[k] + 6 * mp] += phi[k] * SheetModeValue(mp, c, d[k], sc->H) * yr;
          }
        }
        PetscCall(VecRestoreArrayRead(y, &ya));
      }
  if (!wz) PetscCall(VecDestroy(&z));
  if (!wy) PetscCall(VecDestroy(&y));
  PetscCallMPI(MPI_Reduce(sc->rank ? blk : MPI_IN_PLACE, blk, (PetscMPIInt)nblk, MPIU_REAL, MPI_SUM, 0, sc->comm));

  /* A_c and its LU on rank 0 (one copy, whatever the ranks); the others wait for its verdict */
  {
    const PetscInt N = 6 * sc->nc;
    PetscInt       failed = 0;
    PetscCall(PetscFree(sc->w));
    PetscCall(PetscFree(sc->xv));
    PetscCall(PetscMalloc1(PetscMax(N, 1), &sc->w));
    PetscCall(PetscMalloc1(N + 1, &sc->xv));
    if (sc->rank == 0) {
      PetscReal dmax = 0;
      PC        pc;
      PetscCall(MatDestroy(&sc->Ac));
      PetscCall(MatCreateSeqAIJ(PETSC_COMM_SELF, N, N, 6 * q * q, NULL, &sc->Ac));
      for (PetscInt L = 0; L < sc->nc; L++) /* the largest diagonal entry: the shift's scale */
        for (int k = 0; k < 6; k++) dmax = PetscMax(dmax, PetscAbsReal(blk[((L * q * q) + R + q * R) * 36 + 7 * k]));
      for (PetscInt L = 0; L < sc->nc; L++)
        for (int k = 0; k < 6; k++) blk[((L * q * q) + R + q * R) * 36 + 7 * k] += 1e-12 * dmax;
      for (PetscInt gy = 0; gy < sc->ng[1]; gy++)
        for (PetscInt gx = 0; gx < sc->ng[0]; gx++) {
          const PetscInt L = sc->act[gx + gy * sc->ng[0]];
          if (L < 0) continue;
          for (PetscInt oy = -R; oy <= R; oy++)
            for (PetscInt ox = -R; ox <= R; ox++) {
              const PetscInt kx = gx + ox, ky = gy + oy;
              PetscInt       K, rows[6], cols[6];
              if (kx < 0 || ky < 0 || kx >= sc->ng[0] || ky >= sc->ng[1] || (K = sc->act[kx + ky * sc->ng[0]]) < 0) continue;
              for (int k = 0; k < 6; k++) rows[k] = 6 * L + k, cols[k] = 6 * K + k;
              PetscCall(MatSetValues(sc->Ac, 6, rows, 6, cols, &blk[((L * q * q) + (ox + R) + q * (oy + R)) * 36], INSERT_VALUES));
            }
        }
      PetscCall(MatAssemblyBegin(sc->Ac, MAT_FINAL_ASSEMBLY));
      PetscCall(MatAssemblyEnd(sc->Ac, MAT_FINAL_ASSEMBLY));
      if (!sc->ksp) {
        PetscCall(KSPCreate(PETSC_COMM_SELF, &sc->ksp));
        PetscCall(KSPSetOptionsPrefix(sc->ksp, "pc_amgsys_sheet_")); /* not the outer -ksp_ options */
        PetscCall(KSPSetType(sc->ksp, KSPPREONLY));
        PetscCall(KSPGetPC(sc->ksp, &pc));
        PetscCall(PCSetType(pc, PCLU));
        PetscCall(PCFactorSetMatSolverType(pc, MATSOLVERMUMPS));
        PetscCall(KSPSetFromOptions(sc->ksp)); /* -pc_amgsys_sheet_ksp_..., -pc_amgsys_sheet_pc_... */
      }
      PetscCall(KSPSetOperators(sc->ksp, sc->Ac, sc->Ac));
      { /* a failure here is told to the other ranks, which wait in the broadcast below */
        PCFailedReason r;
        PetscErrorCode ierr;
        PetscCall(PetscPushErrorHandler(PetscReturnErrorHandler, NULL));
        ierr = KSPSetUp(sc->ksp);
        PetscCall(PetscPopErrorHandler());
        PetscCall(KSPGetPC(sc->ksp, &pc));
        PetscCall(PCGetFailedReason(pc, &r));
        failed = ierr || r != PC_NOERROR;
      }
      PetscCall(VecDestroy(&sc->bc));
      PetscCall(VecDestroy(&sc->xc));
      PetscCall(MatCreateVecs(sc->Ac, &sc->xc, &sc->bc));
    }
    PetscCall(PetscFree(blk));
    PetscCallMPI(MPI_Bcast(&failed, 1, MPIU_INT, 0, sc->comm));
    PetscCheck(!failed, sc->comm, PETSC_ERR_NOT_CONVERGED, "-pc_amgsys_sheet_spacing %g: the LU of the coarse operator (%" PetscInt_FMT " unknowns) failed", (double)sc->H, N);
  }
  PetscFunctionReturn(0);
}

PetscErrorCode SheetCoarseApply(SheetCoarse sc, Vec r, Vec y)
{
  const PetscInt     N = 6 * sc->nc;
  const PetscScalar *ra, *xa;
  PetscScalar       *ya, *ba;
  PetscInt           lbad = 0, gbad;

  PetscFunctionBeginUser;
  for (PetscInt k = 0; k < N; k++) sc->w[k] = 0;
  PetscCall(VecGetArrayRead(r, &ra));
  for (PetscInt v = 0; v < sc->nv; v++) {
    PetscInt  g[4];
    PetscReal phi[4], d[4][3];
    Hats(sc, v, g, phi, d);
    for (PetscInt c = 0, i = sc->row0[v]; c < 3; c++) {
      PetscReal rv;
      if (!(sc->mask[v] >> c & 1)) continue;
      rv = PetscRealPart(ra[i++]);
      for (int k = 0; k < 4; k++) {
        const PetscInt K = sc->act[g[k]];
        if (phi[k] <= 0 || K < 0) continue;
        for (PetscInt m = 0; m < 6; m++) sc->w[6 * K + m] += phi[k] * SheetModeValue(m, c, d[k], sc->H) * rv;
      }
    }
  }
  PetscCall(VecRestoreArrayRead(r, &ra));
  if (sc->rank == 0) { /* P^T r summed on rank 0, solved there, the solution broadcast */
    PetscCall(VecGetArrayWrite(sc->bc, &ba));
    PetscCallMPI(MPI_Reduce(sc->w, ba, (PetscMPIInt)N, MPIU_REAL, MPI_SUM, 0, sc->comm));
    PetscCall(VecRestoreArrayWrite(sc->bc, &ba));
    { /* an error here is told to the other ranks, which wait in the broadcast below */
      PetscErrorCode ierr;
      PetscCall(PetscPushErrorHandler(PetscReturnErrorHandler, NULL));
      ierr = KSPSolve(sc->ksp, sc->bc, sc->xc);
      PetscCall(PetscPopErrorHandler());
      if (ierr) PetscCall(VecSet(sc->xc, NAN));
    }
    PetscCall(VecGetArrayRead(sc->xc, &xa));
    for (PetscInt k = 0; k < N; k++) {
      sc->xv[k] = PetscRealPart(xa[k]);
      if (PetscIsInfOrNanScalar(xa[k])) lbad = 1;
    }
    PetscCall(VecRestoreArrayRead(sc->xc, &xa));
    sc->xv[N] = (PetscReal)lbad;
  } else PetscCallMPI(MPI_Reduce(sc->w, NULL, (PetscMPIInt)N, MPIU_REAL, MPI_SUM, 0, sc->comm));
  PetscCallMPI(MPI_Bcast(sc->xv, (PetscMPIInt)(N + 1), MPIU_REAL, 0, sc->comm));
  gbad = sc->xv[N] != 0;
  if (gbad) { /* a residual that is not finite (a Krylov breakdown) or a failed coarse solve: the
                 preconditioned vector is made not finite, so that the Krylov method stops on it
                 (KSP_DIVERGED_NANORINF) and the step is retried smaller, as for any failed solve */
    PetscCall(PetscInfo(NULL, "-pc_amgsys_sheet_spacing %g: the coarse solve failed or gave a correction that is not finite\n", (double)sc->H));
    PetscCall(VecSet(y, NAN));
    PetscFunctionReturn(0);
  }
  PetscCall(VecGetArray(y, &ya));
  for (PetscInt v = 0; v < sc->nv; v++) {
    PetscInt  g[4];
    PetscReal phi[4], d[4][3];
    Hats(sc, v, g, phi, d);
    for (PetscInt c = 0, i = sc->row0[v]; c < 3; c++) {
      PetscReal val = 0;
      if (!(sc->mask[v] >> c & 1)) continue;
      for (int k = 0; k < 4; k++) {
        const PetscInt K = sc->act[g[k]];
        if (phi[k] <= 0 || K < 0) continue;
        for (PetscInt m = 0; m < 6; m++) val += phi[k] * SheetModeValue(m, c, d[k], sc->H) * sc->xv[6 * K + m];
      }
      ya[i++] += val;
    }
  }
  PetscCall(VecRestoreArray(y, &ya));
  PetscFunctionReturn(0);
}

PetscErrorCode SheetCoarseGetBasis(SheetCoarse sc, Mat *P)
{
  PetscFunctionBeginUser;
  PetscCall(MatCreateAIJ(sc->comm, sc->n, PETSC_DECIDE, PETSC_DETERMINE, 6 * sc->nc, 24, NULL, 24, NULL, P));
  for (PetscInt v = 0; v < sc->nv; v++) {
    PetscInt  g[4];
    PetscReal phi[4], d[4][3];
    Hats(sc, v, g, phi, d);
    for (PetscInt c = 0, row = sc->rstart + sc->row0[v]; c < 3; c++) {
      if (!(sc->mask[v] >> c & 1)) continue;
      for (int k = 0; k < 4; k++) {
        const PetscInt K = sc->act[g[k]];
        if (phi[k] <= 0 || K < 0) continue;
        for (PetscInt m = 0; m < 6; m++) {
          const PetscInt    col = 6 * K + m;
          const PetscScalar val = phi[k] * SheetModeValue(m, c, d[k], sc->H);
          if (val != 0) PetscCall(MatSetValues(*P, 1, &row, 1, &col, &val, ADD_VALUES));
        }
      }
      row++;
    }
  }
  PetscCall(MatAssemblyBegin(*P, MAT_FINAL_ASSEMBLY));
  PetscCall(MatAssemblyEnd(*P, MAT_FINAL_ASSEMBLY));
  PetscFunctionReturn(0);
}

PetscErrorCode SheetCoarseGetOperator(SheetCoarse sc, Mat *Ac)
{
  PetscFunctionBeginUser;
  *Ac = sc->Ac;
  PetscFunctionReturn(0);
}

PetscErrorCode SheetCoarseGetSize(SheetCoarse sc, PetscInt *nodes, PetscInt *colours)
{
  PetscFunctionBeginUser;
  if (nodes) *nodes = sc->nc;
  if (colours) *colours = sc->q * sc->q;
  PetscFunctionReturn(0);
}
