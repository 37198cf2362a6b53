#!/usr/bin/env bash
# Integration tests of the solver paths, at 1 and 2 ranks. Each check prints "ok - ..." or
# "not ok - ...".
set -u
cd "$(dirname "$0")/.."
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 OPENBLAS_NUM_THREADS=${OPENBLAS_NUM_THREADS:-1}
PY=${PYTHON:-/usr/bin/python3}
OUT=${TEST_OUT:-build/test-out}/solver
rm -rf "$OUT"; mkdir -p "$OUT"
A="bin/atrito"
MPI="mpiexec --oversubscribe -n"
SWIFT="589 1e-4 0.216 69004"

atrito() { # atrito NP NAME ARGS...: run, log to $OUT/NAME.log, report a failed run
  local np=$1 name=$2; shift 2
  if ! timeout 600 $MPI "$np" $A "$@" -output_dir "$OUT/$name" >"$OUT/$name.log" 2>&1; then
    echo "not ok - run $name (np=$np) failed:"; tail -n 5 "$OUT/$name.log" | sed 's/^/    /'; return 1
  fi
}

# 1. uniaxial tension to 30 % strain against the closed form, at 1 and 2 ranks
for np in 1 2; do
  atrito $np tension$np -options_file cases/tension_bar.opts &&
    $PY tests/check_tension.py "$OUT/tension$np/history.csv" pull_fx 1 10 3 $SWIFT 1e-6
done
$PY tests/compare_history.py "$OUT/tension1/history.csv" "$OUT/tension2/history.csv" 8 "tension bar: np=1 and np=2 (METIS) histories"

# 2. the fields of the tension run: valid HDF5/XDMF, end displacement and plastic strain exact
$PY tests/check_fields.py "$OUT/tension2" -q >/dev/null && echo "ok - tension bar fields.h5 and fields.xmf valid (np=2)" || echo "not ok - tension bar fields invalid"
$PY - "$OUT/tension2/fields.h5" <<'PYEOF'
import sys, math, h5py, numpy as np
f = h5py.File(sys.argv[1], "r")
last = sorted(f["steps"].keys())[-1]
g = f["steps"][last]
X = f["mesh/coordinates"][:]
u = g["displacement"][:]
ep = g["plastic_strain"][:]
# homogeneous: u_x = 0.3 x exactly; ep from the closed form at stretch 1.3
eu = np.abs(u[:, 0] - 0.3 * X[:, 0]).max()
E, K, e0, n, lam = 69004.0, 589.0, 1e-4, 0.216, 1.3
lo, hi = 0.0, E * math.log(lam)
for _ in range(200):
    s = 0.5 * (lo + hi)
    (lo, hi) = (lo, s) if s - K * (e0 + math.log(lam) - s / E) ** n > 0 else (s, hi)
ep_ref = math.log(lam) - s / E
eep = np.abs(ep - ep_ref).max() / ep_ref
ok = float(g.attrs["time"]) == 1.0 and eu < 1e-9 and eep < 1e-8
print(("ok" if ok else "not ok") + f" - tension bar fields at time 1: |u_x - 0.3 x| {eu:.1e}, plastic strain {ep.mean():.6f} vs closed form {ep_ref:.6f} (rel {eep:.1e})")
PYEOF

# 3. -snes_test_jacobian on a small plastic problem, F-bar and standard elements
for fbar in 1 0; do
  atrito 1 jac$fbar -options_file cases/clamped_beam.opts -box_cells 3,1,2 -load_steps 3 -output_interval 0 -fe_fbar $fbar -snes_test_jacobian &&
    $PY - "$OUT/jac$fbar.log" "$fbar" <<'PYEOF'
import re, sys
r = [float(x) for x in re.findall(r"\|\|J - Jfd\|\|_F/\|\|J\|\|_F = ([0-9.eE+-]+)", open(sys.argv[1]).read())]
ok = len(r) >= 6 and max(r) < 1e-6
print(("ok" if ok else "not ok") + f" - -snes_test_jacobian, plastic, {'F-bar' if sys.argv[2] == '1' else 'standard'} element: {len(r)} Jacobians, largest ||J - Jfd||/||J|| = {max(r) if r else float('nan'):.2e}")
PYEOF
done

