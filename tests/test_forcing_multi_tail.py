"""Several forcing components far in the upper tail (``RayleighSum``, eq. 22).

Before: the float64 ``log sf`` was ``-inf`` wherever ``sf`` underflowed, the mpmath quadrature
raised at large ``E`` (``p = exp(-E)``) and the scales of the mpmath path had too few digits
for ``p`` at huge ``E``. References, none taken from the package:

(a) a sum with one negligible scale ``s3`` is bracketed by the two-Rayleigh closed form
    (re-derived here): ``sf_pair(x) <= sf_S(x) <= sf_pair(x - a) + P(R3 > a)``;
(b) the Laplace asymptotic of the tail (derived here): the density of the sum concentrates at
    ``r_i = x s_i**2/V`` (``V = sum s_i**2``), so ``log sf = -x**2/(2V) + (n-1) log(x/V) +
    sum log s_i - log(V)/2 + (n-1) log(2 pi)/2 + O(1/E)``; the ``O(1/E)`` is checked to shrink;
(c) composite Gauss-Legendre with panels placed here, at two orders that must agree;
(d) the float64 path against the mpmath path at twice the digits.
"""

from __future__ import annotations

import itertools
import math

import mpmath
import numpy as np
import pytest

from symhx import forcing as F
from symhx.forcing import RayleighSum


def rel(a, b, digits=80):
    with mpmath.workdps(digits):
        a, b = mpmath.mpf(a), mpmath.mpf(b)
        return abs(a / b - 1)


def log_pair_sf(x, a, b):
    """``log P(Ra + Rb > x)`` of the closed form of eq. (27) in log form (no exp(-E)):
    ``x_ = x^2/(2a^2)``, ``y_ = x^2/(2b^2)``, ``r = sqrt(x_ + y_)``, ``u = x_/r``, ``v = y_/r``,
    ``log p = -uv + log((v e^{-u^2} + u e^{-v^2} + sqrt(pi) u v (erf u + erf v))/r)``."""
    with mpmath.workdps(mpmath.mp.dps + 20):
        x, a, b = mpmath.mpf(x), mpmath.mpf(a), mpmath.mpf(b)
        xx, yy = x * x / (2 * a * a), x * x / (2 * b * b)
        r = mpmath.sqrt(xx + yy)
        u, v = xx / r, yy / r
        br = (v * mpmath.exp(-u * u) + u * mpmath.exp(-v * v)
              + mpmath.sqrt(mpmath.pi) * u * v * (mpmath.erf(u) + mpmath.erf(v))) / r
        return -u * v + mpmath.log(br)


def laplace(scales, x):
    """Leading Laplace term of ``log P(S > x)`` (see the module docstring), mpmath."""
    n = len(scales)
    s = [mpmath.mpf(c) for c in scales]
    x = mpmath.mpf(x)
    v = mpmath.fsum(c * c for c in s)
    return (-x * x / (2 * v) + (n - 1) * mpmath.log(x / v) + mpmath.fsum(mpmath.log(c) for c in s)
            - mpmath.log(v) / 2 + (n - 1) * mpmath.log(2 * mpmath.pi) / 2)


def forcing_scales(sigma, oms, digits):
    """``s_0 = sqrt(2) sigma``, ``s_i = sqrt(2) sigma/|1 - Omega_i**2|`` (omega = 1)."""
    with mpmath.workdps(digits):
        sg = mpmath.mpf(sigma)
        return [mpmath.sqrt(2) * sg] + [mpmath.sqrt(2) * sg / abs(1 - mpmath.mpf(o) ** 2)
                                        for o in oms]


# ------------------------------------------------------------------ (d) the reported bug
@pytest.mark.parametrize("sigma", [0.01, 3e-3, 1e-3, 1e-4, 1e-6])
def test_float_log_p_far_tail_is_finite_and_accurate(sigma):
    """Was -inf (E from ~2e3 to ~2e11); the float64 log p against the mpmath path."""
    got = F.log_impact_probability(sigma, Omega=[1.7, 2.2], d=1.0)
    ref = F.log_impact_probability(sigma, Omega=[1.7, 2.2], d=1.0, dps=32)
    assert math.isfinite(got)
    assert rel(got, ref) < 2e-15


