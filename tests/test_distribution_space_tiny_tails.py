"""Quantiles of a higher-order space (the base :class:`symhx.distribution.Distribution` search on
the mpmath path) whose search passes through tails far below the smallest number a user may
pass in: ``sf(N/2)`` of ``N = 200`` at ``p = 1e-20000`` is ~``10**-2000000``, beyond the
``2**+-3400000`` exact-conversion range of user inputs
(:data:`symhx.validation.MAX_BINARY_EXPONENT`).  Such internal values are compared exactly, never
refused.

Reference: Burnside counts of the circuits of each ``X = k`` (``W(k) = sum_d c_d p**d``, every
degree ``d >= k``), which bound ``sf(1) <= sum_{k>=2} W(k) / W(1)`` in exact Fractions.
"""

from __future__ import annotations

from fractions import Fraction

import mpmath

import symhx
from symhx.validation import MAX_BINARY_EXPONENT
from tests.reference.distribution import fraction_of
from tests.reference.spaces import weight_polys

N, SPACE = 200, "eq41"


def test_isf_searches_through_tails_beyond_the_input_range():
    pm = mpmath.mpf("1e-20000")
    p = fraction_of(pm)
    polys = weight_polys(N, SPACE)
    assert min(polys[1]) == 1 and all(min(poly) >= k for k, poly in polys.items())
    # p <= 1: W(k) <= (its circuits) p**k <= (its circuits) p**2 for k >= 2, W(1) >= c_1 p
    upper = sum(sum(poly.values()) for k, poly in polys.items() if k >= 2) * p**2
    sf1_bound = upper / (polys[1][1] * p)
    d = symhx.distribution_of(N, pm, space=SPACE, dps=15)
    for q in (Fraction(1, 2), Fraction(1, 10**100)):
        assert sf1_bound <= q  # so sf(1) <= q: isf(q) = 1
        assert d.isf(q) == 1
    # the search did pass through a tail beyond the input range (~10**-2000000)
    tail = d.sf(N // 2)
    assert 0 < tail and -mpmath.mag(tail) > MAX_BINARY_EXPONENT
