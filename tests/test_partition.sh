#!/bin/bash
# -partition_balance contact (src/mesh/partition.c, mesh.c): at 4 ranks the slave nodes per rank
# are better balanced than with the default partition, the results agree with it to round-off
# (another distribution, the same problem), and the option refuses the simple partitioner.
cd "$(dirname "$0")/.." && . tests/lib.sh
OUT=$(test_out partition)
CASE="-options_file cases/hemisphere_friction_refined.opts -blank_layers 4 -load_steps 40 -load_max_steps 2 -output_interval 0"

imbalance() { sed -n 's/.*slave nodes per rank: .*(imbalance \([0-9.]*\)).*/\1/p' "$1"; }

atrito_rc 4 cells $CASE
atrito_rc 4 contact $CASE -partition_balance contact
if grep -q "partition metis balancing cells and contact nodes" "$OUT/contact.log" && ! grep -q "balancing" "$OUT/cells.log"; then
  ok "the mesh line names the partition that balances the contact nodes"
else not_ok "partition line"; grep "mesh:" "$OUT"/*.log | indent; fi
ic=$(imbalance "$OUT/cells.log"); ik=$(imbalance "$OUT/contact.log")
if [ -n "$ic" ] && [ -n "$ik" ] && awk -v c="$ic" -v k="$ik" 'BEGIN{exit !(k < c - 0.01)}'; then
  ok "slave-node imbalance at 4 ranks: $ik with -partition_balance contact, $ic without"
else not_ok "slave-node imbalance not reduced: '$ik' against '$ic'"; fi
for f in history.csv contact.csv; do
  if [ -s "$OUT/cells/$f" ] && [ -s "$OUT/contact/$f" ]; then
    $PY tests/compare_csv.py "$OUT/cells/$f" "$OUT/contact/$f" --rtol 1e-8 --atol 1e-8 --int-tol newton_its=1 --skip 'residual_*' --label "$f: balanced partition against the default"
  else not_ok "$f missing"; fi
done
atrito_rc 2 bad $CASE -partition_balance contact -partition simple
if [ "$RC" -ne 0 ] && grep -q -- "-partition_balance contact needs -partition metis" "$OUT/bad.log"; then
  ok "-partition_balance contact with -partition simple: one-line error"
else not_ok "bad combination accepted (exit $RC)"; tail -n 3 "$OUT/bad.log" | indent; fi
