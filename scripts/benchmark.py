#!/usr/bin/env python3
"""The hemispherical punch benchmark, full 40 mm runs, and doc/benchmark.md.

usage: benchmark.py [--skip-runs] [--np N] [--fine] [--xfine] [--xfine-np N]
Runs (unless --skip-runs, which only re-reads out/): the seed-mesh cases with Coons tools
(the main cases), with analytic tools, with the paper's own 3-patch Coons tools, and the refined
meshes, on --np ranks (default 1); with --fine also the fine mesh (frictionless, analytic); with
--xfine the extra-fine mesh with friction and Coons tools (20400 hexahedra) on --xfine-np ranks
(default 2). Writes the figures to doc/figures/ and the tables, steps, Newton iterations and wall
times to doc/benchmark.md."""
import argparse
import csv
import os
import re
import subprocess
import sys
import time

import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.abspath(os.path.join(HERE, ".."))
PY = sys.executable
env = dict(os.environ, OMPI_ALLOW_RUN_AS_ROOT="1", OMPI_ALLOW_RUN_AS_ROOT_CONFIRM="1", OPENBLAS_NUM_THREADS="1")

ap = argparse.ArgumentParser()
ap.add_argument("--skip-runs", action="store_true")
ap.add_argument("--np", type=int, default=1)
ap.add_argument("--fine", action="store_true")
ap.add_argument("--xfine", action="store_true")
ap.add_argument("--xfine-np", type=int, default=2)
a = ap.parse_args()

CASES = ["hemisphere_frictionless", "hemisphere_friction", "hemisphere_frictionless_analytic", "hemisphere_friction_analytic",
         "hemisphere_frictionless_coons3", "hemisphere_friction_coons3",
         "hemisphere_frictionless_analytic_refined", "hemisphere_friction_analytic_refined"]
if a.fine:
    CASES.append("hemisphere_frictionless_analytic_fine")
if a.xfine:
    CASES.append("hemisphere_friction_xfine")
# the analytic tools also at the Coons cases' load steps and Newton strategy (their files' -load_
# and -newton_ options, and their increment bound, the default 1/-load_steps unless they set one),
# growing after every step (-load_grow_its 1000): both take the same steps, and the tools are
# compared at the same travels (checked below)
STEPPED = {}
for fr in ("frictionless", "friction"):
    opts = [l.split() for l in open(os.path.join(ROOT, "cases", f"hemisphere_{fr}.opts")) if l.startswith(("-load_", "-newton_"))]
    extra = [w for o in opts for w in o]
    if "-load_dt_max" not in extra:  # the main case's bound is its first increment (the default), not the analytic file's
        steps = int(extra[extra.index("-load_steps") + 1]) if "-load_steps" in extra else 10
        extra += ["-load_dt_max", repr(1.0 / steps)]
    STEPPED[f"hemisphere_{fr}_analytic_steps"] = (f"hemisphere_{fr}_analytic", extra + ["-load_grow_its", "1000"])
    CASES.append(f"hemisphere_{fr}_analytic_steps")
NP = {c: (a.xfine_np if c.endswith("_xfine") else a.np) for c in CASES}
TRAVELS = [10, 15, 20, 25, 30, 35, 40]


def run(case):
    log = os.path.join(ROOT, "out", case + ".log")
    src, extra = STEPPED.get(case, (case, []))
    cmd = ["mpiexec", "--oversubscribe", "-n", str(NP[case]), os.path.join(ROOT, "bin", "atrito"), "-options_file", os.path.join(ROOT, "cases", src + ".opts")] + extra
    if case in STEPPED:
        cmd += ["-output_dir", "out/" + case]
    t0 = time.time()
    with open(os.path.join(ROOT, "out", case + ".load"), "w") as f:  # the machine's load when it started
        f.write(f"{os.getloadavg()[0]:.2f}\n")
    with open(log, "w") as f:
        r = subprocess.run(cmd, cwd=ROOT, env=env, stdout=f, stderr=subprocess.STDOUT)
    print(f"{case}: exit {r.returncode}, {time.time() - t0:.1f} s", file=sys.stderr)


def summary(case):
    d = os.path.join(ROOT, "out", case)
    log = open(os.path.join(ROOT, "out", case + ".log")).read()
    m = re.search(r"done: (\d+) steps, (\d+) Newton iterations, (\d+) cuts, ([0-9.]+) s", log)
    mesh = re.search(r"mesh: (\d+) vertices, (\d+) hexahedra", log)
    rows = [r for r in csv.DictReader(open(os.path.join(d, "contact.csv"))) if r["tool"] == "punch"]
    t = np.array([0.0] + [float(r["travel"]) for r in rows])
    f = np.array([0.0] + [float(r["force_full"]) for r in rows]) / 1e3
    return dict(steps=int(m.group(1)), its=int(m.group(2)), cuts=int(m.group(3)), wall=float(m.group(4)), cells=int(mesh.group(2)), t=t, f=f) if m else None


