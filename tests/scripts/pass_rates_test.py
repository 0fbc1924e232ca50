"""scripts/pass_rates.py (the lab report's fitted rate per pass) on sequences whose rate is known.

Usage: python3 pass_rates_test.py SCRIPTS_DIR
"""
import math
import sys

sys.path.insert(0, sys.argv[1])
from pass_rates import RATE_FLOOR, fit_rate, fitted_rate  # noqa: E402

failures = []


def check(name, ok, detail=""):
    print(("ok   " if ok else "FAIL ") + name + (f": {detail}" if detail else ""))
    if not ok:
        failures.append(name)


def close(a, b, rel=1e-12):
    return abs(a - b) <= rel * abs(b)


# A geometric sequence a r^k: the fit is exact (rounding alone), its rate r and its start a.
for a, r, n in ((0.05, 0.25, 10), (2.0, 0.8, 20), (1e-3, 0.5, 3), (7.0, 1.5, 6)):
    rate, start, used = fit_rate([a * r ** k for k in range(n)])
    check(f"geometric a={a} r={r} n={n}", close(rate, r) and close(start, a) and used == n,
          f"rate {rate!r}, start {start!r}, {used} passes")

# Passes at or below the floor (a loop that reached rounding, exact zeros) are left out: the rate
# is that of the passes above it, still exact, and the pass index is kept (not renumbered).
seq = [0.1 * 0.3 ** k for k in range(8)] + [0.0, 1e-17, RATE_FLOOR]
rate, start, used = fit_rate(seq)
check("floor passes left out", close(rate, 0.3) and close(start, 0.1) and used == 8, f"rate {rate!r}, {used} passes")
seq = [0.0, 0.0] + [0.01 * 0.5 ** k for k in range(2, 7)]
rate, start, used = fit_rate(seq)
check("leading zeros keep the pass index", close(rate, 0.5) and close(start, 0.01) and used == 5, f"rate {rate!r}")

# A sequence that is not geometric: the least-squares slope of log r on k, by hand for 1, 1/2, 1/8
# (logs 0, -ln 2, -3 ln 2 at k = 0, 1, 2: slope -1.5 ln 2, rate 2^-1.5).
rate = fitted_rate([1.0, 0.5, 0.125])
check("least squares on three passes", close(rate, 2 ** -1.5), f"rate {rate!r}")

# Fewer than three passes above the floor: no rate.
check("two passes: none", fit_rate([1.0, 0.1]) is None)
check("rounding alone: none", fit_rate([1e-14, 1e-15, 0.0, 1e-16]) is None)
check("two above the floor: none", fitted_rate([1.0, 0.1, 0.0, 0.0]) is None)
# A floor of the caller's.
check("own floor", fit_rate([1e-3, 1e-4, 1e-5, 1e-6], floor=1e-5) is None
      and close(fitted_rate([1e-3, 1e-4, 1e-5, 1e-6], floor=1e-7), 0.1))

if failures:
    sys.exit(f"{len(failures)} failed: " + ", ".join(failures))
print("all passed")
