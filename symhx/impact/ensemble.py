"""Ensembles of random pipe rows: the statistics of figures 7 and 8 (section 7 of the paper).

For each ``sigma`` every run draws a row with :meth:`PipeRow.random` (eqs. 17, 18, 20), simulates it
with the float64 engine to ``t_transient + t_window`` and counts, in the window
``t >= t_transient``, the impacts per site (gap) ``0..n`` (the paper's ``N = n + 1`` vertices).
From them:

* ``sites``: the number of distinct sites with at least one impact (the graph theory's ``X``);
* ``pipes``: the number of pipes ``1..n`` touching such a site (figures 7 and 8 of the paper count
  impacting pipes; a wall impact involves one pipe, a pipe-pipe impact two);
* ``site_hits[i]``: in how many runs site ``i`` saw an impact (the measured per-gap impact rate,
  to compare with eq. 27).

Runs without any impact in the window are excluded from the ``pipes``/``sites`` statistics, as in
the paper, and counted (``excluded``).  A run whose simulation raises ``RuntimeError`` (the
engines' ``SimulationError``) is recorded as *failed* with its reason and counted (``failed``); it
never aborts the ensemble.

The stored form is compact: per ``sigma`` the histograms of ``pipes`` and ``sites``, the site hit
counts and the failures (:meth:`EnsembleResult.as_dict`); every statistic (mean, standard error,
quantiles, mode and its bootstrap probability of being the mode, bootstrap percentile intervals)
is computed from the histograms.

Reproducibility: run ``k`` at forcing ``sigma`` draws its row from :func:`run_seed`, that is
``numpy.random.SeedSequence([seed, 0, key, k])`` with ``key`` the IEEE-754 bit pattern of
``float(sigma)``.  The rows of one ``sigma`` therefore depend neither on the other values of the
grid nor on its position in it (``ensemble([0.16], ...)`` repeats the ``sigma = 0.16`` rows of
any grid), nor on the executor, the chunking or the order of completion.  Any
``concurrent.futures.Executor`` works (``ProcessPoolExecutor``, a ``dask.distributed`` client's
``client.get_executor()``); ``executor=None`` runs serially.
"""

from __future__ import annotations

import itertools
import json
import math
import os
import struct
import sys
import time
from collections.abc import Callable, Sequence
from concurrent.futures import Executor, as_completed
from dataclasses import dataclass, field
from fractions import Fraction
from pathlib import Path
from typing import Any

import numpy as np

from symhx.impact.engine import IMPACT, STICK
from symhx.impact.fast import count_impacts
from symhx.impact.model import SQRT2, PipeRow, check_horizon, check_pipes
from symhx.validation import InputError, check_int, check_real, check_seed, short_value


def _float(x: Any, name: str) -> float:
    """float64 value of an exact number, refusing what float64 cannot hold."""
    try:
        f = float(x)
    except OverflowError:
        f = math.inf
    if not math.isfinite(f):
        raise InputError(f"{name} = {short_value(Fraction(x))} is beyond the float64 range")
    return f

__all__ = [
    "BOOTSTRAP",
    "MAX_GAPS",
    "MAX_RUNS",
    "MAX_TOTAL_RUNS",
    "QUANTILE_LEVELS",
    "EnsembleResult",
    "SigmaStats",
    "column_stats",
    "describe_histogram",
    "ensemble",
    "free_flight_closure_fraction",
    "pipes_and_sites",
    "run_chunk",
    "run_seed",
    "sigma_key",
    "site_transitions",
    "thresholds",
    "transition_dependence",
    "window_counts",
]

#: bootstrap resamples (multinomial, from the histogram) behind every interval
BOOTSTRAP = 2000
#: documented work cap: more than this many ``runs`` per sigma are refused (10^5 runs of 100
#: pipes take about a core-hour; the statistics' errors shrink like ``1/sqrt(runs)``); split the
#: work over seeds or raise the cap deliberately.
MAX_RUNS = 10**5
#: documented work cap: ``len(sigmas) * runs`` above this is refused (10^8 runs of 100 pipes take
#: about a core-week).
MAX_TOTAL_RUNS = 10**8
#: documented work cap of :func:`free_flight_closure_fraction`: at most this many gaps
#: (50-90 microseconds each, so about 1-2 s; the binomial standard error is then <= 0.0036).
MAX_GAPS = 20_000


# --------------------------------------------------------------------------- one run
def sigma_key(sigma: float) -> int:
    """The IEEE-754 bit pattern of ``float(sigma)`` as an integer ``0 <= key < 2**64``
    (``-0.0`` counts as ``0.0``): the part of a run's seed that names its forcing.

    >>> sigma_key(0.0), sigma_key(-0.0), hex(sigma_key(1.0))
    (0, 0, '0x3ff0000000000000')
    """
    return int(struct.unpack("<Q", struct.pack("<d", float(sigma) + 0.0))[0])


def run_seed(seed: int, sigma: float, run: int) -> np.random.SeedSequence:
    """The seed of run ``run`` at forcing ``sigma`` in an ensemble seeded with ``seed``:
    ``SeedSequence([seed, 0, sigma_key(sigma), run])``.

    Used by :func:`ensemble`, :func:`run_chunk` and :func:`site_transitions`, so that one value
    of ``sigma`` draws the same rows in any grid, on any executor.

    >>> run_seed(3, 0.25, 7).entropy == [3, 0, sigma_key(0.25), 7]
    True
    """
    return np.random.SeedSequence([int(seed), 0, sigma_key(sigma), int(run)])


