/* Bodies: parts of the mesh with materials of their own (include/body.h). */
#include "body.h"
#include "options.h"

PetscErrorCode BodiesSetFromOptions(MPI_Comm comm, Bodies *b)
{
  char     *names[BODY_MAX];
  PetscInt  n = BODY_MAX;
  PetscBool set;

  PetscFunctionBeginUser;
  PetscCall(PetscMemzero(b, sizeof(*b)));
  b->comm = comm;
  PetscOptionsBegin(comm, NULL, "Bodies", "doc/contact-bodies.md");
  PetscCall(PetscOptionsStringArray("-body_names", "Parts of the mesh with materials of their own, each an element set (-body_<name>_set) with the material options -body_<name>_material_...; the other cells take -material_...", "doc/contact-bodies.md", names, &n, &set));
  PetscOptionsEnd();
  b->n = set ? n : 0;
  for (PetscInt k = 0; k < b->n; k++) {
    char      prefix[ATRITO_NAME_LEN + 32], title[ATRITO_NAME_LEN + 8];
    PetscBool has;
    PetscCall(PetscStrncpy(b->name[k], names[k], ATRITO_NAME_LEN));
    PetscCall(PetscFree(names[k]));
    PetscCheck(b->name[k][0], comm, PETSC_ERR_USER_INPUT, "-body_names: an empty name");
    for (PetscInt j = 0; j < k; j++) {
      PetscBool eq;
      PetscCall(PetscStrcmp(b->name[j], b->name[k], &eq));
      PetscCheck(!eq, comm, PETSC_ERR_USER_INPUT, "-body_names: '%s' given twice", b->name[k]);
    }
    PetscCall(PetscSNPrintf(prefix, sizeof(prefix), "body_%s_", b->name[k]));
    PetscCall(PetscSNPrintf(title, sizeof(title), "Body %s", b->name[k]));
    PetscOptionsBegin(comm, prefix, title, "doc/contact-bodies.md");
    PetscCall(PetscOptionsString("-set", "Element set of the body's cells", "doc/contact-bodies.md", b->set[k], b->set[k], sizeof(b->set[k]), &has));
    PetscOptionsEnd();
    PetscCheck(has && b->set[k][0], comm, PETSC_ERR_USER_INPUT, "-body_%s_set: the body needs an element set", b->name[k]);
    PetscCall(PetscSNPrintf(prefix, sizeof(prefix), "body_%s_material_", b->name[k]));
    PetscCall(MaterialCreate(comm, &b->mat[k]));
    PetscCall(MaterialSetOptionsPrefix(b->mat[k], prefix));
    PetscCall(MaterialSetFromOptions(b->mat[k]));
  }
  PetscFunctionReturn(0);
}

PetscErrorCode BodiesCellMap(const Bodies *b, const Mesh *m, PetscInt *cmat)
{
  PetscInt cStart, cEnd, bad = PETSC_MAX_INT;

  PetscFunctionBeginUser;
  for (PetscInt c = 0; c < m->nc; c++) cmat[c] = 0;
  PetscCall(DMPlexGetHeightStratum(m->dm, 0, &cStart, &cEnd));
  for (PetscInt k = 0; k < b->n; k++) {
    DMLabel label;
    char    alt[ATRITO_NAME_LEN + 16];
    PetscCall(DMGetLabel(m->dm, b->set[k], &label));
    if (label) { /* a node set of that name: the element set is then called <name>_elements */
      PetscBool cells = PETSC_FALSE;
      PetscInt  any   = 0;
      for (PetscInt c = cStart; c < cEnd && !cells; c++) {
        PetscInt v;
        PetscCall(DMLabelGetValue(label, c, &v));
        if (v >= 0) cells = PETSC_TRUE;
      }
      any = cells ? 1 : 0;
      PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, &any, 1, MPIU_INT, MPI_MAX, b->comm));
      if (!any) {
        PetscCall(PetscSNPrintf(alt, sizeof(alt), "%s_elements", b->set[k]));
        PetscCall(DMGetLabel(m->dm, alt, &label));
        PetscCheck(label, b->comm, PETSC_ERR_USER_INPUT, "-body_%s_set %s: a node set, not an element set", b->name[k], b->set[k]);
      }
    }
    PetscCheck(label, b->comm, PETSC_ERR_USER_INPUT, "-body_%s_set: the mesh has no set named '%s'", b->name[k], b->set[k]);
    for (PetscInt c = cStart; c < cEnd; c++) {
      PetscInt v;
      PetscCall(DMLabelGetValue(label, c, &v));
      if (v < 0) continue;
      if (cmat[c - cStart] != 0) bad = PetscMin(bad, m->elem_id[c - cStart]);
      cmat[c - cStart] = k + 1;
    }
  }
  PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, &bad, 1, MPIU_INT, MPI_MIN, b->comm));
  PetscCheck(bad == PETSC_MAX_INT, b->comm, PETSC_ERR_USER_INPUT, "-body_names: element id %" PetscInt_FMT " lies in the sets of two bodies", bad);
  PetscFunctionReturn(0);
}

PetscErrorCode BodiesDestroy(Bodies *b)
{
  PetscFunctionBeginUser;
  for (PetscInt k = 0; k < b->n; k++) PetscCall(MaterialDestroy(&b->mat[k]));
  b->n = 0;
  PetscFunctionReturn(0);
}
