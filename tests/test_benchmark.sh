#!/usr/bin/env bash
# A shortened hemispherical punch benchmark (seed mesh, Coons tools, 12 mm of the 40 mm travel)
# at 1 and 2 ranks: the punch force against the reference at 10.6 mm, and the two runs against
# each other. The full 40 mm runs: make run, scripts/benchmark.sh.
set -u
cd "$(dirname "$0")/.."
. tests/lib.sh
OUT=$(test_out benchmark)
ATRITO_TIMEOUT=900
for np in 1 2; do
  atrito $np np$np -options_file cases/hemisphere_frictionless.opts \
    -tool_punch_motion 0,0,12 -load_steps 12 -load_dt_max 0.25 -output_interval 0
done
pycheck benchmark_force "$OUT"
compare "$OUT/np1/contact.csv" "$OUT/np2/contact.csv" 8 "shortened benchmark: np=1 and np=2 contact histories"
