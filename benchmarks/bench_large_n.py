"""Time against error of the simple-space statistics at large N (issue 27).

    python benchmarks/bench_large_n.py     # writes benchmarks/results/large_n.json, large_n.png

For N = 10^2 ... 10^1000 at p = 2 p_c (above the jump) and at p with N p - 1 = N p_c - 1 (the
hard case: head and hump both weigh), each of ``mean``, ``var`` and ``cdf`` at the median is
timed cold (a fresh frozen distribution with the shared caches of one full pass cleared: each
statistic is timed alone) and warm (after ``mean`` of the same N, p, dps: distributions share
the one full pass, so ``var`` is then free and ``cdf`` costs one partial sum), and its error
measured against the same quantity at dps = 100.  The cdf is taken at the median (at the mode
beyond ``MP_QUANTILE_N_LIMIT``).  On the same axes the direct summation a user would write
(every term added in mpmath at 50 digits, ratio recurrence) where it can run (N <= 10^5), and
``critical_point(N, dps=50)`` for the scale of the targets (~30 of its calls per statistic).
For 10^7 < N < 10^300 also the float64 path (``dps=None``): a pmf over 1001 points, symhx's
vectorised route against the ``gammaln`` formula a user would write (given the exact
normaliser), errors against dps = 100.
"""

from __future__ import annotations

import math
import sys
import time
from fractions import Fraction
from pathlib import Path

import mpmath

sys.path.insert(0, str(Path(__file__).resolve().parent))
from _common import RESULTS, write

import symhx
from symhx import distribution as _dist
from symhx.validation import mpf_to_fraction

DPS = 50
NS = (2, 4, 6, 10, 100, 1000)


def rel_err(x, ref) -> float:
    with mpmath.workdps(300):
        e = abs(mpmath.mpf(x) - ref) / abs(ref)
    if not mpmath.isfinite(e) or e > 10:  # nan/inf or no digit right: plotted at 10
        return 10.0
    return max(float(e), 1e-70)  # below 1e-70 (agreement to the last digit) plotted at 1e-70


def timed(fn):
    t = time.perf_counter()
    v = fn()
    return v, time.perf_counter() - t


def direct_mean(N: int, p: Fraction, dps: int):
    with mpmath.workdps(dps + 2 * len(str(N))):
        pm = mpmath.mpf(p.numerator) / p.denominator
        f = N * pm
        s0 = s1 = mpmath.mpf(0)
        for k in range(1, N + 1):
            s0 += f
            s1 += k * f
            f = f * pm * (N - k) * k / (k + 1)
        return s1 / s0


def cold() -> None:
    """Forget the shared one-pass results and this thread's engines (a cold call)."""
    _dist._shared_moments.cache_clear()
    _dist._shared_entropy.cache_clear()
    _dist._ENGINES.__dict__.clear()


def main() -> None:
    rows = []
    for e in NS:
        N = 10**e
        cp = symhx.critical_point(N, dps=2 * DPS + 20)
        # the best of five cold calls (distinct N: nothing cached), as the unit of cost
        t_cp = min(timed(lambda M=N + j: symhx.critical_point(M, dps=DPS))[1]
                   for j in range(2, 7))
        with mpmath.workdps(2 * e + 2 * DPS + 40):  # mpf p: the mpmath path at every N
            cases = {"2 p_c": 2 * cp.p, "N p - 1 = 2 (N p_c - 1)": (1 + 2 * cp.q) / N}
        for label, p in cases.items():
            ref = symhx.distribution_of(N, p, dps=2 * DPS)
            k = ref.median() if N <= _dist.MP_QUANTILE_N_LIMIT else ref.mode()
            for warm in (False, True):
                for stat in ("mean", "var", "cdf"):
                    if warm and stat == "mean":
                        continue
                    best = math.inf
                    for _ in range(3):  # best of three cold calls (process-wide caches, such
                        cold()          # as Gauss-Legendre nodes per precision, stay warm)
                        if warm:
                            symhx.distribution_of(N, p, dps=DPS).mean()
                        d = symhx.distribution_of(N, p, dps=DPS)
                        call = (lambda d=d, k=k: d.cdf(k)) if stat == "cdf" else \
                            getattr(d, stat)
                        val, t1 = timed(call)
                        best = min(best, t1)
                    t = best
                    want = ref.cdf(k) if stat == "cdf" else getattr(ref, stat)()
                    rows.append({"N": f"1e{e}", "case": label,
                                 "stat": stat + (" after mean" if warm else ""), "time_s": t,
                                 "rel_err": rel_err(val, want), "critical_point_s": t_cp,
                                 "ratio_to_critical_point": t / t_cp})
                    print(rows[-1], flush=True)
            if 10**7 < N < 1e300:
                rows.extend(float_rows(N, p, k, ref, t_cp, e, label))
            if N <= 10**5:
                pf = mpf_to_fraction(p)
                val, t = timed(lambda N=N, pf=pf: direct_mean(N, pf, DPS))
                rows.append({"N": f"1e{e}", "case": label, "stat": "mean (direct sum)",
                             "time_s": t, "rel_err": rel_err(val, ref.mean()),
                             "critical_point_s": t_cp, "ratio_to_critical_point": t / t_cp})
                print(rows[-1], flush=True)
    write("large_n", {"dps": DPS, "rows": rows})
    plot(rows)


