"""The entropy of :class:`symhx.distribution.Distribution` (mpmath path) at magnitudes away from
``[1, 8)``: absolute error below ``10**-dps`` with the result rounded once to ``dps`` digits after
the point, which for tens of nats means more than ``dps`` significant digits; and an entropy
near 0 (one value of X almost sure) keeps ``dps`` significant digits, no more.

References: for small N, ``-sum P log P`` over the exact table (Fractions from the factorials,
Burnside weights for a space) at twice the digits; at ``N = 10**30`` (an entropy of ~35 nats,
a hump ~10**15 wide) the entropy at ``2 dps + 10`` digits.
"""

from __future__ import annotations

from fractions import Fraction

import mpmath
import pytest
from mpmath.libmp import dps_to_prec

import symhx
from tests.reference.spaces import exact_table

# N p - 1 = 2: the hump's width is ~sqrt(N), its entropy ~ log(sqrt(N)) + 1.4
HUGE = (10**30, "3e-30")


def test_entropy_of_tens_of_nats_is_accurate_to_dps_digits_after_the_point():
    N, p = HUGE
    for dps in (15, 16, 19, 21, 33):
        h = symhx.distribution_of(N, p, dps=dps).entropy()
        ref = symhx.distribution_of(N, p, dps=2 * dps + 10).entropy()
        assert 32 <= ref < 64  # two digits before the point
        with mpmath.workdps(2 * dps + 10):
            assert abs(h - ref) <= mpmath.mpf(10) ** -dps, dps


@pytest.mark.parametrize(("N", "p", "space"), [(100, Fraction(1, 10**5), "simple"),
                                               (30, Fraction(1, 10**4), "eq41"),
                                               (60, Fraction(1, 4000), "simple")])
def test_entropy_near_zero_keeps_dps_significant_digits(N, p, space):
    table = exact_table(N, p, space)
    for dps in (15, 20, 27, 34, 50):
        ref = table.entropy(2 * dps + 10)
        assert 0 < ref < 0.0625
        h = symhx.distribution_of(N, p, space=space, dps=dps).entropy()
        with mpmath.workdps(2 * dps + 10):
            assert abs(h - ref) <= abs(ref) * mpmath.mpf(10) ** -dps, (space, dps)
        # rounded once to dps significant digits: at most their bits
        assert h._mpf_[3] <= dps_to_prec(dps), (space, dps)
