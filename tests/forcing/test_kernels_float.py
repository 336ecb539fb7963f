"""float64 kernels of one forcing component (``symhx.forcing.kernels_float``): the building
blocks, the chunked vectorised path, the mantissa/exponent path at every range edge, and the
numpy error state, against an independent high-precision reference.

The reference (:func:`tests.reference.forcing.closed_form_values`) evaluates the closed form of
eq. (27) written out (no package code) at a working precision raised by the digits that cancel in
``1 - p`` and by those that ``exp(-uv)`` needs, from the *exact* binary values of the float
inputs; it is itself checked against direct quadrature of the convolution of the two Rayleigh
densities (:func:`tests.reference.forcing.pair_convolution`). The tolerance is the documented
contract "a few ulps for every normal result", scaled by the condition number ``kappa = |d ln
p/d ln d|`` of the value (the roundings of ``x`` and ``y`` are amplified by it): ``|rel. error|
<= C eps (1 + kappa)``, ``C = 8`` (observed worst cases are quoted per test).
"""

from __future__ import annotations

import itertools
import math

import mpmath
import numpy as np
import pytest

from symhx import forcing as F
from symhx._mpctx import mp as thread_mp
from symhx.forcing.arguments import ForcingParams
from symhx.forcing.kernels_float import (
    delta_float,
    gauss_legendre,
    i2_float,
    i3_float,
    pq_float,
    single_float,
    uv_forcing,
    uv_from_h,
)
from tests.harness.errors import assert_refuses
from tests.reference.forcing import closed_form_values, eq27_xy, i_integral, pair_convolution
from tests.reference.mp import rel_err

EPS = float(np.finfo(float).eps)


TINY = float(np.finfo(float).tiny)


C = 8.0


WANTS = ("p", "q", "logp", "logq")


@pytest.mark.parametrize(("s0", "s1", "om", "Om", "d"), [
    (0.05, None, 1.0, None, 1.0), (0.3, None, 1.0, None, 1.0), (3.0, None, 1.0, None, 1.0),
    (0.4, 2e-3, 0.7, 2.0, 0.3), (20.0, 0.5, 1.3, 0.9, 5.0), (0.02, 7.0, 1.0, None, 1.0)])
def test_reference_closed_form_against_convolution_quadrature(s0, s1, om, Om, d):
    p, q, *_ = closed_form_values(s0, s1, om, Om, d)
    up, lo = pair_convolution(s0, s1, om, Om, d)
    assert rel_err(p, up) < 1e-25 and rel_err(q, lo) < 1e-25, (p, up, q, lo)


# ------------------------------------------------------------------------------ grids
CASES = [(1.0, None, 1.0), (0.7, 2.0, 0.3), (1.3, 0.9, 5.0), (2.5, 1.1, 1e-3)]


RATIOS = [None, 1e-8, 1e-4, 0.1, 1.0, 3.0, 1e4, 1e8]


def _check(vals, point, worst, c=C):
    refs = closed_form_values(*point)
    p, q, lp, lq, kp, kq = refs
    assert 0.0 <= vals[0] <= 1.0 and 0.0 <= vals[1] <= 1.0, (point, vals)
    assert vals[2] <= 0.0 and vals[3] <= 0.0, (point, vals)
    for name, val, ref, kappa in (("p", vals[0], p, kp), ("q", vals[1], q, kq),
                                  ("logp", vals[2], lp, kp), ("logq", vals[3], lq, kq)):
        assert not math.isnan(val), (name, point)
        if name.startswith("log"):
            # absolute error of a log: the relative error of its argument
            err = abs(mpmath.mpf(val) - ref)
            bound = c * EPS * (1 + float(kappa) + abs(float(ref)))
        else:
            if abs(ref) < TINY:  # below the normal range: 0 or a subnormal rounding
                assert abs(val) < 2 * TINY, (name, point, val, ref)
                continue
            err = rel_err(val, ref)
            bound = c * EPS * (1 + float(kappa))
        worst[name] = max(worst.get(name, 0.0), float(err) / bound)
        assert err <= bound, (name, point, val, ref, float(err), bound)


def _grid(case, ratio, sigmas):
    om, Om, d = CASES[case]
    return [(float(s), None if ratio is None else float(s * ratio), om, Om, d) for s in sigmas]


