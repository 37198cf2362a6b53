/* The candidate search of contact pairs between bodies (SideCandidates of src/contact/pair.c)
   over the parts of a large two-body mesh, without running it (scripts/pair_search_scaling.py
   builds and runs this; plain C and METIS, no PETSc).

   The mesh: a lower slab of NXL x NXL x NZL hexahedra on [0, L]^2 x [-h, 0] and an upper body of
   NXU x NXU x NZU hexahedra on [c - W/2, c + W/2]^2 x [0, h'] (c = L/2; W = L: a second slab over
   the whole interface, W < L: a square indenter; the thicknesses enter nothing here), separate nodes; the lower body's cells first,
   each body's cells and vertices numbered x fastest, then y, then z. Slave nodes: the upper body's
   bottom vertices; master faces: the lower body's top faces (corners in cyclic order).

   Partitioned as the code does (MeshPartitionCells of src/mesh/partition.c, the cells balanced:
   METIS_PartMeshDual, 4 common nodes, seed 7; part p = rank p); a vertex on a part boundary is
   owned by the highest-numbered part around it (DMPlexDistribute's vote without
   -partition_balance contact, as the comment in src/mesh/mesh.c says); a master face by its
   cell's part. Then per part, at the reference configuration (the first step), what
   SideCandidates computes: the box of its slave nodes, widened by the search distance s = 2 d_max
   (d_max the largest master face diagonal); the candidates it receives (the faces of any owner
   whose box meets the widened box, its own included, as the code's self message); the parts it
   receives from (other than itself); the per-node loop's pairs (slave nodes x candidates); the
   owner's box tests (its faces x the parts with slave nodes); and what it needs: the faces within
   s of one of its slave nodes (the union of its nodes' candidate lists, the per-node test).
   Timed (median of REPS, the thread's CPU time), literally as the code (two passes each, Box
   recomputed per test): on the part with the most per-node pairs its lists by the double loop of
   commit 985c96c and by the bin grid of commit 98b559a (checked to give the same lists); on the
   part with the most owned faces the owner's test (every owned face against every rank's box, both
   commits) and the same with the owner's faces' overall box tried first (a fix, not in the code).

   usage: pair_search_scaling NXL NZL NXU NZU L W REPS P1 [P2 ...]
   output: "mesh ..." then per P one line of "key value" pairs */
#define _POSIX_C_SOURCE 199309L
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include <metis.h>

typedef double PetscReal;

static double now(void)
{
  struct timespec ts;
  clock_gettime(CLOCK_MONOTONIC, &ts);
  return ts.tv_sec + 1e-9 * ts.tv_nsec;
}

/* Box and BoxesMeet as in src/contact/pair.c (PetscMin, PetscMax: the conditional expressions) */
#define PetscMin(a, b) (((a) < (b)) ? (a) : (b))
#define PetscMax(a, b) (((a) < (b)) ? (b) : (a))
static void Box(const PetscReal *x, long n, PetscReal b[6])
{
  b[0] = b[2] = b[4] = 1.7976931348623157e308;
  b[1] = b[3] = b[5] = -1.7976931348623157e308;
  for (long i = 0; i < n; i++)
    for (int d = 0; d < 3; d++) {
      b[2 * d]     = PetscMin(b[2 * d], x[3 * i + d]);
      b[2 * d + 1] = PetscMax(b[2 * d + 1], x[3 * i + d]);
    }
}

static int BoxesMeet(const PetscReal a[6], const PetscReal b[6], PetscReal w)
{
  for (int d = 0; d < 3; d++)
    if (a[2 * d] > b[2 * d + 1] + w || b[2 * d] > a[2 * d + 1] + w) return 0;
  return 1;
}

/* the loops' times: the thread's CPU time (the machine may run other work: time descheduled is not
   counted) */
static double cpu_now(void)
{
  struct timespec ts;
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
  return ts.tv_sec + 1e-9 * ts.tv_nsec;
}

static int cmpd(const void *a, const void *b) { return (*(const double *)a > *(const double *)b) - (*(const double *)a < *(const double *)b); }

static double median(double *t, int n)
{
  qsort(t, (size_t)n, sizeof(double), cmpd);
  return n % 2 ? t[n / 2] : 0.5 * (t[n / 2 - 1] + t[n / 2]);
}

