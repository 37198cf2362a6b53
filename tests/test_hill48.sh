#!/usr/bin/env bash
# Integration tests of the Hill 48 material (-material_type hill48): with r-values 1 it is the J2
# model (tension bar history to 10 digits), its Jacobian in a plastic, non-homogeneous problem
# agrees with finite differences (-snes_test_jacobian; rolling direction along x and oblique),
# and 1 and 2 ranks give the same history to 10 digits. The same for Barlat 1991 (-material_type
# yld91): exponent 2 is hill48 (beam history to 9 digits), its Jacobian with the exponents 8 and 6,
# 1 and 2 ranks. Each check prints "ok - ..." or "not ok - ...".
set -u
cd "$(dirname "$0")/.."
. tests/lib.sh
OUT=$(test_out hill48)
STEEL="-material_type hill48 -material_hill_r0 1.6 -material_hill_r45 1.2 -material_hill_r90 2.0"

# 1. r0 = r45 = r90 = 1: the J2 model's history (uniaxial tension to 30 %), and the closed form
atrito 1 bar_j2 -options_file cases/tension_bar.opts -output_interval 0 &&
  atrito 1 bar_hill -options_file cases/tension_bar.opts -output_interval 0 -material_type hill48 -material_hill_r0 1 -material_hill_r45 1 -material_hill_r90 1 &&
  $PY - "$OUT/bar_j2/history.csv" "$OUT/bar_hill/history.csv" <<'PYEOF' &&
# every value column to 1e-10 of its scale: the column's largest magnitude, for the reactions the
# largest force of the file (the symmetry planes' reactions are zero up to the Newton residual);
# the Newton iteration counts equal, the residual norms not compared
import csv, sys
a, b = (list(csv.DictReader(open(f))) for f in sys.argv[1:3])
force = [k for k in a[0] if k[-3:] in ("_fx", "_fy", "_fz")]
fmax = max(abs(float(r[k])) for r in a for k in force)
worst, where = 0.0, ""
ok = len(a) == len(b) == 30 and all(x["newton_its"] == y["newton_its"] for x, y in zip(a, b))
for k in a[0]:
    if k.startswith("residual") or k == "newton_its":
        continue
    if k == "stage":  # the stage's name: text, equal in every row
        ok = ok and all(x[k] == y[k] for x, y in zip(a, b))
        continue
    scale = fmax if k in force else max(abs(float(r[k])) for r in a) or 1.0
    for i, (x, y) in enumerate(zip(a, b)):
        d = abs(float(x[k]) - float(y[k])) / scale
        if d > worst:
            worst, where = d, f"{k} row {i + 1}"
ok = ok and worst < 1e-10
print(("ok" if ok else "not ok") + f" - tension bar: hill48 with r-values 1 = j2 ({len(a)} steps, same Newton iterations), largest difference {worst:.1e} of the scale ({where}; tolerance 1e-10)")
sys.exit(0 if ok else 1)
PYEOF
  $PY tests/check_tension.py "$OUT/bar_hill/history.csv" pull_fx 1 10 3 $SWIFT 1e-6

# 2. -snes_test_jacobian on a small plastic problem, r-values of a steel: rolling direction x,
#    then oblique axes with linear hardening
beam="-options_file cases/clamped_beam.opts -box_cells 3,1,2 -load_steps 3 -output_interval 0"
atrito 1 jac $beam $STEEL -snes_test_jacobian &&
  pycheck snes_test_jacobian "$OUT/jac.log" 6 1e-6 "hill48 (r 1.6/1.2/2.0), plastic"
atrito 1 jac_obl $beam $STEEL -material_hill_rd 1,1,0.2 -material_hill_normal -1,1,0 -material_hardening linear -material_yield 150 -material_hardening_modulus 800 -snes_test_jacobian &&
  pycheck snes_test_jacobian "$OUT/jac_obl.log" 6 1e-6 "hill48 (r 1.6/1.2/2.0), oblique axes, linear hardening"

# 3. 1 and 2 ranks: the same history
atrito 1 beam1 -options_file cases/clamped_beam.opts -output_interval 0 $STEEL &&
  atrito 2 beam2 -options_file cases/clamped_beam.opts -output_interval 0 $STEEL &&
  compare "$OUT/beam1/history.csv" "$OUT/beam2/history.csv" 10 "clamped beam, hill48 (r 1.6/1.2/2.0): np=1 and np=2 (10 digits)"
# the anisotropy shows: the isotropic and the steel's beam differ
atrito 1 beam_iso -options_file cases/clamped_beam.opts -output_interval 0 -material_type hill48 &&
  ! compare "$OUT/beam1/history.csv" "$OUT/beam_iso/history.csv" 3 "-" >/dev/null &&
  ok "clamped beam: r-values 1.6/1.2/2.0 and 1/1/1 give different histories (3 digits)" || not_ok "clamped beam: the r-values change nothing"

# 4. Barlat 1991 (yld91): exponent 2 with the steel's r-values is hill48; its Jacobian with the
#    aluminium's r-values and exponent 8, and oblique axes with exponent 6; 1 and 2 ranks
Y91="-material_type yld91 -material_yld91_r0 0.71 -material_yld91_r45 0.58 -material_yld91_r90 0.70"
atrito 1 beam_y2 -options_file cases/clamped_beam.opts -output_interval 0 -material_type yld91 -material_yld91_exponent 2 -material_yld91_r0 1.6 -material_yld91_r45 1.2 -material_yld91_r90 2.0 &&
  compare "$OUT/beam1/history.csv" "$OUT/beam_y2/history.csv" 9 "clamped beam: yld91 with exponent 2 = hill48 (r 1.6/1.2/2.0; 9 digits)"
atrito 1 jac_y8 $beam $Y91 -snes_test_jacobian &&
  pycheck snes_test_jacobian "$OUT/jac_y8.log" 6 1e-6 "yld91 (exponent 8, r 0.71/0.58/0.70), plastic"
atrito 1 jac_y6 $beam -material_type yld91 -material_yld91_exponent 6 -material_yld91_r0 1.6 -material_yld91_r45 1.2 -material_yld91_r90 2.0 -material_yld91_rd 1,1,0.2 -material_yld91_normal -1,1,0 \
  -material_hardening linear -material_yield 150 -material_hardening_modulus 800 -snes_test_jacobian &&
  pycheck snes_test_jacobian "$OUT/jac_y6.log" 6 1e-6 "yld91 (exponent 6, r 1.6/1.2/2.0), oblique axes, linear hardening"
atrito 1 beam_y8a -options_file cases/clamped_beam.opts -output_interval 0 $Y91 &&
  atrito 2 beam_y8b -options_file cases/clamped_beam.opts -output_interval 0 $Y91 &&
  compare "$OUT/beam_y8a/history.csv" "$OUT/beam_y8b/history.csv" 10 "clamped beam, yld91 (exponent 8, r 0.71/0.58/0.70): np=1 and np=2 (10 digits)"
