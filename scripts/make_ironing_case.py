#!/usr/bin/env python3
"""Writes the ironing case: a deformable die pressed into an elastic block and dragged along it
with Coulomb friction (mu = 0.3), two bodies in contact through a pair (node to surface).

usage: make_ironing_case.py [--nx N --nz N --h-top H --ndx N --ndz N] [--thickness T] [--ny N]
                            [--slave block|die] [--mesh PATH --case PATH]

  cases/meshes/ironing.inp, cases/ironing.opts (the defaults); a study's variants elsewhere
  (--mesh, --case): --ny 5 --thickness 1 is the reference's own 3D slab (y fixed on y = 0 only)

The problem is the plane-strain "shallow ironing" benchmark of the mortar contact literature
(Fischer & Wriggers 2006; Hartmann et al. 2009; Poulios & Renard 2015), in the form the Kratos
Examples repository runs it (contact_structural_mechanics/validation/shallow_ironing_3D: README,
data/setup.png, source/ProjectParameters_literature.json, StructuralMaterials.json), which also
holds the reference force curves this case is compared with (data/solution_frictional.png, curves
"F ref.", digitized into doc/reference/ironing_force_reference.csv). Not the Puso & Laursen (2004) /
Yang, Laursen & Meng (2005) ironing, whose force curves were found nowhere to compare with
(doc/notes/ironing.md gives that problem's data and sources):

  block 12 x 4, bottom fixed; die 1.2 wide, its bottom edge a circular arc of radius 0.75 (the
  sagitta 0.3 over the die's width), 1.2 high from its lowest point, its left side 0.2 from the
  block's left end, its lowest point 0.2 above the block; neo-Hookean, E = 68.96e8 (die) and
  68.96e7 (block), nu = 0.32 both; mu = 0.3. The die's top moves down by 1.0 over t in [0, 1]
  (contact from t = 0.2: a press of 0.8), then along the block by 10 over t in [1, 2].

Units: the moduli are given in units of 1e8 (68.96 and 6.896): forces scale with E, so the
forces of this case are those of the reference in units of 1e8, per unit thickness once divided
by the thickness T of the one element through y.

Plane strain: one element through y (y in [0, T]), y fixed on every node. Coordinates: x along
the block, z up; the block's top is z = 0, its bottom z = -4; the die's lowest point is z = 0.2.

The material law is this code's Hencky law (J2 with a yield stress of 1e12: elastic), the
reference's neo-Hookean. Both have the same small-strain moduli (E, nu): they agree to first order
in the strain and differ at the second (doc/notes/ironing.md).

Pair p: slave block_top (the block's top, 0.05 along x: the finer surface), master die_surface (the
die's arc and sides, 0.1 along the arc: 7.6 degrees between facets). The automatic penalty is the
slave's, E_block A / h (0.34 per node): the press leaves a penetration of about 0.03. Newton is
converged at 1e-3 of the internal forces' scale (-newton_force_tol 1e-3): a slave node on a crease
of the faceted master changes face, and its force turns by the crease's angle, from one iterate to
the next, which leaves a residual of that order (doc/notes/ironing.md, with the runs of the other
choices: the die as the slave, a stiffer penalty, two-pass, a finer mesh).

The .inp deck is Abaqus-style (*NODE, *ELEMENT TYPE=C3D8, *NSET), each hexahedron checked
positive by scripts/make_pair_cases.py's Deck.
"""
import argparse
import math
import os
import sys

import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)
from make_pair_cases import Deck, geometric  # noqa: E402

ROOT = os.path.abspath(os.path.join(HERE, ".."))
MESH = "cases/meshes/ironing.inp"
CASE = "cases/ironing.opts"

# ------------------------------------------------------------------ the problem (see the header)
LB, HB = 12.0, 4.0            # block length and height
W_DIE, R_DIE, H_DIE = 1.2, 0.75, 1.2   # die width, arc radius, height above its lowest point
X_DIE = 0.2                   # the die's left side
GAP = 0.2                     # the die's lowest point above the block
PRESS, SLIDE = 1.0, 10.0      # the die top's travel: down over t in [0, 1], along x over [1, 2]
E_DIE, E_BLOCK, NU = 68.96, 6.896, 0.32   # units of 1e8 (the reference's 68.96e8, 68.96e7)
MU = 0.3


def grids(nx, nz, h_top):
    """the block's x (uniform) and z (geometric from h_top at the top) coordinates"""
    xs = np.linspace(0.0, LB, nx + 1)
    zs = -np.concatenate([[0.0], np.cumsum(geometric(h_top, HB, nz))])
    zs[-1] = -HB
    return xs, zs


def die_bottom(x):
    """z of the die's arc at x (its lowest point at z = GAP, x = X_DIE + W_DIE/2)"""
    xc = X_DIE + W_DIE / 2
    return GAP + R_DIE - math.sqrt(R_DIE ** 2 - (x - xc) ** 2)


