"""The user-facing functions of symhx: one frozen distribution per sample space, scipy.stats-style
functions that broadcast over ``k`` and ``p``, modes and the critical point.

This is the one module above the distributions.  It parses ``space`` once (a
:class:`symhx.spaces.Space`), validates ``N`` and ``dps`` once, and picks the class:
:class:`symhx.distribution.SimpleDistribution` for ``"simple"``,
:class:`symhx.spaces.SpaceDistribution` for a higher-order space.  The lower layers never
dispatch on a space string.

Conventions (see :mod:`symhx.validation`):

* ``p`` (and ``q``, ``confidence``): ints, ``Fraction``, sympy ``Rational`` and decimal strings
  (``"0.02"``, ``"2e-2"``, ``"1/50"``) are exact; floats and ``mpf`` are taken at their exact
  binary value (``modes(101, "0.02") == (50, 51)`` but ``modes(101, 0.02) == (51,)``).
* ``dps``: significant digits of mpmath results (:data:`symhx.validation.DEFAULT_DPS`);
  ``dps=None`` gives float64 (numpy) results.
* Exact ``p`` with an int ``dps`` gives ``Fraction`` results wherever the value is rational.
* ``k``, ``q`` and ``p`` may be arrays (or lists): the result broadcasts like scipy.stats, with
  dtype float64 for ``dps=None`` and object (``Fraction`` / ``mpf``) otherwise.
* Site probabilities (issue 30): wherever ``p`` is taken, a :class:`symhx.SiteClasses` gives
  each class of impact sites its own probability (a circuit weighs the product of its sites'
  probabilities; :mod:`symhx.site_weights`).  :func:`distribution_of` and
  ``critical_point(weights=...)`` also take a sequence of ``N`` per-site probabilities; in the
  broadcasting functions (:func:`pmf`, :func:`mean`, :func:`modes`, ...) a list is an array of
  scalar ``p``, so per-site values go in as ``SiteClasses.from_sites(values)`` (and a list of
  ``SiteClasses`` broadcasts).  Classes of one common value are the scalar ``p`` they hold, bit
  for bit (today's code path); two or more go through
  :class:`symhx.site_distribution.SitesDistribution`.

>>> import numpy as np
>>> pmf(10, 0.3, np.arange(1, 4), dps=None).round(4)
array([0.0298, 0.0402, 0.0644])
>>> modes(101, "0.02"), modes(101, 0.02)
((50, 51), (51,))
>>> mean(3, "1/2")
Fraction(3, 2)
>>> from symhx.sites import SiteClasses
>>> modes(101, SiteClasses((2, 99), ("0.01", "0.02")))   # walls at 0.01, pipe pairs 0.02
(50,)
"""

from __future__ import annotations

import dataclasses
import warnings
from collections.abc import Callable
from typing import Any

import numpy as np

from symhx.critical import CriticalPoint
from symhx.critical import critical_point as simple_critical_point
from symhx.critical_sites import DirectionCriticalPoint, direction_critical_point
from symhx.distribution import Distribution, SimpleDistribution, simple_modes
from symhx.site_distribution import SitesDistribution, site_modes
from symhx.sites import SiteClasses, as_site_classes, is_site_input
from symhx.spaces import Space, SpaceDistribution, parse_space, space_modes
from symhx.spaces import critical_point as space_critical_point
from symhx.validation import DEFAULT_DPS, DEFAULT_SPACE, check_dps, check_N, check_p

__all__ = [
    "CriticalPoint",
    "DirectionCriticalPoint",
    "SiteClasses",
    "cdf",
    "critical_point",
    "distribution_of",
    "entropy",
    "interval",
    "isf",
    "logcdf",
    "logpmf",
    "logsf",
    "mean",
    "median",
    "mode",
    "modes",
    "normaliser",
    "pmf",
    "ppf",
    "rvs",
    "sf",
    "std",
    "var",
    "variance",
]

SpaceLike = str | Space


def _space(space: SpaceLike, weighting: str | None = None) -> Space:
    if not isinstance(space, (str, Space)):
        raise TypeError(f"space must be a str such as 'simple', 'eq41' or 'excess<=3' (or a "
                        f"symhx.spaces.Space), got {type(space).__name__} {space!r}")
    return parse_space(space, weighting)


