"""symhx._numeric against independent references: decimal digits from str(), the
log-falling-factorial G(N, K) from the exact integer ratio (N-1)!/((N-K-1)! N**K), from
sum log1p(-j/N) and from loggamma at ample precision, Stirling's series from exact Bernoulli
numbers (Fractions) and from loggamma/digamma, mp_value against mpmath's own constants."""

from __future__ import annotations

from fractions import Fraction

import mpmath
import pytest
from hypothesis import given
from hypothesis import strategies as st

from symhx._mpctx import export, mp
from symhx._numeric import (
    G_direct,
    G_mp,
    digits_of,
    mp_value,
    stirling_coefficients,
    stirling_ok,
    stirling_series,
)
from tests.reference.critical import (
    G_exact_ratio,
    G_log1p_sum,
    G_loggamma,
    stirling_remainder,
    stirling_terms,
)


def _at(dps: int, fn, *args, **kwargs):
    """``fn(*args)`` in this thread's symhx context at ``dps`` digits (the helpers compute at
    the caller's thread-context precision, never the global one, issue 28), exported."""
    with mp().workdps(dps):
        return export(fn(*args, **kwargs))


def test_digits_of_matches_str():
    for N in [*range(1, 3000), *(10**e + d for e in range(4, 60) for d in (-1, 0, 1)),
              2**200, 3**300]:
        d = len(str(N))
        assert d <= digits_of(N) <= d + 1, N
    # exact for the one-digit numbers whose bit length is below 4
    assert [digits_of(N) for N in range(1, 8)] == [1] * 7


# --------------------------------------------------------------------------- G(N, K)
@pytest.mark.parametrize("dps", [15, 40, 120])
@pytest.mark.parametrize("N, K", [(10, 1), (100, 3), (100, 99), (5000, 1), (9999, 9998),
                                  (10**4, 1), (10**4, 9999), (20000, 1), (20000, 19990),
                                  (20000, 7000), (10**6, 1), (10**6, 2000), (3 * 10**5, 300)])
def test_G_mp_and_G_direct_against_exact_ratio(N, K, dps):
    ref = G_exact_ratio(N, K, 2 * dps + 20)
    for f in (G_mp, G_direct):
        before = mpmath.mp.prec
        got = _at(dps, f, N, K)
        assert mpmath.mp.prec == before  # the global precision is not touched
        with mpmath.workdps(2 * dps + 20):
            assert abs(got - ref) <= mpmath.mpf(10) ** (1 - dps) * abs(ref), (f.__name__, N, K)


def test_G_huge_N_small_K():
    # G = sum_{j<=K} log(1 - j/N): log1p series at high precision as the reference
    for N, K in [(10**12, 1), (10**12, 5), (10**30, 3), (7 * 10**15 + 3, 40)]:
        for dps in (15, 50):
            ref = G_log1p_sum(N, K, 3 * dps)
            for f in (G_mp, G_direct):
                got = _at(dps, f, N, K)
                with mpmath.workdps(3 * dps):
                    assert abs(got - ref) <= mpmath.mpf(10) ** (1 - dps) * abs(ref), \
                        (f.__name__, N, K, dps)


def test_G_zero_K():
    for N in (1, 2, 10**4 + 5, 10**20):
        assert _at(30, G_mp, N, 0) == 0
        assert _at(30, G_direct, N, 0) == 0 if N > 1 else True


@given(st.integers(10**5, 10**40), st.integers(0, 10**6))
def test_G_rewrite_matches_definition(N, K):
    K = min(K, N - 1)
    a, b = _at(60, G_mp, N, K), _at(60, G_direct, N, K)
    if K == 0:
        assert a == 0
        return
    with mpmath.workdps(60):
        assert abs(a - b) <= mpmath.mpf(10) ** -55 * abs(b)


def test_G_mp_at_high_precision_near_the_stirling_limit():
    # dps = 3000: 4 * dps = 12000 is above 10**4, and the 400-term cap of Stirling's series
    # needs x >= ~2.9e5
    dps = 3000
    # (an earlier version summed the capped series at N - K = 12498 to only ~1940 digits)
    for N, K in [(11000, 1), (12500, 2), (60000, 1), (3 * 10**5, 1), (3 * 10**5, 50)]:
        ref = G_exact_ratio(N, K, dps + 50)
        got = _at(dps, G_mp, N, K)
        with mpmath.workdps(dps + 50):
            assert abs(got - ref) <= mpmath.mpf(10) ** (1 - dps) * abs(ref), (N, K)


# The direct forms: sum of log1p(-j/N) (K = 1), the exact integer ratio (K = 57) and the
# loggamma difference at 30 more digits (large K). At 3000 digits Stirling's series serves
# N - K >= 285852 (the smallest x with stirling_ok(x, 3000)); at 3500 and 4000 digits no N - K
# below 10**6 qualifies, so loggamma with guard digits serves them all.
HIGH_DPS_CASES = [
    (3000, 10**5, 1), (3000, 10**5, 57), (3000, 10**5, 99_000),
    (3000, 10**6, 1), (3000, 10**6, 57), (3000, 10**6, 333_333),
    (3000, 10**6, 10**6 - 285_852), (3000, 10**6, 10**6 - 285_851),
    (3500, 3 * 10**5 + 7, 57), (3500, 3 * 10**5 + 7, 100_002),
    (4000, 10**5, 33_333), (4000, 10**6, 1), (4000, 10**6, 57), (4000, 10**6, 700_000),
]


