#!/usr/bin/python3
"""Assembly throughput benchmark: hex8 elements per second per core for the residual and the
Jacobian, with finite-strain J2 plasticity (Swift hardening) active, on the real code path.

  /usr/bin/python3 scripts/bench_assembly.py [--quick] [--no-build] [--reps N] [--baseline REV]
                                              [--output doc/notes/performance-log.md]

What it does
  1. Builds bin/atrito and build/lib.a with `make` when they are missing or out of date
     (retries while a source file may be mid-edit; --no-build uses what is there), then runs
     private copies of them, so that a rebuild by someone else during the benchmark does not
     interfere.
  2. Runs the clamped_beam case (plastic from the first step) for two load steps of 1/8 of the
     load (-load_steps 8 -load_max_steps 2: the program then stops with the expected
     "-load_max_steps 2 reached" error) with -log_view -memory_view, on three mesh sizes, for
     both Jacobian assembly variants (-assembly_coo 1, the default, and MatSetValues into AIJ with
     -assembly_coo 0), repeated,
     plus the middle size on 2 MPI ranks. The PETSc log events AtritoResidual/AtritoJacobian
     each cover one full assembly over the local cells (gather, element kernels with the
     return maps, insertion/scatter, final assembly); throughput = count * cells / (max time
     over ranks * ranks).
  3. Compiles a small C driver in a temporary directory (not in the repository) against
     build/lib.a and times hex8_element alone (no gather, no insertion) on a plastic state.
  4. With --baseline REV: builds the revision REV (git archive into a temporary directory, make
     there), and measures it against the current code, alternating the two run by run: the
     kernel driver (each compiled against its own build/lib.a and headers) and the full assembly
     on the smallest mesh in both variants; the section then has a "Before and after" table.
  5. Writes the section "## Assembly throughput" of doc/notes/performance-log.md (the
     measurements that doc/performance.md quotes), keeping any other "## " sections of that file
     as they are.

Only the Python standard library is used. Runs with OPENBLAS_NUM_THREADS=1 and the Open MPI
run-as-root variables set.
"""
import argparse
import datetime
import json
import os
import re
import resource
import shutil
import statistics
import subprocess
import sys
import tempfile
import time

import benchutil
from benchutil import children_cpu, cpu_busy_seconds


ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
CASE = "cases/clamped_beam.opts"
HEADING = "## Assembly throughput"
TARGET_JAC = 150000.0  # elements/s/core, the Jacobian target (plastic, element kernel + assembly)
TARGET_RES = 300000.0  # elements/s/core, the residual target

# (cells along x,y,z, repetitions). The box is 8 x 2 x 2; the largest mesh is 80x20x10 rather than
# 40x20x20 because its MUMPS factorisation is about half as expensive (same number of cells).
SIZES = [((20, 10, 10), 5), ((40, 20, 10), 5), ((80, 20, 10), 3)]
PARALLEL = ((40, 20, 10), 2, 3)  # cells, ranks, repetitions
VARIANTS = [("coo", "COO (MatSetValuesCOO, default)", ["-assembly_coo", "1"]), ("aij", "MatSetValues (AIJ)", ["-assembly_coo", "0"])]
STEP_ARGS = ["-load_steps", "8", "-load_max_steps", "2"]
FALLBACK_STEP_ARGS = ["-load_steps", "2"]
KERNEL_REPS = 5
KERNEL_SECONDS = 0.3  # per repetition and mode

KERNEL_C = r"""
/* Element-kernel-only throughput of hex8_element (no gather, no insertion).
   Written and compiled by scripts/bench_assembly.py in a temporary directory. */
#define _POSIX_C_SOURCE 199309L
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include "element_hex8.h"
#include "material_j2.h"

#define M 256 /* distinct elements cycled through */

static double now(void)
{
  struct timespec ts;
  clock_gettime(CLOCK_MONOTONIC, &ts);
  return ts.tv_sec + 1e-9 * ts.tv_nsec;
}

static double cpu(void) /* CPU time of this thread: not counting the time other processes hold the core */
{
  struct timespec ts;
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
  return ts.tv_sec + 1e-9 * ts.tv_nsec;
}

static double X[M][8][3], U1[M][8][3], U2[M][8][3], Ue[M][8][3];
static double H0[M][HEX8_NQP][J2_NHIST], H1[M][HEX8_NQP][J2_NHIST], Ht[M][HEX8_NQP][J2_NHIST];

int main(int argc, char **argv)
{
  const int      reps   = argc > 1 ? atoi(argv[1]) : 5;
  const double   target = argc > 2 ? atof(argv[2]) : 0.3; /* seconds per repetition */
  J2Params       mp;
  MaterialKernel mk;
  Hex8Options    eo = {1}; /* F-bar, as in the application's default */
  double         fe[24], ke[24 * 24], sink = 0;
  unsigned       seed = 12345;

  /* the material of cases/clamped_beam.opts, tolerances as set by the case reader */
  memset(&mp, 0, sizeof(mp));
  mp.E = 69004; mp.nu = 0.3; mp.law = HARDENING_SWIFT;
  mp.swK = 589; mp.sweps0 = 1e-4; mp.swn = 0.216; mp.rtol = 1e-12; mp.maxit = 50;
  if (J2ParamsSetup(&mp)) return 2;
  J2KernelInit(&mp, &mk); /* the J2 model through the material interface, as the application calls it */

  /* elements: 0.2 x 0.1 x 0.2 bricks with perturbed corners; deformation: shear + stretch */
  for (int e = 0; e < M; e++) {
    for (int a = 0; a < 8; a++) {
      const double sz[3] = {0.2, 0.1, 0.2};
      for (int i = 0; i < 3; i++) {
        seed = seed * 1103515245u + 12345u;
        const double r = ((seed >> 8) & 0xffff) / 65535.0 - 0.5;
        X[e][a][i] = 0.5 * sz[i] * (hex8_nodes[a][i] + 1) + 0.05 * sz[i] * r;
      }
    }
    for (int a = 0; a < 8; a++) {
      const double *x = X[e][a];
      seed = seed * 1103515245u + 12345u;
      const double r = 1 + 0.2 * (((seed >> 8) & 0xffff) / 65535.0 - 0.5);
      const double gu[3][3] = {{0.004, 0.0, 0.01}, {0.0, -0.002, 0.0}, {0.002, 0.0, -0.002}};
      for (int i = 0; i < 3; i++) {
        double s = 0;
        for (int k = 0; k < 3; k++) s += gu[i][k] * x[k];
        U1[e][a][i] = r * s;        /* first step: yields */
        U2[e][a][i] = 1.6 * r * s;  /* trial state from the committed first step: plastic */
        Ue[e][a][i] = 1e-3 * r * s; /* reference: elastic */
      }
    }
    for (int q = 0; q < HEX8_NQP; q++) J2HistoryInit(H0[e][q]);
  }
  int minpl = 8, minel = 8;
  for (int e = 0; e < M; e++) {
    ElementInfo info;
    if (hex8_element(&eo, &mk, X[e], U1[e], &H0[e][0][0], fe, NULL, &H1[e][0][0], &info) != MAT_OK) return 3;
    if (hex8_element(&eo, &mk, X[e], U2[e], &H1[e][0][0], fe, NULL, &Ht[e][0][0], &info) != MAT_OK) return 3;
    if (info.nplastic < minpl) minpl = info.nplastic;
    if (e == 0) printf("state committed_ep %.4e trial_ep %.4e\n", H1[0][0][J2_HIST_EP], Ht[0][0][J2_HIST_EP]);
    if (hex8_element(&eo, &mk, X[e], Ue[e], &H0[e][0][0], fe, NULL, &Ht[e][0][0], &info) != MAT_OK) return 3;
    if (8 - info.nplastic < minel) minel = 8 - info.nplastic;
  }
  printf("plastic_gauss_points_min %d\nelastic_gauss_points_min %d\n", minpl, minel);

  const char *names[4] = {"residual_plastic", "jacobian_plastic", "residual_elastic", "jacobian_elastic"};
  for (int mode = 0; mode < 4; mode++) {
    const int jac = mode & 1, plastic = mode < 2;
    double(*U)[8][3]                  = plastic ? U2 : Ue;
    double(*Hn)[HEX8_NQP][J2_NHIST]   = plastic ? H1 : H0;
    long passes = 1;
    for (;;) { /* calibration, also the warm-up */
      const double t0 = now();
      for (long p = 0; p < passes; p++)
        for (int e = 0; e < M; e++) {
          hex8_element(&eo, &mk, X[e], U[e], &Hn[e][0][0], fe, jac ? ke : NULL, &Ht[e][0][0], NULL);
          sink += fe[e % 24] + (jac ? ke[(7 * e) % 576] : 0);
        }
      const double dt = now() - t0;
      if (dt > 0.05 * target || passes > (1L << 30)) {
        passes = (long)(passes * target / dt) + 1;
        break;
      }
      passes *= 4;
    }
    for (int r = 0; r < reps; r++) {
      const double t0 = now(), c0 = cpu();
      for (long p = 0; p < passes; p++)
        for (int e = 0; e < M; e++) {
          hex8_element(&eo, &mk, X[e], U[e], &Hn[e][0][0], fe, jac ? ke : NULL, &Ht[e][0][0], NULL);
          sink += fe[e % 24] + (jac ? ke[(7 * e) % 576] : 0);
        }
      const double dt = now() - t0, dc = cpu() - c0;
      printf("kernel %s rep %d elements %ld seconds %.6f rate %.1f cpu_rate %.1f\n", names[mode], r, passes * M, dt, passes * M / dt, passes * M / dc);
    }
  }
  printf("checksum %.6e\n", sink);
  return 0;
}
"""


