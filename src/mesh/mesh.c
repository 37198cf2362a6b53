/* Mesh module: the serial mesh on rank 0 (generator, .inp deck or Gmsh file), its METIS
   partition handed to DMPlex through the shell partitioner, distribution, boundary-set
   labels, source ids, and the per-rank index arrays of the element and node kernels. */
#include <string.h>
#include <metis.h>
#include <petscsf.h>
#include "mesh.h"
#include "meshgen.h"
#include "options.h"
#include "element_hex8.h"
#include "contact_law.h"
#include "util.h"

/* DMPlex lists a hexahedron's bottom face with its normal pointing into the cell; the standard
   order lists it counter-clockwise seen from above. The map is an involution: swap 1 and 3. */
static const PetscInt hex_plex_to_std[8] = {0, 3, 2, 1, 4, 5, 6, 7};

/* Gmsh file through DMPlex's reader, converted to plain arrays. Every label (physical group)
   becomes a node set holding the vertices of its points' closures: named after the label, with
   "_<value>" appended when the label has several values; blanks become underscores. A group that
   holds cells (a physical volume) also becomes an element set of those cells, of the same name
   (MeshCreate then calls it "<name>_elements"; -body_<b>_set finds it by either name). */
static PetscErrorCode MeshDataReadGmsh(const char *file, MeshData *m)
{
  DM              dm;
  PetscInt        cStart, cEnd, vStart, vEnd, nlabels;
  Vec             coords;
  const PetscScalar *xa;
  FILE           *fp;

  PetscFunctionBeginUser;
  fp = fopen(file, "r");
  PetscCheck(fp, PETSC_COMM_SELF, PETSC_ERR_FILE_OPEN, "cannot open mesh file '%s' (-mesh_file)", file);
  fclose(fp);
  PetscCall(PetscMemzero(m, sizeof(*m)));
  {
    /* physical names become the set names unless the user says otherwise: the reader runs on a
       private copy of the options, so the user's database is not written */
    PetscOptions opts;
    PetscBool    has;
    char        *all;
    PetscCall(PetscOptionsCreate(&opts));
    PetscCall(PetscOptionsGetAll(NULL, &all));
    PetscCall(PetscOptionsInsertString(opts, all));
    PetscCall(PetscFree(all));
    PetscCall(PetscOptionsHasName(NULL, NULL, "-dm_plex_gmsh_use_regions", &has));
    if (!has) PetscCall(PetscOptionsSetValue(opts, "-dm_plex_gmsh_use_regions", "true"));
    PetscCall(PetscOptionsPush(opts));
    PetscErrorCode ierr = DMPlexCreateGmshFromFile(PETSC_COMM_SELF, file, PETSC_TRUE, &dm);
    PetscCall(PetscOptionsPop());
    PetscCall(PetscOptionsDestroy(&opts));
    PetscCall(ierr);
  }
  PetscCall(DMPlexGetHeightStratum(dm, 0, &cStart, &cEnd));
  PetscCall(DMPlexGetDepthStratum(dm, 0, &vStart, &vEnd));
  m->ne = cEnd - cStart;
  m->nv = vEnd - vStart;
  PetscCheck(m->ne > 0, PETSC_COMM_SELF, PETSC_ERR_FILE_UNEXPECTED, "mesh file '%s' holds no 3D cells", file);
  /* separate allocations: MeshDataDestroy frees each array on its own */
  PetscCall(PetscMalloc1(3 * m->nv, &m->X));
  PetscCall(PetscMalloc1(8 * m->ne, &m->conn));
  PetscCall(PetscMalloc1(m->nv, &m->node_id));
  PetscCall(PetscMalloc1(m->ne, &m->elem_id));
  PetscCall(PetscCalloc1(1, &m->elsets));
  PetscCall(DMGetCoordinatesLocal(dm, &coords));
  PetscCall(VecGetArrayRead(coords, &xa));
  for (PetscInt i = 0; i < 3 * m->nv; i++) m->X[i] = PetscRealPart(xa[i]);
  PetscCall(VecRestoreArrayRead(coords, &xa));
  for (PetscInt v = 0; v < m->nv; v++) m->node_id[v] = v + 1;
  for (PetscInt c = cStart; c < cEnd; c++) {
    DMPolytopeType ct;
    PetscInt      *cl = NULL, ncl, k = 0, vv[8];
    PetscCall(DMPlexGetCellType(dm, c, &ct));
    PetscCheck(ct == DM_POLYTOPE_HEXAHEDRON, PETSC_COMM_SELF, PETSC_ERR_SUP, "mesh file '%s': cell %" PetscInt_FMT " is a %s; only 8-node hexahedra are supported", file, c - cStart + 1, DMPolytopeTypes[ct]);
    PetscCall(DMPlexGetTransitiveClosure(dm, c, PETSC_TRUE, &ncl, &cl));
    for (PetscInt i = 0; i < ncl; i++)
      if (cl[2 * i] >= vStart && cl[2 * i] < vEnd && k < 8) vv[k++] = cl[2 * i] - vStart;
    PetscCall(DMPlexRestoreTransitiveClosure(dm, c, PETSC_TRUE, &ncl, &cl));
    for (PetscInt i = 0; i < 8; i++) m->conn[8 * (c - cStart) + i] = vv[hex_plex_to_std[i]];
    m->elem_id[c - cStart] = c - cStart + 1;
  }
  /* element set "all" */
  m->nelset = 1;
  PetscCall(PetscStrncpy(m->elsets[0].name, "all", sizeof(m->elsets[0].name)));
  m->elsets[0].n = m->ne;
  PetscCall(PetscMalloc1(m->ne, &m->elsets[0].idx));
  for (PetscInt c = 0; c < m->ne; c++) m->elsets[0].idx[c] = c;
  /* labels to node sets */
  PetscCall(DMGetNumLabels(dm, &nlabels));
  for (PetscInt l = 0; l < nlabels; l++) {
    const char     *lname;
    DMLabel         label;
    IS              vis;
    const PetscInt *vals;
    PetscInt        nvals;
    PetscCall(DMGetLabelName(dm, l, &lname));
    if (!strcmp(lname, "depth") || !strcmp(lname, "celltype")) continue;
    PetscCall(DMGetLabel(dm, lname, &label));
    PetscCall(DMLabelGetValueIS(label, &vis));
    PetscCall(ISGetLocalSize(vis, &nvals));
    PetscCall(ISGetIndices(vis, &vals));
    for (PetscInt iv = 0; iv < nvals; iv++) {
      IS              pis;
      const PetscInt *pts;
      PetscInt        np, nmark = 0, ncell = 0;
      PetscBool      *mark, *cmark;
      MeshSet        *s;
      PetscCall(PetscCalloc1(m->nv, &mark));
      PetscCall(PetscCalloc1(m->ne, &cmark));
      PetscCall(DMLabelGetStratumIS(label, vals[iv], &pis));
      if (pis) {
        PetscCall(ISGetLocalSize(pis, &np));
        PetscCall(ISGetIndices(pis, &pts));
        for (PetscInt ip = 0; ip < np; ip++) {
          PetscInt *cl = NULL, ncl;
          if (pts[ip] >= cStart && pts[ip] < cEnd && !cmark[pts[ip] - cStart]) {
            cmark[pts[ip] - cStart] = PETSC_TRUE;
            ncell++;
          }
          PetscCall(DMPlexGetTransitiveClosure(dm, pts[ip], PETSC_TRUE, &ncl, &cl));
          for (PetscInt i = 0; i < ncl; i++)
            if (cl[2 * i] >= vStart && cl[2 * i] < vEnd) mark[cl[2 * i] - vStart] = PETSC_TRUE;
          PetscCall(DMPlexRestoreTransitiveClosure(dm, pts[ip], PETSC_TRUE, &ncl, &cl));
        }
        PetscCall(ISRestoreIndices(pis, &pts));
        PetscCall(ISDestroy(&pis));
      }
      PetscCall(PetscRealloc(sizeof(MeshSet) * (m->nnset + 1), &m->nsets));
      s = &m->nsets[m->nnset++];
      if (nvals > 1) PetscCall(PetscSNPrintf(s->name, sizeof(s->name), "%s_%" PetscInt_FMT, lname, vals[iv]));
      else PetscCall(PetscStrncpy(s->name, lname, sizeof(s->name)));
      for (char *ch = s->name; *ch; ch++)
        if (*ch == ' ') *ch = '_';
      for (PetscInt v = 0; v < m->nv; v++) nmark += mark[v];
      s->n = nmark;
      PetscCall(PetscMalloc1(nmark, &s->idx));
      nmark = 0;
      for (PetscInt v = 0; v < m->nv; v++)
        if (mark[v]) s->idx[nmark++] = v;
      PetscCall(PetscFree(mark));
      if (ncell) { /* a physical volume: its cells as an element set */
        MeshSet *es;
        PetscCall(PetscRealloc(sizeof(MeshSet) * (m->nelset + 1), &m->elsets));
        es = &m->elsets[m->nelset++];
        PetscCall(PetscMemzero(es, sizeof(*es)));
        PetscCall(PetscStrncpy(es->name, s->name, sizeof(es->name)));
        es->n = ncell;
        PetscCall(PetscMalloc1(ncell, &es->idx));
        ncell = 0;
        for (PetscInt c = 0; c < m->ne; c++)
          if (cmark[c]) es->idx[ncell++] = c;
      }
      PetscCall(PetscFree(cmark));
    }
    PetscCall(ISRestoreIndices(vis, &vals));
    PetscCall(ISDestroy(&vis));
  }
  PetscCall(DMDestroy(&dm));
  PetscFunctionReturn(0);
}

