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


def _independent_row(N: int, k: int, digits: int) -> dict[str, mpmath.mpf]:
    """p_c, N p_c - 1 and p_d of one row from the definitions with mpmath's loggamma at 3x the
    digits (plus 2 log10 N guard digits for the cancellation): no symhx code involved."""
    d = len(str(N))
    with mpmath.workdps(3 * digits + 2 * d + 20):
        Nm = mpmath.mpf(N)
        s = (mpmath.log(k) + mpmath.loggamma(N - k + 1) - mpmath.loggamma(Nm)) / (k - 1)
        pc = mpmath.exp(s)
        pd = ((1 + mpmath.sqrt(Nm + 1)) / Nm) ** 2
        return {"p_c": pc, "N_p_c_minus_1": Nm * pc - 1, "p_d": pd}


def _is_argmin(N: int, k: int) -> bool:
    """k is the first argmin of c_j: exhaustively for small N, else c_{k-1} > c_k <= c_{k+1}
    (at a precision resolving the ~1/k**2 relative gaps) plus the proved unimodality."""
    def log_c(j: int, dps: int) -> mpmath.mpf:
        with mpmath.workdps(dps + 2 * len(str(N)) + 20):
            return (mpmath.log(j) + mpmath.loggamma(N - j + 1) - mpmath.loggamma(N)) / (j - 1)

    if N <= 400:
        vals = [log_c(j, 60) for j in range(2, N + 1)]
        with mpmath.workdps(80):
            best = min(vals)
            first = next(i for i, v in enumerate(vals) if v - best <= mpmath.mpf(10) ** -55)
        return k == first + 2
    dps = 40 + 2 * len(str(k))
    a, b, c = (log_c(j, dps) for j in (k - 1, k, k + 1))
    with mpmath.workdps(dps + 2 * len(str(N)) + 20):
        return a > b and c > b


@pytest.mark.parametrize("row", ROWS, ids=[r["N"][:12] for r in ROWS])
def test_every_row_rederived_independently(row):
    # issue 16: the golden table is checked against an independent method for EVERY row
    N, k = int(row["N"]), int(row["argmins"][0])
    assert _is_argmin(N, k)
    ref = _independent_row(N, k, TABLE["digits"])
    with mpmath.workdps(3 * TABLE["digits"]):
        tol = mpmath.mpf(10) ** -(TABLE["digits"] - 2)
        for key in ("p_c", "N_p_c_minus_1", "p_d"):
            stored = mpmath.mpf(row[key])
            assert abs(stored - ref[key]) <= tol * abs(ref[key]), (key, N)
        lo, hi = mpmath.mpf(row["p_c_lo"]), mpmath.mpf(row["p_c_hi"])
        # the reference is good to ~10**-150; the slack 10**-100 is far below the width claim
        slack = mpmath.mpf(10) ** -100 * ref["p_c"]
        assert lo - slack <= ref["p_c"] <= hi + slack
        assert (hi - lo) <= mpmath.mpf(10) ** -50 * ref["p_c"]
