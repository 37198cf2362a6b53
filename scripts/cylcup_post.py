#!/usr/bin/env python3
"""Post-processing of the cylindrical cup of doc/tutorial.md (cases/cylindrical_cup.opts).

usage: cylcup_post.py OUTDIR [--step N] [--plot PNG]

Reads OUTDIR/fields.h5 and OUTDIR/contact.csv and prints, at the last output step of the draw (or
step N): the draw-in of the blank's rim (50 minus its radius in the plane, mid-thickness) and its
height above the die's face at the azimuths 0 (rolling direction), 45 and 90 degrees, the earing
(the draw-in at 45 degrees against the mean of 0 and 90: ears form at 0 and 90 degrees where it
is positive, as Hill's r-values with r0 + r90 > 2 r45 predict), the largest thinning (the cells' thickness strain
ln(t/t0)) and where it is, the largest punch force (the whole cup: the quarter's times 4); with
--plot, a figure of the rim's draw-in against the azimuth, the thickness strain along
the rolling and transverse directions against the initial radius, and the punch force against
its stroke."""
import argparse
import csv
import math
import sys

import h5py
import numpy as np

R0 = 50.0


def last_draw_step(f, rows):
    """the last output step whose time is within the draw stage (time <= 2)"""
    steps = sorted(int(k) for k in f["steps"].keys())
    t = {int(k): float(f["steps"][k].attrs["time"]) for k in f["steps"].keys()}
    draw = [s for s in steps if t[s] <= 2.0 + 1e-12]
    return draw[-1] if draw else steps[-1]


def rim(X, u):
    """azimuth (degrees), draw-in and height of the rim's mid-thickness points, by azimuth"""
    r = np.hypot(X[:, 0], X[:, 1])
    sel = np.isclose(r, R0, rtol=0, atol=1e-6)
    x = X + u
    phi = np.degrees(np.arctan2(X[sel, 1], X[sel, 0]))
    out = {}
    for p, xs in zip(np.round(phi, 6), x[sel]):
        out.setdefault(p, []).append(xs)
    az = np.array(sorted(out))
    m = np.array([np.mean(out[p], axis=0) for p in az])
    return az, R0 - np.hypot(m[:, 0], m[:, 1]), m[:, 2]


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("out")
    ap.add_argument("--step", type=int)
    ap.add_argument("--plot")
    a = ap.parse_args()
    f = h5py.File(f"{a.out}/fields.h5", "r")
    rows = list(csv.DictReader(open(f"{a.out}/contact.csv")))
    step = a.step if a.step is not None else last_draw_step(f, rows)
    g = f["steps/%06d" % step]
    X = f["mesh/coordinates"][:]
    hexa = f["mesh/hexahedra"][:]
    u = g["displacement"][:]
    az, din, z = rim(X, u)
    at = {p: (float(np.interp(p, az, din)), float(np.interp(p, az, z))) for p in (0.0, 45.0, 90.0)}
    es = g["thickness_strain"][:]
    c = X[hexa].mean(axis=1)
    k = int(np.argmin(es))
    punch = [r for r in rows if r["tool"] == "punch" and r.get("stage", "draw") in ("close", "draw")]
    fmax = max((abs(float(r["force_full"])) for r in punch), default=0.0)
    stroke = max((abs(float(r["travel"])) for r in punch if int(r["step"]) <= step), default=0.0)
    print(f"step {step} (time {float(g.attrs['time']):.4g}), punch stroke {stroke:.2f} mm, largest punch force {fmax / 1000:.2f} kN")
    for p in (0.0, 45.0, 90.0):
        print(f"rim at {p:4.0f} deg: draw-in {at[p][0]:.3f} mm, height {at[p][1]:.3f} mm")
    ear = at[45.0][0] - 0.5 * (at[0.0][0] + at[90.0][0])
    print(f"earing: the rim draws in {ear:.3f} mm more at 45 deg than at 0 and 90 (ears at 0 and 90 deg where positive)")
    print(f"largest thinning: thickness strain {es[k]:.4f} ({100 * (1 - math.exp(es[k])):.1f} %) at initial radius {math.hypot(c[k, 0], c[k, 1]):.1f} mm, azimuth {math.degrees(math.atan2(c[k, 1], c[k, 0])):.0f} deg")
    if a.plot:
        import matplotlib
        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
        fig, ax = plt.subplots(1, 3, figsize=(13, 3.8))
        ax[0].plot(az, din, "o-")
        ax[0].set_xlabel("azimuth from the rolling direction (deg)")
        ax[0].set_ylabel("draw-in of the rim (mm)")
        rc = np.hypot(c[:, 0], c[:, 1])
        ph = np.degrees(np.arctan2(c[:, 1], c[:, 0]))
        for lo, hi, lab in ((0, 10, "rolling direction"), (80, 90, "transverse")):
            s = (ph >= lo) & (ph <= hi)
            o = np.argsort(rc[s])
            ax[1].plot(rc[s][o], 100 * (np.exp(es[s][o]) - 1), ".-", label=lab)
        ax[1].set_xlabel("initial radius (mm)")
        ax[1].set_ylabel("thickness change (%)")
        ax[1].legend()
        ax[2].plot([abs(float(r["travel"])) for r in punch], [abs(float(r["force_full"])) / 1000 for r in punch])
        ax[2].set_xlabel("punch stroke (mm)")
        ax[2].set_ylabel("punch force (kN)")
        fig.tight_layout()
        fig.savefig(a.plot, dpi=90)
    return 0


if __name__ == "__main__":
    sys.exit(main())
