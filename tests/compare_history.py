#!/usr/bin/env python3
"""Compare two CSV histories (history.csv, contact.csv) row by row. Text columns must be equal;
every numeric column must agree to DIGITS significant digits relative to its largest magnitude.
Force columns (*_fx, *_fy, *_fz, force, force_full, fx, fy, fz, force_normal, force_tangential) use at least 1e-3 of the largest force of the
file as their scale, so that a component that is zero up to round-off compares as zero. Residual
norms and Newton iteration counts (which round-off can change by one near the tolerance) are not
compared.

usage: compare_history.py A.csv B.csv DIGITS LABEL
Prints one line "ok - ..." or "not ok - ..."; exit code 0 or 1."""
import csv
import sys


def num(x):
    try:
        return float(x)
    except ValueError:
        return None


def main():
    a, b, digits, label = sys.argv[1], sys.argv[2], int(sys.argv[3]), sys.argv[4]
    ra, rb = list(csv.DictReader(open(a))), list(csv.DictReader(open(b)))
    ok = len(ra) == len(rb) and len(ra) > 0
    worst, where = 0.0, ""
    if ok:
        cols = [c for c in ra[0].keys() if not c.startswith("residual") and c != "newton_its"]
        numeric = [c for c in cols if all(num(r[c]) is not None for r in ra)]
        isforce = lambda c: c.endswith(("_fx", "_fy", "_fz")) or c in ("force", "force_full", "fx", "fy", "fz", "force_normal", "force_tangential")
        gmax = max([abs(num(r[c])) for r in ra for c in numeric if isforce(c)] + [1e-300])
        for c in cols:
            if c not in numeric:
                if any(x[c] != y[c] for x, y in zip(ra, rb)):
                    ok, where = False, f"text column {c}"
                continue
            va = [num(r[c]) for r in ra]
            vb = [num(r[c]) for r in rb]
            if any(v is None for v in vb):
                ok, where = False, f"column {c} not numeric in {b}"
                continue
            scale = max(max(abs(x) for x in va), 1e-3 * gmax if isforce(c) else 1e-300)
            for i, (x, y) in enumerate(zip(va, vb)):
                d = abs(x - y) / scale
                if d > worst:
                    worst, where = d, f"{c} row {i + 1}"
    tol = 0.5 * 10 ** (1 - digits)
    ok = ok and worst <= tol
    print(f"{'ok' if ok else 'not ok'} - {label}: {len(ra)} vs {len(rb)} rows, largest relative difference {worst:.2e} ({where or '-'}), tolerance {tol:.1e}")
    return 0 if ok else 1


sys.exit(main())
