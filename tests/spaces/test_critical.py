"""The first jump of the mode over a higher-order space (``symhx.spaces.critical_point`` and its
float64 seed ``root_estimates``): ``p_c``, ``q``, the argmins and ``k_after``, the certified
enclosure ``p_bounds``, exact rational critical points and ties, for N from 2 to 10**6.

References (:mod:`tests.reference.spaces`): the weight polynomial of ``X = k`` from Burnside's
count of every visit pattern of the space (not the class tables); each root ``c_k`` of
``W(k) = W(1)`` by plain bisection at 70 digits, by ``mpmath.polyroots`` and by
``mpmath.findroot``; exhaustive exact argmax scans in ``Fraction`` arithmetic on either side of
the enclosure; the rational-root theorem for exact critical points; for ``excess<=0`` and the
``;distinct`` weighting the closed form ``c_k = (S_1 / S_k)**(1/(k-1))``.
"""

from __future__ import annotations

import warnings
from fractions import Fraction

import mpmath
import numpy as np
import pytest

from symhx import critical as simple_critical
from symhx.critical import discriminant_root, discriminant_root_q
from symhx.spaces import critical_point, modes, parse_space, root_estimates
from symhx.validation import as_fraction, mpf_to_fraction
from tests.reference.spaces import (
    ROOT_DIGITS,
    argmax,
    critical_by_bisection,
    critical_by_polyroots,
    evaluate,
    monomial_root,
    rational_root,
    roots,
    weight_poly,
)

WP = ROOT_DIGITS
CASES = [(b, w) for b in ("eq41", "eq41-printed", "excess<=1", "excess<=3")
         for w in ("length", "distinct")]


def _log_Nc(N: int, c) -> float:
    with mpmath.workdps(30):
        return float(mpmath.log(N * c))


# --------------------------------------------------------------------------- against references
@pytest.mark.parametrize("base,w", CASES)
def test_critical_point_against_bisection(base, w):
    for N in (2, 3, 5, 12, 30):
        argmins, pc = critical_by_bisection(N, base, w)
        exact = rational_root(N, base, argmins[0], pc, w)
        if exact is not None:
            with mpmath.workdps(WP):
                pc = mpmath.mpf(exact.numerator) / exact.denominator
        for dps in (15, 35):
            cp = critical_point(N, space=base, weighting=w, dps=dps)
            assert (cp.N, cp.dps, cp.k_before) == (N, dps, 1)
            assert cp.argmins == argmins, (base, w, N)
            with mpmath.workdps(dps):
                assert cp.p == +pc, (base, w, N, dps)      # correctly rounded to dps digits
            with mpmath.workdps(WP):
                q = N * pc - 1
            with mpmath.workdps(dps):
                assert cp.q == +q
            lo, hi = cp.p_bounds
            qlo, qhi = cp.q_bounds
            with mpmath.workdps(WP):
                assert lo <= pc <= hi and lo <= cp.p <= hi
                assert hi - lo <= mpmath.mpf(10) ** -dps * pc
                assert qlo <= q <= qhi and qlo <= cp.q <= qhi
                assert qhi - qlo <= mpmath.mpf(10) ** -dps * N * pc
            assert cp.p_d == discriminant_root(N, dps=dps)
            assert cp.q_d == discriminant_root_q(N, dps=dps)
            assert cp.p_exact == exact, (base, w, N)
            if exact is not None:
                assert mpf_to_fraction(lo) <= exact <= mpf_to_fraction(hi)
        # exhaustive exact scans just outside the enclosure: mode 1 below, k_after above
        flo, fhi = mpf_to_fraction(cp.p_bounds[0]), mpf_to_fraction(cp.p_bounds[1])
        below, above = flo * (1 - Fraction(1, 10**25)), fhi * (1 + Fraction(1, 10**25))
        assert argmax(N, base, below, w) == (1,)
        assert argmax(N, base, above, w) == (cp.k_after,)
        assert cp.k_after in cp.argmins


@pytest.mark.parametrize("space", ["eq41", "eq41-printed", "excess<=2", "excess<=4"])
@pytest.mark.parametrize("weighting", ["length", "distinct"])
def test_against_polynomial_roots(space, weighting):
    for N in (2, 3, 4, 7, 10):
        cp = critical_point(N, space=space, weighting=weighting, dps=25)
        ref, kref = critical_by_polyroots(N, space, weighting)
        assert cp.k_after == kref and cp.k_before == 1
        with mpmath.workdps(40):
            assert mpmath.almosteq(cp.p, ref, 1e-22), (space, N)
            assert mpmath.almosteq(cp.q, N * ref - 1, 1e-20)


