#!/usr/bin/env bash
# Augmented Lagrangian contact (-contact_augmented) and the automatic penalty
# (-contact_penalty_normal auto): the Coulomb law in slip, the exact Jacobian at fixed multipliers
# in stick and slip, 1 and 2 ranks, a restart in the middle of an augmented run, the penetration
# below the tolerance, the retry at softer penalties (-contact_augmented_soften), the defaults of an
# augmented run on the seed punch with friction (the iterations against the plain penalty's).
set -u
cd "$(dirname "$0")/.."
. tests/lib.sh
OUT=$(test_out auglag)
AUG="-contact_augmented -contact_augmented_tol 1e-4"

# 1. block dragged on a plane: slip |t_T| = mu t_N to 1e-8, penetration below the tolerance,
#    at 1 and 2 ranks (the same histories to 8 digits)
atrito 1 drag1 -options_file cases/block_plane_drag.opts -output_interval 0 $AUG && pycheck auglag_drag "$OUT/drag1" 0.3 1e-4 25 "np=1"
atrito 2 drag2 -options_file cases/block_plane_drag.opts -output_interval 0 $AUG && pycheck auglag_drag "$OUT/drag2" 0.3 1e-4 25 "np=2"
compare "$OUT/drag1/contact.csv" "$OUT/drag2/contact.csv" 8 "augmented block on a plane: contact history at np=1 and np=2"
compare "$OUT/drag1/history.csv" "$OUT/drag2/history.csv" 8 "augmented block on a plane: reactions at np=1 and np=2"

# 2. the exact Jacobian with the multipliers held fixed, in stick and in slip, plane and sphere
for tool in plane sphere; do
  name=jac_$tool
  if [ $tool = plane ]; then opts="-options_file cases/block_plane_drag.opts -box_cells 2,2,1"
  else opts="-options_file cases/block_sphere.opts -box_cells 4,4,1"; fi
  # shellcheck disable=SC2086
  atrito 1 $name $opts -output_interval 0 $AUG -snes_test_jacobian &&
    pycheck snes_test_jacobian "$OUT/$name.log" 10 1e-5 "augmented Lagrangian on a $tool" --contact "$OUT/$name"
done

# 3. block and sphere with friction at 1 and 2 ranks, the first iteration holding the frictionless
#    tools' nodes only (-newton_keep_contact frictionless; the default of an augmented run is moving).
#    With the default the symmetric problem acquires a transverse reaction fy of about 1e-7 of the
#    normal force from the step where the nodes turn from stick to slip (with frictionless: 1e-13),
#    seeded by round-off and so not the same at 1 and 2 ranks to 8 digits of the 1e-3 floor; its
#    level is checked (doc/notes/contact-log.md, Augmented Lagrangian)
atrito 1 sph1 -options_file cases/block_sphere.opts -output_interval 0 $AUG -newton_keep_contact frictionless
atrito 2 sph2 -options_file cases/block_sphere.opts -output_interval 0 $AUG -newton_keep_contact frictionless
compare "$OUT/sph1/contact.csv" "$OUT/sph2/contact.csv" 8 "augmented block and sphere: contact history at np=1 and np=2"
atrito 1 sphd -options_file cases/block_sphere.opts -output_interval 0 $AUG
#    the default at 2 ranks: every column but fy to 1e-8, the reactions on the scale of the file's
#    forces; fy, zero by symmetry, is held to the symmetry bound at both rank counts: with `all`
#    the paper's frame recurrence turns the frame by a rank-dependent round-off that the
#    friction carries (doc/notes/performance-log.md, "Why `all` broke the symmetry of block_sphere"): fy
#    6e-9 of fz apart at 1 and 2 ranks on one machine, 1e-7 on another
atrito 2 sphd2 -options_file cases/block_sphere.opts -output_interval 0 $AUG
$PY tests/compare_csv.py "$OUT/sphd/contact.csv" "$OUT/sphd2/contact.csv" --rtol 1e-8 --skip 'residual_*,fy' --int-tol newton_its=1 --label "augmented block and sphere, default keep (moving): contact history at np=1 and np=2 but fy, forces on the forces' scale"
$PY - "$OUT/sphd/contact.csv" "$OUT/sphd2/contact.csv" "$OUT/sph1/contact.csv" <<'PY'
import csv, sys
w = [max(abs(float(r["fy"])) / max(abs(float(r["fz"])), 1e-30) for r in csv.DictReader(open(f))) for f in sys.argv[1:]]
print(("ok - " if max(w[0], w[1]) < 1e-6 else "not ok - ") + f"augmented block and sphere, default keep (moving): |fy|/|fz| at most {w[0]:.1e} (np=1) and {w[1]:.1e} (np=2) (< 1e-6; with -newton_keep_contact frictionless {w[2]:.1e})")
PY

