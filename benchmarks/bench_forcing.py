"""Benchmark of symhx.forcing (impact probability, eqs. 22-27): throughput and work-precision.

Run:  python benchmarks/bench_forcing.py
Writes benchmarks/results/forcing.json and benchmarks/results/forcing_work_precision.png.

* float64 throughput on arrays of 1e6 sigma values (log-spaced in [0.01, 100]), one core; also
  with unequal scales (sigma1 = 2 sigma) and with the sigmas in random order.
* mpmath time per value at 50 digits (also with sigma1 = 2 sigma).
* Work-precision (x: max relative error of p against a 130-digit reference, y: time per value)
  for symhx float64, symhx mpmath at several dps, the paper's eq. (27) as
  ``1 - scipy.integrate.dblquad`` at several tolerances, and ``1 -`` mpmath 2-D ``quad``.
  Two sigma sets: the paper's range where p is not small (0.2-1), and the small tail (0.03-0.1).
"""

from __future__ import annotations

import math
import os
import sys
import time
from pathlib import Path

import mpmath
import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parent))
from _common import RESULTS, best_time, write

from symhx import forcing as F

SETS = {"moderate": [0.2, 0.35, 0.6, 1.0], "small tail": [0.03, 0.05, 0.07, 0.1]}


def reference(sigmas):
    return [F.impact_probability(s, dps=130) for s in sigmas]


def max_rel(vals, refs):
    with mpmath.workdps(150):
        errs = [abs(mpmath.mpf(v) / r - 1) if v == v else mpmath.inf for v, r in
                zip(vals, refs, strict=True)]
        return float(min(max(errs), 1e3))


def dblquad_p(s, tol):
    from scipy import integrate

    k = 1.0  # (omega^2 - Omega^2)^2 for omega = 1, Omega = sqrt 2
    c = k / (4 * s**4)

    def f(t, x):
        return t * (x - t) * math.exp(-t * t / (4 * s * s)) * math.exp(-k * (x - t) ** 2
                                                                      / (4 * s * s))

    val, _ = integrate.dblquad(f, 0.0, 1.0, 0.0, lambda x: x, epsabs=tol, epsrel=tol)
    return 1.0 - c * val


def mp_quad_p(s, dps):
    with mpmath.workdps(dps):
        s = mpmath.mpf(s)
        c = 1 / (4 * s**4)
        q = c * mpmath.quad(lambda x: mpmath.quad(
            lambda t: t * (x - t) * mpmath.exp(-t**2 / (4 * s**2) - (x - t) ** 2 / (4 * s**2)),
            [0, x]), [0, 1])
        return 1 - q


def throughput():
    s = np.logspace(-2, 2, 10**6)
    out = {}
    for fn in (F.impact_probability, F.no_impact_probability, F.log_impact_probability,
               F.log_no_impact_probability):
        t = best_time(lambda fn=fn: fn(s), repeat=7, min_time=0.0)
        out[fn.__name__] = {"seconds_per_1e6": t, "values_per_second": 1e6 / t}
    # harder float64 inputs: unequal Rayleigh scales (sigma1 = 2 sigma: no piece shared between
    # the two scales), and the same sigmas in random order (both 1 - p branches in every chunk)
    shuffled = np.random.default_rng(0).permutation(s)
    for label, arg, kw in (("unequal_scales", s, {"sigma1": 2 * s}), ("shuffled", shuffled, {})):
        block = out.setdefault(f"{label} (sigma1=2 sigma)" if kw else label, {})
        for fn in (F.impact_probability, F.no_impact_probability):
            t = best_time(lambda fn=fn, arg=arg, kw=kw: fn(arg, **kw), repeat=7, min_time=0.0)
            block[fn.__name__] = {"seconds_per_1e6": t, "values_per_second": 1e6 / t}
    # the paper's parameters as scalars broadcast against the array: same code path
    sig = [float(v) for v in np.logspace(-2, 2, 50)]
    mp50 = {}
    for fn in (F.impact_probability, F.no_impact_probability):
        t = best_time(lambda fn=fn: [fn(v, dps=50) for v in sig], repeat=5) / len(sig)
        mp50[fn.__name__] = {"microseconds_per_value": 1e6 * t}
    block = mp50.setdefault("unequal_scales (sigma1=2 sigma)", {})
    for fn in (F.impact_probability, F.no_impact_probability):
        t = best_time(lambda fn=fn: [fn(v, sigma1=2 * v, dps=50) for v in sig], repeat=5) / len(sig)
        block[fn.__name__] = {"microseconds_per_value": 1e6 * t}
    return out, mp50