@pytest.mark.parametrize("space", ["eq41", "eq41-printed", "excess<=3"])
@pytest.mark.parametrize("weighting", ["length", "distinct"])
@pytest.mark.parametrize("N", [6, 23, 60])
def test_enclosure_by_exact_brute_force(space, weighting, N):
    """Just below p_bounds every k >= 2 has W(k) < W(1); just above, W(k_after) beats every
    other k: exact rational arithmetic over all k (a wrong argmin or enclosure fails)."""
    cp = critical_point(N, space=space, weighting=weighting, dps=20)
    lo, hi = (as_fraction(x) for x in cp.p_bounds)
    assert lo <= hi and (hi - lo) <= Fraction(1, 10**20) * lo
    if cp.p_exact is not None:
        assert lo <= cp.p_exact <= hi
    below = lo * (1 - Fraction(1, 10**30))
    above = hi * (1 + Fraction(1, 10**30))
    polys = [weight_poly(N, space, k, weighting) for k in range(1, N + 1)]
    wb = [evaluate(poly, below) for poly in polys]
    wa = [evaluate(poly, above) for poly in polys]
    assert all(w < wb[0] for w in wb[1:]), (space, N)
    top = max(wa)
    assert [k for k, w in enumerate(wa, 1) if w == top] == [cp.k_after], (space, N)


@pytest.mark.parametrize("N,space", [(101, "eq41"), (101, "excess<=2;distinct"),
                                     (10**4, "eq41")])
def test_enclosure_contains_independent_root(N, space):
    """p_bounds (relative width <= 10**-dps) contains the root of W(k_after) = W(1) found by
    mpmath.findroot on the exact polynomials at 3x the digits."""
    for dps in (15, 40):
        cp = critical_point(N, space=space, dps=dps)
        pk, p1 = weight_poly(N, space, cp.k_after), weight_poly(N, space, 1)
        with mpmath.workdps(3 * dps + 2 * len(str(N)) + 20):
            ref = mpmath.findroot(lambda p, pk=pk, p1=p1: mpmath.log(evaluate(pk, p))
                                  - mpmath.log(evaluate(p1, p)), cp.p)
            lo, hi = cp.p_bounds
            assert lo <= ref <= hi
            assert (hi - lo) <= mpmath.mpf(10) ** -dps * ref


@pytest.mark.parametrize("space", ["eq41", "eq41-printed", "excess<=3", "excess<=6",
                                   "excess<=2;distinct"])
def test_modes_either_side(space):
    for N in (5, 17, 100, 101):
        cp = critical_point(N, space=space, dps=30)
        with mpmath.workdps(30):
            below = Fraction(mpmath.nstr(cp.p * (1 - mpmath.mpf(10) ** -12), 28))
            above = Fraction(mpmath.nstr(cp.p * (1 + mpmath.mpf(10) ** -12), 28))
        assert modes(N, below, space=space) == (1,)
        assert modes(N, above, space=space) == (cp.k_after,)
        # and the mode is 1 everywhere below: a coarse exact scan
        for j in range(1, 20):
            assert modes(N, below * j / 20, space=space) == (1,)


def test_large_n():
    cp = critical_point(10**5, space="eq41", dps=20)
    assert 1 < cp.k_after < 10**5
    with mpmath.workdps(20):
        above = Fraction(mpmath.nstr(cp.p * (1 + mpmath.mpf(10) ** -10), 18))
        below = Fraction(mpmath.nstr(cp.p * (1 - mpmath.mpf(10) ** -10), 18))
    assert modes(10**5, above, space="eq41") == (cp.k_after,)
    assert modes(10**5, below, space="eq41") == (1,)


def test_guard_digits_grow_with_the_digits_of_N():
    """N = 10**6 (7 digits, lgamma terms ~ 10**7 cancel): still correctly rounded and bracketed
    (excess<=0: c_k in closed form)."""
    N = 10**6
    cp = critical_point(N, space="excess<=0", dps=15)
    (k,) = cp.argmins
    c = monomial_root(N, "excess<=0", k)
    assert cp.p_bounds[0] <= c <= cp.p_bounds[1]
    with mpmath.workdps(15):
        assert cp.p == +c


# --------------------------------------------------------------------------- ties, rationals
def test_excess0_is_simple_and_ties():
    for N in (2, 3, 4, 5, 6, 50, 101):
        a = critical_point(N, space="excess<=0", dps=30)
        b = simple_critical.critical_point(N, dps=30)
        assert a.argmins == b.argmins and a.k_after == b.k_after
        with mpmath.workdps(40):
            assert mpmath.almosteq(a.p, b.p, 1e-28)
    tie = critical_point(5, space="excess<=0")
    assert tie.argmins == (2, 3) and tie.p_exact == Fraction(1, 2)
    assert modes(5, Fraction(1, 2), space="excess<=0") == (1, 2, 3)


def test_exact_tie_of_two_argmins():
    """excess<=0 at N = 5: c_2 = c_3 = 1/2 exactly; both argmins, the faster-growing h_3 wins."""
    for w in ("length", "distinct"):
        cp = critical_point(5, space="excess<=0", weighting=w, dps=30)
        assert cp.argmins == (2, 3) and cp.p_exact == Fraction(1, 2) and cp.k_after == 3
        with mpmath.workdps(30):
            assert cp.p == mpmath.mpf(1) / 2 and cp.q == mpmath.mpf(3) / 2
        assert cp.p_bounds[0] <= 0.5 <= cp.p_bounds[1]
        assert argmax(5, "excess<=0", Fraction(1, 2), w) == (1, 2, 3)
        assert argmax(5, "excess<=0", Fraction(1, 2) + Fraction(1, 10**20), w) == (3,)


