"""``RayleighSum`` and several forcing components far in both tails.

References, none taken from the package (:mod:`tests.reference.forcing`): (a) a sum with one
negligible scale is bracketed by the two-Rayleigh closed form, ``sf_pair(x) <= sf_S(x) <=
sf_pair(x - a) + P(R3 > a)``; (b) the Laplace asymptotic of the upper tail, ``log sf =
-x**2/(2V) + (n-1) log(x/V) + sum log s_i - log(V)/2 + (n-1) log(2 pi)/2 + O(1/E)``; (c) the
leading power of the lower tail, ``P(S <= x) = x**(2n)/((2n)! prod s_i**2)`` for ``x << min s``;
(d) the float64 path against the mpmath path at more digits; (e) the exponent cap of
``exp(-E)`` (``MAX_EXPONENT``) and the uncapped logs."""

from __future__ import annotations

import itertools
import math
from fractions import Fraction

import mpmath
import numpy as np
import pytest
import sympy

from symhx import forcing as F
from symhx._mpctx import mp as thread_mp
from symhx.forcing import RayleighSum
from symhx.forcing.kernels_mp import MAX_EXPONENT
from tests.harness.errors import assert_refuses
from tests.reference.forcing import forcing_scales, laplace_logsf, log_pair_sf, rayleigh_sum_value
from tests.reference.mp import rel_err


# ------------------------------------------------------------------ (d) the reported bug
@pytest.mark.parametrize("sigma", [0.01, 3e-3, 1e-3, 1e-4, 1e-6])
def test_float_log_p_far_tail_is_finite_and_accurate(sigma):
    """Was -inf (E from ~2e3 to ~2e11); the float64 log p against the mpmath path."""
    got = F.log_impact_probability(sigma, Omega=[1.7, 2.2], d=1.0)
    ref = F.log_impact_probability(sigma, Omega=[1.7, 2.2], d=1.0, dps=32)
    assert math.isfinite(got)
    assert rel_err(got, ref) < 2e-15


def test_float_vs_mp_on_a_sigma_grid():
    """log p and log(1 - p) on a log grid of sigma (E from ~1e-4 to ~2e3), float64 vs 32 digits."""
    for sigma in np.logspace(-2, 2, 7):
        for fn in (F.log_impact_probability, F.log_no_impact_probability):
            got = fn(float(sigma), Omega=[1.7, 2.2], d=1.0)
            ref = fn(float(sigma), Omega=[1.7, 2.2], d=1.0, dps=32)
            if abs(ref) < mpmath.mpf("1e-308"):  # log(1 - p) = -5e-803 at sigma = 0.01
                assert got == 0.0
            else:
                assert rel_err(got, ref) < 1e-13, (sigma, fn.__name__)


# ------------------------------------------------------------------ (a) negligible scale
@pytest.mark.parametrize("x", [3, 30, 300, 3000])
def test_negligible_scale_bracket_mpmath(x):
    """Scales (0.7, 0.4, 1e-60): log sf at 50 digits inside the bracket of the pair closed form
    (width ~ 40e-60 x / V: far below the claim), up to E ~ 7e6."""
    s3 = mpmath.mpf("1e-60")
    S = RayleighSum(["0.7", "0.4", "1e-60"])
    got = S.logsf(x, dps=50)
    with mpmath.workdps(80), thread_mp().workdps(80):
        lo = log_pair_sf(x, "0.7", "0.4")
        hi = log_pair_sf(x - 40 * s3, "0.7", "0.4")  # + P(R3 > a) = e^-800: below 1e-300 of it
        slack = abs(lo) * mpmath.mpf(10) ** -49
        assert lo - slack <= got <= hi + slack