# 4. the same non-homogeneous cases at 1 and 2 ranks, METIS and simple partitions: same history
atrito 1 beam1 -options_file cases/clamped_beam.opts -output_interval 0
atrito 2 beam2 -options_file cases/clamped_beam.opts -output_interval 0
atrito 2 beam2s -options_file cases/clamped_beam.opts -output_interval 0 -partition simple
$PY tests/compare_history.py "$OUT/beam1/history.csv" "$OUT/beam2/history.csv" 8 "clamped beam: np=1 and np=2 (METIS)"
$PY tests/compare_history.py "$OUT/beam1/history.csv" "$OUT/beam2s/history.csv" 8 "clamped beam: np=1 and np=2 (simple partition)"
# the two LU paths: MUMPS with the METIS nested-dissection ordering (default) and MUMPS's own
# ordering through PETSc's interface; the default analyses the pattern once per run
atrito 2 beam2m -options_file cases/clamped_beam.opts -output_interval 0 -lu_ordering mumps
$PY tests/compare_history.py "$OUT/beam2/history.csv" "$OUT/beam2m/history.csv" 10 "clamped beam (np=2): -lu_ordering nd and -lu_ordering mumps"
atrito 2 beam2v -options_file cases/clamped_beam.opts -output_interval 0 -load_steps 4 -ksp_view
v=$(grep -c "LU by MUMPS, METIS nested-dissection ordering" "$OUT/beam2v.log"); a=$(grep -o "unknowns; [0-9]* analyses" "$OUT/beam2v.log" | sort -u | tr '\n' ' ')
s=$(grep -o "^step *[0-9]*" "$OUT/beam2v.log" | wc -l)
[ "$v" -ge 1 ] && [ "$a" = "unknowns; 1 analyses " ] && [ "$s" -ge 4 ] && echo "ok - -ksp_view (np=2): LU with the METIS ordering, one analysis for all $s steps ($v solves)" || echo "not ok - -ksp_view: '$v' views, analyses '$a', $s steps"
atrito 1 blank1 -options_file cases/blank_point.opts -output_interval 3
atrito 2 blank2 -options_file cases/blank_point.opts -output_interval 3
$PY tests/compare_history.py "$OUT/blank1/history.csv" "$OUT/blank2/history.csv" 8 "quarter blank (O-grid): np=1 and np=2 (METIS)"
grep -q "cells per rank: [1-9][0-9]* [1-9][0-9]*$" "$OUT/blank2.log" && echo "ok - partition report: $(grep -o 'cells per rank.*' "$OUT/blank2.log")" || echo "not ok - no cells-per-rank report"
$PY tests/check_fields.py "$OUT/blank2" -q >/dev/null && $PY - "$OUT/blank2/fields.h5" <<'PYEOF'
import sys, h5py, numpy as np
f = h5py.File(sys.argv[1], "r")
g = f["steps"][sorted(f["steps"].keys())[-1]]
t = g["thickness_strain"][:]
ok = t.min() < -1e-3 and t.max() < 1e-2
print(("ok" if ok else "not ok") + f" - blank fields: thickness strain in [{t.min():.4f}, {t.max():.4f}] (thinning under the push)")
PYEOF

# 5. the three mesh sources agree: box, Gmsh file and .inp deck of the same two hexahedra
common="-bc_names fix,pull -bc_fix_components x,y,z -bc_pull_components x -bc_pull_values 0.2 -load_steps 4 -output_interval 0"
atrito 1 src_box -mesh_type box -box_upper 2,1,1 -box_cells 2,1,1 $common -bc_fix_set xmin -bc_pull_set xmax
atrito 2 src_msh -mesh_file tests/data/two_hex.msh $common -bc_fix_set left -bc_pull_set right
atrito 1 src_inp -mesh_file tests/data/two_hex.inp $common -bc_fix_set Left -bc_pull_set Right
for s in msh inp; do
  $PY tests/compare_history.py "$OUT/src_box/history.csv" "$OUT/src_$s/history.csv" 10 "two hexahedra: box and $s mesh give the same history"
done

# 6. failed steps are retried smaller, easy steps grow again, and a run that cannot go on stops
#    with a message naming the cause while its history stays whole and valid
atrito 1 cut_newton -options_file cases/tension_bar.opts -load_steps 1 -snes_max_it 2 -output_interval 0 &&
  n=$(grep -c "retrying with increment" "$OUT/cut_newton.log") && g=$(grep -c "did not converge in the allowed iterations" "$OUT/cut_newton.log") &&
  [ "$n" -ge 1 ] && [ "$g" -ge 1 ] && $PY tests/check_tension.py "$OUT/cut_newton/history.csv" pull_fx 1 10 3 $SWIFT 1e-6 | sed "s/^\(n*o*t* *ok\) - /\1 - after $n cuts (Newton iteration limit): /" ||
  echo "not ok - Newton failure was not retried"