static volatile long sink;

/* the owner's selection, as SideCandidates: two passes over the P boxes and its faces */
static double time_owner(const PetscReal *fox, long nfo, const PetscReal *boxes, int size, PetscReal search, long *ntests)
{
  long   *scount = calloc((size_t)size, sizeof(long)), *sdisp = calloc((size_t)size + 1, sizeof(long)), *sendf = NULL, nsend = 0, tests = 0;
  double  t0     = cpu_now();
  for (int pass = 0; pass < 2; pass++) {
    if (pass) {
      for (int r = 0; r < size; r++) sdisp[r + 1] = sdisp[r] + scount[r];
      nsend = sdisp[size];
      sendf = malloc(sizeof(long) * (size_t)(nsend + 1));
      for (int r = 0; r < size; r++) scount[r] = 0;
    }
    for (int r = 0; r < size; r++) {
      if (boxes[6 * r] > boxes[6 * r + 1]) continue; /* no slave nodes there */
      for (long f = 0; f < nfo; f++) {
        PetscReal fb[6];
        Box(fox + 12 * f, 4, fb);
        tests++;
        if (!BoxesMeet(fb, boxes + 6 * r, search)) continue;
        if (pass) sendf[sdisp[r] + scount[r]] = f;
        scount[r]++;
      }
    }
  }
  const double t = cpu_now() - t0;
  sink += nsend + (nsend ? sendf[nsend - 1] : 0);
  *ntests = tests;
  free(scount);
  free(sdisp);
  free(sendf);
  return t;
}

/* the per-node lists, as SideCandidates at 985c96c: two passes over the slave nodes and the candidates */
static double time_nodes(const PetscReal *ys, long ns, const PetscReal *fcx, long nfc, PetscReal search, long *nlist)
{
  long  *coff = malloc(sizeof(long) * (size_t)(ns + 2)), *cand = NULL, n = 0;
  double t0   = cpu_now();
  for (int pass = 0; pass < 2; pass++) {
    if (pass) cand = malloc(sizeof(long) * (size_t)(n + 1));
    n = 0;
    for (long i = 0; i < ns; i++) {
      PetscReal yb[6];
      Box(ys + 3 * i, 1, yb);
      coff[i] = n;
      for (long c = 0; c < nfc; c++) {
        PetscReal fb[6];
        Box(fcx + 12 * c, 4, fb);
        if (!BoxesMeet(fb, yb, search)) continue;
        if (pass) cand[n] = c;
        n++;
      }
    }
    coff[ns] = n;
  }
  const double t = cpu_now() - t0;
  sink += n + (n ? cand[n - 1] : 0);
  *nlist = n;
  free(coff);
  free(cand);
  return t;
}

/* the per-node lists by a bin grid, as SideCandidates at 98b559a (the same lists): uniform bins
   over the rank's slave box, at least the search distance wide and at most 64 a side; each
   candidate, widened by the search distance, listed in the bins it meets; a node tests its own
   bin's list */
