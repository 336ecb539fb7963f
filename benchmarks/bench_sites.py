"""Benchmark: per-site probabilities (issue 30).

1. The critical point along a direction of two site classes, sizes ``(2, N - 2)`` (a row's two
   walls and its pipe pairs), against today's scalar ``critical_point(N)``, N = 10^2 ... 10^1000,
   measured in one run; the ratio is reported.  Achieved error: against the same call at twice
   the digits.  The naive route (an mpmath scan of every c_k, e_k summed term by term) at
   N = 10^4 for comparison.
2. Distribution methods with site classes: the row (2, 99) and a 3-class lattice-like example
   (sizes of the 10 x 10 lattice: 40 wall, 180 orthogonal and 162 diagonal sites), exact and at
   30 digits, against the naive Fraction convolution of e_k.

Run: ``python benchmarks/bench_sites.py`` -> ``benchmarks/results/sites.json``.
"""

from __future__ import annotations

import math
import sys
from fractions import Fraction
from pathlib import Path

import mpmath

sys.path.insert(0, str(Path(__file__).resolve().parent))
from _common import best_time, write

from symhx.critical import critical_point
from symhx.critical_sites import direction_critical_point
from symhx.site_distribution import SitesDistribution
from symhx.sites import SiteClasses

DPS = 50
WEIGHTS = [("1/2", 1), (3, 1)]


def show(N: int) -> str:
    return str(N) if N < 10**7 else f"1e{len(str(N)) - 1}"


def rel_error(x, ref) -> float:
    with mpmath.workdps(2 * DPS + 20):
        return float(abs((x - ref) / ref))


def naive_scan(N: int, w: tuple[Fraction, Fraction], dps: int) -> tuple[int, object]:
    """min over every k of c_k = (e_1 / ((k-1)! e_k))**(1/(k-1)), e_k summed term by term."""
    w1, w2 = w
    with mpmath.workdps(dps + 20):
        a, b = mpmath.mpf(w1.numerator) / w1.denominator, mpmath.mpf(w2.numerator) / w2.denominator
        e1 = 2 * a + (N - 2) * b
        best = None
        for k in range(2, N + 1):
            ek = mpmath.fsum(math.comb(2, j) * a**j * mpmath.binomial(N - 2, k - j) * b ** (k - j)
                             for j in range(0, min(2, k) + 1) if k - j <= N - 2)
            c = (e1 / (mpmath.factorial(k - 1) * ek)) ** (mpmath.mpf(1) / (k - 1))
            if best is None or c < best[1]:
                best = (k, c)
    assert best is not None
    return best


def bench_critical() -> list[dict]:
    rows = []
    for N in (10**2, 10**4, 10**6, 10**20, 10**100, 10**1000):
        scalar = best_time(lambda N=N: critical_point(N, dps=DPS), repeat=5)
        for w in WEIGHTS:
            sc = SiteClasses((2, N - 2), w)
            cp = direction_critical_point(N, sc, dps=DPS)
            ref = direction_critical_point(N, sc, dps=2 * DPS)
            t = best_time(lambda N=N, sc=sc: direction_critical_point(N, sc, dps=DPS), repeat=5)
            rows.append({"N": show(N), "weights": [str(x) for x in sc.values],
                         "method": cp.method, "k_after": str(cp.k_after),
                         "time": t, "scalar_time": scalar, "ratio": t / scalar,
                         "error": rel_error(cp.p, ref.p),
                         "evaluations": cp.sign_evaluations})
            print(f"critical_point N={show(N):>7} w={rows[-1]['weights']}: {t * 1e3:8.2f} ms "
                  f"(scalar {scalar * 1e3:.2f} ms, x{t / scalar:.1f}), {cp.method}, "
                  f"error {rows[-1]['error']:.1e}")
    return rows


def bench_naive() -> dict:
    N = 10**4
    w = (Fraction(1, 2), Fraction(1))
    cp = direction_critical_point(N, SiteClasses((2, N - 2), w), dps=30)
    t_fast = best_time(lambda: direction_critical_point(N, SiteClasses((2, N - 2), w), dps=30))
    import time

    t0 = time.perf_counter()
    k, c = naive_scan(N, w, 30)
    t_naive = time.perf_counter() - t0
    assert k == cp.k_after
    out = {"N": N, "symhx_s": t_fast, "naive_scan_s": t_naive,
           "naive_error": rel_error(c, direction_critical_point(N, SiteClasses((2, N - 2), w),
                                                                 dps=60).p)}
    print(f"naive mpmath scan, N = 1e4: {t_naive:.2f} s vs {t_fast * 1e3:.2f} ms")
    return out


def naive_pmf(sizes, probs):
    N = sum(sizes)
    W = []
    for k in range(1, N + 1):
        tot = Fraction(0)
        for j in range(max(0, k - sizes[1]), min(sizes[0], k) + 1):
            tot += math.comb(sizes[0], j) * math.comb(sizes[1], k - j) * probs[0] ** j \
                * probs[1] ** (k - j)
        W.append(math.factorial(k - 1) * tot)
    g = sum(W)
    return [x / g for x in W]


def bench_distribution() -> list[dict]:
    rows = []
    cases = [("row (2, 99)", (2, 99), ("0.01", "0.02")),
             ("lattice 10x10 (40, 180, 162)", (40, 180, 162), ("0.005", "0.01", "0.004")),
             ("two large classes (5000, 5000)", (5000, 5000), ("0.0001", "0.0003"))]
    for label, sizes, probs in cases:
        N = sum(sizes)
        for kind, conv in (("exact", lambda p: p), ("dps 30", float), ("float64", float)):
            if kind == "exact" and N > 1000:
                continue
            sc = SiteClasses(sizes, tuple(conv(p) for p in probs))
            dps = None if kind == "float64" else 30

            def run(sc=sc, dps=dps, N=N):
                d = SitesDistribution(N, sc, dps=dps)
                return d.mean(), d.var(), d.modes(), d.median()

            t = best_time(run, repeat=3, min_time=0.0)
            rows.append({"case": label, "N": N, "kind": kind, "mean_var_modes_median_s": t})
            print(f"{label:32s} {kind:8s} mean+var+modes+median: {t * 1e3:9.1f} ms")
    # the naive way for the row: a Fraction convolution of e_k, then the pmf
    t_naive = best_time(lambda: naive_pmf((2, 99), (Fraction(1, 100), Fraction(1, 50))),
                        repeat=3, min_time=0.0)
    t_fast = best_time(lambda: SitesDistribution(101, SiteClasses((2, 99), ("0.01", "0.02")))
                       .table(), repeat=3, min_time=0.0)
    rows.append({"case": "row (2, 99) exact pmf table", "N": 101, "kind": "exact",
                 "table_s": t_fast, "naive_fraction_convolution_s": t_naive})
    print(f"row exact pmf table: {t_fast * 1e3:.1f} ms, naive Fraction convolution "
          f"{t_naive * 1e3:.1f} ms")
    return rows


def main() -> None:
    payload = {"critical": bench_critical(), "naive": bench_naive(),
               "distribution": bench_distribution()}
    path = write("sites", payload)
    print(f"wrote {path}")


if __name__ == "__main__":
    main()