static PetscErrorCode MeshDataLoad(const MeshOptions *o, MeshData *m)
{
  PetscFunctionBeginUser;
  switch (o->source) {
  case MESH_BOX:
    PetscCall(MeshDataCreateBoxGraded(o->box_lower, o->box_upper, o->box_cells, o->box_grading, m));
    break;
  case MESH_BLANK:
    PetscCall(MeshDataCreateBlank(o->blank_radius, o->blank_thickness, o->blank_core, o->blank_core_cells, o->blank_radial_cells, o->blank_layers, o->blank_quarter, m));
    break;
  case MESH_INP:
    PetscCall(MeshDataReadInp(o->file, m));
    break;
  case MESH_GMSH:
    PetscCall(MeshDataReadGmsh(o->file, m));
    break;
  }
  /* every cell must have a positive Jacobian at its Gauss points and corners */
  for (PetscInt e = 0; e < m->ne; e++) {
    double X[8][3];
    for (int a = 0; a < 8; a++)
      for (int i = 0; i < 3; i++) X[a][i] = m->X[3 * m->conn[8 * e + a] + i];
    PetscCheck(hex8_min_jacobian(X) > 0, PETSC_COMM_SELF, PETSC_ERR_ARG_WRONG, "element id %" PetscInt_FMT " is inverted or degenerate (non-positive Jacobian)", m->elem_id[e]);
  }
  PetscFunctionReturn(0);
}

/* METIS partition of the cells, on rank 0 (MeshPartitionCells); with -partition_balance contact
   the vertices of the contact sets (node sets, or all vertices of element sets, as the contact
   object takes them) are balanced with the cells */
