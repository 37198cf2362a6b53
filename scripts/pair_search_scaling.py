#!/usr/bin/env python3
"""The candidate search of contact pairs between bodies (SideCandidates of src/contact/pair.c) over
16 to 1024 ranks, from METIS partitions of a large two-body mesh, without running it. Writes the
section "## Contact between bodies" of doc/scaling-model.md.

usage: scripts/pair_search_scaling.py [--lower 200,12] [--upper 250,8] [--parts 1,16,32,...,1024]
                                      [--reps 5] [--indenter 200,20,100,20,30 | --indenter none]

scripts/pair_search_scaling.c (built here with mpicc against METIS) makes the mesh: a lower slab of
NX x NX x NZ hexahedra on [0, 100]^2 and an upper slab of NX' x NX' x NZ' over the whole interface
(non-matching: 250 slave nodes a side on 200 master faces), the slave set the upper slab's bottom
vertices, the master faces the lower slab's top faces; partitions it as the code does
(METIS_PartMeshDual, 4 common nodes, seed 7; a shared vertex owned by the highest-numbered part
around it, as DMPlexDistribute without -partition_balance contact) and computes per part what
SideCandidates does at the first step (search distance 2 d_max): the slave nodes, the candidate
faces received, the parts they come from, the per-node loop's pairs (slave nodes x candidates),
the owner's box tests (its faces x the parts with slave nodes) and the faces it needs (within the
search distance of one of its slave nodes); it times on the slowest parts (the thread's CPU time,
median of --reps; the 1-part run once) the per-node lists of SideCandidates at 985c96c (a double
loop over the slave nodes and the candidates) and at 98b559a (a bin grid), the owner's test of
both (every owned face against every rank's box) and that test with the owner's faces' overall box
tried first (a fix suggested, not in the code). --indenter: the same for a square indenter (NX, NZ of
the slab, NX', NZ', width) on a thicker slab, reported in one sentence.
"""
import argparse
import os
import re
import subprocess
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(HERE)
sys.path.insert(0, HERE)
import benchutil  # noqa: E402

HEADING = "## Contact between bodies"
OLD, NEW = "985c96c", "98b559a"  # the commits whose SideCandidates scripts/pair_search_scaling.c reproduces
L = 100.0
# the assembly's unit costs of this page (## Unit costs), used when they cannot be read from it
T_JAC, T_RES = 5.47e-6, 3.19e-6


def build(work):
    exe = os.path.join(work, "pair_search_scaling")
    subprocess.run(["mpicc", "-O3", "-march=native", "-fno-math-errno", "-std=c11", os.path.join(HERE, "pair_search_scaling.c"),
                    "-o", exe, "-lmetis", "-lm"], check=True)
    return exe


def run(exe, lower, upper, width, reps, parts):
    args = [exe, str(lower[0]), str(lower[1]), str(upper[0]), str(upper[1]), str(L), str(width), str(reps)] + [str(p) for p in parts]
    out = subprocess.run(args, capture_output=True, text=True, check=True).stdout
    mesh, rows = {}, {}
    for line in out.splitlines():
        t = line.split()
        if t[0] == "mesh":
            mesh = {t[i]: float(t[i + 1]) for i in range(1, len(t), 2)}
        elif t[0] == "parts":
            rows[int(t[1])] = {t[i]: float(t[i + 1]) for i in range(0, len(t), 2)}
    return mesh, rows


def unit_costs(doc):
    try:
        text = open(doc).read()
        m = re.search(r"Jacobian assembly ([\d.]+) µs per element, residual ([\d.]+) µs per element", text)
        if m:
            return 1e-6 * float(m.group(1)), 1e-6 * float(m.group(2))
    except OSError:
        pass
    return T_JAC, T_RES


