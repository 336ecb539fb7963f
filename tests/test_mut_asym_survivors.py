"""Survivors of ``symhx.asymptotics`` that change what a user gets, checked against independent
references: ``p_d`` from its closed form (eq. 16) and ``k`` from the formulas / an mpmath
minimisation of the loggamma relaxation written out here, all at far more digits than claimed.
"""

from __future__ import annotations

import mpmath
import pytest

import symhx.asymptotics as asym
from symhx.asymptotics import asymptotic_critical_point, pd_series


@pytest.mark.parametrize("N", [10**40, 10**100])
@pytest.mark.parametrize("n_terms", [1, 5, 9])
@pytest.mark.parametrize("dps", [200, 400])
def test_pd_series_bound_is_rigorous_at_high_dps(N, n_terms, dps):
    """|p_d - value| <= bound also where the omitted terms are tiny and the rounding of the
    (dps+10)-digit partial sum matters: the 10**-(dps+5) |value| allowance must cover it (an
    allowance of 11**-(dps+5) falls below that rounding for dps >= ~120 and the bound fails)."""
    s = pd_series(N, n_terms, dps=dps)
    with mpmath.workdps(3 * dps + 4 * len(str(N))):
        pd = (N + 2 + 2 * mpmath.sqrt(N + 1)) / mpmath.mpf(N) ** 2
        assert abs(pd - s.value) <= s.bound


def _relaxed_kappa(N: int, dps: int) -> mpmath.mpf:
    """Real minimiser of h(kappa) = (log kappa - lgamma(N) + lgamma(N-K) + K log N) / K,
    K = kappa - 1 (findroot on h' from digamma, at 3x dps)."""
    with mpmath.workdps(3 * dps + 2 * len(str(N)) + 20):
        Nm = mpmath.mpf(N)

        def dh(kap):
            K = kap - 1
            G = mpmath.loggamma(Nm) - mpmath.loggamma(Nm - K) - K * mpmath.log(Nm)
            dG = mpmath.digamma(Nm - K) - mpmath.log(Nm)
            return K * (1 / kap - dG) - (mpmath.log(kap) - G)

        k0 = mpmath.sqrt(Nm * mpmath.log(Nm))
        return mpmath.findroot(dh, (k0 / 3, 2 * k0), solver="anderson")


def _k_ref(N: int, order: str, dps: int) -> mpmath.mpf:
    with mpmath.workdps(3 * dps + 20):
        Nm = mpmath.mpf(N)
        L = mpmath.log(Nm)
        if order == "leading":
            return mpmath.sqrt(Nm * L)
        if order == "next":
            return mpmath.sqrt(Nm * (L - 2 + mpmath.log(L - 2)))
        if order == "lambert":  # v = -W_{-1}(-e**2/N) solves v - log v = log N - 2
            v = mpmath.findroot(lambda t: t - mpmath.log(t) - (L - 2), L)
            return mpmath.sqrt(Nm * v)
    return _relaxed_kappa(N, dps)


@pytest.mark.parametrize("N", [1000, 10**10])
@pytest.mark.parametrize("dps", [20, 45])
@pytest.mark.parametrize("order", ["leading", "next", "lambert", "relaxed"])
def test_real_k_is_returned_at_the_requested_digits(order, N, dps):
    """A real ``k`` is rounded to ``dps`` digits like ``p`` and ``q`` (not handed back with
    the 15+ guard digits of the working precision), and is right to those digits."""
    a = asymptotic_critical_point(N, order=order, dps=dps)
    with mpmath.workdps(dps):
        assert +a.k == a.k and +a.p == a.p and +a.q == a.q
    with mpmath.workdps(3 * dps):
        assert abs(a.k / _k_ref(N, order, dps) - 1) < mpmath.mpf(10) ** (1 - dps)


@pytest.mark.parametrize("N", [10**40, 10**100, 10**1000], ids=["1e40", "1e100", "1e1000"])
@pytest.mark.parametrize("order", ["leading", "next", "lambert", "relaxed"])
def test_k_int_is_the_integer_nearest_k_at_low_dps(order, N):
    """``k`` has about log10(N)/2 integer digits, more than dps = 15 here: ``k_int`` must still
    be the integer nearest the real ``k`` (it was the nearest integer of ``k`` cut to 15
    digits: off by 51452 at N = 10**40 and by ~1e35 at N = 10**100)."""
    a = asymptotic_critical_point(N, order=order, dps=15)
    digits = len(str(N))
    ref = _k_ref(N, order, digits // 6 + 10)  # 3 * dps + 20 >= log10(N)/2 + 50 digits
    with mpmath.workdps(digits + 50):
        nearest = mpmath.nint(ref)
        assert abs(ref - nearest) < mpmath.mpf(0.499)  # not a half-integer tie
        assert a.k_int == int(nearest)


@pytest.mark.parametrize("N", [10**3, 10**40, 10**1000], ids=["1e3", "1e40", "1e1000"])
def test_relaxed_bracket_costs_a_few_evaluations(N, monkeypatch):
    """The root of F is bracketed from the Lambert point in O(1) evaluations: widening ``hi``
    only while ``F(hi) < 0`` (a loop that ran on to N - 2 took ~1660 doublings, 25x the time,
    at N = 10**1000 and gave the same root). Counted by wrapping ``_Relaxation.F``."""
    calls = []
    real = asym._Relaxation.F

    def counted(self, x):
        calls.append(x)
        return real(self, x)

    monkeypatch.setattr(asym._Relaxation, "F", counted)
    a = asymptotic_critical_point(N, order="relaxed", dps=20)
    assert len(calls) <= 60, len(calls)
    with mpmath.workdps(80):
        assert abs(a.k / _k_ref(N, "relaxed", 20) - 1) < mpmath.mpf(10) ** -19
