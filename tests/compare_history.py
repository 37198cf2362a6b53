#!/usr/bin/env python3
"""Compare two history.csv files row by row: step, time and Newton iterations must agree to
DIGITS significant digits, and every force column too, relative to the largest force magnitude in
the file (a component that is zero up to round-off compares as zero). Residual norms are not
compared.

usage: compare_history.py A.csv B.csv DIGITS LABEL
Prints one line "ok - ..." or "not ok - ..."; exit code 0 or 1."""
import csv
import sys


def read(path):
    with open(path) as f:
        rows = list(csv.DictReader(f))
    return rows


def main():
    a, b, digits, label = sys.argv[1], sys.argv[2], int(sys.argv[3]), sys.argv[4]
    ra, rb = read(a), read(b)
    ok = len(ra) == len(rb) and len(ra) > 0
    worst, where = 0.0, ""
    if ok:
        cols = [c for c in ra[0].keys() if not c.startswith("residual")]
        head = {"step", "time", "newton_its"}
        fscale = max([abs(float(r[c])) for r in ra for c in cols if c not in head] + [1e-300])
        for c in cols:
            va = [float(r[c]) for r in ra]
            vb = [float(r[c]) for r in rb]
            scale = max(max(abs(x) for x in va), 1e-300) if c in head else fscale
            for i, (x, y) in enumerate(zip(va, vb)):
                d = abs(x - y) / scale
                if d > worst:
                    worst, where = d, f"{c} row {i + 1}"
    tol = 0.5 * 10 ** (1 - digits)
    ok = ok and worst <= tol
    print(f"{'ok' if ok else 'not ok'} - {label}: {len(ra)} vs {len(rb)} rows, largest relative difference {worst:.2e} ({where or '-'}), tolerance {tol:.1e}")
    return 0 if ok else 1


sys.exit(main())
