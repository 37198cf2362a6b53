/* Case module: every setting is a PETSc option; read them all here, validate them, and keep
   them in one read-only description. Errors name the option and the value. */
#include <math.h>
#include <string.h>
#include "atrito.h"
#include "lu.h"

static PetscErrorCode CheckFinite(MPI_Comm comm, const char *opt, const PetscReal *v, PetscInt n)
{
  PetscFunctionBeginUser;
  for (PetscInt i = 0; i < n; i++) PetscCheck(PetscIsNormalReal(v[i]) || v[i] == 0, comm, PETSC_ERR_USER_INPUT, "%s: value %g is not a finite number", opt, (double)v[i]);
  PetscFunctionReturn(0);
}

static PetscErrorCode ParseComponent(MPI_Comm comm, const char *opt, const char *s, PetscInt *c)
{
  PetscFunctionBeginUser;
  if (!strcmp(s, "x") || !strcmp(s, "0")) *c = 0;
  else if (!strcmp(s, "y") || !strcmp(s, "1")) *c = 1;
  else if (!strcmp(s, "z") || !strcmp(s, "2")) *c = 2;
  else SETERRQ(comm, PETSC_ERR_USER_INPUT, "%s: unknown component '%s' (use x, y, z)", opt, s);
  PetscFunctionReturn(0);
}

