"""Cost: a quantile of the simple space at huge N is a Newton search on k (steps on
sqrt(1 - log C) in the tails, linear ones in the bulk, far k decided from bounds): a cold
ppf/isf/median at N = 10**20 ... 10**300 takes at most a dozen partial sums of the engine
(measured 2-10), where a bisection over the support would take ~log2 N of them (66-1000)."""

from __future__ import annotations

from fractions import Fraction

import pytest

import symhx
from symhx import distribution as dist
from symhx.simple_sums import SimpleSums
from tests.reference.distribution_large_n import critical_p

QS = {"ppf 1e-30": ("ppf", Fraction(1, 10**30)), "median": ("ppf", Fraction(1, 2)),
      "isf 1e-30": ("isf", Fraction(1, 10**30)), "ppf 1-1e-6": ("ppf", 1 - Fraction(1, 10**6))}


@pytest.mark.parametrize(("e", "ratio"), [(100, Fraction(2)), (100, Fraction(1001, 1000)),
                                          (300, Fraction(10)), (20, Fraction(1, 2))])
@pytest.mark.parametrize("which", sorted(QS))
def test_a_cold_quantile_takes_a_dozen_partial_sums(e, ratio, which, monkeypatch) -> None:
    N = 10**e
    calls = [0]
    orig = SimpleSums.sums

    def counted(self, A, B, kinds=(0,)):
        calls[0] += 1
        return orig(self, A, B, kinds)

    dist._shared_moments.cache_clear()
    dist._shared_entropy.cache_clear()
    dist._ENGINES.__dict__.clear()
    monkeypatch.setattr(SimpleSums, "sums", counted)
    d = symhx.distribution_of(N, critical_p(N) * ratio, dps=30)
    method, q = QS[which]
    k = getattr(d, method)(q)
    assert 1 <= k <= N
    assert calls[0] <= 12
