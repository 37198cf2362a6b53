#!/usr/bin/env bash
# Integration tests of frictional contact with rigid tools, at 1 and 2 ranks.
set -u
cd "$(dirname "$0")/.."
. tests/lib.sh
OUT=$(test_out contact)

# 1. block pressed onto a plane, then dragged: K_T x slip in stick, mu x normal in slip (1e-8)
atrito 1 drag1 -options_file cases/block_plane_drag.opts && $PY tests/check_block_drag.py "$OUT/drag1" 1e3 0.3
atrito 2 drag2 -options_file cases/block_plane_drag.opts -output_interval 0
compare "$OUT/drag1/contact.csv" "$OUT/drag2/contact.csv" 8 "block on a plane: contact history at np=1 and np=2"

# 1b. penalties per unit area (-contact_penalty_per_area): node i's K_T is the given value times its
#     tributary area on the bottom face (interior nodes 1/16: the same 1e3 as above, edges and
#     corners a half and a quarter of it), at 1 and 2 ranks
for np in 1 2; do
  atrito $np dragA$np -options_file cases/block_plane_drag.opts -contact_penalty_per_area -contact_penalty_normal 1.6e5 -contact_penalty_tangential 1.6e4 &&
    $PY tests/check_block_drag.py "$OUT/dragA$np" 1.6e4 0.3 per_area | sed "s/\$/ (np=$np)/"
done
compare "$OUT/dragA1/contact.csv" "$OUT/dragA2/contact.csv" 8 "block on a plane, penalties per unit area: contact history at np=1 and np=2"
#     the seed hemisphere, frictionless: the tributary areas of the quarter blank's two faces sum
#     to twice the area of its polygon (14 rim segments of pi/28), and with the per-area penalty
#     that gives the seed's mean node (668 nodes) the paper's 1e5, the punch force at 40 mm
#     stays within 1 % of the per-node run
atrito 1 seedN -options_file cases/hemisphere_frictionless.opts -output_interval 0
atrito 2 seedA -options_file cases/hemisphere_frictionless.opts -output_interval 0 -contact_penalty_per_area -contact_penalty_normal 12168 -contact_penalty_tangential 608.4 &&
  pycheck seed_area "$OUT/seedN" "$OUT/seedA"

# 2. the exact Jacobian with contact, in stick and in slip, plane, sphere and a Coons cap (four
#    great-circle arcs about the sphere's pole, dn/dy from the patch's second derivatives),
#    analytic and finite-difference nodal tangents
C="-tool_ball_patch0_type coons -tool_ball_patch0_sense -1 -tool_ball_path 0,0,0,0,0.5,0,0,-0.25,1,0.2,0,-0.25"
for side in bottom:-1.216741,-1.216741,1.542544,1.216741,-1.216741 top:-1.216741,1.216741,1.542544,1.216741,1.216741 \
  left:-1.216741,-1.216741,1.542544,-1.216741,1.216741 right:1.216741,-1.216741,1.542544,1.216741,1.216741; do
  C="$C -tool_ball_patch0_${side%%:*}_type arc -tool_ball_patch0_${side%%:*}_points ${side#*:},1.542544,0,0,4"
