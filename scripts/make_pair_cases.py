#!/usr/bin/env python3
"""Writes the meshes and cases of contact between two deformable bodies of one mesh (node to
surface, penalty): a contact patch test and a plane-strain Hertz problem.

usage: make_pair_cases.py

  cases/meshes/pair_patch.inp, cases/pair_patch.opts   two elastic blocks stacked, non-matching
                                                       meshes on the interface (3x3 on 4x4)
  cases/meshes/pair_patch_nested.inp, ..._nested.opts  the same, the upper block 8x8: nested faces,
                                                       passed exactly by single-pass node to surface
  cases/meshes/pair_hertz.inp, cases/pair_hertz.opts   an elastic half-cylinder pressed on an
                                                       elastic block, half model, plane strain
  cases/pair_hertz_rigid.opts                          its bodies each against a rigid counterpart
                                                       (runs without the pair: the estimate of d)

The .inp decks are Abaqus-style (*NODE, *ELEMENT TYPE=C3D8, *NSET, *ELSET) as src/mesh/meshgen.c
reads them; each hexahedron is checked positive (det J > 0 at its corners and Gauss points)
before the deck is written. The pair's options (-pair_names, -pair_<p>_slave, _master, _friction,
_two_pass, _penalty_normal) are those of the two-body contact; the closed forms are in each case's
header and in tests/checks/hertz_pair.py.
"""
import math
import os
import sys

import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.abspath(os.path.join(HERE, ".."))
CASES = os.path.join(ROOT, "cases")
MESHES = os.path.join(CASES, "meshes")

E, NU = 1000.0, 0.3

# ---------------------------------------------------------------- Hertz data (plane strain)
R = 10.0          # cylinder radius; axis along y at (0, *, R); its flat cut face z = R on top
T = 0.1           # thickness along y (one element; y fixed on both faces: plane strain)
LB, HB = 20.0, 20.0   # the block [0, LB] x [0, T] x [-HB, 0]
H_BLOCK = 0.05    # block's top surface: element size in |x| < XF (b/20 for b = 1)
H_CYL = 2.0 / 34  # cylinder's surface: arc length per element up to x = XF (0.0588, non-matching)
XF = 2.0          # the fine zone |x| < XF on both surfaces
GROW = 1.10       # the cylinder's ring: growth of its first layer's thickness from line to line
ESTAR = 1.0 / (2 * (1 - NU * NU) / E)   # 1/E* = (1 - nu1^2)/E1 + (1 - nu2^2)/E2
B_TARGET = 1.0
P_TARGET = math.pi * ESTAR * B_TARGET ** 2 / (4 * R)     # b = sqrt(4 P R/(pi E*)): P = 43.15
# The cylinder's top face is displaced by -D, the approach of the pair at P_TARGET, estimated from
# cases/pair_hertz_rigid.opts (this mesh, each body against a rigid counterpart, 8 steps; run
# 2026-11-29): the elastic approaches (the tool's travel less the penalty's penetration at x = 0)
# interpolated to P_TARGET, block under a rigid cylinder APPROACH_BLOCK, cylinder on a rigid plane
# APPROACH_CYL; against a rigid body the contact is narrower (b_r = b/sqrt 2), and the centre of a
# Hertz pressure on a half-space sinks, relative to a distant point, by 2 (1-nu^2) P/(pi E)
# (ln(2 r/b) + 1/2): each body's approach in the pair is less by 2 (1-nu^2) P/(pi E) ln(b/b_r);
# the pair's own penalty then adds its penetration at the centre, about 1.1 p0 h/E (h = H_BLOCK,
# the slave's element size normal to the face, 1.1 the regularisation as in the rigid runs).
APPROACH_BLOCK, APPROACH_CYL = 0.09966, 0.08727


def approach():
    c = 2 * (1 - NU * NU) * P_TARGET / (math.pi * E)
    corr = 2 * c * math.log(math.sqrt(2))
    pen = 1.1 * (2 * P_TARGET / (math.pi * B_TARGET)) * H_BLOCK / E
    return APPROACH_BLOCK + APPROACH_CYL - corr + pen, corr, pen


D_ESTIMATE = round(approach()[0], 3)   # 0.171
# The pair (src/contact/pair.c, 2026-11-29) at D_ESTIMATE: P = 42.668 per unit length (b = 0.9944,
# fitted 0.9948, p0 +0.07 %), dP/dd = 285 over the last step: tuned to
D = 0.173


