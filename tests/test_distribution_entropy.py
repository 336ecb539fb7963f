"""The entropy ``-sum_k P(X=k) log P(X=k)`` of :class:`symhx.distribution.Distribution`: on the
mpmath path absolutely accurate to ``10**-dps`` and rounded once to ``dps`` digits after the
point (no spurious digits beyond them), for the simple space and the higher-order spaces (whose
entropy is the base class's sum over the terms).

Reference: the exact table of the weights (Burnside counts for a space, the definition of
``Phi`` for the simple space), ``-sum P log P`` at twice the digits.
"""

from __future__ import annotations

from fractions import Fraction

import mpmath
import pytest
from mpmath.libmp import dps_to_prec

import symhx
from tests.reference.distribution import ExactTable
from tests.reference.spaces import exact_table

CASES = [(12, "eq41"), (12, "simple"), (9, "excess<=2")]
DPS = (17, 23, 30, 41, 50)


@pytest.mark.parametrize(("N", "space"), CASES)
def test_entropy_is_accurate_and_rounded_to_dps_digits_after_the_point(N, space):
    p = Fraction(1, 2)
    ref_table = ExactTable.simple(N, p) if space == "simple" else exact_table(N, p, space)
    for dps in DPS:
        ref = ref_table.entropy(2 * dps + 10)
        assert 1 <= ref < 8  # one digit before the point
        h = symhx.distribution_of(N, 0.5, space=space, dps=dps).entropy()
        assert isinstance(h, mpmath.mpf)
        with mpmath.workdps(2 * dps + 10):
            assert abs(h - ref) <= mpmath.mpf(10) ** -dps, (space, dps)
        # rounded to dps digits after the point: at most the bits of dps + 1 significant digits
        assert h._mpf_[3] <= dps_to_prec(dps + 1), (space, dps)


def test_entropy_of_a_space_counts_every_term():
    # k = 1 carries a visible share of the mass at small p: leaving any term out shows
    N, p = 6, Fraction(1, 20)
    ref_table = exact_table(N, p, "eq41")
    assert ref_table.pmf_at(1) > Fraction(1, 10)
    h = symhx.distribution_of(N, 0.05, space="eq41", dps=30).entropy()
    # p = 0.05 as a float is not 1/20: compare with the exact table at its binary value
    ref_bin = exact_table(N, Fraction(0.05), "eq41").entropy(60)
    with mpmath.workdps(60):
        assert abs(h - ref_bin) <= mpmath.mpf(10) ** -30
        assert h > 0


def test_entropy_of_a_one_point_distribution_is_zero():
    for space in ("simple", "eq41"):
        assert symhx.distribution_of(1, 0.5, space=space, dps=30).entropy() == 0
