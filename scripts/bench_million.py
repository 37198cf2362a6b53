#!/usr/bin/python3
"""One million hexahedra: memory, Krylov iterations and time per Newton iteration of large sheets.

  /usr/bin/python3 scripts/bench_million.py [--point NC,NR,STEPS,TRAVEL,RANKS ...] [--timeout S]
                                            [--logdir DIR] [--reuse] [--output doc/performance.md]

What it does
  1. Runs the friction benchmark on the whole 4-layer blank (cases/hemisphere_friction_disk.opts:
     analytic tools, contact penalties per unit area; -blank_core_cells NC -blank_radial_cells NR,
     4 (NC^2 + 2 NC NR) quadrilaterals per layer) with the iterative solver of
     cases/solver_amg_sheet.opts, no field output, -memory_view -memory_phases -log_view, for each
     --point: punch travel TRAVEL mm in STEPS equal steps (the first contact and the onset of
     plasticity are in the first millimetre) on RANKS ranks. Default points: 100 352 hexahedra on
     1 rank, 250 512 and 1 010 224 on 2 ranks, one step of 1 mm each.
  2. Reads from each log: the peak resident set size (PETSc's "Maximum (over computational time)
     process memory", summed over the ranks), the memory after the setup phases, the Newton and
     Krylov iterations of every step (the progress line's "krylov N (most M)"), the solve time, and
     from -log_view the time in assembly (SNESFunctionEval + SNESJacobianEval), preconditioner
     setup (PCSetUp) and Krylov iterations (KSPSolve less PCSetUp).
  3. Writes the section "## One million hexahedra" of the output file, keeping its other sections.

--logdir keeps the logs (default: a temporary directory, removed); --reuse reads the logs already
in --logdir instead of running (to rewrite the section from runs made earlier). A run past
--timeout (default 3000 s) is reported with the steps it completed and no log_view split.
Standard library only; OPENBLAS_NUM_THREADS=1 and the Open MPI run-as-root variables set.
"""
import argparse
import os
import re
import shutil
import subprocess
import sys
import tempfile
import time

import benchutil

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
CASE = "cases/hemisphere_friction_disk.opts"
SOLVER = "cases/solver_amg_sheet.opts"
HEADING = "## One million hexahedra"
LAYERS = 4
# (core cells, radial cells, steps, travel mm, ranks): hexahedra = 4 (nc^2 + 2 nc nr) per layer, 4 layers
POINTS = [(32, 82, 1, 1.0, 1), (51, 128, 1, 1.0, 2), (103, 255, 1, 1.0, 2)]
TARGET_GIB = 0.8   # peak resident size per 100 000 hexahedra
TARGET_KRYLOV = 50  # Krylov iterations per Newton iteration

MEM_RE = re.compile(r"Maximum \(over computational time\) process memory:\s+total\s+([\d.eE+-]+)\s+max\s+([\d.eE+-]+)")
MESH_RE = re.compile(r"^mesh:\s+(\d+) vertices,\s+(\d+) hexahedra", re.M)
DONE_RE = re.compile(r"^done: (\d+) steps, (\d+) Newton iterations, (\d+) cuts, ([\d.]+) s", re.M)
STEP_RE = re.compile(r"^step\s+(\d+)\s+time\s+([\d.]+)\s+its\s+(\d+)\s+krylov\s+(\d+)\s+\(most\s+(\d+)\)\s+\|R\|\s+(\S+)\s+elapsed\s+([\d.]+) s", re.M)
CUT_RE = re.compile(r"^step \d+ at load .*retrying.*$", re.M)
PHASE_RE = re.compile(r"^memory: after (.*?): PetscMalloc\(\)ed [\d.]+ MiB, resident ([\d.]+) MiB(?:; Jacobian (\d+) nonzeros)?", re.M)
FORCE_RE = re.compile(r"^(\w+)\s+(\d+)\s+[\d.]+\s+([\d.eE+-]+)\s+[\d.]+\s+([\d.eE+-]+)\s+[\d.]+", re.M)


def log(msg):
    print(f"[bench_million {time.strftime('%H:%M:%S')}] {msg}", file=sys.stderr, flush=True)


def event_time(out, name):
    """max time over the ranks of a -log_view event of the Solve stage (0 when absent)"""
    part = out.split("--- Event Stage 3: Solve", 1)
    if len(part) < 2:
        return 0.0
    m = re.search(r"^" + re.escape(name) + r"\s+(\d+)\s+[\d.]+\s+([\d.eE+-]+)", part[1], re.M)
    return float(m.group(2)) if m else 0.0


def tag(p):
    return f"nc{p[0]}_nr{p[1]}_s{p[2]}_t{p[3]:g}_np{p[4]}"