# ---------------------------------------------------------------- an .inp deck
class Deck:
    """nodes, C3D8 elements (by element set), node sets; ids as given"""

    def __init__(self):
        self.X = {}            # node id -> (x, y, z)
        self.elems = []        # (id, [8 node ids], elset)
        self.nsets = {}        # name -> sorted ids

    def node(self, nid, x):
        assert nid not in self.X
        self.X[nid] = tuple(float(v) for v in x)
        return nid

    def hexa(self, eid, conn, elset):
        """a C3D8; nodes 1-4 one face, 5-8 the opposite face: flipped (2 <-> 4, 6 <-> 8) if the
        given order is left-handed; refused if not positive at every corner and Gauss point"""
        if min_detj(np.array([self.X[n] for n in conn])) < 0:
            conn = [conn[0], conn[3], conn[2], conn[1], conn[4], conn[7], conn[6], conn[5]]
        dj = min_detj(np.array([self.X[n] for n in conn]))
        if dj <= 0:
            raise SystemExit("element %d is degenerate or inverted (det J %g)" % (eid, dj))
        self.elems.append((eid, list(conn), elset))

    def nset(self, name, ids):
        self.nsets[name] = sorted(set(int(i) for i in ids))

    def write(self, path, header):
        os.makedirs(os.path.dirname(path), exist_ok=True)
        with open(path, "w") as f:
            for line in header.splitlines():
                f.write("** %s\n" % line)
            f.write("*NODE\n")
            for nid in sorted(self.X):
                f.write("%d, %.12g, %.12g, %.12g\n" % ((nid,) + self.X[nid]))
            for es in dict.fromkeys(e[2] for e in self.elems):
                f.write("*ELEMENT, TYPE=C3D8, ELSET=%s\n" % es)
                for eid, conn, s in self.elems:
                    if s == es:
                        f.write("%d, %s\n" % (eid, ", ".join(map(str, conn))))
            for name, ids in self.nsets.items():
                f.write("*NSET, NSET=%s\n" % name)
                for a in range(0, len(ids), 16):
                    f.write(", ".join(map(str, ids[a:a + 16])) + "\n")

    def stats(self):
        """(nodes, elements, per element set, smallest det J / element volume ratio, largest aspect)"""
        worst, aspect = 1e300, 0.0
        for _, conn, _ in self.elems:
            x = np.array([self.X[n] for n in conn])
            edges = [np.linalg.norm(x[b] - x[a]) for a, b in
                     ((0, 1), (1, 2), (2, 3), (3, 0), (4, 5), (5, 6), (6, 7), (7, 4), (0, 4), (1, 5), (2, 6), (3, 7))]
            aspect = max(aspect, max(edges) / min(edges))
            worst = min(worst, scaled_jacobian(x))
        per = {}
        for e in self.elems:
            per[e[2]] = per.get(e[2], 0) + 1
        return len(self.X), len(self.elems), per, worst, aspect


def _dN(xi, eta, zeta):
    s = np.array([[-1, -1, -1], [1, -1, -1], [1, 1, -1], [-1, 1, -1],
                  [-1, -1, 1], [1, -1, 1], [1, 1, 1], [-1, 1, 1]], float)
    d = np.empty((8, 3))
    for a in range(8):
        d[a, 0] = s[a, 0] * (1 + s[a, 1] * eta) * (1 + s[a, 2] * zeta) / 8
        d[a, 1] = s[a, 1] * (1 + s[a, 0] * xi) * (1 + s[a, 2] * zeta) / 8
        d[a, 2] = s[a, 2] * (1 + s[a, 0] * xi) * (1 + s[a, 1] * eta) / 8
    return d


_G = 1 / math.sqrt(3)
_PTS = [(i, j, k) for k in (-1, 1) for j in (-1, 1) for i in (-1, 1)] + \
       [(i * _G, j * _G, k * _G) for k in (-1, 1) for j in (-1, 1) for i in (-1, 1)]
_DN = [_dN(*p) for p in _PTS]


def min_detj(x):
    """smallest det J of a hexahedron (8 x 3 nodes, C3D8 order) over its corners and Gauss points"""
    return min(np.linalg.det(x.T @ d) for d in _DN)


def scaled_jacobian(x):
    """smallest det J at the corners over the product of the three edge lengths there (1: a
    rectangular corner)"""
    worst = 1e300
    for d in _DN[:8]:
        J = x.T @ d
        worst = min(worst, np.linalg.det(J) / np.prod(np.linalg.norm(J, axis=0)))
    return worst


# ---------------------------------------------------------------- grading
def geometric(h0, length, n):
    """n sizes starting at h0, growing by a common ratio r >= 1, summing to length (uniform when
    n h0 >= length)"""
    if n * h0 >= length * (1 - 1e-12):
        return [length / n] * n
    lo, hi = 1.0, 10.0
    for _ in range(200):
        r = 0.5 * (lo + hi)
        s = h0 * (r ** n - 1) / (r - 1)
        lo, hi = (r, hi) if s < length else (lo, r)
    return [h0 * r ** k * length / (h0 * (r ** n - 1) / (r - 1)) for k in range(n)]


