#!/usr/bin/env bash
# Regenerates the stored reference histories tests/reference/<case>/{history,contact}.csv that
# tests/test_reference.sh compares every run with (1e-10 relative, tests/compare_csv.py).
#
# References are regenerated ONLY ON PURPOSE: when a change of the code is meant to change the
# results (a new column, a corrected formula, another default). Run it from a build of that
# change (make -j2 all), look at what moved (git diff --stat tests/reference, and
# tests/compare_csv.py old new for the numbers), and commit the new files with the reason in the
# commit message. Never regenerate to make a failing test pass without knowing why it failed.
#
# usage: tests/reference/regenerate.sh [CASE...]   (default: every case below; CASE is the name
#        of cases/CASE.opts; a new case gets its folder here and is then tested)
set -euo pipefail
cd "$(dirname "$0")/../.."
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 OPENBLAS_NUM_THREADS=${OPENBLAS_NUM_THREADS:-1}
CASES=(tension_bar clamped_beam block_plane_drag block_sphere blank_point hemisphere_frictionless hemisphere_friction)
[ $# -gt 0 ] && CASES=("$@")
[ -x bin/atrito ] || { echo "regenerate: build bin/atrito first (make -j2 all)" >&2; exit 1; }
tmp=$(mktemp -d); trap 'rm -rf "$tmp"' EXIT
for c in "${CASES[@]}"; do
  [ -f "cases/$c.opts" ] || { echo "regenerate: no cases/$c.opts" >&2; exit 1; }
  # the same run as tests/test_reference.sh's at 1 rank
  mpiexec -n 1 bin/atrito -options_file "cases/$c.opts" -output_interval 0 -output_dir "$tmp/$c" </dev/null >"$tmp/$c.log" 2>&1 ||
    { echo "regenerate: cases/$c.opts failed:" >&2; tail -n 5 "$tmp/$c.log" >&2; exit 1; }
  rm -rf "tests/reference/$c"; mkdir -p "tests/reference/$c"
  for f in history.csv contact.csv; do
    [ -f "$tmp/$c/$f" ] && cp "$tmp/$c/$f" "tests/reference/$c/$f"
  done
  echo "regenerate: tests/reference/$c: $(cd "tests/reference/$c" && for f in *.csv; do echo -n "$f ($(($(wc -l <"$f") - 1)) rows) "; done)"
done
