#!/usr/bin/env python3
"""The NUMISHEET'93 square cup (aluminium) side by side with CalculiX (ccx): the draw-in of the
same model in a peer code.

usage: scripts/peer_calculix_cup.py [--stroke S] [--penalty K] [--mesh coarse|fine] [--keep DIR] [--skip-ccx]

The question it answers: how much of the difference between this code's draw-in and the measured
one ([D] in doc/forming.md: DX = DY = 5.3 mm at 15 mm of stroke) is the model's (one layer of
solid elements, rigid tools, Coulomb friction, an isotropic yield function) and how much this
code's. CalculiX has no anisotropic plasticity, so both run von Mises (J2) with the aluminium's
Swift curve.

1. Writes the CalculiX deck (scripts/calculix/numisheet93_cup_al.inp) from this code's coarse
   aluminium cup (cases/sheets/numisheet93_cup_al_coarse.inp: 30 x 30 x 1 hexahedra, as C3D8I,
   incompatible modes; --mesh fine: the fine cup's 60 x 60 x 1, the deck in the work folder); the
   punch, the die and the blank holder of cases/tools/numisheet93_cup_al_* as rigid bodies meshed
   with C3D8 shells (the same geometry: a flat head up to x, y = 27 as the tool file's, profile and
   shoulder radii 8, plan corner radii 10 and 12 about (25, 25), the die and holder faces from the
   shoulder's edge, plan radius 20 about (25, 25), outwards); face-to-face
   penalty contact (stiffness K per unit area, tangential stick slope K / 10, as the case's
   -contact_penalty_normal 1000 and -contact_penalty_tangential 100), mu = 0.162 on every tool;
   the holder's reference node driven by its force (19.6 kN / 4 on the quarter, a ramp in a first
   step) with a spring of 1 N/mm to ground on it (so that the holder is not singular before it
   touches: 1 N/mm x its travel of less than 0.1 mm is below 1e-4 of its force), the punch moved
   down by S (default 15 mm) in a second step.
2. Runs ccx (one core) and this code's case with -material_type j2 and the same stroke, once with
   the case's augmented Lagrangian (no penetration) and once with the plain penalty of step 1.
3. Prints DX, DY, DD at 15 mm (the mean of the top and bottom nodes at the blank's edge points
   (75, 0), (0, 75), (75, 75), as scripts/numisheet93.py measures them) and the holder's force.
"""
import argparse, math, os, re, shutil, subprocess, sys, tempfile, time
import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(HERE)
sys.path.insert(0, HERE)
from peer_calculix import orient, run_ccx, shell_from_grid, swift_rows  # noqa: E402

# the blank and the case of each mesh, and the case's draw steps over its 40 mm
MESHES = {"coarse": ("cases/sheets/numisheet93_cup_al_coarse.inp", "cases/numisheet93_cup_al_coarse.opts", 80),
          "fine": ("cases/sheets/numisheet93_cup_al_fine.inp", "cases/numisheet93_cup_al_fine.opts", 160)}
T = 0.81
E, NU = 70000.0, 0.3
SWK, SWE0, SWN = 576.79, 0.01658, 0.3593
MU = 0.162
F_HOLDER = 19600.0 / 4
C0 = 25.0                 # plan centre of the corner radii (x = y = 25)
R_HEAD = 2.0              # punch head: flat out to plan distance 2 from the skeleton (x = 27)
R_PROFILE = 8.0           # punch profile radius
R_SHOULDER = 8.0          # die shoulder radius
PUNCH_WALL = 10.0         # punch wall at plan distance 10 (x = 35)
DIE_WALL = 12.0           # die wall at plan distance 12 (x = 37)
FACE_IN, FACE_OUT = 20.0, 80.0   # die and holder faces from plan distance 20 (x = 45) outwards


def read_sheet(path):
    X, H, mode = {}, [], None
    for line in open(path):
        s = line.strip()
        if not s or s.startswith("**"):
            continue
        if s.startswith("*"):
            mode = "n" if s.upper().startswith("*NODE") else ("e" if s.upper().startswith("*ELEMENT") else None)
            continue
        v = [p for p in s.split(",") if p.strip()]
        if mode == "n":
            X[int(v[0])] = [float(p) for p in v[1:4]]
        elif mode == "e":
            H.append([int(p) for p in v[1:9]])
    ids = sorted(X)
    assert ids == list(range(1, len(ids) + 1)), "sheet nodes must be numbered 1..N"
    return np.array([X[i] for i in ids]), np.array(H) - 1


