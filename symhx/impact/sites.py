"""Per-site impact statistics of simulated rows: walls against the interior, and by position.

The graph model with site classes (:mod:`symhx.forcing.sites`) gives the two wall sites of a row
their own impact probability. This module measures the simulated counterpart: in the counting
window of a run (``t_transient <= t <= t_transient + t_window``, as :func:`symhx.impact.ensemble`),
which sites saw at least one impact (kinds ``impact`` and ``stick``, as the ensemble counts).

* :class:`SiteRates` holds per-site totals (runs with an impact at site ``i = 0..n``, over the
  finished runs): the per-site rate and its binomial standard error, the rate by distance from
  the nearest wall (:meth:`SiteRates.by_position`), and the wall and interior rates. The stored
  ensembles (:class:`symhx.impact.EnsembleResult`) record exactly these totals
  (``SigmaStats.site_hits``): :meth:`SiteRates.from_stats`.
* :class:`SiteHitTable` adds the *joint* per-run record that the stored ensembles do not keep:
  ``joint[w, i]`` = runs in which ``w`` of the 2 wall sites and ``i`` of the ``n - 1`` interior
  sites saw an impact. From it the run-level statistics follow exactly: the distribution of the
  number of distinct impact sites ``X = w + i`` (the graph theory's ``X``), the wall and interior
  rates with standard errors from the runs' own variance and covariance, their ratio, and the
  bootstrap (runs resampled from the joint histogram, :meth:`SiteHitTable.resample`).
  :func:`site_hit_tables` simulates them; run ``k`` of ``sigma`` draws the row of
  ``symhx.impact.ensemble.run_seed``, the same row as :func:`symhx.impact.ensemble.ensemble`
  with the same seed, so the per-site totals and the histogram of ``X`` of a table equal those
  of the ensemble (tested; the stored file reproduces the stored ensemble's columns exactly).

>>> from symhx.impact import PipeRow, simulate
>>> row = PipeRow(1, restitution=1, alpha=[[0.0]], beta=[[0.0]], x0=[1.0], v0=[2.0])
>>> simulate(row, 10.0).impacts_per_site(5.0).tolist()      # 3 and 2 impacts at the walls
[3, 2]
>>> table = SiteHitTable.from_histories([simulate(row, 10.0)], t_from=5.0)
>>> table.site_hits.tolist(), table.joint.tolist()             # one run, both walls hit
([1, 1], [[0], [0], [1]])
"""

from __future__ import annotations

import json
import math
import os
from collections.abc import Sequence
from concurrent.futures import Executor, as_completed
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import numpy as np

from symhx.impact.engine import IMPACT, STICK
from symhx.impact.ensemble import (
    EnsembleResult,
    SigmaStats,
    check_sweep,
    run_seed,
    window_counts,
)
from symhx.impact.history import History
from symhx.impact.model import SQRT2, PipeRow, check_horizon, check_pipes
from symhx.validation import InputError, check_int, check_real, check_seed

__all__ = [
    "SiteHitResult",
    "SiteHitTable",
    "SiteRates",
    "hit_table_chunk",
    "site_hit_tables",
]


def _rate_se(hits: np.ndarray, trials: int) -> tuple[np.ndarray, np.ndarray]:
    q = hits / trials
    return q, np.sqrt(q * (1 - q) / trials)


