"""Closed forms of the class counts as sympy expressions (``symhx.spaces.symbolic``, eqs. 35-40)
against exact counts and brute force, and the paper's printed formulas beside them."""

from __future__ import annotations

import pytest

from symhx.circuits import brute_force_pattern_counts, circuit_count, partitions
from symhx.spaces import (
    boundary_table,
    class_count,
    class_count_symbolic,
    pattern_count_symbolic,
    printed_count,
    printed_formula,
    verify_printed_formulas,
)

sp = pytest.importorskip("sympy")


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
    checked = verify_printed_formulas()
    assert sorted(checked) == ["35", "36", "38", "39", "40"] and all(checked.values())
    for eq in ("35", "38", "39", "40"):
        f = printed_formula(eq)
        syms = {s.name: s for s in f.free_symbols}
        assert f.subs({syms["N"]: 9, syms["L"]: 7}) == printed_count(eq, 9, 7)
    rows = boundary_table(7)
    assert [r["true"] for r in rows] == [7, 7, 7, 42]
    assert [r["correction"] for r in rows] == [sp.Rational(7, 2), sp.Rational(14, 3),
                                               sp.Rational(21, 4), sp.Rational(21, 2)]
    # the symbolic table: the same rows as expressions in N alone (the boundary length
    # substituted), equal to the exact table at every N tried
    sym = boundary_table()
    assert [r["eq"] for r in sym] == [r["eq"] for r in rows] == ["35", "38", "39", "40"]
    for r in sym:
        assert {s.name for s in r["formula"].free_symbols} == {"N"}
    for N in (7, 12, 30):
        exact = boundary_table(N)
        for r, e in zip(sym, exact, strict=True):
            (Ns,) = r["formula"].free_symbols
            assert (r["class"], r["length"]) == (e["class"], e["length"])
            assert r["formula"].subs(Ns, N) == e["formula"]
            assert r["true"].subs(Ns, N) == e["true"]
            assert r["correction"].subs(Ns, N) == e["correction"]
