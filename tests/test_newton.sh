#!/usr/bin/env bash
# The Newton iterations of a load step (doc/notes/performance-log.md, Newton iterations): the curvature
# correction of the extrapolation predictor (-load_predictor_curvature) on the frictionless seed
# mesh with analytic tools and the code's default stepping to 40 mm (0.5 by default): the same
# converged states as the linear extrapolation (-load_predictor_curvature 0; contact and reaction
# forces and reactions to 1e-6, the same steps), fewer Newton iterations (106 against 115 when
# measured); a run restarted from its checkpoint repeats the uninterrupted one
# (the checkpoint holds the third converged state), and one from a checkpoint of a run without the
# correction (two states) takes the linear extrapolation in its first step and ends at the same
# state to the solver's tolerance; a value outside [0, 1] is refused
# with one line naming the option.
# The shrinking of the increment after a hard step (-load_shrink_its, -load_shrink_factor; off by
# default): the seed case never takes more than 10 iterations in a step (the same run with
# -load_shrink_its 10), and with 5 every step that took more than 5 is followed by one of half its size.
# The force-relative Newton tolerance (-newton_force_tol; 1e-6 by default, 0 off): far below the relative
# tolerance it changes nothing, loose it saves iterations and keeps the punch force, and it takes the
# coarse U-channel with a 0.002 mm gap smoothing past the step where its draw stalls without it.
# A failed trial point of the backtracking line search is rejected (-newton_domain_backtrack).
cd "$(dirname "$0")/.." && . tests/lib.sh
OUT=$(test_out newton)
C=cases/hemisphere_frictionless_analytic.opts

atrito 1 def -options_file $C -output_interval 0 &&
atrito 1 lin -options_file $C -output_interval 0 -load_predictor_curvature 0 &&
atrito 1 half -options_file $C -output_interval 0 -load_predictor_curvature 0.5 && {
  its() { sed -n 's/^done: \([0-9]*\) steps, \([0-9]*\) Newton iterations, \([0-9]*\) cuts.*/\2 \1 \3/p' "$OUT/$1.log"; }
  read -r il sl cl <<<"$(its lin)"; read -r id sd cd <<<"$(its def)"; read -r ih sh ch <<<"$(its half)"
  cmp -s "$OUT/def/contact.csv" "$OUT/half/contact.csv" && [ "$id" = "$ih" ] &&
    ok "-load_predictor_curvature: 0.5 is the default (contact.csv identical, $id Newton iterations)" ||
    not_ok "-load_predictor_curvature: the default run differs from 0.5 ($id and $ih Newton iterations)"
  # the quarter blank's converged states split the x and y components of the die's force and of
  # the clamp's reaction by up to 6e-4 one way or the other (the solution is symmetric about the
  # diagonal only to that accuracy); their sums and the z components are compared
  $PY - "$OUT/lin" "$OUT/half" <<'PYEOF'
import csv, sys
def rows(d, f): return list(csv.DictReader(open(f"{d}/{f}")))
a, b = sys.argv[1], sys.argv[2]
worst, where = 0.0, ""
for f, keys in (("contact.csv", [("force",), ("force_normal",), ("fz",), ("fx", "fy")]),
                ("history.csv", [("clamp_fz",), ("clamp_fx", "clamp_fy"), ("symx_fx", "symy_fy")])):
    ra, rb = rows(a, f), rows(b, f)
    if len(ra) != len(rb) or any(x["time"] != y["time"] for x, y in zip(ra, rb)):
        print(f"not ok - -load_predictor_curvature 0.5: {f} has other steps ({len(ra)} and {len(rb)} rows)"); sys.exit(1)
    for k in keys:
        va = [sum(float(r[c]) for c in k) for r in ra]
        vb = [sum(float(r[c]) for c in k) for r in rb]
        scale = max(abs(v) for v in va)
        for i, (x, y) in enumerate(zip(va, vb)):
            d = abs(x - y) / scale
            if d > worst: worst, where = d, f"{f} {'+'.join(k)} row {i + 1}"
print(("ok" if worst < 1e-6 else "not ok") + f" - -load_predictor_curvature 0.5: the converged states of the linear extrapolation (same steps; forces, reactions and their x + y sums to {worst:.1e} relative, {where}; tolerance 1e-6)")
PYEOF
  [ -n "$ih" ] && [ "$ih" -lt "$il" ] && [ "$ch" = 0 ] &&
    ok "-load_predictor_curvature 0.5: $ih Newton iterations in $sh steps against $il in $sl with the linear extrapolation, no cut" ||
    not_ok "-load_predictor_curvature 0.5: $ih Newton iterations ($ch cuts) against $il"
}

