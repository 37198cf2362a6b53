#!/usr/bin/env bash
# Reads of memory never written, which the sanitizers of tests/test_memory.sh do not see: the
# quick part of scripts/memcheck.sh (valgrind's memcheck on the unit tests of the contact object
# and of the sheet's coarse space and on short frictional and augmented runs, 1 and 2 ranks). The
# whole pass is `make memcheck`.
set -u
cd "$(dirname "$0")/.."
. tests/lib.sh
OUT=$(test_out valgrind)
if ! make -s bin-vg/atrito bin-vg/test_contact_object bin-vg/test_sheetcoarse >"$OUT/build.log" 2>&1; then
  not_ok "build of bin-vg/ for valgrind failed"; tail -5 "$OUT/build.log" | indent; exit 1
fi
MEMCHECK_OUT="$OUT/memcheck" bash scripts/memcheck.sh --quick
