/* Contact between deformable bodies: pairs of a slave node set and a master surface
   (include/contact_pair.h; doc/contact-bodies.md).

   A slave node at x_s paired with master face F (corners x_1..x_4, bilinear) at its closest point
   xi contributes, with the kinematics of contact_nts.h (the gap g, the normal n, the slip ds
   relative to the master's material point under the node, all functions of X = (x_s, x_1..x_4)),

       R_s = Phi(g, n, ds)        (the rigid tools' law, contact_law.h, the seed fixed)
       R_a = -N_a(xi) R_s         (the reaction on the face's corners, a = 1..4)

   and the exact tangent

       dR_s/dX = Phi_g dg/dX + Phi_n dn/dX + Phi_ds dds/dX
       dR_a/dX = -N_a dR_s/dX - R_s (dN_a/dxi . dxi/dX).

   The law gives K(dn) = dR/dy for a node on a rigid surface, K(dn) = Phi_g n^T + Phi_n dn + Phi_ds
   (dg/dy = n, dds/dy = I), linear in the given dn. Its slip enters only through t_a . ds, so
   Phi_ds n = 0; hence from two calls, K0 = K(0) and K1 = K(I):
       Phi_g = K0 n,   Phi_ds = K0 - Phi_g n^T,   Phi_n = K1 - K0.

   Parallel: a face is one cell's, owned by its cell's rank (the roots of the PetscSF, 12 values
   per face); the candidates of a rank are the faces whose box meets the box of its slave nodes
   widened by the search distance, its leaves. Each evaluation broadcasts the faces' positions
   from their owners and reduces the forces on them back. */
#include <math.h>
#include <string.h>
#include <petscsf.h>
#include "contact_pair.h"
#include "contact_law.h"
#include "contact_nts.h"
#include "options.h"

#define PAIR_MAX 16

typedef struct {
  char      name[ATRITO_NAME_LEN], slave[ATRITO_NAME_LEN], master[ATRITO_NAME_LEN];
  PetscReal mu, kn, kt, kfactor, kratio, search;
  PetscBool kauto, ktauto, two_pass;
  PetscBool smooth;         /* the master's normal interpolated from its corners' mean normals    */
  PetscReal smooth_tol;     /* the corners' normals at the solution against those its last Newton
                               iteration held: a larger change makes another Newton solve        */
  PetscBool aug;            /* augmented Lagrangian (Uzawa updates between Newton solves)          */
  PetscReal aug_tol, aug_mtol; /* penetration and stick slip accepted (< 0: relative, times the slave
                               element size); the multipliers' change, relative to the largest    */
} PairSpec;

typedef struct {
  PetscInt  status;    /* CONTACT_OPEN / STICK / SLIP                                          */
  PetscInt  face;      /* global id (6 x source cell + face) of the master face, -1: none       */
  PetscReal xi[2];
  PetscReal tT[2];     /* tangential pressure on t1, t2                                        */
  PetscReal t1[3];
  PetscBool has_frame;
  PetscReal y[3];      /* node position                                                        */
  PetscReal gap, tN;
  PetscReal f[3], fT[3];
  PetscReal slip;
} PairState;

/* one pass of a pair: its slave nodes against its master faces */
typedef struct {
  PetscInt   spec;
  PetscBool  smooth;    /* its pair's -pair_<p>_smooth                                          */
  PetscReal  weight;    /* the penalties' share: 1/2 in each pass of a two-pass pair           */
  char       sset[ATRITO_NAME_LEN], mset[ATRITO_NAME_LEN];
  /* master faces of this rank's cells (roots) */
  PetscInt   nfo, *fov, *foid, *fog; /* 4 nfo local vertices; 12 nfo ids (of each 12: the face's, then its corners'
                                        source vertices); 12 nfo global dofs */
  PetscReal *fox, *fox0, *fof;       /* 12 nfo: current and committed corner positions, forces   */
  PetscReal *fofc;                   /* 12 nfo: the forces on the corners in the committed state (the
                                        residual terms: minus the forces the slave nodes exert)     */
  /* candidate faces (leaves) */
  PetscInt   nfc, *fcid, *fcg;
  PetscReal *fcx, *fcx0, *fcf;
  PetscReal *fonb, *fcnb;            /* 12 nfo, 12 nfc: the corners' normals (-pair_<p>_smooth)  */
  PetscSF    sf;
  PetscReal  search;
  /* slave nodes owned here */
  PetscInt   ns, *sv, *sg;           /* local vertices; 3 ns global dofs (-1 constrained)     */
  PetscInt  *ssrc;                   /* ns: their source vertex index (rank-independent)       */
  PetscReal *kn, *kt;
  PairState *st_c, *st_t;
  PetscReal *seed, *seedn;
  PetscBool *has_seed;
  PetscInt  *coff, *cand;            /* per slave node its candidates (CSR into the leaves)    */
  PetscInt  *active_prev;
  PetscReal *lam;                    /* 3 ns: the multipliers of the current solve (lN, lT1, lT2):
                                        lN 0 without the augmentation; lT the committed tangential
                                        pressure at the step's start, Uzawa's updates after      */
  PetscReal  hmin;                   /* smallest slave element size normal to its faces (all ranks) */
  PetscBool  noE;                    /* a slave face's material has no Young's modulus (this rank) */
  PetscReal  tol;                    /* the augmentation's tolerance (a length)                  */
  PetscReal  kscale;                 /* the penalties' factor: grown by the augmentation where an
                                        update removes too little of the penetration; kept for the
                                        next steps                                                */
  PetscReal  pen_prev;               /* the penetration before the last update (< 0: none yet)  */
} PairSide;

struct _p_ContactPairs {
  MPI_Comm    comm;
  PetscMPIInt rank, size;
  const Mesh *mesh;
  PetscReal   E;
  PetscReal  *Ecell;         /* per local cell its material's modulus (several bodies), else NULL */
  PetscInt    np;
  PairSpec    spec[PAIR_MAX];
  PetscInt    nside;
  PairSide    side[2 * PAIR_MAX];
  char        fsets[4 * PAIR_MAX][ATRITO_NAME_LEN];
  PetscLogEvent ev_pair, ev_search;
};

PetscErrorCode ContactPairsCreate(MPI_Comm comm, ContactPairs *p)
{
  PetscFunctionBeginUser;
  PetscCall(PetscNew(p));
  (*p)->comm = comm;
  PetscCallMPI(MPI_Comm_rank(comm, &(*p)->rank));
  PetscCallMPI(MPI_Comm_size(comm, &(*p)->size));
  PetscCall(PetscLogEventRegister("AtritoPairs", DM_CLASSID, &(*p)->ev_pair));
  PetscCall(PetscLogEventRegister("AtritoPairSearch", DM_CLASSID, &(*p)->ev_search));
  PetscFunctionReturn(0);
}

PetscInt ContactPairsNum(ContactPairs p) { return p ? p->np : 0; }

static PetscErrorCode PenaltyOption(MPI_Comm comm, const char *opt, const char *buf, PetscBool *isauto, PetscReal *v)
{
  char *end;

  PetscFunctionBeginUser;
  PetscCall(PetscStrcmp(buf, "auto", isauto));
  if (*isauto) PetscFunctionReturn(0);
  *v = strtod(buf, &end);
  PetscCheck(end != buf && *end == 0 && *v > 0 && PetscIsNormalReal(*v), comm, PETSC_ERR_USER_INPUT, "%s %s must be a positive penalty (force per length, per node) or auto", opt, buf);
  PetscFunctionReturn(0);
}

