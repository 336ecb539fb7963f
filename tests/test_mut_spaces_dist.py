"""symhx.spaces distributions (``_dist``) against independent references (issue 16).

References used here, none of them the package's class tables:

* explicit closed walks up to rotation (``_brute.necklaces``: every word, least rotation) for
  small N, giving each circuit's class and k, hence the weight polynomial of ``X = k``;
* Burnside's count :func:`symhx.circuits.circuit_count` of each visit pattern for larger N
  (itself checked against the walks below);
* exact ``Fraction`` arithmetic for pmfs, moments, cdfs and argmax scans; mpmath comparisons
  at more than twice the claimed digits.
"""

from __future__ import annotations

import math
from collections import Counter
from fractions import Fraction

import mpmath
import numpy as np
import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

import symhx.spaces._dist as dist
from symhx.circuits import circuit_count
from symhx.distribution import SimpleDistribution, simple_modes
from symhx.spaces import (
    EQ41_SHAPES,
    SpaceDistribution,
    class_decomposition,
    class_probabilities,
    distribution,
    modes,
    parse_space,
    shapes_up_to,
    space_modes,
)
from symhx.spaces._classes import visits_of
from symhx.validation import mpf_to_fraction
from tests.reference.combinatorics import necklaces

SPACES = ["eq41", "eq41-printed", "excess<=1", "excess<=2", "excess<=3"]


# --------------------------------------------------------------------------- references
def _excess(shape: tuple[int, ...]) -> int:
    return sum(x - 1 for x in shape)


def _members(base: str) -> tuple[set, bool, int]:
    """(classes, printed, max excess) of a space, written out by hand."""
    if base in ("eq41", "eq41-printed"):
        return set(EQ41_SHAPES), base == "eq41-printed", 3
    m = int(base.split("<=")[1])
    return set(shapes_up_to(m)), False, m


def _counted(base: str, shape: tuple[int, ...], k: int) -> bool:
    shapes, printed, _ = _members(base)
    if shape not in shapes:
        return False
    # the printed space drops the boundary terms k == r except phi^1(2) (eq. 36)
    return not (printed and shape and k == len(shape) and shape != (2,))


def _walk_classes(N: int, m: int) -> Counter:
    """Counter of (class, k, L) over every closed walk (up to rotation) of length <= N + m."""
    out: Counter = Counter()
    for L in range(1, N + m + 1):
        for w in necklaces(N, L):
            c = Counter(w)
            shape = tuple(sorted((v for v in c.values() if v > 1), reverse=True))
            out[(shape, len(c), L)] += 1
    return out


def _walk_poly(N: int, base: str, weighting: str) -> dict[int, dict[int, int]]:
    """{k: {degree of p: number of circuits}} of the space, from explicit walks."""
    _, _, m = _members(base)
    polys: dict[int, dict[int, int]] = {k: {} for k in range(1, N + 1)}
    for (shape, k, L), n in _walk_classes(N, m).items():
        if _excess(shape) > m or not _counted(base, shape, k):
            continue
        deg = L if weighting == "length" else k
        polys[k][deg] = polys[k].get(deg, 0) + n
    return polys


def _burnside_k(N: int, base: str, weighting: str, k: int) -> dict[int, int]:
    """{degree of p: number of circuits} with k distinct vertices, by Burnside's count of each
    visit pattern of the space (any N)."""
    shapes, _, _ = _members(base)
    poly: dict[int, int] = {}
    for s in shapes:
        if k < max(len(s), 1) or not _counted(base, s, k):
            continue
        deg = k + _excess(s) if weighting == "length" else k
        poly[deg] = poly.get(deg, 0) + circuit_count(N, visits_of(s, k))
    return poly


def _burnside_poly(N: int, base: str, weighting: str) -> dict[int, dict[int, int]]:
    """The weight polynomials of every k = 1..N from Burnside's counts."""
    return {k: _burnside_k(N, base, weighting, k) for k in range(1, N + 1)}


def _W(poly: dict[int, dict[int, int]], p: Fraction) -> list[Fraction]:
    return [sum((c * p**d for d, c in poly[k].items()), Fraction(0)) for k in sorted(poly)]


