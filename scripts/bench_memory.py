#!/usr/bin/python3
"""Memory: peak resident size per 100 000 hexahedra with the direct and the iterative solver.

  /usr/bin/python3 scripts/bench_memory.py [--quick] [--two-ranks]
                                           [--output doc/notes/performance-log.md]

What it does
  1. Runs the friction benchmark (cases/hemisphere_friction.opts, Coons tools) on 4-layer blanks
     of about 25 000, 50 000 and 100 000 hexahedra for one load step (punch travel 1 mm: contact
     at the pole, plasticity starting), with -memory_view, once with the default solver (LU by
     MUMPS) and once with GMRES + GAMG (-ksp_type gmres -pc_type gamg -ksp_rtol 1e-8, the
     rigid-body near-null space set by the code); one rank (--two-ranks: the largest mesh on 2
     ranks too). --quick: the two smaller meshes only.
  2. Reads PETSc's "Maximum (over computational time) process memory" (the peak resident set
     size, summed over the ranks) and reports it, and per 100 000 hexahedra.
  3. Writes the section "## Memory" of the output file, keeping its other sections.

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
CASE = "cases/hemisphere_friction.opts"
HEADING = "## Memory"
# (core cells, radial cells, layers): hexahedra = 4 (nc^2 + 2 nc nr)
MESHES = [(33, 80, 4), (46, 114, 4), (65, 161, 4)]
SOLVERS = [("LU (MUMPS, METIS order)", []), ("GMRES + GAMG", ["-ksp_type", "gmres", "-pc_type", "gamg", "-ksp_rtol", "1e-8", "-ksp_max_it", "1000"])]
RUN_ARGS = ["-tool_punch_motion", "0,0,1", "-load_steps", "1", "-load_dt_max", "1", "-output_interval", "0", "-log_view", "-memory_view"]

# the large-sheet solver is measured by scripts/bench_million.py (its own section)
POINTER = ("The iterative solver for large sheets (`cases/solver_amg_sheet.opts`: BiCGStab, BoomerAMG with aggressive "
           "coarsening on the first level, the Jacobian made in hypre's format without its auxiliary assembly structure, no "
           "rigid-body modes) on the whole blank of `cases/hemisphere_friction_disk.opts` is measured by "
           "`scripts/bench_million.py`, section One million hexahedra, with where the memory goes.")
MEM_RE = benchutil.MEM_RE
MESH_RE = benchutil.MESH_RE
DONE_RE = benchutil.DONE_RE
KSP_RE = re.compile(r"^KSPSolve\s+(\d+)", re.M)
KSPIT_RE = re.compile(r"^MatMult\s+(\d+)", re.M)


def log(msg):
    print(f"[bench_memory {time.strftime('%H:%M:%S')}] {msg}", file=sys.stderr, flush=True)


def run(binary, mesh, solver_args, ranks, outdir):
    nc, nr, nl = mesh
    cmd = [] if ranks == 1 else ["mpiexec", "--oversubscribe", "-n", str(ranks)]
    cmd += [binary, "-options_file", CASE, "-blank_core_cells", str(nc), "-blank_radial_cells", str(nr),
            "-blank_layers", str(nl), "-output_dir", outdir] + RUN_ARGS + solver_args
    t0 = time.monotonic()
    r = subprocess.run(cmd, cwd=ROOT, env=benchutil.run_env(), capture_output=True, text=True, timeout=7200)
    wall = time.monotonic() - t0
    out = r.stdout + r.stderr
    mem, me, dn = MEM_RE.search(out), MESH_RE.search(out), DONE_RE.search(out)
    if r.returncode or not (mem and me and dn):
        tail = "\n".join(out.strip().splitlines()[-5:])
        return dict(error=f"exit {r.returncode}: {tail}", wall=wall)
    return dict(cells=int(me.group(2)), vertices=int(me.group(1)), rss=float(mem.group(1)), rss_max=float(mem.group(2)),
                its=int(dn.group(2)), time=float(dn.group(4)), wall=wall)


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--quick", action="store_true", help="the two smaller meshes only")
    ap.add_argument("--two-ranks", action="store_true", help="the largest mesh on 2 ranks too")
    ap.add_argument("--output", default=os.path.join(ROOT, "doc", "notes", "performance-log.md"))
    a = ap.parse_args()
    meshes = MESHES[:2] if a.quick else MESHES
    plan = [(m, s, 1) for m in meshes for s in SOLVERS] + ([(meshes[-1], s, 2) for s in SOLVERS] if a.two_ranks else [])
    work = tempfile.mkdtemp(prefix="bench_memory_")
    rows = []
    try:
        binary = benchutil.build_and_snapshot(ROOT, work, "bench_memory", log)
        for i, (m, (sname, sargs), ranks) in enumerate(plan):
            rec = run(binary, m, sargs, ranks, os.path.join(work, f"run{i}"))
            rec.update(mesh=m, solver=sname, ranks=ranks)
            if "error" in rec:
                log(f"{m} {sname} np={ranks}: FAILED {rec['error']}")
            else:
                log(f"{rec['cells']} hexahedra, {sname}, np={ranks}: peak RSS {rec['rss'] / 2**20:.0f} MiB, "
                    f"{rec['its']} Newton its, {rec['time']:.1f} s")
            rows.append(rec)
    finally:
        shutil.rmtree(work, ignore_errors=True)

    L = [HEADING, "",
         benchutil.measured_by("bench_memory.py", ROOT),
         "",
         f"The friction benchmark (`{CASE}`, Coons tools) on 4-layer blanks, one load step (punch travel 1 mm: contact "
         "at the pole, plastic flow starting). Peak resident set size as PETSc reports it (`-memory_view`: \"Maximum "
         "(over computational time) process memory\", summed over the ranks): mesh, fields, history, matrix, solver, "
         "MPI and library buffers. GAMG runs with `-ksp_type gmres -pc_type gamg -ksp_rtol 1e-8` and the rigid-body "
         "near-null space.",
         "",
         "| hexahedra | unknowns (about) | solver | ranks | peak RSS MiB | MiB per 100 000 hexahedra | Newton its | run s |",
         "|---|---|---|---|---|---|---|---|"]
    for r in rows:
        if "error" in r:
            L.append(f"| {r['mesh']} | – | {r['solver']} | {r['ranks']} | failed: {r['error'].splitlines()[-1][:120]} | – | – | – |")
            continue
        L.append(f"| {r['cells']} | {3 * r['vertices']} | {r['solver']} | {r['ranks']} | {r['rss'] / 2**20:.0f} | "
                 f"{r['rss'] / 2**20 * 1e5 / r['cells']:.0f} | {r['its']} | {r['time']:.1f} |")
    ok = [r for r in rows if "error" not in r]
    big = [r for r in ok if r["cells"] >= 90000 and r["ranks"] == 1]
    if big:
        L.append("")
        L.append("Per 100 000 hexahedra on one rank: " + "; ".join(
            f"{r['solver']} {r['rss'] / 2**30 * 1e5 / r['cells']:.2f} GiB" for r in big) + ".")
    L.append("")
    L.append(POINTER)
    L.append("")
    benchutil.write_doc_section(a.output, HEADING, "\n".join(L) + "\n")
    log(f"wrote {HEADING!r} to {a.output}")


if __name__ == "__main__":
    main()
