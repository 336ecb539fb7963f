"""Scalar fast path of the one-component mpmath evaluation on raw mpf tuples (``mpmath.libmp``):
the same operations, roundings and precisions as the mpf-object code, without the
per-operation object and context costs (used for float and dyadic inputs)."""

from __future__ import annotations

import math
from fractions import Fraction
from typing import Any

import mpmath

from symhx._mpctx import mp as thread_mp
from symhx.forcing.kernels_mp import estimate_float, precision_plan

__all__ = ["from_xy_raw", "raw_xy", "single_mp_fast"]

_lm = mpmath.libmp
_RND = _lm.round_nearest
_MP_FOUR = _lm.from_int(4)
_LOG2E = 1.4426950408889634
_SQRT_PI_CACHE: dict[int, tuple] = {}


def _sqrt_pi_raw(prec: int) -> tuple:
    """``sqrt(pi)`` rounded to ``prec`` bits (as ``mpmath.sqrt(mpmath.pi)``), cached."""
    v = _SQRT_PI_CACHE.get(prec)
    if v is None:
        v = _SQRT_PI_CACHE[prec] = _lm.mpf_sqrt(_lm.mpf_pi(prec, _RND), prec, _RND)
    return v


def _erf_raw(u: tuple, prec: int) -> tuple:
    """``erf(u)`` for ``u > 0`` to ``prec`` bits: mpmath's Taylor series where it is cheap, and
    ``1 - erfc(u)`` (erfc at the few bits that survive, by its asymptotic series) or ``1`` where
    that series is slow (``u`` of ~10 costs mpmath ~300 terms)."""
    mag = u[2] + u[3]
    if mag < 2:  # u < 2
        return _lm.mpf_erf(u, prec, _RND)
    if mag > 40:
        return _lm.fone
    uf = _lm.to_float(u)
    u2 = uf * uf * _LOG2E  # erfc(u) < exp(-u**2) = 2**-u2 (u >= 1)
    if u2 > prec + 3:  # 1 - erf(u) < 1/8 ulp of 1: erf rounds to 1
        return _lm.fone
    pc = max(prec - int(u2) + 30, 53)  # bits of erfc(u) that reach the result (+ 30 guard)
    n = int(uf)
    if n * n * 1.44 > pc + 20 + 2 * mag:  # mpmath's erfc uses its asymptotic series
        return _lm.mpf_sub(_lm.fone, _lm.mpf_erfc(u, pc, _RND), prec, _RND)
    return _lm.mpf_erf(u, prec, _RND)


def _raw_in(value: Any) -> tuple | None:
    """A finite positive float, small int or dyadic Fraction (a float's exact value) as an exact
    raw mpf; None: use the general path."""
    if isinstance(value, Fraction):
        num, den = value.numerator, value.denominator
        if num > 0 and den & (den - 1) == 0 and num.bit_length() <= 64:
            return _lm.from_man_exp(num, -(den.bit_length() - 1))
        return None
    if isinstance(value, float):
        return _lm.from_float(float(value)) if 0.0 < value < math.inf else None
    if type(value) is int and 0 < value < 1 << 53:
        return _lm.from_int(value)
    return None


def _raw_p_parts(x: tuple, y: tuple, prec: int) -> tuple[tuple, tuple, tuple]:
    """``(-uv, B, r)`` of :func:`mp_p_from_xy`, ``p = exp(-uv) B / r``."""
    mul, add, div, exp, neg = _lm.mpf_mul, _lm.mpf_add, _lm.mpf_div, _lm.mpf_exp, _lm.mpf_neg
    rnd = _RND
    r = _lm.mpf_sqrt(add(x, y, prec, rnd), prec, rnd)
    u = div(x, r, prec, rnd)
    v = div(y, r, prec, rnd)
    nu = neg(u)
    eu = exp(mul(nu, u, prec, rnd), prec, rnd)
    fu = _erf_raw(u, prec)
    if u == v:  # e.g. sigma1 = sigma and |omega**2 - Omega**2| = 1 (the paper)
        ev, fv = eu, fu
    else:
        ev = exp(mul(neg(v), v, prec, rnd), prec, rnd)
        fv = _erf_raw(v, prec)
    b = add(mul(v, eu, prec, rnd), mul(u, ev, prec, rnd), prec, rnd)
    c = mul(mul(_sqrt_pi_raw(prec), u, prec, rnd), v, prec, rnd)
    b = add(b, mul(c, add(fu, fv, prec, rnd), prec, rnd), prec, rnd)
    return mul(nu, v, prec, rnd), b, r


