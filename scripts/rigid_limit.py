#!/usr/bin/env python3
"""The rigid limit of the hemispherical punch benchmark: the punch and the die as elastic bodies
meshed in hexahedra (cases/hemisphere_bodies_{frictionless,friction}.opts, mesh and cases by
scripts/make_rigid_limit_cases.py), in contact with the blank through contact pairs, their
Young's modulus 1e3 to 1e6 times the sheet's (69004 MPa), against the rigid tools
(cases/hemisphere_{frictionless,friction}.opts): the punch force must tend to the rigid tools'
within 0.5 % as the modulus grows. Writes doc/notes/rigid-limit.md.

usage: rigid_limit.py [--bin PATH] [--out DIR] [--factors 1,10,100,1e3,1e4,1e5,1e6]
                      [--cases frictionless,friction] [--np N] [--doc PATH] [--no-facets] [--no-run]

  --bin        the atrito binary (default bin/atrito)
  --out        the runs' output directories (default out/rigid_limit; not committed)
  --factors    the tools' modulus over the sheet's (the check: 1e3 to 1e6; below, the trend)
  --cases      frictionless, friction or both
  --np         MPI ranks per run (default 1; with 1 the binary runs without mpiexec)
  --doc        the page written (default doc/notes/rigid-limit.md; text below its closing
               marker <!-- /rigid_limit --> is kept)
  --no-facets  without the rigid run on the bodies' facets
  --runs       the kinds of runs made: rigid, facets, bodies (default all); the others are read
               from --out
  --no-run     only read the runs already in --out and write the page

Besides the rigid Coons tools of the benchmark, the rigid case is run with the bodies' master
faces as rigid tools of raw plane facets (OUT/tools/{punch,die}_facets.inp, R3D4, written from the
mesh and mirrored to the full ring, since a faceted tool gives no contact beside its open edges;
-tool_<t>_smooth 0): the same surfaces without the pairs and without the tools' elasticity, which
separates the facets' error from the pairs' and the modulus'.

Punch force (full sheet, 4 x the quarter): rigid, contact.csv's punch row, force_full; bodies,
contact.csv's row of the pair pp, 4 fz (the z resultant of the punch on the blank's bottom
nodes; the pair's force/force_full columns sum the nodes' normal forces, not the z resultant),
checked against 4 x history.csv's drive_fz (the reaction of the punch's driven inner surface).
Travel: the rigid punch's, the bodies' 40 x the load parameter. Forces at 10, 20, 30 mm are
interpolated linearly between steps (both cases take the same 15 steps of 2.67 mm unless a step
is cut); the largest difference is taken over the steps of the bodies' run, the rigid curve
interpolated at their travels.
"""
import argparse
import csv
import os
import re
import subprocess
import sys
import time

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.abspath(os.path.join(HERE, ".."))
E_SHEET = 69004.0
TRAVELS = (10.0, 20.0, 30.0, 40.0)
SYM = 4.0


def run(binary, nproc, opts, extra, outdir, log):
    env = dict(os.environ, OMPI_ALLOW_RUN_AS_ROOT="1", OMPI_ALLOW_RUN_AS_ROOT_CONFIRM="1",
               OPENBLAS_NUM_THREADS="1", OMP_NUM_THREADS="1")
    cmd = ([] if nproc == 1 else ["mpiexec", "-n", str(nproc)]) + [binary, "-options_file", opts] + extra + ["-output_dir", outdir]
    os.makedirs(outdir, exist_ok=True)
    load = os.getloadavg()[0]
    t0 = time.time()
    with open(log, "w") as f:
        f.write("# " + " ".join(cmd) + "\n")
        f.flush()
        rc = subprocess.call(cmd, cwd=ROOT, stdout=f, stderr=subprocess.STDOUT, env=env)
    wall = time.time() - t0
    with open(os.path.join(outdir, "run.txt"), "w") as f:
        f.write("rc %d\nwall %.2f\nload %.2f\ndate %s\ncmd %s\n" % (rc, wall, load, time.strftime("%Y-%m-%d %H:%M"), " ".join(cmd)))
    return rc, wall


