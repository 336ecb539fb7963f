"""Distributions of X over simple circuits (eqs. 7-8): exact, mpmath, stress."""

from fractions import Fraction

import mpmath
import pytest
from hypothesis import given
from hypothesis import strategies as st

import symhx
from symhx.distribution import SimpleDistribution
from tests.reference.distribution import brute_modes, phi_exact, pmf_table

fractions_p = st.fractions(min_value=Fraction(1, 10**4), max_value=1).filter(lambda x: x > 0)


@given(st.integers(1, 60), fractions_p)
def test_exact_pmf_sums_to_one_and_matches_direct(N, p):
    d = symhx.distribution_of(N, p)
    pm = [d.pmf(k) for k in range(1, d.N + 1)]
    assert sum(pm) == 1
    assert pm == pmf_table(N, p)


@given(st.integers(1, 60), fractions_p)
def test_exact_moments(N, p):
    table = pmf_table(N, p)
    mu = sum(k * x for k, x in enumerate(table, 1))
    assert symhx.mean(N, p) == mu
    assert symhx.var(N, p) == sum((k - mu) ** 2 * x for k, x in enumerate(table, 1))


@given(st.integers(2, 80), fractions_p)
def test_modes_are_the_maximisers(N, p):
    assert symhx.modes(N, p) == brute_modes(N, p)
    assert symhx.mode(N, p) == brute_modes(N, p)[0]


@given(st.integers(2, 300), fractions_p, st.integers(1, 299))
def test_sign_of_difference_is_sign_of_f(N, p, k):
    # eq. (9)-(10): sign(Phi(k+1) - Phi(k)) = sign(f_{N,p}(k))
    k = min(k, N - 1)
    if k < 1:
        return
    diff = phi_exact(N, p, k + 1) - phi_exact(N, p, k)
    f = -p * k * k + (N * p - 1) * k - 1
    assert (diff > 0) - (diff < 0) == (f > 0) - (f < 0)


@given(st.integers(2, 400), st.lists(fractions_p, min_size=2, max_size=6))
def test_mode_non_decreasing_in_p(N, ps):
    ps = sorted(ps)
    ms = [symhx.mode(N, p) for p in ps]
    assert ms == sorted(ms)


def test_documented_ties():
    # N = 101, p = 1/50: Phi(50) = Phi(51) exactly (f(50) = 0)
    p = Fraction(1, 50)
    assert phi_exact(101, p, 50) == phi_exact(101, p, 51)
    assert symhx.modes(101, p) == (50, 51) and symhx.mode(101, p) == 50
    # N = 5, p = 1/2: Phi(1) = Phi(2) = Phi(3)
    assert symhx.modes(5, Fraction(1, 2)) == (1, 2, 3)


