#!/usr/bin/env python3
"""A model of the time per Newton iteration from 1 to 1024 ranks, for a forming case of a million
hexahedra (the hemispherical punch blank, quarter, 4 layers, ~1.0e6 cells), from what can be
measured on this machine. Writes doc/scaling-model.md.

usage: scripts/scaling_model.py [--core 210 --radial 490 --layers 4] [--no-measure]
       scripts/scaling_model.py --measured DIR [DIR ...]   (or --measured with no DIR: from the stored runs)

1. Partition statistics (scripts/partition_stats.c, built here against build/lib.a): the mesh
   partitioned by METIS as the code does into 16 ... 4096 parts; per part owned cells, owned and
   ghost vertices, neighbours, contact slave nodes; the edge cut.
2. Unit costs measured here on one core (--no-measure: the values of doc/notes/performance-log.md): the
   Jacobian and residual assembly per element and the contact evaluation per slave node from a
   run with -log_view, and the iterative solver of the million-hexahedra case
   (cases/solver_amgsys.opts: BiCGStab + BoomerAMG) per unknown and Krylov iteration ((KSPSolve -
   PCSetUp) time over unknowns x iterations) and its setup per unknown (PCSetUp) on the whole
   blank of 25 600 hexahedra, one load step of 1 mm.
3. The model (assumptions stated in the document): per Newton iteration, on the slowest rank,
     T(P) = cells_max (t_jac + n_res t_res) + slaves_max (1 + n_res) t_contact
            + dofs_max (n_kry t_kry + t_setup) + communication(P),
   with the communication of every assembly and every Krylov iteration as messages to the
   neighbours (latency alpha, bandwidth beta, ghost values of 3 doubles per vertex): per BiCGStab
   iteration two operator applications and two V-cycles (per level and cycle 2 sweeps + 3
   exchanges), and log2(P) allreduces (4 per iteration) and per level.
4. --measured: the strong-scaling runs of scripts/scaling.py on a machine with more cores (its
   --out folders: records.json and the raw -log_view outputs) set beside the same model, with the
   unit costs taken from that machine's own 1-rank run of the same case and the partition
   statistics of that case's mesh; the runs are stored in doc/reference/scaling-measured.json
   (--measured with no folder renders from there) and written to the section "Measured on more
   cores, beside the model" of doc/scaling-model.md, every other section kept.
"""
import argparse, json, math, os, re, statistics, subprocess, sys, tempfile
HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(HERE)
sys.path.insert(0, HERE)
import benchutil  # noqa: E402

PARTS = [16, 32, 64, 128, 256, 512, 1024, 2048, 4096]
ALPHA, BETA = 2e-6, 1.0 / 10e9  # network: 2 us latency, 10 GB/s per link (an InfiniBand cluster; assumed)
N_RES = 2.0                     # residual evaluations per Newton iteration (line search, convergence test)
N_KRY = 50                      # Krylov iterations per Newton step (the target of the million-cell case; its measured mean 49)
AMG_LEVELS = 8                  # levels of BoomerAMG's hierarchy at a million hexahedra (assumed)
SWEEPS = 3                      # smoothing sweeps per level and direction (cases/solver_amgsys.opts)
EXCH_PER_KRY = 2 * (1 + AMG_LEVELS * (2 * SWEEPS + 3))  # ghost exchanges per BiCGStab iteration
ALLRED_PER_KRY = 4 + AMG_LEVELS                          # allreduces per BiCGStab iteration
# measured on this machine (doc/notes/performance-log.md, One million hexahedra): the whole blank at 2 ranks
MEASURED = [(250512, 942495, 2, 61.0, "5 Newton iterations of a 1 mm step, 304 s"),
            (1010224, 3794535, 2, 290.0, "9 Newton iterations and the predictor of a 1 mm step, 2 888 s")]


MEASURED_JSON = os.path.join(ROOT, "doc", "reference", "scaling-measured.json")
MEASURED_HEADING = "## Measured on more cores, beside the model"