def window_counts(row: PipeRow, t_transient: float, t_window: float) -> np.ndarray:
    """Impacts per site ``0..n`` of ``row`` with ``t_transient <= t <= t_transient + t_window``
    (float64 engine, :func:`symhx.impact.fast.count_impacts`).

    >>> row = PipeRow(1, restitution=1, alpha=[[0.0]], beta=[[0.0]], x0=[1.0], v0=[2.0])
    >>> window_counts(row, 5.0, 5.0).tolist()
    [3, 2]
    """
    counts, _ = count_impacts(row, float(t_transient) + float(t_window), float(t_transient))
    return counts


def pipes_and_sites(counts: Any) -> tuple[int, int]:
    """``(pipes, sites)`` from impacts per site ``0..n``: distinct sites with an impact, and pipes
    ``1..n`` touching one (pipe ``j`` touches sites ``j - 1`` and ``j``; the walls are not pipes).

    >>> pipes_and_sites([1, 0, 0, 4])    # wall impact of pipe 1, pipe 3 against the right wall
    (2, 2)
    >>> pipes_and_sites([0, 2, 5, 0])    # pipes 1-2 and 2-3 collide: 3 pipes, 2 sites
    (3, 2)
    """
    hit = np.asarray(counts) > 0
    return int((hit[:-1] | hit[1:]).sum()), int(hit.sum())


class _DrawError(RuntimeError):
    """A run whose random row could not be drawn (e.g. overlapping pipes with ``sigma0 = 0``)."""


def run_chunk(sigma: float, runs: Sequence[int], n: int, t_transient: float,
              t_window: float, seed: int, restitution: float, omega: float, d: float,
              Omega: tuple, sigma0: float | None = None) -> dict[str, Any]:
    """Worker: simulate the given runs of one ``sigma`` (rows drawn from :func:`run_seed`).

    Returns a dict of per-run arrays ``pipes``, ``sites``, ``impacts`` (impacts in the window;
    ``-1`` for a failed run), the sum ``site_hits`` over the runs of the hit indicator of each
    site, the total number of ``events`` and the ``failures`` as ``(run, reason)`` pairs.

    >>> out = run_chunk(0.05, [0, 1], 10, 10.0, 10.0, 1, 0.8, 1.0, 1.0, (SQRT2,))
    >>> out["pipes"].tolist(), out["sites"].tolist(), out["failures"]
    ([0, 0], [0, 0], [])
    """
    m = len(runs)
    pipes = np.zeros(m, dtype=np.int64)
    sites = np.zeros(m, dtype=np.int64)
    impacts = np.zeros(m, dtype=np.int64)
    site_hits = np.zeros(n + 1, dtype=np.int64)
    events = 0
    failures: list[tuple[int, str]] = []
    for k, run in enumerate(runs):
        ss = run_seed(seed, sigma, run)
        try:
            try:
                row = PipeRow.random(n, sigma, seed=ss, restitution=restitution, omega=omega,
                                     d=d, Omega=Omega, sigma0=sigma0)
            except ValueError as exc:   # the parameters were checked up front: a failed draw
                raise _DrawError(str(exc)) from exc
            counts, nev = count_impacts(row, t_transient + t_window, t_transient)
        except RuntimeError as exc:   # SimulationError and friends: record, never abort
            pipes[k] = sites[k] = impacts[k] = -1
            name = "draw" if isinstance(exc, _DrawError) else type(exc).__name__
            failures.append((int(run), f"{name}: {exc}"[:300]))
            continue
        hit = counts > 0
        site_hits += hit
        pipes[k], sites[k] = pipes_and_sites(counts)
        impacts[k] = int(counts.sum())
        events += int(nev)
    return {"pipes": pipes, "sites": sites, "impacts": impacts, "site_hits": site_hits,
            "events": events, "failures": failures}


# --------------------------------------------------------------------------- statistics
#: the quantile levels of :func:`describe_histogram`'s ``quantiles``
QUANTILE_LEVELS = (0.1, 0.25, 0.5, 0.75, 0.9)


