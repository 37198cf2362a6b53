#!/usr/bin/env bash
# Checkpoint and restart: a run stopped (cleanly, or killed with SIGKILL at a random moment) and
# restarted from its checkpoint gives the same history rows as one that ran through (10 digits at
# the same rank count, 8 on another rank count); histories and fields are continued, not lost or
# duplicated.
set -u
cd "$(dirname "$0")/.."
. tests/lib.sh
OUT=$(test_out restart)
CASE="-options_file cases/block_sphere.opts -load_steps 40 -load_dt_max 0.025 -output_interval 3"
run() { local np=$1; shift; $MPI "$np" $A $CASE "$@" </dev/null; }

check() { # check REF DIR DIGITS LABEL: histories equal, fields valid with the same steps
  compare "$1/history.csv" "$2/history.csv" "$3" "$4: history.csv"
  compare "$1/contact.csv" "$2/contact.csv" "$3" "$4: contact.csv"
  pycheck restart_fields "$1" "$2" "$4"
}

run 1 -output_dir "$OUT/ref" >"$OUT/ref.log" 2>&1 || not_ok "reference run failed"

# 1. a clean stop after 7 steps, restarted at the same rank count
run 1 -output_dir "$OUT/stop" -checkpoint_interval 2 -load_max_steps 7 >"$OUT/stop1.log" 2>&1
run 1 -output_dir "$OUT/stop" -checkpoint_interval 2 -restart "$OUT/stop/checkpoint.h5" >"$OUT/stop2.log" 2>&1 || not_ok "restart after a stop failed"
grep -q "restart from .*: step 6," "$OUT/stop2.log" && ok "restart from the checkpoint of step 6 (the last before the stop at step 7)" || not_ok "restart did not start from step 6"
check "$OUT/ref" "$OUT/stop" 10 "stopped and restarted (np=1)"

# 2. killed with SIGKILL mid-run, restarted
$MPI 1 $A $CASE -output_dir "$OUT/kill" -checkpoint_interval 3 </dev/null >"$OUT/kill1.log" 2>&1 &
pid=$!
for _ in $(seq 1 400); do
  n=$( { wc -l <"$OUT/kill/history.csv"; } 2>/dev/null || echo 0)
  [ "$n" -ge 12 ] && break
  sleep 0.02
done
pkill -KILL -f "output_dir $OUT/kill" ; wait $pid 2>/dev/null
rows=$(($(wc -l <"$OUT/kill/history.csv") - 1))
run 1 -output_dir "$OUT/kill" -checkpoint_interval 3 -restart "$OUT/kill/checkpoint.h5" >"$OUT/kill2.log" 2>&1 || not_ok "restart after SIGKILL failed"
echo "# killed with $rows history rows written; $(grep -o 'restart from .*' "$OUT/kill2.log")"
check "$OUT/ref" "$OUT/kill" 10 "killed (SIGKILL) and restarted (np=1)"

# 3. a checkpoint of a 1-rank run continued on 2 ranks
run 1 -output_dir "$OUT/np" -checkpoint_interval 4 -load_max_steps 9 >"$OUT/np1.log" 2>&1
run 2 -output_dir "$OUT/np" -restart "$OUT/np/checkpoint.h5" >"$OUT/np2.log" 2>&1 || not_ok "restart on 2 ranks failed"
check "$OUT/ref" "$OUT/np" 8 "1-rank checkpoint continued on 2 ranks"

# 4. a checkpoint of another case is refused with a clear error
run 1 -output_dir "$OUT/bad" -box_cells 4,4,2 -restart "$OUT/np/checkpoint.h5" >"$OUT/bad.log" 2>&1 </dev/null
grep -q "atrito: error: -restart .*not the same mesh or case" "$OUT/bad.log" && ok "a checkpoint of another mesh is refused: $(grep -o 'atrito: error.*' "$OUT/bad.log" | cut -c1-120)" || not_ok "a checkpoint of another mesh was not refused"
# another material type of the same history width (7 values: j2, hill48, yld91), on 2 ranks
$MPI 2 $A $CASE -output_dir "$OUT/badmat" -material_type hill48 -restart "$OUT/np/checkpoint.h5" >"$OUT/badmat.log" 2>&1 </dev/null
rc=$?
[ "$rc" -ne 0 ] && [ "$(grep -c '^atrito: error' "$OUT/badmat.log")" -eq 1 ] && grep -q "atrito: error: -restart .*the checkpoint's material is j2, this case's -material_type hill48" "$OUT/badmat.log" &&
  ok "a checkpoint of another material type is refused (np=2, exit $rc): $(grep -o 'atrito: error.*' "$OUT/badmat.log" | cut -c1-140)" || not_ok "a checkpoint of another material type was not refused (exit $rc)"
alone_ok 2 badmat "a checkpoint of another material type" $CASE -material_type hill48 -restart "$OUT/np/checkpoint.h5"
