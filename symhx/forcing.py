r"""Impact probability from the random forcing: eqs. (19)-(27) of the paper, computed stably.

Model (section 7). The gap between neighbouring pipes is ``d`` plus a free oscillation at the
natural frequency ``omega`` and forced oscillations at the forcing frequencies ``Omega_i``
(eq. 21). Its coefficients are independent normal variables, so the amplitude of each oscillation
is Rayleigh distributed, and an impact happens iff the sum of the amplitudes exceeds ``d``
(eq. 22)::

    p = P(R_0 + R_1 + ... + R_M > d),      R_i ~ Rayleigh(s_i) independent,

    s_0 = sqrt(2) * sigma_0,                 (free oscillation, density eq. 24)
    s_i = sqrt(2) * sigma_i / |omega**2 - Omega_i**2|   (forcing component i, density eq. 25).

A Rayleigh variable of scale ``s`` has density ``(r/s**2) exp(-r**2/(2 s**2))``; ``sigma_i`` is
the standard deviation of each coefficient ``alpha_{i,j}``, ``beta_{i,j}`` (and of the initial
condition coefficients for ``i = 0``), so the difference of two neighbours has variance
``2 sigma_i**2`` per coordinate.

One forcing component (the paper's eq. 27). With ``x = d**2/(2 s_0**2)``, ``y = d**2/(2 s_1**2)``,
``r = sqrt(x + y)``, ``u = x/r``, ``v = y/r`` (so ``u v = d**2/(2(s_0**2 + s_1**2))``,
``u + v = r``), the double integral (27) has the closed form

.. math::

    p = e^{-uv}\,\frac{v e^{-u^2} + u e^{-v^2} + \sqrt\pi\,uv\,(\operatorname{erf}u
        + \operatorname{erf}v)}{u + v},

a sum of positive terms, so ``p`` is accurate to a few ulps however small it is (the paper's
``1 - (double integral)`` loses every digit once ``p`` is below about ``1e-16``).
``1 - p`` uses its own form when ``p > 1/2``:

.. math::

    1 - p = uv\Bigl[\varphi_1(x) + \varphi_1(y)
        - \tfrac{2}{u+v}\bigl(u\chi(u^2) + v\chi(v^2)\bigr)\Bigr],

    \varphi_1(z) = \frac{1 - e^{-z}}{z} - 1,\quad
    \psi(z) = \frac{\sqrt\pi\,\operatorname{erf}\sqrt z}{2\sqrt z},\quad
    \chi(z) = e^{-uv}\psi(z) - 1,

where the ``O(1)`` parts cancel analytically; ``phi_1`` and ``psi - 1`` use their Taylor series
for small arguments, so ``1 - p ~ x y / 6 = d**4/(24 s_0**2 s_1**2)`` stays accurate for large
``sigma`` (down to and below the float range, via the log functions).

Several forcing components (eq. 22 with ``M >= 2``): the Rayleighs are grouped in pairs, each
pair having the closed-form density/tail above, and the pairs are convolved by nested composite
Gauss-Legendre quadrature of *positive* integrands (tail ``P(A + B > d) = P(B > d) +
int_0^d f_B(t) P(A > d - t) dt``; ``P(A + B <= d) = int_0^d f_B(t) P(A <= d - t) dt``), with
panels placed around the Gaussian saddle of the integrand, so both tails keep their relative
accuracy. The error estimate is the difference between two rule orders.

Extreme arguments (scales far from ``d`` or from each other, ratios up to the whole float
range): float64 carries ``sqrt(x)``, ``sqrt(y)`` as mantissa and exponent and uses the limits
``1 - p = x y G(y)`` (``x -> 0``) and ``p = e^{-uv} c (e^{-u^2} + sqrt(pi) u (1 + erf u))``
(``y -> inf``), exact to far below an ulp there; values beyond the float range round to 0,
1 or -inf, never NaN.

Conventions: ``sigma1=None`` means ``sigma_1 = sigma`` (the paper's ``sigma = sigma_0 =
sigma_1``); ``Omega=None`` means the paper's ``sqrt(2)``, used as ``Omega**2 = 2`` exactly at the
working precision. ``dps=None`` selects the float64 path (vectorised, broadcasting over every
argument); an integer ``dps`` selects the mpmath path, correct to ``dps`` significant digits.
"""

from __future__ import annotations

import itertools
import math
import numbers
from collections.abc import Callable, Sequence
from typing import Any, NamedTuple

import mpmath
import numpy as np
from scipy import special as sc

__all__ = [
    "RayleighSumResult",
    "TheoryCurve",
    "dp_dsigma",
    "impact_probability",
    "log_impact_probability",
    "log_no_impact_probability",
    "naive_impact_probability",
    "no_impact_probability",
    "rayleigh_scales",
    "rayleigh_sum_probability",
    "sigma_for_impact_probability",
    "theory_curve",
]

_SQRT_PI = math.sqrt(math.pi)
_SPLIT = 134217729.0  # 2**27 + 1, Dekker splitting constant
_MAX_DPS = 5000


# =========================================================================== input handling
def _check_dps(dps: Any) -> int:
    if isinstance(dps, bool) or not isinstance(dps, numbers.Integral):
        raise TypeError(f"dps must be an integer or None, got {type(dps).__name__}")
    dps = int(dps)
    if not 1 <= dps <= _MAX_DPS:
        raise ValueError(f"dps must be between 1 and {_MAX_DPS}, got {dps}")
    return dps


def _bad_index(arr: np.ndarray, bad: np.ndarray) -> str:
    if arr.ndim == 0:
        return ""
    idx = np.unravel_index(int(np.argmax(bad)), arr.shape)
    return f" at index {idx[0] if len(idx) == 1 else tuple(int(i) for i in idx)}"


def _float_arg(name: str, value: Any, *, positive: bool = True) -> np.ndarray:
    try:
        arr = np.asarray(value, dtype=np.float64)
    except (TypeError, ValueError):
        raise TypeError(f"{name} must be a real number or array of real numbers") from None
    bad = ~np.isfinite(arr)
    if bad.any():
        raise ValueError(f"{name} must be finite, got {float(arr[bad].flat[0])!r}"
                         f"{_bad_index(arr, bad)}")
    if positive:
        bad = ~(arr > 0)
        if bad.any():
            raise ValueError(f"{name} must be > 0, got {float(arr[bad].flat[0])!r}"
                             f"{_bad_index(arr, bad)}")
    return arr


def _mp_arg(name: str, value: Any) -> mpmath.mpf:
    """Convert a scalar to mpf at the current precision (floats exactly) and check ``> 0``."""
    if isinstance(value, bool):
        raise TypeError(f"{name} must be a real number, got bool")
    if isinstance(value, np.generic):
        value = value.item()
    try:
        x = mpmath.mpf(value)
    except (TypeError, ValueError):
        raise TypeError(f"{name} must be a real number, got {value!r}") from None
    if not mpmath.isfinite(x):
        raise ValueError(f"{name} must be finite, got {value!r}")
    if not x > 0:
        raise ValueError(f"{name} must be > 0, got {value!r}")
    return x


def _is_components(Omega: Any) -> bool:
    """A list/tuple ``Omega`` means several forcing components (eq. 22); arrays broadcast."""
    return isinstance(Omega, (list, tuple))


# =========================================================================== float64 core
def _delta_float(omega: np.ndarray, Omega: np.ndarray | None) -> np.ndarray:
    """``omega**2 - Omega**2`` with small relative error also close to resonance."""
    if Omega is None:  # Omega**2 = 2 exactly: omega**2 = hi + lo exactly (Dekker), then - 2
        c = _SPLIT * omega
        hi = c - (c - omega)
        lo = omega - hi
        sq = omega * omega
        err = ((hi * hi - sq) + 2.0 * hi * lo) + lo * lo
        delta = (sq - 2.0) + err
    else:
        delta = (omega - Omega) * (omega + Omega)
    bad = delta == 0
    if Omega is not None and np.any(bad):  # an underflowed product is no resonance
        bad = bad & (omega == Omega)
    if np.any(bad):
        raise ValueError(
            "Omega: resonance Omega == omega (infinite forced amplitude)"
            f"{_bad_index(np.asarray(delta), np.asarray(bad))}"
        )
    return delta


# Taylor coefficients of phi_1(z)/z = sum_{n>=1} (-z)^(n-1)/(n+1)! and of
# (psi(z) - 1)/z = sum_{n>=1} (-z)^(n-1)/(n! (2n+1)); 19-20 terms give < 1e-17 for z < 1
_PHI1_C = [(-1.0) ** n / math.factorial(n + 1) for n in range(1, 20)]
_PSI1_C = [(-1.0) ** n / (math.factorial(n) * (2 * n + 1)) for n in range(1, 21)]

#: truncation error allowed in the series: that of the full 19/20 terms at z = 1 (the worst
#: case of the full series, ~1e-19 relative to the O(1) values), so shorter sums for smaller z
#: are exactly as accurate
_SERIES_TOL = 1.0 / math.factorial(21)


def _series_zmax(coeffs: list[float]) -> list[float]:
    """``zmax[k]``: below it the first ``k`` terms are within ``_SERIES_TOL`` (k >= 1)."""
    out = [0.0]
    for k in range(1, len(coeffs)):
        out.append((_SERIES_TOL / abs(coeffs[k])) ** (1.0 / k))  # first omitted term c_k z^k
    out.append(math.inf)
    return out


_PHI1_ZMAX = _series_zmax(_PHI1_C)
_PSI1_ZMAX = _series_zmax(_PSI1_C)
#: Horner coefficient columns for ``h`` phi~ rows over ``h`` psi~ rows (phi~ padded with a
#: zero leading coefficient to the 20 terms of psi~)
_SERIES_COLS = {h: [np.array([[c1]] * h + [[c2]] * h)
                    for c1, c2 in zip([*_PHI1_C, 0.0], _PSI1_C, strict=True)]
                for h in (1, 2)}

#: float64 work is done in chunks of this many values, so that the ~50 temporaries stay in cache
_CHUNK = 16384


def _n_terms(zmax: float, table: list[float]) -> int:
    k = 1
    while zmax > table[k]:
        k += 1
    return k


def _phi1t_big(z: np.ndarray) -> np.ndarray:
    return -(np.expm1(-z) + z) / (z * z)


def _psi1t_big(z: np.ndarray) -> np.ndarray:
    sz = np.sqrt(z)
    return ((0.5 * _SQRT_PI) * sc.erf(sz) / sz - 1.0) / z


def _fix_rows(acc: np.ndarray, z: np.ndarray, big: np.ndarray, fn: Callable) -> None:
    """``acc[big] = fn(z[big])`` for C-contiguous row blocks (index arrays: no branchy masks)."""
    idx = np.flatnonzero(big)
    if idx.size:
        acc.reshape(-1).put(idx, fn(z.reshape(-1).take(idx)))


