/* Direct solver: MUMPS with a METIS nested-dissection ordering (include/lu.h).

   Data flow: each rank hands MUMPS its own rows as coordinate triplets (ICNTL(18) = 3, distributed
   input; on one rank centralised, ICNTL(18) = 0), in the order of the AIJ storage (the diagonal block, then the off-diagonal block), so that
   a new factorisation only copies the value arrays. The ordering is computed on rank 0 (the MUMPS
   host, which does the sequential analysis anyway) from the gathered graph of the matrix, made
   symmetric, by METIS_NodeND, and passed as PERM_IN (ICNTL(7) = 1). Right-hand side and solution
   are gathered to and scattered from the host (ICNTL(20) = ICNTL(21) = 0). */
#include <string.h>
#include <dmumps_c.h>
#include <metis.h>
#include "lu.h"

#define ICNTL(i)  icntl[(i) - 1]
#define CNTL(i)   cntl[(i) - 1]
#define INFOG(i)  infog[(i) - 1]
#define RINFOG(i) rinfog[(i) - 1]

typedef struct {
  DMUMPS_STRUC_C   id;
  PetscBool        init;      /* JOB = -1 done                                        */
  PetscBool        analysed;  /* for the pattern of state nzstate                     */
  PetscBool        factored;  /* the last factorisation succeeded                     */
  PetscObjectState nzstate;
  PetscObjectId    Aid;       /* the operator analysed (its id: unique, never reused) */
  PetscInt         N;
  MUMPS_INT8       nnz;       /* local triplets                                       */
  MUMPS_INT       *irn, *jcn, *perm;
  PetscScalar     *a;         /* the values MUMPS reads: the matrix's own array on one rank, */
  PetscScalar     *abuf;      /* else this copy of the diagonal and off-diagonal blocks'     */
  Vec              bseq;      /* whole vector on rank 0, empty elsewhere              */
  VecScatter       toz;
  PetscInt         nanalysis, nfactor, nretry;
  PetscLogDouble   t_order;
  PetscLogEvent    ev_analysis, ev_factor, ev_solve;
} LUND;

PetscErrorCode LUNestedDissection(PetscInt N, const PetscInt xadj[], const PetscInt adj[], PetscInt iperm[])
{
  idx_t  n = (idx_t)N, opts[METIS_NOPTIONS], *x, *a, *p, *ip;
  int    st;

  PetscFunctionBeginUser;
  if (!N) PetscFunctionReturn(0);
  PetscCall(PetscMalloc4(N + 1, &x, PetscMax(xadj[N], 1), &a, N, &p, N, &ip));
  for (PetscInt i = 0; i <= N; i++) x[i] = (idx_t)xadj[i];
  for (PetscInt k = 0; k < xadj[N]; k++) a[k] = (idx_t)adj[k];
  METIS_SetDefaultOptions(opts);
  opts[METIS_OPTION_NUMBERING] = 0;
  opts[METIS_OPTION_SEED]      = 7; /* the same ordering on every run: reproducible factors */
  st = METIS_NodeND(&n, x, a, NULL, opts, p, ip);
  PetscCheck(st == METIS_OK, PETSC_COMM_SELF, PETSC_ERR_LIB, "METIS_NodeND failed (status %d) on the graph of the Jacobian (%" PetscInt_FMT " rows)", st, N);
  for (PetscInt i = 0; i < N; i++) iperm[i] = (PetscInt)ip[i];
  PetscCall(PetscFree4(x, a, p, ip));
  PetscFunctionReturn(0);
}

