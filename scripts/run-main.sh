#!/usr/bin/env bash
# The main job: the hemispherical punch stretching benchmark on the seed-size mesh, frictionless
# and with friction (mu = 0.15), then the punch force against travel next to the reference, and
# the figures (out/benchmark/).
set -euo pipefail
cd "$(dirname "$0")/.."
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 OPENBLAS_NUM_THREADS=${OPENBLAS_NUM_THREADS:-1}
PY=${PYTHON:-/usr/bin/python3}
mkdir -p out/benchmark
for c in hemisphere_frictionless hemisphere_friction; do
  echo "== cases/$c.opts"
  bin/atrito -options_file cases/$c.opts | tee out/$c.log | grep -E "^(mesh|contact|done)|retrying"
done
echo
echo "== punch force (full sheet) against travel, with the reference (Lee, Wagoner & Nakamachi)"
$PY scripts/plot_history.py out/hemisphere_frictionless=frictionless out/hemisphere_friction=friction \
  --out out/benchmark/force_travel.png
echo
echo "== equivalent plastic strain against the radius"
$PY scripts/plot_radial.py out/hemisphere_frictionless=frictionless out/hemisphere_friction=friction \
  --travels 20,30,40 --out out/benchmark/radial.png
$PY scripts/plot_sheet.py out/hemisphere_friction out/benchmark/sheet_friction.png --title "mu = 0.15, 40 mm"
$PY scripts/plot_sheet.py out/hemisphere_frictionless out/benchmark/sheet_frictionless.png --title "frictionless, 40 mm"
echo
echo "Histories: out/hemisphere_*/history.csv and contact.csv; fields: out/hemisphere_*/fields.xmf (ParaView);"
echo "figures: out/benchmark/*.png"
