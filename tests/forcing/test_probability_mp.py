"""The mpmath one-component path of the public functions (``symhx.forcing.probability`` over
``kernels_mp`` and ``rawmp``): correct to ``dps`` digits against independent references.

References (:mod:`tests.reference.forcing`, none from the package): the double integral of eq.
(27) and the 1-D convolution (eq. 26) by ``mpmath.quad``; composite Gauss-Legendre of the
convolution at two rule orders that must agree (:func:`quadrature_values`); the completed-square
closed form (:func:`forcing_values`, a different formula from the package's ``u, v`` form)
evaluated far above the claim; and the mpmath path itself at twice the digits. The grids reach
float inputs (raw-libmp fast path) and exact decimal strings (the mpf-object path), both tails,
the logs, the adaptive ``1 - p`` loop, guard digits at huge exponents, inputs beyond the float
range, sympy irrationals and several components.
"""

from __future__ import annotations

from decimal import Decimal
from fractions import Fraction

import mpmath
import numpy as np
import pytest

from symhx import forcing as F
from symhx._mpctx import mp as thread_mp
from tests.reference.forcing import (
    eq26_p,
    eq27_q_double_integral,
    forcing_values,
    mp_exact,
    omega_squared,
    quadrature_values,
    squares,
    three_component_p,
)
from tests.reference.mp import rel_err

PAPER_CASES = [  # (omega, Omega or None, d)
    (1.0, None, 1.0),  # the paper
    (0.7, 1.9, 0.3),
    (2.0, 1.0, 3.0),
    (1.0, 1.001, 1.0),  # near resonance: huge forced amplitude
    (1.3, 0.2, 0.05),
]


# ----------------------------------------------------------------------------- closed form
@pytest.mark.parametrize(
    "sigma, ratio, case",
    [(0.12, None, 0), (0.3, 2.0, 1), (0.05, 3.0, 4), (2.0, None, 3)],
)
def test_closed_form_matches_eq27_double_integral(sigma, ratio, case):
    omega, Omega, d = PAPER_CASES[case]
    s1 = sigma if ratio is None else ratio * sigma
    ref = eq27_q_double_integral(sigma, s1, omega, omega_squared(Omega), d, 20)
    got = F.no_impact_probability(sigma, sigma1=s1, omega=omega, Omega=Omega, d=d, dps=20)
    assert rel_err(got, ref) < mpmath.mpf(10) ** -17


@pytest.mark.parametrize(
    "sigma, ratio, case",
    [(0.01, None, 0), (0.05, None, 0), (0.12, None, 0), (0.02, 0.1, 1), (0.03, 30.0, 2),
     (0.5, 3.0, 3), (0.004, 1.0, 4), (7.0, None, 0)],
)
def test_p_matches_eq26_quadrature_in_the_small_tail(sigma, ratio, case):
    omega, Omega, d = PAPER_CASES[case]
    s1 = sigma if ratio is None else ratio * sigma
    ref = eq26_p(sigma, s1, omega, omega_squared(Omega), d, 45)
    got = F.impact_probability(sigma, sigma1=s1, omega=omega, Omega=Omega, d=d, dps=30)
    assert rel_err(got, ref) < mpmath.mpf(10) ** -29


# ----------------------------------------------------------------------------- mpmath path
@pytest.mark.parametrize("dps", [15, 30, 50])
def test_mpmath_correct_to_dps_against_twice_dps(dps):
    tol = mpmath.mpf(10) ** (-dps)
    for sigma in ("0.0123", "0.05", "0.12", "0.7", "3", "99.5", "1e6"):
        for ratio, case in [(None, 0), ("0.3", 1), ("7", 2), (None, 3)]:
            omega, Omega, d = PAPER_CASES[case]
            s1 = None if ratio is None else mpmath.mpf(ratio) * mpmath.mpf(sigma)
            kw = dict(sigma1=s1, omega=omega, Omega=Omega, d=d)
            for fn in (F.impact_probability, F.no_impact_probability):
                lo = fn(sigma, **kw, dps=dps)
                hi = fn(sigma, **kw, dps=2 * dps)
                assert rel_err(lo, hi) < tol, (fn.__name__, sigma, ratio, case)


