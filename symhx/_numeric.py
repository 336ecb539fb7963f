"""Internal numeric helpers: guard digits, Stirling's series, and the cancellation-free
log-falling-factorial ``G(N, K)`` shared by the distribution, critical and asymptotics modules.

Certified (ball-arithmetic) signs live in :mod:`symhx.certify` (python-flint Arb) and argument
validation in :mod:`symhx.validation`; import those names from there (one address per name).

Precision convention (see :mod:`symhx._mpctx`): the mpmath helpers here (:func:`G_mp`,
:func:`mp_value`, :func:`stirling_series`, :func:`log1m_series`, :func:`G_direct`) take no
precision argument. They compute in the calling thread's context ``mp()`` at its current
precision (the caller sets it with ``mp().workdps``), accept mpf arguments of any context, and
return values of the calling thread's context, ready for the caller's arithmetic. They never
read or change the global ``mpmath.mp``.

>>> from symhx._mpctx import mp
>>> ctx = mp()
>>> with ctx.workdps(30):
...     g = G_mp(10**6, 10**3)        # sum_{j <= 1000} log(1 - j/10**6), no cancellation
>>> type(g) is ctx.mpf, ctx.nstr(g, 12)
(True, '-0.5006670003')
"""

from __future__ import annotations

import math
from fractions import Fraction
from typing import Any

import mpmath
from mpmath import libmp

from symhx._mpctx import local, mp
from symhx.certify import arb_prec, real_ball, rel_width_ok
from symhx.validation import InputError

__all__ = [
    "G_direct",
    "G_mp",
    "digits_of",
    "log1m_series",
    "mp_value",
    "stirling_coefficients",
    "stirling_ok",
    "stirling_series",
]


def digits_of(N: int) -> int:
    """Decimal digits of the positive int ``N`` (cheap, no str() of huge ints)."""
    return max(1, int(N.bit_length() * 0.30103) + 1)


def mp_value(p: Any, fr: Fraction | None) -> mpmath.mpf:
    """``p`` as an mpf of the calling thread's context at its current precision.

    ``fr`` is ``p``'s exact value (rounded once); for a sympy irrational (``fr is None``) the
    result is the midpoint of a rigorous Arb ball (:func:`symhx.certify.real_ball`) whose
    relative radius is below ``10**-(digits + 2)``, rounded to the working precision: within
    about one unit of the last place of ``p``.
    """
    ctx = mp()
    if fr is not None:
        return ctx.mpf(fr.numerator) / fr.denominator
    prec = ctx.prec
    digits = int(prec * 0.30103) + 2
    bits = prec + 32
    while True:
        with arb_prec(bits):
            ball = real_ball(p)
            if ball.is_finite() and rel_width_ok(ball, digits):
                man, exp = ball.mid().man_exp()
                return ctx.make_mpf(libmp.from_man_exp(int(man), int(exp), prec, "n"))
        if bits > 64 * (prec + 32):
            raise InputError(f"p={p} cannot be evaluated to {prec} bits: its rigorous "
                             f"enclosure stays wide (is it 0?)")
        bits *= 2


# --------------------------------------------------------------------------- G(N, K)
# G(N, K) = lgamma(N) - lgamma(N - K) - K log N = sum_{j=1}^{K} log(1 - j/N)   (0 <= K < N).
# It is O(K^2/N) while the lgamma terms are O(N log N): evaluating the definition cancels about
# log10(N) digits. G_mp evaluates the rewrite
#   G = N B(u) + (1/2) log1p(-u) + S(N) - S(N - K),  u = K/N,
#   B(u) = -(1 - u) log1p(-u) - u = -sum_{m>=2} u^m / (m (m - 1)),
#   S(x) = sum_m B_{2m} / (2m (2m - 1) x^(2m - 1))   (Stirling's series),
# which has no cancellation, whenever N - K is large enough for Stirling's series to converge to
# the working precision; otherwise it uses loggamma with guard digits.


#: ``B_2r / (2r (2r - 1))`` as exact ``(numerator, denominator)``, r = 1, 2, ... (grown on demand)
_STIRLING_EXACT: list[tuple[int, int]] = []


