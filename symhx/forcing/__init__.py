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

Several forcing components (eq. 22 with ``M >= 2``): :class:`RayleighSum`. The Rayleighs are
grouped in pairs of comparable scales, each pair having the closed-form density/tail above, and
the pairs are convolved by nested composite Gauss-Legendre quadrature of *positive* integrands
(tail ``P(A + B > d) = P(B > d) + int_0^d f_B(t) P(A > d - t) dt``; ``P(A + B <= d) =
int_0^d f_B(t) P(A <= d - t) dt``), with panels around the Gaussian saddle of the integrand and
at multiples of every scale from both ends, so both tails keep their relative accuracy whatever
the spread of the scales. The error estimate is the difference between two rule orders plus
the rounding of the closed forms.

Extreme arguments (scales far from ``d`` or from each other, ratios up to the whole float
range): float64 carries ``sqrt(x)``, ``sqrt(y)`` as mantissa and exponent and uses the limits
``1 - p = x y G(y)`` (``x -> 0``) and ``p = e^{-uv} c (e^{-u^2} + sqrt(pi) u (1 + erf u))``
(``y -> inf``), exact to far below an ulp there; values beyond the float range round to 0,
1 or -inf, never NaN.

Conventions: ``sigma1=None`` means ``sigma_1 = sigma`` (the paper's ``sigma = sigma_0 =
sigma_1``); ``Omega=None`` means the paper's ``sqrt(2)``, used as ``Omega**2 = 2`` exactly at the
working precision. ``dps=None`` selects the float64 path (vectorised, broadcasting over every
argument); an integer ``dps`` selects the mpmath path, correct to ``dps`` significant digits.

Empty arrays: every function maps an empty array to an empty result of the same shape (as numpy
ufuncs and ``scipy.stats`` do). Scalars may be decimal strings (exact, ``"0.05"``).

Modules (one concept each): :mod:`~symhx.forcing.arguments` (conversion, validation, the
forcing value object), :mod:`~symhx.forcing.kernels_float` (float64 closed forms),
:mod:`~symhx.forcing.kernels_mp` and :mod:`~symhx.forcing.rawmp` (mpmath closed forms and
their raw-libmp fast path), :mod:`~symhx.forcing.rayleigh` (the Rayleigh sum of at most
``MAX_SCALES`` = 64 scales),
:mod:`~symhx.forcing.inversion` (its Laplace-transform inversion for three and more scales),
:mod:`~symhx.forcing.probability` (p, 1 - p, logs), :mod:`~symhx.forcing.derivative`,
:mod:`~symhx.forcing.inverse`, :mod:`~symhx.forcing.theory` (the chain to the graph model).
"""

from __future__ import annotations

from symhx.forcing.arguments import MAX_SCALES, ForcingParams
from symhx.forcing.derivative import dp_dsigma
from symhx.forcing.inverse import sigma_for_impact_probability
from symhx.forcing.probability import (
    impact_probability,
    log_impact_probability,
    log_no_impact_probability,
    naive_impact_probability,
    no_impact_probability,
)
from symhx.forcing.rayleigh import (
    RayleighSum,
    RayleighSumResult,
    rayleigh_scales,
    rayleigh_sum_probability,
)
from symhx.forcing.theory import TheoryCurve, theory_curve

__all__ = [
    "MAX_SCALES",
    "ForcingParams",
    "RayleighSum",
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
