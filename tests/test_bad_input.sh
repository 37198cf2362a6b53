#!/usr/bin/env bash
# Runs every line of tests/bad_input.txt: a one-line error naming the cause, a non-zero exit
# that is not a signal (no crash, no core dump), nothing written to the output directory.
set -u
cd "$(dirname "$0")/.."
. tests/lib.sh
OUT=$(test_out bad)
ATRITO_TIMEOUT=120
n=0
while IFS='|' read -r expect np args; do
  case "$expect" in ''|'#'*) continue ;; esac
  expect=$(echo "$expect" | sed 's/^ *//;s/ *$//'); np=$(echo "$np" | tr -d ' ')
  n=$((n + 1)); dir="$OUT/case$n"; err="$OUT/case$n.err"
  # shellcheck disable=SC2086
  timeout $ATRITO_TIMEOUT $MPI "$np" $A $args -output_dir "$dir" </dev/null >"$OUT/case$n.out" 2>"$err"; RC=$?
  nerr=$(grep -c '^atrito: error' "$err")
  if [ "$RC" -ne 0 ] && [ "$RC" -lt 124 ] && [ "$nerr" -eq 1 ] && grep -qF -- "$expect" "$err" && [ ! -e "$dir/history.csv" ]; then
    ok "bad input $n (np=$np, exit $RC): $(grep '^atrito: error' "$err" | cut -c1-150)"
  else
    not_ok "bad input $n (np=$np): expected '$expect', exit $RC, $nerr error lines:"; head -n 5 "$err" | indent
  fi
done < tests/bad_input.txt