def describe_histogram(hist: Any, rng: np.random.Generator | None = None,
                       boot: int = BOOTSTRAP) -> dict[str, Any]:
    """Mean, standard error, quantiles, mode and bootstrap statistics from a histogram
    (``hist[v]`` = number of runs with value ``v``).

    ``mean_ci``/``mode_ci``: 2.5 and 97.5 percentiles of ``boot`` multinomial resamples of the
    histogram (they never leave the observed range, so never go below 0); ``mode_se``: the
    standard deviation of the resampled modes.  ``mode`` is the smallest most frequent value;
    ``mode_prob`` the fraction of the resamples whose (smallest) most frequent value is that
    mode: its bootstrap probability of being the mode (a near-tie between two values gives
    about 1/2, a clear mode 1) -- report a mode with it.  ``quantiles``: the values at the levels
    :data:`QUANTILE_LEVELS` (the smallest ``v`` whose cumulative share reaches the level), stable
    where the mode is not.  Undefined statistics are ``None``, never NaN: all of them for an
    empty histogram (no run kept), ``se`` and ``mode_se`` for a single run.  The resamples come
    from ``rng`` (default ``numpy.random.default_rng(0)``): seeded, reproducible.

    >>> st = describe_histogram([0, 3, 1], np.random.default_rng(0))
    >>> st["mean"], st["mode"], st["count"], st["quantiles"]
    (1.25, 1, 4, [1, 1, 1, 1, 2])
    >>> describe_histogram([0, 3, 1], np.random.default_rng(0))["mode_prob"] > 0.5
    True
    """
    h = np.asarray(hist, dtype=np.int64)
    k = int(h.sum())
    out: dict[str, Any] = {"count": k, "hist": h.tolist()}
    if k == 0:   # no run kept (e.g. no impact in any window): every statistic is undefined
        out.update(mean=None, se=None, mode=None, mode_se=None, mean_ci=[None, None],
                   mode_ci=[None, None], mode_prob=None,
                   quantiles=[None] * len(QUANTILE_LEVELS))
        return out
    v = np.arange(len(h), dtype=float)
    mean = float((h * v).sum() / k)
    var = float((h * (v - mean) ** 2).sum() / (k - 1)) if k > 1 else None
    mode = int(np.argmax(h))
    cum = np.cumsum(h)
    out.update(mean=mean, se=math.sqrt(var / k) if var is not None else None, mode=mode,
               quantiles=[int(np.searchsorted(cum, q * k - 1e-9 * k)) for q in QUANTILE_LEVELS])
    rng = rng if rng is not None else np.random.default_rng(0)
    samples = rng.multinomial(k, h / k, size=boot)
    bmeans = samples @ v / k
    bmodes = np.argmax(samples, axis=1)
    out["mean_ci"] = [float(x) for x in np.percentile(bmeans, [2.5, 97.5])]
    out["mode_ci"] = [int(x) for x in np.percentile(bmodes, [2.5, 97.5], method="nearest")]
    out["mode_se"] = float(np.std(bmodes, ddof=1)) if k > 1 else None
    out["mode_prob"] = float(np.mean(bmodes == mode))
    return out


def column_stats(pipes_hist: Any, sites_hist: Any, seed: int, sigma: float) -> dict[str, Any]:
    """The statistics of one ``sigma`` of an ensemble seeded with ``seed``, from its histograms of
    impacting pipes and of impact sites: :func:`describe_histogram` of each, with the bootstrap
    stream ``SeedSequence([seed, 1, sigma_key(sigma)])`` (pipes first, then sites).  The stream
    depends only on ``(seed, sigma)``, so the statistics of a stored column are recomputed from
    its histograms alone, bit for bit (``scripts/restat_ensembles.py``).

    >>> st = column_stats([0, 0, 3, 1], [0, 3, 1], 0, 0.2)
    >>> st["pipes"]["mode"], st["sites"]["mode"], st["sites"]["count"]
    (2, 1, 4)
    """
    rng = np.random.default_rng(np.random.SeedSequence([int(seed), 1, sigma_key(sigma)]))
    return {"pipes": describe_histogram(pipes_hist, rng),
            "sites": describe_histogram(sites_hist, rng)}


@dataclass
class SigmaStats:
    """Statistics of one ``sigma``.

    ``runs``: runs attempted; ``failed``: runs whose simulation raised (``failures``: run index
    and reason of each, at most 20 kept); ``excluded``: finished runs without an impact in the
    window; ``pipes``/``sites``: per-run counts of the kept runs (empty when loaded from storage);
    ``stats["pipes"]``, ``stats["sites"]``: :func:`describe_histogram` of the kept runs;
    ``site_hits``: runs with an impact at each site ``0..n`` (over all finished runs);
    ``impacts``: impacts in all windows; ``events``: all events of all runs.
    """

    sigma: float
    runs: int
    excluded: int
    pipes: np.ndarray
    sites: np.ndarray
    events: int = 0
    failed: int = 0
    failures: list[tuple[int, str]] = field(default_factory=list)
    site_hits: np.ndarray = field(default_factory=lambda: np.zeros(0, dtype=np.int64))
    impacts: int = 0
    stats: dict[str, dict[str, Any]] = field(default_factory=dict)

    @property
    def finished(self) -> int:
        """Runs that did not fail."""
        return self.runs - self.failed

    def gap_rate(self, interior: bool = True) -> tuple[float, float]:
        """Measured probability that a gap sees an impact in the window, with its binomial
        standard error (over all finished runs, excluded ones included).  ``interior``: only
        the pipe-pipe sites ``1..n-1`` (the walls excluded)."""
        h = self.site_hits[1:-1] if interior else self.site_hits
        trials = self.finished * len(h)
        if trials == 0:
            return math.nan, math.nan
        q = float(h.sum()) / trials
        return q, math.sqrt(q * (1 - q) / trials)

    def as_dict(self) -> dict[str, Any]:
        return {"sigma": self.sigma, "runs": self.runs, "excluded": self.excluded,
                "failed": self.failed, "failures": [list(f) for f in self.failures],
                "events": self.events, "impacts": self.impacts,
                "site_hits": np.asarray(self.site_hits).tolist(), **self.stats}


