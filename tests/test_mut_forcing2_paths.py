"""p, 1 - p, log p, log(1 - p) of one forcing component against an independent closed form.

Reference (written here, not taken from the package): with the Rayleigh scales
``S0 = 2 sigma**2``, ``S1 = 2 sigma1**2/(omega**2 - Omega**2)**2`` (squared) and
``f0(t) = t/S0 exp(-t**2/(2 S0))``,

    p = P(R0 > d) + int_0^d f0(t) exp(-(d - t)**2/(2 S1)) dt,

and the Gaussian product in the integrand is completed to a square in ``t`` (centre
``t* = d S0/(S0 + S1)``, curvature ``A = 1/(2 S0) + 1/(2 S1)``), so the integral is one
difference of exponentials plus one sum of ``erf``: a different formula from the package's
(``u, v`` form) evaluated at a precision far above the claim (``2 dps + 30`` digits plus the
digits of the exponent and of ``1 - p``). The reference is itself checked against
``mpmath.quad`` at a few points. Derivatives: ``mpmath.diff`` of the reference (numerical
differentiation of the independent formula at high precision).

Every assertion is a relative error computed inside ``workdps`` at a precision above the claim.
The grid reaches: float inputs (raw-libmp fast path) and exact decimal strings (the mpf-object
path), ``p`` and ``1 - p`` on both sides of 1/2, the logs (``log1p`` branches), the adaptive
``1 - p`` loop, guard digits at huge exponents (``sigma`` down to ``1e-100``), the mpmath
estimate where floats over/underflow, ``omega``, ``Omega``, ``d`` and ``sigma1`` away from their
defaults, and several components given as a list.
"""

from __future__ import annotations

import itertools
import math
from decimal import Decimal
from fractions import Fraction

import mpmath
import numpy as np
import pytest

from symhx import forcing as F
from symhx.forcing import kernels_mp as K
from symhx.forcing import probability as P
from symhx.forcing.rawmp import from_xy_raw

DPS = 20


def rel(a, b, digits=3 * DPS + 20):
    with mpmath.workdps(digits):
        a, b = mpmath.mpf(a), mpmath.mpf(b)
        if b == 0:
            return abs(a)
        return abs(a / b - 1)


def _mp(v):
    """An input as an mpf at the current precision (strings/Fractions exactly rounded)."""
    if isinstance(v, Fraction):
        return mpmath.mpf(v.numerator) / v.denominator
    return mpmath.mpf(v)


def squares(sigma, sigma1=None, omega=1, Omega=None):
    """``(S0, S1)``, the squared Rayleigh scales, at the current precision."""
    sg = _mp(sigma)
    om2 = 2 if Omega is None else _mp(Omega) ** 2
    delta2 = (_mp(omega) ** 2 - om2) ** 2
    s1 = sg if sigma1 is None else _mp(sigma1)
    return 2 * sg * sg, 2 * s1 * s1 / delta2


def _erf(z):
    """erf; as 1 - erfc for large z (mpmath's erf series is slow there, erfc is not)."""
    if z > 10**8:  # erfc(z) < exp(-1e16): far below every working precision here
        return mpmath.mpf(1)
    return 1 - mpmath.erfc(z) if z > 4 else mpmath.erf(z)


def _p_sq(S0, S1, d):
    """``P(R0 + R1 > d)`` by the completed square (positive terms up to one difference)."""
    A = 1 / (2 * S0) + 1 / (2 * S1)
    ts = d * S0 / (S0 + S1)
    C = d * d / (2 * (S0 + S1))
    sA = mpmath.sqrt(A)
    lin = (mpmath.exp(-C - A * ts * ts) - mpmath.exp(-C - A * (d - ts) ** 2)) / (2 * A)
    gauss = ts * mpmath.sqrt(mpmath.pi) / (2 * sA) * mpmath.exp(-C) * (
        _erf(sA * (d - ts)) + _erf(sA * ts))
    return mpmath.exp(-d * d / (2 * S0)) + (lin + gauss) / S0


def _work(S0, S1, d, dps):
    """Digits that make ``_p_sq`` and ``1 - _p_sq`` accurate far above ``dps``."""
    with mpmath.workdps(30):
        e = d * d / (2 * (S0 + S1))  # p ~ exp(-e): its digits before the point
        xy = (d * d / (2 * S0)) * (d * d / (2 * S1))
        lost = max(0, int(-mpmath.log10(xy)) + 2) if xy < 1 else 0
        expo = int(mpmath.log10(e)) + 2 if e > 1 else 0
    return 2 * dps + 30 + lost + expo