/* The local diagonal and off-diagonal blocks of an AIJ matrix (Ao NULL on one rank) */
static PetscErrorCode LocalBlocks(Mat A, Mat *Ad, Mat *Ao, const PetscInt **garray)
{
  PetscBool mpi, seq;
  MatType   type;

  PetscFunctionBeginUser;
  PetscCall(MatGetType(A, &type));
  PetscCall(PetscObjectBaseTypeCompare((PetscObject)A, MATMPIAIJ, &mpi));
  PetscCall(PetscObjectBaseTypeCompare((PetscObject)A, MATSEQAIJ, &seq));
  PetscCheck(mpi || seq, PetscObjectComm((PetscObject)A), PETSC_ERR_SUP, "LU with -lu_ordering nd needs an AIJ Jacobian, not %s (-dm_mat_type aij, or -lu_ordering mumps)", type);
  if (mpi) PetscCall(MatMPIAIJGetSeqAIJ(A, Ad, Ao, garray));
  else {
    *Ad     = A;
    *Ao     = NULL;
    *garray = NULL;
  }
  PetscFunctionReturn(0);
}

static PetscErrorCode CopyValues(LUND *lu, Mat A)
{
  Mat                Ad, Ao;
  const PetscInt    *garray;
  const PetscScalar *v;
  PetscInt           nd = 0, no = 0;

  PetscFunctionBeginUser;
  PetscCall(LocalBlocks(A, &Ad, &Ao, &garray));
  PetscCall(MatSeqAIJGetArrayRead(Ad, &v));
  {
    MatInfo info;
    PetscCall(MatGetInfo(Ad, MAT_LOCAL, &info));
    nd = (PetscInt)info.nz_used;
  }
  if (!Ao) lu->a = (PetscScalar *)v; /* valid until the matrix is reallocated, which changes its nonzero state */
  else PetscCall(PetscArraycpy(lu->abuf, v, nd));
  PetscCall(MatSeqAIJRestoreArrayRead(Ad, &v));
  if (Ao) {
    MatInfo info;
    PetscCall(MatGetInfo(Ao, MAT_LOCAL, &info));
    no = (PetscInt)info.nz_used;
    PetscCall(MatSeqAIJGetArrayRead(Ao, &v));
    PetscCall(PetscArraycpy(lu->abuf + nd, v, no));
    PetscCall(MatSeqAIJRestoreArrayRead(Ao, &v));
    lu->a = lu->abuf;
  }
  PetscCheck((MUMPS_INT8)(nd + no) == lu->nnz, PETSC_COMM_SELF, PETSC_ERR_PLIB, "Jacobian storage changed without a change of its nonzero state (%" PetscInt_FMT " entries, %lld analysed)", nd + no, (long long)lu->nnz);
  PetscFunctionReturn(0);
}

