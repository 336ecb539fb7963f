"""The work limits of :func:`symhx.asymptotic_critical_point` (issue 28, item 6): the working
precision carries every digit of N, so each order has a documented digit limit, checked before
any work."""

from __future__ import annotations

import time

import mpmath
import pytest

import symhx
from symhx import asymptotics as A
from tests.harness.errors import assert_refuses


@pytest.mark.parametrize("order, e", [("lambert", 100000), ("leading", 20000),
                                      ("corrected", 20000), ("best", 5000), ("relaxed", 10000)])
def test_an_N_beyond_the_digit_limit_of_its_order_is_refused_at_once(order, e):
    N = 10**e
    t0 = time.perf_counter()
    name = "MAX_RELAXED_DIGITS" if order in ("relaxed", "best") else "MAX_FORMULA_DIGITS"
    limit = getattr(A, name)
    assert_refuses(A.asymptotic_critical_point, N, order=order, arg="N",
                   value=f"N=1.0e+{e}", allowed=[f"N < 10**{limit}", name])
    assert time.perf_counter() - t0 < 0.5


def test_the_limit_is_exclusive_and_the_constant_is_honoured(monkeypatch):
    monkeypatch.setattr(A, "MAX_FORMULA_DIGITS", 40)
    N = 10**40 - 1
    a = A.asymptotic_critical_point(N, order="lambert", dps=20)
    # independent: v = -W_{-1}(-e^2/N) by mpmath at twice the precision, q = expm1(1/k + k/N)
    with mpmath.workdps(120):
        v = -mpmath.lambertw(-mpmath.e**2 / N, -1).real
        k = mpmath.sqrt(N * v)
        q = mpmath.expm1(1 / k + k / N)
        k_int = int(mpmath.nint(k))
    assert abs(a.q / q - 1) < mpmath.mpf(10) ** -19
    assert a.k_int == k_int
    assert_refuses(A.asymptotic_critical_point, 10**40, order="lambert", arg="N",
                   allowed="N < 10**40")


def test_large_allowed_N_still_work_for_the_closed_forms():
    a = symhx.asymptotic_critical_point(10**3000, order="next", dps=15)
    with mpmath.workdps(3100):
        L = mpmath.log(mpmath.mpf(10) ** 3000)
        lam = L - 2
        v = lam + mpmath.log(lam)
        q = (v + 1) / mpmath.sqrt(mpmath.mpf(10) ** 3000 * v)
    assert abs(a.q / q - 1) < mpmath.mpf(10) ** -14
