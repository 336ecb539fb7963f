"""The simple distribution at huge N away from its bulk: cdf, logcdf and logpmf at k far below
or above the hump (where |log Phi| reaches ~N and a sum's relative accuracy needs log Phi to
absolute accuracy), and quantiles at N up to 10**1000, decided to the integer."""

from __future__ import annotations

from fractions import Fraction

import mpmath
import pytest

import symhx
from tests.reference.distribution_large_n import critical_p, log_lower_sum_geometric, log_phi


@pytest.mark.parametrize("k", [10**20, 10**49, 10**60, 10**99])
def test_logcdf_far_below_the_hump_matches_a_direct_walk_down(k: int) -> None:
    """N = 1e100, N p = 2: below the hump every ratio Phi(j+1)/Phi(j) is about 2, so the cdf
    at k is Phi(k) times a geometric factor; log cdf(k) (~ -1.9e99, to 30 significant digits)
    is checked against the terms walked down from k with loggamma minus log Gamma at 140
    digits, and against the same call at 60 digits."""
    N, p = 10**100, Fraction(2, 10**100)
    d = symhx.distribution_of(N, p, dps=30)
    with mpmath.workdps(150):
        want = log_lower_sum_geometric(N, p, k, 140) - \
            symhx.distribution_of(N, p, dps=140).log_normaliser
        assert abs(d.logcdf(k) - want) <= abs(want) * mpmath.mpf(10) ** -29
        hi = symhx.distribution_of(N, p, dps=60).logcdf(k)
        assert abs(hi - want) <= abs(want) * mpmath.mpf(10) ** -59


def test_cdf_far_below_the_hump_keeps_its_digits() -> None:
    """cdf itself (~exp(-1e99)): dps 30 against dps 60 to 29 digits relative."""
    N, p = 10**100, Fraction(2, 10**100)
    lo, hi = symhx.distribution_of(N, p, dps=30), symhx.distribution_of(N, p, dps=60)
    for k in (10**30, 10**99):
        with mpmath.workdps(80):
            assert abs(lo.cdf(k) / hi.cdf(k) - 1) <= mpmath.mpf(10) ** -29, k


def test_cdf_keeps_relative_accuracy_where_its_log_is_huge() -> None:
    """cdf ~ 10**(-10**20) at N = 1e100, 10**60 below the mode: its dps digits hold."""
    N = 10**100
    p = critical_p(N) * 10
    lo, hi = symhx.distribution_of(N, p, dps=30), symhx.distribution_of(N, p, dps=60)
    k = lo.mode() - 10**60
    with mpmath.workdps(80):
        assert abs(lo.cdf(k) / hi.cdf(k) - 1) <= mpmath.mpf(10) ** -29
        assert abs(lo.sf(k + 2 * 10**60) / hi.sf(k + 2 * 10**60) - 1) <= mpmath.mpf(10) ** -29


@pytest.mark.parametrize("offset", [-(10**60), -(10**52), 10**52, 10**60])
def test_logpmf_far_from_the_mode_matches_loggamma(offset: int) -> None:
    """log P(X = k) = log Phi(k) - log Gamma to 10**-dps absolute, |log Phi| up to ~1e20."""
    N = 10**100
    p = critical_p(N) * 10
    d = symhx.distribution_of(N, p, dps=30)
    k = d.mode() + offset
    with mpmath.workdps(200):  # log Phi and log Gamma are ~1e102 each: 140 digits of both
        want = log_phi(N, p, k, 40) - symhx.distribution_of(N, p, dps=145).log_normaliser
        assert abs(d.logpmf(k) - want) <= mpmath.mpf(10) ** -29 * max(1, abs(want))


def _check_quantile(N: int, p: Fraction, q: Fraction, k: int, upper: bool = False,
                    dps: int = 30) -> None:
    """k is the smallest integer with cdf(k) >= q (1 - 10**(1 - dps)) (upper: sf(k) <= q (1 +
    10**(1 - dps))), the documented resolution of q, with the cdf of a fresh distribution at
    dps + digits(N)/2 + 30 digits: enough to tell k - 1 from k where the cdf moves by
    ~1/sqrt(N) per unit of k."""
    ref_dps = dps + len(str(N)) // 2 + 30
    ref = symhx.distribution_of(N, p, dps=ref_dps)
    with mpmath.workdps(ref_dps + 20):
        qm = mpmath.mpf(q.numerator) / q.denominator
        if upper:
            qm *= 1 + mpmath.mpf(10) ** (1 - dps)
            assert ref.sf(k) <= qm < ref.sf(k - 1), (N, q, k)
        else:
            qm *= 1 - mpmath.mpf(10) ** (1 - dps)
            assert ref.cdf(k - 1) < qm <= ref.cdf(k), (N, q, k)


@pytest.mark.parametrize("N", [10**30, 10**100])
@pytest.mark.parametrize("ratio", [Fraction(1, 2), Fraction(999, 1000), Fraction(1001, 1000),
                                   Fraction(2), Fraction(10)])
def test_quantiles_at_huge_N_are_the_smallest_k_that_reach_q(N: int, ratio: Fraction) -> None:
    """ppf at q = 1e-30, 1/2, 1 - 1e-9 and isf at 1e-30, below, at and above the jump."""
    p = critical_p(N) * ratio
    d = symhx.distribution_of(N, p, dps=30)
    for q in (Fraction(1, 10**30), Fraction(1, 2), 1 - Fraction(1, 10**9)):
        _check_quantile(N, p, q, d.ppf(q))
    _check_quantile(N, p, Fraction(1, 10**30), d.isf(Fraction(1, 10**30)), upper=True)