if not a.skip_runs:
    os.makedirs(os.path.join(ROOT, "out"), exist_ok=True)
    for c in CASES:
        run(c)
res = {c: summary(c) for c in CASES if os.path.exists(os.path.join(ROOT, "out", c + ".log"))}
ref = np.array(sorted((float(r["travel_mm"]), float(r["force_full_kN"])) for r in csv.DictReader(open(os.path.join(ROOT, "doc", "reference", "hemisphere_force_reference.csv"))) if float(r["friction"]) == 0))
R = lambda T: float(np.interp(T, ref[:, 0], ref[:, 1])) if ref[0, 0] <= T <= ref[-1, 0] else None
F = lambda c, T: float(np.interp(T, res[c]["t"], res[c]["f"])) if res.get(c) and T <= res[c]["t"][-1] + 1e-9 else None

figs = os.path.join(ROOT, "doc", "figures")
os.makedirs(figs, exist_ok=True)
subprocess.run([PY, os.path.join(HERE, "plot_history.py"), "out/hemisphere_frictionless=frictionless, Coons tools", "out/hemisphere_friction=mu 0.15, Coons tools",
                "out/hemisphere_frictionless_analytic=frictionless, analytic tools", "out/hemisphere_friction_analytic=mu 0.15, analytic tools",
                "--out", os.path.join(figs, "force_travel.png")], cwd=ROOT, check=True, capture_output=True)
rad = subprocess.run([PY, os.path.join(HERE, "plot_radial.py"), "out/hemisphere_frictionless=frictionless", "out/hemisphere_friction=mu 0.15",
                      "--travels", "20,30,40", "--out", os.path.join(figs, "radial.png")], cwd=ROOT, check=True, capture_output=True, text=True).stdout
for c, name in (("hemisphere_friction", "sheet_friction.png"), ("hemisphere_frictionless", "sheet_frictionless.png")):
    subprocess.run([PY, os.path.join(HERE, "plot_sheet.py"), "out/" + c, os.path.join(figs, name), "--title", c.replace("hemisphere_", "") + ", 40 mm"], cwd=ROOT, check=True, capture_output=True)


def dev(v, r):
    return f"{v:.1f} ({100 * (v - r) / r:+.1f} %)" if v is not None and r is not None else (f"{v:.1f}" if v is not None else "–")


L = ["# The hemispherical punch benchmark", "",
     "Lee, Wagoner & Nakamachi's hemispherical punch stretching, the application of the method's paper:",
     "a circular aluminium sheet (radius 59.18 mm, 1 mm thick, rim clamped) stretched 40 mm by a",
     "hemispherical punch (radius 50.8 mm) through a die with a 6.35 mm fillet. E = 69004 MPa,",
     "ν = 0.3, σ̄ = 589 (1e-4 + ε̄p)^0.216 MPa. Quarter model (symmetry planes x = 0 and y = 0).",
     "Contact: K_N = 1e5 N/mm, and for the friction case K_T = 5e3 N/mm, μ = 0.15 (the paper's values,",
     "per node). The refined meshes keep that stiffness per unit area: K_N = 12168 and K_T = 608.4 N/mm³",
     "times each node's tributary area (`-contact_penalty_per_area`; the seed mesh's mean is 8.218 mm²).",
     "The reference is the published curve as encoded in code_aster's SSNV501 (`doc/reference/`).",
     "", "Everything below is produced by `scripts/benchmark.py` (the cases are written by",
     "`scripts/make_hemisphere_cases.py`); `make run` runs the two main cases and prints the force table.", "",
     "## Cases", "",
     "| case | mesh | tools |", "|---|---|---|",
     "| `hemisphere_frictionless`, `hemisphere_friction` (the main cases) | seed: O-grid, 301 hexahedra, 1 layer | Coons (1) |",
     "| `*_coons3` | seed | the paper's own Coons patches (2) |",
     "| `*_analytic` | seed | a sphere and a torus |",
     "| `*_analytic_steps` | seed | a sphere and a torus, the main cases' steps (3) |",
     "| `*_analytic_refined` | 3612 hexahedra, 3 layers | sphere, torus |"]
if a.fine:
    L.append("| `*_analytic_fine` | 9600 hexahedra, 4 layers | sphere, torus |")
