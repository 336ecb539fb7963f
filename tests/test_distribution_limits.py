"""The documented work limits of the simple distribution (``EXACT_N_LIMIT``,
``EXACT_WORK_LIMIT``, ``EXACT_QUANTILE_WORK_LIMIT``, ``MP_SUM_N_LIMIT``,
``MP_QUANTILE_N_LIMIT``, ``FLOAT_N_LIMIT``): refused before any work, by name, with N shown
legibly; inclusive at the limit itself, where the sums still agree with a closed form; past
the exact limits an exact p is evaluated at its exact rational value on the mpmath path.

References: the documented work measure ``N (bits of N + bits of p's numerator and
denominator)``; at N = 10**100 the Poisson limit of ``j = N - X`` (``E[X] = N - 1/p``) and the
logarithmic-series limit for ``N p < 1``; the term ratio for the mode at large N.
"""

from __future__ import annotations

import time
from fractions import Fraction

import mpmath
import pytest

import symhx
from symhx import distribution as dist
from symhx.distribution import (
    MP_QUANTILE_N_LIMIT,
    MP_SUM_N_LIMIT,
    SimpleDistribution,
)
from tests.harness.discrete import Path, check_refusals
from tests.harness.errors import assert_refuses


def test_mpmath_work_limits_refused_up_front():
    """The mpmath sums and quantiles name their documented limit, at once; the mode is decided
    without the sums (any N); at the limits themselves the sums still work: with j = N - X the
    weights are ~ (1/p)**j / j! (Poisson), so Var X = 1/p = 10 up to O(1/N) for p = 0.1 (the
    130-digit value; its binary neighbour is off by 1e-130 relative), and the median of X is N
    minus the Poisson(10) median (10) up to O(1/N)."""
    t = time.monotonic()
    d = symhx.distribution_of(MP_SUM_N_LIMIT * 10, mpmath.mpf("0.1"), dps=15)
    for method in ("mean", "var", "entropy"):
        assert_refuses(getattr(d, method), arg="N", value="N=10**1001",
                       allowed=["N <= 10**1000", "MP_SUM_N_LIMIT"])
    assert_refuses(d.median, arg="N", value="N=10**1001", allowed="MP_QUANTILE_N_LIMIT")
    assert_refuses(d.cdf, 3, arg="N", value="N=10**1001", allowed="MP_SUM_N_LIMIT")
    assert_refuses(symhx.mean, 10**1001, 0.1, arg="N", value="N=10**1001",
                   allowed="MP_SUM_N_LIMIT")
    assert_refuses(symhx.median, MP_QUANTILE_N_LIMIT + 1, mpmath.mpf("0.1"), dps=15, arg="N",
                   value="N=~10**1000", allowed=["N <= 10**1000", "MP_QUANTILE_N_LIMIT"])
    assert time.monotonic() - t < 2
    assert symhx.mode(10**1000, mpmath.mpf("0.1")) == 10**1000 - 9
    with mpmath.workdps(130):
        p = mpmath.mpf(1) / 10
    v = symhx.var(MP_SUM_N_LIMIT, p, dps=60)
    assert abs(v - 10) < mpmath.mpf(10) ** -55
    assert MP_QUANTILE_N_LIMIT - symhx.median(MP_QUANTILE_N_LIMIT, mpmath.mpf("0.1"),
                                              dps=15) == 10


def test_sum_limit_is_inclusive() -> None:
    """N = MP_SUM_N_LIMIT itself is summed (the message says N <= limit).  N p = 0.1 (binary
    p): the logarithmic series, mean = l / ((1 - l) (-log(1 - l))), up to O(1/N)."""
    N = MP_SUM_N_LIMIT
    p = mpmath.mpf("1e-1001")
    d = SimpleDistribution(N, p, dps=15)
    with mpmath.workdps(40):
        lam = N * p
        want = lam / ((1 - lam) * -mpmath.log1p(-lam))
    Path.mp(15).value(d.mean(), want, "mean")
    assert_refuses(SimpleDistribution(N + 1, p, dps=15).mean, arg="N", value="N=~10**1000",
                   allowed=["summing the distribution", "mpmath path", "N <= 10**1000 "])


