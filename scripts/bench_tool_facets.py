#!/usr/bin/python3
"""Projection cost on meshed tool surfaces from 1e2 to 1e6 facets (doc/notes/performance-log.md,
section "Meshed tool surfaces"; quoted in doc/performance.md).

A unit sphere triangulated from an octahedron (8 k^2 triangles, k = 4 ... 354) is written as a
binary STL; scripts/bench_tool_facets.c (compiled here against build/lib.a: run `make` first) reads
it as a tool and times ToolProject and ToolProjectHint on points within 5 % of the radius of the
surface, raw facets and smoothed (Nagata), one core: the queries in random order, and sorted
along a Morton curve (spatially coherent, as the nodes of a mesh come).

  /usr/bin/python3 scripts/bench_tool_facets.py [--ks 4,11,35,112,354] [--queries 200000]
                                                [--repeat 1] [--cputime]
                                                [--output doc/notes/performance-log.md]
Prints the table and writes the section "## Meshed tool surfaces" of the output file, keeping its
other sections (--output '' : print only).
"""
import argparse
import os
import resource
import struct
import subprocess
import sys
import tempfile

import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import benchutil  # noqa: E402

ROOT = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..")


def sphere_stl(path, k):
    O = np.array([[1, 0, 0], [-1, 0, 0], [0, 1, 0], [0, -1, 0], [0, 0, 1], [0, 0, -1]], float)
    Fc = [(0, 2, 4), (2, 1, 4), (1, 3, 4), (3, 0, 4), (2, 0, 5), (1, 2, 5), (3, 1, 5), (0, 3, 5)]
    tris = []
    for a, b, c in Fc:
        i, j = np.meshgrid(np.arange(k + 1), np.arange(k + 1), indexing="ij")
        P = O[a][None, None, :] + (O[b] - O[a])[None, None, :] * i[..., None] / k + (O[c] - O[a])[None, None, :] * j[..., None] / k
        P /= np.linalg.norm(P, axis=2)[..., None]
        ii, jj = np.meshgrid(np.arange(k), np.arange(k), indexing="ij")
        lo = (ii + jj) < k
        t1 = np.stack([P[ii, jj], P[ii + 1, jj], P[ii, jj + 1]], axis=2)[lo]
        hi = (ii + jj) < k - 1
        t2 = np.stack([P[ii + 1, jj], P[ii + 1, jj + 1], P[ii, jj + 1]], axis=2)[hi]
        tris.append(t1)
        tris.append(t2)
    T = np.concatenate(tris).astype(np.float32)
    rec = np.zeros(len(T), dtype=[("n", "<f4", 3), ("v", "<f4", (3, 3)), ("a", "<u2")])
    rec["v"] = T
    with open(path, "wb") as fp:
        fp.write(b"bench sphere".ljust(80, b" "))
        fp.write(struct.pack("<I", len(T)))
        fp.write(rec.tobytes())
    return len(T)


