"""Benchmark: the full pmf of X over each sample space for N = 100 at dps = 30 (float p), and N =
10**4, against the naive way (summing count * p**length over every visit pattern in mpf / Fraction).

Run: ``python benchmarks/bench_spaces.py`` -> ``benchmarks/results/spaces.json``.
Times are the minimum over repeats; "cold" includes building the N-independent class tables.
"""

from __future__ import annotations

import json
import platform
import time
from fractions import Fraction
from pathlib import Path

import mpmath

from symhx.circuits import circuit_count
from symhx.spaces import distribution, parse_space
from symhx.spaces._classes import visits_of

SPACES = ["simple", "eq41", "eq41-printed", "excess<=3", "excess<=6", "excess<=6;distinct"]


def best(fn, repeat=7):
    ts = []
    for _ in range(repeat):
        t = time.perf_counter()
        fn()
        ts.append(time.perf_counter() - t)
    return min(ts)


def fast_pmf(N, p, space, dps=30):
    d = distribution(N, p, space=space, dps=dps)
    return [v for _, v in d.table()]


def naive_pmf(N, p, space, dps=30):
    sp = parse_space(space)
    with mpmath.workdps(dps + 10):
        pm = mpmath.mpf(p) if not isinstance(p, Fraction) else p
        W = []
        for k in range(1, N + 1):
            tot = 0
            for s in sp.shapes:
                if k < len(s):
                    continue
                c = sp.count(N, s, k)  # == circuit_count of the pattern (checked in the tests)
                L = k + sum(x - 1 for x in s) if sp.weighting == "length" else k
                tot += c * pm**L
            W.append(tot)
        g = sum(W)
        return [w / g for w in W]


def naive_burnside_pmf(N, p, space, dps=30):
    """Naive with Burnside's count of every full visit pattern (circuit_count)."""
    sp = parse_space(space)
    with mpmath.workdps(dps + 10):
        pm = mpmath.mpf(p)
        W = [sum(circuit_count(N, visits_of(s, k)) * pm ** (k + sum(x - 1 for x in s))
                 for s in sp.shapes if k >= len(s)) for k in range(1, N + 1)]
        g = mpmath.fsum(W)
        return [w / g for w in W]


def main() -> None:
    res = {"machine": platform.machine(), "python": platform.python_version(),
           "mpmath": mpmath.__version__, "backend": mpmath.libmp.BACKEND, "rows": []}
    for space in SPACES:
        row = {"space": space}
        row["pmf_N100_dps30_s"] = best(lambda s=space: fast_pmf(100, 0.02, s))
        row["pmf_N100_exact_s"] = best(lambda s=space: fast_pmf(100, Fraction(1, 50), s))
        if space != "simple":
            row["naive_mpf_N100_s"] = best(lambda s=space: naive_burnside_pmf(100, 0.02, s), 3)
            row["naive_fraction_N100_s"] = best(lambda s=space: naive_pmf(100, Fraction(1, 50),
                                                                          s), 3)
        row["mean_N1e4_dps30_s"] = best(
            lambda s=space: distribution(10**4, 0.001, space=s, dps=30).mean, 3)
        row["pmf_N1e4_dps30_s"] = best(lambda s=space: fast_pmf(10**4, 0.001, s), 1)
        res["rows"].append(row)
        print(row)
    out = Path(__file__).parent / "results" / "spaces.json"
    out.write_text(json.dumps(res, indent=2) + "\n")


if __name__ == "__main__":
    main()
