"""Inverse of the impact probability: the forcing ``sigma`` at which ``p(sigma)`` equals ``p``."""

from __future__ import annotations

import dataclasses
import math
from collections.abc import Callable
from fractions import Fraction
from typing import Any

import mpmath
import numpy as np

from symhx._mpctx import mp as thread_mp
from symhx.forcing.arguments import ForcingParams, exported, float_arg, is_array, mpf_of
from symhx.forcing.probability import evaluate, impact_probability
from symhx.validation import InputError, check_dps, float64_refusal, to_rational

__all__ = ["sigma_for_impact_probability"]


def _target(p: Any, digits: int) -> Fraction:
    """``p`` as an exact Fraction; a real sympy irrational is evaluated to ``digits`` digits (of
    ``1 - p`` when ``p > 1/2``, which keeps the relative accuracy of ``1 - p`` near 1)."""
    fr = to_rational(p, "p")
    if fr is None:
        fr = Fraction(str(p.evalf(digits)))
        if fr > Fraction(1, 2):
            fr = 1 - Fraction(str((1 - p).evalf(digits)))
    if not 0 < fr < 1:
        raise InputError(f"p must be in (0, 1), got {p!r}")
    return fr


@exported
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
    which keeps the relative accuracy of both tails) is bracketed in ``ln sigma`` by steps from
    ``ln d`` that double, found by Brent's method in float64 (relative error below ``1e-14``
    where ``p(sigma)`` is well conditioned) and, for ``dps``, polished by the secant method at
    ``dps + 15`` digits (correct to ``dps`` digits; roots with ``|ln(sigma/d)| < 32767``). A
    sympy irrational ``p`` is evaluated to ``dps + 20`` digits (of ``1 - p`` when ``p > 1/2``).

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
                raise InputError(f"p must be in (0, 1), got {float(pa[idx])!r} at index {where}")
            out = np.empty(pa.shape)
            for idx in np.ndindex(pa.shape):
                out[idx] = _inverse_float(float(pa[idx]), fp)
            return out
        pf = float(_target(p, 40))
        if not 0.0 < pf < 1.0:
            raise float64_refusal(f"p = {p!r} rounds to {pf} in float64")
        return _inverse_float(pf, fp)

    def one(pv: Any) -> mpmath.mpf:
        return _inverse_mp(_target(pv, dps + 20), fp, dps)

    if is_array(p):
        pa = np.asarray(p, dtype=object)
        out = np.empty(pa.shape, dtype=object)
        for idx in np.ndindex(pa.shape):
            try:
                out[idx] = one(pa[idx])
            except ValueError as exc:
                raise type(exc)(f"{exc} at index {idx if len(idx) > 1 else idx[0]}") from None
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


def _bracket(f: Callable[[Any], Any], x: Any, tries: int,
             clip: tuple[float, float] | None = None) -> tuple[Any, Any] | None:
    """``(lo, hi)`` with ``f(lo) <= 0 <= f(hi)`` for an increasing ``f``, by steps from ``x``
    towards the root that double (1, 2, 4, ...) and stay inside ``clip``; ``None`` when ``tries``
    steps find no change of sign (or ``f`` is NaN)."""
    down = f(x) > 0
    a, step = x, 1
    for _ in range(tries):
        b = a - step if down else a + step
        if clip is not None:
            b = min(max(b, clip[0]), clip[1])
        fb = f(b)
        if (fb <= 0) if down else (fb >= 0):
            return (b, a) if down else (a, b)
        a, step = b, 2 * step
    return None


# ln sigma inside the float64 range (subnormals included): exp never overflows, never gives 0
_FLOAT_LS = (-744.0, 709.0)


def _float_params(fp: ForcingParams) -> ForcingParams:
    """The float64 copy of exact parameters (the start of the mpmath path)."""
    def conv(v: Any) -> Any:
        return None if v is None else [float(x) for x in v] if isinstance(v, tuple) else float(v)

    return ForcingParams.validated(float(fp.sigma), conv(fp.sigma1), float(fp.omega),
                                   conv(fp.Omega), float(fp.d))


def _inverse_float(p: float, fp: ForcingParams) -> float:
    from scipy.optimize import brentq

    f = _inverse_objective(p, fp)
    br = _bracket(f, math.log(float(fp.d)), 12, _FLOAT_LS)
    if br is None:
        raise InputError(f"p = {p!r} is not reachable for these parameters (sigma1 fixed?)")
    ls = brentq(f, br[0], br[1], xtol=1e-15, rtol=4 * np.finfo(float).eps, maxiter=200)
    return math.exp(ls)


def _inverse_mp(exact: Fraction, fp: ForcingParams, dps: int) -> mpmath.mpf:
    """Secant polish at ``dps + 15`` digits from the float64 root (or, outside float64, from a
    bracket refined by bisection); the target's log (or log of ``1 - p``) is taken from the exact
    ``Fraction``, so ``1 - p`` keeps its relative accuracy for ``p`` near 1."""
    upper = exact > Fraction(1, 2)
    work = dps + 15
    with thread_mp().workdps(work):
        tail = mpf_of(1 - exact if upper else exact)  # p, or 1 - p when p > 1/2
        lt = thread_mp().log(tail)
    s0 = None
    if tail > 1e-300:  # the float64 start (p and 1 - p representable)
        try:
            s0 = _inverse_float(float(exact), _float_params(fp))
        except (ValueError, OverflowError):  # not reachable in float64: bracket below
            pass
    with thread_mp().workdps(work):
        if upper:
            def f(ls: mpmath.mpf) -> mpmath.mpf:
                return lt - evaluate(_with_sigma(fp, thread_mp().exp(ls)), work, "logq")
        else:
            def f(ls: mpmath.mpf) -> mpmath.mpf:
                return evaluate(_with_sigma(fp, thread_mp().exp(ls)), work, "logp") - lt

        if s0 is None:  # far outside float64: bracket, then bisect in ln(sigma)
            br = _bracket(f, thread_mp().log(mpf_of(fp.d)), 15)  # |ln(sigma/d)| < 2**15
            if br is None:
                raise InputError(f"{'1 - p' if upper else 'p'} = {thread_mp().nstr(tail, 10)} is "
                                 "not reachable for these parameters (no root with "
                                 "|ln(sigma/d)| < 32767)")
            lo, hi = br
            for _ in range(60):
                mid = (lo + hi) / 2
                if f(mid) > 0:
                    hi = mid
                else:
                    lo = mid
            x0 = (lo + hi) / 2
        else:
            x0 = thread_mp().log(s0)
        ls = thread_mp().findroot(f, (x0, x0 + thread_mp().mpf(10) ** -12), solver="secant",
                             tol=thread_mp().mpf(10) ** (-2 * work + 10))
        val = thread_mp().exp(ls)
    with thread_mp().workdps(dps):
        return +val


_ = impact_probability  # used by the docstring example