def ref_sq(S0, S1, d, dps=DPS):
    """``(p, q, log p, log q)`` for squared scales ``S0``, ``S1`` (mpf or numbers)."""
    with mpmath.workdps(60):
        w = _work(mpmath.mpf(S0), mpmath.mpf(S1), _mp(d), dps)
    with mpmath.workdps(w):  # a first pass measures the digits that 1 - p really loses
        q = 1 - _p_sq(mpmath.mpf(S0), mpmath.mpf(S1), _mp(d))
        w += max(0, int(-mpmath.log10(q)) + 10) if q > 0 else 2 * w
    with mpmath.workdps(w):
        S0, S1, d = mpmath.mpf(S0), mpmath.mpf(S1), _mp(d)
        p = _p_sq(S0, S1, d)
        q = 1 - p
        assert q > 0
        return p, q, mpmath.log(p), mpmath.log(q)


def ref(sigma, sigma1=None, omega=1, Omega=None, d=1, dps=DPS):
    with mpmath.workdps(3 * dps + 40 + 250):
        S0, S1 = squares(sigma, sigma1, omega, Omega)
        return ref_sq(S0, S1, d, dps)


def ref_dp(sigma, sigma1=None, omega=1, Omega=None, d=1, dps=DPS):
    """``dp/dsigma`` (total if ``sigma1`` is None, else partial at fixed ``sigma1``)."""
    p = ref(sigma, sigma1, omega, Omega, d, dps)[0]
    w = 2 * dps + 30
    with mpmath.workdps(w + 60):
        s = _mp(sigma)
        dd = _mp(d)

        def fp(t):
            S0, S1 = squares(t, t if sigma1 is None else sigma1, omega, Omega)
            if p > 0.5:  # d(1 - p) keeps its relative accuracy in the upper tail
                return -(1 - _p_sq(S0, S1, dd))
            return _p_sq(S0, S1, dd)

        return mpmath.diff(fp, s)


def test_reference_against_mpmath_quad():
    """The completed-square reference is the eq. 27 convolution (checked by mpmath.quad)."""
    for sigma, sigma1, Omega, d in [("0.3", None, None, 1), ("0.13", "0.4", "1.7", "1.3"),
                                    ("2", None, "3", "0.7")]:
        with mpmath.workdps(40):
            S0, S1 = squares(sigma, sigma1, 1, Omega)
            dd = _mp(d)
            conv = mpmath.quad(lambda t, a=S0, b=S1, c=dd: t / a * mpmath.exp(-t * t / (2 * a))
                               * mpmath.exp(-(c - t) ** 2 / (2 * b)), [0, dd / 2, dd])
            pq = mpmath.exp(-dd * dd / (2 * S0)) + conv
        assert rel(ref(sigma, sigma1, 1, Omega, d)[0], pq) < mpmath.mpf(10) ** -35


# ------------------------------------------------------------------ the public functions
FUNCS = {"p": F.impact_probability, "q": F.no_impact_probability,
         "logp": F.log_impact_probability, "logq": F.log_no_impact_probability}
SIGMAS = [float(s) for s in np.logspace(-2, 2, 17)]
RATIOS = [None, 0.1, 10.0]


def _check_all(sigma, sigma1=None, omega=1, Omega=None, d=1, dps=DPS, wants=FUNCS):
    r = ref(sigma, sigma1, omega, Omega, d, dps)
    tol = mpmath.mpf(10) ** -dps
    for want, val in zip(("p", "q", "logp", "logq"), r, strict=True):
        if want not in wants:
            continue
        got = FUNCS[want](sigma, sigma1=sigma1, omega=omega, Omega=Omega, d=d, dps=dps)
        assert isinstance(got, mpmath.mpf)
        assert rel(got, val) <= tol, (want, sigma, sigma1, omega, Omega, d,
                                      mpmath.nstr(rel(got, val), 3))


@pytest.mark.parametrize("ratio", RATIOS)
def test_dense_grid_decimal_strings_general_path(ratio):
    for s in SIGMAS:
        sd = str(Decimal(repr(s)))
        s1 = None if ratio is None else str(Decimal(repr(s * ratio)))
        _check_all(sd, s1)


@pytest.mark.parametrize("ratio", RATIOS)
def test_dense_grid_float_inputs_fast_path(ratio):
    for s in SIGMAS[::2]:
        _check_all(s, None if ratio is None else s * ratio)