def _series_rows(z: np.ndarray) -> np.ndarray:
    """``phi~`` of the first half of the rows of ``z`` and ``psi~`` of the second half.

    ``phi~(z) = ((1 - exp(-z))/z - 1)/z`` (-> -1/2) and ``psi~(z) = (sqrt(pi) erf(sqrt z)/
    (2 sqrt z) - 1)/z`` (-> -1/3): Taylor series (Horner on all rows at once, as many terms as
    the largest ``z < 1`` needs for the error of the full series at ``z = 1``) below 1, closed
    forms (no cancellation) above.
    """
    h = z.shape[0] // 2
    small = z < 1.0
    zs = np.max(z, axis=1, where=small, initial=0.0)
    k = max(2, _n_terms(float(zs[:h].max()), _PHI1_ZMAX),
            _n_terms(float(zs[h:].max()), _PSI1_ZMAX))
    cols = _SERIES_COLS[h]
    acc = np.empty_like(z)
    acc[...] = cols[k - 1]
    for c in reversed(cols[: k - 1]):
        acc *= z
        acc += c
    if not small.all():
        big = ~small
        _fix_rows(acc[:h], z[:h], big[:h], _phi1t_big)
        _fix_rows(acc[h:], z[h:], big[h:], _psi1t_big)
    return acc


class _UV(NamedTuple):
    x: np.ndarray
    y: np.ndarray
    r: np.ndarray
    u: np.ndarray
    v: np.ndarray
    e: np.ndarray  # u*v = d**2 / (2 (s0**2 + s1**2))


def _uv_from_h(hx: np.ndarray, hy: np.ndarray) -> _UV:
    """x, y, r, u, v, uv from ``hx = sqrt(x)``, ``hy = sqrt(y)``."""
    with np.errstate(over="ignore", invalid="ignore"):
        r = np.hypot(hx, hy)
        u = hx * (hx / r)
        v = hy * (hy / r)
        m = hx * (hy / r)
        e = m * m
    return _UV(hx * hx, hy * hy, r, u, v, e)


def _uv_forcing(sig0, sig1, omega, Omega, d) -> _UV:
    """``x = d**2/(4 sigma0**2)``, ``y = d**2 Delta**2/(4 sigma1**2)`` (scales of eqs. 24-25).

    Arguments broadcast against each other; ``x`` and ``y`` may keep smaller shapes.
    """
    delta = np.abs(_delta_float(omega, Omega))
    with np.errstate(over="ignore", invalid="ignore", divide="ignore", under="ignore"):
        hx = d / (2.0 * sig0)
        hy = (d * delta) / (2.0 * sig1)
        x = hx * hx
        y = hy * hy
        # e = uv = d**2 / (4 (sigma0**2 + (sigma1/Delta)**2)): few roundings (~2 eps)
        t = sig1 / delta
        e = (d * d) / (4.0 * (sig0 * sig0 + t * t))
        r = np.sqrt(x + y)
        u = x / r
        v = y / r
    return _UV(x, y, r, u, v, e)


def _uv_chunk(sig0, sig1, delta, d, m: int) -> _UV:
    """:func:`_uv_forcing` on a chunk of ``m`` values from ``|Delta|`` (the same roundings);
    arguments are 1-D arrays of length ``m`` or scalars; the error state is the caller's."""
    hx = d / (2.0 * sig0)
    hy = (d * delta) / (2.0 * sig1)
    if np.ndim(hx) == 0:
        hx = np.full(m, hx)
    if np.ndim(hy) == 0:
        hy = np.full(m, hy)
    x = hx * hx
    y = hy * hy
    # e = uv = d**2 / (4 (sigma0**2 + (sigma1/Delta)**2)): few roundings (~2 eps)
    t = sig1 / delta
    t *= t
    t += sig0 * sig0
    t *= 4.0
    e = (d * d) / t
    if np.ndim(e) == 0:
        e = np.full(m, e)
    r = x + y
    np.sqrt(r, out=r)
    u = x / r
    v = y / r
    return _UV(x, y, r, u, v, e)


def _bracket_p(uv: _UV) -> np.ndarray:
    """``B/r`` with ``p = exp(-uv) B/r`` (all terms positive); shared pieces once if u == v."""
    u, v = uv.u, uv.v
    eu = u * u
    np.negative(eu, out=eu)
    np.exp(eu, out=eu)
    fu = sc.erf(u)
    if np.array_equal(u, v):  # e.g. sigma1 = sigma and |omega**2 - Omega**2| = 1 (the paper)
        ev, fv = eu, fu
    else:
        ev = v * v
        np.negative(ev, out=ev)
        np.exp(ev, out=ev)
        fv = sc.erf(v)
    b = v * eu
    ev = u * ev
    b += ev
    fu = fu + fv
    w = u * v
    w *= _SQRT_PI
    w *= fu
    b += w
    b /= uv.r
    return b


def _q_small_float(uv: _UV) -> np.ndarray:
    """``(1 - p)/(x y)`` by the cancellation-free form (digits lost <= ~1 for min(x, y) < 2).

    With ``a = u/r``, ``b = v/r`` (``a + b = 1``), ``phi~ = phi_1(z)/z``, ``psi~ = (psi(z)-1)/z``
    and ``em~ = expm1(-uv)/(uv)``: ``(1-p)/(xy) = a phi~(x) + b phi~(y) - 2(a chi~_u + b chi~_v)``,
    ``chi~_u = em~ a b psi(u^2) + a^2 psi~(u^2)``; every quantity is O(1), so nothing underflows
    for huge ``sigma``.
    """
    x, y, r, u, v, e = uv
    m = u.shape[0]
    ab2 = np.empty((2, m))  # rows a, b
    np.divide(u, r, out=ab2[0])
    np.divide(v, r, out=ab2[1])
    emt = np.negative(e)
    np.expm1(emt, out=emt)
    emt /= e
    if not e.min() > 1e-300:
        emt[~(e > 1e-300)] = -1.0
    if np.array_equal(x, y) and np.array_equal(u, v):  # equal scales (the paper): 2 rows
        z = np.empty((2, m))
        z[0] = x
        np.multiply(u, u, out=z[1])
        t = np.repeat(_series_rows(z), 2, axis=0)
        z = np.repeat(z, 2, axis=0)
    else:
        z = np.empty((4, m))
        z[0] = x
        z[1] = y
        np.multiply(u, u, out=z[2])
        np.multiply(v, v, out=z[3])
        t = _series_rows(z)
    emt *= ab2[0]
    emt *= ab2[1]  # em~ a b
    chi = z[2:] * t[2:]
    chi += 1.0
    chi *= emt
    sq = ab2 * ab2
    sq *= t[2:]
    chi += sq  # rows chi~_u, chi~_v
    chi *= ab2
    ph = ab2 * t[:2]
    res = ph[0] + ph[1]
    s = chi[0] + chi[1]
    s *= 2.0
    res -= s
    return res


#: below this min(x, y) the complement 1 - p uses its own form; above, p < 0.69 and 1 - p
#: loses at most ~1 bit
_Q_SWITCH = 2.0


def _pq_kernel(uv: _UV, want: str) -> np.ndarray:
    """p, q=1-p, log p or log q (``want`` in {'p','q','logp','logq'}) on 1-D arrays of one
    length (a chunk; error state handled by the caller). ``log p`` is ``log1p(-q)`` where the
    complement form is used (``p`` near 1), else ``log(B/r) - uv``."""
    if want == "p":  # p < 1 exactly; rounding can give 1 + ulp when p -> 1
        b = _bracket_p(uv)
        b *= np.exp(-uv.e)
        return np.minimum(b, 1.0, out=b)
    x, y = uv.x, uv.y
    comp = np.minimum(x, y) < _Q_SWITCH
    ncomp = int(np.count_nonzero(comp))
    if ncomp == comp.shape[0]:
        return _q_comp(uv, want)
    if ncomp == 0:
        return _q_direct(uv, want)
    # mixed chunk: gather/scatter by index arrays (boolean masks branch on every element)
    out = np.empty(comp.shape[0])
    idx = np.flatnonzero(comp)
    out.put(idx, _q_comp(_UV(*(a.take(idx) for a in uv)), want))
    idx = np.flatnonzero(~comp)
    out.put(idx, _q_direct(_UV(*(a.take(idx) for a in uv)), want))
    return out


def _q_comp(uv: _UV, want: str) -> np.ndarray:
    qs = _q_small_float(uv)
    if want == "logp":  # p > 0.13 and often ~ 1: log1p(-(1 - p)) keeps the relative accuracy
        qs *= uv.x
        qs *= uv.y
        np.negative(qs, out=qs)
        return np.log1p(qs, out=qs)
    if want == "q":
        xy = uv.x * uv.y
        qs *= xy
        return qs
    lq = np.log(uv.x)
    lq += np.log(uv.y)
    lq += np.log(qs, out=qs)
    return lq


def _q_direct(uv: _UV, want: str) -> np.ndarray:
    if want == "logp":
        b = _bracket_p(uv)
        np.log(b, out=b)
        b -= uv.e
        return np.minimum(b, 0.0, out=b)
    p = _bracket_p(uv)
    p *= np.exp(-uv.e)
    if want == "q":
        np.subtract(1.0, p, out=p)
        return p
    np.negative(p, out=p)
    return np.log1p(p, out=p)


def _pq_float(uv: _UV, want: str) -> np.ndarray:
    """Return p, q=1-p, log p or log q (``want`` in {'p','q','logp','logq'})."""
    shape = uv.u.shape
    if any(a.shape != shape for a in uv):
        uv = _UV(*np.broadcast_arrays(*uv))
    flat = _UV(*(np.ravel(a) for a in uv))
    n = flat.u.shape[0]
    out = np.empty(n)
    with np.errstate(all="ignore"):
        for i in range(0, n, _CHUNK):
            j = min(i + _CHUNK, n)
            out[i:j] = _pq_kernel(_UV(*(a[i:j] for a in flat)), want)
    return out.reshape(shape)


