#!/usr/bin/python3
"""Projection cost on meshed tool surfaces from 1e2 to 1e6 facets (doc/performance.md, section
"Meshed tool surfaces").

A unit sphere triangulated from an octahedron (8 k^2 triangles, k = 4 ... 354) is written as a
binary STL; scripts/bench_tool_facets.c (compiled here against build/lib.a: run `make` first) reads
it as a tool and times ToolProject and ToolProjectHint on points within 5 % of the radius of the
surface, raw facets and smoothed (Nagata), one core: the queries in random order, and sorted
along a Morton curve (spatially coherent, as the nodes of a mesh come).

  /usr/bin/python3 scripts/bench_tool_facets.py [--ks 4,11,35,112,354] [--queries 200000]
"""
import argparse
import os
import resource
import struct
import subprocess
import sys
import tempfile

import numpy as np

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


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--ks", default="4,11,35,112,354")
    ap.add_argument("--queries", type=int, default=200000)
    a = ap.parse_args()
    exe = os.path.join(ROOT, "build", "bench_tool_facets")
    pc = lambda *x: subprocess.check_output(["pkg-config"] + list(x) + ["PETSc"], text=True).split()
    h5 = "/usr/lib/x86_64-linux-gnu/hdf5/openmpi"
    subprocess.check_call(["mpicc", "-O3", "-march=native", "-std=c11", "-I" + os.path.join(ROOT, "include")] + pc("--cflags") +
                          [os.path.join(ROOT, "scripts", "bench_tool_facets.c"), os.path.join(ROOT, "build", "lib.a"), "-o", exe] + pc("--libs") +
                          ["-L" + h5 + "/lib", "-L" + h5, "-lhdf5", "-ldmumps", "-lmumps_common", "-lmetis", "-lm"])
    print("| facets | smoothing | build (s) | bytes per facet | ToolProject, random order (us) | ToolProjectHint, random (us) | ToolProject, coherent order (us) | ToolProjectHint, coherent (us) | peak memory (MB) |")
    print("|---|---|---|---|---|---|---|---|---|")
    with tempfile.TemporaryDirectory() as d:
        for k in [int(x) for x in a.ks.split(",")]:
            path = os.path.join(d, "sphere_%d.stl" % k)
            sphere_stl(path, k)
            for smooth in (0, 1):
                cmd = ["/usr/bin/time", "-f", "%M", exe, "-tool_names", "s", "-tool_s_file", path, "-tool_s_smooth", str(smooth), "-bench_queries", str(a.queries)]
                r = subprocess.run(cmd, capture_output=True, text=True, env=dict(os.environ, OMPI_ALLOW_RUN_AS_ROOT="1", OMPI_ALLOW_RUN_AS_ROOT_CONFIRM="1"))
                if r.returncode:
                    sys.exit(r.stderr)
                nf, tb, bpf, tr, thr, tc, thc, sm, _ = r.stdout.split()
                mem = int(r.stderr.strip().splitlines()[-1]) / 1024.0
                print("| %s | %s | %s | %s | %.2f | %.2f | %.2f | %.2f | %.0f |" % (nf, "Nagata" if smooth else "raw", tb, bpf, float(tr) / 1e3, float(thr) / 1e3, float(tc) / 1e3, float(thc) / 1e3, mem))
                sys.stdout.flush()


if __name__ == "__main__":
    main()
