/* Partition statistics of a blank mesh for the scaling model (scripts/scaling_model.py builds and
   runs this): the built-in clamped blank (quarter, O-grid) of the given size, partitioned with
   METIS exactly as the code does (MeshPartitionCells of src/mesh/partition.c: the cells balanced,
   or with BALANCE = contact the cells and the contact slave nodes together, as
   -partition_balance contact) into each of the given numbers of parts, and per part: owned cells, vertices touched (owned and ghost), owned
   vertices, neighbours (parts sharing a vertex), contact slave nodes owned (top and bottom sets).
   A vertex is owned by the lowest-numbered part among the cells around it (the model's
   assumption; PETSc's distribution makes a similar choice).

   usage: partition_stats [-whole] CORE_CELLS RADIAL_CELLS LAYERS BALANCE P1 [P2 ...]   (BALANCE: cells or contact;
          -whole: the whole disk, -blank_quarter false, instead of the quarter)
   output: one line "mesh cells N vertices N slaves N" and per P one line
     "parts P cut C cells_max M cells_mean M verts_owned_max .. ghosts_max .. ghosts_mean ..
      ghost_frac_max .. neighbours_max .. neighbours_mean .. slaves_max .. slaves_mean .. seconds S" */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include <metis.h>
#include "meshgen.h"

static double now(void)
{
  struct timespec ts;
  clock_gettime(CLOCK_MONOTONIC, &ts);
  return ts.tv_sec + 1e-9 * ts.tv_nsec;
}

static int cmpint(const void *a, const void *b) { return (*(const idx_t *)a > *(const idx_t *)b) - (*(const idx_t *)a < *(const idx_t *)b); }

