r"""The sum of independent Rayleigh variables (eq. 22) as a distribution object.

``S = R_1 + ... + R_n`` with ``R_i`` Rayleigh of scale ``s_i`` (density ``(r/s**2)
exp(-r**2/(2 s**2))``). One or two scales have closed forms (eq. 27 and its complement, see
:mod:`symhx.forcing`); more scales are paired (adjacent scales after sorting, so a pair holds
comparable scales), each pair having the closed-form tail, CDF and density, and the pairs (and a
leftover single) are convolved by nested composite Gauss-Legendre quadrature of *positive*
integrands::

    P(A + B > x)  = P(B > x) + int_0^x f_B(t) P(A > x - t) dt,
    P(A + B <= x) = int_0^x f_B(t) P(A <= x - t) dt,

so both tails keep their relative accuracy. The upper tail and the density are computed scaled:
``P(S > x) = m(x) exp(-x**2/(2V))`` (``V = sum s_i**2``) with the Gaussian factors of the groups
combined analytically, ``exp(-t**2/(2 V_B) - (x - t)**2/(2 V_A)) = exp(-x**2/(2V))
exp(-(t - t*)**2/(2 w**2))``, so ``log P(S > x) = log m - x**2/(2V)`` stays finite and accurate
where ``P(S > x)`` underflows (float64) or needs many guard digits (mpmath); the cdf is ``1 - sf``
where ``sf <= 1/2``. The panels are placed around the Gaussian saddle ``t*`` (in ``tau = t - t*``,
out to where ``exp(-tau**2/(2 w**2))`` is negligible at the requested digits) *and* at multiples
of every scale from both ends of ``[0, x]`` (where a small scale puts its structure), so scales
spread over many orders of magnitude are resolved. The error estimate is the difference of two
rule orders plus the rounding of the closed forms. float64 only: beyond ``x min(s) = 1e5 V`` the
log tail is the Laplace asymptotic (:func:`_laplace_logsf`), below ``x = 1e-9 min(s)`` the log cdf
its leading power.
"""

from __future__ import annotations

import itertools
import math
from collections.abc import Sequence
from fractions import Fraction
from typing import Any, NamedTuple

import mpmath
import numpy as np
from scipy import special as sc

from symhx.forcing.arguments import (
    ForcingParams,
    float_arg,
    is_array,
    is_components,
    mp_arg,
    mpf_of,
    rational_arg,
)
from symhx.forcing.kernels_float import (
    SQRT_PI,
    delta_float,
    gauss_legendre,
    i2_float,
    pq_float,
    uv_from_h,
)
from symhx.forcing.kernels_mp import MAX_EXPONENT, mp_i2, mp_q_from_xy
from symhx.validation import (
    check_array,
    check_choice,
    check_dps,
    check_seed,
    short_value,
    to_rational,
)

__all__ = [
    "RayleighSum",
    "RayleighSumResult",
    "rayleigh_scales",
    "rayleigh_sum_probability",
    "scales_of",
]


class RayleighSumResult(NamedTuple):
    """Result of :func:`rayleigh_sum_probability`: the probability and an error estimate."""

    value: Any
    error: Any
    method: str


# =========================================================================== scales
def scales_of(fp: ForcingParams, work_dps: int | None = None) -> tuple[Any, ...]:
    """Rayleigh scales of a scalar validated forcing: floats, or mpf at ``work_dps`` digits."""
    omegas = list(fp.Omega) if fp.components else [fp.Omega]
    s1s = list(fp.sigma1) if isinstance(fp.sigma1, tuple) else [fp.sigma1] * len(omegas)
    if work_dps is None:
        s0 = float(fp.sigma)
        om = np.float64(fp.omega)
        out = [math.sqrt(2.0) * s0]
        for i, (Om, s1) in enumerate(zip(omegas, s1s, strict=True)):
            scale = math.sqrt(2.0) * (s0 if s1 is None else float(s1))
            if Om is None:   # Omega**2 = 2: omega**2 - 2 by delta_float (never 0 for a float)
                out.append(scale / abs(float(delta_float(om, None))))
                continue
            Omf, omf = float(Om), float(om)
            if Omf == omf:
                raise ValueError(f"{_om_name(fp, i)}: resonance Omega == omega (infinite forced "
                                 "amplitude)")
            # |omega**2 - Omega**2| = |omega - Omega| (omega + Omega), divided one factor at a
            # time: the product under/overflows (or is subnormal, with lost digits) for tiny or
            # huge frequencies whose scale is still a float64 (or +inf)
            out.append(scale / abs(omf - Omf) / (omf + Omf))
        return tuple(out)
    with mpmath.workdps(work_dps):
        s0 = mp_arg("sigma", fp.sigma)
        om = mp_arg("omega", fp.omega)
        out = [mpmath.sqrt(2) * s0]
        for i, (Om, s1) in enumerate(zip(omegas, s1s, strict=True)):
            om2 = 2 if Om is None else mp_arg("Omega", Om) ** 2
            delta = om * om - om2
            if delta == 0:
                raise ValueError(f"{_om_name(fp, i)}: resonance Omega == omega (infinite forced "
                                 "amplitude)")
            s1v = s0 if s1 is None else mp_arg("sigma1", s1)
            out.append(mpmath.sqrt(2) * s1v / abs(delta))
        return tuple(out)


def _om_name(fp: ForcingParams, i: int) -> str:
    return f"Omega[{i}]" if fp.components else "Omega"


