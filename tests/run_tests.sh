#!/usr/bin/env bash
# Test runner: every test program prints one line per check, "ok - ..." or "not ok - ...";
# this script runs them all and ends with the line "N passed, N failed".
# A new test: a program tests/test_NAME.c (built by make as bin/test_NAME) or a script
# tests/test_NAME.sh (sourcing tests/lib.sh), printing its lines, and one `run` line below.
set -u
cd "$(dirname "$0")/.."
# the tests build with make themselves (tests/test_memory.sh, test_valgrind.sh): each such make
# is a make of its own, on all cores, not a sub-make of the `make check` that may have started this
unset MAKEFLAGS MFLAGS MAKELEVEL
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 OMPI_MCA_odls_base_sigkill_timeout=${OMPI_MCA_odls_base_sigkill_timeout:-0}
export OPENBLAS_NUM_THREADS=${OPENBLAS_NUM_THREADS:-1} OMPI_MCA_rmaps_base_oversubscribe=1 OMPI_MCA_btl_vader_single_copy_mechanism=none
export PYTHON=${PYTHON:-/usr/bin/python3}
export TEST_OUT=${TEST_OUT:-build/test-out}
rm -rf "$TEST_OUT"; mkdir -p "$TEST_OUT"
pass=0; fail=0

run() { # run NAME CMD...: count its ok / not ok lines; a crash or non-zero exit without a failed check is a failure
  local name=$1; shift
  local log="$TEST_OUT/$name.log" t0=$SECONDS
  "$@" >"$log" 2>&1; local rc=$?
  local p f
  p=$(grep -c '^ok ' "$log"); f=$(grep -c '^not ok ' "$log")
  grep -E '^(ok|not ok) ' "$log" | sed "s/^/[$name] /"
  if [ "$rc" -ne 0 ] && [ "$f" -eq 0 ]; then
    f=1; echo "[$name] not ok - exited with status $rc"; tail -n 15 "$log" | sed 's/^/    /'
  fi
  if [ "$p" -eq 0 ] && [ "$f" -eq 0 ]; then f=1; echo "[$name] not ok - ran no check"; fi
  echo "[$name] $p passed, $f failed ($((SECONDS - t0)) s)"
  pass=$((pass + p)); fail=$((fail + f))
}

run build           bash tests/test_build.sh
run material        bin/test_material
run hill48          bin/test_hill48
run yld91           bin/test_yld91
run umat            bin/test_umat
run fe              bin/test_fe
run eas             bin/test_eas
run meshgen         bin/test_meshgen
run loadcurve-np1   mpiexec -n 1 bin/test_loadcurve
run loadcurve-np2   mpiexec -n 2 bin/test_loadcurve
run tool            bin/test_tool
run contact-kernels bin/test_contact
run nts             bin/test_nts
run contact-object-np1 mpiexec -n 1 bin/test_contact_object
run contact-object-np2 mpiexec -n 2 bin/test_contact_object
run toolforce-np1   mpiexec -n 1 bin/test_toolforce
run toolforce-np2   mpiexec -n 2 bin/test_toolforce
run output-np1      mpiexec -n 1 bin/test_output -output_dir "$TEST_OUT/output1"
run output-np2      mpiexec -n 2 bin/test_output -output_dir "$TEST_OUT/output2"
run lu-np1          mpiexec -n 1 bin/test_lu
run lu-np2          mpiexec -n 2 bin/test_lu
run bordered-np1    mpiexec -n 1 bin/test_bordered
run bordered-np2    mpiexec -n 2 bin/test_bordered
run sheetcoarse-np1 mpiexec -n 1 bin/test_sheetcoarse
run sheetcoarse-np2 mpiexec -n 2 bin/test_sheetcoarse
run predictor-np1   mpiexec -n 1 bin/test_predictor
run predictor-np2   mpiexec -n 2 bin/test_predictor
run linesearch-np1  mpiexec -n 1 bin/test_linesearch
run linesearch-np2  mpiexec -n 2 bin/test_linesearch
run solver          bash tests/test_solver.sh
run hill48-solver   bash tests/test_hill48.sh
run contact         bash tests/test_contact.sh
run newton          bash tests/test_newton.sh
run activeset       bash tests/test_activeset.sh
run auglag          bash tests/test_auglag.sh
run hertz           bash tests/test_hertz.sh
run pairs           bash tests/test_pairs.sh
run benchmark       bash tests/test_benchmark.sh
run facets          bash tests/test_facets.sh
run partition       bash tests/test_partition.sh
run reference       bash tests/test_reference.sh
run restart         bash tests/test_restart.sh
run stages          bash tests/test_stages.sh
run forcetool       bash tests/test_forcetool.sh
run eas-solver      bash tests/test_eas.sh
run scripts         bash tests/test_scripts.sh
run options         bash tests/test_options.sh
run doc             bash tests/test_doc.sh
run bad-input       bash tests/test_bad_input.sh
run umat-runs       bash tests/test_umat.sh
run tutorial       bash tests/test_tutorial.sh
run memory          bash tests/test_memory.sh
run valgrind        bash tests/test_valgrind.sh

echo "$pass passed, $fail failed"
[ "$fail" -eq 0 ]