def _single_float(sigma, sigma1, omega, Omega, d, want: str) -> Any:
    sig0 = _float_arg("sigma", sigma)
    sig1 = None if sigma1 is None else _float_arg("sigma1", sigma1)
    om = _float_arg("omega", omega)
    Om = None if Omega is None else _float_arg("Omega", Omega)
    dd = _float_arg("d", d)
    with np.errstate(all="ignore"):  # (|Delta| may under/overflow: then _pq_extreme)
        delta = np.abs(_delta_float(om, Om))
        arrs = [sig0, delta, dd] + ([] if sig1 is None else [sig1])
        shape = np.broadcast_shapes(*(a.shape for a in arrs))
        n = math.prod(shape)
        # scalars stay scalars (np.float64: same IEEE semantics as the arrays), the rest is flat
        flat = [a.reshape(-1)[0] if a.size == 1 and n > 1 else np.ravel(np.broadcast_to(a, shape))
                for a in arrs]
        # d and |Delta| in [1e-100, 1e100], and per chunk r < 1e75, uv > 1e-150 (so that
        # 1e-75 < hx, hy < 1e75; NaN fails too) and d/(2r) >= 1e-145 (so sigma0, sigma1/Delta
        # >= 1e-145): then no intermediate of the fast path under/overflows, else _pq_extreme
        de, d_ = flat[1], flat[2]
        lims = ((1e-100 <= de.item() <= 1e100) if de.size == 1
                else (1e-100 <= de.min() and de.max() <= 1e100)) and (
            (1e-100 <= d_.item() <= 1e100) if d_.size == 1
            else (1e-100 <= d_.min() and d_.max() <= 1e100))
        out = np.empty(n)
        for i in range(0, n, _CHUNK):
            j = min(i + _CHUNK, n)
            s0, de, d_, *s1 = (a if a.ndim == 0 else a[i:j] for a in flat)
            s1 = s1[0] if s1 else s0
            uv = _uv_chunk(s0, s1, de, d_, j - i)
            r, e = uv.r, uv.e
            rmax = r.max() if j - i > 1 else r.item()
            if (lims and rmax < 1e75 and (e.min() if j - i > 1 else e.item()) > 1e-150
                    and (d_.item() if d_.size == 1 else d_.min()) >= 2e-145 * rmax):
                out[i:j] = _pq_kernel(uv, want)
                continue
            m = j - i
            ok = (r < 1e75) & (e > 1e-150) & (d_ >= 2e-145 * r)
            ok &= (d_ >= 1e-100) & (d_ <= 1e100) & (de >= 1e-100) & (de <= 1e100)
            ok = np.broadcast_to(ok, (m,))
            res = np.empty(m)
            idx = np.flatnonzero(ok)
            if idx.size:
                res.put(idx, _pq_kernel(_UV(*(a.take(idx) for a in uv)), want))
            idx = np.flatnonzero(~ok)
            full = [None if a is None else np.ravel(np.broadcast_to(a, shape))[i:j]
                    for a in (sig0, sig1 if sig1 is not None else sig0, om, Om, dd)]
            res.put(idx, _pq_extreme(*(None if a is None else a.take(idx) for a in full), want))
            out[i:j] = res
    return float(out[0]) if not shape else out.reshape(shape)


# ---- float64 outside the fast path's range (ratios of scales up to the whole float range)
_LN2 = math.log(2.0)
#: Taylor coefficients of G(z) = phi~(z) - 2 psi~(z) (G(0) = 1/6): z G(z) = (1 - p)/x in the
#: limit x -> 0 (one amplitude's scale infinitely larger than d)
_G_C = [a - 2.0 * b for a, b in zip([*_PHI1_C, 0.0], _PSI1_C, strict=True)]


def _frexp_div(num: list[np.ndarray], den: list[np.ndarray], shift: int):
    """``prod(num)/prod(den) * 2**shift`` as a mantissa in [0.5, 1) and an int exponent."""
    m = np.ones_like(num[0])
    ex = np.full(num[0].shape, shift, dtype=np.int64)
    for a in num:
        fa, ea = np.frexp(a)
        m = m * fa
        ex += ea
    for a in den:
        fa, ea = np.frexp(a)
        m = m / fa
        ex -= ea
    fm, em = np.frexp(m)
    return fm, ex + em


def _g_small_z(z: np.ndarray) -> np.ndarray:
    """``G(z) = phi~(z) - 2 psi~(z)`` (> 0): Taylor series below 1, closed form above."""
    out = np.full_like(z, _G_C[-1])
    for c in reversed(_G_C[:-1]):
        out *= z
        out += c
    big = z >= 1.0
    if big.any():
        zb = z[big]
        sz = np.sqrt(zb)
        out[big] = (1.0 - np.expm1(-zb) / zb - _SQRT_PI * sc.erf(sz) / sz) / zb
    return out


def _pq_extreme(s0, s1, om, Om, d, want: str) -> np.ndarray:
    """p, 1 - p or their logs where the fast path's intermediates would under/overflow.

    ``hx = sqrt(x)``, ``hy = sqrt(y)`` are carried as mantissa * 2**exponent. With ``s <= l``
    the smaller and larger of them: if both lie in [1e-75, 1e75] the fast formulas are used on
    ``hx, hy`` (``x, y`` in [1e-150, 1e150]); if ``l > 1e75`` (one scale negligible against
    ``d``), ``e^{-v^2} = 0``, ``erf v = 1`` and ``p = e^{-uv} c (e^{-u^2} + sqrt(pi) u (1 +
    erf u))`` with ``c = v/r = 1/(1 + (s/l)^2)``, ``1 - p = -expm1(-uv)`` where ``p > 1/2``
    (relative error ``O(1/l)``); otherwise ``s < 1e-75`` and ``1 - p = s^2 l^2 G(l^2)`` with
    relative error ``O(s^2)``.
    """
    with np.errstate(all="ignore"):
        if Om is None:
            small = om <= 1e100
            dl = np.where(small, np.abs(_delta_float(np.where(small, om, 1.0), None)), 1.0)
            dfac = [dl, np.where(small, 1.0, om), np.where(small, 1.0, om)]
            shift = 0
        else:
            dfac = [np.abs(om - Om), 0.5 * om + 0.5 * Om]
            shift = 1
        mx, ex = _frexp_div([d], [s0], -1)
        my, ey = _frexp_div([d, *dfac], [s1], shift - 1)
        lx = np.log(mx) + ex * _LN2
        ly = np.log(my) + ey * _LN2
        sw = lx > ly
        ms, es, ls = np.where(sw, my, mx), np.where(sw, ey, ex), np.where(sw, ly, lx)
        ml, el, ll = np.where(sw, mx, my), np.where(sw, ex, ey), np.where(sw, lx, ly)
        out = np.empty(mx.shape)
        lo, hi = math.log(1e-75), math.log(1e75)
        ra = (ll <= hi) & (ls >= lo)
        rb = ll > hi
        rc = ~(ra | rb)
        if ra.any():
            uv = _uv_from_h(np.ldexp(ms[ra], es[ra]), np.ldexp(ml[ra], el[ra]))
            out[ra] = _pq_kernel(uv, want)
        if rb.any():
            msb, esb, lsb = ms[rb], es[rb], ls[rb]
            rho = np.ldexp(msb / ml[rb], esb - el[rb])
            c = 1.0 / (1.0 + rho * rho)
            u = np.ldexp(msb * rho * np.sqrt(c), esb)
            e = np.ldexp(msb * msb * c, 2 * esb)
            fin = e < math.inf
            f = np.exp(-u * u) + _SQRT_PI * u * (1.0 + sc.erf(u))
            if want == "logp":
                res = np.where(fin, np.log(c * f) - e, -math.inf)
            else:
                p = np.where(fin, np.exp(-e) * c * f, 0.0)
                if want == "p":
                    res = np.minimum(p, 1.0)
                else:
                    near1 = p > 0.5
                    if want == "q":
                        res = np.where(near1, -np.expm1(-e), 1.0 - p)
                    else:
                        lq = np.where(e >= 1e-300, np.log(-np.expm1(-e)), 2.0 * lsb)
                        res = np.where(near1, lq, np.log1p(-p))
            out[rb] = res
        if rc.any():
            msc, esc, mlc, elc = ms[rc], es[rc], ml[rc], el[rc]
            g = _g_small_z(np.ldexp(mlc * mlc, 2 * elc))
            if want == "logq":
                res = 2.0 * (ls[rc] + ll[rc]) + np.log(g)
            else:
                q = np.ldexp((msc * msc) * (mlc * mlc) * g, 2 * (esc + elc))
                # log p = log1p(-q) = -q: q < 1e-150
                res = q if want == "q" else (1.0 - q if want == "p" else -q)
            out[rc] = res
    return out


# =========================================================================== mpmath core
def _mp_p_from_xy(x: mpmath.mpf, y: mpmath.mpf) -> mpmath.mpf:
    r = mpmath.sqrt(x + y)
    u = x / r
    v = y / r
    b = v * mpmath.exp(-u * u) + u * mpmath.exp(-v * v)
    b += mpmath.sqrt(mpmath.pi) * u * v * (mpmath.erf(u) + mpmath.erf(v))
    return mpmath.exp(-u * v) * b / r


def _mp_logp_from_xy(x: mpmath.mpf, y: mpmath.mpf) -> mpmath.mpf:
    r = mpmath.sqrt(x + y)
    u = x / r
    v = y / r
    b = v * mpmath.exp(-u * u) + u * mpmath.exp(-v * v)
    b += mpmath.sqrt(mpmath.pi) * u * v * (mpmath.erf(u) + mpmath.erf(v))
    return -u * v + mpmath.log(b / r)


def _mp_q_from_xy(x: mpmath.mpf, y: mpmath.mpf) -> mpmath.mpf:
    """``1 - p`` at the current precision, raising the precision by the digits that cancel.

    The cancellation in ``1 - p`` is known a priori: ``1 - p ~ x y / 6`` for small ``x + y``;
    the result is checked a posteriori and recomputed if more digits cancelled than planned.
    """
    prec = mpmath.mp.prec
    p = _mp_p_from_xy(x, y)
    if p <= 0.5:
        return 1 - p
    extra = max(0, -mpmath.log(x * y / 7, 2)) + 20
    for _ in range(8):
        with mpmath.workprec(prec + int(extra)):
            q = 1 - _mp_p_from_xy(x, y)
            lost = -mpmath.log(q, 2) if q > 0 else mpmath.inf
        if lost + 10 <= extra:
            return +q
        extra = 2 * extra if not mpmath.isfinite(lost) else lost + 30
    raise ArithmeticError("1 - p: cancellation could not be resolved")  # pragma: no cover


def _mp_xy_forcing(sigma, sigma1, omega, Omega, d) -> tuple[mpmath.mpf, mpmath.mpf]:
    """``x = d**2/(4 sigma0**2)``, ``y = d**2 (omega**2 - Omega**2)**2 / (4 sigma1**2)``."""
    s0 = _mp_arg("sigma", sigma)
    s1 = s0 if sigma1 is None else _mp_arg("sigma1", sigma1)
    om = _mp_arg("omega", omega)
    dd = _mp_arg("d", d)
    om2 = 2 if Omega is None else _mp_arg("Omega", Omega) ** 2
    delta = om * om - om2
    if delta == 0:
        raise ValueError("Omega: resonance Omega == omega (infinite forced amplitude)")
    return dd * dd / (4 * s0 * s0), (dd * delta) ** 2 / (4 * s1 * s1)


def _estimate(x: mpmath.mpf, y: mpmath.mpf) -> tuple[float, float, float]:
    """Rough ``(uv, x*y, p)`` in float64 (mpf exponents keep huge/tiny values in range)."""
    lx = float(mpmath.log(x)) if x > 0 else -1e300
    ly = float(mpmath.log(y)) if y > 0 else -1e300
    lxy = lx + ly
    ls = max(lx, ly) + math.log1p(math.exp(-abs(lx - ly)))
    le = lxy - ls
    e = math.exp(min(le, 700.0))
    if e > 50.0:
        return e, math.exp(min(lxy, 700.0)), 0.0
    if abs(lx - ly) > 60.0 or not -600.0 < lx < 600.0 or not -600.0 < ly < 600.0:
        # scales far apart (p ~ exp(-min(x, y))) or both far above d (p ~ 1)
        return e, math.exp(min(lxy, 700.0)), math.exp(-e)
    xf, yf = math.exp(lx), math.exp(ly)
    r = math.sqrt(xf + yf)
    u, v = xf / r, yf / r
    b = v * math.exp(-u * u) + u * math.exp(-v * v) + _SQRT_PI * u * v * (math.erf(u) + math.erf(v))
    return e, math.exp(min(lxy, 700.0)), math.exp(-e) * b / r