def mesh(nx, nz, h_top, ndx, ndz, T, ny=1):
    """the deck: ny elements through y in [0, T] (1: plane strain with y fixed on every node; more: the
    Kratos slab of thickness T with y fixed on y = 0 only, set y0)"""
    d = Deck()
    sets = {k: [] for k in ("block_top", "block_bottom", "die_surface", "die_top", "all", "y0")}
    ys = np.linspace(0.0, T, ny + 1)

    def extrude(P2, quads, nid0, eid0, elset):
        ids = np.zeros((len(P2), ny + 1), int)
        for l, y in enumerate(ys):
            for p, (x, z) in enumerate(P2):
                ids[p, l] = d.node(nid0 + p + l * len(P2), (x, y, z))
        for l in range(ny):
            for e, q in enumerate(quads):
                d.hexa(eid0 + e + l * len(quads), [ids[q[0], l], ids[q[1], l], ids[q[2], l], ids[q[3], l],
                                                   ids[q[0], l + 1], ids[q[1], l + 1], ids[q[2], l + 1], ids[q[3], l + 1]], elset)
        sets["all"].extend(ids.ravel())
        sets["y0"].extend(ids[:, 0])
        return ids

    # the block, structured: i along x, j down from the top
    xs, zs = grids(nx, nz, h_top)
    P = np.array([(xs[i], zs[j]) for j in range(nz + 1) for i in range(nx + 1)])
    bi = lambda i, j: i + (nx + 1) * j
    Q = [(bi(i, j), bi(i + 1, j), bi(i + 1, j + 1), bi(i, j + 1)) for j in range(nz) for i in range(nx)]
    ids = extrude(P, Q, 1, 1, "BLOCK")
    assert (nx + 1) * (nz + 1) * (ny + 1) < 100000 and nx * nz * ny < 100000, "ids would reach the die's 100001"
    for i in range(nx + 1):
        sets["block_top"].extend(ids[bi(i, 0)])
        sets["block_bottom"].extend(ids[bi(i, nz)])

    # the die, structured: i along x (uniform), j up from the arc to the
    # flat top, geometric (the first layer as thick as the spacing across)
    xd = np.linspace(X_DIE, X_DIE + W_DIE, ndx + 1)
    ztop = GAP + H_DIE
    pts, grid = [], np.zeros((ndx + 1, ndz + 1), int)
    for i in range(ndx + 1):
        zb = die_bottom(xd[i])
        dz = geometric(W_DIE / ndx, ztop - zb, ndz)
        zz = zb + np.concatenate([[0.0], np.cumsum(dz)])
        zz[-1] = ztop
        for j in range(ndz + 1):
            grid[i, j] = len(pts)
            pts.append((xd[i], zz[j]))
    P = np.array(pts)
    Q = [(grid[i, j], grid[i + 1, j], grid[i + 1, j + 1], grid[i, j + 1]) for j in range(ndz) for i in range(ndx)]
    did = extrude(P, Q, 100001, 100001, "DIE")
    for i in range(ndx + 1):
        sets["die_surface"].extend(did[grid[i, 0]])
        sets["die_top"].extend(did[grid[i, ndz]])
    for j in range(ndz):          # both sides, up to (not with) the top's corner
        sets["die_surface"].extend(did[grid[0, j]])
        sets["die_surface"].extend(did[grid[ndx, j]])
    for k, v in sets.items():
        d.nset(k, v)
    info = dict(block_dx=LB / nx, block_dz=(zs[0] - zs[1], zs[-2] - zs[-1]), die_dx=W_DIE / ndx,
                die_side=(P[grid[0, 1], 1] - P[grid[0, 0], 1], P[grid[0, ndz], 1] - P[grid[0, ndz - 1], 1]))
    return d, info


