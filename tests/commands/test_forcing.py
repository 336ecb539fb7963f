"""The ``symhx p-sigma`` command (``symhx.commands.forcing``): the values of the API, strict JSON,
one-line errors."""

from __future__ import annotations

import json
import subprocess
import sys

import mpmath
import pytest

from symhx import forcing as F
from tests.reference.mp import rel_err


def run(*args):
    return subprocess.run([sys.executable, "-m", "symhx.cli", "p-sigma", *args],
                          capture_output=True, text=True, timeout=300)


def test_json_is_strict_for_underflow():
    r = run("1e-200", "--json")
    assert r.returncode == 0, r.stderr
    assert "Infinity" not in r.stdout and "NaN" not in r.stdout
    row = json.loads(r.stdout)[0]
    assert row["log_p"] == "-inf" and row["p"] == 0.0
    # the documented string round-trips to the float value
    assert float(row["log_p"]) == F.log_impact_probability(1e-200)


def test_dps_values_match_api_and_logs_keep_relative_accuracy():
    r = run("0.05", "1000", "--dps", "25", "--json")  # 1 - p ~ 1e-13 at sigma = 1000
    assert r.returncode == 0, r.stderr
    rows = json.loads(r.stdout)
    for row, s in zip(rows, ("0.05", "1000"), strict=True):
        with mpmath.workdps(40):
            for key, fn in (("p", F.impact_probability), ("one_minus_p", F.no_impact_probability),
                            ("log_p", F.log_impact_probability),
                            ("log_one_minus_p", F.log_no_impact_probability)):
                ref = fn(s, dps=35)
                assert abs(mpmath.mpf(row[key]) / ref - 1) < mpmath.mpf(10) ** -24, (s, key)


def test_float_rows_match_api():
    r = run("0.12", "--grid", "0.01", "100", "5", "--json")
    rows = json.loads(r.stdout)
    assert len(rows) == 6
    for row in rows:
        assert row["p"] == F.impact_probability(row["sigma"])
        assert row["one_minus_p"] == F.no_impact_probability(row["sigma"])


@pytest.mark.parametrize("args, word", [(["0.1", "--omega", "abc"], "omega"),
                                        (["0.1", "--d", "x"], "d"),
                                        (["0.1", "--Omega", "1,zz"], "Omega"),
                                        (["0.1", "--d", "1,2"], "--d"),
                                        (["--grid", "a", "1", "3"], "--grid"),
                                        (["-1"], "sigma")])
def test_bad_options_one_line_error(args, word):
    r = run(*args)
    assert r.returncode != 0
    assert "Traceback" not in r.stderr
    assert word in r.stderr


# ----------------------------------------------------------------------------- CLI
def test_cli_p_sigma(tmp_path, capsys):
    from symhx.cli import main

    assert main(["p-sigma", "0.12", "--dps", "40"]) == 0
    out = capsys.readouterr().out
    line = next(ln for ln in out.splitlines() if ln.strip().startswith("p "))
    with mpmath.workdps(50):
        printed = mpmath.mpf(line.split("=")[1].strip())
        assert rel_err(printed, F.impact_probability("0.12", dps=45)) < mpmath.mpf(10) ** -38
    csvf = tmp_path / "grid.csv"
    assert main(["p-sigma", "--grid", "0.01", "100", "7", "--csv", str(csvf)]) == 0
    rows = csvf.read_text().splitlines()
    assert rows[0].startswith("sigma,p,one_minus_p") and len(rows) == 8
    assert main(["p-sigma", "-1"]) == 2
    assert "sigma must be > 0" in capsys.readouterr().err
    assert main(["p-sigma", "0.1", "--Omega", "1.0"]) == 2  # resonance


def test_csv_that_cannot_be_written_is_a_usage_error_naming_the_path(tmp_path, capsys):
    from symhx.cli import main

    where = tmp_path / "no-such-folder" / "grid.csv"
    assert main(["p-sigma", "0.1", "--csv", str(where)]) == 2
    err = capsys.readouterr().err
    assert "--csv" in err and str(where) in err and "Traceback" not in err


def test_forcing_paper_section_writes_figure_9_data_from_eq27(tmp_path):
    """The CSV of figure 9: sigma on a log grid over [0.01, 100], p and 1 - p adding to 1, their
    logs, p against the closed form of eq. (27); the summary's sigma for p = 1e-10 gives it."""
    import csv
    import math

    from symhx.commands.forcing import paper
    from tests.reference.forcing import eq27_p

    lines = paper(tmp_path, False)
    with open(tmp_path / "fig9_p_sigma.csv", newline="") as fh:
        rows = list(csv.reader(fh))
    assert rows[0] == ["sigma", "p", "one_minus_p", "log_p", "log_one_minus_p"]
    body = [[float(v) for v in r] for r in rows[1:]]
    assert len(body) == 161 and body[0][0] == 0.01 and abs(body[-1][0] - 100) < 1e-12
    for s, p, q, lp, lq in body[::20]:
        assert abs(p + q - 1) < 1e-15
        # each log from the smaller of p and 1 - p (log1p near 1; a p that underflows at small
        # sigma keeps its log, checked against eq. 27 below)
        want_lq = math.log1p(-p) if p < 0.5 else math.log(q)
        assert abs(lq - want_lq) <= 1e-14 * abs(lq)
        assert p < 1e-300 or abs(lp - (math.log(p) if p < 0.5 else math.log1p(-q))) \
            <= 1e-14 * abs(lp)
        with mpmath.workdps(40):
            sm = mpmath.mpf(s)
            ref = eq27_p(sm, sm, 1, mpmath.sqrt(2), 1)
            assert rel_err(lp, mpmath.log(ref), 40) < 1e-13
    meta = json.loads((tmp_path / "fig9_p_sigma.json").read_text())
    assert meta["parameters"] == {"sigma1": "sigma", "omega": 1, "Omega": "sqrt(2)", "d": 1}
    # the thresholds at 30 digits in the JSON
    assert len(meta["sigma_at_p_1e-10"].replace(".", "").lstrip("0").split("e")[0]) >= 30
    s_1e10 = mpmath.mpf(next(ln for ln in lines if "p = 1e-10" in ln).split("sigma = ")[1]
                        .split(";")[0])
    assert rel_err(F.impact_probability(s_1e10, dps=20), mpmath.mpf("1e-10"), 20) < 1e-12
