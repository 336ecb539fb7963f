"""The routes inside ``RayleighSum`` (``symhx.forcing.rayleigh``): which evaluation a threshold
takes (the tail integrated is the one below about 1/2, the Laplace region, the rescaling of
extreme magnitudes, the limits at zero and at subnormal thresholds), the order and repetition of
the scales, the group functions at and below zero, the refusals with their way out, and silence
under any numpy error state."""

from __future__ import annotations

import mpmath
import numpy as np
import pytest

from symhx._mpctx import mp as thread_mp
from symhx.forcing import RayleighSum
from symhx.forcing import rayleigh as ray
from symhx.forcing.kernels_mp import MAX_EXPONENT
from tests.harness.errors import assert_refuses


def test_float_routes_under_any_numpy_error_state():
    # underflow, division by zero and overflow are expected inside (tiny x, huge x, subnormal
    # ratios): every float64 entry point handles them itself, whatever the caller's error state
    xs = np.array([5e-324, 1e-310, 1e-100, 1e-5, 0.7, 30.0, 1e5, 1e12])
    for sc in ([1.0], [1.0, 0.5], [1.0, 0.5, 0.3], [1e-170, 2e-170, 3e-170]):
        S = RayleighSum(sc)
        x = xs * sc[0]
        plain = {k: getattr(S, k)(x) for k in ("sf", "cdf", "pdf", "logsf", "logcdf")}
        with np.errstate(all="raise"):
            for k, v in plain.items():
                np.testing.assert_array_equal(getattr(S, k)(x), v)


# ------------------------------------------------------------------ route decisions
@pytest.mark.parametrize(("scales", "x"), [
    ([1.0, 1.0, 1.0], 0.5), ([1.0, 1.0, 1.0], 3.0), ([1.0, 1.0, 1.0], 5.0),
    ([1.0, 1.0, 1.0], 40.0), ([0.5, 0.2], 0.3), ([0.5, 0.2], 2.0), ([0.5], 0.5), ([0.5], 0.7),
    ([1.0, 1.0, 1.0], 0.0), ([1.0, 1.0, 1.0], -1.0),
    ([1e-200, 2e-200, 3e-200], 1e-201), ([1e-200, 2e-200, 3e-200], 0.5),
    ([1e-200, 2e-200, 3e-200], 0.0), ([1e-200, 2e-200, 3e-200], -1.0), ([1e200, 1e200], 1e199),
    ([1e-150, 1e-150], 1e-151), ([1e150, 1e150, 1e150], 1e149), ([5e149, 5e149, 5e149], 1e150),
    ([5e149, 5e149, 5e149], 9e149),
])
def test_the_tail_integrated_keeps_both_tails_accurate(scales, x):
    """The tail below about 1/2 is the one evaluated (from the mean on the upper one), the
    other is ``1 -`` it: both tails (and both logs) at 20 digits agree with 40 digits to 20
    digits on both sides of the median, at scales near and beyond the float64 range."""
    S = RayleighSum(scales)
    with mpmath.workdps(20), thread_mp().workdps(20):
        capped = x > 0 and mpmath.mpf(x) ** 2 / (2 * mpmath.fsum(mpmath.mpf(s) ** 2
                                                                 for s in scales)) > MAX_EXPONENT
    for kind in ("sf", "cdf", "logsf", "logcdf"):
        if capped and kind in ("sf", "cdf", "logcdf"):   # exp(-E) beyond MAX_EXPONENT
            assert_refuses(getattr(S, kind), x, dps=20, arg="x", allowed="MAX_EXPONENT")
            continue
        lo, hi = getattr(S, kind)(x, dps=20), getattr(S, kind)(x, dps=40)
        with mpmath.workdps(60), thread_mp().workdps(60):
            if hi == 0 or mpmath.isinf(hi):
                assert lo == hi, (kind, lo, hi)
            else:
                assert abs(lo / hi - 1) < mpmath.mpf(10) ** -19, (kind, lo, hi)


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

    # scales spread over 30 orders of magnitude have a float64 log sf at every threshold: at
    # 1e32 (beyond x max(s) = 1e30, short of the Laplace regime) it is that of the largest
    # scale alone to the last bit, as the bracket log P(R1 > x) <= log sf <= log P(R1 > x - a)
    # + P(R2 + R3 > a), a = 1e-28, a relative width of 2e-60, says
    S = RayleighSum([1, 1e-30, 1e-30])
    got = S.logsf(np.array([1.0, 1e32]))
    assert abs(got[1] / -0.5e64 - 1) < 4.5e-16
    assert abs(got[0] / float(S.logsf(1, dps=30)) - 1) < 1e-15
    assert S.logsf(np.array([1e36]))[0] < -1e71   # the Laplace regime has its value
    assert_refuses(RayleighSum([1, Fraction(10) ** 400]).sf, 1.0, arg="scales[1]",
                   value="1.0e+400", allowed=["outside the float64 range", "use dps="])
    assert_refuses(RayleighSum([1, 2, "1e-400"]).mean, arg="scales[2]", value="1.0e-400",
                   allowed=["outside the float64 range", "use dps="])


