"""The documented cost of symhx.critical's certification, counted by spies on its ball
functions (private: these are cost tests, not behaviour tests).

Each certified sign is one Arb ball of E(k) at the start precision (the ball separates at once
unless E(k) = 0 exactly), a correct seed is proved by exactly the two signs
E(k*-1) < 0 <= E(k*), a seed a few steps off costs a few more, and a far seed costs a gallop
plus a bisection: at most 2 log2(distance) + 2 signs. The p_c enclosure costs one ball of
s(k*), a comparison of p with p_c one ball (two when p is very close). The first argmin itself
comes from an independent reference (tests.reference.critical)."""

from __future__ import annotations

import dataclasses
from fractions import Fraction

import mpmath
import pytest

from symhx import critical as C
from symhx.critical import certified_argmin, critical_point
from symhx.validation import as_fraction
from tests.reference.critical import is_first_argmin, p_c_direct, p_d_closed

COST_N = [10**4, 10**6, 10**9 + 7, 10**12, 10**18, 10**30]


def _spy(monkeypatch, name):
    """Record the arguments of every call of ``symhx.critical.<name>``."""
    calls = []
    orig = getattr(C, name)

    def spy(*args):
        calls.append(args)
        return orig(*args)

    monkeypatch.setattr(C, name, spy)
    return calls


@pytest.fixture
def e_calls(monkeypatch):
    """The k of every ball of E(k) computed."""
    calls: list[int] = []
    orig = C._E_arb

    def spy(N, k):
        calls.append(k)
        return orig(N, k)

    monkeypatch.setattr(C, "_E_arb", spy)
    return calls


def _first_argmin(N: int) -> int:
    k = certified_argmin(N)[0]
    assert is_first_argmin(N, k)
    return k


@pytest.mark.parametrize("N", [3, 4, 6, 7, 8, 12, 30, 101, *COST_N])
def test_a_correct_seed_costs_exactly_the_two_proving_signs(N, e_calls):
    k = _first_argmin(N)
    e_calls.clear()
    got = C._argmin_c(N, k)
    assert got == (k, False, 1 if k == 2 else 2)
    assert sorted(e_calls) == ([2] if k == 2 else [k - 1, k])  # one ball per sign
    # certified_argmin passes its seed on: the same two balls
    e_calls.clear()
    assert certified_argmin(N, seed=k) == (k,)
    assert sorted(e_calls) == ([2] if k == 2 else [k - 1, k])
    # and critical_point reports the signs its own (Lambert-W) seed needed
    e_calls.clear()
    cp = critical_point(N, dps=5)
    assert cp.argmins[0] == k
    assert cp.sign_evaluations == len(set(e_calls)) == len(e_calls) >= (1 if k == 2 else 2)


def test_the_exact_tie_costs_the_full_doubling_then_integers(e_calls):
    # N = 5: E(2) = 0 exactly, so the ball of E(2) contains 0 at every precision: it is tried at
    # start, 2, 4, 8 and 16 x start bits (max_bits = 16 x start), then the integers decide
    assert C._argmin_c(5, 2) == (2, True, 1)
    assert e_calls == [2] * 5


@pytest.mark.parametrize("N", COST_N)
def test_a_seed_a_few_steps_off_costs_a_few_more_signs(N, e_calls):
    k = _first_argmin(N)
    for d in range(-6, 7):
        e_calls.clear()
        got = C._argmin_c(N, k + d)
        assert got[:2] == (k, False)
        # off by one: the failed check shows the direction, one more sign proves k*;
        # further off: one secant step on the two balls lands on k* (E is nearly linear there)
        assert got[2] == (2 if d == 0 else 3 if abs(d) == 1 else 4), (N, d, got)
        assert len(e_calls) == got[2]


@pytest.mark.parametrize("N", [30, 101, 1000, *COST_N, 10**60])
def test_a_far_seed_costs_a_gallop_and_a_bisection(N, e_calls):
    k = _first_argmin(N)
    for seed in (2, 3, N - 1, N):  # from k >= N - 1 the search gallops down at once
        e_calls.clear()
        got = C._argmin_c(N, seed)
        assert got[:2] == (k, False)
        dist = abs(seed - k)
        assert got[2] <= 2 * dist.bit_length() + 2, (N, seed, got)
        assert len(e_calls) == got[2]


def test_small_N_argmin_costs():
    # N = 2: nothing to compare; N = 3, 4: c_3 > c_2 is the one sign that proves k* = 2
    assert C._argmin_c(2) == (2, False, 0)
    assert C._argmin_c(3) == (2, False, 1)
    assert C._argmin_c(4) == (2, False, 1)
    assert critical_point(3).sign_evaluations == 1


@pytest.mark.parametrize("N", [6, 12, 101, 10**6, 10**30])
@pytest.mark.parametrize("dps", [1, 15, 60, 200])
def test_critical_point_enclosure_costs_one_ball(N, dps, monkeypatch):
    # the start precision of the p_c enclosure already meets the width: a single ball of s(k*)
    calls = _spy(monkeypatch, "_s_arb")
    cp = critical_point(N, dps=dps)
    assert cp.p_exact is None and [k for _, k in calls] == [cp.argmins[0]]
    # p_d (eq. 16), where f first gets real roots: the larger root of (N p - 1)**2 = 4 p
    pd, _ = p_d_closed(N, 3 * dps)
    with mpmath.workdps(3 * dps + 2 * len(str(N)) + 20):
        assert abs(cp.p_d - pd) <= mpmath.mpf(10) ** (1 - dps) * pd


@pytest.mark.parametrize("N, dps", [(12, 5), (101, 20), (101, 60), (10**6, 30), (10**30, 15)])
def test_compare_near_p_c_costs_one_ball_then_two(N, dps, monkeypatch):
    cp = critical_point(N, dps=dps)
    k = cp.argmins[0]
    ref = p_c_direct(N, k, 2 * dps + 40)  # independent p_c, far beyond the distances used
    lo, hi = (as_fraction(b) for b in cp.p_bounds)
    g_calls = _spy(monkeypatch, "G_arb")
    perm_calls = _spy(monkeypatch, "_perm")
    start = C.bits_for(N, int(dps * 3.33) + 2 * k.bit_length() + 40)
    tested = set()
    for sgn in (-1, 1):
        for extra, balls in ((int(dps * 3.33) + 2 * k.bit_length() + 20, 1), (start + 24, 2)):
            with mpmath.workdps(2 * dps + 40 + 2 * len(str(N))):
                fr = as_fraction(ref * (1 + sgn * mpmath.mpf(2) ** -extra))
            if not lo < fr < hi:  # p_c sits near one end of the (hulled) bounds
                continue
            g_calls.clear()
            assert C.compare_with_critical(cp, fr) == sgn
            # the start precision separates at 2**-(dps*3.33 + 2 log2 k + 20); closer
            # (2**-(start + 24)) the doubled precision does: never the exact integers
            assert len(g_calls) == balls and not perm_calls, (sgn, extra)
            tested.add(balls)
    assert tested == {1, 2}


def test_compare_on_an_exact_tie_costs_five_balls_then_integers(monkeypatch):
    # N = 5 with p_exact withheld: the ball of the exact zero is tried at start, 2, 4, 8 and
    # 16 x start bits, then the integers say 0
    blind = dataclasses.replace(critical_point(5), p_exact=None,
                                p_bounds=(mpmath.mpf("0.4"), mpmath.mpf("0.6")))
    g_calls = _spy(monkeypatch, "G_arb")
    assert C.compare_with_critical(blind, Fraction(1, 2)) == 0
    assert len(g_calls) == 5