@dataclass
class EnsembleResult:
    """Result of :func:`ensemble`: one :class:`SigmaStats` per ``sigma`` plus the parameters."""

    params: dict[str, Any]
    per_sigma: list[SigmaStats]
    seconds: float = 0.0

    @property
    def sigmas(self) -> np.ndarray:
        return np.array([s.sigma for s in self.per_sigma])

    def column(self, what: str = "pipes", stat: str = "mean") -> np.ndarray:
        """E.g. ``column("pipes", "mode")`` -> array over sigma (NaN where undefined);
        ``stat="mean_ci"``/``"mode_ci"`` give an array of shape ``(len(sigmas), 2)``."""
        rows = [s.stats[what][stat] for s in self.per_sigma]
        if stat.endswith("_ci"):
            return np.array([[np.nan if x is None else x for x in r] for r in rows], dtype=float)
        return np.array([np.nan if x is None else x for x in rows], dtype=float)

    def gap_rates(self, interior: bool = True) -> tuple[np.ndarray, np.ndarray]:
        """Measured per-gap impact rate and its standard error, per sigma."""
        out = np.array([s.gap_rate(interior) for s in self.per_sigma])
        return out[:, 0], out[:, 1]

    def as_dict(self) -> dict[str, Any]:
        return {"params": self.params, "seconds": self.seconds,
                "per_sigma": [s.as_dict() for s in self.per_sigma]}

    def __repr__(self) -> str:
        """One line: the grid of sigma, the runs and the setting (the dataclass repr printed
        every histogram, thousands of numbers)."""
        p, s = self.params, self.sigmas
        runs = sum(x.runs for x in self.per_sigma)
        grid = f"{len(s)} sigmas in [{s.min():g}, {s.max():g}]" if len(s) else "no sigma"
        setting = ", ".join(f"{k}={p[k]!r}" for k in ("n", "restitution", "t_transient",
                                                       "t_window") if k in p)
        return (f"EnsembleResult({grid}, {runs} runs, "
                f"{sum(x.failed for x in self.per_sigma)} failed; {setting})")

    def save(self, path: Any) -> None:
        """Write :meth:`as_dict` as JSON atomically (a temporary file renamed into place)."""
        path = Path(path)
        tmp = path.with_name(path.name + ".tmp")
        tmp.write_text(json.dumps(self.as_dict(), indent=1) + "\n")
        os.replace(tmp, path)

    @classmethod
    def from_dict(cls, data: dict[str, Any]) -> EnsembleResult:
        per = []
        n = int(data["params"]["n"])
        for s in data["per_sigma"]:
            st = SigmaStats(sigma=s["sigma"], runs=s["runs"], excluded=s["excluded"],
                            pipes=np.array([], int), sites=np.array([], int),
                            events=s.get("events", 0), failed=s.get("failed", 0),
                            failures=[tuple(f) for f in s.get("failures", [])],
                            site_hits=np.array(s.get("site_hits", [0] * (n + 1)), dtype=np.int64),
                            impacts=s.get("impacts", 0))
            st.stats = {"pipes": s["pipes"], "sites": s["sites"]}
            per.append(st)
        return cls(params=data["params"], per_sigma=per, seconds=data.get("seconds", 0.0))

    @classmethod
    def load(cls, path: Any) -> EnsembleResult:
        """Read a file written by :meth:`save`."""
        return cls.from_dict(json.loads(Path(path).read_text()))


# --------------------------------------------------------------------------- the ensemble
def check_sweep(sigmas: Any, runs: Any) -> tuple[list[float], int]:
    """The sigma values (each a float64 ``>= 0``) and the runs per sigma of a sweep of random
    rows (:func:`ensemble`, :func:`symhx.impact.sites.site_hit_tables`), refused before any
    work: ``1 <= runs <= MAX_RUNS`` and ``len(sigmas) * runs <= MAX_TOTAL_RUNS``, both caps as
    they are at the call.

    >>> check_sweep([0.1, 0.25], 3)
    ([0.1, 0.25], 3)
    """
    if isinstance(sigmas, (str, bytes)) or not isinstance(sigmas, (Sequence, np.ndarray)):
        raise TypeError(f"sigmas must be a sequence of numbers, got {type(sigmas).__name__} "
                        f"{sigmas!r}")
    if len(sigmas) == 0:
        raise InputError("sigmas must be a non-empty sequence of numbers >= 0, got []")
    sig = [_float(check_real(s, f"sigmas[{i}]", low=0), f"sigmas[{i}]")
           for i, s in enumerate(sigmas)]
    runs = check_int(runs, "runs", minimum=1)
    if runs > MAX_RUNS:
        raise InputError(f"runs must be <= {MAX_RUNS} per sigma (the work cap "
                         f"symhx.impact.ensemble.MAX_RUNS), got {runs}")
    if len(sig) * runs > MAX_TOTAL_RUNS:
        raise InputError(f"runs: len(sigmas) * runs = {len(sig) * runs} exceeds the work cap "
                         f"symhx.impact.ensemble.MAX_TOTAL_RUNS = {MAX_TOTAL_RUNS}")
    return sig, runs


def _make_progress(total: int, progress: bool | None) -> Any:
    """tqdm bar on stderr: ``None`` -> only when stderr is a terminal."""
    enabled = sys.stderr.isatty() if progress is None else bool(progress)
    from tqdm import tqdm

    return tqdm(total=total, unit="run", desc="ensemble", file=sys.stderr, disable=not enabled,
                dynamic_ncols=True)


