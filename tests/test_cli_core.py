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
