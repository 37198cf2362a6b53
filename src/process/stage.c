/* Stages of the process (stage.h): options, names checked against the case's tools and
   conditions. */
#include <string.h>
#include "stage.h"
#include "tool.h"
#include "options.h"

static PetscErrorCode CheckName(MPI_Comm comm, const char *opt, const char *name)
{
  PetscFunctionBeginUser;
  PetscCheck(name[0] && strlen(name) < 64, comm, PETSC_ERR_USER_INPUT, "%s: empty name or longer than 63 characters", opt);
  for (const char *c = name; *c; c++) PetscCheck((*c >= 'a' && *c <= 'z') || (*c >= 'A' && *c <= 'Z') || (*c >= '0' && *c <= '9') || *c == '_', comm, PETSC_ERR_USER_INPUT, "%s: name '%s' may only contain letters, digits and _", opt, name);
  PetscFunctionReturn(0);
}

/* a name list option of the stage block: -1 when not given (all), else the names ("none": 0) */
static PetscErrorCode NameList(PetscOptionItems *PetscOptionsObject, const char *key, const char *text, const char *full, PetscInt max, char (*out)[64], PetscInt *n)
{
  char     *names[ATRITO_MAX_BC > STAGE_MAX_TOOLS ? ATRITO_MAX_BC : STAGE_MAX_TOOLS];
  PetscInt  cnt = max;
  PetscBool set;

  PetscFunctionBeginUser;
  *n = -1;
  PetscCall(PetscOptionsStringArray(key, text, NULL, names, &cnt, &set));
  if (!set) PetscFunctionReturn(0);
  *n = 0;
  for (PetscInt k = 0; k < cnt; k++) {
    PetscErrorCode ierr = 0;
    if (!(cnt == 1 && !strcmp(names[k], "none"))) {
      ierr = CheckName(PetscOptionsObject->comm, full, names[k]);
      if (!ierr) PetscCall(PetscStrncpy(out[(*n)++], names[k], 64));
    }
    PetscCall(PetscFree(names[k]));
    PetscCall(ierr);
  }
  PetscFunctionReturn(0);
}

