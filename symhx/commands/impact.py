"""``symhx simulate`` / ``symhx ensemble`` and the simulation part of ``symhx paper``
(figures 7, 8, 10 and 13 with the simulation).

The stored ensemble ``symhx/data/ensemble_fig7_8.json`` (per-sigma histograms only) is produced
by one command::

    symhx ensemble --paper --workers 2 --out symhx/data/ensemble_fig7_8.json

(``--paper``: :data:`PAPER_SIGMAS` x :data:`PAPER_RUNS` runs of 100 pipes; partial results are
written to ``--out`` every minute, so an interrupted run leaves an honest smaller ensemble).  On
several machines start a ``dask`` scheduler and workers (``dask scheduler``;
``dask worker tcp://host:8786`` on each machine, all with symhx installed) and add
``--scheduler tcp://host:8786``: the numbers are the same bit for bit.
"""

from __future__ import annotations

import argparse
import csv
import json
import math
import os
import sys
import time
from collections.abc import Iterator
from concurrent.futures import Executor, ProcessPoolExecutor
from contextlib import contextmanager
from pathlib import Path
from typing import Any

import numpy as np

from symhx.commands._common import dump_json
from symhx.validation import InputError

ORDER = 50

#: the stored ensemble of figures 7 and 8: 26 values of sigma in [0.05, 0.4], denser near the
#: jump (0.13..0.19), 10^4 runs of 100 pipes each
PAPER_SIGMAS = [0.05, 0.07, 0.09, 0.10, 0.11, 0.12, 0.13, 0.135, 0.14, 0.145, 0.15, 0.155, 0.16,
                0.165, 0.17, 0.175, 0.18, 0.19, 0.20, 0.22, 0.24, 0.27, 0.30, 0.33, 0.36, 0.40]
PAPER_RUNS = 10_000
#: ``symhx paper --full`` recomputes the paper grid with this many runs per sigma (minutes)
FULL_RUNS = 1000
QUICK_SIGMAS = [0.10, 0.14, 0.18, 0.22, 0.26, 0.30]
QUICK_RUNS = 20
DATA_FILE = Path(__file__).resolve().parent.parent / "data" / "ensemble_fig7_8.json"

def _add_pipes(p: argparse.ArgumentParser, default: int) -> None:
    p.add_argument("--pipes", type=int, default=default,
                   help="number of pipes n in the row (N = n + 1 possible impacts)")
    p.add_argument("--n", dest="pipes", type=int, help=argparse.SUPPRESS)  # deprecated alias


def register(sub: Any) -> None:
    p = sub.add_parser("simulate", help="simulate one random pipe row (section 7)",
                       description="Simulate one random row of pipes (eqs. 17-21) drawn as in "
                       "section 7 and print its events.")
    _add_pipes(p, 10)
    p.add_argument("--sigma", type=float, default=0.3,
                   help="standard deviation of the forcing and initial-condition coefficients")
    p.add_argument("--seed", type=int, default=0, help="seed of the random row")
    p.add_argument("--restitution", type=float, default=0.8, help="coefficient of restitution r")
    p.add_argument("--t-end", type=float, default=20.0, help="simulate over [0, t_end]")
    p.add_argument("--dps", type=int, default=None,
                   help="run the mpmath reference engine at this precision (default: float64)")
    p.add_argument("--json", action="store_true", help="print JSON instead of a table")
    p.set_defaults(func=cmd_simulate)

    e = sub.add_parser(
        "ensemble", help="statistics of impacting pipes against sigma (figs. 7, 8)",
        description="Ensemble of random pipe rows: per sigma, the numbers of impacting pipes and "
        "of distinct impact sites in the window [t_transient, t_transient + t_window] (runs "
        "without impact excluded and counted; failed runs counted with their reason).")
    e.add_argument("--sigmas", type=float, nargs="+", default=QUICK_SIGMAS,
                   help="values of sigma (forcing standard deviation)")
    e.add_argument("--runs", type=int, default=QUICK_RUNS, help="runs per sigma")
    _add_pipes(e, 100)
    e.add_argument("--t-transient", type=float, default=200.0,
                   help="impacts before this time are not counted")
    e.add_argument("--t-window", type=float, default=100.0, help="length of the counting window")
    e.add_argument("--restitution", type=float, default=0.8, help="coefficient of restitution r")
    e.add_argument("--sigma0", type=float, default=None,
                   help="standard deviation of the initial-condition (free-oscillation) "
                   "coefficients; None: the same as sigma")
    e.add_argument("--seed", type=int, default=0, help="ensemble seed")
    e.add_argument("--chunk", type=int, default=50, help="runs per task")
    e.add_argument("--workers", type=int, default=os.cpu_count() or 1,
                   help="local worker processes (1: serial)")
    e.add_argument("--scheduler", default=None, metavar="ADDRESS",
                   help="dask.distributed scheduler address, e.g. tcp://host:8786 (overrides "
                   "--workers); None: run on this machine")
    e.add_argument("--paper", action="store_true",
                   help=f"the stored ensemble: {len(PAPER_SIGMAS)} sigmas in "
                   f"[{PAPER_SIGMAS[0]}, {PAPER_SIGMAS[-1]}] x {PAPER_RUNS} runs")
    e.add_argument("--out", type=Path, default=None,
                   help="write the result JSON here (partial results every minute)")
    e.add_argument("--json", action="store_true", help="print JSON instead of a table")
    e.set_defaults(func=cmd_ensemble)


