"""symhx.asymptotics against independent references (tests.reference.critical): the exact
(certified) solver symhx.critical_point, binomial coefficients from math.comb, p_d from its
closed form, the formulas written out from their definitions (Lambert value by Newton), the
relaxation from mpmath's loggamma / digamma at 3x the digits with a numerical minimiser, the
integer argmin by exact integer comparison; every comparison done inside ``workdps`` above the
claim. The cost of the relaxed bracket is in ``tests/perf/test_asymptotics_cost.py``."""

from __future__ import annotations

import inspect
import itertools
import math
import subprocess
import sys
from fractions import Fraction

import mpmath
import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

import symhx
from symhx import asymptotics as A
from symhx._mpctx import export, local, mp
from symhx.asymptotics import (
    DECAY,
    ORDERS,
    asymptotic_critical_point,
    error_table,
    format_error_table,
    pd_series,
    pd_series_coefficients,
)
from tests.harness.errors import assert_refuses
from tests.reference.critical import (
    G_loggamma,
    asymptotic_formula,
    asymptotic_k,
    binom_half,
    dG_digamma,
    exact_argmins,
    p_d_closed,
    relaxed_minimum,
)
from tests.reference.mp import rel_err

NS = (10**3, 10**6, 10**10, 10**30, 10**100)


@pytest.fixture(scope="module")
def table():
    return error_table(NS, dps=120)


def _err(rows, N, formula):
    (r,) = [r for r in rows if r["N"] == N and r["formula"] == formula]
    return r["rel_error"]


# --------------------------------------------------------------------------- the orders' errors
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


@settings(max_examples=30, deadline=None)
@given(st.integers(21, 10**7))
def test_best_equals_exact_solver(n):
    cp = symhx.critical_point(n, dps=40)
    a = asymptotic_critical_point(n, dps=40)
    assert a.k == cp.k_after
    assert rel_err(a.q, cp.q, dps=200) < mpmath.mpf(10) ** -38
    assert rel_err(a.p, cp.p, dps=200) < mpmath.mpf(10) ** -38


@settings(max_examples=15, deadline=None)
@given(st.integers(10**12, 10**60) | st.integers(10**60, 10**250))
def test_best_equals_exact_solver_huge(n):
    cp = symhx.critical_point(n, dps=40)
    a = asymptotic_critical_point(n, dps=40)
    assert a.k == cp.k_after and rel_err(a.q, cp.q, dps=200) < mpmath.mpf(10) ** -38


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
        assert rel_err(a.q, cp.q, dps=200) < mpmath.mpf(10) ** -claim, order
    b = asymptotic_critical_point(10**5, dps=110)
    assert rel_err(b.q, symhx.critical_point(10**5, dps=150).q, dps=200) < mpmath.mpf(10) ** -100


@pytest.mark.parametrize("N", [21, 1000, 10**8, 10**50])
@pytest.mark.parametrize("dps", [20, 90])
def test_formula_orders(N, dps):
    for order in ("leading", "next", "lambert", "corrected"):
        k, q = asymptotic_formula(N, order, dps)
        a = asymptotic_critical_point(N, order=order, dps=dps)
        assert a.order == order and a.N == N and a.dps == dps and a.decay == DECAY[order]
        claim = mpmath.mpf(10) ** (1 - dps)
        with mpmath.workdps(3 * dps + 20):
            assert rel_err(a.q, q, dps=3 * dps) <= claim, (order, "q")
            assert rel_err(a.p, (1 + q) / N, dps=3 * dps) <= claim, (order, "p")
            # the corrected k uses a closed-form derivative, the reference a numerical one
            assert rel_err(a.k, k, dps=3 * dps) <= (claim if order != "corrected" else
                                                    mpmath.mpf(10) ** (5 - dps)), (order, "k")
        assert isinstance(a.k_int, int)
        with mpmath.workdps(3 * dps + 20):  # the nearest integer of k, up to k's own rounding
            assert abs(a.k_int - k) <= mpmath.mpf("0.5") + claim * k


