"""Deliberate cost tests of the forcing layer: how many evaluations (and which routes) a call
costs. They pin work, not values: the CLI evaluates p and 1 - p once per sigma, the inverse
polishes the float64 root in a few secant steps, float inputs take the raw-libmp route, the
planned ``1 - p`` never needs the adaptive loop, and far in the upper tail the Rayleigh-sum cdf
costs one upper-tail quadrature."""

from __future__ import annotations

import math
from fractions import Fraction

import mpmath
import pytest

from symhx import forcing as F
from symhx._mpctx import mp as thread_mp
from symhx.forcing import RayleighSum
from symhx.forcing import probability as P
from tests.reference.forcing import forcing_values, sigma_root
from tests.reference.mp import rel_err

FUNCS = {"p": F.impact_probability, "q": F.no_impact_probability,
         "logp": F.log_impact_probability, "logq": F.log_no_impact_probability}


def tol(dps):
    return mpmath.mpf(10) ** -dps


def test_cost_of_p_sigma_rows_is_one_p_and_one_q_per_sigma(monkeypatch):
    """mpmath: p and 1 - p once each per sigma (the logs are derived), no log kernels."""
    import argparse

    from symhx.commands import forcing as C
    from symhx.forcing import probability as P

    calls = []
    orig = P.evaluate

    def spy(fp, dps, want):
        calls.append(want)
        return orig(fp, dps, want)

    monkeypatch.setattr(P, "evaluate", spy)
    ns = argparse.Namespace(sigma=["0.1", "0.2"], grid=None, dps=20, sigma1=None, omega="1",
                            Omega=None, d="1", inverse=False)
    rows = C._rows(C._values(ns), ns)
    assert sorted(calls) == ["p", "p", "q", "q"]
    assert math.isclose(float(rows[0]["log_p"]), F.log_impact_probability(0.1), rel_tol=1e-14)


def test_cost_of_the_mp_inverse_is_a_few_secant_steps_from_the_float_root(monkeypatch):
    """Where float64 has a root, the mpmath path starts from it: a few secant steps at the
    working precision (not a bracket and 60 bisections)."""
    import symhx.forcing.inverse as inv

    calls = []
    real = inv.evaluate

    def counting(fp, dps, want):
        calls.append(dps)
        return real(fp, dps, want)

    monkeypatch.setattr(inv, "evaluate", counting)
    for p in ("1e-250", "0.3", "0.9", Fraction(1) - Fraction(1, 10**15)):
        calls.clear()
        got = F.sigma_for_impact_probability(p, dps=30)
        assert rel_err(got, sigma_root(p, work=70)) <= tol(30)
        assert 0 < sum(d is not None for d in calls) <= 10, (p, calls)
    for p, kw in [("0.3", {"d": "1e8"}), ("0.1", {"sigma1": "0.3"}),
                  ("0.01", {"sigma1": "4", "d": "20"}),
                  ("0.2", {"omega": "1.3", "Omega": "1.000001"}),
                  ("0.2", {"sigma1": ["0.3", "0.4"], "Omega": ["1.7", "2.2"]})]:
        calls.clear()
        F.sigma_for_impact_probability(p, **kw, dps=12)
        assert 0 < sum(d is not None for d in calls) <= 10, (p, kw, calls)


def test_cost_of_float_inputs_is_the_raw_libmp_route_only(monkeypatch):
    """The documented route: float (and dyadic) inputs are served by the raw-libmp fast path;
    the mpf-object route (``mp_xy_forcing``, the mpf estimate) is never entered for them."""
    def boom(*args):
        raise AssertionError("mpf-object route entered for float inputs")

    args = dict(sigma1=0.2, omega=1.1, Omega=1.7, d=0.9, dps=30)
    r = forcing_values(0.3, 0.2, 1.1, 1.7, 0.9, dps=30)
    monkeypatch.setattr(P, "mp_xy_forcing", boom)
    monkeypatch.setattr(P, "estimate", boom)
    for k, want in enumerate(("p", "q")):  # p < 1/2 here: both are fast-path quantities
        assert rel_err(FUNCS[want](0.3, **args), r[k]) <= mpmath.mpf(10) ** -30, want


def test_cost_of_planning_mpf_inputs_in_float_range_is_a_float_estimate(monkeypatch):
    """mpf inputs whose values are normal floats are planned by the float estimate; the
    64-bit mpf estimate is only for inputs beyond the float range."""
    def boom(*args):
        raise AssertionError("mpf estimate used for inputs in the float range")

    with mpmath.workdps(40), thread_mp().workdps(40):
        args = (mpmath.mpf("0.3"), mpmath.mpf("0.2"), mpmath.mpf("1.1"), mpmath.mpf("1.7"),
                mpmath.mpf("0.9"))
    monkeypatch.setattr(P, "estimate", boom)
    r = forcing_values(*args, dps=25)
    for k, want in enumerate(("p", "q", "logp", "logq")):
        got = FUNCS[want](args[0], sigma1=args[1], omega=args[2], Omega=args[3], d=args[4],
                          dps=25)
        assert rel_err(got, r[k]) <= mpmath.mpf(10) ** -25, want


@pytest.mark.parametrize("sigma", [0.5, 0.9, 3.0, 30.0, 3e3, 3e5, 3e7])
def test_cost_of_a_planned_one_minus_p_is_one_evaluation(sigma, monkeypatch):
    """The precision plan adds the digits that 1 - p cancels up front (x y / 6 for small x, y):
    1 - p and log(1 - p) near and above p = 1/2 are formed directly, right to dps, and the
    adaptive loop (the a posteriori safety net) is never entered."""
    r = forcing_values(sigma, dps=40)

    def boom(*args):
        raise AssertionError("adaptive 1 - p loop entered")

    monkeypatch.setattr(P, "mp_q_from_xy", boom)
    for dps in (15, 40):
        for k, want in ((1, "q"), (3, "logq")):
            got = FUNCS[want](sigma, dps=dps)
            assert rel_err(got, r[k], 80) <= mpmath.mpf(10) ** -dps, (want, sigma, dps)


def test_cost_of_the_far_upper_cdf_is_one_upper_tail_inversion(monkeypatch):
    # far in the upper tail the cdf is 1 - sf: one inversion, of the upper tail; below the
    # mean one inversion of the lower tail
    import symhx.forcing.rayleigh as R

    calls = []
    orig = R.invert_arb

    def spy(scales, x, kind, dps):
        calls.append(kind)
        return orig(scales, x, kind, dps)

    monkeypatch.setattr(R, "invert_arb", spy)
    S = RayleighSum(["0.5", "0.3", "0.2"])
    far = S.cdf("4", dps=20)
    assert calls == ["sf"]
    with mpmath.workdps(40), thread_mp().workdps(40):
        assert abs(far - (1 - S.sf("4", dps=30))) < mpmath.mpf(10) ** -20
    calls.clear()
    S.cdf("0.5", dps=20)
    assert calls == ["cdf"]
