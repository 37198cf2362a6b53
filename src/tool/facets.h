/* Private to src/tool/: the data of a "facets" patch (facets.c) and its loader (facetsio.c) */
#ifndef ATRITO_FACETS_H
#define ATRITO_FACETS_H
#include "toolimpl.h"

/* a node of the bounding-volume hierarchy: a box (rounded outwards to float) and an oriented box
   (axes n, the facets' mean normal, and t1 perpendicular to it, t2 = n x t1 in double; olo/ohi the
   extents of the facets' vertices along n, t1, t2 with these float axes, rounded outwards: thin
   along n for a patch of a smooth surface, so that the nodes beside a point's foot are pruned,
   which the axis-aligned box of a tilted patch cannot do); a leaf holds the facets first ..
   first+count-1, an inner node (count 0) its children first and first+1 */
/* a leaf's facets at most (a node of more is split in two at its median) */
#ifndef FACETS_LEAF
#define FACETS_LEAF 8
#endif

typedef struct {
  float lo[3], hi[3];
  float n[3], t1[3], olo[3], ohi[3];
  int   first, count;
} FacetsNode;

/* the third axis of a node's oriented box, t2 = n x t1 (the same arithmetic at build and query) */
static inline void FacetsNodeAxes(const FacetsNode *nd, double a[3][3])
{
  for (int i = 0; i < 3; i++) {
    a[0][i] = (double)nd->n[i];
    a[1][i] = (double)nd->t1[i];
  }
  a[2][0] = a[0][1] * a[1][2] - a[0][2] * a[1][1];
  a[2][1] = a[0][2] * a[1][0] - a[0][0] * a[1][2];
  a[2][2] = a[0][0] * a[1][1] - a[0][1] * a[1][0];
}

/* a slot of the bucket grid's table: its cell's key (the packed cell indices; -1: empty) and the
   start of its facets' list in glist (the list's last facet stored as -1 - f) */
typedef struct {
  int key, start;
} FacetsCell;

typedef struct {
  char           file[PETSC_MAX_PATH_LEN];
  int            nv, nf, nn, nnode, nopen;
  double        *V;     /* 3 nv: vertex coordinates (reference position)                          */
  int           *F;     /* 3 nf: vertex ids of each triangle, counterclockwise seen from the normal */
  int           *adj;   /* 3 nf: the neighbour across edge e (P_e P_e+1); -1 open, -2 non-manifold */
  int           *C;     /* 3 nf: corner normal ids (into N)                                         */
  double        *N;     /* 3 nn: unit corner normals (winding orientation; the sense applies)       */
  unsigned char *vbnd;  /* nv: 1 on an open edge                                                    */
  unsigned char *curved; /* nf: bit e set if edge e is smooth (shared, not sharper than the feature
                            angle): curved by the smoothing                                        */
  FacetsNode    *node;  /* nnode                                                                    */
  double         L;     /* the surface's size (bounding-box diagonal)                               */
  double         go[3], gh; /* bucket grid (warm start): origin and cell size (about twice a facet's size) */
  long           gn[3]; /* its cells along each axis (gn[0] gn[1] gn[2] below INT_MAX)              */
  int            gcap, nglist; /* its hash table's slots (a power of 2) and entries                  */
  FacetsCell    *gcell; /* gcap slots (count 0: empty)                                              */
  int           *glist; /* nglist: the facets whose bounding box meets each cell                     */
  float         *clear; /* nf: each triangle's clearance, a lower bound of the distance from it to every
                           triangle outside its star (the facets sharing a vertex with it), rounded
                           down (the local certificate)                                            */
  int           *vfs, *vf; /* nv + 1, 3 nf: the facets around each vertex, vf[vfs[k] .. vfs[k+1]-1],
                           increasing (a triangle's star: the union of its three vertices' lists)  */
  double         dev;   /* the largest distance of a smoothed facet from its plane triangle          */
  int            smooth;
  double         feature_deg;
} FacetsData;

/* what a facet file gives: vertices, triangles (and the file's id of each, for messages) */
typedef struct {
  int     nv, nf;
  double *V;
  int    *F, *fid;
} FacetsRaw;

/* reads the file on rank 0 (format: stl, msh, inp or tool from the extension unless `format` is
   given; group: a physical group (msh) or surface / element set (inp)) and broadcasts it */
PetscErrorCode FacetsRead(MPI_Comm comm, const char path[], const char format[], const char group[], FacetsRaw *raw);
/* builds a facets patch from raw (taken over): orientation and manifold checks, flip, hierarchy,
   corner normals */
PetscErrorCode FacetsBuild(MPI_Comm comm, Patch *p, const char path[], FacetsRaw *raw, PetscBool flip, PetscBool smooth, double feature_deg);
/* the options file, file_format, file_group, flip, smooth, feature_angle under stem (a patch's
   stem "-patch<j>" or "" for the tool's own -file) */
PetscErrorCode FacetsPatchFromOptions(PetscOptionItems *PetscOptionsObject, Patch *p, const char stem[]);
/* the format of path: from `format` if set, else its extension; "" if unknown */
void           FacetsFormat(const char path[], const char format[], char out[16]);
size_t         FacetsBytes(const FacetsData *m);
void           FacetsBytesBreakdown(const FacetsData *m, FILE *fp);
/* the bucket grid of the facets (after the facets and vertices are final) */
PetscErrorCode FacetsGridBuild(FacetsData *m);
/* each triangle's star and clearance (after the hierarchy is final) */
PetscErrorCode FacetsLocalBuild(FacetsData *m);
/* the patch of facet f at its local (u, v): point, first and second derivatives */
void FacetsEvalLocal(const FacetsData *m, int f, double u, double v, double x[3], double xu[3], double xv[3], double *xuu, double *xuv, double *xvv);
/* for the tests: the closest facet by brute force and by the hierarchy (squared distance) */
int FacetsBruteClosest(const Patch *p, const double y[3], double *d2);
int FacetsTreeClosest(const Patch *p, const double y[3], double *d2);
int FacetsCheckNodeBounds(const Patch *p, const double y[3], double *margin);
void FacetsEncodeForTest(int f, double u, double v, double *xi, double *eta);
/* for the tests: the distance of two triangles (squared), a facet's clearance and star, and
   whether the star of facet f alone decides the projection of y (the local certificate) */
double FacetsTriTriDistance2(const double A[3][3], const double B[3][3]);
/* for the tests: the squared distance of y from facet f's (smoothed) patch, and whether it is a stationary point */
double FacetsPatchDistance2(const Patch *p, int f, const double y[3], int *stationary);
double FacetsClearance(const Patch *p, int f, int *nstar, int star[], int maxstar);
int    FacetsStarCertifies(const Patch *p, int f, const double y[3]);
int FacetsOfParameters(const Patch *p, double xi, double eta, double *u, double *v);
#endif