done
#    (sphere_area: the sphere with the penalties per unit area, the same per interior node;
#    spindle: a spindle torus, minor radius 3 > major 0.5, its axis horizontal, the block pressed
#    and dragged by its outer equator's region, where both curvatures differ; sphere_auto: the
#    automatic penalty, so the regularised normal law of 1 % of the element size; sphere_band: its
#    band half the element size, most contact nodes in it at first touch)
P="-tool_ball_patch0_type torus -tool_ball_patch0_center 0,0,4.5 -tool_ball_patch0_axis 0,1,0 -tool_ball_patch0_ref 0,0,-1"
P="$P -tool_ball_patch0_major 0.5 -tool_ball_patch0_minor 3 -tool_ball_patch0_range -90,90,-80,80"
for tool in plane sphere coons sphere_area spindle sphere_auto sphere_band; do
  for tan in analytic fd; do
    name=jac_${tool}_$tan
    if [ $tool = plane ]; then opts="-options_file cases/block_plane_drag.opts -output_interval 0 -box_cells 2,2,1"
    elif [ $tool = sphere ]; then opts="-options_file cases/block_sphere.opts -output_interval 0 -box_cells 4,4,1"
    elif [ $tool = spindle ]; then opts="-options_file cases/block_sphere.opts -output_interval 0 -box_cells 4,4,1 $P"
    elif [ $tool = sphere_auto ]; then opts="-options_file cases/block_sphere.opts -output_interval 0 -box_cells 4,4,1 -contact_penalty_normal auto"
    elif [ $tool = sphere_band ]; then opts="-options_file cases/block_sphere.opts -output_interval 0 -box_cells 4,4,1 -contact_penalty_normal auto -contact_regularization_relative 0.5"
    elif [ $tool = sphere_area ]; then opts="-options_file cases/block_sphere.opts -output_interval 0 -box_cells 4,4,1 -contact_penalty_per_area -contact_penalty_normal 4e4 -contact_penalty_tangential 4e3"
    else opts="-options_file cases/block_sphere.opts -output_interval 0 -box_cells 4,4,1 $C"; fi
    # shellcheck disable=SC2086
    atrito 1 $name $opts -contact_tangent $tan -snes_test_jacobian &&
      pycheck snes_test_jacobian "$OUT/$name.log" 10 1e-5 "with contact on a $tool, $tan tangent" --contact "$OUT/$name"
  done
done
#    the same with the committed contact set held in the first iteration on the frictional sphere
#    too (-newton_keep_contact all): the held nodes' friction (cone of the committed force, a
#    tangential spring anchored at the predictor) and the entering nodes without friction
atrito 1 jac_sphere_keepall -options_file cases/block_sphere.opts -output_interval 0 -box_cells 4,4,1 -newton_keep_contact all -contact_frame_carry rotation -snes_test_jacobian &&
  pycheck snes_test_jacobian "$OUT/jac_sphere_keepall.log" 10 1e-5 "with contact on a sphere, the committed contact set held on it in the first iteration (-newton_keep_contact all)" --contact "$OUT/jac_sphere_keepall"
#    the first iteration of a step holds the committed contact set (-newton_keep_contact, default
#    on frictionless tools): its Jacobian is tested against the held residual (the seed punch with
#    the code's default stepping, steps 16 and 17, where lightly pressed nodes stand off the punch
#    at the predictor; restarted from step 15, since the finite-difference Jacobian costs 2 s each)
#    (-load_max_steps stops each run with exit 1 and its error line)
# shellcheck disable=SC2086
atrito_rc 1 jac_keep0 -options_file cases/hemisphere_frictionless.opts $DEFSTEP -output_interval 0 -load_max_steps 15 -checkpoint_interval 15
# shellcheck disable=SC2086
atrito_rc 1 jac_keep -options_file cases/hemisphere_frictionless.opts $DEFSTEP -output_interval 0 -restart "$OUT/jac_keep0/checkpoint.h5" -load_max_steps 17 -snes_test_jacobian
grep -q "load_max_steps 17 reached" "$OUT/jac_keep.log" || not_ok "jac_keep did not run to step 17 (exit $RC)"
pycheck snes_test_jacobian "$OUT/jac_keep.log" 10 1e-5 "with the committed contact set held in the first iteration (-newton_keep_contact frictionless), frictionless seed punch, steps 16-17"
#    and on every tool with friction (the seed case with friction, -newton_keep_contact all: the
#    moving punch and the die at rest), step 11, where 12 of the 31 nodes pressed on the die's
#    fillet stand off it at the predictor (restarted from step 10)
atrito_rc 1 jac_keepall0 -options_file cases/hemisphere_friction.opts -output_interval 0 -load_max_steps 10 -checkpoint_interval 10
atrito_rc 1 jac_keepall -options_file cases/hemisphere_friction.opts -output_interval 0 -restart "$OUT/jac_keepall0/checkpoint.h5" -load_max_steps 11 -snes_test_jacobian
grep -q "load_max_steps 11 reached" "$OUT/jac_keepall.log" || not_ok "jac_keepall did not run to step 11 (exit $RC)"
pycheck snes_test_jacobian "$OUT/jac_keepall.log" 5 1e-5 "with the committed contact set held in the first iteration on every tool (-newton_keep_contact all), the seed punch with friction, step 11" --contact "$OUT/jac_keepall"

