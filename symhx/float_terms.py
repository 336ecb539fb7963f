"""float64 differences of ``log Phi_{N,p}(k)`` without cancellation, vectorised over ``k``.

``log Phi(k) = k log p + log N! - log (N-k)! - log k`` (eq. 7) is a difference of numbers of size
``N log N``: from ``gammaln`` it keeps only ``~1e-16 N log N`` absolute accuracy (1e-5 at
``N = 1e10``).  Relative to a reference ``c`` (the mode of the hump, or 1) the difference is
written in Loader's saddle-point form (C. Loader, *Fast and accurate computation of binomial
probabilities*, 2000), whose pieces are each as small as the result::

    log Phi(k) - log Phi(c) = (k - c) log(p x) - bd0(y, x) + log(y/x)/2
                              + delta(x) - delta(y) - log(k/c),
    x = N + 1 - c,  y = N + 1 - k,
    bd0(y, x) = y log(y/x) + x - y >= 0,
    delta(z) = log Gamma(z) - (z - 1/2) log z + z - log(2 pi)/2   (Stirling's remainder).

``log(p x)`` is a scalar the caller computes once with the digits it needs (near the hump
``p x ~ 1``).  ``bd0`` is summed as Loader's series in ``v = (x - y)/(x + y)`` when
``|v| < 0.1`` and as ``y log1p(-d/x) + d`` otherwise; ``delta`` is its asymptotic series for
``z >= 15`` and ``gammaln`` minus Stirling below.  The absolute error of the result is about
``1e-16 (1 + |k - c| |log(p x)| + |result|)``: relative accuracy ~1e-15 for the pmf in the bulk at
any N that fits a float.

>>> import numpy as np
>>> from math import lgamma, log
>>> N, p, c = 10**6, 2e-6, 500_000
>>> k = np.array([499_000, 500_000, 503_000])
>>> got = log_phi_diff(N, c, log(p * (N + 1 - c)), k)
>>> want = [(kk - c) * log(p) + lgamma(N + 1 - c) - lgamma(N + 1 - kk) - log(kk / c) for kk in k]
>>> bool(np.allclose(got, want, rtol=0, atol=1e-6))
True
"""

from __future__ import annotations

import math

import numpy as np

from symhx._numeric import stirling_coefficients

__all__ = ["bd0", "log_phi_diff", "log_phi_diff_real", "log_ratio", "stirling_remainder"]

_HALF_LOG_2PI = 0.5 * math.log(2 * math.pi)
#: 1/(12 z) - 1/(360 z^3) + ...: the first six coefficients B_{2m} / (2m (2m - 1)) as floats
_STIRLING = tuple(num / den for num, den in stirling_coefficients(6))
#: below this z the remainder is taken from gammaln (the series' next term is ~1e-17 at 15)
_SERIES_FROM = 15.0


def stirling_remainder(z: np.ndarray) -> np.ndarray:
    """``delta(z) = log Gamma(z) - (z - 1/2) log z + z - log(2 pi)/2`` for ``z >= 1`` (float64,
    elementwise): the asymptotic series for ``z >= 15``, ``gammaln`` minus Stirling below.

    >>> float(stirling_remainder(np.array([100.0]))[0])  # ~ 1/1200
    0.0008333305556...
    """
    from scipy.special import gammaln

    z = np.asarray(z, dtype=float)
    big = z >= _SERIES_FROM
    zb = np.where(big, z, _SERIES_FROM)
    with np.errstate(over="ignore"):
        inv2 = 1 / (zb * zb)  # 0 beyond 1e154: the series is then 1/(12 z)
    ser = np.zeros_like(zb)
    for coef in reversed(_STIRLING):
        ser = ser * inv2 + coef
    ser = ser / zb
    zs = np.where(big, 1.0, z)
    small = gammaln(zs) - (zs - 0.5) * np.log(zs) + zs - _HALF_LOG_2PI
    return np.where(big, ser, small)


def bd0(y: np.ndarray, x: np.ndarray, d: np.ndarray) -> np.ndarray:
    """``y log(y/x) + x - y`` (``>= 0``) with ``d = x - y`` given separately (exact when the
    caller has it in integers), to relative accuracy ~1e-15 (Loader's series near ``y = x``).

    >>> float(bd0(np.array([1.0]), np.array([2.0]), np.array([1.0]))[0]) == 1 - math.log(2)
    True
    """
    y = np.asarray(y, dtype=float)
    x = np.asarray(x, dtype=float)
    d = np.asarray(d, dtype=float)
    half = 0.5 * x + 0.5 * y  # (x + y)/2 without overflow at 1e308
    near = np.abs(d) < 0.2 * half
    v = np.where(near, -0.5 * d / np.where(near, half, 1.0), 0.0)  # (y - x)/(y + x)
    s = -d * v
    ej = y * (2 * v)  # (2 y) would overflow for y > 9e307
    v2 = v * v
    for j in range(1, 40):  # |v| < 0.1: 1e-16 after ~8 terms; stop when nothing moves
        ej = ej * v2
        nxt = s + ej / (2 * j + 1)
        if np.array_equal(nxt, s):
            break
        s = nxt
    return np.where(near, s, y * log_ratio(y, x, d) + d)


