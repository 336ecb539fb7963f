"""Impact-simulation benchmarks (run: ``python benchmarks/bench_impact.py``).

1. Throughput of the float64 C engine: impacts per second for 100 pipes at sigma = 0.3 (every
   site impacts), one process (per CPU second of the process, and per wall second: on a shared
   machine the two differ) and a 2-process pool (wall time after the workers have started;
   OpenBLAS limited to one thread so that it does not compete with the engine).
2. Work-precision against ``scipy.integrate.solve_ivp`` (DOP853, one terminal event per gap,
   impact map applied at each event and the integration restarted) on a forced, elastic 10-pipe
   row over the same horizon.  Reference: the mpmath engine at dps = 30.  Error = max |t - t_ref|
   over the impacts matched in order (same site); "missed" = reference impacts not reproduced
   before the sequence diverges or ends.  Time = minimum of several repeats.

3. Against heyoka (Taylor integrator with guaranteed event detection, ``pip install heyoka``, the
   ``bench`` extra): per-run time at equal accuracy on 10 pipes (t <= 30) and 100 pipes
   (t <= 10), three seeds each.  heyoka gets the forcing amplitudes as runtime parameters (one
   compilation per n, not timed), tol 1e-15, one terminal event per gap whose callback applies
   the impact map and continues.  Both engines must reproduce the impact sites of the mpmath
   reference (dps 20) with impact times within 1e-12.  Time = minimum of 200 alternating repeats
   of one run each (symhx pays its whole set-up per call: validation, the row's closed-form
   arrays, the History; heyoka its state and parameters).
4. Ensemble throughput (runs/s) for the figures 7-8 workload (100 pipes, t = 300, r = 0.8):
   symhx ``count_impacts`` serially and on a 2-process pool against heyoka's own
   ``ensemble_propagate_until`` (2 threads).

Writes ``benchmarks/results/impact*.json`` and ``impact_work_precision.png``;
``--parts throughput,heyoka`` runs only those parts (the machine is shared: the load average at
start and end is recorded).
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
    t0, c0 = time.perf_counter(), time.process_time()
    counts, nev = count_impacts(row, t_end, 0.0)
    return int(counts.sum()), nev, time.perf_counter() - t0, time.process_time() - c0


def throughput(sigma: float = 0.3, rows: int = 16, t_end: float = 300.0) -> dict:
    serial = [_count((s, sigma, t_end)) for s in range(rows)]
    imp = sum(r[0] for r in serial)
    sec = sum(r[2] for r in serial)
    cpu = sum(r[3] for r in serial)
    with ProcessPoolExecutor(2) as ex:
        list(ex.map(_count, [(s, sigma, 10.0) for s in range(2)]))   # start the workers first
        t0 = time.perf_counter()
        par = list(ex.map(_count, [(s, sigma, t_end) for s in range(rows, 5 * rows)]))
        wall = time.perf_counter() - t0
    imp2 = sum(r[0] for r in par)
    return {"sigma": sigma, "n": 100, "t_end": t_end, "rows": rows,
            "impacts_per_s_one_core": imp / cpu,
            "impacts_per_s_one_core_wall": imp / sec,
            "impacts_per_s_two_processes_wall": imp2 / wall,
            "events_per_s_one_core": sum(r[1] for r in serial) / cpu}


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


# ----------------------------------------------------------------- heyoka
def heyoka_integrator(n: int, restitution: float, omega: float = 1.0, d: float = 1.0,
                      Omega: float = float(np.sqrt(2.0))):
    """A heyoka integrator for an n-pipe row (one forcing frequency); forcing amplitudes are the
    runtime parameters ``par[2j], par[2j+1]`` (alpha, beta of pipe j + 1).  Returns
    ``(ta, hits)``: ``hits`` collects ``(t, site)`` of every impact (cleared by the caller)."""
    import heyoka as hy

    xs = hy.make_vars(*[f"x{j}" for j in range(n)])
    vs = hy.make_vars(*[f"v{j}" for j in range(n)])
    dyn = [(xs[j], vs[j]) for j in range(n)]
    for j in range(n):
        force = (hy.par[2 * j] * hy.cos(Omega * hy.time)
                 + hy.par[2 * j + 1] * hy.sin(Omega * hy.time))
        dyn.append((vs[j], -omega**2 * (xs[j] - (j + 1) * d) + force))
    hits: list = []
    r = restitution

    def make_cb(i):
        def cb(ta, d_sgn):
            s = ta.state
            u = (s[n + i] if i < n else 0.0) - (s[n + i - 1] if i > 0 else 0.0)
            if u < 0:
                if i == 0:
                    s[n] -= (1 + r) * u
                elif i == n:
                    s[2 * n - 1] += (1 + r) * u
                else:
                    s[n + i - 1] += (1 + r) * u / 2
                    s[n + i] -= (1 + r) * u / 2
                hits.append((ta.time, i))
            return True
        return cb

    events = []
    for i in range(n + 1):
        g = (xs[i] if i < n else float((n + 1) * d)) - (xs[i - 1] if i > 0 else 0.0)
        events.append(hy.t_event(g, callback=make_cb(i), direction=hy.event_direction.negative))
    ta = hy.taylor_adaptive(dyn, [0.0] * (2 * n), tol=1e-15, pars=[0.0] * (2 * n),
                            t_events=events)
    return ta, hits


def heyoka_run(ta, hits, row, t_end: float):
    hits.clear()
    ta.time = 0.0
    ta.state[:] = np.concatenate((row.x0, row.v0))
    ta.pars[:] = np.column_stack((row.alpha[:, 0], row.beta[:, 0])).ravel()
    ta.reset_cooldowns()
    ta.propagate_until(float(t_end))
    return np.array([h[0] for h in hits]), np.array([h[1] for h in hits], dtype=int)


def vs_heyoka(sigma: float = 0.3, restitution: float = 0.8, repeats: int = 200) -> list:
    from symhx.impact import IMPACT, PipeRow, simulate

    rows = []
    for n, t_end in ((10, 30.0), (100, 10.0)):
        ta, hits = heyoka_integrator(n, restitution)
        for seed in (1, 2, 3):
            row = PipeRow.random(n, sigma, seed=seed, restitution=restitution)
            ref = simulate(row, t_end, dps=20)
            sel = ref.kinds == IMPACT
            ref_t = np.array([float(x) for x in ref.times[sel]])
            ref_s = ref.sites[sel]
            t_sym = t_hy = float("inf")
            for _ in range(repeats):
                t0 = time.perf_counter()
                h = simulate(row, t_end)
                t_sym = min(t_sym, time.perf_counter() - t0)
                t0 = time.perf_counter()
                ht, hs = heyoka_run(ta, hits, row, t_end)
                t_hy = min(t_hy, time.perf_counter() - t0)
            e_sym, m_sym = compare(ref_t, ref_s, h.times[h.kinds == IMPACT],
                                   h.sites[h.kinds == IMPACT])
            e_hy, m_hy = compare(ref_t, ref_s, ht, hs)
            rec = {"n": n, "t_end": t_end, "seed": seed, "sigma": sigma,
                   "restitution": restitution, "impacts": int(sel.sum()),
                   "other_events": int((~sel).sum()),
                   "symhx_s": t_sym, "symhx_error": e_sym, "symhx_missed": m_sym,
                   "heyoka_s": t_hy, "heyoka_error": e_hy, "heyoka_missed": m_hy,
                   "speedup": t_hy / t_sym}
            print(json.dumps(rec), flush=True)
            rows.append(rec)
    return rows


def _count_fig78(args):
    from symhx.impact import PipeRow
    from symhx.impact.fast import count_impacts

    seed, sigma = args
    row = PipeRow.random(100, sigma, seed=seed, restitution=0.8)
    counts, _ = count_impacts(row, 300.0, 200.0)
    return int(counts.sum())


def ensemble_throughput(sigma: float = 0.3, runs: int = 40, heyoka_runs: int = 4) -> dict:
    import heyoka as hy

    from symhx.impact import PipeRow

    t0 = time.perf_counter()
    for s in range(runs):
        _count_fig78((s, sigma))
    serial = runs / (time.perf_counter() - t0)
    with ProcessPoolExecutor(2) as ex:
        list(ex.map(_count_fig78, [(s, sigma) for s in range(2)]))
        t0 = time.perf_counter()
        list(ex.map(_count_fig78, [(s, sigma) for s in range(runs)]))
        pool = runs / (time.perf_counter() - t0)
    ta, _ = heyoka_integrator(100, 0.8)
    rows = [PipeRow.random(100, sigma, seed=s, restitution=0.8) for s in range(heyoka_runs)]

    def gen(ta_copy, i):
        row = rows[i]
        ta_copy.time = 0.0
        ta_copy.state[:] = np.concatenate((row.x0, row.v0))
        ta_copy.pars[:] = np.column_stack((row.alpha[:, 0], row.beta[:, 0])).ravel()
        return ta_copy

    t0 = time.perf_counter()
    hy.ensemble_propagate_until(ta, 300.0, heyoka_runs, gen, max_workers=2)
    hy_rate = heyoka_runs / (time.perf_counter() - t0)
    res = {"n": 100, "t_end": 300.0, "t_from": 200.0, "sigma": sigma, "restitution": 0.8,
           "symhx_runs_per_s_serial": serial, "symhx_runs_per_s_2_processes": pool,
           "heyoka_runs_per_s_ensemble_2_threads": hy_rate, "heyoka_runs": heyoka_runs,
           "speedup_2_workers": pool / hy_rate}
    print(json.dumps(res), flush=True)
    return res


def main(argv: list[str] | None = None) -> None:
    import argparse

    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--parts", default="throughput,heyoka,work-precision",
                    help="comma-separated subset of throughput, heyoka, work-precision")
    parts = set(ap.parse_args(argv).parts.split(","))
    OUT.mkdir(exist_ok=True)
    info = machine()
    info["load_average_at_start"] = os.getloadavg()
    if "throughput" in parts:
        tp = throughput()
        print(json.dumps(tp, indent=1), flush=True)
        (OUT / "impact_throughput.json").write_text(json.dumps({"machine": info, **tp}, indent=1))
    if "heyoka" in parts:
        import heyoka

        peer = {"per_run": vs_heyoka(), "ensemble": ensemble_throughput()}
        info_hy = {**info, "heyoka": heyoka.__version__, "load_average_at_end": os.getloadavg()}
        (OUT / "impact_vs_heyoka.json").write_text(json.dumps({"machine": info_hy, **peer},
                                                              indent=1))
    if "work-precision" not in parts:
        return
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
