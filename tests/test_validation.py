"""symhx.validation, function by function: exact values, every branch and bound, and refusals
that name the argument, show the offending value and say what is allowed.

Reference values are exact rationals written here (binary values of floats spelled out as
``m / 2**e``) or Python's own exact parsers (``Fraction(text)``, ``int(text)``).
"""

import math
import re
from decimal import Decimal
from fractions import Fraction

import mpmath
import numpy as np
import pytest
import sympy

from symhx import validation as v
from tests.harness.errors import assert_refuses

MAXD = v.MAX_DECIMAL_EXPONENT
MAXB = v.MAX_BINARY_EXPONENT
INTEGER_FORMS = "an integer such as 7, 10**100 or '1e100'"
NUMBER_FORMS = "a number such as 0.02, 2e-2, 1/50 or 10**100"
NOT_EXACT_FLOAT = ["an int", "floats above 2**53 are not exact", "10**100", "'1e100'"]
DPS_RANGE = "an int between 1 and 5000"


def test_documented_constants():
    assert (v.DEFAULT_DPS, v.MAX_DPS, v.DEFAULT_SPACE) == (50, 5000, "simple")
    assert (MAXD, MAXB) == (100_000, 3_400_000)


# --------------------------------------------------------------------------- how a value is shown
class _Repr:
    def __init__(self, n):
        self.n = n

    def __repr__(self):
        return "a" * self.n


class _BadRepr:
    def __repr__(self):
        raise RuntimeError("no repr")


def test_a_value_whose_repr_raises_is_still_shown():
    bad = _BadRepr()
    shown = object.__repr__(bad)  # the fallback, cut at 60 characters like any repr
    shown = shown if len(shown) <= 60 else shown[:57] + "..."
    assert_refuses(v.to_rational, bad, exc=TypeError, arg="p", value=f"_BadRepr {shown}",
                   allowed="real number")


@pytest.mark.parametrize("n, shown", [(60, "a" * 60), (61, "a" * 57 + "..."),
                                      (100, "a" * 57 + "...")])
def test_long_reprs_are_cut_at_60_characters(n, shown):
    msg = assert_refuses(v.to_rational, _Repr(n), exc=TypeError, arg="p",
                         value=f"_Repr {shown}", allowed="real number")
    assert "a" * (len(shown.rstrip(".")) + 1) not in msg


# --------------------------------------------------------------------------- strings
@pytest.mark.parametrize("text, exact", [
    ("0.02", Fraction(1, 50)), ("2e-2", Fraction(1, 50)), ("2E-2", Fraction(1, 50)),
    (".5", Fraction(1, 2)), ("5.", Fraction(5)), ("-1.5e+1", Fraction(-15)), ("+7", Fraction(7)),
    ("-1.5e1", Fraction(-15)), ("1e-400", Fraction(1, 10**400)), (" 3 ", Fraction(3)),
    ("\t 3 \n", Fraction(3)), ("1_000.5", Fraction(2001, 2)), ("1_0e1_0", Fraction(10**11)),
    ("1/50", Fraction(1, 50)), (" -3 / +6 ", Fraction(-1, 2)), ("+3/-6", Fraction(-1, 2)),
    ("1_0/2_0", Fraction(1, 2)), ("0/7", Fraction(0)),
    ("10**3", Fraction(1000)), (" 2 ** 10 ", Fraction(1024)), ("0**0", Fraction(1)),
    ("0**5", Fraction(0)), ("1**5", Fraction(1)), ("1**1000000000000", Fraction(1)),
    ("7**0", Fraction(1)),
])
def test_decimal_strings_are_exact(text, exact):
    got = v.to_rational(text)
    assert type(got) is Fraction and got == exact


@pytest.mark.parametrize("text", ["1_000", "1__0", "_1", "1_", "1._5", "1_.5", "1e_5", "1_e5",
                                  "0.000_1", "1_0e1_0", "-_1", "1e-_3", "12_3.4_5e6_7"])
def test_underscores_follow_pythons_rule(text):
    # the reference is Python's own parser: an underscore only between two digits
    try:
        ref = Fraction(text)
    except ValueError:
        assert_refuses(v.to_rational, text, arg="p", value=repr(text),
                       allowed=["a number", "an underscore may only separate two digits"])
    else:
        assert v.to_rational(text) == ref
    if "." not in text and "e" not in text:
        try:
            iref = int(text)
        except ValueError:
            assert_refuses(v.check_int, text, "n", arg="n", value=repr(text),
                           allowed=["an integer", "an underscore may only separate two digits"])
        else:
            assert v.check_int(text, "n") == iref
    for form in (f"{text}/3", f"3**{text}"):     # the same rule inside ratios and powers
        if "." in text or "e" in text or "-" in text:
            continue
        ok = "__" not in text and not text.startswith("_") and not text.endswith("_")
        if ok:
            v.to_rational(form)
        else:
            assert_refuses(v.to_rational, form, arg="p", value=repr(form),
                           allowed="an underscore may only separate two digits")


def _assert_exponent_refused(x, name, shown):
    assert_refuses(v.to_rational, x, name, arg=name, value=shown,
                   allowed=[f"+-{MAXD}", "symhx.validation.MAX_DECIMAL_EXPONENT"])


