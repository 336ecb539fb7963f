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

from __future__ import annotations

import importlib
from typing import Any

__version__ = "0.1.0"

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
    # distribution
    "Distribution": "distribution",
    "distribution_of": "distribution",
    "pmf": "distribution",
    "logpmf": "distribution",
    "normaliser": "distribution",
    "mean": "distribution",
    "variance": "distribution",
    "mode": "distribution",
    "modes": "distribution",
    # critical
    "discriminant_root": "critical",
    "critical_point": "critical",
    "CriticalPoint": "critical",
    "mode_path": "critical",
    "ModePath": "critical",
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
    "theory_curve": "forcing",
    "TheoryCurve": "forcing",
    # impact simulation (eqs. 17-21)
    "PipeRow": "impact",
    "simulate": "impact",
    "ensemble": "impact",
    "EnsembleResult": "impact",
    "History": "impact",
    "free_flight_closure_fraction": "impact",
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


def __getattr__(name: str) -> Any:
    try:
        module = _EXPORTS[name]
    except KeyError:
        raise AttributeError(f"module 'symhx' has no attribute {name!r}") from None
    value = getattr(importlib.import_module(f"symhx.{module}"), name)
    globals()[name] = value
    return value


def __dir__() -> list[str]:
    return sorted(set(globals()) | set(_EXPORTS))
