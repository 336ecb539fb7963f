"""Circuit weights with per-site probabilities (issue 30): the symmetric-polynomial formulas against
brute-force enumeration of every circuit, and the certified ball tables against exact ones."""

from __future__ import annotations

import itertools
import math
import random
from fractions import Fraction

import pytest
from flint import arb

from symhx.certify import arb_prec, to_arb
from symhx.site_weights import (
    BALL_TABLE_N_LIMIT,
    EXACT_TABLE_BITS_LIMIT,
    SIMPLE,
    SITE_PATTERN_LIMIT,
    ball_weights,
    binomial_product_balls,
    distributions,
    elementary_ball,
    elementary_exact,
    exact_weights,
    pattern_terms,
    pattern_work,
    short_sum_split,
)
from symhx.sites import SiteClasses
from symhx.spaces import SpaceDistribution, parse_space
from tests.harness.errors import assert_refuses
from tests.reference.combinatorics import necklaces
from tests.reference.distribution import phi_exact
from tests.reference.sites import brute_weights, elementary, expand, mode_weights

SPACES = ["simple", "eq41", "eq41-printed", "excess<=1", "excess<=2", "excess<=3",
          "simple;distinct", "eq41;distinct", "eq41-printed;distinct", "excess<=2;distinct"]


def _random_sites(rng: random.Random, N: int) -> tuple[Fraction, ...]:
    vals: set[Fraction] = set()
    while len(vals) < N:
        vals.add(Fraction(rng.randint(1, 30), rng.randint(1, 40)))
    return tuple(vals)


@pytest.mark.parametrize("N", [2, 3, 4, 5])
@pytest.mark.parametrize("space", SPACES)
def test_weights_equal_brute_force_enumeration_with_distinct_site_probabilities(N, space):
    rng = random.Random(1000 * N + len(space))
    probs = _random_sites(rng, N)
    nums, den = exact_weights(SiteClasses.from_sites(list(probs)), parse_space(space))
    ref = brute_weights(probs, space)
    assert ref and {k: Fraction(nums[k - 1], den) for k in ref} == ref


@pytest.mark.slow
@pytest.mark.parametrize("space", ["simple", "eq41", "eq41-printed;distinct", "excess<=3"])
def test_weights_equal_brute_force_on_six_sites(space):
    probs = _random_sites(random.Random(6), 6)
    nums, den = exact_weights(SiteClasses.from_sites(list(probs)), parse_space(space))
    ref = brute_weights(probs, space)
    assert {k: Fraction(nums[k - 1], den) for k in ref} == ref


@pytest.mark.parametrize("sizes, probs", [((2, 3), ("1/3", "2/7")), ((1, 2, 2), ("1/2", 3, "1/5")),
                                          ((3, 1), ("2", "1/9"))])
@pytest.mark.parametrize("space", SPACES)
def test_weights_of_classes_equal_brute_force(sizes, probs, space):
    sc = SiteClasses(sizes, probs)
    nums, den = exact_weights(sc, parse_space(space))
    ref = brute_weights(expand(sizes, sc.values), space)
    assert {k: Fraction(nums[k - 1], den) for k in ref} == ref


def test_simple_weights_are_k_minus_1_factorial_e_k_on_larger_classes():
    sizes, probs = (4, 7, 3), (Fraction(1, 3), Fraction(2, 5), Fraction(7, 2))
    nums, den = exact_weights(SiteClasses(sizes, probs))
    assert [Fraction(x, den) for x in nums] == mode_weights(sizes, probs)
    sites = expand(sizes, probs)
    assert Fraction(nums[3], den) == 6 * elementary(sites, 4)


@pytest.mark.parametrize("space", ["simple", "eq41", "eq41-printed", "excess<=4",
                                   "excess<=2;distinct"])