def build_stats(work):
    exe = os.path.join(work, "partition_stats")
    pc = subprocess.run(["pkg-config", "--cflags", "--libs", "PETSc"], capture_output=True, text=True).stdout.split()
    cmd = ["mpicc", "-O2", "-Iinclude", os.path.join(HERE, "partition_stats.c"), "build/lib.a", "-o", exe] + pc + \
          ["-L/usr/lib/x86_64-linux-gnu/hdf5/openmpi", "-lhdf5", "-ldmumps", "-lmumps_common", "-lmetis", "-lm"]
    subprocess.run(cmd, cwd=ROOT, check=True)
    return exe


def partition(exe, core, radial, layers, parts=PARTS, whole=False):
    out = subprocess.run([exe] + (["-whole"] if whole else []) + [str(core), str(radial), str(layers), "cells"] + [str(p) for p in parts],
                         capture_output=True, text=True, check=True).stdout
    mesh = dict(zip(*[iter(out.splitlines()[0].split()[1:])] * 2))
    rows = []
    for line in out.splitlines()[1:]:
        t = line.split()
        rows.append({t[i]: float(t[i + 1]) for i in range(0, len(t), 2)})
    return {k: int(v) for k, v in mesh.items()}, rows


def log_event(log, name):
    m = re.search(rf"^{name}\s+(\d+)\s+\S+\s+(\S+)", log, re.M)
    return (int(m.group(1)), float(m.group(2))) if m else (0, 0.0)


def measure(work):
    """unit costs on one core: the assembly and contact events from a 4-layer quarter blank with
    contact (Coons tools, LU), the iterative solver of the million case from the whole blank of
    25 600 hexahedra (cases/solver_amgsys.opts, one step of 1 mm)"""
    env = dict(os.environ, OMPI_ALLOW_RUN_AS_ROOT="1", OMPI_ALLOW_RUN_AS_ROOT_CONFIRM="1", OPENBLAS_NUM_THREADS="1")
    exe = os.path.join(ROOT, "bin", "atrito")
    runs = {"lu": ["-options_file", os.path.join(ROOT, "cases", "hemisphere_friction_refined.opts"), "-load_max_steps", "3"],
            "amg": ["-options_file", os.path.join(ROOT, "cases", "hemisphere_friction_disk.opts"), "-options_file", os.path.join(ROOT, "cases", "solver_amgsys.opts"),
                    "-blank_core_cells", "16", "-blank_radial_cells", "42", "-blank_layers", "4", "-tool_punch_motion", "0,0,1",
                    "-load_steps", "1", "-load_dt_max", "1", "-ksp_converged_reason"]}
    res = {}
    for name, args in runs.items():
        p = subprocess.run(["mpiexec", "-n", "1", exe] + args + ["-output_interval", "0", "-log_view", "-output_dir", os.path.join(work, name)],
                           capture_output=True, text=True, env=env, cwd=ROOT)
        log = p.stdout
        ended = ("-load_max_steps 3 reached" in p.stdout + p.stderr) if name == "lu" else (p.returncode == 0)
        if not re.search(r"mesh: \d+ vertices", log) or not ended:
            sys.exit(f"scaling_model: the {name} run failed (exit {p.returncode}):\n" + (log + p.stderr)[-2000:])
        m = re.search(r"mesh: (\d+) vertices, (\d+) hexahedra", log)
        nslave = int(re.search(r"contact: (\d+) slave nodes", log).group(1))
        res[name] = dict(log=log, nvert=int(m.group(1)), ncell=int(m.group(2)), nslave=nslave)
    lu = res["lu"]
    nj, tj = log_event(lu["log"], "AtritoJacobian")
    nr, tr = log_event(lu["log"], "AtritoResidual")
    nc, tc = log_event(lu["log"], "AtritoContact")
    g = res["amg"]["log"]
    its = [int(x) for x in re.findall(r"Linear solve converged due to \S+ iterations (\d+)", g)]
    nsolve, tk = log_event(g, "KSPSolve")
    nsetup, ts = log_event(g, "PCSetUp")
    ndof = 3 * res["amg"]["nvert"]  # (the rim's constrained unknowns, 1 %, counted too)
    return dict(t_jac=tj / max(nj, 1) / lu["ncell"], t_res=tr / max(nr, 1) / lu["ncell"],
                t_contact=tc / max(nj + nr, 1) / lu["nslave"], t_kry=(tk - ts) / max(sum(its), 1) / ndof,
                t_setup=ts / max(nsetup, 1) / ndof, kry_its=sum(its) / max(len(its), 1), kry_most=max(its) if its else 0,
                ncell=lu["ncell"], nslave=lu["nslave"], ndof=ndof, amg_cells=res["amg"]["ncell"])