@pytest.mark.parametrize("case", range(len(CASES)))
def test_float64_four_values_on_dense_log_grid(case):
    """sigma in [0.01, 100] (dense) x sigma1/sigma in 1e-8 .. 1e8: both tails, the complement
    form and the direct form of 1 - p, mixed chunks (arrays whose entries take both forms),
    the equal-scales shortcut (ratio None) and unequal scales. Arrays and scalars agree."""
    om, Om, d = CASES[case]
    sig = np.logspace(-2, 2, 33) * (1 + 1 / 7)  # no round values
    worst: dict[str, float] = {}
    for ratio in RATIOS:
        pts = _grid(case, ratio, sig)
        s1 = None if ratio is None else sig * ratio
        arrs = [F.impact_probability(sig, sigma1=s1, omega=om, Omega=Om, d=d),
                F.no_impact_probability(sig, sigma1=s1, omega=om, Omega=Om, d=d),
                F.log_impact_probability(sig, sigma1=s1, omega=om, Omega=Om, d=d),
                F.log_no_impact_probability(sig, sigma1=s1, omega=om, Omega=Om, d=d)]
        for i, pt in enumerate(pts):
            vals = [float(a[i]) for a in arrs]
            _check(vals, pt, worst)
            if i % 8 == 3:  # scalar inputs: the same numbers
                fp = ForcingParams.validated(pt[0], pt[1], om, Om, d)
                assert [single_float(fp, w) for w in WANTS] == vals, pt
    assert set(worst) == set(WANTS)


EXTREME = [  # (s0, s1, om, Om, d): the mantissa/exponent path, every region
    (1e-200, None, 1.0, None, 1.0), (1e200, None, 1.0, None, 1.0), (1e-80, 1e-70, 1.0, None, 1.0),
    (1e80, 1e90, 1.0, None, 1.0), (1e80, 1e-3, 1.0, None, 1.0), (1e-3, 1e80, 1.0, None, 1.0),
    (0.3, 1e120, 1.0, None, 1.0), (1e120, 0.3, 1.0, None, 1.0), (1e-100, 1e100, 1.0, None, 1.0),
    (1e100, 1e-100, 1.0, None, 1.0), (2.0, 3.0, 1e120, None, 1.0), (2.0, 3.0, 1e-120, 2.0, 1.0),
    (1.0, 1.0, 1.0, None, 1e-110), (1e-100, 1e-100, 1.0, None, 1e-110), (1.0, 1.0, 1.0, 1.5, 1e110),
    (1e40, 1e40, 1.0, 3.0, 1e120), (1e-60, 1e-60, 1e120, None, 1e-60),
    (1.0, 1e-20, 2e60, 1e60, 1.0),
    (1e-50, 1e-50, 1.0, None, 1e-60), (1e75, 1e-75, 1.0, None, 1.0), (1e76, 2.0, 1.0, None, 1.0),
    (5e-77, 3e76, 1.0, None, 1.0), (1e150, 1e-150, 1.0, None, 1.0), (1e-150, 1e150, 1.0, None, 1.0),
    (3e160, 1e150, 1.0, 2.0, 1.0), (0.01, 1e-10, 1.0, None, 1.0), (1e-5, 1e-5, 1.0, None, 1e-3),
]


def _check_public(pt, c=C):
    """p, 1 - p and both logs of the public float64 functions at ``pt`` against the reference
    (``c``: the error constant of :func:`_check`); beyond every float
    log p the documented limits."""
    s0, s1, om, Om, d = pt
    vals = [float(getattr(F, f)(s0, sigma1=s1, omega=om, Omega=Om, d=d)) for f in
            ("impact_probability", "no_impact_probability", "log_impact_probability",
             "log_no_impact_probability")]
    with mpmath.workprec(80), thread_mp().workprec(80):
        x, y = eq27_xy(s0, s1, om, Om, d)
        e = x * y / (x + y)
    if e > 1e308:  # log p below every float: the limits
        assert vals == [0.0, 1.0, -math.inf, 0.0]
        return
    _check(vals, pt, {}, c=c)


@pytest.mark.parametrize("pt", EXTREME)
def test_float64_extreme_scales_every_region(pt):
    """Scales far from d or from each other (the mantissa/exponent path and its limits)."""
    _check_public(pt)


#: scales whose sqrt(x) or sqrt(y) is beyond 1e154 (x or y not a float) or below 1e-154,
#: with results that are normal floats or finite logs: every region of the mantissa path
#: (both orders of the two scales, a given Omega and omega above 1e100)
_HUGE_SMALL = [1e-200, 3e-170, 2e-77, 1e200, 5e160, 3e76]


_OTHER = [0.05, 0.3, 0.36, 0.4, 0.55, 0.9, 2.0, 1e3, 1e80, 1e200]  # G(z) near z = 1, 2


