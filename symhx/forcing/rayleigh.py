r"""The sum of independent Rayleigh variables (eq. 22) as a distribution object.

``S = R_1 + ... + R_n`` with ``R_i`` Rayleigh of scale ``s_i`` (density ``(r/s**2)
exp(-r**2/(2 s**2))``). One or two scales have closed forms (eq. 27 and its complement, see
:mod:`symhx.forcing`); more scales are paired (adjacent scales after sorting, so a pair holds
comparable scales), each pair having the closed-form tail, CDF and density, and the pairs (and a
leftover single) are convolved by nested composite Gauss-Legendre quadrature of *positive*
integrands::

    P(A + B > x)  = P(B > x) + int_0^x f_B(t) P(A > x - t) dt,
    P(A + B <= x) = int_0^x f_B(t) P(A <= x - t) dt,

so both tails keep their relative accuracy. The panels are placed around the Gaussian saddle of
the integrand *and* at multiples of every scale from both ends of ``[0, x]`` (where a small scale
puts its structure), so scales spread over many orders of magnitude are resolved. The error
estimate is the difference of two rule orders plus the rounding of the closed forms.
"""

from __future__ import annotations

import itertools
import math
from collections.abc import Sequence
from fractions import Fraction
from typing import Any, NamedTuple

import mpmath
import numpy as np

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
    delta_float,
    gauss_legendre,
    i2_float,
    pq_float,
    uv_from_h,
)
from symhx.forcing.kernels_mp import mp_i2, mp_p_from_xy, mp_q_from_xy
from symhx.validation import check_array, check_choice, check_dps, check_seed, to_rational

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
            try:
                delta = abs(float(delta_float(om, None if Om is None else np.asarray(Om))))
            except ValueError:
                raise ValueError(f"{_om_name(fp, i)}: resonance Omega == omega (infinite forced "
                                 "amplitude)") from None
            out.append(math.sqrt(2.0) * (s0 if s1 is None else float(s1)) / delta)
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
class _FGroup:
    """float64 group of one or two Rayleigh scales (closed forms on arrays)."""

    def __init__(self, scales: Sequence[float]) -> None:
        self.scales = tuple(float(s) for s in scales)
        self.var = sum(s * s for s in self.scales)

    def _uv(self, t: np.ndarray) -> Any:
        a, b = self.scales
        with np.errstate(divide="ignore", invalid="ignore", over="ignore"):
            return uv_from_h(t / (math.sqrt(2.0) * a), t / (math.sqrt(2.0) * b))

    def sf(self, t: np.ndarray) -> np.ndarray:
        t = np.maximum(t, 0.0)
        if len(self.scales) == 1:
            with np.errstate(under="ignore", over="ignore"):
                return np.exp(-0.5 * (t / self.scales[0]) ** 2)
        out = np.ones_like(t)
        pos = t > 0
        with np.errstate(under="ignore"):
            out[pos] = pq_float(self._uv(t[pos]), "p")
        return out

    def cdf(self, t: np.ndarray) -> np.ndarray:
        t = np.maximum(t, 0.0)
        if len(self.scales) == 1:
            with np.errstate(under="ignore", over="ignore"):
                return -np.expm1(-0.5 * (t / self.scales[0]) ** 2)
        out = np.zeros_like(t)
        pos = t > 0
        with np.errstate(under="ignore"):
            out[pos] = pq_float(self._uv(t[pos]), "q")
        return out

    def pdf(self, t: np.ndarray) -> np.ndarray:
        out = np.zeros_like(t)
        pos = t > 0
        tp = t[pos]
        with np.errstate(under="ignore", over="ignore", invalid="ignore"):
            if len(self.scales) == 1:
                s = self.scales[0]
                out[pos] = tp / (s * s) * np.exp(-0.5 * (tp / s) ** 2)
                return out
            uv = self._uv(tp)
            val = 4.0 * uv.u * uv.v / uv.r * np.exp(-uv.e) * i2_float(uv.u, uv.v) / tp
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

    def sf(self, t: mpmath.mpf) -> mpmath.mpf:
        if t <= 0:
            return mpmath.mpf(1)
        if len(self.scales) == 1:
            return mpmath.exp(-t * t / (2 * self.scales[0] ** 2))
        return mp_p_from_xy(*self._xy(t))

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
#: offsets (in units of the saddle's width) of the panels around the Gaussian saddle
_PANEL_C = (-12.0, -8.0, -5.0, -3.0, -1.5, 0.0, 1.5, 3.0, 5.0, 8.0, 12.0)
#: multiples of each scale at which panels start from the ends of [0, x]
_SCALE_C = (0.5, 2.0, 8.0)