def _estimate_float(sigma, sigma1, omega, Omega, d) -> tuple[float, float, float] | None:
    """:func:`_estimate` with Python floats when every input converts to a normal float."""
    try:
        s0 = float(sigma)
        s1 = s0 if sigma1 is None else float(sigma1)
        om = float(omega)
        om2 = 2.0 if Omega is None else float(Omega) ** 2
        dd = float(d)
        x = (dd / (2 * s0)) ** 2
        y = (dd * (om * om - om2) / (2 * s1)) ** 2
    except (TypeError, ValueError, OverflowError, ZeroDivisionError):
        return None
    if not (1e-150 < x < 1e150 and 1e-150 < y < 1e150 and s0 > 0 and s1 > 0 and dd > 0):
        return None
    e = x * y / (x + y)
    if e > 50.0:
        return e, x * y, 0.0
    r = math.sqrt(x + y)
    u, v = x / r, y / r
    b = v * math.exp(-u * u) + u * math.exp(-v * v) + _SQRT_PI * u * v * (math.erf(u) + math.erf(v))
    return e, x * y, math.exp(-e) * b / r


def _guard_digits(e: float) -> int:
    """Extra digits so that ``exp(-uv)`` keeps its relative accuracy (uv ~ 1e6 costs 6)."""
    return 12 + (int(math.log10(e)) + 1 if e > 1 else 0)


# ---- scalar fast path on raw mpf tuples (mpmath.libmp): the same operations, roundings and
# precisions as the mpf-object code below, without the per-operation object and context costs
_lm = mpmath.libmp
_RND = _lm.round_nearest
_MP_FOUR = _lm.from_int(4)
_LOG2E = 1.4426950408889634
_SQRT_PI_CACHE: dict[int, tuple] = {}


def _sqrt_pi_raw(prec: int) -> tuple:
    """``sqrt(pi)`` rounded to ``prec`` bits (as ``mpmath.sqrt(mpmath.pi)``), cached."""
    v = _SQRT_PI_CACHE.get(prec)
    if v is None:
        v = _SQRT_PI_CACHE[prec] = _lm.mpf_sqrt(_lm.mpf_pi(prec, _RND), prec, _RND)
    return v


def _erf_raw(u: tuple, prec: int) -> tuple:
    """``erf(u)`` for ``u > 0`` to ``prec`` bits: mpmath's Taylor series where it is cheap, and
    ``1 - erfc(u)`` (erfc at the few bits that survive, by its asymptotic series) or ``1`` where
    that series is slow (``u`` of ~10 costs mpmath ~300 terms)."""
    mag = u[2] + u[3]
    if mag < 2:  # u < 2
        return _lm.mpf_erf(u, prec, _RND)
    if mag > 40:
        return _lm.fone
    uf = _lm.to_float(u)
    u2 = uf * uf * _LOG2E  # erfc(u) < exp(-u**2) = 2**-u2 (u >= 1)
    if u2 > prec + 3:  # 1 - erf(u) < 1/8 ulp of 1: erf rounds to 1
        return _lm.fone
    pc = max(prec - int(u2) + 30, 53)  # bits of erfc(u) that reach the result (+ 30 guard)
    n = int(uf)
    if n * n * 1.44 > pc + 20 + 2 * mag:  # mpmath's erfc uses its asymptotic series
        return _lm.mpf_sub(_lm.fone, _lm.mpf_erfc(u, pc, _RND), prec, _RND)
    return _lm.mpf_erf(u, prec, _RND)


def _raw_in(value: Any) -> tuple | None:
    """A finite positive float (or small int) as an exact raw mpf; None: use the general path."""
    if isinstance(value, float):
        return _lm.from_float(float(value)) if 0.0 < value < math.inf else None
    if type(value) is int and 0 < value < 1 << 53:
        return _lm.from_int(value)
    return None


def _raw_p_parts(x: tuple, y: tuple, prec: int) -> tuple[tuple, tuple, tuple]:
    """``(-uv, B, r)`` of :func:`_mp_p_from_xy`, ``p = exp(-uv) B / r``."""
    mul, add, div, exp, neg = _lm.mpf_mul, _lm.mpf_add, _lm.mpf_div, _lm.mpf_exp, _lm.mpf_neg
    rnd = _RND
    r = _lm.mpf_sqrt(add(x, y, prec, rnd), prec, rnd)
    u = div(x, r, prec, rnd)
    v = div(y, r, prec, rnd)
    nu = neg(u)
    eu = exp(mul(nu, u, prec, rnd), prec, rnd)
    fu = _erf_raw(u, prec)
    if u == v:  # e.g. sigma1 = sigma and |omega**2 - Omega**2| = 1 (the paper)
        ev, fv = eu, fu
    else:
        ev = exp(mul(neg(v), v, prec, rnd), prec, rnd)
        fv = _erf_raw(v, prec)
    b = add(mul(v, eu, prec, rnd), mul(u, ev, prec, rnd), prec, rnd)
    c = mul(mul(_sqrt_pi_raw(prec), u, prec, rnd), v, prec, rnd)
    b = add(b, mul(c, add(fu, fv, prec, rnd), prec, rnd), prec, rnd)
    return mul(nu, v, prec, rnd), b, r


def _single_mp_fast(sigma, sigma1, omega, Omega, d, dps: int, want: str) -> Any:
    """:func:`_single_mp` for float inputs on raw mpf tuples; None where it does not apply
    (other input types, bad input, resonance, the adaptive ``1 - p`` loop)."""
    s0 = _raw_in(sigma)
    s1 = s0 if sigma1 is None else _raw_in(sigma1)
    om = _raw_in(omega)
    Om = _lm.ftwo if Omega is None else _raw_in(Omega)
    dd = _raw_in(d)
    if s0 is None or s1 is None or om is None or Om is None or dd is None:
        return None
    est = _estimate_float(sigma, sigma1, omega, Omega, d)
    if est is None:
        return None
    e, xy, pest = est
    if pest > 0.5 and want == "logp":
        return None  # log1p(-(1 - p)) in the general path
    guard = _guard_digits(e)
    direct_q = want in ("q", "logq") and pest > 0.45
    if direct_q:
        guard += 8 + max(0, int(math.log10(7.0 / max(xy, 1e-300))) + 1) if xy < 7 else 10
    prec = _lm.dps_to_prec(dps + guard)
    mul, div, sub, rnd = _lm.mpf_mul, _lm.mpf_div, _lm.mpf_sub, _RND
    om2 = Om if Omega is None else mul(Om, Om, prec, rnd)
    delta = sub(mul(om, om, prec, rnd), om2, prec, rnd)
    if not delta[1]:
        return None  # resonance: the general path raises
    x = div(mul(dd, dd, prec, rnd), mul(mul(_MP_FOUR, s0, prec, rnd), s0, prec, rnd), prec, rnd)
    t = mul(dd, delta, prec, rnd)
    y = div(mul(t, t, prec, rnd), mul(mul(_MP_FOUR, s1, prec, rnd), s1, prec, rnd), prec, rnd)
    nuv, b, r = _raw_p_parts(x, y, prec)
    make = mpmath.mp.make_mpf
    if want == "logp":
        lg = _lm.mpf_log(div(b, r, prec, rnd), prec, rnd)
        return make(_lm.mpf_add(nuv, lg, prec, rnd))
    p = div(mul(_lm.mpf_exp(nuv, prec, rnd), b, prec, rnd), r, prec, rnd)
    if want == "p":
        return make(p)
    if not direct_q and _lm.mpf_gt(p, _MP_HALF):
        return None  # 1 - p by the adaptive loop of the general path
    if want == "logq" and not direct_q and p[2] + p[3] < -16:
        return None  # log1p(-p) for small p in the general path
    q = sub(_lm.fone, p, prec, rnd)
    if direct_q and not (q[0] == 0 and q[1] and -(q[2] + q[3]) <= 3.3 * (guard - 4)):
        return None  # more digits cancelled than planned: the general path's loop
    return make(q) if want == "q" else make(_lm.mpf_log(q, prec, rnd))


_MP_HALF = _lm.from_man_exp(1, -1)


def _single_mp(sigma, sigma1, omega, Omega, d, dps: int, want: str) -> mpmath.mpf:
    fast = _single_mp_fast(sigma, sigma1, omega, Omega, d, dps, want)
    if fast is not None:
        return fast
    est = _estimate_float(sigma, sigma1, omega, Omega, d)
    if est is None:
        with mpmath.workprec(64):
            est = _estimate(*_mp_xy_forcing(sigma, sigma1, omega, Omega, d))
    e, xy, pest = est
    if pest > 0.5 and want == "logp":  # log p = log1p(-q) keeps its relative accuracy
        q = _single_mp(sigma, sigma1, omega, Omega, d, dps + 5, "q")
        with mpmath.workdps(dps + 5):
            return mpmath.log1p(-q)
    guard = _guard_digits(e)
    direct_q = want in ("q", "logq") and pest > 0.45
    if direct_q:  # 1 - p cancels ~log10(6/(x y)) digits for small x, y: add them up front
        guard += 8 + max(0, int(math.log10(7.0 / max(xy, 1e-300))) + 1) if xy < 7 else 10
    with mpmath.workdps(dps + guard):
        x, y = _mp_xy_forcing(sigma, sigma1, omega, Omega, d)
        if want == "p":
            return _mp_p_from_xy(x, y)
        if want == "logp":
            return _mp_logp_from_xy(x, y)
        if direct_q:
            q = 1 - _mp_p_from_xy(x, y)
            # a posteriori check of the digits lost; fall back to the adaptive loop if needed
            if not (q > 0 and -mpmath.mag(q) <= 3.3 * (guard - 4)):  # digits lost <= guard-4
                q = _mp_q_from_xy(x, y)
        elif want == "logq":
            p = _mp_p_from_xy(x, y)
            return mpmath.log1p(-p) if p <= 0.5 else mpmath.log(_mp_q_from_xy(x, y))
        else:
            q = _mp_q_from_xy(x, y)
        return q if want == "q" else mpmath.log(q)


def _mp_loop(fn: Callable[..., Any], args: dict[str, Any]) -> Any:
    """Apply a scalar mpmath function elementwise if any argument is an array."""
    if not any(isinstance(v, (list, tuple, np.ndarray)) for v in args.values()):
        return fn(**args)
    arrays = {k: np.asarray(v, dtype=object) for k, v in args.items() if v is not None}
    if all(a.ndim == 0 for a in arrays.values()):
        return fn(**args)
    b = np.broadcast_arrays(*arrays.values())
    keys = list(arrays)
    out = np.empty(b[0].shape, dtype=object)
    for idx in np.ndindex(out.shape):
        kw = dict(args)
        for k, arr in zip(keys, b, strict=True):
            kw[k] = arr[idx]
        try:
            out[idx] = fn(**kw)
        except ValueError as exc:
            raise ValueError(f"{exc} at index {idx if len(idx) > 1 else idx[0]}") from None
    return out


