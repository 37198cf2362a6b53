#!/usr/bin/env bash
# The guide (doc/, README.md, CHANGELOG.md) as `make doc` builds it (scripts/make_doc.py): every
# link, anchor and image resolves, in the pages and in the HTML; every figure is shown by a page;
# a page of the guide stays within 300 lines, its table cells short and its dates in tables
# (history belongs to CHANGELOG.md and doc/notes/); the options reference equals what the code
# registers; the files of the repository a page names exist. A copy of the pages with a broken
# link, a missing figure, a page too long, a dated sentence, a paragraph in a table cell and a
# case file that does not exist fails, naming each, and with no other fault (the radial figure is
# shown twice: 7 faults).
set -u
cd "$(dirname "$0")/.."
. tests/lib.sh
OUT=$(test_out doc)
out=$($PY scripts/make_doc.py --out "$OUT/html" 2>&1); rc=$?
[ $rc -eq 0 ] && [ -f "$OUT/html/doc/README.html" ] && [ -f "$OUT/html/doc/figures/force_travel.png" ] &&
  ok "make doc: $(tail -n 1 <<<"$out" | sed 's/^make_doc: //; s/, HTML in .*//'), HTML built, options reference equal to the code's" ||
  { not_ok "make doc (exit $rc):"; head -n 20 <<<"$out" | indent; }
# the same pages, spoilt four ways
t="$OUT/tampered"; mkdir -p "$t"; cp -r README.md CHANGELOG.md doc "$t/"
for d in cases scripts src tests include; do ln -s "$PWD/$d" "$t/$d"; done  # the files the pages name
sed -i '0,/](getting-started.md)/s//](getting-startd.md)/' "$t/doc/README.md"
rm "$t/doc/figures/radial.png"
seq 1 301 >>"$t/doc/elements.md"
printf '\nUntil 2026-11-24 the elements did otherwise.\n' >>"$t/doc/materials.md"
printf '\n| a | b |\n|---|---|\n| 1 | %s |\n' "$(printf 'a paragraph in a cell %.0s' $(seq 1 10))" >>"$t/doc/process.md"
printf '\nRun `cases/no_such_case.opts`.\n' >>"$t/doc/tutorial.md"
out=$($PY scripts/make_doc.py --root "$t" --check --no-options 2>&1); rc=$?
[ $rc -ne 0 ] && grep -q 'doc/README.md:[0-9]*: link getting-startd.md: no such file' <<<"$out" &&
  grep -q 'radial.png: no such file' <<<"$out" && grep -q 'doc/elements.md: [0-9]* lines, more than 300' <<<"$out" &&
  grep -q 'doc/materials.md:[0-9]*: a date outside a table' <<<"$out" &&
  grep -q 'doc/process.md:[0-9]*: a table cell of 2[0-9][0-9] characters' <<<"$out" &&
  grep -q 'doc/tutorial.md:[0-9]*: cases/no_such_case.opts: no such file' <<<"$out" &&
  grep -q '^make_doc: 7 fault(s)' <<<"$out" &&
  ok "a broken link, a missing figure, a page over 300 lines, a dated sentence, a paragraph in a table cell and a case file that does not exist each fail the check, named" ||
  { not_ok "the spoilt pages (exit $rc):"; head -n 12 <<<"$out" | indent; }