def ensemble(
    sigmas: Sequence[Any],
    runs: int,
    *,
    n: int = 100,
    t_transient: float = 200.0,
    t_window: float = 100.0,
    seed: int = 0,
    executor: Executor | None = None,
    progress: bool | None = None,
    restitution: float = 0.8,
    omega: float = 1.0,
    d: float = 1.0,
    Omega: Sequence[Any] = (SQRT2,),
    sigma0: Any = None,
    chunk: int = 50,
    checkpoint: Any = None,
    checkpoint_every: float = 60.0,
    keep_runs: bool = True,
) -> EnsembleResult:
    """Figures 7 and 8: impacting pipes and distinct impact sites against ``sigma``.

    Parameters
    ----------
    sigmas : forcing standard deviations (eq. 18; the free-oscillation coefficients too unless
        ``sigma0`` is given).
    runs : runs per ``sigma`` (``len(sigmas) * runs <= MAX_RUNS``).
    n : pipes per row (the paper: 100; ``N = n + 1`` possible impacts).
    t_transient, t_window : impacts are counted in ``[t_transient, t_transient + t_window]``
        (the paper's values are not known; defaults 200 and 100, about 32 and 16 periods).
    seed : integer seed >= 0; results are identical for any executor and ``chunk``.
    executor : any ``concurrent.futures.Executor`` (``None``: serial in this process).
    progress : tqdm bar on stderr; ``None`` (default): only when stderr is a terminal.
    restitution, omega, d, Omega : model parameters (:class:`PipeRow`; ``r = 0.8`` assumed).
    sigma0 : standard deviation of the free-oscillation (initial-condition) coefficients:
        ``None`` (the same as ``sigma``, :meth:`PipeRow.random`), one number for every sigma, or
        one number per sigma.
    chunk : runs per task.
    checkpoint : path; when given, the statistics of the completed runs are written there (JSON,
        atomically) every ``checkpoint_every`` seconds and at the end.  A partial file holds, for
        every ``sigma``, the runs ``0..K-1`` of the longest completed prefix (``runs = K``), so
        it is an honest smaller ensemble.
    keep_runs : keep the per-run arrays in memory (``SigmaStats.pipes``/``sites``).

    Returns
    -------
    EnsembleResult

    Raises
    ------
    ValueError, TypeError : naming the argument, for bad input (NaN or infinite times, a float
        seed, bools, an executor that is not a ``concurrent.futures.Executor``).

    >>> res = ensemble([0.05, 0.3], 4, n=10, t_transient=20, t_window=20, seed=1, progress=False)
    >>> [s.excluded for s in res.per_sigma]
    [4, 0]
    >>> res.per_sigma[1].stats["sites"]["mean"] > 0
    True
    """
    sig, runs = check_sweep(sigmas, runs)
    n = check_pipes(n)
    seed_i = check_seed(seed)
    if seed_i is None:
        raise TypeError("seed must be an int >= 0 (an ensemble needs a fixed seed), got None")
    r = _float(check_real(restitution, "restitution", low=0, high=1), "restitution")
    om = _float(check_real(omega, "omega", low=0, low_open=True), "omega")
    dd = _float(check_real(d, "d", low=0, low_open=True), "d")
    t_tr_x = check_horizon(t_transient, "t_transient", om, allow_zero=True)
    t_w_x = check_horizon(t_window, "t_window", om)
    check_horizon(float(t_tr_x + t_w_x), "(t_transient + t_window)", om)
    t_tr, t_w = float(t_tr_x), float(t_w_x)
    if t_w == 0 or (t_tr + t_w) - t_tr <= 0:
        raise InputError(f"t_window = {t_window!r} is too short: t_transient + t_window must "
                         f"exceed t_transient = {t_tr!r} in float64")
    if sigma0 is None or (isinstance(sigma0, (Sequence, np.ndarray))
                          and not isinstance(sigma0, (str, bytes))):
        s0s = [None] * len(sig) if sigma0 is None else [
            _float(check_real(v, f"sigma0[{i}]", low=0), f"sigma0[{i}]")
            for i, v in enumerate(sigma0)]
        if len(s0s) != len(sig):
            raise InputError(f"sigma0 must be None, a number or one number per sigma "
                             f"({len(sig)}), got {len(s0s)} values")
    else:
        s0s = [_float(check_real(sigma0, "sigma0", low=0), "sigma0")] * len(sig)
    chunk = check_int(chunk, "chunk", minimum=1)
    if executor is not None and not isinstance(executor, Executor):
        raise TypeError(f"executor must be a concurrent.futures.Executor or None, got "
                        f"{type(executor).__name__} {executor!r}")
    for name, flag in (("progress", progress), ("keep_runs", keep_runs)):
        if flag is not None and not isinstance(flag, bool):
            raise TypeError(f"{name} must be True, False or None, got {flag!r}")
    every = _float(check_real(checkpoint_every, "checkpoint_every", low=0), "checkpoint_every")
    Om = tuple(Omega) if isinstance(Omega, (Sequence, np.ndarray)) else (Omega,)
    for i, w in enumerate(Om):
        if not isinstance(w, type(SQRT2)):
            check_real(w, f"Omega[{i}]", low=0)
    args_common = (n, t_tr, t_w, seed_i, r, om, dd, Om)
    # the model parameters (resonance, ...) are checked once here, so that a ValueError inside a
    # run can only be a failed draw (recorded as a failed run)
    PipeRow(1, restitution=r, omega=om, d=dd, Omega=Om, alpha=[[0.0] * len(Om)],
            beta=[[0.0] * len(Om)], x0=[dd], v0=[0.0])

    # tasks in rounds (every sigma gets chunk k before any gets chunk k+1): partial results
    # stay balanced over sigma
    nchunks = (runs + chunk - 1) // chunk
    tasks = [(i, c) for c in range(nchunks) for i in range(len(sig))]
    done: list[dict[int, dict[str, Any]]] = [{} for _ in sig]

    params = {"runs": runs, "n": n, "t_transient": t_tr, "t_window": t_w, "seed": seed_i,
              "restitution": r, "omega": om, "d": dd, "Omega": [repr(w) for w in Om],
              "sigma0": "sigma" if sigma0 is None else s0s, "chunk": chunk,
              "engine": "float64 C" if _c_available() else "float64 python"}
    bar = _make_progress(len(sig) * runs, progress)
    t0 = time.time()
    last = [t0]

    def snapshot(final: bool) -> EnsembleResult:
        per = []
        for i, s in enumerate(sig):
            k = 0
            while k in done[i]:
                k += 1
            parts = [done[i][c] for c in range(k)]
            per.append(_combine(s, parts, n, seed_i, keep_runs))
        p = dict(params)
        if not final:
            p["partial"] = True
            p["runs"] = min(st.runs for st in per)
        return EnsembleResult(params=p, per_sigma=per, seconds=time.time() - t0)

    def store(task: tuple[int, int], out: dict[str, Any]) -> None:
        done[task[0]][task[1]] = out
        bar.update(len(out["pipes"]))
        if checkpoint is not None and time.time() - last[0] >= every:
            snapshot(False).save(checkpoint)
            last[0] = time.time()

    def submit_args(task: tuple[int, int]) -> tuple:
        i, c = task
        return (sig[i], list(range(c * chunk, min((c + 1) * chunk, runs))), *args_common,
                s0s[i])

    try:
        if executor is None:
            for task in tasks:
                store(task, run_chunk(*submit_args(task)))
        else:
            futs = {executor.submit(run_chunk, *submit_args(t)): t for t in tasks}
            for f in as_completed(futs):
                store(futs[f], f.result())
    finally:
        bar.close()
    res = snapshot(True)
    if checkpoint is not None:
        res.save(checkpoint)
    return res


