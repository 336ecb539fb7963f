"""Ensembles of random pipe rows: the statistics of figures 7 and 8 (section 7 of the paper).

For each ``sigma`` every run draws a row with :meth:`PipeRow.random` (eqs. 17, 18, 20), simulates it
with the float64 engine to ``t_transient + t_window`` and counts, in the window, the pipes that take
part in an impact and the distinct impact sites (``0..n``; the paper's ``N = n + 1`` vertices).
Runs without any impact in the window are excluded, as in the paper, and counted.

Reproducibility: run ``k`` of ``sigmas[i]`` uses ``numpy.random.SeedSequence([seed, i, k])``, so
the numbers do not depend on the executor, on the chunking or on the order of completion.  Any
``concurrent.futures.Executor`` works (``ProcessPoolExecutor``, a ``dask.distributed`` client's
``client.get_executor()``); ``executor=None`` runs serially.
"""

from __future__ import annotations

import math
import sys
import time
from collections.abc import Sequence
from concurrent.futures import Executor, as_completed
from dataclasses import dataclass, field
from typing import Any

import numpy as np

from symhx.impact.fast import count_impacts
from symhx.impact.model import SQRT2, PipeRow

__all__ = ["EnsembleResult", "SigmaStats", "ensemble", "free_flight_closure_fraction", "run_chunk"]


@dataclass
class SigmaStats:
    """Statistics of one ``sigma``: per-run counts of impacting pipes and of distinct sites.

    ``pipes``/``sites``: counts of the runs with at least one impact in the window;
    ``excluded``: runs without.  ``mean``, ``se`` (standard error of the mean), ``mode`` (smallest
    most frequent value), ``mode_se`` (bootstrap standard error of the mode, 200 resamples seeded
    from the ensemble seed) and ``hist`` (counts of the values ``0..n+1``).
    """

    sigma: float
    runs: int
    excluded: int
    pipes: np.ndarray
    sites: np.ndarray
    events: int = 0
    stats: dict[str, dict[str, Any]] = field(default_factory=dict)

    def as_dict(self) -> dict[str, Any]:
        return {"sigma": self.sigma, "runs": self.runs, "excluded": self.excluded,
                "events": self.events, **self.stats}


def _describe(values: np.ndarray, size: int, rng: np.random.Generator) -> dict[str, Any]:
    k = len(values)
    hist = np.bincount(values, minlength=size + 1)[: size + 1] if k else np.zeros(size + 1, int)
    if k == 0:
        return {"mean": math.nan, "se": math.nan, "mode": None, "mode_se": math.nan,
                "hist": hist.tolist()}
    mean = float(np.mean(values))
    se = float(np.std(values, ddof=1) / math.sqrt(k)) if k > 1 else math.nan
    mode = int(np.argmax(hist))
    boots = []
    for _ in range(200):
        sample = values[rng.integers(0, k, size=k)]
        boots.append(int(np.argmax(np.bincount(sample, minlength=size + 1))))
    return {"mean": mean, "se": se, "mode": mode, "mode_se": float(np.std(boots, ddof=1)),
            "hist": hist.tolist()}


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
        """E.g. ``column("pipes", "mode")`` -> array over sigma (NaN where undefined)."""
        return np.array([np.nan if s.stats[what][stat] is None else s.stats[what][stat]
                         for s in self.per_sigma], dtype=float)

    def as_dict(self) -> dict[str, Any]:
        return {"params": self.params, "seconds": self.seconds,
                "per_sigma": [s.as_dict() for s in self.per_sigma]}

    @classmethod
    def from_dict(cls, data: dict[str, Any]) -> EnsembleResult:
        per = []
        for s in data["per_sigma"]:
            st = SigmaStats(sigma=s["sigma"], runs=s["runs"], excluded=s["excluded"],
                            pipes=np.array([], int), sites=np.array([], int),
                            events=s.get("events", 0))
            st.stats = {"pipes": s["pipes"], "sites": s["sites"]}
            per.append(st)
        return cls(params=data["params"], per_sigma=per, seconds=data.get("seconds", 0.0))


