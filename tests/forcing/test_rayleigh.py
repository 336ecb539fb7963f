"""``RayleighSum`` (``symhx.forcing.rayleigh``) as a distribution object: the methods and their
small print, moments and draws, ``probability`` with its error estimate, exact inputs, values at
and below zero, and every refusal."""

from __future__ import annotations

import math
from fractions import Fraction

import mpmath
import numpy as np
import pytest

from symhx._mpctx import mp as thread_mp
from symhx.forcing import RayleighSum
from symhx.forcing.rayleigh import rayleigh_scales, rayleigh_sum_probability
from tests.harness.errors import assert_refuses
from tests.reference.forcing import pair_tail, rayleigh_sum_value
from tests.reference.mp import rel_err

EPS = np.finfo(float).eps


def test_rayleigh_sum_methods():
    sc = [0.5, 0.3, 0.2]
    S = RayleighSum(sc)
    x = np.array([-1.0, 0.0, 0.3, 1.0, 2.5])
    sf, cdf, pdf = S.sf(x), S.cdf(x), S.pdf(x)
    assert sf[0] == sf[1] == 1.0 and cdf[0] == cdf[1] == 0.0 and pdf[0] == 0.0
    assert np.all(np.abs(sf + cdf - 1) < 4 * EPS)
    # pdf is the derivative of the cdf (independent: central difference at 30 digits)
    with mpmath.workdps(30), thread_mp().workdps(30):
        h = mpmath.mpf("1e-8")
        fd = (S.cdf(mpmath.mpf(1) + h, dps=25) - S.cdf(mpmath.mpf(1) - h, dps=25)) / (2 * h)
        assert rel_err(S.pdf(1.0, dps=20), fd) < 1e-14
    assert abs(S.pdf(1.0) / float(fd) - 1) < 1e-13
    # moments: closed forms vs the sample and vs numerical integration of the sf
    assert S.mean() == pytest.approx(math.sqrt(math.pi / 2) * 1.0, rel=1e-15)
    assert S.var() == pytest.approx((2 - math.pi / 2) * 0.38, rel=1e-15)
    with mpmath.workdps(20), thread_mp().workdps(20):
        m_int = mpmath.quad(lambda t: S.sf(t, dps=15), [0, 0.5, 1, 2, 5, 12])  # sf(12)~e-190
        assert rel_err(S.mean(dps=20), m_int) < 1e-13
    r = S.rvs(size=200_000, random_state=1)
    assert abs(r.mean() - S.mean()) < 5 * S.std() / math.sqrt(r.size)
    assert np.array_equal(r, S.rvs(size=200_000, random_state=1))
    # Kolmogorov-Smirnov against the cdf
    from scipy import stats

    assert stats.kstest(r[:5000], S.cdf).pvalue > 1e-3
    # empty in, empty out
    assert S.sf(np.array([])).shape == (0,)


@pytest.mark.parametrize("bad, exc", [([], ValueError), ([0.5, -1.0], ValueError),
                                      ([0.5, float("nan")], ValueError), ([True, 0.5], TypeError),
                                      ("0.5", TypeError), ([0.5, "x"], ValueError)])
def test_rayleigh_sum_bad_scales(bad, exc):
    with pytest.raises(exc, match="scales"):
        RayleighSum(bad)


def test_rayleigh_sum_bad_x_and_dps():
    S = RayleighSum([1.0, 2.0])
    with pytest.raises(ValueError, match="x"):
        S.sf(float("nan"))
    with pytest.raises(ValueError, match=r"x.*index"):
        S.sf([1.0, float("inf")])
    with pytest.raises(TypeError, match="dps"):
        S.sf(1.0, dps=True)
    with pytest.raises(ValueError, match="tail"):
        S.probability(1.0, tail="middle")


def test_decimal_strings_are_exact_scales():
    a = RayleighSum(["0.1", "0.2", "0.3"]).sf(0.5, dps=30)
    with mpmath.workdps(40), thread_mp().workdps(40):
        b = RayleighSum([mpmath.mpf(1) / 10, mpmath.mpf(2) / 10, mpmath.mpf(3) / 10]).sf(
            mpmath.mpf("0.5"), dps=30)
        assert rel_err(a, b) < 1e-29


