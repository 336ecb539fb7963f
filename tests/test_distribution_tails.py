"""Tails of the simple distribution: ``cdf``, ``sf`` and their logs keep their relative accuracy
far in the tails and where the probability is close to 1, certain events cost no sums, and the
terms summed may form two separate runs.

References: exact partial sums of integer weights proportional to ``Phi(k)`` (a float p at its
binary value) and mpmath's plain ``log`` of them at 700 digits; ``log Phi`` from ``loggamma``
at ``2 dps + 20`` digits with every term summed; the term ratio run downwards from ``k = N``;
the mpmath path at 60 digits for the exact path's logs (another algorithm).
"""

from __future__ import annotations

from fractions import Fraction

import mpmath
import pytest

import symhx
from symhx.distribution import SimpleDistribution
from tests.harness.discrete import Path, check_log_tails_on_path
from tests.reference.distribution import (
    pmf_by_downward_ratio,
    pmf_by_loggamma,
    simple_integer_weights,
    tail_logs,
)

CASES = [(30, Fraction(1, 2)), (1000, Fraction(0.00314159)), (60, Fraction(3, 7))]


@pytest.mark.parametrize("N,p", CASES)
@pytest.mark.parametrize("dps", [None, 0, 15, 40])  # 0: the exact path
def test_log_tails_near_probability_one(N, p, dps):
    """``logcdf`` / ``logsf`` to ``dps`` significant digits (float64: 100x the documented
    relative error) also near probability 1."""
    ks = sorted({1, 2, 3, N // 2, N - 3, N - 2, N - 1})
    logs = tail_logs(simple_integer_weights(N, p), ks)
    check_log_tails_on_path(lambda q, dps: symhx.distribution_of(N, q, dps=dps), p, dps, logs)


def test_log_tails_are_tiny_not_positive():
    """N = 1000, p = 0.00314159, dps = 15: logsf(1) is -2.2e-200 (a log of P rounded to 15
    digits would give a tiny positive number, +1.6e-32)."""
    d = symhx.distribution_of(1000, 0.00314159, space="simple", dps=15)
    v = d.logsf(1)
    assert -1e-199 < v < -1e-201


@pytest.mark.slow
def test_exact_logs_of_huge_fractions_away_from_one():
    """Exact path at dps = 20, |log P| of order 1 for fractions with 241024-bit numerators and
    denominators: log(num) - log(den) cancels about 5 digits, which the working precision must
    add on top of its guard digits. Against the mpmath path at 60 digits (another algorithm:
    sums of mpf terms)."""
    N, p = 20000, Fraction(1, 3)
    ex = symhx.distribution_of(N, p, dps=20)
    with mpmath.workdps(200):
        third = mpmath.mpf(1) / 3  # 1/3 to 200 digits: moves the logs by ~1e-195
    ref = symhx.distribution_of(N, third, dps=60)
    assert ex.exact and not ref.exact
    m = ex.mode()
    far = 0
    for k in range(m - 6, m + 3):
        for got, want in ((ex.logcdf(k), ref.logcdf(k)), (ex.logsf(k), ref.logsf(k))):
            far += want < -0.7  # the difference route (P <= 1/2)
            with mpmath.workdps(60):
                # 3 units of the 70-bit result: a correctly rounded value is within half a unit
                # (with 5 digits too few in the working precision it was 8.5 units off)
                assert abs(got - want) <= 3 * mpmath.mpf(2) ** -69 * abs(want), (k, got, want)
    assert far >= 8


@pytest.mark.parametrize("dps", [20, 50])
def test_logs_of_certain_events_are_exactly_zero(dps: int) -> None:
    for N, pf in ((1, 0.5), (6, 0.3), (40, 0.07)):
        d = symhx.distribution_of(N, pf, dps=dps)
        assert d.logcdf(N) == 0 and d.logcdf(N + 5) == 0
        assert d.logsf(0) == 0 and d.logsf(-3) == 0
        assert d.logsf(N) == mpmath.ninf and d.logcdf(0) == mpmath.ninf
        assert d.cdf(N) == 1 and d.sf(0) == 1 and d.sf(N) == 0 and d.cdf(0) == 0


def test_certain_events_need_no_sums() -> None:
    """cdf(k >= N) = 1 and sf(k >= N) = 0 are answered without summing (any N)."""
    d = SimpleDistribution(10**120, 0.5, dps=15)
    assert d.cdf(10**120) == 1 and d.sf(10**120) == 0 and d.cdf(10**121) == 1
    assert d.logcdf(10**120) == 0 and d.logsf(10**120) == mpmath.ninf
    assert d.cdf(0) == 0 and d.sf(0) == 1


@pytest.mark.parametrize("k", range(540, 560))
def test_tail_sums_with_two_runs_of_significant_terms(k: int) -> None:
    """N = 1000, p = 0.0017, dps = 15: for sf(k) near k = 549 the terms within the working
    precision of the largest one in [k+1, N] form two runs, {1} and a hump run (Phi(1) is just
    above the cut, the valley at k = 2, 3 just below).  Both runs must be kept and summed."""
    N, dps = 1000, 15
    d = SimpleDistribution(N, 0.0017, dps=dps)
    ref = pmf_by_loggamma(N, mpmath.mpf(0.0017), 2 * dps + 20)
    path = Path.mp(dps)
    with mpmath.workdps(2 * dps + 20):
        path.value(d.sf(k), mpmath.fsum(ref[k:]), ("sf", k))
        path.value(d.cdf(k), mpmath.fsum(ref[:k]), ("cdf", k))
        path.log(d.logsf(k), mpmath.fsum(ref[k:]), ("logsf", k))


def test_lower_tail_below_an_exact_binary_tie_far_above_phi_one() -> None:
    """N = 2049, p = 2**-10 (exact in binary): Phi(1024) = Phi(1025) exactly, ~e**390 above
    Phi(1); the lower tail below the hump is still summed to dps digits."""
    N, pf, dps = 2049, 2.0**-10, 20
    assert Fraction(pf) * (N - 1024) * 1024 / 1025 == 1  # the exact tie
    d = symhx.distribution_of(N, pf, dps=dps)
    assert d.modes() == (1024, 1025) and d.mode() == 1024
    ref = pmf_by_downward_ratio(N, Fraction(pf), 2 * dps + 20)
    path = Path.mp(dps)
    with mpmath.workdps(2 * dps + 20):
        for k in (1, 10, 500, 1024):
            c = mpmath.fsum(ref[:k])
            path.value(d.cdf(k), c, ("cdf", k))
            path.log(d.logcdf(k), c, ("logcdf", k))
        path.value(d.sf(1030), mpmath.fsum(ref[1030:]), "sf")
        path.value(d.pmf(1025), ref[1024], "pmf")
