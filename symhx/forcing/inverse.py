"""Inverse of the impact probability: the forcing ``sigma`` at which ``p(sigma)`` equals ``p``."""

from __future__ import annotations

import dataclasses
import math
from collections.abc import Callable
from fractions import Fraction
from typing import Any

import mpmath
import numpy as np

from symhx.forcing.arguments import ForcingParams, float_arg, is_array, mp_arg, mpf_of
from symhx.forcing.probability import evaluate, impact_probability
from symhx.validation import check_dps, to_rational

__all__ = ["sigma_for_impact_probability"]


def _target(p: Any, name: str = "p") -> Fraction:
    fr = to_rational(p, name)
    if fr is None:
        fr = Fraction(str(p.evalf(40)))
    if not 0 < fr < 1:
        raise ValueError(f"{name} must be in (0, 1), got {p!r}")
    return fr


def sigma_for_impact_probability(
    p: Any,
    *,
    sigma1: Any = None,
    omega: Any = 1,
    Omega: Any = None,
    d: Any = 1,
    dps: int | None = None,
) -> Any:
    r"""The forcing ``sigma`` for which the impact probability equals ``p`` (inverse of p(sigma)).

    ``p(sigma)`` increases strictly from 0 to 1 (with ``sigma1`` fixed: from ``P(R_1 > d)``).
    The root of ``ln p(sigma) = ln p`` (or ``ln(1 - p(sigma)) = ln(1 - p)`` when ``p > 1/2``,
    which keeps the relative accuracy of both tails) is bracketed in ``ln sigma`` from the tail
    asymptotics, found by Brent's method in float64 and, for ``dps``, polished by the secant
    method at the working precision.

    Parameters
    ----------
    p : float or array_like (or mpf / str for ``dps``)
        Target impact probability in ``(0, 1)``.
    sigma1, omega, Omega, d, dps
        As in :func:`impact_probability`; with ``sigma1`` given, ``sigma_0`` is solved for at
        fixed ``sigma1``.

    Returns
    -------
    float, ndarray or mpf
        ``sigma``.

    Raises
    ------
    ValueError
        ``p`` outside ``(0, 1)`` or not reachable (fixed ``sigma1``).

    >>> s = sigma_for_impact_probability(0.5)
    >>> abs(impact_probability(s) - 0.5) < 1e-15
    True
    >>> s = sigma_for_impact_probability("1e-10", dps=30)
    >>> abs(impact_probability(s, dps=30) / mpmath.mpf("1e-10") - 1) < 1e-28
    True
    """
    dps = check_dps(dps, allow_none=True)
    for name, v in (("sigma1", sigma1), ("omega", omega), ("Omega", Omega), ("d", d)):
        if is_array(v) and not (name in ("sigma1", "Omega") and isinstance(v, (list, tuple))):
            raise TypeError(f"{name} must be a scalar for the inverse, got {type(v).__name__}")
    fp = ForcingParams.validated(1, sigma1, omega, Omega, d, dps=dps)
    if dps is None:
        if is_array(p):
            pa = float_arg("p", p)
            bad = ~(pa < 1)
            if bad.any():
                idx = tuple(int(j) for j in np.argwhere(bad)[0])
                where = idx[0] if len(idx) == 1 else idx
                raise ValueError(f"p must be in (0, 1), got {float(pa[idx])!r} at index {where}")
            out = np.empty(pa.shape)
            for idx in np.ndindex(pa.shape):
                out[idx] = _inverse_float(float(pa[idx]), fp)
            return out
        pf = float(_target(p))
        if not 0.0 < pf < 1.0:
            raise ValueError(f"p = {p!r} rounds to {pf} in float64; use dps=")
        return _inverse_float(pf, fp)

    def one(pv: Any) -> mpmath.mpf:
        fr = _target(pv)
        with mpmath.workdps(dps + 15):
            pm = mpf_of(fr)
        return _inverse_mp(pm, fp, dps, fr)

    if is_array(p):
        pa = np.asarray(p, dtype=object)
        out = np.empty(pa.shape, dtype=object)
        for idx in np.ndindex(pa.shape):
            try:
                out[idx] = one(pa[idx])
            except ValueError as exc:
                raise ValueError(f"{exc} at index {idx if len(idx) > 1 else idx[0]}") from None
        return out
    return one(p)


