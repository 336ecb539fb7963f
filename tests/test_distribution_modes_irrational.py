"""Modes of the simple space at a sympy irrational ``p`` (issue 28, item 3): decided for ``p``
itself, never for a fixed-precision reading of it. References: exact Fractions (brute force over
every k) at both ends of a 200-digit bracket of ``p`` from sympy's own evalf
(:mod:`tests.reference.irrational`)."""

from __future__ import annotations

import time
from fractions import Fraction

import pytest
import sympy

import symhx
from symhx.certify import UndecidedError
from symhx.validation import mpf_to_fraction
from tests.reference.distribution import brute_modes
from tests.reference.irrational import bracket, decided

R = sympy.Rational


def test_issue_case_beyond_sixty_digits():
    # 1/50 ties k = 50 and 51 at N = 101; sqrt(2)/10**70 moves p above it, where the mode is
    # 51 (it was read at 60 digits as exactly 1/50 and answered 50)
    up = R(1, 50) + sympy.sqrt(2) / 10**70
    down = R(1, 50) - sympy.sqrt(2) / 10**70
    assert symhx.modes(101, up) == decided(lambda fr: brute_modes(101, fr), up, 110) == (51,)
    assert symhx.modes(101, down) == decided(lambda fr: brute_modes(101, fr), down, 110) == (50,)
    assert symhx.mode(101, up) == 51 and symhx.distribution_of(101, up).modes() == (51,)


@pytest.mark.parametrize("N, e", [(9, 20), (9, 150), (20, 75), (20, 150), (101, 20), (101, 75)])
def test_irrationals_next_to_every_kind_of_breakpoint(N, e):
    # the breakpoints of the mode: its jump p_c (irrational; a point of its 60-digit
    # enclosure), the first steps after it (Fractions (k+1)/(k (N-k))); irrational offsets of
    # 10**-e on either side, referenced at e + 40 digits
    path = symhx.mode_path(N, p_max=1, dps=60)
    lo, hi = path.critical.p_bounds
    points = [(mpf_to_fraction(lo) + mpf_to_fraction(hi)) / 2]
    points += [bp for bp, _, _ in path.breakpoints[1:3]]
    for bp in points:
        for sign in (1, -1):
            p = R(bp.numerator, bp.denominator) * (1 + sign * sympy.sqrt(3) / 10**e)
            assert symhx.modes(N, p) \
                == decided(lambda fr: brute_modes(N, fr), p, e + 40), (N, e, bp, sign)


def test_a_true_tie_at_an_irrational_is_refused_clearly():
    # N = 9: c_4 = (1/84)**(1/3) = 882**(1/3)/42 is the jump p_c, where Phi(1) = Phi(4)
    p = sympy.root(882, 3) / 42
    assert sympy.simplify(p**3 - R(1, 84)) == 0
    t = time.perf_counter()
    with pytest.raises(UndecidedError) as info:
        symhx.modes(9, p)
    assert time.perf_counter() - t < 10
    msg = str(info.value)
    assert "Phi(1) and Phi(4)" in msg and "exact rational" in msg and "882" in msg
    # either side of the tie is decided, as the reference says
    for sign in (1, -1):
        q = p * (1 + sign * sympy.pi / 10**90)
        assert symhx.modes(9, q) \
            == decided(lambda fr: brute_modes(9, fr), q) == ((4,) if sign > 0 else (1,))


def test_a_rational_written_irrationally_at_a_tie_is_refused():
    # sqrt(2) * sqrt(2) / 100 is exactly 1/50 (the tie 50, 51 at N = 101); its Arb ball never
    # shrinks to a point, so the hump's bracket never decides: refused, never guessed
    p = sympy.Mul(sympy.sqrt(2), sympy.sqrt(2), R(1, 100), evaluate=False)
    with pytest.raises(UndecidedError, match="breakpoint"):
        symhx.modes(101, p)
    # an exactly representable (dyadic) value written as an expression is decided exactly
    q = sympy.Mul(2, R(1, 128), evaluate=False)
    assert symhx.modes(101, q) == symhx.modes(101, Fraction(1, 64))


def test_precision_rises_as_far_as_the_decision_needs():
    # an offset of 10**-2000 needs ~6700 bits: decided, quickly. Reference: the bracket of p
    # is above the tie 1/50, and just above the tie the mode is 51 (brute force)
    p = R(1, 50) + sympy.sqrt(5) / 10**2000
    t = time.perf_counter()
    assert symhx.modes(101, p) == (51,)
    assert time.perf_counter() - t < 5
    assert bracket(p, 2100)[0] > Fraction(1, 50)
    assert brute_modes(101, Fraction(1, 50) + Fraction(1, 10**30)) == (51,)


@pytest.mark.parametrize("N", [10**6, 10**30])
def test_huge_N_next_to_a_step_of_the_mode(N):
    # after the jump the mode steps from k to k+1 at the rational (k+1)/(k (N-k)) (eq. 10
    # with f = 0): just above it the mode is k + 1, just below it k, for any N
    k = symhx.critical_point(N, dps=20).k_after + 3
    bp = R(k + 1, k * (N - k))
    assert symhx.modes(N, bp) == (k, k + 1)
    assert symhx.modes(N, bp * (1 + sympy.sqrt(2) / 10**90)) == (k + 1,)
    assert symhx.modes(N, bp * (1 - sympy.sqrt(2) / 10**90)) == (k,)


def test_p_far_below_or_above_the_jump():
    assert symhx.modes(10**100, sympy.pi / 10**110) == (1,)
    assert symhx.modes(101, sympy.sqrt(2) / 50) \
        == decided(lambda fr: brute_modes(101, fr), sympy.sqrt(2) / 50)
    assert symhx.modes(5, sympy.E) == decided(lambda fr: brute_modes(5, fr), sympy.E)
