"""The core sub-commands (:mod:`symhx.commands.core`): ``critical``, ``distribution``,
``circuits``, ``mode-path`` and the core section of ``symhx paper``; their output against the API
and against independent references."""

from __future__ import annotations

import json
import math
import subprocess
import sys
import time
from decimal import Decimal
from fractions import Fraction

import mpmath
import pytest

import symhx
from symhx.cli import main
from tests.reference.distribution import pmf_table


def run(capsys, *argv):
    rc = main(list(argv))
    return rc, capsys.readouterr().out


# --------------------------------------------------------------------------- critical
def test_critical_json_matches_the_api(capsys):
    rc, out = run(capsys, "critical", "101", "--dps", "60", "--json")
    assert rc == 0
    data = json.loads(out)
    cp = symhx.critical_point(101, dps=60)
    assert data["k_after"] == cp.k_after == 20
    with mpmath.workdps(70):
        assert abs(mpmath.mpf(data["p_c"]) - cp.p) < mpmath.mpf(10) ** -58 * cp.p


def test_critical_reads_a_huge_N_exactly(capsys):
    rc, out = run(capsys, "critical", "1e100", "--json")
    assert rc == 0 and json.loads(out)["N"] == str(10**100)


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


def test_critical_reads_dps_like_the_api(capsys):
    # "1e1" is the exact integer 10 for check_int, as for every other integer argument
    rc, out = run(capsys, "critical", "101", "--dps", "1e1")
    assert rc == 0
    pc = next(line for line in out.splitlines() if line.startswith("p_c"))
    assert pc.split("=")[1].strip() == "0.01288911533"


# --------------------------------------------------------------------------- distribution
def test_distribution_of_an_exact_p_is_exact(capsys):
    _rc, out = run(capsys, "distribution", "101", "1/50", "--json")
    data = json.loads(out)
    assert data["modes"] == [50, 51] and data["exact"] is True


def test_distribution_reads_decimals_like_the_api(capsys):
    # "0.02" is exactly 1/50 on both sides: the tie of the modes 50, 51 (a float would break it)
    rc, out = run(capsys, "distribution", "101", "0.02", "--json")
    assert rc == 0 and json.loads(out)["modes"] == [50, 51]
    assert list(symhx.modes(101, Fraction(1, 50))) == [50, 51]
    assert list(symhx.modes(101, 0.02)) == [51]


TABLE_CASES = [(2, "1/2"), (3, "1/4"), (8, "1/4"), (30, "0.05"), (101, "1/50"), (101, "0.3")]


@pytest.mark.parametrize("N, p", TABLE_CASES)
def test_distribution_table_lists_k_1_to_N_and_sums_to_one_exactly(capsys, N, p):
    rc, out = run(capsys, "distribution", str(N), p, "--table", "--json")
    assert rc == 0
    pmf = json.loads(out)["pmf"]
    assert list(pmf) == [str(k) for k in range(1, N + 1)]
    values = [Fraction(v) for v in pmf.values()]
    assert sum(values) == 1
    assert values == pmf_table(N, Fraction(p))  # eq. (7) from the factorials


@pytest.mark.parametrize("N, p", [(8, "1/4"), (30, "0.05")])
def test_distribution_text_table_has_one_row_per_k_with_the_exact_value(capsys, N, p):
    rc, out = run(capsys, "distribution", str(N), p, "--table")
    assert rc == 0
    lines = out.splitlines()
    head = next(i for i, line in enumerate(lines) if line.split() == ["k", "P(X=k)"])
    rows = [line.split() for line in lines[head + 1:]]
    assert [int(r[0]) for r in rows] == list(range(1, N + 1))
    exact = [Fraction(r[-1].rstrip(")")) for r in rows]  # "... (exact a/b)"
    assert all(r[-2] == "(exact" for r in rows)
    assert sum(exact) == 1 and exact == pmf_table(N, Fraction(p))


def test_distribution_float_table_sums_to_one_within_its_digits(capsys):
    rc, out = run(capsys, "distribution", "40", "0.05", "--float", "--dps", "30", "--table",
                  "--json")
    assert rc == 0
    pmf = json.loads(out)["pmf"]
    assert list(pmf) == [str(k) for k in range(1, 41)]
    ref = pmf_table(40, Fraction(1, 20))
    with mpmath.workdps(60):
        assert abs(mpmath.fsum(mpmath.mpf(v) for v in pmf.values()) - 1) < mpmath.mpf(10) ** -28
        for k, v in pmf.items():
            r = ref[int(k) - 1]
            assert abs(mpmath.mpf(v) / (mpmath.mpf(r.numerator) / r.denominator) - 1) \
                < mpmath.mpf(10) ** -28, k


def test_distribution_table_of_a_huge_N_is_refused_at_once():
    try:
        proc = subprocess.run([sys.executable, "-m", "symhx", "distribution", "1e100", "0.1",
                               "--float", "--table"], capture_output=True, text=True, timeout=6)
    except subprocess.TimeoutExpired:
        pytest.fail("symhx distribution 1e100 0.1 --float --table ran for 6 s")
    assert proc.returncode == 2 and "--table" in proc.stderr, proc.stderr[-500:]


def test_distribution_prints_huge_exact_rationals_in_full(capsys):
    rc, out = run(capsys, "distribution", "101", "1e-400")
    assert rc == 0 and "mean" in out
    rc, out = run(capsys, "distribution", "101", "1e-400", "--json")
    data = json.loads(out)
    # read back by Decimal, which has no digit limit (independent of the CLI's int_str)
    num, den = (int(Decimal(x)) for x in data["mean"].split("/"))
    d = symhx.distribution_of(101, Fraction(1, 10**400))
    assert Fraction(num, den) == d.mean()


