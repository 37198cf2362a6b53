/* Meshed tool surfaces: the readers (STL ASCII and binary, Gmsh .msh 2.2 and 4.1 ASCII, Abaqus
   .inp surfaces), read on rank 0 and broadcast, and the construction of a "facets" patch: the
   checks (empty surface, coordinates that are not numbers, zero-area facets, inconsistent
   orientation, non-manifold edges when smoothing), the bounding-volume hierarchy and the corner
   normals (doc/notes/tools-log.md "Meshed surfaces"). Every error is one line naming the file and the
   entity. */
#include "facets.h"

#include <ctype.h>
#include <stdarg.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "options.h"

/* ------------------------------------------------------------------ growable arrays */

typedef struct {
  void  *a;
  size_t n, cap, sz;
} Arr;

static int ArrPush(Arr *r, const void *x)
{
  if (r->n == r->cap) {
    size_t c = r->cap ? 2 * r->cap : 1024;
    void  *b = realloc(r->a, c * r->sz);
    if (!b) return 1;
    r->a   = b;
    r->cap = c;
  }
  memcpy((char *)r->a + r->n * r->sz, x, r->sz);
  r->n++;
  return 0;
}

/* the reader's state: the error (first one wins), the vertices, the polygons (3 or 4 vertex
   indices into V, -1 for a triangle's fourth) and the file ids */
typedef struct {
  char   err[512];
  Arr    V, P, id;
  const char *path;
} Reader;

static void Fail(Reader *r, const char *fmt, ...)
{
  va_list ap;
  if (r->err[0]) return;
  va_start(ap, fmt);
  char msg[400];
  vsnprintf(msg, sizeof(msg), fmt, ap);
  va_end(ap);
  snprintf(r->err, sizeof(r->err), "tool file %s: %s", r->path, msg);
}

static void AddPoly(Reader *r, int nvert, const int *v, int id)
{
  int q[4] = {v[0], v[1], v[2], nvert == 4 ? v[3] : -1};
  if (ArrPush(&r->P, q) || ArrPush(&r->id, &id)) Fail(r, "out of memory");
}

/* ------------------------------------------------------------------ STL */

typedef struct {
  double x[3];
  int    k;
} SortV;

static int CmpV(const void *a, const void *b)
{
  const SortV *p = a, *q = b;
  for (int i = 0; i < 3; i++) {
    if (p->x[i] < q->x[i]) return -1;
    if (p->x[i] > q->x[i]) return 1;
  }
  return p->k - q->k;
}

/* triangle soup (3 nt corners) -> shared vertices (equal coordinates merged) */
static void StlMerge(Reader *r, const double *X, int nt)
{
  SortV *s   = malloc((size_t)3 * nt * sizeof(*s));
  int   *map = malloc((size_t)3 * nt * sizeof(int));
  if (!s || !map) {
    free(s);
    free(map);
    Fail(r, "out of memory");
    return;
  }
  for (int k = 0; k < 3 * nt; k++) {
    memcpy(s[k].x, &X[3 * k], sizeof(s[k].x));
    s[k].k = k;
  }
  qsort(s, (size_t)3 * nt, sizeof(*s), CmpV);
  int nv = -1;
  for (int k = 0; k < 3 * nt; k++) {
    if (k == 0 || memcmp(s[k].x, s[k - 1].x, sizeof(s[k].x))) {
      nv++;
      if (ArrPush(&r->V, s[k].x)) Fail(r, "out of memory");
    }
    map[s[k].k] = nv;
  }
  for (int t = 0; t < nt; t++) AddPoly(r, 3, &map[3 * t], t + 1);
  free(s);
  free(map);
}

static void ReadStl(Reader *r, FILE *fp)
{
  unsigned char hdr[84];
  long          size;
  fseek(fp, 0, SEEK_END);
  size = ftell(fp);
  fseek(fp, 0, SEEK_SET);
  size_t got = fread(hdr, 1, 84, fp);
  if (got == 84) {
    uint32_t n;
    memcpy(&n, hdr + 80, 4);
    if ((long)84 + 50L * (long)n == size) { /* binary */
      double *X = malloc((size_t)9 * (n ? n : 1) * sizeof(double));
      if (!X) return Fail(r, "out of memory");
      for (uint32_t t = 0; t < n; t++) {
        unsigned char b[50];
        float         f[12];
        if (fread(b, 1, 50, fp) != 50) {
          free(X);
          return Fail(r, "truncated binary STL at facet %u", t + 1);
        }
        memcpy(f, b, 48);
        for (int i = 0; i < 9; i++) X[9 * t + i] = f[3 + i];
      }
      StlMerge(r, X, (int)n);
      free(X);
      return;
    }
  }
  fseek(fp, 0, SEEK_SET);
  { /* ASCII: "vertex x y z" three times per facet */
    char   line[1024], w[64];
    Arr    X  = {NULL, 0, 0, 3 * sizeof(double)};
    long   ln = 0, nvtx = 0;
    int    solid = 0;
    while (fgets(line, sizeof(line), fp)) {
      ln++;
      if (sscanf(line, "%63s", w) != 1) continue;
      if (!solid) {
        if (strcmp(w, "solid")) {
          free(X.a);
          return Fail(r, "not an STL file (neither binary nor starting with 'solid')");
        }
        solid = 1;
        continue;
      }
      if (!strcmp(w, "vertex")) {
        double x[3];
        char  *s = strstr(line, "vertex") + 6, *e;
        for (int i = 0; i < 3; i++) {
          x[i] = strtod(s, &e);
          if (e == s) {
            free(X.a);
            return Fail(r, "line %ld: '%s' is not a valid vertex (facet %ld)", ln, strtok(line, "\r\n"), nvtx / 3 + 1);
          }
          s = e;
        }
        if (ArrPush(&X, x)) Fail(r, "out of memory");
        nvtx++;
      } else if (!strcmp(w, "endloop") && nvtx % 3) {
        free(X.a);
        return Fail(r, "line %ld: facet %ld has %ld vertices, not 3", ln, nvtx / 3 + 1, nvtx % 3);
      }
    }
    if (!solid) return Fail(r, "empty file");
    StlMerge(r, (double *)X.a, (int)(nvtx / 3));
    free(X.a);
  }
}

/* ------------------------------------------------------------------ node ids -> indices */

typedef struct {
  int *m;
  long n;
} IdMap;

static int IdSet(IdMap *im, long id, int k)
{
  if (id < 0 || id > 100000000) return 1;
  if (id >= im->n) {
    long n = im->n ? im->n : 1024;
    while (n <= id) n *= 2;
    int *b = realloc(im->m, (size_t)n * sizeof(int));
    if (!b) return 1;
    for (long i = im->n; i < n; i++) b[i] = -1;
    im->m = b;
    im->n = n;
  }
  im->m[id] = k;
  return 0;
}
static int IdGet(const IdMap *im, long id) { return id >= 0 && id < im->n ? im->m[id] : -1; }

/* ------------------------------------------------------------------ Gmsh */

static int NextLine(FILE *fp, char *line, int len, long *ln)
{
  while (fgets(line, len, fp)) {
    (*ln)++;
    const char *s = line;
    while (*s && isspace((unsigned char)*s)) s++;
    if (*s) return 1;
  }
  return 0;
}

