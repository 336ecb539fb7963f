"""Modes over a higher-order space (``space_modes``, ``modes``) and the certified comparison of
two weights (``compare_weights``): every maximiser of ``W(k)``, decided exactly for every
rational ``p`` (floats at their binary value), exact ties included, whatever the float64 seed.

References: the weight polynomials from explicit walks and from Burnside's counts
(:mod:`tests.reference.spaces`), exact ``Fraction`` argmax scans, the rational-root theorem for
tie points, and roots of ``W(k) = W(j)`` by bisection in mpmath.
"""

from __future__ import annotations

import math
from fractions import Fraction

import mpmath
import numpy as np
import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

import symhx.spaces._dist as dist
from symhx.certify import space_candidates
from symhx.distribution import SimpleDistribution, simple_modes
from symhx.spaces import (
    SpaceDistribution,
    critical_point,
    distribution,
    modes,
    parse_space,
    space_modes,
)
from symhx.validation import mpf_to_fraction
from tests.harness.errors import assert_refuses
from tests.reference.spaces import (
    argmax,
    root,
    tie_points,
    walk_polys,
    weight_polys,
    weight_sign,
    weights_at,
)

SPACES = ["eq41", "eq41-printed", "excess<=1", "excess<=2", "excess<=3"]
TIES = tie_points()


def _argmax_of(W: list[Fraction]) -> tuple[int, ...]:
    return tuple(k for k, x in enumerate(W, 1) if x == max(W))


# --------------------------------------------------------------------------- exact ties
def test_tie_points_exist():
    assert len(TIES) >= 20
    # some of them are ties at the maximum (more than one mode)
    multi = 0
    for base, w, N, p in TIES:
        W = weights_at(walk_polys(N, base, w), p)
        multi += sum(x == max(W) for x in W) > 1
    assert multi >= 5


@pytest.mark.parametrize("case", TIES, ids=str)
def test_modes_at_exact_ties(case):
    base, w, N, p = case
    want = _argmax_of(weights_at(walk_polys(N, base, w), p))
    assert modes(N, p, space=base, weighting=w) == want
    assert space_modes(parse_space(base, w), N, p) == want
    d = distribution(N, p, space=base, weighting=w)
    assert d.modes() == want and d.mode() == want[0]
    # the float of a tie p is a little off the tie: its exact binary value decides
    pf = Fraction(float(p))
    assert modes(N, float(p), space=base, weighting=w) == _argmax_of(
        weights_at(walk_polys(N, base, w), pf))


