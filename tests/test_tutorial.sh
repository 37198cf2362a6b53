#!/usr/bin/env bash
# The tutorial's cylindrical cup (doc/tutorial.md, cases/cylindrical_cup.opts): a process set up
# from the docs alone, run on the code's defaults. Checks: the options file sets no contact option
# but the sets and the friction, and no stage increment bound; the whole process (close, draw,
# release, springback) runs at 1 and 2 ranks, whose histories agree to 1e-7 (the first draw step
# starts from the tangent predictor, whose correction differs by 2 % between the rank counts and
# between direct solvers, each solve accurate to 1.6e-13 (doc/notes/contact-defaults.md), so its
# Newton iterations may differ by two and its state by the Newton tolerance, 3.8e-8 measured; mean_penetration is written with 7 digits,
# its last one rounding either way); the post-processing of the
# tutorial (scripts/cylcup_post.py) on its output: ears at 0 and 90 degrees (the rim draws in more
# at 45: Hill's r-values with r0 + r90 > 2 r45), the largest thinning at the punch's profile
# (initial radius 20 to 30 mm), the largest punch force within 15 % of the classical estimate
# pi d t UTS (d the punch's diameter plus t, UTS the engineering tensile strength of the Swift
# law, K n^n e^-n: 49.2 kN); the holder's penalty from its force; the process with the iterative
# solver (cases/solver_process.opts) at 2 ranks against LU.
set -u
cd "$(dirname "$0")/.." && . tests/lib.sh
OUT=$(test_out tutorial)
C=cases/cylindrical_cup.opts

bad=$(grep -E '^-(contact_|tool_[a-z]*_(penalty|gap_smoothing|regularization|friction_))' "$C" | grep -v -E '^-contact_friction |^-tool_[a-z]*_contact_set ')
lim=$(grep -E 'dt_max' "$C")
[ -z "$bad" ] && [ -z "$lim" ] && ok "cases/cylindrical_cup.opts: no contact option but the sets and the friction, no increment bound" ||
  not_ok "cases/cylindrical_cup.opts sets tuning options: $bad $lim"

atrito 1 cup1 -options_file $C -output_interval 5 && atrito 2 cup2 -options_file $C -output_interval 0 && {
  d1=$(grep -o 'done: .*' "$OUT/cup1.log"); d2=$(grep -o 'done: .*' "$OUT/cup2.log")
  t1=$(tail -n 1 "$OUT/cup1/history.csv" | awk -F, '{print $2}')
  [ -n "$d1" ] && [ -n "$d2" ] && grep -q '^stage springback' "$OUT/cup1.log" && ok "cylindrical cup on the defaults: close, draw, release, springback at 1 rank ($d1) and 2 ($d2)" ||
    not_ok "cylindrical cup: '$d1' '$d2'"
  for f in history.csv contact.csv; do
    $PY tests/compare_csv.py "$OUT/cup1/$f" "$OUT/cup2/$f" --rtol 1e-7 --atol 1e-9 --skip 'residual_*,mean_penetration' --int-tol newton_its=2 --label "cylindrical cup np=1 against np=2, $f, 1e-7"
  done
  if $PY scripts/cylcup_post.py "$OUT/cup1" --plot "$OUT/cup.png" >"$OUT/post.txt" 2>&1; then
    $PY - "$OUT/post.txt" <<'PYEOF'
import math, re, sys
t = open(sys.argv[1]).read()
ear = float(re.search(r"draws in (-?[0-9.]+) mm more at 45", t).group(1))
m = re.search(r"thinning: thickness strain (-?[0-9.]+) .* at initial radius ([0-9.]+) mm", t)
f = float(re.search(r"largest punch force ([0-9.]+) kN", t).group(1))
K, n = 565.32, 0.2589
est = math.pi * 51.0 * 1.0 * K * n ** n * math.exp(-n) / 1000
good = ear > 0.5 and float(m.group(1)) < 0 and 20 <= float(m.group(2)) <= 30 and abs(f / est - 1) < 0.15
print(("ok - " if good else "not ok - ") + f"cylindrical cup: ears at 0 and 90 deg (draw-in {ear:.2f} mm larger at 45), largest thinning {float(m.group(1)):.3f} at initial radius {m.group(2)} mm (the punch's profile: 20 to 30), largest punch force {f:.1f} kN against pi d t UTS {est:.1f} kN ({100 * (f / est - 1):+.1f} %, within 15 %)")
PYEOF
  else not_ok "scripts/cylcup_post.py failed"; tail -n 3 "$OUT/post.txt" | indent; fi
  [ -s "$OUT/cup.png" ] && ok "the tutorial's figure written" || not_ok "no figure"
  # the holder's automatic penalty from its force: 4000 N over the nodes under it at the start (119:
  # the flange under the annulus of radii 32 to 65), at a penetration of 1e-4 of the element size
  # (the thickness, 1 mm): every one of its 205 slave nodes at that penalty
  l=$(grep -o 'tool holder: .*' "$OUT/cup1.log")
  $PY - "$l" <<'PYEOF'
import re, sys
l = sys.argv[1]
k = float(re.search(r"regularising stiffness ([0-9.e+]+)", l).group(1))
f, n = (float(x) for x in re.search(r"K_N at most ([0-9.e+]+) N over 0.0001 h \(([0-9.]+) nodes under it\)", l).groups())
good = abs(f * n / 4000 - 1) < 1e-5 and 100 < n < 205 and abs(k / (205 * f / 1e-4) - 1) < 1e-2
print(("ok - " if good else "not ok - ") + f"the holder's penalty from its force (-contact_penalty_force_penetration 1e-4): 4000 N over {n:g} nodes under it, {f:.4g} N each; its 205 nodes' penalties sum to {k:.6g} N/mm against {205 * f / 1e-4:.6g}")
PYEOF
}

# the same process with the iterative solver for processes (cases/solver_process.opts: BiCGStab,
# amgsys bordered by the holder's unknowns) at 2 ranks: the displacements at every shared output
# time within 2e-6 of the largest against LU at 1 rank (end of the draw and after springback
# among them; LU corrects its Newton directions for the nodes they pull off the tools,
# -newton_active_set, the iterative solver does not: two paths, each converged to the Newton
# tolerance of 1e-6 of the forces, 1.34e-6 apart measured), and at most 50 Krylov iterations in
# any Newton iteration of any stage
atrito 2 cup_sys2 -options_file $C -options_file cases/solver_process.opts -output_interval 5 && {
  pycheck solver_fields "$OUT/cup1" "$OUT/cup_sys2" 2 2e-6 "cylindrical cup: BiCGStab + amgsys (np=2) against LU (np=1)"
  most=$(grep -o "krylov [0-9]* (most [0-9]*)" "$OUT/cup_sys2.log" | awk '{gsub(/\)/,"",$4); v = $4 + 0; if (v > m) m = v} END {print m + 0}')
  st=$(grep -o '^stage [a-z]*' "$OUT/cup_sys2.log" | sort -u | wc -l)
  [ "$most" -ge 1 ] && [ "$most" -le 50 ] && [ "$st" -eq 4 ] && ok "cylindrical cup with the iterative solver: at most $most Krylov iterations per Newton iteration through its 4 stages ($(grep -o 'done: .*' "$OUT/cup_sys2.log"))" ||
    not_ok "cylindrical cup with the iterative solver: most $most Krylov iterations, $st stages"
}