if a.xfine:
    L.append("| `hemisphere_friction_xfine` | 20400 hexahedra, 4 layers | Coons, as the main cases |")
L += ["", "(1) The paper's punch construction (3 patches of great-circle arcs per quarter and the plane of",
      "its shoulder), each patch split 3 × 3, and a die fillet of 4 Coons patches: within 0.02 mm of the",
      "sphere and the torus. The paper's seed mesh has 294 hexahedra. (2) The paper's own 3 + 1 punch",
      "patches and 1 die patch, whose interiors lie up to 0.52 mm inside the sphere and 0.32 mm off the",
      "torus. (3) The main cases' `-load_` and `-newton_` options, growing after every step: the main",
      "cases' sequence of increments."]
L += ["", "## Punch force against travel (full sheet, kN)", "", "![force](figures/force_travel.png)", ""]
cols = [c for c in ["hemisphere_frictionless", "hemisphere_frictionless_analytic", "hemisphere_frictionless_coons3", "hemisphere_frictionless_analytic_refined", "hemisphere_frictionless_analytic_fine", "hemisphere_friction", "hemisphere_friction_analytic", "hemisphere_friction_analytic_refined", "hemisphere_friction_xfine"] if res.get(c)]
L.append("| travel (mm) | reference | " + " | ".join(c.replace("hemisphere_", "") for c in cols) + " |")
L.append("|---|---|" + "---|" * len(cols))
for T in TRAVELS:
    L.append(f"| {T} | {R(T):.1f} | " if R(T) else f"| {T} | – | ")
    L[-1] += " | ".join(dev(F(c, T), R(T) if "friction_" not in c and not c.endswith("friction") else None) for c in cols) + " |"
L += ["", "Deviations in parentheses are from the frictionless reference curve (linear between its",
      "points; the published points are read off graphs to about ±5 %).", ""]


def worst(c, lo=15, hi=40):
    if not res.get(c):
        return None
    return max(abs(F(c, T) - R(T)) / R(T) for T in np.arange(lo, hi + 0.01, 0.5) if F(c, T) is not None)


def worst_pair(c1, c2):
    """largest relative difference of the two punch forces from 5 to 40 mm: at the travels of the
    steps where the two runs took the same steps, else between them (interpolated every 0.5 mm)"""
    if not (res.get(c1) and res.get(c2)):
        return None
    t1, t2 = res[c1]["t"], res[c2]["t"]
    if len(t1) == len(t2) and np.allclose(t1, t2, rtol=0, atol=1e-9):
        return max(abs(F(c1, T) - F(c2, T)) / F(c2, T) for T in t1 if T >= 5 - 1e-9)
    return max(abs(F(c1, T) - F(c2, T)) / F(c2, T) for T in np.arange(5, 40.01, 0.5))


peaks = {}
for line in rad.splitlines():
    m = re.match(r"(.*): travel ([0-9.]+) mm: peak plastic strain ([0-9.]+) at radius ([0-9.]+) mm", line)
    if m:
        peaks[(m.group(1), round(float(m.group(2))))] = (float(m.group(3)), float(m.group(4)))
L += ["## Accuracy", "", "| requirement | obtained |", "|---|---|"]
w = worst("hemisphere_frictionless_analytic_refined")
L.append(f"| frictionless, refined mesh: within 5 % of the reference from 15 to 40 mm | largest deviation {100 * w:.1f} % |" if w is not None else "| frictionless, refined mesh | not run |")
for c in ("hemisphere_frictionless", "hemisphere_frictionless_analytic"):
    w = worst(c)
    if w is not None:
        L.append(f"| frictionless, seed mesh (`{c}`): within 10 % from 15 to 40 mm | largest deviation {100 * w:.1f} % |")
for (c1, c2) in (("hemisphere_frictionless", "hemisphere_frictionless_analytic_steps"), ("hemisphere_friction", "hemisphere_friction_analytic_steps"), ("hemisphere_frictionless_coons3", "hemisphere_frictionless_analytic")):
    w = worst_pair(c1, c2)
    if w is not None:
        same = len(res[c1]["t"]) == len(res[c2]["t"]) and np.allclose(res[c1]["t"], res[c2]["t"], rtol=0, atol=1e-9)
        L.append(f"| Coons and analytic tools within 1 % (`{c1}` vs `{c2}`, 5 to 40 mm{', at the same steps' if same else ''}) | largest difference {100 * w:.2f} % |")
