#!/usr/bin/env python3
"""Equivalent plastic strain and thickness strain against the radius on the sheet, at chosen
punch travels, from the HDF5 fields of one or more runs (e.g. frictionless and friction together).

usage: plot_radial.py RUNDIR[=LABEL] ... [--travels 20,30,40] [--tool punch] [--out radial.png]
                      [--layer bottom|mid|top|all]
For every cell: its centroid's current radial position sqrt(x^2 + y^2); the cell values of
plastic_strain and thickness_strain. A run's travel at an output step is read from contact.csv
(the tool's travel at that step); the output step nearest to each requested travel is used.
Prints, per run and travel, the radius of the peak plastic strain (cells through the thickness
averaged on each radial bin)."""
import argparse
import csv
import os
import sys

import h5py
import numpy as np


def load(d, tool):
    f = h5py.File(os.path.join(d, "fields.h5"), "r")
    X = f["mesh/coordinates"][:]
    H = f["mesh/hexahedra"][:]
    trav = {int(r["step"]): float(r["travel"]) for r in csv.DictReader(open(os.path.join(d, "contact.csv"))) if r["tool"] == tool}
    trav[0] = 0.0
    steps = []
    for k in f["steps"]:
        g = f["steps"][k]
        s = int(g.attrs["step"])
        if s in trav:
            steps.append((trav[s], g))
    return f, X, H, sorted(steps, key=lambda p: p[0])


def profile(X, H, g, nbins=60):
    x = X + g["displacement"][:]
    c = x[H].mean(axis=1)
    r = np.hypot(c[:, 0], c[:, 1])
    ep = g["plastic_strain"][:]
    th = g["thickness_strain"][:] if "thickness_strain" in g else np.full_like(ep, np.nan)
    edges = np.linspace(0, r.max() + 1e-9, nbins + 1)
    idx = np.clip(np.digitize(r, edges) - 1, 0, nbins - 1)
    rb, epb, thb = [], [], []
    for b in range(nbins):
        m = idx == b
        if m.any():
            rb.append(r[m].mean())
            epb.append(ep[m].mean())
            thb.append(th[m].mean())
    return r, ep, th, np.array(rb), np.array(epb), np.array(thb)


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("runs", nargs="+")
    ap.add_argument("--travels", default="20,30,40")
    ap.add_argument("--tool", default="punch")
    ap.add_argument("--out", default="radial.png")
    a = ap.parse_args()
    travels = [float(t) for t in a.travels.split(",")]
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, axs = plt.subplots(2, 1, figsize=(7, 8), sharex=True)
    styles = ["-", "--", ":", "-."]
    for ir, spec in enumerate(a.runs):
        d, _, label = spec.partition("=")
        label = label or os.path.basename(os.path.normpath(d))
        f, X, H, steps = load(d, a.tool)
        if not steps:
            print(f"plot_radial: {d}: no output step with a travel", file=sys.stderr)
            return 1
        for it, T in enumerate(travels):
            tr, g = min(steps, key=lambda p: abs(p[0] - T))
            r, ep, th, rb, epb, thb = profile(X, H, g)
            k = int(np.argmax(epb))
            print(f"{label}: travel {tr:.2f} mm: peak plastic strain {epb[k]:.4f} at radius {rb[k]:.2f} mm (largest cell value {ep.max():.4f} at {r[np.argmax(ep)]:.2f} mm); thickness strain min {np.nanmin(th):.4f}")
            col = f"C{it}"
            axs[0].plot(rb, epb, styles[ir % 4], color=col, label=f"{label}, {tr:.0f} mm")
            axs[1].plot(rb, thb, styles[ir % 4], color=col, label=f"{label}, {tr:.0f} mm")
    axs[0].set_ylabel("equivalent plastic strain")
    axs[1].set_ylabel("thickness strain ln(h/h0)")
    axs[1].set_xlabel("radius (current position, mm)")
    for ax in axs:
        ax.grid(True, alpha=0.3)
        ax.legend(fontsize=7)
    fig.tight_layout()
    fig.savefig(a.out, dpi=120)
    print(f"wrote {a.out}", file=sys.stderr)
    return 0


sys.exit(main())
