#!/usr/bin/env python3
"""A run that cannot go on: a non-zero exit that is not a signal or timeout, the final message
"step N failed at load L ... after K cuts: CAUSE; the results up to load L0 are complete" in
DIR.log, whole history rows up to L0, and valid fields.

usage: stopped_run.py DIR EXIT_STATUS LABEL"""
import csv
import re
import subprocess
import sys

d, rc, label = sys.argv[1], int(sys.argv[2]), sys.argv[3]
log = open(d + ".log").read()
m = re.search(r"atrito: error: step (\d+) failed at load ([0-9.]+) .* after \d+ cuts: (.*); the results up to load ([0-9.]+) are complete", log)
rows = list(csv.DictReader(open(d + "/history.csv")))
whole = all(len(r) == len(rows[0]) and None not in r.values() for r in rows)
last = float(rows[-1]["time"]) if rows else -1
fields = subprocess.run([sys.executable, "tests/check_fields.py", d, "-q"], capture_output=True).returncode == 0
ok = rc != 0 and rc < 124 and m is not None and whole and abs(last - float(m.group(4))) < 1e-6 and fields
print(("ok" if ok else "not ok") + f" - {label} (exit {rc}): " + (f"step {m.group(1)} failed at load {m.group(2)}: {m.group(3)}; history has {len(rows)} whole rows up to {last:.6f}, fields valid {fields}" if m else "no final message"))
sys.exit(0 if ok else 1)