def test_float_vs_mp_on_a_sigma_grid():
    """log p and log(1 - p) on a log grid of sigma (E from ~1e-4 to ~2e3), float64 vs 32 digits."""
    for sigma in np.logspace(-2, 2, 7):
        for fn in (F.log_impact_probability, F.log_no_impact_probability):
            got = fn(float(sigma), Omega=[1.7, 2.2], d=1.0)
            ref = fn(float(sigma), Omega=[1.7, 2.2], d=1.0, dps=32)
            if abs(ref) < mpmath.mpf("1e-308"):  # log(1 - p) = -5e-803 at sigma = 0.01
                assert got == 0.0
            else:
                assert rel(got, ref) < 1e-13, (sigma, fn.__name__)


# ------------------------------------------------------------------ (a) negligible scale
@pytest.mark.parametrize("x", [3, 30, 300, 3000])
def test_negligible_scale_bracket_mpmath(x):
    """Scales (0.7, 0.4, 1e-60): log sf at 50 digits inside the bracket of the pair closed form
    (width ~ 40e-60 x / V: far below the claim), up to E ~ 7e6."""
    s3 = mpmath.mpf("1e-60")
    S = RayleighSum(["0.7", "0.4", "1e-60"])
    got = S.logsf(x, dps=50)
    with mpmath.workdps(80):
        lo = log_pair_sf(x, "0.7", "0.4")
        hi = log_pair_sf(x - 40 * s3, "0.7", "0.4")  # + P(R3 > a) = e^-800: below 1e-300 of it
        slack = abs(lo) * mpmath.mpf(10) ** -49
        assert lo - slack <= got <= hi + slack


@pytest.mark.parametrize("x", [3.0, 30.0, 300.0, 3000.0, 3e4])
def test_negligible_scale_bracket_float(x):
    """The float64 log sf (E up to ~7e8) inside the bracket (relative width ~1e-16)."""
    S = RayleighSum([0.7, 0.4, 1e-15])
    got = S.logsf(x)
    with mpmath.workdps(40):
        lo = log_pair_sf(x, 0.7, 0.4)
        hi = log_pair_sf(mpmath.mpf(x) - 40 * mpmath.mpf(1e-15), 0.7, 0.4)
        slack = abs(lo) * mpmath.mpf(1e-14)
        assert lo - slack <= got <= hi + slack


# ------------------------------------------------------------------ (b) Laplace asymptotic
def test_laplace_error_shrinks_like_one_over_E():
    """mpmath quadrature vs the leading Laplace term: (log sf - laplace) * E tends to a constant
    (the next order is O(1/E)), from E = 1e2 to 1e5."""
    scales = ["0.5", "0.3", "0.2"]
    S = RayleighSum(scales)
    with mpmath.workdps(40):
        v = mpmath.mpf("0.38")
        prods = []
        for e in (100, 1000, 10000, 100000):
            x = mpmath.sqrt(2 * v * e)
            d = S.logsf(x, dps=30) - laplace(scales, x)
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
        assert rel(got, ref) < 4e-16, x
    assert S.sf(1.001 * edge) == 0.0 and S.cdf(1.001 * edge) == 1.0


# ------------------------------------------------------------------ (c) own quadrature
def ref_three_sf(x, s, n, panels=24):
    """P(A + R2 > x), A the pair (s[0], s[1]) in closed form, R2 (scale s[2]) by ``panels``
    uniform Gauss-Legendre panels of ``n`` nodes on [0, x] (the tail beyond x exactly)."""
    x = mpmath.mpf(x)
    s2 = mpmath.mpf(s[2])
    xs, ws = mpmath.mp.gauss_quadrature(n, "legendre")
    tot = mpmath.exp(-x * x / (2 * s2 * s2))
    pts = [x * k / panels for k in range(panels + 1)]
    for lo, hi in itertools.pairwise(pts):
        h, m = (hi - lo) / 2, (hi + lo) / 2
        for xi, wi in zip(xs, ws, strict=True):
            t = m + h * xi
            tot += h * wi * t / s2**2 * mpmath.exp(-t * t / (2 * s2 * s2)) * mpmath.exp(
                log_pair_sf(x - t, s[0], s[1]))
    return tot


