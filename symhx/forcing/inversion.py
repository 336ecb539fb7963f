r"""Sums of many Rayleigh amplitudes (eq. 22) by inversion of their Laplace transform.

A Rayleigh amplitude of scale ``s`` has the transform (moment generating function)

.. math::

    M_s(\theta) = E\,e^{\theta R} = L(-\theta s/\sqrt2), \qquad
    L(z) = 1 - \sqrt\pi\, z\, e^{z^2}\operatorname{erfc} z = \int_0^\infty 2t\,e^{-t^2-2zt}\,dt,

an entire function, and a sum ``S`` of independent amplitudes has ``M(theta) = prod_j
M_{s_j}(theta)`` and cumulant function ``K = log M``. With ``c`` on the real axis,

.. math::

    P(S > x) = \frac{1}{2\pi i}\int_{c>0} \frac{e^{K(\theta)-\theta x}}{\theta}\,d\theta, \quad
    P(S \le x) = \frac{-1}{2\pi i}\int_{c<0} \frac{e^{K(\theta)-\theta x}}{\theta}\,d\theta, \quad
    f_S(x) = \frac{1}{2\pi i}\int e^{K(\theta)-\theta x}\,d\theta .

The contour passes vertically through the saddle point ``c`` of the integrand on the real axis
(``K'(c) = x + 1/c`` for a tail, ``K'(c) = x`` for the density), so that the integrand there is
of the size of the result (both tails keep their relative accuracy), and bends into the sector
``45 deg < arg(theta) < 90 deg``, ``theta(y) = c + k (sqrt(y**2 + w**2) - w) + i y``, where
``e^{-theta x}`` decays exponentially and the Gaussian factor of ``M`` decays too. The integral
over ``y`` is the trapezoidal rule, which converges geometrically for such analytic integrands:
its step is set from the Chernoff bound of the aliasing (the rule with step ``h`` adds the
tilted tail at distance ``2 pi/h``), the sum is cut where the terms are negligible, and the
error estimate is the difference between the steps ``h`` and ``h/2`` plus the rounding of the
terms and of the normalising exponent ``E0 = K(c) - c x - log|c|`` (``P = e^{E0} T``, with
``T`` of order one). A scale far below ``x`` contributes ``log M ~ theta s sqrt(pi/2)``: any
spread of the scales is evaluated as it is, without grouping or dropping.

``L`` is evaluated without cancellation: by Taylor series on a table of centres (``|z| < 7``;
24 terms at ``|z - z0| <= 0.36``, the coefficients from the differential equation ``z L' =
(1 + 2 z**2) L - 1`` started at Arb values of ``L(z0)``) and by its asymptotic series
``L = sum_k (-1)**(k+1) (2k-1)!!/(2 z**2)**k`` beyond; for ``Re theta > 0`` through ``M =
L(zeta) + 2 sqrt(pi) zeta e^{zeta**2}`` (``zeta = theta s/sqrt 2``), whose Gaussian part
``theta**2 V/2`` (``V = sum s**2``) is combined analytically with ``-theta x``.

Two implementations: float64 (numpy, vectorised over thresholds and contour nodes in chunks)
and Arb (python-flint ``acb`` balls for the ``dps`` path, through :func:`symhx.certify.
arb_prec`; the balls bound the rounding, the step comparison the quadrature).
"""

from __future__ import annotations

import math
import threading
from collections.abc import Sequence
from typing import Any, NamedTuple

import numpy as np
from mpmath import libmp as mpmath_libmp
from scipy import special as sc

__all__ = [
    "ALIAS_EXPONENT",
    "Inversion",
    "invert_float",
    "log_laplace_float",
]

SQRT_PI = math.sqrt(math.pi)
_LOG2 = math.log(2.0)
_LOG_2SQRTPI = math.log(2.0 * SQRT_PI)
_EPS = float(np.finfo(float).eps)

# =========================================================================== L(z), float64
#: beyond this modulus ``L`` is its asymptotic series (at most 28 terms for 1e-17)
_ASYM_R = 7.0
_ASYM_TERMS = 30
#: coefficients ``(-1)**k (2k+1)!!`` of ``2 z**2 L(z) = sum_k c_k (2 z**2)**-k``
_ASYM_C = np.array([(-1.0) ** k * math.prod(range(1, 2 * k + 2, 2)) for k in range(_ASYM_TERMS)])
#: the Taylor table: centres ``((i + 1/2) d, (j + 1/2) d - R)`` on ``[0, R] x [-R, R]``
_TAB_D = 0.5
_TAB_R = 7.5
_TAB_NRE = round(_TAB_R / _TAB_D)
_TAB_NIM = round(2 * _TAB_R / _TAB_D)
_TAB_TERMS = 24
_table: np.ndarray | None = None
_table_lock = threading.Lock()


def _build_table() -> np.ndarray:
    """Taylor coefficients of ``L`` at every centre of the table (Arb at 200 bits: the
    recurrence from ``z L' = (1 + 2z**2) L - 1`` in balls, rounded to complex doubles)."""
    from flint import acb, arb

    from symhx.certify import arb_prec

    out = np.empty((_TAB_NRE, _TAB_NIM, _TAB_TERMS), dtype=complex)
    with arb_prec(200):
        sqrt_pi = arb.pi().sqrt()
        for i in range(_TAB_NRE):
            for j in range(_TAB_NIM):
                z0 = acb(arb((i + 0.5) * _TAB_D), arb((j + 0.5) * _TAB_D - _TAB_R))
                a = [1 - sqrt_pi * z0 * (z0 * z0).exp() * z0.erfc()]
                one_plus = 1 + 2 * z0 * z0
                for n in range(_TAB_TERMS - 1):
                    nxt = (one_plus - n) * a[n]
                    if n >= 1:
                        nxt += 4 * z0 * a[n - 1]
                    if n >= 2:
                        nxt += 2 * a[n - 2]
                    if n == 0:
                        nxt -= 1
                    a.append(nxt / ((n + 1) * z0))
                out[i, j, :] = [complex(float(v.real.mid()), float(v.imag.mid())) for v in a]
    return out


