"""The frozen-distribution base class on the mpmath path of a higher-order space (eq. 41):
cdf, sf and their logs are sums of the space's terms at dps digits, against the exact table of
the space's weights (Burnside counts)."""

from __future__ import annotations

from fractions import Fraction

import mpmath

import symhx
from tests.reference.spaces import exact_table

N, DPS = 12, 30


def test_space_cdf_and_sf_on_the_mpmath_path_match_the_exact_table() -> None:
    ref = exact_table(N, Fraction(1, 2), "eq41")
    d = symhx.distribution_of(N, 0.5, space="eq41", dps=DPS)  # 0.5 is exactly 1/2
    tol = mpmath.mpf(10) ** (1 - DPS)
    with mpmath.workdps(2 * DPS):
        for k in range(1, N):
            for got, want in ((d.cdf(k), ref.cdf(k)), (d.sf(k), ref.sf(k))):
                w = mpmath.mpf(want.numerator) / want.denominator
                assert abs(got - w) <= tol * w, (k, got, w)
            lc = mpmath.log(mpmath.mpf(ref.cdf(k).numerator) / ref.cdf(k).denominator)
            assert abs(d.logcdf(k) - lc) <= tol * max(1, abs(lc)), k
