"""Internal numeric helpers: guard digits, Stirling's series, and the cancellation-free
log-falling-factorial ``G(N, K)`` shared by the distribution, critical and asymptotics modules.

Certified (ball-arithmetic) signs live in :mod:`symhx.certify` (python-flint Arb); the names
``certified_sign``, ``bits_for`` and ``UndecidedError`` are re-exported here for the layers that
import them from this module.

Nothing here changes the global mpmath precision: every routine works inside ``mpmath.workdps``
and restores it.
"""

from __future__ import annotations

import math
from fractions import Fraction
from typing import Any

import mpmath

__all__ = [
    "G_mp",
    "UndecidedError",
    "as_fraction",
    "bits_for",
    "certified_sign",
    "check_N",
    "check_dps",
    "check_p",
    "digits_of",
    "log1m_series",
    "stirling_series",
]

from symhx.certify import UndecidedError, bits_for, certified_sign
from symhx.validation import (  # noqa: F401  (re-exported for the layers below the API)
    MAX_DPS,
    as_fraction,
    check_dps,
    check_N,
    check_p,
    is_exact_type,
)


def digits_of(N: int) -> int:
    """Decimal digits of the positive int ``N`` (cheap, no str() of huge ints)."""
    return max(1, int(N.bit_length() * 0.30103) + 1)


def mp_value(p: Any, fr: Fraction | None) -> mpmath.mpf:
    """``p`` as an mpf at the current working precision."""
    if fr is not None:
        return mpmath.mpf(fr.numerator) / fr.denominator
    return mpmath.mpf(str(p.evalf(mpmath.mp.dps + 10)))


# --------------------------------------------------------------------------- G(N, K)
# G(N, K) = lgamma(N) - lgamma(N - K) - K log N = sum_{j=1}^{K} log(1 - j/N)   (0 <= K < N).
# It is O(K^2/N) while the lgamma terms are O(N log N): evaluating the definition cancels about
# log10(N) digits. G_mp evaluates the rewrite
#   G = N B(u) + (1/2) log1p(-u) + S(N) - S(N - K),  u = K/N,
#   B(u) = -(1 - u) log1p(-u) - u = -sum_{m>=2} u^m / (m (m - 1)),
#   S(x) = sum_m B_{2m} / (2m (2m - 1) x^(2m - 1))   (Stirling's series),
# which has no cancellation, whenever N - K is large enough for Stirling's series to converge to
# the working precision; otherwise it uses loggamma with guard digits.


def stirling_series(x: mpmath.mpf, eps: mpmath.mpf | None = None, *,
                    derivative: bool = False) -> mpmath.mpf:
    """``S(x) = sum_{r>=1} B_2r / (2r (2r-1) x**(2r-1))`` (``lgamma(x) - (x - 1/2) log x + x -
    log(2 pi)/2``), or its x-derivative ``-sum B_2r / (2r x**(2r))``, summed until a term is below
    ``eps`` (default: the working eps) relative to the sum (at most 400 terms; the series is
    asymptotic, so callers use it only for ``x`` well above the working digits)."""
    eps = mpmath.eps if eps is None else eps
    total = mpmath.mpf(0)
    xinv2 = 1 / (x * x)
    power = xinv2 if derivative else 1 / x
    for m in range(1, 401):
        b = mpmath.bernoulli(2 * m)
        term = (-b / (2 * m)) * power if derivative else b / (2 * m * (2 * m - 1)) * power
        total += term
        if abs(term) <= eps * abs(total):
            break
        power *= xinv2
    return total


def log1m_series(u: mpmath.mpf) -> mpmath.mpf:
    """``B(u) = -(1-u) log1p(-u) - u = -sum_{m>=2} u**m / (m (m-1))`` without cancellation for
    small ``u`` (``0 <= u < 1``)."""
    if u < mpmath.mpf("0.01"):
        eps = mpmath.eps
        total = mpmath.mpf(0)
        power = u * u
        m = 2
        while True:
            term = power / (m * (m - 1))
            total += term
            if term <= eps * total:
                return -total
            power *= u
            m += 1
    with mpmath.extradps(5):
        return -(1 - u) * mpmath.log1p(-u) - u


def stirling_ok(x: int, dps: int) -> bool:
    """Whether Stirling's series at ``x`` reaches ``dps`` digits quickly: ``x >= 10**4``, and
    large enough that the 400 terms of :func:`stirling_series` reach ``dps + 20`` digits (the
    term r = 400, ``B_800 / (800 * 799 * x**799)``, is about ``10**1334 / x**798`` relative to
    the sum ``~1/(12 x)``; this second condition matters from ``dps = 1838`` on, and it implies
    ``x > 4 dps``, where the series is far from its divergence at ``r ~ pi x``)."""
    return x >= 10**4 and 798 * math.log10(x) >= dps + 1354


def G_mp(N: int, K: int) -> mpmath.mpf:
    """``lgamma(N) - lgamma(N-K) - K log N`` at the working precision (relative accuracy)."""
    if K == 0:
        return mpmath.mpf(0)
    dps = mpmath.mp.dps
    if stirling_ok(N - K, dps):
        with mpmath.extradps(10):
            u = mpmath.mpf(K) / N
            eps = mpmath.eps
            S = stirling_series(mpmath.mpf(N), eps * mpmath.mpf(10) ** -5) - stirling_series(
                mpmath.mpf(N - K), eps * mpmath.mpf(10) ** -5)
            val = N * log1m_series(u) + mpmath.log1p(-u) / 2 + S
        return +val
    # direct: loggamma cancels ~log10(N) digits; G >= log((N-1)/N)*... is not tiny here
    # (N - K small or N small), but guard generously for K << N with small N.
    with mpmath.extradps(digits_of(N) + 10):
        val = mpmath.loggamma(N) - mpmath.loggamma(N - K) - K * mpmath.log(N)
    return +val


def G_direct(N: int, K: int) -> mpmath.mpf:
    """The definition of ``G`` with loggamma and ``2 log10(N)`` guard digits (an independent
    route used by the tests)."""
    with mpmath.extradps(2 * digits_of(N) + 10):
        val = mpmath.loggamma(N) - mpmath.loggamma(N - K) - K * mpmath.log(N)
    return +val
