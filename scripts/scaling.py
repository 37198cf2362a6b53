#!/usr/bin/python3
"""Strong and weak parallel scaling of atrito from PETSc's -log_view, and the section
"## Parallel scaling" of doc/notes/performance-log.md.

  /usr/bin/python3 scripts/scaling.py [--max-ranks N | --ranks 1,2,4] [--repeat 3]
      [--only strong|weak] [--strong-case FILE] [--strong-args "..."] [--weak-case FILE]
      [--weak-cells NX,NY,NZ] [--weak-args "..."] [--launcher "mpiexec ... -n {np}"]
      [--doc doc/notes/performance-log.md | --no-doc] [--out out/scaling] [--timeout S]
      [--quiet-wait 30] [--quiet-wait-total 150] [--report-only]

Strong scaling: one fixed problem at 1, 2, 4, ... ranks up to --max-ranks (default: the number
of cores; the maximum itself is included when it is not a power of two). Default: the refined
hemispherical punch with friction and analytic tools, shortened to 10 mm of punch travel in
10 steps of 1 mm (cases/hemisphere_friction_analytic_refined.opts -tool_punch_motion 0,0,10
-load_steps 10 -load_dt_max 0.1).

Weak scaling: the clamped beam (cases/clamped_beam.opts) meshed with --weak-cells per rank: at p
ranks the box is refined by the prime factors of p, each applied to the axis refined least so far
(x first), so that the cells per rank stay constant and the elements keep their shape within a
factor 2 (p = 2: 2 NX x NY x NZ; p = 4: 2 NX x 2 NY x NZ; p = 8: 2 NX x 2 NY x 2 NZ). The geometry
and the loading are those of the case.

Every run adds -log_view -output_interval 0 (no field output). Parsed per run: the maximum over
ranks of the times of the events AtritoResidual, AtritoJacobian, AtritoContact, SNESSolve,
KSPSolve, and the LU factorisations AtritoLUFactor or MatLUFactorNum, shown as LUFactor (and
their max/min ratio over ranks), the total ("Time (sec):", max over
ranks), the steps, Newton iterations and cuts of the final "done:" line. Each configuration is run
--repeat times (the repetitions interleaved, so a disturbance does not hit one configuration
only); the tables give medians. Speedup S(p) = T(p0)/T(p), efficiency E(p) = S(p) p0/p for strong
scaling (p0 the smallest rank count, normally 1), E(p) = T(p0)/T(p) for weak scaling. The load
that other processes put on the machine during each run is measured from /proc/stat (busy CPU
time of the machine minus that of the runs); before each run the script waits (up to --quiet-wait
seconds, --quiet-wait-total in all) for a moment when the other processes leave a core free for
every rank, and the tables also give the medians of the runs that were not disturbed.

The raw outputs go to OUT/<strong|weak>_np<p>_rep<k>.log, the parsed records to OUT/records.json
(--report-only rewrites the section from them without running anything). The section "## Parallel scaling" of
--doc is replaced (from its heading to the next "## " heading or the end of the file) or appended;
every other section is kept as it is. Only the Python standard library is used.
"""
import argparse
import datetime
import json
import os
import re
import resource
import shlex
import shutil
import signal
import statistics
import subprocess
import sys
import tempfile
import time

import benchutil
from benchutil import children_cpu, cpu_busy_seconds

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
HEADING = "## Parallel scaling"
EVENTS = ["SNESSolve", "AtritoResidual", "AtritoJacobian", "AtritoContact", "KSPSolve", "LUFactor"]
# the LU factorisations: AtritoLUFactor (-lu_ordering nd, the default) or MatLUFactorNum (-lu_ordering mumps)
EVENT_NAMES = {e: [e] for e in EVENTS}
EVENT_NAMES["LUFactor"] = ["AtritoLUFactor", "MatLUFactorNum"]
STRONG_CASE = "cases/hemisphere_friction_analytic_refined.opts"
STRONG_ARGS = "-tool_punch_motion 0,0,10 -load_steps 10 -load_dt_max 0.1"
WEAK_CASE = "cases/clamped_beam.opts"
WEAK_CELLS = "32,8,8"
WEAK_ARGS = ""
# Open MPI's default binding (one core per rank for up to 2 ranks); waiting ranks yield the core
# instead of busy-polling: on a machine shared with other jobs busy-polling ranks lose whole time
# slices waiting for a descheduled peer (2-rank beam of 64 cells: 2.4 s with --bind-to none and
# busy-polling, 0.27 s with yielding, on the development machine with another job running)
DEFAULT_LAUNCHER = "mpiexec --oversubscribe --mca mpi_yield_when_idle 1 -n {np}"