def log(msg):
    print(f"[bench {time.strftime('%H:%M:%S')}] {msg}", file=sys.stderr, flush=True)


def run_env():
    env = dict(os.environ)
    env.update(OPENBLAS_NUM_THREADS="1", OMPI_ALLOW_RUN_AS_ROOT="1", OMPI_ALLOW_RUN_AS_ROOT_CONFIRM="1")
    return env


def sh(cmd, **kw):
    """stdout of a command (stripped), or '' when it cannot be run"""
    try:
        return subprocess.run(cmd, capture_output=True, text=True, cwd=ROOT, timeout=120, **kw).stdout.strip()
    except (OSError, subprocess.SubprocessError):
        return ""


# ---------------------------------------------------------------------------------- build
def make_var(name):
    """the value of a variable of the project's Makefile, as make sees it"""
    with tempfile.NamedTemporaryFile("w", suffix=".mk", delete=False) as f:
        f.write("print-var-%:\n\t@echo $($*)\n")
        mk = f.name
    try:
        return sh(["make", "-s", "--no-print-directory", "-f", "Makefile", "-f", mk, f"print-var-{name}"])
    finally:
        os.unlink(mk)


def ensure_build(no_build):
    targets = ["bin/atrito", "build/lib.a"]
    missing = [t for t in targets if not os.path.exists(os.path.join(ROOT, t))]
    stale = subprocess.run(["make", "-q"] + targets, cwd=ROOT, capture_output=True).returncode != 0
    if no_build and not missing:
        return "used as found (--no-build)" + ("; make reports them out of date" if stale else "")
    if not missing and not stale:
        return "up to date"
    for attempt in range(4):
        log(f"make {' '.join(targets)} (attempt {attempt + 1})")
        r = subprocess.run(["make"] + targets, cwd=ROOT, capture_output=True, text=True)
        if r.returncode == 0:
            return "rebuilt by the script with make"
        log("make failed (someone may be mid-edit); retrying in 60 s:\n" + r.stderr[-2000:])
        time.sleep(60)
    if missing:
        sys.exit("bench_assembly: cannot build " + " ".join(missing))
    return "make failed; the existing, possibly stale, binaries were used"


SNAP = {}  # private copies of bin/atrito and build/lib.a (others may rebuild the tree meanwhile)


def snapshot_binaries(no_build):
    """copy bin/atrito and build/lib.a to a private directory once they look complete; retry while
    another build is writing them"""
    d = tempfile.mkdtemp(prefix="bench_bin_")
    for attempt in range(6):
        ok = True
        for rel in ("bin/atrito", "build/lib.a"):
            dst = os.path.join(d, os.path.basename(rel))
            try:
                shutil.copy2(os.path.join(ROOT, rel), dst)
                ok = ok and os.path.getsize(dst) > 0
            except OSError:
                ok = False
        if ok:
            try:
                r = subprocess.run([os.path.join(d, "atrito"), "-help", "intro"], cwd=ROOT, env=run_env(),
                                   capture_output=True, text=True, timeout=120)
                ok = r.returncode == 0
            except (OSError, subprocess.SubprocessError):
                ok = False
        if ok:
            SNAP.update(atrito=os.path.join(d, "atrito"), lib=os.path.join(d, "lib.a"), dir=d)
            return
        log("bin/atrito or build/lib.a incomplete (a build may be in progress); waiting 60 s")
        time.sleep(60)
        if not no_build:
            ensure_build(False)
    sys.exit("bench_assembly: no usable bin/atrito / build/lib.a")


def build_baseline(rev):
    """bin/atrito, build/lib.a and include/ of the revision rev, built in a temporary directory
    (git archive, then make with the revision's own Makefile); returns (dir, short commit)"""
    commit = sh(["git", "rev-parse", "--short", rev])
    if not commit:
        sys.exit(f"bench_assembly: unknown revision {rev}")
    d = tempfile.mkdtemp(prefix="bench_base_")
    a = subprocess.run(f"git archive {commit} | tar -x -C {d}", shell=True, cwd=ROOT, capture_output=True, text=True)
    if a.returncode != 0:
        sys.exit(f"bench_assembly: git archive {commit} failed: {a.stderr[-1000:]}")
    os.makedirs(os.path.join(d, "build"), exist_ok=True)
    open(os.path.join(d, "build", ".deps-ok"), "w").close()  # the dependencies are those of this machine
    log(f"building the baseline {commit} in {d}")
    r = subprocess.run(["make", "-j2", "bin/atrito", "build/lib.a"], cwd=d, capture_output=True, text=True)
    if r.returncode != 0:
        sys.exit(f"bench_assembly: the baseline {commit} does not build:\n{r.stderr[-3000:]}")
    return d, commit


# ---------------------------------------------------------------------------------- load by other processes
def timed_run(cmd, timeout):
    """subprocess.run with its wall time, the average number of cores that other processes used
    meanwhile, and the CPU time of the command itself"""
    b0, c0, t0 = cpu_busy_seconds(), children_cpu(), time.monotonic()
    r = subprocess.run(cmd, cwd=ROOT, env=run_env(), capture_output=True, text=True, timeout=timeout)
    wall = time.monotonic() - t0
    b1, c1 = cpu_busy_seconds(), children_cpu()
    other = max(0.0, ((b1 - b0) - (c1 - c0)) / wall) if b0 is not None and wall > 0 else None
    return r, wall, other, c1 - c0


# ---------------------------------------------------------------------------------- machine
def machine_info():
    return benchutil.machine_info(ROOT)