def run_chunk(sigma: float, i_sigma: int, runs: Sequence[int], n: int, t_transient: float,
              t_window: float, seed: int, restitution: float, omega: float, d: float,
              Omega: tuple) -> tuple[np.ndarray, np.ndarray, int]:
    """Worker: simulate the given runs of one ``sigma``; returns (pipes, sites, events) per run.

    >>> p, s, ev = run_chunk(0.05, 0, [0, 1], 10, 10.0, 10.0, 1, 0.8, 1.0, 1.0, (SQRT2,))
    >>> p.tolist(), s.tolist()
    ([0, 0], [0, 0])
    """
    pipes = np.zeros(len(runs), dtype=np.int64)
    sites = np.zeros(len(runs), dtype=np.int64)
    events = 0
    for k, run in enumerate(runs):
        ss = np.random.SeedSequence([int(seed), int(i_sigma), int(run)])
        row = PipeRow.random(n, sigma, seed=ss, restitution=restitution, omega=omega, d=d,
                             Omega=Omega)
        counts, nev = count_impacts(row, t_transient + t_window, t_transient)
        hit = counts > 0
        sites[k] = int(hit.sum())
        pipes[k] = int((hit[:-1] | hit[1:]).sum())
        events += nev
    return pipes, sites, events


class _Progress:
    def __init__(self, total: int, enabled: bool, label: str = "ensemble") -> None:
        self.total, self.enabled, self.done, self.t0 = total, enabled, 0, time.time()
        self.label = label
        self._draw()

    def update(self, k: int) -> None:
        self.done += k
        self._draw()

    def _draw(self) -> None:
        if not self.enabled:
            return
        frac = self.done / self.total if self.total else 1.0
        bar = "#" * int(30 * frac)
        el = time.time() - self.t0
        sys.stderr.write(f"\r{self.label} [{bar:<30}] {self.done}/{self.total} runs {el:6.1f}s")
        if self.done >= self.total:
            sys.stderr.write("\n")
        sys.stderr.flush()


