#!/usr/bin/env python3
"""Options of the benchmark's tools built from Coons patches, as the method's paper did: the
quarter hemispherical punch from 3 Coons patches of great-circle arcs plus a plane (its flat
shoulder at the equator), the die fillet from Coons patches of 4 arcs.

usage: coons_tools.py [--punch-radius 50.8] [--fillet 6.35] [--clamp 59.18] [--thickness 1.0]
                      [--travel 40] [--split N] [--die-sectors M] [--report]
--split N divides each punch patch into N x N Coons patches (the arcs of a finer net of great
circles) and --die-sectors M the die fillet into M patches along the azimuth; the paper's is
N = M = 1, whose Coons interiors lie up to 0.52 mm inside the sphere and 0.32 mm off the torus.
Prints the options on standard output."""
import argparse
import math
import sys

import numpy as np

ap = argparse.ArgumentParser()
ap.add_argument("--punch-radius", type=float, default=50.8)
ap.add_argument("--fillet", type=float, default=6.35)
ap.add_argument("--clamp", type=float, default=59.18)
ap.add_argument("--thickness", type=float, default=1.0)
ap.add_argument("--travel", type=float, default=40.0)
ap.add_argument("--split", type=int, default=1)
ap.add_argument("--die-sectors", type=int, default=1, help="Coons patches of the die fillet along the azimuth (the paper: 1)")
ap.add_argument("--report", action="store_true", help="print the largest distance of the Coons punch from the sphere to stderr")
a = ap.parse_args()

R = a.punch_radius
c = np.array([0.0, 0.0, -R])  # the pole touches the sheet's bottom face z = 0


def on_sphere(d):
    d = np.asarray(d, float)
    return c + R * d / np.linalg.norm(d)


def slerp_dir(p, q, t):
    """point at fraction t of the great-circle arc from p to q (points on the sphere)"""
    u, v = (p - c) / R, (q - c) / R
    w = math.acos(max(-1.0, min(1.0, float(u @ v))))
    return c + R * (math.sin((1 - t) * w) * u + math.sin(t * w) * v) / math.sin(w)


def fmt(*pts):
    return ",".join("%.15g" % x for p in pts for x in p)


N, X, Y = on_sphere([0, 0, 1]), on_sphere([1, 0, 0]), on_sphere([0, 1, 0])
G = on_sphere([1, 1, 1])
Mzx, Mzy, Mxy = on_sphere([1, 0, 1]), on_sphere([0, 1, 1]), on_sphere([1, 1, 0])
# corners (0,0), (1,0), (1,1), (0,1); x_xi x x_eta points out of the sphere
quads = [(N, Mzx, G, Mzy), (X, Mxy, G, Mzx), (Y, Mzy, G, Mxy)]


def bilinear_on_sphere(q, s, t):
    """a point of the quad's net of arcs: the arc between the points at s on the two xi-sides"""
    p00, p10, p11, p01 = q
    b = slerp_dir(p00, p10, s)  # bottom
    tp = slerp_dir(p01, p11, s)  # top
    return slerp_dir(b, tp, t)


lines = ["-tool_names punch,die", f"-tool_punch_motion 0,0,{a.travel:g}"]
patches = []
n = a.split
for q in quads:
    for i in range(n):
        for j in range(n):
            s0, s1, t0, t1 = i / n, (i + 1) / n, j / n, (j + 1) / n
            p00, p10 = bilinear_on_sphere(q, s0, t0), bilinear_on_sphere(q, s1, t0)
            p11, p01 = bilinear_on_sphere(q, s1, t1), bilinear_on_sphere(q, s0, t1)
            patches.append((p00, p10, p11, p01))
lines.append(f"-tool_punch_patches {len(patches) + 1}")
for k, (p00, p10, p11, p01) in enumerate(patches):
    pre = f"-tool_punch_patch{k}"
    lines += [f"{pre}_type coons",
              f"{pre}_bottom_type arc", f"{pre}_bottom_points {fmt(p00, p10, c)}",
              f"{pre}_top_type arc", f"{pre}_top_points {fmt(p01, p11, c)}",
              f"{pre}_left_type arc", f"{pre}_left_points {fmt(p00, p01, c)}",
              f"{pre}_right_type arc", f"{pre}_right_points {fmt(p10, p11, c)}"]
k = len(patches)
lines += [f"-tool_punch_patch{k}_type plane", f"-tool_punch_patch{k}_origin 0,0,{-R:.15g}",
          f"-tool_punch_patch{k}_e1 1,0,0", f"-tool_punch_patch{k}_e2 0,1,0",
          f"-tool_punch_patch{k}_range 0,{1.2 * a.clamp:.6g},0,{1.2 * a.clamp:.6g}"]
# die fillet: tangent to the die face z = t at the clamp radius, opening radius clamp - fillet;
# --die-sectors Coons patches of 4 arcs each (azimuthal arcs at the bottom and at the opening,
# profile arcs of the fillet at the sector's ends); x_xi x x_eta points into the die: sense -1
t, rf, Rc = a.thickness, a.fillet, a.clamp
zc, Ro = t + rf, Rc - rf
lines.append(f"-tool_die_patches {a.die_sectors}")
for k in range(a.die_sectors):
    a0, a1 = 0.5 * math.pi * k / a.die_sectors, 0.5 * math.pi * (k + 1) / a.die_sectors
    e0, e1 = np.array([math.cos(a0), math.sin(a0), 0.0]), np.array([math.cos(a1), math.sin(a1), 0.0])
    z0, z1 = np.array([0, 0, t]), np.array([0, 0, zc])
    pre = f"-tool_die_patch{k}"
    lines += [f"{pre}_type coons", f"{pre}_sense -1",
              f"{pre}_bottom_type arc", f"{pre}_bottom_points {fmt(Rc * e0 + z0, Rc * e1 + z0, z0)}",
              f"{pre}_top_type arc", f"{pre}_top_points {fmt(Ro * e0 + z1, Ro * e1 + z1, z1)}",
              f"{pre}_left_type arc", f"{pre}_left_points {fmt(Rc * e0 + z0, Ro * e0 + z1, Rc * e0 + z1)}",
              f"{pre}_right_type arc", f"{pre}_right_points {fmt(Rc * e1 + z0, Ro * e1 + z1, Rc * e1 + z1)}"]
print("\n".join(lines))


def arc(p, q, ctr, s):
    """the arc from p to q about ctr at fraction s (as the code evaluates it: constant radius)"""
    u, v = p - ctr, q - ctr
    r = np.linalg.norm(u)
    w = math.acos(max(-1.0, min(1.0, float(u @ v) / (r * np.linalg.norm(v)))))
    return ctr + (math.sin((1 - s) * w) * u + math.sin(s * w) * v) / math.sin(w)


if a.report:
    worst = 0.0
    for (p00, p10, p11, p01) in patches:
        for xi in np.linspace(0, 1, 41):
            for eta in np.linspace(0, 1, 41):
                C0, C1 = arc(p00, p10, c, xi), arc(p01, p11, c, xi)
                D0, D1 = arc(p00, p01, c, eta), arc(p10, p11, c, eta)
                B = (1 - xi) * (1 - eta) * p00 + xi * (1 - eta) * p10 + xi * eta * p11 + (1 - xi) * eta * p01
                x = (1 - eta) * C0 + eta * C1 + (1 - xi) * D0 + xi * D1 - B
                worst = max(worst, abs(np.linalg.norm(x - c) - R))
    print(f"coons punch ({len(patches)} patches): largest distance from the sphere {worst:.4f} mm ({100 * worst / R:.3f} % of R)", file=sys.stderr)
