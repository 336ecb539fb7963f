"""symhx.asymptotics against independent references (issue 16, mutation testing): binomial
coefficients from math.comb, p_d from its closed form, the relaxation from mpmath's loggamma /
digamma at 3x the digits with a numerical minimiser, the integer argmin by exact integer
comparison, every comparison done inside ``workdps`` above the claim. Every test is fast."""

from __future__ import annotations

import math
from fractions import Fraction

import mpmath
import numpy as np
import pytest

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


def _rel(a, b, dps):
    with mpmath.workdps(dps):
        return abs(mpmath.mpf(a) / mpmath.mpf(b) - 1)


# ------------------------------------------------------------------------- the p_d series
def _binom_half(j: int) -> Fraction:
    """binom(1/2, j) = (-1)**(j+1) C(2j, j) / ((2j - 1) 4**j)."""
    return Fraction((-1) ** (j + 1) * math.comb(2 * j, j), (2 * j - 1) * 4**j)


def test_pd_coefficients_from_catalan_form():
    coeffs = pd_series_coefficients(40)
    assert coeffs[:3] == ((2, Fraction(1)), (3, Fraction(2)), (4, Fraction(2)))
    for j, (pw, c) in enumerate(coeffs[3:], start=1):
        assert (pw, c) == (3 + 2 * j, 2 * _binom_half(j))
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
        exact = ((1 + mpmath.sqrt(N + 1)) / N) ** 2
        one = mpmath.mpf(10) ** (1 - dps)
        assert abs(s.value - partial) <= one * partial
        # the truncation bound plus at most the rounding of the value to dps digits
        assert bound <= s.bound <= bound * (1 + one) + one * partial
        assert abs(exact - s.value) <= s.bound  # rigorous, no slack


# --------------------------------------------------------------------- the relaxation of h
def _G_ref(N, K, dps):
    with mpmath.workdps(dps + 2 * len(str(N)) + 20):
        K = mpmath.mpf(K)
        return mpmath.loggamma(N) - mpmath.loggamma(N - K) - K * mpmath.log(N)


def _dG_ref(N, K, dps):
    with mpmath.workdps(dps + 2 * len(str(N)) + 20):
        return mpmath.digamma(N - mpmath.mpf(K)) - mpmath.log(N)


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
        Gr, dGr = _G_ref(N, K, 3 * dps), _dG_ref(N, K, 3 * dps)
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
        Gr, dGr = _G_ref(N, K, dps + 40), _dG_ref(N, K, dps + 40)
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


# ----------------------------------------------------------------------- the orders
def _formula_orders(N: int, dps: int) -> dict[str, tuple]:
    """leading / next / lambert / corrected straight from the module docstring, at 3x dps, with
    the Lambert value from the defining equation solved by Newton (not lambertw)."""
    with mpmath.workdps(3 * dps + 20):
        Nm = mpmath.mpf(N)
        L = mpmath.log(Nm)
        out = {"leading": (mpmath.sqrt(Nm * L), mpmath.sqrt(L / Nm))}
        lam = L - 2
        v = lam + mpmath.log(lam)
        out["next"] = (mpmath.sqrt(Nm * v), (v + 1) / mpmath.sqrt(Nm * v))
        w = L
        for _ in range(200):  # v - ln v = L - 2, the root above 1
            w = w - (w - mpmath.log(w) - lam) / (1 - 1 / w)
        k0 = mpmath.sqrt(Nm * w)
        out["lambert"] = (k0, mpmath.expm1(1 / k0 + k0 / Nm))

        def h2(k):
            return mpmath.log(k) / (k - 1) + k / (2 * Nm) + k * (2 * k - 1) / (12 * Nm**2)

        # Newton step for the minimiser of h2 from k0, with h2' by numerical differentiation
        # and the curvature of the leading part log k / k
        d1 = mpmath.diff(h2, k0)
        k1 = k0 - d1 / ((2 * mpmath.log(k0) - 3) / k0**3)
        out["corrected"] = (k1, mpmath.expm1(h2(k0)))
        return out


@pytest.mark.parametrize("N", [21, 1000, 10**8, 10**50])
@pytest.mark.parametrize("dps", [20, 90])
def test_formula_orders(N, dps):
    ref = _formula_orders(N, dps)
    for order, (k, q) in ref.items():
        a = asymptotic_critical_point(N, order=order, dps=dps)
        assert a.order == order and a.N == N and a.dps == dps and a.decay == DECAY[order]
        claim = mpmath.mpf(10) ** (1 - dps)
        with mpmath.workdps(3 * dps + 20):
            assert _rel(a.q, q, 3 * dps) <= claim, (order, "q")
            assert _rel(a.p, (1 + q) / N, 3 * dps) <= claim, (order, "p")
            # the corrected k uses a closed-form derivative, the reference a numerical one
            assert _rel(a.k, k, 3 * dps) <= (claim if order != "corrected" else
                                             mpmath.mpf(10) ** (5 - dps)), (order, "k")
        assert isinstance(a.k_int, int)
        with mpmath.workdps(3 * dps + 20):  # the nearest integer of k, up to k's own rounding
            assert abs(a.k_int - k) <= mpmath.mpf("0.5") + claim * k


