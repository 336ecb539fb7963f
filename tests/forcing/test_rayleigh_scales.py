"""The Rayleigh scales of the forcing (``rayleigh_scales``, eqs. 24-25): ``s_0 = sqrt(2) sigma``,
``s_i = sqrt(2) sigma_i / |omega**2 - Omega_i**2|`` against exact rationals, at tiny and huge
frequencies, with the paper's ``Omega = sqrt(2)``, and the resonance refusal."""

from __future__ import annotations

import math
from fractions import Fraction

import mpmath
import numpy as np
import pytest

from symhx import forcing as F
from symhx._mpctx import mp as thread_mp
from symhx.forcing.rayleigh import rayleigh_scales, scales_of
from tests.harness.errors import assert_refuses
from tests.reference.mp import rel_err

EPS = float(np.finfo(float).eps)


def test_rayleigh_scales_and_groups():
    # s_0 = sqrt(2) sigma, s_i = sqrt(2) sigma_i/|omega^2 - Omega_i^2| (exact rationals here)
    got = rayleigh_scales("0.5", sigma1=["0.25", "0.1"], omega="1.5", Omega=["0.5", 3])
    want = [0.5, 0.25 / 2.0, 0.1 / 6.75]
    assert all(abs(g / (math.sqrt(2) * w) - 1) < 2 * EPS for g, w in zip(got, want, strict=True))
    got = rayleigh_scales("0.5", sigma1=["0.25", "0.1"], omega="1.5", Omega=["0.5", 3], dps=30)
    with mpmath.workdps(40), thread_mp().workdps(40):
        for g, w in zip(got, ("0.5", "0.125", "0.1/6.75"), strict=True):
            wv = mpmath.sqrt(2) * (mpmath.mpf(0.1) / mpmath.mpf(6.75) if "/" in w else
                                   mpmath.mpf(w))
            if "/" in w:
                wv = mpmath.sqrt(2) * mpmath.mpf(1) / 10 / (mpmath.mpf(27) / 4)
            assert abs(g / wv - 1) < mpmath.mpf(10) ** -29
    assert [round(s, 12) for s in rayleigh_scales(0.5)] == [0.707106781187] * 2
    two = rayleigh_scales(0.5, omega=2, dps=25)  # Omega^2 = 2 exactly: |4 - 2| = 2
    with mpmath.workdps(30), thread_mp().workdps(30):
        assert abs(two[1] - mpmath.sqrt(2) / 4) < mpmath.mpf(10) ** -25
    assert rayleigh_scales(0.5, sigma1=0.1, Omega=[3, 2])[1:] == pytest.approx(
        [math.sqrt(2) * 0.1 / 8, math.sqrt(2) * 0.1 / 3], rel=4 * EPS)
    for kw, msg in ((dict(Omega=[3, 1]), r"^Omega\[1\]: resonance"),
                    (dict(Omega=1), r"^Omega: resonance")):
        with pytest.raises(ValueError, match=msg):
            rayleigh_scales(0.5, **kw)
        with pytest.raises(ValueError, match=msg):
            rayleigh_scales(0.5, **kw, dps=20)
    with pytest.raises(TypeError, match="sigma must be a scalar"):
        rayleigh_scales([0.5])
    with pytest.raises(TypeError, match="omega must be a scalar"):
        rayleigh_scales(0.5, omega=[1.0])
    with pytest.raises(TypeError, match="sigma1: a list needs a list"):
        rayleigh_scales(0.5, sigma1=[0.1])
    fp = F.ForcingParams.validated("0.5", None, 1, [3, 2], dps=20)
    sc = scales_of(fp, 30)
    with mpmath.workdps(40), thread_mp().workdps(40):
        assert abs(sc[2] - mpmath.sqrt(2) * mpmath.mpf(1) / 2 / 3) < mpmath.mpf(10) ** -29


def test_forced_scales_at_tiny_and_huge_frequencies():
    # |omega**2 - Omega**2| = |omega - Omega| (omega + Omega), divided one factor at a time:
    # omega = 1e-160, Omega = 2e-160 made Delta subnormal (1.1e-5 relative error), and omega =
    # 1e-200, Omega = 1e-199 made it 0 (ZeroDivisionError); the true scale 7e397 is +inf
    got = F.rayleigh_scales(0.5, sigma1=1e-300, omega=1e-160, Omega=2e-160)
    ref = F.rayleigh_scales(0.5, sigma1=1e-300, omega=1e-160, Omega=2e-160, dps=30)
    assert all(rel_err(g, r) < 1e-15 for g, r in zip(got, ref, strict=True))
    assert F.rayleigh_scales(0.5, omega=1e-200, Omega=1e-199)[1] == math.inf
    with mpmath.workdps(30), thread_mp().workdps(30):
        s = F.rayleigh_scales(0.5, omega=1e-200, Omega=1e-199, dps=30)[1]
        assert rel_err(s, mpmath.sqrt(2) * mpmath.mpf(0.5) / (mpmath.mpf(1e-199) ** 2
                                                          - mpmath.mpf(1e-200) ** 2)) < 1e-28
    # a forced scale beyond float64: a clear error, never NaN (1e-150 gave NaN before); the
    # mpmath route answers. Scales spread over 300 orders of magnitude (a forced scale 2e299
    # next to 0.7) are a value in float64 too (they were refused): p = 1 to the last bit
    assert_refuses(F.impact_probability, 0.5, omega=1e-200, Omega=[1e-199, 2.0],
                   arg=["sigma1", "omega", "Omega"], allowed=["beyond float64", "use dps="])
    with pytest.raises(ValueError, match="use dps="):
        F.impact_probability(0.5, omega=1e-200, Omega=[1e-199, 2.0])
    assert F.impact_probability(0.5, omega=1e-200, Omega=[1e-199, 2.0], dps=20) == 1
    assert F.impact_probability(0.5, omega=1e-150, Omega=[2e-150, 2.0]) == 1.0
    assert F.impact_probability(0.5, omega=1e-150, Omega=[2e-150, 2.0], dps=20) == 1
    assert rel_err(F.impact_probability(0.5, omega=1e-50, Omega=[3e-50, 2.0]),
               F.impact_probability(0.5, omega=1e-50, Omega=[3e-50, 2.0], dps=20)) < 1e-15


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
        assert_refuses(rayleigh_scales, 0.5, omega=1.5, Omega=1.5, dps=dps, arg="Omega",
                       allowed="resonance Omega == omega")
        assert_refuses(rayleigh_scales, 0.5, omega=1.5, Omega=[2, 1.5], dps=dps, arg="Omega[1]",
                       allowed="resonance Omega == omega")


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


def test_resonance_error_names_the_reason():
    for args in (dict(omega=2.0, Omega=2.0), dict(omega=2, Omega="2", dps=30)):
        msg = assert_refuses(rayleigh_scales, 0.3, **args, arg="Omega",
                             allowed="resonance Omega == omega")
        assert msg.endswith("(infinite forced amplitude)")
