"""RayleighSum (``symhx.forcing.rayleigh``): the mpmath lower tail at every nesting depth, the
route decisions and the small print, each against something the package does not compute.

References: the leading power of the lower tail (``P(S <= x) = x**(2n)/((2n)! prod s_i**2)``
for ``x << min s``: each density is ``r/s**2`` near 0, and the n-fold convolution of ``r`` is
``x**(2n-1)/(2n-1)!``); the identity ``cdf + sf = 1`` between the two different integrands of the
mpmath routes (``_conv_mp`` integrates densities against cdfs, ``_conv_scaled_mp`` scaled
densities against scaled tails); scale invariance ``P(S(c s) <= c x) = P(S(s) <= x)``; closed
forms of the moments; the logarithm of the upper tail at twice the digits.
"""

from __future__ import annotations

import math
from fractions import Fraction

import mpmath
import numpy as np
import pytest
import sympy

from symhx.forcing import RayleighSum
from symhx.forcing.kernels_mp import MAX_EXPONENT
from symhx.forcing.rayleigh import _upper_half, rayleigh_sum_probability


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
    with mpmath.workdps(60):
        ref = _mpf(x) ** (2 * n) / mpmath.factorial(2 * n)
        for s in fr:
            ref /= _mpf(s) ** 2
        assert abs(got / ref - 1) < mpmath.mpf(10) ** -29


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
    with mpmath.workdps(60):
        assert abs(cdf + sf - 1) < mpmath.mpf(10) ** -30


def test_mp_five_scales_cdf_and_sf_sum_to_one():
    S = RayleighSum(["1", "0.9", "0.5", "0.3", "0.2"])
    cdf, sf = S.cdf("1", dps=12), S.sf("1", dps=12)
    assert 1e-4 < cdf < 1e-3
    with mpmath.workdps(40):
        assert abs(cdf + sf - 1) < mpmath.mpf(10) ** -12


def test_mp_cdf_is_scale_invariant_beyond_the_float_range():
    # scales 1e-200 (no float64 estimate of sf: the route guesses the upper half, finds sf ~ 1
    # and takes the cdf's own quadrature -- 1 - sf would cancel every digit)
    small = RayleighSum(["1e-200", "2e-200", "3e-200"]).cdf("1e-203", dps=25)
    unit = RayleighSum(["1", "2", "3"]).cdf("0.001", dps=25)
    assert 1e-24 < unit < 1e-22
    with mpmath.workdps(50):
        assert abs(small / unit - 1) < mpmath.mpf(10) ** -25
    big = RayleighSum(["1e200", "2e200", "3e200"]).sf("1e201", dps=25)
    with mpmath.workdps(50):
        assert abs(big / RayleighSum(["1", "2", "3"]).sf("10", dps=25) - 1) < mpmath.mpf(10) ** -25


# ------------------------------------------------------------------ route decisions
def _mp(v):
    return [mpmath.mpf(s) for s in v] if isinstance(v, list) else mpmath.mpf(v)


@pytest.mark.parametrize(("scales", "x", "want"), [
    # the float64 sf decides where it can be formed: True iff it is <= 0.55
    ([1.0, 1.0, 1.0], 0.5, False), ([1.0, 1.0, 1.0], 3.0, False), ([1.0, 1.0, 1.0], 5.0, True),
    ([1.0, 1.0, 1.0], 40.0, True), ([0.5, 0.2], 0.3, False), ([0.5, 0.2], 2.0, True),
    ([0.5], 0.5, False), ([0.5], 0.7, True),
    # x <= 0: sf = 1
    ([1.0, 1.0, 1.0], 0.0, False), ([1.0, 1.0, 1.0], -1.0, False),
    # scales or x where the float64 route is not tried: upper half whenever x > 0
    ([1e-200, 2e-200, 3e-200], 1e-201, True), ([1e-200, 2e-200, 3e-200], 0.5, True),
    ([1e-200, 2e-200, 3e-200], 0.0, False), ([1e-200, 2e-200, 3e-200], -1.0, False),
    ([1e200, 1e200], 1e199, True),
    # the limits are exclusive: 1e-150 and 1e150 themselves are not tried
    ([1e-150, 1e-150], 1e-151, True), ([1e150, 1e150, 1e150], 1e149, True),
    ([5e149, 5e149, 5e149], 1e150, True), ([5e149, 5e149, 5e149], 9e149, False),
])
def test_upper_half_decides_by_the_float64_sf(scales, x, want):
    if 1e-150 < min(scales) and max(scales) < 1e150 and 0 < x < 1e150:
        sf = RayleighSum(scales).sf(x, dps=20)   # the decision agrees with the true sf here
        assert (sf <= 0.5) == want
    assert _upper_half(_mp(scales), _mp(x)) is want


