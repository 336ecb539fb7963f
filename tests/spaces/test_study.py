"""``convergence_study`` (``symhx.spaces.study``): the jump ``p_c -> k_after`` and ``E[X]`` of
each truncated space ``excess<=m`` and of eq. (41), against independent references; its
defaults, its work limit ``STUDY_N_LIMIT`` and its refusals, checked before any work.

References (:mod:`tests.reference.spaces`): ``p_c`` from bisection roots of the Burnside weight
polynomials, ``E[X]`` from exact Fractions of the same weights, exhaustive argmax scans.
"""

from __future__ import annotations

import array
import time
from fractions import Fraction

import mpmath
import numpy as np
import pytest

from symhx.spaces import MAX_EXCESS, convergence_study
from symhx.spaces.study import DEFAULT_PS, STUDY_N_LIMIT, ConvergenceRow
from tests.harness.errors import assert_refuses
from tests.reference.distribution import to_mp
from tests.reference.spaces import argmax, exact_table, roots


def _exact_mean(N: int, base: str, w: str, p: Fraction) -> Fraction:
    return exact_table(N, p, base if w == "length" else f"{base};distinct").mean


@pytest.mark.parametrize("w", ["length", "distinct"])
def test_rows_against_references(w):
    sympy = pytest.importorskip("sympy")
    N, dps = 12, 20
    ps = ["0.01", Fraction(1, 20), 0.03, sympy.Rational(3, 40), "1/3"]
    exact_ps = [Fraction(1, 100), Fraction(1, 20), Fraction(0.03), Fraction(3, 40),
                Fraction(1, 3)]
    rows = convergence_study(N, ms=[0, 1, 3], ps=ps, dps=dps, weighting=w)
    suffix = "" if w == "length" else ";distinct"
    bases = ("excess<=0", "excess<=1", "excess<=3", "eq41", "eq41-printed")
    assert [r.space for r in rows] == [f"{s}{suffix}" for s in bases]
    for r, base in zip(rows, bases, strict=True):
        assert isinstance(r, ConvergenceRow)
        with mpmath.workdps(60):
            pc = min(roots(N, base, w).values())
            assert abs(r.p_c - pc) <= mpmath.mpf(10) ** (1 - dps) * pc, r.space
        # the jump lands on the exact argmax just above p_c
        above = Fraction(mpmath.nstr(pc * (1 + mpmath.mpf(10) ** -15), 40))
        assert (r.k_after,) == argmax(N, base, above, w)
        assert list(r.means) == ps
        for p, fr in zip(ps, exact_ps, strict=True):
            ref = _exact_mean(N, base, w, fr)
            with mpmath.workdps(60):
                assert abs(r.means[p] - to_mp(ref)) <= mpmath.mpf(10) ** (1 - dps) * to_mp(
                    ref), (base, p)
        d = r.as_dict()
        assert d == {"space": r.space, "p_c": r.p_c, "k_after": r.k_after, "means": r.means}
        assert d["means"] is not r.means


def test_dps_60_reaches_the_critical_point_and_means():
    """dps is passed on to the critical-point search and to the distributions (60 is above
    their default 50)."""
    sympy = pytest.importorskip("sympy")
    N, dps, base, w = 12, 60, "excess<=1", "length"
    p_irr = sympy.sqrt(2) / 40
    with mpmath.workdps(100):
        p_fr = Fraction(mpmath.nstr(mpmath.sqrt(2) / 40, 90))
    rows = convergence_study(N, ms=[1], ps=["0.05", p_irr], extra=(), dps=dps)
    r, = rows
    with mpmath.workdps(70):  # the reference roots have 62 digits
        pc = min(roots(N, base, w).values())
        assert abs(r.p_c - pc) <= mpmath.mpf(10) ** (1 - dps) * pc
        for p, fr in (("0.05", Fraction(1, 20)), (p_irr, p_fr)):
            refm = to_mp(_exact_mean(N, base, w, fr))
            assert abs(r.means[p] - refm) <= mpmath.mpf(10) ** (1 - dps) * refm, p


def test_convergence_study_monotone_in_m():
    rows = convergence_study(30, ms=range(0, 4), ps=["0.02", "0.05"], extra=("eq41",), dps=15)
    pcs = [r.p_c for r in rows[:4]]
    assert pcs == sorted(pcs, reverse=True)  # more classes, earlier jump
    for p in ("0.02", "0.05"):
        means = [r.means[p] for r in rows[:4]]
        assert means == sorted(means)


def test_defaults_and_empty_ms():
    assert DEFAULT_PS == ("0.005", "0.01", "0.015", "0.04", "0.05")
    rows = convergence_study(10, ms=range(0), ps=["0.05"], extra=("eq41",), dps=15)
    assert [r.space for r in rows] == ["eq41"]
    rows = convergence_study(10, ms=np.array([2]), ps=("0.05",), extra=[], dps=15)
    assert [r.space for r in rows] == ["excess<=2"]


