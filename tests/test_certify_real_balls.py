"""Balls handed to symhx.certify as they are: ``to_arb`` / ``real_sign`` of an ``arb`` keep its
radius (a ball with an end exactly at 0 is undecided, not signed), ``mpf_bounds`` rounds the
ends of a ball with a short midpoint and a tiny radius to ``dps + 5`` digits, and the sign of
``0**x`` for an irrational ``x`` barely above 0 is found by raising the precision.
References: exact Fractions, sympy's evalf at hundreds of digits."""

from __future__ import annotations

from fractions import Fraction

import pytest
import sympy
from flint import arb

from symhx.certify import (
    UndecidedError,
    arb_prec,
    mpf_bounds,
    rational_bracket,
    real_ball,
    real_sign,
    to_arb,
)


def _from_zero_up() -> arb:
    """A ball whose lower end is exactly 0: [r +/- r] (r the radius Arb gives [0 +/- 1])."""
    ball = arb(0, 1)
    return ball + ball.rad()


def _fraction(man: int, exp: int) -> Fraction:
    return Fraction(int(man)) * Fraction(2) ** int(exp)


def test_to_arb_keeps_the_radius_of_a_ball():
    with arb_prec(64):
        ball = arb(1, 1) / 3
        got = to_arb(ball)
        assert got.mid() == ball.mid() and got.rad() == ball.rad()
        assert rational_bracket(real_ball(ball)) == rational_bracket(ball)


@pytest.mark.parametrize("sign", [1, -1])
def test_a_ball_with_an_end_at_zero_has_no_sign(sign):
    # [0, 2r] (or [-2r, 0]) holds 0: no sign is proved, whatever the precision
    ball = _from_zero_up() if sign > 0 else -_from_zero_up()
    assert (ball >= 0) if sign > 0 else (ball <= 0)
    with pytest.raises(UndecidedError, match="not decided at 256 bits"):
        real_sign(ball, max_bits=256)
    assert real_sign(ball + sign, max_bits=256) == sign  # [1, 1 + 2r]: decided
    assert real_sign(arb(0), max_bits=256) == 0


@pytest.mark.parametrize("dps", [30, 100, 250])
def test_mpf_bounds_of_a_short_midpoint_with_a_tiny_radius(dps):
    # [1 +/- 2**-1000]: the ends 1 -/+ 2**-1000 need 1000 bits, the midpoint 1 bit; the bounds
    # are those ends rounded outward to dps + 5 digits, not to a fixed ~128 bits
    rad = Fraction(1, 2**1000)
    with arb_prec(2000):
        ball = arb(1, arb(2) ** -1000)
        r = _fraction(*ball.rad().man_exp())
    assert rad <= r < 2 * rad
    lo, hi = mpf_bounds(ball, dps)
    flo, fhi = (_fraction(v.man, v.exp) for v in (lo, hi))
    assert flo <= 1 - r and 1 + r <= fhi
    assert fhi - flo <= 2 * r + Fraction(1, 10 ** (dps + 4))


def test_zero_to_an_irrational_power_barely_above_zero_is_zero():
    # sqrt(2) - 1.4142135623730950488 = 1.7e-20 > 0: at 64 bits its ball still holds 0, so the
    # precision is raised until it is positive, and 0**x is 0 (exactly)
    x = sympy.sqrt(2) - sympy.Rational(14142135623730950488, 10**19)
    assert sympy.N(x, 50) > 0
    zero_to_x = sympy.Pow(0, x, evaluate=False)
    assert real_sign(zero_to_x) == 0
    with pytest.raises(ValueError, match="not a finite real number"):
        real_sign(sympy.Pow(0, -x, evaluate=False))
    # an exponent that is exactly 0 but written so that no ball proves it: undecided
    tie = sympy.Add(sympy.pi, -sympy.pi, evaluate=False)
    with pytest.raises(UndecidedError):
        real_sign(sympy.Pow(0, tie, evaluate=False), max_bits=512)