@dataclass(frozen=True, eq=False)
class SiteRates:
    """Per-site impact rates of one ``sigma``: the fraction of finished runs with at least one
    impact at each site ``0..n`` in the counting window (site ``i`` is the gap between pipes
    ``i`` and ``i + 1``; sites ``0`` and ``n`` are the walls).

    Attributes
    ----------
    sigma : float
        The forcing.
    runs : int
        Finished runs (the denominator; runs without impact included).
    site_hits : ndarray of int
        Runs with an impact at each site ``0..n``.

    Examples
    --------
    >>> r = SiteRates(0.2, 10, np.array([2, 6, 8, 6, 3]))
    >>> r.rate.tolist()
    [0.2, 0.6, 0.8, 0.6, 0.3]
    >>> pos, rate, se = r.by_position()
    >>> pos.tolist(), rate.tolist()
    ([0, 1, 2], [0.25, 0.6, 0.8])
    """

    sigma: float
    runs: int
    site_hits: np.ndarray

    def __post_init__(self) -> None:
        hits = np.asarray(self.site_hits, dtype=np.int64)
        if hits.ndim != 1 or hits.size < 2:
            raise InputError(f"site_hits must hold one count per site 0..n (n >= 1), got shape "
                             f"{hits.shape}")
        runs = check_int(self.runs, "runs", minimum=1)
        if hits.min() < 0 or hits.max() > runs:
            raise InputError(f"site_hits must lie in [0, runs = {runs}], got "
                             f"{int(hits.min())}..{int(hits.max())}")
        object.__setattr__(self, "site_hits", hits)
        object.__setattr__(self, "runs", runs)

    @property
    def n(self) -> int:
        """Pipes of the row (``n + 1`` sites)."""
        return len(self.site_hits) - 1

    @property
    def rate(self) -> np.ndarray:
        """Fraction of runs with an impact at each site."""
        return self.site_hits / self.runs

    @property
    def se(self) -> np.ndarray:
        """Binomial standard error of each site's rate (the runs are independent)."""
        return _rate_se(self.site_hits, self.runs)[1]

    def by_position(self) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """``(distance, rate, se)``: sites pooled by their distance ``min(i, n - i)`` from the
        nearer wall site (``0``: the walls), the rate of a pool being the mean of its sites'
        rates. The standard error treats the (at most two, far apart) sites of a pool as
        independent.

        >>> SiteRates(0.1, 4, np.array([1, 2, 1])).by_position()[1].tolist()
        [0.25, 0.5]
        """
        i = np.arange(self.n + 1)
        dist = np.minimum(i, self.n - i)
        pos = np.arange(dist.max() + 1)
        rate = np.array([self.rate[dist == k].mean() for k in pos])
        var = np.array([np.sum(self.se[dist == k] ** 2) / np.sum(dist == k) ** 2 for k in pos])
        return pos, rate, np.sqrt(var)

    def wall_rate(self) -> float:
        """Mean rate of the two wall sites."""
        return float((self.site_hits[0] + self.site_hits[-1]) / (2 * self.runs))

    def interior_rate(self) -> float:
        """Mean rate of the ``n - 1`` pipe-pipe sites (NaN for a row of one pipe)."""
        if self.n < 2:
            return math.nan
        return float(self.site_hits[1:-1].sum() / ((self.n - 1) * self.runs))

    @classmethod
    def from_stats(cls, stats: SigmaStats) -> SiteRates:
        """The rates of one ``sigma`` of an ensemble (``SigmaStats.site_hits`` over its finished
        runs)."""
        if not isinstance(stats, SigmaStats):
            raise TypeError(f"stats must be a SigmaStats (EnsembleResult.per_sigma), got "
                            f"{type(stats).__name__}")
        return cls(stats.sigma, stats.finished, stats.site_hits)


def _counts_of_history(h: History, t_from: float) -> np.ndarray:
    times = np.asarray(h.times, dtype=float)
    sel = np.isin(np.asarray(h.kinds), (IMPACT, STICK)) & (times >= t_from)
    return np.bincount(np.asarray(h.sites, dtype=np.int64)[sel], minlength=h.row.n + 1)


