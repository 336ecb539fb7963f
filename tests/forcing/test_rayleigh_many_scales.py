"""RayleighSum with a negligible scale and with many scales (issue 28, items 2 and 4).

Item 2: a scale far below the others has a rigorous, tiny effect; every method (cdf, sf, pdf,
logcdf, logsf, probability, rayleigh_sum_probability, float64 and dps) must agree with it.
Item 4: sums of up to ``MAX_SCALES`` scales are a supported case, checked against independent
references (a straight-contour Gauss-Legendre inversion in mpmath, Monte Carlo, 2x dps), and
``MAX_SCALES`` is enforced before any work, the same way by the API and the CLI.
Cost checks of the same items are in ``tests/perf/test_forcing_many_scales_cost.py``.
"""

from __future__ import annotations

import math

import mpmath
import numpy as np
import pytest

import symhx
from symhx._mpctx import mp as thread_mp
from symhx.cli import main as cli_main
from symhx.forcing import MAX_SCALES
from tests.harness.errors import assert_refuses
from tests.reference.forcing import bromwich_line, rayleigh_sum_value
from tests.reference.mp import rel_err

RayleighSum = symhx.RayleighSum


# =========================================================================== item 2
def sandwich(big, small, x, dps=40):
    """Rigorous bounds of ``P(S > x)`` and ``P(S <= x)`` for ``S = R_big + sum R_small``:
    ``R_big <= S <= R_big + T`` with ``P(sum R_small > t) <= sum P(R_j > t/M)`` gives
    ``sf_1(x) <= sf(x) <= sf_1(x - t) + eps`` with ``t = 1e10 max(small)`` (the chosen slack),
    ``eps = M exp(-(t/M)**2/(2 max(small)**2))``. Returns ``(lo, hi)`` of sf."""
    with mpmath.workdps(dps), thread_mp().workdps(dps):
        b = mpmath.mpf(big)
        m = len(small)
        smax = max(mpmath.mpf(s) for s in small)
        t = smax * 10**10
        eps = m * mpmath.exp(-((t / m) ** 2) / (2 * smax**2))
        x = mpmath.mpf(x)
        return mpmath.exp(-x * x / (2 * b * b)), mpmath.exp(-((x - t) ** 2) / (2 * b * b)) + eps


NEGLIGIBLE = [[1.0, 1e-100], [1.0, 1e-154], [1.0, 1e-300, 1e-300], [1.0, 1e-200, 1e-250, 1e-300],
              [1e-100, 1e-300], [1.0, 5e-324], [1.0] + [1e-120] * 8]


@pytest.mark.parametrize("scales", NEGLIGIBLE)
@pytest.mark.parametrize("x", [0.01, 1.0, 5.0, 30.0])
def test_negligible_scale_gives_the_dominant_rayleigh_in_every_method(scales, x):
    """With every other scale below 1e-90 of the largest, S is Rayleigh(max) to far below an
    ulp (rigorous sandwich): sf, cdf, pdf, logsf, logcdf agree with it to a few ulps (times
    the condition number ``E = x**2/(2 s**2)`` of ``exp(-E)`` in the far tail, within the
    reported error) and with each other (cdf + sf = 1), in float64."""
    big = max(scales)
    x = x * big
    small = sorted(scales)[:-1]
    lo, hi = sandwich(big, small, x)
    assert rel_err(hi, lo) < 1e-60
    S = RayleighSum(scales)
    sf, cdf, pdf = S.sf(x), S.cdf(x), S.pdf(x)
    with mpmath.workdps(40), thread_mp().workdps(40):
        xm, bm = mpmath.mpf(x), mpmath.mpf(big)
        ref_cdf = -mpmath.expm1(-xm * xm / (2 * bm * bm))
        ref_pdf = xm / bm**2 * mpmath.exp(-xm * xm / (2 * bm * bm))
        e = float(xm * xm / (2 * bm * bm))
        tol = 1e-14 + 4.5e-16 * e
        res = S.probability(x)
        assert abs(res.value - lo) <= res.error <= (1e-14 + 2e-15 * e) * lo, (res, lo)
        assert rel_err(sf, lo) < tol, ("sf", sf, lo)
        assert rel_err(cdf, ref_cdf) < 1e-14, ("cdf", cdf, ref_cdf)
        assert rel_err(pdf, ref_pdf) < 10 * tol, ("pdf", pdf, ref_pdf)
        assert abs(S.logsf(x) - mpmath.log(lo)) <= 1e-14 * max(1, abs(mpmath.log(lo)))
        assert abs(S.logcdf(x) - mpmath.log(ref_cdf)) <= 1e-14 * max(1, abs(mpmath.log(ref_cdf)))
    assert abs(sf + cdf - 1) <= 2.3e-16