@settings(max_examples=60, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(N=st.sampled_from([2, 3, 4]), base=st.sampled_from(SPACES),
       w=st.sampled_from(["length", "distinct"]),
       p=st.one_of(st.sampled_from([t[3] for t in TIES]),
                   st.integers(1, 12).map(lambda j: Fraction(1, 10**j)),
                   st.integers(1, 12).map(lambda j: 1 - Fraction(1, 10**j)),
                   st.integers(1, 12).map(lambda j: 1 + Fraction(1, 10**j)),
                   st.fractions(Fraction(1, 10**6), 10).filter(lambda x: x > 0)))
def test_modes_exhaustive_scan(N, base, w, p):
    assert modes(N, p, space=base, weighting=w) == _argmax_of(
        weights_at(walk_polys(N, base, w), p))


def test_modes_n1_and_simple_dispatch():
    for base in SPACES:
        assert modes(1, Fraction(1, 2), space=base) == (1,)
        assert space_modes(parse_space(base), 1, Fraction(7, 2)) == (1,)
    for N, p in ((5, Fraction(1, 2)), (10, Fraction(1, 3)), (101, Fraction(1, 50))):
        assert modes(N, p, space="simple") == simple_modes(N, p, p)
        assert modes(N, p, space="excess<=0") == simple_modes(N, p, p)
        assert modes(N, p, space="simple", weighting="distinct") == simple_modes(N, p, p)
    assert isinstance(distribution(5, Fraction(1, 2), space="simple"), SimpleDistribution)
    assert isinstance(distribution(5, Fraction(1, 2), space="simple;distinct"),
                      SimpleDistribution)
    assert isinstance(distribution(5, Fraction(1, 2), space="excess<=0"), SpaceDistribution)


def test_space_modes_validates_n():
    assert_refuses(space_modes, parse_space("eq41"), 0, Fraction(1, 2), arg="N", value="got 0",
                   allowed=">= 1")


def test_modes_refuse_N_below_one():
    for space in ("simple", "eq41"):
        assert_refuses(modes, 0, Fraction(1, 3), space=space, arg="N", value="got 0",
                       allowed=">= 1")


def test_simple_modes_of_an_irrational_p():
    """A sympy irrational p (no exact rational value) in the simple space: the argmax of the
    weights p**k N!/(k (N-k)!) evaluated at 60 digits."""
    sympy = pytest.importorskip("sympy")
    N = 40
    for p in (sympy.sqrt(2) / 7, sympy.pi / 30):
        with mpmath.workdps(60):
            pm = mpmath.mpf(sympy.N(p, 70))
            lw = [k * mpmath.log(pm) + mpmath.log(math.factorial(N) // math.factorial(N - k))
                  - mpmath.log(k) for k in range(1, N + 1)]
            top = max(lw)
            ref = tuple(k for k, v in enumerate(lw, 1) if v == top)
        assert modes(N, p, space="simple") == ref, p


def test_space_modes_certified_against_exact_weights(monkeypatch):
    """modes over a space equal the exact argmax of W (Burnside counts, Fractions) on a p grid
    that includes ties at c_k and p > 1, also when the float64 seed is deliberately wrong."""
    for space in ("eq41", "excess<=3"):
        N = 23
        cp = critical_point(N, space=space, dps=20)
        grid = [Fraction(i, 40) for i in range(1, 60)]
        if cp.p_exact is not None:
            grid.append(cp.p_exact)
        for p in grid:
            assert modes(N, p, space=space) == argmax(N, space, p), (space, p)
    monkeypatch.setattr(dist, "log_W_float",
                        lambda sp, n, lp: -np.abs(np.arange(n) - 2.0))  # argmax at k = 3
    for p in (Fraction(1, 3), Fraction(1, 1000), Fraction(3, 2)):
        W = weights_at(weight_polys(23, "eq41"), p)
        assert modes(23, p, space="eq41") == (W.index(max(W)) + 1,), p


def test_space_candidates_superset_for_any_guess():
    """space_candidates(top=guess) contains every k with W(k) >= W(guess), for bad guesses
    over a fine p grid (exact Fractions over all k)."""
    for space, N in (("eq41", 40), ("excess<=4", 25)):
        sp = parse_space(space)
        polys = weight_polys(N, space)
        for i in range(5, 90, 2):
            p = Fraction(i, 20 * N)
            w = weights_at(polys, p)
            for guess in (1, 2, 3):
                got = set(space_candidates(sp, N, p, guess))
                need = {k for k in range(1, N + 1) if w[k - 1] >= w[guess - 1]}
                assert need <= got, (space, p, guess, need - got)


# --------------------------------------------------------------------------- compare_weights
@pytest.mark.parametrize("base,w,N,j,k", [
    ("eq41", "length", 2100, 1, 80),
    ("excess<=2", "distinct", 2500, 3, 90),
    ("eq41-printed", "length", 2100, 5, 70),   # d = 65 > 64: the Arb branch
    ("eq41", "length", 2100, 2, 40),             # d <= 64: exact integers
])
def test_compare_weights_both_sides_of_a_root(base, w, N, j, k):
    """Rationals 10**-40 (relative) on either side of the root of W(k) = W(j): the sign flips.
    Any error in the log-ratio ball larger than that gives a wrong sign on one side."""
    sp = parse_space(base, w)
    r = root(N, base, k, digits=80, j=j, weighting=w)
    with mpmath.workdps(80):
        below = mpf_to_fraction(r * (1 - mpmath.mpf(10) ** -40))
        above = mpf_to_fraction(r * (1 + mpmath.mpf(10) ** -40))
    assert dist.compare_weights(sp, N, below, j, k) == -1
    assert dist.compare_weights(sp, N, above, j, k) == 1
    assert dist.compare_weights(sp, N, below, k, j) == 1
    assert dist.compare_weights(sp, N, above, k, j) == -1
    assert dist.compare_weights(sp, N, above, k, k) == 0


def test_compare_weights_exact_limit(monkeypatch):
    sp = parse_space("eq41")
    monkeypatch.setattr(dist, "EXACT_BITS_LIMIT", 10)
    with pytest.raises(dist.UndecidedError, match="exact comparison"):
        dist.compare_weights(sp, 10, Fraction(1, 3), 1, 3)
    monkeypatch.setattr(dist, "EXACT_BITS_LIMIT", 10**6)
    assert dist.compare_weights(sp, 10, Fraction(1, 3), 1, 3) == weight_sign(
        10, "eq41", 3, Fraction(1, 3))


def test_exact_limit_is_the_documented_bit_count(monkeypatch):
    """The refusal threshold counts d (bit_length(N) + max bit_length(a, b) + 1) bits."""
    sp = parse_space("eq41")
    N, fr, j, k = 10, Fraction(1, 3), 1, 3
    bits = (k - j) * (N.bit_length() + max(1, 3 .bit_length()) + 1)
    monkeypatch.setattr(dist, "EXACT_BITS_LIMIT", bits)
    dist.compare_weights(sp, N, fr, j, k)  # exactly at the limit: allowed
    monkeypatch.setattr(dist, "EXACT_BITS_LIMIT", bits - 1)
    with pytest.raises(dist.UndecidedError, match=f"~{bits} bits"):
        dist.compare_weights(sp, N, fr, j, k)


def test_compare_weights_falls_back_to_exact_integers(monkeypatch):
    """Where Arb balls cannot separate W(k) from W(j) up to 16 x the start precision (simulated
    by widening every input ball to +-50 %), the exact integer comparison decides: with the
    fall-back or the precision cap removed, this raised instead of answering. k - j > 64 and
    N >= 2000, so the ball route is the one taken."""
    flint = pytest.importorskip("flint")
    real = dist.to_arb

    def wide(x):
        b = real(x)
        return flint.arb(b.mid(), abs(b.mid()) / 2)

    monkeypatch.setattr(dist, "to_arb", wide)
    N, fr = 2500, Fraction(1, 700)
    for space in ("eq41", "excess<=2"):
        sp = parse_space(space)
        for j, k in ((1, 100), (300, 400), (50, 2400), (2000, 2100)):
            want = weight_sign(N, space, k, fr, j=j)
            assert want != 0
            assert dist.compare_weights(sp, N, fr, j, k) == want, (space, j, k)
            assert dist.compare_weights(sp, N, fr, k, j) == -want, (space, j, k)
