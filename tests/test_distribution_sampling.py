"""Sampling from the simple distribution: ``rvs`` by inverse transform on the float64 cdf, on
every path, reproducible from its seed, reaching both ends of the support, with a goodness-of-fit
test that has the power to see a wrong pmf.

Reference: the exact pmf of ``Phi(k)`` from factorials, a float p at its binary value.
"""

from __future__ import annotations

from fractions import Fraction
from typing import Any

import numpy as np

import symhx
from tests.harness.discrete import check_refusals, check_rvs, chi_square_pvalue
from tests.reference.distribution import ExactTable


def test_rvs_against_exact_pmf() -> None:
    N, pf = 12, 0.25
    ref = ExactTable.simple(N, Fraction(pf))
    for dps in (20, None):
        d = symhx.distribution_of(N, pf, dps=dps)
        check_rvs(d, ref, size=30_000, seed=9)
        assert d.rvs(30_000, random_state=9).min() == 1
    d = symhx.distribution_of(N, pf, dps=None)
    assert np.array_equal(d.rvs((3, 4), random_state=5),
                          d.rvs((3, 4), random_state=np.random.default_rng(5)))
    # the largest value is reachable: u just below 1 maps to N
    top = symhx.distribution_of(2, 100.0, dps=None)  # P(X = 2) ~ 1
    assert top.rvs(50, random_state=1).tolist() == [2] * 50
    one = symhx.distribution_of(1, 0.5, dps=None)
    assert one.rvs(5, random_state=2).tolist() == [1] * 5


def test_rvs_detects_a_wrong_distribution() -> None:
    """The chi-square check has power: draws from N = 30, p = 0.05 fail against p = 0.055 (so
    a sampler off by a shifted cdf would be caught)."""
    d = symhx.distribution_of(30, 0.05, dps=None)
    a = d.rvs(40_000, random_state=123)
    wrong = ExactTable.simple(30, Fraction(11, 200)).pmf
    assert chi_square_pvalue(a, [float(x) for x in wrong]) < 1e-6


class _FixedUniforms(np.random.Generator):
    """A Generator whose ``random()`` returns chosen values (to hit cdf values exactly)."""

    def __init__(self, values: list[float]) -> None:
        super().__init__(np.random.PCG64(0))
        self.values = np.array(values, dtype=float)

    def random(self, size: Any = None, dtype: Any = None, out: Any = None) -> Any:
        return self.values[0] if size is None else np.resize(self.values, size)


def test_rvs_inverse_transform_at_exact_cdf_values() -> None:
    """X = smallest k with u < cdf(k): u equal to cdf(k) gives k + 1; u just below 1 gives N
    even where the float cdf ends below 1 (N = 2, p = 0.05 ends at 1 - 2**-52)."""
    d = symhx.distribution_of(4, "1/3", dps=None)
    exact_hits = [float(d.cdf(k)) for k in range(1, 4)]
    assert d.rvs(3, random_state=_FixedUniforms(exact_hits)).tolist() == [2, 3, 4]
    u1 = float(np.nextafter(1.0, 0.0))
    for N, pf in ((2, 0.05), (3, 0.5), (7, 2.0)):
        e = symhx.distribution_of(N, pf, dps=None)
        assert e.rvs(random_state=_FixedUniforms([u1])) == N
        assert e.rvs(2, random_state=_FixedUniforms([u1])).tolist() == [N, N]
        assert e.rvs(random_state=_FixedUniforms([0.0])) == 1


def test_rvs_argument_errors_name_the_argument() -> None:
    d = symhx.distribution_of(5, 0.3, dps=None)
    check_refusals(d)
    assert d.rvs((0, 3), random_state=1).shape == (0, 3)
