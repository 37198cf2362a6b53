#!/usr/bin/env python3
"""Compare a CSV history (history.csv, contact.csv) with a stored reference, column by column,
matching the columns BY NAME (their order does not matter).

  * the number of rows must be the same;
  * every column of REF missing from NEW is a failure, unless named in --allow-missing;
    columns only in NEW are listed, not compared;
  * text columns (e.g. the tool name) and integer columns (step, newton_its, active, stick,
    slip: every reference entry an integer) must be equal;
  * numeric columns: |new - ref| <= rtol |ref| + floor, with the floor
        max(atol, rtol * S),  S = max |ref| over the column,
    and for force columns (names ending in _fx, _fy, _fz, and force, force_full, fx, fy, fz, force_normal, force_tangential) S is the largest
    force magnitude of the file, so that a reaction component that is zero up to round-off is
    compared on the scale of the forces it is the round-off of.
  * --int-tol newton_its=1 lets an integer column differ by up to 1: a Newton solve that ends
    near its tolerance takes one iteration more or less with another summation order (2 ranks,
    another CPU); its result moves by round-off only;
  * columns matching a --skip pattern (fnmatch, e.g. 'residual_*': Newton residual norms at
    convergence are round-off) are not compared.

Tolerance of the stored references (tests/test_reference.sh): --rtol 1e-10 --atol 0, i.e. 1e-10
relative, with the absolute floor 1e-10 x the column's (or the file's forces') largest magnitude.

The "relative difference" reported is |new - ref| / max(|ref|, S): the largest over all the
compared numeric entries, with its column and row.

usage: compare_csv.py REF NEW [--rtol R] [--atol A] [--allow-missing C1,C2] [--skip P1,P2]
                     [--int-tol C1=N1,C2=N2] [--label L]
Prints one line "ok - ..." or "not ok - ..."; exit status 0 or 1."""
import argparse
import csv
import fnmatch
import math
import sys


def num(x):
    try:
        v = float(x)
    except ValueError:
        return None
    return v


def is_int(x):
    try:
        int(x)
        return True
    except ValueError:
        return False


def is_force(c):
    return c.endswith(("_fx", "_fy", "_fz")) or c in ("force", "force_full", "fx", "fy", "fz", "force_normal", "force_tangential")


def compare(ref_path, new_path, rtol, atol, allow_missing, skip, int_tol=None):
    """Returns (ok, message)."""
    with open(ref_path) as f:
        rr = list(csv.DictReader(f))
        rcols = list(rr[0].keys()) if rr else []
    with open(new_path) as f:
        rn = list(csv.DictReader(f))
        ncols = list(rn[0].keys()) if rn else []
    problems, notes = [], []
    if len(rr) != len(rn):
        problems.append(f"{len(rn)} rows, reference {len(rr)}")
    if not rr:
        problems.append("reference has no rows")
    missing = [c for c in rcols if c not in ncols and c not in allow_missing]
    if missing:
        problems.append("missing column(s) " + ",".join(missing))
    extra = [c for c in ncols if c not in rcols]
    skipped = [c for c in rcols if any(fnmatch.fnmatch(c, p) for p in skip)]
    cols = [c for c in rcols if c in ncols and c not in skipped]
    n = min(len(rr), len(rn))
    numeric = [c for c in cols if all(num(r[c]) is not None for r in rr)]
    forces = [abs(num(r[c])) for r in rr for c in numeric if is_force(c)]
    fmax = max(forces) if forces else 0.0
    worst, where, ncmp = 0.0, "-", 0
    for c in cols:
        va = [r[c] for r in rr[:n]]
        vb = [r[c] for r in rn[:n]]
        if c not in numeric or all(is_int(x) for x in va):
            kind = "text" if c not in numeric else "integer"
            tol = (int_tol or {}).get(c, 0) if kind == "integer" else 0
            if tol:
                bad = [i for i, (x, y) in enumerate(zip(va, vb)) if not is_int(y or "") or abs(int(y) - int(x)) > tol]
                moved = sum(1 for x, y in zip(va, vb) if is_int(y or "") and int(x) != int(y))
                if moved:
                    notes.append(f"{c} differs by <= {tol} in {moved} row(s)")
            else:
                bad = [i for i, (x, y) in enumerate(zip(va, vb)) if x.strip() != (y or "").strip()]
            if bad:
                i = bad[0]
                problems.append(f"{kind} column {c} differs in {len(bad)} row(s), first row {i + 1}: {vb[i]!r}, reference {va[i]!r}")
            ncmp += len(va)
            continue
        fa = [num(x) for x in va]
        fb = [num(y) if y is not None else None for y in vb]
        S = max(abs(x) for x in fa)
        if is_force(c):
            S = max(S, fmax)
        floor = max(atol, rtol * S)
        nbad = 0
        for i, (x, y) in enumerate(zip(fa, fb)):
            ncmp += 1
            if y is None or not math.isfinite(y):
                nbad += 1
                where = f"{c} row {i + 1} not a number: {vb[i]!r}"
                worst = math.inf
                continue
            d = abs(y - x)
            rel = d / max(abs(x), S, 1e-300)
            if rel > worst:
                worst, where = rel, f"{c} row {i + 1}"
            if d > rtol * abs(x) + floor:
                nbad += 1
        if nbad:
            problems.append(f"column {c}: {nbad} row(s) beyond the tolerance")
    msg = f"{n} rows, {len(cols)} columns compared ({ncmp} entries), largest relative difference {worst:.1e} ({where})"
    if notes:
        msg += ", " + ", ".join(notes)
    if skipped:
        msg += f", not compared: {','.join(skipped)}"
    if extra:
        msg += f", new column(s) not in the reference: {','.join(extra)}"
    allowed = [c for c in allow_missing if c in rcols and c not in ncols]
    if allowed:
        msg += f", allowed missing: {','.join(allowed)}"
    if problems:
        msg += "; " + "; ".join(problems)
    return not problems, msg


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("ref")
    ap.add_argument("new")
    ap.add_argument("--rtol", type=float, default=1e-10)
    ap.add_argument("--atol", type=float, default=0.0)
    ap.add_argument("--allow-missing", default="", help="comma-separated reference columns that NEW may lack")
    ap.add_argument("--skip", default="", help="comma-separated fnmatch patterns of columns not compared")
    ap.add_argument("--int-tol", default="", help="comma-separated COL=N: integer column COL may differ by N")
    ap.add_argument("--label", default=None)
    a = ap.parse_args()
    split = lambda s: [x for x in s.split(",") if x]
    try:
        ok, msg = compare(a.ref, a.new, a.rtol, a.atol, split(a.allow_missing), split(a.skip),
                          {k: int(v) for k, v in (x.split("=") for x in split(a.int_tol))})
    except (OSError, csv.Error, KeyError, IndexError) as e:
        ok, msg = False, f"cannot compare: {e}"
    label = a.label or f"{a.new} against {a.ref}"
    print(f"{'ok' if ok else 'not ok'} - {label} (rtol {a.rtol:g}): {msg}")
    return 0 if ok else 1


if __name__ == "__main__":
    sys.exit(main())
