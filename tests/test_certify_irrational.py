"""Rigorous Arb balls of sympy real expressions (symhx.certify.real_ball and the decisions built
on it, issue 28 item 3). References: mpmath at three times the bits (every ball must contain
it), exact rationals, and sympy's own evaluation at hundreds of digits."""

from __future__ import annotations

from fractions import Fraction

import mpmath
import pytest
import sympy
from flint import arb

from symhx.certify import (
    MAX_IRRATIONAL_BITS,
    UndecidedError,
    arb_prec,
    decide_with_rising_precision,
    rational_bracket,
    real_ball,
    real_sign,
    to_arb,
)
from tests.reference.irrational import bracket

x = sympy.Rational(7, 3)
EXPRESSIONS = [
    sympy.sqrt(2), sympy.pi, sympy.E, sympy.EulerGamma, sympy.Catalan, sympy.GoldenRatio,
    sympy.root(882, 3) / 42, 5 - sympy.Rational(28, 8) ** sympy.Rational(1, 3),
    sympy.exp(x) - sympy.log(x), sympy.sin(x) + sympy.cos(x) ** 2, sympy.tan(x) * sympy.atan(x),
    sympy.asin(sympy.Rational(1, 3)) + sympy.acos(sympy.Rational(1, 5)),
    sympy.sinh(x) - sympy.cosh(x) + sympy.tanh(x), sympy.asinh(x) + sympy.acosh(x),
    sympy.atanh(sympy.Rational(1, 2)), sympy.gamma(x) + sympy.loggamma(x * 10),
    sympy.erf(x) - sympy.erfc(x / 5), sympy.Abs(sympy.pi - 4), sympy.pi ** sympy.E,
    sympy.Float("0.1", 40) * sympy.sqrt(3), sympy.Min(sympy.pi, sympy.E) + sympy.Max(1, x),
    sympy.Rational(1, 50) + sympy.sqrt(2) / 10**70, 2 ** sympy.Rational(-5, 7),
    sympy.floor(sympy.pi * 100) / 100 + sympy.ceiling(sympy.E), sympy.LambertW(3),
]


@pytest.mark.parametrize("expr", EXPRESSIONS, ids=str)
@pytest.mark.parametrize("bits", [53, 300, 2000])
def test_real_ball_contains_the_value_and_is_tight(expr, bits):
    # the reference: sympy's evalf at three times the digits (mpmath's gamma family is slow
    # there, so the log-gamma term stays at 300 bits)
    if bits > 300 and expr.has(sympy.loggamma):
        bits = 300
    with mpmath.workdps(int(bits * 0.3) * 3 + 30):
        ref = mpmath.mpf(sympy.N(expr, int(bits * 0.3) * 3 + 30))
    with arb_prec(bits):
        ball = real_ball(expr)
        assert ball.contains(to_arb(ref)), (expr, ball)
        rad, mid = ball.rad(), abs(ball.mid())
        # a few bits lost to cancellation and to the operations, never most of them
        assert rad <= mid * arb(2) ** (24 - bits), (expr, ball)


def test_real_ball_of_exact_numbers_is_exact():
    with arb_prec(64):
        assert real_ball(sympy.Rational(3, 8)).is_exact()
        assert real_ball(sympy.Float(0.1)).is_exact()  # the float's binary value
        assert real_ball(sympy.Integer(10) ** 40).is_exact()
        assert real_ball(Fraction(1, 3)).contains(to_arb(Fraction(1, 3)))


@pytest.mark.parametrize("bad, kind", [
    (sympy.besselj(1, 2), TypeError), (sympy.zeta(3) * sympy.Symbol("t"), TypeError),
    (sympy.I, ValueError), (sympy.oo, ValueError), (sympy.nan, ValueError),
    (sympy.Pow(-8, sympy.Rational(1, 3), evaluate=False), ValueError),  # complex in sympy
    ("0.5", TypeError),
])
def test_real_ball_refuses_what_it_cannot_enclose(bad, kind):
    with arb_prec(64), pytest.raises(kind):
        real_ball(bad)


def test_a_refusal_names_the_part():
    with arb_prec(64), pytest.raises(TypeError, match=r"besselj.*exact rational or a float"):
        real_ball(sympy.sqrt(2) + sympy.besselj(1, 2))


def test_real_sign_rises_until_proved():
    # sqrt(2) = 1.41421356237309504880168872420969807856967...
    tiny = sympy.sqrt(2) - sympy.Rational(14142135623730950488016887242096, 10**31)
    assert real_sign(tiny) == 1 and real_sign(-tiny) == -1
    # 0 only when the ball is exactly zero; a zero in disguise is refused
    assert real_sign(sympy.Mul(0, sympy.sqrt(2), evaluate=False)) == 0
    with pytest.raises(UndecidedError, match="not decided"):
        real_sign(sympy.Add(sympy.pi, -sympy.pi, evaluate=False), max_bits=4096)


def test_real_sign_stops_at_the_limit_as_it_is_when_called(monkeypatch):
    # without max_bits, the documented MAX_IRRATIONAL_BITS at the call (a raised or lowered
    # constant reaches every caller), not its value at import
    import symhx.certify

    monkeypatch.setattr(symhx.certify, "MAX_IRRATIONAL_BITS", 1 << 11)
    with pytest.raises(UndecidedError, match=f"not decided at {1 << 11} bits"):
        real_sign(sympy.Add(sympy.pi, -sympy.pi, evaluate=False))


def test_rational_bracket_encloses_the_reference():
    expr = sympy.root(882, 3) / 42
    ref_lo, ref_hi = bracket(expr, 300)
    for bits in (64, 500, 900):
        with arb_prec(bits):
            lo, hi = rational_bracket(real_ball(expr))
        assert lo <= ref_lo and ref_hi <= hi
        assert (hi - lo) / lo < Fraction(2) ** (10 - bits)
    with arb_prec(64):
        assert rational_bracket(arb.nan()) is None


def test_decide_with_rising_precision_doubles_to_the_cap():
    tried: list[int] = []

    def never(bits: int) -> None:
        tried.append(bits)
        return None

    with pytest.raises(UndecidedError, match="nothing at 1000"):
        decide_with_rising_precision(never, start_bits=100, max_bits=1000,
                                     undecided=lambda b: f"nothing at {b}")
    assert tried == [100, 200, 400, 800, 1000]
    assert decide_with_rising_precision(lambda b: b if b >= 300 else None, start_bits=70,
                                        undecided=str) == 560
    assert MAX_IRRATIONAL_BITS >= 1 << 16


def test_to_arb_takes_mpf_of_any_context_exactly():
    from symhx._mpctx import mp

    ctx = mp()
    with ctx.workdps(50):
        third = ctx.mpf(1) / 3
    with arb_prec(300):
        a, b = to_arb(third), to_arb(mpmath.mp.make_mpf(third._mpf_))
        assert a.is_exact() and (a == b) and to_arb(0.1).is_exact()
    with arb_prec(64), pytest.raises(ValueError, match="not a finite number"):
        to_arb(mpmath.inf)
