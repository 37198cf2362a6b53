#!/usr/bin/env bash
# Runs every line of tests/bad_input.txt: a one-line error naming the cause, a non-zero exit
# that is not a signal (no crash, no core dump), nothing written to the output directory.
set -u
cd "$(dirname "$0")/.."
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 OPENBLAS_NUM_THREADS=${OPENBLAS_NUM_THREADS:-1}
OUT=${TEST_OUT:-build/test-out}/bad
rm -rf "$OUT"; mkdir -p "$OUT"
n=0
while IFS='|' read -r expect np args; do
  case "$expect" in ''|'#'*) continue ;; esac
  expect=$(echo "$expect" | sed 's/^ *//;s/ *$//'); np=$(echo "$np" | tr -d ' ')
  n=$((n + 1)); dir="$OUT/case$n"
  # shellcheck disable=SC2086
  timeout 120 mpiexec --oversubscribe -n "$np" bin/atrito $args -output_dir "$dir" </dev/null >"$OUT/case$n.out" 2>"$OUT/case$n.err"
  rc=$?
  nerr=$(grep -c '^atrito: error' "$OUT/case$n.err")
  if [ "$rc" -ne 0 ] && [ "$rc" -lt 124 ] && [ "$nerr" -eq 1 ] && grep -qF -- "$expect" "$OUT/case$n.err" && [ ! -e "$dir/history.csv" ]; then
    echo "ok - bad input $n (np=$np, exit $rc): $(grep '^atrito: error' "$OUT/case$n.err" | cut -c1-150)"
  else
    echo "not ok - bad input $n (np=$np): expected '$expect', exit $rc, $nerr error lines:"; head -n 5 "$OUT/case$n.err" | sed 's/^/    /'
  fi
done < tests/bad_input.txt