def rows(path):
    if not os.path.exists(path):
        return []
    with open(path) as f:
        return list(csv.DictReader(f))


def interp(xs, ys, x):
    """linear, None outside [xs[0], xs[-1]]"""
    if not xs or x < xs[0] - 1e-9 or x > xs[-1] + 1e-9:
        return None
    for k in range(1, len(xs)):
        if x <= xs[k] + 1e-9:
            w = (x - xs[k - 1]) / (xs[k] - xs[k - 1])
            return ys[k - 1] + w * (ys[k] - ys[k - 1])
    return ys[-1]


def read_run(outdir, log, rigid):
    """travel and full-sheet punch force per step (from 0), the reaction check, Newton iterations,
    steps, cuts, wall time, the log's last line when the run failed"""
    r = {"travel": [0.0], "force": [0.0], "drive": [0.0], "ok": False}
    c = rows(os.path.join(outdir, "contact.csv"))
    h = rows(os.path.join(outdir, "history.csv"))
    if rigid:
        for row in c:
            if row["tool"] == "punch":
                r["travel"].append(float(row["travel"]))
                r["force"].append(float(row["force_full"]))
    else:
        drive = {row["step"]: SYM * float(row["drive_fz"]) for row in h}
        for row in c:
            if row["tool"] == "pp":
                r["travel"].append(40.0 * float(row["time"]))
                r["force"].append(SYM * float(row["fz"]))
                r["drive"].append(drive.get(row["step"], float("nan")))
    r["its"] = sum(int(row["newton_its"]) for row in h)
    r["steps"] = len(h)
    info = {}
    if os.path.exists(os.path.join(outdir, "run.txt")):
        for line in open(os.path.join(outdir, "run.txt")):
            k, _, v = line.partition(" ")
            info[k] = v.strip()
    r["wall"] = float(info.get("wall", "nan"))
    r["rc"] = int(info.get("rc", "-1"))
    r["load"] = float(info.get("load", "nan"))
    text = open(log).read() if os.path.exists(log) else ""
    m = re.search(r"done: (\d+) steps, (\d+) Newton iterations, (\d+) cuts", text)
    r["cuts"] = int(m.group(3)) if m else None
    r["ok"] = bool(m) and r["rc"] == 0
    lines = [ln for ln in text.splitlines() if ln.strip()]
    r["last"] = lines[-1] if lines else "(no log)"
    return r


def fmt_force(v):
    return "–" if v is None else "%.4f" % (v / 1000.0)


def deck_faces(mesh, elset, nset):
    """the outward quadrangles (C3D8 faces wound out of the solid) of the element set's hexahedra
    whose four nodes lie in the node set, and the nodes' coordinates, from the .inp deck"""
    X, elems, sets, block, cur = {}, [], {}, None, None
    for line in open(mesh):
        s = line.strip()
        if not s or s.startswith("**"):
            continue
        if s.startswith("*"):
            kw = s.upper()
            if kw.startswith("*NODE"):
                block = "node"
            elif kw.startswith("*ELEMENT"):
                block, cur = "elem", re.search(r"ELSET=([^,\s]+)", kw).group(1)
            elif kw.startswith("*NSET"):
                block, cur = "nset", re.search(r"NSET=([^,\s]+)", s, re.I).group(1)
                sets[cur] = set()
            else:
                block = None
            continue
        v = [t for t in s.split(",") if t.strip()]
        if block == "node":
            X[int(v[0])] = tuple(float(t) for t in v[1:4])
        elif block == "elem" and cur == elset.upper():
            elems.append([int(t) for t in v[1:9]])
        elif block == "nset":
            sets[cur].update(int(t) for t in v)
    inside = sets[nset]
    faces = []
    for c in elems:
        for f in ((0, 3, 2, 1), (4, 5, 6, 7), (0, 1, 5, 4), (1, 2, 6, 5), (2, 3, 7, 6), (3, 0, 4, 7)):
            q = [c[a] for a in f]
            if all(n in inside for n in q):
                faces.append(q)
    return X, faces


