"""Tools for summing a long, smooth run of positive terms without visiting them: Gauss-Legendre
panels with an a-priori Bernstein-ellipse bound, and the Euler-Maclaurin endpoint corrections
with their Bernoulli weights.  Used by :mod:`symhx.simple_sums` (the simple-space distribution
at any N); nothing here knows about circuits.

Gauss-Legendre (Trefethen, *Approximation Theory and Approximation Practice*, thm. 19.3): if
``F`` is analytic in the Bernstein ellipse ``E_rho`` of ``[m - l, m + l]`` (foci ``m +/- l``,
semi-axes ``l (rho + 1/rho)/2`` and ``l (rho - 1/rho)/2``) with ``|F| <= M`` there, the
``n``-point rule errs by at most ``(64/15) l M rho**(-2n) / (rho**2 - 1)``
(:func:`gl_error_factor`).  Nodes and weights come from Arb (``arb.legendre_p_root``, through
:func:`symhx.certify.arb_prec`) and are cached as raw mantissa/exponent tuples, so every thread
turns them into numbers of its own mpmath context.

Euler-Maclaurin: ``sum_{k=A}^{B} F(k) = int_A^B F + (F(A) + F(B))/2
+ sum_{m=1}^{M} B_{2m}/(2m)! (F^{(2m-1)}(B) - F^{(2m-1)}(A)) + R_M`` with
``|R_M| <= 2 zeta(2M) (2 pi)**(-2M) int_A^B |F^{(2M)}|`` (:func:`em_remainder_factor` bounds
``(2M)! 2 zeta(2M) / (2 pi r)**(2M)``, the factor that multiplies ``max|F|`` on discs of radius
``r`` by Cauchy's estimate).  :func:`em_correction` takes the Taylor coefficients of ``F`` at an
endpoint.

>>> from symhx._mpctx import mp
>>> ctx = mp()
>>> with ctx.workdps(30):  # int_{-1}^{1} e**x dx with 8 nodes: the rule's own error
...     nodes = gauss_legendre(ctx, 8)
...     err = ctx.fsum(w * ctx.exp(x) for x, w in nodes) - (ctx.e - 1 / ctx.e)
>>> ctx.nstr(err, 3)
'-2.26e-18'
"""

from __future__ import annotations

import math
import threading
from typing import Any

from symhx.certify import arb_prec

__all__ = [
    "GL_SIZES",
    "em_correction",
    "em_remainder_factor",
    "exp_series",
    "gauss_legendre",
    "gauss_legendre_raw",
    "gl_error_factor",
    "series_mul",
]

#: the node counts a panel may use (each size's nodes are computed once per precision); a panel
#: that needs more is halved: the rule's cost grows like n**2 (n roots of a degree-n
#: polynomial), so two panels of 512 cost half one of 1024 to set up (a cold median at
#: N = 10**1000, dps 20: 1.9 s with 768- and 1024-node rules at 1827 bits, 1.1 s without) and
#: about the same to evaluate (measured: the moments at N = 10**6 ... 10**1000 within 4 %)
GL_SIZES = (8, 12, 16, 24, 32, 48, 64, 96, 128, 192, 256, 384, 512)

_NODES: dict[tuple[int, int], list[tuple[tuple, tuple]]] = {}
_LOCK = threading.Lock()


