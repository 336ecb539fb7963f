"""The option helpers shared by the sub-commands (:mod:`symhx.commands._common`): ``--dps`` and
``--json``, the help texts, CSV files, and rationals shown as the user types them."""

from __future__ import annotations

import argparse
import csv
from fractions import Fraction

import pytest

from symhx.commands._common import (
    DPS_HELP,
    add_dps,
    add_json,
    rational_arg,
    rational_show,
    write_csv,
)
from symhx.validation import DEFAULT_DPS, MAX_DPS


def _parser(**kwargs) -> argparse.ArgumentParser:
    parser = argparse.ArgumentParser(exit_on_error=False)
    add_dps(parser, **kwargs)
    add_json(parser)
    return parser


def test_add_dps_defaults_to_the_one_default_and_validates():
    parser = _parser()
    assert parser.parse_args([]).dps == DEFAULT_DPS and parser.parse_args([]).json is False
    assert parser.parse_args(["--dps", "1e3", "--json"]).dps == 1000
    assert parser.parse_args(["--json"]).json is True
    for bad in ("0", str(MAX_DPS + 1), "2.5", "x"):
        with pytest.raises(argparse.ArgumentError, match="dps"):
            parser.parse_args(["--dps", bad])
    assert _parser(default=None).parse_args([]).dps is None
    assert any(a.help == DPS_HELP for a in parser._actions)


def test_write_csv_rows_under_a_header_with_17_digit_cells(tmp_path):
    path = tmp_path / "t.csv"
    write_csv(path, ["k", "p"], [[1, Fraction(1, 3)], [2, 10**100]])
    rows = list(csv.reader(path.open()))
    assert rows == [["k", "p"], ["1", "0.33333333333333331"], ["2", "1e+100"]]


@pytest.mark.parametrize("fr", [Fraction(1, 200), Fraction(3), Fraction(-7, 4), Fraction(1, 3),
                                Fraction(2, 7), Fraction(1, 2**30), Fraction(1, 2**31),
                                Fraction(12345, 10**30), Fraction(0), Fraction(10**40 + 1, 5)])
def test_rational_show_parses_back_to_the_same_rational(fr):
    text = rational_show(fr)
    assert rational_arg("p", positive=False)(text) == fr


def test_rational_show_is_a_decimal_when_short_else_a_ratio():
    assert rational_show(Fraction(1, 200)) == "0.005"
    assert rational_show(Fraction(-7, 4)) == "-1.75"
    assert rational_show(Fraction(1, 3)) == "1/3"
    assert rational_show(Fraction(1, 2**31)) == f"1/{2**31}"  # over 30 decimal places


def test_a_bad_dps_is_a_usage_error_naming_the_allowed_range(capsys):
    from symhx.cli import main

    assert main(["critical", "101", "--dps", "0"]) == 2
    err = capsys.readouterr().err
    assert "--dps" in err and "got 0" in err and "between 1 and" in err
