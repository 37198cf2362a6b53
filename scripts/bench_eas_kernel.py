#!/usr/bin/python3
"""Element-kernel throughput of hex8_eas against the F-bar hex8: elements per second per core for
the residual (force only) and the Jacobian (force and tangent), with the same J2 material
(Swift hardening of cases/clamped_beam.opts) in a plastic and an elastic state.

  /usr/bin/python3 scripts/bench_eas_kernel.py [--reps 7] [--seconds 0.3]

A C driver is compiled in a temporary directory (not in the repository) against build/lib.a with
the Makefile's flags (as scripts/bench_assembly.py does for hex8 alone) and times the element
kernels alone: no gather, no insertion. 256 distorted bricks (0.2 x 0.1 x 0.2, corners moved by up
to 2.5 % of the sides) are cycled through; the states are those of bench_assembly.py: a first
step (yields) committed, then the plastic trial state from it (every Gauss point plastic), and an
elastic state from the virgin history. hex8_eas runs its local Newton on the nine enhanced
parameters from the committed ones at every evaluation, as in the application (its iteration
count is printed). The two elements alternate repetition by repetition (same machine load for
both). Prints one line per element, state and kind: median, min and max of the
repetitions, and the average number of cores other processes used meanwhile.
"""
import argparse
import os
import re
import shutil
import statistics
import subprocess
import sys
import tempfile

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from bench_assembly import ROOT, make_var, timed_run  # noqa: E402

