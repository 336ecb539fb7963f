"""Internal numeric helpers: input conversion, guard digits, interval-certified signs, and the
cancellation-free log-falling-factorial ``G(N, K)`` shared by the distribution and critical modules.

Nothing here changes the global mpmath precision: every routine works inside ``mpmath.workdps``
(or :func:`iv_prec` for the interval context) and restores it.
"""

from __future__ import annotations

from collections.abc import Callable, Iterator
from contextlib import contextmanager
from fractions import Fraction
from typing import Any

import mpmath

__all__ = [
    "G_iv",
    "G_mp",
    "as_fraction",
    "certified_sign",
    "check_N",
    "check_dps",
    "check_p",
    "digits_of",
    "iv_prec",
]

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


# --------------------------------------------------------------------------- interval signs
@contextmanager
def iv_prec(bits: int) -> Iterator[Any]:
    """Temporarily set the precision of mpmath's interval context (restored on exit)."""
    iv = mpmath.iv
    old = iv.prec
    iv.prec = bits
    try:
        yield iv
    finally:
        iv.prec = old


class UndecidedError(ArithmeticError):
    """A sign could not be certified within the precision budget (an exact tie is likely)."""


def certified_sign(
    interval_fn: Callable[[Any], Any],
    *,
    start_bits: int,
    max_bits: int,
    exact_fn: Callable[[], int] | None = None,
) -> int:
    """Sign (-1, 0, +1) of a real quantity, certified by interval arithmetic.

    ``interval_fn(iv)`` evaluates the quantity with mpmath's interval context ``iv`` at the
    precision in force. Precision doubles from ``start_bits`` until the interval excludes 0.
    If it still contains 0 at ``max_bits``, ``exact_fn()`` (exact integer arithmetic, which
    also detects exact ties and returns 0) decides; without one, :class:`UndecidedError`.
    """
    bits = max(64, start_bits)
    while True:
        with iv_prec(bits) as iv:
            x = interval_fn(iv)
        if x.a > 0:
            return 1
        if x.b < 0:
            return -1
        if bits >= max_bits:
            break
        bits = min(2 * bits, max_bits)
    if exact_fn is not None:
        return exact_fn()
    raise UndecidedError(
        f"sign not certified at {bits} bits (interval {x}); an exact tie is likely and the "
        f"integers involved are too large to compare exactly"
    )


# --------------------------------------------------------------------------- G(N, K)
# G(N, K) = lgamma(N) - lgamma(N - K) - K log N = sum_{j=1}^{K} log(1 - j/N)   (0 <= K < N).
# It is O(K^2/N) while the lgamma terms are O(N log N): evaluating the definition cancels about
# log10(N) digits. G_mp evaluates the rewrite
#   G = N B(u) + (1/2) log1p(-u) + S(N) - S(N - K),  u = K/N,
#   B(u) = -(1 - u) log1p(-u) - u = -sum_{m>=2} u^m / (m (m - 1)),
#   S(x) = sum_m B_{2m} / (2m (2m - 1) x^(2m - 1))   (Stirling's series),
# which has no cancellation, whenever N - K is large enough for Stirling's series to converge to
# the working precision; otherwise it uses loggamma with guard digits.


def _stirling_tail(x: mpmath.mpf, eps: mpmath.mpf) -> mpmath.mpf:
    total = mpmath.mpf(0)
    xinv2 = 1 / (x * x)
    power = 1 / x
    m = 1
    while True:
        term = mpmath.bernoulli(2 * m) / (2 * m * (2 * m - 1)) * power
        total += term
        if abs(term) < eps * abs(total) or m > 400:
            return total
        power *= xinv2
        m += 1


def _B(u: mpmath.mpf) -> mpmath.mpf:
    """-(1-u) log1p(-u) - u, without cancellation for small u."""
    if u < mpmath.mpf("0.01"):
        eps = mpmath.eps
        total = mpmath.mpf(0)
        power = u * u
        m = 2
        while True:
            term = power / (m * (m - 1))
            total += term
            if term < eps * total:
                return -total
            power *= u
            m += 1
    with mpmath.extradps(5):
        return -(1 - u) * mpmath.log1p(-u) - u


def stirling_ok(x: int, dps: int) -> bool:
    """Whether Stirling's series at ``x`` reaches ``dps`` digits quickly (x well above dps)."""
    return x >= max(10**4, 4 * dps)


def G_mp(N: int, K: int) -> mpmath.mpf:
    """``lgamma(N) - lgamma(N-K) - K log N`` at the working precision (relative accuracy)."""
    if K == 0:
        return mpmath.mpf(0)
    dps = mpmath.mp.dps
    if stirling_ok(N - K, dps):
        with mpmath.extradps(10):
            u = mpmath.mpf(K) / N
            eps = mpmath.eps
            S = _stirling_tail(mpmath.mpf(N), eps * mpmath.mpf(10) ** -5) - _stirling_tail(
                mpmath.mpf(N - K), eps * mpmath.mpf(10) ** -5)
            val = N * _B(u) + mpmath.log1p(-u) / 2 + S
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


def G_iv(iv: Any, N: int, K: int) -> Any:
    """Interval enclosure of ``G(N, K)`` (mpmath's rigorous interval loggamma)."""
    if K == 0:
        return iv.mpf(0)
    Niv = iv.mpf(N)
    return iv.loggamma(Niv) - iv.loggamma(iv.mpf(N - K)) - K * iv.log(Niv)


def iv_bits_for(N: int, extra_digits: int) -> int:
    """Starting interval precision: enough bits to absorb the lgamma cancellation."""
    return int((2 * digits_of(N) + extra_digits + 10) * 3.33) + 16