# =========================================================================== several components
def rayleigh_scales(
    sigma: Any, *, sigma1: Any = None, omega: Any = 1, Omega: Any = None, dps: int | None = None
) -> tuple[Any, ...]:
    r"""Rayleigh scales ``(s_0, s_1, ..., s_M)`` of the amplitudes in eq. (22).

    ``s_0 = sqrt(2) sigma`` (free oscillation, eq. 24) and ``s_i = sqrt(2) sigma_i /
    |omega**2 - Omega_i**2|`` (forcing component ``i``, eq. 25).

    Parameters
    ----------
    sigma : float
        ``sigma_0``, standard deviation of the initial-condition coefficients.
    sigma1 : float, sequence of floats or None
        ``sigma_i``, standard deviation of the forcing coefficients of each component; ``None``
        means ``sigma_i = sigma``; a scalar applies to every component.
    omega : float
        Natural frequency of the pipes.
    Omega : float, sequence of floats or None
        Forcing frequencies ``Omega_i``; ``None`` is the paper's single ``sqrt(2)``.
    dps : int or None
        ``None`` returns floats, otherwise mpf at ``dps`` digits.

    Returns
    -------
    tuple
        The ``M + 1`` scales.

    >>> [round(s, 12) for s in rayleigh_scales(0.5)]
    [0.707106781187, 0.707106781187]
    """
    omegas = list(Omega) if _is_components(Omega) else [Omega]
    if sigma1 is None or not isinstance(sigma1, (list, tuple)):
        sig1 = [sigma1] * len(omegas)
    else:
        sig1 = list(sigma1)
        if len(sig1) != len(omegas):
            raise ValueError(
                f"sigma1: {len(sig1)} values for {len(omegas)} forcing components (Omega)"
            )
    if dps is None:
        s0 = float(_float_arg("sigma", sigma))
        om = float(_float_arg("omega", omega))
        out = [math.sqrt(2.0) * s0]
        for i, (Om, s1) in enumerate(zip(omegas, sig1, strict=True)):
            s1v = s0 if s1 is None else float(_float_arg(f"sigma1[{i}]", s1))
            Omv = None if Om is None else _float_arg(f"Omega[{i}]", Om)
            try:
                delta = abs(float(_delta_float(np.float64(om), Omv)))
            except ValueError:
                raise ValueError(
                    f"Omega: resonance Omega == omega (infinite forced amplitude) at index {i}"
                ) from None
            out.append(math.sqrt(2.0) * s1v / delta)
        return tuple(out)
    dps = _check_dps(dps)
    with mpmath.workdps(dps + 10):
        s0 = _mp_arg("sigma", sigma)
        om = _mp_arg("omega", omega)
        out = [mpmath.sqrt(2) * s0]
        for i, (Om, s1) in enumerate(zip(omegas, sig1, strict=True)):
            s1v = s0 if s1 is None else _mp_arg(f"sigma1[{i}]", s1)
            om2 = 2 if Om is None else _mp_arg(f"Omega[{i}]", Om) ** 2
            delta = om * om - om2
            if delta == 0:
                raise ValueError(
                    f"Omega: resonance Omega == omega (infinite forced amplitude) at index {i}"
                )
            out.append(mpmath.sqrt(2) * s1v / abs(delta))
        return tuple(out)


class RayleighSumResult(NamedTuple):
    """Result of :func:`rayleigh_sum_probability`: the probability and an error estimate."""

    value: Any
    error: Any
    method: str


# ---- groups: a single Rayleigh or a pair, each with closed-form sf / cdf / pdf on arrays
class _FGroup:
    """float64 group of one or two Rayleigh scales."""

    def __init__(self, scales: Sequence[float]) -> None:
        self.scales = tuple(float(s) for s in scales)
        self.var = sum(s * s for s in self.scales)

    def _uv(self, t: np.ndarray) -> _UV:
        a, b = self.scales
        with np.errstate(divide="ignore", invalid="ignore"):
            return _uv_from_h(t / (math.sqrt(2.0) * a), t / (math.sqrt(2.0) * b))

    def sf(self, t: np.ndarray) -> np.ndarray:
        t = np.maximum(t, 0.0)
        if len(self.scales) == 1:
            return np.exp(-0.5 * (t / self.scales[0]) ** 2)
        out = np.ones_like(t)
        pos = t > 0
        with np.errstate(under="ignore"):
            out[pos] = _pq_float(self._uv(t[pos]), "p")
        return out

    def cdf(self, t: np.ndarray) -> np.ndarray:
        t = np.maximum(t, 0.0)
        if len(self.scales) == 1:
            return -np.expm1(-0.5 * (t / self.scales[0]) ** 2)
        out = np.zeros_like(t)
        pos = t > 0
        with np.errstate(under="ignore"):
            out[pos] = _pq_float(self._uv(t[pos]), "q")
        return out

    def pdf(self, t: np.ndarray) -> np.ndarray:
        if len(self.scales) == 1:
            s = self.scales[0]
            with np.errstate(under="ignore"):
                return t / (s * s) * np.exp(-0.5 * (t / s) ** 2)
        out = np.zeros_like(t)
        pos = t > 0
        uv = self._uv(t[pos])
        with np.errstate(under="ignore"):
            out[pos] = 4.0 * uv.u * uv.v / uv.r * np.exp(-uv.e) * _i2_float(uv.u, uv.v) / t[pos]
        return out


_GL_CACHE: dict[int, tuple[np.ndarray, np.ndarray]] = {}


def _gl(n: int) -> tuple[np.ndarray, np.ndarray]:
    if n not in _GL_CACHE:
        _GL_CACHE[n] = np.polynomial.legendre.leggauss(n)
    return _GL_CACHE[n]


def _i2_float(u: np.ndarray, v: np.ndarray) -> np.ndarray:
    """``int_{-v}^{u} (v+z)(u-z) exp(-z**2) dz`` (positive) for arrays u, v >= 0."""
    r = u + v
    out = np.empty_like(r)
    small = r < 2.0
    if small.any():  # positive integrand, analytic: 16-point Gauss-Legendre is exact to ~1 ulp
        us, vs = u[small], v[small]
        xg, wg = _gl(16)
        h = 0.5 * (us + vs)
        z = (0.5 * (us - vs))[:, None] + h[:, None] * xg[None, :]
        f = (vs[:, None] + z) * (us[:, None] - z) * np.exp(-z * z)
        out[small] = h * (f @ wg)
    big = ~small
    if big.any():
        ub, vb = u[big], v[big]
        k0 = 0.5 * _SQRT_PI * (sc.erf(ub) + sc.erf(vb))
        with np.errstate(under="ignore"):
            out[big] = (ub * vb - 0.5) * k0 + 0.5 * (ub * np.exp(-vb * vb) + vb * np.exp(-ub * ub))
    return out


def _i3_float(u: np.ndarray, v: np.ndarray) -> np.ndarray:
    """``int_{-v}^{u} (v+z)**2 (u-z) exp(-z**2) dz`` (positive)."""
    r = u + v
    out = np.empty_like(r)
    small = r < 3.0
    if small.any():
        us, vs = u[small], v[small]
        xg, wg = _gl(24)
        h = 0.5 * (us + vs)
        z = (0.5 * (us - vs))[:, None] + h[:, None] * xg[None, :]
        f = (vs[:, None] + z) ** 2 * (us[:, None] - z) * np.exp(-z * z)
        out[small] = h * (f @ wg)
    big = ~small
    if big.any():
        ub, vb = u[big], v[big]
        with np.errstate(under="ignore"):
            eu, ev = np.exp(-ub * ub), np.exp(-vb * vb)
        k0 = 0.5 * _SQRT_PI * (sc.erf(ub) + sc.erf(vb))
        k1 = 0.5 * (ev - eu)
        k2 = 0.5 * k0 - 0.5 * (ub * eu + vb * ev)
        k3 = 0.5 * ((vb * vb + 1) * ev - (ub * ub + 1) * eu)
        out[big] = ub * vb * vb * k0 + (2 * ub * vb - vb * vb) * k1 + (ub - 2 * vb) * k2 - k3
    return out


def _make_groups(scales: Sequence[Any]) -> list[tuple[Any, ...]]:
    """Pairs of scales (closed forms); a leftover single goes second to last, so that the
    innermost nested integrand uses its cheap density."""
    s = list(scales)
    groups = [tuple(s[i : i + 2]) for i in range(0, len(s), 2)]
    if len(groups) >= 3 and len(groups[-1]) == 1:
        groups[-2], groups[-1] = groups[-1], groups[-2]
    return groups


_PANEL_C = (-12.0, -8.0, -5.0, -3.0, -1.5, 0.0, 1.5, 3.0, 5.0, 8.0, 12.0)


def _panels_float(x: np.ndarray, var_last: float, var_rest: float) -> np.ndarray:
    """Panel breakpoints (shape (len(x), 13)) around the Gaussian saddle of the integrand."""
    tstar = x * (var_last / (var_last + var_rest))
    w = math.sqrt(var_last * var_rest / (var_last + var_rest))
    pts = tstar[:, None] + w * np.asarray(_PANEL_C)[None, :]
    pts = np.clip(pts, 0.0, x[:, None])
    return np.concatenate([np.zeros((len(x), 1)), pts, x[:, None]], axis=1)


def _conv_float(groups: list[_FGroup], x: np.ndarray, kind: str, n: int) -> np.ndarray:
    """``P(sum > x)`` (kind 'sf'), ``P(sum <= x)`` ('cdf') or the density ('pdf') on array x."""
    if len(groups) == 1:
        return getattr(groups[0], kind)(x)
    last, rest = groups[-1], groups[:-1]
    var_rest = sum(g.var for g in rest)
    bp = _panels_float(x, last.var, var_rest)
    xg, wg = _gl(n)
    a, b = bp[:, :-1], bp[:, 1:]
    h = 0.5 * (b - a)
    t = (0.5 * (a + b))[..., None] + h[..., None] * xg  # (nx, panels, n)
    xr = np.broadcast_to(x[:, None, None], t.shape)
    inner = _conv_float(rest, (xr - t).ravel(), kind, n).reshape(t.shape)
    f = last.pdf(t.ravel()).reshape(t.shape) * inner
    out = np.sum(h * (f @ wg), axis=1)
    if kind == "sf":
        out = out + last.sf(x)
    return out


def _rs_float(scales: Sequence[float], x: float, kind: str) -> RayleighSumResult:
    groups = [_FGroup(g) for g in _make_groups(scales)]
    xa = np.array([float(x)])
    if len(groups) == 1:
        val = float(getattr(groups[0], kind)(xa)[0])
        return RayleighSumResult(val, 4e-16 * abs(val), "closed form")
    lo = float(_conv_float(groups, xa, kind, 12)[0])
    hi = float(_conv_float(groups, xa, kind, 24)[0])
    # quadrature (difference of two orders) + rounding: exp(-E) with E ~ |ln value| carries
    # ~E * few eps from the roundings of its exponent
    err = abs(hi - lo) + 4e-16 * abs(hi) * (len(scales) + 2 * abs(math.log(abs(hi) or 1e-300)))
    return RayleighSumResult(hi, err, f"nested Gauss-Legendre ({len(groups) - 1}-D)")