def _taylor_table() -> np.ndarray:
    global _table
    tab = _table
    if tab is None:
        with _table_lock:
            if _table is None:
                _table = _build_table()
            tab = _table
    return tab


def _laplace_parts(z: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """``(L, big)`` for complex ``z`` with ``Re z >= 0``: ``L(z)`` itself where ``|z| < 7``
    (Taylor table) and, where ``big``, the sum ``S`` of the asymptotic series, ``L = S/(2
    z**2)`` (not formed: it underflows for ``|z| > 1e154``)."""
    out = np.empty(z.shape, dtype=complex)
    big = np.abs(z) >= _ASYM_R
    ib = np.flatnonzero(big)
    if ib.size:
        zb = z.reshape(-1)[ib]
        with np.errstate(under="ignore", over="ignore"):
            q = (0.5 / zb) / zb   # |q| <= 0.0102 (0 beyond |z| ~ 1e154, never nan)
            acc = np.full(zb.shape, complex(_ASYM_C[-1]))
            for cf in _ASYM_C[-2::-1]:
                acc *= q
                acc += cf
        out.reshape(-1)[ib] = acc
    isml = np.flatnonzero(~big)
    if isml.size:
        zs = z.reshape(-1)[isml]
        tab = _taylor_table()
        i = np.clip(np.floor(zs.real * (1 / _TAB_D)).astype(np.int64), 0, _TAB_NRE - 1)
        j = np.clip(np.floor((zs.imag + _TAB_R) * (1 / _TAB_D)).astype(np.int64), 0, _TAB_NIM - 1)
        w = zs - ((i + 0.5) * _TAB_D + 1j * ((j + 0.5) * _TAB_D - _TAB_R))
        coef = tab.reshape(-1, _TAB_TERMS)[i * _TAB_NIM + j]
        acc = coef[:, -1].copy()
        for k in range(_TAB_TERMS - 2, -1, -1):
            acc *= w
            acc += coef[:, k]
        out.reshape(-1)[isml] = acc
    return out, big


def log_laplace_float(z: np.ndarray) -> np.ndarray:
    """``log L(z)`` for complex ``z`` with ``Re z >= 0`` (``L = E e^{-sqrt 2 z R/s}`` of a
    Rayleigh amplitude of scale ``s``), relative accuracy of ``L`` a few ulps everywhere."""
    z = np.asarray(z, dtype=complex)
    val, big = _laplace_parts(z)
    out = np.log(val)
    if big.any():
        out[big] -= _LOG2 + 2.0 * np.log(z[big])
    return out


def _log_mgf(theta: np.ndarray, scales: np.ndarray, mult: np.ndarray
             ) -> tuple[np.ndarray, np.ndarray]:
    """``(explicit, rest)`` with ``K(theta) = sum_j m_j log M_{s_j}(theta) = [explicit]
    theta**2 V/2 + rest``: ``explicit`` where ``|arg theta| < 45 deg`` (there every scale's
    Gaussian part ``zeta**2`` is taken out, to be combined analytically with ``-theta x``).
    ``theta`` complex of any shape; the scales are evaluated together (last axis)."""
    theta = np.asarray(theta, dtype=complex)
    shape = theta.shape
    flat = theta.reshape(-1)
    re, im = flat.real, flat.imag
    explicit = (re > 0) & (np.abs(im) < re)
    left = re <= 0
    rest = np.empty(flat.shape, dtype=complex)
    mult = np.asarray(mult, dtype=float)
    unit = np.asarray(scales, dtype=float) / math.sqrt(2.0)
    with np.errstate(under="ignore", over="ignore", divide="ignore", invalid="ignore"):
        rows = np.flatnonzero(left)
        if rows.size:   # M = L(-zeta)
            rest[rows] = np.sum(log_laplace_float(-flat[rows, None] * unit) * mult, axis=-1)
        for rows, expl in ((np.flatnonzero(explicit), True),
                           (np.flatnonzero(~left & ~explicit), False)):
            if not rows.size:
                continue
            zeta = flat[rows, None] * unit
            val, big = _laplace_parts(zeta)
            # M = L(zeta) + 2 sqrt(pi) zeta e^{zeta**2}, L = S/(2 zeta**2) where big
            gauss = zeta * zeta
            lval = np.where(big, val * (0.5 / gauss), val)
            if expl:   # log M - zeta**2 = log(2 sqrt(pi) zeta + L e^{-zeta**2}), |e^..| < 1
                v = np.log(lval * np.exp(-gauss) + (2.0 * SQRT_PI) * zeta)
            else:      # |e^{zeta**2}| <= 1
                v = np.log(lval + (2.0 * SQRT_PI) * zeta * np.exp(gauss))
            huge = np.abs(zeta) > 1e100
            if huge.any():
                # zeta**2 may overflow: on the contour there the Gaussian term is negligible
                # (Re zeta**2 < -|zeta|**2/2 beyond 63 deg) or, in the explicit sector, L is
                v[huge] = (_LOG_2SQRTPI + np.log(zeta[huge])) if expl else \
                    log_laplace_float(zeta[huge])
            rest[rows] = np.sum(v * mult, axis=-1)
    return explicit.reshape(shape), rest.reshape(shape)


def _branch_values(theta: np.ndarray, unit: np.ndarray
                   ) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
    """Per element (``theta[..., None] * unit``): the branch of ``theta`` (0: ``Re theta <=
    0``, 1: ``|arg theta| < 45 deg``, 2: between), the argument ``z`` of ``L`` in the right
    half-plane, ``Q`` and ``big``. ``Q`` is ``L(-zeta)`` on branch 0 (``L = Q/(2 z**2)`` where
    ``big``: the asymptotic series' sum, not the underflowing ``L``), ``2 sqrt(pi) zeta + L(zeta)
    e^{-zeta**2}`` on branch 1 (``M e^{-zeta**2}``) and ``M = L(zeta) + 2 sqrt(pi) zeta
    e^{zeta**2}`` on branch 2 (``big`` False there)."""
    re, im = theta.real, theta.imag
    branch = np.where(re <= 0, 0, np.where(np.abs(im) < re, 1, 2))[..., None]
    zeta = theta[..., None] * unit
    z = np.where(branch == 0, -zeta, zeta)
    val, big = _laplace_parts(z)
    with np.errstate(under="ignore", over="ignore", invalid="ignore", divide="ignore"):
        right = branch > 0
        if right.any():
            gauss = zeta * zeta
            lval = np.where(big, val * (0.5 / gauss), val)
            q1 = lval * np.exp(-gauss) + (2.0 * SQRT_PI) * zeta
            q2 = lval + (2.0 * SQRT_PI) * zeta * np.exp(gauss)
            huge = np.abs(zeta) > 1e100
            # zeta**2 may overflow: on the contour the Gaussian term is negligible there
            # (Re zeta**2 < -|zeta|**2/2 beyond 63 deg) or, in the explicit sector, L is
            q1 = np.where(huge, (2.0 * SQRT_PI) * zeta, q1)
            q2 = np.where(huge, lval, q2)
            val = np.where(branch == 1, q1, np.where(branch == 2, q2, val))
            big = big & (branch == 0)
    return branch, z, val, big


def _log_q(z: np.ndarray, val: np.ndarray, big: np.ndarray) -> np.ndarray:
    """``log`` of a branch value (``-log(2 z**2)`` added where ``big``)."""
    with np.errstate(divide="ignore", invalid="ignore"):
        out = np.log(val)
        return np.where(big, out - _LOG2 - 2.0 * np.log(z), out)


def _rel_log_mgf(theta: np.ndarray, c: np.ndarray, scales: np.ndarray, mult: np.ndarray
                 ) -> tuple[np.ndarray, np.ndarray]:
    """``(explicit, rel)``: ``K(theta) - K(c) = [explicit] theta**2 V/2 - [c > 0] c**2 V/2 +
    rel`` for ``theta`` of shape (rows, nodes) and the saddles ``c`` (rows): every scale's term
    is the ``log`` of the ratio of its values at ``theta`` and at ``c`` where both lie on the
    same branch (the ratio is of order one near the saddle, so its log keeps the absolute
    accuracy that the difference of two large logs would lose), else the difference."""
    unit = np.asarray(scales, dtype=float) / math.sqrt(2.0)
    mult = np.asarray(mult, dtype=float)
    bt, zt, vt, gt = _branch_values(theta, unit)
    bc, zc, vc, gc = _branch_values(c.astype(complex)[:, None], unit)   # (rows, 1, M)
    with np.errstate(under="ignore", over="ignore", invalid="ignore", divide="ignore"):
        same = bt == bc
        ratio = vt / vc
        # on branch 0 with the asymptotic form: L_t/L_c = (S_t/S_c) (z_c/z_t)**2
        ratio = np.where(gt & gc, ratio * (zc / zt) ** 2,
                         np.where(gt & ~gc, ratio * (0.5 / (zt * zt)),
                                  np.where(~gt & gc, ratio * (2.0 * zc * zc), ratio)))
        rel = np.where(same, np.log(ratio), _log_q(zt, vt, gt) - _log_q(zc, vc, gc))
    return bt[..., 0] == 1, np.sum(rel * mult, axis=-1)


# =========================================================================== the real axis
def _unit_laplace_real(z: np.ndarray) -> np.ndarray:
    """``L(z)`` for real ``z >= 0`` (to ~1e-13 relative: the planning accuracy)."""
    out = np.empty(z.shape)
    far = z >= _ASYM_R
    near = ~far
    if near.any():
        zn = z[near]
        out[near] = 1.0 - SQRT_PI * zn * sc.erfcx(zn)
    if far.any():
        zf = z[far]
        with np.errstate(under="ignore"):
            q = (0.5 / zf) / zf
            acc = np.full(zf.shape, _ASYM_C[-1])
            for cf in _ASYM_C[-2::-1]:
                acc = acc * q + cf
            out[far] = q * acc
    return out


def _unit_logm_real(tau: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """``(gauss, rest)``: ``log M_1(tau) = gauss + rest`` for one amplitude of scale 1 and real
    ``tau``, ``gauss = tau**2/2`` for ``tau > 0`` (else 0)."""
    pos = tau > 0
    a = np.abs(tau) / math.sqrt(2.0)
    lz = _unit_laplace_real(a)
    with np.errstate(under="ignore", over="ignore", divide="ignore", invalid="ignore"):
        rest_pos = np.log(2.0 * SQRT_PI * a + lz * np.exp(-a * a))
        # far out L ~ 1/(2 a**2) underflows: its log from the logs of the factors
        rest_neg = np.where(a < 1e100, np.log(lz), -_LOG2 - 2.0 * np.log(a))
    return np.where(pos, a * a, 0.0), np.where(pos, rest_pos, rest_neg)


def _unit_kprime(tau: np.ndarray, gaussian: bool = True) -> np.ndarray:
    """``d/dtau log M_1(tau)`` (the tilted mean of one amplitude of scale 1), real ``tau``,
    to ~1e-10 relative (enough to place the contour); without its Gaussian part ``tau`` (for
    ``tau > 0``) if not ``gaussian``."""
    out = np.empty(tau.shape)
    a = np.abs(tau) / math.sqrt(2.0)
    pos = tau > 1e-6
    neg = tau < -1e-6
    mid = ~(pos | neg)
    # E R + tau Var R (the Gaussian part tau of Var R = 2 - pi/2 taken out if asked)
    out[mid] = math.sqrt(math.pi / 2) + tau[mid] * ((2 - math.pi / 2) - (0.0 if gaussian else
                                                                            (tau[mid] > 0)))
    if pos.any():   # (1 - 1/M)/tau + tau
        t, ap = tau[pos], a[pos]
        lz = _unit_laplace_real(ap)
        with np.errstate(under="ignore", over="ignore"):
            inv_m = np.exp(-(ap * ap + np.log(2.0 * SQRT_PI * ap + lz * np.exp(-ap * ap))))
        out[pos] = (1.0 - inv_m) / t + (t if gaussian else 0.0)
    if neg.any():   # sqrt 2 K2(z), K2 = (1 - L (1 + 2 z**2))/(2 z L) (or its series far out)
        z = a[neg]
        k2 = np.empty(z.shape)
        far = z >= 60.0
        if far.any():   # K2 = -(log L)'/2 from log S = -3q + 21q**2/2 - 69q**3, q = 1/(2z**2)
            zf = z[far]
            with np.errstate(under="ignore"):
                r = 1.0 / (zf * zf)
                k2[far] = (1.0 + r * (-1.5 + r * (5.25 - 25.875 * r))) / zf
        near = ~far
        if near.any():
            zn = z[near]
            ln = _unit_laplace_real(zn)
            k2[near] = (1.0 - ln * (1.0 + 2.0 * zn * zn)) / (2.0 * zn * ln)
        out[neg] = math.sqrt(2.0) * k2
    return out


def _kprime(theta: np.ndarray, scales: np.ndarray, mult: np.ndarray) -> np.ndarray:
    """``K'(theta)`` of the sum (real ``theta`` of any shape)."""
    tau = theta[..., None] * scales
    return np.sum(_unit_kprime(tau) * (mult * scales), axis=-1)


def _kprime_rest(theta: np.ndarray, scales: np.ndarray, mult: np.ndarray) -> np.ndarray:
    """``K'(theta)`` without its Gaussian part ``theta V`` (for ``theta > 0``)."""
    tau = theta[..., None] * scales
    return np.sum(_unit_kprime(tau, gaussian=False) * (mult * scales), axis=-1)


def _krest_diff(theta: np.ndarray, c: np.ndarray, scales: np.ndarray, mult: np.ndarray
                ) -> np.ndarray:
    """``R(theta) - R(c)``: ``K = [theta > 0] theta**2 V/2 + R`` (real arguments)."""
    r1 = _unit_logm_real(theta[..., None] * scales)[1]
    r0 = _unit_logm_real(c[..., None] * scales)[1]
    return np.sum((r1 - r0) * mult, axis=-1)


# =========================================================================== the plan
#: ``-log`` of the relative size of the aliased tilted tails that the coarse step allows (the
#: fine step's are far smaller: the estimate is the difference of the two)
ALIAS_EXPONENT = 41.0
#: slope of the bent contour's real part (its asymptotic angle is atan(1/k) = 63 deg)
_BEND = 0.5


class _Plan(NamedTuple):
    c: np.ndarray      # the saddle
    sig: np.ndarray    # sqrt of the curvature of the exponent at the saddle
    h: np.ndarray      # the fine step (the coarse one is 2h)
    w: np.ndarray      # where the contour bends


def _bisect(f: Any, lo: np.ndarray, hi: np.ndarray, n: int, geometric: bool) -> np.ndarray:
    """Root of the increasing ``f`` between ``lo`` (``f <= 0``) and ``hi`` (``f >= 0``)."""
    for _ in range(n):
        mid = np.sqrt(lo) * np.sqrt(hi) if geometric else 0.5 * (lo + hi)
        up = f(mid) > 0
        hi = np.where(up, mid, hi)
        lo = np.where(up, lo, mid)
    return np.sqrt(lo) * np.sqrt(hi) if geometric else 0.5 * (lo + hi)


def _saddle(x: np.ndarray, scales: np.ndarray, mult: np.ndarray, kind: str,
            var: float, n: int) -> np.ndarray:
    """The saddle ``c`` on the real axis: ``K'(c) = x + 1/c`` (tails), ``K'(c) = x`` (density)."""
    if kind == "sf":   # c > 0; K'(c) >= c V bounds it above, 1/(K'(hi) - x) below
        hi = (x + np.sqrt(x * x + 4.0 * var)) / (2.0 * var)
        lo = np.minimum(1.0 / np.maximum(_kprime(hi, scales, mult) - x, 1e-300), hi)
        return _bisect(lambda t: _kprime(t, scales, mult) - x - 1.0 / t, lo, hi, 32, True)
    if kind == "cdf":  # c < 0, |c| in [1/x, (2n + 1)/x] (K' <= 2n/|c| for c < 0)
        return -_bisect(lambda t: x - 1.0 / t - _kprime(-t, scales, mult), 1.0 / x,
                        (2 * n + 1.0) / x, 32, True)
    # the density: the mean splits the two signs of c
    mean = math.sqrt(math.pi / 2) * float(np.dot(mult, scales))
    out = np.empty_like(x)
    up = x >= mean
    if up.any():
        xu = x[up]
        hi = (xu + 1e-300) / var
        lo = np.full_like(xu, 1e-300)
        out[up] = _bisect(lambda t: _kprime(t, scales, mult) - xu, np.maximum(lo, hi * 1e-30),
                          hi, 40, True)
    if (~up).any():
        xl = x[~up]
        out[~up] = -_bisect(lambda t: xl - _kprime(-t, scales, mult), np.full_like(xl, 1e-300),
                            2.0 * n / xl, 40, True)
    return out


def _log_e0(c: np.ndarray, x: np.ndarray, scales: np.ndarray, mult: np.ndarray, var: float,
            tail: bool) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """``(E0, explicit, rest)``: ``E0 = K(c) - c x (- log|c|)`` without overflow (``-x**2/(2V)
    + V (c - x/V)**2/2 + rest`` where the Gaussian parts are explicit), and the parts of
    ``K(c)`` (:func:`_log_mgf`, accurate: the value's scale)."""
    ex, r0 = _log_mgf(c.astype(complex), scales, mult)
    rest = np.real(r0)
    with np.errstate(over="ignore"):
        gauss = np.where(ex, -(x / math.sqrt(2 * var)) ** 2 + (var / 2) * (c - x / var) ** 2,
                         -c * x)
    e0 = gauss + rest
    return (e0 - np.log(np.abs(c)) if tail else e0), ex, rest


def _scale_parts(c: np.ndarray, x: np.ndarray, scales: np.ndarray, mult: np.ndarray,
                 var: float, tail: bool) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """``e^{E0} = mant 2**exp2 e^{mod}`` accurately: ``prod_j Q_j(c)**m_j`` (the branch values
    of :func:`_branch_values`, ``L`` on the left, ``M e^{-zeta**2}`` on the right) as a mantissa
    and a binary exponent (no ``log`` of it: the sum of the logs would carry an absolute error
    ``eps sum |log Q_j|``), ``/|c|`` for a tail, and the exponent ``mod``: ``-c x`` on the left,
    ``-x**2/(2V) + V (c - x/V)**2/2`` on the right (its rounding, ``eps x**2/(2V)`` relative,
    is the condition ``kappa eps`` of the value itself)."""
    unit = np.asarray(scales, dtype=float) / math.sqrt(2.0)
    b, z, val, big = _branch_values(c.astype(complex)[:, None], unit)
    q = np.real(val[:, 0, :])
    zr = np.real(z[:, 0, :])
    big = big[:, 0, :]
    mant = np.ones(c.shape)
    exp2 = np.zeros(c.shape, dtype=np.int64)
    fq, eq = np.frexp(q)
    # where big, L = S / (2 z**2): the factor 2**-1 z**-2 as mantissa and exponent too
    fz, ez = np.frexp(np.where(big, zr, 1.0))
    eq = np.where(big, eq - 1 - 2 * ez, eq)
    fq = np.where(big, fq / (fz * fz), fq)
    for j, m in enumerate(np.asarray(mult, dtype=float)):
        mi = int(m)
        mant = mant * fq[:, j] ** mi
        exp2 += mi * eq[:, j]
        mant, e = np.frexp(mant)
        exp2 += e
    if tail:
        fc, ec = np.frexp(np.abs(c))
        mant, e = np.frexp(mant / fc)
        exp2 += e - ec
    right = b[:, 0, 0] == 1
    with np.errstate(over="ignore"):
        a = (x * x) / (2.0 * var)
        mod = np.where(right, -a + (var / 2) * (c - x / var) ** 2, -c * x)
    return mant, exp2, mod


def _mod_estimate(c: np.ndarray, x: np.ndarray, var: float, kind: str) -> np.ndarray:
    """The exponent ``mod`` of :func:`_scale_parts` (its size sets the rounding of e^{mod})."""
    with np.errstate(over="ignore"):
        return np.where(c > 0, x * x / (2.0 * var), np.abs(c * x))


#: ln 2 in two parts (Cody and Waite): ``k _LN2_HI`` is exact for ``|k| < 2**21``
_LN2_HI = 0.6931471803691238
_LN2_LO = 1.9082149292705877e-10


def _scaled_value(t: np.ndarray, mant: np.ndarray, exp2: np.ndarray, mod: np.ndarray
                  ) -> np.ndarray:
    """``t mant 2**exp2 e^{mod}`` without spurious under/overflow of a factor: ``e^{mod} =
    2**k e^{r}``, ``r = mod - k ln 2`` formed exactly (Cody and Waite) for ``|mod| < 1e6``
    (beyond, the value is 0 or inf whatever the other factors: ``|exp2| < 2**17``)."""
    with np.errstate(under="ignore", over="ignore", invalid="ignore"):
        k = np.where(np.abs(mod) > 700.0, np.round(np.clip(mod, -1e6, 1e6) / _LOG2), 0.0)
        r = (mod - k * _LN2_HI) - k * _LN2_LO
        rest = np.exp(r) * (t * mant)
        total = np.clip(exp2 + k, -(1 << 21), 1 << 21).astype(np.int64)
        out = np.ldexp(rest, total)
        return np.where(mod < -1e6, 0.0, np.where(mod > 1e6, np.inf, out))


def _plan(x: np.ndarray, scales: np.ndarray, mult: np.ndarray, kind: str, var: float,
          alias: float) -> _Plan:
    """Saddle, curvature, step and bend of the contour of every threshold.

    The period ``2 pi/h_coarse`` of the trapezoidal rule's aliasing must exceed the distance
    at which the tilted distribution has decayed by ``exp(-alias)`` on both sides of ``x``. By
    Chernoff, ``D(t) = (theta - c) K'(theta) - (K(theta) - K(c))`` is that exponent at the
    distance ``|K'(theta) - x|`` (``theta = c +- t``). Towards a tail's pole (the body of the
    distribution) the integrand ``e^{c v} tail(x + v)`` decays at least like ``e^{-|c| |v|}``
    relative to ``1/tail(x)``; below ``x = 0`` nothing is aliased (the support).
    """
    n = int(np.sum(mult))
    c = _saddle(x, scales, mult, kind, var, n)
    dc = 1e-5 * np.maximum(np.abs(c), 1e-3 / math.sqrt(var))
    k2 = (_kprime(c + dc, scales, mult) - _kprime(c - dc, scales, mult)) / (2.0 * dc)
    if kind != "pdf":
        k2 = k2 + 1.0 / (c * c)
    sig = np.sqrt(np.maximum(k2, 1e-300))
    logtail = None
    span = np.zeros_like(x)
    for side in (1.0, -1.0):
        pole = (kind == "sf" and side < 0) or (kind == "cdf" and side > 0)
        tmax = 0.999 * np.abs(c) if pole else np.full_like(c, np.inf)
        t0 = math.sqrt(2.0 * alias) / sig   # the Gaussian guess
        lo = np.minimum(t0 * 1e-2, 0.5 * tmax)
        hi = np.minimum(t0 * 1e4, tmax)

        def dexp(t: np.ndarray, side: float = side) -> np.ndarray:
            # D = (theta - c) K'(theta) - (K(theta) - K(c)); its Gaussian parts combine to
            # t**2 V/2 where theta, c > 0 (their difference would cancel all digits far out)
            th = c + side * t
            with np.errstate(over="ignore", invalid="ignore", divide="ignore"):
                tp, cp = th > 0, c > 0
                dg = np.where(tp & cp, 0.5 * t * t * var,
                              side * t * np.where(tp, th, 0.0) * var
                              - (np.where(tp, th * th, 0.0) - np.where(cp, c * c, 0.0)) * var / 2)
                d = (dg + side * t * _kprime_rest(th, scales, mult)
                     - _krest_diff(th, c, scales, mult))
            return np.where(np.isfinite(d), d, np.inf) - alias

        t = _bisect(dexp, lo, hi, 12, True)
        dist = np.abs(_kprime(c + side * t, scales, mult) - x)
        if pole:
            if logtail is None:
                e0 = _log_e0(c, x, scales, mult, var, tail=True)[0]
                logtail = e0 - np.log(sig * math.sqrt(2.0 * math.pi))
            short = dexp(t) < -1.0   # the Chernoff exponent never reaches alias before 0
            dist = np.where(short, np.maximum(dist, (alias - logtail) / np.abs(c)), dist)
        if (kind == "pdf" and side < 0) or (kind == "cdf" and side < 0):
            dist = np.minimum(dist, x)   # nothing below 0
        span = np.maximum(span, dist)
    h = math.pi / np.maximum(span, 1e-300)   # the fine step: half of 2 pi/span
    # the contour bends beyond the shift pi/(h sig**2) at which the aliasing of the coarse
    # step is smallest (a branch point of the bend nearer than that would limit it)
    w = np.maximum(math.pi / (h * sig * sig), 2.0 / sig)
    return _Plan(c, sig, h, w)


# =========================================================================== the float integral
class Inversion(NamedTuple):
    """``value = exp(log_scale) * t`` (formed without the rounding of ``log_scale``), ``t > 0``
    of order one, ``err`` the error estimate of ``t`` (absolute in units of ``t``: the value's
    relative error is ``err / t``); ``log(value) = log_scale + log(t)``."""

    log_scale: np.ndarray
    t: np.ndarray
    err: np.ndarray
    value: np.ndarray


#: beyond ``E = x**2/(2V) = _FAR_E`` in the upper tail the float64 values are the saddle-point
#: limit (``P`` and the density underflow long before; ``log P`` to a relative ``1e-16``)
_FAR_E = 1e8
#: contour nodes per threshold evaluated at a time (the walk stops once they are negligible)
_BLOCK = 64
#: at most this many blocks per threshold and step (beyond: a large error estimate)
_MAX_BLOCKS = 400
#: complex values per temporary array (thresholds x nodes x distinct scales): the memory of a
#: call does not grow with the number of thresholds
_BUDGET = 1 << 17


def _contour_sums(x: np.ndarray, plan: _Plan, ex0: np.ndarray, r0: np.ndarray,
                  scales: np.ndarray, mult: np.ndarray, var: float, kind: str
                  ) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
    """Trapezoidal sums with the fine and the coarse step (``h``, ``2h``), the sum of the
    moduli of the terms (rounding) and a bound of the terms beyond the walk (truncation)."""
    c, _, h, w = plan
    m = x.shape[0]
    fine = np.full(m, 0.5)     # the node y = 0: F(c) theta'(0) = i, counted once
    coarse = np.full(m, 0.5)
    absum = np.full(m, 0.5)
    last = np.zeros(m)
    active = np.ones(m, dtype=bool)
    prev = np.full(m, np.inf)
    for b in range(_MAX_BLOCKS):
        idx = np.flatnonzero(active)
        if idx.size == 0:
            break
        j = np.arange(b * _BLOCK + (b == 0), (b + 1) * _BLOCK)
        ci, hi_, wi, xi = c[idx, None], h[idx, None], w[idx, None], x[idx, None]
        y = hi_ * j
        root = np.sqrt(y * y + wi * wi)
        theta = ci + _BEND * (root - wi) + 1j * y
        dth = _BEND * y / root + 1j
        expl, rel = _rel_log_mgf(theta, c[idx], scales, mult)
        delta = theta - ci
        e0x = ex0[idx, None]
        with np.errstate(over="ignore", invalid="ignore", under="ignore"):
            gauss = np.where(expl & e0x, delta * (ci * var - xi) + delta * delta * (var / 2),
                             -delta * xi + np.where(expl, theta * theta * (var / 2), 0.0)
                             - np.where(e0x, ci * ci * (var / 2), 0.0))
            f = np.exp(gauss + rel) * dth
            if kind != "pdf":
                f = f * (ci / theta)
        f = np.where(np.isfinite(f), f, 0.0)
        term = f.imag   # F(theta) theta' at y and -y: 2 i Im(F theta')
        fine[idx] += term.sum(axis=1)
        coarse[idx] += term[:, (j % 2) == 0].sum(axis=1)
        mag = np.abs(f)
        absum[idx] += mag.sum(axis=1)
        bmax = mag.max(axis=1)
        last[idx] = bmax
        done = (bmax < 1e-19 * np.abs(fine[idx])) & (bmax <= prev[idx])
        prev[idx] = bmax
        active[idx[done]] = False
    scale = h / math.pi   # T = (h/2 pi) [1 + 2 sum_{j>=1} Im(F_j theta'_j)]
    trunc = scale * last * np.where(active, 1e6, 10.0)
    return scale * fine, 2.0 * scale * coarse, scale * absum, trunc


def invert_float(scales: Sequence[float], x: np.ndarray, kind: str,
                 alias: float = ALIAS_EXPONENT) -> Inversion:
    """``P(S > x)`` (``kind="sf"``), ``P(S <= x)`` (``"cdf"``) or the density (``"pdf"``) of
    the sum of independent Rayleigh amplitudes of ``scales`` at thresholds ``x > 0`` (float64
    arrays), as ``exp(log_scale) * t`` with an error estimate of ``t``. Ask for the tail that
    is below about 1/2 (the other one is ``1 -`` it); any number and spread of scales."""
    sc_arr = np.asarray(scales, dtype=float)
    uniq, counts = np.unique(sc_arr, return_counts=True)
    mult = counts.astype(float)
    n = int(counts.sum())
    var = float(math.fsum(float(s) * float(s) for s in sc_arr))
    xa = np.asarray(x, dtype=float)
    flat = xa.reshape(-1)
    out = [np.empty(flat.shape) for _ in range(4)]
    chunk = max(1, _BUDGET // (_BLOCK * uniq.shape[0]))
    for lo in range(0, flat.shape[0], chunk):
        xc = flat[lo:lo + chunk]
        with np.errstate(under="ignore", over="ignore"):
            plan = _plan(xc, uniq, mult, kind, var, alias)
            e0, ex0, r0 = _log_e0(plan.c, xc, uniq, mult, var, tail=kind != "pdf")
            big_e = (xc / math.sqrt(2.0 * var)) ** 2
            # far in the upper tail (E >= _FAR_E) float64 cannot form the integrand's phase
            # (x theta has an absolute rounding error eps x/sigma >> 1 radian): the value is 0
            # there anyway, and log T the saddle-point term -log(sigma sqrt(2 pi)), whose
            # relative error O(1/E) is a relative O(1/E**2) of log P
            far = (plan.c > 0) & (big_e >= _FAR_E)
            tf = 1.0 / (plan.sig * math.sqrt(2.0 * math.pi))
            err = tf * (10.0 / np.maximum(big_e, 1.0))
            near = np.flatnonzero(~far)
            if near.size:
                sub = _Plan(*(a[near] for a in plan))
                xs = xc[near]
                for _ in range(4):   # halve the step where the two grids disagree
                    tn, tc, absum, trunc = _contour_sums(xs, sub, ex0[near], r0[near], uniq,
                                                         mult, var, kind)
                    # rounding: a term carries ~(4 + 2n) eps (the logs of the transforms, the
                    # exponential); E0 is a product of the n transforms and e^{mod} whose
                    # rounding is ~(n + |mod|) eps
                    mod_size = _mod_estimate(sub.c, xs, var, kind)
                    rnd = _EPS * ((4.0 + 2.0 * n) * absum
                                  + 2.0 * np.abs(tn) * (n + 1.0 + mod_size))
                    quad = np.abs(tn - tc)
                    bad = quad > np.maximum(1e-15 * np.abs(tn), rnd)
                    if not bad.any():
                        break
                    sub = sub._replace(h=np.where(bad, sub.h / 2, sub.h))
                tf[near] = tn
                err[near] = quad + trunc + rnd
            mant, exp2, mod = _scale_parts(plan.c, xc, uniq, mult, var, kind != "pdf")
            value = np.where(far, 0.0, _scaled_value(tf, mant, exp2, mod))
        sl = slice(lo, lo + xc.shape[0])
        out[0][sl], out[1][sl], out[2][sl], out[3][sl] = e0, tf, err, value
    return Inversion(*(o.reshape(xa.shape) for o in out))


# =========================================================================== Arb (dps)
class ArbInversion(NamedTuple):
    """``value = exp(log_scale) * t`` (mpf of the calling thread's context, ``t > 0``) and the
    relative error bound ``rel_err`` of ``t`` (quadrature estimate plus the balls' radii)."""

    log_scale: Any
    t: Any
    rel_err: float


def _plan_units(scales: Sequence[Any], x: Any) -> tuple[np.ndarray, float, Any]:
    from fractions import Fraction

    """Floats for the plan: ``(scales/u, x/u, u)`` with the unit ``u`` the largest scale, or
    ``x`` where ``x`` is below ``1e-100`` of it (then scales above ``1e100 x`` are clipped:
    their transforms are pure powers there, which only the integrand needs exactly). Ratios
    below float64 become 0 (no effect on the plan, which only places the contour; the
    integrand takes every scale exactly)."""
    top = max(scales)
    u = top if x >= top * Fraction(1, 10**100) else x
    cap = Fraction(10) ** 100
    ratio = [float(min(Fraction(s) / u, cap)) for s in scales]
    return np.array(ratio), float(min(Fraction(x) / u, Fraction(10) ** 300)), u


def _laplace_acb(z: Any, prec: int) -> Any:
    """``L(z)`` (``Re z >= 0``) as an acb ball at the current Arb precision: the asymptotic
    series with its truncation bound where ``|z|**2 > 0.7 prec + 20``, else ``1 - sqrt(pi) z
    e^{z**2} erfc(z)`` (the caller's precision covers the ``2 log2 |z|`` bits it cancels)."""
    from flint import acb, arb

    az = float(abs(z).mid())
    if az * az > 0.7 * prec + 20:
        q = 1 / (2 * z * z)
        term = q
        total = acb(0)
        k = 1
        aq = 1 / (2 * az * az)
        bound = aq
        while True:
            total += term
            nxt = (2 * k + 1) * aq * bound
            if nxt < 2.0 ** (-prec - 8) * aq or k > 4 * prec:
                break
            term = -term * (2 * k + 1) * q
            bound = nxt
            k += 1
        # the alternating-type asymptotic series: the error is below the first omitted term
        # (times a factor 2 for complex z in the right half-plane)
        err = arb(0, 2 * nxt)
        return total + acb(err, err)
    return 1 - arb.pi().sqrt() * z * (z * z).exp() * z.erfc()


def _log_mgf_acb(theta: Any, units: Sequence[tuple[Any, int]], prec: int) -> Any:
    """``K(theta) = sum_j m_j log M_{s_j}(theta)`` for one acb ``theta`` (``units``: pairs of
    ``s_j/sqrt 2`` as arb and the multiplicity)."""
    from flint import arb

    total = 0
    right = float(theta.real.mid()) > 0
    two_sqrt_pi = 2 * arb.pi().sqrt()
    for unit, m in units:
        zeta = theta * unit
        if not right:
            val = _laplace_acb(-zeta, prec).log()
        else:
            val = (_laplace_acb(zeta, prec) + two_sqrt_pi * zeta * (zeta * zeta).exp()).log()
        total += m * val
    return total


def invert_arb(scales: Sequence[Any], x: Any, kind: str, dps: int) -> ArbInversion:
    """:func:`invert_float` in Arb balls for ``dps`` digits at one threshold ``x > 0``;
    ``scales`` and ``x`` are exact Fractions (any magnitude). The results are mpf of this
    thread's context (:mod:`symhx._mpctx`) at the working precision: ``log_scale``, ``t`` and
    ``err`` (the quadrature's estimate plus the radii of the balls, in units of ``t``)."""
    from fractions import Fraction

    from flint import acb, arb, fmpz

    from symhx.certify import arb_prec

    def to_arb(fr: Fraction) -> Any:
        return arb(fmpz(fr.numerator)) / arb(fmpz(fr.denominator))

    alias = (dps + 6) * math.log(10.0)
    fscales = [Fraction(sv) for sv in scales]
    fx = Fraction(x)
    var_exact = sum(sv * sv for sv in fscales)
    # ln(x/sqrt V) beyond 230 (x/sqrt V > 1e100): the deep Gaussian regime, planned in closed
    # form (c = x/V is then within (n - 1)/x << 1/sqrt V of the saddle, the curvature is V)
    lnx = _ln_fraction(fx) - 0.5 * _ln_fraction(var_exact)
    if kind == "sf" and lnx > 230.0:
        u = fx / var_exact   # the plan in units where c = 1: sig = sqrt V c, x c = x**2/V
        sig_u = math.exp(0.5 * _ln_fraction(var_exact) + _ln_fraction(u))
        span = 2.0 * math.sqrt(2.0 * alias) * sig_u   # Chernoff of a Gaussian, both sides
        h_u = math.pi / span
        plan = _Plan(np.array([1.0]), np.array([sig_u]), np.array([h_u]),
                     np.array([max(math.pi / (h_u * sig_u * sig_u), 2.0 / sig_u)]))
        log2e = (2 * lnx - math.log(2.0)) / math.log(2.0)
        u = 1 / u   # lengths in units of 1/c: c = plan.c / u
    else:
        rat, xr, u = _plan_units(fscales, fx)
        uniq, counts = np.unique(rat, return_counts=True)
        var = float(np.dot(counts, uniq * uniq))
        xa1 = np.array([xr])
        plan = _plan(xa1, uniq, counts.astype(float), kind, var, alias)
        # |E0| (its exp needs log2 |E0| more bits): from the plan, in the unit u
        e0f = float(_log_e0(plan.c, xa1, uniq, counts.astype(float), var, kind != "pdf")[0][0])
        e0f = abs(e0f) + abs(_ln_fraction(u))
        log2e = math.log2(e0f) if e0f > 1 else 0.0
    bits = arb_work_bits(dps, log2e)
    exact: dict[Fraction, int] = {}
    for sv in scales:
        exact[Fraction(sv)] = exact.get(Fraction(sv), 0) + 1
    tail = kind != "pdf"
    with arb_prec(bits):
        uu = to_arb(Fraction(u))
        c = arb(float(plan.c[0])) / uu
        h = arb(float(plan.h[0])) / uu
        w = arb(float(plan.w[0])) / uu
        xa = to_arb(Fraction(x))
        sq2 = arb(2).sqrt()
        units = [(to_arb(sv) / sq2, m) for sv, m in exact.items()]
        k0 = _log_mgf_acb(acb(c), units, bits).real
        e0 = k0 - c * xa - (abs(c).log() if tail else 0)
        bend = arb(_BEND)

        def node(y: Any) -> Any:
            root = (y * y + w * w).sqrt()
            theta = acb(c + bend * (root - w), y)
            dth = acb(bend * y / root, 1)
            f = (_log_mgf_acb(theta, units, bits) - theta * xa - (k0 - c * xa)).exp() * dth
            if tail:
                f = f * c / theta
            return f.imag

        cut = 10.0 ** (-dps - 6)   # the terms beyond are negligible at dps digits
        for _ in range(6):   # halve the step while the two grids disagree
            fine, coarse = arb(0.5), arb(0.5)
            j, prev, small, mag = 1, math.inf, 0, 0.0
            while True:
                t = node(h * j)
                fine += t
                if j % 2 == 0:
                    coarse += t
                mag = float(abs(t).mid()) + float(t.rad())
                small = small + 1 if (mag < cut * float(abs(fine).mid()) and mag <= prev) else 0
                prev = mag
                if small >= 4 or j > _MAX_BLOCKS * _BLOCK:
                    break
                j += 1
            tf = fine * h / arb.pi()
            tc = coarse * 2 * h / arb.pi()
            # relative to T: the two steps' difference; the walk: its last terms onwards (T
            # carries the units of 1/theta: the ratios, not T itself, are floats)
            walk = (10 * h * arb(mag) / arb.pi() / abs(tf)) * (1e6 if small < 4 else 1)
            quad = float((abs(tf - tc) / abs(tf)).mid()) + float(walk.mid())
            if quad <= 10.0 ** (-dps - 3):
                break
            h = h / 2
        rel = quad + float((tf.rad() / abs(tf)).mid()) + float(e0.rad())
        return ArbInversion(_arb_to_mpf(e0), _arb_to_mpf(tf), rel)


def _arb_to_mpf(a: Any) -> Any:
    """The midpoint of an arb ball as an mpf of this thread's context (exact)."""
    from symhx._mpctx import mp

    man, exp = a.mid().man_exp()
    return mp().make_mpf(mpmath_libmp.from_man_exp(int(man), int(exp)))


def arb_work_bits(dps: int, log2_exponent: float) -> int:
    """Working bits of :func:`invert_arb` for ``dps`` digits of ``exp(E0) T`` with ``log2
    |E0|`` about ``log2_exponent``: the digits, the bits that ``exp`` of ``E0`` needs, and guard
    bits for the cancellation inside ``L`` and the sums."""
    return int(dps * 3.33) + 40 + max(0, int(log2_exponent) + 1)


def _ln_fraction(fr: Any) -> float:
    """``ln`` of a positive Fraction of any size (as a float)."""
    return math.log(fr.numerator) - math.log(fr.denominator)
