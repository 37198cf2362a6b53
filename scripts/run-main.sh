#!/usr/bin/env bash
# The main job: the cases of the code, serial and on 2 ranks, with a summary of the results.
set -euo pipefail
cd "$(dirname "$0")/.."
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 OPENBLAS_NUM_THREADS=${OPENBLAS_NUM_THREADS:-1}
PY=${PYTHON:-/usr/bin/python3}
for c in tension_bar clamped_beam blank_point; do
  echo "== cases/$c.opts (1 rank)"
  bin/atrito -options_file cases/$c.opts -output_dir out/$c
  echo "== cases/$c.opts (2 ranks)"
  mpiexec --oversubscribe -n 2 bin/atrito -options_file cases/$c.opts -output_dir out/${c}_np2 | tail -n 2
done
echo
echo "== uniaxial tension against the closed form"
$PY tests/check_tension.py out/tension_bar/history.csv pull_fx 1 10 3 589 1e-4 0.216 69004
for c in tension_bar clamped_beam blank_point; do
  $PY tests/compare_history.py out/$c/history.csv out/${c}_np2/history.csv 8 "$c: 1 and 2 ranks"
done
echo
echo "Results: out/<case>/history.csv (one row per converged step), out/<case>/fields.xmf (open in ParaView)"