def log_ratio(y: np.ndarray, x: np.ndarray, d: np.ndarray) -> np.ndarray:
    """``log(y/x)`` with ``d = x - y``: ``log1p(-d/x)`` near 1, ``log`` of the rounded ratio
    away from it, the logs' difference where the ratio would be subnormal (elementwise).

    >>> float(log_ratio(np.array([1.0]), np.array([2.0]), np.array([1.0]))[0]) == math.log(0.5)
    True
    """
    with np.errstate(divide="ignore", invalid="ignore", under="ignore"):
        near = np.log1p(-np.where(np.abs(d) < 0.5 * x, d, 0.0) / x)
        ratio = y / x  # rounded once: log keeps 1e-16 absolute, unless it is subnormal
        far = np.where(ratio > 1e-300, np.log(np.where(ratio > 0, ratio, 1.0)),
                       np.log(y) - np.log(x))
        return np.where(np.abs(d) < 0.5 * x, near, far)


def log_phi_diff(N: int, c: int, log_px: float, k: np.ndarray) -> np.ndarray:
    """``log Phi_{N,p}(k) - log Phi_{N,p}(c)`` for integer ``1 <= k <= N`` (float64, vectorised
    over ``k``), given ``log_px = log(p (N + 1 - c))`` to float accuracy.

    Parameters
    ----------
    N : int
        Number of impacts (any size that fits a float64).
    c : int
        The reference, ``1 <= c <= N``.
    log_px : float
        ``log(p (N + 1 - c))``, computed by the caller with enough digits (it is small near the
        hump, where ``c`` is the mode).
    k : array of int
        The points, ``1 <= k <= N``.

    Returns
    -------
    numpy.ndarray
        The differences, absolute error ~``1e-16 (1 + |k - c| |log_px| + |result|)``.
    """
    kk = np.asarray(k)
    if N < 2**53:  # every k, N + 1 - k and k - c is exact in float64
        kf = kk.astype(float)
        d = kf - c
        y = (N + 1) - kf
    else:  # the differences in integers first (N + 1 - k can be 1 while N is 1e300)
        ints = [int(v) for v in kk.ravel()]
        kf = np.array([float(v) for v in ints]).reshape(kk.shape)
        d = np.array([float(v - c) for v in ints]).reshape(kk.shape)
        y = np.array([float(N + 1 - v) for v in ints]).reshape(kk.shape)
    return log_phi_diff_real(c, log_px, float(N + 1 - c), kf, d, y)


def log_phi_diff_real(c: int, log_px: float, x: float, k: np.ndarray, d: np.ndarray,
                      y: np.ndarray) -> np.ndarray:
    """``log Phi(k) - log Phi(c)`` at *real* ``1 <= k <= N`` (``Phi`` continued by Gamma
    functions, for quadrature), given ``k``, ``d = k - c`` and ``y = N + 1 - k`` each to float
    relative accuracy (the caller forms the differences without cancellation) and
    ``x = N + 1 - c``; the same formula and error as :func:`log_phi_diff`.

    >>> import numpy as np
    >>> from math import lgamma, log
    >>> N, p, c, k = 10**6, 2e-6, 500_000, 500_000.5
    >>> got = log_phi_diff_real(c, log(p * (N + 1 - c)), N + 1.0 - c, np.array([k]),
    ...                         np.array([k - c]), np.array([N + 1 - k]))
    >>> want = (k - c) * log(p) + lgamma(N + 1 - c) - lgamma(N + 1 - k) - log(k / c)
    >>> bool(abs(got[0] - want) < 1e-6)
    True
    """
    kf = np.asarray(k, dtype=float)
    d = np.asarray(d, dtype=float)
    y = np.asarray(y, dtype=float)
    xs = np.full_like(y, x)
    near = np.abs(d) < 0.5 * c  # log(k/c) = log1p(d/c): no rounding of log(k) ~ 700 at 1e300
    with np.errstate(divide="ignore", invalid="ignore"):
        log_kc = np.where(near, np.log1p(np.where(near, d, 0.0) / c),
                          np.log(kf) - math.log(c))
    out = d * log_px - bd0(y, xs, d) + 0.5 * log_ratio(y, xs, d) \
        + (stirling_remainder(np.array([x]))[0] - stirling_remainder(np.maximum(y, 1.0))) \
        - log_kc
    return np.where(d == 0, 0.0, out)