@pytest.mark.parametrize("dps, N, K", HIGH_DPS_CASES)
def test_G_mp_at_3000_to_4000_digits_against_the_direct_form(dps, N, K):
    assert stirling_ok(285_852, 3000) and not stirling_ok(285_851, 3000)
    if K == 1:
        ref = G_log1p_sum(N, K, dps + 30)
    elif K < 100:
        ref = G_exact_ratio(N, K, dps + 30)
    else:
        ref = G_loggamma(N, K, dps + 30)
    got = _at(dps, G_mp, N, K)
    with mpmath.workdps(dps + 30):
        assert abs(got - ref) <= mpmath.mpf(10) ** -dps * abs(ref), (dps, N, K)


# --------------------------------------------------------------------------- Stirling's series
@pytest.mark.parametrize("derivative", [False, True])
def test_stirling_series_against_loggamma(derivative):
    # S(x) = lgamma(x) - (x - 1/2) log x + x - log(2 pi)/2 ; S'(x) = psi(x) - log x + 1/(2x)
    for x in (50, 300, 10**4 + 7):
        with mpmath.workdps(60):
            ref = stirling_remainder(x, derivative=derivative)
        got = _at(30, stirling_series, mpmath.mpf(x), derivative=derivative)
        with mpmath.workdps(60):
            assert abs(got - ref) <= mpmath.mpf(10) ** -29 * abs(ref), x


def test_stirling_series_honours_eps_and_the_term_cap():
    # a coarse eps stops early: the value is the exact partial sum up to the first term below
    # eps relative to the running sum (reproduced here from exact Bernoulli numbers)
    x, eps = Fraction(3), Fraction(1, 10**4)
    terms = stirling_terms(x, 10)
    total = Fraction(0)
    for t in terms:
        total += t
        if abs(t) <= eps * abs(total):
            break
    with mpmath.workdps(40):
        got = _at(40, stirling_series, mpmath.mpf(3),
                  mpmath.mpf(eps.numerator) / eps.denominator)
        ref = mpmath.mpf(total.numerator) / total.denominator
        assert abs(got - ref) <= mpmath.mpf(10) ** -38 * abs(ref)
        full = _at(40, stirling_series, mpmath.mpf(3), mpmath.mpf(10) ** -12)
        assert abs(full - ref) > mpmath.mpf(10) ** -8 * abs(ref)  # the early stop shows
    # x = 1: the asymptotic series diverges before reaching eps, so exactly 400 terms are summed
    terms = stirling_terms(Fraction(1), 401)
    s400 = sum(terms[:400], Fraction(0))
    with mpmath.workdps(30):
        got = _at(30, stirling_series, mpmath.mpf(1))
        ref = mpmath.mpf(s400.numerator) / s400.denominator
        assert abs(got - ref) <= mpmath.mpf(10) ** -25 * abs(ref)


def test_stirling_ok_refuses_where_the_series_cannot_converge():
    # at x = 10**4 the 400 summed terms reach only ~1860 digits (the smallest kept term is
    # ~10**-1860 relative): above that precision x must also grow with dps
    with mpmath.workdps(2600):
        x = mpmath.mpf(10**4)
        ref = stirling_remainder(x)
        err = abs(_at(2600, stirling_series, x) - ref) / abs(ref)
        assert mpmath.mpf(10) ** -2000 < err < mpmath.mpf(10) ** -1500
    for dps in (2600, 5000):
        assert not stirling_ok(10**4, dps) and not stirling_ok(4 * dps, dps)
    for dps in range(15, 5001, 7):  # yes implies x > 4 dps (far below the divergence)
        assert not stirling_ok(4 * dps, dps) or 4 * dps >= 10**4
    # the first x where stirling_ok says yes at 2600 digits: the series does reach them
    dps = 2600
    lo, hi = 10**4, 10**6
    assert not stirling_ok(lo, dps) and stirling_ok(hi, dps)
    while hi - lo > 1:
        mid = (lo + hi) // 2
        lo, hi = (lo, mid) if stirling_ok(mid, dps) else (mid, hi)
    assert all(stirling_ok(x, dps) for x in range(hi, hi + 50))
    with mpmath.workdps(dps + 40):
        ref = stirling_remainder(hi)
    got = _at(dps, stirling_series, mpmath.mpf(hi))
    with mpmath.workdps(dps + 40):
        assert abs(got - ref) <= mpmath.mpf(10) ** (1 - dps) * abs(ref)


# --------------------------------------------------------------------------- mp_value
def test_mp_value_sympy_and_exact():
    sympy = pytest.importorskip("sympy")
    for dps in (15, 40, 100):
        with mpmath.workdps(dps + 20):
            ref = mpmath.sqrt(2) / 100 + mpmath.pi / 10**5
        before = mpmath.mp.prec
        got = _at(dps, mp_value, sympy.sqrt(2) / 100 + sympy.pi / 10**5, None)
        assert mpmath.mp.prec == before  # the global precision is not touched
        got_fr = _at(dps, mp_value, "ignored", Fraction(1, 3))
        with mpmath.workdps(dps + 20):
            assert abs(got - ref) <= mpmath.mpf(10) ** (-dps) * ref
            assert abs(got_fr - mpmath.mpf(1) / 3) <= mpmath.mpf(10) ** (-dps) / 3


def test_stirling_coefficients_are_the_bernoulli_ratios() -> None:
    """B_2r / (2r (2r - 1)) from FLINT's exact Bernoulli numbers equal mpmath's, r < 400."""
    got = stirling_coefficients(399)
    assert len(got) == 399
    for r, (num, den) in enumerate(got, 1):
        with mpmath.workdps(60):
            want = mpmath.bernoulli(2 * r) / (2 * r * (2 * r - 1))
            assert abs(mpmath.mpf(num) / den - want) <= abs(want) * mpmath.mpf(10) ** -55, r