TOTAL_RE = re.compile(r"^Time \(sec\):\s+([\d.eE+-]+)\s+([\d.eE+-]+)", re.M)
DONE_RE = re.compile(r"done: (\d+) steps, (\d+) Newton iterations, (\d+) cuts, ([0-9.eE+-]+) s")
ERROR_RE = re.compile(r"atrito: error: (.*)")
MESH_RE = re.compile(r"mesh:\s+(\d+) vertices,\s+(\d+) hexahedra[^\n]*?cells per rank:\s*([^\n]*)")
PETSC_RE = re.compile(r"Petsc Release Version ([\d.]+)")


def log(msg):
    print(f"[scaling {time.strftime('%H:%M:%S')}] {msg}", file=sys.stderr, flush=True)


def event_re(name):
    # Event  Count(max) ratio  Time(max) ratio  ...   (first occurrence: the main stage)
    return re.compile(r"^" + re.escape(name) + r"\s+(\d+)\s+([\d.]+)\s+([\d.eE+-]+)\s+([\d.]+)", re.M)


EVENT_RES = {e: [event_re(n) for n in EVENT_NAMES[e]] for e in EVENTS}


def sh(cmd):
    try:
        return subprocess.run(cmd, capture_output=True, text=True, cwd=ROOT, timeout=60).stdout.strip()
    except (OSError, subprocess.SubprocessError):
        return ""


def run_env():
    return benchutil.run_env()


# ------------------------------------------------------------------------------------ machine load
def machine_info():
    return benchutil.machine_info(ROOT)


# ------------------------------------------------------------------------------------ runs
def snapshot_binary(path, where, wait=180.0):
    return benchutil.snapshot_binary(path, where, wait, "scaling", log)

def weak_cells(base, p):
    """base cells refined by the prime factors of p, each on the axis refined least so far"""
    fac, n, f = [], p, 2
    while n > 1:
        while n % f == 0:
            fac.append(f)
            n //= f
        f += 1
    mult = [1, 1, 1]
    for f in sorted(fac, reverse=True):
        k = min(range(3), key=lambda i: mult[i])
        mult[k] *= f
    return [b * m for b, m in zip(base, mult)]


def parse(out):
    rec = dict(events={}, total=None, done=None, error=None, cells=None, per_rank=None, petsc=None)
    for e, rxs in EVENT_RES.items():
        m = next((m for rx in rxs if (m := rx.search(out))), None)
        if m:
            rec["events"][e] = dict(count=int(m.group(1)), tmax=float(m.group(3)), ratio=float(m.group(4)))
    m = TOTAL_RE.search(out)
    if m:
        rec["total"] = float(m.group(1))
        rec["total_ratio"] = float(m.group(2))
    m = DONE_RE.search(out)
    if m:
        rec["done"] = dict(steps=int(m.group(1)), its=int(m.group(2)), cuts=int(m.group(3)), time=float(m.group(4)))
    m = ERROR_RE.search(out)
    if m:
        rec["error"] = m.group(1).strip()
    m = MESH_RE.search(out)
    if m:
        rec["cells"] = int(m.group(2))
        rec["per_rank"] = m.group(3).strip()
    m = PETSC_RE.search(out)
    if m:
        rec["petsc"] = m.group(1)
    return rec


def free_threshold(p):
    """other load (cores) above which a run on p ranks no longer has a free core per rank"""
    return max(0.0, (os.cpu_count() or 1) - p) + QUIET


QUIET = 0.3


def undisturbed(r):
    return r.get("other") is not None and r["other"] <= free_threshold(r["p"])


