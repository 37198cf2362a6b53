/* Projection cost on a meshed tool surface (scripts/bench_tool_facets.py builds and runs this):
   bench_tool_facets -tool_names s -tool_s_file sphere.stl [-tool_s_smooth 0] -bench_queries N
   or, for the hinted node passes alone (medians of interleaved runs, doc/notes/tools-log.md "Cost"):
   bench_tool_facets -tool_names s -tool_s_file sphere.stl [-tool_s_smooth 0] -bench_node_passes BAND[,BAND...] [-bench_reps 5] [-bench_cputime]
   or, for the tool's storage per array (bytes per facet):
   bench_tool_facets -tool_names s -tool_s_file sphere.stl -bench_bytes
   or, to compare two builds bit for bit (ToolProject's and ToolProjectHint's results to a file):
   bench_tool_facets -tool_names s -tool_s_file sphere.stl [-tool_s_smooth 0] -bench_dump FILE
   prints one line: facets, build seconds, bytes per facet, ns per ToolProject and per
   ToolProjectHint (hint: the projection of a point 1e-3 R away, as a node's previous pairing),
   the queries in random order, then the same in a spatially coherent order (sorted along a
   Morton curve, as a mesh's nodes come), smoothing */
#define _POSIX_C_SOURCE 200809L
#include <stdio.h>
#include <stdlib.h>
#include <time.h>

#include "tool.h"
#include "../src/tool/facets.h"

static clockid_t clk = CLOCK_MONOTONIC; /* -bench_cputime: the thread's processor time instead (on a machine
                                           shared with other work the wall time counts the time the
                                           process waits for a core) */

static double now(void)
{
  struct timespec t;
  clock_gettime(clk, &t);
  return t.tv_sec + 1e-9 * t.tv_nsec;
}

static double mkey(const double y[3], double R)
{ /* Morton code of y in the box [-1.1 R, 1.1 R]^3, 21 bits per axis */
  unsigned long long k = 0;
  unsigned           c[3];
  for (int i = 0; i < 3; i++) c[i] = (unsigned)((y[i] / (2.2 * R) + 0.5) * 2097151.0);
  for (int b = 20; b >= 0; b--)
    for (int i = 0; i < 3; i++) k = (k << 1) | ((c[i] >> b) & 1u);
  return (double)k;
}

typedef struct {
  double key;
  int    k;
} Key;
static int CmpKey(const void *a, const void *b) { return ((const Key *)a)->key < ((const Key *)b)->key ? -1 : ((const Key *)a)->key > ((const Key *)b)->key; }

static void Time(const Tool *T, const double *Y, const Projection *P, const int *ord, PetscInt nq, double *tp, double *th, double *acc)
{
  const double sh[3] = {0, 0, 0};
  double       t0    = now();
  for (PetscInt q = 0; q < nq; q++) {
    Projection pr;
    ToolProject(T, sh, &Y[3 * ord[q]], PETSC_INFINITY, &pr);
    *acc += pr.gap;
  }
  *tp = now() - t0;
  t0  = now();
  for (PetscInt q = 0; q < nq; q++) {
    Projection pr;
    ToolProjectHint(T, sh, &Y[3 * ord[q]], PETSC_INFINITY, &P[ord[q]], &pr);
    *acc -= pr.gap;
  }
  *th = now() - t0;
}

/* node passes, as the contact object pairs its slave nodes: nn nodes at band R of the surface
   (radius R (1 - band) to R (1 + band)), taken in a coherent (Morton) order, each moving by up to
   1e-3 R per pass; hinted: each query hinted by the node's previous result. ns per node-pass. */
