#!/usr/bin/env python3
"""The plane-strain Hertz pair (cases/pair_hertz.opts: an elastic half-cylinder pressed on an
elastic block, both deformable, frictionless) side by side with CalculiX (ccx) and its deformable
contact: the contact force, half-width and peak pressure against Hertz, and the wall time.

usage: scripts/peer_calculix_pairs.py [--reps N] [--types n2s,s2s] [--materials elastic,neohooke]
                                      [--element C3D8] [--auto-inc] [--work DIR] [--write-doc]
                                      [--skip-atrito]

1. Writes CalculiX decks (under --work, default a fresh folder in /tmp; never in the repository)
   from this code's mesh cases/meshes/pair_hertz.inp: the same nodes and hexahedra (C3D8, or
   --element C3D8I / C3D8R), E 1000, nu 0.3 on both bodies as *ELASTIC (St. Venant-Kirchhoff under
   NLGEOM) and as *HYPERELASTIC, NEO HOOKE (the same small-strain moduli; this code: Hencky), the
   same conditions (y fixed on every node: plane strain; x fixed on xmin: symmetry; block_bottom
   fixed; cyl_top moved by -0.173 in z, x free), the slave surface the block's top faces (the BLOCK elements' faces whose
   four nodes lie in block_top), the master the cylinder's curved faces (the CYLINDER elements'
   boundary faces whose four nodes lie in cyl_surface), *CONTACT PAIR, TYPE=NODE TO SURFACE
   (n2s) or SURFACE TO SURFACE (s2s), *SURFACE BEHAVIOR, PRESSURE-OVERCLOSURE=LINEAR with the
   slope E/h = 1000/0.05 = 2e4 per unit area (this code's automatic K_N = E A/h per slave node
   over its tributary area A), *STEP, NLGEOM, *STATIC, DIRECT: 4 increments of 0.25 as this code's
   4 steps (--auto-inc: ccx's automatic increments from 0.25, which it may cut).
2. Runs ccx (OMP_NUM_THREADS=1 and CCX_NPROC_*=1: one core, as ccx's default) and this code
   (ATRITO, default bin/atrito, one rank, OPENBLAS_NUM_THREADS=1) --reps times each, interleaved,
   with /proc/loadavg noted before each run.
3. Reads P (per unit length of the whole contact: 2 |RF_z of cyl_top| / t), the slave nodes'
   contact pressures (ccx: CPRESS of *CONTACT FILE, nodal; this code: contact_normal_force over the
   tributary length as tests/checks/hertz_pair.py), fits b and p0 to them with hertz_pair.py's
   fit_ellipse, and compares with Hertz from each run's own P (E* = 549.451, R = 10). Newton
   iterations: ccx's .sta file (the iterations of every attempt, cut ones included), this code's
   summary line. --write-doc writes the section "## Against CalculiX: the Hertz pair" of
   doc/notes/contact-bodies-log.md.
"""
import argparse
import math
import os
import re
import shutil
import statistics
import subprocess
import sys
import tempfile
import time

import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(HERE)
sys.path.insert(0, HERE)
sys.path.insert(0, os.path.join(ROOT, "tests", "checks"))
from hertz_pair import fit_ellipse, read_nset  # noqa: E402
from inpdeck import read_inp  # noqa: E402

CASE = "cases/pair_hertz.opts"
MESH = "cases/meshes/pair_hertz.inp"
E, NU = 1000.0, 0.3
R, T = 10.0, 0.1
D = 0.173                     # cyl_top's prescribed displacement (cases/pair_hertz.opts)
H_SLAVE = 0.05                # the block's top element size: K_N = E A/h per slave node
KN_AREA = E / H_SLAVE         # 2e4 per unit area
ESTAR = 1.0 / (2 * (1 - NU ** 2) / E)
STEPS = 4
DOC = os.path.join(ROOT, "doc", "notes", "contact-bodies-log.md")
HEADING = "## Against CalculiX: the Hertz pair"
TYPES = {"n2s": "NODE TO SURFACE", "s2s": "SURFACE TO SURFACE"}

# the faces of a C3D8 in CalculiX's (Abaqus') numbering S1..S6
FACES = {1: (0, 1, 2, 3), 2: (4, 5, 6, 7), 3: (0, 1, 5, 4), 4: (1, 2, 6, 5), 5: (2, 3, 7, 6), 6: (3, 0, 4, 7)}