def run(binary, p, logdir, timeout):
    nc, nr, steps, travel, ranks = p
    cmd = [] if ranks == 1 else ["mpiexec", "--oversubscribe", "-n", str(ranks)]
    cmd += [binary, "-options_file", CASE, "-options_file", SOLVER, "-blank_core_cells", str(nc), "-blank_radial_cells", str(nr),
            "-blank_layers", str(LAYERS), "-tool_punch_motion", f"0,0,{travel:g}", "-load_steps", str(steps), "-load_dt_max", f"{1.0 / steps:.12g}",
            "-output_interval", "0", "-output_dir", os.path.join(logdir, "out_" + tag(p)),
            "-memory_view", "-memory_phases", "-log_view"]
    path = os.path.join(logdir, tag(p) + ".log")
    t0 = time.monotonic()
    with open(path, "w") as f:
        f.write("# " + " ".join(cmd) + "\n")
        f.flush()
        try:
            r = subprocess.run(["nice"] + cmd, cwd=ROOT, env=benchutil.run_env(), stdout=f, stderr=subprocess.STDOUT, timeout=timeout)
            rc = r.returncode
        except subprocess.TimeoutExpired:
            rc = "timeout"
    with open(path, "a") as f:
        f.write(f"\n# exit {rc} wall {time.monotonic() - t0:.1f} s\n")
    return path


def parse(path, p):
    with open(path) as f:
        out = f.read()
    nc, nr, steps, travel, ranks = p
    rec = dict(point=p, ranks=ranks, travel=travel)
    me, dn, mem = MESH_RE.search(out), DONE_RE.search(out), MEM_RE.search(out)
    rec["cells"] = int(me.group(2)) if me else 4 * (nc * nc + 2 * nc * nr) * LAYERS
    rec["vertices"] = int(me.group(1)) if me else None
    rec["steps"] = [dict(step=int(m.group(1)), time=float(m.group(2)), its=int(m.group(3)), krylov=int(m.group(4)), most=int(m.group(5)),
                         elapsed=float(m.group(7))) for m in STEP_RE.finditer(out)]
    rec["cuts"] = len(CUT_RE.findall(out))
    rec["phases"] = [(m.group(1), float(m.group(2)), int(m.group(3)) if m.group(3) else None) for m in PHASE_RE.finditer(out)]
    ex = re.search(r"^# exit (\S+) wall ([\d.]+) s", out, re.M)
    rec["exit"] = ex.group(1) if ex else "?"
    rec["wall"] = float(ex.group(2)) if ex else None
    rec["complete"] = bool(dn and mem)
    if dn:
        rec["newton"], rec["solve_s"] = int(dn.group(2)), float(dn.group(4))
    elif rec["steps"]:
        rec["newton"], rec["solve_s"] = sum(s["its"] for s in rec["steps"]), rec["steps"][-1]["elapsed"]
    if mem:
        rec["rss"] = float(mem.group(1))
    if rec["complete"]:
        fe, je = event_time(out, "SNESFunctionEval"), event_time(out, "SNESJacobianEval")
        pcs, ksp = event_time(out, "PCSetUp"), event_time(out, "KSPSolve")
        rec["split"] = dict(assembly=fe + je, pcsetup=pcs, krylov=max(ksp - pcs, 0.0))
    return rec


def fmt_gib(b):
    return f"{b / 2**30:.2f}"


