"""``symhx._numeric.mp_value`` of a sympy irrational (issue 28 item 3): evaluated to the working
precision of the calling thread's context from a rigorous Arb ball (never at a fixed number of
digits, never through sympy's evalf). Reference: mpmath's own constants at twice the digits."""

from __future__ import annotations

import mpmath
import pytest
import sympy

from symhx._mpctx import export, mp
from symhx._numeric import mp_value


@pytest.mark.parametrize("dps", [5, 15, 60, 400, 2000])
def test_mp_value_reaches_the_working_precision(dps):
    expr = sympy.sqrt(2) / 100 + sympy.pi / 10**5 - sympy.exp(sympy.Rational(-1, 3)) / 10**7
    ctx = mp()
    before = mpmath.mp.prec
    with ctx.workdps(dps):
        got = mp_value(expr, None)
        assert type(got) is ctx.mpf
        got = export(got)
    with mpmath.workdps(2 * dps + 20):
        ref = mpmath.sqrt(2) / 100 + mpmath.pi / 10**5 - mpmath.exp(mpmath.mpf(-1) / 3) / 10**7
        assert abs(got - ref) <= 2 * mpmath.mpf(10) ** (-dps) * ref
    assert mpmath.mp.prec == before  # the global precision is not touched


def test_mp_value_of_a_tiny_irrational_keeps_its_relative_accuracy():
    # the value is ~1e-70 next to an O(1) term that cancels: 60 fixed digits would give 0
    expr = sympy.Add(sympy.Rational(1, 50), sympy.sqrt(2) / 10**70, sympy.Rational(-1, 50),
                     evaluate=False)
    ctx = mp()
    with ctx.workdps(30):
        got = export(mp_value(expr, None))
    with mpmath.workdps(80):
        assert abs(got / (mpmath.sqrt(2) / mpmath.mpf(10) ** 70) - 1) < mpmath.mpf(10) ** -29
