"""The one conversion layer (symhx.validation): exact decimals, binary floats, refusals."""

from decimal import Decimal
from fractions import Fraction

import mpmath
import numpy as np
import pytest
import sympy

from symhx import validation as v


@pytest.mark.parametrize("text, exact", [
    ("0.02", Fraction(1, 50)), ("2e-2", Fraction(1, 50)), ("1/50", Fraction(1, 50)),
    (" 3 ", Fraction(3)), ("10**3", Fraction(1000)), ("-1.5e1", Fraction(-15)),
    ("1e-400", Fraction(1, 10**400)),
])
def test_decimal_strings_are_exact(text, exact):
    assert v.to_rational(text) == exact


@pytest.mark.parametrize("x", [0.1, -0.1, 1e-300, 5e-324, 1e308])
def test_floats_and_mpf_at_their_exact_binary_value(x):
    assert v.to_rational(x) == Fraction(x)  # Python's own exact conversion
    with mpmath.workdps(60):
        m = mpmath.mpf(x)
    assert v.to_rational(m) == Fraction(x)  # the sign too (a negative mpf was once taken as |p|)


def test_other_exact_types():
    assert v.to_rational(Decimal("0.25")) == Fraction(1, 4)
    assert v.to_rational(sympy.Rational(1, 3)) == Fraction(1, 3)
    assert v.to_rational(np.int64(7)) == 7
    assert v.to_rational(sympy.sqrt(2)) is None  # a real irrational


@pytest.mark.parametrize("bad, exc", [
    (True, TypeError), (np.True_, TypeError), ("abc", ValueError), ("1/0", ValueError),
    ("nan", ValueError), (float("nan"), ValueError), (float("inf"), ValueError),
    (mpmath.mpf("-inf"), ValueError), (1j, TypeError), (None, TypeError), ([1], TypeError),
    ("1e200000", ValueError), (mpmath.mpf("1e-100000000000"), ValueError),
])
def test_refusals_name_the_argument(bad, exc):
    with pytest.raises(exc, match=r"^p"):
        v.to_rational(bad, "p")


def test_check_p_sign_and_zero():
    assert v.check_p("0.5")[0] == Fraction(1, 2)
    for bad in (0, "0", -0.1, mpmath.mpf("-0.1")):
        with pytest.raises(ValueError, match="p must be > 0"):
            v.check_p(bad)


@pytest.mark.parametrize("dps, exc", [(0, ValueError), (-1, ValueError), (2.5, TypeError),
                                      (True, TypeError), (10**6, ValueError), ("30", TypeError)])
def test_check_dps(dps, exc):
    with pytest.raises(exc, match=r"^dps must be an int between 1 and 5000"):
        v.check_dps(dps)


def test_check_dps_none_and_bounds():
    assert v.check_dps(None, allow_none=True) is None
    assert v.check_dps(1) == 1 and v.check_dps(v.MAX_DPS) == v.MAX_DPS
    with pytest.raises(TypeError):
        v.check_dps(None)


def test_check_int_and_N():
    assert v.check_N("1e100") == 10**100 and v.check_N(np.int64(5)) == 5
    assert v.check_int(Fraction(6, 3), "k") == 2
    for bad, exc in ((2.0, TypeError), (True, TypeError), ("2.5", ValueError), (1, ValueError)):
        with pytest.raises(exc, match=r"^N must"):
            v.check_N(bad)


def test_check_array_reports_first_bad_index():
    with pytest.raises(ValueError, match=r"at index \(2,\)"):
        v.check_array([1.0, 2.0, float("nan")], "sigma")
    with pytest.raises(ValueError, match=r"sigma must be > 0, got -1.0 at index \(1,\)"):
        v.check_array([1.0, -1.0], "sigma", positive=True)
    with pytest.raises(TypeError):
        v.check_array([True, False], "sigma")
    assert v.check_array([], "sigma", allow_empty=True).size == 0
