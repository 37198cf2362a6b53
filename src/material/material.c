/* Materials: the object, the registry of types and the options common to all of them.

   Adding a material model (a user material, Hill 48, ...):
     1. write src/material/<name>.c with the model's kernels on plain arrays and
        PetscErrorCode MaterialCreate_<Name>(Material mat), which allocates the parameters with
        their defaults in mat->data and fills mat->kernel (nhist -- the history doubles per
        quadrature point, chosen at run time if need be --, ctx = mat->data, update,
        history_init, plastic_strain) and mat->ops (setfromoptions: reads the model's options
        in its own PetscOptionsBegin block with the prefix mat->prefix ("material_" unless
        MaterialSetOptionsPrefix changed it), validates them, naming an option in a message with
        that prefix ("-%sE ...", mat->prefix); its group title from MaterialOptionsTitle; view;
        destroy: frees mat->data); see j2.c and include/material_impl.h;
     2. declare MaterialCreate_<Name> below and add its line to MaterialRegisterAll().
   -material_type <name> (-<prefix>type) then selects it; elements take the history width from
   kernel.nhist.
   A program may also register a type of its own with MaterialRegister() before
   MaterialSetFromOptions(). */
#include <ctype.h>
#include <string.h>

#include "material_impl.h"
#include "options.h"

#define MATERIAL_DEFAULT_PREFIX "material_"

static PetscFunctionList MaterialList;
static PetscBool         MaterialRegisterAllCalled;
static char              MaterialTypeNames[256]; /* "j2, ..." for the error message */

static PetscErrorCode MaterialFinalizePackage(void)
{
  PetscFunctionBeginUser;
  PetscCall(PetscFunctionListDestroy(&MaterialList));
  MaterialRegisterAllCalled = PETSC_FALSE;
  MaterialTypeNames[0]      = '\0';
  PetscFunctionReturn(0);
}

/* the create functions of the types (src/material/<name>.c) */
PETSC_INTERN PetscErrorCode MaterialCreate_J2(Material);
PETSC_INTERN PetscErrorCode MaterialCreate_Hill48(Material);
PETSC_INTERN PetscErrorCode MaterialCreate_Yld91(Material);
PETSC_INTERN PetscErrorCode MaterialCreate_Umat(Material);

static PetscErrorCode MaterialRegisterAll(void)
{
  PetscFunctionBeginUser;
  if (MaterialRegisterAllCalled) PetscFunctionReturn(0);
  MaterialRegisterAllCalled = PETSC_TRUE;
  PetscCall(PetscRegisterFinalize(MaterialFinalizePackage));
  /* one line per material type */
  PetscCall(MaterialRegister("j2", MaterialCreate_J2));
  PetscCall(MaterialRegister("hill48", MaterialCreate_Hill48));
  PetscCall(MaterialRegister("yld91", MaterialCreate_Yld91));
  PetscCall(MaterialRegister("umat", MaterialCreate_Umat));
  PetscFunctionReturn(0);
}

PetscErrorCode MaterialRegister(const char name[], PetscErrorCode (*create)(Material))
{
  PetscErrorCode (*old)(Material) = NULL;

  PetscFunctionBeginUser;
  PetscCall(MaterialRegisterAll());
  PetscCall(PetscFunctionListFind(MaterialList, name, &old));
  PetscCall(PetscFunctionListAdd(&MaterialList, name, create));
  if (!old) {
    if (MaterialTypeNames[0]) PetscCall(PetscStrlcat(MaterialTypeNames, ", ", sizeof(MaterialTypeNames)));
    PetscCall(PetscStrlcat(MaterialTypeNames, name, sizeof(MaterialTypeNames)));
  }
  PetscFunctionReturn(0);
}

PetscErrorCode MaterialCreate(MPI_Comm comm, Material *mat)
{
  PetscFunctionBeginUser;
  PetscCheck(mat, PETSC_COMM_SELF, PETSC_ERR_ARG_NULL, "null pointer: argument 2");
  PetscCall(MaterialRegisterAll());
  PetscCall(PetscNew(mat));
  (*mat)->comm = comm;
  PetscCall(PetscStrncpy((*mat)->prefix, MATERIAL_DEFAULT_PREFIX, sizeof((*mat)->prefix)));
  PetscFunctionReturn(0);
}