def test_one_class_reproduces_the_scalar_weights(space):
    N, p = 9, Fraction(2, 7)
    nums, den = exact_weights(SiteClasses((N,), (p,)), parse_space(space))
    if space == "simple":
        ref = [phi_exact(N, p, k) for k in range(1, N + 1)]
    else:
        d = SpaceDistribution(N, p, parse_space(space))
        ref = [d.weight_exact(k) for k in range(1, N + 1)]
    assert [Fraction(x, den) for x in nums] == ref


def test_rank_one_edge_weights_are_site_weights():
    """p_ij = a_i b_j weighs a closed walk like the site weights a_v b_v (each visit enters and
    leaves its vertex once)."""
    rng = random.Random(3)
    a = [Fraction(rng.randint(1, 9), rng.randint(1, 9)) for _ in range(4)]
    b = [Fraction(rng.randint(1, 9), rng.randint(1, 9)) for _ in range(4)]
    for L in range(1, 6):
        for word in necklaces(4, L):
            edges = math.prod((a[word[t]] * b[word[(t + 1) % L]] for t in range(L)),
                              start=Fraction(1))
            sites = math.prod((a[v] * b[v] for v in word), start=Fraction(1))
            assert edges == sites


def test_distributions_of_a_shape_among_classes():
    got = sorted(distributions((3, 2, 2), 2))
    brute = set()
    for assign in itertools.product(range(2), repeat=3):
        parts: list[list[int]] = [[], []]
        for part, cls in zip((3, 2, 2), assign, strict=True):
            parts[cls].append(part)
        brute.add(tuple(tuple(sorted(p, reverse=True)) for p in parts))
    assert got == sorted(brute)
    assert pattern_terms(SIMPLE, 3) == {0: {((0, 0, 0), (0, 0, 0)): Fraction(1)}}


@pytest.mark.parametrize("parts", [
    [(3, Fraction(1, 2)), (2, Fraction(1, 3))],
    [(40, Fraction(1, 10**8)), (25, Fraction(10**8))],       # scales 1e-8 .. 1e8
    [(30, Fraction(3, 7)), (20, Fraction(1, 1000)), (10, Fraction(5))],
    [(1, Fraction(2)), (60, Fraction(1, 3))],
    [(57, Fraction(2, 9))],
])
@pytest.mark.parametrize("prec", [60, 200])
def test_binomial_product_balls_contain_the_exact_coefficients(parts, prec):
    exact = [elementary_exact(parts, t) for t in range(sum(m for m, _ in parts) + 1)]
    balls = binomial_product_balls(parts, prec)
    assert len(balls) == len(exact)
    with arb_prec(2 * prec + 64):
        for t, (x, e) in enumerate(zip(balls, exact, strict=True)):
            assert x.contains(to_arb(e)), t
            assert x.rel_accuracy_bits() >= prec, (t, x.rel_accuracy_bits())
    t = len(exact) // 3
    one = elementary_ball(parts, t, prec)
    with arb_prec(2 * prec + 64):
        assert one.contains(to_arb(exact[t])) and one.rel_accuracy_bits() >= prec


@pytest.mark.parametrize(("sizes", "probs", "prec"), [
    ((3, 2), (Fraction(1), Fraction(1, 10**400)), 80),  # log(q x) < -700: logistic underflows
    ((5, 5), (Fraction(1), Fraction(1, 10**6)), 80),    # a tilt placed past e_1 skips e_0
    ((6, 6), (Fraction(1), Fraction(1, 10**6)), 110),
])
def test_binomial_product_balls_hold_every_coefficient_of_widely_spread_classes(sizes, probs,
                                                                               prec):
    """One ball per ``t = 0..M``, each holding ``e_t`` summed over all ``t``-subsets."""
    parts = list(zip(sizes, probs, strict=True))
    each = expand(sizes, probs)
    balls = binomial_product_balls(parts, prec)
    assert len(balls) == sum(sizes) + 1
    with arb_prec(2 * prec + 64):
        for t, x in enumerate(balls):
            assert x.contains(to_arb(elementary(each, t))), t
            assert x.rel_accuracy_bits() >= prec, t


