/* The contact object (contact.h): the slave nodes (owned vertices of the contact sets), pairing
   with the rigid tools (replicated on every rank, bounding-box prefilter), the per-node committed
   and trial states, the seeds of the frame recurrence, the assembly of the nodal forces and their
   tangents, the per-tool results, and the node rows of the checkpoint. Each rank handles only the
   slave vertices it owns, so no contact force is counted twice. */
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include "contact.h"
#include "contact_pair.h"
#include "contact_law.h"
#include "tool.h"
#include "util.h"
#include "options.h"

#define NREL 8 /* doubles per node of a release by nodal forces: force (3), tangential part (3), t0, t1 */

/* the share of its nodal forces that a tool released by them still exerts at time lambda: 1 at the
   release's start t0, linearly to 0 at its end t1 (w: a node's NREL doubles) */
static PetscReal NodalReleaseShare(const PetscReal *w, PetscReal lambda)
{
  const PetscReal s = (w[7] - lambda) / (w[7] - w[6]);
  return s > 1 ? 1 : (s > 0 ? s : 0);
}

/* The last pairing of a slave node: the tool and projection found for the position y at the load
   lambda. Pairing the node again at the same y and lambda (bit for bit) returns it unchanged: the
   residual, the Jacobian and the frame update of a Newton iteration see one node position. */
typedef struct {
  PetscReal  y[3], lambda;
  PetscInt   gen;  /* the generation of the tool unknowns it was found at */
  PetscInt   tool; /* -1: no tool within the search distance; -2: empty */
  Projection pr;
} PairMemo;

/* A tool's contact settings (-tool_<name>_contact_set, _penalty_normal, _penalty_tangential,
   _friction, _gap_smoothing; the global -contact_* ones by default) and its drive: per direction, by the
   prescribed displacement (ToolShift plus a held offset) or by a force (target fscale times the
   amplitude: the curve famp, or the ramp a(t) = t when famp is empty), the displacement then an
   unknown of the system (block >= 0: its 3 unknowns, the current values d). */
typedef struct {
  char       set[8][ATRITO_NAME_LEN];
  PetscInt   nset;      /* 0: the global -contact_set                                          */
  ContactLaw law;
  PetscBool  kauto, ktauto;
  PetscBool  own;       /* a setting of its own was given                                      */
  ToolDrive  drive[3];
  PetscReal  fscale[3];
  LoadCurve  famp[3];
  PetscReal  hold[3];   /* displacement drive: prescribed = ToolShift + hold                   */
  PetscBool  reserve;   /* unknowns asked for before the setup                                  */
  PetscInt   block;     /* index of its unknowns (3 from tdof0 + 3 block), -1: none            */
  PetscReal  d[3];      /* the current values of its unknowns                                  */
  PetscReal  dc[3];     /* its committed displacement (tools with unknowns)                    */
  PetscReal  path_c;    /* path length of the committed displacements (tools with unknowns)    */
  PetscReal  kreg;      /* regularising stiffness: the sum of the penalties K_N of its nodes    */
  PetscReal  fnode;     /* driven by force, automatic penalty: its largest force over the nodes under it (0: none) */
  PetscReal  nunder;    /* those nodes: projected on it at the start, at most an element size from it */
  PetscBool  release;   /* force-controlled release (ContactReleaseTool): in x, y, z the target  */
  PetscReal  rel_t[2];  /* goes linearly from rel_f, the force at rel_t[0], to 0 at rel_t[1]      */
  PetscReal  rel_f[3];
  PetscBool  moving;    /* displacement-driven and moved by the step being solved (ContactSeed)  */
  PetscBool  forced;    /* force-driven in some component (ContactSeed)                         */
  double     step_dx[3];/* that motion: its translation over the step (ContactSeed)              */
} ToolContact;

typedef struct {
  PetscInt  status;     /* CONTACT_OPEN / STICK / SLIP                                   */
  PetscInt  tool, patch;/* pairing: tool and patch of the closest point, -1 when none      */
  PetscReal xi, eta;    /* its parameters                                                 */
  PetscReal tT[2];      /* tangential pressure, components on t1, t2                      */
  PetscReal t1[3];      /* the local frame's t1 (eqs 28-30)                               */
  PetscBool has_frame;
  PetscReal y[3];       /* node position                                                   */
  PetscReal gap, tN;    /* gap and normal pressure                                         */
  PetscReal f[3];       /* contact force on the node                                       */
  PetscReal fT[3];      /* its tangential (friction) part                                  */
  PetscReal slip;       /* accumulated tangential slip                                     */
  PetscReal lN, lT[2];  /* multipliers the next step starts from: normal (0 without
                           -contact_augmented) and tangential, components on t1, t2            */
} ContactState;

struct _p_Contact {
  MPI_Comm    comm;
  PetscMPIInt rank;
  const Mesh *mesh;
  /* options */
  char       set[8][ATRITO_NAME_LEN]; /* slave nodes: the union of these sets                */
  PetscInt   nset;
  ContactLaw law;
  PetscBool  per_area;     /* K_N, K_T per unit area, times each node's tributary area        */
  PetscBool  fd;           /* per-node finite-difference tangent instead of the analytic one  */
  PetscBool  frame_rotate; /* -contact_frame_carry rotation: eq 30's seed carried by the rotation
                              between the normals (ContactFrameCarry); else the paper's eq 30 */
  PetscReal  search_opt;   /* pairing: skip a tool whose box is farther than this (<= 0: auto) */
  PetscReal  edge_tol;     /* -contact_edge_tolerance (< 0: auto, 1e-3 of each tool's box diagonal) */
  PetscReal  symmetry;     /* multiplicity of the model (0: from the mesh)                    */
  PetscReal  E_body;       /* the body's Young's modulus (ContactSetYoungModulus; 0: unknown)   */
  PetscReal *Ecell;        /* per local cell its material's modulus (several bodies), else NULL  */
  PetscBool  kauto, ktauto;/* K_N (K_T) per node from the elements under it (auto)              */
  PetscReal  kfactor, kratio;
  PetscBool  aug;          /* augmented Lagrangian (Uzawa updates between Newton solves)      */
  PetscInt   keep;         /* ContactKeepCommitted: the pressed nodes of the committed state stay
                              closed (bilateral) whatever their gap: 0 none, 1 on frictionless
                              tools, 2 on every tool                                             */
  PetscReal  aug_tol, aug_tol_rel, aug_mtol;
  PetscInt   aug_max;
  /* tools, owned slave vertices and their states */
  PetscInt      ntools;
  Tool         *tools;
  PetscInt      ns;            /* owned slave vertices                                       */
  PetscInt     *slave;         /* their local vertex indices                                 */
  PetscInt     *sgdof;         /* ns*3 global dofs, -1 where constrained                    */
  ContactState *cst_c, *cst_t; /* committed and trial                                        */
  PetscReal    *seed;          /* ns*3 frame seed of the current Newton iteration (eqs 28-30) */
  PetscReal    *seedn;         /* ns*3 the normal whose tangent plane holds the seed (0: none)  */
  PetscReal    *yseed;         /* ns*3 the node's position when the seed was last set: the anchor
                                  of a held node's tangential spring (ContactKeepCommitted 2, 3) */
  PetscBool    *has_seed;
  PetscReal     lambda_c;      /* load parameter of the committed state                      */
  PetscReal     search;        /* pairing distance                                           */
  PetscBool    *active_prev;   /* ns: in contact at the start of the current Newton iteration */
  PetscReal    *tN_prev;       /* ns: and its normal force then                              */
  PetscInt     *tool_prev;     /* ns: and its tool then (-1: none)                          */
  PetscInt     *status_prev;   /* ns: and its status then                                   */
  PairMemo     *pmemo;         /* ns: the last pairing of each node                          */
  PetscReal    *kn, *kt;       /* ns: per-node penalties (automatic penalty), else NULL      */
  PetscReal     hmin;          /* smallest element size normal to the contact faces (0: unknown) */
  PetscBool     reg_auto;      /* -contact_regularization auto: reg_rel times the node's element size (automatic penalty) */
  PetscReal     reg_rel;
  PetscReal     kforce_pen;    /* -contact_penalty_force_penetration: a force-driven tool's nodes at its force's share */
  PetscReal    *hn;            /* ns: the element size normal to the contact faces at each node (NULL: unknown) */
  PetscReal     tol;           /* the penetration tolerance of the augmentation              */
  PetscReal    *lam;           /* ns*3: multipliers of the current Newton solve (lN, lT1, lT2) */
  PetscInt     *lam_tool;      /* ns: the tool they belong to, -1: none                      */
  PetscInt      naug;          /* multiplier updates in the current step                     */
  PetscReal     aug_pen, aug_dlam; /* largest penetration and multiplier change of the last  */
  PetscReal    *lam_r;         /* ns*3: the previous Uzawa increment (Aitken's relaxation)    */
  PetscReal     omega[2];      /* the previous relaxation factors (normal, tangential)        */
  PetscReal     kscale;        /* the penalties' factor in the current step (augmentation's growth) */
  PetscReal     aug_grow, aug_grow_max; /* -contact_augmented_growth, _growth_max               */
  PetscBool     aug_keep;      /* -contact_augmented_growth_keep: the grown factor carries over  */
  PetscReal     kscale_c;      /* the factor committed with the last step (the next one starts from it) */
  PetscReal     aug_inexact;   /* -contact_augmented_inexact: relative residual at which a solve is followed by an update (0: exact solves) */
  PetscBool     aug_monitor;   /* -contact_augmented_monitor: one line per update                */
  PetscBool     aug_soften;    /* -contact_augmented_soften: a failed Newton solve retries the step at softer penalties */
  /* per-tool settings and drives, the tool unknowns */
  ToolContact  *tc;            /* ntools                                                      */
  char         *tmask;         /* ns*ntools: node i may pair with tool t (it is in the tool's sets) */
  char        (*uset)[ATRITO_NAME_LEN]; /* the union of the sets of all tools                 */
  PetscInt      nuset;
  PetscBool     kanyauto;      /* some tool has the automatic penalty                         */
  PetscInt      nb;            /* tools with unknowns                                         */
  PetscInt      tdof0;         /* global index of the first tool unknown                      */
  PetscBool     towner;        /* this rank owns the tool unknowns                            */
  PetscInt      gen;           /* changes whenever the values of the tool unknowns change     */
  /* release by nodal forces (ContactReleaseToolNodes): per owned slave node the contact force it
     carried from its tool when the release began (NREL doubles: force (3), its tangential part (3),
     the release's start and end times), the tool (-1: none) */
  PetscReal    *nrel;
  PetscInt     *nrel_tool;
  /* the linearisation of the last Jacobian (ContactLinearRelease, ContactLinearBlock): per owned
     slave node its residual (3), tangent (9) and normal (3), and whether it was in contact there
     by the law (not held by ContactKeepCommitted, its evaluation did not fail) */
  PetscReal    *lin;
  char         *lin_ok;
  PetscLogEvent ev_contact, ev_pairing;
  ContactPairs  pairs;         /* contact between deformable bodies (contact_pair.h)            */
};
#define NLIN 15

/* The tool's displacement now: along a force-driven direction its unknown, along the others the
   prescribed displacement (plus the held offset). A tool without unknowns: ToolShift. */
static void CurShift(const struct _p_Contact *contact, PetscInt t, PetscReal lambda, double sh[3])
{
  const ToolContact *tc = &contact->tc[t];
  ToolShift(&contact->tools[t], lambda, sh);
  if (tc->block < 0) return;
  for (int k = 0; k < 3; k++) sh[k] = tc->drive[k] == TOOL_DRIVE_FORCE ? tc->d[k] : sh[k] + tc->hold[k];
}

/* the tool's committed displacement */
static void CommittedShift(const struct _p_Contact *contact, PetscInt t, double sh[3])
{
  const ToolContact *tc = &contact->tc[t];
  if (tc->block < 0) ToolShift(&contact->tools[t], contact->lambda_c, sh);
  else
    for (int k = 0; k < 3; k++) sh[k] = tc->dc[k];
}

/* the target force along direction k at the process time t */
static PetscReal ToolTarget(const ToolContact *tc, int k, PetscReal t) { return tc->fscale[k] * (tc->famp[k].n ? LoadCurveEval(&tc->famp[k], t) : t); }

/* The tool whose closest point to y has the smallest gap (bounding boxes first). Returns the tool
   index or -1 when no tool is within the search distance. cs: the node's committed state (NULL:
   none), whose pairing is the hint of its tool's projection (the same result, found faster). */
static PetscInt Pair(const struct _p_Contact *contact, const char *mask, const double y[3], PetscReal lambda, const ContactState *cs, Projection *best)
{
  const Projection hint = {.patch = cs ? (int)cs->patch : -1, .xi = cs ? cs->xi : 0.0, .eta = cs ? cs->eta : 0.0};
  PetscInt tbest = -1;
  for (PetscInt t = 0; t < contact->ntools; t++) {
    const Tool *tl = &contact->tools[t];
    double      sh[3], d2 = 0;
    Projection  pr;
    if (!mask[t]) continue; /* the node is in none of the tool's sets */
    CurShift(contact, t, lambda, sh);
    for (int k = 0; k < 3; k++) {
      const double lo = tl->bbox[2 * k] + sh[k], hi = tl->bbox[2 * k + 1] + sh[k];
      const double e  = y[k] < lo ? lo - y[k] : (y[k] > hi ? y[k] - hi : 0);
      d2 += e * e;
    }
    if (d2 > contact->search * contact->search) continue;
    if (ToolProjectHint(tl, sh, y, contact->search, cs && cs->tool == t ? &hint : NULL, &pr)) continue; /* the node's committed pairing as the hint */
    if (tbest < 0 || pr.gap < best->gap) {
      *best = pr;
      tbest = t;
    }
  }
  return tbest;
}

/* Pair for slave node i, through its memo (the same y and lambda give the same result) */
static PetscInt PairNode(const struct _p_Contact *contact, PetscInt i, const double y[3], PetscReal lambda, Projection *pr)
{
  PairMemo *m = &contact->pmemo[i];
  if (m->tool != -2 && m->lambda == lambda && m->gen == contact->gen && m->y[0] == y[0] && m->y[1] == y[1] && m->y[2] == y[2]) {
    if (m->tool >= 0) *pr = m->pr;
    return m->tool;
  }
  m->tool = Pair(contact, contact->tmask + i * contact->ntools, y, lambda, &contact->cst_c[i], &m->pr);
  for (int k = 0; k < 3; k++) m->y[k] = y[k];
  m->lambda = lambda;
  m->gen    = contact->gen;
  if (m->tool >= 0) *pr = m->pr;
  return m->tool;
}

/* chord of eq 28: from the projection to the point at (xi + 0.01, eta) of the same patch */
static void Chord(const struct _p_Contact *contact, PetscInt tool, const Projection *pr, double chord[3])
{
  const Patch *p = &contact->tools[tool].patch[pr->patch];
  double       x0[3], x1[3], xu[3], xv[3];
  PatchEval(p, pr->xi, pr->eta, x0, xu, xv, NULL, NULL, NULL);
  PatchEval(p, pr->xi + 0.01, pr->eta, x1, xu, xv, NULL, NULL, NULL);
  for (int k = 0; k < 3; k++) chord[k] = x1[k] - x0[k];
}

static void NodePosition(const struct _p_Contact *contact, PetscInt i, const PetscScalar *u, double y[3])
{
  const PetscInt v = contact->slave[i];
  for (int k = 0; k < 3; k++) y[k] = contact->mesh->X[3 * v + k] + PetscRealPart(u[contact->mesh->vloff[v] + k]);
}

PetscErrorCode ContactCreate(MPI_Comm comm, Contact *c)
{
  PetscFunctionBeginUser;
  PetscCall(PetscNew(c));
  (*c)->comm = comm;
  PetscCallMPI(MPI_Comm_rank(comm, &(*c)->rank));
  PetscCall(PetscLogEventRegister("AtritoContact", DM_CLASSID, &(*c)->ev_contact));
  PetscCall(PetscLogEventRegister("AtritoPairing", DM_CLASSID, &(*c)->ev_pairing));
  PetscCall(ContactPairsCreate(comm, &(*c)->pairs));
  PetscFunctionReturn(0);
}

/* a penalty option's value: a positive number, or auto */
static PetscErrorCode PenaltyValue(MPI_Comm comm, const char *opt, const char *buf, PetscBool *isauto, PetscReal *v)
{
  char *end;

  PetscFunctionBeginUser;
  PetscCall(PetscStrcasecmp(buf, "auto", isauto));
  if (*isauto) PetscFunctionReturn(0);
  *v = strtod(buf, &end);
  PetscCheck(end != buf && *end == 0, comm, PETSC_ERR_USER_INPUT, "%s '%s' is neither a number nor auto", opt, buf);
  PetscFunctionReturn(0);
}

/* the contact settings and the drive of tool t, in its own block (prefix tool_<name>_, title
   "Tool <name> contact"); the global -contact_* values by default. Errors are raised after the
   block is closed. */