def model(mesh, rows, c):
    out = []
    n = mesh["cells"]
    kry1 = 3 * mesh["vertices"] * (N_KRY * c["t_kry"] + c["t_setup"])
    ser = n * (c["t_jac"] + N_RES * c["t_res"]) + mesh["slaves"] * (1 + N_RES) * c["t_contact"] + kry1
    out.append(dict(P=1, asm=n * (c["t_jac"] + N_RES * c["t_res"]), con=mesh["slaves"] * (1 + N_RES) * c["t_contact"], kry=kry1, comm=0.0, T=ser, eff=1.0, imb_c=1.0, imb_s=1.0))
    for r in rows:
        P = int(r["parts"])
        if P > 1024:
            continue
        asm = r["cells_max"] * (c["t_jac"] + N_RES * c["t_res"])
        con = r["slaves_max"] * (1 + N_RES) * c["t_contact"]
        kry = 3 * r["verts_owned_max"] * (N_KRY * c["t_kry"] + c["t_setup"])
        exch = r["neighbours_max"] * ALPHA + 2 * 3 * 8 * r["ghosts_max"] * BETA  # one ghost exchange (both ways; the coarse levels' smaller ones counted as this)
        comm = (1 + N_RES) * exch + N_KRY * (EXCH_PER_KRY * exch + ALLRED_PER_KRY * ALPHA * math.log2(P))
        T = asm + con + kry + comm
        out.append(dict(P=P, asm=asm, con=con, kry=kry, comm=comm, T=T, eff=ser / (P * T), imb_c=r["cells_max"] / r["cells_mean"], imb_s=r["slaves_max"] / max(r["slaves_mean"], 1e-300)))
    return out


def _opt(args, name, default=None):
    return args[args.index(name) + 1] if name in args else default


def extract_runs(dirs):
    """one record per run of scripts/scaling.py (its records.json and raw logs): the case, the ranks,
    the counts and the event times (maximum over the ranks) that the model is compared with"""
    runs, machine, launcher = [], None, None
    for d in dirs:
        with open(os.path.join(d, "records.json")) as f:
            R = json.load(f)
        machine, launcher = R["machine"], R["args"]["launcher"]
        for r in R["records"]:
            if r["status"] != "ok" or r["kind"] != "strong":
                continue
            with open(os.path.join(d, f"strong_np{r['p']}_rep{r['rep']}.log")) as f:
                log = f.read()
            cmd = r["cmd"]
            case = "cases/" + os.path.basename(cmd[cmd.index("-options_file") + 1])  # the run's case file, named in this tree
            with open(os.path.join(ROOT, case)) as f:
                whole = re.search(r"^-blank_quarter\s+(false|0|no)", f.read(), re.M) is not None
            m = re.search(r"mesh: (\d+) vertices, (\d+) hexahedra; .*cells per rank: ([\d ]+)", log)
            ev = {}
            for name in ("SNESSolve", "AtritoJacobian", "AtritoResidual", "AtritoContact", "KSPSolve", "PCSetUp"):
                ev[name] = log_event(log, name)
            its = [int(x) for x in re.findall(r"Linear solve converged due to \S+ iterations (\d+)", log)]
            done = re.search(r"done: (\d+) steps, (\d+) Newton iterations, (\d+) cuts", log)
            runs.append(dict(case=case, core=int(_opt(cmd, "-blank_core_cells")), radial=int(_opt(cmd, "-blank_radial_cells")),
                             layers=int(_opt(cmd, "-blank_layers", "4")), whole=whole, p=r["p"], rep=r["rep"], total=r["total"],
                             vertices=int(m.group(1)), cells=int(m.group(2)), cells_per_rank=[int(x) for x in m.group(3).split()],
                             slaves=int(re.search(r"contact: (\d+) slave nodes", log).group(1)), newton=int(done.group(2)),
                             cuts=int(done.group(3)), krylov=its, events={k: list(v) for k, v in ev.items()},
                             args=R["args"]["strong_args"], other_load=r["other"], date=machine["date"], commit=machine["commit"]))
    return dict(machine=machine, launcher=launcher, runs=runs)