def _scalar_or_classes(N: int, p: Any) -> tuple[Any, SiteClasses | None]:
    """``(p, None)`` for a scalar ``p`` or site classes of one common value (the scalar they
    hold, the original object, so the result is today's bit for bit); ``(None, classes)`` for
    two or more classes of distinct value."""
    if not isinstance(p, SiteClasses):
        return p, None
    sc = as_site_classes(p, N, "p").merged()
    if len(sc) == 1:
        return sc.probabilities[0], None
    return None, sc


def _build(N: int, p: Any, sp: Space, dps: int | None) -> Distribution:
    p, sc = _scalar_or_classes(N, p)
    if sc is not None:
        return SitesDistribution(N, sc, sp, dps=dps)
    if sp.base == "simple":
        return SimpleDistribution(N, p, dps=dps)
    return SpaceDistribution(N, p, sp, dps=dps)


def distribution_of(N: Any, p: Any, *, space: SpaceLike = DEFAULT_SPACE,
                    dps: int | None = DEFAULT_DPS, weighting: str | None = None
                    ) -> Distribution:
    """The frozen distribution of X (eqs. 7-8, or section 8 for a higher-order space).

    Parameters
    ----------
    N : int
        Number of vertices (possible impacts), ``N = n + 1`` for ``n`` pipes; ``N >= 1``.
    p : int, Fraction, sympy Rational, decimal string, float, mpf, SiteClasses or sequence
        Impact probability, ``p > 0`` (``p > 1`` is accepted but unphysical); or per-site
        probabilities: a :class:`symhx.SiteClasses` of classes summing to ``N`` sites, or a
        sequence (list, tuple, 1-d array) of ``N`` per-site probabilities.  Several classes
        give a :class:`symhx.site_distribution.SitesDistribution` (exact for exact class
        probabilities, mpmath at ``dps`` otherwise, float64 for ``dps=None``; work limits
        :data:`symhx.site_weights.EXACT_TABLE_BITS_LIMIT`,
        :data:`symhx.site_weights.BALL_TABLE_N_LIMIT`,
        :data:`symhx.site_weights.SITE_PATTERN_LIMIT`, checked before any work).
    space : str or Space
        ``"simple"`` (default), ``"eq41"``, ``"eq41-printed"``, ``"excess<=m"``, optionally with
        ``";distinct"`` (see :func:`symhx.spaces.parse_space`).
    dps : int or None
        Significant digits of mpmath results; ``None`` for float64.
    weighting : {"length", "distinct"}, optional
        Instead of the ``;distinct`` suffix.

    Returns
    -------
    Distribution
        With scipy's frozen methods ``pmf, logpmf, cdf, logcdf, sf, logsf, ppf, isf, mean,
        var, std, median, mode, modes, support, interval, rvs, entropy``.

    Raises
    ------
    ValueError
        A bad ``N``, ``p``, ``space`` or ``dps``; site classes not summing to ``N``; work
        beyond a documented limit.
    TypeError
        A wrong kind of object.

    >>> d = distribution_of(3, "1/2")
    >>> [d.pmf(k) for k in (1, 2, 3)], d.mean(), d.cdf(2) + d.sf(2)
    ([Fraction(3, 5), Fraction(3, 10), Fraction(1, 10)], Fraction(3, 2), Fraction(1, 1))
    >>> distribution_of(3, ["1/2", "1/3", "1/3"]).pmf(1)     # per-site probabilities
    Fraction(21, 31)
    """
    sp = _space(space, weighting)
    N = check_N(N, minimum=1)
    dps = check_dps(dps, allow_none=True)
    if is_site_input(p):
        p = as_site_classes(p, N, "p")
    return _build(N, p, sp, dps)


# --------------------------------------------------------------------------- broadcasting
def _is_array(x: Any) -> bool:
    return isinstance(x, (np.ndarray, list, tuple))


def _hashable(x: Any) -> Any:
    try:
        hash(x)
    except TypeError:
        return id(x)
    return (type(x).__name__, x)


def _over_p(N: Any, p: Any, space: SpaceLike, dps: Any,
            call: Callable[[Distribution], Any], *, out_dtype: Any = None) -> Any:
    """``call(distribution)`` for a scalar ``p``, or an array over the entries of ``p``."""
    sp = _space(space)
    N = check_N(N, minimum=1)
    dps = check_dps(dps, allow_none=True)
    if not _is_array(p):
        return call(_build(N, p, sp, dps))
    pa = np.empty(np.shape(np.asarray(p, dtype=object)), dtype=object)
    pa[...] = np.asarray(p, dtype=object)
    cache: dict[Any, Distribution] = {}
    out = np.empty(pa.shape, dtype=object)
    for idx, pv in np.ndenumerate(pa):
        key = _hashable(pv)
        d = cache.get(key)
        if d is None:
            d = cache[key] = _build(N, pv, sp, dps)
        out[idx] = call(d)
    if out_dtype is not None:
        return out.astype(out_dtype)
    return out.astype(float) if dps is None else out