def skeleton(nside, ncorner):
    """plan points c and outward plan normals n along the quarter's rounded square: the side x = const
    (y from -5 to 25), the corner about (25, 25), the side y = const (x from 25 to -5)"""
    c, n = [], []
    for y in np.linspace(-5.0, C0, nside + 1):
        c.append((C0, y)); n.append((1.0, 0.0))
    for th in np.linspace(0, math.pi / 2, ncorner + 1)[1:]:
        c.append((C0, C0)); n.append((math.cos(th), math.sin(th)))
    for x in np.linspace(C0, -5.0, nside + 1)[1:]:
        c.append((x, C0)); n.append((0.0, 1.0))
    return np.array(c), np.array(n)


def sweep_shell(profile, nside, ncorner, thick):
    """C3D8 shell (one layer) of the surface swept by profile = [(rho, z, n_rho, n_z)] (n the contact
    normal, out of the tool) along the skeleton: nodes 5-8 of each hexahedron on the contact surface
    (S2), nodes 1-4 thick behind it"""
    c, n = skeleton(nside, ncorner)
    P, N = [], []
    for (cx, cy), (nx, ny) in zip(c, n):
        P.append([(cx + r * nx, cy + r * ny, z) for r, z, _, _ in profile])
        N.append([(-a * nx, -a * ny, -b) for _, _, a, b in profile])
    return oriented_shell(np.array(P), np.array(N), thick)


def oriented_shell(P, N, thick):
    nodes, hexa = shell_from_grid(P, N, thick)
    return nodes, orient(nodes, hexa)


def plane_shell(x0, x1, y0, y1, z, nz, n, thick):
    xs, ys = np.linspace(x0, x1, n + 1), np.linspace(y0, y1, n + 1)
    P = np.array([[(x, y, z) for y in ys] for x in xs])
    N = np.zeros_like(P)
    N[:, :, 2] = -nz
    return oriented_shell(P, N, thick)


def arc(rc, zc, r, a0, a1, k, sign):
    """profile points on the arc about (rc, zc) of radius r, angles a0..a1 (from -z towards +rho);
    the contact normal (point - centre)/r * sign"""
    out = []
    for a in np.linspace(a0, a1, k + 1):
        dr, dz = math.sin(a), -math.cos(a)
        out.append((rc + r * dr, zc + r * dz, sign * dr, sign * dz))
    return out


def merge(*parts):
    out = []
    for p in parts:
        for q in p:
            if out and abs(out[-1][0] - q[0]) < 1e-9 and abs(out[-1][1] - q[1]) < 1e-9:
                continue
            out.append(q)
    return out


def tools(stroke):
    H = stroke + 10.0
    # punch: head (plane) + profile arc (about rho = 2, z = t + 8, normal outwards from the punch) + wall
    head = plane_shell(-5.0, C0 + R_HEAD, -5.0, C0 + R_HEAD, T, -1.0, 16, 1.0)
    prof = merge(arc(R_HEAD, T + R_PROFILE, R_PROFILE, 0.0, math.pi / 2, 12, 1.0),
                 [(PUNCH_WALL, T + R_PROFILE + h, 1.0, 0.0) for h in np.linspace(0, H, 6)])
    side = sweep_shell(prof, 12, 12, 1.0)
    # die: face (normal +z) from rho = 80 in to 20, the shoulder about (20, -8) (normal from its
    # centre outwards), the wall rho = 12 down
    face = [(r, 0.0, 0.0, 1.0) for r in np.linspace(FACE_OUT, FACE_IN, 23)]
    sh = [(FACE_IN - R_SHOULDER * math.sin(a), -R_SHOULDER + R_SHOULDER * math.cos(a), -math.sin(a), math.cos(a))
          for a in np.linspace(0, math.pi / 2, 13)]
    wall = [(DIE_WALL, -R_SHOULDER - h, -1.0, 0.0) for h in np.linspace(0, H, 6)]
    die = sweep_shell(merge(face, sh, wall), 12, 12, 1.0)
    # holder: the die's face at z = t, normal -z
    holder = sweep_shell([(r, T, 0.0, -1.0) for r in np.linspace(FACE_IN, FACE_OUT, 25)], 12, 12, 1.0)
    return [("PUNCH", [head, side]), ("DIE", [die]), ("HOLDER", [holder])]


