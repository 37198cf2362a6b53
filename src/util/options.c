/* The names of the options the code reads (include/options.h), and the check that refuses a
   misspelt one before the run starts. */
#include <string.h>
#include "options.h"

#define MAX_KNOWN 4096
#define NAME_LEN  128
static char   known[MAX_KNOWN][NAME_LEN];
static size_t nknown;

void AtritoOptionsRecord(const PetscOptionItems *items, const char opt[])
{
  char        name[NAME_LEN];
  const char *pre = (items && items->prefix) ? items->prefix : "";

  if (!opt || opt[0] != '-') return;
  snprintf(name, sizeof(name), "-%s%s", pre, opt + 1);
  for (size_t i = 0; i < nknown; i++)
    if (!strcmp(known[i], name)) return;
  if (nknown < MAX_KNOWN) memcpy(known[nknown++], name, sizeof(name));
}

/* edit distance (insertions, deletions, substitutions, transpositions of neighbours) */
static size_t Distance(const char *a, const char *b)
{
  size_t la = strlen(a), lb = strlen(b), d[NAME_LEN + 1][NAME_LEN + 1];

  if (la > NAME_LEN) la = NAME_LEN;
  if (lb > NAME_LEN) lb = NAME_LEN;
  for (size_t i = 0; i <= la; i++) d[i][0] = i;
  for (size_t j = 0; j <= lb; j++) d[0][j] = j;
  for (size_t i = 1; i <= la; i++)
    for (size_t j = 1; j <= lb; j++) {
      size_t v = d[i - 1][j - 1] + (a[i - 1] != b[j - 1]);
      if (d[i - 1][j] + 1 < v) v = d[i - 1][j] + 1;
      if (d[i][j - 1] + 1 < v) v = d[i][j - 1] + 1;
      if (i > 1 && j > 1 && a[i - 1] == b[j - 2] && a[i - 2] == b[j - 1] && d[i - 2][j - 2] + 1 < v) v = d[i - 2][j - 2] + 1;
      d[i][j] = v;
    }
  return d[la][lb];
}

static const char *Closest(const char name[], size_t *dist)
{
  const char *best = NULL;
  size_t      dbest = (size_t)-1;

  for (size_t i = 0; i < nknown; i++) {
    const size_t d = Distance(name, known[i]);
    if (d < dbest) {
      dbest = d;
      best  = known[i];
    }
  }
  *dist = dbest;
  return best;
}

const char *AtritoOptionsClosest(const char name[])
{
  size_t d;
  return Closest(name, &d);
}

/* the first word of an option name: "-contact_friction" -> "contact" (length returned) */
static size_t FirstWord(const char *name, const char **w)
{
  while (*name == '-') name++;
  *w = name;
  return strcspn(name, "_");
}

static PetscBool KnownPrefix(const char *name)
{
  const char *w;
  size_t      n = FirstWord(name, &w);

  for (size_t i = 0; i < nknown; i++) {
    const char *k;
    size_t      m = FirstWord(known[i], &k);
    if (m == n && !strncmp(w, k, n)) return PETSC_TRUE;
  }
  return PETSC_FALSE;
}

PetscErrorCode AtritoOptionsCheckUnknown(MPI_Comm comm)
{
  PetscInt N;
  char   **names, **values, msg[512] = "";

  PetscFunctionBeginUser;
  PetscCall(PetscOptionsLeftGet(NULL, &N, &names, &values));
  for (PetscInt i = 0; i < N; i++) {
    char        full[NAME_LEN];
    size_t      d;
    const char *c;
    snprintf(full, sizeof(full), "-%s", names[i]);
    if (!KnownPrefix(full)) continue;
    c = Closest(full, &d);
    if (c && d <= ATRITO_OPTIONS_MISSPELT) {
      /* a misspelling: refused */
      if (!msg[0]) PetscCall(PetscSNPrintf(msg, sizeof(msg), "unknown option %s (did you mean %s?)", full, c));
    } else /* an option of another type, tool or condition than this case has: warned now and at the end */
      PetscCall(PetscPrintf(comm, "WARNING: option %s is read by no part of this case%s%s%s\n", full, c ? " (closest: " : "", c ? c : "", c ? ")" : ""));
  }
  PetscCall(PetscOptionsLeftRestore(NULL, &N, &names, &values));
  PetscCheck(!msg[0], comm, PETSC_ERR_USER_INPUT, "%s", msg);
  PetscFunctionReturn(0);
}