def _combine(sigma: float, parts: list[dict[str, Any]], n: int, seed: int,
             keep_runs: bool) -> SigmaStats:
    """Merge the chunks ``0..K-1`` of one sigma into its :class:`SigmaStats`."""
    def cat(key: str) -> np.ndarray:
        return (np.concatenate([p[key] for p in parts]) if parts
                else np.zeros(0, dtype=np.int64))

    pipes, sites, impacts = cat("pipes"), cat("sites"), cat("impacts")
    ok = impacts >= 0
    keep = ok & (sites > 0)
    failures = [f for p in parts for f in p["failures"]]
    hits = (np.sum([p["site_hits"] for p in parts], axis=0) if parts
            else np.zeros(n + 1, dtype=np.int64))
    st = SigmaStats(sigma=sigma, runs=len(pipes), excluded=int((ok & (sites == 0)).sum()),
                    pipes=pipes[keep] if keep_runs else np.zeros(0, dtype=np.int64),
                    sites=sites[keep] if keep_runs else np.zeros(0, dtype=np.int64),
                    events=int(sum(p["events"] for p in parts)), failed=len(failures),
                    failures=failures[:20], site_hits=np.asarray(hits, dtype=np.int64),
                    impacts=int(impacts[ok].sum()))
    # the bootstrap stream depends only on (seed, sigma): identical for any executor and grid
    st.stats = column_stats(np.bincount(pipes[keep], minlength=n + 1)[: n + 1],
                            np.bincount(sites[keep], minlength=n + 2)[: n + 2], seed, sigma)
    return st


def _c_available() -> bool:
    from symhx.impact.fast import available

    return available()


