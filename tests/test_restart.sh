#!/usr/bin/env bash
# Checkpoint and restart: a run stopped (cleanly, or killed with SIGKILL at a random moment) and
# restarted from its checkpoint gives the same history rows as one that ran through (10 digits at
# the same rank count, 8 on another rank count); histories and fields are continued, not lost or
# duplicated; the iterative solver for processes restarted on another number of ranks.
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

# 5. scripts/slurm/process.sbatch on stand-ins for Slurm's srun (mpiexec on 2 ranks) and sbatch
#    (records its call): the first job gets SIGUSR1 (Slurm's --signal) once its first checkpoint
#    is written, submits the next job depending on itself and stops its run; the next job,
#    started as sbatch would, continues from the checkpoint to the end and marks the process
#    complete; the continued history is the uninterrupted one's (8 digits: another rank count);
#    a job submitted again after that exits at once
SH="$OUT/shim"; mkdir -p "$SH"
cat >"$SH/srun" <<SHIM
#!/bin/bash
$MPI 2 "\$@" </dev/null &
p=\$!
trap 'kill -TERM \$p 2>/dev/null; wait \$p; exit 143' TERM
if [ "\${SHIM_SIGNAL:-0}" = 1 ]; then
  while kill -0 \$p 2>/dev/null && [ ! -s "\$OUTDIR/slurm/checkpoint.h5" ]; do sleep 0.02; done
  kill -USR1 \$PPID
fi
wait \$p
SHIM
printf '#!/bin/bash\necho "sbatch $*" >>"$OUTDIR/sbatch.calls"\n' >"$SH/sbatch"
chmod +x "$SH/srun" "$SH/sbatch"
sjob() { env PATH="$SH:$PATH" OUTDIR="$OUT" CASE=cases/block_sphere.opts NAME=slurm CKPT=2 SOLVER=/dev/null "$@" \
  bash scripts/slurm/process.sbatch -load_steps 40 -load_dt_max 0.025 -output_interval 3; }
rm -rf "$OUT/slurm" "$OUT/sbatch.calls"
sjob SLURM_JOB_ID=101 SHIM_SIGNAL=1 >"$OUT/slurm1.log" 2>&1
c=$(cat "$OUT/sbatch.calls" 2>/dev/null)
n1=$(($(wc -l <"$OUT/slurm/history.csv") - 1)); [ -e "$OUT/slurm/.complete" ] && done1=1 || done1=0
sjob SLURM_JOB_ID=102 ATRITO_JOBS=1 >"$OUT/slurm2.log" 2>&1
[[ "$c" == *"--dependency=afterany:101"* ]] && [ "$done1" = 0 ] && [ "$n1" -ge 2 ] && [ "$n1" -lt 40 ] && grep -q "restart from " "$OUT/slurm2.log" && [ -e "$OUT/slurm/.complete" ] &&
  grep -q "process complete after 2 job(s)" "$OUT/slurm2.log" &&
  ok "scripts/slurm/process.sbatch: the first job signalled after $n1 steps resubmitted itself (afterany) and stopped; the second continued from the checkpoint to the end" ||
  { not_ok "scripts/slurm/process.sbatch: sbatch call '$c', $n1 steps in the first job"; tail -n 3 "$OUT/slurm1.log" "$OUT/slurm2.log" | indent; }
check "$OUT/ref" "$OUT/slurm" 8 "process.sbatch: 2 jobs on 2 ranks against the 1-rank run"
sjob SLURM_JOB_ID=103 >"$OUT/slurm3.log" 2>&1 && grep -q "complete" "$OUT/slurm3.log" && [ "$(wc -l <"$OUT/sbatch.calls")" -eq 1 ] &&
  ok "process.sbatch submitted again after the end: exits at once" || not_ok "process.sbatch after the end: $(tail -n 1 "$OUT/slurm3.log")"

# 6. the iterative solver for processes (cases/solver_process.opts: amgsys bordered by a
#    force-driven holder's unknowns, the sheet's coarse space): a 1-rank run stopped after 9
#    steps, continued from its checkpoint on 2 ranks, against the uninterrupted 1-rank run to the
#    solver's tolerance (6 digits)
FT="-options_file cases/forcetool_holder.opts -options_file cases/solver_process.opts -output_interval 5"
$MPI 1 $A $FT -output_dir "$OUT/ft_ref" </dev/null >"$OUT/ft_ref.log" 2>&1 || not_ok "force-driven holder, iterative solver: the reference run failed"
$MPI 1 $A $FT -output_dir "$OUT/ft_np" -checkpoint_interval 4 -load_max_steps 9 </dev/null >"$OUT/ft_np1.log" 2>&1
$MPI 2 $A $FT -output_dir "$OUT/ft_np" -restart "$OUT/ft_np/checkpoint.h5" </dev/null >"$OUT/ft_np2.log" 2>&1 || not_ok "force-driven holder, iterative solver: the restart on 2 ranks failed"
grep -q "restart from .*: step 8," "$OUT/ft_np2.log" && ok "force-driven holder, iterative solver: restarted on 2 ranks from the checkpoint of step 8" || not_ok "force-driven holder: the restart did not start from step 8"
compare "$OUT/ft_ref/history.csv" "$OUT/ft_np/history.csv" 6 "force-driven holder, iterative solver: 1-rank checkpoint continued on 2 ranks: history.csv"