# ---------------------------------------------------------------------------------- application runs
EVENT_RE = re.compile(r"^(AtritoResidual|AtritoJacobian)\s+(\d+)\s+([\d.]+)\s+([\d.eE+-]+)\s+([\d.]+)", re.M)
MESH_RE = benchutil.MESH_RE
MEM_RE = re.compile(r"Maximum \(over computational time\) process memory:\s+total\s+([\d.eE+-]+)\s+max\s+([\d.eE+-]+)\s+min\s+([\d.eE+-]+)")
STEP_RE = re.compile(r"^step\s+(\d+)\s+time\s+([\d.]+)\s+its\s+(\d+)", re.M)
LUF_RE = re.compile(r"^(?:AtritoLUFactor|MatLUFactorNum)\s+(\d+)\s+[\d.]+\s+([\d.eE+-]+)", re.M)
PETSC_RE = re.compile(r"Petsc Release Version ([\d.]+)")
CPR_RE = re.compile(r"cells per rank:\s*([\d ]+)")


def atrito_cmd(cells, ranks, extra, outdir, step_args, exe=None):
    # orte_abort_on_non_zero_status 0: on the expected error exit mpiexec then waits for every rank
    # instead of killing the others, so that their CPU time is accounted (other-load measurement)
    cmd = [] if ranks == 1 else ["mpiexec", "--mca", "orte_abort_on_non_zero_status", "0", "-n", str(ranks)]
    cmd += [exe or SNAP["atrito"], "-options_file", CASE, "-box_cells", ",".join(map(str, cells))] + step_args
    cmd += ["-output_interval", "0", "-output_dir", outdir, "-log_view", "-memory_view"] + extra
    return cmd


def parse_run(out):
    ev = {m.group(1): (int(m.group(2)), float(m.group(4)), float(m.group(5))) for m in EVENT_RE.finditer(out)}
    mesh = MESH_RE.search(out)
    mem = MEM_RE.search(out)
    luf = LUF_RE.search(out)
    pv = PETSC_RE.search(out)
    cpr = CPR_RE.search(out)
    return dict(
        cells_per_rank=[int(x) for x in cpr.group(1).split()] if cpr else None,
        events=ev,
        cells=int(mesh.group(2)) if mesh else None,
        steps=[(int(a), float(b), int(c)) for a, b, c in STEP_RE.findall(out)],
        rss_total=float(mem.group(1)) if mem else None,
        rss_max=float(mem.group(2)) if mem else None,
        lu_time=float(luf.group(2)) if luf else None,
        petsc=pv.group(1) if pv else None,
    )


def run_atrito(cells, ranks, extra, notes, exe=None):
    """one run; returns the parsed record with the throughputs"""
    with tempfile.TemporaryDirectory(prefix="bench_assembly_") as outdir:
        cmd = atrito_cmd(cells, ranks, extra, outdir, STEP_ARGS, exe)
        r, wall, other, own = timed_run(cmd, 900)
        out, err = r.stdout, r.stderr
        rec = parse_run(out)
        mode = "max_steps"
        expected_stop = "-load_max_steps 2 reached" in err or "-load_max_steps 2 reached" in out
        if r.returncode != 0 and not expected_stop:
            sys.exit(f"bench_assembly: unexpected failure of {' '.join(cmd)}\n{err[-3000:]}\n{out[-3000:]}")
        if set(rec["events"]) != {"AtritoResidual", "AtritoJacobian"} or rec["rss_total"] is None:
            # -log_view not printed on the error exit: run to the end with two load steps instead
            notes.add("-log_view output was missing after the -load_max_steps stop; runs fell back to -load_steps 2")
            cmd = atrito_cmd(cells, ranks, extra, outdir, FALLBACK_STEP_ARGS, exe)
            r, wall, other, own = timed_run(cmd, 900)
            out, err = r.stdout, r.stderr
            rec = parse_run(out)
            mode = "to_end"
            if r.returncode != 0 or "done:" not in out or set(rec["events"]) != {"AtritoResidual", "AtritoJacobian"}:
                sys.exit(f"bench_assembly: fallback run failed: {' '.join(cmd)}\n{err[-3000:]}\n{out[-3000:]}")
    ncells = cells[0] * cells[1] * cells[2]
    if rec["cells"] != ncells:
        sys.exit(f"bench_assembly: expected {ncells} cells, the program reports {rec['cells']}")
    if len(rec["steps"]) != 2:
        sys.exit(f"bench_assembly: expected 2 converged load steps, got {rec['steps']}")
    for name in ("AtritoResidual", "AtritoJacobian"):
        count, tmax, _ = rec["events"][name]
        rec[name] = count * ncells / (tmax * ranks)
    rec["wall"] = wall
    rec["other"] = other
    # the share of a core each rank had over the run (its CPU time / wall time; 1 on a free machine):
    # the event times are wall times, so on a shared machine the rates divided by it estimate those
    # of a free core, if the process was held off the core evenly over the run
    rec["cpu_share"] = min(1.0, own / (wall * ranks)) if wall > 0 and own > 0 else None
    for name in ("AtritoResidual", "AtritoJacobian"):
        rec[name + "_cpu"] = rec[name] / rec["cpu_share"] if rec["cpu_share"] else None
    rec["mode"] = mode
    rec["rc"] = r.returncode
    return rec


QUIET = 0.3            # cores of load by other processes above which a run counts as disturbed
# time for waiting and re-running, per phase (s): kernel driver, before/after comparison, 1-rank runs, 2-rank runs
BUDGET = {"kernel": 20.0, "compare": 90.0, "serial": 60.0, "parallel": 45.0}
EXTRA = {"left": 0.0, "reruns": 0, "waited": 0.0}


def disturbed(rec):
    return rec.get("other") is not None and rec["other"] > QUIET


def free_threshold(ranks):
    """other load above which a run counts as disturbed. Not only oversubscription matters: on this
    2-vCPU machine one busy process on the other core slowed the 1-core kernel driver by up to ~30 %
    in trials (shared cache and memory bandwidth, perhaps one physical core), so the threshold is the
    same for any number of ranks"""
    return QUIET


def wait_quiet(threshold, max_wait=20.0):
    """wait (within the budget) until other processes use less than `threshold` cores; returns their load"""
    t0 = time.monotonic()
    while True:
        b0 = cpu_busy_seconds()
        time.sleep(0.5)
        b1 = cpu_busy_seconds()
        load = (b1 - b0) / 0.5 if b0 is not None else 0.0
        spent = time.monotonic() - t0
        if load < threshold or spent >= min(max_wait, EXTRA["left"]):
            if spent > 0.6:
                EXTRA["left"] -= spent
                EXTRA["waited"] += spent
            return load
        time.sleep(1.5)


def measured_run(cells, ranks, extra, notes, exe=None):
    """run_atrito on a machine as quiet as can be had: wait for quiet, and re-run once a run that
    other processes disturbed (while the budget lasts), keeping the less disturbed of the two"""
    thr = free_threshold(ranks)
    wait_quiet(thr)
    rec = run_atrito(cells, ranks, extra, notes, exe)
    if rec["other"] is not None and rec["other"] > thr and EXTRA["left"] > rec["wall"]:
        log(f"run disturbed (other load {rec['other']:.2f} cores); re-running")
        EXTRA["left"] -= rec["wall"]
        EXTRA["reruns"] += 1
        wait_quiet(thr)
        rec2 = run_atrito(cells, ranks, extra, notes, exe)
        if rec2["other"] is not None and rec2["other"] < rec["other"]:
            rec = rec2
    return rec


def summary(vals):
    return statistics.median(vals), min(vals), max(vals)