def main(argv):
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--nx", type=int, default=240, help="block elements along x (default 240: 0.05)")
    ap.add_argument("--nz", type=int, default=20, help="block elements through the height (default 20)")
    ap.add_argument("--h-top", type=float, default=0.05, help="the block's top layer (default 0.05)")
    ap.add_argument("--ndx", type=int, default=12, help="die elements across (default 12: 0.1)")
    ap.add_argument("--ndz", type=int, default=8, help="die elements up (default 8)")
    ap.add_argument("--slave", choices=("block", "die"), default="block",
                    help="the pair's slave: the block's top (default) or the die's surface")
    ap.add_argument("--thickness", type=float, default=0.1, help="T, the one element through y (default 0.1)")
    ap.add_argument("--ny", type=int, default=1, help="elements through y (default 1: plane strain; more: y fixed on y = 0 only)")
    ap.add_argument("--mesh", default=MESH, help="the deck to write (default %s; a study's variant elsewhere)" % MESH)
    ap.add_argument("--case", default=CASE, help="the options file to write (default %s)" % CASE)
    a = ap.parse_args(argv)
    d, info = mesh(a.nx, a.nz, a.h_top, a.ndx, a.ndz, a.thickness, a.ny)
    nv, ne, per, sj, asp = d.stats()
    d.write(os.path.join(ROOT, a.mesh),
            "Ironing (plane strain, one element through y): an elastic die pressed into an elastic block\n"
            "and dragged along it. BLOCK [0,%g] x [0,%g] x [-%g,0], %d x 1 x %d hexahedra (ids 1-); DIE\n"
            "x in [%g,%g], its bottom a circular arc of radius %g (lowest point z = %g), top z = %g,\n"
            "%d x 1 x %d hexahedra (ids 100001-). Node sets: block_top, block_bottom, die_surface (arc and\n"
            "sides), die_top, all. Written by scripts/make_ironing_case.py (the problem: its header)."
            % (LB, a.thickness, HB, a.nx, a.nz, X_DIE, X_DIE + W_DIE, R_DIE, GAP, GAP + H_DIE, a.ndx, a.ndz))
    T = a.thickness
    head = """Ironing: an elastic die pressed into an elastic block and dragged along it, Coulomb friction mu = 0.3
(the plane-strain "shallow ironing" benchmark: Fischer & Wriggers 2006, Poulios & Renard 2015; the setup
and the reference force curves of the Kratos Examples repository, validation/shallow_ironing_3D).
Mesh %s (scripts/make_ironing_case.py, whose header gives the problem and its sources):
block 12 x 4 (%d x %d hexahedra, %g along x, top layer %g), die 1.2 wide with a bottom arc of radius 0.75
(%d x %d, %g across), its lowest point 0.2 above the block; plane strain, one element through y
(T = %g), y fixed on every node. Die E = %g, block E = %g (units of 1e8: the reference's 68.96e8 and
68.96e7), nu = %g; elastic Hencky law (J2, yield stress 1e12) where the reference is neo-Hookean.
Load: die_top down by %g over t in [0, 1] (contact from t = 0.2), then along x by %g over [1, 2].
Pair p: slave %s, master %s, mu 0.3, automatic penalty; Newton converged at 1e-3 of the internal forces'
scale (-newton_force_tol 1e-3: a slave node at a crease of the faceted master; doc/notes/ironing.md).
Forces: history.csv press_fz and drag_fx (the reactions on the die's top), or contact.csv fx, fz (the
resultant on the slave set: the die on the block), divided by T: per unit thickness, in units of 1e8 like the reference.
Compare: scripts/ironing_compare.py out/ironing (doc/notes/ironing.md, doc/figures/ironing.png).""" % (
        a.mesh, a.nx, a.nz, LB / a.nx, a.h_top, a.ndx, a.ndz, W_DIE / a.ndx, T, E_DIE, E_BLOCK, NU, PRESS, SLIDE,
        "block_top" if a.slave == "block" else "die_surface", "die_surface" if a.slave == "block" else "block_top")
    lines = ["-mesh_type inp", "-mesh_file " + a.mesh,
             "-body_names die,block",
             "-body_die_set DIE", "-body_die_material_E %g" % E_DIE, "-body_die_material_nu %g" % NU,
             "-body_die_material_hardening linear", "-body_die_material_yield 1e12",
             "-body_block_set BLOCK", "-body_block_material_E %g" % E_BLOCK, "-body_block_material_nu %g" % NU,
             "-body_block_material_hardening linear", "-body_block_material_yield 1e12",
             "-bc_names base,plane,press,drag",
             "-bc_base_set block_bottom", "-bc_base_components x,y,z",
             "-bc_plane_set %s" % ("all" if a.ny == 1 else "y0"), "-bc_plane_components y",
             "-bc_press_set die_top", "-bc_press_components z", "-bc_press_values %g" % -PRESS,
             "-bc_press_amplitude 0,0,1,1",
             "-bc_drag_set die_top", "-bc_drag_components x", "-bc_drag_values %g" % SLIDE,
             "-bc_drag_amplitude 0,0,1,0,2,1",
             "-pair_names p",
             "-pair_p_slave %s" % ("block_top" if a.slave == "block" else "die_surface"),
             "-pair_p_master %s" % ("die_surface" if a.slave == "block" else "block_top"),
             "-pair_p_friction %g" % MU,
             "-newton_force_tol 1e-3",
             "-stage_names press,slide",
             "-stage_press_duration 1", "-stage_press_steps 20", "-stage_press_dt_max 0.05",
             "-stage_slide_duration 1", "-stage_slide_steps 100", "-stage_slide_dt_max 0.01",
             "-output_dir out/ironing",
             "-output_interval 10"]
    with open(os.path.join(ROOT, a.case), "w") as f:
        for line in head.splitlines():
            f.write("# %s\n" % line)
        for line in lines:
            f.write(line + "\n")
    print("wrote %s (%d nodes, %d hexahedra: %s; smallest scaled Jacobian %.3f, largest aspect %.2f) and %s"
          % (a.mesh, nv, ne, ", ".join("%s %d" % kv for kv in per.items()), sj, asp, a.case))
    print("  block dx %.3g, dz %.3g (top) to %.3g; die dx %.3g, side layers %.3g to %.3g; sets %s"
          % (info["block_dx"], info["block_dz"][0], info["block_dz"][1], info["die_dx"], info["die_side"][0],
             info["die_side"][1], ", ".join("%s %d" % (k, len(v)) for k, v in d.nsets.items())))
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