def test_decimal_exponent_cap_at_its_exact_boundary():
    # accepted: decimal exponent MAXD (the number has MAXD + 1 digits), also as a power
    assert v.to_rational(f"1e{MAXD}") == 10**MAXD
    assert v.to_rational(f"10e{MAXD - 1}") == 10**MAXD
    assert v.to_rational(f"9.5e{MAXD}") == Fraction(19, 2) * 10**MAXD
    assert v.to_rational(f"10**{MAXD}") == 10**MAXD
    assert v.to_rational(f"1e-{MAXD}") == Fraction(1, 10**MAXD)
    assert v.to_rational(f"0e{10 * MAXD}") == 0  # zero has no exponent to cap
    # 10**(MAXD + 1) = 2**332196.6...: 2**332196 is accepted, 2**332197 refused
    assert 2**332196 < 10**(MAXD + 1) < 2**332197
    assert v.to_rational("2**332196") == 2**332196
    # 3**10**9 (200 MB, minutes to compute) is refused by its size bound before it is computed;
    # no larger input here: a broken bound must not exhaust the machine's memory
    for text in (f"1e{MAXD + 1}", f"100e{MAXD - 1}", f"1e-{MAXD + 1}", f"-1e{MAXD + 1}",
                 f"10**{MAXD + 1}", "2**332197", "3**1000000", "9**1000000", "10**200000",
                 "3**1000000000"):
        _assert_exponent_refused(text, "sigma", repr(text))


def test_the_same_cap_for_decimal_objects():
    assert v.to_rational(Decimal(f"1e{MAXD}")) == 10**MAXD
    assert v.to_rational(Decimal(f"1e-{MAXD}")) == Fraction(1, 10**MAXD)
    assert v.to_rational(Decimal("0e999999999")) == 0
    for d in (Decimal(f"1e{MAXD + 1}"), Decimal(f"-1e-{MAXD + 1}"), Decimal("1e999999999")):
        _assert_exponent_refused(d, "p", repr(d))


@pytest.mark.parametrize("text", ["abc", "", "  ", "1/2/3", "1e", "e5", "nan", "inf", "0x10",
                                  "1 000", "1/2.5", "2**-1", "-2**2", "1.5**2", "**2", "--1"])
def test_strings_that_are_not_numbers(text):
    assert_refuses(v.to_rational, text, "q", arg="q", value=repr(text), allowed=NUMBER_FORMS)
    assert_refuses(v.check_int, text, "k", arg="k", value=repr(text), allowed=INTEGER_FORMS)


def test_division_by_zero():
    for text in ("1/0", " 0 / -0 "):
        assert_refuses(v.to_rational, text, "q", arg="q", value=repr(text),
                       allowed=["a finite number", "division by zero"])
    assert_refuses(v.check_int, "1/0", "k", arg="k", value="'1/0'",
                   allowed=["an integer", "division by zero"])


def test_integer_arguments_say_integer():
    # an integer argument is not asked for "a number such as 0.02, 2e-2, 1/50"
    for call, name, text in ((lambda: v.check_int("seed", "random_state"), "random_state",
                              "seed"), (lambda: v.check_seed("x"), "seed", "x"),
                             (lambda: v.check_N("ten"), "N", "ten")):
        msg = assert_refuses(call, arg=name, value=repr(text), allowed=INTEGER_FORMS)
        assert "0.02" not in msg


# --------------------------------------------------------------------------- to_rational by type
@pytest.mark.parametrize("bad", [True, False, np.True_, np.bool_(False)])
def test_bools_are_not_numbers(bad):
    assert_refuses(v.to_rational, bad, "w", exc=TypeError, arg="w", value=f"bool {bad!r}",
                   allowed="real number")


@pytest.mark.parametrize("x", [0.1, -0.1, 1e-300, 5e-324, 1e308])
def test_floats_and_mpf_at_their_exact_binary_value(x):
    assert v.to_rational(x) == Fraction(x)  # Python's own exact conversion
    with mpmath.workdps(60):
        m = mpmath.mpf(x)
    assert v.to_rational(m) == Fraction(x)  # the sign too (a negative mpf was once taken as |p|)


def test_ints_fractions_floats():
    for x, exact in ((3, Fraction(3)), (-(10**30), Fraction(-(10**30))),
                     (Fraction(-2, 6), Fraction(-1, 3)), (0.1, Fraction(3602879701896397, 2**55)),
                     (-0.75, Fraction(-3, 4)), (5e-324, Fraction(1, 2**1074)), (0.0, Fraction(0)),
                     (np.float64(0.1), Fraction(3602879701896397, 2**55))):
        got = v.to_rational(x)
        assert type(got) is Fraction and got == exact


@pytest.mark.parametrize("bad, shown", [(math.nan, "nan"), (math.inf, "inf"), (-math.inf, "-inf"),
                                        (np.float64("nan"), "np.float64(nan)")])
def test_float_nan_and_inf(bad, shown):
    assert_refuses(v.to_rational, bad, "x", arg="x", value=shown, allowed="finite")