def test_moments_and_rvs():
    sc = ["0.5", "0.3", "0.2"]
    S = RayleighSum(sc)
    assert S.mean() == math.sqrt(math.pi / 2) * 1.0
    assert abs(S.var() - (2 - math.pi / 2) * 0.38) < 4 * EPS
    assert abs(S.std() - math.sqrt((2 - math.pi / 2) * 0.38)) < 4 * EPS
    with mpmath.workdps(60), thread_mp().workdps(60):
        m = mpmath.sqrt(mpmath.pi / 2) * 1
        v = (2 - mpmath.pi / 2) * (mpmath.mpf(38) / 100)
        assert abs(S.mean(dps=40) - m) < mpmath.mpf(10) ** -40
        assert abs(S.var(dps=40) - v) < mpmath.mpf(10) ** -40
        assert abs(S.std(dps=40) - mpmath.sqrt(v)) < mpmath.mpf(10) ** -40
        # the mean is the integral of the survival function (independent of the formula)
        mi = mpmath.quad(lambda t: pair_tail(t, mpmath.mpf(0.7), mpmath.mpf(0.2), True),
                         [0, 0.5, 1, 2, 4, 8])
        assert abs(RayleighSum([0.7, 0.2]).mean(dps=30) - mi) < mpmath.mpf(10) ** -25
    r = S.rvs(size=4000, random_state=3)
    assert r.shape == (4000,) and np.array_equal(r, S.rvs(size=4000, random_state=3))
    assert not np.array_equal(r, S.rvs(size=4000, random_state=4))
    assert np.array_equal(r, S.rvs(size=4000, random_state=np.random.default_rng(3)))
    assert isinstance(S.rvs(random_state=1), float)
    from scipy import stats

    assert stats.kstest(r, S.cdf).pvalue > 1e-3
    # each summand is Rayleigh(s): the sample mean of a one-scale sum
    r1 = RayleighSum([2.0]).rvs(size=20000, random_state=5)
    assert abs(r1.mean() - 2.0 * math.sqrt(math.pi / 2)) < 5 * 2.0 * 0.66 / math.sqrt(20000)


def test_bad_input_is_refused_with_its_name():
    with pytest.raises(TypeError, match="scales must be a sequence"):
        RayleighSum("0.5")
    with pytest.raises(TypeError, match="scales must be a sequence"):
        RayleighSum(0.5)
    with pytest.raises(ValueError, match=r"scales: need at least one"):
        RayleighSum([])
    with pytest.raises(ValueError, match=r"scales\[1\] must be > 0"):
        RayleighSum([0.5, -1])
    big = RayleighSum([Fraction(10) ** 400, 1])
    assert_refuses(big.sf, 1.0, arg="scales[0]", value="1.0e+400",
                   allowed=["outside the float64 range", "use dps="])
    assert big.sf(1, dps=15) == 1
    tiny = RayleighSum(["1e-400", 1])
    with pytest.raises(ValueError, match=r"scales\[0\] = .* outside the float64 range"):
        tiny.mean()
    S = RayleighSum([0.5, 0.2, 0.1])
    assert repr(S) == "RayleighSum([0.5, 0.2, 0.1])"
    # beyond float64 the exact scale, briefly (not inf or 0.0)
    assert repr(RayleighSum([10**5000, "1e-5000", 3])) == \
        "RayleighSum([1.0e+5000, 1.0e-5000, 3.0])"
    with pytest.raises(TypeError, match="x must be a scalar here"):
        S.probability([1.0])
    with pytest.raises(ValueError, match="tail"):
        S.probability(1.0, tail="both")
    with pytest.raises(ValueError, match="tail"):
        rayleigh_sum_probability([0.5, 0.2], 1.0, tail="middle")
    with pytest.raises(ValueError, match=r"d must be > 0"):
        rayleigh_sum_probability([0.5, 0.2], -1.0)
    res = rayleigh_sum_probability([0.5, 0.3, 0.2], 1.0, tail="lower", dps=20)
    assert rel_err(res.value, rayleigh_sum_value((0.5, 0.3, 0.2), 1.0, "cdf")) < 1e-20
    res = rayleigh_sum_probability([0.5, 0.3, 0.2], 1.0)
    assert rel_err(res.value, rayleigh_sum_value((0.5, 0.3, 0.2), 1.0, "sf")) < 1e-13