static PetscErrorCode PartitionMetis(const Mesh *mesh, const MeshData *m, char (*names)[ATRITO_NAME_LEN], const PetscInt *is_cell, PetscInt nnames, PetscMPIInt size, PetscInt *sizes, PetscInt *points)
{
  PetscInt  *epart, *off;
  PetscBool *slave = NULL;

  PetscFunctionBeginUser;
  if (mesh->opt.partition_contact) {
    PetscCall(PetscCalloc1(m->nv, &slave));
    for (PetscInt s = 0; s < mesh->ncontact_set; s++) {
      PetscInt set = -1;
      for (PetscInt i = 0; i < nnames && set < 0; i++) {
        PetscBool eq;
        PetscCall(PetscStrcmp(names[i], mesh->contact_set[s], &eq));
        if (eq) set = i;
      }
      if (set < 0) continue; /* reported by ContactSetUp */
      if (!is_cell[set])
        for (PetscInt k = 0; k < m->nsets[set].n; k++) slave[m->nsets[set].idx[k]] = PETSC_TRUE;
      else
        for (PetscInt k = 0; k < m->elsets[set - m->nnset].n; k++)
          for (PetscInt a = 0; a < 8; a++) slave[m->conn[8 * m->elsets[set - m->nnset].idx[k] + a]] = PETSC_TRUE;
    }
  }
  PetscCall(PetscMalloc1(m->ne, &epart));
  PetscCall(MeshPartitionCells(m->ne, m->nv, m->conn, slave, size, epart, NULL));
  for (PetscMPIInt r = 0; r < size; r++) sizes[r] = 0;
  for (PetscInt e = 0; e < m->ne; e++) sizes[epart[e]]++;
  PetscCall(PetscCalloc1(size + 1, &off));
  for (PetscMPIInt r = 0; r < size; r++) off[r + 1] = off[r] + sizes[r];
  for (PetscInt e = 0; e < m->ne; e++) points[off[epart[e]]++] = e;
  PetscCall(PetscFree(off));
  PetscCall(PetscFree(epart));
  PetscCall(PetscFree(slave));
  PetscFunctionReturn(0);
}

/* Vertices of label `set` (any points: their closures), marked in mark[nv] */
PetscErrorCode MeshMarkSetVertices(const Mesh *pb, const char *set, PetscBool *mark, PetscBool *found)
{
  DMLabel  label;
  PetscInt pStart, pEnd;

  PetscFunctionBeginUser;
  PetscCall(DMGetLabel(pb->dm, set, &label));
  *found = label ? PETSC_TRUE : PETSC_FALSE;
  if (!label) PetscFunctionReturn(0);
  PetscCall(DMPlexGetChart(pb->dm, &pStart, &pEnd));
  for (PetscInt p = pStart; p < pEnd; p++) {
    PetscInt val, *cl = NULL, ncl;
    PetscCall(DMLabelGetValue(label, p, &val));
    if (val < 0) continue;
    PetscCall(DMPlexGetTransitiveClosure(pb->dm, p, PETSC_TRUE, &ncl, &cl));
    for (PetscInt i = 0; i < ncl; i++) {
      const PetscInt q = cl[2 * i] - pb->vstart;
      if (q >= 0 && q < pb->nv) mark[q] = PETSC_TRUE;
    }
    PetscCall(DMPlexRestoreTransitiveClosure(pb->dm, p, PETSC_TRUE, &ncl, &cl));
  }
  PetscFunctionReturn(0);
}

/* Output rows: the owned vertices and the cells, in the source mesh's order (iorows.h) */
static PetscErrorCode OutputRowsCreate(Mesh *pb)
{
  PetscInt *src;

  PetscFunctionBeginUser;
  PetscCall(PetscMalloc2(pb->nv, &pb->vloc, pb->nv, &pb->vrow));
  pb->nvo = 0;
  for (PetscInt v = 0; v < pb->nv; v++) {
    pb->vrow[v] = pb->vowned[v] ? pb->nvo : -1;
    if (pb->vowned[v]) pb->vloc[pb->nvo++] = v;
  }
  PetscCall(PetscMalloc1(PetscMax(pb->nvo, pb->nc), &src));
  for (PetscInt k = 0; k < pb->nvo; k++) src[k] = pb->node_src[pb->vloc[k]];
  PetscCall(IORowsCreate(pb->comm, pb->nvo, src, &pb->rv));
  PetscCall(IORowsCreate(pb->comm, pb->nc, pb->elem_src, &pb->rc));
  PetscCall(PetscFree(src));
  PetscCheck(pb->rv.N == pb->nv_global && pb->rc.N == pb->ne_global, pb->comm, PETSC_ERR_PLIB, "output rows: %" PetscInt_FMT " vertices and %" PetscInt_FMT " cells owned, the mesh has %" PetscInt_FMT " and %" PetscInt_FMT, pb->rv.N, pb->rc.N, pb->nv_global, pb->ne_global);
  PetscFunctionReturn(0);
}

/* Section with three displacement dofs per vertex and the Dirichlet constraints (cmask from the
   boundary conditions); the local offsets, ownership, element dof maps and the output rows */