def test_the_simple_pattern_space_counts_only_simple_circuits():
    """The duck-typed :data:`SIMPLE` gives the ratios of the simple space of
    :mod:`symhx.spaces`: 1 for simple circuits of any length, 0 for every other class."""
    simple = parse_space("simple")
    for shape in [(), (2,), (3,), (2, 2), (2, 3)]:
        for k in range(1, 7):
            assert SIMPLE.ratio(shape, k) == simple.ratio(shape, k), (shape, k)
    assert SIMPLE.ratio((), 3) == 1 and SIMPLE.ratio((2,), 3) == 0


@pytest.mark.parametrize("space", ["simple", "eq41", "excess<=2;distinct"])
def test_ball_tables_contain_the_exact_weights(space):
    sc = SiteClasses((5, 30, 12), ("0.3", "1/70", 4))
    nums, den = exact_weights(sc, parse_space(space))
    balls = ball_weights(sc, parse_space(space), prec=80)
    with arb_prec(300):
        for k, (x, n) in enumerate(zip(balls, nums, strict=True), 1):
            assert x.contains(to_arb(Fraction(n, den))), k
            assert x.rel_accuracy_bits() >= 80, k


def test_ball_tables_keep_relative_accuracy_far_in_the_tails():
    """Coefficients spanning thousands of orders of magnitude keep their own digits."""
    sc = SiteClasses((700, 800), (Fraction(1, 10**6), 30))
    balls = ball_weights(sc, prec=64)
    with arb_prec(128):
        logs = [float(x.log().mid()) for x in balls]
        assert max(logs) - min(logs) > 2000  # the weights span over 800 orders of magnitude
        assert all(x.rel_accuracy_bits() >= 64 for x in balls)
    # spot checks against exact values at both ends and the middle
    q1, q2 = Fraction(1, 10**6), Fraction(30)
    for k in (1, 2, 750, 1499, 1500):  # e_k = sum_j C(700, j) C(800, k - j) q1**j q2**(k-j)
        e_k = sum((math.comb(700, j) * math.comb(800, k - j) * q1**j * q2 ** (k - j)
                   for j in range(max(0, k - 800), min(700, k) + 1)), Fraction(0))
        exact = math.factorial(k - 1) * e_k
        with arb_prec(256):
            assert balls[k - 1].contains(to_arb(exact)), k


def test_short_sum_split_finds_one_large_class():
    assert short_sum_split(SiteClasses((2, 99), (1, 2))) == ((99, Fraction(2)), [(2, Fraction(1))])
    assert short_sum_split(SiteClasses((500, 600), (1, 2))) is None


def test_work_limits_are_checked_before_any_work():
    big = SiteClasses((5000, 5000), ("1/3", "1/7"))
    assert_refuses(exact_weights, big, arg="N", value="N=10000",
                   allowed=["EXACT_TABLE_BITS_LIMIT", f"{EXACT_TABLE_BITS_LIMIT:.2g}"])
    huge = SiteClasses((BALL_TABLE_N_LIMIT, 1), (0.5, 0.25))
    assert_refuses(ball_weights, huge, arg="N", value=f"N={BALL_TABLE_N_LIMIT + 1}",
                   allowed=["BALL_TABLE_N_LIMIT", str(BALL_TABLE_N_LIMIT)])


def test_pattern_work_limit_is_checked_before_enumerating():
    sc = SiteClasses((5, 5, 5), (1, 2, 3))
    assert pattern_work(parse_space("excess<=25"), 3) > SITE_PATTERN_LIMIT
    assert_refuses(exact_weights, sc, parse_space("excess<=25"), arg="space",
                   value="'excess<=25'", allowed="SITE_PATTERN_LIMIT")
    assert pattern_work(parse_space("eq41"), 3) == 1 + 3 + 3 + 6 + 3


def test_ball_balls_are_arb():
    assert isinstance(ball_weights(SiteClasses((1, 1), (1, 2)))[0], arb)