static double NodePasses(const Tool *T, double R, double band, int nn, int passes, int hinted, double *acc)
{
  const double sh[3] = {0, 0, 0};
  double      *Y, t = 0.0;
  Projection  *P;
  int         *has, *ord;
  Key         *key;
  PetscCallAbort(PETSC_COMM_SELF, PetscMalloc5(3 * (size_t)nn * passes, &Y, nn, &P, nn, &has, nn, &ord, nn, &key));
  srand(7);
  for (int k = 0; k < nn; k++) {
    double d[3], l;
    do {
      for (int i = 0; i < 3; i++) d[i] = 2.0 * rand() / RAND_MAX - 1.0;
      l = sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
    } while (l > 1.0 || l < 1e-3);
    const double r = R * (1.0 - band + 2.0 * band * rand() / RAND_MAX);
    for (int q = 0; q < passes; q++)
      for (int i = 0; i < 3; i++) Y[3 * ((size_t)q * nn + k) + i] = (q ? Y[3 * ((size_t)(q - 1) * nn + k) + i] : r * d[i] / l) + (q ? 1e-3 * R * (2.0 * rand() / RAND_MAX - 1.0) : 0.0);
    key[k].key = mkey(&Y[3 * k], R);
    key[k].k   = k;
    has[k]     = 0;
  }
  qsort(key, nn, sizeof(*key), CmpKey);
  for (int k = 0; k < nn; k++) ord[k] = key[k].k;
  for (int q = 0; q < passes; q++) {
    const double t0 = now();
    for (int j = 0; j < nn; j++) {
      const int  k = ord[j];
      Projection pr;
      const int  r = hinted ? ToolProjectHint(T, sh, &Y[3 * ((size_t)q * nn + k)], PETSC_INFINITY, has[k] ? &P[k] : NULL, &pr) : ToolProject(T, sh, &Y[3 * ((size_t)q * nn + k)], PETSC_INFINITY, &pr);
      if (!r) {
        P[k]   = pr;
        has[k] = 1;
        *acc += pr.gap;
      }
    }
    if (q) t += now() - t0; /* the first pass has no hints */
  }
  PetscCallAbort(PETSC_COMM_SELF, PetscFree5(Y, P, has, ord, key));
  return 1e9 * t / ((double)nn * (passes - 1));
}

