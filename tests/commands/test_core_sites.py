"""``symhx distribution`` and ``symhx critical`` with ``--sites`` (issue 30): the output against
the API, and one-line errors for bad classes."""

from __future__ import annotations

import json
from fractions import Fraction

import mpmath

import symhx
from symhx.cli import main
from symhx.sites import SiteClasses
from tests.reference.mp import rel_err


def run(capsys, *argv):
    rc = main(list(argv))
    captured = capsys.readouterr()
    return rc, captured.out, captured.err


def test_distribution_with_sites_matches_the_api(capsys):
    rc, out, _ = run(capsys, "distribution", "101", "--sites", "wall=2:0.01,pipe=99:0.02",
                     "--json")
    assert rc == 0
    data = json.loads(out)
    sc = SiteClasses((2, 99), ("0.01", "0.02"), names=("wall", "pipe"))
    d = symhx.distribution_of(101, sc)
    assert data["exact"] is True and data["modes"] == list(d.modes())
    assert Fraction(data["mean"]) == d.mean()
    assert data["sites"] == {"sizes": [2, 99], "probabilities": ["1/100", "1/50"],
                             "names": ["wall", "pipe"]}


def test_distribution_with_sites_float_and_text(capsys):
    rc, out, _ = run(capsys, "distribution", "101", "--sites", "2:0.01,99:0.02", "--float",
                     "--dps", "25")
    assert rc == 0 and "sites 2:0.01,99:0.02" in out and "mean" in out
    sc = SiteClasses((2, 99), (Fraction(1, 100), Fraction(1, 50)))
    line = next(ln for ln in out.splitlines() if ln.strip().startswith("mean"))
    shown = line.split("=")[1].split()[0]
    # the mean printed to --dps 25 digits (the mpmath path computes at 35 + guard digits)
    with mpmath.workdps(40):
        assert rel_err(mpmath.mpf(shown), symhx.mean(101, sc)) < mpmath.mpf(10) ** -23


def test_one_class_sites_print_what_p_prints(capsys):
    _, a, _ = run(capsys, "distribution", "101", "0.02", "--json")
    _, b, _ = run(capsys, "distribution", "101", "--sites", "101:0.02", "--json")
    da, db = json.loads(a), json.loads(b)
    db.pop("sites")
    da.pop("p")
    db.pop("p")
    assert da == db


def test_critical_along_the_sites_direction(capsys):
    rc, out, _ = run(capsys, "critical", "1e100", "--sites", "wall=2:1/2,pipe=1e100-2:1",
                     "--json")
    assert rc == 2  # '1e100-2' is not an integer: sizes are exact integers
    N = 10**100
    rc, out, _ = run(capsys, "critical", "1e100", "--sites", f"2:1/2,{N - 2}:1", "--json")
    assert rc == 0
    data = json.loads(out)
    cp = symhx.critical_point(N, weights=SiteClasses((2, N - 2), ("1/2", 1)))
    assert data["k_after"] == str(cp.k_after) and data["method"] == "perturbative"
    with mpmath.workdps(60):
        assert abs(mpmath.mpf(data["p_c"]) - cp.p) <= cp.p * mpmath.mpf(10) ** -49
    rc, out, _ = run(capsys, "critical", "101", "--sites", "2:1/2,99:1")
    assert rc == 0 and "t_c" in out and "mode jumps" in out


def test_bad_sites_are_one_line_errors(capsys):
    for argv in (["distribution", "101", "--sites", "2:0.01,98:0.02"],
                 ["distribution", "101", "0.02", "--sites", "2:0.01,99:0.02"],
                 ["distribution", "101"],
                 ["distribution", "101", "--sites", "2:0.01,99"],
                 ["distribution", "101", "--sites", "2:0,99:1"],
                 ["critical", "101", "--sites", "2:1,98:1"]):
        rc, out, err = run(capsys, *argv)
        assert rc == 2 and out == "" and len(err.strip().splitlines()) == 1, argv
        assert "error" in err and "Traceback" not in err


def test_sites_work_limits_are_the_api_limits(capsys):
    from symhx.site_weights import BALL_TABLE_N_LIMIT

    big = 10 * BALL_TABLE_N_LIMIT
    for argv in (["distribution", str(big), "--sites", f"2:0.5,{big - 2}:0.02", "--float"],
                 ["critical", str(big), "--sites", f"{big // 2}:1,{big // 2}:2"]):
        rc, out, err = run(capsys, *argv)
        assert rc == 2 and out == "" and len(err.strip().splitlines()) == 1, argv
        assert f"BALL_TABLE_N_LIMIT = {BALL_TABLE_N_LIMIT}" in err


def test_a_rest_size_fills_up_to_N(capsys):
    N = 10**100
    rc, out, _ = run(capsys, "critical", "1e100", "--sites", "wall=2:1/2,pipe=rest:1", "--json")
    assert rc == 0
    cp = symhx.critical_point(N, weights=SiteClasses((2, N - 2), ("1/2", 1)))
    assert json.loads(out)["k_after"] == str(cp.k_after)
    _, a, _ = run(capsys, "distribution", "101", "--sites", "2:0.01,rest:0.02", "--json")
    _, b, _ = run(capsys, "distribution", "101", "--sites", "2:0.01,99:0.02", "--json")
    assert a == b
    for sites in ("2:0.01,rest:0.02,rest:1", "100:0.01,2:0.02,rest:1"):
        rc, out, err = run(capsys, "distribution", "101", "--sites", sites)
        assert rc == 2 and out == "" and "--sites" in err and "rest" in err