def model_newton(doc):
    """the time per Newton iteration of this page's model (## The model), per number of ranks"""
    try:
        text = open(doc).read()
    except OSError:
        return {}
    part = text.split("## The model", 1)
    if len(part) < 2:
        return {}
    out = {}
    for m in re.finditer(r"^\| (\d+) \| [\d.]+ \| [\d.]+ \| [\d.]+ \| [\d.]+ \| ([\d.]+) \| \d+ % \|", part[1].split("\n## ", 1)[0], re.M):
        out[int(m.group(1))] = float(m.group(2))
    return out


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--lower", default="200,12", help="NX,NZ of the lower slab")
    ap.add_argument("--upper", default="250,8", help="NX,NZ of the upper slab")
    ap.add_argument("--parts", default="1,16,32,64,128,256,512,1024")
    ap.add_argument("--reps", type=int, default=5)
    ap.add_argument("--indenter", default="200,20,100,20,30", help="NX,NZ of the slab, NX,NZ and width of the indenter, or none")
    ap.add_argument("--work", default=os.path.join(ROOT, "build", "pair_search_scaling"))
    ap.add_argument("--output", default=os.path.join(ROOT, "doc", "scaling-model.md"))
    a = ap.parse_args()
    with open("/proc/loadavg") as f:
        load0 = f.read().split()[:3]
    os.makedirs(a.work, exist_ok=True)
    exe = build(a.work)
    lower = [int(x) for x in a.lower.split(",")]
    upper = [int(x) for x in a.upper.split(",")]
    parts = [int(p) for p in a.parts.split(",")]
    mesh, rows = run(exe, lower, upper, L, a.reps, [p for p in parts if p > 1])
    if 1 in parts:  # the serial loop takes seconds: once
        rows.update(run(exe, lower, upper, L, 1, [1])[1])
    ind = None
    if a.indenter != "none":
        v = a.indenter.split(",")
        ind = (v, *run(exe, [int(v[0]), int(v[1])], [int(v[2]), int(v[3])], float(v[4]), a.reps, [p for p in parts if p > 1]))
    with open("/proc/loadavg") as f:
        load1 = f.read().split()[:3]
    t_jac, t_res = unit_costs(a.output)
    newton = model_newton(a.output)
    nf, ns = int(mesh["master_faces"]), int(mesh["slaves"])

    lines = [HEADING, "", benchutil.measured_by("pair_search_scaling.py", ROOT) +
             f" Load average (1, 5, 15 min) at the start {', '.join(load0)}, at the end {', '.join(load1)} (2 cores, other work running: the times below are CPU times).", "",
             f"The candidate search of contact pairs (`SideCandidates`, `src/contact/pair.c`; doc/contact-bodies.md, Parallel) on a lower slab of {lower[0]} x {lower[0]} x {lower[1]} "
             f"and an upper slab of {upper[0]} x {upper[0]} x {upper[1]} hexahedra over the whole interface ({int(mesh['cells']):,} cells; {ns} slave nodes, the upper slab's "
             f"bottom, on {nf} master faces, the lower slab's top; search distance 2 d_max = {mesh['search'] / (L / lower[0]):.2f} master faces; "
             f"{mesh['candidates_per_node']:.1f} faces per slave node's list), partitioned as the code does (`scripts/pair_search_scaling.c`: METIS, a shared vertex to the "
             "highest-numbered part). Per part, at the first search: means over the parts with slave nodes; needed = the faces within the search distance of one of "
             "its slave nodes; interface share = master faces / parts with slave nodes; pairs = slave nodes x candidates; owner tests = owned faces x parts with slave "
             f"nodes x 2 passes. Times, CPU, median of {a.reps} (1 part: once), on the part with the most pairs and the one with the most owned faces: the per-node "
             f"lists by the double loop of {OLD} and by the bin grid of {NEW}; the owner's test of both, and with its faces' box first (the code's since this measurement); "
             f"% = the search of {NEW} (bins, owner's test), done at every Newton iteration, over the largest part's assembly of one (this page's unit costs). Not timed: the MPI calls and the PetscSF rebuilt at each search.", "",
             "| parts | parts with slave nodes | slave nodes max (mean) | master faces owned max | candidates max (mean) | candidates / needed max (mean) | "
             f"candidates / interface share | messages max (mean) | pairs max (mean) | pairs max / mean | owner tests max | double loop ms | bins ms | "
             "owner test ms | owner test, box first ms | search % of assembly |",
             "|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|"]
    for p in sorted(rows):
        r = rows[p]
        w = int(r["with_slaves"])
        asm = r["cells_max"] * (t_jac + 2 * t_res)
        lines.append(f"| {p} | {w} | {int(r['slaves_max'])} ({ns / w:.0f}) | {int(r['faces_owned_max'])} | {int(r['cand_max'])} ({r['cand_mean_with']:.0f}) | "
                     f"{r['cand_over_need_max']:.2f} ({r['cand_over_need_mean']:.2f}) | {r['cand_mean_with'] / (nf / w):.2f} | {int(r['msg_max'])} ({r['msg_mean_with']:.1f}) | "
                     f"{r['loop_max']:.3g} ({r['loop_mean_with']:.3g}) | {r['loop_max'] / r['loop_mean_with']:.2f} | {int(r['owner_tests_max'])} | "
                     f"{1e3 * r['t_nodes_s']:.3g} | {1e3 * r['t_binned_s']:.3g} | {1e3 * r['t_owner_s']:.3g} | {1e3 * r['t_prefilter_s']:.3g} | "
                     f"{100 * (r['t_binned_s'] + r['t_owner_s']) / asm:.1f} |")
    ps = [p for p in sorted(rows) if p > 1]
    p0, p1 = ps[0], ps[-1]
    r0, r1 = rows[p0], rows[p1]
    ns_per = [rows[p]["t_nodes_s"] / rows[p]["t_nodes_pairs"] for p in sorted(rows)]  # the code's two passes: 2 tests per pair
    cross = next((p for p in ps if rows[p]["t_owner_s"] > rows[p]["t_binned_s"]), None)
    serial = rows.get(1)

    def pct(r, t):
        return 100 * t / (r["cells_max"] * (t_jac + 2 * t_res))
    txt = (f"Reading: the double loop of {OLD} was quadratic in a rank's share of the interface (its candidates grow with its slave nodes, a sheet, so its "
           f"pairs go as (slave nodes / rank)^2; {1e9 * min(ns_per):.1f} to {1e9 * max(ns_per):.1f} ns per test, two per pair): "
           + (f"{serial['t_nodes_s']:.1f} s at 1 rank, " if serial else "")
           + f"{1e3 * r0['t_nodes_s']:.0f} ms at {p0} ({pct(r0, r0['t_nodes_s']):.0f} % of a Newton iteration's assembly"
           + (f", {100 * r0['t_nodes_s'] / newton[p0]:.1f} % of the model's whole iteration" if p0 in newton else "")
           + f"). The bin grid of {NEW} makes it linear: "
           + (f"{1e3 * serial['t_binned_s']:.0f} ms at 1 rank, " if serial else "")
           + f"{1e3 * r0['t_binned_s']:.1f} ms at {p0}, {1e3 * r1['t_binned_s']:.2f} ms at {p1}. What did not shrink is the owner's test without its prefilter: every owned face "
           f"against every rank's box, {int(r0['owner_tests_max'])} tests at {p0} parts, {int(r1['owner_tests_max'])} at {p1} (about 2 x the interface's faces, "
           "times the owned faces' imbalance)"
           + (f"; from {cross} parts on it is the larger part of the search" if cross else "")
           + f", and with the search now at every Newton iteration it is {pct(r1, r1['t_owner_s']):.1f} % of the assembly at {p1} parts"
           + (f" ({100 * r1['t_owner_s'] / newton[p1]:.2f} % of the model's whole iteration)" if p1 in newton else "")
           + "; with the allgather "
           "of 6 P numbers and the alltoall of P counts it is O(P) per rank. Testing the owner's faces' overall box against each rank's box first, as the code now does, makes it "
           f"O(P + faces x the ranks it sends to): {1e3 * r1['t_prefilter_s']:.3f} ms at {p1} parts ({pct(r1, r1['t_prefilter_s']):.1f} %); past some 10^4 ranks "
           "a tree of the boxes (or a sparse exchange) would replace the P boxes. The boxes fetch "
           f"{min(rows[p]['cand_over_need_mean'] for p in ps):.2f} to {max(rows[p]['cand_over_need_mean'] for p in ps):.2f} times the faces needed on average, "
           f"{max(rows[p]['cand_over_need_max'] for p in ps):.2f} at most (METIS's parts are not rectangles); the search distance's halo makes the "
           f"candidates {r0['cand_mean_with'] / (nf / r0['with_slaves']):.1f} to {r1['cand_mean_with'] / (nf / r1['with_slaves']):.1f} times the rank's share of "
           f"the interface; at most {max(int(rows[p]['msg_max']) for p in ps)} messages. {int(r1['with_slaves'])} of {p1} parts hold slave nodes (the others the "
           f"lower slab); among them the largest has {min(rows[p]['loop_max'] / rows[p]['loop_mean_with'] for p in ps):.2f} to "
           f"{max(rows[p]['loop_max'] / rows[p]['loop_mean_with'] for p in ps):.2f} times the mean pairs.")
    if ind:
        v, im, ir = ind
        q = ir[max(ir)]
        txt += (f" A {v[4]} x {v[4]} indenter ({v[2]} x {v[2]} x {v[3]}) on a {v[0]} x {v[0]} x {v[1]} slab ({int(im['cells']):,} cells): at {max(ir)} parts "
                f"{int(q['with_slaves'])} hold slave nodes, the largest {q['loop_max'] / q['loop_mean']:.0f} times the mean pairs over all parts "
                f"({q['loop_max'] / q['loop_mean_with']:.1f} over those); bins {1e3 * q['t_binned_s']:.2f} ms.")
    lines += ["", txt, "", "Regenerate: `python3 scripts/pair_search_scaling.py` (about a minute and a half; writes this section)."]
    body = "\n".join(lines) + "\n"
    benchutil.write_doc_section(a.output, HEADING, body)
    print(body)


if __name__ == "__main__":
    main()
