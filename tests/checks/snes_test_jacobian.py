#!/usr/bin/env python3
"""-snes_test_jacobian: every ||J - Jfd||_F/||J||_F in LOG below MAX, at least MIN_COUNT of them;
with --contact DIR, the run's contact.csv must also have steps with sticking and with slipping
nodes.

usage: snes_test_jacobian.py LOG MIN_COUNT MAX LABEL [--contact DIR]"""
import csv
import re
import sys

log, nmin, rmax, label = sys.argv[1], int(sys.argv[2]), float(sys.argv[3]), sys.argv[4]
r = [float(x) for x in re.findall(r"\|\|J - Jfd\|\|_F/\|\|J\|\|_F = ([0-9.eE+-]+)", open(log).read())]
ok = len(r) >= nmin and max(r) < rmax
what = f"{len(r)} Jacobians"
if "--contact" in sys.argv:
    rows = list(csv.DictReader(open(sys.argv[sys.argv.index("--contact") + 1] + "/contact.csv")))
    stick = sum(int(x["stick"]) > 0 for x in rows); slip = sum(int(x["slip"]) > 0 for x in rows)
    ok = ok and stick > 0 and slip > 0
    what += f" over {stick} steps with sticking and {slip} with slipping nodes"
print(("ok" if ok else "not ok") + f" - -snes_test_jacobian, {label}: {what}, largest ||J - Jfd||/||J|| = {max(r) if r else float('nan'):.2e} (< {rmax:g})")
sys.exit(0 if ok else 1)