PetscErrorCode StagesSetFromOptions(MPI_Comm comm, Stages *sg, PetscInt load_steps, PetscReal dt_max, PetscReal dt_min)
{
  char     *names[STAGE_MAX];
  PetscInt  n = STAGE_MAX;
  PetscBool set;
  PetscReal t = 0;

  PetscFunctionBeginUser;
  PetscCall(PetscMemzero(sg, sizeof(*sg)));
  PetscOptionsBegin(comm, NULL, "Stages", NULL);
  PetscCall(PetscOptionsStringArray("-stage_names", "Stages of the process, in the order of the process time, each described by -stage_<name>_duration, _steps, _dt_max, _tools, _bcs (default: one stage of duration 1)", NULL, names, &n, &set));
  PetscOptionsEnd();
  sg->given = set && n > 0 ? PETSC_TRUE : PETSC_FALSE;
  if (!sg->given) {
    sg->n = 1;
    PetscCall(PetscStrncpy(sg->s[0].name, "load", sizeof(sg->s[0].name)));
    sg->s[0].t0     = 0;
    sg->s[0].t1     = 1;
    sg->s[0].dt0    = PetscMin(1.0 / load_steps, dt_max); /* the first increment within -load_dt_max, as with stages */
    sg->s[0].dt_max = dt_max;
    sg->s[0].dt_min = dt_min;
    sg->s[0].ntools = sg->s[0].nbcs = -1;
    sg->s[0].nrelease = -1;
    sg->s[0].predictor = -1;
    sg->T           = 1;
    PetscFunctionReturn(0);
  }
  sg->n = n;
  for (PetscInt k = 0; k < n; k++) {
    PetscErrorCode ierr = CheckName(comm, "-stage_names", names[k]);
    if (!ierr) PetscCall(PetscStrncpy(sg->s[k].name, names[k], sizeof(sg->s[k].name)));
    PetscCall(PetscFree(names[k]));
    PetscCall(ierr);
    for (PetscInt j = 0; j < k; j++) PetscCheck(strcmp(sg->s[j].name, sg->s[k].name), comm, PETSC_ERR_USER_INPUT, "-stage_names: name '%s' given twice", sg->s[k].name);
  }
  for (PetscInt k = 0; k < n; k++) {
    Stage         *s = &sg->s[k];
    char           prefix[96], title[96], opt[128];
    PetscInt       steps = load_steps;
    PetscReal      D     = 1;
    PetscBool      sset, mset;
    PetscErrorCode ierr = 0;

    PetscCall(PetscSNPrintf(prefix, sizeof(prefix), "stage_%s_", s->name));
    PetscCall(PetscSNPrintf(title, sizeof(title), "Stage %s", s->name));
    PetscOptionsBegin(comm, prefix, title, NULL);
    PetscCall(PetscOptionsReal("-duration", "Duration of the stage in process time (> 0)", NULL, D, &D, NULL));
    PetscCall(PetscOptionsInt("-steps", "First increment: the duration over this (default -load_steps)", NULL, steps, &steps, &sset));
    s->dt_max = dt_max * D;
    PetscCall(PetscOptionsReal("-dt_max", "Largest increment in the stage (default -load_dt_max times the duration; with -stage_<s>_steps the first increment)", NULL, s->dt_max, &s->dt_max, &mset));
    s->dt_min = dt_min * D;
    PetscCall(PetscSNPrintf(opt, sizeof(opt), "-stage_%s_tools", s->name));
    ierr = NameList(PetscOptionsObject, "-tools", "Tools present in the stage (default: all; none: no tool)", opt, STAGE_MAX_TOOLS, s->tools, &s->ntools);
    if (!ierr) {
      PetscCall(PetscSNPrintf(opt, sizeof(opt), "-stage_%s_bcs", s->name));
      ierr = NameList(PetscOptionsObject, "-bcs", "Dirichlet conditions active in the stage (default: all; none: no condition)", opt, ATRITO_MAX_BC, s->bcs, &s->nbcs);
    }
    if (!ierr) {
      PetscCall(PetscSNPrintf(opt, sizeof(opt), "-stage_%s_release", s->name));
      ierr = NameList(PetscOptionsObject, "-release", "Tools released in the stage (default: none); with -stage_<s>_release_mode tool each is driven by force along the axes in which it carries force, the target going linearly from the force at the stage's start to zero at its end", opt, STAGE_MAX_TOOLS, s->release, &s->nrelease);
    }
    if (!ierr) {
      const char *const modes[] = {"tool", "nodes"};
      PetscInt          mode    = STAGE_RELEASE_TOOL;
      PetscCall(PetscOptionsEList("-release_mode", "How -stage_<s>_release releases its tools: tool (the tool driven by its falling force) or nodes (the tool removed at the stage's start, the contact force of each of its nodes a load falling linearly to zero)", NULL, modes, 2, modes[mode], &mode, NULL));
      s->release_mode = mode;
    }
    if (!ierr) {
      /* the order of Predictor (stepper.h) after "default" */
      const char *const preds[] = {"default", "none", "extrapolate", "tangent", "auto"};
      PetscInt          p       = 0;
      PetscCall(PetscOptionsEList("-predictor", "Start of each step of the stage: default (-load_predictor), none (the committed state), extrapolate, tangent or auto, as -load_predictor", NULL, preds, 5, preds[p], &p, NULL));
      s->predictor = p - 1;
    }
    PetscOptionsEnd();
    PetscCall(ierr);
    PetscCheck(D > 0 && PetscIsNormalReal(D), comm, PETSC_ERR_USER_INPUT, "-stage_%s_duration %g must be > 0", s->name, (double)D);
    PetscCheck(steps >= 1, comm, PETSC_ERR_USER_INPUT, "-stage_%s_steps %" PetscInt_FMT " must be >= 1", s->name, steps);
    s->dt0 = D / steps;
    if (sset && !mset) s->dt_max = PetscMax(s->dt_max, s->dt0);
    PetscCheck(s->dt_max > 0 && s->dt_max <= D, comm, PETSC_ERR_USER_INPUT, "-stage_%s_dt_max %g must lie in (0, duration %g]", s->name, (double)s->dt_max, (double)D);
    s->dt0 = PetscMin(s->dt0, s->dt_max);
    s->dt_min = PetscMin(s->dt_min, s->dt0);
    s->t0  = t;
    t += D;
    s->t1 = t; /* the stage ends where the next starts, exactly */
  }
  sg->T = t;
  PetscFunctionReturn(0);
}

/* the index of the tool named `name`, -1 if none */
static PetscErrorCode FindTool(Contact contact, const char *name, PetscInt *found)
{
  PetscFunctionBeginUser;
  *found = -1;
  for (PetscInt t = 0; t < ContactNumTools(contact); t++) {
    const Tool *tl = NULL;
    PetscCall(ContactGetTool(contact, t, &tl));
    if (!strcmp(tl->name, name)) *found = t;
  }
  PetscFunctionReturn(0);
}

