"""Modes at a sympy irrational ``p`` (:func:`symhx.distribution.simple_modes`): a true tie
``Phi(1) = Phi(top)`` is never separated, and the refusal says which values tie and the exact
condition, and shows ``p`` briefly.

Reference: ``N = 9``, ``p**3 = 1/84 = 4/perm(8, 3)`` gives ``Phi(4) = p**4 8!/(4 5!) =
p * 4 * 336 * p**3 / 4 = 9 p = Phi(1)`` exactly (by hand), and the hump of ``Phi`` at that
``p`` tops at 4 (``f(3) > 0 > f(4)``)."""

from __future__ import annotations

import pytest
import sympy

import symhx
from symhx.certify import MAX_IRRATIONAL_BITS, UndecidedError
from tests.harness.errors import assert_refuses


def test_true_tie_at_an_irrational_p_is_refused_with_the_tie_condition():
    x = sympy.Integer(12345678901234567890)
    # 84**(-1/3) times an unevaluated 1 (sin**2 + cos**2): a long str, an exact tie
    p = sympy.Rational(1, 84) ** sympy.Rational(1, 3) * (sympy.sin(x) ** 2 + sympy.cos(x) ** 2)
    assert len(str(p)) > 60
    msg = assert_refuses(symhx.modes, 9, p, exc=UndecidedError, arg="p",
                         allowed="pass p as an exact rational")
    assert f"p={str(p)[:60]} (N=9) are not decided at {MAX_IRRATIONAL_BITS} bits" in msg
    assert "Phi(1) and Phi(4) agree to that precision" in msg
    assert "(a true tie when p**3 = 4/perm(8, 3))" in msg


def test_irrational_p_exactly_at_a_breakpoint_of_the_mode_is_refused():
    # (k+1)/(k (N-k)) at N = 9, k = 3 is 2/9, where Phi(3) = Phi(4): written with an
    # unevaluated factor 1, no ball of it ever lies on one side of the breakpoint
    x = sympy.Integer(98765432109876543210)
    p = sympy.Rational(2, 9) * (sympy.sin(x) ** 2 + sympy.cos(x) ** 2)
    msg = assert_refuses(symhx.modes, 9, p, exc=UndecidedError, arg="p",
                         allowed="pass p as an exact rational")
    assert "p lies within the ball's width of a breakpoint (k+1)/(k (N-k)) of the mode" in msg


def test_the_irrational_precision_limit_is_read_when_the_modes_are_decided(monkeypatch):
    # symhx.certify.MAX_IRRATIONAL_BITS is a documented limit: a changed value reaches the
    # modes (not the value it had when symhx.distribution was imported)
    import symhx.certify

    x = sympy.Integer(12345678901234567890)
    p = sympy.Rational(2, 9) * (sympy.sin(x) ** 2 + sympy.cos(x) ** 2)
    monkeypatch.setattr(symhx.certify, "MAX_IRRATIONAL_BITS", 1 << 12)
    with pytest.raises(UndecidedError, match=f"not decided at {1 << 12} bits"):
        symhx.modes(9, p)