@dataclass(frozen=True, eq=False)
class SiteHitTable:
    """The joint per-run record of one ``sigma``: which kinds of site saw an impact.

    Attributes
    ----------
    sigma : float
        The forcing.
    joint : ndarray of int, shape ``(3, n)``
        ``joint[w, i]``: finished runs with an impact at ``w`` of the 2 wall sites and at ``i``
        of the ``n - 1`` interior (pipe-pipe) sites.
    site_hits : ndarray of int, shape ``(n + 1,)``
        Runs with an impact at each site ``0..n``.
    failed : int
        Runs whose simulation (or draw) failed; not in ``joint``.

    Examples
    --------
    >>> t = SiteHitTable(0.2, np.array([[3, 0, 0], [0, 1, 0], [0, 0, 1]]), np.array([2, 1, 2, 1]))
    >>> t.runs, t.sites_histogram().tolist(), round(t.wall_rate()[0], 12)
    (5, [3, 0, 1, 0, 1], 0.3)
    """

    sigma: float
    joint: np.ndarray
    site_hits: np.ndarray
    failed: int = 0
    failures: list[tuple[int, str]] = field(default_factory=list)

    def __post_init__(self) -> None:
        joint = np.asarray(self.joint, dtype=np.int64)
        hits = np.asarray(self.site_hits, dtype=np.int64)
        if joint.ndim != 2 or joint.shape[0] != 3 or joint.shape[1] < 1:
            raise InputError(f"joint must have shape (3, n) with n >= 1, got {joint.shape}")
        n = joint.shape[1]
        if hits.shape != (n + 1,):
            raise InputError(f"site_hits must have shape (n + 1,) = ({n + 1},) for joint of shape "
                             f"{joint.shape}, got {hits.shape}")
        if joint.min() < 0:
            raise InputError("joint must hold counts >= 0")
        object.__setattr__(self, "joint", joint)
        object.__setattr__(self, "site_hits", hits)

    # ---------------------------------------------------------------- the runs
    @property
    def n(self) -> int:
        """Pipes of the row."""
        return self.joint.shape[1]

    @property
    def runs(self) -> int:
        """Finished runs."""
        return int(self.joint.sum())

    @property
    def rates(self) -> SiteRates:
        """The per-site totals as :class:`SiteRates`."""
        return SiteRates(self.sigma, self.runs, self.site_hits)

    def sites_histogram(self) -> np.ndarray:
        """``h[x]``: runs with ``x = 0..n + 1`` distinct impact sites (``x = w + i``)."""
        h = np.zeros(self.n + 2, dtype=np.int64)
        for w in range(3):
            h[w: w + self.n] += self.joint[w]
        return h

    def _moments(self) -> tuple[float, float, float, float, float]:
        """Per-run means of ``w/2`` and ``i/(n - 1)``, their variances and covariance."""
        R = self.runs
        w = np.arange(3)[:, None] / 2.0
        i = np.arange(self.n)[None, :] / max(self.n - 1, 1)
        P = self.joint / R
        mw, mi = float((P * w).sum()), float((P * i).sum())
        vw = float((P * (w - mw) ** 2).sum())
        vi = float((P * (i - mi) ** 2).sum())
        cov = float((P * (w - mw) * (i - mi)).sum())
        return mw, mi, vw, vi, cov

    def wall_rate(self) -> tuple[float, float]:
        """``(rate, se)``: the mean rate of the two wall sites, and its standard error from the
        per-run variance (the two walls of a run need not be independent)."""
        self._need_runs()
        mw, _, vw, _, _ = self._moments()
        return mw, math.sqrt(vw / max(self.runs - 1, 1))

    def interior_rate(self) -> tuple[float, float]:
        """``(rate, se)``: the mean rate of the ``n - 1`` interior sites, the standard error from
        the per-run variance of the fraction hit (impacts spread: the sites of a run are strongly
        dependent, so a binomial error over all sites would be far too small)."""
        self._need_runs()
        if self.n < 2:
            return math.nan, math.nan
        _, mi, _, vi, _ = self._moments()
        return mi, math.sqrt(vi / max(self.runs - 1, 1))

    def rate_ratio(self) -> tuple[float, float]:
        """``(ratio, se)``: wall rate over interior rate, the error by the delta method with the
        per-run covariance (NaN where the interior rate is 0).

        >>> t = SiteHitTable(0.3, np.array([[1, 0, 0], [0, 2, 0], [0, 0, 1]]), np.zeros(4))
        >>> t.rate_ratio()[0]
        1.0
        """
        self._need_runs()
        mw, mi, vw, vi, cov = self._moments()
        if not mi > 0:
            return math.nan, math.nan
        r = mw / mi
        var = (vw / mi**2 + vi * mw**2 / mi**4 - 2 * cov * mw / mi**3) / max(self.runs - 1, 1)
        return r, math.sqrt(max(var, 0.0))

    def _need_runs(self) -> None:
        if self.runs == 0:
            raise InputError(f"no finished run at sigma = {self.sigma}: the rates are undefined")

    def resample(self, rng: np.random.Generator) -> SiteHitTable:
        """A bootstrap replicate: the runs drawn with replacement (multinomial over the joint
        histogram). The per-site totals are not resampled (they are not per run): the replicate
        keeps the original ``site_hits``.

        >>> t = SiteHitTable(0.2, np.array([[3, 0], [0, 1], [0, 1]]), np.array([2, 1, 1]))
        >>> t.resample(np.random.default_rng(0)).runs
        5
        """
        R = self.runs
        if R == 0:
            return self
        flat = rng.multinomial(R, (self.joint / R).ravel())
        return SiteHitTable(self.sigma, flat.reshape(self.joint.shape), self.site_hits,
                            self.failed, self.failures)

    # ---------------------------------------------------------------- construction
    @classmethod
    def from_counts(cls, sigma: float, counts: Sequence[Any], failed: int = 0,
                    failures: Sequence[tuple[int, str]] = ()) -> SiteHitTable:
        """The table of runs given by their impacts per site ``0..n`` (one array per run)."""
        rows = [np.asarray(c) for c in counts]
        if not rows:
            raise InputError("counts must hold at least one run")
        n = len(rows[0]) - 1
        if n < 1 or any(r.shape != (n + 1,) for r in rows):
            raise InputError(f"counts must hold one array of n + 1 >= 2 site counts per run, got "
                             f"shapes {sorted({r.shape for r in rows})}")
        joint = np.zeros((3, n), dtype=np.int64)
        hits = np.zeros(n + 1, dtype=np.int64)
        for c in rows:
            hit = c > 0
            hits += hit
            joint[int(hit[0]) + int(hit[-1]), int(hit[1:-1].sum())] += 1
        return cls(float(sigma), joint, hits, int(failed), list(failures))

    @classmethod
    def from_histories(cls, histories: Sequence[History], t_from: float = 0.0,
                       sigma: float = math.nan) -> SiteHitTable:
        """The table of simulated histories (:func:`symhx.impact.simulate`), counting impacts
        and sticks at ``t >= t_from`` (of rows of one length ``n``)."""
        if not histories or not all(isinstance(h, History) for h in histories):
            raise TypeError("histories must be a non-empty sequence of symhx.impact.History")
        t0 = float(check_real(t_from, "t_from", low=0))
        return cls.from_counts(sigma, [_counts_of_history(h, t0) for h in histories])

    def as_dict(self) -> dict[str, Any]:
        """JSON form: the non-zero cells of ``joint`` as ``[w, i, runs]``."""
        cells = [[int(w), int(i), int(self.joint[w, i])] for w, i in zip(*np.nonzero(self.joint),
                                                                         strict=True)]
        return {"sigma": self.sigma, "n": self.n, "joint": cells,
                "site_hits": self.site_hits.tolist(), "failed": self.failed,
                "failures": [list(f) for f in self.failures]}

    @classmethod
    def from_dict(cls, data: dict[str, Any]) -> SiteHitTable:
        """Inverse of :meth:`as_dict`."""
        n = int(data["n"])
        joint = np.zeros((3, n), dtype=np.int64)
        for w, i, c in data["joint"]:
            joint[w, i] = c
        return cls(float(data["sigma"]), joint, np.array(data["site_hits"], dtype=np.int64),
                   int(data.get("failed", 0)), [tuple(f) for f in data.get("failures", [])])


