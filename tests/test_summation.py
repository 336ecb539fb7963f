"""Gauss-Legendre nodes, the Euler-Maclaurin corrections and the series helpers of
symhx.summation, against closed forms."""

from __future__ import annotations

import math

import mpmath

from symhx._mpctx import mp
from symhx.summation import (
    em_correction,
    em_remainder_factor,
    exp_series,
    gauss_legendre,
    gl_error_factor,
    series_mul,
)


def test_gauss_legendre_is_exact_for_degree_2n_minus_1() -> None:
    ctx = mp()
    for n in (8, 24, 96):
        with ctx.workdps(60):
            nodes = gauss_legendre(ctx, n)
            assert len(nodes) == n
            for deg in (0, 2 * n - 2):
                s = ctx.fsum(w * x**deg for x, w in nodes)
                assert abs(s - ctx.mpf(2) / (deg + 1)) < ctx.mpf(10) ** -55


def test_gauss_legendre_error_stays_below_its_bound() -> None:
    """e**(4x) on [-1, 1]: analytic everywhere; the bound with rho = 4 (M = e**(4 a))."""
    ctx = mp()
    rho = 4.0
    a = (rho + 1 / rho) / 2
    for n in (8, 12, 16):
        with ctx.workdps(80):
            s = ctx.fsum(w * ctx.exp(4 * x) for x, w in gauss_legendre(ctx, n))
            err = abs(s - (ctx.exp(4) - ctx.exp(-4)) / 4)
        bound = gl_error_factor(n, math.log(rho)) + 4 * a
        assert float(ctx.log(err)) <= bound


def test_euler_maclaurin_corrections_give_a_tail_of_zeta() -> None:
    """sum_{k>=10} 1/k**2 = int_10^inf + f(10)/2 - sum B_2m/(2m)! f^(2m-1)(10)."""
    ctx = mp()
    with ctx.workdps(40):
        x0 = ctx.mpf(10)
        coef = [(-1) ** j * (j + 1) / x0 ** (j + 2) for j in range(30)]  # 1/(x0+t)**2
        total = 1 / x0 + coef[0] / 2 - em_correction(ctx, coef, 12)
        want = ctx.zeta(2) - ctx.fsum(ctx.mpf(1) / k**2 for k in range(1, 10))
        assert abs(total - want) < ctx.mpf(10) ** -20
    assert em_remainder_factor(12, math.log(5)) < -20


def test_exp_series_and_product() -> None:
    ctx = mp()
    with ctx.workdps(30):
        e = exp_series(ctx, [0, ctx.mpf(1)], 8)  # exp(t)
        assert all(abs(v - 1 / ctx.factorial(n)) < ctx.mpf(10) ** -28 for n, v in enumerate(e))
        sq = series_mul(ctx, e, e, 6)  # exp(2t)
        assert all(abs(v - ctx.mpf(2) ** n / ctx.factorial(n)) < ctx.mpf(10) ** -27
                   for n, v in enumerate(sq))
    assert mpmath.mp.dps == 15