def ratio(sizes):
    return max(sizes[k + 1] / sizes[k] for k in range(len(sizes) - 1)) if len(sizes) > 1 else 1.0


# ---------------------------------------------------------------- 1. patch test
def patch_mesh(nu_upper):
    d = Deck()

    def block(nx, nz, z0, z1, nid0, eid0, elset):
        ids = np.zeros((nx + 1, nx + 1, nz + 1), int)
        for k in range(nz + 1):
            for j in range(nx + 1):
                for i in range(nx + 1):
                    ids[i, j, k] = d.node(nid0 + i + (nx + 1) * (j + (nx + 1) * k),
                                          (i / nx, j / nx, z0 + (z1 - z0) * k / nz))
        e = eid0
        for k in range(nz):
            for j in range(nx):
                for i in range(nx):
                    d.hexa(e, [ids[i, j, k], ids[i + 1, j, k], ids[i + 1, j + 1, k], ids[i, j + 1, k],
                               ids[i, j, k + 1], ids[i + 1, j, k + 1], ids[i + 1, j + 1, k + 1], ids[i, j + 1, k + 1]], elset)
                    e += 1
        return ids

    lo = block(4, 2, 0.0, 0.5, 1, 1, "LOWER")
    up = block(nu_upper, 2, 0.5, 1.0, 1001, 1001, "UPPER")
    d.nset("lower_bottom", lo[:, :, 0].ravel())
    d.nset("lower_top", lo[:, :, -1].ravel())
    d.nset("upper_bottom", up[:, :, 0].ravel())
    d.nset("upper_top", up[:, :, -1].ravel())
    d.nset("lower_mid", lo[:, :, 1].ravel())  # the lower block's mid-plane: no boundary faces (bad input of a master surface)
    d.nset("lower_xmin", lo[0].ravel())
    d.nset("lower_ymin", lo[:, 0].ravel())
    d.nset("upper_xmin", up[0].ravel())
    d.nset("upper_ymin", up[:, 0].ravel())
    d.nset("xmin", list(lo[0].ravel()) + list(up[0].ravel()))
    d.nset("ymin", list(lo[:, 0].ravel()) + list(up[:, 0].ravel()))
    return d


def master_shares(ns, nm=4):
    """largest relative excess over the consistent share p A_a of a master node's force when the
    uniform pressure is carried by ns x ns slave faces on nm x nm master faces (unit square): the
    slave forces p A_i spread by the master face's bilinear shape functions at the slave nodes"""
    s, m = np.linspace(0, 1, ns + 1), np.linspace(0, 1, nm + 1)
    ws = np.full(ns + 1, 1.0 / ns)
    ws[[0, -1]] /= 2
    wm = np.full(nm + 1, 1.0 / nm)
    wm[[0, -1]] /= 2
    F = np.zeros(nm + 1)
    for i in range(ns + 1):
        k = min(int(np.searchsorted(m, s[i], side="right")) - 1, nm - 1)
        xi = (s[i] - m[k]) / (m[k + 1] - m[k])
        F[k] += ws[i] * (1 - xi)
        F[k + 1] += ws[i] * xi
    r = F / wm
    return np.outer(r, r)


# what the pair (src/contact/pair.c) gave, 2026-11-29, one rank
RUNS = {
    "pair_patch": "Run (2026-11-29): the pair's resultant 7.9503 equals the reactions (to 5e-9); cells' von Mises\n"
                  "6.79 to 9.49 in the lower block, 7.09 to 8.76 in the upper; slave pressure 6.31 to 8.72.",
    "pair_patch_nested": "Run (2026-11-29): uniform to round-off: penetration g = 2.0193e-3 at every slave node, so\n"
                         "l = 1 - (0.01 - g) = 0.992019 and the closed form tau/l = 8.0772 (the pressure on every slave\n"
                         "node and the reactions: 8.07718), Cauchy tau/J = 8.0384 (every cell's von Mises: 8.03844).",
}