def single_mp_fast(sigma, sigma1, omega, Omega, d, dps: int, want: str) -> Any:
    """:func:`single_mp` for float inputs on raw mpf tuples; None where it does not apply
    (other input types, bad input, resonance, the adaptive ``1 - p`` loop)."""
    s0 = _raw_in(sigma)
    s1 = s0 if sigma1 is None else _raw_in(sigma1)
    om = _raw_in(omega)
    Om = None if Omega is None else _raw_in(Omega)
    dd = _raw_in(d)
    if s0 is None or s1 is None or om is None or dd is None or (Om is None) != (Omega is None):
        return None
    est = estimate_float(sigma, sigma1, omega, Omega, d)
    if est is None:
        return None
    if est[2] > 0.5 and want == "logp":
        return None  # log1p(-(1 - p)) in the general path
    guard, direct_q = precision_plan(est, want)
    prec = _lm.dps_to_prec(dps + guard)
    xy = raw_xy(s0, s1, om, Om, dd, prec)
    if xy is None:
        return None  # resonance: the general path raises
    return from_xy_raw(*xy, prec, want, guard, direct_q)


def raw_xy(s0: tuple, s1: tuple, om: tuple, Om: tuple | None, dd: tuple, prec: int
           ) -> tuple[tuple, tuple] | None:
    """``x = d**2/(4 sigma0**2)``, ``y = d**2 (omega**2 - Omega**2)**2/(4 sigma1**2)`` from raw
    inputs (``Om`` None: ``Omega**2 = 2``), rounded as
    :func:`~symhx.forcing.kernels_mp.mp_xy_forcing` rounds them at ``prec`` bits; None at
    resonance."""
    mul, div, sub, rnd = _lm.mpf_mul, _lm.mpf_div, _lm.mpf_sub, _RND
    om2 = _lm.ftwo if Om is None else mul(Om, Om, prec, rnd)
    delta = sub(mul(om, om, prec, rnd), om2, prec, rnd)
    if not delta[1]:
        return None
    x = div(mul(dd, dd, prec, rnd), mul(mul(_MP_FOUR, s0, prec, rnd), s0, prec, rnd), prec, rnd)
    t = mul(dd, delta, prec, rnd)
    y = div(mul(t, t, prec, rnd), mul(mul(_MP_FOUR, s1, prec, rnd), s1, prec, rnd), prec, rnd)
    return x, y


def from_xy_raw(x: tuple, y: tuple, prec: int, want: str, guard: int, direct_q: bool) -> Any:
    """``want`` (p, 1 - p or a log) from raw ``x, y`` at ``prec`` bits, as planned by
    :func:`~symhx.forcing.kernels_mp.precision_plan`; None where the caller's adaptive
    ``1 - p`` (or ``log1p(-p)`` for small ``p``) must decide. Shared by the fast path and the
    general one (which passes the raw tuples of its mpf ``x, y``)."""
    mul, div, sub, rnd = _lm.mpf_mul, _lm.mpf_div, _lm.mpf_sub, _RND
    nuv, b, r = _raw_p_parts(x, y, prec)
    make = thread_mp().make_mpf
    if want == "logp":
        lg = _lm.mpf_log(div(b, r, prec, rnd), prec, rnd)
        return make(_lm.mpf_add(nuv, lg, prec, rnd))
    p = mul(_lm.mpf_exp(nuv, prec, rnd), div(b, r, prec, rnd), prec, rnd)
    if want == "p":
        return make(p)
    if not direct_q and _lm.mpf_gt(p, _MP_HALF):
        return None  # 1 - p by the adaptive loop of the general path
    if want == "logq" and not direct_q and p[2] + p[3] < -16:
        return None  # log1p(-p) for small p in the general path
    q = sub(_lm.fone, p, prec, rnd)
    if direct_q and not (q[0] == 0 and q[1] and -(q[2] + q[3]) <= 3.3 * (guard - 4)):
        return None  # more digits cancelled than planned: the general path's loop
    return make(q) if want == "q" else make(_lm.mpf_log(q, prec, rnd))


_MP_HALF = _lm.from_man_exp(1, -1)

