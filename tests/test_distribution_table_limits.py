"""The row limits of ``table()`` (``MAX_TABLE_N``, ``MAX_EXACT_TABLE_N``, ``FLOAT_N_LIMIT``):
refused before any work, by name, with N shown, for every space, and the CLI's ``--table`` the
same; below them the table is the pmf at every k."""

from __future__ import annotations

import time
from fractions import Fraction

import pytest

import symhx
from symhx.distribution import FLOAT_N_LIMIT, MAX_EXACT_TABLE_N, MAX_TABLE_N
from symhx.spaces import MAX_SPACE_WORK
from tests.harness.errors import assert_refuses


@pytest.mark.parametrize(("N", "p", "dps", "name"), [
    (MAX_TABLE_N + 1, 0.001, 30, "MAX_TABLE_N"),
    (10**100, 0.1, 50, "MAX_TABLE_N"),
    (MAX_EXACT_TABLE_N + 1, "0.001", 50, "MAX_EXACT_TABLE_N"),
    (FLOAT_N_LIMIT + 1, 0.5, None, "FLOAT_N_LIMIT"),
])
def test_table_beyond_its_row_limit_is_refused_at_once(N, p, dps, name) -> None:
    t = time.monotonic()
    for space in ("simple", "eq41"):
        if space == "eq41" and 4 * N > MAX_SPACE_WORK:   # the space's own work limit comes first
            assert_refuses(symhx.distribution_of, N, p, dps=dps, space=space, arg="N",
                           allowed="MAX_SPACE_WORK")
            continue
        d = symhx.distribution_of(N, p, dps=dps, space=space)
        assert_refuses(d.table, arg="N", value="N=", allowed=[name, "N <= "])
    assert time.monotonic() - t < 2


def test_table_lists_the_pmf_at_every_k() -> None:
    for p, dps in (("1/7", 50), (0.13, 30), (0.13, None)):
        d = symhx.distribution_of(40, p, dps=dps)
        rows = d.table()
        assert [k for k, _ in rows] == list(range(1, 41))
        assert all(v == d.pmf(k) for k, v in rows)
    exact = symhx.distribution_of(40, "1/7").table()
    assert sum(v for _, v in exact) == 1 and all(isinstance(v, Fraction) for _, v in exact)


def test_cli_table_beyond_the_row_limit_names_the_option(capsys) -> None:
    from symhx.cli import main

    t = time.monotonic()
    assert main(["distribution", "1e100", "0.1", "--table"]) == 2
    err = capsys.readouterr().err
    assert "--table" in err and "MAX_TABLE_N" in err and "N=10**100" in err
    assert main(["distribution", str(MAX_EXACT_TABLE_N + 1), "1/1000", "--table"]) == 2
    assert "MAX_EXACT_TABLE_N" in capsys.readouterr().err
    assert time.monotonic() - t < 2


def test_the_float_table_limit_is_inclusive(monkeypatch) -> None:
    """``N <= FLOAT_N_LIMIT`` has the float64 table (read at call time: a lowered limit here);
    one more is answered without it, to the same float64 values."""
    import symhx.distribution as dist

    monkeypatch.setattr(dist, "FLOAT_N_LIMIT", 1000)
    at = symhx.distribution_of(1000, 0.01, dps=None)
    assert len(at.table()) == 1000
    above = symhx.distribution_of(1001, 0.01, dps=None)
    assert_refuses(above.table, arg="N", value="N=", allowed="FLOAT_N_LIMIT")
    ref = symhx.distribution_of(1001, 0.01, dps=30)
    for d, r in ((at, symhx.distribution_of(1000, 0.01, dps=30)), (above, ref)):
        assert abs(d.mean() - float(r.mean())) <= 1e-12 * float(r.mean())
        assert abs(d.var() - float(r.var())) <= 1e-11 * float(r.var())
        assert abs(d.entropy() - float(r.entropy())) <= 1e-12 * float(r.entropy())
        assert d.isf(0.25) == r.isf(0.25) and d.ppf(0.25) == r.ppf(0.25)