# 3. quadratic convergence: elastic block pressed into a sphere that then slides, with friction
atrito 1 quad -options_file cases/block_sphere.opts -output_interval 0 -snes_monitor &&
  $PY tests/check_quadratic.py "$OUT/quad.log" "elastic block pressed into a sphere with friction (analytic tangent)"
atrito 1 quadfd -options_file cases/block_sphere.opts -output_interval 0 -snes_monitor -contact_tangent fd &&
  $PY tests/check_quadratic.py "$OUT/quadfd.log" "the same with the finite-difference nodal tangent"

# 4. 1 and 2 ranks: the same contact and reaction histories to 8 significant digits
atrito 1 sph1 -options_file cases/block_sphere.opts
atrito 2 sph2 -options_file cases/block_sphere.opts
compare "$OUT/sph1/contact.csv" "$OUT/sph2/contact.csv" 8 "block and sphere: contact history at np=1 and np=2"
compare "$OUT/sph1/history.csv" "$OUT/sph2/history.csv" 8 "block and sphere: reactions at np=1 and np=2"
$PY tests/check_fields.py "$OUT/sph2" -q >/dev/null && pycheck contact_fields "$OUT/sph2/fields.h5" 0.3 "np=2"
#    the frames carried by rotation (-contact_frame_carry rotation) with the committed contact
#    set held on the frictional sphere (-newton_keep_contact all): the symmetric problem stays
#    symmetric (the transverse reaction base_fy at round-off against base_fz; with the paper's
#    projection of t1 a round-off chord at the pole turns the carried traction), 1 and 2 ranks agree
#    (to 6 digits: the 2-rank run takes one more iteration at the absolute tolerance)
#    (Newton to -snes_rtol, -newton_force_tol 0: at the default force tolerance the sliding steps
#    end at |R| ~ 1e-6 and base_fy at 4e-9 of base_fz)
for np in 1 2; do atrito $np sphrot$np -options_file cases/block_sphere.opts -output_interval 0 -newton_keep_contact all -contact_frame_carry rotation -newton_force_tol 0; done
compare "$OUT/sphrot1/history.csv" "$OUT/sphrot2/history.csv" 6 "block and sphere, frames carried by rotation, committed set held on the sphere: reactions at np=1 and np=2"
$PY - "$OUT/sphrot1/history.csv" "$OUT/sphrot2/history.csv" <<'PYEOF'
import csv, sys
worst = max(abs(float(r["base_fy"])) / max(abs(float(r["base_fz"])), 1e-30) for f in sys.argv[1:] for r in csv.DictReader(open(f)))
msg = f"block and sphere, frames carried by rotation, committed set held on the sphere: |base_fy|/|base_fz| at most {worst:.1e} (< 1e-9)"
print(("ok - " if worst < 1e-9 else "not ok - ") + msg)
PYEOF

# 5. contact chattering: with a loose Newton tolerance the active set is still changing when
#    SNES reports convergence; the step is cut back, and with no cut allowed the run stops
#    naming the node
atrito 1 chatter -options_file cases/block_sphere.opts -output_interval 0 -snes_rtol 0.5 &&
  n=$(grep -c "contact chattering: .* (node id [0-9]*); retrying" "$OUT/chatter.log") && [ "$n" -ge 1 ] &&
  ok "contact chattering detected and the step cut back ($n times), run completed" || not_ok "contact chattering was not detected"
atrito_rc 2 chatter2 -options_file cases/block_sphere.opts -output_interval 0 -snes_rtol 0.5 -load_max_cuts 0
msg=$(grep -o "atrito: error: step .*contact chattering.*node id [0-9]*.*" "$OUT/chatter2.log" | head -1)
[ $RC -ne 0 ] && [ -n "$msg" ] && ok "chattering with no cut allowed stops the run (np=2): ${msg:0:120}" || not_ok "chattering final message (exit $RC)"
alone_ok 2 chatter2 "chattering with no cut allowed" -options_file cases/block_sphere.opts -output_interval 0 -snes_rtol 0.5 -load_max_cuts 0
