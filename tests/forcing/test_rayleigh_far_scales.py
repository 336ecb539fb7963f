"""A scale more than 1e100 times the threshold (three or more scales, or a pair out of the
closed form's range) is in its power regime: ``RayleighSum`` takes it there, and each kind
keeps its relative accuracy. Checked against :func:`tests.reference.forcing.three_rayleigh_tail`
(the largest scale's exact density integrated against the closed-form lower tail of the
other two, at 30 digits, two rule orders that must agree); the density against a central
difference of that reference."""

from __future__ import annotations

import mpmath
import numpy as np

from symhx.forcing import RayleighSum
from tests.reference.forcing import three_rayleigh_tail


def test_a_scale_beyond_1e100_x_keeps_every_kind_accurate():
    scales = [1e100, 1.0, 0.5]   # 1e100 / x: beyond the ratio at both thresholds
    S = RayleighSum(scales)
    x = np.array([1.0, 2.0])
    got = {k: getattr(S, k)(x) for k in ("sf", "cdf", "pdf", "logsf", "logcdf")}
    for i, xv in enumerate(x):
        with mpmath.workdps(30):
            cdf = three_rayleigh_tail(scales, float(xv), False)
            assert 0 < cdf < 1e-150
            assert abs(got["cdf"][i] / cdf - 1) < 1e-12, (scales, xv)
            assert abs(got["logcdf"][i] - mpmath.log(cdf)) < 1e-12 * abs(mpmath.log(cdf))
            assert got["sf"][i] == 1.0
            assert abs(got["logsf"][i] / -cdf - 1) < 1e-12, (scales, xv)
            if i == 0:   # the density: a central difference of the reference (h**2 ~ 1e-12)
                h = mpmath.mpf(xv) * mpmath.mpf(10) ** -6
                pdf = (three_rayleigh_tail(scales, xv + h, False)
                       - three_rayleigh_tail(scales, xv - h, False)) / (2 * h)
                assert abs(got["pdf"][i] / pdf - 1) < 1e-9, (scales, xv)


def test_log_cdf_with_a_scale_beyond_1e100_x_below_the_float_range():
    """``P(S <= x)`` below the smallest float64 (1e-400 here): its log is still the log of the
    exact value (the scale's power regime taken in logs), the cdf underflows to 0."""
    scales = [1e200, 1.0, 0.5]
    S = RayleighSum(scales)
    x = np.array([1.0, 2.0])
    got = S.logcdf(x)
    assert S.cdf(x).tolist() == [0.0, 0.0]
    for i, xv in enumerate(x):
        with mpmath.workdps(30):
            ref = mpmath.log(three_rayleigh_tail(scales, float(xv), False))
            assert ref < -900
            assert abs(got[i] - ref) < 1e-13 * abs(ref), (xv, got[i], ref)
