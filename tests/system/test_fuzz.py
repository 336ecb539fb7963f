"""Fuzz test of every public function and every CLI command with hostile inputs (issue 12).

Contract checked for each call: it returns a correct-looking value (no NaN anywhere in it) or raises
ValueError/TypeError; it finishes within :data:`TIME_LIMIT` seconds; it leaves ``mpmath.mp.dps``
unchanged.  For a hostile value that is *not allowed* for the argument's role (NaN, infinities,
bools, negatives where only positives make sense, dps outside ``[1, MAX_DPS]``, ...) returning a
value is a failure too (a silent wrong answer).  A CLI command must exit 0, or exit 2 with exactly
one ``error:`` line on stderr and no traceback; a value that is not allowed must exit 2.

Calls run in a forked child process (one per batch of calls), each under a SIGALRM time limit; a
call stuck in C code (big-int arithmetic, for example) is killed by the parent and reported as a
hang, and the batch continues after it.  Every failure of a function or command is collected and
reported together (``pytest -m fuzz tests/system/test_fuzz.py``).

The table :data:`API` gives, for every name in ``symhx.__all__`` and ``symhx.impact.__all__``, a
valid call and the *role* of each argument; :data:`NOT_CALLABLE` lists the names that are result
classes or constants, each with the reason.  ``test_every_public_name_is_covered`` fails when a new
public name is added without an entry.

Hostile values come one at a time (every argument against every value), several at once
(hypothesis draws, the same examples on every run: see tests/conftest.py), and as *interactions*
(issue 28): two extreme but allowed arguments at once, such as a negligible Rayleigh scale next to
a normal one, a huge ``N`` with ``p`` above ``p_c``, an irrational ``p`` near a tie of the modes
or a huge ``N`` with a tiny ``dps``, whose answers must also satisfy the identities of their
quantity (``cdf + sf = 1``, the modes of an exact reference, the digits asked for).  Every
case must pass: none is marked as a known failure.
"""

from __future__ import annotations

import ast
import contextlib
import io
import math
import os
import pickle
import select
import signal
import struct
import time
import traceback
from collections.abc import Callable, Iterator
from dataclasses import dataclass, fields, is_dataclass
from decimal import Decimal
from fractions import Fraction
from typing import Any

import mpmath
import numpy as np
import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

import symhx
import symhx.impact

pytestmark = [
    pytest.mark.fuzz,
    # the deprecated alias is fuzzed like every public name; its warning is tested elsewhere
    pytest.mark.filterwarnings("ignore:symhx.variance is deprecated:DeprecationWarning"),
]

TIME_LIMIT = 2.0  # seconds per call (SIGALRM in the child; the parent kills it 1 s later)
KILL_GRACE = 1.0

# --------------------------------------------------------------------------- hostile values
_NAN = float("nan")


class _Weird:
    """An object that is no number at all."""

    def __repr__(self) -> str:
        return "<weird object>"


HOSTILE: dict[str, Any] = {
    "nan": _NAN,
    "inf": math.inf,
    "-inf": -math.inf,
    "np.nan": np.float64("nan"),
    "mpf nan": mpmath.mpf("nan"),
    "mpf -inf": mpmath.mpf("-inf"),
    "Decimal nan": Decimal("nan"),
    "0": 0,
    "0.0": 0.0,
    "-1": -1,
    "-3.5": -3.5,
    "mpf -0.1": mpmath.mpf("-0.1"),
    "True": True,
    "False": False,
    "np.True_": np.True_,
    "10**1000": 10**1000,
    "-10**1000": -(10**1000),
    "2.5": 2.5,
    "1e308": 1e308,
    "5e-324": 5e-324,
    "'abc'": "abc",
    "''": "",
    "'1/0'": "1/0",
    "'nan'": "nan",
    "'1e-400'": "1e-400",
    "None": None,
    "[]": [],
    "[1, 'a', nan]": [1, "a", _NAN],
    "np.array([])": np.array([]),
    "1j": 1j,
    "np.int64(-1)": np.int64(-1),
    "np.int64(7)": np.int64(7),
    "np.float32(0.1)": np.float32(0.1),
    "object": _Weird(),
    "10**6": 10**6,
}

_NOT_REAL = {"'abc'", "''", "'1/0'", "'nan'", "None", "[]", "[1, 'a', nan]", "np.array([])", "1j",
             "object", "True", "False", "np.True_"}
_NONFINITE = {"nan", "inf", "-inf", "np.nan", "mpf nan", "mpf -inf", "Decimal nan"}
_NEGATIVE = {"-1", "-3.5", "mpf -0.1", "-10**1000", "np.int64(-1)"}
_NON_INTEGRAL = {"2.5", "1e308", "5e-324", "0.0", "np.float32(0.1)", "'1e-400'", "-3.5",
                 "mpf -0.1"} | _NONFINITE
_ZERO = {"0", "0.0"}

#: role -> labels of HOSTILE that must be refused with ValueError/TypeError
REJECT: dict[str, set[str]] = {
    # a number of vertices / pipes / a count: an int >= 1 (or 2)
    "N": _NOT_REAL | _NON_INTEGRAL | _NEGATIVE | _ZERO,
    # an int that may be zero or negative where documented (phi(N, 0) == 0)
    "int": _NOT_REAL | _NON_INTEGRAL,
    # an int >= 0 (seeds, counts)
    "count": _NOT_REAL | _NON_INTEGRAL | _NEGATIVE,
    # a probability p > 0 (p > 1 allowed but unphysical)
    "p": _NOT_REAL | _NONFINITE | _NEGATIVE | _ZERO,
    # a probability strictly inside (0, 1) (inverse problems)
    "p01": _NOT_REAL | _NONFINITE | _NEGATIVE | _ZERO | {"2.5", "1e308", "10**1000", "np.int64(7)",
                                                         "10**6"},
    # a finite positive real (scales, spacings, frequencies, durations)
    "positive": _NOT_REAL | _NONFINITE | _NEGATIVE | _ZERO,
    # a finite real >= 0 (sigma: 0 means no forcing)
    "nonneg": _NOT_REAL | _NONFINITE | _NEGATIVE,
    # a finite positive real or None (optional parameter)
    "positive?": (_NOT_REAL - {"None"}) | _NONFINITE | _NEGATIVE | _ZERO,
    # a restitution coefficient in (0, 1]
    "restitution": _NOT_REAL | _NONFINITE | _NEGATIVE | _ZERO | {"2.5", "1e308", "10**1000",
                                                                 "np.int64(7)", "10**6"},
    # precision: an int in [1, MAX_DPS]
    "dps": _NOT_REAL | _NON_INTEGRAL | _NEGATIVE | _ZERO | {"10**1000", "10**6"},
    # precision or None for float64
    "dps?": (_NOT_REAL - {"None"}) | _NON_INTEGRAL | _NEGATIVE | _ZERO | {"10**1000", "10**6"},
    # a sample space name (str) or a word from a fixed list
    "choice": set(HOSTILE) - set(),
    # an optional choice (None = default)
    "choice?": set(HOSTILE) - {"None"},
    # an int or None
    "int?": (_NOT_REAL - {"None"}) | _NON_INTEGRAL | _NEGATIVE | _ZERO,
    "seed": (_NOT_REAL - {"None"}) | _NON_INTEGRAL | _NEGATIVE,
    # sequences (of positive reals, of visit multiplicities, ...)
    "array+": set(HOSTILE) - {"np.int64(7)"},  # a scalar may be read as a one-element array
    "visits": set(HOSTILE),
    "shape": set(HOSTILE) - {"[]", "np.array([])"},  # () is the class of simple circuits
    "ints": set(HOSTILE) - {"[]", "np.array([])"},
    # per-site probabilities / weights: a SiteClasses or a sequence (None: the scalar path)
    "sites": set(HOSTILE) - {"None"},
    # optional class names: a sequence of distinct non-empty str, or None
    "names?": set(HOSTILE) - {"None"},
    "row": set(HOSTILE),
    "bool": set(HOSTILE) - {"True", "False", "np.True_"},
}
# Vectorised arguments (float64 paths) broadcast like numpy/scipy: an empty array in gives an
# empty array out (documented), so the empties are not refused there.
_EMPTIES = {"[]", "np.array([])"}
for _role in ("p", "nonneg", "positive", "positive?", "p01"):
    REJECT[_role + "[]"] = REJECT[_role] - _EMPTIES
