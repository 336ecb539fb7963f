"""Impact-simulation benchmarks (run: ``python benchmarks/bench_impact.py``).

1. Throughput of the float64 C engine: impacts per second for 100 pipes at sigma = 0.3 (every
   site impacts), one process and a 2-process pool (wall time after the workers have started;
   OpenBLAS limited to one thread so that it does not compete with the engine).
2. Work-precision against ``scipy.integrate.solve_ivp`` (DOP853, one terminal event per gap,
   impact map applied at each event and the integration restarted) on a forced, elastic 10-pipe
   row over the same horizon.  Reference: the mpmath engine at dps = 30.  Error = max |t - t_ref|
   over the impacts matched in order (same site); "missed" = reference impacts not reproduced
   before the sequence diverges or ends.  Time = minimum of several repeats.

Writes ``benchmarks/results/impact*.json`` and ``impact_work_precision.png``.
"""

from __future__ import annotations

import json
import os
import platform
import sys
import time
from concurrent.futures import ProcessPoolExecutor
from pathlib import Path

os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")   # before numpy: no idle BLAS threads

import numpy as np

HERE = Path(__file__).resolve().parent
OUT = HERE / "results"


def machine() -> dict:
    import mpmath
    import scipy

    return {"python": sys.version.split()[0], "numpy": np.__version__, "scipy": scipy.__version__,
            "mpmath": mpmath.__version__, "platform": platform.platform(),
            "processor": platform.processor(), "cpus": os.cpu_count()}


def _count(args):
    from symhx.impact import PipeRow
    from symhx.impact.fast import count_impacts

    seed, sigma, t_end = args
    row = PipeRow.random(100, sigma, seed=seed, restitution=0.8)
    t0 = time.perf_counter()
    counts, nev = count_impacts(row, t_end, 0.0)
    return int(counts.sum()), nev, time.perf_counter() - t0


def throughput(sigma: float = 0.3, rows: int = 16, t_end: float = 300.0) -> dict:
    serial = [_count((s, sigma, t_end)) for s in range(rows)]
    imp = sum(r[0] for r in serial)
    sec = sum(r[2] for r in serial)
    with ProcessPoolExecutor(2) as ex:
        list(ex.map(_count, [(s, sigma, 10.0) for s in range(2)]))   # start the workers first
        t0 = time.perf_counter()
        par = list(ex.map(_count, [(s, sigma, t_end) for s in range(rows, 5 * rows)]))
        wall = time.perf_counter() - t0
    imp2 = sum(r[0] for r in par)
    return {"sigma": sigma, "n": 100, "t_end": t_end, "rows": rows,
            "impacts_per_s_one_core": imp / sec,
            "impacts_per_s_two_processes_wall": imp2 / wall,
            "events_per_s_one_core": sum(r[1] for r in serial) / sec}


# ----------------------------------------------------------------- solve_ivp with events
def ivp_impacts(row, t_end: float, rtol: float):
    from scipy.integrate import solve_ivp

    n = row.n
    om2 = row.omega**2
    Om = row.omega_float()
    eq = np.arange(1, n + 1) * row.d
    right = (n + 1) * row.d

    def rhs(t, y):
        x, v = y[:n], y[n:]
        f = (row.alpha * np.cos(Om * t) + row.beta * np.sin(Om * t)).sum(axis=1)
        return np.concatenate((v, -om2 * (x - eq) + f))

    def make(i):
        def ev(t, y):
            xl = 0.0 if i == 0 else y[i - 1]
            xr = right if i == n else y[i]
            return xr - xl
        ev.terminal = True
        ev.direction = -1
        return ev

    events = [make(i) for i in range(n + 1)]
    y = np.concatenate((row.x0, row.v0))
    t = 0.0
    out_t, out_s = [], []
    r = row.restitution
    while t < t_end:
        sol = solve_ivp(rhs, (t, t_end), y, method="DOP853", rtol=rtol, atol=rtol * 1e-2,
                        events=events)
        if sol.status != 1:
            break
        hits = [(te[0], i) for i, te in enumerate(sol.t_events) if len(te)]
        te, i = min(hits)
        y = sol.y_events[i][0].copy()
        t = te
        out_t.append(te)
        out_s.append(i)
        if i == 0:
            y[n] = -r * y[n]
        elif i == n:
            y[2 * n - 1] = -r * y[2 * n - 1]
        else:
            u = y[n + i] - y[n + i - 1]
            y[n + i - 1] += (1 + r) * u / 2
            y[n + i] -= (1 + r) * u / 2
    return np.array(out_t), np.array(out_s)


