#!/usr/bin/python3
"""Parametric sweeps of an atrito case: the cartesian product of option values, run in parallel.

  /usr/bin/python3 scripts/sweep.py --case cases/hemisphere_frictionless_analytic.opts \\
      --param -contact_friction=0,0.05,0.1,0.15 --param -contact_penalty_normal=1e4,1e5,1e6 \\
      [--set -tool_punch_motion=0,0,12 ...] [--np 1] [--jobs 2] [--out out/sweep_NAME] \\
      [--travels 10,20,30,40] [--tool punch] [--timeout S] [--force] [--dry-run] [-- EXTRA OPTIONS]

--param -NAME=V1,V2,...   one swept option (any number of --param; the runs are their cartesian
                          product). Values that themselves contain commas (vectors) are separated
                          by ';' instead: --param '-tool_punch_motion=0,0,10;0,0,20'.
--set -NAME=VALUE         an option fixed for every run (-NAME alone: a flag). Anything after
                          `--` is also passed to every run as it stands.
--np N                    MPI ranks per run (default 1); --jobs J runs at most J at a time
                          (default 1). Keep np x jobs <= the number of cores for timings.
--launcher TEMPLATE       how a run is started (default "mpiexec --oversubscribe --bind-to none
                          --mca mpi_yield_when_idle 1 -n {np}": --bind-to none so that concurrent
                          jobs are not all pinned to the same core, and waiting ranks yield the
                          core rather than spin, which keeps multi-rank runs from collapsing when
                          the cores are shared). In a Slurm allocation e.g. "srun --exact -n {np}".
--out DIR                 the sweep's directory (default out/sweep_<case name>).
--travels T1,T2,...       tool travels at which force_full is tabulated (interpolated linearly
                          in contact.csv; empty when the run did not reach it). Default: 1/4,
                          2/4, 3/4 and all of the largest travel reached by any run.
--tool NAME               the tool whose force is reported (default punch, else the first tool
                          in contact.csv).
--timeout S               wall-clock limit per run (default: none); a run over it is killed.
--force                   rerun even the runs already complete. --dry-run: print the commands.
--no-snapshot             run bin/atrito itself rather than a private copy taken at the start
                          (OUT/.atrito_bin_*/, removed at the end; it keeps a rebuild during the
                          sweep from mixing binaries).

Each run has its own directory OUT/<name>, the name made of the swept values
(e.g. contact_friction=0.1__contact_penalty_normal=1e5), holding the run's outputs, its log
run.log (stdout and stderr) and run.json (command, status, timing). The marker OUT/<name>/.complete,
holding the exact command, is written only after a successful run (exit status 0 and the final
"done:" line). Rerunning the sweep skips a run whose marker is there and whose atrito options
(case file and every option, not the launcher or the rank count) are the same; any other run
directory is removed and the run made again from scratch. A failed run (non-zero exit, timeout)
is reported with its error line and the sweep goes on.

At the end: OUT/summary.csv (one row per run: options, force_full at the travels, steps, Newton
iterations, cuts, time, status ok/failed/timeout and the error line), OUT/force_travel.png (force
against travel for every run), OUT/force_vs_<param>.png (force at the largest travel against each
swept parameter, one line per combination of the others) and a table on standard output.
The exit status is 0 when every run is ok, 1 when some failed, 130 when interrupted (Ctrl-C or
SIGTERM kill the running jobs, MPI ranks included, and still write the summary of what finished).
"""
import argparse
import concurrent.futures
import csv
import hashlib
import itertools
import json
import os
import re
import shlex
import shutil
import signal
import subprocess
import sys
import tempfile
import threading
import time

import benchutil

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
DEFAULT_LAUNCHER = "mpiexec --oversubscribe --bind-to none --mca mpi_yield_when_idle 1 -n {np}"
MARKER = ".complete"
LOG = "run.log"
META = "run.json"

