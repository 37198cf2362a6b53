#!/usr/bin/env python3
"""Writes the NUMISHEET'93 square cup (mild steel, coarse mesh) with an elastic blank holder: the
blank of cases/sheets/numisheet93_cup_coarse.inp (its nodes, elements and sets, ids unchanged) and a
steel plate above its flange, a second body in contact with the blank through a contact pair, the
rigid holder tool reduced to a flat plane pressing on the plate's top with the 19.6 kN.

usage: make_cup_elastic_holder.py

  cases/meshes/numisheet93_cup_coarse_holder.inp      blank (element set blank) + plate (holder_plate)
  cases/tools/numisheet93_cup_holder_plate.tool       the plane z = 0.78 + H over the plate's top
  cases/numisheet93_cup_coarse_elastic_holder.opts    the case (cases/numisheet93_cup_coarse.opts with
                                                      the plate, its pair and its symmetry conditions)

The plate (quarter model) covers the region where the rigid holder of
cases/tools/numisheet93_cup_holder.tool acts: outside the die opening's rounded square (half side
45, plan corner radius 20 about (25, 25)) up to the blank's extent, the quarter's outer square
75 x 75. Mapped hexahedra in three blocks: x >= 45, y <= 25 (12 x 10 of 2.5 mm, the blank's grid),
its mirror y >= 45, x <= 25, and the corner between them, an O-grid sector between the arc of
radius 20 and the outer square's two sides (NC divisions around, 12 across: 1.96 mm on the arc,
6.25 mm on the outer square, straight radial lines); NL layers through the thickness H. Its bottom
face z = t touches the blank's top. Element size in the plane: the blank's 2.5 mm in the straight
parts, 2 to 6 mm in the corner (coarsest at the outer corner, which the blank's corner leaves as it
draws in). The .inp writer and the element checks are scripts/make_pair_cases.py's (Deck).
"""
import math
import os
import sys

import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.abspath(os.path.join(HERE, ".."))
sys.path.insert(0, HERE)
from inpdeck import read_inp  # noqa: E402
from make_pair_cases import Deck  # noqa: E402

BLANK = "cases/sheets/numisheet93_cup_coarse.inp"
MESH = "cases/meshes/numisheet93_cup_coarse_holder.inp"
TOOL = "cases/tools/numisheet93_cup_holder_plate.tool"
CASE = "cases/numisheet93_cup_coarse_elastic_holder.opts"
RIGID = "cases/numisheet93_cup_coarse.opts"

T = 0.78            # the blank's thickness: the plate's bottom face
HALF = 75.0         # the quarter blank's side; the plate's outer square
OPEN = 45.0         # the die face's inner edge: x = 45 (and y = 45) on the straight sides
RC = 20.0           # its plan corner radius about (C0, C0)
C0 = OPEN - RC      # 25
H = 25.0            # the plate's thickness
NL = 3              # element layers through it
NR = 12             # divisions across the ring (45 to 75: 2.5 mm on the straight sides)
NS = 10             # along the straight sides (0 to 25: 2.5 mm)
NC = 16             # around the corner sector
E_PLATE, NU_PLATE = 206000.0, 0.3
MU = 0.144          # the blank and the plate: the rigid holder's friction
MU_TOP = 0.0        # the plane on the plate's top (see the case's header)
F_QUARTER = 4900.0  # 19.6 kN on the quarter model
NID0, EID0 = 100001, 100001


def plate_2d():
    """the plate's quadrilaterals in the plane: points (P, 2) and quads (node indices, counterclockwise)"""
    pts, index = [], {}

    def pid(p):
        key = (round(p[0], 9), round(p[1], 9))
        if key not in index:
            index[key] = len(pts)
            pts.append((float(p[0]), float(p[1])))
        return index[key]

    quads = []
    # x side: x in [45, 75], y in [0, 25]
    A = [[pid((OPEN + (HALF - OPEN) * i / NR, C0 * j / NS)) for j in range(NS + 1)] for i in range(NR + 1)]
    quads += [(A[i][j], A[i + 1][j], A[i + 1][j + 1], A[i][j + 1]) for i in range(NR) for j in range(NS)]
    # y side: y in [45, 75], x in [0, 25]
    B = [[pid((C0 * j / NS, OPEN + (HALF - OPEN) * i / NR)) for j in range(NS + 1)] for i in range(NR + 1)]
    quads += [(B[i][j], B[i][j + 1], B[i + 1][j + 1], B[i + 1][j]) for i in range(NR) for j in range(NS)]
    # corner sector: arc of radius RC about (C0, C0), angle 0 to 90, to the outer square's sides
    # (75, 25) -> (75, 75) -> (25, 75) by arc length; straight lines across, NR divisions
    L = 2 * (HALF - C0)
    Cs = []
    for k in range(NC + 1):
        th = 0.5 * math.pi * k / NC
        pin = np.array((C0 + RC * math.cos(th), C0 + RC * math.sin(th)))
        s = L * k / NC
        pout = np.array((HALF, C0 + s)) if s <= HALF - C0 else np.array((HALF - (s - (HALF - C0)), HALF))
        Cs.append([pid(pin + (pout - pin) * r / NR) for r in range(NR + 1)])
    quads += [(Cs[k][r], Cs[k][r + 1], Cs[k + 1][r + 1], Cs[k + 1][r]) for k in range(NC) for r in range(NR)]
    return np.array(pts), quads


