#!/usr/bin/env bash
# The hexahedron with incompatible modes (-element_type hex8_eas) in the solver: a thin cantilever
# plate with one element through the thickness against beam theory (and the F-bar hex8 beside it),
# the pinched cylinder with rigid end diaphragms (a curved shell, one element through the thickness),
# upsetting of a cube to 30 % of its height (homogeneous: the exact force of the F-bar hex8),
# -snes_test_jacobian in the plastic regime, the same history on 1 and 2 ranks, and a restart
# from a checkpoint (the enhanced parameters are element state in the checkpoint).
set -u
cd "$(dirname "$0")/.."
. tests/lib.sh
OUT=$(test_out eas)

# 1. cantilever plate L/t = 100, 20 x 1 x 1 elements, tip deflection 0.1 (plane strain in y):
#    P = 3 E' I d / L^3, E' = E / (1 - nu^2), I = b t^3 / 12
P=$($PY -c "E=200000/(1-0.3**2); print(3*E*5/12*0.1/100**3)")
for el in hex8_eas hex8; do atrito 1 plate_$el -options_file cases/cantilever_plate.opts -element_type $el; done
# the last row's value of the column named $2 of the CSV file $1
lastcol() { awk -F, -v c="$2" 'NR == 1 { for (i = 1; i <= NF; i++) if ($i == c) k = i } END { print $k }' "$1"; }
r=$(awk -v v="$(lastcol "$OUT/plate_hex8_eas/history.csv" tip_fz)" -v p="$P" 'BEGIN { printf "%.5f", -v / p }')
rf=$(awk -v v="$(lastcol "$OUT/plate_hex8/history.csv" tip_fz)" -v p="$P" 'BEGIN { printf "%.3f", -v / p }')
awk -v r="$r" 'BEGIN { exit !(r > 0.98 && r < 1.02) }' &&
  ok "cantilever plate L/t = 100, one element through the thickness: tip force / beam theory = $r with hex8_eas (hex8 F-bar: $rf)" ||
  not_ok "cantilever plate: tip force / beam theory = $r with hex8_eas (hex8 F-bar: $rf)"

# 1b. pinched cylinder with end diaphragms (cases/pinched_cylinder_eas.opts), octant of 32 x 32
#    elements, one through the thickness: the load point moved by the reference displacement of
#    P = 1000 (1.8248e-5 P); the octant's reaction over P/4 is the stiffness over the reference
#    one. The convergence table (doc/elements.md) gives 12.6, 2.52, 1.197, 1.026, 0.995, 0.988
#    at 4 ... 128 elements per side: 1.026 here is 2.6 % above the reference and 4 % above the
#    finest mesh; the band 0.98 ... 1.05 holds this discretisation error and rejects any locking
#    (16 x 16: 1.20; hex8 F-bar on this mesh: 2.94).
atrito 1 pinched_eas -options_file cases/pinched_cylinder_eas.opts -mesh_file cases/shells/pinched_cylinder_32.inp
r=$(awk -v v="$(lastcol "$OUT/pinched_eas/history.csv" load_fx)" 'BEGIN { printf "%.4f", -v / 250 }')
awk -v r="$r" 'BEGIN { exit !(r > 0.98 && r < 1.05) }' &&
  ok "pinched cylinder, 32 x 32 x 1 hex8_eas on the octant: stiffness / reference = $r" ||
  not_ok "pinched cylinder, 32 x 32 x 1 hex8_eas on the octant: stiffness / reference = $r (expected 0.98 ... 1.05)"

# 2. upsetting to 30 % of the height: every step converges, the force is the homogeneous one
atrito 1 upset_eas -options_file cases/compression_block.opts -element_type hex8_eas &&
  atrito 1 upset_fbar -options_file cases/compression_block.opts -element_type hex8 &&
  compare "$OUT/upset_fbar/history.csv" "$OUT/upset_eas/history.csv" 8 "cube upset to 30 % of its height: hex8_eas force history = homogeneous (hex8 F-bar)"

# 3. -snes_test_jacobian on a small plastic problem
atrito 1 jac -options_file cases/clamped_beam.opts -box_cells 3,1,2 -load_steps 3 -output_interval 0 -element_type hex8_eas -snes_test_jacobian &&
  pycheck snes_test_jacobian "$OUT/jac.log" 6 1e-6 "plastic, hex8_eas element"

# 4. 1 and 2 ranks: the same history (10 digits)
atrito 1 beam1 -options_file cases/clamped_beam.opts -output_interval 0 -element_type hex8_eas
atrito 2 beam2 -options_file cases/clamped_beam.opts -output_interval 0 -element_type hex8_eas
compare "$OUT/beam1/history.csv" "$OUT/beam2/history.csv" 10 "clamped beam with hex8_eas: np=1 and np=2"

# 5. a stop after 5 steps and a restart from the checkpoint of step 4 (on 2 ranks): same history
atrito_rc 1 rs -options_file cases/clamped_beam.opts -output_interval 0 -element_type hex8_eas -checkpoint_interval 2 -load_max_steps 5
mv "$OUT/rs.log" "$OUT/rs1.log"
atrito 2 rs -options_file cases/clamped_beam.opts -output_interval 0 -element_type hex8_eas -checkpoint_interval 2 -restart "$OUT/rs/checkpoint.h5" &&
  { grep -q "restart from .*: step 4," "$OUT/rs.log" || not_ok "restart did not start from step 4"; } &&
  compare "$OUT/beam1/history.csv" "$OUT/rs/history.csv" 10 "clamped beam with hex8_eas: stopped after 5 steps, restarted on 2 ranks"