MANTISSA = ([(a, b, 1.0, None, 1.0) for a in _HUGE_SMALL for b in _OTHER]
            + [(b, a, 1.0, None, 1.0) for a in _HUGE_SMALL for b in _OTHER]
            + [(1e-180, 0.4, 1.0, 1.7, 2.0), (0.4, 1e-180, 1.3, 0.6, 0.5),
               (1e180, 0.4, 1.0, 1.7, 2.0), (0.4, 3e190, 1.0, 2.5, 1.0),
               (1e-190, 1e150, 2.0, 1.0, 1.0), (2.0, 1e150, 3e105, None, 1.0),
               (1e210, 1e80, 2e105, None, 1.0), (1e-10, 1e150, 1e120, None, 1e-30),
               (0.3, 0.2, 1e160, None, 1e-160), (0.3, 1e200, 1.5e180, 1e180, 1.0),
               # omega != 1 with Omega None (|omega^2 - 2| != omega^2)
               (1e-200, 0.3, 0.5, None, 1.0), (0.3, 1e-200, 3.0, None, 1.0),
               (1e200, 0.4, 1.7, None, 1.0), (0.4, 1e200, 0.2, None, 1.0),
               # both scales moderate against d, d and |Delta| outside [1e-100, 1e100]
               (1e-120, 0.7, 1e60, None, 1e-120), (1e-120, 0.2, 1e60, 2.0, 1e-120),
               (2e-120, 3.0, 1e60, None, 1e-120),
               # both sqrt(x), sqrt(y) above 1e75 and comparable: log p = -uv, finite
               (1e-100, 1.5e-100, 1.0, None, 1.0), (2e-90, 1e-90, 0.5, None, 1.0)])


@pytest.mark.parametrize("pt", MANTISSA)
def test_float64_mantissa_exponent_path(pt):
    # C = 12 here: G(z) = phi~(z) - 2 psi~(z) by its closed form for 1 <= z < 2 cancels about
    # one digit (observed 8.4 eps for 1 - p at sigma = 3e76, sigma1 = 0.4)
    _check_public(pt, c=12.0)


def test_mixed_chunks_and_chunk_boundaries():
    """More values than one chunk (16384), entries of every region interleaved: every value
    equals its scalar evaluation and the reference."""
    base = [pt for pt in EXTREME if pt[2:] == (1.0, None, 1.0)]
    base += [(s, s * r, 1.0, None, 1.0) for s in (0.02, 0.3, 4.0, 60.0) for r in (1e-6, 1.0, 1e5)]
    n = 16384 + 5000
    idx = np.arange(n) % len(base)
    s0 = np.array([base[i][0] for i in idx])
    s1 = np.array([base[i][0] if base[i][1] is None else base[i][1] for i in idx])
    refs = [closed_form_values(b[0], b[1]) for b in base]
    for k, fn in enumerate((F.impact_probability, F.no_impact_probability,
                            F.log_impact_probability, F.log_no_impact_probability)):
        arr = fn(s0, sigma1=s1)
        assert arr.shape == (n,)
        for j, b in enumerate(base):
            vals = arr[idx == j]
            assert (vals == vals[0]).all(), (fn.__name__, b)
            one = float(fn(b[0], sigma1=b[1] if b[1] is not None else b[0]))
            assert vals[0] == one or (math.isnan(one) and math.isnan(vals[0])), (b, vals[0], one)
            ref = refs[j][k]
            kappa = refs[j][4 if k in (0, 2) else 5]
            if k < 2:
                if abs(ref) < TINY:
                    assert abs(one) < 2 * TINY
                else:
                    assert rel_err(one, ref) <= C * EPS * (1 + float(kappa)), (fn.__name__, b)
            elif mpmath.isfinite(ref) and abs(ref) < 1e300:
                bound = C * EPS * (1 + float(kappa) + abs(float(ref)))
                assert abs(mpmath.mpf(one) - ref) <= bound, (fn.__name__, b, one, ref)


def test_broadcast_shapes_and_empty():
    s = np.array([[0.1], [0.5]])
    d = np.array([0.5, 1.0, 2.0])
    out = F.impact_probability(s, d=d)
    assert out.shape == (2, 3)
    for i in range(2):
        for j in range(3):
            p = closed_form_values(float(s[i, 0]), None, 1.0, None, float(d[j]))[0]
            assert rel_err(out[i, j], p) < 16 * EPS * 20
    assert F.impact_probability(np.array([]), d=1.0).shape == (0,)
    assert F.no_impact_probability(np.zeros((2, 0)) + 1.0).shape == (2, 0)
    # sigma1 as the only array, Omega array (one component), omega array
    out = F.no_impact_probability(0.3, sigma1=np.array([0.1, 0.3, 2.0]), Omega=np.array([1.5]))
    for j, s1 in enumerate((0.1, 0.3, 2.0)):
        assert rel_err(out[j], closed_form_values(0.3, s1, 1.0, 1.5, 1.0)[1]) < 1e-14


