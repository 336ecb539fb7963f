"""mpmath kernels of one forcing component: p, 1 - p and log p from ``x = d**2/(2 s_0**2)``,
``y = d**2/(2 s_1**2)`` (eq. 27 in closed form), cheap float estimates that size the guard
digits, and the positive integrals of the derivative in closed form.
"""

from __future__ import annotations

import math
import sys

import mpmath

from symhx._mpctx import local
from symhx._mpctx import mp as thread_mp
from symhx.forcing.arguments import mp_arg
from symhx.forcing.kernels_float import SQRT_PI
from symhx.validation import InputError

__all__ = [
    "MAX_EXPONENT",
    "estimate",
    "estimate_float",
    "guard_digits",
    "mp_i2",
    "mp_i3",
    "mp_p_from_xy",
    "mp_q_from_xy",
    "mp_xy_forcing",
    "precision_plan",
]


def _uv_b_over_r(x: mpmath.mpf, y: mpmath.mpf) -> tuple[mpmath.mpf, mpmath.mpf]:
    """``(u v, b / r)`` with ``p = exp(-u v) b / r``: the closed form's positive terms."""
    x, y = local(x), local(y)   # any context's mpf: this thread's arithmetic
    r = thread_mp().sqrt(x + y)
    u = x / r
    v = y / r
    b = v * thread_mp().exp(-u * u) + u * thread_mp().exp(-v * v)
    b += thread_mp().sqrt(thread_mp().pi) * u * v * (thread_mp().erf(u) + thread_mp().erf(v))
    return u * v, b / r


def mp_p_from_xy(x: mpmath.mpf, y: mpmath.mpf) -> mpmath.mpf:
    uv, b_r = _uv_b_over_r(x, y)
    return thread_mp().exp(-uv) * b_r


def mp_q_from_xy(x: mpmath.mpf, y: mpmath.mpf) -> mpmath.mpf:
    """``1 - p`` at the current precision, raising the precision by the digits that cancel.

    The cancellation in ``1 - p`` is known a priori: ``1 - p ~ x y / 6`` for small ``x + y``;
    the result is checked a posteriori and recomputed if more digits cancelled than planned.
    """
    prec = thread_mp().prec
    x, y = local(x), local(y)
    p = mp_p_from_xy(x, y)
    if p <= 0.5:
        return 1 - p
    extra = max(0, -thread_mp().log(x * y / 7, 2)) + 20
    for _ in range(8):
        with thread_mp().workprec(prec + int(extra)):
            q = 1 - mp_p_from_xy(x, y)
            lost = -thread_mp().log(q, 2) if q > 0 else thread_mp().inf
        if lost + 10 <= extra:
            return +q
        extra = 2 * extra if not thread_mp().isfinite(lost) else lost + 30
    raise ArithmeticError("1 - p: cancellation could not be resolved")  # pragma: no cover


def mp_xy_forcing(sigma, sigma1, omega, Omega, d) -> tuple[mpmath.mpf, mpmath.mpf]:
    """``x = d**2/(4 sigma0**2)``, ``y = d**2 (omega**2 - Omega**2)**2 / (4 sigma1**2)``."""
    s0 = mp_arg("sigma", sigma)
    s1 = s0 if sigma1 is None else mp_arg("sigma1", sigma1)
    om = mp_arg("omega", omega)
    dd = mp_arg("d", d)
    om2 = 2 if Omega is None else mp_arg("Omega", Omega) ** 2
    delta = om * om - om2
    if delta == 0:
        raise InputError("Omega: resonance Omega == omega (infinite forced amplitude)")
    return dd * dd / (4 * s0 * s0), (dd * delta) ** 2 / (4 * s1 * s1)


def estimate(x: mpmath.mpf, y: mpmath.mpf) -> tuple[float, float, float]:
    """Rough ``(uv, x*y, p)`` in float64 (mpf exponents keep huge/tiny values in range)."""
    lx = float(thread_mp().log(x)) if x > 0 else -1e300
    ly = float(thread_mp().log(y)) if y > 0 else -1e300
    lxy = lx + ly
    ls = max(lx, ly) + math.log1p(math.exp(-abs(lx - ly)))
    le = lxy - ls
    e = math.exp(le) if le < 709.78 else math.inf  # inf: beyond MAX_EXPONENT
    if e > 50.0:
        return e, math.exp(min(lxy, 700.0)), 0.0
    if abs(lx - ly) > 60.0 or not -600.0 < lx < 600.0 or not -600.0 < ly < 600.0:
        # scales far apart (p ~ exp(-min(x, y))) or both far above d (p ~ 1)
        return e, math.exp(min(lxy, 700.0)), math.exp(-e)
    xf, yf = math.exp(lx), math.exp(ly)
    r = math.sqrt(xf + yf)
    u, v = xf / r, yf / r
    b = v * math.exp(-u * u) + u * math.exp(-v * v) + SQRT_PI * u * v * (math.erf(u) + math.erf(v))
    return e, math.exp(min(lxy, 700.0)), math.exp(-e) * b / r