static double time_nodes_binned(const PetscReal *ys, long ns, const PetscReal *fcx, long nfc, PetscReal search, long *nlist)
{
  PetscReal box[6], w[3];
  long      nb[3], nbin = 1, n = 0;
  double    t0 = cpu_now();
  Box(ys, ns, box);
  for (int d = 0; d < 3; d++) {
    const PetscReal ext = box[2 * d + 1] - box[2 * d];
    nb[d] = (long)PetscMin(64, PetscMax(1, floor(ext / search)));
    w[d]  = nb[d] > 1 ? ext / nb[d] : 1.7976931348623157e308;
    nbin *= nb[d];
  }
  long *boff = calloc((size_t)nbin + 1, sizeof(long)), *bfill = calloc((size_t)nbin + 1, sizeof(long)), *blist = NULL, *coff = malloc(sizeof(long) * (size_t)(ns + 2)), *cand = NULL;
#define BIN_RANGE(lo, hi, d, a, b) \
  do { \
    a = nb[d] > 1 ? (long)floor(((lo) - box[2 * (d)]) / w[d]) : 0; \
    b = nb[d] > 1 ? (long)floor(((hi) - box[2 * (d)]) / w[d]) : 0; \
    a = PetscMax(a, 0); \
    b = PetscMin(b, nb[d] - 1); \
  } while (0)
  for (int pass = 0; pass < 2; pass++) {
    if (pass) {
      for (long b = 0; b < nbin; b++) boff[b + 1] += boff[b];
      blist = malloc(sizeof(long) * (size_t)(boff[nbin] + 1));
    }
    for (long c = 0; c < nfc; c++) {
      PetscReal fb[6];
      long      lo[3], hi[3];
      Box(fcx + 12 * c, 4, fb);
      for (int d = 0; d < 3; d++) BIN_RANGE(fb[2 * d] - search, fb[2 * d + 1] + search, d, lo[d], hi[d]);
      for (long i = lo[0]; i <= hi[0]; i++)
        for (long j = lo[1]; j <= hi[1]; j++)
          for (long k = lo[2]; k <= hi[2]; k++) {
            const long b = (i * nb[1] + j) * nb[2] + k;
            if (pass) blist[boff[b] + bfill[b]++] = c;
            else boff[b + 1]++;
          }
    }
  }
  for (int pass = 0; pass < 2; pass++) {
    if (pass) cand = malloc(sizeof(long) * (size_t)(n + 1));
    n = 0;
    for (long i = 0; i < ns; i++) {
      PetscReal yb[6];
      long      bi[3];
      Box(ys + 3 * i, 1, yb);
      for (int d = 0; d < 3; d++) BIN_RANGE(yb[2 * d], yb[2 * d], d, bi[d], bi[d]);
      const long b = (bi[0] * nb[1] + bi[1]) * nb[2] + bi[2];
      coff[i]      = n;
      for (long q = boff[b]; q < boff[b + 1]; q++) {
        const long c = blist[q];
        PetscReal  fb[6];
        Box(fcx + 12 * c, 4, fb);
        if (!BoxesMeet(fb, yb, search)) continue;
        if (pass) cand[n] = c;
        n++;
      }
    }
    coff[ns] = n;
  }
#undef BIN_RANGE
  const double t = cpu_now() - t0;
  sink += n + (n ? cand[n - 1] : 0);
  *nlist = n;
  free(boff); free(bfill); free(blist); free(coff); free(cand);
  return t;
}

/* the owner's selection with its faces' overall box tested against each rank's box first (a fix,
   not in the code; the same faces sent) */
static double time_owner_prefilter(const PetscReal *fox, long nfo, const PetscReal *boxes, int size, PetscReal search, long *nsent)
{
  long     *scount = calloc((size_t)size, sizeof(long)), *sdisp = calloc((size_t)size + 1, sizeof(long)), *sendf = NULL, nsend = 0;
  PetscReal all[6];
  double    t0 = cpu_now();
  Box(fox, 4 * nfo, all);
  for (int pass = 0; pass < 2; pass++) {
    if (pass) {
      for (int r = 0; r < size; r++) sdisp[r + 1] = sdisp[r] + scount[r];
      nsend = sdisp[size];
      sendf = malloc(sizeof(long) * (size_t)(nsend + 1));
      for (int r = 0; r < size; r++) scount[r] = 0;
    }
    for (int r = 0; r < size; r++) {
      if (boxes[6 * r] > boxes[6 * r + 1] || !BoxesMeet(all, boxes + 6 * r, search)) continue;
      for (long f = 0; f < nfo; f++) {
        PetscReal fb[6];
        Box(fox + 12 * f, 4, fb);
        if (!BoxesMeet(fb, boxes + 6 * r, search)) continue;
        if (pass) sendf[sdisp[r] + scount[r]] = f;
        scount[r]++;
      }
    }
  }
  const double t = cpu_now() - t0;
  sink += nsend + (nsend ? sendf[nsend - 1] : 0);
  *nsent = nsend;
  free(scount); free(sdisp); free(sendf);
  return t;
}

