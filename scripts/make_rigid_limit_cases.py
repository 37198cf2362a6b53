#!/usr/bin/env python3
"""Writes the "rigid limit" check of the hemispherical punch benchmark: the seed blank with the
punch and the die as elastic bodies meshed in hexahedra, in contact with the blank through contact
pairs (doc/contact-bodies.md), to be compared with the rigid-tool cases
(cases/hemisphere_frictionless.opts, cases/hemisphere_friction.opts) as the tools' modulus grows
(scripts/rigid_limit.py, doc/notes/rigid-limit.md).

usage: make_rigid_limit_cases.py [--check FIELDS_H5]

  cases/meshes/hemisphere_bodies.inp            blank + punch + die, C3D8
  cases/hemisphere_bodies_frictionless.opts     the bodies' case, frictionless
  cases/hemisphere_bodies_friction.opts         the same with mu = 0.15

--check FIELDS_H5: compare the blank part with the mesh the code builds with -mesh_type blank
(fields.h5 of a run of cases/hemisphere_frictionless.opts): coordinates and connectivity.

The mesh's three parts (node ids: blank 1-, punch 10001-, die 20001-; elements likewise):

* BLANK: exactly the code's O-grid quarter blank of cases/hemisphere_frictionless.opts
  (src/mesh/meshgen.c, MeshDataCreateBlank re-implemented: radius 59.18, thickness 1, core 0.4,
  7 core cells, 18 radial cells, 1 layer; 301 hexahedra, 668 nodes, the same node and element
  order), with its node sets rim, top, bottom, centre and its symmetry edges (blank_symx,
  blank_symy; the generator's symx and symy).
* PUNCH: a thick spherical shell, outer radius 50.8, inner 45.8 (5 mm, 2 layers), centre
  (0, 0, -50.8): its pole touches the blank's bottom face at the origin, as the rigid punch's
  (cases/tools/hemisphere_punch*.tool, sphere centre 0,0,-50.8). The octant x, y >= 0 of the
  sphere as three equiangular "cubed sphere" patches (the faces z = 1, x = 1, y = 1 of the cube
  projected radially on the sphere), N_PUNCH cells along each patch edge (45 degrees of arc):
  2 N_PUNCH = 48 facets per quarter meridian (37 of them kept, down to the cut below), a
  meridian edge of 50.8 (pi/4)/N_PUNCH = 1.66 mm at the axes (1.18 to 1.66 mm in all), the "48 rings" of the faceted tool study
  (doc/tools.md, Hemispherical punch with meshed tools: raw plane facets at 48 rings within
  0.06 % of the analytic punch at 20 mm, 24 rings 0.27 %, 12 rings 1.1 %; the pairs' master faces
  are bilinear, not smoothed). The side patches stop at z/x (resp. z/y) = tan(C0_PUNCH 45/N_PUNCH
  degrees) = tan(20.6 degrees), a polar angle of at least 69 degrees (radius 47.5): the sheet leaves the punch at about 53 degrees at
  40 mm of travel. Node sets punch_surface (outer sphere: the master of the blank's bottom),
  punch_drive (inner sphere: driven by 0,0,40), punch_symx, punch_symy (x = 0, y = 0, the driven
  nodes left out).
* DIE: the fillet ring, a thick quarter-torus shell section: in the (r, z) plane about the fillet's
  centre (59.18, 7.35) the radius rho from 3.35 to 6.35 (2 layers), the angle from 180 degrees (the
  die opening, r = 52.83, z = 7.35) to 270 degrees (r = 59.18, z = 1: the die face, tangent at the
  clamp radius), as the rigid die's torus (cases/tools/hemisphere_die.tool: major 59.18, minor
  6.35, centre z 7.35, range 180..270), continued by the die face's land z = 1 from r = 59.18 to
  60.68 (the clamped rim's top nodes then lie on a plane face, not beside the fillet's open
  edge); N_DIE_ARC cells along the fillet's arc (0.50 mm); around the ring two cells per sector of
  the blank's O-grid ring (3.2 degrees, 3.3 mm at r = 59.18; half cells at the symmetry planes),
  placed so that the blank's radial node lines lie at the cells' middles: a die edge, a concave
  crease seen from the sheet, under a pressed node makes its force jump from face to face (a first
  mesh with 40 uniform cells had an edge at 45 degrees, under the diagonal's nodes, and Newton
  stalled there at 19.8 mm of travel, as the raw faceted tools did near 20 mm in doc/tools.md); the
  chords then lie 0.022 mm inside the torus at the nodes. Node sets die_surface (rho = 6.35 and the
  land's face: the master of the blank's top), die_fixed (every other die node), die_symx, die_symy
  (the free surface nodes on x = 0, y = 0).
* symx, symy: the three parts' symmetry nodes together (blank_symx + punch_symx + die_symx, ...),
  for one condition per plane.

Element sets BLANK, PUNCH, DIE. Every hexahedron is checked positive (det J > 0 at its corners
and Gauss points; scripts/make_pair_cases.py's Deck) before the deck is written.
"""
import math
import os
import sys