# ---- mpmath groups
def _mp_i2(u: mpmath.mpf, v: mpmath.mpf) -> mpmath.mpf:
    """``int_{-v}^{u} (v+z)(u-z) exp(-z**2) dz`` in closed form, extra digits for cancellation."""
    r = u + v
    extra = 10 + (int(-mpmath.log10(r**2 / 3)) if r < 1 else 0)
    with mpmath.workdps(mpmath.mp.dps + extra):
        k0 = mpmath.sqrt(mpmath.pi) / 2 * (mpmath.erf(u) + mpmath.erf(v))
        val = (u * v - mpmath.mpf(1) / 2) * k0
        val += (u * mpmath.exp(-v * v) + v * mpmath.exp(-u * u)) / 2
    return +val


def _mp_i3(u: mpmath.mpf, v: mpmath.mpf) -> mpmath.mpf:
    """``int_{-v}^{u} (v+z)**2 (u-z) exp(-z**2) dz`` (closed form, extra digits as it cancels)."""
    r = u + v
    extra = 10 + (int(-mpmath.log10(r**4 / 12)) if r < 1 else 0)
    with mpmath.workdps(mpmath.mp.dps + extra):
        eu, ev = mpmath.exp(-u * u), mpmath.exp(-v * v)
        k0 = mpmath.sqrt(mpmath.pi) / 2 * (mpmath.erf(u) + mpmath.erf(v))
        k1 = (ev - eu) / 2
        k2 = k0 / 2 - (u * eu + v * ev) / 2
        k3 = ((v * v + 1) * ev - (u * u + 1) * eu) / 2
        val = u * v * v * k0 + (2 * u * v - v * v) * k1 + (u - 2 * v) * k2 - k3
    return +val


class _MGroup:
    def __init__(self, scales: Sequence[Any]) -> None:
        self.scales = tuple(mpmath.mpf(s) for s in scales)
        self.var = sum(s * s for s in self.scales)

    def _xy(self, t: mpmath.mpf) -> tuple[mpmath.mpf, mpmath.mpf]:
        a, b = self.scales
        return t * t / (2 * a * a), t * t / (2 * b * b)

    def sf(self, t: mpmath.mpf) -> mpmath.mpf:
        if t <= 0:
            return mpmath.mpf(1)
        if len(self.scales) == 1:
            return mpmath.exp(-t * t / (2 * self.scales[0] ** 2))
        return _mp_p_from_xy(*self._xy(t))

    def cdf(self, t: mpmath.mpf) -> mpmath.mpf:
        if t <= 0:
            return mpmath.mpf(0)
        if len(self.scales) == 1:
            return -mpmath.expm1(-t * t / (2 * self.scales[0] ** 2))
        return _mp_q_from_xy(*self._xy(t))

    def pdf(self, t: mpmath.mpf) -> mpmath.mpf:
        if t <= 0:
            return mpmath.mpf(0)
        if len(self.scales) == 1:
            s = self.scales[0]
            return t / (s * s) * mpmath.exp(-t * t / (2 * s * s))
        x, y = self._xy(t)
        r = mpmath.sqrt(x + y)
        u, v = x / r, y / r
        return 4 * u * v / r * mpmath.exp(-u * v) * _mp_i2(u, v) / t


_MP_GL_CACHE: dict[tuple[int, int], tuple[list[mpmath.mpf], list[mpmath.mpf]]] = {}


def _mp_gl(n: int) -> tuple[list[mpmath.mpf], list[mpmath.mpf]]:
    key = (n, mpmath.mp.prec)
    if key not in _MP_GL_CACHE:
        xs, ws = mpmath.mp.gauss_quadrature(n, "legendre")
        _MP_GL_CACHE[key] = (list(xs), list(ws))
    return _MP_GL_CACHE[key]


def _conv_mp(groups: list[_MGroup], x: mpmath.mpf, kind: str, n: int) -> mpmath.mpf:
    if len(groups) == 1:
        return getattr(groups[0], kind)(x)
    if x <= 0:
        return mpmath.mpf(1) if kind == "sf" else mpmath.mpf(0)
    last, rest = groups[-1], groups[:-1]
    var_rest = sum(g.var for g in rest)
    tstar = x * last.var / (last.var + var_rest)
    w = mpmath.sqrt(last.var * var_rest / (last.var + var_rest))
    pts = sorted({mpmath.mpf(0), x} | {min(max(tstar + c * w, 0), x) for c in _PANEL_C})
    xg, wg = _mp_gl(n)
    total = mpmath.mpf(0)
    for a, b in itertools.pairwise(pts):
        h = (b - a) / 2
        m = (a + b) / 2
        s = mpmath.fsum(
            wi * last.pdf(m + h * xi) * _conv_mp(rest, x - (m + h * xi), kind, n)
            for xi, wi in zip(xg, wg, strict=True)
        )
        total += h * s
    if kind == "sf":
        total += last.sf(x)
    return total


def _rs_mp(scales: Sequence[Any], x: Any, kind: str, dps: int) -> RayleighSumResult:
    groups_sc = _make_groups(scales)
    with mpmath.workdps(dps + 15):
        xm = mpmath.mpf(x)
        groups = [_MGroup(g) for g in groups_sc]
        if len(groups) == 1:
            val = getattr(groups[0], kind)(xm)
            return RayleighSumResult(val, abs(val) * mpmath.mpf(10) ** (-dps - 10), "closed form")
        tol = mpmath.mpf(10) ** (-dps - 2)
        n = 6 + dps // 4
        prev = _conv_mp(groups, xm, kind, n)
        for _ in range(6):
            n2 = (3 * n) // 2 + 2
            cur = _conv_mp(groups, xm, kind, n2)
            err = abs(cur - prev)
            if err <= tol * abs(cur):
                break
            prev, n = cur, n2
        return RayleighSumResult(cur, err, f"nested Gauss-Legendre ({len(groups) - 1}-D)")


def rayleigh_sum_probability(
    scales: Sequence[Any], d: Any = 1, *, tail: str = "upper", dps: int | None = None
) -> RayleighSumResult:
    r"""``P(R_0 + ... + R_M > d)`` (``tail="upper"``) or ``P(... <= d)`` (``tail="lower"``).

    ``R_i`` are independent Rayleigh variables of scales ``scales[i]`` (density
    ``(r/s**2) exp(-r**2/(2 s**2))``); eq. (22) with the scales of :func:`rayleigh_scales`.

    Method: Rayleighs are paired; a pair has a closed-form tail, CDF and density (see the module
    docstring); the pairs (and a leftover single) are convolved by nested composite
    Gauss-Legendre quadrature of positive integrands with panels around the integrand's Gaussian
    saddle, so relative accuracy holds in both tails. ``M + 1 <= 2``: closed form; 3-4 scales: one
    quadrature; 5-6: two nested quadratures (float64 ~10 ms, mpmath seconds at 30 digits).

    Parameters
    ----------
    scales : sequence of float
        Rayleigh scales ``s_i > 0``.
    d : float
        Threshold (pipe spacing), ``> 0``.
    tail : {"upper", "lower"}
        Which probability.
    dps : int or None
        ``None``: float64; otherwise mpmath with ``dps`` digits (rule orders are increased until
        two agree to ``dps + 2`` digits).

    Returns
    -------
    RayleighSumResult
        ``value``, ``error`` (estimate: difference of two rule orders, plus rounding), ``method``.

    >>> res = rayleigh_sum_probability([0.5, 0.3, 0.2], 1.0)
    >>> ref = rayleigh_sum_probability([0.5, 0.3, 0.2], 1.0, dps=25)
    >>> abs(res.value - float(ref.value)) < 1e-15, res.error < 1e-14
    (True, True)
    """
    if tail not in ("upper", "lower"):
        raise ValueError(f"tail must be 'upper' or 'lower', got {tail!r}")
    kind = "sf" if tail == "upper" else "cdf"
    sc_list = list(scales)
    if not sc_list:
        raise ValueError("scales: need at least one Rayleigh scale")
    if dps is None:
        vals = [float(_float_arg(f"scales[{i}]", s)) for i, s in enumerate(sc_list)]
        dv = float(_float_arg("d", d))
        return _rs_float(vals, dv, kind)
    dps = _check_dps(dps)
    with mpmath.workdps(dps + 15):
        vals = [_mp_arg(f"scales[{i}]", s) for i, s in enumerate(sc_list)]
        dv = _mp_arg("d", d)
    return _rs_mp(vals, dv, kind, dps)


def _multi(sigma, sigma1, omega, Omega, d, dps, want: str) -> Any:
    kind = "sf" if want in ("p", "logp") else "cdf"

    def one(sigma: Any, omega: Any, d: Any) -> Any:
        scales = rayleigh_scales(sigma, sigma1=sigma1, omega=omega, Omega=Omega, dps=dps)
        res = (
            _rs_float(scales, float(_float_arg("d", d)), kind)
            if dps is None
            else _rs_mp(scales, _mp_d(d, dps), kind, dps)
        )
        if dps is None:
            return math.log(res.value) if want.startswith("log") else res.value
        with mpmath.workdps(dps + 10):
            return mpmath.log(res.value) if want.startswith("log") else res.value

    if dps is None:
        s = _float_arg("sigma", sigma)
        o = _float_arg("omega", omega)
        dd = _float_arg("d", d)
        scalar = s.ndim == o.ndim == dd.ndim == 0
        b = np.broadcast_arrays(s, o, dd)
        out = np.empty(b[0].shape)
        for idx in np.ndindex(out.shape):
            out[idx] = one(b[0][idx], b[1][idx], b[2][idx])
        return float(out) if scalar else out
    return _mp_loop(one, {"sigma": sigma, "omega": omega, "d": d})


def _mp_d(d: Any, dps: int) -> mpmath.mpf:
    with mpmath.workdps(dps + 15):
        return _mp_arg("d", d)


def _dispatch(sigma, sigma1, omega, Omega, d, dps, want: str) -> Any:
    if _is_components(Omega) and len(Omega) == 1:  # one component given as a list
        Omega = Omega[0]
        if isinstance(sigma1, (list, tuple)):
            if len(sigma1) != 1:
                raise ValueError(f"sigma1: {len(sigma1)} values for 1 forcing component (Omega)")
            sigma1 = sigma1[0]
    if _is_components(Omega):
        if dps is not None:
            dps = _check_dps(dps)
        return _multi(sigma, sigma1, omega, Omega, d, dps, want)
    if dps is None:
        return _single_float(sigma, sigma1, omega, Omega, d, want)
    dps = _check_dps(dps)

    def one(sigma: Any, sigma1: Any = None, omega: Any = 1, Omega: Any = None, d: Any = 1) -> Any:
        return _single_mp(sigma, sigma1, omega, Omega, d, dps, want)

    return _mp_loop(
        one, {"sigma": sigma, "sigma1": sigma1, "omega": omega, "Omega": Omega, "d": d}
    )


