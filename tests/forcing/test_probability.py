"""The public impact-probability functions (``symhx.forcing.probability``): the closed form
against the paper's integrals, broadcasting, one component given as a list, several forcing
components (the Rayleigh sum at ``d``), the shared parameter documentation and the paper's
literal ``1 - dblquad`` formula (kept to show its failure)."""

from __future__ import annotations

import math

import numpy as np
import pytest

from symhx import forcing as F
from symhx.forcing import probability as P
from tests.harness.errors import assert_refuses
from tests.reference.forcing import eq26_p, forcing_values
from tests.reference.mp import rel_err

EPS = np.finfo(float).eps


# ----------------------------------------------------------------------------- naive formula
def test_naive_dblquad_formula_fails_in_the_small_tail():
    """Documents the failure this module fixes: 1 - dblquad(eq. 27) at sigma = 0.05.

    The true p is ~2.4e-21 (checked against eq. 26 quadrature here); the naive value is
    rounding noise of size ~1e-13 (or 0, or negative, depending on the platform).
    """
    true = eq26_p(0.05, 0.05, 1, 2, 1, 30)
    naive = F.naive_impact_probability(0.05)
    ours = F.impact_probability(0.05)
    assert rel_err(ours, true) < 1e-14
    assert abs(naive - float(true)) > 1e6 * float(true)  # not a single correct digit
    # where p is not small the naive formula is fine (so the comparison is fair)
    assert abs(F.naive_impact_probability(0.5) / F.impact_probability(0.5) - 1) < 1e-8


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
        assert rel_err(got, ref) < 1e-13 + 8 * EPS * abs(math.log(got)), (fn.__name__, got, ref)
        scales = F.rayleigh_scales(sigma, **kw)
        res = F.rayleigh_sum_probability(scales, 1.0, tail=tail)
        # the error estimate bounds the error
        assert rel_err(res.value, ref) < res.error / res.value


def test_with_params_doc_inserts_the_shared_parameters():
    def f():
        pass

    f.__doc__ = "Head.\n    @PARAMS@\n    Tail."
    assert P.with_params_doc(f) is f
    assert "@PARAMS@" not in f.__doc__
    assert "sigma_0 > 0" in f.__doc__ and "Tail." in f.__doc__

    def g():
        pass

    assert P.with_params_doc(g) is g and g.__doc__ is None
    assert "Raises" in F.impact_probability.__doc__


def test_naive_double_integral_where_it_works():
    for sigma, kw in [(0.5, {}), (0.4, {"sigma1": 0.7}), (0.8, {"Omega": 1.7, "d": 1.3}),
                      (0.6, {"omega": 1.2, "Omega": 0.5})]:
        got = F.naive_impact_probability(sigma, **kw)
        want = forcing_values(sigma, kw.get("sigma1"), kw.get("omega", 1), kw.get("Omega"),
                   kw.get("d", 1))[0]
        assert abs(got - float(want)) < 1e-7, (sigma, kw, got, float(want))
    assert_refuses(F.naive_impact_probability, 0.5, omega=2, Omega=2, arg="Omega",
                   allowed="resonance Omega == omega")
    for name in ("sigma", "sigma1", "omega", "Omega", "d"):
        assert_refuses(F.naive_impact_probability, **{"sigma": 0.5, name: -1}, arg=name,
                       value="-1", allowed="> 0")
    import warnings

    with warnings.catch_warnings():  # Omega**2 overflows silently, then a clear refusal
        warnings.simplefilter("error")
        with pytest.raises(ValueError, match="outside the float64 range"):
            F.naive_impact_probability(0.5, Omega=1e200)
    for kw in [{"d": 1e-160},  # d**2 below the normal range
               {"sigma": 1e-75, "Omega": 1e5},  # k/(4 s0**2 s1**2) overflows
               {"sigma": 1e150, "sigma1": 1e-145, "d": 1e10}]:  # k d**2/sigma1**2 overflows
        with pytest.raises(ValueError, match="outside the float64 range"):
            F.naive_impact_probability(**{"sigma": 0.5, **kw})
    with pytest.raises(ValueError, match=r"outside the float64 range of the literal eq\. \(27\) "
                                         r"integrand; use impact_probability"):
        F.naive_impact_probability(1e-170)
    with pytest.raises(ValueError, match="outside the float64 range"):
        F.naive_impact_probability(0.5, d=1e200)
    with pytest.raises(ValueError, match="outside the float64 range"):
        F.naive_impact_probability(0.5, omega=1e160)
    with pytest.raises(ValueError, match="sigma"):
        F.naive_impact_probability(-0.5)
