"""symhx.spaces.critical_point against independent polynomial roots and exact mode scans."""

from __future__ import annotations

from fractions import Fraction

import mpmath
import pytest

from symhx import critical as simple_critical
from symhx.circuits import circuit_count
from symhx.spaces import EQ41_SHAPES, critical_point, modes, parse_space, shapes_up_to
from symhx.spaces._classes import visits_of


def _weight_poly(N: int, k: int, shapes, weighting: str, printed: bool) -> dict[int, int]:
    """{degree: coefficient} of W(k; p), counts from Burnside's circuit_count (not the tables)."""
    poly: dict[int, int] = {}
    for s in shapes:
        if k < len(s) or (not s and k < 1):
            continue
        if printed and k == len(s) and s and s != (2,):
            continue
        c = circuit_count(N, visits_of(s, k))
        deg = k + sum(x - 1 for x in s) if weighting == "length" else k
        poly[deg] = poly.get(deg, 0) + c
    return poly


def _independent_pc(N: int, shapes, weighting: str, printed: bool) -> tuple[mpmath.mpf, int]:
    w1 = _weight_poly(N, 1, shapes, weighting, printed)
    best = None
    for k in range(2, N + 1):
        wk = _weight_poly(N, k, shapes, weighting, printed)
        diff = dict(wk)
        for d, c in w1.items():
            diff[d] = diff.get(d, 0) - c
        top = max(diff)
        coeffs = [diff.get(d, 0) for d in range(top, -1, -1)]
        with mpmath.workdps(40):
            roots = mpmath.polyroots(coeffs, maxsteps=200, extraprec=200)
            pos = [mpmath.re(r) for r in roots
                   if abs(mpmath.im(r)) < 1e-25 and mpmath.re(r) > 1e-30]
        assert len(pos) == 1, (N, k, pos)  # Descartes: exactly one positive root
        if best is None or pos[0] < best[0] - mpmath.mpf(10) ** -30:
            best = (pos[0], k)
    return best


@pytest.mark.parametrize("space,shapes,printed", [
    ("eq41", EQ41_SHAPES, False),
    ("eq41-printed", EQ41_SHAPES, True),
    ("excess<=2", shapes_up_to(2), False),
    ("excess<=4", shapes_up_to(4), False),
])
@pytest.mark.parametrize("weighting", ["length", "distinct"])
def test_against_polynomial_roots(space, shapes, printed, weighting):
    for N in (2, 3, 4, 7, 10):
        cp = critical_point(N, space=space, weighting=weighting, dps=25)
        ref, kref = _independent_pc(N, shapes, weighting, printed)
        assert cp.k_after == kref and cp.k_before == 1
        with mpmath.workdps(40):
            assert mpmath.almosteq(cp.p, ref, 1e-22), (space, N)
            assert mpmath.almosteq(cp.q, N * ref - 1, 1e-20)


@pytest.mark.parametrize("space", ["eq41", "eq41-printed", "excess<=3", "excess<=6",
                                   "excess<=2;distinct"])
def test_modes_either_side(space):
    for N in (5, 17, 100, 101):
        cp = critical_point(N, space=space, dps=30)
        with mpmath.workdps(30):
            below = Fraction(mpmath.nstr(cp.p * (1 - mpmath.mpf(10) ** -12), 28))
            above = Fraction(mpmath.nstr(cp.p * (1 + mpmath.mpf(10) ** -12), 28))
        assert modes(N, below, space=space) == (1,)
        assert modes(N, above, space=space) == (cp.k_after,)
        # and the mode is 1 everywhere below: a coarse exact scan
        for j in range(1, 20):
            assert modes(N, below * j / 20, space=space) == (1,)


def test_excess0_is_simple_and_ties():
    for N in (2, 3, 4, 5, 6, 50, 101):
        a = critical_point(N, space="excess<=0", dps=30)
        b = simple_critical.critical_point(N, dps=30)
        assert a.argmins == b.argmins and a.k_after == b.k_after
        with mpmath.workdps(40):
            assert mpmath.almosteq(a.p, b.p, 1e-28)
    tie = critical_point(5, space="excess<=0")
    assert tie.argmins == (2, 3) and tie.p_exact == Fraction(1, 2)
    assert modes(5, Fraction(1, 2), space="excess<=0") == (1, 2, 3)


def test_distinct_weighting_rational_roots():
    cp = critical_point(3, space="eq41;distinct")
    # W(1) = 4 N p (phi, phi^1, phi^{1,0}, phi^{1,0,0}), W(2) = p^2 * total count at k=2
    sp = parse_space("eq41;distinct")
    tot2 = sum(sp.count(3, s, 2) for s in sp.shapes)
    assert cp.p_exact == Fraction(4 * 3, tot2)
    assert modes(3, cp.p_exact, space="eq41;distinct") == (1, 2)


def test_large_n():
    cp = critical_point(10**5, space="eq41", dps=20)
    assert 1 < cp.k_after < 10**5
    with mpmath.workdps(20):
        above = Fraction(mpmath.nstr(cp.p * (1 + mpmath.mpf(10) ** -10), 18))
        below = Fraction(mpmath.nstr(cp.p * (1 - mpmath.mpf(10) ** -10), 18))
    assert modes(10**5, above, space="eq41") == (cp.k_after,)
    assert modes(10**5, below, space="eq41") == (1,)