# any finite real (a threshold x of a distribution: x <= 0 is allowed, sf(x) = 1 there)
REJECT["real"] = _NOT_REAL | _NONFINITE
REJECT["real[]"] = REJECT["real"] - _EMPTIES
# a restitution coefficient in [0, 1] (0: plastic impacts, supported by both engines)
REJECT["restitution0"] = REJECT["restitution"] - _ZERO
# a flag that may also be None (ensemble's progress: None = only when stderr is a terminal)
REJECT["bool?"] = REJECT["bool"] - {"None"}
# a probability level in [0, 1] (quantiles: ppf(0) = 0, ppf(1) = N; interval(0) is a point)
REJECT["q"] = REJECT["p01"] - _ZERO
REJECT["q[]"] = REJECT["q"] - _EMPTIES
# an optional sample size (None: one draw; 0: an empty sample, as numpy)
REJECT["size?"] = (_NOT_REAL - {"None"}) | _NON_INTEGRAL | _NEGATIVE | {"10**1000"}


@dataclass(frozen=True)
class Entry:
    """A public callable, one valid call (``kwargs``) and the role of each argument."""

    name: str
    func: Callable[..., Any]
    kwargs: dict[str, Any]
    roles: dict[str, str]


def _row() -> Any:
    return symhx.PipeRow.random(3, 0.3, seed=1)


_FORCING = {"sigma": 0.3, "sigma1": None, "omega": 1, "Omega": None, "d": 1, "dps": None}
_FORCING_ROLES = {"sigma": "nonneg[]", "sigma1": "positive?[]", "omega": "positive[]",
                  "Omega": "positive?", "d": "positive[]", "dps": "dps?"}


def _entries() -> list[Entry]:
    s = symhx
    E = Entry
    out = [
        E("asymptotic_critical_point", s.asymptotic_critical_point,
          {"N": 10**6, "order": "best", "dps": 20}, {"N": "N", "order": "choice", "dps": "dps"}),
        E("circuit_count", s.circuit_count, {"N": 5, "visits": (2, 1)},
          {"N": "N", "visits": "visits"}),
        E("circuits_of_length", s.circuits_of_length, {"N": 4, "L": 3}, {"N": "N", "L": "N"}),
        E("class_count", s.class_count, {"N": 10, "shape": (2,), "k": 3},
          {"N": "N", "shape": "shape", "k": "int"}),
        E("class_decomposition", s.class_decomposition,
          {"N": 10, "p": "0.1", "space": "eq41", "dps": 20},
          {"N": "N", "p": "p", "space": "choice", "dps": "dps"}),
        E("class_probabilities", s.class_probabilities,
          {"N": 10, "p": "0.1", "space": "eq41", "dps": 20},
          {"N": "N", "p": "p", "space": "choice", "dps": "dps"}),
        E("convergence_study", s.convergence_study,
          {"N": 20, "ms": (0, 1), "ps": ("0.01",), "dps": 15, "extra": (), "weighting": "length"},
          {"N": "N", "ms": "ints", "ps": "array+", "dps": "dps", "weighting": "choice"}),
        E("critical_point", s.critical_point, {"N": 20, "dps": 20, "space": "simple"},
          {"N": "N", "dps": "dps?", "space": "choice"}),
        E("critical_point(weights)", s.critical_point,
          {"N": 20, "weights": s.SiteClasses((2, 18), ("1/2", 1)), "dps": 20},
          {"N": "N", "weights": "sites", "dps": "dps?"}),
        E("critical_curve", s.critical_curve,
          {"N": 20, "sizes": (2, 18), "directions": 2, "names": None, "dps": 15},
          {"N": "N", "sizes": "ints", "directions": "N", "names": "names?", "dps": "dps"}),
        E("SiteClasses", s.SiteClasses,
          {"sizes": (2, 18), "probabilities": ("0.1", 0.2), "names": None},
          {"sizes": "ints", "probabilities": "sites", "names": "names?"}),
        E("discriminant_root", s.discriminant_root, {"N": 20, "dps": 20},
          {"N": "N", "dps": "dps"}),
        E("distribution_of", s.distribution_of, {"N": 20, "p": "0.1", "space": "simple", "dps": 20},
          {"N": "N", "p": "p", "space": "choice", "dps": "dps?"}),
        E("enumerate_circuits", s.enumerate_circuits, {"N": 3, "L": 3}, {"N": "N", "L": "N"}),
        E("eq41_terms", s.eq41_terms, {"N": 10, "k": 3}, {"N": "N", "k": "int"}),
        E("error_table", s.error_table,
          {"Ns": (1000,), "dps": 20, "orders": ("leading",), "pd_terms": 2},
          {"Ns": "ints", "dps": "dps", "orders": "ints", "pd_terms": "N"}),
        E("ensemble", s.ensemble,
          {"sigmas": [0.5], "runs": 2, "n": 3, "t_transient": 20.0, "t_window": 20.0, "seed": 0,
           "progress": False},
          {"sigmas": "array+", "runs": "N", "n": "N", "t_transient": "nonneg",
           "t_window": "positive", "seed": "seed", "progress": "bool?"}),
        E("free_flight_closure_fraction", s.free_flight_closure_fraction,
          {"sigma": 0.3, "gaps": 3, "horizon": 10.0, "seed": 0},
          {"sigma": "positive", "gaps": "N", "horizon": "positive", "seed": "seed"}),
        E("log_phi", s.log_phi, {"N": 10, "k": 3, "dps": 20}, {"N": "N", "k": "N", "dps": "dps"}),
        E("logpmf", s.logpmf, {"N": 10, "p": "0.1", "k": 3, "space": "simple", "dps": 20},
          {"N": "N", "p": "p[]", "k": "int", "space": "choice", "dps": "dps?"}),
        E("mode", s.mode, {"N": 10, "p": "0.1", "space": "simple"},
          {"N": "N", "p": "p[]", "space": "choice"}),
        E("modes", s.modes, {"N": 10, "p": "0.1", "space": "simple"},
          {"N": "N", "p": "p[]", "space": "choice"}),
        E("mode_path", s.mode_path, {"N": 10, "p_max": 1, "dps": 20},
          {"N": "N", "p_max": "p", "dps": "dps"}),
        E("naive_impact_probability", s.naive_impact_probability,
          {"sigma": 0.3, "sigma1": None, "omega": 1, "Omega": None, "d": 1},
          {k: v for k, v in _FORCING_ROLES.items() if k != "dps"}),
        E("parse_space", s.parse_space, {"space": "eq41", "weighting": None},
          {"space": "choice", "weighting": "choice?"}),
        E("pattern_count_symbolic", s.pattern_count_symbolic, {"visits": (2, 1)},
          {"visits": "visits"}),
        E("pd_series", s.pd_series, {"N": 1000, "n_terms": 3, "dps": 20},
          {"N": "N", "n_terms": "N", "dps": "dps"}),
        E("phi", s.phi, {"N": 10, "k": 3}, {"N": "N", "k": "int"}),
        E("pmf", s.pmf, {"N": 10, "p": "0.1", "k": 3, "space": "simple", "dps": 20},
          {"N": "N", "p": "p[]", "k": "int", "space": "choice", "dps": "dps?"}),
        E("rayleigh_scales", s.rayleigh_scales,
          {k: v for k, v in _FORCING.items() if k != "d"},
          {k: v for k, v in _FORCING_ROLES.items() if k != "d"}),
        E("rayleigh_sum_probability", s.rayleigh_sum_probability,
          {"scales": [0.5, 0.3], "d": 1, "tail": "upper", "dps": None},
          {"scales": "array+", "d": "positive", "tail": "choice", "dps": "dps?"}),
        E("RayleighSum", s.RayleighSum, {"scales": [0.5, 0.3]}, {"scales": "array+"}),
        E("RayleighSum.probability", s.RayleighSum([0.5, 0.3, 0.2]).probability,
          {"x": 1.0, "tail": "upper", "dps": None}, {"x": "real", "tail": "choice", "dps": "dps?"}),
        E("RayleighSum.sf()", s.RayleighSum([0.5, 0.3]).sf, {"x": [0.5, 1.0], "dps": None},
          {"x": "real[]", "dps": "dps?"}),
        E("ForcingParams.validated", s.ForcingParams.validated, dict(_FORCING),
          dict(_FORCING_ROLES)),
        E("sigma_for_impact_probability", s.sigma_for_impact_probability,
          {**{k: v for k, v in _FORCING.items() if k != "sigma"}, "p": 0.1},
          {**{k: v for k, v in _FORCING_ROLES.items() if k != "sigma"}, "p": "p01[]"}),
        E("simulate", s.simulate,
          {"row": "ROW", "t_end": 5.0, "dps": None, "v_stick": None, "max_events": None,
           "engine": "auto"},
          {"row": "row", "t_end": "positive", "dps": "dps?", "v_stick": "positive?",
           "max_events": "int?", "engine": "choice"}),
        E("theory_curve", s.theory_curve,
          {"sigma": [0.2, 0.3], "N": 11, "space": "simple", "dps": 15},
          {"sigma": "positive[]", "N": "N", "space": "choice", "dps": "dps"}),
        E("total_simple_circuits", s.total_simple_circuits, {"N": 10}, {"N": "N"}),
        E("vertices_lattice", s.vertices_lattice, {"m": 3}, {"m": "N"}),
        E("vertices_row", s.vertices_row, {"n": 3}, {"n": "N"}),
        E("impacts_from_pipes", s.impacts_from_pipes, {"n": 3}, {"n": "N"}),
        E("PipeRow.random", s.PipeRow.random,
          {"n": 3, "sigma": 0.3, "seed": 1, "restitution": 0.8, "omega": 1.0, "d": 1.0},
          {"n": "N", "sigma": "nonneg", "seed": "seed", "restitution": "restitution0",
           "omega": "positive", "d": "positive"}),
        E("impact.default_v_stick", symhx.impact.default_v_stick, {"row": "ROW", "dps": None},
          {"row": "row", "dps": "dps?"}),
        E("impact.work_dps", symhx.impact.work_dps, {"dps": 20}, {"dps": "dps"}),
    ]
    for name in ("impact_probability", "no_impact_probability", "log_impact_probability",
                 "log_no_impact_probability", "dp_dsigma"):
        out.append(E(name, getattr(s, name), dict(_FORCING), dict(_FORCING_ROLES)))
    for name in ("mean", "variance", "normaliser", "var", "std", "entropy", "median"):
        out.append(E(name, getattr(s, name), {"N": 10, "p": "0.1", "space": "simple", "dps": 20},
                     {"N": "N", "p": "p[]", "space": "choice", "dps": "dps?"}))
    for name in ("cdf", "sf", "logcdf", "logsf"):  # like pmf: k any int (cdf(0) = 0)
        out.append(E(name, getattr(s, name),
                     {"N": 10, "p": "0.1", "k": 3, "space": "simple", "dps": 20},
                     {"N": "N", "p": "p[]", "k": "int", "space": "choice", "dps": "dps?"}))
    for name in ("ppf", "isf"):
        out.append(E(name, getattr(s, name),
                     {"N": 10, "p": "0.1", "q": "0.3", "space": "simple", "dps": 20},
                     {"N": "N", "p": "p[]", "q": "q[]", "space": "choice", "dps": "dps?"}))
    out.append(E("interval", s.interval,
                 {"N": 10, "p": "0.1", "confidence": "0.9", "space": "simple", "dps": 20},
                 {"N": "N", "p": "p", "confidence": "q", "space": "choice", "dps": "dps?"}))
    out.append(E("rvs", s.rvs,
                 {"N": 10, "p": 0.1, "size": 3, "random_state": 1, "space": "simple"},
                 {"N": "N", "p": "p", "size": "size?", "random_state": "seed",
                  "space": "choice"}))
    return out


