"""Work-precision benchmarks of the exact core (critical point and mean of X).

    python benchmarks/bench_core.py        # writes benchmarks/results/core.json and core_*.png

x = achieved relative error against a reference at far higher precision, y = run time (minimum
of repeats), both log scale. Compared methods:

* critical point p_c: ``symhx.critical_point`` (Lambert/secant seed, then two Arb-certified
  signs and an Arb enclosure) against the naive exhaustive scan of c_k over all k with mpmath at
  the same dps, and the float64 scan with ``scipy.special.gammaln`` (what a user would write
  first).
* speed table (issue 11), all in one run: ``critical_point(N, dps=50)`` for N = 10^2 ... 10^1000
  and ``symhx.spaces.critical_point(N, space="eq41", dps=50)`` at N = 101 and 10^4, with the
  ratios "exhaustive mpmath scan / symhx" at N = 10^4 (target >= 1000) and
  "N = 10^100 / N = 10^4" (target <= 3).
* mean of X: ``symhx.mean`` (log space, significant terms only) against the naive mpmath sum of
  every term with factorials, and the float64 ``gammaln`` + log-sum-exp route.
"""

from __future__ import annotations

import math
import sys
from fractions import Fraction
from pathlib import Path

import mpmath
import numpy as np
from scipy.special import gammaln, logsumexp

sys.path.insert(0, str(Path(__file__).resolve().parent))
from _common import RESULTS, best_time, write

import symhx


def rel_err(x, ref) -> float:
    with mpmath.workdps(300):
        e = abs(mpmath.mpf(x) - ref) / abs(ref)
    return max(float(e), 1e-300)


def naive_scan_mp(N: int, dps: int) -> mpmath.mpf:
    with mpmath.workdps(dps):
        lg = mpmath.loggamma(N)
        best = min((mpmath.log(k) + mpmath.loggamma(N - k + 1) - lg) / (k - 1)
                   for k in range(2, N + 1))
        return mpmath.exp(best)


def naive_scan_float(N: int) -> float:
    k = np.arange(2, N + 1, dtype=float)
    v = (np.log(k) + gammaln(N - k + 1) - gammaln(N)) / (k - 1)
    return float(np.exp(v.min()))


def bench_critical() -> list[dict]:
    rows = []
    for N in (10**3, 10**5):
        ref = symhx.critical_point(N, dps=300).p
        for dps in (10, 20, 50, 100, 200):
            t = best_time(lambda N=N, dps=dps: symhx.critical_point(N, dps=dps), repeat=3)
            rows.append({"task": "critical", "N": N, "method": "symhx.critical_point",
                         "dps": dps, "time": t,
                         "error": rel_err(symhx.critical_point(N, dps=dps).p, ref)})
            if N <= 10**3 or dps <= 20:
                t = best_time(lambda N=N, dps=dps: naive_scan_mp(N, dps), repeat=1,
                              min_time=0)
                rows.append({"task": "critical", "N": N, "method": "naive mpmath scan",
                             "dps": dps, "time": t, "error": rel_err(naive_scan_mp(N, dps), ref)})
        t = best_time(lambda N=N: naive_scan_float(N))
        rows.append({"task": "critical", "N": N, "method": "float64 gammaln scan", "dps": 16,
                     "time": t, "error": rel_err(naive_scan_float(N), ref)})
    return rows


def bench_speed() -> dict:
    """Timings of the issue-11 table and the two ratios, measured in this one run."""
    from symhx.spaces import critical_point as space_cp

    rows = []
    for e in (2, 4, 6, 100, 1000):
        N = 10**e
        cp = symhx.critical_point(N, dps=50)
        t = best_time(lambda N=N: symhx.critical_point(N, dps=50), repeat=5)
        rows.append({"call": f"critical_point(10**{e}, dps=50)", "N": f"1e{e}", "time": t,
                     "sign_evaluations": cp.sign_evaluations})
    for N in (101, 10**4):
        t = best_time(lambda N=N: space_cp(N, space="eq41", dps=50), repeat=3)
        rows.append({"call": f"spaces.critical_point({N}, space='eq41', dps=50)", "N": str(N),
                     "time": t, "sign_evaluations": None})
    t_scan = best_time(lambda: naive_scan_mp(10**4, 50), repeat=1, min_time=0)
    rows.append({"call": "exhaustive mpmath scan, N=10**4, dps=50", "N": "1e4", "time": t_scan,
                 "sign_evaluations": None})
    t4 = next(r["time"] for r in rows if r["call"].startswith("critical_point(10**4,"))
    t100 = next(r["time"] for r in rows if r["call"].startswith("critical_point(10**100,"))
    return {"rows": rows, "scan_over_symhx_N1e4": t_scan / t4, "N1e100_over_N1e4": t100 / t4}