# ---------------------------------------------------------------- small print of the public API
def test_moments_closed_forms_and_types():
    # E R = s sqrt(pi/2), Var R = (2 - pi/2) s**2 for one Rayleigh variable; sums add
    sc = [0.5, 0.3, 0.2]
    S = RayleighSum(sc)
    m, v = S.mean(), S.var()
    assert type(m) is float and type(v) is float and type(S.std()) is float
    assert m == pytest.approx(sum(sc) * math.sqrt(math.pi / 2), rel=1e-15)
    assert v == pytest.approx((2 - math.pi / 2) * sum(s * s for s in sc), rel=1e-15)
    assert S.std() == pytest.approx(math.sqrt(v), rel=1e-15)
    with mpmath.workdps(50), thread_mp().workdps(50):
        ref = mpmath.sqrt(mpmath.pi / 2) * (mpmath.mpf(0.5) + mpmath.mpf(0.3) + mpmath.mpf(0.2))
        assert abs(S.mean(dps=40) - ref) < mpmath.mpf(10) ** -40
        assert isinstance(S.std(dps=30), mpmath.mpf)
    x = S.rvs(random_state=3)
    assert type(x) is float and x > 0
    assert S.rvs(size=4, random_state=3).shape == (4,)
    with pytest.raises((TypeError, ValueError), match="random_state"):
        S.rvs(random_state="seed")


def test_small_print_of_the_functions():
    # d defaults to 1; the tail choice and the scalar-only arguments are named in errors
    assert rayleigh_sum_probability([0.5, 0.3, 0.2]) == rayleigh_sum_probability([0.5, 0.3, 0.2],
                                                                                  1.0)
    with pytest.raises(ValueError, match="tail"):
        rayleigh_sum_probability([0.5, 0.3], 1.0, tail="both")
    with pytest.raises(TypeError, match=r"sigma must be a scalar here, got list"):
        rayleigh_scales([0.5, 0.6])
    assert_refuses(rayleigh_scales, 0.5, sigma1=[0.1, 0.2], exc=TypeError, arg=["sigma1", "Omega"],
                   allowed="a list needs a list of forcing components")
    with pytest.raises(ValueError, match=r"Omega\[1\]: resonance Omega == omega \(infinite "
                                         r"forced amplitude\)"):
        rayleigh_scales(0.5, omega=1.5, Omega=[2.0, 1.5])


def test_one_scale_against_the_rayleigh_closed_form():
    # P(R <= x) = 1 - exp(-x**2/(2 s**2)), density x/s**2 exp(-x**2/(2 s**2)), both 0 at x <= 0
    S = RayleighSum(["0.7"])
    with mpmath.workdps(50), thread_mp().workdps(50):
        s = mpmath.mpf(7) / 10
        for x in ("0.1", "1", "5"):
            xm = mpmath.mpf(x)
            cdf = -mpmath.expm1(-xm**2 / (2 * s**2))
            pdf = xm / s**2 * mpmath.exp(-xm**2 / (2 * s**2))
            for got, ref in ((S.cdf(x, dps=30), cdf), (S.sf(x, dps=30), 1 - cdf),
                             (S.pdf(x, dps=30), pdf)):
                assert abs(got / ref - 1) < mpmath.mpf(10) ** -29, x
            sf_, xf = mpmath.mpf(0.7), mpmath.mpf(float(x))   # float64 takes the binary 0.7
            cdf_f = -mpmath.expm1(-xf**2 / (2 * sf_**2))
            pdf_f = xf / sf_**2 * mpmath.exp(-xf**2 / (2 * sf_**2))
            assert abs(S.cdf(float(x)) / cdf_f - 1) < 1e-15
            # exp(-E) carries the rounding of E = x**2/(2 s**2) (25.5 at x = 5): E eps relative
            assert abs(S.pdf(float(x)) / pdf_f - 1) < (2 + float(xf**2 / (2 * sf_**2))) * 2e-16
        for x in ("0", "-1"):
            assert S.cdf(x, dps=30) == 0 and S.pdf(x, dps=30) == 0 and S.sf(x, dps=30) == 1
            assert S.cdf(float(x)) == 0 and S.pdf(float(x)) == 0


