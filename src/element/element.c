/* Elements: the object and the registry of formulations.

   Adding an element formulation (e.g. an enhanced-strain hexahedron hex8_eas):
     1. write src/element/<name>.c with the formulation's kernels on plain arrays and
        PetscErrorCode ElementCreate_<Name>(Element el), which allocates the formulation's
        options with their defaults in el->data and fills the descriptor el->kernel (name, nen,
        nqp, nstate -- extra history doubles per element, e.g. the enhanced-strain parameters --,
        nface and face, ctx = el->data, kernel, min_jacobian) and el->ops (setfromoptions: reads
        the options in its own PetscOptionsBegin block under its own prefix; view; destroy: frees
        el->data); see hex8.c and include/element_impl.h. The kernel calls the material only
        through the MaterialKernel it is given, with mat->nhist history doubles per point;
     2. declare ElementCreate_<Name> below and add its line to ElementRegisterAll().
   -element_type <name> then selects it. */
#include <string.h>

#include "element_impl.h"
#include "options.h"

static PetscFunctionList ElementList;
static PetscBool         ElementRegisterAllCalled;
static char              ElementTypeNames[256]; /* "hex8, ..." for the error message */

static PetscErrorCode ElementFinalizePackage(void)
{
  PetscFunctionBeginUser;
  PetscCall(PetscFunctionListDestroy(&ElementList));
  ElementRegisterAllCalled = PETSC_FALSE;
  ElementTypeNames[0]      = '\0';
  PetscFunctionReturn(0);
}

/* the create functions of the formulations (src/element/<name>.c) */
PETSC_INTERN PetscErrorCode ElementCreate_Hex8(Element);
PETSC_INTERN PetscErrorCode ElementCreate_Hex8EAS(Element);

static PetscErrorCode ElementRegisterAll(void)
{
  PetscFunctionBeginUser;
  if (ElementRegisterAllCalled) PetscFunctionReturn(0);
  ElementRegisterAllCalled = PETSC_TRUE;
  PetscCall(PetscRegisterFinalize(ElementFinalizePackage));
  /* one line per element formulation */
  PetscCall(ElementRegister("hex8", ElementCreate_Hex8));
  PetscCall(ElementRegister("hex8_eas", ElementCreate_Hex8EAS));
  PetscFunctionReturn(0);
}

PetscErrorCode ElementRegister(const char name[], PetscErrorCode (*create)(Element))
{
  PetscErrorCode (*old)(Element) = NULL;

  PetscFunctionBeginUser;
  PetscCall(ElementRegisterAll());
  PetscCall(PetscFunctionListFind(ElementList, name, &old));
  PetscCall(PetscFunctionListAdd(&ElementList, name, create));
  if (!old) {
    if (ElementTypeNames[0]) PetscCall(PetscStrlcat(ElementTypeNames, ", ", sizeof(ElementTypeNames)));
    PetscCall(PetscStrlcat(ElementTypeNames, name, sizeof(ElementTypeNames)));
  }
  PetscFunctionReturn(0);
}

PetscErrorCode ElementCreate(MPI_Comm comm, Element *el)
{
  PetscFunctionBeginUser;
  PetscCheck(el, PETSC_COMM_SELF, PETSC_ERR_ARG_NULL, "null pointer: argument 2");
  PetscCall(ElementRegisterAll());
  PetscCall(PetscNew(el));
  (*el)->comm = comm;
  PetscFunctionReturn(0);
}

/* drop the current formulation's data and operations */
static PetscErrorCode ElementReset(Element el)
{
  PetscFunctionBeginUser;
  if (el->ops.destroy) PetscCall(el->ops.destroy(el));
  el->data = NULL;
  PetscCall(PetscMemzero(&el->ops, sizeof(el->ops)));
  PetscCall(PetscMemzero(&el->kernel, sizeof(el->kernel)));
  el->type_name[0] = '\0';
  PetscFunctionReturn(0);
}

PetscErrorCode ElementSetFromOptions(Element el)
{
  char      type[sizeof(el->type_name)];
  PetscBool same;
  PetscErrorCode (*create)(Element) = NULL;

  PetscFunctionBeginUser;
  PetscCheck(el, PETSC_COMM_SELF, PETSC_ERR_ARG_NULL, "null pointer: argument 1");
  PetscCall(PetscStrncpy(type, el->type_name[0] ? el->type_name : "hex8", sizeof(type)));
  PetscOptionsBegin(el->comm, "element_", "Element", "Element");
  PetscCall(PetscOptionsFList("-type", "Element formulation", NULL, ElementList, type, type, sizeof(type), NULL));
  PetscOptionsEnd();
  PetscCall(PetscFunctionListFind(ElementList, type, &create));
  PetscCheck(create, el->comm, PETSC_ERR_USER_INPUT, "-element_type %s: unknown element formulation (registered: %s)", type, ElementTypeNames);
  PetscCall(PetscStrcmp(type, el->type_name, &same));
  if (!same) {
    PetscCall(ElementReset(el));
    PetscCall(create(el));
    PetscCheck(el->kernel.kernel && el->kernel.min_jacobian && el->kernel.nen > 0 && el->kernel.nqp > 0 && el->kernel.nstate >= 0 && (el->kernel.face || !el->kernel.nface), el->comm, PETSC_ERR_PLIB, "element type %s: incomplete descriptor", type);
    PetscCall(PetscStrncpy(el->type_name, type, sizeof(el->type_name)));
  }
  if (el->ops.setfromoptions) PetscCall(el->ops.setfromoptions(el));
  PetscFunctionReturn(0);
}

PetscErrorCode ElementGetKernel(Element el, const ElementKernel **k)
{
  PetscFunctionBeginUser;
  PetscCheck(el && k, PETSC_COMM_SELF, PETSC_ERR_ARG_NULL, "null pointer argument");
  PetscCheck(el->type_name[0], el->comm, PETSC_ERR_ORDER, "element has no type: call ElementSetFromOptions() first");
  *k = &el->kernel;
  PetscFunctionReturn(0);
}

PetscErrorCode ElementView(Element el, PetscViewer v)
{
  PetscBool ascii;

  PetscFunctionBeginUser;
  PetscCheck(el, PETSC_COMM_SELF, PETSC_ERR_ARG_NULL, "null pointer: argument 1");
  if (!v) v = PETSC_VIEWER_STDOUT_(el->comm);
  PetscCall(PetscObjectTypeCompare((PetscObject)v, PETSCVIEWERASCII, &ascii));
  if (!ascii) PetscFunctionReturn(0);
  PetscCall(PetscViewerASCIIPrintf(v, "Element: type %s\n", el->type_name[0] ? el->type_name : "(not set)"));
  if (el->ops.view) {
    PetscCall(PetscViewerASCIIPushTab(v));
    PetscCall(el->ops.view(el, v));
    PetscCall(PetscViewerASCIIPopTab(v));
  }
  PetscFunctionReturn(0);
}

PetscErrorCode ElementDestroy(Element *el)
{
  PetscFunctionBeginUser;
  if (!el || !*el) PetscFunctionReturn(0);
  PetscCall(ElementReset(*el));
  PetscCall(PetscFree(*el));
  PetscFunctionReturn(0);
}