PetscErrorCode MaterialSetOptionsPrefix(Material mat, const char prefix[])
{
  size_t len;

  PetscFunctionBeginUser;
  PetscCheck(mat, PETSC_COMM_SELF, PETSC_ERR_ARG_NULL, "null pointer: argument 1");
  if (!prefix) prefix = MATERIAL_DEFAULT_PREFIX;
  PetscCall(PetscStrlen(prefix, &len));
  PetscCheck(len > 0 && len < sizeof(mat->prefix), mat->comm, PETSC_ERR_ARG_OUTOFRANGE, "material options prefix '%s': empty or longer than %d characters", prefix, (int)sizeof(mat->prefix) - 1);
  PetscCheck(prefix[0] != '-', mat->comm, PETSC_ERR_ARG_WRONG, "material options prefix '%s': give it without the leading '-'", prefix);
  for (const char *c = prefix; *c; c++) PetscCheck(!isspace((unsigned char)*c), mat->comm, PETSC_ERR_ARG_WRONG, "material options prefix '%s': contains white space", prefix);
  PetscCall(PetscStrncpy(mat->prefix, prefix, sizeof(mat->prefix)));
  PetscFunctionReturn(0);
}

PetscErrorCode MaterialGetOptionsPrefix(Material mat, const char *prefix[])
{
  PetscFunctionBeginUser;
  PetscCheck(mat && prefix, PETSC_COMM_SELF, PETSC_ERR_ARG_NULL, "null pointer argument");
  *prefix = mat->prefix;
  PetscFunctionReturn(0);
}

PetscErrorCode MaterialOptionsTitle(Material mat, const char type[], const char what[], char title[], size_t len)
{
  PetscBool def;
  char      body[sizeof(mat->prefix) + 8] = "";

  PetscFunctionBeginUser;
  PetscCall(PetscStrcmp(mat->prefix, MATERIAL_DEFAULT_PREFIX, &def));
  if (!def) PetscCall(PetscSNPrintf(body, sizeof(body), " (-%s)", mat->prefix));
  PetscCall(PetscSNPrintf(title, len, "Material%s%s%s%s%s", type ? " " : "", type ? type : "", body, what ? ": " : "", what ? what : ""));
  PetscFunctionReturn(0);
}

/* drop the current type's data and operations */
static PetscErrorCode MaterialReset(Material mat)
{
  PetscFunctionBeginUser;
  if (mat->ops.destroy) PetscCall(mat->ops.destroy(mat));
  mat->data = NULL;
  PetscCall(PetscMemzero(&mat->ops, sizeof(mat->ops)));
  PetscCall(PetscMemzero(&mat->kernel, sizeof(mat->kernel)));
  mat->type_name[0] = '\0';
  PetscFunctionReturn(0);
}

PetscErrorCode MaterialSetFromOptions(Material mat)
{
  char      type[sizeof(mat->type_name)], title[sizeof(mat->prefix) + 32];
  PetscBool same, view = PETSC_FALSE;
  PetscErrorCode (*create)(Material) = NULL;

  PetscFunctionBeginUser;
  PetscCheck(mat, PETSC_COMM_SELF, PETSC_ERR_ARG_NULL, "null pointer: argument 1");
  PetscCall(PetscStrncpy(type, mat->type_name[0] ? mat->type_name : "j2", sizeof(type)));
  PetscCall(MaterialOptionsTitle(mat, NULL, NULL, title, sizeof(title)));
  PetscOptionsBegin(mat->comm, mat->prefix, title, "Material");
  PetscCall(PetscOptionsFList("-type", "Material model", NULL, MaterialList, type, type, sizeof(type), NULL));
  PetscCall(PetscOptionsBool("-view", "Print the material's parameters once they are set (fitted coefficients included)", NULL, view, &view, NULL));
  PetscOptionsEnd();
  PetscCall(PetscFunctionListFind(MaterialList, type, &create));
  PetscCheck(create, mat->comm, PETSC_ERR_USER_INPUT, "-%stype %s: unknown material (registered: %s)", mat->prefix, type, MaterialTypeNames);
  PetscCall(PetscStrcmp(type, mat->type_name, &same));
  if (!same) {
    PetscCall(MaterialReset(mat));
    PetscCall(create(mat));
    PetscCheck(mat->kernel.update && mat->kernel.history_init && mat->kernel.plastic_strain && mat->kernel.nhist >= 0, mat->comm, PETSC_ERR_PLIB, "material type %s: incomplete kernel", type);
    PetscCall(PetscStrncpy(mat->type_name, type, sizeof(mat->type_name)));
  }
  if (mat->ops.setfromoptions) PetscCall(mat->ops.setfromoptions(mat));
  if (view) PetscCall(MaterialView(mat, NULL));
  PetscFunctionReturn(0);
}