static PetscErrorCode ToolContactSetFromOptions(Contact c, PetscInt t)
{
  MPI_Comm     comm = c->comm;
  const Tool  *tl   = &c->tools[t];
  ToolContact *tc   = &c->tc[t];
  const char  *ax   = "xyz";
  char         prefix[PETSC_MAX_PATH_LEN], title[PETSC_MAX_PATH_LEN], kn[64] = "", kt[64] = "", amp[PETSC_MAX_PATH_LEN] = "";
  char        *sets[8];
  PetscInt     nsets = 8;
  PetscBool    sset = PETSC_FALSE, skn = PETSC_FALSE, skt = PETSC_FALSE, smu = PETSC_FALSE, sdl = PETSC_FALSE, sf[3] = {PETSC_FALSE, PETSC_FALSE, PETSC_FALSE}, samp = PETSC_FALSE;
  PetscReal    f[3] = {0, 0, 0};

  PetscFunctionBeginUser;
  tc->law    = c->law;
  tc->kauto  = c->kauto;
  tc->ktauto = c->ktauto;
  tc->block  = -1;
  PetscCall(PetscSNPrintf(prefix, sizeof(prefix), "tool_%s_", tl->name));
  PetscCall(PetscSNPrintf(title, sizeof(title), "Tool %s contact", tl->name));
  PetscOptionsBegin(comm, prefix, title, NULL);
  PetscCall(PetscOptionsStringArray("-contact_set", "Mesh sets of the slave nodes in contact with this tool (their union; default -contact_set)", NULL, sets, &nsets, &sset));
  PetscCall(PetscOptionsString("-penalty_normal", "Normal penalty K_N of this tool's contact, or auto (default -contact_penalty_normal)", NULL, kn, kn, sizeof(kn), &skn));
  PetscCall(PetscOptionsString("-penalty_tangential", "Tangential penalty K_T of this tool's contact, or auto (default -contact_penalty_tangential)", NULL, kt, kt, sizeof(kt), &skt));
  PetscCall(PetscOptionsReal("-friction", "Coulomb friction coefficient of this tool's contact (default -contact_friction)", NULL, tc->law.mu, &tc->law.mu, &smu));
  PetscCall(PetscOptionsReal("-gap_smoothing", "Width (a length) over which this tool's normal contact force is smoothed about gap 0 (default -contact_gap_smoothing)", "doc/contact.md", tc->law.delta, &tc->law.delta, &sdl));
  for (int k = 0; k < 3; k++) {
    char name[16], help[160];
    PetscCall(PetscSNPrintf(name, sizeof(name), "-force_%c", ax[k]));
    PetscCall(PetscSNPrintf(help, sizeof(help), "Drive the tool along %c by force: the total force it exerts on the body along +%c is this value times the amplitude", ax[k], ax[k]));
    PetscCall(PetscOptionsReal(name, help, NULL, f[k], &f[k], &sf[k]));
  }
  PetscCall(PetscOptionsString("-force_amplitude", "Amplitude a(t) of the tool's forces (-tool_<name>_force_x|y|z): a curve t0,a0,t1,a1,... or a two-column file (default: a(t) = t)", NULL, amp, amp, sizeof(amp), &samp));
  PetscOptionsEnd();
  if (sset) {
    for (PetscInt k = 0; k < nsets; k++) {
      PetscCall(PetscStrncpy(tc->set[k], sets[k], sizeof(tc->set[k])));
      PetscCall(PetscFree(sets[k]));
    }
    tc->nset = nsets;
    PetscCheck(nsets > 0, comm, PETSC_ERR_USER_INPUT, "-tool_%s_contact_set names no set", tl->name);
  }
  if (skn) {
    char opt[PETSC_MAX_PATH_LEN];
    PetscCall(PetscSNPrintf(opt, sizeof(opt), "-tool_%s_penalty_normal", tl->name));
    PetscCall(PenaltyValue(comm, opt, kn, &tc->kauto, &tc->law.KN));
    PetscCheck(tc->kauto || (tc->law.KN > 0 && PetscIsNormalReal(tc->law.KN)), comm, PETSC_ERR_USER_INPUT, "%s %g must be positive", opt, (double)tc->law.KN);
    if (!skt) { /* the tangential default follows the tool's normal one, as the global ones do */
      if (tc->kauto) tc->ktauto = PETSC_TRUE;
      else if (c->ktauto) {
        tc->ktauto = PETSC_FALSE;
        tc->law.KT = 5e3;
      }
    }
  }
  if (skt) {
    char opt[PETSC_MAX_PATH_LEN];
    PetscCall(PetscSNPrintf(opt, sizeof(opt), "-tool_%s_penalty_tangential", tl->name));
    PetscCall(PenaltyValue(comm, opt, kt, &tc->ktauto, &tc->law.KT));
    PetscCheck(tc->ktauto || (tc->law.KT > 0 && PetscIsNormalReal(tc->law.KT)), comm, PETSC_ERR_USER_INPUT, "%s %g must be positive", opt, (double)tc->law.KT);
  }
  PetscCheck(!tc->ktauto || tc->kauto, comm, PETSC_ERR_USER_INPUT, "-tool_%s_penalty_tangential auto needs the automatic normal penalty (-tool_%s_penalty_normal auto)", tl->name, tl->name);
  PetscCheck(!(c->per_area && tc->kauto), comm, PETSC_ERR_USER_INPUT, "-tool_%s_penalty_normal auto does not combine with -contact_penalty_per_area", tl->name);
  PetscCheck(tc->law.mu >= 0 && (tc->law.mu == 0 || PetscIsNormalReal(tc->law.mu)), comm, PETSC_ERR_USER_INPUT, "-tool_%s_friction %g must be >= 0", tl->name, (double)tc->law.mu);
  PetscCheck(tc->law.delta >= 0 && !PetscIsInfOrNanReal(tc->law.delta), comm, PETSC_ERR_USER_INPUT, "-tool_%s_gap_smoothing %g must be >= 0", tl->name, (double)tc->law.delta);
  tc->own = (sset || skn || skt || smu || sdl) ? PETSC_TRUE : PETSC_FALSE;
  for (int k = 0; k < 3; k++) {
    PetscBool moves = tl->motion[k] != 0 ? PETSC_TRUE : PETSC_FALSE;
    for (int p = 0; p < tl->npath; p++)
      if (tl->path[4 * p + 1 + k] != 0) moves = PETSC_TRUE;
    if (!sf[k]) continue;
    PetscCheck(PetscIsNormalReal(f[k]) || f[k] == 0, comm, PETSC_ERR_USER_INPUT, "-tool_%s_force_%c %g must be a finite number", tl->name, ax[k], (double)f[k]);
    PetscCheck(!moves, comm, PETSC_ERR_USER_INPUT, "-tool_%s_force_%c: the tool's -tool_%s_motion or -tool_%s_path moves it along %c too; a direction is driven by force or by displacement", tl->name, ax[k], tl->name, tl->name, ax[k]);
    tc->drive[k]  = TOOL_DRIVE_FORCE;
    tc->fscale[k] = f[k];
    tc->reserve   = PETSC_TRUE;
  }
  if (samp) {
    char opt[PETSC_MAX_PATH_LEN];
    PetscCall(PetscSNPrintf(opt, sizeof(opt), "-tool_%s_force_amplitude", tl->name));
    PetscCheck(sf[0] || sf[1] || sf[2], comm, PETSC_ERR_USER_INPUT, "%s: the tool has no -tool_%s_force_x|y|z", opt, tl->name);
    PetscCall(LoadCurveParse(comm, opt, amp, &tc->famp[0]));
    for (int k = 1; k < 3; k++) PetscCall(LoadCurveDuplicate(&tc->famp[0], &tc->famp[k]));
    for (int k = 0; k < 3; k++)
      if (!sf[k]) PetscCall(LoadCurveDestroy(&tc->famp[k]));
  }
  PetscFunctionReturn(0);
}

PetscErrorCode ContactSetToolDrive(Contact c, PetscInt tool, PetscInt dir, ToolDrive mode, const LoadCurve *force)
{
  ToolContact *tc;

  PetscFunctionBeginUser;
  PetscCheck(tool >= 0 && tool < c->ntools, c->comm, PETSC_ERR_ARG_OUTOFRANGE, "ContactSetToolDrive: tool %" PetscInt_FMT " of %" PetscInt_FMT, tool, c->ntools);
  PetscCheck(dir >= 0 && dir < 3, c->comm, PETSC_ERR_ARG_OUTOFRANGE, "ContactSetToolDrive: direction %" PetscInt_FMT " is not 0, 1 or 2", dir);
  tc = &c->tc[tool];
  if (mode == TOOL_DRIVE_FORCE) {
    PetscCheck(force && force->n > 0, c->comm, PETSC_ERR_ARG_WRONG, "ContactSetToolDrive: tool %s driven by force along %c needs a force curve", c->tools[tool].name, "xyz"[dir]);
    PetscCheck(!c->mesh || tc->block >= 0, c->comm, PETSC_ERR_ARG_WRONG, "tool %s: driven by force along %c after the setup, but it has no unknowns (give it a -tool_%s_force_ option or reserve them before the setup)", c->tools[tool].name, "xyz"[dir], c->tools[tool].name);
    PetscCall(LoadCurveDestroy(&tc->famp[dir]));
    PetscCall(LoadCurveDuplicate(force, &tc->famp[dir]));
    tc->fscale[dir] = 1;
    tc->drive[dir]  = TOOL_DRIVE_FORCE;
    tc->reserve     = PETSC_TRUE;
  } else {
    double s[3];
    /* hold the committed position: prescribed = ToolShift + hold equals it at the committed load */
    ToolShift(&c->tools[tool], c->lambda_c, s);
    if (tc->block >= 0) tc->hold[dir] = tc->dc[dir] - s[dir];
    tc->drive[dir] = TOOL_DRIVE_DISPLACEMENT;
  }
  PetscFunctionReturn(0);
}

/* the force curves of a release: from rel_f at rel_t[0] linearly to 0 at rel_t[1], along the
   directions in which the tool carries more than 1e-3 of its force; along the others it holds its
   position (a direction with no force there has only the friction's stiffness, which vanishes
   with the force: driven by force it would leave the tool free at the release's end) */
static PetscErrorCode ReleaseDrive(Contact c, PetscInt tool)
{
  ToolContact    *tc = &c->tc[tool];
  const PetscReal fm = PetscSqrtReal(PetscSqr(tc->rel_f[0]) + PetscSqr(tc->rel_f[1]) + PetscSqr(tc->rel_f[2]));

  PetscFunctionBeginUser;
  for (PetscInt d = 0; d < 3; d++) {
    LoadCurve       cv;
    const PetscReal v[2] = {tc->rel_f[d], 0};
    if (!(PetscAbsReal(tc->rel_f[d]) > 1e-3 * fm)) {
      if (tc->drive[d] == TOOL_DRIVE_FORCE) PetscCall(ContactSetToolDrive(c, tool, d, TOOL_DRIVE_DISPLACEMENT, NULL));
      continue;
    }
    PetscCall(LoadCurveCreate(c->comm, "release", 2, tc->rel_t, v, &cv));
    PetscCall(ContactSetToolDrive(c, tool, d, TOOL_DRIVE_FORCE, &cv));
    PetscCall(LoadCurveDestroy(&cv));
  }
  PetscFunctionReturn(0);
}

PetscErrorCode ContactReleaseTool(Contact c, PetscInt tool, PetscReal t0, PetscReal t1)
{
  ToolContact      *tc;
  ContactToolResult r;

  PetscFunctionBeginUser;
  PetscCheck(tool >= 0 && tool < c->ntools, c->comm, PETSC_ERR_ARG_OUTOFRANGE, "ContactReleaseTool: tool %" PetscInt_FMT " of %" PetscInt_FMT, tool, c->ntools);
  PetscCheck(t1 > t0, c->comm, PETSC_ERR_ARG_OUTOFRANGE, "ContactReleaseTool: tool %s released from time %g to %g", c->tools[tool].name, (double)t0, (double)t1);
  tc = &c->tc[tool];
  PetscCheck(tc->block >= 0, c->comm, PETSC_ERR_ORDER, "tool %s is released by force but has no unknowns (reserve them before the setup: ContactReserveToolUnknowns)", c->tools[tool].name);
  PetscCall(ContactGetToolResult(c, tool, t0, &r)); /* the committed force the tool exerts */
  tc->release  = PETSC_TRUE;
  tc->rel_t[0] = t0;
  tc->rel_t[1] = t1;
  for (int d = 0; d < 3; d++) tc->rel_f[d] = r.f[d];
  PetscCall(ReleaseDrive(c, tool));
  PetscFunctionReturn(0);
}

/* Release by nodal forces: the force each node carries from the tool in the committed state is
   kept as a dead load, scaled by NodalReleaseShare (1 now, 0 at t1); the tool is then removed
   (ContactSetToolPresent), its force-driven directions held where they are. At t0 the body is in
   equilibrium with those loads exactly as it was with the tool, so the release starts without a
   jump; as they fall the body springs back with no contact law in the way (no stick/slip, no tool
   whose force goes to zero). The tool no longer pairs: a node that would touch it again in the
   release passes through it (the release suits tools that the springback moves away from). */
PetscErrorCode ContactReleaseToolNodes(Contact c, PetscInt tool, PetscReal t0, PetscReal t1)
{
  ToolContact *tc;

  PetscFunctionBeginUser;
  PetscCheck(tool >= 0 && tool < c->ntools, c->comm, PETSC_ERR_ARG_OUTOFRANGE, "ContactReleaseToolNodes: tool %" PetscInt_FMT " of %" PetscInt_FMT, tool, c->ntools);
  PetscCheck(t1 > t0, c->comm, PETSC_ERR_ARG_OUTOFRANGE, "ContactReleaseToolNodes: tool %s released from time %g to %g", c->tools[tool].name, (double)t0, (double)t1);
  tc = &c->tc[tool];
  for (PetscInt i = 0; i < c->ns; i++) {
    const ContactState *st = &c->cst_c[i];
    PetscReal          *w  = c->nrel + NREL * i;
    if (st->tool != tool || st->status == CONTACT_OPEN) continue;
    for (int k = 0; k < 3; k++) {
      w[k]     = st->f[k];
      w[3 + k] = st->fT[k];
    }
    w[6]            = t0;
    w[7]            = t1;
    c->nrel_tool[i] = tool;
  }
  for (PetscInt d = 0; d < 3; d++)
    if (tc->drive[d] == TOOL_DRIVE_FORCE) PetscCall(ContactSetToolDrive(c, tool, d, TOOL_DRIVE_DISPLACEMENT, NULL));
  tc->release = PETSC_FALSE;
  PetscCall(ContactSetToolPresent(c, tool, PETSC_FALSE));
  PetscFunctionReturn(0);
}

PetscErrorCode ContactGetToolTarget(Contact c, PetscInt tool, PetscReal t, PetscBool driven[3], PetscReal F[3])
{
  PetscFunctionBeginUser;
  PetscCheck(tool >= 0 && tool < c->ntools, c->comm, PETSC_ERR_ARG_OUTOFRANGE, "ContactGetToolTarget: tool %" PetscInt_FMT " of %" PetscInt_FMT, tool, c->ntools);
  for (int d = 0; d < 3; d++) {
    driven[d] = c->tc[tool].drive[d] == TOOL_DRIVE_FORCE ? PETSC_TRUE : PETSC_FALSE;
    F[d]      = driven[d] ? ToolTarget(&c->tc[tool], d, t) : 0;
  }
  PetscFunctionReturn(0);
}

PetscErrorCode ContactReserveToolUnknowns(Contact c, PetscInt tool)
{
  PetscFunctionBeginUser;
  PetscCheck(tool >= 0 && tool < c->ntools, c->comm, PETSC_ERR_ARG_OUTOFRANGE, "ContactReserveToolUnknowns: tool %" PetscInt_FMT " of %" PetscInt_FMT, tool, c->ntools);
  PetscCheck(!c->mesh, c->comm, PETSC_ERR_ORDER, "ContactReserveToolUnknowns: tool %s after the setup", c->tools[tool].name);
  c->tc[tool].reserve = PETSC_TRUE;
  PetscFunctionReturn(0);
}

PetscReal ContactNextKink(Contact c, PetscReal t)
{
  PetscReal k = PETSC_INFINITY;
  for (PetscInt i = 0; i < c->ntools; i++)
    for (int d = 0; d < 3; d++)
      if (c->tc[i].drive[d] == TOOL_DRIVE_FORCE && c->tc[i].famp[d].n) k = PetscMin(k, LoadCurveNextKink(&c->tc[i].famp[d], t));
  return k;
}

PetscInt ContactNumToolUnknowns(Contact c) { return 3 * c->nb; }

PetscErrorCode ContactSetToolDofs(Contact c, PetscInt first, PetscBool owner)
{
  PetscFunctionBeginUser;
  c->tdof0  = first;
  c->towner = owner;
  PetscFunctionReturn(0);
}

PetscErrorCode ContactSetToolUnknowns(Contact c, const PetscReal *d)
{
  PetscBool changed = PETSC_FALSE;

  PetscFunctionBeginUser;
  for (PetscInt t = 0; t < c->ntools; t++) {
    ToolContact *tc = &c->tc[t];
    if (tc->block < 0) continue;
    for (int k = 0; k < 3; k++) {
      if (tc->d[k] != d[3 * tc->block + k]) changed = PETSC_TRUE;
      tc->d[k] = d[3 * tc->block + k];
    }
  }
  if (changed) c->gen++; /* the pairings found at the old tool positions are stale */
  PetscFunctionReturn(0);
}

