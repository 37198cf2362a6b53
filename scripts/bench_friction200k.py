#!/usr/bin/python3
"""The 200 000-hexahedra friction case to 40 mm on 2 ranks: time, steps, Newton and Krylov
iterations, the time per Newton iteration and its split, the punch force, for solver variants.

  /usr/bin/python3 scripts/bench_friction200k.py [--variant TAG:OPTIONS ...] [--ranks 2]
        [--cells NC,NR] [--probe 5] [--logdir DIR] [--reuse]
        [--output doc/notes/performance-log.md]

What it does
  1. Before each variant, times the seed case without friction (cases/hemisphere_frictionless.opts
     with the code's default stepping, as its file had it before 2026-11-26: 21 steps, 115 Newton
     iterations; 1 rank, --probe runs, the median): the machine's speed at that time, since the machine is
     shared and its speed varies by a factor of two over a day; compare variants only at the same
     probe time.
  2. Runs cases/hemisphere_friction_disk.opts (whole blank, 4 layers, friction mu 0.15, analytic
     tools) with -blank_core_cells NC -blank_radial_cells NR (default 46,113: 200 192 hexahedra),
     cases/solver_amgsys_fast.opts, no field output, -log_view -memory_view, and the variant's
     OPTIONS, on --ranks ranks, one variant after the other (never two at once: the run is bound by
     the memory's bandwidth). Default variants, at the same increments (-load_grow_its 6: the
     increment grows after the 6-iteration first steps, to the case's -load_dt_max): one sweep of
     hypre's l1-Jacobi smoother (-pc_amgsys_relax_type 18), and the file (one sweep of its
     symmetric hybrid Gauss-Seidel).
  3. Reads from each log the progress lines (steps, Newton and Krylov iterations, most Krylov
     iterations per solve), the summary line, -log_view's KSPSolve, PCSetUp, SNESJacobianEval and
     SNESSolve (its Solve stage; the rest of SNESSolve is the residuals' column), the peak resident
     size; from contact.csv the punch force at the last step.
  4. Writes the section "## The 200 000-hexahedra friction case" of --output, keeping its others:
     a row per variant and, for options run more than once (variants of the same OPTIONS under
     other tags, for example l1, l1b, l1c), their median time and spread.

--logdir keeps the runs (DIR/TAG/: log, history.csv, contact.csv, probe; default a temporary
directory, removed); --reuse reads DIR/TAG/ instead of running (to rewrite the section from runs
made earlier; the date, machine and commit come from the logs' header lines, so the section
renders the same anywhere: tests/test_scripts.sh renders it from the trimmed logs of
tests/data/bench200k). Standard library only.
"""
import argparse
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
CASE = "cases/hemisphere_friction_disk.opts"
SOLVER = "cases/solver_amgsys_fast.opts"
SEED = "cases/hemisphere_frictionless.opts"
# the probe's work as it was before the seed case set its own stepping (2026-11-26): the code's
# default stepping and predictor, so that probes of all dates time the same run
SEED_OLD = ["-load_dt_max", "0.05", "-load_grow_factor", "1.5", "-load_predictor_curvature", "0"]
HEADING = "## The 200 000-hexahedra friction case"
TARGET_S = 1800.0

STEP_RE = re.compile(r"^step\s+(\d+)\s+time\s+([\d.]+)\s+its\s+(\d+)\s+krylov\s+(\d+)\s+\(most\s+(\d+)\)", re.M)
DONE_RE = benchutil.DONE_RE
MEM_RE = benchutil.MEM_RE