def measured_section(data, exe):
    mi, L = data["machine"], []
    L += [MEASURED_HEADING, "",
          f"Measured with `scripts/scaling.py` on {mi['date']}: {mi['cpu']}, {mi['cores']} cores ({mi.get('virt', '')}), {mi['mem']}, "
          f"one rank per core (`{data['launcher']}`); commit {mi['commit']}; rendered by `scripts/scaling_model.py --measured` from "
          f"`{os.path.relpath(MEASURED_JSON, ROOT)}` (the runs' counts and event times). Other load on the machine during the runs "
          f"(scripts/scaling.py, from /proc/stat): at most {max(r['other_load'] for r in data['runs']):.2f} cores"
          + (f"; `{data['node']['script']}` on {data['node']['date']}." if data.get("node") else "."), "",
          "The model of this document applied to each measured case with that machine's own unit costs, taken from its 1-rank run "
          "of the same case (per Newton iteration: the assembly time, the contact time; per unknown: the Krylov iteration and "
          "BoomerAMG's setup), the counts measured at each rank count (Krylov iterations and setups per Newton iteration: the "
          "iteration counts change with the number of ranks, since the hybrid Gauss-Seidel smoother is Jacobi across a rank "
          "boundary), the largest part of METIS's partition of the case's mesh (`scripts/partition_stats.c -whole`: the cells and "
          "the owned vertices of the largest part, its ghosts and neighbours) and the model's network (2 µs, 10 GB/s). "
          "Measured: the events of `-log_view` (maximum over the ranks) over the Newton iterations, medians over the runs; "
          "assembly = AtritoJacobian + AtritoResidual (contact nested), Krylov = KSPSolve (BoomerAMG's setup nested; the "
          "predictor's solve included). \"Per Krylov iteration\" is (KSPSolve − PCSetUp) over the Krylov iterations.", ""]
    cases, summary = {}, {}
    for r in data["runs"]:
        cases.setdefault((r["case"], r["core"], r["radial"], r["layers"], r["whole"]), []).append(r)
    for (case, core, radial, layers, whole), rs in sorted(cases.items(), key=lambda kv: kv[1][0]["cells"]):
        ps = sorted({r["p"] for r in rs})
        if 1 not in ps:
            continue
        mesh, rows = partition(exe, core, radial, layers, [p for p in ps if p > 1], whole)
        part = {int(r["parts"]): r for r in rows}
        ndof = 3 * mesh["vertices"]

        def med(p, f):
            return statistics.median(f(r) for r in rs if r["p"] == p)

        def per_newton(r, name):
            return r["events"][name][1] / r["newton"]

        def kry_it(r):
            return (r["events"]["KSPSolve"][1] - r["events"]["PCSetUp"][1]) / max(sum(r["krylov"]), 1)

        asm1 = med(1, lambda r: (r["events"]["AtritoJacobian"][1] + r["events"]["AtritoResidual"][1]) / r["newton"])
        con1 = med(1, lambda r: r["events"]["AtritoContact"][1] / r["newton"])
        u_kry = med(1, kry_it) / ndof
        u_set = med(1, lambda r: r["events"]["PCSetUp"][1] / max(r["events"]["PCSetUp"][0], 1)) / ndof
        t1 = med(1, lambda r: r["total"])
        k1 = med(1, kry_it)
        L += [f"### {mesh['cells']} hexahedra, whole blank" if whole else f"### {mesh['cells']} hexahedra", "",
              f"`{case} {rs[0]['args']}` ({layers} layers): {mesh['vertices']} vertices, {ndof} unknowns, {mesh['slaves']} contact "
              f"slave nodes. Unit costs of the 1-rank run: {1e6 * u_kry:.2f} µs per unknown and Krylov iteration, BoomerAMG's setup "
              f"{1e6 * u_set:.2f} µs per unknown, assembly {asm1:.2f} s per Newton iteration.", "",
              "| ranks | runs | Newton its | Krylov its per solve | total s median [min – max] | speedup (efficiency) | assembly s per Newton it: measured / model "
              "| Krylov s per Newton it: measured / model (communication) | measured / model, assembly + Krylov | s per Krylov iteration: speedup (efficiency) | largest part: cells, ghost share, neighbours |",
              "|---|---|---|---|---|---|---|---|---|---|---|"]
        for p in ps:
            sel = [r for r in rs if r["p"] == p]
            tot = [r["total"] for r in sel]
            asm_m = med(p, lambda r: (r["events"]["AtritoJacobian"][1] + r["events"]["AtritoResidual"][1]) / r["newton"])
            kry_m = med(p, lambda r: per_newton(r, "KSPSolve"))
            kn = med(p, lambda r: sum(r["krylov"]) / r["newton"])
            sn = med(p, lambda r: r["events"]["PCSetUp"][0] / r["newton"])
            if p == 1:
                cmax, omax, gshare, nmax, comm, smax = mesh["cells"], mesh["vertices"], 0.0, 0, 0.0, mesh["slaves"]
            else:
                q = part[p]
                ran = {max(r["cells_per_rank"]) for r in rs if r["p"] == p}
                if ran != {int(q["cells_max"])}:
                    sys.exit(f"scaling_model: the runs at {p} ranks had at most {ints(sorted(ran))} cells per rank, "
                             f"scripts/partition_stats.c gives {int(q['cells_max'])}: it no longer partitions as the code does")
                cmax, omax, gshare, nmax, smax = int(q["cells_max"]), int(q["verts_owned_max"]), q["ghost_frac_max"], int(q["neighbours_max"]), q["slaves_max"]
                exch = q["neighbours_max"] * ALPHA + 2 * 3 * 8 * q["ghosts_max"] * BETA
                comm = (1 + N_RES) * exch + kn * (EXCH_PER_KRY * exch + ALLRED_PER_KRY * ALPHA * math.log2(p))
            # the assembly scales with the largest part's cells, its nested contact with its slave nodes
            asm_mod = asm1 * cmax / mesh["cells"] + con1 * (smax / mesh["slaves"] - cmax / mesh["cells"])
            kry_mod = 3 * omax * (kn * u_kry + sn * u_set) + comm
            ratio = (asm_m + kry_m) / (asm_mod + kry_mod)
            kp = med(p, kry_it)
            L.append(f"| {p} | {len(sel)} | {ints(sorted({r['newton'] for r in sel}))} | {med(p, lambda r: sum(r['krylov']) / len(r['krylov'])):.1f} | "
                     f"{statistics.median(tot):.1f} [{min(tot):.1f} – {max(tot):.1f}] | {t1 / statistics.median(tot):.2f} ({100 * t1 / statistics.median(tot) / p:.0f} %) | "
                     f"{asm_m:.3f} / {asm_mod:.3f} | {kry_m:.2f} / {kry_mod:.2f} ({comm:.3f}) | {ratio:.2f} | {k1 / kp:.2f} ({100 * k1 / kp / p:.0f} %) | "
                     f"{cmax}, {gshare:.3f}, {nmax} |")
            summary.setdefault(mesh["cells"], []).append((p, ratio, asm_m / asm_mod, (kry_m - comm) / (kry_mod - comm), comm / kry_m, k1 / kp / p))
        L.append("")
    if summary:
        newton_note = "; ".join(f"{c} hexahedra: " + ", ".join(f"{n} at {ints(sorted({r['p'] for r in rs if r['newton'] == n}))} ranks"
                                                                   for n in sorted({r["newton"] for r in rs}))
                                for c, rs in sorted(((rs[0]["cells"], rs) for rs in cases.values())))
        spread = max(abs(r["total"] / statistics.median(q["total"] for q in rs if q["p"] == r["p"]) - 1)
                     for rs in cases.values() for r in rs)
        L += ["Reading:", ""]
        for cells, v in sorted(summary.items()):
            p, ratio, ra, rk, cs, ek = v[-1]
            L.append(f"- {cells} hexahedra: measured / model {min(x[1] for x in v):.2f} to {max(x[1] for x in v):.2f} over 1 to {p} ranks; at "
                     f"{p} ranks the assembly takes {ra:.2f} times the model's time and the Krylov solves less their communication {rk:.2f} "
                     f"times; the modelled communication is {100 * cs:.0f} % of the measured Krylov time; a Krylov iteration runs at "
                     f"{100 * ek:.0f} % efficiency.")
        (c0, v0), (c1, v1) = min(summary.items()), max(summary.items())
        node = data.get("node")
        if node:
            a1 = statistics.median(node["alone"])
            runs = "; ".join(f"{n} at once: median {statistics.median(t):.2f} s ({statistics.median(t) / a1:.2f} times), "
                             f"{min(t):.2f} to {max(t):.2f}" for n, t in node["at_once"])
            why = (f"a core of this machine is slower with all its cores busy than alone, with no communication at all: the same "
                   f"1-rank run (`{node['case']}`, `{node['script']}`) took {a1:.2f} s alone; {runs}")
        else:
            why = "a core of this machine is slower with all its cores busy than alone"
        L += [f"- The assembly, compute-bound with one ghost exchange per call, takes {v0[-1][2]:.2f} and {v1[-1][2]:.2f} times the model's "
              f"time at {v1[-1][0]} ranks: {why}. The cause (clock, shared memory bandwidth or the virtual machine's placement on "
              "physical cores) is not separated by these runs; the model leaves it out (its unit costs are one core's with the "
              "machine to itself). The Krylov solves show it at "
              f"{c1} hexahedra ({v1[-1][3]:.2f}) more than at {c0} ({v0[-1][3]:.2f}), whose parts per rank are a quarter as large. "
              "Read the model's times past one node with such a factor.",
              "- The total's speedup counts the Newton iterations each run took, which can differ by one between rank counts "
              f"(the smoother depends on the partition: {newton_note}), so it can exceed the ranks; the columns per Newton iteration "
              "and per Krylov iteration compare the same work.",
              f"- Repeated runs spread by up to {100 * spread:.0f} % about their median on this virtual machine with no other work on it: "
              "the tables give medians and the range.", ""]
    return "\n".join(L)