DONE_RE = re.compile(r"done: (\d+) steps, (\d+) Newton iterations, (\d+) cuts, ([0-9.eE+-]+) s")
ERROR_RE = re.compile(r"atrito: error: (.*)")
UNUSED_RE = re.compile(r"WARNING: option (-\S+).*was set but never used")
CUT_RE = re.compile(r"retrying with increment")
NAME_RE = re.compile(r"^[A-Za-z_][A-Za-z0-9_]*$")


def note(msg):
    print(f"[sweep {time.strftime('%H:%M:%S')}] {msg}", flush=True)


# ------------------------------------------------------------------------------------------ arguments
def preprocess_argv(argv):
    """`--param -x=1,2` -> `--param=-x=1,2` (argparse would take `-x=1,2` for an option)"""
    out, i = [], 0
    while i < len(argv):
        a = argv[i]
        if a == "--":
            out += argv[i:]
            break
        if a in ("--param", "--set") and i + 1 < len(argv):
            out.append(f"{a}={argv[i + 1]}")
            i += 2
            continue
        out.append(a)
        i += 1
    return out


def option_name(s, what):
    name = s.lstrip("-")
    if not NAME_RE.match(name):
        sys.exit(f"sweep: {what}: '{s}' is not an option name")
    return name


def parse_param(spec):
    if "=" not in spec:
        sys.exit(f"sweep: --param {spec}: expected -NAME=V1,V2,...")
    name, vals = spec.split("=", 1)
    name = option_name(name, "--param")
    sep = ";" if ";" in vals else ","
    values = [v.strip() for v in vals.split(sep)]
    if not values or any(v == "" for v in values):
        sys.exit(f"sweep: --param {spec}: empty value")
    if len(set(values)) != len(values):
        sys.exit(f"sweep: --param {spec}: repeated value")
    return name, values


def parse_set(spec):
    if "=" in spec:
        name, val = spec.split("=", 1)
        return option_name(name, "--set"), val
    return option_name(spec, "--set"), None


def parse_args(argv):
    extra = []
    if "--" in argv:
        k = argv.index("--")
        argv, extra = argv[:k], argv[k + 1:]
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0], formatter_class=argparse.RawDescriptionHelpFormatter,
                                 epilog=__doc__.split("\n\n", 1)[1])
    ap.add_argument("--case", required=True, help="options file of the case")
    ap.add_argument("--param", action="append", default=[], metavar="-NAME=V1,V2,...", help="a swept option")
    ap.add_argument("--set", action="append", default=[], metavar="-NAME=VALUE", help="an option for every run")
    ap.add_argument("--np", type=int, default=1, help="MPI ranks per run")
    ap.add_argument("--jobs", type=int, default=1, help="runs at a time")
    ap.add_argument("--out", help="sweep directory (default out/sweep_<case>)")
    ap.add_argument("--travels", help="travels at which the force is tabulated, e.g. 10,20,30,40")
    ap.add_argument("--tool", default="punch", help="tool whose force is reported")
    ap.add_argument("--timeout", type=float, default=0, help="seconds per run (0: none)")
    ap.add_argument("--launcher", default=DEFAULT_LAUNCHER, help="launch command template, {np} = ranks")
    ap.add_argument("--bin", default=os.path.join(ROOT, "bin", "atrito"), help="the program")
    ap.add_argument("--no-snapshot", action="store_true", help="run --bin itself, not a private copy")
    ap.add_argument("--force", action="store_true", help="rerun complete runs too")
    ap.add_argument("--dry-run", action="store_true", help="print the commands and stop")
    ap.add_argument("--no-plots", action="store_true", help="no PNG figures")
    a = ap.parse_args(preprocess_argv(argv))
    a.extra = extra
    if a.np < 1 or a.jobs < 1:
        sys.exit("sweep: --np and --jobs must be at least 1")
    case = a.case if os.path.isabs(a.case) or os.path.exists(a.case) else os.path.join(ROOT, a.case)
    if not os.path.isfile(case):
        sys.exit(f"sweep: no case file {a.case}")
    a.case = os.path.abspath(case)
    a.params = [parse_param(p) for p in a.param]
    names = [n for n, _ in a.params]
    if len(set(names)) != len(names):
        sys.exit("sweep: a parameter is given twice")
    a.sets = [parse_set(s) for s in a.set]
    for n, _ in a.sets:
        if n in names:
            sys.exit(f"sweep: -{n} is both swept (--param) and fixed (--set)")
    for n in names + [n for n, _ in a.sets]:
        if n == "output_dir":
            sys.exit("sweep: -output_dir is set by the sweep itself")
    if any(x == "-output_dir" for x in a.extra):
        sys.exit("sweep: -output_dir is set by the sweep itself")
    stem = os.path.splitext(os.path.basename(a.case))[0]
    a.out = os.path.abspath(a.out or os.path.join(ROOT, "out", "sweep_" + stem))
    a.travels = [float(t) for t in a.travels.split(",")] if a.travels else None
    if "{np}" not in a.launcher:
        sys.exit("sweep: --launcher must contain {np}")
    return a