@pytest.mark.parametrize("kind, want", [("sf", 1), ("pdf", 0)])
def test_sum_at_zero_is_the_limit(kind, want):
    """At a threshold 0 (which the routes can meet by rounding): ``P(S > 0) = 1``, density 0,
    ``P(S <= 0) = 0``, in the mpmath and the float64 evaluation of three scales."""
    from fractions import Fraction

    scales = [Fraction(s) for s in ("0.5", "0.3", "0.2")]
    with mpmath.workdps(30), thread_mp().workdps(30):
        assert ray._mp_sum(scales, Fraction(0), kind, 20) == (want, 0)
        assert ray._mp_sum(scales, Fraction(0), "cdf", 20) == (0, 0)
    assert ray._float_eval([0.5, 0.3, 0.2], np.array([0.0]), kind)[0][0] == want
    assert ray._float_eval([0.5, 0.3, 0.2], np.array([0.0]), "cdf")[0][0] == 0.0


# ------------------------------------------------------------------ order and repetition
def test_the_order_and_repetition_of_the_scales_does_not_matter():
    """The sum is symmetric in its scales: any order of the same scales gives the same values,
    bit for bit (equal scales are evaluated once, with their multiplicity), float64 and mpmath;
    and a repeated scale is the same as listing it twice."""
    x = np.array([0.3, 1.5, 4.0])
    for sets in ([[3, 2, 1], [1, 2, 3], [2, 3, 1]], [[1, 1, 2, 2], [2, 1, 2, 1], [1, 2, 2, 1]],
                 [[5, 4, 3, 2, 1], [1, 3, 5, 2, 4]]):
        base = RayleighSum(sets[0])
        for other in sets[1:]:
            S = RayleighSum(other)
            for kind in ("sf", "cdf", "pdf", "logsf", "logcdf"):
                assert np.array_equal(getattr(S, kind)(x), getattr(base, kind)(x)), (other, kind)
            assert S.sf(1.5, dps=20) == base.sf(1.5, dps=20)


# ------------------------------------------------------------------ group functions at t <= 0
@pytest.mark.parametrize("scales", [["0.5"], ["0.5", "0.3"]])
@pytest.mark.parametrize("t", ["0", "-0.25"])
def test_mp_group_functions_at_and_below_zero(scales, t):
    """A group (one Rayleigh or a pair) is >= 0: cdf 0, density 0 (also scaled), tail 1."""
    with mpmath.workdps(30), thread_mp().workdps(30):
        g = ray._MGroup([mpmath.mpf(s) for s in scales])
        tm = mpmath.mpf(t)
        assert g.cdf(tm) == 0 and g.pdf(tm) == 0 and g.mpdf(tm) == 0 and g.msf(tm) == 1


def test_float_array_mixing_the_laplace_region_with_ordinary_thresholds():
    """An array holding a threshold in the Laplace region (x min(s) >= 1e5 V) and an ordinary
    one: each entry as if evaluated alone, and against mpmath."""
    S = RayleighSum([1.0, 1.0, 1.0])
    x = np.array([64.0, 1e6, 2.0])
    for kind in ("sf", "cdf", "pdf", "logsf", "logcdf"):
        got = S._eval(x, kind, None)
        alone = [S._eval(float(v), kind, None) for v in x]
        assert list(got) == alone, kind
    ref = S.logcdf(64, dps=20)
    assert abs(S.logcdf(x)[0] / float(ref) - 1) < 1e-13