/* Triplets of the local rows (1-based global indices) and, on the host, the ordering */
static PetscErrorCode Analyse(PC pc, LUND *lu, Mat A)
{
  MPI_Comm        comm;
  PetscMPIInt     rank, size;
  Mat             Ad, Ao;
  const PetscInt *garray, *ia, *ja, *ib = NULL, *jb = NULL;
  PetscInt        rstart, rend, m, n, N;
  PetscBool       done;

  PetscFunctionBeginUser;
  PetscCall(PetscObjectGetComm((PetscObject)pc, &comm));
  PetscCallMPI(MPI_Comm_rank(comm, &rank));
  PetscCallMPI(MPI_Comm_size(comm, &size));
  PetscCall(MatGetSize(A, &N, &n));
  PetscCheck(N == n, comm, PETSC_ERR_ARG_WRONG, "LU needs a square matrix (%" PetscInt_FMT " x %" PetscInt_FMT ")", N, n);
  PetscCall(MatGetOwnershipRange(A, &rstart, &rend));
  PetscCall(LocalBlocks(A, &Ad, &Ao, &garray));
  PetscCall(MatGetRowIJ(Ad, 0, PETSC_FALSE, PETSC_FALSE, &m, &ia, &ja, &done));
  PetscCheck(done, PETSC_COMM_SELF, PETSC_ERR_SUP, "no row structure of the diagonal block");
  if (Ao) {
    PetscCall(MatGetRowIJ(Ao, 0, PETSC_FALSE, PETSC_FALSE, &n, &ib, &jb, &done));
    PetscCheck(done, PETSC_COMM_SELF, PETSC_ERR_SUP, "no row structure of the off-diagonal block");
  }
  PetscCall(PetscFree2(lu->irn, lu->jcn));
  PetscCall(PetscFree(lu->abuf));
  lu->N   = N;
  lu->nnz = (MUMPS_INT8)ia[m] + (Ao ? (MUMPS_INT8)ib[m] : 0);
  PetscCall(PetscMalloc2(lu->nnz, &lu->irn, lu->nnz, &lu->jcn));
  if (Ao) PetscCall(PetscMalloc1(lu->nnz, &lu->abuf));
  {
    MUMPS_INT8 k = 0;
    for (PetscInt i = 0; i < m; i++)
      for (PetscInt q = ia[i]; q < ia[i + 1]; q++) {
        lu->irn[k]   = (MUMPS_INT)(rstart + i + 1);
        lu->jcn[k++] = (MUMPS_INT)(rstart + ja[q] + 1);
      }
    for (PetscInt i = 0; Ao && i < m; i++)
      for (PetscInt q = ib[i]; q < ib[i + 1]; q++) {
        lu->irn[k]   = (MUMPS_INT)(rstart + i + 1);
        lu->jcn[k++] = (MUMPS_INT)(garray[jb[q]] + 1);
      }
  }

  /* the graph on the host: every rank sends its rows (global columns, diagonal left out) */
  {
    PetscMPIInt *cnt = NULL, *dsp = NULL, *rcnt = NULL, *rdsp = NULL, nl, ne;
    PetscInt    *len, *col, *alen = NULL, *acol = NULL, k = 0;

    PetscCall(PetscMalloc2(m, &len, (size_t)lu->nnz, &col));
    for (PetscInt i = 0; i < m; i++) {
      len[i] = 0;
      for (PetscInt q = ia[i]; q < ia[i + 1]; q++)
        if (ja[q] != i) { col[k++] = rstart + ja[q]; len[i]++; }
      for (PetscInt q = Ao ? ib[i] : 0; Ao && q < ib[i + 1]; q++) { col[k++] = garray[jb[q]]; len[i]++; }
    }
    {
      PetscInt64 kl = k, tot;
      PetscCallMPI(MPI_Allreduce(&kl, &tot, 1, MPIU_INT64, MPI_SUM, comm));
      PetscCheck(2 * tot < PETSC_MPI_INT_MAX, comm, PETSC_ERR_SUP, "Jacobian graph too large to order on one rank (%lld entries): use -lu_ordering mumps", (long long)tot);
    }
    PetscCall(PetscMPIIntCast(m, &nl));
    PetscCall(PetscMPIIntCast(k, &ne));
    if (rank == 0) PetscCall(PetscMalloc4(size, &cnt, size + 1, &dsp, size, &rcnt, size + 1, &rdsp));
    PetscCallMPI(MPI_Gather(&nl, 1, MPI_INT, cnt, 1, MPI_INT, 0, comm));
    PetscCallMPI(MPI_Gather(&ne, 1, MPI_INT, rcnt, 1, MPI_INT, 0, comm));
    if (rank == 0) {
      dsp[0] = rdsp[0] = 0;
      for (PetscMPIInt r = 0; r < size; r++) {
        dsp[r + 1]  = dsp[r] + cnt[r];
        rdsp[r + 1] = rdsp[r] + rcnt[r];
      }
      PetscCall(PetscMalloc2(N, &alen, PetscMax(rdsp[size], 1), &acol));
    }
    PetscCallMPI(MPI_Gatherv(len, nl, MPIU_INT, alen, cnt, dsp, MPIU_INT, 0, comm));
    PetscCallMPI(MPI_Gatherv(col, ne, MPIU_INT, acol, rcnt, rdsp, MPIU_INT, 0, comm));
    PetscCall(PetscFree2(len, col));
    PetscCall(PetscFree(lu->perm));
    if (rank == 0) {
      /* symmetric graph: rows of A + A^T, sorted, duplicates removed */
      PetscInt      *xadj, *adj, *fill, *ip;
      PetscLogDouble t0, t1;

      PetscCall(PetscTime(&t0));
      PetscCall(PetscCalloc2(N + 1, &xadj, N, &fill));
      for (PetscInt i = 0, q = 0; i < N; i++)
        for (PetscInt e = 0; e < alen[i]; e++, q++) {
          xadj[i + 1]++;
          xadj[acol[q] + 1]++;
        }
      for (PetscInt i = 0; i < N; i++) xadj[i + 1] += xadj[i];
      PetscCall(PetscMalloc1(PetscMax(xadj[N], 1), &adj));
      for (PetscInt i = 0, q = 0; i < N; i++)
        for (PetscInt e = 0; e < alen[i]; e++, q++) {
          const PetscInt j = acol[q];
          adj[xadj[i] + fill[i]++] = j;
          adj[xadj[j] + fill[j]++] = i;
        }
      {
        PetscInt w = 0, start = 0;
        for (PetscInt i = 0; i < N; i++) {
          PetscInt nr = xadj[i + 1] - start, *row = adj + start;
          PetscCall(PetscSortRemoveDupsInt(&nr, row));
          start = xadj[i + 1];
          xadj[i] = w;
          for (PetscInt e = 0; e < nr; e++) adj[w++] = row[e];
        }
        xadj[N] = w;
      }
      PetscCall(PetscMalloc1(N, &ip));
      PetscCall(LUNestedDissection(N, xadj, adj, ip));
      PetscCall(PetscMalloc1(N, &lu->perm));
      for (PetscInt i = 0; i < N; i++) lu->perm[i] = (MUMPS_INT)(ip[i] + 1);
      PetscCall(PetscFree(ip));
      PetscCall(PetscFree2(xadj, fill));
      PetscCall(PetscFree(adj));
      PetscCall(PetscFree2(alen, acol));
      PetscCall(PetscFree4(cnt, dsp, rcnt, rdsp));
      PetscCall(PetscTime(&t1));
      lu->t_order += t1 - t0;
    }
  }
  PetscCall(MatRestoreRowIJ(Ad, 0, PETSC_FALSE, PETSC_FALSE, &m, &ia, &ja, &done));
  if (Ao) PetscCall(MatRestoreRowIJ(Ao, 0, PETSC_FALSE, PETSC_FALSE, &n, &ib, &jb, &done));

  /* the values too, for the controls that analyse with them (e.g. -mat_mumps_icntl_8 -2) */
  PetscCall(CopyValues(lu, A));
  lu->id.job     = 1;
  lu->id.n       = (MUMPS_INT)N;
  if (lu->id.ICNTL(18) == 0) { /* one rank: centralised input */
    lu->id.nnz = lu->nnz;
    lu->id.irn = lu->irn;
    lu->id.jcn = lu->jcn;
    lu->id.a   = lu->a;
  } else {
    lu->id.nnz_loc = lu->nnz;
    lu->id.irn_loc = lu->irn;
    lu->id.jcn_loc = lu->jcn;
    lu->id.a_loc   = lu->a;
  }
  lu->id.perm_in = rank == 0 ? lu->perm : NULL;
  dmumps_c(&lu->id);
  PetscCheck(lu->id.INFOG(1) >= 0, comm, PETSC_ERR_LIB, "MUMPS analysis failed: INFOG(1) = %d, INFOG(2) = %d (Jacobian of %" PetscInt_FMT " rows)", (int)lu->id.INFOG(1), (int)lu->id.INFOG(2), N);
  /* the right-hand side and the solution live on the host */
  PetscCall(VecScatterDestroy(&lu->toz));
  PetscCall(VecDestroy(&lu->bseq));
  {
    Vec b;
    PetscCall(MatCreateVecs(A, NULL, &b));
    PetscCall(VecScatterCreateToZero(b, &lu->toz, &lu->bseq));
    PetscCall(VecDestroy(&b));
  }
  PetscCall(MatGetNonzeroState(A, &lu->nzstate));
  PetscCall(PetscObjectGetId((PetscObject)A, &lu->Aid));
  lu->analysed = PETSC_TRUE;
  lu->nanalysis++;
  PetscFunctionReturn(0);
}

