"""Closed forms of symhx.spaces.symbolic against exact counts and brute force."""

from __future__ import annotations

import sympy as sp

from symhx.circuits import brute_force_pattern_counts, circuit_count, partitions
from symhx.spaces import (
    boundary_table,
    class_count,
    class_count_symbolic,
    convergence_study,
    pattern_count_symbolic,
    printed_count,
    printed_formula,
    verify_printed_formulas,
)


def test_pattern_count_symbolic_matches_brute_force():
    for L in range(1, 7):
        exprs = {v: pattern_count_symbolic(v) for v in partitions(L)}
        for N in range(1, 6):
            brute = brute_force_pattern_counts(N, L)
            for v, e in exprs.items():
                (Nsym,) = e.free_symbols or {sp.Symbol("N")}
                assert int(e.subs(Nsym, N)) == brute.get(v, 0) == circuit_count(N, v)


def test_class_count_symbolic_in_range():
    for shape in [(2,), (3,), (2, 2), (4,), (3, 2), (2, 2, 2)]:
        e = class_count_symbolic(shape)
        N, L = sorted(e.free_symbols, key=str)[::-1][0], sorted(e.free_symbols, key=str)[0]
        for n in range(2, 9):
            for length in range(sum(shape) + 1, n + sum(x - 1 for x in shape) + 1):
                k = length - sum(x - 1 for x in shape)
                assert e.subs({N: n, L: length}) == class_count(n, shape, k)


def test_printed_formulas_recovered_and_boundaries():
    assert all(verify_printed_formulas().values())
    for eq in ("35", "38", "39", "40"):
        f = printed_formula(eq)
        syms = {s.name: s for s in f.free_symbols}
        assert f.subs({syms["N"]: 9, syms["L"]: 7}) == printed_count(eq, 9, 7)
    rows = boundary_table(7)
    assert [r["true"] for r in rows] == [7, 7, 7, 42]
    assert [r["correction"] for r in rows] == [sp.Rational(7, 2), sp.Rational(14, 3),
                                               sp.Rational(21, 4), sp.Rational(21, 2)]


def test_convergence_study_monotone_in_m():
    rows = convergence_study(30, ms=range(0, 4), ps=["0.02", "0.05"], extra=("eq41",), dps=15)
    pcs = [r.p_c for r in rows[:4]]
    assert pcs == sorted(pcs, reverse=True)  # more classes, earlier jump
    for p in ("0.02", "0.05"):
        means = [r.means[p] for r in rows[:4]]
        assert means == sorted(means)


def test_convergence_study_validates_before_work():
    import time

    import pytest

    from symhx.spaces import MAX_EXCESS
    from symhx.spaces.study import STUDY_N_LIMIT

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
    import numpy as np

    rows = convergence_study(**{**good, "ms": np.array([0, 1]), "weighting": "distinct"})
    assert [r.space for r in rows] == ["excess<=0;distinct", "excess<=1;distinct"]