def _relaxed_ref(N: int, dps: int):
    """min over real kappa of h(kappa) with loggamma / digamma at 3x dps (findroot on h')."""
    d = 3 * dps + 2 * len(str(N)) + 20
    with mpmath.workdps(d):
        Nm = mpmath.mpf(N)

        def h(kap):
            K = kap - 1
            return (mpmath.log(kap) - mpmath.loggamma(Nm) + mpmath.loggamma(Nm - K)
                    + K * mpmath.log(Nm)) / K

        def dh_num(kap):  # K**2 h'(kappa), from digamma
            K = kap - 1
            G = mpmath.loggamma(Nm) - mpmath.loggamma(Nm - K) - K * mpmath.log(Nm)
            dG = mpmath.digamma(Nm - K) - mpmath.log(Nm)
            return K * (1 / kap - dG) - (mpmath.log(kap) - G)

        k0 = mpmath.sqrt(Nm * mpmath.log(Nm))
        kap = mpmath.findroot(dh_num, (k0 / 3, 2 * k0), solver="anderson")
        return kap, mpmath.expm1(h(kap)), h


def _exact_argmin(N: int) -> int:
    """Largest integer argmin of c_k by exact integer comparisons (small N only)."""
    best = 2
    for k in range(3, N + 1):
        a = Fraction(k * math.factorial(N - k), math.factorial(N - 1))
        b = Fraction(best * math.factorial(N - best), math.factorial(N - 1))
        lhs = a.numerator ** (best - 1) * b.denominator ** (k - 1)
        rhs = b.numerator ** (k - 1) * a.denominator ** (best - 1)
        if lhs <= rhs:
            best = k
    return best


@pytest.mark.parametrize("N", [21, 22, 57, 400, 1000, 9999])
@pytest.mark.parametrize("dps", [15, 60])
def test_relaxed_and_best_small_N(N, dps):
    kap, qrel, h = _relaxed_ref(N, dps)
    a = asymptotic_critical_point(N, order="relaxed", dps=dps)
    claim = mpmath.mpf(10) ** (1 - dps)
    assert _rel(a.q, qrel, 3 * dps) <= claim
    assert _rel(a.k, kap, 3 * dps) <= mpmath.mpf(10) ** (2 - dps)
    assert a.k_int == int(mpmath.nint(kap))
    b = asymptotic_critical_point(N, dps=dps)
    if N < 100:
        k = _exact_argmin(N)
        assert b.k == k
    k = b.k
    assert b.k_int == k and isinstance(b.k, int)
    with mpmath.workdps(3 * dps + 40):
        vals = [h(mpmath.mpf(k + i)) for i in (-1, 0, 1)]
        assert vals[1] < vals[0] and vals[1] <= vals[2]  # with the proved unimodality
        qbest = mpmath.expm1(vals[1])
        pbest = (1 + qbest) / N
    assert _rel(b.q, qbest, 3 * dps) <= claim
    assert _rel(b.p, pbest, 3 * dps) <= claim


@pytest.mark.parametrize("N", [10**4, 123457, 10**9, 10**25])
@pytest.mark.parametrize("dps", [20, 100])
def test_relaxed_and_best_large_N(N, dps):
    kap, qrel, h = _relaxed_ref(N, dps)
    a = asymptotic_critical_point(N, order="relaxed", dps=dps)
    claim = mpmath.mpf(10) ** (1 - dps)
    assert _rel(a.q, qrel, 3 * dps) <= claim
    assert _rel(a.k, kap, 3 * dps) <= mpmath.mpf(10) ** (2 - dps)
    b = asymptotic_critical_point(N, dps=dps)
    # the integer argmin beats both neighbours (loggamma at 3x dps; unimodality is proved)
    with mpmath.workdps(3 * dps + 2 * len(str(N)) + 40):
        vals = [h(mpmath.mpf(b.k + i)) for i in (-1, 0, 1)]
        assert vals[1] < vals[0] and vals[1] <= vals[2]
        qbest = mpmath.expm1(vals[1])
        pbest = (1 + qbest) / N
    assert _rel(b.q, qbest, 3 * dps) <= claim
    assert _rel(b.p, pbest, 3 * dps) <= claim
    assert abs(b.k - kap) < 1


