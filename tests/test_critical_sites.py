"""The critical point along a direction of site probabilities and the critical curve of two
classes (issue 30): exact references at small N, the table against the perturbative certificate
at moderate N, independent mpmath evaluations at huge N."""

from __future__ import annotations

import dataclasses
import math
import random
from fractions import Fraction

import mpmath
import pytest
from flint import arb

from symhx.critical import critical_point
from symhx.critical_sites import (
    CriticalCurve,
    DirectionCriticalPoint,
    _perturbative,
    _perturbative_argmin,
    _Perturbed,
    _table,
    critical_curve,
    direction_critical_point,
)
from symhx.site_weights import BALL_TABLE_N_LIMIT
from symhx.sites import SiteClasses
from symhx.validation import mpf_to_fraction
from tests.harness.errors import assert_refuses
from tests.reference.sites import direction_argmins, direction_c, expand, mode_weights


def _modes_at(sizes, w, t) -> tuple[int, ...]:
    """Exact modes of X at p_v = t w_v from the class convolution (reference)."""
    W = mode_weights(tuple(sizes), tuple(t * x for x in w))
    top = max(W)
    return tuple(k for k, x in enumerate(W, 1) if x == top)


def _random_direction(rng):
    N = rng.randint(3, 11)
    c = rng.randint(2, min(3, N - 1))
    cuts = sorted(rng.sample(range(1, N), c - 1))
    sizes = tuple(b - a for a, b in zip([0, *cuts], [*cuts, N], strict=True))
    w = tuple(Fraction(rng.randint(1, 30), rng.randint(1, 30)) for _ in sizes)
    return sizes, w


@pytest.mark.parametrize("seed", range(12))
def test_table_argmins_and_enclosure_against_exact_reference(seed):
    rng = random.Random(seed)
    sizes, w = _random_direction(rng)
    N = sum(sizes)
    cp = direction_critical_point(N, SiteClasses(sizes, w), dps=30)
    sites = expand(sizes, w)
    assert cp.argmins == direction_argmins(sites)
    assert cp.k_after == max(cp.argmins) and cp.k_before == 1
    # the enclosure holds the exact crossing: W_t(k) <= W_t(1) for every k at t = lo, and
    # W_t(k_after) >= W_t(1) at t = hi (exact rationals: t**(k-1) c_k**(-(k-1)))
    lo, hi = (mpf_to_fraction(x) for x in cp.p_bounds)
    assert hi > lo and (hi - lo) / lo < Fraction(1, 10**29)
    assert all(lo ** (k - 1) <= direction_c(sites, k) for k in range(2, N + 1))
    assert hi ** (cp.k_after - 1) >= direction_c(sites, cp.k_after)
    # the modes on either side, exactly
    eps = Fraction(1, 10**31)
    assert _modes_at(sizes, w, lo * (1 - eps)) == (1,)
    assert _modes_at(sizes, w, hi * (1 + eps)) == (cp.k_after,)


@pytest.mark.parametrize("weights, argmins, exact", [
    ((1, 1, 1, 1, 1, 4), (2, 3), Fraction(3, 10)),
    ((1, 3, 4, 5, 6, 9), (2, 3), Fraction(1, 11)),
    ((1, 1, 2, 2), (2,), Fraction(6, 13)),
])
def test_exact_ties_and_rational_critical_points(weights, argmins, exact):
    cp = direction_critical_point(len(weights), list(weights), dps=25)
    assert cp.argmins == argmins and cp.k_after == argmins[-1] and cp.p_exact == exact
    assert cp.p_bounds[0] <= cp.p <= cp.p_bounds[1]
    w = tuple(Fraction(x) for x in weights)
    sc = SiteClasses.from_sites(list(w))
    sizes, probs = sc.sizes, sc.values
    assert _modes_at(sizes, probs, exact) == (1, *argmins)          # a tie at the point itself
    assert _modes_at(sizes, probs, exact * (1 + Fraction(1, 10**9))) == (argmins[-1],)


@pytest.mark.parametrize("N", [2, 3, 5, 101, 10**6, 10**30])
def test_one_class_is_the_scalar_critical_point(N):
    cp = direction_critical_point(N, SiteClasses((N,), (1,)), dps=40)
    ref = critical_point(N, dps=40)
    for f in dataclasses.fields(ref):
        if f.compare:
            assert getattr(cp, f.name) == getattr(ref, f.name), f.name
    assert isinstance(cp, DirectionCriticalPoint) and cp.method == "one class"
    assert cp.weights == SiteClasses((N,), (1,))


