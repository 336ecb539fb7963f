"""Extreme arguments of the float64 one-component path (``symhx.forcing.kernels_float``): sigma
over the whole float range, sigma1/sigma far from 1, huge and tiny d, omega, Omega.

float64 ``p``, ``1 - p`` and their logs against the mpmath path (``dps=30``; mpmath has no
overflow): never NaN, ``p, 1 - p`` in [0, 1], logs <= 0, and within ``1e-13 + 4 kappa eps``
(relative) wherever the true value is a normal float, ``kappa`` being the condition number
``|d ln f/d ln d|`` (= every sigma scaled together) of the value ``f`` (for ``log f``:
``kappa_f/|ln f|``), computed by an mpmath central difference.
"""

from __future__ import annotations

import math

import mpmath
import numpy as np
import pytest

from symhx import forcing as F
from symhx._mpctx import mp as thread_mp

EPS = np.finfo(float).eps


TINY = np.finfo(float).tiny


HUGE = np.finfo(float).max


EXTREME_SIGMAS = np.logspace(-300, 300, 29)  # exponents step 21.43: no round values


EXTREME_RATIOS = np.logspace(-150, 150, 15)  # sigma1/sigma (including 1)


def _log10_uv(s0: float, s1: float, omega: float, Omega: float | None, d: float) -> float:
    """log10 of uv = d**2/(4 (sigma0**2 + (sigma1/|omega**2 - Omega**2|)**2)), no overflow."""
    with mpmath.workdps(20), thread_mp().workdps(20):
        om2 = 2 if Omega is None else mpmath.mpf(Omega) ** 2
        t = mpmath.mpf(s1) / abs(mpmath.mpf(omega) ** 2 - om2)
        return float(mpmath.log10(mpmath.mpf(d) ** 2 / (4 * (mpmath.mpf(s0) ** 2 + t**2))))


def _mp_values(s0, s1, omega, Omega, d):
    """mpmath log p, log(1 - p) and kappa_p = |d ln p/d ln d| (dps 30 / 35)."""
    kw = dict(sigma1=s1, omega=omega, Omega=Omega)
    lp = F.log_impact_probability(s0, **kw, d=d, dps=30)
    lq = F.log_no_impact_probability(s0, **kw, d=d, dps=30)
    with mpmath.workdps(40), thread_mp().workdps(40):
        h = mpmath.mpf(10) ** -12
        dm = mpmath.mpf(d) * (1 - h)
        dp = mpmath.mpf(d) * (1 + h)
        kp = abs(F.log_impact_probability(s0, **kw, d=dp, dps=35)
                 - F.log_impact_probability(s0, **kw, d=dm, dps=35)) / (2 * h)
    return lp, lq, kp


def _check_point(s0, s1, vals, omega=1.0, Omega=None, d=1.0):
    """Errors / bound of the four float64 values ``vals = (p, q, log p, log q)`` at one point."""
    p, q, lp, lq = vals
    for v in (p, q, lp, lq):
        assert not math.isnan(v), (s0, s1, vals)
    assert 0.0 <= p <= 1.0 and 0.0 <= q <= 1.0, (s0, s1, vals)
    assert lp <= 0.0 and lq <= 0.0, (s0, s1, vals)
    worst = {}
    if _log10_uv(s0, s1, omega, Omega, d) > 309:  # log p < -1e309: beyond every float
        assert p == 0.0 and lp == -math.inf and q == 1.0 and lq == 0.0, (s0, s1, vals)
        return worst
    mlp, mlq, kp = _mp_values(s0, s1, omega, Omega, d)
    with mpmath.workdps(40), thread_mp().workdps(40):
        mp_, mq = mpmath.exp(mlp), mpmath.exp(mlq)
        kq = kp * mp_ / mq  # |d ln q/d ln d| = d g(d)/q = kappa_p p/q
        cases = (("p", p, mp_, kp), ("q", q, mq, kq),
                 ("logp", lp, mlp, kp / abs(mlp) if mlp else 0),
                 ("logq", lq, mlq, kq / abs(mlq) if mlq else 0))
        for name, val, ref, kappa in cases:
            if not TINY <= abs(ref) <= HUGE:
                # outside the normal range: the float is 0 / the limit, or subnormal/inf rounding
                if abs(ref) < TINY:
                    assert abs(val) < 2 * TINY, (name, s0, s1, val, ref)
                else:
                    assert math.isinf(val), (name, s0, s1, val, ref)
                continue
            bound = 1e-13 + 4 * float(kappa) * EPS
            worst[name] = float(abs(mpmath.mpf(val) / ref - 1)) / bound
    return worst


def _grid_points():
    pts = []
    for s in EXTREME_SIGMAS:
        for r in EXTREME_RATIOS:
            if not -305 < math.log10(s) + math.log10(r) < 305:
                continue
            s1 = float(s * r)
            if 1e-305 < s1 < 1e305:
                pts.append((float(s), s1))
    return pts