import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.abspath(os.path.join(HERE, ".."))
sys.path.insert(0, HERE)
from make_pair_cases import Deck  # noqa: E402

MESH = "cases/meshes/hemisphere_bodies.inp"

# blank (cases/hemisphere_frictionless.opts)
R_BLANK, T_BLANK, CORE, NC, NR, NL = 59.18, 1.0, 0.4, 7, 18, 1
BULGE = math.tan(math.pi / 12) / 2          # BLANK_BULGE of meshgen.c

# punch
R_PUNCH, T_PUNCH, L_PUNCH = 50.8, 5.0, 2
CENTRE_PUNCH = (0.0, 0.0, -50.8)
N_PUNCH = 24                                  # cells per 45 degrees of arc
C0_PUNCH = 11                                 # side patches: rows from C0_PUNCH * 45/N_PUNCH degrees

# die fillet
R_CLAMP, R_FILLET, Z_FILLET = 59.18, 6.35, 7.35
T_DIE, L_DIE = 3.0, 2
N_DIE_ARC = 20                                # cells along the fillet's 90 degrees
N_DIE_LAND, L_LAND = 3, 1.5                   # the die face beyond the clamp radius (z = 1)
DIE_AZ_PER_SECTOR = 2                         # azimuthal cells per sector of the blank's ring

E_SHEET = 69004.0
E_FACTOR = 1e3                                # the options file's default tools' modulus: 1e3 E


# ---------------------------------------------------------------- blank (meshgen.c)
def blank(d, nid0=1, eid0=1):
    """the code's quarter O-grid blank, ids nid0.. in the generator's order; returns its sets"""
    nc, nr, nl = NC, NR, NL
    a = CORE * R_BLANK
    ncore2 = (nc + 1) ** 2
    nq2 = ncore2 + (2 * nc + 1) * nr

    def core(i, j):
        return i + (nc + 1) * j

    def ring(s, k):
        if k == 0:
            return core(nc, s) if s <= nc else core(2 * nc - s, nc)
        return ncore2 + s * nr + k - 1

    Q = np.zeros((nq2, 2))
    rim = np.zeros(nq2, bool)
    ex = -np.ones(nq2, int)
    ey = -np.ones(nq2, int)
    for j in range(nc + 1):
        for i in range(nc + 1):
            u, v = i / nc, j / nc
            Q[core(i, j)] = (a * u * (1 + BULGE * (1 - v * v)), a * v * (1 + BULGE * (1 - u * u)))
    for s in range(2 * nc + 1):
        b = ring(s, 0)
        if s <= nc:
            th = s * math.pi / (4 * nc)
            A = (R_BLANK * math.cos(th), R_BLANK * math.sin(th))
        else:
            ph = (2 * nc - s) * math.pi / (4 * nc)
            A = (R_BLANK * math.sin(ph), R_BLANK * math.cos(ph))
        for k in range(1, nr + 1):
            w = k / nr
            Q[ring(s, k)] = ((1 - w) * Q[b, 0] + w * A[0], (1 - w) * Q[b, 1] + w * A[1])
        rim[ring(s, nr)] = True
    for e in range(nc + nr + 1):
        ex[core(0, e) if e <= nc else ring(2 * nc, e - nc)] = e
        ey[core(e, 0) if e <= nc else ring(0, e - nc)] = e
    quads = []
    for j in range(nc):
        for i in range(nc):
            quads.append((core(i, j), core(i + 1, j), core(i + 1, j + 1), core(i, j + 1)))
    for s in range(2 * nc):
        for k in range(nr):
            quads.append((ring(s, k), ring(s, k + 1), ring(s + 1, k + 1), ring(s + 1, k)))
    ids = {}
    for L in range(nl + 1):
        z = T_BLANK if L == nl else T_BLANK * L / nl
        for p in range(nq2):
            ids[L, p] = d.node(nid0 + L * nq2 + p, (Q[p, 0], Q[p, 1], z))
    e = eid0
    for L in range(nl):
        for q in quads:
            d.hexa(e, [ids[L, p] for p in q] + [ids[L + 1, p] for p in q], "BLANK")
            e += 1
    allv = [(L, p) for L in range(nl + 1) for p in range(nq2)]
    return {"rim": [ids[v] for v in allv if rim[v[1]]],
            "top": [ids[v] for v in allv if v[0] == nl],
            "bottom": [ids[v] for v in allv if v[0] == 0],
            "centre": [ids[v] for v in allv if v[1] == 0],
            "blank_symx": [ids[v] for v in allv if ex[v[1]] >= 0],
            "blank_symy": [ids[v] for v in allv if ey[v[1]] >= 0]}