@pytest.mark.parametrize("x", [3.0, 30.0, 300.0, 3000.0, 3e4])
def test_negligible_scale_bracket_float(x):
    """The float64 log sf (E up to ~7e8) inside the bracket (relative width ~1e-16)."""
    S = RayleighSum([0.7, 0.4, 1e-15])
    got = S.logsf(x)
    with mpmath.workdps(40), thread_mp().workdps(40):
        lo = log_pair_sf(x, 0.7, 0.4)
        hi = log_pair_sf(mpmath.mpf(x) - 40 * mpmath.mpf(1e-15), 0.7, 0.4)
        slack = abs(lo) * mpmath.mpf(1e-14)
        assert lo - slack <= got <= hi + slack


# ------------------------------------------------------------------ (b) Laplace asymptotic
def test_laplace_error_shrinks_like_one_over_E():
    """mpmath quadrature vs the leading Laplace term: (log sf - laplace_logsf) * E tends to a
    constant (the next order is O(1/E)), from E = 1e2 to 1e5."""
    scales = ["0.5", "0.3", "0.2"]
    S = RayleighSum(scales)
    with mpmath.workdps(40), thread_mp().workdps(40):
        v = mpmath.mpf("0.38")
        prods = []
        for e in (100, 1000, 10000, 100000):
            x = mpmath.sqrt(2 * v * e)
            d = S.logsf(x, dps=30) - laplace_logsf(scales, x)
            assert abs(d) < mpmath.mpf(5) / e
            prods.append(d * e)
        steps = [abs(b - a) for a, b in itertools.pairwise(prods)]
        assert all(b < a / 5 for a, b in itertools.pairwise(steps))


def test_float_laplace_regime_and_its_edge():
    """The float64 log sf beyond x min(s) >= 1e9 V (the asymptotic) and just below it (the
    quadrature) against the mpmath quadrature (no asymptotic in mpmath)."""
    S = RayleighSum([0.5, 0.3, 0.2])
    edge = 1e9 * 0.38 / 0.2
    for x in (0.999 * edge, 1.001 * edge, 1e3 * edge):
        got = S.logsf(x)
        ref = S.logsf(x, dps=30)
        assert rel_err(got, ref) < 4e-16, x
    assert S.sf(1.001 * edge) == 0.0 and S.cdf(1.001 * edge) == 1.0


# ------------------------------------------------------------------ mpmath at large E
def test_mpmath_large_E_converges_at_60_digits():
    """The reported traceback (sigma = 1e-4, E ~ 1.9e7, 60 digits): now a value, consistent with
    30 digits and with the Laplace term to its O(1/E) bound."""
    got = F.log_impact_probability("1e-4", Omega=["1.7", "2.2"], d="1", dps=60)
    lo = F.log_impact_probability("1e-4", Omega=["1.7", "2.2"], d="1", dps=30)
    assert rel_err(got, lo) < 1e-29
    with mpmath.workdps(80), thread_mp().workdps(80):
        lap = laplace_logsf(forcing_scales("1e-4", ["1.7", "2.2"], 80), 1)
        e = -lap
        assert abs(got - lap) < 10 / e


def test_scales_carry_digits_for_huge_E():
    """p = exp(-E) with E ~ 1.9e29 at 20 digits: the Laplace term is exact to ~1e-29 there, and
    scales with only dps + 15 digits would leave a relative error ~E 1e-35 ~ 1e-5."""
    got = F.impact_probability("1e-15", Omega=["1.7", "2.2"], d="1", dps=20)
    with mpmath.workdps(90), thread_mp().workdps(90):
        ref = mpmath.exp(laplace_logsf(forcing_scales("1e-15", ["1.7", "2.2"], 90), 1))
        assert rel_err(got, ref, 90) < 1e-19
    lg = F.log_impact_probability("1e-15", Omega=["1.7", "2.2"], d="1", dps=20)
    with mpmath.workdps(90), thread_mp().workdps(90):
        assert rel_err(lg, mpmath.log(ref), 90) < 1e-19