def _with_sigma(fp: ForcingParams, s: Any) -> ForcingParams:
    return dataclasses.replace(fp, sigma=np.asarray(s) if not fp.exact else s)


def _inverse_objective(p_target: float, fp: ForcingParams) -> Callable[[float], float]:
    if p_target <= 0.5:
        lt = math.log(p_target)
        return lambda ls: float(evaluate(_with_sigma(fp, math.exp(ls)), None, "logp")) - lt
    lt = math.log1p(-p_target)
    return lambda ls: lt - float(evaluate(_with_sigma(fp, math.exp(ls)), None, "logq"))


def _inverse_float(p: float, fp: ForcingParams) -> float:
    from scipy.optimize import brentq

    if fp.exact:  # the float64 start of the mpmath path
        fp = ForcingParams.validated(
            1, None if fp.sigma1 is None else (tuple(float(s) for s in fp.sigma1)
                                               if isinstance(fp.sigma1, tuple)
                                               else float(fp.sigma1)),
            float(fp.omega),
            None if fp.Omega is None else (list(float(o) for o in fp.Omega)
                                           if fp.components else float(fp.Omega)),
            float(fp.d), dps=None)
    f = _inverse_objective(p, fp)
    d = float(fp.d)
    lo = hi = math.log(d)
    for _ in range(400):
        if f(lo) < 0:
            break
        lo -= 1.0
    else:
        raise ValueError(f"p = {p!r} is not reachable for these parameters (sigma1 fixed?)")
    for _ in range(400):
        if f(hi) > 0:
            break
        hi += 1.0
    else:  # pragma: no cover
        raise ValueError(f"p = {p!r} is not reachable for these parameters")
    ls = brentq(f, lo, hi, xtol=1e-15, rtol=4 * np.finfo(float).eps, maxiter=200)
    return math.exp(ls)


def _inverse_mp(p: mpmath.mpf, fp: ForcingParams, dps: int, exact: Fraction) -> mpmath.mpf:
    """Secant polish at ``dps + 15`` digits; the target's log (or log of ``1 - p``) is taken
    from the exact ``Fraction``, so ``1 - p`` keeps its relative accuracy for ``p`` near 1."""
    try:
        s0 = _inverse_float(float(p), fp) if 1e-300 < p < 1 - 1e-16 else None
    except (ValueError, OverflowError):
        s0 = None
    work = dps + 15
    with mpmath.workdps(work):
        if p <= 0.5:
            lt = mpmath.log(mpf_of(exact))

            def f(ls: mpmath.mpf) -> mpmath.mpf:
                return evaluate(_with_sigma(fp, mpmath.exp(ls)), work, "logp") - lt
        else:
            lt = mpmath.log(mpf_of(1 - exact))

            def f(ls: mpmath.mpf) -> mpmath.mpf:
                return lt - evaluate(_with_sigma(fp, mpmath.exp(ls)), work, "logq")

        if s0 is None:  # far outside float64: bracket, then bisect in ln(sigma)
            lo = hi = mpmath.log(mp_arg("d", fp.d))
            for _ in range(2000):
                if not f(lo) > 0:
                    break
                lo -= 4
            else:
                raise ValueError(f"p = {p} is not reachable for these parameters")
            for _ in range(2000):
                if not f(hi) < 0:
                    break
                hi += 4
            else:
                raise ValueError(f"p = {p} is not reachable for these parameters")
            for _ in range(60):
                mid = (lo + hi) / 2
                if f(mid) > 0:
                    hi = mid
                else:
                    lo = mid
            x0 = (lo + hi) / 2
        else:
            x0 = mpmath.log(s0)
        ls = mpmath.findroot(f, (x0, x0 + mpmath.mpf(10) ** -12), solver="secant",
                             tol=mpmath.mpf(10) ** (-2 * work + 10))
        val = mpmath.exp(ls)
    with mpmath.workdps(dps):
        return +val


_ = impact_probability  # used by the docstring example