int main(int argc, char **argv)
{
  MeshData  m;
  PetscBool quarter = PETSC_TRUE;

  if (argc > 1 && !strcmp(argv[1], "-whole")) {
    quarter = PETSC_FALSE;
    argv++;
    argc--;
  }
  if (argc < 6 || (strcmp(argv[4], "cells") && strcmp(argv[4], "contact"))) {
    fprintf(stderr, "usage: partition_stats [-whole] CORE_CELLS RADIAL_CELLS LAYERS cells|contact P1 [P2 ...]\n");
    return 1;
  }
  if (PetscInitializeNoArguments()) return 1;
  memset(&m, 0, sizeof(m));
  if (MeshDataCreateBlank(59.18, 1.0, 0.4, atoi(argv[1]), atoi(argv[2]), atoi(argv[3]), quarter, &m)) return 2;
  const idx_t ne = (idx_t)m.ne, nn = (idx_t)m.nv;
  PetscBool  *slave = calloc((size_t)nn, sizeof(PetscBool));
  PetscInt   *ep    = malloc(sizeof(PetscInt) * (size_t)ne);
  const int   balance_contact = !strcmp(argv[4], "contact");
  idx_t       nslave = 0;
  for (PetscInt s = 0; s < m.nnset; s++)
    if (!strcmp(m.nsets[s].name, "top") || !strcmp(m.nsets[s].name, "bottom"))
      for (PetscInt k = 0; k < m.nsets[s].n; k++) slave[m.nsets[s].idx[k]] = 1;
  for (idx_t v = 0; v < nn; v++) nslave += slave[v];
  printf("mesh cells %ld vertices %ld slaves %ld\n", (long)ne, (long)nn, (long)nslave);
  fflush(stdout);

  idx_t *eptr = malloc(sizeof(idx_t) * (size_t)(ne + 1)), *eind = malloc(sizeof(idx_t) * 8 * (size_t)ne);
  idx_t *epart = malloc(sizeof(idx_t) * (size_t)ne), *npart = malloc(sizeof(idx_t) * (size_t)nn);
  idx_t *vown = malloc(sizeof(idx_t) * (size_t)nn);
  for (idx_t e = 0; e <= ne; e++) eptr[e] = 8 * e;
  for (idx_t i = 0; i < 8 * ne; i++) eind[i] = (idx_t)m.conn[i];
  /* cells around each vertex (CSR) */
  idx_t *vptr = calloc((size_t)nn + 1, sizeof(idx_t)), *vcell;
  for (idx_t i = 0; i < 8 * ne; i++) vptr[eind[i] + 1]++;
  for (idx_t v = 0; v < nn; v++) vptr[v + 1] += vptr[v];
  vcell = malloc(sizeof(idx_t) * 8 * (size_t)ne);
  {
    idx_t *fill = calloc((size_t)nn, sizeof(idx_t));
    for (idx_t e = 0; e < ne; e++)
      for (int a = 0; a < 8; a++) {
        const idx_t v = eind[8 * e + a];
        vcell[vptr[v] + fill[v]++] = e;
      }
    free(fill);
  }

  for (int arg = 5; arg < argc; arg++) {
    idx_t    nparts = atoi(argv[arg]), objval;
    PetscInt cut;
    double   t0 = now();
    if (MeshPartitionCells(m.ne, m.nv, m.conn, balance_contact ? slave : NULL, nparts, ep, &cut)) return 3;
    const double tpart = now() - t0;
    objval = (idx_t)cut;
    for (idx_t e = 0; e < ne; e++) epart[e] = (idx_t)ep[e];
    long *cells = calloc((size_t)nparts, sizeof(long)), *owned = calloc((size_t)nparts, sizeof(long)), *touched = calloc((size_t)nparts, sizeof(long));
    long *slaves = calloc((size_t)nparts, sizeof(long)), *nbrs = calloc((size_t)nparts, sizeof(long));
    for (idx_t e = 0; e < ne; e++) cells[epart[e]]++;
    idx_t *parts = malloc(sizeof(idx_t) * 64);
    /* per vertex: the distinct parts around it; owner = the smallest */
    char *seen = calloc((size_t)nparts * 0 + 1, 1);
    (void)seen;
    /* neighbour pairs: collected per part as a sorted unique list (a hash would do; parts are few per vertex) */
    idx_t **nb = calloc((size_t)nparts, sizeof(idx_t *));
    long  *nbn = calloc((size_t)nparts, sizeof(long)), *nbcap = calloc((size_t)nparts, sizeof(long));
    for (idx_t v = 0; v < nn; v++) {
      int np = 0;
      for (idx_t k = vptr[v]; k < vptr[v + 1]; k++) {
        const idx_t p = epart[vcell[k]];
        int         dup = 0;
        for (int j = 0; j < np; j++) dup |= parts[j] == p;
        if (!dup && np < 64) parts[np++] = p;
      }
      qsort(parts, (size_t)np, sizeof(idx_t), cmpint);
      vown[v] = parts[0];
      owned[parts[0]]++;
      if (slave[v]) slaves[parts[0]]++;
      for (int j = 0; j < np; j++) {
        touched[parts[j]]++;
        for (int i = 0; i < np; i++) {
          if (i == j) continue;
          const idx_t p = parts[j], q = parts[i];
          int         have = 0;
          for (long t = 0; t < nbn[p] && !have; t++) have = nb[p][t] == q;
          if (!have) {
            if (nbn[p] == nbcap[p]) {
              nbcap[p] = nbcap[p] ? 2 * nbcap[p] : 8;
              nb[p]    = realloc(nb[p], sizeof(idx_t) * (size_t)nbcap[p]);
            }
            nb[p][nbn[p]++] = q;
          }
        }
      }
    }
    long   cmax = 0, omax = 0, gmax = 0, nmax = 0, smax = 0;
    double gsum = 0, nsum = 0, fmax = 0, ssum = 0, csum = 0;
    for (idx_t p = 0; p < nparts; p++) {
      const long g = touched[p] - owned[p];
      nbrs[p] = nbn[p];
      if (cells[p] > cmax) cmax = cells[p];
      if (owned[p] > omax) omax = owned[p];
      if (g > gmax) gmax = g;
      if (nbrs[p] > nmax) nmax = nbrs[p];
      if (slaves[p] > smax) smax = slaves[p];
      if (touched[p] && (double)g / touched[p] > fmax) fmax = (double)g / touched[p];
      gsum += g;
      nsum += nbrs[p];
      ssum += slaves[p];
      csum += cells[p];
      free(nb[p]);
    }
    printf("parts %ld cut %ld cells_max %ld cells_mean %.1f verts_owned_max %ld ghosts_max %ld ghosts_mean %.1f ghost_frac_max %.4f neighbours_max %ld neighbours_mean %.2f slaves_max %ld slaves_mean %.1f seconds %.2f\n", (long)nparts, (long)objval, cmax, csum / nparts, omax, gmax, gsum / nparts, fmax, nmax, nsum / nparts, smax, ssum / nparts, tpart);
    fflush(stdout);
    free(cells); free(owned); free(touched); free(slaves); free(nbrs); free(parts); free(seen); free(nb); free(nbn); free(nbcap);
  }
  free(eptr); free(eind); free(epart); free(npart); free(vown); free(vptr); free(vcell); free(slave); free(ep);
  MeshDataDestroy(&m);
  PetscFinalize();
  return 0;
}