def test_cdf_picks_one_minus_sf_only_in_the_upper_half(monkeypatch):
    # far in the upper tail the cdf is 1 - sf (one sf quadrature, no cdf quadrature)
    import symhx.forcing.rayleigh as R

    calls = []
    orig = R._conv_mp

    def spy(*a):
        calls.append(a[1])
        return orig(*a)

    monkeypatch.setattr(R, "_conv_mp", spy)
    S = RayleighSum(["0.5", "0.3", "0.2"])
    far = S.cdf("4", dps=20)
    assert calls == []
    with mpmath.workdps(40):
        assert abs(far - (1 - S.sf("4", dps=30))) < mpmath.mpf(10) ** -20
    S.cdf("0.5", dps=20)
    assert calls


# ------------------------------------------------------------------ probability(): small print
def test_probability_names_its_arguments():
    S = RayleighSum([0.5, 0.3, 0.2])
    with pytest.raises(ValueError, match=r"^tail must be one of \['upper', 'lower'\], got 'both'$"):
        S.probability(1.0, tail="both")
    with pytest.raises(ValueError, match=r"^tail must be one of \['upper', 'lower'\], got 'x'$"):
        rayleigh_sum_probability([0.5, 0.3], 1.0, tail="x")
    with pytest.raises(ValueError, match=r"^x must be a number"):
        S.probability("abc")
    with pytest.raises(ValueError, match=r"^x must be a number"):
        S.probability("abc", dps=20)
    with pytest.raises(TypeError, match=r"^x must be a scalar here \(use sf/cdf for arrays\)$"):
        S.probability(np.array([1.0, 2.0]))


@pytest.mark.parametrize("scales", [[0.7], [0.5, 0.3], [0.5, 0.3, 0.2]])
def test_probability_at_and_below_zero_is_exact(scales):
    S = RayleighSum(scales)
    for x in (0.0, -1.0, "0", "-2"):
        # float64: the exact values, with the estimate of the rounding of the formula
        up, lo = S.probability(x), S.probability(x, tail="lower")
        assert up.value == 1.0 and 0 <= up.error < 1e-14
        assert lo.value == 0.0 and 0 <= lo.error < 1e-14
        up = S.probability(x, dps=20)
        assert up.value == 1 and up.error == 0
        lo = S.probability(x, tail="lower", dps=20)
        assert lo.value == 0 and lo.error == 0


def test_probability_method_and_error_estimate():
    assert RayleighSum([0.5, 0.3]).probability(1.0, dps=20).method == "closed form"
    assert (RayleighSum([0.5, 0.3, 0.2]).probability(1.0, dps=20).method
            == "nested Gauss-Legendre (1-D)")
    assert (RayleighSum([1, 0.9, 0.5, 0.3, 0.2]).probability(0.1).method
            == "nested Gauss-Legendre (2-D)")
    # one scale, lower tail below the median: the closed form; the estimate covers the true
    # error (mostly the rounding to 25 digits) and stays within the 25 digits asked for
    S = RayleighSum(["0.7"])
    res = S.probability("0.3", tail="lower", dps=25)
    with mpmath.workdps(60):
        true = -mpmath.expm1(-mpmath.mpf("0.09") / (2 * mpmath.mpf("0.49")))
        err = abs(res.value - true)
        assert err <= res.error <= mpmath.mpf(10) ** -25 * true


def test_probability_keeps_its_digits_far_in_the_tail():
    # E = x**2/(2 V) = 1e12: exp(-E) needs 13 guard digits on top of the 15 of the quadrature
    S = RayleighSum(["1", "1", "1"])
    x = "2449489.742783178"
    res = S.probability(x, dps=20)
    with mpmath.workdps(60):
        ref = mpmath.exp(S.logsf(x, dps=45))
        assert abs(res.value / ref - 1) < mpmath.mpf(10) ** -20


def test_a_sympy_threshold_gets_its_guard_digits():
    # x = sqrt(2) 1e9 (E ~ 3e17): the guard digits for exp(-E) come from the value of x (they
    # used to be 0 for an expression that is not a rational, losing 2 of the 20 digits)
    S = RayleighSum([1, 1, 1])
    x = sympy.sqrt(2) * 10**9
    got = S.sf(x, dps=20)
    with mpmath.workdps(60):
        ref = mpmath.exp(S.logsf(x, dps=60))
        assert abs(got / ref - 1) < mpmath.mpf(10) ** -20