# a restart: the checkpoint holds three converged states, so the first step after it takes the
# curvature term as the uninterrupted run did: the histories are those of that run, bit for bit
atrito_rc 1 stop -options_file $C -output_interval 0 -load_predictor_curvature 0.5 -checkpoint_interval 2 -load_max_steps 7 # stops at step 7 (exit status 1)
atrito_rc 1 stop -options_file $C -output_interval 0 -load_predictor_curvature 0.5 -checkpoint_interval 2 -restart "$OUT/stop/checkpoint.h5"
mv "$OUT/stop.log" "$OUT/stop2.log"
if [ $RC -eq 0 ] && grep -q "restart from .*: step 6," "$OUT/stop2.log" && [ -f "$OUT/half/contact.csv" ]; then
  cmp -s "$OUT/half/contact.csv" "$OUT/stop/contact.csv" && cmp -s "$OUT/half/history.csv" "$OUT/stop/history.csv" &&
    ok "-load_predictor_curvature 0.5 restarted from step 6: contact.csv and history.csv identical to the run without the restart ($(grep -o 'done: [0-9]* steps, [0-9]* Newton' "$OUT/stop2.log"))" ||
    not_ok "-load_predictor_curvature 0.5 restarted from step 6: the histories differ from the run without the restart"
else
  not_ok "-load_predictor_curvature 0.5: the restart from step 6 failed (exit $RC)"; tail -n 3 "$OUT/stop2.log" | indent
fi
# a checkpoint written without the term (two converged states) continued with it: the first step
# after the restart extrapolates linearly, the run ends at the uninterrupted one's state to the
# solver's tolerance
atrito_rc 1 stoplin -options_file $C -output_interval 0 -load_predictor_curvature 0 -checkpoint_interval 2 -load_max_steps 7
atrito_rc 1 stoplin -options_file $C -output_interval 0 -load_predictor_curvature 0.5 -restart "$OUT/stoplin/checkpoint.h5"
if [ $RC -eq 0 ] && [ -f "$OUT/half/contact.csv" ]; then
  $PY - "$OUT/half/contact.csv" "$OUT/stoplin/contact.csv" "$OUT/stop/checkpoint.h5" "$OUT/stoplin/checkpoint.h5" <<'PYEOF'
import csv, sys, h5py
def has3(p):
    with h5py.File(p, "r") as f:
        return "displacement_previous2" in f and "dl_prev2" in f.attrs
third = has3(sys.argv[3]) and not has3(sys.argv[4])  # with the term the third state, without it none
a = [r for r in csv.DictReader(open(sys.argv[1])) if r["tool"] == "punch"]
b = [r for r in csv.DictReader(open(sys.argv[2])) if r["tool"] == "punch"]
fa, fb = float(a[-1]["force"]), float(b[-1]["force"])
d = abs(fa - fb) / abs(fa)
print(("ok" if a[-1]["time"] == b[-1]["time"] and d < 1e-6 and third else "not ok") + f" - -load_predictor_curvature 0.5 continued from a checkpoint of the linear extrapolation (step 6): punch force at 40 mm {fb:.6f} against {fa:.6f} N without the restart ({d:.1e} relative, tolerance 1e-6); the third state in the checkpoint with the term only: {third}")
PYEOF
else
  not_ok "-load_predictor_curvature 0.5 from a checkpoint without the third state: exit $RC"; tail -n 3 "$OUT/stoplin.log" | indent
fi

atrito_rc 1 bad -options_file $C -load_predictor_curvature 1.5
[ $RC -ne 0 ] && [ "$(grep -c 'atrito: error' "$OUT/bad.log")" -eq 1 ] && grep -q -- '-load_predictor_curvature 1.5 must lie in \[0, 1\]' "$OUT/bad.log" &&
  ok "-load_predictor_curvature 1.5 refused with one line naming the option" ||
  { not_ok "-load_predictor_curvature 1.5: exit $RC"; tail -n 3 "$OUT/bad.log" | indent; }

# -load_shrink_its 10 leaves the seed case as it is (no step takes more than 10 iterations);
# with 5, each step after one of more than 5 iterations is half as long (the run's last step may
# be shorter still, landing on the end)
atrito 1 shrink10 -options_file $C -output_interval 0 -load_shrink_its 10 &&
  { cmp -s "$OUT/def/contact.csv" "$OUT/shrink10/contact.csv" && cmp -s "$OUT/def/history.csv" "$OUT/shrink10/history.csv" &&
      ok "-load_shrink_its 10: the seed case as without it (contact.csv and history.csv identical)" ||
      not_ok "-load_shrink_its 10 changed the seed case"; }