def naive_mean_mp(N: int, p: Fraction, dps: int) -> mpmath.mpf:
    with mpmath.workdps(dps):
        pm = mpmath.mpf(p.numerator) / p.denominator
        w = [pm**k * mpmath.factorial(N) / (k * mpmath.factorial(N - k)) for k in range(1, N + 1)]
        return mpmath.fsum(k * x for k, x in enumerate(w, 1)) / mpmath.fsum(w)


def float_mean(N: int, p: float) -> float:
    k = np.arange(1, N + 1, dtype=float)
    lw = k * math.log(p) + gammaln(N + 1) - np.log(k) - gammaln(N - k + 1)
    return float(np.exp(logsumexp(lw, b=k) - logsumexp(lw)))


def bench_mean() -> list[dict]:
    rows = []
    N = 10**4
    p = Fraction(3, N)
    exact = symhx.mean(N, p)
    with mpmath.workdps(300):
        ref = mpmath.mpf(exact.numerator) / exact.denominator
    pm = mpmath.mpf(3) / N
    for dps in (15, 30, 50, 100):
        with mpmath.workdps(dps + 20):
            pm = mpmath.mpf(3) / N
        t = best_time(lambda dps=dps, pm=pm: symhx.mean(N, pm, dps=dps), repeat=3)
        rows.append({"task": "mean", "N": N, "method": "symhx.mean (log space)", "dps": dps,
                     "time": t, "error": rel_err(symhx.mean(N, pm, dps=dps), ref)})
        t = best_time(lambda dps=dps: naive_mean_mp(N, p, dps), repeat=1, min_time=0)
        rows.append({"task": "mean", "N": N, "method": "naive mpmath full sum", "dps": dps,
                     "time": t, "error": rel_err(naive_mean_mp(N, p, dps), ref)})
    t = best_time(lambda: symhx.mean(N, p), repeat=1, min_time=0)
    rows.append({"task": "mean", "N": N, "method": "symhx.mean exact (Fraction)", "dps": None,
                 "time": t, "error": 1e-300})
    t = best_time(lambda: float_mean(N, 3 / N))
    rows.append({"task": "mean", "N": N, "method": "float64 gammaln + logsumexp", "dps": 16,
                 "time": t, "error": rel_err(float_mean(N, 3 / N), ref)})
    return rows


def plot(rows: list[dict]) -> None:
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    for task in ("critical", "mean"):
        fig, ax = plt.subplots(figsize=(6, 4))
        sel = [r for r in rows if r["task"] == task]
        for key in sorted({(r["method"], r["N"]) for r in sel}, key=str):
            pts = sorted((r["error"], r["time"]) for r in sel if (r["method"], r["N"]) == key)
            ax.loglog(*zip(*pts, strict=True), marker="o", label=f"{key[0]}, N={key[1]:.0e}")
        ax.set_xlabel("achieved relative error")
        ax.set_ylabel("time [s]")
        ax.set_title(f"work-precision: {task}")
        ax.legend(fontsize="x-small")
        fig.savefig(RESULTS / f"core_{task}_work_precision.png", dpi=110, bbox_inches="tight")


def main() -> int:
    speed = bench_speed()
    for r in speed["rows"]:
        print(f"{r['call']:55s} {r['time'] * 1e3:10.3f} ms")
    print(f"scan / symhx at N=1e4: {speed['scan_over_symhx_N1e4']:.0f}x (target >= 1000); "
          f"N=1e100 / N=1e4: {speed['N1e100_over_N1e4']:.2f} (target <= 3)")
    rows = bench_critical() + bench_mean()
    write("core", {"rows": rows, "speed": speed})
    plot(rows)
    for r in rows:
        print(f"{r['task']:8s} N={r['N']:<8} {r['method']:30s} dps={r['dps']!s:5s} "
              f"time={r['time']:.3e}s err={r['error']:.1e}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