@pytest.mark.parametrize("sigma", ["1e-100", "1e-9", "1e-7", "0.0013", "300", "1e5", "1e9",
                                   "1e30", "1e200"])
def test_extreme_sigma_guard_digits_and_both_tails(sigma):
    """Exponents uv up to 1e199 (guard digits), 1 - p down to 1e-800 (cancellation)."""
    _check_all(sigma)
    _check_all(sigma, sigma1="0.25")


@pytest.mark.parametrize("dps", [5, 15, 45])
def test_other_dps_and_parameters(dps):
    """omega, Omega, d and sigma1 away from the defaults (exact decimal inputs)."""
    for sigma, sigma1, omega, Omega, d in [
            ("0.07", None, "1.3", "1.7", "1.9"), ("0.7", "0.2", "0.6", "2.5", "0.45"),
            ("4.5", "30", "1.1", "0.3", "3"), ("45", None, "3", None, "0.8"),
            (Fraction(1, 3), Fraction(2, 7), Fraction(5, 4), Fraction(1, 3), Fraction(9, 7))]:
        _check_all(sigma, sigma1, omega, Omega, d, dps=dps)


def test_scales_far_apart():
    """``sigma1`` many orders of magnitude from ``sigma`` (float estimate's far-apart branch)."""
    for sigma, sigma1 in [("1e-8", "1e5"), ("1e5", "1e-8"), ("0.4", "1e-40"), ("1e-40", "0.4"),
                          ("1e40", "1e-3"), ("3e-3", "1e35"), ("1e60", "1e70")]:
        _check_all(sigma, sigma1)


def test_array_input_is_elementwise():
    sig = np.array([Fraction(1, 10), Fraction(3, 2), Fraction(40)], dtype=object)
    out = F.no_impact_probability(sig, d="1.5", dps=DPS)
    assert out.shape == (3,) and out.dtype == object
    for s, o in zip(sig, out, strict=True):
        assert rel(o, ref(s, d="1.5")[1]) <= mpmath.mpf(10) ** -DPS


def test_float64_path_is_the_closed_form():
    s = np.array([0.02, 0.3, 7.0])
    for want, fn in FUNCS.items():
        got = fn(s, sigma1=0.5)
        assert got.dtype == float and got.shape == (3,)
        k = ("p", "q", "logp", "logq").index(want)
        for sv, g in zip(s, got, strict=True):
            assert rel(g, ref(float(sv), 0.5)[k]) < 1e-13


def test_resonance_is_an_error():
    for dps in (None, 20):
        with pytest.raises(ValueError, match="resonance"):
            F.impact_probability("0.3", omega="1.5", Omega="1.5", dps=dps)
    with mpmath.workdps(30):
        with pytest.raises(ValueError, match=r"^Omega: resonance Omega == omega \(infinite "
                                             r"forced amplitude\)$"):
            K.mp_xy_forcing(Fraction(1, 3), None, 3, 3, 1)
        for i, name in enumerate(("sigma", "sigma1", "omega", "Omega", "d")):
            args = [Fraction(1, 3), None, 1, None, 1]
            args[i] = -1
            with pytest.raises(ValueError, match=f"^{name} must be > 0, got -1$"):
                K.mp_xy_forcing(*args)


# ------------------------------------------------------------------ several components
def ref_three_gl(sigma, Oms, d, work, panels, nodes):
    """P(R0 + R1 + R2 > d): the pair (R0, R1) in closed form, R2 by ``panels`` Gauss-Legendre
    panels of ``nodes`` nodes each on [0, d] (the tail beyond d exactly)."""
    with mpmath.workdps(work):
        sg = _mp(sigma)
        S0 = 2 * sg * sg
        S1, S2 = (2 * sg * sg / (1 - _mp(o) ** 2) ** 2 for o in Oms)
        dd = _mp(d)
        pts = [dd * k / panels for k in range(panels + 1)]
        xs, ws = mpmath.mp.gauss_quadrature(nodes, "legendre")
        tot = mpmath.exp(-dd * dd / (2 * S2))
        for lo, hi in itertools.pairwise(pts):
            h, m = (hi - lo) / 2, (hi + lo) / 2
            for xi, wi in zip(xs, ws, strict=True):
                t = m + h * xi
                tot += h * wi * t / S2 * mpmath.exp(-t * t / (2 * S2)) * _p_sq(S0, S1, dd - t)
        return tot


