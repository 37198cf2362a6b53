/* The contact object (include/contact.h) on a small box mesh pressed onto a rigid plane: nodal
   forces against the closed form K_N times the penetration, the per-tool results (a node touching
   with zero force is not counted as pressed; frictionless contact is neither stick nor slip), and
   the chattering check for nodes entering and leaving contact with a significant force, and the
   linear model of the active-set correction (ContactLinearBlock, ContactLinearRelease). Runs on
   1 and 2 ranks: every count is over all ranks. */
#include <petscsys.h>
#include "testutil.h"
#include "mesh.h"
#include "bc.h"
#include "contact.h"

static PetscMPIInt rank;

typedef struct {
  MeshOptions mo;
  Mesh        m;
  BCs         bcs;
  Contact     c;
} Setup;

static PetscErrorCode SetUp(Setup *s, PetscReal mu)
{
  char      buf[32];
  PetscInt *cmask;

  PetscFunctionBeginUser;
  PetscCall(PetscSNPrintf(buf, sizeof(buf), "%g", (double)mu));
  PetscCall(PetscOptionsSetValue(NULL, "-contact_friction", buf));
  PetscCall(PetscMemzero(s, sizeof(*s)));
  PetscCall(MeshSetFromOptions(PETSC_COMM_WORLD, &s->mo));
  PetscCall(BCSetFromOptions(PETSC_COMM_WORLD, &s->bcs));
  PetscCall(ContactCreate(PETSC_COMM_WORLD, &s->c));
  PetscCall(ContactSetFromOptions(s->c));
  PetscCall(MeshCreate(PETSC_COMM_WORLD, &s->mo, &s->m));
  PetscCall(BCComputeMask(&s->bcs, &s->m, &cmask));
  PetscCall(MeshSetConstraints(&s->m, cmask));
  PetscCall(PetscFree(cmask));
  PetscCall(BCSetUp(&s->bcs, &s->m));
  PetscCall(ContactSetUp(s->c, &s->m));
  PetscFunctionReturn(0);
}

static PetscErrorCode TearDown(Setup *s)
{
  PetscFunctionBeginUser;
  PetscCall(ContactDestroy(&s->c));
  PetscCall(BCDestroy(&s->bcs));
  PetscCall(MeshDestroy(&s->m));
  PetscFunctionReturn(0);
}

/* local displacements: every bottom node (z = 0) moved by dz, except those with x = 1, moved by dz1 */
static void Displace(const Mesh *m, PetscScalar *u, double dz, double dz1)
{
  for (PetscInt v = 0; v < m->nv; v++) {
    const PetscReal *X = m->X + 3 * v;
    for (int k = 0; k < 3; k++) u[m->vloff[v] + k] = 0;
    if (X[2] == 0) u[m->vloff[v] + 2] = X[0] == 1 ? dz1 : dz;
  }
}

/* one evaluation under the keep mode `keep` (then ended), at displacements u: the largest relative
   error of the normal force R_z on the lifted nodes pressed in the committed state (x != 1)
   against KN g where they are held, 0 where they are open */
static PetscErrorCode KeptLifted(Setup *s, PetscInt keep, const PetscScalar *u, PetscScalar *f, PetscInt nloc, PetscBool held, double KN, double g, PetscInt *nfail, double *err)
{
  PetscFunctionBeginUser;
  PetscCall(ContactKeepCommitted(s->c, keep));
  PetscCall(PetscArrayzero(f, nloc));
  PetscCall(ContactAssemble(s->c, u, 0, f, NULL, NULL, nfail));
  PetscCall(ContactKeepCommitted(s->c, 0));
  *err = 0;
  for (PetscInt v = 0; v < s->m.nv; v++)
    if (s->m.X[3 * v + 2] == 0 && s->m.vowned[v] && s->m.X[3 * v] != 1) *err = PetscMax(*err, fabs(PetscRealPart(f[s->m.vloff[v] + 2]) - (held ? KN * g : 0)) / (KN * g));
  PetscFunctionReturn(0);
}

