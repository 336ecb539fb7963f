"""Two Rayleigh scales (the closed form of eq. 27) on arrays that straddle the median, in the
float64 and the mpmath paths, against the closed form written independently in
:mod:`tests.reference.forcing` at 20 extra digits: every kind (sf, cdf, pdf, logsf, logcdf),
both sides of the median in one array, the far upper tail (where ``logcdf = -sf`` is below an
ulp of 1) and the near-zero lower tail (where ``logsf = -cdf``), and the error estimates of
:meth:`RayleighSum.probability` (they cover the true error, never 0 in the body)."""

from __future__ import annotations

import math
import time

import mpmath
import numpy as np
import pytest

from symhx.forcing import RayleighSum
from tests.reference.forcing import pair_pdf, pair_tail, pair_value

EPS = float(np.finfo(float).eps)

#: unequal and equal pairs, a spread of 40
PAIRS = [(1.0, 1.0), (1.0, 0.3), (2.0, 0.05)]


def _grid(a: float, b: float) -> np.ndarray:
    """Thresholds from 1e-3 of the smaller scale to E ~ 300, an uneven number on each side of
    the median (so a mask of one side cannot stand in for the other)."""
    sd = math.hypot(a, b)
    return np.array([1e-3 * min(a, b), 0.05 * sd, 0.4 * sd, 0.9 * sd, 1.3 * sd, 1.8 * sd,
                     3.0 * sd, 6.0 * sd, 12.0 * sd, 24.0 * sd])


@pytest.mark.parametrize("a, b", PAIRS)
@pytest.mark.parametrize("kind", ["sf", "cdf", "pdf", "logsf", "logcdf"])
def test_pair_float64_is_the_closed_form_on_both_sides_of_the_median(a, b, kind):
    """One array across the median gives each entry to a few ulp (times the exponent E of
    the tail, whose rounding the closed form carries), logs to a few ulp absolute near 0."""
    S = RayleighSum([a, b])
    x = _grid(a, b)
    got = getattr(S, kind)(x)
    assert got.shape == x.shape
    var = a * a + b * b
    for xi, g in zip(x, got, strict=True):
        ref = pair_value(a, b, float(xi), kind)
        big_e = xi * xi / (2 * var)
        with mpmath.workdps(40):
            err = abs(mpmath.mpf(float(g)) - ref)
            scale = abs(ref) if not kind.startswith("log") else max(abs(ref), 1e-300)
            tol = 16 * EPS * (3 + 2 * big_e) * scale
            assert err <= tol, (kind, a, b, xi, float(g), mpmath.nstr(ref, 20))
        # each entry is the value it has alone
        assert getattr(S, kind)(float(xi)) == g


@pytest.mark.parametrize("a, b", PAIRS)
def test_pair_float64_logs_keep_relative_accuracy_in_both_far_tails(a, b):
    """Far above the median ``log P(S <= x) = log1p(-sf)`` is ``-sf`` (far below an ulp of 1,
    not 0); near zero ``log P(S > x) = -cdf`` likewise."""
    S = RayleighSum([a, b])
    sd = math.hypot(a, b)
    for x in (10.0 * sd, 14.0 * sd):
        ref = pair_value(a, b, x, "sf")
        assert ref < 1e-17
        got = S.logcdf(x)
        assert got < 0
        assert abs(got + float(ref)) <= 1e-12 * float(ref), (x, got, float(ref))
    x = 1e-3 * min(a, b)
    ref = pair_value(a, b, x, "cdf")
    assert ref < 1e-12
    got = S.logsf(x)
    assert abs(got + float(ref)) <= 1e-12 * float(ref), (x, got, float(ref))


