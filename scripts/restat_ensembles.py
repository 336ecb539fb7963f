"""Recompute the per-sigma statistics of stored ensembles from their histograms.

The statistics of a column (mean, quantiles, mode, bootstrap intervals, the mode's bootstrap
probability) are a function of its two histograms and of ``(seed, sigma)`` alone
(:func:`symhx.impact.ensemble.column_stats`, the same call the ensemble makes), so a stored file
gains a statistic added to :func:`~symhx.impact.ensemble.describe_histogram` without simulating
again.  The histograms, counts and events are left as they are; ``--check`` only reports the
columns whose stored statistics differ (exit status 1 if any).

Usage::

    python scripts/restat_ensembles.py [--check] [FILE ...]

(default: every ``symhx/data/ensemble_*.json`` that holds ensembles: the production file and each
configuration of the calibration file).
"""

from __future__ import annotations

import argparse
import json
import sys
from pathlib import Path
from typing import Any

from symhx.impact.ensemble import column_stats

DATA = Path(__file__).resolve().parent.parent / "symhx" / "data"
FILES = ("ensemble_fig7_8.json", "ensemble_calibration.json")


def ensembles(data: dict[str, Any]) -> list[dict[str, Any]]:
    """The ensembles of a stored file: the file itself, or each entry of its ``configs``."""
    return list(data["configs"].values()) if "configs" in data else [data]


def restat(ens: dict[str, Any]) -> int:
    """Recompute the statistics of every column of ``ens`` in place; return how many changed."""
    seed = ens["params"]["seed"]
    changed = 0
    for col in ens["per_sigma"]:
        new = column_stats(col["pipes"]["hist"], col["sites"]["hist"], seed, col["sigma"])
        new = json.loads(json.dumps(new))     # as stored: lists, plain floats
        changed += new != {"pipes": col["pipes"], "sites": col["sites"]}
        col.update(new)
    return changed


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(description=__doc__,
                                 formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("files", nargs="*", type=Path, default=[DATA / f for f in FILES])
    ap.add_argument("--check", action="store_true", help="report, do not write")
    args = ap.parse_args(argv)
    bad = 0
    for path in args.files:
        text = path.read_text()
        data = json.loads(text)
        changed = sum(restat(e) for e in ensembles(data))
        bad += changed
        print(f"{path.name}: {changed} columns with other statistics", file=sys.stderr)
        if changed and not args.check:
            compact = not text.startswith("{\n")
            out = (json.dumps(data, separators=(",", ":")) if compact
                   else json.dumps(data, indent=1))
            path.write_text(out + "\n")
    return 1 if args.check and bad else 0


if __name__ == "__main__":
    sys.exit(main())