@pytest.mark.parametrize("scales", NEGLIGIBLE[:4])
def test_negligible_scale_reported_error_covers_the_true_error(scales):
    """``rayleigh_sum_probability`` and ``.probability``: value correct, the reported error
    covers the true error and is small (the float64 issue case reported 1.7e-15 for a value
    wrong by 0.5)."""
    lo, _ = sandwich(1.0, [s for s in scales if s < 1], 1.0)
    for tail, ref in (("upper", lo), ("lower", 1 - lo)):
        res = symhx.rayleigh_sum_probability(scales, 1.0, tail=tail)
        assert res == RayleighSum(scales).probability(1.0, tail=tail)
        true_err = abs(mpmath.mpf(res.value) - ref)
        assert true_err <= res.error + 1e-17 and res.error < 1e-14, (tail, res, true_err)


@pytest.mark.parametrize("scales", [["1", "1e-100"], ["1", "1e-154"], ["1", "1e-300", "1e-300"]])
@pytest.mark.parametrize("kind", ["sf", "cdf", "pdf", "logsf", "logcdf"])
def test_negligible_scale_at_dps_agrees_with_the_sandwich(scales, kind):
    """dps=20: the value is Rayleigh(1)'s to 20 digits (the negligible scales shift it by
    ~1e-100 relative), and float64 agrees with the dps value to a few ulps."""
    lo, _ = sandwich(1, scales[1:], 1, dps=50)
    with mpmath.workdps(50), thread_mp().workdps(50):
        ref = {"sf": lo, "cdf": 1 - lo, "pdf": lo, "logsf": mpmath.log(lo),
               "logcdf": mpmath.log(1 - lo)}[kind]
    S = RayleighSum(scales)
    got = getattr(S, kind)("1", dps=20)
    assert rel_err(got, ref) < 1e-19, (kind, got, ref)
    assert rel_err(getattr(S, kind)(1.0), ref) < 1e-14


@pytest.mark.parametrize("scales", [[1.0, 1e-8], [1.0, 1e-4, 1e-8], [1e8, 1.0, 1e-8]])
def test_scales_spread_over_1e8_keep_their_small_effect(scales):
    """Scales spread over 1e+-8: the small scales shift the value by ~1e-8 relative, which a
    quadrature reference (tests.reference.forcing) resolves; float64 keeps it to 1e-13."""
    x = 1.5 * max(scales)
    S = RayleighSum(scales)
    for kind in ("sf", "cdf", "pdf"):
        ref = rayleigh_sum_value(scales, x, kind)
        one = {"sf": math.exp(-x * x / (2 * max(scales) ** 2))}.get(kind)
        if one is not None:
            assert rel_err(one, ref) > 1e-10   # the small scales do matter here
        assert rel_err(getattr(S, kind)(x), ref) < 1e-13, (kind, scales)


# =========================================================================== item 4
@pytest.mark.slow
@pytest.mark.parametrize("m", [6, 7])
def test_issue_case_unit_scales_against_a_straight_contour_inversion(m):
    """``RayleighSum([1.0]*7).sf(5.29)`` (was MemoryError after 18 s) and six scales, in
    float64 and at dps=20, against the straight-line Gauss-Legendre inversion at dps 20."""
    ref = bromwich_line([1] * m, "5.29", "sf", dps=20)
    S = RayleighSum([1.0] * m)
    assert rel_err(S.sf(5.29), ref) < 1e-14
    assert rel_err(S.sf("5.29", dps=18), ref) < 1e-17