# 4. restart in the middle of an augmented run (the multipliers are in the checkpoint): the same
#    rows as the uninterrupted run, to 10 digits at 1 rank and 8 digits continued on 2 ranks
CASE="-options_file cases/block_sphere.opts -load_steps 20 -load_dt_max 0.05 -output_interval 0 $AUG"
# shellcheck disable=SC2086
atrito 1 ref $CASE
# shellcheck disable=SC2086
atrito_rc 1 stop $CASE -checkpoint_interval 3 -load_max_steps 8
# shellcheck disable=SC2086
if $MPI 1 $A $CASE -output_dir "$OUT/stop" -checkpoint_interval 3 -restart "$OUT/stop/checkpoint.h5" >"$OUT/stop2.log" 2>&1 </dev/null; then
  grep -q "restart from .*: step 6," "$OUT/stop2.log" && ok "augmented run restarted from the checkpoint of step 6" || not_ok "augmented restart did not start from step 6"
  compare "$OUT/ref/contact.csv" "$OUT/stop/contact.csv" 10 "augmented run stopped and restarted (np=1): contact.csv"
  compare "$OUT/ref/history.csv" "$OUT/stop/history.csv" 10 "augmented run stopped and restarted (np=1): history.csv"
else not_ok "augmented restart failed"; tail -n 5 "$OUT/stop2.log" | indent; fi
# shellcheck disable=SC2086
atrito_rc 1 np $CASE -checkpoint_interval 4 -load_max_steps 9
# shellcheck disable=SC2086
if $MPI 2 $A $CASE -output_dir "$OUT/np" -restart "$OUT/np/checkpoint.h5" >"$OUT/np2.log" 2>&1 </dev/null; then
  compare "$OUT/ref/contact.csv" "$OUT/np/contact.csv" 8 "augmented run, 1-rank checkpoint continued on 2 ranks: contact.csv"
else not_ok "augmented restart on 2 ranks failed"; tail -n 5 "$OUT/np2.log" | indent; fi

# 5. an augmentation that cannot converge in its limit is a failed step, cut back, with the cause
atrito_rc 1 augfail -options_file cases/block_plane_drag.opts -output_interval 0 -contact_augmented -contact_augmented_tol 1e-9 -contact_augmented_max 2 -load_max_cuts 1
msg=$(grep -o "atrito: error: step .*augmented Lagrangian: penetration .* after 2 loops.*" "$OUT/augfail.log" | head -1)
[ $RC -ne 0 ] && [ -n "$msg" ] && grep -q "augmented Lagrangian: penetration .*; retrying" "$OUT/augfail.log" &&
  ok "augmentation not converged: step cut back, then the run stops naming it: ${msg:0:140}" || not_ok "augmentation failure (exit $RC)"

# 6. the automatic penalty: printed per node at set-up; the seed hemisphere runs with it
atrito 1 auto -options_file cases/hemisphere_frictionless.opts -output_interval 0 -contact_penalty_normal auto &&
  line=$(grep -o "contact: automatic penalty.*" "$OUT/auto.log") && [ -n "$line" ] &&
  ok "automatic penalty on the seed hemisphere, $(grep -o 'done: .*' "$OUT/auto.log"): ${line:0:120}" || not_ok "automatic penalty run"

# 7. a stiff block (E = 2e5) pressed and dragged on a plane with no user penalty (automatic K_N and
#    K_T) and the augmented Lagrangian: the penetration below the tolerance, the Coulomb law in slip;
#    the Newton iterations and solves per step reported
atrito 1 stiff -options_file cases/block_plane_drag.opts -output_interval 0 -material_E 2e5 -contact_penalty_normal auto -contact_penalty_tangential auto -contact_augmented -contact_augmented_tol 1e-5 &&
  pycheck auglag_drag "$OUT/stiff" 0.3 1e-5 25 "stiff block, E = 2e5, automatic penalty" &&
  $PY -c "import csv,sys; r=list(csv.DictReader(open(sys.argv[1]))); print('    Newton iterations per step', [int(x['newton_its']) for x in r], 'solves', [int(x['augmentations']) for x in r])" "$OUT/stiff/contact.csv"