static PetscErrorCode PCSetUp_LUND(PC pc)
{
  LUND            *lu;
  Mat              A;
  PetscObjectState nz;
  PetscBool        same;

  PetscFunctionBeginUser;
  PetscCall(PCShellGetContext(pc, &lu));
  PetscCall(PCSetFailedReason(pc, PC_NOERROR));
  PetscCall(PCGetOperators(pc, NULL, &A));
  PetscCall(MatGetNonzeroState(A, &nz));
  PetscCall(PetscObjectCompareId((PetscObject)A, lu->Aid, &same));
  if (!lu->analysed || !same || nz != lu->nzstate) {
    PetscCall(PetscLogEventBegin(lu->ev_analysis, pc, 0, 0, 0));
    PetscCall(Analyse(pc, lu, A));
    PetscCall(PetscLogEventEnd(lu->ev_analysis, pc, 0, 0, 0));
  }
  PetscCall(PetscLogEventBegin(lu->ev_factor, pc, 0, 0, 0));
  PetscCall(CopyValues(lu, A));
  if (lu->id.ICNTL(18) == 0) lu->id.a = lu->a;
  else lu->id.a_loc = lu->a;
  for (int attempt = 0;; attempt++) {
    lu->id.job = 2;
    dmumps_c(&lu->id);
    /* workspace too small (pivots delayed beyond the analysis' estimate): more and again */
    if ((lu->id.INFOG(1) == -8 || lu->id.INFOG(1) == -9) && attempt < 4) {
      lu->id.ICNTL(14) = PetscMax(2 * lu->id.ICNTL(14), 40);
      lu->nretry++;
      PetscCall(PetscInfo(pc, "MUMPS workspace too small (INFOG(1) = %d): factorising again with ICNTL(14) = %d\n", (int)lu->id.INFOG(1), (int)lu->id.ICNTL(14)));
      continue;
    }
    break;
  }
  lu->factored = lu->id.INFOG(1) >= 0;
  if (!lu->factored) {
    PetscCall(PetscInfo(pc, "MUMPS factorisation failed: INFOG(1) = %d, INFOG(2) = %d\n", (int)lu->id.INFOG(1), (int)lu->id.INFOG(2)));
    PetscCall(PCSetFailedReason(pc, lu->id.INFOG(1) == -10 ? PC_FACTOR_NUMERIC_ZEROPIVOT : PC_FACTOR_OTHER));
  } else lu->nfactor++;
  if (lu->factored) PetscCall(PetscLogFlops(lu->id.rinfo[2])); /* RINFO(3): this rank's elimination flops */
  PetscCall(PetscLogEventEnd(lu->ev_factor, pc, 0, 0, 0));
  PetscFunctionReturn(0);
}