atrito 1 cut_stall -options_file cases/tension_bar.opts -load_steps 1 -newton_stall_its 1 -newton_stall_factor 1e-3 -output_interval 0 &&
  n=$(grep -c "Newton stalled (|R| .* did not fall below 0.001 times its value 1 iterations earlier, -newton_stall_its); retrying" "$OUT/cut_stall.log") && [ "$n" -ge 1 ] &&
  $PY tests/check_tension.py "$OUT/cut_stall/history.csv" pull_fx 1 10 3 $SWIFT 1e-6 | sed "s/^\(n*o*t* *ok\) - /\1 - after $n cuts (Newton stalled): /" ||
  echo "not ok - a stalled Newton solve was not cut"
atrito 1 cut_retmap -options_file cases/tension_bar.opts -load_steps 1 -material_return_maxit 3 -output_interval 0 &&
  n=$(grep -c "the local return map did not converge (element id [0-9]*); retrying" "$OUT/cut_retmap.log") && [ "$n" -ge 1 ] &&
  $PY tests/check_tension.py "$OUT/cut_retmap/history.csv" pull_fx 1 10 3 $SWIFT 1e-6 | sed "s/^\(n*o*t* *ok\) - /\1 - after $n cuts (return map failure): /" ||
  echo "not ok - return-map failure was not retried"
$MPI 2 $A -options_file cases/tension_bar.opts -load_steps 2 -bc_pull_values -10.5 -load_max_cuts 3 -output_interval 1 -output_dir "$OUT/cut_fail" >"$OUT/cut_fail.log" 2>&1 </dev/null
rc=$?
$PY - "$OUT/cut_fail" "$rc" <<'PYEOF'
import csv, re, sys, subprocess
d, rc = sys.argv[1], int(sys.argv[2])
log = open(d + ".log").read()
m = re.search(r"atrito: error: step (\d+) failed at load ([0-9.]+) .* after \d+ cuts: (.*); the results up to load ([0-9.]+) are complete", log)
rows = list(csv.DictReader(open(d + "/history.csv")))
whole = all(len(r) == len(rows[0]) and None not in r.values() for r in rows)
last = float(rows[-1]["time"]) if rows else -1
fields = subprocess.run([sys.executable, "tests/check_fields.py", d, "-q"], capture_output=True).returncode == 0
ok = rc not in (0,) and rc < 124 and m is not None and whole and abs(last - float(m.group(4))) < 1e-6 and fields
print(("ok" if ok else "not ok") + f" - impossible compression stops cleanly (np=2, exit {rc}): " + (f"step {m.group(1)} failed at load {m.group(2)}: {m.group(3)}; history has {len(rows)} whole rows up to {last:.6f}, fields valid {fields}" if m else "no final message"))
PYEOF

# 7. a NaN in the residual (fault injection): retried with a smaller increment; with no cut
#    allowed, the run stops naming the cause and the load
atrito 1 nan -options_file cases/tension_bar.opts -fault_nan_residual_at 0.5 -output_interval 0 &&
  grep -q "NaN or Inf in the residual; retrying" "$OUT/nan.log" &&
  $PY tests/check_tension.py "$OUT/nan/history.csv" pull_fx 1 10 3 $SWIFT 1e-6 | sed "s/^\(n*o*t* *ok\) - /\1 - after a NaN residual, retried: /" ||
  echo "not ok - a NaN residual was not retried"
$MPI 2 $A -options_file cases/tension_bar.opts -fault_nan_residual_at 0.5 -load_max_cuts 0 -output_interval 0 -output_dir "$OUT/nanfail" >"$OUT/nanfail.log" 2>&1 </dev/null
rc=$?
msg=$(grep -o "atrito: error: step [0-9]* failed at load [0-9.]* .*NaN or Inf in the residual.*" "$OUT/nanfail.log" | head -1)
[ $rc -ne 0 ] && [ $rc -lt 124 ] && [ -n "$msg" ] && echo "ok - a NaN with no cut allowed stops the run (np=2, exit $rc): ${msg:0:110}" || echo "not ok - NaN final message (exit $rc)"

# 8. the iterative solver path: GMRES with algebraic multigrid and the rigid-body near-null
#    space, at 1 and 2 ranks, against the direct solver's history
GAMG="-ksp_type gmres -pc_type gamg -ksp_rtol 1e-12 -ksp_max_it 400"
atrito 1 gamg1 -options_file cases/clamped_beam.opts -output_interval 0 $GAMG
atrito 2 gamg2 -options_file cases/clamped_beam.opts -output_interval 0 $GAMG
$PY tests/compare_history.py "$OUT/beam1/history.csv" "$OUT/gamg1/history.csv" 8 "clamped beam: GMRES+GAMG (np=1) against LU"
$PY tests/compare_history.py "$OUT/beam1/history.csv" "$OUT/gamg2/history.csv" 8 "clamped beam: GMRES+GAMG (np=2) against LU"
