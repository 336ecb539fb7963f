"""symhx.forcing.sites: per-class impact probabilities against Monte Carlo draws of the pipes'
own motions (tests.reference.geometry), against the closed form of eq. (27) written out for one
pipe's scales and against quadrature at twice the digits, at the extremes of sigma and the gaps,
in threads, and its refusals."""

from __future__ import annotations

import math
import sys
import threading
from fractions import Fraction

import mpmath
import numpy as np
import pytest

import symhx
from symhx.forcing.sites import (
    SiteProbabilities,
    Threshold,
    contact_probability,
    lattice_site_probabilities,
    row_site_probabilities,
)
from tests.harness.errors import assert_refuses
from tests.reference.forcing import eq27_p_xy
from tests.reference.geometry import (
    binomial_tolerance,
    lattice_closure_fractions,
    row_closure_fractions,
)
from tests.reference.mp import rel_err


def wall_closed_form(sigma, gap, dps, sigma1=None, omega=1, Omega=None):
    """P(R_0 + R_1 > gap) for ONE pipe's scales sigma and sigma1/|omega**2 - Omega**2|, from the
    closed form in x = gap**2/(2 s_0**2), y = gap**2/(2 s_1**2), at ``dps`` digits."""
    def mpf(x):
        x = Fraction(x)
        return mpmath.mpf(x.numerator) / x.denominator

    with mpmath.workdps(dps):
        s0 = mpf(sigma)
        s1 = s0 if sigma1 is None else mpf(sigma1)
        om2 = 2 if Omega is None else mpf(Omega) ** 2
        s1 = s1 / abs(mpf(omega) ** 2 - om2)
        g = mpf(gap)
        return eq27_p_xy(g * g / (2 * s0 * s0), g * g / (2 * s1 * s1))


def pipe_by_quadrature(sigma, threshold, dps):
    """P(R_0 + R_1 > x) for the pipe-pair scales sqrt(2) sigma (the paper's forcing) by mpmath
    quadrature of the convolution: P(R_1 > x) + int_0^x f_1(t) P(R_0 > x - t) dt."""
    with mpmath.workdps(dps):
        s = mpmath.sqrt(2) * mpmath.mpf(sigma.numerator) / sigma.denominator
        x = threshold

        def f(t):
            return t / s**2 * mpmath.exp(-t * t / (2 * s * s))

        def tail(t):
            return mpmath.exp(-t * t / (2 * s * s))

        return tail(x) + mpmath.quad(lambda t: f(t) * tail(x - t), mpmath.linspace(0, x, 9))


# ------------------------------------------------------------------ the two kinds of site
@pytest.mark.parametrize("sigma", [0.01, 0.05, 0.12, 0.3, 1.0, 100.0])
def test_a_pipe_pair_is_eq27_bit_for_bit(sigma):
    assert contact_probability(sigma) == symhx.impact_probability(sigma)
    assert contact_probability(sigma, dps=30) == symhx.impact_probability(sigma, dps=30)
    assert contact_probability(sigma, gap="0.5", log=True) == symhx.log_impact_probability(
        sigma, d="0.5")


@pytest.mark.parametrize(("sigma", "gap"), [("0.01", 1), ("0.05", "0.3"), ("0.12", 1),
                                            ("0.3", 1), (1, "2.5"), (100, 1), ("1e-3", "1e-8"),
                                            ("1e5", "1e8")])
@pytest.mark.parametrize("dps", [15, 40])
def test_a_wall_site_has_one_pipe_scales(sigma, gap, dps):
    got = contact_probability(sigma, bodies=1, gap=gap, dps=dps)
    ref = wall_closed_form(Fraction(sigma), Fraction(gap), 2 * dps + 10)
    assert rel_err(got, ref, 2 * dps + 10) < mpmath.mpf(10) ** (1 - dps)


@pytest.mark.parametrize(("sigma", "sigma1", "omega", "Omega"),
                         [("0.2", "0.1", 1, 3), ("0.1", None, "1.5", "0.5"),
                          ("0.3", "0.05", 2, "2.25")])
