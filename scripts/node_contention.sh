#!/bin/bash
# A core alone against a node whose cores are all busy, with no communication between them: the
# same 1-rank run alone (twice), then as N independent copies at once, one pinned to each of the
# cores 0..N-1, for each N given. Prints each run's own time (the code's "done: ... s" line),
# sorted. doc/scaling-model.md, "Measured on more cores", quotes it beside the measured scaling.
#
#   scripts/node_contention.sh [CASE] [N ...]     (default: cases/hemisphere_friction.opts 16 8 16)
set -u
cd "$(dirname "$0")/.."
case=${1:-cases/hemisphere_friction.opts}
[ $# -gt 0 ] && shift
counts=${*:-16 8 16}
[ -f "$case" ] || { echo "node_contention: no case file $case" >&2; exit 2; }
export OPENBLAS_NUM_THREADS=1 OMP_NUM_THREADS=1
work=$(mktemp -d)
one() {  # the run's time, or "failed" (a run that did not finish is never left out of the list)
  local t
  t=$(taskset -c "$1" bin/atrito -options_file "$case" -output_interval 0 -output_dir "$work/o$1" 2>&1 |
    sed -n 's/^done: .* \([0-9.]*\) s$/\1/p')
  echo "${t:-failed}"
}
for k in 1 2; do echo "alone: $(one 0)"; done
for n in $counts; do
  for c in $(seq 0 $((n - 1))); do one "$c" >"$work/t$c" & done
  wait
  echo "$n at once: $(cat $(seq -f "$work/t%g" 0 $((n - 1))) | sort -n | tr '\n' ' ')"
done
rm -rf "$work"