# ------------------------------------------------------------------------------------------ runs
def safe(s):
    return re.sub(r"[^A-Za-z0-9._,+=-]", "_", s)


def run_names(params, combos):
    if not params:
        return ["base"]
    names = []
    for combo in combos:
        n = "__".join(f"{p}={safe(v)}" for (p, _), v in zip(params, combo))
        if len(n) > 150:
            n = n[:140] + "~" + hashlib.sha1(repr(combo).encode()).hexdigest()[:8]
        names.append(n)
    dup = {n for n in names if names.count(n) > 1}  # values that differ only in unsafe characters
    return [n + "~" + hashlib.sha1(repr(c).encode()).hexdigest()[:8] if n in dup else n for n, c in zip(names, combos)]


def option_args(opts):
    out = []
    for n, v in opts:
        out.append("-" + n)
        if v is not None:
            out.append(v)
    return out


def options_signature(cmd):
    """the atrito part of a command (from -options_file on) without the output directory"""
    if "-options_file" not in cmd:
        return None
    s = cmd[cmd.index("-options_file"):]
    if "-output_dir" in s:
        k = len(s) - 1 - s[::-1].index("-output_dir")
        s = s[:k] + s[k + 2:]
    return s


class Sweep:
    def __init__(self, a, binary):
        self.a = a
        self.binary = binary
        self.program_note = ("bin as found" if binary == os.path.abspath(a.bin) else
                             "a private copy of it taken at the start of the sweep") + \
            f" ({os.path.abspath(a.bin)}, modified {time.strftime('%Y-%m-%d %H:%M:%S', time.localtime(os.stat(binary).st_mtime))})"
        self.env = dict(os.environ)
        for k, v in (("OMPI_ALLOW_RUN_AS_ROOT", "1"), ("OMPI_ALLOW_RUN_AS_ROOT_CONFIRM", "1"), ("OPENBLAS_NUM_THREADS", "1")):
            self.env.setdefault(k, v)
        self.stop = threading.Event()
        self.lock = threading.Lock()
        self.procs = {}  # name -> Popen
        self.done = 0
        self.total = 0

    def shown(self, cmd):
        """the command as written to the marker and run.json: with the program's own path rather than
        the private snapshot's, so that it can be run again as it stands"""
        return [os.path.abspath(self.a.bin) if x == self.binary else x for x in cmd]

    def command(self, run):
        a = self.a
        launcher = [t.replace("{np}", str(a.np)) for t in shlex.split(a.launcher)]
        opts = option_args(a.sets) + option_args(list(zip([p for p, _ in a.params], run["values"])))
        return launcher + [self.binary, "-options_file", a.case] + opts + list(a.extra) + ["-output_dir", run["dir"]]

    def is_complete(self, run):
        m = os.path.join(run["dir"], MARKER)
        if not os.path.isfile(m):
            return False, "no marker"
        try:
            with open(m) as f:
                stored = shlex.split(f.readline())
        except (OSError, ValueError):
            return False, "unreadable marker"
        if options_signature(stored) != options_signature(run["cmd"]):
            return False, "options changed since the complete run"
        return True, ""

    def kill(self, p, grace=5.0):
        """SIGTERM to the launcher's process group and to every descendant (MPI ranks sit in process
        groups of their own), SIGKILL to whatever is left after the grace period"""
        pids = descendants(p.pid)
        for sig in (signal.SIGTERM, signal.SIGKILL):
            try:
                os.killpg(p.pid, sig)
            except (ProcessLookupError, PermissionError):
                pass
            for q in pids:
                try:
                    os.kill(q, sig)
                except (ProcessLookupError, PermissionError):
                    pass
            if sig == signal.SIGTERM:
                try:
                    p.wait(grace)
                except subprocess.TimeoutExpired:
                    pass
                pids = [q for q in pids if alive(q)]
                if p.poll() is not None and not pids:
                    return
        try:
            p.wait(5)
        except subprocess.TimeoutExpired:
            pass

    def kill_all(self):
        with self.lock:
            procs = list(self.procs.values())
        threads = [threading.Thread(target=self.kill, args=(p,)) for p in procs]
        for t in threads:
            t.start()
        for t in threads:
            t.join()

    def execute(self, run):
        a = self.a
        if self.stop.is_set():
            run.update(status="interrupted", error="not run (interrupted)")
            return run
        d = run["dir"]
        if os.path.lexists(d):
            shutil.rmtree(d) if os.path.isdir(d) and not os.path.islink(d) else os.unlink(d)
        os.makedirs(d)
        logp = os.path.join(d, LOG)
        t0 = time.time()
        status, err = None, ""
        with open(logp, "w") as log:
            try:
                p = subprocess.Popen(run["cmd"], cwd=ROOT, env=self.env, stdin=subprocess.DEVNULL, stdout=log,
                                     stderr=subprocess.STDOUT, start_new_session=True)
            except OSError as e:
                p, status, err = None, "failed", f"cannot start: {e}"
            if p is not None:
                with self.lock:
                    self.procs[run["name"]] = p
                if self.stop.is_set():  # interrupted while starting: kill_all may have missed it
                    self.kill(p)
                try:
                    p.wait(a.timeout if a.timeout > 0 else None)
                except subprocess.TimeoutExpired:
                    self.kill(p)
                    status, err = "timeout", f"timeout after {a.timeout:g} s"
                with self.lock:
                    self.procs.pop(run["name"], None)
        wall = time.time() - t0
        rc = p.returncode if p is not None else None
        res = parse_run(d, a.tool)
        if status is None:
            if self.stop.is_set() and rc != 0:
                status, err = "interrupted", "interrupted"
            elif rc == 0 and res["done"]:
                status = "ok"
            else:
                status = "failed"
                err = res["error"] or (f"exit status {rc}" + ("" if rc != 0 else ", no 'done:' line")
                                       + (f": {res['last_line']}" if res["last_line"] else ""))
        run.update(res)
        run.update(status=status, error=err, rc=rc, wall=wall, reused=False)
        meta = dict(name=run["name"], command=shlex.join(self.shown(run["cmd"])), status=status, error=err, returncode=rc,
                    wall_s=round(wall, 3), started=time.strftime("%Y-%m-%d %H:%M:%S", time.localtime(t0)),
                    program=self.program_note)
        write_atomic(os.path.join(d, META), json.dumps(meta, indent=1) + "\n")
        if status == "ok":
            write_atomic(os.path.join(d, MARKER), shlex.join(self.shown(run["cmd"])) + "\n")
        with self.lock:
            self.done += 1
            k = self.done
        note(f"[{k}/{self.total}] {run['name']}: {describe(run)}")
        return run