def cmd_simulate(args: argparse.Namespace) -> int:
    from symhx.impact import KIND_NAMES, PipeRow, simulate

    row = PipeRow.random(args.pipes, args.sigma, seed=args.seed, restitution=args.restitution)
    try:
        h = simulate(row, args.t_end, dps=args.dps)
    except RuntimeError as exc:
        print(f"symhx simulate: simulation failed: {exc}", file=sys.stderr)
        return 1
    events = [{"t": t, "site": int(s), "kind": KIND_NAMES[k], "u_before": u0, "u_after": u1}
              for t, s, k, u0, u1 in zip(h.times, h.sites, h.kinds, h.u_before, h.u_after,
                                         strict=True)]
    if args.json:
        print(dump_json({"pipes": args.pipes, "sigma": args.sigma, "seed": args.seed,
                         "restitution": args.restitution, "t_end": args.t_end, "dps": args.dps,
                         "events": events}))
        return 0
    print(f"# {args.pipes} pipes, sigma = {args.sigma}, seed = {args.seed}, "
          f"r = {args.restitution}, t in [0, {args.t_end}], "
          f"{'float64' if args.dps is None else f'mpmath dps = {args.dps}'}")
    print(f"{'time t':>16}  {'site':>4}  {'kind':<8}  {'rel. velocity before':>20}  "
          f"{'after':>13}")
    for ev in events:
        print(f"{float(ev['t']):16.9f}  {ev['site']:4d}  {ev['kind']:<8}  "
              f"{float(ev['u_before']): 20.6e}  {float(ev['u_after']): 13.6e}")
    print(f"{len(events)} events (site i = gap between pipe i and i + 1; 0 and n: the walls)")
    return 0


@contextmanager
def executor_for(workers: int, scheduler: str | None = None) -> Iterator[Executor | None]:
    """The executor behind ``--workers``/``--scheduler``: a ``dask.distributed`` client's
    executor for a scheduler address, a process pool for ``workers > 1``, else ``None``."""
    if scheduler:
        import distributed

        with distributed.Client(scheduler) as client:
            yield client.get_executor()
    elif workers > 1:
        with ProcessPoolExecutor(workers) as ex:
            yield ex
    else:
        yield None


def cmd_ensemble(args: argparse.Namespace) -> int:
    from symhx.impact import ensemble

    if args.workers < 1:
        raise InputError(f"--workers must be >= 1, got {args.workers}")
    sigmas = PAPER_SIGMAS if args.paper else args.sigmas
    runs = PAPER_RUNS if args.paper else args.runs
    with executor_for(args.workers, args.scheduler) as ex:
        res = ensemble(sigmas, runs, n=args.pipes, t_transient=args.t_transient,
                       t_window=args.t_window, seed=args.seed, restitution=args.restitution,
                       sigma0=args.sigma0, chunk=args.chunk, executor=ex, progress=None,
                       checkpoint=args.out, keep_runs=False)
    if args.json:
        print(json.dumps(res.as_dict(), indent=1))
        return 0
    print(f"# {runs} runs/sigma of {args.pipes} pipes, r = {args.restitution}, window "
          f"[{args.t_transient:g}, {args.t_transient + args.t_window:g}], {res.seconds:.1f} s "
          f"({len(sigmas) * runs / max(res.seconds, 1e-9):.0f} runs/s)")
    print(f"{'sigma':>6} {'no-imp':>6} {'failed':>6} {'mean pipes':>10} {'95% CI':>15} "
          f"{'mode':>4} {'95% CI':>9} {'P(mode)':>7} {'mean sites':>10} {'gap rate':>9}")
    for s in res.per_sigma:
        p, q = s.stats["pipes"], s.stats["sites"]
        rate = s.gap_rate()[0]
        rate_s = f"{rate:9.5f}" if math.isfinite(rate) else f"{'-':>9}"
        if p["mean"] is None:   # no run with an impact in the window (or every run failed)
            print(f"{s.sigma:6.3f} {s.excluded:6d} {s.failed:6d} {'no runs with an impact':>55}"
                  f" {rate_s}")
            continue
        lo, hi = p["mean_ci"]
        mlo, mhi = p["mode_ci"]
        print(f"{s.sigma:6.3f} {s.excluded:6d} {s.failed:6d} {p['mean']:10.3f} "
              f"[{lo:6.2f},{hi:6.2f}] {p['mode']!s:>4} [{mlo!s:>3},{mhi!s:>3}] "
              f"{p['mode_prob']:7.2f} {q['mean']:10.3f} {rate_s}")
    if args.out:
        print(f"written to {args.out}")
    return 0


