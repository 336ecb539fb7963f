"""``logcdf`` / ``logsf`` to ``dps`` significant digits also where the probability is close to 1
(the log is then tiny, and log(P) of a P with dps digits would only be absolutely accurate).

Reference: exact Fractions for every weight (a float p at its binary value), the tail sums
exact, and mpmath's plain ``log`` of them at 700 digits (enough for logs down to 1e-600)."""

from __future__ import annotations

import math
from fractions import Fraction
from functools import cache

import mpmath
import numpy as np
import pytest

import symhx
from symhx.spaces import parse_space
from tests.reference.distribution import phi_exact


@cache
def _cdf(N: int, p: Fraction, space: str) -> tuple[Fraction, ...]:
    """Exact P(X <= k), k = 1..N, from W(k) = p**k N!/(k (N-k)!) Q*(k) (common denominator)."""
    sp = None if space == "simple" else parse_space(space)
    w = [phi_exact(N, p, k) * (1 if sp is None else sp.Qstar(k, p))
         for k in range(1, N + 1)]
    den = math.lcm(*(x.denominator for x in w))
    nums = [x.numerator * (den // x.denominator) for x in w]
    tot, acc, out = sum(nums), 0, []
    for n in nums:
        acc += n
        out.append(Fraction(acc, tot))
    return tuple(out)


def _log(x: Fraction) -> mpmath.mpf:
    with mpmath.workdps(700):
        return mpmath.log(mpmath.mpf(x.numerator) / x.denominator)


CASES = [(30, Fraction(1, 2), "simple"), (1000, Fraction(0.00314159), "simple"),
         (200, Fraction(1, 40), "eq41"), (60, Fraction(3, 7), "simple")]


@pytest.mark.parametrize("N,p,space", CASES)
@pytest.mark.parametrize("dps", [None, 0, 15, 40])  # 0: the exact path
def test_log_tails_near_probability_one(N, p, space, dps):
    cdf = _cdf(N, p, space)
    ks = sorted({1, 2, 3, N // 2, N - 3, N - 2, N - 1})
    if dps == 0:
        d = symhx.distribution_of(N, p, space=space)
        tol = mpmath.mpf(10) ** -14
    else:
        d = symhx.distribution_of(N, float(p) if dps is None else p, space=space, dps=dps)
        # float64: 100x the documented relative error ~1e-16 N log N (log-weights from
        # gammaln); before the fix the error near log = 0 was of order 1 or more
        tol = mpmath.mpf(10) ** (1 - dps) if dps else mpmath.mpf(1e-14 * N * math.log(N))
    for k in ks:
        for got, want in ((d.logcdf(k), _log(cdf[k - 1])), (d.logsf(k), _log(1 - cdf[k - 1]))):
            with mpmath.workdps(700):
                err = abs(mpmath.mpf(got) - want) / abs(want)
            assert err <= tol, (k, float(got), mpmath.nstr(want, 8), mpmath.nstr(err, 3))
    if dps is None:  # the array form takes the same table
        arr = d.logsf(np.array(ks))
        assert [float(x) for x in arr] == [float(d.logsf(k)) for k in ks]


def test_log_tails_are_tiny_not_positive():
    """The case that showed the bug: logsf(1) was +1.6e-32 at dps = 15 (true: -2.2e-200)."""
    d = symhx.distribution_of(1000, 0.00314159, space="simple", dps=15)
    v = d.logsf(1)
    assert -1e-199 < v < -1e-201


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