def _offsets(last: Any, rest: list[Any]) -> tuple[list[float], list[float], list[float]]:
    """Saddle offsets, scales of the last group (near t = 0) and of the rest (near t = x)."""
    near0 = [c * s for s in last.scales for c in _SCALE_C]
    nearx = [c * s for g in rest for s in g.scales for c in _SCALE_C]
    return list(_PANEL_C), near0, nearx


def _panels_float(x: np.ndarray, last: _FGroup, rest: list[_FGroup]) -> np.ndarray:
    """Sorted panel breakpoints, shape (len(x), K), clipped to [0, x]."""
    var_rest = sum(g.var for g in rest)
    tstar = x * (last.var / (last.var + var_rest))
    w = math.sqrt(last.var * var_rest / (last.var + var_rest))
    sad, near0, nearx = _offsets(last, rest)
    cols = [np.zeros_like(x), x]
    cols += [tstar + w * c for c in sad]
    cols += [np.full_like(x, a) for a in near0]
    cols += [x - a for a in nearx]
    pts = np.clip(np.stack(cols, axis=1), 0.0, x[:, None])
    return np.sort(pts, axis=1)


def _conv_float(groups: list[_FGroup], x: np.ndarray, kind: str, n: int) -> np.ndarray:
    """``P(sum > x)`` (kind 'sf'), ``P(sum <= x)`` ('cdf') or the density ('pdf') on array x."""
    if len(groups) == 1:
        return getattr(groups[0], kind)(x)
    last, rest = groups[-1], groups[:-1]
    bp = _panels_float(np.maximum(x, 0.0), last, rest)
    xg, wg = gauss_legendre(n)
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
    sad, near0, nearx = _offsets(last, rest)
    raw = [tstar + c * w for c in sad] + list(near0) + [x - a for a in nearx]
    pts = sorted({mpmath.mpf(0), x} | {min(max(p, 0), x) for p in raw})
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


#: float64 rule orders whose difference is the quadrature error estimate
_N_LO, _N_HI = 12, 24
_EPS = float(np.finfo(float).eps)


def _float_with_error(scales: Sequence[float], x: np.ndarray, kind: str
                      ) -> tuple[np.ndarray, np.ndarray]:
    # far tail: sum R_i <= sqrt(M+1) sqrt(sum R_i**2), so sf and pdf are below a polynomial
    # times exp(-x**2 / (2 (M+1) max s**2)) < exp(-2e6): exactly 0 in float64 (cdf: 1); the
    # kernels would overflow there (x**2 beyond float64)
    far = x > _FAR_TAIL * math.sqrt(len(scales)) * max(scales)
    if far.any():
        val = np.full(x.shape, 1.0 if kind == "cdf" else 0.0)
        err = np.zeros(x.shape)
        if (~far).any():
            val[~far], err[~far] = _float_with_error(scales, x[~far], kind)
        return val, err
    groups = [_FGroup(g) for g in make_groups(scales)]
    with np.errstate(under="ignore", over="ignore", invalid="ignore"):
        if len(groups) == 1:
            val = getattr(groups[0], kind)(x)
            return val, 4 * _EPS * np.abs(val) * (2 + np.abs(np.log(np.maximum(val, 1e-300))))
        lo = _conv_float(groups, x, kind, _N_LO)
        hi = _conv_float(groups, x, kind, _N_HI)
        # quadrature (difference of two orders) + rounding: exp(-E) with E ~ |ln value| carries
        # ~E * few eps from the roundings of its exponent
        logterm = np.abs(np.log(np.maximum(np.abs(hi), 1e-300)))
        err = np.abs(hi - lo) + 4 * _EPS * np.abs(hi) * (len(scales) + 2 * logterm)
    return hi, err


