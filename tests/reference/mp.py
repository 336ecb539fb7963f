"""Comparison helpers and argument grids for checks against mpmath (in the style of
scipy.special's ``_mptestutils``): relative errors measured at a precision of their own, and
log-spaced grids that reach every regime of an argument.

>>> import mpmath
>>> assert_mp_close(mpmath.mpf(1) / 3, mpmath.mpf("0.3333333333"), rtol=1e-9)
>>> [float(x) for x in log_grid(1e-2, 1e2, 5)]
[0.01, 0.1, 1.0, 10.0, 100.0]
"""

from __future__ import annotations

import math
from collections.abc import Iterable, Iterator
from fractions import Fraction
from typing import Any

import mpmath
import numpy as np

__all__ = ["assert_mp_close", "int_log_grid", "log_grid", "rel_err", "signed_log_grid", "to_mp"]


def to_mp(x: Any) -> mpmath.mpf:
    """``x`` (int, Fraction, float, mpf of any context, decimal string) as a global mpf at the
    current precision (a Fraction is divided at that precision, whatever its size)."""
    if isinstance(x, Fraction):
        return mpmath.mpf(x.numerator) / x.denominator
    if hasattr(x, "_mpf_"):
        return mpmath.mp.make_mpf(x._mpf_)
    return mpmath.mpf(x)


def rel_err(actual: Any, expected: Any, dps: int = 60) -> mpmath.mpf:
    """``|actual - expected| / |expected|`` at ``dps`` digits (the absolute error when
    ``expected`` is 0; 0 when both are the same infinity)."""
    with mpmath.workdps(dps):
        a, e = to_mp(actual), to_mp(expected)
        if mpmath.isinf(e) or mpmath.isinf(a):
            return mpmath.mpf(0) if a == e else mpmath.inf
        if mpmath.isnan(a) or mpmath.isnan(e):
            return mpmath.inf
        return abs(a - e) / abs(e) if e != 0 else abs(a)


def assert_mp_close(actual: Any, expected: Any, *, rtol: Any, atol: Any = 0, dps: int | None = None,
                    what: str = "") -> None:
    """Assert ``|actual - expected| <= atol + rtol |expected|`` element-wise, measured at
    ``dps`` digits (default: enough for ``rtol``).  ``actual``/``expected`` may be scalars or
    equal-shaped sequences/arrays of numbers mpmath can read.  The message names the worst
    element and its error."""
    a_list = list(np.ravel(np.asarray(actual, dtype=object)))
    e_list = list(np.ravel(np.asarray(expected, dtype=object)))
    assert len(a_list) == len(e_list), f"{what}: {len(a_list)} values against {len(e_list)}"
    if dps is None:
        dps = max(30, int(-math.log10(float(rtol))) + 20) if rtol else 60
    worst = None
    with mpmath.workdps(dps):
        for i, (a, e) in enumerate(zip(a_list, e_list, strict=True)):
            am, em = to_mp(a), to_mp(e)
            if am == em:
                continue
            if not (mpmath.isfinite(am) and mpmath.isfinite(em)):
                raise AssertionError(f"{what}[{i}]: {a} != {e}")
            err = abs(am - em)
            bound = mpmath.mpf(atol) + mpmath.mpf(rtol) * abs(em)
            if err > bound and (worst is None or err / bound > worst[0]):
                worst = (err / bound, i, a, e, err)
    if worst is not None:
        _, i, a, e, err = worst
        raise AssertionError(
            f"{what}[{i}]: {mpmath.nstr(to_mp(a), 20)} vs {mpmath.nstr(to_mp(e), 20)}"
            f" (abs err {mpmath.nstr(err, 3)}, rtol={rtol}, atol={atol})")


def log_grid(lo: float, hi: float, n: int) -> np.ndarray:
    """``n`` float64 points from ``lo`` to ``hi`` (both > 0), equally spaced in log."""
    return np.logspace(math.log10(lo), math.log10(hi), n)


def signed_log_grid(lo: float, hi: float, n: int) -> np.ndarray:
    """``log_grid`` mirrored to negative values, with 0 in the middle (``2n + 1`` points)."""
    g = log_grid(lo, hi, n)
    return np.concatenate([-g[::-1], [0.0], g])


def int_log_grid(lo: int, hi: int, n: int) -> list[int]:
    """Distinct integers from ``lo`` to ``hi`` (any size), about equally spaced in log, ends
    included: ``int_log_grid(2, 10**1000, 5)`` reaches 10**1000 exactly."""
    if hi <= lo:
        return [lo]
    with mpmath.workdps(max(30, len(str(hi)) + 10)):
        a, b = mpmath.log(lo), mpmath.log(hi)
        pts = {lo, hi}
        for i in range(1, n - 1):
            pts.add(int(mpmath.nint(mpmath.exp(a + (b - a) * i / (n - 1)))))
    return sorted(x for x in pts if lo <= x <= hi)


def pairs(xs: Iterable[Any], ys: Iterable[Any]) -> Iterator[tuple[Any, Any]]:
    """The Cartesian grid of two argument lists."""
    ys = list(ys)
    for x in xs:
        for y in ys:
            yield x, y