pf, pm = peaks.get(("frictionless", 40)), peaks.get(("mu 0.15", 40))
if pf and pm:
    L.append(f"| frictionless: peak of ε̄p at the pole (radius < 5 mm at 40 mm) | peak {pf[0]:.3f} at r = {pf[1]:.1f} mm |")
    L.append(f"| friction: peak of ε̄p away from the pole (radius > 10 mm at 40 mm) | peak {pm[0]:.3f} at r = {pm[1]:.1f} mm |")
if res.get("hemisphere_friction") and res.get("hemisphere_frictionless"):
    L.append(f"| friction raises the force | at 40 mm: {F('hemisphere_friction', 40):.1f} kN against {F('hemisphere_frictionless', 40):.1f} kN |")
L += ["", "The refined meshes converge (mesh convergence table below): the remaining difference from the",
      "reference is not discretisation. From 20 to 40 mm the computed force lies within 4 % of the",
      "reference; around 15 mm it lies 6 to 7 % below it, where the published points (10 kN at 10.6 mm,",
      "20 kN at 15.4 mm, 30 kN at 20 mm, read off graphs to about ±5 %) rise more steeply than the",
      "computation, which matches the point at 10.6 mm to 1 %. The requirement of 5 % on the refined",
      "mesh is therefore met from 17.5 mm on and missed between 15 and 17.5 mm. The Coons tools agree",
      "with the analytic ones to 0.3 % once each of the paper's punch patches is split 3 × 3; the",
      "paper's own 3 + 1 patches, whose interiors lie up to 0.52 mm inside the sphere, give forces up to",
      "4 % lower. With friction the force is higher from about 15 mm on, and the peak of ε̄p moves from",
      "the pole to a ring about 27 mm from the axis, as in the paper's Figs. 5 and 6.", ""]
L += ["", "## Equivalent plastic strain and thickness strain", "",
      "Cell values against the current radius (cells averaged on radial bins), frictionless and with",
      "friction, at 20, 30 and 40 mm: without friction the strain peaks at the pole (where necking",
      "would start); with μ = 0.15 the peak moves outwards, as in the paper's Figs. 5 and 6.", "",
      "![radial](figures/radial.png)", "", "![sheet, friction](figures/sheet_friction.png) ![sheet, frictionless](figures/sheet_frictionless.png)", "",
      "```", rad.strip(), "```", "",
      "## Steps, Newton iterations and wall time", "",
      "The paper reports 101 steps and 226 Newton iterations without friction, 108 steps and 248",
      "iterations with friction (seed-size mesh).", "",
      "| case | hexahedra | ranks | steps | Newton iterations | cut steps | wall time (s) |", "|---|---|---|---|---|---|---|"]
for c in CASES:
    s = res.get(c)
    if s:
        L.append(f"| {c} | {s['cells']} | {NP[c]} | {s['steps']} | {s['its']} | {s['cuts']} | {s['wall']:.1f} |")
loads = []
for c in CASES:
    lf = os.path.join(ROOT, "out", c + ".load")
    if res.get(c) and os.path.exists(lf):
        loads.append(float(open(lf).read()))
load = f"; the 1-minute load average when each run started: median {float(np.median(loads)):.2f}, largest {max(loads):.2f}" if loads else ""
L += ["", f"Wall times on the development machine (2 cores, one rank per case unless stated{load}). Load",
      "increments: in the main cases (and `*_analytic_steps`, and the Coons cases of the refined",
      "meshes) 15 steps of 2.67 mm on the code's default stepping, with friction the committed contact",
      "held on every tool in a step's first iteration ([performance.md](performance.md#newton-iterations));",
      "in the others first 1 mm (`-load_steps 40`), grown after easy steps up to 2 mm",
      "(`-load_dt_max 0.05`); cut back on failure in all.", ""]
if a.fine or res.get("hemisphere_frictionless_analytic_refined"):
    mc = [c for c in ("hemisphere_frictionless_analytic", "hemisphere_frictionless_analytic_refined", "hemisphere_frictionless_analytic_fine") if res.get(c)]
    L += ["## Mesh convergence (frictionless, analytic tools, full-sheet force in kN)", "",
          "| travel (mm) | reference | " + " | ".join(f"{res[c]['cells']} hexahedra" for c in mc) + " |", "|---|---|" + "---|" * len(mc)]
    for T in TRAVELS:
        L.append(f"| {T} | " + (f"{R(T):.1f}" if R(T) else "–") + " | " + " | ".join(dev(F(c, T), R(T)) for c in mc) + " |")
    L.append("")
open(os.path.join(ROOT, "doc", "benchmark.md"), "w").write("\n".join(L) + "\n")
print("wrote doc/benchmark.md and doc/figures/", file=sys.stderr)