class Points:
    """node ids by position (shared patch edges merged), from nid0"""

    def __init__(self, d, nid0):
        self.d, self.next, self.key = d, nid0, {}

    def get(self, x):
        k = tuple(int(round(v * 1e8)) for v in x)
        if k not in self.key:
            self.key[k] = self.d.node(self.next, x)
            self.next += 1
        return self.key[k]


# ---------------------------------------------------------------- punch
def punch(d, nid0=10001, eid0=10001):
    P = Points(d, nid0)
    c = np.array(CENTRE_PUNCH)
    th = [math.radians(45.0 * k / N_PUNCH) for k in range(N_PUNCH + 1)]
    radii = [R_PUNCH - T_PUNCH + T_PUNCH * L / L_PUNCH for L in range(L_PUNCH + 1)]

    def patch(f, ni, nj0):
        """f(i, j) -> direction; cells i in [0, N), j in [nj0, N)"""
        return [(f(i, j), f(i + 1, j), f(i + 1, j + 1), f(i, j + 1))
                for j in range(nj0, N_PUNCH) for i in range(N_PUNCH)]

    t = [math.tan(v) for v in th]
    t[-1] = 1.0
    quads = (patch(lambda i, j: (t[i], t[j], 1.0), N_PUNCH, 0) +            # z = 1: the pole's patch
             patch(lambda i, j: (1.0, t[i], t[j]), N_PUNCH, C0_PUNCH) +     # x = 1
             patch(lambda i, j: (t[i], 1.0, t[j]), N_PUNCH, C0_PUNCH))      # y = 1
    e = eid0
    outer, inner = set(), set()
    for q in quads:
        dirs = [np.array(v) / np.linalg.norm(v) for v in q]
        lay = [[P.get(c + r * u) for u in dirs] for r in radii]
        for L in range(L_PUNCH):
            d.hexa(e, lay[L] + lay[L + 1], "PUNCH")
            e += 1
        outer.update(lay[-1])
        inner.update(lay[0])
    allp = set(P.key.values())
    symx = [n for n in allp if abs(d.X[n][0]) < 1e-9 and n not in inner]
    symy = [n for n in allp if abs(d.X[n][1]) < 1e-9 and n not in inner]
    return {"punch_surface": outer, "punch_drive": inner, "punch_symx": symx, "punch_symy": symy}, e - eid0


# ---------------------------------------------------------------- die
def die_azimuths():
    """the die's azimuthal node angles (degrees): two cells per sector of the blank's O-grid ring
    (90/(2 NC) degrees), whose radial node lines (the blank's s-lines, within 0.2 degrees near the
    die) lie at the cells' middles, half cells at the symmetry planes: no die edge (a concave
    crease seen from the sheet) under a row of the sheet's nodes"""
    sector = 90.0 / (2 * NC)
    return [0.0] + [(j / DIE_AZ_PER_SECTOR + 0.5 / DIE_AZ_PER_SECTOR) * sector
                    for j in range(2 * NC * DIE_AZ_PER_SECTOR)] + [90.0]


def die(d, nid0=20001, eid0=20001):
    P = Points(d, nid0)
    ids = {}
    psis = die_azimuths()
    naz = len(psis) - 1
    nsec = N_DIE_ARC + N_DIE_LAND
    for L in range(L_DIE + 1):
        rho = R_FILLET - T_DIE + T_DIE * L / L_DIE
        for i in range(nsec + 1):
            if i <= N_DIE_ARC:      # the fillet, 180 to 270 degrees about (R_CLAMP, Z_FILLET)
                th = math.radians(180.0 + 90.0 * i / N_DIE_ARC)
                r, z = R_CLAMP + rho * math.cos(th), Z_FILLET + rho * math.sin(th)
            else:                   # the die face's land beyond the clamp radius, z = 1
                r, z = R_CLAMP + L_LAND * (i - N_DIE_ARC) / N_DIE_LAND, Z_FILLET - rho
            for k, psd in enumerate(psis):
                ps = math.radians(psd)
                x, y = r * math.cos(ps), r * math.sin(ps)
                ids[L, i, k] = P.get((0.0 if k == naz else x, 0.0 if k == 0 else y, z))
    e = eid0
    for L in range(L_DIE):
        for i in range(nsec):
            for k in range(naz):
                q = [(i, k), (i + 1, k), (i + 1, k + 1), (i, k + 1)]
                d.hexa(e, [ids[L, a, b] for a, b in q] + [ids[L + 1, a, b] for a, b in q], "DIE")
                e += 1
    surf = {ids[L_DIE, i, k] for i in range(nsec + 1) for k in range(naz + 1)}
    fixed = set(P.key.values()) - surf
    return {"die_surface": surf, "die_fixed": fixed,
            "die_symx": [n for n in surf if abs(d.X[n][0]) < 1e-9],
            "die_symy": [n for n in surf if abs(d.X[n][1]) < 1e-9]}, e - eid0