def test_extreme_grid_against_mpmath():
    """~330 points: sigma in [1e-300, 1e300], sigma1/sigma in [1e-150, 1e150].

    (Observed worst case: 0.08 of the bound, for log(1 - p); max relative errors 2e-16 (p),
    2e-15 (1 - p, log p), 8e-15 (log(1 - p)).)
    """
    pts = _grid_points()
    assert len(pts) > 300
    s0 = np.array([a for a, _ in pts])
    s1 = np.array([b for _, b in pts])
    vals = [F.impact_probability(s0, sigma1=s1), F.no_impact_probability(s0, sigma1=s1),
            F.log_impact_probability(s0, sigma1=s1), F.log_no_impact_probability(s0, sigma1=s1)]
    worst = {}
    for i, (a, b) in enumerate(pts):
        vi = tuple(float(v[i]) for v in vals)
        # the scalar path gives the same numbers as the array path
        assert vi == (F.impact_probability(a, sigma1=b), F.no_impact_probability(a, sigma1=b),
                      F.log_impact_probability(a, sigma1=b),
                      F.log_no_impact_probability(a, sigma1=b)), (a, b)
        for k, w in _check_point(a, b, vi).items():
            worst[k] = max(worst.get(k, 0.0), w)
    assert set(worst) == {"p", "q", "logp", "logq"}
    assert max(worst.values()) <= 1.0, worst


def test_tied_sigma_over_the_whole_float_range():
    """sigma1 = None (the paper), sigma in [1e-300, 1e300]."""
    for s in np.logspace(-300, 300, 41):
        s = float(s)
        vals = (F.impact_probability(s), F.no_impact_probability(s),
                F.log_impact_probability(s), F.log_no_impact_probability(s))
        worst = _check_point(s, s, vals)
        assert all(w <= 1.0 for w in worst.values()), (s, worst)


@pytest.mark.parametrize(
    "kw",
    [
        dict(d=1e-200), dict(d=1e200), dict(d=1e-200, sigma=1e-200), dict(d=1e250, sigma=1e249),
        dict(omega=1e-200), dict(omega=1e200), dict(omega=1e200, sigma=1e200),
        dict(omega=1e-200, Omega=1.1e-200, sigma=1e-150),
        dict(omega=1e-200, Omega=3e-200, sigma=1e-300, sigma1=1e-300),
        dict(omega=1e200, Omega=2e200, sigma=1e-50, sigma1=1e300),
        dict(omega=2.0, Omega=1e-300, d=1e150, sigma=1e149),
        dict(omega=1.0, Omega=1e155, sigma=0.3, sigma1=1e300),
        dict(d=1e-150, sigma=1e-151, sigma1=1e-145),
        dict(d=1e-160, sigma=1e-160, sigma1=1e-160),
        dict(d=1e160, sigma=1e160, sigma1=1e160),
    ],
)
def test_huge_and_tiny_d_omega_Omega(kw):
    kw = dict(kw)
    s0 = kw.pop("sigma", 0.3)
    s1 = kw.pop("sigma1", s0)
    omega, Omega, d = kw.get("omega", 1.0), kw.get("Omega"), kw.get("d", 1.0)
    args = dict(sigma1=s1, omega=omega, Omega=Omega, d=d)
    vals = (F.impact_probability(s0, **args), F.no_impact_probability(s0, **args),
            F.log_impact_probability(s0, **args), F.log_no_impact_probability(s0, **args))
    worst = _check_point(s0, s1, vals, omega, Omega, d)
    assert all(w <= 1.0 for w in worst.values()), (kw, vals, worst)


# ----------------------------------------------------------------------------- regressions
def test_tiny_and_huge_sigma_give_limits_not_nan():
    """Bug: sigma = 1e-200 and 1e200 gave NaN (x, y over/underflowed to inf/0, u = x/r NaN)."""
    assert F.impact_probability(1e-200) == 0.0
    assert F.no_impact_probability(1e-200) == 1.0
    assert F.log_impact_probability(1e-200) == -math.inf  # log p = -1.25e399
    assert F.log_no_impact_probability(1e-200) == 0.0  # -p, p = exp(-1.25e399)
    assert F.impact_probability(1e200) == 1.0
    assert F.no_impact_probability(1e200) == 0.0  # 1 - p = 1/(96 sigma**4) ~ 1e-802
    assert F.log_impact_probability(1e200) == 0.0
    x = F.log_no_impact_probability(1e200)
    assert abs(x - (-math.log(96) - 800 * math.log(10))) <= 4 * EPS * abs(x)
    # where the true values are normal floats they are accurate
    assert F.log_impact_probability(1e-150) == pytest.approx(-1.25e299, rel=1e-14)
    q = F.no_impact_probability(1e75)
    assert q == pytest.approx(1 / 96e300, rel=1e-14)
    assert F.log_impact_probability(1e75) == pytest.approx(-q, rel=1e-14)
    arr = F.impact_probability(np.array([1e-200, 0.3, 1e200]))
    assert np.array_equal(arr, [0.0, F.impact_probability(0.3), 1.0])


def test_tiny_sigma1_complement_does_not_overflow():
    """Bug: y**2 overflowed in phi~(y) = -(expm1(-y) + y)/y**2 for huge y, giving +0.96."""
    ref = F.log_no_impact_probability(0.3748, sigma1=1e-150, dps=30)
    val = F.log_no_impact_probability(0.3748, sigma1=1e-150)
    assert val < 0
    assert abs(val - float(ref)) <= 1e-14 * abs(float(ref))
    assert float(ref) == pytest.approx(-0.18475595394599188, rel=1e-15)
    # sigma1 -> 0: R1 -> 0, 1 - p -> P(R0 <= d) = -expm1(-1/(4 sigma**2))
    q = F.no_impact_probability(0.3748, sigma1=1e-150)
    assert q == pytest.approx(-math.expm1(-1 / (4 * 0.3748**2)), rel=1e-14)