@pytest.mark.slow
@pytest.mark.parametrize(("N", "ratio"), [
    (10**300, Fraction(1, 2)), (10**300, Fraction(1001, 1000)), (10**300, Fraction(10)),
    (10**1000, Fraction(2))])
def test_median_up_to_the_quantile_limit(N: int, ratio: Fraction) -> None:
    """The median at N = 10**300 and at MP_QUANTILE_N_LIMIT = 10**1000 (proving the integer
    takes ~dps + 500 digits of the cdf there: it moves by ~1e-500 per unit of k)."""
    from symhx.distribution import MP_QUANTILE_N_LIMIT

    assert N <= MP_QUANTILE_N_LIMIT
    p = critical_p(N) * ratio
    _check_quantile(N, p, Fraction(1, 2), symhx.distribution_of(N, p, dps=30).median())


@pytest.mark.parametrize("offset", [-(10**70), 10**70])
def test_pmf_where_its_log_is_1e40_keeps_relative_accuracy(offset: int) -> None:
    """P(X = k) ~ exp(-1e40) 10**70 from the mode at N = 10**100: its relative accuracy needs
    log P to 1e-30 absolute, 70 digits of it (the engine takes them for that range)."""
    N = 10**100
    p = critical_p(N) * 10
    d = symhx.distribution_of(N, p, dps=30)
    k = d.mode() + offset
    with mpmath.workdps(300):
        want = mpmath.exp(log_phi(N, p, k, 80)
                          - symhx.distribution_of(N, p, dps=145).log_normaliser)
        assert abs(d.pmf(k) / want - 1) <= mpmath.mpf(10) ** -29


def _agree(lo, hi, dps: int, log: bool = False) -> None:
    with mpmath.workdps(2 * dps + 20):
        err = abs(lo - hi) if log else abs(lo - hi) / abs(hi)
        assert err <= mpmath.mpf(10) ** -dps * (max(1, abs(hi)) if log else 1), (lo, hi)


@pytest.mark.parametrize(("e", "ratio", "calls", "dps"), [
    # a short run at x ~ 1e40 below the jump (its log x panels were 1e-36 wide: "quadrature
    # panels do not converge" after 25 s)
    (50, Fraction(999, 1000), ("sf(10**40)", "logsf(10**40)", "mean()"), 20),
    (300, Fraction(1001, 1000), ("mean()", "cdf(N // 10**150)", "logcdf(N // 10**150)"), 20),
    # a step of a cached partial sum into the far tail (the stretch [N - 1, N - 1] at
    # |log Phi| ~ 8e100 without the digits: OverflowError)
    (100, Fraction(1, 1000), ("logcdf(N - 2)", "logcdf(N - 1)", "logsf(N - 2)"), 20),
])
def test_far_tails_and_short_runs_at_huge_N_against_twice_the_digits(e, ratio, calls,
                                                                      dps) -> None:
    N = 10**e
    p = critical_p(N) * ratio
    lo, hi = symhx.distribution_of(N, p, dps=dps), symhx.distribution_of(N, p, dps=2 * dps)
    for call in calls:
        a = eval("lo." + call, {"lo": lo, "N": N})
        b = eval("hi." + call, {"hi": hi, "N": N})
        _agree(a, b, dps, log=call.startswith("log"))


def test_a_tail_whose_complement_lies_far_in_the_other_tail() -> None:
    """sf(k) before any full pass sums [k + 1, N] and its complement [1, k]; at N = 1e100,
    p = 2 p_c (a 60-digit mpf) and k 1e83 below the mode the complement's terms have
    |log Phi| ~ 1e65 and need those digits (at 17 digits two offsets of a run 1e43 long at
    1e83 from the reference rounded to the same number: ZeroDivisionError)."""
    N = 10**100
    p = 2 * symhx.critical_point(N, dps=60).p
    k = N // 2 - 10**51
    lo, hi = symhx.distribution_of(N, p, dps=17), symhx.distribution_of(N, p, dps=34)
    _agree(lo.sf(k), hi.sf(k), 17)
    _agree(lo.logcdf(k), hi.logcdf(k), 17, log=True)


@pytest.mark.parametrize(("ratio", "call", "dps"), [
    (Fraction(11, 10), "sf(105 * 10**47)", 50),
    (Fraction(1001, 1000), "cdf(44320000 * 10**39)", 20),
])
def test_euler_maclaurin_ends_where_the_terms_fall_steeply(ratio, call, dps) -> None:
    """A tail that starts where the terms fall by ~2% per step (N = 1e50, beyond the hump):
    its Euler-Maclaurin end took the Cauchy radius of the hump's width, so one correction
    term, and kept 15 of 50 digits (4.8e-16); against twice the digits."""
    N = 10**50
    p = critical_p(N) * ratio
    lo = eval("d." + call, {"d": symhx.distribution_of(N, p, dps=dps)})
    hi = eval("d." + call, {"d": symhx.distribution_of(N, p, dps=2 * dps + 5)})
    _agree(lo, hi, dps)
