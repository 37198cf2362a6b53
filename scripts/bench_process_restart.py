#!/usr/bin/env python3
"""Restart of a large forming process in the middle of a stage on another number of ranks: the
mild steel square cup of scripts/bench_process.py (box mesh of the quarter blank, N x N x L
hexahedra, cases/solver_process.opts) run uninterrupted for K steps on R1 ranks with a checkpoint
every C steps, then continued from the checkpoint of step C (inside the close stage when C < 4) on
R2 ranks to step K in a copy of its output folder. Reports the steps' Newton and Krylov
iterations of both runs and the largest difference of the history's and contact.csv's values at
step K, relative to each column's largest magnitude; the iterative solver stops at a relative
residual of 1e-3 (the last solve of a Newton iteration at 0.05 of the Newton tolerance, 1e-6 of
the forces), so the two agree within that, not bit for bit. Writes the section "## A forming
process at scale: restart on another number of ranks (measured)" of doc/notes/performance-log.md.

usage: scripts/bench_process_restart.py [--n 158] [--layers 4] [--steps 3] [--checkpoint 2]
                                        [--ranks 2] [--restart-ranks 1] [--logdir DIR] [--reuse]"""
import argparse
import csv
import os
import re
import shutil
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(HERE)
sys.path.insert(0, HERE)
import benchutil  # noqa: E402
import bench_process  # noqa: E402

HEADING = "## A forming process at scale: restart on another number of ranks (measured)"


def command(binary, n, l, k, ranks, outdir, extra):
    return ([] if ranks == 1 else ["mpiexec", "--oversubscribe", "-n", str(ranks)]) + [binary, "-options_file", bench_process.CASE] + bench_process.BOX + [
        "-box_cells", f"{n},{n},{l}", "-options_file", bench_process.SOLVER, "-output_interval", "0", "-load_max_steps", str(k),
        "-output_dir", outdir] + extra


def rows(path):
    with open(path) as f:
        r = list(csv.reader(f))
    return r[0], r[1:]


