#!/usr/bin/env python3
"""Force-driven tools (cases/forcetool_holder.opts and variants). Prints "ok - ..." / "not ok - ...".

usage: forcetool.py target DIR TOOL F T0,A0,T1,A1,...   the tool's force along z (fz in contact.csv)
           equals F a(t) at every step to the step's final residual norm (history.csv), and its
           reported displacement dz moves (it is solved, not prescribed)
       forcetool.py friction DIR Z:MU ...               every slipping node at height Z carries
           |t_T| = MU t_N (fields.h5: contact_tangential_force, contact_normal_force,
           contact_status), with MU its tool's friction, and some node at each height slips
       forcetool.py release DIR TOOL T                  from time T on the tool exerts no force
           and has no node pressed against it, and before T it had"""
import csv
import sys

import numpy as np


def amp(spec, t):
    p = [float(x) for x in spec.split(",")]
    return float(np.interp(t, p[0::2], p[1::2]))


def rows(d, name):
    return list(csv.DictReader(open(f"{d}/{name}")))


what = sys.argv[1]
if what == "target":
    d, tool, F, spec = sys.argv[2], sys.argv[3], float(sys.argv[4]), sys.argv[5]
    hist = {r["step"]: r for r in rows(d, "history.csv")}
    worst, n, moved, ok = 0.0, 0, 0.0, True
    for r in rows(d, "contact.csv"):
        if r["tool"] != tool:
            continue
        t, fz, res = float(r["time"]), float(r["fz"]), float(hist[r["step"]]["residual_final"])
        err = abs(fz - F * amp(spec, t))
        # the tool's row is one entry of the residual: below its norm (and the 13 digits written)
        ok = ok and err <= res * (1 + 1e-6) + 1e-12 * abs(F)
        worst = max(worst, err / max(res, 1e-300))
        moved = max(moved, abs(float(r["dz"])))
        n += 1
    ok = ok and n >= 5 and moved > 0
    print(("ok" if ok else "not ok") + f" - {d.split('/')[-1]}: tool {tool}'s force equals {F:g} a(t) at all {n} steps to the Newton residual (largest |fz - target| / |R| = {worst:.2f}), its solved displacement up to {moved:.4g}")
    sys.exit(0 if ok else 1)

if what == "friction":
    import h5py
    d = sys.argv[2]
    f = h5py.File(d + "/fields.h5", "r")
    X = f["mesh/coordinates"][:]
    ok, lines = True, []
    for spec in sys.argv[3:]:
        z, mu = (float(x) for x in spec.split(":"))
        at = np.abs(X[:, 2] - z) < 1e-9
        worst, nslip = 0.0, 0
        for key in f["steps"]:
            g = f["steps"][key]
            if "contact_status" not in g:
                continue
            st, tn, tt = g["contact_status"][:].ravel(), g["contact_normal_force"][:].ravel(), g["contact_tangential_force"][:]
            sl = at & (st == 2) & (tn > 0)
            if sl.any():
                err = np.abs(np.linalg.norm(tt[sl], axis=1) - mu * tn[sl]) / (mu * tn[sl])
                worst = max(worst, float(err.max()))
                nslip += int(sl.sum())
        ok = ok and nslip > 0 and worst < 1e-8
        lines.append(f"z = {z:g}: mu {mu:g} over {nslip} slipping node-steps, largest error {worst:.1e}")
    print(("ok" if ok else "not ok") + f" - per-tool friction, |t_T| = mu_tool t_N at every slipping node: " + "; ".join(lines))
    sys.exit(0 if ok else 1)

if what == "release":
    d, tool, T = sys.argv[2], sys.argv[3], float(sys.argv[4])
    r = [x for x in rows(d, "contact.csv") if x["tool"] == tool]
    before = [x for x in r if float(x["time"]) < T - 1e-12]
    after = [x for x in r if float(x["time"]) >= T - 1e-12]
    # at t = T itself the target force is zero and the holder's equilibrium leaves nodes at a gap
    # of round-off: some may still touch, with a force of round-off on the scale of the force
    # before (1e-9 of it); after T no node is pressed and the force is exactly zero
    scale = max([abs(float(x["fz"])) for x in before] + [0.0])
    at = [x for x in after if abs(float(x["time"]) - T) <= 1e-12]
    later = [x for x in after if abs(float(x["time"]) - T) > 1e-12]
    ok = len(later) >= 2 and (T <= 0 or any(int(x["active"]) > 0 for x in before))
    ok = ok and all(abs(float(x["fz"])) <= 1e-9 * scale for x in at)
    ok = ok and all(int(x["active"]) == 0 and abs(float(x["fz"])) == 0 for x in later)
    fat = max([abs(float(x["fz"])) for x in at] + [0.0])
    print(("ok" if ok else "not ok") + f" - {d.split('/')[-1]}: tool {tool} pressed before t = {T:g} and, with its force ramped to zero, releases the sheet ({len(later)} steps after with no node pressed and no force; at t = {T:g} {fat:.1e} N against {scale:.3g} before; no singular matrix)")
    sys.exit(0 if ok else 1)
sys.exit(f"unknown check {what}")