static void ReadMsh(Reader *r, FILE *fp, const char group[])
{
  char   line[4096];
  long   ln = 0;
  double version = 0;
  int    gtag = -1, want = group && group[0];
  IdMap  nodes = {NULL, 0};
  Arr    ent   = {NULL, 0, 0, 2 * sizeof(int)}; /* v4: (surface tag, physical tag) pairs */
  while (!r->err[0] && NextLine(fp, line, sizeof(line), &ln)) {
    if (!strncmp(line, "$MeshFormat", 11)) {
      int ft = 0, ds = 0;
      if (!NextLine(fp, line, sizeof(line), &ln) || sscanf(line, "%lf %d %d", &version, &ft, &ds) != 3) Fail(r, "line %ld: bad $MeshFormat", ln);
      else if (ft != 0) Fail(r, "binary .msh files are not supported (save as ASCII)");
      else if (!(version >= 2.0 && version < 3.0) && !(version >= 4.0 && version < 5.0)) Fail(r, "unsupported .msh version %g (2.2 or 4.1)", version);
    } else if (!strncmp(line, "$PhysicalNames", 14)) {
      int n = 0;
      if (!NextLine(fp, line, sizeof(line), &ln) || sscanf(line, "%d", &n) != 1) Fail(r, "line %ld: bad $PhysicalNames", ln);
      for (int k = 0; k < n && !r->err[0]; k++) {
        int  dim, tag;
        char name[256];
        if (!NextLine(fp, line, sizeof(line), &ln) || sscanf(line, "%d %d \"%255[^\"]\"", &dim, &tag, name) != 3) Fail(r, "line %ld: bad physical name", ln);
        else if (want && dim == 2 && !strcmp(name, group)) gtag = tag;
      }
    } else if (!strncmp(line, "$Entities", 9)) {
      long n[4];
      if (!NextLine(fp, line, sizeof(line), &ln) || sscanf(line, "%ld %ld %ld %ld", &n[0], &n[1], &n[2], &n[3]) != 4) Fail(r, "line %ld: bad $Entities", ln);
      for (int d = 0; d < 4 && !r->err[0]; d++)
        for (long k = 0; k < n[d] && !r->err[0]; k++) {
          char *s = line, *e;
          if (!NextLine(fp, line, sizeof(line), &ln)) Fail(r, "line %ld: truncated $Entities", ln);
          const long tag = strtol(s, &e, 10);
          s = e;
          for (int i = 0; i < (d == 0 ? 3 : 6); i++) {
            strtod(s, &e);
            s = e;
          }
          const long np = strtol(s, &e, 10);
          s = e;
          for (long i = 0; i < np; i++) {
            const int pair[2] = {(int)tag, (int)strtol(s, &e, 10)};
            s                 = e;
            if (d == 2 && ArrPush(&ent, pair)) Fail(r, "out of memory");
          }
        }
    } else if (!strncmp(line, "$Nodes", 6)) {
      if (version < 4.0) {
        long n = 0;
        if (!NextLine(fp, line, sizeof(line), &ln) || sscanf(line, "%ld", &n) != 1) Fail(r, "line %ld: bad $Nodes", ln);
        for (long k = 0; k < n && !r->err[0]; k++) {
          long   id;
          double x[3];
          if (!NextLine(fp, line, sizeof(line), &ln) || sscanf(line, "%ld %lf %lf %lf", &id, &x[0], &x[1], &x[2]) != 4) Fail(r, "line %ld: bad node", ln);
          else if (IdSet(&nodes, id, (int)r->V.n) || ArrPush(&r->V, x)) Fail(r, "line %ld: bad node id %ld", ln, id);
        }
      } else {
        long nb = 0, nn, mn, mx;
        if (!NextLine(fp, line, sizeof(line), &ln) || sscanf(line, "%ld %ld %ld %ld", &nb, &nn, &mn, &mx) != 4) Fail(r, "line %ld: bad $Nodes", ln);
        for (long b = 0; b < nb && !r->err[0]; b++) {
          int  ed, et, par;
          long cnt;
          if (!NextLine(fp, line, sizeof(line), &ln) || sscanf(line, "%d %d %d %ld", &ed, &et, &par, &cnt) != 4) {
            Fail(r, "line %ld: bad node block", ln);
            break;
          }
          long *ids = malloc((size_t)(cnt ? cnt : 1) * sizeof(long));
          for (long k = 0; k < cnt && !r->err[0]; k++)
            if (!NextLine(fp, line, sizeof(line), &ln) || sscanf(line, "%ld", &ids[k]) != 1) Fail(r, "line %ld: bad node tag", ln);
          for (long k = 0; k < cnt && !r->err[0]; k++) {
            double x[3];
            if (!NextLine(fp, line, sizeof(line), &ln) || sscanf(line, "%lf %lf %lf", &x[0], &x[1], &x[2]) != 3) Fail(r, "line %ld: bad node coordinates", ln);
            else if (IdSet(&nodes, ids[k], (int)r->V.n) || ArrPush(&r->V, x)) Fail(r, "line %ld: bad node id %ld", ln, ids[k]);
          }
          free(ids);
        }
      }
    } else if (!strncmp(line, "$Elements", 9)) {
      if (want && gtag < 0) {
        char *e;
        gtag = (int)strtol(group, &e, 10);
        if (*e || gtag <= 0) {
          Fail(r, "no physical surface named '%s'", group);
          break;
        }
      }
      long nb = 0, ne, mn, mx;
      if (version < 4.0) {
        if (!NextLine(fp, line, sizeof(line), &ln) || sscanf(line, "%ld", &ne) != 1) Fail(r, "line %ld: bad $Elements", ln);
        for (long k = 0; k < ne && !r->err[0]; k++) {
          long  id, v[64];
          int   type, nt, nv = 0, phys = 0;
          char *s = line, *e;
          if (!NextLine(fp, line, sizeof(line), &ln) || sscanf(line, "%ld %d %d", &id, &type, &nt) != 3) {
            Fail(r, "line %ld: bad element", ln);
            break;
          }
          for (int i = 0; i < 3; i++) {
            strtol(s, &e, 10);
            s = e;
          }
          for (int i = 0; i < nt; i++) {
            const long t = strtol(s, &e, 10);
            s            = e;
            if (i == 0) phys = (int)t;
          }
          while (nv < 64) {
            v[nv] = strtol(s, &e, 10);
            if (e == s) break;
            s = e;
            nv++;
          }
          if (type == 15 || type == 1 || type == 8 || (type >= 4 && type <= 7) || (type >= 11 && type <= 14) || type == 17 || type == 18 || type == 19) continue; /* points, lines, volumes */
          if (type != 2 && type != 3) {
            Fail(r, "element %ld: unknown element type %d (3-node triangles and 4-node quadrangles only)", id, type);
            break;
          }
          if (want && phys != gtag) continue;
          int q[4], nq = type == 2 ? 3 : 4;
          if (nv != nq) {
            Fail(r, "line %ld: element %ld has %d nodes, not %d", ln, id, nv, nq);
            break;
          }
          for (int i = 0; i < nq; i++)
            if ((q[i] = IdGet(&nodes, v[i])) < 0) Fail(r, "element %ld references undefined node %ld", id, v[i]);
          AddPoly(r, nq, q, (int)id);
        }
      } else {
        if (!NextLine(fp, line, sizeof(line), &ln) || sscanf(line, "%ld %ld %ld %ld", &nb, &ne, &mn, &mx) != 4) Fail(r, "line %ld: bad $Elements", ln);
        for (long b = 0; b < nb && !r->err[0]; b++) {
          int  ed, et, type, take = 1;
          long cnt;
          if (!NextLine(fp, line, sizeof(line), &ln) || sscanf(line, "%d %d %d %ld", &ed, &et, &type, &cnt) != 4) {
            Fail(r, "line %ld: bad element block", ln);
            break;
          }
          if (ed == 2 && type != 2 && type != 3) {
            Fail(r, "element block of surface %d: unknown element type %d (3-node triangles and 4-node quadrangles only)", et, type);
            break;
          }
          if (ed != 2) take = 0;
          if (take && want) {
            take = 0;
            for (size_t i = 0; i < ent.n; i++)
              if (((int *)ent.a)[2 * i] == et && ((int *)ent.a)[2 * i + 1] == gtag) take = 1;
          }
          for (long k = 0; k < cnt && !r->err[0]; k++) {
            if (!NextLine(fp, line, sizeof(line), &ln)) {
              Fail(r, "line %ld: truncated element block", ln);
              break;
            }
            if (!take) continue;
            char *s = line, *e;
            long  id = strtol(s, &e, 10), v;
            int   q[4], nq = type == 2 ? 3 : 4;
            s = e;
            for (int i = 0; i < nq; i++) {
              v = strtol(s, &e, 10);
              if (e == s) {
                Fail(r, "line %ld: element %ld has fewer than %d nodes", ln, id, nq);
                break;
              }
              s = e;
              if ((q[i] = IdGet(&nodes, v)) < 0) Fail(r, "element %ld references undefined node %ld", id, v);
            }
            if (!r->err[0]) AddPoly(r, nq, q, (int)id);
          }
        }
      }
    }
  }
  if (!r->err[0] && version == 0) Fail(r, "not a Gmsh file (no $MeshFormat)");
  if (!r->err[0] && want && gtag < 0 && r->P.n == 0) Fail(r, "no physical surface named '%s'", group);
  free(nodes.m);
  free(ent.a);
}