def rayleigh_scales(
    sigma: Any, *, sigma1: Any = None, omega: Any = 1, Omega: Any = None, dps: int | None = None
) -> tuple[Any, ...]:
    r"""Rayleigh scales ``(s_0, s_1, ..., s_M)`` of the amplitudes in eq. (22).

    ``s_0 = sqrt(2) sigma`` (free oscillation, eq. 24) and ``s_i = sqrt(2) sigma_i /
    |omega**2 - Omega_i**2|`` (forcing component ``i``, eq. 25).

    Parameters
    ----------
    sigma : float or str
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
    dps = check_dps(dps, allow_none=True)
    for name, v in (("sigma", sigma), ("omega", omega)):
        if is_array(v):
            raise TypeError(f"{name} must be a scalar here, got {type(v).__name__}")
    if is_array(sigma1) and not is_components(Omega):
        raise TypeError("sigma1: a list needs a list of forcing components Omega")
    fp = ForcingParams.validated(sigma, sigma1, omega, Omega, 1, dps=dps)
    if dps is None:
        return scales_of(fp)
    with mpmath.workdps(dps + 10):
        return tuple(+s for s in scales_of(fp, dps + 10))


# =========================================================================== groups
#: the smallest normal float64
_TINY = float(np.finfo(float).tiny)
#: chunk length of the float64 group functions on the (large) nested node arrays
_CHUNK = 16384


class _FGroup:
    """float64 group of one or two Rayleigh scales (closed forms on arrays).

    Its methods underflow on purpose (``exp(-u**2)`` far out): they are only called inside the
    ``np.errstate(under="ignore")`` of :func:`_float_scaled` and :func:`_float_cdf`, so a
    caller's error state never reaches them.
    """

    def __init__(self, scales: Sequence[float]) -> None:
        self.scales = tuple(float(s) for s in scales)
        self.var = sum(s * s for s in self.scales)

    def _uv(self, t: np.ndarray) -> Any:
        a, b = self.scales
        return uv_from_h(t / (math.sqrt(2.0) * a), t / (math.sqrt(2.0) * b))

    def _pos(self, t: np.ndarray) -> np.ndarray:
        """Where the pair's closed forms apply: ``h = t / (sqrt(2) s)`` a normal float for both
        scales. A subnormal ``h`` has lost its digits (``sf`` came out 1.001, or 2 where both
        ``h`` underflow to 0/0); below that the exact values are their limits at ``t = 0`` in
        float64 (cdf and density below ``h**2 / min(s) < 1e-460``, scaled tail 1)."""
        return t / (math.sqrt(2.0) * max(self.scales)) >= _TINY

    def cdf(self, t: np.ndarray) -> np.ndarray:
        t = np.maximum(t, 0.0)
        if len(self.scales) == 1:
            return -np.expm1(-0.5 * (t / self.scales[0]) ** 2)
        out = np.zeros_like(t)
        pos = self._pos(t)
        out[pos] = pq_float(self._uv(t[pos]), "q")
        return out

    def pdf(self, t: np.ndarray) -> np.ndarray:
        out = np.zeros_like(t)
        if len(self.scales) == 1:
            pos = t > 0
            tp = t[pos]
            s = self.scales[0]
            out[pos] = tp / (s * s) * np.exp(-0.5 * (tp / s) ** 2)
            return out
        pos = self._pos(t)
        tp = t[pos]
        uv = self._uv(tp)
        val = 4.0 * uv.u * uv.v / uv.r * np.exp(-uv.e) * i2_float(uv.u, uv.v) / tp
        out[pos] = np.where(np.isfinite(val), val, 0.0)
        return out

    def msf(self, t: np.ndarray) -> np.ndarray:
        """``sf(t) exp(t**2/(2 var))`` (the group's Gaussian factor taken out), ``t > 0``."""
        if len(self.scales) == 1:
            return np.ones_like(t)
        out = np.ones_like(t)
        for i in range(0, t.shape[0], _CHUNK):  # in cache-sized chunks (nested arrays)
            tc = t[i : i + _CHUNK]
            pos = self._pos(tc)
            uv = self._uv(tc[pos])
            u, v = uv.u, uv.v
            b = v * np.exp(-u * u) + u * np.exp(-v * v)
            b += SQRT_PI * u * v * (sc.erf(u) + sc.erf(v))
            out[i : i + _CHUNK][pos] = b / uv.r
        return out

    def mpdf(self, t: np.ndarray) -> np.ndarray:
        """``pdf(t) exp(t**2/(2 var))``."""
        out = np.zeros_like(t)
        if len(self.scales) == 1:
            pos = t > 0
            out[pos] = t[pos] / (self.scales[0] ** 2)
            return out
        pos = self._pos(t)
        tp = t[pos]
        uv = self._uv(tp)
        val = 4.0 * (uv.u / uv.r) * (uv.v / tp) * i2_float(uv.u, uv.v)
        out[pos] = np.where(np.isfinite(val), val, 0.0)
        return out


class _MGroup:
    """mpmath group of one or two Rayleigh scales (closed forms on scalars)."""

    def __init__(self, scales: Sequence[Any]) -> None:
        self.scales = tuple(mpmath.mpf(s) for s in scales)
        self.var = sum(s * s for s in self.scales)

    def _xy(self, t: mpmath.mpf) -> tuple[mpmath.mpf, mpmath.mpf]:
        a, b = self.scales
        return t * t / (2 * a * a), t * t / (2 * b * b)

    def cdf(self, t: mpmath.mpf) -> mpmath.mpf:
        if t <= 0:
            return mpmath.mpf(0)
        if len(self.scales) == 1:
            return -mpmath.expm1(-t * t / (2 * self.scales[0] ** 2))
        return mp_q_from_xy(*self._xy(t))

    def pdf(self, t: mpmath.mpf) -> mpmath.mpf:
        if t <= 0:
            return mpmath.mpf(0)
        if len(self.scales) == 1:
            s = self.scales[0]
            return t / (s * s) * mpmath.exp(-t * t / (2 * s * s))
        x, y = self._xy(t)
        r = mpmath.sqrt(x + y)
        u, v = x / r, y / r
        return 4 * u * v / r * mpmath.exp(-u * v) * mp_i2(u, v) / t

    def msf(self, t: mpmath.mpf) -> mpmath.mpf:
        """``sf(t) exp(t**2/(2 var))`` (all terms positive)."""
        if t <= 0 or len(self.scales) == 1:
            return mpmath.mpf(1)
        x, y = self._xy(t)
        r = mpmath.sqrt(x + y)
        u, v = x / r, y / r
        b = v * mpmath.exp(-u * u) + u * mpmath.exp(-v * v)
        b += mpmath.sqrt(mpmath.pi) * u * v * (mpmath.erf(u) + mpmath.erf(v))
        return b / r

    def mpdf(self, t: mpmath.mpf) -> mpmath.mpf:
        """``pdf(t) exp(t**2/(2 var))``."""
        if t <= 0:
            return mpmath.mpf(0)
        if len(self.scales) == 1:
            return t / self.scales[0] ** 2
        x, y = self._xy(t)
        r = mpmath.sqrt(x + y)
        u, v = x / r, y / r
        return 4 * u * v / r * mp_i2(u, v) / t


def make_groups(scales: Sequence[Any]) -> list[tuple[Any, ...]]:
    """Pairs of adjacent scales after sorting (closed forms; a pair holds comparable scales); a
    leftover single goes second to last, so that the innermost nested integrand uses its cheap
    density."""
    s = sorted(scales, reverse=True)
    groups = [tuple(s[i : i + 2]) for i in range(0, len(s), 2)]
    if len(groups) >= 3 and len(groups[-1]) == 1:
        groups[-2], groups[-1] = groups[-1], groups[-2]
    return groups


# =========================================================================== panels
#: first offsets (in units of the saddle's width ``w``) of the panels around the Gaussian
#: saddle; further panels every 4 widths out to :func:`_saddle_c`'s ``c_max``
_PANEL_C = (0.0, 1.5, 3.0, 5.0, 8.0, 12.0)
#: multiples of each scale at which panels start from the ends of [0, x]
_SCALE_C = (0.5, 2.0, 8.0)
#: the digits the float64 panels resolve
_FLOAT_DIGITS = 16


class _Panels(NamedTuple):
    """Saddle offsets (units of the width ``w``) and scale multiples of the panel breakpoints."""

    sad: list[float]
    mult: list[float]


def _saddle_c(digits: int, n_scales: int, ratio: float) -> _Panels:
    """Saddle offsets ``c`` (both signs, units of ``w``) out to ``c_max``, scale multiples out to
    ``sqrt(2 (digits + 10) ln 10)``.

    Beyond ``c_max`` the Gaussian factor ``exp(-c**2/2)``, times the largest growth of the
    polynomial factors over ``[0, x]`` (below ``(2 + ratio)**(2 n + 1)`` with ``ratio >= x/w``)
    and the length of the interval, is below ``10**-(digits + 10)`` of the peak: the long
    outer panels then carry nothing at the target precision, however large ``x/w`` (a fixed
    ``c_max`` left a long unresolved panel at ``e**-72`` of the peak, fatal beyond 30 digits).
    Likewise the structure of a scale ``s`` (``exp(-t**2/(2 s**2))``) is resolved out to where
    it is below ``10**-(digits + 10)`` (a fixed ``8 s`` left ``e**-32``).
    """
    lr = math.log(2.0 + ratio)
    cmax = math.sqrt(2 * (digits + 10) * math.log(10) + 2 * (2 * n_scales + 2) * lr)
    cs = list(_PANEL_C)
    while cs[-1] < cmax:
        cs.append(cs[-1] + 4.0)
    mmax = math.sqrt(2 * (digits + 10) * math.log(10))
    mult = list(_SCALE_C)
    while mult[-1] < mmax:
        mult.append(mult[-1] + 4.0)
    return _Panels([-c for c in reversed(cs[1:])] + cs, mult)


def _offsets(last: Any, rest: list[Any], mult: list[float]) -> tuple[list[Any], list[Any]]:
    """Scale multiples of the last group (near t = 0) and of the rest (near t = x)."""
    near0 = [c * s for s in last.scales for c in mult]
    nearx = [c * s for g in rest for s in g.scales for c in mult]
    return near0, nearx


def _split(last: Any, rest: list[Any], x: Any, sqrt: Any) -> tuple[Any, Any, Any]:
    """``(t*, x - t*, w)``: the saddle ``t* = x V_B/V`` of ``exp(-t**2/(2 V_B) - (x - t)**2/
    (2 V_A))`` and its width ``w = sqrt(V_A V_B/V)``; the exponent is ``x**2/(2 V) +
    (t - t*)**2/(2 w**2)`` exactly."""
    vb = last.var
    va = sum(g.var for g in rest)
    v = va + vb
    return x * (vb / v), x * (va / v), sqrt(va * (vb / v))  # (va * vb may overflow)


def _tau_panels_float(ts: np.ndarray, xs: np.ndarray, w: float, last: _FGroup,
                      rest: list[_FGroup], cs: _Panels) -> np.ndarray:
    """Sorted breakpoints in ``tau = t - t*``, shape (len(x), K), clipped to [-t*, x - t*]."""
    near0, nearx = _offsets(last, rest, cs.mult)
    cols = [-ts, xs]
    cols += [np.full_like(ts, c * w) for c in cs.sad]
    cols += [a - ts for a in near0]
    cols += [xs - a for a in nearx]
    pts = np.clip(np.stack(cols, axis=1), -ts[:, None], xs[:, None])
    return np.sort(pts, axis=1)


def _conv_scaled_float(groups: list[_FGroup], x: np.ndarray, kind: str, n: int,
                       cs: _Panels) -> np.ndarray:
    """``P(sum > x) exp(x**2/(2 V))`` (kind 'sf') or the density times it ('pdf'), x >= 0.

    With ``tau = t - t*`` the Gaussian factors of the two groups combine exactly into
    ``exp(-x**2/(2 V)) exp(-tau**2/(2 w**2))``: the first is taken out (so nothing underflows
    however far the tail), the second is evaluated from ``tau`` (no cancellation in
    ``t - t*``) and only the smooth scaled group functions see ``t = t* + tau``.
    """
    if len(groups) == 1:
        return groups[0].msf(x) if kind == "sf" else groups[0].mpdf(x)
    last, rest = groups[-1], groups[:-1]
    ts, xs, w = _split(last, rest, x, math.sqrt)
    bp = _tau_panels_float(ts, xs, w, last, rest, cs)
    xg, wg = gauss_legendre(n)
    a, b = bp[:, :-1], bp[:, 1:]
    h = 0.5 * (b - a)
    tau = (0.5 * (a + b))[..., None] + h[..., None] * xg  # (nx, panels, n)
    t = ts[:, None, None] + tau
    y = np.maximum(xs[:, None, None] - tau, 0.0)
    inner = _conv_scaled_float(rest, y.ravel(), kind, n, cs).reshape(tau.shape)
    f = last.mpdf(t.ravel()).reshape(tau.shape) * inner * np.exp(-0.5 * (tau / w) ** 2)
    out = np.sum(h * (f @ wg), axis=1)
    if kind == "sf":
        out = out + last.msf(x) * np.exp(-0.5 * (xs / w) ** 2)
    return out


def _panels_float(x: np.ndarray, last: _FGroup, rest: list[_FGroup], cs: _Panels
                  ) -> np.ndarray:
    """Sorted panel breakpoints in ``t``, shape (len(x), K), clipped to [0, x]."""
    tstar, _, w = _split(last, rest, x, math.sqrt)
    near0, nearx = _offsets(last, rest, cs.mult)
    cols = [np.zeros_like(x), x]
    cols += [tstar + w * c for c in cs.sad]
    cols += [np.full_like(x, a) for a in near0]
    cols += [x - a for a in nearx]
    pts = np.clip(np.stack(cols, axis=1), 0.0, x[:, None])
    return np.sort(pts, axis=1)


def _conv_float(groups: list[_FGroup], x: np.ndarray, n: int, cs: _Panels) -> np.ndarray:
    """``P(sum <= x)`` on array x (no Gaussian factor to take out)."""
    if len(groups) == 1:
        return groups[0].cdf(x)
    last, rest = groups[-1], groups[:-1]
    bp = _panels_float(np.maximum(x, 0.0), last, rest, cs)
    xg, wg = gauss_legendre(n)
    a, b = bp[:, :-1], bp[:, 1:]
    h = 0.5 * (b - a)
    t = (0.5 * (a + b))[..., None] + h[..., None] * xg  # (nx, panels, n)
    xr = np.broadcast_to(x[:, None, None], t.shape)
    inner = _conv_float(rest, (xr - t).ravel(), n, cs).reshape(t.shape)
    f = last.pdf(t.ravel()).reshape(t.shape) * inner
    return np.sum(h * (f @ wg), axis=1)


_MP_GL_CACHE: dict[tuple[int, int], tuple[list[mpmath.mpf], list[mpmath.mpf]]] = {}


def _mp_gl(n: int) -> tuple[list[mpmath.mpf], list[mpmath.mpf]]:
    key = (n, mpmath.mp.prec)
    if key not in _MP_GL_CACHE:
        xs, ws = mpmath.mp.gauss_quadrature(n, "legendre")
        _MP_GL_CACHE[key] = (list(xs), list(ws))
    return _MP_GL_CACHE[key]


def _conv_scaled_mp(groups: list[_MGroup], x: mpmath.mpf, kind: str, n: int,
                    cs: _Panels) -> mpmath.mpf:
    """mpmath :func:`_conv_scaled_float` (one threshold ``x``)."""
    if len(groups) == 1:
        return groups[0].msf(x) if kind == "sf" else groups[0].mpdf(x)
    if x <= 0:
        return mpmath.mpf(1) if kind == "sf" else mpmath.mpf(0)
    last, rest = groups[-1], groups[:-1]
    ts, xs, w = _split(last, rest, x, mpmath.sqrt)
    near0, nearx = _offsets(last, rest, cs.mult)
    raw = [c * w for c in cs.sad] + [a - ts for a in near0] + [xs - a for a in nearx]
    pts = sorted({-ts, xs} | {min(max(p, -ts), xs) for p in raw})
    xg, wg = _mp_gl(n)
    total = mpmath.mpf(0)
    for a, b in itertools.pairwise(pts):
        h = (b - a) / 2
        m = (a + b) / 2
        s = mpmath.mpf(0)
        for xi, wi in zip(xg, wg, strict=True):
            tau = m + h * xi
            s += (wi * last.mpdf(ts + tau) * _conv_scaled_mp(rest, xs - tau, kind, n, cs)
                  * mpmath.exp(-(tau / w) ** 2 / 2))
        total += h * s
    if kind == "sf":
        total += last.msf(x) * mpmath.exp(-(xs / w) ** 2 / 2)
    return total


def _conv_mp(groups: list[_MGroup], x: mpmath.mpf, n: int, cs: _Panels) -> mpmath.mpf:
    """``P(sum <= x)`` at one threshold."""
    if len(groups) == 1:
        return groups[0].cdf(x)
    if x <= 0:
        return mpmath.mpf(0)
    last, rest = groups[-1], groups[:-1]
    tstar, _, w = _split(last, rest, x, mpmath.sqrt)
    near0, nearx = _offsets(last, rest, cs.mult)
    raw = [tstar + c * w for c in cs.sad] + list(near0) + [x - a for a in nearx]
    pts = sorted({mpmath.mpf(0), x} | {min(max(p, 0), x) for p in raw})
    xg, wg = _mp_gl(n)
    total = mpmath.mpf(0)
    for a, b in itertools.pairwise(pts):
        h = (b - a) / 2
        m = (a + b) / 2
        s = mpmath.fsum(
            wi * last.pdf(m + h * xi) * _conv_mp(rest, x - (m + h * xi), n, cs)
            for xi, wi in zip(xg, wg, strict=True)
        )
        total += h * s
    return total


#: float64 rule orders whose difference is the quadrature error estimate
_N_LO, _N_HI = 12, 24
_EPS = float(np.finfo(float).eps)
#: float64 quadrature range: ``x <= _X_QUAD max(s)`` (the scaled group functions, powers of
#: ``x/s`` up to the 8th, stay far from overflow)
_X_QUAD = 1e30
#: Laplace regime: ``x min(s) >= _X_LAPLACE V``; the neglected relative corrections of the
#: asymptotic log-tail are ``O((V/(x s_i))**2) <= 1e-10`` absolute on ``log P(S > x) <= -5e9``
#: (whose ulp is ~1e-6): within 2 ulp of mpmath from there on (measured for K = 1e5 .. 1e7 on
#: five sets of 3 to 5 scales, spread up to 3e4), as the quadrature is
_X_LAPLACE = 1e5


def _regions(scales: Sequence[float], x: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Masks ``(laplace, out)`` of the float64 sf/pdf: the asymptotic regime, and the rest of
    the region beyond the quadrature range (only for scales spread over > 1e21) or, for one or
    two scales (closed forms, no quadrature), beyond ``x/min(s) = 1e150``."""
    var = math.fsum(s * s for s in scales)
    with np.errstate(under="ignore", over="ignore"):   # a subnormal or huge x: no matter
        laplace = x * min(scales) >= _X_LAPLACE * var
    lim = _X_QUAD * max(scales) if len(scales) > 2 else 1e150 * min(scales)
    out = (x > lim) & ~laplace
    return laplace, out


def _float_scaled(scales: Sequence[float], x: np.ndarray, kind: str
                  ) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """``(m, err_m, E)`` with ``sf`` (or ``pdf``) ``= m exp(-E)``, ``E = x**2/(2 V)``, for
    ``0 <= x`` in the quadrature range (see :func:`_regions`)."""
    groups = [_FGroup(g) for g in make_groups(scales)]
    var = math.fsum(s * s for s in scales)
    xp = np.maximum(x, 0.0)
    with np.errstate(under="ignore"):   # exp(-u**2) of the groups, x**2 of a tiny x
        e = xp * xp / (2.0 * var)
        if len(groups) == 1:
            m = groups[0].msf(xp) if kind == "sf" else groups[0].mpdf(xp)
            return m, 4 * _EPS * np.abs(m), e
        ratio = 2.0 * float(np.max(xp, initial=0.0)) / min(scales)
        cs = _saddle_c(_FLOAT_DIGITS, len(scales), ratio)
        lo = _conv_scaled_float(groups, xp, kind, _N_LO, cs)
        hi = _conv_scaled_float(groups, xp, kind, _N_HI, cs)
        return hi, np.abs(hi - lo) + 4 * _EPS * np.abs(hi) * len(scales), e


def _float_with_error(scales: Sequence[float], x: np.ndarray, kind: str
                      ) -> tuple[np.ndarray, np.ndarray]:
    laplace, out = _regions(scales, x)
    far = laplace | out
    if far.any():
        # E >= 5e17 there: sf and pdf are exactly 0 in float64 (cdf: 1)
        val = np.full(x.shape, 1.0 if kind == "cdf" else 0.0)
        err = np.zeros(x.shape)
        if (~far).any():
            val[~far], err[~far] = _float_with_error(scales, x[~far], kind)
        return val, err
    if kind == "cdf":
        # 1 - sf where sf <= 1/2 (no cancellation; the tail of the cdf's own quadrature would
        # need panels out to the saddle), the quadrature of the cdf below
        sf, err = _float_with_error(scales, x, "sf")
        low = sf > 0.5
        err = err + np.minimum(_EPS, sf)  # the rounding of 1 - sf (1 is a float)
        sf = 1.0 - sf
        if low.any():
            sf[low], err[low] = _float_cdf(scales, x[low])
        return sf, err
    with np.errstate(under="ignore"):   # exp(-E) far out
        m, err_m, e = _float_scaled(scales, x, kind)
        g = np.exp(-e)
        hi = m * g
        # rounding: exp(-E) carries ~E * few eps from the roundings of its exponent
        err = err_m * g + 4 * _EPS * np.abs(hi) * (len(scales) + 2 * e)
    return hi, err


def _float_cdf(scales: Sequence[float], x: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """``P(S <= x)`` and its error by the quadrature of the cdf (where it is below ~1/2)."""
    with np.errstate(under="ignore"):   # the Gaussian factors of the groups far out
        groups = [_FGroup(g) for g in make_groups(scales)]
        if len(groups) == 1:
            val = groups[0].cdf(x)
            return val, 4 * _EPS * np.abs(val) * (2 + np.abs(np.log(np.maximum(val, 1e-300))))
        ratio = 2.0 * float(np.max(x, initial=0.0)) / min(scales)
        cs = _saddle_c(_FLOAT_DIGITS, len(scales), ratio)
        lo = _conv_float(groups, x, _N_LO, cs)
        hi = _conv_float(groups, x, _N_HI, cs)
        return hi, np.abs(hi - lo) + 4 * _EPS * np.abs(hi) * (len(scales) + 2)


def _float_logsf(scales: Sequence[float], x: np.ndarray) -> np.ndarray:
    """``log P(S > x)`` where ``P(S > x) <= 1/2``: ``log m - E`` (no underflow), the Laplace
    asymptotic beyond the quadrature range."""
    laplace, out = _regions(scales, x)
    if out.any():
        i = int(np.argmax(out))
        raise ValueError(f"x = {float(x[i])!r}: log sf of Rayleigh scales spread over more than 21 "
                         "orders of magnitude is beyond the float64 range; use dps=")
    res = np.empty(x.shape)
    q = ~laplace
    if q.any():
        m, _, e = _float_scaled(scales, x[q], "sf")
        res[q] = np.log(m) - e   # m > 0: the scaled tail, a polynomial-like factor
    if laplace.any():
        res[laplace] = _laplace_logsf(scales, x[laplace])
    return res


def _laplace_logsf(scales: Sequence[float], x: np.ndarray) -> np.ndarray:
    r"""Leading Laplace asymptotic of ``log P(S > x)`` for ``x min(s_i) >> sum s_i**2``.

    The density of the sum concentrates at ``r_i = x s_i**2/V`` (``V = sum s_i**2``); the
    Gaussian integral over the hyperplane ``sum r_i = x`` gives ``f_S(x) ~ (x/V)**n
    (2 pi)**((n-1)/2) prod(s_i) V**(-1/2) exp(-x**2/(2V))`` and ``P(S > x) ~ f_S(x) V/x``, with
    relative corrections ``O(sum_i (V/(x s_i))**2)``.
    """
    n = len(scales)
    var = math.fsum(s * s for s in scales)
    const = (math.fsum(math.log(s) for s in scales) - math.log(var) / 2
             + (n - 1) * math.log(2 * math.pi) / 2)
    # x = inf is a threshold beyond float64 after the rescaling of _float_normalized: log P is
    # -inf there (as it is where the square overflows), not inf - inf
    out = np.full(x.shape, -np.inf)
    fin = np.isfinite(x)
    xf = x[fin]
    with np.errstate(over="ignore"):
        out[fin] = (-(xf / math.sqrt(2 * var)) ** 2 + (n - 1) * (np.log(xf) - math.log(var))
                    + const)
    return out


def _mp_scaled_with_error(scales: Sequence[Any], x: mpmath.mpf, kind: str, dps: int
                          ) -> tuple[mpmath.mpf, mpmath.mpf, mpmath.mpf]:
    """``(m, err_m, E)`` with ``sf`` (or ``pdf``) ``= m exp(-E)``, ``E = x**2/(2 V)``, ``x >
    0``, ``m`` correct to ``dps`` digits (call inside the working precision)."""
    # E at the caller's precision (its exp needs log10(E) guard digits), the scaled quadrature
    # at dps + 12 digits: m is a smooth function of x and the scales, and the Gaussian factors
    # inside it only need their absolute accuracy relative to the peak
    e = x * x / (2 * mpmath.fsum(s * s for s in scales))
    with mpmath.workdps(dps + 12):
        groups = [_MGroup(g) for g in make_groups(scales)]
        if len(groups) == 1:
            m = groups[0].msf(x) if kind == "sf" else groups[0].mpdf(x)
            return m, abs(m) * mpmath.mpf(10) ** (-dps - 10), e
        cs = _saddle_c(dps, len(scales), float(2 * x / min(scales)))
        cur, err = _converge(lambda n: _conv_scaled_mp(groups, x, kind, n, cs), dps)
    return cur, err, e


def _converge(fn: Any, dps: int) -> tuple[mpmath.mpf, mpmath.mpf]:
    """Raise the rule order until two successive orders agree to ``dps + 3`` digits."""
    tol = mpmath.mpf(10) ** (-dps - 3)
    n = 6 + dps // 4
    prev = fn(n)
    err = abs(prev)
    for _ in range(8):
        n2 = (3 * n) // 2 + 2
        cur = fn(n2)
        err = abs(cur - prev)
        if err <= tol * abs(cur):
            return cur, err
        prev, n = cur, n2
    raise ArithmeticError(  # pragma: no cover - the panels resolve every scale
        f"Rayleigh sum: the quadrature did not converge to {dps} digits (error {err})")


def _upper_half(scales: Sequence[Any], x: mpmath.mpf) -> bool:
    """Whether ``P(S > x)`` may be ``<= 0.55`` (the float64 value decides; True when it cannot
    be formed): the mpmath cdf is then ``1 - sf``, else its own quadrature (both are accurate
    near 1/2, only the far tail needs ``1 - sf``)."""
    fs = [float(s) for s in scales]
    xf = float(x)
    if not all(1e-150 < s < 1e150 for s in fs) or not 0 < xf < 1e150:
        return xf > 0
    return bool(_float_with_error(fs, np.array([xf]), "sf")[0][0] <= 0.55)


def _mp_with_error(scales: Sequence[Any], x: mpmath.mpf, kind: str, dps: int
                   ) -> tuple[mpmath.mpf, mpmath.mpf]:
    """Value and error estimate at ``dps`` digits (call inside the working precision)."""
    if kind != "cdf":
        if x <= 0:
            return (mpmath.mpf(1) if kind == "sf" else mpmath.mpf(0)), mpmath.mpf(0)
        m, err, e = _mp_scaled_with_error(scales, x, kind, dps)
        g = mpmath.exp(-e)
        return m * g, err * g
    if _upper_half(scales, x):
        sf, err = _mp_with_error(scales, x, "sf", dps)
        if sf <= 0.5:  # no cancellation in 1 - sf (see _float_with_error)
            return 1 - sf, err
    groups = [_MGroup(g) for g in make_groups(scales)]
    if len(groups) == 1:
        val = groups[0].cdf(x)
        return val, abs(val) * mpmath.mpf(10) ** (-dps - 10)
    cs = _saddle_c(dps, len(scales), float(2 * max(x, 0) / min(scales)))
    return _converge(lambda n: _conv_mp(groups, x, n, cs), dps)


# =========================================================================== the distribution
class RayleighSum:
    r"""The sum ``S = sum_i R_i`` of independent Rayleigh variables ``R_i`` of scales ``s_i``.

    ``R_i`` has density ``(r/s_i**2) exp(-r**2/(2 s_i**2))``; with the scales of
    :func:`rayleigh_scales` ``P(S > d)`` is the impact probability of eq. (22) (eq. 27 for two
    scales). Methods follow ``scipy.stats``: ``pdf, cdf, sf, logcdf, logsf`` take a float or
    an array of thresholds ``x`` (float64, vectorised; ``x <= 0`` gives ``sf = 1``; an empty
    array gives an empty result) or, with ``dps=``, mpmath values correct to ``dps`` digits.

    Parameters
    ----------
    scales : sequence of real
        Scales ``s_i > 0`` (decimal strings exact, floats/mpf at their binary value).

    >>> S = RayleighSum([0.5, 0.3, 0.2])
    >>> abs(S.sf(1.0) + S.cdf(1.0) - 1) < 1e-15
    True
    >>> abs(S.sf(1.0) / float(S.sf(1.0, dps=30)) - 1) < 1e-14
    True
    >>> float(S.mean()) == (0.5 + 0.3 + 0.2) * math.sqrt(math.pi / 2)
    True
    """

    def __init__(self, scales: Any) -> None:
        if isinstance(scales, (str, bytes)) or not is_array(scales):
            raise TypeError(f"scales must be a sequence of Rayleigh scales, got {scales!r}")
        arr = np.asarray(scales, dtype=object).ravel()
        if arr.size == 0:
            raise ValueError("scales: need at least one Rayleigh scale, got an empty sequence")
        exact = []
        for i, s in enumerate(arr):
            exact.append(rational_arg(f"scales[{i}]", s))
        self._exact: tuple[Fraction, ...] = tuple(exact)
        self.scales = np.array([_to_float(f) for f in exact])

    def __repr__(self) -> str:
        return f"RayleighSum({[float(s) for s in self.scales]!r})"

    # ---- moments
    def mean(self, *, dps: int | None = None) -> Any:
        """``E[S] = sqrt(pi/2) sum s_i``."""
        dps = check_dps(dps, allow_none=True)
        if dps is None:
            return float(math.sqrt(math.pi / 2) * math.fsum(self._float_scales()))
        with mpmath.workdps(dps + 10):
            val = mpmath.sqrt(mpmath.pi / 2) * mpmath.fsum(mpf_of(s) for s in self._exact)
        return +val

    def var(self, *, dps: int | None = None) -> Any:
        """``Var S = (2 - pi/2) sum s_i**2``."""
        dps = check_dps(dps, allow_none=True)
        if dps is None:
            return float((2 - math.pi / 2) * math.fsum(s * s for s in self._float_scales()))
        with mpmath.workdps(dps + 10):
            val = (2 - mpmath.pi / 2) * mpmath.fsum(mpf_of(s) ** 2 for s in self._exact)
        return +val

    def std(self, *, dps: int | None = None) -> Any:
        """Standard deviation ``sqrt(Var S)``."""
        v = self.var(dps=dps)
        return math.sqrt(v) if dps is None else mpmath.sqrt(v)

    def rvs(self, size: Any = None, random_state: Any = None) -> Any:
        """Random draws (float64): ``sum_i Rayleigh(s_i)`` with numpy's generator.

        ``random_state``: None, an int seed or a ``numpy.random.Generator``.
        """
        rng = (random_state if isinstance(random_state, np.random.Generator)
               else np.random.default_rng(check_seed(random_state, "random_state")))
        sc = self._float_scales()
        return sum(rng.rayleigh(scale=s, size=size) for s in sc)   # a float for size=None

    # ---- probabilities
    def sf(self, x: Any, *, dps: int | None = None) -> Any:
        """``P(S > x)``."""
        return self._eval(x, "sf", dps)

    def cdf(self, x: Any, *, dps: int | None = None) -> Any:
        """``P(S <= x)``."""
        return self._eval(x, "cdf", dps)

    def pdf(self, x: Any, *, dps: int | None = None) -> Any:
        """Density of ``S`` at ``x``."""
        return self._eval(x, "pdf", dps)

    def logsf(self, x: Any, *, dps: int | None = None) -> Any:
        """``log P(S > x)``; ``log1p(-cdf)`` where ``sf > 1/2`` (relative accuracy kept)."""
        return self._eval(x, "logsf", dps)

    def logcdf(self, x: Any, *, dps: int | None = None) -> Any:
        """``log P(S <= x)``; ``log1p(-sf)`` where ``cdf > 1/2``."""
        return self._eval(x, "logcdf", dps)

    def probability(self, x: Any, *, tail: str = "upper", dps: int | None = None
                    ) -> RayleighSumResult:
        """``P(S > x)`` (``tail="upper"``) or ``P(S <= x)`` with an error estimate."""
        tail = check_choice(tail, "tail", ("upper", "lower"))
        kind = "sf" if tail == "upper" else "cdf"
        dps = check_dps(dps, allow_none=True)
        method = ("closed form" if len(self._exact) <= 2 else
                  f"nested Gauss-Legendre ({len(make_groups(self._exact)) - 1}-D)")
        if dps is None:
            xa = float_arg("x", x, positive=False)
            if xa.ndim:
                raise TypeError("x must be a scalar here (use sf/cdf for arrays)")
            sc, xn, _ = _float_normalized(self._float_scales(), xa.reshape(1))
            val, err = _float_with_error(sc, xn, kind)
            return RayleighSumResult(float(val[0]), float(err[0]), method)
        with mpmath.workdps(dps + 15 + self._exp_digits(x)):
            xm = _mp_x(x)
            val, err = _mp_with_error([mpf_of(s) for s in self._exact], xm, kind, dps)
            with mpmath.workdps(dps):   # returned at dps digits (the guard digits are not
                out = +val              # correct digits): the estimate includes that rounding
            err = err + abs(out - val)
        with mpmath.workdps(dps):
            return RayleighSumResult(out, +err, method)

    # ---- internals
    def _exp_digits(self, x: Any) -> int:
        """Extra digits for ``exp(-E)``, ``E ~ x**2/(2 sum s**2)``, to keep its relative
        accuracy (E ~ 1e6 costs 6 digits)."""
        with mpmath.workprec(53):
            xm = _mp_x(x)   # a sympy expression too (evaluated), not taken as 0
            var = mpmath.fsum(mpf_of(s) ** 2 for s in self._exact)
            e = xm * xm / (2 * var) if xm > 0 else mpmath.mpf(0)
        if e > MAX_EXPONENT:
            raise ValueError(
                f"x: P(S > x) = exp(-E) with E ~ {mpmath.nstr(e, 3)} above the cap MAX_EXPONENT "
                f"= {MAX_EXPONENT:.3g} of the mpmath evaluation (exp(-E) would need log10(E) "
                "guard digits); logsf has no cap")
        return int(mpmath.log10(e)) + 1 if e > 1 else 0

    def _float_scales(self) -> list[float]:
        bad = ~((self.scales > 0) & np.isfinite(self.scales))
        if bad.any():
            i = int(np.argmax(bad))
            raise ValueError(f"scales[{i}] = {short_value(self._exact[i])} is outside the "
                             "float64 range; use dps=")
        return [float(s) for s in self.scales]

    def _eval(self, x: Any, kind: str, dps: Any) -> Any:
        dps = check_dps(dps, allow_none=True)
        if dps is None:
            xa = (check_array(x, "x", allow_empty=True) if is_array(x)
                  else float_arg("x", x, positive=False))
            flat = xa.reshape(-1)
            out = self._float_kind(flat, kind)
            return float(out[0]) if xa.ndim == 0 else out.reshape(xa.shape)
        if is_array(x):
            xs = np.asarray(x, dtype=object)
            out = np.empty(xs.shape, dtype=object)
            for idx in np.ndindex(xs.shape):
                out[idx] = self._eval(xs[idx], kind, dps)
            return out
        # exp(-E) needs log10(E) guard digits; log sf = log m - E does not (its absolute
        # error E 10**-prec is relative 10**-prec), so its cost does not grow with E
        guard = 15 + (0 if kind == "logsf" else self._exp_digits(x))
        with mpmath.workdps(dps + guard):
            xm = _mp_x(x)
            scales = [mpf_of(s) for s in self._exact]
            if kind in ("sf", "cdf", "pdf"):
                val = _mp_with_error(scales, xm, kind, dps)[0]
            elif kind == "logsf":
                # log P(S > x) = log m - E: no exp(-E) (and no guard digits for it) needed
                if xm <= 0:
                    val = mpmath.mpf(0)
                else:
                    m, _, e = _mp_scaled_with_error(scales, xm, "sf", dps + 5)
                    val = mpmath.log(m) - e
                    if val > -mpmath.log(2):
                        val = mpmath.log1p(-_mp_with_error(scales, xm, "cdf", dps + 5)[0])
            else:
                v = _mp_with_error(scales, xm, "cdf", dps + 5)[0]
                if v > 0.5:
                    val = mpmath.log1p(-_mp_with_error(scales, xm, "sf", dps + 5)[0])
                else:
                    val = mpmath.log(v) if v > 0 else mpmath.mpf("-inf")
        with mpmath.workdps(dps):
            return +val

    def _float_kind(self, x: np.ndarray, kind: str) -> np.ndarray:
        sc0 = self._float_scales()
        sc, x, e = _float_normalized(sc0, x)
        if kind in ("sf", "cdf", "pdf"):
            val = _float_with_error(sc, x, kind)[0]
            if kind == "pdf" and e:   # the density scales by 2**-e (it may underflow; it
                with np.errstate(under="ignore"):   # is below 1/s_max, so it cannot overflow)
                    return np.ldexp(val, -e)
            return val
        if kind == "logsf":
            out = _float_logsf(sc, x)
            big = out > -math.log(2.0)
            if big.any():
                out[big] = np.log1p(-_float_with_error(sc, x[big], "cdf")[0])
            return out
        tiny = (x > 0) & (x <= _X_SMALL * min(sc))
        out = np.empty(x.shape)
        if tiny.any():   # ratios only: the unscaled values (x / 2**e may be subnormal)
            out[tiny] = _float_small_logcdf(sc0, np.ldexp(x[tiny], e))
        rest = ~tiny
        v = _float_with_error(sc, x[rest], "cdf")[0]
        big = v > 0.5
        with np.errstate(divide="ignore"):
            r = np.log(v)
            if big.any():
                r[big] = np.log1p(-_float_with_error(sc, x[rest][big], "sf")[0])
        out[rest] = r
        return out


#: the float64 routes square the scales and x: beyond ``2**+-200`` both are scaled by the power
#: of two ``2**-e`` that brings the largest scale to [1/2, 1) (exact; the probabilities are
#: scale-free, the density scales by ``2**-e``)
_FLOAT_SCALE_RANGE = 2.0**200


def _float_normalized(scales: list[float], x: np.ndarray) -> tuple[list[float], np.ndarray, int]:
    """``(scales, x, e)`` scaled by ``2**-e`` when the largest scale is outside
    ``[1/_FLOAT_SCALE_RANGE, _FLOAT_SCALE_RANGE]`` (else ``e = 0`` and the inputs as they are).
    A scale that would then be below ``2**-500`` (its square below the normal float64 range)
    is refused (``dps=`` handles it)."""
    top = max(scales)
    if 1 / _FLOAT_SCALE_RANGE <= top <= _FLOAT_SCALE_RANGE:
        return scales, x, 0
    e = math.frexp(top)[1]
    out = [math.ldexp(s, -e) for s in scales]
    if min(out) < 2.0**-500:
        raise ValueError(f"the Rayleigh scales spread over more than float64 resolves here "
                         f"({min(scales):.3g} to {top:.3g}): use dps=")
    with np.errstate(under="ignore", over="ignore"):   # x beyond the range: inf (far tail)
        return out, np.ldexp(x, -e), e


#: lower tail: ``x <= _X_SMALL min(s)`` takes the leading power of ``P(S <= x)`` (relative
#: corrections ``<= sum_i x**2/(2 s_i**2) <= 1e-17``), where the cdf itself may underflow
_X_SMALL = 1e-9


def _float_small_logcdf(scales: Sequence[float], x: np.ndarray) -> np.ndarray:
    r"""``log P(S <= x) = sum_i 2 log(x/s_i) - log((2n)!)`` for ``x << min(s_i)``: each density
    is ``r/s_i**2 (1 + O(r**2/s_i**2))`` near 0 and the ``n``-fold convolution of ``r`` is
    ``x**(2n-1)/(2n-1)!``."""
    out = np.full(x.shape, -math.lgamma(2 * len(scales) + 1))
    with np.errstate(under="ignore", divide="ignore"):
        for s in scales:
            q = x / s
            out += 2 * np.where(q > 1e-300, np.log(q), np.log(x) - math.log(s))
    return out


def _to_float(fr: Fraction) -> float:
    try:
        return float(fr)
    except OverflowError:
        return math.inf


def _mp_x(x: Any) -> mpmath.mpf:
    """A finite real threshold as an mpf at the current precision (``<= 0`` allowed)."""
    fr = to_rational(x, "x")
    if fr is None:
        return mpmath.mpf(x.evalf(mpmath.mp.dps + 5))
    return mpf_of(fr) if fr > 0 else mpmath.mpf(fr.numerator) / fr.denominator


def rayleigh_sum_probability(
    scales: Sequence[Any], d: Any = 1, *, tail: str = "upper", dps: int | None = None
) -> RayleighSumResult:
    r"""``P(sum_i R_i > d)`` (``tail="upper"``) or ``P(sum_i R_i <= d)`` (``tail="lower"``).

    ``R_i`` are independent Rayleigh variables of scales ``scales[i]``; eq. (22) with the scales
    of :func:`rayleigh_scales`. A thin function over :meth:`RayleighSum.probability` (see
    :class:`RayleighSum` for the method). ``M + 1 <= 2``: closed form; 3-4 scales: one
    quadrature; 5-6: two nested quadratures.

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
        two agree to ``dps + 3`` digits).

    Returns
    -------
    RayleighSumResult
        ``value``, ``error`` (estimate: difference of two rule orders, plus rounding), ``method``.

    >>> res = rayleigh_sum_probability([0.5, 0.3, 0.2], 1.0)
    >>> ref = rayleigh_sum_probability([0.5, 0.3, 0.2], 1.0, dps=25)
    >>> abs(res.value - float(ref.value)) < 1e-15, res.error < 1e-14
    (True, True)
    """
    check_choice(tail, "tail", ("upper", "lower"))
    S = RayleighSum(scales)
    rational_arg("d", d)
    return S.probability(d, tail=tail, dps=dps)