def test_decimals():
    assert v.to_rational(Decimal("0.25")) == Fraction(1, 4)
    assert v.to_rational(Decimal("-1.5E+3")) == -1500
    for bad in (Decimal("NaN"), Decimal("Infinity"), Decimal("-Infinity"), Decimal("sNaN")):
        assert_refuses(v.to_rational, bad, "x", arg="x", value=repr(bad), allowed="finite")


def test_mpf_exact_binary_value_and_sign():
    with mpmath.workdps(60):
        tenth = mpmath.mpf("0.1")
    got = v.to_rational(tenth)  # a 203-bit binary value within 10**-60 of 1/10
    assert got.denominator & (got.denominator - 1) == 0 and got.denominator > 2**190
    assert abs(got - Fraction(1, 10)) < Fraction(1, 10**60)
    assert v.to_rational(mpmath.mpf((1, 3, -2, 2))) == Fraction(-3, 4)
    assert v.to_rational(mpmath.mpf((0, 3, 2, 2))) == 12
    assert v.to_rational(mpmath.mpf((0, 5, 0, 3))) == 5
    assert v.to_rational(mpmath.mpf(0)) == 0
    for bad in (mpmath.mpf("inf"), mpmath.mpf("-inf"), mpmath.mpf("nan")):
        assert_refuses(v.to_rational, bad, "x", arg="x", value=repr(bad), allowed="finite")


def _assert_binary_refused(x, shown):
    msg = assert_refuses(v.to_rational, x, "x", arg="x", value=shown,
                         allowed=["2**+-3400000", "symhx.validation.MAX_BINARY_EXPONENT"])
    assert re.search(r"x=-?\d\.\d{4}e[+-]?\d+ ", msg)  # 5 significant digits


def test_mpf_binary_exponent_cap_at_its_exact_boundary():
    # (sign, man, exp, bc): |x| lies in [2**(exp + bc - 1), 2**(exp + bc))
    assert v.to_rational(mpmath.mpf((0, 1, MAXB - 1, 1))) == 2**(MAXB - 1)
    assert v.to_rational(mpmath.mpf((1, 3, MAXB - 2, 2))) == -3 * 2**(MAXB - 2)
    assert v.to_rational(mpmath.mpf((0, 1, -MAXB - 1, 1))) == Fraction(1, 2**(MAXB + 1))
    assert v.to_rational(mpmath.mpf((0, 3, -MAXB - 2, 2))) == Fraction(3, 2**(MAXB + 2))
    with mpmath.workdps(30):
        big = mpmath.mpf("1.234567e1023500")  # log2 = 3399996.2: inside
        tiny = mpmath.mpf("1.234567e-2000000")
        assert v.to_rational(big) == v.mpf_to_fraction(big)
        # the value is shown in 5 significant digits (an mpf beyond the cap has ~10**6 digits)
        for x in (mpmath.mpf((0, 1, MAXB, 1)), mpmath.mpf((0, 3, MAXB - 1, 2)),
                  mpmath.mpf((1, 1, -MAXB - 2, 1)), mpmath.mpf((0, 3, -MAXB - 3, 2))):
            _assert_binary_refused(x, f"x={mpmath.nstr(x, 5)} ")
        _assert_binary_refused(tiny, "x=1.2346e-2000000 ")
        _assert_binary_refused(mpmath.mpf("1.234567e1023600"), "x=1.2346e+1023600 ")


def test_mpf_to_fraction_has_no_cap():
    assert v.mpf_to_fraction(mpmath.mpf((1, 5, -3, 3))) == Fraction(-5, 8)
    assert v.mpf_to_fraction(mpmath.mpf((0, 1, 5 * MAXB, 1))) == 2**(5 * MAXB)
    assert v.mpf_to_fraction(mpmath.mpf((0, 7, 0, 3))) == 7
    assert v.mpf_to_fraction(mpmath.mpf((0, 7, 1, 3))) == 14
    assert v.mpf_to_fraction(mpmath.mpf(0)) == 0


def test_sympy_numbers():
    assert v.to_rational(sympy.Rational(1, 3)) == Fraction(1, 3)
    assert v.to_rational(sympy.Rational(-4, 2)) == -2
    assert v.to_rational(sympy.Integer(10)**40) == 10**40
    assert v.to_rational(sympy.Float(0.1)) == Fraction(3602879701896397, 2**55)
    assert v.to_rational(sympy.Float(-0.75)) == Fraction(-3, 4)
    assert v.to_rational(sympy.Float(0)) == 0
    fifty = v.to_rational(sympy.Float("0.1", 50))  # a binary value within 10**-50 of 1/10
    assert fifty.denominator & (fifty.denominator - 1) == 0
    assert 0 < abs(fifty - Fraction(1, 10)) < Fraction(1, 10**50)
    assert v.to_rational(sympy.sqrt(2)) is None and v.to_rational(sympy.pi - 4) is None
    msg = assert_refuses(v.to_rational, sympy.Float("1.234567e-2000000", 30), "x", arg="x",
                         value="x=1.23456",
                         allowed=["2**+-3400000", "symhx.validation.MAX_BINARY_EXPONENT"])
    assert "E-2000000 " in msg
    for bad, shown in ((sympy.oo, "oo"), (-sympy.oo, "-oo"), (sympy.zoo, "zoo"),
                       (sympy.nan, "nan")):
        msg = assert_refuses(v.to_rational, bad, "x", arg="x", value=shown, allowed="finite")
    for bad, shown in ((sympy.I, "I"), (1 + sympy.I, "1 + I"), (sympy.Symbol("t"), "t"),
                       (sympy.Matrix([[1]]), "Matrix([[1]])"), (sympy.sqrt(-2), "sqrt(2)*I"),
                       (sympy.Symbol("r", rational=True), "r")):
        msg = assert_refuses(v.to_rational, bad, "x", exc=TypeError, arg="x",
                             value=f"sympy object {shown}", allowed="a finite real number")