PetscErrorCode ContactPairsSetFromOptions(ContactPairs p)
{
  MPI_Comm  comm = p->comm;
  char     *names[PAIR_MAX];
  PetscInt  n = PAIR_MAX;
  PetscBool set;

  PetscFunctionBeginUser;
  PetscOptionsBegin(comm, NULL, "Contact between deformable bodies", "doc/contact-bodies.md");
  PetscCall(PetscOptionsStringArray("-pair_names", "Contact pairs between bodies of the mesh (each with -pair_<name>_slave and _master)", "doc/contact-bodies.md", names, &n, &set));
  PetscOptionsEnd();
  p->np = set ? n : 0;
  for (PetscInt k = 0; k < p->np; k++) {
    PairSpec *s = &p->spec[k];
    char      prefix[ATRITO_NAME_LEN + 8], buf[64], opt[ATRITO_NAME_LEN + 48];
    PetscBool hs, hm, ht;
    PetscCall(PetscStrncpy(s->name, names[k], sizeof(s->name)));
    PetscCall(PetscFree(names[k]));
    PetscCheck(s->name[0], comm, PETSC_ERR_USER_INPUT, "-pair_names: an empty name");
    for (PetscInt j = 0; j < k; j++) {
      PetscBool eq;
      PetscCall(PetscStrcmp(p->spec[j].name, s->name, &eq));
      PetscCheck(!eq, comm, PETSC_ERR_USER_INPUT, "-pair_names: '%s' given twice", s->name);
    }
    PetscCall(PetscSNPrintf(prefix, sizeof(prefix), "pair_%s_", s->name));
    s->mu      = 0;
    s->kfactor = 1;
    s->kratio  = 0.1;
    s->search  = -1;
    char title[ATRITO_NAME_LEN + 8];
    PetscCall(PetscSNPrintf(title, sizeof(title), "Pair %s", s->name));
    PetscOptionsBegin(comm, prefix, title, "doc/contact-bodies.md");
    PetscCall(PetscOptionsString("-slave", "Node set of the slave nodes", "doc/contact-bodies.md", s->slave, s->slave, sizeof(s->slave), &hs));
    PetscCall(PetscOptionsString("-master", "Node set of the master surface: the boundary faces whose four nodes lie in it", "doc/contact-bodies.md", s->master, s->master, sizeof(s->master), &hm));
    PetscCall(PetscOptionsReal("-friction", "Coulomb friction coefficient", "doc/contact-bodies.md", s->mu, &s->mu, NULL));
    PetscCall(PetscStrncpy(buf, "auto", sizeof(buf)));
    PetscCall(PetscOptionsString("-penalty_normal", "Normal penalty K_N per node (force per length), or auto: factor * E * A / h per slave node (A its tributary area, h the element size normal to its faces)", "doc/contact-bodies.md", buf, buf, sizeof(buf), NULL));
    PetscCall(PetscSNPrintf(opt, sizeof(opt), "-pair_%s_penalty_normal", s->name));
    PetscCall(PenaltyOption(comm, opt, buf, &s->kauto, &s->kn));
    PetscCall(PetscStrncpy(buf, "auto", sizeof(buf)));
    PetscCall(PetscOptionsString("-penalty_tangential", "Tangential penalty K_T per node, or auto: ratio * K_N", "doc/contact-bodies.md", buf, buf, sizeof(buf), NULL));
    PetscCall(PetscSNPrintf(opt, sizeof(opt), "-pair_%s_penalty_tangential", s->name));
    PetscCall(PenaltyOption(comm, opt, buf, &s->ktauto, &s->kt));
    PetscCall(PetscOptionsReal("-penalty_factor", "With the automatic normal penalty: K_N = factor * E * A / h", "doc/contact-bodies.md", s->kfactor, &s->kfactor, NULL));
    PetscCall(PetscOptionsReal("-penalty_ratio", "With the automatic tangential penalty: K_T = ratio * K_N", "doc/contact-bodies.md", s->kratio, &s->kratio, NULL));
    PetscCall(PetscOptionsBool("-two_pass", "Symmetric treatment: also the master's nodes as slaves against the slave set's faces, each pass with half the penalty", "doc/contact-bodies.md", s->two_pass, &s->two_pass, NULL));
    s->smooth = PETSC_FALSE;
    PetscCall(PetscOptionsBool("-smooth", "Experimental: the master surface's normal interpolated from its corners' normals (each the mean of the master faces' around it, held within a Newton iteration), the slave node projected along it: no jump where two faces meet at an angle (default: each face's own normal, the closest point)", "doc/contact-bodies.md", s->smooth, &s->smooth, NULL));
    s->smooth_tol = 1e-6;
    PetscCall(PetscOptionsReal("-smooth_tol", "With -pair_<p>_smooth: the largest change of a corner's normal between the one the last Newton iteration held and the one at the solution (another Newton solve follows beyond it)", "doc/contact-bodies.md", s->smooth_tol, &s->smooth_tol, NULL));
    PetscCheck(s->smooth_tol > 0 && PetscIsNormalReal(s->smooth_tol), comm, PETSC_ERR_USER_INPUT, "-pair_%s_smooth_tol %g must be positive", s->name, (double)s->smooth_tol);
    s->aug      = s->two_pass;
    s->aug_tol  = -1e-3;
    s->aug_mtol = 0.2;
    PetscCall(PetscOptionsBool("-augmented", "Augmented Lagrangian: Uzawa updates of the slave nodes' multipliers between Newton solves until the penetration and the stick slip are below -pair_<p>_augmented_tol (default with -pair_<p>_two_pass, whose constraints must hold exactly)", "doc/contact-bodies.md", s->aug, &s->aug, NULL));
    PetscCall(PetscOptionsReal("-augmented_tol", "Augmented Lagrangian: the largest penetration and stick slip per step accepted, a length (default 1e-3 times the smallest slave element size)", "doc/contact-bodies.md", PetscAbsReal(s->aug_tol), &s->aug_tol, &ht));
    if (!ht) s->aug_tol = -1e-3; /* (relative) */
    PetscCheck(!ht || (s->aug_tol > 0 && PetscIsNormalReal(s->aug_tol)), comm, PETSC_ERR_USER_INPUT, "-pair_%s_augmented_tol %g must be positive", s->name, (double)s->aug_tol);
    PetscCall(PetscOptionsReal("-augmented_multiplier_tol", "Augmented Lagrangian: the largest change of a multiplier accepted, relative to the largest multiplier", "doc/contact-bodies.md", s->aug_mtol, &s->aug_mtol, NULL));
    PetscCheck(s->aug_mtol > 0 && PetscIsNormalReal(s->aug_mtol), comm, PETSC_ERR_USER_INPUT, "-pair_%s_augmented_multiplier_tol %g must be positive", s->name, (double)s->aug_mtol);
    PetscCall(PetscOptionsReal("-search_distance", "Candidate faces of a slave node: those whose box lies within this distance of it at the start of each Newton iteration (default: twice the largest master face's diagonal)", "doc/contact-bodies.md", s->search, &s->search, NULL));
    PetscOptionsEnd();
    PetscCheck(hs && s->slave[0], comm, PETSC_ERR_USER_INPUT, "-pair_%s_slave: the pair needs a node set of slave nodes", s->name);
    PetscCheck(hm && s->master[0], comm, PETSC_ERR_USER_INPUT, "-pair_%s_master: the pair needs a node set of master faces", s->name);
    PetscCheck(s->mu >= 0 && (s->mu == 0 || PetscIsNormalReal(s->mu)), comm, PETSC_ERR_USER_INPUT, "-pair_%s_friction %g must be >= 0", s->name, (double)s->mu);
    PetscCheck(s->kfactor > 0 && PetscIsNormalReal(s->kfactor), comm, PETSC_ERR_USER_INPUT, "-pair_%s_penalty_factor %g must be positive", s->name, (double)s->kfactor);
    PetscCheck(s->kratio > 0 && PetscIsNormalReal(s->kratio), comm, PETSC_ERR_USER_INPUT, "-pair_%s_penalty_ratio %g must be positive", s->name, (double)s->kratio);
    PetscCheck(s->search < 0 || (s->search > 0 && PetscIsNormalReal(s->search)), comm, PETSC_ERR_USER_INPUT, "-pair_%s_search_distance %g must be positive", s->name, (double)s->search);
    {
      PetscBool same;
      PetscCall(PetscStrcmp(s->slave, s->master, &same));
      PetscCheck(!same, comm, PETSC_ERR_USER_INPUT, "-pair_%s_slave and -pair_%s_master are the same set '%s': a body's contact with itself is not supported", s->name, s->name, s->slave);
    }
  }
  PetscFunctionReturn(0);
}

PetscErrorCode ContactPairsGetFaceSets(ContactPairs p, PetscInt *n, char (**sets)[ATRITO_NAME_LEN])
{
  PetscFunctionBeginUser;
  *n = 0;
  for (PetscInt k = 0; k < p->np; k++) {
    PetscCall(PetscStrncpy(p->fsets[(*n)++], p->spec[k].master, ATRITO_NAME_LEN));
    PetscCall(PetscStrncpy(p->fsets[(*n)++], p->spec[k].slave, ATRITO_NAME_LEN));
  }
  *sets = p->fsets;
  PetscFunctionReturn(0);
}

PetscErrorCode ContactPairsSetCellModuli(ContactPairs p, PetscInt nc, const PetscReal *Ec)
{
  PetscFunctionBeginUser;
  PetscCall(PetscFree(p->Ecell));
  PetscCall(PetscMalloc1(nc + 1, &p->Ecell));
  PetscCall(PetscArraycpy(p->Ecell, Ec, nc));
  PetscFunctionReturn(0);
}

PetscErrorCode ContactPairsSetYoungModulus(ContactPairs p, PetscReal E)
{
  PetscFunctionBeginUser;
  p->E = E;
  PetscFunctionReturn(0);
}

static void FaceCorners(const Mesh *m, const PetscInt *fv, const PetscScalar *u, PetscReal x[12])
{
  for (int a = 0; a < 4; a++)
    for (int k = 0; k < 3; k++) x[3 * a + k] = m->X[3 * fv[a] + k] + (u ? PetscRealPart(u[m->vloff[fv[a]] + k]) : 0);
}

/* a quadrilateral's area times its unit normal, half the cross product of its diagonals (exact for
   a plane face) */
static void FaceAreaNormal(const PetscReal x[12], double nr[3])
{
  double d1[3], d2[3];
  for (int k = 0; k < 3; k++) {
    d1[k] = x[6 + k] - x[k];
    d2[k] = x[9 + k] - x[3 + k];
  }
  nr[0] = 0.5 * (d1[1] * d2[2] - d1[2] * d2[1]);
  nr[1] = 0.5 * (d1[2] * d2[0] - d1[0] * d2[2]);
  nr[2] = 0.5 * (d1[0] * d2[1] - d1[1] * d2[0]);
}

/* a quadrilateral's larger diagonal */
static double FaceDiagonal(const PetscReal x[12])
{
  double d1 = 0, d2 = 0;
  for (int k = 0; k < 3; k++) {
    d1 += (x[6 + k] - x[k]) * (x[6 + k] - x[k]);
    d2 += (x[9 + k] - x[3 + k]) * (x[9 + k] - x[3 + k]);
  }
  return sqrt(d1 > d2 ? d1 : d2);
}

/* the sums over the ranks of what each added at its local vertices in vl (a local vector of the
   unconstrained section): every vertex, owned or ghost, gets the total (collective) */
static PetscErrorCode VertexSum(const Mesh *m, Vec vl)
{
  Vec vg;

  PetscFunctionBeginUser;
  PetscCall(DMGetGlobalVector(m->dmr, &vg));
  PetscCall(VecZeroEntries(vg));
  PetscCall(DMLocalToGlobal(m->dmr, vl, ADD_VALUES, vg));
  PetscCall(DMGlobalToLocal(m->dmr, vg, INSERT_VALUES, vl));
  PetscCall(DMRestoreGlobalVector(m->dmr, &vg));
  PetscFunctionReturn(0);
}

/* The slave faces' smallest element size hmin (all ranks) and, with the automatic penalty, the
   penalty of the slave nodes of side sd: K_N = factor sum_f E_f a_i(f) / h_f over the
   boundary faces f of the slave set at node i (a_i its share of the face's area, h_f the extent of
   the face's cell normal to it, in the reference configuration; E_f the modulus of its cell's
   material); the faces' shares summed over the
   ranks through the unconstrained section */