def write_facet_tool(path, X, faces, what):
    """an Abaqus deck of R3D4 facets, normals out of the body (towards the blank), the quarter
    mirrored to the full ring: a rigid faceted tool has no contact beside its open edges, and
    the blank's nodes on the symmetry planes lie on the quarter's edges there"""
    key, nodes, quads = {}, [], []

    def nid(x):
        k = tuple(int(round(v * 1e8)) for v in x)
        if k not in key:
            nodes.append(x)
            key[k] = len(nodes)
        return key[k]

    for sx, sy in ((1, 1), (-1, 1), (-1, -1), (1, -1)):
        for q in faces:
            ids = [nid((sx * X[n][0] + 0.0, sy * X[n][1] + 0.0, X[n][2])) for n in q]
            quads.append(ids if sx * sy > 0 else ids[::-1])    # a mirror turns the winding
    with open(path, "w") as f:
        f.write("** %s: the bodies' mesh's master faces, mirrored to the full ring, as a rigid tool (scripts/rigid_limit.py)\n*NODE\n" % what)
        for n, x in enumerate(nodes, 1):
            f.write("%d, %.12g, %.12g, %.12g\n" % ((n,) + tuple(x)))
        f.write("*ELEMENT, TYPE=R3D4, ELSET=%s\n" % what.upper())
        for e, q in enumerate(quads, 1):
            f.write("%d, %s\n" % (e, ", ".join(map(str, q))))


def common(a, b):
    """the largest relative difference of a's force to b's at the travels both runs reached in a
    step (within 1e-6 mm), and their number"""
    worst, n = 0.0, 0
    for t, v in zip(a["travel"][1:], a["force"][1:]):
        k = [j for j, t0 in enumerate(b["travel"]) if j and abs(t0 - t) < 1e-6]
        if k and b["force"][k[0]]:
            n += 1
            worst = max(worst, abs(v / b["force"][k[0]] - 1))
    return worst, n