def test_numpy_scalars_and_0d_arrays():
    assert v.to_rational(np.int8(-3)) == -3
    assert v.to_rational(np.int64(7)) == 7
    assert v.to_rational(np.uint64(2**64 - 1)) == 2**64 - 1
    assert v.to_rational(np.float32(0.1)) == Fraction(13421773, 2**27)
    assert v.to_rational(np.float16(0.1)) == Fraction(819, 2**13)
    third = np.longdouble(1) / np.longdouble(3)
    got = v.to_rational(third)  # the long double's own value, not float(third)
    nmant = np.finfo(np.longdouble).nmant
    assert got.denominator & (got.denominator - 1) == 0
    assert abs(got - Fraction(1, 3)) <= Fraction(1, 2**(nmant + 2))
    if nmant > 52:
        assert got != Fraction(float(third))
        big = np.longdouble(2) ** 2000  # finite as a long double, inf as a float
        assert v.to_rational(big) == 2**2000
    for bad, shown in ((np.float32("inf"), "np.float32(inf)"),
                       (np.float16("nan"), "np.float16(nan)")):
        assert_refuses(v.to_rational, bad, "x", arg="x", value=shown, allowed="finite")
    assert v.to_rational(np.array(0.25)) == Fraction(1, 4)
    assert v.to_rational(np.array(-7)) == -7
    assert v.to_rational(np.array(Fraction(1, 3), dtype=object)) == Fraction(1, 3)
    assert v.to_rational(np.array("2/3")) == Fraction(2, 3)
    assert_refuses(v.to_rational, np.array(True), "x", exc=TypeError, arg="x",
                   value="bool np.True_", allowed="real number")
    assert_refuses(v.to_rational, np.array([0.5]), "x", exc=TypeError, arg="x",
                   value="ndarray array([0.5])", allowed="real number")


@pytest.mark.parametrize("bad, shown", [
    (1j, "complex 1j"), (np.complex128(1), "complex128 np.complex128(1+0j)"),
    (mpmath.mpc(1, 1), "mpc mpc(real='1.0', imag='1.0')"), (None, "NoneType None"),
    ([1], "list [1]"), (b"1", "bytes b'1'"), (object, "type <class 'object'>"),
])
def test_non_numbers(bad, shown):
    assert_refuses(v.to_rational, bad, "y", exc=TypeError, arg="y", value=shown,
                   allowed="a real number")


@pytest.mark.parametrize("bad, exc", [
    (True, TypeError), (np.True_, TypeError), ("abc", ValueError), ("1/0", ValueError),
    ("nan", ValueError), (float("nan"), ValueError), (float("inf"), ValueError),
    (mpmath.mpf("-inf"), ValueError), (1j, TypeError), (None, TypeError), ([1], TypeError),
    ("1e200000", ValueError), (mpmath.mpf("1e-100000000000"), ValueError),
])
def test_refusals_name_the_argument(bad, exc):
    msg = assert_refuses(v.to_rational, bad, "p", exc=exc, arg="p")
    assert msg.startswith("p")


def test_default_name_and_alias():
    for call, name in ((lambda: v.to_rational(None), "p"), (lambda: v.as_fraction(None), "p"),
                       (lambda: v.as_fraction(None, "q"), "q")):
        assert_refuses(call, exc=TypeError, arg=name, value="NoneType None",
                       allowed="real number")
    assert v.as_fraction("0.125") == Fraction(1, 8)
    assert v.as_fraction(sympy.sqrt(3)) is None


def test_is_exact_type():
    for x in (3, -3, Fraction(1, 3), "0.02", "junk", np.int64(2), np.uint8(1),
              sympy.Rational(1, 3), sympy.Integer(2), Decimal("0.5"), Decimal("-1e-9")):
        assert v.is_exact_type(x) is True, x
    for x in (True, False, np.True_, 0.5, np.float64(0.5), mpmath.mpf(1),
              sympy.sqrt(2), sympy.Float(0.5), None, [1], 1j, sympy.Matrix([[1]]),
              sympy.Symbol("r", rational=True)):
        assert v.is_exact_type(x) is False, x


