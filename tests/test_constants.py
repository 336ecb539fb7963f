"""Regression table of derived constants (symhx/data/constants.json, written by
scripts/make_constants.py): a change in the 45th significant digit fails."""

import json
from importlib import resources

import mpmath
import pytest

import symhx

TABLE = json.loads(resources.files("symhx").joinpath("data/constants.json").read_text())
ROWS = TABLE["rows"]


def test_table_covers_the_range():
    Ns = [int(r["N"]) for r in ROWS]
    assert min(Ns) == 2 and max(Ns) >= 10**100 and TABLE["digits"] >= 50


@pytest.mark.parametrize("row", ROWS, ids=[r["N"][:12] for r in ROWS])
def test_constants_unchanged(row):
    N = int(row["N"])
    cp = symhx.critical_point(N, dps=55)
    assert cp.k_after == int(row["k_after"])
    assert [str(k) for k in cp.argmins] == row["argmins"]
    with mpmath.workdps(80):
        tol = mpmath.mpf(10) ** -47
        for key, val in (("p_d", cp.p_d), ("p_c", cp.p), ("N_p_c_minus_1", cp.q)):
            stored = mpmath.mpf(row[key])
            assert abs(val - stored) <= tol * abs(stored), (key, N)
