"""Rigorous ball arithmetic (python-flint ``arb``) for every integer decision of symhx.

An ``arb`` is a ball ``[m +/- r]`` guaranteed to contain the exact real value of the expression
that produced it (FLINT/Arb propagates rounding and truncation errors of every operation,
including ``log``, ``lgamma`` and ``digamma``). A sign is *certified* when the ball excludes 0.

The working precision is always local: :func:`arb_prec` sets ``flint.ctx.prec`` for a block and
restores it, so the global flint precision never changes (nor does ``mpmath.mp.dps``).

>>> with arb_prec(bits_for(10**100, 100)):  # lgamma(N) cancels ~log2(N log N) bits
...     x = G_arb(10**100, 10**40)          # sum_{j<=K} log(1 - j/N): about -K**2/(2N) = -5e-21
>>> x < 0, round(float(x.mid()) * 1e21, 9), bool(x.rad() < arb('1e-30'))
(True, -5.0, True)
>>> certified_sign(lambda: arb(2).sqrt() - arb('1.4142135623730950488'), start_bits=64,
...                max_bits=256)
1
"""

from __future__ import annotations

from collections.abc import Callable, Iterator
from contextlib import contextmanager
from typing import Any

import mpmath
from flint import arb, ctx, fmpz

__all__ = [
    "G_arb",
    "UndecidedError",
    "arb_prec",
    "bits_for",
    "certified_sign",
    "mpf_bounds",
    "rel_width_ok",
    "space_candidates",
    "to_arb",
]


class UndecidedError(ArithmeticError):
    """A sign could not be certified within the precision budget (an exact tie is likely)."""


@contextmanager
def arb_prec(bits: int) -> Iterator[None]:
    """Set flint's working precision to ``bits`` for the block (restored on exit)."""
    with ctx.workprec(int(bits)):
        yield


def to_arb(x: Any) -> arb:
    """An int / Fraction / mpf as an ``arb`` ball at the current precision (exact ints stay
    exact up to the precision; a rounded value is a ball containing the exact one)."""
    if isinstance(x, int):
        return arb(fmpz(x))
    if isinstance(x, mpmath.mpf):
        if not mpmath.isfinite(x):
            raise ValueError(f"cannot convert {x} to arb: not a finite number")
        man, exp = x.man_exp  # the magnitude: man_exp carries no sign
        if x < 0:
            man = -man
        return arb(fmpz(man)) * arb(2) ** exp if exp >= 0 else arb(fmpz(man)) / arb(2) ** (-exp)
    num, den = getattr(x, "numerator", None), getattr(x, "denominator", None)
    if num is not None and den is not None:
        return arb(fmpz(int(num))) / arb(fmpz(int(den)))
    raise TypeError(f"cannot convert {type(x).__name__} to arb")


def bits_for(N: int, extra_bits: int) -> int:
    """Starting precision for quantities built from ``lgamma(N)``: the ``log2(N log N)`` bits
    that cancel, plus ``extra_bits``."""
    return N.bit_length() + max(N.bit_length(), 2).bit_length() + int(extra_bits) + 16


def G_arb(N: int, K: int) -> arb:
    """Ball enclosing ``G(N, K) = lgamma(N) - lgamma(N - K) - K log N
    = sum_{j=1}^{K} log(1 - j/N)`` (``0 <= K < N``) at the current precision.

    The definition cancels about ``log2(N log N)`` bits; choose the precision with
    :func:`bits_for`. The ball is rigorous whatever the precision.
    """
    if K == 0:
        return arb(0)
    n = to_arb(N)
    return n.lgamma() - to_arb(N - K).lgamma() - to_arb(K) * n.log()


def certified_sign(
    fn: Callable[[], arb],
    *,
    start_bits: int,
    max_bits: int,
    exact_fn: Callable[[], int] | None = None,
) -> int:
    """Sign (-1, 0, +1) of a real quantity, certified by Arb ball arithmetic.

    ``fn()`` evaluates the quantity as an ``arb`` at the precision in force. The precision
    doubles from ``start_bits`` until the ball excludes 0. If it still contains 0 at
    ``max_bits``, ``exact_fn()`` (exact rational/integer arithmetic, which also detects exact
    ties and returns 0) decides; without one, :class:`UndecidedError` is raised.
    """
    bits = max(64, int(start_bits))
    x = None
    while True:
        with arb_prec(bits):
            x = fn()
        if x > 0:
            return 1
        if x < 0:
            return -1
        if bits >= max_bits:
            break
        bits = min(2 * bits, int(max_bits))
    if exact_fn is not None:
        return exact_fn()
    raise UndecidedError(
        f"sign not certified at {bits} bits (ball {x.str(5, radius=True)}); an exact tie is "
        "likely and the integers involved are too large to compare exactly"
    )


