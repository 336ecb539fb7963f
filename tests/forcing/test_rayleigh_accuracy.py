"""``RayleighSum`` and the several-component forcing against independent quadratures of the
convolution (:mod:`tests.reference.forcing`): the closed form of eq. (27) for one and two
scales, the density of one scale (or pair) against the closed-form tail of the others by
composite Gauss-Legendre with self-checking rule orders, a direct 2-D quadrature, scipy's
adaptive quad grouped differently, and identities between different integrals (``cdf + sf =
1``, scale invariance). Scales spread over 1e-8 .. 1e8 so that both tails and every spread are
reached; float64 to the documented contract with an honest error estimate, mpmath to ``dps``."""

from __future__ import annotations

import math
from fractions import Fraction

import mpmath
import numpy as np
import pytest

from symhx import forcing as F
from symhx._mpctx import mp as thread_mp
from symhx.forcing import RayleighSum
from symhx.forcing.rayleigh import rayleigh_scales
from tests.reference.forcing import (
    RAYLEIGH_REF_DPS,
    one_pdf_float,
    pair_tail_float,
    rayleigh_sum_value,
    three_rayleigh_direct,
    three_rayleigh_tail,
    three_scale_sf_gl,
)
from tests.reference.mp import rel_err

EPS = np.finfo(float).eps


SPREAD_REF_DPS = 30


# scales spread over 1e-8 .. 1e8 (d = 1), both tails; p from ~6e-29 to ~1 - 1.6e-17
SPREAD_CASES = [
    ([0.5, 1e-3, 0.5], 1.0),
    ([0.3, 1e-8, 0.2], 1.0),
    ([1e8, 0.4, 1e-8], 1.0),
    ([3.0, 1e-4, 2.0], 1.0),
    ([0.05, 0.07, 1e-6], 1.0),
    ([50.0, 1e3, 1e-2], 1.0),
]


#: (case, upper tail) with the slow (~30 s each) independent nested quadrature: the issue's
#: example, both tails of the 1e8/1e-8 spread (1 - p ~ 1.6e-17) and the tiny tail p ~ 6e-29;
#: every case is also checked against the mpmath path at 30 digits
SPREAD_REF_KEYS = [(0, True), (2, True), (2, False), (4, True)]


def _key(i, up):
    s, d = SPREAD_CASES[i]
    return (tuple(s), d, up)


@pytest.fixture(scope="module")
def refs():
    out = {_key(i, up): three_rayleigh_tail(*SPREAD_CASES[i], up) for i, up in SPREAD_REF_KEYS}
    for i in range(len(SPREAD_CASES)):
        for up in (True, False):
            if (i, up) not in SPREAD_REF_KEYS:
                s, d = SPREAD_CASES[i]
                out[_key(i, up)] = F.rayleigh_sum_probability(
                    s, d, tail="upper" if up else "lower", dps=24).value
    return out


@pytest.mark.parametrize("scales, d", SPREAD_CASES)
@pytest.mark.parametrize("upper", [True, False])
def test_float64_meets_contract_and_error_estimate_is_honest(scales, d, upper, refs):
    ref = refs[(tuple(scales), d, upper)]
    tail = "upper" if upper else "lower"
    res = F.rayleigh_sum_probability(scales, d, tail=tail)
    S = RayleighSum(scales)
    with mpmath.workdps(SPREAD_REF_DPS), thread_mp().workdps(SPREAD_REF_DPS):
        if not 1e-300 < ref:
            pytest.skip("below the float range")
        # condition number |d ln P/d ln d| = d pdf(d)/P, from the mpmath path
        kappa = float(d * S.pdf(d, dps=20) / ref)
        true_err = float(rel_err(res.value, ref))
    assert true_err <= 1e-13 + 4 * kappa * EPS, (scales, tail, true_err, kappa)
    # the error estimate is never below the true (absolute) error
    assert res.error >= true_err * float(ref), (scales, tail, res.error, true_err)
    # the distribution object gives the same number
    assert (S.sf(d) if upper else S.cdf(d)) == res.value