def float_rows(N: int, p, k: int, ref, t_cp: float, e: int, label: str) -> list[dict]:
    """float64 (``dps=None``) pmf at 1001 points around k: symhx's vectorised path (one
    17-digit normaliser, then numpy) against what a user would write with ``scipy.special.
    gammaln`` (``k log p + gammaln(N + 1) - gammaln(N - k + 1) - log k`` minus a logsumexp
    normaliser over the same points is not possible without the support, so the naive route
    is given symhx's exact normaliser: only the log-weights differ)."""
    import numpy as np
    from scipy.special import gammaln

    pf = float(p)
    ref = symhx.distribution_of(N, pf, dps=2 * DPS)  # the same (binary) p as the float path
    sd = max(1, int(float(mpmath.sqrt(abs(ref.var())))))
    k = ref.mode()
    step = max(1, sd // 100)
    ks = np.array(sorted({min(max(k + i * step, 1), N) for i in range(-500, 501)}),
                  dtype=np.int64 if N < 2**62 else object)
    pick = ks[:: max(1, len(ks) // 20)]
    want = [ref.pmf(int(kk)) for kk in pick]
    want_c = [ref.cdf(int(kk)) for kk in pick]
    out = []

    def row(stat: str, fn, at, reference, **extra) -> None:
        """Time ``fn`` (values at the points ``at``), its worst error at the picked points it
        has against ``reference``, as a row."""
        val, t = timed(fn)
        got = dict(zip([int(v) for v in at], list(val), strict=True))
        err = max(rel_err(got[int(kk)], w) for kk, w in zip(pick, reference, strict=True)
                  if int(kk) in got)
        out.append({"N": f"1e{e}", "case": label, "stat": stat, **extra, "time_s": t,
                    "rel_err": err, "critical_point_s": t_cp,
                    "ratio_to_critical_point": t / t_cp})

    cold()
    row("pmf x1001 (float64)", lambda: symhx.pmf(N, pf, ks, dps=None), ks, want)
    lz = float(ref.log_normaliser)

    def naive():
        kf = ks.astype(float)
        with np.errstate(all="ignore"):  # at N = 1e100 every digit cancels (inf - inf)
            return np.exp(kf * np.log(pf) + gammaln(N + 1.0) - gammaln(N - kf + 1.0) - np.log(kf)
                          - lz)

    row("pmf x1001 (gammaln)", naive, ks, want)
    # the cdf at the same 1001 points: vectorised (symhx.float_sums, after the one normaliser
    # pass) against one 17-digit partial sum per k (the mpmath path walked per point)
    cold()
    row("cdf x1001 (float64)", lambda: symhx.cdf(N, pf, ks, dps=None), ks, want_c)
    cold()
    d17 = symhx.distribution_of(N, pf, dps=17)
    few = ks[:: max(1, len(ks) // 100)]  # ~101 of the points (the same per-point cost)
    row("cdf per k (17 digits)", lambda: [d17.cdf(int(kk)) for kk in few], few, want_c,
        points=len(few))
    for r in out:
        print(r, flush=True)
    return out


def plot(rows: list[dict]) -> None:
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, ax = plt.subplots(figsize=(7.6, 4.4))
    marks = {"mean": "o", "var": "s", "cdf": "^", "var after mean": "D",
             "cdf after mean": "v", "mean (direct sum)": "x", "pmf x1001 (float64)": "P",
             "pmf x1001 (gammaln)": "*", "cdf x1001 (float64)": "h",
             "cdf per k (17 digits)": "X"}
    colours = {f"1e{e}": c for e, c in zip(NS, plt.cm.viridis([i / (len(NS) - 1)
                                                               for i in range(len(NS))]),
                                           strict=True)}
    for r in rows:
        ax.scatter(r["rel_err"], r["time_s"], marker=marks[r["stat"]], color=colours[r["N"]],
                   s=60 if r["stat"] in ("mean (direct sum)", "pmf x1001 (gammaln)") else 36)
    shown = {"pmf x1001 (float64)": "pmf ×1001, float64 (dps=None)",
             "pmf x1001 (gammaln)": "pmf ×1001, gammaln formula\n(no digit right: at 10)",
             "cdf x1001 (float64)": "cdf ×1001, float64 (dps=None)",
             "cdf per k (17 digits)": "cdf ×~100, one 17-digit\npartial sum per k"}
    for name, m in marks.items():
        ax.scatter([], [], marker=m, color="grey", label=shown.get(name, name))
    for n, c in colours.items():
        ax.scatter([], [], marker="o", color=c, label=f"N = {n}")
    ax.set_xscale("log")
    ax.set_yscale("log")
    ax.set_xlabel("relative error against dps = 100 (no difference: plotted at 1e-70)")
    ax.set_ylabel("time per call [s]")
    ax.set_title("simple-space statistics at dps = 50 (and float64 pmf, cdf)")
    ax.legend(fontsize=7, loc="upper left", bbox_to_anchor=(1.02, 1.0))
    fig.tight_layout()
    fig.savefig(RESULTS / "large_n.png", dpi=120)


if __name__ == "__main__":
    if sys.argv[1:] == ["--plot"]:  # redraw from the stored results
        import json

        plot(json.loads((RESULTS / "large_n.json").read_text())["rows"])
    else:
        main()
