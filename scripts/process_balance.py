#!/usr/bin/env python3
"""Balance of the contact work of a forming process over the ranks of a large mesh.

The mild steel square cup (cases/numisheet93_cup_coarse.opts: close, then the draw to 40 mm) is run
on its coarse mesh with the fields of every step (or an earlier run is read, --run DIR); the
vertices in contact with each tool at each step (die: bottom face; punch and holder: top face,
inside and outside x, y < 41 mm, between the die's opening and its flat face) are carried by their
reference position onto the top and bottom faces of a large box mesh of the same quarter blank
(N x N x L hexahedra), which scripts/partition_process.c partitions with METIS as the code does
(the cells balanced, or -partition_balance contact: the cells and the top and bottom faces'
vertices) into 16 to 1024 parts, counting per part the vertices in contact. The contact work of
a Newton iteration (projection, frame, return map, tangent per vertex in contact) is that of the
largest part; the table gives its ratio to the mean. Writes the section
"## A forming process: the contact work per rank (measured)" of doc/scaling-model.md.

usage: scripts/process_balance.py [--run DIR] [--n 250] [--layers 4] [--parts 16,64,256,1024]"""
import argparse
import os
import subprocess
import sys

import h5py
import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(HERE)
sys.path.insert(0, HERE)
import benchutil  # noqa: E402

HEADING = "## A forming process: the contact work per rank (measured)"
CASE = "cases/numisheet93_cup_coarse.opts"
L, T = 75.0, 0.78          # the quarter blank's side and thickness
SPLIT = 41.0               # top vertices beyond it (x or y) touch the holder, inside it the punch
TOOLS = ("punch", "die", "holder")


def run_case(work):
    out = os.path.join(work, "run")
    exe = benchutil.build_and_snapshot(ROOT, work, "process_balance")
    subprocess.run([exe, "-options_file", CASE, "-output_interval", "1", "-output_dir", out], cwd=ROOT, env=benchutil.run_env(),
                   check=True, stdout=subprocess.DEVNULL)
    return out


def contact_flags(run):
    """per output step: time, and per coarse vertex the tool bits (1 punch, 2 die, 4 holder)"""
    with h5py.File(os.path.join(run, "fields.h5"), "r") as f:
        X = f["mesh"]["coordinates"][:]
        steps = sorted(f["steps"].keys(), key=int)
        times, flags = [], []
        for k in steps:
            s = f["steps"][k]
            st = s["contact_status"][:]
            x = X + s["displacement"][:]
            bits = np.zeros(len(X), np.uint8)
            on = st > 0
            bottom, top = X[:, 2] < 0.5 * T, X[:, 2] > 0.5 * T
            out = (x[:, 0] > SPLIT) | (x[:, 1] > SPLIT)
            bits[on & bottom] |= 2
            bits[on & top & ~out] |= 1
            bits[on & top & out] |= 4
            times.append(float(s.attrs["time"]))
            flags.append(bits)
    return X, np.array(times), np.array(flags)


def carry(X, flags, n, layers):
    """the coarse run's flags onto the box mesh's top and bottom vertices, by the nearest coarse
    vertex of the same face in the reference plane (the coarse mesh is a regular grid)"""
    xs = np.unique(np.round(X[:, 0], 9))
    nc = len(xs) - 1
    ic = np.rint(X[:, 0] / (L / nc)).astype(int)
    jc = np.rint(X[:, 1] / (L / nc)).astype(int)
    face = (X[:, 2] > 0.5 * T).astype(int)
    index = -np.ones((2, nc + 1, nc + 1), int)
    index[face, jc, ic] = np.arange(len(X))
    if (index < 0).any():
        sys.exit("process_balance: the run's mesh is not a regular grid of the quarter blank")
    g = np.arange(n + 1) * (L / n)
    jj, ii = np.meshgrid(np.rint(g / (L / nc)).astype(int), np.rint(g / (L / nc)).astype(int), indexing="ij")
    nv = (n + 1) ** 2 * (layers + 1)
    out = np.zeros((len(flags), nv), np.uint8)
    for k, f in ((0, 0), (layers, 1)):
        v = (np.arange((n + 1) ** 2) + (n + 1) ** 2 * k)
        out[:, v] = flags[:, index[f, jj, ii].ravel()]
    return out


def build(work):
    exe = os.path.join(work, "partition_process")
    pc = subprocess.run(["pkg-config", "--cflags", "--libs", "PETSc"], capture_output=True, text=True).stdout.split()
    subprocess.run(["mpicc", "-O2", "-Iinclude", os.path.join(HERE, "partition_process.c"), "build/lib.a", "-o", exe] + pc +
                   ["-L/usr/lib/x86_64-linux-gnu/hdf5/openmpi", "-lhdf5", "-ldmumps", "-lmumps_common", "-lmetis", "-lHYPRE", "-llapack", "-lm"],
                   cwd=ROOT, check=True)
    return exe


