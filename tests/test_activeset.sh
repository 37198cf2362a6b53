#!/usr/bin/env bash
# Newton's active-set correction of contact (-newton_active_set, include/activeset.h): the
# direction corrected by the Sherman-Morrison-Woodbury update for the nodes its linearisation pulls
# off their tools equals the direction of the modified system solved by a factorisation of its
# own (-newton_active_set_verify: a copy of the Jacobian with the released nodes' blocks taken
# out, MUMPS), to 1e-9 relative, at 1 and 2 ranks (the draw of the tutorial's cylindrical cup:
# nodes of the punch, the die and the force-driven holder, whose unknown is among the released
# ones); the two rank counts converge to the same states within the Newton tolerance (1e-6 of
# the forces: the first draw step starts from the tangent predictor, whose correction differs
# between rank counts, tests/test_tutorial.sh; measured 1.7e-8 to 1.9e-7);
# off, the first 12 steps converge to the same states (the Newton tolerance).
set -u
cd "$(dirname "$0")/.." && . tests/lib.sh
OUT=$(test_out activeset)
C="-options_file cases/cylindrical_cup.opts -output_interval 0 -load_max_steps 12"

for np in 1 2; do
  atrito_rc $np v$np $C -newton_active_set_verify
  $PY - "$OUT/v$np.log" $np <<'PYEOF'
import re, sys
t = open(sys.argv[1]).read()
v = [(int(a), int(b), float(c)) for a, b, c in re.findall(r"active set verify: (\d+) nodes, (\d+) unknowns, relative difference from the direct solve (\S+)", t)]
tool = sum(1 for n, u, d in v if u > 3 * n)
worst = max((d for n, u, d in v), default=float("nan"))
good = len(v) >= 5 and tool >= 1 and worst < 1e-9 and "-load_max_steps 12 reached" in t
print(("ok" if good else "not ok") + f" - active-set correction at np={sys.argv[2]}: {len(v)} corrected directions ({tool} with the holder's unknown) equal the direct solve of the modified system to {worst:.1e} (tolerance 1e-9)")
PYEOF
done
for f in history.csv contact.csv; do
  $PY tests/compare_csv.py "$OUT/v1/$f" "$OUT/v2/$f" --rtol 1e-6 --atol 1e-9 --skip 'residual_*,mean_penetration' --int-tol newton_its=2 --label "active-set correction np=1 against np=2, $f, 1e-6"
done

atrito_rc 1 on $C -newton_active_set_monitor
atrito_rc 1 off $C -newton_active_set off
n_on=$(grep -c '^ *active set: [0-9]* nodes released' "$OUT/on.log"); n_off=$(grep -c '^ *active set: [0-9]* nodes released' "$OUT/off.log")
[ "$n_on" -ge 5 ] && [ "$n_off" = 0 ] && ok "-newton_active_set: on by default with the direct solver ($n_on corrected directions in 12 steps), off when asked" ||
  not_ok "-newton_active_set: default on / off not as expected"
$PY tests/compare_csv.py "$OUT/on/history.csv" "$OUT/off/history.csv" --rtol 1e-5 --atol 1e-6 --skip 'residual_*,mean_penetration,newton_its,elapsed*' --label "active-set correction on and off: the first 12 steps' converged states, 1e-5"