def test_one_class_with_a_weight_divides_the_scalar_point():
    N = 101
    ref = critical_point(N, dps=40)
    cp = direction_critical_point(N, SiteClasses((2, 99), ("3", 3)), dps=40)
    with mpmath.workdps(60):
        assert abs(cp.p * 3 - ref.p) <= ref.p * mpmath.mpf(10) ** -39
    lo, hi = (mpf_to_fraction(x) * 3 for x in cp.p_bounds)
    assert lo <= mpf_to_fraction(ref.p_bounds[0]) and hi >= mpf_to_fraction(ref.p_bounds[1])
    assert cp.q == ref.q and cp.k_after == ref.k_after
    five = direction_critical_point(5, [2] * 5, dps=20)
    assert five.p_exact == Fraction(1, 4) and five.argmins == (2, 3)


@pytest.mark.parametrize("N", [3000, 20_000])
@pytest.mark.parametrize("w", [("1/2", 1), (3, 1), (1, "7/5"), ("0.1", 1)])
def test_perturbative_certificate_agrees_with_the_table(N, w):
    sc = SiteClasses((2, N - 2), w)
    a, b = _perturbative(sc, 30), _table(sc, 30)
    assert a is not None and a.method == "perturbative" and b.method == "table"
    assert a.argmins == b.argmins
    with mpmath.workdps(50):
        assert abs(a.p - b.p) <= b.p * mpmath.mpf(10) ** -29
        assert abs(a.q - b.q) <= abs(b.q) * mpmath.mpf(10) ** -29


def test_the_perturbative_certificate_starts_at_its_documented_n():
    # PERTURBATIVE_MIN_N is inclusive: at it a one-large-class direction takes the certificate,
    # one below it the table; both give the same point
    from symhx.critical_sites import PERTURBATIVE_MIN_N

    at, below = (direction_critical_point(n, SiteClasses((2, n - 2), (3, 1)), dps=20)
                 for n in (PERTURBATIVE_MIN_N, PERTURBATIVE_MIN_N - 1))
    assert at.method == "perturbative" and below.method == "table"
    ref = _table(SiteClasses((2, PERTURBATIVE_MIN_N - 2), (3, 1)), 20)
    assert at.argmins == ref.argmins
    with mpmath.workdps(30):
        assert abs(at.p - ref.p) <= ref.p * mpmath.mpf(10) ** -19


def test_small_sites_far_from_a_perturbation_go_to_the_table():
    sc = SiteClasses((2, 4998), (100, 1))
    assert _perturbative(sc, 20) is None
    cp = direction_critical_point(5000, sc, dps=20)
    assert cp.method == "table"


def test_the_perturbative_certificate_needs_the_sign_right_after_its_argmin():
    """Hypothesis (ii) (``E_w > 0`` on ``[k* + 1, n/2)``) starts at ``k* + 1``: with ``E_n``
    doctored to -1 there alone (so ``E_w(k* + 1) < 0``: a made-up sign pattern, not a real
    direction) the certificate must not close, whatever the search found."""
    n, small = 2998, [(2, Fraction(3))]
    k = _perturbative_argmin(_Perturbed(n, small))
    assert k is not None

    class Doctored(_Perturbed):
        def E_n(self, j):
            return arb(-1) if j == k + 1 else super().E_n(j)

    assert _perturbative_argmin(Doctored(n, small)) is None


def _mp_log_c(N: int, sizes, w, k: int, dps: int):
    """log c_k from mpmath loggamma (independent of Arb): two classes, the first small."""
    (s, n), (ws, wb) = sizes, w
    with mpmath.workdps(dps):
        ws, wb = (mpmath.mpf(x.numerator) / x.denominator for x in (ws, wb))
        e1 = s * mpmath.mpf(ws) + n * mpmath.mpf(wb)
        terms = [mpmath.log(math.comb(s, j)) + j * mpmath.log(ws)
                 + mpmath.loggamma(n + 1) - mpmath.loggamma(k - j + 1)
                 - mpmath.loggamma(n - k + j + 1) + (k - j) * mpmath.log(wb)
                 for j in range(0, min(s, k) + 1)]
        top = max(terms)
        log_ek = top + mpmath.log(mpmath.fsum(mpmath.exp(t - top) for t in terms))
        return (mpmath.log(e1) - mpmath.loggamma(k) - log_ek) / (k - 1)


@pytest.mark.parametrize("N", [10**8, 10**30, 10**100])
@pytest.mark.parametrize("w", [(Fraction(1, 2), 1), (Fraction(3), 1)])
def test_huge_N_against_independent_mpmath_evaluation(N, w):
    sizes = (2, N - 2)
    cp = direction_critical_point(N, SiteClasses(sizes, w), dps=30)
    assert cp.method == "perturbative" and cp.sign_evaluations <= 40
    k = cp.k_after
    dig = 2 * 30 + 3 * len(str(N))  # loggamma(N) cancels ~2 log10(N) digits
    vals = {j: _mp_log_c(N, sizes, w, j, dig) for j in (k - 2, k - 1, k, k + 1, k + 2)}
    with mpmath.workdps(dig):
        assert all(vals[j] > vals[k] for j in vals if j != k)       # a strict local minimum
        t = mpmath.exp(vals[k])
        assert abs(cp.p - t) <= t * mpmath.mpf(10) ** -29
        assert cp.p_bounds[0] <= t <= cp.p_bounds[1]
        e1 = sum(n * mpmath.mpf(x.numerator) / x.denominator for n, x in zip(sizes, w,
                                                                              strict=True))
        assert abs(cp.q - (t * e1 - 1)) <= abs(cp.q) * mpmath.mpf(10) ** -28


