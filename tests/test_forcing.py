"""Tests of symhx.forcing: impact probability p(sigma) (eqs. 22-27) for one forcing component.

Accuracy references are never numbers copied from our output: they are (a) the mpmath path
recomputed at higher precision, (b) direct mpmath quadrature of eq. (27) / eq. (26), written
here independently of the package's closed form.
"""

from __future__ import annotations

import math

import mpmath
import numpy as np
import pytest

from symhx import forcing as F

EPS = np.finfo(float).eps

# ----------------------------------------------------------------------------- references


def eq27_q(sigma0, sigma1, omega, Omega2, d, dps):
    """1 - p by direct 2-D quadrature of eq. (27) (the double integral itself), in mpmath."""
    with mpmath.workdps(dps):
        s0, s1, om, d = (mpmath.mpf(v) for v in (sigma0, sigma1, omega, d))
        k = (om**2 - Omega2) ** 2
        c = k / (4 * s0**2 * s1**2)

        def inner(x):
            return mpmath.quad(
                lambda t: t * (x - t) * mpmath.exp(-t**2 / (4 * s0**2))
                * mpmath.exp(-k * (x - t) ** 2 / (4 * s1**2)),
                [0, x / 2, x],
            )

        return c * mpmath.quad(inner, [0, d / 2, d])


def eq26_p(sigma0, sigma1, omega, Omega2, d, dps):
    """p = P(Y0 > d) + int_0^d f_Y0(t) P(Z > d - t) dt (eqs. 24-26), 1-D mpmath quadrature.

    Positive integrand, so it keeps its relative accuracy for tiny p; the interval is split
    around the Gaussian peak of the integrand.
    """
    with mpmath.workdps(dps):
        s0, s1, om, d = (mpmath.mpf(v) for v in (sigma0, sigma1, omega, d))
        k = (om**2 - Omega2) ** 2
        a2 = 2 * s0**2  # Rayleigh scale**2 of Y0 (eq. 24)
        b2 = 2 * s1**2 / k  # of Y1/|omega^2 - Omega^2| (eq. 25)

        # scaled by exp(E) (E = d^2/(2(a2+b2)), the peak's exponent) because mpmath.quad
        # judges convergence by an absolute error
        E = d**2 / (2 * (a2 + b2))

        def f(t):
            return t / a2 * mpmath.exp(E - t**2 / (2 * a2) - (d - t) ** 2 / (2 * b2))

        tstar = d * a2 / (a2 + b2)
        w = mpmath.sqrt(a2 * b2 / (a2 + b2))
        cuts = {min(max(tstar + c * w, 0), d) for c in (-8, -3, 0, 3, 8)}
        pts = sorted({mpmath.mpf(0), d} | cuts)
        return mpmath.exp(-E) * (mpmath.exp(E - d**2 / (2 * a2)) + mpmath.quad(f, pts))


CASES = [  # (omega, Omega or None, d)
    (1.0, None, 1.0),  # the paper
    (0.7, 1.9, 0.3),
    (2.0, 1.0, 3.0),
    (1.0, 1.001, 1.0),  # near resonance: huge forced amplitude
    (1.3, 0.2, 0.05),
]
RATIOS = [None, 0.1, 3.0, 30.0]  # sigma1 = ratio * sigma (None: sigma1 = sigma)


def rel(a, b):
    """|a/b - 1| evaluated at 100 digits (never at the global mpmath precision)."""
    with mpmath.workdps(100):
        return abs(mpmath.mpf(a) / mpmath.mpf(b) - 1)


def _om2(Omega):
    with mpmath.workprec(200):  # the square of a double is exact in 106 bits
        return mpmath.mpf(2) if Omega is None else mpmath.mpf(Omega) ** 2


# ----------------------------------------------------------------------------- closed form
@pytest.mark.parametrize(
    "sigma, ratio, case",
    [(0.12, None, 0), (0.3, 2.0, 1), (0.05, 3.0, 4), (2.0, None, 3)],
)
def test_closed_form_matches_eq27_double_integral(sigma, ratio, case):
    omega, Omega, d = CASES[case]
    s1 = sigma if ratio is None else ratio * sigma
    ref = eq27_q(sigma, s1, omega, _om2(Omega), d, 20)
    got = F.no_impact_probability(sigma, sigma1=s1, omega=omega, Omega=Omega, d=d, dps=20)
    assert rel(got, ref) < mpmath.mpf(10) ** -17