# =========================================================================== public API
_PARAMS_DOC = """
    Parameters
    ----------
    sigma : float or array_like
        ``sigma_0 > 0``: standard deviation of the normal coefficients ``alpha_{0,j}``,
        ``beta_{0,j}`` of the free oscillation (the initial conditions, eq. 21); the amplitude
        ``Y_0`` is Rayleigh with scale ``s_0 = sqrt(2) sigma_0`` (eq. 24).
    sigma1 : float, array_like, sequence or None
        ``sigma_i > 0``: standard deviation of the forcing coefficients ``alpha_{i,j}``,
        ``beta_{i,j}`` (eq. 20); ``Y_i/|omega**2 - Omega_i**2|`` is Rayleigh with scale
        ``sqrt(2) sigma_i/|omega**2 - Omega_i**2|`` (eq. 25). ``None``: ``sigma_i = sigma`` (the
        paper's convention). With several components: a scalar or a list, one per component.
    omega : float or array_like
        Natural frequency ``omega > 0`` of the pipes (eq. 19).
    Omega : float, array_like, list/tuple or None
        Forcing frequency ``Omega_1 > 0``, ``!= omega``. ``None`` is the paper's ``sqrt(2)``,
        taken as ``Omega**2 = 2`` exactly at the working precision. A *list or tuple* means
        several forcing components ``Omega_1 ... Omega_M`` (eq. 22); a numpy array broadcasts
        like the other arguments (one component).
    d : float or array_like
        Equilibrium spacing ``d > 0`` of neighbouring pipes (eq. 19).
    dps : int or None
        ``None``: float64, vectorised with numpy broadcasting over every argument (a Python
        float for scalar input). An int: mpmath, correct to ``dps`` significant digits (an mpf,
        or an object array of mpf for array input).

    Raises
    ------
    ValueError
        Non-positive, NaN or infinite ``sigma``, ``sigma1``, ``omega``, ``Omega``, ``d``, or
        resonance ``Omega == omega``; the message names the argument (and the first bad index
        of an array).
"""



def _with_params(fn: Callable[..., Any]) -> Callable[..., Any]:
    """Insert the shared parameter documentation at the ``@PARAMS@`` marker."""
    if fn.__doc__:
        fn.__doc__ = fn.__doc__.replace("\n    @PARAMS@\n", _PARAMS_DOC)
    return fn

@_with_params
def impact_probability(
    sigma: Any,
    *,
    sigma1: Any = None,
    omega: Any = 1,
    Omega: Any = None,
    d: Any = 1,
    dps: int | None = None,
) -> Any:
    """Impact probability ``p = P(Y_0 + sum_i Y_i/|omega**2 - Omega_i**2| > d)`` (eqs. 22, 27).

    One component: the closed form of the module docstring (a sum of positive terms, accurate
    to a few ulps in float64 for all normal results, however small ``p``). Several
    components: :func:`rayleigh_sum_probability`.

    @PARAMS@

    Returns
    -------
    float, ndarray or mpf
        ``p``. Below ``~1e-308`` the float64 result underflows: use
        :func:`log_impact_probability`.

    Examples
    --------
    >>> p = impact_probability(0.12)           # the paper's parameters
    >>> abs(p + no_impact_probability(0.12) - 1) < 1e-15
    True
    >>> p_mp = impact_probability(0.05, dps=30)  # ~1e-21: 1 - (double integral) gives noise
    >>> abs(impact_probability(0.05) / float(p_mp) - 1) < 1e-14
    True
    >>> impact_probability([0.1, 1.0], Omega=np.array([[1.5], [3.0]])).shape
    (2, 2)
    """
    return _dispatch(sigma, sigma1, omega, Omega, d, dps, "p")


@_with_params
def no_impact_probability(
    sigma: Any,
    *,
    sigma1: Any = None,
    omega: Any = 1,
    Omega: Any = None,
    d: Any = 1,
    dps: int | None = None,
) -> Any:
    """``1 - p = P(Y_0 + sum_i Y_i/|omega**2 - Omega_i**2| < d)``, eqs. (22), (26).

    Computed by its own cancellation-free form where ``p > 1/2`` (see the module docstring), so
    it keeps full relative accuracy for large ``sigma`` where ``1 - p ~ d**4/(24 s_0**2 s_1**2)``.

    @PARAMS@

    Returns
    -------
    float, ndarray or mpf
        ``1 - p``.

    Examples
    --------
    >>> q = no_impact_probability(100.0)
    >>> abs(q / (1 / (24 * 2 * 100.0**2 * 2 * 100.0**2)) - 1) < 1e-3
    True
    >>> abs(no_impact_probability(1e3, dps=20) * 96e12 - 1) < 1e-5   # ~ d**4/(24 s0**2 s1**2)
    True
    """
    return _dispatch(sigma, sigma1, omega, Omega, d, dps, "q")


@_with_params
def log_impact_probability(
    sigma: Any,
    *,
    sigma1: Any = None,
    omega: Any = 1,
    Omega: Any = None,
    d: Any = 1,
    dps: int | None = None,
) -> Any:
    """``log p`` (natural log), also where ``p`` underflows float64 (``sigma`` below ~0.0025).

    @PARAMS@

    Returns
    -------
    float, ndarray or mpf
        ``log p``.

    >>> -125000 < log_impact_probability(1e-3) < -124990   # p = exp(-125000 + ...)
    True
    """
    return _dispatch(sigma, sigma1, omega, Omega, d, dps, "logp")


@_with_params
def log_no_impact_probability(
    sigma: Any,
    *,
    sigma1: Any = None,
    omega: Any = 1,
    Omega: Any = None,
    d: Any = 1,
    dps: int | None = None,
) -> Any:
    """``log(1 - p)``, also where ``1 - p`` underflows float64 (very large ``sigma``).

    @PARAMS@

    Returns
    -------
    float, ndarray or mpf
        ``log(1 - p)``.

    >>> x = log_no_impact_probability(1e100)     # 1 - p ~ 1/(96 sigma**4) = 1e-401.98...
    >>> abs(x - (-math.log(96) - 400 * math.log(10))) < 1e-12 * abs(x)
    True
    """
    return _dispatch(sigma, sigma1, omega, Omega, d, dps, "logq")


def naive_impact_probability(
    sigma: float, *, sigma1: float | None = None, omega: float = 1, Omega: float | None = None,
    d: float = 1,
) -> float:
    """The paper's eq. (27) evaluated literally as ``1 - scipy.integrate.dblquad(...)``.

    Kept to show the failure this module fixes: for small ``sigma`` the double integral rounds
    to 1 and ``p`` comes out as 0, a rounding-noise value or negative.

    Parameters
    ----------
    sigma, sigma1, omega, Omega, d : float
        As in :func:`impact_probability` (scalars only).

    Returns
    -------
    float
        ``1 - dblquad(eq. 27 integrand)`` with scipy's default tolerances.

    >>> abs(naive_impact_probability(0.5) - impact_probability(0.5)) < 1e-6
    True
    >>> naive_impact_probability(0.05) == impact_probability(0.05)
    False
    """
    from scipy import integrate

    s0 = float(_float_arg("sigma", sigma))
    s1 = s0 if sigma1 is None else float(_float_arg("sigma1", sigma1))
    om = float(_float_arg("omega", omega))
    Om2 = 2.0 if Omega is None else float(_float_arg("Omega", Omega)) ** 2
    dd = float(_float_arg("d", d))
    k = (om * om - Om2) ** 2
    if k == 0:
        raise ValueError("Omega: resonance Omega == omega (infinite forced amplitude)")
    c = k / (4 * s0 * s0 * s1 * s1)

    def f(t: float, x: float) -> float:
        return t * (x - t) * math.exp(-t * t / (4 * s0 * s0)) * math.exp(
            -k * (x - t) ** 2 / (4 * s1 * s1)
        )

    val, _ = integrate.dblquad(f, 0.0, dd, 0.0, lambda x: x)
    return 1.0 - c * val


# =========================================================================== derivative
def _dp_float(sigma, sigma1, omega, Omega, d) -> Any:
    sig0 = _float_arg("sigma", sigma)
    tied = sigma1 is None
    sig1 = sig0 if tied else _float_arg("sigma1", sigma1)
    om = _float_arg("omega", omega)
    Om = None if Omega is None else _float_arg("Omega", Omega)
    dd = _float_arg("d", d)
    arrs = [sig0, sig1, om, dd] + ([] if Om is None else [Om])
    scalar = all(a.ndim == 0 for a in arrs)
    b = np.broadcast_arrays(*arrs)
    sig0, sig1, om, dd = b[:4]
    Om = None if Om is None else b[4]
    uv = _UV(*(np.ravel(a) for a in _uv_forcing(sig0, sig1, om, Om, dd)))
    with np.errstate(under="ignore"):
        if tied:  # sigma dp/dsigma = d g(d) = 4 uv/r exp(-uv) I2(u, v)
            val = 4.0 * uv.u * uv.v / uv.r * np.exp(-uv.e) * _i2_float(uv.u, uv.v)
        else:  # sigma0 dp/dsigma0 = E[R0 f1(d - R0)] = 4 uv/r**2 exp(-uv) I3(u, v)
            val = 4.0 * uv.u * uv.v / uv.r**2 * np.exp(-uv.e) * _i3_float(uv.u, uv.v)
    out = val.reshape(sig0.shape) / sig0
    return float(out) if scalar else out


def _dp_mp(sigma, sigma1, omega, Omega, d, dps: int) -> mpmath.mpf:
    with mpmath.workprec(64):
        e = _estimate(*_mp_xy_forcing(sigma, sigma1, omega, Omega, d))[0]
    with mpmath.workdps(dps + _guard_digits(e) + 5):
        x, y = _mp_xy_forcing(sigma, sigma1, omega, Omega, d)
        s0 = _mp_arg("sigma", sigma)
        r = mpmath.sqrt(x + y)
        u, v = x / r, y / r
        if sigma1 is None:
            return 4 * u * v / r * mpmath.exp(-u * v) * _mp_i2(u, v) / s0
        return 4 * u * v / (r * r) * mpmath.exp(-u * v) * _mp_i3(u, v) / s0


