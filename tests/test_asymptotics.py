"""Large-N asymptotics against the certified exact solver (symhx.critical)."""

from __future__ import annotations

import itertools
import math

import mpmath
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

import symhx
from symhx.asymptotics import (
    ORDERS,
    asymptotic_critical_point,
    error_table,
    format_error_table,
    pd_series,
    pd_series_coefficients,
)

NS = (10**3, 10**6, 10**10, 10**30, 10**100)


@pytest.fixture(scope="module")
def table():
    return error_table(NS, dps=120)


def _err(rows, N, formula):
    (r,) = [r for r in rows if r["N"] == N and r["formula"] == formula]
    return r["rel_error"]


def test_best_meets_the_targets(table):
    assert _err(table, 10**10, "best") < 1e-5
    assert _err(table, 10**100, "best") < 1e-30
    # the explicit corrected formula meets them too
    assert _err(table, 10**10, "corrected") < 1e-5
    assert _err(table, 10**100, "corrected") < 1e-30


@pytest.mark.parametrize("order", ORDERS[:-1])
def test_errors_shrink_as_N_grows(table, order):
    errs = [_err(table, N, order) for N in NS]
    assert all(b < a for a, b in itertools.pairwise(errs)), errs


def test_stated_decay_rates(table):
    for N in NS[1:]:
        L = math.log(N)
        # lambert: O(sqrt(L/N)); corrected: O(L/N); relaxed: O(1/(N L)); next: O((lnL/L)^2)
        assert 0.02 < _err(table, N, "lambert") / math.sqrt(L / N) < 2
        assert 0.005 < _err(table, N, "corrected") / (L / N) < 1
        assert _err(table, N, "relaxed") < 1 / (N * L)
        lam = L - 2
        assert 0.5 < _err(table, N, "next") / (math.log(lam) / (2 * lam**2)) < 2
        assert 0.5 < _err(table, N, "leading") / ((math.log(L) - 1) / (2 * L)) < 2


def test_k_jump_orders(table):
    for N in NS:
        rows = {r["formula"]: r for r in table if r["N"] == N and r["quantity"] == "q"}
        assert rows["best"]["k"] == rows["best"]["k_exact"]
        assert rows["leading"]["k_rel_error"] < 0.05
        if N >= 10**6:
            assert rows["corrected"]["k_rel_error"] < rows["lambert"]["k_rel_error"]


def _rel(a, b):
    """Relative difference evaluated at 200 digits (above every claim checked here)."""
    with mpmath.workdps(200):
        return abs(mpmath.mpf(a) / mpmath.mpf(b) - 1)


@settings(max_examples=30, deadline=None)
@given(st.integers(21, 10**7))
def test_best_equals_exact_solver(n):
    cp = symhx.critical_point(n, dps=40)
    a = asymptotic_critical_point(n, dps=40)
    assert a.k == cp.k_after
    assert _rel(a.q, cp.q) < mpmath.mpf(10) ** -38
    assert _rel(a.p, cp.p) < mpmath.mpf(10) ** -38


@settings(max_examples=15, deadline=None)
@given(st.integers(10**12, 10**60) | st.integers(10**60, 10**250))
def test_best_equals_exact_solver_huge(n):
    cp = symhx.critical_point(n, dps=40)
    a = asymptotic_critical_point(n, dps=40)
    assert a.k == cp.k_after and _rel(a.q, cp.q) < mpmath.mpf(10) ** -38


def test_best_integer_for_every_power_of_ten():
    # issue 11: the 'best' integer is the certified one for N = 10**k, k = 2..300
    for e in range(2, 301):
        N = 10**e
        a = asymptotic_critical_point(N, dps=20)
        assert a.k == symhx.critical_point(N, dps=20).k_after, e


def test_stated_precision_is_met_not_vacuous():
    # the relative error claims are checked at 200 digits: a one-term Stirling series or
    # a wrong guard would show here (at mpmath's default 15 digits every difference is 0)
    N = 10**30
    cp = symhx.critical_point(N, dps=150)
    for order, claim in (("best", 100), ("relaxed", 31)):  # relaxed: O(1/(N ln N))
        a = asymptotic_critical_point(N, order=order, dps=110)
        assert _rel(a.q, cp.q) < mpmath.mpf(10) ** -claim, order
    b = asymptotic_critical_point(10**5, dps=110)
    assert _rel(b.q, symhx.critical_point(10**5, dps=150).q) < mpmath.mpf(10) ** -100


def test_pd_series_coefficients_match_sympy():
    from symhx.symbolic.asymptotic import pd_series_coefficients as sym_coeffs

    ours = pd_series_coefficients(8)
    theirs = sym_coeffs(8)
    assert [(pw, c.numerator, c.denominator) for pw, c in ours] == [
        (pw, int(c.p), int(c.q)) for pw, c in theirs]


@pytest.mark.parametrize("n_terms", [1, 2, 3, 4, 5, 6, 8])
@pytest.mark.parametrize("N", [2, 3, 7, 10**3, 10**9])
def test_pd_series_bound_is_rigorous(N, n_terms):
    s = pd_series(N, n_terms, dps=120)
    with mpmath.workdps(120):
        exact = symhx.discriminant_root(N, dps=120)
        err = abs(exact - s.value)
        assert err <= s.bound * (1 + mpmath.mpf(10) ** -40)
        if N >= 10**3:  # and the bound is the actual size of the error (within 2x)
            assert err >= s.bound / 2


def test_lambert_matches_symbolic_formula():
    import sympy as sp

    from symhx.symbolic import N as Ns
    from symhx.symbolic import derivation

    k0, q0 = derivation("pc-lambert").result.rhs
    fk = sp.lambdify(Ns, k0, "mpmath")
    fq = sp.lambdify(Ns, q0, "mpmath")
    for n in (10**3, 10**8, 10**40):
        a = asymptotic_critical_point(n, order="lambert", dps=40)
        with mpmath.workdps(40):
            k_sym, q_sym = fk(mpmath.mpf(n)).real, mpmath.expm1(fq(mpmath.mpf(n)).real)
        assert _rel(k_sym, a.k) < mpmath.mpf(10) ** -30
        assert _rel(q_sym, a.q) < mpmath.mpf(10) ** -30


def test_bad_input():
    with pytest.raises(ValueError):
        asymptotic_critical_point(20)
    with pytest.raises(ValueError):
        asymptotic_critical_point(1000, order="nonsense")
    with pytest.raises(TypeError):
        asymptotic_critical_point(1e10)


def test_format_error_table(table):
    text = format_error_table(table)
    assert text.splitlines()[0].startswith("| N | leading")
    assert "1e100" in text


def test_public_export_and_result_fields():
    a = asymptotic_critical_point(10**4, order="next")
    assert a.order == "next" and isinstance(a.k_int, int) and a.decay
    d = a.as_dict()
    assert set(d) >= {"N", "order", "p", "q", "k"}


def test_error_table_validates_sequences():
    from symhx.asymptotics import error_table

    for kw in (dict(Ns=""), dict(orders=""), dict(orders="best"), dict(Ns=(1000.5,)),
               dict(orders=("nope",)), dict(pd_terms=0), dict(dps=0), dict(Ns=None)):
        with pytest.raises((ValueError, TypeError)):
            error_table(**{**dict(Ns=(1000,), dps=20, orders=("leading",), pd_terms=2), **kw})
    assert error_table((), dps=20) == []