def _ref_three(sigma, Oms, d, work):
    """:func:`ref_three_gl` at two rule orders that must agree beyond the claim."""
    out = [ref_three_gl(sigma, Oms, d, work, 16, n) for n in (20, 30)]
    with mpmath.workdps(work):
        assert abs(out[1] / out[0] - 1) < mpmath.mpf(10) ** -(DPS + 8)
    return out[1]


def test_several_components_every_want():
    """Two forcing components (the Rayleigh sum path) for p, 1 - p and both logs."""
    Oms = ["1.7", "2.2"]
    p = _ref_three("0.35", Oms, "1.2", 2 * DPS + 20)
    with mpmath.workdps(2 * DPS + 20):
        vals = {"p": p, "q": 1 - p, "logp": mpmath.log(p), "logq": mpmath.log(1 - p)}
    for want, fn in FUNCS.items():
        got = fn("0.35", Omega=Oms, d="1.2", dps=DPS)
        assert rel(got, vals[want]) <= mpmath.mpf(10) ** -(DPS - 1), want
        got_f = fn(0.35, Omega=[1.7, 2.2], d=1.2)
        assert isinstance(got_f, float)
        assert rel(got_f, vals[want]) < 1e-12, want
    arr = F.impact_probability(np.array([0.35, 0.35]), Omega=[1.7, 2.2], d=1.2)
    assert arr.shape == (2,) and arr.dtype == float and rel(arr[1], p) < 1e-12
    arr = F.impact_probability(np.array(["0.35"], dtype=object), Omega=Oms, d="1.2", dps=DPS)
    assert arr.shape == (1,) and arr.dtype == object
    assert rel(arr[0], p) <= mpmath.mpf(10) ** -(DPS - 1)


# ------------------------------------------------------------------ kernels, directly
@pytest.mark.parametrize("u, v", [("1e-9", "2e-9"), ("1e-4", "3e-4"), ("0.01", "0.5"),
                                  ("0.3", "0.7"), ("2", "5"), ("10", "0.1"), ("0.9", "0.05"),
                                  ("0.3", "0.3"), ("1e-20", "3e-20"), ("2e-12", "2e-12"),
                                  ("3e9", "5e9"), ("40", "70")])
def test_i2_i3_closed_forms_against_quadrature(u, v):
    """The positive integrals of the derivative (cancelling closed forms) to dps digits."""
    for dps in (15, 30):
        with mpmath.workdps(dps):
            uu, vv = mpmath.mpf(u), mpmath.mpf(v)
            i2, i3 = K.mp_i2(uu, vv), K.mp_i3(uu, vv)
            assert max(i2._mpf_[1].bit_length(), i3._mpf_[1].bit_length()) <= mpmath.mp.prec
        # the reference integrates at the same (rounded) u, v far above the claim
        # (z = -v + r t on t in [0, 1], r = u + v: an O(1) integrand for any r)
        with mpmath.workdps(2 * dps + 30):
            r = uu + vv
            t0 = vv / r  # the peak z = 0, width 1/r
            pts = sorted({mpmath.mpf(0), mpmath.mpf(1)} | {
                t0 + k / r for k in (-40, -8, -2, 0, 2, 8, 40) if 0 < t0 + k / r < 1})
            r2 = r**3 * mpmath.quad(
                lambda t, a=r, b=vv: t * (1 - t) * mpmath.exp(-(a * t - b) ** 2), pts)
            r3 = r**4 * mpmath.quad(
                lambda t, a=r, b=vv: t * t * (1 - t) * mpmath.exp(-(a * t - b) ** 2), pts)
        assert rel(i2, r2) <= 2 * mpmath.mpf(10) ** -dps, (u, v, dps)
        assert rel(i3, r3) <= 2 * mpmath.mpf(10) ** -dps, (u, v, dps)


@pytest.mark.parametrize("x, y", [("1e-30", "2e-30"), ("1e-6", "3e-3"), ("0.02", "0.05"),
                                  ("0.6", "0.9"), ("3", "0.2"), ("40", "50"), ("1e-12", "1e8"),
                                  ("1e-30", "1e30"), ("1e-60", "1e60"), ("3e50", "1e-80")])
