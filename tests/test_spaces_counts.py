"""symhx.spaces: class counts and distributions against brute-force enumeration."""

from __future__ import annotations

import math
from collections import Counter, defaultdict
from fractions import Fraction

import mpmath
import pytest

from symhx._numeric import as_fraction
from symhx.api import distribution_of
from symhx.api import mean as dmean
from symhx.api import modes as dmodes
from symhx.circuits import enumerate_circuits, necklace_count, partitions
from symhx.spaces import (
    EQ41_SHAPES,
    class_count,
    class_decomposition,
    distribution,
    eq41_terms,
    modes,
    parse_space,
    printed_count,
    shapes_up_to,
)
from symhx.spaces._classes import visits_of


def _shape(word: tuple[int, ...]) -> tuple[int, ...]:
    return tuple(sorted((v for v in Counter(word).values() if v > 1), reverse=True))


@pytest.fixture(scope="module")
def brute() -> dict[tuple[int, int], Counter]:
    """{(N, L): Counter of (class, k)} by FKM enumeration (distinct cyclic sequences, periodic
    words included once), N <= 7, L <= N + 3 (capped to keep N**L small)."""
    out = {}
    for N in range(1, 8):
        for L in range(1, N + 4):
            if N**L > 2_500_000:
                continue
            c: Counter = Counter()
            for w in enumerate_circuits(N, L):
                c[(_shape(w), len(set(w)))] += 1
            out[(N, L)] = c
    return out


def test_every_class_count_matches_enumeration(brute):
    checked = 0
    for (N, L), c in brute.items():
        for v in partitions(L, max_parts=N):
            s = tuple(x for x in v if x > 1)
            k = len(v)
            assert class_count(N, s, k) == c.get((s, k), 0), (N, L, v)
            checked += 1
        assert sum(c.values()) == necklace_count(N, L)
    assert checked > 200