# ------------------------------------------------------------------------------ building blocks
def test_delta_float_near_resonance_exact():
    """omega**2 - 2 for omega within ulps of sqrt(2) (Dekker split): relative error ~eps
    against exact rational arithmetic; and omega**2 - Omega**2 for a given Omega."""
    from fractions import Fraction

    r2 = math.sqrt(2.0)
    oms = np.array([math.nextafter(r2, 0), r2, math.nextafter(r2, 3), r2 * (1 + 1e-9), 0.3,
                    1e150, 1e-160, 3.7e100])
    got = delta_float(oms, None)
    for o, g in zip(oms, got, strict=True):
        exact = Fraction(float(o)) ** 2 - 2
        assert abs(Fraction(float(g)) - exact) <= abs(exact) * Fraction(EPS), (o, g)
    assert delta_float(np.array(2e160), None) == math.inf
    Om = np.array([0.9, 1.1, 2.0])
    g = delta_float(np.array(1.0), Om)
    for o, gv in zip(Om, g, strict=True):
        exact = 1 - Fraction(float(o)) ** 2
        assert abs(Fraction(float(gv)) - exact) <= abs(exact) * 2 * Fraction(EPS)
    # an underflowed product is no resonance
    assert delta_float(np.array(1e-200), np.array(2e-200)) == 0.0
    with pytest.raises(ValueError, match=r"resonance.*at index 1"):
        delta_float(np.array([1.0, 2.0]), np.array([1.5, 2.0]))
    with pytest.raises(ValueError, match="resonance"):
        delta_float(np.array(1.5), np.array(1.5))


def test_uv_building_blocks():
    hx, hy = np.array([0.3, 2.0, 5e-3]), np.array([0.7, 2.0, 40.0])
    uv = uv_from_h(hx, hy)
    for i in range(3):
        with mpmath.workdps(40), thread_mp().workdps(40):
            x, y = mpmath.mpf(hx[i]) ** 2, mpmath.mpf(hy[i]) ** 2
            r = mpmath.sqrt(x + y)
            for got, ref in ((uv.x[i], x), (uv.y[i], y), (uv.r[i], r), (uv.u[i], x / r),
                             (uv.v[i], y / r), (uv.e[i], x * y / (x + y))):
                assert rel_err(got, ref) < 4 * EPS
    s0, s1, om, Om, d = np.array(0.3), np.array([0.2, 5.0]), np.array(1.2), np.array(0.6), 0.8
    uv = uv_forcing(s0, s1, om, Om, d)
    for i in range(2):
        with mpmath.workdps(40), thread_mp().workdps(40):
            x, y = eq27_xy(float(s0), s1[i], float(om), float(Om), d)
            r = mpmath.sqrt(x + y)
            for got, ref in ((uv.x[i], x), (uv.y[i], y), (uv.r[i], r), (uv.u[i], x / r),
                             (uv.v[i], y / r), (uv.e[i], x * y / (x + y))):
                assert rel_err(got, ref) < 8 * EPS
    p = pq_float(uv, "p")
    q = pq_float(uv, "q")
    for i in range(2):
        ref = closed_form_values(float(s0), float(s1[i]), float(om), float(Om), d)
        assert rel_err(p[i], ref[0]) < C * EPS * (1 + float(ref[4]))
        assert rel_err(q[i], ref[1]) < C * EPS * (1 + float(ref[5]))


def test_i2_i3_against_quadrature():
    """The positive integrals on both sides of their switches (r = 2 and 3): Gauss-Legendre
    below, the closed form above; relative error within 64 eps (cancellation in the closed form
    just above the switch costs a few bits)."""
    us = np.array([1e-3, 0.05, 0.4, 0.9, 1.0, 1.2, 1.6, 2.2, 3.0, 7.0, 1e-3, 30.0])
    vs = np.array([2e-3, 0.5, 0.1, 0.9, 0.95, 0.5, 1.6, 0.5, 0.1, 2.0, 6.0, 30.0])
    i2, i3 = i2_float(us, vs), i3_float(us, vs)
    for k in range(len(us)):
        assert rel_err(i2[k], i_integral(us[k], vs[k], 1)) < 64 * EPS, (us[k], vs[k], i2[k])
        assert rel_err(i3[k], i_integral(us[k], vs[k], 2)) < 64 * EPS, (us[k], vs[k], i3[k])
    x, w = gauss_legendre(16)
    assert gauss_legendre(16)[0] is x  # cached
    assert abs(w.sum() - 2) < 1e-14 and len(x) == 16


def test_large_sigma_complement_leading_term():
    """1 - p -> d^4/(24 s0^2 s1^2) for scales far above d (independent: the density of each
    Rayleigh near 0 is r/s^2, the simplex volume is d^4/24)."""
    for s, s1 in ((1e6, 1e6), (3e7, 2e5), (1e30, 1e-2 * 1e30)):
        lead = 1.0 / (24 * (2 * s * s) * (2 * s1 * s1))
        q = F.no_impact_probability(s, sigma1=s1)
        assert abs(q / lead - 1) < 1e-5 * (1e6 / s) ** 2 + 16 * EPS
        assert abs(F.log_no_impact_probability(s, sigma1=s1) - math.log(lead)) < 1e-5