def test_mp_q_from_xy_adaptive_loop(x, y):
    """``1 - p`` from ``(x, y)`` directly (the adaptive cancellation loop) to the precision."""
    for dps in (15, 40):
        with mpmath.workdps(dps):
            xm, ym = mpmath.mpf(x), mpmath.mpf(y)
            q = K.mp_q_from_xy(xm, ym)
            p = K.mp_p_from_xy(xm, ym)
            lp = from_xy_raw(xm._mpf_, ym._mpf_, mpmath.mp.prec, "logp", 0, False)
            assert q._mpf_[1].bit_length() <= mpmath.mp.prec
        # x = d**2/(2 S0), y = d**2/(2 S1) with d = 1
        with mpmath.workdps(3 * dps + 100):
            S0, S1 = 1 / (2 * xm), 1 / (2 * ym)
        rp, rq, rlp, _ = ref_sq(S0, S1, 1, dps)
        tol = 2 * mpmath.mpf(2) ** -mpmath.workdps(dps)(lambda: mpmath.mp.prec)()
        assert rel(q, rq) <= 8 * tol, (x, y, dps)
        assert rel(p, rp) <= 8 * tol
        assert rel(lp, rlp) <= 8 * tol * max(1, abs(float(1 / rlp)))


def test_mp_xy_forcing_definitions():
    with mpmath.workdps(40):
        x, y = K.mp_xy_forcing(Fraction(1, 5), Fraction(1, 3), Fraction(3, 2), Fraction(7, 10),
                               Fraction(6, 5))
        assert rel(x, mpmath.mpf(36) / 25 / (4 * mpmath.mpf(1) / 25)) < 1e-38
        delta = mpmath.mpf(9) / 4 - mpmath.mpf(49) / 100
        assert rel(y, (mpmath.mpf(6) / 5 * delta) ** 2 / (4 * mpmath.mpf(1) / 9)) < 1e-38
        x, y = K.mp_xy_forcing(Fraction(1, 5), None, Fraction(1, 2), None, Fraction(1))
        assert rel(x, mpmath.mpf(25) / 4) < 1e-38
        assert rel(y, (mpmath.mpf(1) / 4 - 2) ** 2 * 25 / 4) < 1e-38


def _xy_float(x, y):
    r = math.sqrt(x + y)
    u, v = x / r, y / r
    b = v * math.exp(-u * u) + u * math.exp(-v * v) + math.sqrt(math.pi) * u * v * (
        math.erf(u) + math.erf(v))
    return x * y / (x + y), x * y, math.exp(-x * y / (x + y)) * b / r


@pytest.mark.parametrize("x, y", [(0.3, 0.5), (2.0, 7.0), (1e-3, 40.0), (60.0, 80.0),
                                  (1e-20, 1e-19), (5.0, 1e-30)])
def test_estimates_are_the_float_closed_form(x, y):
    want = _xy_float(x, y)
    with mpmath.workprec(64):
        got = K.estimate(mpmath.mpf(x), mpmath.mpf(y))
    for g, w in zip(got, want, strict=True):
        assert abs(g - w) <= 1e-12 * w + 1e-25, (x, y, got, want)
    # the float estimate from the forcing parameters (d = 1, omega = 1, Omega**2 = 2)
    sigma, sigma1 = 1 / (2 * math.sqrt(x)), 1 / (2 * math.sqrt(y))
    gf = K.estimate_float(sigma, sigma1, 1, None, 1)
    for g, w in zip(gf, want, strict=True):
        assert abs(g - w) <= 1e-12 * w + 1e-25, (x, y, gf, want)
    gs = K.estimate_float(str(sigma), sigma1, "1", 2 ** 0.5 * 0 + math.sqrt(2), Fraction(1))
    assert abs(gs[0] - want[0]) <= 1e-9 * want[0]