int main(int argc, char **argv)
{
  PetscInt n, nq = 200000;
  Tool    *T;
  double   t0, tb, acc = 0, sh[3] = {0, 0, 0};
  PetscReal band[8];
  PetscInt  nband = 8;
  PetscInt  reps = 5;
  PetscBool bytes = PETSC_FALSE;
  char      dump[PETSC_MAX_PATH_LEN] = "";
  PetscCall(PetscInitialize(&argc, &argv, NULL, NULL));
  PetscCall(PetscOptionsGetInt(NULL, NULL, "-bench_queries", &nq, NULL));
  {
    PetscBool set;
    PetscCall(PetscOptionsGetRealArray(NULL, NULL, "-bench_node_passes", band, &nband, &set));
    if (!set) nband = 0;
  }
  PetscCall(PetscOptionsGetInt(NULL, NULL, "-bench_reps", &reps, NULL));
  PetscCall(PetscOptionsGetBool(NULL, NULL, "-bench_bytes", &bytes, NULL));
  {
    PetscBool cpu = PETSC_FALSE;
    PetscCall(PetscOptionsGetBool(NULL, NULL, "-bench_cputime", &cpu, NULL));
    if (cpu) clk = CLOCK_THREAD_CPUTIME_ID;
  }
  PetscCall(PetscOptionsGetString(NULL, NULL, "-bench_dump", dump, sizeof(dump), NULL));
  t0 = now();
  PetscCall(ToolsCreateFromOptions(PETSC_COMM_WORLD, &n, &T));
  tb                  = now() - t0;
  if (bytes) { /* the tool's storage per array, bytes per facet */
    const FacetsData *m = (const FacetsData *)T[0].patch[0].data;
    FacetsBytesBreakdown(m, stdout);
    PetscCall(ToolsDestroy(n, &T));
    PetscCall(PetscFinalize());
    return 0;
  }
  if (dump[0]) { /* the results of ToolProject and of ToolProjectHint (node passes at 1e-4, 1e-2 and
                    5e-2 R) written to a file, to compare two builds of the code bit for bit */
    FILE        *fp = fopen(dump, "wb");
    const double R  = 0.5 * (T[0].bbox[1] - T[0].bbox[0]), bands[3] = {1e-4, 1e-2, 5e-2};
    PetscCheck(fp, PETSC_COMM_SELF, PETSC_ERR_FILE_OPEN, "-bench_dump: cannot write %s", dump);
    srand(3);
    for (int b = 0; b < 3; b++)
      for (int k = 0; k < 2000; k++) {
        double     d[3], l, y[3];
        Projection prev, pr;
        int        has = 0;
        do {
          for (int i = 0; i < 3; i++) d[i] = 2.0 * rand() / RAND_MAX - 1.0;
          l = sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
        } while (l > 1.0 || l < 1e-3);
        for (int q = 0; q < 8; q++) {
          const double r = R * (1.0 + bands[b] * (2.0 * rand() / RAND_MAX - 1.0));
          for (int i = 0; i < 3; i++) d[i] += 2e-3 * (2.0 * rand() / RAND_MAX - 1.0);
          l = sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
          for (int i = 0; i < 3; i++) y[i] = r * d[i] / l;
          const int r0 = ToolProject(&T[0], sh, y, PETSC_INFINITY, &pr);
          double    o[8] = {r0, pr.xi, pr.eta, pr.gap, pr.n[0], pr.n[1], pr.n[2], 0};
          const int r1 = ToolProjectHint(&T[0], sh, y, PETSC_INFINITY, has ? &prev : NULL, &pr);
          o[7]         = (r1 != r0) || (!r1 && (pr.xi != o[1] || pr.eta != o[2] || pr.gap != o[3]));
          if (!r1) {
            prev = pr;
            has  = 1;
          }
          fwrite(o, sizeof(double), 8, fp);
        }
      }
    fclose(fp);
    PetscCall(ToolsDestroy(n, &T));
    PetscCall(PetscFinalize());
    return 0;
  }
  if (nband > 0) { /* only the hinted node passes at these bands: -bench_reps sets of 10 passes of 20000 nodes each */
    const double R = 0.5 * (T[0].bbox[1] - T[0].bbox[0]);
    for (PetscInt b = 0; b < nband; b++) {
      printf("build %.2f s; hinted node passes at band %g, ns per node and pass:", tb, (double)band[b]);
      for (PetscInt r = 0; r < reps; r++) printf(" %.0f", NodePasses(&T[0], R, band[b], 20000, 11, 1, &acc));
      printf(" (%g)\n", acc);
    }
    PetscCall(ToolsDestroy(n, &T));
    PetscCall(PetscFinalize());
    return 0;
  }
  const FacetsData *m = (const FacetsData *)T[0].patch[0].data;
  const double      R = 0.5 * (T[0].bbox[1] - T[0].bbox[0]);
  double           *Y, *Z;
  Projection       *P;
  PetscCall(PetscMalloc3(3 * nq, &Y, 3 * nq, &Z, nq, &P));
  srand(1);
  for (PetscInt k = 0; k < nq; k++) { /* near the surface: radius 0.95 R to 1.05 R, any direction */
    double d[3], l;
    do {
      for (int i = 0; i < 3; i++) d[i] = 2.0 * rand() / RAND_MAX - 1.0;
      l = sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
    } while (l > 1.0 || l < 1e-3);
    const double r = R * (0.95 + 0.1 * rand() / RAND_MAX);
    for (int i = 0; i < 3; i++) {
      Y[3 * k + i] = r * d[i] / l;
      Z[3 * k + i] = Y[3 * k + i] + 1e-3 * R * (2.0 * rand() / RAND_MAX - 1.0);
    }
  }
  for (PetscInt k = 0; k < nq; k++) ToolProject(&T[0], sh, &Z[3 * k], PETSC_INFINITY, &P[k]); /* the hints */
  {
    int   *ord;
    Key   *key;
    double tr, thr, tc, thc;
    PetscCall(PetscMalloc2(nq, &ord, nq, &key));
    for (PetscInt k = 0; k < nq; k++) ord[k] = (int)k;
    Time(&T[0], Y, P, ord, nq, &tr, &thr, &acc);
    for (PetscInt k = 0; k < nq; k++) {
      key[k].key = mkey(&Y[3 * k], R);
      key[k].k   = (int)k;
    }
    qsort(key, nq, sizeof(*key), CmpKey);
    for (PetscInt k = 0; k < nq; k++) ord[k] = key[k].k;
    Time(&T[0], Y, P, ord, nq, &tc, &thc, &acc);
    {
      const int    nn = (int)(nq / 10 > 1000 ? nq / 10 : 1000), np = 11;
      const double a0 = NodePasses(&T[0], R, 0.05, nn, np, 0, &acc), a1 = NodePasses(&T[0], R, 0.05, nn, np, 1, &acc);
      const double b0 = NodePasses(&T[0], R, 1e-3, nn, np, 0, &acc), b1 = NodePasses(&T[0], R, 1e-3, nn, np, 1, &acc);
      printf("%d %.3f %.1f %.1f %.1f %.1f %.1f %d %.1f %.1f %.1f %.1f %g\n", m->nf, tb, (double)FacetsBytes(m) / m->nf, 1e9 * tr / nq, 1e9 * thr / nq, 1e9 * tc / nq, 1e9 * thc / nq, m->smooth, a0, a1, b0, b1, acc);
    }
    PetscCall(PetscFree2(ord, key));
  }
  PetscCall(PetscFree3(Y, Z, P));
  PetscCall(ToolsDestroy(n, &T));
  PetscCall(PetscFinalize());
  return 0;
}
