"""Every command prints what ``--dps`` promised (issue 28, item 9): JSON inexact values carry at
most ``dps`` significant digits, bounds are rounded outward so they still enclose; the API and
the CLI agree on which N they accept (item 8)."""

from __future__ import annotations

import json
from decimal import Decimal
from fractions import Fraction

import mpmath
import pytest

import symhx
from symhx.cli import main
from symhx.commands._common import dump_json, jsonable


def run(capsys, *argv):
    rc = main(list(argv))
    return rc, capsys.readouterr()


def significant_digits(text: str) -> int:
    return len(Decimal(text).as_tuple().digits)


def test_jsonable_rounds_inexact_values_to_the_digits_and_keeps_exact_ones():
    third = mpmath.mpf(1) / 3
    assert jsonable([third, 2 / 3, Fraction(1, 3), 10**30], digits=3) == \
        ["0.333", 0.667, "1/3", "1000000000000000000000000000000"]
    assert json.loads(dump_json({"x": third}))["x"].startswith("0.33333333333333")


@pytest.mark.parametrize("x", [mpmath.mpf(2) / 3, mpmath.mpf("0.00109863281250000"),
                               -mpmath.mpf(1) / 7, mpmath.mpf("0.999")])
@pytest.mark.parametrize("digits", [1, 2, 5])
def test_bounds_are_rounded_outward(x, digits):
    out = jsonable({"p_lo": x, "p_hi": x}, digits=digits)
    lo, hi = Fraction(Decimal(out["p_lo"])), Fraction(Decimal(out["p_hi"]))
    sign, man, exp, _ = x._mpf_  # the exact binary value (-1)**sign man 2**exp
    exact = (-1) ** sign * man * Fraction(2) ** exp
    assert lo <= exact <= hi
    assert significant_digits(out["p_lo"]) <= digits + 1
    assert significant_digits(out["p_hi"]) <= digits + 1


@pytest.mark.parametrize("dps", [1, 2, 3])
def test_critical_json_prints_dps_digits_of_the_true_value(capsys, dps):
    rc, cap = run(capsys, "critical", "10**3", "--dps", str(dps), "--json")
    assert rc == 0
    data = json.loads(cap.out)
    true = symhx.critical_point(1000, dps=40)  # independent of the dps-digit run: 2x precision
    with mpmath.workdps(50):
        want = mpmath.nstr(true.p, dps, strip_zeros=False)
        assert data["p_c"] == want
        assert Decimal(data["p_c_lo"]) <= Decimal(str(true.p)) <= Decimal(data["p_c_hi"])
    for key in ("p_c", "N_p_c_minus_1", "p_d", "N_p_d_minus_1", "p_c_lo", "p_c_hi"):
        assert significant_digits(data[key]) <= dps + (key.endswith(("_lo", "_hi"))), key


@pytest.mark.parametrize("argv", [
    ["distribution", "101", "0.02", "--float", "--dps", "3", "--json"],
    ["spaces", "101", "0.02", "--space", "eq41", "--float", "--dps", "3", "--json"],
    ["mode-path", "20", "--dps", "3", "--json"],
    ["asymptotics", "1e10", "--dps", "3", "--json"],
])
def test_every_json_output_carries_at_most_dps_digits(capsys, argv):
    rc, cap = run(capsys, *argv)
    assert rc == 0

    def walk(x, key=""):
        if isinstance(x, dict):
            for k, v in x.items():
                walk(v, k)
        elif isinstance(x, list):
            for v in x:
                walk(v, key)
        elif isinstance(x, str) and "/" not in x and x.replace(".", "").replace("e", "").lstrip(
                "-+").replace("-", "").replace("+", "").isdigit() and "." in x:
            assert significant_digits(x) <= 3 + key.endswith(("_lo", "_hi")), (key, x)
        elif isinstance(x, float):
            assert significant_digits(repr(x)) <= 3, (key, x)
    walk(json.loads(cap.out))


def test_distribution_accepts_N_1_as_the_api_does(capsys):
    d = symhx.distribution_of(1, "1/2")
    rc, cap = run(capsys, "distribution", "1", "0.5", "--json")
    assert rc == 0
    data = json.loads(cap.out)
    assert data["mean"] == 1 == d.mean() and data["modes"] == [1] and data["variance"] == 0


@pytest.mark.parametrize("argv", [["critical", "1"], ["mode-path", "1"], ["spaces", "1"],
                                  ["asymptotics", "1"]])
def test_commands_that_need_a_jump_refuse_N_1_like_the_api(capsys, argv):
    rc, cap = run(capsys, *argv)
    assert rc == 2 and "N must be >= 2" in cap.err
    with pytest.raises(ValueError, match="N must be >= 2"):
        symhx.critical_point(1)


def test_distribution_table_has_a_documented_row_limit(capsys):
    from symhx.distribution import MAX_TABLE_N as MAX_PMF_TABLE_N

    rc, cap = run(capsys, "distribution", str(MAX_PMF_TABLE_N + 1), "0.1", "--float", "--table")
    assert rc == 2 and "--table" in cap.err and str(MAX_PMF_TABLE_N) in cap.err


@pytest.mark.parametrize("argv, dps", [
    (["asymptotics", "1e10", "--dps", "3", "--exact"], 3),
    (["convergence", "30", "--max-m", "1", "--p", "0.05", "--dps", "2"], 2),
    (["critical", "10**3", "--dps", "2"], 2),
    (["spaces", "101", "0.02", "--dps", "3"], 3),
])
def test_text_output_carries_at_most_dps_digits(capsys, argv, dps):
    import re

    rc, cap = run(capsys, *argv)
    assert rc == 0
    # every decimal number with a point (integers and exact rationals aside)
    for num in re.findall(r"(?<![\w/.])-?\d+\.\d+(?:e[-+]?\d+)?", cap.out):
        assert significant_digits(num) <= dps, (num, cap.out)