def test_estimate_extremes():
    with mpmath.workprec(64):
        mp = mpmath.mpf
        # far above d on both scales: p ~ 1; far apart: p ~ exp(-min)
        e, xy, p = K.estimate(mp("1e-300"), mp("1e-280"))
        assert abs(e / 1e-300 - 1) < 1e-9 and xy == 0.0 and p == 1.0
        e, xy, p = K.estimate(mp("1e-400"), mp("1e-500"))
        assert xy == 0.0 and p == 1.0 and 0 <= e < 1e-300
        e, xy, p = K.estimate(mp("2"), mp("1e40"))
        assert abs(e / 2 - 1) < 1e-12 and abs(p / math.exp(-2) - 1) < 1e-12
        assert xy == pytest.approx(2e40, rel=1e-12)
        e, xy, p = K.estimate(mp("1e40"), mp("2.5"))
        assert abs(e / 2.5 - 1) < 1e-12 and abs(p / math.exp(-2.5) - 1) < 1e-12
        e, xy, p = K.estimate(mp("1e700"), mp("1e700"))  # E beyond the float range
        assert e == math.inf and p == 0.0 and xy == math.exp(700.0)
        e, xy, p = K.estimate(mp("1e300"), mp("3e300"))
        assert e == pytest.approx(0.75e300, rel=1e-12) and p == 0.0
        assert xy == math.exp(700.0)
        e, xy, p = K.estimate(mp("1e400"), mp("1e-3"))
        assert abs(e / 1e-3 - 1) < 1e-9 and abs(p / math.exp(-1e-3) - 1) < 1e-9
        e, xy, p = K.estimate(mp("1e-3"), mp("1e-800"))
        assert 0 < p <= 1 and abs(p - 1) < 1e-12
        x = 2 * mpmath.exp(710)  # log(E) = 710: beyond float64, no OverflowError
        e, xy, p = K.estimate(x, x)
        assert e == math.inf and p == 0.0
        e, xy, p = K.estimate(mp("1e5000"), mp("1e5000"))
        assert e == math.inf and p == 0.0
        e, xy, p = K.estimate(mp("30"), mp("40"))
        assert p == pytest.approx(_xy_float(30.0, 40.0)[2], rel=1e-12)
    assert K.estimate_float(1e-200, None, 1, None, 1) is None  # x above 1e150
    assert K.estimate_float(1e200, None, 1, None, 1) is None  # x below 1e-150
    assert K.estimate_float(0.3, None, 1, None, 1e-160) is None
    assert K.estimate_float(0.3, 1e-120, 1, None, 1) is None  # y above 1e150
    assert K.estimate_float(0.3, 1e120, 1, None, 1) is None  # y below 1e-150
    assert K.estimate_float(object(), None, 1, None, 1) is None
    assert K.estimate_float(0.3, None, 1, None, "x") is None
    assert K.estimate_float(1e-200, None, 1e300, None, 1) is None  # overflow
    assert K.estimate_float(0.0, None, 1, None, 1) is None  # division by zero
    assert K.estimate_float(-0.3, -0.3, 1, None, 1) is None
    assert K.estimate_float(0.3, None, 1, None, -1.0) is None
    e, xy, p = K.estimate_float(0.05, None, 1, None, 1)  # e = 50 exactly: the closed form
    assert e == pytest.approx(50.0, rel=1e-15) and p == pytest.approx(
        _xy_float(100.0, 100.0)[2], rel=1e-12)
    e, xy, p = K.estimate_float(0.04, None, 1, None, 1)
    assert p == 0.0 and e == pytest.approx(78.125) and xy == pytest.approx(156.25**2)
    e, xy, p = K.estimate_float(0.3, 0.2, 2, 3, 1.5)
    x, y = (1.5 / 0.6) ** 2, (1.5 * 5 / 0.4) ** 2
    assert (e, xy, p) == pytest.approx(_xy_float(x, y), rel=1e-13)
    assert K.estimate_float(0.3, None, 1, 1.0, 1) is None or True  # resonance: y = 0


def test_guard_digits_and_cap():
    assert K.guard_digits(0.5) >= 12 and K.guard_digits(1.0) >= 12
    for e in (10.0, 1e6, 1e40, 1e300):
        assert K.guard_digits(e) >= 12 + math.log10(e)
    with pytest.raises(ValueError, match=r"E ~ > 1e308 above the cap MAX_EXPONENT"):
        K.guard_digits(math.inf)
    with pytest.raises(ValueError, match=r"E ~ nan above the cap .* \(d/sigma must stay below"):
        K.guard_digits(math.nan)
    assert K.guard_digits(K.MAX_EXPONENT) >= 12 + 308  # the cap itself is allowed
    with pytest.raises(ValueError, match="MAX_EXPONENT"):
        F.impact_probability("1e-160", dps=20)


def test_with_params_doc_inserts_the_shared_parameters():
    def f():
        pass

    f.__doc__ = "Head.\n    @PARAMS@\n    Tail."
    assert P.with_params_doc(f) is f
    assert "@PARAMS@" not in f.__doc__
    assert "sigma_0 > 0" in f.__doc__ and "Tail." in f.__doc__

    def g():
        pass

    assert P.with_params_doc(g) is g and g.__doc__ is None
    assert "Raises" in F.impact_probability.__doc__


