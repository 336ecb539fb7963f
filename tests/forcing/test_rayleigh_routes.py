"""The routes inside ``RayleighSum`` (``symhx.forcing.rayleigh``): which evaluation a threshold
takes (the upper half decided by the float64 sf, the Laplace region, the rescaling of extreme
magnitudes, the limits at subnormal thresholds), the grouping of the scales, the cached rules,
the group functions at and below zero, the refusals with their way out, and silence under any
numpy error state."""

from __future__ import annotations

import mpmath
import numpy as np
import pytest

from symhx.forcing import RayleighSum
from symhx.forcing import rayleigh as ray
from symhx.forcing.rayleigh import _upper_half
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

    S = RayleighSum([1, 1e-30, 1e-30])   # quadrature range 1e30, Laplace regime from 1e35
    assert_refuses(S.logsf, np.array([1.0, 1e32]), arg="x", value="1e+32",
                   allowed=["beyond the float64 range", "use dps="])
    assert S.logsf(np.array([1e36]))[0] < -1e71   # the Laplace regime has its value
    assert_refuses(RayleighSum([1, Fraction(10) ** 400]).sf, 1.0, arg="scales[1]",
                   value="1.0e+400", allowed=["outside the float64 range", "use dps="])
    assert_refuses(RayleighSum([1, 2, "1e-400"]).mean, arg="scales[2]", value="1.0e-400",
                   allowed=["outside the float64 range", "use dps="])


@pytest.mark.parametrize("kind, want", [("sf", 1), ("pdf", 0)])
def test_scaled_convolution_at_zero(kind, want):
    """The nested scaled integrand at a threshold 0: ``P(S > 0) exp(0) = 1``, density 0 (the
    inner quadratures can reach it by rounding of ``x - tau``)."""
    with mpmath.workdps(30):
        groups = [ray._MGroup(g) for g in ray.make_groups([mpmath.mpf(s) for s in
                                                           ("0.5", "0.3", "0.2")])]
        cs = ray._saddle_c(20, 3, 1.0)
        assert ray._conv_scaled_mp(groups, mpmath.mpf(0), kind, 8, cs) == want
        assert ray._conv_mp(groups, mpmath.mpf(0), 8, cs) == 0


# ------------------------------------------------------------------ groups
def test_make_groups_puts_the_leftover_single_second_to_last():
    """Adjacent pairs after sorting; from three groups on, a single scale goes second to last
    (the innermost integrand then is a pair's)."""
    assert ray.make_groups([3, 2, 1]) == [(3, 2), (1,)]
    assert ray.make_groups([1, 2, 3, 4]) == [(4, 3), (2, 1)]
    assert ray.make_groups([5, 4, 3, 2, 1]) == [(5, 4), (1,), (3, 2)]
    assert ray.make_groups([1, 7, 2, 6, 3, 5, 4]) == [(7, 6), (5, 4), (1,), (3, 2)]
    assert ray.make_groups([6, 5, 4, 3, 2, 1]) == [(6, 5), (4, 3), (2, 1)]


# ------------------------------------------------------------------ the cached rules
def test_mp_gauss_legendre_rule_from_an_empty_cache(monkeypatch):
    """A fresh rule (nothing cached) integrates polynomials of degree 2n - 1 exactly on [-1, 1]
    and is cached per (order, precision)."""
    monkeypatch.setattr(ray, "_MP_GL_CACHE", {})
    with mpmath.workdps(40):
        xs, ws = ray._mp_gl(7)
        assert len(xs) == len(ws) == 7
        for k in range(14):
            exact = mpmath.mpf(2) / (k + 1) if k % 2 == 0 else 0
            assert abs(mpmath.fsum(w * x**k for x, w in zip(xs, ws, strict=True)) - exact) \
                < mpmath.mpf(10) ** -38
        assert ray._mp_gl(7) is ray._MP_GL_CACHE[(7, mpmath.mp.prec)]
    S = RayleighSum(["0.5", "0.3", "0.2"])
    ref = S.sf(1, dps=25)
    monkeypatch.setattr(ray, "_MP_GL_CACHE", {})
    assert S.sf(1, dps=25) == ref


# ------------------------------------------------------------------ group functions at t <= 0
@pytest.mark.parametrize("scales", [["0.5"], ["0.5", "0.3"]])
@pytest.mark.parametrize("t", ["0", "-0.25"])
def test_mp_group_functions_at_and_below_zero(scales, t):
    """A group (one Rayleigh or a pair) is >= 0: cdf 0, density 0 (also scaled), tail 1."""
    with mpmath.workdps(30):
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