@pytest.mark.parametrize("N", [2, 3, 4, 5, 17, 100, 101, 1000])
@pytest.mark.parametrize("p", [1e-300, 1e-3, 0.02, 0.3, 1.0])
def test_mpmath_path_matches_exact(N, p):
    # floats are exact binary rationals: the exact path is an independent route
    if p == 1e-300 and N > 200:
        pytest.skip("exact reference with a 2**-1000 denominator is too slow at this N")
    exact = symhx.distribution_of(N, Fraction(p))
    d = symhx.distribution_of(N, p, dps=40)
    tol = mpmath.mpf(10) ** -38
    with mpmath.workdps(60):
        for got, want in [(d.mean(), exact.mean()), (d.var(), exact.var())]:
            want = mpmath.mpf(want.numerator) / want.denominator
            assert abs(got - want) <= tol * abs(want) + mpmath.mpf(10) ** -300, (got, want)
        for k in {1, 2, max(1, N // 2), N}:
            want = exact.pmf(k)
            lw = mpmath.log(want.numerator) - mpmath.log(want.denominator)
            assert abs(d.logpmf(k) - lw) <= tol * max(1, abs(lw))


@pytest.mark.parametrize("dps", [15, 50, 200])
def test_precision_follows_dps(dps):
    N, p = 10**4, mpmath.mpf("0.0003")
    lo = symhx.mean(N, p, dps=dps)
    hi = symhx.mean(N, p, dps=2 * dps)
    with mpmath.workdps(2 * dps):
        assert abs(lo - hi) <= mpmath.mpf(10) ** (1 - dps) * abs(hi)


def test_huge_N_log_space():
    N = 10**6
    d = symhx.distribution_of(N, 2.5e-6, dps=30)
    d2 = symhx.distribution_of(N, 2.5e-6, dps=60)
    with mpmath.workdps(60):
        assert abs(d.mean() - d2.mean()) <= mpmath.mpf(10) ** -28 * d2.mean()
        assert abs(d.var() - d2.var()) <= mpmath.mpf(10) ** -28 * d2.var()
    assert 1 <= d.mean() <= N
    # the pmf underflows a float but not the log-pmf
    assert d.logpmf(N) < -1e5 and mpmath.isfinite(d.logpmf(N))
    assert float(mpmath.exp(d.logpmf(N))) == 0.0
    # logpmf(k+1) - logpmf(k) = log(p (N-k) k / (k+1))  (ratio of eq. 8 terms)
    k = 1234
    with mpmath.workdps(40):
        want = mpmath.log(mpmath.mpf(2.5e-6) * (N - k) * k / (k + 1))
        assert abs((d2.logpmf(k + 1) - d2.logpmf(k)) - want) < mpmath.mpf(10) ** -28


def test_tiny_p_all_mass_at_one():
    N, p = 1000, 1e-300
    d = symhx.distribution_of(N, p, dps=30)
    with mpmath.workdps(40):
        # P(X=2)/P(X=1) = p (N-1)/2
        assert mpmath.almosteq(d.logpmf(2) - d.logpmf(1), mpmath.log(mpmath.mpf(p) * (N - 1) / 2),
                               rel_eps=mpmath.mpf(10) ** -25)
    assert abs(d.mean() - 1) < 1e-290 and d.mode() == 1


def test_p_equal_one_and_N_two():
    assert symhx.pmf(2, 1, 1) == Fraction(2, 3)
    assert symhx.modes(2, 1) == (1,)
    assert symhx.modes(3, 1) == (1, 2)  # N = 3 ties at p = p_c = 1
    assert symhx.mean(5, 1) == sum(k * x for k, x in enumerate(pmf_table(5, Fraction(1)), 1))


def test_mode_huge_N_rational():
    N = 10**100
    cp = symhx.critical_point(N, dps=120)
    # p = (1 + q (1 -+ 1e-60)) / N with q = N p_c - 1 ~ 1.5e-49: just either side of p_c.
    # (Consecutive breakpoints of the mode are ~1/k**2 ~ 4e-103 apart in N p, so the margin
    # must be that fine for the mode just above p_c to still be k_after.)
    with mpmath.workdps(250):
        below = (1 + cp.q * (1 - mpmath.mpf(10) ** -60)) / N
        above = (1 + cp.q * (1 + mpmath.mpf(10) ** -60)) / N
    assert symhx.mode(N, below) == 1
    assert symhx.mode(N, above) == cp.k_after


def test_bad_input():
    with pytest.raises(ValueError, match="p"):
        symhx.mean(10, 0)
    with pytest.raises(ValueError, match="p"):
        symhx.mean(10, -0.1)
    with pytest.raises(ValueError, match="p"):
        symhx.mode(10, float("nan"))
    with pytest.raises(ValueError, match="p"):
        symhx.mode(10, float("inf"))
    with pytest.raises(ValueError, match="N"):
        symhx.mode(0, 0.5)
    with pytest.raises(TypeError, match="N"):
        symhx.mode(1e10, 0.5)
    with pytest.raises(ValueError, match="dps"):
        symhx.mean(10, 0.5, dps=0)
    with pytest.raises(ValueError, match="exact"):
        SimpleDistribution(10**6, Fraction(1, 3))
    with pytest.raises(ValueError, match="space"):
        symhx.mean(10, 0.5, space="no-such-space")


def test_sympy_rational_is_exact():
    sympy = pytest.importorskip("sympy")
    assert symhx.mean(7, sympy.Rational(1, 3)) == symhx.mean(7, Fraction(1, 3))
    # an irrational sympy number goes through mpmath
    v = symhx.mean(7, sympy.sqrt(2) / 10, dps=30)
    with mpmath.workdps(40):
        p = mpmath.sqrt(2) / 10
        w = [p**k * mpmath.factorial(7) / (k * mpmath.factorial(7 - k)) for k in range(1, 8)]
        want = mpmath.fsum(k * x for k, x in enumerate(w, 1)) / mpmath.fsum(w)
        assert abs(v - want) < mpmath.mpf(10) ** -28


@pytest.mark.parametrize(("N", "p"), [(2, 0.5), (100, 0.02), (101, 1e-300), (300, 0.9)])
def test_table_matches_exact(N, p):
    exact = pmf_table(N, Fraction(p)) if N <= 101 or p > 1e-10 else None
    tab = symhx.distribution_of(N, p, dps=30).table()
    assert [k for k, _ in tab] == list(range(1, N + 1))
    if exact is None:
        return
    with mpmath.workdps(50):
        for (_, got), want in zip(tab, exact, strict=True):
            w = mpmath.mpf(want.numerator) / want.denominator
            assert abs(got - w) <= mpmath.mpf(10) ** -29 * w


def test_work_limits_refused_up_front():
    """Fuzz-round caps: the mpmath sums and quantiles name their documented limit."""
    import time

    from symhx.distribution import MP_QUANTILE_N_LIMIT, MP_SUM_N_LIMIT

    t = time.monotonic()
    d = symhx.distribution_of(MP_SUM_N_LIMIT * 10, mpmath.mpf("0.1"), dps=15)
    for method in ("mean", "var", "entropy", "median"):
        with pytest.raises(ValueError, match=r"MP_SUM_N_LIMIT|MP_QUANTILE_N_LIMIT"):
            getattr(d, method)()
    with pytest.raises(ValueError, match="MP_SUM_N_LIMIT"):
        d.cdf(3)
    with pytest.raises(ValueError, match="MP_SUM_N_LIMIT"):
        symhx.mean(10**1000, 0.1)
    with pytest.raises(ValueError, match="MP_QUANTILE_N_LIMIT"):
        symhx.median(MP_QUANTILE_N_LIMIT + 1, mpmath.mpf("0.1"), dps=15)
    assert time.monotonic() - t < 2
    # the mode is decided without the sums: any N
    assert symhx.mode(10**1000, mpmath.mpf("0.1")) == 10**1000 - 9
    # at the limit itself the sums still work: with j = N - X the weights are ~ (1/p)**j / j!
    # (Poisson), so E[X] = N - 1/p up to O(1/N) for p = 0.1 (at 130 digits; its binary value is
    # off by 1e-130 relative), checked at 110 digits (absolute 1e-8)
    with mpmath.workdps(130):
        p = mpmath.mpf(1) / 10
    m = symhx.mean(MP_SUM_N_LIMIT, p, dps=110)
    with mpmath.workdps(130):
        assert abs(m - (MP_SUM_N_LIMIT - 10)) < mpmath.mpf(10) ** -8
    # and the quantiles: the median of the upper tail is one of the top few k
    assert 0 <= MP_QUANTILE_N_LIMIT - symhx.median(MP_QUANTILE_N_LIMIT, mpmath.mpf("0.1"),
                                                     dps=15) < 20


def test_exact_work_limits():
    """Exact sums and quantiles are refused up front past their documented bit budgets; just
    inside, the exact mean still agrees with the mpmath path at 40 digits."""
    import time

    t = time.monotonic()
    with pytest.raises(ValueError, match="EXACT_WORK_LIMIT"):
        symhx.mean(10**5, "0.1")
    with pytest.raises(ValueError, match="EXACT_WORK_LIMIT"):
        symhx.cdf(10**4, "1e-30", 3)
    with pytest.raises(ValueError, match="EXACT_QUANTILE_WORK_LIMIT"):
        symhx.median(20000, "0.1")
    assert time.monotonic() - t < 1
    # the mode needs no sums: Phi(m+1)/Phi(m) = p (N-m) m/(m+1) <= 1 < the ratio one step below
    N, m, p = 10**5, symhx.mode(10**5, "0.1"), Fraction(1, 10)
    assert p * (N - m) * m / (m + 1) <= 1 < p * (N - m + 1) * (m - 1) / m
    exact = symhx.mean(20000, "0.1")
    with mpmath.workdps(60):
        approx = symhx.mean(20000, mpmath.mpf(1) / 10, dps=40)
        assert abs(mpmath.mpf(exact.numerator) / exact.denominator / approx - 1) < 1e-38


def test_tiny_binary_p_is_fast():
    """A tiny binary p (a 3.3-million-bit denominator) neither hangs nor loses accuracy:
    var X = P(2) + O(p**2) = 5 p (N = 11: Phi(2)/Phi(1) = p (N - 1)/2)."""
    import time

    p = mpmath.mpf("1e-1000000")
    t = time.monotonic()
    v = symhx.var(11, p, dps=30)
    assert time.monotonic() - t < 2
    with mpmath.workdps(60):
        assert abs(v / (5 * p) - 1) < mpmath.mpf(10) ** -25