def _mpf_round(x: arb, prec: int, rnd: str) -> mpmath.mpf:
    man, exp = x.man_exp()
    raw = mpmath.libmp.from_man_exp(int(man), int(exp), prec, rnd)
    return mpmath.mp.make_mpf(raw)


def mpf_bounds(x: arb, dps: int) -> tuple[mpmath.mpf, mpmath.mpf]:
    """``(lo, hi)`` mpf with ``lo <= every point of x <= hi`` (rounded outward to
    ``dps + 5`` digits)."""
    prec = int((dps + 5) * 3.3219280948873626) + 8
    with arb_prec(max(x.mid().bits(), 64) + 64):  # lower/upper round outward at ctx.prec
        lo, hi = x.lower(), x.upper()
    return _mpf_round(lo, prec, "f"), _mpf_round(hi, prec, "c")


def rel_width_ok(x: arb, dps: int) -> bool:
    """Whether the ball's relative width (``radius / |midpoint|``) is below ``10**-dps / 4``."""
    if x.is_exact():
        return True
    if x.contains(0):
        return False
    return bool(x.rad() * 4 * arb(10) ** dps < abs(x.mid()))


def space_candidates(space: Any, N: int, fr: Any, top: int) -> list[int]:
    """Every ``k`` that may maximise ``W(k) = Phi_{N,p}(k) Q*(k)`` at the rational ``p = fr``
    over a sample space (``space.Qnum``, ``.max_parts``, ``.max_excess`` as in
    :class:`symhx.spaces.Space`), given a guess ``top`` (e.g. a float64 argmax): ``top`` plus
    each ``k`` that an Arb ball cannot prove to have ``W(k) < W(top)``.

    ``W(k)/W(1)`` is a running product of the exact ratios
    ``W(k+1)/W(k) = p (N-k) k/(k+1) Q*(k+1)/Q*(k)``; it stops at the first ``k > max(top, r)``
    with ``W(k) < W(top)`` and ``rho(k) = p (N-k) max((k+m)/(k+1-r), 1) < 1``
    (``r = max_parts``, ``m = max_excess``): each later ratio ``W(j+1)/W(j)`` is at most
    ``p (N-j) (j+m)/(j+1-r)`` (mediant inequality on the non-negative polynomial coefficients of
    ``Q*``), and ``(j+m)/(j+1-r)`` is monotone in ``j`` with limit 1, so ``rho(k)`` bounds every
    later ratio and W decreases after it. (Without the ``max(., 1)``, for ``m = r = 0``, the
    excess<=0 space, ``k/(k+1)`` *increases* and a dip of W after ``top`` used to stop the scan
    before a larger maximum.)
    """
    a, b = fr.numerator, fr.denominator
    m, R = space.max_excess, space.max_parts
    bits = 96 + 2 * N.bit_length() + a.bit_length() + b.bit_length()
    with arb_prec(bits):
        pa = to_arb(fr)
        q1 = to_arb(space.Qnum(1, a, b))
        ratios = [to_arb(1)]  # ratios[k - 1] = W(k) / W(1)
        qprev = q1
        for k in range(1, top):
            qk1 = to_arb(space.Qnum(k + 1, a, b))
            ratios.append(ratios[-1] * pa * ((N - k) * k) / (k + 1) * qk1 / qprev)
            qprev = qk1
        wtop = ratios[top - 1]
        out = [k for k in range(1, top) if not ratios[k - 1] < wtop]
        ratio = wtop
        for k in range(top, N):
            qk1 = to_arb(space.Qnum(k + 1, a, b))
            ratio = ratio * pa * ((N - k) * k) / (k + 1) * qk1 / qprev
            qprev = qk1
            kk = k + 1
            below = ratio < wtop
            if not below:
                out.append(kk)
            elif kk > R and fr * (N - kk) * max(kk + m, kk + 1 - R) < kk + 1 - R:
                break
    return sorted({top, *out})
