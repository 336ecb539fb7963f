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


#: digits of the reference; errors below RESOLUTION are reported as an upper bound
REF_DPS = 130
RESOLUTION = 1e-120


def reference(sigmas):
    """p at REF_DPS digits by an independent 1-D quadrature (no closed form of symhx):
    p = P(R0 > 1) + int_0^1 f0(t) P(R1 > 1 - t) dt, R0, R1 Rayleigh of scale sqrt(2) sigma."""
    out = []
    with mpmath.workdps(REF_DPS + 10):
        for s in sigmas:
            sc = mpmath.sqrt(2) * mpmath.mpf(s)

            def f(t, sc=sc):
                return t / sc**2 * mpmath.exp(-t * t / (2 * sc * sc)) * mpmath.exp(
                    -(1 - t) ** 2 / (2 * sc * sc))

            out.append(mpmath.exp(-1 / (2 * sc * sc))
                       + mpmath.quad(f, [0, mpmath.mpf(1) / 4, mpmath.mpf(1) / 2,
                                         mpmath.mpf(3) / 4, 1]))
    return out


def max_rel(vals, refs):
    """Largest relative error (1e3 stands for "no correct digit": p <= 0 or NaN)."""
    with mpmath.workdps(REF_DPS + 20):
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
            err = max_rel(vals, refs)
            rows.append(dict(set=set_name, method="symhx mpmath", param=f"dps={dps}", time=t,
                             error=max(err, RESOLUTION), error_is_bound=err < RESOLUTION))
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


def _is_bound(r: dict) -> bool:
    """True if the error is only an upper bound (below the reference's resolution); rows of
    older result files stored the floor ``10**-(dps + 3)`` for that case."""
    if "error_is_bound" in r:
        return bool(r["error_is_bound"])
    p = r.get("param", "")
    return (r["method"] == "symhx mpmath" and p.startswith("dps=")
            and r["error"] == 10.0 ** -(int(p[4:]) + 3))


def plot(rows, path: Path) -> None:
    """Work-precision figure. An error that is only bounded (below the reference's resolution)
    is drawn as an open marker with a left arrow at the bound, never at a made-up value; "no
    correct digit" (p <= 0, relative error >= 1) is drawn at 1 with a cross."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, axes = plt.subplots(1, 2, figsize=(12, 4.6), sharey=True)
    markers = {"symhx float64": "o", "symhx mpmath": "s", "1 - scipy dblquad (eq. 27)": "x",
               "1 - mpmath 2-D quad (eq. 27)": "^"}
    for ax, set_name in zip(axes, SETS, strict=True):
        for i, (m, mk) in enumerate(markers.items()):
            rr = [r for r in rows if r["set"] == set_name and r["method"] == m]
            if not rr:
                continue
            x = [min(r["error"], 1.0) for r in rr]
            y = [r["time"] for r in rr]
            ax.plot(x, y, "-", color=f"C{i}", alpha=0.5)
            # points of one method at about the same error share one label (no overlap)
            clustered = len(rr) > 1 and max(x) / min(x) < 1e3
            if clustered:
                params = [r["param"] for r in rr]
                note = " no correct digit" if min(r["error"] for r in rr) >= 1 else ""
                ax.annotate(f"{params[0]} … {params[-1]}{note}", (x[0], max(y)), fontsize=6,
                            xytext=(-6, 8), textcoords="offset points", color=f"C{i}",
                            ha="right")
            for k, (r, xx, yy) in enumerate(zip(rr, x, y, strict=True)):
                bound = _is_bound(r)
                ax.plot([xx], [yy], mk, color=f"C{i}", mfc="none" if bound else f"C{i}",
                        label=m if k == 0 else None)
                if bound:
                    ax.annotate("", (xx / 1e8, yy), (xx, yy),
                                arrowprops=dict(arrowstyle="->", color=f"C{i}", lw=0.8))
                text = r["param"] + (" (< bound)" if bound else "")
                if r["error"] >= 1:
                    text = (r["param"] + " " if r["param"] else "") + "no correct digit"
                if text and not clustered:
                    dy = (7, -10)[k % 2] + 3 * i
                    ax.annotate(text, (xx, yy), fontsize=6, xytext=(4, dy),
                                textcoords="offset points", color=f"C{i}")
        ax.set_xscale("log")
        ax.set_yscale("log")
        ax.set_xlim(1e-135, 30)
        ax.set_xlabel(f"max relative error of p (vs independent {REF_DPS}-digit quadrature)")
        ax.set_title(f"σ in {SETS[set_name]} ({set_name})", fontsize=9)
        ax.grid(alpha=0.3, which="both")
    axes[0].set_ylabel("time per value [s]")
    axes[0].legend(fontsize=7, loc="upper left")
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
    if "--plot-only" in sys.argv:  # redraw the figure from the stored results
        import json

        rows = json.loads((RESULTS / "forcing.json").read_text())["work_precision"]
        plot(rows, RESULTS / "forcing_work_precision.png")
        return
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
