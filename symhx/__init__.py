"""symhx: exact, symbolic and asymptotic analysis of a graph-theory + probability model of
impact dynamics in heat exchangers (rows of vibrating pipes that knock into their neighbours).

Conventions (see the book, chapter "Conventions"):

* ``n`` pipes in a row between two walls give ``N = n + 1`` possible impacts, the vertices of the
  complete directed graph with self-loops.
* A circuit is a closed walk up to rotation; its *length* is its number of impacts per period and
  ``k`` is its number of *distinct* impacts (``k == length`` for a simple circuit).
* ``X`` is the number of distinct impacts of a circuit drawn with weight ``p**length``.

Public names are loaded lazily, so ``import symhx`` is cheap and never imports sympy or
matplotlib.

>>> import symhx
>>> symhx.phi(5, 3)
20
>>> symhx.mode(101, 0.02)
51
"""


import importlib as _importlib
from typing import Any as _Any

__version__ = "0.2.0"

# public name -> module that defines it
_EXPORTS: dict[str, str] = {
    # graph
    "vertices_row": "graph",
    "vertices_lattice": "graph",
    "impacts_from_pipes": "graph",
    # circuits
    "phi": "circuits",
    "log_phi": "circuits",
    "circuit_count": "circuits",
    "circuits_of_length": "circuits",
    "total_simple_circuits": "circuits",
    "enumerate_circuits": "circuits",
    # distributions (frozen objects and scipy.stats-style functions: symhx.api)
    "Distribution": "distribution",
    "distribution_of": "api",
    "pmf": "api",
    "logpmf": "api",
    "cdf": "api",
    "logcdf": "api",
    "sf": "api",
    "logsf": "api",
    "ppf": "api",
    "isf": "api",
    "mean": "api",
    "var": "api",
    "std": "api",
    "median": "api",
    "entropy": "api",
    "interval": "api",
    "rvs": "api",
    "normaliser": "api",
    "variance": "api",
    "mode": "api",
    "modes": "api",
    # critical point
    "critical_point": "api",
    "CriticalPoint": "critical",
    "discriminant_root": "critical",
    "mode_path": "critical",
    "ModePath": "critical",
    # per-site probabilities (issue 30)
    "SiteClasses": "sites",
    "SitesDistribution": "site_distribution",
    "DirectionCriticalPoint": "critical_sites",
    "CriticalCurve": "critical_sites",
    "critical_curve": "critical_sites",
    # asymptotics (mpmath only; the sympy derivations live in symhx.symbolic)
    "asymptotic_critical_point": "asymptotics",
    "AsymptoticCriticalPoint": "asymptotics",
    "pd_series": "asymptotics",
    "error_table": "asymptotics",
    # forcing (eqs. 22-27)
    "impact_probability": "forcing",
    "no_impact_probability": "forcing",
    "log_impact_probability": "forcing",
    "log_no_impact_probability": "forcing",
    "naive_impact_probability": "forcing",
    "dp_dsigma": "forcing",
    "sigma_for_impact_probability": "forcing",
    "rayleigh_scales": "forcing",
    "rayleigh_sum_probability": "forcing",
    "RayleighSumResult": "forcing",
    "RayleighSum": "forcing",
    "ForcingParams": "forcing",
    "theory_curve": "forcing",
    "TheoryCurve": "forcing",
    # impact simulation (eqs. 17-21)
    "PipeRow": "impact",
    "simulate": "impact",
    "ensemble": "impact",
    "EnsembleResult": "impact",
    "History": "impact",
    "free_flight_closure_fraction": "impact",
    "SimulationError": "impact",
    # higher-order sample spaces (section 8)
    "class_count": "spaces",
    "class_decomposition": "spaces",
    "class_probabilities": "spaces",
    "convergence_study": "spaces",
    "pattern_count_symbolic": "spaces",
    "parse_space": "spaces",
    "eq41_terms": "spaces",
}

__all__ = sorted(_EXPORTS)


def __getattr__(name: str) -> _Any:
    try:
        module = _EXPORTS[name]
    except KeyError:
        raise AttributeError(f"module 'symhx' has no attribute {name!r}") from None
    value = getattr(_importlib.import_module(f"symhx.{module}"), name)
    globals()[name] = value
    return value


def __dir__() -> list[str]:
    """The public names only (``__version__`` and the lazily loaded API)."""
    return sorted({"__version__", *_EXPORTS})