def descendants(pid):
    kids = {}
    for e in os.listdir("/proc"):
        if e.isdigit():
            try:
                with open(f"/proc/{e}/stat") as f:
                    ppid = int(f.read().rsplit(")", 1)[1].split()[1])
                kids.setdefault(ppid, []).append(int(e))
            except (OSError, ValueError, IndexError):
                pass
    out, todo = [], [pid]
    while todo:
        q = todo.pop()
        for c in kids.get(q, []):
            out.append(c)
            todo.append(c)
    return out


def alive(pid):
    try:
        os.kill(pid, 0)
        return True
    except (ProcessLookupError, PermissionError):
        return False


def show(path):
    r = os.path.relpath(path)
    return path if r.startswith("..") else r


def write_atomic(path, text):
    tmp = path + ".tmp"
    with open(tmp, "w") as f:
        f.write(text)
    os.replace(tmp, path)


def parse_run(d, tool):
    """results of a run directory: done line, error line, steps, force against travel"""
    res = dict(done=False, error="", last_line="", steps=None, newton_its=None, cuts=None, time=None, unused=[],
               tool=None, travel=[], force=[])
    try:
        with open(os.path.join(d, LOG), errors="replace") as f:
            text = f.read()
    except OSError:
        text = ""
    m = DONE_RE.search(text)
    if m:
        res.update(done=True, steps=int(m.group(1)), newton_its=int(m.group(2)), cuts=int(m.group(3)), time=float(m.group(4)))
    e = ERROR_RE.search(text)
    if e:
        res["error"] = "atrito: error: " + e.group(1).strip()
    lines = [l.strip() for l in text.splitlines() if l.strip() and not set(l.strip()) <= set("-")]
    res["last_line"] = lines[-1][:200] if lines else ""
    res["unused"] = sorted(set(UNUSED_RE.findall(text)))
    if not m:  # what converged before the failure
        try:
            with open(os.path.join(d, "history.csv")) as f:
                rows = list(csv.DictReader(f))
            res["steps"] = len(rows)
            res["newton_its"] = sum(int(r["newton_its"]) for r in rows)
        except (OSError, KeyError, ValueError):
            pass
        res["cuts"] = len(CUT_RE.findall(text))
    try:
        with open(os.path.join(d, "contact.csv")) as f:
            rows = list(csv.DictReader(f))
    except OSError:
        rows = []
    tools = list(dict.fromkeys(r.get("tool") for r in rows))
    t = tool if tool in tools else (tools[0] if tools else None)
    if t is not None:
        try:
            sel = [r for r in rows if r.get("tool") == t]
            # the state before the first step: no travel, no force
            res["travel"] = [0.0] + [float(r["travel"]) for r in sel]
            res["force"] = [0.0] + [float(r["force_full"]) for r in sel]
            res["tool"] = t
        except (KeyError, ValueError, TypeError):
            res["travel"], res["force"] = [], []
    return res