@pytest.mark.parametrize(
    "sigma, ratio, case",
    [(0.01, None, 0), (0.05, None, 0), (0.12, None, 0), (0.02, 0.1, 1), (0.03, 30.0, 2),
     (0.5, 3.0, 3), (0.004, 1.0, 4), (7.0, None, 0)],
)
def test_p_matches_eq26_quadrature_in_the_small_tail(sigma, ratio, case):
    omega, Omega, d = CASES[case]
    s1 = sigma if ratio is None else ratio * sigma
    ref = eq26_p(sigma, s1, omega, _om2(Omega), d, 45)
    got = F.impact_probability(sigma, sigma1=s1, omega=omega, Omega=Omega, d=d, dps=30)
    assert rel(got, ref) < mpmath.mpf(10) ** -29


# ----------------------------------------------------------------------------- mpmath path
@pytest.mark.parametrize("dps", [15, 30, 50])
def test_mpmath_correct_to_dps_against_twice_dps(dps):
    tol = mpmath.mpf(10) ** (-dps)
    for sigma in ("0.0123", "0.05", "0.12", "0.7", "3", "99.5", "1e6"):
        for ratio, case in [(None, 0), ("0.3", 1), ("7", 2), (None, 3)]:
            omega, Omega, d = CASES[case]
            s1 = None if ratio is None else mpmath.mpf(ratio) * mpmath.mpf(sigma)
            kw = dict(sigma1=s1, omega=omega, Omega=Omega, d=d)
            for fn in (F.impact_probability, F.no_impact_probability):
                lo = fn(sigma, **kw, dps=dps)
                hi = fn(sigma, **kw, dps=2 * dps)
                assert rel(lo, hi) < tol, (fn.__name__, sigma, ratio, case)


def test_mpmath_p_plus_q_is_one_and_logs_agree():
    for sigma in ("0.01", "0.2", "40"):
        with mpmath.workdps(60):
            p = F.impact_probability(sigma, dps=50)
            q = F.no_impact_probability(sigma, dps=50)
            assert abs(p + q - 1) < mpmath.mpf(10) ** -50
            assert abs(F.log_impact_probability(sigma, dps=50) - mpmath.log(p)) < 1e-45
            assert abs(F.log_no_impact_probability(sigma, dps=50) - mpmath.log(q)) < 1e-45


def test_omega_none_is_exact_sqrt2_in_mpmath():
    with mpmath.workdps(80):
        sqrt2 = mpmath.sqrt(2)
        a = F.impact_probability("0.1", dps=60)
        b = F.impact_probability("0.1", Omega=sqrt2, dps=60)
        assert rel(a, b) < mpmath.mpf(10) ** -58


def test_mpmath_string_inputs_are_exact_decimals():
    with mpmath.workdps(50):
        a = F.impact_probability("0.1", dps=40)
        b = F.impact_probability(0.1, dps=40)  # the binary double nearest 0.1
        # p'(0.1)/p * |0.1 - float(0.1)| / 0.1 ~ 57 * 5.5e-18: distinguishable at 40 digits
        assert rel(a, b) > mpmath.mpf(10) ** -20


# ----------------------------------------------------------------------------- float64 vs mpmath
def _kappa_mp(sigma, s1, kw):
    """|d ln p/d ln sigma| with every sigma_i scaled together, by mpmath central difference."""
    with mpmath.workdps(40):
        h = mpmath.mpf(10) ** -12
        sm, sp = mpmath.mpf(sigma) * (1 - h), mpmath.mpf(sigma) * (1 + h)
        s1m = None if s1 is None else mpmath.mpf(s1) * (1 - h)
        s1p = None if s1 is None else mpmath.mpf(s1) * (1 + h)
        pm = F.impact_probability(sm, sigma1=s1m, **kw, dps=35)
        pp = F.impact_probability(sp, sigma1=s1p, **kw, dps=35)
        return float((pp - pm) / (2 * h))  # = sigma dp/dsigma


