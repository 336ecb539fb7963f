"""dp/dsigma (``symhx.forcing.derivative``) against independent references: ``mpmath.diff`` of
the completed-square closed form (:func:`tests.reference.forcing.forcing_dp`) and of the
package's mpmath path at far higher precision, the elementary one-Rayleigh limit where the
float kernel over/underflows, and a central difference of an independent two-component
quadrature."""

from __future__ import annotations

from fractions import Fraction

import mpmath
import numpy as np
import pytest

from symhx import forcing as F
from symhx._mpctx import mp as thread_mp
from tests.harness.errors import assert_refuses
from tests.reference.forcing import forcing_dp, one_rayleigh_dp, three_gl_p
from tests.reference.mp import rel_err


# ----------------------------------------------------------------------------- derivative
@pytest.mark.parametrize("sigma", ["0.013", "0.05", "0.3", "2", "80"])
@pytest.mark.parametrize("sigma1", [None, "0.07"])
def test_dp_dsigma_against_mpmath_diff(sigma, sigma1):
    # central difference, h = 1e-20: O(h^2) and roundoff ~1e-40
    with mpmath.workdps(70), thread_mp().workdps(70):
        ref = mpmath.diff(lambda s: F.impact_probability(s, sigma1=sigma1, Omega=1.9, dps=60),
                          mpmath.mpf(sigma), h=mpmath.mpf("1e-20"))
        got = F.dp_dsigma(sigma, sigma1=sigma1, Omega=1.9, dps=30)
        assert rel_err(got, ref) < 1e-28
        gf = F.dp_dsigma(float(sigma), sigma1=None if sigma1 is None else float(sigma1),
                         Omega=1.9)
        if ref > 1e-300:  # normal float range
            assert rel_err(gf, ref) < 1e-12
        else:  # below it: the float answer is the subnormal rounding of ref, or 0
            assert abs(gf - ref) <= 2**-1074 + 1e-12 * ref


def test_dp_dsigma_several_components():
    kw = dict(Omega=[1.5, 2.5])
    h = 1e-5
    fd = (F.impact_probability(0.3 + h, **kw) - F.impact_probability(0.3 - h, **kw)) / (2 * h)
    assert abs(F.dp_dsigma(0.3, **kw) / fd - 1) < 1e-8
    # p at 35 digits: the difference quotient keeps ~23 digits
    with mpmath.workdps(40), thread_mp().workdps(40):
        ref = mpmath.diff(lambda s: F.impact_probability(s, **kw, dps=35), mpmath.mpf("0.3"),
                          h=mpmath.mpf("1e-12"))
        assert rel_err(F.dp_dsigma("0.3", **kw, dps=20), ref) < 1e-18


DPS = 20


def tol(dps=DPS):
    return mpmath.mpf(10) ** -dps


# ------------------------------------------------------------------ derivative
@pytest.mark.parametrize("sigma1", [None, "0.25", "4"])
def test_dp_mpmath_on_a_log_grid(sigma1):
    for s in np.logspace(-2, 2, 9):
        sd = repr(float(s))
        want = forcing_dp(sd, sigma1)
        got = F.dp_dsigma(sd, sigma1=sigma1, dps=DPS)
        assert isinstance(got, mpmath.mpf)
        assert rel_err(got, want) <= tol(), (sd, sigma1, mpmath.nstr(rel_err(got, want), 3))
        # rounded once to dps digits
        assert got._mpf_[1].bit_length() <= mpmath.workdps(DPS)(lambda: mpmath.mp.prec)()


def test_dp_mpmath_other_parameters_and_extremes():
    for sigma, kw in [("0.07", {"omega": "1.3", "Omega": "1.7", "d": "1.9"}),
                      ("0.7", {"sigma1": "0.2", "omega": "0.6", "Omega": "2.5", "d": "0.45"}),
                      ("1e-7", {}), ("3e-6", {"sigma1": "0.5"}), ("1e6", {}),
                      (Fraction(1, 3), {"sigma1": Fraction(1, 7)}), (0.3, {}),
                      (0.3, {"sigma1": 0.5})]:
        want = forcing_dp(sigma, kw.get("sigma1"), kw.get("omega", 1), kw.get("Omega"),
                      kw.get("d", 1))
        got = F.dp_dsigma(sigma, **kw, dps=DPS)
        assert rel_err(got, want) <= tol(), (sigma, kw, mpmath.nstr(rel_err(got, want), 3))


