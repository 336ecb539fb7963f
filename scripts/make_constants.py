"""Write the regression table of derived constants (p_d, p_c, N p_c - 1, k_after) at 50 digits.

    python scripts/make_constants.py            # rewrites symhx/data/constants.json

Each constant is certified as described in ``symhx.critical`` (integer argmin proved by Arb ball
arithmetic; ``p_c_lo``/``p_c_hi`` a rigorous Arb enclosure of p_c).
``tests/test_critical_constants.py`` recomputes the table and fails if any digit up to the 47th
changes, and re-derives EVERY row by an independent method (the loggamma definition in mpmath at
3x the digits, the argmin by exhaustive scan or by the local-minimum test plus unimodality).
"""

from __future__ import annotations

import json
import math
import sys
from fractions import Fraction
from pathlib import Path

import mpmath

import symhx

DIGITS = 50
NS = [2, 3, 4, 5, 6, 7, 8, 9, 10, 20, 50, 100, 101, 1000, 10**4, 10**5, 10**6, 10**8, 10**10,
      10**15, 10**20, 10**30, 10**50, 10**100, 10**200, 10**306, 10**1000]
OUT = Path(__file__).resolve().parent.parent / "symhx" / "data" / "constants.json"


def outward(x: mpmath.mpf, digits: int, up: bool) -> str:
    """``x > 0`` rounded DOWN (or UP) to ``digits`` significant decimal digits, exactly."""
    man, exp = x.man_exp
    fr = Fraction(int(man)) * Fraction(2) ** int(exp)
    e = int(mpmath.floor(mpmath.log10(x)))
    while fr >= Fraction(10) ** (e + 1):
        e += 1
    while fr < Fraction(10) ** e:
        e -= 1
    scaled = fr * Fraction(10) ** (digits - 1 - e)
    m = math.ceil(scaled) if up else math.floor(scaled)
    return f"{m}e{e - digits + 1}"


def row(N: int) -> dict[str, object]:
    cp = symhx.critical_point(N, dps=DIGITS)

    def s(x: mpmath.mpf) -> str:
        return mpmath.nstr(x, DIGITS, strip_zeros=False, min_fixed=-4, max_fixed=4)

    lo, hi = cp.p_bounds
    return {
        "N": str(N),
        "p_d": s(cp.p_d),
        "p_c": s(cp.p),
        "N_p_c_minus_1": s(cp.q),
        "k_after": str(cp.k_after),
        "argmins": [str(k) for k in cp.argmins],
        "p_c_exact": None if cp.p_exact is None else str(cp.p_exact),
        "p_c_lo": outward(lo, DIGITS + 5, up=False),
        "p_c_hi": outward(hi, DIGITS + 5, up=True),
    }


def main() -> int:
    table = {
        "description": "Derived constants of the simple-circuit model (symhx.critical_point), "
        f"{DIGITS} significant digits. Regenerate: python scripts/make_constants.py",
        "digits": DIGITS,
        "rows": [row(N) for N in NS],
    }
    OUT.write_text(json.dumps(table, indent=1) + "\n")
    print(f"wrote {len(NS)} rows to {OUT}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