def test_the_row_at_a_googol_costs_a_few_evaluations():
    N = 10**100
    cp = direction_critical_point(N, SiteClasses((2, N - 2), ("1/2", 1)), dps=50)
    assert cp.method == "perturbative" and cp.sign_evaluations <= 20
    assert cp.k_after == critical_point(N - 2).k_after  # walls at half weight do not move k*


def test_critical_curve_points_and_evaluation_anywhere():
    curve = critical_curve(101, (2, 99), directions=4, names=("wall", "pipe"), dps=20)
    assert isinstance(curve, CriticalCurve) and len(curve.points) == 4
    assert curve.directions == ((4, 1), (3, 2), (2, 3), (1, 4))
    assert curve.names == ("wall", "pipe")
    for cp, (w1, w2), a, b in zip(curve.points, curve.directions, curve.p1, curve.p2,
                                  strict=True):
        with mpmath.workdps(40):
            assert abs(a - cp.p * w1) <= a * mpmath.mpf(10) ** -19
            assert abs(b - cp.p * w2) <= b * mpmath.mpf(10) ** -19
        assert cp.weights.names == ("wall", "pipe")
    other = curve.at((1, "0.5"))
    ref = direction_critical_point(101, SiteClasses((2, 99), (1, Fraction(1, 2))), dps=20)
    assert other.p == ref.p and other.k_after == ref.k_after
    assert curve.at((2, 1)) is other  # cached by the ratio
    rows = curve.as_rows()
    assert [r["k_after"] for r in rows] == list(curve.k_after)
    huge = critical_curve(10**50, (2, 10**50 - 2), directions=[(1, 3), (3, 1)], dps=15)
    assert all(cp.method == "perturbative" for cp in huge.points)


def test_refusals():
    assert_refuses(direction_critical_point, 1, [1], arg="N", value="1", allowed=">= 2")
    assert_refuses(direction_critical_point, 3, [1, 2], arg="weights", value="sequence of 2",
                   allowed="one probability per site")
    assert_refuses(direction_critical_point, 3, SiteClasses((2,), (1,)), arg="weights",
                   value="N = 2", allowed="add up to N")
    assert_refuses(direction_critical_point, 3, [1, 0, 2], arg="weights[1]", value="0",
                   allowed="> 0")
    assert_refuses(direction_critical_point, 3, [1, 1, 2], dps=0, arg="dps", value="0",
                   allowed="between 1 and")
    N = 2 * BALL_TABLE_N_LIMIT
    assert_refuses(direction_critical_point, N, SiteClasses((N // 2, N // 2), (1, 2)),
                   arg="N", value=f"N={N}", allowed="BALL_TABLE_N_LIMIT")
    assert_refuses(critical_curve, 10, (3, 6), arg="sizes", value="(3, 6)", allowed="N = 10")
    assert_refuses(critical_curve, 10, (3, 6, 1), exc=TypeError, arg="sizes",
                   value="(3, 6, 1)", allowed="pair")
    assert_refuses(critical_curve, 10, (4, 6), directions=0, arg="directions", value="0",
                   allowed=">= 1")
    assert_refuses(critical_curve, 10, (4, 6), directions=[(1, -1)], arg="directions[0][1]",
                   value="-1", allowed="> 0")
    assert_refuses(critical_curve, 10, (4, 6), directions=[3], exc=TypeError,
                   arg="directions[0]", value="3", allowed="pair")
    assert_refuses(critical_curve, 10, (4, 6), directions=[], arg="directions", value="empty",
                   allowed="at least one")


def test_as_dict_of_a_direction_without_p_d_holds_the_bounds_of_p_c():
    cp = direction_critical_point(30, SiteClasses((10, 20), (1, 3)), dps=30)
    assert cp.p_d is None
    d = cp.as_dict()
    assert d["p_c_lo"] == cp.p_bounds[0] and d["p_c_hi"] == cp.p_bounds[1]
    assert d["p_c_lo"] <= d["p_c"] <= d["p_c_hi"] and d["sizes"] == [10, 20]
    assert d["t_c_e1_minus_1"] == cp.q and "N_p_c_minus_1" not in d
