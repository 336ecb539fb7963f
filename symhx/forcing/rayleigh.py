r"""The sum of independent Rayleigh variables (eq. 22) as a distribution object.

``S = R_1 + ... + R_n`` with ``R_i`` Rayleigh of scale ``s_i`` (density ``(r/s**2)
exp(-r**2/(2 s**2))``), ``n <= MAX_SCALES``. One or two scales have closed forms (eq. 27 and its
complement, see :mod:`symhx.forcing`); more scales (and a pair whose ratio of scales to ``x`` is
beyond the closed form's float64 range) are computed by the inversion of the Laplace transform
of the sum along a saddle-point contour (:mod:`symhx.forcing.inversion`): float64 vectorised
over thresholds, Arb balls for ``dps``, both tails with their relative accuracy, any spread of
the scales (a negligible scale is evaluated, with its tiny effect, never dropped), an error
estimate that includes the quadrature, the truncation and the rounding. The tail below 1/2 is
the one integrated (``x >= E[S]``: the upper tail, else the lower one); the other is ``1 -``
it; ``log`` of a tail above 1/2 is ``log1p`` of the other one.

float64 also has two asymptotic regions where the value is exact to far below an ulp: below
``x = 1e-9 min(s)`` the leading power of the lower tail (:func:`_float_small_logcdf`), beyond
``x min(s) = 1e5 V`` the Laplace asymptotic of ``log P(S > x)`` (:func:`_laplace_logsf`).

The work is bounded before it starts: at most ``MAX_SCALES`` scales (both paths), ``rvs`` at most
``symhx.validation.MAX_SAMPLE_SIZE`` draws (the limit of every ``rvs``), the mpmath path
``MAX_MP_SUM_WORK`` (scales times digits) for three or more scales, and ``exp(-E)`` up to
``MAX_EXPONENT``.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from fractions import Fraction
from typing import Any, NamedTuple

import mpmath
import numpy as np
from scipy import special

from symhx._mpctx import mp as thread_mp
from symhx.forcing import arguments as _arguments  # MAX_SCALES, read when called
from symhx.forcing import kernels_mp as _kernels_mp  # MAX_EXPONENT, read when called
from symhx.forcing.arguments import (
    ForcingParams,
    exported,
    float_arg,
    is_array,
    is_components,
    mp_arg,
    mpf_of,
    rational_arg,
)
from symhx.forcing.inversion import invert_arb, invert_float
from symhx.forcing.kernels_float import (
    SQRT_PI,
    delta_float,
    i2_float,
    pq_float,
    uv_from_h,
)
from symhx.forcing.kernels_mp import mp_i2, mp_q_from_xy
from symhx.validation import (
    InputError,
    check_array,
    check_choice,
    check_dps,
    check_seed,
    check_size,
    float64_refusal,
    mpf_to_fraction,
    short_value,
    to_rational,
)

__all__ = [
    "MAX_MP_SUM_WORK",
    "RayleighSum",
    "RayleighSumResult",
    "rayleigh_scales",
    "rayleigh_sum_probability",
    "scales_of",
]

#: the mpmath path of three or more scales costs about (distinct scales) x (digits) evaluations
#: of ``erfc`` at the working precision: their product is at most this (64 scales at 250
#: digits, 8 at 2000; measured ~1 minute at the cap)
MAX_MP_SUM_WORK = 16_000


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
                raise InputError(f"{_om_name(fp, i)}: resonance Omega == omega (infinite forced "
                                 "amplitude)")
            # |omega**2 - Omega**2| = |omega - Omega| (omega + Omega), divided one factor at a
            # time: the product under/overflows (or is subnormal, with lost digits) for tiny or
            # huge frequencies whose scale is still a float64 (or +inf)
            out.append(scale / abs(omf - Omf) / (omf + Omf))
        return tuple(out)
    with thread_mp().workdps(work_dps):
        s0 = mp_arg("sigma", fp.sigma)
        om = mp_arg("omega", fp.omega)
        out = [thread_mp().sqrt(2) * s0]
        for i, (Om, s1) in enumerate(zip(omegas, s1s, strict=True)):
            om2 = 2 if Om is None else mp_arg("Omega", Om) ** 2
            delta = om * om - om2
            if delta == 0:
                raise InputError(f"{_om_name(fp, i)}: resonance Omega == omega (infinite forced "
                                 "amplitude)")
            s1v = s0 if s1 is None else mp_arg("sigma1", s1)
            out.append(thread_mp().sqrt(2) * s1v / abs(delta))
        return tuple(out)


def _om_name(fp: ForcingParams, i: int) -> str:
    return f"Omega[{i}]" if fp.components else "Omega"


@exported
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
    with thread_mp().workdps(dps + 10):
        return tuple(+s for s in scales_of(fp, dps + 10))


# =========================================================================== float64
#: the smallest normal float64
_TINY = float(np.finfo(float).tiny)
#: chunk length of the pair's closed forms on long arrays
_CHUNK = 16384
_EPS = float(np.finfo(float).eps)
#: a pair of scales takes its closed form where ``x/(sqrt(2) s)`` is in this range for both
#: scales (the fast range of the one-component kernels); beyond it (one scale negligible against
#: ``x``, or both far above it) the inversion, which has no range limits
_PAIR_RANGE = (1e-75, 1e75)
#: lower tail: ``x <= _X_SMALL min(s)`` takes the leading power of ``P(S <= x)`` (relative
#: corrections ``<= sum_i x**2/(2 s_i**2) <= 1e-17``), where the cdf itself may underflow
_X_SMALL = 1e-9
#: Laplace regime: ``x min(s) >= _X_LAPLACE V``; the neglected relative corrections of the
#: asymptotic log-tail are ``O((V/(x s_i))**2) <= 1e-10`` absolute on ``log P(S > x) <= -5e9``
#: (whose ulp is ~1e-6)
_X_LAPLACE = 1e5


# =========================================================================== groups
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

    @exported
    def cdf(self, t: np.ndarray) -> np.ndarray:
        t = np.maximum(t, 0.0)
        if len(self.scales) == 1:
            return -np.expm1(-0.5 * (t / self.scales[0]) ** 2)
        out = np.zeros_like(t)
        pos = self._pos(t)
        out[pos] = pq_float(self._uv(t[pos]), "q")
        return out

    @exported
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
            b += SQRT_PI * u * v * (special.erf(u) + special.erf(v))
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
        self.scales = tuple(thread_mp().mpf(s) for s in scales)
        self.var = sum(s * s for s in self.scales)

    def _xy(self, t: mpmath.mpf) -> tuple[mpmath.mpf, mpmath.mpf]:
        a, b = self.scales
        return t * t / (2 * a * a), t * t / (2 * b * b)

    def cdf(self, t: mpmath.mpf) -> mpmath.mpf:
        if t <= 0:
            return thread_mp().mpf(0)
        if len(self.scales) == 1:
            return -thread_mp().expm1(-t * t / (2 * self.scales[0] ** 2))
        return mp_q_from_xy(*self._xy(t))

    def pdf(self, t: mpmath.mpf) -> mpmath.mpf:
        if t <= 0:
            return thread_mp().mpf(0)
        if len(self.scales) == 1:
            s = self.scales[0]
            return t / (s * s) * thread_mp().exp(-t * t / (2 * s * s))
        x, y = self._xy(t)
        r = thread_mp().sqrt(x + y)
        u, v = x / r, y / r
        return 4 * u * v / r * thread_mp().exp(-u * v) * mp_i2(u, v) / t

    def msf(self, t: mpmath.mpf) -> mpmath.mpf:
        """``sf(t) exp(t**2/(2 var))`` (all terms positive)."""
        if t <= 0 or len(self.scales) == 1:
            return thread_mp().mpf(1)
        x, y = self._xy(t)
        r = thread_mp().sqrt(x + y)
        u, v = x / r, y / r
        b = v * thread_mp().exp(-u * u) + u * thread_mp().exp(-v * v)
        b += thread_mp().sqrt(thread_mp().pi) * u * v * (thread_mp().erf(u) + thread_mp().erf(v))
        return b / r

    def mpdf(self, t: mpmath.mpf) -> mpmath.mpf:
        """``pdf(t) exp(t**2/(2 var))``."""
        if t <= 0:
            return thread_mp().mpf(0)
        if len(self.scales) == 1:
            return t / self.scales[0] ** 2
        x, y = self._xy(t)
        r = thread_mp().sqrt(x + y)
        u, v = x / r, y / r
        return 4 * u * v / r * mp_i2(u, v) / t


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


def _float_regions(scales: list[float], x: np.ndarray) -> dict[str, np.ndarray]:
    """Masks of the thresholds (scales normalised to a largest one in [1/2, 1)): at or below 0,
    beyond float64, the leading power, the Laplace regime and the rest."""
    var = math.fsum(s * s for s in scales)
    smin = min(scales)
    with np.errstate(over="ignore", invalid="ignore"):
        nonpos = ~(x > 0)
        inf = x == math.inf
        small = ~nonpos & (x <= _X_SMALL * smin)
        laplace = ~nonpos & ~inf & ~small & (x * smin >= _X_LAPLACE * var)
    return {"nonpos": nonpos, "inf": inf, "small": small, "laplace": laplace,
            "rest": ~(nonpos | inf | small | laplace)}


_LIMITS = {  # kind: (value at x <= 0, value at x = inf)
    "sf": (1.0, 0.0), "cdf": (0.0, 1.0), "pdf": (0.0, 0.0), "logsf": (0.0, -math.inf),
    "logcdf": (-math.inf, 0.0)}


def _float_eval(scales0: list[float], x: np.ndarray, kind: str
                ) -> tuple[np.ndarray, np.ndarray, str]:
    """``(values, absolute error estimates, method)`` of ``kind`` (sf, cdf, pdf, logsf,
    logcdf) at float64 thresholds (flat array); the scales are float64 > 0 (any spread).

    Under- and overflow inside are expected (far tails, tiny ratios): the caller's numpy error
    state never reaches them; a NaN would be a bug and is raised, never returned."""
    with np.errstate(all="ignore"):
        val, err, method = _float_eval_quiet(scales0, x, kind)
    if np.isnan(val).any():   # pragma: no cover - every route has a value
        i = int(np.argmax(np.isnan(val)))
        raise ArithmeticError(f"RayleighSum({scales0!r}).{kind}({float(x[i])!r}) gave nan")
    return val, err, method


def _float_eval_quiet(scales0: list[float], x: np.ndarray, kind: str
                      ) -> tuple[np.ndarray, np.ndarray, str]:
    # scales (and x) are rescaled by an exact power of two only where the largest scale is
    # outside [2**-200, 2**200] (the probabilities are scale-free, the density scales by 2**-e)
    top = max(scales0)
    e = 0 if 2.0**-200 <= top <= 2.0**200 else math.frexp(top)[1]
    sc = [math.ldexp(s, -e) for s in scales0]
    with np.errstate(under="ignore", over="ignore"):
        xs = np.ldexp(x, -e)
    reg = _float_regions(sc, xs)
    val = np.empty(x.shape)
    err = np.zeros(x.shape)
    lo, hi = _LIMITS[kind]
    val[reg["nonpos"]] = lo
    val[reg["inf"]] = hi
    method = "closed form" if len(sc) <= 2 else "Laplace-transform inversion"
    with np.errstate(under="ignore", over="ignore", divide="ignore"):
        m = reg["small"]
        if m.any():   # unscaled values: only ratios (x / 2**e may be subnormal)
            lc = _float_small_logcdf(scales0, x[m])
            cdf = np.exp(lc)
            vals = {"logcdf": lc, "cdf": cdf, "sf": 1.0 - cdf, "logsf": -cdf,
                    "pdf": np.exp(lc + math.log(2 * len(sc)) - np.log(x[m]))}
            val[m] = vals[kind]
            err[m] = 4 * _EPS * np.abs(val[m]) * (len(sc) + np.abs(lc))
        m = reg["laplace"]
        if m.any():   # E >= 5e9: sf and pdf are 0 in float64, cdf 1
            val[m] = (_laplace_logsf(sc, xs[m]) if kind == "logsf"
                      else {"sf": 0.0, "pdf": 0.0, "cdf": 1.0, "logcdf": 0.0}[kind])
        m = reg["rest"]
        if m.any():
            v, er, meth = _float_body(sc, xs[m], kind)
            val[m], err[m] = v, er
            method = meth
    if kind == "pdf" and e:   # the density scales by 2**-e (it is below 1/s_max: no overflow)
        with np.errstate(under="ignore"):
            val, err = np.ldexp(val, -e), np.ldexp(err, -e)
    return val, err, method


def _float_body(sc: list[float], x: np.ndarray, kind: str) -> tuple[np.ndarray, np.ndarray, str]:
    """The closed forms (one scale; two scales in :data:`_PAIR_RANGE`) or the inversion, for
    thresholds ``0 < x`` in the body (normalised scales)."""
    n = len(sc)
    val = np.empty(x.shape)
    err = np.empty(x.shape)
    if n == 1:
        s = sc[0]
        big_e = 0.5 * (x / s) ** 2
        g = np.exp(-big_e)
        vals = {"sf": g, "cdf": -np.expm1(-big_e), "pdf": x / (s * s) * g, "logsf": -big_e,
                "logcdf": np.log(-np.expm1(-big_e))}
        val = vals[kind]
        return val, 4 * _EPS * np.abs(val) * (1 + big_e), "closed form"
    closed = np.zeros(x.shape, dtype=bool)
    if n == 2:
        with np.errstate(over="ignore", under="ignore"):
            h = [x / (math.sqrt(2.0) * s) for s in sc]
        closed = ((h[0] >= _PAIR_RANGE[0]) & (h[0] <= _PAIR_RANGE[1])
                  & (h[1] >= _PAIR_RANGE[0]) & (h[1] <= _PAIR_RANGE[1]))
        if closed.any():
            val[closed], err[closed] = _float_pair(sc, x[closed], kind)
    rest = ~closed
    if rest.any():
        val[rest], err[rest] = _float_inverted(sc, x[rest], kind)
    return val, err, "closed form" if closed.all() else "Laplace-transform inversion"


def _float_pair(sc: list[float], x: np.ndarray, kind: str) -> tuple[np.ndarray, np.ndarray]:
    """Two scales by the closed forms of eq. (27) (all ``x/(sqrt 2 s)`` in the fast range)."""
    grp = _FGroup(sc)
    big_e = x * x / (2.0 * grp.var)
    g = np.exp(-big_e)
    if kind == "pdf":
        v = grp.mpdf(x) * g
        return v, 4 * _EPS * np.abs(v) * (3 + 2 * big_e)
    m = grp.msf(x)
    sf = m * g
    sf_err = 4 * _EPS * np.abs(sf) * (3 + 2 * big_e)
    upper = sf <= 0.5
    cdf = np.where(upper, 1.0 - sf, 0.0)
    cdf_err = np.where(upper, sf_err + np.minimum(_EPS, sf), 0.0)
    if (~upper).any():   # the cdf's own form below 1/2 (no cancellation)
        c_own = grp.cdf(x[~upper])
        cdf[~upper] = c_own
        cdf_err[~upper] = 4 * _EPS * c_own * (2 + np.abs(np.log(np.maximum(c_own, 1e-300))))
        sf[~upper] = 1.0 - c_own
        sf_err[~upper] = cdf_err[~upper] + _EPS
    if kind == "sf":
        return sf, sf_err
    if kind == "cdf":
        return cdf, cdf_err
    if kind == "logsf":
        v = np.where(upper, np.log(m) - big_e, np.log1p(-cdf))
        return v, sf_err / np.maximum(sf, 1e-300)
    v = np.where(upper, np.log1p(-sf), np.log(cdf))
    return v, cdf_err / np.maximum(cdf, 1e-300)


#: a scale above ``_HUGE_RATIO x`` is in its power regime at ``x`` (density ``r/s**2 (1 +
#: O(x**2/s**2))`` on ``[0, x]``): it is evaluated at ``_HUGE_RATIO x`` and the value (lower
#: tail, density) multiplied by ``(_HUGE_RATIO x/s)**2`` (exact to ``1e-200`` relative)
_HUGE_RATIO = 1e100


def _float_inverted(sc: list[float], x: np.ndarray, kind: str
                    ) -> tuple[np.ndarray, np.ndarray]:
    """Any number of scales by the inversion (:func:`~symhx.forcing.inversion.invert_float`):
    the tail below about 1/2 (the upper one from the mean on), the other as ``1 -`` it.
    Thresholds ``x`` far below the largest scales (by more than :data:`_HUGE_RATIO`) take
    those scales in their power regime, one threshold at a time."""
    far = np.array([max(sc) > _HUGE_RATIO * xv for xv in x], dtype=bool)
    if far.any():
        val = np.empty(x.shape)
        err = np.empty(x.shape)
        if (~far).any():
            val[~far], err[~far] = _float_inverted(sc, x[~far], kind)
        for i in np.flatnonzero(far):
            cap = _HUGE_RATIO * float(x[i])
            clipped = [min(s, cap) for s in sc]
            log_fac = math.fsum(2.0 * math.log(cap / s) for s in sc if s > cap)
            # (through the rescaling entry: the clipped scales may need it)
            v, er, _ = _float_eval_quiet(clipped, x[i:i + 1], kind)
            if kind in ("logcdf", "logsf"):   # x is far below the mean: the lower tail
                if kind == "logcdf":
                    val[i], err[i] = v[0] + log_fac, er[0]
                else:   # log1p(-cdf) = -cdf, cdf below exp(-460)
                    cdf = _float_eval_quiet(clipped, x[i:i + 1], "cdf")[0][0] * math.exp(
                        log_fac)
                    val[i], err[i] = -cdf + 0.0, abs(cdf) * 1e-13
            elif kind == "sf":
                cdf, cerr, _ = _float_eval_quiet(clipped, x[i:i + 1], "cdf")
                val[i] = 1.0 - cdf[0] * math.exp(log_fac)
                err[i] = cerr[0] * math.exp(log_fac) + min(_EPS, cdf[0])
            else:   # cdf, pdf: linear in the factor
                fac = math.exp(log_fac)
                val[i], err[i] = v[0] * fac, er[0] * fac
        return val, err
    if kind == "pdf":
        inv = invert_float(sc, x, "pdf")
        return inv.value, np.abs(inv.value) * inv.err / inv.t
    mean = math.sqrt(math.pi / 2) * math.fsum(sc)
    upper = x >= mean
    val = np.empty(x.shape)
    err = np.empty(x.shape)
    for side, mask in (("sf", upper), ("cdf", ~upper)):
        if not mask.any():
            continue
        inv = invert_float(sc, x[mask], side)
        small = inv.value
        rel = inv.err / inv.t
        log_small = inv.log_scale + np.log(inv.t)
        if kind == side:
            v, er = small, small * rel
        elif kind == "log" + side:
            v, er = log_small, rel
        elif kind in ("sf", "cdf"):   # (1 - small rounds by at most min(eps, small))
            v, er = 1.0 - small, small * rel + np.minimum(_EPS, small)
        else:   # the log of the other tail: log1p(-small) (never -0.0)
            v = np.log1p(-small) + 0.0
            er = small * rel / (1.0 - small)
        val[mask], err[mask] = v, er
    return val, err


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




# =========================================================================== mpmath
def _mp_pair(scales: Sequence[Any], x: mpmath.mpf, kind: str, dps: int
             ) -> tuple[mpmath.mpf, mpmath.mpf]:
    """One or two scales by their closed forms at ``dps`` digits (inside the working
    precision): ``kind`` sf, cdf or pdf, and the absolute error estimate."""
    grp = _MGroup(scales)
    tol = thread_mp().mpf(10) ** (-dps - 10)
    if x <= 0:
        return (thread_mp().mpf(1) if kind == "sf" else thread_mp().mpf(0)), thread_mp().mpf(0)
    e = x * x / (2 * grp.var)
    if kind == "pdf":
        v = grp.mpdf(x) * thread_mp().exp(-e)
        return v, abs(v) * tol
    sf = grp.msf(x) * thread_mp().exp(-e)
    if kind == "sf" or sf <= 0.5:
        v = sf if kind == "sf" else 1 - sf
        return v, abs(sf) * tol
    v = grp.cdf(x)
    return v, abs(v) * tol


def _mp_tail_pair_log(scales: Sequence[Any], x: mpmath.mpf, kind: str, dps: int) -> mpmath.mpf:
    """``log`` of a tail of one or two scales (``kind`` logsf or logcdf), relative accuracy
    kept: ``log m - E`` for the upper tail (no ``exp(-E)``), ``log1p`` of the other tail above
    1/2."""
    grp = _MGroup(scales)
    if kind == "logsf":
        if x <= 0:
            return thread_mp().mpf(0)
        val = thread_mp().log(grp.msf(x)) - x * x / (2 * grp.var)
        if val > -thread_mp().log(2):
            val = thread_mp().log1p(-_mp_pair(scales, x, "cdf", dps + 5)[0])
        return val
    v = _mp_pair(scales, x, "cdf", dps + 5)[0]
    if v > 0.5:
        return thread_mp().log1p(-_mp_pair(scales, x, "sf", dps + 5)[0])
    return thread_mp().log(v) if v > 0 else thread_mp().mpf("-inf")


def _mp_sum(scales: Sequence[Fraction], x: Fraction, kind: str, dps: int
            ) -> tuple[mpmath.mpf, mpmath.mpf]:
    """Three or more scales (or any, for a check) by the Arb inversion: ``(value, absolute
    error)`` of ``kind`` (sf, cdf, pdf, logsf, logcdf) at the current working precision."""
    if x <= 0:
        v = {"sf": 1, "cdf": 0, "pdf": 0, "logsf": 0, "logcdf": thread_mp().mpf("-inf")}[kind]
        return thread_mp().mpf(v), thread_mp().mpf(0)
    if kind == "pdf":
        inv = invert_arb(scales, x, "pdf", dps + 3)
        v = thread_mp().exp(thread_mp().mpf(inv.log_scale)) * thread_mp().mpf(inv.t)
        return v, abs(v) * inv.rel_err
    with thread_mp().workprec(64):
        mean = thread_mp().sqrt(thread_mp().pi / 2) * thread_mp().fsum(mpf_of(s) for s in scales)
        upper = mpf_of(x) >= mean
    side = "sf" if upper else "cdf"
    inv = invert_arb(scales, x, side, dps + 3)
    ls, t = thread_mp().mpf(inv.log_scale), thread_mp().mpf(inv.t)
    if kind == "log" + side:
        return ls + thread_mp().log(t), thread_mp().mpf(inv.rel_err)
    small = thread_mp().exp(ls) * t
    err = abs(small) * inv.rel_err
    if kind == side:
        return small, err
    if kind in ("sf", "cdf"):
        return 1 - small, err
    return thread_mp().log1p(-small), err / (1 - small)


# =========================================================================== the distribution
class RayleighSum:
    r"""The sum ``S = sum_i R_i`` of independent Rayleigh variables ``R_i`` of scales ``s_i``.

    ``R_i`` has density ``(r/s_i**2) exp(-r**2/(2 s_i**2))``; with the scales of
    :func:`rayleigh_scales` ``P(S > d)`` is the impact probability of eq. (22) (eq. 27 for two
    scales). Methods follow ``scipy.stats``: ``pdf, cdf, sf, logcdf, logsf`` take a float or
    an array of thresholds ``x`` (float64, vectorised; ``x <= 0`` gives ``sf = 1``; an empty
    array gives an empty result) or, with ``dps=``, mpmath values correct to ``dps`` digits.
    One or two scales have closed forms; more are computed by the inversion of the Laplace
    transform of the sum (see :mod:`symhx.forcing.inversion`), up to ``MAX_SCALES`` scales of
    any spread.

    Parameters
    ----------
    scales : sequence of real
        Scales ``s_i > 0`` (decimal strings exact, floats/mpf at their binary value), at most
        ``MAX_SCALES`` of them.

    Raises
    ------
    ValueError
        No scale, more than ``MAX_SCALES``, or a scale that is not finite and ``> 0``.

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
            raise InputError("scales: need at least one Rayleigh scale, got an empty sequence")
        if arr.size > _arguments.MAX_SCALES:
            raise InputError(f"scales: {arr.size} Rayleigh scales, more than "
                             f"symhx.forcing.arguments.MAX_SCALES = {_arguments.MAX_SCALES} (the "
                             f"documented limit of the sum's evaluation)")
        exact = []
        for i, s in enumerate(arr):
            exact.append(rational_arg(f"scales[{i}]", s))
        self._exact: tuple[Fraction, ...] = tuple(exact)
        self.scales = np.array([_to_float(f) for f in exact])

    def __repr__(self) -> str:
        # float64's repr where it holds the scale; beyond it the exact value in 5 digits
        # (never "inf" or "0.0" for a scale of 1e5000 or 1e-5000)
        shown = (repr(float(f)) if 1e-300 < f < 1e300 else short_value(s)
                 for f, s in zip(self.scales, self._exact, strict=True))
        return f"RayleighSum([{', '.join(shown)}])"

    # ---- moments
    @exported
    def mean(self, *, dps: int | None = None) -> Any:
        """``E[S] = sqrt(pi/2) sum s_i``."""
        dps = check_dps(dps, allow_none=True)
        if dps is None:
            return float(math.sqrt(math.pi / 2) * math.fsum(self._float_scales()))
        with thread_mp().workdps(dps + 10):
            ctx = thread_mp()
            val = ctx.sqrt(ctx.pi / 2) * ctx.fsum(mpf_of(s) for s in self._exact)
            with thread_mp().workdps(dps):
                return +val

    @exported
    def var(self, *, dps: int | None = None) -> Any:
        """``Var S = (2 - pi/2) sum s_i**2``."""
        dps = check_dps(dps, allow_none=True)
        if dps is None:
            return float((2 - math.pi / 2) * math.fsum(s * s for s in self._float_scales()))
        with thread_mp().workdps(dps + 10):
            val = (2 - thread_mp().pi / 2) * thread_mp().fsum(mpf_of(s) ** 2 for s in self._exact)
            with thread_mp().workdps(dps):
                return +val

    @exported
    def std(self, *, dps: int | None = None) -> Any:
        """Standard deviation ``sqrt(Var S)``."""
        dps = check_dps(dps, allow_none=True)
        if dps is None:
            return math.sqrt(self.var())
        with thread_mp().workdps(dps + 10):
            val = thread_mp().sqrt(self.var(dps=dps + 10))
            with thread_mp().workdps(dps):
                return +val

    def rvs(self, size: Any = None, random_state: Any = None) -> Any:
        """Random draws (float64): ``sum_i Rayleigh(s_i)`` with numpy's generator.

        ``size``: None (one float), an int ``>= 0`` or a tuple of them (an array of that
        shape), at most :data:`symhx.validation.MAX_SAMPLE_SIZE` draws. ``random_state``:
        None, an int seed ``>= 0`` or a ``numpy.random.Generator``; the same seed gives the
        same draws.
        """
        shape = check_size(size)
        rng = (random_state if isinstance(random_state, np.random.Generator)
               else np.random.default_rng(check_seed(random_state, "random_state")))
        sc = self._float_scales()
        out = rng.rayleigh(scale=sc[0], size=shape)
        for s in sc[1:]:
            out = out + rng.rayleigh(scale=s, size=shape)
        return float(out) if shape is None else out

    # ---- probabilities
    @exported
    def sf(self, x: Any, *, dps: int | None = None) -> Any:
        """``P(S > x)``."""
        return self._eval(x, "sf", dps)

    def cdf(self, x: Any, *, dps: int | None = None) -> Any:
        """``P(S <= x)``."""
        return self._eval(x, "cdf", dps)

    def pdf(self, x: Any, *, dps: int | None = None) -> Any:
        """Density of ``S`` at ``x``."""
        return self._eval(x, "pdf", dps)

    @exported
    def logsf(self, x: Any, *, dps: int | None = None) -> Any:
        """``log P(S > x)``; ``log1p(-cdf)`` where ``sf > 1/2`` (relative accuracy kept)."""
        return self._eval(x, "logsf", dps)

    @exported
    def logcdf(self, x: Any, *, dps: int | None = None) -> Any:
        """``log P(S <= x)``; ``log1p(-sf)`` where ``cdf > 1/2``."""
        return self._eval(x, "logcdf", dps)

    @exported
    def probability(self, x: Any, *, tail: str = "upper", dps: int | None = None
                    ) -> RayleighSumResult:
        """``P(S > x)`` (``tail="upper"``) or ``P(S <= x)`` with an error estimate (of the
        quadrature, the truncation and the rounding; for ``dps`` also the final rounding to
        ``dps`` digits) and the method used."""
        tail = check_choice(tail, "tail", ("upper", "lower"))
        kind = "sf" if tail == "upper" else "cdf"
        dps = check_dps(dps, allow_none=True)
        if dps is None:
            xa = float_arg("x", x, positive=False)
            if xa.ndim:
                raise TypeError("x must be a scalar here (use sf/cdf for arrays)")
            val, err, method = _float_eval(self._float_scales(), xa.reshape(1), kind)
            return RayleighSumResult(float(val[0]), float(err[0]), method)
        self._check_mp_work(dps)
        method = "closed form" if len(self._exact) <= 2 else "Laplace-transform inversion"
        with thread_mp().workdps(dps + 15 + self._exp_digits(x)):
            val, err = self._mp_value(x, kind, dps)
            with thread_mp().workdps(dps):   # returned at dps digits (the guard digits are not
                out = +val              # correct digits): the estimate includes that rounding
            err = err + abs(out - val)
            with thread_mp().workdps(dps):
                return RayleighSumResult(out, +err, method)

    # ---- internals
    def _check_mp_work(self, dps: int) -> None:
        """The cap of the mpmath path of three or more scales, before any work."""
        n = len(set(self._exact))
        if len(self._exact) >= 3 and n * dps > MAX_MP_SUM_WORK:
            raise InputError(
                f"dps: {dps} digits for {n} distinct Rayleigh scales (work {n * dps}) is above "
                f"the cap symhx.forcing.rayleigh.MAX_MP_SUM_WORK = {MAX_MP_SUM_WORK} (distinct "
                f"scales x dps) of the "
                "mpmath evaluation of a sum of three or more scales")

    def _exp_digits(self, x: Any) -> int:
        """Extra digits for ``exp(-E)``, ``E ~ x**2/(2 sum s**2)``, to keep its relative
        accuracy (E ~ 1e6 costs 6 digits)."""
        with thread_mp().workprec(53):
            xm = _mp_x(x)   # a sympy expression too (evaluated), not taken as 0
            var = thread_mp().fsum(mpf_of(s) ** 2 for s in self._exact)
            e = xm * xm / (2 * var) if xm > 0 else thread_mp().mpf(0)
        if e > _kernels_mp.MAX_EXPONENT:
            raise InputError(
                f"x: P(S > x) = exp(-E) with E ~ {thread_mp().nstr(e, 3)} above the cap "
                f"MAX_EXPONENT = {_kernels_mp.MAX_EXPONENT:.3g} "
                f"(symhx.forcing.kernels_mp.MAX_EXPONENT) of the mpmath evaluation (exp(-E) "
                f"would need log10(E) "
                "guard digits); logsf has no cap")
        return int(thread_mp().log10(e)) + 1 if e > 1 else 0

    def _float_scales(self) -> list[float]:
        bad = ~((self.scales > 0) & np.isfinite(self.scales))
        if bad.any():
            i = int(np.argmax(bad))
            raise float64_refusal(f"scales[{i}] = {short_value(self._exact[i])} is outside the "
                                  "float64 range")
        return [float(s) for s in self.scales]

    def _mp_value(self, x: Any, kind: str, dps: int) -> tuple[mpmath.mpf, mpmath.mpf]:
        """``(value, absolute error)`` at the current working precision (``dps`` digits of
        accuracy): closed forms for one or two scales, the Arb inversion for more."""
        xm = _mp_x(x)
        if len(self._exact) <= 2:
            scales = [mpf_of(s) for s in self._exact]
            if kind in ("sf", "cdf", "pdf"):
                return _mp_pair(scales, xm, kind, dps)
            return _mp_tail_pair_log(scales, xm, kind, dps), thread_mp().mpf(0)
        fr = to_rational(x, "x")
        xf = fr if fr is not None else mpf_to_fraction(xm)
        return _mp_sum(self._exact, xf, kind, dps)

    def _eval(self, x: Any, kind: str, dps: Any) -> Any:
        dps = check_dps(dps, allow_none=True)
        if dps is None:
            xa = (check_array(x, "x", allow_empty=True) if is_array(x)
                  else float_arg("x", x, positive=False))
            flat = xa.reshape(-1)
            sc = self._float_scales()
            out = _float_eval(sc, flat, kind)[0] if flat.size else np.empty(0)
            return float(out[0]) if xa.ndim == 0 else out.reshape(xa.shape)
        self._check_mp_work(dps)
        if is_array(x):
            xs = np.asarray(x, dtype=object)
            out = np.empty(xs.shape, dtype=object)
            for idx in np.ndindex(xs.shape):
                out[idx] = self._eval(xs[idx], kind, dps)
            return out
        # exp(-E) needs log10(E) guard digits (so does log cdf = log1p(-sf) far out); log sf
        # = log m - E does not (its absolute error E 10**-prec is relative 10**-prec), so its
        # cost does not grow with E
        guard = 15 + (0 if kind == "logsf" else self._exp_digits(x))
        with thread_mp().workdps(dps + guard):
            val = self._mp_value(x, kind, dps)[0]
            with thread_mp().workdps(dps):
                return +val


def _to_float(fr: Fraction) -> float:
    try:
        return float(fr)
    except OverflowError:
        return math.inf


def _mp_x(x: Any) -> mpmath.mpf:
    """A finite real threshold as an mpf at the current precision (``<= 0`` allowed)."""
    fr = to_rational(x, "x")
    if fr is None:
        return thread_mp().mpf(x.evalf(thread_mp().dps + 5))
    return mpf_of(fr) if fr > 0 else thread_mp().mpf(fr.numerator) / fr.denominator


@exported
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

