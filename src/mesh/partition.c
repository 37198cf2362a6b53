/* Cell partition by METIS on the serial mesh (include/meshgen.h), rank 0 only.

   Balancing the cells only: METIS_PartMeshDual on the dual graph (cells sharing a face, 4 common
   nodes), seed 7: what every run did before the contact-balanced option existed.

   Balancing the contact work as well (-partition_balance contact): the same dual graph
   (METIS_MeshToDual) partitioned by METIS_PartGraphKway with two constraints per cell, its cell
   weight 1 and its share of the contact slave nodes, so that every part gets about the same number
   of cells AND of slave nodes (METIS's tolerance 1.03 on each). A slave node shared by k cells
   gives each of them 1/k; the weights are integers, so the shares are scaled by 24 (exact for
   k = 1, 2, 3, 4, 6, 8, the counts of a hexahedral mesh's vertex) and rounded. Which rank owns a
   vertex is decided later by DMPlex (a vertex on a part boundary goes to one of the parts around
   it), so the slave counts per rank follow the cell shares up to the boundary vertices. */
#include <metis.h>
#include "meshgen.h"

PetscErrorCode MeshPartitionCells(PetscInt ne, PetscInt nv, const PetscInt conn[], const PetscBool slave[], PetscInt nparts, PetscInt epart[], PetscInt *edgecut)
{
  idx_t  n = (idx_t)ne, nn = (idx_t)nv, ncommon = 4, np = (idx_t)nparts, objval = 0, opts[METIS_NOPTIONS];
  idx_t *eptr, *eind, *part, *npart;
  int    st;

  PetscFunctionBeginUser;
  PetscCheck(nparts >= 1, PETSC_COMM_SELF, PETSC_ERR_ARG_OUTOFRANGE, "partition into %" PetscInt_FMT " parts", nparts);
  PetscCall(PetscMalloc4(n + 1, &eptr, 8 * n, &eind, n, &part, nn, &npart));
  for (idx_t e = 0; e <= n; e++) eptr[e] = 8 * e;
  for (idx_t i = 0; i < 8 * n; i++) eind[i] = (idx_t)conn[i];
  METIS_SetDefaultOptions(opts);
  opts[METIS_OPTION_NUMBERING] = 0;
  opts[METIS_OPTION_SEED]      = 7;
  if (nparts == 1) {
    for (idx_t e = 0; e < n; e++) part[e] = 0;
  } else if (!slave) {
    st = METIS_PartMeshDual(&n, &nn, eptr, eind, NULL, NULL, &ncommon, &np, NULL, opts, &objval, part, npart);
    PetscCheck(st == METIS_OK, PETSC_COMM_SELF, PETSC_ERR_LIB, "METIS_PartMeshDual failed (status %d) on %" PetscInt_FMT " cells into %" PetscInt_FMT " parts", st, ne, nparts);
  } else {
    idx_t *xadj = NULL, *adjncy = NULL, *vwgt, ncon = 2, numflag = 0;
    int   *deg;
    PetscCall(PetscCalloc1(nv, &deg));
    for (idx_t i = 0; i < 8 * n; i++) deg[eind[i]]++;
    PetscCall(PetscMalloc1(2 * n, &vwgt));
    for (idx_t e = 0; e < n; e++) {
      double w = 0;
      for (int a = 0; a < 8; a++)
        if (slave[eind[8 * e + a]]) w += 24.0 / deg[eind[8 * e + a]];
      vwgt[2 * e]     = 1;
      vwgt[2 * e + 1] = (idx_t)(w + 0.5);
    }
    st = METIS_MeshToDual(&n, &nn, eptr, eind, &ncommon, &numflag, &xadj, &adjncy);
    PetscCheck(st == METIS_OK, PETSC_COMM_SELF, PETSC_ERR_LIB, "METIS_MeshToDual failed (status %d) on %" PetscInt_FMT " cells", st, ne);
    st = METIS_PartGraphKway(&n, &ncon, xadj, adjncy, vwgt, NULL, NULL, &np, NULL, NULL, opts, &objval, part);
    METIS_Free(xadj);
    METIS_Free(adjncy);
    PetscCall(PetscFree(vwgt));
    PetscCall(PetscFree(deg));
    PetscCheck(st == METIS_OK, PETSC_COMM_SELF, PETSC_ERR_LIB, "METIS_PartGraphKway (cells and contact nodes) failed (status %d) on %" PetscInt_FMT " cells into %" PetscInt_FMT " parts", st, ne, nparts);
  }
  for (idx_t e = 0; e < n; e++) epart[e] = (PetscInt)part[e];
  if (edgecut) *edgecut = (PetscInt)objval;
  PetscCall(PetscFree4(eptr, eind, part, npart));
  PetscFunctionReturn(0);
}
