"""symhx.forcing: several forcing components, inverse sigma(p), dp/dsigma, the theory chain."""

from __future__ import annotations

import math

import mpmath
import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from symhx import forcing as F

EPS = np.finfo(float).eps


def rel(a, b):
    with mpmath.workdps(100):
        return abs(mpmath.mpf(a) / mpmath.mpf(b) - 1)


# ----------------------------------------------------------------------------- several components
def direct_three(scales, d, dps, upper):
    """P(R0+R1+R2 > d) or <= d by 2-D mpmath quadrature of the product of Rayleigh densities
    and the third Rayleigh's tail/CDF (no closed forms of the package are used)."""
    with mpmath.workdps(dps):
        a, b, c = (mpmath.mpf(s) for s in scales)
        d = mpmath.mpf(d)

        def f(s, sc):
            return s / sc**2 * mpmath.exp(-s**2 / (2 * sc**2))

        if upper:
            # P(sum > d) = 1 - P(sum <= d) is cancellation-free only for p not small: the
            # chosen cases have p > 1e-3
            inner = lambda t0, t1: -mpmath.expm1(-(d - t0 - t1) ** 2 / (2 * c**2))  # noqa: E731
            q = mpmath.quad(lambda t0: mpmath.quad(lambda t1: f(t0, a) * f(t1, b)
                                                   * inner(t0, t1), [0, d - t0]), [0, d])
            return 1 - q
        inner = lambda t0, t1: -mpmath.expm1(-(d - t0 - t1) ** 2 / (2 * c**2))  # noqa: E731
        return mpmath.quad(lambda t0: mpmath.quad(lambda t1: f(t0, a) * f(t1, b)
                                                  * inner(t0, t1), [0, d - t0]), [0, d])


@pytest.mark.parametrize("scales, d", [([0.5, 0.3, 0.2], 1.0), ([2.0, 0.7, 1.1], 1.3)])
def test_three_rayleighs_against_direct_2d_quadrature(scales, d):
    for upper in (True, False):
        ref = direct_three(scales, d, 20, upper)
        tail = "upper" if upper else "lower"
        res = F.rayleigh_sum_probability(scales, d, tail=tail, dps=15)
        assert rel(res.value, ref) < 1e-14
        resf = F.rayleigh_sum_probability(scales, d, tail=tail)
        assert rel(resf.value, ref) < 1e-13


def test_one_component_list_matches_closed_form():
    s = np.logspace(-2, 2, 9)
    a = F.impact_probability(s, Omega=[1.7], sigma1=[0.3])
    b = F.impact_probability(s, Omega=1.7, sigma1=0.3)
    assert np.all(np.abs(a / b - 1) < 4 * EPS)


def test_pair_of_identical_components_equals_merged_quadrature_path():
    """Two components with scales s1, s2 plus R0: total through the 3-scale convolution equals
    the Rayleigh-sum function on the explicit scales (consistency of eq. 22 scales)."""
    kw = dict(sigma1=[0.05, 0.2], omega=1.0, Omega=[1.5, 3.0], d=1.0)
    p = F.impact_probability(0.1, **kw)
    scales = F.rayleigh_scales(0.1, sigma1=[0.05, 0.2], omega=1.0, Omega=[1.5, 3.0])
    assert scales[1] == math.sqrt(2) * 0.05 / abs(1 - 1.5**2)
    assert p == F.rayleigh_sum_probability(scales, 1.0).value


@pytest.mark.parametrize("nscales", [3, 4])
@pytest.mark.parametrize("sigma", [0.02, 0.15, 1.0, 30.0])
def test_several_components_float_vs_mpmath_both_tails(nscales, sigma):
    Omegas = [1.7, 0.4, 2.5][: nscales - 1]
    sig1 = [1.0, 0.5, 2.0][: nscales - 1]
    kw = dict(sigma1=[sigma * r for r in sig1], Omega=Omegas)
    for fn, tail in ((F.impact_probability, "upper"), (F.no_impact_probability, "lower")):
        got = fn(sigma, **kw)
        ref = fn(sigma, **kw, dps=25)
        if got < 1e-300:  # only where the true value is below the float64 normal range
            assert ref < 1e-300 and abs(got - ref) <= 1e-13 * ref + 2**-1073, (fn.__name__, ref)
            continue
        # contract: 1e-13 + 4 kappa eps, kappa ~ 2|ln p| in the small tail
        assert rel(got, ref) < 1e-13 + 8 * EPS * abs(math.log(got)), (fn.__name__, got, ref)
        scales = F.rayleigh_scales(sigma, **kw)
        res = F.rayleigh_sum_probability(scales, 1.0, tail=tail)
        assert rel(res.value, ref) < res.error / res.value  # the error estimate bounds the error