def test_many_spread_scales_against_monte_carlo():
    """64 scales spread over 1e-3..1 (a turbulent spectrum): sf, cdf and pdf agree with 2e6
    seeded Monte Carlo draws within 5 standard errors (an independent check of the bulk)."""
    rng = np.random.default_rng(20261127)
    scales = list(10 ** rng.uniform(-3, 0, 64))
    S = RayleighSum(scales)
    draws = np.zeros(2_000_000)
    for s in scales:
        draws += rng.rayleigh(scale=s, size=draws.size)
    mean, std = float(S.mean()), float(S.std())
    assert abs(draws.mean() - mean) < 5 * std / math.sqrt(draws.size)
    xs = mean + std * np.array([-2.0, -1.0, 0.0, 1.0, 2.5])
    sf, cdf = S.sf(xs), S.cdf(xs)
    for x, got_sf, got_cdf in zip(xs, sf, cdf, strict=True):
        emp = float(np.mean(draws > x))
        se = math.sqrt(emp * (1 - emp) / draws.size)
        assert abs(got_sf - emp) < 5 * se, (x, got_sf, emp)
        assert abs(got_sf + got_cdf - 1) < 1e-15
    h = 0.05 * std   # density: the empirical mass of a small window
    emp_pdf = float(np.mean(np.abs(draws - mean) < h)) / (2 * h)
    se = math.sqrt(emp_pdf / (2 * h * draws.size))
    assert abs(S.pdf(mean) - emp_pdf) < 5 * se + 1e-3 * emp_pdf


@pytest.mark.parametrize("m", [3, 8, 64])
def test_many_scales_float64_meets_the_documented_contract(m):
    """M scales spread over 1e+-2, thresholds from the far lower to the far upper tail:
    float64's relative error against dps=30 is within the README's contract ``1e-13 + 4 k
    eps`` (``k`` the condition number of the value: ``E = x**2/(2 sum s**2)`` of a far upper
    tail ``exp(-E)``, ``-log P`` of a far lower one), and the reported error is never below
    the true error (nor above ``1e-12 + 10 k eps``)."""
    rng = np.random.default_rng(m)
    scales = [float(s) for s in 10 ** rng.uniform(-2, 0, m)]
    S = RayleighSum(scales)
    mean, std = float(S.mean()), float(S.std())
    eps = np.finfo(float).eps
    for x in (0.3 * mean, mean - std, mean, mean + 3 * std, mean + 12 * std):
        for tail in ("upper", "lower"):
            got = S.probability(x, tail=tail)
            ref = S.probability(x, tail=tail, dps=30)
            assert ref.error < 1e-29 * ref.value
            k = max(1.0, x * x / (2 * sum(s * s for s in scales)), -math.log(got.value))
            true = abs(got.value - ref.value)
            assert true <= (1e-13 + 4 * k * eps) * ref.value, (x, tail, got, ref.value)
            # a value rounded to 1.0 reports the complement it dropped as its error; the
            # reference resolves that complement to its 30 digits only
            assert true <= got.error + 1e-29 * ref.value, got
            assert got.error <= (1e-12 + 10 * k * eps) * got.value, got


@pytest.mark.parametrize("m, kinds", [(4, ("sf", "cdf", "pdf", "logsf")),
                                      pytest.param(8, ("sf", "pdf"), marks=pytest.mark.slow)])
def test_many_scales_at_dps_against_twice_the_digits(m, kinds):
    """dps=30 against dps=60 for up to eight scales, both tails and the density."""
    scales = [f"{(k + 1) / (m + 1):.3f}" for k in range(m)]
    S = RayleighSum(scales)
    x = str(round(float(S.mean()) * 1.7, 3))
    for kind in kinds:
        assert rel_err(getattr(S, kind)(x, dps=30), getattr(S, kind)(x, dps=60)) < 1e-30, kind


