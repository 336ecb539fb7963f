"""The symhx command line (core sub-commands) and the paper job's core section."""

import json
import subprocess
import sys

import pytest

import symhx
from symhx.cli import main


def run(capsys, *argv):
    rc = main(list(argv))
    return rc, capsys.readouterr().out


def test_critical_json_matches_api(capsys):
    rc, out = run(capsys, "critical", "101", "--dps", "60", "--json")
    assert rc == 0
    data = json.loads(out)
    cp = symhx.critical_point(101, dps=60)
    assert data["k_after"] == cp.k_after == 20
    import mpmath

    with mpmath.workdps(70):
        assert abs(mpmath.mpf(data["p_c"]) - cp.p) < mpmath.mpf(10) ** -58 * cp.p


def test_huge_N_parsed_exactly(capsys):
    rc, out = run(capsys, "critical", "1e100", "--json")
    assert rc == 0 and json.loads(out)["N"] == str(10**100)


def test_distribution_exact(capsys):
    _rc, out = run(capsys, "distribution", "101", "1/50", "--json")
    data = json.loads(out)
    assert data["modes"] == [50, 51] and data["exact"] is True


def test_circuits(capsys):
    _rc, out = run(capsys, "circuits", "7", "--visits", "2,1,1", "--json")
    assert json.loads(out)["count"] == symhx.circuit_count(7, (2, 1, 1))
    _rc, out = run(capsys, "circuits", "4", "--length", "3", "--json")
    data = json.loads(out)
    assert data["total"] == sum(data["by_pattern"].values())


def test_mode_path(capsys):
    _rc, out = run(capsys, "mode-path", "8", "--json")
    rows = json.loads(out)["breakpoints"]
    assert rows[0]["k_left"] == 1 and rows[1]["p"] == "5/16"


def test_bad_input_exit_code(capsys):
    assert main(["distribution", "10", "0"]) == 2
    assert "p must be > 0" in capsys.readouterr().err


@pytest.mark.parametrize("argv, prog", [
    (("paper", "--bogus"), "symhx paper"),
    (("critical", "101", "surplus"), "symhx critical"),
])
def test_unknown_option_named_by_its_command(capsys, argv, prog):
    assert main(list(argv)) == 2
    err = capsys.readouterr().err
    assert err.startswith(f"{prog}: error: unrecognized arguments: {argv[-1]}")
    assert err.count("\n") == 1


def test_core_paper_section(tmp_path):
    from symhx.commands import core

    lines = core.paper(tmp_path, full=False)
    assert any("jumps 1 -> 20" in line for line in lines)
    for name in ("critical_N101.json", "critical_table.csv", "mode_path_N101.csv",
                 "fig4_distributions.png", "fig5_mode_path.png", "fig6_f_and_phi.png"):
        assert (tmp_path / name).stat().st_size > 0


@pytest.mark.slow
def test_console_script_runs():
    out = subprocess.run([sys.executable, "-m", "symhx.cli", "critical", "5", "--json"],
                         capture_output=True, text=True, check=True).stdout
    assert json.loads(out)["argmins"] == [2, 3]


# --------------------------------------------------------------------------- issue 12 / 14
import argparse  # noqa: E402
import math  # noqa: E402
from fractions import Fraction  # noqa: E402

import mpmath  # noqa: E402

from symhx.cli import build_parser  # noqa: E402
from symhx.commands._common import csv_num, dump_json, int_show, int_str, jsonable  # noqa: E402

MY_COMMANDS = ("critical", "distribution", "circuits", "mode-path", "paper", "spaces",
               "convergence", "derive", "asymptotics")


def _subparsers():
    parser = build_parser()
    (action,) = [a for a in parser._actions if isinstance(a, argparse._SubParsersAction)]
    return action.choices


@pytest.mark.parametrize("cmd", MY_COMMANDS)
def test_every_option_has_help_and_shows_its_default(cmd):
    sub = _subparsers()[cmd]
    text = sub.format_help()
    for action in sub._actions:
        if isinstance(action, argparse._HelpAction):
            continue
        assert action.help, f"{cmd}: {action.dest} has no help text"
        if action.option_strings and action.default not in (None, False):
            assert f"(default: {action.default})" in " ".join(text.split()), (cmd, action.dest)