def test_series_truncation_table():
    """The number of Taylor terms used below z: the first omitted term at ``zmax[k]`` is the
    tolerance (1/21!), checked against the exact coefficients of phi~ and psi~."""
    from symhx.forcing.kernels_float import PHI1_C, PSI1_C, _series_zmax

    with mpmath.workdps(40), thread_mp().workdps(40):
        exact_phi = [(-1) ** n / mpmath.factorial(n + 1) for n in range(1, 20)]
        exact_psi = [(-1) ** n / (mpmath.factorial(n) * (2 * n + 1)) for n in range(1, 21)]
        tol = 1 / mpmath.factorial(21)
        for coeffs, exact in ((PHI1_C, exact_phi), (PSI1_C, exact_psi)):
            assert [float(c) for c in exact] == coeffs
            z = _series_zmax(coeffs)
            assert len(z) == len(coeffs) + 1 and z[0] == 0.0 and z[-1] == math.inf
            for k in range(1, len(coeffs)):
                assert abs(abs(exact[k]) * mpmath.mpf(z[k]) ** k / tol - 1) < 1e-12, k
            assert all(a < b for a, b in itertools.pairwise(z))


def test_gauss_legendre_fresh_orders(monkeypatch):
    from symhx.forcing import kernels_float

    monkeypatch.setattr(kernels_float, "_GL_CACHE", {})  # computed here, not inherited
    for n in (5, 11, 16):
        x, w = gauss_legendre(n)
        xs, _ = mpmath.mp.gauss_quadrature(n, "legendre")
        assert np.allclose(x, sorted(float(v) for v in xs), rtol=0, atol=1e-15)
        assert abs(w.sum() - 2) < 1e-14 and len(w) == n


def test_pq_float_keeps_the_shape_of_2d_input():
    s0 = np.array([[0.1, 0.5, 3.0], [0.2, 1.0, 20.0]])
    uv = uv_forcing(s0, s0 * 0.7, np.array(1.0), None, np.array(1.0))
    for want, k in (("p", 0), ("q", 1)):
        out = pq_float(uv, want)
        assert out.shape == (2, 3)
        for i in range(2):
            for j in range(3):
                r = closed_form_values(float(s0[i, j]), float(s0[i, j] * 0.7))
                assert rel_err(out[i, j], r[k]) < C * EPS * (1 + float(r[4 + k])), (want, i, j)


# ------------------------------------------------------------------------------ range checks
#: one value past each range test of :func:`single_float`'s fast path whose every other test
#: passes (so only that test sends it to the mantissa path): the fast path would be wrong there
RANGE_EDGES = [
    # |Delta| = 1.25e-312 is subnormal (its rounding error ~4e-12), d and r are ordinary
    (1e50, 1e-262, 1.5e-156, 1e-156, 1e50),
    # d = 1e200 > 1e100: d*d overflows, uv = 1.25e99 would be inf (log p = -inf)
    (1e150, None, 1.0, None, 1e200),
    # d/(2r) ~ 1.4e-160: sigma0**2 = 1e-320 is subnormal in uv
    (1e-160, None, 1.0, None, 1e-100),
]


@pytest.mark.parametrize("pt", RANGE_EDGES)
def test_single_float_each_range_test_alone(pt):
    _check_public(pt)


def test_single_float_range_tests_inside_arrays():
    """The same values as entries of 2- and 3-element arrays of Delta (omega, Omega arrays) and
    of d next to ordinary ones: every entry against the reference, arrays of two entries too
    (one value of each chunk is taken with ``.item()`` only for one-element arrays)."""
    pts = []
    s0, s1, om, Om, d = RANGE_EDGES[0]
    # the other entries ordinary (sqrt(y) ~ 1)
    oms, Oms = np.array([om, 1.1, 0.7]), np.array([Om, 0.6, 1.3])
    s1s = np.array([s1, 4e49, 6e49])
    for n in (2, 3):
        vals = [getattr(F, f)(s0, sigma1=s1s[:n], omega=oms[:n], Omega=Oms[:n], d=d) for f in
                ("impact_probability", "no_impact_probability", "log_impact_probability",
                 "log_no_impact_probability")]
        pts += [([float(v[i]) for v in vals], (s0, float(s1s[i]), float(oms[i]),
                                               float(Oms[i]), d)) for i in range(n)]
    s0, s1, om, Om, d = RANGE_EDGES[1]
    ds = np.array([d, 2.0e200, 3.0e200])
    for n in (2, 3):
        vals = [getattr(F, f)(s0, sigma1=s1, omega=om, Omega=Om, d=ds[:n]) for f in
                ("impact_probability", "no_impact_probability", "log_impact_probability",
                 "log_no_impact_probability")]
        pts += [([float(v[i]) for v in vals], (s0, s1, om, Om, float(ds[i]))) for i in range(n)]
    for vals, pt in pts:
        _check(vals, pt, {})