def test_impact_probability_with_six_forcing_components():
    """``impact_probability(0.2, Omega=[1.5, 2, 2.5, 3, 3.5, 4])`` (was MemoryError): seven
    Rayleigh amplitudes; float64 within its error of dps=30, dps=20 against dps=40, Monte Carlo
    of the seven amplitudes within 5 standard errors, and ``1 - p`` its complement."""
    om = [1.5, 2, 2.5, 3, 3.5, 4]
    p = symhx.impact_probability(0.2, Omega=om)
    p40 = symhx.impact_probability(0.2, Omega=om, dps=40)
    assert rel_err(p, p40) < 1e-14
    assert rel_err(symhx.impact_probability(0.2, Omega=om, dps=20), p40) < 1e-19
    assert abs(symhx.no_impact_probability(0.2, Omega=om) + p - 1) < 1e-15
    rng = np.random.default_rng(28)
    scales = symhx.rayleigh_scales(0.2, Omega=om)
    hits = np.zeros(1_000_000)
    for s in scales:
        hits += rng.rayleigh(scale=s, size=hits.size)
    emp = float(np.mean(hits > 1.0))
    assert abs(p - emp) < 5 * math.sqrt(emp * (1 - emp) / hits.size), (p, emp)


def test_impact_probability_components_in_an_array_of_thresholds():
    """Five components and an array of sigmas give the elementwise values (the memory of 500
    sigmas, 1.9 GiB in the issue, is checked in tests/perf)."""
    om = [1.5, 2, 2.5, 3, 3.5]
    sig = np.linspace(0.05, 0.6, 60)
    p = symhx.impact_probability(sig, Omega=om)
    assert p.shape == (60,) and np.all(np.diff(p) > 0)
    for i in (0, 37, 59):
        assert p[i] == symhx.impact_probability(float(sig[i]), Omega=om)


# --------------------------------------------------------------------------- MAX_SCALES
def test_max_scales_is_the_limit_of_the_sum():
    """``MAX_SCALES`` scales are evaluated, one more is refused, naming the argument."""
    n = MAX_SCALES
    assert n == 64
    assert 0 < RayleighSum([1.0] * n).sf(60.0) < 1
    assert_refuses(RayleighSum, [1.0] * (n + 1), arg="scales", value=str(n + 1),
                   allowed="MAX_SCALES")
    assert_refuses(symhx.rayleigh_sum_probability, [1.0] * (n + 1), 1.0, arg="scales",
                   value=str(n + 1), allowed="MAX_SCALES")


def test_max_scales_is_checked_before_any_conversion():
    """The count is checked first: a 65-long list with an unreadable entry or a huge
    irrational is refused for its length, at once."""
    n = MAX_SCALES
    bad = [1.0] * n + ["not a number"]
    assert_refuses(RayleighSum, bad, arg="scales", value=str(n + 1), allowed="MAX_SCALES")
    assert_refuses(symhx.impact_probability, 0.2, Omega=[1.5] * n + ["x"], arg="Omega",
                   value=str(n), allowed="MAX_SCALES")


def test_max_scales_components_refused_alike_by_api_and_cli(capsys):
    """``MAX_SCALES - 1`` forcing components are the limit for the API and the CLI alike; one
    more is refused by both with the same reason (CLI: exit 2, one line, no traceback)."""
    n = MAX_SCALES
    om = [1.5 + 0.01 * k for k in range(n)]
    assert 0 < symhx.impact_probability(0.02, Omega=om[:-1]) < 1
    msg = assert_refuses(symhx.impact_probability, 0.2, Omega=om, arg="Omega", value=str(n),
                         allowed="MAX_SCALES")
    assert cli_main(["p-sigma", "0.02", "--Omega", ",".join(map(str, om[:-1]))]) == 0
    capsys.readouterr()
    assert cli_main(["p-sigma", "0.2", "--Omega", ",".join(map(str, om))]) == 2
    err = capsys.readouterr().err
    assert "Traceback" not in err and len(err.strip().splitlines()) == 1
    assert f"MAX_SCALES - 1 = {n - 1}" in err and f"MAX_SCALES - 1 = {n - 1}" in msg