class Runner:
    def __init__(self, a, binary):
        self.a, self.binary = a, binary
        self.proc = None
        self.wait_left = a.quiet_wait_total
        self.waited = 0.0

    def wait_quiet(self, p):
        """wait (within the budget) until other processes leave a core free for every rank"""
        thr = free_threshold(p)
        t0 = time.monotonic()
        while True:
            b0 = cpu_busy_seconds()
            time.sleep(1.0)
            b1 = cpu_busy_seconds()
            load = (b1 - b0) / 1.0 if b0 is not None else 0.0
            spent = time.monotonic() - t0
            if load < thr or spent >= min(self.a.quiet_wait, self.wait_left):
                self.wait_left -= spent
                self.waited += spent
                return load

    def command(self, p, case, args, outdir):
        launcher = [t.replace("{np}", str(p)) for t in shlex.split(self.a.launcher)]
        return launcher + [self.binary, "-options_file", case] + args + ["-output_interval", "0", "-output_dir", outdir, "-log_view"]

    def run(self, kind, p, rep, case, args):
        if self.a.quiet_wait > 0:
            self.wait_quiet(p)
        outdir = tempfile.mkdtemp(prefix=f"{kind}_np{p}_", dir=self.a.out)
        cmd = self.command(p, case, args, outdir)
        b0, c0, t0 = cpu_busy_seconds(), children_cpu(), time.monotonic()
        status = "ok"
        try:
            self.proc = subprocess.Popen(cmd, cwd=ROOT, env=run_env(), stdout=subprocess.PIPE, stderr=subprocess.STDOUT,
                                         stdin=subprocess.DEVNULL, text=True, start_new_session=True)
            out, _ = self.proc.communicate(timeout=self.a.timeout)
            rc = self.proc.returncode
        except subprocess.TimeoutExpired:
            kill_tree(self.proc)
            out, _ = self.proc.communicate()
            rc, status = None, "timeout"
        finally:
            self.proc = None
        wall = time.monotonic() - t0
        b1, c1 = cpu_busy_seconds(), children_cpu()
        other = max(0.0, ((b1 - b0) - (c1 - c0)) / wall) if b0 is not None and wall > 0 else None
        shutil.rmtree(outdir, ignore_errors=True)
        shown = [os.path.relpath(self.a.bin, ROOT) if x == self.binary else x for x in cmd]
        shown = [x if x != outdir else "OUTDIR" for x in shown]
        with open(os.path.join(self.a.out, f"{kind}_np{p}_rep{rep}.log"), "w") as f:
            f.write("# " + shlex.join(shown) + "\n" + out)
        rec = parse(out)
        if status == "ok" and (rc != 0 or rec["done"] is None or rec["total"] is None):
            status = "failed"
        rec.update(kind=kind, p=p, rep=rep, wall=wall, other=other, status=status, rc=rc, cmd=shown)
        d = rec["done"] or {}
        log(f"{kind} {p} rank(s), rep {rep + 1}: {status}"
            + (f", {rec['cells']} cells, {d.get('steps')} steps, {d.get('its')} Newton its, total {rec['total']:.2f} s" if status == "ok" else
               f" ({rec['error'] or 'exit ' + str(rc)})")
            + (f", other load {other:.2f} cores" if other is not None else ""))
        return rec


def kill_tree(p):
    """SIGTERM then SIGKILL to the launcher's group and its descendants (MPI ranks have groups of their own)"""
    if p is None or p.poll() is not None:
        return
    kids = {}
    for e in os.listdir("/proc"):
        if e.isdigit():
            try:
                with open(f"/proc/{e}/stat") as f:
                    kids.setdefault(int(f.read().rsplit(")", 1)[1].split()[1]), []).append(int(e))
            except (OSError, ValueError, IndexError):
                pass
    pids, todo = [], [p.pid]
    while todo:
        q = todo.pop()
        for c in kids.get(q, []):
            pids.append(c)
            todo.append(c)
    for sig in (signal.SIGTERM, signal.SIGKILL):
        for q in [p.pid] + pids:
            try:
                os.killpg(q, sig) if q == p.pid else os.kill(q, sig)
            except (ProcessLookupError, PermissionError):
                pass
        try:
            p.wait(5)
            if sig == signal.SIGTERM:
                time.sleep(0.5)
        except subprocess.TimeoutExpired:
            pass


# ------------------------------------------------------------------------------------ analysis
def med(vals):
    vals = [v for v in vals if v is not None]
    return statistics.median(vals) if vals else None


def aggregate(recs):
    """per rank count: medians of the total, of each event's max time and ratio, of wall, load"""
    out = {}
    for p in sorted({r["p"] for r in recs}):
        rs = [r for r in recs if r["p"] == p and r["status"] == "ok"]
        allr = [r for r in recs if r["p"] == p]
        g = dict(p=p, n=len(rs), nfail=len(allr) - len(rs), recs=allr)
        if rs:
            g["total"] = med([r["total"] for r in rs])
            g["tmin"] = min(r["total"] for r in rs)
            g["tmaxr"] = max(r["total"] for r in rs)
            g["events"] = {e: med([r["events"].get(e, {}).get("tmax") for r in rs]) for e in EVENTS}
            g["ratios"] = {e: med([r["events"].get(e, {}).get("ratio") for r in rs]) for e in EVENTS}
            g["counts"] = {e: med([r["events"].get(e, {}).get("count") for r in rs]) for e in EVENTS}
            g["its"] = sorted({r["done"]["its"] for r in rs})
            g["steps"] = sorted({r["done"]["steps"] for r in rs})
            g["cuts"] = sorted({r["done"]["cuts"] for r in rs})
            g["cells"] = rs[0]["cells"]
            g["per_rank"] = rs[0]["per_rank"]
            g["wall"] = med([r["wall"] for r in rs])
            g["other_max"] = max([r["other"] for r in rs if r["other"] is not None] or [0.0])
            g["other_med"] = med([r["other"] for r in rs])
            g["t_per_it"] = med([r["total"] / r["done"]["its"] for r in rs if r["done"]["its"]])
            q = [r for r in rs if undisturbed(r)]
            g["nq"] = len(q)
            g["total_q"] = med([r["total"] for r in q])
            g["events_q"] = {e: med([r["events"].get(e, {}).get("tmax") for r in q]) for e in EVENTS}
        out[p] = g
    return out