def partition(exe, n, layers, mode, flagfile, ntimes, parts):
    out = subprocess.run([exe, str(n), str(n), str(layers), str(L), str(L), str(T), mode, flagfile, str(ntimes), str(len(TOOLS))] +
                         [str(p) for p in parts], capture_output=True, text=True, check=True, cwd=ROOT).stdout
    parts_rows, counts = {}, {}
    for line in out.splitlines():
        t = line.split()
        if t[0] == "parts":
            parts_rows[int(t[1])] = {t[i]: float(t[i + 1]) for i in range(2, len(t), 2)}
        elif t[0] == "time":
            counts[(int(t[1]), int(t[2]), int(t[4]))] = (int(t[6]), float(t[8]))
    return parts_rows, counts


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--run", help="a run of the case with the fields of every step (default: run it)")
    ap.add_argument("--n", type=int, default=250)
    ap.add_argument("--layers", type=int, default=4)
    ap.add_argument("--parts", default="16,64,256,1024")
    ap.add_argument("--work", default=os.path.join(ROOT, "build", "process_balance"))
    ap.add_argument("--output", default=os.path.join(ROOT, "doc", "scaling-model.md"))
    a = ap.parse_args()
    os.makedirs(a.work, exist_ok=True)
    run = a.run or run_case(a.work)
    X, times, flags = contact_flags(run)
    big = carry(X, flags, a.n, a.layers)
    flagfile = os.path.join(a.work, "flags.bin")
    big.tofile(flagfile)
    exe = build(a.work)
    parts = [int(p) for p in a.parts.split(",")]
    res = {m: partition(exe, a.n, a.layers, m, flagfile, len(times), parts) for m in ("cells", "contact")}
    # the times shown: the end of the close (t = 1) and the punch at 15 and 40 mm (t = 1 + s / 40)
    show = [(lbl, int(np.argmin(np.abs(times - t)))) for lbl, t in (("closed", 1.0), ("15 mm", 1.375), ("40 mm", 2.0))]
    cells = a.n * a.n * a.layers
    lines = [HEADING, "", benchutil.measured_by("process_balance.py", ROOT), "",
             f"The vertices in contact of the mild steel square cup's coarse run (`{CASE}`, every step) carried onto a quarter",
             f"blank of {a.n} x {a.n} x {a.layers} = {cells:,} hexahedra, partitioned as the code does (`scripts/partition_process.c`).",
             "Per part count, the largest over the mean: cells; vertices in contact with any tool at the end of the close",
             "and with the punch at 15 and 40 mm; the largest of that over the whole process; per tool at 40 mm.", "",
             "| parts | balance | cells | contact, closed | contact, 15 mm | contact, 40 mm | contact, worst step | punch, 40 mm | die, 40 mm | holder, 40 mm |",
             "|---|---|---|---|---|---|---|---|---|---|"]
    for p in parts:
        for m in ("cells", "contact"):
            pr, cnt = res[m]

            def ratio(t, k):
                mx, mean = cnt[(p, t, k)]
                return mx / mean if mean > 0 else 0.0

            worst = max(ratio(t, len(TOOLS)) for t in range(len(times)))
            row = [str(p), m, f"{pr[p]['cells_max'] / pr[p]['cells_mean']:.2f}"] + [f"{ratio(t, len(TOOLS)):.1f}" for _, t in show] + [f"{worst:.1f}"] + \
                  [f"{ratio(show[-1][1], k):.1f}" for k in range(len(TOOLS))]
            lines.append("| " + " | ".join(row) + " |")
    pm = parts[-1]
    worst = {m: max(res[m][1][(pm, t, len(TOOLS))][0] / res[m][1][(pm, t, len(TOOLS))][1] for t in range(len(times)) if res[m][1][(pm, t, len(TOOLS))][1] > 0)
             for m in ("cells", "contact")}
    lines += ["", f"At {pm} parts the largest part holds up to {worst['cells']:.1f} times the mean of the vertices in contact with the cells "
              f"balanced, {worst['contact']:.1f} with `-partition_balance contact`: that option balances the top and bottom faces, which a plate's "
              "cells balance already; the vertices in contact are a moving part of them (the punch's profile, the die's shoulder, the flange under "
              "the holder), which no static partition balances."]
    benchutil.write_doc_section(a.output, HEADING, "\n".join(lines) + "\n")
    print("\n".join(lines))


if __name__ == "__main__":
    main()