def test_distinct_weighting_rational_roots():
    cp = critical_point(3, space="eq41;distinct")
    # W(1) = 4 N p (phi, phi^1, phi^{1,0}, phi^{1,0,0}), W(2) = p^2 * total count at k=2
    sp = parse_space("eq41;distinct")
    tot2 = sum(sp.count(3, s, 2) for s in sp.shapes)
    assert cp.p_exact == Fraction(4 * 3, tot2)
    assert modes(3, cp.p_exact, space="eq41;distinct") == (1, 2)


def test_rational_critical_points():
    """Distinct weighting: c_2 = S_1 / S_2 (circuits with 1 and 2 distinct vertices) is
    rational; found exactly, bounds collapse onto it, and the modes at p_exact tie."""
    for base in ("eq41", "eq41-printed", "excess<=2"):
        for N in (2, 3):
            cp = critical_point(N, space=base, weighting="distinct", dps=20)
            c2 = Fraction(sum(weight_poly(N, base, 1, "distinct").values()),
                          sum(weight_poly(N, base, 2, "distinct").values()))
            assert cp.argmins == (2,) and cp.p_exact == c2
            with mpmath.workdps(20):
                assert cp.p == mpmath.mpf(c2.numerator) / c2.denominator
                assert cp.q == mpmath.mpf(N * c2.numerator - c2.denominator) / c2.denominator
            assert mpf_to_fraction(cp.p_bounds[0]) <= c2 <= mpf_to_fraction(cp.p_bounds[1])
            assert modes(N, c2, space=base, weighting="distinct") == (1, 2)


def test_simple_space_is_delegated():
    for N in (2, 5, 101):
        assert critical_point(N, space="simple", dps=25) == simple_critical.critical_point(
            N, dps=25)


# --------------------------------------------------------------------------- root_estimates
@pytest.mark.parametrize("base,w", [*CASES, ("excess<=0", "length")])
def test_root_estimates_against_bisection(base, w):
    space = base if w == "length" else base + ";distinct"
    for N in (2, 3, 12, 30):
        s = root_estimates(space, N)
        assert s.shape == (N - 1,)
        for k, c in roots(N, base, w).items():
            ref = _log_Nc(N, c)
            assert abs(s[k - 2] - ref) <= 1e-10 * max(1.0, abs(ref)), (N, k)


@pytest.mark.parametrize("base,Ns", [("eq41", (2, 3, 5, 12)), ("excess<=3", (2, 3, 5, 12)),
                                     ("excess<=12", (2, 3, 5)), ("excess<=20", (2, 3, 5)),
                                     ("excess<=25", (2, 3))])
def test_root_estimates_to_float64_accuracy(base, Ns):
    """Small N (every term of h_k is O(10)): the safeguarded Newton iteration ends at the float64
    root, within a few dozen ulps of the 70-digit bisection root, also for large excess where
    the mean-excess part of the slope dominates (k = 2)."""
    for N in Ns:
        s = root_estimates(base, N)
        for k, c in roots(N, base, "length").items():
            assert abs(s[k - 2] - _log_Nc(N, c)) <= 1e-14, (base, N, k)


@pytest.mark.parametrize("base", ["excess<=6", "excess<=12"])
def test_root_estimates_many_columns(base):
    """N = 200: 199 roots iterated together; each column's slope is its own mean excess."""
    N = 200
    s = root_estimates(base, N)
    p1 = weight_poly(N, base, 1)
    for k in (2, 3, 6):
        pk = weight_poly(N, base, k)
        with mpmath.workdps(40):
            lo, hi = mpmath.mpf(1) / N, mpmath.mpf(5) / N   # plain bisection
            assert evaluate(pk, lo) < evaluate(p1, lo) and evaluate(pk, hi) > evaluate(p1, hi)
            for _ in range(110):
                mid = (lo + hi) / 2
                lo, hi = (mid, hi) if evaluate(pk, mid) < evaluate(p1, mid) else (lo, mid)
        assert abs(s[k - 2] - _log_Nc(N, lo)) <= 1e-12, (base, k)


@pytest.mark.parametrize("base,Ns", [("excess<=20", (2, 3, 5, 12)), ("excess<=25", (2, 3)),
                                     ("eq41-printed", (2, 3, 5, 12))])
def test_root_estimates_distinct_closed_form(base, Ns):
    """``;distinct``: h_k is linear in log p, c_k = (S_1/S_k)**(1/(k-1)) exactly."""
    for N in Ns:
        s = root_estimates(base + ";distinct", N)
        for k in range(2, N + 1):
            ref = _log_Nc(N, monomial_root(N, base, k, "distinct", digits=30))
            assert abs(s[k - 2] - ref) <= 1e-14 * max(1.0, abs(ref)), (base, N, k)


def test_root_estimates_emit_no_float_warnings():
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        for space in ("eq41", "excess<=20", "excess<=3;distinct"):
            for N in (2, 3, 30):
                assert np.all(np.isfinite(root_estimates(space, N)))