/* ------------------------------------------------------------------ Abaqus */

typedef struct {
  char name[80];
  Arr  ids; /* long */
} Set;

static int KeyValue(const char *line, const char *key, char *val, int len)
{
  char up[1024];
  int  i;
  for (i = 0; line[i] && i < 1023; i++) up[i] = (char)toupper((unsigned char)line[i]);
  up[i]   = 0;
  char *s = strstr(up, key);
  if (!s) return 0;
  s += strlen(key);
  while (*s == ' ') s++;
  if (*s != '=') return 0;
  s++;
  while (*s == ' ') s++;
  const char *o = line + (s - up);
  for (i = 0; i < len - 1 && o[i] && o[i] != ',' && o[i] != '\r' && o[i] != '\n' && o[i] != ' '; i++) val[i] = o[i];
  val[i] = 0;
  return 1;
}

static int CaseEq(const char *a, const char *b)
{
  for (; *a && *b; a++, b++)
    if (toupper((unsigned char)*a) != toupper((unsigned char)*b)) return 0;
  return *a == *b;
}

/* C3D8 faces S1..S6 (Abaqus: 1-2-3-4, 5-8-7-6, 1-5-6-2, 2-6-7-3, 3-7-8-4, 4-8-5-1, right-handed
   into the element), here reversed: wound outwards, out of the solid */
static const int Hex8Face[6][4] = {
  {3, 2, 1, 0},
  {5, 6, 7, 4},
  {1, 5, 4, 0},
  {2, 6, 5, 1},
  {3, 7, 6, 2},
  {0, 4, 7, 3}
};