@pytest.mark.parametrize("N", [21, 22, 57, 400, 1000, 9999])
@pytest.mark.parametrize("dps", [15, 60])
def test_relaxed_and_best_small_N(N, dps):
    kap, qrel, h = relaxed_minimum(N, dps)
    a = asymptotic_critical_point(N, order="relaxed", dps=dps)
    claim = mpmath.mpf(10) ** (1 - dps)
    assert rel_err(a.q, qrel, dps=3 * dps) <= claim
    assert rel_err(a.k, kap, dps=3 * dps) <= mpmath.mpf(10) ** (2 - dps)
    assert a.k_int == int(mpmath.nint(kap))
    b = asymptotic_critical_point(N, dps=dps)
    if N < 100:
        k = exact_argmins(N)[-1]  # the largest argmin, by exact integers
        assert b.k == k
    k = b.k
    assert b.k_int == k and isinstance(b.k, int)
    with mpmath.workdps(3 * dps + 40):
        vals = [h(mpmath.mpf(k + i)) for i in (-1, 0, 1)]
        assert vals[1] < vals[0] and vals[1] <= vals[2]  # with the proved unimodality
        qbest = mpmath.expm1(vals[1])
        pbest = (1 + qbest) / N
    assert rel_err(b.q, qbest, dps=3 * dps) <= claim
    assert rel_err(b.p, pbest, dps=3 * dps) <= claim


@pytest.mark.parametrize("N", [10**4, 123457, 10**9, 10**25])
@pytest.mark.parametrize("dps", [20, 100])
def test_relaxed_and_best_large_N(N, dps):
    kap, qrel, h = relaxed_minimum(N, dps)
    a = asymptotic_critical_point(N, order="relaxed", dps=dps)
    claim = mpmath.mpf(10) ** (1 - dps)
    assert rel_err(a.q, qrel, dps=3 * dps) <= claim
    assert rel_err(a.k, kap, dps=3 * dps) <= mpmath.mpf(10) ** (2 - dps)
    b = asymptotic_critical_point(N, dps=dps)
    # the integer argmin beats both neighbours (loggamma at 3x dps; unimodality is proved)
    with mpmath.workdps(3 * dps + 2 * len(str(N)) + 40):
        vals = [h(mpmath.mpf(b.k + i)) for i in (-1, 0, 1)]
        assert vals[1] < vals[0] and vals[1] <= vals[2]
        qbest = mpmath.expm1(vals[1])
        pbest = (1 + qbest) / N
    assert rel_err(b.q, qbest, dps=3 * dps) <= claim
    assert rel_err(b.p, pbest, dps=3 * dps) <= claim
    assert abs(b.k - kap) < 1


@pytest.mark.parametrize("N", [1000, 10**10])
@pytest.mark.parametrize("dps", [20, 45])
@pytest.mark.parametrize("order", ["leading", "next", "lambert", "relaxed"])
def test_real_k_is_returned_at_the_requested_digits(order, N, dps):
    """A real ``k`` is rounded to ``dps`` digits like ``p`` and ``q`` (not handed back with
    the 15+ guard digits of the working precision), and is right to those digits."""
    a = asymptotic_critical_point(N, order=order, dps=dps)
    with mpmath.workdps(dps):
        assert +a.k == a.k and +a.p == a.p and +a.q == a.q
    with mpmath.workdps(3 * dps):
        assert abs(a.k / asymptotic_k(N, order, dps) - 1) < mpmath.mpf(10) ** (1 - dps)