static PetscErrorCode PCApply_LUND(PC pc, Vec x, Vec y)
{
  LUND        *lu;
  PetscMPIInt  rank;
  PetscScalar *b;

  PetscFunctionBeginUser;
  PetscCall(PCShellGetContext(pc, &lu));
  if (!lu->factored) {
    PetscCall(VecSetInf(y));
    PetscFunctionReturn(0);
  }
  PetscCall(PetscLogEventBegin(lu->ev_solve, pc, x, y, 0));
  PetscCallMPI(MPI_Comm_rank(PetscObjectComm((PetscObject)pc), &rank));
  PetscCall(VecScatterBegin(lu->toz, x, lu->bseq, INSERT_VALUES, SCATTER_FORWARD));
  PetscCall(VecScatterEnd(lu->toz, x, lu->bseq, INSERT_VALUES, SCATTER_FORWARD));
  PetscCall(VecGetArray(lu->bseq, &b));
  lu->id.job  = 3;
  lu->id.nrhs = 1;
  lu->id.lrhs = (MUMPS_INT)lu->N;
  lu->id.rhs  = rank == 0 ? b : NULL;
  dmumps_c(&lu->id);
  PetscCall(VecRestoreArray(lu->bseq, &b));
  if (lu->id.INFOG(1) < 0) {
    PetscCall(PetscInfo(pc, "MUMPS solve failed: INFOG(1) = %d\n", (int)lu->id.INFOG(1)));
    PetscCall(PCSetFailedReason(pc, PC_SUBPC_ERROR));
    PetscCall(VecSetInf(y));
  } else {
    PetscCall(VecScatterBegin(lu->toz, lu->bseq, y, INSERT_VALUES, SCATTER_REVERSE));
    PetscCall(VecScatterEnd(lu->toz, lu->bseq, y, INSERT_VALUES, SCATTER_REVERSE));
  }
  PetscCall(PetscLogEventEnd(lu->ev_solve, pc, x, y, 0));
  PetscFunctionReturn(0);
}

