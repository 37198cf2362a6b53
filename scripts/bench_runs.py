#!/usr/bin/python3
"""Run times of the hemispherical punch benchmark against the speed targets.

  /usr/bin/python3 scripts/bench_runs.py [--reps N] [--xfine] [--efficiency] [--eff-reps N]
                                         [--eff-orderings nd,mumps]
                                         [--output doc/notes/performance-log.md]

What it does
  1. Runs the two main seed-mesh cases (cases/hemisphere_frictionless.opts and
     cases/hemisphere_friction.opts: 301 hexahedra, Coons tools, 40 mm of punch travel) --reps
     times each (default 5, interleaved) on one rank. Target: under 5 s each.
  2. --xfine: the extra-fine case with friction (cases/hemisphere_friction_xfine.opts, 20400
     hexahedra, Coons tools, 40 mm) once on 2 ranks. Target: under 10 minutes.
  3. --efficiency: the same case shortened to 8 mm of travel in 4 steps of 2 mm (the first steps
     of the full run), --eff-reps times (default 3) on 1 and on 2 ranks (interleaved): the parallel efficiency at 2 ranks
     (target 80 %), overall and per event. And the machine's own limit: two independent 1-rank runs
     of that case started together (the work of 2 ranks without any communication or
     load imbalance): the ratio of the 1-rank time alone to their time is the efficiency no code
     can beat on this machine (shared memory bandwidth, caches, virtual cores).
     --eff-orderings nd,mumps: the efficiency runs with each LU ordering (-lu_ordering), interleaved.
  4. Every run: -output_interval 0 (no field output) and -log_view; the wall time is the program's
     own (the "done:" line: all load steps, without start-up); the other load on the machine during
     the run is measured from /proc/stat.
  5. Writes the section "## Benchmark run times" of the output file, keeping its other sections.

Standard library only; OPENBLAS_NUM_THREADS=1 and the Open MPI run-as-root variables set.
"""
import argparse
import concurrent.futures
import os
import re
import shutil
import statistics
import subprocess
import sys
import tempfile
import time

import benchutil

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
HEADING = "## Benchmark run times"
SEED = ["hemisphere_frictionless", "hemisphere_friction"]
XFINE = "hemisphere_friction_xfine"

DONE_RE = benchutil.DONE_RE
MESH_RE = benchutil.MESH_RE
EV_RE = {e: re.compile(r"^" + e + r"\s+(\d+)\s+[\d.]+\s+([\d.eE+-]+)", re.M)
         for e in ("AtritoResidual", "AtritoJacobian", "AtritoContact", "MatLUFactorNum", "AtritoLUFactor", "SNESSolve")}
LU = "LU factorisation"  # MatLUFactorNum (-lu_ordering mumps) or AtritoLUFactor (-lu_ordering nd)


def log(msg):
    print(f"[bench_runs {time.strftime('%H:%M:%S')}] {msg}", file=sys.stderr, flush=True)


SHORT = ["-tool_punch_motion", "0,0,8", "-load_steps", "4", "-load_dt_max", "0.25"]