def test_exact_work_limits():
    """Beyond the exact work limits an exact p is evaluated at its exact rational value on the
    mpmath path (mpf results, not its binary neighbour): the mean at p = "0.1" equals the mean
    at a 130-digit 1/10 to 50 digits and differs from the mean at the float 0.1 (p off by
    5.6e-18 relative moves E[X] ~ N - 1/p by ~5e-16).  The mode needs no sums
    (Phi(m+1)/Phi(m) = p (N-m) m/(m+1) <= 1 < the ratio one step below); just inside the limit,
    the exact mean still agrees with the mpmath path at 40 digits."""
    with mpmath.workdps(130):
        tenth = mpmath.mpf(1) / 10
    exact_p = symhx.mean(10**5, "0.1", dps=50)
    assert not isinstance(exact_p, Fraction)
    with mpmath.workdps(60):
        assert abs(exact_p / symhx.mean(10**5, tenth, dps=50) - 1) < mpmath.mpf(10) ** -49
        assert abs(exact_p / symhx.mean(10**5, 0.1, dps=50) - 1) > mpmath.mpf(10) ** -25
    assert symhx.median(20000, "0.1") == symhx.median(20000, tenth, dps=50)
    N, m, p = 10**5, symhx.mode(10**5, "0.1"), Fraction(1, 10)
    assert p * (N - m) * m / (m + 1) <= 1 < p * (N - m + 1) * (m - 1) / m
    exact = symhx.mean(20000, "0.1")
    assert isinstance(exact, Fraction)
    with mpmath.workdps(60):
        approx = symhx.mean(20000, mpmath.mpf(1) / 10, dps=40)
        assert abs(mpmath.mpf(exact.numerator) / exact.denominator / approx - 1) < 1e-38


def test_every_limit_is_refused_by_name() -> None:
    """Each documented limit: refused with N shown and the constant named; trivial quantiles
    need no sums; past EXACT_N_LIMIT an exact p runs on the mpmath path; past FLOAT_N_LIMIT the
    float64 path runs on the summation engine (only the sampling table is refused); bad k, q,
    size and random_state are refused by name."""
    past = SimpleDistribution(dist.EXACT_N_LIMIT + 1, "0.5")
    assert not past.exact and not isinstance(past.pmf(past.N), Fraction)
    SimpleDistribution(dist.EXACT_N_LIMIT, "0.5")  # the limit itself is allowed
    big = SimpleDistribution(dist.MP_QUANTILE_N_LIMIT + 1, 0.5, dps=15)
    for method in (big.ppf, big.isf):
        assert_refuses(method, "0.5", arg="N", value="N=~10**1000",
                       allowed=["N <= 10**1000", "MP_QUANTILE_N_LIMIT"])
    assert big.ppf(0) == 0 and big.isf(0) == big.N  # trivial quantiles need no sums
    huge = SimpleDistribution(10**1020, 0.5, dps=15)
    assert_refuses(huge.pmf, 5, arg="N", value="N=10**1020", allowed="MP_SUM_N_LIMIT")
    assert_refuses(SimpleDistribution(10**1020 + 1, 0.5, dps=15).mean, arg="N",
                   value="N=~10**1020", allowed="MP_SUM_N_LIMIT")
    wide = SimpleDistribution(dist.FLOAT_N_LIMIT + 1, 0.5, dps=None)
    want = SimpleDistribution(dist.FLOAT_N_LIMIT + 1, 0.5, dps=30).var()
    assert isinstance(wide.var(), float) and abs(wide.var() / float(want) - 1) < 1e-13
    assert_refuses(SimpleDistribution(dist.FLOAT_N_LIMIT + 1, 0.5).rvs, random_state=1,
                   arg="N", value="N=10000001", allowed="FLOAT_N_LIMIT=10000000")
    check_refusals(SimpleDistribution(10, 0.3, dps=20))  # k, q, size, random_state