static PetscErrorCode SlaveFaces(ContactPairs p, PairSide *sd, const PairSpec *s)
{
  const Mesh  *m = p->mesh;
  PetscInt     nf, *fv, *fc;
  Vec          kl;
  PetscSection ls;
  PetscScalar *a;
  static const int opp[6] = {1, 0, 4, 5, 2, 3};
  static const int hexface[6][4] = {{0, 3, 2, 1}, {4, 5, 6, 7}, {0, 1, 5, 4}, {1, 2, 6, 5}, {2, 3, 7, 6}, {3, 0, 4, 7}};

  PetscFunctionBeginUser;
  PetscCall(MeshGetBoundaryFaces(m, sd->sset, &nf, &fv, &fc));
  sd->hmin = PETSC_MAX_REAL;
  PetscCall(DMGetLocalSection(m->dmr, &ls));
  PetscCall(DMGetLocalVector(m->dmr, &kl));
  PetscCall(VecZeroEntries(kl));
  PetscCall(VecGetArray(kl, &a));
  for (PetscInt f = 0; f < nf; f++) {
    const PetscInt c = fc[f] / 6, k = fc[f] % 6, *cv = m->cv + 8 * c;
    double         x[4][3], ar[4], c0[3] = {0, 0, 0}, c1[3] = {0, 0, 0}, nrm[3], A = 0, h = 0;
    PetscReal      xf[12];
    for (int j = 0; j < 4; j++)
      for (int d = 0; d < 3; d++) {
        x[j][d] = m->X[3 * cv[hexface[k][j]] + d];
        c0[d] += 0.25 * x[j][d];
        c1[d] += 0.25 * m->X[3 * cv[hexface[opp[k]][j]] + d];
      }
    ContactQuadAreas(x, ar);
    for (int j = 0; j < 4; j++)
      for (int d = 0; d < 3; d++) xf[3 * j + d] = x[j][d];
    FaceAreaNormal(xf, nrm);
    for (int d = 0; d < 3; d++) A += nrm[d] * nrm[d];
    A = PetscSqrtReal(A);
    for (int d = 0; d < 3; d++) h += (c0[d] - c1[d]) * nrm[d] / A;
    h        = PetscAbsReal(h);
    sd->hmin = PetscMin(sd->hmin, h);
    for (int j = 0; j < 4; j++) {
      PetscInt off;
      PetscCall(PetscSectionGetOffset(ls, m->vstart + cv[hexface[k][j]], &off));
      const PetscReal Ef = p->Ecell ? p->Ecell[c] : p->E;
      if (!(Ef > 0)) sd->noE = PETSC_TRUE; /* a material without a modulus (a UMAT) */
      a[off] += h > 0 ? Ef * ar[j] / h : 0;
    }
  }
  PetscCall(VecRestoreArray(kl, &a));
  PetscCall(VertexSum(m, kl));
  PetscCall(VecGetArray(kl, &a));
  for (PetscInt i = 0; i < sd->ns && s->kauto; i++) {
    PetscInt off;
    PetscCall(PetscSectionGetOffset(ls, m->vstart + sd->sv[i], &off));
    sd->kn[i] = sd->weight * s->kfactor * PetscRealPart(a[off]);
  }
  PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, &sd->hmin, 1, MPIU_REAL, MPIU_MIN, p->comm));
  PetscCall(VecRestoreArray(kl, &a));
  PetscCall(DMRestoreLocalVector(m->dmr, &kl));
  PetscCall(PetscFree(fv));
  PetscCall(PetscFree(fc));
  PetscFunctionReturn(0);
}

static PetscErrorCode SideSetUp(ContactPairs p, PairSide *sd)
{
  const Mesh     *m = p->mesh;
  const PairSpec *s = &p->spec[sd->spec];
  PetscInt        nf, *fc, g[2];
  PetscBool      *mark, found;
  PetscReal       dmax = 0;

  PetscFunctionBeginUser;
  /* master faces */
  PetscCall(MeshGetBoundaryFaces(m, sd->mset, &nf, &sd->fov, &fc));
  sd->nfo = nf;
  PetscCall(PetscMalloc4(12 * nf + 1, &sd->foid, 12 * nf + 1, &sd->fog, 12 * nf + 1, &sd->fox, 12 * nf + 1, &sd->fox0));
  PetscCall(PetscCalloc1(12 * nf + 1, &sd->fof));
  PetscCall(PetscCalloc1(12 * nf + 1, &sd->fofc));
  PetscCall(PetscCalloc1(12 * nf + 1, &sd->fonb));
  for (PetscInt f = 0; f < nf; f++) {
    sd->foid[12 * f] = 6 * m->elem_src[fc[f] / 6] + fc[f] % 6;
    for (int a = 0; a < 4; a++) sd->foid[12 * f + 1 + a] = m->node_src[sd->fov[4 * f + a]]; /* its corners */
    for (int a = 0; a < 4; a++) PetscCall(MeshVertexDofs(m, sd->fov[4 * f + a], sd->fog + 12 * f + 3 * a));
    FaceCorners(m, sd->fov + 4 * f, NULL, sd->fox0 + 12 * f);
    for (int k = 0; k < 12; k++) sd->fox[12 * f + k] = sd->fox0[12 * f + k];
    dmax = PetscMax(dmax, FaceDiagonal(sd->fox0 + 12 * f));
  }
  PetscCall(PetscFree(fc));
  /* slave nodes: the owned vertices of the set */
  PetscCall(PetscCalloc1(m->nv, &mark));
  PetscCall(MeshMarkSetVertices(m, sd->sset, mark, &found));
  sd->ns = 0;
  for (PetscInt v = 0; v < m->nv; v++)
    if (mark[v] && m->vowned[v]) sd->ns++;
  g[0] = nf;
  g[1] = sd->ns;
  PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, g, 2, MPIU_INT, MPI_SUM, p->comm));
  {
    /* both sets must exist (the master's is looked up like the slave's) */
    PetscBool  fm;
    PetscInt   fl[2];
    PetscBool *mm;
    PetscCall(PetscCalloc1(m->nv, &mm));
    PetscCall(MeshMarkSetVertices(m, sd->mset, mm, &fm));
    PetscCall(PetscFree(mm));
    fl[0] = found ? 1 : 0;
    fl[1] = fm ? 1 : 0;
    PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, fl, 2, MPIU_INT, MPI_MAX, p->comm));
    PetscCheck(fl[0], p->comm, PETSC_ERR_USER_INPUT, "-pair_%s_%s: the mesh has no set named '%s'", s->name, strcmp(sd->sset, s->slave) ? "master" : "slave", sd->sset);
    PetscCheck(fl[1], p->comm, PETSC_ERR_USER_INPUT, "-pair_%s_%s: the mesh has no set named '%s'", s->name, strcmp(sd->mset, s->master) ? "slave" : "master", sd->mset);
  }
  PetscCheck(g[0] > 0, p->comm, PETSC_ERR_USER_INPUT, "-pair_%s_%s %s: the set has no boundary faces (a master surface needs faces of the body's boundary whose four nodes all lie in the set)", s->name, strcmp(sd->mset, s->master) ? "slave" : "master", sd->mset);
  PetscCheck(g[1] > 0, p->comm, PETSC_ERR_USER_INPUT, "-pair_%s_slave %s: the set has no nodes", s->name, sd->sset);
  PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, &dmax, 1, MPIU_REAL, MPIU_MAX, p->comm));
  sd->search = s->search > 0 ? s->search : 2 * dmax;
  PetscCall(PetscMalloc4(sd->ns + 1, &sd->sv, 3 * sd->ns + 1, &sd->sg, sd->ns + 1, &sd->kn, sd->ns + 1, &sd->kt));
  PetscCall(PetscCalloc4(sd->ns + 1, &sd->st_c, sd->ns + 1, &sd->st_t, 3 * sd->ns + 1, &sd->seed, 3 * sd->ns + 1, &sd->seedn));
  PetscCall(PetscCalloc3(sd->ns + 1, &sd->has_seed, sd->ns + 2, &sd->coff, sd->ns + 1, &sd->active_prev));
  PetscCall(PetscMalloc1(sd->ns + 1, &sd->ssrc));
  sd->ns = 0;
  for (PetscInt v = 0; v < m->nv; v++)
    if (mark[v] && m->vowned[v]) {
      const PetscInt i = sd->ns++;
      sd->sv[i]        = v;
      sd->ssrc[i]      = m->node_src[v];
      PetscCall(MeshVertexDofs(m, v, sd->sg + 3 * i));
      sd->st_c[i].face = -1;
      for (int k = 0; k < 3; k++) sd->st_c[i].y[k] = m->X[3 * v + k];
      sd->st_c[i].gap = PETSC_INFINITY;
      sd->st_t[i]     = sd->st_c[i];
    }
  PetscCall(PetscFree(mark));
  if (!s->kauto)
    for (PetscInt i = 0; i < sd->ns; i++) sd->kn[i] = sd->weight * s->kn;
  PetscCall(SlaveFaces(p, sd, s));
  sd->tol    = s->aug_tol > 0 ? s->aug_tol : -s->aug_tol * sd->hmin;
  sd->kscale = 1;
  PetscCall(PetscCalloc1(3 * sd->ns + 1, &sd->lam));
  for (PetscInt i = 0; i < sd->ns; i++) sd->kt[i] = s->ktauto ? s->kratio * sd->kn[i] : sd->weight * s->kt;
  {
    PetscReal kmin = PETSC_MAX_REAL, kmax = 0;
    for (PetscInt i = 0; i < sd->ns; i++) {
      kmin = PetscMin(kmin, sd->kn[i]);
      kmax = PetscMax(kmax, sd->kn[i]);
    }
    PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, &kmin, 1, MPIU_REAL, MPIU_MIN, p->comm));
    PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, &kmax, 1, MPIU_REAL, MPIU_MAX, p->comm));
    PetscInt noE = (s->kauto && sd->noE) ? 1 : 0;
    PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, &noE, 1, MPIU_INT, MPI_MAX, p->comm));
    PetscCheck(!noE, p->comm, PETSC_ERR_USER_INPUT, "-pair_%s_penalty_normal auto: the material of a slave face has no Young's modulus (a user material); give -pair_%s_penalty_normal a value", s->name, s->name);
    PetscCheck(kmin > 0, p->comm, PETSC_ERR_USER_INPUT, "-pair_%s_slave %s: a slave node lies on no boundary face of its set, so it has no automatic penalty (the set must be a surface of the body)", s->name, sd->sset);
    PetscCall(PetscPrintf(p->comm, "contact pair %s%s: %" PetscInt_FMT " slave nodes (set '%s') on %" PetscInt_FMT " master faces (set '%s'), K_N per node %g to %g%s, mu %g, search distance %g", s->name, s->two_pass ? (sd->weight < 1 && !strcmp(sd->sset, s->master) ? " (second pass)" : " (first pass)") : "", g[1], sd->sset, g[0], sd->mset, (double)kmin, (double)kmax, s->kauto ? " (automatic)" : "", (double)s->mu, (double)sd->search));
    if (s->aug) PetscCall(PetscPrintf(p->comm, ", augmented Lagrangian to %g", (double)sd->tol));
    PetscCall(PetscPrintf(p->comm, "\n"));
  }
  PetscFunctionReturn(0);
}