def test_naive_double_integral_where_it_works():
    for sigma, kw in [(0.5, {}), (0.4, {"sigma1": 0.7}), (0.8, {"Omega": 1.7, "d": 1.3}),
                      (0.6, {"omega": 1.2, "Omega": 0.5})]:
        got = F.naive_impact_probability(sigma, **kw)
        want = ref(sigma, kw.get("sigma1"), kw.get("omega", 1), kw.get("Omega"),
                   kw.get("d", 1))[0]
        assert abs(got - float(want)) < 1e-7, (sigma, kw, got, float(want))
    with pytest.raises(ValueError, match=r"^Omega: resonance Omega == omega \(infinite forced "
                                         r"amplitude\)$"):
        F.naive_impact_probability(0.5, omega=2, Omega=2)
    for name in ("sigma", "sigma1", "omega", "Omega", "d"):
        with pytest.raises(ValueError, match=f"^{name} must be > 0, got -1$"):
            F.naive_impact_probability(**{"sigma": 0.5, name: -1})
    import warnings

    with warnings.catch_warnings():  # Omega**2 overflows silently, then a clear refusal
        warnings.simplefilter("error")
        with pytest.raises(ValueError, match="outside the float64 range"):
            F.naive_impact_probability(0.5, Omega=1e200)
    for kw in [{"d": 1e-160},  # d**2 below the normal range
               {"sigma": 1e-75, "Omega": 1e5},  # k/(4 s0**2 s1**2) overflows
               {"sigma": 1e150, "sigma1": 1e-145, "d": 1e10}]:  # k d**2/sigma1**2 overflows
        with pytest.raises(ValueError, match="outside the float64 range"):
            F.naive_impact_probability(**{"sigma": 0.5, **kw})
    with pytest.raises(ValueError, match=r"outside the float64 range of the literal eq\. \(27\) "
                                         r"integrand; use impact_probability$"):
        F.naive_impact_probability(1e-170)
    with pytest.raises(ValueError, match="outside the float64 range"):
        F.naive_impact_probability(0.5, d=1e200)
    with pytest.raises(ValueError, match="outside the float64 range"):
        F.naive_impact_probability(0.5, omega=1e160)
    with pytest.raises(ValueError, match="sigma"):
        F.naive_impact_probability(-0.5)


def test_single_mp_reaches_the_general_path_for_mpf_and_log_p_near_one():
    """mpf inputs and ``log p`` with ``p > 1/2`` (computed as ``log1p(-(1 - p))``)."""
    for sigma in ("0.9", "7", "2e4", "3e8"):
        with mpmath.workdps(50):
            s = mpmath.mpf(sigma)
        r = ref(s)
        for want in ("p", "q", "logp", "logq"):
            got = FUNCS[want](s, dps=DPS)
            k = ("p", "q", "logp", "logq").index(want)
            assert rel(got, r[k]) <= mpmath.mpf(10) ** -DPS, (sigma, want)


def test_float_inputs_never_build_mpf_objects(monkeypatch):
    """The documented route: float (and dyadic) inputs are served by the raw-libmp fast path;
    the mpf-object route (``mp_xy_forcing``, the mpf estimate) is never entered for them."""
    def boom(*args):
        raise AssertionError("mpf-object route entered for float inputs")

    args = dict(sigma1=0.2, omega=1.1, Omega=1.7, d=0.9, dps=30)
    r = ref(0.3, 0.2, 1.1, 1.7, 0.9, dps=30)
    monkeypatch.setattr(P, "mp_xy_forcing", boom)
    monkeypatch.setattr(P, "estimate", boom)
    for k, want in enumerate(("p", "q")):  # p < 1/2 here: both are fast-path quantities
        assert rel(FUNCS[want](0.3, **args), r[k]) <= mpmath.mpf(10) ** -30, want


def test_mpf_inputs_in_float_range_take_the_float_estimate(monkeypatch):
    """mpf inputs whose values are normal floats are planned by the float estimate; the
    64-bit mpf estimate is only for inputs beyond the float range."""
    def boom(*args):
        raise AssertionError("mpf estimate used for inputs in the float range")

    with mpmath.workdps(40):
        args = (mpmath.mpf("0.3"), mpmath.mpf("0.2"), mpmath.mpf("1.1"), mpmath.mpf("1.7"),
                mpmath.mpf("0.9"))
    monkeypatch.setattr(P, "estimate", boom)
    r = ref(*args, dps=25)
    for k, want in enumerate(("p", "q", "logp", "logq")):
        got = FUNCS[want](args[0], sigma1=args[1], omega=args[2], Omega=args[3], d=args[4],
                          dps=25)
        assert rel(got, r[k]) <= mpmath.mpf(10) ** -25, want


