"""Section 4's independence assumption tested on the simulation (issue 15 (ii)).

For each sigma, ``--runs`` rows (drawn as in ``symhx ensemble``, from
:func:`symhx.impact.ensemble.run_seed`) are simulated with full event histories; the sequence of
impact sites in the window is tested against independence of successive sites with
:func:`symhx.impact.ensemble.transition_dependence` (mutual information of (last, next) against
within-run shuffles; fractions of repeats and of neighbouring sites).

Usage (a few minutes on one core; writes symhx/data/ensemble_assumptions.json)::

    PYTHONPATH=. nice -n 19 python scripts/assumptions.py [--runs 60] [--restitution 0.8]
"""

from __future__ import annotations

import argparse
import json
import sys
import time
from pathlib import Path

import numpy as np

from symhx.impact.ensemble import sigma_key, site_transitions, transition_dependence

OUT = Path(__file__).resolve().parent.parent / "symhx" / "data" / "ensemble_assumptions.json"


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__,
                                 formatter_class=argparse.ArgumentDefaultsHelpFormatter)
    ap.add_argument("--sigmas", type=float, nargs="+", default=[0.15, 0.17, 0.2, 0.25, 0.35],
                    help="values of sigma")
    ap.add_argument("--runs", type=int, default=60, help="runs per sigma")
    ap.add_argument("--pipes", type=int, default=100, help="pipes per row")
    ap.add_argument("--restitution", type=float, default=0.8, help="restitution r")
    ap.add_argument("--t-transient", type=float, default=200.0, help="transient")
    ap.add_argument("--t-window", type=float, default=100.0, help="window length")
    ap.add_argument("--seed", type=int, default=0, help="ensemble seed")
    ap.add_argument("--shuffles", type=int, default=100, help="shuffles of the null")
    ap.add_argument("--out", type=Path, default=OUT, help="output JSON")
    args = ap.parse_args()
    result = {"params": {k: v for k, v in vars(args).items() if k != "out"}, "per_sigma": []}
    for s in args.sigmas:
        t0 = time.time()
        seqs = site_transitions(s, args.runs, n=args.pipes, t_transient=args.t_transient,
                                t_window=args.t_window, seed=args.seed,
                                restitution=args.restitution)
        # the null's shuffles are seeded by sigma too: one row of the table is recomputed alone
        dep = transition_dependence(seqs, args.pipes + 1, shuffles=args.shuffles,
                                    seed=sigma_key(s))
        lens = [len(q) for q in seqs]
        dep.update(sigma=s, runs=args.runs, runs_with_pairs=int(sum(n > 1 for n in lens)),
                   median_impacts=float(np.median(lens)))
        result["per_sigma"].append(dep)
        args.out.write_text(json.dumps(result, indent=1) + "\n")
        print(f"sigma {s}: {time.time() - t0:.1f} s  {dep}", file=sys.stderr, flush=True)
    return 0


if __name__ == "__main__":
    sys.exit(main())
