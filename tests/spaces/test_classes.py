"""Sample spaces of circuits and their exact class counts (``symhx.spaces._classes``, section 8,
eqs. 28-41): class counts and ratios, the paper's printed formulas inside and outside their
stated ranges, the classes of a space, its integer tables ``U_e(k)`` and ``Q*``, parsing, and
the refusals and work limit ``MAX_EXCESS``.

References (:mod:`tests.reference.spaces`, :mod:`tests.reference.combinatorics`): explicit
circuits classified by class (every word up to rotation for small N, FKM enumeration up to
``N**L`` of a few million), the count by choosing the vertices and counting the necklaces of a
content by enumeration, MacMahon's necklace count, partition counts by the coin-change
recurrence, the closed form of ``R_s(k)`` from the module docstring.
"""

from __future__ import annotations

import math
from collections import Counter
from fractions import Fraction

import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from symhx.circuits import necklace_count, partitions
from symhx.spaces import (
    EQ41_SHAPES,
    MAX_EXCESS,
    Space,
    class_count,
    class_ratio,
    eq41_terms,
    paper_label,
    parse_space,
    printed_count,
    shape_excess,
    shapes_up_to,
)
from symhx.spaces._classes import check_shape, visits_of
from tests.harness.errors import assert_refuses
from tests.reference.combinatorics import necklace_formula, pattern_count_by_choice
from tests.reference.spaces import (
    class_counts_by_walks,
    classes_by_fkm,
    partition_counts,
    qstar,
    walk_polys,
)

BOUNDARY_N = [2, 3, 5, 10, 100, 10**3, 10**8, 10**20]
SHAPES = [(), (2,), (3,), (2, 2), (4,), (3, 2), (2, 2, 2), (5,), (3, 3), (4, 2)]
INT_WORDS = "an integer such as 7, 10**100 or '1e100'"


def _circuits(N: int, k: int) -> Fraction:
    """The simple count phi_N(k) = N!/(k (N-k)!) (eq. 5), as a falling product (any N)."""
    return Fraction(math.prod(range(N - k + 1, N + 1)), k)


@pytest.fixture(scope="module")
def fkm() -> dict[tuple[int, int], Counter]:
    """{(N, L): Counter of (class, k)} by FKM enumeration, N <= 7, L <= N + 3 (capped to keep
    N**L small)."""
    return {(N, L): classes_by_fkm(N, L) for N in range(1, 8) for L in range(1, N + 4)
            if N**L <= 2_500_000}


# --------------------------------------------------------------------------- class counts
def test_every_class_count_matches_enumeration(fkm):
    checked = 0
    for (N, L), c in fkm.items():
        for v in partitions(L, max_parts=N):
            s = tuple(x for x in v if x > 1)
            k = len(v)
            assert class_count(N, s, k) == c.get((s, k), 0), (N, L, v)
            checked += 1
        assert sum(c.values()) == necklace_count(N, L)
    assert checked > 200


@pytest.mark.parametrize(("N", "max_len"), [(1, 6), (2, 7), (3, 7), (4, 6), (5, 6)])
def test_class_count_matches_explicit_circuits(N, max_len):
    brute = class_counts_by_walks(N, max_len)
    for s in SHAPES:
        for k in range(0, N + 2):
            if k + shape_excess(s) > max_len:
                continue
            assert class_count(N, s, k) == brute.get((s, k), 0), (s, k)
            if 1 <= k <= N:
                assert class_ratio(s, k) == brute.get((s, k), 0) / _circuits(N, k), (s, k)


def test_totals_per_length_are_necklace_counts():
    """Summed over every pattern of length L: MacMahon's (1/L) sum_{d|L} phi(d) N**(L/d)."""
    for N in range(1, 9):
        for L in range(1, N + 6):
            total = 0
            for v in partitions(L, max_parts=N):
                s = tuple(x for x in v if x > 1)
                total += class_count(N, s, len(v))
            assert total == necklace_formula(N, L)