def _mp_with_error(scales: Sequence[Any], x: mpmath.mpf, kind: str, dps: int
                   ) -> tuple[mpmath.mpf, mpmath.mpf]:
    """Value and error estimate at ``dps`` digits (call inside the working precision)."""
    groups = [_MGroup(g) for g in make_groups(scales)]
    if len(groups) == 1:
        val = getattr(groups[0], kind)(x)
        return val, abs(val) * mpmath.mpf(10) ** (-dps - 10)
    tol = mpmath.mpf(10) ** (-dps - 3)
    n = 6 + dps // 4
    prev = _conv_mp(groups, x, kind, n)
    err = abs(prev)
    for _ in range(8):
        n2 = (3 * n) // 2 + 2
        cur = _conv_mp(groups, x, kind, n2)
        err = abs(cur - prev)
        if err <= tol * abs(cur):
            break
        prev, n = cur, n2
    else:
        raise ArithmeticError(  # pragma: no cover - the panels resolve every scale
            f"Rayleigh sum: the quadrature did not converge to {dps} digits (error {err})")
    return cur, err


# =========================================================================== the distribution
class RayleighSum:
    r"""The sum ``S = R_1 + ... + R_n`` of independent Rayleigh variables of scales ``s_i``.

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
        with np.errstate(over="ignore", under="ignore"):
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
        out = sum(rng.rayleigh(scale=s, size=size) for s in sc)
        return float(out) if size is None else out

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
            val, err = _float_with_error(self._float_scales(), xa.reshape(1), kind)
            return RayleighSumResult(float(val[0]), float(err[0]), method)
        with mpmath.workdps(dps + 15 + self._exp_digits(x)):
            xm = _mp_x(x)
            val, err = _mp_with_error([mpf_of(s) for s in self._exact], xm, kind, dps)
        return RayleighSumResult(val, err, method)

    # ---- internals
    def _exp_digits(self, x: Any) -> int:
        """Extra digits for ``exp(-E)``, ``E ~ x**2/(2 sum s**2)``, to keep its relative
        accuracy (E ~ 1e6 costs 6 digits)."""
        with mpmath.workprec(53):
            fr = to_rational(x, "x")
            xm = mpmath.mpf(fr.numerator) / fr.denominator if fr is not None else mpmath.mpf(0)
            var = mpmath.fsum(mpf_of(s) ** 2 for s in self._exact)
            e = xm * xm / (2 * var) if xm > 0 else mpmath.mpf(0)
            return int(mpmath.log10(e)) + 1 if e > 1 else 0

    def _float_scales(self) -> list[float]:
        bad = ~((self.scales > 0) & np.isfinite(self.scales))
        if bad.any():
            i = int(np.argmax(bad))
            raise ValueError(f"scales[{i}] = {self._exact[i]} is outside the float64 range; "
                             "use dps=")
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
        with mpmath.workdps(dps + 15 + self._exp_digits(x)):
            xm = _mp_x(x)
            scales = [mpf_of(s) for s in self._exact]
            if kind in ("sf", "cdf", "pdf"):
                val = _mp_with_error(scales, xm, kind, dps)[0]
            else:
                main, other = ("sf", "cdf") if kind == "logsf" else ("cdf", "sf")
                v = _mp_with_error(scales, xm, main, dps + 5)[0]
                if v > 0.5:
                    val = mpmath.log1p(-_mp_with_error(scales, xm, other, dps + 5)[0])
                else:
                    val = mpmath.log(v) if v > 0 else mpmath.mpf("-inf")
        with mpmath.workdps(dps):
            return +val

    def _float_kind(self, x: np.ndarray, kind: str) -> np.ndarray:
        sc = self._float_scales()
        if kind in ("sf", "cdf", "pdf"):
            return _float_with_error(sc, x, kind)[0]
        main, other = ("sf", "cdf") if kind == "logsf" else ("cdf", "sf")
        v = _float_with_error(sc, x, main)[0]
        out = np.empty_like(v)
        big = v > 0.5
        with np.errstate(divide="ignore"):
            out[~big] = np.log(v[~big])
            if big.any():
                out[big] = np.log1p(-_float_with_error(sc, x[big], other)[0])
        return out


#: ``x / (sqrt(M+1) max s)`` beyond which the float64 sf/pdf are 0 and the cdf 1
_FAR_TAIL = 2000.0


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
    r"""``P(R_0 + ... + R_M > d)`` (``tail="upper"``) or ``P(... <= d)`` (``tail="lower"``).

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

