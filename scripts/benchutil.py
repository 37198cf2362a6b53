"""Helpers shared by the measurement scripts (bench_assembly.py, bench_pairing.py, bench_memory.py,
scaling.py, sweep.py)."""
import datetime
import os
import re
import resource
import shutil
import subprocess
import sys
import tempfile
import time


def _proc_stat_cpu():
    """the machine-wide CPU tick counters of /proc/stat (user, nice, system, idle, iowait, irq,
    softirq, steal, ...), or None"""
    try:
        with open("/proc/stat") as f:
            return [int(x) for x in f.readline().split()[1:]]
    except (OSError, ValueError):
        return None


def cpu_busy_seconds():
    """busy CPU seconds of the whole machine since boot (all cores), or None"""
    v = _proc_stat_cpu()
    if v is None:
        return None
    busy = v[0] + v[1] + v[2] + (v[5] if len(v) > 5 else 0) + (v[6] if len(v) > 6 else 0)
    return busy / os.sysconf("SC_CLK_TCK")


def cpu_steal_seconds():
    """CPU seconds the hypervisor took from this virtual machine since boot (all cores), or None"""
    v = _proc_stat_cpu()
    return v[7] / os.sysconf("SC_CLK_TCK") if v is not None and len(v) > 7 else None


def children_cpu():
    """CPU seconds of the finished child processes"""
    ru = resource.getrusage(resource.RUSAGE_CHILDREN)
    return ru.ru_utime + ru.ru_stime


# the mesh line (vertices, hexahedra), the run's summary line (steps, Newton iterations, cuts,
# seconds) and -memory_view's peak (total over the ranks, the largest rank), as the code prints them
MESH_RE = re.compile(r"^mesh:\s+(\d+) vertices,\s+(\d+) hexahedra", re.M)
DONE_RE = re.compile(r"^done: (\d+) steps, (\d+) Newton iterations, (\d+) cuts, ([\d.]+) s", re.M)
MEM_RE = re.compile(r"Maximum \(over computational time\) process memory:\s+total\s+([\d.eE+-]+)\s+max\s+([\d.eE+-]+)")


def log_event_time(text, name, stage=None):
    """the max time over the ranks of a -log_view event, or None when absent; with stage (e.g.
    "Solve"), only that log stage's table is read (the code's stages: Main Stage, Mesh, Setup,
    Solve)"""
    if stage is not None:
        part = re.split(r"^--- Event Stage \d+: " + re.escape(stage) + r"\s*$", text, maxsplit=1, flags=re.M)
        if len(part) < 2:
            return None
        text = part[1].split("--- Event Stage", 1)[0]
    m = re.search(r"^" + re.escape(name) + r"\s+\d+\s+[\d.]+\s+([\d.eE+-]+)", text, re.M)
    return float(m.group(1)) if m else None


def write_doc_section(path, heading, body, keep_written=False):
    """replace the section `heading` of a Markdown file (to the next '## ' heading or the end) with
    body, keeping every other section; append it when absent; written atomically. With
    keep_written, the old section's '### ' subsections whose headings body does not have (written
    by hand after a run: analyses, later measurements) are kept, in their order, after body."""
    text = ""
    if os.path.exists(path):
        with open(path) as f:
            text = f.read()
    lines = text.splitlines(keepends=True)
    start = next((i for i, l in enumerate(lines) if l.rstrip() == heading), None)
    if start is None:
        new = ("# Performance\n\n" + body) if not text.strip() else text.rstrip("\n") + "\n\n" + body
    else:
        end = next((i for i in range(start + 1, len(lines)) if lines[i].startswith("## ")), len(lines))
        tail = "".join(lines[end:])
        if keep_written:
            own = {l.rstrip() for l in body.splitlines() if l.startswith("### ")}
            subs = [i for i in range(start + 1, end) if lines[i].startswith("### ")] + [end]
            kept = ["".join(lines[a:b]).rstrip("\n") for a, b in zip(subs, subs[1:]) if lines[a].rstrip() not in own]
            if kept:
                body = body.rstrip("\n") + "\n\n" + "\n\n".join(kept) + "\n"
        new = "".join(lines[:start]) + body.rstrip("\n") + "\n" + ("\n" + tail if tail else "")
    os.makedirs(os.path.dirname(os.path.abspath(path)), exist_ok=True)
    tmp = path + ".tmp"
    with open(tmp, "w") as f:
        f.write(new)
    os.replace(tmp, path)


