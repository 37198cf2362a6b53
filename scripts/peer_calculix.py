#!/usr/bin/env python3
"""The hemispherical punch benchmark with friction side by side with CalculiX (ccx), one core each.

usage: scripts/peer_calculix.py [--reps N] [--write-doc] [--keep DIR]

1. Runs this code's seed case with analytic tools (cases/hemisphere_friction_analytic.opts: 301
   hexahedra, one layer, F-bar hex8, Swift aluminium, mu = 0.15, penalties per node K_N 1e5,
   K_T 5e3) and takes its mesh from fields.h5.
2. Writes the same problem as a CalculiX deck (scripts/calculix/hemisphere_friction.inp): the
   same nodes and hexahedra as C3D8I (incompatible modes), the Swift curve tabulated as *PLASTIC,
   the clamped rim and the two symmetry planes, the punch (sphere R 50.8) and the die (torus,
   profile radius 6.35) as rigid bodies meshed with C3D8 shells whose outer faces are the master
   surfaces, face-to-face penalty contact with the same stiffness per unit area as this code's
   per-node penalties over the seed mesh's mean tributary area (12168 and 608.4 N/mm^3) and
   Coulomb friction 0.15, the punch moved 40 mm in increments of at most 2 mm.
3. Runs both --reps times (OMP_NUM_THREADS=1, one MPI rank), interleaved, and reports the
   punch force of the full sheet (4 x the quarter's) at 10, 20, 30, 40 mm, the wall times (medians)
   and their ratio, with the machine's load. --write-doc writes the section "Against CalculiX"
   of doc/notes/performance-log.md.
"""
import argparse, math, os, re, shutil, subprocess, sys, tempfile, time
import numpy as np
import h5py

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(HERE)
sys.path.insert(0, HERE)
import benchutil  # noqa: E402

CASE = "cases/hemisphere_friction_analytic.opts"
R_BLANK, T_BLANK = 59.18, 1.0
R_PUNCH = 50.8
DIE_MAJOR, DIE_MINOR, DIE_ZC = 59.18, 6.35, 7.35
TRAVEL = 40.0
KN_AREA, KT_AREA, MU = 12168.0, 608.4, 0.15
E, NU, SWK, SWE0, SWN = 69004.0, 0.3, 589.0, 1e-4, 0.216


def run_atrito(out):
    env = dict(os.environ, OMPI_ALLOW_RUN_AS_ROOT="1", OMPI_ALLOW_RUN_AS_ROOT_CONFIRM="1", OPENBLAS_NUM_THREADS="1")
    t0 = time.time()
    subprocess.run(["mpiexec", "-n", "1", os.path.join(ROOT, "bin", "atrito"), "-options_file", os.path.join(ROOT, CASE),
                    "-output_dir", out, "-output_interval", "100"], check=True, env=env, stdout=subprocess.DEVNULL, cwd=ROOT)
    return time.time() - t0


def atrito_force(out):
    import csv
    rows = [r for r in csv.DictReader(open(os.path.join(out, "contact.csv"))) if r["tool"] == "punch"]
    return np.array([0.0] + [float(r["travel"]) for r in rows]), np.array([0.0] + [float(r["force_full"]) for r in rows])


def rigid_shell(points_fn, nu, nv, thick, inward):
    """C3D8 shell of one layer: outer surface points_fn(i/nu, j/nv) (3-vector), the layer `thick`
    along -inward normal; returns nodes (N x 3), hexahedra (0-based, C3D8 order with the outer
    surface as face S2: nodes 5-8)"""
    P = np.array([[points_fn(i / nu, j / nv) for j in range(nv + 1)] for i in range(nu + 1)])
    N = np.array([[inward(P[i, j]) for j in range(nv + 1)] for i in range(nu + 1)])
    return shell_from_grid(P, N, thick)


def shell_from_grid(P, N, thick):
    """C3D8 shell of one layer from a grid of outer surface points P ((nu+1) x (nv+1) x 3) and unit
    vectors N into the tool: the inner nodes `thick` along N; nodes (inner, then outer) and hexahedra
    (0-based, outer face S2: nodes 5-8; orient() makes their volumes positive)"""
    nu, nv = P.shape[0] - 1, P.shape[1] - 1
    outer = P.reshape(-1, 3)
    inner = (P + thick * N).reshape(-1, 3)
    nodes = np.vstack([inner, outer])
    off = outer.shape[0]
    idx = lambda i, j: i * (nv + 1) + j
    hexa = []
    for i in range(nu):
        for j in range(nv):
            q = [idx(i, j), idx(i + 1, j), idx(i + 1, j + 1), idx(i, j + 1)]
            hexa.append(q + [k + off for k in q])
    return nodes, np.array(hexa)


