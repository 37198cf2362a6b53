#!/usr/bin/python3
"""Meshes of the pinched cylinder with rigid end diaphragms (MacNeal & Harder 1985, Belytschko et
al. 1985) for solid elements: one octant, N x N hexahedra on the shell surface, one element
through the thickness. Writes cases/shells/pinched_cylinder_N.inp (Abaqus-style, C3D8).

  /usr/bin/python3 scripts/make_shell_meshes.py [N ...]      (default 4 8 16 32)

Geometry: mid-surface radius R = 300, length L = 600, thickness t = 3, axis along z, the octant
0 <= theta <= 90 deg (x = r cos theta, y = r sin theta), 0 <= z <= L/2. Nodes on the inner
(r = R - t/2) and outer (r = R + t/2) surfaces; the element faces are flat (the circumference is
a polygon of N sides per quarter).

Node sets:
  symy       y = 0   (theta = 0):   u_y = 0
  symx       x = 0   (theta = 90):  u_x = 0
  symz       z = 0   (mid-length):  u_z = 0
  diaphragm  z = L/2 (end):         u_x = u_y = 0 (radial and circumferential), u_z free
  load       theta = 0, z = 0: the two nodes of the line through the thickness under the load
             (inner and outer surface); the pinching displacement is prescribed along -x there
Element set: shell (all elements).
"""
import math
import os
import sys

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
R, L, T = 300.0, 600.0, 3.0


def write_mesh(n, path):
    nt = n + 1  # nodes along theta and along z

    def nid(i, j, k):  # i: theta, j: z, k: 0 inner / 1 outer
        return 1 + i + nt * (j + nt * k)

    lines = [f"** pinched cylinder octant: R = {R:g}, L = {L:g}, t = {T:g}; {n} x {n} x 1 hexahedra",
             "** written by scripts/make_shell_meshes.py", "*NODE"]
    for k in range(2):
        r = R + (k - 0.5) * T
        for j in range(nt):
            z = 0.5 * L * j / n
            for i in range(nt):
                th = 0.5 * math.pi * i / n
                x, y = r * math.cos(th), r * math.sin(th)
                if i == n:
                    x = 0.0
                if i == 0:
                    y = 0.0
                lines.append(f"{nid(i, j, k)}, {x:.12g}, {y:.12g}, {z:.12g}")
    lines.append("*ELEMENT, TYPE=C3D8, ELSET=shell")
    e = 0
    for j in range(n):
        for i in range(n):
            e += 1
            # bottom face (inner surface) counter-clockwise seen from outside: theta, z, then r
            c = [nid(i, j, 0), nid(i + 1, j, 0), nid(i + 1, j + 1, 0), nid(i, j + 1, 0),
                 nid(i, j, 1), nid(i + 1, j, 1), nid(i + 1, j + 1, 1), nid(i, j + 1, 1)]
            lines.append(f"{e}, " + ", ".join(map(str, c)))

    def nset(name, ids):
        lines.append(f"*NSET, NSET={name}")
        ids = sorted(ids)
        for a in range(0, len(ids), 16):
            lines.append(", ".join(map(str, ids[a:a + 16])))

    both = range(2)
    nset("symy", [nid(0, j, k) for j in range(nt) for k in both])
    nset("symx", [nid(n, j, k) for j in range(nt) for k in both])
    nset("symz", [nid(i, 0, k) for i in range(nt) for k in both])
    nset("diaphragm", [nid(i, n, k) for i in range(nt) for k in both])
    nset("load", [nid(0, 0, k) for k in both])
    with open(path, "w") as f:
        f.write("\n".join(lines) + "\n")


def main():
    sizes = [int(a) for a in sys.argv[1:]] or [4, 8, 16, 32]
    d = os.path.join(ROOT, "cases", "shells")
    os.makedirs(d, exist_ok=True)
    for n in sizes:
        p = os.path.join(d, f"pinched_cylinder_{n}.inp")
        write_mesh(n, p)
        print(p)


if __name__ == "__main__":
    main()