API = _entries()

#: public names that are not functions to fuzz, with the reason
NOT_CALLABLE = {
    "AsymptoticCriticalPoint": "result class, built by asymptotic_critical_point",
    "CriticalPoint": "result class, built by critical_point",
    "CriticalCurve": "result class, built by critical_curve",
    "DirectionCriticalPoint": "result class, built by critical_point(N, weights=...)",
    "SitesDistribution": "result class, built by distribution_of with site classes (fuzzed "
                         "through the site interactions)",
    "Distribution": "result class, built by distribution_of",
    "EnsembleResult": "result class, built by ensemble",
    "History": "result class, built by simulate",
    "ModePath": "result class, built by mode_path",
    "RayleighSumResult": "result class, built by rayleigh_sum_probability",
    "ForcingParams": "value object; its constructor is fuzzed as ForcingParams.validated",
    "TheoryCurve": "result class, built by theory_curve",
    "SigmaStats": "result class, built by ensemble",
    "PipeRow": "fuzzed through PipeRow.random",
    "GRAZE": "constant",
    "IMPACT": "constant",
    "KIND_NAMES": "constant",
    "RELEASE": "constant",
    "SQRT2": "constant",
    "STICK": "constant",
    "default_v_stick": "fuzzed as impact.default_v_stick",
    "EventKind": "enum of event kinds (IMPACT, GRAZE, STICK, RELEASE), a class",
    "SimulationError": "exception class raised by the impact engines",
    "InputError": "exception class (a ValueError) of every refused input",
    "work_dps": "fuzzed as impact.work_dps",
}


# --------------------------------------------------------------------------- isolated runner
class _CallTimeout(BaseException):
    pass


def _has_nan(x: Any, depth: int = 0) -> bool:
    """True if a NaN hides anywhere in a result (numbers, arrays, containers, dataclasses)."""
    if depth > 6:
        return False
    if isinstance(x, (bool, int, str, Fraction)) or x is None:
        return False
    if isinstance(x, float):
        return math.isnan(x)
    if isinstance(x, mpmath.mpf):
        return bool(mpmath.isnan(x))
    if isinstance(x, mpmath.mpc):
        return bool(mpmath.isnan(x.real) or mpmath.isnan(x.imag))
    if isinstance(x, np.ndarray):
        if x.dtype.kind in "fc":
            return bool(np.isnan(x).any())
        if x.dtype.kind == "O":
            return any(_has_nan(v, depth + 1) for v in x.ravel()[:1000])
        return False
    if isinstance(x, np.generic):
        return bool(np.isnan(x)) if x.dtype.kind in "fc" else False
    if isinstance(x, dict):
        return any(_has_nan(v, depth + 1) for v in list(x.values())[:1000])
    if isinstance(x, (list, tuple)):
        return any(_has_nan(v, depth + 1) for v in x[:1000])
    if is_dataclass(x):
        return any(_has_nan(getattr(x, f.name, None), depth + 1) for f in fields(x))
    return False


def _one_call(thunk: Callable[[], Any]) -> dict[str, Any]:
    before = mpmath.mp.dps
    t0 = time.perf_counter()
    signal.setitimer(signal.ITIMER_REAL, TIME_LIMIT)
    try:
        res = thunk()
        if isinstance(res, Iterator):
            res = [x for _, x in zip(range(100_000), res, strict=False)]
        out = {"kind": "value", "nan": _has_nan(res), "repr": repr(res)[:120]}
    except _CallTimeout:
        out = {"kind": "timeout"}
    except (ValueError, TypeError) as exc:
        out = {"kind": "error", "type": type(exc).__name__, "msg": str(exc)[:200]}
    except BaseException as exc:
        tb = traceback.extract_tb(exc.__traceback__)[-1]
        out = {"kind": "crash", "type": type(exc).__name__, "msg": str(exc)[:200],
               "where": f"{os.path.basename(tb.filename)}:{tb.lineno}"}
    finally:
        signal.setitimer(signal.ITIMER_REAL, 0)
    out["seconds"] = round(time.perf_counter() - t0, 3)
    out["dps_changed"] = mpmath.mp.dps != before
    mpmath.mp.dps = before
    return out


