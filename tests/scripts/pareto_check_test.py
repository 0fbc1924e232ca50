"""scripts/pareto-check on a made-up sweep whose answer is known.

Usage: python3 pareto_check_test.py SCRIPTS_DIR WORK_DIR

One scene, one error measure, three engines with these fronts (cost in µs per simulated second,
error in m):
  own-impulse  (100, 1e-3) (400, 1e-6)
  cheap        (50, 1e-2)                 reaches only 1e-2: overlap e >= 1e-2, ours 100 > 50
  dear         (200, 1e-3) (800, 1e-5)    overlap e >= 1e-5: ours 100 <= 200 at 1e-3, 400 <= 800 at 1e-5
  unstable     a cell but no front (every cell unstable)
The check must say ours is below "dear" at both levels (cost ratios 0.5), not below "cheap"
(ratio 2 at 1e-2), and that "unstable" has no front. A measure no cell has (null errors) gives no overlap. A missing file exits 1.
"""
import json
import os
import subprocess
import sys

scripts, work = sys.argv[1], sys.argv[2]
os.makedirs(work, exist_ok=True)


def cell(index, engine, cost, error):
    return {"index": index, "scene": "s.json", "engine": engine, "us_per_simulated_second": cost,
            "error": {"stack_height": error, "drift": None}}


cells = [cell(0, "own-impulse", 100, 1e-3), cell(1, "own-impulse", 400, 1e-6), cell(2, "cheap", 50, 1e-2),
         cell(3, "dear", 200, 1e-3), cell(4, "dear", 800, 1e-5), cell(5, "unstable", 10, 1e-9)]
sweep = {"cells": cells,
         "error_measures": [{"name": "stack_height", "unit": "m"}, {"name": "drift", "unit": "m"}],
         "fronts": {"s.json": {"stack_height": {"all": [2, 0, 1], "own-impulse": [0, 1], "cheap": [2], "dear": [3, 4]},
                               "drift": {"all": [], "own-impulse": [0], "dear": [3]}}}}
with open(os.path.join(work, "sweep.json"), "w") as f:
    json.dump(sweep, f)

check = os.path.join(scripts, "pareto-check")
out = subprocess.run([sys.executable, check, work], capture_output=True, text=True, check=True).stdout
lines = {line.split(":")[0]: line for line in out.splitlines()}  # "scene measure vs engine"
print(out)
failures = []


def expect(key, text):
    line = lines.get(key, "")
    if text not in line:
        failures.append(f"{key}: expected {text!r} in {line!r}")

expect("s stack_height vs dear", "2 levels, cost ratio 0.5–0.5; below: yes")
expect("s stack_height vs cheap", "1 levels, cost ratio 2–2; below: no, at 1 of 1 levels, e.g. 0.01 m: 100 against 50")
expect("s stack_height vs unstable", "no overlap: no front for unstable (no stable cell)")
expect("s drift vs dear", "0 levels, cost ratio —; below: no overlap")

only = subprocess.run([sys.executable, check, work, "--against", "cheap"], capture_output=True, text=True,
                      check=True).stdout
if "dear" in only or "cheap" not in only:
    failures.append(f"--against cheap: {only!r}")

missing = subprocess.run([sys.executable, check, os.path.join(work, "nothing")], capture_output=True, text=True)
if missing.returncode != 1 or "nothing" not in missing.stderr:
    failures.append(f"missing file: exit {missing.returncode}, {missing.stderr!r}")

if failures:
    sys.exit("\n".join(failures))
print("pareto-check: all expectations met")
