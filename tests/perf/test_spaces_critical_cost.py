"""Cost of the higher-order critical point (``symhx.spaces._critical``): the number of certified
signs it reports is the number it evaluated, and Newton's refinement from the float64 seed
takes the few steps quadratic convergence promises."""

from __future__ import annotations

import mpmath

import symhx.spaces._critical as crit
from symhx.spaces import critical_point, parse_space, root_estimates
from tests.reference.spaces import ROOT_DIGITS, root


def _count_h_mp(monkeypatch) -> list[int]:
    calls: list[int] = []
    real = crit._h_mp

    def counting(sp, N, k, s):
        calls.append(k)
        return real(sp, N, k, s)

    monkeypatch.setattr(crit, "_h_mp", counting)
    return calls


def test_sign_evaluations_count_the_certified_signs(monkeypatch):
    real = crit._sign_h
    calls = []

    def counting(*a):
        calls.append(a[2])
        return real(*a)

    monkeypatch.setattr(crit, "_sign_h", counting)
    for base, N in (("eq41", 30), ("excess<=3;distinct", 12), ("excess<=0", 5)):
        calls.clear()
        cp = critical_point(N, space=base, dps=20)
        assert cp.sign_evaluations == len(calls) >= 2


def test_root_mp_newton_is_quadratic_from_the_float_seed(monkeypatch):
    """From the float64 seed (~16 digits) Newton doubles the digits per step: at most 5 steps up
    to 200 digits, and the root agrees with the 70-digit bisection root."""
    calls = _count_h_mp(monkeypatch)
    for base, N in (("eq41", 30), ("excess<=3", 12), ("excess<=20", 3)):
        sp = parse_space(base)
        est = root_estimates(sp, N)
        for k in (2, 3, N):
            ck = root(N, base, k)
            for wp in (20, 50, 200):
                calls.clear()
                s = crit._root_mp(sp, N, k, float(est[k - 2]), wp)
                assert 1 <= len(calls) <= 5, (base, N, k, wp, len(calls))
                with mpmath.workdps(ROOT_DIGITS):
                    ref = mpmath.log(N * ck)
                    assert abs(s - ref) <= mpmath.mpf(10) ** (3 - min(wp, ROOT_DIGITS - 8)), (
                        k, wp)


def test_critical_point_refines_each_root_from_its_own_seed(monkeypatch):
    """critical_point refines c_best from the float64 seed of the same k (error ~1e-15): at
    dps = 30 (wp ~ 50) two Newton steps reach 1e-60 and the third, below 10**(3-wp), stops; a
    neighbour's seed (0.05 to 0.15 off in log p) needs two more."""
    calls = _count_h_mp(monkeypatch)
    for base, N in (("eq41", 12), ("eq41", 30), ("excess<=3", 30), ("excess<=6", 100),
                    ("excess<=1", 200)):
        calls.clear()
        critical_point(N, space=base, dps=30)
        assert calls and all(calls.count(k) <= 3 for k in set(calls)), (base, calls)
