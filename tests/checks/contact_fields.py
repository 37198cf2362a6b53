#!/usr/bin/env python3
"""Contact fields of the last step in fields.h5: slipping nodes carry |f_T| = mu t_N (1e-10 of the
largest t_N), and the gap and slip fields are written.

usage: contact_fields.py fields.h5 MU LABEL"""
import sys

import h5py
import numpy as np

f = h5py.File(sys.argv[1], "r")
mu, label = float(sys.argv[2]), sys.argv[3]
g = f["steps"][sorted(f["steps"].keys())[-1]]
st, tn, ft = g["contact_status"][:], g["contact_normal_force"][:], g["contact_tangential_force"][:]
slipping = st == 2
ratio = np.abs(np.linalg.norm(ft[slipping], axis=1) - mu * tn[slipping]).max() / tn[slipping].max() if slipping.any() else float("nan")
ok = slipping.sum() > 0 and ratio < 1e-10 and all(k in g for k in ("contact_gap", "contact_slip"))
print(("ok" if ok else "not ok") + f" - contact fields ({label}): {int((st > 0).sum())} nodes in contact, {int(slipping.sum())} slipping with |f_T| = mu t_N to {ratio:.1e}")
sys.exit(0 if ok else 1)