PetscErrorCode ContactPairsSetUp(ContactPairs p, const Mesh *m)
{
  PetscFunctionBeginUser;
  p->mesh  = m;
  p->nside = 0;
  for (PetscInt k = 0; k < p->np; k++) {
    const PairSpec *s = &p->spec[k];
    PetscCheck(!s->kauto || p->E > 0 || p->Ecell, p->comm, PETSC_ERR_USER_INPUT, "-pair_%s_penalty_normal auto needs the material's Young's modulus: give a value", s->name);
    for (int pass = 0; pass < (s->two_pass ? 2 : 1); pass++) {
      PairSide *sd = &p->side[p->nside++];
      sd->spec     = k;
      sd->smooth   = s->smooth;
      sd->weight   = s->two_pass ? 0.5 : 1.0;
      PetscCall(PetscStrncpy(sd->sset, pass ? s->master : s->slave, ATRITO_NAME_LEN));
      PetscCall(PetscStrncpy(sd->mset, pass ? s->slave : s->master, ATRITO_NAME_LEN));
      PetscCall(SideSetUp(p, sd));
    }
  }
  PetscFunctionReturn(0);
}

static PetscErrorCode SideDestroy(PairSide *sd)
{
  PetscFunctionBeginUser;
  PetscCall(PetscFree(sd->fov));
  PetscCall(PetscFree4(sd->foid, sd->fog, sd->fox, sd->fox0));
  PetscCall(PetscFree(sd->fof));
  PetscCall(PetscFree(sd->fofc));
  PetscCall(PetscFree(sd->fonb));
  PetscCall(PetscFree(sd->fcnb));
  PetscCall(PetscFree5(sd->fcid, sd->fcg, sd->fcx, sd->fcx0, sd->fcf));
  PetscCall(PetscSFDestroy(&sd->sf));
  PetscCall(PetscFree4(sd->sv, sd->sg, sd->kn, sd->kt));
  PetscCall(PetscFree4(sd->st_c, sd->st_t, sd->seed, sd->seedn));
  PetscCall(PetscFree3(sd->has_seed, sd->coff, sd->active_prev));
  PetscCall(PetscFree(sd->cand));
  PetscCall(PetscFree(sd->lam));
  PetscCall(PetscFree(sd->ssrc));
  PetscFunctionReturn(0);
}

PetscErrorCode ContactPairsDestroy(ContactPairs *p)
{
  PetscFunctionBeginUser;
  if (!*p) PetscFunctionReturn(0);
  for (PetscInt s = 0; s < (*p)->nside; s++) PetscCall(SideDestroy(&(*p)->side[s]));
  PetscCall(PetscFree((*p)->Ecell));
  PetscCall(PetscFree(*p));
  PetscFunctionReturn(0);
}

static void SlavePosition(const Mesh *m, PetscInt v, const PetscScalar *u, double y[3])
{
  for (int k = 0; k < 3; k++) y[k] = m->X[3 * v + k] + PetscRealPart(u[m->vloff[v] + k]);
}

static void Box(const PetscReal *x, PetscInt n, PetscReal b[6])
{
  b[0] = b[2] = b[4] = PETSC_MAX_REAL;
  b[1] = b[3] = b[5] = -PETSC_MAX_REAL;
  for (PetscInt i = 0; i < n; i++)
    for (int d = 0; d < 3; d++) {
      b[2 * d]     = PetscMin(b[2 * d], x[3 * i + d]);
      b[2 * d + 1] = PetscMax(b[2 * d + 1], x[3 * i + d]);
    }
}

static PetscBool BoxesMeet(const PetscReal a[6], const PetscReal b[6], PetscReal w)
{
  for (int d = 0; d < 3; d++)
    if (a[2 * d] > b[2 * d + 1] + w || b[2 * d] > a[2 * d + 1] + w) return PETSC_FALSE;
  return PETSC_TRUE;
}

/* the candidates of side sd at u (collective): the faces whose box meets this rank's slave box
   widened by the search distance, as leaves of a PetscSF from their owners; then per slave node
   the candidates whose box lies within the search distance of it */
static PetscErrorCode SideCandidates(ContactPairs p, PairSide *sd, const PetscScalar *u)
{
  const Mesh  *m = p->mesh;
  PetscReal    box[6], obox[6], *boxes, *ys;
  PetscMPIInt *scount, *rcount, *sdisp, *rdisp, size = p->size;
  PetscInt    *sendf, *recvf, nsend = 0;
  PetscSFNode *remote;

  PetscFunctionBeginUser;
  for (PetscInt f = 0; f < sd->nfo; f++) FaceCorners(m, sd->fov + 4 * f, u, sd->fox + 12 * f);
  PetscCall(PetscMalloc1(3 * sd->ns + 1, &ys));
  for (PetscInt i = 0; i < sd->ns; i++) SlavePosition(m, sd->sv[i], u, ys + 3 * i);
  Box(ys, sd->ns, box);
  PetscCall(PetscMalloc1(6 * size, &boxes));
  PetscCallMPI(MPI_Allgather(box, 6, MPIU_REAL, boxes, 6, MPIU_REAL, p->comm));
  PetscCall(PetscCalloc4(size, &scount, size, &rcount, size + 1, &sdisp, size + 1, &rdisp));
  Box(sd->fox, 4 * sd->nfo, obox); /* the box of all the faces this rank owns: tested first */
  for (int pass = 0; pass < 2; pass++) {
    if (pass) {
      for (PetscMPIInt r = 0; r < size; r++) sdisp[r + 1] = sdisp[r] + scount[r];
      nsend = sdisp[size];
      PetscCall(PetscMalloc1(nsend + 1, &sendf));
      for (PetscMPIInt r = 0; r < size; r++) scount[r] = 0;
    }
    for (PetscMPIInt r = 0; r < size; r++) {
      if (boxes[6 * r] > boxes[6 * r + 1]) continue; /* no slave nodes there */
      if (!sd->nfo || !BoxesMeet(obox, boxes + 6 * r, sd->search)) continue;
      for (PetscInt f = 0; f < sd->nfo; f++) {
        PetscReal fb[6];
        Box(sd->fox + 12 * f, 4, fb);
        if (!BoxesMeet(fb, boxes + 6 * r, sd->search)) continue;
        if (pass) sendf[sdisp[r] + scount[r]] = f;
        scount[r]++;
      }
    }
  }
  PetscCallMPI(MPI_Alltoall(scount, 1, MPI_INT, rcount, 1, MPI_INT, p->comm));
  for (PetscMPIInt r = 0; r < size; r++) rdisp[r + 1] = rdisp[r] + rcount[r];
  PetscCall(PetscMalloc1(rdisp[size] + 1, &recvf));
  PetscCallMPI(MPI_Alltoallv(sendf, scount, sdisp, MPIU_INT, recvf, rcount, rdisp, MPIU_INT, p->comm));
  /* the leaves: 12 per candidate face */
  PetscCall(PetscFree5(sd->fcid, sd->fcg, sd->fcx, sd->fcx0, sd->fcf));
  PetscCall(PetscSFDestroy(&sd->sf));
  sd->nfc = rdisp[size];
  PetscCall(PetscMalloc5(12 * sd->nfc + 1, &sd->fcid, 12 * sd->nfc + 1, &sd->fcg, 12 * sd->nfc + 1, &sd->fcx, 12 * sd->nfc + 1, &sd->fcx0, 12 * sd->nfc + 1, &sd->fcf));
  PetscCall(PetscFree(sd->fcnb));
  PetscCall(PetscCalloc1(12 * sd->nfc + 1, &sd->fcnb));
  PetscCall(PetscMalloc1(12 * sd->nfc + 1, &remote));
  for (PetscMPIInt r = 0; r < size; r++)
    for (PetscInt j = rdisp[r]; j < rdisp[r + 1]; j++)
      for (int k = 0; k < 12; k++) {
        remote[12 * j + k].rank  = r;
        remote[12 * j + k].index = 12 * recvf[j] + k;
      }
  PetscCall(PetscSFCreate(p->comm, &sd->sf));
  PetscCall(PetscSFSetGraph(sd->sf, 12 * sd->nfo, 12 * sd->nfc, NULL, PETSC_COPY_VALUES, remote, PETSC_OWN_POINTER));
  PetscCall(PetscSFSetUp(sd->sf));
  PetscCall(PetscInfo(NULL, "contact pair side %s -> %s: %" PetscInt_FMT " slave nodes, %" PetscInt_FMT " faces owned, %" PetscInt_FMT " candidate faces (%" PetscInt_FMT " from other ranks)\n", sd->sset, sd->mset, sd->ns, sd->nfo, sd->nfc, sd->nfc - (PetscInt)rcount[p->rank]));
  PetscCall(PetscSFBcastBegin(sd->sf, MPIU_INT, sd->foid, sd->fcid, MPI_REPLACE));
  PetscCall(PetscSFBcastEnd(sd->sf, MPIU_INT, sd->foid, sd->fcid, MPI_REPLACE));
  PetscCall(PetscSFBcastBegin(sd->sf, MPIU_INT, sd->fog, sd->fcg, MPI_REPLACE));
  PetscCall(PetscSFBcastEnd(sd->sf, MPIU_INT, sd->fog, sd->fcg, MPI_REPLACE));
  PetscCall(PetscSFBcastBegin(sd->sf, MPIU_REAL, sd->fox0, sd->fcx0, MPI_REPLACE));
  PetscCall(PetscSFBcastEnd(sd->sf, MPIU_REAL, sd->fox0, sd->fcx0, MPI_REPLACE));
  PetscCall(PetscSFBcastBegin(sd->sf, MPIU_REAL, sd->fox, sd->fcx, MPI_REPLACE));
  PetscCall(PetscSFBcastEnd(sd->sf, MPIU_REAL, sd->fox, sd->fcx, MPI_REPLACE));
  /* per slave node */
  /* per slave node: a uniform grid of bins over this rank's slave box (bins at least the search
     distance wide, at most 64 per direction); each candidate, widened by the search distance, is
     listed in the bins it meets; a node tests the candidates of its own bin only: the work grows
     with the nodes and the candidates, not with their product */
  {
    PetscInt  nb[3], nbin = 1, *boff, *bfill, *blist = NULL, n = 0;
    PetscReal w[3];
    for (int d = 0; d < 3; d++) {
      const PetscReal ext = sd->ns ? box[2 * d + 1] - box[2 * d] : 0;
      nb[d] = sd->ns ? (PetscInt)PetscMin(64, PetscMax(1, PetscFloorReal(ext / sd->search))) : 1;
      w[d]  = nb[d] > 1 ? ext / nb[d] : PETSC_MAX_REAL;
      nbin *= nb[d];
    }
    PetscCall(PetscCalloc2(nbin + 1, &boff, nbin + 1, &bfill));
#define BIN_RANGE(lo, hi, d, a, b) \
  do { \
    a = nb[d] > 1 ? (PetscInt)PetscFloorReal(((lo) - box[2 * (d)]) / w[d]) : 0; \
    b = nb[d] > 1 ? (PetscInt)PetscFloorReal(((hi) - box[2 * (d)]) / w[d]) : 0; \
    a = PetscMax(a, 0); \
    b = PetscMin(b, nb[d] - 1); \
  } while (0)
    for (int pass = 0; pass < 2; pass++) { /* count, then fill the bins' lists */
      if (pass) {
        for (PetscInt b = 0; b < nbin; b++) boff[b + 1] += boff[b];
        PetscCall(PetscFree(blist));
        PetscCall(PetscMalloc1(boff[nbin] + 1, &blist));
      }
      for (PetscInt c = 0; c < sd->nfc && sd->ns; c++) {
        PetscReal fb[6];
        PetscInt  lo[3], hi[3];
        Box(sd->fcx + 12 * c, 4, fb);
        for (int d = 0; d < 3; d++) BIN_RANGE(fb[2 * d] - sd->search, fb[2 * d + 1] + sd->search, d, lo[d], hi[d]);
        for (PetscInt i = lo[0]; i <= hi[0]; i++)
          for (PetscInt j = lo[1]; j <= hi[1]; j++)
            for (PetscInt k = lo[2]; k <= hi[2]; k++) {
              const PetscInt b = (i * nb[1] + j) * nb[2] + k;
              if (pass) blist[boff[b] + bfill[b]++] = c;
              else boff[b + 1]++;
            }
      }
    }
    PetscCall(PetscFree(sd->cand));
    for (int pass = 0; pass < 2; pass++) {
      if (pass) PetscCall(PetscMalloc1(n + 1, &sd->cand));
      n = 0;
      for (PetscInt i = 0; i < sd->ns; i++) {
        PetscReal yb[6];
        PetscInt  bi[3], b;
        Box(ys + 3 * i, 1, yb);
        for (int d = 0; d < 3; d++) BIN_RANGE(yb[2 * d], yb[2 * d], d, bi[d], bi[d]);
        b           = (bi[0] * nb[1] + bi[1]) * nb[2] + bi[2];
        sd->coff[i] = n;
        for (PetscInt q = boff[b]; q < boff[b + 1]; q++) { /* (in increasing candidate order) */
          const PetscInt c = blist[q];
          PetscReal      fb[6];
          Box(sd->fcx + 12 * c, 4, fb);
          if (!BoxesMeet(fb, yb, sd->search)) continue;
          if (pass) sd->cand[n] = c;
          n++;
        }
      }
      sd->coff[sd->ns] = n;
    }
#undef BIN_RANGE
    PetscCall(PetscFree2(boff, bfill));
    PetscCall(PetscFree(blist));
  }
  PetscCall(PetscFree(ys));
  PetscCall(PetscFree(boxes));
  PetscCall(PetscFree4(scount, rcount, sdisp, rdisp));
  PetscCall(PetscFree(sendf));
  PetscCall(PetscFree(recvf));
  PetscFunctionReturn(0);
}

