#!/usr/bin/python3
"""The hemispherical punch benchmark with its tools given every way the code reads them: the
punch force against the analytic tools, per tool source and facet size, smoothed and raw facets
(doc/tools.md, section "Hemispherical punch with meshed tools", and doc/figures/tool_facet_error.png).

  /usr/bin/python3 scripts/tool_mesh_study.py [--levels 12,24,48,96] [--jobs 2] [--timeout 300]
                                              [--skip-runs] [--output doc/tools.md]

Runs (frictionless, seed mesh, 40 steps of 1 mm with -load_dt_max 0.05, each into out/tool_study/):
  analytic      cases/hemisphere_frictionless_analytic.opts (sphere and torus patches as options)
  tool file     cases/hemisphere_frictionless_toolfile.opts (the same patches from .tool files)
  Coons file    cases/hemisphere_frictionless.opts (the benchmark's Coons patches from .tool files)
  STL <n>       cases/hemisphere_frictionless_stl<n>.opts (triangles), smoothed (Nagata) and raw
                (-tool_punch_smooth 0 -tool_die_smooth 0)
  Gmsh <n>      cases/hemisphere_frictionless_msh<n>.opts (quadrangles), smoothed
  .inp <n>      cases/hemisphere_frictionless_inp<n>.opts (one Abaqus deck: the punch's *SURFACE on
                C3D8 faces, the die's on R3D4 elements of a *RIGID BODY), smoothed; also on 2 ranks
n: the punch's rings (scripts/make_tool_meshes.py writes the files); the facet size is the
punch's meridian edge, (pi/2) 50.8 / n mm. The punch force (contact.csv force_full, the whole
punch) is interpolated linearly in the travel at 20, 30 and 40 mm; a run that stops early is
listed with the travel it reached. Writes the block between the markers
"<!-- tool_mesh_study -->" and "<!-- /tool_mesh_study -->" of the output file and the figure.
Needs numpy and matplotlib (Debian packages python3-numpy, python3-matplotlib).
"""
import argparse
import concurrent.futures
import csv
import datetime
import math
import os
import re
import subprocess
import sys

import numpy as np

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
OUT = os.path.join(ROOT, "out", "tool_study")
TRAVELS = (20.0, 30.0, 40.0)
BEGIN, END = "<!-- tool_mesh_study -->", "<!-- /tool_mesh_study -->"
RAW = ["-tool_punch_smooth", "0", "-tool_die_smooth", "0"]
DONE = re.compile(r"^done: (\d+) steps, (\d+) Newton iterations, (\d+) cuts, ([\d.]+) s", re.M)


def plan(levels):
    runs = [("analytic", "analytic", None, "hemisphere_frictionless_analytic", [], 1),
            ("toolfile", "tool file (sphere, torus)", None, "hemisphere_frictionless_toolfile", [], 1),
            ("coons", "Coons file (28 + 4 patches)", None, "hemisphere_frictionless", [], 1)]
    for n in levels:
        runs.append((f"stl{n}", f"STL {n} rings", n, f"hemisphere_frictionless_stl{n}", [], 1))
        runs.append((f"msh{n}", f"Gmsh quadrangles {n}", n, f"hemisphere_frictionless_msh{n}", [], 1))
        if os.path.exists(os.path.join(ROOT, "cases", f"hemisphere_frictionless_inp{n}.opts")):
            runs.append((f"inp{n}", f".inp {n} (C3D8 faces, R3D4)", n, f"hemisphere_frictionless_inp{n}", [], 1))
            runs.append((f"inp{n}_np2", f".inp {n}, 2 ranks", n, f"hemisphere_frictionless_inp{n}", [], 2))
        runs.append((f"raw{n}", f"STL {n} rings, raw facets", n, f"hemisphere_frictionless_stl{n}", RAW, 1))
    return runs


def run(r, timeout):
    key, _, _, case, extra, np_ = r
    d = os.path.join(OUT, key)
    cmd = ([] if np_ == 1 else ["mpiexec", "--oversubscribe", "-n", str(np_)]) + [os.path.join(ROOT, "bin", "atrito"), "-options_file", os.path.join("cases", case + ".opts"),
                                                                                  "-output_dir", d, "-output_interval", "0"] + extra
    env = dict(os.environ, OMPI_ALLOW_RUN_AS_ROOT="1", OMPI_ALLOW_RUN_AS_ROOT_CONFIRM="1", OPENBLAS_NUM_THREADS="1")
    with open(d + ".log", "w") as f:
        try:
            rc = subprocess.run(cmd, cwd=ROOT, env=env, stdout=f, stderr=subprocess.STDOUT, timeout=timeout).returncode
        except subprocess.TimeoutExpired:
            rc = "timeout"
    print(f"[tool_mesh_study] {key}: {rc}", file=sys.stderr, flush=True)


