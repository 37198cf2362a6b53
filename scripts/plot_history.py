#!/usr/bin/env python3
"""Punch force (full sheet) against punch travel for any set of runs, with the reference points
of the hemispherical punch benchmark; a PNG and a table.

usage: plot_history.py RUNDIR[=LABEL] ... [--tool punch] [--out force.png]
                       [--reference doc/reference/hemisphere_force_reference.csv]
                       [--table-travels 10,15,20,25,30,35,40] [--markdown]
Each RUNDIR holds the contact.csv of a run. The table gives, at each chosen travel, each run's
force (linear interpolation between converged steps) and its deviation from the frictionless
reference curve (interpolated between the published points)."""
import argparse
import csv
import os
import sys

import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))


def read_run(d, tool):
    rows = [r for r in csv.DictReader(open(os.path.join(d, "contact.csv"))) if r["tool"] == tool]
    t = np.array([float(r["travel"]) for r in rows])
    f = np.array([float(r["force_full"]) for r in rows]) / 1000.0  # kN
    return np.concatenate([[0.0], t]), np.concatenate([[0.0], f])


def read_reference(path):
    rows = list(csv.DictReader(open(path)))
    ref = {}
    for r in rows:
        ref.setdefault(float(r["friction"]), []).append((float(r["travel_mm"]), float(r["force_full_kN"])))
    return {k: np.array(sorted(v)) for k, v in ref.items()}


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("runs", nargs="+")
    ap.add_argument("--tool", default="punch")
    ap.add_argument("--out", default="force_travel.png")
    ap.add_argument("--reference", default=os.path.join(HERE, "..", "doc", "reference", "hemisphere_force_reference.csv"))
    ap.add_argument("--table-travels", default="10,15,20,25,30,35,40")
    ap.add_argument("--markdown", action="store_true")
    a = ap.parse_args()
    runs = []
    for spec in a.runs:
        d, _, label = spec.partition("=")
        if not os.path.exists(os.path.join(d, "contact.csv")):
            print(f"plot_history: {d}/contact.csv not found", file=sys.stderr)
            return 1
        runs.append((label or os.path.basename(os.path.normpath(d)), *read_run(d, a.tool)))
    ref = read_reference(a.reference) if os.path.exists(a.reference) else {}

    travels = [float(x) for x in a.table_travels.split(",")]
    ref0 = ref.get(0.0)
    head = ["travel (mm)", "reference (kN)"] + [r[0] + " (kN)" for r in runs]
    lines = []
    for T in travels:
        rv = np.interp(T, ref0[:, 0], ref0[:, 1]) if ref0 is not None and ref0[0, 0] <= T <= ref0[-1, 0] else None
        row = [f"{T:g}", f"{rv:.1f}" if rv is not None else "-"]
        for name, t, f in runs:
            if T > t[-1] + 1e-9:
                row.append("-")
                continue
            v = np.interp(T, t, f)
            row.append(f"{v:.1f}" + (f" ({100 * (v - rv) / rv:+.1f} %)" if rv is not None else ""))
        lines.append(row)
    if a.markdown:
        print("| " + " | ".join(head) + " |")
        print("|" + "---|" * len(head))
        for row in lines:
            print("| " + " | ".join(row) + " |")
    else:
        w = [max(len(x) for x in col) for col in zip(head, *lines)]
        for row in [head] + lines:
            print("  ".join(x.rjust(n) for x, n in zip(row, w)))

    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, ax = plt.subplots(figsize=(7, 5))
    for k, (name, t, f) in enumerate(runs):
        ax.plot(t, f, ["-", "--", "-.", ":"][k % 4], label=name)
    for mu, pts in sorted(ref.items()):
        ax.plot(pts[:, 0], pts[:, 1], "o" if mu == 0 else "s", mfc="none", color="k" if mu == 0 else "tab:red",
                label=f"reference (Lee et al.), mu = {mu:g}")
    ax.set_xlabel("punch travel (mm)")
    ax.set_ylabel("punch force, full sheet (kN)")
    ax.grid(True, alpha=0.3)
    ax.legend(fontsize=8)
    ax.set_xlim(left=0)
    ax.set_ylim(bottom=0)
    fig.tight_layout()
    fig.savefig(a.out, dpi=120)
    print(f"wrote {a.out}", file=sys.stderr)
    return 0


sys.exit(main())