def table(fr, rigid, facets, bodies, factors, fmin):
    out = ["| tools | E (MPa) | %s | largest difference over the steps | steps | Newton its | cuts | wall (s) |"
           % " | ".join("F at %g mm (kN)" % t for t in TRAVELS),
           "|---|---|" + "---|" * len(TRAVELS) + "---|---|---|---|---|"]
    rf = [interp(rigid["travel"], rigid["force"], t) for t in TRAVELS]

    def cuts(r):
        return r["cuts"] if r["ok"] else "stopped at %.2f mm" % r["travel"][-1]

    def row(name, E, r):
        cells = []
        for t, v0 in zip(TRAVELS, rf):
            v = interp(r["travel"], r["force"], t)
            cells.append(fmt_force(v) + ("" if v is None or not v0 else " (%+.3f %%)" % (100 * (v / v0 - 1))))
        worst, at, n = 0.0, None, 0
        for t, v in zip(r["travel"][1:], r["force"][1:]):
            k = [j for j, t0 in enumerate(rigid["travel"]) if abs(t0 - t) < 1e-6 and j]
            if k:              # the steps both runs took (no interpolation of a curved force)
                n += 1
                d = 100 * (v / rigid["force"][k[0]] - 1)
                if abs(d) > abs(worst):
                    worst, at = d, t
        steps_all = n == len(r["travel"]) - 1 and n == len(rigid["travel"]) - 1
        out.append("| %s | %s | %s | %s | %d | %d | %s | %.1f |"
                   % (name, E, " | ".join(cells),
                      ("%+.3f %% at %.2f mm%s" % (worst, at, "" if steps_all else " (%d common steps)" % n)) if at is not None else "–",
                      r["steps"], r["its"], cuts(r), r["wall"]))
        return worst, at, steps_all

    out.append("| rigid, Coons (`hemisphere_%s`) | – | %s | – | %d | %d | %s | %.1f |"
               % (fr, " | ".join(fmt_force(v) for v in rf), rigid["steps"], rigid["its"], cuts(rigid), rigid["wall"]))
    notes, worst = [], {}
    if facets is not None:
        row("rigid, the bodies' facets (raw)", "–", facets)
        if not facets["ok"]:
            notes.append("rigid, the bodies' facets: the run stopped (exit %d) at %.2f mm: `%s`" % (facets["rc"], facets["travel"][-1], facets["last"][:300]))
    for f in factors:
        b = bodies[f]
        worst[f] = row("bodies, %g E" % f, "%.4g" % (f * E_SHEET), b)
        if not b["ok"]:
            notes.append("%g E: the run stopped (exit %d) at %.2f mm: `%s`" % (f, b["rc"], b["travel"][-1], b["last"][:300]))
    # the modulus' effect: each run against the stiffest, and the bodies against the rigid tools of
    # their own facets, at the steps both runs took
    top = max(factors)
    eff = []
    for f in factors:
        d, n = common(bodies[f], bodies[top])
        eff.append("%g E %.1e%s" % (f, d, "" if n == len(bodies[f]["travel"]) - 1 else " (%d common steps)" % n))
    notes.append("The modulus' effect, largest relative difference of a step's force to the %g E run's: %s." % (top, ", ".join(eff)))
    if facets is not None:
        eff = []
        for f in factors:
            d, n = common(bodies[f], facets)
            eff.append("%g E %.2e%s" % (f, d, "" if n == len(bodies[f]["travel"]) - 1 else " (%d common steps)" % n))
        notes.append("Bodies against the rigid tools made of the same facets (the pairs' formulation and the tools' "
                     "elasticity together), largest relative difference over the steps: %s." % ", ".join(eff))
    dr = []
    for f in factors:
        b = bodies[f]
        dr.append("%g E %.0e" % (f, max((abs(p - q) / max(abs(p), 1e-300) for p, q in zip(b["force"][1:], b["drive"][1:])), default=0.0)))
    notes.append("The pair's z resultant against the reaction of the punch's driven surface, largest relative "
                 "difference: %s." % ", ".join(dr))
    req = [f for f in factors if f >= fmin]
    ok = all(bodies[f]["ok"] and worst[f][2] and abs(worst[f][0]) <= 0.5 for f in req) if req else False
    notes.append("Requirement (from %g E: every step within 0.5 %% of the rigid tools, all steps common): %s." %
                 (fmin, "met" if ok else "NOT met"))
    return out, notes


