"""Derivative of the impact probability with respect to the forcing ``sigma`` (eqs. 22-27)."""

from __future__ import annotations

from typing import Any

import mpmath
import numpy as np

from symhx._mpctx import mp as thread_mp
from symhx.forcing.arguments import ForcingParams, elementwise, exported, mp_arg
from symhx.forcing.kernels_float import UV, i2_float, i3_float, uv_forcing
from symhx.forcing.kernels_mp import estimate, guard_digits, mp_i2, mp_i3, mp_xy_forcing
from symhx.forcing.probability import with_params_doc
from symhx.forcing.rayleigh import RayleighSum, scales_of
from symhx.validation import InputError, check_dps

__all__ = ["dp_dsigma"]


def _dp_float(fp: ForcingParams) -> Any:
    sig0 = fp.sigma
    tied = fp.sigma1 is None
    sig1 = sig0 if tied else fp.sigma1
    arrs = [sig0, sig1, fp.omega, fp.d] + ([] if fp.Omega is None else [fp.Omega])
    scalar = all(a.ndim == 0 for a in arrs)
    b = np.broadcast_arrays(*arrs)
    sig0, sig1, om, dd = b[:4]
    Om = None if fp.Omega is None else b[4]
    if sig0.size == 0:
        return np.empty(sig0.shape)
    with np.errstate(under="ignore", over="ignore", invalid="ignore", divide="ignore"):
        uv = UV(*(np.ravel(a) for a in uv_forcing(sig0, sig1, om, Om, dd)))
        if tied:  # sigma dp/dsigma = d g(d) = 4 uv/r exp(-uv) I2(u, v)
            val = 4.0 * uv.u * uv.v / uv.r * np.exp(-uv.e) * i2_float(uv.u, uv.v)
        else:  # sigma0 dp/dsigma0 = E[R0 f1(d - R0)] = 4 uv/r**2 exp(-uv) I3(u, v)
            val = 4.0 * uv.u * uv.v / uv.r**2 * np.exp(-uv.e) * i3_float(uv.u, uv.v)
        out = val.reshape(sig0.shape) / sig0
    bad = ~np.isfinite(out)
    if bad.any():  # extreme but finite inputs (over/underflow inside the float kernel)
        out = np.array(out, dtype=float)
        e = np.broadcast_to(uv.e.reshape(-1) if uv.e.size > 1 else uv.e, (out.size,))
        flat_bad = np.flatnonzero(bad.reshape(-1))
        parts = [a.reshape(-1) for a in (sig0, sig1, om, dd)] + (
            [] if Om is None else [Om.reshape(-1)])
        for i in flat_bad:
            out.reshape(-1)[i] = _dp_fallback(float(e[i]), *(float(a[i]) for a in parts),
                                              tied=tied, omega_none=Om is None)
    return float(out) if scalar else out


#: above this exponent ``uv`` the derivative underflows float64: it is at most
#: ``exp(-uv)`` times a polynomial in ``u, v, 1/sigma`` (< exp(1e4) for float64 inputs)
_DP_UNDERFLOW_E = 1e6


def _dp_fallback(e: float, s0: float, s1: float, om: float, dd: float, *rest: float,
                 tied: bool, omega_none: bool) -> float:
    """One float64 derivative where the float kernel over/underflows: 0.0 where the exact value
    is below float64's range, else the mpmath path at 20 digits rounded to float."""
    if e > _DP_UNDERFLOW_E:
        return 0.0
    fp1 = ForcingParams.validated(s0, None if tied else s1, om, None if omega_none else rest[0],
                                  dd, dps=20)
    return float(_dp_mp(fp1, 20))


def _dp_mp(fp: ForcingParams, dps: int) -> mpmath.mpf:
    args = (fp.sigma, fp.sigma1, fp.omega, fp.Omega, fp.d)
    with thread_mp().workprec(64):
        e = estimate(*mp_xy_forcing(*args))[0]
    with thread_mp().workdps(dps + guard_digits(e) + 5):
        x, y = mp_xy_forcing(*args)
        s0 = mp_arg("sigma", fp.sigma)
        r = thread_mp().sqrt(x + y)
        u, v = x / r, y / r
        if fp.sigma1 is None:
            val = 4 * u * v / r * thread_mp().exp(-u * v) * mp_i2(u, v) / s0
        else:
            val = 4 * u * v / (r * r) * thread_mp().exp(-u * v) * mp_i3(u, v) / s0
    with thread_mp().workdps(dps):
        return +val


def _dp_multi(fp: ForcingParams, dps: int | None) -> Any:
    if fp.sigma1 is not None:
        raise InputError(
            "sigma1: dp_dsigma with several components supports only sigma1=None "
            "(all sigma_i = sigma)"
        )

    def one(f: ForcingParams) -> Any:
        # sigma dp/dsigma = d * density of the sum at d (all scales proportional to sigma)
        if dps is None:
            return float(f.d) * RayleighSum(scales_of(f)).pdf(float(f.d)) / float(f.sigma)
        with thread_mp().workdps(dps + 15):
            S = RayleighSum(scales_of(f, dps + 15))
        dens = S.pdf(f.d, dps=dps + 3)
        with thread_mp().workdps(dps + 15):
            val = mp_arg("d", f.d) * dens / mp_arg("sigma", f.sigma)
        with thread_mp().workdps(dps):
            return +val

    return elementwise(fp, one, dtype=float if dps is None else object)


@exported
@with_params_doc
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

    >>> from symhx.forcing import impact_probability
    >>> h = 1e-6
    >>> fd = (impact_probability(0.3 + h) - impact_probability(0.3 - h)) / (2 * h)
    >>> abs(dp_dsigma(0.3) / fd - 1) < 1e-8
    True
    """
    dps = check_dps(dps, allow_none=True)
    fp = ForcingParams.validated(sigma, sigma1, omega, Omega, d, dps=dps)
    if fp.components:
        return _dp_multi(fp, dps)
    if dps is None:
        return _dp_float(fp)
    return elementwise(fp, lambda one: _dp_mp(one, dps))
