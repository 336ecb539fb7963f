"""symhx.spaces.critical_point against independent polynomial roots and exact mode scans."""

from __future__ import annotations

import math
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


# ----------------------------------------------------------------- Arb certification (issue 11)
def _exact_W(N: int, k: int, p: Fraction, shapes, weighting: str, printed: bool) -> Fraction:
    """W(k) at an exact rational p from Burnside's circuit counts (independent of the tables)."""
    return sum((Fraction(c) * p**d for d, c in _weight_poly(N, k, shapes, weighting, printed)
                .items()), Fraction(0))


@pytest.mark.parametrize("space,shapes,printed", [
    ("eq41", EQ41_SHAPES, False),
    ("eq41-printed", EQ41_SHAPES, True),
    ("excess<=3", shapes_up_to(3), False),
])
@pytest.mark.parametrize("weighting", ["length", "distinct"])
@pytest.mark.parametrize("N", [6, 23, 60])
def test_enclosure_by_exact_brute_force(space, shapes, printed, weighting, N):
    """Just below p_bounds every k >= 2 has W(k) < W(1); just above, W(k_after) beats every
    other k: exact rational arithmetic over all k (a wrong argmin or enclosure fails)."""
    from symhx.validation import as_fraction

    cp = critical_point(N, space=space, weighting=weighting, dps=20)
    lo, hi = (as_fraction(x) for x in cp.p_bounds)
    assert lo <= hi and (hi - lo) <= Fraction(1, 10**20) * lo
    if cp.p_exact is not None:
        assert lo <= cp.p_exact <= hi
    below = lo * (1 - Fraction(1, 10**30))
    above = hi * (1 + Fraction(1, 10**30))
    wb = [_exact_W(N, k, below, shapes, weighting, printed) for k in range(1, N + 1)]
    wa = [_exact_W(N, k, above, shapes, weighting, printed) for k in range(1, N + 1)]
    assert all(w < wb[0] for w in wb[1:]), (space, N)
    top = max(wa)
    assert [k for k, w in enumerate(wa, 1) if w == top] == [cp.k_after], (space, N)


@pytest.mark.parametrize("N,space", [(101, "eq41"), (101, "excess<=2;distinct"),
                                     (10**4, "eq41")])
def test_enclosure_contains_independent_root(N, space):
    """p_bounds (relative width <= 10**-dps) contains the root of W(k_after) = W(1) found by
    mpmath.findroot on the exact polynomial at 3x the digits."""
    from symhx.spaces._classes import parse_space

    sp = parse_space(space)
    for dps in (15, 40):
        cp = critical_point(N, space=space, dps=dps)
        k = cp.k_after
        with mpmath.workdps(3 * dps + 2 * len(str(N)) + 20):
            def f(p, k=k):
                # log W(k) - log W(1) with exact counts (class_count) and mpmath logs
                def W(j):
                    tot = mpmath.mpf(0)
                    for s in sp.shapes:
                        c = sp.count(N, s, j)
                        if c:
                            e = sum(x - 1 for x in s) if sp.weighting == "length" else 0
                            tot += c * p ** (j + e)
                    return tot
                return mpmath.log(W(k)) - mpmath.log(W(1))

            ref = mpmath.findroot(f, cp.p)
            lo, hi = cp.p_bounds
            assert lo <= ref <= hi
            assert (hi - lo) <= mpmath.mpf(10) ** -dps * ref


def test_exclusion_stop_bound_against_exhaustive():
    """The certified running product lists every k that it cannot exclude; the k it skips
    (after its stopping bound) really have W(k) < W(1): exact check over all k."""
    from symhx.spaces._classes import parse_space
    from symhx.spaces._critical import _unexcluded

    for space, N in (("eq41", 40), ("excess<=4", 30), ("eq41-printed", 35)):
        sp = parse_space(space)
        cp = critical_point(N, space=space, dps=20)
        for p in (Fraction(1, N), Fraction(3, 2 * N), Fraction(1, 3), Fraction(9, 10)):
            listed = set(_unexcluded(sp, N, p, cp.k_after))
            w1 = sp.Qstar(1, p) * p * N  # W(1) up to the common factor
            for k in range(2, N + 1):
                wk = sp.Qstar(k, p) * p**k * Fraction(math.perm(N, k), k)
                if wk >= w1 and k != cp.k_after:
                    assert k in listed, (space, N, p, k)


