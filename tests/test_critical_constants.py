"""The regression table of derived constants (symhx/data/constants.json, written by
scripts/make_constants.py), read through symhx.critical: a change in the 45th significant digit
fails, and every row is re-derived independently (tests.reference.critical)."""

import json
from importlib import resources

import mpmath
import pytest

import symhx
from tests.reference.critical import is_first_argmin, p_c_direct, p_d_closed

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


@pytest.mark.parametrize("row", ROWS, ids=[r["N"][:12] for r in ROWS])
def test_every_row_rederived_independently(row):
    # the stored table is checked against an independent method for every row: p_c, N p_c - 1
    # and p_d from their definitions with mpmath's loggamma at 3x the digits (no symhx code)
    N, k = int(row["N"]), int(row["argmins"][0])
    digits = TABLE["digits"]
    assert is_first_argmin(N, k)
    pc = p_c_direct(N, k, digits)
    with mpmath.workdps(3 * digits + 2 * len(str(N)) + 20):
        ref = {"p_c": pc, "N_p_c_minus_1": N * pc - 1, "p_d": p_d_closed(N, 3 * digits)[0]}
    with mpmath.workdps(3 * digits):
        tol = mpmath.mpf(10) ** -(digits - 2)
        for key in ("p_c", "N_p_c_minus_1", "p_d"):
            stored = mpmath.mpf(row[key])
            assert abs(stored - ref[key]) <= tol * abs(ref[key]), (key, N)
        lo, hi = mpmath.mpf(row["p_c_lo"]), mpmath.mpf(row["p_c_hi"])
        # the reference is good to ~10**-150; the slack 10**-100 is far below the width claim
        slack = mpmath.mpf(10) ** -100 * ref["p_c"]
        assert lo - slack <= ref["p_c"] <= hi + slack
        assert (hi - lo) <= mpmath.mpf(10) ** -50 * ref["p_c"]
