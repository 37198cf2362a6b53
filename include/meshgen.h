/* Serial mesh sources on plain arrays: built-in generators and the Abaqus-style .inp
   reader. They run on rank 0 only; mesh.c turns the result into a DMPlex. */
#ifndef ATRITO_MESHGEN_H
#define ATRITO_MESHGEN_H
#include <petscsys.h>

typedef struct {
  char      name[PETSC_MAX_PATH_LEN]; /* set name as given (case kept)      */
  PetscInt  n;                        /* number of entries                  */
  PetscInt *idx;                      /* 0-based vertex (nset) or cell (elset) indices, sorted, unique */
} MeshSet;

typedef struct {
  PetscInt   nv, ne;   /* vertices, hexahedra                                                      */
  PetscReal *X;        /* nv*3 reference coordinates                                               */
  PetscInt  *conn;     /* ne*8 0-based vertex indices, standard hex8 order: nodes 0-3 on the face
                          zeta=-1 counter-clockwise seen from +zeta, 4-7 above them; positive volume */
  PetscInt  *node_id;  /* nv: 1-based ids (deck ids for .inp, 1..nv for generators)                */
  PetscInt  *elem_id;  /* ne: 1-based ids                                                          */
  PetscInt   nnset, nelset;
  MeshSet   *nsets, *elsets;
} MeshData;

/* Box [lo, hi] with n[0] x n[1] x n[2] hexahedra.
   Node sets: xmin xmax ymin ymax zmin zmax. Element set: all. */
PetscErrorCode MeshDataCreateBox(const PetscReal lo[3], const PetscReal hi[3], const PetscInt n[3], MeshData *m);
/* The same with geometric grading along each direction: grading[d] is the size of the last cell
   over the first (cell sizes in geometric progression; 1: uniform, > 1: fine at lo, < 1: fine at hi). */
PetscErrorCode MeshDataCreateBoxGraded(const PetscReal lo[3], const PetscReal hi[3], const PetscInt n[3], const PetscReal grading[3], MeshData *m);

/* Circular blank of radius R and thickness t in 0 <= z <= t, centred on the z axis, O-grid:
   a central square block of half-side core*R (0 < core < 1) with ncore x ncore cells per
   quarter, joined to the circular rim by nradial cells along each radial line (2*ncore cells
   around the quarter arc), nlayers cells through the thickness. quarter: x >= 0, y >= 0 only;
   otherwise the full disk (4x the cells). Node sets: rim (r = R), top (z = t), bottom (z = 0),
   centre (the vertices on the axis), and for the quarter symx (x = 0), symy (y = 0).
   Element set: all. */
PetscErrorCode MeshDataCreateBlank(PetscReal R, PetscReal t, PetscReal core, PetscInt ncore, PetscInt nradial, PetscInt nlayers, PetscBool quarter, MeshData *m);

/* Abaqus-style deck: *NODE, *ELEMENT (TYPE=C3D8, C3D8R, C3D8I: all read as 8-node hexahedra),
   *NSET and *ELSET (lists, or GENERATE), comment lines **, continuation lines. Keeps the deck's
   ids in node_id / elem_id. Errors name the file and the line. */
PetscErrorCode MeshDataReadInp(const char *file, MeshData *m);

PetscErrorCode MeshDataDestroy(MeshData *m);

/* METIS partition of the cells into nparts (src/mesh/partition.c): epart[ne] the part of each
   cell, edgecut the dual graph's cut. slave = NULL: the cells balanced (METIS_PartMeshDual, 4
   common nodes, seed 7); slave[nv] marks the contact slave nodes: the cells and the slave nodes
   balanced together (two constraints). */
PetscErrorCode MeshPartitionCells(PetscInt ne, PetscInt nv, const PetscInt conn[], const PetscBool slave[], PetscInt nparts, PetscInt epart[], PetscInt *edgecut);
#endif