@pytest.mark.parametrize("x", ["1", "4", "7"])
def test_three_scales_against_own_quadrature(x):
    """sf, cdf, log sf at moderate E (up to ~65): mpmath at 25 digits and float64."""
    s = ("0.5", "0.3", "0.2")
    with mpmath.workdps(40):
        a, b = ref_three_sf(x, s, 20), ref_three_sf(x, s, 28)
        assert rel(a, b) < 1e-32
        S = RayleighSum(list(s))
        assert rel(S.sf(x, dps=25), b) < 1e-24
        assert rel(S.cdf(x, dps=25), 1 - b) < 1e-24
        assert rel(S.logsf(x, dps=25), mpmath.log(b)) < 1e-24
        assert rel(S.sf(float(x)), b) < 2e-14
        assert rel(S.logsf(float(x)), mpmath.log(b)) < 1e-15
        assert rel(S.logcdf(float(x)), mpmath.log1p(-b)) < 1e-14


# ------------------------------------------------------------------ mpmath at large E
def test_mpmath_large_E_converges_at_60_digits():
    """The reported traceback (sigma = 1e-4, E ~ 1.9e7, 60 digits): now a value, consistent with
    30 digits and with the Laplace term to its O(1/E) bound."""
    got = F.log_impact_probability("1e-4", Omega=["1.7", "2.2"], d="1", dps=60)
    lo = F.log_impact_probability("1e-4", Omega=["1.7", "2.2"], d="1", dps=30)
    assert rel(got, lo) < 1e-29
    with mpmath.workdps(80):
        lap = laplace(forcing_scales("1e-4", ["1.7", "2.2"], 80), 1)
        e = -lap
        assert abs(got - lap) < 10 / e


def test_scales_carry_digits_for_huge_E():
    """p = exp(-E) with E ~ 1.9e29 at 20 digits: the Laplace term is exact to ~1e-29 there, and
    scales with only dps + 15 digits would leave a relative error ~E 1e-35 ~ 1e-5."""
    got = F.impact_probability("1e-15", Omega=["1.7", "2.2"], d="1", dps=20)
    with mpmath.workdps(90):
        ref = mpmath.exp(laplace(forcing_scales("1e-15", ["1.7", "2.2"], 90), 1))
        assert rel(got, ref, 90) < 1e-19
    lg = F.log_impact_probability("1e-15", Omega=["1.7", "2.2"], d="1", dps=20)
    with mpmath.workdps(90):
        assert rel(lg, mpmath.log(ref), 90) < 1e-19


def test_cap_and_uncapped_log():
    """Beyond MAX_EXPONENT p needs more guard digits than the cap allows: a clear ValueError;
    log p has no cap (it never forms exp(-E))."""
    with pytest.raises(ValueError, match="MAX_EXPONENT"):
        F.impact_probability("1e-160", Omega=["1.7", "2.2"], d="1", dps=20)
    got = F.log_impact_probability("1e-160", Omega=["1.7", "2.2"], d="1", dps=20)
    with mpmath.workdps(40):
        ref = laplace(forcing_scales("1e-160", ["1.7", "2.2"], 40), 1)
        assert rel(got, ref) < 1e-19


# ------------------------------------------------------------------ RayleighSum directly
def test_direct_methods_tails_and_arrays():
    """sf, cdf, log sf, log cdf near 0, in the body and far in the tail (sf underflowing),
    float64 against 32 digits; arrays keep their shape and equal the scalar calls."""
    S = RayleighSum([0.5, 0.3, 0.2])
    xs = np.array([[1e-3, 0.05, 1.0], [5.0, 20.0, 40.0]])
    got = {k: getattr(S, k)(xs) for k in ("sf", "cdf", "logsf", "logcdf")}
    for idx in np.ndindex(xs.shape):
        x = float(xs[idx])
        with mpmath.workdps(40):  # the small one of sf, cdf at 32 digits, the other by 1 - it
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
                assert rel(got[kind][idx], ref[kind]) < tol, (kind, x)
    # the error estimate bounds the true error in the tail and is not vacuous
    res = S.probability(20.0)
    true = abs(res.value - S.sf(20, dps=32))
    assert true <= res.error < 1e-12 * res.value
    res = S.probability(40.0, tail="lower")
    assert res.value == 1.0 and res.error < 1e-300