# 8. the seed hemisphere at a soft penalty (K_N 1e3), where the penalties grow and the growth carries
#    over to the next steps (-contact_augmented_growth_keep, in the checkpoint) and the solves that an
#    update follows are inexact (-contact_augmented_inexact): the punch force within 0.2 % of the
#    stiff run's (K_N 1e5), the penetration below the tolerance at every step; a run stopped and
#    restarted repeats the uninterrupted one (10 digits), and 2 ranks repeat 1 rank (8 digits)
HEM="-options_file cases/hemisphere_frictionless.opts -output_interval 0 -contact_augmented -contact_augmented_tol 1e-3"
# shellcheck disable=SC2086
atrito 1 hsoft $HEM -contact_penalty_normal 1e3
# shellcheck disable=SC2086
atrito 1 hstiff $HEM -contact_penalty_normal 1e5
$PY - "$OUT/hsoft/contact.csv" "$OUT/hstiff/contact.csv" <<'PY' && ok "$(cat "$OUT/hcheck.txt")" || not_ok "$(cat "$OUT/hcheck.txt" 2>/dev/null)"
import csv, sys, os
rows = [[x for x in csv.DictReader(open(f)) if x["tool"] == "punch"] for f in sys.argv[1:3]]
fs, fk = float(rows[0][-1]["force"]), float(rows[1][-1]["force"])
pen = max(float(x["max_penetration"]) for r in rows for x in r)
d = abs(fs / fk - 1)
msg = f"augmented hemisphere, K_N 1e3 against 1e5: punch force {fs:.2f} and {fk:.2f} N ({100 * d:.3f} %), largest penetration {pen:.2e} (tolerance 1e-3), Newton iterations {sum(int(x['newton_its']) for x in rows[0])} and {sum(int(x['newton_its']) for x in rows[1])}"
open(os.path.join(os.path.dirname(os.path.dirname(sys.argv[1])), "hcheck.txt"), "w").write(msg)
sys.exit(0 if d < 2e-3 and pen <= 1e-3 else 1)
PY
# shellcheck disable=SC2086
# 2 ranks against 1 at the seed's K_N 1e5: at 1e3 about one 2-rank run in eight takes another
# step sequence (a step's first solve stalls and is cut: MUMPS's parallel factorisation is not
# bitwise reproducible, and the augmentation's decisions at its tolerances can flip with it), an
# open robustness point of the soft penalty (doc/notes/contact-log.md)
atrito 2 hstiff2 $HEM -contact_penalty_normal 1e5
compare "$OUT/hstiff/contact.csv" "$OUT/hstiff2/contact.csv" 8 "augmented hemisphere, K_N 1e5: contact history at np=1 and np=2"
# shellcheck disable=SC2086
atrito_rc 1 hstop $HEM -contact_penalty_normal 1e3 -checkpoint_interval 4 -load_max_steps 10
# shellcheck disable=SC2086
if $MPI 1 $A $HEM -contact_penalty_normal 1e3 -output_dir "$OUT/hstop" -restart "$OUT/hstop/checkpoint.h5" >"$OUT/hstop2.log" 2>&1 </dev/null; then
  compare "$OUT/hsoft/contact.csv" "$OUT/hstop/contact.csv" 10 "augmented hemisphere, K_N 1e3, stopped at step 10 and restarted from step 8 (np=1): contact.csv"
else not_ok "augmented hemisphere restart failed"; tail -n 5 "$OUT/hstop2.log" | indent; fi

# 9. -contact_augmented_soften: block and sphere at a stiff penalty (K_N 1e7), where Newton fails:
#    the failed step is retried at the same increment with the penalties 8 times softer (kept for
#    the next steps), the run ends with fewer cuts than without, the penetration below the
#    tolerance; a restart from a checkpoint after the softening repeats the uninterrupted run (the
#    factor is in the checkpoint)
SOFT="-options_file cases/block_sphere.opts -output_interval 0 -contact_penalty_normal 1e7 $AUG"
# shellcheck disable=SC2086
atrito 1 stiff_plain $SOFT
# shellcheck disable=SC2086
atrito 1 stiff_soft $SOFT -contact_augmented_soften &&
  $PY - "$OUT/stiff_plain.log" "$OUT/stiff_soft.log" "$OUT/stiff_soft/contact.csv" <<'PY'
import csv, re, sys
plain, soft = open(sys.argv[1]).read(), open(sys.argv[2]).read()
cuts = [int(re.search(r"done: \d+ steps, \d+ Newton iterations, (\d+) cuts", t).group(1)) for t in (plain, soft)]
nsoft = len(re.findall(r"retrying with the penalties' factor", soft))
pen = max(float(x["max_penetration"]) for x in csv.DictReader(open(sys.argv[3])))
ok = nsoft > 0 and "steps retried at softer penalties" in soft and cuts[1] < cuts[0] and pen <= 1e-4
print(("ok - " if ok else "not ok - ") + f"augmented, K_N 1e7, -contact_augmented_soften: {nsoft} softened retries, {cuts[1]} cuts (without: {cuts[0]}), largest penetration {pen:.2e} (tolerance 1e-4)")
PY
# shellcheck disable=SC2086
atrito_rc 1 softstop $SOFT -contact_augmented_soften -checkpoint_interval 4 -load_max_steps 8
# shellcheck disable=SC2086
if $MPI 1 $A $SOFT -contact_augmented_soften -output_dir "$OUT/softstop" -restart "$OUT/softstop/checkpoint.h5" >"$OUT/softstop2.log" 2>&1 </dev/null; then
  compare "$OUT/stiff_soft/contact.csv" "$OUT/softstop/contact.csv" 10 "augmented, softened penalties, stopped at step 8 and restarted (np=1): contact.csv"