static void ReadInp(Reader *r, FILE *fp, const char group[])
{
  char  line[4096], val[256], elset[80] = "";
  long  ln   = 0;
  int   mode = 0, etype = 0; /* mode: 1 node, 2 element, 3 elset, 4 surface; etype: 3, 4 surface, 8 C3D8 */
  int   gen  = 0, want = group && group[0];
  IdMap nodes = {NULL, 0}, elem = {NULL, 0};
  Arr   E     = {NULL, 0, 0, 10 * sizeof(long)}; /* id, type, 8 nodes */
  Arr   sets  = {NULL, 0, 0, sizeof(Set)};
  Arr   faces = {NULL, 0, 0, 2 * sizeof(long)}; /* element id, face; of the surfaces selected */
  int   nsurf = 0, found = 0, cursurf = 0;
  Set  *cur   = NULL;
  while (!r->err[0] && fgets(line, sizeof(line), fp)) {
    ln++;
    if (line[0] == '*' && line[1] == '*') continue;
    if (line[0] == '*') {
      char kw[64] = "";
      int  i;
      for (i = 0; line[1 + i] && line[1 + i] != ',' && line[1 + i] != '\n' && line[1 + i] != '\r' && i < 63; i++) kw[i] = (char)toupper((unsigned char)line[1 + i]);
      kw[i] = 0;
      while (i > 0 && kw[i - 1] == ' ') kw[--i] = 0;
      mode = 0;
      cur  = NULL;
      if (!strcmp(kw, "NODE")) mode = 1;
      else if (!strcmp(kw, "ELEMENT")) {
        if (!KeyValue(line, "TYPE", val, sizeof(val))) {
          Fail(r, "line %ld: *ELEMENT without TYPE", ln);
          break;
        }
        if (CaseEq(val, "R3D3") || CaseEq(val, "S3") || CaseEq(val, "M3D3") || CaseEq(val, "S3R")) etype = 3;
        else if (CaseEq(val, "R3D4") || CaseEq(val, "S4") || CaseEq(val, "S4R") || CaseEq(val, "M3D4") || CaseEq(val, "M3D4R")) etype = 4;
        else if (CaseEq(val, "C3D8") || CaseEq(val, "C3D8R") || CaseEq(val, "C3D8I")) etype = 8;
        else {
          Fail(r, "line %ld: unknown element type %s (R3D3, R3D4, S3, S4, S4R, M3D3, M3D4 or C3D8)", ln, val);
          break;
        }
        mode = 2;
        if (KeyValue(line, "ELSET", elset, sizeof(elset))) {
          Set s = {{0}, {NULL, 0, 0, sizeof(long)}};
          snprintf(s.name, sizeof(s.name), "%s", elset);
          ArrPush(&sets, &s);
          cur = &((Set *)sets.a)[sets.n - 1];
        }
      } else if (!strcmp(kw, "ELSET")) {
        Set s = {{0}, {NULL, 0, 0, sizeof(long)}};
        KeyValue(line, "ELSET", s.name, sizeof(s.name));
        gen = strstr(line, "enerate") || strstr(line, "ENERATE");
        ArrPush(&sets, &s);
        cur  = &((Set *)sets.a)[sets.n - 1];
        mode = 3;
      } else if (!strcmp(kw, "SURFACE")) {
        char name[80] = "";
        KeyValue(line, "NAME", name, sizeof(name));
        nsurf++;
        cursurf = !want || CaseEq(name, group);
        found |= want && cursurf;
        mode = 4;
      } else if (!strcmp(kw, "RIGID BODY")) {
        if (!want && KeyValue(line, "ELSET", val, sizeof(val))) { /* the rigid body's elements */
        }
      }
      continue;
    }
    if (mode == 1) {
      long   id;
      double x[3];
      if (sscanf(line, "%ld , %lf , %lf , %lf", &id, &x[0], &x[1], &x[2]) != 4) Fail(r, "line %ld: bad node line", ln);
      else if (IdSet(&nodes, id, (int)r->V.n) || ArrPush(&r->V, x)) Fail(r, "line %ld: bad node id %ld", ln, id);
    } else if (mode == 2) {
      long  e[10] = {0}, v;
      char *s     = line, *t;
      int   n     = 0;
      e[1]        = etype;
      e[0]        = strtol(s, &t, 10);
      if (t == s) continue;
      s = t;
      while (n < etype) {
        while (*s == ',' || *s == ' ') s++;
        v = strtol(s, &t, 10);
        if (t == s) break;
        e[2 + n++] = v;
        s          = t;
      }
      if (n != etype) {
        Fail(r, "line %ld: element %ld has %d nodes, not %d", ln, e[0], n, etype);
        break;
      }
      IdSet(&elem, e[0], (int)E.n);
      ArrPush(&E, e);
      if (cur) ArrPush(&cur->ids, &e[0]);
    } else if (mode == 3 && cur) {
      char *s = line, *t;
      long  v[3];
      int   n = 0;
      for (;;) {
        while (*s == ',' || *s == ' ') s++;
        const long x = strtol(s, &t, 10);
        if (t == s) break;
        if (gen && n < 3) v[n++] = x;
        else ArrPush(&cur->ids, &x);
        s = t;
      }
      if (gen && n >= 2)
        for (long x = v[0]; x <= v[1]; x += (n == 3 && v[2] > 0 ? v[2] : 1)) ArrPush(&cur->ids, &x);
    } else if (mode == 4 && cursurf) {
      char name[256], face[16];
      if (sscanf(line, " %255[^, ] , %15s", name, face) != 2) continue;
      /* S1..S6 (F1..F6); SPOS and SNEG (coded 7 and 8): the positive and negative side of a surface element */
      const int fn = CaseEq(face, "SPOS") ? 7 : CaseEq(face, "SNEG") ? 8 : (toupper((unsigned char)face[0]) == 'S' || toupper((unsigned char)face[0]) == 'F') ? atoi(face + 1) : 0;
      if (fn < 1 || fn > 8) {
        Fail(r, "line %ld: face '%s' (S1 to S6, SPOS or SNEG)", ln, face);
        break;
      }
      char *t;
      const long id = strtol(name, &t, 10);
      if (!*t) {
        const long pr[2] = {id, fn};
        ArrPush(&faces, pr);
      } else {
        int hit = 0;
        for (size_t k = 0; k < sets.n; k++)
          if (CaseEq(((Set *)sets.a)[k].name, name)) {
            hit = 1;
            for (size_t j = 0; j < ((Set *)sets.a)[k].ids.n; j++) {
              const long pr[2] = {((long *)((Set *)sets.a)[k].ids.a)[j], fn};
              ArrPush(&faces, pr);
            }
          }
        if (!hit) Fail(r, "line %ld: surface names unknown element set '%s'", ln, name);
      }
    }
  }
  if (!r->err[0]) {
    const long *Ea = (const long *)E.a;
    if (faces.n) { /* the selected *SURFACE faces */
      for (size_t k = 0; k < faces.n && !r->err[0]; k++) {
        const long id = ((long *)faces.a)[2 * k], fn = ((long *)faces.a)[2 * k + 1];
        const int  j  = IdGet(&elem, id);
        if (j < 0) {
          Fail(r, "surface references undefined element %ld", id);
          break;
        }
        const long *e = &Ea[10 * j];
        int         q[4];
        if (e[1] == 8 && fn > 6) {
          Fail(r, "surface face %s of solid element %ld (S1 to S6)", fn == 7 ? "SPOS" : "SNEG", id);
          break;
        }
        if (e[1] == 8) {
          for (int i = 0; i < 4; i++)
            if ((q[i] = IdGet(&nodes, e[2 + Hex8Face[fn - 1][i]])) < 0) Fail(r, "element %ld references undefined node %ld", id, e[2 + Hex8Face[fn - 1][i]]);
          if (!r->err[0]) AddPoly(r, 4, q, (int)id);
        } else { /* a surface element: as wound (SPOS, S1), or reversed (SNEG, S2) */
          for (int i = 0; i < e[1]; i++)
            if ((q[i] = IdGet(&nodes, e[2 + i])) < 0) Fail(r, "element %ld references undefined node %ld", id, e[2 + i]);
          if (fn == 2 || fn == 8) {
            const int t = q[1];
            q[1]        = q[e[1] - 1];
            q[e[1] - 1] = t;
          }
          if (!r->err[0]) AddPoly(r, (int)e[1], q, (int)id);
        }
      }
    } else if (want && nsurf && !found) {
      int hit = 0; /* an element set of surface elements */
      for (size_t k = 0; k < sets.n && !r->err[0]; k++)
        if (CaseEq(((Set *)sets.a)[k].name, group)) {
          hit = 1;
          for (size_t j = 0; j < ((Set *)sets.a)[k].ids.n; j++) {
            const long id = ((long *)((Set *)sets.a)[k].ids.a)[j];
            const int  i  = IdGet(&elem, id);
            if (i < 0 || Ea[10 * i + 1] == 8) continue;
            int q[4];
            for (int c = 0; c < Ea[10 * i + 1]; c++) q[c] = IdGet(&nodes, Ea[10 * i + 2 + c]);
            AddPoly(r, (int)Ea[10 * i + 1], q, (int)id);
          }
        }
      if (!hit) Fail(r, "no surface or element set named '%s'", group);
    } else {
      int hitset = 0;
      if (want)
        for (size_t k = 0; k < sets.n; k++)
          if (CaseEq(((Set *)sets.a)[k].name, group)) hitset = 1;
      if (want && !hitset) Fail(r, "no surface or element set named '%s'", group);
      for (size_t i = 0; i < E.n && !r->err[0]; i++) { /* the surface elements (of the set) */
        const long *e = &Ea[10 * i];
        if (e[1] == 8) continue;
        if (want) {
          int in = 0;
          for (size_t k = 0; k < sets.n && !in; k++)
            if (CaseEq(((Set *)sets.a)[k].name, group))
              for (size_t j = 0; j < ((Set *)sets.a)[k].ids.n && !in; j++) in = ((long *)((Set *)sets.a)[k].ids.a)[j] == e[0];
          if (!in) continue;
        }
        int q[4];
        for (int c = 0; c < e[1]; c++)
          if ((q[c] = IdGet(&nodes, e[2 + c])) < 0) Fail(r, "element %ld references undefined node %ld", e[0], e[2 + c]);
        if (!r->err[0]) AddPoly(r, (int)e[1], q, (int)e[0]);
      }
    }
  }
  for (size_t k = 0; k < sets.n; k++) free(((Set *)sets.a)[k].ids.a);
  free(sets.a);
  free(faces.a);
  free(E.a);
  free(nodes.m);
  free(elem.m);
}

/* ------------------------------------------------------------------ reading */

void FacetsFormat(const char path[], const char format[], char out[16])
{
  const char *dot = strrchr(path, '.');
  out[0]          = 0;
  if (format && format[0]) snprintf(out, 16, "%s", format);
  else if (dot) snprintf(out, 16, "%s", dot + 1);
  for (char *c = out; *c; c++) *c = (char)tolower((unsigned char)*c);
}