DRIVER = r"""
#define _POSIX_C_SOURCE 199309L
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include "element_hex8.h"
#include "element_hex8_eas.h"
#include "material_j2.h"

#define M 256
#define NH (HEX8_NQP * J2_NHIST + HEX8_EAS_NALPHA) /* room for either element's history */

static double now(void)
{
  struct timespec ts;
  clock_gettime(CLOCK_MONOTONIC, &ts);
  return ts.tv_sec + 1e-9 * ts.tv_nsec;
}

static double X[M][8][3], U1[M][8][3], U2[M][8][3], Ue[M][8][3];
static double H0[M][NH], H1[2][M][NH], Ht[M][NH]; /* H1: committed first step, per element type */
static Hex8Options    fo = {1};        /* F-bar, the application's default */
static Hex8EASOptions ea = {20, 1e-10}; /* -fe_eas_max_it, -fe_eas_rtol defaults */
static MaterialKernel mk;

static int elem(int eas, int e, double (*u)[3], const double *hn, double *fe, double *ke, double *h, ElementInfo *info, Hex8EASTrace *tr)
{
  return eas ? hex8_eas_element(&ea, &mk, X[e], u, hn, fe, ke, h, info, tr) : hex8_element(&fo, &mk, X[e], u, hn, fe, ke, h, info);
}

int main(int argc, char **argv)
{
  const int    reps   = argc > 1 ? atoi(argv[1]) : 7;
  const double target = argc > 2 ? atof(argv[2]) : 0.3;
  J2Params     mp;
  double       fe[24], ke[24 * 24], sink = 0;
  unsigned     seed = 12345;

  memset(&mp, 0, sizeof(mp));
  mp.E = 69004; mp.nu = 0.3; mp.law = HARDENING_SWIFT;
  mp.swK = 589; mp.sweps0 = 1e-4; mp.swn = 0.216; mp.rtol = 1e-12; mp.maxit = 50;
  if (J2ParamsSetup(&mp)) return 2;
  J2KernelInit(&mp, &mk);

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
        U1[e][a][i] = r * s;
        U2[e][a][i] = 1.6 * r * s;
        Ue[e][a][i] = 1e-3 * r * s;
      }
    }
  }
  const char *names[4] = {"residual_plastic", "jacobian_plastic", "residual_elastic", "jacobian_elastic"};
  const char *els[2]    = {"hex8_fbar", "hex8_eas"};
  for (int eas = 0; eas < 2; eas++) {
    int minpl = 8, minel = 8, nitp = 0, nite = 0;
    for (int e = 0; e < M; e++) {
      ElementInfo  info;
      Hex8EASTrace tr;
      memset(H0[e], 0, sizeof(H0[e]));
      for (int q = 0; q < HEX8_NQP; q++) J2HistoryInit(&H0[e][q * J2_NHIST]);
      if (elem(eas, e, U1[e], H0[e], fe, ke, H1[eas][e], &info, &tr) != MAT_OK) return 3;
      if (elem(eas, e, U2[e], H1[eas][e], fe, ke, Ht[e], &info, &tr) != MAT_OK) return 3;
      if (info.nplastic < minpl) minpl = info.nplastic;
      if (eas) nitp += tr.nit;
      if (elem(eas, e, Ue[e], H0[e], fe, ke, Ht[e], &info, &tr) != MAT_OK) return 3;
      if (8 - info.nplastic < minel) minel = 8 - info.nplastic;
      if (eas) nite += tr.nit;
    }
    printf("%s plastic_gauss_points_min %d elastic_gauss_points_min %d local_newton_mean_plastic %.2f elastic %.2f\n", els[eas], minpl, minel, (double)nitp / M, (double)nite / M);
  }
  /* the two elements alternate repetition by repetition, so that both see the same machine load */
  for (int mode = 0; mode < 4; mode++) {
    const int jac = mode & 1, plastic = mode < 2;
    double(*U)[8][3] = plastic ? U2 : Ue;
    long passes[2];
    for (int eas = 0; eas < 2; eas++) {
      double(*Hn)[NH] = plastic ? H1[eas] : H0;
      passes[eas]     = 1;
      for (;;) { /* calibration, also the warm-up */
        const double t0 = now();
        for (long p = 0; p < passes[eas]; p++)
          for (int e = 0; e < M; e++) {
            elem(eas, e, U[e], Hn[e], fe, jac ? ke : NULL, Ht[e], NULL, NULL);
            sink += fe[e % 24] + (jac ? ke[(7 * e) % 576] : 0);
          }
        const double dt = now() - t0;
        if (dt > 0.05 * target || passes[eas] > (1L << 30)) {
          passes[eas] = (long)(passes[eas] * target / dt) + 1;
          break;
        }
        passes[eas] *= 4;
      }
    }
    for (int r = 0; r < reps; r++)
      for (int eas = 0; eas < 2; eas++) {
        double(*Hn)[NH] = plastic ? H1[eas] : H0;
        const double t0 = now();
        for (long p = 0; p < passes[eas]; p++)
          for (int e = 0; e < M; e++) {
            elem(eas, e, U[e], Hn[e], fe, jac ? ke : NULL, Ht[e], NULL, NULL);
            sink += fe[e % 24] + (jac ? ke[(7 * e) % 576] : 0);
          }
        const double dt = now() - t0;
        printf("kernel %s %s rep %d rate %.1f\n", els[eas], names[mode], r, passes[eas] * M / dt);
      }
  }
  printf("checksum %.6e\n", sink);
  return 0;
}
"""


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--reps", type=int, default=7)
    ap.add_argument("--seconds", type=float, default=0.3, help="per repetition")
    a = ap.parse_args()
    lib = os.path.join(ROOT, "build", "lib.a")
    if not os.path.exists(lib):
        sys.exit("bench_eas_kernel: build/lib.a missing (make all)")
    cc = make_var("CC") or "mpicc"
    cppflags, cflags, ldlibs = make_var("CPPFLAGS"), make_var("CFLAGS"), make_var("LDLIBS")
    tmp = tempfile.mkdtemp(prefix="bench_eas_")
    try:
        shutil.copy2(lib, os.path.join(tmp, "lib.a"))  # a private copy: the tree may be rebuilt meanwhile
        src, exe = os.path.join(tmp, "drv.c"), os.path.join(tmp, "drv")
        with open(src, "w") as f:
            f.write(DRIVER)
        cmd = [cc] + cppflags.split() + cflags.split() + [src, os.path.join(tmp, "lib.a")] + ldlibs.split() + ["-o", exe]
        r = subprocess.run(cmd, cwd=ROOT, capture_output=True, text=True)
        if r.returncode != 0:
            sys.exit("bench_eas_kernel: the driver does not compile:\n" + " ".join(cmd) + "\n" + r.stderr[-3000:])
        r, wall, other, _ = timed_run([exe, str(a.reps), str(a.seconds)], 1200)
        if r.returncode != 0:
            sys.exit(f"bench_eas_kernel: driver failed ({r.returncode}):\n{r.stdout}\n{r.stderr}")
    finally:
        shutil.rmtree(tmp, ignore_errors=True)
    print(f"compiler: {cc} {cflags}")
    for line in r.stdout.splitlines():
        if not line.startswith("kernel"):
            print(line)
    rates = {}
    for m in re.finditer(r"^kernel (\S+) (\S+) rep \d+ rate ([\d.]+)", r.stdout, re.M):
        rates.setdefault((m.group(1), m.group(2)), []).append(float(m.group(3)))
    print(f"{'element':10s} {'kind':18s} {'median':>10s} {'min':>10s} {'max':>10s}  (elements/s, {a.reps} repetitions)")
    for (el, kind), v in rates.items():
        print(f"{el:10s} {kind:18s} {statistics.median(v):10.0f} {min(v):10.0f} {max(v):10.0f}")
    pair = {}
    for m in re.finditer(r"^kernel (\S+) (\S+) rep (\d+) rate ([\d.]+)", r.stdout, re.M):
        pair.setdefault((m.group(2), m.group(3)), {})[m.group(1)] = float(m.group(4))
    for kind in ("residual_plastic", "jacobian_plastic", "residual_elastic", "jacobian_elastic"):
        f, e = statistics.median(rates[("hex8_fbar", kind)]), statistics.median(rates[("hex8_eas", kind)])
        pr = [d["hex8_fbar"] / d["hex8_eas"] for (k, _), d in pair.items() if k == kind]
        print(f"ratio hex8_fbar / hex8_eas {kind}: {f / e:.2f} (of the medians); per repetition pair: median {statistics.median(pr):.2f}, min {min(pr):.2f}, max {max(pr):.2f}")
    print(f"wall {wall:.1f} s; other processes used {other:.2f} cores on average" if other is not None else f"wall {wall:.1f} s")
    print("load average (1, 5, 15 min): " + open("/proc/loadavg").read().split(" ", 3)[:3].__str__())


if __name__ == "__main__":
    main()
