#!/usr/bin/env bash
# The measurements of the benchmark scripts on synthetic data (no run of the code): the
# NUMISHEET'93 sections (theta1, theta2, rho), the square cup's draw-in and its verdict; the
# measured scaling section of doc/scaling-model.md from its stored runs; the 200 000-hexahedra
# friction case's section of doc/performance.md from its runs' trimmed logs.
set -u
cd "$(dirname "$0")/.."
. tests/lib.sh
OUT=$(test_out scripts)
if $PY scripts/numisheet93.py --selftest >"$OUT/numisheet93.log" 2>&1 && ! grep -q FAIL "$OUT/numisheet93.log"; then
  ok "scripts/numisheet93.py --selftest: $(grep -c ' ok$' "$OUT/numisheet93.log") measurements on synthetic geometry"
else
  not_ok "scripts/numisheet93.py --selftest:"; indent <"$OUT/numisheet93.log"
fi
# the measured strong scaling beside the model (doc/scaling-model.md, "Measured on more cores"):
# rendered again from the stored runs, it must give the committed section; the renderer also
# checks that scripts/partition_stats.c -whole partitions the whole blank as the runs did
cp doc/scaling-model.md "$OUT/scaling-model.md"
if $PY scripts/scaling_model.py --measured --doc "$OUT/scaling-model.md" >"$OUT/scaling_model.log" 2>&1 &&
   cmp -s doc/scaling-model.md "$OUT/scaling-model.md"; then
  ok "scripts/scaling_model.py --measured: the committed section again from doc/reference/scaling-measured.json"
else
  not_ok "scripts/scaling_model.py --measured: the section differs from doc/scaling-model.md, or the render failed:"
  { tail -5 "$OUT/scaling_model.log"; diff doc/scaling-model.md "$OUT/scaling-model.md" | head -20; } | indent
fi
# the 200 000-hexahedra friction case (doc/performance.md, "The 200 000-hexahedra friction case"):
# rendered again from the trimmed logs of its runs (tests/data/bench200k: each run's header lines,
# progress lines, summary, -log_view events of the Solve stage and last punch force), it must give
# the committed section
B200="--variant l1: --variant l1b: --variant l1c: --variant l1d: --variant file: --variant file_grow5:"
cp doc/performance.md "$OUT/performance.md"
if $PY scripts/bench_friction200k.py --reuse --logdir tests/data/bench200k $B200 --output "$OUT/performance.md" >"$OUT/bench200k.log" 2>&1 &&
   cmp -s doc/performance.md "$OUT/performance.md"; then
  ok "scripts/bench_friction200k.py --reuse: the committed section again from tests/data/bench200k"
else
  not_ok "scripts/bench_friction200k.py --reuse: the section differs from doc/performance.md, or the render failed:"
  { tail -5 "$OUT/bench200k.log"; diff doc/performance.md "$OUT/performance.md" | head -20; } | indent
fi
