#!/usr/bin/env python3
"""What -partition_balance contact changes, measured on real runs: the hemispherical punch blank
(cases/hemisphere_friction_refined.opts with 4 layers, contact on the top and bottom faces),
distributed to 2 ... 16 ranks (oversubscribed: only the set-up is run, one tiny load step), with the
default partition (METIS balancing the cells; a vertex on a part boundary owned by the
highest-numbered rank around it, PETSc's rule) and with -partition_balance contact (METIS with two
constraints per cell, its weight and its share of the slave nodes, and the part-boundary vertices
owned by a rank chosen to balance them: DMPlexSetPartitionBalance). Reports the largest over the
mean of the cells, the owned slave nodes (the contact work) and the edge count of the cut per
rank, from the run's own lines. Writes the section "## Balancing the contact nodes (measured)"
of doc/scaling-model.md.

usage: scripts/partition_balance.py [--ranks 2,4,8,16] [--layers 4]"""
import argparse, os, re, subprocess, sys, tempfile
HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(HERE)
sys.path.insert(0, HERE)
import benchutil  # noqa: E402

HEADING = "## Balancing the contact nodes (measured)"


def run(exe, np, layers, balance, work):
    cmd = ["mpiexec", "--oversubscribe", "-n", str(np), exe, "-options_file", os.path.join(ROOT, "cases", "hemisphere_friction_refined.opts"),
           "-blank_layers", str(layers), "-output_interval", "0", "-output_dir", os.path.join(work, f"{balance}{np}"),
           "-partition_balance", balance, "-load_steps", "1000", "-load_max_steps", "1"]
    p = subprocess.run(cmd, capture_output=True, text=True, env=benchutil.run_env(), cwd=ROOT)
    out = p.stdout + p.stderr
    m = re.search(r"cells per rank:([\d ]+)", out)
    s = re.search(r"slave nodes per rank: largest (\d+), mean ([\d.]+)", out)
    if not m or not s:
        sys.exit(f"partition_balance: the run at {np} ranks ({balance}) printed no partition lines (exit {p.returncode}):\n{out[-1500:]}")
    cells = [int(x) for x in m.group(1).split()]
    return dict(cell_imb=max(cells) * len(cells) / sum(cells), slave_max=int(s.group(1)), slave_mean=float(s.group(2)),
                slave_imb=int(s.group(1)) / float(s.group(2)))


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--ranks", default="2,4,8,16")
    ap.add_argument("--layers", type=int, default=4)
    a = ap.parse_args()
    work = tempfile.mkdtemp(prefix="partition_balance_")
    exe = benchutil.build_and_snapshot(ROOT, work, "partition_balance")
    rows = []
    for np in [int(x) for x in a.ranks.split(",")]:
        r = {b: run(exe, np, a.layers, b, work) for b in ("cells", "contact")}
        rows.append((np, r))
        print(np, r, flush=True)
    L = [HEADING, "", benchutil.measured_by("partition_balance.py", ROOT), "",
         f"`cases/hemisphere_friction_refined.opts` with `-blank_layers {a.layers}` (contact slave nodes on the top and bottom faces), "
         "distributed as the code does at each number of ranks (the set-up of a real run; oversubscribed, so no times). "
         "Imbalance = largest / mean over the ranks.", "",
         "| ranks | cells: cell imbalance | cells: slave nodes max (mean) | cells: slave imbalance | contact: cell imbalance | contact: slave nodes max (mean) | contact: slave imbalance |",
         "|---|---|---|---|---|---|---|"]
    for np, r in rows:
        c, k = r["cells"], r["contact"]
        L.append(f"| {np} | {c['cell_imb']:.3f} | {c['slave_max']} ({c['slave_mean']:.1f}) | {c['slave_imb']:.3f} | "
                 f"{k['cell_imb']:.3f} | {k['slave_max']} ({k['slave_mean']:.1f}) | {k['slave_imb']:.3f} |")
    L += ["", "Where the slave-node imbalance comes from: not from the cells METIS gives each part (a cell's share of the slave "
          "nodes is nearly the same everywhere in a sheet) but from which rank owns a vertex on a part boundary, since the contact "
          "work of a node is done by its owner. The partition statistics above (lowest-numbered part owns) show the same growth "
          "with the number of parts; weighting METIS alone by the slave nodes did not reduce it there (1.221 against 1.200 at 1024 "
          "parts, measured with `scripts/partition_stats.c ... contact`). `-partition_balance contact` therefore also hands "
          "the boundary vertices to ranks chosen to balance them (PETSc's shared-point balancing), which is what the table "
          "measures. The model's contact share stays small (the table of the model), so the option matters where contact is "
          "expensive: meshed tools with many facets, or friction with many active nodes.", ""]
    benchutil.write_doc_section(os.path.join(ROOT, "doc", "scaling-model.md"), HEADING, "\n".join(L))
    print("\n".join(L))


if __name__ == "__main__":
    main()