def test_wrong_seed_is_corrected(monkeypatch):
    """The float64 seed decides nothing: a seed whose argmin is wrong still gives the
    certified answer (the exclusion step finds the smaller root and restarts)."""
    import numpy as np

    import symhx.spaces._critical as crit

    for space, N in (("eq41", 101), ("excess<=3", 60)):
        right = critical_point(N, space=space, dps=25)
        real = crit.root_estimates

        def fake(sp, n, real=real, k=right.k_after):
            s = np.array(real(sp, n))
            s[k + 3 - 2] = s.min() - 1e-3  # pretend c_{k+3} is the smallest
            return s

        monkeypatch.setattr(crit, "root_estimates", fake)
        got = crit.critical_point(N, space=space, dps=25)
        monkeypatch.setattr(crit, "root_estimates", real)
        assert got.argmins == right.argmins and got.p_bounds == right.p_bounds


def test_exclusion_with_any_best_over_a_p_grid():
    """_unexcluded with best=2 over a fine p grid: everything it skips is below W(1)."""
    from symhx.spaces._classes import parse_space
    from symhx.spaces._critical import _unexcluded

    for space, N in (("eq41", 40), ("excess<=4", 25)):
        sp = parse_space(space)
        for i in range(10, 80):
            p = Fraction(i, 20 * N)
            listed = set(_unexcluded(sp, N, p, 2))
            w1 = sp.Qstar(1, p) * p * N
            for k in range(3, N + 1):
                wk = sp.Qstar(k, p) * p**k * Fraction(math.perm(N, k), k)
                if wk >= w1:
                    assert k in listed, (space, N, p, k)


def test_space_modes_certified_against_exact_weights(monkeypatch):
    """modes over a space equal the exact argmax of W (Burnside counts, Fractions) on a p grid
    that includes ties at c_k and p > 1, also when the float64 seed is deliberately wrong."""
    import numpy as np

    import symhx.spaces._dist as dist

    for space, shapes, printed in (("eq41", EQ41_SHAPES, False),
                                   ("excess<=3", shapes_up_to(3), False)):
        N = 23
        cp = critical_point(N, space=space, dps=20)
        grid = [Fraction(i, 40) for i in range(1, 60)]
        if cp.p_exact is not None:
            grid.append(cp.p_exact)
        for p in grid:
            w = [_exact_W(N, k, p, shapes, "length", printed) for k in range(1, N + 1)]
            top = max(w)
            exact = tuple(k for k, x in enumerate(w, 1) if x == top)
            assert modes(N, p, space=space) == exact, (space, p)
    real = dist.log_W_float
    monkeypatch.setattr(dist, "log_W_float",
                        lambda sp, n, lp: -np.abs(np.arange(n) - 2.0))  # argmax at k = 3
    for p in (Fraction(1, 3), Fraction(1, 1000), Fraction(3, 2)):
        w = [_exact_W(23, k, p, EQ41_SHAPES, "length", False) for k in range(1, 24)]
        assert modes(23, p, space="eq41") == (w.index(max(w)) + 1,), p
    monkeypatch.setattr(dist, "log_W_float", real)


def test_space_candidates_superset_for_any_guess():
    """space_candidates(top=guess) contains every k with W(k) >= W(guess), for bad guesses
    over a fine p grid (exact Fractions over all k)."""
    from symhx.certify import space_candidates
    from symhx.spaces._classes import parse_space

    for space, N in (("eq41", 40), ("excess<=4", 25)):
        sp = parse_space(space)
        for i in range(5, 90, 2):
            p = Fraction(i, 20 * N)
            w = [sp.Qstar(k, p) * p**k * Fraction(math.perm(N, k), k) for k in range(1, N + 1)]
            for guess in (1, 2, 3):
                got = set(space_candidates(sp, N, p, guess))
                need = {k for k in range(1, N + 1) if w[k - 1] >= w[guess - 1]}
                assert need <= got, (space, p, guess, need - got)