PetscErrorCode MeshSetConstraints(Mesh *pb, const PetscInt *cmask)
{
  PetscSection s, sr;
  PetscInt     pStart, pEnd;

  PetscFunctionBeginUser;
  PetscCall(DMPlexGetChart(pb->dm, &pStart, &pEnd));
  PetscCall(PetscSectionCreate(pb->comm, &s));
  PetscCall(PetscSectionSetNumFields(s, 1));
  PetscCall(PetscSectionSetFieldName(s, 0, "displacement"));
  PetscCall(PetscSectionSetFieldComponents(s, 0, 3));
  PetscCall(PetscSectionSetChart(s, pStart, pEnd));
  for (PetscInt v = 0; v < pb->nv; v++) {
    PetscInt nc = 0;
    for (PetscInt c = 0; c < 3; c++) nc += (cmask[v] >> c) & 1;
    PetscCall(PetscSectionSetDof(s, pb->vstart + v, 3));
    PetscCall(PetscSectionSetFieldDof(s, pb->vstart + v, 0, 3));
    if (nc) {
      PetscCall(PetscSectionSetConstraintDof(s, pb->vstart + v, nc));
      PetscCall(PetscSectionSetFieldConstraintDof(s, pb->vstart + v, 0, nc));
    }
  }
  PetscCall(PetscSectionSetUp(s));
  for (PetscInt v = 0; v < pb->nv; v++) {
    PetscInt idx[3], nc = 0;
    for (PetscInt c = 0; c < 3; c++)
      if ((cmask[v] >> c) & 1) idx[nc++] = c;
    if (nc) {
      PetscCall(PetscSectionSetConstraintIndices(s, pb->vstart + v, idx));
      PetscCall(PetscSectionSetFieldConstraintIndices(s, pb->vstart + v, 0, idx));
    }
  }
  PetscCall(DMSetLocalSection(pb->dm, s));
  PetscCall(DMSetBasicAdjacency(pb->dm, PETSC_FALSE, PETSC_TRUE));

  /* the unconstrained twin, for reactions */
  PetscCall(DMClone(pb->dm, &pb->dmr));
  PetscCall(PetscSectionCreate(pb->comm, &sr));
  PetscCall(PetscSectionSetChart(sr, pStart, pEnd));
  for (PetscInt v = 0; v < pb->nv; v++) PetscCall(PetscSectionSetDof(sr, pb->vstart + v, 3));
  PetscCall(PetscSectionSetUp(sr));
  PetscCall(DMSetLocalSection(pb->dmr, sr));

  /* per-vertex local offsets; the two local layouts must agree */
  PetscCall(PetscMalloc1(pb->nv, &pb->vloff));
  for (PetscInt v = 0; v < pb->nv; v++) {
    PetscInt off, offr;
    PetscCall(PetscSectionGetOffset(s, pb->vstart + v, &off));
    PetscCall(PetscSectionGetOffset(sr, pb->vstart + v, &offr));
    PetscCheck(off == offr, PETSC_COMM_SELF, PETSC_ERR_PLIB, "local layouts differ at vertex %" PetscInt_FMT, v);
    pb->vloff[v] = off;
  }

  /* BC dof lists and owned-vertex lists */
  {
    PetscSection gs;
    PetscCall(DMGetGlobalSection(pb->dm, &gs));
    PetscCall(PetscMalloc1(pb->nv, &pb->vowned));
    for (PetscInt v = 0; v < pb->nv; v++) {
      PetscInt goff;
      PetscCall(PetscSectionGetOffset(gs, pb->vstart + v, &goff));
      pb->vowned[v] = goff >= 0 ? PETSC_TRUE : PETSC_FALSE;
    }
    /* element dof map: the unconstrained element dofs, sorted by global index (sorted columns make
       MatSetValues faster), with the element-local dof (3a+c) of each */
    PetscCall(PetscMalloc3(24 * pb->nc, &pb->cgdof, 24 * pb->nc, &pb->cperm, pb->nc, &pb->cndof));
    for (PetscInt e = 0; e < pb->nc; e++) {
      PetscInt g[24], p[24], n = 0;
      for (PetscInt a = 0; a < 8; a++) {
        const PetscInt v = pb->cv[8 * e + a];
        PetscInt       goff, skipped = 0;
        PetscCall(PetscSectionGetOffset(gs, pb->vstart + v, &goff));
        if (goff < 0) goff = -(goff + 1);
        for (PetscInt c = 0; c < 3; c++) {
          if ((cmask[v] >> c) & 1) skipped++;
          else {
            g[n]   = goff + c - skipped;
            p[n++] = 3 * a + c;
          }
        }
      }
      PetscCall(PetscSortIntWithArray(n, g, p));
      pb->cndof[e] = n;
      for (PetscInt k = 0; k < n; k++) {
        pb->cgdof[24 * e + k] = g[k];
        pb->cperm[24 * e + k] = (unsigned char)p[k];
      }
    }
  }
  PetscCall(PetscSectionDestroy(&s));
  PetscCall(PetscSectionDestroy(&sr));
  PetscCall(OutputRowsCreate(pb));
  PetscFunctionReturn(0);
}

/* Rank 0, with -contact_penalty_per_area: the tributary area of every source vertex on the faces
   of the contact sets. A face counts when its four vertices all lie in one set and no other cell
   has the same four vertices (a boundary face); each corner receives the integral of its shape
   function over the face (ContactQuadAreas), in the reference configuration. */
typedef struct {
  PetscInt key[4], cell, face;
} FaceRec;

static int FaceRecCmp(const void *a, const void *b)
{
  const FaceRec *x = (const FaceRec *)a, *y = (const FaceRec *)b;
  for (int i = 0; i < 4; i++)
    if (x->key[i] != y->key[i]) return x->key[i] < y->key[i] ? -1 : 1;
  return 0;
}

static const int hexface[6][4] = {{0, 3, 2, 1}, {4, 5, 6, 7}, {0, 1, 5, 4}, {1, 2, 6, 5}, {2, 3, 7, 6}, {3, 0, 4, 7}};

/* Rank 0: the boundary faces among those whose four vertices are all marked: faces no other cell
   has (the same four vertices). Each as its cell and its face (hexface: corners in cyclic order,
   counter-clockwise seen from outside the cell). */
static PetscErrorCode SerialBoundaryFaces(const MeshData *md, const PetscBool *mark, PetscInt *nb, FaceRec **out)
{
  FaceRec *fr = NULL;
  PetscInt nf = 0, m = 0;

  PetscFunctionBeginUser;
  for (int pass = 0; pass < 2; pass++) { /* count the faces in the set, then list them */
    if (pass) PetscCall(PetscMalloc1(nf + 1, &fr));
    nf = 0;
    for (PetscInt e = 0; e < md->ne; e++)
      for (int k = 0; k < 6; k++) {
        PetscBool all = PETSC_TRUE;
        for (int j = 0; j < 4; j++) all = all && mark[md->conn[8 * e + hexface[k][j]]];
        if (!all) continue;
        if (pass) {
          for (int j = 0; j < 4; j++) fr[nf].key[j] = md->conn[8 * e + hexface[k][j]];
          PetscCall(PetscSortInt(4, fr[nf].key));
          fr[nf].cell = e;
          fr[nf].face = k;
        }
        nf++;
      }
  }
  qsort(fr, (size_t)nf, sizeof(FaceRec), FaceRecCmp);
  for (PetscInt f = 0; f < nf;) {
    PetscInt g = f + 1;
    while (g < nf && !FaceRecCmp(&fr[f], &fr[g])) g++;
    if (g == f + 1) fr[m++] = fr[f]; /* on the boundary */
    f = g;
  }
  *nb  = m;
  *out = fr;
  PetscFunctionReturn(0);
}