def test_default_order_and_result_dict():
    a = asymptotic_critical_point(1000)
    assert a.order == "best" and a.dps == 50
    d = a.as_dict()
    assert d == {"N": 1000, "order": "best", "p": a.p, "q": a.q, "k": a.k, "k_int": a.k_int,
                 "dps": 50, "decay": DECAY["best"]}
    assert ORDERS == ("leading", "next", "lambert", "corrected", "relaxed", "best")
    with pytest.raises(ValueError, match="N >= 21"):
        asymptotic_critical_point(20)
    assert asymptotic_critical_point(21, order="leading").N == 21


# -------------------------------------------------------------------------- error table
def test_error_table_rows_against_independent_errors():
    Ns = (1000, 10**7)
    rows = error_table(Ns, dps=30, orders=("leading", "lambert", "best"), pd_terms=3)
    assert [(r["N"], r["formula"]) for r in rows] == [
        (N, f) for N in Ns for f in ("leading", "lambert", "best", "pd-series-3")]
    floor = mpmath.mpf(10) ** -30
    for r in rows:
        N = r["N"]
        if r["quantity"] == "q":
            _, _, h = _relaxed_ref(N, 30)
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
                pd = ((1 + mpmath.sqrt(N + 1)) / N) ** 2
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


def test_documented_defaults_and_validation_messages():
    import inspect

    # the defaults are part of the API (book tables, CLI): 5 terms at 50 digits; the error
    # table over DEFAULT_NS at 120 digits
    s = pd_series(10**6)
    assert s.n_terms == 5 and s.value == pd_series(10**6, 5, dps=50).value
    assert s.value != pd_series(10**6, 5, dps=51).value
    sig = inspect.signature(error_table).parameters
    assert sig["dps"].default == 120 and sig["Ns"].default == A.DEFAULT_NS
    assert sig["orders"].default == ORDERS and sig["pd_terms"].default == 5
    for call in (lambda: pd_series(100, 0), lambda: pd_series_coefficients(0)):
        with pytest.raises(ValueError, match=r"^n_terms must be >= 1"):
            call()
    for call in (lambda: pd_series(100, A.MAX_PD_TERMS + 1),
                 lambda: pd_series_coefficients(A.MAX_PD_TERMS + 1)):
        with pytest.raises(ValueError, match=rf"^n_terms must be <= {A.MAX_PD_TERMS}, got "
                                             rf"{A.MAX_PD_TERMS + 1}$"):
            call()
    with pytest.raises(ValueError, match=r"^each N of Ns must be >= 2"):
        error_table((1,), dps=15)
    with pytest.raises(TypeError, match=r"^Ns must be a list or tuple"):
        error_table("1000", dps=15)
    with pytest.raises(TypeError, match=r"^orders must be a list or tuple"):
        error_table((1000,), orders="best", dps=15)
    with pytest.raises(ValueError, match=r"^each order of orders must be one of"):
        error_table((1000,), orders=("worst",), dps=15)
    with pytest.raises(ValueError, match=r"^pd_terms must be >= 1"):
        error_table((1000,), pd_terms=0, dps=15)

    class ListLike:  # tolist() but no ndim: not an array, and not a list either
        def tolist(self):
            return [1000]

    with pytest.raises(TypeError, match="Ns must be a list or tuple"):
        A._sequence(ListLike(), "Ns")


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


def test_pd_series_bound_at_huge_N_and_dps():
    # N = 10**2000: the truncation error is within 10**-2000 of the bound, so the rounding of
    # the value and of the bound (dps = 1000) must both be covered
    N = 10**2000
    for n_terms in (2, 4):
        s = pd_series(N, n_terms, dps=1000)
        with mpmath.workdps(5000):
            exact = ((1 + mpmath.sqrt(N + 1)) / N) ** 2
            assert abs(exact - s.value) <= s.bound


def test_small_N_and_order_messages():
    for N in (2, 3, 20):
        with pytest.raises(ValueError, match=rf"^the asymptotic formulas need N >= 21, got N={N}; "
                                             r"use symhx\.critical_point for small N$"):
            asymptotic_critical_point(N)
    with pytest.raises(ValueError, match=r"^N must be >= 2"):
        asymptotic_critical_point(1)
    with pytest.raises(ValueError, match=r"^order must be one of"):
        asymptotic_critical_point(1000, order="fast")


def test_error_table_default_digits():
    (row, _) = error_table((1000,), orders=("leading",))  # dps defaults to 120
    with mpmath.workdps(120):
        assert +row["approx"] == row["approx"]
    with mpmath.workdps(110):
        assert +row["approx"] != row["approx"]