# --------------------------------------------------------------------------- check_p, check_real
def test_check_p():
    for p, exact in (("0.5", Fraction(1, 2)), (2, Fraction(2)), (0.25, Fraction(1, 4)),
                     (mpmath.mpf((0, 1, -1100, 1)), Fraction(1, 2**1100)),
                     (Fraction(1, 10**400), Fraction(1, 10**400))):
        fr, orig = v.check_p(p)
        assert type(fr) is Fraction and fr == exact and orig is p
    s = sympy.sqrt(2) / 50
    fr, orig = v.check_p(s)
    assert fr is None and orig is s
    tiny = sympy.sqrt(2) * sympy.Rational(1, 10**50) - sympy.Rational(141421356, 10**58)  # > 0
    assert v.check_p(tiny)[0] is None
    for bad, shown in ((0, "0"), ("0", "'0'"), ("-1/3", "'-1/3'"), (-0.1, "-0.1"),
                       (mpmath.mpf("-0.1"), "mpf('-0.10000000000000001')"),
                       (Fraction(0), "Fraction(0, 1)"), (sympy.sqrt(2) - 2, "-2 + sqrt(2)"),
                       (-tiny, repr(-tiny))):
        assert_refuses(v.check_p, bad, "a", arg="a", value=shown, allowed="> 0")
    assert_refuses(v.check_p, 0, arg="p", value="0", allowed="> 0")
    assert_refuses(v.check_p, True, exc=TypeError, arg="p", value="bool True",
                   allowed="real number")
    assert_refuses(v.check_p, True, "a", exc=TypeError, arg="a", value="bool True",
                   allowed="real number")
    # zeros that are not simplified: an exact 0 is refused as <= 0; a zero that cancels has no
    # decidable sign (plain evalf gives 0.e-163, which is > 0: pi - pi used to be accepted)
    msg = assert_refuses(v.check_p, sympy.Mul(0, sympy.sqrt(2), evaluate=False), "a", arg="a",
                         value="0*sqrt(2)", allowed="> 0")
    assert "decided" not in msg
    for zero in (sympy.Add(sympy.pi, -sympy.pi, evaluate=False),
                 sympy.Add(sympy.sqrt(2), -sympy.sqrt(2), evaluate=False),
                 sympy.cos(1)**2 + sympy.sin(1)**2 - 1):
        assert_refuses(v.check_p, zero, "a", arg="a", value=repr(zero),
                       allowed=["> 0", "its sign cannot be decided numerically", "simplify it"])
    # sqrt(2) - floor(sqrt(2) * 10**60) / 10**60: positive, 60 digits of cancellation
    s = sympy.sqrt(2) - sympy.Rational(int(sympy.sqrt(2 * 10**120)), 10**60)
    assert v.check_p(s)[0] is None
    assert_refuses(v.check_p, -s, "a", arg="a", value=repr(-s), allowed="> 0")


def test_check_real_bounds_at_their_exact_values():
    assert v.check_real("0.5", "x") == Fraction(1, 2)
    assert type(v.check_real(3, "x")) is Fraction
    # closed bounds include the bound itself, exactly (float bounds at their binary value)
    assert v.check_real(0, "x", low=0) == 0
    assert v.check_real("1", "x", high=1) == 1
    assert v.check_real(0.1, "x", low=0.1, high=0.1) == Fraction(3602879701896397, 2**55)
    assert v.check_real("0.1", "x", high=0.1) == Fraction(1, 10)  # 1/10 < the float 0.1
    for call, shown, allowed in (
            (lambda: v.check_real("0.1", "x", low=0.1), "'0.1'", ">= 0.1"),
            (lambda: v.check_real(-1e-300, "x", low=0), "-1e-300", ">= 0"),
            (lambda: v.check_real(0, "x", low=0, low_open=True), "0", "> 0"),
            (lambda: v.check_real("1/2", "x", low=0.5, low_open=True), "'1/2'", "> 0.5"),
            (lambda: v.check_real("1.0000001", "x", high=1), "'1.0000001'", "<= 1"),
            (lambda: v.check_real(1, "x", high=1, high_open=True), "1", "< 1"),
            (lambda: v.check_real(1, "x", low=1, high=3, low_open=True), "1", "> 1"),
            (lambda: v.check_real(4, "x", low=1, high=3), "4", "<= 3")):
        msg = assert_refuses(call, arg="x", value=shown, allowed=allowed)
        assert shown in msg.replace(allowed, "")  # the value itself, not the bound
    assert v.check_real("0.5000001", "x", low=0.5, low_open=True) == Fraction(5000001, 10**7)
    assert v.check_real("0.9999999", "x", high=1, high_open=True) == Fraction(9999999, 10**7)
    assert v.check_real(2, "x", low=1, high=3, low_open=True, high_open=True) == 2
    assert v.check_real(-5, "x", high=3) == -5 and v.check_real(10**50, "x", low=3) == 10**50
    assert_refuses(v.check_real, sympy.sqrt(2), "x", exc=TypeError, arg="x",
                   value="Pow sqrt(2)", allowed="a rational or float number")
    assert_refuses(v.check_real, None, "x", exc=TypeError, arg="x", value="NoneType None",
                   allowed="a real number")


# --------------------------------------------------------------------------- integers
def test_check_int_accepts_exact_integers():
    for x, exact in ((7, 7), (-(10**40), -(10**40)), (np.int64(5), 5), (np.uint8(255), 255),
                     (np.array(4), 4), (Fraction(6, 3), 2), (sympy.Integer(-7), -7),
                     (sympy.Integer(10)**30, 10**30), ("101", 101), (" -3 ", -3),
                     ("1e100", 10**100), ("2.5e1", 25), ("10**100", 10**100), ("6/3", 2),
                     ("1_000", 1000)):
        got = v.check_int(x, "k")
        assert type(got) is int and got == exact, x