# ---------------------------------------------------------------------------------- kernel driver
def kernel_bench(reps, lib=None, inc=None):
    """the kernel driver against lib (default: the snapshot of build/lib.a) with the headers of inc
    (default: include/ of this tree)"""
    lib = lib or SNAP["lib"]
    cc = make_var("CC") or "mpicc"
    cppflags = make_var("CPPFLAGS")
    cflags = make_var("CFLAGS")
    ldlibs = make_var("LDLIBS")
    if not cflags or not ldlibs:  # fallback: the Makefile's flags as of writing
        petsc_c = sh(["pkg-config", "--cflags", "PETSc"])
        petsc_l = sh(["pkg-config", "--libs", "PETSc"])
        cppflags = f"-Iinclude {petsc_c} -I/usr/include/hdf5/openmpi"
        cflags = "-O3 -march=native -flto=auto -g -std=c11 -fno-math-errno"
        ldlibs = f"{petsc_l} -L/usr/lib/x86_64-linux-gnu/hdf5/openmpi -lhdf5 -lmetis -lm"
    tmp = tempfile.mkdtemp(prefix="bench_kernel_")
    try:
        src, exe = os.path.join(tmp, "kernel_bench.c"), os.path.join(tmp, "kernel_bench")
        with open(src, "w") as f:
            f.write(KERNEL_C)
        cpp = [("-I" + inc if (inc and f == "-Iinclude") else f) for f in cppflags.split()]
        cmd = [cc] + cpp + cflags.split() + [src, lib] + ldlibs.split() + ["-o", exe]
        r = subprocess.run(cmd, cwd=ROOT, capture_output=True, text=True)
        if r.returncode != 0:
            sys.exit("bench_assembly: kernel driver does not compile:\n" + " ".join(cmd) + "\n" + r.stderr[-3000:])
        r, _, other, _ = timed_run([exe, str(reps), str(KERNEL_SECONDS)], 600)
        if r.returncode != 0:
            sys.exit(f"bench_assembly: kernel driver failed (status {r.returncode}):\n{r.stdout}\n{r.stderr}")
    finally:
        shutil.rmtree(tmp, ignore_errors=True)
    rates, crates = {}, {}
    for m in re.finditer(r"^kernel (\S+) rep \d+ elements \d+ seconds [\d.]+ rate ([\d.]+) cpu_rate ([\d.]+)", r.stdout, re.M):
        rates.setdefault(m.group(1), []).append(float(m.group(2)))
        crates.setdefault(m.group(1), []).append(float(m.group(3)))
    res = {k: summary(v) for k, v in rates.items()}
    res["raw"] = rates
    res["cpu"] = {k: summary(v) for k, v in crates.items()}
    res["cpu_raw"] = crates
    res["plastic_gp_min"] = int(re.search(r"plastic_gauss_points_min (\d+)", r.stdout).group(1))
    res["elastic_gp_min"] = int(re.search(r"elastic_gauss_points_min (\d+)", r.stdout).group(1))
    st = re.search(r"state committed_ep (\S+) trial_ep (\S+)", r.stdout)
    res["state"] = (float(st.group(1)), float(st.group(2)))
    res["compile"] = " ".join([cc] + cflags.split())
    res["other"] = other
    return res


# ---------------------------------------------------------------------------------- plasticity check
def plastic_fraction(cells):
    """share of cells with plastic strain after steps 1 and 2 (needs h5py; None if unavailable)"""
    try:
        import h5py
    except ImportError:
        return None
    with tempfile.TemporaryDirectory(prefix="bench_plastic_") as outdir:
        cmd = [SNAP["atrito"], "-options_file", CASE, "-box_cells", ",".join(map(str, cells))] + STEP_ARGS
        cmd += ["-output_interval", "1", "-output_dir", outdir]
        subprocess.run(cmd, cwd=ROOT, env=run_env(), capture_output=True, text=True, timeout=600)
        fr = {}
        try:
            with h5py.File(os.path.join(outdir, "fields.h5"), "r") as f:
                for step in ("000001", "000002"):
                    a = f[f"steps/{step}/plastic_strain"][()]
                    fr[int(step)] = float((a > 0).mean())
        except (OSError, KeyError):
            return None
    return fr


# ---------------------------------------------------------------------------------- report
def fmt_rate(s):
    med, lo, hi = s
    return f"{med:,.0f} [{lo:,.0f} – {hi:,.0f}]"


def span(vals, fmt="{:.0f}"):
    """'a' or 'a – b' for a list of numbers"""
    lo, hi = min(vals), max(vals)
    return fmt.format(lo) if fmt.format(lo) == fmt.format(hi) else f"{fmt.format(lo)} – {fmt.format(hi)}"


def mib(x):
    return x / 2**20


def write_section(path, body):
    benchutil.write_doc_section(path, HEADING, body)

def qmed(recs, key="AtritoJacobian"):
    """median over the runs that other processes did not disturb, and their number"""
    q = [r[key] for r in recs if not disturbed(r)]
    return (statistics.median(q) if q else None), len(q)


def cmed_val(recs, key):
    v = [r.get(key + "_cpu") for r in recs]
    return statistics.median(v) if v and all(x is not None for x in v) else None


def cmed(recs, key):
    m = cmed_val(recs, key)
    return f"{m:,.0f}" if m is not None else "n/a"


def cshare(recs):
    v = [r.get("cpu_share") for r in recs]
    return f"{statistics.median(v):.2f}" if v and all(x is not None for x in v) else "n/a"


def qmed_str(recs):
    m, n = qmed(recs)
    return f"{m:,.0f} ({n})" if m is not None else "– (0)"


def cmp_table(cmp, mi):
    """the "Before and after" subsection from the alternating runs of the baseline and this code"""
    L = []
    A = L.append
    b, n = cmp["base_commit"], mi["commit"]
    cells = tuple(cmp["cells"])
    nc = cells[0] * cells[1] * cells[2]
    A("### Before and after\n")
    A(f"The baseline `{b}` (`--baseline`, built by the script from the repository in a temporary directory with "
      f"the same Makefile flags) against this code (`{n}`), alternating run by run in the same invocation: the kernel "
      f"driver {cmp['kernel_rounds']} times each ({KERNEL_REPS} repetitions per run, pooled), the full assembly "
      f"on the {nc:,}-cell mesh {cmp['reps']} times each per variant. Kernel rates by wall time and by the thread's "
      "CPU time (the latter does not count the time other processes held the core, so it is the steadier one on a "
      "shared machine). Medians [min – max].\n")
    A(f"| quantity (el/s/core) | before `{b}` | after `{n}` | after / before |")
    A("|---|---|---|---|")
    def row(label, vb, vn):
        sb, sn = summary(vb), summary(vn)
        A(f"| {label} | {fmt_rate(sb)} | {fmt_rate(sn)} | {sn[0] / sb[0]:.2f} |")
    kb, kn = cmp["kern_base"], cmp["kern_new"]
    for key, lab in (("jacobian_plastic", "Jacobian, plastic"), ("residual_plastic", "residual, plastic"),
                     ("jacobian_elastic", "Jacobian, elastic"), ("residual_elastic", "residual, elastic")):
        row(f"kernel alone, {lab} (wall)", kb["raw"][key], kn["raw"][key])
        row(f"kernel alone, {lab} (CPU time)", kb["cpu_raw"][key], kn["cpu_raw"][key])
    runs = cmp["runs"]
    for v, lab, _ in VARIANTS:
        rb, rn = runs.get(f"base/{v}", []), runs.get(f"new/{v}", [])
        if rb and rn:
            row(f"full assembly, {nc:,} cells, Jacobian, {lab}", [r["AtritoJacobian"] for r in rb], [r["AtritoJacobian"] for r in rn])
            if all(r.get("AtritoJacobian_cpu") for r in rb + rn):
                row(f"full assembly, {nc:,} cells, Jacobian, {lab}, / CPU share", [r["AtritoJacobian_cpu"] for r in rb], [r["AtritoJacobian_cpu"] for r in rn])
    allb = [r for k, rr in runs.items() if k.startswith("base/") for r in rr]
    alln = [r for k, rr in runs.items() if k.startswith("new/") for r in rr]
    if allb and alln:
        row(f"full assembly, {nc:,} cells, residual (all runs)", [r["AtritoResidual"] for r in allb], [r["AtritoResidual"] for r in alln])
        if all(r.get("AtritoResidual_cpu") for r in allb + alln):
            row(f"full assembly, {nc:,} cells, residual (all runs), / CPU share", [r["AtritoResidual_cpu"] for r in allb], [r["AtritoResidual_cpu"] for r in alln])
    oth = [r["other"] for r in allb + alln if r.get("other") is not None] + [x for x in cmp.get("kernel_other", []) if x is not None]
    if oth:
        A("")
        A(f"Other processes' load during these runs: {min(oth):.2f} to {max(oth):.2f} cores (median {statistics.median(oth):.2f}); "
          f"load average (1 min) {cmp['load'][0]:.2f} before, {cmp['load'][1]:.2f} after.")
    A("")
    return L