def test_distribution_float_huge_N_refused_quickly(capsys):
    t = time.monotonic()
    assert main(["distribution", "1e1001", "0.1", "--float"]) == 2
    assert "MP_SUM_N_LIMIT" in capsys.readouterr().err
    assert time.monotonic() - t < 1


# --------------------------------------------------------------------------- circuits
def test_circuits_counts_match_the_api(capsys):
    _rc, out = run(capsys, "circuits", "7", "--visits", "2,1,1", "--json")
    assert json.loads(out)["count"] == symhx.circuit_count(7, (2, 1, 1))
    assert json.loads(out)["length"] == 4 and json.loads(out)["visits"] == [2, 1, 1]
    _rc, out = run(capsys, "circuits", "4", "--length", "3", "--json")
    data = json.loads(out)
    assert data["total"] == sum(data["by_pattern"].values()) and data["length"] == 3


def test_circuits_prints_json_only_with_the_flag(capsys):
    rc, out = run(capsys, "circuits", "5")
    assert rc == 0 and not out.lstrip().startswith("{") and "phi_N(k)" in out
    # the last row: the total 5 + 10 + 20 + 30 + 24 (brute-force sum), labelled
    assert out.splitlines()[-1].split() == ["total", "89"]
    rc, out = run(capsys, "circuits", "5", "--json")
    assert json.loads(out)["total"] == 89
    # the text table: a header, then "k phi_N(k)" rows equal to N!/((N-k)! k) (eq. 5)
    rc, out = run(capsys, "circuits", "9")
    lines = out.splitlines()
    assert lines[1].split() == ["k", "phi_N(k)"]
    body = [line.split() for line in lines[2:-1]]
    assert [(int(k), int(v)) for k, v in body] == [
        (k, math.perm(9, k) // k) for k in range(1, 10)]


def test_circuits_empty_visits_is_an_error_naming_the_option(capsys):
    assert main(["circuits", "12", "--visits", ""]) == 2
    assert "--visits" in capsys.readouterr().err


# --------------------------------------------------------------------------- mode-path
def test_mode_path_breakpoints_are_exact(capsys):
    _rc, out = run(capsys, "mode-path", "8", "--json")
    rows = json.loads(out)["breakpoints"]
    assert rows[0]["k_left"] == 1 and rows[1]["p"] == "5/16"


def test_text_tables_have_headers(capsys):
    for argv, header in ((["mode-path", "8"], "breakpoint p"),
                         (["circuits", "4", "--length", "3"], "visit pattern"),
                         (["distribution", "8", "1/4", "--table"], "P(X=k)")):
        rc, out = run(capsys, *argv)
        assert rc == 0 and header in out, argv


# --------------------------------------------------------------------------- symhx paper
def test_core_paper_section_writes_its_files(tmp_path):
    from symhx.commands import core

    lines = core.paper(tmp_path, full=False)
    assert any("jumps 1 -> 20" in line for line in lines)
    for name in ("critical_N101.json", "critical_table.csv", "mode_path_N101.csv",
                 "fig4_distributions.png", "fig5_mode_path.png", "fig6_f_and_phi.png"):
        assert (tmp_path / name).stat().st_size > 0
    # the table's columns against the closed forms: N p_d - 1 = 2 (1 + sqrt(N + 1))/N
    # (eq. 16), N p_c - 1 from p_c, k_after from the API
    import csv

    with open(tmp_path / "critical_table.csv", newline="") as fh:
        table = list(csv.DictReader(fh))
    assert len(table) >= 3
    for row in table:
        N = int(Decimal(row["N"]))  # 17-digit cells: 1e+30 is exact for these N
        qd = 2 * (1 + math.sqrt(N + 1)) / N
        assert abs(float(row["N_p_d_minus_1"]) - qd) <= 1e-15 * qd
        assert abs(float(row["p_d"]) - (1 + qd) / N) <= 1e-15 * (1 + qd) / N
        assert abs(float(row["N_p_c_minus_1"]) - (N * float(row["p_c"]) - 1)) <= 1e-12
        k_after = symhx.critical_point(N, dps=20).k_after
        assert abs(Decimal(row["k_after"]) - k_after) <= Decimal(k_after) / 2**52  # a float64
    # the last line: N = 10**100, N p_d - 1 = 2 (1 + sqrt(N + 1))/N = 2.0e-50 (to 20 digits)
    big = next(line for line in lines if line.startswith("N = 10**100"))
    assert "N p_d - 1 = 2.0000000000000000000e-50" in big


def test_a_paper_section_reports_its_lines_or_its_failure(tmp_path, monkeypatch):
    """``symhx paper`` runs each module's section in a worker: its summary lines and time, or,
    when the section raises, one FAILED line naming the error (never an exception)."""
    import symhx.commands.derive as derive_mod
    from symhx.commands.core import _paper_section

    lines, seconds, failed = _paper_section("symhx.commands.derive", tmp_path, False)
    assert not failed and seconds > 0 and (tmp_path / "derivations.json").exists()
    assert lines == derive_mod.paper(tmp_path, False)

    def broken(out, full):
        raise ArithmeticError("no\nconvergence")

    monkeypatch.setattr(derive_mod, "paper", broken)
    lines, _, failed = _paper_section("symhx.commands.derive", tmp_path, False)
    assert failed and lines == ["FAILED: ArithmeticError: no convergence"]


def test_critical_text_names_the_number_of_pipes(capsys):
    _rc, out = run(capsys, "critical", "1000", "--dps", "20")
    assert out.splitlines()[0].startswith("N = 1000 vertices (999 pipes)")
    _rc, out = run(capsys, "critical", "10**30", "--dps", "20")
    assert "(N - 1 pipes)" in out.splitlines()[0]