def test_a_wall_site_with_another_forcing(sigma, sigma1, omega, Omega):
    got = contact_probability(sigma, bodies=1, sigma1=sigma1, omega=omega, Omega=Omega, dps=30)
    ref = wall_closed_form(Fraction(sigma), 1, 70, None if sigma1 is None else Fraction(sigma1),
                           Fraction(omega), Fraction(Omega))
    assert rel_err(got, ref, 70) < 1e-29


def test_the_diagonal_threshold_against_quadrature_at_twice_the_digits():
    sp = lattice_site_probabilities(3, "0.4", pitch="1.25", diameter=1, dps=25)
    with mpmath.workdps(60):
        x = mpmath.sqrt(2) * mpmath.mpf(5) / 4 - 1
    ref = pipe_by_quadrature(Fraction(2, 5), x, 60)
    assert rel_err(sp["diagonal"], ref, 60) < 1e-24


def test_wall_equals_pipe_at_sqrt2_times_the_gap_and_at_sigma_over_sqrt2():
    for s in (0.07, 0.15, 0.5, 3.0):
        wall = contact_probability(s, bodies=1, dps=40)
        with mpmath.workdps(80):
            d = mpmath.sqrt(2)
            sig = mpmath.mpf(s) / mpmath.sqrt(2)
        assert rel_err(wall, symhx.impact_probability(s, d=d, dps=40), 45) < 1e-39
        assert rel_err(wall, symhx.impact_probability(sig, dps=40), 45) < 1e-39


# ------------------------------------------------------------------ float64 against mpmath
@pytest.mark.parametrize("bodies", [1, 2])
@pytest.mark.parametrize("gap", ["1e-8", "0.3", "1", "7", "1e8"])
def test_float64_meets_the_forcing_contract_over_sigma(bodies, gap):
    sig = np.geomspace(1e-2, 1e2, 41) * float(Fraction(gap))
    got = contact_probability(sig, bodies=bodies, gap=gap)
    for s, g in zip(sig, got, strict=True):
        ref = contact_probability(float(s), bodies=bodies, gap=gap, dps=30)
        if ref < 1e-300:     # beyond the float range: 0 there, log p is the way
            assert g == 0 or rel_err(g, ref) < 1e-10
            continue
        # the threshold sqrt(2) gap is rounded once: kappa = |d log p/d log x| ~ 2 E
        kappa = 2 * max(1.0, -math.log(float(ref)))
        assert rel_err(g, ref) < 1e-13 + 4 * kappa * 2.0**-53, (s, g, ref)


def test_log_probability_where_p_underflows():
    lp = contact_probability(0.001, bodies=1, log=True)
    ref = contact_probability("0.001", bodies=1, log=True, dps=30)
    assert abs(lp / float(ref) - 1) < 1e-14
    # log p_wall ~ -d**2/(2 V_wall) = -2 * (-d**2/(2 V_pipe)): twice the pipe's exponent
    lpipe = contact_probability(0.001, bodies=2, log=True)
    assert 1.99 < lp / lpipe < 2.01


def test_arrays_broadcast_like_impact_probability():
    sig = np.array([[0.1], [0.2]])
    Om = np.array([1.5, 3.0])
    got = contact_probability(sig, bodies=1, Omega=Om)
    assert got.shape == (2, 2)
    for i in range(2):
        for j in range(2):
            assert got[i, j] == contact_probability(float(sig[i, 0]), bodies=1,
                                                    Omega=float(Om[j]))
    assert contact_probability(np.zeros(1) + 0.1, bodies=1).shape == (1,)
    assert contact_probability(np.array([]), bodies=1).shape == (0,)
    mp_arr = contact_probability([0.1, 0.2], bodies=1, dps=20)
    assert mp_arr.dtype == object and mp_arr[1] == contact_probability(0.2, bodies=1, dps=20)