def write_deck(path, X, H, stroke, kn, sheet):
    nb = X.shape[0]
    lines = ["** NUMISHEET'93 square cup, aluminium, von Mises, quarter model: written by scripts/peer_calculix_cup.py",
             f"** from {sheet} and the geometry of cases/tools/numisheet93_cup_al_*.tool. Units: mm, N, MPa.",
             "*NODE, NSET=NALL"]
    lines += [f"{i + 1}, {x[0]:.12g}, {x[1]:.12g}, {x[2]:.12g}" for i, x in enumerate(X)]
    next_node, next_elem = nb + 1, H.shape[0] + 1
    elems, refs = [], {}
    for name, parts in tools(stroke):
        lines.append(f"*NODE, NSET=N{name}")
        conn = []
        for nodes, hexa in parts:
            lines += [f"{next_node + i}, {x[0]:.12g}, {x[1]:.12g}, {x[2]:.12g}" for i, x in enumerate(nodes)]
            conn += [[next_node + k for k in h] for h in hexa]
            next_node += nodes.shape[0]
        elems.append((name, next_elem, conn))
        next_elem += len(conn)
        refs[name] = (next_node, next_node + 1)
        lines.append(f"*NODE, NSET={name[0]}REF\n{next_node}, 0, 0, 0\n*NODE, NSET={name[0]}ROT\n{next_node + 1}, 0, 0, 0")
        next_node += 2
    lines.append("*ELEMENT, TYPE=C3D8I, ELSET=BLANK")
    lines += [f"{e + 1}, " + ", ".join(str(k + 1) for k in h) for e, h in enumerate(H)]
    for name, e0, conn in elems:
        lines.append(f"*ELEMENT, TYPE=C3D8, ELSET={name}")
        lines += [f"{e0 + e}, " + ", ".join(str(k) for k in h) for e, h in enumerate(conn)]
    lines.append(f"*ELEMENT, TYPE=SPRING1, ELSET=HSPRING\n{next_elem}, {refs['HOLDER'][0]}")
    sets = {"SYMX": np.where(np.abs(X[:, 0]) < 1e-9)[0], "SYMY": np.where(np.abs(X[:, 1]) < 1e-9)[0]}
    for nm, p in (("EDGEX", (75, 0)), ("EDGEY", (0, 75)), ("EDGED", (75, 75))):
        sets[nm] = np.where(np.hypot(X[:, 0] - p[0], X[:, 1] - p[1]) < 1e-6)[0]
        assert len(sets[nm]) == 2, nm
    for nm, ids in sets.items():
        lines.append(f"*NSET, NSET={nm}")
        lines += [", ".join(str(i + 1) for i in ids[k:k + 12]) for k in range(0, len(ids), 12)]
    lines += ["*SURFACE, NAME=SBOTTOM, TYPE=ELEMENT", "BLANK, S1", "*SURFACE, NAME=STOP, TYPE=ELEMENT", "BLANK, S2"]
    for name, _, _ in elems:
        lines += [f"*SURFACE, NAME=M{name}, TYPE=ELEMENT", f"{name}, S2"]
    lines += ["*MATERIAL, NAME=AL", "*ELASTIC", f"{E:.12g}, {NU}", "*PLASTIC"] + swift_rows(SWK, SWE0, SWN)
    lines += ["*MATERIAL, NAME=RIGID", "*ELASTIC", "2e5, 0.3", "*SOLID SECTION, ELSET=BLANK, MATERIAL=AL"]
    for name, _, _ in elems:
        lines.append(f"*SOLID SECTION, ELSET={name}, MATERIAL=RIGID")
    for name, _, _ in elems:
        lines.append(f"*RIGID BODY, ELSET={name}, REF NODE={refs[name][0]}, ROT NODE={refs[name][1]}")
    lines += ["*SPRING, ELSET=HSPRING", "3", "1.0",
              "*SURFACE INTERACTION, NAME=SI", "*SURFACE BEHAVIOR, PRESSURE-OVERCLOSURE=LINEAR", f"{kn:.8g}",
              "*FRICTION", f"{MU}, {kn / 10:.8g}"]
    for slave, master in (("STOP", "MPUNCH"), ("SBOTTOM", "MDIE"), ("STOP", "MHOLDER")):
        lines += ["*CONTACT PAIR, INTERACTION=SI, TYPE=SURFACE TO SURFACE", f"{slave}, {master}"]
    lines += ["*BOUNDARY", "SYMX, 1, 1", "SYMY, 2, 2", "PREF, 1, 3", "PROT, 1, 3", "DREF, 1, 3", "DROT, 1, 3",
              "HREF, 1, 2", "HROT, 1, 3",
              "*STEP, NLGEOM, INC=1000", "*STATIC", "0.25, 1., 1e-5, 0.25", "*CLOAD", f"HREF, 3, {-F_HOLDER:.8g}",
              "*NODE PRINT, NSET=HREF", "U, RF", "*END STEP",
              "*STEP, NLGEOM, INC=4000", "*STATIC", f"{0.5 / stroke:.6g}, 1., 1e-6, {0.5 / stroke:.6g}",
              "*BOUNDARY", f"PREF, 3, 3, {-stroke:.8g}",
              "*NODE PRINT, NSET=PREF", "U, RF", "*NODE PRINT, NSET=HREF", "U, RF",
              "*NODE PRINT, NSET=EDGEX", "U", "*NODE PRINT, NSET=EDGEY", "U", "*NODE PRINT, NSET=EDGED", "U",
              "*END STEP"]
    open(path, "w").write("\n".join(lines) + "\n")