def ensemble(
    sigmas: Sequence[float],
    runs: int,
    *,
    n: int = 100,
    t_transient: float = 200.0,
    t_window: float = 100.0,
    seed: int = 0,
    executor: Executor | None = None,
    progress: bool = True,
    restitution: float = 0.8,
    omega: float = 1.0,
    d: float = 1.0,
    Omega: Sequence[Any] = (SQRT2,),
    chunk: int = 50,
) -> EnsembleResult:
    """Figures 7 and 8: impacting pipes and distinct impact sites against ``sigma``.

    Parameters
    ----------
    sigmas : forcing standard deviations (eq. 18; the free-oscillation coefficients too).
    runs : runs per ``sigma``.
    n : pipes per row (the paper: 100).
    t_transient, t_window : impacts are counted in ``[t_transient, t_transient + t_window]``
        (the paper's values are not known; defaults 200 and 100, about 32 and 16 periods).
    seed : integer seed; results are identical for any executor and ``chunk``.
    executor : any ``concurrent.futures.Executor`` (``None``: serial in this process).
    progress : draw a progress bar on stderr.
    restitution, omega, d, Omega : model parameters (:class:`PipeRow`; ``r = 0.8`` assumed).
    chunk : runs per task.

    Returns
    -------
    EnsembleResult

    >>> res = ensemble([0.05, 0.3], 4, n=10, t_transient=20, t_window=20, seed=1, progress=False)
    >>> [s.excluded for s in res.per_sigma]
    [4, 0]
    >>> res.per_sigma[1].stats["sites"]["mean"] > 0
    True
    """
    sig = [float(s) for s in sigmas]
    if not sig or any(not math.isfinite(s) or s < 0 for s in sig):
        raise ValueError("sigmas must be a non-empty sequence of finite numbers >= 0")
    if int(runs) != runs or runs < 1:
        raise ValueError(f"runs must be an integer >= 1, got {runs!r}")
    if not (t_transient >= 0 and t_window > 0):
        raise ValueError("t_transient must be >= 0 and t_window > 0")
    if int(chunk) < 1:
        raise ValueError("chunk must be >= 1")
    runs = int(runs)
    Om = tuple(Omega)
    args_common = (n, float(t_transient), float(t_window), int(seed), float(restitution),
                   float(omega), float(d), Om)
    tasks = []
    for i, s in enumerate(sig):
        for start in range(0, runs, chunk):
            tasks.append((s, i, list(range(start, min(start + chunk, runs)))))
    pipes = [np.zeros(runs, dtype=np.int64) for _ in sig]
    sites = [np.zeros(runs, dtype=np.int64) for _ in sig]
    events = [0 for _ in sig]
    bar = _Progress(len(sig) * runs, progress)
    t0 = time.time()

    def store(task: tuple, res: tuple) -> None:
        _, i, rr = task
        pipes[i][rr] = res[0]
        sites[i][rr] = res[1]
        events[i] += res[2]
        bar.update(len(rr))

    if executor is None:
        for task in tasks:
            store(task, run_chunk(task[0], task[1], task[2], *args_common))
    else:
        futs = {executor.submit(run_chunk, t[0], t[1], t[2], *args_common): t for t in tasks}
        for f in as_completed(futs):
            store(futs[f], f.result())
    rng = np.random.default_rng(np.random.SeedSequence([int(seed), 10**6]))
    per = []
    for i, s in enumerate(sig):
        keep = sites[i] > 0
        st = SigmaStats(sigma=s, runs=runs, excluded=int((~keep).sum()), pipes=pipes[i][keep],
                        sites=sites[i][keep], events=events[i])
        st.stats = {"pipes": _describe(pipes[i][keep], n, rng),
                    "sites": _describe(sites[i][keep], n + 1, rng)}
        per.append(st)
    params = {"runs": runs, "n": n, "t_transient": float(t_transient),
              "t_window": float(t_window), "seed": int(seed), "restitution": float(restitution),
              "omega": float(omega), "d": float(d), "Omega": [repr(w) for w in Om],
              "engine": "float64 C" if _c_available() else "float64 python"}
    return EnsembleResult(params=params, per_sigma=per, seconds=time.time() - t0)


def _c_available() -> bool:
    from symhx.impact.fast import available

    return available()


def free_flight_closure_fraction(sigma: float, gaps: int, *, horizon: float = 400.0,
                                 seed: int = 0, omega: float = 1.0, d: float = 1.0,
                                 Omega: float = math.sqrt(2)) -> float:
    """Fraction of interior gaps (eq. 21, random coefficients as in section 7) that close during
    free flight within ``[0, horizon]``, found with the certified search of the engine.

    As ``horizon -> inf`` this tends to ``P(Y0 + Y1/|omega^2 - Omega^2| > d)``, eq. (22)/(27),
    i.e. :func:`symhx.forcing.impact_probability`.

    >>> free_flight_closure_fraction(0.01, 10, horizon=50.0)
    0.0
    """
    from symhx.impact.engine import _NONE, _Engine, _FloatCtx

    rng = np.random.default_rng(seed)
    row = PipeRow(1, restitution=1.0, omega=omega, d=d, Omega=(Omega,), alpha=[[0.0]],
                  beta=[[0.0]], x0=[d], v0=[0.0])
    eng = _Engine(row, _FloatCtx(), v_stick=0.0)
    den = omega**2 - Omega**2
    closed = 0
    for _ in range(gaps):
        a0, b0, a1, b1 = rng.normal(0.0, sigma, size=(4, 2)) @ np.array([1.0, -1.0])
        g = [d, a0, b0, a1 / den, b1 / den]
        _, code = eng.search(g, 0.0, float(horizon))
        closed += code not in (_NONE, 1)
    return closed / gaps