def _grid_errors(sigmas, case, ratio):
    omega, Omega, d = CASES[case]
    kw = dict(omega=omega, Omega=Omega, d=d)
    s1 = None if ratio is None else ratio * sigmas
    p = F.impact_probability(sigmas, sigma1=s1, **kw)
    q = F.no_impact_probability(sigmas, sigma1=s1, **kw)
    worst = {"p": 0.0, "q": 0.0}
    for i, s in enumerate(sigmas):
        s1i = None if s1 is None else s1[i]
        pm = F.impact_probability(s, sigma1=s1i, **kw, dps=30)
        qm = F.no_impact_probability(s, sigma1=s1i, **kw, dps=30)
        sdp = abs(_kappa_mp(s, s1i, kw))
        for name, val, ref in (("p", p[i], pm), ("q", q[i], qm)):
            if ref < np.finfo(float).tiny:
                continue  # only normal floats are in the contract
            kappa = sdp / float(ref)
            bound = 1e-13 + 4 * kappa * EPS
            worst[name] = max(worst[name], float(rel(val, ref)) / bound)
    return worst


@pytest.mark.parametrize("case", range(len(CASES)))
@pytest.mark.parametrize("ratio", RATIOS)
def test_float64_within_bound_on_log_grid(case, ratio):
    """Max relative error <= 1e-13 + 4 kappa eps for p and 1 - p on sigma in [0.01, 100].

    (Observed worst case: ~0.11 of the bound for p, ~0.04 for 1 - p.)
    """
    sigmas = np.logspace(-2, 2, 81)
    worst = _grid_errors(sigmas, case, ratio)
    assert worst["p"] <= 1.0, worst
    assert worst["q"] <= 1.0, worst


def test_float64_few_ulps_where_well_conditioned():
    """Stronger than the contract: within 40 eps where kappa is small (both tails covered)."""
    sigmas = np.logspace(-1, 4, 60)
    p = F.impact_probability(sigmas)
    q = F.no_impact_probability(sigmas)
    for i, s in enumerate(sigmas):
        assert rel(p[i], F.impact_probability(s, dps=25)) < 40 * EPS * (1 + 1 / s**2)
        assert rel(q[i], F.no_impact_probability(s, dps=25)) < 40 * EPS


def test_float64_tails_are_nonzero_and_accurate_where_naive_is_zero():
    # p at sigma = 0.0125: ~1e-348 -> 0 in float64 but its log is exact
    lp = F.log_impact_probability(np.array([0.0025, 0.01, 0.03]))
    for s, v in zip([0.0025, 0.01, 0.03], lp, strict=True):
        ref = F.log_impact_probability(s, dps=30)
        assert rel(v, ref) < 4 * EPS
    # 1 - p at sigma = 1e100 is ~1e-402 (below float range): its log is exact
    lq = F.log_no_impact_probability(np.array([1e2, 1e50, 1e100, 1e150]))
    for s, v in zip([1e2, 1e50, 1e100, 1e150], lq, strict=True):
        ref = F.log_no_impact_probability(s, dps=30)
        assert rel(v, ref) < 4 * EPS


def test_large_sigma_leading_term():
    """1 - p -> d^4/(24 s0^2 s1^2) (density r/s^2 near 0 of each Rayleigh, simplex volume)."""
    for s, s1, om, Om, d in [(1e4, 1e4, 1.0, None, 1.0), (3e3, 5e2, 0.7, 2.0, 0.3)]:
        k = abs(om**2 - (2.0 if Om is None else Om**2))
        s0sq, s1sq = 2 * s**2, 2 * s1**2 / k**2
        lead = d**4 / (24 * s0sq * s1sq)
        q = F.no_impact_probability(s, sigma1=s1, omega=om, Omega=Om, d=d)
        assert abs(q / lead - 1) < 1e-5


# ----------------------------------------------------------------------------- naive formula
def test_naive_dblquad_formula_fails_in_the_small_tail():
    """Documents the failure this module fixes: 1 - dblquad(eq. 27) at sigma = 0.05.

    The true p is ~2.4e-21 (checked against eq. 26 quadrature here); the naive value is
    rounding noise of size ~1e-13 (or 0, or negative, depending on the platform).
    """
    true = eq26_p(0.05, 0.05, 1, 2, 1, 30)
    naive = F.naive_impact_probability(0.05)
    ours = F.impact_probability(0.05)
    assert rel(ours, true) < 1e-14
    assert abs(naive - float(true)) > 1e6 * float(true)  # not a single correct digit
    # where p is not small the naive formula is fine (so the comparison is fair)
    assert abs(F.naive_impact_probability(0.5) / F.impact_probability(0.5) - 1) < 1e-8