/* several right-hand sides at once (KSPMatSolve, the active-set correction's columns): the columns
   of the dense X gathered on the host side by side, one MUMPS solve with NRHS of them */
static PetscErrorCode PCMatApply_LUND(PC pc, Mat X, Mat Y)
{
  LUND        *lu;
  PetscMPIInt  rank;
  PetscInt     n;
  PetscScalar *buf = NULL, *b;
  Vec          c;

  PetscFunctionBeginUser;
  PetscCall(PCShellGetContext(pc, &lu));
  PetscCall(MatGetSize(X, NULL, &n));
  if (!lu->factored) {
    for (PetscInt j = 0; j < n; j++) {
      PetscCall(MatDenseGetColumnVecWrite(Y, j, &c));
      PetscCall(VecSetInf(c));
      PetscCall(MatDenseRestoreColumnVecWrite(Y, j, &c));
    }
    PetscFunctionReturn(0);
  }
  PetscCall(PetscLogEventBegin(lu->ev_solve, pc, 0, 0, 0));
  PetscCallMPI(MPI_Comm_rank(PetscObjectComm((PetscObject)pc), &rank));
  if (rank == 0) PetscCall(PetscMalloc1(lu->N * n, &buf));
  for (PetscInt j = 0; j < n; j++) {
    PetscCall(MatDenseGetColumnVecRead(X, j, &c));
    PetscCall(VecScatterBegin(lu->toz, c, lu->bseq, INSERT_VALUES, SCATTER_FORWARD));
    PetscCall(VecScatterEnd(lu->toz, c, lu->bseq, INSERT_VALUES, SCATTER_FORWARD));
    PetscCall(MatDenseRestoreColumnVecRead(X, j, &c));
    if (rank == 0) {
      PetscCall(VecGetArray(lu->bseq, &b));
      PetscCall(PetscArraycpy(buf + lu->N * j, b, lu->N));
      PetscCall(VecRestoreArray(lu->bseq, &b));
    }
  }
  lu->id.job  = 3;
  lu->id.nrhs = (MUMPS_INT)n;
  lu->id.lrhs = (MUMPS_INT)lu->N;
  lu->id.rhs  = rank == 0 ? buf : NULL;
  dmumps_c(&lu->id);
  lu->id.nrhs = 1;
  for (PetscInt j = 0; j < n; j++) {
    PetscCall(MatDenseGetColumnVecWrite(Y, j, &c));
    if (lu->id.INFOG(1) < 0) PetscCall(VecSetInf(c));
    else {
      if (rank == 0) {
        PetscCall(VecGetArray(lu->bseq, &b));
        PetscCall(PetscArraycpy(b, buf + lu->N * j, lu->N));
        PetscCall(VecRestoreArray(lu->bseq, &b));
      }
      PetscCall(VecScatterBegin(lu->toz, lu->bseq, c, INSERT_VALUES, SCATTER_REVERSE));
      PetscCall(VecScatterEnd(lu->toz, lu->bseq, c, INSERT_VALUES, SCATTER_REVERSE));
    }
    PetscCall(MatDenseRestoreColumnVecWrite(Y, j, &c));
  }
  if (lu->id.INFOG(1) < 0) {
    PetscCall(PetscInfo(pc, "MUMPS solve failed: INFOG(1) = %d\n", (int)lu->id.INFOG(1)));
    PetscCall(PCSetFailedReason(pc, PC_SUBPC_ERROR));
  }
  PetscCall(PetscFree(buf));
  PetscCall(PetscLogEventEnd(lu->ev_solve, pc, 0, 0, 0));
  PetscFunctionReturn(0);
}

