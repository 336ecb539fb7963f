"""X with per-site probabilities in several classes (issue 30): exact Fractions against the
brute-force class convolution, mpmath against exact at twice the digits, float64 against mpmath,
certified modes with exact ties."""

from __future__ import annotations

import math
from fractions import Fraction

import mpmath
import numpy as np
import pytest

from symhx.site_distribution import SitesDistribution, site_modes
from symhx.site_weights import BALL_TABLE_N_LIMIT, EXACT_TABLE_BITS_LIMIT
from symhx.sites import SiteClasses
from symhx.spaces import parse_space
from tests.harness.discrete import check_quantiles_at_exact_ties
from tests.harness.errors import assert_refuses
from tests.reference.mp import assert_mp_close
from tests.reference.sites import brute_weights, expand, mode_weights, site_pmf

CASES = [((2, 99), (Fraction(1, 100), Fraction(1, 50))),
         ((3, 5, 4), (Fraction(1, 2), Fraction(1, 9), Fraction(3))),
         ((1, 40), (Fraction(7), Fraction(1, 30)))]


def _mp(x):
    """An exact Fraction as an mpf at 80 digits (the references are compared at 30)."""
    with mpmath.workdps(80):
        return mpmath.mpf(x.numerator) / x.denominator


@pytest.mark.parametrize("sizes, probs", CASES)
def test_exact_distribution_equals_the_class_convolution(sizes, probs):
    N = sum(sizes)
    d = SitesDistribution(N, SiteClasses(sizes, probs))
    ref = site_pmf(sizes, probs)
    assert d.exact and [d.pmf(k) for k in range(1, N + 1)] == ref
    mean = sum(k * p for k, p in enumerate(ref, 1))
    assert d.mean() == mean
    assert d.var() == sum((k - mean) ** 2 * p for k, p in enumerate(ref, 1))
    cum = np.cumsum(np.array(ref, dtype=object))
    for k in (0, 1, N // 3, N - 1, N):
        assert d.cdf(k) == (cum[k - 1] if k >= 1 else 0)
        assert d.cdf(k) + d.sf(k) == 1
    assert d.median() == next(k for k, c in enumerate(cum, 1) if c >= Fraction(1, 2))
    top = max(ref)
    assert d.modes() == tuple(k for k, p in enumerate(ref, 1) if p == top)
    assert d.normaliser == sum(mode_weights(sizes, probs))


@pytest.mark.parametrize("sizes, probs", CASES)
def test_mpmath_path_matches_exact_values_to_the_requested_digits(sizes, probs):
    """Floats are binary rationals: the exact distribution of their values is the reference."""
    N = sum(sizes)
    floats = tuple(float(p) for p in probs)
    binary = tuple(Fraction(f) for f in floats)
    d = SitesDistribution(N, SiteClasses(sizes, floats), dps=30)
    ex = SitesDistribution(N, SiteClasses(sizes, binary))
    assert not d.exact and ex.exact
    ks = [1, 2, N // 2, N - 1, N]
    assert_mp_close([d.pmf(k) for k in ks], [_mp(ex.pmf(k)) for k in ks], rtol=1e-29)
    assert_mp_close([d.cdf(k) for k in ks[:-1]], [_mp(ex.cdf(k)) for k in ks[:-1]], rtol=1e-29)
    assert_mp_close([d.sf(k) for k in ks[:-1]], [_mp(ex.sf(k)) for k in ks[:-1]], rtol=1e-29)
    assert_mp_close(d.mean(), _mp(ex.mean()), rtol=1e-29)
    assert_mp_close(d.var(), _mp(ex.var()), rtol=1e-29)
    with mpmath.workdps(60):
        logs = [mpmath.log(mpmath.mpf(ex.pmf(k).numerator) / ex.pmf(k).denominator) for k in ks]
        ent = -mpmath.fsum(mpmath.mpf(p.numerator) / p.denominator
                           * mpmath.log(mpmath.mpf(p.numerator) / p.denominator)
                           for p in (ex.pmf(k) for k in range(1, N + 1)))
    assert_mp_close([d.logpmf(k) for k in ks], logs, rtol=1e-29)
    assert_mp_close(d.entropy(), ent, rtol=1e-28)
    assert d.modes() == ex.modes() and d.median() == ex.median()


def test_float64_path_matches_mpmath():
    sizes, probs = (2, 99), (0.01, 0.02)
    d = SitesDistribution(101, SiteClasses(sizes, probs), dps=None)
    m = SitesDistribution(101, SiteClasses(sizes, probs), dps=30)
    ks = np.arange(1, 102)
    assert_mp_close(d.pmf(ks), [m.pmf(int(k)) for k in ks], rtol=1e-12)
    assert_mp_close(d.logsf(ks[:-1]), [m.logsf(int(k)) for k in ks[:-1]], rtol=1e-12)
    assert_mp_close(d.mean(), m.mean(), rtol=1e-13)
    assert d.modes() == m.modes()
    draws = d.rvs(1000, random_state=3)
    assert draws.min() >= 1 and draws.max() <= 101


def test_higher_order_space_with_classes_matches_brute_force():
    sizes, probs = (2, 2), (Fraction(1, 3), Fraction(1, 2))
    sp = parse_space("eq41")
    d = SitesDistribution(4, SiteClasses(sizes, probs), sp)
    w = brute_weights(expand(sizes, probs), "eq41")  # complete for k <= 4 = 7 - 3
    g = sum(w.values())
    assert [d.pmf(k) for k in range(1, 5)] == [w[k] / g for k in range(1, 5)]
    assert d.space == "eq41"


def test_exact_ties_are_found_for_exact_and_binary_inputs():
    # four sites (1, 1, 2, 2): W = 6, 13, 24, 24
    assert site_modes(4, SiteClasses((2, 2), (1, 2))) == (3, 4)
    assert site_modes(4, SiteClasses((2, 2), (1.0, 2.0))) == (3, 4)  # balls never separate
    assert site_modes(4, SiteClasses((2, 2), (1.0, 2.0000000000000004))) == (4,)
    assert SitesDistribution(4, SiteClasses((2, 2), ("1", "2"))).mode() == 3


def test_refusals_name_the_limit():
    big = SiteClasses((3000, 3000), ("1/3", "1/7"))
    assert_refuses(SitesDistribution, 6000, big, arg="N", value="N=6000",
                   allowed="EXACT_TABLE_BITS_LIMIT")
    huge = SiteClasses((BALL_TABLE_N_LIMIT, 1), (0.5, 0.25))
    assert_refuses(SitesDistribution, BALL_TABLE_N_LIMIT + 1, huge, arg="N",
                   value=f"N={BALL_TABLE_N_LIMIT + 1}", allowed="BALL_TABLE_N_LIMIT")
    assert_refuses(site_modes, BALL_TABLE_N_LIMIT + 1, huge, arg="N",
                   value=f"N={BALL_TABLE_N_LIMIT + 1}", allowed="BALL_TABLE_N_LIMIT")
    assert_refuses(SitesDistribution, 5, SiteClasses((2, 2), (1, 2)), arg="N", value="N = 5",
                   allowed="4 sites")
    assert_refuses(SitesDistribution, 4, [0.5] * 4, exc=TypeError, arg="classes",
                   value="[0.5, 0.5", allowed="SiteClasses")
    assert EXACT_TABLE_BITS_LIMIT > 0


@pytest.mark.parametrize("dps", [20, 30])
def test_quantiles_at_an_exact_tie_are_k(dps: int) -> None:
    """The mpmath path resolves q to dps digits (``ppf``: the smallest k with
    ``cdf(k) >= q (1 - 10**(1 - dps))``): a q whose resolved target equals cdf(k) / sf(k)
    exactly gives k, whatever the rounding of the cdf's last digit (it gave k + 1 for about
    half the k), and one resolution step beyond gives k + 1.  Reference: the exact
    distribution at the floats' binary values."""
    N = 30
    exact = SitesDistribution(N, SiteClasses((10, 20), (Fraction(0.05), Fraction(0.12))))
    d = SitesDistribution(N, SiteClasses((10, 20), (0.05, 0.12)), dps=dps)
    m = d.median()
    check_quantiles_at_exact_ties(d, exact, dps, range(m - 4, m + 5))


@pytest.mark.parametrize("dps", [None, 25, "exact"])
def test_table_lists_every_k_and_sums_to_one(dps) -> None:
    """``table()`` is ``[(k, P(X = k)) for k = 1..N]`` in every arithmetic: N rows, the pmf of
    each k, a total of 1 (exactly for exact probabilities)."""
    N = 9
    if dps == "exact":
        d = SitesDistribution(N, SiteClasses((4, 5), (Fraction(1, 7), Fraction(2, 9))))
    else:
        d = SitesDistribution(N, SiteClasses((4, 5), (1 / 7, 2 / 9)), dps=dps)
    t = d.table()
    assert [k for k, _ in t] == list(range(1, N + 1))
    assert all(v == d.pmf(k) for k, v in t)
    with mpmath.workdps(40):
        total = sum(v for _, v in t)
    if dps == "exact":
        assert total == 1
    else:
        assert abs(total - 1) < (1e-14 if dps is None else mpmath.mpf(10) ** (1 - dps))


def test_N_below_one_is_refused_by_name() -> None:
    assert_refuses(SitesDistribution, 0, SiteClasses((1,), (0.5,)), arg="N", value="0",
                   allowed=">= 1")


def test_the_distribution_keeps_its_classes_as_p() -> None:
    classes = SiteClasses((4, 5), (Fraction(1, 7), Fraction(2, 9)))
    d = SitesDistribution(9, classes)
    assert d.p is classes and d.N == 9
    assert d.fr is None          # no scalar rational p (documented): classes carry the values


def test_the_float_normaliser_is_the_exact_one_rounded() -> None:
    classes = ((4, 5), (Fraction(1, 7), Fraction(2, 9)))
    exact = SitesDistribution(9, SiteClasses(*classes)).normaliser
    fl = SitesDistribution(9, SiteClasses(classes[0], (1 / 7, 2 / 9)), dps=None).normaliser
    assert isinstance(fl, float) and abs(fl - float(exact)) <= 1e-14 * float(exact)
    # and its log far beyond float64's range (the table keeps logs relative to the largest
    # weight; the normaliser used to stay relative too: 3.69 instead of 6.20 above)
    big = SiteClasses((1000, 2000), (0.3, 0.6))
    ref = SitesDistribution(3000, big, dps=30).log_normaliser
    got = SitesDistribution(3000, big, dps=None)
    assert abs(got.log_normaliser - float(ref)) <= 1e-12 * float(ref)
    assert got.normaliser == math.inf
