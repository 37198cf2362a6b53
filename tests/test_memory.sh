#!/usr/bin/env bash
# Memory checks: every unit-test program under AddressSanitizer and UndefinedBehaviorSanitizer
# (invalid accesses, undefined behaviour, and leaks for the programs without MPI), and PETSc's
# -malloc_debug -malloc_dump (every PETSc allocation freed) for the programs with MPI and for
# integration runs of the solver (plasticity, contact, checkpoint and restart, 1 and 2 ranks).
set -u
cd "$(dirname "$0")/.."
. tests/lib.sh
OUT=$(test_out memory)
if ! make -s sanitize >"$OUT/build.log" 2>&1; then not_ok "sanitizer build failed"; tail -5 "$OUT/build.log"; exit 1; fi
export UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1

leaks() { grep -cE '^\[ *[0-9]+\] *[0-9]+ bytes' "$1"; }

# san NAME: bin-san/test_NAME under the sanitizers; its report line goes to $OUT/NAME.res.
# test_contact has no MPI: LeakSanitizer checks its leaks. The others use MPI, whose plugins keep
# memory until exit: their leaks are checked by PETSc's -malloc_dump instead.
san() {
  local t=$1 rc n l
  if [ "$t" = contact ]; then
    ASAN_OPTIONS=detect_leaks=1 bin-san/test_$t >"$OUT/test_$t.log" 2>&1; rc=$?
    n=$(grep -c '^ok' "$OUT/test_$t.log")
    [ $rc -eq 0 ] && [ "$n" -gt 0 ] && ! grep -q 'ERROR: \|runtime error' "$OUT/test_$t.log" && ok "test_$t under ASan/UBSan/LSan: $n checks, no invalid access, no leak" ||
      { not_ok "test_$t under the sanitizers (exit $rc)"; grep -m5 'ERROR\|runtime error\|SUMMARY' "$OUT/test_$t.log" | indent; }
  else
    ASAN_OPTIONS=detect_leaks=0 bin-san/test_$t -malloc_debug -malloc_dump >"$OUT/test_$t.log" 2>&1; rc=$?
    n=$(grep -c '^ok' "$OUT/test_$t.log"); l=$(leaks "$OUT/test_$t.log")
    [ $rc -eq 0 ] && [ "$n" -gt 0 ] && [ "$l" -eq 0 ] && ! grep -q 'ERROR: \|runtime error' "$OUT/test_$t.log" && ok "test_$t under ASan/UBSan and -malloc_dump: $n checks, no invalid access, no unfreed PETSc memory" ||
      { not_ok "test_$t (exit $rc, $n checks, $l unfreed blocks)"; grep -m5 'ERROR\|runtime error\|bytes' "$OUT/test_$t.log" | indent; }
  fi >"$OUT/$t.res"
}
# every unit-test program (the programs with MPI on one rank). test_tool, whose brute-force
# reference projections take some 45 s under the sanitizers, runs beside all the rest, which run
# one after the other on the other core.
UNITS=$(ls tests/test_*.c | sed 's|tests/test_\(.*\)\.c|\1|')
san tool & TOOL_PID=$!
for t in $UNITS; do [ "$t" = tool ] || san "$t"; done
md() { # md NP NAME ARGS...: an integration run under -malloc_debug -malloc_dump
  local np=$1 name=$2; shift 2
  atrito_rc "$np" "$name" "$@" -malloc_debug -malloc_dump
  local l; l=$(leaks "$OUT/$name.log")
  [ $RC -eq 0 ] && [ "$l" -eq 0 ] && ok "-malloc_debug -malloc_dump, $name (np=$np): clean exit, no unfreed memory" ||
    { not_ok "$name (np=$np) under -malloc_dump: exit $RC, $l unfreed blocks"; grep -m5 'bytes\|error' "$OUT/$name.log" | indent; }
}
md 1 contact -options_file cases/block_sphere.opts -checkpoint_interval 4 -load_max_steps 100
md 2 restart -options_file cases/block_sphere.opts -restart "$OUT/contact/checkpoint.h5" -output_interval 0
md 2 coons -options_file cases/hemisphere_friction.opts -tool_punch_motion 0,0,2 -load_steps 2 -assembly_coo 1
md 2 gmsh -mesh_file tests/data/two_hex.msh -bc_names fix,pull -bc_fix_set left -bc_pull_set right -bc_fix_components x,y,z -bc_pull_components x -bc_pull_values 0.2 -load_steps 2
md 2 amgdisk -options_file cases/hemisphere_friction_disk.opts -options_file cases/solver_amg_sheet.opts -blank_core_cells 4 -blank_radial_cells 10 -blank_layers 2 -tool_punch_motion 0,0,1 -load_steps 1 -output_interval 0
wait $TOOL_PID
for t in $UNITS; do
  if [ -s "$OUT/$t.res" ]; then cat "$OUT/$t.res"; else not_ok "test_$t under the sanitizers: no report"; fi
done