def section(rows, timeout):
    L = [HEADING, "",
         benchutil.measured_by("bench_million.py", ROOT), "",
         f"The friction benchmark on the whole blank (`{CASE}`: analytic tools, penalties per unit area, Coulomb 0.15, "
         f"4 layers), with the iterative solver of `{SOLVER}` (BiCGStab, BoomerAMG, `-ksp_rtol 1e-3`, the Jacobian "
         "assembled in hypre's format), no field output. Peak resident set size as PETSc reports it (`-memory_view`, summed over the ranks); "
         "Krylov iterations from the progress line (`krylov N (most M)`: the step's total and the most in one Newton "
         "iteration; one BiCGStab iteration applies the matrix and the preconditioner twice); time per Newton iteration "
         "= the solve's time over its Newton iterations, split by `-log_view` into assembly (residuals and Jacobians, "
         "contact included), preconditioner setup (BoomerAMG's hierarchy) and Krylov iterations.", "",
         f"| hexahedra | unknowns (about) | ranks | travel mm | steps done | Newton its | cuts | Krylov its per Newton it, most | "
         f"peak RSS GiB | GiB per 100 000 hex | s per Newton it | assembly / PC setup / Krylov s per Newton it | run |",
         "|---|---|---|---|---|---|---|---|---|---|---|---|---|"]
    for r in rows:
        n = r.get("newton") or 0
        most = max((s["most"] for s in r["steps"]), default=None)
        per100 = fmt_gib(r["rss"] * 1e5 / r["cells"]) if "rss" in r else "–"
        rss = fmt_gib(r["rss"]) if "rss" in r else "–"
        spn = f"{r['solve_s'] / n:.1f}" if n else "–"
        if "split" in r and n:
            sp = r["split"]
            split = f"{sp['assembly'] / n:.1f} / {sp['pcsetup'] / n:.1f} / {sp['krylov'] / n:.1f}"
        else:
            split = "–"
        status = "complete" if r["complete"] else (f"stopped at the {timeout:.0f} s limit" if r["exit"] == "timeout" else f"exit {r['exit']}")
        unk = 3 * r["vertices"] if r["vertices"] else "–"
        L.append(f"| {r['cells']} | {unk} | {r['ranks']} | {r['travel']:g} | {len(r['steps'])} | {n} | {r['cuts']} | "
                 f"{most if most is not None else '–'} | {rss} | {per100} | {spn} | {split} | {status} |")
    L.append("")
    for r in rows:
        if not r["steps"]:
            continue
        L.append(f"Steps of the {r['cells']}-hexahedra run ({r['ranks']} rank{'s' if r['ranks'] > 1 else ''}): " + "; ".join(
            f"step {s['step']} at {s['time'] * r['travel']:.2f} mm: {s['its']} Newton its, Krylov {s['krylov']} (most {s['most']}), "
            f"{s['elapsed']:.0f} s elapsed" for s in r["steps"]) + ".")
        L.append("")
    for r in rows:
        if r["phases"]:
            L.append(f"Memory after the setup phases, {r['cells']} hexahedra (resident, summed over the ranks): " + "; ".join(
                f"{ph} {mib / 1024:.2f} GiB" + (f" (Jacobian {nz} nonzeros)" if nz else "") for ph, mib, nz in r["phases"]) + ".")
            L.append("")
    ok = [r for r in rows if "rss" in r]
    big = max(rows, key=lambda r: r["cells"]) if rows else None
    if big:
        most = max((s["most"] for s in big["steps"]), default=None)
        per = big["rss"] * 1e5 / big["cells"] / 2**30 if "rss" in big else None
        L.append(f"Against the targets ({big['cells']} hexahedra): memory {'met' if per is not None and per <= TARGET_GIB else 'not met'} "
                 f"({'%.2f' % per if per is not None else 'no'} GiB per 100 000 hexahedra against {TARGET_GIB}); Krylov iterations "
                 f"{'met' if most is not None and most <= TARGET_KRYLOV else 'not met'} (most in one Newton iteration "
                 f"{most if most is not None else '–'} against {TARGET_KRYLOV}); {len(big['steps'])} steps to "
                 f"{(big['steps'][-1]['time'] * big['travel']) if big['steps'] else 0:.2f} mm.")
        L.append("")
    return "\n".join(L) + "\n"


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--point", action="append", default=[], help="NC,NR,STEPS,TRAVEL,RANKS (repeatable)")
    ap.add_argument("--timeout", type=float, default=3000.0, help="seconds per run")
    ap.add_argument("--logdir", default=None, help="keep the logs here")
    ap.add_argument("--reuse", action="store_true", help="read the logs in --logdir instead of running")
    ap.add_argument("--output", default=os.path.join(ROOT, "doc", "performance.md"))
    a = ap.parse_args()
    points = []
    for s in a.point:
        v = s.split(",")
        if len(v) != 5:
            sys.exit(f"--point {s}: give NC,NR,STEPS,TRAVEL,RANKS")
        points.append((int(v[0]), int(v[1]), int(v[2]), float(v[3]), int(v[4])))
    points = points or POINTS
    if a.reuse and not a.logdir:
        sys.exit("--reuse needs --logdir")
    logdir = a.logdir or tempfile.mkdtemp(prefix="bench_million_")
    os.makedirs(logdir, exist_ok=True)
    rows = []
    try:
        binary = None if a.reuse else benchutil.build_and_snapshot(ROOT, logdir, "bench_million", log)
        for p in points:
            path = os.path.join(logdir, tag(p) + ".log")
            if not a.reuse:
                log(f"running {tag(p)} ({4 * (p[0] ** 2 + 2 * p[0] * p[1]) * LAYERS} hexahedra)")
                run(binary, p, logdir, a.timeout)
            if not os.path.exists(path):
                log(f"{tag(p)}: no log")
                continue
            rec = parse(path, p)
            log(f"{rec['cells']} hexahedra np={p[4]}: {len(rec['steps'])} steps, peak RSS "
                f"{fmt_gib(rec['rss']) + ' GiB' if 'rss' in rec else '?'}, exit {rec['exit']}")
            rows.append(rec)
    finally:
        if not a.logdir:
            shutil.rmtree(logdir, ignore_errors=True)
    benchutil.write_doc_section(a.output, HEADING, section(rows, a.timeout))
    log(f"wrote {HEADING!r} to {a.output}")


if __name__ == "__main__":
    main()