/* Rank 0: the vertices of set `name` (a node set, or the vertices of an element set) marked; -1 if
   there is no such set */
static PetscErrorCode SerialMarkSet(const MeshData *md, char (*names)[ATRITO_NAME_LEN], const PetscInt *is_cell, PetscInt nnames, const char *name, PetscBool *mark, PetscInt *set)
{
  PetscFunctionBeginUser;
  *set = -1;
  for (PetscInt i = 0; i < nnames && *set < 0; i++) {
    PetscBool eq;
    PetscCall(PetscStrcmp(names[i], name, &eq));
    if (eq) *set = i;
  }
  if (*set < 0) PetscFunctionReturn(0);
  PetscCall(PetscArrayzero(mark, md->nv));
  if (!is_cell[*set])
    for (PetscInt k = 0; k < md->nsets[*set].n; k++) mark[md->nsets[*set].idx[k]] = PETSC_TRUE;
  else
    for (PetscInt k = 0; k < md->elsets[*set - md->nnset].n; k++)
      for (PetscInt a = 0; a < 8; a++) mark[md->conn[8 * md->elsets[*set - md->nnset].idx[k] + a]] = PETSC_TRUE;
  PetscFunctionReturn(0);
}

static PetscErrorCode SerialContactAreas(const Mesh *mesh, const MeshData *md, char (*names)[ATRITO_NAME_LEN], const PetscInt *is_cell, PetscInt nnames, PetscReal *area)
{
  PetscBool *mark;

  PetscFunctionBeginUser;
  PetscCall(PetscMalloc1(md->nv, &mark));
  for (PetscInt s = 0; s < mesh->narea_set; s++) {
    PetscInt set, nf;
    FaceRec *fr;
    PetscCall(SerialMarkSet(md, names, is_cell, nnames, mesh->area_set[s], mark, &set));
    if (set < 0) continue; /* reported by ContactSetUp */
    PetscCall(SerialBoundaryFaces(md, mark, &nf, &fr));
    for (PetscInt f = 0; f < nf; f++) {
      const PetscInt *c = md->conn + 8 * fr[f].cell;
      double          x[4][3], af[4];
      for (int j = 0; j < 4; j++)
        for (int d = 0; d < 3; d++) x[j][d] = md->X[3 * c[hexface[fr[f].face][j]] + d];
      ContactQuadAreas(x, af);
      for (int j = 0; j < 4; j++) area[c[hexface[fr[f].face][j]]] += af[j];
    }
    PetscCall(PetscFree(fr));
  }
  PetscCall(PetscFree(mark));
  PetscFunctionReturn(0);
}

/* the cell label that marks the boundary faces of node set `set` (MeshSetFaceSets) */
static void FaceLabelName(const char *set, char name[ATRITO_NAME_LEN + 16])
{
  snprintf(name, ATRITO_NAME_LEN + 16, "__faces_%s", set);
}

/* Rank 0, on the serial DM: for every face set, the label whose value on a cell is the bit mask of
   its faces (1 << k, hexface k) that lie on the boundary with their four vertices in the set. The
   label travels with the cells through the distribution. A set that does not exist gets an empty
   label (reported by the module that asked). */
static PetscErrorCode SerialFaceLabels(const Mesh *mesh, DM dm, const MeshData *md, char (*names)[ATRITO_NAME_LEN], const PetscInt *is_cell, PetscInt nnames)
{
  PetscBool *mark = NULL;
  PetscMPIInt rank;

  PetscFunctionBeginUser;
  PetscCallMPI(MPI_Comm_rank(PetscObjectComm((PetscObject)dm), &rank));
  if (!rank) PetscCall(PetscMalloc1(md->nv, &mark));
  for (PetscInt s = 0; s < mesh->nface_set; s++) {
    char     lname[ATRITO_NAME_LEN + 16];
    PetscInt set, nf;
    FaceRec *fr;
    FaceLabelName(mesh->face_set[s], lname);
    PetscCall(DMCreateLabel(dm, lname));
    if (rank) continue;
    PetscCall(SerialMarkSet(md, names, is_cell, nnames, mesh->face_set[s], mark, &set));
    if (set < 0) continue;
    PetscCall(SerialBoundaryFaces(md, mark, &nf, &fr));
    for (PetscInt f = 0; f < nf; f++) {
      PetscInt v;
      PetscCall(DMGetLabelValue(dm, lname, fr[f].cell, &v));
      if (v >= 0) PetscCall(DMClearLabelValue(dm, lname, fr[f].cell, v));
      PetscCall(DMSetLabelValue(dm, lname, fr[f].cell, (v < 0 ? 0 : v) | (1 << fr[f].face)));
    }
    PetscCall(PetscFree(fr));
  }
  PetscCall(PetscFree(mark));
  PetscFunctionReturn(0);
}