PetscErrorCode FacetsRead(MPI_Comm comm, const char path[], const char format[], const char group[], FacetsRaw *raw)
{
  PetscMPIInt rank;
  Reader      r = {"", {NULL, 0, 0, 3 * sizeof(double)}, {NULL, 0, 0, 4 * sizeof(int)}, {NULL, 0, 0, sizeof(int)}, path};
  char        fmt[16];
  int         n[2] = {0, 0};

  PetscFunctionBeginUser;
  PetscCallMPI(MPI_Comm_rank(comm, &rank));
  memset(raw, 0, sizeof(*raw));
  FacetsFormat(path, format, fmt);
  if (rank == 0) {
    FILE *fp = fopen(path, "rb");
    if (!fp) snprintf(r.err, sizeof(r.err), "cannot open tool file '%s'", path);
    else {
      if (!strcmp(fmt, "stl")) ReadStl(&r, fp);
      else if (!strcmp(fmt, "msh")) ReadMsh(&r, fp, group);
      else if (!strcmp(fmt, "inp")) ReadInp(&r, fp, group);
      else Fail(&r, "unknown format '%s' (stl, msh, inp or tool)", fmt);
      fclose(fp);
    }
    if (!r.err[0] && r.P.n == 0) Fail(&r, group && group[0] ? "empty surface: no triangles or quadrangles in '%s'" : "empty surface: no triangles or quadrangles%s", group && group[0] ? group : "");
    if (!r.err[0]) { /* quadrangles split in two along the diagonal from their first corner, or along the other one where it is shorter by more than 10 % */
      Arr          T = {NULL, 0, 0, 3 * sizeof(int)}, id = {NULL, 0, 0, sizeof(int)};
      const double *X = (const double *)r.V.a;
      for (size_t k = 0; k < r.P.n; k++) {
        const int *q = &((int *)r.P.a)[4 * k], fid = ((int *)r.id.a)[k];
        if (q[3] < 0) {
          ArrPush(&T, q);
          ArrPush(&id, &fid);
        } else {
          int t1[3], t2[3];
          if (Dist2(&X[3 * q[1]], &X[3 * q[3]]) >= 0.81 * Dist2(&X[3 * q[0]], &X[3 * q[2]])) { /* q0-q2 unless q1-q3 is shorter by 10 % (consistent on a structured grid) */
            t1[0] = q[0], t1[1] = q[1], t1[2] = q[2];
            t2[0] = q[0], t2[1] = q[2], t2[2] = q[3];
          } else {
            t1[0] = q[0], t1[1] = q[1], t1[2] = q[3];
            t2[0] = q[1], t2[1] = q[2], t2[2] = q[3];
          }
          ArrPush(&T, t1);
          ArrPush(&T, t2);
          ArrPush(&id, &fid);
          ArrPush(&id, &fid);
        }
      }
      free(r.P.a);
      free(r.id.a);
      r.P  = T;
      r.id = id;
      n[0] = (int)r.V.n;
      n[1] = (int)r.P.n;
    }
  }
  PetscCallMPI(MPI_Bcast(r.err, sizeof(r.err), MPI_CHAR, 0, comm));
  if (r.err[0]) {
    free(r.V.a);
    free(r.P.a);
    free(r.id.a);
    SETERRQ(comm, PETSC_ERR_FILE_UNEXPECTED, "%s", r.err);
  }
  PetscCallMPI(MPI_Bcast(n, 2, MPI_INT, 0, comm));
  raw->nv = n[0];
  raw->nf = n[1];
  PetscCall(PetscMalloc1(3 * (size_t)raw->nv, &raw->V));
  PetscCall(PetscMalloc1(3 * (size_t)raw->nf, &raw->F));
  PetscCall(PetscMalloc1((size_t)raw->nf, &raw->fid));
  if (rank == 0) {
    memcpy(raw->V, r.V.a, 3 * (size_t)raw->nv * sizeof(double));
    memcpy(raw->F, r.P.a, 3 * (size_t)raw->nf * sizeof(int));
    memcpy(raw->fid, r.id.a, (size_t)raw->nf * sizeof(int));
  }
  free(r.V.a);
  free(r.P.a);
  free(r.id.a);
  PetscCallMPI(MPI_Bcast(raw->V, 3 * raw->nv, MPI_DOUBLE, 0, comm));
  PetscCallMPI(MPI_Bcast(raw->F, 3 * raw->nf, MPI_INT, 0, comm));
  PetscCallMPI(MPI_Bcast(raw->fid, raw->nf, MPI_INT, 0, comm));
  PetscFunctionReturn(0);
}

/* ------------------------------------------------------------------ construction */

typedef struct {
  int a, b, f, e; /* a < b: the edge's vertices; facet f, its edge e; */
  int fwd;        /* the facet runs a -> b */
} Edge;

static int CmpE(const void *x, const void *y)
{
  const Edge *p = x, *q = y;
  if (p->a != q->a) return p->a < q->a ? -1 : 1;
  if (p->b != q->b) return p->b < q->b ? -1 : 1;
  return p->f != q->f ? (p->f < q->f ? -1 : 1) : p->e - q->e;
}

typedef struct {
  const double *c; /* centroids */
  int          *perm;
  FacetsNode   *node;
  int           nnode;
  const double *V;
  const int    *F;
} Builder;

static void Select(const double *c, int *perm, int lo, int hi, int k, int ax)
{ /* quickselect: perm[lo..hi) ordered so that perm[k] has the k-th coordinate */
  while (hi - lo > 1) {
    const double pv = c[3 * perm[(lo + hi) / 2] + ax];
    int          i = lo, j = hi - 1;
    while (i <= j) {
      while (c[3 * perm[i] + ax] < pv) i++;
      while (c[3 * perm[j] + ax] > pv) j--;
      if (i <= j) {
        const int t = perm[i];
        perm[i++]   = perm[j];
        perm[j--]   = t;
      }
    }
    if (k <= j) hi = j + 1;
    else if (k >= i) lo = i;
    else return;
  }
}

/* The oriented box of facets perm[lo..hi): n the sum of the facets' area vectors normalised (any
   unit vector when they cancel, as for a closed surface: the box is then valid, only not thin), t1
   the coordinate axis least along n made perpendicular to it; both rounded to float, and the
   extents computed with the rounded axes (FacetsNodeAxes), so that every vertex, and with it every
   point of the plane triangles (convex combinations), lies inside [olo, ohi] along them */
static void OrientedBox(Builder *B, FacetsNode *n, int lo, int hi)
{
  double s[3] = {0, 0, 0}, a[3][3], e[3] = {0, 0, 0}, len, t[3], elo[3] = {HUGE_VAL, HUGE_VAL, HUGE_VAL}, ehi[3] = {-HUGE_VAL, -HUGE_VAL, -HUGE_VAL};
  int    m = 0;
  for (int k = lo; k < hi; k++) {
    const int     f = B->perm[k];
    const double *p = B->V + 3 * B->F[3 * f], *q = B->V + 3 * B->F[3 * f + 1], *r = B->V + 3 * B->F[3 * f + 2];
    const double  u[3] = {q[0] - p[0], q[1] - p[1], q[2] - p[2]}, v[3] = {r[0] - p[0], r[1] - p[1], r[2] - p[2]};
    s[0] += u[1] * v[2] - u[2] * v[1];
    s[1] += u[2] * v[0] - u[0] * v[2];
    s[2] += u[0] * v[1] - u[1] * v[0];
  }
  len = sqrt(s[0] * s[0] + s[1] * s[1] + s[2] * s[2]);
  if (!(len > 0)) {
    s[0] = 0, s[1] = 0, s[2] = 1;
    len  = 1;
  }
  for (int i = 0; i < 3; i++) s[i] /= len;
  for (int i = 1; i < 3; i++)
    if (fabs(s[i]) < fabs(s[m])) m = i;
  e[m] = 1;
  for (int i = 0; i < 3; i++) t[i] = e[i] - s[m] * s[i];
  len = sqrt(t[0] * t[0] + t[1] * t[1] + t[2] * t[2]);
  for (int i = 0; i < 3; i++) {
    n->n[i]  = (float)s[i];
    n->t1[i] = (float)(t[i] / len);
  }
  FacetsNodeAxes(n, a);
  for (int k = lo; k < hi; k++)
    for (int c = 0; c < 3; c++) {
      const double *x = B->V + 3 * B->F[3 * B->perm[k] + c];
      for (int j = 0; j < 3; j++) {
        const double d = a[j][0] * x[0] + a[j][1] * x[1] + a[j][2] * x[2];
        elo[j]         = fmin(elo[j], d);
        ehi[j]         = fmax(ehi[j], d);
      }
    }
  for (int j = 0; j < 3; j++) { /* outwards by one float step beyond the rounding */
    float l = (float)elo[j], h = (float)ehi[j];
    if ((double)l >= elo[j]) l = nextafterf(l, -HUGE_VALF);
    if ((double)h <= ehi[j]) h = nextafterf(h, HUGE_VALF);
    n->olo[j] = l;
    n->ohi[j] = h;
  }
}

/* The facets perm[lo..hi) in the order of a hierarchy with leaves of at most 4 facets (each range
   split at its median along the longest extent of its centroids), inside a leaf of up to
   FACETS_LEAF facets: the facets' indices, and with them the ties between equally close facets,
   do not depend on the leaves' size */
static void Order(Builder *B, int lo, int hi)
{
  double clo[3] = {HUGE_VAL, HUGE_VAL, HUGE_VAL}, chi[3] = {-HUGE_VAL, -HUGE_VAL, -HUGE_VAL};
  int    ax     = 0;
  if (hi - lo <= 4) return;
  for (int k = lo; k < hi; k++)
    for (int i = 0; i < 3; i++) {
      clo[i] = fmin(clo[i], B->c[3 * B->perm[k] + i]);
      chi[i] = fmax(chi[i], B->c[3 * B->perm[k] + i]);
    }
  for (int i = 1; i < 3; i++)
    if (chi[i] - clo[i] > chi[ax] - clo[ax]) ax = i;
  const int mid = (lo + hi) / 2;
  Select(B->c, B->perm, lo, hi, mid, ax);
  Order(B, lo, mid);
  Order(B, mid, hi);
}