def swift_rows(K, e0, n):
    """*PLASTIC rows of the Swift curve K (e0 + ep)^n, tabulated (stress, plastic strain)"""
    return [f"{K * (e0 + ep) ** n:.8g}, {ep}" for ep in
            [0, 0.0005, 0.001, 0.002, 0.004, 0.007, 0.01, 0.015, 0.02, 0.03, 0.05, 0.07, 0.1, 0.15, 0.2, 0.3, 0.4, 0.6, 0.8, 1.0, 2.0]]


def orient(nodes, hexa):
    """a hexahedron of negative volume gets its nodes reversed within each layer (1-4 and 5-8), so
    that every volume is positive and the outer layer stays nodes 5-8 (face S2)"""
    out = []
    for h in hexa:
        x = nodes[h]
        v = np.dot(np.cross(x[1] - x[0], x[3] - x[0]), x[4] - x[0])
        if v < 0:
            h = [h[0], h[3], h[2], h[1], h[4], h[7], h[6], h[5]]
        out.append(h)
    return np.array(out)


def write_deck(path, X, H):
    """X: blank nodes, H: blank hexahedra (0-based, standard hex8 order = Abaqus C3D8 order)"""
    nb = X.shape[0]
    r = np.hypot(X[:, 0], X[:, 1])
    rim = np.where(np.abs(r - R_BLANK) < 1e-6 * R_BLANK)[0]
    symx = np.where(np.abs(X[:, 0]) < 1e-9)[0]
    symy = np.where(np.abs(X[:, 1]) < 1e-9)[0]
    # punch: the polar cap of the sphere by the cube-face map (no degenerate elements), quadrant x, y >= 0 with a margin
    a = math.tan(math.radians(62.0))
    lo = -0.08 * a

    def punch_pt(s, t):
        u, v = lo + (a - lo) * s, lo + (a - lo) * t
        d = np.array([u, v, 1.0])
        return np.array([0, 0, -R_PUNCH]) + R_PUNCH * d / np.linalg.norm(d)

    pn, ph = rigid_shell(punch_pt, 24, 24, 1.0, lambda p: (np.array([0, 0, -R_PUNCH]) - p) / R_PUNCH)
    # die: the torus's lower inner quarter of the tube, azimuth -5..95 degrees
    def die_pt(s, t):
        ph_ = math.radians(-5 + 100 * s)
        ps = math.radians(160 + 112.5 * t)
        rr = DIE_MAJOR + DIE_MINOR * math.cos(ps)
        return np.array([rr * math.cos(ph_), rr * math.sin(ph_), DIE_ZC + DIE_MINOR * math.sin(ps)])

    def die_in(p):
        ph_ = math.atan2(p[1], p[0])
        c = np.array([DIE_MAJOR * math.cos(ph_), DIE_MAJOR * math.sin(ph_), DIE_ZC])
        return (c - p) / DIE_MINOR

    dn, dh = rigid_shell(die_pt, 30, 16, 1.0, die_in)
    ph = orient(pn, ph)
    dh = orient(dn, dh)
    # the outer face of each shell element is S2 in C3D8 numbering only if nodes 5-8 are outer:
    # after orient() a flipped element has its outer nodes still at 5-8 (we swapped within layers)
    op, od = nb, nb + pn.shape[0]
    ref_p, rot_p, ref_d, rot_d = od + dn.shape[0] + 1, od + dn.shape[0] + 2, od + dn.shape[0] + 3, od + dn.shape[0] + 4
    ep0, ed0 = H.shape[0] + 1, H.shape[0] + ph.shape[0] + 1
    with open(path, "w") as f:
        w = f.write
        w("** The hemispherical punch benchmark with friction (quarter model), written by scripts/peer_calculix.py\n")
        w("** from this code's seed mesh (cases/hemisphere_friction_analytic.opts). Units: mm, N, MPa.\n")
        w("*NODE, NSET=NALL\n")
        for i, x in enumerate(X):
            w(f"{i + 1}, {x[0]:.12g}, {x[1]:.12g}, {x[2]:.12g}\n")
        w("*NODE, NSET=NPUNCH\n")
        for i, x in enumerate(pn):
            w(f"{op + i + 1}, {x[0]:.12g}, {x[1]:.12g}, {x[2]:.12g}\n")
        w("*NODE, NSET=NDIE\n")
        for i, x in enumerate(dn):
            w(f"{od + i + 1}, {x[0]:.12g}, {x[1]:.12g}, {x[2]:.12g}\n")
        w(f"*NODE, NSET=PREF\n{ref_p}, 0, 0, {-R_PUNCH:.12g}\n*NODE, NSET=PROT\n{rot_p}, 0, 0, {-R_PUNCH:.12g}\n")
        w(f"*NODE, NSET=DREF\n{ref_d}, 0, 0, {DIE_ZC:.12g}\n*NODE, NSET=DROT\n{rot_d}, 0, 0, {DIE_ZC:.12g}\n")
        w("*ELEMENT, TYPE=C3D8I, ELSET=BLANK\n")
        for e, h in enumerate(H):
            w(f"{e + 1}, " + ", ".join(str(k + 1) for k in h) + "\n")
        w("*ELEMENT, TYPE=C3D8, ELSET=PUNCH\n")
        for e, h in enumerate(ph):
            w(f"{ep0 + e}, " + ", ".join(str(op + k + 1) for k in h) + "\n")
        w("*ELEMENT, TYPE=C3D8, ELSET=DIE\n")
        for e, h in enumerate(dh):
            w(f"{ed0 + e}, " + ", ".join(str(od + k + 1) for k in h) + "\n")
        for name, ids in (("RIM", rim), ("SYMX", symx), ("SYMY", symy)):
            w(f"*NSET, NSET={name}\n")
            for k in range(0, len(ids), 12):
                w(", ".join(str(i + 1) for i in ids[k:k + 12]) + "\n")
        w("*SURFACE, NAME=SBOTTOM, TYPE=ELEMENT\nBLANK, S1\n*SURFACE, NAME=STOP, TYPE=ELEMENT\nBLANK, S2\n")
        w("*SURFACE, NAME=MPUNCH, TYPE=ELEMENT\nPUNCH, S2\n*SURFACE, NAME=MDIE, TYPE=ELEMENT\nDIE, S2\n")
        w("*MATERIAL, NAME=AL\n*ELASTIC\n" f"{E:.12g}, {NU}\n*PLASTIC\n")
        w("".join(r + "\n" for r in swift_rows(SWK, SWE0, SWN)))
        w("*MATERIAL, NAME=RIGID\n*ELASTIC\n2e5, 0.3\n")
        w("*SOLID SECTION, ELSET=BLANK, MATERIAL=AL\n*SOLID SECTION, ELSET=PUNCH, MATERIAL=RIGID\n*SOLID SECTION, ELSET=DIE, MATERIAL=RIGID\n")
        w(f"*RIGID BODY, ELSET=PUNCH, REF NODE={ref_p}, ROT NODE={rot_p}\n*RIGID BODY, ELSET=DIE, REF NODE={ref_d}, ROT NODE={rot_d}\n")
        w("*SURFACE INTERACTION, NAME=SI\n*SURFACE BEHAVIOR, PRESSURE-OVERCLOSURE=LINEAR\n" f"{KN_AREA:.8g}\n*FRICTION\n{MU}, {KT_AREA:.8g}\n")
        w("*CONTACT PAIR, INTERACTION=SI, TYPE=SURFACE TO SURFACE\nSBOTTOM, MPUNCH\n*CONTACT PAIR, INTERACTION=SI, TYPE=SURFACE TO SURFACE\nSTOP, MDIE\n")
        w("*BOUNDARY\nRIM, 1, 3\nSYMX, 1, 1\nSYMY, 2, 2\nPREF, 1, 2\nPROT, 1, 3\nDREF, 1, 3\nDROT, 1, 3\n")
        w("*STEP, NLGEOM, INC=2000\n*STATIC\n0.025, 1., 1e-5, 0.025\n" f"*BOUNDARY\nPREF, 3, 3, {TRAVEL}\n")
        w("*NODE PRINT, NSET=PREF\nU, RF\n*END STEP\n")


