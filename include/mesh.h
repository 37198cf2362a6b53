/* Mesh module: the serial mesh on rank 0 (built-in box or clamped blank, Abaqus-style .inp deck,
   Gmsh file), its METIS partition handed to DMPlex through the shell partitioner, distribution,
   one label per node or element set, the source ids, the section with the Dirichlet constraints,
   and the per-rank index arrays the kernels read.

   The arrays of a Mesh are read-only outside this module: mesh.c fills them, the other modules
   (assembly, contact, output, checkpoint) read them. */
#ifndef ATRITO_MESH_H
#define ATRITO_MESH_H
#include <petscdmplex.h>
#include "iorows.h"

#define ATRITO_NAME_LEN 256

typedef enum { MESH_BOX = 0, MESH_BLANK, MESH_GMSH, MESH_INP } MeshSource;

/* Options of the mesh (-mesh_*, -box_*, -blank_*, -partition, -partition_balance) */
typedef struct {
  MeshSource source;
  PetscBool  given;          /* -mesh_type or -mesh_file was set */
  char       file[PETSC_MAX_PATH_LEN];
  PetscReal  box_lower[3], box_upper[3];
  PetscInt   box_cells[3];
  PetscReal  box_grading[3]; /* last cell over first along x, y, z (geometric; 1 uniform) */
  PetscReal  blank_radius, blank_thickness, blank_core;
  PetscInt   blank_core_cells, blank_radial_cells, blank_layers;
  PetscBool  blank_quarter;
  PetscBool  partition_metis;
  PetscBool  partition_contact; /* -partition_balance contact: the slave nodes balanced with the cells */
} MeshOptions;

typedef struct {
  MPI_Comm    comm;
  PetscMPIInt rank, size;
  MeshOptions opt;

  DM        dm;        /* distributed mesh, section with the Dirichlet constraints     */
  DM        dmr;       /* same mesh, unconstrained section (reactions)                 */
  PetscInt  nc;        /* local cells                                                  */
  PetscInt  nv;        /* local vertices (owned and ghost)                             */
  PetscInt  vstart;    /* first vertex point                                           */
  PetscInt *cv;        /* nc*8 local vertex indices, standard hex8 order               */
  PetscReal *X;        /* nv*3 reference coordinates                                   */
  PetscInt *vloff;     /* nv: offset of the vertex's 3 dofs in the local vector        */
  PetscInt *cgdof;     /* nc*24: the element's unconstrained global dofs, sorted          */
  unsigned char *cperm;/* nc*24: the element-local dof (3a+c) of each of them             */
  PetscInt *cndof;     /* nc: how many                                                   */
  PetscBool *vowned;   /* nv                                                           */
  PetscInt *node_id, *elem_id;   /* source ids (1-based) per local vertex / cell          */
  PetscInt *node_src, *elem_src; /* 0-based position in the source mesh: the rank-independent
                                    numbering of the output and checkpoint rows              */
  PetscInt  nv_global, ne_global;
  PetscReal *varea;    /* nv: tributary area on the faces of the area sets (MeshSetAreaSets), else NULL */

  /* output and checkpoint rows, in the source mesh's order */
  PetscInt  nvo;       /* owned vertices                                                 */
  PetscInt *vloc;      /* their local indices                                           */
  PetscInt *vrow;      /* per local vertex: its row among the owned ones, -1 if a ghost */
  IORows    rv, rc;    /* owned vertices, cells                                         */

  /* requested before creation: the sets whose boundary faces give each node a tributary area */
  PetscInt  narea_set;
  char      area_set[8][ATRITO_NAME_LEN];
  /* requested before creation: the node sets whose boundary faces are marked (MeshSetFaceSets) */
  PetscInt  nface_set;
  char      face_set[16][ATRITO_NAME_LEN];
  /* requested before creation: the contact sets, for -partition_balance contact */
  PetscInt  ncontact_set;
  char      contact_set[8][ATRITO_NAME_LEN];
} Mesh;

/* reads the mesh options (collective; errors name the option) */
PetscErrorCode MeshSetFromOptions(MPI_Comm comm, MeshOptions *opt);
/* before MeshCreate: compute the tributary area of the nodes on the boundary faces of these sets
   (reference configuration, on the serial mesh) and carry it with the distribution */
PetscErrorCode MeshSetAreaSets(Mesh *m, PetscInt n, char (*sets)[ATRITO_NAME_LEN]);
/* before MeshCreate: mark the boundary faces of these sets (faces of one cell only whose four
   vertices all lie in the set; a set of elements gives its vertices), so that MeshGetBoundaryFaces
   lists them on the distributed mesh; repeated names are kept once */
PetscErrorCode MeshSetFaceSets(Mesh *m, PetscInt n, char (*sets)[ATRITO_NAME_LEN]);
/* the boundary faces of set `set` in this rank's cells (each face is in one cell, so on one rank):
   nf faces, fv[4 nf] their local vertices in cyclic order counter-clockwise seen from outside the
   body (the outward normal by the right-hand rule), fc[nf] 6 x their local cell + the face's
   index in the cell (0-5; fc may be NULL);
   the caller frees fv and fc */
PetscErrorCode MeshGetBoundaryFaces(const Mesh *m, const char *set, PetscInt *nf, PetscInt **fv, PetscInt **fc);
/* before MeshCreate: the sets of the contact slave nodes (balanced by -partition_balance contact) */
PetscErrorCode MeshSetContactSets(Mesh *m, PetscInt n, char (*sets)[ATRITO_NAME_LEN]);
/* builds, partitions and distributes the mesh; the sections come with MeshSetConstraints */
PetscErrorCode MeshCreate(MPI_Comm comm, const MeshOptions *opt, Mesh *m);
/* section: 3 dofs per vertex, cmask[v] bit c set where component c of local vertex v is
   constrained; then the local offsets, ownership, element dof maps and output rows */
PetscErrorCode MeshSetConstraints(Mesh *m, const PetscInt *cmask);
PetscErrorCode MeshDestroy(Mesh *m);
/* vertices of the set (label) `set`, marked in mark[nv]; found: this rank has the label */
PetscErrorCode MeshMarkSetVertices(const Mesh *m, const char *set, PetscBool *mark, PetscBool *found);
/* global dof of each component of local vertex v, -1 where constrained */
PetscErrorCode MeshVertexDofs(const Mesh *m, PetscInt v, PetscInt idx[3]);
#endif
