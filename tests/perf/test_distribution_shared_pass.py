"""Cost: frozen simple distributions of the same (N, p, dps) share the one full pass of the
summation engine (normaliser, mean, variance); the entropy is a pass of its own, once; a cdf
then costs one partial sum."""

from __future__ import annotations

import mpmath

import symhx
from symhx import distribution as dist
from symhx.simple_sums import SimpleSums


def _count_sums(monkeypatch) -> list[tuple[int, int]]:
    calls: list[tuple[int, int]] = []
    orig = SimpleSums.sums

    def counted(self, A, B, kinds=(0,)):
        calls.append((A, B))
        return orig(self, A, B, kinds)

    monkeypatch.setattr(SimpleSums, "sums", counted)
    return calls


def test_statistics_of_one_N_p_dps_share_the_full_pass(monkeypatch) -> None:
    N, p = 10**40, mpmath.mpf(3) * 10**-39
    _forget()
    calls = _count_sums(monkeypatch)
    m = symhx.mean(N, p, dps=30)
    assert calls == [(1, N)]
    v = symhx.var(N, p, dps=30)
    assert calls == [(1, N)]  # no second pass
    h = symhx.entropy(N, p, dps=30)
    assert calls == [(1, N), (1, N)]  # the entropy's own pass
    symhx.entropy(N, p, dps=30)
    symhx.cdf(N, p, N // 2, dps=30)
    assert calls == [(1, N), (1, N), (1, N // 2)]  # once; then one partial sum
    # the shared values are the ones a cold pass gives
    _forget()
    d = symhx.distribution_of(N, p, dps=30)
    assert (d.mean(), d.var(), d.entropy()) == (m, v, h)
    # another dps is another pass
    symhx.mean(N, p, dps=31)
    assert calls.count((1, N)) == 5


def _forget() -> None:
    dist._shared_moments.cache_clear()
    dist._shared_entropy.cache_clear()
    dist._ENGINES.__dict__.clear()