def test_exponent_cap_and_negative_thresholds():
    S = RayleighSum(["10"])   # V = 100: E = x**2/200
    x = "2e155"               # E = 2e308 > MAX_EXPONENT (float max)
    assert 2e308 > MAX_EXPONENT > 1e308
    with pytest.raises(ValueError, match=r"^x: P\(S > x\) = exp\(-E\) with E ~ 2\.0e\+308 above "
                                         r"the cap MAX_EXPONENT"):
        S.sf(x, dps=15)
    with pytest.raises(ValueError, match=r"E ~ 2\.0e\+308 above"):
        S.probability(x, dps=15)
    assert S.logsf(x, dps=15) < -1e308   # log sf has no cap
    # a huge negative threshold is sf = 1 (no exponent at all)
    assert S.sf("-2e155", dps=15) == 1 and S.cdf("-2e155", dps=15) == 0
    # below the cap (E = 1.8e306 here) the guard digits follow log10(E)
    assert S.logsf("1.9e154", dps=15) < 0


# ------------------------------------------------------------------ moments and draws
def test_moments_with_scales_not_summing_to_one():
    sc = ["2", "0.5", "0.25"]
    S = RayleighSum(sc)
    assert S.mean() == pytest.approx(2.75 * math.sqrt(math.pi / 2), rel=2e-16)
    assert S.var() == pytest.approx((2 - math.pi / 2) * 4.3125, rel=4e-16)
    with mpmath.workdps(60):
        m = mpmath.sqrt(mpmath.pi / 2) * mpmath.mpf("2.75")
        v = (2 - mpmath.pi / 2) * mpmath.mpf("4.3125")
        assert abs(S.mean(dps=30) / m - 1) < mpmath.mpf(10) ** -30
        assert abs(S.var(dps=30) / v - 1) < mpmath.mpf(10) ** -30
    one = S.rvs(random_state=7)
    assert type(one) is float
    with pytest.raises(ValueError, match=r"^random_state must be"):
        S.rvs(random_state="seed")


def test_float_routes_beyond_the_float_range_after_rescaling():
    # a threshold that overflows once scaled with the scales (2**997 here): sf 0, cdf 1,
    # log sf -inf (it was inf - inf = nan); a density that underflows: 0; and none of it
    # raises under a caller's np.errstate(all="raise")
    for sc in ([1e-300], [1e-170, 2e-170, 3e-170]):
        S = RayleighSum(sc)
        x = np.array([1e12, 1e300])
        with np.errstate(all="raise"):
            assert np.array_equal(S.sf(x), [0.0, 0.0]) and np.array_equal(S.cdf(x), [1.0, 1.0])
            assert np.array_equal(S.logsf(x), [-np.inf, -np.inf])
            assert np.array_equal(S.pdf(x), [0.0, 0.0])
            assert np.array_equal(S.logcdf(x), [0.0, 0.0])
    with np.errstate(all="raise"):
        assert RayleighSum([1e300]).pdf(1e-300) == 0.0
    # the same point at dps: log sf is finite and below every float
    assert RayleighSum(["1e-300"]).logsf("1e12", dps=15) < -1e308


def test_mpmath_results_come_at_the_digits_asked_for():
    # the guard digits of the evaluation are not correct digits: every mpmath result is rounded
    # to dps (its mantissa fits the precision of dps digits), the estimate covers the rounding
    from symhx.forcing import impact_probability, log_no_impact_probability, no_impact_probability

    prec = mpmath.libmp.dps_to_prec(20)
    S = RayleighSum(["0.5", "0.3", "0.2"])
    for tail in ("upper", "lower"):
        res = S.probability("1", tail=tail, dps=20)
        assert res.value._mpf_[3] <= prec
        with mpmath.workdps(60):
            ref = S.sf("1", dps=40) if tail == "upper" else S.cdf("1", dps=40)
            assert abs(res.value - ref) <= res.error <= mpmath.mpf(10) ** -20 * ref
    for fn in (impact_probability, no_impact_probability, log_no_impact_probability):
        for kw in ({}, {"Omega": [2, "0.5"]}):
            v = fn("0.5", d="1.3", dps=20, **kw)
            assert v._mpf_[3] <= prec, (fn.__name__, kw)
            with mpmath.workdps(60):
                ref = fn("0.5", d="1.3", dps=40, **kw)
                assert abs(v / ref - 1) <= mpmath.mpf(10) ** -19