PetscErrorCode ContactSetFromOptions(Contact c)
{
  MPI_Comm comm = c->comm;

  PetscFunctionBeginUser;
  c->law.KN       = 1e5;
  c->law.KT       = 5e3;
  c->law.mu       = 0;
  c->search_opt   = -1;
  c->edge_tol     = -1;
  c->symmetry     = 0;
  PetscOptionsBegin(comm, NULL, "Contact with rigid tools", NULL);
  {
    char     *sets[8];
    PetscInt  nsets = 8;
    PetscBool sset;
    PetscCall(PetscOptionsStringArray("-contact_set", "Mesh sets of the slave nodes (their union)", NULL, sets, &nsets, &sset));
    if (!sset || nsets == 0) {
      PetscCall(PetscStrncpy(c->set[0], "contact", sizeof(c->set[0])));
      c->nset = 1;
    } else {
      for (PetscInt k = 0; k < nsets; k++) {
        PetscCall(PetscStrncpy(c->set[k], sets[k], sizeof(c->set[k])));
        PetscCall(PetscFree(sets[k]));
      }
      c->nset = nsets;
    }
  }
  {
    char      buf[64] = "auto"; /* a user who gives no penalty gets one from the mesh and the material */
    PetscBool set;
    PetscCall(PetscOptionsString("-contact_penalty_normal", "Normal penalty K_N (force per length, per node; per unit area with -contact_penalty_per_area), or auto: per node from the elements under it", NULL, buf, buf, sizeof(buf), NULL));
    PetscCall(PenaltyValue(comm, "-contact_penalty_normal", buf, &c->kauto, &c->law.KN));
    PetscCall(PetscStrncpy(buf, c->kauto ? "auto" : "5e3", sizeof(buf)));
    PetscCall(PetscOptionsString("-contact_penalty_tangential", "Tangential penalty K_T (force per length, per node; per unit area with -contact_penalty_per_area), or auto: -contact_penalty_ratio times K_N (the default with -contact_penalty_normal auto)", NULL, buf, buf, sizeof(buf), &set));
    PetscCall(PenaltyValue(comm, "-contact_penalty_tangential", buf, &c->ktauto, &c->law.KT));
    PetscCheck(!c->ktauto || c->kauto, comm, PETSC_ERR_USER_INPUT, "-contact_penalty_tangential auto needs -contact_penalty_normal auto");
  }
  c->kfactor = 1;
  c->kratio  = 0.1;
  PetscCall(PetscOptionsReal("-contact_penalty_factor", "With -contact_penalty_normal auto: K_N = factor * E * A / h per node (A its tributary area, h the element size normal to the contact face)", NULL, c->kfactor, &c->kfactor, NULL));
  PetscCall(PetscOptionsReal("-contact_penalty_ratio", "With -contact_penalty_tangential auto: K_T = ratio * K_N per node", NULL, c->kratio, &c->kratio, NULL));
  PetscCheck(c->kfactor > 0 && PetscIsNormalReal(c->kfactor), comm, PETSC_ERR_USER_INPUT, "-contact_penalty_factor %g must be positive", (double)c->kfactor);
  PetscCheck(c->kratio > 0 && PetscIsNormalReal(c->kratio), comm, PETSC_ERR_USER_INPUT, "-contact_penalty_ratio %g must be positive", (double)c->kratio);
  PetscCall(PetscOptionsBool("-contact_penalty_per_area", "K_N and K_T are per unit area (force per length^3); each slave node's are scaled by its tributary area on the contact faces", NULL, c->per_area, &c->per_area, NULL));
  PetscCheck(!(c->per_area && c->kauto), comm, PETSC_ERR_USER_INPUT, "-contact_penalty_per_area needs -contact_penalty_normal and -contact_penalty_tangential values per unit area (the automatic penalty, auto, is per node already)");
  c->aug_tol     = -1;
  c->aug_tol_rel = -1;
  c->aug_mtol    = 0.2;
  c->aug_max     = 20;
  c->aug_grow    = 8;
  c->aug_grow_max = 1e3;
  c->kscale      = 1;
  c->kscale_c    = 1;
  c->aug_keep    = PETSC_TRUE;
  c->aug_inexact = 1e-3;
  PetscCall(PetscOptionsBool("-contact_augmented", "Augmented Lagrangian: Uzawa updates of the nodal multipliers between Newton solves until the penetration is below the tolerance", NULL, c->aug, &c->aug, NULL));
  {
    PetscBool sa, sr, sm, sx;
    PetscCall(PetscOptionsReal("-contact_augmented_tol", "Augmented Lagrangian: largest penetration (and stick slip per step) accepted, a length (default 1e-2 times the smallest element size normal to the contact faces)", NULL, c->aug_tol, &c->aug_tol, &sa));
    PetscCall(PetscOptionsReal("-contact_augmented_tol_relative", "Augmented Lagrangian: the tolerance as a fraction of the smallest element size normal to the contact faces (with -contact_augmented_tol: the smaller of the two)", NULL, c->aug_tol_rel, &c->aug_tol_rel, &sr));
    PetscCall(PetscOptionsReal("-contact_augmented_multiplier_tol", "Augmented Lagrangian: largest change of a nodal multiplier accepted, relative to the largest multiplier", NULL, c->aug_mtol, &c->aug_mtol, &sm));
    PetscCall(PetscOptionsInt("-contact_augmented_max", "Augmented Lagrangian: Newton solves (multiplier updates) allowed per load step", NULL, c->aug_max, &c->aug_max, &sx));
    PetscCall(PetscOptionsReal("-contact_augmented_growth", "Augmented Lagrangian: factor on the penalties (for the rest of the step, and with -contact_augmented_growth_keep the next steps) after an update that did not reduce the largest penetration by 4 (1: never)", NULL, c->aug_grow, &c->aug_grow, NULL));
    PetscCall(PetscOptionsBool("-contact_augmented_growth_keep", "Augmented Lagrangian: the penalties' growth carries over to the next steps (false: every step starts from the penalties as given)", NULL, c->aug_keep, &c->aug_keep, NULL));
    PetscCall(PetscOptionsReal("-contact_augmented_inexact", "Augmented Lagrangian: the multipliers are updated as soon as |R| is below this fraction of the step's initial residual; the step ends with a fully converged solve at the final multipliers (0: every solve fully converged)", NULL, c->aug_inexact, &c->aug_inexact, NULL));
    PetscCheck(c->aug_inexact >= 0 && c->aug_inexact < 1, comm, PETSC_ERR_USER_INPUT, "-contact_augmented_inexact %g must lie in [0, 1)", (double)c->aug_inexact);
    PetscCall(PetscOptionsBool("-contact_augmented_soften", "Augmented Lagrangian: a step whose Newton solve fails is retried once at the same increment with the penalties -contact_augmented_growth times softer (down to 1/-contact_augmented_growth_max times the given ones; kept for the next steps), before the increment is cut", NULL, c->aug_soften, &c->aug_soften, NULL));
    PetscCall(PetscOptionsBool("-contact_augmented_monitor", "Augmented Lagrangian: print one line per multiplier update (penetration, stick slip, multiplier changes, relaxation, penalties' factor)", NULL, c->aug_monitor, &c->aug_monitor, NULL));
    PetscCall(PetscOptionsReal("-contact_augmented_growth_max", "Augmented Lagrangian: largest factor the penalties grow by", NULL, c->aug_grow_max, &c->aug_grow_max, NULL));
    PetscCheck(c->aug_grow >= 1 && PetscIsNormalReal(c->aug_grow), comm, PETSC_ERR_USER_INPUT, "-contact_augmented_growth %g must be >= 1", (double)c->aug_grow);
    PetscCheck(c->aug_grow_max >= 1 && PetscIsNormalReal(c->aug_grow_max), comm, PETSC_ERR_USER_INPUT, "-contact_augmented_growth_max %g must be >= 1", (double)c->aug_grow_max);
    PetscCheck(!sa || (c->aug_tol > 0 && PetscIsNormalReal(c->aug_tol)), comm, PETSC_ERR_USER_INPUT, "-contact_augmented_tol %g must be positive", (double)c->aug_tol);
    PetscCheck(!sr || (c->aug_tol_rel > 0 && PetscIsNormalReal(c->aug_tol_rel)), comm, PETSC_ERR_USER_INPUT, "-contact_augmented_tol_relative %g must be positive", (double)c->aug_tol_rel);
    PetscCheck(c->aug_mtol > 0 && PetscIsNormalReal(c->aug_mtol), comm, PETSC_ERR_USER_INPUT, "-contact_augmented_multiplier_tol %g must be positive", (double)c->aug_mtol);
    PetscCheck(c->aug_max >= 1, comm, PETSC_ERR_USER_INPUT, "-contact_augmented_max %" PetscInt_FMT " must be >= 1", c->aug_max);
    if (!sa && !sr) c->aug_tol_rel = 1e-2;
  }
  PetscCall(PetscOptionsReal("-contact_friction", "Coulomb friction coefficient mu", NULL, c->law.mu, &c->law.mu, NULL));
  {
    char      buf[64] = "auto";
    PetscBool set;
    PetscCall(PetscOptionsString("-contact_regularization", "Width of the band over which the normal contact force starts quadratically (C1; it reaches a tenth of the width to the open side, the full penalty beyond the band; 0: the plain bracket), a length, or auto: -contact_regularization_relative times the element size normal to the contact face at each node with the automatic penalty, 0 with a given one", "doc/contact.md", buf, buf, sizeof(buf), &set));
    PetscCall(PetscStrcmp(buf, "auto", &c->reg_auto));
    if (!c->reg_auto) {
      char *end;
      c->law.reg = strtod(buf, &end);
      PetscCheck(end != buf && *end == 0 && c->law.reg >= 0 && PetscIsNormalReal(c->law.reg + 1), comm, PETSC_ERR_USER_INPUT, "-contact_regularization %s must be a length >= 0 or auto", buf);
    }
    c->reg_rel = 1e-2;
    PetscCall(PetscOptionsReal("-contact_regularization_relative", "With -contact_regularization auto: the regularisation's width as a fraction of the element size normal to the contact face", "doc/contact.md", c->reg_rel, &c->reg_rel, NULL));
    PetscCheck(c->reg_rel >= 0 && c->reg_rel < 1, comm, PETSC_ERR_USER_INPUT, "-contact_regularization_relative %g must lie in [0, 1)", (double)c->reg_rel);
  }
  c->kforce_pen = 1e-4;
  PetscCall(PetscOptionsReal("-contact_penalty_force_penetration", "Automatic penalty of a tool driven by force: at most its largest force's share per node under it (projected on it at the start, within an element size) divided by this fraction of each node's element size (the penetration at that share of the force; 0: E A / h alone)", "doc/contact.md", c->kforce_pen, &c->kforce_pen, NULL));
  PetscCheck(c->kforce_pen >= 0 && c->kforce_pen < 1, comm, PETSC_ERR_USER_INPUT, "-contact_penalty_force_penetration %g must lie in [0, 1)", (double)c->kforce_pen);
  PetscCall(PetscOptionsReal("-contact_gap_smoothing", "Width (a length) over which the normal contact force is smoothed about gap 0 (C1 quadratic; 0: the plain bracket)", "doc/contact.md", c->law.delta, &c->law.delta, NULL));
  PetscCheck(c->law.delta >= 0 && !PetscIsInfOrNanReal(c->law.delta), comm, PETSC_ERR_USER_INPUT, "-contact_gap_smoothing %g must be >= 0", (double)c->law.delta);
  PetscCheck(c->kauto || (c->law.KN > 0 && PetscIsNormalReal(c->law.KN)), comm, PETSC_ERR_USER_INPUT, "-contact_penalty_normal %g must be positive", (double)c->law.KN);
  PetscCheck(c->ktauto || (c->law.KT > 0 && PetscIsNormalReal(c->law.KT)), comm, PETSC_ERR_USER_INPUT, "-contact_penalty_tangential %g must be positive", (double)c->law.KT);
  PetscCheck(c->law.mu >= 0 && (c->law.mu == 0 || PetscIsNormalReal(c->law.mu)), comm, PETSC_ERR_USER_INPUT, "-contact_friction %g must be >= 0", (double)c->law.mu);
  {
    const char *tang[] = {"analytic", "fd", "ContactTangent", "CT_", NULL};
    PetscInt    t      = 0;
    PetscCall(PetscOptionsEList("-contact_tangent", "Contact tangent: analytic (with curvature) or per-node finite differences", NULL, tang, 2, tang[0], &t, NULL));
    c->fd = t == 1 ? PETSC_TRUE : PETSC_FALSE;
  }
  {
    const char *carry[] = {"projection", "rotation", "ContactFrameCarry", "CFC_", NULL};
    PetscInt    t       = 0;
    PetscCall(PetscOptionsEList("-contact_frame_carry", "How eq 30 carries a node's frame to the next iterate's normal: projection (the previous t1 projected on the new plane, eqs 28-30 as published) or rotation (t1 turned by the rotation between the normals; symmetric problems stay symmetric with -newton_keep_contact all)", "doc/contact.md", carry, 2, carry[0], &t, NULL));
    c->frame_rotate = t == 1 ? PETSC_TRUE : PETSC_FALSE;
  }
  PetscCall(PetscOptionsReal("-contact_search_distance", "Pairing: tools farther than this from a node are skipped (default: 5% of the largest tool box)", NULL, c->search_opt, &c->search_opt, NULL));
  {
    PetscBool set = PETSC_FALSE;
    PetscCall(PetscOptionsReal("-contact_edge_tolerance", "Pairing: a node beside an open edge of a tool (its closest point held on a patch boundary) by more than this in the tool's tangent plane, and by more than it lies inside the tool, is not in contact with the tool (default: 1e-3 of the tool's box diagonal; 0: not checked)", "doc/contact.md", c->edge_tol, &c->edge_tol, &set));
    PetscCheck(!set || (c->edge_tol >= 0 && PetscIsNormalReal(c->edge_tol + 1)), comm, PETSC_ERR_USER_INPUT, "-contact_edge_tolerance %g must be a length >= 0", (double)c->edge_tol);
  }
  PetscCall(PetscOptionsReal("-model_symmetry", "Multiplicity of the model: force_full = force * multiplicity (default 4 for the quarter blank, else 1)", NULL, c->symmetry, &c->symmetry, NULL));
  PetscCheck(c->symmetry == 0 || c->symmetry >= 1, comm, PETSC_ERR_USER_INPUT, "-model_symmetry %g must be >= 1", (double)c->symmetry);
  PetscOptionsEnd();
  PetscCall(ToolsCreateFromOptions(comm, &c->ntools, &c->tools));
  PetscCall(PetscCalloc1(c->ntools + 1, &c->tc));
  for (PetscInt t = 0; t < c->ntools; t++) {
    const double *b = c->tools[t].bbox;
    c->tools[t].edge_tol = c->edge_tol >= 0 ? c->edge_tol : 1e-3 * PetscSqrtReal(PetscSqr(b[1] - b[0]) + PetscSqr(b[3] - b[2]) + PetscSqr(b[5] - b[4]));
    PetscCall(ToolContactSetFromOptions(c, t));
  }
  PetscCall(ContactPairsSetFromOptions(c->pairs));
  PetscFunctionReturn(0);
}

PetscErrorCode ContactGetAreaSets(Contact c, PetscInt *n, char (**sets)[ATRITO_NAME_LEN])
{
  PetscBool anyauto = c->kauto;
  PetscFunctionBeginUser;
  *n    = 0;
  *sets = c->set;
  for (PetscInt t = 0; t < c->ntools; t++) anyauto = anyauto || c->tc[t].kauto;
  if (!c->uset) { /* the union of the tools' sets (the global ones first) */
    PetscInt nmax = c->nset;
    for (PetscInt t = 0; t < c->ntools; t++) nmax += c->tc[t].nset;
    PetscCall(PetscCalloc1(nmax + 1, &c->uset));
    for (PetscInt t = -1; t < c->ntools; t++) {
      const PetscInt ns = t < 0 ? c->nset : c->tc[t].nset;
      if (t < 0) { /* the global sets, when some tool uses them */
        PetscBool used = c->ntools ? PETSC_FALSE : PETSC_TRUE;
        for (PetscInt u = 0; u < c->ntools; u++) used = used || !c->tc[u].nset;
        if (!used) continue;
      }
      for (PetscInt k = 0; k < ns; k++) {
        const char *nm  = t < 0 ? c->set[k] : c->tc[t].set[k];
        PetscBool   dup = PETSC_FALSE;
        for (PetscInt j = 0; j < c->nuset; j++) {
          PetscBool eq;
          PetscCall(PetscStrcmp(c->uset[j], nm, &eq));
          dup = dup || eq;
        }
        if (!dup) PetscCall(PetscStrncpy(c->uset[c->nuset++], nm, sizeof(c->uset[0])));
      }
    }
  }
  *n    = (c->ntools && (c->per_area || anyauto || c->aug)) ? c->nuset : 0;
  *sets = c->uset;
  PetscFunctionReturn(0);
}

PetscErrorCode ContactSetYoungModulus(Contact c, PetscReal E)
{
  PetscFunctionBeginUser;
  c->E_body = E;
  PetscCall(ContactPairsSetYoungModulus(c->pairs, E));
  PetscFunctionReturn(0);
}

PetscInt ContactNumPairs(Contact c) { return ContactPairsNum(c->pairs); }

PetscErrorCode ContactSetCellModuli(Contact c, PetscInt nc, const PetscReal *Ec)
{
  PetscFunctionBeginUser;
  PetscCall(ContactPairsSetCellModuli(c->pairs, nc, Ec));
  PetscCall(PetscFree(c->Ecell));
  PetscCall(PetscMalloc1(nc + 1, &c->Ecell));
  PetscCall(PetscArraycpy(c->Ecell, Ec, nc));
  PetscFunctionReturn(0);
}
ContactPairs ContactGetPairs(Contact c) { return c->pairs; }

PetscErrorCode ContactGetFaceSets(Contact c, PetscInt *n, char (**sets)[ATRITO_NAME_LEN])
{
  PetscFunctionBeginUser;
  PetscCall(ContactPairsGetFaceSets(c->pairs, n, sets));
  PetscFunctionReturn(0);
}

PetscInt ContactNumTools(Contact c) { return c->ntools; }
PetscInt ContactNumSlaves(Contact c) { return c->ns; }
PetscReal ContactSymmetry(Contact c) { return c->symmetry; }

/* volume of a hex8 (2x2x2 Gauss: exact for the trilinear map) */
static double HexVolume(const double x[8][3])
{
  static const double xa[8] = {-1, 1, 1, -1, -1, 1, 1, -1}, ea[8] = {-1, -1, 1, 1, -1, -1, 1, 1}, za[8] = {-1, -1, -1, -1, 1, 1, 1, 1};
  const double        gq    = 0.57735026918962576451;
  double              V     = 0;
  for (int q = 0; q < 8; q++) {
    const double xi = xa[q] * gq, eta = ea[q] * gq, zeta = za[q] * gq;
    double       J[3][3] = {{0}};
    for (int a = 0; a < 8; a++) {
      const double d[3] = {0.125 * xa[a] * (1 + ea[a] * eta) * (1 + za[a] * zeta), 0.125 * ea[a] * (1 + xa[a] * xi) * (1 + za[a] * zeta), 0.125 * za[a] * (1 + xa[a] * xi) * (1 + ea[a] * eta)};
      for (int k = 0; k < 3; k++)
        for (int l = 0; l < 3; l++) J[k][l] += x[a][k] * d[l];
    }
    V += J[0][0] * (J[1][1] * J[2][2] - J[1][2] * J[2][1]) - J[0][1] * (J[1][0] * J[2][2] - J[1][2] * J[2][0]) + J[0][2] * (J[1][0] * J[2][1] - J[1][1] * J[2][0]);
  }
  return fabs(V);
}

/* The element size normal to the contact faces at each slave node: h_i = 2 V_i / A_i, V_i the
   node's share of the volume of the elements around it (an eighth of each; summed over the ranks
   through the unconstrained twin DM, so rank-independent), A_i its tributary area (for a regular
   mesh, the thickness of the element layer under the face). h[i] = 0 where A_i = 0. With several
   bodies (ContactSetCellModuli) En[i] is the modulus of the node's elements, weighted by the same
   volume shares (E_body without them). */
static PetscErrorCode ElementSizes(Contact contact, PetscReal *h, PetscReal *En)
{
  const Mesh        *m = contact->mesh;
  Vec                Vl, Vg;
  PetscScalar       *vl;
  const PetscScalar *vr;

  PetscFunctionBeginUser;
  PetscCall(DMGetLocalVector(m->dmr, &Vl));
  PetscCall(DMGetGlobalVector(m->dmr, &Vg));
  PetscCall(VecZeroEntries(Vl));
  PetscCall(VecZeroEntries(Vg));
  PetscCall(VecGetArray(Vl, &vl));
  for (PetscInt c = 0; c < m->nc; c++) {
    double x[8][3];
    for (int a = 0; a < 8; a++)
      for (int k = 0; k < 3; k++) x[a][k] = m->X[3 * m->cv[8 * c + a] + k];
    const double V = HexVolume(x);
    for (int a = 0; a < 8; a++) {
      vl[m->vloff[m->cv[8 * c + a]]] += V / 8;
      if (contact->Ecell) vl[m->vloff[m->cv[8 * c + a]] + 1] += contact->Ecell[c] * V / 8;
    }
  }
  PetscCall(VecRestoreArray(Vl, &vl));
  PetscCall(DMLocalToGlobal(m->dmr, Vl, ADD_VALUES, Vg));
  PetscCall(DMGlobalToLocal(m->dmr, Vg, INSERT_VALUES, Vl));
  PetscCall(VecGetArrayRead(Vl, &vr));
  for (PetscInt i = 0; i < contact->ns; i++) {
    const PetscInt  v = contact->slave[i];
    const PetscReal A = m->varea ? m->varea[v] : 0;
    h[i]              = A > 0 ? 2 * PetscRealPart(vr[m->vloff[v]]) / A : 0;
    if (En) En[i] = contact->Ecell ? PetscRealPart(vr[m->vloff[v] + 1]) / PetscRealPart(vr[m->vloff[v]]) : contact->E_body;
  }
  PetscCall(VecRestoreArrayRead(Vl, &vr));
  PetscCall(DMRestoreLocalVector(m->dmr, &Vl));
  PetscCall(DMRestoreGlobalVector(m->dmr, &Vg));
  PetscFunctionReturn(0);
}

/* the law of slave node i against tool t (the tool's settings, the global ones by default): its
   own penalties (automatic), or the given ones (times its area) */
static inline ContactLaw NodeLaw(const struct _p_Contact *contact, PetscInt i, PetscInt t)
{
  const ToolContact *tc  = &contact->tc[t < 0 ? 0 : t];
  ContactLaw         law = tc->law;
  if (tc->kauto) {
    law.KN = contact->kn[i];
    /* a tool driven by force: no stiffer than its force's share per node over a penetration of
       kforce_pen times the element size (a light holder on a sheet: E A / h put its nodes at
       nanometre penetrations, at the open end of the regularised law where the stiffness vanishes) */
    if (tc->fnode > 0 && contact->hn && contact->hn[i] > 0) law.KN = PetscMin(law.KN, tc->fnode / (contact->kforce_pen * contact->hn[i]));
    law.KT = tc->ktauto ? contact->kratio * law.KN : tc->law.KT;
  } else if (contact->per_area) { /* penalties per unit area times the node's tributary area */
    law.KN *= contact->mesh->varea[contact->slave[i]];
    law.KT *= contact->mesh->varea[contact->slave[i]];
  }
  if (contact->reg_auto) {
    /* a width of reg_rel times the element size, at most the augmented Lagrangian's penetration
       tolerance (its converged penetration is up to half the width) */
    law.reg = (tc->kauto && contact->hn) ? contact->reg_rel * contact->hn[i] : 0;
    if (contact->aug && contact->tol > 0) law.reg = PetscMin(law.reg, contact->tol);
  }
  if (contact->kscale != 1) { /* grown by the augmentation within the current step */
    law.KN *= contact->kscale;
    law.KT *= contact->kscale;
  }
  return law;
}