PetscErrorCode CaseRead(MPI_Comm comm, Case *cs)
{
  const char *mesh_types[] = {"box", "blank", "gmsh", "inp", "MeshSource", "MESH_", NULL};
  const char *hard_types[] = {"linear", "swift", "HardeningLaw", "HARDENING_", NULL};
  char        opt[ATRITO_NAME_LEN + 64];
  PetscInt    n;
  PetscBool   set, fileset;
  char       *bcnames[ATRITO_MAX_BC];

  PetscFunctionBeginUser;
  PetscCall(PetscMemzero(cs, sizeof(*cs)));
  /* defaults */
  cs->mesh_source = MESH_BOX;
  for (int i = 0; i < 3; i++) {
    cs->box_lower[i] = 0;
    cs->box_upper[i] = 1;
    cs->box_cells[i] = 2;
  }
  cs->blank_radius       = 59.18;
  cs->blank_thickness    = 1.0;
  cs->blank_core         = 0.4;
  cs->blank_core_cells   = 6;
  cs->blank_radial_cells = 12;
  cs->blank_layers       = 1;
  cs->blank_quarter      = PETSC_TRUE;
  cs->partition_metis    = PETSC_TRUE;
  cs->mat.E              = 69004;
  cs->mat.nu             = 0.3;
  cs->mat.law            = HARDENING_SWIFT;
  cs->mat.sy0            = 100;
  cs->mat.H              = 0;
  cs->mat.swK            = 589;
  cs->mat.sweps0         = 1e-4;
  cs->mat.swn            = 0.216;
  cs->elem.fbar          = 1;
  cs->load_dt0           = 0.1;
  cs->load_dt_min        = 1e-6;
  cs->load_dt_max        = 0;
  cs->load_cut           = 0.5;
  cs->load_grow          = 1.5;
  cs->load_grow_its      = 5;
  cs->load_max_cuts      = 10;
  cs->stall_its          = 0;
  cs->stall_factor       = 0.9;
  cs->load_max_steps     = 100000;
  cs->load_predictor     = PREDICTOR_AUTO;
  cs->lu_ordering        = LU_ORDERING_ND;
  cs->output_interval    = 1;
  PetscCall(PetscStrncpy(cs->output_dir, "out", sizeof(cs->output_dir)));

  PetscOptionsBegin(comm, NULL, "atrito: finite-strain elasto-plastic solver", NULL);
  {
    PetscInt  mt = (PetscInt)cs->mesh_source, ht = (PetscInt)cs->mat.law;
    PetscBool mtset, fbar = PETSC_TRUE;
    PetscReal v3[3];
    PetscInt  i3[3];

    /* mesh */
    PetscCall(PetscOptionsString("-mesh_file", "Mesh file: Gmsh (.msh) or Abaqus-style deck (.inp)", NULL, cs->mesh_file, cs->mesh_file, sizeof(cs->mesh_file), &fileset));
    PetscCall(PetscOptionsEList("-mesh_type", "Mesh source", NULL, mesh_types, 4, mesh_types[mt], &mt, &mtset));
    if (!mtset && fileset) {
      size_t len;
      PetscCall(PetscStrlen(cs->mesh_file, &len));
      if (len > 4 && !strcmp(cs->mesh_file + len - 4, ".inp")) mt = MESH_INP;
      else if (len > 4 && !strcmp(cs->mesh_file + len - 4, ".msh")) mt = MESH_GMSH;
      else SETERRQ(comm, PETSC_ERR_USER_INPUT, "-mesh_file %s: unknown extension (use .msh or .inp, or set -mesh_type)", cs->mesh_file);
    }
    cs->mesh_source = (MeshSource)mt;
    PetscCheck(!(cs->mesh_source == MESH_GMSH || cs->mesh_source == MESH_INP) || fileset, comm, PETSC_ERR_USER_INPUT, "-mesh_type %s needs -mesh_file", mesh_types[mt]);

    n = 3;
    PetscCall(PetscOptionsRealArray("-box_lower", "Box: lower corner", NULL, cs->box_lower, &n, &set));
    PetscCheck(!set || n == 3, comm, PETSC_ERR_USER_INPUT, "-box_lower needs 3 values, got %" PetscInt_FMT, n);
    n = 3;
    PetscCall(PetscOptionsRealArray("-box_upper", "Box: upper corner", NULL, cs->box_upper, &n, &set));
    PetscCheck(!set || n == 3, comm, PETSC_ERR_USER_INPUT, "-box_upper needs 3 values, got %" PetscInt_FMT, n);
    PetscCall(CheckFinite(comm, "-box_lower", cs->box_lower, 3));
    PetscCall(CheckFinite(comm, "-box_upper", cs->box_upper, 3));
    for (int i = 0; i < 3; i++) PetscCheck(cs->box_upper[i] > cs->box_lower[i], comm, PETSC_ERR_USER_INPUT, "-box_upper: component %d (%g) must exceed -box_lower (%g)", i, (double)cs->box_upper[i], (double)cs->box_lower[i]);
    n = 3;
    for (int i = 0; i < 3; i++) i3[i] = cs->box_cells[i];
    PetscCall(PetscOptionsIntArray("-box_cells", "Box: cells along x,y,z", NULL, i3, &n, &set));
    PetscCheck(!set || n == 3, comm, PETSC_ERR_USER_INPUT, "-box_cells needs 3 values, got %" PetscInt_FMT, n);
    for (int i = 0; i < 3; i++) {
      PetscCheck(i3[i] >= 1, comm, PETSC_ERR_USER_INPUT, "-box_cells: %" PetscInt_FMT " must be >= 1", i3[i]);
      cs->box_cells[i] = i3[i];
    }

    PetscCall(PetscOptionsReal("-blank_radius", "Blank: radius", NULL, cs->blank_radius, &cs->blank_radius, NULL));
    PetscCall(PetscOptionsReal("-blank_thickness", "Blank: thickness", NULL, cs->blank_thickness, &cs->blank_thickness, NULL));
    PetscCall(PetscOptionsReal("-blank_core", "Blank: half side of the central square over the radius", NULL, cs->blank_core, &cs->blank_core, NULL));
    PetscCall(PetscOptionsInt("-blank_core_cells", "Blank: cells along the central square's side (per quarter)", NULL, cs->blank_core_cells, &cs->blank_core_cells, NULL));
    PetscCall(PetscOptionsInt("-blank_radial_cells", "Blank: cells from the central square to the rim", NULL, cs->blank_radial_cells, &cs->blank_radial_cells, NULL));
    PetscCall(PetscOptionsInt("-blank_layers", "Blank: cells through the thickness", NULL, cs->blank_layers, &cs->blank_layers, NULL));
    PetscCall(PetscOptionsBool("-blank_quarter", "Blank: quarter model (symmetry planes x=0, y=0)", NULL, cs->blank_quarter, &cs->blank_quarter, NULL));
    PetscCheck(cs->blank_radius > 0 && PetscIsNormalReal(cs->blank_radius), comm, PETSC_ERR_USER_INPUT, "-blank_radius %g must be positive", (double)cs->blank_radius);
    PetscCheck(cs->blank_thickness > 0 && PetscIsNormalReal(cs->blank_thickness), comm, PETSC_ERR_USER_INPUT, "-blank_thickness %g must be positive", (double)cs->blank_thickness);
    PetscCheck(cs->blank_core > 0 && cs->blank_core < 1, comm, PETSC_ERR_USER_INPUT, "-blank_core %g must lie in (0,1)", (double)cs->blank_core);
    PetscCheck(cs->blank_core_cells >= 1, comm, PETSC_ERR_USER_INPUT, "-blank_core_cells %" PetscInt_FMT " must be >= 1", cs->blank_core_cells);
    PetscCheck(cs->blank_radial_cells >= 1, comm, PETSC_ERR_USER_INPUT, "-blank_radial_cells %" PetscInt_FMT " must be >= 1", cs->blank_radial_cells);
    PetscCheck(cs->blank_layers >= 1, comm, PETSC_ERR_USER_INPUT, "-blank_layers %" PetscInt_FMT " must be >= 1", cs->blank_layers);

    {
      const char *parts[] = {"metis", "simple", "Partition", "P_", NULL};
      PetscInt    p       = 0;
      PetscCall(PetscOptionsEList("-partition", "Cell partition", NULL, parts, 2, parts[0], &p, NULL));
      cs->partition_metis = p == 0 ? PETSC_TRUE : PETSC_FALSE;
    }

    /* material */
    PetscCall(PetscOptionsReal("-material_E", "Young's modulus", NULL, cs->mat.E, &cs->mat.E, NULL));
    PetscCall(PetscOptionsReal("-material_nu", "Poisson's ratio", NULL, cs->mat.nu, &cs->mat.nu, NULL));
    PetscCall(PetscOptionsEList("-material_hardening", "Hardening law", NULL, hard_types, 2, hard_types[ht], &ht, NULL));
    cs->mat.law = (HardeningLaw)ht;
    PetscCall(PetscOptionsReal("-material_yield", "Linear hardening: initial yield stress", NULL, cs->mat.sy0, &cs->mat.sy0, NULL));
    PetscCall(PetscOptionsReal("-material_hardening_modulus", "Linear hardening: slope", NULL, cs->mat.H, &cs->mat.H, NULL));
    PetscCall(PetscOptionsReal("-material_swift_K", "Swift: K in K (eps0 + ep)^n", NULL, cs->mat.swK, &cs->mat.swK, NULL));
    PetscCall(PetscOptionsReal("-material_swift_eps0", "Swift: eps0", NULL, cs->mat.sweps0, &cs->mat.sweps0, NULL));
    PetscCall(PetscOptionsReal("-material_swift_n", "Swift: exponent n", NULL, cs->mat.swn, &cs->mat.swn, NULL));
    PetscCheck(cs->mat.E > 0 && PetscIsNormalReal(cs->mat.E), comm, PETSC_ERR_USER_INPUT, "-material_E %g must be positive", (double)cs->mat.E);
    PetscCheck(cs->mat.nu > -1 && cs->mat.nu < 0.5, comm, PETSC_ERR_USER_INPUT, "-material_nu %g must lie in (-1, 0.5)", (double)cs->mat.nu);
    if (cs->mat.law == HARDENING_LINEAR) {
      PetscCheck(cs->mat.sy0 > 0 && PetscIsNormalReal(cs->mat.sy0), comm, PETSC_ERR_USER_INPUT, "-material_yield %g must be positive", (double)cs->mat.sy0);
      PetscCheck(cs->mat.H >= 0 && (cs->mat.H == 0 || PetscIsNormalReal(cs->mat.H)), comm, PETSC_ERR_USER_INPUT, "-material_hardening_modulus %g must be >= 0", (double)cs->mat.H);
    } else {
      PetscCheck(cs->mat.swK > 0 && PetscIsNormalReal(cs->mat.swK), comm, PETSC_ERR_USER_INPUT, "-material_swift_K %g must be positive", (double)cs->mat.swK);
      PetscCheck(cs->mat.sweps0 > 0 && PetscIsNormalReal(cs->mat.sweps0), comm, PETSC_ERR_USER_INPUT, "-material_swift_eps0 %g must be positive", (double)cs->mat.sweps0);
      PetscCheck(cs->mat.swn >= 0 && cs->mat.swn < 1, comm, PETSC_ERR_USER_INPUT, "-material_swift_n %g must lie in [0, 1)", (double)cs->mat.swn);
    }
    cs->mat.rtol  = 1e-12;
    cs->mat.maxit = 50;
    PetscCall(PetscOptionsReal("-material_return_rtol", "Relative tolerance of the local return map", NULL, cs->mat.rtol, &cs->mat.rtol, NULL));
    PetscCall(PetscOptionsInt("-material_return_maxit", "Iteration limit of the local return map", NULL, cs->mat.maxit, &cs->mat.maxit, NULL));
    PetscCheck(cs->mat.rtol > 0 && cs->mat.rtol < 1, comm, PETSC_ERR_USER_INPUT, "-material_return_rtol %g must lie in (0, 1)", (double)cs->mat.rtol);
    PetscCheck(cs->mat.maxit >= 1, comm, PETSC_ERR_USER_INPUT, "-material_return_maxit %d must be >= 1", cs->mat.maxit);
    PetscCheck(MaterialParamsSetup(&cs->mat) == 0, comm, PETSC_ERR_USER_INPUT, "invalid material parameters");
    PetscCall(PetscOptionsBool("-assembly_coo", "Assemble the Jacobian in coordinate form (faster, more memory)", NULL, cs->assembly_coo, &cs->assembly_coo, NULL));
    PetscCall(PetscOptionsBool("-fe_fbar", "F-bar treatment of the volumetric part", NULL, fbar, &fbar, NULL));
    cs->elem.fbar = fbar ? 1 : 0;

    /* boundary conditions */
    n = ATRITO_MAX_BC;
    PetscCall(PetscOptionsStringArray("-bc_names", "Dirichlet conditions, each described by -bc_<name>_set, _components, _values", NULL, bcnames, &n, &set));
    cs->nbc = set ? n : 0;
    for (PetscInt b = 0; b < cs->nbc; b++) {
      BCSpec *bc = &cs->bc[b];
      char   *comps[3];
      PetscInt nc = 3, nvals = 3;
      PetscCall(PetscStrncpy(bc->name, bcnames[b], sizeof(bc->name)));
      PetscCall(PetscFree(bcnames[b]));
      PetscCall(PetscStrncpy(bc->set, bc->name, sizeof(bc->set)));
      PetscCall(PetscSNPrintf(opt, sizeof(opt), "-bc_%s_set", bc->name));
      PetscCall(PetscOptionsString(opt, "Mesh set (label) of the condition", NULL, bc->set, bc->set, sizeof(bc->set), NULL));
      PetscCall(PetscSNPrintf(opt, sizeof(opt), "-bc_%s_components", bc->name));
      PetscCall(PetscOptionsStringArray(opt, "Constrained components (x,y,z)", NULL, comps, &nc, &set));
      PetscCheck(set && nc >= 1, comm, PETSC_ERR_USER_INPUT, "%s is required for the boundary condition '%s' (e.g. x,y,z)", opt, bc->name);
      bc->ncomp = nc;
      for (PetscInt k = 0; k < nc; k++) {
        PetscCall(ParseComponent(comm, opt, comps[k], &bc->comp[k]));
        PetscCall(PetscFree(comps[k]));
        for (PetscInt j = 0; j < k; j++) PetscCheck(bc->comp[j] != bc->comp[k], comm, PETSC_ERR_USER_INPUT, "%s: component listed twice", opt);
      }
      PetscCall(PetscSNPrintf(opt, sizeof(opt), "-bc_%s_values", bc->name));
      for (int k = 0; k < 3; k++) v3[k] = 0;
      PetscCall(PetscOptionsRealArray(opt, "Prescribed displacements at load 1 (ramped linearly)", NULL, v3, &nvals, &set));
      PetscCheck(!set || nvals == nc, comm, PETSC_ERR_USER_INPUT, "%s needs %" PetscInt_FMT " values (one per component), got %" PetscInt_FMT, opt, nc, nvals);
      PetscCall(CheckFinite(comm, opt, v3, 3));
      for (int k = 0; k < 3; k++) bc->value[k] = v3[k];
    }

    /* load stepping */
    {
      PetscInt steps = 10;
      PetscCall(PetscOptionsInt("-load_steps", "Initial number of load steps (first increment 1/N)", NULL, steps, &steps, NULL));
      PetscCheck(steps >= 1, comm, PETSC_ERR_USER_INPUT, "-load_steps %" PetscInt_FMT " must be >= 1", steps);
      cs->load_dt0 = 1.0 / steps;
    }
    cs->load_dt_max = cs->load_dt0;
    PetscCall(PetscOptionsReal("-load_dt_max", "Largest load increment", NULL, cs->load_dt_max, &cs->load_dt_max, NULL));
    PetscCall(PetscOptionsReal("-load_dt_min", "Smallest load increment before the run stops", NULL, cs->load_dt_min, &cs->load_dt_min, NULL));
    PetscCall(PetscOptionsReal("-load_cut_factor", "Increment factor after a failed step", NULL, cs->load_cut, &cs->load_cut, NULL));
    PetscCall(PetscOptionsReal("-load_grow_factor", "Increment factor after an easy step", NULL, cs->load_grow, &cs->load_grow, NULL));
    PetscCall(PetscOptionsInt("-load_grow_its", "A step is easy when Newton took at most this many iterations", NULL, cs->load_grow_its, &cs->load_grow_its, NULL));
    PetscCall(PetscOptionsInt("-load_max_cuts", "Successive cuts allowed in one step", NULL, cs->load_max_cuts, &cs->load_max_cuts, NULL));
    PetscCall(PetscOptionsInt("-load_max_steps", "Largest number of converged steps", NULL, cs->load_max_steps, &cs->load_max_steps, NULL));
    PetscCall(PetscOptionsInt("-newton_stall_its", "Newton has stalled (the step fails at once) when |R| has not fallen below -newton_stall_factor times its value this many iterations earlier (0: never)", NULL, cs->stall_its, &cs->stall_its, NULL));
    PetscCall(PetscOptionsReal("-newton_stall_factor", "See -newton_stall_its", NULL, cs->stall_factor, &cs->stall_factor, NULL));
    {
      const char *preds[] = {"none", "extrapolate", "tangent", "auto", "Predictor", "PREDICTOR_", NULL};
      PetscInt    p       = (PetscInt)cs->load_predictor;
      PetscCall(PetscOptionsEList("-load_predictor", "Start of each step: the committed state, the extrapolation of the last two, the tangent response to the load increment, or auto (extrapolation when there is a previous step, else tangent)", NULL, preds, 4, preds[p], &p, NULL));
      cs->load_predictor = (Predictor)p;
    }
    {
      const char *ords[] = {"mumps", "nd", "LUOrdering", "LU_ORDERING_", NULL};
      PetscInt    o      = (PetscInt)cs->lu_ordering;
      PetscCall(PetscOptionsEList("-lu_ordering", "Ordering of the LU factorisation (-pc_type lu with MUMPS): nd = METIS nested dissection of the Jacobian's graph, MUMPS called directly; mumps = MUMPS's own ordering (PORD here) through PETSc's interface", NULL, ords, 2, ords[o], &o, NULL));
      cs->lu_ordering = (LUOrdering)o;
      if (cs->lu_ordering == LU_ORDERING_ND) PetscCall(LUNDCheckOptions(comm, NULL));
    }
    PetscCheck(cs->load_dt_max > 0 && cs->load_dt_max <= 1, comm, PETSC_ERR_USER_INPUT, "-load_dt_max %g must lie in (0, 1]", (double)cs->load_dt_max);
    PetscCheck(cs->load_dt_min > 0 && cs->load_dt_min <= cs->load_dt0, comm, PETSC_ERR_USER_INPUT, "-load_dt_min %g must lie in (0, first increment %g]", (double)cs->load_dt_min, (double)cs->load_dt0);
    PetscCheck(cs->load_cut > 0 && cs->load_cut < 1, comm, PETSC_ERR_USER_INPUT, "-load_cut_factor %g must lie in (0, 1)", (double)cs->load_cut);
    PetscCheck(cs->load_grow >= 1 && PetscIsNormalReal(cs->load_grow), comm, PETSC_ERR_USER_INPUT, "-load_grow_factor %g must be >= 1", (double)cs->load_grow);
    PetscCheck(cs->load_max_cuts >= 0, comm, PETSC_ERR_USER_INPUT, "-load_max_cuts %" PetscInt_FMT " must be >= 0", cs->load_max_cuts);
    PetscCheck(cs->load_max_steps >= 1, comm, PETSC_ERR_USER_INPUT, "-load_max_steps %" PetscInt_FMT " must be >= 1", cs->load_max_steps);
    PetscCheck(cs->stall_its >= 0 && cs->stall_its < 256, comm, PETSC_ERR_USER_INPUT, "-newton_stall_its %" PetscInt_FMT " must lie in [0, 255]", cs->stall_its);
    PetscCheck(cs->stall_factor > 0 && cs->stall_factor <= 1, comm, PETSC_ERR_USER_INPUT, "-newton_stall_factor %g must lie in (0, 1]", (double)cs->stall_factor);

    /* contact */
    {
      char     *sets[8];
      PetscInt  nsets = 8;
      PetscBool sset;
      PetscCall(PetscOptionsStringArray("-contact_set", "Mesh sets of the slave nodes (their union)", NULL, sets, &nsets, &sset));
      if (!sset || nsets == 0) {
        PetscCall(PetscStrncpy(cs->contact_set[0], "contact", sizeof(cs->contact_set[0])));
        cs->ncontact_set = 1;
      } else {
        for (PetscInt k = 0; k < nsets; k++) {
          PetscCall(PetscStrncpy(cs->contact_set[k], sets[k], sizeof(cs->contact_set[k])));
          PetscCall(PetscFree(sets[k]));
        }
        cs->ncontact_set = nsets;
      }
    }
    cs->law.KN = 1e5;
    cs->law.KT = 5e3;
    cs->law.mu = 0;
    PetscCall(PetscOptionsReal("-contact_penalty_normal", "Normal penalty K_N (force per length, per node; per unit area with -contact_penalty_per_area)", NULL, cs->law.KN, &cs->law.KN, NULL));
    PetscCall(PetscOptionsReal("-contact_penalty_tangential", "Tangential penalty K_T (force per length, per node; per unit area with -contact_penalty_per_area)", NULL, cs->law.KT, &cs->law.KT, NULL));
    cs->contact_per_area = PETSC_FALSE;
    PetscCall(PetscOptionsBool("-contact_penalty_per_area", "K_N and K_T are per unit area (force per length^3); each slave node's are scaled by its tributary area on the contact faces", NULL, cs->contact_per_area, &cs->contact_per_area, NULL));
    PetscCall(PetscOptionsReal("-contact_friction", "Coulomb friction coefficient mu", NULL, cs->law.mu, &cs->law.mu, NULL));
    PetscCheck(cs->law.KN > 0 && PetscIsNormalReal(cs->law.KN), comm, PETSC_ERR_USER_INPUT, "-contact_penalty_normal %g must be positive", (double)cs->law.KN);
    PetscCheck(cs->law.KT > 0 && PetscIsNormalReal(cs->law.KT), comm, PETSC_ERR_USER_INPUT, "-contact_penalty_tangential %g must be positive", (double)cs->law.KT);
    PetscCheck(cs->law.mu >= 0 && (cs->law.mu == 0 || PetscIsNormalReal(cs->law.mu)), comm, PETSC_ERR_USER_INPUT, "-contact_friction %g must be >= 0", (double)cs->law.mu);
    {
      const char *tang[] = {"analytic", "fd", "ContactTangent", "CT_", NULL};
      PetscInt    t      = 0;
      PetscCall(PetscOptionsEList("-contact_tangent", "Contact tangent: analytic (with curvature) or per-node finite differences", NULL, tang, 2, tang[0], &t, NULL));
      cs->contact_fd = t == 1 ? PETSC_TRUE : PETSC_FALSE;
    }
    cs->contact_search = -1;
    PetscCall(PetscOptionsReal("-contact_search_distance", "Pairing: tools farther than this from a node are skipped (default: 5% of the largest tool box)", NULL, cs->contact_search, &cs->contact_search, NULL));
    cs->chatter_check = PETSC_TRUE;
    PetscCall(PetscOptionsBool("-contact_chatter_check", "Fail (and cut) a step whose last Newton iteration still changed the set of nodes in contact", NULL, cs->chatter_check, &cs->chatter_check, NULL));
    cs->fault_nan_load = -1;
    PetscCall(PetscOptionsReal("-fault_nan_residual_at", "Testing: once, put a NaN into the residual at the first evaluation at or beyond this load", NULL, cs->fault_nan_load, &cs->fault_nan_load, NULL));
    cs->symmetry = (cs->mesh_source == MESH_BLANK && cs->blank_quarter) ? 4 : 1;
    PetscCall(PetscOptionsReal("-model_symmetry", "Multiplicity of the model (4 for a quarter): force_full = force * multiplicity", NULL, cs->symmetry, &cs->symmetry, NULL));
    PetscCheck(cs->symmetry >= 1, comm, PETSC_ERR_USER_INPUT, "-model_symmetry %g must be >= 1", (double)cs->symmetry);

    /* output */
    PetscCall(PetscOptionsString("-output_dir", "Output directory", NULL, cs->output_dir, cs->output_dir, sizeof(cs->output_dir), NULL));
    PetscCall(PetscOptionsInt("-output_interval", "Write fields every N converged steps (0: never)", NULL, cs->output_interval, &cs->output_interval, NULL));
    PetscCheck(cs->output_interval >= 0, comm, PETSC_ERR_USER_INPUT, "-output_interval %" PetscInt_FMT " must be >= 0", cs->output_interval);
    PetscCall(PetscOptionsInt("-checkpoint_interval", "Write DIR/checkpoint.h5 every N converged steps and at the end (0: never)", NULL, cs->checkpoint_interval, &cs->checkpoint_interval, NULL));
    PetscCheck(cs->checkpoint_interval >= 0, comm, PETSC_ERR_USER_INPUT, "-checkpoint_interval %" PetscInt_FMT " must be >= 0", cs->checkpoint_interval);
    PetscCall(PetscOptionsString("-restart", "Continue from this checkpoint (same case; any number of ranks)", NULL, cs->restart, cs->restart, sizeof(cs->restart), NULL));
    v3[0] = 0;
    v3[1] = 0;
    v3[2] = 1;
    n     = 3;
    cs->thickness_output = cs->mesh_source == MESH_BLANK ? PETSC_TRUE : PETSC_FALSE;
    PetscCall(PetscOptionsRealArray("-output_thickness_direction", "Reference sheet normal: enables the thickness strain field", NULL, v3, &n, &set));
    if (set) {
      PetscReal nrm;
      PetscCheck(n == 3, comm, PETSC_ERR_USER_INPUT, "-output_thickness_direction needs 3 values");
      nrm = PetscSqrtReal(v3[0] * v3[0] + v3[1] * v3[1] + v3[2] * v3[2]);
      PetscCheck(nrm > 0 && PetscIsNormalReal(nrm), comm, PETSC_ERR_USER_INPUT, "-output_thickness_direction must be a nonzero vector");
      for (int k = 0; k < 3; k++) v3[k] /= nrm;
      cs->thickness_output = PETSC_TRUE;
    }
    for (int k = 0; k < 3; k++) cs->thickness_dir[k] = v3[k];
  }
  PetscOptionsEnd();
  PetscFunctionReturn(0);
}