def test_cap_and_uncapped_log():
    """Beyond MAX_EXPONENT p needs more guard digits than the cap allows: a clear ValueError;
    log p has no cap (it never forms exp(-E))."""
    with pytest.raises(ValueError, match="MAX_EXPONENT"):
        F.impact_probability("1e-160", Omega=["1.7", "2.2"], d="1", dps=20)
    got = F.log_impact_probability("1e-160", Omega=["1.7", "2.2"], d="1", dps=20)
    with mpmath.workdps(40), thread_mp().workdps(40):
        ref = laplace_logsf(forcing_scales("1e-160", ["1.7", "2.2"], 40), 1)
        assert rel_err(got, ref) < 1e-19


# ------------------------------------------------------------------ RayleighSum directly
def test_direct_methods_tails_and_arrays():
    """sf, cdf, log sf, log cdf near 0, in the body and far in the tail (sf underflowing),
    float64 against 32 digits; arrays keep their shape and equal the scalar calls."""
    S = RayleighSum([0.5, 0.3, 0.2])
    xs = np.array([[1e-3, 0.05, 1.0], [5.0, 20.0, 40.0]])
    got = {k: getattr(S, k)(xs) for k in ("sf", "cdf", "logsf", "logcdf")}
    for idx in np.ndindex(xs.shape):
        x = float(xs[idx])
        # the small one of sf, cdf at 32 digits, the other by 1 - it
        with mpmath.workdps(40), thread_mp().workdps(40):
            if x <= 1:
                cdf = S.cdf(x, dps=32)
                sf, lsf, lcdf = 1 - cdf, mpmath.log1p(-cdf), mpmath.log(cdf)
            else:
                sf = S.sf(x, dps=32)
                cdf, lsf, lcdf = 1 - sf, mpmath.log(sf), mpmath.log1p(-sf)
            ref = {"sf": sf, "cdf": cdf, "logsf": lsf, "logcdf": lcdf}
        for kind, tol in (("sf", 6e-14), ("cdf", 1e-15), ("logsf", 1e-15), ("logcdf", 6e-14)):
            assert got[kind].shape == (2, 3)
            assert got[kind][idx] == getattr(S, kind)(x)
            if abs(ref[kind]) < mpmath.mpf("1e-308"):  # 1.7e-911 at x = 40 rounds to 0
                assert got[kind][idx] == 0.0, (kind, x)
            else:
                assert rel_err(got[kind][idx], ref[kind]) < tol, (kind, x)
    # the error estimate bounds the true error in the tail and is not vacuous
    res = S.probability(20.0)
    true = abs(res.value - S.sf(20, dps=32))
    assert true <= res.error < 1e-12 * res.value
    res = S.probability(40.0, tail="lower")
    assert res.value == 1.0 and res.error < 1e-300


def test_float_scales_spread_far_apart():
    """Scales 1e25 apart: the pair's closed form (no quadrature) up to x/min(s) = 1e150, the
    bracket of (a) for three scales; beyond x max(s) = 1e30 the Laplace regime, and short of
    it (x min(s) < 1e5 V) a value too (it used to be refused): the bracket again."""
    two = RayleighSum([1.0, 1e-25])
    for x in (10.0, 1e3, 1e20, 1e31):
        with mpmath.workdps(40), thread_mp().workdps(40):
            assert rel_err(two.logsf(x), log_pair_sf(x, 1.0, 1e-25)) < 1e-15, x
    three = RayleighSum([1.0, 0.5, 1e-25])
    for x in (10.0, 1e3, 1e5):
        with mpmath.workdps(40), thread_mp().workdps(40):
            lo = log_pair_sf(x, 1.0, 0.5)
            hi = log_pair_sf(mpmath.mpf(x) - 40 * mpmath.mpf(1e-25), 1.0, 0.5)
            assert lo - abs(lo) * 1e-14 <= three.logsf(x) <= hi + abs(lo) * 1e-14, x
    # x min(s) = 1e6 V: the Laplace regime (the third scale moves log P by O(10) of 4e61)
    with mpmath.workdps(40), thread_mp().workdps(40):
        assert rel_err(three.logsf(1e31), log_pair_sf(mpmath.mpf(1e31), 1.0, 0.5)) < 1e-15
    assert three.sf(1e31) == 0.0 and three.cdf(1e31) == 1.0
    # beyond x max(s) = 1e30 but short of the Laplace regime: the bracket (relative width
    # 40e-30 x / V ~ 1e-58, far below an ulp)
    with mpmath.workdps(40), thread_mp().workdps(40):
        got = RayleighSum([1.0, 0.5, 1e-30]).logsf(1e31)
        assert rel_err(got, log_pair_sf(mpmath.mpf(1e31), 1.0, 0.5)) < 1e-15