def probe(binary, n, work):
    ts = []
    for _ in range(n):
        t0 = time.time()
        r = subprocess.run([binary, "-options_file", SEED] + SEED_OLD + ["-output_interval", "0", "-output_dir", os.path.join(work, "probe_out")],
                           cwd=ROOT, env=benchutil.run_env(), stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
        if r.returncode:
            sys.exit(f"bench_friction200k: the probe ({SEED}) failed with exit code {r.returncode}")
        ts.append(time.time() - t0)
    return statistics.median(ts)


def run(binary, tag, opts, args, logdir):
    d = os.path.join(logdir, tag)
    os.makedirs(d, exist_ok=True)
    if args.probe > 0:
        with open(os.path.join(d, "probe"), "w") as f:
            f.write(f"{probe(binary, args.probe, d):.2f}\n")
        shutil.rmtree(os.path.join(d, "probe_out"), ignore_errors=True)
    nc, nr = args.cells.split(",")
    cmd = ["mpiexec", "-n", str(args.ranks), binary, "-options_file", CASE, "-options_file", SOLVER,
           "-blank_core_cells", nc, "-blank_radial_cells", nr, "-output_interval", "0", "-output_dir", d,
           "-log_view", "-memory_view"] + opts.split()
    print(f"bench_friction200k: {tag}: {' '.join(cmd)}", flush=True)
    with open(os.path.join(d, "log"), "w") as f:
        mi = benchutil.machine_info(ROOT)
        f.write(f"# start {time.strftime('%Y-%m-%d %H:%M %Z')} load {os.getloadavg()[0]:.2f}\n# options {opts}\n"
                f"# machine {mi['cpu']}, {mi['cores']} cores, {mi['mem']}\n"
                f"# commit {mi['commit']}{' (with local changes)' if mi['dirty'] else ''}\n")
        f.flush()
        r = subprocess.run(cmd, cwd=ROOT, env=benchutil.run_env(), stdout=f, stderr=subprocess.STDOUT)
        f.write(f"# end {time.strftime('%Y-%m-%d %H:%M:%S %Z')} rc {r.returncode}\n")


def parse(logdir, tag):
    d = os.path.join(logdir, tag)
    if not os.path.isfile(os.path.join(d, "log")):
        sys.exit(f"bench_friction200k: no log of variant '{tag}' in {logdir}")
    with open(os.path.join(d, "log")) as f:
        text = f.read()
    row = dict(tag=tag, opts="", probe=None, done=None)
    for key in ("options", "start", "machine", "commit"):
        m = re.search(r"^# " + key + r" (.*)$", text, re.M)
        row[key] = m.group(1).strip() if m else ""
    row["opts"] = row["options"]
    try:
        with open(os.path.join(d, "probe")) as f:
            row["probe"] = float(f.read().split()[0])
    except (OSError, ValueError, IndexError):
        pass
    steps = STEP_RE.findall(text)
    row["krylov"] = sum(int(s[3]) for s in steps)
    row["most"] = [int(s[4]) for s in steps]
    m = DONE_RE.search(text)
    if m:
        row["done"] = dict(steps=int(m.group(1)), its=int(m.group(2)), cuts=int(m.group(3)), time=float(m.group(4)))
    for key, ev in (("ksp", "KSPSolve"), ("setup", "PCSetUp"), ("jac", "SNESJacobianEval"), ("solve", "SNESSolve")):
        row[key] = benchutil.log_event_time(text, ev, "Solve")
    m = MEM_RE.search(text)
    row["peak"] = float(m.group(2)) if m else None
    row["force"] = None
    try:
        with open(os.path.join(d, "contact.csv")) as f:
            lines = f.read().splitlines()
        head = lines[0].split(",")
        last = [l.split(",") for l in lines[1:] if l.split(",")[head.index("tool")] == "punch"]
        if last:
            row["force"] = float(last[-1][head.index("force")])
    except (OSError, ValueError, IndexError):
        pass
    return row


def repeats(rows):
    """One line per set of options run more than once to the end: the median time and the spread,
    the figure to compare with the target (a single run's time moves with the machine's load)."""
    groups = {}
    for r in rows:
        if r["done"] is not None:
            groups.setdefault(r["opts"], []).append(r)
    out = []
    for opts, rs in groups.items():
        if len(rs) < 2:
            continue
        ts = sorted(r["done"]["time"] for r in rs)
        med = statistics.median(ts)
        probes = [r["probe"] for r in rs if r["probe"]]
        ptxt = f", probes {min(probes):.2f} to {max(probes):.2f} s" if probes else ""
        same = len(set((r["done"]["its"], r["krylov"]) for r in rs)) == 1
        forces = [r["force"] for r in rs if r["force"] is not None]
        ftxt = ""
        if len(forces) == len(rs):
            spread = (max(forces) - min(forces)) / max(abs(max(forces, key=abs)), 1e-300)
            ftxt = "; the same punch force" if spread == 0 else f"; punch forces within {spread:.1e} of each other"
        flag = "under" if med < TARGET_S else "above"
        out.append(f"- `{opts or '(the file)'}`, {len(rs)} runs ({', '.join(r['tag'] for r in rs)}): median "
                   f"{med:.0f} s ({med / 60:.1f} min, {flag} the 30 minutes), {ts[0]:.0f} to {ts[-1]:.0f} s{ptxt}; "
                   + ("the same Newton and Krylov iterations in each" if same else "their Newton or Krylov iterations differ")
                   + ftxt + ".")
    return [""] + out if out else []


def section(rows):
    # the runs' own dates, machine and commit (from their logs), so that --reuse renders the same
    # section on any machine
    runs = "; ".join(f"{r['tag']} started {r['start'].split(' load')[0] or '?'}, commit {r['commit'] or '?'}" for r in rows)
    machines = sorted(set(r["machine"] or "?" for r in rows))
    out = [HEADING, "", f"Measured by `scripts/bench_friction200k.py` on {' and '.join(machines)}: {runs}.", "",
           f"`{CASE}` with `{SOLVER}` and the variant's options, whole blank, 4 layers, friction "
           "mu 0.15, to 40 mm, no field output, one variant after the other, no other job. The probe: the "
           f"seed case without friction (`{SEED}`, 1 rank, median) just before the variant, the machine's "
           "speed at that time. Target: under 30 minutes on 2 ranks.", "",
           "| variant | options | probe (s) | time (s) | steps | Newton | cuts | Krylov (per Newton) | most per solve: steps 1-3, then | s per Newton: all (Krylov, setup, Jacobian, residuals) | punch force at 40 mm (N) | peak memory, largest rank (GB, -memory_view) |",
           "|---|---|---|---|---|---|---|---|---|---|---|---|"]
    for r in rows:
        d = r["done"]
        if d is None:
            out.append(f"| {r['tag']} | `{r['opts']}` | {r['probe'] or '—'} | did not finish ({len(r['most'])} steps) | | | | | | | | |")
            continue
        its = d["its"]
        split = "—"
        if r["ksp"] is not None and r["setup"] is not None and r["jac"] is not None and r["solve"] is not None:
            # BoomerAMG's set-up is logged outside KSPSolve here (SNESSolve = KSPSolve + PCSetUp +
            # SNESJacobianEval + SNESLineSearch to some 0.1 %); when nested, take it out of KSPSolve
            nested = r["ksp"] + r["setup"] + r["jac"] > r["solve"]
            kry = r["ksp"] - r["setup"] if nested else r["ksp"]
            other = r["solve"] - kry - r["setup"] - r["jac"]
            split = f"{d['time'] / its:.1f} ({kry / its:.1f}, {r['setup'] / its:.1f}, {r['jac'] / its:.1f}, {other / its:.1f})"
        most = r["most"]
        mtxt = ", ".join(str(x) for x in most[:3]) + (f"; {max(most[3:])}" if len(most) > 3 else "")
        flag = "" if d["time"] < TARGET_S else " (above 30 min)"
        force = f"{r['force']:.1f}" if r["force"] is not None else "—"
        peak = f"{r['peak'] / 1e9:.2f}" if r["peak"] is not None else "—"
        out.append(f"| {r['tag']} | `{r['opts'] or '(the file)'}` | {r['probe'] if r['probe'] else '—'} | "
                   f"{d['time']:.0f} ({d['time'] / 60:.1f} min){flag} | {d['steps']} | {its} | {d['cuts']} | "
                   f"{r['krylov']} ({r['krylov'] / its:.1f}) | {mtxt} | {split} | {force} | {peak} |")
    out += repeats(rows)
    out += ["", "The residuals' column is the rest of the Newton solve (residuals, line search, contact pairing); "
            "a probe of — was not taken before the run. "
            "Regenerate with `/usr/bin/python3 scripts/bench_friction200k.py` (some 30 to 40 minutes a variant on this machine)."]
    return "\n".join(out) + "\n"


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--variant", action="append", default=[], help="TAG:OPTIONS (repeatable)")
    ap.add_argument("--ranks", type=int, default=2)
    ap.add_argument("--cells", default="46,113", help="NC,NR: -blank_core_cells, -blank_radial_cells")
    ap.add_argument("--probe", type=int, default=5, help="seed-case runs before each variant (0: none)")
    ap.add_argument("--logdir", default=None)
    ap.add_argument("--reuse", action="store_true")
    ap.add_argument("--output", default=os.path.join(ROOT, "doc", "notes", "performance-log.md"))
    args = ap.parse_args()
    variants = args.variant or ["l1:-load_grow_its 6 -pc_amgsys_relax_type 18", "file:-load_grow_its 6"]
    parsed = []
    for v in variants:
        if ":" not in v or not v.split(":", 1)[0]:
            sys.exit(f"bench_friction200k: --variant '{v}' is not TAG:OPTIONS")
        parsed.append(tuple(v.split(":", 1)))
    if not re.fullmatch(r"\d+,\d+", args.cells):
        sys.exit(f"bench_friction200k: --cells '{args.cells}' is not NC,NR")
    if args.reuse and not args.logdir:
        sys.exit("bench_friction200k: --reuse needs --logdir")
    logdir = args.logdir or tempfile.mkdtemp(prefix="bench200k_")
    binary = None
    try:
        if not args.reuse:
            binary = benchutil.build_and_snapshot(ROOT, logdir, "bench_friction200k")
            for tag, opts in parsed:
                run(binary, tag, opts, args, logdir)
        rows = [parse(logdir, tag) for tag, _ in parsed]
        benchutil.write_doc_section(args.output, HEADING, section(rows))
        print(f"bench_friction200k: wrote '{HEADING}' in {args.output}")
    finally:
        if binary:
            shutil.rmtree(os.path.dirname(binary), ignore_errors=True)
        if not args.logdir:
            shutil.rmtree(logdir, ignore_errors=True)


if __name__ == "__main__":
    main()