def gauss_legendre_raw(n: int, prec: int) -> list[tuple[tuple[int, int], tuple[int, int]]]:
    """``[((xm, xe), (wm, we))]``: the ``n``-point Gauss-Legendre rule on ``[-1, 1]``, node
    ``xm 2**xe`` and weight ``wm 2**we``, computed by Arb at ``prec + 32`` bits or a few more
    (cached per ``n`` and ``prec`` rounded up to a multiple of 128 bits: engines whose
    precisions differ by a few bits share one rule)."""
    prec = -(-prec // 128) * 128
    key = (n, prec)
    raw = _NODES.get(key)
    if raw is None:
        from flint import arb

        out = []
        with _LOCK, arb_prec(prec + 32):
            for k in range((n + 1) // 2):
                x, w = arb.legendre_p_root(n, k, weight=True)
                out.append((_raw(x.mid()), _raw(w.mid())))
        half = n // 2
        full = list(out)
        for (xm, xe), wr in reversed(out[:half]):
            full.append(((-xm, xe), wr))
        raw = _NODES[key] = full
    return raw


def gauss_legendre(ctx: Any, n: int) -> list[tuple[Any, Any]]:
    """``[(x_i, w_i)]`` of the ``n``-point Gauss-Legendre rule on ``[-1, 1]`` as numbers of
    ``ctx`` at its current precision (computed by Arb at ``ctx.prec + 32`` bits, cached)."""
    return [(ctx.ldexp(ctx.mpf(xm), xe), ctx.ldexp(ctx.mpf(wm), we))
            for (xm, xe), (wm, we) in gauss_legendre_raw(n, ctx.prec)]


def _raw(x: Any) -> tuple[int, int]:
    man, exp = x.man_exp()
    return int(man), int(exp)


def gl_error_factor(n: int, log_rho: float) -> float:
    """``log`` of ``(64/15) rho**(-2n) / (rho**2 - 1)`` (multiply by ``l M``)."""
    rho2 = math.exp(2 * log_rho)
    return math.log(64 / 15) - 2 * n * log_rho - math.log(rho2 - 1)


def em_remainder_factor(M: int, log_r: float) -> float:
    """``log`` of ``2 zeta(2M) (2M)! / (2 pi r)**(2M)`` (given ``log r``): times ``max|F|`` on
    discs of radius ``r`` around ``[A, B]`` and ``B - A``, this bounds the Euler-Maclaurin
    remainder ``R_M``."""
    # zeta(2M) <= 1 + 2**-2M + int_2^inf x**-2M dx = 1 + 2**-2M (1 + 2/(2M - 1)) for M >= 1
    # (1.75 >= zeta(2) = 1.645 at M = 1, where 1 + 2**(1-2M) = 1.5 is not a bound)
    zeta = 1 + 2.0 ** (-2 * M) * (1 + 2 / (2 * M - 1))
    return math.log(2 * zeta) + math.lgamma(2 * M + 1) - 2 * M * (math.log(2 * math.pi) + log_r)


def exp_series(ctx: Any, c: list[Any], order: int) -> list[Any]:
    """Taylor coefficients ``E_0..E_order`` of ``exp(sum_{n>=1} c[n] t**n)`` (``c[0]`` ignored):
    ``n E_n = sum_{k=1}^{n} k c_k E_{n-k}``."""
    E = [ctx.mpf(1)]
    for n in range(1, order + 1):
        s = ctx.mpf(0)
        for k in range(1, min(n, len(c) - 1) + 1):
            s += k * c[k] * E[n - k]
        E.append(s / n)
    return E


def series_mul(ctx: Any, a: list[Any], b: list[Any], order: int) -> list[Any]:
    """Product of two truncated Taylor series, coefficients ``0..order``."""
    out = []
    for n in range(order + 1):
        s = ctx.mpf(0)
        for k in range(max(0, n - len(b) + 1), min(n, len(a) - 1) + 1):
            s += a[k] * b[n - k]
        out.append(s)
    return out


def em_correction(ctx: Any, coef: list[Any], M: int) -> Any:
    """``sum_{m=1}^{M} B_{2m}/(2m)! F^{(2m-1)}(x0)`` from the Taylor coefficients ``coef`` of
    ``F`` at ``x0`` (``F^{(j)}(x0) = j! coef[j]``): ``sum_m B_{2m}/(2m) coef[2m-1]``."""
    s = ctx.mpf(0)
    for m in range(1, M + 1):
        j = 2 * m - 1
        if j >= len(coef):
            break
        s += ctx.bernoulli(2 * m) / (2 * m) * coef[j]
    return s