def _send(fd: int, obj: Any) -> None:
    data = pickle.dumps(obj)
    os.write(fd, struct.pack("!I", len(data)) + data)


def _alarm(signum: int, frame: Any) -> None:
    raise _CallTimeout


_WARM: list[bool] = []


def _warm_up() -> None:
    """Run every valid call once in this process, so that lazy imports (scipy, sympy, the C
    engine) happen before forking: an import in a forked child is slow and may fail."""
    if _WARM:
        return
    _WARM.append(True)
    for entry in API:
        with contextlib.suppress(Exception):
            res = _call(entry, {})()
            if isinstance(res, Iterator):
                list(res)
    # the Laplace-transform inversion of three or more Rayleigh scales builds its Taylor table
    # of L(z) once a process (~0.3 s) and imports python-flint: before forking, too
    with contextlib.suppress(Exception):
        symhx.RayleighSum([1.0, 0.5, 0.25]).sf(1.0)
        symhx.RayleighSum([1.0, 0.5, 0.25]).sf(1.0, dps=20)
    import tempfile

    from symhx.cli import main

    here = os.getcwd()
    with tempfile.TemporaryDirectory() as tmp:
        os.chdir(tmp)
        try:
            for command, (template, _) in CLI.items():
                if command == "paper":  # the valid call is the whole paper job
                    continue
                argv = [a.format(**dict(CLI_VALID, path=os.path.join(tmp, "out")))
                        for a in template]
                with (contextlib.suppress(BaseException),
                      contextlib.redirect_stdout(io.StringIO()),
                      contextlib.redirect_stderr(io.StringIO())):
                    main(argv)
        finally:
            os.chdir(here)


def run_isolated(thunks: list[Callable[[], Any]]) -> list[dict[str, Any]]:
    """Run each thunk in a forked child (one child per batch), each under the time limit."""
    _warm_up()
    results: list[dict[str, Any] | None] = [None] * len(thunks)
    start = 0
    while start < len(thunks):
        r, w = os.pipe()
        pid = os.fork()
        if pid == 0:  # child
            os.close(r)
            code = 0
            try:
                signal.signal(signal.SIGALRM, _alarm)
                with open(os.devnull, "w") as devnull, contextlib.redirect_stderr(devnull):
                    for i in range(start, len(thunks)):
                        _send(w, ("start", i))
                        _send(w, ("done", i, _one_call(thunks[i])))
            except BaseException:
                code = 1
            finally:
                os._exit(code)
        os.close(w)
        buf = b""
        current, t_start = start, time.monotonic()
        killed = False
        while True:
            left = TIME_LIMIT + KILL_GRACE - (time.monotonic() - t_start)
            ready, _, _ = select.select([r], [], [], max(left, 0))
            if not ready:
                os.kill(pid, signal.SIGKILL)
                results[current] = {"kind": "hang", "seconds": TIME_LIMIT + KILL_GRACE,
                                    "dps_changed": False}
                killed = True
                break
            chunk = os.read(r, 65536)
            if not chunk:
                break
            buf += chunk
            while len(buf) >= 4:
                (n,) = struct.unpack("!I", buf[:4])
                if len(buf) < 4 + n:
                    break
                msg, buf = pickle.loads(buf[4:4 + n]), buf[4 + n:]
                if msg[0] == "start":
                    current, t_start = msg[1], time.monotonic()
                else:
                    results[msg[1]] = msg[2]
        os.close(r)
        os.waitpid(pid, 0)
        if results[current] is None and not killed:
            results[current] = {"kind": "crash", "type": "child died", "msg": "",
                                "dps_changed": False, "seconds": 0}
        start = current + 1
    return [x if x is not None else {"kind": "skipped"} for x in results]


def _verdict(res: dict[str, Any], must_reject: bool) -> str | None:
    """None if the outcome meets the contract, else a one-line description of the failure."""
    if res["dps_changed"]:
        return "changed mpmath.mp.dps"
    kind = res["kind"]
    if kind in ("timeout", "hang"):
        return f"no answer within {TIME_LIMIT} s ({kind})"
    if kind == "crash":
        return f"raised {res['type']}: {res['msg'][:100]} ({res.get('where', '')})"
    if kind == "error":
        return None
    if kind == "value":
        if must_reject:
            return f"returned a value instead of an error: {res['repr'][:80]}"
        if res["nan"]:
            return f"returned NaN: {res['repr'][:80]}"
        return None
    return f"unexpected outcome {res}"


def _call(entry: Entry, override: dict[str, Any]) -> Callable[[], Any]:
    def thunk() -> Any:
        kw = {**entry.kwargs, **override}
        for k, v in kw.items():
            if isinstance(v, str) and v == "ROW":
                kw[k] = _row()
        return entry.func(**kw)

    return thunk


# --------------------------------------------------------------------------- API tests
def test_every_public_name_is_covered():
    names = {e.name.split(".")[-1] for e in API}
    missing = [n for n in (*symhx.__all__, *symhx.impact.__all__)
               if n not in names and n not in NOT_CALLABLE]
    assert not missing, f"public names without a fuzz table entry: {missing}"


@pytest.mark.parametrize("entry", API, ids=[e.name for e in API])
def test_valid_call_works(entry: Entry):
    """The table's valid call itself must work (otherwise the fuzz below proves nothing)."""
    (res,) = run_isolated([_call(entry, {})])
    assert res["kind"] == "value" and not res["nan"] and not res["dps_changed"], res


@pytest.mark.parametrize("entry", API, ids=[e.name for e in API])
def test_hostile_single_argument(entry: Entry):
    """Every argument of every public function against every hostile value, one at a time."""
    cases = [(arg, label) for arg in entry.roles for label in HOSTILE]
    results = run_isolated([_call(entry, {arg: HOSTILE[label]}) for arg, label in cases])
    failures = []
    for (arg, label), res in zip(cases, results, strict=True):
        bad = _verdict(res, label in REJECT[entry.roles[arg]])
        if bad:
            failures.append(f"{entry.name}({arg}={label}): {bad}")
    assert not failures, f"{len(failures)} failures:\n" + "\n".join(failures)


_LABELS = sorted(HOSTILE)


# The same examples on every run (tests/conftest.py's deterministic profile; fresh draws are an
# opt-in there), so a stop is judged on what was run before it.
@settings(max_examples=30, deadline=None, suppress_health_check=list(HealthCheck))
@given(data=st.data())
def test_hostile_combinations(data):
    """Random functions with several arguments hostile at once, plus random floats and ints."""
    entry = data.draw(st.sampled_from(API), label="function")
    args = data.draw(st.lists(st.sampled_from(sorted(entry.roles)), min_size=1, max_size=3,
                              unique=True), label="arguments")
    override, must_reject = {}, False
    for arg in args:
        value = data.draw(st.one_of(
            st.sampled_from(_LABELS).map(lambda k: ("hostile", k)),
            st.floats(allow_nan=True, allow_infinity=True).map(lambda x: ("float", x)),
            st.integers(min_value=-(10**30), max_value=10**30).map(lambda x: ("int", x)),
        ), label=arg)
        if value[0] == "hostile":
            override[arg] = HOSTILE[value[1]]
            must_reject |= value[1] in REJECT[entry.roles[arg]]
        else:
            override[arg] = value[1]
            if value[0] == "float" and not math.isfinite(value[1]):
                must_reject |= entry.roles[arg] not in ("choice", "choice?")
    (res,) = run_isolated([_call(entry, override)])
    bad = _verdict(res, must_reject)
    assert bad is None, f"{entry.name}({override!r}): {bad}"


