/* Field output: one HDF5 file written in parallel (MPI-IO), with an XDMF index that
   ParaView opens. Every rank passes the rows it owns (a contiguous block of the global
   numbering); plain arrays at the interface. */
#ifndef ATRITO_OUTPUT_H
#define ATRITO_OUTPUT_H
#include <petscsys.h>

typedef struct {
  const char      *name;  /* dataset / attribute name, e.g. "displacement" */
  PetscInt         ncomp; /* 1 (scalar) or 3 (vector)                      */
  const PetscReal *data;  /* nlocal*ncomp values, rows in global order     */
} OutputField;

typedef struct _p_OutputFields *OutputFields;

/* Create DIR/fields.h5 (truncating it) and DIR/fields.xmf. Collective. */
PetscErrorCode OutputFieldsCreate(MPI_Comm comm, const char *dir, OutputFields *of);
/* The reference mesh, written once under /mesh: coordinates (nv x 3), hexahedra (ne x 8 global
   0-based vertex numbers in the standard hex8 / VTK order), node_ids, element_ids (1-based ids
   of the source). v_offset / e_offset: the global index of this rank's first row. */
PetscErrorCode OutputFieldsWriteMesh(OutputFields of, PetscInt nv_local, PetscInt v_offset, PetscInt nv_global, const PetscReal *X, const PetscInt *node_id, PetscInt ne_local, PetscInt e_offset, PetscInt ne_global, const PetscInt *conn, const PetscInt *elem_id);
/* One output time under /steps/NNNNNN: node fields (nv rows) and cell fields (ne rows), with
   the step and time as attributes; the file is closed after each call and the XDMF index
   rewritten atomically (write then rename), so a run killed at any moment leaves both readable. */
PetscErrorCode OutputFieldsWriteStep(OutputFields of, PetscInt step, PetscReal time, PetscInt nnode, const OutputField node[], PetscInt ncell, const OutputField cell[]);
PetscErrorCode OutputFieldsDestroy(OutputFields *of);
/* Helpers. OutputEnsureDirectory: collective; rank 0 creates dir and its parents (mkdir -p),
   every rank fails, naming dir, when it could not. OutputWriteTextAtomic: rank-local; writes
   path.tmp, fsyncs it and renames it onto path, so readers see the old or the new text. */
PetscErrorCode OutputEnsureDirectory(MPI_Comm comm, const char *dir);
PetscErrorCode OutputWriteTextAtomic(const char *path, const char *text);


/* Restart: continue DIR/fields.h5 written by an earlier run of the same mesh. The steps after
   keep_step (written after the checkpoint the run restarts from) are removed; the XDMF index is
   rebuilt from the file. The rows of this rank: as for OutputFieldsWriteMesh. Collective. */
PetscErrorCode OutputFieldsReopen(MPI_Comm comm, const char *dir, PetscInt keep_step, PetscInt nv_local, PetscInt v_offset, PetscInt ne_local, PetscInt e_offset, OutputFields *of);
#endif