# ---------------------------------------------------------------- checks
def check_blank(d, path):
    import h5py
    with h5py.File(path, "r") as f:
        X = f["mesh/coordinates"][:]
        H = f["mesh/hexahedra"][:]
        nid = f["mesh/node_ids"][:]
    ours = np.array([d.X[i] for i in range(1, len(X) + 1)])
    conn = np.array([c for _, c, s in d.elems if s == "BLANK"]) - 1
    dx = np.abs(ours - X[np.argsort(nid)]).max() if len(ours) == len(X) else float("inf")
    same = conn.shape == H.shape and (conn == H).all()
    print("blank against %s: %d nodes, %d hexahedra; largest coordinate difference %.3g; connectivity %s"
          % (path, len(X), len(H), dx, "identical" if same else "DIFFERENT"))
    return dx < 1e-9 and same


# ---------------------------------------------------------------- the options files
HEAD = """Hemispherical punch stretching, the rigid limit: {what}, quarter model; the punch and the die
as elastic bodies meshed in hexahedra, in contact with the blank through contact pairs
(doc/contact-bodies.md), against the rigid tools of cases/hemisphere_{fr}.opts (scripts/rigid_limit.py,
doc/notes/rigid-limit.md). Mesh {mesh} (scripts/make_rigid_limit_cases.py): BLANK the code's seed blank
(-mesh_type blank of the rigid case, 301 hexahedra, one layer: rim clamped, symmetry x = 0, y = 0);
PUNCH a spherical shell of outer radius 50.8, 5 thick, 2 layers ({np} hexahedra; bilinear facets of
1.66 mm along the meridian, 48 per quarter circle), its pole touching the blank's bottom at the
origin, its inner surface (punch_drive) moved by 0,0,40 as the rigid punch; DIE the fillet (radius
6.35, tangent to the die face at the clamp radius 59.18) as a quarter-torus shell 3 thick with a
1.5 mm land at z = 1 ({nd} hexahedra; 0.50 mm along the fillet, 3.2 degrees around, the blank's
radial node lines at the cells' middles), every node but its fillet surface fixed. Sheet as the rigid case (E 69004, nu 0.3,
Swift 589 (1e-4 + ep)^0.216); tools J2 elastic (yield 1e12), E = {ef:g} x 69004 by default
(-body_punch_material_E, -body_die_material_E on the command line for the study).
Pairs: pp, the blank's bottom nodes on the punch's outer faces; pd, its top nodes on the die's
fillet faces; the rigid case's per-node penalties (K_N 1e5, K_T 5e3 N/mm){fric}.
Punch force: contact.csv, pair pp's fz (the resultant on the blank, quarter) times 4; the pair's
force and force_full columns sum the nodes' normal forces (not the z resultant);
history.csv drive_fz the reaction on punch_drive."""