@pytest.mark.parametrize("N", [10**40, 10**100, 10**1000], ids=["1e40", "1e100", "1e1000"])
@pytest.mark.parametrize("order", ["leading", "next", "lambert", "relaxed"])
def test_k_int_is_the_integer_nearest_k_at_low_dps(order, N):
    """``k`` has about log10(N)/2 integer digits, more than dps = 15 here: ``k_int`` must still
    be the integer nearest the real ``k`` (it was the nearest integer of ``k`` cut to 15
    digits: off by 51452 at N = 10**40 and by ~1e35 at N = 10**100)."""
    a = asymptotic_critical_point(N, order=order, dps=15)
    digits = len(str(N))
    ref = asymptotic_k(N, order, digits // 6 + 10)  # 3 * dps + 20 >= log10(N)/2 + 50 digits
    with mpmath.workdps(digits + 50):
        nearest = mpmath.nint(ref)
        assert abs(ref - nearest) < mpmath.mpf(0.499)  # not a half-integer tie
        assert a.k_int == int(nearest)


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
        assert rel_err(k_sym, a.k, dps=200) < mpmath.mpf(10) ** -30
        assert rel_err(q_sym, a.q, dps=200) < mpmath.mpf(10) ** -30



# --------------------------------------------------------------------------- the relaxation
@pytest.mark.parametrize("N", [21, 1000, 9999, 10**4, 10**6, 10**30])
@pytest.mark.parametrize("dps", [30, 120])
def test_relaxation_against_loggamma(N, dps):
    rel = A._Relaxation(N)
    Ks = [mpmath.mpf("0.5"), mpmath.mpf(1), mpmath.mpf(7) / 3]
    with mpmath.workdps(60):
        Ks.append(mpmath.sqrt(mpmath.mpf(N) * mpmath.log(N)) * mpmath.pi / 3)
    for K in Ks:
        if K >= N - 1:
            continue
        with mp().workdps(dps):  # the relaxation computes in this thread's symhx context
            G, dG = rel.G(local(K)), rel.dG(local(K))
            h, F = rel.h(local(K) + 1), rel.F(local(K))
            G, dG, h, F = export((G, dG, h, F))
        Gr, dGr = G_loggamma(N, K, 3 * dps), dG_digamma(N, K, 3 * dps)
        with mpmath.workdps(3 * dps + 2 * len(str(N)) + 20):
            kap = K + 1
            hr = (mpmath.log(kap) - Gr) / K
            Fr = K * (1 / kap - dGr) - (mpmath.log(kap) - Gr)
            tol = mpmath.mpf(10) ** (3 - dps)
            assert abs(G - Gr) <= tol * abs(Gr), (N, K, "G")
            assert abs(dG - dGr) <= tol * abs(dGr), (N, K, "dG")
            assert abs(h - hr) <= tol * abs(hr), (N, K, "h")
            # F cancels near the minimiser: compare at the scale of its terms
            scale = abs(K / kap) + abs(K * dGr) + abs(mpmath.log(kap)) + abs(Gr)
            assert abs(F - Fr) <= tol * scale, (N, K, "F")


def test_relaxation_beyond_the_reach_of_stirling():
    """N = 20000: the 400 Stirling terms reach ~2098 digits at N - K ~ 2e4, so at dps = 2200 G
    and dG must come from loggamma/digamma (the series was used for every N >= 10**4: errors
    ~1e-2098, and the relaxed q of asymptotic_critical_point(20000, dps=2500) was off by
    ~1e-2101)."""
    dps = 2200
    # (22000, 7000): N - K = 15000 (series ~1999 digits) decides, not N or N + K
    for N, K in ((20000, mpmath.mpf(7) / 3), (20000, mpmath.mpf(400)), (22000, mpmath.mpf(7000))):
        rel = A._Relaxation(N)
        with mp().workdps(dps):  # the relaxation computes in this thread's symhx context
            G, dG = export((rel.G(local(K)), rel.dG(local(K))))
        Gr, dGr = G_loggamma(N, K, dps + 40), dG_digamma(N, K, dps + 40)
        with mpmath.workdps(dps + 60):
            tol = mpmath.mpf(10) ** (3 - dps)
            assert abs(G - Gr) <= tol * abs(Gr) and abs(dG - dGr) <= tol * abs(dGr), K


def test_lambert_v():
    for N in (21, 1000, 10**10, 10**200):
        with mp().workdps(60):  # in this thread's symhx context
            v = export(A._lambert_v(N))
        with mpmath.workdps(90):
            # v solves v - ln v = ln N - 2 (from -v e**-v = -e**2/N), with v > 1 (branch -1)
            assert v > 1
            assert abs(v - mpmath.log(v) - (mpmath.log(N) - 2)) < mpmath.mpf(10) ** -55 * v



# --------------------------------------------------------------------------- the p_d series
def test_pd_coefficients_from_catalan_form():
    coeffs = pd_series_coefficients(40)
    assert coeffs[:3] == ((2, Fraction(1)), (3, Fraction(2)), (4, Fraction(2)))
    for j, (pw, c) in enumerate(coeffs[3:], start=1):
        assert (pw, c) == (3 + 2 * j, 2 * binom_half(j))
    assert len(pd_series_coefficients(1)) == 1 and len(pd_series_coefficients()) == 5
    assert len(pd_series_coefficients(300)) == 300


@pytest.mark.parametrize("N", [2, 5, 21, 1000, 10**9, 10**40])
@pytest.mark.parametrize("n_terms", [1, 2, 3, 4, 5, 9])
@pytest.mark.parametrize("dps", [15, 80])
def test_pd_series_value_and_bound(N, n_terms, dps):
    s = pd_series(N, n_terms, dps=dps)
    assert s.N == N and s.n_terms == n_terms and len(s.coefficients) == n_terms
    with mpmath.workdps(3 * dps + 2 * len(str(N))):
        eps = 1 / mpmath.sqrt(N)
        terms = [(pw, c) for pw, c in pd_series_coefficients(n_terms + 3)]
        partial = mpmath.fsum(mpmath.mpf(c.numerator) / c.denominator * eps**pw
                              for pw, c in terms[:n_terms])
        # the documented bound: omitted powers <= 4 in full, then the first omitted power >= 5
        bound = mpmath.mpf(0)
        for pw, c in terms[n_terms:]:
            bound += abs(mpmath.mpf(c.numerator) / c.denominator) * eps**pw
            if pw >= 5:
                break
        exact = p_d_closed(N, 3 * dps)[0]
        one = mpmath.mpf(10) ** (1 - dps)
        assert abs(s.value - partial) <= one * partial
        # the truncation bound plus at most the rounding of the value to dps digits
        assert bound <= s.bound <= bound * (1 + one) + one * partial
        assert abs(exact - s.value) <= s.bound  # rigorous, no slack


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


@pytest.mark.parametrize("N", [10**40, 10**100])
@pytest.mark.parametrize("n_terms", [1, 5, 9])
@pytest.mark.parametrize("dps", [200, 400])
def test_pd_series_bound_is_rigorous_at_high_dps(N, n_terms, dps):
    """|p_d - value| <= bound also where the omitted terms are tiny and the rounding of the
    (dps+10)-digit partial sum matters: the 10**-(dps+5) |value| allowance must cover it (an
    allowance of 11**-(dps+5) falls below that rounding for dps >= ~120 and the bound fails)."""
    s = pd_series(N, n_terms, dps=dps)
    with mpmath.workdps(3 * dps + 4 * len(str(N))):
        pd = p_d_closed(N, 3 * dps + 2 * len(str(N)))[0]
        assert abs(pd - s.value) <= s.bound


def test_pd_series_bound_at_huge_N_and_dps():
    # N = 10**2000: the truncation error is within 10**-2000 of the bound, so the rounding of
    # the value and of the bound (dps = 1000) must both be covered
    N = 10**2000
    for n_terms in (2, 4):
        s = pd_series(N, n_terms, dps=1000)
        with mpmath.workdps(5000):
            exact = p_d_closed(N, 3000)[0]
            assert abs(exact - s.value) <= s.bound


# --------------------------------------------------------------------------- the error table
def test_error_table_rows_against_independent_errors():
    Ns = (1000, 10**7)
    rows = error_table(Ns, dps=30, orders=("leading", "lambert", "best"), pd_terms=3)
    assert [(r["N"], r["formula"]) for r in rows] == [
        (N, f) for N in Ns for f in ("leading", "lambert", "best", "pd-series-3")]
    floor = mpmath.mpf(10) ** -30
    for r in rows:
        N = r["N"]
        if r["quantity"] == "q":
            _, _, h = relaxed_minimum(N, 30)
            k = r["k_exact"]
            with mpmath.workdps(120):
                vals = [h(mpmath.mpf(k + i)) for i in (-1, 0, 1)]
                assert vals[1] < vals[0] and vals[1] <= vals[2]  # the integer argmin
                qx = mpmath.expm1(vals[1])
                assert abs(r["exact"] / qx - 1) < mpmath.mpf(10) ** -29
                err = max(abs(r["approx"] / qx - 1), floor)
                # both relative errors are differences of 30-digit numbers
                assert abs(r["rel_error"] - err) <= mpmath.mpf(10) ** -28
                kerr = abs(mpmath.mpf(r["k"]) / k - 1)
                assert abs(r["k_rel_error"] - kerr) <= mpmath.mpf(10) ** -28
            assert r["decay"] == DECAY[r["formula"]] and r["bound"] is None
        else:
            assert r["quantity"] == "p_d" and r["k"] is None and r["k_rel_error"] is None
            with mpmath.workdps(120):
                pd = p_d_closed(N, 120)[0]
                assert abs(r["exact"] / pd - 1) < mpmath.mpf(10) ** -29
                err = max(abs(r["approx"] / pd - 1), floor)
                assert abs(r["rel_error"] - err) <= mpmath.mpf(10) ** -28
                assert abs(r["bound"] * pd - pd_series(N, 3, dps=30).bound) <= (
                    mpmath.mpf(10) ** -28 * r["bound"] * pd)
                assert r["rel_error"] <= r["bound"] * (1 + mpmath.mpf(10) ** -20)
            assert r["decay"] == ""
    # the best row sits at the floor, the named decay of the 5-term series is reported
    assert [r["rel_error"] for r in rows if r["formula"] == "best"] == [floor, floor]
    five = error_table((1000,), dps=20, orders=("next",))
    assert five[-1]["formula"] == "pd-series-5" and five[-1]["decay"] == DECAY["pd-series-5"]


def test_error_table_sequences():
    assert A._sequence(np.array([1000, 2000]), "Ns") == (1000, 2000)
    assert A._sequence(range(3), "Ns") == (0, 1, 2)
    assert A._sequence([5], "Ns") == (5,)
    for bad in (np.array([[1000]]), "1000", 1000, None, {1000}):
        with pytest.raises(TypeError, match="Ns must be a list or tuple"):
            A._sequence(bad, "Ns")
    rows = error_table(np.array([1000]), dps=15, orders=["leading"], pd_terms=1)
    assert [r["formula"] for r in rows] == ["leading", "pd-series-1"]
    with pytest.raises(ValueError, match="each N of Ns"):
        error_table((1,), dps=15)
    with pytest.raises(ValueError, match="each order of orders"):
        error_table((1000,), orders=("leading", "worst"), dps=15)
    with pytest.raises(ValueError, match="pd_terms"):
        error_table((1000,), pd_terms=0, dps=15)


def test_format_error_table_layout():
    rows = [{"N": 1000, "formula": "a", "rel_error": mpmath.mpf("0.012345")},
            {"N": 1000, "formula": "b", "rel_error": mpmath.mpf(0)},
            {"N": 1234, "formula": "a", "rel_error": mpmath.mpf("2.5e-7")},
            {"N": 10**30, "formula": "b", "rel_error": mpmath.mpf("1.23456e-40")}]
    text = format_error_table(rows)
    assert text.splitlines() == [
        "| N | a | b |", "|---|---|---|",
        "| 1e3 | 0.0123 | 0 |", "| 1234 | 2.5e-7 |  |", "| 1e30 |  | 1.23e-40 |"]
    assert format_error_table(rows, digits=5).splitlines()[2] == "| 1e3 | 0.012345 | 0 |"


def test_format_error_table(table):
    text = format_error_table(table)
    assert text.splitlines()[0].startswith("| N | leading")
    assert "1e100" in text


def test_error_table_validates_sequences():
    from symhx.asymptotics import error_table

    for kw in (dict(Ns=""), dict(orders=""), dict(orders="best"), dict(Ns=(1000.5,)),
               dict(orders=("nope",)), dict(pd_terms=0), dict(dps=0), dict(Ns=None)):
        with pytest.raises((ValueError, TypeError)):
            error_table(**{**dict(Ns=(1000,), dps=20, orders=("leading",), pd_terms=2), **kw})
    assert error_table((), dps=20) == []
def test_error_table_values_at_the_requested_digits():
    rows = error_table((1000,), dps=25, orders=("leading", "best"), pd_terms=2)
    keys = {"N", "formula", "quantity", "approx", "exact", "rel_error", "k", "k_exact",
            "k_rel_error", "decay", "bound"}
    assert all(set(r) == keys for r in rows)
    assert rows[-1]["k_exact"] is None and rows[0]["k_exact"] == rows[1]["k_exact"]
    for r in rows:  # every reported value is a 25-digit number (the solvers ran at dps=25)
        for key in ("approx", "exact"):
            with mpmath.workdps(25):
                assert +r[key] == r[key], (r["formula"], key)
            with mpmath.workdps(20):
                assert +r[key] != r[key], (r["formula"], key)
    with mpmath.workdps(60):  # the leading row is the leading formula, q = sqrt(ln N / N)
        assert abs(rows[0]["approx"] / mpmath.sqrt(mpmath.log(1000) / 1000) - 1) < 1e-23


def test_format_error_table_small_N_names():
    rows = [{"N": 1, "formula": "a", "rel_error": mpmath.mpf("0.5")},
            {"N": 0, "formula": "a", "rel_error": None}]
    assert format_error_table(rows).splitlines()[2:] == ["| 1e0 | 0.5 |", "| 0 |  |"]


def test_error_table_default_digits():
    (row, _) = error_table((1000,), orders=("leading",))  # dps defaults to 120
    with mpmath.workdps(120):
        assert +row["approx"] == row["approx"]
    with mpmath.workdps(110):
        assert +row["approx"] != row["approx"]

# --------------------------------------------------------------------------- results and input
def test_default_order_and_result_dict():
    a = asymptotic_critical_point(1000)
    assert a.order == "best" and a.dps == 50
    d = a.as_dict()
    assert d == {"N": 1000, "order": "best", "p": a.p, "q": a.q, "k": a.k, "k_int": a.k_int,
                 "dps": 50, "decay": DECAY["best"]}
    assert ORDERS == ("leading", "next", "lambert", "corrected", "relaxed", "best")
    assert_refuses(asymptotic_critical_point, 20, arg="N", allowed=">= 21")
    assert asymptotic_critical_point(21, order="leading").N == 21


def test_public_export_and_result_fields():
    a = asymptotic_critical_point(10**4, order="next")
    assert a.order == "next" and isinstance(a.k_int, int) and a.decay
    d = a.as_dict()
    assert set(d) >= {"N", "order", "p", "q", "k"}


def test_documented_defaults():
    # the defaults are part of the API (book tables, CLI): 5 terms at 50 digits; the error
    # table over DEFAULT_NS at 120 digits
    s = pd_series(10**6)
    assert s.n_terms == 5 and s.value == pd_series(10**6, 5, dps=50).value
    assert s.value != pd_series(10**6, 5, dps=51).value
    sig = inspect.signature(error_table).parameters
    assert sig["dps"].default == 120 and sig["Ns"].default == A.DEFAULT_NS
    assert sig["orders"].default == ORDERS and sig["pd_terms"].default == 5


ORDER_LIST = "['leading', 'next', 'lambert', 'corrected', 'relaxed', 'best']"


def test_validation_messages():
    for call in (lambda: pd_series(100, 0), lambda: pd_series_coefficients(0)):
        assert_refuses(call, arg="n_terms", value="0", allowed=">= 1")
    for call in (lambda: pd_series(100, A.MAX_PD_TERMS + 1),
                 lambda: pd_series_coefficients(A.MAX_PD_TERMS + 1)):
        assert_refuses(call, arg="n_terms", value=str(A.MAX_PD_TERMS + 1),
                       allowed=f"<= {A.MAX_PD_TERMS}")
    assert_refuses(error_table, (1,), dps=15, arg="each N of Ns", value="1", allowed=">= 2")
    assert_refuses(error_table, "1000", dps=15, exc=TypeError, arg="Ns", value="'1000'",
                   allowed="a list or tuple")
    assert_refuses(error_table, (1000,), orders="best", dps=15, exc=TypeError, arg="orders",
                   value="'best'", allowed="a list or tuple")
    assert_refuses(error_table, (1000,), orders=("worst",), dps=15, arg="each order of orders",
                   value="'worst'", allowed=ORDER_LIST)
    assert_refuses(error_table, (1000,), pd_terms=0, dps=15, arg="pd_terms", value="0",
                   allowed=">= 1")

    class ListLike:  # tolist() but no ndim: not an array, and not a list either
        def tolist(self):
            return [1000]

    assert_refuses(A._sequence, ListLike(), "Ns", exc=TypeError, arg="Ns",
                   allowed="a list or tuple")


def test_small_N_and_order_messages():
    for N in (2, 3, 20):
        assert_refuses(asymptotic_critical_point, N, arg="N", value=f"N={N}",
                       allowed=[">= 21", "symhx.critical_point"])
    assert_refuses(asymptotic_critical_point, 1, arg="N", value="1", allowed=">= 2")
    for order in ("fast", "nonsense"):
        assert_refuses(asymptotic_critical_point, 1000, order=order, arg="order",
                       value=repr(order), allowed=ORDER_LIST)
    assert_refuses(asymptotic_critical_point, 1e10, exc=TypeError, arg="N",
                   value="float 10000000000.0", allowed="an int")


@pytest.mark.parametrize("bad", [0, -1, 2.5, True, 10**6, "50", None])
def test_bad_dps(bad):
    exc = ValueError if type(bad) is int else TypeError
    for call in (lambda: asymptotic_critical_point(1000, dps=bad),
                 lambda: pd_series(100, dps=bad)):
        assert_refuses(call, exc=exc, arg="dps", allowed="an int between 1 and 5000")


def test_bad_inputs():
    for N in (1, 0, -5):
        assert_refuses(pd_series, N, arg="N", value=str(N), allowed=">= 2")
    for N in (True, 10.0, 101.5, [3]):
        assert_refuses(pd_series, N, exc=TypeError, arg="N")
    for n_terms in (0, -1, 10**9):
        assert_refuses(pd_series, 100, n_terms, arg="n_terms", value=str(n_terms))
        assert_refuses(pd_series_coefficients, n_terms, arg="n_terms", value=str(n_terms))
    assert_refuses(pd_series, 100, 2.0, exc=TypeError, arg="n_terms", value="float 2.0")
    assert_refuses(asymptotic_critical_point, 1000, order="best ", arg="order",
                   value="'best '", allowed=ORDER_LIST)
    assert_refuses(asymptotic_critical_point, 1000, order=True, exc=TypeError, arg="order",
                   value="bool True", allowed=ORDER_LIST)


def test_import_of_the_asymptotics_does_not_import_sympy():
    code = ("import sys, symhx\n"
            "from symhx.asymptotics import asymptotic_critical_point, error_table\n"
            "asymptotic_critical_point(10**6); error_table((10**3,), dps=20)\n"
            "assert 'sympy' not in sys.modules, 'sympy imported'")
    subprocess.run([sys.executable, "-c", code], check=True)