def hit_table_chunk(sigma: float, runs: Sequence[int], n: int, t_transient: float,
                    t_window: float, seed: int, restitution: float, omega: float, d: float,
                    Omega: tuple) -> dict[str, Any]:
    """Worker: the runs ``runs`` of one ``sigma`` (rows of ``run_seed``, float64 engine), as
    ``{"counts": hit vectors of the finished runs, "failures": [(run, reason)]}``; a run whose
    draw or simulation fails is recorded, never raised (as the ensemble does).

    >>> out = hit_table_chunk(0.05, [0, 1], 10, 10.0, 10.0, 1, 0.8, 1.0, 1.0, (SQRT2,))
    >>> [int(c.sum()) for c in out["counts"]], out["failures"]
    ([0, 0], [])
    """
    counts, failures = [], []
    for run in runs:
        try:
            try:
                row = PipeRow.random(n, sigma, seed=run_seed(seed, sigma, run),
                                     restitution=restitution, omega=omega, d=d, Omega=Omega)
            except ValueError as exc:
                raise RuntimeError(f"draw: {exc}") from exc
            c = window_counts(row, t_transient, t_window)
        except RuntimeError as exc:
            failures.append((int(run), f"{type(exc).__name__}: {exc}"[:300]))
            continue
        counts.append((np.asarray(c) > 0).astype(np.int8))
    return {"counts": counts, "failures": failures}


