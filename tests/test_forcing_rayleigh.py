"""RayleighSum and the several-component forcing against an independent nested quadrature.

The reference integrates the largest Rayleigh's density against the two-Rayleigh closed form of
eq. (27) (re-derived in this file, no package code) by dense composite Gauss-Legendre at 30 digits
and two rule orders (``mpmath.quad`` was tried first: its tanh-sinh error estimate is optimistic
here, it was off by up to 1.7e-5 at 22 digits for the 1e-6 scale).
Scales are spread over 1e-8 .. 1e8 so that every panel family and both tails are reached.
"""

from __future__ import annotations

import itertools
import math

import mpmath
import numpy as np
import pytest

from symhx import forcing as F
from symhx.forcing import RayleighSum

EPS = np.finfo(float).eps
REF_DPS = 30


def rel(a, b):
    with mpmath.workdps(100):
        return abs(mpmath.mpf(a) / mpmath.mpf(b) - 1)


def pair_tail(s, a, b, upper):
    """P(Ra + Rb > s) (or <= s) from the two-Rayleigh closed form of eq. (27), written here
    independently of the package: x = s^2/(2a^2), y = s^2/(2b^2), r = sqrt(x + y), u = x/r,
    v = y/r, p = e^{-uv} (v e^{-u^2} + u e^{-v^2} + sqrt(pi) u v (erf u + erf v))/r; 1 - p at
    40 extra digits (no cancellation left at the reference precision)."""
    if s <= 0:
        return mpmath.mpf(1) if upper else mpmath.mpf(0)
    with mpmath.workdps(mpmath.mp.dps + 40):
        x, y = s * s / (2 * a * a), s * s / (2 * b * b)
        r = mpmath.sqrt(x + y)
        u, v = x / r, y / r
        p = mpmath.exp(-u * v) * (v * mpmath.exp(-u * u) + u * mpmath.exp(-v * v) + mpmath.sqrt(
            mpmath.pi) * u * v * (mpmath.erf(u) + mpmath.erf(v))) / r
        return +p if upper else 1 - p


def gl_sum(f, pts, n):
    xs, ws = mpmath.mp.gauss_quadrature(n, "legendre")
    tot = mpmath.mpf(0)
    for lo, hi in itertools.pairwise(pts):
        h, m = (hi - lo) / 2, (hi + lo) / 2
        tot += h * mpmath.fsum(w * f(m + h * x) for x, w in zip(xs, ws, strict=True))
    return tot


def ref_three(scales, d, upper):
    """P(R1 + R2 + R3 > d) (upper) or <= d: the *largest* scale is integrated against the
    closed-form tail of the other two (the package pairs the two largest instead), by composite
    Gauss-Legendre on 64 uniform panels plus panels at multiples of every scale from both ends,
    at two rule orders that must agree (the reference certifies itself)."""
    with mpmath.workdps(REF_DPS):
        c, a, b = (mpmath.mpf(s) for s in sorted(scales, reverse=True))
        d = mpmath.mpf(d)

        def f(t):
            return t / c**2 * mpmath.exp(-t * t / (2 * c * c)) * pair_tail(d - t, a, b, upper)

        pts = {d * k / 64 for k in range(65)}
        for s in (a, b, c):
            for k in (0.25, 0.5, 1, 2, 3, 4, 6, 8, 12, 16, 24):
                for q in (k * s, d - k * s):
                    if 0 < q < d:
                        pts.add(q)
        pts = sorted(pts)
        lo, hi = gl_sum(f, pts, 20), gl_sum(f, pts, 40)
        assert abs(hi - lo) < mpmath.mpf(10) ** -(REF_DPS - 4) * abs(hi), (scales, lo, hi)
        if upper:
            hi += mpmath.exp(-d * d / (2 * c * c))
        return hi


