#!/usr/bin/env python3
"""Fields of the pushed quarter blank: the thickness strain of the last step shows thinning
(minimum below -1e-3) and no thickening above 1e-2.

usage: blank_fields.py fields.h5"""
import sys

import h5py

f = h5py.File(sys.argv[1], "r")
g = f["steps"][sorted(f["steps"].keys())[-1]]
t = g["thickness_strain"][:]
ok = t.min() < -1e-3 and t.max() < 1e-2
print(("ok" if ok else "not ok") + f" - blank fields: thickness strain in [{t.min():.4f}, {t.max():.4f}] (thinning under the push)")
sys.exit(0 if ok else 1)