static PetscErrorCode PCView_LUND(PC pc, PetscViewer viewer)
{
  LUND     *lu;
  PetscBool ascii;

  PetscFunctionBeginUser;
  PetscCall(PCShellGetContext(pc, &lu));
  PetscCall(PetscObjectTypeCompare((PetscObject)viewer, PETSCVIEWERASCII, &ascii));
  if (!ascii) PetscFunctionReturn(0);
  PetscCall(PetscViewerASCIIPrintf(viewer, "LU by MUMPS, METIS nested-dissection ordering (-lu_ordering nd)\n"));
  if (lu->analysed) {
    PetscCall(PetscViewerASCIIPrintf(viewer, "  %" PetscInt_FMT " unknowns; %" PetscInt_FMT " analyses (ordering %.3g s on the host), %" PetscInt_FMT " factorisations, %" PetscInt_FMT " retried with more workspace\n", lu->N, lu->nanalysis, (double)lu->t_order, lu->nfactor, lu->nretry));
    PetscCall(PetscViewerASCIIPrintf(viewer, "  estimated flops per factorisation %.4g, entries in the factors %.4g, largest front %d\n", (double)lu->id.RINFOG(1),
                                     lu->id.INFOG(20) >= 0 ? (double)lu->id.INFOG(20) : -1e6 * lu->id.INFOG(20), (int)lu->id.INFOG(5)));
  }
  PetscFunctionReturn(0);
}

static PetscErrorCode PCDestroy_LUND(PC pc)
{
  LUND *lu;

  PetscFunctionBeginUser;
  PetscCall(PCShellGetContext(pc, &lu));
  if (lu->init) {
    lu->id.job = -2;
    dmumps_c(&lu->id);
  }
  PetscCall(PetscFree2(lu->irn, lu->jcn));
  PetscCall(PetscFree(lu->abuf));
  PetscCall(PetscFree(lu->perm));
  PetscCall(VecScatterDestroy(&lu->toz));
  PetscCall(VecDestroy(&lu->bseq));
  PetscCall(PetscFree(lu));
  PetscFunctionReturn(0);
}

PetscErrorCode PCLUNDGetCounts(PC pc, PetscInt *nanalysis, PetscInt *nfactor)
{
  LUND     *lu;
  PetscBool shell;

  PetscFunctionBeginUser;
  PetscCall(PetscObjectTypeCompare((PetscObject)pc, PCSHELL, &shell));
  PetscCheck(shell, PetscObjectComm((PetscObject)pc), PETSC_ERR_ARG_WRONG, "the PC is not LU with -lu_ordering nd");
  PetscCall(PCShellGetContext(pc, &lu));
  if (nanalysis) *nanalysis = lu->nanalysis;
  if (nfactor) *nfactor = lu->nfactor;
  PetscFunctionReturn(0);
}

PetscErrorCode LUNDCheckOptions(MPI_Comm comm, const char prefix[])
{
  /* set by this solver: no column permutation, the ordering, the input layout, centralised
     right-hand side and solution */
  static const int fixed[] = {6, 7, 18, 20, 21, 28, 29};

  PetscFunctionBeginUser;
  for (size_t k = 0; k < sizeof(fixed) / sizeof(fixed[0]); k++) {
    char      name[64];
    PetscBool set;
    PetscCall(PetscSNPrintf(name, sizeof(name), "-mat_mumps_icntl_%d", fixed[k]));
    PetscCall(PetscOptionsHasName(NULL, prefix, name, &set));
    PetscCheck(!set, comm, PETSC_ERR_USER_INPUT, "%s: this MUMPS control is set by -lu_ordering nd (METIS ordering, analysis of the pattern alone, data layout); give -lu_ordering mumps to use MUMPS through PETSc", name);
  }
  PetscFunctionReturn(0);
}