def test_mpmath_p_plus_q_is_one_and_logs_agree():
    for sigma in ("0.01", "0.2", "40"):
        with mpmath.workdps(60), thread_mp().workdps(60):
            p = F.impact_probability(sigma, dps=50)
            q = F.no_impact_probability(sigma, dps=50)
            assert abs(p + q - 1) < mpmath.mpf(10) ** -50
            assert abs(F.log_impact_probability(sigma, dps=50) - mpmath.log(p)) < 1e-45
            assert abs(F.log_no_impact_probability(sigma, dps=50) - mpmath.log(q)) < 1e-45


def test_omega_none_is_exact_sqrt2_in_mpmath():
    with mpmath.workdps(80), thread_mp().workdps(80):
        sqrt2 = mpmath.sqrt(2)
        a = F.impact_probability("0.1", dps=60)
        b = F.impact_probability("0.1", Omega=sqrt2, dps=60)
        assert rel_err(a, b) < mpmath.mpf(10) ** -58


def test_mpmath_string_inputs_are_exact_decimals():
    with mpmath.workdps(50), thread_mp().workdps(50):
        a = F.impact_probability("0.1", dps=40)
        b = F.impact_probability(0.1, dps=40)  # the binary double nearest 0.1
        # p'(0.1)/p * |0.1 - float(0.1)| / 0.1 ~ 57 * 5.5e-18: distinguishable at 40 digits
        assert rel_err(a, b) > mpmath.mpf(10) ** -20


GRID_DPS = 20


GRID = [(float(s), r, None) for s in np.logspace(-2.2, 9, 9) for r in (None, 1e-3, 30.0)]
GRID += [(float(s), r, 1.7) for s in (0.01, 0.3, 40.0) for r in (None, 30.0)]


@pytest.mark.parametrize("sigma, ratio, Omega", GRID)
def test_mpmath_path_against_independent_quadrature(sigma, ratio, Omega):
    sigma1 = None if ratio is None else sigma * ratio
    p, q, dp = quadrature_values(sigma, sigma1, 1, Omega, 1, 2 * GRID_DPS + 10)
    kw = dict(sigma1=sigma1, Omega=Omega)
    tol = mpmath.mpf(10) ** -GRID_DPS
    # each log from the tail that is small
    with mpmath.workdps(2 * GRID_DPS + 10), thread_mp().workdps(2 * GRID_DPS + 10):
        lp = mpmath.log(p) if p < 0.5 else mpmath.log1p(-q)
        lq = mpmath.log(q) if q < 0.5 else mpmath.log1p(-p)
    # float inputs (raw-libmp fast path) and decimal strings (general path)
    # the exact decimal expansions of the same binary values go through the general path
    for s in (sigma, str(Decimal(sigma))):
        k = kw if isinstance(s, float) else {**kw, "sigma1": None if sigma1 is None
                                              else str(Decimal(sigma1))}
        assert rel_err(F.impact_probability(s, **k, dps=GRID_DPS), p) < tol, ("p", s)
        assert rel_err(F.no_impact_probability(s, **k, dps=GRID_DPS), q) < tol, ("q", s)
        assert rel_err(F.log_impact_probability(s, **k, dps=GRID_DPS), lp) < tol, ("logp", s)
        assert rel_err(F.log_no_impact_probability(s, **k, dps=GRID_DPS), lq) < tol, ("logq", s)
    if 1e-300 < dp:
        assert rel_err(F.dp_dsigma(sigma, **kw, dps=GRID_DPS), dp) < tol, "dp"


