#!/usr/bin/env python3
"""Shortened hemispherical punch benchmark: the full-sheet punch force at 10.6 mm of travel
against the reference 10 kN (10 %), for the runs DIR/np1 and DIR/np2, which reach 12 mm.

usage: benchmark_force.py DIR"""
import csv
import sys

import numpy as np

d = sys.argv[1]
for np_ in (1, 2):
    rows = [r for r in csv.DictReader(open(f"{d}/np{np_}/contact.csv")) if r["tool"] == "punch"]
    t = np.array([0.0] + [float(r["travel"]) for r in rows]); f = np.array([0.0] + [float(r["force_full"]) for r in rows]) / 1e3
    F = np.interp(10.6, t, f)
    ok = abs(t[-1] - 12) < 1e-9 and abs(F - 10.0) / 10.0 < 0.10
    print(("ok" if ok else "not ok") + f" - shortened benchmark (np={np_}): full-sheet punch force at 10.6 mm {F:.2f} kN, reference 10 kN ({100 * (F - 10) / 10:+.1f} %, tolerance 10 %)")
