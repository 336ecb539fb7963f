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


def test_gauss_legendre_rules_carry_the_contexts_full_precision() -> None:
    """At a working precision that is a multiple of the cache's 128-bit step (the rule is
    shared by the precisions up to it), every bit of it is right: x**(2n-2) integrates to
    2/(2n-1) within a few units of 2**-prec."""
    ctx = mp()
    for prec in (256, 512):
        for n in (8, 40):
            with ctx.workprec(prec):
                nodes = gauss_legendre(ctx, n)
            with ctx.workprec(2 * prec):
                s = ctx.fsum(w * x ** (2 * n - 2) for x, w in nodes)
                err = abs(s - ctx.mpf(2) / (2 * n - 1))
            assert err < ctx.mpf(2) ** (8 - prec), (prec, n)


def test_euler_maclaurin_remainder_factor_bounds_zeta() -> None:
    """The factor is an upper bound: log(2 zeta(2M) (2M)! / (2 pi r)**(2M)) with the exact zeta,
    M = 1 (zeta(2) = 1.64...) up to 60, at r = 0.5, 1 and 7."""
    for M in range(1, 61):
        for lr in (math.log(0.5), 0.0, math.log(7)):
            with mpmath.workdps(30):
                exact = (mpmath.log(2 * mpmath.zeta(2 * M)) + mpmath.loggamma(2 * M + 1)
                         - 2 * M * (mpmath.log(2 * mpmath.pi) + lr))
            # (a float64 bound: up to its own rounding)
            slack = 1e-13 * max(1.0, abs(float(exact)))
            assert em_remainder_factor(M, lr) >= float(exact) - slack, (M, lr)


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
        assert len(sq) == 7  # coefficients 0..order
        assert all(abs(v - ctx.mpf(2) ** n / ctx.factorial(n)) < ctx.mpf(10) ** -27
                   for n, v in enumerate(sq))
    assert mpmath.mp.dps == 15


def test_series_product_of_short_series_keeps_every_coefficient() -> None:
    ctx = mp()
    with ctx.workdps(20):
        one_plus_t = [ctx.mpf(1), ctx.mpf(1)]
        assert series_mul(ctx, one_plus_t, one_plus_t, 3) == [1, 2, 1, 0]  # (1 + t)**2
        assert series_mul(ctx, [ctx.mpf(2)], [ctx.mpf(3), ctx.mpf(5)], 2) == [6, 10, 0]