NOTE = ("The warm start (src/tool/facets.c, `FacetsClosestHint`): the hint's facet f at distance d, if its star certificate (below) holds; else a greedy walk from it over the neighbours gives a facet f at distance d; "
        "if d + r (r the search radius: d raw, d + 2δ + τ smoothed) is below f's clearance (a lower bound, computed when the tool is built, of the "
        "distance from the triangle to every triangle outside its star, the facets sharing a vertex with it), every facet within r shares a vertex "
        "with f and f's star alone gives the result (read from the facet lists of f's three vertices): a node near the surface evaluates its own dozen facets, whatever the tool's size. Otherwise "
        "the bucket grid (cells about twice a facet's size, each listing the facets whose box meets it) holds every facet within d in the cells that meet "
        "the cube y ± d, and when that cube spans at most 27 cells those cells give the result; otherwise (a node farther than about one cell from "
        "the surface, or a smoothed coarse surface whose bound d + 2δ is wide) the hierarchy is searched from its root with the bound. The result "
        "is ToolProject's bit for bit (tests/test_tool.c). Near contact (±0.1 % R) the star decides almost every query, and the facets a query "
        "evaluates no longer grow with the tool; its time still does at 1e6 facets: the 20000 nodes are spread over a tool of about 120 MB, and "
        "the cache lines a node touches (its facets, their vertices and neighbours, its star) are no longer cached from the previous pass "
        "(with 2000 nodes the hinted raw pass cost about the same at 1e6 facets as at 128). At ±5 % R most nodes of the finer spheres are "
        "many cells away, beyond their facet's clearance, and take the hierarchy, whose cost grows with the tool."
        " On a machine shared with other work (busy cores near the machine's count) the rows are measured at different loads and, by the wall time, their ratios are not reliable (`--cputime`: the thread's processor time): doc/notes/tools-log.md, *Cost*, gives medians of interleaved runs of the code before and after the star certificate and before and after the smaller tool.")


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--ks", default="4,11,35,112,354")
    ap.add_argument("--queries", type=int, default=200000)
    ap.add_argument("--repeat", type=int, default=1, help="runs per row; the table gives each column's median")
    ap.add_argument("--output", default=os.path.join(ROOT, "doc", "notes", "performance-log.md"))
    ap.add_argument("--cputime", action="store_true", help="time by the thread's processor time (bench_tool_facets -bench_cputime): on a machine shared with other work, the wall time counts the waits for a core")
    a = ap.parse_args()
    exe = os.path.join(ROOT, "build", "bench_tool_facets")
    pc = lambda *x: subprocess.check_output(["pkg-config"] + list(x) + ["PETSc"], text=True).split()
    h5 = "/usr/lib/x86_64-linux-gnu/hdf5/openmpi"
    subprocess.check_call(["mpicc", "-O3", "-march=native", "-std=c11", "-I" + os.path.join(ROOT, "include")] + pc("--cflags") +
                          [os.path.join(ROOT, "scripts", "bench_tool_facets.c"), os.path.join(ROOT, "build", "lib.a"), "-o", exe] + pc("--libs") +
                          ["-L" + h5 + "/lib", "-L" + h5, "-lhdf5", "-ldmumps", "-lmumps_common", "-lmetis", "-lm"])
    rows, vals = [], []
    busy0 = benchutil.cpu_busy_seconds()
    import time
    t0 = time.time()
    head = ("| facets | smoothing | build (s) | bytes per facet | ToolProject, random order (us) | ToolProject, coherent order (us) | "
            "node passes at ±5 % R: ToolProject (us) | node passes at ±5 % R: ToolProjectHint (us) | node passes at ±0.1 % R: ToolProject (us) | node passes at ±0.1 % R: ToolProjectHint (us) | peak memory (MB) |\n"
            "|---|---|---|---|---|---|---|---|---|---|---|")
    print(head)
    with tempfile.TemporaryDirectory() as d:
        for k in [int(x) for x in a.ks.split(",")]:
            path = os.path.join(d, "sphere_%d.stl" % k)
            sphere_stl(path, k)
            for smooth in (0, 1):
                cmd = ["/usr/bin/time", "-f", "%M", exe, "-tool_names", "s", "-tool_s_file", path, "-tool_s_smooth", str(smooth), "-bench_queries", str(a.queries)] + (["-bench_cputime"] if a.cputime else [])
                runs = []
                for _ in range(a.repeat):
                    r = subprocess.run(cmd, capture_output=True, text=True, env=dict(os.environ, OMPI_ALLOW_RUN_AS_ROOT="1", OMPI_ALLOW_RUN_AS_ROOT_CONFIRM="1"))
                    if r.returncode:
                        sys.exit(r.stderr)
                    runs.append(r.stdout.split() + [r.stderr.strip().splitlines()[-1]])
                med = lambda i: float(np.median([float(x[i]) for x in runs]))
                nf, bpf = runs[0][0], runs[0][2]
                tb = "%.3f" % med(1)
                mem = med(13) / 1024.0
                us = [med(i) / 1e3 for i in (3, 5, 8, 9, 10, 11)]
                vals.append((int(nf), smooth, *us, float(bpf)))
                rows.append("| %s | %s | %s | %s | %s | %.0f |" % (nf, "Nagata" if smooth else "raw", tb, bpf, " | ".join("%.2f" % x for x in us), mem))
                print(rows[-1])
                sys.stdout.flush()
    wall = time.time() - t0
    busy1 = benchutil.cpu_busy_seconds()
    busy = (busy1 - busy0) / wall if busy0 is not None and busy1 is not None else float("nan")
    if a.output:
        commit = subprocess.run(["git", "-C", ROOT, "rev-parse", "--short", "HEAD"], capture_output=True, text=True).stdout.strip()
        cpu = next((l.split(":", 1)[1].strip() for l in open("/proc/cpuinfo") if l.startswith("model name")), "?")
        body = ["## Meshed tool surfaces", "", "Measured by `scripts/bench_tool_facets.py` on %s: %s, %d cores; commit %s; %d queries per row, one core%s%s; busy cores of the machine during the run, this benchmark's included: %.2f (mean)." % (time.strftime("%Y-%m-%d %H:%M UTC", time.gmtime()), cpu, os.cpu_count(), commit, a.queries, ", each entry the median of %d runs" % a.repeat if a.repeat > 1 else "", "; times: the thread's processor time (`--cputime`), not the wall time" if a.cputime else "", busy), "",
                "A unit sphere triangulated from an octahedron (8 k² triangles) read from a binary STL as a `facets` tool. Single queries: points uniformly in direction at 0.95 R to 1.05 R from the centre, `ToolProject` (the hierarchy from its root) in random order and in a spatially coherent order (sorted along a Morton curve). Node passes, as the contact object pairs its slave nodes: %d nodes (one tenth of the queries) uniformly in direction at R (1 ± 5 %%) or, near contact, R (1 ± 0.1 %%), taken in a Morton order, each moving by up to 1e-3 R per pass, 10 timed passes after a first one; `ToolProject` from the root, or `ToolProjectHint` with the node's previous result as the hint (as `Pair` in src/contact/contact.c); time per node and pass. Raw facets: the closest triangle. Nagata: the smoothed surface (candidates within d + 2δ + τ, Newton on each). Bytes per facet: the tool's storage (`FacetsBytes`: vertices, connectivity, neighbours, corner normals, edge flags, hierarchy, stars and clearances, bucket grid) over the triangles; peak memory: the process's maximum resident size (reading the file and building the tool included; PETSc's own about 40 MB)." % max(a.queries // 10, 1000), "",
                head] + rows + ["",
                ]
        for smooth in (0, 1):
            v = [x for x in vals if x[1] == smooth]
            if len(v) < 2:
                continue
            lo, hi = v[0], v[-1]
            for col, what in ((3, "coherent order, from the root"), (5, "node passes at ±5 % R with the hint"), (7, "node passes at ±0.1 % R with the hint")):
                body.append("%s, %s: %.2f µs at %d facets, %.2f µs at %d (ratio %.1f; target: ratio ≤ 2 and ≤ 5 µs at 1e6: %s)." % ("Nagata" if smooth else "Raw facets", what, lo[col], lo[0], hi[col], hi[0], hi[col] / lo[col], "met" if hi[col] / lo[col] <= 2 and hi[col] <= 5 else "not met"))
                body.append("")
        bmin, bmax = min(x[8] for x in vals), max(x[8] for x in vals)
        body.append("Tool storage: %.0f to %.0f bytes per facet from %d to %d facets (target: at most 200 at every size: %s)." % (bmin, bmax, vals[0][0], vals[-1][0], "met" if bmax <= 200 else "not met"))
        body.append("")
        body.append(NOTE)
        benchutil.write_doc_section(a.output, "## Meshed tool surfaces", "\n".join(body) + "\n")


if __name__ == "__main__":
    main()