def test_five_scales_two_nested_quadratures():
    """M = 4 components (5 Rayleighs, 2-D nesting): float64 against mpmath (one point, the
    mpmath 2-D nesting costs seconds) and against a different grouping of the same scales."""
    scales = [0.3, 0.1, 0.25, 0.2, 0.15]
    res = F.rayleigh_sum_probability(scales, 1.0)
    ref = F.rayleigh_sum_probability(scales, 1.0, dps=12)
    assert rel(res.value, ref.value) < 1e-12
    for perm in ([0.15, 0.2, 0.3, 0.25, 0.1], [0.1, 0.3, 0.15, 0.25, 0.2]):
        for tail in ("upper", "lower"):
            a = F.rayleigh_sum_probability(scales, 1.0, tail=tail)
            b = F.rayleigh_sum_probability(perm, 1.0, tail=tail)
            assert rel(a.value, b.value) < a.error / a.value + b.error / b.value
    tiny = F.rayleigh_sum_probability([s / 6 for s in scales], 1.0)  # deep upper tail
    big = F.rayleigh_sum_probability([s * 40 for s in scales], 1.0, tail="lower")  # deep lower
    assert 0 < tiny.value < 1e-30 and tiny.error < 1e-12 * tiny.value
    assert 0 < big.value < 1e-15 and big.error < 1e-12 * big.value


def test_several_components_mpmath_converges_with_dps():
    kw = dict(sigma1=[0.08, 0.03], Omega=[1.7, 0.4])
    lo = F.rayleigh_sum_probability(F.rayleigh_scales(0.04, **kw, dps=40), 1, dps=20)
    hi = F.rayleigh_sum_probability(F.rayleigh_scales(0.04, **kw, dps=40), 1, dps=40)
    assert rel(lo.value, hi.value) < mpmath.mpf(10) ** -20
    assert lo.error < mpmath.mpf(10) ** -21 * lo.value
    assert hi.value < 1e-15  # a deep tail


def test_several_components_bad_input():
    with pytest.raises(ValueError, match=r"Omega\[1\]: resonance"):
        F.impact_probability(0.1, Omega=[1.5, 1.0])
    with pytest.raises(ValueError, match="sigma1"):
        F.impact_probability(0.1, Omega=[1.5, 2.0], sigma1=[0.1])
    with pytest.raises(ValueError, match=r"sigma1\[1\]"):
        F.impact_probability(0.1, Omega=[1.5, 2.0], sigma1=[0.1, -1.0])
    with pytest.raises(ValueError, match="scales"):
        F.rayleigh_sum_probability([0.1, float("nan")], 1.0)
    with pytest.raises(ValueError, match="tail"):
        F.rayleigh_sum_probability([0.1, 0.2], 1.0, tail="both")


# ----------------------------------------------------------------------------- derivative
@pytest.mark.parametrize("sigma", ["0.013", "0.05", "0.3", "2", "80"])
@pytest.mark.parametrize("sigma1", [None, "0.07"])
def test_dp_dsigma_against_mpmath_diff(sigma, sigma1):
    with mpmath.workdps(70):  # central difference, h = 1e-20: O(h^2) and roundoff ~1e-40
        ref = mpmath.diff(lambda s: F.impact_probability(s, sigma1=sigma1, Omega=1.9, dps=60),
                          mpmath.mpf(sigma), h=mpmath.mpf("1e-20"))
        got = F.dp_dsigma(sigma, sigma1=sigma1, Omega=1.9, dps=30)
        assert rel(got, ref) < 1e-28
        gf = F.dp_dsigma(float(sigma), sigma1=None if sigma1 is None else float(sigma1),
                         Omega=1.9)
        if ref > 1e-300:  # normal float range
            assert rel(gf, ref) < 1e-12
        else:  # below it: the float answer is the subnormal rounding of ref, or 0
            assert abs(gf - ref) <= 2**-1074 + 1e-12 * ref


def test_dp_dsigma_several_components():
    kw = dict(Omega=[1.5, 2.5])
    h = 1e-5
    fd = (F.impact_probability(0.3 + h, **kw) - F.impact_probability(0.3 - h, **kw)) / (2 * h)
    assert abs(F.dp_dsigma(0.3, **kw) / fd - 1) < 1e-8
    with mpmath.workdps(40):  # p at 35 digits: the difference quotient keeps ~23 digits
        ref = mpmath.diff(lambda s: F.impact_probability(s, **kw, dps=35), mpmath.mpf("0.3"),
                          h=mpmath.mpf("1e-12"))
        assert rel(F.dp_dsigma("0.3", **kw, dps=20), ref) < 1e-18


