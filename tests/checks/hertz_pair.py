#!/usr/bin/env python3
"""Plane-strain Hertz contact of a run (cases/pair_hertz.opts): the slave nodes' pressures against
the closed form from the run's own force.

usage: hertz_pair.py OUT_DIR [--mesh cases/meshes/pair_hertz.inp] [--slave block_top] [--pair p]
                     [--step N] [--E 1000] [--nu 0.3] [--rigid] [--estar E*] [--R 10] [--t 0.1]
                     [--tol 0.05] [--reaction press_fz] [--quiet]

The model: a half model x >= 0 (symmetry plane x = 0), one element along y of thickness t, the
slave set a line of nodes pairs (y = 0 and y = t) along the contact surface. From OUT_DIR/fields.h5
(the last step, or --step): /mesh/node_ids, /mesh/coordinates, the displacement and the node field
contact_normal_force (a nodal force, the same field the rigid tools' contact writes); the slave
nodes are those of the mesh's node set --slave (read from the .inp deck, matched by node id).

  P     the force per unit length of the whole contact: 2 sum(f_i)/t over the slave nodes (the
        symmetry half times 2); compared with contact.csv's row of the pair (force_normal, else
        |(fx, fy, fz)|) and with the reaction --reaction of history.csv when they exist
  p_i   nodal pressure (f_i(y=0) + f_i(y=t)) / (l_i t), l_i the node's tributary length on the
        current surface (half of each adjacent segment; the node on x = 0 and the last node half a
        segment); the two nodes of a pair each carry half the thickness, half the force
  b, p0 fitted: p(x) = p0 sqrt(1 - x^2/b^2) for |x| < b, 0 beyond, by least squares weighted by l_i
        over every slave node (p0 linear for each b, b by a scan and a golden-section search);
        x the current coordinate
  edge  the last node pressed (f > 0) and the first open after it bracket b

The closed form (plane strain): 1/E* = (1-nu1^2)/E1 + (1-nu2^2)/E2 (two bodies of E, nu; --rigid:
one of them rigid, E* = E/(1-nu^2); --estar gives it), b = sqrt(4 P R/(pi E*)), p0 = 2 P/(pi b).
Checks, one line each (ok / not ok): P against contact.csv and against the reaction (5e-3: the
nodal normal forces act along the master's normal, tilted by about x/R, so that their sum exceeds
the vertical resultant by about b^2/8R^2, 1.3e-3 at b = 1, R = 10), b and
p0 against the closed form (--tol, default 5 %), the profile's RMS deviation from the fitted
ellipse (2 --tol of p0), the closed form's b within the bracket widened by one element.
Exit status 0 when every check passes, 1 otherwise.
"""
import argparse
import csv
import math
import os
import sys

import h5py
import numpy as np


def read_nset(path, name):
    """the node ids of *NSET, NSET=name (case-insensitive, GENERATE understood) of an .inp deck"""
    ids, cur, gen = [], False, False
    with open(path) as f:
        for line in f:
            s = line.strip()
            if not s or s.startswith("**"):
                continue
            if s.startswith("*"):
                parts = [p.strip() for p in s[1:].split(",")]
                kw = parts[0].upper()
                opts = {}
                for p in parts[1:]:
                    k, _, v = p.partition("=")
                    opts[k.strip().upper()] = v.strip().strip('"')
                cur = kw == "NSET" and opts.get("NSET", "").lower() == name.lower()
                gen = "GENERATE" in opts
                continue
            if cur:
                v = [int(x) for x in s.replace(",", " ").split()]
                if gen:
                    ids.extend(range(v[0], v[1] + 1, v[2] if len(v) > 2 else 1))
                else:
                    ids.extend(v)
    return np.array(sorted(set(ids)), int)


def fit_ellipse(x, p, w):
    """b, p0 minimising sum w (p - p0 sqrt(1 - x^2/b^2)_+)^2"""
    def cost(b):
        s = np.sqrt(np.clip(1 - (x / b) ** 2, 0, None))
        ss = np.sum(w * s * s)
        p0 = np.sum(w * s * p) / ss if ss > 0 else 0.0
        return np.sum(w * (p - p0 * s) ** 2), p0
    xs = np.sort(x[x > 0])
    grid = np.linspace(xs[0], xs[-1], 4000)
    c = [cost(b)[0] for b in grid]
    k = int(np.argmin(c))
    lo, hi = grid[max(k - 1, 0)], grid[min(k + 1, len(grid) - 1)]
    g = (math.sqrt(5) - 1) / 2
    for _ in range(80):
        m1, m2 = hi - g * (hi - lo), lo + g * (hi - lo)
        if cost(m1)[0] < cost(m2)[0]:
            hi = m2
        else:
            lo = m1
    b = 0.5 * (lo + hi)
    return b, cost(b)[1]


