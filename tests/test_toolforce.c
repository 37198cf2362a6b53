/* Force-driven tools in the contact object (include/contact.h): a box's bottom face pressed onto a
   rigid plane whose z displacement is an unknown (-tool_plane_force_z), with friction (slip):
   the coupling blocks of the Jacobian (node rows x tool columns, tool row x node and tool columns)
   against central differences of the residual; the tool's residual row against its closed form;
   the regularisation of a tool out of contact (its row's stiffness and residual) and of a force-driven
   direction whose contacts all slip along it (no stiffness); the drive switches of ContactSetToolDrive and the
   kinks of ContactNextKink. Runs on 1 and 2 ranks. */
#include <petscmat.h>
#include "testutil.h"
#include "mesh.h"
#include "bc.h"
#include "contact.h"

static PetscMPIInt rank, size;

typedef struct {
  MeshOptions mo;
  Mesh        m;
  BCs         bcs;
  Contact     c;
  PetscInt    nbody, nloc; /* global body unknowns, local vector length */
  Mat         J;
  PetscScalar *coo_v;
} Setup;

/* local displacements: every bottom node (z = 0) pressed by pen and slid by sx */
static void Displace(const Mesh *m, PetscScalar *u, double pen, double sx)
{
  for (PetscInt v = 0; v < m->nv; v++) {
    const PetscReal *X = m->X + 3 * v;
    for (int k = 0; k < 3; k++) u[m->vloff[v] + k] = 0;
    if (X[2] == 0) {
      u[m->vloff[v] + 2] = -pen * (1 + 0.3 * X[0] + 0.1 * X[1]); /* uneven: the nodes differ */
      u[m->vloff[v] + 0] = sx * (1 + X[1]);
    }
  }
}

/* residual at (u, d): the local body part f and the tool rows r (3) */
static PetscErrorCode Residual(Setup *s, const PetscScalar *u, const PetscReal d[3], PetscReal lam, PetscScalar *f, PetscReal r[3])
{
  PetscInt nfail;

  PetscFunctionBeginUser;
  PetscCall(ContactSetToolUnknowns(s->c, d));
  PetscCall(PetscArrayzero(f, s->nloc));
  PetscCall(ContactAssemble(s->c, u, lam, f, NULL, NULL, &nfail));
  PetscCall(ContactToolResidual(s->c, lam, r));
  PetscFunctionReturn(0);
}

/* the z force on the body from the local residual f (over all ranks) */
static PetscErrorCode ForceZ(Setup *s, const PetscScalar *f, PetscReal *fz)
{
  PetscFunctionBeginUser;
  *fz = 0;
  for (PetscInt v = 0; v < s->m.nv; v++)
    if (s->m.vowned[v] && s->m.X[3 * v + 2] == 0) *fz -= PetscRealPart(f[s->m.vloff[v] + 2]);
  PetscCall(MPIU_Allreduce(MPI_IN_PLACE, fz, 1, MPIU_REAL, MPIU_SUM, PETSC_COMM_WORLD));
  PetscFunctionReturn(0);
}

/* the Jacobian at (u, d) by coordinate assembly */
static PetscErrorCode Jacobian(Setup *s, const PetscScalar *u, const PetscReal d[3], PetscReal lam)
{
  PetscInt nfail;

  PetscFunctionBeginUser;
  PetscCall(ContactSetToolUnknowns(s->c, d));
  PetscCall(ContactAssemble(s->c, u, lam, NULL, s->J, s->coo_v, &nfail));
  PetscCall(MatSetValuesCOO(s->J, s->coo_v, INSERT_VALUES));
  PetscFunctionReturn(0);
}

static PetscReal Entry(Mat J, PetscInt i, PetscInt j)
{
  PetscScalar v = 0;
  (void)MatGetValues(J, 1, &i, 1, &j, &v);
  return PetscRealPart(v);
}