def test_single_float_scalar_in_float_out_and_two_element_chunks():
    fp = ForcingParams.validated(0.3, None, 1.0, None, 1.0)
    for w in WANTS:
        assert type(single_float(fp, w)) is float
    # two entries in every argument: no one-element shortcut applies
    s0, s1 = np.array([0.3, 2.0]), np.array([0.5, 0.4])
    om, Om, d = np.array([1.2, 0.8]), np.array([0.5, 1.9]), np.array([0.7, 1.5])
    vals = [getattr(F, f)(s0, sigma1=s1, omega=om, Omega=Om, d=d) for f in
            ("impact_probability", "no_impact_probability", "log_impact_probability",
             "log_no_impact_probability")]
    for i in range(2):
        _check([float(v[i]) for v in vals],
               (float(s0[i]), float(s1[i]), float(om[i]), float(Om[i]), float(d[i])), {})


def test_single_float_several_chunks_scalar_sigma1():
    """More values than one chunk, every one on the fast path, sigma1 a scalar (so sqrt(y) is
    one number broadcast over each chunk) and the last chunk of 2 values: each value against
    the reference."""
    base = [0.05, 0.3, 0.9, 4.0, 40.0]
    n = 16384 + 2
    s0 = np.array([base[i % len(base)] for i in range(n)])
    for k, f in enumerate(("impact_probability", "no_impact_probability",
                           "log_impact_probability", "log_no_impact_probability")):
        arr = getattr(F, f)(s0, sigma1=0.7, omega=1.2, Omega=0.5, d=1.3)
        for j, b in enumerate(base):
            sel = arr[j::len(base)]
            assert (sel == sel[0]).all(), (f, b)
            ref = closed_form_values(b, 0.7, 1.2, 0.5, 1.3)
            kappa = float(ref[4 if k in (0, 2) else 5])
            if k < 2:
                assert rel_err(sel[0], ref[k]) <= C * EPS * (1 + kappa), (f, b)
            else:
                assert abs(mpmath.mpf(sel[0]) - ref[k]) <= C * EPS * (1 + kappa
                                                                      + abs(float(ref[k])))


def test_uv_chunk_scalar_and_array_arguments():
    """:func:`uv_chunk` takes 1-D arrays of length m or scalars: every field has length m and
    the values of eqs. 24-25 (x, y, r, u, v, uv) within a few ulps, whatever mix is given."""
    from symhx.forcing.kernels_float import uv_chunk

    m = 3
    s0v, s1v, dev, dv = [0.3, 0.45, 2.0], [0.5, 0.2, 7.0], [0.84, 1.5, 3.0], [1.3, 0.4, 2.5]
    for mask in itertools.product((False, True), repeat=4):
        args = [np.array(v) if a else np.float64(v[0])
                for a, v in zip(mask, (s0v, s1v, dev, dv), strict=True)]
        uv = uv_chunk(*args, m)
        for f in uv:
            assert isinstance(f, np.ndarray) and f.shape == (m,), mask
        for i in range(m):
            s0, s1, de, d = (mpmath.mpf(v[i] if a else v[0])
                             for a, v in zip(mask, (s0v, s1v, dev, dv), strict=True))
            with mpmath.workdps(40), thread_mp().workdps(40):
                x, y = d * d / (4 * s0 * s0), (d * de) ** 2 / (4 * s1 * s1)
                r = mpmath.sqrt(x + y)
                for got, ref in ((uv.x[i], x), (uv.y[i], y), (uv.r[i], r), (uv.u[i], x / r),
                                 (uv.v[i], y / r), (uv.e[i], x * y / (x + y))):
                    assert rel_err(got, ref) < 8 * EPS, (mask, i)


#: (sigma0, sigma1) powers of two with omega = 1, Omega = None, d = 1, so that sqrt(x) =
#: 1/(2 sigma0) and sqrt(y) = 1/(2 sigma1) are exact: pq_float on uv_from_h (the route of
#: the Rayleigh-sum groups) sees the exact scales of the reference
_UNDER = [
    (2.0**536, 2.0**536),    # x = y = 2**-1074: uv = 2**-1075 rounds to 0, 1 - p underflows
    (2.0**265, 2.0**265),    # x = y = 2**-532: 1 - p ~ xy/6 is subnormal
    (2.0**265, 2.0**250),    # the same, unequal scales
    (1.0, 0.5),              # x = 1/4, y = 1: the complement form, ordinary
    (0.125, 0.0625),         # x = 16, y = 64: the direct form
    (2.0**100, 0.5),         # x = 2**-202, y = 1: 1 - p ~ 1e-61, normal
    (2.0**-201, 2.0**4),     # x = 2**400, y = 2**-10: log x + log y would cancel 2 digits
    (2.0**-170, 2.0**3),     # x = 2**338, y = 2**-8
    (2.0**-120, 2.0**2),     # x = 2**238, y = 2**-6
]