# scales spread over 1e-8 .. 1e8 (d = 1), both tails; p from ~6e-29 to ~1 - 1.6e-17
CASES = [
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
REF_KEYS = [(0, True), (2, True), (2, False), (4, True)]


def _key(i, up):
    s, d = CASES[i]
    return (tuple(s), d, up)


@pytest.fixture(scope="module")
def refs():
    out = {_key(i, up): ref_three(*CASES[i], up) for i, up in REF_KEYS}
    for i in range(len(CASES)):
        for up in (True, False):
            if (i, up) not in REF_KEYS:
                s, d = CASES[i]
                out[_key(i, up)] = F.rayleigh_sum_probability(
                    s, d, tail="upper" if up else "lower", dps=24).value
    return out


@pytest.mark.parametrize("scales, d", CASES)
@pytest.mark.parametrize("upper", [True, False])
def test_float64_meets_contract_and_error_estimate_is_honest(scales, d, upper, refs):
    ref = refs[(tuple(scales), d, upper)]
    tail = "upper" if upper else "lower"
    res = F.rayleigh_sum_probability(scales, d, tail=tail)
    S = RayleighSum(scales)
    with mpmath.workdps(REF_DPS):
        if not 1e-300 < ref:
            pytest.skip("below the float range")
        # condition number |d ln P/d ln d| = d pdf(d)/P, from the mpmath path
        kappa = float(d * S.pdf(d, dps=20) / ref)
        true_err = float(rel(res.value, ref))
    assert true_err <= 1e-13 + 4 * kappa * EPS, (scales, tail, true_err, kappa)
    # the error estimate is never below the true (absolute) error
    assert res.error >= true_err * float(ref), (scales, tail, res.error, true_err)
    # the distribution object gives the same number
    assert (S.sf(d) if upper else S.cdf(d)) == res.value


@pytest.mark.parametrize("i, upper", REF_KEYS)
def test_mpmath_meets_dps_against_nested_quadrature(i, upper, refs):
    scales, d = CASES[i]
    ref = refs[(tuple(scales), d, upper)]
    tail = "upper" if upper else "lower"
    res = F.rayleigh_sum_probability(scales, d, tail=tail, dps=18)
    assert rel(res.value, ref) < 1e-18
    # its error estimate is honest too (against the 22-digit reference)
    with mpmath.workdps(REF_DPS + 10):
        assert res.error + mpmath.mpf(10) ** -21 * ref >= abs(res.value - ref)


@pytest.mark.parametrize("scales, d", CASES[::2])
def test_mpmath_meets_dps_at_twice_dps(scales, d):
    for tail in ("upper", "lower"):
        a = F.rayleigh_sum_probability(scales, d, tail=tail, dps=20).value
        b = F.rayleigh_sum_probability(scales, d, tail=tail, dps=40).value
        assert rel(a, b) < 1e-20


@pytest.mark.parametrize("i, upper", REF_KEYS)
def test_logs_both_tails(i, upper, refs):
    scales, d = CASES[i]
    ref = refs[_key(i, upper)]
    S = RayleighSum(scales)
    with mpmath.workdps(REF_DPS):
        # near 1, log(ref) keeps only absolute accuracy: use the other tail
        lref = mpmath.log(ref) if ref < 0.5 else mpmath.log1p(-refs[_key(i, not upper)])
        fn = S.logsf if upper else S.logcdf
        assert rel(fn(d, dps=18), lref) < 1e-18
        # float64: relative accuracy of the log too (log1p of the other tail near 1)
        assert rel(fn(d), lref) < 1e-12, (fn(d), lref)


def test_rayleigh_sum_methods():
    sc = [0.5, 0.3, 0.2]
    S = RayleighSum(sc)
    x = np.array([-1.0, 0.0, 0.3, 1.0, 2.5])
    sf, cdf, pdf = S.sf(x), S.cdf(x), S.pdf(x)
    assert sf[0] == sf[1] == 1.0 and cdf[0] == cdf[1] == 0.0 and pdf[0] == 0.0
    assert np.all(np.abs(sf + cdf - 1) < 4 * EPS)
    # pdf is the derivative of the cdf (independent: central difference at 30 digits)
    with mpmath.workdps(30):
        h = mpmath.mpf("1e-8")
        fd = (S.cdf(mpmath.mpf(1) + h, dps=25) - S.cdf(mpmath.mpf(1) - h, dps=25)) / (2 * h)
        assert rel(S.pdf(1.0, dps=20), fd) < 1e-14
    assert abs(S.pdf(1.0) / float(fd) - 1) < 1e-13
    # moments: closed forms vs the sample and vs numerical integration of the sf
    assert S.mean() == pytest.approx(math.sqrt(math.pi / 2) * 1.0, rel=1e-15)
    assert S.var() == pytest.approx((2 - math.pi / 2) * 0.38, rel=1e-15)
    with mpmath.workdps(20):
        m_int = mpmath.quad(lambda t: S.sf(t, dps=15), [0, 0.5, 1, 2, 5, 12])  # sf(12)~e-190
        assert rel(S.mean(dps=20), m_int) < 1e-13
    r = S.rvs(size=200_000, random_state=1)
    assert abs(r.mean() - S.mean()) < 5 * S.std() / math.sqrt(r.size)
    assert np.array_equal(r, S.rvs(size=200_000, random_state=1))
    # Kolmogorov-Smirnov against the cdf
    from scipy import stats

    assert stats.kstest(r[:5000], S.cdf).pvalue > 1e-3
    # empty in, empty out
    assert S.sf(np.array([])).shape == (0,)


@pytest.mark.parametrize("bad, exc", [([], ValueError), ([0.5, -1.0], ValueError),
                                      ([0.5, float("nan")], ValueError), ([True, 0.5], TypeError),
                                      ("0.5", TypeError), ([0.5, "x"], ValueError)])
def test_rayleigh_sum_bad_scales(bad, exc):
    with pytest.raises(exc, match="scales"):
        RayleighSum(bad)


def test_rayleigh_sum_bad_x_and_dps():
    S = RayleighSum([1.0, 2.0])
    with pytest.raises(ValueError, match="x"):
        S.sf(float("nan"))
    with pytest.raises(ValueError, match=r"x.*index"):
        S.sf([1.0, float("inf")])
    with pytest.raises(TypeError, match="dps"):
        S.sf(1.0, dps=True)
    with pytest.raises(ValueError, match="tail"):
        S.probability(1.0, tail="middle")


def test_decimal_strings_are_exact_scales():
    a = RayleighSum(["0.1", "0.2", "0.3"]).sf(0.5, dps=30)
    with mpmath.workdps(40):
        b = RayleighSum([mpmath.mpf(1) / 10, mpmath.mpf(2) / 10, mpmath.mpf(3) / 10]).sf(
            mpmath.mpf("0.5"), dps=30)
        assert rel(a, b) < 1e-29