def stirling_coefficients(count: int) -> list[tuple[int, int]]:
    """The first ``count`` coefficients ``B_2r / (2r (2r - 1))`` of Stirling's series as exact
    ``(numerator, denominator)``, from FLINT's Bernoulli numbers (mpmath's ``bernoulli`` takes
    ~6 ms each at 17000 bits: 11 s of a 13 s pass at dps 5000).  Shared by every thread.

    >>> stirling_coefficients(3)
    [(1, 12), (-1, 360), (1, 1260)]
    """
    if len(_STIRLING_EXACT) < count:
        from flint import fmpq

        with arb_prec(64):  # the process-wide Arb lock: FLINT's Bernoulli cache is shared
            for r in range(len(_STIRLING_EXACT) + 1, count + 1):
                b = fmpq.bernoulli(2 * r) / (2 * r * (2 * r - 1))
                if len(_STIRLING_EXACT) == r - 1:
                    _STIRLING_EXACT.append((int(b.p), int(b.q)))
    return _STIRLING_EXACT[:count]


def stirling_series(x: Any, eps: Any = None, *, derivative: bool = False) -> mpmath.mpf:
    """``S(x) = sum_{r>=1} B_2r / (2r (2r-1) x**(2r-1))`` (``lgamma(x) - (x - 1/2) log x + x -
    log(2 pi)/2``), or its x-derivative ``-sum B_2r / (2r x**(2r))``, summed until a term is below
    ``eps`` (default: the working eps) relative to the sum (at most 400 terms; the series is
    asymptotic, so callers use it only for ``x`` well above the working digits). In the calling
    thread's context at its precision."""
    ctx = mp()
    x = local(x) if hasattr(x, "_mpf_") else ctx.mpf(x)
    eps = ctx.eps if eps is None else local(eps)
    total = ctx.mpf(0)
    xinv2 = 1 / (x * x)
    power = xinv2 if derivative else 1 / x
    for m, (num, den) in enumerate(stirling_coefficients(400), 1):
        coef = ctx.mpf(num) / den  # B_2m / (2m (2m - 1))
        term = -(2 * m - 1) * coef * power if derivative else coef * power
        total += term
        if abs(term) <= eps * abs(total):
            break
        power *= xinv2
    return total


def log1m_series(u: Any) -> mpmath.mpf:
    """``B(u) = -(1-u) log1p(-u) - u = -sum_{m>=2} u**m / (m (m-1))`` without cancellation for
    small ``u`` (``0 <= u < 1``); in the calling thread's context at its precision."""
    ctx = mp()
    u = local(u) if hasattr(u, "_mpf_") else ctx.mpf(u)
    if u < ctx.mpf("0.01"):
        eps = ctx.eps
        total = ctx.mpf(0)
        power = u * u
        m = 2
        while True:
            term = power / (m * (m - 1))
            total += term
            if term <= eps * total:
                return -total
            power *= u
            m += 1
    with ctx.extradps(5):
        return -(1 - u) * ctx.log1p(-u) - u


def stirling_ok(x: int, dps: int) -> bool:
    """Whether Stirling's series at ``x`` reaches ``dps`` digits quickly: ``x >= 10**4``, and
    large enough that the 400 terms of :func:`stirling_series` reach ``dps + 20`` digits (the
    term r = 400, ``B_800 / (800 * 799 * x**799)``, is about ``10**1334 / x**798`` relative to
    the sum ``~1/(12 x)``; this second condition matters from ``dps = 1838`` on, and it implies
    ``x > 4 dps``, where the series is far from its divergence at ``r ~ pi x``)."""
    return x >= 10**4 and 798 * math.log10(x) >= dps + 1354


def G_mp(N: int, K: int) -> mpmath.mpf:
    """``lgamma(N) - lgamma(N-K) - K log N`` at the calling thread's working precision
    (relative accuracy), as a value of that thread's context."""
    ctx = mp()
    if K == 0:
        return ctx.mpf(0)
    if stirling_ok(N - K, ctx.dps):
        with ctx.extradps(10):
            u = ctx.mpf(K) / N
            eps = ctx.eps * ctx.mpf(10) ** -5
            S = stirling_series(ctx.mpf(N), eps) - stirling_series(ctx.mpf(N - K), eps)
            val = N * log1m_series(u) + ctx.log1p(-u) / 2 + S
        return +val
    # direct: loggamma cancels ~log10(N) digits; G >= log((N-1)/N)*... is not tiny here
    # (N - K small or N small), but guard generously for K << N with small N.
    with ctx.extradps(digits_of(N) + 10):
        val = ctx.loggamma(N) - ctx.loggamma(N - K) - K * ctx.log(N)
    return +val


def G_direct(N: int, K: int) -> mpmath.mpf:
    """The definition of ``G`` with loggamma and ``2 log10(N)`` guard digits (an independent
    route used by the tests); in the calling thread's context at its precision."""
    ctx = mp()
    with ctx.extradps(2 * digits_of(N) + 10):
        val = ctx.loggamma(N) - ctx.loggamma(N - K) - K * ctx.log(N)
    return +val
