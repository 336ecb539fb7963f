"""Quantiles of the frozen-distribution base class (:class:`symhx.distribution.Distribution`):
on the mpmath path ``q`` is resolved to the ``dps`` digits of the cdf (a ``q`` within a relative
``10**(1 - dps)`` of ``cdf(k)`` gives ``k``, one a little further gives ``k + 1``), the
higher-order spaces' quantiles on that path, the exact-work refusal of their exact quantiles,
and the inclusive ``EXACT_QUANTILE_WORK_LIMIT`` of the simple space.

References: the exact table of the space's weights from Burnside counts
(:func:`tests.reference.spaces.exact_table`), the simple weights by their definition.
"""

from __future__ import annotations

from fractions import Fraction

import pytest

import symhx
from symhx.distribution import EXACT_QUANTILE_WORK_LIMIT
from tests.harness.errors import assert_refuses
from tests.reference.distribution import phi_exact
from tests.reference.spaces import exact_table

N, P, SPACE, DPS = 12, Fraction(1, 2), "eq41", 30


@pytest.fixture(scope="module")
def ref():
    return exact_table(N, P, SPACE)


@pytest.fixture(scope="module")
def dist():
    # p = 0.5 is exactly 1/2 as a float: the mpmath path at dps digits, same distribution
    return symhx.distribution_of(N, 0.5, space=SPACE, dps=DPS)


def test_space_quantiles_on_the_mpmath_path_match_the_exact_table(ref, dist):
    for q in (Fraction(1, 1000), Fraction(1, 10), Fraction(1, 2), Fraction(9, 10)):
        assert dist.ppf(q) == ref.ppf(q)
        assert dist.isf(q) == ref.isf(q)
    assert dist.median() == ref.ppf(Fraction(1, 2))
    assert dist.interval(Fraction(1, 2)) == (ref.ppf(Fraction(1, 4)), ref.ppf(Fraction(3, 4)))


def test_ppf_resolves_q_to_the_digits_of_the_cdf(ref, dist):
    # cdf(11) ~ 0.79 (a leading digit >= 5: rounding it to DPS digits moves it by at most a
    # relative 1e-30); a q 3e-30 above it is within the cdf's digits -> 11, 2e-29 above is not
    k = 11
    c = ref.cdf(k)
    assert Fraction(1, 2) <= c < 1 and ref.pmf_at(k + 1) > Fraction(1, 10)
    eps = Fraction(1, 10**DPS)
    assert dist.ppf(c) == k
    assert dist.ppf(c * (1 + 3 * eps)) == k
    assert dist.ppf(c * (1 + 20 * eps)) == k + 1
    assert dist.ppf(c * (1 - 20 * eps)) == k


def test_isf_resolves_q_to_the_digits_of_the_sf(ref, dist):
    # sf(10) ~ 0.55; a q 3e-30 below it is within the sf's digits -> 10, 2e-29 below is not
    k = 10
    s = ref.sf(k)
    assert Fraction(1, 2) <= s < 1 and ref.sf(k - 1) > s * Fraction(101, 100)
    eps = Fraction(1, 10**DPS)
    assert dist.isf(s) == k
    assert dist.isf(s * (1 - 3 * eps)) == k
    assert dist.isf(s * (1 - 20 * eps)) == k + 1
    assert dist.isf(s * (1 + 20 * eps)) == k


def test_exact_space_quantile_beyond_its_work_limit_is_refused_before_work():
    # N (bits of N + (m + 1) bits of p) = 20000 (15 + 2 * 4) > EXACT_QUANTILE_WORK_LIMIT
    d = symhx.distribution_of(20000, "1/3", space="excess<=1", dps=30)
    for fn in (d.ppf, d.isf):
        msg = assert_refuses(fn, Fraction(1, 2), arg="p",
                             allowed=(str(EXACT_QUANTILE_WORK_LIMIT),
                                      "symhx.distribution.EXACT_QUANTILE_WORK_LIMIT"))
        assert msg.startswith("a quantile in exact rational arithmetic")


def test_exact_quantiles_at_the_work_limit_itself_are_decided_on_the_exact_cdf():
    # N (bits of N + bits of num + bits of den) = 5000 (13 + 1 + 26) = EXACT_QUANTILE_WORK_LIMIT
    n, p = 5000, Fraction(1, 2**25)
    assert n * (n.bit_length() + 1 + p.denominator.bit_length()) == EXACT_QUANTILE_WORK_LIMIT
    # cdf(1) = Phi(1) / Gamma; the terms fall by a factor <= N p < 2e-4 per k, so 40 of them
    # bound Gamma from below to ~1e-140 relative: q is above cdf(1) by ~1e-80, far inside the
    # 30 digits an mpmath cdf would resolve (which would answer 1)
    gamma_lo = sum((phi_exact(n, p, k) for k in range(1, 41)), Fraction(0))
    q = phi_exact(n, p, 1) / gamma_lo + Fraction(1, 10**80)
    d = symhx.distribution_of(n, p, dps=30)
    assert d.exact
    assert d.ppf(q) == 2
    # and a q at or below cdf(1) (Gamma bounded from above the same way) gives 1
    assert d.ppf(phi_exact(n, p, 1) / (gamma_lo * (1 + Fraction(1, 10**140)))) == 1