PetscErrorCode ContactSetUp(Contact contact, const Mesh *m)
{
  PetscBool *mark, found;

  PetscFunctionBeginUser;
  contact->mesh = m;
  if (contact->symmetry == 0) contact->symmetry = (m->opt.source == MESH_BLANK && m->opt.blank_quarter) ? 4 : 1;
  contact->ns = 0;
  PetscCall(ContactPairsSetUp(contact->pairs, m));
  if (!contact->ntools) PetscFunctionReturn(0);
  contact->search = contact->search_opt;
  if (contact->search <= 0) { /* default: 5 % of the largest tool's box diagonal */
    for (PetscInt t = 0; t < contact->ntools; t++) {
      const double *b = contact->tools[t].bbox;
      contact->search      = PetscMax(contact->search, 0.05 * PetscSqrtReal(PetscSqr(b[1] - b[0]) + PetscSqr(b[3] - b[2]) + PetscSqr(b[5] - b[4])));
    }
  }

  /* the slave nodes: the union of the tools' sets; tmark[v * ntools + t]: vertex v may pair with
     tool t (it lies in one of the tool's sets, the global -contact_set by default) */
  const PetscInt nt = contact->ntools;
  char          *tmark;
  PetscCall(PetscCalloc1(m->nv, &mark));
  PetscCall(PetscCalloc1(m->nv * nt, &tmark));
  {
    PetscBool used = PETSC_FALSE;
    for (PetscInt t = 0; t < nt; t++) used = used || !contact->tc[t].nset;
    if (used) {
      PetscBool *gm;
      PetscCall(PetscCalloc1(m->nv, &gm));
      for (PetscInt s = 0; s < contact->nset; s++) {
        PetscCall(MeshMarkSetVertices(m, contact->set[s], gm, &found));
        PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, &found, 1, MPIU_BOOL, MPI_LOR, contact->comm));
        PetscCheck(found, contact->comm, PETSC_ERR_USER_INPUT, "-contact_set: the mesh has no set named '%s'", contact->set[s]);
      }
      for (PetscInt v = 0; v < m->nv; v++)
        for (PetscInt t = 0; t < nt; t++)
          if (gm[v] && !contact->tc[t].nset) tmark[v * nt + t] = 1;
      PetscCall(PetscFree(gm));
    }
    for (PetscInt t = 0; t < nt; t++) {
      PetscBool *tm;
      if (!contact->tc[t].nset) continue;
      PetscCall(PetscCalloc1(m->nv, &tm));
      for (PetscInt s = 0; s < contact->tc[t].nset; s++) {
        PetscCall(MeshMarkSetVertices(m, contact->tc[t].set[s], tm, &found));
        PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, &found, 1, MPIU_BOOL, MPI_LOR, contact->comm));
        PetscCheck(found, contact->comm, PETSC_ERR_USER_INPUT, "-tool_%s_contact_set: the mesh has no set named '%s'", contact->tools[t].name, contact->tc[t].set[s]);
      }
      for (PetscInt v = 0; v < m->nv; v++)
        if (tm[v]) tmark[v * nt + t] = 1;
      PetscCall(PetscFree(tm));
    }
    for (PetscInt v = 0; v < m->nv; v++)
      for (PetscInt t = 0; t < nt; t++)
        if (tmark[v * nt + t]) mark[v] = PETSC_TRUE;
  }
  for (PetscInt v = 0; v < m->nv; v++)
    if (mark[v] && m->vowned[v]) contact->ns++;
  PetscCall(PetscMalloc1(contact->ns * nt + 1, &contact->tmask));
  PetscCall(PetscMalloc4(contact->ns, &contact->slave, 3 * contact->ns, &contact->sgdof, 3 * contact->ns, &contact->seed, contact->ns, &contact->has_seed));
  PetscCall(PetscArrayzero(contact->seed, 3 * contact->ns)); /* zero: no seed set yet (NodeEval) */
  PetscCall(PetscCalloc2(3 * contact->ns + 1, &contact->seedn, 3 * contact->ns + 1, &contact->yseed));
  PetscCall(PetscCalloc4(contact->ns, &contact->active_prev, contact->ns, &contact->tN_prev, contact->ns + 1, &contact->tool_prev, contact->ns + 1, &contact->status_prev));
  PetscCall(PetscMalloc1(contact->ns, &contact->pmemo));
  PetscCall(PetscCalloc2(contact->ns, &contact->cst_c, contact->ns, &contact->cst_t));
  PetscCall(PetscCalloc3(3 * contact->ns, &contact->lam, contact->ns, &contact->lam_tool, 3 * contact->ns, &contact->lam_r));
  PetscCall(PetscCalloc2(NREL * contact->ns, &contact->nrel, contact->ns, &contact->nrel_tool));
  PetscCall(PetscCalloc2(NLIN * contact->ns, &contact->lin, contact->ns + 1, &contact->lin_ok));
  contact->ns = 0;
  for (PetscInt v = 0; v < m->nv; v++) {
    if (!(mark[v] && m->vowned[v])) continue;
    const PetscInt i = contact->ns++;
    contact->slave[i]     = v;
    PetscCall(MeshVertexDofs(m, v, contact->sgdof + 3 * i));
    for (PetscInt t = 0; t < nt; t++) contact->tmask[i * nt + t] = tmark[v * nt + t];
    contact->has_seed[i] = PETSC_FALSE;
    for (int k = 0; k < 3; k++) contact->cst_c[i].y[k] = m->X[3 * v + k];
    contact->cst_c[i].tool = contact->cst_c[i].patch = -1;
    contact->cst_c[i].gap                       = PETSC_INFINITY;
    contact->cst_t[i]                           = contact->cst_c[i];
    contact->pmemo[i].tool                      = -2;
    contact->lam_tool[i]                        = -1;
    contact->nrel_tool[i]                       = -1;
  }
  PetscCall(PetscFree(mark));
  PetscCall(PetscFree(tmark));
  for (PetscInt t = 0; t < nt; t++) contact->kanyauto = contact->kanyauto || contact->tc[t].kauto;
  if (m->varea || contact->kanyauto || contact->aug) { /* element sizes: the automatic penalty, the relative tolerance, the
                                                           regularisation, the step limit, the predictor's projection */
    PetscReal *h, hmin = PETSC_MAX_REAL;
    PetscInt   nzero = 0;
    PetscCheck(m->varea, contact->comm, PETSC_ERR_PLIB, "contact: the mesh carries no tributary areas");
    PetscReal *En;
    PetscCall(PetscMalloc1(contact->ns + 1, &h));
    PetscCall(PetscMalloc1(contact->ns + 1, &En));
    PetscCall(ElementSizes(contact, h, En));
    for (PetscInt i = 0; i < contact->ns; i++) {
      if (h[i] > 0) hmin = PetscMin(hmin, h[i]);
      else nzero++;
    }
    PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, &hmin, 1, MPIU_REAL, MPI_MIN, contact->comm));
    PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, &nzero, 1, MPIU_INT, MPI_SUM, contact->comm));
    contact->hmin = hmin < PETSC_MAX_REAL ? hmin : 0;
    contact->hn   = h;
    if (contact->kanyauto) {
      PetscReal E, kmin = PETSC_MAX_REAL, kmax = 0;
      PetscCheck(!nzero, contact->comm, PETSC_ERR_USER_INPUT, "-contact_penalty_normal auto: %" PetscInt_FMT " slave nodes of -contact_set '%s'%s lie on no boundary face whose four vertices are all in one of the sets, so they have no tributary area", nzero, contact->set[0], contact->nset > 1 ? ", ..." : "");
      /* the body's Young's modulus, from its material (ContactSetYoungModulus; with several bodies
         each node's, from the materials of its elements) */
      E = contact->E_body;
      {
        PetscInt bad = 0;
        for (PetscInt i = 0; i < contact->ns; i++) bad += !(En[i] > 0 && PetscIsNormalReal(En[i]));
        PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, &bad, 1, MPIU_INT, MPI_SUM, contact->comm));
        if (contact->Ecell) E = bad ? 0 : 1; /* (checked below) */
      }
      PetscCheck(E > 0 && PetscIsNormalReal(E), contact->comm, PETSC_ERR_USER_INPUT, "-contact_penalty_normal auto needs the body's Young's modulus, which its material does not give (a user material: give -contact_penalty_normal a value)");
      PetscCall(PetscMalloc2(contact->ns, &contact->kn, contact->ns, &contact->kt));
      for (PetscInt i = 0; i < contact->ns; i++) {
        contact->kn[i] = contact->kfactor * En[i] * m->varea[contact->slave[i]] / h[i];
        contact->kt[i] = contact->ktauto ? contact->kratio * contact->kn[i] : contact->law.KT;
        kmin      = PetscMin(kmin, contact->kn[i]);
        kmax      = PetscMax(kmax, contact->kn[i]);
      }
      PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, &kmin, 1, MPIU_REAL, MPI_MIN, contact->comm));
      PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, &kmax, 1, MPIU_REAL, MPI_MAX, contact->comm));
      if (contact->Ecell) PetscCall(PetscPrintf(contact->comm, "contact: automatic penalty K_N = %g x E x A / h per node (E of its elements' materials): smallest %g, largest %g; K_T %s; smallest element size normal to the contact faces %g\n", (double)contact->kfactor, (double)kmin, (double)kmax, contact->ktauto ? "= -contact_penalty_ratio x K_N" : "as given", (double)contact->hmin));
      else PetscCall(PetscPrintf(contact->comm, "contact: automatic penalty K_N = %g x E %g x A / h per node: smallest %g, largest %g; K_T %s; smallest element size normal to the contact faces %g\n", (double)contact->kfactor, (double)E, (double)kmin, (double)kmax, contact->ktauto ? "= -contact_penalty_ratio x K_N" : "as given", (double)contact->hmin));
    }
    PetscCall(PetscFree(En));
  }
  if (contact->aug) {
    contact->tol = contact->aug_tol > 0 ? contact->aug_tol : PETSC_MAX_REAL;
    if (contact->aug_tol_rel > 0) {
      PetscCheck(contact->hmin > 0, contact->comm, PETSC_ERR_USER_INPUT, "-contact_augmented_tol_relative: no slave node lies on a boundary face of -contact_set, so there is no element size; give -contact_augmented_tol");
      contact->tol = PetscMin(contact->tol, contact->aug_tol_rel * contact->hmin);
    }
    PetscCall(PetscPrintf(contact->comm, "contact: augmented Lagrangian, penetration tolerance %g (smallest element size normal to the contact faces %g), multiplier change tolerance %g, at most %" PetscInt_FMT " Newton solves per step\n", (double)contact->tol, (double)contact->hmin, (double)contact->aug_mtol, contact->aug_max));
  }
  if (contact->per_area) { /* the tributary areas come with the mesh (MeshSetAreaSets) */
    PetscReal amin = PETSC_MAX_REAL, amax = 0, asum = 0;
    PetscInt  nzero = 0;
    PetscCheck(m->varea, contact->comm, PETSC_ERR_PLIB, "-contact_penalty_per_area: the mesh carries no tributary areas");
    for (PetscInt i = 0; i < contact->ns; i++) {
      const PetscReal A = m->varea[contact->slave[i]];
      if (!(A > 0)) nzero++;
      amin = PetscMin(amin, A);
      amax = PetscMax(amax, A);
      asum += A;
    }
    PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, &nzero, 1, MPIU_INT, MPI_SUM, contact->comm));
    PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, &amin, 1, MPIU_REAL, MPI_MIN, contact->comm));
    PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, &amax, 1, MPIU_REAL, MPI_MAX, contact->comm));
    PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, &asum, 1, MPIU_REAL, MPI_SUM, contact->comm));
    PetscCheck(!nzero, contact->comm, PETSC_ERR_USER_INPUT, "-contact_penalty_per_area: %" PetscInt_FMT " slave nodes of -contact_set '%s'%s lie on no boundary face whose four vertices are all in one of the sets, so they have no tributary area", nzero, contact->set[0], contact->nset > 1 ? ", ..." : "");
    PetscCall(PetscPrintf(contact->comm, "contact: penalties per unit area; tributary areas of the slave nodes: total %.10g, smallest %g, largest %g\n", (double)asum, (double)amin, (double)amax));
  }
  {
    PetscInt n = contact->ns, na;
    char (*us)[ATRITO_NAME_LEN];
    PetscCall(ContactGetAreaSets(contact, &na, &us)); /* the union of the tools' sets */
    PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, &n, 1, MPIU_INT, MPI_SUM, contact->comm));
    if (contact->kauto) PetscCall(PetscPrintf(contact->comm, "contact: %" PetscInt_FMT " slave nodes (set '%s'%s), %" PetscInt_FMT " tools, K_N per node (automatic), K_T %s, mu %g, %s tangent\n", n, contact->uset[0], contact->nuset > 1 ? ", ..." : "", contact->ntools, contact->ktauto ? "per node (automatic)" : "as given", (double)contact->law.mu, contact->fd ? "finite-difference" : "analytic"));
    else PetscCall(PetscPrintf(contact->comm, "contact: %" PetscInt_FMT " slave nodes (set '%s'%s), %" PetscInt_FMT " tools, K_N %g, K_T %g, mu %g, %s tangent\n", n, contact->uset[0], contact->nuset > 1 ? ", ..." : "", contact->ntools, (double)contact->law.KN, (double)contact->law.KT, (double)contact->law.mu, contact->fd ? "finite-difference" : "analytic"));
    PetscCheck(n > 0, contact->comm, PETSC_ERR_USER_INPUT, "-contact_set '%s' holds no vertex", contact->set[0]);
  }
  /* per tool: its nodes, its own settings, its unknowns and the regularising stiffness (the sum of
     the penalties K_N of the nodes that may pair with it) */
  contact->nb = 0;
  for (PetscInt t = 0; t < nt; t++) {
    ToolContact *tc = &contact->tc[t];
    PetscReal    loc[2] = {0, 0}, F = 0;
    for (PetscInt i = 0; i < contact->ns; i++) loc[0] += contact->tmask[i * nt + t] ? 1 : 0;
    PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, loc, 1, MPIU_REAL, MPI_SUM, contact->comm));
    /* a force-driven tool's largest force (the amplitude's largest value, 1 for the ramp) */
    for (int k = 0; k < 3; k++)
      if (tc->drive[k] == TOOL_DRIVE_FORCE) {
        PetscReal a = tc->famp[k].n ? 0 : 1;
        for (PetscInt j = 0; j < tc->famp[k].n; j++) a = PetscMax(a, PetscAbsReal(tc->famp[k].v[j]));
        F += PetscSqr(tc->fscale[k] * a);
      }
    tc->fnode = 0;
    if (tc->kauto && contact->kforce_pen > 0 && F > 0) {
      /* its force's share per node: over the nodes under it at the start (projected on it, at most
         an element size from it), or over all its slave nodes when none is */
      PetscReal   nu = 0;
      const double sh[3] = {0, 0, 0};
      for (PetscInt i = 0; i < contact->ns; i++) {
        Projection pr;
        double     y[3];
        if (!contact->tmask[i * nt + t] || !contact->hn) continue;
        for (int k = 0; k < 3; k++) y[k] = m->X[3 * contact->slave[i] + k];
        if (!ToolProject(&contact->tools[t], sh, y, contact->search, &pr) && PetscAbsReal(pr.gap) <= contact->hn[i]) nu += 1;
      }
      PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, &nu, 1, MPIU_REAL, MPI_SUM, contact->comm));
      tc->nunder = nu > 0 ? nu : loc[0];
      tc->fnode  = PetscSqrtReal(F) / tc->nunder;
    }
    for (PetscInt i = 0; i < contact->ns; i++)
      if (contact->tmask[i * nt + t]) loc[1] += NodeLaw(contact, i, t).KN;
    PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, loc + 1, 1, MPIU_REAL, MPI_SUM, contact->comm));
    tc->kreg  = loc[1];
    tc->block = tc->reserve ? contact->nb++ : -1;
    if (tc->own || tc->block >= 0) {
      char drv[320] = "";
      if (tc->block >= 0) {
        size_t l = 0;
        PetscCall(PetscStrncpy(drv, ", driven by force along", sizeof(drv)));
        for (int k = 0; k < 3; k++)
          if (tc->drive[k] == TOOL_DRIVE_FORCE) {
            PetscCall(PetscStrlen(drv, &l));
            PetscCall(PetscSNPrintf(drv + l, sizeof(drv) - l, " %c (%g%s)", "xyz"[k], (double)tc->fscale[k], tc->famp[k].n ? " x amplitude" : " x t"));
          }
        PetscCall(PetscStrlen(drv, &l));
        PetscCall(PetscSNPrintf(drv + l, sizeof(drv) - l, ", regularising stiffness %g", (double)tc->kreg));
        if (tc->fnode > 0) {
          PetscCall(PetscStrlen(drv, &l));
          PetscCall(PetscSNPrintf(drv + l, sizeof(drv) - l, ", K_N at most %g N over %g h (%g nodes under it)", (double)tc->fnode, (double)contact->kforce_pen, (double)tc->nunder));
        }
      }
      if (tc->law.delta > 0) {
        size_t l = 0;
        PetscCall(PetscStrlen(drv, &l));
        PetscCall(PetscSNPrintf(drv + l, sizeof(drv) - l, ", gap smoothing %g", (double)tc->law.delta));
      }
      if (tc->kauto) PetscCall(PetscPrintf(contact->comm, "contact: tool %s: %" PetscInt_FMT " slave nodes, K_N per node (automatic), K_T %s, mu %g%s\n", contact->tools[t].name, (PetscInt)loc[0], tc->ktauto ? "per node (automatic)" : "as given", (double)tc->law.mu, drv));
      else PetscCall(PetscPrintf(contact->comm, "contact: tool %s: %" PetscInt_FMT " slave nodes, K_N %g, K_T %g, mu %g%s\n", contact->tools[t].name, (PetscInt)loc[0], (double)tc->law.KN, (double)tc->law.KT, (double)tc->law.mu, drv));
    }
    PetscCheck(loc[0] > 0 || !tc->own, contact->comm, PETSC_ERR_USER_INPUT, "-tool_%s_contact_set '%s' holds no vertex", contact->tools[t].name, tc->nset ? tc->set[0] : contact->set[0]);
    PetscCheck(tc->block < 0 || tc->kreg > 0, contact->comm, PETSC_ERR_USER_INPUT, "tool %s is driven by force but no slave node may touch it (-tool_%s_contact_set)", contact->tools[t].name, contact->tools[t].name);
  }
  PetscFunctionReturn(0);
}

