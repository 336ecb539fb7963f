"""symhx.spaces._dist: the float64 table cache and the class decomposition's guard digits.

Tests written for surviving mutants of the mutation run (issue 16). References: ``math.log`` of
the exact integers ``U_e(k)``, Burnside's count :func:`symhx.circuits.circuit_count` of each
class, and the mpmath distribution at 25 more digits (another algorithm than the class split).
"""

from __future__ import annotations

import math
from fractions import Fraction

import mpmath
import numpy as np

import symhx.spaces._dist as dist
from symhx.circuits import circuit_count
from symhx.spaces import EQ41_SHAPES, class_decomposition, distribution, parse_space
from symhx.spaces._classes import visits_of
from symhx.validation import mpf_to_fraction
from tests.reference.distribution import phi_exact


def _exact_log_u(sp, K: int) -> np.ndarray:
    out = np.full((sp.max_excess + 1, K), -np.inf)
    for k in range(1, K + 1):
        for e, u in enumerate(sp.U(k)):
            if u:
                out[e, k - 1] = math.log(u)
    return out


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
        ref = _exact_log_u(sp, K)
        fin = np.isfinite(ref)
        assert (np.isfinite(got) == fin).all()
        assert np.allclose(got[fin], ref[fin], rtol=1e-13, atol=0)


def test_class_decomposition_keeps_its_digits_at_large_k():
    """``class_decomposition`` at N = 20000 (the largest N it accepts) and dps = 15: the
    recurrence for Phi(k) runs 20000 steps, so it needs the guard digits 10 + 2 digits(N)
    (with none, P(X = k, class) at k = 3000 was wrong in the 12th digit). Checked at
    k = 1, 2, 1000, 3000 against the mpmath pmf at 40 digits (the distribution's own term
    recurrence, at 60 working digits) split by Burnside's count of each class."""
    N, p, dps = 20000, 0.001, 15
    cd = class_decomposition(N, p, space="eq41", dps=dps)
    d = distribution(N, p, space="eq41", dps=40)
    fr = Fraction(p)
    for k in (1, 2, 1000, 3000):
        counts = {s: circuit_count(N, visits_of(s, k)) * fr ** sum(x - 1 for x in s)
                  for s in EQ41_SHAPES if k >= len(s)}
        tot = sum(counts.values())
        pk = mpf_to_fraction(d.pmf(k))
        for s, c in counts.items():
            ref = pk * c / tot
            with mpmath.workdps(60):
                refm = mpmath.mpf(ref.numerator) / ref.denominator
                err = abs(cd.joint[s][k - 1] / refm - 1)
            assert err <= mpmath.mpf(10) ** (1 - dps), (k, s, err)


def _exact_sign(sp, N: int, fr: Fraction, j: int, k: int) -> int:
    """Sign of W(k) - W(j) from exact Fractions: W(k) = p**k N!/(k (N-k)!) Q*(k)."""
    def w(i: int) -> Fraction:
        return phi_exact(N, fr, i) * sp.Qstar(i, fr)
    wk, wj = w(k), w(j)
    return (wk > wj) - (wk < wj)


def test_compare_weights_falls_back_to_exact_integers(monkeypatch):
    """Where Arb balls cannot separate W(k) from W(j) up to 16 x the start precision (simulated
    by widening every input ball to +-50 %), the exact integer comparison decides: with the
    fall-back or the precision cap removed, this raised instead of answering. k - j > 64 and
    N >= 2000, so the ball route is the one taken."""
    flint = __import__("flint")
    real = dist.to_arb

    def wide(x):
        b = real(x)
        return flint.arb(b.mid(), abs(b.mid()) / 2)

    monkeypatch.setattr(dist, "to_arb", wide)
    N, fr = 2500, Fraction(1, 700)
    for space in ("eq41", "excess<=2"):
        sp = parse_space(space)
        for j, k in ((1, 100), (300, 400), (50, 2400), (2000, 2100)):
            want = _exact_sign(sp, N, fr, j, k)
            assert want != 0
            assert dist.compare_weights(sp, N, fr, j, k) == want, (space, j, k)
            assert dist.compare_weights(sp, N, fr, k, j) == -want, (space, j, k)


def test_space_modes_seed_leaves_one_candidate(monkeypatch):
    """The float64 argmax of log W seeds the certified search; away from ties Arb then keeps
    exactly one candidate, so one mode costs no exact comparisons. (A seed of k = 1 made every
    k with W(k) >= W(1) a candidate, thousands of comparisons here; a seed one step off kept
    two.) The modes are checked against an argmax of log W over every k at 30 digits."""
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


def test_screened_logpmf_of_a_sympy_irrational(monkeypatch):
    """log P(X = k) for a k below the float screen (not among the stored terms) and a sympy
    irrational p: the fall-back evaluates W(k) from p itself (there is no exact rational).
    Against exact Fractions at a 200-digit rational stand-in for p."""
    sympy = __import__("sympy")
    monkeypatch.setattr(dist, "DIRECT_LIMIT", 10)  # the screened path at a small N
    N, dps = 60, 20
    d = distribution(N, sympy.sqrt(2) / 400, space="eq41", dps=dps)
    assert N not in d._terms
    sp = parse_space("eq41")
    with mpmath.workdps(200):
        pr = mpf_to_fraction(mpmath.sqrt(2) / 400)
    W = [phi_exact(N, pr, k) * sp.Qstar(k, pr) for k in range(1, N + 1)]
    tot = sum(W)
    with mpmath.workdps(60):
        ref = mpmath.log(mpmath.mpf(W[-1].numerator) / W[-1].denominator) - mpmath.log(
            mpmath.mpf(tot.numerator) / tot.denominator)
        assert abs(d.logpmf(N) - ref) <= mpmath.mpf(10) ** (1 - dps) * abs(ref)
