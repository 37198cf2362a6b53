/* The contact work of a forming process over the parts of a large mesh (scripts/process_balance.py
   builds and runs this): the box mesh of a quarter blank, NX x NY x NZ hexahedra on
   [0, LX] x [0, LY] x [0, LZ], partitioned with METIS exactly as the code does
   (MeshPartitionCells of src/mesh/partition.c: the cells balanced, or with BALANCE = contact the
   cells and the slave nodes, the top and bottom faces, together, as -partition_balance contact)
   into each given number of parts; a vertex owned by the lowest-numbered part around it. Then, for
   each time of a process, the vertices in contact with each tool (a flags file: per time one byte
   per vertex, bit k set when the vertex touches tool k) counted per part.

   usage: partition_process NX NY NZ LX LY LZ cells|contact FLAGS NTIMES NTOOLS P1 [P2 ...]
   output: "mesh cells N vertices N slaves N", then per P
     "parts P cut C cells_max M cells_mean M slaves_max M slaves_mean M seconds S"
   and per P, time and tool "time P T tool K max M mean M" (the vertices in contact owned per part;
   tool NTOOLS: in contact with any tool) */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include "meshgen.h"

static double now(void)
{
  struct timespec ts;
  clock_gettime(CLOCK_MONOTONIC, &ts);
  return ts.tv_sec + 1e-9 * ts.tv_nsec;
}

int main(int argc, char **argv)
{
  MeshData m;

  if (argc < 12 || atoi(argv[10]) < 1 || atoi(argv[10]) > 8 || (strcmp(argv[7], "cells") && strcmp(argv[7], "contact"))) {
    fprintf(stderr, "usage: partition_process NX NY NZ LX LY LZ cells|contact FLAGS NTIMES NTOOLS P1 [P2 ...]\n");
    return 1;
  }
  if (PetscInitializeNoArguments()) return 1;
  memset(&m, 0, sizeof(m));
  const PetscInt  n[3]  = {atoi(argv[1]), atoi(argv[2]), atoi(argv[3])};
  const PetscReal lo[3] = {0, 0, 0}, hi[3] = {atof(argv[4]), atof(argv[5]), atof(argv[6])};
  if (MeshDataCreateBox(lo, hi, n, &m)) return 2;
  const long      ne = (long)m.ne, nn = (long)m.nv, ntimes = atol(argv[9]);
  const int       ntools = atoi(argv[10]), balance_contact = !strcmp(argv[7], "contact");
  PetscBool      *slave  = calloc((size_t)nn, sizeof(PetscBool));
  PetscInt       *ep     = malloc(sizeof(PetscInt) * (size_t)ne);
  int            *vown   = malloc(sizeof(int) * (size_t)nn);
  unsigned char  *flags  = malloc((size_t)nn * (size_t)ntimes);
  long            nslave = 0;
  FILE           *f      = fopen(argv[8], "rb");
  if (!f || fread(flags, 1, (size_t)nn * (size_t)ntimes, f) != (size_t)nn * (size_t)ntimes) {
    fprintf(stderr, "partition_process: %s: expected %ld bytes (%ld times x %ld vertices)\n", argv[8], nn * ntimes, ntimes, nn);
    return 3;
  }
  fclose(f);
  for (PetscInt s = 0; s < m.nnset; s++)
    if (!strcmp(m.nsets[s].name, "zmin") || !strcmp(m.nsets[s].name, "zmax"))
      for (PetscInt k = 0; k < m.nsets[s].n; k++) slave[m.nsets[s].idx[k]] = 1;
  for (long v = 0; v < nn; v++) nslave += slave[v];
  printf("mesh cells %ld vertices %ld slaves %ld\n", ne, nn, nslave);
  fflush(stdout);
  for (int arg = 11; arg < argc; arg++) {
    const int nparts = atoi(argv[arg]);
    PetscInt  cut;
    double    t0 = now();
    if (MeshPartitionCells(m.ne, m.nv, m.conn, balance_contact ? slave : NULL, nparts, ep, &cut)) return 4;
    const double tpart = now() - t0;
    long        *cells = calloc((size_t)nparts, sizeof(long)), *slaves = calloc((size_t)nparts, sizeof(long));
    const int    nk    = ntools + 1; /* the tools, then any tool */
    long        *cnt   = malloc(sizeof(long) * (size_t)nparts * (size_t)nk);
    long         cmax = 0, smax = 0;
    for (long v = 0; v < nn; v++) vown[v] = nparts;
    for (long e = 0; e < ne; e++) {
      cells[ep[e]]++;
      for (int a = 0; a < 8; a++) {
        const PetscInt v = m.conn[8 * e + a];
        if (ep[e] < vown[v]) vown[v] = (int)ep[e];
      }
    }
    for (long v = 0; v < nn; v++)
      if (slave[v]) slaves[vown[v]]++;
    for (int p = 0; p < nparts; p++) {
      if (cells[p] > cmax) cmax = cells[p];
      if (slaves[p] > smax) smax = slaves[p];
    }
    printf("parts %d cut %ld cells_max %ld cells_mean %.1f slaves_max %ld slaves_mean %.1f seconds %.2f\n", nparts, (long)cut, cmax, (double)ne / nparts, smax, (double)nslave / nparts, tpart);
    for (long t = 0; t < ntimes; t++) {
      const unsigned char *fl = flags + (size_t)t * (size_t)nn;
      memset(cnt, 0, sizeof(long) * (size_t)nparts * (size_t)nk);
      long tot[9] = {0};
      for (long v = 0; v < nn; v++) {
        for (int k = 0; k < ntools; k++)
          if (fl[v] & (1u << k)) {
            cnt[(size_t)vown[v] * (size_t)nk + (size_t)k]++;
            tot[k]++;
          }
        if (fl[v]) {
          cnt[(size_t)vown[v] * (size_t)nk + (size_t)ntools]++;
          tot[ntools]++;
        }
      }
      for (int k = 0; k < nk; k++) {
        long mx = 0;
        for (int p = 0; p < nparts; p++)
          if (cnt[(size_t)p * (size_t)nk + (size_t)k] > mx) mx = cnt[(size_t)p * (size_t)nk + (size_t)k];
        printf("time %d %ld tool %d max %ld mean %.3f\n", nparts, t, k, mx, (double)tot[k] / nparts);
      }
    }
    fflush(stdout);
    free(cells);
    free(slaves);
    free(cnt);
  }
  free(slave);
  free(ep);
  free(vown);
  free(flags);
  MeshDataDestroy(&m);
  PetscFinalize();
  return 0;
}