int main(int argc, char **argv)
{
  Setup             s;
  PetscScalar      *u, *f;
  PetscInt          nfail, nch, node, nloc;
  ContactToolResult r;
  const double      KN = 100, pen = 0.01;

  PetscCall(PetscInitialize(&argc, &argv, NULL, NULL));
  PetscCallMPI(MPI_Comm_rank(PETSC_COMM_WORLD, &rank));
  PetscCall(PetscOptionsInsertString(NULL, "-mesh_type box -box_cells 2,2,1 -contact_set zmin -contact_penalty_normal 100 -contact_penalty_tangential 10 "
                                           "-tool_names plane -tool_plane_patches 1 -tool_plane_patch0_type plane -tool_plane_patch0_origin 0,0,0 "
                                           "-tool_plane_patch0_e1 1,0,0 -tool_plane_patch0_e2 0,1,0 -tool_plane_patch0_range -2,3,-2,3 "
                                           "-tool_plane_path 0,0,0,0,1,1e-6,0,0"));

  for (int pass = 0; pass < 2; pass++) {
    const PetscReal mu = pass ? 0.3 : 0.0;
    PetscCall(SetUp(&s, mu));
    nloc = 3 * s.m.nv;
    PetscCall(PetscCalloc2(nloc, &u, nloc, &f));

    /* every bottom node pressed by pen, those at x = 1 touching without penetration */
    Displace(&s.m, u, -pen, 0);
    PetscCall(ContactSeed(s.c, u, 0, PETSC_TRUE));
    PetscCall(ContactAssemble(s.c, u, 0, f, NULL, NULL, &nfail));
    {
      double err = 0;
      int    pressed = 0;
      for (PetscInt v = 0; v < s.m.nv; v++)
        if (s.m.X[3 * v + 2] == 0 && s.m.X[3 * v] != 1 && s.m.vowned[v]) {
          err = PetscMax(err, fabs(PetscRealPart(f[s.m.vloff[v] + 2]) + KN * pen) / (KN * pen));
          pressed++;
        }
      CHECK_ALL(nfail == 0 && err < 1e-12, "mu %g: residual -K_N g at every pressed node (%d on rank %d), relative error %.1e", (double)mu, pressed, rank, err);
    }
    PetscCall(ContactRecordActive(s.c));
    PetscCall(ContactCommit(s.c, 0));
    PetscCall(ContactGetToolResult(s.c, 0, 0, &r));
    /* 9 bottom nodes: 6 pressed (x < 1), 3 touching at x = 1 with zero force */
    CHECK_ALL(r.active == 6, "mu %g: 6 nodes pressed, the 3 touching without force not counted (got %d)", (double)mu, (int)r.active);
    CHECK_ALL(fabs(r.f[2] - 6 * KN * pen) < 1e-12 && fabs(r.fn - 6 * KN * pen) < 1e-12 && fabs(r.ft) < 1e-12, "mu %g: resultant (%g, %g, %g), normal %g, tangential %g", (double)mu, r.f[0], r.f[1], r.f[2], r.fn, r.ft);
    if (mu == 0) CHECK_ALL(r.stick == 0 && r.slip == 0, "frictionless contact counted as neither stick nor slip (stick %d, slip %d)", (int)r.stick, (int)r.slip);
    else CHECK_ALL(r.stick == 6 && r.slip == 0, "with friction and no slip: 6 nodes sticking (stick %d, slip %d)", (int)r.stick, (int)r.slip);

    /* the next Newton iterate: the nodes at x = 1 enter with a significant force, the others stay */
    Displace(&s.m, u, -pen, -pen);
    PetscCall(ContactAssemble(s.c, u, 0, f, NULL, NULL, &nfail));
    PetscCall(ContactChatter(s.c, 0, &nch, &node));
    CHECK_ALL(nch == 0, "mu %g: nodes already touching (active, zero force) that become pressed do not change the active set: %d", (double)mu, (int)nch);
    PetscCall(ContactRecordActive(s.c));
    /* the next iterate: the nodes at x = 1 leave contact; they carried a significant force */
    Displace(&s.m, u, -pen, 0.01);
    PetscCall(ContactAssemble(s.c, u, 0, f, NULL, NULL, &nfail));
    PetscCall(ContactChatter(s.c, 0, &nch, &node));
    CHECK_ALL(nch == 3, "mu %g: 3 nodes leaving contact with a significant force are seen by the chattering check (got %d, smallest node id %d)", (double)mu, (int)nch, (int)node);
    PetscCall(ContactRecordActive(s.c));
    /* and enter again */
    Displace(&s.m, u, -pen, -pen);
    PetscCall(ContactAssemble(s.c, u, 0, f, NULL, NULL, &nfail));
    PetscCall(ContactChatter(s.c, 0, &nch, &node));
    CHECK_ALL(nch == 3, "mu %g: 3 nodes entering contact with a significant force are seen (got %d)", (double)mu, (int)nch);
    /* the same changes within the Newton solve's tolerance (a force below fmin) are accepted */
    PetscCall(ContactChatter(s.c, 2 * KN * pen, &nch, &node));
    CHECK_ALL(nch == 0, "mu %g: 3 nodes entering with forces below the solve's tolerance are not chattering (got %d)", (double)mu, (int)nch);
    PetscCall(ContactChatter(s.c, 0.5 * KN * pen, &nch, &node));
    CHECK_ALL(nch == 3, "mu %g: the same nodes above a tolerance of half their force are (got %d)", (double)mu, (int)nch);
    /* a node leaving with a negligible force (1e-6 of the largest) is not chattering */
    PetscCall(ContactRecordActive(s.c));
    Displace(&s.m, u, -pen, 0.01);
    PetscCall(ContactAssemble(s.c, u, 0, f, NULL, NULL, &nfail));
    PetscCall(ContactRecordActive(s.c));
    Displace(&s.m, u, -pen, -1e-6 * pen);
    PetscCall(ContactAssemble(s.c, u, 0, f, NULL, NULL, &nfail));
    PetscCall(ContactRecordActive(s.c));
    Displace(&s.m, u, -pen, 0.01);
    PetscCall(ContactAssemble(s.c, u, 0, f, NULL, NULL, &nfail));
    PetscCall(ContactChatter(s.c, 0, &nch, &node));
    CHECK_ALL(nch == 0, "mu %g: nodes leaving with a force of 1e-6 of the largest are not chattering (got %d)", (double)mu, (int)nch);

    /* ContactKeepCommitted (the first Newton iteration of a step): the 6 nodes pressed in the
       committed state, now lifted off the plane by g, stay closed with the normal force continued
       linearly, R_z = -t_N = K_N g (a pull), and the tangent K_N n n^T (with friction: held
       tangentially too, K_T (I - n n^T) on top of the stick tangent K_T); the 3 nodes that only
       touched stay open; the Jacobian assembly leaves the keep on (residual and tangent of one
       iteration are one law), ContactKeepCommitted(c, 0) (the line search's precheck) ends it */
    {
      const double g = 0.002, KT = 10;
      PetscCount   nco;
      PetscScalar *cv;
      Mat          Jd; /* only a non-NULL handle: the coordinate values are asked for */
      int          nheld = 0, nopen = 0, bad = 0;
      double       err = 0;
      /* the step's seed at the load 1e-9: the plane slides in its own plane by 1e-15 (a tool moved
         by the step: the keep of every tool holds its frictional nodes); the assemblies below
         evaluate at load 0, where it has not moved */
      PetscCall(ContactSeed(s.c, u, 1e-9, PETSC_TRUE));
      Displace(&s.m, u, g, g);
      PetscCall(ContactGetCOO(s.c, &nco, NULL, NULL));
      PetscCall(PetscCalloc1(nco + 1, &cv));
      PetscCall(MatCreate(PETSC_COMM_SELF, &Jd));
      PetscCall(ContactKeepCommitted(s.c, 2));
      PetscCall(PetscArrayzero(f, nloc)); /* (the assembly adds) */
      PetscCall(ContactAssemble(s.c, u, 0, f, NULL, NULL, &nfail));
      for (PetscInt v = 0; v < s.m.nv; v++)
        if (s.m.X[3 * v + 2] == 0 && s.m.vowned[v]) {
          const double rz = PetscRealPart(f[s.m.vloff[v] + 2]), want = s.m.X[3 * v] != 1 ? KN * g : 0;
          err = PetscMax(err, fabs(rz - want) / (KN * g));
        }
      CHECK_ALL(nfail == 0 && err < 1e-12, "mu %g, keep: residual K_N g (a pull) at the committed pressed nodes lifted by g, 0 at the touching ones; relative error %.1e", (double)mu, err);
      PetscCall(ContactAssemble(s.c, u, 0, NULL, Jd, cv, &nfail));
      for (PetscCount k = 0; k + 9 <= nco; k += 9) {
        const PetscScalar *K = cv + k;
        double             o = 0;
        if (PetscRealPart(K[8]) == 0) {
          for (int q = 0; q < 9; q++) o += fabs(PetscRealPart(K[q]));
          nopen++;
          bad += o != 0;
          continue;
        }
        nheld++;
        for (int q = 0; q < 9; q++) {
          const double want = q == 8 ? KN : ((q == 0 || q == 4) && mu > 0 ? 2 * KT : 0);
          err = PetscMax(err, fabs(PetscRealPart(K[q]) - want) / KN);
        }
      }
      PetscCall(MPIU_Allreduce(MPI_IN_PLACE, &nheld, 1, MPI_INT, MPI_SUM, PETSC_COMM_WORLD));
      PetscCall(MPIU_Allreduce(MPI_IN_PLACE, &nopen, 1, MPI_INT, MPI_SUM, PETSC_COMM_WORLD));
      CHECK_ALL(nfail == 0 && nheld == 6 && nopen == 3 && !bad && err < 1e-12, "mu %g, keep: tangent diag(%s, K_N) at the 6 held nodes, 0 at the 3 open ones (held %d, open %d, relative error %.1e)", (double)mu, mu > 0 ? "2 K_T, 2 K_T" : "0, 0", nheld, nopen, err);
      /* the Jacobian did not end the keep: the residual after it is the held one still */
      PetscCall(PetscArrayzero(f, nloc));
      PetscCall(ContactAssemble(s.c, u, 0, f, NULL, NULL, &nfail));
      err = 0;
      for (PetscInt v = 0; v < s.m.nv; v++)
        if (s.m.X[3 * v + 2] == 0 && s.m.vowned[v]) {
          const double rz = PetscRealPart(f[s.m.vloff[v] + 2]), want = s.m.X[3 * v] != 1 ? KN * g : 0;
          err = PetscMax(err, fabs(rz - want) / (KN * g));
        }
      CHECK_ALL(nfail == 0 && err < 1e-12, "mu %g, keep: after the Jacobian the residual is still the held one (relative error %.1e)", (double)mu, err);
      /* ended as the line search's precheck ends it: the lifted nodes are open again */
      PetscCall(ContactKeepCommitted(s.c, 0));
      PetscCall(PetscArrayzero(f, nloc));
      PetscCall(ContactAssemble(s.c, u, 0, f, NULL, NULL, &nfail));
      err = 0;
      for (PetscInt v = 0; v < s.m.nv; v++)
        if (s.m.X[3 * v + 2] == 0 && s.m.vowned[v]) err = PetscMax(err, fabs(PetscRealPart(f[s.m.vloff[v] + 2])));
      CHECK_ALL(err == 0, "mu %g: once the keep has ended, no force on lifted nodes (largest %g)", (double)mu, err);
      /* keep 1: nodes on frictionless tools only */
      PetscCall(KeptLifted(&s, 1, u, f, nloc, mu > 0 ? PETSC_FALSE : PETSC_TRUE, KN, g, &nfail, &err));
      CHECK_ALL(err < 1e-12, "mu %g, keep 1 (frictionless tools): the lifted nodes %s (relative error %.1e)", (double)mu, mu > 0 ? "are open" : "are held", err);
      /* keep 2, a node entering contact (the 3 at x = 1 only touched in the committed state): no
         friction while the keep lasts, the stick force K_T ds once it has ended; the 6 pressed
         nodes stick throughout */
      if (mu > 0) {
        const double ds = 1e-4, pz = 0.02;
        double       e2[2] = {0, 0};
        for (int pass2 = 0; pass2 < 2; pass2++) {
          Displace(&s.m, u, -pen, -pz);
          for (PetscInt v = 0; v < s.m.nv; v++)
            if (s.m.X[3 * v + 2] == 0) u[s.m.vloff[v]] = ds;
          PetscCall(ContactKeepCommitted(s.c, pass2 ? 0 : 2));
          PetscCall(PetscArrayzero(f, nloc));
          PetscCall(ContactAssemble(s.c, u, 0, f, NULL, NULL, &nfail));
          for (PetscInt v = 0; v < s.m.nv; v++)
            if (s.m.X[3 * v + 2] == 0 && s.m.vowned[v]) {
              const double fx = PetscRealPart(f[s.m.vloff[v]]), want = (s.m.X[3 * v] == 1 && !pass2) ? 0 : KT * ds;
              e2[pass2] = PetscMax(e2[pass2], fabs(fx - want) / (KT * ds));
            }
        }
        PetscCall(ContactKeepCommitted(s.c, 0));
        CHECK_ALL(nfail == 0 && e2[0] < 1e-9 && e2[1] < 1e-9, "mu %g, keep 2: a node entering contact has no friction while the keep lasts, K_T ds after; the pressed ones K_T ds throughout (relative errors %.1e, %.1e)", (double)mu, e2[0], e2[1]);
      }
      /* keep 2 with the step's seed at the load 0, where the plane is at rest (as committed): the
         lifted frictional nodes are not held (the keep holds them on tools the step moves), the
         frictionless ones are */
      Displace(&s.m, u, -pen, -pen);
      PetscCall(ContactSeed(s.c, u, 0, PETSC_TRUE));
      Displace(&s.m, u, g, g);
      PetscCall(KeptLifted(&s, 2, u, f, nloc, mu > 0 ? PETSC_FALSE : PETSC_TRUE, KN, g, &nfail, &err));
      CHECK_ALL(nfail == 0 && err < 1e-12, "mu %g, keep 2 on a tool at rest: the lifted nodes %s (relative error %.1e)", (double)mu, mu > 0 ? "are open" : "are held", err);
      /* keep 3 (all): the tool at rest holds them too, frictional or not */
      PetscCall(KeptLifted(&s, 3, u, f, nloc, PETSC_TRUE, KN, g, &nfail, &err));
      CHECK_ALL(nfail == 0 && err < 1e-12, "mu %g, keep 3 on a tool at rest: the lifted nodes are held (relative error %.1e)", (double)mu, err);
      PetscCall(MatDestroy(&Jd));
      PetscCall(PetscFree(cv));
    }

    PetscCall(PetscFree2(u, f));
    PetscCall(TearDown(&s));
  }

  /* A node that has never had a frame seed, left unpaired by the pairing at an iteration's start
     (beyond the search distance) and found on the tool by an evaluation within the iteration (a
     line-search trial), takes the chord of eq 28 at its projection as its seed (it once read a
     seed never set). The plane's first parameter direction is y: the chord, and so t1, along y
     (the fallback of a seed along the normal would give x). */
  PetscCall(PetscOptionsInsertString(NULL, "-tool_plane_patch0_e1 0,1,0 -tool_plane_patch0_e2 -1,0,0 -tool_plane_patch0_range -2,3,-3,2 -contact_search_distance 0.05"));
  PetscCall(SetUp(&s, 0.3));
  nloc = 3 * s.m.nv;
  PetscCall(PetscCalloc2(nloc, &u, nloc, &f));
  {
    const PetscInt w = ContactCheckpointWidth();
    PetscReal     *rows;
    double         err = 0, ferr = 0;
    int            n = 0;
    Displace(&s.m, u, 1.0, 1.0); /* the bottom 1 above the plane: no node paired */
    PetscCall(ContactSeed(s.c, u, 0, PETSC_TRUE));
    Displace(&s.m, u, -pen, -pen); /* the trial: every bottom node pressed by pen */
    PetscCall(ContactAssemble(s.c, u, 0, f, NULL, NULL, &nfail));
    PetscCall(ContactCommit(s.c, 0));
    PetscCall(PetscMalloc1(w * s.m.nvo + 1, &rows));
    PetscCall(ContactCheckpointPack(s.c, rows));
    for (PetscInt v = 0; v < s.m.nv; v++)
      if (s.m.X[3 * v + 2] == 0 && s.m.vowned[v]) {
        const PetscReal *row = rows + w * s.m.vrow[v]; /* t1 at 8..10, has_frame at 11 (ContactCheckpointPack) */
        err  = PetscMax(err, PetscMax(fabs(fabs(row[9]) - 1), PetscMax(fabs(row[8]), fabs(row[10]))) + (row[11] == 1 ? 0 : 1));
        ferr = PetscMax(ferr, fabs(PetscRealPart(f[s.m.vloff[v] + 2]) + KN * pen) / (KN * pen));
        n++;
      }
    CHECK_ALL(nfail == 0 && err < 1e-12 && ferr < 1e-12, "a node first paired within an iteration: the chord's frame, t1 along the patch's first direction y on all %d bottom nodes of rank %d (error %.1e), force -K_N g (relative error %.1e)", n, rank, err, ferr);
    PetscCall(PetscFree(rows));
  }
  PetscCall(PetscFree2(u, f));
  PetscCall(TearDown(&s));

  /* the linear model of the active-set correction (ContactLinearBlock, ContactLinearRelease):
     frictionless, every bottom node pressed by pen; each node's block is its tangent diag(0, 0,
     K_N) and its residual (0, 0, -K_N pen) on its three unknowns; along a step x - Y that lifts
     the nodes at x = 0 by 2 pen (the others by pen/2) the linearised normal force of those three
     is -K_N pen, a pull: they are listed, and none with a threshold above K_N pen */
  {
    PetscCount   nco;
    PetscInt     ns, bad = 0, n, nrel = 0, nrel_hi = 0, *idx;
    PetscScalar *cv;
    Mat          Jd;
    Vec          Y;
    char        *released;
    double       err = 0;
    PetscCall(SetUp(&s, 0.0));
    nloc = 3 * s.m.nv;
    PetscCall(PetscCalloc2(nloc, &u, nloc, &f));
    Displace(&s.m, u, -pen, -pen);
    PetscCall(ContactSeed(s.c, u, 0, PETSC_TRUE));
    PetscCall(ContactGetCOO(s.c, &nco, NULL, NULL));
    PetscCall(PetscCalloc1(nco + 1, &cv));
    PetscCall(MatCreate(PETSC_COMM_SELF, &Jd));
    PetscCall(ContactAssemble(s.c, u, 0, NULL, Jd, cv, &nfail));
    ns = ContactNumSlaves(s.c);
    for (PetscInt i = 0; i < ns; i++) {
      PetscInt  nd, dof[6];
      PetscReal M[36], r[6];
      PetscCall(ContactLinearBlock(s.c, i, &nd, dof, M, r));
      if (nd != 3) {
        bad++;
        continue;
      }
      for (int a = 0; a < 3; a++) {
        err = PetscMax(err, fabs(r[a] - (a == 2 ? -KN * pen : 0)) / (KN * pen));
        for (int q = 0; q < 3; q++) err = PetscMax(err, fabs(M[6 * a + q] - (a == 2 && q == 2 ? KN : 0)) / KN);
      }
    }
    PetscCall(MPIU_Allreduce(MPI_IN_PLACE, &bad, 1, MPIU_INT, MPI_SUM, PETSC_COMM_WORLD));
    CHECK_ALL(nfail == 0 && bad == 0 && err < 1e-12, "the linear model of the active-set correction: each pressed node's block diag(0, 0, K_N) and residual -K_N pen on its 3 unknowns (relative error %.1e)", err);
    PetscCall(DMCreateGlobalVector(s.m.dm, &Y));
    PetscCall(VecZeroEntries(Y));
    for (PetscInt v = 0; v < s.m.nv; v++)
      if (s.m.X[3 * v + 2] == 0 && s.m.vowned[v]) {
        PetscInt d[3];
        PetscCall(MeshVertexDofs(&s.m, v, d));
        PetscCall(VecSetValue(Y, d[2], s.m.X[3 * v] == 0 ? -2 * pen : -0.5 * pen, INSERT_VALUES));
      }
    PetscCall(VecAssemblyBegin(Y));
    PetscCall(VecAssemblyEnd(Y));
    PetscCall(PetscCalloc2(ns + 1, &released, ns + 1, &idx));
    PetscCall(ContactLinearRelease(s.c, Y, NULL, 0.5 * KN * pen, released, &n, idx));
    nrel = n;
    for (PetscInt k = 0; k < n; k++) released[idx[k]] = 1;
    PetscCall(ContactLinearRelease(s.c, Y, NULL, 0, released, &n, idx)); /* the flagged ones are not listed again */
    nrel_hi = n;
    PetscCall(PetscArrayzero(released, ns + 1));
    PetscCall(ContactLinearRelease(s.c, Y, NULL, 2 * KN * pen, released, &n, idx));
    nrel_hi += n;
    PetscCall(MPIU_Allreduce(MPI_IN_PLACE, &nrel, 1, MPIU_INT, MPI_SUM, PETSC_COMM_WORLD));
    PetscCall(MPIU_Allreduce(MPI_IN_PLACE, &nrel_hi, 1, MPIU_INT, MPI_SUM, PETSC_COMM_WORLD));
    CHECK_ALL(nrel == 3 && nrel_hi == 0, "the linear model: the 3 nodes a step lifts by 2 pen are pulled (listed: %d), none again once flagged nor with a threshold above K_N pen (%d)", (int)nrel, (int)nrel_hi);
    PetscCall(PetscFree2(released, idx));
    PetscCall(VecDestroy(&Y));
    PetscCall(MatDestroy(&Jd));
    PetscCall(PetscFree(cv));
    PetscCall(PetscFree2(u, f));
    PetscCall(TearDown(&s));
  }
  PetscCall(PetscFinalize());
  TU_RETURN();
}
