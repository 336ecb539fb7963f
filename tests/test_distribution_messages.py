"""Refusals of :mod:`symhx.distribution` name the documented constant by its qualified name,
say what is allowed for the kind of arithmetic at hand, and show huge values briefly; the
row limits of ``table()`` are inclusive."""

from __future__ import annotations

import re
from fractions import Fraction

import pytest

import symhx
import symhx.distribution as sd
from tests.harness.errors import assert_refuses


def _table_refusal(N, p, dps):
    d = symhx.distribution_of(N, p, dps=dps)
    return assert_refuses(d.table, arg="N", value=f"N={N}" if N < 10**15 else None,
                          allowed="table()")


def test_exact_table_refusal_names_its_limit_and_the_float_route():
    N = sd.MAX_EXACT_TABLE_N + 1
    msg = _table_refusal(N, "1/2", 30)
    assert f"limited to N <= {sd.MAX_EXACT_TABLE_N} " in msg
    assert "(symhx.distribution.MAX_EXACT_TABLE_N, a work limit of exact rows); " in msg
    assert msg.endswith("(an array of k works), or a float p")


def test_mpmath_table_refusal_names_its_limit_without_the_exact_advice():
    N = sd.MAX_TABLE_N + 1
    msg = _table_refusal(N, 0.5, 30)
    assert f"limited to N <= {sd.MAX_TABLE_N} " in msg
    assert "(symhx.distribution.MAX_TABLE_N, a work limit); " in msg
    assert msg.endswith("(an array of k works)")


def test_float_table_refusal_names_float_n_limit():
    N = sd.FLOAT_N_LIMIT + 1
    msg = _table_refusal(N, 0.5, None)
    assert "(symhx.distribution.FLOAT_N_LIMIT, a work limit); " in msg
    assert msg.endswith("(an array of k works)")


@pytest.mark.parametrize(("name", "p", "dps"), [("MAX_TABLE_N", 0.5, 30),
                                                ("MAX_EXACT_TABLE_N", "1/2", 30),
                                                ("FLOAT_N_LIMIT", 0.5, None)])
def test_table_row_limit_is_inclusive(monkeypatch, name, p, dps):
    monkeypatch.setattr(sd, name, 5)  # "raise it here": the limits are read at call time
    rows = symhx.distribution_of(5, p, dps=dps).table()
    assert [k for k, _ in rows] == [1, 2, 3, 4, 5]
    assert_refuses(symhx.distribution_of(6, p, dps=dps).table, arg="N", value="N=6",
                   allowed=f"symhx.distribution.{name}")


def test_huge_n_in_a_message_is_a_power_of_ten_up_to_10000_bits_then_five_digits():
    # 2**9999 has 10000 bits (3010 digits, under Python's 4300-digit str limit): ~10**3009;
    # beyond 10000 bits the value is shown in 5 significant digits
    msg = _table_refusal(2**9999, 0.5, None)
    assert "got N=~10**3009." in msg
    msg = _table_refusal(2**10000, 0.5, None)
    assert re.search(r"got N=1\.99\d*e\+3010\. ", msg), msg
    msg = _table_refusal(10**3000, 0.5, None)
    assert "got N=10**3000." in msg


def test_huge_p_in_a_message_is_shown_in_five_digits():
    # the exact-work refusal of the simple space shows p through this helper
    assert sd._p_show(Fraction(1, 3)) == "1/3"
    assert sd._p_show(Fraction(1, 7**50)) == str(Fraction(1, 7**50))[:40]
    short = sd._p_show(Fraction(1, 2**10000))  # 10001 bits
    assert re.fullmatch(r"5\.0\d*e-3011", short), short
    at_limit = Fraction(1, 2**9999)  # 10000 bits: str() still works (3010 digits)
    assert sd._p_show(at_limit) == str(at_limit)[:40]
