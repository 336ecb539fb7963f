"""float64 kernels of one forcing component: p, 1 - p and their logs (eq. 27 in closed form),
vectorised, over the whole float range; the positive integrals of the derivative.

See :mod:`symhx.forcing` for the formulas. Every function takes validated float64 arrays.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from typing import Any, NamedTuple

import numpy as np
from scipy import special as sc

from symhx.forcing.arguments import ForcingParams, bad_index
from symhx.validation import InputError

__all__ = [
    "SQRT_PI",
    "UV",
    "delta_float",
    "gauss_legendre",
    "i2_float",
    "i3_float",
    "pq_float",
    "single_float",
    "uv_forcing",
    "uv_from_h",
]

SQRT_PI = math.sqrt(math.pi)
_SPLIT = 134217729.0  # 2**27 + 1, Dekker splitting constant
_TINY = float(np.finfo(float).tiny)


def delta_float(omega: np.ndarray, Omega: np.ndarray | None) -> np.ndarray:
    """``omega**2 - Omega**2`` with small relative error also close to resonance (whatever the
    caller's numpy error state: over/underflow of the squares is expected)."""
    with np.errstate(over="ignore", invalid="ignore", under="ignore"):
        if Omega is None:  # Omega**2 = 2 exactly: omega**2 = hi + lo exactly (Dekker), then - 2
            c = _SPLIT * omega
            hi = c - (c - omega)
            lo = omega - hi
            sq = omega * omega
            err = ((hi * hi - sq) + 2.0 * hi * lo) + lo * lo
            delta = (sq - 2.0) + err
            # omega**2 beyond float64 (omega > ~1.3e154): the split overflows; Delta = +inf
            delta = np.where(np.isfinite(sq), delta, sq)
        else:
            delta = (omega - Omega) * (omega + Omega)
    bad = delta == 0
    if Omega is not None and np.any(bad):  # an underflowed product is no resonance
        bad = bad & (omega == Omega)
    if np.any(bad):
        raise InputError(
            "Omega: resonance Omega == omega (infinite forced amplitude)"
            f"{bad_index(np.asarray(delta), np.asarray(bad))}"
        )
    return delta


# Taylor coefficients of phi_1(z)/z = sum_{n>=1} (-z)^(n-1)/(n+1)! and of
# (psi(z) - 1)/z = sum_{n>=1} (-z)^(n-1)/(n! (2n+1)); 19-20 terms give < 1e-17 for z < 1
PHI1_C = [(-1.0) ** n / math.factorial(n + 1) for n in range(1, 20)]
PSI1_C = [(-1.0) ** n / (math.factorial(n) * (2 * n + 1)) for n in range(1, 21)]

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


_PHI1_ZMAX = _series_zmax(PHI1_C)
_PSI1_ZMAX = _series_zmax(PSI1_C)
#: Horner coefficient columns for ``h`` phi~ rows over ``h`` psi~ rows (phi~ padded with a
#: zero leading coefficient to the 20 terms of psi~)
_SERIES_COLS = {h: [np.array([[c1]] * h + [[c2]] * h)
                    for c1, c2 in zip([*PHI1_C, 0.0], PSI1_C, strict=True)]
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
    return ((0.5 * SQRT_PI) * sc.erf(sz) / sz - 1.0) / z


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


class UV(NamedTuple):
    x: np.ndarray
    y: np.ndarray
    r: np.ndarray
    u: np.ndarray
    v: np.ndarray
    e: np.ndarray  # u*v = d**2 / (2 (s0**2 + s1**2))


def uv_from_h(hx: np.ndarray, hy: np.ndarray) -> UV:
    """x, y, r, u, v, uv from ``hx = sqrt(x)``, ``hy = sqrt(y)`` (whatever the caller's numpy
    error state: the squares may over/underflow)."""
    with np.errstate(over="ignore", invalid="ignore", under="ignore"):
        r = np.hypot(hx, hy)
        u = hx * (hx / r)
        v = hy * (hy / r)
        m = hx * (hy / r)
        e = m * m
        return UV(hx * hx, hy * hy, r, u, v, e)


def uv_forcing(sig0, sig1, omega, Omega, d) -> UV:
    """``x = d**2/(4 sigma0**2)``, ``y = d**2 Delta**2/(4 sigma1**2)`` (scales of eqs. 24-25).

    Arguments broadcast against each other. ``sqrt(x) = d/(2 sigma0)`` and ``sqrt(y) = d
    |Delta|/(2 sigma1)`` are products of mantissas and exponents (``|Delta| = |omega - Omega|
    (omega + Omega)``, or ``omega**2 - 2`` and ``omega**2`` beyond 1e100 for ``Omega=None``), so
    they are accurate whenever they are normal floats, even where ``Delta`` or another
    intermediate would under/overflow; the rest as :func:`uv_from_h` (``uv`` also where ``r``
    overflows).
    """
    with np.errstate(all="ignore"):
        if Omega is None:
            small = omega <= 1e100
            dl = np.where(small, np.abs(delta_float(np.where(small, omega, 1.0), None)), 1.0)
            dfac = [dl, np.where(small, 1.0, omega), np.where(small, 1.0, omega)]
            shift = -1
        else:
            delta_float(omega, Omega)  # the resonance check
            dfac = [np.abs(omega - Omega), 0.5 * omega + 0.5 * Omega]
            shift = 0
        sig0, sig1, d, *dfac = np.broadcast_arrays(sig0, sig1, d, *dfac)
        mx, ex = _frexp_div([d], [sig0], -1)
        my, ey = _frexp_div([d, *dfac], [sig1], shift)
        hx, hy = np.ldexp(mx, ex), np.ldexp(my, ey)
        uv = uv_from_h(hx, hy)
        if np.isfinite(uv.r).all():
            return uv
        # r = hypot(hx, hy) beyond float64: uv = s**2/(1 + (s/l)**2) from the smaller and the
        # larger of hx, hy (inf only where uv itself is beyond float64)
        s, l_ = np.minimum(hx, hy), np.maximum(hx, hy)
        rho = s / l_
        e = s / np.sqrt(1.0 + rho * rho)
        e *= e
        e = np.where(s == math.inf, math.inf, e)  # both beyond float64
        return uv._replace(e=np.where(np.isfinite(uv.r), uv.e, e))


def uv_chunk(sig0, sig1, delta, d, m: int) -> UV:
    """:func:`uv_forcing` on a chunk of ``m`` values from ``|Delta|`` (the same roundings);
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
    return UV(x, y, r, u, v, e)


def _bracket_p(uv: UV) -> np.ndarray:
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
    w *= SQRT_PI
    w *= fu
    b += w
    b /= uv.r
    return b


def _q_small_float(uv: UV) -> np.ndarray:
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


def pq_kernel(uv: UV, want: str) -> np.ndarray:
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
    out.put(idx, _q_comp(UV(*(a.take(idx) for a in uv)), want))
    idx = np.flatnonzero(~comp)
    out.put(idx, _q_direct(UV(*(a.take(idx) for a in uv)), want))
    return out


def _q_comp(uv: UV, want: str) -> np.ndarray:
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
    # log of the product where it is a normal float (an error of a few ulps of q); the sum of
    # the logs (no under/overflow for huge or tiny scales) only where it is not
    q = qs * uv.x
    q *= uv.y
    ok = (q >= _TINY) & (q < math.inf)
    if ok.all():
        return np.log(q, out=q)
    lq = np.log(uv.x)
    lq += np.log(uv.y)
    lq += np.log(qs, out=qs)
    np.log(q, out=q, where=ok)
    return np.where(ok, q, lq)


def _q_direct(uv: UV, want: str) -> np.ndarray:
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


def pq_float(uv: UV, want: str) -> np.ndarray:
    """Return p, q=1-p, log p or log q (``want`` in {'p','q','logp','logq'})."""
    shape = uv.u.shape
    if any(a.shape != shape for a in uv):
        uv = UV(*np.broadcast_arrays(*uv))
    flat = UV(*(np.ravel(a) for a in uv))
    n = flat.u.shape[0]
    out = np.empty(n)
    with np.errstate(all="ignore"):
        for i in range(0, n, _CHUNK):
            j = min(i + _CHUNK, n)
            out[i:j] = pq_kernel(UV(*(a[i:j] for a in flat)), want)
    return out.reshape(shape)


def single_float(fp: ForcingParams, want: str) -> Any:
    """p, 1 - p, log p or log(1 - p) (``want`` in p, q, logp, logq) of one validated float64
    forcing component, broadcasting over every field; a float for scalar input."""
    sig0, sig1, om, Om, dd = fp.sigma, fp.sigma1, fp.omega, fp.Omega, fp.d
    with np.errstate(all="ignore"):  # (|Delta| may under/overflow: then pq_extreme)
        delta = np.abs(delta_float(om, Om))
        arrs = [sig0, delta, dd] + ([] if sig1 is None else [sig1])
        shape = np.broadcast_shapes(*(a.shape for a in arrs))
        n = math.prod(shape)
        if n == 0:  # empty in, empty out (numpy/scipy semantics)
            return np.empty(shape)
        # scalars stay scalars (np.float64: same IEEE semantics as the arrays), the rest is flat
        flat = [a.reshape(-1)[0] if a.size == 1 and n > 1 else np.ravel(np.broadcast_to(a, shape))
                for a in arrs]
        # d and |Delta| in [1e-100, 1e100], and per chunk r < 1e75, uv > 1e-150 (so that
        # 1e-75 < hx, hy < 1e75; NaN fails too) and d/(2r) >= 1e-145 (so sigma0, sigma1/Delta
        # >= 1e-145): then no intermediate of the fast path under/overflows, else pq_extreme
        de, d_ = flat[1], flat[2]
        lims = ((1e-100 <= de.item() <= 1e100) if de.size == 1
                else (1e-100 <= de.min() and de.max() <= 1e100)) and (
            (1e-100 <= d_.item() <= 1e100) if d_.size == 1
            else (1e-100 <= d_.min() and d_.max() <= 1e100))
        out = np.empty(n)
        for i in range(0, n, _CHUNK):
            j = min(i + _CHUNK, n)
            s0, de, d_, *rest = (a if a.ndim == 0 else a[i:j] for a in flat)
            s1 = rest[0] if rest else s0
            uv = uv_chunk(s0, s1, de, d_, j - i)
            r, e = uv.r, uv.e
            rmax = r.max() if j - i > 1 else r.item()
            if (lims and rmax < 1e75 and (e.min() if j - i > 1 else e.item()) > 1e-150
                    and (d_.item() if d_.size == 1 else d_.min()) >= 2e-145 * rmax):
                out[i:j] = pq_kernel(uv, want)
                continue
            m = j - i
            ok = (r < 1e75) & (e > 1e-150) & (d_ >= 2e-145 * r)
            ok &= (d_ >= 1e-100) & (d_ <= 1e100) & (de >= 1e-100) & (de <= 1e100)
            ok = np.broadcast_to(ok, (m,))
            res = np.empty(m)
            idx = np.flatnonzero(ok)
            if idx.size:
                res.put(idx, pq_kernel(UV(*(a.take(idx) for a in uv)), want))
            idx = np.flatnonzero(~ok)
            full = [None if a is None else np.ravel(np.broadcast_to(a, shape))[i:j]
                    for a in (sig0, sig1 if sig1 is not None else sig0, om, Om, dd)]
            a0, a1, a2, a3, a4 = (None if a is None else a.take(idx) for a in full)
            res.put(idx, pq_extreme(a0, a1, a2, a3, a4, want))
            out[i:j] = res
    return float(out[0]) if not shape else out.reshape(shape)


# ---- float64 outside the fast path's range (ratios of scales up to the whole float range)
_LN2 = math.log(2.0)
#: Taylor coefficients of G(z) = phi~(z) - 2 psi~(z) (G(0) = 1/6): z G(z) = (1 - p)/x in the
#: limit x -> 0 (one amplitude's scale infinitely larger than d)
_G_C = [a - 2.0 * b for a, b in zip([*PHI1_C, 0.0], PSI1_C, strict=True)]


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
        out[big] = (1.0 - np.expm1(-zb) / zb - SQRT_PI * sc.erf(sz) / sz) / zb
    return out


def pq_extreme(s0, s1, om, Om, d, want: str) -> np.ndarray:
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
            dl = np.where(small, np.abs(delta_float(np.where(small, om, 1.0), None)), 1.0)
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
            uv = uv_from_h(np.ldexp(ms[ra], es[ra]), np.ldexp(ml[ra], el[ra]))
            out[ra] = pq_kernel(uv, want)
        if rb.any():
            msb, esb, lsb = ms[rb], es[rb], ls[rb]
            rho = np.ldexp(msb / ml[rb], esb - el[rb])
            c = 1.0 / (1.0 + rho * rho)
            u = np.ldexp(msb * rho * np.sqrt(c), esb)
            e = np.ldexp(msb * msb * c, 2 * esb)
            fin = e < math.inf
            f = np.exp(-u * u) + SQRT_PI * u * (1.0 + sc.erf(u))
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



_GL_CACHE: dict[int, tuple[np.ndarray, np.ndarray]] = {}


def gauss_legendre(n: int) -> tuple[np.ndarray, np.ndarray]:
    if n not in _GL_CACHE:
        _GL_CACHE[n] = np.polynomial.legendre.leggauss(n)
    return _GL_CACHE[n]


def i2_float(u: np.ndarray, v: np.ndarray) -> np.ndarray:
    """``int_{-v}^{u} (v+z)(u-z) exp(-z**2) dz`` (positive) for arrays u, v >= 0."""
    r = u + v
    out = np.empty_like(r)
    small = r < 2.0
    if small.any():  # positive integrand, analytic: 16-point Gauss-Legendre is exact to ~1 ulp
        us, vs = u[small], v[small]
        xg, wg = gauss_legendre(16)
        h = 0.5 * (us + vs)
        z = (0.5 * (us - vs))[:, None] + h[:, None] * xg[None, :]
        f = (vs[:, None] + z) * (us[:, None] - z) * np.exp(-z * z)
        out[small] = h * (f @ wg)
    big = ~small
    if big.any():
        ub, vb = u[big], v[big]
        k0 = 0.5 * SQRT_PI * (sc.erf(ub) + sc.erf(vb))
        with np.errstate(under="ignore"):
            out[big] = (ub * vb - 0.5) * k0 + 0.5 * (ub * np.exp(-vb * vb) + vb * np.exp(-ub * ub))
    return out


def i3_float(u: np.ndarray, v: np.ndarray) -> np.ndarray:
    """``int_{-v}^{u} (v+z)**2 (u-z) exp(-z**2) dz`` (positive)."""
    r = u + v
    out = np.empty_like(r)
    small = r < 3.0
    if small.any():
        us, vs = u[small], v[small]
        xg, wg = gauss_legendre(24)
        h = 0.5 * (us + vs)
        z = (0.5 * (us - vs))[:, None] + h[:, None] * xg[None, :]
        f = (vs[:, None] + z) ** 2 * (us[:, None] - z) * np.exp(-z * z)
        out[small] = h * (f @ wg)
    big = ~small
    if big.any():
        ub, vb = u[big], v[big]
        with np.errstate(under="ignore"):
            eu, ev = np.exp(-ub * ub), np.exp(-vb * vb)
        k0 = 0.5 * SQRT_PI * (sc.erf(ub) + sc.erf(vb))
        k1 = 0.5 * (ev - eu)
        k2 = 0.5 * k0 - 0.5 * (ub * eu + vb * ev)
        k3 = 0.5 * ((vb * vb + 1) * ev - (ub * ub + 1) * eu)
        out[big] = ub * vb * vb * k0 + (2 * ub * vb - vb * vb) * k1 + (ub - 2 * vb) * k2 - k3
    return out

