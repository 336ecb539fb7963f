"""Modes of the higher-order spaces at a sympy irrational ``p`` (issue 28, item 3): decided on Arb
balls of ``p`` itself (they were read at 60 digits). References: exact Fractions of the Burnside
weights (:mod:`tests.reference.spaces`) at both ends of a bracket of ``p`` from sympy's evalf at
far more digits than the offset (:mod:`tests.reference.irrational`)."""

from __future__ import annotations

import math
from fractions import Fraction

import pytest
import sympy

import symhx
from symhx.certify import UndecidedError
from symhx.validation import mpf_to_fraction
from tests.reference.irrational import decided
from tests.reference.spaces import argmax, space_weights

N = 40


def _distinct_jump(space: str) -> tuple[int, sympy.Expr]:
    """With the ;distinct weighting W(k) = C_k p**k, so the jump is the exact algebraic number
    p_c = (C_1 / C_k)**(1/(k-1)) at the argmin k (from the reference weights at p = 1)."""
    C = space_weights(N, Fraction(1), space)
    logc = {k: (math.log(C[0]) - math.log(C[k - 1])) / (k - 1) for k in range(2, N + 1)}
    k = min(logc, key=logc.__getitem__)
    r = Fraction(C[0], C[k - 1])
    return k, sympy.Rational(r.numerator, r.denominator) ** sympy.Rational(1, k - 1)


@pytest.mark.parametrize("space", ["eq41;distinct", "excess<=2;distinct"])
def test_the_jump_written_exactly_is_a_tie_refused_clearly(space):
    k, pc = _distinct_jump(space)
    assert k >= 3 and not pc.is_Rational
    with pytest.raises(UndecidedError) as info:
        symhx.modes(N, pc, space=space)
    assert f"(1, {k})" in str(info.value) and "exact rational" in str(info.value)
    for sign, want in ((1, (k,)), (-1, (1,))):
        p = pc * (1 + sign * sympy.sqrt(2) / 10**60)
        assert symhx.modes(N, p, space=space) \
            == decided(lambda fr: argmax(N, space, fr), p, 100) == want


@pytest.mark.parametrize("space", ["eq41", "excess<=2", "eq41;distinct"])
@pytest.mark.parametrize("e", [30, 80])
def test_next_to_the_jump_beyond_sixty_digits(space, e):
    # p_c of a length-weighted space is a root of a polynomial: approach it from both sides
    # with irrational offsets (a point of its 100-digit enclosure is within 1e-100 of it)
    cp = symhx.critical_point(N, space=space, dps=100)
    mid = (mpf_to_fraction(cp.p_bounds[0]) + mpf_to_fraction(cp.p_bounds[1])) / 2
    base = sympy.Rational(mid.numerator, mid.denominator)
    for sign in (1, -1):
        p = base * (1 + sign * sympy.pi / 10**e)
        got = symhx.modes(N, p, space=space)
        assert got == decided(lambda fr: argmax(N, space, fr), p, e + 40), (space, e, sign)
        assert got == ((cp.k_after,) if sign > 0 else (1,))


def test_the_distribution_object_and_the_float_seed_at_an_irrational():
    p = sympy.sqrt(2) / 40
    d = symhx.distribution_of(N, p, space="eq41", dps=30)
    want = decided(lambda fr: argmax(N, "eq41", fr), p, 60)
    assert d.modes() == want == symhx.spaces.modes(N, p, space="eq41")
    with pytest.raises(ValueError, match="irrational"):
        d.weight_exact(3)  # no exact value exists (it was a 60-digit rational)
