"""Per-run site hits of the production ensemble (issue 30): which of the 2 wall sites and how many
of the 99 interior sites saw an impact in each run's window, for every sigma of the stored
ensemble ``symhx/data/ensemble_fig7_8.json``.

The stored ensemble keeps per-site totals and the histogram of distinct impact sites, not the
joint per-run record that the wall/interior rate ratio and its bootstrap need; this script
simulates the same rows again (run ``k`` of ``sigma`` is drawn from ``run_seed(0, sigma, k)``) with
:func:`symhx.impact.sites.site_hit_tables` and checks that the per-site totals and the histogram
equal the stored ones exactly before writing.

Usage (about 40 minutes of CPU; writes symhx/data/ensemble_sites.json)::

    PYTHONPATH=. nice -n 19 python scripts/site_rates.py [--runs 10000] [--workers 2]
"""

from __future__ import annotations

import argparse
import json
import sys
import time
from concurrent.futures import ProcessPoolExecutor
from importlib import resources
from pathlib import Path

from symhx.impact import EnsembleResult
from symhx.impact.sites import SiteHitResult, site_hit_tables

OUT = Path(__file__).resolve().parent.parent / "symhx" / "data" / "ensemble_sites.json"


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__,
                                 formatter_class=argparse.ArgumentDefaultsHelpFormatter)
    ap.add_argument("--runs", type=int, default=10_000, help="runs per sigma")
    ap.add_argument("--workers", type=int, default=2, help="worker processes")
    ap.add_argument("--out", type=Path, default=OUT, help="output JSON")
    args = ap.parse_args()
    stored = EnsembleResult.from_dict(json.loads(
        resources.files("symhx.data").joinpath("ensemble_fig7_8.json").read_text()))
    P = stored.params
    tables = []
    with ProcessPoolExecutor(args.workers) as ex:
        for sigma in stored.sigmas:   # one sigma at a time: progress is written as it goes
            t0 = time.time()
            part = site_hit_tables([float(sigma)], args.runs, n=P["n"],
                                   t_transient=P["t_transient"], t_window=P["t_window"],
                                   seed=P["seed"], restitution=P["restitution"],
                                   omega=P["omega"], d=P["d"], executor=ex, chunk=100)
            tables += part.tables
            res = SiteHitResult(part.params, tables)
            if args.runs == P["runs"] and not res.matches(stored):
                print(f"sigma {sigma}: the per-site totals differ from the stored ensemble",
                      file=sys.stderr)
                return 1
            res.save(args.out)
            print(f"sigma {sigma:g}: {time.time() - t0:.1f} s", file=sys.stderr, flush=True)
    return 0


if __name__ == "__main__":
    sys.exit(main())