def test_pq_float_complement_underflow_and_zero_uv():
    """1 - p below the normal range (and uv = 0 after rounding) next to ordinary values in one
    array: 1 - p is 0 or subnormal, log(1 - p) the finite sum of logs, every other value to the
    contract; then each value alone (the arrays share the complement form's chunk)."""
    hx = np.array([0.5 / s0 for s0, _ in _UNDER])
    hy = np.array([0.5 / s1 for _, s1 in _UNDER])
    assert uv_from_h(hx[:1], hy[:1]).e[0] == 0.0  # the case of uv rounded to 0
    sets = [list(range(len(_UNDER)))] + [[i] for i in range(len(_UNDER))]
    for idx in sets:
        uv = uv_from_h(hx[idx], hy[idx])
        arrs = [pq_float(uv, w) for w in WANTS]
        for k, i in enumerate(idx):
            _check([float(a[k]) for a in arrs], (_UNDER[i][0], _UNDER[i][1], 1.0, None, 1.0), {})


def test_delta_float_dense_near_sqrt2_and_message():
    """omega**2 - 2 within one rounding of the exact rational value for 400 omegas within
    1e-6 of sqrt(2) (where omega**2 - 2 cancels up to 6 digits, and up to 15 next to it)."""
    from fractions import Fraction

    r2 = math.sqrt(2.0)
    oms = [r2 * (1 + k * 2.5e-9) for k in range(-200, 200)]
    oms += [float(np.nextafter(r2, 3) + k * 2.0**-52) for k in range(-20, 20)]
    got = delta_float(np.array(oms), None)
    for o, g in zip(oms, got, strict=True):
        exact = Fraction(o) ** 2 - 2
        assert abs(Fraction(float(g)) - exact) <= abs(exact) * Fraction(EPS) / 2, (o, g)
    assert_refuses(delta_float, np.array([1.0, 2.0]), np.array([1.5, 2.0]), arg="Omega",
                   value="at index 1", allowed="resonance Omega == omega")


#: omega > 1e100 with Omega = None (|Delta| = omega**2, maybe beyond float64) and both
#: sqrt(x), sqrt(y) ~ 1: the mantissa path's both-moderate region
OMEGA_HUGE = [(1.0, 1e240, 1e120, None, 1.0), (1e-160, 1e160, 1e160, None, 1e-160),
              (0.7, 3e250, 2e125, None, 0.5)]


@pytest.mark.parametrize("pt", OMEGA_HUGE)
def test_float64_huge_omega_moderate_scales(pt):
    _check_public(pt)


def test_kernels_under_any_numpy_error_state():
    """The kernels set their own numpy error state where they under/overflow on purpose: under
    the caller's ``np.errstate(all="raise")`` every public float64 function gives the same
    values at every extreme point above, and the building blocks run on inputs that overflow,
    underflow and divide by zero inside them (with the values of the default error state)."""
    from symhx.forcing.kernels_float import pq_extreme

    fns = ("impact_probability", "no_impact_probability", "log_impact_probability",
           "log_no_impact_probability")
    for pt in EXTREME + MANTISSA + RANGE_EDGES + OMEGA_HUGE:
        s0, s1, om, Om, d = pt
        ref = [getattr(F, f)(s0, sigma1=s1, omega=om, Omega=Om, d=d) for f in fns]
        with np.errstate(all="raise"):
            got = [getattr(F, f)(s0, sigma1=s1, omega=om, Omega=Om, d=d) for f in fns]
        assert got == ref, pt
    big_small = np.array([1e-200, 1e200, 0.3])
    calls = [
        lambda: delta_float(np.array([2e160, 1e-200, 1.3]), None),
        lambda: delta_float(np.array([1e200, 1e-200]), np.array([1e-200, 3e-200])),
        lambda: uv_forcing(big_small, np.array([1e-200, 1e-200, 1e200]), np.array(1.0), None,
                           np.array(1.0)),
        lambda: uv_forcing(np.array([5e-324, 0.3]), np.array([5e-324, 1e-300]),
                           np.array([1.0, 1e-160]), np.array([2.0, 2e-160]), np.array(1.0)),
        lambda: uv_from_h(np.array([1e200, 0.0, 1e-200]), np.array([1e-200, 0.0, 1e-200])),
        lambda: pq_float(uv_from_h(np.array([1e200, 1e-160, 0.5]),
                                   np.array([1e-200, 1e-160, 0.7])), "logq"),
        lambda: i2_float(np.array([30.0, 0.1, 27.0]), np.array([40.0, 0.2, 0.5])),
        lambda: i3_float(np.array([30.0, 0.1, 27.0]), np.array([40.0, 0.2, 0.5])),
        lambda: pq_extreme(big_small, big_small[::-1], np.array([1.0, 1e160, 2.0]), None,
                           np.array([1.0, 1e-160, 1e200]), "logp"),
    ]
    for k, call in enumerate(calls):
        ref = call()
        with np.errstate(all="raise"):
            got = call()
        for a, b in zip(ref if isinstance(ref, tuple) else (ref,),
                        got if isinstance(got, tuple) else (got,), strict=True):
            np.testing.assert_array_equal(a, b, err_msg=str(k))


