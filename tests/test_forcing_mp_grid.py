"""The one-component mpmath path against an independent 1-D quadrature on a dense log grid.

Reference (no closed form of the package): with Rayleigh scales ``s0 = sqrt(2) sigma``,
``s1 = sqrt(2) sigma1/|omega**2 - Omega**2|`` and elementary densities/tails,

    p     = P(R0 > d) + int_0^d f0(t) P(R1 > d - t) dt,
    1 - p = int_0^d f0(t) P(R1 <= d - t) dt,
    sigma dp/dsigma (sigma1 = sigma)        = d int_0^d f0(t) f1(d - t) dt,
    sigma0 dp/dsigma0 (sigma1 fixed)        = int_0^d t f0(t) f1(d - t) dt,

by composite Gauss-Legendre at 2*dps + 10 digits on dense panels around the saddle and at
multiples of both scales, at two rule orders that must agree (``mpmath.quad``'s error estimate
was found optimistic for these peaked integrands). The grid runs from
p ~ 1e-2000 to 1 - p ~ 1e-40, so it reaches the raw-libmp fast path (float inputs), the general
path (decimal strings), both tails, the logs and the adaptive 1 - p loop.
"""

from __future__ import annotations

import itertools
from decimal import Decimal

import mpmath
import numpy as np
import pytest

from symhx import forcing as F

DPS = 20


def rel(a, b):
    with mpmath.workdps(100):
        return abs(mpmath.mpf(a) / mpmath.mpf(b) - 1)


def reference(sigma, sigma1, omega, Omega, d, dps):
    with mpmath.workdps(dps):
        sg = mpmath.mpf(sigma)
        s0 = mpmath.sqrt(2) * sg
        om2 = 2 if Omega is None else mpmath.mpf(Omega) ** 2
        delta = abs(mpmath.mpf(omega) ** 2 - om2)
        s1 = mpmath.sqrt(2) * (sg if sigma1 is None else mpmath.mpf(sigma1)) / delta
        d = mpmath.mpf(d)

        def f(t, s):
            return t / s**2 * mpmath.exp(-t * t / (2 * s * s)) if t > 0 else mpmath.mpf(0)

        tstar = d * s0**2 / (s0**2 + s1**2)
        w = s0 * s1 / mpmath.sqrt(s0**2 + s1**2)
        pts = {d * k / 32 for k in range(33)}
        pts |= {tstar + w * k / 2 for k in range(-60, 61)}
        pts |= {c * s for s in (s0, s1) for c in (0.25, 0.5, 1, 2, 3, 4, 6, 8, 11, 16)}
        pts |= {d - c * s for s in (s0, s1) for c in (0.25, 0.5, 1, 2, 3, 4, 6, 8, 11, 16)}
        pts = sorted(q for q in pts if 0 <= q <= d)

        def gl(fn):  # composite Gauss-Legendre at two orders that must agree (self-check)
            out = []
            for n in (12, 24):
                xs, ws = mpmath.mp.gauss_quadrature(n, "legendre")
                tot = mpmath.mpf(0)
                for lo, hi in itertools.pairwise(pts):
                    h, m = (hi - lo) / 2, (hi + lo) / 2
                    tot += h * mpmath.fsum(wi * fn(m + h * xi) for xi, wi in zip(xs, ws,
                                                                              strict=True))
                out.append(tot)
            assert abs(out[1] - out[0]) <= mpmath.mpf(10) ** -(DPS + 1) * abs(out[1]), (
                mpmath.nstr(out[1] / out[0] - 1, 5))
            return out[1]

        p = mpmath.exp(-d * d / (2 * s0 * s0)) + gl(
            lambda t: f(t, s0) * mpmath.exp(-(d - t) ** 2 / (2 * s1 * s1)))
        q = gl(lambda t: f(t, s0) * -mpmath.expm1(-(d - t) ** 2 / (2 * s1 * s1)))
        if sigma1 is None:
            dp = d * gl(lambda t: f(t, s0) * f(d - t, s1)) / sg
        else:
            dp = gl(lambda t: t * f(t, s0) * f(d - t, s1)) / sg
        return p, q, dp


GRID = [(float(s), r, None) for s in np.logspace(-2.2, 9, 9) for r in (None, 1e-3, 30.0)]
GRID += [(float(s), r, 1.7) for s in (0.01, 0.3, 40.0) for r in (None, 30.0)]


@pytest.mark.parametrize("sigma, ratio, Omega", GRID)
def test_mpmath_path_against_independent_quadrature(sigma, ratio, Omega):
    sigma1 = None if ratio is None else sigma * ratio
    p, q, dp = reference(sigma, sigma1, 1, Omega, 1, 2 * DPS + 10)
    kw = dict(sigma1=sigma1, Omega=Omega)
    tol = mpmath.mpf(10) ** -DPS
    with mpmath.workdps(2 * DPS + 10):  # each log from the tail that is small
        lp = mpmath.log(p) if p < 0.5 else mpmath.log1p(-q)
        lq = mpmath.log(q) if q < 0.5 else mpmath.log1p(-p)
    # float inputs (raw-libmp fast path) and decimal strings (general path)
    # the exact decimal expansions of the same binary values go through the general path
    for s in (sigma, str(Decimal(sigma))):
        k = kw if isinstance(s, float) else {**kw, "sigma1": None if sigma1 is None
                                              else str(Decimal(sigma1))}
        assert rel(F.impact_probability(s, **k, dps=DPS), p) < tol, ("p", s)
        assert rel(F.no_impact_probability(s, **k, dps=DPS), q) < tol, ("q", s)
        assert rel(F.log_impact_probability(s, **k, dps=DPS), lp) < tol, ("logp", s)
        assert rel(F.log_no_impact_probability(s, **k, dps=DPS), lq) < tol, ("logq", s)
    if 1e-300 < dp:
        assert rel(F.dp_dsigma(sigma, **kw, dps=DPS), dp) < tol, "dp"


@pytest.mark.parametrize("target", ["1e-300", "1e-40", "0.001", "0.5", "0.999", "1 - 1e-30"])
def test_inverse_against_independent_quadrature(target):
    with mpmath.workdps(60):
        pt = (1 - mpmath.mpf("1e-30")) if target == "1 - 1e-30" else mpmath.mpf(target)
    s = F.sigma_for_impact_probability(pt, dps=DPS)
    p, q, dp = reference(s, None, 1, None, 1, 2 * DPS + 10)
    with mpmath.workdps(2 * DPS + 10):
        # sigma is correct to dps digits, so p(sigma) is within kappa * 10**-dps of the target
        # (kappa = |d ln p/d ln sigma|, or of 1 - p in the upper half)
        if pt <= 0.5:
            kappa = s * dp / p
            assert rel(p, pt) < 2 * kappa * mpmath.mpf(10) ** -DPS
        else:
            kappa = s * dp / q
            assert rel(q, 1 - pt) < 2 * kappa * mpmath.mpf(10) ** -DPS