def f2(x, spec="{:.2f}"):
    return "–" if x is None else spec.format(x)


def ints(v):
    return "/".join(str(x) for x in v) if v else "–"


def speed(kind, t0, p0, t, p):
    if t0 is None or t is None or t <= 0:
        return None, None
    if kind == "strong":
        s = t0 / t
        return s, s * p0 / p
    return None, t0 / t


def qspeed(kind, g0, p0, g, p, ev):
    """speedup/efficiency from the undisturbed runs only ('–' without such runs at both rank counts)"""
    if not g0.get("nq") or not g.get("nq"):
        return "–"
    t0 = g0["total_q"] if ev == "total" else g0["events_q"].get(ev)
    t = g["total_q"] if ev == "total" else g["events_q"].get(ev)
    if not t0 or not t or (ev != "total" and t0 < 1e-3):
        return "–"
    s, e = speed(kind, t0, p0, t, p)
    return f"{s:.2f} ({e:.0%})" if kind == "strong" else f"{e:.0%}"


def write_section(path, body):
    benchutil.write_doc_section(path, HEADING, body)

def report(a, mi, strong, weak, recs, t_total, load0, load1, petsc, bin_mtime, cmdline):
    L = []
    A = L.append
    A(HEADING + "\n")
    A(f"Written by `scripts/scaling.py` on {mi['date']} (total script time {t_total / 60:.1f} min); rerun it to "
      f"regenerate this section (`{cmdline}`).\n")
    A("### Machine\n")
    tpc = f", {mi['threads_per_core']} thread(s) per core" if mi["threads_per_core"] else ""
    A(f"- CPU: {mi['cpu']}, {mi['cores']} cores visible to the OS{tpc}"
      + (f" ({mi['virt']})" if mi["virt"] else "") + f", {mi['mem']} memory, Linux {mi['kernel']}")
    A(f"- PETSc {petsc or 'unknown'}, LU by MUMPS (the code's default solver), `OPENBLAS_NUM_THREADS=1`; MPI: {mi['mpi']}; "
      f"launcher `{a.launcher}`")
    A(f"- Code: commit `{mi['commit']}`" + (f"; uncommitted changes in {', '.join('`' + d + '`' for d in mi['dirty'])}" if mi["dirty"] else "")
      + f"; `bin/atrito` built {time.strftime('%Y-%m-%d %H:%M', time.localtime(bin_mtime))} (a private copy was run)")
    A(f"- Load average (1 min) before / after: {load0:.2f} / {load1:.2f}.")
    A("")
    ncores = mi["cores"]
    if ncores <= 2:
        others = [r["other"] for r in recs if r.get("other") is not None]
        busy = sum(o > 0.3 for o in others)
        A(f"**This machine has {ncores} cores: only 1 and 2 ranks are meaningful here.** More ranks than cores would share "
          "cores and measure time slicing, not parallel scaling. The machine is shared with other jobs; the load they "
          "caused is measured during every run (last column of the tables, in cores): "
          f"{busy} of the {len(others)} runs had more than {QUIET} cores of other load"
          + (f" (up to {max(others):.2f})" if others else "") + ". A 2-rank run that shares a core with another "
          "process is slowed directly, so a disturbed 2-rank figure is a lower bound of what two free cores give. The "
          "column counts CPU time only: a neighbour that competes for memory bandwidth and the shared cache slows even a "
          "run that has a core to itself (assembly and factorisation are both memory-bound), which it does not show; "
          "compare absolute times between measurements with care. Use the script on a cluster node (`--max-ranks`, "
          "`--launcher \"srun -n {np}\"`) for real scaling curves.\n")
    else:
        A(f"This machine has {ncores} cores; rank counts up to {ncores} were measured.\n")

    A("### Method\n")
    A(f"- Strong scaling: `{os.path.relpath(a.strong_case, ROOT)} {a.strong_args}` — the refined hemispherical punch "
      "with friction (μ = 0.15) and analytic tools, shortened to the first part of the punch travel; the same problem on every rank count.")
    weak_cmd = f"{os.path.relpath(a.weak_case, ROOT)} -box_cells NX,NY,NZ" + (f" {a.weak_args}" if a.weak_args else "")
    A(f"- Weak scaling: `{weak_cmd}` — the clamped beam (8 × 2 × 2, clamped at x = 0, tip sheared and pulled, Swift "
      f"plasticity), {a.weak_cells_str} cells per rank: at p ranks the box is refined by the prime factors of p, each on "
      "the axis refined least so far (2 ranks: NX doubled), so the cells per rank stay constant; geometry and loading unchanged.")
    A("- Every run: `-log_view -output_interval 0` (no field output). Times are PETSc's event times, the maximum over "
      "the ranks; \"total\" is the `Time (sec):` line (the whole run: mesh, setup, all load steps). `AtritoResidual` "
      "and `AtritoJacobian` are the assemblies (element kernels with the return maps, insertion, final assembly); "
      "`AtritoContact` is the contact part, nested inside them (zero for the beam); `LUFactor` the MUMPS "
      "numerical factorisations (`AtritoLUFactor`, or `MatLUFactorNum` with `-lu_ordering mumps`); `KSPSolve` the solves proper (the factorisation is logged apart, under `PCSetUp`); "
      "`SNESSolve` all Newton iterations (assembly, factorisation, solves, line search, contact).")
    if "yield_when_idle" in a.launcher:
        A("- `--mca mpi_yield_when_idle 1`: ranks waiting for a message yield the core instead of busy-polling. With "
          "busy-polling, on a machine where another job holds a core, a waiting rank loses whole time slices to a "
          "descheduled peer: in a check on this machine the 2-rank beam of 64 cells took 2.4 s with `--bind-to none` "
          "and busy-polling against 0.27 s with yielding. On a dedicated cluster node the default busy-polling is fine.")
    A(f"- {a.repeat} repetition(s) per configuration, interleaved; medians. Strong: speedup S = T(1)/T(p), "
      "efficiency E = S/p. Weak: E = T(1)/T(p). \"Other load\": busy CPU of the whole machine minus that of the run, "
      "per second of the run, in cores (/proc/stat). A run counts as undisturbed when that load left a free core for each "
      f"of its ranks (other load ≤ cores − ranks + {QUIET}); the \"undisturbed\" columns use those runs only. Before each "
      f"run the script waited up to {a.quiet_wait:g} s for such a quiet moment (at most {a.quiet_wait_total:g} s in all; "
      f"{a.waited:.0f} s waited).")
    A("")

    def table(kind, agg):
        if not agg:
            return
        ps = sorted(agg)
        p0 = ps[0]
        g0 = agg[p0]
        A("| ranks | cells | cells per rank | steps | Newton its | total s median [min – max] | "
          + ("speedup | efficiency | " if kind == "strong" else "s per Newton it | efficiency | ")
          + " | ".join(f"{e} s" for e in EVENTS) + " | other load, cores (max) | undisturbed runs: total s median (n) | "
          + ("undisturbed: speedup (efficiency) |" if kind == "strong" else "undisturbed: efficiency |"))
        ncol = 11 + len(EVENTS)
        A("|" + "---|" * ncol)
        for p in ps:
            g = agg[p]
            if not g["n"]:
                A(f"| {p} | all {g['nfail']} runs failed |" + " – |" * (ncol - 2))
                continue
            s, e = speed(kind, g0.get("total"), p0, g["total"], p)
            mid = (f"{f2(s)} | {f2(e, '{:.0%}')} | " if kind == "strong" else f"{f2(g['t_per_it'], '{:.3f}')} | {f2(e, '{:.0%}')} | ")
            A(f"| {p} | {g['cells']:,} | {g['cells'] / p:,.0f} | {ints(g['steps'])} | {ints(g['its'])} | "
              f"{f2(g['total'])} [{f2(g['tmin'])} – {f2(g['tmaxr'])}] | " + mid
              + " | ".join(f2(g["events"][ev], "{:.3f}") for ev in EVENTS) + f" | {f2(g['other_max'])} | "
              + f"{f2(g['total_q'])} ({g['nq']}) | " + qspeed(kind, g0, p0, g, p, "total") + " |")
        A("")
        if len(ps) > 1:
            A("Per event: " + ("speedup T(1)/T(p) and efficiency" if kind == "strong" else "efficiency T(1)/T(p)")
              + ", and the max/min ratio of the event's time over the ranks (load imbalance; 1 = balanced):\n")
            A("| event | " + " | ".join(f"{p} ranks" for p in ps[1:]) + " | "
              + " | ".join(f"{p} ranks, undisturbed runs" for p in ps[1:]) + " | max/min over ranks at " + f"{ps[-1]} ranks |")
            A("|---|" + "---|" * (2 * (len(ps) - 1)) + "---|")
            for ev in ["total"] + EVENTS:
                cells = []
                for p in ps[1:]:
                    t0 = g0.get("total") if ev == "total" else (g0.get("events") or {}).get(ev)
                    t = agg[p].get("total") if ev == "total" else (agg[p].get("events") or {}).get(ev)
                    if not t0 or not t or (ev != "total" and t0 < 1e-3):
                        cells.append("–")
                        continue
                    s, e = speed(kind, t0, p0, t, p)
                    cells.append(f"{s:.2f} ({e:.0%})" if kind == "strong" else f"{e:.0%}")
                cells += [qspeed(kind, g0, p0, agg[p], p, ev) for p in ps[1:]]
                r = agg[ps[-1]].get("total_ratio") if ev == "total" else (agg[ps[-1]].get("ratios") or {}).get(ev)
                A(f"| {ev} | " + " | ".join(cells) + f" | {f2(r)} |")
            A("")

    def runs_line(kind, agg):
        parts = []
        for p in sorted(agg):
            rs = agg[p]["recs"]
            parts.append(f"{p} rank{'s' if p > 1 else ''}: " + ", ".join(
                (f"{r['total']:.1f}" if r["status"] == "ok" else r["status"]) + (f" [{r['other']:.2f}]" if r.get("other") is not None else "")
                for r in sorted(rs, key=lambda r: r["rep"])))
        A("Every run, in order, total s [other load, cores]: " + "; ".join(parts) + ".\n")

    if strong is not None:
        A("### Strong scaling (fixed problem)\n")
        table("strong", strong)
        runs_line("strong", strong)
    if weak is not None:
        A("### Weak scaling (constant cells per rank)\n")
        table("weak", weak)
        runs_line("weak", weak)

    A("### Observations\n")
    obs = observations(strong, weak, ncores)
    for o in obs:
        A(f"- {o}")
    fails = [r for r in recs if r["status"] != "ok"]
    if fails:
        A(f"- {len(fails)} run(s) did not complete and are left out of the medians: "
          + "; ".join(f"{r['kind']} {r['p']} ranks rep {r['rep'] + 1}: {r['status']} ({r['error'] or 'exit ' + str(r['rc'])})" for r in fails) + ".")
    A("- Raw `-log_view` outputs: `out/scaling/<strong|weak>_np<p>_rep<k>.log` (not in the repository).")
    A("")
    return "\n".join(L).rstrip("\n") + "\n"