int main(int argc, char **argv)
{
  if (argc < 9) {
    fprintf(stderr, "usage: pair_search_scaling NXL NZL NXU NZU L W REPS P1 [P2 ...]\n");
    return 1;
  }
  const long   nxl = atol(argv[1]), nzl = atol(argv[2]), nxu = atol(argv[3]), nzu = atol(argv[4]);
  const double L = atof(argv[5]), W = atof(argv[6]);
  const int    reps = atoi(argv[7]);
  const long   nel = nxl * nxl * nzl, neu = nxu * nxu * nzu, ne = nel + neu;
  const long   nvl = (nxl + 1) * (nxl + 1) * (nzl + 1), nvu = (nxu + 1) * (nxu + 1) * (nzu + 1), nv = nvl + nvu;
  const double x0u = 0.5 * (L - W), dxl = L / nxl, dxu = W / nxu;
#define VL(i, j, k) ((i) + (nxl + 1) * ((j) + (nxl + 1) * (k)))
#define VU(i, j, k) (nvl + (i) + (nxu + 1) * ((j) + (nxu + 1) * (k)))
  idx_t *eptr = malloc(sizeof(idx_t) * (size_t)(ne + 1)), *eind = malloc(sizeof(idx_t) * 8 * (size_t)ne);
  idx_t *part = malloc(sizeof(idx_t) * (size_t)ne), *npart = malloc(sizeof(idx_t) * (size_t)nv);
  {
    long e = 0;
    for (int b = 0; b < 2; b++) {
      const long nx = b ? nxu : nxl, nz = b ? nzu : nzl;
      for (long k = 0; k < nz; k++)
        for (long j = 0; j < nx; j++)
          for (long i = 0; i < nx; i++, e++) {
            idx_t *c = eind + 8 * e;
            for (int a = 0; a < 8; a++) {
              const long ii = i + ((a == 1 || a == 2 || a == 5 || a == 6) ? 1 : 0), jj = j + ((a == 2 || a == 3 || a == 6 || a == 7) ? 1 : 0), kk = k + (a >= 4);
              c[a] = (idx_t)(b ? VU(ii, jj, kk) : VL(ii, jj, kk));
            }
          }
    }
    for (long i = 0; i <= ne; i++) eptr[i] = (idx_t)(8 * i);
  }
  /* master faces: the lower body's top faces, face f = (i, j) of cell nel - nxl^2 + f */
  const long nf = nxl * nxl;
  PetscReal *fx = malloc(sizeof(PetscReal) * 12 * (size_t)nf), *fb = malloc(sizeof(PetscReal) * 6 * (size_t)nf), dmax = 0;
  for (long j = 0; j < nxl; j++)
    for (long i = 0; i < nxl; i++) {
      const long f = i + nxl * j;
      const double cx[4] = {i * dxl, (i + 1) * dxl, (i + 1) * dxl, i * dxl}, cy[4] = {j * dxl, j * dxl, (j + 1) * dxl, (j + 1) * dxl};
      for (int a = 0; a < 4; a++) {
        fx[12 * f + 3 * a]     = cx[a];
        fx[12 * f + 3 * a + 1] = cy[a];
        fx[12 * f + 3 * a + 2] = 0;
      }
      Box(fx + 12 * f, 4, fb + 6 * f);
      for (int a = 0; a < 2; a++) {
        const PetscReal *x = fx + 12 * f;
        dmax = fmax(dmax, sqrt(pow(x[3 * (a + 2)] - x[3 * a], 2) + pow(x[3 * (a + 2) + 1] - x[3 * a + 1], 2) + pow(x[3 * (a + 2) + 2] - x[3 * a + 2], 2)));
      }
    }
  const PetscReal search = 2 * dmax;
  /* slave nodes: the upper body's bottom vertices, s = i + (nxu + 1) j */
  const long ns = (nxu + 1) * (nxu + 1);
  PetscReal *ys = malloc(sizeof(PetscReal) * 3 * (size_t)ns);
  for (long j = 0; j <= nxu; j++)
    for (long i = 0; i <= nxu; i++) {
      const long s = i + (nxu + 1) * j;
      ys[3 * s]     = x0u + i * dxu;
      ys[3 * s + 1] = x0u + j * dxu;
      ys[3 * s + 2] = 0;
    }
  /* the faces within s of each slave node (the per-node test, rank-independent): a bin grid of the
     faces' widened boxes in x, y */
  const double binw = search;
  const long   nb = (long)ceil((L + 2 * search) / binw) + 1;
  long        *bcnt = calloc((size_t)(nb * nb + 1), sizeof(long)), *bidx = NULL;
#define BIN(v) ((long)floor(((v) + search) / binw))
  for (int pass = 0; pass < 2; pass++) {
    if (pass) {
      for (long b = 0; b < nb * nb; b++) bcnt[b + 1] += bcnt[b];
      bidx = malloc(sizeof(long) * (size_t)bcnt[nb * nb]);
    }
    for (long f = 0; f < nf; f++) {
      const PetscReal *b = fb + 6 * f;
      for (long by = BIN(b[2] - search); by <= BIN(b[3] + search); by++)
        for (long bx = BIN(b[0] - search); bx <= BIN(b[1] + search); bx++) {
          if (bx < 0 || by < 0 || bx >= nb || by >= nb) continue;
          if (pass) bidx[--bcnt[bx + nb * by + 1]] = f;
          else bcnt[bx + nb * by + 1]++;
        }
    }
  }
  long *nstart = malloc(sizeof(long) * (size_t)(ns + 1)), *nlist = NULL, ntot = 0;
  for (int pass = 0; pass < 2; pass++) {
    if (pass) nlist = malloc(sizeof(long) * (size_t)ntot);
    ntot = 0;
    for (long s = 0; s < ns; s++) {
      PetscReal yb[6];
      Box(ys + 3 * s, 1, yb);
      const long b = BIN(ys[3 * s]) + nb * BIN(ys[3 * s + 1]);
      nstart[s] = ntot;
      for (long k = bcnt[b]; k < bcnt[b + 1]; k++)
        if (BoxesMeet(fb + 6 * bidx[k], yb, search)) {
          if (pass) nlist[ntot] = bidx[k];
          ntot++;
        }
    }
    nstart[ns] = ntot;
  }
  printf("mesh cells %ld cells_lower %ld cells_upper %ld vertices %ld slaves %ld master_faces %ld search %.6g candidates_per_node %.2f\n", ne, nel, neu, nv, ns, nf, search, (double)ntot / ns);
  fflush(stdout);

  idx_t       nn = (idx_t)nv, n = (idx_t)ne, ncommon = 4, opts[METIS_NOPTIONS];
  METIS_SetDefaultOptions(opts);
  opts[METIS_OPTION_NUMBERING] = 0;
  opts[METIS_OPTION_SEED]      = 7;
  for (int arg = 8; arg < argc; arg++) {
    idx_t        np = atoi(argv[arg]), objval = 0;
    const int    P  = (int)np;
    const double t0 = now();
    if (P == 1) memset(part, 0, sizeof(idx_t) * (size_t)ne);
    else if (METIS_PartMeshDual(&n, &nn, eptr, eind, NULL, NULL, &ncommon, &np, NULL, opts, &objval, part, npart) != METIS_OK) {
      fprintf(stderr, "METIS_PartMeshDual failed\n");
      return 2;
    }
    const double tmetis = now() - t0;
    long        *sown = malloc(sizeof(long) * (size_t)ns), *fown = malloc(sizeof(long) * (size_t)nf);
    long        *nsp = calloc((size_t)P, sizeof(long)), *nfo = calloc((size_t)P, sizeof(long)), *nfc = calloc((size_t)P, sizeof(long));
    long        *need = calloc((size_t)P, sizeof(long)), *msg = calloc((size_t)P, sizeof(long)), *msgout = calloc((size_t)P, sizeof(long));
    long        *bothbodies = calloc((size_t)P, sizeof(long));
    PetscReal   *boxes = malloc(sizeof(PetscReal) * 6 * (size_t)P);
    unsigned char *pair = calloc((size_t)P * (size_t)P, 1);
    /* owners: a slave vertex by the highest-numbered part of the upper body's bottom cells around it */
    for (long j = 0; j <= nxu; j++)
      for (long i = 0; i <= nxu; i++) {
        long o = -1;
        for (long jj = j - 1; jj <= j; jj++)
          for (long ii = i - 1; ii <= i; ii++)
            if (ii >= 0 && jj >= 0 && ii < nxu && jj < nxu) {
              const long p = part[nel + ii + nxu * jj];
              if (p > o) o = p;
            }
        sown[i + (nxu + 1) * j] = o;
        nsp[o]++;
      }
    for (long f = 0; f < nf; f++) {
      fown[f] = part[nel - nf + f];
      nfo[fown[f]]++;
    }
    {
      char *inl = calloc((size_t)P, 1), *inu = calloc((size_t)P, 1);
      for (long e = 0; e < ne; e++) (e < nel ? inl : inu)[part[e]] = 1;
      for (int p = 0; p < P; p++) bothbodies[p] = inl[p] && inu[p];
      free(inl);
      free(inu);
    }
    /* the boxes of the slave nodes per part (empty: min > max, as the code's Box of no points) */
    for (int p = 0; p < P; p++) Box(NULL, 0, boxes + 6 * p);
    for (long s = 0; s < ns; s++) {
      PetscReal *b = boxes + 6 * sown[s];
      for (int d = 0; d < 3; d++) {
        b[2 * d]     = fmin(b[2 * d], ys[3 * s + d]);
        b[2 * d + 1] = fmax(b[2 * d + 1], ys[3 * s + d]);
      }
    }
    int nwith = 0;
    for (int p = 0; p < P; p++) nwith += boxes[6 * p] <= boxes[6 * p + 1];
    /* candidates received: every face whose box meets the widened box */
    for (int q = 0; q < P; q++) {
      if (boxes[6 * q] > boxes[6 * q + 1]) continue;
      for (long f = 0; f < nf; f++)
        if (BoxesMeet(fb + 6 * f, boxes + 6 * q, search)) {
          nfc[q]++;
          pair[(size_t)fown[f] * P + q] = 1;
        }
    }
    for (int o = 0; o < P; o++)
      for (int q = 0; q < P; q++)
        if (o != q && pair[(size_t)o * P + q]) {
          msg[q]++;
          msgout[o]++;
        }
    /* needed: the union of its nodes' lists */
    {
      int  *stamp = malloc(sizeof(int) * (size_t)nf);
      long *order = malloc(sizeof(long) * (size_t)ns), *off = calloc((size_t)P + 1, sizeof(long));
      for (long f = 0; f < nf; f++) stamp[f] = -1;
      for (long s = 0; s < ns; s++) off[sown[s] + 1]++;
      for (int p = 0; p < P; p++) off[p + 1] += off[p];
      for (long s = 0; s < ns; s++) order[off[sown[s]]++] = s;
      for (long k = 0; k < ns; k++) {
        const long s = order[k], q = sown[s];
        for (long t = nstart[s]; t < nstart[s + 1]; t++)
          if (stamp[nlist[t]] != q) {
            stamp[nlist[t]] = (int)q;
            need[q]++;
          }
      }
      free(stamp);
      free(order);
      free(off);
    }
    /* statistics */
    long   smax = 0, fomax = 0, fcmax = 0, mmax = 0, momax = 0, nmax = 0, both = 0, cmax = 0;
    double nsum = 0;
    {
      long *cells = calloc((size_t)P, sizeof(long));
      for (long e = 0; e < ne; e++) cells[part[e]]++;
      for (int p = 0; p < P; p++)
        if (cells[p] > cmax) cmax = cells[p];
      free(cells);
    }
    double ssum = 0, fosum = 0, fcsum = 0, msum = 0, lsum = 0, lmax = 0, osum = 0, omax = 0, ratmax = 0, ratsum = 0;
    int    qloop = 0, qown = 0;
    for (int p = 0; p < P; p++) {
      const double loop = (double)nsp[p] * nfc[p], own = (double)nwith * nfo[p];
      if (nsp[p] > smax) smax = nsp[p];
      if (nfo[p] > fomax) fomax = nfo[p];
      if (nfc[p] > fcmax) fcmax = nfc[p];
      if (msg[p] > mmax) mmax = msg[p];
      if (msgout[p] > momax) momax = msgout[p];
      if (need[p] > nmax) nmax = need[p];
      if (loop > lmax) lmax = loop, qloop = p;
      if (own > omax) omax = own, qown = p;
      if (need[p] > 0) {
        const double r = (double)nfc[p] / need[p];
        ratsum += r;
        if (r > ratmax) ratmax = r;
      }
      both += bothbodies[p];
      nsum += need[p];
      ssum += nsp[p];
      fosum += nfo[p];
      fcsum += nfc[p];
      msum += msg[p];
      lsum += loop;
      osum += own;
    }
    /* the timed loops */
    double *tn = malloc(sizeof(double) * (size_t)reps), *to = malloc(sizeof(double) * (size_t)reps);
    double *tb = malloc(sizeof(double) * (size_t)reps), *tp = malloc(sizeof(double) * (size_t)reps);
    long    nlist_q = 0, nlist_b = 0, ntests = 0, nsent = 0;
    {
      PetscReal *qys = malloc(sizeof(PetscReal) * 3 * (size_t)(nsp[qloop] + 1)), *qfcx = malloc(sizeof(PetscReal) * 12 * (size_t)(nfc[qloop] + 1));
      long       a = 0, c = 0;
      for (long s = 0; s < ns; s++)
        if (sown[s] == qloop) memcpy(qys + 3 * a++, ys + 3 * s, 3 * sizeof(PetscReal));
      for (int o = 0; o < P; o++) /* as received: by the owner's rank, then its face order */
        for (long f = 0; f < nf; f++)
          if (fown[f] == o && BoxesMeet(fb + 6 * f, boxes + 6 * qloop, search)) memcpy(qfcx + 12 * c++, fx + 12 * f, 12 * sizeof(PetscReal));
      for (int r = 0; r < reps; r++) tn[r] = time_nodes(qys, a, qfcx, c, search, &nlist_q);
      for (int r = 0; r < reps; r++) tb[r] = time_nodes_binned(qys, a, qfcx, c, search, &nlist_b);
      if (nlist_b != nlist_q) {
        fprintf(stderr, "the binned lists hold %ld candidates, the double loop's %ld\n", nlist_b, nlist_q);
        return 3;
      }
      free(qys);
      free(qfcx);
      PetscReal *ofx = malloc(sizeof(PetscReal) * 12 * (size_t)(nfo[qown] + 1));
      a = 0;
      for (long f = 0; f < nf; f++)
        if (fown[f] == qown) memcpy(ofx + 12 * a++, fx + 12 * f, 12 * sizeof(PetscReal));
      for (int r = 0; r < reps; r++) to[r] = time_owner(ofx, a, boxes, P, search, &ntests);
      for (int r = 0; r < reps; r++) tp[r] = time_owner_prefilter(ofx, a, boxes, P, search, &nsent);
      free(ofx);
    }
    const double tnode = median(tn, reps), town = median(to, reps), tbin = median(tb, reps), tpre = median(tp, reps);
    printf("parts %d cut %ld metis_s %.2f cells_max %ld cells_mean %.2f with_slaves %d both_bodies %ld slaves_max %ld slaves_mean %.2f faces_owned_max %ld faces_owned_mean %.2f "
           "cand_max %ld cand_mean %.2f cand_mean_with %.2f need_max %ld need_mean_with %.2f cand_over_need_max %.3f cand_over_need_mean %.3f msg_max %ld msg_mean %.3f msg_mean_with %.3f msg_out_max %ld "
           "loop_max %.6g loop_mean %.6g loop_mean_with %.6g owner_tests_max %.6g owner_tests_mean %.6g "
           "t_nodes_s %.6g t_nodes_pairs %.6g t_nodes_lists %ld t_owner_s %.6g t_owner_tests %ld qloop_slaves %ld qloop_cand %ld t_binned_s %.6g t_prefilter_s %.6g\n",
           P, (long)objval, tmetis, cmax, (double)ne / P, nwith, both, smax, ssum / P, fomax, fosum / P, fcmax, fcsum / P, fcsum / (nwith ? nwith : 1), nmax, nsum / (nwith ? nwith : 1), ratmax, ratsum / (nwith ? nwith : 1),
           mmax, msum / P, msum / (nwith ? nwith : 1), momax, lmax, lsum / P, lsum / (nwith ? nwith : 1), 2 * omax, 2 * osum / P, tnode, 2 * lmax, nlist_q, town, ntests, nsp[qloop], nfc[qloop], tbin, tpre);
    fflush(stdout);
    free(sown); free(fown); free(nsp); free(nfo); free(nfc); free(need); free(msg); free(msgout); free(bothbodies); free(boxes); free(pair); free(tn); free(to); free(tb); free(tp);
  }
  free(eptr); free(eind); free(part); free(npart); free(fx); free(fb); free(ys); free(bcnt); free(bidx); free(nstart); free(nlist);
  return 0;
}