def surface_faces(elems, elset, nodes):
    """(element, face number) of the elements of elset whose face's four nodes all lie in nodes
    and which no other element shares (boundary faces)"""
    nodes = set(nodes)
    count = {}
    for _, conn, _ in elems:
        for f in FACES.values():
            k = frozenset(conn[i] for i in f)
            count[k] = count.get(k, 0) + 1
    out = []
    for eid, conn, es in elems:
        if es != elset:
            continue
        for s, f in FACES.items():
            fn = [conn[i] for i in f]
            if all(n in nodes for n in fn) and count[frozenset(fn)] == 1:
                out.append((eid, s))
    return out


def material_lines(material):
    """*ELASTIC (St. Venant-Kirchhoff under NLGEOM: PK2 linear in the Green-Lagrange strain) or
    *HYPERELASTIC, NEO HOOKE with the same small-strain moduli (C10 = G/2, D1 = 2/K)"""
    if material == "elastic":
        return ["*ELASTIC", "%g, %g" % (E, NU)]
    G, K = E / (2 * (1 + NU)), E / (3 * (1 - 2 * NU))
    return ["*HYPERELASTIC, NEO HOOKE", "%.10g, %.10g" % (G / 2, 2 / K)]


def write_deck(path, kind, element, material="elastic", kn=KN_AREA, steps=STEPS, direct=True):
    X, elems, nsets = read_inp(os.path.join(ROOT, MESH))
    slave = surface_faces(elems, "BLOCK", nsets["block_top"])
    master = surface_faces(elems, "CYLINDER", nsets["cyl_surface"])
    L = ["** The plane-strain Hertz pair of cases/pair_hertz.opts (mesh %s), written by" % MESH,
         "** scripts/peer_calculix_pairs.py: %s contact, %s, %s, penalty slope %g per unit area." % (TYPES[kind], element, material, kn),
         "*NODE, NSET=NALL"]
    L += ["%d, %.12g, %.12g, %.12g" % ((n,) + X[n]) for n in sorted(X)]
    for es in ("BLOCK", "CYLINDER"):
        L.append("*ELEMENT, TYPE=%s, ELSET=%s" % (element, es))
        L += ["%d, %s" % (eid, ", ".join(map(str, c))) for eid, c, s in elems if s == es]
    for name in ("block_top", "block_bottom", "cyl_top", "cyl_surface", "xmin", "yfaces"):
        ids = sorted(set(nsets[name]))
        L.append("*NSET, NSET=%s" % name.upper())
        L += [", ".join(map(str, ids[k:k + 16])) for k in range(0, len(ids), 16)]
    L.append("*SURFACE, NAME=SSLAVE, TYPE=ELEMENT")
    L += ["%d, S%d" % f for f in slave]
    L.append("*SURFACE, NAME=SMASTER, TYPE=ELEMENT")
    L += ["%d, S%d" % f for f in master]
    L += ["*MATERIAL, NAME=EL"] + material_lines(material) + [
          "*SOLID SECTION, ELSET=BLOCK, MATERIAL=EL", "*SOLID SECTION, ELSET=CYLINDER, MATERIAL=EL",
          "*SURFACE INTERACTION, NAME=SI", "*SURFACE BEHAVIOR, PRESSURE-OVERCLOSURE=LINEAR",
          "%.8g" % kn,
          "*CONTACT PAIR, INTERACTION=SI, TYPE=%s" % TYPES[kind], "SSLAVE, SMASTER",
          "*BOUNDARY", "YFACES, 2, 2", "XMIN, 1, 1", "BLOCK_BOTTOM, 1, 3",
          "*STEP, NLGEOM, INC=1000", "*STATIC, DIRECT" if direct else "*STATIC", "%g, 1., 1e-5, %g" % (1.0 / steps, 1.0 / steps),
          "*BOUNDARY", "CYL_TOP, 3, 3, %.12g" % -D,
          "*NODE PRINT, NSET=CYL_TOP, TOTALS=ONLY", "RF",
          "*NODE PRINT, NSET=BLOCK_TOP", "U",
          "*CONTACT PRINT", "CSTR, CDIS",
          "*END STEP"]
    open(path, "w").write("\n".join(L) + "\n")
    return len(slave), len(master)