@pytest.mark.parametrize("i, upper", SPREAD_REF_KEYS)
def test_mpmath_meets_dps_against_nested_quadrature(i, upper, refs):
    scales, d = SPREAD_CASES[i]
    ref = refs[(tuple(scales), d, upper)]
    tail = "upper" if upper else "lower"
    res = F.rayleigh_sum_probability(scales, d, tail=tail, dps=18)
    assert rel_err(res.value, ref) < 1e-18
    # its error estimate is honest too (against the 22-digit reference)
    with mpmath.workdps(SPREAD_REF_DPS + 10), thread_mp().workdps(SPREAD_REF_DPS + 10):
        assert res.error + mpmath.mpf(10) ** -21 * ref >= abs(res.value - ref)


@pytest.mark.parametrize("scales, d", SPREAD_CASES[::2])
def test_mpmath_meets_dps_at_twice_dps(scales, d):
    for tail in ("upper", "lower"):
        a = F.rayleigh_sum_probability(scales, d, tail=tail, dps=20).value
        b = F.rayleigh_sum_probability(scales, d, tail=tail, dps=40).value
        assert rel_err(a, b) < 1e-20


@pytest.mark.parametrize("i, upper", SPREAD_REF_KEYS)
def test_logs_both_tails(i, upper, refs):
    scales, d = SPREAD_CASES[i]
    ref = refs[_key(i, upper)]
    S = RayleighSum(scales)
    with mpmath.workdps(SPREAD_REF_DPS), thread_mp().workdps(SPREAD_REF_DPS):
        # near 1, log(ref) keeps only absolute accuracy: use the other tail
        lref = mpmath.log(ref) if ref < 0.5 else mpmath.log1p(-refs[_key(i, not upper)])
        fn = S.logsf if upper else S.logcdf
        assert rel_err(fn(d, dps=18), lref) < 1e-18
        # float64: relative accuracy of the log too (log1p of the other tail near 1)
        assert rel_err(fn(d), lref) < 1e-12, (fn(d), lref)


# ------------------------------------------------------------------------------ cases
#: scales (spread over 1e-8 .. 1e8) and thresholds reaching both tails and the body
REF_CASES = [
    ([0.5, 0.3, 0.2], [0.05, 0.4, 1.0, 2.5, 5.0]),
    ([1e8, 0.4, 1e-8], [0.3, 1.0]),
    ([3.0, 1e-4, 2.0], [0.01, 1.0, 30.0]),
    ([0.6, 0.45, 0.3, 0.1], [0.02, 1.5, 6.0]),
    ([1e4, 7e3, 1.0, 0.5], [3.0, 1e4, 8e4]),
    ([0.7, 0.2], [0.1, 1.0, 9.0]),
    ([0.7], [0.1, 1.0, 9.0]),
]


def _points():
    return [(tuple(sc), x) for sc, xs in REF_CASES for x in xs]


@pytest.mark.parametrize(("scales", "x"), _points())
def test_float64_three_kinds_and_error_estimate(scales, x):
    """sf, cdf, pdf within ~1e-13 relative (and ~eps times the digits of the exponent), the
    error estimate above the true error and itself small; logs of both tails."""
    S = RayleighSum(list(scales))
    vals = {k: getattr(S, k)(x) for k in ("sf", "cdf", "pdf")}
    refs = {k: rayleigh_sum_value(scales, x, k) for k in ("sf", "cdf", "pdf")}
    n = len(scales)
    for k in ("sf", "cdf", "pdf"):
        r = refs[k]
        if r < 1e-300:
            assert vals[k] < 1e-290, (k, vals[k], r)
            continue
        bound = 1e-13 + 8 * EPS * (n + 2 * abs(math.log(float(r))))
        assert rel_err(vals[k], r) < bound, (k, scales, x, vals[k], r)
    for tail, kind in (("upper", "sf"), ("lower", "cdf")):
        res = S.probability(x, tail=tail)
        assert res.value == vals[kind]
        assert res.method == ("closed form" if n <= 2 else "Laplace-transform inversion")
        r = refs[kind]
        if r > 1e-300:
            true = float(abs(mpmath.mpf(res.value) - r))
            assert res.error >= true, (tail, res.error, true)
            assert res.error <= 1e-12 * float(r) * (1 + abs(math.log(float(r)))), (tail, res)
    # logs: log1p of the other tail where the tail is above 1/2
    for fn, main, other in ((S.logsf, "sf", "cdf"), (S.logcdf, "cdf", "sf")):
        r, ro = refs[main], refs[other]
        if not r > 1e-300:
            continue
        with mpmath.workdps(40), thread_mp().workdps(40):
            lr = mpmath.log(r) if r <= 0.5 else mpmath.log1p(-ro)
        v = fn(x)
        assert abs(v - float(lr)) <= 1e-13 * abs(float(lr)) + 8 * EPS * (n + abs(float(lr))), (
            fn.__name__, scales, x, v, lr)


