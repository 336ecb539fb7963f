"""Survivors of the raw-libmp fast path (``symhx.forcing.rawmp``) that change what a user gets.

Every value is checked against the closed form of eq. (27) written out here and evaluated from
the exact binary inputs at far more digits than requested (``_ref``), never against numbers
taken from the package.
"""

from __future__ import annotations

import mpmath
import pytest

import symhx
from tests.reference.forcing import eq27_p


def _ref(sigma, sigma1, omega, Omega, d, want, extra):
    """``p`` or ``1 - p`` of one component from the exact inputs at ``extra`` digits."""
    with mpmath.workdps(extra):
        p = eq27_p(sigma, sigma1, omega, Omega, d)
        return p if want == "p" else 1 - p


def _units(value, ref, dps):
    """Relative error in units of ``10**-dps``."""
    with mpmath.workdps(dps + 60):
        return abs(value / ref - 1) * mpmath.mpf(10) ** dps


LOW_DPS_POINTS = [  # 53-bit sigma/sigma1 (4 sigma**2 rounds below 53 bits), omega < 1
    (0.1, None, 0.3, None, 1.0), (0.2, 0.7, 0.8, 1.7, 0.6), (0.3, 0.1, 0.7, None, 0.9),
    (0.1, 0.3, 1.3, 0.9, 2.0),
]


@pytest.mark.parametrize("dps", [1, 2, 3])
@pytest.mark.parametrize("pt", LOW_DPS_POINTS)
def test_low_dps_float_inputs_give_correct_digits(pt, dps):
    """dps 1-3 work below 53 bits: the roundings of 4 sigma**2 and of omega**2 - Omega**2 must
    still use a rounding mode (a dropped mode raised KeyError inside mpmath.libmp)."""
    sigma, sigma1, omega, Omega, d = pt
    p = symhx.impact_probability(sigma, sigma1=sigma1, omega=omega, Omega=Omega, d=d, dps=dps)
    assert _units(p, _ref(*pt, "p", 60), dps) < 1


# sigma1 far from sigma, omega near Omega: the estimate with sigma1 = sigma sees E ~ 0.04,
# the true exponent is E = 5e13 (13 more guard digits needed)
TAIL_SIGMA1 = (5e-8, 1e-15, 1.0, 1.00000001, 1.0)
# omega**2 ~ 2 but Omega = 0.1: the estimate with Omega**2 = 2 sees E ~ 1e-17, the true E ~ 8e13
TAIL_OMEGA = (5e-8, None, 1.4142135623730951, 0.1, 1.0)


@pytest.mark.parametrize("dps", [15, 30])
@pytest.mark.parametrize("pt", [TAIL_SIGMA1, TAIL_OMEGA])
def test_far_tail_guard_uses_sigma1_and_Omega(pt, dps):
    """The precision plan must be made from the actual sigma1 and Omega: p = exp(-E) with
    E ~ 1e14 needs log10(E) guard digits, an estimate that drops sigma1 or Omega gives ~12
    and p then carries ~100 units of error at dps digits."""
    sigma, sigma1, omega, Omega, d = pt
    p = symhx.impact_probability(sigma, sigma1=sigma1, omega=omega, Omega=Omega, d=d, dps=dps)
    assert _units(p, _ref(*pt, "p", dps + 60), dps) < 1


def _sigma_for_q_bits(bits):
    """sigma (omega = 1, Omega**2 = 2, d = 1: x = y = 1/(4 sigma**2)) with 1 - p ~ x y / 6
    = 2**-bits."""
    with mpmath.workdps(30):
        return float((mpmath.mpf(2) ** bits / 96) ** mpmath.mpf(0.25))


@pytest.mark.parametrize("dps", [10, 15, 20, 30])
@pytest.mark.parametrize("bits", [1072.2, 1072.9, 1100.0])
def test_one_minus_p_for_tiny_x_y_keeps_its_digits(bits, dps):
    """sigma ~ 1e80: x, y below the float range, the estimate floors x y at 1e-300 and plans
    ~301 cancelled digits while 1 - p ~ 2**-1072 .. 2**-1100 cancels up to 331: the a
    posteriori check (at most guard - 4 digits cancelled) must send these to the adaptive loop;
    a looser check returns 1 - p with fewer than dps correct digits."""
    sigma = _sigma_for_q_bits(bits)
    q = symhx.no_impact_probability(sigma, dps=dps)
    ref = _ref(sigma, None, 1.0, None, 1.0, "q", dps + 1100)
    with mpmath.workdps(40):
        assert abs(-mpmath.log(ref, 2) - bits) < 0.01  # the point is where it was aimed
    assert _units(q, ref, dps) < 1
