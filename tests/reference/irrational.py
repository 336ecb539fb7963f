"""Independent references for decisions at an irrational ``p``: a rational bracket of ``p`` from a
much higher-precision evaluation (sympy's own ``evalf`` at hundreds of digits, not symhx's Arb
walker), and a decision taken exactly (integers / Fractions) at both ends of the bracket.

>>> import sympy
>>> lo, hi = bracket(sympy.sqrt(2), 50)
>>> lo**2 < 2 < hi**2, hi - lo < Fraction(3, 10**50)
(True, True)
"""

from __future__ import annotations

from collections.abc import Callable
from fractions import Fraction
from typing import Any

__all__ = ["bracket", "decided", "decided_at_both_ends", "sympy_value"]


def bracket(expr: Any, digits: int = 200) -> tuple[Fraction, Fraction]:
    """``lo < expr < hi`` with ``(hi - lo) / |expr| ~ 2 * 10**-digits``: sympy's ``evalf`` at
    ``digits + 40`` digits (its error is far below the widening by ``10**-digits``)."""
    import sympy

    v = sympy.Rational(expr.evalf(digits + 40))  # the exact binary value of the Float
    fr = Fraction(int(v.p), int(v.q))
    eps = abs(fr) / 10**digits
    return fr - eps, fr + eps


def decided_at_both_ends(decide: Callable[[Fraction], Any], expr: Any,
                         digits: int = 200) -> Any:
    """``decide(lo)`` if it equals ``decide(hi)`` for the bracket of ``expr`` (the decision is
    then that of every p in between when ``decide`` is monotone in p or, as for the modes, a
    step function whose steps are isolated points), else ``None``."""
    lo, hi = bracket(expr, digits)
    a, b = decide(lo), decide(hi)
    return a if a == b else None


def decided(decide: Callable[[Fraction], Any], expr: Any, digits: int = 200) -> Any:
    """:func:`decided_at_both_ends`, asserting that the bracket is narrow enough to decide."""
    want = decided_at_both_ends(decide, expr, digits)
    assert want is not None, "the reference bracket is too wide for this p"
    return want


def sympy_value(expr: Any, bits: int) -> Any:
    """sympy's own evaluation of ``expr`` (``N``) at three times the digits of ``bits``, as an
    mpf of that precision."""
    import mpmath
    import sympy

    digits = int(bits * 0.3) * 3 + 30
    with mpmath.workdps(digits):
        return mpmath.mpf(sympy.N(expr, digits))