# ------------------------------------------------------------------ probability(): small print
def test_probability_names_its_arguments():
    S = RayleighSum([0.5, 0.3, 0.2])
    assert_refuses(S.probability, 1.0, tail="both", arg="tail", value="'both'",
                   allowed="one of ['upper', 'lower']")
    assert_refuses(rayleigh_sum_probability, [0.5, 0.3], 1.0, tail="x", arg="tail", value="'x'",
                   allowed="one of ['upper', 'lower']")
    with pytest.raises(ValueError, match=r"x must be a number"):
        S.probability("abc")
    with pytest.raises(ValueError, match=r"x must be a number"):
        S.probability("abc", dps=20)
    assert_refuses(S.probability, np.array([1.0, 2.0]), exc=TypeError, arg="x",
                   allowed=["a scalar here", "use sf/cdf for arrays"])


@pytest.mark.parametrize("scales", [[0.7], [0.5, 0.3], [0.5, 0.3, 0.2]])
def test_probability_at_and_below_zero_is_exact(scales):
    S = RayleighSum(scales)
    for x in (0.0, -1.0, "0", "-2"):
        # float64: the exact values, with the estimate of the rounding of the formula
        up, lo = S.probability(x), S.probability(x, tail="lower")
        assert up.value == 1.0 and 0 <= up.error < 1e-14
        assert lo.value == 0.0 and 0 <= lo.error < 1e-14
        up = S.probability(x, dps=20)
        assert up.value == 1 and up.error == 0
        lo = S.probability(x, tail="lower", dps=20)
        assert lo.value == 0 and lo.error == 0


def test_probability_method_and_error_estimate():
    assert RayleighSum([0.5, 0.3]).probability(1.0, dps=20).method == "closed form"
    assert (RayleighSum([0.5, 0.3, 0.2]).probability(1.0, dps=20).method
            == "Laplace-transform inversion")
    assert (RayleighSum([1, 0.9, 0.5, 0.3, 0.2]).probability(0.1).method
            == "Laplace-transform inversion")
    # a pair whose closed form is beyond its float64 range (one scale negligible)
    assert RayleighSum([1.0, 1e-100]).probability(1.0).method == "Laplace-transform inversion"
    assert RayleighSum([1.0, 1e-20]).probability(1.0).method == "closed form"
    # one scale, lower tail below the median: the closed form; the estimate covers the true
    # error (mostly the rounding to 25 digits) and stays within the 25 digits asked for
    S = RayleighSum(["0.7"])
    res = S.probability("0.3", tail="lower", dps=25)
    with mpmath.workdps(60), thread_mp().workdps(60):
        true = -mpmath.expm1(-mpmath.mpf("0.09") / (2 * mpmath.mpf("0.49")))
        err = abs(res.value - true)
        assert err <= res.error <= mpmath.mpf(10) ** -25 * true


# ------------------------------------------------------------------ moments and draws
def test_moments_with_scales_not_summing_to_one():
    sc = ["2", "0.5", "0.25"]
    S = RayleighSum(sc)
    assert S.mean() == pytest.approx(2.75 * math.sqrt(math.pi / 2), rel=2e-16)
    assert S.var() == pytest.approx((2 - math.pi / 2) * 4.3125, rel=4e-16)
    with mpmath.workdps(60), thread_mp().workdps(60):
        m = mpmath.sqrt(mpmath.pi / 2) * mpmath.mpf("2.75")
        v = (2 - mpmath.pi / 2) * mpmath.mpf("4.3125")
        assert abs(S.mean(dps=30) / m - 1) < mpmath.mpf(10) ** -30
        assert abs(S.var(dps=30) / v - 1) < mpmath.mpf(10) ** -30
    one = S.rvs(random_state=7)
    assert type(one) is float
    with pytest.raises(ValueError, match=r"random_state must be"):
        S.rvs(random_state="seed")