static void Build(Builder *B, int me, int lo, int hi)
{
  FacetsNode *n = &B->node[me];
  double      blo[3] = {HUGE_VAL, HUGE_VAL, HUGE_VAL}, bhi[3] = {-HUGE_VAL, -HUGE_VAL, -HUGE_VAL}, clo[3] = {HUGE_VAL, HUGE_VAL, HUGE_VAL}, chi[3] = {-HUGE_VAL, -HUGE_VAL, -HUGE_VAL};
  for (int k = lo; k < hi; k++) {
    const int f = B->perm[k];
    for (int c = 0; c < 3; c++)
      for (int i = 0; i < 3; i++) {
        const double x = B->V[3 * B->F[3 * f + c] + i];
        blo[i]         = fmin(blo[i], x);
        bhi[i]         = fmax(bhi[i], x);
      }
    for (int i = 0; i < 3; i++) {
      clo[i] = fmin(clo[i], B->c[3 * f + i]);
      chi[i] = fmax(chi[i], B->c[3 * f + i]);
    }
  }
  for (int i = 0; i < 3; i++) {
    float l = (float)blo[i], h = (float)bhi[i];
    if ((double)l > blo[i]) l = nextafterf(l, -HUGE_VALF);
    if ((double)h < bhi[i]) h = nextafterf(h, HUGE_VALF);
    n->lo[i] = l;
    n->hi[i] = h;
  }
  OrientedBox(B, n, lo, hi);
  if (hi - lo <= FACETS_LEAF) {
    Order(B, lo, hi);
    n->first = lo;
    n->count = hi - lo;
    return;
  }
  int ax = 0;
  for (int i = 1; i < 3; i++)
    if (chi[i] - clo[i] > chi[ax] - clo[ax]) ax = i;
  const int mid = (lo + hi) / 2, l = B->nnode;
  Select(B->c, B->perm, lo, hi, mid, ax);
  B->nnode += 2;
  n->first = l;
  n->count = 0;
  Build(B, l, lo, mid);
  Build(B, l + 1, mid, hi);
}

static int Find(int *u, int i)
{
  while (u[i] != i) {
    u[i] = u[u[i]];
    i    = u[i];
  }
  return i;
}

/* Solves the 5 x 5 system A x = b (Gaussian elimination, partial pivoting); 1 if singular */
static int Solve5(double A[5][5], double b[5], double x[5])
{
  double scale = 0.0;
  for (int i = 0; i < 5; i++) scale = fmax(scale, fabs(A[i][i]));
  for (int c = 0; c < 5; c++) {
    int p = c;
    for (int r = c + 1; r < 5; r++)
      if (fabs(A[r][c]) > fabs(A[p][c])) p = r;
    if (!(fabs(A[p][c]) > 1e-10 * scale)) return 1;
    for (int k = 0; k < 5; k++) {
      const double t = A[c][k];
      A[c][k]        = A[p][k];
      A[p][k]        = t;
    }
    const double t = b[c];
    b[c]           = b[p];
    b[p]           = t;
    for (int r = c + 1; r < 5; r++) {
      const double f = A[r][c] / A[c][c];
      for (int k = c; k < 5; k++) A[r][k] -= f * A[c][k];
      b[r] -= f * b[c];
    }
  }
  for (int r = 4; r >= 0; r--) {
    double s = b[r];
    for (int k = r + 1; k < 5; k++) s -= A[r][k] * x[k];
    x[r] = s / A[r][r];
  }
  return 0;
}

/* The corner normals refined by a local quadric fit: in the frame of the averaged normal n0,
   z = a x^2 + b xy + c y^2 + d x + e y through the other vertices of the group's facets (least
   squares), normal (-d, -e, 1): exact for a quadric, and unbiased at a vertex on an open edge
   whose facets lie on one side only (the average is tilted there). Kept: n0 where the fit is
   singular or turns the normal by more than 30 degrees. */
static PetscErrorCode FitNormals(FacetsData *m)
{
  int *cnt, *start, *list;

  PetscFunctionBeginUser;
  PetscCall(PetscCalloc1((size_t)m->nn + 1, &start));
  PetscCall(PetscCalloc1((size_t)m->nn, &cnt));
  PetscCall(PetscMalloc1(3 * (size_t)m->nf, &list));
  for (int k = 0; k < 3 * m->nf; k++) start[m->C[k] + 1]++;
  for (int c = 0; c < m->nn; c++) start[c + 1] += start[c];
  for (int k = 0; k < 3 * m->nf; k++) list[start[m->C[k]] + cnt[m->C[k]]++] = k;
  for (int c = 0; c < m->nn; c++) {
    double       A[5][5] = {{0}}, b[5] = {0}, x[5], t1[3], t2[3], n0[3], nf[3];
    const int    k0 = list[start[c]];
    const double *v = &m->V[3 * m->F[k0]];
    int          np = 0;
    for (int i = 0; i < 3; i++) n0[i] = m->N[3 * c + i];
    { /* t1 normal to n0 */
      const double a[3] = {fabs(n0[0]) < 0.6 ? 1.0 : 0.0, fabs(n0[0]) < 0.6 ? 0.0 : 1.0, 0.0};
      Cross(n0, a, t1);
      const double l = Norm(t1);
      for (int i = 0; i < 3; i++) t1[i] /= l;
      Cross(n0, t1, t2);
    }
    for (int ring = 1; ring <= 2 && np < 8; ring++) /* the 1-ring; the 2-ring too where it is small */
      for (int j = start[c]; j < start[c + 1]; j++) {
        const int f = list[j] / 3, cc = list[j] % 3;
        for (int o = 1; o <= 2; o++) {
          const int c2 = m->C[3 * f + (cc + o) % 3];
          for (int j2 = ring == 1 ? 0 : start[c2]; j2 < (ring == 1 ? 1 : start[c2 + 1]); j2++) {
            const int     f2 = ring == 1 ? f : list[j2] / 3, k2 = ring == 1 ? (cc + o) % 3 : (list[j2] % 3 + o) % 3;
            const double *q = &m->V[3 * m->F[3 * f2 + k2]], d[3] = {q[0] - v[0], q[1] - v[1], q[2] - v[2]};
            const double  px = Dot(d, t1), py = Dot(d, t2), pz = Dot(d, n0), h2 = px * px + py * py;
            const double  row[5] = {px * px, px * py, py * py, px, py};
            if (!(h2 > 0.0)) continue;
            for (int r = 0; r < 5; r++) { /* weights 1/h^2: every neighbour counts alike */
              for (int s = 0; s < 5; s++) A[r][s] += row[r] * row[s] / h2;
              b[r] += row[r] * pz / h2;
            }
            np++;
          }
        }
      }
    if (np < 5 || Solve5(A, b, x)) continue;
    for (int i = 0; i < 3; i++) nf[i] = n0[i] - x[3] * t1[i] - x[4] * t2[i];
    const double l = Norm(nf);
    if (!(l > 0.0) || Dot(nf, n0) / l < cos(30.0 * TOOL_PI / 180.0)) continue;
    for (int i = 0; i < 3; i++) m->N[3 * c + i] = nf[i] / l;
  }
  PetscCall(PetscFree(start));
  PetscCall(PetscFree(cnt));
  PetscCall(PetscFree(list));
  PetscFunctionReturn(0);
}

