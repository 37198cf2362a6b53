/* Options of the mesh module: the source (built-in box or blank, .inp deck, Gmsh file), the
   generators' parameters and the partitioner. */
#include <string.h>
#include "mesh.h"
#include "util.h"
#include "options.h"

PetscErrorCode MeshSetFromOptions(MPI_Comm comm, MeshOptions *o)
{
  const char *mesh_types[] = {"box", "blank", "gmsh", "inp", "MeshSource", "MESH_", NULL};
  PetscInt    n;
  PetscBool   set, fileset;

  PetscFunctionBeginUser;
  PetscCall(PetscMemzero(o, sizeof(*o)));
  o->source = MESH_BOX;
  for (int i = 0; i < 3; i++) {
    o->box_lower[i] = 0;
    o->box_upper[i] = 1;
    o->box_cells[i] = 2;
    o->box_grading[i] = 1;
  }
  o->blank_radius       = 59.18;
  o->blank_thickness    = 1.0;
  o->blank_core         = 0.4;
  o->blank_core_cells   = 6;
  o->blank_radial_cells = 12;
  o->blank_layers       = 1;
  o->blank_quarter      = PETSC_TRUE;
  o->partition_metis    = PETSC_TRUE;
  PetscOptionsBegin(comm, NULL, "Mesh: source, generators, partition", NULL);
  {
    PetscInt  mt = (PetscInt)o->source;
    PetscBool mtset;
    PetscInt  i3[3];

    /* mesh */
    PetscCall(PetscOptionsString("-mesh_file", "Mesh file: Gmsh (.msh) or Abaqus-style deck (.inp)", NULL, o->file, o->file, sizeof(o->file), &fileset));
    PetscCall(PetscOptionsEList("-mesh_type", "Mesh source", NULL, mesh_types, 4, mesh_types[mt], &mt, &mtset));
    if (!mtset && fileset) {
      size_t len;
      PetscCall(PetscStrlen(o->file, &len));
      if (len > 4 && !strcmp(o->file + len - 4, ".inp")) mt = MESH_INP;
      else if (len > 4 && !strcmp(o->file + len - 4, ".msh")) mt = MESH_GMSH;
      else SETERRQ(comm, PETSC_ERR_USER_INPUT, "-mesh_file %s: unknown extension (use .msh or .inp, or set -mesh_type)", o->file);
    }
    o->source = (MeshSource)mt;
    PetscCheck(!(o->source == MESH_GMSH || o->source == MESH_INP) || fileset, comm, PETSC_ERR_USER_INPUT, "-mesh_type %s needs -mesh_file", mesh_types[mt]);

    n = 3;
    PetscCall(PetscOptionsRealArray("-box_lower", "Box: lower corner", NULL, o->box_lower, &n, &set));
    PetscCheck(!set || n == 3, comm, PETSC_ERR_USER_INPUT, "-box_lower needs 3 values, got %" PetscInt_FMT, n);
    n = 3;
    PetscCall(PetscOptionsRealArray("-box_upper", "Box: upper corner", NULL, o->box_upper, &n, &set));
    PetscCheck(!set || n == 3, comm, PETSC_ERR_USER_INPUT, "-box_upper needs 3 values, got %" PetscInt_FMT, n);
    PetscCall(AtritoCheckFinite(comm, "-box_lower", o->box_lower, 3));
    PetscCall(AtritoCheckFinite(comm, "-box_upper", o->box_upper, 3));
    for (int i = 0; i < 3; i++) PetscCheck(o->box_upper[i] > o->box_lower[i], comm, PETSC_ERR_USER_INPUT, "-box_upper: component %d (%g) must exceed -box_lower (%g)", i, (double)o->box_upper[i], (double)o->box_lower[i]);
    n = 3;
    for (int i = 0; i < 3; i++) i3[i] = o->box_cells[i];
    PetscCall(PetscOptionsIntArray("-box_cells", "Box: cells along x,y,z", NULL, i3, &n, &set));
    PetscCheck(!set || n == 3, comm, PETSC_ERR_USER_INPUT, "-box_cells needs 3 values, got %" PetscInt_FMT, n);
    for (int i = 0; i < 3; i++) {
      PetscCheck(i3[i] >= 1, comm, PETSC_ERR_USER_INPUT, "-box_cells: %" PetscInt_FMT " must be >= 1", i3[i]);
      o->box_cells[i] = i3[i];
    }
    n = 3;
    PetscCall(PetscOptionsRealArray("-box_grading", "Box: geometric grading along x,y,z, the size of the last cell over the first's (1: uniform; > 1 fine at -box_lower, < 1 fine at -box_upper)", NULL, o->box_grading, &n, &set));
    PetscCheck(!set || n == 3, comm, PETSC_ERR_USER_INPUT, "-box_grading needs 3 values, got %" PetscInt_FMT, n);
    PetscCall(AtritoCheckFinite(comm, "-box_grading", o->box_grading, 3));
    for (int i = 0; i < 3; i++) PetscCheck(o->box_grading[i] > 0, comm, PETSC_ERR_USER_INPUT, "-box_grading: component %d (%g) must be positive", i, (double)o->box_grading[i]);

    PetscCall(PetscOptionsReal("-blank_radius", "Blank: radius", NULL, o->blank_radius, &o->blank_radius, NULL));
    PetscCall(PetscOptionsReal("-blank_thickness", "Blank: thickness", NULL, o->blank_thickness, &o->blank_thickness, NULL));
    PetscCall(PetscOptionsReal("-blank_core", "Blank: half side of the central square over the radius", NULL, o->blank_core, &o->blank_core, NULL));
    PetscCall(PetscOptionsInt("-blank_core_cells", "Blank: cells along the central square's side (per quarter)", NULL, o->blank_core_cells, &o->blank_core_cells, NULL));
    PetscCall(PetscOptionsInt("-blank_radial_cells", "Blank: cells from the central square to the rim", NULL, o->blank_radial_cells, &o->blank_radial_cells, NULL));
    PetscCall(PetscOptionsInt("-blank_layers", "Blank: cells through the thickness", NULL, o->blank_layers, &o->blank_layers, NULL));
    PetscCall(PetscOptionsBool("-blank_quarter", "Blank: quarter model (symmetry planes x=0, y=0)", NULL, o->blank_quarter, &o->blank_quarter, NULL));
    PetscCheck(o->blank_radius > 0 && PetscIsNormalReal(o->blank_radius), comm, PETSC_ERR_USER_INPUT, "-blank_radius %g must be positive", (double)o->blank_radius);
    PetscCheck(o->blank_thickness > 0 && PetscIsNormalReal(o->blank_thickness), comm, PETSC_ERR_USER_INPUT, "-blank_thickness %g must be positive", (double)o->blank_thickness);
    PetscCheck(o->blank_core > 0 && o->blank_core < 1, comm, PETSC_ERR_USER_INPUT, "-blank_core %g must lie in (0,1)", (double)o->blank_core);
    PetscCheck(o->blank_core_cells >= 1, comm, PETSC_ERR_USER_INPUT, "-blank_core_cells %" PetscInt_FMT " must be >= 1", o->blank_core_cells);
    PetscCheck(o->blank_radial_cells >= 1, comm, PETSC_ERR_USER_INPUT, "-blank_radial_cells %" PetscInt_FMT " must be >= 1", o->blank_radial_cells);
    PetscCheck(o->blank_layers >= 1, comm, PETSC_ERR_USER_INPUT, "-blank_layers %" PetscInt_FMT " must be >= 1", o->blank_layers);

    {
      const char *parts[] = {"metis", "simple", "Partition", "P_", NULL};
      PetscInt    p       = 0;
      PetscCall(PetscOptionsEList("-partition", "Cell partition", NULL, parts, 2, parts[0], &p, NULL));
      o->partition_metis = p == 0 ? PETSC_TRUE : PETSC_FALSE;
    }
    {
      const char *bal[] = {"cells", "contact", "PartitionBalance", "PB_", NULL};
      PetscInt    b     = 0;
      PetscBool   bset  = PETSC_FALSE;
      PetscCall(PetscOptionsEList("-partition_balance", "What the METIS partition balances: the cells, or the cells and the contact slave nodes together", "doc/scaling-model.md", bal, 2, bal[0], &b, &bset));
      o->partition_contact = b == 1 ? PETSC_TRUE : PETSC_FALSE;
      PetscCheck(!(bset && o->partition_contact && !o->partition_metis), comm, PETSC_ERR_USER_INPUT, "-partition_balance contact needs -partition metis");
    }

    o->given = (mtset || fileset) ? PETSC_TRUE : PETSC_FALSE;
  }
  PetscOptionsEnd();
  PetscFunctionReturn(0);
}
