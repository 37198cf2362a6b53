#!/usr/bin/env bash
# The measurements of the benchmark scripts on synthetic data (no run of the code): the
# NUMISHEET'93 sections (theta1, theta2, rho), the square cup's draw-in and its verdict.
set -u
cd "$(dirname "$0")/.."
. tests/lib.sh
OUT=$(test_out scripts)
if $PY scripts/numisheet93.py --selftest >"$OUT/numisheet93.log" 2>&1 && ! grep -q FAIL "$OUT/numisheet93.log"; then
  ok "scripts/numisheet93.py --selftest: $(grep -c ' ok$' "$OUT/numisheet93.log") measurements on synthetic geometry"
else
  not_ok "scripts/numisheet93.py --selftest:"; indent <"$OUT/numisheet93.log"
fi