def work_precision():
    rows = []
    for set_name, sig in SETS.items():
        refs = reference(sig)
        vals = F.impact_probability(np.array(sig))
        t = best_time(lambda sig=sig: F.impact_probability(np.array(sig))) / len(sig)
        rows.append(dict(set=set_name, method="symhx float64", param="", time=t,
                         error=max_rel(list(vals), refs)))
        for dps in (15, 30, 50, 100):
            vals = [F.impact_probability(s, dps=dps) for s in sig]
            t = best_time(lambda sig=sig, dps=dps: [F.impact_probability(s, dps=dps)
                                                    for s in sig]) / len(sig)
            rows.append(dict(set=set_name, method="symhx mpmath", param=f"dps={dps}", time=t,
                             error=max(max_rel(vals, refs), 10.0 ** -(dps + 3))))
        dblquad_p(0.5, 1e-8)  # warm-up (imports)
        for tol in (1e-4, 1e-8, 1.49e-8 / 100, 1e-13):
            t0 = time.perf_counter()
            vals = [dblquad_p(s, tol) for s in sig]
            t = (time.perf_counter() - t0) / len(sig)
            rows.append(dict(set=set_name, method="1 - scipy dblquad (eq. 27)",
                             param=f"tol={tol:.0e}", time=t, error=max_rel(vals, refs)))
        for dps in (10, 15, 20):
            t0 = time.perf_counter()
            vals = [mp_quad_p(s, dps) for s in sig[:2]]
            t = (time.perf_counter() - t0) / 2
            rows.append(dict(set=set_name, method="1 - mpmath 2-D quad (eq. 27)",
                             param=f"dps={dps}", time=t, error=max_rel(vals, refs[:2])))
    return rows


def naive_at(sigma=0.05):
    return {"sigma": sigma, "naive_1_minus_dblquad": F.naive_impact_probability(sigma),
            "true_p": F.impact_probability(sigma, dps=30)}


def plot(rows, path: Path) -> None:
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, axes = plt.subplots(1, 2, figsize=(11, 4.3), sharey=True)
    markers = {"symhx float64": "o", "symhx mpmath": "s", "1 - scipy dblquad (eq. 27)": "x",
               "1 - mpmath 2-D quad (eq. 27)": "^"}
    for ax, set_name in zip(axes, SETS, strict=True):
        for i, (m, mk) in enumerate(markers.items()):
            rr = [r for r in rows if r["set"] == set_name and r["method"] == m]
            x = [max(r["error"], 1e-110) for r in rr]
            y = [r["time"] for r in rr]
            ax.plot(x, y, mk + "-", color=f"C{i}", label=m)
            for r, xx, yy in zip(rr, x, y, strict=True):
                if r["param"]:
                    ax.annotate(r["param"], (xx, yy), fontsize=6, xytext=(3, 3),
                                textcoords="offset points")
        ax.set_xscale("log")
        ax.set_yscale("log")
        ax.set_xlabel("max relative error of p (vs 130-digit reference)")
        ax.set_title(f"σ in {SETS[set_name]} ({set_name})", fontsize=9)
        ax.grid(alpha=0.3, which="both")
    axes[0].set_ylabel("time per value [s]")
    axes[0].legend(fontsize=7)
    fig.suptitle("Work-precision: impact probability p(σ), eq. (27), ω = 1, Ω = √2, d = 1",
                 fontsize=10)
    fig.savefig(path, dpi=110, bbox_inches="tight")


def _flat(results: dict) -> dict:
    """``{name: timing}`` with the nested groups (unequal scales, shuffled) as "group / name"."""
    out = {}
    for k, v in results.items():
        if any(isinstance(x, dict) and isinstance(next(iter(x.values())), dict)
               for x in [v]):
            out.update({f"{k} / {a}": b for a, b in v.items()})
        else:
            out[k] = v
    return out


def main() -> None:
    try:
        os.sched_setaffinity(0, {min(os.sched_getaffinity(0))})  # one core
    except (AttributeError, OSError):  # pragma: no cover
        pass
    thr, mp50 = throughput()
    rows = work_precision()
    payload = {"float64_1e6_array": thr, "mpmath_50_digits": mp50, "work_precision": rows,
               "naive_at_0.05": naive_at(),
               "rerun": "python benchmarks/bench_forcing.py"}
    p = write("forcing", payload)
    plot(rows, RESULTS / "forcing_work_precision.png")
    for k, v in _flat(thr).items():
        print(f"{k:60s} {v['values_per_second'] / 1e6:7.2f} M values/s (1e6 array)")
    for k, v in _flat(mp50).items():
        print(f"{k:60s} {v['microseconds_per_value']:7.1f} us/value at 50 digits")
    for r in rows:
        print(f"{r['set']:10s} {r['method']:30s} {r['param']:10s} {r['time']:.2e} s "
              f"err {r['error']:.1e}")
    print(f"wrote {p}")


if __name__ == "__main__":
    main()
