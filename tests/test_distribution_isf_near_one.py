"""Quantiles at a level within the resolution of the cdf of 1 or 0 (mpmath path of
:class:`symhx.distribution.SimpleDistribution`).

On the mpmath path ``isf(q)`` resolves ``q`` to the ``dps`` digits of the sf: it is the smallest
``k`` in ``1..N`` with ``sf(k) <= q (1 + 10**(1 - dps))`` (``ppf``: ``cdf(k) >= q (1 -
10**(1 - dps))``).  For ``q`` within ``10**(1 - dps)`` of 1 the level that the lower side must
reach, ``1 - q (1 + 10**(1 - dps))``, is zero or negative: every ``k`` meets it, and the answer
is 1 however small ``P(X = 1)`` is.

Reference: that rule applied to the exact table of ``Phi`` (Fractions from the factorials) at
the exact binary value of the float ``p``.
"""

from __future__ import annotations

from fractions import Fraction

import pytest

import symhx
from tests.reference.distribution import ExactTable

DPS = 15
RES = Fraction(10) ** (1 - DPS)
# below, at and above the jump (N p = 0.5, 5, 25)
CASES = [(40, 0.0125), (100, 0.05), (50, 0.5)]
# 1 - q far below 10**(1 - dps); exactly at it (the level is 0); just above it (a positive level)
NEAR_ONE = [1 - Fraction(1, 10**20), 1 - Fraction(1, 10**40), 1 / (1 + RES), 1 - 10 * RES]


def resolved_isf(table: ExactTable, q: Fraction) -> int:
    return next(k for k in range(1, table.N + 1) if table.sf(k) <= q * (1 + RES))


def resolved_ppf(table: ExactTable, q: Fraction) -> int:
    return next(k for k in range(1, table.N + 1) if table.cdf(k) >= q * (1 - RES))


@pytest.mark.parametrize(("N", "p"), CASES)
def test_isf_of_a_level_within_the_resolution_of_one(N, p):
    table = ExactTable.simple(N, Fraction(p))
    for q in NEAR_ONE:
        ref = resolved_isf(table, q)
        assert ref == 1 or q == NEAR_ONE[-1]
        for fresh in (True, False):  # before and after the distribution's first full pass
            d = symhx.distribution_of(N, p, dps=DPS)
            if not fresh:
                d.mean()
            assert d.isf(q) == ref, (N, p, q, fresh)


@pytest.mark.parametrize(("N", "p"), CASES)
def test_ppf_of_a_level_within_the_resolution_of_zero(N, p):
    # the mirror image: the upper side's level 1 - q (1 - 10**(1 - dps)) stays positive
    table = ExactTable.simple(N, Fraction(p))
    for q in (Fraction(1, 10**20), Fraction(1, 10**40), 1 - 1 / (1 + RES)):
        ref = resolved_ppf(table, q)
        assert symhx.distribution_of(N, p, dps=DPS).ppf(q) == ref, (N, p, q)