@dataclass
class SiteHitResult:
    """:func:`site_hit_tables`'s result: one :class:`SiteHitTable` per ``sigma``, the parameters.

    ``save``/``load`` write and read JSON.
    """

    params: dict[str, Any]
    tables: list[SiteHitTable]

    @property
    def sigmas(self) -> np.ndarray:
        """The forcings, in order."""
        return np.array([t.sigma for t in self.tables])

    def table(self, sigma: float) -> SiteHitTable:
        """The table of the given ``sigma`` (KeyError if absent)."""
        for t in self.tables:
            if t.sigma == float(sigma):
                return t
        raise KeyError(f"no table at sigma = {sigma!r}; the sigmas are {self.sigmas.tolist()}")

    def as_dict(self) -> dict[str, Any]:
        """JSON form."""
        return {"params": self.params, "tables": [t.as_dict() for t in self.tables]}

    def save(self, path: Any) -> None:
        """Write :meth:`as_dict` as JSON, atomically."""
        path = Path(path)
        tmp = path.with_name(path.name + ".tmp")
        tmp.write_text(json.dumps(self.as_dict(), separators=(",", ":")) + "\n")
        os.replace(tmp, path)

    @classmethod
    def load(cls, path: Any) -> SiteHitResult:
        """Read a file written by :meth:`save`."""
        data = json.loads(Path(path).read_text())
        return cls(data["params"], [SiteHitTable.from_dict(t) for t in data["tables"]])

    def matches(self, ensemble: EnsembleResult) -> bool:
        """True when this result is the same runs as ``ensemble``: for every common ``sigma``
        the per-site totals and the histogram of distinct impact sites (runs with an impact)
        agree exactly, with the same parameters."""
        keys = ("n", "t_transient", "t_window", "seed", "restitution", "omega", "d")
        if any(self.params[k] != ensemble.params[k] for k in keys):
            return False
        for st in ensemble.per_sigma:
            try:
                t = self.table(st.sigma)
            except KeyError:
                continue
            h = t.sites_histogram()
            h[0] = 0
            stored = np.array(st.stats["sites"]["hist"], dtype=np.int64)
            if (t.runs + t.failed != st.runs or not np.array_equal(t.site_hits, st.site_hits)
                    or not np.array_equal(h[: len(stored)], stored)):
                return False
        return True