def test_all_commands_use_the_defaults_formatter():
    for name, sub in _subparsers().items():
        assert "ArgumentDefaults" in type(sub.formatter_class).__mro__.__repr__() or issubclass(
            sub.formatter_class, argparse.ArgumentDefaultsHelpFormatter), name


def test_default_dps_is_the_api_default():
    from symhx.validation import DEFAULT_DPS

    for cmd in ("critical", "distribution", "mode-path", "spaces", "asymptotics"):
        assert _subparsers()[cmd].get_default("dps") == DEFAULT_DPS, cmd


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
def test_bad_input_is_one_line_and_exit_2(argv, capsys):
    with _exit_code() as rc:
        rc.value = main(argv)
    captured = capsys.readouterr()
    assert rc.value == 2, captured
    lines = captured.err.strip().splitlines()
    assert len(lines) == 1 and len(lines[0]) < 400, captured.err
    # argparse reports unknown options from the top-level parser ("symhx: error: ...")
    assert lines[0].startswith((f"symhx {argv[0]}: error: ", "symhx: error: ")), captured.err
    assert "Traceback" not in captured.err and captured.out == ""


class _exit_code:
    """main() returns the code; argparse errors raise SystemExit: take both."""

    def __enter__(self):
        return self

    def __exit__(self, typ, exc, tb):
        if typ is SystemExit:
            self.value = exc.code
            return True
        return False


def test_unwritable_out_is_exit_2(tmp_path, capsys):
    blocker = tmp_path / "file"
    blocker.write_text("x")
    assert main(["paper", "--out", str(blocker / "sub")]) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and "symhx paper: error:" in err


def test_internal_error_is_exit_1_with_hint(monkeypatch, capsys):
    from symhx.commands import core

    def boom(args):
        raise RuntimeError("kaboom")

    monkeypatch.setattr(core, "cmd_critical", boom)
    assert main(["critical", "5"]) == 1
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and "kaboom" in err and "please report" in err


def test_python_dash_m_symhx():
    proc = subprocess.run([sys.executable, "-m", "symhx", "critical", "5", "--json"],
                          capture_output=True, text=True, check=False)
    assert proc.returncode == 0, proc.stderr
    assert json.loads(proc.stdout)["argmins"] == [2, 3]
    proc = subprocess.run([sys.executable, "-m", "symhx", "critical", "1e-3"],
                          capture_output=True, text=True, check=False)
    assert proc.returncode == 2 and "Traceback" not in proc.stderr


def test_cli_reads_decimals_like_the_api(capsys):
    # "0.02" is exactly 1/50 on both sides: the tie of the modes 50, 51 (a float would break it)
    rc, out = run(capsys, "distribution", "101", "0.02", "--json")
    assert rc == 0 and json.loads(out)["modes"] == [50, 51]
    assert list(symhx.modes(101, Fraction(1, 50))) == [50, 51]
    assert list(symhx.modes(101, 0.02)) == [51]


def test_critical_huge_N_separates_p_c_and_p_d(capsys):
    rc, out = run(capsys, "critical", "1e100")
    assert rc == 0
    lines = dict(line.split("=", 1) for line in out.splitlines() if "=" in line
                 and line.startswith(("N p_", "p_")))
    N = 10**100
    with mpmath.workdps(120):  # independent: eq. 16, N p_d - 1 = 2 (1 + sqrt(N + 1)) / N
        qd = mpmath.mpf(lines["N p_d - 1           "].strip())
        qc = mpmath.mpf(lines["N p_c - 1           "].strip())
        ref = (2 * (1 + mpmath.sqrt(N + 1))) / N
        assert abs(qd / ref - 1) < mpmath.mpf(10) ** -48
    assert qc > 5 * qd  # visibly different at the shown precision
    # 50 significant digits (the default dps) are printed for p_c
    pc = lines["p_c  (mode jumps)   "].strip()
    assert len(pc.split("e")[0].replace(".", "").lstrip("0")) == 50


def test_huge_rational_output_never_hits_the_int_str_limit(capsys):
    rc, out = run(capsys, "distribution", "101", "1e-400")
    assert rc == 0 and "mean" in out
    rc, out = run(capsys, "distribution", "101", "1e-400", "--json")
    data = json.loads(out)
    num, den = (_parse_big(x) for x in data["mean"].split("/"))
    d = symhx.distribution_of(101, Fraction(1, 10**400))
    assert Fraction(num, den) == d.mean()