def _over_p_and_x(N: Any, p: Any, x: Any, method: str, space: SpaceLike, dps: Any,
                  int_result: bool = False) -> Any:
    """``getattr(distribution_of(N, p), method)(x)`` broadcast over ``p`` and ``x``."""
    if not _is_array(p):
        return _over_p(N, p, space, dps, lambda d: getattr(d, method)(x))
    pa = np.asarray(p, dtype=object)
    xa = np.asarray(x, dtype=object)
    shape = np.broadcast_shapes(pa.shape, xa.shape)
    pb = np.broadcast_to(pa, shape)
    xb = np.broadcast_to(xa, shape)
    sp = _space(space)
    N = check_N(N, minimum=1)
    dps = check_dps(dps, allow_none=True)
    cache: dict[Any, Distribution] = {}
    out = np.empty(shape, dtype=object)
    for idx in np.ndindex(*shape):
        pv, xv = pb[idx], xb[idx]
        key = _hashable(pv)
        d = cache.get(key)
        if d is None:
            d = cache[key] = _build(N, pv, sp, dps)
        out[idx] = getattr(d, method)(xv)
    if int_result:
        return out.astype(np.int64) if dps is None else out
    return out.astype(float) if dps is None else out


# --------------------------------------------------------------------------- per-k functions
def pmf(N: int, p: Any, k: Any, *, space: SpaceLike = DEFAULT_SPACE,
        dps: int | None = DEFAULT_DPS) -> Any:
    """``P(X = k)`` (eq. 7); broadcasts over ``p`` and ``k``.

    >>> pmf(2, 1, 2), pmf(4, "1/2", [1, 2])
    (Fraction(1, 3), array([Fraction(16, 39), Fraction(4, 13)], dtype=object))
    """
    return _over_p_and_x(N, p, k, "pmf", space, dps)


def logpmf(N: int, p: Any, k: Any, *, space: SpaceLike = DEFAULT_SPACE,
           dps: int | None = DEFAULT_DPS) -> Any:
    """``log P(X = k)``; works where the pmf underflows.

    >>> float(logpmf(10**6, 0.5, 1)) < -1e6
    True
    """
    return _over_p_and_x(N, p, k, "logpmf", space, dps)


def cdf(N: int, p: Any, k: Any, *, space: SpaceLike = DEFAULT_SPACE,
        dps: int | None = DEFAULT_DPS) -> Any:
    """``P(X <= k)``; ``cdf + sf == 1`` exactly for rational ``p``.

    >>> cdf(3, "1/2", 2)
    Fraction(9, 10)
    """
    return _over_p_and_x(N, p, k, "cdf", space, dps)


def logcdf(N: int, p: Any, k: Any, *, space: SpaceLike = DEFAULT_SPACE,
           dps: int | None = DEFAULT_DPS) -> Any:
    """``log P(X <= k)``."""
    return _over_p_and_x(N, p, k, "logcdf", space, dps)


def sf(N: int, p: Any, k: Any, *, space: SpaceLike = DEFAULT_SPACE,
       dps: int | None = DEFAULT_DPS) -> Any:
    """``P(X > k)`` (summed from the upper tail).

    >>> sf(3, "1/2", 2)
    Fraction(1, 10)
    """
    return _over_p_and_x(N, p, k, "sf", space, dps)


def logsf(N: int, p: Any, k: Any, *, space: SpaceLike = DEFAULT_SPACE,
          dps: int | None = DEFAULT_DPS) -> Any:
    """``log P(X > k)``."""
    return _over_p_and_x(N, p, k, "logsf", space, dps)


def ppf(N: int, p: Any, q: Any, *, space: SpaceLike = DEFAULT_SPACE,
        dps: int | None = DEFAULT_DPS) -> Any:
    """Smallest ``k`` with ``cdf(k) >= q``.

    >>> ppf(101, "0.02", "1/2")
    50
    """
    return _over_p_and_x(N, p, q, "ppf", space, dps, int_result=True)


