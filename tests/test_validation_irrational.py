"""The conversion layer and sympy irrationals (issue 28 item 3): the sign of an irrational ``p``
is proved on Arb balls with rising precision, never read at a fixed number of digits and never
through sympy's evalf (its special functions run in mpmath's process-wide context). References:
the digits of sqrt(2) and pi, and exact identities."""

from __future__ import annotations

import pytest
import sympy

from symhx.validation import IRRATIONAL_SIGN_BITS, check_p, to_rational
from tests.harness.errors import assert_refuses

SQRT2_31 = sympy.Rational(14142135623730950488016887242096, 10**31)  # floor(sqrt(2) 10**31)


def test_an_irrational_just_above_zero_is_accepted():
    # 1e-31 above zero: a 15-digit reading would see 0 (or the wrong sign)
    p = sympy.sqrt(2) - SQRT2_31
    fr, same = check_p(p)
    assert fr is None and same is p
    far = sympy.pi - sympy.Rational(31415926535897932384626433832795028841971, 10**40)
    assert check_p(far / sympy.Integer(10) ** 500)[0] is None  # ~1e-541, still proved positive


def test_an_irrational_just_below_zero_is_refused():
    p = SQRT2_31 - sympy.sqrt(2)
    assert_refuses(check_p, p, arg="p", value=str(p)[:20], allowed="> 0")


def test_zero_in_disguise_is_refused_with_its_reason():
    assert_refuses(check_p, sympy.Mul(0, sympy.sqrt(2), evaluate=False), arg="p",
                   allowed="> 0")
    msg = assert_refuses(check_p, sympy.Add(sympy.pi, -sympy.pi, evaluate=False), arg="p",
                         allowed="> 0")
    assert "cannot be decided numerically" in msg
    assert IRRATIONAL_SIGN_BITS >= 1 << 12


def test_what_cannot_be_enclosed_is_a_type_error():
    # a real number symhx has no rigorous enclosure of is refused, not guessed
    assert to_rational(sympy.sqrt(2)) is None
    with pytest.raises(TypeError):
        check_p(sympy.exp(sympy.besselj(1, 2)))
    with pytest.raises(TypeError, match="enclose rigorously"):
        check_p(sympy.sqrt(2) + sympy.fresnels(1))