/* -pair_<p>_smooth: the master surface's normal at each of its vertices, the mean of the normals of
   the master faces around it weighted by their areas (over all ranks, through the unconstrained
   section), at the face positions fox; each owned face's four, then the candidates' from their
   owners (collective). Held within a Newton iteration, as the frame seeds are. */
static PetscErrorCode SideNormals(ContactPairs p, PairSide *sd)
{
  const Mesh  *m = p->mesh;
  Vec          vl;
  PetscSection ls;
  PetscScalar *a;

  PetscFunctionBeginUser;
  if (!p->spec[sd->spec].smooth) PetscFunctionReturn(0);
  PetscCall(DMGetLocalSection(m->dmr, &ls));
  PetscCall(DMGetLocalVector(m->dmr, &vl));
  PetscCall(VecZeroEntries(vl));
  PetscCall(VecGetArray(vl, &a));
  for (PetscInt f = 0; f < sd->nfo; f++) {
    double nr[3];
    FaceAreaNormal(sd->fox + 12 * f, nr);
    for (int c = 0; c < 4; c++) {
      PetscInt off;
      PetscCall(PetscSectionGetOffset(ls, m->vstart + sd->fov[4 * f + c], &off));
      for (int k = 0; k < 3; k++) a[off + k] += nr[k];
    }
  }
  PetscCall(VecRestoreArray(vl, &a));
  PetscCall(VertexSum(m, vl));
  PetscCall(VecGetArray(vl, &a));
  for (PetscInt f = 0; f < sd->nfo; f++)
    for (int c = 0; c < 4; c++) {
      PetscInt  off;
      PetscReal nn = 0;
      PetscCall(PetscSectionGetOffset(ls, m->vstart + sd->fov[4 * f + c], &off));
      for (int k = 0; k < 3; k++) nn += PetscSqr(PetscRealPart(a[off + k]));
      nn = PetscSqrtReal(nn);
      for (int k = 0; k < 3; k++) sd->fonb[12 * f + 3 * c + k] = nn > 0 ? PetscRealPart(a[off + k]) / nn : 0;
    }
  PetscCall(VecRestoreArray(vl, &a));
  PetscCall(DMRestoreLocalVector(m->dmr, &vl));
  PetscCall(PetscSFBcastBegin(sd->sf, MPIU_REAL, sd->fonb, sd->fcnb, MPI_REPLACE));
  PetscCall(PetscSFBcastEnd(sd->sf, MPIU_REAL, sd->fonb, sd->fcnb, MPI_REPLACE));
  PetscFunctionReturn(0);
}

/* the current corner positions of the candidates from their owners (collective) */
static PetscErrorCode SideRefresh(ContactPairs p, PairSide *sd, const PetscScalar *u)
{
  PetscFunctionBeginUser;
  if (!sd->sf) { /* an evaluation before the first step (the initial state): the candidates at u */
    PetscCall(SideCandidates(p, sd, u));
    PetscCall(SideNormals(p, sd));
    PetscFunctionReturn(0);
  }
  for (PetscInt f = 0; f < sd->nfo; f++) FaceCorners(p->mesh, sd->fov + 4 * f, u, sd->fox + 12 * f);
  PetscCall(PetscSFBcastBegin(sd->sf, MPIU_REAL, sd->fox, sd->fcx, MPI_REPLACE));
  PetscCall(PetscSFBcastEnd(sd->sf, MPIU_REAL, sd->fox, sd->fcx, MPI_REPLACE));
  PetscFunctionReturn(0);
}

/* Pairing of slave node i at y: among its candidates, the face on whose (bilinear) surface the node
   projects inside the face and nearest (ties: the smaller face id). Where no face has it inside (a
   node beyond the open edge of the master surface, or over a convex kink between two faces), the
   face it overshoots least, if by at most PAIR_EDGE_TOL in the face's parameters (a twentieth of
   the face's width), on that face's extension: a node at the edge of a surface, which the bodies'
   equal lateral strains keep there to round-off, would otherwise enter and leave contact from one
   iterate to the next. A face the node lies behind by more than half the face's larger diagonal
   is not a candidate (the node is at the body's other side), nor is a face the node is a corner of.
   -1 if none. */
#define PAIR_EDGE_TOL 0.1
/* the projection of y on candidate c: along the interpolated normal field (-pair_<p>_smooth, the
   corners' normals fcnb) or the closest point */
static int Project(const PairSide *sd, PetscInt c, const double y[3], const double xi0[2], int derivs, NTSProjection *pr);
static PetscInt PairNode(const PairSide *sd, PetscInt i, const double y[3], NTSProjection *best)
{
  const PetscInt self = sd->ssrc[i];
  PetscInt  bc = -1, oc = -1;
  PetscReal bd = PETSC_MAX_REAL, bo = PETSC_MAX_REAL;
  NTSProjection po;

  for (PetscInt j = sd->coff[i]; j < sd->coff[i + 1]; j++) {
    const PetscInt c      = sd->cand[j];
    const double  *x      = sd->fcx + 12 * c;
    const double   xi0[2] = {0, 0};
    NTSProjection  pr;
    double         d = 0, o;
    if (sd->fcid[12 * c + 1] == self || sd->fcid[12 * c + 2] == self || sd->fcid[12 * c + 3] == self || sd->fcid[12 * c + 4] == self) continue; /* its own face */
    if (Project(sd, c, y, xi0, 0, &pr)) continue;
    if (pr.g < -0.5 * FaceDiagonal(x)) continue; /* deeper behind it than half its diagonal: the body's other side */
    if (!pr.inside) {
      o = PetscMax(PetscAbsReal(pr.xi[0]), PetscAbsReal(pr.xi[1])) - 1;
      if (o <= PAIR_EDGE_TOL && (o < bo || (o == bo && sd->fcid[12 * c] < sd->fcid[12 * oc]))) {
        bo = o;
        oc = c;
        po = pr;
      }
      continue;
    }
    for (int k = 0; k < 3; k++) d += (y[k] - pr.x[k]) * (y[k] - pr.x[k]);
    if (d < bd || (d == bd && sd->fcid[12 * c] < sd->fcid[12 * bc])) {
      bd    = d;
      bc    = c;
      *best = pr;
    }
  }
  if (bc < 0 && oc >= 0) {
    bc    = oc;
    *best = po;
  }
  return bc;
}

