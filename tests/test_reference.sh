#!/usr/bin/env bash
# The main cases against their stored reference histories: every folder tests/reference/CASE
# holds the history.csv (and contact.csv) of cases/CASE.opts at 1 rank; the case is run here at 1
# and 2 ranks (-output_interval 0) and each file is compared with tests/compare_csv.py, columns by
# name, 1e-10 relative (floor 1e-10 x the column's largest magnitude; for forces, the file's
# largest force); text and integer columns exactly, except the Newton iteration count, which may
# differ by one (a solve ending near its tolerance, another summation order); the Newton residual
# norms are round-off at convergence and are not compared.
# One line per case, rank count and file. References: tests/reference/regenerate.sh (on purpose
# only, the reason in the commit message).
set -u
cd "$(dirname "$0")/.."
. tests/lib.sh
OUT=$(test_out reference)
RTOL=${REFERENCE_RTOL:-1e-10}
for ref in tests/reference/*/; do
  c=$(basename "$ref")
  for np in 1 2; do
    atrito $np ${c}_np$np -options_file "cases/$c.opts" -output_interval 0 || continue
    for f in "$ref"*.csv; do
      $PY tests/compare_csv.py "$f" "$OUT/${c}_np$np/$(basename "$f")" --rtol "$RTOL" --atol 0 \
        --skip 'residual_*' --int-tol newton_its=1 --label "reference $c (np=$np) $(basename "$f")"
    done
  done
done

# the comparison itself: a copy of a reference with one change must fail (and the copy pass)
R=tests/reference/hemisphere_friction/contact.csv
mutate() { # mutate NAME PYTHON-EXPR-ON-ROWS: $OUT/NAME.csv from R with the rows (list of lists) changed
  $PY - "$R" "$OUT/$1.csv" "$2" <<'PYEOF'
import csv, sys
rows = list(csv.reader(open(sys.argv[1])))
h, body = rows[0], rows[1:]
exec(sys.argv[3])
csv.writer(open(sys.argv[2], "w", newline=""), lineterminator="\n").writerows([h] + body)
PYEOF
}
i_force=$(head -1 "$R" | tr ',' '\n' | grep -nx force | cut -d: -f1)
mutate same "pass"
mutate scaled "body[20][$((i_force - 1))] = repr(float(body[20][$((i_force - 1))]) * (1 + 1e-8))"
mutate tool "body[3][h.index('tool')] = 'die' if body[3][h.index('tool')] != 'die' else 'punch'"
mutate stick "k = h.index('stick'); r = body[len(body) // 2]; r[k] = str(int(r[k]) + 1)"
mutate nocol "k = h.index('slip'); h.pop(k); [r.pop(k) for r in body]"
mutate norow "body.pop()"
mutate swapped "p = list(range(len(h))); p.reverse(); h[:] = [h[k] for k in p]; body[:] = [[r[k] for k in p] for r in body]"
for m in same:0 swapped:0 scaled:1 tool:1 stick:1 nocol:1 norow:1; do
  name=${m%%:*}; want=${m#*:}
  # a mutation that raised leaves no copy, and a copy equal to the reference changes nothing:
  # either would pass the comparison's failure for the wrong reason
  if [ ! -s "$OUT/$name.csv" ] || { [ "$name" != same ] && cmp -s "$R" "$OUT/$name.csv"; }; then
    not_ok "compare_csv.py on a copy of $R, $name: the mutation made no changed copy"; continue
  fi
  line=$($PY tests/compare_csv.py "$R" "$OUT/$name.csv" --rtol "$RTOL" --atol 0 --skip 'residual_*' --int-tol newton_its=1 --label x); rc=$?
  [ $((rc != 0)) -eq "$want" ] && ok "compare_csv.py on a copy of $R, $name: exit $rc (${line:0:150})" ||
    not_ok "compare_csv.py on a copy of $R, $name: exit $rc, expected $([ "$want" = 1 ] && echo a failure || echo success): $line"
done
$PY tests/compare_csv.py "$R" "$OUT/nocol.csv" --allow-missing slip --label x >/dev/null && ok "compare_csv.py: a missing column named in --allow-missing is accepted" ||
  not_ok "compare_csv.py: --allow-missing slip did not accept the file without slip"