def build():
    X, elems, nsets = read_inp(os.path.join(ROOT, BLANK))
    d = Deck()
    for n in sorted(X):
        d.node(n, X[n])
    for eid, conn, es in elems:
        d.hexa(eid, conn, es)
    for name, ids in nsets.items():
        d.nset(name, ids)
    P, Q = plate_2d()
    z = [T + H * k / NL for k in range(NL + 1)]
    nid = lambda p, k: NID0 + p + len(P) * k
    for k in range(NL + 1):
        for p in range(len(P)):
            d.node(nid(p, k), (P[p, 0], P[p, 1], z[k]))
    e = EID0
    for k in range(NL):
        for q in Q:
            d.hexa(e, [nid(a, k) for a in q] + [nid(a, k + 1) for a in q], "holder_plate")
            e += 1
    d.nset("holder_bottom", [nid(p, 0) for p in range(len(P))])
    d.nset("holder_top", [nid(p, NL) for p in range(len(P))])
    d.nset("holder_symx", [nid(p, k) for k in range(NL + 1) for p in range(len(P)) if P[p, 0] == 0.0])
    d.nset("holder_symy", [nid(p, k) for k in range(NL + 1) for p in range(len(P)) if P[p, 1] == 0.0])
    # the blank's top nodes the rigid holder's face covers initially (x >= 45 or y >= 45 or outside
    # the corner arc): the nodes a holder can press on at the start
    top = set(nsets["top"])
    under = [n for n in top if X[n][0] >= OPEN - 1e-9 or X[n][1] >= OPEN - 1e-9 or
             (X[n][0] >= C0 and X[n][1] >= C0 and math.hypot(X[n][0] - C0, X[n][1] - C0) >= RC - 1e-9)]
    d.nset("flange_top", under)
    return d, P, Q


def tool_file():
    zt = T + H
    with open(os.path.join(ROOT, TOOL), "w") as f:
        f.write("# NUMISHEET'93 square cup, elastic blank holder: the press's plane on the plate's top z = %g\n"
                "# (quarter, beyond the plate's 75 x 75 by 10 mm), normal -z; written by\n"
                "# scripts/make_cup_elastic_holder.py\n" % zt)
        f.write("patches 1\npatch0_type plane\npatch0_origin -10,-10,%.10g\npatch0_e1 1,0,0\npatch0_e2 0,1,0\n"
                "patch0_range 0,95,0,95\npatch0_sense -1\n" % zt)