def force_at(run, T):
    """force_full at travel T, linear between the steps around the first crossing; None if not reached"""
    tr, fo = run.get("travel") or [], run.get("force") or []
    for i in range(1, len(tr)):
        lo, hi = tr[i - 1], tr[i]
        if min(lo, hi) - 1e-9 <= T <= max(lo, hi) + 1e-9:
            if abs(hi - lo) < 1e-300:
                return fo[i]
            w = (T - lo) / (hi - lo)
            return fo[i - 1] + min(max(w, 0.0), 1.0) * (fo[i] - fo[i - 1])
    return None


def describe(r):
    s = r["status"] + (" (already complete)" if r.get("reused") else "")
    if r.get("steps") is not None:
        s += f", {r['steps']} steps, {r['newton_its']} Newton iterations, {r['cuts']} cuts"
    t = r.get("time") if r.get("time") is not None else r.get("wall")
    if t is not None:
        s += f", {t:.1f} s"
    if r.get("error"):
        s += f": {r['error']}"
    if r.get("unused"):
        s += f" [unused options: {' '.join(r['unused'])}]"
    return s


def snapshot_binary(path, where, wait=120.0):
    """a private copy of the program (in the sweep's directory, so that ranks on other nodes of a
    cluster allocation see it too)"""
    dst, d, _ = benchutil.snapshot_binary(path, where, wait, "sweep", note)
    return dst, d