PetscErrorCode ContactDestroy(Contact *c)
{
  Contact contact = *c;

  PetscFunctionBeginUser;
  if (!contact) PetscFunctionReturn(0);
  PetscCall(ContactPairsDestroy(&contact->pairs));
  PetscCall(PetscFree(contact->Ecell));
  if (contact->ntools && contact->mesh) {
    PetscCall(PetscFree4(contact->slave, contact->sgdof, contact->seed, contact->has_seed));
    PetscCall(PetscFree2(contact->seedn, contact->yseed));
    PetscCall(PetscFree4(contact->active_prev, contact->tN_prev, contact->tool_prev, contact->status_prev));
    PetscCall(PetscFree(contact->pmemo));
    PetscCall(PetscFree2(contact->cst_c, contact->cst_t));
    PetscCall(PetscFree3(contact->lam, contact->lam_tool, contact->lam_r));
    PetscCall(PetscFree2(contact->nrel, contact->nrel_tool));
    PetscCall(PetscFree2(contact->lin, contact->lin_ok));
    PetscCall(PetscFree2(contact->kn, contact->kt));
    PetscCall(PetscFree(contact->hn));
    PetscCall(PetscFree(contact->tmask));
  }
  for (PetscInt t = 0; contact->tc && t < contact->ntools; t++)
    for (int k = 0; k < 3; k++) PetscCall(LoadCurveDestroy(&contact->tc[t].famp[k]));
  PetscCall(PetscFree(contact->tc));
  PetscCall(PetscFree(contact->uset));
  PetscCall(ToolsDestroy(contact->ntools, &contact->tools));
  PetscCall(PetscFree(*c));
  PetscFunctionReturn(0);
}

/* the committed state cc was pressed on the tool */
static inline PetscBool PressedOn(const ContactState *cc, PetscInt tool) { return (cc->status != CONTACT_OPEN && cc->tN > 0 && cc->tool == tool) ? PETSC_TRUE : PETSC_FALSE; }

/* the committed normal of node i (0 when it carries no normal force): f - f_T = t_N n */
static void CommittedNormal(const ContactState *cc, double n[3])
{
  double a[3], na;
  n[0] = n[1] = n[2] = 0;
  if (!(cc->status != CONTACT_OPEN && cc->has_frame && cc->tN > 0)) return;
  for (int k = 0; k < 3; k++) a[k] = cc->f[k] - cc->fT[k];
  na = sqrt(a[0] * a[0] + a[1] * a[1] + a[2] * a[2]);
  if (!(na > 0)) return;
  for (int k = 0; k < 3; k++) n[k] = a[k] / na;
}

/* node i, paired with tool now (its law: mu), is held closed (ContactKeepCommitted): it was
   pressed on that tool in the committed state, and the tool is frictionless, or (keep moving)
   moves by a prescribed displacement in the step being solved (ToolContact.moving), not away
   from the node (below), or (keep all) is that or at rest in the step. The keep is for the nodes
   that the predictor would open or push in: a moving tool's by the tool's motion, a resting
   tool's by the extrapolation of the body's motion, which carries a node sliding over a curved
   tool along a chord, off it or into it (the hemisphere with friction, 2.9 mm steps: up to 15 of
   the 30 nodes pressed on the die's fillet, radius 6.35 mm, open at the predictor by up to
   0.034 mm, and that step took 14 Newton iterations against 6 with them held, doc/notes/performance-log.md).
   A force-driven tool's position is an unknown of the solve, set by the nodes' forces on it,
   which a tangential spring anchored at the predictor would fight: never held. Holding every
   frictional tool's nodes failed the NUMISHEET'93 mild-steel cup at the start of the draw (its
   force-driven holder), holding all but the force-driven ones (keep all) the aluminium cup in an
   augmented run, whose default is therefore moving (doc/contact.md, Augmented Lagrangian) */
static inline PetscBool Held(const struct _p_Contact *contact, PetscInt i, PetscInt tool, double mu)
{
  const ContactState *cc = &contact->cst_c[i];
  if (!contact->keep || !PressedOn(cc, tool)) return PETSC_FALSE;
  if (!(mu > 0)) return PETSC_TRUE;
  if (contact->keep < 2 || contact->tc[tool].forced) return PETSC_FALSE;
  if (!contact->tc[tool].moving) return contact->keep == 3 ? PETSC_TRUE : PETSC_FALSE;
  {
    /* keep moving or all: not a node its tool moves away from (the step's translation against the
       committed normal, which points from the tool into the body, below -1/2 of its length; a
       tool sliding past the node, at right angles to the normal, is still held): a retracting
       tool lets its nodes go, and the keep's pull would drag the body along with it
       (kink_retract's lift-off) */
    double n[3];
    const double *dx = contact->tc[tool].step_dx;
    CommittedNormal(cc, n);
    const double  dn = dx[0] * n[0] + dx[1] * n[1] + dx[2] * n[2], d = sqrt(dx[0] * dx[0] + dx[1] * dx[1] + dx[2] * dx[2]);
    return (dn < -0.5 * d) ? PETSC_FALSE : PETSC_TRUE;
  }
}

PetscErrorCode ContactSeed(Contact contact, const PetscScalar *u, PetscReal lambda, PetscBool from_committed)
{
  PetscFunctionBeginUser;
  if (from_committed) { /* a step or a retry: no augmentation yet (on every rank) */
    contact->naug     = 0;
    contact->kscale   = 1; /* the penalties as given: a step and each retry start from them */
    contact->omega[0] = contact->omega[1] = 1;
    contact->aug_pen = contact->aug_dlam = 0;
    for (PetscInt t = 0; t < contact->ntools; t++) {
      ToolContact *tc = &contact->tc[t];
      double       sc[3], sn[3];
      tc->forced = PETSC_FALSE;
      for (int k = 0; k < 3; k++)
        if (tc->drive[k] == TOOL_DRIVE_FORCE) tc->forced = PETSC_TRUE;
      tc->moving = tc->forced ? PETSC_FALSE : PETSC_TRUE;
      for (int k = 0; k < 3; k++) tc->step_dx[k] = 0;
      if (!tc->moving) continue;
      CommittedShift(contact, t, sc);
      CurShift(contact, t, lambda, sn);
      tc->moving = (sn[0] != sc[0] || sn[1] != sc[1] || sn[2] != sc[2]) ? PETSC_TRUE : PETSC_FALSE;
      for (int k = 0; k < 3; k++) tc->step_dx[k] = sn[k] - sc[k];
    }
  }
  PetscCall(ContactPairsSeed(contact->pairs, u, from_committed));
  if (!contact->ns) PetscFunctionReturn(0);
  PetscCall(PetscLogEventBegin(contact->ev_pairing, 0, 0, 0, 0));
  for (PetscInt i = 0; i < contact->ns; i++) {
    double     y[3], t2[3], t1[3];
    Projection pr;
    PetscInt   tool;
    if (from_committed) {
      /* step start or retry: the committed multipliers (the normal one with -contact_augmented
         only) and the committed frame of a node in contact */
      const ContactState *cc = &contact->cst_c[i];
      contact->lam_tool[i]        = cc->status != CONTACT_OPEN ? cc->tool : -1;
      contact->lam[3 * i]         = (contact->aug && cc->status != CONTACT_OPEN) ? cc->lN : 0;
      contact->lam[3 * i + 1]     = cc->lT[0];
      contact->lam[3 * i + 2]     = cc->lT[1];
      contact->lam_r[3 * i] = contact->lam_r[3 * i + 1] = contact->lam_r[3 * i + 2] = 0;

      contact->has_seed[i] = (contact->cst_c[i].has_frame && contact->cst_c[i].status != CONTACT_OPEN) ? PETSC_TRUE : PETSC_FALSE;
      if (contact->has_seed[i])
        for (int k = 0; k < 3; k++) contact->seed[3 * i + k] = contact->cst_c[i].t1[k];
      /* the committed normal, whose tangent plane holds the committed t1: f - f_T = t_N n */
      CommittedNormal(cc, contact->seedn + 3 * i);
    }
    NodePosition(contact, i, u, y);
    for (int k = 0; k < 3; k++) contact->yseed[3 * i + k] = y[k];
    tool = PairNode(contact, i, y, lambda, &pr);
    if (tool < 0) {
      contact->has_seed[i] = PETSC_FALSE;
      continue;
    }
    if (!from_committed) {
      /* start of a Newton iteration: eq 30 for the nodes in contact, t2 = n x t1, t1 = t2 x n,
         with t1 the previous iteration's (the paper's recurrence, -contact_frame_carry
         projection) or that t1 carried to the new normal by the rotation between the normals
         (rotation, ContactFrameCarry: the carried traction does not depend on the frame's
         orientation); a node out of contact forgets its frame (one pressed in the committed
         state too: its committed tangential multipliers are then read on the new chord, an open
         question, doc/notes/performance-log.md) */
      const double lN    = contact->lam_tool[i] == tool ? contact->lam[3 * i] : 0;
      const ContactLaw nl = NodeLaw(contact, i, tool);
      const PetscBool  in = (pr.gap <= 0 || (lN > 0 && lN - nl.KN * pr.gap > 0) || (nl.delta > 0 && lN - nl.KN * pr.gap > -nl.KN * nl.delta) || (nl.reg > 0 && lN - nl.KN * pr.gap > -CONTACT_REG_GAP * nl.KN * nl.reg) || Held(contact, i, tool, nl.mu)) ? PETSC_TRUE : PETSC_FALSE;
      double *s = contact->seed + 3 * i, *sn = contact->seedn + 3 * i;
      if (in && contact->has_seed[i]) {
        double r[3];
        if (contact->frame_rotate) ContactFrameCarry(sn, pr.n, s, r);
        else
          for (int k = 0; k < 3; k++) r[k] = s[k];
        if (!ContactFrame(pr.n, r, t1, t2)) {
          for (int k = 0; k < 3; k++) {
            s[k]  = t1[k];
            sn[k] = pr.n[k];
          }
        }
      } else if (!in) contact->has_seed[i] = PETSC_FALSE;
    }
    if (!contact->has_seed[i]) { /* first contact: the chord of eq 28 (rotation: t1, its projection) */
      double *s = contact->seed + 3 * i, *sn = contact->seedn + 3 * i;
      Chord(contact, tool, &pr, s);
      if (!contact->frame_rotate) sn[0] = sn[1] = sn[2] = 0;
      else if (!ContactFrame(pr.n, s, t1, t2))
        for (int k = 0; k < 3; k++) {
          s[k]  = t1[k];
          sn[k] = pr.n[k];
        }
      else sn[0] = sn[1] = sn[2] = 0;
      contact->has_seed[i] = PETSC_TRUE;
    }
  }
  PetscCall(PetscLogEventEnd(contact->ev_pairing, 0, 0, 0, 0));
  PetscFunctionReturn(0);
}

/* Contribution of slave node i at position y: residual R, tangent K (if asked), trial state */
static int NodeEval(Contact contact, PetscInt i, const double y[3], PetscReal lambda, double R[3], double *K, ContactState *st)
{
  const ContactState *cc = &contact->cst_c[i];
  Projection          pr;
  double              sh[3], shc[3], ds[3], tTn[2] = {0, 0}, dn[9], *dnp = NULL;
  PetscInt            tool;
  ContactLaw          law;
  double              lN  = 0;

  memset(R, 0, 3 * sizeof(double));
  if (K) memset(K, 0, 9 * sizeof(double));
  if (K) contact->lin_ok[i] = 0; /* set below where the law puts the node in contact (not held) */
  *st = *cc;
  for (int k = 0; k < 3; k++) {
    st->y[k]  = y[k];
    st->f[k]  = 0;
    st->fT[k] = 0;
  }
  st->tT[0] = st->tT[1] = 0;
  st->tN                = 0;
  st->status            = CONTACT_OPEN;
  st->has_frame         = PETSC_FALSE;
  tool                  = PairNode(contact, i, y, lambda, &pr);
  st->tool              = tool;
  st->gap               = tool < 0 ? PETSC_INFINITY : pr.gap;
  if (tool < 0) return 0;
  st->patch = pr.patch;
  st->xi    = pr.xi;
  st->eta   = pr.eta;
  law       = NodeLaw(contact, i, tool);
  /* the first Newton iteration with the keep of frictional tools (ContactKeepCommitted 2, 3): a node not
     pressed on this tool in the committed state has no friction there. Such a node enters
     contact at the predictor, where the extrapolation leaves it 0.03-0.12 mm inside the tool: a
     normal force K_N g some 100 times the converged one, and so a friction cone that made it
     stick (K_T held it to the tool) where the converged state has it slip; it flipped to slip at
     the second iteration (hemisphere with friction: 8-11 such nodes a step, doc/notes/performance-log.md). */
  if (contact->keep >= 2 && !PressedOn(cc, tool)) law.mu = 0;
  /* the multipliers of the current solve (the committed state's at the start of a step) */
  if (contact->lam_tool[i] == tool) {
    lN     = contact->lam[3 * i];
    tTn[0] = contact->lam[3 * i + 1];
    tTn[1] = contact->lam[3 * i + 2];
  }
  PetscBool bilateral = PETSC_FALSE;
  if (pr.gap > 0 && !(lN - law.KN * pr.gap > 0) && !(law.delta > 0 && lN - law.KN * pr.gap > -law.KN * law.delta) && !(law.reg > 0 && lN - law.KN * pr.gap > -CONTACT_REG_GAP * law.KN * law.reg)) { /* open (the kernel's test) */
    if (!Held(contact, i, tool, law.mu)) return 0;
    bilateral = PETSC_TRUE;
  }

  /* the frame's seed: the one the pairing set at the iteration's start (eqs 28-30). A node that
     the pairing left unpaired there (beyond the search distance) and that an evaluation within
     the iteration (a line-search trial) finds on a tool keeps the last seed it had, fixed within
     the iteration as the Jacobian assumes; one that never had a seed (the array's zero) takes
     the chord of eq 28 at its projection: it has no committed tangential multipliers there, so
     its force does not depend on the frame */
  double        chord[3];
  const double *seed = contact->seed + 3 * i;
  if (!contact->has_seed[i] && seed[0] == 0 && seed[1] == 0 && seed[2] == 0) {
    Chord(contact, tool, &pr, chord);
    seed = chord;
  }
  const Tool *tl = &contact->tools[tool];
  CurShift(contact, tool, lambda, sh);
  CommittedShift(contact, tool, shc);
  /* slip increment: the node's displacement relative to the tool over the step */
  for (int k = 0; k < 3; k++) ds[k] = (y[k] - cc->y[k]) - (sh[k] - shc[k]);
  if (K && !contact->fd) {
    if (PatchNormalDerivative(&tl->patch[pr.patch], sh, y, &pr, dn)) {
      /* no closed form (Coons patch): the derivative of the normal by central differences */
      const double h = 1e-6 * (1.0 + fabs(y[0]) + fabs(y[1]) + fabs(y[2]));
      for (int j = 0; j < 3; j++) {
        double     yp[3] = {y[0], y[1], y[2]}, ym[3] = {y[0], y[1], y[2]};
        Projection pp, pm;
        yp[j] += h;
        ym[j] -= h;
        if (ToolProject(tl, sh, yp, contact->search, &pp) || ToolProject(tl, sh, ym, contact->search, &pm)) return 1;
        for (int k = 0; k < 3; k++) dn[3 * k + j] = (pp.n[k] - pm.n[k]) / (2 * h);
      }
    }
    dnp = dn;
  }
  if (bilateral) {
    /* a node pressed on this tool in the committed state, held closed although it stands off it
       (ContactKeepCommitted: the first Jacobian of a step and the residual it solves for). The
       kernel at the gap where the bracket has its full slope (0, or -delta with the smoothing)
       and the committed normal force as multiplier: stiffness K_N and the friction cone of the
       committed force, t_N0 = tN_c (+ K_N delta); the normal force then continued linearly to the
       actual gap, t_N = lN - K_N g (a pull where negative), R += -(t_N - t_N0) n, with its
       curvature term -(t_N - t_N0) dn/dy. On a frictional tool the node is also held tangentially
       by a spring K_T (I - n n^T) (y - y_0) anchored at its position y_0 at the iteration's start
       (the predictor): the slip tangent has no stiffness along the slip, and with the small
       committed forces of such nodes the linearised sheet would slide along the tool as a whole
       (measured: the hemisphere with friction, doc/notes/performance-log.md). The spring's force vanishes at
       the anchor, where the keep's residual is evaluated (the keep ends before the line search);
       its tangent there is K_T (I - n n^T), the terms of dn/dy vanishing with y - y_0, so the
       Jacobian stays the derivative of the residual (-snes_test_jacobian). */
    const double g0 = law.delta > 0 ? -law.delta : (law.reg > 0 ? -law.reg : 0.0), tb = lN - law.KN * pr.gap;
    double       tN0;
    st->status = ContactNodeEvalAug(&law, cc->tN, g0, pr.n, dnp, seed, tTn, ds, R, contact->fd ? NULL : K, st->t1, &tN0, st->tT);
    for (int k = 0; k < 3; k++) R[k] -= (tb - tN0) * pr.n[k];
    if (K && dnp)
      for (int k = 0; k < 9; k++) K[k] -= (tb - tN0) * dnp[k];
    if (K && !contact->fd && st->status == CONTACT_SLIP && law.mu > 0) {
      /* the held node's cone is that of the committed force, mu t_N0, whatever its gap: the
         kernel's slip tangent carries d(mu t_N)/dy = -mu K_N n^T along the slip (eq 23's third
         column), which the held residual does not have; taken out */
      const double nt = sqrt(st->tT[0] * st->tT[0] + st->tT[1] * st->tT[1]);
      double       t1[3], t2[3];
      if (nt > 0 && !ContactFrame(pr.n, st->t1, t1, t2)) /* t2 = n x t1 */
        for (int r = 0; r < 3; r++)
          for (int c = 0; c < 3; c++) K[3 * r + c] += law.mu * law.KN * (st->tT[0] * st->t1[r] + st->tT[1] * t2[r]) / nt * pr.n[c];
    }
    if (law.mu > 0) {
      const double *y0 = contact->yseed + 3 * i;
      double        d[3], dn = 0;
      for (int k = 0; k < 3; k++) d[k] = y[k] - y0[k];
      for (int k = 0; k < 3; k++) dn += pr.n[k] * d[k];
      for (int k = 0; k < 3; k++) R[k] += law.KT * (d[k] - dn * pr.n[k]);
      if (K)
        for (int r = 0; r < 3; r++)
          for (int c = 0; c < 3; c++) K[3 * r + c] += law.KT * ((r == c) - pr.n[r] * pr.n[c]);
    }
    st->tN = tb;
  } else {
    st->status = ContactNodeEvalAug(&law, lN, pr.gap, pr.n, dnp, seed, tTn, ds, R, contact->fd ? NULL : K, st->t1, &st->tN, st->tT);
    if (K && st->status != CONTACT_OPEN) contact->lin_ok[i] = 1;
  }
  st->has_frame = PETSC_TRUE;
  for (int k = 0; k < 3; k++) {
    st->f[k]  = -R[k];
    st->fT[k] = st->f[k] - st->tN * pr.n[k];
  }
  {
    const double dsn = ds[0] * pr.n[0] + ds[1] * pr.n[1] + ds[2] * pr.n[2];
    double       dt2 = 0;
    for (int k = 0; k < 3; k++) dt2 += (ds[k] - dsn * pr.n[k]) * (ds[k] - dsn * pr.n[k]);
    st->slip = cc->slip + sqrt(dt2);
  }
  if (K && contact->fd) {
    /* per-node 3x3 finite-difference tangent: the contact block of a node depends on that node only */
    const double h = 1e-7 * (1.0 + fabs(y[0]) + fabs(y[1]) + fabs(y[2]));
    for (int j = 0; j < 3; j++) {
      double       yp[3] = {y[0], y[1], y[2]}, ym[3] = {y[0], y[1], y[2]}, Rp[3], Rm[3];
      ContactState sp;
      yp[j] += h;
      ym[j] -= h;
      if (NodeEval(contact, i, yp, lambda, Rp, NULL, &sp) || NodeEval(contact, i, ym, lambda, Rm, NULL, &sp)) return 1;
      for (int k = 0; k < 3; k++) K[3 * k + j] = (Rp[k] - Rm[k]) / (2 * h);
    }
  }
  return 0;
}