static int Project(const PairSide *sd, PetscInt c, const double y[3], const double xi0[2], int derivs, NTSProjection *pr)
{
  const double(*x)[3] = (const double(*)[3])(sd->fcx + 12 * c);
  if (sd->smooth) return NTSProjectNormal(4, y, x, (const double(*)[3])(sd->fcnb + 12 * c), xi0, 1e-10, derivs, pr);
  return NTSProject(4, y, x, xi0, 1e-10, derivs, pr);
}

PetscErrorCode ContactPairsSeed(ContactPairs p, const PetscScalar *u, PetscBool from_committed)
{
  PetscFunctionBeginUser;
  if (!p || !p->np) PetscFunctionReturn(0);
  PetscCall(PetscLogEventBegin(p->ev_search, 0, 0, 0, 0));
  for (PetscInt s = 0; s < p->nside; s++) {
    PairSide *sd = &p->side[s];
    if (from_committed) sd->pen_prev = -1; /* (the augmentation starts) */
    /* the candidates at the iterate: found again at every Newton iteration, so that a node sliding
       far within a step finds the faces it reaches (fixed within the iteration: its residual,
       line search and Jacobian see the same faces) */
    PetscCall(SideCandidates(p, sd, u));
    PetscCall(SideNormals(p, sd));
    for (PetscInt i = 0; i < sd->ns; i++) {
      double        y[3], t1[3], t2[3];
      NTSProjection pr;
      PetscInt      c;
      if (from_committed) {
        const PairState *cc = &sd->st_c[i];
        const PetscBool  in = cc->status != CONTACT_OPEN ? PETSC_TRUE : PETSC_FALSE;
        /* the multipliers the step starts from: the committed forces (the normal one with the
           augmentation only) */
        sd->lam[3 * i]      = (in && p->spec[sd->spec].aug) ? cc->tN : 0;
        sd->lam[3 * i + 1]  = in ? cc->tT[0] : 0;
        sd->lam[3 * i + 2]  = in ? cc->tT[1] : 0;
        sd->has_seed[i]     = (cc->has_frame && in) ? PETSC_TRUE : PETSC_FALSE;
        for (int k = 0; k < 3; k++) {
          sd->seed[3 * i + k]  = cc->t1[k];
          sd->seedn[3 * i + k] = 0;
        }
        continue;
      }
      SlavePosition(p->mesh, sd->sv[i], u, y);
      c = PairNode(sd, i, y, &pr);
      if (c < 0 || (pr.g > 0 && !(sd->lam[3 * i] - sd->kscale * sd->kn[i] * pr.g > 0))) { /* out of contact: the frame is forgotten */
        sd->has_seed[i] = PETSC_FALSE;
        continue;
      }
      if (sd->has_seed[i]) { /* eq 30: the previous t1 carried to the new normal */
        double        r[3];
        double       *sdp = sd->seed + 3 * i, *sn = sd->seedn + 3 * i;
        ContactFrameCarry(sn, pr.n, sdp, r);
        if (!ContactFrame(pr.n, r, t1, t2))
          for (int k = 0; k < 3; k++) {
            sdp[k] = t1[k];
            sn[k]  = pr.n[k];
          }
      }
    }
  }
  PetscCall(PetscLogEventEnd(p->ev_search, 0, 0, 0, 0));
  PetscFunctionReturn(0);
}

/* slave node i of side sd at y: residual Rs (3), the 15 x 15 tangent Kx (if asked; rows and
   columns x_s, x_1..x_4, row-major), the corner rows' factors; the trial state; returns the
   candidate face or -1 */
static PetscInt NodeEval(ContactPairs p, PairSide *sd, PetscInt i, const double y[3], double Rs[3], double N[4], double *Kx, PetscInt *status_err)
{
  const PairSpec  *s  = &p->spec[sd->spec];
  const PairState *cc = &sd->st_c[i];
  PairState       *st = &sd->st_t[i];
  NTSProjection    pr;
  PetscInt         c;
  ContactLaw       law = {sd->kscale * sd->kn[i], sd->kscale * sd->kt[i], s->mu, 0, 0};
  double           tTn[2] = {0, 0}, ds[3], dds[45], K0[9], K1[9], R1[3], t1b[3], tNb, tTb[2];
  static const double I3[9] = {1, 0, 0, 0, 1, 0, 0, 0, 1};

  *status_err = 0;
  *st         = *cc;
  for (int k = 0; k < 3; k++) {
    st->y[k]  = y[k];
    st->f[k]  = 0;
    st->fT[k] = 0;
    Rs[k]     = 0;
  }
  st->tT[0] = st->tT[1] = 0;
  st->tN                = 0;
  st->status            = CONTACT_OPEN;
  st->has_frame         = PETSC_FALSE;
  st->face              = -1;
  st->gap               = PETSC_INFINITY;
  c                     = PairNode(sd, i, y, &pr);
  if (c < 0) return -1;
  st->face  = sd->fcid[12 * c];
  st->xi[0] = pr.xi[0];
  st->xi[1] = pr.xi[1];
  st->gap   = pr.g;
  if (pr.g > 0 && !(sd->lam[3 * i] - law.KN * pr.g > 0)) return c; /* open (held by no multiplier) */
  if (Kx && Project(sd, c, y, pr.xi, 1, &pr)) {
    *status_err = 1;
    return -1;
  }
  tTn[0] = sd->lam[3 * i + 1];
  tTn[1] = sd->lam[3 * i + 2];
  {
    const double *seed = sd->seed + 3 * i;
    double        chord[3];
    if (!sd->has_seed[i]) {
      NTSChord(&pr, (const double(*)[3])(sd->fcx + 12 * c), chord);
      seed = chord;
    }
    NTSSlip(&pr, y, cc->y, (const double(*)[3])(sd->fcx + 12 * c), (const double(*)[3])(sd->fcx0 + 12 * c), ds, Kx ? dds : NULL);
    st->status = ContactNodeEvalAug(&law, sd->lam[3 * i], pr.g, pr.n, NULL, seed, tTn, ds, Rs, Kx ? K0 : NULL, st->t1, &st->tN, st->tT);
    if (Kx) (void)ContactNodeEvalAug(&law, sd->lam[3 * i], pr.g, pr.n, I3, seed, tTn, ds, R1, K1, t1b, &tNb, tTb);
  }
  for (int a = 0; a < 4; a++) N[a] = pr.N[a];
  st->has_frame = PETSC_TRUE;
  for (int k = 0; k < 3; k++) {
    st->f[k]  = -Rs[k];
    st->fT[k] = st->f[k] - st->tN * pr.n[k];
  }
  {
    const double dsn = ds[0] * pr.n[0] + ds[1] * pr.n[1] + ds[2] * pr.n[2];
    double       dt2 = 0;
    for (int k = 0; k < 3; k++) dt2 += (ds[k] - dsn * pr.n[k]) * (ds[k] - dsn * pr.n[k]);
    st->slip = cc->slip + PetscSqrtReal(dt2);
  }
  if (Kx) {
    double Pg[3], Pn[9], Pds[9], dRs[45];
    for (int r = 0; r < 3; r++) {
      Pg[r] = K0[3 * r] * pr.n[0] + K0[3 * r + 1] * pr.n[1] + K0[3 * r + 2] * pr.n[2];
      for (int q = 0; q < 3; q++) Pn[3 * r + q] = K1[3 * r + q] - K0[3 * r + q];
    }
    for (int r = 0; r < 3; r++)
      for (int q = 0; q < 3; q++) Pds[3 * r + q] = K0[3 * r + q] - Pg[r] * pr.n[q];
    for (int r = 0; r < 3; r++)
      for (int j = 0; j < 15; j++) {
        double v = Pg[r] * pr.dg[j];
        for (int q = 0; q < 3; q++) v += Pn[3 * r + q] * pr.dn[15 * q + j] + Pds[3 * r + q] * dds[15 * q + j];
        dRs[15 * r + j] = v;
      }
    for (int r = 0; r < 3; r++)
      for (int j = 0; j < 15; j++) Kx[15 * r + j] = dRs[15 * r + j];
    for (int a = 0; a < 4; a++)
      for (int r = 0; r < 3; r++)
        for (int j = 0; j < 15; j++) {
          const double dNa = pr.dN[a][0] * pr.dxi[j] + pr.dN[a][1] * pr.dxi[15 + j];
          Kx[15 * (3 + 3 * a + r) + j] = -pr.N[a] * dRs[15 * r + j] - Rs[r] * dNa;
        }
  }
  return c;
}

