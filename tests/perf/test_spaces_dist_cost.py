"""Cost of the higher-order distributions (``symhx.spaces._dist``): the float64 table of
``log U_e(k)`` is built once and grows by doubling, and one mode away from ties costs no exact
comparison."""

from __future__ import annotations

from fractions import Fraction

import mpmath
import numpy as np

import symhx.spaces._dist as dist
from symhx.spaces import parse_space
from tests.reference.spaces import log_U_exact


def test_log_U_table_is_computed_once_and_grows_by_doubling(monkeypatch):
    """The float64 table of ``log U_e(k)`` is built once per space: a call for the same or a
    smaller K returns a view of the cached table, and a call for a larger K rebuilds it at
    twice the old width or more, so growing K one step at a time costs O(K) table entries,
    not O(K**2). (A cache that never hit, or that grew to exactly K, gave the same numbers:
    no value test could see it.)"""
    monkeypatch.setattr(dist, "_LOGU", {})
    sp = parse_space("eq41")
    a = dist.log_U_table(sp, 40)
    assert np.shares_memory(dist.log_U_table(sp, 40), a)  # same K: a hit
    assert np.shares_memory(dist.log_U_table(sp, 25), a)  # a prefix
    b = dist.log_U_table(sp, 41)  # a miss: rebuilt at twice the old width
    assert not np.shares_memory(a, b)
    for K in (42, 60, 80):
        assert np.shares_memory(dist.log_U_table(sp, K), b), K
    for K in (40, 41, 81):
        got = dist.log_U_table(sp, K)
        ref = log_U_exact(sp, K)
        fin = np.isfinite(ref)
        assert (np.isfinite(got) == fin).all()
        assert np.allclose(got[fin], ref[fin], rtol=1e-13, atol=0)


def test_space_modes_seed_leaves_one_candidate(monkeypatch):
    """The float64 argmax of log W seeds the certified search; away from ties Arb then keeps
    exactly one candidate, so one mode costs no exact comparisons. (A seed of k = 1 made every
    k with W(k) >= W(1) a candidate, thousands of comparisons here; a seed one step off kept
    two.) The modes are checked against an argmax of log W over every k at 30 digits
    (``loggamma`` and the space's exact integers ``U_e(k)``)."""
    real = dist.space_candidates

    def spy(space, N, fr, top):
        out = real(space, N, fr, top)
        assert out == [top], f"candidates {out[:5]}... ({len(out)}) for the seed {top}"
        return out

    monkeypatch.setattr(dist, "space_candidates", spy)
    for space, N, fr in (("eq41", 3000, Fraction(1, 1000)), ("eq41", 3000, Fraction(1, 10**6)),
                         ("excess<=3", 2500, Fraction(3, 1000)),
                         ("eq41-printed", 2000, Fraction(1, 400))):
        sp = parse_space(space)
        with mpmath.workdps(30):
            p = mpmath.mpf(fr.numerator) / fr.denominator
            lw = [k * mpmath.log(p) + mpmath.loggamma(N + 1) - mpmath.loggamma(N - k + 1)
                  - mpmath.log(k)
                  + mpmath.log(sum(p**e * u for e, u in enumerate(sp.U(k))))
                  for k in range(1, N + 1)]
        want = max(range(N), key=lw.__getitem__) + 1
        assert dist.space_modes(sp, N, fr) == (want,), (space, N, fr)
