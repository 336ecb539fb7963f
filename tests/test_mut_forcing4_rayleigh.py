"""RayleighSum (``symhx.forcing.rayleigh``): the small print the other Rayleigh tests left open.

Found by mutation testing (``scripts/mutation.py``): the float64 scales of the paper's default
forcing at a natural frequency other than 1 (where ``|omega**2 - 2| = 1`` hid a product for a
quotient), values of mixed kinds in one list (a float is its binary value, a decimal string its
decimal value, also when they share a list), the constant answers at ``x <= 0`` on the mpmath
routes, the grouping of five and more scales, the cached Gauss-Legendre rules, and the words of
the errors. References: the definition ``s = sqrt(2) sigma / |omega**2 - Omega**2|`` (eq. 25)
in exact rationals, Python's ``Fraction`` of a float, the rule's exactness on polynomials of
degree ``2n - 1``, and ``P(S > 0) = 1``.
"""

from __future__ import annotations

import math
from fractions import Fraction

import mpmath
import numpy as np
import pytest

from symhx.forcing import RayleighSum, rayleigh_scales
from symhx.forcing import rayleigh as ray
from symhx.forcing.kernels_mp import MAX_EXPONENT


# ------------------------------------------------------------------ scales (eq. 25)
@pytest.mark.parametrize("omega", [2.0, 0.5, 3.0, 1.25])
def test_float_scales_of_the_default_forcing_follow_eq25(omega):
    """Omega = sqrt(2) (the default): s_1 = sqrt(2) sigma / |omega**2 - 2|, at omegas where
    |omega**2 - 2| is not 1."""
    sigma = 0.3
    s0, s1 = rayleigh_scales(sigma, omega=omega)
    ref = math.sqrt(2) * Fraction(sigma) / abs(Fraction(omega) ** 2 - 2)
    assert s0 == pytest.approx(math.sqrt(2) * sigma, rel=1e-15)
    assert s1 == pytest.approx(float(ref), rel=1e-15)
    # and the float route agrees with the mpmath one
    m1 = rayleigh_scales(sigma, omega=omega, dps=30)[1]
    assert s1 == pytest.approx(float(m1), rel=1e-15)


RESONANCE = r"resonance Omega == omega \(infinite forced amplitude\)$"


def test_resonance_error_names_the_reason():
    with pytest.raises(ValueError, match=RESONANCE):
        rayleigh_scales(0.3, omega=2.0, Omega=2.0)
    with pytest.raises(ValueError, match=RESONANCE):
        rayleigh_scales(0.3, omega=2, Omega="2", dps=30)


# ------------------------------------------------------------------ values of mixed kinds
def test_a_float_in_a_list_of_scales_is_its_binary_value():
    """``[0.1, "1/3"]``: 0.1 is the double nearest 1/10 (as ``RayleighSum([0.1])`` reads it),
    not the decimal 1/10 that a string array would make of it."""
    S = RayleighSum([0.1, "1/3"])
    assert S._exact == (Fraction(0.1), Fraction(1, 3))
    assert S.sf(0.2, dps=30) == RayleighSum([Fraction(0.1), Fraction(1, 3)]).sf(0.2, dps=30)
    assert S.sf(0.2, dps=30) != RayleighSum(["0.1", "1/3"]).sf(0.2, dps=30)


def test_a_float_in_a_list_of_thresholds_is_its_binary_value():
    S = RayleighSum(["0.5", "0.3", "0.2"])
    got = S.sf([0.1, "1/3"], dps=30)
    assert got[0] == S.sf(0.1, dps=30)
    assert got[0] != S.sf("0.1", dps=30)   # the decimal 1/10 is a different threshold
    assert got[1] == S.sf(Fraction(1, 3), dps=30)


# ------------------------------------------------------------------ x <= 0 on the mpmath routes
@pytest.mark.parametrize("scales", [["0.7"], ["0.5", "0.3"], ["0.5", "0.3", "0.2"]])
@pytest.mark.parametrize("x", [0, -1, "-1/3"])
def test_mp_values_at_and_below_zero(scales, x):
    """S > 0 almost surely: P(S > x) = 1, P(S <= x) = 0 and no density for x <= 0."""
    S = RayleighSum(scales)
    assert S.sf(x, dps=20) == 1
    assert S.cdf(x, dps=20) == 0
    assert S.pdf(x, dps=20) == 0
    assert S.logsf(x, dps=20) == 0
    assert S.logcdf(x, dps=20) == -mpmath.inf


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


def test_mp_logsf_far_below_the_median_keeps_its_relative_accuracy():
    """log P(S > x) = log1p(-P(S <= x)) where the cdf is ~1e-20 (log m - E would cancel)."""
    S = RayleighSum(["0.5", "0.3", "0.2"])
    x = "1e-8"
    c = S.cdf(x, dps=60)
    assert c < mpmath.mpf(10) ** -40
    ref = -c   # log1p(-c) = -c (1 + c/2 + ...): c/2 is far below 30 digits
    got = S.logsf(x, dps=30)
    assert abs(got / ref - 1) < mpmath.mpf(10) ** -29


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


# ------------------------------------------------------------------ the words of the errors
def test_errors_name_x():
    S = RayleighSum([0.5, 0.3, 0.2])
    with pytest.raises(ValueError, match=r"^x must be finite"):
        S.sf(math.nan)
    with pytest.raises(ValueError, match=r"^x must be finite, got nan at index \(1,\)"):
        S.sf([1.0, math.nan])
    with pytest.raises(ValueError, match=r"^x must be finite, got nan at index \(1,\)"):
        S.sf(np.array([1.0, math.nan]))   # a float64 array: the same words as a list
    with pytest.raises(ValueError, match=r"^x must be a number"):
        S.cdf("abc")


def test_empty_scales_error():
    with pytest.raises(ValueError, match=r"^scales: need at least one Rayleigh scale"):
        RayleighSum([])


def test_exponent_cap_error_quotes_E_to_three_digits():
    S = RayleighSum(["0.5", "0.3", "0.2"])
    x = 10**155
    with mpmath.workprec(53):
        e = mpmath.mpf(x) ** 2 / (2 * mpmath.mpf("0.38"))
    assert e > MAX_EXPONENT
    with pytest.raises(ValueError) as info:
        S.sf(x, dps=20)
    msg = str(info.value)
    assert f"E ~ {mpmath.nstr(e, 3)} above the cap MAX_EXPONENT" in msg
    assert msg.endswith("guard digits); logsf has no cap")
    assert S.logsf(x, dps=20) < -e * (1 - mpmath.mpf(10) ** -10)


# ------------------------------------------------------------------ group functions at t <= 0
@pytest.mark.parametrize("scales", [["0.5"], ["0.5", "0.3"]])
@pytest.mark.parametrize("t", ["0", "-0.25"])
def test_mp_group_functions_at_and_below_zero(scales, t):
    """A group (one Rayleigh or a pair) is >= 0: cdf 0, density 0 (also scaled), tail 1."""
    with mpmath.workdps(30):
        g = ray._MGroup([mpmath.mpf(s) for s in scales])
        tm = mpmath.mpf(t)
        assert g.cdf(tm) == 0 and g.pdf(tm) == 0 and g.mpdf(tm) == 0 and g.msf(tm) == 1


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