def dat_blocks(dat, kind, setname):
    """{time: rows} of the .dat file's blocks 'kind (...) for set SETNAME and time t'"""
    txt = open(dat).read()
    pat = r"\s" + kind + r" \([^)]*\) for set " + setname + r" and time\s+(\S+)\s*\n((?:\s*\d+\s+\S+\s+\S+\s+\S+\s*\n)+)"
    out = []
    for t, rows in re.findall(pat, txt):
        vals = np.array([[float(x) for x in r.split()[1:4]] for r in rows.strip().split("\n")])
        out.append((float(t), vals))
    return out


def ccx_drawin(dat):
    pu = dat_blocks(dat, "displacements", "PREF")
    hr = dat_blocks(dat, "forces", "HREF")
    ex, ey, ed = (dat_blocks(dat, "displacements", s) for s in ("EDGEX", "EDGEY", "EDGED"))
    # the blocks of the draw step come in the same order: the punch's travel and the mean edge displacement
    n = min(len(pu), len(ex), len(ey), len(ed))
    tr = np.array([-pu[k][1][0, 2] for k in range(n)])
    dx = np.array([-ex[k][1][:, 0].mean() for k in range(n)])
    dy = np.array([-ey[k][1][:, 1].mean() for k in range(n)])
    dd = np.array([-(ed[k][1][:, 0] + ed[k][1][:, 1]).mean() / math.sqrt(2) for k in range(n)])
    fh = np.array([b[1][0, 2] for b in hr])
    return tr, dx, dy, dd, fh


def run_atrito(out, stroke, extra, mesh):
    case, draw_steps = MESHES[mesh][1:]
    env = dict(os.environ, OMPI_ALLOW_RUN_AS_ROOT="1", OMPI_ALLOW_RUN_AS_ROOT_CONFIRM="1", OPENBLAS_NUM_THREADS="1")
    steps = max(4, int(round(draw_steps * stroke / 40.0)))
    t0 = time.time()
    subprocess.run([os.environ.get("ATRITO", os.path.join(ROOT, "bin", "atrito")), "-options_file", os.path.join(ROOT, case),
                    "-output_dir", out, "-material_type", "j2", "-tool_punch_motion", f"0,0,{-stroke:g}",
                    "-stage_draw_steps", str(steps), "-stage_draw_dt_max", f"{1.0 / steps:.6g}"] + extra,
                   check=True, env=env, stdout=subprocess.DEVNULL, cwd=ROOT)
    return time.time() - t0


