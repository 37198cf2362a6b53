#!/usr/bin/env python3
"""Fields of the tension bar at time 1 (stretch 1.3): u_x = 0.3 x (1e-9) and the plastic strain
equal to the closed form of the Swift material (1e-8 relative).

usage: tension_fields.py fields.h5"""
import math
import sys

import h5py
import numpy as np

f = h5py.File(sys.argv[1], "r")
last = sorted(f["steps"].keys())[-1]
g = f["steps"][last]
X = f["mesh/coordinates"][:]
u = g["displacement"][:]
ep = g["plastic_strain"][:]
# homogeneous: u_x = 0.3 x exactly; ep from the closed form at stretch 1.3
eu = np.abs(u[:, 0] - 0.3 * X[:, 0]).max()
E, K, e0, n, lam = 69004.0, 589.0, 1e-4, 0.216, 1.3
lo, hi = 0.0, E * math.log(lam)
for _ in range(200):
    s = 0.5 * (lo + hi)
    (lo, hi) = (lo, s) if s - K * (e0 + math.log(lam) - s / E) ** n > 0 else (s, hi)
ep_ref = math.log(lam) - s / E
eep = np.abs(ep - ep_ref).max() / ep_ref
ok = float(g.attrs["time"]) == 1.0 and eu < 1e-9 and eep < 1e-8
print(("ok" if ok else "not ok") + f" - tension bar fields at time 1: |u_x - 0.3 x| {eu:.1e}, plastic strain {ep.mean():.6f} vs closed form {ep_ref:.6f} (rel {eep:.1e})")
sys.exit(0 if ok else 1)