PetscErrorCode MeshCreate(MPI_Comm comm, const MeshOptions *opt, Mesh *pb)
{
  MeshData       md;
  PetscErrorCode ierr = 0;
  DM             dm, dmd = NULL;
  PetscSF        sfmig = NULL;
  PetscInt       nnames = 0;
  char         (*names)[ATRITO_NAME_LEN] = NULL;
  PetscInt      *is_cell = NULL;
  PetscInt       dims[2] = {0, 0};

  PetscFunctionBeginUser;
  pb->comm = comm;
  pb->opt  = *opt;
  PetscCallMPI(MPI_Comm_rank(comm, &pb->rank));
  PetscCallMPI(MPI_Comm_size(comm, &pb->size));
  PetscCall(PetscMemzero(&md, sizeof(md)));
  /* rank 0 reads or generates; a failure there is reported on every rank */
  if (pb->rank == 0) {
    PetscCall(PetscPushErrorHandler(PetscReturnErrorHandler, NULL));
    ierr = MeshDataLoad(opt, &md);
    PetscCall(PetscPopErrorHandler());
  }
  PetscCall(AtritoRootError(pb->comm, ierr));
  if (pb->rank == 0) {
    dims[0] = md.nv;
    dims[1] = md.ne;
  }
  PetscCallMPI(MPI_Bcast(dims, 2, MPIU_INT, 0, pb->comm));
  pb->nv_global = dims[0];
  pb->ne_global = dims[1];

  {
    PetscInt *cells = NULL;
    if (pb->rank == 0) {
      PetscCall(PetscMalloc1(8 * md.ne, &cells));
      for (PetscInt e = 0; e < md.ne; e++)
        for (PetscInt i = 0; i < 8; i++) cells[8 * e + i] = md.conn[8 * e + hex_plex_to_std[i]];
    }
    PetscCall(DMPlexCreateFromCellListPetsc(pb->comm, 3, pb->rank ? 0 : md.ne, pb->rank ? 0 : md.nv, 8, PETSC_FALSE, cells, 3, pb->rank ? NULL : md.X, &dm));
    PetscCall(PetscFree(cells));
  }
  PetscCall(PetscObjectSetName((PetscObject)dm, "mesh"));

  /* set names, broadcast so that every rank creates every label */
  if (pb->rank == 0) {
    nnames = md.nnset + md.nelset;
    PetscCall(PetscCalloc2(nnames, &names, nnames, &is_cell));
    for (PetscInt i = 0; i < md.nnset; i++) PetscCall(PetscStrncpy(names[i], md.nsets[i].name, ATRITO_NAME_LEN));
    for (PetscInt i = 0; i < md.nelset; i++) {
      PetscBool clash = PETSC_FALSE;
      for (PetscInt j = 0; j < md.nnset; j++) {
        PetscBool eq;
        PetscCall(PetscStrcmp(md.nsets[j].name, md.elsets[i].name, &eq));
        clash = clash || eq;
      }
      if (clash) PetscCall(PetscSNPrintf(names[md.nnset + i], ATRITO_NAME_LEN, "%s_elements", md.elsets[i].name));
      else PetscCall(PetscStrncpy(names[md.nnset + i], md.elsets[i].name, ATRITO_NAME_LEN));
      is_cell[md.nnset + i] = 1;
    }
  }
  PetscCallMPI(MPI_Bcast(&nnames, 1, MPIU_INT, 0, pb->comm));
  if (pb->rank) PetscCall(PetscCalloc2(nnames, &names, nnames, &is_cell));
  PetscCallMPI(MPI_Bcast(names, (PetscMPIInt)(nnames * ATRITO_NAME_LEN), MPI_CHAR, 0, pb->comm));
  {
    PetscInt vStart, vEnd;
    PetscCall(DMPlexGetDepthStratum(dm, 0, &vStart, &vEnd));
    for (PetscInt i = 0; i < nnames; i++) {
      PetscCall(DMCreateLabel(dm, names[i]));
      if (pb->rank) continue;
      if (!is_cell[i])
        for (PetscInt k = 0; k < md.nsets[i].n; k++) PetscCall(DMSetLabelValue(dm, names[i], vStart + md.nsets[i].idx[k], 1));
      else
        for (PetscInt k = 0; k < md.elsets[i - md.nnset].n; k++) PetscCall(DMSetLabelValue(dm, names[i], md.elsets[i - md.nnset].idx[k], 1));
    }
  }

  PetscCall(SerialFaceLabels(pb, dm, &md, names, is_cell, nnames));

  /* source ids (and tributary areas) as a field on the serial mesh, carried through distribution */
  PetscSection   idsec;
  Vec            idvec;
  const PetscInt nid = pb->narea_set ? 3 : 2;
  {
    PetscReal   *area = NULL;
    PetscInt     pStart, pEnd, vStart, vEnd, n;
    PetscScalar *a;
    PetscCall(DMPlexGetChart(dm, &pStart, &pEnd));
    PetscCall(DMPlexGetDepthStratum(dm, 0, &vStart, &vEnd));
    PetscCall(PetscSectionCreate(PETSC_COMM_SELF, &idsec));
    PetscCall(PetscSectionSetChart(idsec, pStart, pEnd));
    for (PetscInt p = pStart; p < pEnd; p++) PetscCall(PetscSectionSetDof(idsec, p, nid)); /* id, source index[, area] */
    PetscCall(PetscSectionSetUp(idsec));
    PetscCall(PetscSectionGetStorageSize(idsec, &n));
    PetscCall(VecCreateSeq(PETSC_COMM_SELF, n, &idvec));
    if (nid == 3 && pb->rank == 0) {
      PetscCall(PetscCalloc1(md.nv, &area));
      PetscCall(SerialContactAreas(pb, &md, names, is_cell, nnames, area));
    }
    PetscCall(VecGetArray(idvec, &a));
    for (PetscInt p = pStart; p < pEnd; p++) {
      PetscInt off;
      PetscCall(PetscSectionGetOffset(idsec, p, &off));
      a[off]     = (p >= vStart && p < vEnd) ? (PetscScalar)md.node_id[p - vStart] : (PetscScalar)md.elem_id[p];
      a[off + 1] = (p >= vStart && p < vEnd) ? (PetscScalar)(p - vStart) : (PetscScalar)p;
      if (nid == 3) a[off + 2] = (p >= vStart && p < vEnd) ? area[p - vStart] : 0;
    }
    PetscCall(VecRestoreArray(idvec, &a));
    PetscCall(PetscFree(area));
  }

  /* partition and distribute */
  if (pb->size > 1) {
    PetscPartitioner part;
    PetscCall(DMPlexGetPartitioner(dm, &part));
    if (opt->partition_metis) {
      PetscInt *sizes, *points = NULL;
      PetscCall(PetscCalloc1(pb->size, &sizes));
      if (pb->rank == 0) {
        PetscCall(PetscMalloc1(md.ne, &points));
        PetscCall(PetscPushErrorHandler(PetscReturnErrorHandler, NULL));
        ierr = PartitionMetis(pb, &md, names, is_cell, nnames, pb->size, sizes, points);
        PetscCall(PetscPopErrorHandler());
      }
      PetscCall(AtritoRootError(pb->comm, ierr));
      PetscCall(PetscPartitionerSetType(part, PETSCPARTITIONERSHELL));
      PetscCall(PetscPartitionerShellSetPartition(part, pb->size, sizes, points));
      /* the vertices on part boundaries: owned by a rank chosen to balance them (PETSc's shared
         point balancing) instead of always the highest-numbered rank around them */
      if (opt->partition_contact) PetscCall(DMPlexSetPartitionBalance(dm, PETSC_TRUE));
      PetscCall(PetscFree(sizes));
      PetscCall(PetscFree(points));
    } else PetscCall(PetscPartitionerSetType(part, PETSCPARTITIONERSIMPLE));
    PetscCall(DMPlexDistribute(dm, 0, &sfmig, &dmd));
  }
  if (dmd) {
    PetscSection nsec;
    Vec          nvec;
    PetscCall(PetscSectionCreate(PETSC_COMM_SELF, &nsec));
    PetscCall(VecCreate(PETSC_COMM_SELF, &nvec));
    PetscCall(DMPlexDistributeField(dm, sfmig, idsec, idvec, nsec, nvec));
    PetscCall(PetscSectionDestroy(&idsec));
    PetscCall(VecDestroy(&idvec));
    idsec = nsec;
    idvec = nvec;
    PetscCall(PetscSFDestroy(&sfmig));
    PetscCall(DMDestroy(&dm));
    dm = dmd;
  }
  pb->dm = dm;
  PetscCall(MeshDataDestroy(&md));
  PetscCall(PetscFree2(names, is_cell));

  /* per-rank arrays */
  {
    PetscInt           cStart, cEnd, vStart, vEnd;
    Vec                coords;
    const PetscScalar *xa, *ida;
    PetscCall(DMPlexGetHeightStratum(dm, 0, &cStart, &cEnd));
    PetscCall(DMPlexGetDepthStratum(dm, 0, &vStart, &vEnd));
    pb->nc     = cEnd - cStart;
    pb->nv     = vEnd - vStart;
    pb->vstart = vStart;
    PetscCall(PetscMalloc4(8 * pb->nc, &pb->cv, 3 * pb->nv, &pb->X, pb->nv, &pb->node_id, pb->nc, &pb->elem_id));
    PetscCall(PetscMalloc2(pb->nv, &pb->node_src, pb->nc, &pb->elem_src));
    if (nid == 3) PetscCall(PetscMalloc1(pb->nv, &pb->varea));
    for (PetscInt c = cStart; c < cEnd; c++) {
      const PetscInt *cone;
      PetscInt        csize;
      PetscCall(DMPlexGetConeSize(dm, c, &csize));
      PetscCheck(csize == 8, PETSC_COMM_SELF, PETSC_ERR_PLIB, "cell %" PetscInt_FMT " has %" PetscInt_FMT " vertices", c, csize);
      PetscCall(DMPlexGetCone(dm, c, &cone));
      for (PetscInt i = 0; i < 8; i++) pb->cv[8 * (c - cStart) + i] = cone[hex_plex_to_std[i]] - vStart;
    }
    PetscCall(DMGetCoordinatesLocal(dm, &coords));
    PetscCall(VecGetArrayRead(coords, &xa));
    for (PetscInt i = 0; i < 3 * pb->nv; i++) pb->X[i] = PetscRealPart(xa[i]);
    PetscCall(VecRestoreArrayRead(coords, &xa));
    PetscCall(VecGetArrayRead(idvec, &ida));
    for (PetscInt p = cStart; p < vEnd; p++) {
      PetscInt off;
      PetscCall(PetscSectionGetOffset(idsec, p, &off));
      if (p < cEnd) {
        pb->elem_id[p - cStart]  = (PetscInt)PetscRealPart(ida[off]);
        pb->elem_src[p - cStart] = (PetscInt)PetscRealPart(ida[off + 1]);
      } else if (p >= vStart) {
        pb->node_id[p - vStart]  = (PetscInt)PetscRealPart(ida[off]);
        pb->node_src[p - vStart] = (PetscInt)PetscRealPart(ida[off + 1]);
        if (pb->varea) pb->varea[p - vStart] = PetscRealPart(ida[off + 2]);
      }
    }
    PetscCall(VecRestoreArrayRead(idvec, &ida));
    PetscCall(PetscSectionDestroy(&idsec));
    PetscCall(VecDestroy(&idvec));
  }

  /* report the partition */
  {
    PetscInt *counts = NULL;
    if (pb->rank == 0) PetscCall(PetscMalloc1(pb->size, &counts));
    PetscCallMPI(MPI_Gather(&pb->nc, 1, MPIU_INT, counts, 1, MPIU_INT, 0, pb->comm));
    PetscCall(PetscPrintf(pb->comm, "mesh: %" PetscInt_FMT " vertices, %" PetscInt_FMT " hexahedra; partition %s; cells per rank:", pb->nv_global, pb->ne_global, pb->size == 1 ? "none" : (opt->partition_metis ? (opt->partition_contact ? "metis balancing cells and contact nodes" : "metis") : "simple")));
    if (pb->rank == 0)
      for (PetscMPIInt r = 0; r < pb->size; r++) PetscCall(PetscPrintf(PETSC_COMM_SELF, " %" PetscInt_FMT, counts[r]));
    PetscCall(PetscPrintf(pb->comm, "\n"));
    PetscCall(PetscFree(counts));
  }
  PetscFunctionReturn(0);
}