def result(r):
    key = r[0]
    log = open(os.path.join(OUT, key + ".log")).read() if os.path.exists(os.path.join(OUT, key + ".log")) else ""
    m = DONE.search(log)
    t, f = [0.0], [0.0]
    path = os.path.join(OUT, key, "contact.csv")
    if os.path.exists(path):
        for row in csv.DictReader(open(path)):
            if row["tool"] == "punch":
                t.append(float(row["travel"]))
                f.append(float(row["force_full"]) / 1e3)
    t, f = np.array(t), np.array(f)
    err = re.search(r"atrito: error: (.*)", log)
    return dict(done=bool(m), steps=int(m.group(1)) if m else None, its=int(m.group(2)) if m else None, cuts=int(m.group(3)) if m else None,
                wall=float(m.group(4)) if m else None, t=t, f=f, reached=t.max(), error=err.group(1) if err else ("timeout" if not m else ""),
                force={x: float(np.interp(x, t, f)) for x in TRAVELS if t.max() >= x - 1e-9})


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--levels", default="12,24,48,96")
    ap.add_argument("--jobs", type=int, default=2)
    ap.add_argument("--timeout", type=float, default=300)
    ap.add_argument("--skip-runs", action="store_true")
    ap.add_argument("--output", default=os.path.join(ROOT, "doc", "tools.md"))
    a = ap.parse_args()
    levels = [int(x) for x in a.levels.split(",")]
    runs = plan(levels)
    os.makedirs(OUT, exist_ok=True)
    if not a.skip_runs:
        if not os.path.exists(os.path.join(ROOT, "bin", "atrito")):
            sys.exit("tool_mesh_study: bin/atrito missing (make)")
        # the 2-rank runs alone (they would share the 2 cores with another run), the others in parallel
        with concurrent.futures.ThreadPoolExecutor(a.jobs) as ex:
            list(ex.map(lambda r: run(r, a.timeout), [r for r in runs if r[5] == 1]))
        for r in runs:
            if r[5] > 1:
                run(r, a.timeout)
    res = {r[0]: result(r) for r in runs}
    ref = res["analytic"]
    if not ref["done"]:
        sys.exit("tool_mesh_study: the analytic run did not finish: " + ref["error"])
    lines = [BEGIN, "",
             f"Measured by `scripts/tool_mesh_study.py` on {datetime.datetime.utcnow():%Y-%m-%d %H:%M} UTC (commit {subprocess.run(['git', 'rev-parse', '--short', 'HEAD'], cwd=ROOT, capture_output=True, text=True).stdout.strip() or '?'}); "
             f"one rank unless said, two runs at a time on the 2-core machine (wall times indicative). Punch force (kN) at the travel, "
             f"its deviation from the analytic tools in brackets; h: the punch facets' meridian edge.", "",
             "| tools | h (mm) | 20 mm | 30 mm | 40 mm | steps | Newton its | cuts | wall (s) |", "|---|---|---|---|---|---|---|---|---|"]
    for r in runs:
        key, label, n, *_ = r
        x = res[key]
        h = f"{math.pi / 2 * 50.8 / n:.2f}" if n else "–"
        cells = []
        for tr in TRAVELS:
            if tr in x["force"]:
                v = x["force"][tr]
                cells.append(f"{v:.4f}" if key == "analytic" else f"{v:.4f} ({100 * (v / ref['force'][tr] - 1):+.3f} %)")
            else:
                cells.append("–")
        tail = (f"{x['steps']} | {x['its']} | {x['cuts']} | {x['wall']:.1f}" if x["done"] else
                f"stopped at {x['reached']:.2f} mm: {x['error'][:90]} | | |")
        lines.append(f"| {label} | {h} | " + " | ".join(cells) + f" | {tail} |")
    lines.append("")
    # the same tools read in different ways, and the ranks
    notes = []
    for a_, b_ in (("analytic", "toolfile"),) + tuple((f"msh{n}", f"inp{n}") for n in levels) + tuple((f"inp{n}", f"inp{n}_np2") for n in levels):
        if a_ in res and b_ in res and res[a_]["done"] and res[b_]["done"] and len(res[a_]["f"]) == len(res[b_]["f"]):
            fa, fb = res[a_]["f"], res[b_]["f"]
            d = float(np.max(np.abs(fa - fb)) / np.max(np.abs(fa)))
            notes.append(f"{dict((r[0], r[1]) for r in runs)[b_]} against {dict((r[0], r[1]) for r in runs)[a_]}: punch forces of every step within {d:.1e} of the largest")
    if notes:
        lines += ["Same tools, other readers or ranks: " + "; ".join(notes) + ".", ""]
    lines += ["![punch force error against facet size](figures/tool_facet_error.png)", "", END]
    block = "\n".join(lines)
    print(block)
    if a.output:
        s = open(a.output).read()
        if BEGIN in s and END in s:
            s = s[:s.index(BEGIN)] + block + s[s.index(END) + len(END):]
        else:
            sys.exit(f"tool_mesh_study: {a.output} has no {BEGIN} ... {END} block")
        open(a.output, "w").write(s)
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, axs = plt.subplots(1, 3, figsize=(12, 3.8), sharey=True)
    for ax, tr in zip(axs, TRAVELS):
        for pre, lab, mk in (("stl", "STL, smoothed", "o-"), ("msh", "Gmsh quadrangles, smoothed", "s--"), ("inp", ".inp, smoothed", "^:"), ("raw", "STL, raw facets", "x-")):
            hs, es = [], []
            for n in levels:
                x = res.get(f"{pre}{n}")
                if x:  # a run that stopped before the travel leaves a gap in its line
                    hs.append(math.pi / 2 * 50.8 / n)
                    es.append(max(abs(100 * (x["force"][tr] / ref["force"][tr] - 1)), 1e-4) if tr in x["force"] else float("nan"))
            if hs:
                ax.loglog(hs, es, mk, label=lab)
                ax.set_xticks([math.pi / 2 * 50.8 / n for n in levels])
                ax.set_xticklabels([f"{math.pi / 2 * 50.8 / n:.2g}" for n in levels])
                ax.minorticks_off()
        ax.set_title(f"punch travel {tr:.0f} mm")
        ax.set_xlabel("punch facet edge h (mm)")
        ax.grid(True, which="both", alpha=0.3)
    axs[0].set_ylabel("|punch force error| against analytic tools (%)")
    axs[0].legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(os.path.join(ROOT, "doc", "figures", "tool_facet_error.png"), dpi=110)


if __name__ == "__main__":
    main()
