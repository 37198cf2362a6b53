/* Options: every option the code reads is read inside a PetscOptionsBegin block of the module
   that owns it (so that -help lists it under that module's title), and is recorded here, so that
   a misspelt option with one of the code's prefixes can be refused before the run starts, naming
   the closest known option.

   Recording is transparent: this header redefines PETSc's PetscOptions<Type> macros (which
   expand to PetscOptions<Type>_Private(PetscOptionsObject, ...)) to record the full name,
   prefix included, before the call. Include it after the PETSc headers in every module that
   reads options. */
#ifndef ATRITO_OPTIONS_H
#define ATRITO_OPTIONS_H
#include <petscsys.h>

/* records PetscOptionsObject's prefix + opt (opt starts with '-'); never fails */
void AtritoOptionsRecord(const PetscOptionItems *items, const char opt[]);
/* Before any work, for every option that was set but not used and whose first word (up to the
   first '_') is the first word of an option the code knows: when a known option lies within
   ATRITO_OPTIONS_MISSPELT edits (insertions, deletions, substitutions, swaps of neighbours), the
   run is refused (collectively), naming it: -contact_fricton -> "did you mean
   -contact_friction?"; otherwise (an option of a patch type, material or condition this case
   does not have) a warning is printed at once, and again at the end with the other unused ones. */
#define ATRITO_OPTIONS_MISSPELT 2
PetscErrorCode AtritoOptionsCheckUnknown(MPI_Comm comm);
/* The closest recorded option to name (Levenshtein distance); NULL when none is recorded */
const char *AtritoOptionsClosest(const char name[]);

#undef PetscOptionsReal
#undef PetscOptionsInt
#undef PetscOptionsBool
#undef PetscOptionsString
#undef PetscOptionsEList
#undef PetscOptionsFList
#undef PetscOptionsEnum
#undef PetscOptionsRealArray
#undef PetscOptionsIntArray
#undef PetscOptionsStringArray
#undef PetscOptionsBoolArray
#define PetscOptionsReal(a, b, c, d, e, f)        (AtritoOptionsRecord(PetscOptionsObject, a), PetscOptionsReal_Private(PetscOptionsObject, a, b, c, d, e, f))
#define PetscOptionsInt(a, b, c, d, e, f)         (AtritoOptionsRecord(PetscOptionsObject, a), PetscOptionsInt_Private(PetscOptionsObject, a, b, c, d, e, f, PETSC_MIN_INT, PETSC_MAX_INT))
#define PetscOptionsBool(a, b, c, d, e, f)        (AtritoOptionsRecord(PetscOptionsObject, a), PetscOptionsBool_Private(PetscOptionsObject, a, b, c, d, e, f))
#define PetscOptionsString(a, b, c, d, e, f, g)   (AtritoOptionsRecord(PetscOptionsObject, a), PetscOptionsString_Private(PetscOptionsObject, a, b, c, d, e, f, g))
#define PetscOptionsEList(a, b, c, d, e, f, g, h) (AtritoOptionsRecord(PetscOptionsObject, a), PetscOptionsEList_Private(PetscOptionsObject, a, b, c, d, e, f, g, h))
#define PetscOptionsFList(a, b, c, d, e, f, g, h) (AtritoOptionsRecord(PetscOptionsObject, a), PetscOptionsFList_Private(PetscOptionsObject, a, b, c, d, e, f, g, h))
#define PetscOptionsEnum(a, b, c, d, e, f, g)     (AtritoOptionsRecord(PetscOptionsObject, a), PetscOptionsEnum_Private(PetscOptionsObject, a, b, c, d, e, f, g))
#define PetscOptionsRealArray(a, b, c, d, e, f)   (AtritoOptionsRecord(PetscOptionsObject, a), PetscOptionsRealArray_Private(PetscOptionsObject, a, b, c, d, e, f))
#define PetscOptionsIntArray(a, b, c, d, e, f)    (AtritoOptionsRecord(PetscOptionsObject, a), PetscOptionsIntArray_Private(PetscOptionsObject, a, b, c, d, e, f))
#define PetscOptionsStringArray(a, b, c, d, e, f) (AtritoOptionsRecord(PetscOptionsObject, a), PetscOptionsStringArray_Private(PetscOptionsObject, a, b, c, d, e, f))
#define PetscOptionsBoolArray(a, b, c, d, e, f)   (AtritoOptionsRecord(PetscOptionsObject, a), PetscOptionsBoolArray_Private(PetscOptionsObject, a, b, c, d, e, f))
#endif
