"""The mpmath reference engine on exact inputs: rows given as decimal strings are simulated as
those exact rationals, checked against an independent high-precision event-driven solver
(``tests.reference.impact.independent_impacts``: its own closed form per pipe, a dense sign scan
and Anderson's method at 60 digits), and impact times converge as ``dps`` grows."""

from __future__ import annotations

import mpmath
import pytest

from symhx.impact import IMPACT, PipeRow, simulate
from tests.reference.impact import independent_impacts

ONE_PIPE = dict(n=1, omega="1.3", d="0.7", r="0.9", Omega=("0.45",), alpha=[["0.11"]],
                beta=[["-0.07"]], x0=["0.61"], v0=["1.1"], t_end="12")
THREE_PIPES = dict(n=3, omega="1.1", d="1", r="0.85", Omega=("0.3", "2.7"),
                   alpha=[["0.2", "-0.15"], ["-0.1", "0.3"], ["0.25", "0.05"]],
                   beta=[["0.05", "0.1"], ["0.3", "-0.2"], ["-0.15", "0.12"]],
                   x0=["0.9", "2.05", "3.1"], v0=["1.2", "-1.3", "0.9"], t_end="12")


def _row(p):
    return PipeRow(p["n"], omega=p["omega"], d=p["d"], restitution=p["r"], Omega=p["Omega"],
                   alpha=p["alpha"], beta=p["beta"], x0=p["x0"], v0=p["v0"])


@pytest.mark.parametrize("case", [ONE_PIPE, THREE_PIPES], ids=["one-pipe", "three-pipes"])
def test_decimal_row_matches_independent_solution(case):
    ref = independent_impacts(**case)
    assert len(ref) >= 6
    row = _row(case)
    for dps in (30, 60):
        h = simulate(row, case["t_end"], dps=dps)
        assert h.kinds.tolist() == [IMPACT] * len(ref)
        assert h.sites.tolist() == [i for _, i in ref]
        with mpmath.workdps(120):
            err = max(abs(mpmath.mpf(a) - b) for a, (b, _) in zip(h.times, ref, strict=True))
        assert err < mpmath.mpf("1e-28"), (dps, err)


def test_decimal_inputs_are_not_rounded_to_float64():
    # the same row rounded to float64 differs from the decimal row by ~1e-17: the reference
    # engine must see the difference (it answered for the rounded row before)
    row = _row(ONE_PIPE)
    fl = PipeRow(1, omega=1.3, d=0.7, restitution=0.9, Omega=(0.45,), alpha=[[0.11]],
                 beta=[[-0.07]], x0=[0.61], v0=[1.1])
    a = simulate(row, 12, dps=40).times
    b = simulate(fl, 12, dps=40).times
    with mpmath.workdps(100):
        diff = max(abs(mpmath.mpf(x) - y) for x, y in zip(a, b, strict=True))
    assert mpmath.mpf("1e-20") < diff < mpmath.mpf("1e-12")


@pytest.mark.slow
def test_dps_convergence_10_pipes():
    row = PipeRow.random(10, 0.3, seed=11, restitution=1.0)
    h30 = simulate(row, 60.0, dps=30)
    h60 = simulate(row, 60.0, dps=60)
    k = min(100, len(h30))
    assert k >= 100
    assert list(h30.sites[:k]) == list(h60.sites[:k])
    assert max(abs(a - b) for a, b in zip(h30.times[:k], h60.times[:k], strict=False)) < 1e-25