def test_mpmath_results_come_at_the_digits_asked_for():
    # the guard digits of the evaluation are not correct digits: every mpmath result is rounded
    # to dps (its mantissa fits the precision of dps digits), the estimate covers the rounding
    from symhx.forcing import impact_probability, log_no_impact_probability, no_impact_probability

    prec = mpmath.libmp.dps_to_prec(20)
    S = RayleighSum(["0.5", "0.3", "0.2"])
    for tail in ("upper", "lower"):
        res = S.probability("1", tail=tail, dps=20)
        assert res.value._mpf_[3] <= prec
        with mpmath.workdps(60), thread_mp().workdps(60):
            ref = S.sf("1", dps=40) if tail == "upper" else S.cdf("1", dps=40)
            assert abs(res.value - ref) <= res.error <= mpmath.mpf(10) ** -20 * ref
    for fn in (impact_probability, no_impact_probability, log_no_impact_probability):
        for kw in ({}, {"Omega": [2, "0.5"]}):
            v = fn("0.5", d="1.3", dps=20, **kw)
            assert v._mpf_[3] <= prec, (fn.__name__, kw)
            with mpmath.workdps(60), thread_mp().workdps(60):
                ref = fn("0.5", d="1.3", dps=40, **kw)
                assert abs(v / ref - 1) <= mpmath.mpf(10) ** -19


# ------------------------------------------------------------------ values of mixed kinds
def test_a_float_in_a_list_of_scales_is_its_binary_value():
    """``[0.1, "1/3"]``: 0.1 is the double nearest 1/10 (as ``RayleighSum([0.1])`` reads it),
    not the decimal 1/10 that a string array would make of it."""
    S = RayleighSum([0.1, "1/3"])
    assert S._exact == (Fraction(0.1), Fraction(1, 3))
    assert S.sf(0.2, dps=30) == RayleighSum([Fraction(0.1), Fraction(1, 3)]).sf(0.2, dps=30)
    assert S.sf(0.2, dps=30) != RayleighSum(["0.1", "1/3"]).sf(0.2, dps=30)


def test_a_float_in_a_list_of_thresholds_is_its_binary_value():
    S = RayleighSum(["0.5", "0.3", "0.2"])
    got = S.sf([0.1, "1/3"], dps=30)
    assert got[0] == S.sf(0.1, dps=30)
    assert got[0] != S.sf("0.1", dps=30)   # the decimal 1/10 is a different threshold
    assert got[1] == S.sf(Fraction(1, 3), dps=30)


# ------------------------------------------------------------------ x <= 0 on the mpmath routes
@pytest.mark.parametrize("scales", [["0.7"], ["0.5", "0.3"], ["0.5", "0.3", "0.2"]])
@pytest.mark.parametrize("x", [0, -1, "-1/3"])
def test_mp_values_at_and_below_zero(scales, x):
    """S > 0 almost surely: P(S > x) = 1, P(S <= x) = 0 and no density for x <= 0."""
    S = RayleighSum(scales)
    assert S.sf(x, dps=20) == 1
    assert S.cdf(x, dps=20) == 0
    assert S.pdf(x, dps=20) == 0
    assert S.logsf(x, dps=20) == 0
    assert S.logcdf(x, dps=20) == -mpmath.inf


# ------------------------------------------------------------------ the words of the errors
def test_errors_name_x():
    S = RayleighSum([0.5, 0.3, 0.2])
    with pytest.raises(ValueError, match=r"x must be finite"):
        S.sf(math.nan)
    with pytest.raises(ValueError, match=r"x must be finite, got nan at index \(1,\)"):
        S.sf([1.0, math.nan])
    with pytest.raises(ValueError, match=r"x must be finite, got nan at index \(1,\)"):
        S.sf(np.array([1.0, math.nan]))   # a float64 array: the same words as a list
    with pytest.raises(ValueError, match=r"x must be a number"):
        S.cdf("abc")


def test_empty_scales_error():
    with pytest.raises(ValueError, match=r"scales: need at least one Rayleigh scale"):
        RayleighSum([])