# ------------------------------------------------------------------------------------------ outputs
def fmt(x, spec="{:.6g}"):
    return "" if x is None else spec.format(x)


def tstr(T):
    return f"{T:g}"


def write_summary(a, runs, travels):
    path = os.path.join(a.out, "summary.csv")
    pnames = [p for p, _ in a.params]
    head = ["run", "status"] + pnames + [f"force_full_at_{tstr(T)}" for T in travels] + [
        "travel_final", "force_full_final", "steps", "newton_its", "cuts", "time_s", "wall_s", "reused", "options",
        "unused_options", "error", "dir"]
    tmp = path + ".tmp"
    with open(tmp, "w", newline="") as f:
        w = csv.writer(f)
        w.writerow(head)
        for r in runs:
            opts = shlex.join(option_args(a.sets) + option_args(list(zip(pnames, r["values"]))) + list(a.extra))
            tr, fo = r.get("travel") or [], r.get("force") or []
            w.writerow([r["name"], r["status"]] + list(r["values"]) + [fmt(force_at(r, T)) for T in travels] + [
                fmt(tr[-1] if tr else None), fmt(fo[-1] if fo else None), fmt(r.get("steps"), "{}"),
                fmt(r.get("newton_its"), "{}"), fmt(r.get("cuts"), "{}"), fmt(r.get("time"), "{:.2f}"),
                fmt(r.get("wall"), "{:.2f}"), "yes" if r.get("reused") else "no", opts, " ".join(r.get("unused") or []),
                r.get("error", ""), os.path.relpath(r["dir"], a.out)])
    os.replace(tmp, path)
    return path


def numeric(values):
    try:
        return [float(v) for v in values]
    except ValueError:
        return None


def label(a, r):
    return ", ".join(f"{p}={v}" for (p, _), v in zip(a.params, r["values"])) or "base"