# ---------------------------------------------------------------- runs
def run_ccx(rundir, name="hz"):
    """ccx on rundir/name.inp, one core; (wall s, child CPU s, exit status, log)"""
    env = dict(os.environ, OMP_NUM_THREADS="1", CCX_NPROC_EQUATION_SOLVER="1", CCX_NPROC_RESULTS="1",
               CCX_NPROC_STIFFNESS="1")
    c0, t0 = children_cpu(), time.time()
    p = subprocess.run(["ccx", "-i", name], cwd=rundir, env=env, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
    dt, cpu = time.time() - t0, children_cpu() - c0
    open(os.path.join(rundir, "ccx.log"), "w").write(p.stdout)
    ok = p.returncode == 0 and "Job finished" in p.stdout
    return dt, cpu, ok, p.stdout


def run_atrito(exe, out):
    """this code's case on one rank; (wall s, child CPU s, ok, log)"""
    env = dict(os.environ, OMPI_ALLOW_RUN_AS_ROOT="1", OMPI_ALLOW_RUN_AS_ROOT_CONFIRM="1", OPENBLAS_NUM_THREADS="1",
               OMP_NUM_THREADS="1")
    shutil.rmtree(out, ignore_errors=True)
    c0, t0 = children_cpu(), time.time()
    p = subprocess.run([exe, "-options_file", os.path.join(ROOT, CASE), "-output_dir", out], cwd=ROOT, env=env,
                       stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
    dt, cpu = time.time() - t0, children_cpu() - c0
    return dt, cpu, p.returncode == 0, p.stdout


def children_cpu():
    import resource
    ru = resource.getrusage(resource.RUSAGE_CHILDREN)
    return ru.ru_utime + ru.ru_stime


def loadavg():
    try:
        return open("/proc/loadavg").read().split()[0]
    except OSError:
        return "?"


# ---------------------------------------------------------------- results
def pair_lines(ids, X0):
    """the slave node ids grouped in pairs through the thickness (the same reference x, z), by x"""
    key = {}
    for n in ids:
        key.setdefault((round(X0[n][0], 9), round(X0[n][2], 9)), []).append(n)
    lines = sorted(key.values(), key=lambda ns: X0[ns[0]][0])
    assert all(len(ns) == 2 for ns in lines), "the slave set is not pairs of nodes through the thickness"
    return lines


def tributary(xc):
    """each point's tributary length along the current surface (half of each adjacent segment)"""
    seg = np.linalg.norm(np.diff(xc[:, [0, 2]], axis=0), axis=1)
    trib = np.zeros(len(xc))
    trib[:-1] += seg / 2
    trib[1:] += seg / 2
    return trib


def fit(xc, p):
    """b, p0 fitted to pressures p at the current mid-thickness points xc (n x 3, along x) as
    tests/checks/hertz_pair.py; the tributary lengths; the RMS deviation over x < 1.5 b; the last
    pressed node's x"""
    trib = tributary(xc)
    xs = xc[:, 0]
    b, p0 = fit_ellipse(xs, p, trib)
    s = np.sqrt(np.clip(1 - (xs / b) ** 2, 0, None))
    inside = xs < 1.5 * b
    rms = math.sqrt(np.sum((trib * (p - p0 * s) ** 2)[inside]) / np.sum(trib[inside]))
    pressed = np.nonzero(p > 0)[0]
    return dict(b=b, p0=p0, rms=rms, trib=trib, x_edge=xs[pressed.max()] if len(pressed) else 0.0,
                P_contact=2 * np.sum(p * trib))


def dat_block(txt, head, setname=None):
    """the rows of the last block of the .dat file whose title starts with head (and names set)"""
    pat = re.escape(head) + r"[^\n]*" + (r"for set " + re.escape(setname) + r"[^\n]*" if setname else "") + \
        r"time\s+(\S+)\s*\n\s*\n((?:[ \t]*[-\d][^\n]*\n)+)"
    m = re.findall(pat, txt)
    if not m:
        return None, None
    t, rows = m[-1]
    return float(t), [r.split() for r in rows.strip().split("\n")]


def frd_contact(path):
    """{node: (COPEN, CPRESS)} of the last CONTACT block of a .frd file"""
    out, cur = {}, None
    for line in open(path):
        if line.startswith(" -4  CONTACT"):
            cur = {}
        elif cur is not None:
            if line.startswith(" -1"):
                v = [float(line[13 + 12 * k:25 + 12 * k]) for k in range(6)]
                cur[int(line[3:13])] = (v[0], v[3])
            elif line.startswith(" -3"):
                out, cur = cur, None
    return out


def ccx_results(rundir, X0, lines, name="hz"):
    txt = open(os.path.join(rundir, name + ".dat")).read()
    t, rf = dat_block(txt, "total force", "CYL_TOP")
    _, u = dat_block(txt, "displacements", "BLOCK_TOP")
    U = {int(r[0]): np.array([float(v) for v in r[1:4]]) for r in u}
    cp = frd_contact(os.path.join(rundir, name + ".frd"))
    xc = np.array([np.mean([np.array(X0[n]) + U[n] for n in ns], axis=0) for ns in lines])
    p = np.array([np.mean([cp.get(n, (0.0, 0.0))[1] for n in ns]) for ns in lines])
    its, incs, cuts = 0, 0, 0
    for line in open(os.path.join(rundir, name + ".sta")):
        v = line.split()
        if len(v) == 7 and v[0].isdigit():
            its += int(v[3])
            if v[2].endswith("U"):       # an attempt that did not converge: the increment cut
                cuts += 1
            else:
                incs += 1
    r = fit(xc, p)
    r.update(time=t, P=2 * abs(float(rf[0][2])) / T, its=its, incs=incs, cuts=cuts,
             pen=-min(cp.get(n, (0.0, 0.0))[0] for ns in lines for n in ns))
    return r


def atrito_results(out, X0, lines, log):
    import csv
    import h5py
    with h5py.File(os.path.join(out, "fields.h5"), "r") as f:
        g = f["steps"][sorted(f["steps"])[-1]]
        nid = f["mesh/node_ids"][:]
        x = f["mesh/coordinates"][:] + g["displacement"][:]
        fn = g["contact_normal_force"][:]
        gap = g["contact_gap"][:] if "contact_gap" in g else None
    row = {int(i): k for k, i in enumerate(nid)}
    xc = np.array([np.mean([x[row[n]] for n in ns], axis=0) for ns in lines])
    F = np.array([sum(fn[row[n]] for n in ns) for ns in lines])
    F = F if F.sum() > 0 else -F
    r = fit(xc, F / (tributary(xc) * T))
    hist = list(csv.DictReader(open(os.path.join(out, "history.csv"))))
    m = re.search(r"^done: (\d+) steps, (\d+) Newton iterations, (\d+) cuts", log, re.M)
    r.update(P=2 * abs(float(hist[-1]["press_fz"])) / T, its=int(m.group(2)) if m else -1,
             incs=int(m.group(1)) if m else -1, cuts=int(m.group(3)) if m else 0, P_slave=2 * F.sum() / T,
             pen=-min(gap[row[n]] for ns in lines for n in ns) if gap is not None else float("nan"))
    return r


def hertz(P):
    b = math.sqrt(4 * P * R / (math.pi * ESTAR))
    return b, 2 * P / (math.pi * b)


# ---------------------------------------------------------------- main
def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0], formatter_class=argparse.RawDescriptionHelpFormatter,
                                 epilog=__doc__.split("\n", 2)[2])
    ap.add_argument("--reps", type=int, default=3)
    ap.add_argument("--types", default="n2s,s2s", help="ccx contact types: n2s (NODE TO SURFACE), s2s (SURFACE TO SURFACE)")
    ap.add_argument("--materials", default="elastic,neohooke", help="ccx materials: elastic (*ELASTIC), neohooke")
    ap.add_argument("--element", default="C3D8", help="ccx element type (C3D8, C3D8I, C3D8R)")
    ap.add_argument("--auto-inc", action="store_true", help="ccx's automatic increments (default: *STATIC, DIRECT, 4 x 0.25)")
    ap.add_argument("--work", default=None, help="work folder (default: a new one under /tmp)")
    ap.add_argument("--write-doc", action="store_true", help="write the section of doc/notes/contact-bodies-log.md")
    ap.add_argument("--skip-atrito", action="store_true")
    a = ap.parse_args()
    if not shutil.which("ccx"):
        sys.exit("peer_calculix_pairs: ccx not found (Debian package calculix-ccx)")
    work = a.work or tempfile.mkdtemp(prefix="peer_pairs_")
    os.makedirs(work, exist_ok=True)
    exe = os.environ.get("ATRITO", os.path.join(ROOT, "bin", "atrito"))
    X0 = read_inp(os.path.join(ROOT, MESH))[0]
    lines = pair_lines(sorted(set(read_nset(os.path.join(ROOT, MESH), "block_top"))), X0)

    variants = [(k, m) for m in a.materials.split(",") for k in a.types.split(",")]
    runs = {}
    for k, m in variants:
        d = os.path.join(work, "ccx_%s_%s" % (k, m))
        os.makedirs(d, exist_ok=True)
        ns, nm = write_deck(os.path.join(d, "hz.inp"), k, a.element, m, direct=not a.auto_inc)
        # the nodal contact pressures (CPRESS) come from the .frd file
        txt = open(os.path.join(d, "hz.inp")).read().replace("*END STEP", "*CONTACT FILE\nCSTR, CDIS\n*END STEP")
        open(os.path.join(d, "hz.inp"), "w").write(txt)
        runs[("ccx", k, m)] = dict(dir=d, wall=[], cpu=[], load=[], ok=True)
    print("peer_calculix_pairs: decks in %s (slave %d faces, master %d faces; slope %g per unit area)" % (work, ns, nm, KN_AREA))
    if not a.skip_atrito:
        runs[("atrito",)] = dict(dir=os.path.join(work, "atrito"), wall=[], cpu=[], load=[], ok=True)
    logs = {}
    for rep in range(a.reps):
        for key, r in runs.items():
            if not r["ok"]:
                continue
            r["load"].append(loadavg())
            if key[0] == "ccx":
                dt, cpu, ok, log = run_ccx(r["dir"])
            else:
                dt, cpu, ok, log = run_atrito(exe, r["dir"])
            logs[key] = log
            r["ok"] = ok
            if not ok:
                print(log[-2000:])
                print("peer_calculix_pairs: %s failed (see %s)" % (" ".join(key), r["dir"]))
                continue
            r["wall"].append(dt)
            r["cpu"].append(cpu)
            print("  run %d %-22s %6.2f s wall, %6.2f s CPU (load %s)" % (rep + 1, " ".join(key), dt, cpu, r["load"][-1]))

    rows = []
    ref = None
    for key, r in runs.items():
        if not r["ok"] and not r["wall"]:
            rows.append((key, None, r))
            continue
        res = ccx_results(r["dir"], X0, lines) if key[0] == "ccx" else atrito_results(r["dir"], X0, lines, logs[key])
        if key[0] == "atrito":
            ref = res
        rows.append((key, res, r))
    rows.sort(key=lambda kr: kr[0][0] != "atrito")
    table = ["| code | P | b | p0 | profile RMS | max. penetration | increments, Newton its | wall (median) | CPU (median) |",
             "|---|---|---|---|---|---|---|---|---|"]
    for key, res, r in rows:
        name = label(key, a.element)
        if res is None:
            table.append("| %s | did not finish | | | | | | | |" % name)
            continue
        bH, p0H = hertz(res["P"])
        dP = "" if ref is None or res is ref else " (%+.2f %%)" % (100 * (res["P"] / ref["P"] - 1))
        incs = "%d%s" % (res["incs"], " (%d cut)" % res["cuts"] if res["cuts"] else "")
        table.append("| %s | %.4g%s | %.4f (%+.2f %%) | %.4g (%+.2f %%) | %.2f %% | %.3g | %s, %d | %.2f s | %.2f s |" % (
            name, res["P"], dP, res["b"], 100 * (res["b"] / bH - 1), res["p0"], 100 * (res["p0"] / p0H - 1),
            100 * res["rms"] / res["p0"], res["pen"], incs, res["its"], statistics.median(r["wall"]),
            statistics.median(r["cpu"])))
        print("%s: P %.5g (slave pressures' sum %.5g), Hertz b %.5g p0 %.5g; fitted b %.5g p0 %.5g; edge x %.4g; "
              "RMS %.3g; penetration %.3g; %d increments, %d iterations; wall %s; CPU %s; load %s" % (
                  name, res["P"], res["P_contact"], bH, p0H, res["b"], res["p0"], res["x_edge"], res["rms"], res["pen"],
                  res["incs"], res["its"], " ".join("%.2f" % w for w in r["wall"]), " ".join("%.2f" % w for w in r["cpu"]),
                  " ".join(r["load"])))
    print("\n".join(table))
    if a.write_doc:
        write_doc(a, table, runs)
    return 0 if all(r["ok"] for r in runs.values()) else 1