def atrito_drawin(out, strokes=(5.0, 10.0, 15.0)):
    """DX, DY, DD at the given strokes (interpolated between output steps, as scripts/numisheet93.py)
    and the holder's force over the draw (kN, full blank)"""
    import csv
    import h5py
    import numisheet93  # noqa: E402
    rows = list(csv.DictReader(open(os.path.join(out, "contact.csv"))))
    stroke = {int(r["step"]): abs(float(r["travel"])) for r in rows if r["tool"] == "punch"}
    hold = np.array([abs(float(r["force_full"])) for r in rows if r["tool"] == "holder" and r.get("stage") == "draw"]) / 1e3
    with h5py.File(os.path.join(out, "fields.h5"), "r") as f:
        X = f["mesh/coordinates"][:]
        U = {int(k): f["steps"][k]["displacement"][:] for k in f["steps"].keys()}
    steps = sorted(k for k in U if k in stroke or k == 0)
    h = np.array([0.0 if k == 0 else stroke[k] for k in steps])
    D = [numisheet93.drawin(X, U[k], T) for k in steps]
    res = {}
    for s in strokes:
        if h[-1] >= s - 1e-9:
            res[s] = {k: float(np.interp(s, h, [d[k] for d in D])) for k in ("DX", "DY", "DD")}
    return res, hold


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--stroke", type=float, default=15.0)
    ap.add_argument("--penalty", type=float, default=1000.0, help="normal contact stiffness per unit area (N/mm^3)")
    ap.add_argument("--mesh", choices=sorted(MESHES), default="coarse", help="the case's blank (default coarse)")
    ap.add_argument("--keep", default=None, help="work folder (kept)")
    ap.add_argument("--skip-ccx", action="store_true")
    ap.add_argument("--skip-atrito", action="store_true")
    a = ap.parse_args()
    sheet = MESHES[a.mesh][0]
    work = a.keep or tempfile.mkdtemp(prefix="peer_cup_")
    os.makedirs(work, exist_ok=True)
    X, H = read_sheet(os.path.join(ROOT, sheet))
    # the deck kept in the repository is the default one (coarse, stroke 15 mm, 1000 N/mm^3); others go to the work folder
    default = a.stroke == 15.0 and a.penalty == 1000.0 and a.mesh == "coarse"
    deck = os.path.join(HERE if default else work, *(["calculix"] if default else []), "numisheet93_cup_al.inp")
    write_deck(deck, X, H, a.stroke, a.penalty, sheet)
    if not a.skip_ccx:
        if not shutil.which("ccx"):
            sys.exit("peer_calculix_cup: ccx not found (Debian package calculix-ccx)")
        rundir = os.path.join(work, "ccx")
        os.makedirs(rundir, exist_ok=True)
        shutil.copy(deck, rundir)
        dt, rc, log = run_ccx(rundir, "numisheet93_cup_al")
        if rc != 0 or "Job finished" not in log:
            print(log[-3000:])
            sys.exit(f"peer_calculix_cup: ccx failed (exit {rc}); deck and log in {rundir}")
        tr, dx, dy, dd, fh = ccx_drawin(os.path.join(rundir, "numisheet93_cup_al.dat"))
        print(f"CalculiX: {dt:.1f} s, {len(tr)} increments to {tr[-1]:.2f} mm; holder force at the end {-4 * fh[-1]:.0f} N (full)")
        for s in (5, 10, 15, 40):
            if tr[-1] >= s - 1e-3:  # ccx ends its step at step time 0.999999
                print(f"  CalculiX at {s} mm: DX {np.interp(s, tr, dx):.3f}  DY {np.interp(s, tr, dy):.3f}  DD {np.interp(s, tr, dd):.3f}")
    if not a.skip_atrito:
        for label, extra in (("augmented Lagrangian (the case's)", []), ("plain penalty", ["-contact_augmented", "0"])):
            out = os.path.join(work, "atrito_" + ("auglag" if not extra else "penalty"))
            dt = run_atrito(out, a.stroke, extra + ["-contact_penalty_normal", f"{a.penalty:g}", "-contact_penalty_tangential", f"{a.penalty / 10:g}"], a.mesh)
            res, hold = atrito_drawin(out)
            print(f"this code, J2, {label}: {dt:.1f} s; holder force {hold.min():.2f}..{hold.max():.2f} kN (full)")
            for s, d in res.items():
                print(f"  this code at {s:g} mm: DX {d['DX']:.3f}  DY {d['DY']:.3f}  DD {d['DD']:.3f}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