def plots(a, runs, travels):
    try:
        import matplotlib
        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
    except ImportError:
        note("matplotlib not available: no plots")
        return []
    out = []
    tool = next((r["tool"] for r in runs if r.get("tool")), None)
    case = os.path.basename(a.case)
    fig, ax = plt.subplots(figsize=(8, 5.5))
    n = 0
    cmap = plt.get_cmap("viridis" if len(runs) > 10 else "tab10")
    for i, r in enumerate(runs):
        if len(r.get("travel") or []) < 2:
            continue
        c = cmap(i / max(1, len(runs) - 1)) if len(runs) > 10 else cmap(i % 10)
        ok = r["status"] == "ok"
        ax.plot(r["travel"], r["force"], "-" if ok else "--", color=c, lw=1.4,
                label=label(a, r) + ("" if ok else f" ({r['status']})"))
        if not ok:
            ax.plot(r["travel"][-1], r["force"][-1], "x", color=c, ms=8)
        n += 1
    if n:
        for T in travels:
            ax.axvline(T, color="0.85", lw=0.8, zorder=0)
        ax.set_xlabel(f"travel of tool '{tool}'")
        ax.set_ylabel("force_full")
        ax.set_title(f"{case}: force against travel", fontsize=10)
        ax.grid(alpha=0.3)
        ax.legend(fontsize=7 if len(runs) <= 12 else 5, ncol=1 if len(runs) <= 12 else 2)
        fig.tight_layout()
        p = os.path.join(a.out, "force_travel.png")
        fig.savefig(p, dpi=120)
        out.append(p)
    plt.close(fig)
    if not travels:
        return out
    Tmax = max(travels)
    for k, (pname, pvals) in enumerate(a.params):
        others = [j for j in range(len(a.params)) if j != k]
        groups = {}
        for r in runs:
            key = tuple(r["values"][j] for j in others)
            groups.setdefault(key, []).append(r)
        xs_num = numeric(pvals)
        fig, ax = plt.subplots(figsize=(7, 4.8))
        any_pt = False
        for gi, (key, rs) in enumerate(groups.items()):
            pts = []
            for r in rs:
                F = force_at(r, Tmax)
                if F is not None:
                    x = float(r["values"][k]) if xs_num else pvals.index(r["values"][k])
                    pts.append((x, F))
            if not pts:
                continue
            pts.sort()
            lab = ", ".join(f"{a.params[j][0]}={v}" for j, v in zip(others, key)) or None
            ax.plot([p[0] for p in pts], [p[1] for p in pts], "o-", label=lab)
            any_pt = True
        if any_pt:
            if xs_num:
                pos = [x for x in xs_num if x > 0]
                if len(pos) == len(xs_num) and max(pos) / min(pos) >= 100:
                    ax.set_xscale("log")
            else:
                ax.set_xticks(range(len(pvals)))
                ax.set_xticklabels(pvals, rotation=30, fontsize=8)
            ax.set_xlabel("-" + pname)
            ax.set_ylabel(f"force_full at travel {tstr(Tmax)}")
            ax.set_title(f"{case}: force at travel {tstr(Tmax)} against -{pname}", fontsize=10)
            ax.grid(alpha=0.3)
            if others:
                ax.legend(fontsize=7)
            fig.tight_layout()
            p = os.path.join(a.out, f"force_vs_{safe(pname)}.png")
            fig.savefig(p, dpi=120)
            out.append(p)
        else:
            note(f"force_vs_{pname}.png: no run reached travel {tstr(Tmax)}")
        plt.close(fig)
    return out


def print_table(a, runs, travels):
    head = ["run", "status", "steps", "its", "cuts", "time s"] + [f"F@{tstr(T)}" for T in travels] + ["error"]
    rows = []
    for r in runs:
        t = r.get("time") if r.get("time") is not None else r.get("wall")
        err = r.get("error", "")
        if r.get("unused"):
            err = (err + " " if err else "") + "[unused: " + " ".join(r["unused"]) + "]"
        rows.append([r["name"], r["status"] + ("*" if r.get("reused") else ""), fmt(r.get("steps"), "{}"),
                     fmt(r.get("newton_its"), "{}"), fmt(r.get("cuts"), "{}"), fmt(t, "{:.1f}")]
                    + [fmt(force_at(r, T), "{:.5g}") for T in travels] + [err[:90]])
    w = [max(len(str(x)) for x in col) for col in zip(head, *rows)]
    line = "  ".join(h.ljust(w[i]) for i, h in enumerate(head))
    print(line)
    print("-" * len(line))
    for row in rows:
        print("  ".join(str(x).ljust(w[i]) for i, x in enumerate(row)))
    if any(r.get("reused") for r in runs):
        print("* complete from an earlier sweep, not rerun")