# --------------------------------------------------------------------------- CLI
#: command -> (valid argv, {placeholder position or option: role})
CLI: dict[str, tuple[list[str], dict[str, str]]] = {
    "critical": (["critical", "{N}", "--dps", "{dps}"], {"N": "N", "dps": "dps"}),
    "distribution": (["distribution", "{N}", "{p}", "--dps", "{dps}", "--space", "{space}"],
                     {"N": "N", "p": "p", "dps": "dps", "space": "choice"}),
    "distribution --float": (["distribution", "{N}", "{p}", "--float"], {"N": "N", "p": "p"}),
    "circuits": (["circuits", "{N}", "--visits", "{visits}"], {"N": "N", "visits": "visits"}),
    "circuits --length": (["circuits", "{N}", "--length", "{L}"], {"N": "N", "L": "N"}),
    "mode-path": (["mode-path", "{N}", "--p-max", "{p}", "--dps", "{dps}"],
                  {"N": "N", "p": "p", "dps": "dps"}),
    "asymptotics": (["asymptotics", "{N}", "--order", "{order}", "--dps", "{dps}"],
                    {"N": "N", "order": "choice", "dps": "dps"}),
    "derive": (["derive", "{label}"], {"label": "choice"}),
    "p-sigma": (["p-sigma", "{sigma}", "--omega", "{omega}", "--d", "{d}", "--dps", "{dps}"],
                {"sigma": "nonneg", "omega": "positive", "d": "positive", "dps": "dps"}),
    "p-sigma --json": (["p-sigma", "{sigma}", "--json"], {"sigma": "nonneg"}),
    "p-sigma --inverse": (["p-sigma", "{sigma}", "--inverse"], {"sigma": "p01"}),
    "p-sigma --csv": (["p-sigma", "0.3", "--csv", "{path}"], {"path": "path"}),
    "simulate": (["simulate", "--pipes", "{n}", "--sigma", "{sigma}", "--t-end", "{t}", "--seed",
                  "{seed}"], {"n": "N", "sigma": "nonneg", "t": "positive", "seed": "seed"}),
    "ensemble": (["ensemble", "--sigmas", "{sigma}", "--runs", "{runs}", "--pipes", "{n}",
                  "--t-transient", "{tt}", "--t-window", "{tw}", "--workers", "1"],
                 {"sigma": "nonneg", "runs": "N", "n": "N", "tt": "nonneg", "tw": "positive"}),
    "spaces": (["spaces", "{N}", "{p}", "--space", "{space}", "--dps", "{dps}"],
               {"N": "N", "p": "p", "space": "choice", "dps": "dps"}),
    "convergence": (["convergence", "{N}", "--max-m", "{m}", "--dps", "{dps}"],
                    {"N": "N", "m": "count", "dps": "dps"}),
    "paper": (["paper", "--out", "{path}"], {"path": "path"}),
}
CLI_VALID = {"N": "12", "dps": "15", "p": "0.1", "space": "simple", "visits": "2,1,1", "L": "3",
             "order": "best", "label": "5", "sigma": "0.3", "omega": "1", "d": "1", "n": "3",
             "t": "5", "seed": "0", "runs": "1", "tt": "1", "tw": "1", "m": "1",
             "path": "/tmp/symhx-fuzz-out.csv"}
CLI_HOSTILE = {
    "nan": "nan", "inf": "inf", "-inf": "-inf", "0": "0", "-1": "-1", "-0.1": "-0.1",
    "1e-400": "1e-400", "1e1000": "1e1000", "10**1000": "10**1000", "abc": "abc", "empty": "",
    "1/0": "1/0", "True": "True", "2.5": "2.5", "1e-3": "1e-3", "1e6": "1e6", "10**6": "10**6",
    "excess<=1000": "excess<=1000", "1,,2": "1,,2", "unwritable": "/proc/symhx/forbidden/out",
}
#: role -> hostile labels that must be refused (exit code 2)
CLI_REJECT: dict[str, set[str]] = {
    "N": {"nan", "inf", "-inf", "0", "-1", "-0.1", "1e-400", "abc", "empty", "1/0", "True", "2.5",
          "1e-3", "excess<=1000", "1,,2", "unwritable"},
    "count": {"nan", "inf", "-inf", "-1", "-0.1", "1e-400", "abc", "empty", "1/0", "True", "2.5",
              "1e-3", "excess<=1000", "1,,2", "unwritable"},
    "p": {"nan", "inf", "-inf", "0", "-1", "-0.1", "abc", "empty", "1/0", "True", "excess<=1000",
          "1,,2", "unwritable"},
    "p01": {"nan", "inf", "-inf", "0", "-1", "-0.1", "abc", "empty", "1/0", "True", "2.5",
            "excess<=1000", "1,,2", "unwritable", "1e1000", "10**1000", "1e6", "10**6"},
    "positive": {"nan", "inf", "-inf", "0", "-1", "-0.1", "abc", "empty", "1/0", "True",
                 "excess<=1000", "1,,2", "unwritable"},
    "nonneg": {"nan", "inf", "-inf", "-1", "-0.1", "abc", "empty", "1/0", "True", "excess<=1000",
               "1,,2", "unwritable"},
    "seed": {"nan", "inf", "-inf", "-1", "-0.1", "1e-400", "abc", "empty", "1/0", "True", "2.5",
             "1e-3", "excess<=1000", "1,,2", "unwritable"},
    "dps": {"nan", "inf", "-inf", "0", "-1", "-0.1", "1e-400", "1e1000", "10**1000", "abc",
            "empty", "1/0", "True", "2.5", "1e-3", "1e6", "10**6", "excess<=1000", "1,,2",
            "unwritable"},
    "choice": set(CLI_HOSTILE) - {"excess<=1000"},
    "visits": set(CLI_HOSTILE) - {"1e6", "10**6", "1e1000", "10**1000"},
    "path": {"unwritable"},
}


def _cli_thunk(argv: list[str], cwd: str) -> Callable[[], Any]:
    def thunk() -> Any:
        from symhx.cli import main

        os.chdir(cwd)  # in the forked child: files a command writes land in a temporary folder
        out, err = io.StringIO(), io.StringIO()
        with contextlib.redirect_stdout(out), contextlib.redirect_stderr(err):
            try:
                rc = main(argv)
            except SystemExit as exc:  # argparse
                rc = exc.code if isinstance(exc.code, int) else 1
        return {"rc": rc, "stdout": out.getvalue()[-2000:], "stderr": err.getvalue()[-2000:]}

    return thunk


@pytest.mark.parametrize("command", sorted(CLI), ids=sorted(CLI))
def test_cli_hostile(command: str, tmp_path):
    """Each placeholder of each command against every hostile string, the others valid."""
    template, roles = CLI[command]
    # an output path that is merely unusual ("-1", "") is valid and would run the whole job
    cases = [(slot, label) for slot in roles for label in CLI_HOSTILE
             if roles[slot] != "path" or label in CLI_REJECT["path"]]
    argvs = []
    base = [] if command == "paper" else [(None, None)]  # paper's valid call: the whole job
    for slot, label in [*base, *cases]:
        values = dict(CLI_VALID, path=str(tmp_path / "out"))
        if slot is not None:
            values[slot] = CLI_HOSTILE[label]
        argvs.append([a.format(**values) for a in template])
    outcomes = run_isolated([_cli_result(argv, str(tmp_path)) for argv in argvs])
    failures = []
    for (slot, label), argv, res in zip([*base, *cases], argvs, outcomes, strict=True):
        must_reject = slot is not None and label in CLI_REJECT[roles[slot]]
        bad = _judge_cli(res, must_reject)
        if bad:
            failures.append(f"symhx {' '.join(argv)}  [{slot}={label}]: {bad}")
    assert not failures, f"{len(failures)} failures:\n" + "\n".join(failures)


def _cli_result(argv: list[str], cwd: str) -> Callable[[], Any]:
    inner = _cli_thunk(argv, cwd)

    def thunk() -> Any:
        r = inner()
        # summarised in the child: the parent only gets this tuple back through repr(), cut at
        # 120 characters by _one_call, so the problems are shortened until the repr fits (a cut
        # repr is no Python literal: ast.literal_eval raised SyntaxError)
        out = (r["rc"], _stderr_problem(r["stderr"], r["rc"]), _stdout_problem(r["stdout"]))
        while len(repr(out)) > 110:
            out = (out[0], out[1][:max(len(out[1]) - 10, 0)], out[2][:max(len(out[2]) - 10, 0)])
        return out

    return thunk