def patch_case(nu_upper, name):
    d = patch_mesh(nu_upper)
    mesh = "cases/meshes/%s.inp" % name
    nv, ne, per, sj, asp = d.stats()
    d.write(os.path.join(ROOT, mesh),
            "Contact patch test between two deformable blocks: LOWER [0,1]x[0,1]x[0,0.5], 4x4x2 hexahedra\n"
            "(ids 1-), UPPER [0,1]x[0,1]x[0.5,1], %dx%dx2 (ids 1001-), touching at z = 0.5, separate nodes.\n"
            "Node sets: lower_bottom, lower_top, upper_bottom, upper_top, xmin, ymin (both blocks),\n"
            "lower_xmin, lower_ymin, upper_xmin, upper_ymin. Written by scripts/make_pair_cases.py." % (nu_upper, nu_upper))
    delta, H = 0.01, 1.0
    lam = 1 - delta / H
    tau = E * math.log(lam)                  # Kirchhoff stress of the Hencky law in uniaxial stress
    J = lam ** (1 - 2 * NU)
    sh = master_shares(nu_upper)
    nested = abs(sh - 1).max() < 1e-12
    head = """Contact patch test, two deformable bodies%s: two elastic blocks stacked, the
lower 4x4x2 hexahedra, the upper %dx%dx2,
%s on the contact face z = 0.5
(separate nodes, zero initial gap); mesh %s
(scripts/make_pair_cases.py). E = %g, nu = %g (J2, yield stress 1e9).
Conditions: lower_bottom z fixed; rollers x = 0 (set xmin, both blocks: x fixed) and y = 0 (ymin: y
fixed); upper_top displaced by -%g in z; 2 load steps. Pair p: slave upper_bottom, master lower_top
(the lower block's top faces), frictionless.
Closed form: uniaxial stress, uniform in both blocks and the same in both (one material); the contact
pressure uniform; with the same lateral strain in both blocks nothing slips (a friction coefficient
changes nothing). Small strain: sigma_zz = -E eps, eps = (%g - g)/%g, g the penalty's penetration:
with a penalty per unit area k, sigma_zz = -E %g/(%g + E/k); the automatic penalty K_N = E A/h per
node (k = E/h, h = 0.25 the element height on either side) gives -E %g/(%g + h) = %.4g, without
penetration %.4g: the penalty's compliance is that of one more element layer, not small here.
Finite strain (Hencky law), g = 0: stretch l = %g, Kirchhoff tau_zz = E ln l = %.5g, Cauchy
sigma_zz = tau/J = %.5g (J = l^(1-2 nu) = %.6g, the von Mises field), lateral stretch l^-nu =
%.7g; reactions fz of upper_top and lower_bottom -/+ tau/l = -/+ %.5g on the 1 x 1 section (checked
without contact by prescribing -%g to both upper_bottom and lower_top: %.5g).
%s
Every slave node on x = 1 or y = 1 lies on the master's free edge (and stays there: both blocks
expand alike), the nodes on x = 0, y = 0 on its symmetry edges: the projection must accept points
on a master face's boundary.
%s""" % (
        " (nested interface)" if nested else "", nu_upper, nu_upper,
        "nested meshes (each master face split 2 x 2 by the slave's)" if nested else "non-matching meshes",
        mesh, E, NU, delta, delta, H, delta, H, delta, H, -E * delta / (H + 0.25),
        -E * delta / H, lam, tau, tau / J, J, lam ** -NU, -tau / lam, delta / 2, -tau / lam,
        ("Nested: every master node is a slave node, the slave nodes' forces p A_i reach the master nodes\n"
         "as the consistent p A_a (the trapezoidal rule on the slave faces integrates the master's\n"
         "bilinear shape functions exactly): single-pass node to surface passes this test to round-off.\n"
         "The non-matching test: cases/pair_patch.opts.") if nested else
        ("Single-pass node to surface does not pass this test exactly with non-nested faces (Taylor &\n"
         "Papadopoulos 1991): the slave nodes' forces p A_i reach the master nodes through the master\n"
         "faces' shape functions at the slave points (the trapezoidal rule on the slave faces), here %.2f to\n"
         "%.2f times the consistent p A_a (the corner %.2f, edges %.2f): the resultant, the reactions and\n"
         "the stress far from the interface are exact, the interface's element layers are not uniform\n"
         "(the slave pressure neither, as the master face then deflects unevenly). Passed to round-off\n"
         "by the nested variant cases/pair_patch_nested.opts (upper 8x8x2)."
         % (sh.min(), sh.max(), sh[0, 0], sh[0, 2])), RUNS[name])
    lines = ["-mesh_type inp", "-mesh_file " + mesh,
             "-material_E %g" % E, "-material_nu %g" % NU,
             "-material_hardening linear", "-material_yield 1e9",
             "-bc_names base,symx,symy,top",
             "-bc_base_set lower_bottom", "-bc_base_components z",
             "-bc_symx_set xmin", "-bc_symx_components x",
             "-bc_symy_set ymin", "-bc_symy_components y",
             "-bc_top_set upper_top", "-bc_top_components z", "-bc_top_values %g" % -delta,
             "-pair_names p",
             "-pair_p_slave upper_bottom",
             "-pair_p_master lower_top",
             "-load_steps 2",
             "-output_dir out/%s" % name,
             "-output_interval 1"]
    write_case(name, head, lines)
    return dict(mesh=mesh, nv=nv, ne=ne, per=per, sj=sj, aspect=asp,
                sets={k: len(v) for k, v in d.nsets.items()})