def test_mpmath_extremes_keep_relative_accuracy():
    """mpmath: no ZeroDivisionError for huge sigma; log p = log1p(-(1 - p)) where p ~ 1 and
    log(1 - p) = log1p(-p) where p is tiny (both lost all digits before)."""
    lp = F.log_impact_probability(1e200, dps=30)
    lq = F.log_no_impact_probability(0.01346, dps=30)
    p = F.impact_probability(0.01346, dps=30)
    with mpmath.workdps(40), thread_mp().workdps(40):
        assert lp < 0 and abs(lp / (-1 / (96 * mpmath.mpf(1e200) ** 4)) - 1) < 1e-25
        assert abs(lq / -p - 1) < 1e-25
    assert F.no_impact_probability(1e-200, sigma1=1e100, dps=30) > 0


DPS = 20


def test_reference_against_mpmath_quad():
    """The completed-square reference is the eq. 27 convolution (checked by mpmath.quad)."""
    for sigma, sigma1, Omega, d in [("0.3", None, None, 1), ("0.13", "0.4", "1.7", "1.3"),
                                    ("2", None, "3", "0.7")]:
        with mpmath.workdps(40), thread_mp().workdps(40):
            S0, S1 = squares(sigma, sigma1, 1, Omega)
            dd = mp_exact(d)
            conv = mpmath.quad(lambda t, a=S0, b=S1, c=dd: t / a * mpmath.exp(-t * t / (2 * a))
                               * mpmath.exp(-(c - t) ** 2 / (2 * b)), [0, dd / 2, dd])
            pq = mpmath.exp(-dd * dd / (2 * S0)) + conv
        assert rel_err(forcing_values(sigma, sigma1, 1, Omega, d)[0], pq) < mpmath.mpf(10) ** -35


# ------------------------------------------------------------------ the public functions
FUNCS = {"p": F.impact_probability, "q": F.no_impact_probability,
         "logp": F.log_impact_probability, "logq": F.log_no_impact_probability}


SIGMAS = [float(s) for s in np.logspace(-2, 2, 17)]


PATH_RATIOS = [None, 0.1, 10.0]


def _check_all(sigma, sigma1=None, omega=1, Omega=None, d=1, dps=DPS, wants=FUNCS):
    r = forcing_values(sigma, sigma1, omega, Omega, d, dps)
    tol = mpmath.mpf(10) ** -dps
    for want, val in zip(("p", "q", "logp", "logq"), r, strict=True):
        if want not in wants:
            continue
        got = FUNCS[want](sigma, sigma1=sigma1, omega=omega, Omega=Omega, d=d, dps=dps)
        assert isinstance(got, mpmath.mpf)
        assert rel_err(got, val) <= tol, (want, sigma, sigma1, omega, Omega, d,
                                      mpmath.nstr(rel_err(got, val), 3))


@pytest.mark.parametrize("ratio", PATH_RATIOS)
def test_dense_grid_decimal_strings_general_path(ratio):
    for s in SIGMAS:
        sd = str(Decimal(repr(s)))
        s1 = None if ratio is None else str(Decimal(repr(s * ratio)))
        _check_all(sd, s1)


@pytest.mark.parametrize("ratio", PATH_RATIOS)
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
        assert rel_err(o, forcing_values(s, d="1.5")[1]) <= mpmath.mpf(10) ** -DPS


def test_float64_path_is_the_closed_form():
    s = np.array([0.02, 0.3, 7.0])
    for want, fn in FUNCS.items():
        got = fn(s, sigma1=0.5)
        assert got.dtype == float and got.shape == (3,)
        k = ("p", "q", "logp", "logq").index(want)
        for sv, g in zip(s, got, strict=True):
            assert rel_err(g, forcing_values(float(sv), 0.5)[k]) < 1e-13


