#!/usr/bin/env python3
"""Block dragged on a plane with the augmented Lagrangian (cases/block_plane_drag.opts,
-contact_augmented): while every bottom node slips, the tangential reaction at the held face is mu
times the normal one, and the tool's friction resultant mu times its normal resultant (1e-8); every
step's largest penetration is below the tolerance, and every step ran at least one augmentation.

usage: auglag_drag.py OUTDIR MU TOL NODES LABEL"""
import csv
import sys

d, mu, tol, nb, label = sys.argv[1], float(sys.argv[2]), float(sys.argv[3]), int(sys.argv[4]), sys.argv[5]
hist = {int(r["step"]): r for r in csv.DictReader(open(d + "/history.csv"))}
cont = [r for r in csv.DictReader(open(d + "/contact.csv"))]
err, nslip, pen, naug, ok = 0.0, 0, 0.0, [], True
for c in cont:
    s = int(c["step"])
    pen = max(pen, float(c["max_penetration"]))
    naug.append(int(c["augmentations"]))
    if int(c["slip"]) == nb:
        h = hist[s]
        fx, fz = float(h["hold_fx"]), float(h["hold_fz"])
        err = max(err, abs(abs(fx) - mu * abs(fz)) / (mu * abs(fz)))
        err = max(err, abs(float(c["force_tangential"]) - mu * float(c["force_normal"])) / (mu * float(c["force_normal"])))
        nslip += 1
ok = nslip >= 2 and err < 1e-8 and pen <= tol and min(naug) >= 1
print(("ok" if ok else "not ok") + f" - augmented Lagrangian, block dragged on a plane ({label}): {nslip} steps in slip, |t_T| = mu t_N to {err:.1e}; largest penetration {pen:.2e} (tolerance {tol:g}); {min(naug)} to {max(naug)} Newton solves per step")
sys.exit(0 if ok else 1)