# --------------------------------------------------------------------------- thresholds
def thresholds(res: EnsembleResult, *, level: int = 10, min_kept: int = 20, boot: int = 400,
               seed: int = 0) -> dict[str, list[float]]:
    """The simulated threshold of an ensemble, three ways, with bootstrap 16-84 % intervals.

    Only sigmas with at least ``min_kept`` runs with an impact are used (the statistics of the
    paper's figures 7 and 8 exclude runs without impact).

    * ``mode``: the smallest sigma of the grid from which on the mode of the number of impacting
      pipes is ``>= level`` (the mode has left small values).  Near the jump the histogram is
      bimodal and its mode can tie: prefer the two below;
    * ``half``: where the mean number of impacting pipes (figure 8) first reaches half the
      row, ``n / 2`` (linear interpolation between the two grid points around it; NaN if it
      never does or already does at the first usable sigma): stable where the mode is not;
    * ``steep``: the midpoint of the grid interval where the mean number of impacting pipes
      rises steepest (largest difference quotient).

    Each is ``[estimate, low, high]``; the interval comes from ``boot`` multinomial resamples of
    every sigma's histogram (the grid spacing is a further resolution limit).

    >>> res = ensemble([0.1, 0.2, 0.3], 30, n=10, t_transient=20, t_window=20, progress=False)
    >>> thresholds(res, level=5, min_kept=5, boot=20)["mode"][0]
    0.2
    """
    sig = res.sigmas
    hists = [np.array(s.stats["pipes"]["hist"], dtype=float) for s in res.per_sigma]
    rng = np.random.default_rng(seed)

    def half_row(means: np.ndarray) -> float:
        target = (len(hists[0]) - 1) / 2 if hists else math.nan   # n / 2 (hist: 0..n pipes)
        usable = [j for j in range(len(sig)) if not np.isnan(means[j])]
        for a, b in itertools.pairwise(usable):
            if means[a] < target <= means[b]:
                return float(sig[a] + (target - means[a]) * (sig[b] - sig[a])
                             / (means[b] - means[a]))
        return math.nan

    def est(hs: list[np.ndarray]) -> tuple[float, float, float]:
        ok = [h.sum() >= min_kept for h in hs]
        m = math.nan
        for j in range(len(sig) - 1, -1, -1):
            if not ok[j] or int(np.argmax(hs[j])) < level:
                break
            m = float(sig[j])
        means = np.array([(h * np.arange(len(h))).sum() / h.sum() if k else np.nan
                          for h, k in zip(hs, ok, strict=True)])
        half = half_row(means)
        diffs = np.diff(means) / np.diff(sig)      # slopes: the grid need not be uniform
        if len(diffs) == 0 or np.all(np.isnan(diffs)):
            return m, half, math.nan
        k = int(np.nanargmax(diffs))
        return m, half, float((sig[k] + sig[k + 1]) / 2)

    m0, md0, s0 = est(hists)
    bm, bmd, bs = [], [], []
    for _ in range(boot):
        hb = [rng.multinomial(int(h.sum()), h / h.sum()).astype(float) if h.sum() else h
              for h in hists]
        a, b, c = est(hb)
        bm.append(a)
        bmd.append(b)
        bs.append(c)

    def q(x: list[float]) -> list[float]:
        x = [v for v in x if not math.isnan(v)]
        return [float(v) for v in np.percentile(x, [16, 84])] if x else [math.nan, math.nan]

    return {"mode": [m0, *q(bm)], "half": [md0, *q(bmd)], "steep": [s0, *q(bs)]}


# --------------------------------------------------------------------------- assumptions
def site_transitions(
    sigma: float,
    runs: int,
    *,
    n: int = 100,
    t_transient: float = 200.0,
    t_window: float = 100.0,
    seed: int = 0,
    restitution: float = 0.8,
    sigma0: float | None = None,
) -> list[np.ndarray]:
    """Sequences of impact sites in the window (section 4's independence assumption).

    Runs ``k = 0..runs-1`` draw the same rows as :func:`ensemble` (:func:`run_seed`) and are
    simulated with :func:`symhx.impact.simulate` (float64); for each run
    the sites of the impacts (kinds ``impact`` and ``stick``, as counted by the ensemble) with
    ``t >= t_transient``, in time order.  Failed
    runs give an empty sequence.

    >>> seqs = site_transitions(0.3, 2, n=6, t_transient=5, t_window=5, seed=1)
    >>> len(seqs), all(s.min() >= 0 and s.max() <= 6 for s in seqs if len(s))
    (2, True)
    """
    from symhx.impact.simulate import simulate

    sig = _float(check_real(sigma, "sigma", low=0), "sigma")
    runs = check_int(runs, "runs", minimum=1)
    seed_i = check_seed(seed)
    if seed_i is None:
        raise TypeError("seed must be an int >= 0 (the rows of ensemble() need one), got None")
    t_tr = float(check_real(t_transient, "t_transient", low=0))
    t_w = float(check_real(t_window, "t_window", low=0, low_open=True))
    out = []
    for k in range(runs):
        row = PipeRow.random(n, sig, seed=run_seed(seed_i, sig, k), restitution=restitution,
                             sigma0=sigma0)
        try:
            h = simulate(row, t_tr + t_w)
        except RuntimeError:
            out.append(np.zeros(0, dtype=np.int64))
            continue
        times = np.asarray(h.times, dtype=float)
        sel = np.isin(np.asarray(h.kinds), (IMPACT, STICK)) & (times >= t_tr)
        out.append(np.asarray(h.sites, dtype=np.int64)[sel])
    return out