def main(argv):
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("out")
    ap.add_argument("--mesh", default="cases/meshes/pair_hertz.inp")
    ap.add_argument("--slave", default="block_top")
    ap.add_argument("--pair", default="p")
    ap.add_argument("--step", type=int)
    ap.add_argument("--E", type=float, default=1000.0)
    ap.add_argument("--nu", type=float, default=0.3)
    ap.add_argument("--rigid", action="store_true", help="one body rigid: E* = E/(1-nu^2)")
    ap.add_argument("--estar", type=float)
    ap.add_argument("--R", type=float, default=10.0)
    ap.add_argument("--t", type=float, default=0.1)
    ap.add_argument("--tol", type=float, default=0.05)
    ap.add_argument("--reaction", default="press_fz")
    ap.add_argument("--quiet", action="store_true", help="no profile table")
    a = ap.parse_args(argv[1:])

    Es = a.estar or (1.0 / ((1 if a.rigid else 2) * (1 - a.nu ** 2) / a.E))
    f = h5py.File(os.path.join(a.out, "fields.h5"), "r")
    steps = sorted(f["steps"])
    gname = "%06d" % a.step if a.step is not None else steps[-1]
    g = f["steps"][gname]
    step, time = int(g.attrs["step"]), float(g.attrs["time"])
    X = f["mesh/coordinates"][:]
    nid = f["mesh/node_ids"][:]
    x = X + g["displacement"][:]
    if "contact_normal_force" not in g:
        print("not ok - hertz_pair: no node field contact_normal_force in %s step %s" % (a.out, gname))
        return 1
    fn = g["contact_normal_force"][:]

    ids = read_nset(a.mesh, a.slave)
    if len(ids) == 0:
        print("not ok - hertz_pair: no node set '%s' in %s" % (a.slave, a.mesh))
        return 1
    row = {int(i): r for r, i in enumerate(nid)}
    rows = np.array([row[i] for i in ids if i in row])
    if len(rows) != len(ids):
        print("not ok - hertz_pair: %d of the %d nodes of '%s' are not in the run's mesh" % (len(ids) - len(rows), len(ids), a.slave))
        return 1
    # pairs of nodes through the thickness: the same reference (x, z)
    key = {}
    for r in rows:
        key.setdefault((round(X[r, 0], 9), round(X[r, 2], 9)), []).append(r)
    lines = sorted(key.values(), key=lambda rs: X[rs[0], 0])
    if any(len(rs) != 2 for rs in lines):
        print("not ok - hertz_pair: the slave set is not pairs of nodes through the thickness")
        return 1
    sign = 1.0
    if sum(fn[r] for r in rows) < 0:     # a field of compressive forces counted negative
        sign = -1.0
        print("hertz_pair: the slave nodes' normal forces are negative: taken with the opposite sign")
    xc = np.array([0.5 * (x[rs[0]] + x[rs[1]]) for rs in lines])       # current, mid-thickness
    F = sign * np.array([fn[rs[0]] + fn[rs[1]] for rs in lines])       # force of the pair
    split = max(abs(fn[rs[0]] - fn[rs[1]]) for rs in lines) / max(np.abs(F).max(), 1e-300)
    if F.max() <= 0:
        print("not ok - hertz_pair: no slave node of '%s' is pressed at step %d" % (a.slave, step))
        return 1
    seg = np.linalg.norm(np.diff(xc[:, [0, 2]], axis=0), axis=1)
    trib = np.zeros(len(lines))
    trib[:-1] += seg / 2
    trib[1:] += seg / 2
    p = F / (trib * a.t)
    xs = xc[:, 0]

    P = 2 * F.sum() / a.t
    bH, p0H = math.sqrt(4 * P * a.R / (math.pi * Es)), 2 * P / (math.pi * math.sqrt(4 * P * a.R / (math.pi * Es)))
    b, p0 = fit_ellipse(xs, p, trib)
    s = np.sqrt(np.clip(1 - (xs / b) ** 2, 0, None))
    inside = xs < 1.5 * b
    rms = math.sqrt(np.sum((trib * (p - p0 * s) ** 2)[inside]) / np.sum(trib[inside]))
    pressed = np.nonzero(F > 0)[0]
    last = pressed.max() if len(pressed) else 0
    x_in, x_out = xs[last], xs[min(last + 1, len(xs) - 1)]
    gaps = int(np.sum(F[:last + 1] <= 0))
    h = max(seg[max(last - 1, 0)], seg[min(last, len(seg) - 1)])

    print("hertz_pair: %s step %d (time %g), slave set %s: %d node pairs, %d pressed (x up to %.4g; %d open "
          "among them), the two layers' forces equal to %.1e" % (a.out, step, time, a.slave, len(lines), len(pressed),
                                                                 x_in, gaps, split))
    print("hertz_pair: P = %.6g per unit length (2 sum f / t), E* = %.6g, R = %g: Hertz b = %.5g, p0 = %.5g; "
          "fitted b = %.5g, p0 = %.5g" % (P, Es, a.R, bH, p0H, b, p0))
    if not a.quiet:
        print("hertz_pair:      x        l_i          f_i        p_i    p_Hertz    p_fit")
        for k in range(min(len(xs), last + 4)):
            ph = p0H * math.sqrt(max(0.0, 1 - (xs[k] / bH) ** 2))
            print("hertz_pair: %8.4f  %8.4g  %11.5g  %9.4g  %9.4g  %7.4g" % (xs[k], trib[k], F[k], p[k], ph, p0 * s[k]))

    results = []

    def check(ok, msg):
        results.append(ok)
        print(("ok" if ok else "not ok") + " - " + msg)

    # the resultant from contact.csv (a row per pair) and the reaction of the loaded face
    cpath = os.path.join(a.out, "contact.csv")
    Pc = None
    if os.path.exists(cpath):
        rs = [r for r in csv.DictReader(open(cpath)) if int(r["step"]) == step
              and (r.get("tool") == a.pair or r.get("pair") == a.pair)]
        if rs:
            r = rs[-1]
            if r.get("force_normal") not in (None, ""):
                Pc = float(r["force_normal"])
            else:
                Pc = math.sqrt(sum(float(r[c]) ** 2 for c in ("fx", "fy", "fz")))
            Pc = 2 * abs(Pc) / a.t
    if Pc is not None:
        check(abs(Pc - P) <= 5e-3 * abs(P), "hertz_pair: P from contact.csv (pair %s) %.6g, from the slave nodes %.6g (%+.1e; 5e-3)" % (a.pair, Pc, P, Pc / P - 1))
    else:
        print("hertz_pair: no contact.csv row for pair %s at step %d (P from the slave nodes only)" % (a.pair, step))
    hpath = os.path.join(a.out, "history.csv")
    if os.path.exists(hpath):
        hs = [r for r in csv.DictReader(open(hpath)) if int(r["step"]) == step]
        if hs and a.reaction in hs[-1]:
            Pr = 2 * abs(float(hs[-1][a.reaction])) / a.t
            check(abs(Pr - P) <= 5e-3 * abs(P), "hertz_pair: P from the reaction %s %.6g, from the slave nodes %.6g (%+.1e; 5e-3)" % (a.reaction, Pr, P, Pr / P - 1))
    check(abs(b / bH - 1) <= a.tol, "hertz_pair: half-width b = %.5g (fitted), Hertz %.5g at P = %.5g: %+.2f %% (tolerance %g %%)"
          % (b, bH, P, 100 * (b / bH - 1), 100 * a.tol))
    check(abs(p0 / p0H - 1) <= a.tol, "hertz_pair: peak pressure p0 = %.5g (fitted), Hertz %.5g: %+.2f %% (tolerance %g %%)"
          % (p0, p0H, 100 * (p0 / p0H - 1), 100 * a.tol))
    check(rms <= 2 * a.tol * p0, "hertz_pair: pressure profile, RMS deviation from the fitted ellipse over x < 1.5 b: %.3g (%.2f %% of p0; "
          "tolerance %g %%)" % (rms, 100 * rms / p0, 200 * a.tol))
    check(x_in - h <= bH <= x_out + h and gaps == 0, "hertz_pair: contact edge between the nodes x = %.4g (pressed) and %.4g (open), "
          "Hertz b = %.4g (one element, %.3g, either side)%s" % (x_in, x_out, bH, h, "" if gaps == 0 else "; %d open nodes inside" % gaps))
    print("hertz_pair: %d passed, %d failed" % (sum(results), len(results) - sum(results)))
    return 0 if all(results) else 1


if __name__ == "__main__":
    sys.exit(main(sys.argv))