def test_float_scales_spread_far_apart():
    """Scales 1e25 apart: the pair's closed form (no quadrature) up to x/min(s) = 1e150, the
    bracket of (a) for three scales; beyond the quadrature range the Laplace regime, or short of
    it a clear error (use dps=)."""
    two = RayleighSum([1.0, 1e-25])
    for x in (10.0, 1e3, 1e20, 1e31):
        with mpmath.workdps(40):
            assert rel(two.logsf(x), log_pair_sf(x, 1.0, 1e-25)) < 1e-15, x
    three = RayleighSum([1.0, 0.5, 1e-25])
    for x in (10.0, 1e3, 1e5):
        with mpmath.workdps(40):
            lo = log_pair_sf(x, 1.0, 0.5)
            hi = log_pair_sf(mpmath.mpf(x) - 40 * mpmath.mpf(1e-25), 1.0, 0.5)
            assert lo - abs(lo) * 1e-14 <= three.logsf(x) <= hi + abs(lo) * 1e-14, x
    # x min(s) = 1e6 V: the Laplace regime (the third scale moves log P by O(10) of 4e61)
    with mpmath.workdps(40):
        assert rel(three.logsf(1e31), log_pair_sf(mpmath.mpf(1e31), 1.0, 0.5)) < 1e-15
    assert three.sf(1e31) == 0.0 and three.cdf(1e31) == 1.0
    # beyond the quadrature range but short of the Laplace regime: a clear error
    with pytest.raises(ValueError, match="use dps="):
        RayleighSum([1.0, 0.5, 1e-30]).logsf(1e31)


def test_float_lower_tail_log_cdf():
    """log P(S <= x) where the cdf underflows (huge sigma: was -inf, and nan from an overflow of
    the saddle width at sigma = 1e100), against the mpmath quadrature at 32 digits, on both
    sides of the switch to the leading power at x = 1e-9 min(s)."""
    for sigma in (1e40, 1e60, 1e100):
        got = F.log_no_impact_probability(sigma, Omega=[1.7, 2.2])
        ref = F.log_no_impact_probability(sigma, Omega=[1.7, 2.2], dps=32)
        assert rel(got, ref) < 1e-15, sigma
    assert 0 < F.no_impact_probability(1e40, Omega=[1.7, 2.2]) < 1e-240
    assert F.no_impact_probability(1e100, Omega=[1.7, 2.2]) == 0.0
    S = RayleighSum([1.0, 0.5, 0.3])
    xs = np.array([1e-5, 0.99e-9 * 0.3, 1.01e-9 * 0.3, 1e-100, 5e-324])
    got = S.logcdf(xs)
    for x, g in zip(xs, got, strict=True):
        assert rel(g, S.logcdf(float(x), dps=32)) < 1e-15, x


def test_far_tail_density_is_minus_the_derivative_of_sf():
    """The scaled density (its own quadrature) against a central difference of the scaled sf at
    E ~ 1.2e3 (both mpmath); the float64 density against the mpmath one at E ~ 5e2."""
    S = RayleighSum(["0.5", "0.3", "0.2"])
    with mpmath.workdps(40):
        x, h = mpmath.mpf(30), mpmath.mpf("1e-12")
        fd = (S.sf(x - h, dps=32) - S.sf(x + h, dps=32)) / (2 * h)
        pdf = S.pdf(x, dps=20)
        assert rel(pdf, fd) < 1e-17
        assert S.pdf(30.0) == 0.0  # 7.6e-510
        assert rel(S.pdf(20.0), S.pdf(20, dps=20)) < 1e-12  # ~1e-226