# ---------------------------------------------------------------- 2. Hertz, plane strain
def hertz_grids():
    """the block's x and z coordinates, the cylinder's arc angles, core and radial layers"""
    # block: x uniform H_BLOCK to XF, then geometric to LB; z geometric from H_BLOCK at the top
    nfx = int(round(XF / H_BLOCK))
    xs = np.concatenate([np.linspace(0, XF, nfx + 1), XF + np.cumsum(geometric(H_BLOCK, LB - XF, 22))])
    dz = geometric(H_BLOCK, HB, 32)
    zs = -np.concatenate([[0], np.cumsum(dz)])
    xs[-1], zs[-1] = LB, -HB
    # cylinder (u = x, v = R - z): the arc by its angle th from the lowest point; up to asin(XF/R)
    # uniform arc length H_CYL (about), then geometric to 45 degrees; 45 to 90 uniform
    thf = math.asin(XF / R)
    nfa = int(round(R * thf / H_CYL))
    ga = geometric(R * thf / nfa, R * (math.pi / 4 - thf), 20)
    th1 = np.concatenate([np.linspace(0, thf, nfa + 1), thf + np.cumsum(ga) / R])
    th1[-1] = math.pi / 4
    n2 = 8
    th2 = np.linspace(math.pi / 4, math.pi / 2, n2 + 1)
    return xs, zs, th1, th2


def hertz_mesh():
    d = Deck()
    xs, zs, th1, th2 = hertz_grids()
    ys = (0.0, T)
    sets = {k: [] for k in ("block_top", "block_bottom", "block_xmin", "cyl_surface", "cyl_top", "cyl_xmin", "yfaces")}

    def extrude(P2, quads, nid0, eid0, elset):
        """2D points (n x 2: x, z) and quads (4 indices) to nodes at y = 0 and T and hexahedra;
        returns the node ids, shape (n, 2)"""
        ids = np.zeros((len(P2), 2), int)
        for l, y in enumerate(ys):
            for p, (x, z) in enumerate(P2):
                ids[p, l] = d.node(nid0 + p + l * len(P2), (x, y, z))
        for e, q in enumerate(quads):
            d.hexa(eid0 + e, [ids[q[0], 0], ids[q[1], 0], ids[q[2], 0], ids[q[3], 0],
                              ids[q[0], 1], ids[q[1], 1], ids[q[2], 1], ids[q[3], 1]], elset)
        sets["yfaces"].extend(ids.ravel())
        return ids

    # the block, structured (i along x, j down)
    nx, nz = len(xs) - 1, len(zs) - 1
    P = np.array([(xs[i], zs[j]) for j in range(nz + 1) for i in range(nx + 1)])
    bi = lambda i, j: i + (nx + 1) * j
    Q = [(bi(i, j), bi(i + 1, j), bi(i + 1, j + 1), bi(i, j + 1)) for j in range(nz) for i in range(nx)]
    ids = extrude(P, Q, 1, 1, "BLOCK")
    for i in range(nx + 1):
        sets["block_top"].extend(ids[bi(i, 0)])
        sets["block_bottom"].extend(ids[bi(i, nz)])
    for j in range(nz + 1):
        sets["block_xmin"].extend(ids[bi(0, j)])

    # the cylinder: a core square [0, a]^2 in (u, v) = (x, R - z) and a ring to the arc
    a = 0.55 * R
    n1, n2 = len(th1) - 1, len(th2) - 1
    w = 0.5   # the core's bottom edge: half like the arc's x (sin th), half uniform
    U = a * (w * np.sin(th1) / math.sin(math.pi / 4) + (1 - w) * np.arange(n1 + 1) / n1)
    V = np.linspace(0, a, n2 + 1)          # the core's right edge, v from the top face down
    pts = []
    core = np.zeros((n1 + 1, n2 + 1), int)
    for j in range(n2 + 1):
        for i in range(n1 + 1):
            core[i, j] = len(pts)
            pts.append((U[i], V[j]))
    # the ring: tangential m = 0..n1+n2 from the lowest point (th = 0) to the top face (th = 90),
    # radial k = 0 (the core's edge) .. nr (the arc)
    th = np.concatenate([th1, th2[1:]])
    inner = [core[m, n2] for m in range(n1 + 1)] + [core[n1, n2 - (m - n1)] for m in range(n1 + 1, n1 + n2 + 1)]
    nr = 20
    arcs = R * np.diff(th)
    ring = np.zeros((n1 + n2 + 1, nr + 1), int)
    # the thickness of the layer on the arc: the arc's spacing in the fine zone, then growing by at
    # most GROW per line (slower than the arc's spacing: gently curved layers, no kink)
    mf = int(np.sum(th1 <= math.asin(XF / R) + 1e-12)) - 1      # the fine zone's last line
    h = [arcs[0]]
    for m in range(1, n1 + n2 + 1):
        g = 1 + (GROW - 1) * min(1.0, max(0.0, (m - mf) / 8.0))  # the growth ramped in over 8 lines
        h.append(min(arcs[m - 1:m + 1].mean() if m < n1 + n2 else arcs[-1], h[-1] * g))
    for m in range(n1 + n2 + 1):
        p0 = np.array(pts[inner[m]])
        p1 = np.array((R * math.sin(th[m]), R * math.cos(th[m])))
        L = np.linalg.norm(p1 - p0)
        sizes = geometric(h[m], L, nr)               # from the arc inwards
        dist = np.concatenate([[0], np.cumsum(sizes)])
        ring[m, 0] = inner[m]
        for k in range(1, nr + 1):
            s = 1 - dist[nr - k] / L
            pts.append(tuple(p0 + s * (p1 - p0)) if k < nr else tuple(p1))
            ring[m, k] = len(pts) - 1
    uv = np.array(pts)
    P = np.column_stack([uv[:, 0], R - uv[:, 1]])
    P[np.abs(P[:, 0]) < 1e-13, 0] = 0.0
    Q = [(core[i, j], core[i + 1, j], core[i + 1, j + 1], core[i, j + 1]) for j in range(n2) for i in range(n1)]
    Q += [(ring[m, k], ring[m + 1, k], ring[m + 1, k + 1], ring[m, k + 1]) for k in range(nr) for m in range(n1 + n2)]
    cid = extrude(P, Q, 100001, 100001, "CYLINDER")
    for m in range(n1 + n2 + 1):
        sets["cyl_surface"].extend(cid[ring[m, nr]])
    for p in range(len(P)):
        if abs(P[p, 1] - R) < 1e-12:
            sets["cyl_top"].extend(cid[p])
        if P[p, 0] == 0.0:
            sets["cyl_xmin"].extend(cid[p])
    for k, v in sets.items():
        d.nset(k, v)
    d.nset("xmin", sets["block_xmin"] + sets["cyl_xmin"])
    d.nset("cyl_bottom", [n for n in d.nsets["cyl_surface"] if d.X[n][0] <= XF + 1e-9])
    info = dict(nx=nx, nz=nz, n1=n1, n2=n2, nr=nr, a=a,
                block_dx=(xs[1] - xs[0], xs[-1] - xs[-2], ratio(np.diff(xs)[nx - 20:])),
                block_dz=(-np.diff(zs)[0], -np.diff(zs)[-1], ratio(-np.diff(zs))),
                cyl_arc=(arcs[0], arcs[len(th1) - 2], arcs[-1]),
                fine_block=int(round(XF / H_BLOCK)), fine_cyl=int(np.sum(R * np.sin(th1) <= XF + 1e-9)) - 1)
    return d, info