def estimate_float(sigma, sigma1, omega, Omega, d) -> tuple[float, float, float] | None:
    """:func:`estimate` with Python floats when every input converts to a normal float."""
    try:
        s0 = float(sigma)
        s1 = s0 if sigma1 is None else float(sigma1)
        om = float(omega)
        om2 = 2.0 if Omega is None else float(Omega) ** 2
        dd = float(d)
        x = (dd / (2 * s0)) ** 2
        y = (dd * (om * om - om2) / (2 * s1)) ** 2
    except (TypeError, ValueError, OverflowError, ZeroDivisionError):
        return None
    if not (1e-150 < x < 1e150 and 1e-150 < y < 1e150 and s0 > 0 and s1 > 0 and dd > 0):
        return None
    e = x * y / (x + y)
    if e > 50.0:
        return e, x * y, 0.0
    r = math.sqrt(x + y)
    u, v = x / r, y / r
    b = v * math.exp(-u * u) + u * math.exp(-v * v) + SQRT_PI * u * v * (math.erf(u) + math.erf(v))
    return e, x * y, math.exp(-e) * b / r


#: cap on the exponent ``E = uv`` of ``p ~ exp(-E)`` in the mpmath evaluation (``p`` below
#: ``10**(-7e307)``, beyond every float64 ``log p``): ``exp`` of a larger argument costs seconds
#: to minutes, so such a forcing (``d/sigma`` above ~1e154) is refused up front
MAX_EXPONENT = sys.float_info.max


def guard_digits(e: float) -> int:
    """Extra digits so that ``exp(-uv)`` keeps its relative accuracy (uv ~ 1e6 costs 6).

    Raises ValueError when ``e`` exceeds :data:`MAX_EXPONENT` (before any mpmath work).
    """
    if not e <= MAX_EXPONENT:
        raise InputError(
            f"sigma, d: the forcing gives p = exp(-E) with E ~ "
            f"{'> 1e308' if e == math.inf else format(e, '.3g')} above the cap "
            f"MAX_EXPONENT = {MAX_EXPONENT:.3g} (symhx.forcing.kernels_mp.MAX_EXPONENT) of the "
            "mpmath evaluation (d/sigma must stay "
            "below ~1e154)")
    return 12 + (int(math.log10(e)) + 1 if e > 1 else 0)


def precision_plan(est: tuple[float, float, float], want: str) -> tuple[int, bool]:
    """``(guard, direct_q)``: the guard digits of one evaluation and whether ``1 - p`` is formed
    directly as ``1 - p`` (``want`` in ``("q", "logq")`` and ``p`` near or above 1/2).

    ``est = (uv, x y, p)`` is the rough estimate of :func:`estimate`/:func:`estimate_float`.
    For small ``x, y``, ``1 - p ~ x y / 6`` cancels ``log10(6/(x y))`` digits: they are added up
    front (the result is checked a posteriori).
    """
    e, xy, pest = est
    guard = guard_digits(e)
    direct_q = want in ("q", "logq") and pest > 0.45
    if direct_q:
        guard += 8 + max(0, int(math.log10(7.0 / max(xy, 1e-300))) + 1) if xy < 7 else 10
    return guard, direct_q




# ---- mpmath groups
def mp_i2(u: mpmath.mpf, v: mpmath.mpf) -> mpmath.mpf:
    """``int_{-v}^{u} (v+z)(u-z) exp(-z**2) dz`` in closed form, extra digits for cancellation."""
    u, v = local(u), local(v)
    r = u + v
    extra = 10 + (int(-thread_mp().log10(r**2 / 3)) if r < 1 else 0)
    with thread_mp().workdps(thread_mp().dps + extra):
        k0 = thread_mp().sqrt(thread_mp().pi) / 2 * (thread_mp().erf(u) + thread_mp().erf(v))
        val = (u * v - thread_mp().mpf(1) / 2) * k0
        val += (u * thread_mp().exp(-v * v) + v * thread_mp().exp(-u * u)) / 2
    return +val


def mp_i3(u: mpmath.mpf, v: mpmath.mpf) -> mpmath.mpf:
    """``int_{-v}^{u} (v+z)**2 (u-z) exp(-z**2) dz`` (closed form, extra digits as it cancels)."""
    u, v = local(u), local(v)
    r = u + v
    extra = 10 + (int(-thread_mp().log10(r**4 / 12)) if r < 1 else 0)
    with thread_mp().workdps(thread_mp().dps + extra):
        eu, ev = thread_mp().exp(-u * u), thread_mp().exp(-v * v)
        k0 = thread_mp().sqrt(thread_mp().pi) / 2 * (thread_mp().erf(u) + thread_mp().erf(v))
        k1 = (ev - eu) / 2
        k2 = k0 / 2 - (u * eu + v * ev) / 2
        k3 = ((v * v + 1) * ev - (u * u + 1) * eu) / 2
        val = u * v * v * k0 + (2 * u * v - v * v) * k1 + (u - 2 * v) * k2 - k3
    return +val

