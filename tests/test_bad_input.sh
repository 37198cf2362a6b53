#!/usr/bin/env bash
# Runs every line of tests/bad_input.txt: a one-line error naming the cause, a non-zero exit
# that is not a signal (no crash, no core dump), nothing written to the output directory; a
# 2-rank case runs again without mpiexec's kill (alone, tests/lib.sh) and must end by itself.
set -u
cd "$(dirname "$0")/.."
. tests/lib.sh
OUT=$(test_out bad)
ATRITO_TIMEOUT=120
# the cases are independent (each its own output folder): run BAD_INPUT_JOBS of them at a time,
# then report in the table's order (a case is mostly the start and the end of the MPI job)
JOBS=${BAD_INPUT_JOBS:-4}
check_case() { # check_case N NP EXPECT ARGS: writes the report line of case N to $OUT/caseN.res
  local n=$1 np=$2 expect=$3 args=$4 dir="$OUT/case$1" err="$OUT/case$1.err" RC nerr
  # shellcheck disable=SC2086
  timeout $ATRITO_TIMEOUT $MPI "$np" $A $args -output_dir "$dir" </dev/null >"$OUT/case$n.out" 2>"$err"; RC=$?
  nerr=$(grep -c '^atrito: error' "$err")
  # on 2 ranks the error must end every rank by itself (no rank left in a collective)
  # shellcheck disable=SC2086
  local arc=0; [ "$np" -gt 1 ] && { alone "$np" "$dir.alone" $args; arc=$?; }
  if [ "$RC" -ne 0 ] && [ "$RC" -lt 124 ] && [ "$nerr" -eq 1 ] && grep -qF -- "$expect" "$err" && [ ! -e "$dir/history.csv" ] && [ "$arc" -ne 124 ]; then
    ok "bad input $n (np=$np, exit $RC$([ "$np" -gt 1 ] && echo ', every rank ends')): $(grep '^atrito: error' "$err" | cut -c1-150)" >"$OUT/case$n.res"
  elif [ "$arc" -eq 124 ]; then
    not_ok "bad input $n (np=$np): a rank was left waiting (the run without mpiexec's kill hung ${ALONE_TIMEOUT:-30} s): '$expect'" >"$OUT/case$n.res"
  else
    { not_ok "bad input $n (np=$np): expected '$expect', exit $RC, $nerr error lines:"; head -n 5 "$err" | indent; } >"$OUT/case$n.res"
  fi
}
n=0
while IFS='|' read -r expect np args; do
  case "$expect" in ''|'#'*) continue ;; esac
  expect=$(echo "$expect" | sed 's/^ *//;s/ *$//'); np=$(echo "$np" | tr -d ' ')
  n=$((n + 1))
  while [ "$(jobs -rp | wc -l)" -ge "$JOBS" ]; do wait -n; done
  check_case "$n" "$np" "$expect" "$args" &
done < tests/bad_input.txt
wait
for k in $(seq 1 "$n"); do
  if [ -s "$OUT/case$k.res" ]; then cat "$OUT/case$k.res"; else not_ok "bad input $k: no report"; fi
done
