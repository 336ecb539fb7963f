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


def test_a_cold_cdf_costs_its_tail_and_the_complement(monkeypatch) -> None:
    """Before any full pass a cdf sums [1, k] and [k + 1, N] (together about one pass), keeps
    their sum as the normaliser; a second cdf or sf near an earlier one then sums only the
    stretch between (an earlier sum shares its end); the values agree with those after a full
    pass to the dps digits."""
    N, p = 10**40, mpmath.mpf(3) * 10**-39
    _forget()
    calls = _count_sums(monkeypatch)
    d = symhx.distribution_of(N, p, dps=30)
    k = d.mode()
    c1 = d.cdf(k)
    assert calls == [(1, k), (k + 1, N)]
    c2 = d.cdf(k + 10**19)
    assert calls[2:] == [(k + 1, k + 10**19)]
    s1 = d.sf(k - 10**19)
    assert calls[3:] == [(k - 10**19 + 1, k)]
    d.cdf(3 * k // 4)  # far from every earlier end: summed whole
    assert calls[4:] == [(1, 3 * k // 4)]
    _forget()
    warm = symhx.distribution_of(N, p, dps=30)
    warm.mean()
    with mpmath.workdps(40):
        for got, want in ((c1, warm.cdf(k)), (c2, warm.cdf(k + 10**19)),
                          (s1, warm.sf(k - 10**19))):
            assert abs(got - want) <= abs(want) * mpmath.mpf(10) ** -29


def _count_kinds(monkeypatch) -> list[tuple[int, int, tuple[int, ...]]]:
    calls: list[tuple[int, int, tuple[int, ...]]] = []
    orig = SimpleSums.sums

    def counted(self, A, B, kinds=(0,)):
        calls.append((A, B, tuple(kinds)))
        return orig(self, A, B, kinds)

    monkeypatch.setattr(SimpleSums, "sums", counted)
    return calls


def test_a_cold_entropy_is_one_pass_and_a_cold_pmf_needs_no_moments(monkeypatch) -> None:
    """The entropy sums its weight log(Phi/Phi(c)) and the normaliser in one pass; a pmf or a
    cdf far in a tail needs the normaliser alone (weight 1), not the mean and the variance."""
    N, p = 10**40, mpmath.mpf(3) * 10**-39
    _forget()
    calls = _count_kinds(monkeypatch)
    symhx.entropy(N, p, dps=30)
    assert calls == [(1, N, (0, 3))]
    _forget()
    calls.clear()
    d = symhx.distribution_of(N, p, dps=30)
    d.pmf(d.mode())
    assert calls == [(1, N, (0,))]
    d.cdf(10**10)  # far in the left tail (more working digits): a partial sum, normalised
    assert calls[1:] == [(1, 10**10, (0,))]


def test_a_hump_cut_at_its_levels_needs_no_taylor_series_at_its_ends(monkeypatch) -> None:
    """The Euler-Maclaurin terms at a hump's ends (cut at e**-171 of its top at N = 10**6)
    are bounded by Cauchy's estimate and dropped: the moments' pass computes one Taylor series,
    of order 2, for the hump's width."""
    N = 10**6
    _forget()
    orders: list[int] = []
    orig = SimpleSums.taylor

    def counted(self, x0, order, d0=None):
        orders.append(order)
        return orig(self, x0, order, d0)

    monkeypatch.setattr(SimpleSums, "taylor", counted)
    symhx.mean(N, mpmath.mpf(4) / N, dps=50)
    assert orders == [2]


def test_a_cold_normaliser_is_a_pass_of_weight_one(monkeypatch) -> None:
    """log Gamma = log Phi(c) + log S0 needs S0 alone; the value equals the moments' one."""
    N, p = 10**40, mpmath.mpf(3) * 10**-39
    _forget()
    calls = _count_kinds(monkeypatch)
    lg = symhx.distribution_of(N, p, dps=30).log_normaliser
    assert calls == [(1, N, (0,))]
    _forget()
    d = symhx.distribution_of(N, p, dps=30)
    d.mean()
    assert d.log_normaliser == lg
