"""mpmath kernels of one forcing component (``symhx.forcing.kernels_mp``): the closed forms of the
derivative's integrals, the adaptive ``1 - p``, ``x, y`` of the forcing, the float estimates that
plan the precision, the guard digits and the exponent cap. References: ``mpmath.quad`` of the
integrals, the completed-square formula (:mod:`tests.reference.forcing`), and the float closed
form written out."""

from __future__ import annotations

import math
from fractions import Fraction

import mpmath
import pytest

from symhx import forcing as F
from symhx._mpctx import mp as thread_mp
from symhx.forcing import kernels_mp as K
from symhx.forcing.rawmp import from_xy_raw
from tests.harness.errors import assert_refuses
from tests.reference.forcing import closed_form_float, ref_sq
from tests.reference.mp import rel_err


# ------------------------------------------------------------------ kernels, directly
@pytest.mark.parametrize("u, v", [("1e-9", "2e-9"), ("1e-4", "3e-4"), ("0.01", "0.5"),
                                  ("0.3", "0.7"), ("2", "5"), ("10", "0.1"), ("0.9", "0.05"),
                                  ("0.3", "0.3"), ("1e-20", "3e-20"), ("2e-12", "2e-12"),
                                  ("3e9", "5e9"), ("40", "70")])
def test_i2_i3_closed_forms_against_quadrature(u, v):
    """The positive integrals of the derivative (cancelling closed forms) to dps digits."""
    for dps in (15, 30):
        with mpmath.workdps(dps), thread_mp().workdps(dps):
            uu, vv = mpmath.mpf(u), mpmath.mpf(v)
            i2, i3 = K.mp_i2(uu, vv), K.mp_i3(uu, vv)
            assert max(i2._mpf_[1].bit_length(), i3._mpf_[1].bit_length()) <= mpmath.mp.prec
        # the reference integrates at the same (rounded) u, v far above the claim
        # (z = -v + r t on t in [0, 1], r = u + v: an O(1) integrand for any r)
        with mpmath.workdps(2 * dps + 30), thread_mp().workdps(2 * dps + 30):
            r = uu + vv
            t0 = vv / r  # the peak z = 0, width 1/r
            pts = sorted({mpmath.mpf(0), mpmath.mpf(1)} | {
                t0 + k / r for k in (-40, -8, -2, 0, 2, 8, 40) if 0 < t0 + k / r < 1})
            r2 = r**3 * mpmath.quad(
                lambda t, a=r, b=vv: t * (1 - t) * mpmath.exp(-(a * t - b) ** 2), pts)
            r3 = r**4 * mpmath.quad(
                lambda t, a=r, b=vv: t * t * (1 - t) * mpmath.exp(-(a * t - b) ** 2), pts)
        assert rel_err(i2, r2) <= 2 * mpmath.mpf(10) ** -dps, (u, v, dps)
        assert rel_err(i3, r3) <= 2 * mpmath.mpf(10) ** -dps, (u, v, dps)


@pytest.mark.parametrize("x, y", [("1e-30", "2e-30"), ("1e-6", "3e-3"), ("0.02", "0.05"),
                                  ("0.6", "0.9"), ("3", "0.2"), ("40", "50"), ("1e-12", "1e8"),
                                  ("1e-30", "1e30"), ("1e-60", "1e60"), ("3e50", "1e-80")])
def test_mp_q_from_xy_adaptive_loop(x, y):
    """``1 - p`` from ``(x, y)`` directly (the adaptive cancellation loop) to the precision."""
    for dps in (15, 40):
        with mpmath.workdps(dps), thread_mp().workdps(dps):
            xm, ym = mpmath.mpf(x), mpmath.mpf(y)
            q = K.mp_q_from_xy(xm, ym)
            p = K.mp_p_from_xy(xm, ym)
            lp = from_xy_raw(xm._mpf_, ym._mpf_, mpmath.mp.prec, "logp", 0, False)
            assert q._mpf_[1].bit_length() <= mpmath.mp.prec
        # x = d**2/(2 S0), y = d**2/(2 S1) with d = 1
        with mpmath.workdps(3 * dps + 100), thread_mp().workdps(3 * dps + 100):
            S0, S1 = 1 / (2 * xm), 1 / (2 * ym)
        rp, rq, rlp, _ = ref_sq(S0, S1, 1, dps)
        tol = 2 * mpmath.mpf(2) ** -mpmath.workdps(dps)(lambda: mpmath.mp.prec)()
        assert rel_err(q, rq) <= 8 * tol, (x, y, dps)
        assert rel_err(p, rp) <= 8 * tol
        assert rel_err(lp, rlp) <= 8 * tol * max(1, abs(float(1 / rlp)))


def test_mp_xy_forcing_definitions():
    with mpmath.workdps(40), thread_mp().workdps(40):
        x, y = K.mp_xy_forcing(Fraction(1, 5), Fraction(1, 3), Fraction(3, 2), Fraction(7, 10),
                               Fraction(6, 5))
        assert rel_err(x, mpmath.mpf(36) / 25 / (4 * mpmath.mpf(1) / 25)) < 1e-38
        delta = mpmath.mpf(9) / 4 - mpmath.mpf(49) / 100
        assert rel_err(y, (mpmath.mpf(6) / 5 * delta) ** 2 / (4 * mpmath.mpf(1) / 9)) < 1e-38
        x, y = K.mp_xy_forcing(Fraction(1, 5), None, Fraction(1, 2), None, Fraction(1))
        assert rel_err(x, mpmath.mpf(25) / 4) < 1e-38
        assert rel_err(y, (mpmath.mpf(1) / 4 - 2) ** 2 * 25 / 4) < 1e-38


@pytest.mark.parametrize("x, y", [(0.3, 0.5), (2.0, 7.0), (1e-3, 40.0), (60.0, 80.0),
                                  (1e-20, 1e-19), (5.0, 1e-30)])
def test_estimates_are_the_float_closed_form(x, y):
    want = closed_form_float(x, y)
    with mpmath.workprec(64), thread_mp().workprec(64):
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
    with mpmath.workprec(64), thread_mp().workprec(64):
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
        assert p == pytest.approx(closed_form_float(30.0, 40.0)[2], rel=1e-12)
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
        closed_form_float(100.0, 100.0)[2], rel=1e-12)
    e, xy, p = K.estimate_float(0.04, None, 1, None, 1)
    assert p == 0.0 and e == pytest.approx(78.125) and xy == pytest.approx(156.25**2)
    e, xy, p = K.estimate_float(0.3, 0.2, 2, 3, 1.5)
    x, y = (1.5 / 0.6) ** 2, (1.5 * 5 / 0.4) ** 2
    assert (e, xy, p) == pytest.approx(closed_form_float(x, y), rel=1e-13)
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


def test_resonance_is_an_error():
    for dps in (None, 20):
        with pytest.raises(ValueError, match="resonance"):
            F.impact_probability("0.3", omega="1.5", Omega="1.5", dps=dps)
    with mpmath.workdps(30), thread_mp().workdps(30):
        assert_refuses(K.mp_xy_forcing, Fraction(1, 3), None, 3, 3, 1, arg="Omega",
                       allowed="resonance Omega == omega")
        for i, name in enumerate(("sigma", "sigma1", "omega", "Omega", "d")):
            args = [Fraction(1, 3), None, 1, None, 1]
            args[i] = -1
            assert_refuses(K.mp_xy_forcing, *args, arg=name, value="-1", allowed="> 0")