def _dp_multi(sigma, sigma1, omega, Omega, d, dps) -> Any:
    if sigma1 is not None:
        raise ValueError(
            "sigma1: dp_dsigma with several components supports only sigma1=None "
            "(all sigma_i = sigma)"
        )

    def one(sigma: Any, omega: Any, d: Any) -> Any:
        # sigma dp/dsigma = d * density of the sum at d (all scales proportional to sigma)
        scales = rayleigh_scales(sigma, omega=omega, Omega=Omega, dps=dps)
        if dps is None:
            groups = [_FGroup(g) for g in _make_groups(scales)]
            dv = float(_float_arg("d", d))
            dens = float(_conv_float(groups, np.array([dv]), "pdf", 24)[0])
            return dv * dens / float(sigma)
        with mpmath.workdps(dps + 15):
            groups = [_MGroup(g) for g in _make_groups(scales)]
            dv = _mp_arg("d", d)
            n = 8 + dps // 3
            prev = _conv_mp(groups, dv, "pdf", n)
            for _ in range(6):
                n = (3 * n) // 2 + 2
                cur = _conv_mp(groups, dv, "pdf", n)
                if abs(cur - prev) <= abs(cur) * mpmath.mpf(10) ** (-dps - 2):
                    break
                prev = cur
            return dv * cur / _mp_arg("sigma", sigma)

    if dps is None:
        s = _float_arg("sigma", sigma)
        o = _float_arg("omega", omega)
        dd = _float_arg("d", d)
        scalar = s.ndim == o.ndim == dd.ndim == 0
        b = np.broadcast_arrays(s, o, dd)
        out = np.empty(b[0].shape)
        for idx in np.ndindex(out.shape):
            out[idx] = one(b[0][idx], b[1][idx], b[2][idx])
        return float(out) if scalar else out
    return _mp_loop(one, {"sigma": sigma, "omega": omega, "d": d})


@_with_params
def dp_dsigma(
    sigma: Any,
    *,
    sigma1: Any = None,
    omega: Any = 1,
    Omega: Any = None,
    d: Any = 1,
    dps: int | None = None,
) -> Any:
    r"""Derivative of the impact probability with respect to ``sigma``.

    With ``sigma1=None`` (``sigma_i = sigma``) this is the total derivative; every scale is
    proportional to ``sigma`` and ``sigma dp/dsigma = d g(d)`` with ``g`` the density of the
    sum of amplitudes, for one component
    ``d g(d) = (4uv/r) e^{-uv} int_{-v}^{u} (v+z)(u-z) e^{-z^2} dz``.
    With ``sigma1`` given it is the partial derivative at fixed ``sigma1`` (one component only):
    ``sigma_0 dp/dsigma_0 = E[R_0 f_1(d - R_0)] = (4uv/r^2) e^{-uv} int (v+z)^2 (u-z) e^{-z^2} dz``.
    The integrals are positive; float64 uses Gauss-Legendre where the closed form would cancel.

    @PARAMS@

    Returns
    -------
    float, ndarray or mpf
        ``dp/dsigma``; ``|d ln p/d ln sigma| = sigma dp/dsigma / p`` is the condition number.

    >>> h = 1e-6
    >>> fd = (impact_probability(0.3 + h) - impact_probability(0.3 - h)) / (2 * h)
    >>> abs(dp_dsigma(0.3) / fd - 1) < 1e-8
    True
    """
    if _is_components(Omega):
        return _dp_multi(sigma, sigma1, omega, Omega, d, None if dps is None else _check_dps(dps))
    if dps is None:
        return _dp_float(sigma, sigma1, omega, Omega, d)
    dps = _check_dps(dps)

    def one(sigma: Any, sigma1: Any = None, omega: Any = 1, Omega: Any = None, d: Any = 1) -> Any:
        return _dp_mp(sigma, sigma1, omega, Omega, d, dps)

    return _mp_loop(
        one, {"sigma": sigma, "sigma1": sigma1, "omega": omega, "Omega": Omega, "d": d}
    )


# =========================================================================== inverse
def _target_check(p: Any) -> None:
    if not (0 < p < 1):
        raise ValueError(f"p must be in (0, 1), got {p!r}")


def sigma_for_impact_probability(
    p: Any,
    *,
    sigma1: Any = None,
    omega: Any = 1,
    Omega: Any = None,
    d: Any = 1,
    dps: int | None = None,
) -> Any:
    r"""The forcing ``sigma`` for which the impact probability equals ``p`` (inverse of p(sigma)).

    ``p(sigma)`` increases strictly from 0 to 1 (with ``sigma1`` fixed: from ``P(R_1 > d)``).
    The root of ``ln p(sigma) = ln p`` (or ``ln(1 - p(sigma)) = ln(1 - p)`` when ``p > 1/2``,
    which keeps the relative accuracy of both tails) is bracketed in ``ln sigma`` from the tail
    asymptotics, found by Brent's method in float64 and, for ``dps``, polished by the secant
    method at the working precision.

    Parameters
    ----------
    p : float or array_like (or mpf / str for ``dps``)
        Target impact probability in ``(0, 1)``.
    sigma1, omega, Omega, d, dps
        As in :func:`impact_probability`; with ``sigma1`` given, ``sigma_0`` is solved for at
        fixed ``sigma1``.

    Returns
    -------
    float, ndarray or mpf
        ``sigma``.

    Raises
    ------
    ValueError
        ``p`` outside ``(0, 1)`` or not reachable (fixed ``sigma1``).

    >>> s = sigma_for_impact_probability(0.5)
    >>> abs(impact_probability(s) - 0.5) < 1e-15
    True
    >>> s = sigma_for_impact_probability("1e-10", dps=30)
    >>> abs(impact_probability(s, dps=30) / mpmath.mpf("1e-10") - 1) < 1e-28
    True
    """
    kw = {"sigma1": sigma1, "omega": omega, "Omega": Omega, "d": d}
    if dps is None:
        pa = np.asarray(p, dtype=np.float64)
        bad = ~((pa > 0) & (pa < 1))
        if bad.any():
            raise ValueError(f"p must be in (0, 1), got {float(pa[bad].flat[0])!r}"
                             f"{_bad_index(pa, bad)}")
        out = np.empty(pa.shape)
        for idx in np.ndindex(pa.shape):
            out[idx] = _inverse_float(float(pa[idx]), kw)
        return float(out) if pa.ndim == 0 else out
    dps = _check_dps(dps)

    def one(p: Any) -> mpmath.mpf:
        with mpmath.workdps(dps + 15):
            pm = mpmath.mpf(p)
        _target_check(pm)
        return _inverse_mp(pm, kw, dps)

    return _mp_loop(one, {"p": p})


def _inverse_objective(p_target: float, kw: dict[str, Any]) -> Callable[[float], float]:
    if p_target <= 0.5:
        lt = math.log(p_target)
        return lambda ls: float(log_impact_probability(math.exp(ls), **kw)) - lt
    lt = math.log1p(-p_target)
    return lambda ls: lt - float(log_no_impact_probability(math.exp(ls), **kw))


def _inverse_float(p: float, kw: dict[str, Any]) -> float:
    from scipy.optimize import brentq

    f = _inverse_objective(p, kw)
    d = float(np.asarray(kw["d"], dtype=float))
    lo = hi = math.log(d)
    for _ in range(400):
        if f(lo) < 0:
            break
        lo -= 1.0
    else:
        raise ValueError(f"p = {p!r} is not reachable for these parameters (sigma1 fixed?)")
    for _ in range(400):
        if f(hi) > 0:
            break
        hi += 1.0
    else:  # pragma: no cover
        raise ValueError(f"p = {p!r} is not reachable for these parameters")
    ls = brentq(f, lo, hi, xtol=1e-15, rtol=4 * np.finfo(float).eps, maxiter=200)
    return math.exp(ls)


def _inverse_mp(p: mpmath.mpf, kw: dict[str, Any], dps: int) -> mpmath.mpf:
    s0 = _inverse_float(float(p), kw) if 1e-300 < p < 1 - 1e-16 else None
    work = dps + 15
    with mpmath.workdps(work):
        if p <= 0.5:
            lt = mpmath.log(p)

            def f(ls: mpmath.mpf) -> mpmath.mpf:
                return log_impact_probability(mpmath.exp(ls), **kw, dps=work) - lt
        else:
            lt = mpmath.log1p(-p)

            def f(ls: mpmath.mpf) -> mpmath.mpf:
                return lt - log_no_impact_probability(mpmath.exp(ls), **kw, dps=work)

        if s0 is None:  # far outside float64: bracket, then bisect in ln(sigma)
            lo = hi = mpmath.log(_mp_arg("d", kw["d"]))
            while f(lo) > 0:
                lo -= 4
            while f(hi) < 0:
                hi += 4
            for _ in range(60):
                mid = (lo + hi) / 2
                if f(mid) > 0:
                    hi = mid
                else:
                    lo = mid
            x0 = (lo + hi) / 2
        else:
            x0 = mpmath.log(s0)
        ls = mpmath.findroot(f, (x0, x0 + mpmath.mpf(10) ** -12), solver="secant",
                             tol=mpmath.mpf(10) ** (-2 * work + 10))
        return mpmath.exp(ls)


# =========================================================================== theory chain
class TheoryCurve(NamedTuple):
    """Result of :func:`theory_curve`: arrays over ``sigma`` (mean, mode from the graph model)."""

    sigma: np.ndarray
    p: np.ndarray
    mean: np.ndarray
    mode: np.ndarray
    N: int


def theory_curve(
    sigma: Any,
    *,
    N: int = 101,
    sigma1: Any = None,
    omega: Any = 1,
    Omega: Any = None,
    d: Any = 1,
    space: str = "simple",
    dps: int = 30,
) -> TheoryCurve:
    """The chain ``sigma -> p -> (mean, mode of X)``: figure 10's theory curve in one call.

    ``p`` is :func:`impact_probability` at ``dps`` digits (mpmath, so ``p`` far below 1e-16 is
    exact), then ``symhx.mean(N, p, space=space, dps=dps)`` and ``symhx.mode(N, p,
    space=space)`` of the graph model (``N = n + 1`` possible impacts for ``n`` pipes; the
    paper's simulation has ``n = 100``, ``N = 101``).

    Parameters
    ----------
    sigma : float or array_like
        Forcing standard deviations.
    N : int
        Number of possible impacts (vertices).
    sigma1, omega, Omega, d
        As in :func:`impact_probability`.
    space : str
        Sample space of the graph model (``"simple"``, ``"eq41"``, ...).
    dps : int
        Digits of the mpmath evaluation.

    Returns
    -------
    TheoryCurve
        ``sigma``, ``p`` (float arrays), ``mean`` (float array), ``mode`` (int array), ``N``.

    >>> tc = theory_curve([0.05, 0.3], N=101)
    >>> int(tc.mode[0]), bool(tc.mode[1] > 50), bool(tc.mean[0] < tc.mean[1])
    (1, True, True)
    """
    from symhx.distribution import mean as _mean
    from symhx.distribution import mode as _mode

    s = np.atleast_1d(np.asarray(sigma, dtype=np.float64))
    ps, means, modes_ = [], [], []
    for sv in s.ravel():
        pm = impact_probability(float(sv), sigma1=sigma1, omega=omega, Omega=Omega, d=d, dps=dps)
        ps.append(float(pm))
        means.append(float(_mean(N, pm, space=space, dps=dps)))
        modes_.append(int(_mode(N, pm, space=space)))
    return TheoryCurve(
        sigma=s,
        p=np.array(ps).reshape(s.shape),
        mean=np.array(means).reshape(s.shape),
        mode=np.array(modes_, dtype=np.int64).reshape(s.shape),
        N=N,
    )
