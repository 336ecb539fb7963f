"""``symhx simulate`` / ``symhx ensemble`` and the simulation part of ``symhx paper`` (figs. 7, 8).

The stored data file ``symhx/data/ensemble_fig7_8.json`` is produced by
``symhx ensemble --paper --json > symhx/data/ensemble_fig7_8.json`` (same numbers as
``symhx paper --full``), so the book reads it instead of recomputing.
"""

from __future__ import annotations

import argparse
import csv
import json
import os
import time
from concurrent.futures import ProcessPoolExecutor
from pathlib import Path
from typing import Any

import numpy as np

from symhx.commands._common import dump_json

ORDER = 50

#: the paper's ensemble: 24 values of sigma, 1000 runs of 100 pipes each
PAPER_SIGMAS = [round(0.10 + 0.01 * k, 2) for k in range(24)]
PAPER_RUNS = 1000
QUICK_SIGMAS = [0.10, 0.14, 0.18, 0.22, 0.26, 0.30]
QUICK_RUNS = 20
DATA_FILE = Path(__file__).resolve().parent.parent / "data" / "ensemble_fig7_8.json"


def register(sub: Any) -> None:
    p = sub.add_parser("simulate", help="simulate one random pipe row (section 7)")
    p.add_argument("--n", type=int, default=10, help="pipes (default 10)")
    p.add_argument("--sigma", type=float, default=0.3)
    p.add_argument("--seed", type=int, default=0)
    p.add_argument("--restitution", type=float, default=0.8)
    p.add_argument("--t-end", type=float, default=20.0)
    p.add_argument("--dps", type=int, default=None,
                   help="mpmath reference engine at this precision")
    p.add_argument("--json", action="store_true", help="print JSON")
    p.set_defaults(func=cmd_simulate)

    e = sub.add_parser("ensemble", help="statistics of impacting pipes against sigma (figs. 7, 8)")
    e.add_argument("--sigmas", type=float, nargs="+", default=QUICK_SIGMAS)
    e.add_argument("--runs", type=int, default=QUICK_RUNS)
    e.add_argument("--n", type=int, default=100)
    e.add_argument("--t-transient", type=float, default=200.0)
    e.add_argument("--t-window", type=float, default=100.0)
    e.add_argument("--restitution", type=float, default=0.8)
    e.add_argument("--seed", type=int, default=0)
    e.add_argument("--workers", type=int, default=os.cpu_count() or 1)
    e.add_argument("--paper", action="store_true",
                   help=f"the paper's ensemble: {len(PAPER_SIGMAS)} sigmas x {PAPER_RUNS} runs")
    e.add_argument("--json", action="store_true", help="print JSON")
    e.set_defaults(func=cmd_ensemble)


def cmd_simulate(args: argparse.Namespace) -> int:
    from symhx.impact import KIND_NAMES, PipeRow, simulate

    row = PipeRow.random(args.n, args.sigma, seed=args.seed, restitution=args.restitution)
    h = simulate(row, args.t_end, dps=args.dps)
    events = [{"t": t, "site": int(s), "kind": KIND_NAMES[k], "u_before": u0, "u_after": u1}
              for t, s, k, u0, u1 in zip(h.times, h.sites, h.kinds, h.u_before, h.u_after,
                                         strict=True)]
    if args.json:
        print(dump_json({"n": args.n, "sigma": args.sigma, "seed": args.seed,
                         "restitution": args.restitution, "t_end": args.t_end, "dps": args.dps,
                         "events": events}))
    else:
        for ev in events:
            print(f"{float(ev['t']):14.9f}  site {ev['site']:3d}  {ev['kind']:8s}  "
                  f"u = {float(ev['u_before']): .6e}")
        print(f"{len(events)} events")
    return 0


def _run(sigmas: list[float], runs: int, workers: int, **kw: Any) -> Any:
    from symhx.impact import ensemble

    if workers > 1:
        with ProcessPoolExecutor(workers) as ex:
            return ensemble(sigmas, runs, executor=ex, **kw)
    return ensemble(sigmas, runs, **kw)


def cmd_ensemble(args: argparse.Namespace) -> int:
    sigmas = PAPER_SIGMAS if args.paper else args.sigmas
    runs = PAPER_RUNS if args.paper else args.runs
    res = _run(sigmas, runs, args.workers, n=args.n, t_transient=args.t_transient,
               t_window=args.t_window, seed=args.seed, restitution=args.restitution,
               progress=not args.json)
    if args.json:
        print(json.dumps(res.as_dict(), indent=1))
    else:
        print(" sigma  excl  mean_pipes   se    mode  mean_sites  mode_sites")
        for s in res.per_sigma:
            p, q = s.stats["pipes"], s.stats["sites"]
            print(f"{s.sigma:6.3f} {s.excluded:5d}  {p['mean']:9.3f} {p['se']:6.3f} "
                  f"{p['mode']!s:>5}  {q['mean']:9.3f}  {q['mode']!s:>5}")
    return 0


def paper(out: Path, full: bool) -> list[str]:
    """Simulation part of ``symhx paper``: ensemble JSON/CSV and figures 7 and 8.

    ``full=False``: 6 sigmas x 20 runs of 100 pipes (seconds); ``full=True``: the paper's
    24 sigmas x 1000 runs (a few minutes on 2 cores).
    """
    from symhx import plots

    t0 = time.perf_counter()
    sigmas = PAPER_SIGMAS if full else QUICK_SIGMAS
    runs = PAPER_RUNS if full else QUICK_RUNS
    res = _run(sigmas, runs, os.cpu_count() or 1, n=100, progress=False, seed=0)
    out.mkdir(parents=True, exist_ok=True)
    (out / "ensemble_fig7_8.json").write_text(json.dumps(res.as_dict(), indent=1) + "\n")
    with open(out / "ensemble_fig7_8.csv", "w", newline="") as fh:
        w = csv.writer(fh)
        w.writerow(["sigma", "runs", "excluded", "mean_pipes", "se_pipes", "mode_pipes",
                    "mode_se_pipes", "mean_sites", "se_sites", "mode_sites", "mode_se_sites"])
        for s in res.per_sigma:
            p, q = s.stats["pipes"], s.stats["sites"]
            w.writerow([s.sigma, s.runs, s.excluded, p["mean"], p["se"], p["mode"], p["mode_se"],
                        q["mean"], q["se"], q["mode"], q["mode_se"]])
    plots.plot_mode_vs_sigma(res).savefig(out / "fig7_mode_vs_sigma.png", dpi=110,
                                          bbox_inches="tight")
    plots.plot_mean_vs_sigma(res).savefig(out / "fig8_mean_vs_sigma.png", dpi=110,
                                          bbox_inches="tight")
    dt = time.perf_counter() - t0
    modes = res.column("pipes", "mode")
    jump = ""
    if np.any(np.isfinite(modes)):
        k = int(np.nanargmax(np.diff(np.nan_to_num(modes)))) if len(modes) > 1 else 0
        jump = f"; largest jump of the mode between sigma={sigmas[k]} and {sigmas[k + 1]}"
    return [f"impact ensemble: {len(sigmas)} sigmas x {runs} runs of 100 pipes in {dt:.1f} s"
            f"{jump}", "figures 7, 8 -> fig7_mode_vs_sigma.png, fig8_mean_vs_sigma.png"]