def _mp(x: Fraction) -> mpmath.mpf:
    return mpmath.mpf(x.numerator) / x.denominator


def _close(got, ref: Fraction, dps: int) -> bool:
    """|got - ref| <= 10**(1 - dps) |ref|, decided at 2 dps + 30 digits."""
    with mpmath.workdps(2 * dps + 30):
        return abs(got - _mp(ref)) <= mpmath.mpf(10) ** (1 - dps) * abs(_mp(ref))


def _log_close(got, ref: Fraction, dps: int) -> bool:
    """log of an exact positive value, absolute error <= 10**(1 - dps) max(1, |log|)."""
    with mpmath.workdps(2 * dps + 30):
        lr = mpmath.log(_mp(ref))
        return abs(got - lr) <= mpmath.mpf(10) ** (1 - dps) * max(1, abs(lr))


# --------------------------------------------------------------------------- walks vs Burnside
@pytest.mark.parametrize("base", SPACES)
def test_burnside_polynomials_equal_the_walks(base):
    for N in (1, 2, 3, 4):
        for w in ("length", "distinct"):
            assert _walk_poly(N, base, w) == _burnside_poly(N, base, w), (base, N, w)


# --------------------------------------------------------------------------- exact path
P_EXACT = [Fraction(1, 3), Fraction(1), Fraction(5, 2), Fraction(1, 1000), Fraction(999, 1000)]


@pytest.mark.parametrize("base", SPACES)
@pytest.mark.parametrize("weighting", ["length", "distinct"])
def test_exact_distribution_against_walks(base, weighting):
    for N in (1, 2, 3, 4):
        poly = _walk_poly(N, base, weighting)
        for p in P_EXACT:
            W = _W(poly, p)
            g = sum(W)
            pmf = [w / g for w in W]
            d = distribution(N, p, space=base, weighting=weighting)
            assert isinstance(d, SpaceDistribution) and d.exact
            assert d.normaliser == g
            assert d.table() == list(enumerate(pmf, 1))
            for k in range(0, N + 2):
                ref = pmf[k - 1] if 1 <= k <= N else Fraction(0)
                assert d.pmf(k) == ref
                assert d.weight_exact(k) == (W[k - 1] if 1 <= k <= N else 0)
                assert d.cdf(k) == sum(pmf[:max(k, 0)], Fraction(0))
                assert d.sf(k) == 1 - d.cdf(k)
            mu = sum(k * v for k, v in enumerate(pmf, 1))
            assert d.mean() == mu
            assert d.var() == sum((k - mu) ** 2 * v for k, v in enumerate(pmf, 1))
            assert _log_close(d.log_normaliser, g, d.dps)
            for k in range(1, N + 1):
                assert _log_close(d.logpmf(k), pmf[k - 1], d.dps)
            top = max(pmf)
            want = tuple(k for k, v in enumerate(pmf, 1) if v == top)
            assert d.modes() == want and d.mode() == want[0]
            assert modes(N, p, space=base, weighting=weighting) == want
            with mpmath.workdps(80):
                h = -mpmath.fsum(_mp(v) * mpmath.log(_mp(v)) for v in pmf)
                assert abs(d.entropy() - h) <= mpmath.mpf(10) ** (1 - d.dps) * max(1, h)