PetscErrorCode FacetsBuild(MPI_Comm comm, Patch *p, const char path[], FacetsRaw *raw, PetscBool flip, PetscBool smooth, double feature_deg)
{
  FacetsData *m;
  const int   nf = raw->nf, nv = raw->nv;
  double     *cen;
  int        *perm, *F, *fid;
  Edge       *E;

  PetscFunctionBeginUser;
  PetscCheck(nf > 0, comm, PETSC_ERR_FILE_UNEXPECTED, "tool file %s: empty surface", path);
  for (int k = 0; k < nv; k++)
    for (int i = 0; i < 3; i++) PetscCheck(PetscIsNormalReal(raw->V[3 * k + i]) || raw->V[3 * k + i] == 0.0, comm, PETSC_ERR_FILE_UNEXPECTED, "tool file %s: vertex %d has a coordinate that is not a finite number (%g)", path, k + 1, raw->V[3 * k + i]);
  for (int f = 0; f < nf; f++) {
    const int *t = &raw->F[3 * f];
    double     e1[3], e2[3], n[3];
    for (int i = 0; i < 3; i++) {
      e1[i] = raw->V[3 * t[1] + i] - raw->V[3 * t[0] + i];
      e2[i] = raw->V[3 * t[2] + i] - raw->V[3 * t[0] + i];
    }
    Cross(e1, e2, n);
    PetscCheck(Norm(n) > 0.0, comm, PETSC_ERR_FILE_UNEXPECTED, "tool file %s: facet %d has zero area", path, raw->fid[f]);
  }
  PetscCall(PetscNew(&m));
  p->data = m;
  PetscCall(PetscStrncpy(m->file, path, sizeof(m->file)));
  m->nv          = nv;
  m->nf          = nf;
  m->smooth      = smooth ? 1 : 0;
  m->feature_deg = feature_deg;
  m->V           = raw->V;
  raw->V         = NULL;
  p->sense       = flip ? -1 : 1;
  /* hierarchy, then the facets in its order */
  PetscCall(PetscMalloc1(3 * (size_t)nf, &cen));
  PetscCall(PetscMalloc1((size_t)nf, &perm));
  for (int f = 0; f < nf; f++) {
    perm[f] = f;
    for (int i = 0; i < 3; i++) cen[3 * f + i] = (m->V[3 * raw->F[3 * f] + i] + m->V[3 * raw->F[3 * f + 1] + i] + m->V[3 * raw->F[3 * f + 2] + i]) / 3.0;
  }
  PetscCall(PetscMalloc1(2 * (size_t)nf + 1, &m->node));
  {
    Builder B = {cen, perm, m->node, 1, m->V, raw->F};
    Build(&B, 0, 0, nf);
    m->nnode = B.nnode;
    PetscCall(PetscRealloc(sizeof(FacetsNode) * (size_t)m->nnode, &m->node));
  }
  PetscCall(PetscFree(cen));
  PetscCall(PetscMalloc1(3 * (size_t)nf, &F));
  PetscCall(PetscMalloc1((size_t)nf, &fid));
  for (int k = 0; k < nf; k++) {
    for (int c = 0; c < 3; c++) F[3 * k + c] = raw->F[3 * perm[k] + c];
    fid[k] = raw->fid[perm[k]];
  }
  PetscCall(PetscFree(perm));
  PetscCall(PetscFree(raw->F));
  PetscCall(PetscFree(raw->fid));
  m->F = F;
  { /* vertices renumbered in the order the facets first use them: a leaf's vertices lie together */
    int    *map;
    double *V2;
    int     nv2 = 0;
    PetscCall(PetscMalloc1((size_t)nv, &map));
    PetscCall(PetscMalloc1(3 * (size_t)nv, &V2));
    for (int k = 0; k < nv; k++) map[k] = -1;
    for (int k = 0; k < 3 * nf; k++) {
      if (map[F[k]] < 0) {
        map[F[k]] = nv2;
        for (int i = 0; i < 3; i++) V2[3 * nv2 + i] = m->V[3 * F[k] + i];
        nv2++;
      }
      F[k] = map[F[k]];
    }
    PetscCall(PetscFree(map));
    PetscCall(PetscFree(m->V));
    m->V  = V2;
    m->nv = nv2; /* vertices no facet uses are dropped */
  }
  /* edges: neighbours, orientation, manifold */
  PetscCall(PetscMalloc1(3 * (size_t)nf, &E));
  PetscCall(PetscMalloc1(3 * (size_t)nf, &m->adj));
  PetscCall(PetscCalloc1((size_t)m->nv, &m->vbnd));
  for (int f = 0; f < nf; f++)
    for (int e = 0; e < 3; e++) {
      const int a = F[3 * f + e], b = F[3 * f + (e + 1) % 3];
      E[3 * f + e] = (Edge){a < b ? a : b, a < b ? b : a, f, e, a < b};
    }
  qsort(E, 3 * (size_t)nf, sizeof(*E), CmpE);
  {
    PetscErrorCode ierr = 0;
    char           msg[512];
    for (size_t i = 0; i < 3 * (size_t)nf && !ierr;) {
      size_t j = i + 1;
      while (j < 3 * (size_t)nf && E[j].a == E[i].a && E[j].b == E[i].b) j++;
      if (j - i == 1) {
        m->adj[3 * E[i].f + E[i].e] = -1;
        m->vbnd[E[i].a] = m->vbnd[E[i].b] = 1;
        m->nopen++;
      } else if (j - i == 2) {
        if (E[i].fwd == E[i + 1].fwd) {
          snprintf(msg, sizeof(msg), "tool file %s: the surface is not consistently oriented: facet %d and facet %d run the same way along their shared edge", path, fid[E[i].f] < fid[E[i + 1].f] ? fid[E[i + 1].f] : fid[E[i].f], fid[E[i].f] < fid[E[i + 1].f] ? fid[E[i].f] : fid[E[i + 1].f]);
          ierr = 1;
        }
        m->adj[3 * E[i].f + E[i].e]         = E[i + 1].f;
        m->adj[3 * E[i + 1].f + E[i + 1].e] = E[i].f;
      } else {
        if (smooth) {
          snprintf(msg, sizeof(msg), "tool file %s: non-manifold edge shared by %d facets (facet %d among them); smoothing needs a manifold surface (-smooth 0 keeps the raw facets)", path, (int)(j - i), fid[E[i].f]);
          ierr = 1;
        }
        for (size_t k = i; k < j; k++) m->adj[3 * E[k].f + E[k].e] = -2;
      }
      i = j;
    }
    PetscCall(PetscFree(E));
    PetscCall(PetscFree(fid));
    PetscCheck(!ierr, comm, PETSC_ERR_FILE_UNEXPECTED, "%s", msg);
  }
  /* corner normals: the corners of the facets around a vertex joined across edges not sharper than
     the feature angle, each group the angle-weighted average of its facets' normals */
  {
    const double cosf = cos(feature_deg * TOOL_PI / 180.0);
    int         *u, *cls, nn = 0;
    double      *fn;
    PetscCall(PetscMalloc1(3 * (size_t)nf, &u));
    PetscCall(PetscMalloc1(3 * (size_t)nf, &fn));
    for (int k = 0; k < 3 * nf; k++) u[k] = k;
    for (int f = 0; f < nf; f++) {
      double e1[3], e2[3], n[3], l;
      for (int i = 0; i < 3; i++) {
        e1[i] = m->V[3 * F[3 * f + 1] + i] - m->V[3 * F[3 * f] + i];
        e2[i] = m->V[3 * F[3 * f + 2] + i] - m->V[3 * F[3 * f] + i];
      }
      Cross(e1, e2, n);
      l = Norm(n);
      for (int i = 0; i < 3; i++) fn[3 * f + i] = n[i] / l;
    }
    for (int f = 0; f < nf; f++)
      for (int e = 0; e < 3; e++) {
        const int g = m->adj[3 * f + e];
        if (g < 0 || g < f || Dot(&fn[3 * f], &fn[3 * g]) < cosf) continue;
        for (int s = 0; s < 2; s++) {
          const int v = F[3 * f + (e + s) % 3];
          for (int c = 0; c < 3; c++)
            if (F[3 * g + c] == v) {
              const int a = Find(u, 3 * f + (e + s) % 3), b = Find(u, 3 * g + c);
              if (a != b) u[a < b ? b : a] = a < b ? a : b;
            }
        }
      }
    PetscCall(PetscMalloc1(3 * (size_t)nf, &cls));
    for (int k = 0; k < 3 * nf; k++) cls[k] = -1;
    PetscCall(PetscMalloc1(3 * (size_t)nf, &m->C));
    for (int k = 0; k < 3 * nf; k++) {
      const int r = Find(u, k);
      if (cls[r] < 0) cls[r] = nn++;
      m->C[k] = cls[r];
    }
    PetscCall(PetscFree(cls));
    PetscCall(PetscCalloc1(3 * (size_t)nn, &m->N));
    m->nn = nn;
    for (int f = 0; f < nf; f++)
      for (int c = 0; c < 3; c++) {
        const double *x0 = &m->V[3 * F[3 * f + c]], *x1 = &m->V[3 * F[3 * f + (c + 1) % 3]], *x2 = &m->V[3 * F[3 * f + (c + 2) % 3]];
        double        a[3], b[3];
        for (int i = 0; i < 3; i++) {
          a[i] = x1[i] - x0[i];
          b[i] = x2[i] - x0[i];
        }
        const double w = acos(fmax(-1.0, fmin(1.0, Dot(a, b) / (Norm(a) * Norm(b)))));
        for (int i = 0; i < 3; i++) m->N[3 * m->C[3 * f + c] + i] += w * fn[3 * f + i];
      }
    for (int k = 0; k < nn; k++) {
      const double l = Norm(&m->N[3 * k]);
      for (int i = 0; i < 3; i++) m->N[3 * k + i] /= l;
    }
    PetscCall(FitNormals(m));
    PetscCall(PetscCalloc1((size_t)nf, &m->curved));
    for (int f = 0; f < nf; f++)
      for (int e = 0; e < 3; e++) {
        const int g = m->adj[3 * f + e];
        if (g == -2) continue;
        if (g == -1) { /* an open edge: curved by its vertices' normals */
          m->curved[f] |= (unsigned char)(1 << e);
          continue;
        }
        int same = 1;
        for (int s = 0; s < 2; s++) {
          const int vv = F[3 * f + (e + s) % 3];
          for (int c = 0; c < 3; c++)
            if (F[3 * g + c] == vv && m->C[3 * g + c] != m->C[3 * f + (e + s) % 3]) same = 0;
        }
        if (same) m->curved[f] |= (unsigned char)(1 << e);
      }
    if (smooth) /* the patches' largest distance from their triangles: |c01 u w + c12 u v + c20 v w| <= sum |c| / 4 */
      for (int f = 0; f < nf; f++) {
        double s = 0.0, x[3], xu[3], xv[3], xuu[3], xuv[3], xvv[3];
        FacetsEvalLocal(m, f, 0.25, 0.25, x, xu, xv, xuu, xuv, xvv);
        s         = (Norm(xuu) / 2.0 + Norm(xvv) / 2.0 + Norm(xuv) + Norm(xuu) / 2.0 + Norm(xvv) / 2.0) / 4.0;
        m->dev    = fmax(m->dev, s);
      }
    PetscCall(PetscFree(u));
    PetscCall(PetscFree(fn));
  }
  {
    double b[6] = {HUGE_VAL, -HUGE_VAL, HUGE_VAL, -HUGE_VAL, HUGE_VAL, -HUGE_VAL};
    for (int k = 0; k < m->nv; k++)
      for (int i = 0; i < 3; i++) {
        b[2 * i]     = fmin(b[2 * i], m->V[3 * k + i]);
        b[2 * i + 1] = fmax(b[2 * i + 1], m->V[3 * k + i]);
      }
    m->L = sqrt((b[1] - b[0]) * (b[1] - b[0]) + (b[3] - b[2]) * (b[3] - b[2]) + (b[5] - b[4]) * (b[5] - b[4]));
  }
  PetscCall(FacetsGridBuild(m));
  PetscCall(FacetsLocalBuild(m));
  PetscFunctionReturn(0);
}