def build_report(mi, build_state, results, par, kern, pfrac, notes, t_total, load0, load1, petsc_v, sizes, par_cfg, cmp=None):
    L = []
    A = L.append
    A(HEADING + "\n")
    A(f"Written by `scripts/bench_assembly.py` on {mi['date']} (total script time {t_total / 60:.1f} min); "
      "rerun it to regenerate this section (`/usr/bin/python3 scripts/bench_assembly.py`).\n")
    allrecs = [r for recs in list(results.values()) + list(par.values()) for r in recs]
    nover = sum(1 for (c, v), recs in results.items() for r in recs if r["other"] is not None and r["other"] > free_threshold(1))
    nover += sum(1 for recs in par.values() for r in recs if r["other"] is not None and r["other"] > free_threshold(par_cfg[1]))
    kdist = kern.get("other") is not None and kern["other"] > QUIET
    if 3 * nover > len(allrecs) or kdist:
        A(f"**Caution:** {nover} of the {len(allrecs)} runs ({'and also' if kdist else 'but not'} "
          "the kernel driver) ran while other processes loaded the machine (last column of the first table, and the "
          "notes); their figures are too low. Rerun the script on a quiet machine.\n")
    A("### Machine and software\n")
    A(f"- CPU: {mi['cpu']}, {mi['cores']} cores visible to the OS, {mi['mem']} memory, Linux {mi['kernel']}")
    A(f"- Compiler: `mpicc` → {mi['cc']}; flags `{kern['compile'].split(' ', 1)[1]}` (from the Makefile)")
    A(f"- PETSc {petsc_v or mi['petsc_pc']} (Debian package), LU by MUMPS, BLAS `{mi['blas']}` with `OPENBLAS_NUM_THREADS=1`")
    A(f"- MPI: {mi['mpi']} (default binding; `--mca orte_abort_on_non_zero_status 0` so that mpiexec waits for "
      "both ranks on the expected error exit and their CPU time is accounted)")
    dirty = f"; uncommitted changes in {', '.join('`' + d + '`' for d in mi['dirty'])}" if mi["dirty"] else ""
    A(f"- Code: commit `{mi['commit']}`{dirty}; binaries {build_state}")
    A(f"- Load average (1 min) before / after the benchmark: {load0:.2f} / {load1:.2f}. Other jobs share this "
      "2-core machine; the load they caused during each run is given in the last column of the first table\n")

    A("### Method\n")
    A(f"- Case: `{CASE}` (cantilever block 8 × 2 × 2 clamped at x = 0, tip sheared and pulled; finite-strain J2 "
      "with Swift hardening, F-bar hex8, 2×2×2 Gauss points), `-box_cells` as in the tables, "
      f"`{' '.join(STEP_ARGS)} -output_interval 0 -log_view -memory_view`. Each run does two converged load steps of "
      "1/8 of the load and then stops with the expected error `-load_max_steps 2 reached`; `-log_view` and "
      "`-memory_view` are still printed on that exit"
      + (" — except in some runs, see the notes below." if any("fell back" in n for n in notes) else "."))
    if pfrac:
        A(f"- Plasticity is active: in a check run of the {sizes[0][0][0]}×{sizes[0][0][1]}×{sizes[0][0][2]} mesh, "
          f"{100 * pfrac[1]:.1f} % of the cells carry plastic strain after step 1 and {100 * pfrac[2]:.1f} % after step 2.")
    A("- Timed: the PETSc log events `AtritoResidual` and `AtritoJacobian`. Each covers one full assembly over "
      "the local cells: gather of the element displacements, the element kernel with the material return maps, "
      "and the insertion (residual: scatter into the local vector and `DMLocalToGlobal`; Jacobian: `MatZeroEntries`, "
      "`MatSetValues` per element and `MatAssemblyBegin/End`, or with `-assembly_coo 1` the copy into the COO value "
      "array and one `MatSetValuesCOO`). The count includes the evaluations of the tangent predictor and of the "
      "Newton iterations (column \"Evaluations per run\").")
    A("- Other processes' load: (busy CPU time of the whole machine from /proc/stat − CPU time of the benchmark's "
      f"own processes) / wall time of the run, in cores. Runs above {QUIET} are counted as disturbed: their numbers are "
      f"pessimistic (kernel driver: {kern['other']:.2f})."
      if kern.get("other") is not None else "- Other processes' load: not available.")
    A("- Throughput in elements/s/core = count × total cells / (maximum time over ranks × ranks). On one rank "
      "this is simply count × cells / time.")
    A("- CPU share: the CPU time of the run's own processes / (wall time × ranks), the share of a core each rank "
      "had on average (1 on a free machine). The event times are wall times; divided by the CPU share, the rates "
      "estimate those of a free core, assuming the process was held off its core evenly over the run (the "
      "assembly and the factorisation alike). On 2 ranks MPI's busy waiting counts as CPU time, so there the "
      "share says little.")
    A(f"- Repetitions: {sizes[0][1]} run(s) per configuration ({sizes[-1][1]} for the largest mesh, {par_cfg[2]} on "
      f"{par_cfg[1]} ranks), the two variants "
      "alternating; the tables give the median and [min – max] over the runs. Peak memory is the median over the runs "
      "of `-memory_view`'s \"Maximum (over computational time) process memory\" (resident set size, the whole "
      "process, dominated by the MUMPS factors, not by the assembly).")
    if tuple(sizes[-1][0]) == (80, 20, 10):
        A("- The largest mesh is 80×20×10 rather than 40×20×20: same number of cells, about half the LU time, which "
          "keeps the whole script within about 10 minutes on 2 cores.")
    A(f"- Element kernel alone: a C driver compiled at run time in a temporary directory against `build/lib.a` "
      f"calls `hex8_element` (F-bar on, the case's material) in a loop over 256 distinct perturbed bricks, with and "
      f"without the tangent `ke`; no gather, no insertion. Plastic state: history committed after one plastic step, "
      f"then a trial state 1.6 times further (all 8 Gauss points return-map in every element, e.g. committed "
      f"ε_p = {kern['state'][0]:.2e}, trial ε_p = {kern['state'][1]:.2e} at one point); elastic state for "
      f"reference. About {KERNEL_SECONDS} s per repetition after a warm-up, {KERNEL_REPS} repetitions, median.\n")

    A("### Full assembly (real code path)\n")
    A("| Cells (mesh) | Jacobian assembly | Ranks | Runs | Residual el/s/core median [min – max] | "
      "Jacobian el/s/core median [min – max] | Jacobian median of the quiet runs (other load < 0.3), (n) | "
      "CPU share of a core (median) | Residual / CPU share (median) | Jacobian / CPU share (median) | "
      "Evaluations per run (res./Jac.) | Peak RSS per rank, MiB | LU factorisation share of wall time | Other processes' load, cores (max over runs) |")
    A("|---|---|---|---|---|---|---|---|---|---|---|---|---|---|")
    rows = [(c, v, 1, recs) for (c, v), recs in results.items()] + [(c, v, par_cfg[1], recs) for (c, v), recs in par.items()]
    vlabel = {k: lab for k, lab, _ in VARIANTS}
    for cells, v, ranks, recs in rows:
        n = cells[0] * cells[1] * cells[2]
        res = summary([r["AtritoResidual"] for r in recs])
        jac = summary([r["AtritoJacobian"] for r in recs])
        ev = recs[0]["events"]
        rss = statistics.median([r["rss_max"] for r in recs])
        lus = statistics.median([r["lu_time"] / r["wall"] for r in recs if r["lu_time"]]) if all(r["lu_time"] for r in recs) else None
        A(f"| {n:,} ({cells[0]}×{cells[1]}×{cells[2]}) | {vlabel[v]} | {ranks} | {len(recs)} | {fmt_rate(res)} | "
          f"{fmt_rate(jac)} | {qmed_str(recs)} | {cshare(recs)} | {cmed(recs, 'AtritoResidual')} | {cmed(recs, 'AtritoJacobian')} | "
          f"{ev['AtritoResidual'][0]} / {ev['AtritoJacobian'][0]} | {mib(rss):,.0f}"
          + (f" (total {mib(statistics.median([r['rss_total'] for r in recs])):,.0f})" if ranks > 1 else "")
          + f" | {'%.0f %%' % (100 * lus) if lus is not None else 'n/a'} | "
          + (f"{max(r['other'] for r in recs):.2f}" if all(r["other"] is not None for r in recs) else "n/a") + " |")
    A("")
    A("### Element kernel alone (`hex8_element`, no gather, no insertion, 1 core)\n")
    A("| State | Residual el/s median [min – max] | Jacobian el/s median [min – max] | Residual, by CPU time | Jacobian, by CPU time |")
    A("|---|---|---|---|---|")
    kc = kern.get("cpu", {})
    cr = lambda k: fmt_rate(kc[k]) if k in kc else "n/a"
    A(f"| plastic (8 of 8 Gauss points return-map) | {fmt_rate(kern['residual_plastic'])} | {fmt_rate(kern['jacobian_plastic'])} | {cr('residual_plastic')} | {cr('jacobian_plastic')} |")
    A(f"| elastic (reference) | {fmt_rate(kern['residual_elastic'])} | {fmt_rate(kern['jacobian_elastic'])} | {cr('residual_elastic')} | {cr('jacobian_elastic')} |")
    A("")
    if cmp:
        L.extend(cmp_table(cmp, mi))

    # cost split per element for the serial runs
    kj = kern["jacobian_plastic"][0]
    kr = kern["residual_plastic"][0]
    A("### Where the Jacobian time goes (1 rank, medians)\n")
    A("Time per element = 1 / throughput. \"Rest\" = full assembly minus the kernel alone: gather, the permutation "
      "copy of the element matrix, the insertion and the final matrix assembly (plus any difference between the "
      "benchmark's all-plastic state and the real mix of plastic and elastic points).\n")
    if kern.get("other") is not None and kern["other"] > QUIET:
        A(f"The kernel driver ran with {kern['other']:.2f} cores of other load, so its time is overstated and this "
          "split is unreliable (a negative rest is the sign of it).\n")
    A("| Cells | Jacobian assembly | Jacobian µs/element | of which kernel | rest (share) |")
    A("|---|---|---|---|---|")
    split = {}
    for (cells, v), recs in results.items():
        jm = statistics.median([r["AtritoJacobian"] for r in recs])
        t, tk = 1e6 / jm, 1e6 / kj
        split[(cells, v)] = (t, tk)
        A(f"| {cells[0] * cells[1] * cells[2]:,} | {vlabel[v]} | {t:.1f} | {tk:.1f} | {t - tk:.1f} ({100 * (t - tk) / t:.0f} %) |")
    A("")

    # against the target
    A(f"### Against the targets (1 core: Jacobian ≥ {TARGET_JAC:,.0f}, residual ≥ {TARGET_RES:,.0f} elements/s)\n")
    best_key, best = max(((k, statistics.median([r["AtritoJacobian"] for r in recs])) for k, recs in results.items()), key=lambda x: x[1])
    par_best = max((statistics.median([r["AtritoJacobian"] for r in recs]) for recs in par.values()), default=None)
    aij = {c: statistics.median([r["AtritoJacobian"] for r in recs]) for (c, v), recs in results.items() if v == "aij"}
    coo = {c: statistics.median([r["AtritoJacobian"] for r in recs]) for (c, v), recs in results.items() if v == "coo"}
    met = best >= TARGET_JAC
    A(f"- {'Met' if met else 'Not met'}. The best Jacobian median is {best:,.0f} elements/s/core "
      f"({vlabel[best_key[1]]}, {best_key[0][0] * best_key[0][1] * best_key[0][2]:,} cells), "
      f"{100 * best / TARGET_JAC:.0f} % of the target"
      + (f" ({TARGET_JAC / best:.2f}× short)." if not met else "."))
    if aij and coo:
        A(f"- With COO assembly (the default) the Jacobian medians are "
          + ", ".join(f"{coo[c]:,.0f}" for c in sorted(coo, key=lambda c: c[0] * c[1] * c[2]))
          + f" el/s/core over the mesh sizes ({span([100 * x / TARGET_JAC for x in coo.values()])} % of the target); "
          "with MatSetValues/AIJ (`-assembly_coo 0`) "
          + ", ".join(f"{aij[c]:,.0f}" for c in sorted(aij, key=lambda c: c[0] * c[1] * c[2]))
          + f" ({span([100 * x / TARGET_JAC for x in aij.values()])} %).")
    cj = {k: cmed_val(recs, "AtritoJacobian") for k, recs in results.items()}
    cr_ = {k: cmed_val(recs, "AtritoResidual") for k, recs in results.items()}
    if all(x is not None for x in list(cj.values()) + list(cr_.values())):
        A(f"- Divided by the CPU share (an estimate of a free core, see the method): Jacobian, COO "
          + ", ".join(f"{cj[k]:,.0f}" for k in sorted(cj, key=lambda k: k[0][0] * k[0][1] * k[0][2]) if k[1] == "coo")
          + ", AIJ " + ", ".join(f"{cj[k]:,.0f}" for k in sorted(cj, key=lambda k: k[0][0] * k[0][1] * k[0][2]) if k[1] == "aij")
          + f" el/s/core (best {max(cj.values()):,.0f}, {100 * max(cj.values()) / TARGET_JAC:.0f} % of the target); residual "
          + ", ".join(f"{cr_[k]:,.0f}" for k in sorted(cr_, key=lambda k: (k[0][0] * k[0][1] * k[0][2], k[1])))
          + f" (best {max(cr_.values()):,.0f}, {100 * max(cr_.values()) / TARGET_RES:.0f} %).")
    resm = {k: statistics.median([r["AtritoResidual"] for r in recs]) for k, recs in results.items()}
    rbest_key = max(resm, key=resm.get)
    A(f"- Residual: {'met' if resm[rbest_key] >= TARGET_RES else 'not met'}; medians "
      + ", ".join(f"{resm[k]:,.0f}" for k in sorted(resm, key=lambda k: (k[0][0] * k[0][1] * k[0][2], k[1])))
      + f" el/s/core over the meshes and variants (best {resm[rbest_key]:,.0f}, {100 * resm[rbest_key] / TARGET_RES:.0f} % of the target).")
    shares_aij = [100 * (t - tk) / t for (c, v), (t, tk) in split.items() if v == "aij"]
    shares_coo = [100 * (t - tk) / t for (c, v), (t, tk) in split.items() if v == "coo"]
    A(f"- The element kernel alone (plastic state) reaches {kj:,.0f} Jacobians/s on one core "
      f"({100 * kj / TARGET_JAC:.0f} % of the target"
      + ("" if kj >= TARGET_JAC else "; so even with free insertion the target is not reachable without a faster kernel — "
         f"it has to become at least {TARGET_JAC / kj:.2f}× faster, and more to leave room for the insertion")
      + (f"; for the target with the COO insertion measured here the kernel would have to reach about "
         f"{1e6 / (1e6 / TARGET_JAC - min(t - tk for (c, v), (t, tk) in split.items() if v == 'coo')):,.0f}/s"
         if any(v == "coo" for (c, v) in split) and 1e6 / TARGET_JAC > min(t - tk for (c, v), (t, tk) in split.items() if v == "coo") else "")
      + f"); residual kernel {kr:,.0f}/s. The elastic-state kernel reaches {kern['jacobian_elastic'][0]:,.0f} Jacobians/s, "
      f"so the return map and its consistent tangent cost about "
      f"{100 * (1 / kj - 1 / kern['jacobian_elastic'][0]) / (1 / kj):.0f} % of the plastic kernel time.")
    if shares_aij and shares_coo:
        dom = lambda sh: "the kernel dominates" if max(sh) < 40 else ("gather + insertion dominate" if min(sh) > 60 else "kernel and the rest about even")
        A(f"- What dominates: with AIJ, gather + insertion + assembly take {span(shares_aij)} % of the Jacobian time "
          f"({dom(shares_aij)}); with COO {span(shares_coo)} % ({dom(shares_coo)}). The kernel share is estimated "
          "with the all-plastic kernel benchmark, so if fewer points return-map in the real run the kernel share is "
          "somewhat overstated.")
    for v in ("aij", "coo"):
        ks = sorted((c for (c, vv) in results if vv == v), key=lambda c: c[0] * c[1] * c[2])
        if len(ks) > 1:
            q = {c: qmed(results[(c, v)])[0] for c in ks}
            use_q = all(x is not None for x in q.values())
            d = q if use_q else {c: statistics.median([r["AtritoJacobian"] for r in results[(c, v)]]) for c in ks}
            A(f"- Size dependence ({vlabel[v]}): from {ks[0][0] * ks[0][1] * ks[0][2]:,} to {ks[-1][0] * ks[-1][1] * ks[-1][2]:,} "
              f"cells the Jacobian median {'of the quiet runs ' if use_q else ''}changes by "
              f"{100 * (d[ks[-1]] / d[ks[0]] - 1):+.0f} % (" + ", ".join(f"{d[c]:,.0f}" for c in ks) + ")"
              + ("." if use_q else "; some of these runs were disturbed by other processes."))
    if par_best is not None:
        ser = coo.get(par_cfg[0]) if par else None
        parts, losses = [], []
        cprs = [tuple(r["cells_per_rank"]) for recs in par.values() for r in recs if r.get("cells_per_rank")]
        imb = max(max(c) / min(c) for c in cprs) if cprs and all(min(c) > 0 for c in cprs) else None
        for (c, v), recs in par.items():
            pm = statistics.median([r["AtritoJacobian"] for r in recs])
            sm = statistics.median([r["AtritoJacobian"] for r in results.get((c, v), [])]) if (c, v) in results else None
            if sm:
                parts.append(f"{vlabel[v]}: {pm:,.0f} el/s/core = {100 * pm / sm:.0f} % of the 1-rank figure")
                losses.append(1 - pm / sm)
        if parts:
            A(f"- On {par_cfg[1]} ranks ({par_cfg[0][0] * par_cfg[0][1] * par_cfg[0][2]:,} cells) the per-core Jacobian "
              "throughput is " + "; ".join(parts) + ". The time is the slower rank's (the assembly ends in a collective, "
              "so both ranks' event times include the wait for the slower one)"
              + (f"; the cells are split {' / '.join(f'{x:,}' for x in cprs[0])} over the ranks"
                 + (": equal shares of the cells." if imb < 1.02 else f" (max/min {imb:.2f}).")
                 if imb is not None else ".")
              + (" Both variants lose about the same share although only AIJ communicates off-rank entries at "
                 "every assembly (PETSc's stash; COO arranges that once at preallocation), which points to the two "
                 "ranks slowing each other through shared hardware, as other processes do (see the notes), "
                 "rather than to the insertion."
                 if len(losses) == 2 and abs(losses[0] - losses[1]) < 0.08 else
                 " With AIJ the entries of rows owned by the other rank go through PETSc's stash and are "
                 "communicated in MatAssemblyBegin/End at every assembly; COO assembly arranges that once at "
                 "preallocation.")
              + (" Some of these runs shared the cores with other processes (last column of the first table), "
                 "which on 2 ranks of a 2-core machine directly slows them: take these figures as lower bounds."
                 if any(disturbed(r) for recs in par.values() for r in recs) else ""))
    ratios = [statistics.median([r["AtritoResidual"] for r in recs]) / statistics.median([r["AtritoJacobian"] for r in recs])
              for recs in list(results.values()) + list(par.values())]
    lus = [r["lu_time"] / r["wall"] for recs in list(results.values()) + list(par.values()) for r in recs if r["lu_time"]]
    A(f"- The residual assembly runs at {span(ratios, '{:.1f}')}× the Jacobian's throughput. Over the whole run, the "
      f"LU factorisation (MUMPS, `AtritoLUFactor` or `MatLUFactorNum`) takes {span([100 * x for x in lus])} % of the wall time "
      "(last column of the first table).")
    ndist = sum(1 for r in allrecs if disturbed(r))
    notes = set(notes)
    notes.add(f"Disturbance by other processes: before each run the script waited for other load below {QUIET} "
              f"cores (at most 20 s per wait), and re-ran once a run with more, keeping the less disturbed of the "
              f"two, within a time budget ({', '.join(f'{k} {v:.0f} s' for k, v in BUDGET.items())}): "
              f"{EXTRA['waited']:.0f} s waited, {EXTRA['reruns']} re-run(s); {ndist} of the {len(allrecs)} kept runs "
              f"ran with other load above {QUIET} cores"
              + (f", and so did the kernel driver ({kern['other']:.2f})" if kdist else "")
              + ". Even a 1-rank run is affected: with one other busy process on the second core the kernel driver "
              "ran up to about 30 % slower in trials on this machine (shared cache and memory bandwidth; the two "
              "virtual CPUs may share a physical core)."
              + (" Wide ranges in the tables come from such runs; the medians are less affected, and the column "
                 "\"Jacobian median of the quiet runs\" leaves them out." if ndist else ""))
    A("\n### Notes\n")
    for n in sorted(notes):
        A(f"- {n}")
    A("")
    return "\n".join(L) + "\n"