PetscErrorCode StagesSetUp(Stages *sg, BCs *bcs, Contact contact)
{
  const PetscInt nt = ContactNumTools(contact);

  PetscFunctionBeginUser;
  PetscCheck(nt <= STAGE_MAX_TOOLS, PETSC_COMM_WORLD, PETSC_ERR_SUP, "-tool_names: at most %d tools with stages", STAGE_MAX_TOOLS);
  for (PetscInt k = 0; k < sg->n; k++) {
    Stage *s = &sg->s[k];
    for (PetscInt t = 0; t < nt; t++) s->tool_on[t] = s->ntools < 0 ? PETSC_TRUE : PETSC_FALSE;
    for (PetscInt j = 0; j < s->ntools; j++) {
      PetscInt found;
      PetscCall(FindTool(contact, s->tools[j], &found));
      PetscCheck(found >= 0, PETSC_COMM_WORLD, PETSC_ERR_USER_INPUT, "-stage_%s_tools: unknown tool '%s' (not in -tool_names)", s->name, s->tools[j]);
      s->tool_on[found] = PETSC_TRUE;
    }
    for (PetscInt t = 0; t < nt; t++) s->tool_release[t] = PETSC_FALSE;
    for (PetscInt j = 0; j < s->nrelease; j++) {
      PetscInt found;
      PetscCall(FindTool(contact, s->release[j], &found));
      PetscCheck(found >= 0, PETSC_COMM_WORLD, PETSC_ERR_USER_INPUT, "-stage_%s_release: unknown tool '%s' (not in -tool_names)", s->name, s->release[j]);
      PetscCheck(s->tool_on[found], PETSC_COMM_WORLD, PETSC_ERR_USER_INPUT, "-stage_%s_release: tool '%s' is not present in the stage (-stage_%s_tools)", s->name, s->release[j], s->name);
      s->tool_release[found] = PETSC_TRUE;
      if (s->release_mode == STAGE_RELEASE_TOOL) PetscCall(ContactReserveToolUnknowns(contact, found));
    }
    for (PetscInt b = 0; b < bcs->n; b++) s->bc_on[b] = s->nbcs < 0 ? PETSC_TRUE : PETSC_FALSE;
    for (PetscInt j = 0; j < s->nbcs; j++) {
      PetscInt found = -1;
      for (PetscInt b = 0; b < bcs->n; b++)
        if (!strcmp(bcs->bc[b].name, s->bcs[j])) found = b;
      PetscCheck(found >= 0, PETSC_COMM_WORLD, PETSC_ERR_USER_INPUT, "-stage_%s_bcs: unknown condition '%s' (not in -bc_names)", s->name, s->bcs[j]);
      s->bc_on[found] = PETSC_TRUE;
    }
  }
  /* a tool removed at a stage's start while a force of its options still drives it (not released
     in the stage before): refused, the force would vanish at once */
  for (PetscInt k = 1; k < sg->n; k++)
    for (PetscInt t = 0; t < nt; t++) {
      PetscBool   driven[3];
      PetscReal   F[3];
      const Tool *tl = NULL;
      if (!sg->s[k - 1].tool_on[t] || sg->s[k].tool_on[t] || sg->s[k - 1].tool_release[t]) continue;
      PetscCall(ContactGetTool(contact, t, &tl));
      PetscCall(ContactGetToolTarget(contact, t, sg->s[k].t0, driven, F));
      for (int d = 0; d < 3; d++)
        PetscCheck(!driven[d] || F[d] == 0, PETSC_COMM_WORLD, PETSC_ERR_USER_INPUT, "-stage_%s_tools: tool %s is removed at time %g while a force of %g along %c still drives it (-tool_%s_force_%c); release it in the stage before (-stage_%s_release %s) or bring its -tool_%s_force_amplitude to 0 there", sg->s[k].name, tl->name, (double)sg->s[k].t0, (double)F[d], "xyz"[d], tl->name, "xyz"[d], sg->s[k - 1].name, tl->name, tl->name);
    }
  for (PetscInt b = 0; b < bcs->n; b++) {
    bcs->bc[b].always = PETSC_TRUE;
    for (PetscInt k = 0; k < sg->n; k++)
      if (!sg->s[k].bc_on[b]) bcs->bc[b].always = PETSC_FALSE;
    bcs->bc[b].active = sg->s[0].bc_on[b];
  }
  bcs->T = sg->T;
  ToolsSetTotalTime(sg->T);
  PetscFunctionReturn(0);
}

PetscInt StageAt(const Stages *sg, PetscReal t)
{
  const PetscReal tol = 1e-12 * sg->T;
  PetscInt        k   = 0;
  while (k < sg->n - 1 && t >= sg->s[k].t1 - tol) k++;
  return k;
}