PetscErrorCode MeshDestroy(Mesh *pb)
{
  PetscFunctionBeginUser;
  PetscCall(PetscFree4(pb->cv, pb->X, pb->node_id, pb->elem_id));
  PetscCall(PetscFree2(pb->node_src, pb->elem_src));
  PetscCall(PetscFree(pb->varea));
  PetscCall(PetscFree(pb->vloff));
  PetscCall(PetscFree(pb->vowned));
  PetscCall(PetscFree3(pb->cgdof, pb->cperm, pb->cndof));
  PetscCall(IORowsDestroy(&pb->rv));
  PetscCall(IORowsDestroy(&pb->rc));
  PetscCall(PetscFree2(pb->vloc, pb->vrow));
  PetscCall(DMDestroy(&pb->dmr));
  PetscCall(DMDestroy(&pb->dm));
  PetscFunctionReturn(0);
}

/* copies n set names into one of the mesh's lists of at most 8 (`what` names it in the error) */
static PetscErrorCode SetNames(PetscInt n, char (*sets)[ATRITO_NAME_LEN], PetscInt *nout, char (*out)[ATRITO_NAME_LEN], const char *what)
{
  PetscFunctionBeginUser;
  PetscCheck(n <= 8, PETSC_COMM_SELF, PETSC_ERR_ARG_OUTOFRANGE, "at most 8 %s, got %" PetscInt_FMT, what, n);
  *nout = n;
  for (PetscInt i = 0; i < n; i++) PetscCall(PetscStrncpy(out[i], sets[i], ATRITO_NAME_LEN));
  PetscFunctionReturn(0);
}