PetscErrorCode MaterialGetYoungModulus(Material mat, PetscReal *E)
{
  PetscFunctionBeginUser;
  PetscCheck(mat && E, PETSC_COMM_SELF, PETSC_ERR_ARG_NULL, "null pointer argument");
  PetscCheck(mat->type_name[0], mat->comm, PETSC_ERR_ORDER, "material has no type: call MaterialSetFromOptions() first");
  *E = mat->modulus;
  PetscFunctionReturn(0);
}

PetscErrorCode MaterialGetKernel(Material mat, const MaterialKernel **k)
{
  PetscFunctionBeginUser;
  PetscCheck(mat && k, PETSC_COMM_SELF, PETSC_ERR_ARG_NULL, "null pointer argument");
  PetscCheck(mat->type_name[0], mat->comm, PETSC_ERR_ORDER, "material has no type: call MaterialSetFromOptions() first");
  *k = &mat->kernel;
  PetscFunctionReturn(0);
}

PetscErrorCode MaterialGetType(Material mat, const char **type)
{
  PetscFunctionBeginUser;
  PetscCheck(mat && type, PETSC_COMM_SELF, PETSC_ERR_ARG_NULL, "null pointer argument");
  PetscCheck(mat->type_name[0], mat->comm, PETSC_ERR_ORDER, "material has no type: call MaterialSetFromOptions() first");
  *type = mat->type_name;
  PetscFunctionReturn(0);
}

PetscErrorCode MaterialView(Material mat, PetscViewer v)
{
  PetscBool ascii;

  PetscFunctionBeginUser;
  PetscCheck(mat, PETSC_COMM_SELF, PETSC_ERR_ARG_NULL, "null pointer: argument 1");
  if (!v) v = PETSC_VIEWER_STDOUT_(mat->comm);
  PetscCall(PetscObjectTypeCompare((PetscObject)v, PETSCVIEWERASCII, &ascii));
  if (!ascii) PetscFunctionReturn(0);
  {
    PetscBool def;
    PetscCall(PetscStrcmp(mat->prefix, MATERIAL_DEFAULT_PREFIX, &def));
    if (def) PetscCall(PetscViewerASCIIPrintf(v, "Material: type %s\n", mat->type_name[0] ? mat->type_name : "(not set)"));
    else PetscCall(PetscViewerASCIIPrintf(v, "Material (-%s): type %s\n", mat->prefix, mat->type_name[0] ? mat->type_name : "(not set)"));
  }
  if (mat->ops.view) {
    PetscCall(PetscViewerASCIIPushTab(v));
    PetscCall(mat->ops.view(mat, v));
    PetscCall(PetscViewerASCIIPopTab(v));
  }
  PetscFunctionReturn(0);
}

PetscErrorCode MaterialDestroy(Material *mat)
{
  PetscFunctionBeginUser;
  if (!mat || !*mat) PetscFunctionReturn(0);
  PetscCall(MaterialReset(*mat));
  PetscCall(PetscFree(*mat));
  PetscFunctionReturn(0);
}