def test_float_lower_tail_log_cdf():
    """log P(S <= x) where the cdf underflows (huge sigma: was -inf, and nan from an overflow of
    the saddle width at sigma = 1e100), against the mpmath quadrature at 32 digits, on both
    sides of the switch to the leading power at x = 1e-9 min(s)."""
    for sigma in (1e40, 1e60, 1e100):
        got = F.log_no_impact_probability(sigma, Omega=[1.7, 2.2])
        ref = F.log_no_impact_probability(sigma, Omega=[1.7, 2.2], dps=32)
        assert rel_err(got, ref) < 1e-15, sigma
    assert 0 < F.no_impact_probability(1e40, Omega=[1.7, 2.2]) < 1e-240
    assert F.no_impact_probability(1e100, Omega=[1.7, 2.2]) == 0.0
    S = RayleighSum([1.0, 0.5, 0.3])
    xs = np.array([1e-5, 0.99e-9 * 0.3, 1.01e-9 * 0.3, 1e-100, 5e-324])
    got = S.logcdf(xs)
    for x, g in zip(xs, got, strict=True):
        assert rel_err(g, S.logcdf(float(x), dps=32)) < 1e-15, x


def test_far_tail_density_is_minus_the_derivative_of_sf():
    """The scaled density (its own quadrature) against a central difference of the scaled sf at
    E ~ 1.2e3 (both mpmath); the float64 density against the mpmath one at E ~ 5e2."""
    S = RayleighSum(["0.5", "0.3", "0.2"])
    with mpmath.workdps(40), thread_mp().workdps(40):
        x, h = mpmath.mpf(30), mpmath.mpf("1e-12")
        fd = (S.sf(x - h, dps=32) - S.sf(x + h, dps=32)) / (2 * h)
        pdf = S.pdf(x, dps=20)
        assert rel_err(pdf, fd) < 1e-17
        assert S.pdf(30.0) == 0.0  # 7.6e-510
        assert rel_err(S.pdf(20.0), S.pdf(20, dps=20)) < 1e-12  # ~1e-226


def test_small_scale_structure_resolved_at_30_digits():
    """Scales (3, 2, 0.7, 1e-4): the pair (0.7, 1e-4) has structure ``exp(-t**2/(2e-8))`` near
    t = 0 that the panels at 0.5, 2, 8 scales left at e**-32 (no convergence at 30 digits,
    ArithmeticError); now 20 and 30 digits agree and the float64 value matches."""
    S = RayleighSum(["3", "1e-4", "2", "0.7"])
    hi = S.logsf("7.35", dps=30)
    assert rel_err(S.logsf("7.35", dps=20), hi) < 1e-19
    assert rel_err(S.logsf(7.35), hi) < 1e-14