def test_dp_float64_vectorised_against_reference():
    s = np.array([0.03, 0.05, 0.3, 1.0, 7.0, 80.0])
    d = np.array([[1.0], [1.7]])
    got = F.dp_dsigma(s, d=d)
    assert got.shape == (2, 6) and got.dtype == float
    got1 = F.dp_dsigma(s, sigma1=0.4, Omega=2.0, d=d)
    for i, dv in enumerate(d[:, 0]):
        for j, sv in enumerate(s):
            assert rel_err(got[i, j], forcing_dp(float(sv), None, 1, None, float(dv))) < 1e-12
            assert rel_err(got1[i, j], forcing_dp(float(sv), 0.4, 1, 2.0, float(dv))) < 1e-12
    sc = F.dp_dsigma(0.3)
    assert isinstance(sc, float) and rel_err(sc, forcing_dp(0.3)) < 1e-13
    assert F.dp_dsigma(np.array([])).shape == (0,)


def test_dp_float64_fallback_where_the_kernel_overflows():
    """Inputs whose float kernel over/underflows: the elementary one-Rayleigh limit."""
    # sigma1 -> 0 (y overflows): p = P(R0 > d), partial derivative at fixed sigma1
    got = F.dp_dsigma(np.array([0.5, 0.3]), sigma1=np.array([1e-170, 0.5]))
    assert rel_err(got[0], one_rayleigh_dp(0.5)) < 1e-14
    assert rel_err(got[1], forcing_dp(0.3, 0.5)) < 1e-12
    # huge |omega**2 - Omega**2| (tied scales): s1 -> 0 again, total derivative
    got = F.dp_dsigma(0.4, omega=1e200)
    assert isinstance(got, float) and rel_err(got, one_rayleigh_dp(0.4)) < 1e-14
    got = F.dp_dsigma(np.array([0.4, 0.6]), omega=1e200, Omega=3.0, d=np.array([1.0, 1.2]))
    assert rel_err(got[0], one_rayleigh_dp(0.4)) < 1e-14
    assert rel_err(got[1], one_rayleigh_dp(0.6, 1.2)) < 1e-14
    got = F.dp_dsigma(0.5, sigma1=2.0, Omega=1e200, d=1.5)
    assert rel_err(got, one_rayleigh_dp(0.5, 1.5)) < 1e-14
    # the float kernel's over/underflow stays silent even where numpy is told to raise
    with np.errstate(all="raise"):
        assert F.dp_dsigma(1e160) == 0.0  # x, y underflow; dp ~ 1e-801
        assert F.dp_dsigma(9.43e-115, sigma1=2.01e-147) == 0.0  # y overflows, E ~ 3e227
        assert rel_err(F.dp_dsigma(0.5, sigma1=1e-170), one_rayleigh_dp(0.5)) < 1e-14
    # exponent far beyond float64: exactly 0.0, no NaN
    assert F.dp_dsigma(1e-160) == 0.0
    out = F.dp_dsigma(np.array([1e-160, 0.3]))
    assert out[0] == 0.0 and rel_err(out[1], forcing_dp(0.3)) < 1e-12


def test_dp_several_components():
    """Central difference (h = 1e-12, 60 digits) of an independent two-component quadrature."""
    Oms, d = ["1.7", "2.2"], "1.2"
    with mpmath.workdps(60), thread_mp().workdps(60):
        s = mpmath.mpf("0.35")
        h = mpmath.mpf("1e-12")
        want = (three_gl_p(s + h, Oms, d, 60) - three_gl_p(s - h, Oms, d, 60)) / (2 * h)
    got = F.dp_dsigma("0.35", Omega=Oms, d=d, dps=DPS)
    assert rel_err(got, want) <= tol(DPS - 1), mpmath.nstr(rel_err(got, want), 3)
    gf = F.dp_dsigma(0.35, Omega=[1.7, 2.2], d=1.2)
    assert isinstance(gf, float) and rel_err(gf, want) < 1e-11
    ga = F.dp_dsigma(np.array([0.35, 0.35]), Omega=[1.7, 2.2], d=1.2)
    assert ga.shape == (2,) and ga.dtype == float and rel_err(ga[0], want) < 1e-11
    gm = F.dp_dsigma(np.array(["0.35"], dtype=object), Omega=Oms, d=d, dps=DPS)
    assert gm.shape == (1,) and gm.dtype == object and rel_err(gm[0], want) <= tol(DPS - 1)
    assert_refuses(F.dp_dsigma, 0.35, sigma1=0.2, Omega=[1.7, 2.2], arg="sigma1",
                   allowed="only sigma1=None (all sigma_i = sigma)")