# ----------------------------------------------------------------------------- inverse
@pytest.mark.parametrize("p", [1e-300, 1e-30, 1e-10, 0.01, 0.5, 0.9, 1 - 1e-9, 1 - 1e-15])
def test_inverse_round_trip_float(p):
    s = F.sigma_for_impact_probability(p)
    if p <= 0.5:
        assert rel(F.impact_probability(s), p) < 1e-12 + 8 * EPS * abs(math.log(p))
    else:
        assert rel(F.no_impact_probability(s), 1 - p) < 1e-12


def test_inverse_mpmath_and_arrays():
    with mpmath.workdps(60):
        for p in ("1e-400", "1e-20", "0.3", "0.999999"):
            s = F.sigma_for_impact_probability(p, dps=40, Omega=1.9, d=0.5)
            back = F.impact_probability(s, Omega=1.9, d=0.5, dps=45)
            if mpmath.mpf(p) < 0.5:
                assert rel(back, mpmath.mpf(p)) < mpmath.mpf(10) ** -37
            else:
                assert rel(1 - back, 1 - mpmath.mpf(p)) < mpmath.mpf(10) ** -33
    arr = F.sigma_for_impact_probability(np.array([1e-5, 0.2, 0.7]))
    assert arr.shape == (3,) and np.all(np.diff(arr) > 0)


def test_inverse_fixed_sigma1_and_components():
    s = F.sigma_for_impact_probability(0.3, sigma1=0.2)
    assert rel(F.impact_probability(s, sigma1=0.2), 0.3) < 1e-13
    with pytest.raises(ValueError, match="not reachable"):
        # with sigma1 fixed, p(sigma0 -> 0) = P(R1 > 1) = exp(-1/(4 * 0.4**2)) ~ 0.21
        F.sigma_for_impact_probability(0.1, sigma1=0.4)
    s2 = F.sigma_for_impact_probability(1e-6, Omega=[1.5, 2.5])
    assert rel(F.impact_probability(s2, Omega=[1.5, 2.5]), 1e-6) < 1e-12
    with pytest.raises(ValueError, match="p must be in"):
        F.sigma_for_impact_probability(np.array([0.5, 1.0]))


# ----------------------------------------------------------------------------- theory chain
def test_theory_curve_is_the_composition():
    from symhx.api import mean, mode

    tc = F.theory_curve([0.06, 0.12, 0.2], N=101, dps=20)
    for s, p, m, k in zip(tc.sigma, tc.p, tc.mean, tc.mode, strict=True):
        pm = F.impact_probability(float(s), dps=20)
        assert rel(p, pm) < 1e-15
        assert rel(m, mean(101, pm, dps=20)) < 1e-15
        assert k == mode(101, pm)
    assert np.all(np.diff(tc.mean) > 0)


# ----------------------------------------------------------------------------- properties
@settings(max_examples=60, deadline=None)
@given(
    sigma=st.floats(1e-2, 1e2),
    ratio=st.floats(0.05, 20),
    omega=st.floats(0.2, 3.0),
    Omega=st.floats(0.2, 3.0),
    d=st.floats(0.05, 5.0),
)
def test_property_p_and_q_complementary_and_accurate(sigma, ratio, omega, Omega, d):
    if abs(omega - Omega) < 1e-3:
        return
    kw = dict(sigma1=ratio * sigma, omega=omega, Omega=Omega, d=d)
    p = F.impact_probability(sigma, **kw)
    q = F.no_impact_probability(sigma, **kw)
    assert 0 <= p <= 1 and 0 <= q <= 1
    assert abs(p + q - 1) <= 8 * EPS
    lp = F.log_impact_probability(sigma, **kw)
    ref = F.log_impact_probability(sigma, **kw, dps=25)
    assert abs(lp - ref) <= 1e-13 * max(1.0, abs(ref))


# ----------------------------------------------------------------------------- CLI
def test_cli_p_sigma(tmp_path, capsys):
    from symhx.cli import main

    assert main(["p-sigma", "0.12", "--dps", "40"]) == 0
    out = capsys.readouterr().out
    line = next(ln for ln in out.splitlines() if ln.strip().startswith("p "))
    with mpmath.workdps(50):
        printed = mpmath.mpf(line.split("=")[1].strip())
        assert rel(printed, F.impact_probability("0.12", dps=45)) < mpmath.mpf(10) ** -38
    csvf = tmp_path / "grid.csv"
    assert main(["p-sigma", "--grid", "0.01", "100", "7", "--csv", str(csvf)]) == 0
    rows = csvf.read_text().splitlines()
    assert rows[0].startswith("sigma,p,one_minus_p") and len(rows) == 8
    assert main(["p-sigma", "-1"]) == 2
    assert "sigma must be > 0" in capsys.readouterr().err
    assert main(["p-sigma", "0.1", "--Omega", "1.0"]) == 2  # resonance