def transition_dependence(seqs: Sequence[np.ndarray], size: int, *, shuffles: int = 50,
                          seed: int = 0,
                          stat: Callable[[np.ndarray, np.ndarray], float] | None = None
                          ) -> dict[str, float]:
    """Dependence of the next impact site on the last one, against independence.

    Statistic (default): the mutual information (nats) of the pooled pairs (last, next).  The
    null: each run's sequence randomly permuted (keeps each run's site frequencies, destroys the
    order), ``shuffles`` times.  Also ``same``/``adjacent``: the fraction of pairs with
    ``next == last`` / ``|next - last| == 1``, observed and under the null.

    >>> rng = np.random.default_rng(1)
    >>> alt = [np.tile([3, 7], 200)]           # strictly alternating: fully dependent
    >>> transition_dependence(alt, 10, shuffles=20)["z"] > 10
    True
    """
    rng = np.random.default_rng(seed)
    stat = stat or _mutual_information_pairs(size)

    def pairs(ss: Sequence[np.ndarray]) -> tuple[np.ndarray, np.ndarray]:
        a = [s[:-1] for s in ss if len(s) > 1]
        b = [s[1:] for s in ss if len(s) > 1]
        if not a:
            return np.zeros(0, dtype=np.int64), np.zeros(0, dtype=np.int64)
        return np.concatenate(a), np.concatenate(b)

    a, b = pairs(seqs)
    obs = stat(a, b)
    null, same0, adj0 = [], [], []
    for _ in range(shuffles):
        sa, sb = pairs([rng.permutation(s) for s in seqs])
        null.append(stat(sa, sb))
        same0.append(float(np.mean(sa == sb)) if len(sa) else math.nan)
        adj0.append(float(np.mean(np.abs(sa - sb) == 1)) if len(sa) else math.nan)
    mu, sd = float(np.mean(null)), float(np.std(null, ddof=1))
    return {"pairs": len(a), "mi": obs, "mi_null": mu, "mi_null_sd": sd,
            "z": (obs - mu) / sd if sd > 0 else math.nan,
            "same": float(np.mean(a == b)) if len(a) else math.nan,
            "same_null": float(np.mean(same0)),
            "adjacent": float(np.mean(np.abs(a - b) == 1)) if len(a) else math.nan,
            "adjacent_null": float(np.mean(adj0))}


def _mutual_information_pairs(size: int) -> Callable[[np.ndarray, np.ndarray], float]:
    def mi(a: np.ndarray, b: np.ndarray) -> float:
        if len(a) == 0:
            return math.nan
        joint = np.zeros((size, size))
        np.add.at(joint, (a, b), 1.0)
        joint /= joint.sum()
        pa, pb = joint.sum(1), joint.sum(0)
        nz = joint > 0
        return float((joint[nz] * np.log(joint[nz] / np.outer(pa, pb)[nz])).sum())
    return mi


# --------------------------------------------------------------------------- eq. 27 check
def free_flight_closure_fraction(sigma: float, gaps: int, *, horizon: float = 400.0,
                                 seed: int = 0, omega: float = 1.0, d: float = 1.0,
                                 Omega: float = math.sqrt(2)) -> float:
    """Fraction of interior gaps (eq. 21, random coefficients as in section 7) that close during
    free flight within ``[0, horizon]``, found with the certified search of the engine.

    As ``horizon -> inf`` this tends to ``P(Y0 + Y1/|omega^2 - Omega^2| > d)``, eq. (22)/(27),
    i.e. :func:`symhx.forcing.impact_probability`.

    Parameters
    ----------
    sigma : standard deviation ``> 0`` of the four coefficients of each gap (finite).
    gaps : number of random gaps, an int in ``[1, MAX_GAPS]``.
    horizon : length ``> 0`` of the window, ``omega * horizon <= MAX_HORIZON``
        (``symhx.impact.model``).
    seed : ``None`` or an int ``>= 0``.
    omega, d, Omega : as for :class:`PipeRow` (``Omega != omega``).

    >>> free_flight_closure_fraction(0.01, 10, horizon=50.0)
    0.0
    """
    from symhx.impact.engine import Engine, FloatContext, Outcome

    sig = _float(check_real(sigma, "sigma", low=0, low_open=True), "sigma")
    gaps = check_int(gaps, "gaps", minimum=1)
    if gaps > MAX_GAPS:
        raise InputError(f"gaps must be <= {MAX_GAPS} (the work cap "
                         f"symhx.impact.ensemble.MAX_GAPS), got {gaps}")
    seed_i = check_seed(seed)
    om = _float(check_real(omega, "omega", low=0, low_open=True), "omega")
    dd = _float(check_real(d, "d", low=0, low_open=True), "d")
    Om = _float(check_real(Omega, "Omega", low=0), "Omega")
    hor = float(check_horizon(horizon, "horizon", om))
    # PipeRow checks resonance and the float64 range of the wall
    row = PipeRow(1, restitution=1.0, omega=om, d=dd, Omega=(Om,), alpha=[[0.0]],
                  beta=[[0.0]], x0=[dd], v0=[0.0])
    den = om**2 - Om**2
    try:   # the search squares amplitudes (up to ~4 sigma / |den|): they must stay finite
        ok = math.isfinite((4 * sig * max(1.0, 1 / abs(den))) ** 2)
    except OverflowError:
        ok = False
    if not ok:
        raise InputError(f"sigma = {sigma!r} is too large for the float64 engine (the "
                         "amplitudes overflow); use a smaller sigma")
    rng = np.random.default_rng(seed_i)
    eng = Engine(row, FloatContext(), v_stick=0.0)
    closed = 0
    for _ in range(gaps):
        a0, b0, a1, b1 = rng.normal(0.0, sig, size=(4, 2)) @ np.array([1.0, -1.0])
        g = [dd, a0, b0, a1 / den, b1 / den]
        _, code = eng.search(g, 0.0, hor)
        closed += code not in (Outcome.NONE, Outcome.CONT)
    return closed / gaps
