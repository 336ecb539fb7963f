"""How symhx.certify.real_ball names what it cannot evaluate: sympy objects that are not real
numbers (a matrix, a symbol, a function itself) are a TypeError naming the object's kind and
saying what to pass instead, never an AttributeError from inside the walker."""

from __future__ import annotations

import pytest
import sympy

from symhx.certify import arb_prec, real_ball, real_sign, to_arb


@pytest.mark.parametrize(("obj", "kind"), [
    (sympy.Matrix([[1]]), "MutableDenseMatrix"),
    (sympy.ImmutableMatrix([[1, 2]]), "ImmutableDenseMatrix"),
    (sympy.Symbol("x"), "Symbol"),
    (sympy.sqrt(2) + sympy.Symbol("y"), "Symbol"),
])
def test_what_is_not_a_real_number_is_named_in_a_type_error(obj, kind):
    with arb_prec(64), pytest.raises(TypeError) as info:
        real_ball(obj)
    msg = str(info.value)
    assert f"cannot evaluate {kind} " in msg, msg
    assert msg.endswith("; pass the number as an exact rational or a float instead"), msg
    with arb_prec(64), pytest.raises(TypeError, match=kind):
        to_arb(obj)
    with pytest.raises(TypeError, match=kind):
        real_sign(obj)