@pytest.mark.parametrize("c", [1e-160, 1e160, 2.0**-300, 1e250])
def test_float64_routes_at_extreme_magnitudes(c):
    """Scales and x far outside 2**+-200: the float64 routes square them, so they work on the
    scale-free problem (scaled by a power of two). Before: scales (1, 2, 3) e-160 gave a cdf
    off by 1.8e-4 and an infinite density; (1, 2, 3) e160 gave sf = 0 and log sf = -inf (true
    0.848 and -84.4). References: mpmath at 25 digits, and the density's scaling
    pdf_{cS}(c x) = pdf_S(x) / c against the unscaled float64 value."""
    base = RayleighSum([1.0, 2.0, 3.0])
    S = RayleighSum([c, 2 * c, 3 * c])
    for u in (0.1, 5.0, 50.0):
        x = u * c
        for kind in ("sf", "cdf", "logsf", "logcdf"):
            got = getattr(S, kind)(x)
            ref = getattr(S, kind)(mpmath.mpf(x), dps=25)
            assert rel_err(got, ref) < 1e-13, (kind, u)
            assert rel_err(got, getattr(base, kind)(u)) < 1e-13, (kind, u)
        with mpmath.workdps(30), thread_mp().workdps(30):
            assert rel_err(S.pdf(x), S.pdf(mpmath.mpf(x), dps=25)) < 1e-13
            assert rel_err(S.pdf(x) * c, base.pdf(u)) < 1e-13
    res = S.probability(5 * c)
    assert rel_err(res.value, base.sf(5.0)) < 1e-13 and res.error < 1e-13


@pytest.mark.parametrize("scales", [[1.0, 0.5, 0.3], [3.0, 2.0, 0.7, 1e-4], [2.0, 1e-3, 1e-3],
                                    [5.0, 0.2, 0.1, 0.05]])
def test_laplace_log_tail_every_term(scales):
    """From x min(s) = 1e5 V on, float64 log sf is the Laplace expansion; its terms beyond
    -x**2/(2V) are O(10) there against an ulp of ~1e-5, so each of them shows: compared with the
    mpmath route (scaled quadrature, 20 digits) to 4 ulp at K = 1e5, 1e6 and 1e7."""
    S = RayleighSum(scales)
    V = math.fsum(s * s for s in scales)
    for K in (1e5, 1e6, 1e7):
        x = K * V / min(scales)
        got = S.logsf(x)
        ref = S.logsf(mpmath.mpf(x), dps=20)
        with mpmath.workdps(30), thread_mp().workdps(30):
            assert abs(got - ref) <= 4 * math.ulp(got), (K, float(got - ref))


def test_multi_component_p_far_out_keeps_its_digits():
    """p = exp(-E) with E ~ 2e17 (d = 1e9): a relative error eps of a scale moves p by 2 E eps,
    so the scales carry log10(E) more digits; with only the 15 guard digits p at dps = 20 was
    off by ~4e-18.  Reference: dps = 40 (there the guard digits alone would suffice)."""
    a = F.impact_probability(1, Omega=[1.7, 2.2], d="1e9", dps=20)
    b = F.impact_probability(1, Omega=[1.7, 2.2], d="1e9", dps=40)
    with mpmath.workdps(50), thread_mp().workdps(50):
        assert abs(a / b - 1) < mpmath.mpf(10) ** -20