def hertz_common(mesh):
    return ["-mesh_type inp", "-mesh_file " + mesh,
            "-material_E %g" % E, "-material_nu %g" % NU,
            "-material_hardening linear", "-material_yield 1e9",
            "-bc_names base,symx,plane,press",
            "-bc_base_set block_bottom", "-bc_base_components x,y,z",
            "-bc_symx_set xmin", "-bc_symx_components x",
            "-bc_plane_set yfaces", "-bc_plane_components y",
            "-bc_press_set cyl_top", "-bc_press_components z"]


def hertz_case():
    d, info = hertz_mesh()
    mesh = "cases/meshes/pair_hertz.inp"
    nv, ne, per, sj, asp = d.stats()
    d.write(os.path.join(ROOT, mesh),
            "Plane-strain Hertz contact of two deformable bodies, half model x >= 0, one element along y\n"
            "(thickness %g): BLOCK [0,%g] x [0,%g] x [-%g,0], %d x %d hexahedra graded towards the origin\n"
            "(ids 1-); CYLINDER, the quarter x >= 0, z <= %g of the disc of radius %g about (0, *, %g), an O-grid\n"
            "(a core square of side %g and a ring of %d layers), lowest point touching the block at the origin\n"
            "(ids 100001-). Node sets: block_top, block_bottom, block_xmin, cyl_surface (the curved face),\n"
            "cyl_bottom (its part x <= %g), cyl_top (the flat face z = %g), cyl_xmin, xmin (both), yfaces (every\n"
            "node: y = 0 or %g). Element sets BLOCK, CYLINDER. Written by scripts/make_pair_cases.py."
            % (T, LB, T, HB, info["nx"], info["nz"], R, R, R, info["a"], info["nr"], XF, R, T))
    P, b, p0 = P_TARGET, B_TARGET, 2 * P_TARGET / (math.pi * B_TARGET)
    _, corr, pen = approach()
    head = """Plane-strain Hertz contact between two deformable bodies: an elastic half-cylinder (R = %g, axis
along y) pressed on an elastic block, both E = %g, nu = %g (J2, yield stress 1e9), frictionless.
Half model x >= 0, one element along y (t = %g, y fixed on every node: plane strain); mesh
%s (scripts/make_pair_cases.py; %d hexahedra): the block [0,%g] x [0,%g] x [-%g,0],
bottom fixed; the cylinder's quarter x in [0, R], its flat cut face z = R on top, its lowest point
touching the block at the origin (zero gap); symmetry x = 0 (set xmin, both bodies). The cylinder's
top face (cyl_top) displaced by -d, d = %g, in 4 load steps (x free: a frictionless platen).
Pair p: slave block_top (the block's flat top, %d elements of %g in x < %g), master cyl_surface (the
cylinder's curved faces, %d elements of %.4g of arc in x < %g). The slave is the flat and finer side:
the pressure is read at its nodes with tributary lengths along a straight line, and its nodes sample
the master's facets (sagitta h^2/8R = 4e-5) densely, none falling between two master nodes unseen;
the master is the smooth convex side. Every slave node lies on an edge of a master face (y = 0 or
y = t; the one on x = 0 on the symmetry edge too): the projection must accept a face's boundary.
Closed form (plane strain, P the force per unit length of the whole contact): 1/E* = (1-nu1^2)/E1 +
(1-nu2^2)/E2 (E* = %.6g), b = sqrt(4 P R/(pi E*)), p0 = 2 P/(pi b) = E* b/(2 R), p(x) =
p0 sqrt(1 - x^2/b^2). For b = 1: P = %.6g per unit length (%.6g on the modelled half strip of
thickness t), p0 = %.6g.
The approach d has no simple closed form (the bodies' size enters through log terms); %g was
estimated from cases/pair_hertz_rigid.opts (this mesh, each body against a rigid counterpart): at
the force P the block under a rigid cylinder approaches %.5g, the cylinder on a rigid plane %.5g
(elastic, the penalty's penetration taken out); against a rigid body the contact is narrower (b/sqrt 2)
and each body's approach less by 2 (1-nu^2) P/(pi E) ln(sqrt 2) in the pair: -%.4g for the two; the
pair's penalty adds its penetration at the centre, about %.2g. The pair at %g gave P = 42.668
(b = 0.9944), 1.1 %% short: d = %g, from the last step's slope dP/dd = 285 (b grows as sqrt(P)).
Run (2026-11-29, 1 and 2 ranks alike, 4 steps, 21 Newton iterations): P = 43.2545 (b = 1.0012,
p0 = 27.505 by Hertz), fitted b -0.28 %%, p0 +0.24 %%, the profile's RMS deviation from the fitted
ellipse 1.2 %% of p0, the edge between the nodes x = 0.990 (pressed) and 1.040; the contact.csv row
equals the slave nodes' sum, the reaction of cyl_top 3.4e-4 less (the normals tilt by x/R).
The automatic penalty (K_N = E A/h, h = %g) lets the peak pressure penetrate about p0 h/E = %.2g
(largest penetration 1.38e-3; 3 %% of the surfaces' deflection b^2/2R). With one material on both
sides (Dundurs' beta = 0) friction changes nothing in the half-space theory.
Check: tests/checks/hertz_pair.py out/pair_hertz (b and p0 fitted to the slave nodes' pressures
against the closed form from the run's own P; default tolerance 5 %%, --tol).""" % (
        R, E, NU, T, mesh, ne, LB, T, HB, D, info["fine_block"], H_BLOCK, XF, info["fine_cyl"], H_CYL, XF,
        ESTAR, P, P * T / 2, p0, D_ESTIMATE, APPROACH_BLOCK, APPROACH_CYL, corr, pen, D_ESTIMATE, D, H_BLOCK,
        p0 * H_BLOCK / E)
    lines = hertz_common(mesh) + [
        "-bc_press_values %g" % -D,
        "-pair_names p",
        "-pair_p_slave block_top",
        "-pair_p_master cyl_surface",
        "-pair_p_friction 0",
        "-pair_p_penalty_normal auto",
        "-load_steps 4",
        "-output_dir out/pair_hertz",
        "-output_interval 1"]
    write_case("pair_hertz", head, lines)

    # the same bodies, each against a rigid counterpart (runs without the pair): d's estimate
    head = """The bodies of cases/pair_hertz.opts (mesh %s), each against a rigid counterpart, in one run
without contact between them: the block's top (block_top) under a rigid cylinder (tool roller, R = %g,
moved down %g), the cylinder's curved face (cyl_surface) on a rigid plane z = 0 (tool floor) with
its top face displaced by -%g; automatic penalty, frictionless, 8 load steps. The approach of each
at the pair's force P = %.5g per unit length (contact.csv: force_full = P with -model_symmetry 2/t
= %g; the travel, or d times the load, less the penalty's penetration at x = 0, contact_gap) gave
the estimate of d in cases/pair_hertz.opts (scripts/make_pair_cases.py, APPROACH_BLOCK = %g,
APPROACH_CYL = %g). Against a rigid body E* = E/(1-nu^2) = %.6g. Checks of the pressure profiles:
  tests/checks/hertz_pair.py out/pair_hertz_rigid --rigid --pair roller --reaction base_fz
  tests/checks/hertz_pair.py out/pair_hertz_rigid --rigid --pair floor --slave cyl_surface
(b +2.1 %%, p0 -2.0 %% against Hertz for the block, +1.8 %%, -1.8 %% for the cylinder, at the last step).""" % (
        mesh, R, 0.12, 0.10, P, 2 / T, APPROACH_BLOCK, APPROACH_CYL, E / (1 - NU * NU))
    lines = hertz_common(mesh) + [
        "-bc_press_values -0.1",
        "-model_symmetry %g" % (2 / T),
        "-tool_names roller,floor",
        "-tool_roller_contact_set block_top",
        "-tool_roller_motion 0,0,-0.12",
        "-tool_roller_patches 1",
        "-tool_roller_patch0_type cylinder",
        "-tool_roller_patch0_center 0,0,%g" % R,
        "-tool_roller_patch0_axis 0,1,0",
        "-tool_roller_patch0_ref 0,0,-1",
        "-tool_roller_patch0_radius %g" % R,
        "-tool_roller_patch0_range -90,90,-1,1",
        "-tool_floor_contact_set cyl_surface",
        "-tool_floor_patches 1",
        "-tool_floor_patch0_type plane",
        "-tool_floor_patch0_origin -5,-1,0",
        "-tool_floor_patch0_e1 1,0,0",
        "-tool_floor_patch0_e2 0,1,0",
        "-tool_floor_patch0_range 0,30,0,2",
        "-contact_penalty_normal auto",
        "-contact_friction 0",
        "-load_steps 8",
        "-output_dir out/pair_hertz_rigid",
        "-output_interval 1"]
    write_case("pair_hertz_rigid", head, lines)
    return dict(mesh=mesh, nv=nv, ne=ne, per=per, sj=sj, aspect=asp, info=info,
                sets={k: len(v) for k, v in d.nsets.items()}, P=P, b=b, p0=p0)