def isf(N: int, p: Any, q: Any, *, space: SpaceLike = DEFAULT_SPACE,
        dps: int | None = DEFAULT_DPS) -> Any:
    """Smallest ``k`` with ``sf(k) <= q``."""
    return _over_p_and_x(N, p, q, "isf", space, dps, int_result=True)


# --------------------------------------------------------------------------- summaries
def mean(N: int, p: Any, *, space: SpaceLike = DEFAULT_SPACE,
         dps: int | None = DEFAULT_DPS) -> Any:
    """``E[X]``: Fraction for exact ``p``, mpf to ``dps`` digits, float for ``dps=None``.

    >>> mean(2, "1/2"), mean(101, [0.01, 0.02], dps=None).round(4).tolist()
    (Fraction(6, 5), [4.2886, 49.954])
    """
    return _over_p(N, p, space, dps, lambda d: d.mean())


def var(N: int, p: Any, *, space: SpaceLike = DEFAULT_SPACE,
        dps: int | None = DEFAULT_DPS) -> Any:
    """``Var[X]``.

    >>> var(2, "1/2")
    Fraction(4, 25)
    """
    return _over_p(N, p, space, dps, lambda d: d.var())


def variance(N: int, p: Any, *, space: SpaceLike = DEFAULT_SPACE,
             dps: int | None = DEFAULT_DPS) -> Any:
    """Deprecated alias of :func:`var`."""
    warnings.warn("symhx.variance is deprecated: use symhx.var (scipy's name)",
                  DeprecationWarning, stacklevel=2)
    return var(N, p, space=space, dps=dps)


def std(N: int, p: Any, *, space: SpaceLike = DEFAULT_SPACE,
        dps: int | None = DEFAULT_DPS) -> Any:
    """``sqrt(Var[X])`` (mpf, or float for ``dps=None``)."""
    return _over_p(N, p, space, dps, lambda d: d.std())


def entropy(N: int, p: Any, *, space: SpaceLike = DEFAULT_SPACE,
            dps: int | None = DEFAULT_DPS) -> Any:
    """Shannon entropy of X in nats."""
    return _over_p(N, p, space, dps, lambda d: d.entropy())


def median(N: int, p: Any, *, space: SpaceLike = DEFAULT_SPACE,
           dps: int | None = DEFAULT_DPS) -> Any:
    """``ppf(1/2)``.

    >>> median(101, "0.02")
    50
    """
    return _over_p(N, p, space, dps, lambda d: d.median(), out_dtype=np.int64)


def interval(N: int, p: Any, confidence: Any, *, space: SpaceLike = DEFAULT_SPACE,
             dps: int | None = DEFAULT_DPS) -> tuple[int, int]:
    """``(ppf((1 - c)/2), ppf((1 + c)/2))`` for a scalar ``p``."""
    return distribution_of(N, p, space=space, dps=dps).interval(confidence)


def rvs(N: int, p: Any, size: Any = None, random_state: Any = None, *,
        space: SpaceLike = DEFAULT_SPACE) -> Any:
    """Random draws of X (see :meth:`symhx.distribution.Distribution.rvs`).

    >>> bool((rvs(101, 0.02, 3, random_state=7) == rvs(101, 0.02, 3, random_state=7)).all())
    True
    """
    return distribution_of(N, p, space=space, dps=None).rvs(size, random_state)


def normaliser(N: int, p: Any, *, space: SpaceLike = DEFAULT_SPACE,
               dps: int | None = DEFAULT_DPS) -> Any:
    """``Gamma_{N,p}`` (eq. 8), or its generalisation to ``space``.

    >>> normaliser(4, 1) == sum(phi for phi in (4, 6, 8, 6))
    True
    """
    return _over_p(N, p, space, dps, lambda d: d.normaliser)


# --------------------------------------------------------------------------- modes
def _modes1(N: int, p: Any, sp: Space) -> tuple[int, ...]:
    p, sc = _scalar_or_classes(N, p)
    if sc is not None:
        return site_modes(N, sc, sp)
    fr, p = check_p(p)
    if sp.base == "simple":
        return simple_modes(N, fr, p)
    return space_modes(sp, N, p, fr)