def _parse_big(text):
    """int() of a long decimal string, independent of int_str (and of the 4300-digit limit)."""
    old = sys.get_int_max_str_digits()
    sys.set_int_max_str_digits(0)
    try:
        return int(text)
    finally:
        sys.set_int_max_str_digits(old)


def test_json_only_with_the_flag(capsys):
    rc, out = run(capsys, "circuits", "5")
    assert rc == 0 and not out.lstrip().startswith("{") and "phi_N(k)" in out
    assert "89" in out.splitlines()[-1]  # total 5 + 10 + 20 + 30 + 24 (brute-force sum)
    rc, out = run(capsys, "circuits", "5", "--json")
    assert json.loads(out)["total"] == 89
    # the text table: a header, then "k phi_N(k)" rows equal to N!/((N-k)! k) (eq. 5)
    rc, out = run(capsys, "circuits", "9")
    lines = out.splitlines()
    assert lines[1].split() == ["k", "phi_N(k)"]
    body = [line.split() for line in lines[2:-1]]
    assert [(int(k), int(v)) for k, v in body] == [
        (k, math.perm(9, k) // k) for k in range(1, 10)]


def test_dps_is_read_like_the_api(capsys):
    # "1e1" is the exact integer 10 for check_int, as for every other integer argument
    rc, out = run(capsys, "critical", "101", "--dps", "1e1")
    assert rc == 0
    pc = next(line for line in out.splitlines() if line.startswith("p_c"))
    assert pc.split("=")[1].strip() == "0.01288911533"


def test_text_tables_have_headers(capsys):
    for argv, header in ((["mode-path", "8"], "breakpoint p"),
                         (["circuits", "4", "--length", "3"], "visit pattern"),
                         (["distribution", "8", "1/4", "--table"], "P(X=k)")):
        rc, out = run(capsys, *argv)
        assert rc == 0 and header in out, argv


def test_strict_json():
    text = dump_json({"a": float("nan"), "b": float("inf"), "c": mpmath.mpf("-inf"),
                      "d": [mpmath.mpf(1) / 3, Fraction(2, 3), 2**80]})
    data = json.loads(text, parse_constant=lambda c: pytest.fail(f"non-strict JSON {c}"))
    assert data == {"a": None, "b": "inf", "c": "-inf",
                    "d": [data["d"][0], "2/3", str(2**80)]}
    assert jsonable(mpmath.mpf("nan")) is None


def test_int_str_and_int_show():
    n = 7**20000  # 16902 digits, beyond Python's default 4300-digit str limit
    s = int_str(n)
    assert len(s) == 16902 and _parse_big(s) == n
    assert int_show(10**100) == "10**100"
    assert int_show(2**300).endswith("(exact integer, 91 digits)")


def test_csv_num_round_trips_float64():
    for x in (Fraction(1, 3), mpmath.mpf(2) ** -1000 / 3, 10**100, Fraction(10**40 + 1, 7)):
        cell = csv_num(x)
        assert len(str(cell)) <= 26
        with mpmath.workdps(40):
            v = mpmath.mpf(x.numerator) / x.denominator if isinstance(x, (int, Fraction)) else x
            assert float(cell) == float(v)


def test_options_without_help_text_still_show_their_default():
    # commands of other modules too: every option with a default shows it in --help
    for name, sub in _subparsers().items():
        text = " ".join(sub.format_help().split())
        for action in sub._actions:
            if action.option_strings and not any(action.default is x for x in
                                                 (None, False, argparse.SUPPRESS)):
                assert f"default: {action.default}" in text or "default" in (
                    action.help or "").lower(), (name, action.dest)


def test_empty_visits_is_an_error(capsys):
    assert main(["circuits", "12", "--visits", ""]) == 2
    assert "--visits" in capsys.readouterr().err


def test_distribution_float_huge_N_refused_quickly(capsys):
    import time

    t = time.monotonic()
    assert main(["distribution", "1e1000", "0.1", "--float"]) == 2
    assert "MP_SUM_N_LIMIT" in capsys.readouterr().err
    assert time.monotonic() - t < 1