# ------------------------------------------------------------------------------------------ main
def main():
    a = parse_args(sys.argv[1:])
    combos = list(itertools.product(*[v for _, v in a.params])) if a.params else [()]
    names = run_names(a.params, combos)
    runs = [dict(name=n, values=list(c), dir=os.path.join(a.out, n), status="pending", error="") for n, c in zip(names, combos)]

    if a.dry_run:
        sw = Sweep(a, a.bin)
        for r in runs:
            print(shlex.join(sw.command(r)))
        return 0

    os.makedirs(a.out, exist_ok=True)
    tmpdir = None
    if a.no_snapshot:
        binary = os.path.abspath(a.bin)
        if not os.access(binary, os.X_OK):
            sys.exit(f"sweep: {binary} is missing (run make)")
    else:
        binary, tmpdir = snapshot_binary(os.path.abspath(a.bin), a.out)
    sw = Sweep(a, binary)
    for r in runs:
        r["cmd"] = sw.command(r)

    todo = []
    for r in runs:
        complete, why = sw.is_complete(r)
        if complete and not a.force:
            r.update(parse_run(r["dir"], a.tool))
            r.update(status="ok", reused=True, error="")
            try:
                with open(os.path.join(r["dir"], META)) as f:
                    r["wall"] = json.load(f).get("wall_s")
            except (OSError, ValueError):
                pass
        else:
            if os.path.isdir(r["dir"]) and why != "no marker":
                note(f"{r['name']}: {why}: rerun")
            todo.append(r)
    sw.total = len(todo)
    ncores = os.cpu_count() or 1
    note(f"case {os.path.relpath(a.case, ROOT)}: {len(runs)} runs, {len(runs) - len(todo)} already complete, "
         f"{len(todo)} to run, {a.jobs} at a time on {a.np} rank(s) each; output in {a.out}")
    if min(a.jobs, len(todo)) * a.np > ncores:
        note(f"note: {min(a.jobs, len(todo))} x {a.np} ranks on {ncores} cores: the runs share cores (slower, timings distorted)")

    interrupted = False

    def on_term(signum, frame):
        raise KeyboardInterrupt

    # Ctrl-C, kill and a closed terminal all stop the sweep the same way (SIGINT set explicitly:
    # a shell starts background jobs with it ignored, and Python would then leave it so)
    sigs = [signal.SIGINT, signal.SIGTERM] + ([signal.SIGHUP] if signal.getsignal(signal.SIGHUP) != signal.SIG_IGN else [])
    old = {s: signal.signal(s, on_term) for s in sigs}
    t0 = time.time()
    pool = concurrent.futures.ThreadPoolExecutor(max_workers=a.jobs)
    futs = [pool.submit(sw.execute, r) for r in todo]
    try:
        pending = set(futs)
        while pending:
            _, pending = concurrent.futures.wait(pending, timeout=0.5)
    except KeyboardInterrupt:
        interrupted = True
        note("interrupted: stopping the running jobs")
        sw.stop.set()
        for f in futs:
            f.cancel()
        sw.kill_all()
    finally:
        pool.shutdown(wait=True)
        for s, h in old.items():
            signal.signal(s, h)
        if tmpdir:
            shutil.rmtree(tmpdir, ignore_errors=True)
    for f, r in zip(futs, todo):
        if f.cancelled():
            r.update(status="interrupted", error="not run (interrupted)")
        elif f.exception() is not None:
            r.update(status="failed", error=f"sweep: {f.exception()!r}")

    if a.travels is not None:
        travels = a.travels
    else:
        tm = max([r["travel"][-1] for r in runs if r.get("travel")] or [0.0])
        travels = [float(f"{tm * k / 4:.6g}") for k in (1, 2, 3, 4)] if tm > 0 else []
    summ = write_summary(a, runs, travels)
    figs = [] if a.no_plots else plots(a, runs, travels)
    print()
    print_table(a, runs, travels)
    print()
    cnt = {s: sum(r["status"] == s for r in runs) for s in ("ok", "failed", "timeout", "interrupted")}
    reused = sum(bool(r.get("reused")) for r in runs)
    note(f"{len(runs)} runs: {cnt['ok']} ok ({reused} already complete), {cnt['failed']} failed, {cnt['timeout']} timeout"
         + (f", {cnt['interrupted']} interrupted" if cnt["interrupted"] else "") + f"; {time.time() - t0:.1f} s")
    unused = sorted({u for r in runs for u in (r.get("unused") or [])})
    if unused:
        note(f"warning: options set but never used by the program (misspelt?): {' '.join(unused)}")
    note(f"wrote {show(summ)}" + "".join(f", {show(p)}" for p in figs))
    if interrupted:
        return 130
    return 0 if cnt["ok"] == len(runs) else 1


if __name__ == "__main__":
    sys.exit(main())