def observations(strong, weak, ncores):
    obs = []
    if strong and len(strong) > 1:
        ps = sorted(strong)
        p0, p1 = ps[0], ps[-1]
        g0, g1 = strong[p0], strong[p1]
        if g0.get("total") and g1.get("total"):
            s, e = speed("strong", g0["total"], p0, g1["total"], p1)
            obs.append(f"Strong scaling, {p0} → {p1} ranks: the whole run speeds up {s:.2f}× (efficiency {e:.0%}); "
                       f"Newton iterations {ints(g0['its'])} vs {ints(g1['its'])}"
                       + (" (the same work on every rank count)" if g0["its"] == g1["its"] else
                          " (different: the partition changes the round-off and with it, through the contact and the step cuts, the Newton path; compare per iteration)") + ".")
            q = qspeed("strong", g0, p0, g1, p1, "total")
            obs.append(f"From the undisturbed runs only ({g0.get('nq', 0)} at {p0}, {g1.get('nq', 0)} at {p1} ranks): " +
                       (f"speedup (efficiency) {q}." if q != "–" else "none at one of the rank counts, no figure."))
            parts = []
            for ev in EVENTS:
                t0, t1 = g0["events"].get(ev), g1["events"].get(ev)
                if t0 and t1 and t0 >= 1e-3:
                    parts.append((ev, t0 / t1 * p0 / p1, t0 / g0["total"]))
            if parts:
                obs.append("Per event (efficiency, share of the 1-rank total): " + ", ".join(
                    f"{ev} {e:.0%} ({sh:.0%})" for ev, e, sh in parts) + ".")
                asm = [x for x in parts if x[0] in ("AtritoResidual", "AtritoJacobian")]
                lu = [x for x in parts if x[0] == "LUFactor"]
                if asm and lu:
                    obs.append("The assembly (element loops, no communication but the ghost exchange) scales better than the "
                               "MUMPS factorisation, whose share of the run therefore grows with the ranks."
                               if min(x[1] for x in asm) > lu[0][1] else
                               "Here the factorisation scaled as well as or better than the assembly.")
            nb = [r for r in g1["recs"] if r["status"] == "ok" and (r.get("other") or 0) > 0.3]
            if nb and p1 >= ncores:
                obs.append(f"{len(nb)} of the {g1['n']} {p1}-rank strong-scaling runs shared the {ncores}-core machine with other "
                           f"processes (up to {max(r['other'] for r in nb):.2f} cores of other load); such contention, not the "
                           "code, accounts for part of their loss of efficiency.")
    if weak and len(weak) > 1:
        ps = sorted(weak)
        p0, p1 = ps[0], ps[-1]
        g0, g1 = weak[p0], weak[p1]
        if g0.get("total") and g1.get("total"):
            e = g0["total"] / g1["total"]
            ei = g0["t_per_it"] / g1["t_per_it"] if g0.get("t_per_it") and g1.get("t_per_it") else None
            obs.append(f"Weak scaling, {p0} → {p1} ranks ({g0['cells']:,} → {g1['cells']:,} cells): efficiency {e:.0%} on the "
                       f"total time" + (f", {ei:.0%} per Newton iteration" if ei else "") + f" (Newton iterations {ints(g0['its'])} vs {ints(g1['its'])})"
                       + (f"; from the undisturbed runs only: {qspeed('weak', g0, p0, g1, p1, 'total')}." if qspeed('weak', g0, p0, g1, p1, 'total') != "–"
                          else "; no undisturbed runs at one of the rank counts."))
            l0, l1 = g0["events"].get("LUFactor"), g1["events"].get("LUFactor")
            j0, j1 = g0["events"].get("AtritoJacobian"), g1["events"].get("AtritoJacobian")
            if l0 and l1 and j0 and j1:
                obs.append(f"Weak efficiency of the Jacobian assembly {j0 / j1:.0%}, of the LU factorisation {l0 / l1:.0%}: "
                           "MUMPS's parallel factorisation is less efficient than the element loops, and once the mesh is "
                           "refined in more than one direction (4 ranks and more) its fill-in grows faster than the unknowns, "
                           "so weak scaling with a direct solver cannot stay flat; that needs an iterative solver.")
    if not obs:
        obs.append("Only one rank count was measured: no speedup to report.")
    return obs