def case(d, nplate_e, nplate_n):
    rigid = [l.rstrip("\n") for l in open(os.path.join(ROOT, RIGID)) if l.strip() and not l.startswith("#")]
    out = []
    for l in rigid:
        key = l.split()[0]
        if key == "-mesh_file":
            l = "-mesh_file " + MESH
        elif key == "-tool_holder_file":
            l = "-tool_holder_file " + TOOL
        elif key == "-tool_holder_contact_set":
            l = "-tool_holder_contact_set holder_top"
        elif key == "-tool_holder_friction":
            l = "-tool_holder_friction %g" % MU_TOP
        elif key == "-bc_names":
            l = "-bc_names symx,symy,holder_symx,holder_symy"
        elif key in ("-stage_close_bcs", "-stage_draw_bcs"):
            l = key + " symx,symy,holder_symx,holder_symy"
        elif key == "-output_dir":
            l = "-output_dir out/numisheet93_cup_coarse_elastic_holder"
        out.append(l)
        if key == "-bc_symy_components":
            out += ["-bc_holder_symx_components x", "-bc_holder_symy_components y"]
        if key == "-model_symmetry":
            out += ["-body_names holder", "-body_holder_set holder_plate",
                    "-body_holder_material_type j2",
                    "-body_holder_material_E %g" % E_PLATE, "-body_holder_material_nu %g" % NU_PLATE,
                    "-body_holder_material_hardening linear", "-body_holder_material_yield 1e12",
                    "-pair_names ph", "-pair_ph_slave top", "-pair_ph_master holder_bottom",
                    "-pair_ph_friction %g" % MU]
    head = """NUMISHEET'93 square cup deep drawing, mild steel, coarse mesh, with an ELASTIC blank holder: the
case cases/numisheet93_cup_coarse.opts (material, punch, die, stages close and draw, friction 0.144,
the holder's force 19.6 kN, 4900 N on the quarter, ramped over the close stage) with a steel plate
between the holder and the blank. Mesh %s (scripts/make_cup_elastic_holder.py):
the blank of cases/sheets/numisheet93_cup_coarse.inp (element set blank, its nodes, elements and sets
unchanged) and the plate (element set holder_plate, %d hexahedra, %d nodes): the quarter of a ring
outside the die opening's rounded square (half side 45, plan corner radius 20) up to the blank's
75 x 75, thickness %g in %d layers, its bottom face z = %g on the blank's top, elastic
(E %g, nu %g; J2 with yield stress 1e12, Hencky law).
Contact: pair ph, the blank's top nodes (slave) on the plate's bottom faces (holder_bottom), Coulomb
mu = %g as the rigid holder's, automatic penalty; the holder tool is the plane z = %g
(%s) pressing on the plate's top nodes (holder_top), force-driven
as in the rigid case (-tool_holder_force_z -4900, same amplitude), frictionless (mu = %g: the press
holds the plate by its force only; in the plane the plate is held by its symmetry conditions,
holder_symx x and holder_symy y, as the quarter of a closed ring). The punch on the blank's top,
the die on its bottom, as in the rigid case.
Written by scripts/make_cup_elastic_holder.py; results: doc/notes/elastic-holder.md.""" % (
        MESH, nplate_e, nplate_n, H, NL, T, E_PLATE, NU_PLATE, MU, T + H, TOOL, MU_TOP)
    with open(os.path.join(ROOT, CASE), "w") as f:
        for h in head.splitlines():
            f.write("# %s\n" % h)
        f.write("\n".join(out) + "\n")


def main():
    d, P, Q = build()
    nplate_e, nplate_n = len(Q) * NL, len(P) * (NL + 1)
    d.write(os.path.join(ROOT, MESH),
            "NUMISHEET'93 square cup, coarse: the quarter blank 75 x 75 x %g, 30 x 30 x 1 hexahedra (element\n"
            "set blank, ids 1-, as %s) and an elastic blank holder plate (element\n"
            "set holder_plate, ids %d-; nodes %d-): the quarter ring outside the die opening's rounded square\n"
            "(half side %g, corner radius %g about (%g, %g)) up to the outer square %g x %g, thickness %g in %d\n"
            "layers, bottom face z = %g. Blank sets: top, bottom, symx, symy, pin, rim, flange_top (its top nodes\n"
            "under the rigid holder's face at the start). Plate sets: holder_bottom, holder_top,\n"
            "holder_symx (x = 0), holder_symy (y = 0). Written by scripts/make_cup_elastic_holder.py."
            % (T, BLANK, EID0, NID0, OPEN, RC, C0, C0, HALF, HALF, H, NL, T))
    tool_file()
    case(d, nplate_e, nplate_n)
    nv, ne, per, sj, asp = d.stats()
    print("%s: %d nodes, %d hexahedra (%s); smallest scaled Jacobian %.3f, largest edge ratio %.1f"
          % (MESH, nv, ne, ", ".join("%s %d" % kv for kv in per.items()), sj, asp))
    print("  node sets: " + ", ".join("%s %d" % (k, len(v)) for k, v in d.nsets.items()))
    # in-plane sizes of the plate's faces
    e = []
    for q in Q:
        for a in range(4):
            e.append(np.linalg.norm(P[q[(a + 1) % 4]] - P[q[a]]))
    print("  plate: %d quadrilaterals per layer, edges %.2f to %.2f mm in the plane, %.2f through the thickness"
          % (len(Q), min(e), max(e), H / NL))
    print("wrote %s, %s, %s" % (MESH, TOOL, CASE))
    return 0


if __name__ == "__main__":
    sys.exit(main())