@pytest.mark.parametrize(("scales", "x"), [((0.5, 0.3, 0.2), 0.4), ((0.5, 0.3, 0.2), 2.5),
                                           ((1e8, 0.4, 1e-8), 1.0),
                                           ((0.6, 0.45, 0.3, 0.1), 1.5),
                                           ((0.6, 0.45, 0.3, 0.1), 6.0),
                                           ((0.7, 0.2), 9.0), ((0.7,), 1.0)])
def test_mpmath_meets_dps(scales, x):
    """dps = 20 against the 24-digit reference: all five functions and the error estimate."""
    S = RayleighSum(list(scales))
    refs = {k: rayleigh_sum_value(scales, x, k) for k in ("sf", "cdf", "pdf")}
    for k in ("sf", "cdf", "pdf"):
        v = getattr(S, k)(x, dps=20)
        assert rel_err(v, refs[k]) < 1e-20, (k, scales, x)
    with mpmath.workdps(40), thread_mp().workdps(40):
        lsf = mpmath.log(refs["sf"]) if refs["sf"] <= 0.5 else mpmath.log1p(-refs["cdf"])
        lcdf = mpmath.log(refs["cdf"]) if refs["cdf"] <= 0.5 else mpmath.log1p(-refs["sf"])
    assert rel_err(S.logsf(x, dps=20), lsf) < 1e-20
    assert rel_err(S.logcdf(x, dps=20), lcdf) < 1e-20
    for tail, kind in (("upper", "sf"), ("lower", "cdf")):
        res = S.probability(x, tail=tail, dps=20)
        with mpmath.workdps(40), thread_mp().workdps(40):
            true = abs(res.value - refs[kind])
            assert res.error + mpmath.mpf(10) ** -(RAYLEIGH_REF_DPS - 1) * refs[kind] >= true
            assert res.error <= mpmath.mpf(10) ** -20 * abs(refs[kind])


def test_five_scales_two_nested_levels():
    """Five scales (the package's groups: pair, single, pair -- the single moved second to last)
    against scipy's adaptive quad grouped differently: the pair A = (0.8, 0.35) with density
    f_A(t) = int f_0.8(w) f_0.35(t - w) dw, convolved with the three-scale tail
    T(s) = P(R_0.5 + B > s), B the pair (0.2, 0.1) with its closed-form tail:
    P(S > x) = P(A > x) + int_0^x f_A(t) T(x - t) dt (float64, moderate tails)."""
    from scipy import integrate

    S = RayleighSum([0.8, 0.5, 0.35, 0.2, 0.1])
    kw = dict(epsabs=0, epsrel=1e-12, limit=100)

    def f_a(t):
        return integrate.quad(lambda w: one_pdf_float(w, 0.8) * one_pdf_float(t - w, 0.35), 0, t,
                              **kw)[0]

    def t3(s):
        if s <= 0:
            return 1.0
        return math.exp(-s * s / (2 * 0.25)) + integrate.quad(
            lambda w: one_pdf_float(w, 0.5) * pair_tail_float(s - w, 0.2, 0.1), 0, s, **kw)[0]

    for x in (0.9, 2.4):
        up = pair_tail_float(x, 0.8, 0.35) + integrate.quad(lambda t, x=x: f_a(t) * t3(x - t), 0, x,
                                                         **kw)[0]
        assert abs(S.sf(x) / up - 1) < 1e-10, (x, S.sf(x), up)
        assert abs(S.cdf(x) - (1 - up)) < 1e-10 * up, (x, S.cdf(x), 1 - up)
        assert abs(S.sf(x) + S.cdf(x) - 1) < 8 * EPS
        assert S.probability(x).method == "Laplace-transform inversion"