def test_several_components_every_want():
    """Two forcing components (the Rayleigh sum path) for p, 1 - p and both logs."""
    Oms = ["1.7", "2.2"]
    p = three_component_p("0.35", Oms, "1.2", 2 * DPS + 20)
    with mpmath.workdps(2 * DPS + 20), thread_mp().workdps(2 * DPS + 20):
        vals = {"p": p, "q": 1 - p, "logp": mpmath.log(p), "logq": mpmath.log(1 - p)}
    for want, fn in FUNCS.items():
        got = fn("0.35", Omega=Oms, d="1.2", dps=DPS)
        assert rel_err(got, vals[want]) <= mpmath.mpf(10) ** -(DPS - 1), want
        got_f = fn(0.35, Omega=[1.7, 2.2], d=1.2)
        assert isinstance(got_f, float)
        assert rel_err(got_f, vals[want]) < 1e-12, want
    arr = F.impact_probability(np.array([0.35, 0.35]), Omega=[1.7, 2.2], d=1.2)
    assert arr.shape == (2,) and arr.dtype == float and rel_err(arr[1], p) < 1e-12
    arr = F.impact_probability(np.array(["0.35"], dtype=object), Omega=Oms, d="1.2", dps=DPS)
    assert arr.shape == (1,) and arr.dtype == object
    assert rel_err(arr[0], p) <= mpmath.mpf(10) ** -(DPS - 1)


def test_single_mp_reaches_the_general_path_for_mpf_and_log_p_near_one():
    """mpf inputs and ``log p`` with ``p > 1/2`` (computed as ``log1p(-(1 - p))``)."""
    for sigma in ("0.9", "7", "2e4", "3e8"):
        with mpmath.workdps(50), thread_mp().workdps(50):
            s = mpmath.mpf(sigma)
        r = forcing_values(s)
        for want in ("p", "q", "logp", "logq"):
            got = FUNCS[want](s, dps=DPS)
            k = ("p", "q", "logp", "logq").index(want)
            assert rel_err(got, r[k]) <= mpmath.mpf(10) ** -DPS, (sigma, want)


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
        r = forcing_values(sigma, sigma1, 1, "1.7", d, dps=dps)
        for k, want in enumerate(("p", "q", "logp", "logq")):
            got = FUNCS[want](sigma, sigma1=sigma1, omega=1, Omega="1.7", d=d, dps=dps)
            assert rel_err(got, r[k]) <= mpmath.mpf(10) ** -dps, (want, sigma, sigma1, d, dps)


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
    r = forcing_values(sigma, sigma1, omega, Omega, 1, dps=dps)
    for k, want in ((0, "p"), (2, "logp")):
        got = FUNCS[want](sigma, sigma1=sigma1, omega=omega, Omega=Omega, d=1, dps=dps)
        assert rel_err(got, r[k], 60) <= mpmath.mpf(10) ** -dps, (want, sigma, sigma1)


@pytest.mark.parametrize("dps", [15, 60, 120])
def test_sympy_irrational_inputs_keep_every_digit(dps):
    """A sympy irrational sigma (or d) is taken to dps + IRRATIONAL_EXTRA_DIGITS digits: p and
    log p to dps digits, also where p = exp(-E) amplifies the input's error by 2E ~ 1e14 (it
    used to be rounded to 40 digits: 2.7e-39 off at dps = 60)."""
    import sympy

    for sigma, d in [(sympy.sqrt(2) / 10, 1), (sympy.pi / 10**7, sympy.sqrt(3))]:
        with mpmath.workdps(dps + 200), thread_mp().workdps(dps + 200):
            s_mp, d_mp = mpmath.mpf(sympy.N(sigma, dps + 200)), mpmath.mpf(sympy.N(d, dps + 200))
            r = forcing_values(s_mp, None, 1, None, d_mp, dps=dps)
        for k, want in ((0, "p"), (2, "logp")):
            got = FUNCS[want](sigma, d=d, dps=dps)
            assert rel_err(got, r[k], dps + 40) <= mpmath.mpf(10) ** -dps, (want, sigma, dps)
