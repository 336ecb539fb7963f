"""symhx.validation, function by function: exact values, exact messages, every branch and bound.

Reference values are exact rationals written here (binary values of floats spelled out as
``m / 2**e``); messages are matched whole (``^...$``) so that a changed word or number fails.
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

MAXD = v.MAX_DECIMAL_EXPONENT
MAXB = v.MAX_BINARY_EXPONENT


def raises(exc, message, f, *args, **kwargs):
    """``f(*args, **kwargs)`` raises exactly ``exc`` (not a subclass) with exactly ``message``."""
    with pytest.raises(Exception) as info:
        f(*args, **kwargs)
    assert type(info.value) is exc, (type(info.value), str(info.value))
    assert str(info.value) == message


def raises_re(exc, pattern, f, *args, **kwargs):
    with pytest.raises(Exception) as info:
        f(*args, **kwargs)
    assert type(info.value) is exc, (type(info.value), str(info.value))
    assert re.fullmatch(pattern, str(info.value)), str(info.value)


def test_constants():
    assert (v.DEFAULT_DPS, v.MAX_DPS, v.DEFAULT_SPACE) == (50, 5000, "simple")
    assert (MAXD, MAXB) == (100_000, 3_400_000)


# --------------------------------------------------------------------------- _show (via errors)
class _Repr:
    def __init__(self, n):
        self.n = n

    def __repr__(self):
        return "a" * self.n


class _BadRepr:
    def __repr__(self):
        raise RuntimeError("no repr")


def test_a_value_whose_repr_raises_is_still_shown():
    raises_re(TypeError, r"p must be a real number, got _BadRepr "
              r"<[\w.]*_BadRepr object at 0x[0-9a-f]+>", v.to_rational, _BadRepr())


@pytest.mark.parametrize("n, shown", [(60, "a" * 60), (61, "a" * 57 + "..."),
                                      (100, "a" * 57 + "...")])
def test_long_reprs_are_cut_at_60_characters(n, shown):
    raises(TypeError, f"p must be a real number, got _Repr {shown}", v.to_rational, _Repr(n))


# --------------------------------------------------------------------------- strings
@pytest.mark.parametrize("text, exact", [
    ("0.02", Fraction(1, 50)), ("2e-2", Fraction(1, 50)), ("2E-2", Fraction(1, 50)),
    (".5", Fraction(1, 2)), ("5.", Fraction(5)), ("-1.5e+1", Fraction(-15)), ("+7", Fraction(7)),
    ("\t 3 \n", Fraction(3)), ("1_000.5", Fraction(2001, 2)), ("1_0e1_0", Fraction(10**11)),
    ("1/50", Fraction(1, 50)), (" -3 / +6 ", Fraction(-1, 2)), ("+3/-6", Fraction(-1, 2)),
    ("1_0/2_0", Fraction(1, 2)), ("0/7", Fraction(0)),
    ("10**3", Fraction(1000)), (" 2 ** 10 ", Fraction(1024)), ("0**0", Fraction(1)),
    ("0**5", Fraction(0)), ("1**5", Fraction(1)), ("1**1000000000000", Fraction(1)),
    ("7**0", Fraction(1)),
])
def test_strings_are_exact(text, exact):
    got = v.to_rational(text)
    assert type(got) is Fraction and got == exact


@pytest.mark.parametrize("text", ["1_000", "1__0", "_1", "1_", "1._5", "1_.5", "1e_5", "1_e5",
                                  "0.000_1", "1_0e1_0", "-_1", "1e-_3", "12_3.4_5e6_7"])
def test_underscores_follow_pythons_rule(text):
    # the reference is Python's own parser: an underscore only between two digits
    try:
        ref = Fraction(text)
    except ValueError:
        raises(ValueError, f"p must be a number; an underscore may only separate two digits, "
               f"got {text!r}", v.to_rational, text)
    else:
        assert v.to_rational(text) == ref
    if "." not in text and "e" not in text:
        try:
            iref = int(text)
        except ValueError:
            raises(ValueError, f"n must be an integer; an underscore may only separate two "
                   f"digits, got {text!r}", v.check_int, text, "n")
        else:
            assert v.check_int(text, "n") == iref
    for form in (f"{text}/3", f"3**{text}"):     # the same rule inside ratios and powers
        if "." in text or "e" in text or "-" in text:
            continue
        ok = "__" not in text and not text.startswith("_") and not text.endswith("_")
        if ok:
            v.to_rational(form)
        else:
            with pytest.raises(ValueError, match="an underscore may only separate two digits"):
                v.to_rational(form)


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
    # no larger input here: a mutant that skips the bound must not exhaust the machine's memory
    for text in (f"1e{MAXD + 1}", f"100e{MAXD - 1}", f"1e-{MAXD + 1}", f"-1e{MAXD + 1}",
                 f"10**{MAXD + 1}", "2**332197", "3**1000000", "9**1000000", "10**200000",
                 "3**1000000000"):
        raises(ValueError, f"sigma={text!r}: decimal exponent beyond +-{MAXD} "
               f"(symhx.validation.MAX_DECIMAL_EXPONENT)", v.to_rational, text, "sigma")


def test_the_same_cap_for_decimal_objects():
    assert v.to_rational(Decimal(f"1e{MAXD}")) == 10**MAXD
    assert v.to_rational(Decimal(f"1e-{MAXD}")) == Fraction(1, 10**MAXD)
    assert v.to_rational(Decimal("0e999999999")) == 0
    for d in (Decimal(f"1e{MAXD + 1}"), Decimal(f"-1e-{MAXD + 1}"), Decimal("1e999999999")):
        raises(ValueError, f"p={d!r}: decimal exponent beyond +-{MAXD} "
               f"(symhx.validation.MAX_DECIMAL_EXPONENT)", v.to_rational, d)


@pytest.mark.parametrize("text", ["abc", "", "  ", "1/2/3", "1e", "e5", "nan", "inf", "0x10",
                                  "1 000", "1/2.5", "2**-1", "-2**2", "1.5**2", "**2", "--1"])
def test_strings_that_are_not_numbers(text):
    raises(ValueError, f"q must be a number such as 0.02, 2e-2, 1/50 or 10**100, got {text!r}",
           v.to_rational, text, "q")
    raises(ValueError, f"k must be an integer such as 7, 10**100 or '1e100', got {text!r}",
           v.check_int, text, "k")


def test_division_by_zero():
    raises(ValueError, "q must be a finite number, got '1/0' (division by zero)",
           v.to_rational, "1/0", "q")
    raises(ValueError, "q must be a finite number, got ' 0 / -0 ' (division by zero)",
           v.to_rational, " 0 / -0 ", "q")
    raises(ValueError, "k must be an integer, got '1/0' (division by zero)", v.check_int, "1/0",
           "k")


def test_integer_arguments_say_integer():
    # the old wording asked an integer argument for "a number such as 0.02, 2e-2, 1/50"
    raises(ValueError, "random_state must be an integer such as 7, 10**100 or '1e100', "
           "got 'seed'", v.check_int, "seed", "random_state")
    raises(ValueError, "seed must be an integer such as 7, 10**100 or '1e100', got 'x'",
           v.check_seed, "x")
    raises(ValueError, "N must be an integer such as 7, 10**100 or '1e100', got 'ten'",
           v.check_N, "ten")


# --------------------------------------------------------------------------- to_rational by type
@pytest.mark.parametrize("bad", [True, False, np.True_, np.bool_(False)])
def test_bools_are_not_numbers(bad):
    raises(TypeError, f"w must be a real number, got bool {bad!r}", v.to_rational, bad, "w")


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
    raises(ValueError, f"x must be finite, got {shown}", v.to_rational, bad, "x")


def test_decimals():
    assert v.to_rational(Decimal("0.25")) == Fraction(1, 4)
    assert v.to_rational(Decimal("-1.5E+3")) == -1500
    for bad in (Decimal("NaN"), Decimal("Infinity"), Decimal("-Infinity"), Decimal("sNaN")):
        raises(ValueError, f"x must be finite, got {bad!r}", v.to_rational, bad, "x")


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
        raises(ValueError, f"x must be finite, got {bad!r}", v.to_rational, bad, "x")


def test_mpf_binary_exponent_cap_at_its_exact_boundary():
    # (sign, man, exp, bc): |x| lies in [2**(exp + bc - 1), 2**(exp + bc))
    assert v.to_rational(mpmath.mpf((0, 1, MAXB - 1, 1))) == 2**(MAXB - 1)
    assert v.to_rational(mpmath.mpf((1, 3, MAXB - 2, 2))) == -3 * 2**(MAXB - 2)
    assert v.to_rational(mpmath.mpf((0, 1, -MAXB - 1, 1))) == Fraction(1, 2**(MAXB + 1))
    assert v.to_rational(mpmath.mpf((0, 3, -MAXB - 2, 2))) == Fraction(3, 2**(MAXB + 2))
    msg = (r"x=%s is beyond the exact-conversion range 2\*\*\+-3400000 "
           r"\(symhx\.validation\.MAX_BINARY_EXPONENT\)")
    with mpmath.workdps(30):
        big = mpmath.mpf("1.234567e1023500")  # log2 = 3399996.2: inside
        tiny = mpmath.mpf("1.234567e-2000000")
        assert v.to_rational(big) == v.mpf_to_fraction(big)
        for x in (mpmath.mpf((0, 1, MAXB, 1)), mpmath.mpf((0, 3, MAXB - 1, 2)),
                  mpmath.mpf((1, 1, -MAXB - 2, 1)), mpmath.mpf((0, 3, -MAXB - 3, 2))):
            raises_re(ValueError, msg % r"-?\d\.\d{4}e[+-]?\d+", v.to_rational, x, "x")
        raises_re(ValueError, msg % r"1\.2346e-2000000", v.to_rational, tiny, "x")
        raises_re(ValueError, msg % r"1\.2346e\+1023600",
                  v.to_rational, mpmath.mpf("1.234567e1023600"), "x")


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
    raises_re(ValueError, r"x=1\.23456\d*E-2000000 is beyond the exact-conversion range "
              r"2\*\*\+-3400000 \(symhx\.validation\.MAX_BINARY_EXPONENT\)",
              v.to_rational, sympy.Float("1.234567e-2000000", 30), "x")
    for bad, shown in ((sympy.oo, "oo"), (-sympy.oo, "-oo"), (sympy.zoo, "zoo"),
                       (sympy.nan, "nan")):
        raises(ValueError, f"x must be finite, got {shown}", v.to_rational, bad, "x")
    for bad, shown in ((sympy.I, "I"), (1 + sympy.I, "1 + I"), (sympy.Symbol("t"), "t"),
                       (sympy.Matrix([[1]]), "Matrix([[1]])"), (sympy.sqrt(-2), "sqrt(2)*I"),
                       (sympy.Symbol("r", rational=True), "r")):
        raises(TypeError, f"x must be a finite real number, got sympy object {shown}",
               v.to_rational, bad, "x")


def test_numpy_scalars_and_0d_arrays():
    assert v.to_rational(np.int8(-3)) == -3
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
    raises(ValueError, "x must be finite, got np.float32(inf)", v.to_rational, np.float32("inf"),
           "x")
    raises(ValueError, "x must be finite, got np.float16(nan)", v.to_rational, np.float16("nan"),
           "x")
    assert v.to_rational(np.array(0.25)) == Fraction(1, 4)
    assert v.to_rational(np.array(-7)) == -7
    assert v.to_rational(np.array(Fraction(1, 3), dtype=object)) == Fraction(1, 3)
    assert v.to_rational(np.array("2/3")) == Fraction(2, 3)
    raises(TypeError, "x must be a real number, got bool np.True_", v.to_rational, np.array(True),
           "x")
    raises(TypeError, "x must be a real number, got ndarray array([0.5])", v.to_rational,
           np.array([0.5]), "x")


@pytest.mark.parametrize("bad, shown", [
    (1j, "complex 1j"), (np.complex128(1), "complex128 np.complex128(1+0j)"),
    (mpmath.mpc(1, 1), "mpc mpc(real='1.0', imag='1.0')"), (None, "NoneType None"),
    ([1], "list [1]"), (b"1", "bytes b'1'"), (object, "type <class 'object'>"),
])
def test_non_numbers(bad, shown):
    raises(TypeError, f"y must be a real number, got {shown}", v.to_rational, bad, "y")


def test_default_name_and_alias():
    raises(TypeError, "p must be a real number, got NoneType None", v.to_rational, None)
    raises(TypeError, "p must be a real number, got NoneType None", v.as_fraction, None)
    raises(TypeError, "q must be a real number, got NoneType None", v.as_fraction, None, "q")
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
                       (Fraction(0), "Fraction(0, 1)"), (sympy.sqrt(2) - 2, "-2 + sqrt(2)"),
                       (-tiny, repr(-tiny))):
        raises(ValueError, f"a must be > 0, got {shown}", v.check_p, bad, "a")
    raises(ValueError, "p must be > 0, got 0", v.check_p, 0)
    raises(TypeError, "p must be a real number, got bool True", v.check_p, True)
    raises(TypeError, "a must be a real number, got bool True", v.check_p, True, "a")
    # zeros that are not simplified: an exact 0 is refused as <= 0; a zero that cancels has no
    # decidable sign (plain evalf gives 0.e-163, which is > 0: pi - pi used to be accepted)
    raises(ValueError, "a must be > 0, got 0*sqrt(2)", v.check_p,
           sympy.Mul(0, sympy.sqrt(2), evaluate=False), "a")
    for zero in (sympy.Add(sympy.pi, -sympy.pi, evaluate=False),
                 sympy.Add(sympy.sqrt(2), -sympy.sqrt(2), evaluate=False),
                 sympy.cos(1)**2 + sympy.sin(1)**2 - 1):
        raises(ValueError, f"a must be > 0, got {zero!r} (its sign cannot be decided numerically: "
               "simplify it)", v.check_p, zero, "a")
    # sqrt(2) - floor(sqrt(2) * 10**60) / 10**60: positive, 60 digits of cancellation
    s = sympy.sqrt(2) - sympy.Rational(int(sympy.sqrt(2 * 10**120)), 10**60)
    assert v.check_p(s)[0] is None
    raises(ValueError, f"a must be > 0, got {-s!r}", v.check_p, -s, "a")


def test_check_real_bounds_at_their_exact_values():
    assert v.check_real("0.5", "x") == Fraction(1, 2)
    assert type(v.check_real(3, "x")) is Fraction
    # closed bounds include the bound itself, exactly (float bounds at their binary value)
    assert v.check_real(0, "x", low=0) == 0
    assert v.check_real("1", "x", high=1) == 1
    assert v.check_real(0.1, "x", low=0.1, high=0.1) == Fraction(3602879701896397, 2**55)
    assert v.check_real("0.1", "x", high=0.1) == Fraction(1, 10)  # 1/10 < the float 0.1
    raises(ValueError, "x must be >= 0.1, got '0.1'", v.check_real, "0.1", "x", low=0.1)
    raises(ValueError, "x must be >= 0, got -1e-300", v.check_real, -1e-300, "x", low=0)
    raises(ValueError, "x must be > 0, got 0", v.check_real, 0, "x", low=0, low_open=True)
    raises(ValueError, "x must be > 0.5, got '1/2'", v.check_real, "1/2", "x", low=0.5,
           low_open=True)
    assert v.check_real("0.5000001", "x", low=0.5, low_open=True) == Fraction(5000001, 10**7)
    raises(ValueError, "x must be <= 1, got '1.0000001'", v.check_real, "1.0000001", "x", high=1)
    raises(ValueError, "x must be < 1, got 1", v.check_real, 1, "x", high=1, high_open=True)
    assert v.check_real("0.9999999", "x", high=1, high_open=True) == Fraction(9999999, 10**7)
    assert v.check_real(2, "x", low=1, high=3, low_open=True, high_open=True) == 2
    raises(ValueError, "x must be > 1, got 1", v.check_real, 1, "x", low=1, high=3, low_open=True)
    raises(ValueError, "x must be <= 3, got 4", v.check_real, 4, "x", low=1, high=3)
    assert v.check_real(-5, "x", high=3) == -5 and v.check_real(10**50, "x", low=3) == 10**50
    raises(TypeError, "x must be a rational or float number, got Pow sqrt(2)", v.check_real,
           sympy.sqrt(2), "x")
    raises(TypeError, "x must be a real number, got NoneType None", v.check_real, None, "x")


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
        raises(TypeError, f"k must be an integer, got bool {bad!r}", v.check_int, bad, "k")
    for bad, shown in (("2.5", "'2.5'"), ("1/3", "'1/3'"), (Fraction(5, 2), "Fraction(5, 2)"),
                       (sympy.Rational(1, 2), "1/2"), (sympy.Rational(-7, 3), "-7/3")):
        raises(ValueError, f"k must be an integer, got {shown}", v.check_int, bad, "k")
    for bad, shown in ((2.0, "2.0"), (1e100, "1e+100"), (np.float32(2), "np.float32(2.0)"),
                       (np.float64(3), "np.float64(3.0)")):
        raises(TypeError, f"k must be an int, got float {shown} (floats above 2**53 are not exact: "
               "write e.g. 10**100 or the string '1e100')", v.check_int, bad, "k")
    for bad, shown in ((None, "NoneType None"), (mpmath.mpf(2), "mpf mpf('2.0')"),
                       (Decimal(2), "Decimal Decimal('2')"), (sympy.sqrt(2), "Pow sqrt(2)"),
                       (sympy.Float(2), "Float 2.00000000000000"), (1j, "complex 1j"),
                       (np.array(2.0), "ndarray array(2.)"), ([2], "list [2]"),
                       (sympy.Matrix([[1]]), "MutableDenseMatrix Matrix([[1]])"),
                       (sympy.Symbol("r", rational=True), "Symbol r")):
        raises(TypeError, f"k must be an integer, got {shown}", v.check_int, bad, "k")


def test_check_int_bounds_at_their_exact_values():
    assert v.check_int(3, "k", minimum=3) == 3 and v.check_int(5, "k", maximum=5) == 5
    assert v.check_int(4, "k", minimum=3, maximum=5) == 4
    raises(ValueError, "k must be >= 3, got 2", v.check_int, 2, "k", minimum=3)
    raises(ValueError, "k must be <= 5, got 6", v.check_int, 6, "k", maximum=5)
    raises(ValueError, "k must be <= 5, got 10", v.check_int, "1e1", "k", minimum=3, maximum=5)
    raises(ValueError, "k must be >= 0, got -1", v.check_int, Fraction(-2, 2), "k", minimum=0)
    assert v.check_int(-(10**9), "k", maximum=0) == -(10**9)
    assert v.check_int(10**9, "k", minimum=0) == 10**9


def test_check_N():
    assert v.check_N(2) == 2 and v.check_N("1e100") == 10**100
    raises(ValueError, "N must be >= 2, got 1", v.check_N, 1)
    raises(ValueError, "M must be >= 2, got 1", v.check_N, 1, "M")
    assert v.check_N(1, minimum=1) == 1
    raises(ValueError, "N must be >= 5, got 4", v.check_N, 4, minimum=5)
    raises(TypeError, "N must be an integer, got bool True", v.check_N, True)


def test_check_dps():
    assert v.check_dps(1) == 1 and v.check_dps(5000) == 5000 and v.check_dps(np.int16(30)) == 30
    assert type(v.check_dps(np.int16(30))) is int
    assert v.check_dps(None, allow_none=True) is None
    assert v.check_dps(40, allow_none=True) == 40
    base = "dps must be an int between 1 and 5000"
    for bad in (0, -1, 5001, 10**6):
        raises(ValueError, f"{base}, got {bad} (the cap is symhx.validation.MAX_DPS)",
               v.check_dps, bad)
    raises(ValueError, f"{base} (or None for float64), got 0 (the cap is symhx.validation.MAX_DPS)",
           v.check_dps, 0, allow_none=True)
    for bad, shown in ((None, "NoneType None"), (True, "bool True"), (np.True_, "bool np.True_"),
                       (2.5, "float 2.5"), ("30", "str '30'"),
                       (Fraction(30), "Fraction Fraction(30, 1)")):
        raises(TypeError, f"{base}, got {shown}", v.check_dps, bad)
    raises(TypeError, f"{base} (or None for float64), got bool False", v.check_dps, False,
           allow_none=True)
    raises(TypeError, "prec must be an int between 1 and 5000 (or None for float64), got float 2.0",
           v.check_dps, 2.0, allow_none=True, name="prec")
    raises(ValueError, "prec must be an int between 1 and 5000, got 0 (the cap is "
           "symhx.validation.MAX_DPS)", v.check_dps, 0, name="prec")


def test_check_seed():
    assert v.check_seed(None) is None
    assert v.check_seed(0) == 0 and v.check_seed(np.int64(12)) == 12 and v.check_seed("7") == 7
    raises(ValueError, "seed must be >= 0, got -1", v.check_seed, -1)
    raises(ValueError, "rng must be >= 0, got -1", v.check_seed, -1, "rng")
    raises(TypeError, "seed must be an integer, got bool True", v.check_seed, True)
    raises(TypeError, "seed must be an int, got float 1.0 (floats above 2**53 are not exact: "
           "write e.g. 10**100 or the string '1e100')", v.check_seed, 1.0)


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
    raises(TypeError, "mode must be one of ['a', 'b'], got bool True", v.check_choice, True,
           "mode", opts)
    raises(TypeError, "k must be one of [1, 2], got bool np.True_", v.check_choice, np.True_, "k",
           [1, 2])
    raises(ValueError, "mode must be one of ['a', 'b'], got 'c'", v.check_choice, "c", "mode", opts)
    raises(ValueError, "mode must be one of ['a', 'b'], got 'c'", v.check_choice, "c", "mode",
           iter(opts))
    raises(ValueError, "mode must be one of [E], got 'c'", v.check_choice, "c", "mode",
           [_EqRaises()])


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
    raises(ValueError, "s is empty: give at least one value", v.check_array, [], "s")
    raises(ValueError, "s is empty: give at least one value", v.check_array,
           np.array([], dtype=object), "s")


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
    raises(ValueError, "s must be within the float64 range (magnitude below 1.8e308), got int "
           + repr(2**1024 - 2**970)[:57] + "... at index (1,)",
           v.check_array, [1, 2**1024 - 2**970], "s")
    raises(ValueError, "s must be within the float64 range (magnitude below 1.8e308), got int "
           + repr(-(10**400))[:57] + "...", v.check_array, -(10**400), "s")


def test_check_array_object_refusals_name_the_index():
    raises(TypeError, "s must be a real number, got NoneType None at index (1,)", v.check_array,
           [1, None], "s")
    raises(TypeError, "s must be a real number, got bool True at index (0, 1)", v.check_array,
           np.array([[Fraction(1), True]], dtype=object), "s")
    raises(TypeError, "s must be a real number, got NoneType None", v.check_array,
           np.array(None, dtype=object), "s")
    raises(TypeError, "s must be a rational or float number, got Pow sqrt(2) at index (1, 1)",
           v.check_array, [[1, 2], [3, sympy.sqrt(2)]], "s")
    raises(TypeError, "s must be a rational or float number, got Pi pi", v.check_array, sympy.pi,
           "s")
    raises(TypeError, "s must hold real numbers, got str '0.5' at index (1,)", v.check_array,
           [Fraction(1, 2), "0.5"], "s")
    raises(TypeError, "s must hold real numbers, got bytes b'1' at index (0,)", v.check_array,
           np.array([b"1", 2], dtype=object), "s")
    raises(ValueError, "s must be finite, got Decimal('NaN') at index (2,)", v.check_array,
           [Fraction(1), 2, Decimal("NaN")], "s")
    raises(ValueError, "s must be finite, got Decimal('NaN') at index (2,)", v.check_array,
           [Fraction(1), 2, Decimal("NaN")], "s", finite=False)


def test_check_array_refuses_wrong_kinds():
    for bad, shown in ((True, "bool True"), (np.False_, "bool np.False_"), ("1", "str '1'"),
                       (b"1", "bytes b'1'")):
        raises(TypeError, f"s must be a real number or an array of them, got {shown}",
               v.check_array, bad, "s")
    raises_re(TypeError, r"s must be a real number or an array of them \(setting an array "
              r"element with a sequence\..*\)", v.check_array, [[1], [1, 2]], "s")
    for bad, dtype in (([1 + 1j], "complex128"), ([True, False], "bool"), (["a", "b"], "<U1"),
                       (np.array([1], dtype="m8[s]"), "timedelta64[s]")):
        raises(TypeError, f"s must hold real numbers, got an array of dtype {dtype}",
               v.check_array, bad, "s")


def test_check_array_first_bad_index():
    raises(ValueError, "s must be finite, got inf at index (1,)", v.check_array,
           [1.0, math.inf, math.nan], "s")
    raises(ValueError, "s must be finite, got nan at index (0, 1)", v.check_array,
           [[1.0, math.nan], [math.inf, 2.0]], "s")
    raises(ValueError, "s must be finite, got -inf", v.check_array, -math.inf, "s")
    assert v.check_array([math.inf, -math.inf], "s", finite=False).tolist() == [math.inf, -math.inf]
    raises(ValueError, "s must not be NaN, got nan at index (2,)", v.check_array,
           [math.inf, 1.0, math.nan], "s", finite=False)
    raises(ValueError, "s must not be NaN, got nan", v.check_array, math.nan, "s", finite=False)
    raises(ValueError, "s must not be NaN, got nan at index (0,)", v.check_array, [math.nan], "s",
           finite=False, positive=True)
    assert v.check_array([5e-324, 1.0], "s", positive=True).tolist() == [5e-324, 1.0]
    raises(ValueError, "s must be > 0, got 0.0 at index (1,)", v.check_array, [1, 0], "s",
           positive=True)
    raises(ValueError, "s must be > 0, got -2.0 at index (1, 0)", v.check_array,
           [[1, 2], [-2, -1]], "s", positive=True)
    raises(ValueError, "s must be > 0, got -0.0", v.check_array, -0.0, "s", positive=True)
    raises(ValueError, "s must be > 0, got -inf at index (0,)", v.check_array, [-math.inf], "s",
           positive=True, finite=False)
    assert v.check_array([0.0, -0.0, 2.0], "s", nonnegative=True).tolist() == [0.0, -0.0, 2.0]
    raises(ValueError, "s must be >= 0, got -5e-324 at index (2,)", v.check_array,
           [0.0, 1.0, -5e-324], "s", nonnegative=True)
    raises(ValueError, "s must be > 0, got 0.0 at index (0,)", v.check_array, [0.0], "s",
           positive=True, nonnegative=True)
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