def ints(v):
    return ", ".join(str(x) for x in v)


def measured_main(dirs, doc):
    if dirs:
        data = extract_runs(dirs)
        if os.path.exists(MEASURED_JSON):  # scripts/node_contention.sh's figures, entered by hand, are kept
            with open(MEASURED_JSON) as f:
                node = json.load(f).get("node")
            if node:
                data["node"] = node
        with open(MEASURED_JSON, "w") as f:
            json.dump(data, f, indent=1)
    with open(MEASURED_JSON) as f:
        data = json.load(f)
    work = tempfile.mkdtemp(prefix="scaling_model_")
    body = measured_section(data, build_stats(work))
    benchutil.write_doc_section(doc, MEASURED_HEADING, body)
    print(body)


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--core", type=int, default=210)
    ap.add_argument("--radial", type=int, default=490)
    ap.add_argument("--layers", type=int, default=4)
    ap.add_argument("--no-measure", action="store_true")
    ap.add_argument("--measured", nargs="*", metavar="DIR", help="scripts/scaling.py --out folders (none: the stored runs)")
    ap.add_argument("--doc", default=os.path.join(ROOT, "doc", "scaling-model.md"), help="with --measured: the document whose section is written")
    a = ap.parse_args()
    if a.measured is not None:
        return measured_main(a.measured, a.doc)
    work = tempfile.mkdtemp(prefix="scaling_model_")
    exe = build_stats(work)
    mesh, rows = partition(exe, a.core, a.radial, a.layers)
    if a.no_measure:
        c = dict(t_jac=1 / 46000, t_res=1 / 172000, t_contact=0.75e-6, t_kry=float("nan"), kry_its=float("nan"), ncell=0, nslave=0, ndof=0)
    else:
        load0 = os.getloadavg()[0]
        c = measure(work)
        c["load"] = (load0, os.getloadavg()[0])
    m = model(mesh, rows, c)
    L = ["# A scaling model past this machine", "", benchutil.measured_by("scaling_model.py", ROOT), "",
         f"The case: the hemispherical punch blank (quarter, O-grid, `-blank_core_cells {a.core} -blank_radial_cells {a.radial} -blank_layers {a.layers}`): "
         f"{mesh['cells']} hexahedra, {mesh['vertices']} vertices, {mesh['slaves']} contact slave nodes (top and bottom).", "",
         "## Partitions (measured)", "",
         "METIS as the code calls it by default (`METIS_PartMeshDual`, 4 common nodes, seed 7). A vertex is owned by the lowest-numbered part around it "
         "(the model's assumption). Imbalance = largest / mean over the parts.", "",
         "| parts | edge cut | cells max | cell imbalance | owned vertices max | ghost vertices max (mean) | ghost share max | neighbours max (mean) | slave nodes max (mean) | slave imbalance | METIS s |",
         "|---|---|---|---|---|---|---|---|---|---|---|"]
    for r in rows:
        L.append(f"| {int(r['parts'])} | {int(r['cut'])} | {int(r['cells_max'])} | {r['cells_max'] / r['cells_mean']:.3f} | {int(r['verts_owned_max'])} | "
                 f"{int(r['ghosts_max'])} ({r['ghosts_mean']:.0f}) | {r['ghost_frac_max']:.3f} | {int(r['neighbours_max'])} ({r['neighbours_mean']:.1f}) | "
                 f"{int(r['slaves_max'])} ({r['slaves_mean']:.0f}) | {r['slaves_max'] / r['slaves_mean']:.3f} | {r['seconds']:.2f} |")
    L += ["", "## Unit costs (measured on one core of this machine)", ""]
    if a.no_measure:
        L.append("Not measured in this run (--no-measure): the assembly costs of doc/notes/performance-log.md; no Krylov cost, so no model below.")
    else:
        L += [f"From `cases/hemisphere_friction_refined.opts` ({c['ncell']} hexahedra, {c['nslave']} slave nodes, 3 load steps, `-log_view`):",
              f"Jacobian assembly {1e6 * c['t_jac']:.2f} µs per element, residual {1e6 * c['t_res']:.2f} µs per element, contact "
              f"{1e6 * c['t_contact']:.3f} µs per slave node and evaluation. The iterative solver of the million-hexahedra case "
              f"(`cases/solver_amgsys.opts`: BiCGStab, BoomerAMG with {SWEEPS} sweeps, `-ksp_rtol 1e-3`) on the whole blank of {c['amg_cells']} hexahedra "
              f"(`cases/hemisphere_friction_disk.opts`, one load step of 1 mm, {c['ndof']} unknowns): {1e6 * c['t_kry']:.2f} µs per unknown and Krylov iteration "
              f"(KSPSolve less PCSetUp; one BiCGStab iteration applies the operator and the V-cycle twice; {c['kry_its']:.0f} iterations per linear solve, "
              f"at most {c['kry_most']}), BoomerAMG's setup {1e6 * c['t_setup']:.2f} µs per unknown and Newton iteration. "
              f"Machine load (1-minute average) before and after: {c['load'][0]:.2f}, {c['load'][1]:.2f} on {os.cpu_count()} cores: "
              "with other work running the unit costs are overstated, the ratios between ranks are not."]
    if not a.no_measure:
        L += ["", "## The model", "",
              f"Per Newton iteration on the slowest rank: one Jacobian and {N_RES:g} residual assemblies over its cells, the contact of its "
              f"slave nodes at each, BoomerAMG's setup and {N_KRY} BiCGStab iterations over its unknowns (the bound the iterative solver "
              f"has to hold; the million-hexahedra step's mean was 49, its most 78), and the communication: a ghost exchange per assembly and "
              f"{EXCH_PER_KRY} per Krylov iteration (two operator applications and two V-cycles over {AMG_LEVELS} levels, assumed, with "
              f"{SWEEPS} sweeps down and up and 3 transfers per level, each exchange counted at the finest level's size), each one message "
              f"per neighbour of latency {ALPHA * 1e6:g} µs and the ghost values (3 doubles per vertex, both ways) at {1 / BETA / 1e9:g} GB/s, "
              f"plus {ALLRED_PER_KRY} allreduces of log2(P) latencies per Krylov iteration. Not modelled: BoomerAMG's setup communication "
              "and its coarse levels' load balance (which limit it beyond a few thousand ranks), memory bandwidth shared by the cores of a "
              "node (the unit costs are one core's with the machine to itself; measured on 16 cores: Measured on more cores, below), output.", "",
              "| ranks | assembly s | contact s | Krylov s | communication s | time per Newton iteration s | efficiency | cell imbalance | slave imbalance |",
              "|---|---|---|---|---|---|---|---|---|"]
        for r in m:
            L.append(f"| {r['P']} | {r['asm']:.4f} | {r['con']:.4f} | {r['kry']:.4f} | {r['comm']:.5f} | {r['T']:.4f} | {100 * r['eff']:.0f} % | {r['imb_c']:.3f} | {r['imb_s']:.3f} |")
        t1 = m[0]["T"]
        L += ["", "Against the whole steps measured on this machine (2 ranks, doc/notes/performance-log.md, One million hexahedra; the model at 2 ranks "
              "taken as its 1-rank time over 2 scaled to the case's unknowns, i.e. perfectly balanced, no communication):", "",
              "| hexahedra | unknowns | ranks | measured s per Newton iteration | model s | measured / model | measured run |", "|---|---|---|---|---|---|---|"]
        for cells, dofs, P, meas, what in MEASURED:
            mod = t1 * dofs / (3 * mesh["vertices"]) / P
            L.append(f"| {cells} | {dofs} | {P} | {meas:.0f} | {mod:.0f} | {meas / mod:.2f} | {what} |")
        L += ["", "The measured Newton iteration includes its share of the step's other solves (the predictor's) and the machine's two "
              "cores share one memory bus: a Krylov iteration over 1.9 million unknowns per rank costs more per unknown than over the "
              f"{c['ndof']} of the unit-cost run (caches). Read the table above with that factor on the Krylov column at the smallest rank "
              "counts; from 64 ranks on (60 000 unknowns per rank and fewer) the unit-cost run's size applies."]
        L += ["", "Reading: the cells stay balanced to a few per cent up to 1024 parts, the contact slave nodes do not (METIS balances cells "
              "only, and a vertex on a part boundary goes to one of its parts): their imbalance grows with the number of parts, but contact is a small share of the time per iteration (`-partition_balance contact`: below). The "
              "communication share grows with the ghost share of the parts."]
    L.append("")
    # the sections that scripts/partition_balance.py and --measured write (the last ones) are kept
    doc = os.path.join(ROOT, "doc", "scaling-model.md")
    if os.path.exists(doc):
        old = open(doc).read()
        i = old.find("\n## Balancing the contact nodes (measured)")
        if i >= 0:
            L.append(old[i + 1:].rstrip("\n") + "\n")
    with open(doc, "w") as f:
        f.write("\n".join(L))
    print("\n".join(L))


if __name__ == "__main__":
    main()