def test_check_int_refusals():
    for bad in (True, np.False_):
        assert_refuses(v.check_int, bad, "k", exc=TypeError, arg="k", value=f"bool {bad!r}",
                       allowed="an integer")
    for bad, shown in (("2.5", "'2.5'"), ("1/3", "'1/3'"), (Fraction(5, 2), "Fraction(5, 2)"),
                       (sympy.Rational(1, 2), "1/2"), (sympy.Rational(-7, 3), "-7/3")):
        assert_refuses(v.check_int, bad, "k", arg="k", value=shown, allowed="an integer")
    for bad, shown in ((2.0, "2.0"), (1e100, "1e+100"), (np.float32(2), "np.float32(2.0)"),
                       (np.float64(3), "np.float64(3.0)")):
        assert_refuses(v.check_int, bad, "k", exc=TypeError, arg="k", value=f"float {shown}",
                       allowed=NOT_EXACT_FLOAT)
    for bad, shown in ((None, "NoneType None"), (mpmath.mpf(2), "mpf mpf('2.0')"),
                       (Decimal(2), "Decimal Decimal('2')"), (sympy.sqrt(2), "Pow sqrt(2)"),
                       (sympy.Float(2), "Float 2.00000000000000"), (1j, "complex 1j"),
                       (np.array(2.0), "ndarray array(2.)"), ([2], "list [2]"),
                       (sympy.Matrix([[1]]), "MutableDenseMatrix Matrix([[1]])"),
                       (sympy.Symbol("r", rational=True), "Symbol r")):
        assert_refuses(v.check_int, bad, "k", exc=TypeError, arg="k", value=shown,
                       allowed="an integer")


def test_check_int_bounds_at_their_exact_values():
    assert v.check_int(3, "k", minimum=3) == 3 and v.check_int(5, "k", maximum=5) == 5
    assert v.check_int(4, "k", minimum=3, maximum=5) == 4
    for call, shown, allowed in (
            (lambda: v.check_int(2, "k", minimum=3), "2", ">= 3"),
            (lambda: v.check_int(6, "k", maximum=5), "6", "<= 5"),
            (lambda: v.check_int("1e1", "k", minimum=3, maximum=5), "10", "<= 5"),
            (lambda: v.check_int(Fraction(-2, 2), "k", minimum=0), "-1", ">= 0")):
        assert_refuses(call, arg="k", value=shown, allowed=allowed)
    assert v.check_int(-(10**9), "k", maximum=0) == -(10**9)
    assert v.check_int(10**9, "k", minimum=0) == 10**9


def test_check_N():
    assert v.check_N(2) == 2 and v.check_N("1e100") == 10**100
    assert v.check_N(np.int64(5)) == 5 and type(v.check_N(np.int64(5))) is int
    for call, name, shown, allowed in (
            (lambda: v.check_N(1), "N", "1", ">= 2"), (lambda: v.check_N(1, "M"), "M", "1", ">= 2"),
            (lambda: v.check_N(4, minimum=5), "N", "4", ">= 5"),
            (lambda: v.check_N("2.5"), "N", "'2.5'", "an integer")):
        assert_refuses(call, arg=name, value=shown, allowed=allowed)
    assert v.check_N(1, minimum=1) == 1
    assert_refuses(v.check_N, True, exc=TypeError, arg="N", value="bool True",
                   allowed="an integer")
    assert_refuses(v.check_N, 2.0, exc=TypeError, arg="N", value="float 2.0",
                   allowed=NOT_EXACT_FLOAT)


def test_check_dps():
    assert v.check_dps(1) == 1 and v.check_dps(5000) == 5000 and v.check_dps(np.int16(30)) == 30
    assert v.check_dps(v.MAX_DPS) == v.MAX_DPS
    assert type(v.check_dps(np.int16(30))) is int
    assert v.check_dps(None, allow_none=True) is None
    assert v.check_dps(40, allow_none=True) == 40
    for bad in (0, -1, 5001, 10**6):
        msg = assert_refuses(v.check_dps, bad, arg="dps", value=f" {bad} ",
                             allowed=[DPS_RANGE, "symhx.validation.MAX_DPS"])
        assert "None" not in msg
    assert_refuses(v.check_dps, 0, allow_none=True, arg="dps", value=" 0 ",
                   allowed=[f"{DPS_RANGE} (or None for float64)", "symhx.validation.MAX_DPS"])
    for bad, shown in ((None, "NoneType None"), (True, "bool True"), (np.True_, "bool np.True_"),
                       (2.5, "float 2.5"), ("30", "str '30'"),
                       (Fraction(30), "Fraction Fraction(30, 1)")):
        msg = assert_refuses(v.check_dps, bad, exc=TypeError, arg="dps", value=shown,
                             allowed=DPS_RANGE)
        assert "None for float64" not in msg
    assert_refuses(v.check_dps, False, allow_none=True, exc=TypeError, arg="dps",
                   value="bool False", allowed=f"{DPS_RANGE} (or None for float64)")
    assert_refuses(v.check_dps, 2.0, allow_none=True, name="prec", exc=TypeError, arg="prec",
                   value="float 2.0", allowed=f"{DPS_RANGE} (or None for float64)")
    msg = assert_refuses(v.check_dps, 0, name="prec", arg="prec", value=" 0 ",
                         allowed=[DPS_RANGE, "symhx.validation.MAX_DPS"])
    assert "dps" not in msg.replace("MAX_DPS", "")


