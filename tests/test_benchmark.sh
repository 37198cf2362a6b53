#!/usr/bin/env bash
# A shortened hemispherical punch benchmark (seed mesh, Coons tools, 12 mm of the 40 mm travel)
# at 1 and 2 ranks: the punch force against the reference at 10.6 mm, and the two runs against
# each other. The full 40 mm runs: make run, scripts/benchmark.sh.
set -u
cd "$(dirname "$0")/.."
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 OPENBLAS_NUM_THREADS=${OPENBLAS_NUM_THREADS:-1}
PY=${PYTHON:-/usr/bin/python3}
OUT=${TEST_OUT:-build/test-out}/benchmark
rm -rf "$OUT"; mkdir -p "$OUT"
for np in 1 2; do
  if ! timeout 900 mpiexec --oversubscribe -n $np bin/atrito -options_file cases/hemisphere_frictionless.opts \
       -tool_punch_motion 0,0,12 -load_steps 12 -load_dt_max 0.25 -output_interval 0 -output_dir "$OUT/np$np" >"$OUT/np$np.log" 2>&1 </dev/null; then
    echo "not ok - shortened benchmark at np=$np failed:"; tail -n 5 "$OUT/np$np.log" | sed 's/^/    /'
  fi
done
$PY - "$OUT" <<'PYEOF'
import csv, sys
import numpy as np
d = sys.argv[1]
for np_ in (1, 2):
    rows = [r for r in csv.DictReader(open(f"{d}/np{np_}/contact.csv")) if r["tool"] == "punch"]
    t = np.array([0.0] + [float(r["travel"]) for r in rows]); f = np.array([0.0] + [float(r["force_full"]) for r in rows]) / 1e3
    F = np.interp(10.6, t, f)
    ok = abs(t[-1] - 12) < 1e-9 and abs(F - 10.0) / 10.0 < 0.10
    print(("ok" if ok else "not ok") + f" - shortened benchmark (np={np_}): full-sheet punch force at 10.6 mm {F:.2f} kN, reference 10 kN ({100 * (F - 10) / 10:+.1f} %, tolerance 10 %)")
PYEOF
$PY tests/compare_history.py "$OUT/np1/contact.csv" "$OUT/np2/contact.csv" 8 "shortened benchmark: np=1 and np=2 contact histories"
