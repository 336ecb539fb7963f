"""Hostile inputs to the public forcing functions (``symhx.forcing.probability`` and
``dp_dsigma``): a correct value or a clear ValueError/TypeError naming the argument, the value
and what is allowed (first bad index of an array); empty in, empty out; exact decimal strings;
the global mpmath precision left alone."""

from __future__ import annotations

import math
from fractions import Fraction

import mpmath
import numpy as np
import pytest

from symhx import forcing as F
from symhx._mpctx import mp as thread_mp

FUNCS = [F.impact_probability, F.no_impact_probability, F.log_impact_probability,
         F.log_no_impact_probability, F.dp_dsigma]


@pytest.mark.parametrize("fn", FUNCS)
@pytest.mark.parametrize("dps", [None, 20])
@pytest.mark.parametrize("arg", ["sigma", "sigma1", "omega", "Omega", "d"])
@pytest.mark.parametrize("bad, exc, msg", [
    (True, TypeError, "bool"), (float("nan"), ValueError, "finite"),
    (float("inf"), ValueError, "finite"), (-1.0, ValueError, "> 0"), (0, ValueError, "> 0"),
    ("abc", ValueError, ""), (1 + 2j, TypeError, "real"),
])
def test_bad_scalars_name_the_argument(fn, dps, arg, bad, exc, msg):
    kw = {"sigma": 0.3, arg: bad}
    sigma = kw.pop("sigma")
    with pytest.raises(exc, match=arg) as info:
        fn(sigma, **kw, dps=dps)
    assert msg in str(info.value)


@pytest.mark.parametrize("fn", FUNCS)
def test_arrays_report_first_bad_index(fn):
    with pytest.raises(ValueError, match=r"sigma.*index \(?2"):
        fn(np.array([0.1, 0.2, -1.0, -2.0]))
    with pytest.raises(ValueError, match=r"d.*index \(1, 0\)"):
        fn(0.3, d=np.array([[1.0, 2.0], [0.0, 1.0]]))
    with pytest.raises(ValueError, match=r"sigma.*index 1"):
        fn(["0.1", "-0.2"], dps=15)


@pytest.mark.parametrize("fn", FUNCS)
@pytest.mark.parametrize("dps", [True, 0, -1, 2.5, "20", 10**6])
def test_bad_dps(fn, dps):
    with pytest.raises((TypeError, ValueError), match="dps"):
        fn(0.3, dps=dps)


@pytest.mark.parametrize("fn", FUNCS)
def test_empty_in_empty_out(fn):
    out = fn(np.array([]))
    assert isinstance(out, np.ndarray) and out.shape == (0,)
    assert fn(np.empty((0, 3))).shape == (0, 3)


def test_decimal_strings_are_exact_and_floats_binary():
    # "0.1" is exactly 1/10; the float 0.1 is 0.1000000000000000055...
    a = F.impact_probability("0.1", dps=40)
    b = F.impact_probability(Fraction(1, 10), dps=40)
    c = F.impact_probability(0.1, dps=40)
    assert a == b and a != c
    with mpmath.workdps(60), thread_mp().workdps(60):
        ref = F.impact_probability(mpmath.mpf(1) / 10, dps=50)
        assert abs(a / ref - 1) < mpmath.mpf(10) ** -40
    # float64 path: a string is the correctly rounded float
    assert F.impact_probability("0.1") == F.impact_probability(0.1)
    with pytest.raises(ValueError, match="float64 range"):
        F.impact_probability("1e400")
    # E = uv = 2.5e799 is beyond the documented cap MAX_EXPONENT (exp of it takes seconds)
    with pytest.raises(ValueError, match="MAX_EXPONENT"):
        F.log_impact_probability("1e-400", dps=15)
    assert F.log_impact_probability("1e-150", dps=15) < mpmath.mpf("-1e299")


def test_none_empty_omega_and_extreme_inputs():
    """Issue 12: None is a TypeError, an empty Omega array an error, extremes no NaN."""
    for name in ("sigma", "omega", "d"):
        kw = {"sigma": 0.3, name: None}
        with pytest.raises(TypeError, match=name):
            F.impact_probability(**kw)
    with pytest.raises(ValueError, match="Omega: an empty"):
        F.dp_dsigma(0.3, Omega=np.array([]))
    # dp/dsigma where the float kernel overflows: the mpmath value (independent path) or 0
    for kw in (dict(sigma1=5e-324), dict(omega=1e308), dict(Omega=1e308)):
        ref = float(F.dp_dsigma(0.3, **kw, dps=30))
        assert abs(F.dp_dsigma(0.3, **kw) / ref - 1) < 1e-14, kw
        # a single Rayleigh(sqrt2 sigma) amplitude: p = exp(-d^2/(4 sigma^2))
        assert abs(ref - 0.5 / 0.3**3 * math.exp(-1 / 0.36)) < 1e-12, kw
    for kw in (dict(sigma=1e308), dict(sigma=5e-324), dict(d=1e308), dict(d=5e-324)):
        assert F.dp_dsigma(**{"sigma": 0.3, **kw}) == 0.0, kw
    assert F.rayleigh_scales(0.3, omega=1e308) == (0.3 * math.sqrt(2), 0.0)
    assert F.rayleigh_sum_probability([0.5, 0.3], d=1e308).value == 0.0
    for scales in ([0.5, 0.3], [0.5, 0.3, 0.2]):  # the far-tail cut leaves the normal tail alone
        for x in (2.0, 4.0):
            ref = F.rayleigh_sum_probability(scales, d=x, dps=30).value
            got = F.rayleigh_sum_probability(scales, d=x).value
            assert ref > 1e-30 and abs(got / float(ref) - 1) < 1e-11, (scales, x, got, ref)
    with pytest.raises(TypeError, match="dps"):
        F.ForcingParams.validated(0.3, dps="abc")
    assert F.rayleigh_sum_probability([0.5, 0.3], d=1e308, tail="lower").value == 1.0
    for kw in (dict(sigma=5e-324), dict(Omega=1e308), dict(d=1e308), dict(omega=1e308)):
        with pytest.raises(ValueError, match="float64 range"):
            F.naive_impact_probability(**{"sigma": 0.3, **kw})
    with pytest.raises(ValueError, match="MAX_EXPONENT"):
        F.impact_probability("0.3", d="1e1000", dps=15)


def test_resonance_and_components():
    with pytest.raises(ValueError, match="resonance"):
        F.impact_probability(0.3, Omega=1.0)
    with pytest.raises(ValueError, match=r"Omega\[1\]: resonance"):
        F.impact_probability(0.3, Omega=[1.5, 1.0])
    with pytest.raises(ValueError, match="sigma1: 3 values for 2"):
        F.impact_probability(0.3, Omega=[1.5, 2.5], sigma1=[0.1, 0.2, 0.3])
    with pytest.raises(ValueError, match="empty"):
        F.impact_probability(0.3, Omega=[])


def test_global_precision_untouched():
    before = mpmath.mp.dps
    F.impact_probability(0.2, dps=60)
    F.no_impact_probability(50.0, dps=60)
    F.rayleigh_sum_probability([0.5, 0.3, 0.2], 1.0, dps=25)
    F.sigma_for_impact_probability("0.25", dps=30)
    assert mpmath.mp.dps == before


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