#: one scale beyond 1e75 against d and uv beyond every float (e = inf in the limit form of
#: the mantissa path, where u and f are inf too): p = 0, 1 - p = 1, log p = -inf, no NaN
UV_INF = [(4.7e-272, 1.5e-66, 2.9e93, None, 5e145), (2.8e-277, 1e-84, 6.8e93, None, 2.9e86),
          (3.6e-259, 1.9e-232, 3.9e25, None, 2.9e113)]


@pytest.mark.parametrize("pt", UV_INF)
def test_float64_uv_beyond_floats_limit_form(pt):
    _check_public(pt)


#: Delta = omega**2 - Omega**2 subnormal or underflowing to 0 (its float product loses digits),
#: omega**2 beyond float64 with Omega None, sqrt(x) beyond float64: sqrt(y), uv still normal
UV_FORCING_EDGES = [(0.5, 1e-300, 1e-160, 2e-160, 1.0), (0.5, 1e-300, 1e-200, 1e-199, 1.0),
                    (0.5, 1e300, 1e200, None, 1.0), (0.5, 3e-300, 2e-160, 1e-160, 0.7),
                    (0.4, 0.3, 0.7, None, 1.2), (0.4, 0.3, 0.7, 1.9, 1.2)]


def test_uv_forcing_where_delta_under_or_overflows():
    """uv_forcing (the derivative's scales) against exact rational x, y: every field within a
    few ulps where Delta itself is no normal float; uv right where sqrt(x) overflows; and the
    float64 derivative there against its mpmath route (exact Delta, quadrature-free closed
    forms at 30 digits: an independent evaluation of the same formula)."""
    for s0, s1, om, Om, d in UV_FORCING_EDGES:
        uv = uv_forcing(np.array(s0), np.array(s1), np.array(om),
                        None if Om is None else np.array(Om), np.array(d))
        with mpmath.workdps(40), thread_mp().workdps(40):
            x, y = eq27_xy(s0, s1, om, Om, d)
            r = mpmath.sqrt(x + y)
            for got, ref in ((uv.x, x), (uv.y, y), (uv.r, r), (uv.u, x / r), (uv.v, y / r),
                             (uv.e, x * y / (x + y))):
                assert rel_err(float(got), ref) < 8 * EPS, (s0, s1, om, Om, d)
        got = F.dp_dsigma(s0, sigma1=s1, omega=om, Omega=Om, d=d)
        ref = F.dp_dsigma(s0, sigma1=s1, omega=om, Omega=Om, d=d, dps=30)
        assert rel_err(got, ref) < 64 * EPS, (s0, s1, om, Om, d, got, ref)
    # sqrt(x) beyond float64 (then uv ~ y), both beyond (uv = inf), next to ordinary values and
    # omega > 1e100 in one array
    s0 = np.array([5e-324, 5e-324, 0.5, 0.4])
    s1 = np.array([0.3, 5e-324, 1e300, 0.3])
    om = np.array([1.0, 1.0, 1e200, 0.7])
    uv = uv_forcing(s0, s1, om, None, np.array(1.0))
    assert uv.r[0] == uv.r[1] == uv.e[1] == math.inf
    for i in (0, 2, 3):
        with mpmath.workdps(40), thread_mp().workdps(40):
            x, y = eq27_xy(float(s0[i]), float(s1[i]), float(om[i]), None, 1.0)
            assert rel_err(uv.e[i], x * y / (x + y)) < 8 * EPS, i
            if i:
                assert rel_err(uv.u[i], x / mpmath.sqrt(x + y)) < 8 * EPS, i
    with pytest.raises(ValueError, match="resonance"):
        uv_forcing(np.array(0.3), np.array(0.3), np.array(1.5), np.array(1.5), np.array(1.0))


def test_near_resonance_with_default_omega_sqrt2():
    """omega = fl(sqrt 2) is not sqrt 2: a (very) near resonance, not an error, and both paths
    agree on omega**2 - 2 = 2.7e-16 exactly (float64 uses an exact two-product)."""
    pf = F.no_impact_probability(0.1, omega=math.sqrt(2.0))
    pm = F.no_impact_probability(0.1, omega=math.sqrt(2.0), dps=30)
    assert 0 < pf < 1e-10
    assert rel_err(pf, pm) < 1e-13
