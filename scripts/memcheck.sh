#!/usr/bin/env bash
# valgrind's memcheck over the unit-test programs and short runs of the solver paths (`make
# memcheck`, which builds the programs of bin-vg/ first): reads of memory never written, invalid
# accesses and bad frees. The sanitizers of tests/test_memory.sh find invalid accesses and leaks
# but not uninitialised reads; this pass does, at some 30 to 50 times the run time: about 9
# minutes on 2 cores, so the whole pass is not part of the test suite. Leaks are left to
# tests/test_memory.sh (PETSc's -malloc_dump): MPI's libraries keep memory until exit.
#
#   bash scripts/memcheck.sh [--quick]
#
# --quick: only the unit tests of the contact object and of the sheet's coarse space and the
# frictional and augmented runs (about a minute; tests/test_valgrind.sh runs these in `make check`).
# Each program must exit 0 with no error reported (valgrind's --error-exitcode); reports inside
# Open MPI's runtime thread are suppressed by tests/valgrind.supp. The logs go to $MEMCHECK_OUT
# (default out/memcheck); a program still running after $MEMCHECK_TIMEOUT s (default 1200) is
# stopped and fails. Ends with "N passed, N failed", non-zero if any failed.
set -u
QUICK=0
case "${1:-}" in
  --quick) QUICK=1 ;;
  "") ;;
  *) echo "memcheck: error: unknown argument '$1' (the only option is --quick)" >&2; exit 1 ;;
esac
cd "$(dirname "$0")/.."
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 OMPI_MCA_rmaps_base_oversubscribe=1
export OPENBLAS_NUM_THREADS=1
if ! command -v valgrind >/dev/null 2>&1; then
  echo "memcheck: error: valgrind is not installed (Debian package valgrind: apt-get install valgrind)" >&2
  exit 1
fi
OUT=${MEMCHECK_OUT:-out/memcheck}
rm -rf "$OUT" && mkdir -p "$OUT"
VG=(valgrind -q --error-exitcode=99 --track-origins=yes --suppressions=tests/valgrind.supp)
pass=0 fail=0

# check NAME NP PROGRAM ARGS...: PROGRAM under valgrind on NP ranks (NP 0: without mpiexec); with
# DONE=1 the log must also hold the solver's last line ("done: N steps ...")
check() {
  local name=$1 np=$2; shift 2
  local t0=$SECONDS rc
  local launch=(); [ "$np" -gt 0 ] && launch=(mpiexec -n "$np")
  timeout "${MEMCHECK_TIMEOUT:-1200}" "${launch[@]}" "${VG[@]}" "$@" >"$OUT/$name.log" 2>&1 </dev/null; rc=$?
  local errs ended=1; errs=$(grep -c '^==[0-9]*== [A-Z]' "$OUT/$name.log")
  [ "${DONE:-0}" -eq 1 ] && ! grep -q '^done: ' "$OUT/$name.log" && ended=0
  if [ $rc -eq 0 ] && [ "$errs" -eq 0 ] && [ $ended -eq 1 ]; then
    pass=$((pass + 1)); echo "ok - $name: no error ($((SECONDS - t0)) s)"
  else
    fail=$((fail + 1))
    echo "not ok - $name: exit $rc$([ $rc -eq 124 ] && echo ' (past MEMCHECK_TIMEOUT)'), $errs valgrind report lines$([ $ended -eq 0 ] && echo ', the run did not end') ($OUT/$name.log)"
    if grep -q '^==[0-9]*== ' "$OUT/$name.log"; then grep -m 8 '^==[0-9]*== ' "$OUT/$name.log"
    else grep -m 4 'error' "$OUT/$name.log"; fi | sed 's/^/    /'
  fi
}

# (not test_tool: its brute-force reference projections, spread over the whole program, take
# over 10 minutes under valgrind; tests/test_memory.sh runs it under the sanitizers. The runs below
# project on planes, spheres, cylinders, tori, Coons patches and meshed tools read from STL, Gmsh
# and Abaqus files)
if [ $QUICK -eq 1 ]; then
  check test_contact_object-np2 2 bin-vg/test_contact_object
  check test_sheetcoarse-np2 2 bin-vg/test_sheetcoarse
else
  for t in material hill48 yld91 umat fe eas meshgen contact; do
    check "test_$t" 0 "bin-vg/test_$t"
  done
  for t in loadcurve contact_object toolforce lu predictor linesearch sheetcoarse; do
    check "test_$t-np2" 2 "bin-vg/test_$t"
  done
  check test_output-np2 2 bin-vg/test_output -output_dir "$OUT/output"
fi

# run NAME NP ARGS...: the solver under valgrind, to the end of its run
run() {
  local name=$1 np=$2; shift 2
  DONE=1 check "$name" "$np" bin-vg/atrito "$@" -output_dir "$OUT/$name"
}
# frictional contact with the first iteration's keep, the frame carried by rotation and the
# predictor's curvature (an unpaired node found by a line-search trial read a frame seed never set)
run seed_friction_keepall 2 -options_file cases/hemisphere_friction.opts -tool_punch_motion 0,0,8 \
  -load_steps 4 -newton_keep_contact all -contact_frame_carry rotation -load_predictor_curvature 0.5
run block_sphere_augmented 1 -options_file cases/block_sphere.opts -contact_augmented
if [ $QUICK -eq 1 ]; then
  echo "$pass passed, $fail failed"
  [ "$fail" -eq 0 ]; exit
fi
run forcetool_holder 2 -options_file cases/forcetool_holder.opts
run kink_retract 1 -options_file cases/kink_retract.opts
run stages_release 1 -options_file cases/stages_release.opts
# Hill 1948, hex8_eas, the force-driven holder, stages: the U-channel's close stage and its draw's
# first 1.4 mm (the release and springback stages left out: their options are reported unused)
run uchannel_start 1 -options_file cases/numisheet93_uchannel_coarse.opts -stage_names close,draw \
  -stage_draw_duration 0.02 -stage_draw_steps 2 -stage_draw_dt_max 0.01
# meshed tools: an STL ball with friction (Nagata smoothing, the hinted projection), the seed
# mesh's tools from a Gmsh file (2 ranks) and from an Abaqus deck's surface groups
run block_sphere_stl 1 -options_file cases/block_sphere_stl.opts
run seed_msh24 2 -options_file cases/hemisphere_frictionless_msh24.opts -tool_punch_motion 0,0,4 -load_steps 2
run seed_inp24 1 -options_file cases/hemisphere_frictionless_inp24.opts -tool_punch_motion 0,0,4 -load_steps 2
# the iterative solver (BoomerAMG through -pc_type amgsys) on a small whole blank
run amgsys_disk 2 -options_file cases/hemisphere_friction_disk.opts -options_file cases/solver_amgsys.opts \
  -blank_core_cells 4 -blank_radial_cells 10 -blank_layers 2 -tool_punch_motion 0,0,1 -load_steps 1
# the same with the sheet's coarse space (the iterate composed on the Jacobian, hypre's vectors as work)
run amgsys_sheet_disk 2 -options_file cases/hemisphere_friction_disk.opts -options_file cases/solver_amgsys_sheet.opts \
  -blank_core_cells 4 -blank_radial_cells 10 -blank_layers 2 -tool_punch_motion 0,0,1 -load_steps 1

echo "$pass passed, $fail failed"
[ "$fail" -eq 0 ]