else not_ok "augmented restart with softened penalties failed"; tail -n 5 "$OUT/softstop2.log" | indent; fi

# 10. the seed punch with friction at K_N 1e3 with the augmented Lagrangian's defaults: the first
#     Newton iteration holds the moving frictional tools' nodes too (the default -newton_keep_contact
#     is moving in an augmented run: the same history as with the option given, bit for bit, on the
#     seed mesh with analytic tools, whose file gives no -newton_keep_contact); the punch force
#     within 0.2 % of the augmented run at K_N 1e5, the Newton iterations at most 1.7 times the plain
#     penalty run's at K_N 1e3 (doc/notes/contact-log.md, measurements: the Coons seed case with the code's
#     default stepping and keeps, given here since its file now sets its own, doc/notes/performance-log.md;
#     1.5 before the energy line search and the force tolerance, which took the plain run from 94
#     to 82 iterations and the augmented one from 138 to 131)
FRI="-options_file cases/hemisphere_friction.opts -output_interval 0 $DEFSTEP"
FRA="-options_file cases/hemisphere_friction_analytic.opts -output_interval 0 -contact_penalty_normal 1e3 -contact_augmented -contact_augmented_tol 1e-3"
# shellcheck disable=SC2086
atrito 1 fpen $FRI -contact_penalty_normal 1e3 -newton_keep_contact frictionless
# shellcheck disable=SC2086
atrito 1 faug $FRI -contact_penalty_normal 1e3 -contact_augmented -contact_augmented_tol 1e-3 -newton_keep_contact moving
# shellcheck disable=SC2086
atrito 1 fadef $FRA
# shellcheck disable=SC2086
atrito 1 fall $FRA -newton_keep_contact moving
# shellcheck disable=SC2086
atrito 1 faug5 $FRI -contact_penalty_normal 1e5 -contact_augmented -contact_augmented_tol 1e-3 -newton_keep_contact moving
# (bit for bit: the keep changes the iterates, not the converged states, and with all, which
# holds the die's nodes too, the history differs from moving's by 4e-13)
cmp -s "$OUT/fadef/contact.csv" "$OUT/fall/contact.csv" && cmp -s "$OUT/fadef/history.csv" "$OUT/fall/history.csv" &&
  ok "augmented punch with friction (analytic tools): the default keep is -newton_keep_contact moving (contact.csv and history.csv identical)" ||
  not_ok "augmented punch with friction (analytic tools): the default keep's histories differ from -newton_keep_contact moving's"
# shellcheck disable=SC2086
atrito 2 faug52 $FRI -contact_penalty_normal 1e5 -contact_augmented -contact_augmented_tol 1e-3 -newton_keep_contact moving
compare "$OUT/faug5/contact.csv" "$OUT/faug52/contact.csv" 8 "augmented punch with friction, K_N 1e5, defaults: contact history at np=1 and np=2"
$PY - "$OUT/fpen.log" "$OUT/faug.log" "$OUT/faug/contact.csv" "$OUT/faug5/contact.csv" <<'PY'
import csv, re, sys
its = [int(re.search(r"done: \d+ steps, (\d+) Newton iterations", open(f).read()).group(1)) for f in sys.argv[1:3]]
rows = [[x for x in csv.DictReader(open(f)) if x["tool"] == "punch"] for f in sys.argv[3:5]]
f3, f5 = float(rows[0][-1]["force"]), float(rows[1][-1]["force"])
pen = max(float(x["max_penetration"]) for x in rows[0])
d = abs(f3 / f5 - 1)
ok = its[1] <= 1.7 * its[0] and d < 2e-3 and pen <= 1e-3
print(("ok - " if ok else "not ok - ") + f"augmented punch with friction, K_N 1e3: {its[1]} Newton iterations against the plain penalty's {its[0]} ({its[1] / its[0]:.2f}, at most 1.7), punch force {f3:.2f} N against {f5:.2f} N at K_N 1e5 ({100 * d:.3f} %), largest penetration {pen:.2e} (tolerance 1e-3)")
PY