@pytest.mark.parametrize("a, b", PAIRS)
@pytest.mark.parametrize("tail", ["upper", "lower"])
def test_pair_float64_error_estimate_covers_the_error_and_is_never_zero(a, b, tail):
    """``probability(x, tail)``'s error estimate is at least the true error and positive
    (at least the half ulp of a rounded result) on both sides of the median."""
    S = RayleighSum([a, b])
    kind = "sf" if tail == "upper" else "cdf"
    for x in _grid(a, b)[1:8]:
        res = S.probability(float(x), tail=tail)
        ref = pair_value(a, b, float(x), kind)
        with mpmath.workdps(40):
            true = abs(mpmath.mpf(res.value) - ref)
        assert res.error > 0, (tail, x)
        assert res.error >= float(true), (tail, x, res.error, float(true))
        assert res.error <= 1e-13 * max(res.value, 1e-300) * (1 + x * x), (tail, x)


@pytest.mark.parametrize("a, b", [(1, 1), ("0.3", "1")])
@pytest.mark.parametrize("kind", ["logsf", "logcdf"])
def test_pair_mp_logs_meet_dps_on_both_sides_of_the_median_and_in_both_far_tails(a, b, kind):
    """``logsf`` and ``logcdf`` at 20 digits (relative) from near zero (where ``logsf`` is
    ``-cdf``, ~1e-30) across the median to the far upper tail (``logcdf = -sf``, ~1e-40)."""
    S = RayleighSum([a, b])
    af, bf = float(a), float(b)
    sd = math.hypot(af, bf)
    for x in (1e-7, 0.5 * sd, 1.1 * sd, 1.25 * sd, 1.6 * sd, 14 * sd):
        got = getattr(S, kind)(x, dps=20)
        with mpmath.workdps(60):
            am, bm, xm = mpmath.mpf(a), mpmath.mpf(b), mpmath.mpf(x)
            sf = pair_tail(xm, am, bm, True)
            cdf = pair_tail(xm, am, bm, False)   # each tail to relative accuracy
            if kind == "logsf":
                ref = mpmath.log(sf) if sf < 0.5 else mpmath.log1p(-cdf)
            else:
                ref = mpmath.log(cdf) if cdf < 0.5 else mpmath.log1p(-sf)
            assert abs(got - ref) <= mpmath.mpf(10) ** -19 * abs(ref), (kind, x, got, ref)


@pytest.mark.parametrize("a, b", [("0.1", "0.1"), ("0.3", "0.07"), ("2", "0.5")])
@pytest.mark.parametrize("kind", ["sf", "cdf", "pdf"])
def test_pair_mp_meets_dps_on_both_sides_of_the_median(a, b, kind):
    """sf, cdf and the density at 20 digits (relative) on both sides of the median, with
    scales below and above 1 (thresholds below and above 1 on either side)."""
    S = RayleighSum([a, b])
    sd = math.hypot(float(a), float(b))
    for q in (0.02, 0.3, 0.8, 1.2, 1.7, 3.0, 6.0):
        x = q * sd
        got = getattr(S, kind)(x, dps=20)
        with mpmath.workdps(60):
            am, bm, xm = mpmath.mpf(a), mpmath.mpf(b), mpmath.mpf(x)
            ref = (pair_pdf(xm, am, bm) if kind == "pdf"
                   else pair_tail(xm, am, bm, kind == "sf"))
            assert abs(got - ref) <= mpmath.mpf(10) ** -19 * abs(ref), (kind, x, got, ref)


def test_pair_float64_on_a_long_array_is_entrywise_and_linear_in_its_length():
    """Thresholds are evaluated in chunks: 40,000 of them (three chunks) give each entry's own
    value, across the chunk boundaries, in linear time (~10 ms; a quadratic walk takes
    minutes)."""
    S = RayleighSum([1.0, 0.3])
    x = np.linspace(0.05, 6.0, 40_000)
    t0 = time.perf_counter()
    got = S.sf(x)
    assert time.perf_counter() - t0 < 5.0
    for i in (0, 16_383, 16_384, 32_767, 32_768, 39_999):
        assert got[i] == S.sf(float(x[i])), i