def _stderr_problem(err: str, rc: Any) -> str:
    if "Traceback" in err:
        return "traceback on stderr: " + err.strip().splitlines()[-1][:100]
    if rc == 0:
        return ""
    lines = [ln for ln in err.splitlines() if "error:" in ln]
    if len(lines) != 1:
        return f"stderr has {len(lines)} 'error:' lines: {err.strip()[:120]!r}"
    return ""


def _stdout_problem(out: str) -> str:
    low = out.lower()
    for bad in ("nan", "infinity", "traceback"):
        if bad in low.replace("nan_", "").replace("\"infinity\"", ""):
            return f"{bad!r} in stdout: {out.strip()[:100]!r}"
    return ""


def _judge_cli(res: dict[str, Any], must_reject: bool) -> str | None:
    if res["kind"] != "value":
        return _verdict(res, False) or f"escaped main(): {res}"
    if res["dps_changed"]:
        return "changed mpmath.mp.dps"
    rc, err_problem, out_problem = ast.literal_eval(res["repr"])
    if rc not in (0, 2):
        return f"exit code {rc} (want 0 or 2)" + (f"; {err_problem}" if err_problem else "")
    if err_problem:
        return err_problem
    if rc == 0 and must_reject:
        return "exit code 0 for a value that is not allowed (silent wrong answer)"
    if rc == 0 and out_problem:
        return out_problem
    return None


# --------------------------------------------------------------------------- interactions
# Two hostile or extreme arguments at once (issue 28: the silent wrong numbers and hangs came from
# such pairs, never from one bad value alone): a negligible scale next to a normal one, a huge N
# with p above p_c, an irrational p near a tie of the modes, a huge N with a tiny dps.  Each case
# runs in the forked child under the time limit like the calls above; a returned value must also
# satisfy the identities of its quantity (cdf + sf = 1, E[X] in [1, N], the modes of an exact
# reference, the digits asked for, ...), checked in the child.  Any failure is a bug.
class InvariantBroken(Exception):
    """A returned value contradicts an identity it must satisfy (neither a refusal nor a crash)."""


def _mpf(x: Any) -> mpmath.mpf:
    if isinstance(x, Fraction):
        return mpmath.mpf(x.numerator) / x.denominator
    return mpmath.mpf(x)


def _close(actual: Any, expected: Any, rtol: float, atol: float = 0.0, what: str = "") -> None:
    with mpmath.workdps(60):
        a, e = _mpf(actual), _mpf(expected)
        if not abs(a - e) <= atol + rtol * abs(e):
            raise InvariantBroken(f"{what}: got {mpmath.nstr(a, 20)}, want {mpmath.nstr(e, 20)} "
                                  f"(rtol {rtol:g}, atol {atol:g})")


def _outcomes(calls: dict[str, Callable[[], Any]]) -> dict[str, Any]:
    """Each call's value, or its refusal (the ValueError/TypeError object)."""
    out: dict[str, Any] = {}
    for name, fn in calls.items():
        try:
            out[name] = fn()
        except (ValueError, TypeError) as exc:
            out[name] = exc
    return out


def _answered_all_or_none(out: dict[str, Any]) -> bool:
    """True if every method answered, False if every one refused; mixed is a failure ("refuse
    consistently in every method, never one of each")."""
    refused = sorted(k for k, v in out.items() if isinstance(v, Exception))
    if refused and len(refused) < len(out):
        raise InvariantBroken(f"refuses in {refused} ({out[refused[0]]}) but answers in "
                              f"{sorted(set(out) - set(refused))}")
    return not refused


def _tol(dps: int | None) -> float:
    return 1e-13 if dps is None else 10.0 ** (2 - dps)


def _rayleigh_tiny_scale(scales: list[float], dps: int | None) -> Callable[[], Any]:
    """A sum of Rayleigh variables with scale 1 and negligible ones (sum s): at x = 1 it is
    Rayleigh(1) within 0.8 s (|sf - e^(-1/2)| <= max pdf * E[sum of the small ones])."""
    def thunk() -> Any:
        R = symhx.RayleighSum(scales)
        out = _outcomes({m: (lambda m=m: getattr(R, m)(1.0, dps=dps))
                         for m in ("cdf", "sf", "logsf", "logcdf", "pdf")})
        if not _answered_all_or_none(out):
            return "refused"
        small, tol = sum(scales[1:]), _tol(dps)
        with mpmath.workdps(60):
            e = mpmath.exp(mpmath.mpf(-0.5))
            log1me = mpmath.log(1 - e)
        _close(_mpf(out["cdf"]) + _mpf(out["sf"]), 1, 0, tol, "cdf + sf")
        _close(out["sf"], e, tol, small, "sf against Rayleigh(1)")
        _close(out["pdf"], e, tol, small, "pdf against Rayleigh(1)")
        _close(out["logsf"], -0.5, tol, 2 * small, "logsf against Rayleigh(1)")
        _close(out["logcdf"], log1me, tol, 2 * small, "logcdf against Rayleigh(1)")
        return out
    return thunk


def _one_rayleigh_sf(sigma: float) -> mpmath.mpf:
    """P(R0 > 1) for the free oscillation alone: Rayleigh with s0 = sqrt(2) sigma (eq. 24)."""
    with mpmath.workdps(60):
        return mpmath.exp(-1 / (4 * mpmath.mpf(sigma) ** 2))


def _forcing_tiny_component(kw: dict[str, Any], reference: Callable[[], Any], small: float,
                            dps: int | None) -> Callable[[], Any]:
    """p(sigma) with a negligible component: within ``small`` of p without it, p + (1 - p) = 1,
    and the logs are the logs."""
    def thunk() -> Any:
        fns = ("impact_probability", "no_impact_probability", "log_impact_probability",
               "log_no_impact_probability")
        out = _outcomes({f: (lambda f=f: getattr(symhx, f)(**kw, dps=dps)) for f in fns})
        if not _answered_all_or_none(out):
            return "refused"
        tol = _tol(dps)
        with mpmath.workdps(60):
            p0 = _mpf(reference())
            lp, lq = mpmath.log(p0), mpmath.log(1 - p0)
        _close(_mpf(out["impact_probability"]) + _mpf(out["no_impact_probability"]), 1, 0, tol,
               "p + (1 - p)")
        _close(out["impact_probability"], p0, tol, small, "p against p without the component")
        _close(out["log_impact_probability"], lp, tol, small / p0, "log p")
        _close(out["log_no_impact_probability"], lq, tol, small / (1 - p0), "log (1 - p)")
        return out
    return thunk


def _many_scales(kind: str) -> Callable[[], Any]:
    def thunk() -> Any:
        if kind == "RayleighSum":
            R = symhx.RayleighSum([1.0] * 7)
            sf, cdf = R.sf(5.29), R.cdf(5.29)
        else:
            kw = {"sigma": 0.2, "Omega": [1.5, 2, 2.5, 3, 3.5, 4]}
            sf, cdf = symhx.impact_probability(**kw), symhx.no_impact_probability(**kw)
        if not 0 < sf < 1:
            raise InvariantBroken(f"probability {sf} outside (0, 1)")
        _close(sf + cdf, 1, 0, 1e-13, "p + (1 - p)")
        return sf
    return thunk