@settings(max_examples=40, deadline=None)
@given(N=st.sampled_from(BOUNDARY_N), s=st.sampled_from(SHAPES), k=st.integers(0, 9))
def test_class_count_by_choosing_vertices(N, s, k):
    if k + shape_excess(s) > 8:  # explicit necklaces with this content: at most 8! words
        k = max(0, 8 - shape_excess(s))
    want = 0 if k < max(len(s), 1) or k > N else pattern_count_by_choice(
        N, tuple(sorted(s + (1,) * (k - len(s)), reverse=True)))
    assert class_count(N, s, k) == want
    if 1 <= k <= N:
        assert class_ratio(s, k) * _circuits(N, k) == want


@pytest.mark.parametrize("k", range(1, 12))
def test_polynomial_ratio_closed_form(k):
    """k > r: R_s(k) = (k+e-1)!/(k-1)! * k!/(k-r)! / (prod_j c_j! prod_i s_i!) (module doc)."""
    for s in SHAPES:
        r, e = len(s), shape_excess(s)
        if k <= r:
            continue
        C = math.prod(math.factorial(c) for c in Counter(s).values())
        S = math.prod(math.factorial(x) for x in s)
        want = Fraction(math.factorial(k + e - 1) // math.factorial(k - 1)
                        * (math.factorial(k) // math.factorial(k - r)), C * S)
        assert class_ratio(s, k) == want, (s, k)


def test_boundary_values_explicit():
    """k = r: every vertex repeated; values from explicit circuits on N = r vertices."""
    for s in [(2,), (3,), (4,), (2, 2), (3, 2), (2, 2, 2)]:
        r = len(s)
        brute = class_counts_by_walks(r, sum(s))
        assert class_count(r, s, r) == brute[(s, r)], s
    assert class_ratio((2,), 0) == 0 and class_ratio((2, 2), 1) == 0
    assert class_ratio((), 0) == 0 and class_ratio((), 1) == 1


def test_periodic_boundary_classes():
    """The boundary lengths (every vertex repeated), enumerated: the printed formulas evaluated
    there give words / L instead of the number of circuits."""
    for N in range(2, 7):
        c3, c4 = classes_by_fkm(N, 3), classes_by_fkm(N, 4)
        assert class_count(N, (3,), 1) == c3[((3,), 1)] == N
        assert class_count(N, (4,), 1) == c4[((4,), 1)] == N
        assert class_count(N, (2, 2), 2) == c4[((2, 2), 2)] == N * (N - 1)
        assert printed_count("38", N, 3, outside="formula") == Fraction(N, 3)
        assert printed_count("39", N, 4, outside="formula") == Fraction(N, 4)
        assert printed_count("40", N, 4, outside="formula") == Fraction(3 * N * (N - 1), 4)
        assert printed_count("35", N, 2, outside="formula") == Fraction(N, 2)
        assert printed_count("36", N, 2) == N == class_count(N, (2,), 1)


# --------------------------------------------------------------------------- printed formulas
PRINTED = (("35", (2,), 3), ("38", (3,), 4), ("39", (4,), 5), ("40", (2, 2), 5))


def test_printed_formulas_inside_their_ranges_are_right(fkm):
    """Inside its stated range (L >= lo) each printed formula equals the enumerated count
    (FKM: N <= 7, L <= N + 3; explicit walks: N = 3, 4, 5, 7, L <= 7 or 6), below it
    ``printed_count`` gives 0; eq. (36) is N at L = 2 only."""
    for (N, L), c in fkm.items():
        for eq, shape, lo in PRINTED:
            if L >= lo:
                assert printed_count(eq, N, L) == c.get((shape, L - shape_excess(shape)), 0), (
                    eq, N, L)
    for N in (3, 4, 5, 7):
        brute = class_counts_by_walks(N, 7 if N <= 4 else 6)
        for L in range(1, 8 if N <= 4 else 7):
            for eq, s, lo in PRINTED:
                k = L - shape_excess(s)
                got = printed_count(eq, N, L)
                if L >= lo:
                    assert got == brute.get((s, k), 0), (eq, N, L)
                else:
                    assert got == 0, (eq, N, L)
            assert printed_count("36", N, L) == (N if L == 2 else 0)


def test_printed_formulas_outside_their_ranges():
    N = 10
    assert printed_count("38", N, 3, outside="formula") == Fraction(N, 3)
    assert printed_count("39", N, 4, outside="formula") == Fraction(N, 4)
    assert printed_count("40", N, 4, outside="formula") == Fraction(3 * N * (N - 1), 4)
    assert printed_count("35", N, 2, outside="formula") == Fraction(N, 2)
    assert printed_count("38", N, 2, outside="formula") == 0  # shorter than the class
    assert_refuses(printed_count, "37", N, 4, arg="eq", value="'37'",
                   allowed="35, 36, 38, 39, 40")
    assert_refuses(printed_count, "38", N, 5, outside="x", arg="outside", value="'x'",
                   allowed="'zero' or 'formula'")


@pytest.mark.parametrize("N", [5, 10, 1000])
def test_printed_class_counts(N):
    for s in EQ41_SHAPES:
        for k in range(1, 8):
            true = class_count(N, s, k)
            printed = class_count(N, s, k, printed=True)
            if k > len(s):
                assert printed == true
            elif s == (2,) and k == 1:
                assert printed == true == N  # eq. (36)
            elif s == ():
                assert printed == true
            else:
                assert printed == 0


def test_eq41_terms_explicit():
    N = 4
    brute = class_counts_by_walks(N, 7)
    for k in range(1, 5):
        terms = eq41_terms(N, k)
        want = {paper_label(s): brute.get((s, k), 0) for s in EQ41_SHAPES}
        if k + 3 <= 7:
            assert terms == want
    assert list(eq41_terms(10, 3)) == ["phi", "phi^1", "phi^{1,0}", "phi^2", "phi^{1,0,0}"]


def test_eq41_terms_sum_and_printed_difference():
    """The printed terms miss exactly phi^{1,0}(3) = N and phi^{1,0,0}(4) = N at k = 1 and
    phi^2(4) = N (N - 1) at k = 2."""
    for N in range(2, 9):
        for k in range(1, N + 1):
            good = eq41_terms(N, k)
            bad = eq41_terms(N, k, printed=True)
            diff = {lab: good[lab] - bad[lab] for lab in good}
            expect = {"phi": 0, "phi^1": 0, "phi^{1,0}": N if k == 1 else 0,
                      "phi^2": N * (N - 1) if k == 2 else 0,
                      "phi^{1,0,0}": N if k == 1 else 0}
            assert diff == expect


# --------------------------------------------------------------------------- shapes
def test_shapes_up_to_counts_partitions():
    cumulative = [1, 2, 4, 7, 12, 19, 30, 45, 67]
    for m, want in enumerate(cumulative):
        shapes = shapes_up_to(m)
        assert len(shapes) == len(set(shapes)) == want
        assert all(list(s) == sorted(s, reverse=True) and min(s, default=2) >= 2
                   for s in shapes)
        assert all(shape_excess(s) <= m for s in shapes)
    assert_refuses(shapes_up_to, -1, arg="maximum excess m", value="-1", allowed=">= 0")


def test_max_excess_is_an_inclusive_limit():
    shapes = shapes_up_to(MAX_EXCESS)
    assert len(shapes) == sum(partition_counts(MAX_EXCESS)) == 9296
    assert_refuses(shapes_up_to, MAX_EXCESS + 1, arg="maximum excess m",
                   value=f"m={MAX_EXCESS + 1}",
                   allowed=[f"documented work limit {MAX_EXCESS}", "MAX_EXCESS"])


def test_paper_labels():
    assert paper_label(()) == "phi"
    assert paper_label((2,)) == "phi^1"
    assert paper_label((2, 2, 2)) == "phi^3"
    assert paper_label((3,)) == "phi^{1,0}"
    assert paper_label((3, 2)) == "phi^{1,1}"
    assert paper_label((4, 2, 2)) == "phi^{1,0,2}"
    assert_refuses(paper_label, (2, 1), arg="class", value="(2, 1)",
                   allowed="the parts > 1 of a visit pattern")


def test_visits_of():
    assert visits_of((3, 2), 4) == (3, 2, 1, 1)
    assert visits_of((), 2) == (1, 1)
    assert visits_of((), 0) == ()
    assert_refuses(visits_of, (2, 2), 1, arg="class", value="(2, 2)",
                   allowed="at least 2 distinct vertices")


# --------------------------------------------------------------------------- refusals
@pytest.mark.parametrize("shape, shown", [("ab", "str 'ab'"), (5, "int 5"), (b"x", "bytes b'x'")])
def test_check_shape_refuses_non_sequences(shape, shown):
    assert_refuses(check_shape, shape, exc=TypeError, arg="shape", value=f"got {shown}",
                   allowed="a tuple of ints >= 2")


def test_check_shape_names_a_bad_entry():
    assert_refuses(check_shape, [2, "x"], arg="shape entry", value="'x'", allowed=INT_WORDS)


@pytest.mark.parametrize("fn", [lambda k: class_count(5, (2,), k), lambda k: class_ratio((2,), k)])
def test_k_is_named(fn):
    assert_refuses(fn, "a", arg="k", value="'a'", allowed=INT_WORDS)


def test_printed_count_names_L():
    assert_refuses(printed_count, "35", 5, "x", arg="L", value="'x'", allowed=INT_WORDS)


@pytest.mark.parametrize("N", [0, -3])
def test_N_at_least_one(N):
    for call in (lambda: class_count(N, (2,), 2), lambda: printed_count("35", N, 3)):
        assert_refuses(call, arg="N", value=f"got {N}", allowed=">= 1")


# --------------------------------------------------------------------------- spaces
@pytest.mark.parametrize("name", ["simple", "eq41", "excess<=2", "excess<=3;distinct",
                                  "eq41;distinct", "eq41-printed"])
def test_space_Q_against_explicit_circuits(name):
    """Q*(k), its integer form Qnum/Qden and the table U_e(k) against circuits listed one by
    one (N = 4, length <= 7; the printed space drops its boundary terms)."""
    space = parse_space(name)
    N = 4
    polys = walk_polys(N, name)  # walks of length <= N + max excess <= 7
    p = Fraction(2, 7)
    for k in range(1, N + 1):
        want = qstar(N, p, k, polys[k])
        assert space.Qstar(k, p) == want, k
        a, b = p.numerator, p.denominator
        assert Fraction(space.Qnum(k, a, b), space.Qden(b)) == want
        U = space.U(k)
        assert len(U) == space.max_excess + 1
        assert sum(Fraction(u, space.denominator) * (p**e if space.weighting == "length" else 1)
                   for e, u in enumerate(U)) == want


@pytest.mark.parametrize("name", ["eq41", "excess<=4", "eq41-printed;distinct"])
def test_space_polynomial_region(name):
    """k > max_parts: Q*(k) from the class counts at a large N (Q* does not depend on N)."""
    space = parse_space(name)
    N = 10**6
    p = Fraction(3, 100)
    for k in range(1, 14):
        w = sum((p ** shape_excess(s) if space.weighting == "length" else 1)
                * class_count(N, s, k, printed=space.printed) for s in space.shapes)
        assert space.Qstar(k, p) == w / _circuits(N, k), k
        assert space.Qstar(k, p) == space.Qstar(k, p)  # cached value equal
        for e, u in enumerate(space.U(k)):
            assert u == space.denominator * sum(class_ratio(s, k, printed=space.printed)
                                                for s in space.shapes if shape_excess(s) == e)


def test_space_denominator_makes_integers():
    for name in ("eq41", "excess<=5", "eq41-printed"):
        sp = parse_space(name)
        D = sp.denominator
        for s in sp.shapes:
            for k in range(1, 10):
                assert (class_ratio(s, k, printed=sp.printed) * D).denominator == 1


def test_space_ratio_count_and_properties():
    sp = parse_space("eq41")
    assert sp.levels == (0, 1, 2, 3)
    assert sp.max_parts == 2
    assert parse_space("simple").max_parts == 0
    assert sp.ratio((3, 2), 5) == 0 and sp.count(10, (3, 2), 5) == 0
    assert sp.ratio((2,), 3) == class_ratio((2,), 3)
    assert sp.count(10, (2, 2), 4) == class_count(10, (2, 2), 4) == 37800
    pr = parse_space("eq41-printed")
    assert pr.count(100, (3,), 1) == 0 and pr.ratio((2, 2), 2) == 0
    assert pr.printed and not sp.printed
    assert parse_space("eq41;distinct").Qstar(3, Fraction(1, 2)) == \
        parse_space("eq41;distinct").Qstar(3, Fraction(1, 5))


def test_parse_space_names_and_errors():
    assert parse_space("excess <= 2").name == "excess<=2"
    assert parse_space("excess <= 3").name == "excess<=3"
    assert parse_space("excess<=2").shapes == shapes_up_to(2)
    assert parse_space("excess<=0").shapes == ((),)
    assert parse_space("eq41;distinct").weighting == "distinct"
    assert parse_space("eq41; weight=distinct").name == "eq41;distinct"
    assert parse_space("eq41;length").name == "eq41"
    assert parse_space("eq41", "distinct").name == "eq41;distinct"
    assert parse_space("simple").weighting == "length" and parse_space("simple").max_excess == 0
    assert parse_space("simple;distinct").base == "simple"
    sp = parse_space("excess<=2")
    assert parse_space(sp) is sp
    assert parse_space(sp, "length") is sp
    assert parse_space(sp, "distinct").name == "excess<=2;distinct"
    assert parse_space(parse_space("eq41"), "distinct").name == "eq41;distinct"
    for bad in ("abc", "eq42"):
        assert_refuses(parse_space, bad, arg="space", value=repr(bad),
                       allowed=["'simple'", "'eq41'", "'eq41-printed'", "'excess<=m'"])
    for bad in ("x", "heavy"):
        assert_refuses(parse_space, f"eq41;{bad}", arg="weighting", value=f"'{bad}'",
                       allowed=["';length'", "';distinct'"])
    assert_refuses(parse_space, "eq41", "w", arg="weighting", value="'w'",
                   allowed="'length' or 'distinct'")
    assert_refuses(parse_space, "eq41;distinct", "length", arg="weighting",
                   value="'eq41;distinct'", allowed="weighting='length'")
    assert_refuses(parse_space, 3, exc=TypeError, arg="space", value="int", allowed="a str")


def test_fresh_space_tables():
    """A Space built directly (not the cached one from parse_space) fills its own tables, in the
    boundary region (k <= max_parts) and the polynomial one, and a cache hit returns the same."""
    p = Fraction(1, 3)
    for m, weighting in ((2, "length"), (3, "length"), (3, "distinct"), (4, "length")):
        shapes = shapes_up_to(m)
        sp = Space(f"excess<={m}", "excess", m, weighting, shapes)
        assert sp._cache == {}
        for k in (1, 2, 3, 5, 9, 2, 1):
            ratios = [sum(class_ratio(s, k) for s in shapes if shape_excess(s) == e)
                      for e in range(m + 1)]
            assert sp.U(k) == tuple(r * sp.denominator for r in ratios), (m, k)
            w = [p**e if weighting == "length" else 1 for e in range(m + 1)]
            assert sp.Qstar(k, p) == sum(wi * r for wi, r in zip(w, ratios, strict=True))
    sp = parse_space("excess<=2")
    assert parse_space(sp, "distinct").weighting == "distinct"
    assert parse_space(sp, "distinct").Qstar(3, p) == sum(class_ratio(s, 3)
                                                          for s in shapes_up_to(2))


def test_fresh_printed_space_boundary():
    """eq41-printed built directly: at k <= max_parts the printed boundary values are used."""
    sp = Space("eq41-printed", "eq41-printed", 3, "length", EQ41_SHAPES, printed=True)
    for k in (1, 2, 3, 6):
        ratios = [sum(class_ratio(s, k, printed=True) for s in EQ41_SHAPES
                      if shape_excess(s) == e) for e in range(4)]
        assert sp.U(k) == tuple(r * sp.denominator for r in ratios), k
    # the printed boundary differs from the true one: phi^{1,0}(3) = N is missing at k = 1
    assert sp.U(1) != parse_space("eq41").U(1)
