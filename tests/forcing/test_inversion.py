"""The inversion of the Laplace transform of a Rayleigh sum (``symhx.forcing.inversion``): the
transform ``L(z) = 1 - sqrt(pi) z e^{z**2} erfc(z)`` of one amplitude to a few ulps over the
right half-plane (against mpmath at 40 digits, also where ``1 -`` it cancels), its Taylor table
(built once, lazily, the same from an empty cache), and the tilted means that place the contour.
"""

from __future__ import annotations

import math

import mpmath
import numpy as np
import pytest

from symhx._mpctx import mp as thread_mp
from symhx.forcing import RayleighSum
from symhx.forcing import inversion as inv

#: the inversion's users: RayleighSum of three or more scales in float64 (its contract on
#: random scale sets and a straight-contour reference); mutation runs of inversion.py take them
MUTATION_ALSO = ("tests/forcing/test_rayleigh_many_scales.py",)

EPS = float(np.finfo(float).eps)


def _laplace_mp(z: complex) -> mpmath.mpc:
    """``L(z)`` at 40 digits (mpmath's erfc; the digits 1 - ... cancels are far below 40)."""
    with mpmath.workdps(40), thread_mp().workdps(40):
        zz = mpmath.mpc(z.real, z.imag)
        return 1 - mpmath.sqrt(mpmath.pi) * zz * mpmath.exp(zz * zz) * mpmath.erfc(zz)


def test_laplace_transform_to_a_few_ulps_over_the_right_half_plane():
    """|z| from 1e-3 to 1e6 at every argument from -90 to 90 degrees (the imaginary axis,
    where the continued fraction does not converge and 1 - sqrt(pi) z w(iz) cancels up to 3
    digits, included): relative error of L below 8 eps (the table and the asymptotic series)."""
    rng = np.random.default_rng(7)
    mods = np.concatenate([10 ** rng.uniform(-3, 6, 300), rng.uniform(0.5, 8.0, 300)])
    args = rng.uniform(-np.pi / 2, np.pi / 2, mods.size)
    args[:40] = np.pi / 2
    args[40:80] = -np.pi / 2
    z = mods * np.exp(1j * args)
    z.real[:80] = 0.0
    val, big = inv._laplace_parts(z)
    got = np.where(big, val * (0.5 / (z * z)), val)
    worst = 0.0
    for g, zz in zip(got, z, strict=True):
        ref = _laplace_mp(complex(zz))
        with mpmath.workdps(40), thread_mp().workdps(40):
            err = float(abs(mpmath.mpc(g.real, g.imag) / ref - 1))
        worst = max(worst, err)
        assert err < 8 * EPS, (zz, err)
    assert worst > 0   # the check measured something
    # beyond |z| ~ 1e154 L underflows: its log keeps the relative accuracy of L (an absolute
    # error of a few eps times |log L| from the rounding of the log itself)
    for zz in (1e200j, 3e250 + 1e250j, 1e300 + 0j):
        lg = complex(inv.log_laplace_float(np.array([zz]))[0])
        with mpmath.workdps(40), thread_mp().workdps(40):
            zm = mpmath.mpc(zz.real, zz.imag)
            ref = -mpmath.log(2 * zm * zm) + mpmath.log(1 - 3 / (2 * zm * zm))
            assert abs(mpmath.mpc(lg.real, lg.imag) - ref) < 4 * EPS * abs(ref), zz


def test_taylor_table_from_an_empty_cache(monkeypatch):
    """The table is built on first use (Arb values of L at the centres, the coefficients from
    the differential equation) and is the same when built again; the values of a sum do not
    depend on whether it was cached."""
    S = RayleighSum([0.5, 0.3, 0.2])
    before = S.sf(np.array([0.4, 1.0, 3.0]))
    table = inv._taylor_table()
    monkeypatch.setattr(inv, "_table", None)
    assert np.array_equal(inv._taylor_table(), table)
    assert inv._table is not None
    monkeypatch.setattr(inv, "_table", None)
    assert np.array_equal(S.sf(np.array([0.4, 1.0, 3.0])), before)


@pytest.mark.parametrize("tau", [-1e6, -300.0, -8.0, -1.0, -1e-3, 0.0, 1e-7, 0.5, 3.0, 40.0])
def test_tilted_mean_of_one_amplitude(tau):
    """``d/dtau log M(tau)`` for a unit-scale Rayleigh amplitude (the tilted mean that places
    the contour), ``M(tau) = E e^{tau R} = 1 + tau sqrt(pi/2) e^{tau**2/2} erfc(-tau/sqrt 2)``
    and ``M' = (M - 1)/tau + tau M`` (integration by parts of the density) at 60 digits."""
    got = float(inv._unit_kprime(np.array([tau]))[0])
    with mpmath.workdps(60), thread_mp().workdps(60):
        t = mpmath.mpf(tau)
        if t == 0:
            ref = mpmath.sqrt(mpmath.pi / 2)
        else:
            m = 1 + t * mpmath.sqrt(mpmath.pi / 2) * mpmath.exp(t * t / 2) * mpmath.erfc(
                -t / mpmath.sqrt(2))
            ref = ((m - 1) / t + t * m) / m
    assert abs(got / float(ref) - 1) < 1e-10, (tau, got, ref)


def test_float_inversion_memory_does_not_grow_with_the_thresholds():
    """The float64 evaluation works in chunks: a temporary array never holds more than
    ``_BUDGET`` complex values whatever the number of thresholds (a spy on the contour sums
    records the nodes x distinct scales of each call)."""
    sizes = []
    orig = inv._log_mgf

    def spy(theta, scales, mult):
        sizes.append(np.asarray(theta).size * len(scales))
        return orig(theta, scales, mult)

    inv._log_mgf = spy
    try:
        x = np.linspace(0.5, 20.0, 3000)
        inv.invert_float([1.0, 0.7, 0.5, 0.3, 0.2], x, "sf")
    finally:
        inv._log_mgf = orig
    assert max(sizes) <= inv._BUDGET and len(sizes) > 10
    assert math.isfinite(float(max(sizes)))