PetscErrorCode ContactPairsAssemble(ContactPairs p, const PetscScalar *u, PetscScalar *f, Mat J, PetscInt *nfail)
{
  PetscInt nerr = 0;

  PetscFunctionBeginUser;
  if (!p || !p->np) PetscFunctionReturn(0);
  PetscCall(PetscLogEventBegin(p->ev_pair, 0, 0, 0, 0));
  for (PetscInt s = 0; s < p->nside; s++) {
    PairSide *sd = &p->side[s];
    PetscCall(SideRefresh(p, sd, u));
    PetscCall(PetscArrayzero(sd->fcf, 12 * sd->nfc));
    for (PetscInt i = 0; i < sd->ns; i++) {
      double   y[3], Rs[3], N[4] = {0, 0, 0, 0}, Kx[225];
      PetscInt c, err;
      SlavePosition(p->mesh, sd->sv[i], u, y);
      c = NodeEval(p, sd, i, y, Rs, N, J ? Kx : NULL, &err);
      nerr += err;
      if (c < 0 || sd->st_t[i].status == CONTACT_OPEN) continue;
      if (f) {
        const PetscInt o = p->mesh->vloff[sd->sv[i]];
        for (int k = 0; k < 3; k++) f[o + k] += Rs[k];
        for (int a = 0; a < 4; a++)
          for (int k = 0; k < 3; k++) sd->fcf[12 * c + 3 * a + k] -= N[a] * Rs[k];
      }
      if (J) {
        PetscInt idx[15];
        for (int k = 0; k < 3; k++) idx[k] = sd->sg[3 * i + k];
        for (int k = 0; k < 12; k++) idx[3 + k] = sd->fcg[12 * c + k];
        PetscCall(MatSetValues(J, 15, idx, 15, idx, Kx, ADD_VALUES));
      }
    }
    if (f) { /* the corners' forces to the faces' owners, into their local residual */
      PetscCall(PetscArrayzero(sd->fof, 12 * sd->nfo));
      PetscCall(PetscSFReduceBegin(sd->sf, MPIU_REAL, sd->fcf, sd->fof, MPI_SUM));
      PetscCall(PetscSFReduceEnd(sd->sf, MPIU_REAL, sd->fcf, sd->fof, MPI_SUM));
      for (PetscInt fo = 0; fo < sd->nfo; fo++)
        for (int a = 0; a < 4; a++) {
          const PetscInt o = p->mesh->vloff[sd->fov[4 * fo + a]];
          for (int k = 0; k < 3; k++) f[o + k] += sd->fof[12 * fo + 3 * a + k];
        }
    }
  }
  *nfail += nerr; /* (a projection that did not converge at the Jacobian: reported as a failed evaluation) */
  PetscCall(PetscLogEventEnd(p->ev_pair, 0, 0, 0, 0));
  PetscFunctionReturn(0);
}

PetscErrorCode ContactPairsCommit(ContactPairs p)
{
  PetscFunctionBeginUser;
  if (!p) PetscFunctionReturn(0);
  for (PetscInt s = 0; s < p->nside; s++) {
    PairSide *sd = &p->side[s];
    PetscCall(PetscArraycpy(sd->st_c, sd->st_t, sd->ns));
    PetscCall(PetscArraycpy(sd->fox0, sd->fox, 12 * sd->nfo));
    PetscCall(PetscArraycpy(sd->fofc, sd->fof, 12 * sd->nfo));
  }
  PetscFunctionReturn(0);
}

/* The node fields: the slave nodes' own states; the master nodes' from the forces the slave nodes
   exert on their faces (committed), summed per vertex over the faces and the ranks, with the
   vertex's normal the area-weighted mean of its master faces' (the forces pressing on the master
   surface: normal force -F.n, tangential F - (F.n) n). Collective. */
PetscErrorCode ContactPairsGetNodeFields(ContactPairs p, PetscReal *gap, PetscReal *fn, PetscReal *ft, PetscReal *status, PetscReal *slip)
{
  const Mesh  *m = p ? p->mesh : NULL;
  Vec          vf, vn;
  PetscSection ls;
  PetscScalar *af, *an;

  PetscFunctionBeginUser;
  if (!p || !p->np) PetscFunctionReturn(0);
  for (PetscInt s = 0; s < p->nside; s++) {
    PairSide *sd = &p->side[s];
    for (PetscInt i = 0; i < sd->ns; i++) {
      const PairState *st = &sd->st_c[i];
      const PetscInt   r  = m->vrow[sd->sv[i]];
      if (r < 0) continue;
      if (st->face >= 0 && gap) gap[r] = st->gap;
      if (fn) fn[r] += st->tN;
      for (int k = 0; ft && k < 3; k++) ft[3 * r + k] += st->fT[k];
      /* as the tools' (0 open or touching without force, 1 stick, 2 slip, 3 pressed without friction) */
      if (status && st->status != CONTACT_OPEN && st->tN > 0) status[r] = p->spec[sd->spec].mu > 0 ? st->status : 3;
      if (slip) slip[r] += st->slip;
    }
  }
  /* the master side: per vertex the force and the normal (area-weighted), summed over the faces
     and the ranks in two local vectors of the unconstrained section */
  PetscCall(DMGetLocalSection(m->dmr, &ls));
  PetscCall(DMGetLocalVector(m->dmr, &vf));
  PetscCall(DMGetLocalVector(m->dmr, &vn));
  PetscCall(VecZeroEntries(vf));
  PetscCall(VecZeroEntries(vn));
  PetscCall(VecGetArray(vf, &af));
  PetscCall(VecGetArray(vn, &an));
  for (PetscInt s = 0; s < p->nside; s++) {
    const PairSide *sd = &p->side[s];
    for (PetscInt f = 0; f < sd->nfo; f++) {
      double nr[3];
      FaceAreaNormal(sd->fox0 + 12 * f, nr);
      for (int c = 0; c < 4; c++) {
        PetscInt off;
        PetscCall(PetscSectionGetOffset(ls, m->vstart + sd->fov[4 * f + c], &off));
        for (int k = 0; k < 3; k++) {
          af[off + k] -= sd->fofc[12 * f + 3 * c + k];
          an[off + k] += nr[k];
        }
      }
    }
  }
  PetscCall(VecRestoreArray(vf, &af));
  PetscCall(VecRestoreArray(vn, &an));
  PetscCall(VertexSum(m, vf));
  PetscCall(VertexSum(m, vn));
  PetscCall(VecGetArray(vf, &af));
  PetscCall(VecGetArray(vn, &an));
  for (PetscInt v = 0; v < m->nv; v++) {
    PetscInt  off, r = m->vrow[v];
    PetscReal nr[3], nn = 0, F[3], Fn = 0;
    if (r < 0) continue;
    PetscCall(PetscSectionGetOffset(ls, m->vstart + v, &off));
    for (int k = 0; k < 3; k++) {
      nr[k] = PetscRealPart(an[off + k]);
      nn += nr[k] * nr[k];
      F[k] = PetscRealPart(af[off + k]);
    }
    if (!(nn > 0)) continue; /* not a master node */
    nn = PetscSqrtReal(nn);
    for (int k = 0; k < 3; k++) {
      nr[k] /= nn;
      Fn += F[k] * nr[k];
    }
    if (fn) fn[r] += -Fn;
    for (int k = 0; ft && k < 3; k++) ft[3 * r + k] += F[k] - Fn * nr[k];
    if (status && -Fn > 0 && !(status[r] > 0)) status[r] = 3;
  }
  PetscCall(VecRestoreArray(vf, &af));
  PetscCall(VecRestoreArray(vn, &an));
  PetscCall(DMRestoreLocalVector(m->dmr, &vf));
  PetscCall(DMRestoreLocalVector(m->dmr, &vn));
  PetscFunctionReturn(0);
}

PetscErrorCode ContactPairsGetResult(ContactPairs p, PetscInt k, ContactPairResult *r)
{
  PetscReal v[8] = {0, 0, 0, 0, 0, 0, 0, 0};
  PetscInt  n[3] = {0, 0, 0};

  PetscFunctionBeginUser;
  PetscCall(PetscMemzero(r, sizeof(*r)));
  r->name = p->spec[k].name;
  for (PetscInt s = 0; s < p->nside; s++) {
    PairSide *sd = &p->side[s];
    if (sd->spec != k) continue;
    for (PetscInt i = 0; i < sd->ns; i++) {
      const PairState *st = &sd->st_c[i];
      if (st->status == CONTACT_OPEN) continue;
      /* the first pass's slaves receive the force; the second pass's act on the first's slave set */
      const PetscReal sg = strcmp(sd->sset, p->spec[k].slave) ? -1 : 1;
      for (int d = 0; d < 3; d++) v[d] += sg * st->f[d];
      v[3] += st->tN;
      v[4] += PetscSqrtReal(st->fT[0] * st->fT[0] + st->fT[1] * st->fT[1] + st->fT[2] * st->fT[2]);
      v[5] = PetscMax(v[5], -st->gap);
      n[0]++;
      n[1] += st->status == CONTACT_STICK;
      n[2] += st->status == CONTACT_SLIP;
    }
  }
  PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, v, 5, MPIU_REAL, MPIU_SUM, p->comm));
  PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, &v[5], 1, MPIU_REAL, MPIU_MAX, p->comm));
  PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, n, 3, MPIU_INT, MPI_SUM, p->comm));
  for (int d = 0; d < 3; d++) r->f[d] = v[d];
  r->fn      = v[3];
  r->ft      = v[4];
  r->max_pen = PetscMax(v[5], 0);
  r->active  = n[0];
  r->stick   = n[1];
  r->slip    = n[2];
  PetscFunctionReturn(0);
}

PetscErrorCode ContactPairsRecordActive(ContactPairs p)
{
  PetscFunctionBeginUser;
  if (!p) PetscFunctionReturn(0);
  for (PetscInt s = 0; s < p->nside; s++) {
    PairSide *sd = &p->side[s];
    for (PetscInt i = 0; i < sd->ns; i++) sd->active_prev[i] = sd->st_t[i].status != CONTACT_OPEN;
  }
  PetscFunctionReturn(0);
}

PetscErrorCode ContactPairsChanges(ContactPairs p, PetscInt *nchange)
{
  PetscFunctionBeginUser;
  *nchange = 0;
  if (!p) PetscFunctionReturn(0);
  for (PetscInt s = 0; s < p->nside; s++) {
    PairSide *sd = &p->side[s];
    for (PetscInt i = 0; i < sd->ns; i++) *nchange += (sd->active_prev[i] != (sd->st_t[i].status != CONTACT_OPEN));
  }
  PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, nchange, 1, MPIU_INT, MPI_SUM, p->comm));
  PetscFunctionReturn(0);
}

/* checkpoint rows: per pass of a pair PAIR_CKPT doubles per owned vertex (zero where the vertex is
   not the pass's slave node): 1, status, face, xi (2), tT (2), t1 (3), has_frame, y (3), gap,
   tN, f (3), fT (3), slip, the pass's penalties' factor (the augmentation's growth) */