/* a force-driven direction whose contacts' stiffness (the diagonal of the tool's block) is at most
   this fraction of the tool's regularising stiffness has none: it is regularised (ContactAssemble) */
#define TOOL_STIFF_MIN 1e-8

/* Tools driven by force: the coupling with the tool unknowns.

   A tool T with unknowns has the displacement d (3 components; along a force-driven direction the
   unknown, along the others the prescribed displacement, which does not depend on the unknowns).
   Everything a node i paired with T contributes depends on d only through y - d:
   * the projection of y on the tool translated by d is the projection of y - d on the tool at rest,
     translated by d: the gap g = (y - x).n, the normal n and its derivative dn/dy are functions of
     y - d (the closest point x moves with the tool);
   * the slip increment ds = (y - y_n) - (d - d_n) is a function of y - d (the committed y_n, d_n
     are fixed within a step);
   * the frame seed and the multipliers are fixed within a Newton iteration.
   So R_i = R_i(y - d), and with K_i = dR_i/dy (the node's 3x3 block, analytic or by differences)

       dR_i/dd = -K_i                (node rows, tool columns)

   restricted to the force-driven columns. The tool's residual rows along a force-driven
   direction k are r_k = sum_i f_i,k - F_k(t), f_i = -R_i the force on node i (the force the tool
   exerts on the body), so

       dr_k/dy_i = -K_i[k, :],       dr_k/dd_l = sum_i K_i[k, l]   (l force-driven).

   Along a direction that is not force-driven the row is r_k = d_k - (prescribed displacement):
   an identity row. While no node paired with the tool is in contact (the rows above vanish), the
   diagonal of the force-driven rows is the regularising stiffness kreg (the sum of the penalties
   K_N of the tool's nodes; so is that of a direction its contacts give no stiffness, below), and
   while the target presses the tool onto the body the force row holds the penalty law continued
   across the nearest node's gap (ContactToolResidual): Newton closes the gap without a singular
   matrix; a converged state has contact (or a zero target), so its residual, and the
   equilibrium, are exact (doc/contact.md). */
PetscErrorCode ContactAssemble(Contact contact, const PetscScalar *u, PetscReal lambda, PetscScalar *f, Mat J, PetscScalar *coo_v, PetscInt *nfail_out)
{
  PetscInt     nfail = 0;
  const PetscInt nb = contact->nb, nt = contact->ntools;
  PetscScalar *kt   = NULL; /* 9 nb: the tool x tool blocks, sums over this rank's nodes */
  PetscInt    *nact = NULL; /* nb: nodes in contact with each tool                      */

  PetscFunctionBeginUser;
  *nfail_out = 0;
  PetscCheck(!ContactPairsNum(contact->pairs) || !coo_v, PETSC_COMM_SELF, PETSC_ERR_PLIB, "contact pairs need the MatSetValues assembly");
  PetscCall(ContactPairsAssemble(contact->pairs, u, f, J, &nfail));
  *nfail_out = nfail;
  if (!contact->ns && !(nb && J)) PetscFunctionReturn(0);
  PetscCall(PetscLogEventBegin(contact->ev_contact, 0, 0, 0, 0));
  if (nb && J) PetscCall(PetscCalloc2(9 * nb, &kt, nb, &nact));
  /* pairing phase: every slave node to its tool and patch (kept in the node's memo) */
  PetscCall(PetscLogEventBegin(contact->ev_pairing, 0, 0, 0, 0));
  for (PetscInt i = 0; i < contact->ns; i++) {
    double     y[3];
    Projection pr;
    NodePosition(contact, i, u, y);
    (void)PairNode(contact, i, y, lambda, &pr);
  }
  PetscCall(PetscLogEventEnd(contact->ev_pairing, 0, 0, 0, 0));
  for (PetscInt i = 0; i < contact->ns; i++) {
    double         y[3], R[3], K[9];
    const PetscInt v = contact->slave[i];
    if (f && contact->nrel_tool[i] >= 0) { /* a released tool's nodal force: a dead load, no tangent */
      const PetscReal *w = contact->nrel + NREL * i, sh = NodalReleaseShare(w, lambda);
      for (int k = 0; k < 3; k++) f[contact->mesh->vloff[v] + k] -= sh * w[k];
    }
    NodePosition(contact, i, u, y);
    if (NodeEval(contact, i, y, lambda, R, J ? K : NULL, &contact->cst_t[i])) {
      nfail++;
      if (J) PetscCall(PetscArrayzero(K, 9)); /* keep the coordinate-assembly slots aligned */
      contact->lin_ok[i] = 0; /* (the finite-difference tangent fails after the law's status) */
      if (!J) continue;
    }
    if (f)
      for (int k = 0; k < 3; k++) f[contact->mesh->vloff[v] + k] += R[k];
    if (J) {
      const PetscInt *sg = contact->sgdof + 3 * i;
      PetscReal      *ln = contact->lin + NLIN * i;
      for (int k = 0; k < 3; k++) ln[k] = R[k];
      for (int k = 0; k < 9; k++) ln[3 + k] = K[k];
      for (int k = 0; k < 3; k++) ln[12 + k] = contact->pmemo[i].pr.n[k];
      if (coo_v) {
        PetscInt m = 0;
        for (int r = 0; r < 3; r++)
          for (int c = 0; c < 3; c++)
            if (sg[r] >= 0 && sg[c] >= 0) coo_v[m++] = K[3 * r + c];
        coo_v += m;
      } else PetscCall(MatSetValues(J, 3, sg, 3, sg, K, ADD_VALUES));
      /* the coupling with the unknowns of every tool the node may pair with (zero but for its tool) */
      for (PetscInt t = 0; nb && t < nt; t++) {
        const ToolContact *tc = &contact->tc[t];
        const PetscBool    mine = contact->cst_t[i].tool == t ? PETSC_TRUE : PETSC_FALSE;
        PetscScalar        C[9], D[9];
        PetscInt           td[3];
        if (tc->block < 0 || !contact->tmask[i * nt + t]) continue;
        if (mine && contact->cst_t[i].status != CONTACT_OPEN) nact[tc->block]++;
        for (int r = 0; r < 3; r++) {
          td[r] = contact->tdof0 + 3 * tc->block + r;
          for (int c = 0; c < 3; c++) {
            const PetscBool fr = tc->drive[r] == TOOL_DRIVE_FORCE ? PETSC_TRUE : PETSC_FALSE, fc = tc->drive[c] == TOOL_DRIVE_FORCE ? PETSC_TRUE : PETSC_FALSE;
            C[3 * r + c] = (mine && fc) ? -K[3 * r + c] : 0; /* node rows, tool columns */
            D[3 * r + c] = (mine && fr) ? -K[3 * r + c] : 0; /* tool rows, node columns */
            if (mine && fr && fc) kt[9 * tc->block + 3 * r + c] += K[3 * r + c];
          }
        }
        if (coo_v) {
          for (int r = 0; r < 3; r++)
            for (int c = 0; c < 3; c++)
              if (sg[r] >= 0) *coo_v++ = C[3 * r + c];
          for (int r = 0; r < 3; r++)
            for (int c = 0; c < 3; c++)
              if (sg[c] >= 0) *coo_v++ = D[3 * r + c];
        } else {
          PetscCall(MatSetValues(J, 3, sg, 3, td, C, ADD_VALUES));
          PetscCall(MatSetValues(J, 3, td, 3, sg, D, ADD_VALUES));
        }
      }
    }
  }
  if (nb && J) {
    /* the tool x tool blocks: this rank's sums; on the owner the identity of the directions that
       are not force-driven and the regularisation of a force-driven direction without stiffness:
       no node in contact, or (kdiag, every rank's sum of the diagonal) contacts that give it none.
       The latter are contacts that slip along that direction (the slip tangent K_T mu t_N/|t_T^e|
       (I - e e^T) has no stiffness along e, and on a face parallel to it the normal gives none:
       exactly zero for a sheet in plane strain sliding on a flat die) or carry a vanishing normal
       force (-contact_gap_smoothing: the stiffness K_N dt_N/dx -> 0 at the band's lower end). The
       column of the tool's unknown is then zero, and so the pivot. The residual is not changed:
       the direction holds its position for the iteration, and the converged state, where the
       regularisation is inactive or the force is met anyway, is the exact equilibrium. */
    PetscReal *kdiag;
    PetscCall(PetscCalloc1(3 * nb, &kdiag));
    for (PetscInt b = 0; b < nb; b++)
      for (int k = 0; k < 3; k++) kdiag[3 * b + k] = PetscRealPart(kt[9 * b + 4 * k]);
    PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, nact, (PetscMPIInt)nb, MPIU_INT, MPI_SUM, contact->comm));
    PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, kdiag, (PetscMPIInt)(3 * nb), MPIU_REAL, MPI_SUM, contact->comm));
    for (PetscInt t = 0; t < nt; t++) {
      const ToolContact *tc = &contact->tc[t];
      PetscScalar       *E;
      PetscInt           td[3];
      if (tc->block < 0) continue;
      E = kt + 9 * tc->block;
      for (int k = 0; k < 3; k++) {
        const PetscBool stiff = (nact[tc->block] && kdiag[3 * tc->block + k] > TOOL_STIFF_MIN * tc->kreg) ? PETSC_TRUE : PETSC_FALSE;
        td[k] = contact->tdof0 + 3 * tc->block + k;
        if (contact->towner) E[4 * k] += tc->drive[k] == TOOL_DRIVE_FORCE ? (stiff ? 0 : tc->kreg) : 1;
      }
      if (coo_v) {
        for (int k = 0; k < 9; k++) *coo_v++ = E[k];
      } else PetscCall(MatSetValues(J, 3, td, 3, td, E, ADD_VALUES));
    }
    PetscCall(PetscFree2(kt, nact));
    PetscCall(PetscFree(kdiag));
  }
  *nfail_out = nfail;
  PetscCall(PetscLogEventEnd(contact->ev_contact, 0, 0, 0, 0));
  PetscFunctionReturn(0);
}

PetscErrorCode ContactGetCOO(Contact contact, PetscCount *n, PetscInt *ci, PetscInt *cj)
{
  PetscCount     m  = 0;
  const PetscInt nt = contact->ntools;

  PetscFunctionBeginUser;
#define COO_ADD(I, J) \
  do { \
    if (ci) { \
      ci[m] = (I); \
      cj[m] = (J); \
    } \
    m++; \
  } while (0)
  for (PetscInt i = 0; i < contact->ns; i++) {
    const PetscInt *sg = contact->sgdof + 3 * i;
    for (int r = 0; r < 3; r++)
      for (int c = 0; c < 3; c++)
        if (sg[r] >= 0 && sg[c] >= 0) COO_ADD(sg[r], sg[c]);
    for (PetscInt t = 0; contact->nb && t < nt; t++) {
      const PetscInt b = contact->tc[t].block, td = contact->tdof0 + 3 * b;
      if (b < 0 || !contact->tmask[i * nt + t]) continue;
      for (int r = 0; r < 3; r++)
        for (int c = 0; c < 3; c++)
          if (sg[r] >= 0) COO_ADD(sg[r], td + c);
      for (int r = 0; r < 3; r++)
        for (int c = 0; c < 3; c++)
          if (sg[c] >= 0) COO_ADD(td + r, sg[c]);
    }
  }
  for (PetscInt t = 0; contact->nb && t < nt; t++) {
    const PetscInt b = contact->tc[t].block, td = contact->tdof0 + 3 * b;
    if (b < 0) continue;
    for (int r = 0; r < 3; r++)
      for (int c = 0; c < 3; c++) COO_ADD(td + r, td + c);
  }
#undef COO_ADD
  *n = m;
  PetscFunctionReturn(0);
}

PetscErrorCode ContactToolResidual(Contact contact, PetscReal lambda, PetscReal *r)
{
  const PetscInt nb = contact->nb;
  PetscReal     *fs, *loc, *all;
  PetscMPIInt    size;

  PetscFunctionBeginUser;
  if (!nb) PetscFunctionReturn(0);
  PetscCallMPI(MPI_Comm_size(contact->comm, &size));
  /* per tool: the force on the body; the nodes in contact, the smallest gap of its paired nodes
     and the normal there (this rank's, then every rank's) */
  PetscCall(PetscCalloc3(3 * nb, &fs, 5 * nb, &loc, 5 * nb * size, &all));
  for (PetscInt b = 0; b < nb; b++) loc[5 * b + 1] = PETSC_MAX_REAL;
  for (PetscInt i = 0; i < contact->ns; i++) {
    const ContactState *st = &contact->cst_t[i];
    const PairMemo     *pm = &contact->pmemo[i];
    if (pm->tool >= 0 && contact->tc[pm->tool].block >= 0 && pm->pr.gap < loc[5 * contact->tc[pm->tool].block + 1]) {
      PetscReal *l = loc + 5 * contact->tc[pm->tool].block;
      l[1]         = pm->pr.gap;
      for (int k = 0; k < 3; k++) l[2 + k] = pm->pr.n[k];
    }
    if (st->tool < 0 || st->status == CONTACT_OPEN || contact->tc[st->tool].block < 0) continue;
    for (int k = 0; k < 3; k++) fs[3 * contact->tc[st->tool].block + k] += st->f[k];
    loc[5 * contact->tc[st->tool].block] += 1;
  }
  PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, fs, (PetscMPIInt)(3 * nb), MPIU_REAL, MPI_SUM, contact->comm));
  PetscCallMPI(MPI_Allgather(loc, (PetscMPIInt)(5 * nb), MPIU_REAL, all, (PetscMPIInt)(5 * nb), MPIU_REAL, contact->comm));
  for (PetscInt t = 0; t < contact->ntools; t++) {
    const ToolContact *tc = &contact->tc[t];
    const PetscInt     b  = tc->block;
    double             sh[3], T[3] = {0, 0, 0}, gmin = PETSC_MAX_REAL, n[3] = {0, 0, 0}, nact = 0, tn = 0, tns = 0;
    if (b < 0) continue;
    ToolShift(&contact->tools[t], lambda, sh);
    for (PetscMPIInt p = 0; p < size; p++) { /* the smallest gap (the lowest rank on a tie) */
      const PetscReal *l = all + 5 * nb * p + 5 * b;
      nact += l[0];
      if (l[1] < gmin) {
        gmin = l[1];
        for (int k = 0; k < 3; k++) n[k] = l[2 + k];
      }
    }
    for (int k = 0; k < 3; k++)
      if (tc->drive[k] == TOOL_DRIVE_FORCE) { /* the target along the normal, and its slope from the right */
        T[k] = ToolTarget(tc, k, lambda);
        tn += T[k] * n[k];
        tns += tc->fscale[k] * (tc->famp[k].n ? LoadCurveSlope(&tc->famp[k], lambda) : 1) * n[k];
      }
    for (int k = 0; k < 3; k++) {
      PetscReal f = fs[3 * b + k];
      /* no node in contact and the target pressing the tool onto the body (or zero and about to,
         so that the residual is continuous in the load there): the penalty law continued across
         the gap of the tool's nearest paired node with the regularising stiffness, f = -k_reg g n
         (zero at first touch, where the contact rows take over). A zero target otherwise: the row
         is zero, the tool holds its position (out of contact and without a force it has no
         equilibrium position of its own: where it stops depends on the iterate at which its last
         node left contact). */
      if (nact == 0 && gmin < PETSC_MAX_REAL && (tn > 0 || (tn == 0 && tns > 0))) f = -tc->kreg * gmin * n[k];
      r[3 * b + k] = tc->drive[k] == TOOL_DRIVE_FORCE ? f - T[k] : tc->d[k] - (sh[k] + tc->hold[k]);
    }
  }
  PetscCall(PetscFree3(fs, loc, all));
  PetscFunctionReturn(0);
}

#define CKPT_TOOL 16 /* per tool: committed displacement (3), path length, drive (3), held offset (3), release (flag, its two times, its three forces) */

PetscInt ContactToolCheckpointWidth(Contact contact) { return CKPT_TOOL * contact->ntools; }

PetscErrorCode ContactToolCheckpointPack(Contact contact, PetscReal *v)
{
  PetscFunctionBeginUser;
  for (PetscInt t = 0; t < contact->ntools; t++) {
    const ToolContact *tc = &contact->tc[t];
    PetscReal         *w  = v + CKPT_TOOL * t;
    for (int k = 0; k < 3; k++) {
      w[k]     = tc->dc[k];
      w[4 + k] = (PetscReal)tc->drive[k];
      w[7 + k] = tc->hold[k];
    }
    w[3]  = tc->path_c;
    w[10] = tc->release ? 1 : 0;
    w[11] = tc->rel_t[0];
    w[12] = tc->rel_t[1];
    for (int k = 0; k < 3; k++) w[13 + k] = tc->rel_f[k];
  }
  PetscFunctionReturn(0);
}

PetscErrorCode ContactToolCheckpointUnpack(Contact contact, const PetscReal *v)
{
  PetscFunctionBeginUser;
  for (PetscInt t = 0; t < contact->ntools; t++) {
    ToolContact     *tc = &contact->tc[t];
    const PetscReal *w  = v + CKPT_TOOL * t;
    if (w[10] != 0) { /* a release under way: its force curves again */
      tc->release  = PETSC_TRUE;
      tc->rel_t[0] = w[11];
      tc->rel_t[1] = w[12];
      for (int k = 0; k < 3; k++) tc->rel_f[k] = w[13 + k];
      PetscCall(ReleaseDrive(contact, t));
    }
    for (int k = 0; k < 3; k++) {
      const ToolDrive dr = w[4 + k] != 0 ? TOOL_DRIVE_FORCE : TOOL_DRIVE_DISPLACEMENT;
      PetscCheck(dr == TOOL_DRIVE_DISPLACEMENT || tc->famp[k].n || tc->fscale[k] != 0 || tc->drive[k] == TOOL_DRIVE_FORCE, contact->comm, PETSC_ERR_FILE_UNEXPECTED, "-restart: the checkpoint drives tool %s by force along %c, this run has no force for it", contact->tools[t].name, "xyz"[k]);
      tc->dc[k]    = w[k];
      tc->drive[k] = dr;
      tc->hold[k]  = w[7 + k];
    }
    tc->path_c = w[3];
  }
  PetscFunctionReturn(0);
}

/* in contact with a force: the node presses on the tool (a touching node, g = 0, carries none) */
static inline PetscBool Pressed(const ContactState *st) { return (st->status != CONTACT_OPEN && st->tN > 0) ? PETSC_TRUE : PETSC_FALSE; }

