"""The ``symhx`` command line as a whole (:mod:`symhx.cli`): one-line errors and their exit codes,
every option's help text and default, the console entry point.  The sub-commands are tested in
``tests/commands/``."""

from __future__ import annotations

import argparse
import json
import subprocess
import sys

import pytest

from symhx.cli import HelpFormatter, build_parser, main
from symhx.validation import DEFAULT_DPS

COMMANDS_WITH_DPS = ("critical", "distribution", "mode-path", "spaces", "asymptotics")


def _subparsers() -> dict[str, argparse.ArgumentParser]:
    parser = build_parser()
    (action,) = [a for a in parser._actions if isinstance(a, argparse._SubParsersAction)]
    return action.choices


COMMANDS = tuple(_subparsers())


class _exit_code:
    """main() returns the code; argparse errors raise SystemExit: take both."""

    def __enter__(self):
        return self

    def __exit__(self, typ, exc, tb):
        if typ is SystemExit:
            self.value = exc.code
            return True
        return False


def test_bad_value_exits_2_and_names_the_argument_value_and_bound(capsys):
    assert main(["distribution", "10", "0"]) == 2
    err = capsys.readouterr().err
    assert err.startswith("symhx distribution: error: ")
    assert "p must be > 0" in err and "got '0'" in err


@pytest.mark.parametrize("argv, prog", [
    (("paper", "--bogus"), "symhx paper"),
    (("critical", "101", "surplus"), "symhx critical"),
])
def test_unknown_option_is_reported_by_its_command(capsys, argv, prog):
    assert main(list(argv)) == 2
    err = capsys.readouterr().err
    assert err.startswith(f"{prog}: error: unrecognized arguments: {argv[-1]}")
    assert err.count("\n") == 1


BAD = [
    ["critical", "1e-3"], ["critical", "abc"], ["critical", "1"], ["critical", "101", "--dps", "0"],
    ["critical", "101", "--dps", "2.5"], ["critical", "101", "--dps", "99999"],
    ["distribution", "101", "1/0"], ["distribution", "101", "-0.1", "--float"],
    ["distribution", "101", "nan"], ["distribution", "101", "inf"], ["distribution", "1.5", "0.1"],
    ["distribution", "101", "1e999999"], ["circuits", "3", "--length", "10**7"],
    ["circuits", "3", "--visits", "a,b"], ["circuits", "10**9"], ["mode-path", "8", "--p-max", "x"],
    ["spaces", "20", "--space", "bogus"], ["convergence", "20", "--p", "-1"],
    ["asymptotics", "1"], ["derive", "999"], ["spaces", "1e1000"], ["spaces", "1e7"],
    ["paper", "--bogus"],
]


@pytest.mark.parametrize("argv", BAD, ids=[" ".join(a) for a in BAD])
def test_bad_input_is_one_line_on_stderr_and_exit_2(argv, capsys):
    with _exit_code() as rc:
        rc.value = main(argv)
    captured = capsys.readouterr()
    assert rc.value == 2, captured
    lines = captured.err.strip().splitlines()
    assert len(lines) == 1 and len(lines[0]) < 400, captured.err
    # argparse reports unknown options from the top-level parser ("symhx: error: ...")
    assert lines[0].startswith((f"symhx {argv[0]}: error: ", "symhx: error: ")), captured.err
    assert "Traceback" not in captured.err and captured.out == ""


def test_unwritable_out_folder_is_exit_2(tmp_path, capsys):
    blocker = tmp_path / "file"
    blocker.write_text("x")
    assert main(["paper", "--out", str(blocker / "sub")]) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and "symhx paper: error:" in err


def test_internal_error_is_exit_1_with_a_request_to_report(monkeypatch, capsys):
    from symhx.commands import core

    def boom(args):
        raise RuntimeError("kaboom")

    monkeypatch.setattr(core, "cmd_critical", boom)
    assert main(["critical", "5"]) == 1
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and "kaboom" in err and "please report" in err


@pytest.mark.parametrize("cmd", COMMANDS)
def test_every_option_has_help_and_shows_its_default(cmd):
    sub = _subparsers()[cmd]
    text = sub.format_help()
    for action in sub._actions:
        if isinstance(action, argparse._HelpAction):
            continue
        assert action.help, f"{cmd}: {action.dest} has no help text"
        if action.option_strings and action.default not in (None, False):
            assert f"(default: {action.default})" in " ".join(text.split()), (cmd, action.dest)


def test_every_command_uses_the_symhx_help_formatter():
    # argparse's own defaults formatter would print "(default: None)" and "(default: False)"
    for name, sub in _subparsers().items():
        assert sub.formatter_class is HelpFormatter, name
        text = " ".join(sub.format_help().split())
        assert "(default: None)" not in text and "(default: False)" not in text, name


def test_options_without_help_text_still_show_their_default():
    # commands of every module: every option with a default shows it in --help
    for name, sub in _subparsers().items():
        text = " ".join(sub.format_help().split())
        for action in sub._actions:
            if action.option_strings and not any(action.default is x for x in
                                                 (None, False, argparse.SUPPRESS)):
                assert f"default: {action.default}" in text or "default" in (
                    action.help or "").lower(), (name, action.dest)


def test_default_dps_is_the_api_default():
    for cmd in COMMANDS_WITH_DPS:
        assert _subparsers()[cmd].get_default("dps") == DEFAULT_DPS, cmd


@pytest.mark.slow
def test_python_dash_m_symhx_cli_runs_a_command():
    out = subprocess.run([sys.executable, "-m", "symhx.cli", "critical", "5", "--json"],
                         capture_output=True, text=True, check=True).stdout
    assert json.loads(out)["argmins"] == [2, 3]


def test_a_long_error_is_one_line_of_at_most_2000_characters():
    from symhx.cli import _one_line

    long = ValueError("x:\n" + "word " * 1000)
    text = _one_line(long)
    assert len(text) == 2000 and text.endswith("...") and "\n" not in text
    assert text[:-3] == " ".join(str(long).split())[:1997]
    assert _one_line(ValueError("short  one\n")) == "short one"
    assert _one_line(ValueError("")) == "ValueError"


def test_help_states_each_default_once():
    """An option whose help already states its default gets no second "(default: ...)"; one
    without gets it appended."""
    import contextlib
    import io

    from symhx.cli import main

    buf = io.StringIO()
    with contextlib.redirect_stdout(buf), contextlib.suppress(SystemExit):
        main(["convergence", "--help"])
    text = " ".join(buf.getvalue().split())
    p_help = text.split("--p P impact", 1)[1].split("--dps DPS", 1)[0]
    assert "default: the paper's figure values" in p_help and "(default:" not in p_help
    assert "significant decimal digits of the results (default: 50)" in text


def test_no_option_states_its_default_twice():
    # an option whose own help text already names its default (p-sigma's --omega and --d say
    # "(default: 1)") must not get the formatter's "(default: ...)" on top
    stated = 0
    for name, sub in _subparsers().items():
        formatter = sub._get_formatter()
        for action in sub._actions:
            if not action.option_strings or isinstance(action, argparse._HelpAction):
                continue
            shown = formatter._expand_help(action) if action.help else ""  # as --help shows it
            assert shown.lower().count("default") <= 1, (name, action.dest, shown)
            stated += "default" in (action.help or "").lower()
    assert stated >= 2  # the check above meets options that state their default themselves