def run(binary, case, ranks, outdir, timeout, extra=()):
    cmd = [] if ranks == 1 else ["mpiexec", "--oversubscribe", "-n", str(ranks)]
    cmd += [binary, "-options_file", os.path.join("cases", case + ".opts"), "-output_dir", outdir, "-output_interval", "0", "-log_view"] + list(extra)
    b0, c0, s0, t0 = benchutil.cpu_busy_seconds(), benchutil.children_cpu(), benchutil.cpu_steal_seconds(), time.monotonic()
    try:
        r = subprocess.run(cmd, cwd=ROOT, env=benchutil.run_env(), capture_output=True, text=True, timeout=timeout)
        out, rc = r.stdout + r.stderr, r.returncode
    except subprocess.TimeoutExpired as e:
        out, rc = (e.stdout or b"").decode() if isinstance(e.stdout, bytes) else (e.stdout or ""), "timeout"
    wall = time.monotonic() - t0
    b1, c1 = benchutil.cpu_busy_seconds(), benchutil.children_cpu()
    other = max(0.0, ((b1 - b0) - (c1 - c0)) / wall) if b0 is not None and wall > 0 else None
    s1 = benchutil.cpu_steal_seconds()
    steal = (s1 - s0) / wall if s0 is not None and s1 is not None and wall > 0 else None
    d, me = DONE_RE.search(out), MESH_RE.search(out)
    if rc != 0 or not d:
        tail = " / ".join(out.strip().splitlines()[-3:])
        return dict(case=case, ranks=ranks, error=f"exit {rc}: {tail}", wall=wall, other=other, steal=steal)
    ev = {e: float(m.group(2)) for e, rx in EV_RE.items() if (m := rx.search(out))}
    if "MatLUFactorNum" in ev or "AtritoLUFactor" in ev:
        ev[LU] = ev.get("MatLUFactorNum", 0.0) + ev.get("AtritoLUFactor", 0.0)
    return dict(case=case, ranks=ranks, cells=int(me.group(2)) if me else None, steps=int(d.group(1)), its=int(d.group(2)),
                cuts=int(d.group(3)), time=float(d.group(4)), wall=wall, other=other, steal=steal, events=ev)


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--reps", type=int, default=5, help="runs of each seed case (default 5)")
    ap.add_argument("--xfine", action="store_true", help="also the 20400-hexahedra friction case on 2 ranks")
    ap.add_argument("--efficiency", action="store_true", help="the 20400-hexahedra case to 8 mm on 1 and 2 ranks")
    ap.add_argument("--eff-reps", type=int, default=3, help="repetitions of the efficiency runs (default 3)")
    ap.add_argument("--eff-orderings", default="nd", help="LU orderings of the efficiency runs, comma-separated: nd, mumps "
                    "(default nd; the first one also gets the machine-limit pairs)")
    ap.add_argument("--output", default=os.path.join(ROOT, "doc", "notes", "performance-log.md"))
    a = ap.parse_args()
    if a.reps < 1 or a.eff_reps < 1:
        sys.exit("bench_runs: --reps and --eff-reps must be >= 1")
    orderings = a.eff_orderings.split(",")
    if not orderings or any(o not in ("nd", "mumps") for o in orderings) or len(set(orderings)) != len(orderings):
        sys.exit(f"bench_runs: --eff-orderings {a.eff_orderings!r}: a list of distinct values among nd, mumps")
    work = tempfile.mkdtemp(prefix="bench_runs_")
    recs = []
    try:
        binary = benchutil.build_and_snapshot(ROOT, work, "bench_runs", log)
        plan = [(c, 1, 600, False, None) for _ in range(a.reps) for c in SEED]
        if a.xfine:
            plan.append((XFINE, 2, 3600, False, None))
        if a.efficiency:  # interleaved: every ordering and rank count once per repetition
            plan += [(XFINE, p, 3600, True, o) for _ in range(a.eff_reps) for o in orderings
                     for p in ((1, 2, "pair") if o == orderings[0] else (1, 2))]
        for i, (case, ranks, timeout, short, order) in enumerate(plan):
            extra = (SHORT if short else []) + (["-lu_ordering", order] if order else [])
            if ranks == "pair":  # two 1-rank runs at once
                with concurrent.futures.ThreadPoolExecutor(2) as ex:
                    both = list(ex.map(lambda k: run(binary, case, 1, os.path.join(work, f"run{i}_{k}"), timeout, extra), (0, 1)))
                bad = [r for r in both if "error" in r]
                rec = bad[0] if bad else dict(both[0], time=sum(r["time"] for r in both) / 2)
                rec["ranks"] = "pair"
            else:
                rec = run(binary, case, ranks, os.path.join(work, f"run{i}"), timeout, extra)
            rec["short"], rec["order"] = short, order or "nd"
            if "error" in rec:
                log(f"{case} np={ranks} {' '.join(extra)}: FAILED ({rec['error']})")
            else:
                log(f"{case} np={ranks} {' '.join(extra)}: {rec['time']:.2f} s, {rec['steps']} steps, {rec['its']} Newton its, other load {rec['other'] or 0:.2f}, stolen {rec['steal'] or 0:.2f}")
            recs.append(rec)
    finally:
        shutil.rmtree(work, ignore_errors=True)

    L = [HEADING, "",
         benchutil.measured_by("bench_runs.py", ROOT) + " Full runs to 40 mm of punch travel, "
         "no field output; time = the program's own (all load steps, after start-up); median [min – max] of the runs.",
         "",
         "| case | hexahedra | ranks | runs | steps | Newton its | cuts | time s | target | met | other load (cores, max) |",
         "|---|---|---|---|---|---|---|---|---|---|---|"]
    groups = {}
    for r in recs:
        if not r["short"]:
            groups.setdefault((r["case"], r["ranks"]), []).append(r)
    med = {}
    for (case, ranks), rs in groups.items():
        ok = [r for r in rs if "error" not in r]
        target = 5.0 if case in SEED else (600.0 if ranks == 2 else None)
        tgt = f"< {target:g} s" if target else "–"
        if not ok:
            L.append(f"| {case} | – | {ranks} | {len(rs)} | failed: {rs[0]['error'][:100]} | | | | {tgt} | no | |")
            continue
        t = [r["time"] for r in ok]
        m = statistics.median(t)
        med[(case, ranks)] = (m, ok[0])
        met = "–" if target is None else ("yes" if m < target and len(ok) == len(rs) else "no")
        L.append(f"| {case} | {ok[0]['cells']} | {ranks} | {len(ok)}/{len(rs)} | {ok[0]['steps']} | {ok[0]['its']} | {ok[0]['cuts']} | "
                 f"{m:.2f} [{min(t):.2f} – {max(t):.2f}] | {tgt} | {met} | {max((r['other'] or 0) for r in rs):.2f} |")
    L += ["", "The seed paper reports 226 (frictionless) and 248 (friction) Newton iterations for its seed-size mesh."]
    for o in orderings if a.efficiency else []:
        sh = {p: [r for r in recs if r["short"] and r["order"] == o and r["ranks"] == p and "error" not in r] for p in (1, 2, "pair")}
        if not (sh[1] and sh[2]):
            continue
        t1, t2 = statistics.median(r["time"] for r in sh[1]), statistics.median(r["time"] for r in sh[2])
        eff = t1 / (2 * t2)
        r1, r2 = [r["time"] for r in sh[1]], [r["time"] for r in sh[2]]
        what = {"nd": "LU with the METIS nested-dissection ordering (`-lu_ordering nd`, the default)",
                "mumps": "LU with MUMPS's own ordering through PETSc (`-lu_ordering mumps`, PORD)"}[o]
        L += ["", f"Parallel efficiency at 2 ranks, {what}: `{XFINE}` ({sh[1][0]['cells']} hexahedra) to 8 mm of travel in 4 steps "
              f"of 2 mm, {len(sh[1])} and {len(sh[2])} runs (interleaved{' with the other ordering' if len(orderings) > 1 else ''}): 1 rank {t1:.1f} s [{min(r1):.1f} – {max(r1):.1f}], "
              f"2 ranks {t2:.1f} s [{min(r2):.1f} – {max(r2):.1f}] (medians [min – max]), speedup {t1 / t2:.2f}, efficiency "
              f"{100 * eff:.0f} % (target 80 %: {'met' if eff >= 0.8 else 'not met'}; from the fastest runs "
              f"{100 * min(r1) / (2 * min(r2)):.0f} %); Newton iterations {sh[1][0]['its']} and {sh[2][0]['its']}; other load at most "
              f"{max((r['other'] or 0) for r in sh[1] + sh[2]):.2f} cores, time stolen by the hypervisor at most "
              f"{max((r['steal'] or 0) for r in sh[1] + sh[2]):.2f} cores."]
        rows = []
        for e in ("AtritoJacobian", "AtritoResidual", "AtritoContact", LU, "SNESSolve"):
            e1 = [r["events"][e] for r in sh[1] if e in r["events"]]
            e2 = [r["events"][e] for r in sh[2] if e in r["events"]]
            if e1 and e2 and statistics.median(e2) > 0:
                m1, m2 = statistics.median(e1), statistics.median(e2)
                rows.append(f"{e} {100 * m1 / (2 * m2):.0f} % ({100 * m1 / t1:.0f} % of the 1-rank time, {m1:.1f} s)")
        if rows:
            L.append("Per event (efficiency; share of the 1-rank run): " + "; ".join(rows) + ".")
        if sh["pair"]:
            tp = statistics.median(r["time"] for r in sh["pair"])
            L += ["", f"The machine's limit: two independent 1-rank runs of the same case started together took {tp:.1f} s "
                  f"each (median of {len(sh['pair'])} pairs) against {t1:.1f} s alone, so two processes on this machine "
                  f"run at {100 * t1 / tp:.0f} % of the speed of one: no code reaches more than that efficiency at 2 ranks "
                  f"here. The 2-rank run reaches {100 * eff / (t1 / tp):.0f} % of that limit."]
    L.append("")
    benchutil.write_doc_section(a.output, HEADING, "\n".join(L) + "\n")
    log(f"wrote {HEADING!r} to {a.output}")


if __name__ == "__main__":
    main()
