"""Powers in symhx.certify.real_ball: ``E**x`` as ``exp(x)``, rational exponents that are not a
sympy ``Rational`` atom, exact perfect powers, a zero base, a base ball that still holds 0.
References: mpmath at twice the bits (the ball must contain it), exact integers."""

from __future__ import annotations

import mpmath
import pytest
import sympy
from flint import arb

from symhx.certify import _pow_ball, arb_prec, real_ball, real_sign
from tests.reference.mp import to_mp

S = sympy.S


def _pow(base, expo):
    return sympy.Pow(base, expo, evaluate=False)


def _contains(ball: arb, ref: mpmath.mpf) -> bool:
    lo, hi = (mpmath.mpf(tuple(int(v) for v in end.man_exp())) for end in (ball.lower(),
                                                                             ball.upper()))
    return lo <= ref <= hi


def test_e_to_a_power_is_as_tight_as_exp():
    # E**(10**6) is exp(10**6): a relative radius of a few ulps at 64 bits. Raising a 64-bit
    # ball of e to the 10**6-th power instead would widen it ~10**6 times (~5e-14)
    with arb_prec(64):
        ball = real_ball(_pow(S.Exp1, 10**6))
        rel = ball.rad() / abs(ball.mid())
    with mpmath.workdps(60):
        ref = mpmath.exp(10**6)
        assert _contains(ball, ref)
    assert rel < arb(2) ** -58, rel


def test_e_to_an_irrational_power_contains_the_value():
    with arb_prec(128):
        ball = real_ball(_pow(S.Exp1, sympy.sqrt(2) * 1000))
    with mpmath.workdps(80):
        assert _contains(ball, mpmath.exp(mpmath.sqrt(2) * 1000))


def test_rational_exponent_written_as_an_unevaluated_sum():
    # 1/2 + 1/3 unevaluated is rational-valued but not a Rational atom: 2**(5/6)
    expo = sympy.Add(S.Half, sympy.Rational(1, 3), evaluate=False)
    assert not expo.is_Rational and expo.is_rational
    with arb_prec(200):
        ball = real_ball(_pow(2, expo))
        assert ball.rad() < abs(ball.mid()) * arb(2) ** -180
    with mpmath.workdps(130):
        assert _contains(ball, mpmath.mpf(2) ** (mpmath.mpf(5) / 6))


@pytest.mark.parametrize(("base", "expo", "value"), [
    (9, sympy.Rational(3, 2), 27), (25, sympy.Rational(5, 2), 3125),
    (sympy.Rational(9, 4), sympy.Rational(3, 2), sympy.Rational(27, 8)),
])
def test_perfect_powers_are_exact_so_a_tie_is_recognised(base, expo, value):
    # sqrt of an exact perfect square is exact in Arb, and so is its integer power: the
    # difference is the exact ball 0, whose sign is 0 without raising the precision
    tie = sympy.Add(_pow(base, expo), -value, evaluate=False)
    assert real_sign(tie, max_bits=256) == 0
    with arb_prec(64):
        assert real_ball(_pow(base, expo)).is_exact()


@pytest.mark.parametrize("expo", [sympy.sqrt(2), S.Half, sympy.Rational(7, 3), S.Pi / 100])
def test_zero_base_to_a_positive_power_is_zero(expo):
    for zero in (S.Zero, sympy.Add(1, -1, evaluate=False)):
        with arb_prec(64):
            ball = real_ball(_pow(zero, expo))
        assert ball.is_zero() and ball.is_exact()


@pytest.mark.parametrize("expo", [-sympy.sqrt(2), -S.Half, sympy.Rational(-7, 3)])
def test_zero_base_to_a_negative_power_is_refused(expo):
    with arb_prec(64), pytest.raises(ValueError, match="not a finite real number"):
        real_ball(_pow(0, expo))


@pytest.mark.parametrize("expo", [S.ImaginaryUnit, S.NaN, S.Infinity, S.ComplexInfinity])
def test_zero_base_to_a_non_real_power_is_a_value_error(expo):
    # the exponent is evaluated as a real ball, never compared by sympy (which would raise
    # TypeError for I and nan, and call 0**oo zero)
    with arb_prec(64), pytest.raises(ValueError, match="not a finite real number"):
        real_ball(_pow(0, expo))


def _from_zero_up() -> arb:
    """A ball whose lower end is exactly 0: [r +/- r] (r the radius Arb gives [0 +/- 1])."""
    ball = arb(0, 1)
    return ball + ball.rad()


@pytest.mark.parametrize("expo", [S.Half, sympy.Rational(3, 2), sympy.Rational(-1, 3),
                                  sympy.sqrt(2)])
def test_a_base_ball_that_still_holds_zero_gives_nan(expo):
    # [0, 2r] reaches 0 (even though no point is negative): its root / power is not a finite
    # ball (the caller raises the precision)
    with arb_prec(64):
        base = _from_zero_up()
        assert base >= 0 and not base > 0
        assert not _pow_ball(base, expo, "x").is_finite()
        assert _pow_ball(base + 1, expo, "x").is_finite()  # [1, 1 + 2r]: decided


def test_negative_and_fractional_powers_contain_the_value():
    cases = [(sympy.pi, -3), (sympy.sqrt(3), sympy.Rational(-5, 2)), (7, sympy.Rational(-2, 3)),
             (sympy.Rational(5, 3), sympy.Rational(4, 5)), (sympy.pi, sympy.sqrt(2))]
    for base, expo in cases:
        with arb_prec(128):
            ball = real_ball(_pow(base, expo))
        with mpmath.workdps(80):
            ref = to_mp(sympy.N(base, 80)) ** to_mp(sympy.N(expo, 80))
            assert _contains(ball, ref), (base, expo, ball)
