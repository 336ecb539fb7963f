r"""Does a per-site theory predict the simulated row better? Three ways to give the sites of a
row their impact probabilities, each compared with the simulation (issue 30).

For every ``sigma`` of a :class:`~symhx.impact.sites.SiteHitResult` (the per-run record of an
ensemble), the graph model of simple circuits with two site classes, the 2 wall sites and the
``n - 1`` pipe-pipe sites (:mod:`symhx.site_distribution`), gives the distribution of the number
``X`` of distinct impact sites; the simulation gives its histogram over the runs with at least one
impact (as in the paper). The models:

* ``"uniform"``: the paper's single ``p(sigma)`` of eq. (27) at every site;
* ``"geometry"``: eq. (27)'s own geometry, pipe pairs ``p(sigma)`` and walls
  ``p_wall(sigma)`` (one moving body: :func:`symhx.forcing.sites.contact_probability`);
* ``"scaled"``: pipe pairs ``lambda p(sigma)`` and walls ``rho(sigma) lambda p(sigma)``, with
  ``rho(sigma)`` the *measured* ratio of the wall rate to the interior rate at that ``sigma``
  (:meth:`~symhx.impact.sites.SiteHitTable.rate_ratio`) and one scale ``lambda`` fitted to the
  simulated means (least squares over ``sigma``).

Distances, over the values of ``sigma`` with at least ``min_kept`` runs with an impact: the RMS of
``mean_sim - E[X]`` (sites) and the RMS of the Kolmogorov distance ``max_k |F_sim(k) - F(k)|``
between the two distributions. Their uncertainty: a bootstrap of the runs (each ``sigma``'s joint
histogram resampled, :meth:`~symhx.impact.sites.SiteHitTable.resample`; the measured ratios move
with it and ``lambda`` is fitted again in every replicate), seeded. The threshold a model
predicts is the ``sigma`` at which the mode of ``X`` leaves 1 along the model's path through the
plane of the two probabilities (:func:`symhx.critical_point` with ``weights=``, certified
at each point; the path crosses it once); the simulated one is the first ``sigma`` of the grid
from which on the simulated mode of ``X`` stays above 1.

The comparison is computed by ``python scripts/site_calibration.py`` (a few minutes: every
bootstrap replicate fits ``lambda`` anew) into ``symhx/data/site_calibration.json``; the book loads
it and recomputes the point estimates with :func:`fit_models`.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass, field
from typing import Any

import numpy as np
from scipy.optimize import brentq, minimize_scalar

from symhx.critical import critical_point as simple_critical_point
from symhx.critical_sites import direction_critical_point
from symhx.distribution import SimpleDistribution
from symhx.forcing.inverse import sigma_for_impact_probability
from symhx.forcing.sites import row_site_probabilities
from symhx.impact.sites import SiteHitResult, SiteHitTable
from symhx.site_distribution import SitesDistribution
from symhx.sites import SiteClasses
from symhx.validation import InputError, check_int, check_seed

__all__ = [
    "MAX_REPLICATES",
    "MODELS",
    "ModelFit",
    "SimulatedX",
    "SiteModelComparison",
    "compare_site_models",
    "fit_models",
    "model_pmfs",
    "simulated_x",
]

#: the three models, in order
MODELS = ("uniform", "geometry", "scaled")
#: documented work cap of :func:`compare_site_models`: each bootstrap replicate fits ``lambda``
#: and locates two thresholds (about a second for the production ensemble's 22 kept sigmas)
MAX_REPLICATES = 2000
#: the bracket of the fitted scale ``lambda`` (a fit at either end is reported as such)
SCALE_BRACKET = (0.02, 50.0)


@dataclass(frozen=True, eq=False)
class SimulatedX:
    """The simulated side at the kept values of ``sigma``.

    Attributes
    ----------
    sigmas : ndarray
        The kept values (at least ``min_kept`` runs with an impact).
    hists : ndarray of int, shape ``(len(sigmas), n + 2)``
        Runs with ``X = 0..n + 1`` distinct impact sites (``X = 0`` set to 0: excluded).
    ratios : ndarray
        Measured wall rate / interior rate (over all finished runs).
    n : int
        Pipes of the row.
    params : dict
        The simulation's parameters (the forcing that maps ``sigma`` to ``p``).
    """

    sigmas: np.ndarray
    hists: np.ndarray
    ratios: np.ndarray
    n: int
    params: dict[str, Any] = field(default_factory=dict)

    @property
    def means(self) -> np.ndarray:
        """Mean ``X`` over the runs with an impact, per ``sigma``."""
        k = np.arange(self.hists.shape[1])
        return (self.hists @ k) / self.hists.sum(axis=1)

    @property
    def cdfs(self) -> np.ndarray:
        """Empirical distribution functions ``F(k)``, ``k = 1..n + 1``."""
        c = np.cumsum(self.hists[:, 1:], axis=1)
        return c / c[:, -1:]

    @property
    def modes(self) -> np.ndarray:
        """Most frequent ``X`` (the smallest on a tie)."""
        return np.argmax(self.hists, axis=1)

    def threshold(self) -> float:
        """The first ``sigma`` from which on the simulated mode stays above 1 (NaN if never)."""
        above = self.modes > 1
        if not above[-1]:
            return math.nan
        j = len(above) - 1
        while j > 0 and above[j - 1]:
            j -= 1
        return float(self.sigmas[j])


def simulated_x(result: SiteHitResult, *, min_kept: int = 20,
                tables: Sequence[SiteHitTable] | None = None) -> SimulatedX:
    """The simulated side of the comparison from a per-run record (or replicate ``tables``).

    Parameters
    ----------
    result : SiteHitResult
        The simulation (:func:`symhx.impact.sites.site_hit_tables`).
    min_kept : int
        Keep the ``sigma`` with at least this many runs with an impact.
    tables : sequence of SiteHitTable, optional
        Replicates of ``result.tables`` (same order): a bootstrap sample.

    Returns
    -------
    SimulatedX

    >>> t = SiteHitTable(0.2, np.array([[5, 20, 0], [0, 30, 10], [0, 0, 40]]), np.zeros(4))
    >>> sx = simulated_x(SiteHitResult({"n": 3}, [t]))
    >>> sx.means.round(4).tolist(), sx.ratios.round(4).tolist()   # (20 + 60 + 30 + 160)/100
    ([2.7], [0.8])
    """
    if not isinstance(result, SiteHitResult):
        raise TypeError(f"result must be a SiteHitResult, got {type(result).__name__}")
    min_kept = check_int(min_kept, "min_kept", minimum=1)
    tabs = list(result.tables if tables is None else tables)
    keep = []
    for t in tabs:
        h = t.sites_histogram()
        if h[1:].sum() >= min_kept:
            keep.append((t, h))
    if not keep:
        raise InputError(f"min_kept: no sigma has {min_kept} runs with an impact")
    n = keep[0][0].n
    hists = np.array([np.concatenate(([0], h[1:])) for _, h in keep])
    ratios = np.array([t.rate_ratio()[0] for t, _ in keep])
    return SimulatedX(np.array([t.sigma for t, _ in keep]), hists, ratios, n,
                      dict(result.params))


def _forcing(params: dict[str, Any]) -> dict[str, Any]:
    """The forcing arguments of the simulation (the paper's sqrt(2) kept exact)."""
    Om = params.get("Omega", ["sqrt(2)"])
    if Om not in (["sqrt(2)"], ("sqrt(2)",)):
        if len(Om) != 1:
            raise InputError(f"params: one forcing component expected, got Omega={Om!r}")
        Om = float(Om[0])
    else:
        Om = None
    if params.get("sigma0", "sigma") != "sigma":
        raise InputError("params: the models need sigma0 = sigma (the forcing of eq. 27)")
    return {"omega": params.get("omega", 1.0), "Omega": Om, "d": params.get("d", 1.0)}


def _class_p(model: str, sigmas: np.ndarray, n: int, params: dict[str, Any],
             ratio: Any = None, scale: float = 1.0) -> tuple[np.ndarray, np.ndarray]:
    """``(p_wall, p_pipe)`` of a model along ``sigmas``."""
    sp = row_site_probabilities(n, np.asarray(sigmas, dtype=float), **_forcing(params))
    pipe = np.asarray(sp["pipe-pipe"], dtype=float)
    if model == "uniform":
        return pipe, pipe
    if model == "geometry":
        return np.asarray(sp["wall"], dtype=float), pipe
    return np.asarray(ratio, dtype=float) * scale * pipe, scale * pipe


def model_pmfs(p_wall: Any, p_pipe: Any, n: int) -> np.ndarray:
    """``P(X = k)``, ``k = 1..n + 1``, of simple circuits with 2 wall sites of probability
    ``p_wall`` and ``n - 1`` pipe-pipe sites of ``p_pipe`` (float64; one row per pair).

    >>> import symhx
    >>> pmf = model_pmfs([0.02, 0.01], [0.02, 0.02], 100)
    >>> bool(np.all(pmf[0] == symhx.pmf(101, 0.02, np.arange(1, 102), dps=None)))  # eq. (7)
    True
    >>> bool(pmf[1] @ np.arange(1, 102) < pmf[0] @ np.arange(1, 102))   # walls less likely
    True
    """
    pw = np.atleast_1d(np.asarray(p_wall, dtype=float))
    pp = np.atleast_1d(np.asarray(p_pipe, dtype=float))
    k = np.arange(1, n + 2)
    out = np.empty((len(pw), n + 1))
    for j, (a, b) in enumerate(zip(pw, pp, strict=True)):
        if a == b:
            d: Any = SimpleDistribution(n + 1, float(b), dps=None)
        else:
            d = SitesDistribution(n + 1, SiteClasses((2, n - 1), (float(a), float(b))),
                                  dps=None)
        out[j] = d.pmf(k)
    return out


def _distances(sim: SimulatedX, pmfs: np.ndarray) -> tuple[float, float, np.ndarray]:
    k = np.arange(1, sim.n + 2)
    means = pmfs @ k
    ks = np.max(np.abs(sim.cdfs - np.cumsum(pmfs, axis=1)), axis=1)
    return (float(np.sqrt(np.mean((sim.means - means) ** 2))),
            float(np.sqrt(np.mean(ks**2))), means)


def _fit_scale(sim: SimulatedX) -> float:
    """The ``lambda`` of the scaled model minimising the RMS distance of the means."""
    k = np.arange(1, sim.n + 2)

    def rms(loglam: float) -> float:
        pw, pp = _class_p("scaled", sim.sigmas, sim.n, sim.params, sim.ratios, math.exp(loglam))
        return float(np.mean((sim.means - model_pmfs(pw, pp, sim.n) @ k) ** 2))

    lo, hi = (math.log(x) for x in SCALE_BRACKET)
    res = minimize_scalar(rms, bounds=(lo, hi), method="bounded", options={"xatol": 1e-5})
    return math.exp(float(res.x))


def _ratio_of_sigma(sim: SimulatedX) -> Any:
    ok = np.isfinite(sim.ratios)
    xs, ys = sim.sigmas[ok], sim.ratios[ok]
    return lambda s: float(np.interp(s, xs, ys))


def _threshold(model: str, sim: SimulatedX, scale: float) -> float:
    """The ``sigma`` where the model's mode of X leaves 1 (NaN outside the measured range)."""
    n, N = sim.n, sim.n + 1
    forcing = _forcing(sim.params)
    if model == "uniform":
        cp = simple_critical_point(N, dps=20)
        s = sigma_for_impact_probability(float(cp.p), **forcing)
        return float(s)
    ratio = _ratio_of_sigma(sim) if model == "scaled" else None

    def log_tc(s: float) -> float:
        r = None if ratio is None else ratio(s)
        pw, pp = _class_p(model, np.array([s]), n, sim.params, r, scale)
        w = SiteClasses((2, n - 1), (float(pw[0]), float(pp[0])))
        return math.log(float(direction_critical_point(N, w, dps=15).p))

    lo, hi = float(sim.sigmas[0]), float(sim.sigmas[-1])
    a, b = log_tc(lo), log_tc(hi)
    if not (a > 0 > b):
        return math.nan
    return float(brentq(log_tc, lo, hi, xtol=1e-7))


@dataclass(frozen=True, eq=False)
class ModelFit:
    """One model against the simulation (point estimates).

    Attributes
    ----------
    model : str
        ``"uniform"``, ``"geometry"`` or ``"scaled"``.
    scale : float
        ``lambda`` (1 for the models without a fit).
    p_wall, p_pipe : ndarray
        The class probabilities along the kept ``sigma``.
    means : ndarray
        ``E[X]`` per ``sigma``.
    rms_mean : float
        RMS over ``sigma`` of ``mean_sim - E[X]`` (sites).
    rms_ks : float
        RMS over ``sigma`` of the Kolmogorov distance of the distributions.
    threshold : float
        The ``sigma`` where the model's mode of X leaves 1.
    """

    model: str
    scale: float
    p_wall: np.ndarray
    p_pipe: np.ndarray
    means: np.ndarray
    rms_mean: float
    rms_ks: float
    threshold: float


def fit_models(sim: SimulatedX, *, thresholds: bool = True) -> dict[str, ModelFit]:
    """Each model of :data:`MODELS` against ``sim``: its scale, distances and threshold.

    Parameters
    ----------
    sim : SimulatedX
        The simulated side (:func:`simulated_x`).
    thresholds : bool
        Also locate each model's threshold (certified critical points along its path; skip in
        a bootstrap replicate that needs only the distances).

    Returns
    -------
    dict
        Model name -> :class:`ModelFit`.
    """
    if not isinstance(sim, SimulatedX):
        raise TypeError(f"sim must be a SimulatedX (simulated_x), got {type(sim).__name__}")
    out = {}
    for model in MODELS:
        scale = _fit_scale(sim) if model == "scaled" else 1.0
        pw, pp = _class_p(model, sim.sigmas, sim.n, sim.params, sim.ratios, scale)
        rm, rk, means = _distances(sim, model_pmfs(pw, pp, sim.n))
        th = _threshold(model, sim, scale) if thresholds else math.nan
        out[model] = ModelFit(model, scale, pw, pp, means, rm, rk, th)
    return out


@dataclass(frozen=True, eq=False)
class SiteModelComparison:
    """:func:`compare_site_models`'s result.

    Attributes
    ----------
    sim : SimulatedX
        The simulated side.
    fits : dict
        Model name -> :class:`ModelFit` (point estimates).
    boot : dict
        Model name -> bootstrap replicates: ``{"rms_mean": [...], "rms_ks": [...],
        "scale": [...], "threshold": [...]}`` (the simulated threshold under ``"simulation"``).
    seed, replicates : int
        The bootstrap's seed and size.
    """

    sim: SimulatedX
    fits: dict[str, ModelFit]
    boot: dict[str, dict[str, list[float]]]
    seed: int
    replicates: int

    def summary(self) -> dict[str, dict[str, float]]:
        """Per model: point estimates and bootstrap standard deviations (and 16-84 % of the
        threshold)."""
        out = {}
        for m, f in self.fits.items():
            b = self.boot[m]
            th = [x for x in b["threshold"] if math.isfinite(x)]
            out[m] = {"scale": f.scale, "rms_mean": f.rms_mean,
                      "rms_mean_sd": float(np.std(b["rms_mean"], ddof=1)),
                      "rms_ks": f.rms_ks, "rms_ks_sd": float(np.std(b["rms_ks"], ddof=1)),
                      "scale_sd": float(np.std(b["scale"], ddof=1)),
                      "threshold": f.threshold,
                      "threshold_lo": float(np.percentile(th, 16)) if th else math.nan,
                      "threshold_hi": float(np.percentile(th, 84)) if th else math.nan}
        return out

    def as_dict(self) -> dict[str, Any]:
        """JSON form (NaN written as ``None``): the simulated side, each model's point estimates
        and per-sigma values, the bootstrap replicates."""
        def num(x: Any) -> Any:
            return None if isinstance(x, float) and not math.isfinite(x) else x

        def arr(a: Any) -> list[Any]:
            return [num(float(x)) for x in np.asarray(a, dtype=float)]

        sim = self.sim
        return {
            "params": sim.params, "seed": self.seed, "replicates": self.replicates,
            "sigmas": arr(sim.sigmas),
            "simulation": {"means": arr(sim.means), "modes": [int(m) for m in sim.modes],
                           "ratios": arr(sim.ratios), "threshold": num(sim.threshold()),
                           "boot": {"threshold": arr(self.boot["simulation"]["threshold"])}},
            "models": {m: {"scale": f.scale, "rms_mean": f.rms_mean, "rms_ks": f.rms_ks,
                           "threshold": num(f.threshold), "means": arr(f.means),
                           "p_wall": arr(f.p_wall), "p_pipe": arr(f.p_pipe),
                           "boot": {k: arr(v) for k, v in self.boot[m].items()}}
                       for m, f in self.fits.items()},
            "summary": {m: {k: num(v) for k, v in d.items()} for m, d in self.summary().items()},
        }


def compare_site_models(result: SiteHitResult, *, min_kept: int = 20, replicates: int = 100,
                        seed: int = 0, progress: Any = None) -> SiteModelComparison:
    """The three models against a simulation, with a bootstrap of the runs.

    Parameters
    ----------
    result : SiteHitResult
        The per-run record (``symhx/data/ensemble_sites.json``).
    min_kept : int
        Keep the ``sigma`` with at least this many runs with an impact.
    replicates : int
        Bootstrap replicates (each refits ``lambda`` and relocates the thresholds).
    seed : int
        Seed of the bootstrap.
    progress : callable, optional
        Called with the replicate index after each replicate.

    Returns
    -------
    SiteModelComparison

    Raises
    ------
    ValueError, TypeError
        Naming the argument.
    """
    replicates = check_int(replicates, "replicates", minimum=2)
    if replicates > MAX_REPLICATES:
        raise InputError(f"replicates must be <= {MAX_REPLICATES} (the work cap "
                         f"symhx.impact.site_theory.MAX_REPLICATES), got {replicates}")
    seed_i = check_seed(seed)
    if seed_i is None:
        raise TypeError("seed must be an int >= 0 (the bootstrap needs a fixed seed), got None")
    sim = simulated_x(result, min_kept=min_kept)
    fits = fit_models(sim)
    rng = np.random.default_rng(seed_i)
    boot: dict[str, dict[str, list[float]]] = {
        m: {"rms_mean": [], "rms_ks": [], "scale": [], "threshold": []} for m in MODELS}
    boot["simulation"] = {"threshold": []}
    kept = {float(s) for s in sim.sigmas}
    for b in range(replicates):
        tabs = [t.resample(rng) if t.sigma in kept else t for t in result.tables]
        sb = simulated_x(result, min_kept=1, tables=[t for t in tabs if t.sigma in kept])
        for m, f in fit_models(sb).items():
            boot[m]["rms_mean"].append(f.rms_mean)
            boot[m]["rms_ks"].append(f.rms_ks)
            boot[m]["scale"].append(f.scale)
            boot[m]["threshold"].append(f.threshold)
        boot["simulation"]["threshold"].append(sb.threshold())
        if progress is not None:
            progress(b)
    return SiteModelComparison(sim, fits, boot, seed_i, replicates)