def _huge_N_above_pc(N: int, p: Any, dps: int | None) -> list[tuple[str, Callable[[], Any]]]:
    """Each frozen-distribution method at a huge N with p above p_c (one call each, under the
    time limit): a value in its range, consistent with its siblings."""
    k = N // 2
    slack = 1 + _tol(dps if dps is None else dps - 1)  # E[X] rounded to dps digits may pass N

    def d() -> Any:
        return symhx.distribution_of(N, p, dps=dps)

    def mean() -> Any:
        m = d().mean()
        if not 1 <= _mpf(m) <= N * mpmath.mpf(slack):
            raise InvariantBroken(f"mean {m} outside [1, N]")
        return m

    def var() -> Any:
        v = d().var()
        if _mpf(v) < 0:
            raise InvariantBroken(f"variance {v} < 0")
        return v

    def entropy() -> Any:
        h = d().entropy()
        if _mpf(h) < -_tol(dps):
            raise InvariantBroken(f"entropy {h} < 0")
        return h

    def modes() -> Any:
        dist = d()
        m, ms = dist.mode(), dist.modes()
        if not (isinstance(m, int) and 1 <= m <= N and m in ms):
            raise InvariantBroken(f"mode {m!r} not an int in [1, N] among the modes {ms}")
        return ms

    def cdf_sf() -> Any:
        dist = d()
        c, s = dist.cdf(k), dist.sf(k)
        _close(_mpf(c) + _mpf(s), 1, 0, _tol(dps), "cdf(k) + sf(k)")
        return c, s

    def pmf() -> Any:
        dist = d()
        q, lq = dist.pmf(N), dist.logpmf(N)
        if not 0 <= _mpf(q) <= 1:
            raise InvariantBroken(f"pmf {q} outside [0, 1]")
        if q > 0:
            with mpmath.workdps(60):
                _close(lq, mpmath.log(_mpf(q)), _tol(dps), 0, "logpmf against log pmf")
        return q

    def quantile(name: str) -> Callable[[], Any]:
        def f() -> Any:
            dist = d()
            m = dist.median() if name == "median" else dist.ppf(0.5)
            if not (isinstance(m, int) and 1 <= m <= N):
                raise InvariantBroken(f"{name} {m!r} is not an int in [1, N]")
            return m
        return f

    return [("mean", mean), ("var", var), ("entropy", entropy), ("mode/modes", modes),
            ("cdf/sf", cdf_sf), ("pmf/logpmf", pmf), ("median", quantile("median")),
            ("ppf", quantile("ppf"))]


