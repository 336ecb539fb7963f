"""``symhx convergence``'s options follow the CLI's conventions: ``--p`` is an exact rational
parsed like every other p (``0.05``, ``5e-2`` and ``1/20`` are the same p), refused with a usage
error naming ``--p``; ``--dps`` defaults to :data:`symhx.validation.DEFAULT_DPS`."""

from __future__ import annotations

import json

import pytest

from symhx.cli import build_parser, main
from symhx.validation import DEFAULT_DPS


def _convergence_parser():
    parser = build_parser()
    return parser.parse_args(["convergence"]), parser


def test_convergence_dps_defaults_to_the_cli_default():
    args, _ = _convergence_parser()
    assert args.dps == DEFAULT_DPS


@pytest.mark.parametrize("text", ["0.05", "5e-2", "1/20", "0.050"])
def test_convergence_p_spellings_of_one_rational_give_one_column(text, capsys):
    assert main(["convergence", "12", "--max-m", "0", "--p", text, "--dps", "15", "--json"]) == 0
    rows = json.loads(capsys.readouterr().out)["rows"]
    assert list(rows[0]["means"]) == ["0.05"]
    assert main(["convergence", "12", "--max-m", "0", "--p", "0.05", "--dps", "15", "--json"]) == 0
    assert json.loads(capsys.readouterr().out)["rows"] == rows


def test_convergence_p_without_a_finite_decimal_is_shown_as_a_ratio(capsys):
    assert main(["convergence", "12", "--max-m", "0", "--p", "1/30", "--p", "0.01",
                 "--dps", "15"]) == 0
    out = capsys.readouterr().out
    assert out.splitlines()[0] == "N = 12: E[X] at p = 1/30, 0.01"


@pytest.mark.parametrize("bad", ["-1", "0", "abc", "1/0"])
def test_convergence_bad_p_is_a_usage_error_naming_it(bad, capsys):
    assert main(["convergence", "12", "--p", bad]) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and "--p" in err and "Traceback" not in err