PetscErrorCode ContactCommit(Contact contact, PetscReal lambda)
{
  PetscFunctionBeginUser;
  PetscCall(ContactPairsCommit(contact->pairs));
  if (contact->ns) PetscCall(PetscArraycpy(contact->cst_c, contact->cst_t, contact->ns));
  /* the penalties' factor the next step starts from (-contact_augmented_growth_keep) */
  if (contact->aug && contact->aug_keep) contact->kscale_c = contact->kscale;
  /* the tools' displacements: the solved ones along the force-driven directions */
  for (PetscInt t = 0; t < contact->ntools; t++) {
    ToolContact *tc = &contact->tc[t];
    double       sh[3];
    if (tc->block < 0) continue;
    CurShift(contact, t, lambda, sh);
    tc->path_c += PetscSqrtReal(PetscSqr(sh[0] - tc->dc[0]) + PetscSqr(sh[1] - tc->dc[1]) + PetscSqr(sh[2] - tc->dc[2]));
    for (int k = 0; k < 3; k++) tc->dc[k] = sh[k];
  }
  /* the multipliers the next step starts from: the forces of this one (the Uzawa update
     lN <- <lN - K_N g> = t_N, lT <- the returned tT); the normal one only with augmentation */
  for (PetscInt i = 0; i < contact->ns; i++) {
    ContactState *s = &contact->cst_c[i];
    s->lN           = (contact->aug && s->status != CONTACT_OPEN) ? s->tN : 0;
    s->lT[0]        = s->tT[0];
    s->lT[1]        = s->tT[1];
  }
  contact->lambda_c = lambda;
  PetscFunctionReturn(0);
}

PetscBool ContactAugmented(Contact contact) { return ((contact->aug && contact->ntools) || ContactPairsAugmented(contact->pairs)) ? PETSC_TRUE : PETSC_FALSE; }
PetscBool ContactToolsAugmented(Contact contact) { return (contact->aug && contact->ntools) ? PETSC_TRUE : PETSC_FALSE; }
PetscInt  ContactAugmentedMax(Contact contact) { return contact->aug_max; }

/* One Uzawa update from the trial state of the last evaluation (the converged Newton solution at
   the current multipliers): lN <- <lN - K_N g> (= t_N), lT <- the return map of the augmented
   predictor lT + K_T dg_T (= t_T); converged when the largest penetration of a pressed node and the
   largest stick slip of the step (|change of lT|/K_T at a sticking node) are below the tolerance
   and no multiplier changed by more than -contact_augmented_multiplier_tol times the largest. */
static PetscErrorCode ToolsAugment(Contact contact, PetscBool inexact, PetscBool *converged, PetscBool *held, PetscReal *maxpen, PetscReal *dlambda)
{
  PetscReal loc[6] = {0, 0, 0, 0, 0, 0}, gl[6]; /* penetration, stick slip, change, largest multiplier, normal change, tangential change */
  PetscReal cnt[3] = {0, 0, 0}, gcnt[3];         /* nodes pressed, sticking, slipping (monitor) */
  PetscReal dot[4] = {0, 0, 0, 0}, gdot[4], omega[2] = {1, 1};
  PetscBool conv;

  PetscFunctionBeginUser;
  /* the Uzawa increments r = (t_N, t_T) - (lN, lT) at the solution */
  for (PetscInt i = 0; i < contact->ns; i++) {
    const ContactState *st   = &contact->cst_t[i];
    const PetscBool     in   = st->status != CONTACT_OPEN ? PETSC_TRUE : PETSC_FALSE;
    const PetscInt      nt   = in ? st->tool : -1;
    const PetscReal     nN   = in ? st->tN : 0, nT[2] = {in ? st->tT[0] : 0, in ? st->tT[1] : 0};
    const PetscBool     same = (contact->lam_tool[i] == nt && nt >= 0) ? PETSC_TRUE : PETSC_FALSE;
    PetscReal          *l = contact->lam + 3 * i, r[3];
    if (!same) l[0] = l[1] = l[2] = 0;
    contact->lam_tool[i] = nt;
    r[0]            = nN - l[0];
    r[1]            = nT[0] - l[1];
    r[2]            = nT[1] - l[2];
    const PetscReal dT = PetscSqrtReal(r[1] * r[1] + r[2] * r[2]);
    loc[2]             = PetscMax(loc[2], PetscSqrtReal(r[0] * r[0] + dT * dT));
    loc[3]             = PetscMax(loc[3], PetscSqrtReal(nN * nN + nT[0] * nT[0] + nT[1] * nT[1]));
    loc[4]             = PetscMax(loc[4], PetscAbsReal(r[0]));
    loc[5]             = PetscMax(loc[5], dT);
    if (Pressed(st)) cnt[0] += 1;
    if (in && st->status == CONTACT_STICK) cnt[1] += 1;
    if (in && st->status == CONTACT_SLIP) cnt[2] += 1;
    if (Pressed(st)) loc[0] = PetscMax(loc[0], -st->gap);
    if (st->status == CONTACT_STICK && nt >= 0 && contact->tc[nt].law.mu > 0) loc[1] = PetscMax(loc[1], dT / NodeLaw(contact, i, nt).KT);
    for (int k = 0; k < 3; k++) {
      const PetscReal d = r[k] - contact->lam_r[3 * i + k];
      dot[2 * (k > 0)] += contact->lam_r[3 * i + k] * d;
      dot[2 * (k > 0) + 1] += d * d;
    }
  }
  PetscCall(MPIU_Allreduce(loc, gl, 6, MPIU_REAL, MPIU_MAX, contact->comm));
  if (contact->aug_monitor) PetscCall(MPIU_Allreduce(cnt, gcnt, 3, MPIU_REAL, MPIU_SUM, contact->comm));
  PetscCall(MPIU_Allreduce(dot, gdot, 4, MPIU_REAL, MPIU_SUM, contact->comm));
  /* Aitken's relaxation of the fixed-point iteration lambda <- lambda + r (Irons and Tuck): the
     first update of a step is the plain Uzawa one, the later ones lambda + omega r with
     omega = -omega_prev r_prev.(r - r_prev)/|r - r_prev|^2, kept in [1, 100]; one factor for the
     normal multipliers, one for the tangential ones (their rates differ: K_N against K_T) */
  conv = (gl[0] <= contact->tol && gl[1] <= contact->tol && gl[2] <= contact->aug_mtol * gl[3]) ? PETSC_TRUE : PETSC_FALSE;
  *held = (inexact && gl[0] <= contact->tol && gl[1] <= contact->tol) ? PETSC_TRUE : PETSC_FALSE;
  if (contact->aug_monitor)
    PetscCall(PetscPrintf(contact->comm, "  augmentation %" PetscInt_FMT "%s: penetration %.3e stick slip %.3e change %.3e (normal %.3e, tangential %.3e) of %.3e; pressed %d stick %d slip %d; factor %g%s\n", contact->naug + 1, inexact ? " (inexact)" : "", (double)gl[0], (double)gl[1], (double)gl[2], (double)gl[4], (double)gl[5], (double)gl[3], (int)gcnt[0], (int)gcnt[1], (int)gcnt[2], (double)contact->kscale, *held ? ", held" : (conv ? ", converged" : "")));
  if (*held) {
    /* an inexact solve whose penetration and stick slip are below the tolerance: the multipliers
       stay, the solve is completed at them and checked again (an update that is still needed then
       is made from the converged state; the relaxation starts again) */
    for (PetscInt i = 0; i < 3 * contact->ns; i++) contact->lam_r[i] = 0;
    contact->omega[0] = contact->omega[1] = 1;
    contact->aug_pen  = gl[0];
    contact->aug_dlam = gl[2];
    *maxpen           = gl[0];
    *dlambda          = gl[2];
    *converged        = conv;
    PetscFunctionReturn(0);
  }
  for (int k = 0; k < 2; k++)
    if (contact->naug > 0 && gdot[2 * k + 1] > 0) omega[k] = PetscMin(PetscMax(-contact->omega[k] * gdot[2 * k] / gdot[2 * k + 1], 1.0), 100.0);
  for (PetscInt i = 0; i < contact->ns; i++) {
    const ContactState *st = &contact->cst_t[i];
    PetscReal          *l  = contact->lam + 3 * i, *r = contact->lam_r + 3 * i;
    const PetscBool     in = st->status != CONTACT_OPEN ? PETSC_TRUE : PETSC_FALSE;
    r[0]                   = (in ? st->tN : 0) - l[0];
    r[1]                   = (in ? st->tT[0] : 0) - l[1];
    r[2]                   = (in ? st->tT[1] : 0) - l[2];
    for (int k = 0; k < 3; k++) l[k] += omega[k > 0] * r[k];
    /* back into the admissible set: lN >= 0, |lT| <= mu lN */
    l[0] = PetscMax(l[0], 0);
    {
      const PetscReal nT = PetscSqrtReal(l[1] * l[1] + l[2] * l[2]), cap = (st->tool >= 0 ? contact->tc[st->tool].law.mu : 0) * l[0];
      if (nT > cap) {
        l[1] = nT > 0 ? l[1] * cap / nT : 0;
        l[2] = nT > 0 ? l[2] * cap / nT : 0;
      }
    }
  }
  contact->omega[0] = omega[0];
  contact->omega[1] = omega[1];
  /* Uzawa's rate is the penalty's stiffness against the body's: with a soft penalty each update
     removes only a small part of the penetration. An update that did not reduce the largest
     penetration by 4 (and left it above the tolerance) makes the penalties of the rest of the step
     -contact_augmented_growth times stiffer (at most -contact_augmented_growth_max); the
     multipliers carry on (the force of a node is its multiplier plus its penalty times its
     penetration, so the converged forces do not depend on the factor), the relaxation restarts. */
  if (contact->naug > 0 && contact->aug_grow > 1 && gl[0] > contact->tol && gl[0] > 0.25 * contact->aug_pen && contact->kscale * contact->aug_grow <= contact->aug_grow_max * (1 + 1e-12)) {
    contact->kscale *= contact->aug_grow;
    contact->omega[0] = contact->omega[1] = 1;
  }
  contact->naug++;
  contact->aug_pen  = gl[0];
  contact->aug_dlam = gl[2];
  *maxpen      = gl[0];
  *dlambda     = gl[2];
  *converged   = conv;
  PetscFunctionReturn(0);
}

/* the tools' update (with -contact_augmented) and the augmented contact pairs' (contact_pair.h):
   converged when both are; the largest penetration and multiplier change of the two */
PetscErrorCode ContactAugment(Contact contact, PetscBool inexact, PetscBool *converged, PetscBool *held, PetscReal *maxpen, PetscReal *dlambda)
{
  PetscBool pconv = PETSC_TRUE;
  PetscReal ppen = 0, pdl = 0;

  PetscFunctionBeginUser;
  *converged = PETSC_TRUE;
  *held      = PETSC_FALSE;
  *maxpen = *dlambda = 0;
  if (contact->aug && contact->ntools) PetscCall(ToolsAugment(contact, inexact, converged, held, maxpen, dlambda));
  if (ContactPairsAugmented(contact->pairs)) {
    PetscCall(ContactPairsAugment(contact->pairs, &pconv, &ppen, &pdl));
    *converged = (*converged && pconv) ? PETSC_TRUE : PETSC_FALSE;
    *maxpen    = PetscMax(*maxpen, ppen);
    *dlambda   = PetscMax(*dlambda, pdl);
  }
  PetscFunctionReturn(0);
}

/* Start of a step's augmentation (after the frame seeds from the committed state, which reset the
   multipliers to the committed ones and the penalties' factor to 1): the factor committed with the
   last step (-contact_augmented_growth_keep), and the relative residual of the inexact solves. */
PetscErrorCode ContactAugmentStart(Contact contact, PetscReal *inexact)
{
  PetscFunctionBeginUser;
  *inexact = (contact->aug && contact->ntools) ? contact->aug_inexact : 0; /* (the pairs' solves are exact) */
  if (contact->aug) contact->kscale = contact->aug_keep ? contact->kscale_c : 1;
  PetscFunctionReturn(0);
}

/* -contact_augmented_soften: the Newton solve of a step failed. The augmented Lagrangian does not
   need a stiff penalty for its accuracy (the multipliers carry the force, the penetration is
   driven below the tolerance by the updates), while a stiff one makes Newton's contact terms switch
   hard (the seed punch at K_N = 1e6 per node: first solves of 12 to 23 iterations, the failed ones
   cut). So the retry of the step starts from penalties -contact_augmented_growth times softer than
   the committed factor (at most down to 1/-contact_augmented_growth_max times the given ones) and,
   with -contact_augmented_growth_keep, the next steps start from it too (the growth makes them
   stiffer again where the updates converge too slowly). softened: PETSC_FALSE when off, without
   growth_keep, or at the floor. */
PetscErrorCode ContactAugmentSoften(Contact contact, PetscBool *softened, PetscReal *factor)
{
  PetscFunctionBeginUser;
  *softened = PETSC_FALSE;
  *factor   = contact->kscale_c;
  if (!contact->aug || !contact->ntools || !contact->aug_soften || !contact->aug_keep || !(contact->aug_grow > 1)) PetscFunctionReturn(0);
  if (contact->kscale_c / contact->aug_grow < (1 - 1e-12) / contact->aug_grow_max) PetscFunctionReturn(0);
  contact->kscale_c /= contact->aug_grow;
  *softened = PETSC_TRUE;
  *factor   = contact->kscale_c;
  PetscFunctionReturn(0);
}

PetscErrorCode ContactAugmentTolerances(Contact contact, PetscReal *tol, PetscReal *mtol)
{
  PetscFunctionBeginUser;
  PetscReal pt;
  *tol  = (contact->aug && contact->ntools) ? contact->tol : 0;
  *mtol = contact->aug_mtol;
  PetscCall(ContactPairsAugmentTolerance(contact->pairs, &pt));
  *tol = PetscMax(*tol, pt);
  PetscFunctionReturn(0);
}


/* Chattering: nodes whose contact status changed in the last Newton iteration although they carry
   a significant normal force, before (a node leaving) or after (a node entering): more than 1e-3
   of the largest normal force and more than fmin. Returns the count over all ranks and the
   smallest such node id. */
PetscErrorCode ContactChatter(Contact contact, PetscReal fmin, PetscInt *count, PetscInt *node)
{
  PetscReal tmax = 0;
  PetscInt  c = 0, id = PETSC_MAX_INT;

  PetscFunctionBeginUser;
  /* significant: above 1e-3 of the largest normal force of the step, committed or at the last two
     iterates (the committed forces too: where a release brings every force to zero, a node flipping
     with a force of round-off is no chattering, and 1e-3 of the vanishing forces alone made the
     check depend on the round-off of the run), and above fmin (the Newton solve's tolerance: a
     node whose force is within it changes the residual by no more than the solve accepts) */
  for (PetscInt i = 0; i < contact->ns; i++) tmax = PetscMax(tmax, PetscMax(contact->cst_c[i].tN, PetscMax(contact->cst_t[i].tN, contact->tN_prev[i])));
  PetscCall(MPIU_Allreduce(MPI_IN_PLACE, &tmax, 1, MPIU_REAL, MPIU_MAX, contact->comm));
  for (PetscInt i = 0; i < contact->ns; i++) {
    const PetscBool active = contact->cst_t[i].status != CONTACT_OPEN;
    if (active != contact->active_prev[i] && PetscMax(contact->cst_t[i].tN, contact->tN_prev[i]) > PetscMax(1e-3 * tmax, fmin)) {
      c++;
      id = PetscMin(id, contact->mesh->node_id[contact->slave[i]]);
    }
  }
  PetscCall(MPIU_Allreduce(&c, count, 1, MPIU_INT, MPI_SUM, contact->comm));
  PetscCall(MPIU_Allreduce(&id, node, 1, MPIU_INT, MPI_MIN, contact->comm));
  PetscFunctionReturn(0);
}

PetscErrorCode ContactProjectPressed(Contact contact, const PetscScalar *u, PetscReal lambda, Vec U, PetscInt *nmoved, PetscReal *dmax)
{
  PetscInt  n = 0;
  PetscReal dm = 0;

  PetscFunctionBeginUser;
  for (PetscInt i = 0; i < contact->ns; i++) {
    const ContactState *cc = &contact->cst_c[i];
    double              y[3], sh[3];
    Projection          pr;
    PetscScalar         d[3];
    double              dg;
    NodePosition(contact, i, u, y);
    if (cc->status != CONTACT_OPEN && cc->tN > 0 && cc->tool >= 0 && !contact->tools[cc->tool].absent) {
      double shc[3];
      CurShift(contact, cc->tool, lambda, sh);
      CommittedShift(contact, cc->tool, shc);
      /* a tool moved by its prescribed displacement carries its nodes through the extrapolation of
         the body, which moves the whole thickness; the projection would move the contact face alone */
      if (!contact->tc[cc->tool].forced && (sh[0] != shc[0] || sh[1] != shc[1] || sh[2] != shc[2])) continue;
      if (ToolProject(&contact->tools[cc->tool], sh, y, contact->search, &pr)) continue;
      dg = cc->gap - pr.gap;
    } else continue;
    if (!(PetscAbsReal(dg) <= 0.1 * (contact->hn ? contact->hn[i] : contact->hmin))) continue;
    for (int k = 0; k < 3; k++) {
      d[k] = dg * pr.n[k];
      if (contact->sgdof[3 * i + k] >= 0) PetscCall(VecSetValue(U, contact->sgdof[3 * i + k], d[k], ADD_VALUES));
    }
    n++;
    dm = PetscMax(dm, PetscAbsReal(dg));
  }
  PetscCall(VecAssemblyBegin(U));
  PetscCall(VecAssemblyEnd(U));
  PetscCall(MPIU_Allreduce(&n, nmoved, 1, MPIU_INT, MPI_SUM, contact->comm));
  PetscCall(MPIU_Allreduce(&dm, dmax, 1, MPIU_REAL, MPIU_MAX, contact->comm));
  PetscFunctionReturn(0);
}

PetscErrorCode ContactStepLimit(Contact contact, const PetscScalar *u, PetscReal lambda, Vec Y, const PetscReal *ytool, PetscReal depth, PetscReal *lmax)
{
  const PetscScalar *y;
  PetscInt           rstart;
  PetscReal          lm = PETSC_MAX_REAL;

  PetscFunctionBeginUser;
  PetscCall(VecGetOwnershipRange(Y, &rstart, NULL));
  PetscCall(VecGetArrayRead(Y, &y));
  for (PetscInt i = 0; i < contact->ns; i++) {
    double         x[3], dy[3] = {0, 0, 0}, dn;
    Projection     pr;
    const PetscInt t = (NodePosition(contact, i, u, x), PairNode(contact, i, x, lambda, &pr));
    if (t < 0) continue;
    for (int k = 0; k < 3; k++)
      if (contact->sgdof[3 * i + k] >= 0) dy[k] = PetscRealPart(y[contact->sgdof[3 * i + k] - rstart]);
    if (ytool && contact->tc[t].block >= 0) /* a force-driven tool moves with the step too */
      for (int k = 0; k < 3; k++)
        if (contact->tc[t].drive[k] == TOOL_DRIVE_FORCE) dy[k] -= ytool[3 * contact->tc[t].block + k];
    dn = pr.n[0] * dy[0] + pr.n[1] * dy[1] + pr.n[2] * dy[2]; /* the step x - lambda Y: the gap falls by lambda dn */
    {
      const PetscReal h = depth * (contact->hn ? contact->hn[i] : contact->hmin), p = -pr.gap;
      if (dn > 0 && h > 0 && p < h) lm = PetscMin(lm, (h - p) / dn);
    }
  }
  PetscCall(VecRestoreArrayRead(Y, &y));
  PetscCall(MPIU_Allreduce(&lm, lmax, 1, MPIU_REAL, MPIU_MIN, contact->comm));
  PetscFunctionReturn(0);
}