def test_small_scale_structure_resolved_at_30_digits():
    """Scales (3, 2, 0.7, 1e-4): the pair (0.7, 1e-4) has structure ``exp(-t**2/(2e-8))`` near
    t = 0 that the panels at 0.5, 2, 8 scales left at e**-32 (no convergence at 30 digits,
    ArithmeticError); now 20 and 30 digits agree and the float64 value matches."""
    S = RayleighSum(["3", "1e-4", "2", "0.7"])
    hi = S.logsf("7.35", dps=30)
    assert rel(S.logsf("7.35", dps=20), hi) < 1e-19
    assert rel(S.logsf(7.35), hi) < 1e-14


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
            assert rel(got, ref) < 1e-13, (kind, u)
            assert rel(got, getattr(base, kind)(u)) < 1e-13, (kind, u)
        with mpmath.workdps(30):
            assert rel(S.pdf(x), S.pdf(mpmath.mpf(x), dps=25)) < 1e-13
            assert rel(S.pdf(x) * c, base.pdf(u)) < 1e-13
    res = S.probability(5 * c)
    assert rel(res.value, base.sf(5.0)) < 1e-13 and res.error < 1e-13


def test_forced_scales_at_tiny_and_huge_frequencies():
    # |omega**2 - Omega**2| = |omega - Omega| (omega + Omega), divided one factor at a time:
    # omega = 1e-160, Omega = 2e-160 made Delta subnormal (1.1e-5 relative error), and omega =
    # 1e-200, Omega = 1e-199 made it 0 (ZeroDivisionError); the true scale 7e397 is +inf
    got = F.rayleigh_scales(0.5, sigma1=1e-300, omega=1e-160, Omega=2e-160)
    ref = F.rayleigh_scales(0.5, sigma1=1e-300, omega=1e-160, Omega=2e-160, dps=30)
    assert all(rel(g, r) < 1e-15 for g, r in zip(got, ref, strict=True))
    assert F.rayleigh_scales(0.5, omega=1e-200, Omega=1e-199)[1] == math.inf
    with mpmath.workdps(30):
        s = F.rayleigh_scales(0.5, omega=1e-200, Omega=1e-199, dps=30)[1]
        assert rel(s, mpmath.sqrt(2) * mpmath.mpf(0.5) / (mpmath.mpf(1e-199) ** 2
                                                          - mpmath.mpf(1e-200) ** 2)) < 1e-28
    # a forced scale beyond float64, or scales spread beyond what float64 squares: a clear
    # error, never NaN (1e-150 gave NaN before); the mpmath route answers
    with pytest.raises(ValueError, match=r"^a forced component's Rayleigh scale sigma1 / "
                                         r"\|omega\*\*2 - Omega\*\*2\| is beyond float64 here: "
                                         r"use dps=$"):
        F.impact_probability(0.5, omega=1e-200, Omega=[1e-199, 2.0])
    for om, Om in ((1e-200, 1e-199), (1e-150, 2e-150)):
        with pytest.raises(ValueError, match="use dps="):
            F.impact_probability(0.5, omega=om, Omega=[Om, 2.0])
        assert F.impact_probability(0.5, omega=om, Omega=[Om, 2.0], dps=20) == 1
    assert rel(F.impact_probability(0.5, omega=1e-50, Omega=[3e-50, 2.0]),
               F.impact_probability(0.5, omega=1e-50, Omega=[3e-50, 2.0], dps=20)) < 1e-15


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
        with mpmath.workdps(30):
            assert abs(got - ref) <= 4 * math.ulp(got), (K, float(got - ref))


def test_multi_component_p_far_out_keeps_its_digits():
    """p = exp(-E) with E ~ 2e17 (d = 1e9): a relative error eps of a scale moves p by 2 E eps,
    so the scales carry log10(E) more digits; with only the 15 guard digits p at dps = 20 was
    off by ~4e-18.  Reference: dps = 40 (there the guard digits alone would suffice)."""
    a = F.impact_probability(1, Omega=[1.7, 2.2], d="1e9", dps=20)
    b = F.impact_probability(1, Omega=[1.7, 2.2], d="1e9", dps=40)
    with mpmath.workdps(50):
        assert abs(a / b - 1) < mpmath.mpf(10) ** -20
