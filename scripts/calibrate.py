"""Calibration of the simulated threshold (issue 15): how the sigma where the mode of the number
of impacting pipes leaves small values, and the sigma where their mean rises steepest, move with
restitution, transient, window and the initial-condition law.

Usage (about 10 minutes on one core; writes symhx/data/ensemble_calibration.json)::

    PYTHONPATH=. nice -n 19 python scripts/calibrate.py [--runs 300] [--workers 2]

Each configuration: 26 values of sigma (0.05..0.30, step 0.01) x ``--runs`` runs of 100 pipes.
Only per-sigma histograms are stored.  The thresholds and their bootstrap intervals are computed
from the histograms by :func:`thresholds` (also used by the book).
"""

from __future__ import annotations

import argparse
import json
import sys
import time
from concurrent.futures import ProcessPoolExecutor
from pathlib import Path

import numpy as np

from symhx.impact.ensemble import ensemble

SIGMAS = [round(0.05 + 0.01 * k, 2) for k in range(26)]
BASE = {"restitution": 0.8, "t_transient": 200.0, "t_window": 100.0, "sigma0": None}
#: (label, changes to BASE); sigma0 as a multiple of sigma is written "x<factor>"
CONFIGS = [
    ("base r=0.8 T=200 W=100 sigma0=sigma", {}),
    ("r=0.5", {"restitution": 0.5}),
    ("r=0.65", {"restitution": 0.65}),
    ("r=0.9", {"restitution": 0.9}),
    ("r=0.95", {"restitution": 0.95}),
    ("r=1", {"restitution": 1.0}),
    ("T=0", {"t_transient": 0.0}),
    ("T=50", {"t_transient": 50.0}),
    ("T=800", {"t_transient": 800.0}),
    ("W=20", {"t_window": 20.0}),
    ("W=400", {"t_window": 400.0}),
    ("sigma0=0", {"sigma0": "x0"}),
    ("sigma0=sigma/2", {"sigma0": "x0.5"}),
    ("sigma0=2 sigma", {"sigma0": "x2"}),
    ("sigma0=0.3 fixed", {"sigma0": 0.3}),
]
OUT = Path(__file__).resolve().parent.parent / "symhx" / "data" / "ensemble_calibration.json"


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__,
                                 formatter_class=argparse.ArgumentDefaultsHelpFormatter)
    ap.add_argument("--runs", type=int, default=300, help="runs per sigma and configuration")
    ap.add_argument("--workers", type=int, default=2, help="worker processes")
    ap.add_argument("--only", type=int, nargs="*", help="indices of CONFIGS to run")
    ap.add_argument("--out", type=Path, default=OUT, help="output JSON")
    args = ap.parse_args()
    data = json.loads(args.out.read_text()) if args.out.exists() else {"configs": {}}
    idx = args.only if args.only else range(len(CONFIGS))
    with ProcessPoolExecutor(args.workers) as ex:
        for k in idx:
            label, change = CONFIGS[k]
            cfg = {**BASE, **change}
            s0 = cfg.pop("sigma0")
            if isinstance(s0, str):
                s0 = [float(s0[1:]) * s for s in SIGMAS]
            t0 = time.time()
            res = ensemble(SIGMAS, args.runs, n=100, seed=0, executor=ex, progress=False,
                           sigma0=s0, keep_runs=False, **cfg)
            d = res.as_dict()
            d["label"] = label
            data["configs"][label] = d
            args.out.write_text(json.dumps(data, indent=0) + "\n")
            print(f"{label:40s} {time.time() - t0:7.1f} s", file=sys.stderr, flush=True)
    return 0


def thresholds(res_dict: dict, *, level: int = 10, boot: int = 400, seed: int = 0
               ) -> dict[str, list[float]]:
    """Simulated thresholds of one stored ensemble, with bootstrap 16-84 % intervals.

    ``mode``: the first sigma whose mode of impacting pipes is ``>= level``;
    ``steep``: the midpoint of the grid interval where the mean number of impacting pipes
    (runs without impact counted as 0 here, so that the mean is not conditioned on the
    exclusion) rises most.  Each as ``[estimate, low, high]``.
    """
    per = res_dict["per_sigma"]
    sig = np.array([s["sigma"] for s in per])
    hists = []
    for s in per:
        h = np.array(s["pipes"]["hist"], dtype=float)
        h[0] += s["excluded"]          # runs without impact: 0 pipes
        hists.append(h)
    rng = np.random.default_rng(seed)

    def est(hs: list[np.ndarray]) -> tuple[float, float]:
        modes = np.array([np.argmax(h[1:]) + 1 if h[1:].sum() else 0 for h in hs])
        means = np.array([(h * np.arange(len(h))).sum() / h.sum() for h in hs])
        above = np.nonzero(modes >= level)[0]
        m = sig[above[0]] if len(above) else np.nan
        k = int(np.argmax(np.diff(means)))
        return float(m), float((sig[k] + sig[k + 1]) / 2)

    m0, s0 = est(hists)
    bm, bs = [], []
    for _ in range(boot):
        hb = [rng.multinomial(int(h.sum()), h / h.sum()).astype(float) for h in hists]
        a, b = est(hb)
        bm.append(a)
        bs.append(b)
    q = lambda x: [float(v) for v in np.nanpercentile(x, [16, 84])]  # noqa: E731
    return {"mode": [m0, *q(bm)], "steep": [s0, *q(bs)]}


if __name__ == "__main__":
    sys.exit(main())
