#!/usr/bin/env python3
"""Seed quarter blank with penalties per unit area: the tributary areas of the slave nodes (from
the log of run A) sum to twice the polygon of the quarter blank (1e-9), and the punch force at
40 mm is that of the per-node run N to 1 %.

usage: seed_area.py N_DIR A_DIR"""
import csv
import math
import re
import sys

n, a = sys.argv[1:3]
tot = float(re.search(r"tributary areas of the slave nodes: total ([0-9.eE+-]+)", open(a + ".log").read()).group(1))
exact = 2 * 0.5 * 59.18**2 * math.sin(math.pi / 28) * 14
ok1 = abs(tot - exact) < 1e-9 * exact
print(("ok" if ok1 else "not ok") + f" - tributary areas on the seed quarter blank (np=2): total {tot:.10g}, polygon {exact:.10g}")


def force(d):
    rows = list(csv.DictReader(open(d + "/contact.csv")))
    last = [r for r in rows if r["tool"] == "punch"][-1]
    return float(last["time"]), float(last["force"])


(tn, fn), (ta, fa) = force(n), force(a)
ok2 = tn == 1 and ta == 1 and abs(fa - fn) < 0.01 * abs(fn)
print(("ok" if ok2 else "not ok") + f" - seed hemisphere: punch force at 40 mm {fa:.6g} with the penalty per unit area, {fn:.6g} per node (difference {abs(fa - fn) / abs(fn):.2%})")