def write_case(name, header, lines):
    with open(os.path.join(CASES, name + ".opts"), "w") as f:
        for h in header.splitlines():
            f.write("# %s\n" % h)
        f.write("\n".join(lines) + "\n")


def report(name, r):
    print("%s: %d nodes, %d hexahedra (%s); smallest scaled Jacobian %.3f, largest edge ratio %.1f"
          % (r["mesh"], r["nv"], r["ne"], ", ".join("%s %d" % kv for kv in r["per"].items()), r["sj"], r["aspect"]))
    print("  node sets: " + ", ".join("%s %d" % kv for kv in r["sets"].items()))


def main(argv):
    os.makedirs(MESHES, exist_ok=True)
    report("patch", patch_case(3, "pair_patch"))
    report("patch", patch_case(8, "pair_patch_nested"))
    r = hertz_case()
    report("hertz", r)
    i = r["info"]
    print("  block: %d x %d; x: %g to %.3g (ratio %.3f), z: %g to %.3g (ratio %.3f); cylinder: core %d x %d, "
          "ring %d x %d, arc %.4g to %.3g, %.3g" % (i["nx"], i["nz"], i["block_dx"][0], i["block_dx"][1], i["block_dx"][2],
                                                 i["block_dz"][0], i["block_dz"][1], i["block_dz"][2], i["n1"], i["n2"],
                                                 i["n1"] + i["n2"], i["nr"], *i["cyl_arc"]))
    _, corr, pen = approach()
    print("  Hertz: E* %.6g; for b = %g: P %.6g per unit length (%.6g on the half strip), p0 %.6g; d %g "
          "(estimated %g = %.4g + %.4g - %.4g + %.4g)" % (ESTAR, B_TARGET, r["P"], r["P"] * T / 2, r["p0"], D,
                                                       D_ESTIMATE, APPROACH_BLOCK, APPROACH_CYL, corr, pen))
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