atrito 1 shrink5 -options_file $C -output_interval 0 -load_shrink_its 5 && {
  $PY - "$OUT/shrink5.log" "$OUT/def.log" <<'PYEOF'
import re, sys
def steps(f):
    out, prev = [], 0.0
    for line in open(f):
        if "retrying" in line: out.append(None)  # a cut between two converged steps
        m = re.match(r"step +\d+ +time ([0-9.]+) +its +(\d+)", line)
        if m:
            t = float(m.group(1)); out.append((t - prev, int(m.group(2)), t)); prev = t
    return out
s, bad, hard = steps(sys.argv[1]), [], 0
for a, b in zip(s, s[1:]):
    if a is None or b is None or a[1] <= 5: continue
    hard += 1
    if abs(b[0] - 0.5 * a[0]) > 2e-6 and not (b[0] < 0.5 * a[0] and abs(b[2] - 1.0) < 1e-9):  # times printed to 1e-6
        bad.append(f"after {a[1]} iterations at dt {a[0]:.6g}: dt {b[0]:.6g}")
base = [x for x in steps(sys.argv[2]) if x]
most = max(x[1] for x in base)
ok = hard > 0 and not bad and most <= 10
print(("ok" if ok else "not ok") + f" - -load_shrink_its 5: {hard} steps of more than 5 Newton iterations, each followed by half its increment"
      + (f" ({'; '.join(bad[:3])})" if bad else "") + f"; the default run's hardest step {most} iterations (<= 10: -load_shrink_its 10 never shrinks it)")
PYEOF
}
atrito_rc 1 badshrink -options_file $C -load_shrink_factor 0
[ $RC -ne 0 ] && [ "$(grep -c 'atrito: error' "$OUT/badshrink.log")" -eq 1 ] && grep -q -- '-load_shrink_factor 0. must lie in (0, 1\]' "$OUT/badshrink.log" &&
  ok "-load_shrink_factor 0 refused with one line naming the option" ||
  { not_ok "-load_shrink_factor 0: exit $RC"; tail -n 3 "$OUT/badshrink.log" | indent; }

# -newton_force_tol (1e-6 by default): Newton has converged also when |R| <= eps F, F the size of the
# elements' force vectors. Far below -snes_rtol |R_0| (1e-12) it changes nothing against the option
# off (0); loose (1e-6, the default) it saves iterations on the seed case and the punch force stays
# within 1e-5 of the run with the option off.
atrito 1 ftol0 -options_file $C -output_interval 0 -newton_force_tol 0 &&
atrito 1 ftol12 -options_file $C -output_interval 0 -newton_force_tol 1e-12 &&
  { cmp -s "$OUT/ftol0/contact.csv" "$OUT/ftol12/contact.csv" &&
      ok "-newton_force_tol 1e-12: the seed case as with -newton_force_tol 0 (contact.csv identical)" ||
      not_ok "-newton_force_tol 1e-12 changed the seed case"; }