def site_hit_tables(
    sigmas: Sequence[Any],
    runs: int,
    *,
    n: int = 100,
    t_transient: float = 200.0,
    t_window: float = 100.0,
    seed: int = 0,
    restitution: float = 0.8,
    omega: float = 1.0,
    d: float = 1.0,
    Omega: Sequence[Any] = (SQRT2,),
    executor: Executor | None = None,
    chunk: int = 50,
) -> SiteHitResult:
    """Simulate ``runs`` rows per ``sigma`` and record the joint per-run site hits.

    The rows are those of :func:`symhx.impact.ensemble.ensemble` with the same ``seed`` and
    parameters (initial-condition coefficients with ``sigma0 = sigma``), so the per-site totals
    and the histogram of ``X`` equal the ensemble's.

    Parameters
    ----------
    sigmas : sequence of float
        Forcings ``>= 0``.
    runs : int
        Runs per ``sigma`` (``<= MAX_RUNS``; ``len(sigmas) * runs <= MAX_TOTAL_RUNS``).
    n, t_transient, t_window, seed, restitution, omega, d, Omega
        As for :func:`symhx.impact.ensemble.ensemble`.
    executor : concurrent.futures.Executor or None
        Where the chunks run (``None``: serially).
    chunk : int
        Runs per task.

    Returns
    -------
    SiteHitResult

    Raises
    ------
    ValueError, TypeError
        Naming the argument, for bad input or work beyond the caps.

    Examples
    --------
    >>> res = site_hit_tables([0.3], 3, n=6, t_transient=10, t_window=10, seed=1)
    >>> t = res.table(0.3)
    >>> t.runs, int(t.sites_histogram().sum())
    (3, 3)
    """
    sig, runs = check_sweep(sigmas, runs)
    n = check_pipes(n)
    seed_i = check_seed(seed)
    if seed_i is None:
        raise TypeError("seed must be an int >= 0 (the rows need a fixed seed), got None")
    om = float(check_real(omega, "omega", low=0, low_open=True))
    t_tr = float(check_horizon(t_transient, "t_transient", om, allow_zero=True))
    t_w = float(check_horizon(t_window, "t_window", om))
    r = float(check_real(restitution, "restitution", low=0, high=1))
    dd = float(check_real(d, "d", low=0, low_open=True))
    chunk = check_int(chunk, "chunk", minimum=1)
    if executor is not None and not isinstance(executor, Executor):
        raise TypeError(f"executor must be a concurrent.futures.Executor or None, got "
                        f"{type(executor).__name__}")
    Om = tuple(Omega) if isinstance(Omega, (Sequence, np.ndarray)) else (Omega,)
    # the model parameters are checked once here: a ValueError in a run is a failed draw
    PipeRow(1, restitution=r, omega=om, d=dd, Omega=Om, alpha=[[0.0] * len(Om)],
            beta=[[0.0] * len(Om)], x0=[dd], v0=[0.0])
    tasks = [(i, list(range(c, min(c + chunk, runs)))) for i in range(len(sig))
             for c in range(0, runs, chunk)]
    args = (n, t_tr, t_w, seed_i, r, om, dd, Om)
    done: dict[int, list[dict[str, Any]]] = {i: [] for i in range(len(sig))}
    if executor is None:
        for i, rr in tasks:
            done[i].append(hit_table_chunk(sig[i], rr, *args))
    else:
        futs = {executor.submit(hit_table_chunk, sig[i], rr, *args): i for i, rr in tasks}
        for f in as_completed(futs):
            done[futs[f]].append(f.result())
    tables = []
    for i, s in enumerate(sig):
        counts = [c for part in done[i] for c in part["counts"]]
        failures = sorted(f for part in done[i] for f in part["failures"])
        if counts:
            t = SiteHitTable.from_counts(s, counts, len(failures), failures[:20])
        else:
            t = SiteHitTable(s, np.zeros((3, n), dtype=np.int64), np.zeros(n + 1, np.int64),
                             len(failures), failures[:20])
        tables.append(t)
    params = {"runs": runs, "n": n, "t_transient": t_tr, "t_window": t_w, "seed": seed_i,
              "restitution": r, "omega": om, "d": dd, "Omega": [repr(w) for w in Om],
              "sigma0": "sigma"}
    return SiteHitResult(params, tables)