def test_edges_far_tail_and_arrays():
    S = RayleighSum([0.5, 0.3, 0.2])
    xs = np.array([-1.0, 0.0, 1.0, 1e4, 3e4])
    sf, cdf, pdf = S.sf(xs), S.cdf(xs), S.pdf(xs)
    assert list(sf[:2]) == [1.0, 1.0] and list(cdf[:2]) == [0.0, 0.0] and pdf[0] == 0 == pdf[1]
    assert sf[3] == 0.0 and cdf[3] == 1.0 and pdf[3] == 0.0 and sf[4] == 0.0 and cdf[4] == 1.0
    assert rel_err(sf[2], rayleigh_sum_value((0.5, 0.3, 0.2), 1.0, "sf")) < 1e-13
    assert S.sf(np.array([[1.0, 2.5]])).shape == (1, 2)
    assert S.sf(np.array([])).shape == (0,)
    assert isinstance(S.sf(1.0), float) and isinstance(S.logsf([1.0]), np.ndarray)
    assert S.logsf(-1.0) == 0.0 and S.logcdf(0.0) == -math.inf
    # sf underflows at 1e4 but log sf is finite (the mpmath path, 30 digits, is the reference)
    with mpmath.workdps(30), thread_mp().workdps(30):
        assert abs(S.logsf(1e4) / S.logsf(1e4, dps=30) - 1) < 1e-14 and S.logcdf(1e4) == 0.0
    for k in ("sf", "cdf", "pdf"):
        res = S.probability(1e4, tail="upper" if k == "sf" else "lower")
        assert res.error == 0.0
    # x <= 0 in mpmath; arrays in mpmath; exact decimal thresholds
    assert S.sf(-2, dps=20) == 1 and S.cdf(0, dps=20) == 0 and S.pdf("-0.5", dps=20) == 0
    two = RayleighSum([0.7, 0.2])
    assert two.sf(0, dps=15) == 1 and two.cdf(-1, dps=15) == 0 and two.pdf(0, dps=15) == 0
    one = RayleighSum([0.7])
    assert one.pdf(-1.0) == 0.0 and one.sf(-1, dps=15) == 1 and one.pdf(0, dps=15) == 0
    out = S.sf([[0.4, 1]], dps=20)
    assert out.shape == (1, 2) and out.dtype == object
    assert rel_err(out[0, 0], rayleigh_sum_value((0.5, 0.3, 0.2), 0.4, "sf")) < 1e-20
    # far upper tail in mpmath: E = x^2/(2 sum s^2) ~ 1e6 needs its extra digits
    p = S.sf(300, dps=20)
    with mpmath.workdps(40), thread_mp().workdps(40):
        c = mpmath.mpf(0.5)
        assert 0 < p < mpmath.exp(-300**2 / (2 * 3 * c * c)) * 1e10
    sympy = pytest.importorskip("sympy")
    v = S.sf(sympy.sqrt(2) / 2, dps=20)
    with mpmath.workdps(40), thread_mp().workdps(40):
        h = mpmath.sqrt(2) / 2
    w = S.sf(h, dps=20)
    assert rel_err(v, w) < 1e-19


def test_log_cdf_leading_power_takes_logs_of_ratios():
    # log P(S <= x) = sum 2 log(x / s_i) - log((2n)!) far in: with x = 2**-1074 and scales
    # ~1e-314 the ratios are ~1e-10 (normal); log x - log s_i would lose ~1e-13 per term to the
    # rounding of log x ~ -744 (3e-15 relative here); the ratio is only avoided when it
    # underflows
    S = RayleighSum([1e-314, 2e-314, 3e-314])
    got = S.logcdf(5e-324)
    ref = S.logcdf(mpmath.mpf(5e-324), dps=30)
    with mpmath.workdps(40), thread_mp().workdps(40):
        assert abs(got / ref - 1) < 4e-16
    # a ratio below 1e-300 (x / 1e10): log x - log s, still to a few ulp of each log
    S2 = RayleighSum([1e10, 2e10, 3e10])
    got = S2.logcdf(5e-300)
    ref = S2.logcdf(mpmath.mpf(5e-300), dps=30)
    with mpmath.workdps(40), thread_mp().workdps(40):
        assert abs(got / ref - 1) < 1e-15


def _mpf(fr: Fraction) -> mpmath.mpf:
    return mpmath.mpf(fr.numerator) / fr.denominator


# ------------------------------------------------------------------ lower tail, every nesting
#: one scale, a pair, one quadrature (3, 4 scales), two nested quadratures (5, 6 scales; the
#: leftover single second to last), and scales spread over 1e-6 .. 1e4
LOWER_SETS = [["0.7"], ["0.7", "0.3"], ["0.5", "0.3", "0.2"], ["0.6", "0.45", "0.3", "0.1"],
              ["1", "0.9", "0.5", "0.3", "0.2"], ["1", "0.8", "0.6", "0.5", "0.3", "0.2"],
              ["1e4", "1", "1e-4"], ["3", "1e-6", "2", "1e-3", "0.5"]]