def test_defaults_are_N_100_and_dps_20():
    # the documented defaults: the same rows as with N=100, dps=20 spelled out, and not dps=21
    kw = dict(ms=[0], ps=["0.05"], extra=())
    rows = convergence_study(**kw)
    assert rows == convergence_study(100, dps=20, **kw)
    assert rows != convergence_study(101, dps=20, **kw)
    assert rows[0].p_c != convergence_study(100, dps=21, **kw)[0].p_c


def test_limit_is_inclusive_and_shown_exactly():
    rows = convergence_study(STUDY_N_LIMIT, ms=[0], ps=["0.05"], extra=(), dps=15)
    assert [r.space for r in rows] == ["excess<=0"] and 0 < rows[0].p_c < mpmath.mpf("0.05")
    good = dict(ms=(0,), ps=("0.01",), dps=15, extra=())
    assert_refuses(convergence_study, 10**15, **good, arg="N", value="N=~10**15",
                   allowed=f"N <= {STUDY_N_LIMIT}")


def test_convergence_study_validates_before_work():
    good = dict(N=20, ms=(0,), ps=("0.01",), dps=15, extra=())
    bad = [dict(ms=""), dict(ps=""), dict(ps=[]), dict(weighting=None), dict(weighting="abc"),
           dict(N=STUDY_N_LIMIT + 1), dict(ms=range(10**1000)), dict(ms=(MAX_EXCESS + 1,)),
           dict(ms=(-1,)), dict(ps=("nan",)), dict(extra=("simple",)), dict(dps=0)]
    t = time.monotonic()
    for kw in bad:
        with pytest.raises((ValueError, TypeError)):
            convergence_study(**{**good, **kw})
    assert time.monotonic() - t < 1
    # valid: a numpy array of m and the distinct weighting are accepted, one row per m
    rows = convergence_study(**{**good, "ms": np.array([0, 1]), "weighting": "distinct"})
    assert [r.space for r in rows] == ["excess<=0;distinct", "excess<=1;distinct"]


def test_refusals_name_the_limits():
    good = dict(N=20, ms=(0,), ps=("0.01",), dps=15, extra=())
    assert_refuses(convergence_study, **{**good, "N": STUDY_N_LIMIT + 1}, arg="N",
                   value=f"N={STUDY_N_LIMIT + 1}",
                   allowed=[f"N <= {STUDY_N_LIMIT}", "STUDY_N_LIMIT"])
    assert_refuses(convergence_study, **{**good, "N": 10**20}, arg="N", value="N=~10**20",
                   allowed=f"N <= {STUDY_N_LIMIT}")
    assert_refuses(convergence_study, **{**good, "N": 10**15 - 1}, arg="N",
                   value="N=999999999999999", allowed=f"N <= {STUDY_N_LIMIT}")
    for ms in (range(MAX_EXCESS + 5, 0, -1), range(0, MAX_EXCESS + 2)):
        assert_refuses(convergence_study, **{**good, "ms": ms}, arg="ms", value="range(",
                       allowed=[f"m <= {MAX_EXCESS}", "MAX_EXCESS"])
    assert convergence_study(**{**good, "ms": range(MAX_EXCESS, MAX_EXCESS - 1, -1),
                                "N": 3})[0].space == f"excess<={MAX_EXCESS}"
    assert_refuses(convergence_study, **{**good, "ps": ()}, arg="ps", value="got none",
                   allowed="at least one p")
    assert_refuses(convergence_study, **{**good, "ms": np.zeros((2, 2), dtype=int)},
                   exc=TypeError, arg="ms", value="got None", allowed="a list, tuple or range")
    assert_refuses(convergence_study, **{**good, "ps": "0.01"}, exc=TypeError, arg="ps",
                   value="'0.01'", allowed="a list, tuple or range")
    assert_refuses(convergence_study, **{**good, "extra": "eq41"}, exc=TypeError, arg="extra",
                   value="'eq41'", allowed="a list, tuple or range")


def test_refusals_name_the_argument():
    good = dict(N=10, ms=(0,), ps=("0.01",), dps=15, extra=())
    assert_refuses(convergence_study, **{**good, "ms": array.array("i", [0])}, exc=TypeError,
                   arg="ms", value="array('i', [0])",  # tolist() but no ndim
                   allowed="a list, tuple or range")
    for kw, arg, value, allowed in [
            ({"weighting": "x"}, "weighting", "'x'", "one of ['length', 'distinct']"),
            ({"ms": [-1]}, "each maximum excess m of ms", "got -1", ">= 0"),
            ({"ms": [MAX_EXCESS + 1]}, "each maximum excess m of ms", f"got {MAX_EXCESS + 1}",
             f"<= {MAX_EXCESS}"),
            ({"ps": ["0.01", "-1"]}, "each p of ps", "'-1'", "> 0"),
            ({"extra": ["x"]}, "each extra space", "'x'", "one of ['eq41', 'eq41-printed']"),
            ({"ps": []}, "ps", "got none", "at least one p value (decimal strings)")]:
        assert_refuses(convergence_study, **{**good, **kw}, arg=arg, value=value,
                       allowed=allowed)