/* what changed at the last evaluation against the start of the Newton iteration (ContactRecordActive),
   per tool: nodes that entered and left its contact, the largest normal force among them (before
   for a node leaving, after for one entering), nodes pressed now, the largest penetration and
   normal force now (collective) */
PetscErrorCode ContactStatusChanges(Contact contact, ContactToolStatus *ts)
{
  const PetscInt nt = contact->ntools;
  PetscReal     *cnt, *mx;

  PetscFunctionBeginUser;
  PetscCall(PetscCalloc2(4 * nt + 1, &cnt, 4 * nt + 1, &mx));
  for (PetscInt i = 0; i < contact->ns; i++) {
    const ContactState *s   = &contact->cst_t[i];
    const PetscInt      now = s->status != CONTACT_OPEN ? s->tool : -1, was = contact->tool_prev[i];
    if (now >= 0) {
      const PetscReal h = contact->hn ? contact->hn[i] : contact->hmin;
      cnt[3 * now + 2] += 1;
      mx[3 * now + 1] = PetscMax(mx[3 * now + 1], -s->gap);
      mx[3 * now + 2] = PetscMax(mx[3 * now + 2], s->tN);
      if (h > 0) mx[3 * nt + now] = PetscMax(mx[3 * nt + now], -s->gap / h);
    }
    if (now == was) {
      if (now >= 0 && s->status != contact->status_prev[i]) cnt[3 * nt + now] += 1;
      continue;
    }
    if (now >= 0) {
      cnt[3 * now] += 1;
      mx[3 * now] = PetscMax(mx[3 * now], s->tN);
    }
    if (was >= 0) {
      cnt[3 * was + 1] += 1;
      mx[3 * was] = PetscMax(mx[3 * was], contact->tN_prev[i]);
    }
  }
  PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, cnt, (PetscMPIInt)(4 * nt), MPIU_REAL, MPIU_SUM, contact->comm));
  PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, mx, (PetscMPIInt)(4 * nt), MPIU_REAL, MPIU_MAX, contact->comm));
  for (PetscInt t = 0; t < nt; t++) {
    ts[t].nin     = (PetscInt)cnt[3 * t];
    ts[t].nout    = (PetscInt)cnt[3 * t + 1];
    ts[t].nactive = (PetscInt)cnt[3 * t + 2];
    ts[t].nslip   = (PetscInt)cnt[3 * nt + t];
    ts[t].fchange = mx[3 * t];
    ts[t].pen     = mx[3 * t + 1];
    ts[t].fmax    = mx[3 * t + 2];
    ts[t].penh    = mx[3 * nt + t];
  }
  PetscCall(PetscFree2(cnt, mx));
  PetscFunctionReturn(0);
}

PetscErrorCode ContactLinearRelease(Contact contact, Vec Y, const PetscReal *ytool, PetscReal tmin, const char *released, PetscInt *n, PetscInt *idx)
{
  const PetscScalar *y;
  PetscInt           rstart;

  PetscFunctionBeginUser;
  *n = 0;
  PetscCall(VecGetOwnershipRange(Y, &rstart, NULL));
  PetscCall(VecGetArrayRead(Y, &y));
  for (PetscInt i = 0; i < contact->ns; i++) {
    const PetscReal *ln = contact->lin + NLIN * i;
    const PetscInt   t  = contact->cst_t[i].tool;
    double           u[3], tlin = 0;
    if (!contact->lin_ok[i] || released[i] || t < 0) continue;
    /* the step x - Y: the node moves by -Y_i, a force-driven tool by -Y_tool; R_i depends on
       their difference (ContactAssemble) */
    for (int k = 0; k < 3; k++) {
      u[k] = contact->sgdof[3 * i + k] >= 0 ? -PetscRealPart(y[contact->sgdof[3 * i + k] - rstart]) : 0;
      if (ytool && contact->tc[t].block >= 0 && contact->tc[t].drive[k] == TOOL_DRIVE_FORCE) u[k] += ytool[3 * contact->tc[t].block + k];
    }
    for (int r = 0; r < 3; r++) {
      double Rl = ln[r];
      for (int c = 0; c < 3; c++) Rl += ln[3 + 3 * r + c] * u[c];
      tlin -= ln[12 + r] * Rl; /* the normal force n.f, f = -R */
    }
    if (tlin < -tmin) idx[(*n)++] = i;
  }
  PetscCall(VecRestoreArrayRead(Y, &y));
  PetscFunctionReturn(0);
}

PetscErrorCode ContactLinearBlock(Contact contact, PetscInt i, PetscInt *nd, PetscInt dof[6], PetscReal M[36], PetscReal r[6])
{
  const PetscReal *ln = contact->lin + NLIN * i;
  const PetscInt   t  = contact->cst_t[i].tool, b = t >= 0 ? contact->tc[t].block : -1;
  PetscInt         comp[6], m = 0;
  PetscReal        sgn[6];

  PetscFunctionBeginUser;
  /* the unknowns of the block: the node's free components (sign +1) and its tool's force-driven
     directions (sign -1: R_i depends on y - d) */
  for (int k = 0; k < 3; k++)
    if (contact->sgdof[3 * i + k] >= 0) {
      dof[m]  = contact->sgdof[3 * i + k];
      comp[m] = k;
      sgn[m++] = 1;
    }
  for (int k = 0; b >= 0 && k < 3; k++)
    if (contact->tc[t].drive[k] == TOOL_DRIVE_FORCE) {
      dof[m]  = contact->tdof0 + 3 * b + k;
      comp[m] = k;
      sgn[m++] = -1;
    }
  for (PetscInt a = 0; a < m; a++) {
    r[a] = sgn[a] * ln[comp[a]];
    for (PetscInt c = 0; c < m; c++) M[6 * a + c] = sgn[a] * sgn[c] * ln[3 + 3 * comp[a] + comp[c]];
  }
  *nd = m;
  PetscFunctionReturn(0);
}

PetscErrorCode ContactRecordActive(Contact contact)
{
  PetscFunctionBeginUser;
  PetscCall(ContactPairsRecordActive(contact->pairs));
  for (PetscInt i = 0; i < contact->ns; i++) {
    contact->active_prev[i] = contact->cst_t[i].status != CONTACT_OPEN;
    contact->tN_prev[i]     = contact->cst_t[i].status != CONTACT_OPEN ? contact->cst_t[i].tN : 0;
    contact->tool_prev[i]   = contact->cst_t[i].status != CONTACT_OPEN ? contact->cst_t[i].tool : -1;
    contact->status_prev[i] = contact->cst_t[i].status;
  }
  PetscFunctionReturn(0);
}

/* the direction along which a tool's force and travel are reported: its -motion vector, or the displacement at the last
   point of its -path (the whole process, stages included), +z for a fixed tool */
static void ToolDirection(const Tool *t, double m[3])
{
  double sh[3], nrm;
  if (t->motion[0] != 0 || t->motion[1] != 0 || t->motion[2] != 0)
    for (int k = 0; k < 3; k++) sh[k] = t->motion[k];
  else if (t->npath > 0)
    for (int k = 0; k < 3; k++) sh[k] = t->path[4 * (t->npath - 1) + 1 + k];
  else ToolShift(t, 1.0, sh);
  nrm = sqrt(sh[0] * sh[0] + sh[1] * sh[1] + sh[2] * sh[2]);
  if (nrm > 0)
    for (int k = 0; k < 3; k++) m[k] = sh[k] / nrm;
  else {
    m[0] = m[1] = 0;
    m[2]        = 1;
  }
}

PetscErrorCode ContactGetToolResult(Contact contact, PetscInt t, PetscReal lambda, ContactToolResult *r)
{
  const Tool *tl = &contact->tools[t];
  /* sums: force along dir, f (3), normal resultant (3), tangential resultant (3), active, stick, slip */
  double      loc[15] = {0}, pen = 0, gl[15], gpen;

  PetscFunctionBeginUser;
  PetscCall(PetscMemzero(r, sizeof(*r)));
  r->name = tl->name;
  ToolDirection(tl, r->dir);
  if (contact->tc[t].block >= 0) { /* the solved displacement of the committed state */
    CommittedShift(contact, t, r->shift);
    r->path = contact->tc[t].path_c;
  } else {
    ToolShift(tl, lambda, r->shift);
    r->path = ToolTravel(tl, lambda);
  }
  r->travel = r->shift[0] * r->dir[0] + r->shift[1] * r->dir[1] + r->shift[2] * r->dir[2];
  for (PetscInt i = 0; i < contact->ns; i++) {
    const ContactState *st = &contact->cst_c[i];
    if (contact->nrel_tool[i] == t) { /* released by nodal forces: what they still exert */
      const PetscReal *w = contact->nrel + NREL * i, sh = NodalReleaseShare(w, lambda);
      if (sh > 0) {
        loc[0] += sh * (w[0] * r->dir[0] + w[1] * r->dir[1] + w[2] * r->dir[2]);
        for (int k = 0; k < 3; k++) {
          loc[1 + k] += sh * w[k];
          loc[4 + k] += sh * (w[k] - w[3 + k]);
          loc[7 + k] += sh * w[3 + k];
        }
        loc[10] += 1;
      }
    }
    if (st->tool != t || st->status == CONTACT_OPEN) continue;
    loc[0] += st->f[0] * r->dir[0] + st->f[1] * r->dir[1] + st->f[2] * r->dir[2];
    for (int k = 0; k < 3; k++) {
      loc[1 + k] += st->f[k];
      loc[4 + k] += st->f[k] - st->fT[k];
      loc[7 + k] += st->fT[k];
    }
    if (Pressed(st)) {
      loc[10] += 1;
      if (contact->tc[t].law.mu > 0) {
        loc[11] += st->status == CONTACT_STICK;
        loc[12] += st->status == CONTACT_SLIP;
      }
    }
    pen = PetscMax(pen, -st->gap);
    if (Pressed(st)) {
      loc[13] += PetscMax(0, -st->gap);
      loc[14] += 1;
    }
  }
  PetscCall(MPIU_Allreduce(loc, gl, 15, MPI_DOUBLE, MPI_SUM, contact->comm));
  PetscCall(MPIU_Allreduce(&pen, &gpen, 1, MPI_DOUBLE, MPI_MAX, contact->comm));
  r->force = gl[0];
  for (int k = 0; k < 3; k++) r->f[k] = gl[1 + k];
  r->fn      = sqrt(gl[4] * gl[4] + gl[5] * gl[5] + gl[6] * gl[6]);
  r->ft      = sqrt(gl[7] * gl[7] + gl[8] * gl[8] + gl[9] * gl[9]);
  r->active  = (PetscInt)gl[10];
  r->stick   = (PetscInt)gl[11];
  r->slip    = (PetscInt)gl[12];
  r->max_pen = gpen;
  r->mean_pen = gl[14] > 0 ? gl[13] / gl[14] : 0;
  r->augmentations = contact->naug;
  r->dlambda = contact->aug_dlam;
  PetscFunctionReturn(0);
}

PetscErrorCode ContactGetNodeFields(Contact contact, PetscReal *cg, PetscReal *cn, PetscReal *ct, PetscReal *cst, PetscReal *csl)
{
  const Mesh *m = contact->mesh;

  PetscFunctionBeginUser;
  PetscCall(PetscArrayzero(cn, m->nvo));
  PetscCall(PetscArrayzero(ct, 3 * m->nvo));
  PetscCall(PetscArrayzero(cst, m->nvo));
  PetscCall(PetscArrayzero(csl, m->nvo));
  for (PetscInt k = 0; k < m->nvo; k++) cg[k] = contact->search;
  for (PetscInt i = 0; i < contact->ns; i++) {
    const ContactState *st = &contact->cst_c[i];
    const PetscInt      r  = m->vrow[contact->slave[i]];
    cg[r]                  = PetscIsInfReal(st->gap) ? contact->search : st->gap;
    cn[r]                  = st->tN;
    /* 0 open or touching without force, 1 stick, 2 slip, 3 pressed without friction */
    cst[r] = !Pressed(st) ? 0 : (contact->tc[st->tool].law.mu > 0 ? st->status : 3);
    csl[r] = st->slip;
    for (int k = 0; k < 3; k++) ct[3 * r + k] = st->fT[k];
  }
  PetscCall(ContactPairsGetNodeFields(contact->pairs, cg, cn, ct, cst, csl));
  PetscFunctionReturn(0);
}

#define CKPT_NST 28                  /* the node state's doubles in a row (24 before the multipliers, 27 before the penalties' factor) */
#define CKPT_NCS (CKPT_NST + 1 + NREL) /* doubles per vertex for the contact state: the node state, then the release by nodal forces (its tool, its NREL doubles) */

PetscInt ContactCheckpointWidth(void) { return CKPT_NCS; }

PetscErrorCode ContactCheckpointPack(Contact contact, PetscReal *rows)
{
  PetscFunctionBeginUser;
  PetscCall(PetscArrayzero(rows, CKPT_NCS * contact->mesh->nvo));
  for (PetscInt i = 0; i < contact->ns; i++) {
    const ContactState *s = &contact->cst_c[i];
    const PetscReal     v[CKPT_NST] = {1, (PetscReal)s->status, (PetscReal)s->tool, (PetscReal)s->patch, s->xi, s->eta, s->tT[0], s->tT[1], s->t1[0], s->t1[1], s->t1[2], (PetscReal)s->has_frame, s->y[0], s->y[1], s->y[2], s->gap, s->tN, s->f[0], s->f[1], s->f[2], s->fT[0], s->fT[1], s->fT[2], s->slip, s->lN, s->lT[0], s->lT[1], contact->kscale_c};
    PetscReal          *row = rows + CKPT_NCS * contact->mesh->vrow[contact->slave[i]];
    PetscCall(PetscArraycpy(row, v, CKPT_NST));
    row[CKPT_NST] = (PetscReal)contact->nrel_tool[i];
    PetscCall(PetscArraycpy(row + CKPT_NST + 1, contact->nrel + NREL * i, NREL));
  }
  PetscFunctionReturn(0);
}

PetscErrorCode ContactCheckpointUnpack(Contact contact, const PetscReal *rows, PetscReal lambda, const char *path)
{
  PetscInt  bad = PETSC_MAX_INT;
  PetscReal kc  = 0;

  PetscFunctionBeginUser;
  for (PetscInt i = 0; i < contact->ns; i++) {
    const PetscReal *d = rows + CKPT_NCS * contact->mesh->vrow[contact->slave[i]];
    ContactState    *s = &contact->cst_c[i];
    if (d[0] != 1) {
      bad = PetscMin(bad, contact->mesh->node_id[contact->slave[i]]);
      continue;
    }
    s->status    = (PetscInt)d[1];
    s->tool      = (PetscInt)d[2];
    s->patch     = (PetscInt)d[3];
    s->xi        = d[4];
    s->eta       = d[5];
    s->tT[0]     = d[6];
    s->tT[1]     = d[7];
    s->has_frame = d[11] != 0 ? PETSC_TRUE : PETSC_FALSE;
    for (int k = 0; k < 3; k++) {
      s->t1[k] = d[8 + k];
      s->y[k]  = d[12 + k];
      s->f[k]  = d[17 + k];
      s->fT[k] = d[20 + k];
    }
    s->gap  = d[15];
    s->tN   = d[16];
    s->slip  = d[23];
    s->lN    = d[24];
    s->lT[0] = d[25];
    s->lT[1] = d[26];
    kc       = PetscMax(kc, d[27]);
    contact->nrel_tool[i] = (PetscInt)d[CKPT_NST];
    PetscCall(PetscArraycpy(contact->nrel + NREL * i, d + CKPT_NST + 1, NREL));
  }
  PetscCall(MPIU_Allreduce(MPI_IN_PLACE, &bad, 1, MPIU_INT, MPI_MIN, contact->comm));
  /* the augmentation's penalty factor (the same in every slave node's row; a rank without slave
     nodes takes it from the others) */
  PetscCall(MPIU_Allreduce(MPI_IN_PLACE, &kc, 1, MPIU_REAL, MPIU_MAX, contact->comm));
  contact->kscale_c = kc > 0 ? kc : 1;
  PetscCheck(bad == PETSC_MAX_INT, contact->comm, PETSC_ERR_FILE_UNEXPECTED, "-restart %s: node id %" PetscInt_FMT " is a slave node here but not in the checkpoint", path, bad);
  if (contact->ns) PetscCall(PetscArraycpy(contact->cst_t, contact->cst_c, contact->ns));
  contact->lambda_c = lambda;
  PetscFunctionReturn(0);
}

/* the node sets of the slave nodes, the union over the tools (for the partition that balances them, MeshSetContactSets) */
PetscErrorCode ContactGetSets(Contact c, PetscInt *n, char (**sets)[ATRITO_NAME_LEN])
{
  PetscInt na;
  PetscFunctionBeginUser;
  PetscCall(ContactGetAreaSets(c, &na, sets)); /* builds the union of the tools' sets */
  *n    = c->ntools ? c->nuset : 0;
  *sets = c->uset;
  PetscFunctionReturn(0);
}

/* Stages (stage.h, stepper.c): read access to a tool, and tools that are absent in a stage */
PetscErrorCode ContactGetTool(Contact contact, PetscInt t, const Tool **tool)
{
  PetscFunctionBeginUser;
  PetscCheck(t >= 0 && t < contact->ntools, contact->comm, PETSC_ERR_ARG_OUTOFRANGE, "tool %" PetscInt_FMT " of %" PetscInt_FMT, t, contact->ntools);
  *tool = &contact->tools[t];
  PetscFunctionReturn(0);
}

/* An absent tool pairs no node (ToolProject gives no point); the nodes in contact with it lose
   their contact state (open, no force, no frame, no multipliers), committed and trial, and every
   node is paired again. */
PetscErrorCode ContactSetToolPresent(Contact contact, PetscInt t, PetscBool present)
{
  PetscFunctionBeginUser;
  PetscCheck(t >= 0 && t < contact->ntools, contact->comm, PETSC_ERR_ARG_OUTOFRANGE, "tool %" PetscInt_FMT " of %" PetscInt_FMT, t, contact->ntools);
  contact->tools[t].absent = present ? 0 : 1;
  for (PetscInt i = 0; i < contact->ns; i++) {
    ContactState *s = &contact->cst_c[i];
    contact->pmemo[i].tool = -2;
    if (present || s->tool != t) continue;
    s->status    = CONTACT_OPEN;
    s->tool      = -1;
    s->patch     = -1;
    s->has_frame = PETSC_FALSE;
    s->gap       = PETSC_INFINITY;
    s->tN = s->lN = 0;
    s->tT[0] = s->tT[1] = s->lT[0] = s->lT[1] = 0;
    for (int k = 0; k < 3; k++) s->f[k] = s->fT[k] = 0;
    contact->cst_t[i] = *s;
  }
  PetscFunctionReturn(0);
}

PetscErrorCode ContactKeepCommitted(Contact contact, PetscInt keep)
{
  PetscFunctionBeginUser;
  PetscCheck(keep >= 0 && keep <= 3, contact->comm, PETSC_ERR_ARG_OUTOFRANGE, "ContactKeepCommitted: mode %" PetscInt_FMT " must be 0, 1, 2 or 3", keep);
  contact->keep = keep;
  PetscFunctionReturn(0);
}