def ccx_force(dat):
    """punch travel and force of the full sheet from the .dat file's U and RF blocks of PREF"""
    txt = open(dat).read()
    out = {}
    for kind, rows in re.findall(r"\s(displacements|forces) \([^)]*\) for set PREF and time\s+\S+\s*\n((?:\s*\d+\s+\S+\s+\S+\s+\S+\s*\n)+)", txt):
        vals = [float(x) for x in rows.split()[1:4]]
        out.setdefault(kind, []).append(vals[2])
    u = np.array([0.0] + out.get("displacements", []))
    f = np.array([0.0] + out.get("forces", []))
    n = min(len(u), len(f))
    return u[:n], 4 * f[:n]


def run_ccx(deck_dir, name="hemisphere_friction"):
    """runs ccx on deck_dir/name.inp on one core; its output in deck_dir/ccx.log"""
    env = dict(os.environ, OMP_NUM_THREADS="1", CCX_NPROC_EQUATION_SOLVER="1", CCX_NPROC_RESULTS="1", CCX_NPROC_STIFFNESS="1")
    t0 = time.time()
    p = subprocess.run(["ccx", "-i", name], cwd=deck_dir, env=env, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
    dt = time.time() - t0
    open(os.path.join(deck_dir, "ccx.log"), "w").write(p.stdout)
    return dt, p.returncode, p.stdout


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--reps", type=int, default=3)
    ap.add_argument("--write-doc", action="store_true")
    ap.add_argument("--keep", default=None, help="work folder (kept)")
    a = ap.parse_args()
    work = a.keep or tempfile.mkdtemp(prefix="peer_ccx_")
    os.makedirs(work, exist_ok=True)
    if not shutil.which("ccx"):
        sys.exit("peer_calculix: ccx not found (Debian package calculix-ccx)")
    out = os.path.join(work, "atrito")
    t_first = run_atrito(out)
    with h5py.File(os.path.join(out, "fields.h5"), "r") as f:
        X = f["mesh/coordinates"][...]
        H = f["mesh/hexahedra"][...]
    deckdir = os.path.join(HERE, "calculix")
    os.makedirs(deckdir, exist_ok=True)
    write_deck(os.path.join(deckdir, "hemisphere_friction.inp"), X, H)
    rundir = os.path.join(work, "ccx")
    os.makedirs(rundir, exist_ok=True)
    shutil.copy(os.path.join(deckdir, "hemisphere_friction.inp"), rundir)
    t_at, t_cc, loads = [t_first], [], []
    rc = 0
    for k in range(a.reps):
        loads.append(os.getloadavg()[0])
        dt, rc, log = run_ccx(rundir)
        t_cc.append(dt)
        if rc != 0 or "Job finished" not in log:
            print(log[-3000:])
            print(f"peer_calculix: ccx failed (exit {rc}); deck and log in {rundir}")
            break
        if k + 1 < a.reps:
            t_at.append(run_atrito(out))
    u_at, f_at = atrito_force(out)
    u_cc, f_cc = ccx_force(os.path.join(rundir, "hemisphere_friction.dat"))
    print(f"ccx increments: {len(u_cc) - 1}, last travel {u_cc[-1]:.3f} mm")
    rows = []
    for d in (10, 20, 30, 40):
        fa = np.interp(d, u_at, f_at) if u_at[-1] >= d - 1e-9 else float("nan")
        fc = np.interp(d, u_cc, f_cc) if u_cc[-1] >= d - 1e-9 else float("nan")
        rows.append((d, fa / 1e3, fc / 1e3, 100 * (fc - fa) / fa if fa else float("nan")))
        print(f"travel {d} mm: this code {fa / 1e3:.2f} kN, CalculiX {fc / 1e3:.2f} kN ({rows[-1][3]:+.1f} %)")
    ma, mc = float(np.median(t_at)), float(np.median(t_cc)) if t_cc else float("nan")
    print(f"wall time, one core: this code {ma:.2f} s (median of {len(t_at)}), CalculiX {mc:.2f} s (median of {len(t_cc)}), ratio {mc / ma:.1f}")
    if a.write_doc:
        body = ["## Against CalculiX", "", benchutil.measured_by("peer_calculix.py", ROOT), "",
                "The seed benchmark with friction, side by side with CalculiX 2.20 (`ccx`), one core each",
                f"(`scripts/peer_calculix.py --reps {a.reps} --write-doc`; the deck: `scripts/calculix/hemisphere_friction.inp`,",
                "generated from this code's mesh: the same 301 hexahedra as C3D8I, the Swift curve tabulated, rigid",
                "punch and die meshed with C3D8 shells, face-to-face penalty contact with this code's stiffness per unit",
                "area (12168 and 608.4 N/mm^3 = K_N 1e5, K_T 5e3 per node over the mean tributary area), mu 0.15).",
                "", "| travel (mm) | this code (kN) | CalculiX (kN) | difference |", "|---|---|---|---|"]
        body += [f"| {d} | {fa:.2f} | {fc:.2f} | {dd:+.1f} % |" for d, fa, fc, dd in rows]
        body += ["", f"Wall time to 40 mm: this code {ma:.2f} s (median of {len(t_at)}: C3D8-type F-bar hex8, analytic tools, 21 steps),",
                 f"CalculiX {mc:.2f} s (median of {len(t_cc)}, {len(u_cc) - 1} increments): CalculiX takes {mc / ma:.1f} times as long.",
                 f"Machine load (1-minute average) before the CalculiX runs: {', '.join(f'{l:.2f}' for l in loads)}."]
        benchutil.write_doc_section(os.path.join(ROOT, "doc", "notes", "performance-log.md"), "## Against CalculiX", "\n".join(body) + "\n")
    return 0 if rc == 0 else 1


if __name__ == "__main__":
    sys.exit(main())