def test_work_measure_is_the_documented_one() -> None:
    """N (bits of N + bits of p's numerator and denominator) against EXACT_WORK_LIMIT: just
    inside and just outside."""
    def work(N: int, p: Fraction) -> int:
        return N * (N.bit_length() + p.numerator.bit_length() + p.denominator.bit_length())

    p = Fraction(1, 3)
    inside = max(N for N in range(10_000, 40_000, 7) if work(N, p) <= dist.EXACT_WORK_LIMIT)
    assert SimpleDistribution(inside, p)._check_exact_work("x", dist.EXACT_WORK_LIMIT,
                                                           "EXACT_WORK_LIMIT") is None
    with pytest.raises(ValueError, match="EXACT_WORK_LIMIT"):
        SimpleDistribution(inside + 7, p)._check_exact_work("x", dist.EXACT_WORK_LIMIT,
                                                            "EXACT_WORK_LIMIT")
    q = Fraction(1, 2)
    N = max(n for n in range(1000, 20_000) if work(n, q) <= dist.EXACT_QUANTILE_WORK_LIMIT)
    SimpleDistribution(N, q)._check_exact_work("q", dist.EXACT_QUANTILE_WORK_LIMIT, "E")
    with pytest.raises(ValueError, match=str(dist.EXACT_QUANTILE_WORK_LIMIT)):
        SimpleDistribution(N + 1, q)._check_exact_work("q", dist.EXACT_QUANTILE_WORK_LIMIT,
                                                       "E")


def test_exact_work_boundary_is_inclusive() -> None:
    """work == EXACT_WORK_LIMIT is exact, one more N runs on the mpmath path (N = 20000,
    p = 1/256: 20000 * (15 + 1 + 9) = 500000); 1/256 is a binary number, so there the exact p
    and the mpf give the same values."""
    p = Fraction(1, 256)
    assert 20000 * (20000 .bit_length() + 1 + 9) == dist.EXACT_WORK_LIMIT
    d = SimpleDistribution(20000, p)
    d._check_exact_work("x", dist.EXACT_WORK_LIMIT, "EXACT_WORK_LIMIT")  # no error
    assert isinstance(d.cdf(3), Fraction)
    e = SimpleDistribution(20001, p)
    assert not e.exact
    binary = SimpleDistribution(20001, mpmath.mpf(1) / 256, dps=e.dps)
    assert e.cdf(3) == binary.cdf(3) and e.pmf(3) == binary.pmf(3)


def test_exact_work_message_shows_p_cut_to_40_characters() -> None:
    p = Fraction(1, 3**100)
    assert len(str(p)) > 41
    assert_refuses(SimpleDistribution(5000, p)._check_exact_work, "x", dist.EXACT_WORK_LIMIT,
                   "EXACT_WORK_LIMIT", arg=["N", "p"], value=f"N=5000, p={str(p)[:40]} (",
                   allowed="(documented work limit 500000,")


def test_quantile_limit_messages() -> None:
    """The mpmath quantile cap names itself; an exact p beyond the exact quantile budget is
    answered on the mpmath path (the smallest k with cdf(k) >= q)."""
    big = SimpleDistribution(10**1000 + 1, 0.5, dps=15)
    for method in (big.ppf, big.isf):
        assert_refuses(method, "0.5", arg="N", value="N=~10**1000",
                       allowed=["a quantile on the mpmath path", "N <= 10**1000",
                                "(symhx.distribution.MP_QUANTILE_N_LIMIT, a work limit)"])
    ex = SimpleDistribution(20000, "0.1")
    k = ex.ppf("0.5")
    assert ex.cdf(k - 1) < Fraction(1, 2) <= ex.cdf(k)
    assert ex.median() == k
    j = ex.isf("0.5")
    assert ex.sf(j) <= Fraction(1, 2) < ex.sf(j - 1)


def test_messages_show_huge_N() -> None:
    """Error messages write N as digits below 10**15, else as 10**e or ~10**e."""
    cases = {10**1001: "N=10**1001", 10**1001 + 1: "N=~10**1001",
             2 * 10**1002: "N=~10**1002"}
    for N, shown in cases.items():
        d = SimpleDistribution(N, 0.5, dps=15)
        msg = assert_refuses(d.ppf, "0.5", arg="N", value=shown,
                             allowed=["limited to N <= 10**1000 ", "MP_QUANTILE_N_LIMIT"])
        assert shown + "." in msg or shown + " " in msg or msg.endswith(shown), (N, msg)
    for N, shown in {10**15 - 1: "N=999999999999999", 10**15: "N=10**15",
                     10**15 + 1: "N=~10**15", 10**7 + 1: "N=10000001"}.items():
        assert_refuses(SimpleDistribution(N, 0.5).rvs, random_state=1, arg="N", value=shown,
                       allowed="FLOAT_N_LIMIT")


def test_N_below_one_is_refused() -> None:
    """N counts vertices: N = 0 and N = -3 are refused with the value and the bound."""
    for N in (0, -3):
        assert_refuses(SimpleDistribution, N, "1/2", arg="N", value=f"got {N}", allowed=">= 1")
