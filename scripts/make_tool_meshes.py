#!/usr/bin/python3
"""Meshed tool surfaces for the benchmark cases and the tests (python3 + numpy only).

Writes under cases/tools/:
  hemisphere_punch_s<n>.stl   the punch (sphere R 50.8, centre (0,0,-50.8), polar angle 0..90,
                              azimuth -10..100, as the analytic patch) in triangles, n rings
  hemisphere_punch_q<n>.msh   the same in quadrangles (three grids of n/2 x n/2), Gmsh 4.1
  hemisphere_die_s<n>.stl     the die fillet (torus, major 59.18, minor 6.35, centre (0,0,7.35),
  hemisphere_die_q<n>.msh     azimuth -10..100, tube angle 180..270) in triangles / quadrangles
  hemisphere_tools_q<n>.inp   both tools in one Abaqus deck (n = 24, 48): the punch quadrangles as
                              the S2 faces of C3D8 solids 2 mm thick (*SURFACE PUNCH_SURF), the die
                              quadrangles as R3D4 elements of a *RIGID BODY (*SURFACE DIE_SURF, SPOS)
  hemisphere_punch.tool, hemisphere_die.tool   the analytic patches as tool files
  ball_s<n>.stl               the ball of cases/block_sphere.opts (R 3, centre (0,0,4), lower half)
and the cases cases/hemisphere_frictionless_{toolfile,stl<n>,msh<n>,inp<n>}.opts from
cases/hemisphere_frictionless_analytic.opts (the tool options replaced by -tool_<t>_file).

  python3 scripts/make_tool_meshes.py [--levels 12,24,48,96]
"""
import argparse
import os
import struct

import numpy as np

ROOT = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..")


def sphere_cap(c, R, axis, th0, th1, ph0, ph1, nth, quads=False):
    """Cap of a sphere about axis (+-z): rings of constant polar angle (degrees), triangles zipped
    between rings of growing vertex counts (quasi-uniform), or a structured grid of quadrangles
    (fans of triangles at the pole). Oriented outwards."""
    th = np.radians(np.linspace(th0, th1, nth + 1))
    span = ph1 - ph0
    periodic = abs(span - 360.0) < 1e-9
    s = np.sign(axis)
    V, rings = [], []

    def point(t, p):
        return [c[0] + R * np.sin(t) * np.cos(p), c[1] + R * np.sin(t) * np.sin(p) * s, c[2] + s * R * np.cos(t)]

    nmax = max(4, int(round(np.radians(span) * nth / np.radians(th1 - th0) * np.sin(th[-1]))))
    for i, t in enumerate(th):
        if i == 0 and th0 == 0.0:
            rings.append([len(V)])
            V.append(point(0.0, 0.0))
            continue
        m = nmax if quads else max(3 if periodic else 1, int(round(np.radians(span) * R * np.sin(t) / (R * (th[1] - th[0])))))
        ph = np.radians(ph0 + span * np.arange(m + (0 if periodic else 1)) / m)
        rings.append(list(range(len(V), len(V) + len(ph))))
        V.extend(point(t, p) for p in ph)
    F = []
    for i in range(len(rings) - 1):
        a, b = rings[i], rings[i + 1]
        if periodic and len(a) > 1:
            a = a + [a[0]]
        if periodic:
            b = b + [b[0]]
        if len(a) == 1:
            F.extend([a[0], b[k], b[k + 1]] for k in range(len(b) - 1))
        elif quads:
            F.extend([a[k], b[k], b[k + 1], a[k + 1]] for k in range(len(a) - 1))
        else:  # zipper: advance along the ring whose next diagonal is shorter
            j = k = 0
            P = np.array(V)
            while j < len(a) - 1 or k < len(b) - 1:
                if k == len(b) - 1 or (j < len(a) - 1 and np.linalg.norm(P[a[j + 1]] - P[b[k]]) < np.linalg.norm(P[a[j]] - P[b[k + 1]])):
                    F.append([a[j], b[k], a[j + 1]])
                    j += 1
                else:
                    F.append([a[j], b[k], b[k + 1]])
                    k += 1
    V = np.array(V)
    F = [orient_out(V, f, c) for f in F]
    return V, F