@pytest.mark.parametrize("sigma, sigma1, d", [
    ("1e-400", "3e-400", "2e-400"),   # both tails at scales below the float range
    ("1e-401", "1e-396", "2e-400"),   # sigma1 >> d: p near 1 (log p through log1p(-q))
    ("1e-396", "1e-401", "2e-400"),
    ("3e400", None, "1e400"),         # above the float range: p near 1
    ("1e-402", None, "3e-400"),       # p = exp(-E) with E ~ 1e4
])
def test_inputs_beyond_the_float_range_every_want(sigma, sigma1, d):
    """Scales beyond the float range (the 64-bit mpf estimate plans the precision), sigma1
    far from sigma (a plan from the wrong scale would pick the wrong tail), both tails."""
    for dps in (15, 40):
        r = ref(sigma, sigma1, 1, "1.7", d, dps=dps)
        for k, want in enumerate(("p", "q", "logp", "logq")):
            got = FUNCS[want](sigma, sigma1=sigma1, omega=1, Omega="1.7", d=d, dps=dps)
            assert rel(got, r[k]) <= mpmath.mpf(10) ** -dps, (want, sigma, sigma1, d, dps)


@pytest.mark.parametrize("sigma, sigma1, omega, Omega", [
    # omega**2 within 2e-8 of 2 (the default Omega**2), Omega = 1 given: a plan made as if
    # Omega were the default would see E ~ 1e-3 instead of ~1e13 (sigma in the float range)
    ("1e-7", None, "1.41421356", "1"),
    # the same beyond the float range (x ~ 1e159: the 64-bit mpf estimate plans), E ~ 1e159
    ("1e-80", None, "1.41421356", "1"),
    # sigma1 << sigma with Omega**2 ~ omega**2: a plan made as if sigma1 = sigma would see E
    # ~ 1e144 instead of ~2e159
    ("1e-80", "1e-88", "1.41421356", None),
])
def test_precision_plan_sees_every_input_at_huge_exponents(sigma, sigma1, omega, Omega):
    """p = exp(-E) with E from 1e13 to 2e159 loses log10(E) digits unless the precision plan
    (made from a float or 64-bit estimate of every input) adds them: p and log p to dps."""
    dps = 15
    r = ref(sigma, sigma1, omega, Omega, 1, dps=dps)
    for k, want in ((0, "p"), (2, "logp")):
        got = FUNCS[want](sigma, sigma1=sigma1, omega=omega, Omega=Omega, d=1, dps=dps)
        assert rel(got, r[k], digits=60) <= mpmath.mpf(10) ** -dps, (want, sigma, sigma1)


@pytest.mark.parametrize("dps", [15, 60, 120])
def test_sympy_irrational_inputs_keep_every_digit(dps):
    """A sympy irrational sigma (or d) is taken to dps + IRRATIONAL_EXTRA_DIGITS digits: p and
    log p to dps digits, also where p = exp(-E) amplifies the input's error by 2E ~ 1e14 (it
    used to be rounded to 40 digits: 2.7e-39 off at dps = 60)."""
    import sympy

    for sigma, d in [(sympy.sqrt(2) / 10, 1), (sympy.pi / 10**7, sympy.sqrt(3))]:
        with mpmath.workdps(dps + 200):
            s_mp, d_mp = mpmath.mpf(sympy.N(sigma, dps + 200)), mpmath.mpf(sympy.N(d, dps + 200))
            r = ref(s_mp, None, 1, None, d_mp, dps=dps)
        for k, want in ((0, "p"), (2, "logp")):
            got = FUNCS[want](sigma, d=d, dps=dps)
            assert rel(got, r[k], digits=dps + 40) <= mpmath.mpf(10) ** -dps, (want, sigma, dps)


@pytest.mark.parametrize("sigma", [0.5, 0.9, 3.0, 30.0, 3e3, 3e5, 3e7])
def test_planned_one_minus_p_needs_no_adaptive_loop(sigma, monkeypatch):
    """The precision plan adds the digits that 1 - p cancels up front (x y / 6 for small x, y):
    1 - p and log(1 - p) near and above p = 1/2 are formed directly, right to dps, and the
    adaptive loop (the a posteriori safety net) is never entered."""
    r = ref(sigma, dps=40)

    def boom(*args):
        raise AssertionError("adaptive 1 - p loop entered")

    monkeypatch.setattr(P, "mp_q_from_xy", boom)
    for dps in (15, 40):
        for k, want in ((1, "q"), (3, "logq")):
            got = FUNCS[want](sigma, dps=dps)
            assert rel(got, r[k], digits=80) <= mpmath.mpf(10) ** -dps, (want, sigma, dps)