def snapshot_binary(path, where, wait=120.0, who="benchmark", note=print):
    """a private copy of the program, once it exists and has not changed for a few seconds (others
    may be rebuilding the tree), checked to start; returns (copy, its directory, source mtime)"""
    t0 = time.time()
    d = tempfile.mkdtemp(prefix=".atrito_bin_", dir=where)
    env = dict(os.environ, OMPI_ALLOW_RUN_AS_ROOT="1", OMPI_ALLOW_RUN_AS_ROOT_CONFIRM="1")
    while True:
        try:
            st = os.stat(path)
            if time.time() - st.st_mtime > 3 and st.st_size > 0:
                dst = os.path.join(d, "atrito")
                shutil.copy2(path, dst)
                if os.stat(path).st_mtime == st.st_mtime:
                    r = subprocess.run([dst, "-help", "intro"], env=env, capture_output=True, timeout=60)
                    if r.returncode == 0:
                        return dst, d, st.st_mtime
        except (OSError, subprocess.SubprocessError):
            pass
        if time.time() - t0 > wait:
            shutil.rmtree(d, ignore_errors=True)
            sys.exit(f"{who}: {path} is missing or keeps changing (run make)")
        note(f"waiting for {path} (missing or being rebuilt)")
        time.sleep(5)


def run_env():
    """environment of a measured run: one BLAS thread per rank, Open MPI allowed as root"""
    env = dict(os.environ)
    env.update(OMPI_ALLOW_RUN_AS_ROOT="1", OMPI_ALLOW_RUN_AS_ROOT_CONFIRM="1", OPENBLAS_NUM_THREADS="1", OMP_NUM_THREADS="1")
    return env


def _sh(cmd, cwd):
    try:
        return subprocess.run(cmd, capture_output=True, text=True, cwd=cwd, timeout=60).stdout.strip()
    except (OSError, subprocess.SubprocessError):
        return ""


def machine_info(root):
    """the machine and the source state a measurement ran on (cpu, cores, threads_per_core, virt,
    mem, cc, mpi, petsc_pc, blas, kernel, commit, dirty: changed files under src, include,
    Makefile; date)"""
    info = dict(cpu="unknown", cores=os.cpu_count() or 1, mem="unknown")
    try:
        with open("/proc/cpuinfo") as f:
            for line in f:
                if line.startswith("model name"):
                    info["cpu"] = line.split(":", 1)[1].strip()
                    break
    except OSError:
        pass
    try:
        with open("/proc/meminfo") as f:
            kb = int(re.search(r"MemTotal:\s+(\d+)", f.read()).group(1))
        info["mem"] = f"{kb / 1024**2:.1f} GiB"
    except (OSError, AttributeError):
        pass
    lscpu = _sh(["lscpu"], root)
    m = re.search(r"Thread\(s\) per core:\s+(\d+)", lscpu)
    info["threads_per_core"] = int(m.group(1)) if m else None
    info["virt"] = "KVM virtual machine" if "KVM" in lscpu else ""
    info["cc"] = (_sh(["mpicc", "--version"], root).splitlines() or ["unknown"])[0]
    info["mpi"] = (_sh(["mpiexec", "--version"], root).splitlines() or ["unknown"])[0]
    info["petsc_pc"] = _sh(["pkg-config", "--modversion", "PETSc"], root) or "unknown"
    blas = "/etc/alternatives/libblas.so.3-x86_64-linux-gnu"
    info["blas"] = os.path.realpath(blas) if os.path.exists(blas) else "unknown"
    info["kernel"] = _sh(["uname", "-r"], root)
    info["commit"] = _sh(["git", "rev-parse", "--short", "HEAD"], root) or "unknown"
    dirty = _sh(["git", "status", "--porcelain", "--", "src", "include", "Makefile"], root)
    info["dirty"] = [l[3:] for l in dirty.splitlines() if len(l) > 3]
    info["date"] = datetime.datetime.now().astimezone().strftime("%Y-%m-%d %H:%M %Z")
    return info


def build_and_snapshot(root, work, who, note=print):
    """make all (exits on failure), then a private copy of bin/atrito in work (snapshot_binary)"""
    if subprocess.run(["make", "-s", "all"], cwd=root).returncode:
        sys.exit(f"{who}: make failed")
    return snapshot_binary(os.path.join(root, "bin", "atrito"), work, who=who, note=note)[0]


def measured_by(script, root):
    """the first line of a measurement section: script, date, machine, commit"""
    mi = machine_info(root)
    return (f"Measured by `scripts/{script}` on {mi['date']}: {mi['cpu']}, {mi['cores']} cores, {mi['mem']}; "
            f"commit {mi['commit']}{' (with local changes)' if mi['dirty'] else ''}.")
