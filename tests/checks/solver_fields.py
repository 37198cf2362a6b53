#!/usr/bin/env python3
"""Two runs of one process with different linear solvers: the displacement fields at every output
time the two share, against each other relative to the largest displacement at that time; the
last shared time of the stage ending at T_DRAW (the draw) and the run's last time (springback)
must be among them.

usage: solver_fields.py A_DIR B_DIR T_DRAW RTOL LABEL"""
import sys

import h5py
import numpy as np

a, b, tdraw, rtol, label = sys.argv[1], sys.argv[2], float(sys.argv[3]), float(sys.argv[4]), sys.argv[5]


def fields(d):
    with h5py.File(d + "/fields.h5", "r") as f:
        return {round(float(f["steps"][k].attrs["time"]), 9): f["steps"][k]["displacement"][:] for k in f["steps"]}


fa, fb = fields(a), fields(b)
shared = sorted(set(fa) & set(fb))
worst, at = 0.0, None
for t in shared:
    d = np.abs(fa[t] - fb[t]).max() / max(np.abs(fa[t]).max(), 1e-300)
    if d >= worst:
        worst, at = d, t
draw = [t for t in shared if t <= tdraw + 1e-9]
ok = bool(shared) and bool(draw) and draw[-1] == max(t for t in fa if t <= tdraw + 1e-9) and shared[-1] == max(fa) == max(fb) and worst <= rtol
print(("ok" if ok else "not ok") + f" - {label}: displacements at {len(shared)} shared output times (end of the draw {draw[-1] if draw else None}, last {shared[-1] if shared else None}), largest difference {worst:.2e} of the largest displacement (time {at}), tolerance {rtol:g}")
sys.exit(0 if ok else 1)