def test_several_components_match_rayleigh_sum():
    """The forcing with two components is the three-scale sum at d (both tails, float and
    mpmath)."""
    sc = rayleigh_scales(0.3, Omega=[2.0, 0.5])
    for x in (0.7,):
        p = F.impact_probability(0.3, Omega=[2.0, 0.5], d=x)
        assert rel_err(p, rayleigh_sum_value(tuple(sc), x, "sf")) < 1e-13
        q = F.no_impact_probability(0.3, Omega=[2.0, 0.5], d=x)
        assert rel_err(q, rayleigh_sum_value(tuple(sc), x, "cdf")) < 1e-13


@pytest.mark.parametrize("scales, d", [([0.5, 0.3, 0.2], 1.0), ([2.0, 0.7, 1.1], 1.3)])
def test_three_rayleighs_against_direct_2d_quadrature(scales, d):
    for upper in (True, False):
        ref = three_rayleigh_direct(scales, d, 20, upper)
        tail = "upper" if upper else "lower"
        res = F.rayleigh_sum_probability(scales, d, tail=tail, dps=15)
        assert rel_err(res.value, ref) < 1e-14
        resf = F.rayleigh_sum_probability(scales, d, tail=tail)
        assert rel_err(resf.value, ref) < 1e-13


def test_five_scales_two_nested_quadratures():
    """M = 4 components (5 Rayleighs, 2-D nesting): float64 against mpmath (one point, the
    mpmath 2-D nesting costs seconds) and against a different grouping of the same scales."""
    scales = [0.3, 0.1, 0.25, 0.2, 0.15]
    res = F.rayleigh_sum_probability(scales, 1.0)
    ref = F.rayleigh_sum_probability(scales, 1.0, dps=12)
    assert rel_err(res.value, ref.value) < 1e-12
    for perm in ([0.15, 0.2, 0.3, 0.25, 0.1], [0.1, 0.3, 0.15, 0.25, 0.2]):
        for tail in ("upper", "lower"):
            a = F.rayleigh_sum_probability(scales, 1.0, tail=tail)
            b = F.rayleigh_sum_probability(perm, 1.0, tail=tail)
            assert rel_err(a.value, b.value) < a.error / a.value + b.error / b.value
    tiny = F.rayleigh_sum_probability([s / 6 for s in scales], 1.0)  # deep upper tail
    big = F.rayleigh_sum_probability([s * 40 for s in scales], 1.0, tail="lower")  # deep lower
    assert 0 < tiny.value < 1e-30 and tiny.error < 1e-12 * tiny.value
    assert 0 < big.value < 1e-15 and big.error < 1e-12 * big.value


def test_several_components_mpmath_converges_with_dps():
    kw = dict(sigma1=[0.08, 0.03], Omega=[1.7, 0.4])
    lo = F.rayleigh_sum_probability(F.rayleigh_scales(0.04, **kw, dps=40), 1, dps=20)
    hi = F.rayleigh_sum_probability(F.rayleigh_scales(0.04, **kw, dps=40), 1, dps=40)
    assert rel_err(lo.value, hi.value) < mpmath.mpf(10) ** -20
    assert lo.error < mpmath.mpf(10) ** -21 * lo.value
    assert hi.value < 1e-15  # a deep tail


@pytest.mark.parametrize("x", ["1", "4", "7"])
def test_three_scales_against_own_quadrature(x):
    """sf, cdf, log sf at moderate E (up to ~65): mpmath at 25 digits and float64."""
    s = ("0.5", "0.3", "0.2")
    with mpmath.workdps(40), thread_mp().workdps(40):
        a, b = three_scale_sf_gl(x, s, 20), three_scale_sf_gl(x, s, 28)
        assert rel_err(a, b) < 1e-32
        S = RayleighSum(list(s))
        assert rel_err(S.sf(x, dps=25), b) < 1e-24
        assert rel_err(S.cdf(x, dps=25), 1 - b) < 1e-24
        assert rel_err(S.logsf(x, dps=25), mpmath.log(b)) < 1e-24
        assert rel_err(S.sf(float(x)), b) < 2e-14
        assert rel_err(S.logsf(float(x)), mpmath.log(b)) < 1e-15
        assert rel_err(S.logcdf(float(x)), mpmath.log1p(-b)) < 1e-14