#define PAIR_CKPT 24

PetscInt ContactPairsCheckpointWidth(ContactPairs p) { return p ? PAIR_CKPT * p->nside : 0; }

PetscErrorCode ContactPairsCheckpointPack(ContactPairs p, PetscReal *rows)
{
  const PetscInt w = ContactPairsCheckpointWidth(p);

  PetscFunctionBeginUser;
  PetscCall(PetscArrayzero(rows, w * p->mesh->nvo));
  for (PetscInt s = 0; s < p->nside; s++) {
    const PairSide *sd = &p->side[s];
    for (PetscInt i = 0; i < sd->ns; i++) {
      const PairState *t = &sd->st_c[i];
      const PetscReal  v[PAIR_CKPT] = {1, (PetscReal)t->status, (PetscReal)t->face, t->xi[0], t->xi[1], t->tT[0], t->tT[1], t->t1[0], t->t1[1], t->t1[2], (PetscReal)t->has_frame, t->y[0], t->y[1], t->y[2], t->gap, t->tN, t->f[0], t->f[1], t->f[2], t->fT[0], t->fT[1], t->fT[2], t->slip, sd->kscale};
      PetscCall(PetscArraycpy(rows + w * p->mesh->vrow[sd->sv[i]] + PAIR_CKPT * s, v, PAIR_CKPT));
    }
  }
  PetscFunctionReturn(0);
}

PetscErrorCode ContactPairsCheckpointUnpack(ContactPairs p, const PetscReal *rows, const PetscScalar *uc, const char *path)
{
  const PetscInt w   = ContactPairsCheckpointWidth(p);
  PetscInt       bad = PETSC_MAX_INT;

  PetscFunctionBeginUser;
  for (PetscInt s = 0; s < p->nside; s++) {
    PairSide *sd = &p->side[s];
    PetscReal kc = 0;
    for (PetscInt i = 0; i < sd->ns; i++) {
      const PetscReal *d = rows + w * p->mesh->vrow[sd->sv[i]] + PAIR_CKPT * s;
      PairState       *t = &sd->st_c[i];
      if (d[0] != 1) {
        bad = PetscMin(bad, p->mesh->node_id[sd->sv[i]]);
        continue;
      }
      t->status    = (PetscInt)d[1];
      t->face      = (PetscInt)d[2];
      t->xi[0]     = d[3];
      t->xi[1]     = d[4];
      t->tT[0]     = d[5];
      t->tT[1]     = d[6];
      t->has_frame = d[10] != 0 ? PETSC_TRUE : PETSC_FALSE;
      for (int k = 0; k < 3; k++) {
        t->t1[k] = d[7 + k];
        t->y[k]  = d[11 + k];
        t->f[k]  = d[16 + k];
        t->fT[k] = d[19 + k];
      }
      t->gap  = d[14];
      t->tN   = d[15];
      t->slip = d[22];
      kc      = PetscMax(kc, d[23]);
    }
    /* the penalties' factor (the same in all the pass's rows; a rank without its slave nodes takes it from the others) */
    PetscCall(MPIU_Allreduce(MPI_IN_PLACE, &kc, 1, MPIU_REAL, MPIU_MAX, p->comm));
    sd->kscale = kc > 0 ? kc : 1;
    PetscCall(PetscArraycpy(sd->st_t, sd->st_c, sd->ns));
    /* the master faces' committed positions: the committed displacements */
    for (PetscInt f = 0; f < sd->nfo; f++) FaceCorners(p->mesh, sd->fov + 4 * f, uc, sd->fox0 + 12 * f);
    PetscCall(PetscArraycpy(sd->fox, sd->fox0, 12 * sd->nfo));
    PetscCall(PetscSFDestroy(&sd->sf)); /* the candidates are found again at the next step */
  }
  PetscCall(MPIU_Allreduce(MPI_IN_PLACE, &bad, 1, MPIU_INT, MPI_MIN, p->comm));
  PetscCheck(bad == PETSC_MAX_INT, p->comm, PETSC_ERR_FILE_UNEXPECTED, "-restart %s: node id %" PetscInt_FMT " is a slave node of a contact pair here but not in the checkpoint", path, bad);
  PetscFunctionReturn(0);
}

/* the pairs need the stepper's loop after a converged Newton solve: augmented, or smoothed (the
   normals held in the last iteration checked against the solution's) */
PetscBool ContactPairsAugmented(ContactPairs p)
{
  if (!p) return PETSC_FALSE;
  for (PetscInt k = 0; k < p->np; k++)
    if (p->spec[k].aug || p->spec[k].smooth) return PETSC_TRUE;
  return PETSC_FALSE;
}

/* One Uzawa update of the augmented pairs' multipliers from the trial state of the last evaluation
   (the converged Newton solution at the current multipliers): lN <- <lN - K_N g> (= t_N), lT <- the
   return of lT + K_T dg_T (= t_T), then lN >= 0, |lT| <= mu lN. Converged when, on every augmented
   pair, the largest penetration of a pressed node and the largest stick slip of the step (|change
   of lT| / K_T at a sticking node) are below the pair's tolerance and no multiplier changed by more
   than its multiplier tolerance times the largest. Collective. */
PetscErrorCode ContactPairsAugment(ContactPairs p, PetscBool *converged, PetscReal *maxpen, PetscReal *dlambda)
{
  PetscReal *loc;
  const PetscInt nv = 4 * p->nside;

  PetscFunctionBeginUser;
  *converged = PETSC_TRUE;
  *maxpen = *dlambda = 0;
  /* the smoothed sides: the corners' normals at the solution (the positions of its evaluation)
     against the ones held in its last Newton iteration */
  for (PetscInt s = 0; s < p->nside; s++) {
    PairSide  *sd = &p->side[s];
    PetscReal *old, dn = 0;
    if (!sd->smooth) continue;
    PetscCall(PetscMalloc1(12 * sd->nfo + 1, &old));
    PetscCall(PetscArraycpy(old, sd->fonb, 12 * sd->nfo));
    PetscCall(SideNormals(p, sd));
    for (PetscInt k = 0; k < 12 * sd->nfo; k++) dn = PetscMax(dn, PetscAbsReal(sd->fonb[k] - old[k]));
    PetscCall(PetscFree(old));
    PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, &dn, 1, MPIU_REAL, MPIU_MAX, p->comm));
    if (dn > p->spec[sd->spec].smooth_tol) *converged = PETSC_FALSE;
  }
  PetscCall(PetscCalloc1(nv + 1, &loc)); /* per side: penetration, stick slip, change, largest multiplier */
  for (PetscInt s = 0; s < p->nside; s++) {
    PairSide       *sd = &p->side[s];
    const PairSpec *sp = &p->spec[sd->spec];
    PetscReal      *v  = loc + 4 * s;
    if (!sp->aug) continue;
    for (PetscInt i = 0; i < sd->ns; i++) {
      const PairState *st = &sd->st_t[i];
      const PetscBool  in = st->status != CONTACT_OPEN ? PETSC_TRUE : PETSC_FALSE;
      PetscReal       *l  = sd->lam + 3 * i, r[3], dT;
      r[0] = (in ? st->tN : 0) - l[0];
      r[1] = (in ? st->tT[0] : 0) - l[1];
      r[2] = (in ? st->tT[1] : 0) - l[2];
      dT   = PetscSqrtReal(r[1] * r[1] + r[2] * r[2]);
      if (in && st->tN > 0) v[0] = PetscMax(v[0], -st->gap);
      if (in && st->status == CONTACT_STICK && sp->mu > 0) v[1] = PetscMax(v[1], dT / (sd->kscale * sd->kt[i]));
      v[2] = PetscMax(v[2], PetscSqrtReal(r[0] * r[0] + dT * dT));
      v[3] = PetscMax(v[3], PetscSqrtReal(st->tN * st->tN + st->tT[0] * st->tT[0] + st->tT[1] * st->tT[1]) * in);
      for (int k = 0; k < 3; k++) l[k] += r[k];
      l[0] = PetscMax(l[0], 0);
      {
        const PetscReal nT = PetscSqrtReal(l[1] * l[1] + l[2] * l[2]), cap = sp->mu * l[0];
        if (nT > cap) {
          l[1] = nT > 0 ? l[1] * cap / nT : 0;
          l[2] = nT > 0 ? l[2] * cap / nT : 0;
        }
      }
    }
  }
  PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, loc, (PetscMPIInt)nv, MPIU_REAL, MPIU_MAX, p->comm));
  for (PetscInt s = 0; s < p->nside; s++) {
    const PairSide *sd = &p->side[s];
    const PairSpec *sp = &p->spec[sd->spec];
    const PetscReal *v = loc + 4 * s;
    if (!sp->aug) continue;
    PairSide *sw = &p->side[s];
    if (!(v[0] <= sd->tol && v[1] <= sd->tol && v[2] <= sp->aug_mtol * v[3])) *converged = PETSC_FALSE;
    /* Uzawa's rate is the penalty's stiffness against the bodies': an update that did not reduce
       the penetration by 4 (and left it above the tolerance) makes the pair's penalties 8 times
       stiffer, up to 1e3 times the automatic ones, for the rest of the step and the next steps (the
       multipliers carry the force, so the converged state does not depend on the factor) */
    if (sw->pen_prev >= 0 && v[0] > sd->tol && v[0] > 0.25 * sw->pen_prev && sw->kscale * 8 <= 1e3 * (1 + 1e-12)) sw->kscale *= 8;
    sw->pen_prev = v[0];
    *maxpen  = PetscMax(*maxpen, v[0]);
    *dlambda = PetscMax(*dlambda, v[2]);
  }
  PetscCall(PetscFree(loc));
  PetscFunctionReturn(0);
}

PetscErrorCode ContactPairsAugmentTolerance(ContactPairs p, PetscReal *tol)
{
  PetscFunctionBeginUser;
  *tol = 0;
  for (PetscInt s = 0; s < p->nside; s++)
    if (p->spec[p->side[s].spec].aug) *tol = PetscMax(*tol, p->side[s].tol);
  PetscFunctionReturn(0);
}