def compare(ref_t, ref_s, t, s):
    m = 0
    while m < min(len(ref_s), len(s)) and ref_s[m] == s[m] and abs(t[m] - ref_t[m]) < 1e-2:
        m += 1
    err = float(np.max(np.abs(np.asarray(t[:m]) - ref_t[:m]))) if m else float("inf")
    return err, len(ref_s) - m


def work_precision(t_end: float = 30.0, seed: int = 2, repeats: int = 3) -> dict:
    from symhx.impact import IMPACT, PipeRow, simulate

    row = PipeRow.random(10, 0.3, seed=seed, restitution=1.0)
    ref = simulate(row, t_end, dps=30)
    sel = ref.kinds == IMPACT
    ref_t = np.array([float(x) for x in ref.times[sel]])
    ref_s = ref.sites[sel]
    res = {"t_end": t_end, "n": 10, "sigma": 0.3, "restitution": 1.0, "reference_impacts":
           int(sel.sum()), "symhx": {}, "solve_ivp": []}
    best = float("inf")
    for _ in range(repeats):
        t0 = time.perf_counter()
        h = simulate(row, t_end)
        best = min(best, time.perf_counter() - t0)
    err, missed = compare(ref_t, ref_s, h.times[h.kinds == IMPACT], h.sites[h.kinds == IMPACT])
    res["symhx"] = {"seconds": best, "error": err, "missed": missed}
    for rtol in [1e-3, 1e-4, 1e-5, 1e-6, 1e-7, 1e-8, 1e-9, 1e-10, 1e-11, 1e-12]:
        best = float("inf")
        for _ in range(repeats if rtol > 1e-9 else 1):
            t0 = time.perf_counter()
            t, s = ivp_impacts(row, t_end, rtol)
            best = min(best, time.perf_counter() - t0)
        err, missed = compare(ref_t, ref_s, t, s)
        res["solve_ivp"].append({"rtol": rtol, "seconds": best, "error": err, "missed": missed,
                                 "found": len(t)})
        print(f"solve_ivp rtol={rtol:.0e}: {best:.3f} s, error {err:.2e}, missed {missed}",
              flush=True)
    return res


def main() -> None:
    OUT.mkdir(exist_ok=True)
    info = machine()
    tp = throughput()
    print(json.dumps(tp, indent=1), flush=True)
    (OUT / "impact_throughput.json").write_text(json.dumps({"machine": info, **tp}, indent=1))
    wp = work_precision()
    (OUT / "impact_work_precision.json").write_text(json.dumps({"machine": info, **wp}, indent=1))
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, ax = plt.subplots(figsize=(6, 4))
    iv = wp["solve_ivp"]
    ax.loglog([max(r["error"], 1e-17) for r in iv], [r["seconds"] for r in iv], "o-",
              label="solve_ivp DOP853 + events")
    for r in iv:
        if r["missed"]:
            ax.annotate(f"{r['missed']} missed", (max(r["error"], 1e-17), r["seconds"]),
                        fontsize=6)
    s = wp["symhx"]
    ax.loglog([max(s["error"], 1e-17)], [s["seconds"]], "r*", ms=12, label="symhx float64 (C)")
    ax.set_xlabel("max error of impact times (vs mpmath dps=30)")
    ax.set_ylabel("time [s] (min of repeats)")
    ax.set_title(f"10 pipes, t in [0, {wp['t_end']:g}], {wp['reference_impacts']} impacts",
                 fontsize=9)
    ax.legend(fontsize=8)
    fig.savefig(OUT / "impact_work_precision.png", dpi=110, bbox_inches="tight")
    print(json.dumps(s, indent=1))


if __name__ == "__main__":
    main()
