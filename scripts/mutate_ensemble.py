"""Hand-made mutation test of symhx/impact/ensemble.py (issue 16).

Each mutant is a plausible one-line bug; the script applies it, runs the fast ensemble tests and
restores the file.  Usage: ``python scripts/mutate_ensemble.py [words of mutant names]``.
Do not run other symhx processes meanwhile: they would import a mutated module.
"""

from __future__ import annotations

import os
import subprocess
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
TARGET = ROOT / "symhx" / "impact" / "ensemble.py"
MUTANTS = [
    ("pipes from sites: | -> &",
     "return int((hit[:-1] | hit[1:]).sum()), int(hit.sum())",
     "return int((hit[:-1] & hit[1:]).sum()), int(hit.sum())"),
    ("pipes/sites swapped",
     "pipes[k], sites[k] = pipes_and_sites(counts)",
     "sites[k], pipes[k] = pipes_and_sites(counts)"),
    ("window from t=0",
     "counts, nev = count_impacts(row, t_transient + t_window, t_transient)",
     "counts, nev = count_impacts(row, t_transient + t_window, 0.0)"),
    ("window end = t_window",
     "counts, nev = count_impacts(row, t_transient + t_window, t_transient)",
     "counts, nev = count_impacts(row, t_window, t_transient)"),
    ("no-impact runs kept",
     "keep = ok & (sites > 0)",
     "keep = ok & (sites >= 0)"),
    ("se with k-1",
     "out.update(mean=mean, se=math.sqrt(var / k)",
     "out.update(mean=mean, se=math.sqrt(var / (k - 1))"),
    ("mode largest instead of smallest",
     "mode=int(np.argmax(h)))",
     "mode=int(len(h) - 1 - np.argmax(h[::-1])))"),
    ("seed without sigma",
     "return np.random.SeedSequence([int(seed), 0, sigma_key(sigma), int(run)])",
     "return np.random.SeedSequence([int(seed), 0, int(run)])"),
    ("site_hits counts impacts",
     "site_hits += hit",
     "site_hits += counts"),
    ("gap rate interior -> all",
     "h = self.site_hits[1:-1] if interior else self.site_hits",
     "h = self.site_hits"),
    ("failures: catch ValueError",
     "except RuntimeError as exc:   # SimulationError",
     "except ValueError as exc:   # SimulationError"),
    ("mean_ci 2.5/97.5 -> 25/75",
     "np.percentile(bmeans, [2.5, 97.5])",
     "np.percentile(bmeans, [25, 75])"),
    ("excluded counts failed too",
     "excluded=int((ok & (sites == 0)).sum())",
     "excluded=int((sites <= 0).sum())"),
    ("same-site pairs: shuffle ignored",
     "sa, sb = pairs([rng.permutation(s) for s in seqs])",
     "sa, sb = pairs(list(seqs))"),
]


def main() -> int:
    orig = TARGET.read_text()
    chosen = [m for m in MUTANTS if len(sys.argv) < 2 or any(w in m[0] for w in sys.argv[1:])]
    survived = 0
    for name, a, b in chosen:
        assert orig.count(a) == 1, name
        TARGET.write_text(orig.replace(a, b))
        try:
            r = subprocess.run(
                [sys.executable, "-m", "pytest", "-q", "-x", "-p", "no:cacheprovider",
                 "tests/impact/test_ensemble.py", "tests/impact/test_ensemble_statistics.py", "-k",
                 "not dask and not executors and not free_flight"],
                cwd=ROOT, capture_output=True, text=True, timeout=900,
                env={**os.environ, "PYTHONPATH": str(ROOT)})
        finally:
            TARGET.write_text(orig)
        killed = r.returncode != 0
        survived += not killed
        print(f"{'KILLED' if killed else 'SURVIVED'}: {name}", flush=True)
    return int(survived > 0)


if __name__ == "__main__":
    sys.exit(main())
