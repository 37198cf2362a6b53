#!/usr/bin/env python3
"""Block pressed onto a rigid plane and dragged (cases/block_plane_drag.opts).

While every bottom node sticks, the tangential reaction at the held top face equals
K_T * sum_i (u_x,i - s_x): the tangential penalty times each node's slip relative to the plane
(from the output fields), s_x the plane's x translation. While every node slips, it equals
mu times the normal reaction. Prints "ok - ..." / "not ok - ..." lines.

usage: check_block_drag.py OUTDIR KT MU"""
import csv
import sys

import h5py
import numpy as np

d, KT, mu = sys.argv[1], float(sys.argv[2]), float(sys.argv[3])
per_area = len(sys.argv) > 4 and sys.argv[4] == "per_area"
hist = {int(r["step"]): r for r in csv.DictReader(open(d + "/history.csv"))}
cont = {int(r["step"]): r for r in csv.DictReader(open(d + "/contact.csv"))}
f = h5py.File(d + "/fields.h5", "r")
X = f["mesh/coordinates"][:]
bottom = np.abs(X[:, 2]) < 1e-12
nb = int(bottom.sum())


def tributary(c):  # half the distance to the neighbours on each side, per grid line
    g = np.unique(c)
    w = np.zeros_like(g)
    w[1:] += 0.5 * np.diff(g)
    w[:-1] += 0.5 * np.diff(g)
    return w[np.searchsorted(g, c)]


A = tributary(X[bottom, 0]) * tributary(X[bottom, 1]) if per_area else np.ones(nb)


def sx(t):  # the plane's path: rises until load 0.5, then slides 0.05 along x
    return 0.0 if t <= 0.5 else 0.05 * (t - 0.5) / 0.5


stick_err, slip_err, nstick, nslip = 0.0, 0.0, 0, 0
for key in f["steps"]:
    g = f["steps"][key]
    step, t = int(g.attrs["step"]), float(g.attrs["time"])
    if step == 0:
        continue
    h, c = hist[step], cont[step]
    fx, fz = float(h["hold_fx"]), float(h["hold_fz"])
    if int(c["stick"]) == nb and t > 0.5 + 1e-12:
        u = g["displacement"][:]
        expect = KT * np.sum(A * (u[bottom, 0] - sx(t)))
        stick_err = max(stick_err, abs(fx - expect) / abs(expect))
        nstick += 1
    elif int(c["slip"]) == nb:
        slip_err = max(slip_err, abs(abs(fx) - mu * abs(fz)) / (mu * abs(fz)))
        nslip += 1
ok1 = nstick >= 2 and stick_err < 1e-8
ok2 = nslip >= 2 and slip_err < 1e-8
what = " (K_T per unit area x tributary area)" if per_area else ""
print(("ok" if ok1 else "not ok") + f" - block dragged on a plane{what}, {nstick} steps in stick ({nb} nodes): tangential reaction = K_T x slip, largest relative error {stick_err:.1e}")
print(("ok" if ok2 else "not ok") + f" - block dragged on a plane{what}, {nslip} steps in slip: tangential reaction = mu x normal reaction, largest relative error {slip_err:.1e}")
sys.exit(0 if ok1 and ok2 else 1)