atrito 1 ftol6 -options_file $C -output_interval 0 -newton_force_tol 1e-6 && {
  $PY - "$OUT/ftol0" "$OUT/ftol6" <<'PYEOF'
import csv, re, sys
def punch(d): return [r for r in csv.DictReader(open(f"{d}/contact.csv")) if r["tool"] == "punch"]
def its(d): return int(re.search(r"done: \d+ steps, (\d+) Newton", open(d + ".log").read()).group(1))
a, b = punch(sys.argv[1]), punch(sys.argv[2])
fa, fb = float(a[-1]["force"]), float(b[-1]["force"])
d = abs(fa - fb) / abs(fa)
ia, ib = its(sys.argv[1]), its(sys.argv[2])
ok = a[-1]["time"] == b[-1]["time"] and d < 1e-5 and ib < ia
print(("ok" if ok else "not ok") + f" - -newton_force_tol 1e-6: {ib} Newton iterations against {ia} with 0, punch force at 40 mm {fb:.4f} against {fa:.4f} N ({d:.1e} relative, tolerance 1e-5)")
PYEOF
}
# and on 2 ranks (the force scale summed over the ranks): the same steps and Newton iterations, the
# punch force to 1e-9
atrito 2 ftol6np2 -options_file $C -output_interval 0 -newton_force_tol 1e-6 && [ -f "$OUT/ftol6/contact.csv" ] && {
  $PY - "$OUT/ftol6" "$OUT/ftol6np2" <<'PYEOF'
import csv, re, sys
def punch(d): return [r for r in csv.DictReader(open(f"{d}/contact.csv")) if r["tool"] == "punch"]
def its(d): return re.search(r"done: (\d+) steps, (\d+) Newton", open(d + ".log").read()).groups()
a, b = punch(sys.argv[1]), punch(sys.argv[2])
d = max(abs(float(x["force"]) - float(y["force"])) / abs(float(x["force"])) for x, y in zip(a, b) if float(x["force"]) != 0)
ok = len(a) == len(b) and all(x["time"] == y["time"] for x, y in zip(a, b)) and its(sys.argv[1]) == its(sys.argv[2]) and d < 1e-9
print(("ok" if ok else "not ok") + f" - -newton_force_tol 1e-6 on 1 and 2 ranks: steps and Newton iterations {its(sys.argv[1])} and {its(sys.argv[2])}, punch force to {d:.1e} (tolerance 1e-9)")
PYEOF
}
# what it is for: the coarse U-channel with a gap smoothing of 0.002 mm stalls in step 41 (the end of
# the flange floats micrometres above the die at the smoothing band's edge, its force a near-double
# root: Newton converges linearly to |R| 1e-5, 2e-8 of F, while -snes_rtol 1e-9 |R_0| asks 1.3e-6);
# with -newton_force_tol 1e-7 the draw goes on. (The case's earlier hand-found contact settings,
# given here: the soft penalty per unit area and the augmented Lagrangian; the case itself now runs
# on the defaults.)
UCT="-contact_penalty_per_area -contact_penalty_normal 100 -contact_penalty_tangential 10 -contact_augmented -contact_augmented_tol 0.01 -contact_augmented_multiplier_tol 0.2 -contact_search_distance 300"
atrito_rc 1 ucftol -options_file cases/numisheet93_uchannel_coarse.opts $UCT -output_interval 0 -contact_gap_smoothing 0.002 -newton_force_tol 1e-7 -load_max_steps 50
[ $RC -ne 0 ] && grep -q -- "-load_max_steps 50 reached" "$OUT/ucftol.log" &&
  ok "-newton_force_tol 1e-7: the coarse U-channel with a 0.002 mm gap smoothing passes step 41 and reaches step 50" ||
  { not_ok "-newton_force_tol 1e-7: the coarse U-channel did not reach step 50 (exit $RC)"; tail -n 2 "$OUT/ucftol.log" | indent; }

# A trial point of the backtracking line search where the residual cannot be evaluated
# (-newton_domain_backtrack, default on; PETSc's line search, which -newton_linesearch_contact petsc
# keeps in the stages with a tool, the energy search's own shortening being tested in
# tests/test_linesearch.c): the seed case in steps of up to 4 mm, where Newton's full
# steps invert elements at the pole, rejects such points (counted in the summary) and reaches the same
# converged states as without (the same steps, contact forces to 1e-6), on 1 and 2 ranks alike (the
# counts differ: the four steps that are cut iterate differently at round-off; Newton to -snes_rtol,
# -newton_force_tol 0, for the comparison to 1e-8; the linear extrapolation, whose iterates take the
# same steps with and without the rejection)
BIG="-options_file $C -output_interval 0 -load_predictor_curvature 0 -load_dt_max 0.1 -load_grow_its 7 -newton_linesearch_contact petsc -newton_force_tol 0"
atrito 1 dom1 $BIG && atrito 2 dom2 $BIG && atrito 1 dom0 $BIG -newton_domain_backtrack 0 && {
  n1=$(grep -o 'line search: [0-9]* trial points' "$OUT/dom1.log" | grep -o '[0-9]*')
  n2=$(grep -o 'line search: [0-9]* trial points' "$OUT/dom2.log" | grep -o '[0-9]*')
  [ -n "$n1" ] && [ "$n1" -gt 0 ] && [ -n "$n2" ] && [ "$n2" -gt 0 ] && ! grep -q 'trial points' "$OUT/dom0.log" &&
    ok "-newton_domain_backtrack: $n1 trial points rejected on 1 rank, $n2 on 2 ($(grep -o 'done: .*' "$OUT/dom1.log"); off: $(grep -o 'done: .*' "$OUT/dom0.log"))" ||
    not_ok "-newton_domain_backtrack: rejected trial points '$n1' (np=1), '$n2' (np=2), off: $(grep -c 'trial points' "$OUT/dom0.log")"
  $PY tests/compare_csv.py "$OUT/dom0/contact.csv" "$OUT/dom1/contact.csv" --rtol 1e-6 --atol 1e-9 --skip 'newton_its,residual_*,augmentations,fx,fy' --label "-newton_domain_backtrack against off, the same steps, contact.csv, 1e-6"
  $PY tests/compare_csv.py "$OUT/dom1/contact.csv" "$OUT/dom2/contact.csv" --rtol 1e-8 --atol 1e-9 --skip 'residual_*' --label "-newton_domain_backtrack np=1 against np=2, contact.csv, 1e-8"
}