def label(key, element):
    if key[0] == "atrito":
        return "this code (node to surface, hex8 F-bar, Hencky)"
    return "CalculiX %s (%s, %s)" % (TYPES[key[1]].lower(), element,
                                     "*ELASTIC: St. Venant-Kirchhoff" if key[2] == "elastic" else "neo-Hooke")


def write_doc(a, table, runs):
    import benchutil
    if not os.path.exists(DOC):
        open(DOC, "w").write(
            "# Contact between bodies: measurements and investigations\n\n"
            "Measurements behind [contact-bodies.md](../contact-bodies.md) (node-to-surface penalty pairs between\n"
            "deformable bodies), kept as written, dates included. `scripts/peer_calculix_pairs.py --write-doc`\n"
            "rewrites the section \"Against CalculiX: the Hertz pair\".\n")
    loads = sorted(set(l for r in runs.values() for l in r["load"]), key=float)
    cmd = "scripts/peer_calculix_pairs.py --reps %d --write-doc" % a.reps + \
        ("" if a.element == "C3D8" else " --element " + a.element) + (" --auto-inc" if a.auto_inc else "")
    body = [HEADING, "", benchutil.measured_by("peer_calculix_pairs.py", ROOT), "",
            "The plane-strain Hertz pair (`cases/pair_hertz.opts`: an elastic half-cylinder R = 10 pressed by d = 0.173",
            "on an elastic block, E 1000, nu 0.3 both, frictionless, 3,656 hexahedra) in CalculiX 2.20 (`ccx`) with its",
            "deformable contact, the deck generated from `cases/meshes/pair_hertz.inp` (written under the work folder,",
            "not kept): the same nodes and hexahedra (%s), the same conditions (y fixed on every node, x on `xmin`," % a.element,
            "`block_bottom` fixed, `cyl_top` moved by -0.173 in z), slave the block's top faces, master the cylinder's",
            "curved faces, `*SURFACE BEHAVIOR, PRESSURE-OVERCLOSURE=LINEAR` with the slope E/h = 2e4 per unit area",
            "(this code's automatic K_N = E A/h per slave node, h = 0.05), `*STEP, NLGEOM`, %s." % (
                "automatic increments from 0.25" if a.auto_inc else "`*STATIC, DIRECT`: 4 increments of 0.25 as this code's 4 steps"),
            "Materials: ccx's `*ELASTIC` under NLGEOM is St. Venant-Kirchhoff (PK2 linear in the Green-Lagrange strain);",
            "neo-Hooke: `*HYPERELASTIC, NEO HOOKE` with C10 = G/2 = 192.31, D1 = 2/K = 0.0024 (the same small-strain",
            "moduli); this code: the Hencky law (J2 with yield 1e9, never reached).",
            "",
            "P: the force per unit length of the whole contact, 2 |RF_z(cyl_top)| / t (this code: its reaction `press_fz`,",
            "3.4e-4 below the slave nodes' sum that hertz_pair.py takes; in brackets against this code's);",
            "b, p0: fitted p0 sqrt(1 - x^2/b^2) to the slave nodes' pressures (ccx: CPRESS of `*CONTACT FILE`; this",
            "code: `contact_normal_force` over the tributary length), as `tests/checks/hertz_pair.py`, each against",
            "Hertz from the run's own P (E* = 549.451); profile RMS: the deviation from the fitted ellipse over x < 1.5 b,",
            "of p0; max. penetration: the largest overclosure of a slave node (ccx: COPEN; this code: `contact_gap`);",
            "Newton iterations: ccx's `.sta` (every attempt), this code's summary line. Wall and CPU time (the child",
            "process's user + system time, the fairer measure on a loaded machine): medians of %d runs each, interleaved," % a.reps,
            "one core each (ccx with OMP_NUM_THREADS=1 and CCX_NPROC_*=1, its default being one thread anyway; this code",
            "one MPI rank, OPENBLAS_NUM_THREADS=1).", ""]
    body += table
    body += ["", "Load average (1 minute, /proc/loadavg) before the runs: %s to %s (%s cores)." % (
        loads[0], loads[-1], os.cpu_count()), "", "Regenerate: `%s` (ATRITO=path runs a copy of bin/atrito)." % cmd, ""]
    benchutil.write_doc_section(DOC, HEADING, "\n".join(body) + "\n", keep_written=True)


if __name__ == "__main__":
    sys.exit(main())