# ---------------------------------------------------------------------------------- main
def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--output", default=os.path.join(ROOT, "doc", "notes", "performance-log.md"))
    ap.add_argument("--no-build", action="store_true", help="do not run make; use the binaries as found")
    ap.add_argument("--quick", action="store_true", help="smoke test: smallest mesh, one run each (for checking the script)")
    ap.add_argument("--from-json", metavar="FILE", help="only rewrite the report from the raw results of an earlier run")
    ap.add_argument("--reps", type=int, metavar="N", help="repetitions of every configuration (default: 5, 3 for the largest mesh and on 2 ranks)")
    ap.add_argument("--baseline", metavar="REV", help="also measure the revision REV against this code, alternating (a 'Before and after' table)")
    args = ap.parse_args()
    if args.from_json:
        with open(args.from_json) as f:
            raw = json.load(f)
        tup = lambda c: tuple(c)
        results = {(tup(c), v): recs for c, v, recs in raw["results"]}
        par = {(tup(c), v): recs for c, v, recs in raw["par"]}
        kern = {k: (tuple(v) if isinstance(v, list) else v) for k, v in raw["kern"].items()}
        pfrac = {int(k): v for k, v in raw["pfrac"].items()} if raw["pfrac"] else None
        sizes = [(tup(c), n) for c, n in raw["sizes"]]
        pc = raw["par_cfg"]
        EXTRA.update(raw.get("extra", {}))
        body = build_report(raw["mi"], raw["build_state"], results, par, kern, pfrac, set(raw["notes"]), raw["t_total"],
                            raw["load0"], raw["load1"], raw["petsc_v"], sizes, (tup(pc[0]), pc[1], pc[2]), raw.get("cmp"))
        write_section(args.output, body)
        log(f"wrote {args.output} from {args.from_json}")
        return

    t_start = time.monotonic()
    os.chdir(ROOT)
    load0 = os.getloadavg()[0]
    build_state = ensure_build(args.no_build)
    snapshot_binaries(args.no_build)
    mi = machine_info()
    sizes = [(SIZES[0][0], 1)] if args.quick else [(c, args.reps or n) for c, n in SIZES]
    par_cfg = (SIZES[0][0], 2, 1) if args.quick else ((PARALLEL[0], PARALLEL[1], args.reps) if args.reps else PARALLEL)
    kreps = 2 if args.quick else KERNEL_REPS
    notes = set()

    log("kernel-only driver")
    EXTRA["left"] = BUDGET["kernel"]
    wait_quiet(free_threshold(1))
    kern = kernel_bench(kreps)
    if kern["other"] is not None and kern["other"] > free_threshold(1) and EXTRA["left"] > 10:
        log(f"kernel driver disturbed (other load {kern['other']:.2f} cores); re-running")
        EXTRA["left"] -= 8
        EXTRA["reruns"] += 1
        wait_quiet(free_threshold(1))
        k2 = kernel_bench(kreps)
        if k2["other"] is not None and k2["other"] < kern["other"]:
            kern = k2
    if kern["plastic_gp_min"] != 8:
        notes.add(f"the kernel benchmark's plastic state had only {kern['plastic_gp_min']} of 8 plastic Gauss points in some element")
    log(f"kernel: jacobian {kern['jacobian_plastic'][0]:,.0f}/s residual {kern['residual_plastic'][0]:,.0f}/s")

    pfrac = plastic_fraction(sizes[0][0])

    cmp = None
    if args.baseline:
        bdir, bcommit = build_baseline(args.baseline)
        cmp = dict(base_commit=bcommit, cells=list(sizes[0][0]), reps=sizes[0][1], kernel_rounds=2, runs={},
                   kernel_other=[], load=[os.getloadavg()[0], None])
        kb, kn = {"raw": {}, "cpu_raw": {}}, {"raw": {}, "cpu_raw": {}}
        EXTRA["left"] = BUDGET["compare"]
        for rnd in range(cmp["kernel_rounds"]):
            for who, lib, inc, acc in (("base", os.path.join(bdir, "build", "lib.a"), os.path.join(bdir, "include"), kb),
                                       ("new", None, None, kn)):
                wait_quiet(free_threshold(1))
                k = kernel_bench(kreps, lib, inc)
                cmp["kernel_other"].append(k.get("other"))
                for f in ("raw", "cpu_raw"):
                    for key, v in k[f].items():
                        acc[f].setdefault(key, []).extend(v)
                log(f"kernel {who} round {rnd + 1}: jacobian {k['jacobian_plastic'][0]:,.0f}/s residual {k['residual_plastic'][0]:,.0f}/s")
        cmp["kern_base"], cmp["kern_new"] = kb, kn
        bexe = os.path.join(bdir, "bin", "atrito")
        for rep in range(cmp["reps"]):
            for key, _, extra in VARIANTS:
                for who, exe in (("base", bexe), ("new", None)):
                    wait_quiet(free_threshold(1))
                    rec = run_atrito(sizes[0][0], 1, extra, notes, exe)
                    cmp["runs"].setdefault(f"{who}/{key}", []).append(rec)
                    log(f"compare {who} {key} run {rep + 1}: res {rec['AtritoResidual']:,.0f} jac {rec['AtritoJacobian']:,.0f} el/s/core")
        cmp["load"][1] = os.getloadavg()[0]
        shutil.rmtree(bdir, ignore_errors=True)

    results, petsc_v = {}, None
    EXTRA["left"] = BUDGET["serial"]
    for cells, reps in sizes:
        for rep in range(reps):
            for key, _, extra in VARIANTS:
                rec = measured_run(cells, 1, extra, notes)
                petsc_v = petsc_v or rec["petsc"]
                results.setdefault((cells, key), []).append(rec)
                log(f"{cells} {key} run {rep + 1}/{reps}: res {rec['AtritoResidual']:,.0f} jac {rec['AtritoJacobian']:,.0f} "
                    f"el/s/core, wall {rec['wall']:.1f} s")
    par = {}
    EXTRA["left"] = BUDGET["parallel"]
    pcells, pranks, preps = par_cfg
    for rep in range(preps):
        for key, _, extra in VARIANTS:
            rec = measured_run(pcells, pranks, extra, notes)
            par.setdefault((pcells, key), []).append(rec)
            log(f"{pcells} {key} {pranks} ranks run {rep + 1}/{preps}: res {rec['AtritoResidual']:,.0f} "
                f"jac {rec['AtritoJacobian']:,.0f} el/s/core, wall {rec['wall']:.1f} s")
    if any(r["mode"] == "to_end" for recs in list(results.values()) + list(par.values()) for r in recs):
        notes.add("some runs were made to the end with -load_steps 2 because -log_view was missing on the error exit")
    load1 = os.getloadavg()[0]
    t_total = time.monotonic() - t_start
    raw = dict(mi=mi, build_state=build_state, kern=kern, pfrac=pfrac, notes=sorted(notes), t_total=t_total, extra=EXTRA, cmp=cmp,
               load0=load0, load1=load1, petsc_v=petsc_v, sizes=sizes, par_cfg=par_cfg,
               results=[[list(c), v, recs] for (c, v), recs in results.items()],
               par=[[list(c), v, recs] for (c, v), recs in par.items()])
    rawpath = os.path.join(tempfile.gettempdir(), "bench_assembly_last.json")
    with open(rawpath, "w") as f:
        json.dump(raw, f)
    log(f"raw results in {rawpath} (--from-json {rawpath} rewrites the report from them)")
    body = build_report(mi, build_state, results, par, kern, pfrac, notes, t_total, load0, load1, petsc_v, sizes, par_cfg, cmp)
    write_section(args.output, body)
    shutil.rmtree(SNAP["dir"], ignore_errors=True)
    log(f"wrote {args.output} in {t_total:.0f} s")


if __name__ == "__main__":
    main()