def test_totals_per_length_are_necklace_counts():
    # sum over all patterns of length L equals (1/L) sum_{d|L} phi(d) N**(L/d)
    for N in range(1, 9):
        for L in range(1, N + 6):
            total = 0
            for v in partitions(L, max_parts=N):
                s = tuple(x for x in v if x > 1)
                total += class_count(N, s, len(v))
            euler = sum(1 for i in range(1, L + 1) if math.gcd(i, L) == 1)
            assert euler >= 1
            direct = sum(
                sum(1 for i in range(1, d + 1) if math.gcd(i, d) == 1) * N ** (L // d)
                for d in range(1, L + 1) if L % d == 0) // L
            assert total == direct


def test_periodic_boundary_classes():
    # DESIGN §3.1: the boundary lengths; enumerated independently
    for N in range(2, 7):
        words3 = [w for w in enumerate_circuits(N, 3) if _shape(w) == (3,)]
        words4 = [w for w in enumerate_circuits(N, 4) if _shape(w) == (4,)]
        words22 = [w for w in enumerate_circuits(N, 4) if _shape(w) == (2, 2)]
        assert class_count(N, (3,), 1) == len(words3) == N
        assert class_count(N, (4,), 1) == len(words4) == N
        assert class_count(N, (2, 2), 2) == len(words22) == N * (N - 1)
        # the printed formulas evaluated there give words / L instead
        assert printed_count("38", N, 3, outside="formula") == Fraction(N, 3)
        assert printed_count("39", N, 4, outside="formula") == Fraction(N, 4)
        assert printed_count("40", N, 4, outside="formula") == Fraction(3 * N * (N - 1), 4)
        assert printed_count("35", N, 2, outside="formula") == Fraction(N, 2)
        assert printed_count("36", N, 2) == N == class_count(N, (2,), 1)


def test_printed_formulas_hold_in_their_ranges(brute):
    for (N, L), c in brute.items():
        for eq, shape in (("35", (2,)), ("38", (3,)), ("39", (4,)), ("40", (2, 2))):
            lo = {"35": 3, "38": 4, "39": 5, "40": 5}[eq]
            if L >= lo:
                k = L - sum(x - 1 for x in shape)
                assert printed_count(eq, N, L) == c.get((shape, k), 0), (eq, N, L)


def test_eq41_terms_sum_and_printed_difference():
    for N in range(2, 9):
        for k in range(1, N + 1):
            good = eq41_terms(N, k)
            bad = eq41_terms(N, k, printed=True)
            diff = {lab: good[lab] - bad[lab] for lab in good}
            expect = {"phi": 0, "phi^1": 0, "phi^{1,0}": N if k == 1 else 0,
                      "phi^2": N * (N - 1) if k == 2 else 0,
                      "phi^{1,0,0}": N if k == 1 else 0}
            assert diff == expect


def test_shapes_and_visits():
    assert len(shapes_up_to(6)) == 30
    for s in shapes_up_to(4):
        assert sum(x - 1 for x in s) <= 4
        assert all(x >= 2 for x in s)
    assert visits_of((3, 2), 4) == (3, 2, 1, 1)


def _brute_pmf(N: int, p: Fraction, shapes: set, weighting: str = "length",
               printed: bool = False) -> dict[int, Fraction]:
    maxexc = max(sum(x - 1 for x in s) for s in shapes)
    W: dict[int, Fraction] = defaultdict(Fraction)
    for L in range(1, N + maxexc + 1):
        for w in enumerate_circuits(N, L):
            s = _shape(w)
            k = len(set(w))
            if s not in shapes:
                continue
            if printed and k == len(s) and s != (2,) and s:
                continue  # the paper's boundary terms are missing
            W[k] += p**L if weighting == "length" else p**k
    tot = sum(W.values())
    return {k: W[k] / tot for k in range(1, N + 1)}


@pytest.mark.parametrize("space,shapes,printed", [
    ("eq41", set(EQ41_SHAPES), False),
    ("eq41-printed", set(EQ41_SHAPES), True),
    ("excess<=0", {()}, False),
    ("excess<=2", set(shapes_up_to(2)), False),
    ("excess<=3", set(shapes_up_to(3)), False),
])
@pytest.mark.parametrize("weighting", ["length", "distinct"])
def test_pmf_against_enumeration(space, shapes, printed, weighting):
    for N in (2, 3, 4, 5):
        for p in (Fraction(1, 3), Fraction(3, 2)):
            d = distribution(N, p, space=space, weighting=weighting)
            ref = _brute_pmf(N, p, shapes, weighting, printed)
            got = {k: d.pmf(k) for k in range(1, d.N + 1)}
            assert got == ref, (space, N, p)
            assert sum(got.values()) == 1
            mu = sum(k * v for k, v in ref.items())
            assert d.mean() == mu
            assert d.var() == sum((k - mu) ** 2 * v for k, v in ref.items())
            top = max(ref.values())
            assert modes(N, p, space=space, weighting=weighting) == tuple(
                k for k in sorted(ref) if ref[k] == top)


def test_dispatch_from_distribution_module():
    d = distribution_of(6, Fraction(1, 4), space="eq41;distinct")
    assert d.space == "eq41;distinct"
    assert dmean(6, Fraction(1, 4), space="excess<=0") == dmean(6, Fraction(1, 4))
    assert dmodes(6, Fraction(1, 4), space="eq41") == modes(6, Fraction(1, 4), space="eq41")


def test_pmf_sums_to_one_exactly_n100():
    for space in ("eq41", "eq41-printed", "excess<=5", "excess<=2;distinct"):
        d = distribution(100, Fraction(1, 70), space=space)
        assert sum(v for _, v in d.table()) == 1


def test_mpmath_matches_exact_and_higher_precision():
    for space in ("eq41", "excess<=6", "eq41-printed;distinct"):
        p = Fraction(3, 200)
        ex = distribution(100, p, space=space)
        lo = distribution(100, float(p), space=space, dps=30)  # 3/200 is not a float: close
        with mpmath.workdps(80):
            p_hi = mpmath.mpf(3) / 200
        hi = distribution(100, p_hi, space=space, dps=60)
        ex = distribution(100, as_fraction(p_hi), space=space)  # its exact binary value
        pf = Fraction(float(p))
        ex_f = distribution(100, pf, space=space)
        for k in (1, 2, 17, 40, 100):
            with mpmath.workdps(40):
                assert abs(lo.pmf(k) - mpmath.mpf(ex_f.pmf(k).numerator) / ex_f.pmf(k).denominator
                           ) <= mpmath.mpf(10) ** -28 * abs(lo.pmf(k))
        with mpmath.workdps(80):
            exact_mean = mpmath.mpf(ex.mean().numerator) / ex.mean().denominator
            assert abs(hi.mean() - exact_mean) < mpmath.mpf(10) ** -57 * exact_mean
            exact_var = mpmath.mpf(ex.var().numerator) / ex.var().denominator
            assert abs(hi.var() - exact_var) < mpmath.mpf(10) ** -55 * exact_var
        with mpmath.workdps(30):
            assert mpmath.almosteq(lo.logpmf(3), mpmath.log(lo.pmf(3)), 1e-25)


def test_small_p_puts_all_mass_on_one():
    for space in ("eq41", "eq41-printed", "excess<=6", "excess<=3;distinct"):
        prev = Fraction(0)
        for j in (3, 6, 12, 24):
            v = distribution(50, Fraction(1, 10**j), space=space).pmf(1)
            assert prev < v < 1
            prev = v
        assert 1 - prev < Fraction(1, 10**20)
        assert modes(50, Fraction(1, 10**6), space=space) == (1,)


def test_class_decomposition_adds_up():
    for space in ("eq41", "excess<=4"):
        cd = class_decomposition(12, Fraction(1, 9), space=space)
        d = cd.distribution
        for k in range(1, d.N + 1):
            assert sum(cd.joint[s][k - 1] for s in cd.shapes) == d.pmf(k)
        assert sum(cd.totals.values()) == 1
        assert sum(cd.by_excess.values()) == 1
        cf = class_decomposition(12, 1 / 9, space=space, dps=30)
        ce = class_decomposition(12, Fraction(1 / 9), space=space)  # the float's exact value
        for s in cd.shapes:
            t = ce.totals[s]
            with mpmath.workdps(40):
                assert mpmath.almosteq(cf.totals[s], mpmath.mpf(t.numerator) / t.denominator,
                                       1e-25)


def test_large_n_runs():
    d = distribution(10**4, 0.001, space="excess<=3", dps=20)
    assert 1 <= d.mean() <= 10**4
    m = modes(10**4, 0.001, space="excess<=3")
    lw = [d.logpmf(k) for k in range(m[0] - 2, m[0] + 3)]
    assert max(lw) == lw[2]
    e = distribution(3000, Fraction(1, 300), space="eq41")
    assert abs(float(e.mean()) - float(distribution(3000, 1 / 300, space="eq41", dps=20).mean())
               ) < 1e-3


def test_space_parsing_errors():
    with pytest.raises(ValueError):
        parse_space("eq42")
    with pytest.raises(ValueError):
        parse_space("eq41;heavy")
    with pytest.raises(ValueError):
        parse_space("eq41;distinct", "length")
    assert parse_space("excess <= 3").name == "excess<=3"
    assert parse_space("simple;distinct").base == "simple"