def main(argv):
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--bin", default="bin/atrito")
    ap.add_argument("--out", default="out/rigid_limit")
    ap.add_argument("--factors", default="1,10,100,1e3,1e4,1e5,1e6")
    ap.add_argument("--cases", default="frictionless,friction")
    ap.add_argument("--np", type=int, default=1)
    ap.add_argument("--doc", default="doc/notes/rigid-limit.md")
    ap.add_argument("--no-facets", action="store_true")
    ap.add_argument("--no-run", action="store_true")
    ap.add_argument("--runs", default="rigid,facets,bodies", help="the kinds of runs to (re)run; the others are read")
    a = ap.parse_args(argv)
    binary = os.path.abspath(os.path.join(ROOT, a.bin)) if not os.path.isabs(a.bin) else a.bin
    out = os.path.join(ROOT, a.out)
    factors = [float(v) for v in a.factors.split(",")]
    cases = a.cases.split(",")
    os.makedirs(out, exist_ok=True)
    study = os.path.join(out, "study.txt")
    kinds = set() if a.no_run else set(a.runs.split(","))
    if kinds >= {"rigid", "facets", "bodies"} or (kinds and not os.path.exists(study)):
        try:
            commit = subprocess.run(["git", "rev-parse", "--short", "HEAD"], cwd=ROOT, capture_output=True, text=True).stdout.strip()
        except OSError:
            commit = "?"
        built = time.strftime("%Y-%m-%d %H:%M", time.localtime(os.path.getmtime(binary))) if os.path.exists(binary) else "?"
        with open(study, "w") as f:     # the study's start: load average, commit, the binary's build time
            f.write("%.2f %.2f %.2f\n%s\n%s\n" % (os.getloadavg() + (commit, built)))
    st = open(study).read().split("\n") if os.path.exists(study) else []
    load = [float(v) for v in st[0].split()] if st else [float("nan")] * 3
    commit = st[1] if len(st) > 1 and st[1] else "?"
    built = st[2] if len(st) > 2 and st[2] else "?"
    tools = os.path.join(out, "tools")
    facet_opts = []
    if not a.no_facets:
        os.makedirs(tools, exist_ok=True)
        mesh = os.path.join(ROOT, "cases/meshes/hemisphere_bodies.inp")
        for t, es, ns in (("punch", "PUNCH", "punch_surface"), ("die", "DIE", "die_surface")):
            X, faces = deck_faces(mesh, es, ns)
            path = os.path.join(tools, "%s_facets.inp" % t)
            write_facet_tool(path, X, faces, t)
            facet_opts += ["-tool_%s_file" % t, path, "-tool_%s_smooth" % t, "0"]
    results = {}
    for fr in cases:
        rd, rl = os.path.join(out, "rigid_" + fr), os.path.join(out, "rigid_%s.log" % fr)
        if "rigid" in kinds:
            rc, w = run(binary, a.np, "cases/hemisphere_%s.opts" % fr, [], rd, rl)
            print("rigid %s: exit %d, %.1f s" % (fr, rc, w), flush=True)
        rigid = read_run(rd, rl, True)
        facets = None
        if not a.no_facets:
            fd, fl = os.path.join(out, "facets_" + fr), os.path.join(out, "facets_%s.log" % fr)
            if "facets" in kinds:
                rc, w = run(binary, a.np, "cases/hemisphere_%s.opts" % fr, facet_opts, fd, fl)
                print("rigid facets %s: exit %d, %.1f s" % (fr, rc, w), flush=True)
            facets = read_run(fd, fl, True)
        bodies = {}
        for f in factors:
            tag = "%s_E%g" % (fr, f)
            bd, bl = os.path.join(out, "bodies_" + tag), os.path.join(out, "bodies_%s.log" % tag)
            if "bodies" in kinds:
                E = "%.10g" % (f * E_SHEET)
                rc, w = run(binary, a.np, "cases/hemisphere_bodies_%s.opts" % fr,
                            ["-body_punch_material_E", E, "-body_die_material_E", E], bd, bl)
                print("bodies %s E factor %g: exit %d, %.1f s" % (fr, f, rc, w), flush=True)
            bodies[f] = read_run(bd, bl, False)
        results[fr] = (rigid, facets, bodies)

    loads = [r["load"] for fr in cases for r in [results[fr][0]] + ([results[fr][1]] if results[fr][1] else []) + list(results[fr][2].values())]
    text = ["# The rigid limit of the hemispherical punch benchmark", "",
            "Run on 2026-11-29 by `scripts/rigid_limit.py` (commit %s and the working tree, binary `%s` built %s, "
            "%d rank%s per run, one run at a time); the machine's load average at the start: %.2f, %.2f, %.2f (1, 5, "
            "15 minutes; 1 minute at each run's start: %.2f to %.2f)."
            % (commit, a.bin, built, a.np, "" if a.np == 1 else "s", load[0], load[1], load[2], min(loads), max(loads)), "",
            "The seed benchmark (`cases/hemisphere_frictionless.opts`, `cases/hemisphere_friction.opts`: quarter "
            "blank of 301 hexahedra, rigid Coons punch and die, K_N 1e5 and K_T 5e3 N/mm per node, 15 steps) against "
            "the same blank with the punch and the die as elastic bodies meshed in hexahedra "
            "(`cases/hemisphere_bodies_*.opts`, mesh `cases/meshes/hemisphere_bodies.inp` by "
            "`scripts/make_rigid_limit_cases.py`): the punch a spherical shell (outer radius 50.8, 5 mm, 2 layers, "
            "2400 hexahedra, 48 bilinear facets of 1.66 mm along the meridian), its inner surface driven by 0, 0, 40; "
            "the die fillet a quarter-torus shell 3 mm thick with a 1.5 mm land (1334 hexahedra, 0.50 mm along the "
            "fillet, 3.2 degrees around), all its nodes but the fillet's surface fixed; contact pairs `pp` (the "
            "blank's bottom nodes on the punch's outer faces) and `pd` (its top nodes on the die's fillet) with the "
            "rigid case's penalties per node; tools J2 with a yield stress of 1e12, E a factor times the sheet's "
            "69004 MPa (`-body_punch_material_E`, `-body_die_material_E`). The factors 1 to 100 are below the "
            "check's range (1e3 to 1e6), run for the trend.%s"
            % ("" if a.no_facets else " \"Rigid, the bodies' facets\": the rigid case with the bodies' master "
               "faces as rigid tools of raw plane facets (R3D4, `-tool_<t>_smooth 0`; written to the runs' folder, "
               "mirrored to the full ring: a faceted tool gives no contact beside its open edges, and the blank's "
               "nodes on the symmetry planes lie on the quarter's edges): the same surfaces as the bodies, without "
               "the pairs and without the tools' elasticity."), "",
            "Punch force of the full sheet (4 x the quarter): rigid, the punch's `force_full` in `contact.csv`; "
            "bodies, 4 x the z resultant `fz` of the pair `pp` (the pair's `force`/`force_full` columns sum the "
            "nodes' normal forces, not the z resultant), checked against the reaction of the punch's driven surface "
            "(`drive_fz` of `history.csv`). Forces at 10, 20 and 30 mm are interpolated linearly between the steps of "
            "2.67 mm; in brackets the difference to the rigid Coons tools. Largest difference: over the steps both "
            "runs took (all 15 unless a run cut a step: then the common steps only, their number in brackets; the "
            "interpolated forces at 10, 20, 30 mm then also differ by the interpolation's error where the curve "
            "bends, up to about 2 % below 10 mm). Wall times are "
            "indicative (2-core machine, other jobs running)."]
    for fr in cases:
        rigid, facets, bodies = results[fr]
        t, notes = table(fr, rigid, facets, bodies, factors, 1e3)
        text += ["", "## %s" % ("Frictionless" if fr == "frictionless" else "Friction, mu = 0.15"), ""] + t
        if notes:
            text += [""] + ["* " + n for n in notes]
    path = os.path.join(ROOT, a.doc)
    os.makedirs(os.path.dirname(path), exist_ok=True)
    keep = ""
    if os.path.exists(path):     # a hand-written reading below the marker is kept
        old = open(path).read()
        k = old.find("<!-- /rigid_limit -->")
        if k >= 0:
            keep = old[k + len("<!-- /rigid_limit -->"):]
    with open(path, "w") as f:
        f.write("<!-- rigid_limit: written by scripts/rigid_limit.py -->\n" + "\n".join(text) + "\n\n<!-- /rigid_limit -->" + (keep if keep else "\n"))
    print("wrote " + a.doc)
    for fr in cases:
        rigid, facets, bodies = results[fr]
        t, notes = table(fr, rigid, facets, bodies, factors, 1e3)
        print("\n".join(t + notes))
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