# ------------------------------------------------------------------ the classes
def test_row_classes_and_their_probabilities():
    sp = row_site_probabilities(100, "0.15", dps=30)
    assert isinstance(sp, SiteProbabilities)
    assert sp.names == ("wall", "pipe-pipe") and sp.sizes == (2, 99)
    assert sp["pipe-pipe"] == symhx.impact_probability("0.15", dps=30)
    assert sp["wall"] == contact_probability("0.15", bodies=1, dps=30)
    one = row_site_probabilities(1, 0.15)
    assert one.names == ("wall",) and one.probabilities == (contact_probability(0.15, bodies=1),)
    with pytest.raises(KeyError, match="pipe-pipe"):
        one["pipe-pipe"]
    assert row_site_probabilities(10**100, 0.2).sizes == (2, 10**100 - 1)


def test_lattice_classes_and_their_thresholds():
    sp = lattice_site_probabilities(5, 0.2, pitch="1.5", diameter=1)
    assert sp.names == ("wall", "orthogonal", "diagonal") and sp.sizes == (20, 40, 32)
    assert sp.thresholds == (Threshold(Fraction(0), Fraction(1, 2)),
                             Threshold(Fraction(1, 2), Fraction(0)),
                             Threshold(Fraction(-1), Fraction(3, 2)))
    assert sp["orthogonal"] == contact_probability(0.2, gap="0.5")
    assert sp["wall"] == contact_probability(0.2, bodies=1, gap="0.5")
    walls = lattice_site_probabilities(5, 0.2, pitch="1.5", diameter=1, wall_gap="0.25")
    assert walls["wall"] == contact_probability(0.2, bodies=1, gap="0.25")
    assert walls["diagonal"] == sp["diagonal"]
    # point pipes (diameter 0): the orthogonal gap is the pitch, the diagonal sqrt(2) pitch,
    # which a pipe pair closes exactly as a wall site closes its gap of one pitch
    pts = lattice_site_probabilities(2, "0.3", pitch=1, diameter=0, dps=30)
    assert rel_err(pts["diagonal"], pts["wall"], 40) < 1e-29
    assert lattice_site_probabilities(1, 0.2, pitch=1, diameter="0.5").names == ("wall",)
    # log=True: log p per class, in float64 and in mpmath alike; a threshold as a float
    for dps in (None, 30):
        lg = lattice_site_probabilities(5, "0.2", pitch="1.5", diameter=1, log=True, dps=dps)
        pl = lattice_site_probabilities(5, "0.2", pitch="1.5", diameter=1, dps=dps)
        for name in pl.names:
            with mpmath.workdps(40):
                ref = mpmath.log(pl[name])
            assert rel_err(lg[name], ref, 40) < (1e-14 if dps is None else 1e-29)
    assert abs(float(sp.thresholds[2]) - (math.sqrt(2) * 1.5 - 1)) < 1e-15


@pytest.mark.parametrize(("sigma", "n"), [(0.15, 30), (0.25, 30), (0.5, 12)])
def test_row_classes_against_monte_carlo_of_the_pipes(sigma, n):
    samples = 40_000
    mc = row_closure_fractions(n, sigma, samples, seed=1)
    sp = row_site_probabilities(n, sigma)
    for name in ("wall", "pipe-pipe"):
        p = sp[name]
        assert abs(mc[name] - p) <= binomial_tolerance(p, samples), (name, mc[name], p)


@pytest.mark.parametrize(("sigma", "pitch", "diameter", "wall_gap"),
                         [(0.15, 1.5, 1.0, None), (0.25, 1.0, 0.0, None), (0.2, 1.4, 1.0, 0.3)])
def test_lattice_classes_against_monte_carlo_of_2d_motion(sigma, pitch, diameter, wall_gap):
    samples = 20_000
    mc = lattice_closure_fractions(3, sigma, samples, pitch=pitch, diameter=diameter,
                                   wall_gap=wall_gap, seed=2)
    sp = lattice_site_probabilities(3, sigma, pitch=pitch, diameter=diameter, wall_gap=wall_gap)
    for name in sp.names:
        p = sp[name]
        assert abs(mc[name] - p) <= binomial_tolerance(p, samples), (name, mc[name], p)