# ------------------------------------------------------------------------------------ main
def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0], formatter_class=argparse.RawDescriptionHelpFormatter,
                                 epilog=__doc__.split("\n\n", 1)[1])
    ap.add_argument("--max-ranks", type=int, default=os.cpu_count() or 1)
    ap.add_argument("--ranks", help="explicit rank counts, e.g. 1,2,4 (overrides --max-ranks)")
    ap.add_argument("--repeat", type=int, default=3)
    ap.add_argument("--only", choices=["strong", "weak"])
    ap.add_argument("--strong-case", default=STRONG_CASE)
    ap.add_argument("--strong-args", default=STRONG_ARGS, help="options added to the strong case (write --strong-args=\"-opt v\")")
    ap.add_argument("--weak-case", default=WEAK_CASE)
    ap.add_argument("--weak-cells", default=WEAK_CELLS, help="cells per rank as NX,NY,NZ of the 1-rank mesh")
    ap.add_argument("--weak-args", default=WEAK_ARGS, help="options added to the weak case (write --weak-args=\"-opt v\")")
    ap.add_argument("--launcher", default=DEFAULT_LAUNCHER, help="launch template, {np} = ranks")
    ap.add_argument("--bin", default=os.path.join(ROOT, "bin", "atrito"))
    ap.add_argument("--doc", default=os.path.join(ROOT, "doc", "notes", "performance-log.md"))
    ap.add_argument("--no-doc", action="store_true", help="print the section instead of writing it")
    ap.add_argument("--out", default=os.path.join(ROOT, "out", "scaling"))
    ap.add_argument("--timeout", type=float, default=600, help="seconds per run")
    ap.add_argument("--quiet-wait", type=float, default=30, help="before each run, wait up to this many seconds for "
                    "the other processes to leave a core per rank free (0: do not wait)")
    ap.add_argument("--quiet-wait-total", type=float, default=150, help="budget for all these waits, seconds")
    ap.add_argument("--report-only", action="store_true", help="no runs: rewrite the section from OUT/records.json")
    a = ap.parse_args()
    if a.ranks:
        ranks = sorted({int(x) for x in a.ranks.split(",")})
    else:
        ranks, p = [], 1
        while p <= a.max_ranks:
            ranks.append(p)
            p *= 2
        if a.max_ranks not in ranks and a.max_ranks > 0:
            ranks.append(a.max_ranks)
    if not ranks or ranks[0] < 1 or a.repeat < 1:
        sys.exit("scaling: bad --ranks/--max-ranks/--repeat")
    a.strong_case = os.path.abspath(a.strong_case if os.path.exists(a.strong_case) else os.path.join(ROOT, a.strong_case))
    a.weak_case = os.path.abspath(a.weak_case if os.path.exists(a.weak_case) else os.path.join(ROOT, a.weak_case))
    base = [int(x) for x in a.weak_cells.split(",")]
    a.weak_cells_str = "×".join(map(str, base)) + f" = {base[0] * base[1] * base[2]:,}"
    a.out = os.path.abspath(a.out)
    a.bin = os.path.abspath(a.bin)
    os.makedirs(a.out, exist_ok=True)
    cmdline = "/usr/bin/python3 scripts/scaling.py " + shlex.join(sys.argv[1:]) if sys.argv[1:] else "/usr/bin/python3 scripts/scaling.py"

    a.waited = 0.0
    if a.report_only:  # re-render from the records of the last measurement
        with open(os.path.join(a.out, "records.json")) as f:
            R = json.load(f)
        for k, v in R["args"].items():
            setattr(a, k, v)
        finish(a, R["records"], R["machine"], R["kinds"], R["seconds"], R["load"][0], R["load"][1], R["bin_mtime"], R["cmdline"])
        return 0

    def on_term(signum, frame):
        raise KeyboardInterrupt

    signal.signal(signal.SIGTERM, on_term)
    signal.signal(signal.SIGINT, on_term)
    t_start = time.monotonic()
    load0 = os.getloadavg()[0]
    mi = machine_info()
    binary, bindir, bin_mtime = snapshot_binary(a.bin, a.out)
    runner = Runner(a, binary)
    recs = []
    kinds = [k for k in ("strong", "weak") if a.only in (None, k)]
    log(f"ranks {ranks}, {a.repeat} repetition(s), {', '.join(kinds)}; raw logs in {a.out}")
    if max(ranks) > (os.cpu_count() or 1):
        log(f"note: more ranks than the {os.cpu_count()} cores: those runs share cores")
    try:
        for rep in range(a.repeat):
            for kind in kinds:
                for p in ranks:
                    if kind == "strong":
                        rec = runner.run(kind, p, rep, a.strong_case, shlex.split(a.strong_args))
                    else:
                        cells = weak_cells(base, p)
                        rec = runner.run(kind, p, rep, a.weak_case, ["-box_cells", ",".join(map(str, cells))] + shlex.split(a.weak_args))
                    recs.append(rec)
    except KeyboardInterrupt:
        kill_tree(runner.proc)
        shutil.rmtree(bindir, ignore_errors=True)
        sys.exit("scaling: interrupted; nothing written")
    shutil.rmtree(bindir, ignore_errors=True)
    a.waited = runner.waited
    load1 = os.getloadavg()[0]
    with open(os.path.join(a.out, "records.json"), "w") as f:
        json.dump(dict(records=recs, machine=mi, load=[load0, load1], bin_mtime=bin_mtime, seconds=time.monotonic() - t_start,
                       ranks=ranks, kinds=kinds, cmdline=cmdline, args={k: getattr(a, k) for k in SAVED_ARGS}), f, indent=1)
    finish(a, recs, mi, kinds, time.monotonic() - t_start, load0, load1, bin_mtime, cmdline)
    return 0 if all(r["status"] == "ok" for r in recs) else 1


SAVED_ARGS = ["strong_case", "strong_args", "weak_case", "weak_cells_str", "weak_args", "launcher", "repeat", "quiet_wait",
              "quiet_wait_total", "waited"]


def finish(a, recs, mi, kinds, seconds, load0, load1, bin_mtime, cmdline):
    petsc = next((r["petsc"] for r in recs if r.get("petsc")), None)
    strong = aggregate([r for r in recs if r["kind"] == "strong"]) if "strong" in kinds else None
    weak = aggregate([r for r in recs if r["kind"] == "weak"]) if "weak" in kinds else None
    for agg in (strong, weak):
        for g in (agg or {}).values():
            rs = [r for r in g["recs"] if r["status"] == "ok"]
            g["total_ratio"] = med([r.get("total_ratio") for r in rs])
    body = report(a, mi, strong, weak, recs, seconds, load0, load1, petsc, bin_mtime, cmdline)
    print(body, end="")
    if not a.no_doc:
        write_section(a.doc, body)
        log(f"wrote the section '{HEADING}' of {os.path.relpath(a.doc)}")


if __name__ == "__main__":
    sys.exit(main())
