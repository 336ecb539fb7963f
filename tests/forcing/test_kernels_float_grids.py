"""The float64 one-component path (``symhx.forcing.kernels_float`` through the public functions)
on log grids against the mpmath path and independent formulas: the documented contract
``relative error <= 1e-13 + 4 kappa eps`` (``kappa = |d ln p/d ln sigma|``), a few ulps where
well conditioned, both tails, monotonicity and complementarity, symmetry in the two scales."""

from __future__ import annotations

import mpmath
import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from symhx import forcing as F
from symhx._mpctx import mp as thread_mp
from tests.harness.twins import check_twins
from tests.reference.mp import assert_mp_close, rel_err

EPS = np.finfo(float).eps


PAPER_CASES = [  # (omega, Omega or None, d)
    (1.0, None, 1.0),  # the paper
    (0.7, 1.9, 0.3),
    (2.0, 1.0, 3.0),
    (1.0, 1.001, 1.0),  # near resonance: huge forced amplitude
    (1.3, 0.2, 0.05),
]


PAPER_RATIOS = [None, 0.1, 3.0, 30.0]  # sigma1 = ratio * sigma (None: sigma1 = sigma)


# ----------------------------------------------------------------------------- float64 vs mpmath
def _kappa_mp(sigma, s1, kw):
    """|d ln p/d ln sigma| with every sigma_i scaled together, by mpmath central difference."""
    with mpmath.workdps(40), thread_mp().workdps(40):
        h = mpmath.mpf(10) ** -12
        sm, sp = mpmath.mpf(sigma) * (1 - h), mpmath.mpf(sigma) * (1 + h)
        s1m = None if s1 is None else mpmath.mpf(s1) * (1 - h)
        s1p = None if s1 is None else mpmath.mpf(s1) * (1 + h)
        pm = F.impact_probability(sm, sigma1=s1m, **kw, dps=35)
        pp = F.impact_probability(sp, sigma1=s1p, **kw, dps=35)
        return float((pp - pm) / (2 * h))  # = sigma dp/dsigma


def _grid_errors(sigmas, case, ratio):
    omega, Omega, d = PAPER_CASES[case]
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
            worst[name] = max(worst[name], float(rel_err(val, ref)) / bound)
    return worst


@pytest.mark.parametrize("case", range(len(PAPER_CASES)))
@pytest.mark.parametrize("ratio", PAPER_RATIOS)
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
        assert rel_err(p[i], F.impact_probability(s, dps=25)) < 40 * EPS * (1 + 1 / s**2)
        assert rel_err(q[i], F.no_impact_probability(s, dps=25)) < 40 * EPS


def test_float64_tails_are_nonzero_and_accurate_where_naive_is_zero():
    # p at sigma = 0.0125: ~1e-348 -> 0 in float64 but its log is exact
    lp = F.log_impact_probability(np.array([0.0025, 0.01, 0.03]))
    for s, v in zip([0.0025, 0.01, 0.03], lp, strict=True):
        ref = F.log_impact_probability(s, dps=30)
        assert rel_err(v, ref) < 4 * EPS
    # 1 - p at sigma = 1e100 is ~1e-402 (below float range): its log is exact
    lq = F.log_no_impact_probability(np.array([1e2, 1e50, 1e100, 1e150]))
    for s, v in zip([1e2, 1e50, 1e100, 1e150], lq, strict=True):
        ref = F.log_no_impact_probability(s, dps=30)
        assert rel_err(v, ref) < 4 * EPS


def test_large_sigma_leading_term():
    """1 - p -> d^4/(24 s0^2 s1^2) (density r/s^2 near 0 of each Rayleigh, simplex volume)."""
    for s, s1, om, Om, d in [(1e4, 1e4, 1.0, None, 1.0), (3e3, 5e2, 0.7, 2.0, 0.3)]:
        k = abs(om**2 - (2.0 if Om is None else Om**2))
        s0sq, s1sq = 2 * s**2, 2 * s1**2 / k**2
        lead = d**4 / (24 * s0sq * s1sq)
        q = F.no_impact_probability(s, sigma1=s1, omega=om, Omega=Om, d=d)
        assert abs(q / lead - 1) < 1e-5


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


# ----------------------------------------------------------------------------- seeded twins
_WANT_FN = {"p": F.impact_probability, "q": F.no_impact_probability,
            "logp": F.log_impact_probability, "logq": F.log_no_impact_probability}


def _seeded_forcings(n, seed):
    """Seeded random one-component forcings: sigma log-uniform over [0.01, 100] (log grids of
    the contract), sigma1/sigma over 1e-3 .. 1e3, omega, Omega, d away from 1."""
    rng = np.random.default_rng(seed)
    out = []
    for _ in range(n):
        s0 = float(10 ** rng.uniform(-2, 2))
        s1 = None if rng.random() < 0.3 else float(s0 * 10 ** rng.uniform(-3, 3))
        om = float(10 ** rng.uniform(-0.5, 0.5))
        Om = None if rng.random() < 0.25 else float(om * 10 ** rng.uniform(-0.6, 0.6))
        out.append((s0, s1, om, Om, float(10 ** rng.uniform(-1, 1)),
                    ("p", "q", "logp", "logq")[int(rng.integers(4))]))
    return out


def _float_twin(s0, s1, om, Om, d, want):
    return _WANT_FN[want](s0, sigma1=s1, omega=om, Omega=Om, d=d)


def _mp_twin(s0, s1, om, Om, d, want):
    """The mpmath value at 30 digits and the condition number ``kappa = |d ln f/d ln d|`` of
    the value (of its argument, for a log), by a central difference at 35 digits."""
    kw = dict(sigma1=s1, omega=om, Omega=Om)
    fn = _WANT_FN[want if want in ("p", "q") else want[3:]]
    val = _WANT_FN[want](s0, **kw, d=d, dps=30)
    with mpmath.workdps(40), thread_mp().workdps(40):
        h = mpmath.mpf(10) ** -12
        lo = fn(s0, **kw, d=mpmath.mpf(d) * (1 - h), dps=35)
        hi = fn(s0, **kw, d=mpmath.mpf(d) * (1 + h), dps=35)
        kappa = abs(mpmath.log(hi) - mpmath.log(lo)) / (2 * h)
    return val, float(kappa)


def _within_contract(got, twin, case):
    """``1e-13 + 4 kappa eps`` relative for p and 1 - p (normal floats); the logs carry the
    relative error of their argument as an absolute error (plus their own rounding)."""
    ref, kappa = twin
    bound = 1e-13 + 4 * kappa * float(EPS)
    if case[-1].startswith("log"):
        assert_mp_close(got, ref, rtol=4 * float(EPS), atol=bound, what=case[-1])
    elif ref >= np.finfo(float).tiny:
        assert_mp_close(got, ref, rtol=bound, what=case[-1])


def test_float64_and_mpmath_twins_on_seeded_forcings():
    """Twins (tests/harness/twins.py): the float64 path and the mpmath path at 30 digits on 300
    seeded random forcings (p, 1 - p and both logs), to the documented contract."""
    assert check_twins(_float_twin, _mp_twin, _seeded_forcings(300, 20260629),
                       _within_contract) == 300
