"""How :func:`symhx.cli.main` tells a user's mistake from a bug in symhx: only
:class:`symhx.validation.InputError` (and argparse's usage errors) is a usage error, exit code 2;
any other exception, a plain ``ValueError`` included, is an internal error, exit code 1, one line
that says it is a bug, and the traceback only with ``--debug`` or ``SYMHX_DEBUG``."""

from __future__ import annotations

import os
import subprocess
import sys

import pytest

import symhx.critical
from symhx.cli import DEBUG_ENV, REPORT_HINT, main
from symhx.validation import InputError


@pytest.fixture(autouse=True)
def _no_debug_env(monkeypatch):
    monkeypatch.delenv(DEBUG_ENV, raising=False)


def _break_critical_point(monkeypatch, exc: BaseException) -> None:
    """``symhx critical`` calls symhx.critical.critical_point: make it fail as a bug would."""
    def broken(*args, **kwargs):
        raise exc

    monkeypatch.setattr(symhx.critical, "critical_point", broken)


@pytest.mark.parametrize("argv, named", [
    (["circuits", "3000"], "N <= 2000"),                       # raised by the command
    (["spaces", "20", "--space", "excess<=x"], "excess<=x"),   # raised by symhx.spaces
    (["distribution", "10**1001", "1/3"], "MP_SUM_N_LIMIT"),     # raised by symhx.distribution
])
def test_input_error_from_below_the_cli_is_a_usage_error(argv, named, capsys):
    assert main(argv) == 2
    err = capsys.readouterr().err
    assert err.startswith(f"symhx {argv[0]}: error: ") and named in err
    assert err.count("\n") == 1 and "internal error" not in err and "Traceback" not in err


@pytest.mark.parametrize("exc", [ValueError("bad internal state"), TypeError("unsupported"),
                                 OverflowError("too big"), ZeroDivisionError("division")])
def test_other_exceptions_are_internal_errors_without_traceback(exc, monkeypatch, capsys):
    _break_critical_point(monkeypatch, exc)
    assert main(["critical", "10"]) == 1
    err = capsys.readouterr().err
    assert err == (f"symhx critical: internal error: {type(exc).__name__}: {exc} "
                   f"({REPORT_HINT})\n")
    assert "bug" in err


def test_an_input_error_raised_where_a_bug_would_be_is_still_a_usage_error(monkeypatch, capsys):
    _break_critical_point(monkeypatch, InputError("N must be >= 2, got 1"))
    assert main(["critical", "10"]) == 2
    assert capsys.readouterr().err == "symhx critical: error: N must be >= 2, got 1\n"


@pytest.mark.parametrize("argv, env", [
    (["--debug", "critical", "10"], None),
    (["critical", "10", "--debug"], None),
    (["critical", "10"], "1"),
])
def test_debug_prints_the_traceback_of_an_internal_error(argv, env, monkeypatch, capsys):
    if env is not None:
        monkeypatch.setenv(DEBUG_ENV, env)
    _break_critical_point(monkeypatch, ValueError("bad internal state"))
    assert main(argv) == 1
    err = capsys.readouterr().err
    assert err.startswith("Traceback (most recent call last):")
    assert "in broken" in err and "ValueError: bad internal state" in err
    assert err.splitlines()[-1].startswith("symhx critical: internal error: ValueError")


@pytest.mark.parametrize("env", ["", "0"])
def test_debug_env_set_to_nothing_or_zero_is_off(env, monkeypatch, capsys):
    monkeypatch.setenv(DEBUG_ENV, env)
    _break_critical_point(monkeypatch, ValueError("bad internal state"))
    assert main(["critical", "10"]) == 1
    assert "Traceback" not in capsys.readouterr().err


def test_debug_does_not_change_a_usage_error(capsys):
    assert main(["--debug", "circuits", "3000"]) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and "Traceback" not in err


def test_debug_flag_does_not_change_a_good_run(capsys):
    assert main(["circuits", "3", "--debug"]) == 0
    plain = capsys.readouterr().out
    assert main(["circuits", "3"]) == 0
    assert capsys.readouterr().out == plain


def test_an_integer_beyond_pythons_str_digit_limit_parses(capsys):
    """Python refuses int(str) beyond 4300 digits; the CLI lifts that limit while it parses."""
    assert main(["circuits", "1" * 5000, "--visits", "1,1", "--json"]) == 0
    assert '"N": "' + "1" * 5000 + '"' in capsys.readouterr().out


@pytest.mark.parametrize("debug", [False, True])
def test_a_bug_in_a_real_process_is_exit_1_with_traceback_only_under_debug(debug):
    """The CLI in a child process whose critical_point is broken as a bug would be."""
    code = ("import sys, symhx.critical as c\n"
            "def broken(*a, **k):\n    raise ValueError('bad internal state')\n"
            "c.critical_point = broken\n"
            "from symhx.cli import main\nsys.exit(main(['critical', '10']))\n")
    env = {k: v for k, v in os.environ.items() if k != DEBUG_ENV}
    if debug:
        env[DEBUG_ENV] = "1"
    proc = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True,
                          timeout=120, env=env)
    assert proc.returncode == 1 and proc.stdout == ""
    assert proc.stderr.splitlines()[-1] == ("symhx critical: internal error: ValueError: bad "
                                            f"internal state ({REPORT_HINT})")
    assert ("Traceback" in proc.stderr) is debug


@pytest.mark.parametrize("argv, option", [
    (["spaces", "100000", "1/50000"], "--float"),                # exact sums, sample spaces
    (["distribution", "5000", "1/2500", "--table"], "--float"),  # exact table rows
    (["distribution", "3000", "1/1000", "--space", "eq41", "--table"], "--float"),
    (["distribution", "300000", "--sites", "2:1/7,rest:1/300000"], "--float"),  # site weights
    (["p-sigma", "1e-400"], "--dps"),                            # beyond float64
    (["p-sigma", "1e400"], "--dps"),
    (["p-sigma", "--inverse", "1e-400"], "--dps"),
])
def test_a_refusal_points_to_the_cli_option_not_the_api_argument(argv, option, capsys):
    # the API's remedies ("pass p as a float or mpmath.mpf ... or dps=None", "use dps=") are
    # worded for the command line there: its options
    assert main(argv) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and f"use {option} " in err
    assert "dps=" not in err and "mpmath.mpf" not in err and "pmf(k)" not in err


def test_an_input_error_may_carry_its_command_line_wording():
    e = InputError("x: bad; pass dps=None", cli="x: bad; use --float")
    assert str(e) == "x: bad; pass dps=None" and e.cli == "x: bad; use --float"
    assert InputError("plain").cli is None