def test_exact_larger_n_against_burnside():
    """N = 9 and 23 (beyond the walks): pmf, moments, cdf and modes from Burnside counts."""
    for base, w, N, p in (("eq41", "length", 9, Fraction(2, 7)),
                          ("eq41-printed", "length", 23, Fraction(1, 19)),
                          ("excess<=3", "distinct", 23, Fraction(3, 40)),
                          ("excess<=2", "length", 23, Fraction(7, 5))):
        W = _W(_burnside_poly(N, base, w), p)
        g = sum(W)
        d = distribution(N, p, space=base, weighting=w)
        assert d.normaliser == g
        assert [v for _, v in d.table()] == [x / g for x in W]
        assert d.mean() == sum(k * x for k, x in enumerate(W, 1)) / g
        assert d.cdf(N // 2) == sum(W[:N // 2]) / g
        top = max(W)
        assert d.modes() == tuple(k for k, x in enumerate(W, 1) if x == top)


# --------------------------------------------------------------------------- exact ties
def _rational_roots(coeffs: dict[int, int]) -> set[Fraction]:
    """Positive rational roots of an integer polynomial {degree: coefficient} (rational-root
    theorem, checked exactly)."""
    lo = min(d for d, c in coeffs.items() if c)
    c = {d - lo: v for d, v in coeffs.items() if v}
    top = max(c)
    a0, an = abs(c[0]), abs(c[top])

    def divisors(n: int) -> list[int]:
        return [i for i in range(1, n + 1) if n % i == 0]

    out = set()
    for num in divisors(a0):
        for den in divisors(an):
            x = Fraction(num, den)
            if sum(v * x**d for d, v in c.items()) == 0:
                out.add(x)
    return out


def _tie_points() -> list[tuple[str, str, int, Fraction]]:
    """(space, weighting, N, p) where two weights tie exactly, found from the walk polynomials."""
    pts = []
    for base in ("eq41", "eq41-printed", "excess<=1", "excess<=2"):
        for w in ("length", "distinct"):
            for N in (2, 3, 4):
                poly = _walk_poly(N, base, w)
                for j in range(1, N + 1):
                    for k in range(j + 1, N + 1):
                        diff = dict(poly[k])
                        for dg, c in poly[j].items():
                            diff[dg] = diff.get(dg, 0) - c
                        if any(diff.values()) and max(abs(v) for v in diff.values()) < 10**5:
                            pts += [(base, w, N, x) for x in _rational_roots(diff)]
    return sorted(set(pts))


TIES = _tie_points()


def test_tie_points_exist():
    assert len(TIES) >= 20
    # some of them are ties at the maximum (more than one mode)
    multi = 0
    for base, w, N, p in TIES:
        W = _W(_walk_poly(N, base, w), p)
        multi += sum(x == max(W) for x in W) > 1
    assert multi >= 5


@pytest.mark.parametrize("case", TIES, ids=str)
def test_modes_at_exact_ties(case):
    base, w, N, p = case
    W = _W(_walk_poly(N, base, w), p)
    want = tuple(k for k, x in enumerate(W, 1) if x == max(W))
    assert modes(N, p, space=base, weighting=w) == want
    assert space_modes(parse_space(base, w), N, p) == want
    d = distribution(N, p, space=base, weighting=w)
    assert d.modes() == want and d.mode() == want[0]
    # the float of a tie p is a little off the tie: its exact binary value decides
    pf = Fraction(float(p))
    Wf = _W(_walk_poly(N, base, w), pf)
    assert modes(N, float(p), space=base, weighting=w) == tuple(
        k for k, x in enumerate(Wf, 1) if x == max(Wf))


@settings(max_examples=60, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(N=st.sampled_from([2, 3, 4]), base=st.sampled_from(SPACES),
       w=st.sampled_from(["length", "distinct"]),
       p=st.one_of(st.sampled_from([t[3] for t in TIES]),
                   st.integers(1, 12).map(lambda j: Fraction(1, 10**j)),
                   st.integers(1, 12).map(lambda j: 1 - Fraction(1, 10**j)),
                   st.integers(1, 12).map(lambda j: 1 + Fraction(1, 10**j)),
                   st.fractions(Fraction(1, 10**6), 10).filter(lambda x: x > 0)))
def test_modes_exhaustive_scan(N, base, w, p):
    W = _W(_walk_poly(N, base, w), p)
    assert modes(N, p, space=base, weighting=w) == tuple(
        k for k, x in enumerate(W, 1) if x == max(W))


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
    with pytest.raises(TypeError, match="parse_space"):
        SpaceDistribution(5, Fraction(1, 2), "eq41")


# --------------------------------------------------------------------------- compare_weights
def _pair_root(N: int, base: str, w: str, j: int, k: int) -> mpmath.mpf:
    """Root of W(k) = W(j) from Burnside polynomials (mpmath bisection, 80 digits)."""
    poly = {i: _burnside_k(N, base, w, i) for i in (j, k)}

    def f(p):
        def W(i):
            return mpmath.fsum(c * p**d for d, c in poly[i].items())
        return mpmath.log(W(k)) - mpmath.log(W(j))

    with mpmath.workdps(80):
        lo, hi = mpmath.mpf(10) ** -12, mpmath.mpf(100)
        for _ in range(240):  # bisection: f increases with p (one sign change)
            mid = (lo + hi) / 2
            if f(mid) < 0:
                lo = mid
            else:
                hi = mid
        assert hi - lo < mpmath.mpf(10) ** -60 * lo
        return (lo + hi) / 2


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
    r = _pair_root(N, base, w, j, k)
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
    W = _W(_burnside_poly(10, "eq41", "length"), Fraction(1, 3))
    assert dist.compare_weights(sp, 10, Fraction(1, 3), 1, 3) == (W[2] > W[0]) - (W[2] < W[0])


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


# --------------------------------------------------------------------------- float64 screens
@pytest.mark.parametrize("space", ["eq41", "eq41-printed", "excess<=0", "excess<=4",
                                   "excess<=3;distinct"])
def test_log_U_table_against_exact_logs(space, monkeypatch):
    monkeypatch.setattr(dist, "_LOGU", {})
    sp = parse_space(space)
    for K in (3, 40, 7, 200):  # grows the cache (doubling), then reads a prefix of it
        tab = dist.log_U_table(sp, K)
        assert tab.shape == (sp.max_excess + 1, K)
        for k in range(1, K + 1):
            for e, u in enumerate(sp.U(k)):
                if u == 0:
                    assert tab[e, k - 1] == -np.inf
                else:
                    assert abs(tab[e, k - 1] - math.log(u)) <= 1e-13 * max(1, math.log(u))


@pytest.mark.parametrize("space", ["eq41", "eq41-printed", "excess<=3", "eq41;distinct"])
def test_log_W_float_against_exact(space):
    sp = parse_space(space)
    for N, p in ((30, Fraction(1, 7)), (30, Fraction(5, 2)), (2000, Fraction(1, 1500))):
        lw = dist.log_W_float(sp, N, dist._logp_float(p))
        assert lw.shape == (N,)
        with mpmath.workdps(40):
            for k in sorted({1, 2, 3, 4, 5, N // 3, N - 1, N}):
                ref = mpmath.log(_mp(p**k * Fraction(math.perm(N, k), k) * sp.Qstar(k, p)))
                assert abs(lw[k - 1] - ref) < 1e-8 * max(1, abs(ref)), (N, k)


def test_logp_float_of_huge_fractions():
    fr = Fraction(3**700, 2**1200)  # beyond the float range in both parts
    with mpmath.workdps(30):
        ref = 700 * mpmath.log(3) - 1200 * mpmath.log(2)
    assert abs(dist._logp_float(fr) - ref) < 1e-12 * abs(ref)


# --------------------------------------------------------------------------- mpmath path
def _check_mp(d, W: list[Fraction], dps: int, ks) -> None:
    g = sum(W)
    pmf = [x / g for x in W]
    assert not d.exact and d.dps == dps
    assert _close(d.normaliser, g, dps)
    assert _log_close(d.log_normaliser, g, dps)
    mu = sum(k * v for k, v in enumerate(pmf, 1))
    assert _close(d.mean(), mu, dps)
    assert _close(d.var(), sum((k - mu) ** 2 * v for k, v in enumerate(pmf, 1)), dps)
    for k in ks:
        assert _close(d.pmf(k), pmf[k - 1], dps), k
        assert _log_close(d.logpmf(k), pmf[k - 1], dps), k
        if k < d.N:
            assert _close(d.cdf(k), sum(pmf[:k]), dps), k
            assert _close(d.sf(k), sum(pmf[k:]), dps), k
    with mpmath.workdps(2 * dps + 30):
        h = -mpmath.fsum(_mp(v) * mpmath.log(_mp(v)) for v in pmf)
        assert abs(d.entropy() - h) <= mpmath.mpf(10) ** (1 - dps) * max(1, h)


@pytest.mark.parametrize("base,w", [("eq41", "length"), ("eq41-printed", "length"),
                                    ("excess<=3", "length"), ("excess<=2", "distinct"),
                                    ("eq41-printed", "distinct")])
def test_mpmath_path_against_exact_binary_value(base, w):
    N = 40
    poly = _burnside_poly(N, base, w)
    for p, dps in ((0.03, 20), (0.7, 45), (1.5, 30)):
        W = _W(poly, Fraction(p))
        d = distribution(N, p, space=base, weighting=w, dps=dps)
        _check_mp(d, W, dps, range(1, N + 1))
        table = d.table()
        g = sum(W)
        assert [k for k, _ in table] == list(range(1, N + 1))
        assert all(_close(v, W[k - 1] / g, dps) for k, v in table)
    with mpmath.workdps(60):
        pm = mpmath.mpf(1) / 37
    d = distribution(N, pm, space=base, weighting=w, dps=50)
    _check_mp(d, _W(poly, mpf_to_fraction(pm)), 50, (1, 2, 3, 20, 40))


def test_float64_path_against_exact():
    for base, w in (("eq41", "length"), ("excess<=2", "distinct")):
        N, p = 40, 0.05
        W = _W(_burnside_poly(N, base, w), Fraction(p))
        g = sum(W)
        d = distribution(N, p, space=base, weighting=w, dps=None)
        for k in range(1, N + 1):
            ref = float(W[k - 1] / g)
            assert abs(d.pmf(k) - ref) <= 1e-10 * ref
        assert abs(d.normaliser - float(g)) <= 1e-10 * float(g)
        assert abs(d.log_normaliser - math.log(g)) <= 1e-12 * max(1.0, abs(math.log(g)))
        assert [k for k, _ in d.table()] == list(range(1, N + 1))
        assert all(abs(v - float(W[k - 1] / g)) <= 1e-10 * float(W[k - 1] / g)
                   for k, v in d.table())


@pytest.fixture
def screened(monkeypatch):
    """Force the N > DIRECT_LIMIT (float-screened) mpmath path at small N."""
    monkeypatch.setattr(dist, "DIRECT_LIMIT", 10)


@pytest.mark.parametrize("base,w", [("eq41", "length"), ("excess<=3", "length"),
                                    ("eq41-printed", "distinct"), ("excess<=1", "distinct")])
def test_screened_path_against_exact(screened, base, w):
    N = 80
    poly = _burnside_poly(N, base, w)
    for p, dps in ((1 / 800, 15), (0.4, 25), (0.004, 20)):
        fr = Fraction(p)
        W = _W(poly, fr)
        g = sum(W)
        d = distribution(N, p, space=base, weighting=w, dps=dps)
        # the screen keeps exactly the k within the documented cut of the largest weight
        with mpmath.workdps(40):
            lw = [mpmath.log(_mp(x)) for x in W]
            cut = max(lw) - d._wdps * mpmath.log(10) - 20
        kept = [k for k in range(1, N + 1) if lw[k - 1] >= cut + 1e-6]
        dropped = [k for k in range(1, N + 1) if lw[k - 1] < cut - 1e-6]
        runs = d._runs()
        inside = {k for lo, hi in runs for k in range(lo, hi + 1)}
        assert set(kept) <= inside and not (set(dropped) & inside), (p, runs)
        assert all(lo <= hi for lo, hi in runs)
        assert dropped, "the test needs weights below the screen"
        _check_mp(d, W, dps, (kept[0], kept[-1], dropped[0], dropped[-1],
                              (kept[0] + kept[-1]) // 2))
        table = dict(d.table())
        for k in range(1, N + 1):
            if k in inside:
                assert _close(table[k], W[k - 1] / g, dps)
            else:
                assert table[k] == 0


def test_runs_split_at_gaps(monkeypatch):
    """A screen with two separate bands gives two runs, and W(k) restarts correctly after the
    gap (values against exact weights)."""
    N, base = 60, "eq41"
    monkeypatch.setattr(dist, "DIRECT_LIMIT", 10)
    fake = np.full(N, -1e6)
    fake[0:5] = 0.0       # k = 1..5
    fake[19:23] = 0.0     # k = 20..23
    fake[40] = -5.0       # k = 41
    monkeypatch.setattr(dist, "log_W_float", lambda sp, n, lp: fake.copy())
    p = Fraction(0.05)
    d = distribution(N, 0.05, space=base, dps=20)
    assert d._runs() == [(1, 5), (20, 23), (41, 41)]
    W = _W(_burnside_poly(N, base, "length"), p)
    terms = d._terms
    assert sorted(terms) == [1, 2, 3, 4, 5, 20, 21, 22, 23, 41]
    for k, v in terms.items():
        assert _close(v, W[k - 1], d._wdps - 2), k


def test_sympy_irrational_p():
    sympy = pytest.importorskip("sympy")
    p = sympy.sqrt(2) / 40
    N, base = 30, "eq41"
    with mpmath.workdps(200):
        pr = mpf_to_fraction(mpmath.sqrt(2) / 40)
    W = _W(_burnside_poly(N, base, "length"), pr)
    d = distribution(N, p, space=base, dps=30)
    _check_mp(d, W, 30, (1, 2, 10, 30))
    want = tuple(k for k, x in enumerate(W, 1) if x == max(W))
    assert modes(N, p, space=base) == want
    with pytest.raises(ValueError, match="irrational"):  # never read at a fixed precision
        dist._rational(p, None)
    with pytest.raises(ValueError, match="irrational"):
        d.weight_exact(3)
    assert d.modes() == want and d.mode() == want[0]
    g = sum(W)
    f64 = distribution(N, p, space=base, dps=None)
    assert all(abs(f64.pmf(k) - float(W[k - 1] / g)) <= 1e-10 * float(W[k - 1] / g)
               for k in (1, 5, 30))
    cd = class_decomposition(N, p, space=base, dps=30)
    with mpmath.workdps(60):
        assert _close(mpmath.fsum(cd.joint[s][4] for s in cd.shapes), W[4] / g, 30)


# --------------------------------------------------------------------------- classes
def _walk_class_poly(N: int, base: str, w: str) -> dict[tuple, dict[int, dict[int, int]]]:
    _, _, m = _members(base)
    out: dict = {}
    for (shape, k, L), n in _walk_classes(N, m).items():
        if _excess(shape) > m or not _counted(base, shape, k):
            continue
        deg = L if w == "length" else k
        row = out.setdefault(shape, {}).setdefault(k, {})
        row[deg] = row.get(deg, 0) + n
    return out


@pytest.mark.parametrize("base", ["eq41", "eq41-printed", "excess<=2"])
@pytest.mark.parametrize("w", ["length", "distinct"])
def test_class_decomposition_against_walks(base, w):
    for N in (2, 3, 4):
        cls = _walk_class_poly(N, base, w)
        for p in (Fraction(1, 3), Fraction(5, 2)):
            tot = {s: {k: sum(c * p**d for d, c in row.get(k, {}).items())
                       for k in range(1, N + 1)} for s, row in cls.items()}
            g = sum(sum(r.values()) for r in tot.values())
            cd = class_decomposition(N, p, space=base, weighting=w)
            assert set(cd.shapes) == _members(base)[0]
            for s in cd.shapes:
                want = [tot.get(s, {}).get(k, 0) / g for k in range(1, N + 1)]
                assert cd.joint[s] == want, (s, N, p)
                assert cd.totals[s] == sum(want)
            by: dict[int, Fraction] = {}
            for s in cd.shapes:
                by[_excess(s)] = by.get(_excess(s), 0) + cd.totals[s]
            assert cd.by_excess == by
            assert all(isinstance(v, Fraction) for v in cd.by_excess.values())
            probs = class_probabilities(N, p, space=base, weighting=w)
            assert probs == {cd.labels[s]: cd.totals[s] for s in cd.shapes}
            assert "classes=" in repr(cd)


@pytest.mark.parametrize("base,w", [("eq41", "length"), ("excess<=3", "distinct"),
                                    ("eq41-printed", "length")])
def test_class_decomposition_mpmath_against_exact(base, w, monkeypatch):
    N, p, dps = 30, 0.06, 25
    monkeypatch.setattr(dist, "DIRECT_LIMIT", N)  # N = DIRECT_LIMIT is still listed
    ex = class_decomposition(N, Fraction(p), space=base, weighting=w)
    mp = class_decomposition(N, p, space=base, weighting=w, dps=dps)
    assert mp.shapes == ex.shapes
    for s in ex.shapes:
        for k in range(1, N + 1):
            ref = ex.joint[s][k - 1]
            got = mp.joint[s][k - 1]
            if ref == 0:
                assert got == 0
            else:
                assert _close(got, ref, dps), (s, k)
        assert _close(mp.totals[s], ex.totals[s], dps)
    for e, v in ex.by_excess.items():
        assert _close(mp.by_excess[e], v, dps)
    # by_excess is rounded once to dps digits (not left at the working or global precision)
    for v in mp.by_excess.values():
        with mpmath.workdps(dps):
            assert +v == v
        with mpmath.workdps(dps - 3):
            assert +v != v or v == 0
    with pytest.raises(ValueError, match="N <= "):
        class_decomposition(dist.DIRECT_LIMIT + 1, 0.001, space=base, weighting=w, dps=15)
    # class_probabilities keeps the requested digits
    probs = class_probabilities(N, p, space=base, weighting=w, dps=dps)
    assert probs == {mp.labels[s]: mp.totals[s] for s in mp.shapes}
    for s in mp.shapes:
        v = probs[mp.labels[s]]
        with mpmath.workdps(dps):
            assert +v == v
        with mpmath.workdps(dps - 3):
            assert +v != v
        assert _close(v, ex.totals[s], dps)


def test_class_defaults_are_eq41():
    p = Fraction(1, 7)
    assert class_decomposition(6, p).totals == class_decomposition(6, p, space="eq41").totals
    assert class_probabilities(6, p) == class_probabilities(6, p, space="eq41")
    assert class_probabilities(6, p) != class_probabilities(6, p, space="eq41-printed")


def test_class_decomposition_at_many_digits_and_large_n():
    """dps = 40 (sums of the excess levels at dps + 10 digits) and N = 5000 (the Phi recurrence
    over 5000 steps, with its guard digits): against Burnside class shares and the exact pmf."""
    N, p, base = 12, 0.06, "excess<=3"
    ex = class_decomposition(N, Fraction(p), space=base)
    mp = class_decomposition(N, p, space=base, dps=40)
    for e, v in ex.by_excess.items():
        assert _close(mp.by_excess[e], v, 40)
    N, p, dps = 5000, 0.0005, 15
    cd = class_decomposition(N, p, space="eq41", dps=dps)
    d = distribution(N, p, space="eq41", dps=40)  # another algorithm, 25 digits more
    for k in (1, 2, 3, 7, 40):
        counts = {s: circuit_count(N, visits_of(s, k)) * Fraction(p) ** (sum(x - 1 for x in s))
                  for s in EQ41_SHAPES if k >= len(s)}
        tot = sum(counts.values())
        pk = mpf_to_fraction(d.pmf(k))
        for s, c in counts.items():
            assert _close(cd.joint[s][k - 1], pk * c / tot, dps), (k, s)


def test_class_decomposition_object_without_dps():
    """ClassDecomposition of any object: mpf totals are summed at 25 digits, rounded to 15."""
    with mpmath.workdps(40):
        a, b = mpmath.mpf(1) / 3, mpmath.mpf(2) / 7
    cd = dist.ClassDecomposition(object(), ((), (2,)), {(): [a], (2,): [b]}, {(): a, (2,): b})
    with mpmath.workdps(15):
        want = {0: +a, 1: +b}
    assert cd.by_excess == want
    assert cd.labels == {(): "phi", (2,): "phi^1"}


def test_direct_path_lists_every_k(monkeypatch):
    """N <= DIRECT_LIMIT: every W(k) by the recurrence (no k left out, even at 10**-200)."""
    N, p, base = 80, 1 / 800, "eq41"
    W = _W(_burnside_poly(N, base, "length"), Fraction(p))
    g = sum(W)
    for limit, complete in ((N, True), (N - 1, False)):
        monkeypatch.setattr(dist, "DIRECT_LIMIT", limit)
        d = distribution(N, p, space=base, dps=15)
        assert (d._runs() == [(1, N)]) == complete
        assert (sorted(d._terms) == list(range(1, N + 1))) == complete
        table = d.table()
        assert all(v > 0 for _, v in table) == complete
        assert _close(table[-1][1], W[-1] / g, 15) == complete
        # cdf and sf by the k listed in [lo, hi]; in the far tail as accurate either way
        assert _close(d.sf(N - 3), sum(W[N - 3:]) / g, 15)


def test_terms_accurate_to_the_working_precision():
    """The fixed-point Q* of the recurrence: every W(k) to ~wdps digits (large U_e(k) at
    large k, where too few fractional bits would show)."""
    for base, w in (("excess<=4", "length"), ("eq41", "distinct")):
        N, p = 400, 0.3
        d = distribution(N, p, space=base, weighting=w, dps=20)
        terms = d._terms
        for k in (1, 2, 3, 5, 150, 399, 400):
            ref = _W({k: _burnside_k(N, base, w, k)}, Fraction(p))[0]
            assert _close(terms[k], ref, d._wdps - 3), (base, k)


def test_run_starting_at_two(monkeypatch):
    """A run that starts at k = 2 gets Phi(2) from its closed form, not N p."""
    N, base = 40, "excess<=2"
    monkeypatch.setattr(dist, "DIRECT_LIMIT", 10)
    fake = np.full(N, -1e6)
    fake[1:6] = 0.0       # k = 2..6
    monkeypatch.setattr(dist, "log_W_float", lambda sp, n, lp: fake.copy())
    p = Fraction(0.125)
    d = distribution(N, 0.125, space=base, dps=20)
    assert d._runs() == [(2, 6)]
    W = _W(_burnside_poly(N, base, "length"), p)
    assert sorted(d._terms) == [2, 3, 4, 5, 6]
    for k, v in d._terms.items():
        assert _close(v, W[k - 1], d._wdps - 2), k


def test_space_modes_validates_n():
    with pytest.raises(ValueError, match="N"):
        space_modes(parse_space("eq41"), 0, Fraction(1, 2))


def test_screened_sympy_irrational(screened):
    """The fallback W(k) of a k below the screen, for a sympy irrational p."""
    sympy = pytest.importorskip("sympy")
    p = sympy.sqrt(2) / 400
    N, base = 60, "eq41"
    with mpmath.workdps(200):
        pr = mpf_to_fraction(mpmath.sqrt(2) / 400)
    W = _W(_burnside_poly(N, base, "length"), pr)
    d = distribution(N, p, space=base, dps=20)
    assert N not in d._terms
    assert _close(d.pmf(N), W[-1] / sum(W), 20)


def test_simple_space_distribution_keeps_dps():
    """``distribution(..., space="simple", dps=30)`` is the mpmath SimpleDistribution at 30 digits
    (a float p is taken at its exact binary value): checked against exact Fractions."""
    N, p = 12, 0.3
    d = distribution(N, p, space="simple", dps=30)
    assert isinstance(d, SimpleDistribution) and d.dps == 30
    fr = Fraction(p)
    w = {k: fr**k * Fraction(math.factorial(N), k * math.factorial(N - k)) for k in range(1, N + 1)}
    tot = sum(w.values())
    for k in (1, 5, 12):
        got = d.pmf(k)
        assert isinstance(got, mpmath.mpf)
        with mpmath.workdps(60):
            ref = mpmath.mpf(w[k].numerator) / w[k].denominator / tot
            assert abs(got / ref - 1) < mpmath.mpf(10) ** -29, k


def test_modes_refuse_N_below_one():
    for space in ("simple", "eq41"):
        with pytest.raises(ValueError, match="N"):
            modes(0, Fraction(1, 3), space=space)


def test_simple_modes_of_an_irrational_p():
    """A sympy irrational p (no exact rational value) in the simple space: the argmax of the
    weights p**k N!/(k (N-k)!) evaluated at 60 digits."""
    import sympy

    N = 40
    for p in (sympy.sqrt(2) / 7, sympy.pi / 30):
        with mpmath.workdps(60):
            pm = mpmath.mpf(sympy.N(p, 70))
            lw = [k * mpmath.log(pm) + mpmath.log(math.factorial(N) // math.factorial(N - k))
                  - mpmath.log(k) for k in range(1, N + 1)]
            top = max(lw)
            ref = tuple(k for k, v in enumerate(lw, 1) if v == top)
        assert modes(N, p, space="simple") == ref, p


def test_space_distribution_refuses_an_unparsed_space():
    with pytest.raises(TypeError, match=r"got str 'eq41'"):
        dist.SpaceDistribution(5, Fraction(1, 3), "eq41")