# ------------------------------------------------------------------ threads
def test_threads_at_different_precisions_get_their_own_digits():
    cases = [(s, b, dps) for s in ("0.07", "0.2", "3") for b in (1, 2) for dps in (20, 60)]
    serial = {c: contact_probability(c[0], bodies=c[1], dps=c[2])._mpf_ for c in cases}
    bad: list = []

    def work(c):
        for _ in range(20):   # the bits (a repr would depend on the global mp.dps)
            if contact_probability(c[0], bodies=c[1], dps=c[2])._mpf_ != serial[c]:
                bad.append(c)

    interval = sys.getswitchinterval()
    sys.setswitchinterval(1e-6)   # switch threads often: a shared precision would show
    try:
        threads = [threading.Thread(target=work, args=(c,)) for c in cases for _ in range(2)]
        for t in threads:
            t.start()
        for t in threads:
            t.join()
    finally:
        sys.setswitchinterval(interval)
    assert bad == []


# ------------------------------------------------------------------ refusals
def test_refusals_name_the_argument_the_value_and_what_is_allowed():
    assert_refuses(contact_probability, 0.1, bodies=3, arg="bodies", value="3", allowed="<= 2")
    assert_refuses(contact_probability, 0.1, bodies=0, arg="bodies", value="0", allowed=">= 1")
    assert_refuses(contact_probability, 0.1, bodies=True, exc=TypeError, arg="bodies",
                   value="True", allowed="1 (a wall site) or 2")
    assert_refuses(contact_probability, 0.1, gap=0, arg="gap", value="0", allowed="> 0")
    assert_refuses(contact_probability, 0.1, gap=[1, 2], exc=TypeError, arg="gap",
                   value="[1, 2]", allowed="scalar")
    assert_refuses(contact_probability, 0.1, gap=None, exc=TypeError, arg="gap", value="None")
    assert_refuses(contact_probability, 0.1, log="yes", exc=TypeError, arg="log", value="'yes'",
                   allowed="True or False")
    assert_refuses(contact_probability, -0.1, bodies=1, arg="sigma", value="-0.1", allowed="> 0")
    assert_refuses(contact_probability, 0.1, bodies=1, dps=0, arg="dps", value="0")
    assert_refuses(contact_probability, 0.1, bodies=1, Omega=1, arg="Omega", allowed="resonance")
    assert_refuses(row_site_probabilities, 0, 0.1, arg="n", value="0", allowed=">= 1")
    assert_refuses(row_site_probabilities, 5, 0.1, d="-1", arg="d", value="-1", allowed="> 0")
    assert_refuses(lattice_site_probabilities, 3, 0.1, pitch=1, diameter=1, arg="diameter",
                   value="1", allowed="< pitch")
    assert_refuses(lattice_site_probabilities, 3, 0.1, pitch=1, diameter=-0.5, arg="diameter",
                   value="-0.5", allowed=">= 0")
    assert_refuses(lattice_site_probabilities, 3, 0.1, pitch=0, diameter=0, arg="pitch",
                   value="0", allowed="> 0")
    assert_refuses(lattice_site_probabilities, 3, 0.1, pitch=1, diameter=0, wall_gap=0,
                   arg="wall_gap", value="0", allowed="> 0")
    assert_refuses(lattice_site_probabilities, 0, 0.1, pitch=1, diameter=0, arg="m", value="0",
                   allowed=">= 1")
    assert_refuses(lattice_site_probabilities, 2, 0.1, pitch=1, diameter=0, log=1,
                   exc=TypeError, arg="log", value="1")


def test_a_rational_threshold_is_exact_with_dps_and_a_float_without():
    th = Threshold(Fraction(3, 4), Fraction(0))
    assert th.value(30) == Fraction(3, 4) and isinstance(th.value(30), Fraction)
    assert th.value(None) == 0.75 and isinstance(th.value(None), float) and float(th) == 0.75