@pytest.mark.parametrize(("scales", "x"), [(["0.5", "0.3", "0.2"], "0.3"),
                                           (["0.5", "0.3", "0.2"], "0.9"),
                                           (["0.6", "0.45", "0.3", "0.1"], "1.2"),
                                           (["1e4", "1", "1e-4"], "1"),
                                           (["1e4", "1", "1e-4"], "2e3"),
                                           # the saddle panels resolve this one (without them
                                           # the cdf is off by 2e-27 relative)
                                           (["1", "1e-6", "1e-6", "1e-6"], "0.3")])
def test_mp_cdf_and_sf_are_two_integrands_summing_to_one(scales, x):
    # below the median (sf > 0.55) the cdf is the quadrature of densities against cdfs, the sf
    # that of scaled densities against scaled tails: their sum is 1 to the digits asked for
    S = RayleighSum(scales)
    cdf, sf = S.cdf(x, dps=30), S.sf(x, dps=30)
    assert 1e-12 < cdf < 0.45
    with mpmath.workdps(60), thread_mp().workdps(60):
        assert abs(cdf + sf - 1) < mpmath.mpf(10) ** -30


def test_mp_five_scales_cdf_and_sf_sum_to_one():
    S = RayleighSum(["1", "0.9", "0.5", "0.3", "0.2"])
    cdf, sf = S.cdf("1", dps=12), S.sf("1", dps=12)
    assert 1e-4 < cdf < 1e-3
    with mpmath.workdps(40), thread_mp().workdps(40):
        assert abs(cdf + sf - 1) < mpmath.mpf(10) ** -12


def test_mp_cdf_is_scale_invariant_beyond_the_float_range():
    # scales 1e-200 (no float64 estimate of sf: the route guesses the upper half, finds sf ~ 1
    # and takes the cdf's own quadrature -- 1 - sf would cancel every digit)
    small = RayleighSum(["1e-200", "2e-200", "3e-200"]).cdf("1e-203", dps=25)
    unit = RayleighSum(["1", "2", "3"]).cdf("0.001", dps=25)
    assert 1e-24 < unit < 1e-22
    with mpmath.workdps(50), thread_mp().workdps(50):
        assert abs(small / unit - 1) < mpmath.mpf(10) ** -25
    big = RayleighSum(["1e200", "2e200", "3e200"]).sf("1e201", dps=25)
    with mpmath.workdps(50), thread_mp().workdps(50):
        assert abs(big / RayleighSum(["1", "2", "3"]).sf("10", dps=25) - 1) < mpmath.mpf(10) ** -25


@pytest.mark.parametrize("scales, q", [(["0.5", "0.3", "0.2"], q) for q in
                                       ("0.05", "0.3", "0.45", "0.7", "0.95")]
                         + [(["0.6", "0.45", "0.3", "0.1"], q) for q in ("0.3", "0.7")])
def test_mp_logs_at_20_digits_against_40(scales, q):
    """log sf and log cdf where |log| is O(1) (no cancellation to hide an inaccurate inner
    value): the 20-digit results agree with the 40-digit ones to 20 digits. The thresholds are
    the float64 quantiles, so both tails and both sides of the median are met."""
    S = RayleighSum(scales)
    x = _quantile(S, float(q))
    for kind in ("logsf", "logcdf", "sf", "cdf", "pdf"):
        got = S._eval(x, kind, 20)
        ref = S._eval(x, kind, 40)
        assert abs(got / ref - 1) < mpmath.mpf(10) ** -19, kind


def _quantile(S, q):
    lo, hi = 0.0, 20.0
    for _ in range(60):
        mid = 0.5 * (lo + hi)
        lo, hi = (mid, hi) if S.cdf(mid) < q else (lo, mid)
    return Fraction(0.5 * (lo + hi))


# ------------------------------------------------------------------ float64 routes
def test_float_lower_tail_with_scales_spread_over_six_decades():
    """Scales 1e-6 .. 3 at a threshold between the two smallest (x = 2.7e-4): the panels at
    multiples of every scale near both ends of [0, x] resolve the small scales; float64 density
    and cdf against mpmath at 17 digits."""
    S = RayleighSum([3.0, 1e-6, 2.0, 1e-3, 0.5])
    x = 0.0002731601224582885
    for kind in ("pdf", "cdf"):
        ref = S._eval(x, kind, 17)
        assert abs(S._eval(x, kind, None) / ref - 1) < 1e-13, kind
