#!/usr/bin/env python3
"""Quadratic convergence from a -snes_monitor log. For every step with at least three Newton
iterations above the round-off floor (100 times the smallest final residual of the run), the last
pair satisfies r_{k+1} <= C r_k^2 with C = c / r_0 and c <= 100 (r_0 the step's initial residual):
a linearly converging Newton (r_{k+1} = q r_k) would give c = q r_0 / r_k, which grows without bound
as r_k -> 0 (1e6 for q = 0.1 at r_k = 1e-7 r_0).

usage: check_quadratic.py LOG LABEL"""
import re
import sys

log, label = sys.argv[1], sys.argv[2]
steps, cur = [], []
for line in open(log):
    m = re.match(r"\s*(\d+) SNES Function norm ([0-9.eE+-]+)", line)
    if m:
        if int(m.group(1)) == 0 and cur:
            steps.append(cur)
            cur = []
        cur.append(float(m.group(2)))
if cur:
    steps.append(cur)
floor = 100 * min(r[-1] for r in steps)  # a hundred times the round-off level reached
cs = []
for r in steps:
    r0 = r[0]
    r = [x for x in r if x > floor]
    if len(r) < 4:
        continue
    b, c = r[-2], r[-1]
    cs.append(c * r0 / b**2)
ok = len(cs) >= 3 and max(cs) <= 100
print(("ok" if ok else "not ok") + f" - quadratic convergence, {label}: {len(cs)} steps checked, largest c = r_k+1 r_0 / r_k^2 = {max(cs) if cs else float('nan'):.2e} (<= 100)")
sys.exit(0 if ok else 1)
