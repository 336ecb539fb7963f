"""The CLI's shared output helpers (:mod:`symhx.commands._common`): strict JSON, exact integers of
any size, 17-digit CSV cells."""

from __future__ import annotations

import json
from decimal import Decimal
from fractions import Fraction

import mpmath
import pytest

from symhx.commands._common import csv_num, dump_json, int_show, int_str, jsonable


def test_dump_json_is_strict_json():
    text = dump_json({"a": float("nan"), "b": float("inf"), "c": mpmath.mpf("-inf"),
                      "d": [mpmath.mpf(1) / 3, Fraction(2, 3), 2**80]})
    data = json.loads(text, parse_constant=lambda c: pytest.fail(f"non-strict JSON {c}"))
    assert data == {"a": None, "b": "inf", "c": "-inf",
                    "d": [data["d"][0], "2/3", str(2**80)]}
    assert jsonable(mpmath.mpf("nan")) is None


def test_int_str_prints_every_digit_beyond_the_int_str_limit_and_int_show_abbreviates():
    n = 7**20000  # 16902 digits, beyond Python's default 4300-digit str limit
    s = int_str(n)
    # read back by Decimal, which has no digit limit (independent of int_str)
    assert len(s) == 16902 and int(Decimal(s)) == n
    assert int_show(10**100) == "10**100"
    assert int_show(2**300).endswith("(exact integer, 91 digits)")
    # in full up to MAX_INT_DIGITS_SHOWN digits, abbreviated from one digit more
    from symhx.commands._common import MAX_INT_DIGITS_SHOWN as D

    assert int_show(10**D - 1) == "9" * D and int_show(-(10**D - 1)) == "-" + "9" * D
    assert int_show(10**D) == f"10**{D}" and int_show(-(10**D)) == f"-10**{D}"


def test_csv_num_round_trips_float64():
    for x in (Fraction(1, 3), mpmath.mpf(2) ** -1000 / 3, 10**100, Fraction(10**40 + 1, 7)):
        cell = csv_num(x)
        assert len(str(cell)) <= 26
        with mpmath.workdps(40):
            v = mpmath.mpf(x.numerator) / x.denominator if isinstance(x, (int, Fraction)) else x
            assert float(cell) == float(v)


@pytest.mark.parametrize("digits", [8, 30])
def test_mpstr_switches_to_an_exponent_below_1e_5_at_any_number_of_digits(digits):
    from symhx._mpctx import mp
    from symhx.commands._common import mpstr

    ctx = mp()
    with ctx.workdps(50):
        small, fixed = ctx.mpf("1.5e-7"), ctx.mpf("0.00015")
    assert mpstr(small, digits) == "1.5" + "0" * (digits - 2) + "e-7"
    assert mpstr(fixed, digits).startswith("0.00015")
    # a Fraction: the decimal and the exact value
    assert mpstr(Fraction(1, 8), digits).endswith("(exact 1/8)")


def test_jsonable_rounds_numpy_scalars_to_the_digits():
    import numpy as np

    assert jsonable(np.float64(1) / 3, 5) == jsonable(1 / 3, 5) == 0.33333
    assert jsonable(np.int64(7), 5) == 7
    # float32 is no float subclass (float64 is): converted through .item(), then rounded
    assert jsonable(np.float32(1) / 3, 3) == 0.333
