"""Quantiles of the simple distribution: ``ppf`` / ``isf`` decided on the exact cdf for exact
``p`` (no tolerance), resolved to the ``dps`` digits of the cdf on the mpmath path (exactly the
documented ``10**(1 - dps)``), in the support on the float64 path; ``q`` and ``confidence`` are
checked like probabilities.

Reference: the exact table of ``Phi(k)`` from factorials
(:class:`tests.reference.distribution.ExactTable`), a float p at its binary value.
"""

from __future__ import annotations

from fractions import Fraction

import numpy as np
import pytest

import symhx
from symhx.distribution import SimpleDistribution
from tests.harness.discrete import check_quantiles_at_exact_ties
from tests.harness.errors import assert_refuses
from tests.reference.distribution import ExactTable, fraction_of

#: the cost tests of the quantile search and of the shared passes also pin behaviour of
#: symhx/distribution.py: its mutation runs take them too (scripts/mutation.py)
MUTATION_ALSO = ("tests/perf/test_distribution_quantile_cost.py",
                 "tests/perf/test_distribution_shared_pass.py")


def test_mpmath_quantiles_resolve_q_to_dps_digits() -> None:
    """A q within a relative 10**(1 - dps) of cdf(k) counts as equal to it (documented), and
    one a little further does not."""
    N, pf, dps = 12, 0.3, 20
    t = ExactTable.simple(N, Fraction(pf))
    d = symhx.distribution_of(N, pf, dps=dps)
    for k in (2, 5, 8):
        c, s = t.cdf(k), t.sf(k)
        assert d.ppf(c * (1 + Fraction(1, 10**25))) == k
        assert d.ppf(c * (1 + Fraction(1, 10**15))) == k + 1
        assert d.isf(s * (1 - Fraction(1, 10**25))) == k
        assert d.isf(s * (1 - Fraction(1, 10**15))) == k + 1
        assert d.ppf(c * (1 - Fraction(1, 10**15))) == k
        assert d.isf(s * (1 + Fraction(1, 10**15))) == k


@pytest.mark.parametrize("N, pf, dps", [(300, 0.02, 30), (120, 0.3, 20), (200, 0.011, 17)])
def test_mpmath_quantile_at_an_exact_tie_is_k(N: int, pf: float, dps: int) -> None:
    """q built so that the resolved target q (1 -+ 10**(1 - dps)) equals cdf(k) / sf(k)
    exactly: k reaches it (``cdf(k) >= target``), whatever the rounding of the sums at any
    number of digits.  (The search used to settle such a tie by the sign of the rounding
    error and gave k + 1 at N = 300.)"""
    d = symhx.distribution_of(N, pf, dps=dps)
    m = d.median()
    check_quantiles_at_exact_ties(d, ExactTable.simple(N, Fraction(pf)), dps, (m - 3, m, m + 2))


@pytest.mark.parametrize("space, N, pf, dps", [("excess<=1", 40, 0.05, 20),
                                                ("eq41", 60, 0.03, 30)])
def test_space_quantile_at_an_exact_tie_is_k(space: str, N: int, pf: float, dps: int) -> None:
    """The same for a sample space's distribution (the search over its dps-digit cdf): a
    resolved target equal to cdf(k) / sf(k) gives k (the rounding of the cdf's last digit used
    to give k + 1 for about half the k), and one resolution step beyond it gives k + 1.
    Reference: the distribution at the exact binary value of p (exact cdf)."""
    exact = symhx.distribution_of(N, Fraction(pf), space=space)
    d = symhx.distribution_of(N, pf, dps=dps, space=space)
    m = d.median()
    check_quantiles_at_exact_ties(d, exact, dps, range(m - 4, m + 5))


@pytest.mark.parametrize("dps", [20, 30])
def test_mpmath_quantile_resolution_is_exactly_ten_to_one_minus_dps(dps: int) -> None:
    """The documented resolution: ppf gives k when q <= cdf(k) (1 + 10**(1 - dps)) and isf
    gives k when q >= sf(k) (1 - 10**(1 - dps)), against the returned (rounded) cdf / sf
    values; half the resolution inside counts as equal, twice outside does not."""
    N, pf = 12, 0.3
    d = symhx.distribution_of(N, pf, dps=dps)
    eps = Fraction(10) ** (1 - dps)
    for k in (3, 6, 9):
        c, s = fraction_of(d.cdf(k)), fraction_of(d.sf(k))
        assert d.ppf(c * (1 + eps / 2)) == k and d.ppf(c * (1 + 2 * eps)) == k + 1
        assert d.isf(s * (1 - eps / 2)) == k and d.isf(s * (1 - 2 * eps)) == k + 1


def test_exact_quantiles_have_no_tolerance() -> None:
    """Exact p: q a relative 10**-40 away from cdf(k) / sf(k) moves the quantile."""
    d = symhx.distribution_of(12, "0.3", dps=30)
    t = ExactTable.simple(12, Fraction(3, 10))
    tiny = Fraction(1, 10**40)
    for k in (3, 6, 9):
        assert d.ppf(t.cdf(k) * (1 + tiny)) == k + 1
        assert d.ppf(t.cdf(k)) == k
        assert d.isf(t.sf(k) * (1 - tiny)) == k + 1
        assert d.isf(t.sf(k)) == k


def test_float_ppf_near_one_stays_in_the_support() -> None:
    """N = 2, p = 0.05: the float cdf ends at 1 - 2**-52; q = 1 - 2**-53 lies above it and
    must still give N (not N + 1)."""
    q = float(np.nextafter(1.0, 0.0))
    for N, pf in ((2, 0.05), (3, 0.5), (20, 0.3)):
        d = symhx.distribution_of(N, pf, dps=None)
        assert d.ppf(q) == N and d.ppf([q]).tolist() == [N]


def test_q_is_checked_like_a_probability() -> None:
    d = symhx.distribution_of(6, 0.4, dps=20)
    for bad in (1.5, "2", Fraction(101, 100)):
        assert_refuses(d.ppf, bad, arg="q", value=repr(bad), allowed="<= 1")
    assert_refuses(d.isf, -0.25, arg="q", value="-0.25", allowed=">= 0")
    assert_refuses(d.ppf, [0.5, True], exc=TypeError, arg="q", value="bool True",
                   allowed="a real number")
    assert_refuses(d.isf, [0.5, 1.5], arg="q", value="1.5", allowed="<= 1")
    assert_refuses(d.interval, 1.5, arg="confidence", value="1.5", allowed="<= 1")


@pytest.mark.parametrize("c", [-0.5, "-1/3", Fraction(-1, 10**9)])
def test_interval_refuses_a_negative_confidence(c: object) -> None:
    """A negative confidence would give reversed ppf bounds: refused like c > 1."""
    d = SimpleDistribution(20, "1/10")
    assert_refuses(d.interval, c, arg="confidence", value=repr(c), allowed=">= 0")