def _sites_tiny_class(N: int, tiny: Any, dps: int | None) -> list[tuple[str, Callable[[], Any]]]:
    """Two sites of a negligible probability next to N - 2 sites of p = 0.02 (issue 30): X is
    that of N - 2 sites of p within a relative ~N * tiny, so every method must agree with the
    scalar distribution of N - 2 sites (or every method refuse)."""
    sc = symhx.SiteClasses((2, N - 2), (tiny, 0.02))

    def mean() -> Any:
        m = symhx.mean(N, sc, dps=dps)
        # float64: summing N probabilities (the scalar path itself is 4e-13 off at N = 2000)
        tol = _tol(dps) if dps is not None else 1e-11
        _close(m, symhx.mean(N - 2, 0.02, dps=40), tol, 0, "mean against N - 2 sites")
        return m

    def modes() -> Any:
        ms = symhx.modes(N, sc)
        if ms != symhx.modes(N - 2, 0.02):
            raise InvariantBroken(f"modes {ms} != {symhx.modes(N - 2, 0.02)} of N - 2 sites")
        return ms

    def cdf_sf() -> Any:
        c, f = symhx.cdf(N, sc, N // 2, dps=dps), symhx.sf(N, sc, N // 2, dps=dps)
        _close(_mpf(c) + _mpf(f), 1, 0, _tol(dps), "cdf(k) + sf(k)")
        _close(c, symhx.cdf(N - 2, 0.02, N // 2, dps=40), _tol(dps), _tol(dps), "cdf")
        return c

    def logpmf() -> Any:
        lq = symhx.logpmf(N, sc, 1, dps=dps)
        _close(lq, symhx.logpmf(N - 2, 0.02, 1, dps=40), _tol(dps), 0, "logpmf(1)")
        return lq

    return [("mean", mean), ("modes", modes), ("cdf/sf", cdf_sf), ("logpmf", logpmf)]


def _sites_direction(N: int, w: Any) -> Callable[[], Any]:
    """The critical point along (w, 1) for sizes (2, N - 2) (issue 30): a refusal (documented
    limit), or t_c inside its Arb bounds; a negligible w gives the scalar p_c of N - 2 sites."""
    def thunk() -> Any:
        cp = symhx.critical_point(N, weights=symhx.SiteClasses((2, N - 2), (w, 1)), dps=20)
        lo, hi = cp.p_bounds
        if not (lo <= cp.p <= hi and cp.k_after >= 2 and cp.k_after in cp.argmins):
            raise InvariantBroken(f"t_c {cp.p} outside {cp.p_bounds} or k_after {cp.k_after} "
                                  f"not among {cp.argmins}")
        if _mpf(w) < 1e-200:
            ref = symhx.critical_point(N - 2, dps=20)
            _close(cp.p, ref.p, 1e-18, 0, "t_c against p_c of N - 2 sites")
            if cp.k_after != ref.k_after:
                raise InvariantBroken(f"k_after {cp.k_after} != {ref.k_after} of N - 2 sites")
        return cp
    return thunk


def _irrational_near_tie(sign: int, e: int) -> Callable[[], Any]:
    """N = 101 at p = 1/50 +- sqrt(2)/10**e: Phi(50) = Phi(51) exactly at 1/50, so the modes are
    those of any rational on the same side of the tie (brute force, exact Fractions)."""
    def thunk() -> Any:
        import sympy

        from tests.reference.distribution import brute_modes

        p = sympy.Rational(1, 50) + sign * sympy.sqrt(2) / 10**e
        want = brute_modes(101, Fraction(1, 50) + Fraction(sign, 10 ** (e + 1)))
        got = tuple(symhx.modes(101, p))
        if got != want:
            raise InvariantBroken(f"modes {got}, want {want}")
        if symhx.mode(101, p) not in want:
            raise InvariantBroken(f"mode {symhx.mode(101, p)} not in {want}")
        return got
    return thunk


def _tiny_dps(what: str, N: int) -> list[tuple[str, Callable[[], Any]]]:
    """Results at dps = 1, 2, 3 for a huge N meet their digits (against dps = 12; one call
    each)."""
    def value(dps: int) -> Any:
        if what == "critical_point":
            return symhx.critical_point(N, dps=dps).p
        if what == "discriminant_root":
            return symhx.discriminant_root(N, dps=dps)
        if what == "mean":
            return symhx.mean(N, 0.5, dps=dps)
        if what == "log_phi":
            return symhx.log_phi(N, N // 2, dps=dps)
        return symhx.asymptotic_critical_point(N, dps=dps).p

    def at(dps: int) -> Callable[[], Any]:
        def f() -> Any:
            got = value(dps)
            _close(got, value(12), 10.0 ** (1 - dps), 0, f"{what} at dps={dps}")
            return got
        return f

    return [(f"dps={d}", at(d)) for d in (1, 2, 3)]


def _thunk(fn: Callable[..., Any], *args: Any, **kwargs: Any) -> Callable[[], Any]:
    return lambda: fn(*args, **kwargs)


def _interactions() -> list[Any]:
    """pytest params, each a list of (label, thunk): one forked call per thunk."""
    def one(thunk: Callable[[], Any], id: str, marks: Any = ()) -> Any:
        return pytest.param([("", thunk)], id=id, marks=marks)

    P = pytest.param
    cases = []
    for scales in ([1.0, 1e-8], [1.0, 1e-100], [1.0, 1e-154], [1.0, 1e-200], [1.0, 1e-300],
                   [1.0, 1e-300, 1e-300]):
        for dps in (None, 20):
            cases.append(one(_rayleigh_tiny_scale(scales, dps), f"RayleighSum{scales}-dps={dps}"))
    for sigma1 in (1e-8, 1e-100, 1e-300):
        for dps in (None, 20):
            cases.append(one(_forcing_tiny_component({"sigma": 0.3, "sigma1": sigma1},
                                                     lambda: _one_rayleigh_sf(0.3),
                                                     3 * sigma1, dps),
                             f"impact_probability(0.3, sigma1={sigma1:g})-dps={dps}"))
    for dps in (None, 20):
        cases.append(one(_forcing_tiny_component(
            {"sigma": 0.3, "Omega": [1.5, 1e100]},
            lambda: symhx.impact_probability(0.3, Omega=[1.5], dps=40), 1e-199, dps),
            f"impact_probability(0.3, Omega=[1.5, 1e100])-dps={dps}"))
    for kind in ("RayleighSum", "impact_probability"):
        cases.append(one(_many_scales(kind), f"{kind}-seven-scales"))
    for N, label in ((10**6, "1e6"), (10**30, "1e30"), (10**1000, "1e1000")):
        for p, plabel in ((0.5, "0.5"), (2.0, "2.0"), (10 / N if N < 10**300 else 1e-299,
                                                      "10/N")):
            for dps in (20, None):
                cases.append(P(_huge_N_above_pc(N, p, dps),
                               id=f"distribution_of(N={label}, p={plabel})-dps={dps}"))
    for N in (101, 2000):  # site classes: a negligible class next to a normal one (issue 30)
        for tiny in (1e-300, 5e-324, "1e-5000"):
            for dps in (20, None):
                cases.append(P(_sites_tiny_class(N, tiny, dps),
                               id=f"SiteClasses((2, {N}-2), ({tiny}, 0.02))-dps={dps}"))
    for N, label in ((10**4, "1e4"), (10**100, "1e100"), (10**1000, "1e1000")):
        for w in (1e-300, "1e-5000", "1/2", 2, 1e300):  # huge N with one small class
            cases.append(one(_sites_direction(N, w), f"critical_point(N={label}, weights=(2: {w}, "
                                                     f"N-2: 1))"))
    cases.append(one(_thunk(symhx.mean, 10**100, symhx.SiteClasses((2, 10**100 - 2),
                                                                  (0.5, 0.02))),
                     "mean(1e100, SiteClasses((2, N-2), (0.5, 0.02)))"))
    cases.append(one(_thunk(symhx.critical_curve, 10**100, (2, 10**100 - 2), directions=5),
                     "critical_curve(1e100, (2, N-2))"))
    for sign in (1, -1):
        for e in (30, 70, 100):
            cases.append(one(_irrational_near_tie(sign, e),
                             f"modes(101, 1/50{'+-'[sign < 0]}sqrt(2)/10**{e})"))
    for what in ("critical_point", "discriminant_root", "mean", "log_phi",
                 "asymptotic_critical_point"):
        for N, label in ((10**3, "1e3"), (10**30, "1e30"), (10**1000, "1e1000")):
            cases.append(P(_tiny_dps(what, N), id=f"{what}(N={label})-dps=1,2,3"))
    cases += [
        one(_thunk(symhx.pmf, 101, "1e-5000", 3), "pmf(101, '1e-5000', 3)"),
        one(lambda: symhx.distribution_of(101, 0.02).rvs(10**12), "rvs(10**12) at N=101"),
        one(lambda: symhx.RayleighSum([1, 1]).rvs(-1), "RayleighSum([1, 1]).rvs(-1)"),
        one(lambda: symhx.RayleighSum([1, 1]).rvs(2.5), "RayleighSum([1, 1]).rvs(2.5)"),
        one(_thunk(symhx.critical_point, 2 * 10**7, space="eq41", dps=20),
            "critical_point(2e7, eq41)"),
        one(_thunk(symhx.critical_point, 10**6, space="excess<=25", dps=20),
            "critical_point(1e6, excess<=25)"),
        one(_thunk(symhx.asymptotic_critical_point, 10**100000, order="lambert"),
            "asymptotic_critical_point(10**100000, lambert)"),
        one(_thunk(symhx.phi, 10**30, 10**30), "phi(10**30, 10**30)"),
        one(_thunk(symhx.circuit_count, 10**1000, (1,) * 20000),
            "circuit_count(1e1000, 1*20000)"),
        one(_thunk(symhx.log_phi, 10**1000, 10**999, dps=1), "log_phi(1e1000, 1e999, dps=1)"),
        one(_thunk(symhx.theory_curve, [1e-3, 10.0], N=10**30, dps=5),
            "theory_curve(1e-3..10, N=1e30, dps=5)"),
    ]
    return cases


@pytest.mark.parametrize("calls", _interactions())
def test_hostile_interactions(calls):
    """Two extreme arguments at once: an answer that meets its identities, or a refusal."""
    results = run_isolated([thunk for _, thunk in calls])
    failures = [f"{label}: {bad}" if label else bad for (label, _), res in
                zip(calls, results, strict=True) if (bad := _verdict(res, False))]
    assert not failures, f"{len(failures)} failures:\n" + "\n".join(failures)


CLI_INTERACTIONS = [
    pytest.param(["critical", "10**3", "--dps", "1", "--json"], "0.001",
                 id="critical 10**3 --dps 1"),
    pytest.param(["critical", "1e1000", "--dps", "2", "--json"], None,
                 id="critical 1e1000 --dps 2"),
    pytest.param(["distribution", "1e30", "0.5", "--float", "--dps", "1", "--json"], None,
                 id="distribution 1e30 0.5 --float --dps 1"),
    pytest.param(["spaces", "101", "1e-5000", "--space", "eq41"], None,
                 id="spaces 101 1e-5000 --space eq41"),
]


@pytest.mark.parametrize("argv, p_c", CLI_INTERACTIONS)
def test_cli_hostile_interactions(argv, p_c, tmp_path):
    """The CLI with two extreme arguments at once: exit 0 or a one-line refusal; with --dps d a
    printed p_c has at most d significant digits."""
    def thunk() -> Any:
        r = _cli_thunk(argv, str(tmp_path))()
        if p_c is not None and r["rc"] == 0:
            import json

            shown = json.loads(r["stdout"])["p_c"]
            if shown != p_c:
                raise InvariantBroken(f"p_c printed as {shown!r}, want {p_c!r}")
        return (r["rc"], _stderr_problem(r["stderr"], r["rc"]), _stdout_problem(r["stdout"]))

    (res,) = run_isolated([thunk])
    bad = _judge_cli(res, False)
    assert bad is None, bad


#: role -> extreme values that are allowed (two of them are drawn at once below)
EXTREMES: dict[str, list[Any]] = {
    "N": [2, 10**6, 10**30, 10**1000],
    "int": [-(10**30), 0, 2**63, 10**30],
    "count": [0, 10**6],
    "p": [1e-300, "1e-300", 0.999999, 1, 2.0, "1/3"],
    "p01": [1e-300, 0.5, 1 - 1e-16],
    "q": [0, 1, 1e-300, 1 - 1e-16],
    "positive": [1e-300, 1e-8, 1e8, 1e300],
    "nonneg": [0, 1e-300, 1e300],
    "positive?": [None, 1e-300, 1e300],
    "restitution": [1e-300, 1],
    "restitution0": [0, 1],
    "dps": [1, 2, 500],
    "dps?": [None, 1, 500],
    "real": [-1e300, 0.0, 1e-300, 1e300],
    "array+": [[1.0, 1e-100], [1e-300] * 3, [1.0] * 7, [1e300]],
    "seed": [0, 2**63],
    "int?": [None, 1, 10**6],
    "size?": [None, 0, 10**6],
    "bool?": [None, True],
}


def _extremes(role: str) -> list[Any]:
    return EXTREMES.get(role.removesuffix("[]"), [])


_PAIRED = [e for e in API if sum(bool(_extremes(r)) for r in e.roles.values()) >= 2]


@settings(max_examples=60, deadline=None, suppress_health_check=list(HealthCheck))
@given(data=st.data())
def test_extreme_pairs(data):
    """Two arguments of one function at allowed extremes at once (a tiny value next to a huge
    one, a huge N with a tiny dps, ...): a value without NaN, or a refusal, in time."""
    entry = data.draw(st.sampled_from(_PAIRED), label="function")
    args = data.draw(st.lists(st.sampled_from(sorted(a for a, r in entry.roles.items()
                                                     if _extremes(r))),
                              min_size=2, max_size=2, unique=True), label="arguments")
    override = {a: data.draw(st.sampled_from(_extremes(entry.roles[a])), label=a) for a in args}
    (res,) = run_isolated([_call(entry, override)])
    bad = _verdict(res, False)
    assert bad is None, f"{entry.name}({override!r}): {bad}"