int main(int argc, char **argv)
{
  Setup         s;
  PetscScalar  *u, *f, *fp, *fm;
  PetscInt     *cmask, nl;
  PetscCount    n;
  PetscInt     *ci, *cj;
  const double  KN = 100, lam = 0.7, h = 1e-7;
  PetscReal     d[3] = {0, 0, 0}, r[3], rp[3], rm[3];
  Vec           gv;

  PetscCall(PetscInitialize(&argc, &argv, NULL, NULL));
  PetscCallMPI(MPI_Comm_rank(PETSC_COMM_WORLD, &rank));
  PetscCallMPI(MPI_Comm_size(PETSC_COMM_WORLD, &size));
  PetscCall(PetscOptionsInsertString(NULL, "-mesh_type box -box_cells 2,2,1 -contact_set zmin -contact_penalty_normal 100 -contact_penalty_tangential 10 -contact_friction 0.3 "
                                           "-tool_names plane -tool_plane_patches 1 -tool_plane_patch0_type plane -tool_plane_patch0_origin 0,0,0 "
                                           "-tool_plane_patch0_e1 1,0,0 -tool_plane_patch0_e2 0,1,0 -tool_plane_patch0_range -2,3,-2,3 "
                                           "-tool_plane_force_z 5 -tool_plane_force_amplitude 0,0,0.5,1,1,0.5"));
  PetscCall(PetscMemzero(&s, sizeof(s)));
  PetscCall(MeshSetFromOptions(PETSC_COMM_WORLD, &s.mo));
  PetscCall(BCSetFromOptions(PETSC_COMM_WORLD, &s.bcs));
  PetscCall(ContactCreate(PETSC_COMM_WORLD, &s.c));
  PetscCall(ContactSetFromOptions(s.c));
  PetscCall(MeshCreate(PETSC_COMM_WORLD, &s.mo, &s.m));
  PetscCall(BCComputeMask(&s.bcs, &s.m, &cmask));
  PetscCall(MeshSetConstraints(&s.m, cmask));
  PetscCall(PetscFree(cmask));
  PetscCall(BCSetUp(&s.bcs, &s.m));
  PetscCall(ContactSetUp(s.c, &s.m));

  CHECK_ALL(ContactNumToolUnknowns(s.c) == 3, "a force-driven tool has 3 unknowns (got %d)", (int)ContactNumToolUnknowns(s.c));
  CHECK_ALL(ContactNextKink(s.c, 0.2) == 0.5 && ContactNextKink(s.c, 0.5) == 1 && ContactNextKink(s.c, 1) == PETSC_INFINITY, "ContactNextKink: the amplitude's breakpoints 0.5 and 1 after 0.2 and 0.5, none after 1");

  /* the extended system: the body's global unknowns, then the tool's on the last rank */
  PetscCall(DMCreateGlobalVector(s.m.dm, &gv));
  PetscCall(VecGetSize(gv, &s.nbody));
  PetscCall(VecGetLocalSize(gv, &nl));
  PetscCall(VecDestroy(&gv));
  PetscCall(ContactSetToolDofs(s.c, s.nbody, rank == size - 1 ? PETSC_TRUE : PETSC_FALSE));
  nl += rank == size - 1 ? 3 : 0;
  PetscCall(MatCreate(PETSC_COMM_WORLD, &s.J));
  PetscCall(MatSetSizes(s.J, nl, nl, PETSC_DETERMINE, PETSC_DETERMINE));
  PetscCall(MatSetType(s.J, MATAIJ));
  PetscCall(ContactGetCOO(s.c, &n, NULL, NULL));
  PetscCall(PetscMalloc2(n + 1, &ci, n + 1, &cj));
  PetscCall(PetscMalloc1(n + 1, &s.coo_v));
  PetscCall(ContactGetCOO(s.c, &n, ci, cj));
  PetscCall(MatSetPreallocationCOO(s.J, n, ci, cj));
  PetscCall(PetscFree2(ci, cj));

  s.nloc = 3 * s.m.nv;
  PetscCall(PetscCalloc4(s.nloc, &u, s.nloc, &f, s.nloc, &fp, s.nloc, &fm));
  Displace(&s.m, u, 0.01, 0.05); /* slip: K_T x 0.05 > mu t_N */
  PetscCall(ContactSeed(s.c, u, lam, PETSC_TRUE));

  /* 1. the tool's row: the force it exerts on the body minus the target 5 a(0.7) = 5 x 0.8;
        the directions not driven by force: the unknown minus the prescribed displacement (0) */
  {
    PetscReal fz;
    d[0] = 1e-3;
    d[2] = -2e-3;
    PetscCall(Residual(&s, u, d, lam, f, r));
    PetscCall(ForceZ(&s, f, &fz));
    CHECK_ALL(PetscAbsReal(r[2] - (fz - 4)) < 1e-12 * PetscAbsReal(fz) && r[0] == d[0] && r[1] == 0, "tool row: force on the body %g minus the target %g (residual %g); pinned rows: the unknown (%g, %g)", (double)fz, 4.0, (double)r[2], (double)r[0], (double)r[1]);
    CHECK_ALL(fz > 9 * KN * 0.008, "the bottom nodes are pressed by the tool (force %g)", (double)fz);
  }

  /* 2. the coupling blocks against central differences in d_z and in one node's y */
  PetscCall(Jacobian(&s, u, d, lam));
  {
    const PetscInt tz = s.nbody + 2;
    PetscReal      err = 0, scale = 0, dp[3] = {d[0], d[1], d[2] + h}, dm[3] = {d[0], d[1], d[2] - h};
    /* node rows, tool column: dR_i/dd_z */
    PetscCall(Residual(&s, u, dp, lam, fp, rp));
    PetscCall(Residual(&s, u, dm, lam, fm, rm));
    for (PetscInt v = 0; v < s.m.nv; v++) {
      PetscInt idx[3];
      if (!s.m.vowned[v] || s.m.X[3 * v + 2] != 0) continue;
      PetscCall(MeshVertexDofs(&s.m, v, idx));
      for (int k = 0; k < 3; k++) {
        const PetscReal fd = PetscRealPart(fp[s.m.vloff[v] + k] - fm[s.m.vloff[v] + k]) / (2 * h);
        if (idx[k] < 0) continue;
        err   = PetscMax(err, PetscAbsReal(Entry(s.J, idx[k], tz) - fd));
        scale = PetscMax(scale, PetscAbsReal(fd));
      }
    }
    PetscCall(MPIU_Allreduce(MPI_IN_PLACE, &err, 1, MPIU_REAL, MPIU_MAX, PETSC_COMM_WORLD));
    PetscCall(MPIU_Allreduce(MPI_IN_PLACE, &scale, 1, MPIU_REAL, MPIU_MAX, PETSC_COMM_WORLD));
    CHECK_ALL(scale > KN / 2 && err < 1e-5 * scale, "node rows x tool column: dR/dd_z against central differences, largest error %.2e of %g", (double)err, (double)scale);
    /* tool row, tool columns: dr/dd (z against x too: friction) */
    {
      PetscReal e = 0, J22 = 0;
      if (rank == size - 1) J22 = Entry(s.J, tz, tz);
      PetscCall(MPIU_Allreduce(MPI_IN_PLACE, &J22, 1, MPIU_REAL, MPIU_SUM, PETSC_COMM_WORLD));
      e = PetscAbsReal(J22 - (rp[2] - rm[2]) / (2 * h));
      CHECK_ALL(e < 1e-5 * J22 && J22 > 8 * KN, "tool row x tool column: dr_z/dd_z = %g against central differences (error %.2e)", (double)J22, (double)e);
    }
    /* tool row, node columns: dr_z/dy of every owned bottom node, one at a time (collective) */
    {
      PetscInt  nv = 0;
      PetscReal e = 0, sc = 0;
      for (PetscInt v = 0; v < s.m.nv; v++)
        if (s.m.vowned[v] && s.m.X[3 * v + 2] == 0) nv++;
      PetscCall(MPIU_Allreduce(MPI_IN_PLACE, &nv, 1, MPIU_INT, MPI_MAX, PETSC_COMM_WORLD));
      for (PetscInt p = 0; p < size; p++) {
        for (PetscInt q = 0; q < nv; q++) {
          for (int k = 0; k < 3; k++) {
            PetscInt v = -1, c = 0, idx[3] = {-1, -1, -1}, col = -1;
            PetscReal Jv = 0;
            if (rank == p)
              for (PetscInt w = 0; w < s.m.nv; w++)
                if (s.m.vowned[w] && s.m.X[3 * w + 2] == 0 && c++ == q) v = w;
            if (v >= 0) {
              PetscCall(MeshVertexDofs(&s.m, v, idx));
              col = idx[k];
              u[s.m.vloff[v] + k] += h;
            }
            PetscCall(Residual(&s, u, d, lam, fp, rp));
            if (v >= 0) u[s.m.vloff[v] + k] -= 2 * h;
            PetscCall(Residual(&s, u, d, lam, fm, rm));
            if (v >= 0) u[s.m.vloff[v] + k] += h;
            PetscCall(MPIU_Allreduce(MPI_IN_PLACE, &col, 1, MPIU_INT, MPI_MAX, PETSC_COMM_WORLD));
            if (col < 0) continue;
            if (rank == size - 1) Jv = Entry(s.J, tz, col);
            PetscCall(MPIU_Allreduce(MPI_IN_PLACE, &Jv, 1, MPIU_REAL, MPIU_SUM, PETSC_COMM_WORLD));
            e  = PetscMax(e, PetscAbsReal(Jv - (rp[2] - rm[2]) / (2 * h)));
            sc = PetscMax(sc, PetscAbsReal(Jv));
          }
        }
      }
      /* the Jacobian was assembled at the unperturbed state: reassemble nothing, compare */
      CHECK_ALL(sc > KN / 2 && e < 1e-5 * sc, "tool row x node columns: dr_z/dy against central differences, largest error %.2e of %g", (double)e, (double)sc);
    }
  }

  /* 3. out of contact: the tool row is the regularising stiffness (9 nodes x K_N), the residual
        minus the target; a zero target gives a zero row residual */
  {
    PetscReal J22 = 0, d0[3] = {0, 0, -0.5};
    PetscCall(Residual(&s, u, d0, lam, f, r));
    PetscCall(Jacobian(&s, u, d0, lam));
    if (rank == size - 1) J22 = Entry(s.J, s.nbody + 2, s.nbody + 2);
    PetscCall(MPIU_Allreduce(MPI_IN_PLACE, &J22, 1, MPIU_REAL, MPIU_SUM, PETSC_COMM_WORLD));
    CHECK_ALL(J22 == 9 * KN && r[2] == -4, "out of contact, beyond the search distance: the tool's diagonal is the sum of the penalties %g (got %g), its residual minus the target 4 (got %g)", 9 * KN, (double)J22, (double)r[2]);
    /* within the search distance: the penalty law continued across the nearest node's gap
       0.1 - 0.01 (1 + 0.3 + 0.1) with the regularising stiffness */
    d0[2] = -0.1;
    PetscCall(Residual(&s, u, d0, lam, f, r));
    {
      const PetscReal expect = -9 * KN * (0.1 - 0.014) - 4;
      CHECK_ALL(PetscAbsReal(r[2] - expect) < 1e-12 * PetscAbsReal(expect), "out of contact, within the search distance: the tool's row is -k_reg g_min minus the target, %g (got %g)", (double)expect, (double)r[2]);
    }
  }

  /* 3b. a force-driven direction whose contacts give it no stiffness: every node slips along x on
         the plane (the slip tangent has none along the slip, the plane's normal none along x), so
         the tool's x column is zero and the diagonal would be a zero pivot; it is the regularising
         stiffness 9 K_N instead, and the residual row is still the force minus the target. With
         the nodes sticking the diagonal is exactly their stiffness, K_T each. */
  {
    LoadCurve       cv;
    const PetscReal t[2] = {0, 1}, val[2] = {1, 1};
    PetscReal       J00 = 0, fx = 0, Jxz = 0, d1[3] = {0, 0, d[2]};
    PetscCall(LoadCurveCreate(PETSC_COMM_WORLD, "test", 2, t, val, &cv));
    PetscCall(ContactSetToolDrive(s.c, 0, 0, TOOL_DRIVE_FORCE, &cv));
    PetscCall(LoadCurveDestroy(&cv));
    PetscCall(Residual(&s, u, d, lam, f, r));
    PetscCall(Jacobian(&s, u, d, lam));
    if (rank == size - 1) {
      J00 = Entry(s.J, s.nbody, s.nbody);
      Jxz = Entry(s.J, s.nbody, s.nbody + 2);
    }
    for (PetscInt v = 0; v < s.m.nv; v++)
      if (s.m.vowned[v] && s.m.X[3 * v + 2] == 0) fx -= PetscRealPart(f[s.m.vloff[v]]);
    PetscCall(MPIU_Allreduce(MPI_IN_PLACE, &fx, 1, MPIU_REAL, MPIU_SUM, PETSC_COMM_WORLD));
    PetscCall(MPIU_Allreduce(MPI_IN_PLACE, &J00, 1, MPIU_REAL, MPIU_SUM, PETSC_COMM_WORLD));
    PetscCall(MPIU_Allreduce(MPI_IN_PLACE, &Jxz, 1, MPIU_REAL, MPIU_SUM, PETSC_COMM_WORLD));
    CHECK_ALL(J00 == 9 * KN && PetscAbsReal(r[0] - (fx - 1)) < 1e-12 * PetscAbsReal(fx) && PetscAbsReal(fx) > 0.2 && Jxz != 0, "x driven by force, every node slipping along x: the x diagonal is the regularising stiffness %g (got %g; the contacts give it none), the coupling with z (friction) kept (%g), the row the force %g minus the target 1 (got %g)", 9 * KN, (double)J00, (double)Jxz, (double)fx, (double)r[0]);
    Displace(&s.m, u, 0.01, 1e-3); /* stick: K_T x 2e-3 < mu t_N */
    PetscCall(Residual(&s, u, d1, lam, f, r));
    PetscCall(Jacobian(&s, u, d1, lam));
    J00 = 0;
    if (rank == size - 1) J00 = Entry(s.J, s.nbody, s.nbody);
    PetscCall(MPIU_Allreduce(MPI_IN_PLACE, &J00, 1, MPIU_REAL, MPIU_SUM, PETSC_COMM_WORLD));
    CHECK_ALL(PetscAbsReal(J00 - 9 * 10.0) < 1e-12 * 90, "x driven by force, every node sticking: the x diagonal is the contacts' stiffness 9 K_T = 90 (got %.15g)", (double)J00);
    PetscCall(ContactSetToolDrive(s.c, 0, 0, TOOL_DRIVE_DISPLACEMENT, NULL));
    Displace(&s.m, u, 0.01, 0.05);
  }

  /* 4. drive switches: to displacement the tool holds its committed position; back to force the
        target is the curve's value itself */
  {
    LoadCurve       cv;
    const PetscReal t[2] = {0, 1}, val[2] = {7, 7};
    PetscCall(Residual(&s, u, d, lam, f, r));
    PetscCall(ContactCommit(s.c, lam));
    PetscCall(ContactSetToolDrive(s.c, 0, 2, TOOL_DRIVE_DISPLACEMENT, NULL));
    {
      PetscReal d1[3] = {d[0], d[1], d[2] + 0.25};
      PetscCall(Residual(&s, u, d1, lam + 0.1, f, r));
      CHECK_ALL(PetscAbsReal(r[2] - 0.25) < 1e-15, "switched to displacement: the z row is the unknown minus the committed position (%g, expected 0.25)", (double)r[2]);
    }
    PetscCall(LoadCurveCreate(PETSC_COMM_WORLD, "test", 2, t, val, &cv));
    PetscCall(ContactSetToolDrive(s.c, 0, 2, TOOL_DRIVE_FORCE, &cv));
    PetscCall(LoadCurveDestroy(&cv));
    {
      PetscReal r0[3], fz;
      PetscCall(Residual(&s, u, d, lam, f, r0));
      PetscCall(ForceZ(&s, f, &fz));
      CHECK_ALL(fz > 0 && PetscAbsReal(r0[2] - (fz - 7)) < 1e-12 * fz, "switched back to force with the curve 7: the z row is the force %g minus 7 (got %g)", (double)fz, (double)r0[2]);
      PetscCall(ContactSetToolDrive(s.c, 0, 2, TOOL_DRIVE_DISPLACEMENT, NULL));
    }
  }
  CHECK_ALL(ContactNextKink(s.c, 0.2) == PETSC_INFINITY, "no force-driven direction left: no kink");

  PetscCall(PetscFree4(u, f, fp, fm));
  PetscCall(PetscFree(s.coo_v));
  PetscCall(MatDestroy(&s.J));
  PetscCall(ContactDestroy(&s.c));
  PetscCall(BCDestroy(&s.bcs));
  PetscCall(MeshDestroy(&s.m));
  PetscCall(PetscFinalize());
  TU_RETURN();
}