def paper(out: Path, full: bool) -> list[str]:
    """Simulation part of ``symhx paper``: ensemble JSON/CSV and figures 7, 8, 10 and 13.

    ``full=False``: the figures are drawn from the stored ensemble
    (``symhx/data/ensemble_fig7_8.json``, regenerated by ``symhx ensemble --paper``), and a quick
    fresh ensemble (6 sigmas x 20 runs, seconds) is written to ``ensemble_quick.{json,csv}`` as a
    smoke check.  ``full=True``: the paper grid is recomputed with :data:`FULL_RUNS` runs per
    sigma (minutes on 2 cores, tqdm progress on a terminal) and the figures are drawn from it.
    """
    from symhx.plots.paper import save_paper_figure, stored_ensemble

    t0 = time.perf_counter()
    sigmas = PAPER_SIGMAS if full else QUICK_SIGMAS
    runs = FULL_RUNS if full else QUICK_RUNS
    with executor_for(os.cpu_count() or 1) as ex:
        from symhx.impact import ensemble

        res = ensemble(sigmas, runs, n=100, progress=None if full else False, seed=0,
                       executor=ex, keep_runs=False)
    out.mkdir(parents=True, exist_ok=True)
    stem = "ensemble_fig7_8" if full else "ensemble_quick"
    res.save(out / f"{stem}.json")
    with open(out / f"{stem}.csv", "w", newline="") as fh:
        w = csv.writer(fh)
        w.writerow(["sigma", "runs", "excluded", "failed", "mean_pipes", "se_pipes",
                    "mean_pipes_ci_lo", "mean_pipes_ci_hi", "mode_pipes", "mode_pipes_ci_lo",
                    "mode_pipes_ci_hi", "mode_pipes_prob", "mean_sites", "se_sites",
                    "mode_sites", "gap_rate"])
        for s in res.per_sigma:
            p, q = s.stats["pipes"], s.stats["sites"]
            w.writerow([s.sigma, s.runs, s.excluded, s.failed, p["mean"], p["se"],
                        *p["mean_ci"], p["mode"], *p["mode_ci"], p["mode_prob"], q["mean"],
                        q["se"], q["mode"], s.gap_rate()[0]])
    figs = res if full else stored_ensemble()
    names = {7: "fig7_mode_vs_sigma.png", 8: "fig8_mean_vs_sigma.png",
             10: "fig10_theory_vs_simulation.png", 13: "fig13_spaces_vs_simulation.png"}
    for number, name in names.items():
        save_paper_figure(number, out / name, ensemble=figs)
    dt = time.perf_counter() - t0
    # the threshold from a stable statistic: where the mean rises steepest (the mode of a
    # bimodal histogram near the jump is a near-tie, see the book)
    means = figs.column("pipes", "mean")
    jump = ""
    if len(means) > 1 and np.sum(np.isfinite(np.diff(means))) > 0:
        k = int(np.nanargmax(np.diff(means) / np.diff(figs.sigmas)))
        jump = (f"; the mean number of impacting pipes rises steepest between sigma = "
                f"{figs.sigmas[k]:g} and {figs.sigmas[k + 1]:g}")
    source = ("this run" if full else
              f"the stored ensemble, {len(figs.per_sigma)} sigmas x "
              f"{figs.per_sigma[0].runs} runs; rerun with --full")
    return [f"impact ensemble: {len(sigmas)} sigmas x {runs} runs of 100 pipes in {dt:.1f} s"
            f"{jump}",
            f"figures 7, 8, 10, 13 (from {source}) -> " + ", ".join(names.values())]