PetscErrorCode FacetsPatchFromOptions(PetscOptionItems *PetscOptionsObject, Patch *p, const char stem[])
{
  const MPI_Comm comm = PetscOptionsObject->comm;
  char           opt[PETSC_MAX_PATH_LEN], full[PETSC_MAX_PATH_LEN], path[PETSC_MAX_PATH_LEN] = "", fmt[16] = "", group[256] = "";
  PetscBool      flg, flip = PETSC_FALSE, smooth = PETSC_TRUE;
  PetscReal      fa = 45.0;
  FacetsRaw      raw;
  const char    *base = stem[0] ? stem : "-", *sep = stem[0] ? "_" : "";

  PetscFunctionBeginUser;
  PetscCall(PetscSNPrintf(opt, sizeof(opt), "%s%sfile", base, sep));
  PetscCall(ToolOptionFullName(PetscOptionsObject, opt, full, sizeof(full)));
  PetscCall(PetscOptionsString(opt, "Meshed surface file (.stl, .msh, .inp)", "doc/tools.md", path, path, sizeof(path), &flg));
  PetscCheck(flg, comm, PETSC_ERR_USER_INPUT, "%s: missing required option (the surface file)", full);
  PetscCall(PetscSNPrintf(opt, sizeof(opt), "%s%sfile_format", base, sep));
  PetscCall(PetscOptionsString(opt, "Format of the file: stl, msh, inp (default: from the extension)", NULL, fmt, fmt, sizeof(fmt), NULL));
  PetscCall(PetscSNPrintf(opt, sizeof(opt), "%s%sfile_group", base, sep));
  PetscCall(PetscOptionsString(opt, "Physical group (msh) or surface / element set (inp) to read (default: all surface elements)", NULL, group, group, sizeof(group), NULL));
  PetscCall(PetscSNPrintf(opt, sizeof(opt), "%s%sflip", base, sep));
  PetscCall(PetscOptionsBool(opt, "Reverse the facets' orientation (the normal is x_1 - x_0 cross x_2 - x_0, out of the tool)", NULL, flip, &flip, NULL));
  PetscCall(PetscSNPrintf(opt, sizeof(opt), "%s%ssmooth", base, sep));
  PetscCall(PetscOptionsBool(opt, "Smooth normal field over the facets (0: raw facets)", NULL, smooth, &smooth, NULL));
  PetscCall(PetscSNPrintf(opt, sizeof(opt), "%s%sfeature_angle", base, sep));
  PetscCall(ToolOptionFullName(PetscOptionsObject, opt, full, sizeof(full)));
  PetscCall(PetscOptionsReal(opt, "Angle between facet normals (degrees) beyond which an edge stays sharp", NULL, fa, &fa, NULL));
  PetscCheck(fa >= 0 && fa <= 180, comm, PETSC_ERR_USER_INPUT, "%s %g: must lie in [0, 180]", full, (double)fa);
  {
    char f[16];
    FacetsFormat(path, fmt, f);
    PetscCall(PetscSNPrintf(opt, sizeof(opt), "%s%sfile", base, sep));
    PetscCall(ToolOptionFullName(PetscOptionsObject, opt, full, sizeof(full)));
    PetscCheck(!strcmp(f, "stl") || !strcmp(f, "msh") || !strcmp(f, "inp"), comm, PETSC_ERR_USER_INPUT, "%s %s: unknown format '%s' (stl, msh or inp; or -file_format)", full, path, f);
  }
  PetscCall(FacetsRead(comm, path, fmt, group, &raw));
  PetscCall(FacetsBuild(comm, p, path, &raw, flip, smooth, fa));
  PetscFunctionReturn(0);
}
