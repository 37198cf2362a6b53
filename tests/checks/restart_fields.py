#!/usr/bin/env python3
"""A restarted run B against the uninterrupted run A: B's fields valid, with the same steps as
A's, and B's history without a duplicate or unordered step.

usage: restart_fields.py A_DIR B_DIR LABEL"""
import subprocess
import sys

import h5py

a, b, label = sys.argv[1:4]
valid = subprocess.run([sys.executable, "tests/check_fields.py", b, "-q"], capture_output=True).returncode == 0


def steps(d):
    with h5py.File(d + "/fields.h5", "r") as f:
        return [int(f["steps"][k].attrs["step"]) for k in f["steps"]]


sa, sb = steps(a), steps(b)
rows = open(b + "/history.csv").read().splitlines()[1:]
hist = [int(r.split(",")[0]) for r in rows]
ok = valid and sorted(sa) == sorted(sb) and hist == sorted(set(hist))
print(("ok" if ok else "not ok") + f" - {label}: fields valid ({valid}), field steps {len(sb)} (uninterrupted {len(sa)}), history rows {len(hist)}, no duplicate")
sys.exit(0 if ok else 1)
