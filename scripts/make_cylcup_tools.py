#!/usr/bin/env python3
"""Tool files of the cylindrical cup of doc/tutorial.md (cases/cylindrical_cup.opts): a flat punch
of radius 25 with a 5 mm profile radius, a die of opening radius 26.5 (clearance 1.5 t) with a 5 mm
shoulder, a flat blank holder; the blank (1 mm thick) lies at 0 <= z <= 1, the punch and the holder
above it, the die below. Quarter model (x, y >= 0): every revolved patch spans the azimuths -10 to
100 degrees, past the symmetry planes, so that no node on them lies beside an open edge.

usage: make_cylcup_tools.py [OUTDIR]   (default cases/tools)"""
import math
import os
import sys

T = 1.0                   # blank thickness
RP, RP_PROF = 25.0, 5.0   # punch radius, punch profile radius
RD, RD_SHOULDER = 26.5, 5.0  # die opening radius, die shoulder radius
R_OUT = 65.0              # outer radius of the die's face and of the holder
R_HOLD = 32.0             # inner radius of the holder
PHI0, PHI1 = -10.0, 100.0  # azimuths of the revolved patches (degrees)
A = 8.0                   # half side of the punch's central flat square


def pt(r, phi, z):
    p = math.radians(phi)
    return "%.12g,%.12g,%.12g" % (r * math.cos(p), r * math.sin(p), z)


def annulus(k, r0, r1, z, sense):
    """a Coons patch: the annulus r0 <= r <= r1 at height z between the azimuths PHI0, PHI1
    (xi along the azimuth, eta outwards: x_xi x x_eta points to -z)"""
    c = "0,0,%.12g" % z
    return [f"patch{k}_type coons",
            f"patch{k}_bottom_type arc", f"patch{k}_bottom_points {pt(r0, PHI0, z)},{pt(r0, PHI1, z)},{c}",
            f"patch{k}_top_type arc", f"patch{k}_top_points {pt(r1, PHI0, z)},{pt(r1, PHI1, z)},{c}",
            f"patch{k}_left_type line", f"patch{k}_left_points {pt(r0, PHI0, z)},{pt(r1, PHI0, z)}",
            f"patch{k}_right_type line", f"patch{k}_right_points {pt(r0, PHI1, z)},{pt(r1, PHI1, z)}",
            f"patch{k}_sense {sense}"]


def revolved(k, kind, z0, radius=None, major=None, minor=None, rng=None, sense=1):
    out = [f"patch{k}_type {kind}", f"patch{k}_center 0,0,{z0:.12g}", f"patch{k}_axis 0,0,1", f"patch{k}_ref 1,0,0"]
    if kind == "cylinder":
        out.append(f"patch{k}_radius {radius:.12g}")
    else:
        out += [f"patch{k}_major {major:.12g}", f"patch{k}_minor {minor:.12g}"]
    out += [f"patch{k}_range {rng}", f"patch{k}_sense {sense}"]
    return out


def punch():
    rf, z = RP - RP_PROF, T
    p = ["patches 5",
         # the flat head: a square about the axis and two Coons patches out to the profile's start
         "patch0_type plane", f"patch0_origin 0,0,{z:.12g}", "patch0_e1 1,0,0", "patch0_e2 0,1,0",
         f"patch0_range {-A},{A},{-A},{A}", "patch0_sense -1"]
    # east (-45..45 degrees) and north (45..135): xi outwards, eta along the azimuth: x_xi x x_eta = +z
    for k, (x0, y0), (x1, y1), ph0, ph1 in ((1, (A, -A), (A, A), -45.0, 45.0), (2, (A, A), (-A, A), 45.0, 135.0)):
        e0, e1 = pt(rf, ph0, z), pt(rf, ph1, z)
        p += [f"patch{k}_type coons",
              f"patch{k}_bottom_type line", f"patch{k}_bottom_points {x0:.12g},{y0:.12g},{z:.12g},{e0}",
              f"patch{k}_top_type line", f"patch{k}_top_points {x1:.12g},{y1:.12g},{z:.12g},{e1}",
              f"patch{k}_left_type line", f"patch{k}_left_points {x0:.12g},{y0:.12g},{z:.12g},{x1:.12g},{y1:.12g},{z:.12g}",
              f"patch{k}_right_type arc", f"patch{k}_right_points {e0},{e1},0,0,{z:.12g}",
              f"patch{k}_sense -1"]
    # the profile (a torus below its core circle, tube angles -90..0) and the wall
    p += revolved(3, "torus", T + RP_PROF, major=rf, minor=RP_PROF, rng=f"{PHI0},{PHI1},-90,0")
    p += revolved(4, "cylinder", T + RP_PROF, radius=RP, rng=f"{PHI0},{PHI1},0,80")
    return "# cylindrical cup (doc/tutorial.md): flat punch, radius 25, profile radius 5; written by scripts/make_cylcup_tools.py\n" + "\n".join(p) + "\n"


def die():
    rs = RD + RD_SHOULDER
    p = ["patches 3"] + annulus(0, rs, R_OUT, 0.0, -1)
    p += revolved(1, "torus", -RD_SHOULDER, major=rs, minor=RD_SHOULDER, rng=f"{PHI0},{PHI1},90,180")
    p += revolved(2, "cylinder", -RD_SHOULDER, radius=RD, rng=f"{PHI0},{PHI1},-80,0", sense=-1)
    return "# cylindrical cup (doc/tutorial.md): die, opening radius 26.5, shoulder radius 5, face z = 0; written by scripts/make_cylcup_tools.py\n" + "\n".join(p) + "\n"


def holder():
    p = ["patches 1"] + annulus(0, R_HOLD, R_OUT, T, 1)
    return "# cylindrical cup (doc/tutorial.md): blank holder, face z = t over the die's face; written by scripts/make_cylcup_tools.py\n" + "\n".join(p) + "\n"


if __name__ == "__main__":
    out = sys.argv[1] if len(sys.argv) > 1 else os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "cases", "tools")
    for name, text in (("punch", punch()), ("die", die()), ("holder", holder())):
        with open(os.path.join(out, f"cylcup_{name}.tool"), "w") as f:
            f.write(text)