def sphere_sector_quads(c, R, ph0, ph1, n):
    """Quadrangles on the sphere sector polar angle 0..90, azimuth ph0..ph1 (degrees) about +z:
    split through its centroid G and the midpoints of its sides into three quadrilaterals, each a
    k x k grid (k = n/2) of bilinear points projected radially onto the sphere (no pole fan)."""
    c = np.array(c)
    u = lambda th, ph: np.array([np.sin(np.radians(th)) * np.cos(np.radians(ph)), np.sin(np.radians(th)) * np.sin(np.radians(ph)), np.cos(np.radians(th))])
    N, A, B = u(0, 0), u(90, ph0), u(90, ph1)
    Mab, Mna, Mnb = u(90, 0.5 * (ph0 + ph1)), u(45, ph0), u(45, ph1)
    G = (N + A + B) / np.linalg.norm(N + A + B)
    k = max(1, n // 2)
    V, F, index = [], [], {}

    def vid(p):
        key = tuple(np.round(p, 9))
        if key not in index:
            index[key] = len(V)
            V.append(c + R * p)
        return index[key]

    for P00, P10, P11, P01 in ((N, Mna, G, Mnb), (Mna, A, Mab, G), (G, Mab, B, Mnb)):
        ids = [[vid(((1 - s) * (1 - t) * P00 + s * (1 - t) * P10 + s * t * P11 + (1 - s) * t * P01) / np.linalg.norm((1 - s) * (1 - t) * P00 + s * (1 - t) * P10 + s * t * P11 + (1 - s) * t * P01))
                for t in np.linspace(0, 1, k + 1)] for s in np.linspace(0, 1, k + 1)]
        for i in range(k):
            for j in range(k):
                F.append([ids[i][j], ids[i + 1][j], ids[i + 1][j + 1], ids[i][j + 1]])
    V = np.array(V)
    F = [orient_out(V, f, c) for f in F]
    return V, F


def orient_out(V, f, c, inward=False):
    """the facet wound so that its normal points away from c (towards it if inward)"""
    P = V[f]
    n = np.cross(P[1] - P[0], P[2] - P[0])
    out = np.dot(n, P.mean(axis=0) - c) > 0
    return list(f) if out != inward else list(f[::-1])


def torus(c, Rmaj, r, ph0, ph1, ps0, ps1, nph, nps, quads=False):
    """Torus about z, azimuth ph, tube angle ps (0 outer equator, 90 towards +z), degrees; oriented
    away from the tube's core circle"""
    ph = np.radians(np.linspace(ph0, ph1, nph + 1))
    ps = np.radians(np.linspace(ps0, ps1, nps + 1))
    V = np.array([[c[0] + (Rmaj + r * np.cos(q)) * np.cos(p), c[1] + (Rmaj + r * np.cos(q)) * np.sin(p), c[2] + r * np.sin(q)] for p in ph for q in ps])
    idx = lambda i, j: i * (nps + 1) + j
    F = []
    for i in range(nph):
        for j in range(nps):
            q = [idx(i, j), idx(i + 1, j), idx(i + 1, j + 1), idx(i, j + 1)]
            core = np.mean([[c[0] + Rmaj * np.cos(p), c[1] + Rmaj * np.sin(p), c[2]] for p in (ph[i], ph[i + 1])], axis=0)
            if quads:
                F.append(orient_out(V, q, core))
            else:
                F.append(orient_out(V, q[:3], core))
                F.append(orient_out(V, [q[0], q[2], q[3]], core))
    return V, F


def write_stl(path, V, F, binary=False):
    T = [f for f in F if len(f) == 3] + [t for f in F if len(f) == 4 for t in ([f[0], f[1], f[2]], [f[0], f[2], f[3]])]
    if binary:
        with open(path, "wb") as fp:
            fp.write(b"atrito tool surface".ljust(80, b" "))
            fp.write(struct.pack("<I", len(T)))
            for t in T:
                P = V[t]
                n = np.cross(P[1] - P[0], P[2] - P[0])
                n = n / np.linalg.norm(n)
                fp.write(struct.pack("<12fH", *n, *P[0], *P[1], *P[2], 0))
        return
    with open(path, "w") as fp:
        fp.write("solid tool\n")
        for t in T:
            P = V[t]
            n = np.cross(P[1] - P[0], P[2] - P[0])
            n = n / np.linalg.norm(n)
            fp.write("facet normal %.9e %.9e %.9e\n outer loop\n" % tuple(n))
            for p in P:
                fp.write("  vertex %.17g %.17g %.17g\n" % tuple(p))
            fp.write(" endloop\nendfacet\n")
        fp.write("endsolid tool\n")


def write_msh(path, V, F, name="tool"):
    """Gmsh 4.1 ASCII: one surface entity in the physical group `name` (tag 1)"""
    tris = [f for f in F if len(f) == 3]
    quads = [f for f in F if len(f) == 4]
    lo, hi = V.min(axis=0), V.max(axis=0)
    with open(path, "w") as fp:
        fp.write("$MeshFormat\n4.1 0 8\n$EndMeshFormat\n")
        fp.write('$PhysicalNames\n1\n2 1 "%s"\n$EndPhysicalNames\n' % name)
        fp.write("$Entities\n0 0 1 0\n1 %.17g %.17g %.17g %.17g %.17g %.17g 1 1 0\n$EndEntities\n" % (*lo, *hi))
        fp.write("$Nodes\n1 %d 1 %d\n2 1 0 %d\n" % (len(V), len(V), len(V)))
        fp.write("".join("%d\n" % (k + 1) for k in range(len(V))))
        fp.write("".join("%.17g %.17g %.17g\n" % tuple(p) for p in V))
        fp.write("$EndNodes\n")
        nb = (1 if tris else 0) + (1 if quads else 0)
        ne = len(tris) + len(quads)
        fp.write("$Elements\n%d %d 1 %d\n" % (nb, ne, ne))
        k = 1
        for typ, E in ((2, tris), (3, quads)):
            if not E:
                continue
            fp.write("2 1 %d %d\n" % (typ, len(E)))
            for f in E:
                fp.write("%d %s\n" % (k, " ".join(str(v + 1) for v in f)))
                k += 1
        fp.write("$EndElements\n")


def write_inp(path, punch, die, c, R, h=2.0):
    """An Abaqus deck of both tools, as a CAD-to-FE export would give them: the punch a shell of
    C3D8 solids of thickness h under its surface quads (nodes 1-4 on the inner face, 5-8 on the
    outer one, so that the outer face is S2), its contact surface the *SURFACE PUNCH_SURF on S2; the
    die R3D4 rigid elements, each wound so that its normal points to the sheet, in a *RIGID BODY
    and the *SURFACE DIE_SURF on their SPOS side"""
    (Vp, Fp), (Vd, Fd) = punch, die
    c = np.array(c)
    npn, ndn = len(Vp), len(Vd)
    Vin = c + (Vp - c) * (R - h) / R
    with open(path, "w") as fp:
        fp.write("** hemispherical punch benchmark: punch (C3D8 shell, surface PUNCH_SURF) and die fillet\n"
                 "** (R3D4, surface DIE_SURF). Written by scripts/make_tool_meshes.py.\n*HEADING\nrigid tools\n")
        fp.write("*NODE, NSET=PUNCH_NODES\n")
        fp.write("".join("%d, %.17g, %.17g, %.17g\n" % (k + 1, *p) for k, p in enumerate(Vp)))
        fp.write("".join("%d, %.17g, %.17g, %.17g\n" % (npn + k + 1, *p) for k, p in enumerate(Vin)))
        fp.write("*NODE, NSET=DIE_NODES\n")
        fp.write("".join("%d, %.17g, %.17g, %.17g\n" % (2 * npn + k + 1, *p) for k, p in enumerate(Vd)))
        ref = 2 * npn + ndn
        fp.write("*NODE, NSET=REF\n%d, 0, 0, 0\n%d, 0, 0, 7.35\n" % (ref + 1, ref + 2))
        fp.write("*ELEMENT, TYPE=C3D8, ELSET=PUNCH\n")
        fp.write("".join("%d, %s, %s\n" % (e + 1, ", ".join(str(npn + v + 1) for v in f), ", ".join(str(v + 1) for v in f)) for e, f in enumerate(Fp)))
        fp.write("*ELEMENT, TYPE=R3D4, ELSET=DIE\n")
        fp.write("".join("%d, %s\n" % (len(Fp) + e + 1, ", ".join(str(2 * npn + v + 1) for v in f)) for e, f in enumerate(Fd)))
        fp.write("*SOLID SECTION, ELSET=PUNCH, MATERIAL=STEEL\n*MATERIAL, NAME=STEEL\n*ELASTIC\n210000, 0.3\n")
        fp.write("*RIGID BODY, ELSET=PUNCH, REF NODE=%d\n*RIGID BODY, ELSET=DIE, REF NODE=%d\n" % (ref + 1, ref + 2))
        fp.write("*SURFACE, NAME=PUNCH_SURF, TYPE=ELEMENT\nPUNCH, S2\n*SURFACE, NAME=DIE_SURF, TYPE=ELEMENT\nDIE, SPOS\n")


PUNCH = dict(c=(0.0, 0.0, -50.8), R=50.8)
DIE = dict(c=(0.0, 0.0, 7.35), R=59.18, r=6.35)

PUNCH_TOOL = """# hemispherical punch of the stretching benchmark: one sphere patch (doc/tools.md)
patches 1
patch0_type sphere
patch0_center 0,0,-50.8
patch0_radius 50.8
patch0_axis 0,0,1
patch0_ref 1,0,0
patch0_range 0,90,-10,100
"""
DIE_TOOL = """# die fillet of the stretching benchmark: one torus patch (doc/tools.md)
patches 1
patch0_type torus
patch0_center 0,0,7.35
patch0_axis 0,0,1
patch0_ref 1,0,0
patch0_major 59.18
patch0_minor 6.35
patch0_range -10,100,180,270
"""


def case(name, punch, die, comment, groups=None):
    src = open(os.path.join(ROOT, "cases", "hemisphere_frictionless_analytic.opts")).read().splitlines()
    out = ["# " + comment, "# Written by scripts/make_tool_meshes.py from hemisphere_frictionless_analytic.opts."]
    for l in src:
        if l.startswith("#"):
            continue
        if l.startswith("-tool_punch_patch") or l.startswith("-tool_die_patch"):
            continue
        if l.startswith("-output_dir"):
            l = "-output_dir out/" + name
        out.append(l)
        if l.startswith("-tool_punch_motion"):
            out.append("-tool_punch_file " + punch)
            out.append("-tool_die_file " + die)
            if groups:
                out.append("-tool_punch_file_group " + groups[0])
                out.append("-tool_die_file_group " + groups[1])
    open(os.path.join(ROOT, "cases", name + ".opts"), "w").write("\n".join(out) + "\n")


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--levels", default="12,24,48,96")
    a = ap.parse_args()
    d = os.path.join(ROOT, "cases", "tools")
    os.makedirs(d, exist_ok=True)
    open(os.path.join(d, "hemisphere_punch.tool"), "w").write(PUNCH_TOOL)
    open(os.path.join(d, "hemisphere_die.tool"), "w").write(DIE_TOOL)
    case("hemisphere_frictionless_toolfile", "cases/tools/hemisphere_punch.tool", "cases/tools/hemisphere_die.tool", "The analytic benchmark with its tools from tool files (the same patches).")
    for n in [int(x) for x in a.levels.split(",")]:
        V, F = sphere_cap(PUNCH["c"], PUNCH["R"], 1, 0.0, 90.0, -10.0, 100.0, n)
        write_stl(os.path.join(d, "hemisphere_punch_s%d.stl" % n), V, F, binary=n >= 48)
        V, F = sphere_sector_quads(PUNCH["c"], PUNCH["R"], -10.0, 100.0, n)
        write_msh(os.path.join(d, "hemisphere_punch_q%d.msh" % n), V, F, "punch")
        nph = int(round(n * 110.0 / 90.0 * 59.18 / 50.8))
        nps = max(4, n // 3)
        V, F = torus(DIE["c"], DIE["R"], DIE["r"], -10.0, 100.0, 180.0, 270.0, nph, nps)
        write_stl(os.path.join(d, "hemisphere_die_s%d.stl" % n), V, F, binary=n >= 48)
        V, F = torus(DIE["c"], DIE["R"], DIE["r"], -10.0, 100.0, 180.0, 270.0, nph, nps, quads=True)
        write_msh(os.path.join(d, "hemisphere_die_q%d.msh" % n), V, F, "die")
        if n in (24, 48):
            write_inp(os.path.join(d, "hemisphere_tools_q%d.inp" % n), sphere_sector_quads(PUNCH["c"], PUNCH["R"], -10.0, 100.0, n), (V, F), PUNCH["c"], PUNCH["R"])
            case("hemisphere_frictionless_inp%d" % n, "cases/tools/hemisphere_tools_q%d.inp" % n, "cases/tools/hemisphere_tools_q%d.inp" % n,
                 "The analytic benchmark with both tools from one Abaqus deck (%d rings on the punch: its C3D8 faces, the die's R3D4 elements), normals smoothed." % n,
                 groups=("PUNCH_SURF", "DIE_SURF"))
        case("hemisphere_frictionless_stl%d" % n, "cases/tools/hemisphere_punch_s%d.stl" % n, "cases/tools/hemisphere_die_s%d.stl" % n,
             "The analytic benchmark with STL tools (%d rings on the punch), normals smoothed." % n)
        case("hemisphere_frictionless_msh%d" % n, "cases/tools/hemisphere_punch_q%d.msh" % n, "cases/tools/hemisphere_die_q%d.msh" % n,
             "The analytic benchmark with Gmsh quadrangle tools (%d rings on the punch), normals smoothed." % n)
    for n in (8, 16, 32):
        V, F = sphere_cap((0.0, 0.0, 4.0), 3.0, -1, 0.0, 90.0, 0.0, 360.0, n)
        write_stl(os.path.join(d, "ball_s%d.stl" % n), V, F, binary=n >= 16)


if __name__ == "__main__":
    main()