def test_check_seed():
    assert v.check_seed(None) is None
    assert v.check_seed(0) == 0 and v.check_seed(np.int64(12)) == 12 and v.check_seed("7") == 7
    assert_refuses(v.check_seed, -1, arg="seed", value="-1", allowed=">= 0")
    assert_refuses(v.check_seed, -1, "rng", arg="rng", value="-1", allowed=">= 0")
    assert_refuses(v.check_seed, True, exc=TypeError, arg="seed", value="bool True",
                   allowed="an integer")
    assert_refuses(v.check_seed, 1.0, exc=TypeError, arg="seed", value="float 1.0",
                   allowed=NOT_EXACT_FLOAT)


# --------------------------------------------------------------------------- check_choice
class _EqRaises:
    def __eq__(self, other):
        raise RuntimeError("no comparison")

    __hash__ = object.__hash__

    def __repr__(self):
        return "E"


def test_check_choice():
    opts = ["a", "b"]
    assert v.check_choice("b", "mode", opts) == "b"
    got = v.check_choice(np.int64(2), "k", [1, 2])
    assert got == 2 and type(got) is int  # the option itself is returned
    assert v.check_choice("b", "mode", (c for c in "ab")) == "b"  # any iterable, read once
    assert v.check_choice(True, "flag", [False, True]) is True
    assert v.check_choice(np.False_, "flag", [False, True]) is False
    assert v.check_choice("a", "mode", [_EqRaises(), "a"]) == "a"  # a raising == is skipped
    assert_refuses(v.check_choice, True, "mode", opts, exc=TypeError, arg="mode",
                   value="bool True", allowed="['a', 'b']")
    assert_refuses(v.check_choice, np.True_, "k", [1, 2], exc=TypeError, arg="k",
                   value="bool np.True_", allowed="[1, 2]")
    for options in (opts, iter(opts)):
        assert_refuses(v.check_choice, "c", "mode", options, arg="mode", value="'c'",
                       allowed="one of ['a', 'b']")
    assert_refuses(v.check_choice, "c", "mode", [_EqRaises()], arg="mode", value="'c'",
                   allowed="one of [E]")


# --------------------------------------------------------------------------- check_array
def test_check_array_values_and_dtypes():
    a = v.check_array([1, 2], "s")
    assert a.dtype == np.float64 and a.tolist() == [1.0, 2.0]
    a = v.check_array(np.array([3, 255], dtype=np.uint8), "s")
    assert a.dtype == np.float64 and a.tolist() == [3.0, 255.0]
    a = v.check_array(2, "s")
    assert a.shape == () and a.dtype == np.float64 and float(a) == 2.0
    x = np.array([0.5, 1.5])
    assert np.shares_memory(v.check_array(x, "s"), x)  # float64 input is not copied
    a = v.check_array(np.array([1.0, 2.0], dtype=np.float32), "s")
    assert a.dtype == np.float64
    assert v.check_array([], "s", allow_empty=True).shape == (0,)
    assert v.check_array(np.zeros((2, 0)), "s", allow_empty=True).shape == (2, 0)
    for empty in ([], np.array([], dtype=object)):
        assert_refuses(v.check_array, empty, "s", arg="s", allowed=["empty", "at least one"])


def test_check_array_object_entries_at_their_exact_value():
    a = v.check_array([Fraction(1, 3), mpmath.mpf((0, 3, -2, 2)), 10**20, Decimal("0.1")],
                      "s")
    assert a.dtype == np.float64 and a.tolist() == [1 / 3, 0.75, 1e20, 0.1]
    a = v.check_array(np.array([[Fraction(1, 2), 2], [3, Fraction(-1, 4)]], dtype=object), "s")
    assert a.shape == (2, 2) and a.tolist() == [[0.5, 2.0], [3.0, -0.25]]
    a = v.check_array(np.array(Fraction(1, 8), dtype=object), "s")
    assert a.shape == () and float(a) == 0.125
    # just below 2**1024 rounds to the largest float; beyond overflows
    top = 2**1024 - 2**970 - 1
    assert v.check_array([top], "s").tolist() == [np.finfo(float).max]
    a = v.check_array([10**400, -(10**400), 1], "s", finite=False)
    assert a.tolist() == [math.inf, -math.inf, 1.0]
    a = v.check_array([Fraction(-(10**400), 3)], "s", finite=False)
    assert a.tolist() == [-math.inf]
    float_range = ["within the float64 range", "1.8e308"]
    msg = assert_refuses(v.check_array, [1, 2**1024 - 2**970], "s", arg="s",
                         value="int " + repr(2**1024 - 2**970)[:57] + "...", allowed=float_range)
    assert "at index (1,)" in msg
    msg = assert_refuses(v.check_array, -(10**400), "s", arg="s",
                         value="int " + repr(-(10**400))[:57] + "...", allowed=float_range)
    assert "index" not in msg


