"""Impact probability of the random forcing, eqs. (22)-(27): ``p``, ``1 - p`` and their logs.

Thin public functions over one validated :class:`~symhx.forcing.arguments.ForcingParams`
(converted once per call) and the kernels: the float64 closed form, the mpmath closed form (with
its raw-libmp fast path) and, for several forcing components, :class:`RayleighSum`.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from typing import Any

import mpmath
import numpy as np

from symhx._mpctx import mp as thread_mp
from symhx.forcing.arguments import ForcingParams, elementwise, exported, float_arg, mp_arg
from symhx.forcing.kernels_float import single_float
from symhx.forcing.kernels_mp import (
    estimate,
    estimate_float,
    mp_p_from_xy,
    mp_q_from_xy,
    mp_xy_forcing,
    precision_plan,
)
from symhx.forcing.rawmp import from_xy_raw, single_mp_fast
from symhx.forcing.rayleigh import RayleighSum, scales_of
from symhx.validation import InputError, check_dps, float64_refusal

__all__ = [
    "WANTS",
    "evaluate",
    "impact_probability",
    "log_impact_probability",
    "log_no_impact_probability",
    "naive_impact_probability",
    "no_impact_probability",
    "single_mp",
    "with_params_doc",
]

#: the quantities a kernel can return: p, q = 1 - p, log p, log q
WANTS = ("p", "q", "logp", "logq")
_KIND = {"p": "sf", "q": "cdf", "logp": "logsf", "logq": "logcdf"}


def single_mp(fp: ForcingParams, dps: int, want: str) -> mpmath.mpf:
    """One scalar component at ``dps`` digits (``want`` in :data:`WANTS`).

    Float and dyadic inputs take the raw-libmp fast path; other inputs (mpf, decimal strings,
    other Fractions, huge ints) form ``x, y`` with mpf objects and share the fast path's
    precision plan and closed form (:func:`~symhx.forcing.rawmp.from_xy_raw`)."""
    sigma, sigma1, omega, Omega, d = fp.sigma, fp.sigma1, fp.omega, fp.Omega, fp.d
    fast = single_mp_fast(sigma, sigma1, omega, Omega, d, dps, want)
    if fast is not None:
        return fast
    est = estimate_float(sigma, sigma1, omega, Omega, d)
    if est is None:  # an input beyond the float range: estimate from mpf x, y
        with thread_mp().workprec(64):
            est = estimate(*mp_xy_forcing(sigma, sigma1, omega, Omega, d))
    if est[2] > 0.5 and want == "logp":  # log p = log1p(-q) keeps its relative accuracy
        q = single_mp(fp, dps + 5, "q")
        with thread_mp().workdps(dps + 5):
            return thread_mp().log1p(-q)
    guard, direct_q = precision_plan(est, want)
    with thread_mp().workdps(dps + guard):
        x, y = mp_xy_forcing(sigma, sigma1, omega, Omega, d)
        value = from_xy_raw(x._mpf_, y._mpf_, thread_mp().prec, want, guard, direct_q)
        if value is not None:
            return value
        # the adaptive 1 - p (p above 1/2, or more digits cancelled than planned) or log1p(-p)
        if want == "logq":
            p = mp_p_from_xy(x, y)
            if p <= 0.5:
                return thread_mp().log1p(-p)
        q = mp_q_from_xy(x, y)
        return q if want == "q" else thread_mp().log(q)


def _multi(fp: ForcingParams, dps: int | None, want: str) -> Any:
    """Several forcing components: the Rayleigh sum of :func:`scales_of` at ``d``."""
    kind = _KIND[want]

    def one(f: ForcingParams) -> Any:
        if dps is None:
            scales = scales_of(f)
            if not all(math.isfinite(s) for s in scales):
                raise float64_refusal("a forced component's Rayleigh scale sigma1 / |omega**2 - "
                                      "Omega**2| is beyond float64 here")
            S = RayleighSum(scales)
            return getattr(S, kind)(float(f.d))
        # a relative error eps of a scale moves log p by ~2 E eps (p = exp(-E), E = d**2/(2
        # sum s**2)): the scales carry log10(E) more digits (RayleighSum takes them exactly)
        with thread_mp().workdps(20):
            dd = mp_arg("d", f.d)
            e = dd * dd / (2 * thread_mp().fsum(s * s for s in scales_of(f, 20)))
            extra = int(thread_mp().log10(e)) + 1 if e > 1 else 0
        S = RayleighSum(scales_of(f, dps + 15 + extra))
        return getattr(S, kind)(f.d, dps=dps)

    return elementwise(fp, one, dtype=float if dps is None else object)


def evaluate(fp: ForcingParams, dps: int | None, want: str) -> Any:
    """``p``, ``1 - p``, ``log p`` or ``log(1 - p)`` (``want``) of a validated forcing."""
    if fp.components:
        return _multi(fp, dps, want)
    if dps is None:
        return single_float(fp, want)
    return elementwise(fp, lambda one: _at_dps(single_mp(one, dps, want), dps))


def _at_dps(value: mpmath.mpf, dps: int) -> mpmath.mpf:
    """``value`` (computed with guard digits) rounded to ``dps`` digits, as every mpmath result
    of the package is returned (the guard digits are not correct digits)."""
    with thread_mp().workdps(dps):
        return +value


def _dispatch(sigma: Any, sigma1: Any, omega: Any, Omega: Any, d: Any, dps: Any, want: str
              ) -> Any:
    dps = check_dps(dps, allow_none=True)
    return evaluate(ForcingParams.validated(sigma, sigma1, omega, Omega, d, dps=dps), dps, want)


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



def with_params_doc(fn: Callable[..., Any]) -> Callable[..., Any]:
    """Insert the shared parameter documentation at the ``@PARAMS@`` marker."""
    if fn.__doc__:
        fn.__doc__ = fn.__doc__.replace("\n    @PARAMS@\n", _PARAMS_DOC)
    return fn

@exported
@with_params_doc
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
    >>> import numpy as np
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


@exported
@with_params_doc
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


@exported
@with_params_doc
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


@exported
@with_params_doc
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

    s0 = float(float_arg("sigma", sigma))
    s1 = s0 if sigma1 is None else float(float_arg("sigma1", sigma1))
    om = float(float_arg("omega", omega))
    dd = float(float_arg("d", d))
    with np.errstate(over="ignore"):
        Om2 = 2.0 if Omega is None else float(np.float64(float_arg("Omega", Omega)) ** 2)
        k = float((np.float64(om) * om - Om2) ** 2)
    if k == 0:
        raise InputError("Omega: resonance Omega == omega (infinite forced amplitude)")
    den = 4 * s0 * s0 * s1 * s1
    # the literal integrand needs k, 1/(4 s0^2 s1^2), d**2/sigma**2 and k d**2/sigma1**2 as
    # normal float64 numbers: refuse the rest up front (impact_probability has no such limits)
    if not (math.isfinite(k) and 1e-300 < den < 1e300 and 1e-300 < dd * dd < 1e300
            and math.isfinite(k / den) and math.isfinite(k * dd * dd / (s1 * s1))):
        raise InputError(
            f"naive_impact_probability: sigma={sigma!r}, sigma1={sigma1!r}, omega={omega!r}, "
            f"Omega={Omega!r}, d={d!r} are outside the float64 range of the literal eq. (27) "
            "integrand; use impact_probability")
    c = k / den

    def f(t: float, x: float) -> float:
        return t * (x - t) * math.exp(-t * t / (4 * s0 * s0)) * math.exp(
            -k * (x - t) ** 2 / (4 * s1 * s1)
        )

    val, _ = integrate.dblquad(f, 0.0, dd, 0.0, lambda x: x)
    return 1.0 - c * val