PetscErrorCode PCSetLUND(PC pc)
{
  LUND       *lu;
  MPI_Comm    comm;
  const char *prefix;

  PetscFunctionBeginUser;
  PetscCall(PetscObjectGetComm((PetscObject)pc, &comm));
  PetscCall(PCGetOptionsPrefix(pc, &prefix));
  PetscCall(LUNDCheckOptions(comm, prefix));
  PetscCall(PetscNew(&lu));
  PetscCall(PetscLogEventRegister("AtritoLUAnalysis", PC_CLASSID, &lu->ev_analysis));
  PetscCall(PetscLogEventRegister("AtritoLUFactor", PC_CLASSID, &lu->ev_factor));
  PetscCall(PetscLogEventRegister("AtritoLUSolve", PC_CLASSID, &lu->ev_solve));
  lu->id.comm_fortran = (MUMPS_INT)MPI_Comm_c2f(comm);
  lu->id.par          = 1; /* the host works too */
  lu->id.sym          = 0; /* friction makes the Jacobian unsymmetric */
  lu->id.job          = -1;
  dmumps_c(&lu->id);
  PetscCheck(lu->id.INFOG(1) >= 0, comm, PETSC_ERR_LIB, "MUMPS initialisation failed: INFOG(1) = %d", (int)lu->id.INFOG(1));
  lu->init         = PETSC_TRUE;
  lu->id.ICNTL(1)  = 6; /* errors on stdout, no diagnostics or statistics */
  lu->id.ICNTL(2)  = 0;
  lu->id.ICNTL(3)  = 0;
  lu->id.ICNTL(4)  = 0;
  lu->id.ICNTL(6)  = 0; /* no permutation by values: the analysis depends on the pattern alone */
  lu->id.ICNTL(7)  = 1;
  lu->id.ICNTL(8)  = 0; /* no scaling: see doc/notes/design-log.md */
  {
    PetscMPIInt size;
    PetscCallMPI(MPI_Comm_size(comm, &size));
    lu->id.ICNTL(18) = size == 1 ? 0 : 3; /* centralised on one rank, distributed input otherwise */
  }
  lu->id.ICNTL(20) = 0;
  lu->id.ICNTL(21) = 0;
  lu->id.ICNTL(28) = 1;
  for (int i = 1; i <= 60; i++) {
    char      name[64];
    PetscInt  v;
    PetscBool set;
    PetscCall(PetscSNPrintf(name, sizeof(name), "-mat_mumps_icntl_%d", i));
    PetscCall(PetscOptionsGetInt(NULL, prefix, name, &v, &set));
    if (set) lu->id.ICNTL(i) = (MUMPS_INT)v; /* those fixed above were refused */
  }
  for (int i = 1; i <= 15; i++) {
    char      name[64];
    PetscReal v;
    PetscBool set;
    PetscCall(PetscSNPrintf(name, sizeof(name), "-mat_mumps_cntl_%d", i));
    PetscCall(PetscOptionsGetReal(NULL, prefix, name, &v, &set));
    if (set) lu->id.CNTL(i) = (DMUMPS_REAL)v;
  }
  PetscCall(PCSetType(pc, PCSHELL));
  PetscCall(PCShellSetContext(pc, lu));
  PetscCall(PCShellSetName(pc, "lu-nd"));
  PetscCall(PCShellSetSetUp(pc, PCSetUp_LUND));
  PetscCall(PCShellSetApply(pc, PCApply_LUND));
  PetscCall(PCShellSetMatApply(pc, PCMatApply_LUND));
  PetscCall(PCShellSetView(pc, PCView_LUND));
  PetscCall(PCShellSetDestroy(pc, PCDestroy_LUND));
  PetscFunctionReturn(0);
}