def test_check_array_object_refusals_name_the_index():
    for x, shown, allowed, at in (
            ([1, None], "NoneType None", "a real number", " at index (1,)"),
            (np.array([[Fraction(1), True]], dtype=object), "bool True", "a real number",
             " at index (0, 1)"),
            (np.array(None, dtype=object), "NoneType None", "a real number", ""),
            ([[1, 2], [3, sympy.sqrt(2)]], "Pow sqrt(2)", "a rational or float number",
             " at index (1, 1)"),
            (sympy.pi, "Pi pi", "a rational or float number", ""),
            ([Fraction(1, 2), "0.5"], "str '0.5'", "real numbers", " at index (1,)"),
            (np.array([b"1", 2], dtype=object), "bytes b'1'", "real numbers", " at index (0,)")):
        assert_refuses(v.check_array, x, "s", exc=TypeError, arg="s", value=shown + at,
                       allowed=allowed)
    for finite in (True, False):
        assert_refuses(v.check_array, [Fraction(1), 2, Decimal("NaN")], "s",
                       finite=finite, arg="s", value="Decimal('NaN') at index (2,)",
                       allowed="finite")


def test_check_array_refuses_wrong_kinds():
    for bad, shown in ((True, "bool True"), (np.False_, "bool np.False_"), ("1", "str '1'"),
                       (b"1", "bytes b'1'")):
        assert_refuses(v.check_array, bad, "s", exc=TypeError, arg="s", value=shown,
                       allowed="a real number or an array of them")
    assert_refuses(v.check_array, [[1], [1, 2]], "s", exc=TypeError, arg="s",
                   allowed=["a real number or an array of them",
                            "setting an array element with a sequence."])
    for bad, dtype in (([1 + 1j], "complex128"), ([True, False], "bool"), (["a", "b"], "<U1"),
                       (np.array([1], dtype="m8[s]"), "timedelta64[s]")):
        assert_refuses(v.check_array, bad, "s", exc=TypeError, arg="s",
                       value=f"dtype {dtype}", allowed="real numbers")


def test_check_array_first_bad_index():
    cases = (
        (([1.0, math.inf, math.nan], "s"), {}, "inf at index (1,)", "finite"),
        (([1.0, 2.0, math.nan], "sigma"), {}, "nan at index (2,)", "finite"),
        (([[1.0, math.nan], [math.inf, 2.0]], "s"), {}, "nan at index (0, 1)", "finite"),
        ((-math.inf, "s"), {}, "-inf", "finite"),
        (([math.inf, 1.0, math.nan], "s"), {"finite": False}, "nan at index (2,)", "not be NaN"),
        ((math.nan, "s"), {"finite": False}, "nan", "not be NaN"),
        (([math.nan], "s"), {"finite": False, "positive": True}, "nan at index (0,)",
         "not be NaN"),
        (([1, 0], "s"), {"positive": True}, "0.0 at index (1,)", "> 0"),
        (([1.0, -1.0], "sigma"), {"positive": True}, "-1.0 at index (1,)", "> 0"),
        (([[1, 2], [-2, -1]], "s"), {"positive": True}, "-2.0 at index (1, 0)", "> 0"),
        ((-0.0, "s"), {"positive": True}, "-0.0", "> 0"),
        (([-math.inf], "s"), {"positive": True, "finite": False}, "-inf at index (0,)", "> 0"),
        (([0.0, 1.0, -5e-324], "s"), {"nonnegative": True}, "-5e-324 at index (2,)", ">= 0"),
        (([0.0], "s"), {"positive": True, "nonnegative": True}, "0.0 at index (0,)", "> 0"),
    )
    for args, kwargs, shown, allowed in cases:
        assert_refuses(v.check_array, *args, arg=args[1], value=shown, allowed=allowed,
                       **kwargs)
    assert v.check_array([math.inf, -math.inf], "s", finite=False).tolist() == [math.inf, -math.inf]
    assert v.check_array([5e-324, 1.0], "s", positive=True).tolist() == [5e-324, 1.0]
    assert v.check_array([0.0, -0.0, 2.0], "s", nonnegative=True).tolist() == [0.0, -0.0, 2.0]
    assert v.check_array([-1.0], "s").tolist() == [-1.0]


# ------------------------------------------------------------------ short_value
@pytest.mark.parametrize("fr", [Fraction(1, 3), Fraction(10**400, 3), Fraction(-7, 2**1100),
                                Fraction(12345678), Fraction(1, 10**500), Fraction(2, 7)])
def test_short_value_is_five_significant_digits_of_the_exact_value(fr):
    """Read back by Python's exact Fraction parser: within half a unit of the 5th digit, and no
    more than 5 significant digits written (error messages stay short for huge values)."""
    s = v.short_value(fr)
    back = Fraction(s)
    assert abs(back / fr - 1) <= Fraction(5, 10**5)
    mantissa = s.lstrip("-").split("e")[0].replace(".", "").lstrip("0")
    assert 1 <= len(mantissa.rstrip("0")) <= 5