@pytest.mark.parametrize("scales", LOWER_SETS, ids=lambda s: f"{len(s)}-scales")
def test_mp_lower_tail_is_the_leading_power(scales):
    # x = 1e-17 min(s): the relative corrections (sum x**2/s_i**2 ~ n 1e-34) are far below the
    # 30 digits asked for, so the leading power is the value itself
    n = len(scales)
    fr = [Fraction(s) for s in scales]
    x = min(fr) / 10**17
    got = RayleighSum(scales).cdf(x, dps=30)
    with mpmath.workdps(60), thread_mp().workdps(60):
        ref = _mpf(x) ** (2 * n) / mpmath.factorial(2 * n)
        for s in fr:
            ref /= _mpf(s) ** 2
        assert abs(got / ref - 1) < mpmath.mpf(10) ** -29


def test_probability_keeps_its_digits_far_in_the_tail():
    # E = x**2/(2 V) = 1e12: exp(-E) needs 13 guard digits on top of the 15 of the quadrature
    S = RayleighSum(["1", "1", "1"])
    x = "2449489.742783178"
    res = S.probability(x, dps=20)
    with mpmath.workdps(60), thread_mp().workdps(60):
        ref = mpmath.exp(S.logsf(x, dps=45))
        assert abs(res.value / ref - 1) < mpmath.mpf(10) ** -20


def test_a_sympy_threshold_gets_its_guard_digits():
    # x = sqrt(2) 1e9 (E ~ 3e17): the guard digits for exp(-E) come from the value of x (they
    # used to be 0 for an expression that is not a rational, losing 2 of the 20 digits)
    S = RayleighSum([1, 1, 1])
    x = sympy.sqrt(2) * 10**9
    got = S.sf(x, dps=20)
    with mpmath.workdps(60), thread_mp().workdps(60):
        ref = mpmath.exp(S.logsf(x, dps=60))
        assert abs(got / ref - 1) < mpmath.mpf(10) ** -20


def test_exponent_cap_and_negative_thresholds():
    S = RayleighSum(["10"])   # V = 100: E = x**2/200
    x = "2e155"               # E = 2e308 > MAX_EXPONENT (float max)
    assert 2e308 > MAX_EXPONENT > 1e308
    assert_refuses(S.sf, x, dps=15, arg="x", value="E ~ 2.0e+308",
                   allowed="the cap MAX_EXPONENT")
    with pytest.raises(ValueError, match=r"E ~ 2\.0e\+308 above"):
        S.probability(x, dps=15)
    assert S.logsf(x, dps=15) < -1e308   # log sf has no cap
    # a huge negative threshold is sf = 1 (no exponent at all)
    assert S.sf("-2e155", dps=15) == 1 and S.cdf("-2e155", dps=15) == 0
    # below the cap (E = 1.8e306 here) the guard digits follow log10(E)
    assert S.logsf("1.9e154", dps=15) < 0


def test_mp_logsf_far_below_the_median_keeps_its_relative_accuracy():
    """log P(S > x) = log1p(-P(S <= x)) where the cdf is ~1e-20 (log m - E would cancel)."""
    S = RayleighSum(["0.5", "0.3", "0.2"])
    x = "1e-8"
    c = S.cdf(x, dps=60)
    assert c < mpmath.mpf(10) ** -40
    ref = -c   # log1p(-c) = -c (1 + c/2 + ...): c/2 is far below 30 digits
    got = S.logsf(x, dps=30)
    assert abs(got / ref - 1) < mpmath.mpf(10) ** -29


def test_exponent_cap_error_quotes_E_to_three_digits():
    S = RayleighSum(["0.5", "0.3", "0.2"])
    x = 10**155
    with mpmath.workprec(53), thread_mp().workprec(53):
        e = mpmath.mpf(x) ** 2 / (2 * mpmath.mpf("0.38"))
    assert e > MAX_EXPONENT
    with pytest.raises(ValueError) as info:
        S.sf(x, dps=20)
    msg = str(info.value)
    assert f"E ~ {mpmath.nstr(e, 3)} above the cap MAX_EXPONENT" in msg
    assert msg.endswith("guard digits); logsf has no cap")
    assert S.logsf(x, dps=20) < -e * (1 - mpmath.mpf(10) ** -10)
