#!/usr/bin/env bash
# The measurements of the benchmark scripts on synthetic data (no run of the code): the
# NUMISHEET'93 sections (theta1, theta2, rho), the square cup's draw-in and its verdict; the
# measured scaling section of doc/scaling-model.md from its stored runs; the 200 000-hexahedra
# friction case's section of doc/notes/performance-log.md (the measurements behind
# doc/performance.md) from its runs' trimmed logs; a section rewritten
# by a benchmark keeps its hand-written subsections (benchutil.write_doc_section keep_written).
set -u
cd "$(dirname "$0")/.."
. tests/lib.sh
OUT=$(test_out scripts)
if $PY scripts/numisheet93.py --selftest >"$OUT/numisheet93.log" 2>&1 && ! grep -q FAIL "$OUT/numisheet93.log"; then
  ok "scripts/numisheet93.py --selftest: $(grep -c ' ok$' "$OUT/numisheet93.log") measurements on synthetic geometry"
else
  not_ok "scripts/numisheet93.py --selftest:"; indent <"$OUT/numisheet93.log"
fi
# the measured strong scaling beside the model (doc/scaling-model.md, "Measured on more cores"):
# rendered again from the stored runs, it must give the committed section; the renderer also
# checks that scripts/partition_stats.c -whole partitions the whole blank as the runs did
cp doc/scaling-model.md "$OUT/scaling-model.md"
if $PY scripts/scaling_model.py --measured --doc "$OUT/scaling-model.md" >"$OUT/scaling_model.log" 2>&1 &&
   cmp -s doc/scaling-model.md "$OUT/scaling-model.md"; then
  ok "scripts/scaling_model.py --measured: the committed section again from doc/reference/scaling-measured.json"
else
  not_ok "scripts/scaling_model.py --measured: the section differs from doc/scaling-model.md, or the render failed:"
  { tail -5 "$OUT/scaling_model.log"; diff doc/scaling-model.md "$OUT/scaling-model.md" | head -20; } | indent
fi
# the 200 000-hexahedra friction case (doc/notes/performance-log.md, "The 200 000-hexahedra
# friction case"):
# rendered again from the trimmed logs of its runs (tests/data/bench200k: each run's header lines,
# progress lines, summary, -log_view events of the Solve stage and last punch force), it must give
# the committed section
B200="--variant l1: --variant l1b: --variant l1c: --variant l1d: --variant file: --variant file_grow5:"
PLOG=doc/notes/performance-log.md
cp $PLOG "$OUT/performance-log.md"
if $PY scripts/bench_friction200k.py --reuse --logdir tests/data/bench200k $B200 --output "$OUT/performance-log.md" >"$OUT/bench200k.log" 2>&1 &&
   cmp -s $PLOG "$OUT/performance-log.md"; then
  ok "scripts/bench_friction200k.py --reuse: the committed section again from tests/data/bench200k"
else
  not_ok "scripts/bench_friction200k.py --reuse: the section differs from $PLOG, or the render failed:"
  { tail -5 "$OUT/bench200k.log"; diff $PLOG "$OUT/performance-log.md" | head -20; } | indent
fi
# a section rewritten by a benchmark keeps the subsections written by hand after its runs
# (scripts/bench_million.py: the iteration bound, the sheet's coarse space): the committed
# "One million hexahedra" written again from its own generated part must give the committed file,
# and a subsection the body writes again must be replaced, not kept twice
if $PY - $PLOG "$OUT/keep.md" >"$OUT/keep.log" 2>&1 <<'PYEOF'
import sys
sys.path.insert(0, "scripts")
import benchutil
src, out = sys.argv[1], sys.argv[2]
text = open(src).read()
head = "## One million hexahedra"
a = text.index(head + "\n")
b = text.index("\n### The iteration bound", a)
open(out, "w").write(text)
benchutil.write_doc_section(out, head, text[a:b].rstrip("\n") + "\n", keep_written=True)
assert open(out).read() == text, "the hand-written subsections were not kept as they were"
open(out, "w").write("# T\n\n## A\n\nold\n\n### gen\n\nold gen\n\n### hand\n\nhand text\n\n## B\n\nb\n")
benchutil.write_doc_section(out, "## A", "## A\n\nnew\n\n### gen\n\nnew gen\n", keep_written=True)
want = "# T\n\n## A\n\nnew\n\n### gen\n\nnew gen\n\n### hand\n\nhand text\n\n## B\n\nb\n"
assert open(out).read() == want, repr(open(out).read())
benchutil.write_doc_section(out, "## A", "## A\n\nnewer\n")
assert open(out).read() == "# T\n\n## A\n\nnewer\n\n## B\n\nb\n", repr(open(out).read())
print("ok")
PYEOF
then
  ok "benchutil.write_doc_section keep_written: the million-hexahedra section's hand-written subsections kept, a rewritten one replaced"
else
  not_ok "benchutil.write_doc_section keep_written:"; indent <"$OUT/keep.log"
fi