# ----------------------------------------------------------------------------- bad input
@pytest.mark.parametrize("dps", [None, 20])
@pytest.mark.parametrize(
    "kwargs, name",
    [
        (dict(sigma=0.0), "sigma"),
        (dict(sigma=-1.0), "sigma"),
        (dict(sigma=float("nan")), "sigma"),
        (dict(sigma=float("inf")), "sigma"),
        (dict(sigma=0.1, sigma1=0.0), "sigma1"),
        (dict(sigma=0.1, sigma1=float("nan")), "sigma1"),
        (dict(sigma=0.1, d=0.0), "d"),
        (dict(sigma=0.1, d=-2.0), "d"),
        (dict(sigma=0.1, d=float("inf")), "d"),
        (dict(sigma=0.1, omega=float("nan")), "omega"),
        (dict(sigma=0.1, omega=0.0), "omega"),
        (dict(sigma=0.1, Omega=-float("inf")), "Omega"),
        (dict(sigma=0.1, Omega=1.0), "resonance"),
        (dict(sigma=0.1, omega=1.5, Omega=1.5), "resonance"),
    ],
)
def test_bad_input_names_the_argument(kwargs, name, dps):
    for fn in (F.impact_probability, F.no_impact_probability, F.log_impact_probability,
               F.log_no_impact_probability, F.dp_dsigma):
        kw = dict(kwargs)
        sigma = kw.pop("sigma")
        with pytest.raises(ValueError, match=name):
            fn(sigma, **kw, dps=dps)


def test_near_resonance_with_default_omega_sqrt2():
    """omega = fl(sqrt 2) is not sqrt 2: a (very) near resonance, not an error, and both paths
    agree on omega**2 - 2 = 2.7e-16 exactly (float64 uses an exact two-product)."""
    pf = F.no_impact_probability(0.1, omega=math.sqrt(2.0))
    pm = F.no_impact_probability(0.1, omega=math.sqrt(2.0), dps=30)
    assert 0 < pf < 1e-10
    assert rel(pf, pm) < 1e-13


def test_bad_array_input_reports_first_bad_index():
    s = np.array([0.1, 0.2, np.nan, -1.0])
    with pytest.raises(ValueError, match=r"sigma.*index 2"):
        F.impact_probability(s)
    with pytest.raises(ValueError, match=r"d must be > 0.*index \(1, 0\)"):
        F.impact_probability(0.1, d=np.array([[1.0, 2.0], [0.0, 1.0]]))
    with pytest.raises(ValueError, match=r"resonance.*index 1"):
        F.impact_probability(0.1, omega=1.0, Omega=np.array([2.0, 1.0, 3.0]))
    with pytest.raises(ValueError, match=r"sigma.*index 1"):
        F.impact_probability([0.1, 0.0], dps=15)


# ----------------------------------------------------------------------------- API behaviour
def test_broadcasting_over_every_parameter():
    s = np.logspace(-2, 1, 4)[:, None, None, None]
    om = np.array([0.5, 1.0])[None, :, None, None]
    Om = np.array([1.7, 3.0, 0.2])[None, None, :, None]
    d = np.array([0.5, 2.0])
    p = F.impact_probability(s, sigma1=2 * s, omega=om, Omega=Om, d=d)
    assert p.shape == (4, 2, 3, 2)
    i = (2, 1, 0, 1)
    ref = F.impact_probability(
        float(s[2, 0, 0, 0]), sigma1=2 * float(s[2, 0, 0, 0]), omega=1.0, Omega=1.7, d=2.0
    )
    assert p[i] == ref
    assert isinstance(F.impact_probability(0.2), float)


def test_monotone_and_complementary():
    s = np.logspace(-2, 2, 2000)
    p = F.impact_probability(s)
    q = F.no_impact_probability(s)
    assert np.all(np.diff(p) >= 0)
    assert np.all(np.diff(q) <= 0)
    assert np.all(np.abs(p + q - 1) <= 6 * EPS)


def test_symmetry_in_the_two_scales():
    """p depends on the Rayleigh scales only: swap s0 <-> s1 (omega=1, Omega^2=2: Delta=1)."""
    a = F.impact_probability(0.07, sigma1=0.2)
    b = F.impact_probability(0.2, sigma1=0.07)
    assert abs(a / b - 1) < 8 * EPS