def case_text(fr, mu, nh):
    lines = [
        "-mesh_type inp",
        "-mesh_file " + MESH,
        "-model_symmetry 4",
        "-material_E 69004",
        "-material_nu 0.3",
        "-material_hardening swift",
        "-material_swift_K 589",
        "-material_swift_eps0 1e-4",
        "-material_swift_n 0.216",
        "-body_names punch,die",
        "-body_punch_set PUNCH",
        "-body_punch_material_E %.10g" % (E_FACTOR * E_SHEET),
        "-body_punch_material_nu 0.3",
        "-body_punch_material_hardening linear",
        "-body_punch_material_yield 1e12",
        "-body_die_set DIE",
        "-body_die_material_E %.10g" % (E_FACTOR * E_SHEET),
        "-body_die_material_nu 0.3",
        "-body_die_material_hardening linear",
        "-body_die_material_yield 1e12",
        "-bc_names clamp,symx,symy,drive,diefix",
        "-bc_clamp_set rim",
        "-bc_clamp_components x,y,z",
        "-bc_symx_set symx",
        "-bc_symx_components x",
        "-bc_symy_set symy",
        "-bc_symy_components y",
        "-bc_drive_set punch_drive",
        "-bc_drive_components x,y,z",
        "-bc_drive_values 0,0,40",
        "-bc_diefix_set die_fixed",
        "-bc_diefix_components x,y,z",
        "# contact: the blank's bottom on the punch, its top on the die",
        "-pair_names pp,pd",
        "-pair_pp_slave bottom",
        "-pair_pp_master punch_surface",
        "-pair_pp_penalty_normal 1e5",
        "-pair_pp_penalty_tangential 5e3",
        "-pair_pp_friction %g" % mu,
        "-pair_pd_slave top",
        "-pair_pd_master die_surface",
        "-pair_pd_penalty_normal 1e5",
        "-pair_pd_penalty_tangential 5e3",
        "-pair_pd_friction %g" % mu,
        "# 15 equal steps, as the rigid case",
        "-load_steps 15",
    ]
    if mu:
        lines.append("-newton_keep_contact all")
    lines += ["-output_interval 4", "-output_dir out/hemisphere_bodies_%s" % fr]
    return lines


def main(argv):
    d = Deck()
    sets = blank(d)
    ps, np_ = punch(d)
    ds, nd = die(d)
    sets.update(ps)
    sets.update(ds)
    sets["symx"] = list(sets["blank_symx"]) + list(ps["punch_symx"]) + list(ds["die_symx"])
    sets["symy"] = list(sets["blank_symy"]) + list(ps["punch_symy"]) + list(ds["die_symy"])
    for k, v in sets.items():
        d.nset(k, v)
    if "--check" in argv:
        if not check_blank(d, argv[argv.index("--check") + 1]):
            return 1
    nv, ne, per, sj, asp = d.stats()
    header = ("Hemispherical punch benchmark, the rigid limit: the seed blank (BLANK, node ids 1-, the code's\n"
              "-mesh_type blank of cases/hemisphere_frictionless.opts), the punch (PUNCH, ids 10001-: spherical\n"
              "shell R 50.8, 5 thick, centre 0,0,-50.8) and the die fillet (DIE, ids 20001-: quarter-torus shell\n"
              "about r 59.18, z 7.35, radius 3.35 to 6.35, 180 to 270 degrees). %d nodes, %d hexahedra (%s).\n"
              "Node sets: %s.\nWritten by scripts/make_rigid_limit_cases.py."
              % (nv, ne, ", ".join("%s %d" % kv for kv in per.items()), ", ".join(d.nsets)))
    d.write(os.path.join(ROOT, MESH), header)
    print("%s: %d nodes, %d hexahedra (%s); smallest scaled Jacobian %.3f, largest edge ratio %.1f"
          % (MESH, nv, ne, ", ".join("%s %d" % kv for kv in per.items()), sj, asp))
    print("  node sets: " + ", ".join("%s %d" % (k, len(v)) for k, v in d.nsets.items()))
    # facet sizes of the master surfaces
    for name, es in (("punch", "PUNCH"), ("die", "DIE")):
        surf = set(d.nsets[name + "_surface"])
        diag, edges = 0.0, []
        for _, conn, s in d.elems:
            if s != es:
                continue
            for face in ((4, 5, 6, 7), (0, 1, 2, 3)):
                f = [conn[a] for a in face]
                if all(n in surf for n in f):
                    x = np.array([d.X[n] for n in f])
                    diag = max(diag, np.linalg.norm(x[2] - x[0]), np.linalg.norm(x[3] - x[1]))
                    edges += [np.linalg.norm(x[(a + 1) % 4] - x[a]) for a in range(4)]
        print("  %s surface: %d faces, edges %.3f to %.3f mm, largest diagonal %.3f" % (name, len(edges) // 4, min(edges), max(edges), diag))
    for fr, mu, what in (("frictionless", 0, "frictionless"), ("friction", 0.15, "Coulomb friction mu = 0.15")):
        head = HEAD.format(what=what, fr=fr, mesh=MESH, np=np_, nd=nd, ef=E_FACTOR,
                           fric=", mu 0.15 on both pairs" if mu else ", frictionless")
        path = os.path.join(ROOT, "cases", "hemisphere_bodies_%s.opts" % fr)
        with open(path, "w") as f:
            for h in head.splitlines():
                f.write("# %s\n" % h)
            f.write("\n".join(case_text(fr, mu, ne)) + "\n")
        print("wrote cases/hemisphere_bodies_%s.opts" % fr)
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