PetscErrorCode MeshSetContactSets(Mesh *m, PetscInt n, char (*sets)[ATRITO_NAME_LEN])
{
  PetscFunctionBeginUser;
  PetscCall(SetNames(n, sets, &m->ncontact_set, m->contact_set, "contact sets are balanced by the partition"));
  PetscFunctionReturn(0);
}

PetscErrorCode MeshSetFaceSets(Mesh *m, PetscInt n, char (*sets)[ATRITO_NAME_LEN])
{
  PetscFunctionBeginUser;
  for (PetscInt i = 0; i < n; i++) {
    PetscBool dup = PETSC_FALSE;
    for (PetscInt j = 0; j < m->nface_set && !dup; j++) PetscCall(PetscStrcmp(m->face_set[j], sets[i], &dup));
    if (dup) continue;
    PetscCheck(m->nface_set < 16, PETSC_COMM_SELF, PETSC_ERR_ARG_OUTOFRANGE, "at most 16 sets of boundary faces (contact pairs' surfaces), got more");
    PetscCall(PetscStrncpy(m->face_set[m->nface_set++], sets[i], ATRITO_NAME_LEN));
  }
  PetscFunctionReturn(0);
}

PetscErrorCode MeshGetBoundaryFaces(const Mesh *m, const char *set, PetscInt *nf, PetscInt **fv, PetscInt **fc)
{
  char     lname[ATRITO_NAME_LEN + 16];
  DMLabel  label;
  PetscInt cStart, cEnd, n = 0;

  PetscFunctionBeginUser;
  FaceLabelName(set, lname);
  PetscCall(DMGetLabel(m->dm, lname, &label));
  PetscCheck(label, PETSC_COMM_SELF, PETSC_ERR_ARG_WRONGSTATE, "the boundary faces of set '%s' were not asked for before the mesh was made (MeshSetFaceSets)", set);
  PetscCall(DMPlexGetHeightStratum(m->dm, 0, &cStart, &cEnd));
  for (int pass = 0; pass < 2; pass++) {
    if (pass) {
      PetscCall(PetscMalloc1(4 * n + 1, fv));
      if (fc) PetscCall(PetscMalloc1(n + 1, fc));
    }
    n = 0;
    for (PetscInt c = cStart; c < cEnd; c++) {
      PetscInt v;
      PetscCall(DMLabelGetValue(label, c, &v));
      if (v <= 0) continue;
      for (int k = 0; k < 6; k++) {
        if (!((v >> k) & 1)) continue;
        if (pass) {
          for (int j = 0; j < 4; j++) (*fv)[4 * n + j] = m->cv[8 * (c - cStart) + hexface[k][j]];
          if (fc) (*fc)[n] = 6 * (c - cStart) + k;
        }
        n++;
      }
    }
  }
  *nf = n;
  PetscFunctionReturn(0);
}

PetscErrorCode MeshSetAreaSets(Mesh *m, PetscInt n, char (*sets)[ATRITO_NAME_LEN])
{
  PetscFunctionBeginUser;
  PetscCall(SetNames(n, sets, &m->narea_set, m->area_set, "sets carry tributary areas"));
  PetscFunctionReturn(0);
}

/* Global dof of each displacement component of local vertex v (owned or not), -1 where the
   component is constrained: the global section numbers the unconstrained components in order. */
PetscErrorCode MeshVertexDofs(const Mesh *pb, PetscInt v, PetscInt idx[3])
{
  PetscSection    ls, gs;
  PetscInt        goff, cdof, skipped = 0;
  const PetscInt *cidx;

  PetscFunctionBeginUser;
  PetscCall(DMGetLocalSection(pb->dm, &ls));
  PetscCall(DMGetGlobalSection(pb->dm, &gs));
  PetscCall(PetscSectionGetOffset(gs, pb->vstart + v, &goff));
  if (goff < 0) goff = -(goff + 1);
  PetscCall(PetscSectionGetConstraintDof(ls, pb->vstart + v, &cdof));
  PetscCall(PetscSectionGetConstraintIndices(ls, pb->vstart + v, &cidx));
  for (PetscInt c = 0; c < 3; c++) {
    PetscBool con = PETSC_FALSE;
    for (PetscInt j = 0; j < cdof; j++) con = con || cidx[j] == c;
    if (con) {
      idx[c] = -1;
      skipped++;
    } else idx[c] = goff + c - skipped;
  }
  PetscFunctionReturn(0);
}
