"""Modes of the simple distribution (eqs. 9-10): every maximiser of ``Phi_{N,p}(k)``, decided
exactly for every rational ``p`` (floats at their binary value, irrational ``p`` at a binary
approximation), exact ties included, any N.

References: ``Phi`` from factorials and its brute-force argmax
(:func:`tests.reference.distribution.brute_modes`); the term ratio
``Phi(m+1)/Phi(m) = p (N-m) m/(m+1)`` for huge N; the mpmath pmf from ``loggamma`` for
irrational ``p``.
"""

from __future__ import annotations

from fractions import Fraction
from typing import Any

import mpmath
from hypothesis import example, given
from hypothesis import strategies as st

import symhx
import symhx.distribution as dist
from symhx.distribution import simple_modes
from tests.reference.distribution import brute_modes, fraction_of, phi_exact, tie_cases

fractions_p = st.fractions(min_value=Fraction(1, 10**4), max_value=1).filter(lambda x: x > 0)


@given(st.integers(2, 80), fractions_p)
def test_modes_are_the_maximisers(N, p):
    assert symhx.modes(N, p) == brute_modes(N, p)
    assert symhx.mode(N, p) == brute_modes(N, p)[0]


@given(st.integers(2, 300), fractions_p, st.integers(1, 299))
def test_sign_of_difference_is_sign_of_f(N, p, k):
    """eq. (9)-(10): sign(Phi(k+1) - Phi(k)) = sign(f_{N,p}(k)), the identity the mode search
    rests on (checked on the factorial form)."""
    k = min(k, N - 1)
    if k < 1:
        return
    diff = phi_exact(N, p, k + 1) - phi_exact(N, p, k)
    f = -p * k * k + (N * p - 1) * k - 1
    assert (diff > 0) - (diff < 0) == (f > 0) - (f < 0)


@given(st.integers(2, 400), st.lists(fractions_p, min_size=2, max_size=6))
def test_mode_non_decreasing_in_p(N, ps):
    ps = sorted(ps)
    ms = [symhx.mode(N, p) for p in ps]
    assert ms == sorted(ms)


def test_documented_ties_give_the_smallest_maximiser():
    """N = 101, p = 1/50: Phi(50) = Phi(51) exactly (f(50) = 0); N = 5, p = 1/2:
    Phi(1) = Phi(2) = Phi(3). ``mode`` is the smallest maximiser on the exact and the float64
    path."""
    p = Fraction(1, 50)
    assert phi_exact(101, p, 50) == phi_exact(101, p, 51)
    assert symhx.modes(101, p) == (50, 51) and symhx.mode(101, p) == 50
    assert symhx.distribution_of(101, "1/50").mode() == 50
    assert symhx.distribution_of(101, "1/50").modes() == (50, 51)
    assert symhx.modes(5, Fraction(1, 2)) == (1, 2, 3)
    assert symhx.distribution_of(5, "1/2").mode() == 1
    assert symhx.distribution_of(5, "1/2", dps=None).mode() == 1


@given(tie_cases())
@example((101, Fraction(1, 50)))
@example((3, Fraction(1)))
def test_ties_every_path(case: tuple[int, Fraction]) -> None:
    """The frozen ``mode`` is the smallest tied maximiser on every path (exact, mpmath and
    float64 p); a float p is taken at its binary value (often no longer a tie)."""
    N, p = case
    modes = brute_modes(N, p)
    assert phi_exact(N, p, modes[0]) == max(phi_exact(N, p, k) for k in range(1, N + 1))
    for dps in (30, None):
        d = symhx.distribution_of(N, p, dps=dps)
        assert d.modes() == modes and d.mode() == modes[0]
    pf = float(p)
    fmodes = brute_modes(N, Fraction(pf))
    for dps in (30, None):
        d = symhx.distribution_of(N, pf, dps=dps)
        assert d.modes() == fmodes and d.mode() == fmodes[0]
    assert simple_modes(N, p, None) == modes
    with mpmath.workdps(40):
        pm = mpmath.mpf(p.numerator) / p.denominator
    assert symhx.mode(N, pm) == brute_modes(N, fraction_of(pm))[0]


def test_known_multi_ties() -> None:
    """Ties involving Phi(1), found by brute force over small N and p = a/b."""
    found = []
    for N in range(2, 13):
        for b in range(1, 13):
            for a in range(1, 3 * b + 1):
                p = Fraction(a, b)
                if p.denominator != b:
                    continue
                m = brute_modes(N, p)
                if len(m) > 1:
                    found.append((N, p, m))
                    assert symhx.modes(N, p) == m
                    d = symhx.distribution_of(N, p)
                    assert d.modes() == m and d.mode() == m[0]
    assert any(m[0] == 1 and len(m) == 3 for _, _, m in found)  # (5, 1/2): (1, 2, 3)
    assert any(m[0] == 1 and len(m) == 2 for _, _, m in found)
    assert any(m[0] > 1 for _, _, m in found)


@given(st.integers(2, 60), st.fractions(Fraction(1, 200), 3).filter(lambda x: x > 0))
@example(5, Fraction(1, 2))
@example(101, Fraction(1, 50))
@example(40, Fraction(3, 40))
@example(101, Fraction(1, 80))  # a hump (tie 16/17) below Phi(1): the mode is 1
@example(60, Fraction(1, 40))  # the hump wins
def test_modes_decided_by_the_exact_fallback_alone(N: int, p: Fraction) -> None:
    """The comparison of Phi(top) with Phi(1) falls back to exact integers when interval
    arithmetic cannot certify its sign (an exact tie): forcing that fallback everywhere must
    give the brute-force modes too."""
    calls = []

    def exact_only(fn: Any, *, start_bits: int, max_bits: int, exact_fn: Any = None) -> int:
        calls.append(start_bits)
        assert exact_fn is not None and start_bits >= 64 and max_bits >= start_bits
        return exact_fn()

    real = dist.certified_sign
    dist.certified_sign = exact_only
    try:
        got = simple_modes(N, p, None)
    finally:
        dist.certified_sign = real
    assert got == brute_modes(N, p)


def test_mode_huge_N_rational():
    """N = 10**100 either side of p_c: mode 1 below, k_after above."""
    N = 10**100
    cp = symhx.critical_point(N, dps=120)
    # p = (1 + q (1 -+ 1e-60)) / N with q = N p_c - 1 ~ 1.5e-49: just either side of p_c.
    # (Consecutive breakpoints of the mode are ~1/k**2 ~ 4e-103 apart in N p, so the margin
    # must be that fine for the mode just above p_c to still be k_after.)
    with mpmath.workdps(250):
        below = (1 + cp.q * (1 - mpmath.mpf(10) ** -60)) / N
        above = (1 + cp.q * (1 + mpmath.mpf(10) ** -60)) / N
    assert symhx.mode(N, below) == 1
    assert symhx.mode(N, above) == cp.k_after