def modes(N: int, p: Any, *, space: SpaceLike = DEFAULT_SPACE) -> Any:
    """All maximisers of ``P(X = k)``, increasing; certified exact for every rational ``p``
    (floats at their binary value), any ``N``.  An array of ``p`` gives an object array of
    tuples.  ``p`` may be a :class:`symhx.SiteClasses` (exact integer comparisons for exact
    class probabilities, else Arb balls at doubling precision with the exact table on a near
    tie; :func:`symhx.site_distribution.site_modes`).

    >>> modes(5, "1/2"), modes(100, "1/50", space="eq41")
    ((1, 2, 3), (53,))
    >>> from symhx.sites import SiteClasses
    >>> modes(4, SiteClasses((2, 2), (1, 2)))            # W = 6, 13, 24, 24: a tie
    (3, 4)
    """
    sp = _space(space)
    N = check_N(N, minimum=1)
    if not _is_array(p):
        return _modes1(N, p, sp)
    pa = np.asarray(p, dtype=object)
    out = np.empty(pa.shape, dtype=object)
    for idx, pv in np.ndenumerate(pa):
        out[idx] = _modes1(N, pv, sp)
    return out


def mode(N: int, p: Any, *, space: SpaceLike = DEFAULT_SPACE) -> Any:
    """The mode of X (the smallest maximiser), eq. (7); for an array of ``p`` an int64 array
    (an object array of Python ints when a mode does not fit in int64, e.g. ``N = 10**100``).

    >>> mode(101, 0.01), mode(101, 0.013), mode(10**100, "1e-100")
    (1, 21, 1)
    """
    m = modes(N, p, space=space)
    if isinstance(m, np.ndarray):
        first = [t[0] for t in m.ravel()]
        fits = all(v <= _INT64_MAX for v in first)
        return np.array(first, dtype=np.int64 if fits else object).reshape(m.shape)
    return m[0]


_INT64_MAX = 2**63 - 1


# --------------------------------------------------------------------------- critical point
def critical_point(N: Any, *, weights: Any = None, space: SpaceLike = DEFAULT_SPACE,
                   dps: int | None = DEFAULT_DPS) -> CriticalPoint:
    """The critical probability ``p_c`` at which the mode of X jumps away from 1 (eqs. 11-16),
    over ``space``; ``dps=None`` returns float64 ``p``, ``q``, ``p_d`` (computed at 20 digits).

    With ``weights`` (a :class:`symhx.SiteClasses` or a sequence of ``N`` per-site weights):
    the critical point along the direction ``p_v = t w_v`` of site probabilities, a
    :class:`symhx.critical_sites.DirectionCriticalPoint` whose ``p`` is
    ``t_c = min_{k>=2} (e_1(w)/((k-1)! e_k(w)))**(1/(k-1))`` (simple circuits only; see
    :func:`symhx.critical_sites.direction_critical_point` for the methods and limits).  One
    class of weight ``w`` gives today's ``p_c / w``.

    Parameters
    ----------
    N : int
        Number of vertices, ``N >= 2``.
    weights : SiteClasses or sequence, optional
        The direction of the site probabilities (only ratios matter).
    space : str or Space
        The sample space (``"simple"`` only with ``weights``).
    dps : int or None
        Digits of ``p``, ``q``, ``p_d``; ``None`` for float64 (computed at 20 digits).

    Returns
    -------
    CriticalPoint or DirectionCriticalPoint

    Raises
    ------
    ValueError
        A bad ``N``, ``space``, ``dps`` or ``weights``; ``weights`` with a higher-order space.

    >>> cp = critical_point(101, dps=20)
    >>> cp.k_before, cp.k_after
    (1, 20)
    >>> from symhx.sites import SiteClasses
    >>> cp = critical_point(101, weights=SiteClasses((2, 99), (3, 1)), dps=20)
    >>> cp.k_after, cp.method            # walls 3x as likely as pipe pairs: jumps to 19
    (19, 'table')
    """
    sp = _space(space)
    N = check_N(N)
    d = check_dps(dps, allow_none=True)
    work = 20 if d is None else d
    if weights is not None:
        if sp.base != "simple":
            raise ValueError(f"weights (a direction of site probabilities) are supported over "
                             f"the simple space only, got space={sp.name!r}; pass "
                             f"space='simple'")
        dcp = direction_critical_point(N, weights, dps=work)
        if d is None:
            dcp = dataclasses.replace(dcp, p=float(dcp.p), q=float(dcp.q),
                                      p_d=None if dcp.p_d is None else float(dcp.p_d))
        return dcp
    if sp.base == "simple":
        cp = simple_critical_point(N, dps=work)
    else:
        cp = space_critical_point(N, space=sp, dps=work)
    if d is None:  # float(mpf) rounds the mpf's own bits once: no context involved
        cp = dataclasses.replace(cp, p=float(cp.p), q=float(cp.q), p_d=float(cp.p_d))
    return cp