def largest_difference(a, b, step):
    """largest |a - b| at step `step` over the numeric columns, relative to the column's largest
    magnitude in a (over all its rows); the column"""
    ha, ra = rows(a)
    hb, rb = rows(b)
    if ha != hb:
        sys.exit(f"bench_process_restart: {a} and {b} have other columns")
    worst, col = 0.0, None
    skip = {"step", "time", "newton_its", "residual_initial", "residual_final", "krylov_its", "stage", "tool"}
    for i, h in enumerate(ha):
        if h in skip:
            continue
        try:
            scale = max(abs(float(r[i])) for r in ra)
        except ValueError:
            continue
        if scale < 1e-9:
            continue
        ka = [r for r in ra if r[0] == str(step)]
        kb = [r for r in rb if r[0] == str(step)]
        if not ka or len(ka) != len(kb):
            sys.exit(f"bench_process_restart: step {step} missing or different rows in {a} / {b}")
        for x, y in zip(ka, kb):
            d = abs(float(x[i]) - float(y[i])) / scale
            if d > worst:
                worst, col = d, h
    return worst, col


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--n", type=int, default=158)
    ap.add_argument("--layers", type=int, default=4)
    ap.add_argument("--steps", type=int, default=3)
    ap.add_argument("--checkpoint", type=int, default=2)
    ap.add_argument("--ranks", type=int, default=2)
    ap.add_argument("--restart-ranks", type=int, default=1)
    ap.add_argument("--logdir", default=os.path.join(ROOT, "build", "bench_process_restart"))
    ap.add_argument("--reuse", action="store_true", help="read the logs and outputs in --logdir instead of running")
    ap.add_argument("--timeout", type=float, default=7200.0)
    ap.add_argument("--output", default=os.path.join(ROOT, "doc", "notes", "performance-log.md"))
    a = ap.parse_args()
    if not 1 <= a.checkpoint < a.steps:
        sys.exit("bench_process_restart: --checkpoint must lie in [1, --steps)")
    os.makedirs(a.logdir, exist_ok=True)
    full, cont = os.path.join(a.logdir, "full"), os.path.join(a.logdir, "restarted")
    lfull, lcont = os.path.join(a.logdir, "full.log"), os.path.join(a.logdir, "restarted.log")
    if not a.reuse:
        binary = benchutil.build_and_snapshot(ROOT, a.logdir, "bench_process_restart")
        shutil.rmtree(full, ignore_errors=True)
        shutil.rmtree(cont, ignore_errors=True)
        bench_process.execute(command(binary, a.n, a.layers, a.steps, a.ranks, full, ["-checkpoint_interval", str(a.checkpoint)]), lfull, a.timeout)
        # the checkpoint of step `checkpoint`: the run writes one every `checkpoint` steps, the last
        # one at the largest multiple below `steps`; a copy of the folder is continued from it
        last = (a.steps - 1) // a.checkpoint * a.checkpoint
        if last != a.checkpoint:
            sys.exit("bench_process_restart: --steps must be at most 2 x --checkpoint (one checkpoint)")
        shutil.copytree(full, cont)
        ck = os.path.join(a.logdir, "checkpoint.h5")
        shutil.copy(os.path.join(full, "checkpoint.h5"), ck)
        bench_process.execute(command(binary, a.n, a.layers, a.steps, a.restart_ranks, cont, ["-restart", ck]), lcont, a.timeout)
    pf = bench_process.parse(lfull, (a.n, a.layers, a.steps, a.ranks))
    text = open(lcont).read()
    if "restart from" not in text:
        sys.exit(f"bench_process_restart: {lcont}: the run did not restart")
    dh, ch = largest_difference(os.path.join(full, "history.csv"), os.path.join(cont, "history.csv"), a.steps)
    dc, cc = largest_difference(os.path.join(full, "contact.csv"), os.path.join(cont, "contact.csv"), a.steps)
    st = re.findall(r"^step +(\d+) +time ([\d.]+) +its +(\d+) +krylov (\d+) \(most (\d+)\).*elapsed ([\d.]+) s.*stage (\w+)", text, re.M)
    fst = re.findall(r"^step +(\d+) +time ([\d.]+) +its +(\d+) +krylov (\d+) \(most (\d+)\).*stage (\w+)", open(lfull).read(), re.M)
    cells = a.n * a.n * a.layers
    lines = [HEADING, "", benchutil.measured_by("bench_process_restart.py", ROOT), "",
             f"The square cup of the section above on {cells:,} hexahedra ({a.n} x {a.n} x {a.layers}), `{bench_process.SOLVER}`: run for {a.steps} steps on",
             f"{a.ranks} rank(s) with a checkpoint every {a.checkpoint} steps, then continued from the checkpoint of step {a.checkpoint} on {a.restart_ranks}",
             f"rank(s) (`-restart`, in a copy of the output folder) to step {a.steps}. Load at the start of the runs: {pf['load']:.2f}.", "",
             "| run | ranks | steps (time, stage) | Newton/Krylov its per step | most Krylov per Newton it |",
             "|---|---|---|---|---|",
             f"| uninterrupted | {a.ranks} | {', '.join(f'{s[0]} ({float(s[1]):g}, {s[5]})' for s in fst)} | {' '.join(f'{s[2]}/{s[3]}' for s in fst)} | {max(int(s[4]) for s in fst)} |",
             f"| restarted at step {a.checkpoint} | {a.restart_ranks} | {', '.join(f'{s[0]} ({float(s[1]):g}, {s[6]})' for s in st)} | {' '.join(f'{s[2]}/{s[3]}' for s in st)} | {max(int(s[4]) for s in st)} |",
             "",
             f"At step {a.steps}: the history's values differ by at most {dh:.1e} of their column's largest ({ch}), contact.csv's by",
             f"at most {dc:.1e} ({cc}); the solver's tolerances (relative residual 1e-3, Newton 1e-6 of the forces) set that level."]
    body = "\n".join(lines) + "\n"
    print(body)
    benchutil.write_doc_section(a.output, HEADING, body)


if __name__ == "__main__":
    main()
