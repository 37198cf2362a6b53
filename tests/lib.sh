# Shared by the integration test scripts (tests/test_*.sh); source it after cd to the repository
# root:   cd "$(dirname "$0")/.." && . tests/lib.sh
# Every check prints one line "ok - ..." or "not ok - ..." (tests/run_tests.sh counts them).
#
#   OUT=$(test_out NAME)          a fresh output folder $TEST_OUT/NAME
#   atrito NP NAME ARGS...        run bin/atrito on NP ranks with -output_dir $OUT/NAME, log in
#                                 $OUT/NAME.log; prints "not ok" and returns 1 if the run fails
#   atrito_rc NP NAME ARGS...     the same for a run expected to fail: no report, exit status in RC
#   ok MSG / not_ok MSG           a check's line;  cmd | indent  for details under it
#   alone NP DIR ARGS...          a run expected to fail, again, where a rank left waiting in a
#                                 collective hangs (exit 124) instead of being killed
#   alone_ok NP NAME LABEL ARGS...  the same as a check line of its own (output in $OUT/NAME.alone)
#   compare A B DIGITS LABEL      two CSV histories to DIGITS digits (tests/compare_history.py)
#   pycheck NAME ARGS...          tests/checks/NAME.py (prints its own ok / not ok line)
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
# when a rank exits non-zero (every bad-input run), mpiexec ends the job's other processes with
# SIGTERM and, 1 s later, SIGKILL, and waits that second even when none is left: 1 to 2 s a run.
# The tests kill at once: an error's exit status and its one line are the same either way.
export OMPI_MCA_odls_base_sigkill_timeout=${OMPI_MCA_odls_base_sigkill_timeout:-0}
export OPENBLAS_NUM_THREADS=${OPENBLAS_NUM_THREADS:-1}
# the seed cases' stepping of before 2026-11-29 (first increment 1/40 grown by 1.5 up to 1/20, the
# linear extrapolation), given on the command line where a test measures a state of that run
DEFSTEP="-load_steps 40 -load_dt_max 0.05 -load_grow_factor 1.5 -load_predictor_curvature 0"
PY=${PYTHON:-/usr/bin/python3}
TEST_OUT=${TEST_OUT:-build/test-out}
A=bin/atrito
MPI="mpiexec --oversubscribe -n"
ATRITO_TIMEOUT=${ATRITO_TIMEOUT:-600}
# Swift hardening of the benchmark's aluminium (tests/check_tension.py's K EPS0 N E)
SWIFT="589 1e-4 0.216 69004"

ok() { echo "ok - $*"; }
not_ok() { echo "not ok - $*"; }
indent() { sed 's/^/    /'; }

test_out() { # test_out NAME: empty $TEST_OUT/NAME, printed
  local d="$TEST_OUT/$1"
  rm -rf "$d" && mkdir -p "$d" && echo "$d"
}

atrito() { # atrito NP NAME ARGS...
  local np=$1 name=$2; shift 2
  if ! timeout "$ATRITO_TIMEOUT" $MPI "$np" $A "$@" -output_dir "$OUT/$name" >"$OUT/$name.log" 2>&1 </dev/null; then
    not_ok "run $name (np=$np) failed:"; tail -n 5 "$OUT/$name.log" | indent; return 1
  fi
}

atrito_rc() { # atrito_rc NP NAME ARGS...: RC is the exit status
  local np=$1 name=$2; shift 2
  timeout "$ATRITO_TIMEOUT" $MPI "$np" $A "$@" -output_dir "$OUT/$name" >"$OUT/$name.log" 2>&1 </dev/null
  RC=$?
}

# alone NP DIR ARGS...: the run again with mpiexec told not to end the job when a rank exits
# non-zero. By default mpiexec kills the other ranks then, so an error raised on one rank only
# that leaves the others waiting in a collective still ends the run; here such a run hangs until
# the timeout (exit 124), which the caller reports. (mpiexec's own exit status is 0 this way: the
# status is checked in the default run.)
alone() {
  local np=$1 dir=$2; shift 2
  OMPI_MCA_orte_abort_on_non_zero_status=0 timeout "${ALONE_TIMEOUT:-30}" $MPI "$np" $A "$@" -output_dir "$dir" </dev/null >/dev/null 2>&1
}

# alone_ok NP NAME LABEL ARGS...: alone, reported as a check of its own
alone_ok() {
  local np=$1 name=$2 label=$3 rc; shift 3
  alone "$np" "$OUT/$name.alone" "$@"; rc=$?
  [ $rc -ne 124 ] && ok "$label: every rank ends by itself (np=$np, without mpiexec's kill)" ||
    not_ok "$label: a rank was left waiting (np=$np: the run without mpiexec's kill hung ${ALONE_TIMEOUT:-30} s)"
}

compare() { $PY tests/compare_history.py "$@"; }
pycheck() { local name=$1; shift; $PY "tests/checks/$name.py" "$@"; }