def test_forced_scales_with_the_papers_omega_and_resonance_messages():
    # Omega = None is the paper's Omega**2 = 2: s_1 = sqrt(2) sigma / |omega**2 - 2|, here with
    # omega = 2 (|4 - 2| = 2) so that dividing and multiplying differ
    from symhx.forcing.rayleigh import rayleigh_scales

    got = rayleigh_scales(0.5, omega=2.0)
    assert got[0] == pytest.approx(math.sqrt(2) * 0.5, rel=2e-16)
    assert got[1] == pytest.approx(math.sqrt(2) * 0.5 / 2, rel=2e-16)
    got = rayleigh_scales("0.5", omega="0.5", sigma1="0.25")   # |0.25 - 2| = 1.75
    assert got[1] == pytest.approx(math.sqrt(2) * 0.25 / 1.75, rel=4e-16)
    for dps in (None, 20):
        with pytest.raises(ValueError, match=r"^Omega: resonance Omega == omega \(infinite "
                                             r"forced amplitude\)$"):
            rayleigh_scales(0.5, omega=1.5, Omega=1.5, dps=dps)
        with pytest.raises(ValueError, match=r"^Omega\[1\]: resonance Omega == omega \(infinite "
                                             r"forced amplitude\)$"):
            rayleigh_scales(0.5, omega=1.5, Omega=[2, 1.5], dps=dps)


#: scale sets for the numpy error-state check: one to five scales, spread ones, and magnitudes
#: where the float64 routes rescale by a power of two
_ERRSTATE_SETS = [[1.0], [1.0, 0.5], [1.0, 0.5, 0.3], [1.0, 0.9, 0.5, 0.3, 0.2],
                  [1e8, 0.4, 1e-8], [1e-12, 1.0, 1.0, 1e-6], [1e20, 1.0, 1.0],
                  [1e10, 2e10, 3e10], [1e-170, 2e-170, 3e-170], [1e170, 2e170, 3e170],
                  [1e-300], [1e300]]


@pytest.mark.parametrize("scales", _ERRSTATE_SETS, ids=lambda s: f"{len(s)}x{s[0]:g}")
def test_every_float_route_is_silent_under_a_raising_error_state(scales):
    # tiny, subnormal, huge and beyond-the-range thresholds (relative to the largest scale and
    # absolute): the same values whatever the caller's np.errstate
    rel = np.array([0.0, 5e-324, 1e-200, 1e-9, 0.3, 1.0, 3.0, 30.0, 1e5, 1e12, 1e200])
    S = RayleighSum(scales)
    with np.errstate(over="ignore"):
        scaled = rel * scales[0]
    for x in (scaled[np.isfinite(scaled)], np.array([5e-324, 1e-300, 1e-100, 1.0, 1e100, 1e301])):
        with np.errstate(all="ignore"):
            plain = {k: getattr(S, k)(x) for k in ("sf", "cdf", "pdf", "logsf", "logcdf")}
        with np.errstate(all="raise"):
            for k, v in plain.items():
                np.testing.assert_array_equal(getattr(S, k)(x), v, err_msg=k)


@pytest.mark.parametrize("scales", [[3.0, 2.0], [3.0, 2.0, 1.0], [3.0, 2.0, 1.0, 0.5]])
def test_subnormal_thresholds_take_the_limit_at_zero(scales):
    # x = 5e-324: x / (sqrt(2) s) underflows to 0 for every scale, and the pair's closed forms
    # were 0/0 there (the cdf of two or three scales was nan); the true values underflow
    S = RayleighSum(scales)
    x = np.array([5e-324, 1e-323, 1e-320])
    with np.errstate(all="raise"):
        assert np.array_equal(S.cdf(x), [0.0, 0.0, 0.0])
        assert np.array_equal(S.sf(x), [1.0, 1.0, 1.0])
        assert np.array_equal(S.pdf(x), [0.0, 0.0, 0.0])
        assert np.array_equal(S.logsf(x), [0.0, 0.0, 0.0])
        assert np.all(S.logcdf(x) < -1400 * len(scales))


def test_float_route_refusals_name_the_value_and_the_way_out():
    from fractions import Fraction

    S = RayleighSum([1, 1e-30, 1e-30])   # quadrature range 1e30, Laplace regime from 1e35
    with pytest.raises(ValueError, match=r"^x = 1e\+32: log sf of Rayleigh scales spread over "
                                         r"more than 21 orders of magnitude is beyond the "
                                         r"float64 range; use dps=$"):
        S.logsf(np.array([1.0, 1e32]))
    assert S.logsf(np.array([1e36]))[0] < -1e71   # the Laplace regime has its value
    with pytest.raises(ValueError, match=r"^scales\[1\] = 1\.0e\+400 is outside the float64 range; "
                                         r"use dps=$"):
        RayleighSum([1, Fraction(10) ** 400]).sf(1.0)
    with pytest.raises(ValueError, match=r"^scales\[2\] = 1\.0e-400 is outside the float64 range; "
                                         r"use dps=$"):
        RayleighSum([1, 2, "1e-400"]).mean()
