#!/usr/bin/env python3
"""A forming process on a large mesh with the iterative solver for processes: the NUMISHEET'93
square cup in mild steel (cases/numisheet93_cup_coarse.opts: holder under 19.6 kN driven by
force, punch stroke 40) on a box mesh of the quarter blank, N x N hexahedra in the plane and L
through the thickness, with cases/solver_process.opts (BiCGStab, -pc_type amgsys bordered by the
holder's unknowns, the sheet's coarse space), through its first K steps (close, then the start of
the draw). Reports per point: hexahedra, ranks, steps, Newton and Krylov iterations (per step, the
most in one Newton iteration), seconds per Newton iteration, the peak resident memory summed over
the ranks (PETSc's -memory_view) and per 100 000 hexahedra, the machine's load at the start.
Writes the section "## A forming process at scale (measured)" of doc/notes/performance-log.md
(the measurements that doc/performance.md quotes).

usage: scripts/bench_process.py [--point N,L,K,RANKS ...] [--logdir DIR] [--reuse] [--output FILE]"""
import argparse
import os
import re
import subprocess
import sys
import time

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(HERE)
sys.path.insert(0, HERE)
import benchutil  # noqa: E402

HEADING = "## A forming process at scale (measured)"
CASE = "cases/numisheet93_cup_coarse.opts"
SOLVER = "cases/solver_process.opts"
BOX = ["-mesh_type", "box", "-box_upper", "75,75,0.78", "-bc_symx_set", "xmin", "-bc_symy_set", "ymin",
       "-tool_punch_contact_set", "zmax", "-tool_die_contact_set", "zmin", "-tool_holder_contact_set", "zmax"]


def tag(p):
    return "n%d_l%d_k%d_np%d" % p


def run(binary, p, logdir, timeout):
    n, l, k, ranks = p
    cmd = ([] if ranks == 1 else ["mpiexec", "--oversubscribe", "-n", str(ranks)]) + [binary, "-options_file", CASE] + BOX + [
        "-box_cells", f"{n},{n},{l}", "-options_file", SOLVER, "-output_interval", "0", "-load_max_steps", str(k),
        "-memory_view", "-output_dir", os.path.join(logdir, "out_" + tag(p))]
    path = os.path.join(logdir, tag(p) + ".log")
    execute(cmd, path, timeout)
    return path


def execute(cmd, path, timeout):
    """run cmd (niced) with its output in path, headed by the command, the load and the commit"""
    load = os.getloadavg()[0]
    mi = benchutil.machine_info(ROOT)
    t0 = time.monotonic()
    with open(path, "w") as f:
        f.write("# " + " ".join(cmd) + "\n# load %.2f\n# commit %s%s\n" % (load, mi["commit"], " (with local changes)" if mi["dirty"] else ""))
        f.flush()
        try:
            subprocess.run(["nice"] + cmd, cwd=ROOT, env=benchutil.run_env(), stdout=f, stderr=subprocess.STDOUT, timeout=timeout)
        except subprocess.TimeoutExpired:
            f.write("# timeout\n")
    with open(path, "a") as f:
        f.write("# wall %.1f s\n" % (time.monotonic() - t0))


def parse(path, p):
    n, l, k, ranks = p
    out = open(path).read()
    steps = re.findall(r"^step +\d+ +time [\d.]+ +its +(\d+) +krylov (\d+) \(most (\d+)\).*elapsed ([\d.]+) s.*stage (\w+)", out, re.M)
    cuts = len(re.findall(r"retrying with increment", out))
    mem = re.search(r"Maximum \(over computational time\) process memory: +total ([\d.e+]+)", out)
    load = re.search(r"^# load ([\d.]+)", out, re.M)
    if not steps:
        sys.exit(f"bench_process: {path}: no step line")
    its = [int(s[0]) for s in steps]
    kry = [int(s[1]) for s in steps]
    most = max(int(s[2]) for s in steps)
    wall = float(steps[-1][3])
    cells = n * n * l
    gib = float(mem.group(1)) / 2**30 if mem else None
    ended = time.strftime("%Y-%m-%d %H:%M UTC", time.gmtime(os.path.getmtime(path)))
    commit = re.search(r"^# commit (.+)$", out, re.M)
    return dict(ended=ended, commit=commit.group(1) if commit else "unknown", cells=cells, ranks=ranks, steps=len(steps), stages=sorted(set(s[4] for s in steps)), its=sum(its), kry=sum(kry), most=most,
                cuts=cuts, per_it=wall / max(sum(its), 1), wall=wall, gib=gib, per100k=gib / cells * 1e5 if gib else None,
                load=float(load.group(1)) if load else None, per_step=" ".join(f"{a}/{b}" for a, b in zip(its, kry)))


def section(rows):
    lines = [HEADING, "", benchutil.measured_by("bench_process.py", ROOT), "",
             f"The mild steel square cup (`{CASE}`: holder driven by its 19.6 kN force, the punch 40 mm) on a box mesh of",
             "the quarter blank, N x N hexahedra in the plane and L through the thickness, with",
             f"`{SOLVER}` (BiCGStab, `-pc_type amgsys` bordered by the holder's unknowns, the sheet's coarse",
             "space), through its first steps (`-load_max_steps`). Newton/Krylov iterations per step in the last column.",
             "The runs (hexahedra: end, commit): " + "; ".join(f"{r['cells']:,}: {r['ended']}, {r['commit']}" for r in rows) + ".", "",
             "| hexahedra | ranks | load at start | steps | stages | Newton its | cuts | Krylov its | most per Newton it | s per Newton it | peak GiB | GiB per 100 000 | its/Krylov per step |",
             "|---|---|---|---|---|---|---|---|---|---|---|---|---|"]
    for r in rows:
        lines.append(f"| {r['cells']:,} | {r['ranks']} | {r['load']:.2f} | {r['steps']} | {', '.join(r['stages'])} | {r['its']} | {r['cuts']} | {r['kry']} | {r['most']} | "
                     f"{r['per_it']:.2f} | {r['gib']:.2f} | {r['per100k']:.2f} | {r['per_step']} |" if r['gib'] else
                     f"| {r['cells']:,} | {r['ranks']} | {r['load']:.2f} | {r['steps']} | {', '.join(r['stages'])} | {r['its']} | {r['cuts']} | {r['kry']} | {r['most']} | "
                     f"{r['per_it']:.2f} | – | – | {r['per_step']} |")
    return "\n".join(lines) + "\n"


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--point", action="append", default=[], help="N,L,K,RANKS (repeatable; default 40,2,6,1 and 158,4,6,2)")
    ap.add_argument("--logdir", default=os.path.join(ROOT, "build", "bench_process"))
    ap.add_argument("--reuse", action="store_true", help="read the logs in --logdir instead of running")
    ap.add_argument("--timeout", type=float, default=7200.0)
    ap.add_argument("--output", default=os.path.join(ROOT, "doc", "notes", "performance-log.md"))
    a = ap.parse_args()
    pts = [tuple(int(x) for x in s.split(",")) for s in (a.point or ["40,2,6,1", "158,4,6,2"])]
    os.makedirs(a.logdir, exist_ok=True)
    binary = None if a.reuse else benchutil.build_and_snapshot(ROOT, a.logdir, "bench_process")
    rows = []
    for p in pts:
        path = os.path.join(a.logdir, tag(p) + ".log") if a.reuse else run(binary, p, a.logdir, a.timeout)
        rows.append(parse(path, p))
        print(rows[-1], flush=True)
    benchutil.write_doc_section(a.output, HEADING, section(rows))


if __name__ == "__main__":
    main()
