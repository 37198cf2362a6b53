#!/usr/bin/env python3
"""Uniaxial tension of a prismatic bar against the closed form.

Homogeneous uniaxial stress with the Hencky law and J2 plasticity: at stretch lam the axial
Kirchhoff stress s solves s = sigma_y(ln lam - s/E), and the reaction is F = s A0 / lam
(Cauchy s/J on the current area A0 lam_t^2, J = lam lam_t^2).

usage: check_tension.py history.csv COLUMN A0 L0 U_END K EPS0 N E [TOL]
Checks every row; prints "ok - ..." or "not ok - ..."."""
import csv
import math
import sys

path, col = sys.argv[1], sys.argv[2]
A0, L0, U, K, eps0, n, E = map(float, sys.argv[3:10])
tol = float(sys.argv[10]) if len(sys.argv) > 10 else 1e-6


def kirchhoff(lam):
    e = math.log(lam)
    sy = lambda ep: K * (eps0 + ep) ** n
    if E * e <= sy(0.0):
        return E * e
    lo, hi = 0.0, E * e
    for _ in range(200):
        s = 0.5 * (lo + hi)
        if s - sy(e - s / E) > 0:
            hi = s
        else:
            lo = s
    return 0.5 * (lo + hi)


worst, last = 0.0, None
with open(path) as f:
    rows = list(csv.DictReader(f))
for r in rows:
    lam = 1.0 + U * float(r["time"]) / L0
    F = kirchhoff(lam) * A0 / lam
    worst = max(worst, abs(float(r[col]) - F) / abs(F))
    last = (float(r["time"]), lam, float(r[col]), F)
ok = len(rows) > 0 and worst < tol and abs(last[0] - 1.0) < 1e-12
print(f"{'ok' if ok else 'not ok'} - uniaxial tension to stretch {last[1]:.3f}: {len(rows)} steps, reaction {last[2]:.6f} vs closed form {last[3]:.6f}, largest relative error {worst:.2e} (tolerance {tol:.0e})")
sys.exit(0 if ok else 1)
